"""Why the hard-iron fit is inconsistent when fed often: the regressor's noise (issue 28 item 1).

A Python mirror of `HardIron::step` (src/estimation/hard_iron.rs: the 4-state Kalman filter
on `z = |u|^2 = 2 u.h + c`, its random walk of 1 % of the norm per 10 s, the prior), fed the
fixed magnet of the `synthesize` hard-iron tests (offset (21, -10.6, 16.5) uT, 0.2 uT of white
noise per axis, hand-held rotation) along each seed's true attitudes from t = 15 s, with the
noise drawn here so that one trajectory can be rerun with many noise draws. The measurement
noise R is fixed at its true value and the consistency resets are off, so that only the
regressor is varied:

  noisy   the samples as a magnetometer gives them: the noise in z and in H = (2u, 1)
  clean   the same z noise to first order, H from the noise-free sample
  debias  noisy, with the bias E[H nu] = (4 sigma^2 (u - h), 0) removed after each update
          (x -= P+ (u - h) / r^2, r the sphere's radius)

For each, fed every 20 ms and every 40 ms (each sample standing for its interval): the RMS over
the fed samples from t = 30 s of the error divided by the fit's own standard deviation, per
axis, mean over the seeds (a consistent filter: about 1 or below), and for one seed the mean
error over noise draws (the bias) against the spread of the error and the fit's sd.

    cargo build --release -p gyrostat-tools --bin synthesize
    /work/venv/bin/python benches/hard_iron/regressor_noise.py [--seeds 6] [--draws 12]
"""

import argparse
import math
import pathlib
import subprocess

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPEC = "rate = 100\nmag_noise = 0.2\nmag_hard_iron = 1.0, -0.6, 1.5\nmag_rate = 100\n"
FIELD = np.array([0.0, 15.8, -40.7])  # synthesize's default earth field, ENU, uT
OFFSET = np.array([21.0, -10.6, 16.5])  # the magnet plus the residual
SIGMA = 0.2  # uT per axis
SCALE = 42.06  # the estimator's reference norm on these logs (the first sample's norm)
DRIFT, TAU = 0.01, 10.0
R_TRUE = (2 * SIGMA * np.linalg.norm(FIELD) / SCALE**2) ** 2


def rot(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def trajectory(seed, synth):
    spec = pathlib.Path(f"/tmp/gyrostat-regressor-noise-{seed}.spec")
    spec.write_text(SPEC)
    out = subprocess.run([synth, "--sensor", str(spec), "--seed", str(seed), "--magnet-fixed",
                          "20,-10,15"], check=True, capture_output=True, text=True).stdout
    d = np.array([[float(v) if v else np.nan for v in line.split(",")]
                  for line in out.splitlines()[1:]])
    t, gyro, q = d[:, 0], d[:, 1:4], d[:, 10:14]
    keep = (t >= 15.0) & (np.linalg.norm(gyro, axis=1) >= math.radians(20))  # the feed gate
    return t[keep], np.array([rot(qi).T @ FIELD + OFFSET for qi in q[keep]])


def run(t, u_true, mode, every, rng):
    """The fit over the trajectory; returns [(t, error / sd per axis)], errors (uT) at t = 50 s."""
    x = np.array([0.0, 0.0, 0.0, 1.0])
    p = np.diag([4.0, 4.0, 4.0, 16.0])
    h = OFFSET / SCALE
    dt = 0.01 * every
    out, at50 = [], None
    for i in range(0, len(t), every):
        ut = u_true[i] / SCALE
        n = rng.normal(0.0, SIGMA, 3) / SCALE
        p[0, 0] += DRIFT**2 * dt / TAU
        p[1, 1] += DRIFT**2 * dt / TAU
        p[2, 2] += DRIFT**2 * dt / TAU
        p[3, 3] += 4 * DRIFT**2 * dt / TAU
        if mode == "clean":
            hv = np.array([*(2 * ut), 1.0])
            z = ut @ ut + 2 * (ut - h) @ n
        else:
            u = ut + n
            hv = np.array([*(2 * u), 1.0])
            z = u @ u
        innov = z - hv @ x
        ph = p @ hv
        s = hv @ ph + R_TRUE
        g = (u - x[:3]) / (x[3] + x[:3] @ x[:3]) if mode == "debias" else None
        x = x + ph / s * innov
        p = p - np.outer(ph, ph) / s
        if g is not None:
            x = x - p[:, :3] @ g
        sd = np.sqrt(np.diag(p)[:3]) * SCALE
        e = x[:3] * SCALE - OFFSET
        if t[i] >= 30.0:
            out.append(e / sd)
        if at50 is None and t[i] >= 50.0:
            at50 = (e, sd)
    return np.array(out), at50


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--draws", type=int, default=12)
    ap.add_argument("--synthesize", default=str(ROOT / "target/release/synthesize"))
    args = ap.parse_args()
    trajs = [trajectory(s, args.synthesize) for s in range(1, args.seeds + 1)]
    print(f"R = {math.sqrt(R_TRUE):.4f}^2 (squared reference norms); seeds 1-{args.seeds}")
    print("| regressor | feed | RMS error/sd x, y, z (mean over seeds) | largest |error|/sd |")
    print("|---|---|---|---|")
    for mode in ["noisy", "clean", "debias"]:
        for every in [2, 4]:
            rms, worst = [], 0.0
            for seed, (t, u) in enumerate(trajs, 1):
                r, _ = run(t, u, mode, every, np.random.default_rng(seed))
                rms.append(np.sqrt((r**2).mean(axis=0)))
                worst = max(worst, np.abs(r).max())
            m = np.mean(rms, axis=0)
            print(f"| {mode} | {10 * every} ms | {m[0]:.2f}, {m[1]:.2f}, {m[2]:.2f} | {worst:.1f} |")
    t, u = trajs[min(3, len(trajs)) - 1]
    print(f"\nseed {min(3, len(trajs))}, t = 50 s, {args.draws} noise draws: mean error (the bias), "
          "its spread and the fit's sd (uT; x, y, z)")
    for mode in ["noisy", "clean", "debias"]:
        for every in [2, 4]:
            res = [run(t, u, mode, every, np.random.default_rng(100 + k))[1]
                   for k in range(args.draws)]
            e = np.array([a for a, _ in res])
            sd = np.array([b for _, b in res]).mean(axis=0)
            print(f"{mode:6s} {10 * every} ms: bias {np.round(e.mean(axis=0), 2)}, spread "
                  f"{np.round(e.std(axis=0), 2)}, sd {np.round(sd, 2)}")


if __name__ == "__main__":
    main()
