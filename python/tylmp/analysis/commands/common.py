"""What the subcommands share: the records read, the key numbers printed as `label: key=value
...` lines, the legend labels, and the subcommand that reads fix cell/servo records and draws a
figure (files_command)."""
import math
import sys

from .. import io


def formatted(x):
    if x is None:
        return "none"
    if isinstance(x, float) and not math.isfinite(x):
        return "nan"
    return f"{x:.6g}" if isinstance(x, float) else str(x)


def report(label, pairs):
    print(f"{label}: " + " ".join(f"{k}={formatted(v)}" for k, v in pairs))


def legend_labels(files, labels):
    if labels and len(labels) != len(files):
        raise SystemExit(f"error: {len(labels)} labels for {len(files)} files")
    return labels or [io.stem(f) for f in files]


def read_records(files):
    tables = [io.read_servo_csv(f) for f in files]
    for t in tables:
        if t.dropped_partial:
            print(f"note: {t.path}: dropped an incomplete final row", file=sys.stderr)
    return tables


def wrote(out):
    print(f"wrote {out}")


def about(a):
    """(number of spheres, specimen) for the figure's caption (figures.about_text)."""
    return a.n, a.specimen


def files_command(sub, name, func, help_, out=True):
    """A subcommand of fix cell/servo records; with `out`, one that draws a figure."""
    p = sub.add_parser(name, help=help_, description=help_)
    p.add_argument("files", nargs="+", help="fix cell/servo CSV file(s)")
    if out:
        p.add_argument("--out", required=True, help="PNG to write")
        p.add_argument("--labels", nargs="+", help="one legend label per file")
        p.add_argument("--paper", action="store_true",
                       help="draw the paper's values over the records "
                       "(tylmp/analysis/paper.py)")
        p.add_argument("--n", type=int, help="number of spheres, stated under the figure")
        p.add_argument("--specimen", help="the specimen (e.g. dense, loose), stated under "
                                          "the figure")
    p.set_defaults(func=func)
    return p
