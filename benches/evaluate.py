#!/usr/bin/env python3
"""Three-way evaluation: gyrostat and its peers on BROAD at full rate, BROAD decimated, and the
synthetic grid, in one run, per half of each split (issue 28 item 5).

    cargo build --release -p host-tests --bin broad_estimate \\
        -p gyrostat-tools --bin estimate --bin synthesize
    python3 benches/evaluate.py --jobs 2                 # the default size (BENCHMARKS.md)
    python3 benches/evaluate.py --jobs 2 --seeds 4 --duration 30 --grid-peers \\
        vqf,fusion,madgwick,mahony                       # a larger grid, Madgwick/Mahony 6D too
    python3 benches/evaluate.py --skip-grid              # BROAD only (full rate and decimated)

Data sets (each a table of total / heading / inclination RMSE in degrees, BROAD's metric from
its score.py, mean per estimator over all runs and over each half of the split):

  (a) BROAD        the 16 shared trials at 285.714 Hz. Halves: A = 01 05 09 14 21 26 30 34,
                   B = 03 07 11 16 24 28 32 36 (the split the estimator's design is checked on).
  (b) decimated    the same trials keeping every 2nd, 3rd and 6th row (142.9, 95.2, 47.6 Hz;
                   nothing else changed; --every), the mean over the three rates (48 runs) and per
                   rate; the same halves.
  (c) grid         `synthesize` logs with exact truth (benches/synthetic/grid.py): sensors x
                   disturbances x rates x seeds; default 3 sensor grades x 5 disturbances x
                   25/50/100/285.7/1000 Hz x 2 seeds, hand-held motion 2 x 10 s (150 logs).
                   Halves: A = even seeds, B = odd seeds (different motion, noise and jitter).

Estimators: gyrostat full and light (`--set light_period=0.025` / `--mode light`), 9D and 6D,
through `target/release/broad_estimate` on BROAD and `target/release/estimate` on the grid
(default parameters, online from the first sample); VQF, Fusion, Madgwick, Mahony 9D and 6D from
benches/peers.py (PyPI vqf, imufusion, ahrs; the settings and frame mappings of
benches/broad/run_peers.py; Madgwick and Mahony with BROAD's best common gains, beta 0.12 and
kP 0.74 / kI 0.0012, the same on every data set and rate: not re-tuned). On the grid Madgwick and
Mahony run 9D only by default (ahrs is pure Python, 150-400 us per update; `--grid-peers` adds
their 6D). The summary ("all three") gives gyrostat's change against each peer on every data set
and half: 9D rows on the total, 6D rows on the inclination.

Every filter runs online, sample by sample, with BROAD's initialisation rule. Frames are checked
on every run: the error over each log's initial rest phase (before the first movement row) must
stay below 20 degrees (a wrong frame is off by 90 or 180).

Runtime (2 shared cores, --jobs 2): about 4.5 minutes when the peers are cached (a rerun after
an estimator change: BROAD 2 min, the grid 2.5 min); the first run computes the peers, about 25
minutes (the pure-Python ahrs filters: 1500 s of filter time on BROAD's four rates, 700 s on the
grid).

Caching: the peers do not change when gyrostat does, so their scores are cached (BROAD: under
target/broad-peers/, shared with run_peers.py and keyed by the peer's settings and the trial;
grid: under target/synthetic-grid/peer-cache/, keyed by the log's bytes and the peer's settings);
gyrostat always reruns. --force-peers reruns the peers. Results are deterministic (seeded logs,
deterministic filters, cells in a fixed order whatever --jobs).

Data: the full BROAD trials and score.py from --data DIR, else $GYROSTAT_BROAD_DIR, else
../shared/real-data/broad beside the repository (data/README.md says where to get them). Outputs:
the markdown on stdout and in --markdown FILE, every score in --json FILE (defaults under
target/evaluate/). Exit status: 0; 1 if a tool fails, a frame check fails or an estimate is
missing; 2 for a bad command line or absent data.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benches"))
sys.path.insert(0, str(ROOT / "benches" / "broad"))
sys.path.insert(0, str(ROOT / "benches" / "synthetic"))
import grid  # noqa: E402  (benches/synthetic/grid.py)
import peers  # noqa: E402  (benches/peers.py)
import run_peers as rp  # noqa: E402  (benches/broad/run_peers.py)

OUT = ROOT / "target" / "evaluate"
HALF_A = ["01", "05", "09", "14", "21", "26", "30", "34"]
HALF_B = ["03", "07", "11", "16", "24", "28", "32", "36"]
BROAD_RATE = 1000.0 / 3.5  # 285.714 Hz
LIGHT = "light_period=0.025"

# (label, broad_estimate flags, estimate flags)
GYROSTAT = [
    ("gyrostat 9D", [], []),
    ("gyrostat light 9D", ["--set", LIGHT], ["--mode", "light"]),
    ("gyrostat 6D", ["--6d"], ["--6d"]),
    ("gyrostat light 6D", ["--6d", "--set", LIGHT], ["--6d", "--mode", "light"]),
]
BROAD_PEERS = ["VQF 9D", "VQF 6D", "Fusion 9D", "Fusion 6D", "Madgwick 9D", "Madgwick 6D",
               "Mahony 9D", "Mahony 6D"]
GRID_PEERS = "vqf,fusion,madgwick:9d,mahony:9d"
# Rows of the tables, in order; the peers gyrostat is summarised against.
ORDER = [g[0] for g in GYROSTAT] + BROAD_PEERS
MAGNETIC = {"passing-magnet", "fixed-magnet", "steel"}  # grid disturbances of the field
SUMMARY_PEERS = ["VQF 9D", "Madgwick 9D", "Mahony 9D", "Fusion 9D",
                 "VQF 6D", "Madgwick 6D", "Mahony 6D", "Fusion 6D"]


def fail(msg, code):
    print(f"error: {msg}", file=sys.stderr)
    sys.exit(code)


def half_of_stem(stem):
    num = stem.split("_")[0]
    return "A" if num in HALF_A else "B" if num in HALF_B else None


# --- BROAD ---------------------------------------------------------------------------------------


def _broad_peer(data, every, label, path, force):
    """One peer on one trial (a worker process): run_peers.py's cached run."""
    if every > 1:
        rp.CACHE = rp.CACHE / f"every{every}"
    score = rp.load_score_module(Path(data))
    tr = rp.Trial(Path(path), score, every)
    _, _, desc, fn = next(p for p in peers.peer_table() if p[0] == label)
    res, secs, cached = rp.run_cached(label, desc, fn, tr, score, force, None)
    return res, secs, cached


def _cached_peer(every, label, desc, path):
    """run_peers.py's cached score of this peer on this trial, or None (the same check as
    run_peers.run_cached, without loading the trial)."""
    cache = rp.CACHE / f"every{every}" if every > 1 else rp.CACHE
    d = cache / "peers" / rp.slug(label)
    stem = path.name[: -len(".csv.gz")]
    qf, sf = d / f"{stem}.npy", d / f"{stem}.json"
    if not (qf.exists() and sf.exists()):
        return None
    with open(sf) as f:
        saved = json.load(f)
    if saved.get("meta") != dict(desc=desc, trial_key=f"{path.stat().st_size}"):
        return None
    return saved["scores"]


def run_broad(args, score, paths, log):
    """Every estimator on every trial at every decimation: {every: {label: {stem: result}}}."""
    everys = [1] + args.every
    out = {e: {} for e in everys}
    # gyrostat: one broad_estimate run per configuration and rate (16 trials each).
    procs = []
    for e in everys:
        for label, flags, _ in GYROSTAT:
            d = OUT / "broad" / f"every{e}" / rp.slug(label)
            d.mkdir(parents=True, exist_ok=True)
            for f in d.glob("*.csv"):
                f.unlink()
            cmd = [str(args.bin / "broad_estimate"), "--quiet", "--data", str(args.data),
                   "--every", str(e), *flags, *sum((["--set", s] for s in args.set), []),
                   "--out", str(d)]
            procs.append((e, label, d, cmd))
    t0 = time.time()
    for e, label, d, cmd in procs:  # one at a time: broad_estimate runs two threads itself
        p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            fail(f"`{' '.join(cmd)}` exited with {p.returncode}: {p.stderr.strip()[-300:]}", 1)
    log(f"BROAD: gyrostat ({len(procs)} broad_estimate runs) {time.time() - t0:.0f} s")
    # Trials (parsed once; run_peers.py caches the parse under target/broad-peers/data).
    t0 = time.time()
    trials = {e: [rp.Trial(p, score, e) for p in paths] for e in everys}
    for e in everys:
        for label, _, _ in GYROSTAT:
            d = OUT / "broad" / f"every{e}" / rp.slug(label)
            res = {}
            for tr in trials[e]:
                f = rp.find_estimate(d, tr.stem)
                res[tr.stem] = None if f is None else rp.score_file(score, tr, f)
            out[e][label] = res
    log(f"BROAD: gyrostat scored {time.time() - t0:.0f} s")
    # Peers, in processes (each peer and trial a task; cached ones return at once).
    t0 = time.time()
    desc = {p[0]: p[2] for p in peers.peer_table()}
    tasks, ran, secs = [], 0, 0.0
    for e in everys:
        for label in BROAD_PEERS:
            for p in paths:
                stem = p.name[: -len(".csv.gz")]
                r = None if args.force_peers else _cached_peer(e, label, desc[label], p)
                out[e].setdefault(label, {})[stem] = r
                if r is None:
                    tasks.append((e, label, p))
    with ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futs = [pool.submit(_broad_peer, str(args.data), e, label, str(p), args.force_peers)
                for e, label, p in tasks]
        for (e, label, p), fu in zip(tasks, futs):
            res, s, cached = fu.result()
            out[e][label][p.name[: -len(".csv.gz")]] = res
            if not cached:
                ran += 1
                secs += s
    n_runs = len(everys) * len(BROAD_PEERS) * len(paths)
    log(f"BROAD: peers {time.time() - t0:.0f} s ({ran} of {n_runs} trial runs computed, "
        f"{secs:.0f} s of filter time; the rest cached)")
    return out


def broad_means(results, stems):
    """{label: {"all"|"A"|"B": (total, heading, inclination, n)}} over the listed runs."""
    out = {}
    for label, res in results.items():
        row = {}
        for part in ("all", "A", "B"):
            sel = [res.get(s) for s in stems if part == "all" or half_of_stem(s) == part]
            if not sel or any(r is None or r["main"]["missing"] for r in sel):
                row[part] = None
                continue
            m = [r["main"] for r in sel]
            row[part] = tuple(sum(x[k] for x in m) / len(m) for k in
                              ("total", "heading", "inclination")) + (len(m),)
        out[label] = row
    return out


def merge_everys(results, everys):
    """The decimated runs as one set: label -> {f"{stem}@{every}": result}."""
    out = {}
    for e in everys:
        for label, res in results[e].items():
            for stem, r in res.items():
                out.setdefault(label, {})[f"{stem}@{e}"] = r
    return out


def broad_rest(results):
    """Worst initial-rest-phase error per estimator over every BROAD run."""
    worst = {}
    for per in results.values():
        for label, res in per.items():
            six = label.endswith("6D")
            for stem, r in res.items():
                if r is None or r["rest"]["n"] == 0:
                    continue
                v = r["rest"]["inclination" if six else "total"]
                if v > worst.get(label, (-1.0, ""))[0]:
                    worst[label] = (v, stem.split("_")[0])
    return worst


# --- the grid ------------------------------------------------------------------------------------


def grid_means(rows, label_of):
    """{label: {"all"|"A"|"B": (total, heading, inclination, n)}}; halves by seed parity."""
    out = {}
    for r in rows:
        lab = label_of(r["estimator"])
        part = "A" if r["seed"] % 2 == 0 else "B"
        for p in ("all", part):
            out.setdefault(lab, {}).setdefault(p, []).append(r)
    means = {}
    for lab, parts in out.items():
        row = {}
        for p in ("all", "A", "B"):
            sel = parts.get(p, [])
            if not sel or any(r.get("missing") for r in sel):
                row[p] = None
                continue
            row[p] = tuple(sum(r[k] for r in sel) / len(sel) for k in
                           ("total", "heading", "inclination")) + (len(sel),)
        means[lab] = row
    return means


# --- tables --------------------------------------------------------------------------------------


def cell3(v, six):
    if v is None:
        return "—"
    if six:
        return f"– / – / {v[2]:.3f}"
    return f"{v[0]:.3f} / {v[1]:.3f} / {v[2]:.3f}"


def means_table(means, note):
    head = ["estimator", "all", "half A", "half B"]
    lines = [note, "", "| " + " | ".join(head) + " |", "|---|---:|---:|---:|"]
    for lab in ORDER + [k for k in means if k not in ORDER]:
        if lab not in means:
            continue
        m = means[lab]
        six = lab.endswith("6D")
        lines.append(f"| {lab} | " + " | ".join(cell3(m.get(p), six) for p in ("all", "A", "B"))
                     + " |")
    return "\n".join(lines)


def change(g, p, six):
    """gyrostat's change against the peer (percent of the peer's value): total (9D) or
    inclination (6D)."""
    if g is None or p is None:
        return None
    k = 2 if six else 0
    return 100.0 * (g[k] - p[k]) / p[k]


def runs_of(dump, every_list):
    """Per-run scores, per data set: {set: {label: {run: (total, inclination)}}}."""
    out = {}
    if "broad" in dump:
        def take(res):
            return {s.split("_")[0]: (r["main"]["total"], r["main"]["inclination"])
                    for s, r in res.items()
                    if r is not None and not r["main"]["missing"]}
        out["BROAD"] = {lab: take(res) for lab, res in dump["broad"]["1"].items()}
        dec = {}
        for e in every_list:
            for lab, res in dump["broad"][str(e)].items():
                dec.setdefault(lab, {}).update({f"{k} at {BROAD_RATE / e:.1f} Hz": v
                                                for k, v in take(res).items()})
        if dec:
            out["decimated"] = dec
    if "grid" in dump:
        g = {}
        for r in dump["grid"]:
            lab = "gyrostat 9D" if r["estimator"] == "estimate" else r["estimator"]
            run = (f"{r['sensor']} {r['disturbance']} {grid.rate_label(r['rate'])} Hz "
                   f"seed {r['seed']}")
            g.setdefault(lab, {})[run] = (r["total"], r["inclination"])
        out["grid"] = g
    return out


def losses(runs, gyro):
    """Per peer and data set: on how many runs gyrostat's score is above the peer's, and the
    run where it is furthest above (9D: total, 6D: inclination)."""
    sets = list(runs)
    lines = ["| peer | " + " | ".join(sets) + " |", "|---|" + "---|" * len(sets)]
    for peer in SUMMARY_PEERS:
        six = peer.endswith("6D")
        g_lab = gyro.replace("9D", "6D") if six else gyro
        k = 1 if six else 0
        cells = []
        for name in sets:
            p, g = runs[name].get(peer), runs[name].get(g_lab)
            if not p or not g:
                cells.append("—")
                continue
            common = [run for run in g if run in p]
            worse = [(g[run][k] - p[run][k], run) for run in common if g[run][k] > p[run][k]]
            cell = f"{len(worse)} of {len(common)}"
            if worse:
                d, run = max(worse)
                cell += f"; worst {run}: {g[run][k]:.2f} vs {p[run][k]:.2f}"
            cells.append(cell)
        if all(c == "—" for c in cells):
            continue
        lines.append(f"| {peer} ({'inclination' if six else 'total'}) | " + " | ".join(cells)
                     + " |")
    return "\n".join(lines)


def summary(sets, gyro):
    """The "all three" table: gyrostat (label gyro, or its 6D twin for 6D peers) against each
    peer on every data set and half; a row ends with where gyrostat wins or loses."""
    parts = [(name, h) for name, _ in sets for h in ("A", "B")]
    head = ["peer"] + [f"{name} {h}" for name, h in parts] + ["gyrostat"]
    lines = ["| " + " | ".join(head) + " |", "|---|" + "---:|" * len(parts) + "---|"]
    for peer in SUMMARY_PEERS:
        six = peer.endswith("6D")
        g_lab = gyro.replace("9D", "6D") if six else gyro
        cells, losses, wins = [], [], 0
        for name, h in parts:
            means = dict(sets)[name]
            if peer not in means or g_lab not in means:
                cells.append("—")
                continue
            c = change(means[g_lab].get(h), means[peer].get(h), six)
            if c is None:
                cells.append("—")
                continue
            cells.append(f"{c:+.1f} %")
            if c < 0:
                wins += 1
            else:
                losses.append(f"{name} {h}")
        n = sum(1 for c in cells if c != "—")
        if n == 0:
            continue
        verdict = (f"wins all {n}" if not losses else
                   f"wins {wins} of {n}; loses {', '.join(losses)}")
        lines.append(f"| {peer} ({'inclination' if six else 'total'}) | " + " | ".join(cells)
                     + f" | {verdict} |")
    return "\n".join(lines)


def per_rate_table(results, everys, stems):
    """BROAD total (9D) or inclination (6D) per rate, A / B."""
    rates = [f"{BROAD_RATE / e:.1f} Hz" for e in everys]
    lines = ["| estimator | " + " | ".join(rates) + " |", "|---|" + "---:|" * len(everys)]
    for lab in ORDER:
        six = lab.endswith("6D")
        cells = []
        for e in everys:
            m = broad_means({lab: results[e].get(lab, {})}, stems)[lab]
            if m["all"] is None:
                cells.append("—")
                continue
            k = 2 if six else 0
            cells.append(f"{m['all'][k]:.3f} ({m['A'][k]:.3f} / {m['B'][k]:.3f})")
        lines.append(f"| {lab} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


# --- main ----------------------------------------------------------------------------------------


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", type=Path, default=None,
                    help="the folder of the full BROAD trials and score.py (default: "
                         "$GYROSTAT_BROAD_DIR, else ../shared/real-data/broad)")
    ap.add_argument("--every", default="2,3,6",
                    help="the decimations of data set (b), comma-separated (default 2,3,6)")
    ap.add_argument("--jobs", type=int, default=1,
                    help="processes for the peers, broad_estimate runs and grid cells (default 1)")
    ap.add_argument("--skip-broad", action="store_true", help="only the synthetic grid")
    ap.add_argument("--skip-grid", action="store_true", help="only BROAD (full rate and decimated)")
    ap.add_argument("--grid-peers", default=GRID_PEERS, metavar="LIST",
                    help=f"the Python peers on the grid (grid.py --peers; default {GRID_PEERS})")
    ap.add_argument("--markdown", type=Path, default=OUT / "evaluate.md")
    ap.add_argument("--json", type=Path, default=OUT / "evaluate.json")
    grid.add_grid_flags(ap, seeds=2, duration=10.0)
    args = ap.parse_args(argv)
    if args.jobs < 1:
        ap.error("--jobs needs a whole number >= 1")
    if args.skip_broad and args.skip_grid:
        ap.error("--skip-broad and --skip-grid leave nothing to run")
    try:
        args.every = sorted({int(x) for x in args.every.split(",") if x.strip()})
    except ValueError:
        ap.error(f"--every: not whole numbers: {args.every}")
    if any(e < 2 for e in args.every):
        ap.error("--every: decimations are whole numbers >= 2")
    if args.data is None:
        env = os.environ.get("GYROSTAT_BROAD_DIR")
        args.data = Path(env) if env else ROOT.parent / "shared" / "real-data" / "broad"
    score_py = args.data / "score.py"
    paths = sorted(args.data.glob("*.csv.gz")) if args.data.is_dir() else []
    if not score_py.exists() or not paths:
        fail(f"no BROAD trials and score.py in {args.data}: pass --data DIR or set "
             "GYROSTAT_BROAD_DIR (data/README.md says where to get the trials)", 2)
    nums = {p.name.split("_")[0] for p in paths}
    if not args.skip_broad and nums != set(HALF_A + HALF_B):
        fail(f"{args.data} holds trials {' '.join(sorted(nums))}, not the 16 shared ones of the "
             "half-split", 2)
    if not args.skip_broad and not (args.bin / "broad_estimate").exists():
        fail(f"{args.bin / 'broad_estimate'} not found: cargo build --release -p host-tests "
             "--bin broad_estimate", 2)
    if not args.skip_grid:
        args.score = score_py
        args.check_frames = True
        args.peer_list = grid.parse_peers(ap, args.grid_peers)
        grid.check_grid_args(ap, args)
        # gyrostat 9D full is grid.py's own `estimate --truth` run (with every --set); the
        # other gyrostat columns run through grid.py's --estimator with the same --set flags
        # and parameter file ({params}: --params-from-sensor).
        est = " ".join([shlex.quote(str(args.estimate_bin)), "{params}"]
                       + [f"--set {shlex.quote(s)}" for s in args.set])
        args.estimator = [(lab, f"{est} {' '.join(flags)} {{log}} > {{out}}")
                          for lab, _, flags in GYROSTAT[1:]] + list(args.estimator)

    start = time.time()
    timing = []

    def log(msg):
        timing.append(msg)
        print(msg, file=sys.stderr, flush=True)

    score = rp.load_score_module(args.data)
    sets, texts, dump, rest = [], [], {}, {}
    stems = [p.name[: -len(".csv.gz")] for p in paths]
    if not args.skip_broad:
        res = run_broad(args, score, paths, log)
        full = broad_means(res[1], stems)
        sets.append(("BROAD", full))
        texts.append(means_table(full, f"**(a) BROAD, the 16 shared trials at 285.7 Hz**: mean "
                                       "total / heading / inclination RMSE (°), all 16 and "
                                       "each half of 8 (6D: inclination only)."))
        if args.every:
            dec = broad_means(merge_everys(res, args.every),
                              [f"{s}@{e}" for e in args.every for s in stems])
            sets.append(("decimated", dec))
            rates = ", ".join(f"{BROAD_RATE / e:.1f}" for e in args.every)
            texts.append(means_table(dec, f"**(b) BROAD decimated** (every "
                                          f"{'/'.join(map(str, args.every))}th row: {rates} Hz), "
                                          f"mean over the {len(args.every) * len(stems)} runs "
                                          "(each half: its 8 trials at each rate)."))
            texts.append("Per rate, BROAD: mean total (9D) or inclination (6D) RMSE (°), "
                         "(half A / half B):\n\n" + per_rate_table(res, [1] + args.every, stems))
        for label, (v, where) in broad_rest(res).items():
            rest[label] = [(v, f"BROAD trial {where}")]
        dump["broad"] = {str(e): res[e] for e in res}
    if not args.skip_grid:
        t0 = time.time()

        def progress(i, n):
            if i % 10 == 0 or i == n:
                print(f"  grid: {i}/{n} logs ({time.time() - t0:.0f} s)", file=sys.stderr,
                      flush=True)

        try:
            cells, rows = grid.run_grid(args, progress)
        except RuntimeError as e:
            fail(str(e), 1)
        log(f"grid: {len(cells)} logs {time.time() - t0:.0f} s")
        label_of = lambda e: "gyrostat 9D" if e == "estimate" else e  # noqa: E731
        gm = grid_means(rows, label_of)
        sets.append(("grid", gm))
        texts.append(means_table(gm, f"**(c) Synthetic grid**: {len(cells)} logs "
                                     f"({', '.join(args.sensors)} x "
                                     f"{', '.join(args.disturbances)} x "
                                     f"{', '.join(grid.rate_label(r) for r in args.rates)} Hz "
                                     f"x {args.seeds} seeds, hand-held {args.phases} x "
                                     f"{args.duration:g} s); mean total / heading / "
                                     "inclination RMSE (°) over the logs; half A: even seeds, "
                                     "B: odd seeds."))
        # The magnet cells dominate the grid's means (a peer without hard-iron estimation is off
        # by tens of degrees there): the logs without a magnet are a set of their own.
        calm = [r for r in rows if r["disturbance"] not in MAGNETIC]
        if calm and len(calm) < len(rows):
            gc = grid_means(calm, label_of)
            sets.append(("grid, no magnet", gc))
            names = sorted({r["disturbance"] for r in calm}, key=args.disturbances.index)
            texts.append(means_table(gc, f"**(c') The grid's logs without a magnet** "
                                         f"({', '.join(names)}: {len(calm) // len(gc)} logs)."))
        worst, _ = grid.frame_check(rows)
        for e, (v, where) in worst.items():
            rest.setdefault(label_of(e), []).append((v, f"grid {where}"))
        dump["grid"] = rows

    texts.append("**All three**: gyrostat's change against each peer (9D: total; 6D: "
                 "inclination, gyrostat 6D) per data set and half; negative: gyrostat lower "
                 "(better).\n\ngyrostat (full):\n\n" + summary(sets, "gyrostat 9D")
                 + "\n\ngyrostat light:\n\n" + summary(sets, "gyrostat light 9D"))
    runs = runs_of(dump, args.every)
    texts.append("**Runs lost**: on how many single runs (BROAD trial, decimated trial, grid "
                 "log) gyrostat (full) scores above the peer, and its largest loss (gyrostat vs "
                 "peer, °):\n\n" + losses(runs, "gyrostat 9D"))
    flagged = []
    lines = []
    for lab in ORDER:
        if lab in rest:
            v, where = max(rest[lab])
            lines.append(f"- {lab}: {v:.2f} ({where})")
            if any(x > 20.0 for x, _ in rest[lab]):
                flagged.append(lab)
    texts.append("Frame check: worst initial-rest-phase RMSE (°; 9D total, 6D inclination) "
                 "per estimator, BROAD and grid (a wrong frame: 90 or 180):\n\n"
                 + "\n".join(lines))
    log(f"total {time.time() - start:.0f} s")
    texts.append("Runtime (--jobs {}): ".format(args.jobs) + "; ".join(timing) + ".")
    text = "\n\n".join(texts) + "\n"
    print(text)
    for p in (args.markdown, args.json):
        p.parent.mkdir(parents=True, exist_ok=True)
    args.markdown.write_text(text)
    args.json.write_text(json.dumps(dump))
    missing = [lab for name, m in sets for lab, row in m.items() if row.get("all") is None]
    if flagged:
        print(f"error: initial rest phase above 20 deg (a wrong frame?): {', '.join(flagged)}",
              file=sys.stderr)
        return 1
    if missing:
        print(f"error: missing estimates: {', '.join(sorted(set(missing)))}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
