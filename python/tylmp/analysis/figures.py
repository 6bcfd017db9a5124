"""Figures in the style of the paper (Agg backend, PNG). Stresses in kPa, strains in %."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import invariants as inv  # noqa: E402
from . import paper  # noqa: E402
from .metrics import derived, dilation_rate, tail_mean  # noqa: E402

KPA = 1e-3
PCT = 100.0


def save_figure(fig, out, dpi=120):
    """Lay out, write the PNG whole under a temporary name and rename it onto `out`, so that an
    interrupted run never leaves a torn figure; close the figure."""
    fig.tight_layout(rect=(0, 0.03, 1, 1) if fig.texts else None)
    root, ext = os.path.splitext(out)
    tmp = root + ".tmp" + (ext or ".png")
    fig.savefig(tmp, dpi=dpi)
    plt.close(fig)
    os.replace(tmp, out)
    return out


def _pi_axes(ax, title, unit):
    ax.set_aspect("equal", adjustable="datalim")
    ax.axhline(0, color="0.85", lw=0.6, zorder=0)
    ax.axvline(0, color="0.85", lw=0.6, zorder=0)
    ax.set_xlabel(f"x = (v2 - v3)/√2  [{unit}]")
    ax.set_ylabel(f"y = (2v1 - v2 - v3)/√6  [{unit}]")
    ax.set_title(title)


def _axis_rays(ax, radius):
    """Projections of the three principal axes (1 up, 2 lower right, 3 lower left)."""
    for k, theta in enumerate((0.0, 120.0, 240.0)):
        x, y = inv.pi_point(radius, theta)
        ax.plot([0, x], [0, y], color="0.7", lw=0.6, ls=":")
        ax.annotate(str(k + 1), (x, y), color="0.4", fontsize=8, ha="center", va="center")


PAPER_STYLE = dict(color="k", mfc="none", ms=7, mew=1.2, ls="none")
# records drawn one after another get these line styles in turn, so that they stay apart in
# black and white (e.g. the clockwise and anticlockwise plane-strain paths, Figs 8-9)
LINESTYLES = ("-", "--", "-.", ":")
# the smallest span of a volumetric-strain axis [%]: a record whose eps_v stays at round-off
# level (1e-14 %) is drawn flat on this span instead of autoscaled into its noise
MIN_EPS_V_SPAN_PCT = 1e-3


def record_style(k):
    """Line style of the k-th record of a figure."""
    return LINESTYLES[k % len(LINESTYLES)]


def legend(ax, **kw):
    """The axes' legend with each label once (several records may draw the same surface)."""
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(reversed(labels), reversed(handles)))
    ordered = [label for label in dict.fromkeys(labels)]
    ax.legend([unique[label] for label in ordered], ordered, **kw)


def eps_v_limits(ax, values_pct):
    """Widen a volumetric-strain axis to at least MIN_EPS_V_SPAN_PCT around its data."""
    v = np.asarray(values_pct, float)
    v = v[np.isfinite(v)]
    if v.size and float(v.max() - v.min()) < MIN_EPS_V_SPAN_PCT:
        mid = 0.5 * float(v.max() + v.min())
        ax.set_ylim(mid - MIN_EPS_V_SPAN_PCT / 2, mid + MIN_EPS_V_SPAN_PCT / 2)


def strain_rate(table):
    """The record's deviatoric strain rate ε̇_q [1/s]: the median of |Δε_q/Δt| over its rows."""
    d = derived(table)
    dt = np.diff(np.asarray(table["time"], float))
    de = np.abs(np.diff(d["eps_q"]))
    ok = dt > 0
    return float(np.median(de[ok] / dt[ok])) if np.any(ok) else float("nan")


def about_text(tables, n=None, specimen=None, rate=None, rate_name="deviatoric strain rate ε̇_q"):
    """What the figure shows: number of spheres, specimen and the records' strain rates (by
    default the deviatoric strain rate; a simple-shear figure gives its shear rate)."""
    values = sorted({float(f"{(rate or strain_rate)(t):.2g}") for t in tables})
    rates = (", ".join(f"{v:.2g}" for v in values) if len(values) <= 2 else
             f"{values[0]:.2g}–{values[-1]:.2g}")   # many records: the range fits the line
    what = [f"N = {n} spheres" if n else "N not given (--n)",
            f"specimen {specimen}" if specimen else "specimen not given (--specimen)",
            f"{rate_name} = {rates} 1/s"]
    return "; ".join(what)


def caption(fig, tables, about, **rate):
    """Write the about_text line under the figure (about = (n, specimen))."""
    fig.text(0.5, 0.003, about_text(tables, *(about or (None, None)), **rate), ha="center",
             va="bottom", fontsize=8, color="0.25")


def criterion_label(criterion, constant, through):
    """Legend text of a failure surface: the criterion's formula and parameter value."""
    if criterion == inv.LADE_DUNCAN:
        formula = f"Lade–Duncan: η = I1³/I3 − 27 = {constant:.3g}"
    else:
        formula = f"Matsuoka–Nakai: I1·I2/I3 = {constant:.4g} (9 isotropic)"
    return f"{formula}, through {through}"


def axisym(tables, labels, out, paper_marks=False, about=None):
    """Figs 1-2: deviator stress sigma1 - sigma3, void ratio and volumetric strain against the
    deviator strain eps1 - eps3; with paper_marks (--paper) the paper's numbers (§3: dense peak
    at about 5 %; void ratios at the start and at 30 %)."""
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(15, 4.6))
    eps_v = []
    for k, (t, lab) in enumerate(zip(tables, labels)):
        d = derived(t)
        ls = record_style(k)
        a1.plot(d["eps_d13"] * PCT, d["dev_stress"] * KPA, ls=ls, label=lab)
        a2.plot(d["eps_d13"] * PCT, t["void_ratio"], ls=ls, label=lab)
        a3.plot(d["eps_d13"] * PCT, d["eps_v"] * PCT, ls=ls, label=lab)
        eps_v.append(d["eps_v"] * PCT)
    if paper_marks:
        _axisym_paper(a1, a2)
    a1.set(xlabel="deviator strain ε1 − ε3 [%]", ylabel="deviator stress σ1 − σ3 [kPa]",
           title="Axisymmetric compression (Fig. 1)")
    a2.set(xlabel="deviator strain ε1 − ε3 [%]", ylabel="void ratio e", title="Void ratio (Fig. 2)")
    a3.set(xlabel="deviator strain ε1 − ε3 [%]", ylabel="volumetric strain εv [%] (compression +)",
           title="Volumetric strain")
    eps_v_limits(a3, np.concatenate(eps_v) if eps_v else [])
    for a in (a1, a2, a3):
        a.grid(alpha=0.3)
        legend(a, fontsize=7)
    caption(fig, tables, about)
    return save_figure(fig, out)


def _axisym_paper(a1, a2):
    """The paper's numbers of Figs 1-2 (tylmp/analysis/paper.py)."""
    a1.axvline(paper.value("eps_d13_at_peak_dense_pct"), color="0.5", ls=":", lw=1,
               label=paper.label("eps_d13_at_peak_dense_pct", "dense peak at about 5 %"))
    for role, marker in (("dense", "o"), ("loose", "s")):
        e0, e30 = paper.value(f"void_ratio_start_{role}"), paper.value(f"void_ratio_30pct_{role}")
        a2.plot([0.0], [e0], marker, **dict(PAPER_STYLE, color="0.45"),
                label=paper.label(f"void_ratio_start_{role}", f"{role} start, e = {e0:.3f}"))
        a2.plot([30.0], [e30], marker, **PAPER_STYLE,
                label=paper.label(f"void_ratio_30pct_{role}", f"{role} at 30 %, e = {e30:.3f}"))


def cyclic(tables, labels, out, about=None):
    """Cyclic axisymmetric test: signed deviator stress sigma1 - sigma3 (negative in
    extension; the record's q = √(3J2) is its magnitude) and volumetric strain against
    eps1 - eps3."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    eps_v = []
    for k, (t, lab) in enumerate(zip(tables, labels)):
        d = derived(t)
        a1.plot(d["eps_d13"] * PCT, d["dev_stress"] * KPA, lw=0.8, ls=record_style(k), label=lab)
        a2.plot(d["eps_d13"] * PCT, d["eps_v"] * PCT, lw=0.8, ls=record_style(k), label=lab)
        eps_v.append(d["eps_v"] * PCT)
    eps_v_limits(a2, np.concatenate(eps_v) if eps_v else [])
    a1.set_xlabel("deviator strain ε1 − ε3 [%]")
    a1.set_ylabel("σ1 − σ3 [kPa] (< 0 in extension; q = √(3J2) = |σ1 − σ3|)")
    a1.set_title("Cyclic axisymmetric test at constant p")
    a2.set_xlabel("deviator strain ε1 − ε3 [%]")
    a2.set_ylabel("volumetric strain εv [%] (compression +)")
    a2.set_title("Volumetric strain")
    for a in (a1, a2):
        a.axhline(0, color="0.8", lw=0.6, zorder=0)
        a.axvline(0, color="0.8", lw=0.6, zorder=0)
        a.grid(alpha=0.3)
        legend(a, fontsize=8)
    caption(fig, tables, about)
    return save_figure(fig, out)


def friction(mus, sinphi_max, sinphi_cv, out, paper_marks=False, tables=(), about=None):
    """Fig. 3: peak and critical-state sin(phi) against interparticle friction, points in
    increasing mu. The paper's Skinner data and Horne curve have no numbers in its text
    (tylmp/analysis/paper.py): the figure says so instead of drawing them."""
    order = np.argsort(mus)
    mus = np.asarray(mus, float)[order]
    fig, ax = plt.subplots(figsize=(5.5, 4.5))
    ax.plot(mus, np.asarray(sinphi_max)[order], "o-", label="sin φ_max (peak)")
    ax.plot(mus, np.asarray(sinphi_cv)[order], "s--", label="sin φ_cv (mean of the last 10 %)")
    if paper_marks:
        ax.text(0.98, 0.03, "paper's Skinner data and Horne curve:\nno numbers in its text, "
                "not drawn", transform=ax.transAxes, ha="right", va="bottom", fontsize=7,
                color="0.4")
    ax.set_xlabel("interparticle friction μ")
    ax.set_ylabel("sin φ")
    ax.set_title("Effect of interparticle friction (Fig. 3)")
    ax.set_xlim(-0.03, float(np.max(mus)) * 1.05 + 0.03)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    if tables:
        caption(fig, tables, about)
    return save_figure(fig, out)


def radial(tables, labels, out, peaks, sinphi_tc, p_ref, strain="eps_q", paper_marks=False,
           about=None):
    """Figs 4-6: sin(phi) vs eps1 - eps3, eta vs deviatoric strain (the paper's eta = 7 below
    which the curves coincide), dilation rate vs deviatoric strain, and the peak states in the Pi
    plane with the LD and MN surfaces through the compression (b = 0) strength sinphi_tc at mean
    stress p_ref. Records are drawn in increasing b."""
    order = np.argsort([pk["b"] for pk in peaks], kind="stable")
    tables, labels, peaks = ([seq[k] for k in order] for seq in (tables, labels, peaks))
    fig, axes = plt.subplots(2, 2, figsize=(11, 11.5))
    a_s, a_eta, a_dil, a_pi = axes.ravel()
    slabel = "ε_q = √(2/3 e:e)" if strain == "eps_q" else "ε1 − ε3"
    colors = []
    for k, (t, lab) in enumerate(zip(tables, labels)):
        d = derived(t)
        ed = d[strain]
        ls = record_style(k)
        (line,) = a_s.plot(d["eps_d13"] * PCT, d["sinphi"], ls=ls, label=lab)
        colors.append(line.get_color())
        a_eta.plot(ed * PCT, d["eta_LD"], ls=ls, label=lab)
        x, r = dilation_rate(ed, d["eps_v"])
        a_dil.plot(x * PCT, r, ls=ls, label=lab)
    if paper_marks:
        eta7 = paper.value("eta_normalisation_limit")
        a_eta.axhline(eta7, color="k", ls=":", lw=1, label=paper.label(
            "eta_normalisation_limit", f"curves coincide for η < {eta7:g}"))
    a_s.set(xlabel="deviator strain ε1 − ε3 [%]", ylabel="sin φ", title="Mobilised friction")
    a_eta.set(xlabel=f"deviatoric strain {slabel} [%]", ylabel="η = I1³/I3 − 27",
              title="Lade–Duncan η (Fig. 5)")
    a_dil.set(xlabel=f"deviatoric strain {slabel} [%]", ylabel="−dεv/dεd",
              title="Rate of dilation (Fig. 6)")
    a_dil.axhline(0, color="0.6", lw=0.6)
    for a in (a_s, a_eta, a_dil):
        a.grid(alpha=0.3)
        legend(a, fontsize=7)

    _pi_axes(a_pi, "Peak states, Π plane (Fig. 4)", "kPa")
    rmax = 0.0
    if sinphi_tc is not None:
        through = f"sin φ_TC = {sinphi_tc:.3f} (b = 0), p = {p_ref * KPA:.4g} kPa"
        for crit, style in ((inv.LADE_DUNCAN, "-"), (inv.MATSUOKA_NAKAI, "--")):
            x, y = inv.failure_surface_pi(crit, p=p_ref, sinphi_tc=sinphi_tc)
            const = float(inv.criterion_constant(crit, sinphi_tc))
            a_pi.plot(x * KPA, y * KPA, style, color="0.3", lw=1,
                      label=criterion_label(crit, const, through))
            rmax = max(rmax, float(np.max(np.hypot(x, y))) * KPA)
    for pk, lab, color in zip(peaks, labels, colors):
        a_pi.plot(pk["pi_x"] * KPA, pk["pi_y"] * KPA, "o", color=color, label=lab)
        rmax = max(rmax, float(np.hypot(pk["pi_x"], pk["pi_y"])) * KPA)
    R = 1.1 * rmax if rmax else 1.0
    if paper_marks:
        bx, by = inv.pi_point(R, inv.lode_from_b(paper.value("b_at_max_sinphi")))
        a_pi.plot([0, bx], [0, by], color="k", ls="-.", lw=0.8,
                  label=paper.label("b_at_max_sinphi", "strongest at b = 0.5"))
    _axis_rays(a_pi, R)
    legend(a_pi, fontsize=6.5, loc="upper center", bbox_to_anchor=(0.5, -0.1))
    caption(fig, tables, about)
    return save_figure(fig, out)


def pi_plane(tables, labels, out, stress_surfaces, strain_guides, paper_marks=(), about=None):
    """Figs 7-9: stress paths (kPa) and strain paths (%) in the Pi plane with failure surfaces
    (list of (record index, label, x, y), Pa; drawn in the record's colour: Lade-Duncan dashed,
    others dotted), strain guides (list of (label, x, y), strain units) and the paper's values
    (list of (panel 'strain'|'stress', label, x, y, marker or line style), strain units or Pa)."""
    fig, (a_e, a_s) = plt.subplots(1, 2, figsize=(12.5, 8))
    _pi_axes(a_e, "Deviatoric strain path (Π plane)", "%")
    _pi_axes(a_s, "Deviatoric stress path (Π plane)", "kPa")
    re, rs = 0.0, 0.0
    for lab, x, y in strain_guides:
        a_e.plot(x * PCT, y * PCT, ":", color="0.4", lw=1, label=lab)
        re = max(re, float(np.max(np.hypot(x, y))) * PCT)
    colors = []
    for k, (t, lab) in enumerate(zip(tables, labels)):
        d = derived(t)
        (line,) = a_e.plot(d["pi_ex"] * PCT, d["pi_ey"] * PCT, ls=record_style(k), label=lab)
        colors.append(line.get_color())
        a_s.plot(d["pi_x"] * KPA, d["pi_y"] * KPA, color=line.get_color(), ls=record_style(k),
                 label=lab)
        re = max(re, float(np.nanmax(np.hypot(d["pi_ex"], d["pi_ey"]))) * PCT)
        rs = max(rs, float(np.nanmax(np.hypot(d["pi_x"], d["pi_y"]))) * KPA)
    for k, lab, x, y in stress_surfaces:
        style = "--" if inv.LADE_DUNCAN in lab or "Lade" in lab else ":"
        a_s.plot(x * KPA, y * KPA, style, color=colors[k], lw=0.9, alpha=0.8, label=lab)
        rs = max(rs, float(np.max(np.hypot(x, y))) * KPA)
    for panel, lab, x, y, style in paper_marks:
        ax, scale = (a_e, PCT) if panel == "strain" else (a_s, KPA)
        x, y = np.asarray(x, float) * scale, np.asarray(y, float) * scale
        if style in ("o", "s", "D"):
            ax.plot(x, y, style, **PAPER_STYLE, label=lab)
        else:
            ax.plot(x, y, style, color="k", lw=0.9, label=lab)
    _axis_rays(a_e, 1.1 * re if re else 1.0)
    _axis_rays(a_s, 1.1 * rs if rs else 1.0)
    for ax in (a_e, a_s):       # below the plane, where no path runs
        legend(ax, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1))
    caption(fig, tables, about)
    return save_figure(fig, out)


def p_q(tables, labels, out, M, about=None):
    """q = √(3J2) against p of each record, and the critical-state line q = M p (M: the
    records' mean q/p over their last 10 % of rows, metrics.TAIL_FRACTION)."""
    fig, ax = plt.subplots(figsize=(6, 5))
    pmax = 0.0
    for k, (t, lab) in enumerate(zip(tables, labels)):
        ax.plot(np.asarray(t["p"]) * KPA, np.asarray(t["q"]) * KPA, ls=record_style(k),
                label=lab)
        pmax = max(pmax, float(np.nanmax(t["p"])) * KPA)
    ps = np.array([0.0, 1.1 * pmax])
    ax.plot(ps, M * ps, color="k", lw=0.9, ls=(0, (6, 2, 1, 2)),
            label=f"critical state q = M p, M = {M:.3f} (mean q/p of the last 10 %)")
    ax.set(xlabel="mean stress p = (σ1 + σ2 + σ3)/3 [kPa]", ylabel="q = √(3J2) [kPa]",
           title="Stress path, p–q plane")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    legend(ax, fontsize=7, loc="upper left")
    caption(fig, tables, about)
    return save_figure(fig, out)


def undrained(tables, labels, out, drained=(), drained_labels=(), csl=None, about=None):
    """Undrained (constant-volume) triaxial records: the stress path in the p–q plane with the
    drained critical-state line q = M p, and the path in e–log p with the drained records and
    their critical states (csl: principal.critical_state_line of the drained records)."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 5))
    pmax = 0.0
    for k, (t, lab) in enumerate(zip(drained, drained_labels)):
        style = dict(color="0.6", lw=0.9, ls=record_style(k), label=f"drained: {lab}")
        a1.plot(np.asarray(t["p"]) * KPA, np.asarray(t["q"]) * KPA, **style)
        a2.plot(np.asarray(t["p"]) * KPA, t["void_ratio"], **style)
    for k, (t, lab) in enumerate(zip(tables, labels)):
        p = np.asarray(t["p"]) * KPA
        a1.plot(p, np.asarray(t["q"]) * KPA, ls=record_style(k), label=lab)
        a2.plot(p, t["void_ratio"], ls=record_style(k), label=lab)
        # the end state: the mean p of the last 10 % of the rows at the record's (constant) e
        a2.plot([tail_mean(p)], np.asarray(t["void_ratio"])[-1:], "o", ms=5,
                color=a2.lines[-1].get_color())
        pmax = max(pmax, float(np.nanmax(p)))
    if csl is not None:
        ps = np.array([0.0, 1.1 * pmax])
        a1.plot(ps, csl["M"] * ps, color="k", lw=0.9, ls=(0, (6, 2, 1, 2)),
                label=f"drained critical state q = M p, M = {csl['M']:.3f}")
        for s in csl["states"]:
            a2.plot([s["p"] * KPA], [s["e"]], "s", **dict(PAPER_STYLE, color="k"))
        a2.plot([], [], "s", **dict(PAPER_STYLE, color="k"),
                label="drained critical states (mean of the last 10 %)")
        lo, hi = a2.get_xlim()
        if csl["lam"] is not None:
            pl = np.geomspace(max(lo, 1e-6), hi, 50)
            scatter = ("" if csl.get("scatter") is None
                       else f", scatter of e {csl['scatter']:.2g}")
            a2.plot(pl, csl["e_ref"] - csl["lam"] * np.log(pl / (csl["p_ref"] * KPA)), color="k",
                    lw=0.9, ls=(0, (6, 2, 1, 2)),
                    label=f"drained critical-state line e = Γ − λ ln p, λ = {csl['lam']:.3g}"
                          f"{scatter}")
        else:
            a2.axhline(csl["e_ref"], color="k", lw=0.9, ls=(0, (6, 2, 1, 2)),
                       label=f"e_cs = {csl['e_ref']:.3f} at p = {csl['p_ref'] * KPA:.0f} kPa "
                             "(one p: slope not given by the drained tests)")
    a1.set(xlabel="mean stress p [kPa]", ylabel="q = √(3J2) [kPa]",
           title="Undrained stress path, p–q plane")
    a1.set_xlim(left=0)
    a1.set_ylim(bottom=0)
    a2.set_xscale("log")
    a2.set(xlabel="mean stress p [kPa] (log)", ylabel="void ratio e", title="e–log p")
    for a in (a1, a2):
        a.grid(alpha=0.3, which="both")
        legend(a, fontsize=7)
    caption(fig, tables, about)
    return save_figure(fig, out)


def rotation(table, label, out, alpha, psi, principal, commanded=None, about=None):
    """Principal stress rotation: the non-coaxiality ψ = θσ − θε̇ against the rotation angle
    α (the major stress direction, unwrapped), and the principal stresses against α."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
    # points, not a line: the measured angle steps back and forth with the servo's error
    a1.plot(alpha, psi, ".", ms=3, label=label)
    a1.axhline(0.0, color="0.6", lw=0.6)
    a1.set(xlabel="rotation angle α of σ1 [°]", ylabel="non-coaxiality ψ = θσ − θε̇ [°]",
           title="Non-coaxiality")
    a1.set_ylim(-90, 90)
    for k, (name, marker) in enumerate(zip(("σ1 (major)", "σ2 (intermediate)", "σ3 (minor)"),
                                           ".xs")):
        a2.plot(alpha, principal[:, k] * KPA, marker, ms=3, mfc="none", label=name)
    if commanded is not None:
        for k in range(3):
            a2.axhline(commanded[k] * KPA, color="0.5", lw=0.6, ls=":")
        a2.plot([], [], color="0.5", lw=0.6, ls=":", label="targets")
    a2.set(xlabel="rotation angle α of σ1 [°]", ylabel="principal stress [kPa]",
           title="Principal stresses")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        legend(a, fontsize=7)
    caption(fig, [table], about)
    return save_figure(fig, out)


def two_spheres(overlap, force, out, curves=(), xlabel="overlap", ylabel="normal force"):
    """Normal force against overlap (µm, mN); `curves` = list of (label, overlap, force)."""
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for lab, x, y in curves:
        ax.plot(np.asarray(x) * 1e6, np.asarray(y) * 1e3, "--", lw=1, label=lab)
    ax.plot(np.asarray(overlap) * 1e6, np.asarray(force) * 1e3, "-", lw=1.2, label="simulation")
    ax.axhline(0, color="0.7", lw=0.6)
    ax.axvline(0, color="0.7", lw=0.6)
    ax.set_xlabel(f"{xlabel} [µm]")
    ax.set_ylabel(f"{ylabel} [mN]")
    ax.set_title("Two spheres: normal force vs overlap")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return save_figure(fig, out)


def micromechanics(x, xlabel, values, out, label=""):
    """Contact-network measures of compute thornton/yin/micromechanics against x: deviatoric
    fabric, q of the normal/tangential and strong/weak parts of the stress, sliding fraction."""
    from . import micromechanics as micro
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), sharex=True)
    (a_fab, a_nt), (a_sw, a_frac) = axes
    a_fab.plot(x, values["phi_d"], color="k")
    a_fab.set_ylabel("deviatoric fabric φ_d = √(3/2 φ′:φ′)")
    a_fab.set_title("(a) contact-normal fabric")
    q = {part: micro.mean_and_deviator(micro.tensor(values, part))[1] * KPA
         for part in micro.STRESS_PARTS}
    splits = ((a_nt, "(b) stress from normal and tangential forces",
               (("s_normal", "normal forces", "C0-"), ("s_tangential", "tangential forces", "C3--"))),
              (a_sw, "(c) strong and weak networks",
               (("s_strong", "strong: P > ⟨P⟩", "C1-"), ("s_weak", "weak: P ≤ ⟨P⟩", "C2--"))))
    for ax, title, parts in splits:
        for part, name, style in (("s", "total", "k-"),) + parts:
            ax.plot(x, q[part], style, label=name)
        ax.set_ylabel("q [kPa]")
        ax.set_title(title)
        ax.legend(frameon=False)
    a_frac.plot(x, values["sliding_fraction"], "C3-", label="sliding contacts")
    a_frac.plot(x, values["strong_fraction"], "C1--", label="strong contacts")
    a_frac.set_ylabel("fraction of contacts")
    a_frac.set_ylim(bottom=0)
    a_frac.set_title("(d) sliding and strong fractions")
    a_frac.legend(frameon=False)
    for ax in (a_sw, a_frac):
        ax.set_xlabel(xlabel)
    if label:
        fig.suptitle(label)
    return save_figure(fig, out)


def _shear_caption(fig, tables, about):
    from . import shear
    caption(fig, tables, about, rate=shear.shear_rate, rate_name="shear rate |γ̇|")


def _zero_lines(ax):
    ax.axhline(0, color="0.8", lw=0.6, zorder=0)
    ax.axvline(0, color="0.8", lw=0.6, zorder=0)
    ax.grid(alpha=0.3)


def shear(tables, labels, out, about=None):
    """Monotonic simple shear (docs/theory.md §13): τ/σn against γ and, for drained records,
    εv against γ; for constant-volume records the stress path σn–τ and r_u against γ. The
    panels follow the first record's kind; records of the other kind are drawn where their
    columns allow."""
    from . import shear as sh
    kinds = [sh.kind(t) for t in tables]
    drained = kinds[0] == "drained"
    if drained:
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
        a3 = None
    else:
        fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(14, 4))
    eps_v = []
    for k, (t, lab) in enumerate(zip(tables, labels)):
        ls = record_style(k)
        g = t["gamma"] * PCT
        a1.plot(g, t["tau_ratio"], lw=0.9, ls=ls, color="k", label=lab)
        if drained:
            a2.plot(g, t["eps_v"] * PCT, lw=0.9, ls=ls, color="k", label=lab)
            eps_v.append(t["eps_v"] * PCT)
        else:
            a2.plot(t["sig_n"] * KPA, t["tau"] * KPA, lw=0.9, ls=ls, color="k", label=lab)
            if "r_u" in t:
                a3.plot(g, t["r_u"], lw=0.9, ls=ls, color="k", label=lab)
    a1.set(xlabel="shear strain γ [%]", ylabel="stress ratio τ/σn",
           title="Simple shear: " + ("drained (σn held)" if drained else "constant volume"))
    if drained:
        eps_v_limits(a2, np.concatenate(eps_v) if eps_v else [])
        a2.set(xlabel="shear strain γ [%]", ylabel="volumetric strain εv [%] (compression +)",
               title="Volumetric strain (εv < 0: dilation)")
    else:
        a2.set(xlabel="normal stress σn [kPa]", ylabel="shear stress τ [kPa]",
               title="Stress path")
        a2.set_xlim(left=0)
        a3.set(xlabel="shear strain γ [%]", ylabel="r_u = 1 − σn/σn0",
               title="Normal-stress ratio (pore pressure)")
    for a in (a1, a2, a3):
        if a is not None:
            _zero_lines(a)
            legend(a, fontsize=8)
    _shear_caption(fig, tables, about)
    return save_figure(fig, out)


def cyclic_shear(tables, labels, out, about=None, n_l=None, limits=None):
    """Cyclic constant-volume simple shear: r_u against the cycle count N (continuous within a
    half cycle, shear.continuous_cycles), the τ–γ loops and the stress path τ against σn, with
    N_L by r_u (circle) and by double-amplitude γ (square) marked on every panel at the first
    row where each criterion holds, labelled with the N_L of n_l (per record (N_L_ru,
    N_L_gamma); default the fix's columns); limits = (r_u limit, double-amplitude limit),
    default 0.95 and 0.0375. The path panel draws ±τ_cyc = ±CSR·σn0 as dotted lines."""
    from . import shear as sh
    ru_limit, da_limit = limits or (sh.RU_LIMIT, sh.DA_LIMIT)
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(15.5, 4.3))
    for k, (t, lab) in enumerate(zip(tables, labels)):
        ls = record_style(k)
        n = sh.continuous_cycles(t)
        a1.plot(n, t["r_u"], lw=0.9, ls=ls, color="k", label=lab)
        a2.plot(t["gamma"] * PCT, t["tau"] * KPA, lw=0.7, ls=ls, color="k", label=lab)
        a3.plot(t["sig_n"] * KPA, t["tau"] * KPA, lw=0.7, ls=ls, color="k", label=lab)
        amplitude = sh.cyclic_stress_ratio(t) * t["sig_n"][0] * KPA
        for sign in ((1, -1) if np.isfinite(amplitude) else ()):
            a3.axhline(sign * amplitude, color="0.5", lw=0.7, ls=":")
        marks = n_l[k] if n_l else sh.liquefaction_reported(t)
        rows = sh.liquefaction_rows(t, ru_limit, da_limit)
        for value, r, marker, what in zip(marks, rows, ("o", "s"),
                                          (f"N_L (r_u ≥ {ru_limit:g})",
                                           f"N_L (double amplitude γ ≥ {da_limit * PCT:g} %)")):
            if not value > 0 or r is None:
                continue
            style = dict(marker=marker, mfc="white", mec="k", ms=8, mew=1.3, ls="none",
                         label=f"{what} = {value:g}")
            a1.plot(n[r], t["r_u"][r], **style)
            a2.plot(t["gamma"][r] * PCT, t["tau"][r] * KPA, **style)
            a3.plot(t["sig_n"][r] * KPA, t["tau"][r] * KPA, **style)
    a1.axhline(ru_limit, color="0.5", lw=0.7, ls=":")
    a1.set(xlabel="number of cycles N", ylabel="r_u = 1 − σn/σn0",
           title="Cyclic simple shear at constant volume")
    a2.set(xlabel="shear strain γ [%]", ylabel="shear stress τ [kPa]", title="Stress–strain loops")
    a3.set(xlabel="normal stress σn [kPa]", ylabel="shear stress τ [kPa]", title="Stress path")
    a3.set_xlim(left=0.0)
    for a in (a1, a2, a3):
        _zero_lines(a)
        legend(a, fontsize=8)
    _shear_caption(fig, tables, about)
    return save_figure(fig, out)


def _axial_caption(fig, tables, about):
    from . import axial_tests
    caption(fig, tables, about, rate=axial_tests.axial_rate, rate_name="axial strain rate |ε̇_a|")


def k0(tables, labels, out, sinphi=None, about=None):
    """Oedometric loading and unloading (docs/theory.md §13): the stress path σr against σa,
    K0 = σr/σa against σa, and K0 against OCR on unloading. With sinphi (sin φ′), Jaky's
    1 − sin φ′ is drawn on the second panel and Mayne–Kulhawy's K0_nc·OCR^sin φ′ (K0_nc: the
    record's K0 at the end of loading) on the third, both empirical rules."""
    from . import axial_tests as ax
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(15.5, 4.3))
    for k, (t, lab) in enumerate(zip(tables, labels)):
        ls = record_style(k)
        peak = ax.peak_row(t)
        a1.plot(t["sig_a"] * KPA, t["sig_r"] * KPA, lw=0.9, ls=ls, color="k", label=lab)
        a2.plot(t["sig_a"][:peak + 1] * KPA, t["K0"][:peak + 1], lw=0.9, ls=ls, color="k",
                label=f"{lab}: loading")
        a2.plot(t["sig_a"][peak:] * KPA, t["K0"][peak:], lw=0.9, ls=ls, color="0.55",
                label=f"{lab}: unloading")
        a3.plot(t["ocr"][peak:], t["K0"][peak:], lw=0.9, ls=ls, color="k", label=lab)
        if sinphi is not None:
            ocr = np.linspace(1.0, max(float(np.max(t["ocr"])), 1.0), 50)
            a3.plot(ocr, ax.mayne_kulhawy(t["K0"][peak], ocr, sinphi), lw=0.8, ls=ls,
                    color="0.5", label=f"K0_nc·OCR^sinφ′ (sinφ′ = {sinphi:g})")
    if sinphi is not None:
        a2.axhline(ax.jaky(sinphi), color="0.5", lw=0.8, ls=":",
                   label=f"Jaky: 1 − sinφ′ = {ax.jaky(sinphi):.3f}")
    a1.set(xlabel="axial stress σa [kPa]", ylabel="radial stress σr [kPa]",
           title="Oedometric stress path")
    a2.set(xlabel="axial stress σa [kPa]", ylabel="K0 = σr/σa", title="K0 in loading and "
           "unloading")
    a3.set(xlabel="OCR = max σa/σa", ylabel="K0 = σr/σa", title="K0 on unloading")
    for a in (a1, a2, a3):
        a.grid(alpha=0.3)
        legend(a, fontsize=8)
    a1.set_xlim(left=0.0)
    a1.set_ylim(bottom=0.0)
    _axial_caption(fig, tables, about)
    return save_figure(fig, out)


def cyclic_triaxial(tables, labels, out, about=None, limits=None):
    """Undrained cyclic triaxial test: the stress path q_a against p′, the q_a–ε_a loops before
    liquefaction (the half cycles before the one in which a criterion first held) and over the
    whole test, and r_u
    against the cycle count N (continuous within a half cycle, shear.continuous_cycles), with
    N_L by r_u (circle) and by double-amplitude ε_a (square) marked at the first row where each
    criterion holds, labelled with the fix's N_L; limits = (r_u limit, double-amplitude
    limit), default 0.95 and 0.05. The stress panels draw the amplitude q_a = ±2 CSR p0 as
    dotted lines."""
    from . import axial_tests as ax
    from . import shear as sh
    ru_limit, da_limit = limits or (ax.RU_LIMIT, ax.DA_LIMIT)
    fig, ((a1, a2), (a3, a4)) = plt.subplots(2, 2, figsize=(12.5, 8.6))
    for k, (t, lab) in enumerate(zip(tables, labels)):
        ls = record_style(k)
        n = sh.continuous_cycles(t)
        rows = sh.liquefaction_rows(t, ru_limit, da_limit, strain="eps_a")
        # the complete half cycles before the one in which a criterion first held
        first = min([r for r in rows if r is not None] + [len(n) - 1])
        starts = [int(j) for j in sh.half_cycle_starts(t) if j <= first]
        first = starts[-1] if starts else first + 1
        a1.plot(t["p"] * KPA, t["q_a"] * KPA, lw=0.7, ls=ls, color="k", label=lab)
        a2.plot(t["eps_a"][:first] * PCT, t["q_a"][:first] * KPA, lw=0.7, ls=ls, color="k",
                label=lab)
        a3.plot(t["eps_a"] * PCT, t["q_a"] * KPA, lw=0.7, ls=ls, color="k", label=lab)
        a4.plot(n, t["r_u"], lw=0.9, ls=ls, color="k", label=lab)
        amplitude = 2.0 * ax.amplitude_ratio(t) * t["p"][0] * KPA
        for a in ((a1, a2, a3) if np.isfinite(amplitude) else ()):
            for sign in (1, -1):
                a.axhline(sign * amplitude, color="0.5", lw=0.7, ls=":")
        for value, r, marker, what in zip(ax.liquefaction_reported(t), rows, ("o", "s"),
                                          (f"N_L (r_u ≥ {ru_limit:g})",
                                           f"N_L (double amplitude ε_a ≥ {da_limit * PCT:g} %)")):
            if not value > 0 or r is None:
                continue
            style = dict(marker=marker, mfc="white", mec="k", ms=8, mew=1.3, ls="none",
                         label=f"{what} = {value:g}")
            a1.plot(t["p"][r] * KPA, t["q_a"][r] * KPA, **style)
            a3.plot(t["eps_a"][r] * PCT, t["q_a"][r] * KPA, **style)
            a4.plot(n[r], t["r_u"][r], **style)
    a4.axhline(ru_limit, color="0.5", lw=0.7, ls=":")
    a1.set(xlabel="mean effective stress p′ [kPa]", ylabel="deviator q_a = σa − σr [kPa]",
           title="Undrained cyclic triaxial: stress path")
    a2.set(xlabel="axial strain ε_a [%]", ylabel="deviator q_a [kPa]",
           title="Stress–strain loops before the half cycle of liquefaction")
    a3.set(xlabel="axial strain ε_a [%]", ylabel="deviator q_a [kPa]",
           title="Stress–strain, the whole test")
    a4.set(xlabel="number of cycles N", ylabel="r_u = 1 − p′/p′0", title="Excess pore pressure")
    a1.set_xlim(left=0.0)
    for a in (a1, a2, a3, a4):
        _zero_lines(a)
        legend(a, fontsize=8)
    _axial_caption(fig, tables, about)
    return save_figure(fig, out)
