"""tylmp.analysis (python/tylmp/analysis): invariants against hand calculations, the CSV reader's
tolerance of a partially written last row, and every CLI subcommand run as
`/usr/bin/python3 -m tylmp.analysis ...` on synthetic records whose answers are known in closed form."""
import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from tylmp.analysis import compare, io, metrics
from tylmp.analysis import invariants as inv

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PY = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
P0 = 100e3                      # mean stress, Pa


# ---- synthetic records ----------------------------------------------------------------------------

def record(sig, eps, void_ratio=None, **extra):
    """All fix cell/servo columns from principal stress and strain histories (n, 3)."""
    sig, eps = np.asarray(sig, float), np.asarray(eps, float)
    n = len(sig)
    px, py = inv.pi_coordinates(sig)
    ex, ey = inv.pi_coordinates(eps)
    with np.errstate(invalid="ignore", divide="ignore"):
        cols = {
            "step": np.arange(n) * 100.0, "time": np.arange(n) * 1e-3,
            "eps1": eps[:, 0], "eps2": eps[:, 1], "eps3": eps[:, 2],
            "eps_v": inv.volumetric_strain(eps), "eps_q": inv.deviatoric_strain(eps),
            "eps_d13": eps[:, 0] - eps[:, 2],
            "sig1": sig[:, 0], "sig2": sig[:, 1], "sig3": sig[:, 2],
            "p": inv.mean_stress(sig), "q": inv.deviatoric_stress(sig), "b": inv.b_value(sig),
            "lode_deg": inv.lode_angle_deg(px, py), "eta_LD": inv.lade_duncan_eta(sig),
            "sinphi": inv.sinphi(sig),
            "void_ratio": np.full(n, 0.6) if void_ratio is None else void_ratio,
            "solid_fraction": np.full(n, 0.62), "Z": np.full(n, 5.0), "Zm": np.full(n, 5.5),
            "sliding_fraction": np.zeros(n), "unbalanced": np.full(n, 1e-3),
            "inertial_number": np.full(n, 1e-4),
            "pi_x": px, "pi_y": py, "pi_ex": ex, "pi_ey": ey}
    cols.update(extra)
    assert tuple(cols) == io.SERVO_COLUMNS
    return cols


def axisym_record(kmax, kcv, e0=0.515, e_slope=0.3, n=401):
    """Axisymmetric compression at p = 100 kPa: sig1 = p(1 + 2k), sig2 = sig3 = p(1 - k), so
    q = sig1 - sig3 = 3pk and sin(phi) = 3k/(2 + k). eps1 - eps3 = x runs 0..40 %, k rises
    linearly to kmax at x = 5 %, falls to kcv at 15 % and stays; eps_v = -x/10 (dilation);
    void ratio e0 + e_slope x."""
    x = np.linspace(0.0, 0.40, n)
    k = np.where(x <= 0.05, kmax * x / 0.05,
                 np.where(x < 0.15, kmax + (kcv - kmax) * (x - 0.05) / 0.10, kcv))
    sig = np.stack([P0 * (1 + 2 * k), P0 * (1 - k), P0 * (1 - k)], axis=1)
    ev = -0.1 * x
    eps = np.stack([2 * x / 3 + ev / 3, -x / 3 + ev / 3, -x / 3 + ev / 3], axis=1)
    return record(sig, eps, void_ratio=e0 + e_slope * x,
                  solid_fraction=np.full(n, 1 / (1 + e0)), Z=np.full(n, 6.07), Zm=np.full(n, 6.3))


def sinphi_of_k(k):
    return 3 * k / (2 + k)


def radial_record(b, sinphi_peak, n=201):
    """Constant p and b; sin(phi) rises linearly to sinphi_peak at row n/2 and falls to 80 %;
    strains: eps1 = x, eps2 = (2b - 1) x/2, eps3 = -(1 + b) x/2, plus a growing dilation."""
    t = np.linspace(0, 1, n)
    s = np.where(t <= 0.5, sinphi_peak * t / 0.5, sinphi_peak * (1 - 0.4 * (t - 0.5)))
    state = inv.state_at_ratio(inv.stress_ratio_from_sinphi(s), b)
    sig = state * (P0 / state.mean(axis=1))[:, None]
    x = 0.2 * t
    eps = np.stack([x, (2 * b - 1) * x / 2, -(1 + b) * x / 2], axis=1) - 0.02 * x[:, None] * t[:, None]
    return record(sig, eps)


EPS_Q0 = 0.00285                # prestrain (deviatoric strain eps_q), paper §5
Q0 = 51.4e3                     # deviatoric stress after the prestrain, Pa


def nonradial_record(path="circle", n_pre=30, step_deg=3.0, circle_radius=1.0):
    """Prestrain in axisymmetric compression to eps_q = 0.285 %, q = 51.4 kPa, then the strain
    Lode angle turns (circle of constant radius, or along the plane-strain triangle's first side
    to its vertex at 60 deg); the stress Lode angle turns 79/60 times as fast and q stays
    constant; p = 100 kPa + 0.5 kPa cos(3 theta_e)."""
    r0 = EPS_Q0 / math.sqrt(2 / 3)          # |e| = eps_q / sqrt(2/3)
    rs = Q0 / math.sqrt(1.5)                # |s| = q / sqrt(3/2)
    pre = np.linspace(0.0, 1.0, n_pre)
    if path == "circle":
        th = np.arange(step_deg, 360.0 + 1e-9, step_deg)
        re_ = np.full_like(th, circle_radius * r0)
    else:                                     # side y = r0 from x = 0 to the vertex x = sqrt3 r0
        xs = np.linspace(0.0, math.sqrt(3) * r0, 41)[1:]
        th = np.degrees(np.arctan2(xs, r0))
        re_ = np.hypot(xs, r0)
    theta_e = np.concatenate([np.zeros(n_pre), th])
    rad_e = np.concatenate([pre * r0, re_])
    theta_s = theta_e * 79.0 / 60.0
    rad_s = np.concatenate([pre * rs, np.full_like(th, rs)])
    p = P0 + 500.0 * np.cos(np.radians(3 * theta_e))
    sig = inv.principal_from_pi(*inv.pi_point(rad_s, theta_s), p)
    eps = inv.principal_from_pi(*inv.pi_point(rad_e, theta_e), np.zeros_like(p))
    return record(sig, eps)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("tyanalysis")
    out = {}

    def w(name, cols, **kw):
        io.write_servo_csv(d / name, cols, **kw)
        out[name] = str(d / name)

    w("dense.csv", axisym_record(kmax=0.4, kcv=0.25, e0=0.515, e_slope=0.3))
    w("loose.csv", axisym_record(kmax=0.3, kcv=0.25, e0=0.618, e_slope=-0.02),
      partial_tail="401,0.401,0.1,0.0")      # crashed writer: unterminated last row
    for mu, (kmax, kcv) in {0.1: (0.25, 0.2), 0.3: (0.4, 0.25), 0.5: (0.5, 0.3)}.items():
        w(f"sweep_mu{mu}.csv", axisym_record(kmax, kcv))
    for b in (0.0, 0.5, 1.0):
        w(f"b{b}.csv", radial_record(b, inv.sinphi_on_surface(inv.LADE_DUNCAN, 0.45, b)))
    w("cdst.csv", nonradial_record("circle"))
    w("ps.csv", nonradial_record("triangle"))
    out["dir"] = d
    return out


def run_cli(*args, cwd=None):
    env = dict(os.environ)
    env["MPLBACKEND"] = "Agg"
    r = subprocess.run([PY, "-m", "tylmp.analysis", *map(str, args)], capture_output=True, text=True,
                       env=env, cwd=cwd, timeout=60)
    assert r.returncode == 0, f"{args}\nstdout:\n{r.stdout}\nstderr:\n{r.stderr}"
    return r.stdout


def kv(stdout, label):
    """Parse 'label: k=v k=v' lines of the CLI output."""
    for line in stdout.splitlines():
        if line.startswith(label + ":"):
            out = {}
            for k, v in re.findall(r"(\S+?)=(\S+)", line[len(label) + 1:]):
                try:
                    out[k] = float(v)
                except ValueError:
                    out[k] = v
            return out
    raise AssertionError(f"no line for {label!r} in\n{stdout}")


def png_ok(path):
    assert os.path.exists(path) and os.path.getsize(path) > 1000
    with open(path, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n"


# ---- invariants against hand calculations ---------------------------------------------------------

def test_pi_coordinates_of_2_1_0_and_cpp_convention(repo):
    x, y = inv.pi_coordinates([2.0, 1.0, 0.0])
    assert x == pytest.approx(1 / math.sqrt(2)) and y == pytest.approx(3 / math.sqrt(6))
    assert math.hypot(x, y) == pytest.approx(np.linalg.norm([1.0, 0.0, -1.0]))   # |s|
    assert np.allclose(inv.principal_from_pi(x, y, 1.0), [2, 1, 0])
    assert inv.lode_angle_of([2.0, 1.0, 0.0]) == pytest.approx(30.0)            # b = 0.5
    # same unit vectors as the C++ core
    hpp = os.path.join(repo, "plugin", "core", "pi_plane.hpp")
    if os.path.exists(hpp):
        text = open(hpp).read()
        assert "Eigen::Vector3d(0, 1, -1) / piplane::sqrt2" in text
        assert "Eigen::Vector3d(2, -1, -1) / piplane::sqrt6" in text
    assert np.allclose(inv.PI_UNIT_X, np.array([0, 1, -1]) / math.sqrt(2))
    assert np.allclose(inv.PI_UNIT_Y, np.array([2, -1, -1]) / math.sqrt(6))


def test_lode_angles_of_axisymmetric_states():
    assert inv.lode_angle_of([3.0, 1.0, 1.0]) == pytest.approx(0.0)      # compression along 1
    assert inv.lode_angle_of([2.0, 2.0, 1.0]) == pytest.approx(60.0)     # extension along 3
    assert inv.lode_angle_of([1.0, 3.0, 1.0]) == pytest.approx(120.0)    # compression along 2
    assert inv.lode_angle_of([1.0, 2.0, 2.0]) == pytest.approx(180.0)    # extension along 1
    assert inv.lode_angle_of([1.0, 1.0, 3.0]) == pytest.approx(240.0)    # compression along 3
    assert np.isnan(inv.lode_angle_of([1.0, 1.0, 1.0]))
    for b in (0.0, 0.25, 0.5, 1.0):
        K = 3.0
        assert inv.lode_angle_of(inv.state_at_ratio(K, b)) == pytest.approx(
            math.degrees(math.atan2(math.sqrt(3) * b, 2 - b)))
        assert inv.b_from_lode(inv.lode_from_b(b)) == pytest.approx(b)


def test_axisymmetric_sinphi_q_and_b():
    for k in (0.1, 0.3, 0.5):
        sig = [P0 * (1 + 2 * k), P0 * (1 - k), P0 * (1 - k)]
        assert inv.sinphi(sig) == pytest.approx(3 * k / (2 + k))
        assert inv.deviatoric_stress(sig) == pytest.approx(3 * P0 * k)
        assert inv.mean_stress(sig) == pytest.approx(P0)
        assert inv.b_value(sig) == pytest.approx(0.0)
        assert inv.b_value([P0 * (1 + k), P0 * (1 + k), P0 * (1 - 2 * k)]) == pytest.approx(1.0)
    sig = [150e3, 100e3, 50e3]                       # b = 0.5, sin(phi) = 100/200
    assert inv.b_value(sig) == pytest.approx(0.5)
    assert inv.sinphi(sig) == pytest.approx(0.5)
    assert inv.b_value([50e3, 150e3, 100e3]) == pytest.approx(0.5)     # order of axes irrelevant
    assert inv.deviatoric_strain([0.02, -0.01, -0.01]) == pytest.approx(2 / 3 * 0.03)


def test_lade_duncan_and_matsuoka_nakai_values():
    assert inv.lade_duncan_eta([P0, P0, P0]) == pytest.approx(0.0, abs=1e-12)
    assert inv.matsuoka_nakai_ratio([P0, P0, P0]) == pytest.approx(9.0)
    # sin(phi) = 0.5 -> K = 3: eta = 5^3/3 - 27, MN = 9 + 8 tan^2(phi) = 9 + 8/3
    assert inv.criterion_constant(inv.LADE_DUNCAN, 0.5) == pytest.approx(125 / 3 - 27)
    assert inv.criterion_constant(inv.MATSUOKA_NAKAI, 0.5) == pytest.approx(9 + 8 / 3)
    sig = np.array([3.0, 2.0, 1.0])
    i1, i2, i3 = 6.0, 11.0, 6.0
    assert inv.lade_duncan_eta(sig) == pytest.approx(i1 ** 3 / i3 - 27)
    assert inv.matsuoka_nakai_ratio(sig) == pytest.approx(i1 * i2 / i3)


@pytest.mark.parametrize("s_tc", [0.35, 0.45, 0.5])
def test_failure_surfaces_through_compression_strength(s_tc):
    for crit in inv.CRITERIA:
        assert inv.sinphi_on_surface(crit, s_tc, 0.0) == pytest.approx(s_tc, abs=1e-12)
    # MN: same strength in extension
    assert inv.sinphi_on_surface(inv.MATSUOKA_NAKAI, s_tc, 1.0) == pytest.approx(s_tc, abs=1e-12)
    # LD at b = 1: state (K, K, 1) with (2K + 1)^3/K^2 = (K0 + 2)^3/K0, solved as a cubic
    K0 = (1 + s_tc) / (1 - s_tc)
    c = (K0 + 2) ** 3 / K0
    roots = np.roots([8.0, 12.0 - c, 6.0, 1.0])
    K = max(r.real for r in roots if abs(r.imag) < 1e-9 and r.real > 1)
    assert inv.sinphi_on_surface(inv.LADE_DUNCAN, s_tc, 1.0) == pytest.approx((K - 1) / (K + 1), abs=1e-12)
    assert inv.sinphi_on_surface(inv.LADE_DUNCAN, s_tc, 1.0) > s_tc
    # docs/theory.md §7.3 table
    table = {0.35: (0.4153, 0.3778), 0.45: (0.5346, 0.4946), 0.5: (0.5933, 0.5538)}
    assert inv.sinphi_on_surface(inv.LADE_DUNCAN, s_tc, [0.5, 1.0]) == pytest.approx(table[s_tc], abs=6e-5)
    # Pi-plane curve passes through the compression state at p, and is 120-deg periodic
    p = 100e3
    x, y = inv.failure_surface_pi(inv.LADE_DUNCAN, p=p, sinphi_tc=s_tc, n=361)
    r = np.hypot(x, y)
    state = inv.state_at_ratio(K0, 0.0)
    expect = np.linalg.norm(inv.deviator(state * p / state.mean()))
    assert r[0] == pytest.approx(expect) and r[120] == pytest.approx(expect) and r[240] == pytest.approx(expect)
    assert inv.lode_angle_deg(x[30], y[30]) == pytest.approx(30.0)


def test_peak_plateau_of_a_broad_noisy_peak():
    """R2 of docs/fidelity.md: on q = q0 (1 - ((x - x0)/w)^2) the 1 % plateau is
    x0 -+ 0.1 w exactly (crossings interpolated); for a peak as broad as the dense one
    (w = 15 %: q within 1 % of its maximum from 3.5 to 6.5 %) with fluctuations of +-0.4 % of
    q0 (wavelength 1.5 % strain, random phase) the largest row wanders by more than 1 % strain,
    the midpoint by less than a third of that; a flat
    top from 2 % to 8 % between a linear rise from 0 and a linear fall to 0.6 q0 at 30 % is
    within 1 % from 1.98 % to 8 + 0.01 x 22/0.4 = 8.55 %."""
    x = np.linspace(0.0, 0.3, 3001)
    x0, w, q0 = 0.05, 0.15, 104e3
    q = q0 * (1.0 - ((x - x0) / w) ** 2)
    lo, hi, mid = metrics.peak_plateau(x, q)
    assert (lo, hi) == (pytest.approx(x0 - 0.1 * w, abs=1e-9), pytest.approx(x0 + 0.1 * w, abs=1e-9))
    assert mid == pytest.approx(x0, abs=1e-9)
    rng = np.random.default_rng(3)
    argmax, mids = [], []
    for _ in range(20):
        noisy = q + 0.004 * q0 * np.sin(2 * np.pi * x / 0.015 + rng.uniform(0, 2 * np.pi))
        argmax.append(x[np.argmax(noisy)])
        mids.append(metrics.peak_plateau(x, noisy)[2])
    assert np.ptp(argmax) > 0.01
    assert np.max(np.abs(np.array(mids) - x0)) < np.ptp(argmax) / 3
    flat = np.interp(x, [0.0, 0.02, 0.08, 0.3], [0.0, q0, q0, 0.6 * q0])
    assert metrics.peak_plateau(x, flat) == pytest.approx((0.0198, 0.0855, 0.05265), abs=1e-9)


def test_metrics_of_synthetic_axisymmetric_record():
    t = io.Table(axisym_record(kmax=0.4, kcv=0.25), "x.csv")
    s = metrics.summarize(t)
    assert s["q_peak_kPa"] == pytest.approx(3 * 100 * 0.4)
    assert s["eps_d13_at_q_peak_pct"] == pytest.approx(5.0)
    assert s["sinphi_max"] == pytest.approx(sinphi_of_k(0.4))
    assert s["sinphi_end"] == pytest.approx(sinphi_of_k(0.25))
    assert s["void_ratio_at_30pct"] == pytest.approx(0.515 + 0.3 * 0.3)
    assert max(s["consistency_max"].values()) < 1e-12
    x, rate = metrics.dilation_rate(t["eps_d13"], t["eps_v"])
    assert np.allclose(rate, 0.1)


# ---- reader ------------------------------------------------------------------------------------------

def test_reader_drops_partial_last_row(tmp_path):
    cols = axisym_record(0.4, 0.25, n=21)
    f = tmp_path / "a.csv"
    io.write_servo_csv(f, cols, partial_tail="2100,0.021,0.0012")
    t = io.read_servo_csv(f)
    assert len(t) == 21 and t.dropped_partial
    assert np.allclose(t["sig1"], cols["sig1"])
    # an unterminated row cut mid-number (all fields present) is dropped as well
    line = ",".join(repr(float(cols[c][-1])) for c in cols)
    io.write_servo_csv(f, cols, partial_tail=line[:-3])
    assert len(io.read_servo_csv(f)) == 21
    # a terminated but short final row is dropped; nothing to drop -> flag stays False
    io.write_servo_csv(f, cols, partial_tail="2100,0.021,0.0012\n")
    t = io.read_servo_csv(f)
    assert len(t) == 21 and t.dropped_partial
    io.write_servo_csv(f, cols)
    t = io.read_servo_csv(f)
    assert len(t) == 21 and not t.dropped_partial
    # damage in the middle is an error, as is a header-only file
    text = f.read_text().split("\n")
    text[5] = text[5][:20]
    f.write_text("\n".join(text))
    with pytest.raises(ValueError, match=":6: bad row"):
        io.read_servo_csv(f)
    f.write_text(",".join(cols) + "\n")
    with pytest.raises(ValueError, match="no complete data rows"):
        io.read_servo_csv(f)
    f.write_text("step,time\n1,2\n")
    with pytest.raises(ValueError, match="missing column"):
        io.read_servo_csv(f)



def test_reader_opens_compressed_records(tmp_path):
    """NAME.csv.xz and NAME.csv.gz (the committed records of docs/validation/) read as NAME.csv
    does, under the same name, and a partial last row is dropped as from a plain file."""
    import gzip
    import lzma
    cols = axisym_record(0.4, 0.25, n=21)
    plain = io.write_servo_csv(tmp_path / "a.csv", cols, partial_tail="2100,0.021")
    text = plain.read_text()
    for suffix, opener in ((".xz", lzma.open), (".gz", gzip.open)):
        packed = tmp_path / f"a.csv{suffix}"
        with opener(packed, "wt") as fh:
            fh.write(text)
        t = io.read_servo_csv(packed)
        assert len(t) == 21 and t.dropped_partial and t.name == "a"
        assert np.array_equal(t["sig1"], io.read_servo_csv(plain)["sig1"])
    assert io.find_record(str(tmp_path / "a.csv")) == str(plain)
    plain.unlink()
    assert io.find_record(str(tmp_path / "a.csv")) == str(tmp_path / "a.csv.xz")
    assert io.find_record(str(tmp_path / "b.csv")) is None
    assert io.stem("d/x_mu0.3.csv.xz") == io.stem("x_mu0.3.csv") == "x_mu0.3"

def test_print_table_reader(tmp_path):
    f = tmp_path / "t.txt"
    f.write_text("# t d fx f1x\n0 1e-9 2.0 -2.0\n1e-9 2e-9 3.0 -3.0\n2e-9 3e-9 4")
    t = io.read_print_table(f)
    assert list(t.keys()) == ["t", "d", "fx", "f1x"] and len(t) == 2 and t.dropped_partial
    f.write_text("time,overlap,normal_force\n0,1e-9,2\n1,2e-9,3\n")
    t = io.read_print_table(f)
    assert np.allclose(t["normal_force"], [2, 3]) and not t.dropped_partial


# ---- CLI ------------------------------------------------------------------------------------------------

def test_cli_axisym(files):
    out = os.path.join(files["dir"], "axisym.png")
    so = run_cli("axisym", files["dense.csv"], files["loose.csv"], "--labels", "dense", "loose",
                 "--out", out)
    png_ok(out)
    d, l = kv(so, "dense"), kv(so, "loose")
    assert d["q_peak_kPa"] == pytest.approx(120.0, rel=1e-5)
    assert d["eps_d13_at_q_peak_pct"] == pytest.approx(5.0, rel=1e-5)
    assert d["sinphi_max"] == pytest.approx(sinphi_of_k(0.4), rel=1e-5)
    assert d["sinphi_end"] == pytest.approx(sinphi_of_k(0.25), rel=1e-5)
    assert d["void_ratio_end"] == pytest.approx(0.515 + 0.3 * 0.4, rel=1e-5)
    assert d["void_ratio_at_30pct"] == pytest.approx(0.515 + 0.3 * 0.3, rel=1e-5)
    assert d["eps_v_end_pct"] == pytest.approx(-4.0, rel=1e-5)
    assert l["q_peak_kPa"] == pytest.approx(90.0, rel=1e-5)     # despite the truncated last row
    assert l["void_ratio_at_30pct"] == pytest.approx(0.618 - 0.02 * 0.3, rel=1e-5)
    out2 = os.path.join(files["dir"], "axisym_e.png")
    run_cli("axisym", files["dense.csv"], "--out", out2)
    png_ok(out2)


def test_cli_friction(files):
    out = os.path.join(files["dir"], "friction.png")
    names = [files[f"sweep_mu{m}.csv"] for m in (0.1, 0.3, 0.5)]
    so = run_cli("friction", *names, "--mu", 0.1, 0.3, 0.5, "--out", out)
    png_ok(out)
    for m, (kmax, kcv) in {0.1: (0.25, 0.2), 0.3: (0.4, 0.25), 0.5: (0.5, 0.3)}.items():
        r = kv(so, f"sweep_mu{m}")
        assert r["mu"] == pytest.approx(m)
        assert r["sinphi_max"] == pytest.approx(sinphi_of_k(kmax), rel=1e-5)
        assert r["sinphi_cv"] == pytest.approx(sinphi_of_k(kcv), rel=1e-5)
    run_cli("friction", *names, "--out", out)        # mu from the file names


def test_cli_radial(files):
    out = os.path.join(files["dir"], "radial.png")
    so = run_cli("radial", files["b0.0.csv"], files["b0.5.csv"], files["b1.0.csv"],
                 "--labels", "b0", "b05", "b1", "--out", out)
    png_ok(out)
    s = kv(so, "surfaces")
    assert s["sinphi_tc"] == pytest.approx(0.45, rel=1e-5)
    assert s["eta_LD"] == pytest.approx(10.803, abs=1e-3)           # docs/theory.md §7.3 table
    for lab, b, ld, mn in (("b0", 0, 0.45, 0.45), ("b05", 0.5, 0.5346, 0.5029), ("b1", 1, 0.4946, 0.45)):
        r = kv(so, lab)
        assert r["b"] == pytest.approx(b, abs=1e-9)
        assert r["sinphi_max"] == pytest.approx(ld, abs=6e-5)     # peaks built on the LD surface
        assert r["sinphi_LD"] == pytest.approx(ld, abs=6e-5)
        assert r["sinphi_MN"] == pytest.approx(mn, abs=6e-5)
        assert r["lode_deg"] == pytest.approx(math.degrees(math.atan2(math.sqrt(3) * b, 2 - b)), abs=1e-6)
        assert r["eta_at_peak"] == pytest.approx(s["eta_LD"], rel=1e-5)


def test_cli_pi_plane(files):
    out = os.path.join(files["dir"], "pi.png")
    so = run_cli("pi-plane", files["cdst.csv"], files["ps.csv"], "--labels", "cdst", "ps", "--out", out)
    png_ok(out)
    for lab in ("cdst", "ps"):
        r = kv(so, lab)
        assert r["prestrain_eps_q_pct"] == pytest.approx(0.285, rel=1e-5)
        assert r["prestrain_q_kPa"] == pytest.approx(51.4, rel=1e-5)
        assert r["p_max_kPa"] == pytest.approx(100.5, rel=1e-6)
    assert kv(so, "cdst")["path"] == "circle" and "stress_rotation_deg" not in kv(so, "cdst")
    r = kv(so, "ps")
    assert r["path"] == "triangle"
    # the rotation of the paper's Fig. 9 is a measure of the triangle's first leg
    assert r["stress_rotation_deg"] == pytest.approx(79.0, rel=1e-5)
    assert r["strain_rotation_deg"] == pytest.approx(60.0, rel=1e-5)
    out2 = os.path.join(files["dir"], "pi2.png")
    run_cli("pi-plane", files["b0.5.csv"], "--guide", "both", "--strain-radius", 0.01,
            "--sinphi-tc", 0.45, "--out", out2)
    png_ok(out2)


def test_nonradial_measures_direct(files):
    t = io.read_servo_csv(files["ps.csv"])
    i0 = compare.prestrain_end(t)
    assert i0 == 29
    rot = compare.stress_rotation(t)
    assert rot == pytest.approx((79.0, 60.0))
    # the triangle guide starts at the prestrain radius, vertices at twice that radius
    x, y = inv.plane_strain_triangle_pi(1.0)
    assert np.allclose(y[[0, 2]], 1.0) and np.allclose(np.hypot(x, y), 2.0)


def test_cli_table_and_compare(files):
    res = os.path.join(files["dir"], "ours.json")
    with open(res, "w") as fh:
        json.dump({"solid_fraction_dense": 0.652, "solid_fraction_loose": 0.62,
                   "b_at_max_sinphi": 0.5, "extra_thing": 1.25}, fh)
    md = os.path.join(files["dir"], "table.md")
    so = run_cli("table", res, "--out", md)
    assert "| quantity | paper | ours | difference | band | inside | source |" in so
    # bands of the issue: solid fraction 0.660 ± 0.005, 0.618 ± 0.005; b 0.4-0.6
    assert "| solid_fraction_dense | 0.66 | 0.652 | -0.008 (-1.2 %) | 0.655–0.665 | no |" in so
    assert "| solid_fraction_loose | 0.618 | 0.62 | +0.002 (+0.3 %) | 0.613–0.623 | yes |" in so
    assert "| b_at_max_sinphi | 0.5 | 0.5 | +0 (+0.0 %) | 0.4–0.6 | yes |" in so
    assert "| extra_thing | — | 1.25 | — | — | — |" in so
    assert "| coordination_loose | 5.02 | — | — | 4.82–5.22 | — |" in so
    assert os.path.getsize(md) > 0
    so = run_cli("compare", "--dense", files["dense.csv"], "--loose", files["loose.csv"],
                 "--radial", files["b0.0.csv"], files["b0.5.csv"], files["b1.0.csv"],
                 "--radial-loose", files["b0.5.csv"], files["b1.0.csv"],
                 "--cdst", files["cdst.csv"], "--plane-strain", files["ps.csv"])
    rows = {r.split("|")[1].strip().split(" [")[0]: [c.strip() for c in r.split("|")[1:-1]]
            for r in so.splitlines() if r.startswith("| ") and not r.startswith("| quantity")}
    assert float(rows["coordination_dense"][2]) == pytest.approx(6.3)     # Zm (docs/fidelity.md)
    assert float(rows["Z_all_spheres_dense"][2]) == pytest.approx(6.07)
    assert float(rows["void_ratio_30pct_dense"][2]) == pytest.approx(0.515 + 0.09, rel=1e-3)
    # the synthetic q rises linearly to its peak at 5 % and falls by (kmax - kcv)/kmax of it
    # over the next 10 %: it is within 1 % of the peak from 4.95 % to 5 % + 10 % x 0.01 kmax /
    # (kmax - kcv); the dense peak is that range's midpoint, the loose "levels off" its start
    hi = 5.0 + 10.0 * 0.01 * 0.4 / (0.4 - 0.25)
    assert float(rows["eps_d13_at_peak_dense_pct"][2]) == pytest.approx((4.95 + hi) / 2, rel=1e-3)
    assert rows["eps_d13_at_peak_dense_pct"][5] == "yes"                  # band 3-7 %
    assert float(rows["eps_d13_steady_loose_pct"][2]) == pytest.approx(4.95, rel=1e-3)
    assert rows["eps_d13_steady_loose_pct"][5] == "no"                    # band 10-20 %
    assert float(rows["b_at_max_sinphi"][2]) == pytest.approx(0.5)
    # Lade-Duncan at eta = 0.45: sinphi_max(b = 1) = 0.4946 against the dense axisymmetric
    # record's 3k/(2 + k) = 0.5 at k = 0.4 (--dense is the b = 0 of the radial set)
    ext = inv.sinphi_on_surface(inv.LADE_DUNCAN, 0.45, 1.0) - 0.5
    assert float(rows["extension_minus_compression_dense"][2]) == pytest.approx(ext, abs=1e-3)
    assert rows["extension_minus_compression_dense"][4:6] == ["> 0", "no"]
    # loose: its axisymmetric record, k = 0.3, sinphi_max = 0.9/2.3, is the b = 0
    ext = inv.sinphi_on_surface(inv.LADE_DUNCAN, 0.45, 1.0) - 0.9 / 2.3
    assert float(rows["extension_minus_compression_loose"][2]) == pytest.approx(ext, abs=1e-3)
    assert rows["extension_minus_compression_loose"][5] == "yes"
    assert float(rows["b_at_max_sinphi_loose"][2]) == pytest.approx(0.5)
    assert float(rows["prestrain_q_kPa"][2]) == pytest.approx(51.4, rel=1e-3)
    assert rows["prestrain_q_kPa"][5] == "yes"
    assert float(rows["prestrain_eps_d_pct"][2]) == pytest.approx(0.285, rel=1e-3)
    assert float(rows["cdst_p_deviation_kPa"][2]) == pytest.approx(0.5, rel=1e-3)
    assert float(rows["ps_stress_rotation_deg"][2]) == pytest.approx(79.0, rel=1e-3)
    assert rows["ps_stress_rotation_deg"][5] == "yes"


def test_cli_summary(files):
    so = run_cli("summary", files["dense.csv"], files["loose.csv"])
    lines = [json.loads(x) for x in so.strip().splitlines()]
    assert len(lines) == 2
    d, l = lines
    assert d["sinphi_max"] == pytest.approx(sinphi_of_k(0.4))
    assert d["q_peak_kPa"] == pytest.approx(120.0)
    assert d["solid_fraction_start"] == pytest.approx(1 / 1.515)
    assert l["rows"] == 401 and l["dropped_partial_row"] is True
    assert max(d["consistency_max"].values()) < 1e-9


def test_cli_two_spheres(files):
    E, nu, R = 70e9, 0.3, 1e-4
    estar, rstar = E / (2 * (1 - nu ** 2)), R / 2
    d = np.linspace(0, 2e-8, 50)
    f = 4 / 3 * estar * math.sqrt(rstar) * d ** 1.5
    tab = os.path.join(files["dir"], "two.txt")
    with open(tab, "w") as fh:
        fh.write("# t d fx f1x\n")
        for i in range(len(d)):
            fh.write(f"{i * 1e-9:.9e} {d[i]!r} {f[i]!r} {-f[i]!r}\n")
        fh.write("5e-8 2.1e-8")                  # partial last line
    out = os.path.join(files["dir"], "two.png")
    so = run_cli("two-spheres", tab, "--out", out, "--E", E, "--nu", nu, "--radius", R)
    png_ok(out)
    r = kv(so, "two")
    assert r["rows"] == 50 and r["x"] == "d" and r["y"] == "fx"
    assert r["force_max"] == pytest.approx(f[-1], rel=1e-5)
    assert r["hertz_max_rel_dev"] < 1e-9
    # CSV form of inputs/two_spheres.in, with JKR curves
    csv = os.path.join(files["dir"], "two_spheres.csv")
    with open(csv, "w") as fh:
        fh.write("time,overlap,normal_force\n")
        for i in range(len(d)):
            fh.write(f"{i * 1e-9:.9e},{d[i]!r},{f[i] - 1e-4!r}\n")
    so = run_cli("two-spheres", csv, "--out", out, "--E", E, "--radius", R, "--gamma", 0.3)
    r = kv(so, "two_spheres")
    assert r["force_min"] == pytest.approx(-1e-4, rel=1e-6)
    assert r["pull_off_theory"] == pytest.approx(3 * math.pi * 0.3 * rstar, rel=1e-5)


def test_cli_isotropic_record_does_not_break(tmp_path):
    # isotropic compaction: q = 0, b and Lode angle undefined (NaN in the CSV)
    n = 20
    sig = np.full((n, 3), P0) * np.linspace(0.5, 1.0, n)[:, None]
    eps = np.full((n, 3), 1e-3) * np.linspace(0, 1, n)[:, None]
    f = tmp_path / "iso.csv"
    io.write_servo_csv(f, record(sig, eps))
    so = run_cli("summary", f)
    s = json.loads(so)
    assert s["sinphi_max"] == pytest.approx(0.0, abs=1e-12) and s["q_peak_kPa"] == pytest.approx(0.0, abs=1e-9)
    out = tmp_path / "iso.png"
    so = run_cli("pi-plane", f, "--out", out)
    png_ok(out)
    assert "prestrain_row" not in so


def test_curve_spread_measures_horizontal_distance_of_curves():
    # y = x and y = 1.1 x reach every level y0 at x = y0 and y0/1.1: spread (1 - 1/1.1)/mean
    from tylmp.analysis import metrics
    x = np.linspace(0.0, 10.0, 1001)
    spread = metrics.curve_spread([(x, x), (x, 1.1 * x)], np.linspace(1.0, 7.0, 13))
    assert spread == pytest.approx((1 - 1 / 1.1) / ((1 + 1 / 1.1) / 2), rel=1e-9)
    # identical curves do not spread; a level one curve never reaches is skipped
    assert metrics.curve_spread([(x, x), (x, x)], [1.0, 5.0]) == 0.0
    assert metrics.curve_spread([(x, x), (x, 0.1 * x)], [5.0]) is None


# ---- definitions of the pre-strain amplitude (docs/fidelity.md "Definitions") -----------------------

G_SEC = 20e6                      # synthetic secant stiffness: q = G_SEC (eps1 - eps3), Pa


def linear_axisym_record(d13_end=0.01, n=201):
    """Axisymmetric compression at p = 100 kPa with q = sig1 - sig3 = G_SEC d, d = eps1 - eps3,
    and a dilation eps_v = -d/5 (which must not enter any deviatoric measure)."""
    d = np.linspace(0.0, d13_end, n)
    q = G_SEC * d
    sig = np.stack([P0 + 2 * q / 3, P0 - q / 3, P0 - q / 3], axis=1)
    ev = -0.2 * d
    eps = np.stack([2 * d / 3 + ev / 3, -d / 3 + ev / 3, -d / 3 + ev / 3], axis=1)
    return record(sig, eps)


def test_strain_measures_in_axisymmetric_compression():
    """Closed forms for e = (d/3)(2, -1, -1): eps_q = 2d/3, |e| = sqrt(2/3) d,
    gamma_oct = (2/3) sqrt((e1-e2)^2 + (e2-e3)^2 + (e3-e1)^2) = (2 sqrt2 / 3) d."""
    d = 0.003
    eps = np.array([[2 * d / 3 + 1e-3, -d / 3 + 1e-3, -d / 3 + 1e-3]])
    closed = {"eps_d13": d, "eps_q": 2 * d / 3, "pi_radius": math.sqrt(2 / 3) * d,
              "gamma_oct": 2 / 3 * math.sqrt(d ** 2 + 0 + d ** 2)}
    for key, (_, f, factor) in metrics.STRAIN_MEASURES.items():
        assert float(f(eps)[0]) == pytest.approx(closed[key], rel=1e-12)
        assert factor * d == pytest.approx(closed[key], rel=1e-12)


def test_q_at_prestrain_amplitude_each_measure(tmp_path):
    f = tmp_path / "lin.csv"
    io.write_servo_csv(f, linear_axisym_record())
    t = io.read_servo_csv(str(f))
    a = 0.00285
    rows = {k: (d13, q) for k, _, d13, q in metrics.prestrain_readings(t, a)}
    # the amplitude a in measure m is reached at d = a / (m per unit d), where q = G_SEC d
    for key, d_needed in {"eps_d13": a, "eps_q": 1.5 * a, "pi_radius": a / math.sqrt(2 / 3),
                          "gamma_oct": a * 3 / (2 * math.sqrt(2))}.items():
        assert rows[key][0] == pytest.approx(d_needed, rel=1e-12)
        assert rows[key][1] == pytest.approx(G_SEC * d_needed, rel=1e-9)
    assert metrics.strain_at_q(t, 51.4e3) == pytest.approx(51.4e3 / G_SEC, rel=1e-9)
    assert metrics.q_at_amplitude(t, 0.02, "eps_d13") == (None, None)      # beyond the record
    so = run_cli("prestrain", str(f))
    r = kv(so, "lin eps_q")
    assert r["q_kPa"] == pytest.approx(G_SEC * 1.5 * a * 1e-3, rel=1e-5)
    assert r["vs_paper_pct"] == pytest.approx(100 * (G_SEC * 1.5 * a / 51.4e3 - 1), rel=1e-5)
    s = kv(so, "lin stress measures at eps_d13")
    assert s["sqrt_J2_kPa"] == pytest.approx(G_SEC * a * 1e-3 / math.sqrt(3), rel=1e-5)
    assert s["tau_oct_kPa"] == pytest.approx(G_SEC * a * 1e-3 * math.sqrt(2) / 3, rel=1e-5)


def test_prestrain_end_is_the_last_row_on_the_leg():
    """A circle whose first row has turned only 0.8 deg (the paper-scale CSV interval) still
    starts after the prestrain: that row must not be taken as its end."""
    t = io.Table({k: np.asarray(v, float) for k, v in
                  nonradial_record("circle", n_pre=30, step_deg=0.8).items()})
    i0 = compare.prestrain_end(t)
    assert i0 == 29
    assert metrics.derived(t)["q"][i0] == pytest.approx(Q0, rel=1e-9)


# ---- coordination numbers (docs/fidelity.md "Coordination") ---------------------------------------

def lattice_with_rattlers(m=4, a=1e-3):
    """Simple cubic lattice of m^3 spheres of diameter a (1 + 1e-6) (six contacts each, across
    the periodic faces too), plus a sphere of radius 0.2 a at a cube centre (no contact: the
    corners are sqrt(3) a / 2 away) and one of radius 0.2 a displaced 0.2 a from another cube
    centre towards one corner (one contact: 0.666 a < 0.7 a; the next corners are 0.821 a away)."""
    g = (np.arange(m) + 0.25) * a
    lat = np.array([[x, y, z] for x in g for y in g for z in g])
    centre = lat[0] + 0.5 * a
    toward = lat[0] + 1.5 * a + 0.2 * a * np.ones(3) / math.sqrt(3)    # towards lattice point (2,2,2)
    pos = np.vstack([lat, centre, toward])
    diam = np.concatenate([np.full(m ** 3, a * (1 + 1e-6)), [0.4 * a, 0.4 * a]])
    return np.full(3, m * a), diam, pos


def test_coordination_closed_form():
    box, diam, pos = lattice_with_rattlers()
    i, j, overlap = metrics.contacts(box, diam, pos)
    c = metrics.coordination(metrics.counts_per_sphere(i, j, len(diam)))
    # 64 lattice spheres x 6 / 2 = 192 contacts, plus the single contact of the last sphere
    assert (c["N"], c["C"], c["N0"], c["N1"]) == (66, 193, 1, 1)
    assert c["Z"] == pytest.approx(2 * 193 / 66, rel=1e-15)
    assert c["Zm"] == pytest.approx((2 * 193 - 1) / (66 - 1 - 1), rel=1e-15)
    single = (i == 65) | (j == 65)
    assert np.allclose(overlap[~single], 1 - 1 / (1 + 1e-6), rtol=1e-6)
    dist, sumr = (math.sqrt(3) / 2 - 0.2), 0.5 * (1 + 1e-6) + 0.2
    assert overlap[single] == pytest.approx(1 - dist / sumr, rel=1e-9)
    # the same with the spheres shifted by a box length (positions outside [0, L))
    i2, _, _ = metrics.contacts(box, diam, pos + box * np.array([1, -1, 2]))
    assert len(i2) == 193


def test_cli_coordination(tmp_path):
    box, diam, pos = lattice_with_rattlers()
    f = tmp_path / "lattice.data"
    lines = ["LAMMPS data file", "", f"{len(diam)} atoms", "1 atom types", "",
             f"-1e-3 {box[0] - 1e-3!r} xlo xhi", f"0 {box[1]!r} ylo yhi", f"0 {box[2]!r} zlo zhi", "",
             "Atoms # sphere", ""]
    lines += [f"{k + 1} 1 {diam[k]!r} 2650 {pos[k, 0] - 1e-3!r} {pos[k, 1]!r} {pos[k, 2]!r} 0 0 0"
              for k in range(len(diam))]
    lines += ["", "Velocities", ""] + [f"{k + 1} 0 0 0 0 0 0" for k in range(len(diam))]
    f.write_text("\n".join(lines) + "\n")
    r = kv(run_cli("coordination", str(f)), "lattice")
    assert (r["N"], r["C"], r["N0"], r["N1"]) == (66, 193, 1, 1)
    assert r["Zm"] == pytest.approx(385 / 64, rel=1e-5)
    vol = math.pi / 6 * float(np.sum(diam ** 3))
    assert r["solid_fraction"] == pytest.approx(vol / float(np.prod(box)), rel=1e-5)


def test_rattlers_recovered_from_recorded_z_and_zm(tmp_path):
    """A record keeps Z and Zm to 12 digits; for N = 3620, 2C = 13596, N0 = 721, N1 = 3 the
    integers follow back uniquely (the same for the small lattice)."""
    n, two_c, n0, n1 = 3620, 13596, 721, 3
    z, zm = float(f"{two_c / n:.12g}"), float(f"{(two_c - n1) / (n - n0 - n1):.12g}")
    assert metrics.rattlers_from_z(n, z, zm) == [(n0, n1)]
    assert metrics.rattlers_from_z(66, 386 / 66, 385 / 64) == [(1, 1)]
    cols = axisym_record(0.4, 0.25, n=11)
    cols["Z"], cols["Zm"] = np.full(11, z), np.full(11, zm)
    f = tmp_path / "prep.csv"
    io.write_servo_csv(f, cols)
    r = kv(run_cli("coordination", str(f)), "prep")
    assert r["N0_N1"] == "721,3" and r["N"] == 3620


# ---- figures: the paper's values, labels, guides ----------------------------------------------

@pytest.fixture
def drawn(monkeypatch):
    """Run the CLI in this process and keep, for every figure it saves, its axes' legend
    entries (label -> x, y data), titles and whether every axis label lies inside the figure."""
    def keep(fig):
        fig.tight_layout()
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        box = fig.bbox
        axes = []
        for ax in fig.axes:
            lines = {ln.get_label(): (np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float))
                     for ln in ax.get_lines() if not ln.get_label().startswith("_")}
            labels_inside = all(
                t.get_text() == "" or (lambda e: e.x0 >= box.x0 - 1 and e.x1 <= box.x1 + 1
                                       and e.y0 >= box.y0 - 1 and e.y1 <= box.y1 + 1)(t.get_window_extent(renderer))
                for t in (ax.xaxis.label, ax.yaxis.label))
            legend = ax.get_legend()
            axes.append({"title": ax.get_title(), "lines": lines, "labels_inside": labels_inside,
                         "legend": [t.get_text() for t in legend.get_texts()] if legend else []})
        return axes

    return capture_figures(monkeypatch, keep)


def capture_figures(monkeypatch, describe):
    """A function running the CLI in this process that returns describe(fig) of the last figure
    it saved (describe may lay the figure out)."""
    from tylmp.analysis import cli, figures
    kept = []
    save = figures.save_figure

    def keep(fig, out, dpi=120):
        kept.append(describe(fig))
        return save(fig, out, dpi)

    monkeypatch.setattr(figures, "save_figure", keep)

    def run(*args):
        assert cli.main([str(a) for a in args]) == 0
        return kept[-1]
    return run


def _axes(fig, title_part):
    (ax,) = [a for a in fig if title_part in a["title"]]
    return ax


def _paper_line(ax, text):
    (hit,) = [v for k, v in ax["lines"].items() if k.startswith("paper") and text in k]
    return hit


def test_axisym_figure_carries_the_papers_void_ratios(files, drawn, tmp_path):
    fig = drawn("axisym", files["dense.csv"], files["loose.csv"], "--paper", "--out",
                tmp_path / "a.png")
    e = _axes(fig, "Void ratio (Fig. 2)")
    # §3: 0.598 dense, 0.606 loose at 30 %; §2: start e = 1/0.660 - 1, 1/0.618 - 1
    for text, x, y in (("dense at 30 %", 30.0, 0.598), ("loose at 30 %", 30.0, 0.606),
                       ("dense start", 0.0, 1 / 0.660 - 1), ("loose start", 0.0, 1 / 0.618 - 1)):
        xs, ys = _paper_line(e, text)
        assert (xs[0], ys[0]) == pytest.approx((x, y))
    xs, _ = _paper_line(_axes(fig, "Fig. 1"), "peak at about 5 %")
    assert np.all(xs == 5.0)
    assert all(ax["labels_inside"] for ax in fig)


def test_radial_figure_labels_by_b_in_order_and_explains_the_surfaces(files, drawn, tmp_path):
    fig = drawn("radial", files["b1.0.csv"], files["b0.0.csv"], files["b0.5.csv"],
                "--paper", "--out", tmp_path / "r.png")
    # the records' own b, in increasing order, whatever the order of the files
    assert _axes(fig, "Mobilised")["legend"] == ["b = 0", "b = 0.5", "b = 1"]
    pi = _axes(fig, "Fig. 4")
    # through sin(phi_TC) = 0.45 (b = 0): K = (1 + s)/(1 - s), LD eta = (K + 2)^3/K - 27,
    # MN I1 I2/I3 = (K + 2)(2K + 1)/K
    K = 1.45 / 0.55
    eta, mn = (K + 2) ** 3 / K - 27, (K + 2) * (2 * K + 1) / K
    ld_label = [t for t in pi["legend"] if t.startswith("Lade–Duncan")]
    mn_label = [t for t in pi["legend"] if t.startswith("Matsuoka–Nakai")]
    assert ld_label and f"η = I1³/I3 − 27 = {eta:.3g}" in ld_label[0] and "0.450" in ld_label[0]
    assert mn_label and f"I1·I2/I3 = {mn:.4g}" in mn_label[0]
    # §4, Fig. 5: the eta curves coincide below eta = 7
    _, ys = _paper_line(_axes(fig, "Fig. 5"), "η < 7")
    assert np.all(ys == 7.0)
    # §4: strongest near b = 0.5, Lode angle 30 deg
    xs, ys = _paper_line(pi, "b = 0.5")
    assert math.degrees(math.atan2(xs[-1], ys[-1])) == pytest.approx(30.0)
    assert all(ax["labels_inside"] for ax in fig)


def test_pi_plane_figure_carries_the_papers_prestrain_and_rotation(files, drawn, tmp_path):
    fig = drawn("pi-plane", files["ps.csv"], "--labels", "ps", "--paper", "--out",
                tmp_path / "p.png")
    stress = _axes(fig, "stress path")
    xs, ys = _paper_line(stress, "51.4 kPa")
    # Pi radius of q = 51.4 kPa in axisymmetric compression: sqrt(2/3) q, on axis 1
    assert (xs[0], ys[0]) == pytest.approx((0.0, math.sqrt(2 / 3) * 51.4))
    xs, ys = _paper_line(stress, "79°")
    assert math.degrees(math.atan2(xs[-1], ys[-1])) == pytest.approx(79.0)
    assert all(ax["labels_inside"] for ax in fig)


def test_pi_plane_guides_only_for_the_path_followed(files, drawn, tmp_path):
    """A circle off the prestrain radius (a user's path) gets its circle, no triangle and no
    rotation; the paper's triangle gets its triangle."""
    path = tmp_path / "user_circle.csv"
    io.write_servo_csv(path, nonradial_record("circle", circle_radius=1.5))
    fig = drawn("pi-plane", path, "--out", tmp_path / "c.png")
    strain = _axes(fig, "strain path")
    guides = [k for k in strain["lines"] if ": circle" in k or ": plane-strain" in k]
    r0 = EPS_Q0 / math.sqrt(2 / 3)
    assert guides == [f"user_circle: circle r = {100 * 1.5 * r0:.3g} %"]
    xs, ys = strain["lines"][guides[0]]
    assert np.allclose(np.hypot(xs, ys), 100 * 1.5 * r0)
    assert not any("79°" in k for k in _axes(fig, "stress path")["lines"])
    so = run_cli("pi-plane", path, "--out", tmp_path / "c2.png")
    assert kv(so, "user_circle")["path"] == "circle" and "stress_rotation_deg" not in so
    fig = drawn("pi-plane", files["ps.csv"], "--labels", "ps", "--out", tmp_path / "t.png")
    assert [k for k in _axes(fig, "strain path")["lines"] if ": circle" in k or ": plane-strain" in k] \
        == ["ps: plane-strain triangle"]


def test_axisym_figure_labels_records_by_their_parameter(files, drawn, tmp_path):
    """Records named by mu are labelled 'μ = ...' and drawn in increasing mu."""
    names = [files[f"sweep_mu{m}.csv"] for m in (0.5, 0.1, 0.3)]
    fig = drawn("axisym", *names, "--out", tmp_path / "mu.png")
    curves = [k for k in _axes(fig, "Fig. 1")["lines"] if not k.startswith("paper")]
    assert curves == ["μ = 0.1", "μ = 0.3", "μ = 0.5"]


def test_resumed_preparation_keeps_the_log_of_the_first(tmp_path):
    """A resumed reproduce call runs each preparation again, which only finds its cached
    specimen; its LAMMPS log goes to a free name, not over the log of the run that prepared it."""
    from tylmp.analysis import reproduce
    specimen = ("dense", (("seed", "2"),))
    first = reproduce.prepare_command(specimen, "paper", "inputs", str(tmp_path))
    assert first[first.index("-log") + 1] == "prepare_dense_seed2.log"
    (tmp_path / "prepare_dense_seed2.log").write_text("the preparation\n")
    (tmp_path / "prepare_dense_seed2.1.log").write_text("a first resumed call\n")
    again = reproduce.prepare_command(specimen, "paper", "inputs", str(tmp_path))
    assert again[again.index("-log") + 1] == "prepare_dense_seed2.2.log"
    assert again[:again.index("-log")] == first[:first.index("-log")]


def test_fidelity_table_shifts_from_the_base(tmp_path, capsys):
    """tyanalysis fidelity: each factor's responses and their shifts from the base, from the
    records named as reproduce --programme fidelity names them. Synthetic axisymmetric
    records: void ratio e0 + 0.3 x, so e at 30 % is e0 + 0.09; solid fraction 1/(1 + e0)."""
    from tylmp.analysis import fidelity, reproduce
    prog = reproduce.PROGRAMMES["fidelity"]
    for factor, e0 in (("base", 0.515), ("seed2", 0.525), ("rate_1e-5", 0.505)):
        name = fidelity.run_name(factor, "axisym_dense")
        io.write_servo_csv(tmp_path / reproduce.record_name(name, prog),
                           axisym_record(kmax=0.4, kcv=0.25, e0=e0, e_slope=0.3))
    # a record of the paper programme in the same directory is not a factor's
    io.write_servo_csv(tmp_path / reproduce.record_name("axisym_dense"),
                       axisym_record(kmax=0.4, kcv=0.25, e0=0.495, e_slope=0.3))
    text = fidelity.table(str(tmp_path))
    rows = {r.split("|")[1].strip().split(":")[0]: [c.strip() for c in r.split("|")[2:-1]]
            for r in text.splitlines()[2:]}
    head = [c.strip() for c in text.splitlines()[0].split("|")[2:-1]]
    e30 = head.index("R4 e at 30 %, dense")
    phi = head.index("R1 dense φ")
    assert set(rows) == {"base", "seed2", "rate_1e-5"}
    assert float(rows["rate_1e-5"][e30].split()[1].strip("()")) == pytest.approx(-0.010, rel=1e-2)
    assert float(rows["base"][e30]) == pytest.approx(0.515 + 0.09, rel=1e-3)
    value, shift = rows["seed2"][e30].split()
    assert float(value) == pytest.approx(0.525 + 0.09, rel=1e-3)
    assert float(shift.strip("()")) == pytest.approx(0.010, rel=1e-2)
    value, shift = rows["seed2"][phi].split()
    assert float(shift.strip("()")) == pytest.approx(1 / 1.525 - 1 / 1.515, rel=1e-2)
    # no record of a response, no column: the loose runs are missing
    assert "R4 e at 30 %, loose" not in head
    # the runs of the programme: every factor's runs, each with its preparation variables
    assert prog["seed2_axisym_loose"][4] == {"seed": "2"}
    assert prog["n8000_axisym_dense"][1]["strain"] == "0.80"
    assert "n8000_plane_strain_cw" not in prog and "hold_undamped_axisym_dense" not in prog
    # a directory without the study's records, or none at all: an error that says so
    empty = tmp_path / "empty"
    empty.mkdir()
    from tylmp.analysis import cli
    for d, message in ((empty, "no record of tyanalysis reproduce --programme fidelity"),
                       (tmp_path / "missing", "no such directory")):
        assert cli.main(["fidelity", str(d)]) == 2
        assert message in capsys.readouterr().err
    cmd = reproduce.command("seed2_axisym_loose", "paper", "inputs", prog)
    assert cmd[cmd.index("seed") + 1] == "2" and cmd[cmd.index("specimen") + 1] == "loose"


# ---- figures for a user's runs (issue 31 item 5) ------------------------------------------------

@pytest.fixture
def figure(monkeypatch):
    """Run the CLI in this process and keep the last figure it saves (its texts, and for each
    axes its title, y label and limits, line styles and legend)."""
    def keep(fig):
        axes = []
        for ax in fig.axes:
            legend = ax.get_legend()
            axes.append({"title": ax.get_title(), "ylabel": ax.get_ylabel(),
                         "xlabel": ax.get_xlabel(), "ylim": ax.get_ylim(),
                         "lines": {ln.get_label(): ln for ln in ax.get_lines()},
                         "legend": [t.get_text() for t in legend.get_texts()] if legend else []})
        return {"texts": [t.get_text() for t in fig.texts], "axes": axes}

    return capture_figures(monkeypatch, keep)


def _ax(fig, title_part):
    (ax,) = [a for a in fig["axes"] if title_part in a["title"]]
    return ax


@pytest.mark.parametrize("command,names", [
    ("axisym", ["dense.csv", "loose.csv"]), ("radial", ["b0.0.csv", "b0.5.csv", "b1.0.csv"]),
    ("pi-plane", ["ps.csv"]), ("friction", ["sweep_mu0.1.csv", "sweep_mu0.3.csv"])])
def test_paper_values_are_drawn_only_with_paper(files, figure, tmp_path, command, names):
    """A user's records get no overlay of the paper's numbers unless --paper asks for it."""
    paths = [files[n] for n in names]
    for flag, expected in (([], False), (["--paper"], True)):
        fig = figure(command, *paths, *flag, "--out", tmp_path / "f.png")
        drawn = [k for a in fig["axes"] for k in a["lines"] if k.startswith("paper")] + \
            [t for a in fig["axes"] for t in a["legend"] if t.startswith("paper")]
        if command == "friction":      # the paper gives no numbers for Fig. 3, only a note
            drawn = [t for t in fig["texts"] if "paper" in t]
            drawn += [1] if expected and not drawn else []
        assert bool(drawn) == expected, (command, flag, drawn)


def test_pq_plot_draws_the_critical_state_line(files, figure, tmp_path):
    """q = √(3J2) against p, and the critical-state line q = M p with M the mean q/p of the last
    10 % of the rows: 3 kcv for the synthetic axisymmetric records (q = 3pk)."""
    fig = figure("pq", files["dense.csv"], files["sweep_mu0.5.csv"], "--out", tmp_path / "pq.png")
    ax = _ax(fig, "p–q")
    (line,) = [ln for k, ln in ax["lines"].items() if k.startswith("critical state")]
    x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
    M = np.mean([3 * 0.25, 3 * 0.3])        # kcv of the two records
    assert y[-1] / x[-1] == pytest.approx(M, rel=1e-9) and y[0] == 0
    assert ax["ylabel"].startswith("q = √(3J2)")
    so = run_cli("pq", files["dense.csv"], "--out", tmp_path / "pq2.png")
    assert kv(so, "dense")["M_critical_state"] == pytest.approx(0.75, rel=1e-6)


def _cyclic_file(tmp_path, rec=None):
    """A synthetic axisymmetric record with the rate1 column of a cyclic record."""
    rec = dict(rec or axisym_record(kmax=0.4, kcv=0.25))
    rec["rate1"] = np.full(len(rec["p"]), 1.0)
    path = tmp_path / "cyc.csv"
    io.write_servo_csv(path, rec)
    return path


def test_figures_state_n_rate_and_specimen(files, figure, tmp_path):
    """Under every figure: the number of spheres and the specimen as given, and the records'
    deviatoric strain rate ε̇_q: 2/3 of d(ε1 − ε3)/dt = (2/3)(0.001/1e-3 s) in the synthetic
    axisymmetric record."""
    paths = dict(files, cyclic=_cyclic_file(tmp_path))
    for command in ("axisym", "cyclic", "pq", "radial", "pi-plane"):
        name = {"radial": "b0.5.csv", "pi-plane": "cdst.csv", "cyclic": "cyclic"}.get(
            command, "dense.csv")
        fig = figure(command, paths[name], "--n", 500, "--specimen", "dense",
                     "--out", tmp_path / "f.png")
        (text,) = fig["texts"]
        assert "N = 500 spheres" in text and "specimen dense" in text, text
    fig = figure("axisym", files["dense.csv"], "--n", 500, "--out", tmp_path / "f.png")
    rate = float(re.search(r"ε̇_q = (\S+) 1/s", fig["texts"][0]).group(1))
    assert rate == pytest.approx(2 / 3, rel=0.02)
    assert "specimen not given" in fig["texts"][0]


def test_clockwise_and_anticlockwise_paths_differ_in_black_and_white(files, figure, tmp_path):
    """Two records on one figure differ by line style, not only by colour."""
    fig = figure("pi-plane", files["ps.csv"], files["cdst.csv"], "--labels", "cw", "ccw",
                 "--out", tmp_path / "p.png")
    for panel in ("strain path", "stress path"):
        lines = _ax(fig, panel)["lines"]
        assert lines["cw"].get_linestyle() != lines["ccw"].get_linestyle()


def test_eps_v_axis_is_not_autoscaled_into_round_off(figure, tmp_path):
    """A record whose εv = ε1 + ε2 + ε3 stays at -2 % but for round-off (the three strains
    summed) is drawn on a span of at least 1e-3 %, not zoomed into its noise."""
    x = np.linspace(0.0, 0.4, 401)
    k = np.minimum(x / 0.05, 1.0) * 0.3
    sig = np.stack([P0 * (1 + 2 * k), P0 * (1 - k), P0 * (1 - k)], axis=1)
    eps = np.stack([2 * x / 3 - 0.02 / 3, -x / 3 - 0.02 / 3, -x / 3 - 0.02 / 3], axis=1)
    ev = eps.sum(axis=1)
    assert 0 < np.ptp(ev) < 1e-15            # round-off only
    path = _cyclic_file(tmp_path, record(sig, eps))
    for command, title in (("axisym", "Volumetric"), ("cyclic", "Volumetric")):
        lo, hi = _ax(figure(command, path, "--out", tmp_path / "f.png"), title)["ylim"]
        assert hi - lo >= 1e-3


def test_no_duplicate_legend_entries(files, figure, tmp_path):
    """Two plane-strain records with surfaces through one strength (Figs 8-9): each label once
    in every legend."""
    fig = figure("pi-plane", files["ps.csv"], files["cdst.csv"], "--labels", "cw", "ccw",
                 "--sinphi-tc", 0.45, "--out", tmp_path / "p.png")
    for ax in fig["axes"]:
        assert len(ax["legend"]) == len(set(ax["legend"])), ax["legend"]
    assert any(t.startswith("Lade–Duncan") for t in _ax(fig, "stress path")["legend"])


def test_q_is_labelled_by_its_definition(files, figure, tmp_path):
    """q is √(3J2) in the record (docs/fix_cell_servo.md, output 11): no figure calls the signed
    σ1 − σ3 'q'."""
    for command in ("axisym", "cyclic"):
        fig = figure(command, _cyclic_file(tmp_path), "--out", tmp_path / "f.png")
        for ax in fig["axes"]:
            assert "q = σ1 − σ3" not in ax["ylabel"], (command, ax["ylabel"])


def test_cycle_work_is_numbered_as_the_cyclic_deck_numbers_cycles(tmp_path):
    """inputs/cyclic.in: cycle k runs from -A (the first from 0) to +A and back to -A. A
    synthetic record of 3 cycles whose deviator is +s_k while compressing and -s_k while
    extending in cycle k (p and eps_v constant): the loop of cycle k encloses 2A x 2 s_k, its
    work is (2/3)(4 A s_k); cycles 2 and 3 are complete, cycle 1 is not."""
    from tylmp.analysis import cyclic as cyc
    A, s_k, m = 0.01, {1: 10e3, 2: 20e3, 3: 40e3}, 400
    legs = [(0.0, A, 1)] + [(A, -A, 1)] + [(-A, A, 2), (A, -A, 2), (-A, A, 3), (A, -A, 3)]
    d13, s, rate = [], [], []
    for a, b, k in legs:
        x = np.linspace(a, b, m + 1)[1:] if d13 else np.linspace(a, b, m + 1)
        d13 += list(x)
        s += [np.sign(b - a) * s_k[k]] * len(x)
        rate += [np.sign(b - a)] * len(x)
    d13, s = np.array(d13), np.array(s)
    sig = np.stack([P0 + 2 * s / 3, P0 - s / 3, P0 - s / 3], axis=1)
    eps = np.stack([d13 * 2 / 3, -d13 / 3, -d13 / 3], axis=1)
    rec = dict(record(sig, eps), rate1=np.array(rate))
    path = tmp_path / "cyclic.csv"
    io.write_servo_csv(path, rec)
    works = cyc.cycle_work(io.read_servo_csv(path))
    assert sorted(works) == [2, 3]
    for k in (2, 3):      # the switch of sign within one row costs s_k x one row's strain
        assert works[k] == pytest.approx(2 / 3 * 4 * A * s_k[k], rel=2 / m)


def test_caption_gives_the_range_of_many_rates():
    """A figure of many records (Fig 3: six) gives the range of their rates, which fits under
    the figure, and one or two rates as they are."""
    from tylmp.analysis import figures
    one = figures.about_text([5.2e-5], 3620, "dense", rate=lambda r: r)
    assert one.endswith("ε̇_q = 5.2e-05 1/s"), one
    many = figures.about_text([5.7e-5, 5.2e-5, 5.5e-5, 5.2e-5], 3620, "dense", rate=lambda r: r)
    assert many.endswith("ε̇_q = 5.2e-05–5.7e-05 1/s"), many


def test_reproduce_figures_state_the_spheres_and_specimens_of_their_runs():
    """Each figure `reproduce` draws names under it the scale's number of spheres (the paper's
    3620; 500 at the quick scale) and the specimen(s) its runs shear: the paper's Fig 3 and
    Figs 4-9 are of the dense specimen, Figs 1-2 of both, the loose radial set of the loose."""
    from tylmp.analysis import reproduce

    def caption_args(cmds):
        return {c[0] + (" " + c[c.index("--out") + 1].rsplit("/", 1)[-1] if "--out" in c else ""):
                (c[c.index("--n") + 1], c[c.index("--specimen") + 1])
                for c in cmds if "--n" in c}
    paper = caption_args(reproduce.figure_commands("d"))
    assert paper == {"axisym fig1_2_axisym_paper.png": ("3620", "dense and loose"),
                     "friction fig3_friction_paper.png": ("3620", "dense"),
                     "radial fig4_6_radial_dense_paper.png": ("3620", "dense"),
                     "radial fig4_6_radial_loose_paper.png": ("3620", "loose"),
                     "pi-plane fig7_cdst_paper.png": ("3620", "dense"),
                     "pi-plane fig8_9_plane_strain_paper.png": ("3620", "dense")}
    quick = caption_args(reproduce.figure_commands("d", "quick"))
    assert {n for n, _ in quick.values()} == {"500"}
