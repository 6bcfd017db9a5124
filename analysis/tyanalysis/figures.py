"""Figures in the style of the paper (Agg backend, PNG). Stresses in kPa, strains in %."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import invariants as inv  # noqa: E402
from .metrics import derived, dilation_rate  # noqa: E402

KPA = 1e-3
PCT = 100.0


def save_figure(fig, out, dpi=120):
    """Lay out, write the PNG whole under a temporary name and rename it onto `out`, so that an
    interrupted run never leaves a torn figure; close the figure."""
    fig.tight_layout()
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


def axisym(tables, labels, out, void_ratio=False):
    """Figs 1-2: deviator stress sigma1 - sigma3 and volumetric strain (or void ratio) against
    the deviator strain eps1 - eps3."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for t, lab in zip(tables, labels):
        d = derived(t)
        a1.plot(d["eps_d13"] * PCT, d["dev_stress"] * KPA, label=lab)
        if void_ratio:
            a2.plot(d["eps_d13"] * PCT, t["void_ratio"], label=lab)
        else:
            a2.plot(d["eps_d13"] * PCT, d["eps_v"] * PCT, label=lab)
    a1.set_xlabel("deviator strain ε1 − ε3 [%]")
    a1.set_ylabel("deviator stress σ1 − σ3 [kPa]")
    a1.set_title("Axisymmetric compression (Fig. 1)")
    a2.set_xlabel("deviator strain ε1 − ε3 [%]")
    if void_ratio:
        a2.set_ylabel("void ratio e")
        a2.set_title("Void ratio (Fig. 2)")
    else:
        a2.set_ylabel("volumetric strain εv [%] (compression +)")
        a2.set_title("Volumetric strain (Fig. 2)")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    return save_figure(fig, out)


def cyclic(tables, labels, out):
    """Cyclic axisymmetric test: signed deviator stress sigma1 - sigma3 (q, negative in
    extension) and volumetric strain against eps1 - eps3."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for t, lab in zip(tables, labels):
        d = derived(t)
        a1.plot(d["eps_d13"] * PCT, d["dev_stress"] * KPA, lw=0.8, label=lab)
        a2.plot(d["eps_d13"] * PCT, d["eps_v"] * PCT, lw=0.8, label=lab)
    a1.set_xlabel("deviator strain ε1 − ε3 [%]")
    a1.set_ylabel("q = σ1 − σ3 [kPa] (< 0 in extension)")
    a1.set_title("Cyclic axisymmetric test at constant p")
    a2.set_xlabel("deviator strain ε1 − ε3 [%]")
    a2.set_ylabel("volumetric strain εv [%] (compression +)")
    a2.set_title("Volumetric strain")
    for a in (a1, a2):
        a.axhline(0, color="0.8", lw=0.6, zorder=0)
        a.axvline(0, color="0.8", lw=0.6, zorder=0)
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    return save_figure(fig, out)


def friction(mus, sinphi_max, sinphi_cv, out):
    """Fig. 3: peak and critical-state sin(phi) against interparticle friction."""
    order = np.argsort(mus)
    mus = np.asarray(mus, float)[order]
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.plot(mus, np.asarray(sinphi_max)[order], "o-", label="sin φ_max")
    ax.plot(mus, np.asarray(sinphi_cv)[order], "s--", label="sin φ_cv (last 10 %)")
    ax.set_xlabel("interparticle friction μ")
    ax.set_ylabel("sin φ")
    ax.set_title("Effect of interparticle friction (Fig. 3)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend()
    return save_figure(fig, out)


def radial(tables, labels, out, peaks, sinphi_tc, p_ref, strain="eps_q"):
    """Figs 4-6: sin(phi) vs eps1 - eps3, eta vs deviatoric strain, dilation rate vs
    deviatoric strain, and the peak states in the Pi plane with LD and MN surfaces through the
    compression (b = 0) strength sinphi_tc at mean stress p_ref."""
    fig, axes = plt.subplots(2, 2, figsize=(10, 9))
    a_s, a_eta, a_dil, a_pi = axes.ravel()
    slabel = "ε_q = √(2/3 e:e)" if strain == "eps_q" else "ε1 − ε3"
    for t, lab in zip(tables, labels):
        d = derived(t)
        ed = d[strain]
        a_s.plot(d["eps_d13"] * PCT, d["sinphi"], label=lab)
        a_eta.plot(ed * PCT, d["eta_LD"], label=lab)
        x, r = dilation_rate(ed, d["eps_v"])
        a_dil.plot(x * PCT, r, label=lab)
    a_s.set(xlabel="deviator strain ε1 − ε3 [%]", ylabel="sin φ", title="Mobilised friction")
    a_eta.set(xlabel=f"deviatoric strain {slabel} [%]", ylabel="η = I1³/I3 − 27",
              title="Lade–Duncan η (Fig. 5)")
    a_dil.set(xlabel=f"deviatoric strain {slabel} [%]", ylabel="−dεv/dεd",
              title="Rate of dilation (Fig. 6)")
    a_dil.axhline(0, color="0.6", lw=0.6)
    for a in (a_s, a_eta, a_dil):
        a.grid(alpha=0.3)
        a.legend(fontsize=7)

    _pi_axes(a_pi, "Peak states, Π plane (Fig. 4)", "kPa")
    rmax = 0.0
    if sinphi_tc is not None:
        for crit, style in ((inv.LADE_DUNCAN, "-"), (inv.MATSUOKA_NAKAI, "--")):
            x, y = inv.failure_surface_pi(crit, p=p_ref, sinphi_tc=sinphi_tc)
            a_pi.plot(x * KPA, y * KPA, style, color="0.3", lw=1,
                      label=f"{crit} (sin φ_TC = {sinphi_tc:.3f})")
            rmax = max(rmax, float(np.max(np.hypot(x, y))) * KPA)
    for pk, lab in zip(peaks, labels):
        a_pi.plot(pk["pi_x"] * KPA, pk["pi_y"] * KPA, "o", label=f"{lab} (b={pk['b']:.2f})")
        rmax = max(rmax, float(np.hypot(pk["pi_x"], pk["pi_y"])) * KPA)
    _axis_rays(a_pi, 1.1 * rmax if rmax else 1.0)
    a_pi.legend(fontsize=6, loc="lower right")
    return save_figure(fig, out)


def pi_plane(tables, labels, out, stress_surfaces, strain_guides):
    """Figs 7-9: stress paths (kPa) and strain paths (%) in the Pi plane with failure surfaces
    (list of (record index, label, x, y), Pa; drawn in the record's colour: Lade-Duncan dashed,
    others dotted) and strain guides (list of (label, x, y), strain units)."""
    fig, (a_e, a_s) = plt.subplots(1, 2, figsize=(11, 5.5))
    _pi_axes(a_e, "Deviatoric strain path (Π plane)", "%")
    _pi_axes(a_s, "Deviatoric stress path (Π plane)", "kPa")
    re, rs = 0.0, 0.0
    for lab, x, y in strain_guides:
        a_e.plot(x * PCT, y * PCT, ":", color="0.4", lw=1, label=lab)
        re = max(re, float(np.max(np.hypot(x, y))) * PCT)
    colors = []
    for t, lab in zip(tables, labels):
        d = derived(t)
        (line,) = a_e.plot(d["pi_ex"] * PCT, d["pi_ey"] * PCT, label=lab)
        colors.append(line.get_color())
        a_s.plot(d["pi_x"] * KPA, d["pi_y"] * KPA, color=line.get_color(), label=lab)
        re = max(re, float(np.nanmax(np.hypot(d["pi_ex"], d["pi_ey"]))) * PCT)
        rs = max(rs, float(np.nanmax(np.hypot(d["pi_x"], d["pi_y"]))) * KPA)
    for k, lab, x, y in stress_surfaces:
        style = "--" if inv.LADE_DUNCAN in lab else ":"
        a_s.plot(x * KPA, y * KPA, style, color=colors[k], lw=0.9, alpha=0.8, label=lab)
        rs = max(rs, float(np.max(np.hypot(x, y))) * KPA)
    _axis_rays(a_e, 1.1 * re if re else 1.0)
    _axis_rays(a_s, 1.1 * rs if rs else 1.0)
    a_e.legend(fontsize=7, loc="lower right")
    a_s.legend(fontsize=7, loc="lower right")
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
