"""The installed packages are what a user's `lmp` and `/usr/bin/python3` see without any
PYTHONPATH: README's set-up must leave tylmp (with the freshly built library) and tyanalysis
importable from the stock interpreter, or `lmp -in inputs/axisym.in` cannot load the styles."""
import os
import subprocess

import pytest

from conftest import BUILD

pytestmark = pytest.mark.skipif(
    "TYLMP_BUILD_DIR" in os.environ or "TYLMP_LIBRARY" in os.environ,
    reason="a development build is under test, not the installed one")


def clean_env():
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TYLMP_LIBRARY")}
    return env


def test_installed_packages_import_from_the_stock_interpreter(tmp_path):
    out = subprocess.run(
        ["/usr/bin/python3", "-c",
         "import tylmp, tyanalysis, tylmp.specimen; print(tylmp.library_path())"],
        cwd=tmp_path, env=clean_env(), capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    installed = out.stdout.strip()
    assert os.path.exists(installed)
    # the install is the build under test, not an older one (cmake --install rewrites the
    # RUNPATH, so the bytes differ; the install must not predate the build)
    built = os.path.join(BUILD, "python", "tylmp", "tylmp.so")
    assert os.path.getmtime(installed) >= os.path.getmtime(built) - 1.0


def test_stock_lmp_loads_the_styles_in_any_directory(tmp_path):
    deck = tmp_path / "in.load"
    deck.write_text(
        'python tylmp_load input 1 SELF format p here "from tylmp import load as tylmp_load"\n'
        "python tylmp_load invoke\n"
        "units si\natom_style sphere\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\n"
        "create_atoms 1 single 0.5 0.5 0.5\nset atom 1 diameter 0.1 density 2650\n"
        "comm_modify vel yes\npair_style thornton/yin\npair_coeff * * 70e9 0.3 0.3 0.6\n"
        "fix cell all cell/servo iso 1e5 max_rate 1e-3\nfix d all damping/cundall 0.1 0.1\n"
        "fix nve all nve/sphere\nrun 10\n")
    out = subprocess.run(["lmp", "-in", "in.load", "-log", "none"], cwd=tmp_path,
                         env=clean_env(), capture_output=True, text=True)
    assert out.returncode == 0 and "ERROR" not in out.stdout, out.stdout[-2000:] + out.stderr
