#!/usr/bin/env python3
"""The synthetic benchmark grid: attitude estimators scored on logs with exact truth.

    cargo build --release -p gyrostat-tools --bin synthesize --bin estimate
    python3 benches/synthetic/grid.py                        # the whole grid, gyrostat's estimate
    python3 benches/synthetic/grid.py --quick                # a slice (seconds)
    python3 benches/synthetic/grid.py --vqf                  # + VQF (PyPI vqf: pip install vqf)
    python3 benches/synthetic/grid.py --estimator 'mine=path/to/filter {log} > {out}'
    python3 benches/synthetic/grid.py --set rest.gyro=0.05   # estimate with a parameter changed
    python3 benches/synthetic/grid.py --estimate-bin ../other/target/release/estimate  # another build
    python3 benches/synthetic/grid.py --params-from-sensor   # estimate with each sensor's parameters

Grid: sample rate (--rates, default 25, 50, 100, 285.714285714 (BROAD's), 1000 Hz) x sensor
grade (--sensors, the presets of `synthesize --sensor`: consumer, industrial, tactical) x
disturbance (--disturbances: none, translation, vibration, passing-magnet, fixed-magnet; also
taps and steel) x seed (--seeds N: 0..N-1, default 3). Each cell is one log of
`synthesize --motion handheld` (a 5 s rest, two 30 s phases of smooth, non-repeating hand-held
rotation with a 5 s rest between; --duration, --phases, --rest change that) at that rate, with
that sensor and disturbance and seed; the seed draws the motion, the noise and the jitter.

Disturbances (the flags given to synthesize):
    none            -
    translation     --translation 0.3        (about 4.5 m/s^2 peak linear acceleration)
    vibration       --vibration 5,30         (5 m/s^2 body-frame vibration near 30 Hz; aliased
                                              at 25 and 50 Hz, as an IMU without anti-alias
                                              filtering would see it)
    passing-magnet  --magnet-pass 1,0.2,0.05 (a 1 A m^2 dipole passing 0.2 m away at 5 cm/s in
                                              the middle of each phase: up to 25 uT)
    fixed-magnet    --magnet-fixed 20,-10,15 (a magnet fixed on the device a third into the
                                              first phase: 27 uT of extra hard iron)
    taps            --taps 30                (a 60 Hz pulse decaying in 10 ms, peak 20 m/s^2,
                                              every 1.5-3 s)
    steel           --steel 10,-8,12         (the field changes by up to 18 uT near steel)

Parameters: `estimate` runs with its defaults (a consumer MEMS IMU's figures) unless
--params-from-sensor: then, per sensor and rate, a 300 s rest log of that sensor (`synthesize
--motion rest`, seed 1000: not a seed of the grid) is characterised (`characterize --params`:
the gyroscope's noise density and bias stability from its Allan deviation) and every cell of
that sensor and rate is estimated with `--params FILE` (before any --set).

Scoring: BROAD's metric (total / heading / inclination RMSE in degrees over the movement phases,
score.py's definition). gyrostat's `estimate` is scored by its own `--truth` (the same metric,
computed from the numbers it prints; checked equal to score.py on the first cell when score.py is
found). Other estimators write a CSV (header, then t_s or t, qw, qx, qy, qz: sensor -> earth, ENU)
scored by BROAD's score.py, imported from --score (default ../shared/real-data/broad/score.py
beside the repository); without it they are skipped with a message.

Plugging in an estimator: --estimator 'LABEL=CMD' (repeatable) runs CMD through the shell from the
repository root for every cell, {log} the log's path (CSV, BROAD's columns: t_s, gyr_*_rad_s,
acc_*_m_s2, mag_*_uT, opt_q*, movement; rows without a new magnetometer sample have empty mag
fields), {out} the CSV to write, {rate} the nominal rate (Hz). A LABEL ending in "6D" is scored
on inclination only. In Python, add a function to PEERS below (arrays in, quaternions out): VQF
is the example (`--vqf`: vqf.VQF(1/rate) with default parameters, online (updateBatch), 9D and
6D; an empty magnetometer row repeats the last sample).

Output: a markdown table per estimator (rows: sensor x disturbance; columns: rates; cells: total
RMSE mean over seeds, inclination in brackets) on stdout and in --markdown FILE, every cell and
seed in --json FILE and --csv FILE (defaults under target/synthetic-grid/). Logs are written to
target/synthetic-grid/logs/ and deleted after scoring unless --keep.

Exit status: 0; 1 if a tool fails; 2 for a bad command line.
"""
import argparse
import csv
import importlib.util
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "target" / "synthetic-grid"

RATES = [25.0, 50.0, 100.0, 285.714285714, 1000.0]
SENSORS = ["consumer", "industrial", "tactical"]
DISTURBANCES = {
    "none": [],
    "translation": ["--translation", "0.3"],
    "vibration": ["--vibration", "5,30"],
    "passing-magnet": ["--magnet-pass", "1,0.2,0.05"],
    "fixed-magnet": ["--magnet-fixed", "20,-10,15"],
    "taps": ["--taps", "30"],
    "steel": ["--steel", "10,-8,12"],
}
DEFAULT_DISTURBANCES = ["none", "translation", "vibration", "passing-magnet", "fixed-magnet"]
TRUTH = re.compile(
    r"truth: total (\S+) deg, heading (\S+) deg, inclination (\S+) deg, n = (\d+)(, MISSING (\d+))?"
)


def rate_label(r):
    return f"{r:g}" if abs(r - round(r)) < 1e-9 else f"{r:.1f}"


# --- peers in Python ---------------------------------------------------------------------------


def read_log(path):
    """The log's arrays (numpy): t, gyr, acc, mag (NaN rows where empty)."""
    import numpy as np

    with open(path, newline="") as f:
        rd = csv.reader(f)
        head = next(rd)
        rows = list(rd)
    col = {h: i for i, h in enumerate(head)}

    def arr(names):
        return np.array(
            [[float(r[col[n]]) if r[col[n]] else math.nan for n in names] for r in rows]
        )

    return dict(
        t=arr(["t_s"])[:, 0],
        gyr=arr(["gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s"]),
        acc=arr(["acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"]),
        mag=arr(["mag_x_uT", "mag_y_uT", "mag_z_uT"]),
    )


def hold_last(mag):
    """Empty magnetometer rows repeat the last sample (the first row always has one)."""
    import numpy as np

    out = mag.copy()
    for i in range(1, len(out)):
        if not np.all(np.isfinite(out[i])):
            out[i] = out[i - 1]
    return out


def peer_vqf(log, rate):
    """VQF (PyPI vqf), default parameters, online: {'VQF 9D': quats, 'VQF 6D': quats}."""
    import numpy as np
    from vqf import VQF

    v = VQF(1.0 / rate)
    out = v.updateBatch(
        np.ascontiguousarray(log["gyr"]),
        np.ascontiguousarray(log["acc"]),
        np.ascontiguousarray(hold_last(log["mag"])),
    )
    return {"VQF 9D": out["quat9D"], "VQF 6D": out["quat6D"]}


PEERS = {"vqf": peer_vqf}


# --- the grid ------------------------------------------------------------------------------------


def load_score(path):
    if not path.exists():
        return None
    spec = importlib.util.spec_from_file_location("broad_score", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def run(cmd, **kw):
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        raise RuntimeError(f"{cmd if isinstance(cmd, str) else shlex.join(map(str, cmd))}: "
                           f"exit {p.returncode}: {p.stderr.strip()[-500:]}")
    return p


def write_estimate(path, t, quats):
    with open(path, "w") as f:
        f.write("t_s,qw,qx,qy,qz\n")
        for ti, q in zip(t, quats):
            f.write(f"{ti:.9f}," + ",".join(repr(float(x)) for x in q) + "\n")


def score_file(score, log, est, six):
    r = score.score(score.load_trial(str(log)), score.load_estimate(str(est)))
    if six:
        r["total"] = r["heading"] = math.nan
    return r


def cell(args, score, rate, sensor, dist, seed, check_score):
    name = f"{sensor}_{dist}_{rate_label(rate)}Hz_seed{seed}"
    logs = OUT / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    log = logs / f"{name}.csv"
    synth = [str(args.bin / "synthesize"), "--sensor", sensor, "--rate", repr(rate),
             "--seed", str(seed), "--duration", str(args.duration), "--phases", str(args.phases),
             "--rest", str(args.rest), *DISTURBANCES[dist]]
    with open(log, "w") as f:
        p = subprocess.run(synth, stdout=f, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(synth)}: {p.stderr.strip()}")
    results = []
    est_out = logs / f"{name}.estimate.csv"
    params = ["--params", str(args.params[(sensor, rate)])] if args.params else []
    est = [str(args.estimate_bin), "--truth", *params,
           *sum((["--set", s] for s in args.set), []), str(log)]
    with open(est_out, "w") as f:
        p = subprocess.run(est, stdout=f, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(est)}: {p.stderr.strip()}")
    m = TRUTH.search(p.stderr)
    if not m:
        raise RuntimeError(f"{shlex.join(est)}: no truth line in {p.stderr!r}")
    r = dict(total=float(m[1]), heading=float(m[2]), inclination=float(m[3]), n=int(m[4]),
             missing=int(m[6] or 0))
    if check_score and score is not None:
        s = score_file(score, log, est_out, False)
        for k in ("total", "heading", "inclination"):
            if abs(s[k] - r[k]) > 1e-3:
                raise RuntimeError(f"{name}: estimate --truth {k} {r[k]} != score.py {s[k]}")
    results.append(("estimate", r))
    if score is not None and (args.peers or args.estimator):
        if args.peers:
            data = read_log(log)
            for peer in args.peers:
                for label, quats in PEERS[peer](data, rate).items():
                    out = logs / f"{name}.{label.replace(' ', '_')}.csv"
                    write_estimate(out, data["t"], quats)
                    results.append((label, score_file(score, log, out, label.endswith("6D"))))
                    out.unlink()
        for label, cmd in args.estimator:
            out = logs / f"{name}.{re.sub(r'[^A-Za-z0-9]+', '_', label)}.csv"
            run(cmd.format(log=shlex.quote(str(log)), out=shlex.quote(str(out)), rate=rate),
                shell=True, cwd=ROOT)
            results.append((label, score_file(score, log, out, label.endswith("6D"))))
            if not args.keep:
                out.unlink()
    if not args.keep:
        log.unlink()
        est_out.unlink()
    return [dict(estimator=e, rate=rate, sensor=sensor, disturbance=dist, seed=seed, **r)
            for e, r in results]


def sensor_params(args, sensor, rate):
    """The parameter file `characterize --params` writes from a 300 s rest log of the sensor."""
    d = OUT / "params"
    d.mkdir(parents=True, exist_ok=True)
    log = d / f"{sensor}_{rate_label(rate)}Hz_rest.csv"
    path = d / f"{sensor}_{rate_label(rate)}Hz.params"
    synth = [str(args.bin / "synthesize"), "--sensor", sensor, "--rate", repr(rate), "--motion",
             "rest", "--rest", "300", "--phases", "1", "--duration", "1", "--seed", "1000"]
    with open(log, "w") as f:
        p = subprocess.run(synth, stdout=f, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(synth)}: {p.stderr.strip()}")
    run([str(args.bin / "characterize"), "--params", str(path), str(log)])
    log.unlink()
    return path


def table(rows, estimator, args):
    lines = [f"**{estimator}**: total RMSE (deg) mean over {args.seeds} seed(s), "
             "(inclination) in brackets", "",
             "| sensor | disturbance | " + " | ".join(f"{rate_label(r)} Hz" for r in args.rates) + " |",
             "|---|---|" + "---:|" * len(args.rates)]
    for sensor in args.sensors:
        for dist in args.disturbances:
            cells = []
            for rate in args.rates:
                sel = [r for r in rows if r["estimator"] == estimator and r["sensor"] == sensor
                       and r["disturbance"] == dist and r["rate"] == rate]
                if not sel:
                    cells.append("-")
                    continue
                tot = sum(r["total"] for r in sel) / len(sel)
                inc = sum(r["inclination"] for r in sel) / len(sel)
                cells.append(f"{tot:.2f} ({inc:.2f})" if not math.isnan(tot) else f"({inc:.2f})")
            lines.append(f"| {sensor} | {dist} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rates", default=",".join(map(repr, RATES)))
    ap.add_argument("--sensors", default=",".join(SENSORS))
    ap.add_argument("--disturbances", default=",".join(DEFAULT_DISTURBANCES))
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--duration", type=float, default=30.0)
    ap.add_argument("--phases", type=int, default=2)
    ap.add_argument("--rest", type=float, default=5.0)
    ap.add_argument("--quick", action="store_true",
                    help="a slice: 25 and 285.7 Hz, consumer, none and passing-magnet, 1 seed, 10 s")
    ap.add_argument("--vqf", action="store_true", help="also run VQF (PyPI vqf)")
    ap.add_argument("--estimator", action="append", default=[], metavar="LABEL=CMD")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="an estimate parameter (estimate --set)")
    ap.add_argument("--bin", type=Path, default=ROOT / "target" / "release",
                    help="the directory of the synthesize and estimate binaries")
    ap.add_argument("--estimate-bin", type=Path, default=None,
                    help="the estimate binary to score (default: BIN/estimate), e.g. another "
                         "checkout's target/release/estimate")
    ap.add_argument("--score", type=Path, default=ROOT.parent / "shared" / "real-data" / "broad" / "score.py")
    ap.add_argument("--params-from-sensor", action="store_true",
                    help="estimate with the parameters characterize --params finds on a rest "
                         "log of each sensor (per rate)")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--keep", action="store_true", help="keep the logs and estimates")
    ap.add_argument("--markdown", type=Path, default=OUT / "grid.md")
    ap.add_argument("--json", type=Path, default=OUT / "grid.json")
    ap.add_argument("--csv", type=Path, default=OUT / "grid.csv")
    args = ap.parse_args(argv)
    if args.quick:
        args.rates, args.sensors, args.disturbances = "25,285.714285714", "consumer", "none,passing-magnet"
        args.seeds, args.duration = 1, 10.0
    try:
        args.rates = [float(r) for r in args.rates.split(",")]
    except ValueError:
        ap.error(f"--rates: not numbers: {args.rates}")
    args.sensors = args.sensors.split(",")
    args.disturbances = args.disturbances.split(",")
    for d in args.disturbances:
        if d not in DISTURBANCES:
            ap.error(f"--disturbances: unknown '{d}' (one of {', '.join(DISTURBANCES)})")
    args.estimator = [tuple(e.split("=", 1)) for e in args.estimator]
    if any(len(e) != 2 for e in args.estimator):
        ap.error("--estimator takes LABEL=CMD")
    args.peers = ["vqf"] if args.vqf else []
    args.estimate_bin = args.estimate_bin or args.bin / "estimate"
    for exe in (args.bin / "synthesize", args.estimate_bin):
        if not exe.exists():
            ap.error(f"{exe} not found: cargo build --release -p gyrostat-tools "
                     "--bin synthesize --bin estimate")
    args.params = {}
    if args.params_from_sensor:
        if not (args.bin / "characterize").exists():
            ap.error(f"{args.bin / 'characterize'} not found: cargo build --release -p "
                     "gyrostat-tools --bin characterize")
        try:
            args.params = {(s, r): sensor_params(args, s, r) for s in args.sensors
                           for r in args.rates}
        except RuntimeError as e:
            print(f"error: {e}", file=sys.stderr)
            return 1
    score = load_score(args.score)
    if score is None and (args.peers or args.estimator):
        print(f"note: {args.score} not found: the other estimators are skipped", file=sys.stderr)
    cells = [(rate, sensor, dist, seed) for sensor in args.sensors for dist in args.disturbances
             for rate in args.rates for seed in range(args.seeds)]
    start = time.time()
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = [pool.submit(cell, args, score, *c, i == 0) for i, c in enumerate(cells)]
        rows = []
        try:
            for fu in futures:
                rows.extend(fu.result())
        except RuntimeError as e:
            print(f"error: {e}", file=sys.stderr)
            return 1
    estimators = list(dict.fromkeys(r["estimator"] for r in rows))
    text = "\n\n".join(table(rows, e, args) for e in estimators)
    head = (f"Synthetic grid: {len(cells)} logs ({len(args.rates)} rates x {len(args.sensors)} "
            f"sensors x {len(args.disturbances)} disturbances x {args.seeds} seeds; hand-held "
            f"motion, {args.phases} x {args.duration:g} s), {time.time() - start:.0f} s"
            + ("; estimate with each sensor's characterised parameters"
               if args.params else ""))
    print(head + "\n\n" + text)
    for path in (args.markdown, args.json, args.csv):
        path.parent.mkdir(parents=True, exist_ok=True)
    args.markdown.write_text(head + "\n\n" + text + "\n")
    args.json.write_text(json.dumps(rows, indent=1))
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
