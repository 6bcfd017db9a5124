"""The run lists of `tyanalysis reproduce`: the paper's programme (every run behind the figures
of docs/validation.md) and the trace study of docs/fidelity.md (one factor at a time against a
base set of runs), with the names of their records. Data only: reproduce runs them, fidelity
tabulates the trace study's records, and neither imports the other.
"""

# ---- the paper's programme -------------------------------------------------------------------

# name -> (deck, {variable: value}, the deck's `out` prefix, weight = expected core-minutes at
# paper scale, validation.md). The variables are those of validation.md's commands.
PROGRAMME = {
    "axisym_dense": ("axisym.in", {"specimen": "dense", "rate": "1e-5"}, "axisym_dense_paper", 43),
    "axisym_loose": ("axisym.in", {"specimen": "loose", "rate": "1e-5"}, "axisym_loose_paper", 46),
    **{f"friction_mu{mu}": ("friction.in", {"mu": mu, "rate": "5e-5"}, "friction_paper", w)
       for mu, w in (("0", 5), ("0.1", 7), ("0.2", 9), ("0.3", 10), ("0.5", 14), ("1.0", 19))},
    **{f"radial_dense_b{b}": ("radial.in", {"specimen": "dense", "b": b, "strain": "0.10",
                                            "rate": "1e-5"}, "radial_paper", 16)
       for b in ("0.25", "0.5", "0.75", "1")},
    **{f"radial_loose_b{b}": ("radial.in", {"specimen": "loose", "b": b, "strain": "0.30",
                                            "rate": "1e-5"}, "radial_loose_paper_1e-5", w)
       for b, w in (("0.25", 16), ("0.5", 22), ("0.75", 18), ("1", 26))},
    "cdst": ("cdst.in", {}, "cdst_paper", 3),
    "plane_strain_cw": ("plane_strain.in", {"rotation": "cw"}, "plane_strain_cw_paper", 7),
    "plane_strain_ccw": ("plane_strain.in", {"rotation": "ccw"}, "plane_strain_ccw_paper", 7),
}
# expected core-minutes of each preparation at paper scale (the two-stage protocol,
# docs/fidelity.md "Preparation protocol"): preparations start before any run
PREP_WEIGHT = {"dense": 15, "loose": 5}
# decks that run a list of values and name each record PREFIX_<variable><value>.csv
LIST_VARIABLE = {"friction.in": "mu", "radial.in": "b"}


# ---- the trace study (docs/fidelity.md) -----------------------------------------------------

# The base set's shear runs: name -> (deck, shear variables; `specimen` names the specimen)
BASE_RUNS = {
    "axisym_dense": ("axisym.in", {"specimen": "dense", "rate": "5e-5"}),
    "axisym_loose": ("axisym.in", {"specimen": "loose", "rate": "5e-5"}),
    "radial_loose": ("radial.in", {"specimen": "loose", "b": "1", "strain": "0.30",
                                   "rate": "5e-5"}),
    "plane_strain_cw": ("plane_strain.in", {"rotation": "cw"}),
}
# relative cost of each base run at paper scale, the weight that orders the scheduler (the
# study's measured wall times are in docs/fidelity.md, "The base set and the factors")
BASE_WEIGHT = {"axisym_dense": 4, "axisym_loose": 5, "radial_loose": 5, "plane_strain_cw": 2}

# factor -> (preparation variables, shear variables, runs (None: all of BASE_RUNS), weight
# factor, what it changes), in the order `reproduce` starts them: the base set and its
# scatter, then the factors likeliest to move the residuals of validation.md, the earlier
# preparation protocol last. Preparation variables go to the preparation and to each of its
# runs (the specimen cache is keyed by them); shear variables to the runs only.
FACTORS = {
    "base": ({}, {}, None, 1.0, "the chosen protocol: two-stage preparation, seed 1, maxent"),
    "seed2": ({"seed": "2"}, {}, None, 1.0, "run-to-run scatter: generator seed 2"),
    "gamma0_shear": ({}, {"gamma": "0"}, None, 1.0, "Γ = 0 during shear (paper: 0.6)"),
    "gamma06_prep": ({"prep_gamma": "0.6"}, {}, None, 1.0, "Γ = 0.6 during the preparation (base: 0)"),
    "geometric": ({"distribution": "geometric"}, {}, None, 1.0, "size distribution geometric"),
    "mean_only": ({"distribution": "mean-only"}, {}, None, 1.0, "size distribution mean-only"),
    "volume_mean": ({"distribution": "volume-mean"}, {}, None, 1.0,
                    "size distribution volume-mean"),
    "hold_undamped": ({"prep_hold_damping": "0"}, {}, ("axisym_loose", "radial_loose"), 1.0,
                      "two-stage without damping in the hold (loose only: a frictionless "
                      "packing never settles without dissipation)"),
    # to eps1 - eps3 = 80 %: eps1 = 50 % at constant volume is 75 %, and dilation by 7 % adds 3.5 %
    "n8000": ({"nspheres": "8000"}, {"strain": "0.80"}, ("axisym_dense", "axisym_loose"), 2.5,
              "8000 spheres, sheared to ε1 − ε3 = 80 % (past ε1 = 50 %)"),
    "rate_1e-5": ({}, {"rate": "1e-5"}, ("axisym_dense", "axisym_loose", "radial_loose"), 5.0,
                  "strain rate 1e-5 1/s, the paper's (base 5e-5; the plane-strain test runs at "
                  "1e-5 in both)"),
    "settle": ({}, {"settle": "50000"}, None, 1.0,
               "50 000 steps of isotropic settling at the shearing μ and Γ before the shear"),
    "dt01": ({"dt_fraction": "0.1"}, {}, None, 2.0, "timestep 0.1 of the Rayleigh time (base 0.2)"),
    "damped": ({"prep_protocol": "damped"}, {}, None, 1.0,
               "the earlier protocol: compression and hold under damping 0.7"),
}


def run_name(factor, run):
    return f"{factor}_{run}"


def factor_rank(name):
    """Place in FACTORS of the factor of a run named by run_name."""
    for i, factor in enumerate(FACTORS):
        if name.startswith(factor + "_") and name[len(factor) + 1:] in BASE_RUNS:
            return i
    raise KeyError(f"{name}: not a run of the trace study")


def out_prefix(factor, run):
    return f"fid_{factor}_{run}"


def fidelity_programme():
    """name -> (deck, variables, out prefix, weight, preparation variables): the trace study's
    runs in the form of PROGRAMME."""
    out = {}
    for factor, (prep, shear, runs, scale, _) in FACTORS.items():
        for run in runs or BASE_RUNS:
            deck, base_vars = BASE_RUNS[run]
            variables = dict(base_vars, **shear)
            out[run_name(factor, run)] = (deck, variables, out_prefix(factor, run),
                                          BASE_WEIGHT[run] * scale, dict(prep))
    return out


# the programmes: the paper's figures, and the trace study of docs/fidelity.md, whose entries
# carry a fifth element, the preparation variables of the run's specimen
PROGRAMMES = {"paper": PROGRAMME, "fidelity": fidelity_programme()}


def entry(name, prog=PROGRAMME):
    """(deck, variables, out prefix, weight, preparation variables) of a run."""
    deck, vars_, out, weight, *prep = prog[name]
    return deck, vars_, out, weight, (prep[0] if prep else {})


def record_name(name, prog=PROGRAMME):
    """CSV file of a run."""
    deck, vars_, out, _, _ = entry(name, prog)
    key = LIST_VARIABLE.get(deck)
    return f"{out}_{key}{vars_[key]}.csv" if key else out + ".csv"
