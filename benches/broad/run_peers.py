#!/usr/bin/env python3
"""Attitude estimation on BROAD: the peers (and gyrostat) scored in one run with BROAD's own metric.

    python3 benches/broad/run_peers.py                      # the PyPI peers, cached
    python3 benches/broad/run_peers.py --rust               # + uf-ahrs and the vqf crate (cargo bench)
    python3 benches/broad/run_peers.py \\
        --gyrostat 'target/release/broad_estimate --9d {trial} > {out}' \\
        --gyrostat-6d 'target/release/broad_estimate --6d {trial} > {out}'
    python3 benches/broad/run_peers.py --estimates 'my filter=path/to/dir'

Trials: every `*.csv.gz` of the full BROAD folder: `--data DIR`, else $GYROSTAT_BROAD_DIR, else
../shared/real-data/broad/ beside the repository (data/README.md says where to get the trials; the
repository keeps only trimmed copies, in data/broad/, for its tests). Metric: that folder's
`score.py` (BROAD's official total / heading / inclination RMSE over the movement phase), imported
and called as it is; nothing here recomputes an error.

Every estimator runs ONLINE (sample by sample, causal) over the whole trial, with the same
initialisation rule, BROAD's: the initial attitude from the accelerometer and magnetometer of the
first sample (earth frame ENU with y towards magnetic north, the frame of BROAD's optical
reference), then one update per sample from the first sample on, the output after update i being
the estimate for row i. 6D runs start from the first accelerometer sample alone (their heading is
unobservable; only inclination is scored). The peers' code is benches/peers.py (shared with the
synthetic grid and benches/evaluate.py). Peers, versions and settings:

  VQF 9D / 6D     PyPI vqf 2.1.2, class `VQF(Ts)` with default parameters (not offlineVQF). Its own
                  start-up already is BROAD's rule: after the first sample its 9D output equals the
                  accelerometer/magnetometer attitude of that sample (checked below). Run through
                  `VQF.updateBatch`, the same C++ online update looped in C++; checked equal to
                  per-sample `update` calls on each trial's first samples. Output frame: ENU.
  Fusion 9D / 6D  PyPI imufusion 1.3.3 (x-io Fusion), default settings (gain 0.5, no rejection,
                  no gyroscope range), `sample_rate` set to BROAD's 285.714 Hz.
  Fusion doc.     the settings its README and advanced example document: gain 0.5, gyroscope
                  range 2000 deg/s, acceleration and magnetic rejection 10 deg, rejection timeout
                  5 s, and its gyroscope `Bias` estimator (default settings) in front.
                  Both Fusion runs: initial attitude set with `set_quaternion` + `skip_startup`
                  (Fusion's API for a known initial orientation). Units: deg/s, g, uT. Output
                  frame: NWU (imufusion 1.3.3 ignores `AhrsSettings(convention=...)`; the default
                  NWU is used and mapped: q_ENU = Rz(+90 deg) q_NWU).
  Madgwick 9D/6D  PyPI ahrs 0.4.0 `Madgwick(gain=0.12)` (BROAD's best common beta),
                  `updateMARG` / `updateIMU` per sample, q0 given. Output frame: NWU (mapped).
  Mahony 9D / 6D  PyPI ahrs 0.4.0 `Mahony(k_P=0.74, k_I=0.0012)` (BROAD's best common gains),
                  bias integral starting at zero, q0 given. Output frame: ENU.
  strapdown       gyro only, started from the optical truth at its first sample, gyro bias = the
                  mean over the first 10 s (rest), exact exponential per sample. A reference for
                  what the corrections buy; not a filter.

Every frame mapping is verified on each trial's initial rest phase (rest rows with optical data
before the first movement row): the rest-phase error is printed, and an estimator whose rest
error exceeds 20 deg is flagged (a wrong frame is off by 90 or 180 deg).

Outputs are cached under target/broad-peers/ (keyed by a description of the run: change a setting
and it reruns); the pure-Python ahrs filters take about 3 minutes per configuration, everything
else seconds. `--export DIR` writes every peer estimate as CSV (t_s,qw,qx,qy,qz), which score.py
scores from the command line the same way; `--json FILE` writes every score.

gyrostat: `--gyrostat CMD` / `--gyrostat-6d CMD` run CMD through the shell from the repository
root once per trial ({trial}: the trial's .csv.gz path, {out}: the CSV to write, {stem}: the
trial's name) and score the CSV (header, then t_s or t, qw, qx, qy, qz; extra columns ignored).
`--estimates LABEL=DIR` scores a directory of such files named <trial stem>.csv[.gz]; a LABEL ending
in "6D" is scored as 6D. `--rust` first runs `cargo bench --bench broad_peers`, which writes the
Rust peers' estimates to target/broad-peers/rust/; estimates found there are always included.

Exit status: 0; 1 if an estimator fails the rest-phase check; 2 if a trial has no estimate file
or a scored row has no finite estimate (score.py's MISSING).

BROAD: D. Laidig, M. Caruso, A. Cereatti, T. Seel, "BROAD - A Benchmark for Robust Inertial
Orientation Estimation", Data 6(7):72, 2021, doi:10.3390/data6070072 (CC BY 4.0).
"""
import argparse
import csv
import gzip
import importlib.util
import json
import math
import os
import pickle
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benches"))
CACHE = ROOT / "target" / "broad-peers"

# --- trials and groups --------------------------------------------------------------------------

GROUPS = [
    ("all", lambda s: True),
    ("undisturbed", lambda s: "_undisturbed_" in s),
    ("disturbed", lambda s: "_disturbed_" in s),
    ("rotation", lambda s: "_undisturbed_" in s and "_rotation" in s),
    ("translation", lambda s: "_undisturbed_" in s and "_translation" in s),
    ("combined", lambda s: "_undisturbed_" in s and "_combined" in s),
    ("tapping", lambda s: "_tapping" in s),
    ("vibration", lambda s: "_vibration" in s),
    ("stat. magnet", lambda s: "_stationary_magnet" in s),
    ("att. magnet", lambda s: "_attached_magnet" in s),
]


# The BROAD folder when no --data is given: $GYROSTAT_BROAD_DIR, else ../shared/real-data/broad
# beside the repository.
DEFAULT_DATA = os.environ.get("GYROSTAT_BROAD_DIR", str(ROOT.parent / "shared" / "real-data" / "broad"))


def broad_trials(data, trials=None):
    """score.py's module and the trial files (`*.csv.gz`, only the numbers in `trials` when
    given) of the BROAD folder `data`; exits with one `error:` line (status 2) when either is
    missing."""
    data = Path(data)
    paths = sorted(data.glob("*.csv.gz"))
    if trials:
        paths = [p for p in paths if p.name.split("_")[0] in set(trials)]
    if not (data / "score.py").exists() or not paths:
        print(f"error: no BROAD trials and score.py in {data} (pass --data DIR or set "
              "GYROSTAT_BROAD_DIR; data/README.md says where to get them)", file=sys.stderr)
        sys.exit(2)
    return load_score_module(data), paths


def load_score_module(data):
    spec = importlib.util.spec_from_file_location("broad_score", data / "score.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


class Trial:
    """One BROAD trial: the arrays the estimators read, and score.py's own parse for scoring."""

    def __init__(self, path, score, every=1):
        self.path = path
        self.stem = path.name[: -len(".csv.gz")]
        st = path.stat()
        key = f"{st.st_size}-{int(st.st_mtime)}"
        cache = ROOT / "target" / "broad-peers" / "data" / f"{self.stem}.pkl"
        obj = None
        if cache.exists():
            with open(cache, "rb") as f:
                obj = pickle.load(f)
            if obj.get("key") != key:
                obj = None
        if obj is None:
            with gzip.open(path, "rt", newline="") as f:
                rd = csv.reader(f)
                head = next(rd)
                rows = list(rd)
            col = {h: i for i, h in enumerate(head)}

            def arr(names):
                return np.array([[float(r[col[n]]) for n in names] for r in rows])

            obj = dict(
                key=key,
                t=arr(["t_s"])[:, 0],
                gyr=arr(["gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s"]),
                acc=arr(["acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"]),
                mag=arr(["mag_x_uT", "mag_y_uT", "mag_z_uT"]),
                score_rows=score.load_trial(str(path)),
            )
            cache.parent.mkdir(parents=True, exist_ok=True)
            with open(cache, "wb") as f:
                pickle.dump(obj, f)
        # Every Nth row (N = every): the same rows broad_estimate --every N reads.
        pick = lambda a: np.ascontiguousarray(a[::every])
        self.t, self.gyr, self.acc, self.mag = (pick(obj[k]) for k in ("t", "gyr", "acc", "mag"))
        self.rows = obj["score_rows"][::every]  # score.load_trial(): (t_s, q_opt or None, movement)
        for a in (self.gyr, self.acc, self.mag):
            assert a.flags["C_CONTIGUOUS"] and np.all(np.isfinite(a)), self.stem
        dt = np.diff(self.t)
        self.ts = float(np.median(dt))
        assert np.all(np.abs(dt - self.ts) < 1e-6), f"{self.stem}: uneven sample times"
        moving = [i for i, r in enumerate(self.rows) if r[2]]
        self.first_move = moving[0] if moving else len(self.rows)


# --- the peers: benches/peers.py (shared with the synthetic grid and evaluate.py) ---------------

from peers import (  # noqa: E402
    ENU_FROM_NWU, G, NWU_FROM_ENU, initial_enu, peer_table, pkg_version, qmul, qmul_rows,
    quat_from_matrix, run_fusion, run_madgwick, run_mahony, run_vqf,
)


def run_strapdown(tr):
    rows = tr.rows
    k0 = next(i for i, r in enumerate(rows) if r[1] is not None)
    bias = tr.gyr[tr.t < 10.0].mean(axis=0)
    out = np.full((len(rows), 4), np.nan)
    q = np.array(rows[k0][1])
    q /= np.linalg.norm(q)
    out[k0] = q
    for i in range(k0 + 1, len(rows)):
        phi = (tr.gyr[i] - bias) * tr.ts
        a = float(np.linalg.norm(phi))
        dq = np.array([math.cos(a / 2), *(phi * (math.sin(a / 2) / a if a > 0 else 0.5))])
        q = qmul(q, dq)
        q /= np.linalg.norm(q)
        out[i] = q
    return out


def peers():
    return peer_table() + [
        ("strapdown", True, "gyro only from truth, bias = mean of first 10 s, exact exp", run_strapdown),
    ]


def slug(label):
    return re.sub(r"[^a-z0-9]+", "-", label.lower()).strip("-")


# --- scoring ------------------------------------------------------------------------------------


def score_estimate(score, tr, est):
    """score.py's metric over the movement phase, and over the initial rest phase (frame check)."""
    main = score.score(tr.rows, est)
    rest_rows = [(t, q, i < tr.first_move and q is not None) for i, (t, q, _) in enumerate(tr.rows)]
    rest = score.score(rest_rows, est)
    return dict(main=main, rest=rest)


def est_from_array(tr, Q):
    return {round(r[0] * 1e6): tuple(float(v) for v in q) for r, q in zip(tr.rows, Q)}


def write_csv(path, tr, Q):
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w") as f:
        f.write("t_s,qw,qx,qy,qz\n")
        for t, q in zip(tr.t, Q):
            f.write(f"{t:.6f},{q[0]:.9f},{q[1]:.9f},{q[2]:.9f},{q[3]:.9f}\n")


def run_cached(label, desc, fn, tr, score, force, export):
    d = CACHE / "peers" / slug(label)
    qf, sf = d / f"{tr.stem}.npy", d / f"{tr.stem}.json"
    meta = dict(desc=desc, trial_key=f"{tr.path.stat().st_size}")
    Q = None
    if not force and qf.exists() and sf.exists():
        with open(sf) as f:
            saved = json.load(f)
        if saved.get("meta") == meta:
            if export is None:
                return saved["scores"], saved["seconds"], True
            Q = np.load(qf)
            res, secs = saved["scores"], saved["seconds"]
    if Q is None:
        t0 = time.time()
        Q = fn(tr)
        secs = time.time() - t0
        res = score_estimate(score, tr, est_from_array(tr, Q))
        d.mkdir(parents=True, exist_ok=True)
        np.save(qf, Q)
        with open(sf, "w") as f:
            json.dump(dict(meta=meta, scores=res, seconds=secs), f)
    if export is not None:
        write_csv(Path(export) / slug(label) / f"{tr.stem}.csv", tr, Q)
    return res, secs, False


def score_file(score, tr, path):
    """score.py on an estimate file; the result is cached against the file's size and time."""
    st = path.stat()
    key = f"{path.resolve()}|{st.st_size}|{st.st_mtime_ns}|{tr.path.stat().st_size}"
    cache = CACHE / "scores" / (slug(str(path.resolve())) + ".json")
    if cache.exists():
        with open(cache) as f:
            saved = json.load(f)
        if saved.get("key") == key:
            return saved["scores"]
    res = score_estimate(score, tr, score.load_estimate(str(path)))
    cache.parent.mkdir(parents=True, exist_ok=True)
    with open(cache, "w") as f:
        json.dump(dict(key=key, scores=res), f)
    return res


def find_estimate(directory, stem):
    for name in (f"{stem}.csv", f"{stem}.csv.gz"):
        p = Path(directory) / name
        if p.exists():
            return p
    num = stem.split("_")[0]
    for name in (f"{num}.csv", f"{num}.csv.gz"):
        p = Path(directory) / name
        if p.exists():
            return p
    return None


# --- table --------------------------------------------------------------------------------------


def fmt(r, nine):
    if r is None:
        return "—"
    m = r["main"]
    if m["missing"]:
        return f"MISSING {m['missing']}"
    if nine:
        return f"{m['total']:.2f} / {m['heading']:.2f} / {m['inclination']:.2f}"
    return f"– / – / {m['inclination']:.2f}"


def md_table(head, rows):
    w = [max(len(str(x)) for x in col) for col in zip(head, *rows)]
    line = lambda cells: "| " + " | ".join(str(c).ljust(n) for c, n in zip(cells, w)) + " |"
    out = [line(head), "|" + "|".join("-" * (n + 2) for n in w) + "|"]
    out += [line(r) for r in rows]
    return "\n".join(out)


def group_mean(results, stems, nine):
    vals = [results.get(s) for s in stems]
    if not stems or any(v is None or v["main"]["missing"] for v in vals):
        return "—"
    m = [v["main"] for v in vals]
    mean = lambda k: sum(x[k] for x in m) / len(m)
    if nine:
        return f"{mean('total'):.2f} / {mean('heading'):.2f} / {mean('inclination'):.2f}"
    return f"– / – / {mean('inclination'):.2f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", default=DEFAULT_DATA,
                    help="BROAD folder with score.py (default: $GYROSTAT_BROAD_DIR, else "
                         "../shared/real-data/broad beside the repository; see data/README.md)")
    ap.add_argument("--trials", help="comma-separated trial numbers, e.g. 07,24 (default: all)")
    ap.add_argument("--only", help="comma-separated peer labels to run (default: all), e.g. 'VQF 9D,strapdown'")
    ap.add_argument("--no-peers", action="store_true", help="score only gyrostat / --estimates / rust outputs")
    ap.add_argument("--force", action="store_true", help="rerun the peers even if cached")
    ap.add_argument("--gyrostat", metavar="CMD", help="command template writing gyrostat's 9D estimate")
    ap.add_argument("--gyrostat-6d", metavar="CMD", help="command template writing gyrostat's 6D estimate")
    ap.add_argument("--estimates", metavar="LABEL=DIR", action="append", default=[],
                    help="score a directory of estimate CSVs (LABEL ending in 6D: scored as 6D)")
    ap.add_argument("--rust", action="store_true",
                    help="first run `cargo bench --bench broad_peers` (uf-ahrs and vqf crates; package gyrostat-benches)")
    ap.add_argument("--export", metavar="DIR", help="also write every peer estimate as CSV under DIR")
    ap.add_argument("--every", type=int, default=1, metavar="N",
                    help="keep every Nth row of each trial (rows 0, N, 2N, ...; nothing else changed): "
                         "the trial at 1/N of its rate; cached apart; {every} in a command template")
    ap.add_argument("--json", metavar="FILE", help="also write every score (per trial and rest phase) as JSON")
    args = ap.parse_args()

    global CACHE
    if args.every < 1:
        sys.exit("error: --every needs a whole number >= 1")
    if args.every > 1:
        CACHE = CACHE / f"every{args.every}"
    data = Path(args.data)
    score, paths = broad_trials(data, args.trials.split(",") if args.trials else None)
    trials = [Trial(p, score, args.every) for p in paths]
    stems = [t.stem for t in trials]

    columns = []  # (label, nine, description, {stem: result})
    timing = {}
    if not args.no_peers:
        only = set(args.only.split(",")) if args.only else None
        for label, nine, desc, fn in peers():
            if only and label not in only:
                continue
            res, total, cached_all = {}, 0.0, True
            for tr in trials:
                r, secs, cached = run_cached(label, desc, fn, tr, score, args.force, args.export)
                res[tr.stem] = r
                total += secs
                cached_all &= cached
                if not cached:
                    print(f"  {label}: {tr.stem} ({secs:.1f} s)", file=sys.stderr, flush=True)
            timing[label] = (total, cached_all)
            columns.append((label, nine, desc, res))

    if args.rust:
        cmd = ["cargo", "bench", "-q", "--bench", "broad_peers", "--", "--data", str(data)]
        print("$ " + " ".join(cmd), file=sys.stderr, flush=True)
        subprocess.run(cmd, cwd=ROOT, check=True)
    about = {}  # label -> how it was run, for the estimates written by other programs
    rust_dir = CACHE / "rust"
    if rust_dir.is_dir():
        for d in sorted(p for p in rust_dir.iterdir() if p.is_dir()):
            manifest = d / "label.txt"
            lines = manifest.read_text().splitlines() if manifest.exists() else []
            label = lines[0].strip() if lines else d.name
            if len(lines) > 1:
                about[label] = lines[1].strip()
            args.estimates.append(f"{label}={d}")

    commands = []
    if args.gyrostat:
        commands.append(("gyrostat 9D", True, args.gyrostat))
    if args.gyrostat_6d:
        commands.append(("gyrostat 6D", False, args.gyrostat_6d))
    for label, nine, cmd in commands:
        out_dir = CACHE / "gyrostat" / slug(label)
        out_dir.mkdir(parents=True, exist_ok=True)
        t0 = time.time()
        for tr in trials:
            out = out_dir / f"{tr.stem}.csv"
            if out.exists():
                out.unlink()
            c = cmd.format(trial=tr.path, out=out, stem=tr.stem, every=args.every)
            p = subprocess.run(c, shell=True, cwd=ROOT)
            if p.returncode != 0:
                sys.exit(f"error: `{c}` exited with {p.returncode}")
        timing[label] = (time.time() - t0, False)
        about[label] = f"`{cmd}`"
        args.estimates.append(f"{label}={out_dir}")

    for spec in args.estimates:
        label, _, directory = spec.partition("=")
        nine = not label.rstrip().endswith("6D")
        res = {}
        for tr in trials:
            p = find_estimate(directory, tr.stem)
            if p is None:
                res[tr.stem] = None
                continue
            res[tr.stem] = score_file(score, tr, p)
        where = Path(directory).resolve()
        where = where.relative_to(ROOT) if where.is_relative_to(ROOT) else where
        columns.append((label, nine, about.get(label, f"estimates in {where}"), res))

    # Frame check: the initial rest phase must agree with the optical reference.
    print("## Rest-phase check (frames and initialisation)\n")
    print("RMSE over each trial's initial rest phase (rows with optical data before the first movement")
    print("row), worst trial; 9D: total, 6D: inclination. A wrong frame is off by 90 or 180 deg;")
    print("above 20 deg: flagged (a disturbed first sample or rest phase stays well below).\n")
    flagged = []
    rows = []
    for label, nine, desc, res in columns:
        worst, where = -1.0, ""
        for s in stems:
            r = res.get(s)
            if r is None or r["rest"]["n"] == 0:
                continue
            v = r["rest"]["total" if nine else "inclination"]
            if v > worst:
                worst, where = v, s
        mark = "FLAGGED" if worst > 20 else "ok"
        if worst > 20:
            flagged.append(label)
        rows.append([label, f"{worst:.2f}" if worst >= 0 else "—", where.split("_")[0], mark])
    print(md_table(["estimator", "worst rest RMSE (deg)", "trial", ""], rows))

    # gyrostat first, then the peers in the order they were run.
    columns.sort(key=lambda c: not c[0].startswith("gyrostat"))
    nine_cols = [c for c in columns if c[1]]
    six_cols = [c for c in columns if not c[1]]
    group_head = [f"{g} ({sum(1 for s in stems if f(s))})" for g, f in GROUPS]

    def incl(r):
        if r is None:
            return "—"
        m = r["main"]
        return f"MISSING {m['missing']}" if m["missing"] else f"{m['inclination']:.2f}"

    def incl_mean(res, group):
        vals = [res.get(s) for s in group]
        if not group or any(v is None or v["main"]["missing"] for v in vals):
            return "—"
        return f"{sum(v['main']['inclination'] for v in vals) / len(vals):.2f}"

    short = {s: s.split("_", 1)[0] + " " + s.split("_", 1)[1].replace("undisturbed_", "").replace("disturbed_", "")
             for s in stems}
    print("\n## 9D: group means of total / heading / inclination RMSE (deg), movement phase\n")
    rows = [[c[0]] + [group_mean(c[3], [s for s in stems if f(s)], True) for g, f in GROUPS] for c in nine_cols]
    print(md_table(["estimator"] + group_head, rows))
    print("\n## 6D: group means of inclination RMSE (deg), movement phase\n")
    rows = [[c[0]] + [incl_mean(c[3], [s for s in stems if f(s)]) for g, f in GROUPS] for c in six_cols]
    print(md_table(["estimator"] + group_head, rows))
    print("\n## 9D per trial: total / heading / inclination RMSE (deg)\n")
    rows = [[short[s]] + [fmt(c[3].get(s), True) for c in nine_cols] for s in stems]
    print(md_table(["trial"] + [c[0] for c in nine_cols], rows))
    print("\n## 6D per trial: inclination RMSE (deg)\n")
    rows = [[short[s]] + [incl(c[3].get(s)) for c in six_cols] for s in stems]
    print(md_table(["trial"] + [c[0] for c in six_cols], rows))

    print("\n## Runs\n")
    for label, nine, desc, res in columns:
        t = timing.get(label)
        when = "" if t is None else (" (cached)" if t[1] else f" ({t[0]:.0f} s)")
        print(f"- {label}: {desc}{when}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({c[0]: dict(nine=c[1], run=c[2], trials=c[3]) for c in columns}, f, indent=1)
    incomplete = [c[0] for c in columns if any(r is None or r["main"]["missing"] for r in c[3].values())]
    if flagged:
        print(f"\nerror: rest-phase check failed for: {', '.join(flagged)}", file=sys.stderr)
    if incomplete:
        # As score.py: a scored row without a finite estimate (or a trial without a file) fails.
        print(f"\nerror: missing estimates for: {', '.join(incomplete)}", file=sys.stderr)
    return 1 if flagged else 2 if incomplete else 0


if __name__ == "__main__":
    sys.exit(main())
