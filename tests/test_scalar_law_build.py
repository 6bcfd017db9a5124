"""A build without the contact law's SIMD builds: -DTYLMP_VECTOR_LAW=OFF gives what a compiler
or architecture without them gets (plugin/core/contact_batch.hpp: TYCORE_VECTOR_BUILDS unset),
the scalar instantiation of the law's one text (plugin/core/contact_law.hpp) alone. It must
build, offer only the scalar build, and pass the core tests of the law: the closed-form tests
(Mindlin-Deresiewicz, Savkoor-Briggs, JKR, energy) through the scalar entry, the batch entry
against the scalar entry on random paths through every branch (attached, snap-in, break,
peeling, sliding, unload/reload), the setup pass, first touch and separation, damping and
tallies against their formulas, the cube root, and the contact geometry
(contact_geometry.hpp). And it must be the same law to the bit as
every build of the default configuration: the digests of the outputs along those paths
(tests/core/test_contact_batch.cpp, print_digest) equal those of the default build's
core_tests (in TYLMP_BUILD_DIR), one per build this processor runs.
Configured and built in a temporary directory: the target core_law_tests (CMakeLists.txt), the
law's test files of core_tests alone, about 40 s of compile time (core_tests: about 130 s);
the law's tests it lists must be those of the default build's core_tests."""
import os
import re
import subprocess

from conftest import BUILD, REPO

LAW_TESTS = ("Mindlin*:ThorntonYin*:JkrWarm*:*BatchLaw*:BatchForces*:BatchDispatch*:SimdCbrt*:"
             "ContactGeometry*")
DIGEST = re.compile(r"^law trajectory digest (\S+) (\S+) ([0-9a-f]{16})$", re.M)


def run_law_tests(core_tests):
    proc = subprocess.run([core_tests, f"--gtest_filter={LAW_TESTS}"], capture_output=True,
                          text=True)
    assert proc.returncode == 0 and "FAILED" not in proc.stdout, proc.stdout[-4000:]
    return proc.stdout


def list_law_tests(core_tests):
    """(suite, test) of the law's tests in a core_tests binary; a parametrized test's name ends
    in the build it runs (Test/avx2)."""
    out = subprocess.run([core_tests, f"--gtest_filter={LAW_TESTS}", "--gtest_list_tests"],
                         capture_output=True, text=True, check=True).stdout
    names, suite = [], None
    for line in out.splitlines():
        if not line.strip():
            continue
        first = line.split()[0]
        if not line.startswith(" "):
            suite = first if first.endswith(".") else None
        elif suite:
            names.append((suite, first))
    return names


def without_build(name):
    """(suite, test) without the build the test runs: (Suite., Test/avx2) -> (Suite., Test)."""
    suite, test = name
    return suite, test.rsplit("/", 1)[0] if "/" in test else test


def test_core_law_tests_pass_without_simd_builds(tmp_path):
    build = str(tmp_path / "build")
    for cmd in (["cmake", "-S", REPO, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                 "-DTYLMP_VECTOR_LAW=OFF"],
                ["cmake", "--build", build, "-j2", "--target", "core_law_tests"]):
        proc = subprocess.run(cmd, capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    core_tests = os.path.join(build, "core_law_tests")
    listed = list_law_tests(core_tests)
    # the batch tests run once per build the processor runs: here the scalar one alone
    builds = {test.rsplit("/", 1)[1] for _, test in listed if "/" in test}
    assert builds == {"scalar"}, listed
    # every law test of the default build is here (a law test in a file that core_law_tests
    # leaves out would not run without the SIMD builds)
    default_listed = list_law_tests(os.path.join(BUILD, "core_tests"))
    assert {without_build(n) for n in listed} == {without_build(n) for n in default_listed}
    out = run_law_tests(core_tests)
    assert "advance_batch uses scalar" in out, out[-4000:]

    # the same law to the bit as every build of the default configuration
    scalar_only = {(path, isa): digest for path, isa, digest in DIGEST.findall(out)}
    assert {isa for _, isa in scalar_only} == {"scalar"}, out[-4000:]
    paths = {path for path, _ in scalar_only}
    assert paths == {"adhesive", "hertz", "frictionless", "frictionless-hertz"}, scalar_only
    default = DIGEST.findall(run_law_tests(os.path.join(BUILD, "core_tests")))
    assert {path for path, _, _ in default} == paths, default
    for path, isa, digest in default:
        assert digest == scalar_only[(path, "scalar")], (path, isa)
