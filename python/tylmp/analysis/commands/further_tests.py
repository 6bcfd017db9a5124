"""Subcommands of the tests beyond the paper: cyclic axisymmetric loading, simple shear (drained,
constant volume, cyclic), the critical state in p-q, undrained triaxial compression, principal
stress rotation, oedometric (K0) loading and unloading, and the undrained cyclic triaxial
test."""
import numpy as np

from .. import figures, metrics, principal
from .common import about, files_command, legend_labels, read_records, report, wrote


def cmd_cyclic(a):
    from .. import cyclic
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        report(lab, [("reversals", len(cyclic.reversals(t)))]
               + [(f"work_cycle{k}_J_per_m3", float(w)) for k, w in cyclic.cycle_work(t).items()])
    wrote(figures.cyclic(tables, labels, a.out, about=about(a)))


def cmd_shear(a):
    from .. import shear
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
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
        report(lab, pairs)
    wrote(figures.shear(tables, labels, a.out, about=about(a)))


def cmd_cyclic_shear(a):
    from .. import shear
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        if shear.kind(t) != "cyclic":
            raise ValueError(f"{t.path}: not a cyclic simple-shear record (no column 'cycles')")
        fix_ru, fix_da = shear.liquefaction_reported(t)
        rec_ru, rec_da = shear.liquefaction_from_record(t, a.ru_limit, a.da_limit)
        report(lab, [("CSR", shear.cyclic_stress_ratio(t)), ("cycles", float(t["cycles"][-1])),
                     ("r_u_max", float(np.max(t["r_u"]))),
                     ("N_L_ru", fix_ru), ("N_L_gamma", fix_da),
                     ("N_L_ru_record", rec_ru), ("N_L_gamma_record", rec_da)])
    wrote(figures.cyclic_shear(tables, labels, a.out, about=about(a),
                               limits=(a.ru_limit, a.da_limit)))


def critical_state_ratio(table):
    """M = q/p at the critical state: the mean of q/p over the record's last 10 % of rows."""
    return float(metrics.tail_mean(np.asarray(table["q"]) / np.asarray(table["p"])))


def cmd_pq(a):
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
    ratios = [critical_state_ratio(t) for t in tables]
    for lab, M in zip(labels, ratios):
        report(lab, [("M_critical_state", M)])
    M = float(np.mean(ratios))
    report("critical state line", [("M", M)])
    wrote(figures.p_q(tables, labels, a.out, M, about=about(a)))


def cmd_undrained(a):
    """Undrained triaxial records against the drained critical state (docs/theory.md §13)."""
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
    drained = read_records(a.drained) if a.drained else []
    drained_labels = legend_labels(a.drained, None) if a.drained else []
    csl = principal.critical_state_line(drained) if drained else None
    if csl:
        report("drained critical state", [("M", csl["M"]), ("p_kPa", csl["p_ref"] * 1e-3),
                                          ("e_cs", csl["e_ref"]), ("lambda", csl["lam"]),
                                          ("scatter_e", csl["scatter"])])
        for s, lab in zip(csl["states"], drained_labels):
            report(lab, [("p_kPa", s["p"] * 1e-3), ("e", s["e"]), ("M", s["M"])])
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
        report(lab, pairs)
    wrote(figures.undrained(tables, labels, a.out, drained, drained_labels, csl,
                            about=about(a)))


def cmd_rotation(a):
    """Principal stress rotation: non-coaxiality and principal stresses against the angle."""
    t = read_records(a.files)[0]
    label = legend_labels(a.files[:1], a.labels)[0]
    i, j = principal.plane_indices(a.plane)
    sigma = principal.stress_tensor(t)
    values = principal.principal_values(sigma)
    alpha = principal.unwrapped_angle_deg(principal.major_angle_deg(sigma, i, j))
    psi = principal.noncoaxiality_deg(t, a.plane)
    s = principal.rotation_summary(t, a.plane)
    report(label, [(k, v) for k, v in s.items()])
    commanded = None
    if a.target:
        p, dev, b = a.target
        s1 = p + (2.0 - b) * dev / 3.0
        s3 = p - (1.0 + b) * dev / 3.0
        commanded = (s1, s3 + b * (s1 - s3), s3)
    wrote(figures.rotation(t, label, a.out, alpha, psi, values, commanded, about=about(a)))


def cmd_k0(a):
    """Oedometric loading and unloading: K0 at the end of loading and after unloading, beside
    Jaky's 1 - sin(phi') and Mayne-Kulhawy's K0_nc OCR^sin(phi') when --sinphi is given."""
    from .. import axial_tests as ax
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        s = ax.k0_summary(t)
        pairs = [("sig_a_peak_kPa", s["sig_a_peak"] * 1e-3), ("eps_a_peak_pct", s["eps_a_peak"] * 100),
                 ("void_ratio_peak", s["void_ratio_peak"]), ("K0_loading", s["K0_loading"]),
                 ("K0_inc_loading", s["K0_inc_loading"])]
        pairs += [(f"K0_ocr{o:g}", ax.k0_at_ocr(t, o)) for o in (2.0, 4.0)]
        pairs += [("ocr_end", s["ocr_end"]), ("K0_end", s["K0_end"])]
        if a.sinphi is not None:
            pairs += [("jaky", ax.jaky(a.sinphi))]
            if s["ocr_end"] > 1.0:
                pairs += [("mayne_kulhawy_end", float(ax.mayne_kulhawy(s["K0_loading"],
                                                                       s["ocr_end"], a.sinphi)))]
        report(lab, pairs)
    wrote(figures.k0(tables, labels, a.out, a.sinphi, about=about(a)))


def cmd_cyclic_triaxial(a):
    from .. import axial_tests as ax
    tables = read_records(a.files)
    labels = legend_labels(a.files, a.labels)
    for t, lab in zip(tables, labels):
        t.require(ax.CYCLIC_COLUMNS)
        fix_ru, fix_da = ax.liquefaction_reported(t)
        rec_ru, rec_da = ax.liquefaction_from_record(t, a.ru_limit, a.da_limit)
        report(lab, [("CSR", ax.amplitude_ratio(t)), ("cycles", float(t["cycles"][-1])),
                     ("r_u_max", float(np.max(t["r_u"]))), ("N_L_ru", fix_ru),
                     ("N_L_eps", fix_da), ("N_L_ru_record", rec_ru),
                     ("N_L_eps_record", rec_da)])
    wrote(figures.cyclic_triaxial(tables, labels, a.out, about=about(a),
                                  limits=(a.ru_limit, a.da_limit)))


def register(sub):
    """Adds the subcommands cyclic, shear, cyclic-shear, pq, undrained, rotation, k0 and
    cyclic-triaxial."""
    files_command(sub, "cyclic", cmd_cyclic, "cyclic axisymmetric test: q and εv against ε1 − ε3")
    files_command(sub, "shear", cmd_shear, "simple shear: τ/σn and εv against γ (drained), or τ/σn "
                  "against γ, the stress path σn–τ and r_u against γ (constant volume)")
    p = files_command(sub, "cyclic-shear", cmd_cyclic_shear, "cyclic constant-volume simple shear: r_u "
              "against the number of cycles, the τ–γ loops and the stress path σn–τ, N_L by "
              "r_u ≥ 0.95 and by double-amplitude γ ≥ 3.75 %% (the fix's, and recomputed from "
              "the record's rows: N_L_ru_record, N_L_gamma_record)")
    p.add_argument("--ru-limit", type=float, default=0.95,
                   help="the r_u criterion of the test (the deck's -var ru_limit; 0.95)")
    p.add_argument("--da-limit", type=float, default=0.0375,
                   help="the double-amplitude γ criterion (the deck's -var da_limit; 0.0375)")
    files_command(sub, "pq", cmd_pq, "q = √(3J2) against p with the critical-state line q = M p (M: "
                  "mean q/p of the last 10 %% of the rows)")
    p = files_command(sub, "undrained", cmd_undrained, "undrained (constant-volume) triaxial test: "
                      "p–q with the drained critical-state line, and e–log p")
    p.add_argument("--drained", nargs="+", help="drained records (inputs/axisym.in, at one or "
                   "several -var pressure) whose last 10 %% of rows give the critical states "
                   "and, from two mean stresses on, the line e = Γ − λ ln p")
    p = files_command(sub, "rotation", cmd_rotation, "principal stress rotation: non-coaxiality and "
                      "principal stresses against the rotation angle of σ1 (first file)")
    p.add_argument("--plane", choices=("xz", "xy", "yz"), default="xz",
                   help="the rotation plane of the test (xz)")
    p.add_argument("--target", type=float, nargs=3, metavar=("P", "D", "B"),
                   help="the held p and deviator stress σ1 − σ3 [Pa] and b (fix cell/servo "
                        "rotation's P Q B), drawn as the principal-stress targets")
    p = files_command(sub, "k0", cmd_k0, "oedometric (K0) loading and unloading: the stress path "
                      "σr–σa, K0 against σa and against OCR; K0 at the end of loading, at OCR 2 "
                      "and 4 and at the end")
    p.add_argument("--sinphi", type=float, help="sin φ′ of the material: draws Jaky's 1 − sin φ′ "
                   "and Mayne–Kulhawy's K0_nc·OCR^sin φ′ (empirical rules) and prints them")
    p = files_command(sub, "cyclic-triaxial", cmd_cyclic_triaxial, "undrained cyclic triaxial "
                      "test: the stress path q_a–p′, the q_a–ε_a loops and r_u against the number "
                      "of cycles, N_L by r_u ≥ 0.95 and by double-amplitude ε_a ≥ 5 %% (the fix's, "
                      "and recomputed from the record's rows: N_L_ru_record, N_L_eps_record)")
    p.add_argument("--ru-limit", type=float, default=0.95,
                   help="the r_u criterion of the test (the deck's -var ru_limit; 0.95)")
    p.add_argument("--da-limit", type=float, default=0.05,
                   help="the double-amplitude ε_a criterion (the deck's -var da_limit; 0.05)")
