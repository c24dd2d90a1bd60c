//! Kinematics, the exact exponential step and spin precession (6.6.16a–c), f32 and f64.

use gyrostat::propagation::exponential::step_constant_rate;
use gyrostat::propagation::kernels;
use gyrostat::propagation::kinematics::{
    body_rate_between, body_rate_from_quat_rate, lab_rate_between, quat_rate_body, quat_rate_lab,
};
use gyrostat::propagation::normalization::norm_deviation;
use gyrostat::propagation::{
    ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::{Error, Quat, UnitQuat, Vec3};
use host_tests::cast::vec3;
use host_tests::ref_propagation::{Coning, crank_axis, spin_precession};

host_tests::per_type! {
    /// `q̇ = ½ q ⊗ (0, ω_body) = ½ (0, ω_lab) ⊗ q` against central differences of the closed-form
    /// coning attitude, whose body rate is known in closed form.
    #[test]
    fn quat_rate_matches_closed_form() {
        let c = Coning {
            alpha: 0.4,
            omega_c: 1.7,
        };
        for &t in &[0.0, 0.3, 1.9] {
            let a = c.attitude(t);
            let q = UnitQuat::<T>::try_new(Quat::new(
                T::from_f64(a[0]),
                T::from_f64(a[1]),
                T::from_f64(a[2]),
                T::from_f64(a[3]),
            ))
            .unwrap();
            let w: Vec3<T> = vec3(c.body_rate(t));
            let qd = quat_rate_body(*q.as_quat(), w);
            let dt = 1e-6;
            let (p, m) = (c.attitude(t + dt), c.attitude(t - dt));
            let fd: Vec<f64> = (0..4).map(|i| (p[i] - m[i]) / (2.0 * dt)).collect();
            let got = qd.to_array().map(|x| x.to_f64());
            for i in 0..4 {
                // f64: central difference error (dt²|q⃛|/6 ≈ 1e-12) dominates; f32: rounding.
                assert!((got[i] - fd[i]).abs() < T::SHORT.max(1e-9), "t={t} i={i}");
            }
            let w_lab = q.rotate(w);
            let qd_lab = quat_rate_lab(*q.as_quat(), w_lab);
            for (x, y) in qd.to_array().iter().zip(qd_lab.to_array()) {
                assert!((x.to_f64() - y.to_f64()).abs() < T::SHORT);
            }
            let back = body_rate_from_quat_rate(q, qd);
            assert!((back - w).norm().to_f64() < T::SHORT * 4.0);
        }
    }

    /// `body_rate_between` inverts the exact step (angles below π), `lab_rate_between` is the same
    /// rate in lab coordinates; bad steps are typed errors.
    #[test]
    fn rate_between_inverts_step() {
        let q0 = UnitQuat::<T>::try_from_axis_angle(vec3([0.2, -1.0, 0.5]), T::from_f64(2.2)).unwrap();
        let w: Vec3<T> = vec3([0.9, -0.4, 1.3]);
        let dt = T::from_f64(0.8); // |ω| dt ≈ 1.3 rad
        let q1 = step_constant_rate(q0, w, dt).unwrap();
        let wb = body_rate_between(q0, q1, dt).unwrap();
        let wl = lab_rate_between(q0, q1, dt).unwrap();
        assert!((wb - w).norm().to_f64() < 4.0 * T::SHORT);
        assert!((wl - q0.rotate(w)).norm().to_f64() < 4.0 * T::SHORT);
        assert_eq!(
            body_rate_between(q0, q1, T::ZERO),
            Err(Error::InvalidArgument)
        );
        assert_eq!(body_rate_between(q0, q1, -dt), Err(Error::InvalidArgument));
        assert_eq!(
            lab_rate_between(q0, q1, T::from_f64(f64::NAN)),
            Err(Error::NonFinite)
        );
        assert_eq!(
            step_constant_rate(q0, vec3([f64::NAN, 0.0, 0.0]), dt),
            Err(Error::NonFinite)
        );
        assert_eq!(
            step_constant_rate(q0, w, T::from_f64(f64::INFINITY)),
            Err(Error::NonFinite)
        );
    }

    /// Spin precession about a fixed crank axis: a body spinning at Ω about the lab-fixed axis
    /// `Ω̂ = (cos φ sin ϑ, sin φ sin ϑ, cos ϑ)` (its body rate is the same constant vector, since the
    /// axis is invariant) carries its body z axis (the spin S, initially along A = Z) along the
    /// seed's closed form (6.6.16a–c). Checked for every propagation path, f32 and f64.
    #[test]
    fn spin_precession_matches_seed() {
        let (theta, phi, big_omega) = (0.955, 0.785, 2.5); // near the seed's magic angle, φ = π/4
        let axis = crank_axis(theta, phi);
        let w: Vec3<T> = vec3([
            axis[0] * big_omega,
            axis[1] * big_omega,
            axis[2] * big_omega,
        ]);
        let dt = 0.01;
        let n = 400; // 4 s: Θ = 10 rad, beyond 2π
        let dtt = T::from_f64(dt);
        let z = |q: UnitQuat<T>| q.to_rotation_matrix().col(2);
        let check = |name: &str, k: usize, q: UnitQuat<T>, tol: f64| {
            let s = spin_precession(theta, phi, big_omega, k as f64 * dt);
            let col = z(q);
            let err = ((col.x.to_f64() - s[0]).powi(2)
                + (col.y.to_f64() - s[1]).powi(2)
                + (col.z.to_f64() - s[2]).powi(2))
            .sqrt();
            assert!(err < tol, "{name} at step {k}: {err}");
        };
        // Rounding budget for n = 400 chained updates: f32 ~ 400 × 6e-8 worst case ≈ 2.4e-5 (the
        // walk is random, so 2e-5 holds with margin); f64 ~ 400 × 1.1e-16 ≈ 5e-14.
        let tol = T::per_type(2e-5, 1e-12);
        // Exact exponential step.
        let mut q = UnitQuat::<T>::IDENTITY;
        for k in 1..=n {
            q = Normalization::Fast.apply(kernels::step_constant_rate(q, w, dtt));
            check("exp step", k, q, tol);
        }
        // Increments (constant rate: every coning correction vanishes, increments are ω dt).
        for rule in ConingRule::ALL {
            let mut integ =
                IncrementIntegrator::new(UnitQuat::<T>::IDENTITY, rule, Normalization::Fast);
            for k in 1..=n {
                integ.push(w.scale(dtt)).unwrap();
                check("increments", k, integ.provisional_attitude(), tol);
            }
        }
        // Rate samples. RK4 adds its truncation error, per step 2(|ω| dt/2)⁵/120 ≈ 5e-12 in angle:
        // over 400 steps ≤ 2e-9 (below the f32 rounding budget, above the f64 one).
        let rk4_tol = tol.max(3e-9);
        for (method, tol) in [
            (RateMethod::Magnus4, tol),
            (RateMethod::Cf4, tol),
            (RateMethod::Rk4, rk4_tol),
        ] {
            let mut integ =
                RateIntegrator::try_new(UnitQuat::<T>::IDENTITY, method, Normalization::Fast, dtt).unwrap();
            let mut k = 0;
            for _ in 0..=n {
                for q in integ.push(w).unwrap() {
                    check("rates", k, q, tol);
                    k += 1;
                }
            }
            assert_eq!(k, n + 1);
        }
    }
}

/// The exact step is valid beyond π: 2π about any axis is the spinor −q (6.6.6c), 4π is +q, and
/// tiny rates are not snapped to the identity.
#[test]
fn exact_step_beyond_pi_and_tiny() {
    let q0 = UnitQuat::<f64>::try_from_axis_angle(Vec3::new(1.0, 1.0, 0.0), 0.3).unwrap();
    let axis = Vec3::new(0.3, -0.5, 0.8).try_normalize().unwrap();
    let two_pi = step_constant_rate(q0, axis.scale(2.0), core::f64::consts::PI).unwrap();
    for (a, b) in two_pi.to_array().iter().zip(q0.to_array()) {
        assert!((a + b).abs() < 1e-15);
    }
    let four_pi = step_constant_rate(q0, axis.scale(4.0), core::f64::consts::PI).unwrap();
    assert!((four_pi.dot(q0) - 1.0).abs() < 1e-15);
    let tiny =
        kernels::step_constant_rate(UnitQuat::<f32>::IDENTITY, Vec3::new(0.0, 2e-30, 0.0), 1.0);
    assert_eq!(tiny.y(), 1e-30);
}

/// The health value is `|q| − 1`, accurate when it is a few ulp, and each policy does what it
/// says on a quaternion off the sphere by δ.
#[test]
fn normalisation_policies_and_health() {
    for delta in [1e-3f64, 1e-7, -3e-5] {
        let raw = Quat::new(0.5, -0.5, 0.5, 0.5).scale(1.0 + delta);
        let q = UnitQuat::new_unchecked(raw);
        assert!((norm_deviation(q) - delta).abs() < 1e-15);
        assert!(norm_deviation(Normalization::Exact.apply(q)).abs() < 3e-16);
        // Fast: |q|² = 1 − 3δ²/4 + O(δ³) → |q| − 1 ≈ −3δ²/8 (2δ³ bounds the O(δ³) part).
        let f = norm_deviation(Normalization::Fast.apply(q));
        assert!(
            (f + 1.5 * delta * delta).abs() < 2.0 * delta.abs().powi(3) + 3e-16,
            "{delta}: {f}"
        );
        assert_eq!(Normalization::None.apply(q), q);
    }
    let q = UnitQuat::new_unchecked(Quat::new(1.0f32 + 3.0 * f32::EPSILON, 0.0, 0.0, 0.0));
    assert!((norm_deviation(q) - 3.0 * f32::EPSILON).abs() < 0.5 * f32::EPSILON);
}

mod laws {
    use super::*;
    use gyrostat::propagation::coning::{four_sample, one_plus_previous, three_sample, two_sample};
    use proptest::prelude::*;

    fn vec3() -> impl Strategy<Value = Vec3<f64>> {
        (-3.0..3.0f64, -3.0..3.0f64, -3.0..3.0f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        /// The log map inverts the exact step while |ω| dt < π (f64 rounding: a few ulp of the
        /// angle, divided by dt ≥ 0.05).
        #[test]
        fn body_rate_between_inverts_step(w in vec3(), dt in 0.05..0.5f64, axis in vec3(), angle in -3.0..3.0f64) {
            prop_assume!(w.norm() * dt < 3.0);
            prop_assume!(axis.norm() > 1e-3);
            let q0 = UnitQuat::try_from_axis_angle(axis, angle).unwrap();
            let q1 = step_constant_rate(q0, w, dt).unwrap();
            let back = body_rate_between(q0, q1, dt).unwrap();
            prop_assert!((back - w).norm() < 1e-12, "{:?} vs {:?}", back, w);
        }

        /// Parallel increments commute: every coning correction vanishes and each rule returns
        /// the plain sum (exactly the sum of the rotation angles about the common axis).
        #[test]
        fn parallel_increments_need_no_coning_correction(axis in vec3(), a in -0.1..0.1f64, b in -0.1..0.1f64, c in -0.1..0.1f64, d in -0.1..0.1f64) {
            let n = axis.norm();
            prop_assume!(n > 1e-3);
            let u = axis.scale(1.0 / n);
            let (ta, tb, tc, td) = (u.scale(a), u.scale(b), u.scale(c), u.scale(d));
            let sum = u.scale(a + b + c + d);
            prop_assert!((four_sample(ta, tb, tc, td) - sum).norm() < 1e-15);
            prop_assert!((three_sample(ta, tb, tc) - u.scale(a + b + c)).norm() < 1e-15);
            prop_assert!((two_sample(ta, tb) - u.scale(a + b)).norm() < 1e-15);
            prop_assert!((one_plus_previous(ta, tb) - tb).norm() < 1e-15);
        }

        /// Time reversal: the 2-sample rule is antisymmetric, `φ(−θ₂, −θ₁) = −φ(θ₁, θ₂)`, so
        /// feeding the increments backwards with opposite sign undoes the update to rounding
        /// (|θ| ≤ 0.026 rad; f64 rounding of the angle ≈ 1e-17).
        #[test]
        fn two_sample_rule_is_time_reversible(t1 in vec3(), t2 in vec3()) {
            let (t1, t2) = (t1.scale(0.005), t2.scale(0.005));
            let fwd = UnitQuat::try_exp(two_sample(t1, t2)).unwrap();
            let back = UnitQuat::try_exp(two_sample(-t2, -t1)).unwrap();
            let e = (fwd * back).angle();
            prop_assert!(e < 1e-15, "{}", e);
        }
    }
}
