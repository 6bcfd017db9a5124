"""Shared test set-up: use the freshly built tylmp (build/python) and tyanalysis (analysis/)."""
import importlib.util
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.environ.get("TYLMP_BUILD_DIR", os.path.join(REPO, "build"))
PYTHON_DIRS = [os.path.join(BUILD, "python"), os.path.join(REPO, "analysis")]

for d in reversed(PYTHON_DIRS):
    if d not in sys.path:
        sys.path.insert(0, d)
# subprocesses (lmp decks, mpirun) must import the same packages
os.environ["PYTHONPATH"] = os.pathsep.join(
    PYTHON_DIRS + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])


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
