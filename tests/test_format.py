"""The C++ of plugin/ is in the style of .clang-format (LAMMPS's; scripts/format.sh applies it)
and no line of it is longer than 100 columns. clang-format leaves a long comment or string as
it is, so the second check is apart from the first. Two made-up files show that each check
can fail."""
import os
import shutil
import subprocess

import pytest

from conftest import REPO

CLANG_FORMAT = shutil.which("clang-format")
LIMIT = 100
needs_clang_format = pytest.mark.skipif(
    CLANG_FORMAT is None, reason="clang-format is not installed (scripts/setup.sh installs it)")


def plugin_sources():
    out = []
    for root, _, files in os.walk(os.path.join(REPO, "plugin")):
        out += [os.path.join(root, f) for f in files if f.endswith((".h", ".hpp", ".cpp"))]
    return sorted(out)


def differs_from_style(path):
    """True if clang-format, with the repository's .clang-format, would change the file."""
    r = subprocess.run([CLANG_FORMAT, "--style=file:" + os.path.join(REPO, ".clang-format"),
                        "--dry-run", "-Werror", path], capture_output=True, text=True)
    return r.returncode != 0


def long_lines(path):
    """(line number, columns) of the lines longer than LIMIT characters."""
    with open(path, encoding="utf-8") as fh:
        return [(k, len(line)) for k, line in enumerate(fh.read().splitlines(), 1)
                if len(line) > LIMIT]


def test_there_is_code_to_check():
    names = {os.path.relpath(p, REPO) for p in plugin_sources()}
    assert {"plugin/core/contact_law.hpp", "plugin/lammps/pair_thornton_yin.cpp",
            "plugin/liggghts/normal_model_thornton_yin.h"} <= names


@needs_clang_format
def test_plugin_is_in_the_style_of_clang_format(tmp_path):
    unformatted = tmp_path / "unformatted.cpp"
    unformatted.write_text("int  f(int* a){return *a;}\n")
    assert differs_from_style(str(unformatted))
    formatted = tmp_path / "formatted.cpp"
    formatted.write_text("int f(int *a)\n{\n  return *a;\n}\n")
    assert not differs_from_style(str(formatted))
    differ = [os.path.relpath(p, REPO) for p in plugin_sources() if differs_from_style(p)]
    assert not differ, ("not in the style of .clang-format (bash scripts/format.sh formats them):\n"
                        + "\n".join(differ))


def test_no_line_of_plugin_exceeds_100_columns(tmp_path):
    probe = tmp_path / "probe.h"
    probe.write_text("// " + "§" * (LIMIT - 3) + "\n// " + "x" * (LIMIT - 2) + "\n")
    assert long_lines(str(probe)) == [(2, LIMIT + 1)]      # characters, not bytes
    found = [f"{os.path.relpath(p, REPO)}:{k} ({n} columns)"
             for p in plugin_sources() for k, n in long_lines(p)]
    assert not found, f"lines longer than {LIMIT} columns:\n" + "\n".join(found)
