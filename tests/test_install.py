"""The package tylmp as a user gets it: one package (loader, decks, analysis) without import
circles; `pip install` of the build's package (build/python) into a fresh virtual environment
gives the `tyanalysis` command and a tylmp that Debian's `lmp` imports when that environment is
first on PATH, with nothing written outside the environment; and the environment README's
set-up made (.venv, scripts/setup.sh) holds the build under test, the system's Python none."""
import ast
import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import BUILD, REPO

SOURCE = os.path.join(REPO, "python")
VENV = os.environ.get("TYLMP_VENV", os.path.join(REPO, ".venv"))

LOAD_DECK = (
    'python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"\n'
    "python tylmp_load invoke\n"
    'python where here """\n'
    "def where():\n"
    "    import tylmp\n"
    "    print('tylmp from', tylmp.__file__)\n"
    '"""\n'
    "python where invoke\n"
    "units si\natom_style sphere\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\n"
    "create_atoms 1 single 0.5 0.5 0.5\nset atom 1 diameter 0.1 density 2650\n"
    "comm_modify vel yes\npair_style thornton/yin\npair_coeff * * 70e9 0.3 0.3 0.6\n"
    "fix cell all cell/servo iso 1e5 max_rate 1e-3\nfix d all damping/cundall 0.1 0.1\n"
    "fix nve all nve/sphere\nrun 10\n")


def clean_env(**extra):
    """The environment of a user's shell: no PYTHONPATH of the test set-up, no library override."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TYLMP_LIBRARY")}
    env.update(extra)
    return env


def inside(path, directory):
    return os.path.realpath(path).startswith(os.path.realpath(directory) + os.sep)


# ---- the import graph ------------------------------------------------------------------------

def package_modules():
    """{module name: source file} of every module of the package tylmp in python/."""
    out = {}
    for root, _, files in os.walk(os.path.join(SOURCE, "tylmp")):
        for f in files:
            if f.endswith(".py"):
                rel = os.path.relpath(os.path.join(root, f), SOURCE)[:-3].split(os.sep)
                if rel[-1] == "__init__":
                    rel = rel[:-1]
                out[".".join(rel)] = os.path.join(root, f)
    return out


def imports_of(name, path, modules):
    """The package's modules that module `name` imports anywhere in its code (at the top or
    inside a function: a deferred import of a circle is still a circle)."""
    is_package = path.endswith("__init__.py")
    base = name.split(".") if is_package else name.split(".")[:-1]
    found = set()
    for node in ast.walk(ast.parse(open(path, encoding="utf-8").read())):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name in modules)
        elif isinstance(node, ast.ImportFrom):
            parent = base[:len(base) - node.level + 1] if node.level else []
            target = ".".join(parent + (node.module.split(".") if node.module else []))
            for a in node.names:        # `from package import module` imports the module
                sub = f"{target}.{a.name}"
                found.add(sub if sub in modules else target)
    return {m for m in found if m in modules and m != name}


def test_the_package_imports_no_module_in_a_circle():
    """Static: the graph of imports between the package's modules has no cycle. Two cases to
    show the check can fail: a made-up pair that import each other is found, and the old
    circles (metrics -> compare -> metrics) would be."""
    modules = package_modules()
    assert {"tylmp", "tylmp.decks", "tylmp.specimen", "tylmp.analysis",
            "tylmp.analysis.cli", "tylmp.analysis.reproduce"} <= set(modules)
    graph = {m: imports_of(m, p, modules) for m, p in modules.items()}
    assert "tylmp.analysis.metrics" in graph["tylmp.analysis.compare"]    # the graph is read

    def cycle(g):
        state, stack = {}, []

        def visit(m):
            state[m] = "open"
            stack.append(m)
            for n in sorted(g[m]):
                if state.get(n) == "open":
                    return stack[stack.index(n):] + [n]
                if n not in state:
                    found = visit(n)
                    if found:
                        return found
            stack.pop()
            state[m] = "done"
            return None
        for m in sorted(g):
            if m not in state:
                found = visit(m)
                if found:
                    return found
        return None

    assert cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert cycle(dict(graph, **{"tylmp.analysis.metrics": graph["tylmp.analysis.metrics"] |
                                {"tylmp.analysis.compare"}})) is not None
    found = cycle(graph)
    assert found is None, "import circle: " + " -> ".join(found)


def test_every_module_imports_first_in_a_fresh_interpreter():
    """Dynamic: each module imported first, alone, in a new interpreter (an import circle
    shows as a partly initialised module whose name is missing); __main__ runs the command."""
    names = sorted(m for m in package_modules() if not m.endswith(".__main__"))
    code = ("import importlib, subprocess, sys\n"
            "bad = []\n"
            "for m in sys.argv[1:]:\n"
            "    r = subprocess.run([sys.executable, '-c', f'import {m}'], capture_output=True,\n"
            "                       text=True)\n"
            "    if r.returncode:\n"
            "        bad.append(m + ': ' + r.stderr.strip().splitlines()[-1])\n"
            "print('\\n'.join(bad))\n")
    out = subprocess.run([sys.executable, "-c", code, *names], capture_output=True, text=True,
                         env=clean_env(PYTHONPATH=SOURCE, MPLBACKEND="Agg"), timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == ""


# ---- pip install into a fresh virtual environment --------------------------------------------

def debian_lmp_version():
    """LAMMPS version of /usr/bin/lmp as tylmp names it ('29 Sep 2021'), or None."""
    if not os.path.exists("/usr/bin/lmp"):
        return None
    out = subprocess.run(["/usr/bin/lmp", "-h"], capture_output=True, text=True,
                         env=clean_env(), timeout=60).stdout
    found = re.search(r"Simulator - (\d+ \w+ \d{4})", out)
    return found.group(1).strip() if found else None


@pytest.fixture(scope="module")
def fresh_venv(tmp_path_factory):
    """A virtual environment made from /usr/bin/python3 with --system-site-packages, and
    build/python (a copy: pip builds in the tree it installs) installed into it with pip,
    offline, as README's Install says."""
    work = tmp_path_factory.mktemp("pip")
    package = work / "package"
    shutil.copytree(os.path.join(BUILD, "python"), package, symlinks=True,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
    venv = work / "venv"
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(venv)],
                   check=True, env=clean_env(), timeout=300)
    out = subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "--quiet",
                          "--no-build-isolation", "--no-index", str(package)],
                         capture_output=True, text=True, env=clean_env(), timeout=600)
    assert out.returncode == 0, out.stdout + out.stderr
    return venv


def test_pip_install_gives_the_command_and_writes_only_into_the_environment(fresh_venv,
                                                                              tmp_path):
    venv = str(fresh_venv)
    py = os.path.join(venv, "bin", "python")
    # every file pip wrote is in the environment (its RECORD), the command among them
    info = subprocess.run([py, "-c", "import importlib.metadata as m, os; d = m.distribution("
                           "'tylmp'); print('\\n'.join(os.path.abspath(d.locate_file(f)) "
                           "for f in d.files))"], capture_output=True, text=True,
                          env=clean_env(), cwd=tmp_path, timeout=60)
    assert info.returncode == 0, info.stderr
    files = info.stdout.split()
    assert files and all(inside(f, venv) for f in files), files
    command = os.path.join(venv, "bin", "tyanalysis")
    assert command in files and os.access(command, os.X_OK)
    # the package has the library of the build, the analysis and the decks
    lib = subprocess.run([py, "-c", "import tylmp, tylmp.analysis.cli; p = tylmp.library_path();"
                          " print(p, tylmp.built_for(p))"], capture_output=True, text=True,
                         env=clean_env(), cwd=tmp_path, timeout=60)
    assert lib.returncode == 0, lib.stderr
    path, version = lib.stdout.split()
    assert inside(path, venv)
    import tylmp
    assert int(version) == tylmp.built_for(os.path.join(BUILD, "python", "tylmp", "tylmp.so"))
    # the command, typed by name, runs with the environment's Python even when the python3
    # first on PATH is another one (a user's pyenv, say) that lacks the packages
    fake = tmp_path / "fakebin"
    fake.mkdir()
    (fake / "python3").write_text("#!/bin/sh\necho 'not the python with tylmp' >&2\nexit 3\n")
    (fake / "python3").chmod(0o755)
    env = clean_env(MPLBACKEND="Agg",
                    PATH=os.pathsep.join([str(fake), os.path.dirname(command), os.environ["PATH"]]))
    r = subprocess.run(["tyanalysis", "--help"], capture_output=True, text=True, env=env,
                       cwd=tmp_path, timeout=60)
    assert r.returncode == 0 and r.stdout.startswith("usage: tyanalysis "), r.stdout + r.stderr
    # the decks went with the package: reproduce (outside a checkout) runs the installed ones
    r = subprocess.run(["tyanalysis", "reproduce", "--scale", "quick", "--dir", "runs",
                        "--only", "axisym_dense", "--dry-run"], capture_output=True, text=True,
                       env=env, cwd=tmp_path, timeout=60)
    assert r.returncode == 0, r.stdout + r.stderr
    decks = re.findall(r"-in (\S+\.in)", r.stdout)
    assert len(decks) == 2 and all(inside(d, venv) and os.path.isfile(d) for d in decks), r.stdout


def test_debian_lmp_imports_tylmp_from_the_environment_on_path(fresh_venv, tmp_path):
    """LAMMPS's embedded Python finds the environment through the python3 first on PATH (as
    `. venv/bin/activate` sets it), in any directory, without PYTHONPATH."""
    import tylmp
    built = tylmp.built_for(os.path.join(BUILD, "python", "tylmp", "tylmp.so"))
    if debian_lmp_version() != tylmp._version_name(built):
        pytest.skip(f"the build under test is for LAMMPS {tylmp._version_name(built)}, "
                    "not for Debian's /usr/bin/lmp")
    (tmp_path / "in.load").write_text(LOAD_DECK)
    env = clean_env(PATH=os.pathsep.join([str(fresh_venv / "bin"), os.environ["PATH"]]))
    out = subprocess.run(["/usr/bin/lmp", "-in", "in.load", "-log", "none"], cwd=tmp_path,
                         env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0 and "ERROR" not in out.stdout, out.stdout[-2000:] + out.stderr
    where = re.search(r"^tylmp from (\S+)", out.stdout, re.M)
    assert where and inside(where.group(1), str(fresh_venv)), out.stdout[-2000:]


# ---- the environment of scripts/setup.sh -----------------------------------------------------

setup_only = pytest.mark.skipif(
    "TYLMP_BUILD_DIR" in os.environ or "TYLMP_LIBRARY" in os.environ,
    reason="a development build is under test, not the one scripts/setup.sh installed")


@setup_only
def test_setup_environment_holds_the_build_under_test(tmp_path):
    py = os.path.join(VENV, "bin", "python")
    out = subprocess.run(
        [py, "-c", "import tylmp, tylmp.analysis.cli, tylmp.specimen, tylmp.decks; "
         "print(tylmp.library_path())"],
        cwd=tmp_path, env=clean_env(), capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    installed = out.stdout.strip()
    assert inside(installed, VENV) and os.path.exists(installed)
    # the install is the build under test, not an older one
    built = os.path.join(BUILD, "python", "tylmp", "tylmp.so")
    assert os.path.getmtime(installed) >= os.path.getmtime(built) - 1.0
    r = subprocess.run([os.path.join(VENV, "bin", "tyanalysis"), "--help"], cwd=tmp_path,
                       env=clean_env(), capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.startswith("usage: tyanalysis ")
    r = subprocess.run(["/usr/bin/python3", "-c", "import importlib.util as u; "
                        "print(u.find_spec('tylmp'), u.find_spec('tyanalysis'))"],
                       capture_output=True, text=True, env=clean_env(), cwd=tmp_path)
    assert r.stdout.strip() == "None None", "tylmp in the system's Python: " + r.stdout


@setup_only
def test_stock_lmp_loads_the_styles_in_any_directory(tmp_path):
    (tmp_path / "in.load").write_text(LOAD_DECK)
    env = clean_env(PATH=os.pathsep.join([os.path.join(VENV, "bin"), os.environ["PATH"]]))
    out = subprocess.run(["lmp", "-in", "in.load", "-log", "none"], cwd=tmp_path,
                         env=env, capture_output=True, text=True)
    assert out.returncode == 0 and "ERROR" not in out.stdout, out.stdout[-2000:] + out.stderr
    where = re.search(r"^tylmp from (\S+)", out.stdout, re.M)
    assert where and inside(where.group(1), VENV), out.stdout[-2000:]
