"""Bad input to pair thornton/yin stops LAMMPS with an error that names the problem."""
import numpy as np
import pytest

from lmprun import LOAD_TYLMP, reduce_local, run_deck

R = 1.0e-4


def deck(pair_coeff="pair_coeff * * 70e9 0.3 0.3 0.3", atom_style="sphere",
         comm="comm_modify vel yes", neighbor="neighbor 1e-6 bin", pair_style="pair_style thornton/yin"):
    return f"""
units si
atom_style {atom_style}
boundary p p p
{comm}
region box block 0 2e-3 0 2e-3 0 2e-3
create_box 1 box
create_atoms 1 single 1e-3 1e-3 1e-3
create_atoms 1 single {1e-3 + 2 * R - 1e-8} 1e-3 1e-3
{"set atom * diameter 2e-4 density 2650" if atom_style == "sphere" else "mass 1 1e-8"}
{LOAD_TYLMP}
{pair_style}
{pair_coeff}
{neighbor}
timestep 1e-9
run 0
"""


CASES = {
    # each: deck keyword arguments -> text the error must contain
    "E_zero": (dict(pair_coeff="pair_coeff * * 0 0.3 0.3 0.3"), "Young's modulus E must be > 0"),
    "E_negative": (dict(pair_coeff="pair_coeff * * -1e9 0.3 0.3 0.3"), "Young's modulus E must be > 0"),
    "nu_half": (dict(pair_coeff="pair_coeff * * 70e9 0.5 0.3 0.3"), "Poisson's ratio nu must lie in (-1, 0.5)"),
    "nu_minus_one": (dict(pair_coeff="pair_coeff * * 70e9 -1 0.3 0.3"), "Poisson's ratio nu must lie in (-1, 0.5)"),
    "mu_negative": (dict(pair_coeff="pair_coeff * * 70e9 0.3 -0.1 0.3"), "friction coefficient mu must be >= 0"),
    "Gamma_negative": (dict(pair_coeff="pair_coeff * * 70e9 0.3 0.3 -0.3"), "interface energy Gamma must be >= 0"),
    "too_few": (dict(pair_coeff="pair_coeff * * 70e9 0.3 0.3"), "expected 'pair_coeff I J E nu mu Gamma"),
    "unknown_keyword": (dict(pair_coeff="pair_coeff * * 70e9 0.3 0.3 0.3 stiff 2"), "Unknown pair_coeff keyword 'stiff'"),
    "damping_missing_value": (dict(pair_coeff="pair_coeff * * 70e9 0.3 0.3 0.3 damping 0.1"), "'damping' needs two values"),
    "pair_style_args": (dict(pair_style="pair_style thornton/yin 1.0"), "pair_style thornton/yin takes no arguments, got '1.0'"),
    # a benchmark build now (bench/variants.cmake), no longer a keyword
    "pair_style_paths": (dict(pair_style="pair_style thornton/yin paths generic"), "pair_style thornton/yin takes no arguments, got 'paths'"),
    "no_radius": (dict(atom_style="atomic"), "requires atom style sphere"),
    "no_ghost_velocity": (dict(comm=""), "comm_modify vel yes"),
    "skin_too_small": (dict(pair_coeff="pair_coeff * * 70e9 0.3 0.3 3.0", neighbor="neighbor 1e-8 bin"),
                       "is not larger than the JKR break separation"),
}

# every numeric argument refuses inf, nan and a value that overflows to inf, naming itself
# (utils::numeric alone turns 1e400 into inf and refuses 'inf' without naming the argument)
COEFF_ARGUMENTS = [("Young's modulus E", "{} 0.3 0.3 0.3"), ("Poisson's ratio nu", "70e9 {} 0.3 0.3"),
                   ("friction coefficient mu", "70e9 0.3 {} 0.3"),
                   ("interface energy Gamma", "70e9 0.3 0.3 {}"),
                   ("damping ratio beta_n", "70e9 0.3 0.3 0.3 damping {} 0.1"),
                   ("damping ratio beta_t", "70e9 0.3 0.3 0.3 damping 0.1 {}")]
for _name, _args in COEFF_ARGUMENTS:
    for _value in ("inf", "nan", "1e400", "-inf"):
        CASES[f"{_name.split()[-1]}_{_value}"] = (
            dict(pair_coeff="pair_coeff * * " + _args.format(_value)),
            f"pair_coeff thornton/yin: {_name} must be a finite number, got '{_value}'")
    # text that is no number at all is named too (utils::numeric would not say which)
    CASES[f"{_name.split()[-1]}_text"] = (
        dict(pair_coeff="pair_coeff * * " + _args.format("7O")),
        f"pair_coeff thornton/yin: {_name} must be a number, got '7O'")


@pytest.mark.parametrize("name", sorted(CASES))
def test_bad_input_is_rejected_with_named_error(name, tmp_path):
    kwargs, message = CASES[name]
    rc, out = run_deck(deck(**kwargs), tmp_path)
    assert "ERROR" in out, out[-2000:]
    assert message in out, out[-2000:]


def test_good_input_runs(tmp_path):
    # the reference deck above is accepted as it stands (so the cases differ only by their fault)
    rc, out = run_deck(deck(), tmp_path)
    assert rc == 0 and "ERROR" not in out, out[-2000:]


def test_timestep_near_rayleigh_limit_warns(tmp_path):
    # R = 0.1 mm, rho = 2650: Rayleigh time 1.065e-7 s (docs/theory.md §4.1); dt = 1e-7 must warn
    text = deck().replace("timestep 1e-9", "timestep 1e-7")
    rc, out = run_deck(text, tmp_path)
    assert rc == 0
    assert "exceeds 0.3 x the Rayleigh time" in out and "reduce the timestep" in out, out[-2000:]


def deforming_deck(deform):
    # two touching spheres in a periodic box deformed by fix deform with remap x
    return deck().replace("run 0", f"""fix integrate all nve/sphere
fix deform all deform 1 {deform} remap x
run 5
""")


@pytest.mark.parametrize("deform, warns", [
    ("x erate 1e3 y volume z volume", True),      # LAMMPS 2021 leaves h_rate = 0 for 'volume'
    ("x erate 1e3 y erate -5e2 z erate -5e2", False),
    ("x trate 1e3 y trate -5e2 z trate -5e2", False),
])
def test_box_change_without_rate_warns(deform, warns, tmp_path):
    # the affine contact velocity comes from domain->h_rate: a box change it does not explain
    # gets a warning naming the component and what to use instead
    rc, out = run_deck(deforming_deck(deform), tmp_path)
    assert rc == 0 and "ERROR" not in out, out[-2000:]
    warned = "changed by" in out and "h_rate" in out
    assert warned == warns, out[-3000:]
    if warns:
        assert "box component h_yy" in out and "fix cell/servo" in out


@pytest.mark.parametrize("parameter, formula, name", [
    ("mu", "(1e308*10)-(1e308*10)", "friction coefficient mu"),     # inf - inf = nan
    ("Gamma", "1e308*10", "interface energy Gamma"),                # overflows to inf
    ("mu", "-0.1", "friction coefficient mu"),
])
def test_fix_adapt_cannot_set_a_non_finite_or_negative_value(parameter, formula, name, tmp_path):
    # fix adapt writes mu and Gamma through extract() at run time: the pair re-checks them
    text = deck().replace("run 0", f"""variable value equal {formula}
fix adapt all adapt 1 pair thornton/yin {parameter} * * v_value
run 1
""")
    rc, out = run_deck(text, tmp_path)
    assert f"pair thornton/yin: {name} of types 1 1 must be finite and >= 0" in out, out[-2000:]


NAN = "variable bad atom (1e308*10)-(1e308*10)\n"    # inf - inf: a NaN per-atom value


@pytest.mark.parametrize("setting, bad, damping", [
    ("set atom 1 vx v_bad", "velocity of atom 1", ""),
    ("set atom 2 omega 0 0 v_bad", "angular velocity of atom 2", ""),
    # damped: the NaN velocity reaches the force already at step 0 (setup)
    ("set atom 1 vx v_bad", "velocity of atom 1", " damping 0.1 0.1"),
])
def test_nan_during_a_run_stops_it_naming_the_atoms(setting, bad, damping, tmp_path):
    # a NaN position fails no 'delta > r' test and a NaN velocity or spin none at all: the run
    # must stop at the step the NaN reaches the contact, not continue with NaN energies
    text = deck(pair_coeff=f"pair_coeff * * 70e9 0.3 0.3 0.3{damping}").replace(
        "run 0", NAN + setting + "\nfix integrate all nve/sphere\nthermo 1\nrun 5\n")
    rc, out = run_deck(text, tmp_path)
    step = 0 if damping else 1
    assert (f"non-finite value at step {step} in the contact of atoms 1 and 2" in out
            and bad in out), out[-2000:]
    # nothing after it: no thermo line of a later step
    assert "\n       2 " not in out


# ---- coefficients finite but outside what the law means (bounds derived from the law) --------
R_STAR = R / 2.0                                  # two equal spheres of radius R
E_STAR = 70e9 / (2.0 * (1.0 - 0.3 ** 2))


@pytest.mark.parametrize("pair_coeff, extra, message", [
    # the closed-form JKR root overflows (Gamma^2 R*^4 E*^4 delta^3): ran with -nan at step 0
    ("pair_coeff * * 1e100 0.3 0.3 0.3", "", "the contact radius a of the contact law is not finite"),
    # E*^2 underflows in delta_f: NaN cutoff, segmentation fault in the neighbor binning
    ("pair_coeff * * 1e-300 0.3 0.3 0", "", "the break overlap delta_f of the contact law is not finite"),
    # the sliding limit's stored energy overflows
    ("pair_coeff * * 70e9 0.3 1e300 0.3", "", "the tangential energy at sliding of the contact law is not finite"),
    # rho/G underflows: 'reduce the timestep to at most 0' before
    ("pair_coeff * * 1e200 0.3 0 0", "set atom * density 1e-200\n",
     "the Rayleigh time pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smallest sphere is 0"),
])
def test_coefficients_the_law_cannot_represent_are_refused(pair_coeff, extra, message, tmp_path):
    text = deck(pair_coeff=pair_coeff).replace("timestep", extra + "timestep")
    rc, out = run_deck(text, tmp_path)
    assert "ERROR" in out and message in out, out[-2000:]


def test_gamma_whose_zero_load_contact_exceeds_the_sphere_is_refused(tmp_path):
    # JKR is a small-contact theory: a0 = (9 pi Gamma R*^2/E*)^(1/3) < R*, i.e.
    # Gamma < E* R*/(9 pi); before, Gamma = 1e10 J/m^2 only got a skin suggestion
    rc, out = run_deck(deck(pair_coeff="pair_coeff * * 70e9 0.3 0.3 1e10",
                            neighbor="neighbor 0.1 bin"), tmp_path)
    bound = E_STAR * R_STAR / (9.0 * np.pi)
    a0 = (9.0 * np.pi * 1e10 * R_STAR ** 2 / E_STAR) ** (1.0 / 3.0)
    assert "is not smaller than R* = 5e-05" in out, out[-2000:]
    assert f"= {a0:.4g} is not smaller" in out and f"below E* R*/(9 pi) = {bound:.4g}" in out


def test_large_but_legal_gamma_warns_with_the_contact_size(tmp_path):
    # Gamma = 1000 J/m^2: a0/R* = 0.245 > 0.1, legal but the contact is large before any load
    rc, out = run_deck(deck(pair_coeff="pair_coeff * * 70e9 0.3 0.3 1000",
                            neighbor="neighbor 1e-5 bin"), tmp_path)
    ratio = (9.0 * np.pi * 1000 * R_STAR ** 2 / E_STAR) ** (1.0 / 3.0) / R_STAR
    assert rc == 0 and "ERROR" not in out, out[-2000:]
    assert f"zero-load contact radius a0 = {ratio:.4g} R*" in out, out[-2000:]


@pytest.mark.parametrize("beta, message", [
    ("2", "is above 1: contacts are overdamped"),
    # dt_R/(2 pi dt) = 1.065e-7 s/(2 pi 1e-9 s) = 16.9 (theory.md §4)
    ("50", "too large for the explicit step"),
])
def test_large_damping_ratio_warns(beta, message, tmp_path):
    rc, out = run_deck(deck(pair_coeff=f"pair_coeff * * 70e9 0.3 0.3 0.3 damping {beta} 0"),
                       tmp_path)
    assert rc == 0 and f"damping ratio {beta} " in out and message in out, out[-2000:]


def test_moderate_damping_ratio_does_not_warn(tmp_path):
    rc, out = run_deck(deck(pair_coeff="pair_coeff * * 70e9 0.3 0.3 0.3 damping 0.9 0.5"),
                       tmp_path)
    # (4 Feb 2025 also warns that no fix integrates this static deck: not about the pair)
    warnings = [l for l in out.splitlines()
                if "WARNING" in l and "No fixes with time integration" not in l]
    assert rc == 0 and not warnings, out[-2000:]


def one_sphere_cell(box_fix):
    # a sphere alone in a 1 cm periodic box: the pair's box-rate check runs without contacts
    return f"""
units si
atom_style sphere
boundary p p p
comm_modify vel yes
region box block 0 1e-2 0 1e-2 0 1e-2
create_box 1 box
create_atoms 1 single 2e-3 7e-3 4e-3
set atom 1 diameter 1e-3 density 2650
{LOAD_TYLMP}
pair_style thornton/yin
pair_coeff * * 70e9 0.3 0.3 0.0
fix integrate all nve/sphere
{box_fix}
timestep 1e-3
run 40
"""


@pytest.mark.parametrize("box_fix, warns", [
    # eps_dot dt up to 1e-2 per step: the exponential update of fix cell/servo differs from
    # h_rate dt by eps_dot dt/2 = 0.5 %, which the old linear check blamed on a barostat
    ("fix cell all cell/servo axes x rate 2 y rate -10 z rate 4", False),
    ("fix deform all deform 1 x trate 5 y trate -10 z trate 2 remap x", False),
    ("fix deform all deform 1 x erate 5 y erate -10 z erate 2 remap x", False),
    # a box change h_rate does not carry is still caught at fast rates
    ("fix deform all deform 1 x trate 10 y volume z volume remap x", True),
])
def test_box_rate_check_is_exact_for_exponential_updates(box_fix, warns, tmp_path):
    rc, out = run_deck(one_sphere_cell(box_fix), tmp_path)
    assert rc == 0 and "ERROR" not in out, out[-2000:]
    assert ("changed by" in out and "h_rate" in out) == warns, out[-3000:]
    if warns:
        assert "box component h_yy" in out


def test_overflowing_damping_force_stops_the_run(tmp_path):
    # beta = 1e300 is finite and only warned about at init; the velocities it produces
    # overflow the next force, which must stop the run naming the contact, not run on with
    # an infinite temperature
    text = deck(pair_coeff="pair_coeff * * 70e9 0.3 0.3 0.3 damping 1e300 0").replace(
        "run 0", "fix integrate all nve/sphere\nrun 5\n")
    rc, out = run_deck(text, tmp_path)
    assert "damping ratio 1e+300 is too large for the explicit step" in out
    assert rc != 0, out[-2000:]
    # the run stops: in 29 Sep 2021 at the pair's check of the next (overflowing) force; in
    # 4 Feb 2025 the spheres thrown out by the first, finite but huge, damping force are lost
    # before that force is evaluated, and LAMMPS stops on the lost atoms
    assert ("the contact force of atoms 1 and 2 is not finite at step" in out
            or "4 Feb 2025" in out and "ERROR: Lost atoms" in out), out[-2000:]


# ---------------------------------------------------------------------------------------------
# hybrid pair styles and units (issue 31 items 12 and 14)

HYBRID = dict(pair_style="pair_style hybrid thornton/yin",
              pair_coeff="pair_coeff * * thornton/yin 70e9 0.3 0.3 0.3")
PAIR_LOCAL_SUM = ("compute pl all pair/local force\n" + reduce_local("s", "c_pl") +
                  "thermo_style custom step c_s\nthermo_modify format float %.15g\nthermo 1\n")


@pytest.mark.parametrize("style", ["hybrid", "hybrid/overlay"])
def test_pair_local_force_under_hybrid_is_the_jkr_force(style, tmp_path):
    """compute pair/local force with the pair under pair_style hybrid: the JKR load of the two
    touching spheres (tests/jkr_reference.py), not the segmentation fault of LAMMPS's
    PairHybrid::copy_svector (an endless loop over the sub-style's extra values)."""
    import jkr_reference as ref
    kwargs = dict(HYBRID, pair_style=f"pair_style {style} thornton/yin")
    rc, out = run_deck(deck(**kwargs).replace("run 0", PAIR_LOCAL_SUM + "run 0"), tmp_path)
    assert rc == 0 and "ERROR" not in out, out[-2000:]
    lines = out.splitlines()
    value = float(lines[[l.split()[:2] for l in lines].index(["Step", "c_s"]) + 1].split()[1])
    E_star = ref.effective_modulus(70e9, 0.3)
    assert value == pytest.approx(ref.normal_force(1e-8, R / 2, E_star, 0.3), rel=1e-6)


@pytest.mark.parametrize("reader", ["compute c all thornton/yin/contacts",
                                    "compute m all thornton/yin/micromechanics",
                                    "fix c all cell/servo iso 1e5"],
                         ids=["contacts", "micromechanics", "cell_servo"])
def test_hybrid_scaled_with_contact_outputs_is_refused(reader, tmp_path):
    """hybrid/scaled 2 applies 2F to the atoms while the contact outputs read F: refused,
    naming the reader (they reported half the applied force)."""
    kwargs = dict(HYBRID, pair_style="pair_style hybrid/scaled 2.0 thornton/yin")
    rc, out = run_deck(deck(**kwargs).replace("run 0", reader + "\nrun 0"), tmp_path)
    name = reader.split()[1]
    assert ("pair thornton/yin under pair_style hybrid/scaled: the scale factor multiplies the "
            "forces on the atoms, but") in out and f" {name} (" in out, out[-2000:]
    # without a reader the forces are the scaled ones, and nothing is refused
    rc, out = run_deck(deck(**kwargs), tmp_path, name="in.plain")
    assert rc == 0 and "ERROR" not in out, out[-2000:]


@pytest.mark.parametrize("units,unit", [("si", "J/m^2"), ("cgs", "erg/cm^2")])
def test_gamma_message_names_the_deck_units(units, unit, tmp_path):
    """'units cgs': the message gives Gamma in erg/cm^2, the unit the deck uses."""
    text = deck(pair_coeff="pair_coeff * * 70e9 0.3 0.3 -0.3").replace("units si",
                                                                      f"units {units}")
    rc, out = run_deck(text, tmp_path)
    assert f"interface energy Gamma must be >= 0 {unit} (got -0.3)" in out, out[-2000:]


def two_type_deck(pair_style, pair_coeff):
    """The two touching spheres of deck(), the second of type 2."""
    text = deck(pair_style=pair_style, pair_coeff=pair_coeff).replace("create_box 1 box",
                                                                     "create_box 2 box")
    return text.replace(f"create_atoms 1 single {1e-3 + 2 * R - 1e-8}",
                        f"create_atoms 2 single {1e-3 + 2 * R - 1e-8}").replace("run 0", "run 5")


def test_hybrid_with_another_style_on_other_types_runs(tmp_path):
    """thornton/yin on types 1 1 only, pair zero on the rest: the pair checks only its own
    type pairs (it stopped with 'coefficients for types 2 2 are not set and cannot be mixed',
    though pair_coeff 2 2 zero was given)."""
    text = two_type_deck("pair_style hybrid thornton/yin zero 1e-4",
                         "pair_coeff 1 1 thornton/yin 70e9 0.3 0.3 0.3\n"
                         "pair_coeff 1 2 zero\npair_coeff 2 2 zero")
    rc, out = run_deck(text, tmp_path)
    assert rc == 0 and "ERROR" not in out, out[-2000:]


def test_second_thornton_yin_in_hybrid_is_refused(tmp_path):
    """Two thornton/yin sub-styles would share one contact-history store (LAMMPS said 'Modify
    replace_fix ID NEIGH_HISTORY_THORNTON_YIN_DUMMY could not be found')."""
    text = two_type_deck("pair_style hybrid thornton/yin thornton/yin",
                         "pair_coeff 1 1 thornton/yin 1 70e9 0.3 0.3 0.3\n"
                         "pair_coeff 2 2 thornton/yin 2 70e9 0.3 0.3 0.3\n"
                         "pair_coeff 1 2 thornton/yin 1 70e9 0.3 0.3 0.3")
    rc, out = run_deck(text, tmp_path)
    assert "pair thornton/yin may appear only once in a hybrid pair style" in out, out[-2000:]
