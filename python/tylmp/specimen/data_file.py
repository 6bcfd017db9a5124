"""The specimen as a LAMMPS data file (``units si``, ``atom_style sphere``): written
atomically, read back."""

import os
import tempfile

import numpy as np

from .paper import DENSITY
from .sizes import solid_fraction


def write_data(path, box, diameters, positions, density=DENSITY, comment=None):
    """Write a LAMMPS data file (``atom_style sphere``, ``units si``) atomically.

    Atoms lines: ``id type diameter density x y z``; box from 0 to L on every axis.
    """
    L = np.broadcast_to(np.asarray(box, dtype=float), (3,))
    d = np.asarray(diameters, dtype=float)
    x = np.asarray(positions, dtype=float)
    n = len(d)
    if x.shape != (n, 3):
        raise ValueError("positions must have shape (n, 3)")
    if comment is None:
        comment = (f"Thornton periodic-cell specimen: {n} spheres, solid fraction "
                   f"{solid_fraction(d, L):.6f} (tylmp.specimen)")
    lines = [f"LAMMPS data file - {comment}", "",
             f"{n} atoms", "1 atom types", "",
             f"0 {L[0]!r} xlo xhi", f"0 {L[1]!r} ylo yhi", f"0 {L[2]!r} zlo zhi", "",
             "Atoms # sphere", ""]
    rho = float(density)
    body = [f"{k + 1} 1 {d[k]!r} {rho!r} {x[k, 0]!r} {x[k, 1]!r} {x[k, 2]!r}"
            for k in range(n)]
    text = "\n".join(lines + body) + "\n"
    path = os.fspath(path)
    directory = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".specimen-", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
    return path


def read_data(path):
    """Read back a file written by :func:`write_data`: (box (3,), diam, density, pos)."""
    box = np.zeros(3)
    rows = []
    in_atoms = False
    with open(path) as f:
        next(f)
        for line in f:
            s = line.split("#")[0].strip() if not line.startswith("Atoms") else line.strip()
            if not s:
                continue
            if s.startswith("Atoms"):
                in_atoms = True
                continue
            t = s.split()
            if not in_atoms:
                for a, key in enumerate(("xlo", "ylo", "zlo")):
                    if len(t) >= 3 and t[2] == key:
                        box[a] = float(t[1]) - float(t[0])
            else:
                rows.append([float(v) for v in t[:7]])
    a = np.array(rows)
    a = a[np.argsort(a[:, 0])]
    return box, a[:, 2], a[:, 3], a[:, 4:7]
