//! Propagation on unequal intervals, against the closed-form coning motion and an independent
//! fine-step integration:
//!
//! - the 2-sample rule for unequal sub-intervals, coefficient `(h₁ + h₂)²/(6 h₁ h₂)`: equal to
//!   `⅔` on equal intervals; on a linearly varying rate its one-pair error is of 4th order in
//!   the pair's length (the `⅔` rule on the same unequal pair: 3rd order); under coning on a
//!   jittered clock its drift falls as `(ΩT)⁴` (the `⅔` rule's as `(ΩT)²`);
//! - Magnus-4 on rate samples at jittered times: global order 4.

use super::Rng;
use gyrostat::fixed::IncrementQuantizer;
use gyrostat::propagation::coning::{
    two_sample_terms, two_sample_unequal_coefficient, two_sample_unequal_terms,
};
use gyrostat::propagation::kernels::{
    cf4_step_unequal, coning2_update_unequal, magnus4_step_unequal, rk4_step_unequal,
};
use gyrostat::real::Q30;
use gyrostat::{Quat, UnitQuat, Vec3};
use host_tests::ref_propagation::{Coning, body_error, fit_slope};
use host_tests::reference::{Q, V3, add, qmul, quat_angle, scale};

fn uq(q: Q) -> UnitQuat<f64> {
    UnitQuat::try_new(Quat::from_array(q)).unwrap()
}

#[test]
fn coefficient_reduces_to_two_thirds() {
    let mut rng = Rng::new(40);
    for _ in 0..1000 {
        let h = rng.range(1e-5, 1.0);
        let c = two_sample_unequal_coefficient(h, h);
        assert!((c - 2.0 / 3.0).abs() <= 2.0 * f64::EPSILON, "{c}");
        let t1 = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ) * 0.01;
        let t2 = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ) * 0.01;
        let a = two_sample_unequal_terms(t1, t2, c).rotation_vector();
        let b = two_sample_terms(t1, t2).rotation_vector();
        assert!((a - b).max_abs() <= 1e-18);
        // (h₁ + h₂)²/(6 h₁ h₂) written directly.
        let (h1, h2) = (rng.range(0.1, 2.0), rng.range(0.1, 2.0));
        let direct = (h1 + h2) * (h1 + h2) / (6.0 * h1 * h2);
        assert!(
            (two_sample_unequal_coefficient(h1, h2) - direct).abs() <= 4.0 * f64::EPSILON * direct
        );
    }
}

/// `q̇ = ½ q ⊗ (0, ω(t))` by classical RK4 on 4000 substeps, plain arrays: the reference for one
/// pair under a given rate function.
fn fine(q0: Q, w: impl Fn(f64) -> V3, t0: f64, t1: f64) -> Q {
    let n = 4000;
    let h = (t1 - t0) / n as f64;
    let f = |q: Q, t: f64| {
        let o = w(t);
        let d = qmul(q, [0.0, o[0], o[1], o[2]]);
        d.map(|x| 0.5 * x)
    };
    let mut q = q0;
    for i in 0..n {
        let t = t0 + i as f64 * h;
        let k1 = f(q, t);
        let k2 = f(std::array::from_fn(|j| q[j] + 0.5 * h * k1[j]), t + 0.5 * h);
        let k3 = f(std::array::from_fn(|j| q[j] + 0.5 * h * k2[j]), t + 0.5 * h);
        let k4 = f(std::array::from_fn(|j| q[j] + h * k3[j]), t + h);
        q = std::array::from_fn(|j| q[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]));
    }
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    q.map(|x| x / n)
}

#[test]
fn linear_rate_one_pair_orders() {
    // ω(t) = a + b t over [0, h₁ + h₂] with h₂ = 2.7 h₁; increments integrated here in closed form.
    let a: V3 = [0.9, -0.4, 0.3];
    let b: V3 = [-3.0, 5.0, 2.0];
    let w = |t: f64| add(a, scale(b, t));
    let inc = |t0: f64, t1: f64| add(scale(a, t1 - t0), scale(b, 0.5 * (t1 * t1 - t0 * t0)));
    let mut errs = vec![];
    for k in 0..4 {
        let h1 = 0.04 / 2f64.powi(k);
        let h2 = 2.7 * h1;
        let (t1, t2) = (inc(0.0, h1), inc(h1, h1 + h2));
        let truth = fine([1.0, 0.0, 0.0, 0.0], w, 0.0, h1 + h2);
        let c = two_sample_unequal_coefficient(h1, h2);
        let v = |x: V3| Vec3::from_array(x);
        let qu = coning2_update_unequal(UnitQuat::IDENTITY, v(t1), v(t2), c).renormalize();
        let qn = coning2_update_unequal(UnitQuat::IDENTITY, v(t1), v(t2), 2.0 / 3.0).renormalize();
        errs.push((
            quat_angle(qu.to_array(), truth),
            quat_angle(qn.to_array(), truth),
        ));
    }
    for p in errs.windows(2) {
        let (ru, rn) = (p[0].0 / p[1].0, p[0].1 / p[1].1);
        // Halving the pair: the unequal rule's error falls ≥ 2^3.5 (4th order), the ⅔ rule's as
        // 2³ (its coning term is wrong at 3rd order).
        assert!(ru > 11.3, "unequal ratio {ru} {errs:?}");
        assert!((6.5..10.0).contains(&rn), "2/3 ratio {rn} {errs:?}");
    }
    assert!(errs[3].0 < errs[3].1 / 50.0, "{errs:?}");
}

/// Jittered intervals `h·(1 + j·u)`, `u` uniform in `[−1, 1)`, from a seed: the same pattern at
/// every `h` so that a halving compares like with like.
fn intervals(h: f64, jitter: f64, n: usize, seed: u64) -> Vec<f64> {
    let mut rng = Rng::new(seed);
    (0..n)
        .map(|_| h * (1.0 + jitter * rng.range(-1.0, 1.0)))
        .collect()
}

enum Coef {
    Unequal,
    TwoThirds,
}

/// Runs the 2-sample update in pairs of jittered increments of the cone for `duration` s;
/// returns the fitted axial drift rate (rad/s) of the body error.
fn coning_drift(c: &Coning, h: f64, jitter: f64, duration: f64, coef: Coef) -> f64 {
    let n = (duration / h) as usize & !1;
    let hs = intervals(h, jitter, n, 41);
    let mut q = uq(c.attitude(0.0));
    let mut t = 0.0;
    let (mut ts, mut ys) = (vec![], vec![]);
    for pair in hs.chunks_exact(2) {
        let (h1, h2) = (pair[0], pair[1]);
        let t1 = Vec3::from_array(c.increment(t, t + h1));
        let t2 = Vec3::from_array(c.increment(t + h1, t + h1 + h2));
        t += h1 + h2;
        let k = match coef {
            Coef::Unequal => two_sample_unequal_coefficient(h1, h2),
            Coef::TwoThirds => 2.0 / 3.0,
        };
        q = coning2_update_unequal(q, t1, t2, k).renormalize();
        ts.push(t);
        ys.push(body_error(c.attitude(t), q.to_array())[2]);
    }
    fit_slope(&ts, &ys)
}

#[test]
fn jittered_coning_drift_order() {
    // α = 0.02 rad, Ω = 2π·25 Hz; mean interval h with ±40 % jitter; 2 s of motion. ΩT for the
    // pair T = 2h: 0.31 and 0.16.
    let c = Coning {
        alpha: 0.02,
        omega_c: 2.0 * std::f64::consts::PI * 25.0,
    };
    let (h0, jit, dur) = (1e-3, 0.4, 2.0);
    let du = [
        coning_drift(&c, h0, jit, dur, Coef::Unequal),
        coning_drift(&c, h0 / 2.0, jit, dur, Coef::Unequal),
    ];
    let dn = [
        coning_drift(&c, h0, jit, dur, Coef::TwoThirds),
        coning_drift(&c, h0 / 2.0, jit, dur, Coef::TwoThirds),
    ];
    let de = [
        coning_drift(&c, h0, 0.0, dur, Coef::TwoThirds),
        coning_drift(&c, h0 / 2.0, 0.0, dur, Coef::TwoThirds),
    ];
    eprintln!("unequal {du:?}\n2/3 on jitter {dn:?}\nequal clock {de:?}");
    // The published 2-sample drift on an equal clock, Ωα²(ΩT)⁴/960 (small α), is the scale.
    let classical = |h: f64| {
        let wt = c.omega_c * 2.0 * h;
        c.omega_c * c.alpha * c.alpha * wt.powi(4) / 960.0
    };
    assert!(
        (de[0].abs() / classical(h0) - 1.0).abs() < 0.05,
        "{} {}",
        de[0],
        classical(h0)
    );
    let ru = du[0] / du[1];
    assert!(
        (13.0..19.0).contains(&ru),
        "unequal: order 4 expected, ratio {ru}"
    );
    let rn = dn[0] / dn[1];
    assert!(
        (3.5..4.6).contains(&rn),
        "2/3 on jitter: order 2 expected, ratio {rn}"
    );
    // On the jittered clock the unequal rule stays within a small factor of the equal-clock
    // drift; the ⅔ rule is far off.
    assert!(du[0].abs() < 3.0 * de[0].abs(), "{du:?} {de:?}");
    assert!(dn[0].abs() > 10.0 * du[0].abs(), "{dn:?} {du:?}");
}

/// The same jittered run in f32 and Q1.30 (coefficient converted per pair, increments through
/// the remainder-carrying quantizer): the end error against the closed form, beside f64's.
#[test]
fn jittered_coning_in_f32_and_q30() {
    let c = Coning {
        alpha: 0.05,
        omega_c: 2.0 * std::f64::consts::PI * 7.3,
    };
    let hs = intervals(1e-3, 0.4, 10_000, 42);
    let mut q64 = uq(c.attitude(0.0));
    let mut q32: UnitQuat<f32> = host_tests::cast::unit_quat(c.attitude(0.0));
    let mut qq = UnitQuat::<Q30>::try_from_f64(q64).unwrap();
    let mut quant = IncrementQuantizer::<30>::new();
    let mut t = 0.0;
    for pair in hs.chunks_exact(2) {
        let (h1, h2) = (pair[0], pair[1]);
        let t1 = Vec3::from_array(c.increment(t, t + h1));
        let t2 = Vec3::from_array(c.increment(t + h1, t + h1 + h2));
        t += h1 + h2;
        let k = two_sample_unequal_coefficient(h1, h2);
        q64 = coning2_update_unequal(q64, t1, t2, k);
        let f = |v: Vec3<f64>| Vec3::from_array(v.to_array().map(|x| x as f32));
        q32 = coning2_update_unequal(q32, f(t1), f(t2), k as f32);
        let (a, b) = (
            quant.try_quantize(t1).unwrap(),
            quant.try_quantize(t2).unwrap(),
        );
        qq = coning2_update_unequal(qq, a, b, Q30::try_from_f64(k).unwrap());
    }
    let truth = c.attitude(t);
    let e64 = quat_angle(q64.to_array(), truth);
    let e32 = quat_angle(q32.to_array().map(f64::from), q64.to_array());
    let eq = quat_angle(qq.to_f64().to_array(), q64.to_array());
    eprintln!("10 s jittered cone: f64 error {e64:e} rad; f32 − f64 {e32:e}, Q1.30 − f64 {eq:e}");
    // f64: the rule's truncation, the equal-clock drift Ωα²(ΩT)⁴/960 over 10 s (8.4e-8 rad)
    // within a factor 2 (the jitter).
    let wt = c.omega_c * 2e-3;
    let classical = c.omega_c * c.alpha * c.alpha * wt.powi(4) / 960.0 * t;
    assert!(
        e64 < 2.0 * classical && e64 > classical / 2.0,
        "{e64:e} {classical:e}"
    );
    // f32: the plain attitude's rounding over 5000 updates (≈ 6e-8 each, partly systematic);
    // Q1.30: the plain update's rounding bias (see gyrostat::fixed, "Rounding bias": up to
    // 1.5e-5 rad in 60 s at 1 kHz).
    assert!(e32 < 1e-4, "{e32:e}");
    assert!(eq < 3e-6, "{eq:e}");
}

/// The unequal-time rate steps: Magnus-4, CF4 and RK4 (renormalised exactly).
#[derive(Clone, Copy, Debug)]
enum Method {
    Magnus4,
    Cf4,
    Rk4,
}

/// A rate method on jittered rate samples of the cone: window of the last four samples (fewer
/// at the start), order 4 under halving.
fn rate_error(method: Method, c: &Coning, h: f64, jitter: f64, duration: f64) -> f64 {
    let n = (duration / h) as usize;
    let hs = intervals(h, jitter, n, 43);
    let mut times = vec![0.0];
    for d in &hs {
        times.push(times.last().unwrap() + d);
    }
    let w = |t: f64| Vec3::from_array(c.body_rate(t));
    let mut q = uq(c.attitude(0.0));
    for k in 1..times.len() {
        // The interval [t_{k−1}, t_k] with samples k−3 … k; the first three with samples 0 … 3.
        let first = k.saturating_sub(3).min(times.len() - 4);
        let ts: [f64; 4] = std::array::from_fn(|i| times[first + i]);
        let (ws, a, b) = (ts.map(w), times[k - 1], times[k]);
        q = match method {
            Method::Magnus4 => magnus4_step_unequal(q, &ts, &ws, a, b),
            Method::Cf4 => cf4_step_unequal(q, &ts, &ws, a, b),
            Method::Rk4 => rk4_step_unequal(q.into_quat(), &ts, &ws, a, b)
                .try_normalize()
                .unwrap(),
        }
        .renormalize();
    }
    quat_angle(q.to_array(), c.attitude(*times.last().unwrap()))
}

/// Magnus-4, CF4 and RK4 on jittered rate samples (±40 %), f64, against the closed-form cone:
/// the error falls 11 to 24 times per halving of the step (order 4: 16), and is within a factor
/// 4 of the same method on the regular clock.
#[test]
fn rate_methods_on_jittered_rate_samples_are_fourth_order() {
    let c = Coning {
        alpha: 0.3,
        omega_c: 2.0 * std::f64::consts::PI * 3.1,
    };
    for method in [Method::Magnus4, Method::Cf4, Method::Rk4] {
        let e: Vec<f64> = [4e-3, 2e-3, 1e-3]
            .iter()
            .map(|&h| rate_error(method, &c, h, 0.4, 1.0))
            .collect();
        eprintln!("{method:?} unequal errors {e:?}");
        for p in e.windows(2) {
            let r = p[0] / p[1];
            assert!((11.0..24.0).contains(&r), "{method:?} ratio {r} {e:?}");
        }
        // The same clock without the jitter, for scale: the jittered run is within a small
        // factor.
        let reg = rate_error(method, &c, 1e-3, 0.0, 1.0);
        assert!(
            e[2] < 4.0 * reg && e[2] > reg / 4.0,
            "{method:?} {} {reg}",
            e[2]
        );
    }
}

#[test]
fn q30_coefficient_from_microseconds() {
    use gyrostat::Error;
    use gyrostat::sensor::timing::unequal_coefficient_q30;
    let mut rng = Rng::new(44);
    for _ in 0..200_000 {
        let h1 = 1 + (rng.uniform() * 1_048_575.0) as u32;
        let h2 = 1 + (rng.uniform() * 1_048_575.0) as u32;
        // The exact rational in f64 (numerator and denominator exact below 2⁵³).
        let (a, b) = (h1 as f64, h2 as f64);
        let want = (a + b) * (a + b) / (6.0 * a * b);
        match unequal_coefficient_q30(h1, h2) {
            Ok(c) => assert!(
                (c.to_f64() - want).abs() <= 2f64.powi(-31) + 2.0 * f64::EPSILON,
                "{h1} {h2}"
            ),
            Err(e) => assert!(
                e == Error::OutOfRange && want >= 2.0 - 2f64.powi(-31),
                "{h1} {h2} {e:?}"
            ),
        }
    }
    assert_eq!(
        unequal_coefficient_q30(1000, 1000).unwrap().to_f64(),
        (2.0f64 / 3.0 * 2f64.powi(30)).round() / 2f64.powi(30)
    );
    assert_eq!(unequal_coefficient_q30(0, 5), Err(Error::InvalidArgument));
    assert_eq!(
        unequal_coefficient_q30(5, (1 << 20) + 1),
        Err(Error::InvalidArgument)
    );
    assert_eq!(unequal_coefficient_q30(1, 1000), Err(Error::OutOfRange));
}
