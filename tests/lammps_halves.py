"""Which tests run in which half of scripts/test.sh (docs/developer.md), and the check that keeps
that choice honest: a pytest plugin that tests/conftest.py registers.

scripts/test.sh runs the suite against LAMMPS 29 Sep 2021 and then against 4 Feb 2025, and names
the half in TYLMP_TEST_HALF (2021 or 2025). Each test is in one of four classes:

  independent   starts no LAMMPS: its outcome cannot depend on the version. 29 Sep 2021 half only.
  each          starts the LAMMPS under test: both halves.
  once          starts it, but is a long run whose every version-dependent path a shorter test
                of the 4 Feb 2025 half takes too (@pytest.mark.lammps_once(reason=...), the
                reason naming that test): 29 Sep 2021 half only.
  cross         runs both versions itself (@pytest.mark.both_lammps): 4 Feb 2025 half only, where
                both builds exist.

Without TYLMP_TEST_HALF (pytest by hand; scripts/lammps2025.sh by hand; TYLMP_TEST_LAMMPS=2021
or 2025, which run one version only) every test runs.

A test starts LAMMPS when its module names the lmp command (a string "lmp", "lmp ...",
".../lmp" or "mpirun") or imports the Python module lammps, or a module it uses does: a helper
module of tests/ that it imports, a script of bench/ that it loads with the `bench` fixture
(bench("compare_assembly")), and theirs in turn. Markers override where that reading is wrong:
  @pytest.mark.runs_lammps   starts LAMMPS where the module does not name it (a script, a page's
                             commands, a tool of the package that runs lmp)
  @pytest.mark.no_lammps     starts none, in a module that does

The check: every run puts a shim `lmp` first on PATH that counts the LAMMPS processes started
(`mpirun ... lmp` too), and counts an import of lammps into pytest itself. A test classified
independent that started LAMMPS, in its own set-up or call or in a fixture it uses, fails with
the marker to add. So a misclassified test fails in the 29 Sep 2021 half and cannot be skipped
silently in the 4 Feb 2025 half. The other way round (classified as starting LAMMPS, started
none) costs only time; `pytest -v` lists those tests at the end."""
import ast
import os
import shutil
import sys
import tempfile

import pytest

TESTS = os.path.dirname(os.path.abspath(__file__))
BENCH = os.path.join(os.path.dirname(TESTS), "bench")
HALVES = ("2021", "2025")
LAUNCHERS = ("lmp", "mpirun")
NOT_SCANNED = ("conftest", "lammps_halves")      # the test machinery itself, not a test's code

SKIP_REASON = {
    ("2025", "independent"): "version-independent (starts no LAMMPS): runs in the 29 Sep 2021 half",
    ("2025", "once"): "runs in the 29 Sep 2021 half only: {reason}",
    ("2021", "cross"): "runs both LAMMPS versions itself: in the 4 Feb 2025 half",
}

MARKERS = (
    "runs_lammps: starts LAMMPS although its module does not name lmp (tests/lammps_halves.py)",
    "no_lammps: starts no LAMMPS although its module does (tests/lammps_halves.py)",
    "lammps_once(reason): a long LAMMPS run whose version-dependent paths a shorter test of the "
    "4 Feb 2025 half takes too: the 29 Sep 2021 half only (tests/lammps_halves.py)",
    "both_lammps: runs both LAMMPS versions itself: the 4 Feb 2025 half only "
    "(tests/lammps_halves.py)",
)

CLASS = pytest.StashKey[str]()
_scanned = {}


def names_lammps(path):
    """Whether the module at `path`, or a module it uses (the module's docstring), names the lmp
    command or imports the Python module lammps."""
    path = os.path.abspath(path)
    if path not in _scanned:
        _scanned[path] = False                       # an import cycle adds nothing
        with open(path, encoding="utf-8") as fh:
            tree = ast.parse(fh.read(), path)
        here = os.path.dirname(path)
        _scanned[path] = any(_node_names_lammps(node, here) for node in ast.walk(tree))
    return _scanned[path]


def _uses_lammps(module, here):
    """An imported module: lammps itself, or a module beside the importing one that names it."""
    top = module.split(".")[0]
    local = os.path.join(here, top + ".py")
    return top == "lammps" or (top not in NOT_SCANNED and os.path.isfile(local)
                               and names_lammps(local))


def _node_names_lammps(node, here):
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        word = node.value.split(" ", 1)[0]
        return word in LAUNCHERS or word.endswith("/lmp")
    if isinstance(node, ast.Import):
        return any(_uses_lammps(alias.name, here) for alias in node.names)
    if isinstance(node, ast.ImportFrom):
        return node.level == 0 and bool(node.module) and _uses_lammps(node.module, here)
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "bench"
            and node.args and isinstance(node.args[0], ast.Constant)
            and isinstance(node.args[0].value, str)):
        script = os.path.join(BENCH, node.args[0].value + ".py")
        return os.path.isfile(script) and names_lammps(script)
    return False


def lammps_class(item):
    """independent, each, once or cross (the module's docstring)."""
    if item.get_closest_marker("both_lammps"):
        return "cross"
    if item.get_closest_marker("no_lammps"):
        return "independent"
    if not (item.get_closest_marker("runs_lammps") or names_lammps(str(item.path))):
        return "independent"
    return "once" if item.get_closest_marker("lammps_once") else "each"


# ---- the hooks --------------------------------------------------------------------------------

class _Launches:
    """The shim `lmp` on PATH and its count of LAMMPS processes."""

    def __init__(self):
        self.dir = tempfile.mkdtemp(prefix="tylmp-lmp-shim-")
        self.log = os.path.join(self.dir, "started")
        open(self.log, "w").close()
        shim = os.path.join(self.dir, "lmp")
        with open(shim, "w") as fh:
            # one byte per process, then the lmp that comes next on PATH (PATH without this
            # directory): the wrapper of scripts/lammps2025.sh or Debian's /usr/bin/lmp
            fh.write(f"""#!/bin/sh
# tests/lammps_halves.py: count this LAMMPS process, then run the lmp next on PATH
printf x >> '{self.log}'
rest=""
IFS=:
for d in $PATH; do [ "$d" = '{self.dir}' ] || rest="${{rest:+$rest:}}$d"; done
unset IFS
PATH="$rest" exec lmp "$@"
""")
        os.chmod(shim, 0o755)
        os.environ["PATH"] = self.dir + os.pathsep + os.environ.get("PATH", "")

    def count(self):
        return os.path.getsize(self.log) + ("lammps" in sys.modules)

    def close(self):
        parts = os.environ.get("PATH", "").split(os.pathsep)
        os.environ["PATH"] = os.pathsep.join(p for p in parts if p != self.dir)
        shutil.rmtree(self.dir, ignore_errors=True)


_launches = None
_idle = []            # classified as starting LAMMPS, started none (reported at the end)


def configure(config):
    """Called by tests/conftest.py's pytest_configure: the markers, the shim, and this module's
    hooks registered as a plugin (a conftest's own hooks do not see the set-up of a session
    fixture, whose node is above tests/)."""
    global _launches
    for line in MARKERS:
        config.addinivalue_line("markers", line)
    half = os.environ.get("TYLMP_TEST_HALF", "")
    if half not in ("",) + HALVES:
        raise pytest.UsageError(f"TYLMP_TEST_HALF={half!r}: expected 2021 or 2025 (or unset)")
    if _launches is None:
        _launches = _Launches()
    if not config.pluginmanager.is_registered(sys.modules[__name__]):
        config.pluginmanager.register(sys.modules[__name__], "tylmp-lammps-halves")


def pytest_unconfigure(config):
    global _launches
    if _launches is not None:
        _launches.close()
        _launches = None


def pytest_collection_modifyitems(config, items):
    half = os.environ.get("TYLMP_TEST_HALF", "")
    for item in items:
        kind = lammps_class(item)
        item.stash[CLASS] = kind
        reason = SKIP_REASON.get((half, kind))
        if reason:
            marker = item.get_closest_marker("lammps_once")
            why = (marker.kwargs.get("reason") or (marker.args or [""])[0]) if marker else ""
            item.add_marker(pytest.mark.skip(reason=reason.format(reason=why)))


@pytest.hookimpl(hookwrapper=True)
def pytest_fixture_setup(fixturedef, request):
    before = _launches.count()
    yield
    if _launches.count() > before:
        fixturedef.tylmp_started_lammps = True


@pytest.hookimpl(hookwrapper=True, tryfirst=True)
def pytest_runtest_setup(item):
    item.tylmp_launches_before = _launches.count()
    yield


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if call.when != "call" or report.skipped:
        return
    # the fixtures it uses: those it names and those it asked for (request.getfixturevalue)
    fixtures = [defs[-1] for name, defs in item._fixtureinfo.name2fixturedefs.items()
                if name in item.fixturenames and defs]
    fixtures += list(getattr(getattr(item, "_request", None), "_fixture_defs", {}).values())
    started = (_launches.count() > getattr(item, "tylmp_launches_before", _launches.count())
               or any(getattr(d, "tylmp_started_lammps", False) for d in fixtures))
    kind = item.stash.get(CLASS, None)
    if kind == "independent" and started:
        message = (f"{item.nodeid} started LAMMPS (lmp, or the Python module lammps; in the "
                   "test or a fixture it uses), but tests/lammps_halves.py classifies it as "
                   "version-independent, so the 4 Feb 2025 half of scripts/test.sh would skip "
                   "it: mark it @pytest.mark.runs_lammps (or remove its no_lammps marker)")
        report.longrepr = message if report.passed else f"{report.longrepr}\n\n{message}"
        report.outcome = "failed"
    elif kind in ("each", "once") and not started and report.passed:
        _idle.append(item.nodeid)


def pytest_terminal_summary(terminalreporter, config):
    if _idle:
        terminalreporter.write_line(
            f"tests/lammps_halves.py: {len(_idle)} tests classified as starting LAMMPS started "
            "none (@pytest.mark.no_lammps would leave them to the 29 Sep 2021 half)"
            + ("" if config.option.verbose > 0 else "; pytest -v lists them"))
        if config.option.verbose > 0:
            for nodeid in _idle:
                terminalreporter.write_line(f"  {nodeid}")
