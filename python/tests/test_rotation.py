"""Conversions against scipy's Rotation (an independent implementation) on random and
near-singular attitudes, and against the `convert` tool."""

from __future__ import annotations

import itertools
import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as R

import gyrostat
from gyrostat import GyrostatError, Rotation as G

from conftest import angle_between, csv_rows, parse_csv, random_unit_quats, run_tool

# Every one of scipy's three-axis sequences: 12 axis orders, intrinsic and extrinsic.
AXES = ["".join(p) for p in itertools.product("xyz", repeat=3) if p[0] != p[1] and p[1] != p[2]]
SEQS = AXES + [s.upper() for s in AXES]
# f64 tolerances: a few roundings of unit-sized numbers.
EPS = np.finfo(float).eps
N = 3000


@pytest.fixture(scope="module")
def quats() -> np.ndarray:
    return random_unit_quats(N, seed=1)


def test_quat_round_trip_and_order(quats):
    scaled = quats * np.random.default_rng(2).uniform(1e-3, 1e3, size=(N, 1))
    g = G.from_quat(scaled)
    r = R.from_quat(scaled)
    assert np.abs(g.as_quat() - r.as_quat()).max() < 4 * EPS
    assert np.abs(g.as_quat(canonical=True) - r.as_quat(canonical=True)).max() < 4 * EPS
    wxyz = np.roll(scaled, 1, axis=1)
    g2 = G.from_quat(wxyz, scalar_first=True)
    assert np.abs(g2.as_quat() - r.as_quat()).max() < 4 * EPS
    assert np.abs(g2.as_quat(scalar_first=True) - r.as_quat(scalar_first=True)).max() < 4 * EPS
    c = g.as_quat(canonical=True)
    assert (c[:, 3] >= 0).all()


def test_quat_extreme_norms_use_the_scaled_normalisation():
    # Components near the ends of the f64 range: |q|^2 overflows or underflows, where the
    # library's scaled normalisation takes over.
    q = np.array([[1e300, 2e300, -3e300, 1e300], [1e-14, 0.0, 2e-14, 0.0], [3.0, 0, 0, 4.0]])
    g = G.from_quat(q).as_quat()
    ref = np.array([[1, 2, -3, 1] / np.sqrt(15.0), [1, 0, 2, 0] / np.sqrt(5.0), [0.6, 0, 0, 0.8]])
    assert np.abs(g - ref).max() < 4 * EPS
    assert np.abs(np.linalg.norm(g, axis=1) - 1).max() < 4 * EPS
    # A norm at or below eps is the library's zero norm (UnitQuat::MIN_NORM: no attitude
    # computation makes one, its direction is noise), on both sides of the fast path's bound.
    for tiny in [1e-310, 1e-200, 1e-16, 2e-16]:
        with pytest.raises(GyrostatError, match="row 0: quaternion has zero norm"):
            G.from_quat([tiny, 0.0, 0.0, 0.0])
    for small in [3e-16, 1e-15, 8.9e-16, 9e-16]:
        assert G.from_quat([0.0, small, 0.0, 0.0]).as_quat()[1] == 1.0


@pytest.mark.parametrize("seq", SEQS)
def test_as_euler_matches_scipy(quats, seq):
    e_g = G.from_quat(quats).as_euler(seq)
    e_s = R.from_quat(quats).as_euler(seq)
    assert np.abs(e_g - e_s).max() < 1e-12
    deg, lock = G.from_quat(quats).as_euler(seq, degrees=True, return_gimbal_lock=True)
    assert np.abs(deg - np.degrees(e_s)).max() < 1e-10
    assert not lock.any()


@pytest.mark.parametrize("seq", SEQS)
def test_from_euler_matches_scipy(seq):
    rng = np.random.default_rng(abs(hash(seq)) % 2**32)
    angles = rng.uniform(-4, 4, size=(N, 3))
    qg = G.from_euler(seq, angles).as_quat()
    qs = R.from_euler(seq, angles).as_quat()
    assert angle_between(qg, qs).max() < 8 * EPS
    qd = G.from_euler(seq, np.degrees(angles), degrees=True).as_quat()
    assert angle_between(qd, qs).max() < 1e-14


@pytest.mark.parametrize("seq", SEQS)
def test_gimbal_lock_reported_per_row(seq):
    # Middle angle exactly at each pole (+-pi/2 for Tait-Bryan, 0 and pi for proper), beside
    # rows 1e-9 and 1e-6 away from it.
    proper = seq[0].lower() == seq[2].lower()
    poles = [0.0, np.pi] if proper else [np.pi / 2, -np.pi / 2]
    rows, expect = [], []
    for pole in poles:
        off = 1.0 if pole <= 0 else -1.0
        for d, locked in [(0.0, True), (1e-9, False), (1e-6, False)]:
            rows.append([0.7, pole + off * d, -0.4])
            expect.append(locked)
    rows = np.array(rows)
    r = G.from_euler(seq, rows)
    angles, lock = r.as_euler(seq, return_gimbal_lock=True)
    assert (lock == np.array(expect)).all()
    # The angles rebuild the attitude to rounding at and next to the pole.
    back = G.from_euler(seq, angles).as_quat()
    assert angle_between(back, r.as_quat()).max() < 16 * EPS
    # At the pole: third angle 0, as scipy (which warns; no warning here).
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scipy_angles = R.from_quat(r.as_quat()).as_euler(seq)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r.as_euler(seq)
    locked = np.array(expect)
    assert (angles[locked, 2] == 0).all()
    assert np.abs(angles[locked] - scipy_angles[locked]).max() < 1e-12


def test_rotvec_mrp_matrix_match_scipy(quats):
    g, r = G.from_quat(quats), R.from_quat(quats)
    assert np.abs(g.as_rotvec() - r.as_rotvec()).max() < 1e-14
    assert np.abs(g.as_rotvec(degrees=True) - r.as_rotvec(degrees=True)).max() < 1e-12
    assert np.abs(g.as_mrp() - r.as_mrp()).max() < 4 * EPS
    assert np.abs(g.as_matrix() - r.as_matrix()).max() < 8 * EPS
    v = r.as_rotvec()
    assert angle_between(G.from_rotvec(v).as_quat(), quats).max() < 8 * EPS
    vd = np.degrees(v)
    assert angle_between(G.from_rotvec(vd, degrees=True).as_quat(), quats).max() < 1e-14
    p = r.as_mrp()
    assert angle_between(G.from_mrp(p).as_quat(), quats).max() < 8 * EPS
    # The shadow set (|p| > 1) is the same rotation.
    shadow = -p / np.sum(p * p, axis=1, keepdims=True)
    assert angle_between(G.from_mrp(shadow).as_quat(), quats).max() < 1e-13
    m = r.as_matrix()
    assert angle_between(G.from_matrix(m).as_quat(), quats).max() < 8 * EPS


def test_from_matrix_nearest_rotation_matches_scipy(quats):
    m = R.from_quat(quats).as_matrix()
    noisy = m + 1e-4 * np.random.default_rng(3).normal(size=m.shape)
    qg = G.from_matrix(noisy).as_quat()
    qs = R.from_matrix(noisy).as_quat()
    assert angle_between(qg, qs).max() < 1e-13


def test_half_turns_and_tiny_angles():
    rng = np.random.default_rng(4)
    axes = rng.normal(size=(500, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    # 180 degrees: the rotation vector has length pi (its sign is free), the MRP norm 1.
    half = G.from_rotvec(np.pi * axes)
    rv = half.as_rotvec()
    assert np.abs(np.linalg.norm(rv, axis=1) - np.pi).max() < 8 * EPS
    assert angle_between(G.from_rotvec(rv).as_quat(), half.as_quat()).max() < 8 * EPS
    assert np.abs(np.linalg.norm(half.as_mrp(), axis=1) - 1).max() < 4 * EPS
    assert np.abs(half.as_matrix() - R.from_rotvec(np.pi * axes).as_matrix()).max() < 8 * EPS
    assert np.abs(half.magnitude() - np.pi).max() < 8 * EPS
    # Tiny angles: relative accuracy kept (no 1 - cos cancellation).
    for a in [1e-8, 1e-12, 1e-200]:
        g = G.from_rotvec(a * axes)
        assert np.abs(g.as_rotvec() / a - axes).max() < 4 * EPS
        assert np.abs(g.as_mrp() / (a / 4) - axes).max() < 4 * EPS
        assert np.abs(g.magnitude() / a - 1).max() < 4 * EPS
        r = R.from_rotvec(a * axes)
        assert np.abs(g.as_rotvec() - r.as_rotvec()).max() <= 4 * EPS * a


def test_group_operations_match_scipy(quats):
    a, b = quats[: N // 2], quats[N // 2 :]
    ga, gb, ra, rb = G.from_quat(a), G.from_quat(b), R.from_quat(a), R.from_quat(b)
    assert angle_between((ga * gb).as_quat(), (ra * rb).as_quat()).max() < 8 * EPS
    assert angle_between(ga.inv().as_quat(), ra.inv().as_quat()).max() < 4 * EPS
    v = np.random.default_rng(5).normal(size=(N // 2, 3))
    assert np.abs(ga.apply(v) - ra.apply(v)).max() < 1e-14
    assert np.abs(ga.apply(v, inverse=True) - ra.apply(v, inverse=True)).max() < 1e-14
    assert np.abs(ga.magnitude() - ra.magnitude()).max() < 1e-14
    one = G.from_quat(a[0])
    assert one.single and one.as_quat().shape == (4,)
    assert np.abs((one * gb).as_quat() - (R.from_quat(a[0]) * rb).as_quat()).max() < 8 * EPS
    assert len(ga[1:5]) == 4 and ga[3].single
    assert np.abs(G.identity(3).as_matrix() - np.eye(3)).max() == 0


def test_bad_rows_raise_naming_the_row():
    q = random_unit_quats(10, seed=6)
    q[7] = 0.0
    with pytest.raises(GyrostatError, match=r"^row 7: quaternion has zero norm") as e:
        G.from_quat(q)
    assert e.value.row == 7
    for make, width, name in [
        (lambda x: G.from_euler("ZYX", x), 3, "angles"),
        (G.from_rotvec, 3, "rotation vector"),
        (G.from_mrp, 3, "MRP"),
        (G.from_quat, 4, "quaternion"),
    ]:
        x = np.ones((5, width)) * 0.1
        x[3, 1] = np.nan
        with pytest.raises(GyrostatError, match=rf"^row 3: {name} has a NaN") as e:
            make(x)
        assert e.value.row == 3
    m = np.tile(np.eye(3), (4, 1, 1))
    m[2] = np.diag([1.0, 1.0, -1.0])
    with pytest.raises(GyrostatError, match=r"^row 2: matrix has no nearest rotation"):
        G.from_matrix(m)
    with pytest.raises(GyrostatError, match="seq") as e:
        G.from_quat(q[:2]).as_euler("ZYz")
    assert e.value.row is None
    with pytest.raises(GyrostatError, match="shape"):
        G.from_quat(np.ones((3, 5)))
    assert issubclass(GyrostatError, ValueError)


@pytest.mark.parametrize("to", ["quat", "quat-xyzw", "matrix", "rotvec", "mrp", "euler:ZYX", "euler:zxz"])
def test_against_convert_tool(quats, to):
    """The `convert` tool (the library's CLI) on the same rows: the same numbers."""
    q = quats[:400]
    wxyz = np.roll(q, 1, axis=1)
    out = parse_csv(run_tool("convert", ["--from", "quat", "--to", to], csv_rows(wxyz)))
    g = G.from_quat(q)
    if to == "quat":
        mine = g.as_quat(canonical=True, scalar_first=True)
    elif to == "quat-xyzw":
        mine = g.as_quat(canonical=True)
    elif to == "matrix":
        mine = g.as_matrix().reshape(-1, 9)
    elif to == "rotvec":
        mine = g.as_rotvec()
    elif to == "mrp":
        mine = g.as_mrp()
    else:
        angles, lock = g.as_euler(to.split(":")[1], return_gimbal_lock=True)
        mine = np.column_stack([angles, lock.astype(float)])
    assert out.shape == mine.shape
    # The tool normalises with the library's scaled method, the package in one square root in
    # the normal range: the same to an ulp or two.
    assert np.abs(out - mine).max() < 8 * EPS


def test_from_tool_representations(quats):
    q = quats[:300]
    wxyz = np.roll(q, 1, axis=1)
    euler = parse_csv(run_tool("convert", ["--from", "quat", "--to", "euler:YXZ"], csv_rows(wxyz)))
    back = parse_csv(
        run_tool("convert", ["--from", "euler:YXZ", "--to", "quat"], csv_rows(euler[:, :3]))
    )
    mine = G.from_euler("YXZ", euler[:, :3]).as_quat(canonical=True, scalar_first=True)
    assert np.abs(back - mine).max() < 8 * EPS


def test_version_and_exports():
    assert set(gyrostat.__all__) <= set(dir(gyrostat))
