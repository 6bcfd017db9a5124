"""LAMMPS's own pair-style tester on pair thornton/yin (docs/lammps_harness.md).

LAMMPS tests its pair styles with unittest/force-styles/test_pair_style: a YAML file gives the
system and reference forces, stress and energy, and the tester checks one build of the style
against them in several ways. This module builds that tester from the sources of LAMMPS 4 Feb
2025 against the liblammps of scripts/lammps2025.sh (tests/lammps_harness/CMakeLists.txt, no
LAMMPS rebuild; cached in the build tree) and runs it on tests/lammps_harness/*.yaml. It runs
in the 4 Feb 2025 half of scripts/test.sh and skips in the other.

The reference numbers in the YAML files come from our own code (the tester's -g), so they are a
regression lock, not a physics reference. The physics is in what the tester compares with
them: the forces, virial and energy of the first evaluation with newton on and newton off,
after a restart file, after `pair_modify nofdotr`, from the data file the first run wrote,
and after four steps of fix nve, where the pair energy must also equal the sum of
`compute pe/atom`. Its `single()` stage does not run on a granular style: it builds a two-atom
`atom_style full` system (no radius), so the YAML files skip it (docs/lammps_harness.md names
the tests of single() against compute()).

The style comes from our library through LAMMPS_PLUGIN_PATH (a *plugin.so link to it): the
tester's restart and data-file stages start with `clear`, which unloads every plugin, so a
`plugin load` among the YAML's pre_commands is lost there (test_plugin_load_alone_is_lost_at_clear).

    python3 tests/test_lammps_harness.py --regenerate    (new reference data, under the
                                                          LAMMPS of scripts/lammps2025.sh)
"""
import glob
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

import test_lammps_versions as versions
from conftest import BUILD, REPO

HERE = Path(REPO) / "tests" / "lammps_harness"
YAMLS = sorted(HERE.glob("pair-thornton_yin*.yaml"))
# stages of TEST(PairStyle, plain) in test_pair_style.cpp, in the order they are compared
PLAIN_CHECKS = ["init_forces (newton on)", "init_stress (newton on)", "run_forces (newton on)",
                "run_stress (newton on)", "init_forces (newton off)", "init_stress (newton off)",
                "run_forces (newton off)", "run_stress (newton off)", "restart_forces",
                "restart_stress", "nofdotr_forces", "nofdotr_stress", "data_forces",
                "data_stress"]


def lammps2025_prefix():
    """The install prefix of scripts/lammps2025.sh's LAMMPS (its wrapper is tylmp/bin/lmp)."""
    wrapper = versions.lammps2025_wrapper()
    return Path(wrapper).resolve().parents[2] if wrapper else None


def build_tester(prefix, build_dir):
    """Configure (once) and build test_pair_style in build_dir; return (path, seconds)."""
    sources = prefix / "share" / "lammps-src"
    if not (sources / "unittest" / "force-styles" / "test_pair_style.cpp").exists():
        pytest.fail(f"{sources} has no unittest/force-styles: run scripts/lammps2025.sh, which "
                    "installs the tester's sources beside the LAMMPS headers")
    start = time.monotonic()
    if not (build_dir / "CMakeCache.txt").exists():
        subprocess.run(["cmake", "-S", str(HERE), "-B", str(build_dir),
                        f"-DLAMMPS_DIR={prefix / 'lib' / 'cmake' / 'LAMMPS'}",
                        f"-DLAMMPS_SOURCE_DIR={sources}",
                        f"-DLAMMPS_FORCE_STYLES_DIR={sources / 'unittest' / 'force-styles'}"],
                       check=True, capture_output=True, text=True)
    proc = subprocess.run(["cmake", "--build", str(build_dir), "-j", str(os.cpu_count() or 1)],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return build_dir / "test_pair_style", time.monotonic() - start


def plugin_dir(build_dir, library):
    """A directory with a link *plugin.so to our library: LAMMPS loads every such file of the
    directories in LAMMPS_PLUGIN_PATH into each new instance, also after `clear`."""
    d = build_dir / "plugins"
    d.mkdir(parents=True, exist_ok=True)
    link = d / "tylmp-plugin.so"
    if link.is_symlink() or link.exists():
        link.unlink()
    link.symlink_to(library)
    return d


def run_tester(tester, yaml, workdir, plugins, *args):
    """Run test_pair_style on a YAML in workdir; (process, {test name: gtest result})."""
    env = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none")
    env.pop("LAMMPS_PLUGIN_PATH", None)
    if plugins:
        env["LAMMPS_PLUGIN_PATH"] = str(plugins)
    report = Path(workdir) / "gtest.json"
    proc = subprocess.run([str(tester), str(yaml), *args, f"--gtest_output=json:{report}"],
                          cwd=workdir, env=env, capture_output=True, text=True, timeout=600)
    results = {}
    if report.exists():
        for suite in json.loads(report.read_text())["testsuites"]:
            for case in suite["testsuite"]:
                results[case["name"]] = case
    return proc, results


@pytest.fixture(scope="module")
def harness():
    if versions.LMP_VERSION != versions.V2025:
        pytest.skip(f"LAMMPS's tester is built from 4 Feb 2025 sources against its liblammps: "
                    f"runs in the 4 Feb 2025 half of scripts/test.sh (this lmp is "
                    f"{versions.LMP_VERSION})")
    prefix = lammps2025_prefix()
    library = versions.library_for(versions.V2025)
    assert prefix and library, "scripts/lammps2025.sh has not built LAMMPS 4 Feb 2025 and tylmp"
    build_dir = Path(BUILD) / "lammps_harness"
    tester, seconds = build_tester(prefix, build_dir)
    print(f"\nLAMMPS's test_pair_style: built (or found current) in {seconds:.1f} s")
    return tester, plugin_dir(build_dir, library)


def failures(case):
    return "\n".join(f["failure"] for f in case.get("failures", []))


@pytest.mark.parametrize("yaml", YAMLS, ids=[y.stem for y in YAMLS])
def test_lammps_pair_style_tester_passes(harness, yaml, tmp_path):
    tester, plugins = harness
    start = time.monotonic()
    proc, results = run_tester(tester, yaml, tmp_path, plugins)
    print(f"\n{yaml.name}: {time.monotonic() - start:.1f} s; " +
          ", ".join(f"{name} {case['result'].lower()}" +
                    (" FAILED" if case.get("failures") else "") for name, case in results.items()))
    assert results, proc.stdout[-3000:] + proc.stderr[-3000:]
    plain, extract, single = results["plain"], results["extract"], results["single"]
    # every comparison of TEST(PairStyle, plain) ran (a failure names its stage) and passed
    assert plain["result"] == "COMPLETED" and not plain.get("failures"), failures(plain)
    assert extract["result"] == "COMPLETED" and not extract.get("failures"), failures(extract)
    assert single["result"] == "SKIPPED"                  # skip_tests: single (see above)
    # the accelerator variants (omp, kokkos_omp, gpu, intel, opt) need packages this LAMMPS
    # is built without, and skip themselves
    assert all(c["result"] == "SKIPPED" for n, c in results.items()
               if n not in ("plain", "extract", "single"))
    assert proc.returncode == 0


def yaml_block(text, key):
    """The rows of a block of per-atom values of a test_pair_style YAML file."""
    block = re.search(rf"^{key}: ! \|2?\n((?:   *\d+ .*\n)+)", text, re.M).group(1)
    return [[float(v) for v in row.split()[1:]] for row in block.splitlines()]


@pytest.mark.no_lammps       # reads the YAML files only: the 29 Sep 2021 half (tests/lammps_halves.py)
@pytest.mark.parametrize("yaml", YAMLS, ids=[y.stem for y in YAMLS])
def test_reference_system_has_contacts_that_change_during_the_run(yaml):
    # the comparisons above are only as good as the system: most spheres must touch, and the
    # four steps of the run must change the forces (not a lattice at rest)
    text = yaml.read_text()
    init, run = yaml_block(text, "init_forces"), yaml_block(text, "run_forces")
    assert len(init) == len(run) == 32
    loaded = [max(abs(c) for c in f) > 0 for f in init]
    assert sum(loaded) >= 24
    changes = [max(abs(a - b) for a, b in zip(f0, f1)) / max(max(abs(c) for c in f0), 1e-300)
               for f0, f1 in zip(init, run) if max(abs(c) for c in f0) > 0]
    assert sorted(changes)[len(changes) // 2] > 1e-4       # the median force changed


def test_plugin_load_alone_is_lost_at_clear(harness, tmp_path):
    # the same YAML with `plugin load` among its pre_commands instead of LAMMPS_PLUGIN_PATH
    tester, plugins = harness
    library = os.path.realpath(plugins / "tylmp-plugin.so")
    text = YAMLS[0].read_text().replace("pre_commands: ! |\n",
                                         f"pre_commands: ! |\n  plugin load {library}\n")
    yaml = tmp_path / "pair-plugin_load.yaml"
    # the tester checks the prerequisites before the pre_commands: it skips every test
    yaml.write_text(text)
    proc, results = run_tester(tester, yaml, tmp_path, None)
    assert "One or more prerequisite styles are not available" in proc.stderr
    assert all(case["result"] == "SKIPPED" for case in results.values()) and results
    # without the prerequisite line the first stages pass (the first force evaluation and the
    # run, newton on and off); the restart stage starts with `clear` and stops
    yaml.write_text(text.replace("  pair thornton/yin\n", "", 1))
    proc, results = run_tester(tester, yaml, tmp_path, None, "--gtest_filter=PairStyle.plain")
    failure = failures(results["plain"])
    assert proc.returncode != 0
    assert len(results["plain"]["failures"]) == 1         # nothing failed before it
    assert "ERROR: Unrecognized pair style 'thornton/yin'" in failure
    assert "Last input line: read_restart" in failure


def regenerate():
    """New reference data for every YAML of tests/lammps_harness, keeping its comment lines:
    run under the LAMMPS of scripts/lammps2025.sh (its wrapper or cache)."""
    import tempfile
    prefix = lammps2025_prefix()
    build = Path(os.environ.get("TYLMP_LAMMPS2025_BUILD_DIR", Path(REPO) / "build-lammps2025"))
    library = versions.library_for(versions.V2025, str(build))
    if not prefix or not library:
        sys.exit("run scripts/lammps2025.sh first (LAMMPS 4 Feb 2025 and tylmp built for it)")
    tester, _ = build_tester(prefix, build / "lammps_harness")
    plugins = plugin_dir(build / "lammps_harness", library)
    for yaml in YAMLS:
        with tempfile.TemporaryDirectory() as work:
            new = Path(work) / yaml.name
            proc, _ = run_tester(tester, yaml, work, plugins, "-g", str(new))
            if proc.returncode or not new.exists():
                sys.exit(proc.stdout[-3000:] + proc.stderr[-3000:])
            comments = [ln for ln in yaml.read_text().splitlines(keepends=True)
                        if ln.startswith("#")]
            yaml.write_text("".join(comments) + new.read_text())
            print(f"regenerated {yaml}")


if __name__ == "__main__":
    if sys.argv[1:] != ["--regenerate"]:
        sys.exit(__doc__)
    regenerate()
