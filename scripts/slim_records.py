"""The committed copy of a `fix cell/servo` record (docs/validation.md, "How the runs were
made", "Records in the repository"): the columns tyanalysis reads (tyanalysis.io.SERVO_COLUMNS, in the record's order),
xz-compressed, as NAME.csv.xz beside NAME.csv (the tyanalysis readers open .xz transparently).
`step`, `Z` and `Z_m` stay as written; the columns the analysis computes from (PRIMARY) are
rounded to 9 significant digits, the others, which it recomputes from those (metrics.derived)
or only plots, to DIGITS. The full record is what the run writes; the
command that wrote each one is in docs/validation.md and docs/fidelity.md.

    PYTHONPATH=python /usr/bin/python3 scripts/slim_records.py [--digits 4] NAME.csv ...
"""
import argparse
import lzma
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "python"))
from tylmp.analysis import io  # noqa: E402


# Z and Z_m are solved for integer rattler counts (metrics.rattlers_from_z): kept as written
EXACT = ("step", "Z", "Zm")
# the invariants are recomputed from the principal strains and stresses; a test's end
# (eps_d13 = 0.3) is passed by as little as 1e-8; p's deviation from its target is a few Pa;
# the strain rate of a figure's caption is the median of Δε_q/Δt over rows 2.9 s apart
PRIMARY = ("time", "eps1", "eps2", "eps3", "sig1", "sig2", "sig3", "p", "void_ratio",
           "solid_fraction")
PRIMARY_DIGITS = 9


def rounded(text, digits):
    v = float(text)
    if math.isnan(v):
        return "nan"
    return f"{v:.{digits}g}"


def slim(path, digits):
    """Write path.xz (the kept columns, rounded) and return its name."""
    with open(path, encoding="utf-8") as fh:
        lines = fh.read().split("\n")
    header = lines[0].lstrip("#").split(",")
    missing = [c for c in io.SERVO_COLUMNS if c not in header]
    if missing:
        raise SystemExit(f"{path}: not a fix cell/servo record (no {', '.join(missing)})")
    keep = [j for j, name in enumerate(header) if name in io.SERVO_COLUMNS]
    out = [",".join(header[j] for j in keep)]
    for line in lines[1:]:
        if not line or line == lines[0]:            # end, or a repeated header (restart)
            continue
        cells = line.split(",")
        out.append(",".join(
            cells[j] if header[j] in EXACT else
            rounded(cells[j], PRIMARY_DIGITS if header[j] in PRIMARY else digits) for j in keep))
    target = path + ".xz"
    with lzma.open(target + ".tmp", "wt", encoding="utf-8", preset=9 | lzma.PRESET_EXTREME) as fh:
        fh.write("\n".join(out) + "\n")
    os.replace(target + ".tmp", target)
    return target


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("records", nargs="+", help="fix cell/servo CSV records")
    ap.add_argument("--digits", type=int, default=4,
                    help="significant digits of the columns but PRIMARY and EXACT (default 4)")
    a = ap.parse_args(argv)
    for path in a.records:
        print(f"wrote {slim(path, a.digits)}")


if __name__ == "__main__":
    main()
