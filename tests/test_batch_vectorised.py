"""The vector builds of the batch contact law (plugin/core/contact_batch.cpp) are vector code in
the plugin users load: each build of tycore::advance_batch, and of tycore::batch_geometry (the
law's inputs from the spheres' data), does its arithmetic in registers of its width (AVX-512
zmm, AVX2 ymm, SSE2 xmm), its divisions and square roots packed.

GCC vectorises those loops only while every one of them stays branch-free and is compiled with
the flags CMakeLists.txt sets for that file; a change that breaks this still passes the
numerical tests (the scalar fallback gives the same bits), so it is checked here on the
disassembly of build/python/tylmp/tylmp.so.
"""
import os
import re
import shutil
import subprocess

import pytest

from conftest import BUILD

LIBRARY = os.path.join(BUILD, "python", "tylmp", "tylmp.so")
BUILDS = {"sse2": "xmm", "avx2": "ymm", "avx512": "zmm"}


def batch_functions(disassembly, entry="advance_batch"):
    """{(build, first, second): body} of the <entry>_<build><bool, bool> functions
    (advance_batch<Adhesive, Damped>, batch_geometry<Affine, Damped>)."""
    found = {}
    for chunk in re.split(r"\n(?=[0-9a-f]+ <)", disassembly):
        m = re.match(rf"[0-9a-f]+ <\w+ tycore::detail::{entry}_(\w+)<(\w+), (\w+)>\(", chunk)
        if m:
            found[(m.group(1), m.group(2) == "true", m.group(3) == "true")] = chunk
    return found


def packed_and_scalar(body, register):
    """Counts of packed divisions and square roots on `register`s, and of scalar ones."""
    packed = len(re.findall(rf"\bv?(?:div|sqrt)pd\s[^\n]*%{register}", body))
    scalar = len(re.findall(r"\bv?(?:div|sqrt)sd\s", body))
    return packed, scalar


def test_parser_on_synthetic_disassembly():
    text = ("0000000000001000 <void tycore::detail::advance_batch_avx2<true, false>(int)>:\n"
            "    1000:\tvdivpd %ymm1,%ymm2,%ymm3\n    1004:\tvsqrtpd %ymm1,%ymm2\n"
            "    1008:\tvdivsd %xmm1,%xmm2,%xmm3\n\n"
            "0000000000002000 <other()>:\n    2000:\tdivpd %xmm1,%xmm2\n")
    found = batch_functions(text)
    assert list(found) == [("avx2", True, False)]
    assert packed_and_scalar(found[("avx2", True, False)], "ymm") == (2, 1)
    assert packed_and_scalar(found[("avx2", True, False)], "zmm") == (0, 1)


def builds_of(entry):
    """{(build, register, first, second): (packed, scalar)} of every build of `entry` in the
    plugin (a build missing fails)."""
    assert os.path.exists(LIBRARY), f"{LIBRARY} missing: build the plugin first"
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-C", LIBRARY],
                         capture_output=True, text=True, check=True).stdout
    found = batch_functions(out, entry)
    counts = {}
    for build, register in BUILDS.items():
        for first in (False, True):
            for second in (False, True):
                body = found.get((build, first, second))
                assert body is not None, f"{entry}_{build}<{first}, {second}> missing"
                counts[(build, register, first, second)] = packed_and_scalar(body, register)
    return counts


@pytest.mark.skipif(shutil.which("objdump") is None, reason="objdump (binutils) not installed")
def test_every_build_of_the_batch_law_is_vector_code():
    for (build, register, adhesive, damped), (packed, scalar) in builds_of("advance_batch").items():
        # the law's divisions and roots (cube roots, the Halley steps, directions, the Coulomb
        # cap, damping) are in the vector loops; scalar ones only in the lane-by-lane rare
        # cases (first touch, separation, JKR closed form)
        assert packed >= 30 and packed >= 3 * scalar, (
            f"advance_batch_{build}<{adhesive}, {damped}>: {packed} packed divisions and square "
            f"roots on {register}, {scalar} scalar: a loop of the batch law no longer "
            f"vectorises (check with -fopt-info-vec-missed)")


@pytest.mark.skipif(shutil.which("objdump") is None, reason="objdump (binutils) not installed")
def test_every_build_of_the_contact_geometry_is_vector_code():
    for (build, register, affine, damped), (packed, scalar) in builds_of("batch_geometry").items():
        # |x_i - x_j|, 1/r, the one division for R* and 1/R*, and m* when damped: all in the
        # lane loop, none left scalar
        assert packed >= 3 + damped and scalar == 0, (
            f"batch_geometry_{build}<{affine}, {damped}>: {packed} packed divisions and square "
            f"roots on {register}, {scalar} scalar: the geometry's lane loop no longer "
            f"vectorises")
