"""The Allan deviation and the noise characterisation: ``gyrostat.allan_deviation`` against
``allantools.oadev`` (PyPI, the reference implementation people use) on the same data; the fit
recovering the N and K of noise drawn here with numpy (independent of the crate's generator);
the package against the ``characterize`` tool; argument errors.

Tolerance against allantools: 1e-9 relative. Both sum the same squared second differences of
the integrated (mean-removed) samples in f64, but allantools sums numpy's pairwise way and the
crate in order: the differences are rounding, about 1e-13 relative over 10^5 samples."""

from __future__ import annotations

import numpy as np
import pytest

import gyrostat
from gyrostat import GyrostatError

from conftest import csv_rows, run_tool

allantools = pytest.importorskip("allantools")


def noise(n: int, rate: float, density: float, walk: float, seed: int) -> np.ndarray:
    """White noise of density ``density`` plus a random walk of ``walk`` per sqrt(s), an offset
    and a slow non-periodic drift, numpy's generator."""
    rng = np.random.default_rng(seed)
    dt = 1.0 / rate
    white = rng.normal(size=n) * density / np.sqrt(dt)
    rw = np.cumsum(rng.normal(size=n)) * walk * np.sqrt(dt)
    return 0.3 + white + rw


@pytest.mark.parametrize("seed,n,rate", [(1, 100_000, 100.0), (2, 33_333, 285.714), (3, 777, 1.0)])
def test_equals_allantools_octave(seed, n, rate):
    x = noise(n, rate, 2e-3, 1e-4, seed)
    taus, adev, ns = gyrostat.allan_deviation(x, rate)
    t_ref, a_ref, _, n_ref = allantools.oadev(x, rate=rate, data_type="freq", taus="octave")
    assert np.array_equal(taus, t_ref)
    np.testing.assert_allclose(adev, a_ref, rtol=1e-9, atol=0)
    assert np.array_equal(ns, n_ref.astype(np.uint64))


def test_equals_allantools_given_taus():
    rate = 200.0
    x = noise(50_000, rate, 1e-2, 3e-3, 4)
    want = np.array([0.005, 0.013, 0.1, 0.77, 3.3, 12.0, 60.0])
    taus, adev, ns = gyrostat.allan_deviation(x, rate, taus=want)
    t_ref, a_ref, _, n_ref = allantools.oadev(x, rate=rate, data_type="freq", taus=want)
    np.testing.assert_allclose(taus, t_ref, rtol=1e-15)
    np.testing.assert_allclose(adev, a_ref, rtol=1e-9, atol=0)
    assert np.array_equal(ns, n_ref.astype(np.uint64))


def test_decade_grid_equals_allantools_at_its_taus():
    rate = 50.0
    x = noise(40_000, rate, 5e-3, 0.0, 5)
    taus, adev, _ = gyrostat.allan_deviation(x, rate, taus="decade")
    assert len(taus) > 30
    _, a_ref, _, _ = allantools.oadev(x, rate=rate, data_type="freq", taus=taus)
    np.testing.assert_allclose(adev, a_ref, rtol=1e-9, atol=0)


def test_characterize_recovers_white_noise_and_random_walk():
    # 10 Hz, 2e4 s: the random walk overtakes the white noise at sqrt(3) N/K = 1.7 s; the log
    # is 10^4 times longer, enough for K within 10 % (see tools/tests/tools/characterize.rs).
    rate, density, walk = 10.0, 1e-3, 1e-3
    x = np.column_stack([noise(200_000, rate, density, walk, s) for s in (10, 11, 12)])
    fit = gyrostat.characterize(x, rate)
    assert fit["noise_density"].shape == (3,)
    np.testing.assert_allclose(fit["noise_density"], density, rtol=0.10)
    np.testing.assert_allclose(fit["rate_random_walk"], walk, rtol=0.10)
    assert fit["adev"].shape == (3, len(fit["taus"]))
    # The curve of characterize is allan_deviation's.
    t, a, _ = gyrostat.allan_deviation(x[:, 1], rate)
    assert np.array_equal(fit["taus"], t) and np.array_equal(fit["adev"][1], a)
    one = gyrostat.characterize(x[:, 0], rate)
    assert one["noise_density"] == fit["noise_density"][0]


def test_characterize_equals_the_tool():
    rate = 100.0
    n = 20_000
    g = np.column_stack([noise(n, rate, 4e-3, 1e-3, s) for s in (20, 21, 22)])
    a = np.column_stack([noise(n, rate, 2e-2, 1e-3, s) for s in (23, 24, 25)])
    t = np.arange(n) / rate
    out = run_tool("characterize", ["--fit-from", "0.05"], csv_rows(np.column_stack([t, g, a])))
    rows = [l.split(",") for l in out.split("\n\n")[0].splitlines()[1:]]
    tool_n = {(r[0], r[1]): float(r[5]) for r in rows}
    fit_g = gyrostat.characterize(g, rate, fit_from=0.05)
    fit_a = gyrostat.characterize(a, rate, fit_from=0.05)
    for i, axis in enumerate("xyz"):
        # The tool's rate comes from the printed time stamps: the same to rounding.
        assert tool_n[("gyro", axis)] == pytest.approx(fit_g["noise_density"][i], rel=1e-9)
        assert tool_n[("accel", axis)] == pytest.approx(fit_a["noise_density"][i], rel=1e-9)


def test_errors():
    x = noise(1000, 10.0, 1e-3, 0.0, 6)
    with pytest.raises(GyrostatError, match="averaging factor"):
        gyrostat.allan_deviation(x, 10.0, taus=[1000.0])
    with pytest.raises(GyrostatError, match="shorter than half a sample"):
        gyrostat.allan_deviation(x, 10.0, taus=[0.01])
    with pytest.raises(GyrostatError, match="sample rate"):
        gyrostat.allan_deviation(x, 0.0)
    with pytest.raises(GyrostatError, match="not finite"):
        gyrostat.allan_deviation(np.array([1.0, np.nan, 2.0, 3.0]), 1.0)
    with pytest.raises(GyrostatError, match="at least 3"):
        gyrostat.allan_deviation(np.array([1.0, 2.0]), 1.0)
    with pytest.raises(GyrostatError, match="expected shape"):
        gyrostat.allan_deviation(np.zeros((10, 2)), 1.0)
    with pytest.raises(GyrostatError, match="taus"):
        gyrostat.characterize(x, 10.0, taus="all")
