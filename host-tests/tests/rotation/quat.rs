//! The foundation types against the independent f64 reference, for f32 and f64.
//!
//! Reference: rotation matrices from the Rodrigues form (6.6.14)–(6.6.15), spinors from the 2×2
//! matrix (6.6.4), both in `host_tests::reference` (no gyrostat code). Every test runs for f32
//! and f64 (`host_tests::per_type!`) with the tolerance `Tolerance::SHORT` (f32 2e-6, f64
//! 1e-13), stated there.

// Angles near π and 2π (3.14159, 6.2831853) are deliberate test inputs, not approximations.
#![allow(clippy::approx_constant)]

use gyrostat::{Complex, Error, Mat3, Quat, Real, Su2, UnitQuat, Vec3};
use host_tests::cast::{m64, u2_64, v64};
use host_tests::reference::{self as r, C};
use proptest::prelude::*;

/// Axis-angle inputs on a grid that covers small, generic, near-π and beyond-2π angles.
fn grid() -> Vec<([f64; 3], f64)> {
    let axes = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 2.0, 3.0],
        [-0.3, 0.9, -0.1],
        [0.577, -0.577, 0.577],
    ];
    let angles = [
        0.0, 1e-7, 1e-3, 0.4, 1.0, 2.0, 3.0, 3.14159, 3.2, 5.0, 6.2831853, 9.0, -2.5,
    ];
    axes.iter()
        .flat_map(|a| angles.iter().map(move |t| (*a, *t)))
        .collect()
}

host_tests::per_type! {
    const TOL: f64 = T::SHORT;


    fn q(axis: [f64; 3], angle: f64) -> UnitQuat<T> {
        let a = Vec3::new(T::from_f64(axis[0]), T::from_f64(axis[1]), T::from_f64(axis[2]));
        UnitQuat::try_from_axis_angle(a, T::from_f64(angle)).unwrap()
    }

    /// The inputs as the type sees them (rounded), so the reference gets the same rotation.
    fn rounded(axis: [f64; 3], angle: f64) -> ([f64; 3], f64) {
        (axis.map(|c| T::from_f64(c).to_f64()), T::from_f64(angle).to_f64())
    }

    #[test]
    fn rotation_matrix_is_rodrigues_6_6_15() {
        for (axis, angle) in grid() {
            let (ra, rt) = rounded(axis, angle);
            let d = r::mat_dist(&m64(&q(axis, angle).to_rotation_matrix()), &r::rodrigues(ra, rt));
            assert!(d <= TOL, "axis {axis:?} angle {angle}: {d:e}");
        }
    }

    #[test]
    fn composition_is_matrix_product_and_rotation_is_matrix_times_vector() {
        let v = [0.3, -0.7, 0.64];
        let vt = Vec3::new(T::from_f64(v[0]), T::from_f64(v[1]), T::from_f64(v[2]));
        let vr = v64(vt);
        for (a1, t1) in grid().into_iter().step_by(5) {
            for (a2, t2) in grid().into_iter().step_by(7) {
                let (ra1, rt1) = rounded(a1, t1);
                let (ra2, rt2) = rounded(a2, t2);
                let rr = r::mat_mul(&r::rodrigues(ra1, rt1), &r::rodrigues(ra2, rt2));
                let qq = q(a1, t1) * q(a2, t2);
                let d = r::mat_dist(&m64(&qq.to_rotation_matrix()), &rr);
                assert!(d <= TOL, "{d:e}");
                let dv = r::vec_dist(&v64(qq.rotate(vt)), &r::mat_vec(&rr, &vr));
                assert!(dv <= TOL, "{dv:e}");
                let dv = r::vec_dist(&v64(qq.inverse_rotate(vt)), &r::mat_vec(&r::transpose(&rr), &vr));
                assert!(dv <= TOL, "{dv:e}");
            }
        }
    }

    #[test]
    fn su2_matrix_is_6_6_4_and_product_is_u2_product() {
        for (axis, angle) in grid() {
            let (ra, rt) = rounded(axis, angle);
            let u = Su2::from(q(axis, angle));
            let d = r::u2_dist(&u2_64(&u), &r::su2_matrix(ra, rt));
            assert!(d <= TOL, "axis {axis:?} angle {angle}: {d:e}");
            // The adjoint action of the spinor is the quaternion's rotation matrix.
            let d = r::mat_dist(&r::su2_to_so3(&u2_64(&u)), &m64(&q(axis, angle).to_rotation_matrix()));
            assert!(d <= TOL, "{d:e}");
        }
        for (a1, t1) in grid().into_iter().step_by(3) {
            for (a2, t2) in grid().into_iter().step_by(4) {
                let (ra1, rt1) = rounded(a1, t1);
                let (ra2, rt2) = rounded(a2, t2);
                let want = r::u2_mul(&r::su2_matrix(ra1, rt1), &r::su2_matrix(ra2, rt2));
                let got = Su2::from(q(a1, t1)) * Su2::from(q(a2, t2));
                assert!(r::u2_dist(&u2_64(&got), &want) <= TOL);
                // The Hamilton product and the U(2) product agree, sign included.
                let via_q = Su2::from(q(a1, t1) * q(a2, t2));
                assert!(r::u2_dist(&u2_64(&via_q), &want) <= TOL);
            }
        }
    }

    #[test]
    fn su2_rotate_is_similarity_transform_6_6_8() {
        let v = Vec3::new(T::from_f64(-0.2), T::from_f64(0.5), T::from_f64(0.8));
        for (axis, angle) in grid() {
            let (ra, rt) = rounded(axis, angle);
            let want = r::mat_vec(&r::rodrigues(ra, rt), &v64(v));
            let d = r::vec_dist(&v64(Su2::from(q(axis, angle)).rotate(v)), &want);
            assert!(d <= TOL, "{d:e}");
        }
    }

    /// Seed §6.6.b.1, (6.6.6c–d): a 2π rotation is −1 in SU(2) and the identity in SO(3);
    /// 4π is +1.
    #[test]
    fn two_pi_is_minus_one_in_su2_and_identity_in_so3() {
        let two_pi = 2.0 * core::f64::consts::PI;
        for axis in [[0.0, 0.0, 1.0], [1.0, 2.0, 3.0], [-0.3, 0.9, -0.1]] {
            let u = Su2::from(q(axis, two_pi));
            let minus_one = [[C::new(-1.0, 0.0), C::new(0.0, 0.0)], [C::new(0.0, 0.0), C::new(-1.0, 0.0)]];
            assert!(r::u2_dist(&u2_64(&u), &minus_one) <= TOL);
            assert!(r::mat_dist(&m64(&q(axis, two_pi).to_rotation_matrix()), &r::IDENTITY) <= TOL);
            let four_pi = Su2::from(q(axis, 2.0 * two_pi));
            assert!(r::u2_dist(&u2_64(&four_pi), &r::u2_mul(&minus_one, &minus_one)) <= TOL);
            // Also via the exponential map: exp of a 2π whirl vector is −1.
            let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
            let phi = Vec3::new(T::from_f64(axis[0] / n * two_pi), T::from_f64(axis[1] / n * two_pi), T::from_f64(axis[2] / n * two_pi));
            let e = UnitQuat::try_exp(phi).unwrap();
            assert!((e.w().to_f64() + 1.0).abs() <= TOL);
        }
    }

    /// exp against the Rodrigues matrix of the same rotation vector on both sides of the
    /// series threshold, and log ∘ exp = id on angles in [0, π).
    #[test]
    fn exp_and_log_match_reference_across_the_series_threshold() {
        let dir = [0.48, -0.6, 0.64]; // unit
        let mut angles = vec![0.0, 1e-30, 1e-12, 1e-6, 1e-4, 3.0];
        for k in 0..200 {
            angles.push(0.0005 + k as f64 * 0.005); // crosses 0.013 (f64) and 0.37 (f32)
        }
        angles.extend([3.1, 3.14, 3.1415, 3.14159]);
        for th in angles {
            let phi = Vec3::new(T::from_f64(dir[0] * th), T::from_f64(dir[1] * th), T::from_f64(dir[2] * th));
            let p = v64(phi);
            let pn = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            let e = UnitQuat::try_exp(phi).unwrap();
            if pn > 0.0 {
                let want = r::rodrigues(p, pn);
                let d = r::mat_dist(&m64(&e.to_rotation_matrix()), &want);
                assert!(d <= TOL, "angle {th}: {d:e}");
                // The spinor, not only the rotation: sin(θ/2)/θ·φ exactly as (6.6.4).
                let want_u = r::su2_matrix(p, pn);
                assert!(r::u2_dist(&u2_64(&Su2::from(e)), &want_u) <= TOL);
            }
            let back = v64(e.log());
            // Relative accuracy: the log of a tiny rotation keeps its digits.
            let err = r::vec_dist(&back, &p);
            assert!(err <= TOL * pn.max(T::SHORT * 1e-3), "angle {th}: log error {err:e}");
        }
    }

    #[test]
    fn constructors_reject_bad_input_with_typed_errors() {
        let nan = T::from_f64(f64::NAN);
        let inf = T::from_f64(f64::INFINITY);
        let one = T::from_f64(1.0);
        let zero = T::from_f64(0.0);
        assert_eq!(UnitQuat::try_new(Quat::new(nan, zero, zero, zero)), Err(Error::NonFinite));
        assert_eq!(UnitQuat::try_new(Quat::new(one, inf, zero, zero)), Err(Error::NonFinite));
        assert_eq!(UnitQuat::try_new(Quat::<T>::ZERO), Err(Error::ZeroNorm));
        let tiny = T::EPSILON * T::from_f64(0.5);
        assert_eq!(UnitQuat::try_new(Quat::new(tiny, zero, zero, zero)), Err(Error::ZeroNorm));
        assert!(UnitQuat::try_new(Quat::new(T::EPSILON * T::from_f64(4.0), zero, zero, zero)).is_ok());
        // Huge components normalise without overflow.
        let big = T::from_f64(1e30);
        let qb = UnitQuat::try_new(Quat::new(big, big, zero, zero)).unwrap();
        assert!((qb.w().to_f64() - core::f64::consts::FRAC_1_SQRT_2).abs() <= TOL);
        assert_eq!(UnitQuat::try_from_axis_angle(Vec3::<T>::ZERO, one), Err(Error::ZeroNorm));
        assert_eq!(UnitQuat::try_from_axis_angle(Vec3::<T>::X, nan), Err(Error::NonFinite));
        assert_eq!(UnitQuat::try_from_axis_angle(Vec3::new(inf, zero, zero), one), Err(Error::NonFinite));
        let tol = T::from_f64(1e-3);
        assert_eq!(UnitQuat::try_from_near_unit(Quat::new(T::from_f64(1.01), zero, zero, zero), tol), Err(Error::NotUnit));
        assert!(UnitQuat::try_from_near_unit(Quat::new(T::from_f64(1.0005), zero, zero, zero), tol).is_ok());
        assert_eq!(UnitQuat::try_from_near_unit(Quat::new(nan, zero, zero, zero), tol), Err(Error::NonFinite));
        assert_eq!(Quat::<T>::ZERO.try_inverse(), Err(Error::ZeroNorm));
        assert_eq!(UnitQuat::try_exp(Vec3::new(nan, zero, zero)), Err(Error::NonFinite));
        assert_eq!(Vec3::<T>::ZERO.try_normalize(), Err(Error::ZeroNorm));
        assert_eq!(Su2::try_new(Complex::new(zero, zero), Complex::new(zero, zero)), Err(Error::ZeroNorm));
        let singular = Mat3::from_rows([one, T::TWO, zero], [T::TWO, T::from_f64(4.0), zero], [zero, zero, one]);
        assert_eq!(singular.try_inverse(), Err(Error::Singular));
        let mut m = Mat3::<T>::IDENTITY;
        m.m[1][2] = nan;
        assert_eq!(m.try_inverse(), Err(Error::NonFinite));
    }

    #[test]
    fn matrix_inverse_matches_reference() {
        let a = [[4.0, -1.0, 0.5], [0.25, 3.0, -2.0], [1.0, 0.0, 2.5]];
        let m = Mat3::from_rows(a[0].map(T::from_f64), a[1].map(T::from_f64), a[2].map(T::from_f64));
        let inv = m64(&m.try_inverse().unwrap());
        assert!(r::mat_dist(&r::mat_mul(&inv, &a), &r::IDENTITY) <= 4.0 * TOL);
        assert!((m.determinant().to_f64() - r::det(&a)).abs() <= 40.0 * TOL);
    }

    /// `renormalize_fast` is one Newton step: the norm error goes from δ to ~3δ²/4.
    #[test]
    fn renormalize_fast_converges_quadratically_and_exact_is_exact() {
        for delta in [1e-2, 1e-3] {
            let s = T::from_f64((1.0f64 + delta).sqrt());
            let q = UnitQuat::new_unchecked(Quat::new(T::from_f64(0.5) * s, T::from_f64(0.5) * s, T::from_f64(-0.5) * s, T::from_f64(0.5) * s));
            let after = q.renormalize_fast().as_quat().norm_squared().to_f64() - 1.0;
            assert!(after.abs() <= 0.76 * delta * delta + 4.0 * TOL, "delta {delta}: {after:e}");
            let exact = q.renormalize().as_quat().norm_squared().to_f64() - 1.0;
            assert!(exact.abs() <= TOL);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]
        /// R(q₁q₂) = R(q₁)R(q₂).
        #[test]
        fn matrix_of_product_is_product_of_matrices(a in arb_quat::<T>(), b in arb_quat::<T>()) {
            let lhs = m64(&(a * b).to_rotation_matrix());
            let rhs = r::mat_mul(&m64(&a.to_rotation_matrix()), &m64(&b.to_rotation_matrix()));
            prop_assert!(r::mat_dist(&lhs, &rhs) <= TOL);
        }
        /// R(q) = R(−q): the double cover.
        #[test]
        fn q_and_minus_q_are_the_same_rotation(a in arb_quat::<T>()) {
            prop_assert_eq!(a.to_rotation_matrix(), (-a).to_rotation_matrix());
        }
        /// det R = 1 and RᵀR = 1.
        #[test]
        fn matrix_is_proper_orthogonal(a in arb_quat::<T>()) {
            let m = m64(&a.to_rotation_matrix());
            prop_assert!((r::det(&m) - 1.0).abs() <= TOL);
            prop_assert!(r::mat_dist(&r::mat_mul(&r::transpose(&m), &m), &r::IDENTITY) <= TOL);
        }
        /// |q v q*| = |v|, and the sandwich equals R(q)·v.
        #[test]
        fn rotation_preserves_length(a in arb_quat::<T>(), v in arb_vec::<T>()) {
            let n0 = v64(v).iter().map(|c| c * c).sum::<f64>().sqrt();
            let w = a.rotate(v);
            let n1 = v64(w).iter().map(|c| c * c).sum::<f64>().sqrt();
            prop_assert!((n1 - n0).abs() <= TOL * n0.max(1.0));
            let via_m = r::mat_vec(&m64(&a.to_rotation_matrix()), &v64(v));
            prop_assert!(r::vec_dist(&v64(w), &via_m) <= TOL * n0.max(1.0));
        }
        /// Su2 ↔ UnitQuat is a bijection that keeps the sign.
        #[test]
        fn su2_round_trip_keeps_sign(a in arb_quat::<T>()) {
            prop_assert_eq!(UnitQuat::from(Su2::from(a)), a);
            prop_assert_eq!(UnitQuat::from(Su2::from(-a)), -a);
        }
    }
}

fn arb_quat<T: Real>() -> impl Strategy<Value = UnitQuat<T>> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
        .prop_filter("non-degenerate", |(w, x, y, z)| {
            w * w + x * x + y * y + z * z > 1e-3
        })
        .prop_map(|(w, x, y, z)| {
            UnitQuat::try_new(Quat::new(
                T::from_f64(w),
                T::from_f64(x),
                T::from_f64(y),
                T::from_f64(z),
            ))
            .unwrap()
        })
}

fn arb_vec<T: Real>() -> impl Strategy<Value = Vec3<T>> {
    (-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0)
        .prop_map(|(x, y, z)| Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z)))
}

#[test]
fn interop_round_trips_keep_components() {
    let q = UnitQuat::try_from_axis_angle(Vec3::new(1.0f64, -2.0, 0.5), 0.8).unwrap();
    let n: nalgebra::UnitQuaternion<f64> = q.into();
    assert_eq!((n.w, n.i, n.j, n.k), (q.w(), q.x(), q.y(), q.z()));
    // Same rotation in both libraries.
    let v = Vec3::new(0.1, 0.2, 0.3);
    let nv = n * nalgebra::Vector3::new(0.1, 0.2, 0.3);
    assert!(r::vec_dist(&v64(q.rotate(v)), &[nv.x, nv.y, nv.z]) <= 1e-15);
    assert_eq!(UnitQuat::from(n), q);
    let m: nalgebra::Matrix3<f64> = q.to_rotation_matrix().into();
    assert!(r::mat_dist(&m64(&Mat3::from(m)), &m64(&q.to_rotation_matrix())) == 0.0);
    assert!((m - n.to_rotation_matrix().into_inner()).abs().max() <= 1e-15);
    let mq: mint::Quaternion<f32> = Quat::new(1.0f32, 2.0, 3.0, 4.0).into();
    assert_eq!((mq.s, mq.v.x, mq.v.y, mq.v.z), (1.0, 2.0, 3.0, 4.0));
    assert_eq!(Quat::from(mq), Quat::new(1.0, 2.0, 3.0, 4.0));
    let bad = mint::Quaternion {
        s: 0.0f32,
        v: mint::Vector3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        },
    };
    assert_eq!(UnitQuat::try_from(bad), Err(Error::ZeroNorm));
    let rm: mint::RowMatrix3<f64> = q.to_rotation_matrix().into();
    let cm: mint::ColumnMatrix3<f64> = q.to_rotation_matrix().into();
    assert_eq!(Mat3::from(rm), Mat3::from(cm));
}
