"""Propagation against the `propagate` tool (the same numbers, bit for bit, in f64, f32,
compensated and Q1.30) and against closed-form motions."""

from __future__ import annotations

import numpy as np
import pytest

import gyrostat
from gyrostat import GyrostatError

from conftest import angle_between, csv_rows, parse_csv, run_tool

RULES = ["exp", "coning1", "coning2", "coning3", "coning4"]
METHODS = ["magnus4", "cf4", "rk4"]


def coning_increments(n: int, dt: float) -> np.ndarray:
    """Increments of a coning motion with a slow drift of its frequency (no period repeats)."""
    t = np.arange(n + 1) * dt
    w = 2 * np.pi * (3.0 + 0.37 * t)  # rad/s, chirped
    phase = np.cumsum(np.concatenate([[0.0], w[:-1] * dt]))
    a = 0.02
    # Rates of a coning motion of half-angle a: omega = (-a w sin, a w cos, small), integrated
    # per interval by the trapezoid rule: increments need not be exact for a tool comparison.
    rate = np.column_stack([-a * w * np.sin(phase), a * w * np.cos(phase), 0.1 + 0 * t])
    return 0.5 * (rate[1:] + rate[:-1]) * dt


def tool_rows(args: list[str], samples: np.ndarray, dtype=np.float64) -> np.ndarray:
    out = parse_csv(run_tool("propagate", args, csv_rows(samples)), dtype=str)
    assert (out[:, 0].astype(int) == np.arange(len(samples))).all()
    return out[:, 1:].astype(np.float64 if dtype is np.float64 else np.float32)


# Compensated accumulation is for floating point (q30 rounds as the firmware does).
ARITHMETIC = [("f64", False), ("f64", True), ("f32", False), ("f32", True), ("q30", False)]


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("precision,compensated", ARITHMETIC)
def test_increments_match_the_tool(rule, precision, compensated):
    inc = coning_increments(203, 1e-3)
    q0 = [0.9, 0.1, -0.3, 0.2]
    q0 = [float(x) for x in np.array(q0) / np.linalg.norm(q0)]
    args = ["--input", "increments", "--algo", rule, "--dt", "0.001"]
    args += ["--q0", ",".join(repr(float(x)) for x in q0)]
    args += {"f64": [], "f32": ["--f32"], "q30": ["--fixed"]}[precision]
    args += ["--compensated"] if compensated else []
    dtype = np.float32 if precision == "f32" else np.float64
    ref = tool_rows(args, inc, dtype)
    mine = gyrostat.propagate_increments(
        inc, rule=rule, q0=q0, precision=precision, compensated=compensated
    )
    assert mine.dtype == dtype and mine.shape == (len(inc), 4)
    assert (mine == ref).all()
    if precision == "q30":
        assert (mine * 2**30 == np.round(mine * 2**30)).all()


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("precision", ["f64", "f32"])
@pytest.mark.parametrize("compensated", [False, True])
def test_rates_match_the_tool(method, precision, compensated):
    dt = 0.00125
    t = np.arange(157) * dt
    rates = np.column_stack([np.sin(7 * t + t * t), 0.3 * np.cos(3 * t), 1.0 + 0.1 * t])
    args = ["--input", "rates", "--algo", method, "--dt", repr(dt)]
    args += ["--f32"] if precision == "f32" else []
    args += ["--compensated"] if compensated else []
    dtype = np.float32 if precision == "f32" else np.float64
    ref = tool_rows(args, rates, dtype)
    mine = gyrostat.propagate_rates(
        rates, dt, method=method, precision=precision, compensated=compensated
    )
    assert mine.dtype == dtype and (mine == ref).all()


def test_constant_rate_against_the_closed_form():
    # A constant body rate turns the body about a fixed axis: q(t) = exp(w t / 2).
    w = np.array([0.3, -0.2, 0.9])
    dt, n = 0.002, 1500
    exact_angle = np.linalg.norm(w) * dt * np.arange(1, n + 1)
    axis = w / np.linalg.norm(w)
    exact = np.column_stack(
        [np.cos(exact_angle / 2), np.outer(np.sin(exact_angle / 2), axis)]
    )
    for rule in RULES:
        q = gyrostat.propagate_increments(np.tile(w * dt, (n, 1)), rule=rule)
        assert angle_between(q, exact).max() < 1e-12, rule
    for method in METHODS:
        q = gyrostat.propagate_rates(np.tile(w, (n + 1, 1)), dt, method=method)
        assert angle_between(q[1:], exact).max() < 1e-12, method
    q32 = gyrostat.propagate_increments(np.tile(w * dt, (n, 1)), precision="f32", compensated=True)
    assert angle_between(q32.astype(np.float64), exact).max() < 2e-6
    qfix = gyrostat.propagate_increments(np.tile(w * dt, (n, 1)), precision="q30")
    assert angle_between(qfix, exact).max() < 1e-6


def test_bad_samples_raise_naming_the_row():
    inc = coning_increments(50, 1e-3)
    inc[17, 2] = np.nan
    with pytest.raises(GyrostatError, match=r"^row 17: sample has a NaN") as e:
        gyrostat.propagate_increments(inc)
    assert e.value.row == 17
    big = np.zeros((10, 3))
    big[4] = [3.0, 0, 0]
    with pytest.raises(GyrostatError, match=r"^row 4: .*Q1\.30") as e:
        gyrostat.propagate_increments(big, precision="q30")
    assert e.value.row == 4
    with pytest.raises(GyrostatError, match=r"^row 4: step too long"):
        gyrostat.propagate_increments(big * 2, rule="coning2")
    with pytest.raises(GyrostatError, match="rule"):
        gyrostat.propagate_increments(big, rule="coning9")
    with pytest.raises(GyrostatError, match="compensated needs floating point"):
        gyrostat.propagate_increments(big, precision="q30", compensated=True)
    with pytest.raises(GyrostatError, match="q0"):
        gyrostat.propagate_increments(big, q0=[2.0, 0, 0, 0])
    with pytest.raises(GyrostatError, match="dt"):
        gyrostat.propagate_rates(big, -1.0)
