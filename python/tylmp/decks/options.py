"""A deck's start: its enumerated and numeric -var options checked (CHOICES, NUMBERS), the
directory of the shared fragments set (tylmp_common), and after the material file the material,
the size distribution and the smallest diameter (d_min, from which numerics.in derives the
timestep)."""

import math
import os

from .. import specimen
from .restitution import damping_ratio_for_restitution
from .session import (command_line_vars, deck_path, defined_variables, fail, lammps_at, say,
                      variable_values)

# the enumerated -var options of the decks: variable -> allowed values (first: the default)
CHOICES = {
    "specimen": ("dense", "loose"),
    "scale": ("quick", "paper"),
    "rotation": ("cw", "ccw"),
    "plane": ("total", "deviatoric"),
    "control": ("strain", "stress"),
    "prep_protocol": ("damped", "two_stage"),
    # the contact law of the shearing stage (common/pair.in)
    "law": ("thornton_yin", "granular", "gran_hertz_history"),
    # the tests of the six-component cell (simple_shear.in, cyclic_simple_shear.in, undrained.in)
    "drainage": ("drained", "constant_volume"),
    "shear_plane": ("xz", "xy", "yz"),
    "direction": ("compression", "extension"),
    "after_liquefaction": ("continue", "stop"),
    # the loaded axis of the tests along an axis (k0.in, cyclic_triaxial.in)
    "axis": ("z", "x", "y"),
    "loading": ("two_way", "one_way"),
}

# -var distribution: a candidate of tylmp.specimen or a user's distribution string, checked by
# tylmp.specimen.parse_distribution
MATERIAL = ("E", "nu", "rho", "mu", "gamma", "damping")

# the numeric -var options: variable -> (integer?, smallest allowed value, what it is[, above,
# below]); each must be a finite number (inf, nan, 1e400 refused) not below its bound (above
# it when `above`) and below `below` when given
NUMBERS = {
    # the material (MATERIAL; materials/glass.in) and the timestep
    "E": (False, 0.0, "Young's modulus of the spheres, Pa", True),
    "nu": (False, -1.0, "Poisson's ratio of the spheres", True, 0.5),
    "rho": (False, 0.0, "the particle density, kg/m3", True),
    "mu": (False, 0.0, "the interparticle friction coefficient"),
    "prep_mu": (False, 0.0, "the friction coefficient of a loose preparation"),
    "damping": (False, 0.0, "the viscous damping ratio of the contacts"),
    "restitution": (False, 0.0, "the coefficient of restitution of a head-on impact (at most 1)",
                    True),
    "dt": (False, 0.0, "the timestep, s", True),
    "dt_fraction": (False, 0.0, "the timestep as a fraction of the Rayleigh time", True),
    "seed": (True, 0, "the specimen generator's seed"),
    # at least 100: a 1.3 mm cell at phi0 = 0.5, 1.2 mm at phi = 0.66; fix cell/servo refuses a
    # cell narrower than twice the neighbour cutoff (0.83 mm), which fewer than about 40
    # spheres reach, and a few dozen spheres are no assembly
    "nspheres": (True, 100, "the number of spheres"),
    "settle": (True, 0, "the steps of isotropic settling at the shearing mu and Gamma"),
    "gamma": (False, 0.0, "the interface energy during shear, J/m2"),
    "prep_gamma": (False, 0.0, "the interface energy during the preparation, J/m2"),
    "sigma_n": (False, 0.0, "the normal stress of simple shear, Pa", True),
    # the mean stress of the axisymmetric and undrained tests (common/settle.in consolidates)
    "pressure": (False, 0.0, "the mean stress p of the test, Pa", True),
    "consolidate_steps": (True, 1, "the most steps of the consolidation to -var pressure"),
    "csr": (False, 0.0, "the cyclic stress ratio (tau_cyc/sigma_n0 of simple shear, q_cyc/(2 p0) "
                        "of the triaxial test)", True),
    # principal stress rotation (rotation.in)
    "rotation_p": (False, 0.0, "the mean stress p held during the rotation, Pa", True),
    "rotation_dev": (False, 0.0, "the deviator stress sigma1 - sigma3 held during the rotation, "
                                 "Pa"),
    "servo_gain": (False, 0.0, "the fraction of the stress error the servo removes per step",
                   True),
    "rotation_b": (False, 0.0, "the intermediate principal stress ratio b = (sigma2 - "
                               "sigma3)/(sigma1 - sigma3) held during the rotation (0 to 1)"),
    "rotation_rate": (False, 0.0, "the rotation rate of the major principal stress, degree/s",
                      True),
    "rotation_turn": (False, 0.0, "the total rotation of the major principal stress, degrees",
                      True),
    "ramp": (False, 0.0, "the deviator strain rate of the ramp to (p, q, b), 1/s", True),
    # cyclic simple shear and cyclic triaxial (cyclic_simple_shear.in, cyclic_triaxial.in)
    "ru_limit": (False, 0.0, "the liquefaction criterion on r_u (at most 1)", True, 1.0 + 1e-12),
    "da_limit": (False, 0.0, "the liquefaction criterion on the double amplitude strain (gamma, "
                             "or eps_a of the triaxial test)", True),
    "gamma_max": (False, 0.0, "the |gamma| at which a cyclic test ends", True),
    # oedometric compression (k0.in)
    "sigma_max": (False, 0.0, "the axial stress at which the loading of a k0 test ends, Pa", True),
    "ocr": (False, 1.0, "the overconsolidation ratio at the end of unloading (1: none)"),
    "eps_max": (False, 0.0, "the |axial strain| at which a k0 or cyclic triaxial test ends", True),
}

def fragments_dir(deck=None):
    """Directory of the shared fragments: common/ beside the deck if it has one (the
    repository's inputs/), else the copy installed with this package (tylmp/inputs/common)."""
    if deck:
        beside = os.path.join(os.path.dirname(os.path.abspath(deck)), "common")
        if os.path.isfile(os.path.join(beside, "specimen.in")):
            return beside
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))      # tylmp/
    return os.path.join(package, "inputs", "common")


def check_number(name, value):
    """None if `value` (a string) is allowed for the numeric option `name`, else why not."""
    entry = NUMBERS[name]
    integer, lowest, what, above, below = entry + (False, None)[len(entry) - 3:]
    try:
        number = int(value) if integer else float(value)
    except ValueError:
        return (f"-var {name} {value}: not {'an integer' if integer else 'a number'}; "
                f"{name} is {what}")
    if not math.isfinite(number):
        return f"-var {name} {value}: not a finite number; {name} is {what}"
    if number < lowest or (above and number == lowest):
        return (f"-var {name} {value}: must be {'above' if above else 'at least'} {lowest:g}; "
                f"{name} is {what}")
    if below is not None and number >= below:
        return f"-var {name} {value}: must be below {below:g}; {name} is {what}"
    return None


def _check_options(L, names, origin=None):
    """Fail on the first of the present options `names` whose value is not allowed; a value
    not given with -var is named as coming from `origin` (e.g. the material file)."""
    given = command_line_vars()
    present = defined_variables(L, names)
    values = variable_values(L, present)
    for name in present:
        if name in CHOICES and values[name] not in CHOICES[name]:
            fail(L, f"-var {name} {values[name]}: unknown value; {name} is one of "
                    f"{', '.join(CHOICES[name])}")
        why = check_number(name, values[name]) if name in NUMBERS else None
        if name == "distribution":
            try:
                specimen.parse_distribution(values[name])
            except ValueError as err:
                why = f"-var distribution {values[name]}: {err}"
        if why and origin and name not in given:
            why = f"{origin}: " + why[len("-var "):]
        if why:
            fail(L, why)
    return values


def begin(ptr):
    """Check the deck's enumerated and numeric -var options; set tylmp_common (unless the
    user did)."""
    L = lammps_at(ptr)
    _check_options(L, list(CHOICES) + list(NUMBERS) + ["distribution"])
    values = variable_values(L, defined_variables(L, ["tylmp_common"]))
    if "tylmp_common" in values:
        common = values["tylmp_common"]
    else:
        common = fragments_dir(deck_path())
        L.command(f'variable tylmp_common string "{common}"')
    say(L, f"deck fragments: {common}")
    if not os.path.isfile(os.path.join(common, "specimen.in")):
        fail(L, f"tylmp_common = {common}: the deck fragments (specimen.in, prepare.in, "
                "numerics.in) are not there")


def material(ptr):
    """After the material file (specimen.in): check the material and the size distribution,
    print them, and set d_min, the smallest diameter of nspheres spheres of the distribution
    (a string variable holding the exact number), from which numerics.in derives the
    timestep."""
    L = lammps_at(ptr)
    source = variable_values(L, ["material"])["material"]
    values = _check_options(L, list(MATERIAL) + ["prep_mu", "distribution", "nspheres"],
                            f"material {source}")
    missing = [name for name in MATERIAL if name not in values]
    if missing:
        fail(L, f"material {source}: {', '.join(missing)} not defined; a material file "
                "defines E, nu, rho, mu, gamma and damping (inputs/materials/glass.in)")
    restitution = variable_values(L, defined_variables(L, ["restitution"])).get("restitution")
    if restitution is not None:
        _check_options(L, ["restitution"])
        e = float(restitution)
        if e > 1.0:
            fail(L, f"-var restitution {restitution}: must be at most 1 (1: elastic contacts)")
        if "damping" in command_line_vars() and float(values["damping"]) != 0.0:
            fail(L, f"-var restitution {restitution} and -var damping {values['damping']} "
                    "both set the contacts' damping: give one of them")
        values["damping"] = repr(damping_ratio_for_restitution(e))
        L.command("variable damping delete")    # the material file's index variable
        L.command(f'variable damping string "{values["damping"]}"')
    law = variable_values(L, defined_variables(L, ["law"])).get("law", CHOICES["law"][0])
    if law != "thornton_yin" and float(values["damping"]) != 0.0:
        fail(L, f"-var law {law} shears without contact damping (common/pair.in), but the "
                f"material's damping is {values['damping']}: give -var damping 0")
    if law == "gran_hertz_history" and float(values["gamma"]) != 0.0:
        fail(L, f"-var law gran_hertz_history has no adhesion, but the material's Gamma is "
                f"{values['gamma']}: give -var gamma 0")
    d_min = float(specimen.diameters(int(values["nspheres"]), values["distribution"]).min())
    L.command(f'variable d_min string "{d_min!r}"')
    damping = f"damping {values['damping']}" + (
        f" (restitution {restitution})" if restitution is not None else "")
    say(L, f"material {source}: E = {values['E']} Pa, nu = {values['nu']}, "
           f"rho = {values['rho']} kg/m3, mu = {values['mu']}, Gamma = {values['gamma']} J/m2, "
           f"{damping}; size distribution {values['distribution']}, "
           f"{values['nspheres']} spheres, smallest diameter {d_min!r} m")
