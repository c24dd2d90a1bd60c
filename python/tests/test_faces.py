"""One log, three faces, the same rows bit for bit: the ``estimate`` tool, Python's
``gyrostat.estimate`` and a C program on the C interface (``ffi/tests/c/faces.c``: the sample
clock of the sensor front end and the estimator) read the same CSV file. The tool and Python run
the loop of ``gyrostat-pipeline`` (pipeline/src/estimate.rs); the C program writes the same loop
with the C interface. Logs: the trimmed BROAD trial 07 (data/broad/), a log that starts while
the sensor turns at 5 rad/s, a log with a time gap, clipped samples (a rate beyond the
gyroscope's range, a garbage specific force), and non-finite rows (skipped as gaps, or ending
the run at the same line in every face), and each rate rule by name; f64 and f32.

The C program is built with the host C compiler against target/release/libgyrostat_ffi.a (the
README test command builds it: ffi/tests/c_host.rs); without a compiler or the library the test
skips, unless GYROSTAT_REQUIRE_TOOLS=1 (CI), where it fails."""

from __future__ import annotations

import csv
import gzip
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import gyrostat
from gyrostat import GyrostatError

from conftest import ROOT, tool

G = 9.81
B_EARTH = np.array([0.0, 15.8, -40.7])
BROAD_07 = ROOT / "data" / "broad" / "07_undisturbed_fast_rotation_B.first60s.csv.gz"


def _missing(msg: str):
    if os.environ.get("GYROSTAT_REQUIRE_TOOLS") == "1":
        pytest.fail(msg)
    pytest.skip(msg)


@pytest.fixture(scope="module")
def c_program(tmp_path_factory) -> Path:
    """faces.c built against the host static library of the C interface."""
    cc = os.environ.get("CC", "cc")
    if shutil.which(cc) is None:
        _missing(f"no C compiler `{cc}` to build ffi/tests/c/faces.c")
    lib = Path(os.environ.get("GYROSTAT_TOOLS_DIR", ROOT / "target" / "release")) / "libgyrostat_ffi.a"
    if not lib.is_file():
        _missing(f"{lib} not built (cargo build --release -p gyrostat-ffi)")
    exe = tmp_path_factory.mktemp("faces") / "faces"
    libs = ["-lgcc_s", "-lutil", "-lrt", "-lpthread", "-lm", "-ldl", "-lc"]
    p = subprocess.run(
        [cc, "-std=c11", "-Wall", "-Wextra", "-Werror", "-O2", "-ffp-contract=off",
         "-I", str(ROOT / "ffi" / "include"), str(ROOT / "ffi" / "tests" / "c" / "faces.c"),
         str(lib), *libs, "-o", str(exe)],
        capture_output=True, text=True, check=False,
    )
    assert p.returncode == 0, f"building faces.c: {p.stderr}"
    return exe


def write_log(path: Path, t, gyro, accel, mag) -> None:
    """The log as CSV, every number in the shortest form that round-trips (repr)."""
    with open(path, "w", encoding="utf-8") as f:
        f.write("t,gx,gy,gz,ax,ay,az,mx,my,mz\n")
        for k in range(len(t)):
            values = [t[k], *gyro[k], *accel[k], *mag[k]]
            f.write(",".join(repr(float(x)) for x in values) + "\n")


def parse_rows(text: str, dtype):
    """Rows of the tool or the C program: t text, 7 numbers in `dtype` (the value the printed
    text rounds to in that type: f32 output round-trips in f32), the 4 flags."""
    rows = []
    for line in text.strip().splitlines()[1:]:
        f = line.split(",")
        rows.append((f[0], np.array([dtype(x) for x in f[1:8]]), tuple(f[8:12])))
    return rows


def python_rows(est, dtype, t_text):
    """Python's arrays as the same rows: NaN before the attitude is initialised (the tool
    prints nan there), the flags the arrays give (rest, accel and mag used or not, skipped)."""
    rows = []
    for k in range(len(t_text)):
        if est.initialized[k]:
            v = np.concatenate([est.q[k], est.bias[k]]).astype(dtype)
        else:
            v = np.full(7, np.nan, dtype=dtype)
        rows.append((t_text[k], v, est.skipped[k], est.at_rest[k], est.accel_used[k], est.mag_used[k]))
    return rows


def same(a: np.ndarray, b: np.ndarray) -> bool:
    """Bit for bit (NaN equal to NaN)."""
    return a.dtype == b.dtype and a.tobytes() == b.tobytes()


def run(cmd, stdin_path: Path):
    with open(stdin_path, "rb") as f:
        return subprocess.run(cmd, stdin=f, capture_output=True, text=True, check=False)


def check_faces(c_program: Path, path: Path, t, gyro, accel, mag, *, skip: bool, expect_error_row=None,
                rate_rule=None):
    """The log through the three faces in f64 and f32: the same rows, or the same failing row.
    `rate_rule`: a rule's name given to every face (the tool's `--set rate_rule=`, Python's
    `rate_rule=`, the C program's `rate_rule=`), or None for the defaults. Returns the tool's
    f64 output."""
    t_text = [repr(float(x)) for x in t]
    rule_cli = [] if rate_rule is None else ["--set", f"rate_rule={rate_rule}"]
    rule_c = [] if rate_rule is None else [f"rate_rule={rate_rule}"]
    out = None
    for precision, dtype in [("f64", np.float64), ("f32", np.float32)]:
        cli = run([str(tool("estimate")), *(["--f32"] if precision == "f32" else []),
                   *(["--skip-bad-rows"] if skip else []), *rule_cli, str(path)], path)
        c = run([str(c_program), precision, *(["skip"] if skip else []), *rule_c], path)
        if precision == "f64":
            out = cli.stdout
        if expect_error_row is not None:
            line = expect_error_row + 2  # the header is line 1
            assert cli.returncode == 1 and cli.stderr.startswith(f"error: line {line}: "), cli.stderr
            assert c.returncode == 1 and c.stderr.startswith(f"error: line {line}: "), c.stderr
            with pytest.raises(GyrostatError) as e:
                gyrostat.estimate(t, gyro, accel, mag, precision=precision, skip_errors=skip)
            assert e.value.row == expect_error_row
            # The rows before the failing one agree too.
            tool_rows = parse_rows(cli.stdout, dtype)
            c_rows = parse_rows(c.stdout, dtype)
            assert len(tool_rows) == len(c_rows) == expect_error_row
            for r1, r2 in zip(tool_rows, c_rows):
                assert r1[0] == r2[0] and same(r1[1], r2[1]) and r1[2] == r2[2]
            continue
        assert cli.returncode == 0, cli.stderr
        assert c.returncode == 0, c.stderr
        est = gyrostat.estimate(t, gyro, accel, mag, precision=precision, skip_errors=skip,
                                rate_rule=rate_rule)
        tool_rows = parse_rows(cli.stdout, dtype)
        c_rows = parse_rows(c.stdout, dtype)
        py_rows = python_rows(est, dtype, t_text)
        assert len(tool_rows) == len(c_rows) == len(py_rows) == len(t)
        for k, (r_tool, r_c, r_py) in enumerate(zip(tool_rows, c_rows, py_rows)):
            where = f"{path.name} {precision} row {k}"
            assert r_tool[0] == r_c[0] == r_py[0], where
            assert same(r_tool[1], r_c[1]), f"{where}: tool {r_tool[1]} C {r_c[1]}"
            assert same(r_tool[1], r_py[1]), f"{where}: tool {r_tool[1]} Python {r_py[1]}"
            assert r_tool[2] == r_c[2], f"{where}: flags tool {r_tool[2]} C {r_c[2]}"
            rest, gyro_flag, accel_flag, mag_flag = r_tool[2]
            skipped_row = gyro_flag == "skipped"
            assert r_py[2] == skipped_row, where
            assert r_py[3] == (rest == "1"), where
            assert r_py[4] == (accel_flag == "used"), where
            assert r_py[5] == (mag_flag == "used"), where
    return out


def rotating(n: int, dt: float, rate: float, seed: int):
    """A sensor turning about z at `rate` (rad/s) from its first sample, level, with a little
    noise that never repeats; the field turns with it."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    a = rate * t
    gyro = np.column_stack([np.zeros(n), np.zeros(n), np.full(n, rate)]) + rng.normal(0, 1e-3, (n, 3))
    accel = np.tile([0.0, 0.0, G], (n, 1)) + rng.normal(0, 1e-2, (n, 3))
    c, s = np.cos(a), np.sin(a)
    mag = np.column_stack([c * B_EARTH[0] + s * B_EARTH[1], -s * B_EARTH[0] + c * B_EARTH[1],
                           np.full(n, B_EARTH[2])]) + rng.normal(0, 0.1, (n, 3))
    return t, gyro, accel, mag


def test_broad_trial(c_program, tmp_path):
    with gzip.open(BROAD_07, "rt") as f:
        rows = list(csv.DictReader(f))
    col = lambda names: np.array([[float(r[n]) for n in names] for r in rows])
    t = col(["t_s"])[:, 0]
    gyro = col(["gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s"])
    accel = col(["acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"])
    mag = col(["mag_x_uT", "mag_y_uT", "mag_z_uT"])
    path = tmp_path / "broad07.csv"
    write_log(path, t, gyro, accel, mag)
    check_faces(c_program, path, t, gyro, accel, mag, skip=False)


def test_log_starting_in_motion(c_program, tmp_path):
    """5 rad/s from the first sample: at 100 Hz, and at 1 Hz (the first step would be 5 rad)."""
    for n, dt in [(400, 0.01), (12, 1.0)]:
        t, gyro, accel, mag = rotating(n, dt, 5.0, seed=n)
        if dt == 1.0:
            gyro[1:] = 0.0  # then at rest: only the first sample turns
        path = tmp_path / f"motion-{n}.csv"
        write_log(path, t, gyro, accel, mag)
        check_faces(c_program, path, t, gyro, accel, mag, skip=False)


def test_log_with_a_time_gap(c_program, tmp_path):
    """A 2.37 s gap in a 100 Hz log turning at 0.3 rad/s: propagated over, the same in every face."""
    t, gyro, accel, mag = rotating(900, 0.01, 0.3, seed=3)
    t[450:] += 2.37
    path = tmp_path / "gap.csv"
    write_log(path, t, gyro, accel, mag)
    check_faces(c_program, path, t, gyro, accel, mag, skip=False)


def test_clipped_samples(c_program, tmp_path):
    """A rate beyond the gyroscope's range (2000 deg/s: clipped by the estimator, `saturated`)
    and a garbage specific force (1e30 m/s^2: beyond the accelerometer's range, ignored)."""
    t, gyro, accel, mag = rotating(600, 0.01, 0.5, seed=4)
    gyro[300] = [61.0, -2.0, 40.0]
    accel[301] = [1e30, 0.0, 1e30]
    accel[350] = [0.0, 400.0, 0.0]
    path = tmp_path / "clipped.csv"
    write_log(path, t, gyro, accel, mag)
    check_faces(c_program, path, t, gyro, accel, mag, skip=False)
    out = run([str(tool("estimate")), str(path)], path).stdout.splitlines()
    assert out[301].split(",")[9] == "saturated"
    assert out[302].split(",")[10] == "saturated"


def test_non_finite_rows(c_program, tmp_path):
    """A NaN gyroscope value, an infinite one, a NaN time stamp: skipped as gaps in every face
    (--skip-bad-rows, skip_errors=True, the C program's skip), or the run ends at the first of
    them in every face; and a value finite in f64 but beyond f32 (a bad row in f32 only)."""
    t, gyro, accel, mag = rotating(500, 0.01, 0.4, seed=5)
    gyro[200, 1] = np.nan
    gyro[201, 0] = np.inf
    t[320] = np.nan
    gyro[400, 2] = 1e39
    path = tmp_path / "nonfinite.csv"
    write_log(path, t, gyro, accel, mag)
    check_faces(c_program, path, t, gyro, accel, mag, skip=True)
    check_faces(c_program, path, t, gyro, accel, mag, skip=False, expect_error_row=200)


def test_rate_rules(c_program, tmp_path):
    """Each rate rule by name in every face (the tool's --set, Python's keyword, the C struct's
    code): the same rows bit for bit; the three rules give three different runs, one of them
    the defaults' run; an unknown name is refused by every face."""
    t, gyro, accel, mag = rotating(600, 0.01, 1.5, seed=6)
    gyro[:, 0] += 0.4 * np.sin(0.013 * np.arange(600) ** 1.3)  # a rate that bends
    path = tmp_path / "rules.csv"
    write_log(path, t, gyro, accel, mag)
    runs = {rule: check_faces(c_program, path, t, gyro, accel, mag, skip=False, rate_rule=rule)
            for rule in ["trapezoid", "magnus4", "cf4"]}
    assert len(set(runs.values())) == 3
    default = run([str(tool("estimate")), str(path)], path).stdout
    assert sum(out == default for out in runs.values()) == 1
    bad_cli = run([str(tool("estimate")), "--set", "rate_rule=rk4", str(path)], path)
    assert bad_cli.returncode == 2 and bad_cli.stderr.startswith("error: "), bad_cli.stderr
    bad_c = run([str(c_program), "f64", "rate_rule=rk4"], path)
    assert bad_c.returncode == 2 and bad_c.stdout == "", bad_c.stderr
    with pytest.raises(ValueError, match='rate_rule: unknown "rk4"'):
        gyrostat.estimate(t, gyro, accel, mag, rate_rule="rk4")
