"""Shared test set-up: use the package tylmp of the fresh build (build/python: the sources of
python/ with the library and the decks), not an installed one."""
import importlib.util
import os
import subprocess
import sys

import pytest

import lammps_halves

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.environ.get("TYLMP_BUILD_DIR", os.path.join(REPO, "build"))
PYTHON_DIRS = [os.path.join(BUILD, "python")]

for d in reversed(PYTHON_DIRS):
    if d not in sys.path:
        sys.path.insert(0, d)
# subprocesses (lmp decks, mpirun) must import the same packages
os.environ["PYTHONPATH"] = os.pathsep.join(
    PYTHON_DIRS + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])


def pytest_configure(config):
    # which half of scripts/test.sh runs each test, and the check of that choice
    lammps_halves.configure(config)


def cpu_flags():
    """The instruction-set flags this processor reports (/proc/cpuinfo; empty elsewhere)."""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


@pytest.fixture
def repo():
    return REPO


@pytest.fixture(scope="session")
def bench():
    """The scripts under bench/ as modules, each loaded once: bench("programme_speed")."""
    modules = {}

    def load(name):
        if name not in modules:
            spec = importlib.util.spec_from_file_location(
                name, os.path.join(REPO, "bench", f"{name}.py"))
            modules[name] = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(modules[name])
        return modules[name]
    return load


@pytest.fixture(scope="session")
def command_dir(tmp_path_factory):
    """A directory with a `tyanalysis` command of the build under test, for PATH: what pip's
    console script is in an install (python/pyproject.toml), run by this interpreter with
    build/python first on sys.path."""
    d = tmp_path_factory.mktemp("bin")
    script = d / "tyanalysis"
    script.write_text(f"#!{sys.executable}\nimport sys\nsys.path.insert(0, {PYTHON_DIRS[0]!r})\n"
                      "from tylmp.analysis.cli import main\nsys.exit(main())\n")
    script.chmod(0o755)
    return str(d)


@pytest.fixture(scope="session")
def specimen_preparation(tmp_path_factory):
    """The decks' dense and loose quick specimens (inputs/common/specimen.in with its defaults,
    as `lmp -in inputs/axisym.in` prepares them), prepared once per session for every module
    that uses them, both at once (one lmp each): {"dir": the tylmp_specimens directory,
    "output": {"dense": lmp's output, "loose": ...}}. Tests copy the directory, never write
    into it."""
    work = tmp_path_factory.mktemp("specimens")
    os.symlink(os.path.join(REPO, "inputs"), work / "inputs")
    env = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none")
    procs = {}
    for kind in ("dense", "loose"):
        deck = work / f"in.prepare_{kind}"
        deck.write_text(f"variable specimen index {kind}\nvariable scale index quick\n"
                        f"variable tylmp_common string {REPO}/inputs/common\n"
                        "include ${tylmp_common}/specimen.in\n")
        procs[kind] = subprocess.Popen(["lmp", "-in", deck.name, "-log", "none", "-nocite"],
                                       cwd=str(work), text=True, env=env,
                                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    output = {}
    for kind, proc in procs.items():
        output[kind], _ = proc.communicate(timeout=1800)
        assert proc.returncode == 0 and "ERROR" not in output[kind], \
            f"preparation of the {kind} specimen failed:\n{output[kind][-4000:]}"
        assert (work / "tylmp_specimens" / f"{kind}_quick.restart").is_file()
    return {"dir": work / "tylmp_specimens", "output": output}


@pytest.fixture(scope="session")
def specimens(specimen_preparation):
    """The tylmp_specimens directory of specimen_preparation."""
    return specimen_preparation["dir"]
