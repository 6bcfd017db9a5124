"""Shared test set-up: use the freshly built tylmp (build/python) and tyanalysis (analysis/)."""
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
