"""inputs/rotation.in, principal stress rotation at constant p, sigma1 - sigma3 and b (the
hollow-cylinder path, docs/theory.md §13), run as a user runs it on the 500-sphere dense quick
specimen (prepared once per session: tests/conftest.py), and `tyanalysis rotation` on its record.
The rotation turns sigma1 by 90 degrees in the xz plane at 0.5 degree/s after the ramp and hold.

  * the record starts at the start of the rotation (`continue no`): time and strains from zero;
  * the non-coaxiality column equals an independent recomputation from the record's stress
    tensor (sig1..3, sig_xy..sig_yz) and strain-rate columns (rate1..3, rate_xy..rate_yz):
    tan 2θ = 2 s_ij/(s_ii - s_jj) of each tensor, ψ = θσ - θε̇ wrapped to (-90, 90] (§10.5);
  * p and the normal stresses sig1..3 held at the targets of §13 within the servo tolerance (1 %
    of p on each stress component, the tolerance tests/test_decks.py holds p and b to);
  * sigma1 - sigma3, b and the in-plane shear held, the major principal direction following
    alpha(t) = rate t within the lag that tolerance allows, and the out-of-plane shears at zero:
    held with the deck's servo gain 0.01 (at gain 0.03 the shear components ring, sig_yz
    reaching 1.5 % of p; at 0.02 they stay within 0.25 % of p: docs/decks/rotation.md, "The
    servo's gain").
About 2 minutes with the specimens' preparation.
"""
import math
import os

import numpy as np
import pytest

from test_decks import cli, read_csv, run_deck

P, DEV, B = 1e5, 4e4, 0.5          # the deck's defaults
RATE, TURN = 0.5, 90.0             # degree/s, degrees
SERVO_TOL = 0.01                   # of p, on each held stress component


@pytest.fixture(scope="module")
def record(tmp_path_factory, specimens):
    work, out = run_deck(tmp_path_factory, specimens, "rotation",
                         {"rotation_turn": TURN, "rotation_rate": RATE}, tag="rotation")
    assert "plot: tyanalysis rotation rotation.csv --target" in out
    t, _ = read_csv(work / "rotation.csv")
    return work, t


def tensors(diag, off):
    """(n, 3, 3) symmetric tensors from the diagonal and the (xy, xz, yz) entries."""
    n = len(diag[0])
    m = np.zeros((n, 3, 3))
    for k in range(3):
        m[:, k, k] = diag[k]
    for (i, j), v in zip(((0, 1), (0, 2), (1, 2)), off):
        m[:, i, j] = m[:, j, i] = v
    return m


def stress(t):
    return tensors([t["sig1"], t["sig2"], t["sig3"]], [t["sig_xy"], t["sig_xz"], t["sig_yz"]])


def angle_xz(m):
    """Major direction in the xz plane from x towards z, degrees in (-90, 90]."""
    a = 0.5 * np.degrees(np.arctan2(2.0 * m[:, 0, 2], m[:, 0, 0] - m[:, 2, 2]))
    return np.where(a <= -90.0, a + 180.0, a)


def wrap(a):
    a = np.asarray(a, float)
    return a - 180.0 * np.ceil((a - 90.0) / 180.0)


def test_record_starts_with_the_rotation(record):
    _, t = record
    dt = np.median(np.diff(t["time"]) / np.diff(t["step"]))
    assert 0.0 <= t["time"][0] <= 200 * dt
    assert np.all(np.abs([t["eps1"][0], t["eps2"][0], t["eps3"][0]]) < 1e-5)
    # the run length follows from the rate: TURN/RATE seconds
    assert t["time"][-1] == pytest.approx(TURN / RATE, abs=200 * dt)


def test_noncoaxiality_equals_recomputation(record):
    _, t = record
    sig = stress(t)
    # the compression-positive strain-rate tensor: rate_ij = L_ij, its entry is -L_ij/2
    rate = tensors([t["rate1"], t["rate2"], t["rate3"]],
                   [-0.5 * t["rate_xy"], -0.5 * t["rate_xz"], -0.5 * t["rate_yz"]])
    theta_s, theta_r = angle_xz(sig), angle_xz(rate)
    psi = wrap(theta_s - theta_r)
    # rows whose in-plane strain-rate deviator is not at round-off of the 12-digit record
    inplane = np.hypot(0.5 * (rate[:, 0, 0] - rate[:, 2, 2]), rate[:, 0, 2])
    ok = inplane > 1e-6 * np.abs(rate).max(axis=(1, 2))
    assert ok.sum() > 0.9 * len(ok)
    assert np.max(np.abs(wrap(t["stress_angle"] - theta_s))) < 1e-6
    assert np.max(np.abs(wrap(t["rate_angle"][ok] - theta_r[ok]))) < 1e-4
    assert np.max(np.abs(wrap(t["noncoaxiality"][ok] - psi[ok]))) < 1e-4
    # and the analysis package's own recomputation agrees
    from tylmp.analysis import io, principal
    table = io.Table(t)
    assert np.max(np.abs(wrap(principal.noncoaxiality_deg(table, "xz")[ok] - psi[ok]))) < 1e-9


def targets(t):
    """The held stress tensor of §13 at each row: sigma1 = p + (2 - b)D/3 at alpha = RATE time
    from x towards z, sigma3 = p - (1 + b)D/3 at right angles in the plane, sigma2 along y."""
    s1, s3 = P + (2.0 - B) * DEV / 3.0, P - (1.0 + B) * DEV / 3.0
    s2 = s3 + B * (s1 - s3)
    a = np.radians(RATE * t["time"])
    c, s = np.cos(a), np.sin(a)
    return {"sig1": c * c * s1 + s * s * s3, "sig2": np.full_like(a, s2),
            "sig3": s * s * s1 + c * c * s3, "sig_xz": c * s * (s1 - s3)}


def test_p_and_normal_stresses_held(record):
    _, t = record
    p = np.trace(stress(t), axis1=1, axis2=2) / 3.0
    assert np.max(np.abs(p / P - 1.0)) < SERVO_TOL
    want = targets(t)
    for name in ("sig1", "sig2", "sig3"):
        assert np.max(np.abs(t[name] - want[name])) < SERVO_TOL * P, name


def test_deviator_b_and_in_plane_shear_held(record):
    _, t = record
    values = np.linalg.eigvalsh(stress(t))[:, ::-1]
    s1, s2, s3 = values.T
    # each component within SERVO_TOL p: sigma1 - sigma3 within twice it, b within
    # 2 SERVO_TOL p/(sigma1 - sigma3)
    assert np.max(np.abs(t["sig_xz"] - targets(t)["sig_xz"])) < SERVO_TOL * P
    assert np.max(np.abs((s1 - s3) - DEV)) < 2 * SERVO_TOL * P
    assert np.max(np.abs((s2 - s3) / (s1 - s3) - B)) < 2 * SERVO_TOL * P / DEV


# the major direction within the servo tolerance of alpha(t): a stress error e on the held
# components turns the in-plane major direction by at most e/(sigma1 - sigma3) radians (from
# tan 2θ = 2 s_xz/(s_xx - s_zz)): 1.43 degrees at e = 1 % of p; the proportional loop's lag of the
# turning target adds d/(r g) with d = (sigma1 - sigma3) alpha_dot dt = 5 Pa per step, under
# 0.3 degrees for a stiffness ratio r > 0.3 at g = 0.03 (§6.2): 1.7 degrees in all.
ANGLE_TOL = math.degrees(SERVO_TOL * P / DEV) + 0.3


def test_major_direction_follows_alpha(record):
    _, t = record
    assert np.max(np.abs(wrap(angle_xz(stress(t)) - RATE * t["time"]))) < ANGLE_TOL


def test_out_of_plane_shears_zero(record):
    _, t = record
    assert np.max(np.abs(t["sig_xy"])) < SERVO_TOL * P
    assert np.max(np.abs(t["sig_yz"])) < SERVO_TOL * P


def test_major_direction_turns(record):
    """The weaker statement that holds now: sigma1 turns with alpha(t), within 6 degrees."""
    _, t = record
    err = wrap(angle_xz(stress(t)) - RATE * t["time"])
    assert np.max(np.abs(err)) < 6.0
    assert np.mean(np.abs(err)) < 2.0


def test_analysis_figure(record, tmp_path):
    work, t = record
    out = tmp_path / "rotation.png"
    text = cli("rotation", str(work / "rotation.csv"), "--target", str(P), str(DEV), str(B),
               "--out", str(out), cwd=tmp_path)
    assert os.path.getsize(out) > 10_000
    turned = float(text.split("turned_deg=")[1].split()[0])
    assert turned == pytest.approx(RATE * (t["time"][-1] - t["time"][0]), abs=6.0)
