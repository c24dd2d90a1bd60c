"""Synthetic logs: the same numbers as the `synthesize` tool, closed-form motion, a simulated
motion's rows, and the error paths."""

from __future__ import annotations

import numpy as np
import pytest

import gyrostat
from gyrostat import GyrostatError

from conftest import run_tool


def qmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ])


def matrix(q: np.ndarray) -> np.ndarray:
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def test_the_same_numbers_as_the_tool():
    kw = dict(sensor="consumer", rate=100.0, duration=4.0, rest=1.0, phases=2,
              translation=0.2, magnet_pass=(1.0, 0.2, 0.05), seed=3)
    log = gyrostat.synthesize(**kw)
    text = run_tool("synthesize", ["--sensor", "consumer", "--rate", "100", "--duration", "4",
                                   "--rest", "1", "--phases", "2", "--translation", "0.2",
                                   "--magnet-pass", "1,0.2,0.05", "--seed", "3"])
    lines = text.strip().splitlines()[1:]
    assert len(lines) == len(log.t)
    for k, line in enumerate(lines):
        f = [float(x) if x else np.nan for x in line.split(",")]
        assert abs(f[0] - log.t[k]) < 5e-10
        np.testing.assert_array_equal(f[1:4], log.gyr[k])
        np.testing.assert_array_equal(f[4:7], log.acc[k])
        np.testing.assert_array_equal(f[7:10], log.mag[k])
        np.testing.assert_array_equal(f[10:14], log.q[k])
        assert bool(f[14]) == log.movement[k]


def test_constant_rate_about_a_tilted_axis():
    w = np.array([0.3, -0.5, 0.81])
    log = gyrostat.synthesize(motion="spin:0.3,-0.5,0.81", rest=0.0, ramp=0.0, phases=1,
                              duration=5.0, rate=50.0)
    for t, g, a, q in zip(log.t_true, log.gyr, log.acc, log.q):
        n = np.linalg.norm(w)
        qt = np.concatenate([[np.cos(n * t / 2)], np.sin(n * t / 2) * w / n])
        assert np.allclose(q, qt, atol=1e-12) or np.allclose(q, -qt, atol=1e-12)
        np.testing.assert_array_equal(g, w)
        np.testing.assert_allclose(a, matrix(qt).T @ [0, 0, 9.81], atol=1e-12)


def test_simulated_rows_as_the_motion():
    sim = gyrostat.simulate(inertia=(2, 2, 3), omega=(0.4, -0.3, 1.5), dt=0.01, steps=500,
                            integrator="exact")
    log = gyrostat.synthesize(motion_rows=sim, rest=0.5)
    assert len(log.t) == 50 + 501
    t = log.t_true[50:] - 0.5
    lam = (3 - 2) / 2 * 1.5
    w = np.stack([0.4 * np.cos(lam * t) + 0.3 * np.sin(lam * t),
                  0.4 * np.sin(lam * t) - 0.3 * np.cos(lam * t), np.full_like(t, 1.5)], axis=1)
    np.testing.assert_allclose(log.gyr[50:], w, atol=1e-9)
    assert not log.movement[:50].any() and log.movement[50:].all()


def test_errors_name_keywords():
    with pytest.raises(GyrostatError, match="^rate: must be finite and > 0"):
        gyrostat.synthesize(rate=0.0)
    with pytest.raises(GyrostatError, match="not a preset"):
        gyrostat.synthesize(sensor="nope")
    with pytest.raises(GyrostatError, match="motion: handheld, axes"):
        gyrostat.synthesize(motion="wobble")
    assert "ICM-42688-P" in gyrostat.sensor_text("consumer")
