"""What the bench scripts read from LAMMPS's output, parsed in one place: the "Loop time of ..."
line that closes every run, and the rows of the timing breakdown that follows it
("Pair | min | avg | max | %varavg | %total"). LIGGGHTS 3.8 prints the same loop line.

    from lammps_log import loops, first_loop, section
"""
import re

LOOP = re.compile(r"^Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                  re.M)


def loops(text):
    """Every run's loop line, in order: dicts with seconds, procs, steps, atoms."""
    return [{"seconds": float(t), "procs": int(p), "steps": int(s), "atoms": int(a)}
            for t, p, s, a in LOOP.findall(text)]


def first_loop(text, what="LAMMPS output"):
    """The first run's loop line (see loops); RuntimeError naming `what` when there is none."""
    found = loops(text)
    if not found:
        raise RuntimeError(f"{what}: no 'Loop time of ...' line\n{text[-2000:]}")
    return found[0]


def section(text, name):
    """Every timing-breakdown row of section `name` (Pair, Neigh, Comm, Modify, Other, ...), in
    order: dicts with avg (s) and pct (% of the loop). "Other" has only these two columns."""
    rows = []
    for m in re.finditer(rf"^{name}\s*\|(.*)$", text, re.M):
        fields = [f.strip() for f in m.group(1).split("|")]
        rows.append({"avg": float(fields[1]) if len(fields) > 1 and fields[1] else float("nan"),
                     "pct": float(fields[-1]) if fields[-1] else float("nan")})
    return rows
