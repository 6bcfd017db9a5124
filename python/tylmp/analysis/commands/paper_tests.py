"""Subcommands of the paper's tests: axisymmetric compression (Figs 1-2), friction (Fig. 3),
the radial b tests (Figs 4-6), the paths on the Π plane and the pre-strain (Figs 7-9), and the
table of the paper's numbers against ours."""
import os
import re

import numpy as np

from .. import compare, figures
from .. import invariants as inv
from .. import io, metrics, paper
from .common import about, files_command, legend_labels, read_records, report, wrote


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
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        s = metrics.summarize(t)
        report(lab, [("q_peak_kPa", s["q_peak_kPa"]), ("eps_d13_at_q_peak_pct", s["eps_d13_at_q_peak_pct"]),
                     ("eps_d13_q_plateau_mid_pct", s["eps_d13_q_plateau_mid_pct"]),
                     ("dev_stress_peak_kPa", s["dev_stress_peak_kPa"]), ("sinphi_max", s["sinphi_max"]),
                     ("sinphi_end", s["sinphi_end"]), ("void_ratio_end", s.get("void_ratio_end")),
                     ("void_ratio_at_30pct", s.get("void_ratio_at_30pct")),
                     ("eps_v_end_pct", s["eps_v_end_pct"]), ("eps_d13_end_pct", s["eps_d13_end_pct"])])
    wrote(figures.axisym(tables, labels, a.out, paper_marks=a.paper, about=about(a)))



def _mu_of(path):
    m = re.search(r"mu[_=-]?([0-9]+(?:\.[0-9]+)?)", os.path.basename(path))
    return float(m.group(1)) if m else None


def cmd_friction(a):
    mus = a.mu or [_mu_of(f) for f in a.files]
    if len(mus) != len(a.files) or any(m is None for m in mus):
        raise SystemExit("error: give one --mu value per file (or name files like run_mu0.3.csv)")
    tables = read_records(a.files)
    smax, scv = [], []
    for t, mu in zip(tables, mus):
        s = metrics.summarize(t)
        smax.append(s["sinphi_max"])
        scv.append(s["sinphi_end"])
        report(t.name, [("mu", float(mu)), ("sinphi_max", s["sinphi_max"]), ("sinphi_cv", s["sinphi_end"])])
    wrote(figures.friction(mus, smax, scv, a.out, paper_marks=a.paper, tables=tables,
                           about=about(a)))


def _peak(table):
    d = metrics.derived(table)
    i = int(np.nanargmax(d["sinphi"]))
    loaded = d["q"] > 0.1 * np.nanmax(d["q"])
    b = float(np.nanmedian(d["b"][loaded]))
    return {"index": i, "sinphi": float(d["sinphi"][i]), "b": b, "b_at_peak": float(d["b"][i]),
            "lode_deg": float(d["lode_deg"][i]), "eta": float(d["eta_LD"][i]),
            "p": float(d["p"][i]), "pi_x": float(d["pi_x"][i]), "pi_y": float(d["pi_y"][i])}


def cmd_radial(a):
    tables = read_records(a.files)
    peaks = [_peak(t) for t in tables]
    # curves labelled by their parameter: b as held by the record (median while loaded)
    labels = legend_labels(a.files, a.labels or [f"b = {round(pk['b'], 2):g}" for pk in peaks])
    sinphi_tc, source = a.sinphi_tc, "--sinphi-tc"
    if sinphi_tc is None:
        i0 = int(np.argmin([abs(pk["b"]) for pk in peaks]))
        if abs(peaks[i0]["b"]) <= a.b_tol:
            sinphi_tc, source = peaks[i0]["sinphi"], labels[i0]
    p_ref = float(np.mean([pk["p"] for pk in peaks]))
    if sinphi_tc is None:
        print(f"note: no record with |b| <= {a.b_tol}: failure surfaces not drawn")
    else:
        report("surfaces", [("sinphi_tc", sinphi_tc), ("from", source), ("p_kPa", p_ref * 1e-3),
                            ("eta_LD", float(inv.criterion_constant(inv.LADE_DUNCAN, sinphi_tc))),
                            ("MN_ratio", float(inv.criterion_constant(inv.MATSUOKA_NAKAI, sinphi_tc)))])
    for pk, lab in zip(peaks, labels):
        pairs = [("b", pk["b"]), ("sinphi_max", pk["sinphi"]), ("lode_deg", pk["lode_deg"]),
                 ("eta_at_peak", pk["eta"])]
        if sinphi_tc is not None and 0.0 <= pk["b"] <= 1.0:
            pairs += [("sinphi_LD", inv.sinphi_on_surface(inv.LADE_DUNCAN, sinphi_tc, pk["b"])),
                      ("sinphi_MN", inv.sinphi_on_surface(inv.MATSUOKA_NAKAI, sinphi_tc, pk["b"]))]
        report(lab, pairs)
    if len(tables) > 1:
        # Figs 5-6: do the eta-eps_d curves (eta < 7) and the dilation rates coincide across b?
        ds = [metrics.derived(t) for t in tables]
        eta_curves = [(d[a.strain], d["eta_LD"]) for d in ds]
        max_dilation = [float(np.nanmax(metrics.dilation_rate(d[a.strain], d["eps_v"])[1]))
                        for d in ds]
        # levels up to eta = 7 (the paper's range), but below 80 % of the lowest peak: near a
        # plateau a small difference in eta is a large one in strain (loose specimens)
        eta_top = min(7.0, 0.8 * min(float(np.nanmax(d["eta_LD"])) for d in ds))
        report("spread across records", [
               ("eta_levels_up_to", eta_top),
               ("eta_eps_d_spread", metrics.curve_spread(eta_curves, np.linspace(1.0, eta_top, 13))),
               ("max_dilation_rate_min", min(max_dilation)),
               ("max_dilation_rate_max", max(max_dilation))])
    wrote(figures.radial(tables, labels, a.out, peaks, sinphi_tc, p_ref, strain=a.strain,
                         paper_marks=a.paper, about=about(a)))


def cmd_pi_plane(a):
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
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
        report(lab, pairs)
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
    wrote(figures.pi_plane(tables, labels, a.out, surfaces, guides, marks, about=about(a)))


def cmd_prestrain(a):
    """q at the pre-strain amplitude under each deviatoric strain measure (docs/fidelity.md)."""
    q_paper = compare.PAPER["prestrain_q_kPa"][0]
    for t in read_records(a.files):
        d = metrics.derived(t)
        leg = metrics.compression_leg(t)
        k = leg.stop - 1
        report(t.name, [("leg_end_eps_d13_pct", float(d["eps_d13"][k]) * 100),
                        ("leg_end_q_kPa", float(d["q"][k]) * 1e-3),
                        ("eps_d13_at_paper_q_pct", metrics._f(metrics.strain_at_q(t, q_paper * 1e3), 100))])
        readings = metrics.prestrain_readings(t, a.amplitude)
        for key, label, d13, q in readings:
            report(f"{t.name} {key}", [("eps_d13_needed_pct", d13 * 100), ("q_kPa", metrics._f(q, 1e-3)),
                                       ("vs_paper_pct", None if q is None else 100 * (q * 1e-3 / q_paper - 1))])
        q13 = readings[0][3]            # the decks' reading, eps1 - eps3, in other stress measures
        if q13 is not None:
            report(f"{t.name} stress measures at eps_d13", [
                   (f"{key}_kPa", q13 * factor * 1e-3) for key, (_, factor) in metrics.STRESS_MEASURES.items()])


def cmd_table(a):
    ours = compare.load_results(a.results)
    _emit_table(ours, a.out)


def _emit_table(ours, out):
    text = compare.markdown_table(ours)
    print(text)
    if out:
        io.write_text(out, text + "\n")
        wrote(out)


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


def register(sub):
    """Adds the subcommands axisym, friction, radial, pi-plane, prestrain, table and compare."""
    files_command(sub, "axisym", cmd_axisym, "Figs 1-2: deviator stress, void ratio and volumetric strain vs ε1 − ε3")
    p = files_command(sub, "friction", cmd_friction, "Fig. 3: sinφ_max and sinφ_cv against μ")
    p.add_argument("--mu", type=float, nargs="+", help="μ of each file (default: from names like mu0.3)")
    p = files_command(sub, "radial", cmd_radial, "Figs 4-6: radial b tests, peak states on the Π plane")
    p.add_argument("--sinphi-tc", type=float, help="compression strength for the surfaces "
                   "(default: sinφ_max of the record with b closest to 0)")
    p.add_argument("--b-tol", type=float, default=0.05, help="|b| accepted as compression (0.05)")
    p.add_argument("--strain", choices=("eps_q", "eps_d13"), default="eps_q",
                   help="deviatoric strain measure for η and dilation panels (eps_q)")
    p = files_command(sub, "pi-plane", cmd_pi_plane, "Figs 7-9: stress and strain paths on the Π plane")
    p.add_argument("--guide", choices=("auto", "circle", "triangle", "both", "none"), default="auto",
                   help="strain-path guide: constant-deviatoric-strain circle / plane-strain triangle")
    p.add_argument("--strain-radius", type=float,
                   help="Π radius of the guides (strain; default: at the end of the prestrain)")
    p.add_argument("--sinphi-tc", type=float, help="draw the surfaces through this compression "
                   "strength (default: through the stress state at the end of the prestrain)")
    p = files_command(sub, "prestrain", cmd_prestrain, "q at the pre-strain amplitude read as ε1 − ε3, ε_q, "
                      "γ_oct or |e| (Figs 7-9)", out=False)
    p.add_argument("--amplitude", type=float, default=compare.PAPER["prestrain_eps_d_pct"][0] / 100,
                   help="pre-strain amplitude (default 0.00285, the paper's 0.285 %%)")
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
