"""A build without the contact law's SIMD builds: -DTYLMP_VECTOR_LAW=OFF gives what a compiler
or architecture without them gets (plugin/core/contact_batch.hpp: TYCORE_VECTOR_BUILDS unset),
the scalar instantiation of the law's one text (plugin/core/contact_law.hpp) alone. It must
build, offer only the scalar build, and pass the core tests of the law: the batch entry
against the reference law (thornton_yin.hpp) and the scalar entry on random paths through
every branch (attached, snap-in, break, peeling, sliding, unload/reload), the setup pass, first
touch and separation, damping and tallies against their formulas, and the cube root.
Configured and built in a temporary directory (core_tests only, about a minute on 2 cores)."""
import os
import subprocess

from conftest import REPO

LAW_TESTS = "ContactKernel*:*BatchLaw*:BatchForces*:BatchDispatch*:SimdCbrt*"


def test_core_law_tests_pass_without_simd_builds(tmp_path):
    build = str(tmp_path / "build")
    for cmd in (["cmake", "-S", REPO, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                 "-DTYLMP_VECTOR_LAW=OFF"],
                ["cmake", "--build", build, "-j2", "--target", "core_tests"]):
        proc = subprocess.run(cmd, capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    core_tests = os.path.join(build, "core_tests")
    listed = subprocess.run([core_tests, f"--gtest_filter={LAW_TESTS}", "--gtest_list_tests"],
                            capture_output=True, text=True, check=True).stdout
    # the batch tests run once per build the processor runs: here the scalar one alone
    builds = {line.split("/")[-1].split()[0] for line in listed.splitlines()
              if line.startswith("  ") and "/" in line}
    assert builds == {"scalar"}, listed
    proc = subprocess.run([core_tests, f"--gtest_filter={LAW_TESTS}"], capture_output=True,
                          text=True)
    assert proc.returncode == 0 and "FAILED" not in proc.stdout, proc.stdout[-4000:]
    assert "advance_batch uses scalar" in proc.stdout, proc.stdout[-4000:]
