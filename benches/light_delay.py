#!/usr/bin/env python3
"""The light mode's magnetometer delay against the sensor's (issue 28 item 2), in two parts.

    cargo build --release -p host-tests --bin broad_estimate \\
        -p gyrostat-tools --bin estimate --bin synthesize
    python3 benches/light_delay.py [--every 1,2,3,6] [--skip-broad] [--skip-synthetic]

synthetic: logs of `synthesize` from a sensor spec whose only timing error is the magnetometer's
    delay (`mag_delay` = 0, 10, 20 ms; white noise on every channel, no bias, scale or iron error;
    100 Hz magnetometer samples on every row), the evaluate.py grid's motion (two 10 s hand-held
    phases, 5 s rests), 25, 50, 100, 285.7 and 1000 Hz, seeds 0 and 1. The light mode (`estimate
    --mode light`) is scored over fixed delays 0-30 ms (`--set mag_delay=D --set
    mag_delay_estimation_time=0`), once with the default `gyro_delay` (2.9 ms: the output carried
    2.9 ms ahead, which these sensors do not need) and once with `gyro_delay = 0` (the sensor's);
    the full mode with the true delay fixed beside it. Prints the mean total RMSE (deg) per
    true delay and rate, the best fixed delay marked.

broad: the 16 BROAD trials at every Nth row (--every). Per trial: the full mode's online delay
    estimate (`broad_estimate`'s "delay ms" column), the light mode's total with its default delay
    (Mode::LIGHT_MAG_DELAY, 9.25 ms) and with that trial's full-mode estimate fixed; the means per
    half (A = 01 05 09 14 21 26 30 34, B = 03 07 11 16 24 28 32 36) and per group (undisturbed
    01-21, disturbed 24-36). Then the light and the full mode over fixed delays 0-20 ms, mean total
    per half, and each trial's best fixed delay in both modes.

Data: BROAD from ../shared/real-data/broad beside the repository or $GYROSTAT_BROAD_DIR (as
broad_estimate finds it). Logs are written to target/light-delay/ and deleted after scoring.
"""
import argparse
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BIN = ROOT / "target" / "release"
OUT = ROOT / "target" / "light-delay"
HALF_A = ["01", "05", "09", "14", "21", "26", "30", "34"]
HALF_B = ["03", "07", "11", "16", "24", "28", "32", "36"]
UNDISTURBED = ["01", "03", "05", "07", "09", "11", "14", "16", "21"]
LIGHT = ["--set", "light_period=0.025"]
RATES = [25.0, 50.0, 100.0, 285.714285714, 1000.0]
TRUTH = re.compile(r"truth: total (\S+) deg")
ROW = re.compile(r"^\| (\d\d) \| ([\d.]+) \| [\d.]+ \| [\d.]+ \|.*\| ([\d.]+|-) \| [^|]*\|$")


def fixed(d):
    return ["--set", f"mag_delay={d}", "--set", "mag_delay_estimation_time=0"]


def broad(every, flags):
    """Per trial (total, delay ms) from one broad_estimate run."""
    out = subprocess.run([str(BIN / "broad_estimate"), "--every", str(every), *flags],
                         capture_output=True, text=True, check=True).stdout
    rows = {}
    for line in out.splitlines():
        m = ROW.match(line)
        if m:
            rows[m.group(1)] = (float(m.group(2)), float(m.group(3)))
    if sorted(rows) != sorted(HALF_A + HALF_B):
        sys.exit(f"broad_estimate --every {every}: not the 16 shared trials")
    return rows


def mean(rows, trials):
    return sum(rows[t][0] for t in trials) / len(trials)


def broad_part(everies):
    for n in everies:
        full = broad(n, [])
        light = broad(n, LIGHT)
        own = {}
        for t, (_, d) in full.items():
            own[t] = broad(n, LIGHT + fixed(d / 1000.0))[t]
        disturbed = [t for t in HALF_A + HALF_B if t not in UNDISTURBED]
        print(f"\n### BROAD every {n} row(s): the light mode with each trial's full-mode delay\n")
        print("| trial | full-mode delay (ms) | light, 9.25 ms | light, own delay | change |")
        print("|---|---:|---:|---:|---:|")
        for t in sorted(full):
            a, b = light[t][0], own[t][0]
            print(f"| {t} | {full[t][1]:.2f} | {a:.3f} | {b:.3f} | {b - a:+.3f} |")
        for name, ts in (("half A", HALF_A), ("half B", HALF_B), ("undisturbed", UNDISTURBED),
                         ("disturbed", disturbed)):
            print(f"| **{name}** | | {mean(light, ts):.4f} | {mean(own, ts):.4f} | "
                  f"{mean(own, ts) - mean(light, ts):+.4f} |")
        delays = [k / 1000.0 for k in range(21)]
        scans = {}
        for mode, flags in (("light", LIGHT), ("full", [])):
            scans[mode] = {d: broad(n, flags + fixed(d)) for d in delays}
        print(f"\nFixed delays, mean total per half (every {n}):\n")
        print("| delay (ms) | light A | light B | full A | full B |")
        print("|---:|---:|---:|---:|---:|")
        for d in delays:
            cells = [mean(scans[m][d], h) for m in ("light", "full") for h in (HALF_A, HALF_B)]
            print(f"| {d * 1000:.0f} | " + " | ".join(f"{c:.4f}" for c in cells) + " |")
        print("\nEach trial's best fixed delay (ms), light / full: " + ", ".join(
            f"{t} {min(delays, key=lambda d: scans['light'][d][t][0]) * 1000:.0f} / "
            f"{min(delays, key=lambda d: scans['full'][d][t][0]) * 1000:.0f}"
            for t in sorted(full)))


def synth_log(delay, rate, seed):
    OUT.mkdir(parents=True, exist_ok=True)
    spec = OUT / f"delay{delay}.spec"
    spec.write_text("rate = 100\ngyro_noise_density = 4.89e-5\naccel_noise_density = 6.86e-4\n"
                    f"mag_noise = 0.1\nmag_delay = {delay}\n")
    log = OUT / f"delay{delay}_{rate:g}_{seed}.csv"
    with open(log, "w") as f:
        subprocess.run([str(BIN / "synthesize"), "--sensor", str(spec), "--rate", repr(rate),
                        "--seed", str(seed), "--duration", "10", "--phases", "2", "--rest", "5"],
                       stdout=f, check=True)
    return log


def score(log, flags):
    p = subprocess.run([str(BIN / "estimate"), "--truth", *flags, str(log)],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, check=True)
    return float(TRUTH.search(p.stderr).group(1))


def synthetic_part():
    delays = [k / 1000.0 for k in range(0, 31, 5)]
    for gyro_delay in (None, 0.0):
        g = [] if gyro_delay is None else ["--set", "gyro_delay=0"]
        label = "default gyro_delay (2.9 ms)" if gyro_delay is None else "gyro_delay = 0"
        print(f"\n### Synthetic, light mode over fixed delays, {label}\n")
        print("| true delay | rate | " + " | ".join(f"{d * 1000:.0f} ms" for d in delays)
              + " | full, true delay fixed |")
        print("|---|---|" + "---:|" * (len(delays) + 1))
        for true in (0.0, 0.01, 0.02):
            for rate in RATES:
                logs = [synth_log(true, rate, s) for s in (0, 1)]
                jobs = [(log, ["--mode", "light", *g, *fixed(d)]) for d in delays for log in logs]
                jobs += [(log, [*g, *fixed(true)]) for log in logs]
                with ThreadPoolExecutor(2) as ex:
                    res = list(ex.map(lambda j: score(*j), jobs))
                for log in logs:
                    log.unlink()
                cells = [(res[2 * i] + res[2 * i + 1]) / 2 for i in range(len(delays) + 1)]
                best = min(range(len(delays)), key=lambda i: cells[i])
                print(f"| {true * 1000:.0f} ms | {rate:g} Hz | " + " | ".join(
                    f"**{c:.4f}**" if i == best else f"{c:.4f}"
                    for i, c in enumerate(cells[:-1])) + f" | {cells[-1]:.4f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--every", default="1,2,3,6")
    ap.add_argument("--skip-broad", action="store_true")
    ap.add_argument("--skip-synthetic", action="store_true")
    args = ap.parse_args()
    try:
        everies = [int(x) for x in args.every.split(",")]
    except ValueError:
        ap.error("--every: a comma-separated list of whole numbers")
    for exe in ("broad_estimate", "estimate", "synthesize"):
        if not (BIN / exe).exists():
            sys.exit(f"{BIN / exe} not found: build it (see the docstring)")
    if not args.skip_synthetic:
        synthetic_part()
    if not args.skip_broad:
        broad_part(everies)


if __name__ == "__main__":
    main()
