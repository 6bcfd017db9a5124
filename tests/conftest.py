"""Shared test set-up: use the package tylmp of the fresh build (build/python: the sources of
python/ with the library and the decks), not an installed one."""
import importlib.util
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.environ.get("TYLMP_BUILD_DIR", os.path.join(REPO, "build"))
PYTHON_DIRS = [os.path.join(BUILD, "python")]

for d in reversed(PYTHON_DIRS):
    if d not in sys.path:
        sys.path.insert(0, d)
# subprocesses (lmp decks, mpirun) must import the same packages
os.environ["PYTHONPATH"] = os.pathsep.join(
    PYTHON_DIRS + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])


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
