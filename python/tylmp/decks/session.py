"""The running LAMMPS as the decks' `python` commands see it: its variables, its command line,
and messages and errors in LAMMPS's form ("ERROR: ..." on the screen and in the log, then exit
status 1: LAMMPS 29 Sep 2021 has no library call to raise a LAMMPS error from Python)."""

import os

_collected = []


def collect(*values):
    """Receives variable values from LAMMPS (see variable_values)."""
    _collected[:] = values


def lammps_at(ptr):
    from lammps import lammps
    return lammps(ptr=ptr)


def defined_variables(L, names):
    """The subset of names that are LAMMPS variables now."""
    out = []
    for name in names:
        L.command(f"variable tylmp_defined equal is_defined(variable,{name})")
        if L.extract_variable("tylmp_defined") == 1.0:
            out.append(name)
    L.command("variable tylmp_defined delete")
    return out


def variable_values(L, names):
    """Current values (strings) of LAMMPS variables of any style: the `python` command passes
    v_name arguments as their values, whatever the style (the library cannot read strings)."""
    if not names:
        return {}
    args = " ".join(f"v_{n}" for n in names)
    L.command(f'python tylmp_values input {len(names)} {args} format {"s" * len(names)} '
              'here "from tylmp.decks.session import collect as tylmp_values"')
    L.command("python tylmp_values invoke")
    return dict(zip(names, _collected))


def say(L, text):
    # triple quotes: no variable substitution, quotes allowed
    L.command('print """' + text.replace('"""', "'''") + '"""')


def fail(L, text):
    """An error met by every rank alike: the message, then exit status 1."""
    say(L, "ERROR: " + text)
    L.command("quit 1")
    raise SystemExit(1)         # not reached: quit ends the process


def fail_one(L, text):
    """An error met by one rank: the message, then a Python exception, which LAMMPS turns into
    an error on that rank (MPI_Abort), so that no other rank waits for it."""
    say(L, "ERROR: " + text)
    raise RuntimeError(text)


def world_rank(L):
    return L.extract_setting("world_rank")


def process_argv():
    """The command line of this process (lmp's, the python command runs inside it)."""
    try:
        with open("/proc/self/cmdline", "rb") as fh:
            return [a.decode(errors="replace") for a in fh.read().split(b"\0") if a]
    except OSError:
        return []


def deck_path():
    """The deck given with -in/-i to this process, from its command line (None for stdin)."""
    argv = process_argv()
    for k, arg in enumerate(argv[:-1]):
        if arg in ("-in", "-i"):
            return os.path.abspath(argv[k + 1])
    return None


def command_line_vars():
    """The names of the variables given with -var/-v on the command line."""
    argv = process_argv()
    return {argv[k + 1] for k, a in enumerate(argv[:-1]) if a in ("-var", "-v")}

