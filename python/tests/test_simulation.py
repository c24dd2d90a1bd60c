"""The simulation against the `simulate` tool (the same scenarios, the same numbers) and
against physics the integrators must keep (conserved |J|, the closed-form flip interval)."""

from __future__ import annotations

import concurrent.futures
import re

import numpy as np
import pytest

import gyrostat
from gyrostat import GyrostatError

from conftest import run_tool

SCENARIOS = [
    (
        dict(inertia=(6, 4, 3), omega=(0.05, 1, 0.01), dt=0.01, steps=700, every=7,
             integrator="strang"),
        "--inertia 6,4,3 --omega 0.05,1,0.01 --dt 0.01 --steps 700 --every 7 --integrator strang",
    ),
    (
        dict(inertia=(6, 4, 3), omega=(0.05, 1, 0.01), wheels=[(0, 1, 0, 0.05, 60)],
             wheel_torque=(-0.015,), dt=0.01, steps=600, every=50, integrator="yoshida4",
             f32=True),
        "--inertia 6,4,3 --omega 0.05,1,0.01 --wheel 0,1,0,0.05,60 --wheel-torque -0.015 "
        "--dt 0.01 --steps 600 --every 50 --integrator yoshida4 --f32",
    ),
    (
        dict(inertia=(5, 4, 2), inertia_offdiag=(0.1, -0.05, 0.2), momentum=(1, 2, 0.5),
             spin=(0.1, 0, 0.2), q0=(0.6, 0.8, 0, 0), torque=(0.01, 0, -0.02), dt=0.02,
             steps=400, every=3, integrator="rk4"),
        "--inertia 5,4,2 --inertia-offdiag 0.1,-0.05,0.2 --momentum 1,2,0.5 --spin 0.1,0,0.2 "
        "--q0 0.6,0.8,0,0 --torque 0.01,0,-0.02 --dt 0.02 --steps 400 --every 3 --integrator rk4",
    ),
    (
        dict(semi_rigid=("cubic", 1, 10, 0.5), omega=(0.3, 0.2, 1), dt=0.01, steps=300,
             integrator="suzuki4"),
        "--semi-rigid cubic:1,10,0.5 --omega 0.3,0.2,1 --dt 0.01 --steps 300 --integrator suzuki4",
    ),
    (
        dict(inertia=(3, 2, 1), omega=(0.1, 2, 0.2), quartic=("octahedral", 0.001), dt=0.01,
             steps=300, every=10, integrator="yoshida4"),
        "--inertia 3,2,1 --omega 0.1,2,0.2 --quartic octahedral:0.001 --dt 0.01 --steps 300 "
        "--every 10 --integrator yoshida4",
    ),
    (
        dict(inertia=(6, 4, 3), omega=(0.05, 1, 0.01), dt=0.05, steps=400, every=9,
             integrator="exact"),
        "--inertia 6,4,3 --omega 0.05,1,0.01 --dt 0.05 --steps 400 --every 9 --integrator exact",
    ),
    (
        dict(inertia=(6, 4, 3), omega=(0.2, 0.5, 0.1),
             wheels=[(1, 0, 0, 0.05), (0, 1, 0, 0.05, 10), (0, 0, 1, 0.05), (1, 1, 1, 0.02, -5)],
             wheel_speed=(5, 0, -3, 1), dt=0.01, steps=200, every=20, integrator="strang"),
        "--inertia 6,4,3 --omega 0.2,0.5,0.1 --wheel 1,0,0,0.05 --wheel 0,1,0,0.05,10 "
        "--wheel 0,0,1,0.05 --wheel 1,1,1,0.02,-5 --wheel-speed 5,0,-3,1 --dt 0.01 --steps 200 "
        "--every 20 --integrator strang",
    ),
]


def columns(sim: gyrostat.Simulation) -> np.ndarray:
    return np.column_stack(
        [sim.t, sim.q, sim.omega, sim.momentum, sim.energy, sim.wheel_speeds]
    )


@pytest.mark.parametrize("kw,flags", SCENARIOS)
def test_matches_the_tool(kw, flags):
    text = run_tool("simulate", flags.split())
    lines = text.strip().splitlines()
    dtype = np.float32 if kw.get("f32") else np.float64
    ref = np.array([[dtype(x) for x in line.split(",")] for line in lines[1:]], dtype=np.float64)
    sim = gyrostat.simulate(**kw)
    assert columns(sim).shape == ref.shape
    assert (columns(sim) == ref).all()
    assert sim.monitors is not None


def test_torque_schedule_matches_the_tool_file(tmp_path):
    rows = np.array([[0.0, 0.01, 0, 0], [0.333, 0, -0.02, 0.005], [1.0, 0, 0, 0]])
    f = tmp_path / "torque.csv"
    f.write_text("t,tx,ty,tz\n" + "".join(",".join(repr(float(x)) for x in r) + "\n" for r in rows))
    flags = ("--inertia 6,4,3 --omega 0.05,1,0.01 --dt 0.01 --steps 150 --every 5 "
             f"--integrator strang --torque-file {f}").split()
    ref = np.array([[float(x) for x in line.split(",")]
                    for line in run_tool("simulate", flags).strip().splitlines()[1:]])
    sim = gyrostat.simulate(inertia=(6, 4, 3), omega=(0.05, 1, 0.01), dt=0.01, steps=150,
                            every=5, integrator="strang", torque_schedule=rows)
    assert (columns(sim) == ref).all()


def test_default_scenario_matches_the_tool_and_the_closed_form():
    d = gyrostat.default_scenario()
    text = run_tool("simulate", [])
    m = re.search(r"flip interval \(mean\)\s+(\S+) s\s+(\S+) s\s+(\S+) s\s+(\S+) s", text)
    assert m, text
    f32c, f32, f64, closed = (float(x) for x in m.groups())
    assert round(d["f32_compensated"]["flip_interval"], 4) == f32c
    assert round(d["f32"]["flip_interval"], 4) == f32
    assert round(d["f64"]["flip_interval"], 4) == f64
    assert round(d["flip_interval_closed_form"], 4) == closed
    # Physics, not the tool: the f64 flip interval is the closed form's 2K(m)/lambda.
    assert abs(d["f64"]["flip_interval"] / d["flip_interval_closed_form"] - 1) < 1e-4
    assert d["f64"]["momentum_norm_drift_max"] < 1e-13
    assert d["q_exact"].shape == d["f64"]["q"].shape == (2000, 4)


def test_compensated_matches_the_tool_and_beats_plain_f32():
    # The same numbers as `simulate --f32 --compensated`, and against the f64 run (the reference
    # for the rounding): closer than plain f32, |J| within 1.5e-7 (plain f32 drifts ~1e-5).
    kw = dict(inertia=(5, 3.5, 2), momentum=(-1.2, 0.3, 2.5), dt=0.004, steps=25000, every=250,
              integrator="yoshida4")
    flags = ("--inertia 5,3.5,2 --momentum -1.2,0.3,2.5 --dt 0.004 --steps 25000 --every 250 "
             "--integrator yoshida4 --f32 --compensated").split()
    lines = run_tool("simulate", flags).strip().splitlines()
    ref = np.array([[np.float32(x) for x in line.split(",")] for line in lines[1:]],
                   dtype=np.float64)
    comp = gyrostat.simulate(f32=True, compensated=True, **kw)
    assert (columns(comp) == ref).all()
    plain = gyrostat.simulate(f32=True, **kw)
    f64 = gyrostat.simulate(**kw)

    def angle(a, b):
        # The rotation angle of conj(a) b, by atan2 (accurate for small angles).
        w = (a * b).sum(axis=1)
        v = a[:, :1] * b[:, 1:] - b[:, :1] * a[:, 1:] - np.cross(a[:, 1:], b[:, 1:])
        return 2 * np.arctan2(np.linalg.norm(v, axis=1), np.abs(w))

    def drift(s):
        n = np.linalg.norm(s.momentum, axis=1)
        return np.abs(n / n[0] - 1).max()

    assert angle(comp.q, f64.q).max() < angle(plain.q, f64.q).max()
    assert drift(comp) < 1.5e-7 < drift(plain)


def test_splitting_keeps_the_momentum_norm():
    # Lie-Poisson splittings turn J exactly: |J| is conserved to rounding over a long run
    # (a non-repeating tumble near the separatrix).
    sim = gyrostat.simulate(inertia=(6, 4, 3), omega=(0.011, 1, 0.013), dt=0.02, steps=20000,
                            every=100, integrator="yoshida4")
    n = np.linalg.norm(sim.momentum, axis=1)
    assert np.abs(n / n[0] - 1).max() < 1e-13
    assert np.abs(np.linalg.norm(sim.q, axis=1) - 1).max() < 1e-14


def test_errors():
    with pytest.raises(GyrostatError, match="inertia") as e:
        gyrostat.simulate(inertia=(6, 4, -3), omega=(0, 1, 0), dt=0.01, steps=10,
                          integrator="strang")
    assert e.value.row is None
    with pytest.raises(GyrostatError, match="give either omega or momentum"):
        gyrostat.simulate(inertia=(6, 4, 3), omega=(0, 1, 0), momentum=(0, 1, 0), dt=0.01,
                          steps=10, integrator="strang")
    with pytest.raises(GyrostatError, match="wheel_torque needs at least one wheel$"):
        gyrostat.simulate(inertia=(6, 4, 3), omega=(0, 1, 0), wheel_torque=(1,), dt=0.01,
                          steps=10, integrator="strang")
    with pytest.raises(GyrostatError, match="integrator"):
        gyrostat.simulate(inertia=(6, 4, 3), omega=(0, 1, 0), dt=0.01, steps=10,
                          integrator="euler")
    with pytest.raises(GyrostatError, match="no compensated form"):
        gyrostat.simulate(inertia=(6, 4, 3), omega=(0, 1, 0.1), dt=0.01, steps=10,
                          integrator="exact", compensated=True)
    # A step the library rejects (more than half a turn): the rows before it come along.
    with pytest.raises(GyrostatError, match="step 1: step too long") as e:
        gyrostat.simulate(inertia=(6, 4, 3), omega=(0, 400, 0), dt=0.01, steps=10,
                          integrator="strang")
    assert len(e.value.partial.t) == 1


def test_threads_give_the_sequential_results():
    # Batch calls release the GIL: concurrent runs in a thread pool give the same rows.
    kws = [dict(inertia=(6, 4, 3), omega=(0.05 + 0.01 * i, 1, 0.01), dt=0.01, steps=2000,
                every=100, integrator="yoshida4") for i in range(6)]
    seq = [columns(gyrostat.simulate(**kw)) for kw in kws]
    with concurrent.futures.ThreadPoolExecutor(3) as pool:
        par = list(pool.map(lambda kw: columns(gyrostat.simulate(**kw)), kws))
    assert all((a == b).all() for a, b in zip(seq, par))
