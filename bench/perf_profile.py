#!/usr/bin/env python3
"""Where the time of a thornton/yin run goes, by sampling: the law (the batch entry of
plugin/core), the pair's own loop (neighbour loop, gather, scatter: the rest of its eval), the
neighbour-list builds with the contact-history bookkeeping, communication, integration and
the rest, as shares of the samples of the whole run.

    /usr/bin/python3 bench/perf_profile.py [--cases "thornton/yin G=0.6" "thornton/yin G=0"]
        [--steps 5000] [--data bench/data/dense_paper_100kPa.data]
        [--out PREFIX]   (default: perf_profile in the repository's bench results)

Each case runs the deck of bench/pair_speed.py (same data file, neighbor settings, timestep,
plain NVE, one rank) under `perf record -e cpu-clock` (the kernel's timer, so it works without
hardware counters), then `perf report --sort symbol` attributes every sample to the function
it fell in (self time; inlined code counts to the function it was inlined into). Functions are
grouped by GROUPS below (first match wins). ns per atom-step of each group = its share times
the loop time per atom-step (LAMMPS's "Loop time"; setup and the read of the data file are a
few per cent of the samples and land in "other"). Wall-clock shares: run on a quiet machine.
Writes OUT.json and prints the table. TYLMP_LIBRARY selects the build, as for pair_speed.py.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pair_speed  # noqa: E402
from lammps_log import first_loop  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import write_result  # noqa: E402

# group -> regular expression on the symbol (first match wins, in this order)
GROUPS = [
    ("law (tycore batch entry)", r"tycore::"),
    ("pair loop, gather, scatter", r"PairThorntonYin::"),
    ("neighbour lists, history bookkeeping", r"NPair|NBin|NStencil|Neighbor::|FixNeighHistory|"
                                              r"MyPage|Neighbor"),
    ("communication", r"Comm|MPI|mca_|ompi_|opal_"),
    ("integration", r"FixNVE"),
    ("memory (libc copies)", r"memcpy|memmove|memset"),
]


def profile(case, data, steps, workdir):
    deck = pair_speed.case_deck(case, data, steps)
    path = os.path.join(workdir, "in.perf")
    with open(path, "w") as fh:
        fh.write(deck)
    perf_data = os.path.join(workdir, "perf.data")
    proc = subprocess.run(["perf", "record", "-e", "cpu-clock", "-F", "4000", "-o", perf_data,
                           "--", "lmp", "-in", path, "-log", "none", "-nocite"],
                          cwd=workdir, capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"perf record failed\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    run = first_loop(proc.stdout, "perf record")
    loop, nsteps, natoms = run["seconds"], run["steps"], run["atoms"]
    rep = subprocess.run(["perf", "report", "-i", perf_data, "--stdio", "--sort", "symbol",
                          "--percent-limit", "0"], cwd=workdir, capture_output=True, text=True)
    shares = {g: 0.0 for g, _ in GROUPS}
    shares["other"] = 0.0
    top = []
    for line in rep.stdout.splitlines():    # "    12.34%  [.] symbol"
        s = re.match(r"\s*([0-9.]+)%\s+\[[.k]\]\s+(.*)$", line)
        if not s:
            continue
        pct, sym = float(s.group(1)), s.group(2).strip()
        top.append((pct, sym))
        for g, pattern in GROUPS:
            if re.search(pattern, sym):
                shares[g] += pct
                break
        else:
            shares["other"] += pct
    ns = loop / (natoms * nsteps) * 1e9
    return {"loop_s": loop, "ns_per_atom_step": ns, "share_pct": shares,
            "ns_per_atom_step_by_group": {g: ns * v / 100 for g, v in shares.items()},
            "top_symbols": [{"pct": p, "symbol": s[:160]} for p, s in sorted(top)[::-1][:12]]}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", default=pair_speed.DATA)
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--cases", nargs="+", default=["thornton/yin G=0.6", "thornton/yin G=0"],
                    choices=[c for c in pair_speed.CASES if c.startswith("thornton/yin")])
    ap.add_argument("--out", default=os.path.join(pair_speed.REPO, "bench", "results",
                                                  "perf_profile"))
    args = ap.parse_args(argv)
    if args.steps < 1:
        ap.error("--steps must be positive")
    result = {"data": os.path.relpath(os.path.abspath(args.data), pair_speed.REPO),
              "steps": args.steps, "library": os.environ.get("TYLMP_LIBRARY"), "cases": {}}
    with tempfile.TemporaryDirectory() as work:
        for case in args.cases:
            result["cases"][case] = profile(case, os.path.abspath(args.data), args.steps, work)
    write_result(args.out + ".json", result, indent=2)
    groups = [g for g, _ in GROUPS] + ["other"]
    print("| group | " + " | ".join(f"{c}: % / ns per atom-step" for c in args.cases) +
          " |\n|---|" + "---|" * len(args.cases))
    for g in groups:
        cells = [f"{r['share_pct'][g]:.1f} % / {r['ns_per_atom_step_by_group'][g]:.1f}"
                 for r in result["cases"].values()]
        print(f"| {g} | " + " | ".join(cells) + " |")
    print("| whole run | " + " | ".join(f"100 % / {r['ns_per_atom_step']:.1f}"
                                       for r in result["cases"].values()) + " |")
    for case, r in result["cases"].items():
        print(f"\n{case}: top symbols")
        for t in r["top_symbols"]:
            print(f"  {t['pct']:6.2f} %  {t['symbol']}")


if __name__ == "__main__":
    main()
