"""What the repository ships is portable (issue 29, a distributable plugin): no committed file
carries a path of the machine that wrote it, and every benchmark result is written through
bench/provenance.py, which stamps it with commit, CPU, compiler and LAMMPS version and makes
its paths relative."""
import json
import os
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# a home or work directory of some machine: /root/..., /home/NAME/..., /work/...
MACHINE_PATH = re.compile(r"(?<![\w.~$}-])/(?:root|home/[\w.-]+|work)/[\w.-]")


def shipped_text_files():
    names = subprocess.run(["git", "-C", str(ROOT), "ls-files", "--cached", "--others",
                            "--exclude-standard"], capture_output=True, text=True,
                           check=True).stdout.split()
    for name in names:
        path = ROOT / name
        if not path.is_file() or path.stat().st_size > 4_000_000:
            continue
        data = path.read_bytes()
        if b"\0" in data:
            continue
        yield name, data.decode("utf-8", errors="replace")


def machine_paths(text):
    return [m.group(0) for m in MACHINE_PATH.finditer(text)]


def test_the_machine_path_pattern_catches_what_it_must():
    assert machine_paths('"data": "/work/main/bench/data/x.data"')
    assert machine_paths("lmp at /root/.cache/tylmp/lammps/bin/lmp")
    assert machine_paths("see /home/alice/runs/a.csv")
    assert not machine_paths("/usr/bin/python3 and /etc/apt/sources.list.d and /proc/cpuinfo")
    assert not machine_paths("~/.cache/tylmp/lammps and $HOME/work/x and build/work/y")


def test_no_committed_file_names_a_path_of_the_machine_that_wrote_it():
    this = Path(__file__).resolve().relative_to(ROOT).as_posix()
    found = {name: machine_paths(text)[:3] for name, text in shipped_text_files()
             if name != this and machine_paths(text)}
    assert not found, f"machine paths in committed files: {found}"


def test_a_benchmark_result_is_stamped_and_portable(bench, tmp_path):
    provenance = bench("provenance")
    home = os.path.expanduser("~")
    out = tmp_path / "result.json"
    provenance.write_result(str(out), {
        "data": str(ROOT / "bench" / "data" / "dense_paper_100kPa.data"),
        "lmp": os.path.join(home, ".cache", "tylmp", "bin", "lmp"),
        "cases": {"a": 1.5}})
    record = json.loads(out.read_text())
    assert record["data"] == "bench/data/dense_paper_100kPa.data"
    assert record["lmp"] == "~/.cache/tylmp/bin/lmp"
    assert record["cases"] == {"a": 1.5}
    stamp = record["provenance"]
    head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True,
                          text=True, check=True).stdout.strip()
    assert head.startswith(stamp["commit"].removesuffix("-dirty"))
    with open("/proc/cpuinfo") as fh:
        model = next(line.split(":", 1)[1].strip() for line in fh
                     if line.startswith("model name"))
    assert stamp["cpu"].startswith(model)
    assert re.search(r"\d+\.\d+", stamp["compiler"])       # a compiler's version line
    assert re.fullmatch(r"\d{1,2} [A-Z][a-z]{2} \d{4}", stamp["lammps"])
