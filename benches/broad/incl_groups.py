#!/usr/bin/env python3
"""Inclination per BROAD trial group × half × rate: gyrostat 6D / 9D against VQF 6D / 9D, one run.

    python3 benches/broad/incl_groups.py [--every 1,2,3,6] [--set NAME=VALUE ...] [--no-9d]
                                         [--bin target/release/broad_estimate] [--json FILE]

For each decimation N (every Nth row, the rows `run_peers.py --every N` gives the peers; 285.7 /
142.9 / 95.2 / 47.6 Hz for N = 1 / 2 / 3 / 6) it runs `broad_estimate --quiet [--6d] --every N
--out DIR` (with every `--set` passed on) and VQF 2.1.2 with its defaults (`run_peers.run_vqf`,
cached by `run_peers.py`'s cache), and scores every estimate with BROAD's `score.py` (movement
phase; `run_peers.score_file` / `score_estimate`). Prints, per group (run_peers.GROUPS) and half
(A = 01 05 09 14 21 26 30 34, B = 03 07 11 16 24 28 32 36, as `broad_estimate`), the mean 6D
inclination RMSE (°) as `gyrostat / VQF`, in bold where gyrostat is behind (worse by more than
0.0005°), how far each one's 9D inclination is from its 6D, then the list of every 6D and 9D
cell where gyrostat is behind, then the per-trial 6D inclination.
"""
import argparse
import json
import pathlib
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import run_peers as rp  # noqa: E402

HALF_A = {"01", "05", "09", "14", "21", "26", "30", "34"}
HALF_B = {"03", "07", "11", "16", "24", "28", "32", "36"}
# The trial groups (run_peers.GROUPS without "all"; undisturbed/disturbed kept as summaries).
GROUPS = [g for g in rp.GROUPS if g[0] != "all"] + [("all", lambda s: True)]
RATE = 2000.0 / 7.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=rp.DEFAULT_DATA,
                    help="BROAD folder with score.py (default: $GYROSTAT_BROAD_DIR, else "
                         "../shared/real-data/broad beside the repository)")
    ap.add_argument("--every", default="1,2,3,6")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--no-9d", action="store_true", help="6D only (gyrostat and VQF)")
    ap.add_argument("--bin", default=str(rp.ROOT / "target" / "release" / "broad_estimate"))
    ap.add_argument("--out", default="/tmp/incl_groups", help="where gyrostat's estimates go")
    ap.add_argument("--json", metavar="FILE", help="write every per-trial inclination as JSON")
    args = ap.parse_args()

    data = pathlib.Path(args.data)
    score, paths = rp.broad_trials(data)
    dims = [("6D", False)] + ([] if args.no_9d else [("9D", True)])
    vqf_v = rp.pkg_version("vqf")
    base_cache = rp.CACHE
    res = {}  # (every, est, dim) -> {trial number: inclination}
    for every in (int(e) for e in args.every.split(",")):
        rp.CACHE = base_cache / f"every{every}" if every > 1 else base_cache
        trials = [rp.Trial(p, score, every) for p in paths]
        for dim, nine in dims:
            out = pathlib.Path(args.out) / f"every{every}_{dim}"
            cmd = [args.bin, "--quiet", "--every", str(every), "--out", str(out), "--data", str(data)]
            cmd += [] if nine else ["--6d"]
            for s in args.set:
                cmd += ["--set", s]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            ours, peer = {}, {}
            for tr in trials:
                num = tr.stem[:2]
                r = rp.score_file(score, tr, rp.find_estimate(out, tr.stem))
                ours[num] = r["main"]["inclination"]
                r, _, _ = rp.run_cached(f"VQF {dim}", f"vqf {vqf_v} VQF(Ts) defaults",
                                        lambda t, n=nine: rp.run_vqf(t, n), tr, score, False, None)
                peer[num] = r["main"]["inclination"]
            res[(every, "gyrostat", dim)] = ours
            res[(every, "VQF", dim)] = peer
    rp.CACHE = base_cache

    stems = [p.name[: -len(".csv.gz")] for p in paths]
    everies = sorted({k[0] for k in res})
    head = ["group (trials)", "half"] + [f"{RATE / e:.1f} Hz" for e in everies]
    rows, losses = [], []
    for gname, f in GROUPS:
        members = [s[:2] for s in stems if f(s)]
        for half, sel in (("A", HALF_A), ("B", HALF_B), ("A+B", HALF_A | HALF_B)):
            nums = [n for n in members if n in sel]
            if not nums:
                continue
            row = [f"{gname} ({' '.join(nums)})" if half == "A+B" else gname, half]
            for e in everies:
                for dim, _ in dims:
                    a = sum(res[(e, "gyrostat", dim)][n] for n in nums) / len(nums)
                    b = sum(res[(e, "VQF", dim)][n] for n in nums) / len(nums)
                    lose = a > b + 0.0005
                    if dim == "6D":
                        row.append(f"{'**' if lose else ''}{a:.3f} / {b:.3f}{'**' if lose else ''}")
                    if lose:
                        losses.append(f"{gname} {half} {dim} {RATE / e:.1f} Hz: {a:.3f} against "
                                      f"VQF {b:.3f} (+{a - b:.3f}; trials {' '.join(nums)})")
            rows.append(row)
    print("6D inclination RMSE (°), mean over the group's trials in the half: gyrostat / VQF "
          "(bold: gyrostat behind)\n")
    print(rp.md_table(head, rows))
    if not args.no_9d:
        for est in ("gyrostat", "VQF"):
            d = max(abs(res[(e, est, "9D")][n] - res[(e, est, "6D")][n])
                    for e in everies for n in res[(e, est, "6D")])
            print(f"\n{est}: 9D inclination within {d:.4f}° of 6D on every trial at every rate "
                  "(the losses below list both)")
    print("\nCells where gyrostat is behind:" + ("" if losses else " none"))
    for line in losses:
        print("- " + line)
    print("\nPer trial, 6D inclination (°) gyrostat / VQF:\n")
    head = ["trial"] + [f"{RATE / e:.1f} Hz" for e in everies]
    rows = [[s[:2]] + [f"{res[(e, 'gyrostat', '6D')][s[:2]]:.3f} / {res[(e, 'VQF', '6D')][s[:2]]:.3f}"
                       for e in everies] for s in stems]
    print(rp.md_table(head, rows))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({f"{k[0]} {k[1]} {k[2]}": v for k, v in res.items()}, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
