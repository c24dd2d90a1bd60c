#!/usr/bin/env python3
"""VQF 6D inclination on BROAD with and without its integration's half-step lead.

VQF 2.1.2 (PyPI, defaults, online) integrates each step with the rate sample at its end, which
carries its strapdown attitude Δt/2 ahead of the samples (0.175 ms per 100 Hz of rate: 1.75 ms at
285.7 Hz, 3.5 ms at 142.9 Hz, 5.25 ms at 95.2 Hz, 10.5 ms at 47.6 Hz). Fed the trapezoid of the
two rate samples of each step instead (`trap`: the mean of rows i−1 and i), it integrates to the
samples' own time, as gyrostat does before its output lead (`gyro_delay`). Prints BROAD's
inclination RMSE (score.py, movement phase) per trial, `raw/trap`, and the means, for every
decimation asked for (the rows `run_peers.py --every N` and `broad_estimate --every N` read).

    python3 benches/broad/vqf_alignment.py [--every 1,2,3,6] [--trials 07,09]
"""
import argparse
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import run_peers as rp  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", default=rp.DEFAULT_DATA)
    ap.add_argument("--every", default="1,2,3,6")
    ap.add_argument("--trials", default="", help="comma-separated trial numbers (default: all)")
    args = ap.parse_args()
    from vqf import VQF

    data = pathlib.Path(args.data)
    score, paths = rp.broad_trials(data, [s for s in args.trials.split(",") if s])
    for every in (int(e) for e in args.every.split(",")):
        res = {}
        for p in paths:
            tr = rp.Trial(p, score, every)
            row = []
            for trap in (False, True):
                g = tr.gyr.copy()
                if trap:
                    g[1:] = 0.5 * (tr.gyr[1:] + tr.gyr[:-1])
                q = VQF(tr.ts).updateBatch(g, tr.acc.copy())["quat6D"]
                row.append(rp.score_estimate(score, tr, rp.est_from_array(tr, q))["main"]["inclination"])
            res[p.name[:2]] = row
        per = "  ".join(f"{k} {a:.3f}/{b:.3f}" for k, (a, b) in res.items())
        raw = np.mean([a for a, _ in res.values()])
        trap = np.mean([b for _, b in res.values()])
        print(f"every {every}: {per} | mean raw {raw:.3f} trap {trap:.3f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
