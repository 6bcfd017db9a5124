"""Where a benchmark's figures come from, stamped into every result it writes.

A timing means nothing without the code, the machine, the compiler and the LAMMPS that
produced it (timings of different machines are not comparable: docs/performance.md), and a
result committed to the repository must not carry the paths of the machine that wrote it.
`write_result` is the one writer of bench/results/*.json: it adds `provenance` (commit, CPU,
compiler, LAMMPS version) and writes every path under the repository relative to it and every
path under the user's home as `~/...`.
"""
import functools
import os
import re
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from tylmp.analysis.io import write_json  # noqa: E402


@functools.lru_cache(maxsize=None)
def machine():
    """The processor a call ran on (model, logical CPUs, widest SIMD, clock)."""
    model, isa, mhz = "unknown", "no AVX2", ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                key, _, value = line.partition(":")
                key, value = key.strip(), value.strip()
                if key == "model name" and model == "unknown":
                    model = value
                elif key == "cpu MHz" and not mhz:
                    mhz = f", {float(value):.0f} MHz"
                elif key == "flags":
                    flags = value.split()
                    isa = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else isa
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} CPUs, {isa}{mhz}"


def _first_line(cmd):
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return None
    lines = (out.stdout or out.stderr).strip().splitlines()
    return lines[0].strip() if lines else None


@functools.lru_cache(maxsize=None)
def commit():
    """HEAD of the working tree, with '-dirty' when tracked files differ from it."""
    head = _first_line(["git", "-C", REPO, "rev-parse", "--short=12", "HEAD"])
    if head is None:
        return "unknown"
    dirty = subprocess.run(["git", "-C", REPO, "diff", "--quiet", "HEAD", "--"],
                           capture_output=True).returncode != 0
    return head + ("-dirty" if dirty else "")


def compiler(build_dir=None):
    """The C++ compiler of a build (its CMakeCache), else the default c++, with its version."""
    cxx = "c++"
    cache = os.path.join(build_dir or os.path.join(REPO, "build"), "CMakeCache.txt")
    if os.path.exists(cache):
        with open(cache) as fh:
            for line in fh:
                if line.startswith("CMAKE_CXX_COMPILER:"):
                    cxx = line.split("=", 1)[1].strip() or cxx
    return _first_line([cxx, "--version"]) or cxx


@functools.lru_cache(maxsize=None)
def lammps_version(lmp="lmp"):
    """LAMMPS's own version line (e.g. '29 Sep 2021'), read from `lmp -h`."""
    text = _first_line([lmp, "-h"]) if lmp else None
    if text:
        m = re.search(r"\((\d{1,2} \w{3} \d{4})[^)]*\)|- (\d{1,2} \w{3} \d{4})", text)
        if m:
            return m.group(1) or m.group(2)
    return text or "unknown"


def stamp(lmp="lmp", build_dir=None):
    return {"commit": commit(), "cpu": machine(), "compiler": compiler(build_dir),
            "lammps": lammps_version(lmp)}


def portable(value):
    """value with every absolute path of this machine made relative: under the repository,
    relative to it; under the home directory, '~/...'."""
    if isinstance(value, str):
        home = os.path.expanduser("~")
        value = value.replace(REPO + os.sep, "").replace(REPO, ".")
        if home not in ("", "/"):
            value = value.replace(home + os.sep, "~" + os.sep)
        return value
    if isinstance(value, dict):
        return {portable(k): portable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [portable(v) for v in value]
    return value


def write_result(path, summary, indent=2, lmp="lmp", build_dir=None):
    """Write a benchmark's summary (a dict) atomically with its provenance, paths portable."""
    record = dict(summary)
    record.setdefault("provenance", stamp(lmp, build_dir))
    write_json(path, portable(record), indent=indent)
