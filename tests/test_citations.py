"""Citations in code comments and docs point at text the repository ships (issues 13 and 14).

* No file cites the reference notes that are not part of the repository (physics.md and its
  companions) or their location on the developers' machine.
* Every `docs/theory.md §N.M` (or `theory.md §N.M`) names a numbered heading of docs/theory.md.
  So does every bare `§N.M` inside docs/theory.md and inside any file that cites docs/theory.md
  (there a bare § continues those citations), except a `paper §N` (a section of the paper).
* Every path to a markdown file (`docs/<file>.md`, `bench/data/README.md`, ...) and every
  relative markdown link `[...](<file>.md)` points at an existing file, and every mention of a
  results file `bench/results/<name>` (`name.{csv,json}`, `name.*`, an `--out` prefix) names
  the start of an existing file there (results are renamed by what they measure, issue 13).

The repository scan covers every file git tracks or would track (untracked, not ignored), except
this one, whose unit tests below hold deliberately bad citations; the parsers are unit-tested
on synthetic text so that each check is shown to fail on what it must reject.
"""
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
THEORY = ROOT / "docs" / "theory.md"
SELF = Path(__file__).resolve()

# reference notes kept outside the repository; citing them leaves the reader with nothing
NOT_SHIPPED = ("physics.md", "peers.md", "peer-runs.md", "aesthetics.md",
               "seed-paper-thornton-periodic-cell", "shared/reference")

SECTION = r"§\s?(\d+(?:\.\d+)*)"
# "theory.md §1.2", "docs/theory.md §0–§3", "theory.md §2.1/§2.3", "theory.md §1 and §3.2"
THEORY_CITATION = re.compile(
    r"theory\.md\)?\s*(§\s?\d+(?:\.\d+)*(?:\s*(?:,|–|-|/|and|or|to)\s*§\s?\d+(?:\.\d+)*)*)")
HEADING = re.compile(r"^#{1,6}\s+(\d+(?:\.\d+)*)\.?\s", re.MULTILINE)
# a path ending in .md with at least one directory: docs/theory.md, bench/data/README.md
MD_PATH = re.compile(r"(?<![\w./-])((?:[\w-]+/)+[\w.-]+\.md)\b")
# a relative markdown link target: [text](performance.md#anchor), [x](docs/theory.md)
MD_LINK = re.compile(r"\]\((?!https?:|mailto:|#)([^)\s#]+\.md)(?:#[^)\s]*)?\)")
# a results file of the tree; one named as COMMIT:bench/results/NAME (what `git show` takes) is
# a record of that commit, looked up there instead
RESULTS = re.compile(r"(?<![0-9a-f]:)bench/results/([\w.-]+)")
RESULTS_AT = re.compile(r"\b([0-9a-f]{7,40}):(bench/results/[\w.-]+\w)")


def line_of(text, match):
    """The line number (from 1) at which a regular-expression match starts in text."""
    return text.count("\n", 0, match.start()) + 1


def theory_sections(text):
    """Section numbers of the numbered headings ('## 1.', '### 1.2 ...') of a theory page."""
    return set(HEADING.findall(text))


def cited_theory_sections(text):
    """(line number, section) for every docs/theory.md or theory.md § citation in text."""
    cited = []
    for m in THEORY_CITATION.finditer(text):
        line = line_of(text, m)
        cited += [(line, s) for s in re.findall(SECTION, m.group(1))]
    return cited


def bare_sections(text):
    """(line number, section) for every § reference in text but those of the paper (paper §5)."""
    return [(line_of(text, m), m.group(1))
            for m in re.finditer(r"(?<!paper )(?<!paper's )" + SECTION, text)]


def unshipped_citations(text):
    """(line number, name) of every mention of a reference note that is not shipped."""
    found = []
    for lineno, line in enumerate(text.splitlines(), 1):
        found += [(lineno, name) for name in NOT_SHIPPED if name in line]
    return found


def missing_markdown_targets(text, source_dir, root=ROOT):
    """(line number, target) of .md paths and relative .md links that name no existing file.

    A path with a directory (docs/x.md) is read from the repository root or, in a markdown
    page, also relative to the page; a link target relative to the page that holds it."""
    missing = []
    for m in MD_PATH.finditer(text):
        target = m.group(1)
        if not ((root / target).is_file() or (source_dir / target).is_file()):
            missing.append((line_of(text, m), target))
    for m in MD_LINK.finditer(text):
        target = m.group(1)
        if not (source_dir / target).is_file():
            missing.append((line_of(text, m), target))
    return sorted(set(missing))


def missing_results(text, results_dir=ROOT / "bench" / "results"):
    """(line number, name) of bench/results/<name> mentions that start no file's name there."""
    present = [p.name for p in results_dir.iterdir()] if results_dir.is_dir() else []
    missing = []
    for m in RESULTS.finditer(text):
        name = m.group(1).rstrip(".")
        if not any(f.startswith(name) for f in present):
            missing.append((line_of(text, m), name))
    return missing


def repository_file_names():
    """Files git tracks or would track; without git (an exported tree), every file but those of
    hidden and build directories."""
    try:
        return subprocess.run(
            ["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
            cwd=ROOT, check=True, capture_output=True).stdout.decode().split("\0")
    except (OSError, subprocess.CalledProcessError):
        skip = lambda part: part.startswith(".") or part.startswith("build") or part == "__pycache__"
        return [str(p.relative_to(ROOT)) for p in ROOT.rglob("*")
                if not any(skip(part) for part in p.relative_to(ROOT).parts[:-1])]


def repository_text_files():
    for name in repository_file_names():
        path = ROOT / name
        if not name or not path.is_file() or path.resolve() == SELF:
            continue
        data = path.read_bytes()
        if b"\0" in data[:8192]:
            continue                                   # binary (figures, restart files)
        try:
            yield path, data.decode("utf-8")
        except UnicodeDecodeError:
            continue


@pytest.fixture(scope="module")
def files():
    found = list(repository_text_files())
    assert len(found) > 50                             # the scan sees the repository
    assert any(p == THEORY for p, _ in found)
    return found


@pytest.fixture(scope="module")
def sections():
    return theory_sections(THEORY.read_text(encoding="utf-8"))


# ---------------------------------------------------------------- the repository


def test_no_file_cites_reference_notes_that_are_not_shipped(files):
    bad = [f"{p.relative_to(ROOT)}:{line}: {name}"
           for p, text in files for line, name in unshipped_citations(text)]
    assert not bad, "cite docs/theory.md or the paper instead:\n" + "\n".join(bad)


def test_every_theory_citation_names_an_existing_section(files, sections):
    bad = [f"{p.relative_to(ROOT)}:{line}: §{s}"
           for p, text in files for line, s in cited_theory_sections(text) if s not in sections]
    assert not bad, "no such heading in docs/theory.md:\n" + "\n".join(bad)


def test_bare_sections_in_citing_files_exist(files, sections):
    # docs/theory.md itself, and files whose § references continue a docs/theory.md citation
    bad = [f"{p.relative_to(ROOT)}:{line}: §{s}"
           for p, text in files if p == THEORY or cited_theory_sections(text)
           for line, s in bare_sections(text) if s not in sections]
    assert not bad, "no such heading in docs/theory.md:\n" + "\n".join(bad)


def test_theory_sections_are_numbered_in_order(sections):
    # the sections the code cites: fixed numbers, 0 to 9, each with its subsections in order
    text = THEORY.read_text(encoding="utf-8")
    numbers = [tuple(int(x) for x in s.split(".")) for s in HEADING.findall(text)]
    assert numbers == sorted(numbers) and len(numbers) == len(set(numbers))
    assert {str(n) for n in range(10)} <= sections


def test_every_markdown_path_and_link_exists(files):
    bad = [f"{p.relative_to(ROOT)}:{line}: {target}"
           for p, text in files for line, target in missing_markdown_targets(text, p.parent)]
    assert not bad, "points at no file:\n" + "\n".join(bad)


def test_every_results_file_mentioned_exists(files):
    bad = [f"{p.relative_to(ROOT)}:{line}: bench/results/{name}"
           for p, text in files for line, name in missing_results(text)]
    assert not bad, "no such results file:\n" + "\n".join(bad)


def in_commit(commit, path):
    """True if `path` is a file of `commit`, None if git cannot tell (no repository, or a
    shallow clone without that commit)."""
    try:
        if subprocess.run(["git", "cat-file", "-e", commit + "^{commit}"], cwd=ROOT,
                          capture_output=True).returncode != 0:
            return None
        return subprocess.run(["git", "cat-file", "-e", f"{commit}:{path}"], cwd=ROOT,
                              capture_output=True).returncode == 0
    except OSError:
        return None


def test_every_results_file_of_a_commit_exists_there(files):
    found = [(p, line_of(text, m), m.group(1), m.group(2))
             for p, text in files for m in RESULTS_AT.finditer(text)]
    bad = [f"{p.relative_to(ROOT)}:{line}: {commit}:{path}"
           for p, line, commit, path in found if in_commit(commit, path) is False]
    assert not bad, "no such file in that commit:\n" + "\n".join(bad)


# ---------------------------------------------------------------- the checks can fail


def test_parser_rejects_a_reference_note_citation():
    text = "x = 1  // closed form (physics.md §1.4)\n# see peers.md\nok: docs/theory.md §1.4\n"
    assert unshipped_citations(text) == [(1, "physics.md"), (2, "peers.md")]


def test_parser_finds_every_section_of_a_citation():
    text = ("// (docs/theory.md §1.4; Parteli 2014)\n"
            "# theory.md §0–§3, then §9 of nothing\n"
            "(docs/theory.md §2.1/§2.3 with P -> Peff), theory.md §1 and §3.2\n"
            "docs/theory.md §4.1, Li, Xu & Thornton 2005; theory.md §2.3, step 5\n"
            "see [theory.md](theory.md) for all\n")
    assert cited_theory_sections(text) == [(1, "1.4"), (2, "0"), (2, "3"), (3, "2.1"),
                                           (3, "2.3"), (3, "1"), (3, "3.2"), (4, "4.1"),
                                           (4, "2.3")]


def test_a_citation_of_a_missing_section_is_caught(sections):
    assert "1.4" in sections and "7.3" in sections
    text = "// the closed form (docs/theory.md §1.4)\n// the fabric tensor (docs/theory.md §12.7)\n"
    assert [c for c in cited_theory_sections(text) if c[1] not in sections] == [(2, "12.7")]


def test_a_results_file_of_a_commit_is_looked_up_in_that_commit():
    text = "speed (`git show\n800a0c9:bench/results/pair_speed_plumbing.json`), now bench/results/x.csv"
    assert [m.groups() for m in RESULTS_AT.finditer(text)] == [
        ("800a0c9", "bench/results/pair_speed_plumbing.json")]
    assert [m.group(1) for m in RESULTS.finditer(text)] == ["x.csv"]
    if in_commit("800a0c9", "README.md") is None:
        pytest.skip("git cannot read commit 800a0c9 here (no repository or a shallow clone)")
    assert in_commit("800a0c9", "bench/results/pair_speed_plumbing.json")
    assert in_commit("800a0c9", "bench/results/no_such_record.json") is False


def test_bare_section_parser_skips_the_papers_sections():
    text = "// §1.4b Newton (§2.2 stage A), prestrain of the paper §5, the paper's §3\n§1.2-1.3\n"
    assert bare_sections(text) == [(1, "1.4"), (1, "2.2"), (2, "1.2")]


def test_headings_parser_reads_numbered_headings_only():
    page = "# Title\n\n## 0. Symbols\n### 1.2 Points\n#### 10.3.1 Deep\n## Notes\n§5 in text\n"
    assert theory_sections(page) == {"0", "1.2", "10.3.1"}


def test_missing_markdown_paths_and_links_are_caught(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "theory.md").write_text("# t\n")
    page = ("see docs/theory.md and docs/gone.md,\n"
            "[ok](theory.md#1-normal), [bad](missing.md), [web](https://x.org/a.md)\n"
            "self.md(x) is code, not a path\n")
    assert missing_markdown_targets(page, tmp_path / "docs", root=tmp_path) == [
        (1, "docs/gone.md"), (2, "missing.md")]


def test_missing_results_files_are_caught(tmp_path):
    for name in ("contact_level.csv", "contact_level.json", "kernel_rework_speedup.csv"):
        (tmp_path / name).write_text("")
    text = ("writes bench/results/contact_level.{csv,json}; see bench/results/kernel_rework_speedup.\n"
            "old name bench/results/kernel_since_b6360e3.csv, and bench/results/ itself\n")
    assert missing_results(text, tmp_path) == [(2, "kernel_since_b6360e3.csv")]
