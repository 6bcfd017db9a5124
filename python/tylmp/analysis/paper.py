"""The paper's numbers, in one place: Thornton, "DEM simulations of quasi-static shear
deformation of granular media" (the periodic-cell paper the decks reproduce). Each entry names
the paper's section and figure. The paper gives most results only as curves; the numbers here
are the ones stated in its text (plus e = 1/nu_s - 1 derived from the stated solid fractions).

Figure 3 overlays Skinner's experimental sin(phi_cv) and Horne's theoretical phi_cv(mu) curve,
but the text states no numbers for either (only that Skinner's data suggest sin(phi_cv)
independent of mu and that Horne's theory, which ignores rotation, lies well above both): no
entry, and the friction figure says so.
"""
import math

# key: (value, unit, source, note)
VALUES = {
    "n_particles": (3620, "", "§2", "five sizes, 0.135-0.4 mm, mean 0.26 mm, cell 4.3 mm"),
    "p_kPa": (100.0, "kPa", "§2-§5", "constant mean stress of all shear tests"),
    "solid_fraction_dense": (0.660, "", "§2", "start of shear, prepared with μ = 0"),
    "solid_fraction_loose": (0.618, "", "§2", "start of shear, prepared with μ = 0.3"),
    "void_ratio_start_dense": (1 / 0.660 - 1, "", "§2 (derived)", "e = 1/ν_s − 1"),
    "void_ratio_start_loose": (1 / 0.618 - 1, "", "§2 (derived)", "e = 1/ν_s − 1"),
    "coordination_dense": (6.07, "", "§2", "average coordination number, end of isotropic compression; "
                           "compared with Zm, rattlers excluded (docs/fidelity.md)"),
    "coordination_loose": (5.02, "", "§2", "average coordination number, end of isotropic compression; "
                           "compared with Zm, rattlers excluded (docs/fidelity.md)"),
    "eps_d13_at_peak_dense_pct": (5.0, "%", "§3, Fig. 1", "'peak ... at about 5% strain' (approx.)"),
    "eps_d13_steady_loose_pct": (15.0, "%", "§3, Fig. 1", "loose: constant deviator stress from about 15% (approx.)"),
    "void_ratio_30pct_dense": (0.598, "", "§3, Fig. 2", "at 30% deviator strain"),
    "void_ratio_30pct_loose": (0.606, "", "§3, Fig. 2", "at 30% deviator strain"),
    "b_at_max_sinphi": (0.5, "", "§4, Fig. 4", "dense: largest sinφ_max of the radial b tests"),
    "b_at_max_sinphi_loose": (0.5, "", "§4, Fig. 4", "loose: largest sinφ_max of the radial b tests "
                              "('the maximum value of sinφ_max occurred when b = 0.5', both systems)"),
    "extension_minus_compression_dense": (None, "", "§4, Fig. 4",
                                          "dense: sinφ_max(b = 1) − sinφ_max(b = 0) > 0 "
                                          "(Lade–Duncan, 'confirmed ... for both the dense and loose systems')"),
    "extension_minus_compression_loose": (None, "", "§4, Fig. 4",
                                          "loose: sinφ_max(b = 1) − sinφ_max(b = 0) > 0"),
    "eta_normalisation_limit": (7.0, "", "§4, Fig. 5", "η–ε_d curves of b = 0, 0.5, 1 coincide for η < 7"),
    "prestrain_eps_d_pct": (0.285, "%", "§5, Figs 7-9", "axisymmetric-compression prestrain (deviatoric strain)"),
    "prestrain_q_kPa": (51.4, "kPa", "§5, Figs 7-9", "deviatoric stress after the prestrain"),
    "cdst_p_deviation_kPa": (0.8, "kPa", "§5, Fig. 7", "constant deviatoric strain test: p within 100 ± 0.8 kPa"),
    "ps_stress_rotation_deg": (79.0, "deg", "§5, Fig. 9",
                               "multi-axial plane-strain test: stress rotation while the strain rotates the first 60°"),
}

# The bands inside which a result counts as reproducing the paper (lo, hi), one per quantity
# (docs/validation.md, "The numbers"): the paper states most numbers as "ca." or reads them off a
# curve, so each band is the width such a reading allows: solid fraction ±0.005, coordination
# ±0.2, dense peak strain 3–7 %, loose plateau 10–20 %, void ratio at 30 % ±0.015, q after the
# pre-strain ±15 %, rotation 70–88°, b of the largest sinφ_max 0.4–0.6, extension stronger
# than compression (a positive difference).
BANDS = {
    "solid_fraction_dense": (0.655, 0.665),
    "solid_fraction_loose": (0.613, 0.623),
    "coordination_dense": (5.87, 6.27),
    "coordination_loose": (4.82, 5.22),
    "eps_d13_at_peak_dense_pct": (3.0, 7.0),
    "eps_d13_steady_loose_pct": (10.0, 20.0),
    "void_ratio_30pct_dense": (0.583, 0.613),
    "void_ratio_30pct_loose": (0.591, 0.621),
    "prestrain_q_kPa": (51.4 * 0.85, 51.4 * 1.15),
    "ps_stress_rotation_deg": (70.0, 88.0),
    "b_at_max_sinphi": (0.4, 0.6),
    "b_at_max_sinphi_loose": (0.4, 0.6),
    "extension_minus_compression_dense": (0.0, float("inf")),
    "extension_minus_compression_loose": (0.0, float("inf")),
}

# the strain rotation over which the paper's 79° is measured (§5, Figs 8-9: "as the deviatoric
# strain vector rotates through 60° from an axisymmetric compression strain state to an
# axisymmetric extension state")
PS_STRAIN_ROTATION_DEG = 60.0


def value(key):
    return VALUES[key][0]


def label(key, text=None):
    """Legend text of an overlaid paper value: 'paper (§3, Fig. 2): ...'."""
    v, unit, source, note = VALUES[key]
    return f"paper ({source}): {text if text is not None else note}"


def prestrain_q_pi_radius():
    """Π radius (Pa) of the paper's stress after the prestrain: q = 51.4 kPa in axisymmetric
    compression, |s| = sqrt(2/3) q."""
    return math.sqrt(2.0 / 3.0) * value("prestrain_q_kPa") * 1e3
