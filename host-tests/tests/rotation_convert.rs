//! The `convert` example as an interface: flags, CSV formats, error lines, exit status,
//! round-tripping output numbers, checked against the independent reference matrices.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::OnceLock;

use host_tests::examples::build_example;
use host_tests::ref_rotation::{euler_matrix, rot_dist, rotvec_matrix};
use host_tests::reference::quat_matrix;

/// The example, built once (same profile as this test).
fn binary() -> &'static PathBuf {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| build_example("convert"))
}

/// Runs `convert ARGS` with `input` on stdin: (stdout, stderr, success).
fn run(args: &[&str], input: &str) -> (String, String, bool) {
    let mut child = Command::new(binary())
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("convert runs");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    (
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
        out.status.success(),
    )
}

fn nums(line: &str) -> Vec<f64> {
    line.split(',').map(|f| f.parse().unwrap()).collect()
}

#[test]
fn help_documents_the_interface() {
    let (out, _, ok) = run(&["--help"], "");
    assert!(ok);
    for word in [
        "--from",
        "--to",
        "--f32",
        "--degrees",
        "quat",
        "matrix",
        "rotvec",
        "mrp",
        "axis-angle",
        "euler:SEQ",
        "intrinsic",
        "extrinsic",
        "error: line N",
    ] {
        assert!(out.contains(word), "help lacks {word}");
    }
    let (_, err, ok) = run(&["--from", "nope", "--to", "quat"], "");
    assert!(!ok && err.contains("unknown representation"));
}

#[test]
fn bad_rows_are_reported_and_skipped() {
    let input = "1,0,0,0\n1,2,3\nabc,0,0,0\n0,0,0,0\n2,0,0,0\nnan,0,0,0\n0,1,0,0\n";
    let (out, err, ok) = run(&["--from", "quat", "--to", "rotvec"], input);
    assert!(!ok, "exit status must be non-zero");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert_eq!(nums(lines[0]), vec![0.0, 0.0, 0.0]);
    let v = nums(lines[1]);
    assert!((v[0] - core::f64::consts::PI).abs() < 1e-15 && v[1] == 0.0 && v[2] == 0.0);
    let errs: Vec<&str> = err.lines().collect();
    assert_eq!(errs.len(), 5, "{err}");
    for (e, n) in errs.iter().zip([2, 3, 4, 5, 6]) {
        assert!(e.starts_with(&format!("error: line {n}: ")), "{e}");
    }
    // All rows valid: success.
    let (_, err, ok) = run(&["--from", "quat", "--to", "quat"], "0.5,0.5,0.5,0.5\n");
    assert!(ok && err.is_empty());
}

/// Euler output matches the reference in every convention; the 4th column flags gimbal lock.
#[test]
fn euler_rows_against_reference() {
    let q = [0.3, -0.4, 0.5, 0.7];
    let n: f64 = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let q = q.map(|c| c / n);
    let input = format!("{:?},{:?},{:?},{:?}\n", q[0], q[1], q[2], q[3]);
    for seq in host_tests::ref_rotation::all_sequences() {
        let to = format!("euler:{seq}");
        let (out, _, ok) = run(&["--from", "quat", "--to", &to], &input);
        assert!(ok);
        let v = nums(out.trim());
        assert_eq!(v.len(), 4);
        assert_eq!(v[3], 0.0);
        let e = rot_dist(&quat_matrix(q), &euler_matrix(&seq, [v[0], v[1], v[2]]));
        assert!(e < 1e-14, "{seq}: {e:e}");
    }
    // Gimbal lock flagged, degrees, f32.
    let (out, _, ok) = run(
        &[
            "--from",
            "euler:ZYX",
            "--to",
            "euler:ZYX",
            "--degrees",
            "--f32",
        ],
        "30,90,10\n30,45,10\n",
    );
    assert!(ok);
    let rows: Vec<Vec<f64>> = out.lines().map(nums).collect();
    assert_eq!(rows[0][3], 1.0);
    assert!(
        (rows[0][0] - 20.0).abs() < 1e-4 && rows[0][2] == 0.0,
        "{out}"
    );
    assert_eq!(rows[1][3], 0.0);
    assert!((rows[1][0] - 30.0).abs() < 1e-4 && (rows[1][2] - 10.0).abs() < 1e-4);
}

/// Output numbers round-trip: matrix → rotvec → matrix keeps the rotation to f64 precision, and
/// f32 output parses back to the same f32 values.
#[test]
fn output_round_trips() {
    let (m_out, _, ok) = run(&["--from", "rotvec", "--to", "matrix"], "0.1,-0.2,0.3\n");
    assert!(ok);
    let m = nums(m_out.trim());
    let m3 = [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]];
    assert!(rot_dist(&m3, &rotvec_matrix([0.1, -0.2, 0.3])) < 1e-15);
    let (v_out, _, ok) = run(&["--from", "matrix", "--to", "rotvec"], &m_out);
    assert!(ok);
    let v = nums(v_out.trim());
    assert!(rot_dist(&rotvec_matrix([v[0], v[1], v[2]]), &m3) < 1e-15);
    let (out, _, ok) = run(
        &["--from", "axis-angle", "--to", "mrp", "--f32", "--degrees"],
        "0,0,2,90\n",
    );
    assert!(ok);
    let s: Vec<f32> = out.trim().split(',').map(|f| f.parse().unwrap()).collect();
    assert_eq!(s[0], 0.0);
    assert!((s[2] - (22.5f32).to_radians().tan()).abs() < 1e-7);
}
