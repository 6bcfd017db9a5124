"""Command line: tyanalysis <subcommand> ... (the console command of the tylmp package, or
python -m tylmp.analysis); see --help of each subcommand."""
import argparse
import json
import math
import os
import re
import sys

import numpy as np

from . import compare, figures
from . import invariants as inv
from . import io, metrics, paper
from . import micromechanics as micro
from . import fidelity, reproduce
from . import principal


def _g(x):
    if x is None:
        return "none"
    if isinstance(x, float) and not math.isfinite(x):
        return "nan"
    return f"{x:.6g}" if isinstance(x, float) else str(x)


def _kv(label, pairs):
    print(f"{label}: " + " ".join(f"{k}={_g(v)}" for k, v in pairs))


def _labels(files, labels):
    if labels and len(labels) != len(files):
        raise SystemExit(f"error: {len(labels)} labels for {len(files)} files")
    return labels or [io.stem(f) for f in files]


def _read_all(files):
    tables = [io.read_servo_csv(f) for f in files]
    for t in tables:
        if t.dropped_partial:
            print(f"note: {t.path}: dropped an incomplete final row", file=sys.stderr)
    return tables


def _wrote(out):
    print(f"wrote {out}")


def _about(a):
    """(number of spheres, specimen) for the figure's caption (figures.about_text)."""
    return a.n, a.specimen


# ---- subcommands ---------------------------------------------------------------------------------

def _by_parameter(files):
    """Files named by a parameter (friction_mu0.3.csv, radial_b0.5.csv): their legend labels
    ('μ = 0.3', 'b = 0.5') and the files in increasing parameter; else (None, files)."""
    for symbol, pattern in (("μ", r"mu[_=-]?([0-9]+(?:\.[0-9]+)?)"), ("b", r"_b([0-9]+(?:\.[0-9]+)?)")):
        found = [re.search(pattern, io.stem(f)) for f in files]
        if all(found):
            values = [float(m.group(1)) for m in found]
            order = sorted(range(len(files)), key=values.__getitem__)
            return [f"{symbol} = {values[k]:g}" for k in order], [files[k] for k in order]
    return None, files


def cmd_axisym(a):
    if not a.labels:
        a.labels, a.files = _by_parameter(a.files)
    tables = _read_all(a.files)
    labels = _labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        s = metrics.summarize(t)
        _kv(lab, [("q_peak_kPa", s["q_peak_kPa"]), ("eps_d13_at_q_peak_pct", s["eps_d13_at_q_peak_pct"]),
                  ("eps_d13_q_plateau_mid_pct", s["eps_d13_q_plateau_mid_pct"]),
                  ("dev_stress_peak_kPa", s["dev_stress_peak_kPa"]), ("sinphi_max", s["sinphi_max"]),
                  ("sinphi_end", s["sinphi_end"]), ("void_ratio_end", s.get("void_ratio_end")),
                  ("void_ratio_at_30pct", s.get("void_ratio_at_30pct")),
                  ("eps_v_end_pct", s["eps_v_end_pct"]), ("eps_d13_end_pct", s["eps_d13_end_pct"])])
    _wrote(figures.axisym(tables, labels, a.out, paper_marks=a.paper, about=_about(a)))


def cmd_liggghts_record(a):
    from . import liggghts
    record = liggghts.servo_record(a.raw)
    _wrote(io.write_servo_csv(a.out, {k: record[k] for k in io.SERVO_COLUMNS}))


def cmd_cyclic(a):
    from . import cyclic
    tables = _read_all(a.files)
    labels = _labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        _kv(lab, [("reversals", len(cyclic.reversals(t)))]
            + [(f"work_cycle{k}_J_per_m3", float(w)) for k, w in cyclic.cycle_work(t).items()])
    _wrote(figures.cyclic(tables, labels, a.out, about=_about(a)))


def cmd_shear(a):
    from . import shear
    tables = _read_all(a.files)
    labels = _labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        tau_peak, gamma_peak = shear.peak(t)
        pairs = [("kind", shear.kind(t)), ("tau_ratio_peak", tau_peak),
                 ("gamma_at_peak_pct", gamma_peak * 100), ("gamma_end_pct", float(t["gamma"][-1]) * 100),
                 ("tau_ratio_end", float(t["tau_ratio"][-1])),
                 ("sig_n_end_kPa", float(t["sig_n"][-1]) / 1e3)]
        if shear.kind(t) == "drained":
            pairs.append(("eps_v_end_pct", float(t["eps_v"][-1]) * 100))
        else:
            pairs.append(("r_u_end", float(t["r_u"][-1])))
        _kv(lab, pairs)
    _wrote(figures.shear(tables, labels, a.out, about=_about(a)))


def cmd_cyclic_shear(a):
    from . import shear
    tables = _read_all(a.files)
    labels = _labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        if shear.kind(t) != "cyclic":
            raise ValueError(f"{t.path}: not a cyclic simple-shear record (no column 'cycles')")
        fix_ru, fix_da = shear.liquefaction_reported(t)
        rec_ru, rec_da = shear.liquefaction_from_record(t, a.ru_limit, a.da_limit)
        _kv(lab, [("CSR", shear.cyclic_stress_ratio(t)), ("cycles", float(t["cycles"][-1])),
                  ("r_u_max", float(np.max(t["r_u"]))),
                  ("N_L_ru", fix_ru), ("N_L_gamma", fix_da),
                  ("N_L_ru_record", rec_ru), ("N_L_gamma_record", rec_da)])
    _wrote(figures.cyclic_shear(tables, labels, a.out, about=_about(a),
                                limits=(a.ru_limit, a.da_limit)))


def _mu_of(path):
    m = re.search(r"mu[_=-]?([0-9]+(?:\.[0-9]+)?)", os.path.basename(path))
    return float(m.group(1)) if m else None


def cmd_friction(a):
    mus = a.mu or [_mu_of(f) for f in a.files]
    if len(mus) != len(a.files) or any(m is None for m in mus):
        raise SystemExit("error: give one --mu value per file (or name files like run_mu0.3.csv)")
    tables = _read_all(a.files)
    smax, scv = [], []
    for t, mu in zip(tables, mus):
        s = metrics.summarize(t)
        smax.append(s["sinphi_max"])
        scv.append(s["sinphi_end"])
        _kv(t.name, [("mu", float(mu)), ("sinphi_max", s["sinphi_max"]), ("sinphi_cv", s["sinphi_end"])])
    _wrote(figures.friction(mus, smax, scv, a.out, paper_marks=a.paper, tables=tables,
                            about=_about(a)))


def _peak(table):
    d = metrics.derived(table)
    i = int(np.nanargmax(d["sinphi"]))
    loaded = d["q"] > 0.1 * np.nanmax(d["q"])
    b = float(np.nanmedian(d["b"][loaded]))
    return {"index": i, "sinphi": float(d["sinphi"][i]), "b": b, "b_at_peak": float(d["b"][i]),
            "lode_deg": float(d["lode_deg"][i]), "eta": float(d["eta_LD"][i]),
            "p": float(d["p"][i]), "pi_x": float(d["pi_x"][i]), "pi_y": float(d["pi_y"][i])}


def cmd_radial(a):
    tables = _read_all(a.files)
    peaks = [_peak(t) for t in tables]
    # curves labelled by their parameter: b as held by the record (median while loaded)
    labels = _labels(a.files, a.labels or [f"b = {round(pk['b'], 2):g}" for pk in peaks])
    sinphi_tc, source = a.sinphi_tc, "--sinphi-tc"
    if sinphi_tc is None:
        i0 = int(np.argmin([abs(pk["b"]) for pk in peaks]))
        if abs(peaks[i0]["b"]) <= a.b_tol:
            sinphi_tc, source = peaks[i0]["sinphi"], labels[i0]
    p_ref = float(np.mean([pk["p"] for pk in peaks]))
    if sinphi_tc is None:
        print(f"note: no record with |b| <= {a.b_tol}: failure surfaces not drawn")
    else:
        _kv("surfaces", [("sinphi_tc", sinphi_tc), ("from", source), ("p_kPa", p_ref * 1e-3),
                         ("eta_LD", float(inv.criterion_constant(inv.LADE_DUNCAN, sinphi_tc))),
                         ("MN_ratio", float(inv.criterion_constant(inv.MATSUOKA_NAKAI, sinphi_tc)))])
    for pk, lab in zip(peaks, labels):
        pairs = [("b", pk["b"]), ("sinphi_max", pk["sinphi"]), ("lode_deg", pk["lode_deg"]),
                 ("eta_at_peak", pk["eta"])]
        if sinphi_tc is not None and 0.0 <= pk["b"] <= 1.0:
            pairs += [("sinphi_LD", inv.sinphi_on_surface(inv.LADE_DUNCAN, sinphi_tc, pk["b"])),
                      ("sinphi_MN", inv.sinphi_on_surface(inv.MATSUOKA_NAKAI, sinphi_tc, pk["b"]))]
        _kv(lab, pairs)
    if len(tables) > 1:
        # Figs 5-6: do the eta-eps_d curves (eta < 7) and the dilation rates coincide across b?
        ds = [metrics.derived(t) for t in tables]
        eta_curves = [(d[a.strain], d["eta_LD"]) for d in ds]
        max_dilation = [float(np.nanmax(metrics.dilation_rate(d[a.strain], d["eps_v"])[1]))
                        for d in ds]
        # levels up to eta = 7 (the paper's range), but below 80 % of the lowest peak: near a
        # plateau a small difference in eta is a large one in strain (loose specimens)
        eta_top = min(7.0, 0.8 * min(float(np.nanmax(d["eta_LD"])) for d in ds))
        _kv("spread across records", [
            ("eta_levels_up_to", eta_top),
            ("eta_eps_d_spread", metrics.curve_spread(eta_curves, np.linspace(1.0, eta_top, 13))),
            ("max_dilation_rate_min", min(max_dilation)),
            ("max_dilation_rate_max", max(max_dilation))])
    _wrote(figures.radial(tables, labels, a.out, peaks, sinphi_tc, p_ref, strain=a.strain,
                          paper_marks=a.paper, about=_about(a)))


def cmd_pi_plane(a):
    tables = _read_all(a.files)
    labels = _labels(a.files, a.labels)
    surfaces, guides, marks = [], [], []
    drawn = set()
    for idx, (t, lab) in enumerate(zip(tables, labels)):
        d = metrics.derived(t)
        i0 = compare.prestrain_end(t)
        re_ = np.hypot(d["pi_ex"], d["pi_ey"])
        kind, radius = compare.path_kind(t)
        pairs = [("p_min_kPa", float(np.min(d["p"])) * 1e-3), ("p_max_kPa", float(np.max(d["p"])) * 1e-3),
                 ("path", kind or "other")]
        rot = None
        if i0 is not None:
            pairs += [("prestrain_row", i0), ("prestrain_eps_q_pct", float(d["eps_q"][i0]) * 100),
                      ("prestrain_strain_radius_pct", float(re_[i0]) * 100),
                      ("prestrain_q_kPa", float(d["q"][i0]) * 1e-3)]
            # the paper's rotation (79 deg of stress over 60 deg of strain) is a measure of the
            # plane-strain triangle's first leg only
            rot = compare.stress_rotation(t) if kind == "triangle" else None
            if rot is not None:
                pairs += [("stress_rotation_deg", rot[0]), ("strain_rotation_deg", rot[1])]
        _kv(lab, pairs)
        # failure surfaces through the state at the end of the prestrain (else the peak)
        k = i0 if i0 is not None else int(np.nanargmax(d["sinphi"]))
        p_ref = float(np.median(d["p"]))
        if a.sinphi_tc is not None:
            consts = {c: float(inv.criterion_constant(c, a.sinphi_tc)) for c in inv.CRITERIA}
            through = f"sin φ_TC = {a.sinphi_tc:g}"
        else:
            consts = {c: float(inv.criterion_value(c, d["sigma"][k])) for c in inv.CRITERIA}
            through = f"{lab} at the end of the prestrain" if i0 is not None else f"{lab} at its peak"
        for crit, const in consts.items():
            if const > float(inv.criterion_value(crit, np.ones(3))) + 1e-12:
                x, y = inv.failure_surface_pi(crit, p=p_ref, constant=const)
                surfaces.append((idx, figures.criterion_label(crit, const, through), x, y))
        # strain guides: only the path this record followed (or the one asked for)
        r0 = a.strain_radius if a.strain_radius is not None else radius
        guide = kind if a.guide == "auto" else a.guide
        if r0 and guide in ("circle", "both"):
            guides.append((f"{lab}: circle r = {100 * r0:.3g} %", *inv.circle_pi(r0)))
        if r0 and guide in ("triangle", "both"):
            guides.append((f"{lab}: plane-strain triangle", *inv.plane_strain_triangle_pi(r0)))
        # the paper's values (tylmp/analysis/paper.py), with --paper
        if a.paper and i0 is not None and "q0" not in drawn:
            drawn.add("q0")
            marks.append(("stress", paper.label("prestrain_q_kPa",
                          f"q = {paper.value('prestrain_q_kPa'):g} kPa after the prestrain"),
                          [0.0], [paper.prestrain_q_pi_radius()], "o"))
        if a.paper and rot is not None:
            sign = compare.turn_direction(t)
            rs = 1.05 * float(np.nanmax(np.hypot(d["pi_x"], d["pi_y"])))
            turn = paper.value("ps_stress_rotation_deg")
            x, y = inv.pi_point(np.array([0.0, rs]), sign * turn)
            marks.append(("stress", paper.label("ps_stress_rotation_deg",
                          f"{lab}: stress turns {turn:g}° while the strain turns "
                          f"{paper.PS_STRAIN_ROTATION_DEG:g}°"), x, y, "-."))
            x, y = inv.pi_point(np.array([0.0, 2.0 * radius]), sign * paper.PS_STRAIN_ROTATION_DEG)
            marks.append(("strain", f"{lab}: strain turned {paper.PS_STRAIN_ROTATION_DEG:g}° (paper §5)",
                          x, y, "-."))
    _wrote(figures.pi_plane(tables, labels, a.out, surfaces, guides, marks, about=_about(a)))


def critical_state_ratio(table):
    """M = q/p at the critical state: the mean of q/p over the record's last 10 % of rows."""
    return float(metrics.tail_mean(np.asarray(table["q"]) / np.asarray(table["p"])))


def cmd_pq(a):
    tables = _read_all(a.files)
    labels = _labels(a.files, a.labels)
    ratios = [critical_state_ratio(t) for t in tables]
    for lab, M in zip(labels, ratios):
        _kv(lab, [("M_critical_state", M)])
    M = float(np.mean(ratios))
    _kv("critical state line", [("M", M)])
    _wrote(figures.p_q(tables, labels, a.out, M, about=_about(a)))


def cmd_undrained(a):
    """Undrained triaxial records against the drained critical state (docs/theory.md §13)."""
    tables = _read_all(a.files)
    labels = _labels(a.files, a.labels)
    drained = _read_all(a.drained) if a.drained else []
    drained_labels = _labels(a.drained, None) if a.drained else []
    csl = principal.critical_state_line(drained) if drained else None
    if csl:
        _kv("drained critical state", [("M", csl["M"]), ("p_kPa", csl["p_ref"] * 1e-3),
                                       ("e_cs", csl["e_ref"]), ("lambda", csl["lam"]),
                                       ("scatter_e", csl["scatter"])])
        for s, lab in zip(csl["states"], drained_labels):
            _kv(lab, [("p_kPa", s["p"] * 1e-3), ("e", s["e"]), ("M", s["M"])])
    for t, lab in zip(tables, labels):
        s = principal.undrained_summary(t)
        pairs = [("p_start_kPa", s["p_start"] * 1e-3), ("p_end_kPa", s["p_end"] * 1e-3),
                 ("p_tail_kPa", s["p_tail"] * 1e-3),
                 ("q_end_kPa", s["q_end"] * 1e-3), ("q_over_p_end", s["q_over_p_end"]),
                 ("e", s["e_end"]), ("eps_v_max_abs", s["eps_v_max_abs"]),
                 ("max_sig2_minus_sig3_over_p", s["lateral_diff_over_p_max"])]
        if csl:
            # the end state against the line at its own p (p_tail: the last 10 % of the rows)
            e_cs = float(principal.critical_void_ratio(csl, s["p_tail"]))
            pairs += [("e_cs_at_p_tail", e_cs), ("e_minus_e_cs", s["e_end"] - e_cs)]
        _kv(lab, pairs)
    _wrote(figures.undrained(tables, labels, a.out, drained, drained_labels, csl,
                             about=_about(a)))


def cmd_rotation(a):
    """Principal stress rotation: non-coaxiality and principal stresses against the angle."""
    t = _read_all(a.files)[0]
    label = _labels(a.files[:1], a.labels)[0]
    i, j = principal.plane_indices(a.plane)
    sigma = principal.stress_tensor(t)
    values = principal.principal_values(sigma)
    alpha = principal.unwrapped_angle_deg(principal.major_angle_deg(sigma, i, j))
    psi = principal.noncoaxiality_deg(t, a.plane)
    s = principal.rotation_summary(t, a.plane)
    _kv(label, [(k, v) for k, v in s.items()])
    commanded = None
    if a.target:
        p, dev, b = a.target
        s1 = p + (2.0 - b) * dev / 3.0
        s3 = p - (1.0 + b) * dev / 3.0
        commanded = (s1, s3 + b * (s1 - s3), s3)
    _wrote(figures.rotation(t, label, a.out, alpha, psi, values, commanded, about=_about(a)))


def cmd_prestrain(a):
    """q at the pre-strain amplitude under each deviatoric strain measure (docs/fidelity.md)."""
    q_paper = compare.PAPER["prestrain_q_kPa"][0]
    for t in _read_all(a.files):
        d = metrics.derived(t)
        leg = metrics.compression_leg(t)
        k = leg.stop - 1
        _kv(t.name, [("leg_end_eps_d13_pct", float(d["eps_d13"][k]) * 100),
                     ("leg_end_q_kPa", float(d["q"][k]) * 1e-3),
                     ("eps_d13_at_paper_q_pct", metrics._f(metrics.strain_at_q(t, q_paper * 1e3), 100))])
        readings = metrics.prestrain_readings(t, a.amplitude)
        for key, label, d13, q in readings:
            _kv(f"{t.name} {key}", [("eps_d13_needed_pct", d13 * 100), ("q_kPa", metrics._f(q, 1e-3)),
                                    ("vs_paper_pct", None if q is None else 100 * (q * 1e-3 / q_paper - 1))])
        q13 = readings[0][3]            # the decks' reading, eps1 - eps3, in other stress measures
        if q13 is not None:
            _kv(f"{t.name} stress measures at eps_d13", [
                (f"{key}_kPa", q13 * factor * 1e-3) for key, (_, factor) in metrics.STRESS_MEASURES.items()])


def cmd_coordination(a):
    """Z and the rattler-free Z_m of the spheres in LAMMPS data files (docs/fidelity.md)."""
    for f in a.files:
        if f.endswith((".csv", ".csv.xz", ".csv.gz")):   # a fix cell/servo record: last row
            t = io.read_servo_csv(f)
            z, zm = float(t["Z"][-1]), float(t["Zm"][-1])
            sols = metrics.rattlers_from_z(a.n, z, zm)
            _kv(t.name, [("step", float(t["step"][-1])), ("N", a.n), ("Z", z), ("Zm", zm),
                         ("solid_fraction", float(t["solid_fraction"][-1]))]
                + [("N0_N1", " or ".join(f"{n0},{n1}" for n0, n1 in sols) or None)])
            continue
        lo, hi, _, diam, pos = io.read_sphere_data(f)
        i, j, overlap = metrics.contacts(hi - lo, diam, pos - lo)
        c = metrics.coordination(metrics.counts_per_sphere(i, j, len(diam)))
        phi = float(np.sum(math.pi / 6 * diam ** 3) / np.prod(hi - lo))
        _kv(os.path.splitext(os.path.basename(f))[0],
            [(k, c[k]) for k in ("N", "C", "N0", "N1", "Z", "Zm")]
            + [("solid_fraction", phi), ("overlap_rel_mean", float(np.mean(overlap)) if len(overlap) else None),
               ("overlap_rel_max", float(np.max(overlap)) if len(overlap) else None)])


def cmd_table(a):
    ours = compare.load_results(a.results)
    _emit_table(ours, a.out)


def _emit_table(ours, out):
    text = compare.markdown_table(ours)
    print(text)
    if out:
        io.write_text(out, text + "\n")
        _wrote(out)


def cmd_compare(a):
    ours = {}
    if a.json:
        ours.update(compare.load_results(a.json))
    axisym = {}
    for role in ("dense", "loose"):
        f = getattr(a, role)
        if f:
            axisym[role] = io.read_servo_csv(f)
            ours.update(compare.from_axisym(axisym[role], role))
    for role, files in (("dense", a.radial), ("loose", a.radial_loose)):
        if files:
            ours.update(compare.from_radial([io.read_servo_csv(f) for f in files], role,
                                            axisym.get(role)))
    if a.cdst:
        ours.update(compare.from_nonradial(io.read_servo_csv(a.cdst), "cdst", a.p_target))
    if a.plane_strain:
        ps = compare.from_nonradial(io.read_servo_csv(a.plane_strain), "ps", a.p_target)
        ours.update({k: v for k, v in ps.items() if k not in ours or k == "ps_stress_rotation_deg"})
    _emit_table(ours, a.out)


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
    _kv(t.name, pairs)
    _wrote(figures.two_spheres(x, y, a.out, curves, xlabel=xc, ylabel=yc))


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
    _kv(t.name, sorted(micro.summary(values).items()))
    _wrote(figures.micromechanics(x, xlabel, values, a.out, a.label or ""))


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


# ---- parser --------------------------------------------------------------------------------------

def build_parser():
    ap = argparse.ArgumentParser(prog="tyanalysis",
                                 description="Figures and tables for the periodic-cell tests "
                                             "(CSV of fix cell/servo).")
    sub = ap.add_subparsers(dest="command", required=True)

    def files_cmd(name, func, help_, out=True):
        p = sub.add_parser(name, help=help_, description=help_)
        p.add_argument("files", nargs="+", help="fix cell/servo CSV file(s)")
        if out:
            p.add_argument("--out", required=True, help="PNG to write")
            p.add_argument("--labels", nargs="+", help="one legend label per file")
            p.add_argument("--paper", action="store_true",
                           help="draw the paper's values over the records "
                           "(tylmp/analysis/paper.py)")
            p.add_argument("--n", type=int, help="number of spheres, stated under the figure")
            p.add_argument("--specimen", help="the specimen (e.g. dense, loose), stated under "
                                              "the figure")
        p.set_defaults(func=func)
        return p

    files_cmd("axisym", cmd_axisym, "Figs 1-2: deviator stress, void ratio and volumetric strain vs ε1 − ε3")
    files_cmd("cyclic", cmd_cyclic, "cyclic axisymmetric test: q and εv against ε1 − ε3")
    files_cmd("shear", cmd_shear, "simple shear: τ/σn and εv against γ (drained), or τ/σn "
              "against γ, the stress path σn–τ and r_u against γ (constant volume)")
    p = files_cmd("cyclic-shear", cmd_cyclic_shear, "cyclic constant-volume simple shear: r_u "
              "against the number of cycles, the τ–γ loops and the stress path σn–τ, N_L by "
              "r_u ≥ 0.95 and by double-amplitude γ ≥ 3.75 %% (the fix's, and recomputed from "
              "the record's rows: N_L_ru_record, N_L_gamma_record)")
    p.add_argument("--ru-limit", type=float, default=0.95,
                   help="the r_u criterion of the test (the deck's -var ru_limit; 0.95)")
    p.add_argument("--da-limit", type=float, default=0.0375,
                   help="the double-amplitude γ criterion (the deck's -var da_limit; 0.0375)")
    files_cmd("pq", cmd_pq, "q = √(3J2) against p with the critical-state line q = M p (M: "
              "mean q/p of the last 10 %% of the rows)")
    p = files_cmd("undrained", cmd_undrained, "undrained (constant-volume) triaxial test: "
                  "p–q with the drained critical-state line, and e–log p")
    p.add_argument("--drained", nargs="+", help="drained records (inputs/axisym.in, at one or "
                   "several -var pressure) whose last 10 %% of rows give the critical states "
                   "and, from two mean stresses on, the line e = Γ − λ ln p")
    p = files_cmd("rotation", cmd_rotation, "principal stress rotation: non-coaxiality and "
                  "principal stresses against the rotation angle of σ1 (first file)")
    p.add_argument("--plane", choices=("xz", "xy", "yz"), default="xz",
                   help="the rotation plane of the test (xz)")
    p.add_argument("--target", type=float, nargs=3, metavar=("P", "D", "B"),
                   help="the held p and deviator stress σ1 − σ3 [Pa] and b (fix cell/servo "
                        "rotation's P Q B), drawn as the principal-stress targets")
    p = files_cmd("friction", cmd_friction, "Fig. 3: sinφ_max and sinφ_cv against μ")
    p.add_argument("--mu", type=float, nargs="+", help="μ of each file (default: from names like mu0.3)")
    p = files_cmd("radial", cmd_radial, "Figs 4-6: radial b tests, peak states on the Π plane")
    p.add_argument("--sinphi-tc", type=float, help="compression strength for the surfaces "
                   "(default: sinφ_max of the record with b closest to 0)")
    p.add_argument("--b-tol", type=float, default=0.05, help="|b| accepted as compression (0.05)")
    p.add_argument("--strain", choices=("eps_q", "eps_d13"), default="eps_q",
                   help="deviatoric strain measure for η and dilation panels (eps_q)")
    p = files_cmd("pi-plane", cmd_pi_plane, "Figs 7-9: stress and strain paths on the Π plane")
    p.add_argument("--guide", choices=("auto", "circle", "triangle", "both", "none"), default="auto",
                   help="strain-path guide: constant-deviatoric-strain circle / plane-strain triangle")
    p.add_argument("--strain-radius", type=float,
                   help="Π radius of the guides (strain; default: at the end of the prestrain)")
    p.add_argument("--sinphi-tc", type=float, help="draw the surfaces through this compression "
                   "strength (default: through the stress state at the end of the prestrain)")
    p = files_cmd("prestrain", cmd_prestrain, "q at the pre-strain amplitude read as ε1 − ε3, ε_q, "
                  "γ_oct or |e| (Figs 7-9)", out=False)
    p.add_argument("--amplitude", type=float, default=compare.PAPER["prestrain_eps_d_pct"][0] / 100,
                   help="pre-strain amplitude (default 0.00285, the paper's 0.285 %%)")
    p = sub.add_parser("coordination", help="Z = 2C/N and Zm = (2C - N1)/(N - N0 - N1) of LAMMPS data files")
    p.add_argument("files", nargs="+", help="data files with 'Atoms # sphere' rows, orthogonal periodic "
                   "box; or fix cell/servo CSV records (N0, N1 recovered from the last row's Z and Zm)")
    p.add_argument("--n", type=int, default=compare.PAPER["n_particles"][0],
                   help="number of spheres of the CSV records (default 3620)")
    p.set_defaults(func=cmd_coordination)
    files_cmd("summary", cmd_summary, "key numbers of each file, one JSON line per file", out=False)

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

    p = sub.add_parser("table", help="markdown table paper vs ours from a JSON {quantity: value}")
    p.add_argument("results", help="JSON object of our values (keys as in compare.PAPER)")
    p.add_argument("--out", help="also write the markdown to this file")
    p.set_defaults(func=cmd_table)

    p = sub.add_parser("compare", help="markdown table paper vs ours from records and/or JSON")
    p.add_argument("--json", help="JSON object of our values")
    p.add_argument("--dense", help="dense axisymmetric compression CSV")
    p.add_argument("--loose", help="loose axisymmetric compression CSV")
    p.add_argument("--radial", nargs="+", help="radial b-test CSVs of the dense specimen "
                   "(with --dense, its b = 0 joins them)")
    p.add_argument("--radial-loose", nargs="+", help="radial b-test CSVs of the loose specimen "
                   "(with --loose, its b = 0 joins them)")
    p.add_argument("--cdst", help="constant deviatoric strain test CSV")
    p.add_argument("--plane-strain", help="multi-axial plane-strain test CSV")
    p.add_argument("--p-target", type=float, default=100.0, help="target mean stress, kPa (100)")
    p.add_argument("--out", help="also write the markdown to this file")
    p.set_defaults(func=cmd_compare)

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
    p = sub.add_parser("reproduce", help="run the paper's programme (every deck behind the figures "
                       "of docs/validation.md) and draw its figures and summary table",
                       description=reproduce.__doc__.split("\n\n")[0])
    p.add_argument("--scale", choices=("paper", "quick"), default="paper",
                   help="the decks' scale (paper: 3620 spheres, hours; quick: 500, minutes)")
    p.add_argument("--dir", default="paper_runs", help="run directory: records, logs, specimens, "
                   "figures (default paper_runs)")
    p.add_argument("--jobs", type=int, help="runs at once (default: the number of cores)")
    p.add_argument("--inputs", help="directory of the decks (default: the repository's inputs/, "
                   "else the copy installed with tylmp)")
    p.add_argument("--programme", choices=tuple(reproduce.PROGRAMMES), default="paper",
                   help="paper: every run behind the figures of docs/validation.md (default); "
                   "fidelity: the trace study of docs/fidelity.md, one factor at a time, and "
                   "its table (tyanalysis fidelity)")
    p.add_argument("--only", nargs="+", metavar="RUN", help="only these runs (--dry-run lists "
                   "them); paper: " + ", ".join(reproduce.PROGRAMME))
    p.add_argument("--every", type=float, default=300.0,
                   help="seconds between progress lines (300)")
    p.add_argument("--dry-run", action="store_true", help="print the commands, run nothing")
    p.set_defaults(func=cmd_reproduce)
    p = sub.add_parser("fidelity", help="the trace study's table: every response of every factor "
                       "and its shift from the base (records of reproduce --programme fidelity)")
    p.add_argument("dir", help="the run directory of tyanalysis reproduce --programme fidelity")
    p.add_argument("--out", help="also write the table to this markdown file")
    p.set_defaults(func=cmd_fidelity)
    return ap


def cmd_fidelity(a):
    text = fidelity.table(a.dir)
    print(text)
    if a.out:
        io.write_text(a.out, text + "\n")
        _wrote(a.out)


def cmd_reproduce(a):
    if a.jobs is not None and a.jobs < 1:
        raise ValueError("--jobs must be at least 1")
    if not a.every > 0:
        raise ValueError("--every must be positive")
    status = reproduce.main(a, draw=main)
    if status:
        raise SystemExit(status)


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except (ValueError, KeyError, OSError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    return 0
