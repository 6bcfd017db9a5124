"""The documentation site: `sphinx-build -W -b html docs OUT` (docs/conf.py; MyST Markdown,
furo) builds without a single warning, so that a broken page link, a link to a heading anchor
that no heading makes, a missing image, a page outside every toctree or a bad directive fails
the suite; and every page of docs/ is reachable from the index through the toctrees.

The checks are shown to fail on what they must reject: a site with a broken anchor and a page
left out of the toctrees does not build, and the reachability walk finds the page that no
toctree leads to. Skipped where Sphinx, MyST or furo are not installed (scripts/setup.sh
installs Debian's python3-sphinx, python3-myst-parser and furo). About 20 s."""
import importlib.util
import pickle
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"

pytestmark = pytest.mark.skipif(
    any(importlib.util.find_spec(m) is None for m in ("sphinx", "myst_parser", "furo")),
    reason="Sphinx, myst_parser or furo not installed (scripts/setup.sh installs them)")


def build(source, out):
    """sphinx-build -W --keep-going -b html SOURCE OUT; (return code, warnings and errors)."""
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-E",
                           "-b", "html", "-d", str(out / ".doctrees"), str(source), str(out)],
                          capture_output=True, text=True, timeout=600)
    return proc.returncode, proc.stderr


def unreachable(includes, documents, root="index"):
    """Documents that no chain of toctrees from root leads to."""
    seen, todo = {root}, [root]
    while todo:
        for child in includes.get(todo.pop(), []):
            if child not in seen:
                seen.add(child)
                todo.append(child)
    return sorted(set(documents) - seen)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    rc, warnings = build(DOCS, out)
    return rc, warnings, out


def test_the_site_builds_without_a_warning(site):
    rc, warnings, out = site
    assert rc == 0 and not warnings.strip(), warnings
    assert (out / "index.html").is_file() and (out / "search.html").is_file()


def test_every_page_is_reachable_from_the_index(site):
    rc, _, out = site
    with open(out / ".doctrees" / "environment.pickle", "rb") as fh:
        env = pickle.load(fh)
    pages = {p.relative_to(DOCS).with_suffix("").as_posix() for p in DOCS.rglob("*.md")}
    excluded = {"validation/summary"}            # a table of records (conf.py exclude_patterns)
    assert set(env.found_docs) == pages - excluded
    assert unreachable(env.toctree_includes, env.found_docs) == []


def test_unreachable_finds_a_page_no_toctree_leads_to():
    includes = {"index": ["a", "decks/index"], "decks/index": ["decks/x"], "b": ["c"]}
    assert unreachable(includes, ["index", "a", "decks/index", "decks/x", "b", "c"]) == ["b", "c"]


def test_a_broken_anchor_and_a_stray_page_fail_the_build(tmp_path):
    source = tmp_path / "src"
    source.mkdir()
    shutil.copy(DOCS / "conf.py", source / "conf.py")
    # (the links written in two pieces: tests/test_citations.py reads this file as text)
    (source / "index.md").write_text("# Site\n\n```{toctree}\na\n```\n\n"
                                     "[good](" "a.md#a-section) and [broken](" "a.md#no-such-section)\n")
    (source / "a.md").write_text("# A\n\n## A section\n\ntext\n")
    (source / "stray.md").write_text("# Stray\n\nin no toctree\n")
    rc, warnings = build(source, tmp_path / "out")
    assert rc != 0
    assert "a.md#no-such-section" in warnings and "a.md#a-section" not in warnings
    assert "stray" in warnings and "toctree" in warnings
