"""Runs the GoogleTest unit tests of plugin/core (built by CMake as build/core_tests),
one pytest item per C++ test, so that README's single test command covers them."""
import os
import subprocess

import pytest

from conftest import BUILD

CORE_TESTS = os.path.join(BUILD, "core_tests")


def _list_core_tests():
    if not os.path.exists(CORE_TESTS):
        return []
    out = subprocess.run([CORE_TESTS, "--gtest_list_tests"], capture_output=True, text=True,
                         check=True).stdout
    names, suite = [], None
    for line in out.splitlines():
        if not line.strip():
            continue
        if not line.startswith(" "):
            suite = line.split()[0]
        else:
            names.append(suite + line.split()[0])
    return names


CORE_TEST_NAMES = _list_core_tests()


def test_core_tests_were_built():
    # the C++ physics tests must exist; a silent skip would hide them
    assert os.path.exists(CORE_TESTS), f"{CORE_TESTS} missing: run scripts/setup.sh"
    assert len(CORE_TEST_NAMES) > 10


@pytest.mark.parametrize("name", CORE_TEST_NAMES)
def test_core(name):
    proc = subprocess.run([CORE_TESTS, f"--gtest_filter={name}"], capture_output=True, text=True)
    assert proc.returncode == 0 and "[  PASSED  ] 1 test" in proc.stdout, proc.stdout[-4000:]
