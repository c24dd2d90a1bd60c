//! The three command-line tools under an adversarial input campaign: garbage lines (blank,
//! missing and extra fields, non-numbers, non-UTF-8 bytes, very long lines, NaN/inf text, huge
//! and tiny values) mixed at random with valid rows, bad flags (unknown, missing values, zero and
//! negative counts and steps, non-UTF-8 arguments), values that would overflow, and closed
//! output pipes. Each run must end with its documented status and message (naming the line),
//! keep every valid row, and never panic.
//!
//! The oracles are the documented contracts, not the tools' own output: `convert` converts every
//! valid row and names every bad one; `propagate` stops at the first bad line and prints what a
//! run on the lines before it prints (a run the test makes itself, on the clean prefix); the
//! attitude rows are checked against quaternions the test knows.
//!
//! `GYROSTAT_CLI_CAMPAIGN=N` sets the number of random streams per tool and setting (default 12,
//! a few seconds under `cargo test --workspace --release`).

use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;

use crate::cli::{Closed, Output, numbers, run, run_closed, run_raw};

/// Random streams per tool and setting.
fn rounds() -> usize {
    std::env::var("GYROSTAT_CLI_CAMPAIGN")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(12)
}

/// A small deterministic generator (SplitMix64), so a failure names a reproducible seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// No panic, a normal exit.
fn no_panic(what: &str, out: &Output) {
    assert!(
        !out.stderr.contains("panicked") && out.status.is_some() && out.status != Some(101),
        "{what}: status {:?}, stderr {}",
        out.status,
        out.stderr
    );
}

/// The `error: line N: ` lines of stderr, as line numbers.
fn error_lines(stderr: &str, prefix: &str) -> Vec<u64> {
    stderr
        .lines()
        .filter_map(|l| l.strip_prefix(prefix))
        .filter_map(|l| l.split(':').next()?.parse().ok())
        .collect()
}

/// Garbage lines for a row of `fields` numbers (first the kind, for the report).
pub(crate) fn garbage(fields: usize) -> Vec<(&'static str, Vec<u8>)> {
    let row = |f: &dyn Fn(usize) -> String| -> Vec<u8> {
        (0..fields)
            .map(f)
            .collect::<Vec<_>>()
            .join(",")
            .into_bytes()
    };
    let mut long = vec![b'1'; (1 << 20) + 10];
    long.extend_from_slice(b",0,0");
    vec![
        ("missing field", row(&|_| "0".into())[2..].to_vec()),
        (
            "extra field",
            [row(&|_| "0".into()), b",0".to_vec()].concat(),
        ),
        (
            "not a number",
            row(&|i| if i == 1 { "x".into() } else { "0".into() }),
        ),
        ("empty fields", vec![b','; fields - 1]),
        (
            "NaN text",
            row(&|i| if i == 0 { "NaN".into() } else { "0".into() }),
        ),
        (
            "inf text",
            row(&|i| if i == 1 { "-inf".into() } else { "0".into() }),
        ),
        (
            "overflowing text",
            row(&|i| if i == 0 { "1e400".into() } else { "0".into() }),
        ),
        (
            "non-UTF-8 bytes",
            [b"\xff\xfe".to_vec(), row(&|_| "0".into())[1..].to_vec()].concat(),
        ),
        (
            "non-UTF-8 tail",
            [row(&|_| "0".into()), b"\xc3".to_vec()].concat(),
        ),
        ("very long line", long),
        ("words", b"hello world".to_vec()),
        ("control bytes", b"\x00\x01\x02".to_vec()),
    ]
}

/// Blank lines: every tool skips them (and counts them).
pub(crate) const BLANKS: [&[u8]; 4] = [b"", b"   ", b"\t", b" \r"];

// ---------------------------------------------------------------------------------------------
// convert

/// Valid quaternion rows and their `--to quat` output (canonical: w >= 0).
const QUATS: [(&str, &str); 4] = [
    ("1,0,0,0", "1.0,0.0,0.0,0.0"),
    ("0,0,1,0", "0.0,0.0,1.0,0.0"),
    (" 0 , 0 , 0 , 1 ", "0.0,0.0,0.0,1.0"),
    ("0,1,0,0", "0.0,1.0,0.0,0.0"),
];

#[test]
fn convert_keeps_every_valid_row_and_names_every_bad_line() {
    let bad = garbage(4);
    let (mut tried, mut errors) = (0usize, 0usize);
    for round in 0..rounds() {
        let mut rng = Rng(0xC0_4E47 + round as u64);
        let mut input = Vec::new();
        let (mut expected, mut bad_lines) = (Vec::new(), Vec::new());
        let lines = 5 + rng.below(30);
        for n in 1..=lines as u64 {
            match rng.below(3) {
                0 => {
                    let (row, out) = QUATS[rng.below(QUATS.len())];
                    input.extend_from_slice(row.as_bytes());
                    expected.push(out);
                }
                1 => input.extend_from_slice(BLANKS[rng.below(BLANKS.len())]),
                _ => {
                    input.extend_from_slice(&bad[rng.below(bad.len())].1);
                    bad_lines.push(n);
                }
            }
            // The last line sometimes ends without a line break, sometimes with CRLF.
            if n < lines as u64 || rng.below(2) == 0 {
                input.extend_from_slice(if rng.below(4) == 0 { b"\r\n" } else { b"\n" });
            }
        }
        let f32 = round % 2 == 1;
        let mut args: Vec<OsString> = ["--from", "quat", "--to", "quat"]
            .map(OsString::from)
            .into();
        if f32 {
            args.push("--f32".into());
        }
        let out = run_raw("convert", &args, input.clone());
        no_panic(&format!("convert round {round}"), &out);
        // The shortest round-trip forms of 0 and 1 are the same in f32 and f64.
        assert_eq!(
            out.lines(),
            expected,
            "round {round}: input {:?}",
            String::from_utf8_lossy(&input)
        );
        assert_eq!(
            error_lines(&out.stderr, "error: line "),
            bad_lines,
            "round {round}: {}",
            out.stderr
        );
        assert_eq!(
            out.status,
            Some(if bad_lines.is_empty() { 0 } else { 1 }),
            "round {round}"
        );
        tried += lines;
        errors += bad_lines.len();
    }
    println!(
        "convert: {} streams, {tried} lines, {errors} bad lines named",
        rounds()
    );
}

#[test]
fn convert_rejects_values_at_the_ends_of_the_range() {
    // Each row alone: a typed line error (status 1), no NaN or inf on stdout.
    for (args, row) in [
        (
            &["--from", "axis-angle", "--to", "quat"][..],
            "5e-324,0,0,1",
        ),
        (
            &["--from", "axis-angle", "--to", "quat", "--f32"][..],
            "1e-45,0,0,1",
        ),
        (
            &["--from", "quat", "--to", "quat", "--normalize"][..],
            "5e-324,0,0,0",
        ),
        (
            &["--from", "quat", "--to", "quat", "--normalize"][..],
            "1e300,1e300,1e300,1e300",
        ),
        (&["--from", "rotvec", "--to", "quat"][..], "1e308,1e308,0"),
        (
            &["--from", "matrix", "--to", "quat", "--normalize"][..],
            "1e200,0,0,0,1e200,0,0,0,1e200",
        ),
        (
            &["--op", "rotate", "--from", "quat"][..],
            "1,0,0,0,1e308,1e308,1e308",
        ),
        (
            &["--op", "slerp", "--from", "quat", "--to", "quat"][..],
            "1,0,0,0,0,1,0,0,1.7976931348623157e308",
        ),
        (
            &["--from", "gibbs", "--to", "quat"][..],
            "1e300,1e300,1e300",
        ),
        (&["--from", "mrp", "--to", "quat"][..], "1e300,1e300,1e300"),
    ] {
        let out = run("convert", args, &format!("1,0,0,0\n{row}\n"));
        no_panic(&format!("{args:?} {row}"), &out);
        let bad = out
            .stdout
            .to_lowercase()
            .split([',', '\n'])
            .any(|f| f.contains("nan") || f.contains("inf"));
        assert!(!bad, "{args:?} {row}: {}", out.stdout);
        // The first row may or may not fit the operation's fields; the huge row must not
        // produce a row of non-finite numbers: either a line error or finite output.
        if out.status == Some(1) {
            assert!(
                out.stderr.contains("error: line "),
                "{args:?} {row}: {}",
                out.stderr
            );
        } else {
            assert_eq!(out.status, Some(0), "{args:?} {row}: {}", out.stderr);
        }
    }
    // The case of the report (a NaN row with exit 0): the library normalises a subnormal axis
    // exactly (5e-324·x̂ has the direction x̂), so the row is the rotation by 1 rad about x, and
    // the row after it is kept.
    let out = run(
        "convert",
        &["--from", "axis-angle", "--to", "quat"],
        "5e-324,0,0,1\n0,0,1,1\n",
    );
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let rows = out.lines();
    assert_eq!(rows.len(), 2, "{}", out.stdout);
    let q: Vec<f64> = rows[0].split(',').map(|f| f.parse().unwrap()).collect();
    let want = [0.5f64.cos(), 0.5f64.sin(), 0.0, 0.0];
    for (a, b) in q.iter().zip(want) {
        assert!((a - b).abs() < 1e-15, "{}", rows[0]);
    }
}

// ---------------------------------------------------------------------------------------------
// propagate

/// Small valid samples (increments in rad, rates in rad/s).
const SAMPLES: [&str; 4] = [
    "0.001,0,0",
    "0,0.002,0",
    "0,0,-0.001",
    " 0.0005 , 0.0005 , 0 ",
];

#[test]
fn propagate_stops_at_the_first_bad_line_with_what_the_lines_before_give() {
    let bad = garbage(3);
    let settings: [&[&str]; 4] = [
        &["--input", "increments", "--algo", "coning2", "--dt", "0.01"],
        &[
            "--input",
            "increments",
            "--algo",
            "coning4",
            "--dt",
            "0.01",
            "--f32",
        ],
        &["--input", "rates", "--algo", "magnus4", "--dt", "0.01"],
        &["--input", "rates", "--algo", "rk4", "--dt", "0.01", "--f32"],
    ];
    let mut tried = 0usize;
    for (s, setting) in settings.iter().enumerate() {
        for round in 0..rounds() {
            let mut rng = Rng(0x9209 + 1000 * s as u64 + round as u64);
            let every = ["1", "3", "7"][rng.below(3)];
            let mut args: Vec<&str> = setting.to_vec();
            args.extend(["--every", every]);
            // Valid samples and blank lines, then (usually) one bad line, then more lines.
            let (mut prefix, mut input) = (Vec::new(), Vec::new());
            let mut n = 0u64;
            let valid = rng.below(12);
            let mut k = 0;
            while k < valid {
                n += 1;
                if rng.below(4) == 0 {
                    input.extend_from_slice(BLANKS[rng.below(BLANKS.len())]);
                } else {
                    input.extend_from_slice(SAMPLES[rng.below(SAMPLES.len())].as_bytes());
                    k += 1;
                }
                input.push(b'\n');
            }
            prefix.extend_from_slice(&input);
            let bad_line = (rng.below(4) != 0).then(|| {
                n += 1;
                let (kind, line) = &bad[rng.below(bad.len())];
                input.extend_from_slice(line);
                input.push(b'\n');
                input.extend_from_slice(b"0.001,0,0\n");
                (n, *kind)
            });
            let out = run_raw(
                "propagate",
                &args.iter().map(OsString::from).collect::<Vec<_>>(),
                input.clone(),
            );
            let what = format!(
                "{args:?} round {round}: {:?}",
                String::from_utf8_lossy(&input)
            );
            no_panic(&what, &out);
            // The oracle: the same run on the valid lines alone.
            let clean = run_raw(
                "propagate",
                &args.iter().map(OsString::from).collect::<Vec<_>>(),
                prefix,
            );
            assert_eq!(clean.status, Some(0), "{what}: {}", clean.stderr);
            assert_eq!(out.stdout, clean.stdout, "{what}");
            // The last valid sample's attitude is always printed.
            if valid > 0 {
                let last = out.lines().last().map(|l| numbers(l)[0]);
                assert_eq!(last, Some((valid - 1) as f64), "{what}");
            }
            match bad_line {
                Some((n, kind)) => {
                    assert_eq!(out.status, Some(1), "{what}");
                    assert_eq!(
                        error_lines(&out.stderr, "error: line "),
                        [n],
                        "{what} ({kind}): {}",
                        out.stderr
                    );
                }
                None => assert_eq!(out.status, Some(0), "{what}: {}", out.stderr),
            }
            tried += 1;
        }
    }
    println!("propagate: {tried} streams");
}

#[test]
fn propagate_rejects_values_too_large_for_a_step() {
    // Non-finite results, and turns beyond a rule's half-turn limit (the library's StepTooLong)
    // or, for `--algo exp`, beyond the angle's own resolution.
    for (args, input, line) in [
        (
            &["--input", "increments", "--algo", "coning2", "--dt", "0.01"][..],
            "0.001,0,0\n1e200,0,0\n",
            2,
        ),
        (
            &[
                "--input",
                "increments",
                "--algo",
                "exp",
                "--dt",
                "0.01",
                "--f32",
            ][..],
            "0.001,0,0\n1e30,0,0\n",
            2,
        ),
        (
            &["--input", "increments", "--algo", "coning4", "--dt", "0.01"][..],
            "0.001,0,0\n\n0,1e13,0\n",
            3,
        ),
        (
            &[
                "--input",
                "increments",
                "--algo",
                "coning3",
                "--dt",
                "0.01",
                "--f32",
            ][..],
            "0.001,0,0\n0,1e4,0\n",
            2,
        ),
        (
            &["--input", "rates", "--algo", "rk4", "--dt", "1e300"][..],
            "0,0,0\n0,0,1\n0,0,1\n",
            2,
        ),
        (
            &["--input", "rates", "--algo", "cf4", "--dt", "0.1", "--f32"][..],
            "0,0,1\n0,0,1e5\n",
            2,
        ),
    ] {
        let out = run("propagate", args, input);
        let what = format!("{args:?} {input:?}");
        no_panic(&what, &out);
        assert_eq!(out.status, Some(1), "{what}: {}", out.stderr);
        assert!(
            out.stderr.starts_with(&format!("error: line {line}: ")),
            "{what}: {}",
            out.stderr
        );
        for l in out.lines() {
            assert!(numbers(l).iter().all(|x| x.is_finite()), "{what}: {l}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// simulate

fn sim_base() -> Vec<&'static str> {
    vec![
        "--inertia",
        "1,2,3",
        "--omega",
        "0.1,0.2,0.3",
        "--dt",
        "0.01",
        "--steps",
        "20",
        "--integrator",
        "rk4",
    ]
}

/// Every row of a simulate CSV is finite; returns the number of data rows.
fn finite_rows(what: &str, out: &Output) -> usize {
    let lines = out.lines();
    if lines.is_empty() {
        return 0;
    }
    assert!(lines[0].starts_with("t,qw,"), "{what}: {}", out.stdout);
    for l in &lines[1..] {
        assert!(numbers(l).iter().all(|x| x.is_finite()), "{what}: {l}");
    }
    lines.len() - 1
}

#[test]
fn simulate_turns_overflow_and_long_steps_into_errors() {
    // (args, rows written before the error)
    let cases: [(&[&str], usize); 7] = [
        (
            &[
                "--inertia",
                "1,2,3",
                "--momentum",
                "1e300,1e300,1e300",
                "--dt",
                "0.1",
                "--steps",
                "3",
                "--integrator",
                "rk4",
            ],
            0,
        ),
        (
            &[
                "--inertia",
                "1,2,3",
                "--omega",
                "0.1,0.2,0.3",
                "--integrator",
                "exact",
                "--f32",
                "--dt",
                "1e38",
                "--steps",
                "5",
            ],
            4,
        ),
        (
            &[
                "--inertia",
                "1,1,1",
                "--momentum",
                "1e100,1,1",
                "--quartic",
                "octahedral:1",
                "--dt",
                "0.1",
                "--steps",
                "2",
                "--integrator",
                "strang",
            ],
            0,
        ),
        (
            &[
                "--inertia",
                "1,2,3",
                "--omega",
                "1e10,0,0",
                "--dt",
                "1e10",
                "--steps",
                "3",
                "--integrator",
                "rk4",
            ],
            1,
        ),
        (
            &[
                "--inertia",
                "0.54669124,1.3501836,1.8901684",
                "--momentum",
                "-57.255016,24.834936,-0.9194957",
                "--dt",
                "10",
                "--steps",
                "2",
                "--integrator",
                "rk4",
                "--f32",
            ],
            1,
        ),
        (
            &[
                "--inertia",
                "1,2,3",
                "--omega",
                "1e30,0,0",
                "--dt",
                "1",
                "--steps",
                "3",
                "--integrator",
                "yoshida4",
                "--f32",
            ],
            0,
        ),
        (
            &[
                "--inertia",
                "1,2,3",
                "--omega",
                "0.1,0.2,0.3",
                "--torque",
                "1e300,0,0",
                "--dt",
                "1",
                "--steps",
                "50",
                "--integrator",
                "strang",
            ],
            usize::MAX,
        ),
    ];
    for (args, rows) in cases {
        let out = run("simulate", args, "");
        let what = format!("{args:?}");
        no_panic(&what, &out);
        assert_eq!(out.status, Some(2), "{what}: {}", out.stderr);
        assert!(out.stderr.starts_with("error: "), "{what}: {}", out.stderr);
        let written = finite_rows(&what, &out);
        if rows != usize::MAX {
            assert_eq!(written, rows, "{what}: {}", out.stdout);
        }
        if rows == 0 {
            assert!(
                out.stdout.is_empty(),
                "{what}: nothing before an invalid start"
            );
        }
    }
}

#[test]
fn simulate_torque_file_garbage_names_its_line() {
    let bad = garbage(4);
    let dir = std::env::temp_dir().join(format!("gyrostat-cli-campaign-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    for round in 0..rounds() {
        let mut rng = Rng(0x7042 + round as u64);
        let mut text = b"t,tx,ty,tz\n".to_vec();
        let mut n = 1;
        let mut time = 0.0;
        for _ in 0..rng.below(6) {
            n += 1;
            if rng.below(3) == 0 {
                text.extend_from_slice(BLANKS[rng.below(BLANKS.len())]);
            } else {
                text.extend_from_slice(format!("{time},0.001,0,0").as_bytes());
                time += 0.05;
            }
            text.push(b'\n');
        }
        n += 1;
        let (kind, line) = &bad[rng.below(bad.len())];
        text.extend_from_slice(line);
        text.extend_from_slice(b"\n10,0,0,0\n");
        let path = dir.join(format!("torque-{round}.csv"));
        std::fs::write(&path, &text).expect("torque file");
        let mut args = sim_base();
        let p = path.to_str().expect("UTF-8 temp path");
        args.extend(["--torque-file", p]);
        let out = run("simulate", &args, "");
        let what = format!("round {round} ({kind})");
        no_panic(&what, &out);
        assert_eq!(out.status, Some(2), "{what}: {}", out.stderr);
        assert!(
            out.stderr
                .starts_with(&format!("error: --torque-file {p}: line {n}: ")),
            "{what}: {}",
            out.stderr
        );
        assert!(out.stdout.is_empty(), "{what}: no output before a bad file");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------------------------
// Flags, for all three tools

#[test]
fn bad_flags_give_status_2_and_a_message() {
    let conv = ["--from", "quat", "--to", "rotvec"];
    let prop = ["--input", "increments", "--algo", "exp", "--dt", "0.01"];
    let with = |base: &[&'static str], extra: &[&'static str]| -> Vec<&'static str> {
        [base, extra].concat()
    };
    let mut cases: Vec<(&str, Vec<&str>, &str)> = vec![
        (
            "convert",
            with(&conv, &["--bogus"]),
            "unknown argument '--bogus'",
        ),
        ("convert", vec!["--from"], "--from needs a value"),
        (
            "convert",
            vec!["--from", "quat", "--to"],
            "--to needs a value",
        ),
        (
            "convert",
            vec!["--from", "quat"],
            "--from and --to are required",
        ),
        (
            "convert",
            vec!["--from", "quaternion", "--to", "quat"],
            "unknown representation",
        ),
        ("convert", with(&conv, &["--op"]), "--op needs a value"),
        (
            "convert",
            vec!["--from", "euler:XYQ", "--to", "quat"],
            "invalid Euler sequence",
        ),
        (
            "propagate",
            with(&prop, &["--bogus"]),
            "unknown argument '--bogus'",
        ),
        ("propagate", vec!["--input"], "--input needs a value"),
        (
            "propagate",
            with(&prop, &["--every"]),
            "--every needs a value",
        ),
        (
            "propagate",
            with(&prop, &["--every", "0"]),
            "--every: must be at least 1",
        ),
        (
            "propagate",
            with(&prop, &["--every", "-3"]),
            "--every: invalid count",
        ),
        (
            "propagate",
            with(&prop, &["--q0", "nan,0,0,0"]),
            "--q0: not a finite number",
        ),
        (
            "propagate",
            with(&prop, &["--q0", "1,0,0"]),
            "--q0: expected 4",
        ),
    ];
    for dt in ["0", "-1", "nan", "inf", "1e400", "x", ""] {
        cases.push((
            "propagate",
            vec!["--input", "rates", "--algo", "rk4", "--dt", dt],
            "--dt",
        ));
    }
    cases.push((
        "propagate",
        vec![
            "--input", "rates", "--algo", "rk4", "--dt", "1e-50", "--f32",
        ],
        "not a positive finite f32",
    ));
    let sim = sim_base();
    for (flag, values) in [
        ("--steps", &["-1", "x", "1.5", ""][..]),
        ("--every", &["0", "-2"][..]),
        ("--dt", &["0", "-0.01", "nan", "inf", "1e400"][..]),
        (
            "--inertia",
            &["1,2", "1,2,3,4", "1,x,3", "nan,1,1", "6,4,-3", "1,1,100"][..],
        ),
        ("--omega", &["1,2", "inf,0,0"][..]),
        ("--integrator", &["euler", ""][..]),
    ] {
        for v in values {
            let mut args: Vec<&str> = Vec::new();
            let mut it = sim.iter();
            while let Some(a) = it.next() {
                args.push(a);
                if *a == flag {
                    it.next();
                    args.push(v);
                }
            }
            if !sim.contains(&flag) {
                args.extend([flag, v]);
            }
            // The messages of a bad --inertia name the inertia, not always the flag.
            cases.push(("simulate", args, flag.trim_start_matches('-')));
        }
    }
    cases.extend([
        (
            "simulate",
            with(&sim, &["--bogus"]),
            "unknown argument '--bogus'",
        ),
        (
            "simulate",
            with(&sim, &["--wheel"]),
            "--wheel needs a value",
        ),
        (
            "simulate",
            with(&sim, &["--dt", "0.1"]),
            "--dt given more than once",
        ),
        (
            "simulate",
            with(&sim, &["--wheel", "0,0,0,1"]),
            "the axis must not be zero",
        ),
        (
            "simulate",
            with(&sim, &["--wheel", "1,0,0,-1"]),
            "the wheel inertia must be > 0",
        ),
        (
            "simulate",
            with(&sim, &["--torque-file", "/nonexistent/torque.csv"]),
            "--torque-file",
        ),
        (
            "simulate",
            vec![
                "--dt",
                "0.01",
                "--steps",
                "1",
                "--integrator",
                "rk4",
                "--inertia",
                "1,2,3",
            ],
            "missing --omega",
        ),
    ]);
    let mut tiny: Vec<&str> = sim
        .iter()
        .map(|a| if *a == "0.01" { "1e-50" } else { a })
        .collect();
    tiny.push("--f32");
    cases.push(("simulate", tiny, "--dt 1e-50 is not a positive finite f32"));
    for (tool, args, msg) in &cases {
        let out = run(tool, args, "1,0,0,0\n");
        let what = format!("{tool} {args:?}");
        no_panic(&what, &out);
        assert_eq!(out.status, Some(2), "{what}: {}", out.stderr);
        assert!(
            out.stderr.starts_with("error: ") && out.stderr.contains(msg),
            "{what}: expected {msg:?} in {}",
            out.stderr
        );
        assert!(out.stdout.is_empty(), "{what}: {}", out.stdout);
    }
    // A non-UTF-8 argument is an error, not a panic.
    for (tool, base) in [
        ("convert", &conv[..]),
        ("propagate", &prop[..]),
        ("simulate", &sim[..]),
    ] {
        let mut args: Vec<OsString> = base.iter().map(OsString::from).collect();
        args.push(OsString::from_vec(b"--\xff".to_vec()));
        let out = run_raw(tool, &args, b"1,0,0,0\n".to_vec());
        no_panic(tool, &out);
        assert_eq!(out.status, Some(2), "{tool}: {}", out.stderr);
        assert!(
            out.stderr.contains("argument") && out.stderr.contains("not valid UTF-8"),
            "{tool}: {}",
            out.stderr
        );
    }
    // Zero steps are a valid run: the header and the row at step 0.
    let mut args = sim_base();
    let at = args.iter().position(|a| *a == "--steps").expect("--steps") + 1;
    args[at] = "0";
    let out = run("simulate", &args, "");
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    assert_eq!(out.lines().len(), 2);
    println!(
        "flags: {} bad argument lists, 3 non-UTF-8 arguments",
        cases.len()
    );
}

// ---------------------------------------------------------------------------------------------
// Closed pipes

#[test]
fn a_closed_pipe_ends_a_run_quietly() {
    let many_quats = "1,0,0,0\n".repeat(20_000);
    let many_samples = "0.001,0,0\n".repeat(20_000);
    let mut long_sim = sim_base();
    let at = long_sim
        .iter()
        .position(|a| *a == "--steps")
        .expect("--steps")
        + 1;
    long_sim[at] = "20000";
    let cases: [(&str, Vec<&str>, &str, i32); 8] = [
        ("convert", vec!["--help"], "", 0),
        ("propagate", vec!["--help"], "", 0),
        ("simulate", vec!["--help"], "", 0),
        ("simulate", vec![], "", 0),
        ("simulate", long_sim, "", 0),
        (
            "convert",
            vec!["--from", "quat", "--to", "rotvec"],
            &many_quats,
            0,
        ),
        (
            "convert",
            vec!["--from", "quat", "--to", "rotvec"],
            "x\n1,0,0,0\n",
            1,
        ),
        (
            "propagate",
            vec!["--input", "increments", "--algo", "coning2", "--dt", "0.01"],
            &many_samples,
            0,
        ),
    ];
    for (tool, args, input, status) in &cases {
        let what = format!("{tool} {args:?}");
        let (code, stderr) = run_closed(tool, args, input, Closed::Stdout);
        assert_eq!(code, Some(*status), "{what}: {stderr}");
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert!(!stderr.contains("Broken pipe"), "{what}: {stderr}");
    }
    // Diagnostics into a closed stderr do not panic either (a panic exits with 101).
    for (tool, args) in [
        ("convert", vec!["--bogus"]),
        ("propagate", vec!["--bogus"]),
        ("simulate", vec!["--bogus"]),
    ] {
        let (code, _) = run_closed(tool, &args, "", Closed::Both);
        assert_eq!(code, Some(2), "{tool} {args:?}");
    }
    let (code, _) = run_closed(
        "convert",
        &["--from", "quat", "--to", "quat"],
        "x\n",
        Closed::Both,
    );
    assert_eq!(code, Some(1));
}

// ---------------------------------------------------------------------------------------------
// Prompt output

#[test]
fn simulate_shows_its_header_before_a_long_run_ends() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    // A run of many seconds; the header must arrive long before it ends (it used to wait for
    // 8 KiB of buffered rows).
    let mut args = sim_base();
    let steps = args.iter().position(|a| *a == "--steps").expect("--steps") + 1;
    args[steps] = "1000000000";
    args.extend(["--every", "100000000"]);
    let mut child = Command::new(crate::cli::tool("simulate"))
        .args(&args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("simulate runs");
    let start = std::time::Instant::now();
    let mut reader = BufReader::new(child.stdout.take().expect("stdout"));
    let mut header = String::new();
    let mut row = String::new();
    reader.read_line(&mut header).expect("header");
    reader.read_line(&mut row).expect("row 0");
    let waited = start.elapsed();
    child.kill().expect("kill simulate");
    let _ = child.wait();
    assert!(header.starts_with("t,qw,qx,qy,qz"), "{header}");
    assert!(row.starts_with("0,"), "{row}");
    // Not a timing assertion of speed: a bound far above any start-up time, far below the run.
    assert!(waited.as_secs() < 30, "header after {waited:?}");
}

#[test]
fn convert_and_propagate_answer_a_line_while_the_input_stays_open() {
    use std::io::{BufRead, BufReader, Write};
    use std::process::{Command, Stdio};
    use std::sync::mpsc;
    use std::time::Duration;
    // A live stream (a sensor feeding a pipe): the row of a line must come out before the next
    // line arrives, i.e. the tool flushes before it waits for input.
    for (tool, args, line) in [
        (
            "convert",
            &["--from", "quat", "--to", "quat"][..],
            "1,0,0,0\n",
        ),
        (
            "propagate",
            &["--input", "increments", "--algo", "exp", "--dt", "0.01"][..],
            "0.001,0,0\n",
        ),
    ] {
        let mut child = Command::new(crate::cli::tool(tool))
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("the tool runs");
        let mut stdin = child.stdin.take().expect("stdin");
        stdin.write_all(line.as_bytes()).expect("one line in");
        stdin.flush().expect("flushed");
        let stdout = child.stdout.take().expect("stdout");
        let (tx, rx) = mpsc::channel();
        let reader = std::thread::spawn(move || {
            let mut row = String::new();
            let _ = BufReader::new(stdout).read_line(&mut row);
            let _ = tx.send(row);
        });
        // A bound far above any start-up time; without the flush the row never comes.
        let row = rx.recv_timeout(Duration::from_secs(60));
        drop(stdin);
        let _ = child.kill();
        let _ = child.wait();
        let _ = reader.join();
        let row = row.unwrap_or_else(|_| panic!("{tool}: no row while the input stays open"));
        assert!(!row.is_empty(), "{tool}: no row");
    }
}
