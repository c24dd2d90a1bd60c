"""Throughput of gyrostat's numpy conversions beside scipy's Rotation on the same 10**6
attitudes, in one process (BENCHMARKS.md, "Python conversions").

    python3 python/benches/conversions.py [--n 1000000] [--repeat 5]

Each row times the same conversion in both packages on the same input: the best of
``--repeat`` runs, in millions of attitudes per second. Both run on one thread (gyrostat's
conversions release the GIL but do not start threads), timed by the process's CPU time (user
plus system, so page faults count) rather than the wall clock, which on a shared machine
measures the other processes too. The inputs are
random unit quaternions (normal components, normalised), their Euler angles, rotation vectors,
MRPs and matrices as scipy computes them. Before timing, each pair of outputs is compared (the
largest difference is printed), so that both rows compute the same thing.
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np
import scipy
from scipy.spatial.transform import Rotation as R

import gyrostat
from gyrostat import Rotation as G


def best(f, repeat: int) -> float:
    f()  # warm up (allocation, lazy imports)
    t = []
    for _ in range(repeat):
        t0 = time.process_time()
        f()
        t.append(time.process_time() - t0)
    return min(t)


def same_rotation(qa: np.ndarray, qb: np.ndarray) -> float:
    """The largest angle (rad) between rows of unit quaternions: 4 atan2(|a - b|, |a + b|)
    on the nearer sign (accurate for small angles, unlike an arccos of the dot product)."""
    d, s = np.linalg.norm(qa - qb, axis=1), np.linalg.norm(qa + qb, axis=1)
    return float(np.max(4.0 * np.arctan2(np.minimum(d, s), np.maximum(d, s))))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    n, rep = args.n, args.repeat
    rng = np.random.default_rng(20)
    quat = rng.normal(size=(n, 4))
    quat /= np.linalg.norm(quat, axis=1, keepdims=True)
    rs = R.from_quat(quat)
    rg = G.from_quat(quat)
    euler = rs.as_euler("ZYX")
    rotvec = rs.as_rotvec()
    mrp = rs.as_mrp()
    matrix = rs.as_matrix()

    rows = [
        ("from_quat", lambda: R.from_quat(quat), lambda: G.from_quat(quat),
         lambda a, b: same_rotation(a.as_quat(), b.as_quat())),
        ("as_quat", lambda: rs.as_quat(), lambda: rg.as_quat(),
         lambda a, b: float(np.max(np.abs(a - b)))),
        ("as_quat(scalar_first=True)", lambda: rs.as_quat(scalar_first=True),
         lambda: rg.as_quat(scalar_first=True), lambda a, b: float(np.max(np.abs(a - b)))),
        ("as_quat(canonical=True)", lambda: rs.as_quat(canonical=True),
         lambda: rg.as_quat(canonical=True), lambda a, b: float(np.max(np.abs(a - b)))),
        ("from_euler('ZYX')", lambda: R.from_euler("ZYX", euler),
         lambda: G.from_euler("ZYX", euler), lambda a, b: same_rotation(a.as_quat(), b.as_quat())),
        ("as_euler('ZYX')", lambda: rs.as_euler("ZYX"), lambda: rg.as_euler("ZYX"),
         lambda a, b: float(np.max(np.abs(a - b)))),
        ("from_rotvec", lambda: R.from_rotvec(rotvec), lambda: G.from_rotvec(rotvec),
         lambda a, b: same_rotation(a.as_quat(), b.as_quat())),
        ("as_rotvec", lambda: rs.as_rotvec(), lambda: rg.as_rotvec(),
         lambda a, b: float(np.max(np.abs(a - b)))),
        ("from_mrp", lambda: R.from_mrp(mrp), lambda: G.from_mrp(mrp),
         lambda a, b: same_rotation(a.as_quat(), b.as_quat())),
        ("as_mrp", lambda: rs.as_mrp(), lambda: rg.as_mrp(),
         lambda a, b: float(np.max(np.abs(a - b)))),
        ("from_matrix", lambda: R.from_matrix(matrix), lambda: G.from_matrix(matrix),
         lambda a, b: same_rotation(a.as_quat(), b.as_quat())),
        ("as_matrix", lambda: rs.as_matrix(), lambda: rg.as_matrix(),
         lambda a, b: float(np.max(np.abs(a - b)))),
        ("apply", lambda: rs.apply(rotvec), lambda: rg.apply(rotvec),
         lambda a, b: float(np.max(np.abs(a - b)))),
        ("a * b (compose)", lambda: rs * rs, lambda: rg * rg,
         lambda a, b: same_rotation(a.as_quat(), b.as_quat())),
    ]
    print(f"{n} attitudes, best of {rep} (CPU time); Python {platform.python_version()}, numpy "
          f"{np.__version__}, scipy {scipy.__version__}, gyrostat (pip install ./python, release); "
          f"{platform.processor() or platform.machine()}")
    print()
    print("| conversion | scipy (M/s) | gyrostat (M/s) | gyrostat / scipy | max difference |")
    print("|---|---:|---:|---:|---:|")
    for name, fs, fg, diff in rows:
        d = diff(fs(), fg())
        ts, tg = best(fs, rep), best(fg, rep)
        print(f"| `{name}` | {n / ts / 1e6:.1f} | {n / tg / 1e6:.1f} | {ts / tg:.2f}x | {d:.1e} |")


if __name__ == "__main__":
    main()
