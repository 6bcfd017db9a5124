"""Readers for the files written by `fix cell/servo` (CSV) and by `fix print` (two-sphere tables),
and the atomic writer of JSON summaries. A file named *.xz or *.gz is read decompressed (the
committed records of docs/validation/ are NAME.csv.xz).

Both files are append-only and may be read while a run is going or after a crash, so a final
line without its newline (a partially written row) is dropped, as is a final row with the wrong
number of fields or an unparsable number. A damaged row anywhere else is an error.
"""
import gzip
import json
import lzma
import math
import os

import numpy as np

SERVO_COLUMNS = (
    "step", "time", "eps1", "eps2", "eps3", "eps_v", "eps_q", "eps_d13", "sig1", "sig2", "sig3",
    "p", "q", "b", "lode_deg", "eta_LD", "sinphi", "void_ratio", "solid_fraction", "Z", "Zm",
    "sliding_fraction", "unbalanced", "inertial_number", "pi_x", "pi_y", "pi_ex", "pi_ey")


class Table:
    """Named numeric columns of equal length (dict-like), with the source path."""

    def __init__(self, columns, path="", dropped_partial=False):
        self.columns = {k: np.asarray(v, dtype=float) for k, v in columns.items()}
        self.path = str(path)
        self.dropped_partial = dropped_partial
        lengths = {len(v) for v in self.columns.values()}
        if len(lengths) > 1:
            raise ValueError(f"{path}: columns of unequal length {sorted(lengths)}")

    @property
    def name(self):
        return stem(self.path) or "data"

    def __getitem__(self, key):
        try:
            return self.columns[key]
        except KeyError:
            raise KeyError(f"{self.path}: no column {key!r} (have: {', '.join(self.columns)})") from None

    def __contains__(self, key):
        return key in self.columns

    def __len__(self):
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def keys(self):
        return self.columns.keys()

    def require(self, names):
        missing = [n for n in names if n not in self.columns]
        if missing:
            raise ValueError(f"{self.path}: missing column(s) {', '.join(missing)}")
        return self


_OPENERS = {".xz": lzma.open, ".gz": gzip.open}


def stem(path):
    """File name without its directory, compression suffix and extension (a.csv.xz -> a)."""
    base = os.path.basename(str(path))
    root, ext = os.path.splitext(base)
    return os.path.splitext(root)[0] if ext in _OPENERS else root


def find_record(path):
    """path if it exists, else path.xz or path.gz if one does (a compressed record), else None."""
    for p in (path, f"{path}.xz", f"{path}.gz"):
        if os.path.exists(p):
            return p
    return None


def _read_text(path):
    opener = _OPENERS.get(os.path.splitext(str(path))[1], open)
    with opener(path, "rt", encoding="utf-8", errors="replace") as fh:
        return fh.read()


def _parse_row(fields, ncol):
    if len(fields) != ncol:
        raise ValueError(f"{len(fields)} fields, expected {ncol}")
    return [float(f) for f in fields]


def _read_rows(path, header_names, lines, split, complete_last):
    """Parse data lines; drop a damaged or unterminated final line, reject damaged others."""
    ncol = len(header_names)
    rows, dropped = [], False
    data = [(i, ln) for i, ln in lines if ln.strip()]
    for k, (lineno, line) in enumerate(data):
        last = k == len(data) - 1
        if last and not complete_last:
            dropped = True                 # no newline yet: the writer may be mid-row
            break
        try:
            rows.append(_parse_row(split(line), ncol))
        except ValueError as err:
            if last:
                dropped = True
                break
            raise ValueError(f"{path}:{lineno}: bad row ({err}): {line.strip()[:80]!r}") from None
    arr = np.array(rows, dtype=float).reshape(len(rows), ncol)
    return {name: arr[:, j] for j, name in enumerate(header_names)}, dropped


def read_servo_csv(path, require=SERVO_COLUMNS):
    """Read a `fix cell/servo` CSV: first line is the header (a leading '#' is tolerated),
    comma-separated numeric columns. Repeated header lines (restarts) are skipped."""
    text = _read_text(path)
    if not text.strip():
        raise ValueError(f"{path}: empty file")
    complete_last = text.endswith("\n")
    raw = text.split("\n")
    if complete_last:
        raw = raw[:-1]
    header_line = raw[0]
    header = [h.strip() for h in header_line.lstrip("#").split(",")]
    if any(not h for h in header):
        raise ValueError(f"{path}: malformed header {header_line!r}")
    if len(raw) == 1 and not complete_last:
        raise ValueError(f"{path}: header line is incomplete")
    lines = [(i + 2, ln) for i, ln in enumerate(raw[1:])
             if ln.strip() and ln.strip() != header_line.strip()]
    columns, dropped = _read_rows(path, header, lines, lambda s: s.split(","), complete_last)
    table = Table(columns, path, dropped)
    if require:
        table.require(require)
    if len(table) == 0:
        raise ValueError(f"{path}: no complete data rows")
    return table


def read_print_table(path):
    """Read a `fix print` table: '#'-prefixed header line naming the columns, whitespace-
    separated numbers (a comma-separated file with a plain header line is accepted as well)."""
    text = _read_text(path)
    complete_last = text.endswith("\n")
    raw = text.split("\n")
    if complete_last:
        raw = raw[:-1]
    header, lines = None, []
    for i, ln in enumerate(raw):
        s = ln.strip()
        if not s:
            continue
        if s.startswith("#"):
            names = s.lstrip("#").replace(",", " ").split()
            if header is None and names:
                header = names
            continue
        if header is None:                 # plain (CSV-style) header line
            header = s.replace(",", " ").split()
            if all(_is_number(h) for h in header):
                raise ValueError(f"{path}: no header line naming the columns")
            continue
        lines.append((i + 1, ln))
    if header is None:
        raise ValueError(f"{path}: no header line naming the columns")
    columns, dropped = _read_rows(path, header, lines, lambda s: s.replace(",", " ").split(),
                                  complete_last)
    table = Table(columns, path, dropped)
    if len(table) == 0:
        raise ValueError(f"{path}: no complete data rows")
    return table


def _is_number(s):
    try:
        float(s)
        return True
    except ValueError:
        return False


def write_servo_csv(path, columns, partial_tail=None):
    """Write columns in the `fix cell/servo` layout, atomically (write_text); `partial_tail`
    appends an unterminated fragment, as a crashed writer would leave (tests). Returns path."""
    names = list(columns)
    n = len(next(iter(columns.values())))
    lines = [",".join(names)] + [",".join(_fmt(columns[c][i]) for c in names) for i in range(n)]
    write_text(path, "\n".join(lines) + "\n" + (partial_tail or ""))
    return path


def _fmt(v):
    v = float(v)
    if math.isnan(v):
        return "nan"
    return repr(v)


def write_text(path, text):
    """Write text to path atomically (whole to path.tmp, then renamed), as write_json does."""
    tmp = f"{path}.tmp"
    with open(tmp, "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(tmp, path)


def write_json(path, obj, indent=1):
    """Write obj as JSON to path atomically: whole to path.tmp, then renamed (a crash leaves the
    previous file or the new one, never a torn one)."""
    tmp = f"{path}.tmp"
    with open(tmp, "w") as fh:
        json.dump(obj, fh, indent=indent)
    os.replace(tmp, path)


_DATA_SECTIONS = ("Atoms", "Velocities", "Masses", "Ellipsoids", "Lines", "Triangles", "Bodies",
                  "Bonds", "Angles", "Dihedrals", "Impropers", "Pair Coeffs", "PairIJ Coeffs")


def read_sphere_data(path):
    """Box and spheres of a LAMMPS data file with `Atoms # sphere` rows (id type diameter
    density x y z [ix iy iz], as `write_data` and tylmp.specimen write them), orthogonal box:
    (lo (3,), hi (3,), ids (n,), diameters (n,), positions (n, 3)), rows sorted by id."""
    lo, hi = np.zeros(3), np.zeros(3)
    rows, section = [], None
    with open(path, "r", encoding="utf-8") as fh:
        next(fh)                                         # title line
        for line in fh:
            s = line.split("#")[0].strip()
            head = line.strip()
            if any(head.startswith(name) for name in _DATA_SECTIONS):
                section = head.split()[0]
                if section == "Atoms" and "#" in head and head.split("#")[1].strip() != "sphere":
                    raise ValueError(f"{path}: Atoms section is not atom_style sphere: {head!r}")
                continue
            if not s:
                continue
            t = s.split()
            if section is None:
                for a, key in enumerate(("xlo", "ylo", "zlo")):
                    if len(t) >= 4 and t[2] == key:
                        lo[a], hi[a] = float(t[0]), float(t[1])
                if len(t) >= 4 and t[3] == "xy":
                    if any(float(v) != 0.0 for v in t[:3]):
                        raise ValueError(f"{path}: triclinic box (tilt {t[:3]}) is not supported")
            elif section == "Atoms":
                rows.append([float(v) for v in t[:7]])
    if not rows:
        raise ValueError(f"{path}: no Atoms rows")
    a = np.array(rows)
    a = a[np.argsort(a[:, 0])]
    return lo, hi, a[:, 0].astype(np.int64), a[:, 2], a[:, 4:7]
