//! Euler-rate kinematics for all 24 conventions: against central differences of the reference
//! Euler matrices, the seed's closed forms (6.7.5c–f) for ZYZ, and the typed singular error.
#![allow(clippy::needless_range_loop)] // 3×3 index loops read like the formulas

use gyrostat::rotation::{Euler, EulerSequence, euler_rate_min_det};
use gyrostat::{Error, Mat3, Vec3};
use host_tests::cast::m64;
use host_tests::ref_rotation::{
    all_sequences, euler_matrix, is_proper, omega_from_matrices, poles,
};

host_tests::per_type! {
    /// ω from the rate matrices equals the angular velocity of the reference Euler matrices
    /// moved along the rates (central differences, h = 1e-5: truncation ~1e-10); inverses give
    /// back the rates. Bounds: f64 1e-9 (the differences' truncation and rounding), f32 2e-6
    /// (~15 ulp of the order-one entries).
    #[test]
    fn rates_all_conventions() {
        let tol = T::per_type(2e-6, 1e-9);
        let h = 1e-5;
        for seq_s in all_sequences() {
            let seq = EulerSequence::try_from_str(&seq_s).unwrap();
            let b = if is_proper(&seq_s) { 0.9 } else { 0.4 };
            let ang = [0.7, b, -1.3];
            let rates = [0.3, -0.8, 1.1];
            let e = Euler::new(seq, ang.map(T::from_f64));
            let at = |s: f64| euler_matrix(&seq_s, [0, 1, 2].map(|i| ang[i] + s * rates[i]));
            for body in [true, false] {
                let want = omega_from_matrices(&at(-h), &at(h), h, body);
                let m = if body {
                    e.rates_to_body_matrix()
                } else {
                    e.rates_to_lab_matrix()
                };
                let m = m64(&m);
                for i in 0..3 {
                    let got: f64 = (0..3).map(|k| m[i][k] * rates[k]).sum();
                    assert!(
                        (got - want[i]).abs() < tol,
                        "{seq_s} body={body}: {got} vs {}",
                        want[i]
                    );
                }
                let w = Vec3::from_array(want.map(T::from_f64));
                let back = if body {
                    e.try_rates_from_body(w)
                } else {
                    e.try_rates_from_lab(w)
                }
                .unwrap();
                for k in 0..3 {
                    assert!((back[k].to_f64() - rates[k]).abs() < 10.0 * tol, "{seq_s}");
                }
            }
        }
    }

    /// The inverses are singular at gimbal lock: a typed error within √ε of the pole in every
    /// convention, never Inf or NaN; just outside the threshold they are finite.
    #[test]
    fn inverse_rates_are_singular_at_gimbal_lock() {
        let thr = euler_rate_min_det::<T>().to_f64();
        for seq_s in all_sequences() {
            let seq = EulerSequence::try_from_str(&seq_s).unwrap();
            for p in poles(&seq_s) {
                for d in [0.0, 0.5 * thr, -0.5 * thr] {
                    let e = Euler::new(seq, [0.3, p + d, -0.2].map(T::from_f64));
                    assert_eq!(
                        e.try_body_to_rates_matrix(),
                        Err(Error::Singular),
                        "{seq_s}"
                    );
                    assert_eq!(
                        e.try_rates_from_lab(Vec3::new(T::ONE, T::ONE, T::ONE)),
                        Err(Error::Singular)
                    );
                }
                let e = Euler::new(seq, [0.3, p + 4.0 * thr, -0.2].map(T::from_f64));
                let m = e.try_body_to_rates_matrix().unwrap();
                assert!(m.is_finite());
            }
        }
    }
}

/// Seed (6.7.5c–f) for the seed's ZYZ `(α, β, γ)`, entry by entry.
#[test]
fn seed_6_7_5_zyz_matrices() {
    let (a, b, g) = (0.4f64, 1.1, -0.7);
    let e = Euler::new(EulerSequence::ZYZ, [a, b, g]);
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sg, cg) = g.sin_cos();
    let close = |m: &Mat3<f64>, want: [[f64; 3]; 3]| {
        for i in 0..3 {
            for j in 0..3 {
                assert!((m.m[i][j] - want[i][j]).abs() < 1e-15, "{m:?} vs {want:?}");
            }
        }
    };
    // (6.7.5c) lab
    close(
        &e.rates_to_lab_matrix(),
        [[0.0, -sa, ca * sb], [0.0, ca, sa * sb], [1.0, 0.0, cb]],
    );
    // (6.7.5d) body
    close(
        &e.rates_to_body_matrix(),
        [[-sb * cg, sg, 0.0], [sb * sg, cg, 0.0], [cb, 0.0, 1.0]],
    );
    // (6.7.5e) inverse of lab
    let (cot, csc) = (cb / sb, 1.0 / sb);
    close(
        &e.try_lab_to_rates_matrix().unwrap(),
        [
            [-ca * cot, -sa * cot, 1.0],
            [-sa, ca, 0.0],
            [ca * csc, sa * csc, 0.0],
        ],
    );
    // (6.7.5f) inverse of body
    close(
        &e.try_body_to_rates_matrix().unwrap(),
        [
            [-cg * csc, sg * csc, 0.0],
            [sg, cg, 0.0],
            [cot * cg, -cot * sg, 1.0],
        ],
    );
}
