#!/usr/bin/env python3
"""Regenerates the trimmed real-data fixtures of this folder from the full files.

Usage: python3 data/trim.py [BROAD_DIR] [FUSION_DIR]
  BROAD_DIR   the full BROAD trials (gzip CSV, one header line; default $GYROSTAT_BROAD_DIR or
              ../shared/real-data/broad beside the repository)
  FUSION_DIR  the folder with x-io Fusion's sensor_data.csv (default ../shared/real-data/fusion)

Each fixture is the header and the first rows of the full file, copied byte for byte (no value is
parsed or rewritten): a BROAD trial up to (excluding) the first row with t_s >= SECONDS, the
Fusion log's first FUSION_ROWS samples. Written with gzip level 9, no file name and mtime 0, so
a rerun on the same input gives the same bytes. Standard library only.
"""
import gzip
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

# (trial stem, seconds kept): the rest phase and the first part of the movement phase.
# Trial 07: rest until 26.5 s, movement scored from there; 60 s keeps 33.5 s of fast rotation.
# Trial 32: rest until 41.3 s; 65 s keeps 23.7 s of movement near the attached magnet.
BROAD = [("07_undisturbed_fast_rotation_B", 60), ("32_disturbed_attached_magnet_1cm", 65)]
# The Fusion log's first 4000 samples (40.0 s): its fastest turn (6.4 rad/s) and its longest
# (30.24 ms) and shortest (7.56 ms) steps are inside.
FUSION_ROWS = 4000


def write_gz(path, lines):
    with open(path, "wb") as raw:
        with gzip.GzipFile(filename="", mode="wb", compresslevel=9, fileobj=raw, mtime=0) as f:
            f.write(b"".join(lines))


def main():
    broad = Path(sys.argv[1] if len(sys.argv) > 1 else
                 os.environ.get("GYROSTAT_BROAD_DIR", ROOT.parent / "shared" / "real-data" / "broad"))
    fusion = Path(sys.argv[2] if len(sys.argv) > 2 else ROOT.parent / "shared" / "real-data" / "fusion")
    for stem, seconds in BROAD:
        with gzip.open(broad / f"{stem}.csv.gz", "rb") as f:
            lines = f.readlines()
        header, rows = lines[0], lines[1:]
        assert header.startswith(b"t_s,"), header
        kept = [r for r in rows if float(r.split(b",", 1)[0]) < seconds]
        assert kept == rows[: len(kept)], "t_s not increasing"
        out = HERE / "broad" / f"{stem}.first{seconds}s.csv.gz"
        write_gz(out, [header] + kept)
        print(f"{out.relative_to(ROOT)}: {len(kept)} of {len(rows)} rows, {out.stat().st_size} bytes")
    with open(fusion / "sensor_data.csv", "rb") as f:
        lines = f.readlines()
    out = HERE / "fusion" / f"sensor_data.first{FUSION_ROWS}.csv.gz"
    write_gz(out, lines[: 1 + FUSION_ROWS])
    print(f"{out.relative_to(ROOT)}: {FUSION_ROWS} of {len(lines) - 1} rows, {out.stat().st_size} bytes")


if __name__ == "__main__":
    main()
