"""Run LAMMPS decks with the stock Debian `lmp` and read what they wrote.

LAMMPS is built without exceptions: an input error ends the process, so every deck runs
in its own `lmp` process and errors are asserted on its output.
"""
import os
import subprocess

import numpy as np

LOAD_TYLMP = (
    'python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"\n'
    "python tylmp_load invoke\n")


def reduce_local(name, *values, mode="sum"):
    """`compute NAME all reduce MODE VALUES` of local values (e.g. of compute
    thornton/yin/contacts) in the syntax of the running LAMMPS: from 21 Nov 2023 it needs
    'inputs local'."""
    base = f"compute {name} all reduce {mode} {' '.join(values)}"
    return f'if "$(version) >= 20231121" then "{base} inputs local" else "{base}"\n'


def two_spheres_box(x2, diameter, density, types=1, second=None,
                    block="-1e-3 1e-3 -1e-3 1e-3 -1e-3 1e-3"):
    """Two spheres in a box with fixed boundaries (by default 2 mm wide): atom 1 (type 1) at
    the origin, atom 2 (type `types`) at (x2, 0, 0); groups `one` and `two`. Both spheres get
    `diameter` and `density`, or sphere 2 gets `second` = (diameter, density)."""
    if second is None:
        sizes = f"set atom * diameter {diameter!r} density {density!r}\n"
    else:
        sizes = (f"set atom 1 diameter {diameter!r} density {density!r}\n"
                 f"set atom 2 diameter {second[0]!r} density {second[1]!r}\n")
    return f"""
units si
atom_style sphere
atom_modify map array
boundary f f f
comm_modify vel yes
region box block {block}
create_box {types} box
create_atoms 1 single 0 0 0
create_atoms {types} single {x2!r} 0 0
{sizes}group one id 1
group two id 2
"""


def run_deck(text, workdir, name="in.test", np_ranks=1, variables=None, timeout=600,
             program=("lmp", "-nocite"), environment=None):
    """Write `text` to workdir/name, run it with `program` (the executable and its extra
    flags; default the stock lmp) and the variables of `environment` added to the process's
    environment; return (returncode, combined output)."""
    path = os.path.join(str(workdir), name)
    with open(path, "w") as fh:
        fh.write(text)
    cmd = [program[0], "-in", name, "-log", "none", *program[1:]]
    for key, value in (variables or {}).items():
        cmd += ["-var", key, str(value)]
    if np_ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_ranks)] + cmd
    proc = subprocess.run(cmd, cwd=str(workdir), capture_output=True, text=True,
                          errors="replace",    # LIGGGHTS prints stray bytes after some errors
                          timeout=timeout, env=dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none",
                                                    **(environment or {})))
    return proc.returncode, proc.stdout + proc.stderr


def run_ok(text, workdir, **kw):
    rc, out = run_deck(text, workdir, **kw)
    assert rc == 0 and "ERROR" not in out, out[-3000:]
    return out


def read_table(path):
    """Whitespace table with a '#' header line naming the columns -> dict of arrays."""
    with open(path) as fh:
        header = fh.readline().lstrip("#").split()
    data = np.loadtxt(path, comments="#", ndmin=2)
    return {name: data[:, k] for k, name in enumerate(header)}
