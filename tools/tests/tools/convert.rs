//! The `convert` tool as an interface: flags, CSV formats, error lines, exit status,
//! round-tripping output numbers, checked against the independent reference matrices.

use host_tests::ref_rotation::{euler_matrix, rot_dist, rotvec_matrix};
use host_tests::reference::quat_matrix;

/// Runs `convert ARGS` with `input` on stdin: (stdout, stderr, success).
fn run(args: &[&str], input: &str) -> (String, String, bool) {
    let out = crate::cli::run("convert", args, input);
    (out.stdout, out.stderr, out.status == Some(0))
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

// ---------------------------------------------------------------------------------------------
// The representations and operations for users of scipy, Basilisk and PX4

use host_tests::ref_rotation::{gibbs_matrix, omega_from_matrices};
use host_tests::reference::{M3, mat_mul, mat_vec, quat_angle, transpose};

/// Unit quaternions spread over SO(3) (normalised here), none near 180°.
fn sample_quats() -> Vec<[f64; 4]> {
    [
        [0.3, -0.4, 0.5, 0.7],
        [0.9, 0.1, -0.3, 0.2],
        [-0.2, 0.6, 0.1, -0.5],
        [0.5, 0.5, -0.5, 0.5],
        [1.0, 1e-9, 0.0, -2e-9],
    ]
    .map(|q| {
        let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
        q.map(|c| c / n)
    })
    .to_vec()
}

fn csv(rows: &[Vec<f64>]) -> String {
    rows.iter().map(|r| crate::cli::row(r) + "\n").collect()
}

fn m3(v: &[f64]) -> M3 {
    [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]]
}

/// `convert ARGS` on `rows`; every row must succeed; the output rows.
fn ok_rows(args: &[&str], rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let (out, err, ok) = run(args, &csv(rows));
    assert!(ok && err.is_empty(), "{args:?}: {err}");
    let r: Vec<Vec<f64>> = out.lines().map(nums).collect();
    assert_eq!(r.len(), rows.len());
    r
}

#[test]
fn scalar_last_gibbs_and_passive_matrix_against_reference() {
    let qs = sample_quats();
    let rows: Vec<Vec<f64>> = qs.iter().map(|q| q.to_vec()).collect();
    for f32 in [false, true] {
        let tol = if f32 { 2e-7 } else { 2e-15 };
        let with = |a: &[&'static str]| {
            let mut v = a.to_vec();
            if f32 {
                v.push("--f32");
            }
            v
        };
        // Scalar last: the same (canonical, w >= 0) quaternion, reordered.
        let xyzw = ok_rows(&with(&["--from", "quat", "--to", "quat-xyzw"]), &rows);
        for (q, o) in qs.iter().zip(&xyzw) {
            let s = if q[0] < 0.0 { -1.0 } else { 1.0 };
            for (i, k) in [1, 2, 3, 0].iter().enumerate() {
                assert!((o[i] - s * q[*k]).abs() < tol, "{q:?} -> {o:?}");
            }
        }
        let back = ok_rows(&with(&["--from", "quat-xyzw", "--to", "matrix"]), &xyzw);
        for (q, m) in qs.iter().zip(&back) {
            assert!(rot_dist(&m3(m), &quat_matrix(*q)) < 4.0 * tol);
        }
        // Gibbs: g = axis tan(angle/2) = v/w, against the Cayley-form matrix of the reference.
        let g = ok_rows(&with(&["--from", "quat", "--to", "gibbs"]), &rows);
        for (q, g) in qs.iter().zip(&g) {
            let r = gibbs_matrix([g[0], g[1], g[2]]);
            assert!(rot_dist(&r, &quat_matrix(*q)) < 4.0 * tol, "{q:?} {g:?}");
        }
        let from_g = ok_rows(&with(&["--from", "gibbs", "--to", "quat"]), &g);
        for (q, o) in qs.iter().zip(&from_g) {
            assert!(quat_angle(*q, [o[0], o[1], o[2], o[3]]) < 4.0 * tol);
        }
        // [BN] is the transpose of the body -> lab matrix: rows are the body axes.
        let bn = ok_rows(&with(&["--from", "quat", "--to", "dcm-bn"]), &rows);
        for (q, m) in qs.iter().zip(&bn) {
            let want = transpose(&quat_matrix(*q));
            for (a, b) in m3(m).iter().flatten().zip(want.iter().flatten()) {
                assert!((a - b).abs() < 2.0 * tol);
            }
        }
        let from_bn = ok_rows(&with(&["--from", "dcm-bn", "--to", "quat"]), &bn);
        for (q, o) in qs.iter().zip(&from_bn) {
            assert!(quat_angle(*q, [o[0], o[1], o[2], o[3]]) < 4.0 * tol);
        }
    }
    // A half turn has no Gibbs vector: the row is an error, the others go through.
    let (out, err, ok) = run(&["--from", "quat", "--to", "gibbs"], "0,0,1,0\n1,0,0,0\n");
    assert!(!ok && out == "0.0,0.0,0.0\n", "{out}");
    assert!(
        err.starts_with("error: line 1: the Gibbs vector is infinite"),
        "{err}"
    );
}

#[test]
fn normalize_accepts_scaled_quaternions_and_noisy_matrices_on_purpose() {
    let q = sample_quats()[0];
    // Strict by default.
    let scaled = [3.0 * q[0], 3.0 * q[1], 3.0 * q[2], 3.0 * q[3]];
    let (_, err, ok) = run(
        &["--from", "quat", "--to", "quat"],
        &csv(&[scaled.to_vec()]),
    );
    assert!(!ok && err.contains("is not within 1e-3 of 1"), "{err}");
    let o = ok_rows(
        &["--from", "quat", "--to", "quat", "--normalize"],
        &[scaled.to_vec()],
    );
    assert!(quat_angle(q, [o[0][0], o[0][1], o[0][2], o[0][3]]) < 1e-15);
    let (_, err, ok) = run(
        &["--from", "quat-xyzw", "--to", "quat", "--normalize"],
        "0,0,0,0\n",
    );
    assert!(!ok && err.contains("quaternion has zero norm"), "{err}");
    // A matrix 1% off orthogonal: rejected, or with --normalize its nearest rotation, which for
    // a symmetric perturbation R(I + E) is R itself.
    let r = quat_matrix(q);
    let e = [
        [0.01, 0.004, 0.0],
        [0.004, -0.006, 0.002],
        [0.0, 0.002, 0.008],
    ];
    let noisy = mat_mul(
        &r,
        &[
            [1.0 + e[0][0], e[0][1], e[0][2]],
            [e[1][0], 1.0 + e[1][1], e[1][2]],
            [e[2][0], e[2][1], 1.0 + e[2][2]],
        ],
    );
    let row: Vec<f64> = noisy.iter().flatten().copied().collect();
    let (_, err, ok) = run(
        &["--from", "matrix", "--to", "quat"],
        &csv(std::slice::from_ref(&row)),
    );
    assert!(!ok && err.contains("matrix is not a rotation"), "{err}");
    let o = ok_rows(
        &["--from", "matrix", "--to", "matrix", "--normalize"],
        &[row],
    );
    assert!(rot_dist(&m3(&o[0]), &r) < 1e-14);
    // A reflection has no nearest rotation.
    let (_, err, ok) = run(
        &["--from", "matrix", "--to", "quat", "--normalize"],
        "-1,0,0,0,1,0,0,0,1\n",
    );
    assert!(
        !ok && err.starts_with("error: line 1: matrix has no nearest rotation"),
        "{err}"
    );
}

#[test]
fn compose_inverse_relative_rotate_slerp_against_reference() {
    let qs = sample_quats();
    let pairs: Vec<(usize, usize)> = vec![(0, 1), (1, 2), (2, 3), (3, 4), (4, 0)];
    let ab = |extra: &[f64]| -> Vec<Vec<f64>> {
        pairs
            .iter()
            .map(|&(i, j)| [&qs[i][..], &qs[j][..], extra].concat())
            .collect()
    };
    let mats = |rows: &[Vec<f64>]| -> Vec<M3> { rows.iter().map(|m| m3(m)).collect() };
    let to_matrix = |op: &str, rows: &[Vec<f64>]| {
        mats(&ok_rows(
            &["--op", op, "--from", "quat", "--to", "matrix"],
            rows,
        ))
    };
    let compose = to_matrix("compose", &ab(&[]));
    let relative = to_matrix("relative", &ab(&[]));
    let inverse = to_matrix(
        "inverse",
        &qs.iter().map(|q| q.to_vec()).collect::<Vec<_>>(),
    );
    for (k, &(i, j)) in pairs.iter().enumerate() {
        let (a, b) = (quat_matrix(qs[i]), quat_matrix(qs[j]));
        assert!(rot_dist(&compose[k], &mat_mul(&a, &b)) < 1e-15);
        assert!(rot_dist(&relative[k], &mat_mul(&transpose(&a), &b)) < 1e-15);
        assert!(rot_dist(&inverse[i], &transpose(&a)) < 1e-15);
    }
    // rotate: the body vector in lab coordinates, R(A) v.
    let v = [0.3, -1.2, 2.0];
    let rows: Vec<Vec<f64>> = qs.iter().map(|q| [&q[..], &v[..]].concat()).collect();
    let (out, err, ok) = run(&["--op", "rotate", "--from", "quat"], &csv(&rows));
    assert!(ok && err.is_empty(), "{err}");
    for (q, line) in qs.iter().zip(out.lines()) {
        let got = nums(line);
        let want = mat_vec(&quat_matrix(*q), &v);
        for k in 0..3 {
            assert!((got[k] - want[k]).abs() < 1e-14, "{got:?} {want:?}");
        }
    }
    // slerp: on the geodesic, a fraction t of the angle from A (t outside [0, 1] extrapolates).
    for t in [0.0, 0.25, 0.5, 1.0, 1.5] {
        let out = ok_rows(
            &["--op", "slerp", "--from", "quat", "--to", "quat"],
            &ab(&[t]),
        );
        for (o, &(i, j)) in out.iter().zip(&pairs) {
            let q = [o[0], o[1], o[2], o[3]];
            let full = quat_angle(qs[i], qs[j]);
            if t * full > 3.0 {
                continue; // past the half turn the angle from A wraps
            }
            assert!((quat_angle(qs[i], q) - t * full).abs() < 1e-14, "t {t}");
            assert!(
                (quat_angle(q, qs[j]) - (1.0 - t).abs() * full).abs() < 1e-14,
                "t {t}"
            );
        }
    }
    // Two attitudes in another representation: euler angles in degrees.
    let out = ok_rows(
        &[
            "--op",
            "relative",
            "--from",
            "euler:ZYX",
            "--to",
            "euler:ZYX",
            "--degrees",
        ],
        &[vec![10.0, 20.0, 30.0, 10.0, 20.0, 30.0]],
    );
    assert!(out[0][..3].iter().all(|x| x.abs() < 1e-12), "{out:?}");
}

#[test]
fn euler_rate_matrices_against_finite_differences() {
    // E_body [a', b', c'] = w_body: each column is the body rate of a unit rate of one angle,
    // from central differences of the reference Euler matrices.
    let angles = [0.4, -0.7, 1.1];
    let h = 1e-6;
    for seq in host_tests::ref_rotation::all_sequences() {
        let from = format!("euler:{seq}");
        for (op, body) in [("euler-rates", true), ("euler-rates-lab", false)] {
            let out = ok_rows(&["--op", op, "--from", &from], &[angles.to_vec()]);
            let e = m3(&out[0]);
            for col in 0..3 {
                let (mut lo, mut hi) = (angles, angles);
                lo[col] -= h;
                hi[col] += h;
                let w =
                    omega_from_matrices(&euler_matrix(&seq, lo), &euler_matrix(&seq, hi), h, body);
                for row in 0..3 {
                    assert!(
                        (e[row][col] - w[row]).abs() < 1e-8,
                        "{seq} {op} {out:?} {w:?}"
                    );
                }
            }
        }
    }
    // --degrees: the input angles in degrees; the matrix is the same.
    let deg = angles.map(f64::to_degrees);
    let a = ok_rows(
        &["--op", "euler-rates", "--from", "euler:ZYZ"],
        &[angles.to_vec()],
    );
    let b = ok_rows(
        &["--op", "euler-rates", "--from", "euler:ZYZ", "--degrees"],
        &[deg.to_vec()],
    );
    for (x, y) in a[0].iter().zip(&b[0]) {
        assert!((x - y).abs() < 1e-15);
    }
}

#[test]
fn degrees_scale_exactly_the_documented_fields() {
    // rotvec: the whole vector scales by 180/pi (its length is the angle); mrp, gibbs and the
    // quaternion do not change.
    let q = sample_quats()[1].to_vec();
    for to in [
        "rotvec",
        "axis-angle",
        "euler:XYZ",
        "mrp",
        "gibbs",
        "quat",
        "quat-xyzw",
    ] {
        let rad = ok_rows(&["--from", "quat", "--to", to], std::slice::from_ref(&q));
        let deg = ok_rows(
            &["--from", "quat", "--to", to, "--degrees"],
            std::slice::from_ref(&q),
        );
        let scaled: Vec<usize> = match to {
            "rotvec" => vec![0, 1, 2],
            "axis-angle" => vec![3],
            "euler:XYZ" => vec![0, 1, 2],
            _ => vec![],
        };
        for (k, (r, d)) in rad[0].iter().zip(&deg[0]).enumerate() {
            let want = if scaled.contains(&k) {
                r.to_degrees()
            } else {
                *r
            };
            assert!(
                (d - want).abs() <= 1e-13 * want.abs().max(1.0),
                "{to} field {k}"
            );
        }
    }
}

#[test]
fn operation_flags_are_checked() {
    for (args, msg) in [
        (
            &["--op", "compose", "--from", "quat"][..],
            "--op compose needs --to",
        ),
        (
            &["--op", "rotate", "--from", "quat", "--to", "quat"][..],
            "--to does not apply",
        ),
        (
            &["--op", "euler-rates", "--from", "quat"][..],
            "need --from euler:SEQ",
        ),
        (
            &["--op", "twist", "--from", "quat", "--to", "quat"][..],
            "unknown operation 'twist'",
        ),
        (
            &["--op", "inverse", "--to", "quat"][..],
            "--op inverse needs --from",
        ),
    ] {
        let (out, err, ok) = run(args, "1,0,0,0\n");
        assert!(!ok && out.is_empty(), "{args:?}");
        assert!(
            err.starts_with(&format!("error: {msg}")) || err.contains(msg),
            "{args:?}: {err}"
        );
        let st = crate::cli::run("convert", args, "").status;
        assert_eq!(st, Some(2));
    }
    // A row of the wrong length for the operation names it.
    let (_, err, ok) = run(
        &["--op", "compose", "--from", "quat", "--to", "quat"],
        "1,0,0,0\n",
    );
    assert!(
        !ok && err.starts_with("error: line 1: expected 8 fields, got 4"),
        "{err}"
    );
}
