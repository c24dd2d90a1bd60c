"""The estimator on a synthetic IMU record of known attitude and bias (the sensor model written
here, independently of the library), in f64 and f32, and on a real BROAD trial (a trimmed copy in
data/broad/, scored against the optical reference)."""

from __future__ import annotations

import csv
import gzip
from pathlib import Path

import numpy as np
import pytest

import gyrostat
from gyrostat import GyrostatError, Rotation

from conftest import ROOT, angle_between

G = 9.81
B_EARTH = np.array([0.0, 15.8, -40.7])  # ENU, uT (Berlin's field, as BROAD)


def synthetic(n: int = 12000, dt: float = 0.005, bias=(0.01, -0.02, 0.005)):
    """A sensor at rest for 10 s, then turning about a slowly changing axis (non-periodic),
    with a constant gyroscope bias and no noise; jittered time stamps."""
    rng = np.random.default_rng(7)
    t = np.cumsum(np.full(n, dt) * rng.uniform(0.8, 1.2, n))
    t -= t[0]
    tt = np.maximum(t - 10.0, 0.0)
    w = np.column_stack([0.4 * np.sin(0.7 * tt), 0.3 * np.cos(0.31 * tt + 0.2 * tt**1.1), 0.2 * np.ones(n)])
    w[t < 10.0] = 0.0
    # True attitude (sensor -> earth): exact exponential of the rate held over each interval.
    q = np.zeros((n, 4))
    q[0] = Rotation.from_euler("ZYX", [0.5, 0.1, -0.2]).as_quat(scalar_first=True)
    for k in range(1, n):
        phi = w[k - 1] * (t[k] - t[k - 1])
        a = np.linalg.norm(phi)
        dq = np.concatenate([[np.cos(a / 2)], np.sinc(a / 2 / np.pi) * phi / 2])
        w0, v0 = q[k - 1, 0], q[k - 1, 1:]
        w1, v1 = dq[0], dq[1:]
        q[k] = np.concatenate([[w0 * w1 - v0 @ v1], w0 * v1 + w1 * v0 + np.cross(v0, v1)])
        q[k] /= np.linalg.norm(q[k])
    r = Rotation.from_quat(q, scalar_first=True)
    # Rate sample k is the rate held over [t_k, t_k+1]: the estimator propagates sample k over
    # t_k - t_(k-1), so feed the rate of the interval ending at t_k.
    gyro = np.vstack([w[:1], w[:-1]]) + np.array(bias)
    accel = r.apply(np.array([0.0, 0.0, G]), inverse=True)
    mag = r.apply(B_EARTH, inverse=True)
    return t, gyro, accel, mag, q


def test_synthetic_9d_and_6d():
    t, gyro, accel, mag, q = synthetic()
    for precision in ["f64", "f32"]:
        est = gyrostat.estimate(t, gyro, accel, mag, precision=precision)
        err = np.degrees(angle_between(est.q, q))
        assert err[len(t) // 2 :].max() < 1.0, precision
        assert np.abs(est.bias[-1] - [0.01, -0.02, 0.005]).max() < 2e-3, precision
        assert est.at_rest[: len(t) // 20].any()
        assert est.mag_used.mean() > 0.9
    # 6D: inclination only (no heading reference): the tilt of the estimate is right.
    est6 = gyrostat.estimate(t, gyro, accel)
    up_true = Rotation.from_quat(q, scalar_first=True).apply([0, 0, 1.0], inverse=True)
    up_est = Rotation.from_quat(est6.q, scalar_first=True).apply([0, 0, 1.0], inverse=True)
    tilt = np.degrees(np.arccos(np.clip(np.sum(up_true * up_est, axis=1), -1, 1)))
    assert tilt[len(t) // 2 :].max() < 1.0
    assert not est6.mag_used.any()


def test_parameters_and_errors():
    t, gyro, accel, mag, _ = synthetic(2000)
    d = gyrostat.estimator_defaults()
    assert d["accel_time_constant"] == 3.0
    est = gyrostat.estimate(t, gyro, accel, mag, accel_time_constant=1.0, frame="ned",
                            heading_time_constant=9.0)
    assert est.q.shape == (2000, 4)
    with pytest.raises(GyrostatError, match='unknown estimator parameter "nope"'):
        gyrostat.estimate(t, gyro, accel, nope=1.0)
    bad = gyro.copy()
    bad[321, 0] = np.inf
    with pytest.raises(GyrostatError, match=r"^row 321: input is NaN or infinite") as e:
        gyrostat.estimate(t, bad, accel, mag)
    assert e.value.row == 321
    skipped = gyrostat.estimate(t, bad, accel, mag, skip_errors=True)
    assert (skipped.q[321] == skipped.q[320]).all()
    tb = t.copy()
    tb[500] = tb[499]
    with pytest.raises(GyrostatError, match=r"^row 500: ") as e:
        gyrostat.estimate(tb, gyro, accel)
    with pytest.raises(GyrostatError, match="rows for"):
        gyrostat.estimate(t[:10], gyro, accel)


# BROAD trial 07 trimmed to its first 60 s (rest, then 33.5 s of fast rotation), kept in the
# repository (data/README.md: licence, citation and how it was cut).
BROAD_07 = ROOT / "data" / "broad" / "07_undisturbed_fast_rotation_B.first60s.csv.gz"


def test_broad_trial_07_against_the_optical_reference():
    with gzip.open(BROAD_07, "rt") as f:
        rows = list(csv.DictReader(f))
    col = lambda names: np.array([[float(r[n]) if r[n] else np.nan for n in names] for r in rows])
    t = col(["t_s"])[:, 0]
    gyro = col(["gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s"])
    accel = col(["acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"])
    mag = col(["mag_x_uT", "mag_y_uT", "mag_z_uT"])
    ref = col(["opt_qw", "opt_qx", "opt_qy", "opt_qz"])
    moving = col(["movement"])[:, 0] == 1
    est = gyrostat.estimate(t, gyro, accel, mag)
    ok = moving & np.isfinite(ref).all(axis=1)
    err = np.degrees(angle_between(est.q[ok], ref[ok] / np.linalg.norm(ref[ok], axis=1, keepdims=True)))
    rmse = float(np.sqrt(np.mean(err**2)))
    # The library documents 1.56 deg mean over 16 trials (BROAD metric; 1.81 deg on this trimmed
    # trial); the fast-rotation trial 07 of a working filter stays within a few degrees, a wrong
    # frame would be off by ~90.
    assert rmse < 4.0, rmse
