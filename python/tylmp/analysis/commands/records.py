"""Subcommands of single records and files: the coordination of data files, the key numbers
of records, micromechanics, two spheres' force against overlap, and the LIGGGHTS deck's raw
record."""
import json
import math
import os

import numpy as np

from .. import compare, figures, io, metrics
from .. import micromechanics as micro
from .common import files_command, report, wrote


def cmd_liggghts_record(a):
    from .. import liggghts
    record = liggghts.servo_record(a.raw)
    wrote(io.write_servo_csv(a.out, {k: record[k] for k in io.SERVO_COLUMNS}))


def cmd_coordination(a):
    """Z and the rattler-free Z_m of the spheres in LAMMPS data files (docs/fidelity.md)."""
    for f in a.files:
        if f.endswith((".csv", ".csv.xz", ".csv.gz")):   # a fix cell/servo record: last row
            t = io.read_servo_csv(f)
            z, zm = float(t["Z"][-1]), float(t["Zm"][-1])
            sols = metrics.rattlers_from_z(a.n, z, zm)
            report(t.name, [("step", float(t["step"][-1])), ("N", a.n), ("Z", z), ("Zm", zm),
                            ("solid_fraction", float(t["solid_fraction"][-1]))]
                   + [("N0_N1", " or ".join(f"{n0},{n1}" for n0, n1 in sols) or None)])
            continue
        lo, hi, _, diam, pos = io.read_sphere_data(f)
        i, j, overlap = metrics.contacts(hi - lo, diam, pos - lo)
        c = metrics.coordination(metrics.counts_per_sphere(i, j, len(diam)))
        phi = float(np.sum(math.pi / 6 * diam ** 3) / np.prod(hi - lo))
        report(os.path.splitext(os.path.basename(f))[0],
               [(k, c[k]) for k in ("N", "C", "N0", "N1", "Z", "Zm")]
               + [("solid_fraction", phi), ("overlap_rel_mean", float(np.mean(overlap)) if len(overlap) else None),
                  ("overlap_rel_max", float(np.max(overlap)) if len(overlap) else None)])


def _pick(table, wanted, given, what):
    if given:
        table.require([given])
        return given
    lower = {k.lower(): k for k in table.keys()}
    for w in wanted:
        if w in lower:
            return lower[w]
    raise SystemExit(f"error: no {what} column among {list(table.keys())}; name it with --{what[0]}")


def cmd_two_spheres(a):
    t = io.read_print_table(a.table)
    xc = _pick(t, ("overlap", "delta", "delta_n", "dn", "d"), a.x, "x (overlap)")
    yc = _pick(t, ("normal_force", "fn", "force", "fx", "p", "f"), a.y, "y (force)")
    x, y = t[xc], t[yc] * a.force_scale
    curves = []
    pairs = [("rows", len(t)), ("x", xc), ("y", yc), ("overlap_max", float(np.max(x))),
             ("force_max", float(np.max(y))), ("force_min", float(np.min(y))),
             ("overlap_at_force_min", float(x[int(np.argmin(y))]))]
    if a.E is not None and a.radius is not None:
        estar = a.E / (2.0 * (1.0 - a.nu ** 2))
        rstar = a.radius / 2.0
        if a.gamma > 0:
            a0 = (9 * math.pi * a.gamma * rstar ** 2 / estar) ** (1 / 3)
            amax = math.sqrt(rstar * max(float(np.max(x)), 0.0) + a0 ** 2) * 1.05
            ac = np.linspace(a0 * 6 ** (-2 / 3), amax, 400)
            dj = ac ** 2 / rstar - 2 * np.sqrt(math.pi * a.gamma * ac / estar)
            fj = 4 * estar * ac ** 3 / (3 * rstar) - 4 * np.sqrt(math.pi * a.gamma * estar * ac ** 3)
            keep = dj <= max(float(np.max(x)), 0.0)
            curves.append((f"JKR (Γ = {a.gamma:g} J/m²)", dj[keep], fj[keep]))
            pairs.append(("pull_off_theory", 3 * math.pi * a.gamma * rstar))
        dh = np.linspace(0.0, max(float(np.max(x)), 0.0), 200)
        curves.append(("Hertz", dh, 4.0 / 3.0 * estar * np.sqrt(rstar) * dh ** 1.5))
        pos = x > 0
        if a.gamma == 0 and pos.any():
            fh = 4.0 / 3.0 * estar * np.sqrt(rstar) * x[pos] ** 1.5
            pairs.append(("hertz_max_rel_dev", float(np.max(np.abs(y[pos] - fh)) / np.max(np.abs(fh)))))
    report(t.name, pairs)
    wrote(figures.two_spheres(x, y, a.out, curves, xlabel=xc, ylabel=yc))


def cmd_micromechanics(a):
    t = micro.read_record(a.file)
    values = micro.columns(t, a.prefix)
    xname = a.x or next((c for c in ("eps_d13", "step", "TimeStep") if c in t), None)
    if xname is None:
        raise ValueError(f"{t.path}: no eps_d13, step or TimeStep column; choose x with --x")
    x = np.asarray(t[xname], float)
    xlabel = xname
    if xname.startswith("eps"):
        x, xlabel = x * 100.0, f"{xname} [%]"
    report(t.name, sorted(micro.summary(values).items()))
    wrote(figures.micromechanics(x, xlabel, values, a.out, a.label or ""))


def cmd_summary(a):
    for f in a.files:
        s = metrics.summarize(io.read_servo_csv(f))
        print(json.dumps(_finite(s), allow_nan=False))


def _finite(obj):
    """JSON-safe copy: NaN/inf -> None, numpy scalars -> Python."""
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        return float(obj) if math.isfinite(obj) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def register(sub):
    """Adds the subcommands coordination, summary, micromechanics, liggghts-record, two-spheres."""
    p = sub.add_parser("coordination", help="Z = 2C/N and Zm = (2C - N1)/(N - N0 - N1) of LAMMPS data files")
    p.add_argument("files", nargs="+", help="data files with 'Atoms # sphere' rows, orthogonal periodic "
                   "box; or fix cell/servo CSV records (N0, N1 recovered from the last row's Z and Zm)")
    p.add_argument("--n", type=int, default=compare.PAPER["n_particles"][0],
                   help="number of spheres of the CSV records (default 3620)")
    p.set_defaults(func=cmd_coordination)
    files_command(sub, "summary", cmd_summary, "key numbers of each file, one JSON line per file", out=False)

    p = sub.add_parser("micromechanics", help="fabric, strong/weak and normal/tangential stress, "
                       "sliding fraction from a record of compute thornton/yin/micromechanics")
    p.add_argument("file", help="CSV of fix cell/servo, or table of fix print or fix ave/time, "
                   "with the compute's 41 values (named as "
                   "tylmp.analysis.micromechanics.NAMES or PREFIX[1..41])")
    p.add_argument("--out", required=True, help="PNG to write")
    p.add_argument("--x", help="x-axis column (default eps_d13, else step or TimeStep)")
    p.add_argument("--prefix", help="indexed columns PREFIX[k] to use (e.g. c_micro)")
    p.add_argument("--label", help="figure title")
    p.set_defaults(func=cmd_micromechanics)
    p = sub.add_parser("liggghts-record", help="the raw record of inputs/liggghts/axisym.in as a "
                       "fix cell/servo record, which every other command reads")
    p.add_argument("raw", help="OUT_raw.csv written by the LIGGGHTS deck")
    p.add_argument("--out", required=True, help="CSV to write")
    p.set_defaults(func=cmd_liggghts_record)
    p = sub.add_parser("two-spheres", help="normal force vs overlap from a fix print table")
    p.add_argument("table")
    p.add_argument("--out", required=True)
    p.add_argument("--x", help="overlap column (default: overlap/delta/d)")
    p.add_argument("--y", help="force column (default: normal_force/fn/fx)")
    p.add_argument("--force-scale", type=float, default=1.0, help="multiply the force (e.g. -1)")
    p.add_argument("--E", type=float, help="Young's modulus (Pa) for theory curves")
    p.add_argument("--nu", type=float, default=0.3, help="Poisson's ratio (0.3)")
    p.add_argument("--radius", type=float, help="sphere radius (m), equal spheres: R* = R/2")
    p.add_argument("--gamma", type=float, default=0.0, help="interface energy Γ (J/m²) for JKR")
    p.set_defaults(func=cmd_two_spheres)
