#!/usr/bin/env python3
"""The synthetic benchmark grid: attitude estimators scored on logs with exact truth.

    cargo build --release -p gyrostat-tools --bin synthesize --bin estimate
    python3 benches/synthetic/grid.py                        # the whole grid, gyrostat's estimate
    python3 benches/synthetic/grid.py --quick                # a slice (seconds)
    python3 benches/synthetic/grid.py --vqf                  # + VQF (PyPI vqf: pip install vqf)
    python3 benches/synthetic/grid.py --peers vqf,fusion,madgwick:9d,mahony:9d --jobs 2
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
the gyroscope's noise density and bias stability from its Allan deviation; plus `gyro_delay =
0`, the synthetic sensors' group delay, which a rest log cannot show) and every cell of that
sensor and rate is estimated with `--params FILE` (before any --set).

Scoring: BROAD's metric (total / heading / inclination RMSE in degrees over the movement phases,
score.py's definition). gyrostat's `estimate` is scored by its own `--truth` (the same metric,
computed from the numbers it prints; checked equal to score.py on the first cell when score.py is
found). Other estimators write a CSV (header, then t_s or t, qw, qx, qy, qz: sensor -> earth, ENU)
scored by BROAD's score.py, imported from --score (default ../shared/real-data/broad/score.py
beside the repository); without it they are skipped with a message.

Plugging in an estimator: --estimator 'LABEL=CMD' (repeatable) runs CMD through the shell from the
repository root for every cell, {log} the log's path (CSV, BROAD's columns: t_s, gyr_*_rad_s,
acc_*_m_s2, mag_*_uT, opt_q*, movement; rows without a new magnetometer sample have empty mag
fields), {out} the CSV to write, {rate} the nominal rate (Hz), {params} `--params FILE` with
--params-from-sensor (the cell's sensor and rate; empty without it). A LABEL ending in "6D" is
scored on inclination only.

Python peers (--peers LIST; --vqf is --peers vqf): vqf, fusion, madgwick, mahony, each 9D and 6D
(`madgwick:9d`: 9D only), from benches/peers.py: the code, settings and frame mappings
benches/broad/run_peers.py uses on BROAD (VQF 2.1.2 and Fusion with their defaults; Madgwick
beta 0.12 and Mahony kP 0.74 / kI 0.0012, BROAD's best common gains: the same gains here, not
re-tuned for the grid), online from the first sample with BROAD's initialisation rule, the
nominal period 1/rate, an empty magnetometer row repeating the last sample. To add one, add an
entry to PEERS below (arrays in, quaternions out, sensor -> ENU). The ahrs filters (Madgwick,
Mahony) are pure Python: measured 234 and 284 us per 9D update on the 2 shared cores (their 6D
two thirds to three quarters of that; VQF 2, Fusion 5, `estimate` 10 us with its process and
CSV), so their 9D takes about 18 and 22 core-minutes on this script's default grid (225 logs of
70 s), 5 and 6 on benches/evaluate.py's (150 logs of 30 s). Peers' scores are cached under
target/synthetic-grid/peer-cache/ against the log's bytes and the peer's settings (--force-peers reruns them). Frames: every peer
(and with --check-frames `estimate`) is also scored over each log's initial rest phase, the
worst log printed per estimator, and above 20 deg the run fails (a wrong frame gives about 90).
Cells run in --jobs processes (the Python peers hold the GIL); the rows come in the cells' order.

Output: a markdown table per estimator (rows: sensor x disturbance; columns: rates; cells: total
RMSE mean over seeds, inclination in brackets) on stdout and in --markdown FILE, every cell and
seed in --json FILE and --csv FILE (defaults under target/synthetic-grid/). Logs are written to
target/synthetic-grid/logs/ and deleted after scoring unless --keep.

Exit status: 0; 1 if a tool fails or an estimator fails the rest-phase check; 2 for a bad
command line.
"""
import argparse
import csv
import hashlib
import importlib.util
import json
import math
import os
import re
import shlex
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "target" / "synthetic-grid"
sys.path.insert(0, str(ROOT / "benches"))
import peers  # noqa: E402  (benches/peers.py)

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

    with open(path) as f:
        head = f.readline().strip().split(",")
        a = np.genfromtxt(f, delimiter=",", dtype=float, filling_values=np.nan)
    a = np.atleast_2d(a)
    col = {h: i for i, h in enumerate(head)}

    def arr(names):
        return np.ascontiguousarray(a[:, [col[n] for n in names]])

    return dict(
        t=arr(["t_s"])[:, 0],
        gyr=arr(["gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s"]),
        acc=arr(["acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"]),
        mag=arr(["mag_x_uT", "mag_y_uT", "mag_z_uT"]),
    )


class PeerLog:
    """A grid log as benches/peers.py reads it: the magnetometer held between its samples (an
    empty row repeats the last sample), the nominal period 1/rate."""

    def __init__(self, log, rate, name):
        self.gyr, self.acc = log["gyr"], log["acc"]
        self.mag = peers.hold_last(log["mag"])
        self.ts = 1.0 / rate
        self.stem = name


def _family(labels):
    """The peer functions of benches/peers.py with these labels: [(label, description, fn)]."""
    table = {label: (desc, fn) for label, _, desc, fn in peers.peer_table()}
    return [(label, *table[label]) for label in labels]


# Python peers (benches/peers.py: the same code, settings and frame mappings as
# benches/broad/run_peers.py on BROAD, BROAD's best common gains for Madgwick and Mahony, not
# re-tuned for the grid): name -> [(label, description, fn(PeerLog) -> (n, 4) quats)].
PEERS = {
    "vqf": _family(["VQF 9D", "VQF 6D"]),
    "fusion": _family(["Fusion 9D", "Fusion 6D"]),
    "madgwick": _family(["Madgwick 9D", "Madgwick 6D"]),
    "mahony": _family(["Mahony 9D", "Mahony 6D"]),
}


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


_SCORE = {}


def score_module(path):
    """score.py, loaded once per process (None when absent)."""
    if path not in _SCORE:
        _SCORE[path] = load_score(Path(path))
    return _SCORE[path]


def score_rows(score, trial, est, six):
    """BROAD's metric over the movement phase, and over the initial rest phase ("rest": rows with
    a reference before the first movement row; a wrong frame is off by tens of degrees there)."""
    r = score.score(trial, est)
    first = next((i for i, row in enumerate(trial) if row[2]), len(trial))
    rest_rows = [(t, q, i < first and q is not None) for i, (t, q, _) in enumerate(trial)]
    rest = score.score(rest_rows, est)
    r["rest"] = rest["inclination" if six else "total"] if rest["n"] else math.nan
    if six:
        r["total"] = r["heading"] = math.nan
    return r


def score_file(score, log, est, six):
    return score_rows(score, score.load_trial(str(log)), score.load_estimate(str(est)), six)


def peer_results(args, score, log, rate, name):
    """Every requested Python peer on one log, scored; cached under OUT/peer-cache against the
    log's bytes and the peer's description (the peers are deterministic: a rerun on the same log
    gives the same numbers), so a rerun after a change of gyrostat reruns only gyrostat."""
    with open(log, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()[:32]
    results, todo = [], []
    for label, desc, fn in args.peer_list:
        key = hashlib.sha256(f"{label}|{desc}|{rate!r}|{digest}".encode()).hexdigest()[:32]
        path = OUT / "peer-cache" / re.sub(r"[^a-z0-9]+", "-", label.lower()) / f"{key}.json"
        if path.exists() and not args.force_peers:
            r = json.loads(path.read_text())
            r["seconds"] = 0.0
            results.append((label, r))
        else:
            results.append((label, None))
            todo.append((len(results) - 1, label, fn, path))
    if todo:
        data = read_log(log)
        plog = PeerLog(data, rate, name)
        trial = score.load_trial(str(log))
        est_t = [round(r[0] * 1e6) for r in trial]
        for k, label, fn, path in todo:
            t0 = time.time()
            quats = fn(plog)
            secs = time.time() - t0
            est = {t: tuple(float(v) for v in q) for t, q in zip(est_t, quats)}
            r = score_rows(score, trial, est, label.endswith("6D"))
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps(r))
            r["seconds"] = secs
            results[k] = (label, r)
    return results


def cell(args, rate, sensor, dist, seed, check_score):
    score = score_module(str(args.score))
    name = f"{sensor}_{dist}_{rate_label(rate)}Hz_seed{seed}"
    logs = OUT / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    # The process id keeps two runs at the same time (another --duration, say) apart.
    log = logs / f"{name}.{os.getpid()}.csv"
    synth = [str(args.bin / "synthesize"), "--sensor", sensor, "--rate", repr(rate),
             "--seed", str(seed), "--duration", str(args.duration), "--phases", str(args.phases),
             "--rest", str(args.rest), *DISTURBANCES[dist]]
    with open(log, "w") as f:
        p = subprocess.run(synth, stdout=f, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(synth)}: {p.stderr.strip()}")
    results = []
    est_out = log.with_suffix(".estimate.csv")
    params = ["--params", str(args.params[(sensor, rate)])] if args.params else []
    est = [str(args.estimate_bin), "--truth", *params,
           *sum((["--set", s] for s in args.set), []), str(log)]
    t0 = time.time()
    with open(est_out, "w") as f:
        p = subprocess.run(est, stdout=f, stderr=subprocess.PIPE, text=True)
    secs = time.time() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(est)}: {p.stderr.strip()}")
    m = TRUTH.search(p.stderr)
    if not m:
        raise RuntimeError(f"{shlex.join(est)}: no truth line in {p.stderr!r}")
    r = dict(total=float(m[1]), heading=float(m[2]), inclination=float(m[3]), n=int(m[4]),
             missing=int(m[6] or 0), seconds=secs)
    if score is not None and (check_score or args.check_frames):
        s = score_file(score, log, est_out, False)
        if check_score:
            for k in ("total", "heading", "inclination"):
                if abs(s[k] - r[k]) > 1e-3:
                    raise RuntimeError(f"{name}: estimate --truth {k} {r[k]} != score.py {s[k]}")
        r["rest"] = s["rest"]
    results.append(("estimate", r))
    if score is not None and (args.peer_list or args.estimator):
        if args.peer_list:
            results.extend(peer_results(args, score, log, rate, name))
        for label, cmd in args.estimator:
            out = log.with_suffix(f".{re.sub(r'[^A-Za-z0-9]+', '_', label)}.csv")
            t0 = time.time()
            run(cmd.format(log=shlex.quote(str(log)), out=shlex.quote(str(out)), rate=rate,
                           params=shlex.join(params)),
                shell=True, cwd=ROOT)
            secs = time.time() - t0
            r = score_file(score, log, out, label.endswith("6D"))
            r["seconds"] = secs
            results.append((label, r))
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
    # What a rest log cannot show but the sensor's spec states: `synthesize` samples the motion
    # at the time stamps (no low-pass), so the gyroscope's group delay is 0, not the default's
    # 2.9 ms of a consumer MEMS low-pass (BENCHMARKS, "The grid's inclination against VQF").
    with open(path, "a") as f:
        f.write("# the gyroscope's group delay: synthesize samples the motion at its time stamps\n"
                "gyro_delay = 0\n")
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


def add_grid_flags(ap, seeds=3, duration=30.0):
    """The flags that define the grid and its estimators (shared with benches/evaluate.py)."""
    ap.add_argument("--rates", default=",".join(map(repr, RATES)))
    ap.add_argument("--sensors", default=",".join(SENSORS))
    ap.add_argument("--disturbances", default=",".join(DEFAULT_DISTURBANCES))
    ap.add_argument("--seeds", type=int, default=seeds)
    ap.add_argument("--duration", type=float, default=duration)
    ap.add_argument("--phases", type=int, default=2)
    ap.add_argument("--rest", type=float, default=5.0)
    ap.add_argument("--estimator", action="append", default=[], metavar="LABEL=CMD")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="an estimate parameter (estimate --set)")
    ap.add_argument("--bin", type=Path, default=ROOT / "target" / "release",
                    help="the directory of the synthesize and estimate binaries")
    ap.add_argument("--estimate-bin", type=Path, default=None,
                    help="the estimate binary to score (default: BIN/estimate), e.g. another "
                         "checkout's target/release/estimate")
    ap.add_argument("--params-from-sensor", action="store_true",
                    help="estimate with the parameters characterize --params finds on a rest "
                         "log of each sensor (per rate)")
    ap.add_argument("--force-peers", action="store_true",
                    help="rerun the Python peers even when their score is cached")
    ap.add_argument("--keep", action="store_true", help="keep the logs and estimates")


def parse_peers(ap, spec):
    """--peers: names of PEERS, each optionally :9d or :6d -> [(label, description, fn)]."""
    out = []
    for item in filter(None, (x.strip() for x in spec.split(","))):
        name, _, dim = item.lower().partition(":")
        if name not in PEERS or dim not in ("", "9d", "6d"):
            ap.error(f"--peers: unknown '{item}' (one of {', '.join(PEERS)}, each optionally "
                     ":9d or :6d)")
        out += [p for p in PEERS[name] if not dim or p[0].lower().endswith(dim)]
    return list({p[0]: p for p in out}.values())


def check_grid_args(ap, args):
    """Parses the grid flags in place; exits through ap.error on a bad one."""
    try:
        args.rates = [float(r) for r in str(args.rates).split(",")]
    except ValueError:
        ap.error(f"--rates: not numbers: {args.rates}")
    args.sensors = args.sensors.split(",")
    args.disturbances = args.disturbances.split(",")
    for d in args.disturbances:
        if d not in DISTURBANCES:
            ap.error(f"--disturbances: unknown '{d}' (one of {', '.join(DISTURBANCES)})")
    if args.seeds < 1:
        ap.error("--seeds needs a whole number >= 1")
    args.estimator = [tuple(e.split("=", 1)) for e in args.estimator]
    if any(len(e) != 2 for e in args.estimator):
        ap.error("--estimator takes LABEL=CMD")
    args.estimate_bin = args.estimate_bin or args.bin / "estimate"
    for exe in (args.bin / "synthesize", args.estimate_bin):
        if not exe.exists():
            ap.error(f"{exe} not found: cargo build --release -p gyrostat-tools "
                     "--bin synthesize --bin estimate")
    if args.params_from_sensor and not (args.bin / "characterize").exists():
        ap.error(f"{args.bin / 'characterize'} not found: cargo build --release -p "
                 "gyrostat-tools --bin characterize")


def run_grid(args, progress=None):
    """Every cell of the grid (sensors x disturbances x rates x seeds), in args.jobs processes.
    Returns the rows (one per estimator and cell, in the cells' order: deterministic whatever
    the number of jobs). Raises RuntimeError when a tool fails."""
    args.params = {}
    if args.params_from_sensor:
        args.params = {(s, r): sensor_params(args, s, r) for s in args.sensors
                       for r in args.rates}
    cells = [(rate, sensor, dist, seed) for sensor in args.sensors for dist in args.disturbances
             for rate in args.rates for seed in range(args.seeds)]
    rows = []
    with ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = [pool.submit(cell, args, *c, i == 0) for i, c in enumerate(cells)]
        try:
            for i, fu in enumerate(futures):
                rows.extend(fu.result())
                if progress:
                    progress(i + 1, len(cells))
        except BaseException:
            for fu in futures:
                fu.cancel()
            raise
    return cells, rows


def frame_check(rows):
    """Worst initial-rest-phase error per estimator (a wrong frame: tens of degrees), and the
    estimators above 20 degrees."""
    worst = {}
    for r in rows:
        v = r.get("rest", math.nan)
        if not math.isnan(v) and v > worst.get(r["estimator"], (-1.0, ""))[0]:
            worst[r["estimator"]] = (v, f"{r['sensor']} {r['disturbance']} "
                                        f"{rate_label(r['rate'])} Hz seed {r['seed']}")
    return worst, [e for e, (v, _) in worst.items() if v > 20.0]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    add_grid_flags(ap)
    ap.add_argument("--quick", action="store_true",
                    help="a slice: 25 and 285.7 Hz, consumer, none and passing-magnet, 1 seed, 10 s")
    ap.add_argument("--vqf", action="store_true", help="also run VQF (PyPI vqf): --peers vqf")
    ap.add_argument("--peers", default="", metavar="LIST",
                    help="Python peers to run: vqf, fusion, madgwick, mahony, each optionally "
                         ":9d or :6d (e.g. vqf,madgwick:9d); default none")
    ap.add_argument("--check-frames", action="store_true",
                    help="also score estimate over each log's initial rest phase (the peers "
                         "always are) and print the worst per estimator")
    ap.add_argument("--score", type=Path, default=ROOT.parent / "shared" / "real-data" / "broad" / "score.py")
    ap.add_argument("--jobs", type=int, default=1, help="processes (default 1)")
    ap.add_argument("--markdown", type=Path, default=OUT / "grid.md")
    ap.add_argument("--json", type=Path, default=OUT / "grid.json")
    ap.add_argument("--csv", type=Path, default=OUT / "grid.csv")
    args = ap.parse_args(argv)
    if args.quick:
        args.rates, args.sensors, args.disturbances = "25,285.714285714", "consumer", "none,passing-magnet"
        args.seeds, args.duration = 1, 10.0
    check_grid_args(ap, args)
    args.peer_list = parse_peers(ap, ",".join(filter(None, [args.peers, "vqf" if args.vqf else ""])))
    if load_score(args.score) is None and (args.peer_list or args.estimator):
        print(f"note: {args.score} not found: the other estimators are skipped", file=sys.stderr)
        args.peer_list, args.estimator = [], []
    start = time.time()
    try:
        cells, rows = run_grid(args)
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
    worst, flagged = frame_check(rows)
    if worst:
        text += "\n\nInitial rest phase, worst log per estimator (deg; 9D total, 6D inclination):\n\n"
        text += "\n".join(f"- {e}: {v:.2f} ({where})" for e, (v, where) in worst.items())
    print(head + "\n\n" + text)
    for path in (args.markdown, args.json, args.csv):
        path.parent.mkdir(parents=True, exist_ok=True)
    args.markdown.write_text(head + "\n\n" + text + "\n")
    args.json.write_text(json.dumps(rows, indent=1))
    fields = list(dict.fromkeys(k for r in rows for k in r))
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    if flagged:
        print(f"error: initial rest phase above 20 deg (a wrong frame?): {', '.join(flagged)}",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
