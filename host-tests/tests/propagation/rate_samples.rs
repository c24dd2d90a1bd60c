//! Convergence orders of the rate-sample integrators, measured by halving the sample interval.
//!
//! Reference: the closed-form coning motion (`ref_propagation::Coning`) with a large half-cone
//! angle (α = 0.6, Ω = 2 rad/s), whose body rate has a constant axial part and a rotating
//! transverse part, so successive rates do not commute. Each method integrates the equally
//! spaced samples `ω(k h)` from t = 0 to t = 3 s; the error is the rotation angle to the exact
//! `q(3 s)`. The order is `log₂(e(h)/e(h/2))`, averaged over three halvings. f64, so that the
//! finest error (~1e-11) stays far above rounding (~1e-15).

use gyrostat::propagation::kernels::{cf4_step, magnus4_step, rk4_step};
use gyrostat::propagation::rate_samples::{cf4_rotation_vectors, gauss_rates, midpoint_rate};
use gyrostat::propagation::{Normalization, RateIntegrator, RateMethod};
use gyrostat::{Quat, UnitQuat, Vec3};
use host_tests::ref_propagation::Coning;
use host_tests::reference::quat_angle;

const CONE: Coning = Coning {
    alpha: 0.6,
    omega_c: 2.0,
};
const T_END: f64 = 3.0;

fn v3(a: [f64; 3]) -> Vec3<f64> {
    Vec3::new(a[0], a[1], a[2])
}

fn q0() -> UnitQuat<f64> {
    let a = CONE.attitude(0.0);
    UnitQuat::try_new(Quat::new(a[0], a[1], a[2], a[3])).unwrap()
}

/// Final error of `method` with `n` intervals (n + 1 samples).
fn error_of(method: RateMethod, n: usize) -> f64 {
    let h = T_END / n as f64;
    let mut integ = RateIntegrator::try_new(q0(), method, Normalization::Exact, h).unwrap();
    let mut last = q0();
    let mut reached = 0usize;
    for k in 0..=n {
        let out = integ.push(v3(CONE.body_rate(k as f64 * h))).unwrap();
        reached += out.len();
        if let Some(q) = out.last() {
            last = *q;
        }
    }
    assert_eq!(reached, n + 1, "one attitude per sample time");
    quat_angle(CONE.attitude(T_END), last.to_array())
}

fn order(errs: &[f64]) -> f64 {
    let orders: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    orders.iter().sum::<f64>() / orders.len() as f64
}

fn check_order(name: &str, f: impl Fn(usize) -> f64, expected: f64) {
    let errs: Vec<f64> = [24, 48, 96, 192].iter().map(|&n| f(n)).collect();
    let p = order(&errs);
    println!("{name}: errors {errs:?}, order {p:.3}");
    assert!((p - expected).abs() < 0.3, "{name}: order {p}");
}

#[test]
fn magnus4_from_samples_is_order_4() {
    check_order("magnus4", |n| error_of(RateMethod::Magnus4, n), 4.0);
}

#[test]
fn cf4_from_samples_is_order_4() {
    check_order("cf4", |n| error_of(RateMethod::Cf4, n), 4.0);
}

#[test]
fn rk4_from_samples_is_order_4() {
    check_order("rk4", |n| error_of(RateMethod::Rk4, n), 4.0);
}

/// The step functions alone, fed the EXACT rates at the Gauss nodes (no interpolation), are
/// order 4; swapping CF4's two exponentials (later-weighted one first) drops it to order 2.
/// This guards the composition order in `cf4_step`.
#[test]
fn cf4_swapped_exponentials_drop_to_order_2() {
    let c1 = 0.5 - 3f64.sqrt() / 6.0;
    let c2 = 0.5 + 3f64.sqrt() / 6.0;
    let run = |n: usize, swapped: bool| {
        let h = T_END / n as f64;
        let mut q = q0();
        for k in 0..n {
            let t = k as f64 * h;
            let w1 = v3(CONE.body_rate(t + c1 * h));
            let w2 = v3(CONE.body_rate(t + c2 * h));
            q = if swapped {
                let (p1, p2) = cf4_rotation_vectors(w1, w2, h);
                q * UnitQuat::try_exp(p2).unwrap() * UnitQuat::try_exp(p1).unwrap()
            } else {
                cf4_step(q, w1, w2, h)
            };
        }
        quat_angle(CONE.attitude(T_END), q.to_array())
    };
    check_order("cf4 exact nodes", |n| run(n, false), 4.0);
    check_order("cf4 swapped", |n| run(n, true), 2.0);
    let magnus = |n: usize| {
        let h = T_END / n as f64;
        let mut q = q0();
        for k in 0..n {
            let t = k as f64 * h;
            q = magnus4_step(
                q,
                v3(CONE.body_rate(t + c1 * h)),
                v3(CONE.body_rate(t + c2 * h)),
                h,
            );
        }
        quat_angle(CONE.attitude(T_END), q.to_array())
    };
    check_order("magnus4 exact nodes", magnus, 4.0);
}

/// The interpolation helpers reproduce a cubic rate exactly at the Gauss nodes and midpoints of
/// each interval of the window (the property the order-4 argument rests on).
#[test]
fn interpolation_is_exact_for_cubics() {
    let f = |t: f64| {
        Vec3::new(
            1.0 + 2.0 * t - 0.5 * t * t + 0.25 * t * t * t,
            -t * t * t,
            3.0 - t,
        )
    };
    let window = [f(0.0), f(1.0), f(2.0), f(3.0)];
    let (c1, c2) = (0.5 - 3f64.sqrt() / 6.0, 0.5 + 3f64.sqrt() / 6.0);
    for j in 0..3 {
        let (g1, g2) = gauss_rates(&window, j);
        let m = midpoint_rate(&window, j);
        let t = j as f64;
        assert!((g1 - f(t + c1)).norm() < 1e-13);
        assert!((g2 - f(t + c2)).norm() < 1e-13);
        assert!((m - f(t + 0.5)).norm() < 1e-13);
    }
}

/// Constant rate: Magnus-4 and CF4 are exact (one exponential of ω h per step, or two that
/// commute), RK4 is within its truncation error; all match the exact exponential step.
#[test]
fn constant_rate_is_exact_for_lie_group_methods() {
    let w = Vec3::new(0.7, -1.1, 2.3);
    let h = 0.05;
    let exact = |n: usize| UnitQuat::try_exp(w.scale(n as f64 * h)).unwrap();
    // RK4 is the 4th-order Taylor polynomial of exp(h A), |A| = |ω|/2: per step the dropped
    // term is (|ω|h/2)⁵/120 ≈ 9.7e-9 in the quaternion, 2× that in angle; 100 steps ≈ 1.9e-6.
    let x = w.norm() * h / 2.0;
    let rk4_budget = 100.0 * 2.0 * x.powi(5) / 120.0 * 1.2;
    for (method, tol) in [
        (RateMethod::Magnus4, 1e-13),
        (RateMethod::Cf4, 1e-13),
        (RateMethod::Rk4, rk4_budget),
    ] {
        let mut integ =
            RateIntegrator::try_new(UnitQuat::IDENTITY, method, Normalization::Exact, h).unwrap();
        let mut q = UnitQuat::IDENTITY;
        for _ in 0..=100 {
            if let Some(last) = integ.push(w).unwrap().last() {
                q = *last;
            }
        }
        let e = quat_angle(exact(100).to_array(), q.to_array());
        assert!(e < tol, "{method:?}: {e}");
    }
    // RK4 step alone, one step: local error O((|ω|h)⁵).
    let q = rk4_step(Quat::IDENTITY, w, w, w, h);
    assert!((q.norm() - 1.0).abs() < 1e-7);
}

/// Short records: two samples (linear interpolant) and three (quadratic) are finished by
/// `finish`, one attitude per sample time; f32 and f64 agree.
#[test]
fn short_records_are_finished() {
    for n in 1..=4usize {
        let h = 0.01;
        let mut i64 =
            RateIntegrator::try_new(q0(), RateMethod::Magnus4, Normalization::Fast, h).unwrap();
        let mut i32 = RateIntegrator::try_new(
            UnitQuat::<f32>::IDENTITY,
            RateMethod::Cf4,
            Normalization::Fast,
            h as f32,
        )
        .unwrap();
        let mut count = 0;
        let mut last = q0();
        for k in 0..n {
            let w = CONE.body_rate(k as f64 * h);
            let out = i64.push(v3(w)).unwrap();
            count += out.len();
            if let Some(q) = out.last() {
                last = *q;
            }
            i32.push(Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32))
                .unwrap();
        }
        let rest = i64.finish();
        count += rest.len();
        if let Some(q) = rest.last() {
            last = *q;
        }
        let _ = i32.finish();
        assert_eq!(count, n, "n = {n}");
        let e = quat_angle(CONE.attitude((n - 1) as f64 * h), last.to_array());
        // n = 2: one linear-interpolation step, error O(h³ Ω³ α) ≈ 1e-6.
        assert!(e < 1e-5, "n = {n}: {e}");
    }
}

/// Bad input: non-finite samples and steps are typed errors; the state is unchanged.
#[test]
fn bad_input_is_rejected() {
    use gyrostat::Error;
    assert_eq!(
        RateIntegrator::try_new(
            UnitQuat::<f64>::IDENTITY,
            RateMethod::Rk4,
            Normalization::Fast,
            0.0
        )
        .err(),
        Some(Error::InvalidArgument)
    );
    assert_eq!(
        RateIntegrator::try_new(
            UnitQuat::<f32>::IDENTITY,
            RateMethod::Rk4,
            Normalization::Fast,
            f32::NAN
        )
        .err(),
        Some(Error::NonFinite)
    );
    let mut integ = RateIntegrator::try_new(
        UnitQuat::<f32>::IDENTITY,
        RateMethod::Cf4,
        Normalization::Fast,
        0.01,
    )
    .unwrap();
    assert_eq!(
        integ.push(Vec3::new(0.0, f32::NAN, 0.0)).err(),
        Some(Error::NonFinite)
    );
    assert_eq!(integ.push(Vec3::new(0.1, 0.0, 0.0)).unwrap().len(), 1); // still sample 0
}

/// The methods' names as the `propagate` tool (`--algo`) and Python (`method=`) spell them.
#[test]
fn method_names() {
    let all = [RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4];
    assert_eq!(RateMethod::ALL, all);
    for (method, name) in all.into_iter().zip(["magnus4", "cf4", "rk4"]) {
        assert_eq!(method.name(), name);
        assert_eq!(method.to_string(), name);
        assert_eq!(name.parse::<RateMethod>(), Ok(method));
    }
    for bad in ["", "Magnus4", "rk45", "exp"] {
        assert_eq!(
            bad.parse::<RateMethod>(),
            Err(gyrostat::Error::InvalidArgument),
            "{bad:?}"
        );
    }
}
