"""A second compiler: the core tests built with clang++ (Debian's clang, installed by
scripts/setup.sh) must build without a warning and pass the core tests of the contact law. On
x86-64 clang gets the law's SIMD builds too (plugin/core/contact_batch.hpp: TYCORE_VECTOR_BUILDS),
one per instruction set the processor runs, and the batch tests hold each of them to the scalar
build bit for bit: every build against the scalar kernel (advance_contact) from the same state,
on paths through the contact's whole life, and the law's closed-form tests (Mindlin, Thornton-Yin)
on its scalar instantiation;
damping, tallies, stored energy, first touch and separation against their formulas and the
vector builds against the scalar one; the setup pass; the lane-wide cube root against
jkr::fast_cbrt; the contact geometry's lanes against an independent calculation and the scalar
build. So a result that depends on GCC (its vectoriser, its contraction of
multiply-adds, an unspecified evaluation order) fails here.
Configured and built in a temporary directory (the core_tests target only, -j2)."""
import os
import platform
import shutil
import subprocess

import pytest

from conftest import REPO, cpu_flags

CLANG = shutil.which("clang++")
LAW_TESTS = ("Mindlin*:ThorntonYin*:*BatchLaw*:BatchForces*:BatchDispatch*:SimdCbrt*:"
             "ContactGeometry*")


def expected_builds():
    """The builds of advance_batch this processor runs (contact_batch.hpp, isa_supported)."""
    builds = {"scalar"}
    if platform.machine() == "x86_64":
        flags = cpu_flags()
        builds.add("sse2")
        if "avx2" in flags:
            builds.add("avx2")
        if {"avx512f", "avx512dq", "avx512vl"} <= flags:
            builds.add("avx512")
    return builds


@pytest.mark.skipif(CLANG is None, reason="clang++ is not installed (scripts/setup.sh installs "
                    "Debian's package clang)")
def test_core_law_tests_pass_built_with_clang(tmp_path):
    build = str(tmp_path / "build")
    outputs = []
    for cmd in (["cmake", "-S", REPO, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                 f"-DCMAKE_CXX_COMPILER={CLANG}"],
                ["cmake", "--build", build, "-j2", "--target", "core_tests"]):
        proc = subprocess.run(cmd, capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
        outputs.append(proc.stdout + proc.stderr)
    assert "CXX compiler identification is Clang" in outputs[0], outputs[0][-2000:]
    warnings = [line for line in outputs[1].splitlines() if "warning:" in line]
    assert not warnings, "\n".join(warnings[:20])

    core_tests = os.path.join(build, "core_tests")
    listed = subprocess.run([core_tests, f"--gtest_filter={LAW_TESTS}", "--gtest_list_tests"],
                            capture_output=True, text=True, check=True).stdout
    # the batch tests run once per build the processor runs: the SIMD builds under clang
    builds = {line.split("/")[-1].split()[0] for line in listed.splitlines()
              if line.startswith("  ") and "/" in line}
    assert builds == expected_builds(), listed
    proc = subprocess.run([core_tests, f"--gtest_filter={LAW_TESTS}"], capture_output=True,
                          text=True)
    assert proc.returncode == 0 and "FAILED" not in proc.stdout, proc.stdout[-4000:]
    widest = max(builds, key=["scalar", "sse2", "avx2", "avx512"].index)
    assert f"advance_batch uses {widest}" in proc.stdout, proc.stdout[-4000:]
