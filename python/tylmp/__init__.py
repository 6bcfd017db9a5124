"""tylmp: Thornton–Yin contact law and stress-controlled periodic cell for LAMMPS.

The package: this loader, the decks' helpers (tylmp.decks, tylmp.specimen) and the decks
themselves (tylmp/inputs), and the analysis (tylmp.analysis, the `tyanalysis` command).

Load the styles into a running LAMMPS (the Debian `lmp` has no PLUGIN package) with
two lines of an input deck:

    python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"
    python tylmp_load invoke

or, from Python, ``tylmp.load(lmp)`` with a ``lammps.lammps`` object. Loading must come
before ``pair_style thornton/yin``, ``fix cell/servo`` and ``read_restart``. The library
loaded is the build for the running LAMMPS version (tylmp-YYYYMMDD.so); a build for another
version is refused with an error naming both versions.
"""

import ctypes
import os
import re
import sys

__all__ = ["load", "library_path", "built_for"]

_LIBRARY_NAME = "tylmp.so"             # in a build tree: the build made last
_VERSIONED_NAME = "tylmp-{}.so"        # the build for LAMMPS version YYYYMMDD
_TAG = re.compile(rb"tylmp-lammps-version=(\d{8})")
_libraries = {}

_MONTHS = "Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec".split()


def _version_name(number):
    """20250204 -> '4 Feb 2025', LAMMPS's own spelling of its version."""
    year, month, day = number // 10000, number // 100 % 100, number % 100
    if not 1 <= month <= 12:
        return str(number)
    return f"{day} {_MONTHS[month - 1]} {year}"


def library_path(lammps_version=None):
    """Path of the shared library with the styles: $TYLMP_LIBRARY if set, else the build for
    `lammps_version` (YYYYMMDD, as lammps.version() gives it) next to this file or in another
    tylmp package directory on sys.path (builds for two LAMMPS versions on one PYTHONPATH),
    else the build next to this file: tylmp.so in a build tree (the build made last), the one
    tylmp-YYYYMMDD.so in an installed package."""
    override = os.environ.get("TYLMP_LIBRARY")
    if override:
        return override
    here = os.path.dirname(os.path.abspath(__file__))
    if lammps_version is not None:
        name = _VERSIONED_NAME.format(int(lammps_version))
        for directory in [here] + [os.path.join(p or ".", "tylmp") for p in sys.path]:
            if os.path.exists(os.path.join(directory, name)):
                return os.path.join(directory, name)
    if not os.path.exists(os.path.join(here, _LIBRARY_NAME)):
        builds = sorted(f for f in os.listdir(here) if re.fullmatch(r"tylmp-\d{8}\.so", f))
        if len(builds) == 1:
            return os.path.join(here, builds[0])
    return os.path.join(here, _LIBRARY_NAME)


def built_for(path):
    """The LAMMPS version (YYYYMMDD) a tylmp library was compiled against, read from the file
    without loading it (loading a build for another version may already fail or crash)."""
    with open(path, "rb") as fh:
        found = _TAG.search(fh.read())
    if not found:
        raise RuntimeError(f"tylmp: {path} is not a tylmp library (it has no LAMMPS version tag)")
    return int(found.group(1))


def _open_library(lammps_version):
    path = library_path(lammps_version)
    if path in _libraries:
        return _libraries[path]
    if not os.path.exists(path):
        raise FileNotFoundError(
            f"tylmp: shared library not found at {path}; build it and install the package "
            "build/python with it: 'cmake -S . -B build && cmake --build build && "
            ".venv/bin/pip install --no-build-isolation --no-index build/python' "
            "(README, Install), or point TYLMP_LIBRARY at a build")
    built = built_for(path)
    if built != lammps_version:
        here = os.path.dirname(path)
        others = sorted(f for f in os.listdir(here) if re.fullmatch(r"tylmp-\d{8}\.so", f))
        raise RuntimeError(
            f"tylmp: {path} was built for LAMMPS {_version_name(built)} ({built}), but the "
            f"running LAMMPS is {_version_name(lammps_version)} ({lammps_version}): a build runs "
            f"only in the LAMMPS it was compiled against. Build tylmp against this LAMMPS "
            f"(README, Install) so that {_VERSIONED_NAME.format(lammps_version)} sits next to "
            f"{os.path.basename(path)}, or point TYLMP_LIBRARY at such a build"
            + (f" (found here: {', '.join(others)})" if others else ""))
    # RTLD_GLOBAL: the styles' typeinfo must resolve against the running liblammps
    library = ctypes.CDLL(path, mode=ctypes.RTLD_GLOBAL)
    library.tylmp_register.argtypes = [ctypes.c_void_p]
    library.tylmp_register.restype = ctypes.c_int
    _libraries[path] = library
    return library


def _lammps_of(lmp):
    """lammps.lammps object of a lammps.lammps object or of the capsule of `python ... SELF`."""
    if hasattr(lmp, "lmp") and hasattr(lmp, "command"):
        return lmp
    from lammps import lammps
    return lammps(ptr=lmp)


def load(lmp):
    """Register pair_style thornton/yin and the fixes of tylmp into a running LAMMPS, from the
    build of tylmp for that LAMMPS version."""
    lammps = _lammps_of(lmp)
    handle = lammps.lmp
    handle = handle.value if isinstance(handle, ctypes.c_void_p) else handle
    if not handle:
        raise ValueError("tylmp.load: got a null LAMMPS handle")
    version = int(lammps.version())
    count = _open_library(version).tylmp_register(ctypes.c_void_p(handle))
    if count < 0:       # the library checks the version it was compiled for itself too
        raise RuntimeError(f"tylmp.load: {library_path(version)} was compiled for another "
                           f"LAMMPS than the running {_version_name(version)}")
    if count == 0:
        raise RuntimeError("tylmp.load: no style was registered")
    return count
