"""Shared helpers: the command-line tools of the repository (built by
`cargo build --release -p gyrostat-tools`) run on the same inputs as the package."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def tool(name: str) -> Path:
    """The built tool `name`: $GYROSTAT_TOOLS_DIR or target/release of the repository. Missing
    tools skip the test, unless GYROSTAT_REQUIRE_TOOLS=1 (CI), where they fail it."""
    d = Path(os.environ.get("GYROSTAT_TOOLS_DIR", ROOT / "target" / "release"))
    exe = d / name
    if not exe.is_file():
        msg = f"{exe} not built (cargo build --release -p gyrostat-tools)"
        if os.environ.get("GYROSTAT_REQUIRE_TOOLS") == "1":
            pytest.fail(msg)
        pytest.skip(msg)
    return exe


def run_tool(name: str, args: list[str], stdin: str = "") -> str:
    """stdout of the tool, which must exit 0."""
    p = subprocess.run(
        [str(tool(name)), *args], input=stdin, capture_output=True, text=True, check=False
    )
    assert p.returncode == 0, f"{name} {' '.join(args)}: {p.stderr}"
    return p.stdout


def csv_rows(rows: np.ndarray) -> str:
    """Rows as CSV text, each number in the shortest form that round-trips (repr)."""
    return "".join(",".join(repr(float(x)) for x in r) + "\n" for r in rows)


def parse_csv(text: str, dtype=np.float64, header: bool = False) -> np.ndarray:
    lines = text.strip().splitlines()[1 if header else 0 :]
    return np.array([[dtype(x) for x in line.split(",")] for line in lines])


def random_unit_quats(n: int, seed: int) -> np.ndarray:
    """Unit quaternions of normal components (every attitude equally likely), scalar last."""
    q = np.random.default_rng(seed).normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def angle_between(qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
    """The rotation angle (rad) between rows of two unit-quaternion arrays (same order), by
    the numerically accurate 2 atan2(|qa - qb|, |qa + qb|) on the nearer sign."""
    d = np.minimum(np.linalg.norm(qa - qb, axis=1), np.linalg.norm(qa + qb, axis=1))
    s = np.maximum(np.linalg.norm(qa - qb, axis=1), np.linalg.norm(qa + qb, axis=1))
    return 4.0 * np.arctan2(d, s)
