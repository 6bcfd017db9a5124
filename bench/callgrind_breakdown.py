#!/usr/bin/env python3
"""Where the instructions of a pair computation go: for callgrind files kept by
bench/instruction_profile.py (--keep DIR), the instructions per atom-step of the functions of the
force loop, inclusive (with what they call) and self (exclusive), from callgrind_annotate, and
how many contacts the law evaluated (calls of its scalar step or its vector builds; the SIMD
builds take up to 16 contacts a call, so only the scalar files give contacts).

    /usr/bin/python3 bench/callgrind_breakdown.py DIR/callgrind.CASE.out ... [--atom-steps N]
        [--json OUT.json]

--atom-steps: atoms x (steps + 1) of the profiled run (default 3620 x 201, the dense specimen
for 200 steps and the setup pass, as instruction_profile.py counts them).
"""
import argparse
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import write_result    # noqa: E402

# label -> pattern of the function (the first match in callgrind_annotate's list)
FUNCTIONS = [
    ("LAMMPS pair: compute", r"PairThorntonYin::compute\("),
    ("LAMMPS pair: run_batch", r"PairThorntonYin::run_batch<"),
    ("LAMMPS pair: scatter", r"PairThorntonYin::scatter<"),
    ("LIGGGHTS pair loop: Granular::compute_force",
     r"^[^ ]*LIGGGHTS::PairStyles::Granular<.*>::compute_force"),
    ("model's pair style: ThorntonYinPair::compute_force", r"ThorntonYinPair::compute_force"),
    ("model's pair loop: pair_loop_of (walk, gather, history load)",
     r"NormalModel<31>::pair_loop_of<"),
    ("model: contact (one at a time)", r"NormalModel<31>::contact\("),
    ("model: run_batch", r"NormalModel<31>::run_batch\("),
    ("model: lane_result", r"NormalModel<31>::lane_result[<(]"),
    ("law: advance_batch (any build)", r"void tycore::advance_batch<"),
    ("law: scalar_lane", r"tycore::detail::scalar_lane<"),
    ("law: scalar_step", r"tycore::law::scalar_step<"),
    ("geometry: batch_geometry (vector)", r"tycore::detail::batch_geometry_"),
    ("touch_or_break", r"tycore::detail::touch_or_break<"),
    ("store_history", r"tycore::store_history\("),
]


def annotate(path, inclusive):
    args = ["callgrind_annotate", "--threshold=100"] + (["--inclusive=yes"] if inclusive else [])
    return subprocess.run(args + [path], capture_output=True, text=True, check=True).stdout


def per_function(text):
    """{function text: instructions} from callgrind_annotate's function list."""
    found = {}
    for line in text.splitlines():
        m = re.match(r"^\s*([\d,]+) \([ \d.]+%\)\s+\S*?\?\?\?:(.*) \[", line)
        if m:
            found.setdefault(m.group(2), int(m.group(1).replace(",", "")))
    return found


def calls_of(path, pattern):
    """Calls of the first function matching pattern: the sum over its callers in
    callgrind_annotate --tree=caller (a block: the "<" lines of the callers, then the "*" line
    of the function)."""
    text = subprocess.run(["callgrind_annotate", "--tree=caller", "--threshold=100", path],
                          capture_output=True, text=True, check=True).stdout
    for block in text.split("\n\n"):
        lines = block.splitlines()
        own = [l for l in lines if re.match(r"^\s*[\d,]+ \([ \d.]+%\)\s+\*", l)]
        if own and re.search(pattern, own[0]):
            return sum(int(m.group(1).replace(",", "")) for l in lines if "  < " in l
                       for m in [re.search(r"\(([\d,]+)x\)", l)] if m)
    return 0


def breakdown(path, atom_steps):
    inc, exc = per_function(annotate(path, True)), per_function(annotate(path, False))
    rows = {}
    for label, pattern in FUNCTIONS:
        name = next((f for f in inc if re.search(pattern, f)), None)
        if name is None:
            continue
        rows[label] = {"inclusive": inc[name] / atom_steps, "self": exc.get(name, 0) / atom_steps}
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--atom-steps", type=int, default=3620 * 201)
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    result = {"atom_steps": args.atom_steps, "files": {}}
    for path in args.files:
        rows = breakdown(path, args.atom_steps)
        contacts = calls_of(path, r"tycore::law::scalar_step<")
        name = os.path.basename(path)
        result["files"][name] = {"per_atom_step": rows,
                                 "scalar_law_calls": contacts or None}
        print(f"{name}" + (f"  (the scalar law called {contacts} times)" if contacts else ""))
        for label, r in rows.items():
            print(f"  {label:46s} {r['inclusive']:8.0f} inclusive {r['self']:8.0f} self")
    if args.json:
        write_result(args.json, result)


if __name__ == "__main__":
    main()
