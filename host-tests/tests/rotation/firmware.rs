//! Checks the output of the `fw_rotations` firmware (run under QEMU on Cortex-M0, M3, M4F, M33 and
//! RISC-V RV32IMAC) against the independent f64 reference.
//!
//! `.ci/run` runs the firmware, writes its output to `$GYROSTAT_FIRMWARE_OUTPUT/<target>.txt` for
//! each target, and then runs this test with `GYROSTAT_FIRMWARE_OUTPUT` set and `--ignored`;
//! every expected file must then exist and hold one line per case. The test
//! is `#[ignore]`d, so a plain `cargo test` lists it as ignored instead of passing without
//! checking anything, and it fails when run without its input.
//!
//! For each case the reference computes, from the same f32 inputs widened to f64:
//! - the product spinor `U₁U₂` from the 2×2 matrices of seed (6.6.4) (checks the sign too);
//! - the rotation matrix `R₁R₂` from the Rodrigues form (6.6.14)–(6.6.15);
//! - the rotated vector `R₁R₂ v`.
//!
//! Tolerance (f32 firmware): 5e-7 absolute per component (4 ulp at 1.0, 2⁻²¹ ≈ 4.8e-7) for the
//! spinor and the matrix: unit-size entries after a handful of roundings of 2⁻²⁴ each and
//! ≤ 1-ulp `sinf`/`cosf` of the half angles; scaled by `max(1, |v|)` for the rotated vector (its
//! components are `|v|`-sized). Observed worst case: about 1.1e-7.

use host_tests::examples::firmware_output;
use host_tests::reference::{
    C, mat_dist, mat_mul, mat_vec, rodrigues, su2_matrix, u2_dist, u2_mul,
};

include!("../../../examples/fw/rotation_cases.rs");

struct Line {
    case: usize,
    q: [f64; 4],
    m: [[f64; 3]; 3],
    v: [f64; 3],
}

fn parse(line: &str) -> Option<Line> {
    let t: Vec<&str> = line.split_whitespace().collect();
    if t.len() != 21 || t[0] != "case" || t[2] != "q" || t[7] != "m" || t[17] != "v" {
        return None;
    }
    let f = |i: usize| -> Option<f64> { t[i].parse::<f32>().ok().map(f64::from) };
    let q = [f(3)?, f(4)?, f(5)?, f(6)?];
    let mut m = [[0.0; 3]; 3];
    for (k, e) in m.iter_mut().flatten().enumerate() {
        *e = f(8 + k)?;
    }
    Some(Line {
        case: t[1].parse().ok()?,
        q,
        m,
        v: [f(18)?, f(19)?, f(20)?],
    })
}

fn widen(a: [f32; 3]) -> [f64; 3] {
    a.map(f64::from)
}

#[test]
#[ignore = "needs the firmware output of .ci/run in $GYROSTAT_FIRMWARE_OUTPUT"]
fn firmware_output_matches_f64_reference() {
    for (target, text) in firmware_output("") {
        // QEMU may print its own notices; only `case` lines are data, and `done N` must close it.
        let lines: Vec<Line> = text
            .lines()
            .filter(|l| l.starts_with("case "))
            .map(|l| parse(l).unwrap_or_else(|| panic!("{target}: bad line {l:?}")))
            .collect();
        assert!(
            text.lines().any(|l| l == format!("done {N_CASES}")),
            "{target}: no `done {N_CASES}` line"
        );
        assert_eq!(
            lines.len(),
            N_CASES,
            "{target}: expected {N_CASES} case lines"
        );
        for (i, l) in lines.iter().enumerate() {
            assert_eq!(l.case, i, "{target}: cases out of order");
            let (a1, t1, a2, t2, v) = CASES[i];
            let (a1, t1, a2, t2, v) =
                (widen(a1), f64::from(t1), widen(a2), f64::from(t2), widen(v));
            let tol = 5e-7;

            let u_ref = u2_mul(&su2_matrix(a1, t1), &su2_matrix(a2, t2));
            let [w, x, y, z] = l.q;
            // U = w·1 − i(x σx + y σy + z σz): the crate convention, seed (6.6.4).
            let u_fw = [
                [C::new(w, -z), C::new(-y, -x)],
                [C::new(y, -x), C::new(w, z)],
            ];
            let du = u2_dist(&u_fw, &u_ref);
            assert!(
                du <= tol,
                "{target} case {i}: spinor differs from U1·U2 by {du:e}"
            );

            let r_ref = mat_mul(&rodrigues(a1, t1), &rodrigues(a2, t2));
            let dm = mat_dist(&l.m, &r_ref);
            assert!(
                dm <= tol,
                "{target} case {i}: matrix differs from R1·R2 by {dm:e}"
            );

            let v_ref = mat_vec(&r_ref, &v);
            let vn = v.iter().map(|c| c * c).sum::<f64>().sqrt().max(1.0);
            let dv = (0..3)
                .map(|k| (l.v[k] - v_ref[k]).abs())
                .fold(0.0, f64::max);
            assert!(
                dv <= tol * vn,
                "{target} case {i}: rotated vector differs by {dv:e}"
            );
        }
        println!("{target}: {N_CASES} cases within tolerance");
    }
}
