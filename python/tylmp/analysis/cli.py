"""Command line: tyanalysis <subcommand> ... (the console command of the tylmp package, or
python -m tylmp.analysis); see --help of each subcommand."""
import argparse
import sys

from . import fidelity, io, reproduce
from .commands import further_tests, paper_tests, records
from .commands.common import wrote


def build_parser():
    ap = argparse.ArgumentParser(prog="tyanalysis",
                                 description="Figures and tables for the periodic-cell tests "
                                             "(CSV of fix cell/servo).")
    sub = ap.add_subparsers(dest="command", required=True)
    paper_tests.register(sub)
    further_tests.register(sub)
    records.register(sub)
    p = sub.add_parser("reproduce", help="run the paper's programme (every deck behind the figures "
                       "of docs/validation.md) and draw its figures and summary table",
                       description=reproduce.__doc__.split("\n\n")[0])
    p.add_argument("--scale", choices=("paper", "quick"), default="paper",
                   help="the decks' scale (paper: 3620 spheres, hours; quick: 500, minutes)")
    p.add_argument("--dir", default="paper_runs", help="run directory: records, logs, specimens, "
                   "figures (default paper_runs)")
    p.add_argument("--jobs", type=int, help="runs at once (default: the number of cores)")
    p.add_argument("--inputs", help="directory of the decks (default: the repository's inputs/, "
                   "else the copy installed with tylmp)")
    p.add_argument("--programme", choices=tuple(reproduce.PROGRAMMES), default="paper",
                   help="paper: every run behind the figures of docs/validation.md (default); "
                   "fidelity: the trace study of docs/fidelity.md, one factor at a time, and "
                   "its table (tyanalysis fidelity)")
    p.add_argument("--only", nargs="+", metavar="RUN", help="only these runs (--dry-run lists "
                   "them); paper: " + ", ".join(reproduce.PROGRAMME))
    p.add_argument("--every", type=float, default=300.0,
                   help="seconds between progress lines (300)")
    p.add_argument("--dry-run", action="store_true", help="print the commands, run nothing")
    p.set_defaults(func=cmd_reproduce)
    p = sub.add_parser("fidelity", help="the trace study's table: every response of every factor "
                       "and its shift from the base (records of reproduce --programme fidelity)")
    p.add_argument("dir", help="the run directory of tyanalysis reproduce --programme fidelity")
    p.add_argument("--out", help="also write the table to this markdown file")
    p.set_defaults(func=cmd_fidelity)
    return ap


def cmd_fidelity(a):
    text = fidelity.table(a.dir)
    print(text)
    if a.out:
        io.write_text(a.out, text + "\n")
        wrote(a.out)


def cmd_reproduce(a):
    if a.jobs is not None and a.jobs < 1:
        raise ValueError("--jobs must be at least 1")
    if not a.every > 0:
        raise ValueError("--every must be positive")
    status = reproduce.main(a, draw=main)
    if status:
        raise SystemExit(status)


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except (ValueError, KeyError, OSError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    return 0
