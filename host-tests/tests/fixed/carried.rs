//! The carried fixed-point attitude (`propagation::CarriedAttitude`, `fixed::IncrementQuantizer`,
//! `src/propagation/carried_attitude.rs`, `src/fixed/quantizer.rs`) against the closed-form coning attitude and the exact constant-rate
//! attitude, beside the plain f32 and the f64 paths fed the same f64 increments (f32: rounded to
//! f32), on inputs that do not repeat and on one that does.
//!
//! Targets (issue 18): the fixed error ≤ the plain f32 error for every rule and start, and on a
//! cone that does not repeat the drift of the one-plus-previous and 2-sample rules within 5 % of
//! f64's. Where the rule's own error is below both arithmetics' floors, f32's end value depends
//! on the last bits of its inputs (the 4-sample rule on the repeating 1° cone: 6.4e-9 rad here
//! with the f64 increments cast to f32, 1.29e-7 through `propagate --f32`, which parses the
//! decimal text as f32); the check is then the fixed floor: within 1e-8 rad of f64 after 60 s
//! (measured 9.3e-9, growing at 1.5e-10 rad/s).
//!
//! `rounding_causes` shows the causes of the plain path's bias one at a time (see the
//! `gyrostat::fixed` module docs, "Rounding bias").

use gyrostat::fixed::IncrementQuantizer;
use gyrostat::propagation::CarriedAttitude;
use gyrostat::propagation::{ConingRule, IncrementIntegrator, Normalization};
use gyrostat::real::Q30;
use gyrostat::{Quat, UnitQuat, Vec3};
use host_tests::cast::{self, vec3};
use host_tests::ref_propagation::Coning;
use host_tests::reference::{Q, qconj, qmul, quat_angle};

const H: f64 = 1e-3;

/// A motion: its exact increments and attitude.
struct Motion {
    name: String,
    increments: Vec<[f64; 3]>,
    truth: Box<dyn Fn(f64) -> Q>,
}

fn cone(alpha_deg: f64, hz: f64, seconds: f64) -> Motion {
    let c = Coning {
        alpha: alpha_deg.to_radians(),
        omega_c: 2.0 * std::f64::consts::PI * hz,
    };
    let n = (seconds / H).round() as usize;
    Motion {
        name: format!("cone {alpha_deg}° at {hz} Hz, {seconds} s"),
        increments: (0..n)
            .map(|k| c.increment(k as f64 * H, (k + 1) as f64 * H))
            .collect(),
        truth: Box::new(move |t| c.attitude(t)),
    }
}

/// A constant body rate from the base attitude `q0`: `q0 ⊗ exp(ω t)`.
fn constant_rate(w: [f64; 3], q0: Q, seconds: f64) -> Motion {
    let n = (seconds / H).round() as usize;
    let norm = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    Motion {
        name: format!("constant rate {w:?} rad/s, {seconds} s"),
        increments: vec![w.map(|x| x * H); n],
        truth: Box::new(move |t| {
            let (s, c) = (0.5 * norm * t).sin_cos();
            qmul(q0, [c, s * w[0] / norm, s * w[1] / norm, s * w[2] / norm])
        }),
    }
}

/// The start: on the motion (its exact attitude at t = 0), or the identity (then the truth is
/// the motion's attitude seen from its start, `q(0)* ⊗ q(t)`).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Start {
    OnMotion,
    Identity,
}

/// Final errors (rad) of the carried fixed path, plain f32 and f64 for one rule.
struct Errors {
    fixed: f64,
    f32: f64,
    f64: f64,
}

/// How the fixed path converts its input and carries its attitude (`rounding_causes`).
#[derive(Clone, Copy, PartialEq)]
enum FixedPath {
    /// `IncrementQuantizer` + `CarriedAttitude`: the unbiased path.
    Carried,
    /// Each increment rounded on its own (`Vec3::try_from_f64`) + `CarriedAttitude`.
    RoundedInput,
    /// `IncrementQuantizer` + the plain `UnitQuat<Q30>` attitude.
    PlainAttitude,
}

fn run_fixed(m: &Motion, rule: ConingRule, q0: Q, path: FixedPath) -> Q {
    let q0x = UnitQuat::<Q30>::try_from_f64(UnitQuat::new_unchecked(Quat::from_array(q0))).unwrap();
    let mut quant = IncrementQuantizer::<30>::new();
    let mut conv = |d: &[f64; 3]| match path {
        FixedPath::RoundedInput => Vec3::<Q30>::try_from_f64(Vec3::from_array(*d)).unwrap(),
        _ => quant.try_quantize(Vec3::from_array(*d)).unwrap(),
    };
    let fast = Normalization::Fast;
    let q = if path == FixedPath::PlainAttitude {
        let mut integ = IncrementIntegrator::new(q0x, rule, fast);
        for d in &m.increments {
            integ.push(conv(d)).unwrap();
        }
        integ.flush()
    } else {
        let mut integ = IncrementIntegrator::new(CarriedAttitude::new(q0x), rule, fast);
        for d in &m.increments {
            integ.push(conv(d)).unwrap();
        }
        integ.flush()
    };
    q.to_f64().to_array()
}

fn errors(m: &Motion, rule: ConingRule, start: Start) -> Errors {
    let on = (m.truth)(0.0);
    let (q0, pre) = match start {
        Start::OnMotion => (on, [1.0, 0.0, 0.0, 0.0]),
        Start::Identity => ([1.0, 0.0, 0.0, 0.0], qconj(on)),
    };
    let t_end = m.increments.len() as f64 * H;
    let truth = qmul(pre, (m.truth)(t_end));
    let fast = Normalization::Fast;
    let mut i32 = IncrementIntegrator::new(
        UnitQuat::new_unchecked(Quat::from_array(q0.map(|x| x as f32))).renormalize(),
        rule,
        fast,
    );
    let mut i64 =
        IncrementIntegrator::new(UnitQuat::new_unchecked(Quat::from_array(q0)), rule, fast);
    for d in &m.increments {
        i32.push(vec3::<f32>(*d)).unwrap();
        i64.push(Vec3::from_array(*d)).unwrap();
    }
    Errors {
        fixed: quat_angle(truth, run_fixed(m, rule, q0, FixedPath::Carried)),
        f32: quat_angle(truth, cast::q64(i32.flush())),
        f64: quat_angle(truth, i64.flush().to_array()),
    }
}

/// Every rule and both starts: fixed ≤ f32 (or within the fixed floor of f64, see the module
/// docs); returns the
/// errors per (start, rule) for further checks.
fn check_every_rule(m: &Motion) -> Vec<(Start, ConingRule, Errors)> {
    let mut out = Vec::new();
    for start in [Start::OnMotion, Start::Identity] {
        for rule in ConingRule::ALL {
            let e = errors(m, rule, start);
            println!(
                "{:<40} {start:<9?} {rule:<16?} fixed {:.3e}  f32 {:.3e}  f64 {:.3e} rad",
                m.name, e.fixed, e.f32, e.f64
            );
            assert!(
                e.fixed <= e.f32 || e.fixed <= e.f64 + 1e-8,
                "{} {start:?} {rule:?}: fixed {:e} > f32 {:e} (f64 {:e})",
                m.name,
                e.fixed,
                e.f32,
                e.f64
            );
            out.push((start, rule, e));
        }
    }
    out
}

/// The cone of the issue that does not repeat (3°, 19.37 Hz: 51.6 samples per period), 20 s:
/// the fixed drift of the one-plus-previous and 2-sample rules within 5 % of f64's, and f64
/// within 3 % of the leading drift terms `α²Ω(Ωh)⁴/60` and `α²Ω(ΩT)⁴/960` (the `O(α⁴)` terms
/// are 1.4 % and 0.4 % here).
#[test]
fn cone_that_does_not_repeat() {
    let m = cone(3.0, 19.37, 20.0);
    let (alpha, omega) = (3f64.to_radians(), 2.0 * std::f64::consts::PI * 19.37);
    let a2w = alpha * alpha * omega;
    let theory = |rule| match rule {
        ConingRule::OnePlusPrevious => a2w * (omega * H).powi(4) / 60.0 * 20.0,
        _ => a2w * (2.0 * omega * H).powi(4) / 960.0 * 20.0,
    };
    for (start, rule, e) in check_every_rule(&m) {
        if matches!(rule, ConingRule::OnePlusPrevious | ConingRule::TwoSample) {
            let th = theory(rule);
            println!(
                "  {start:?} {rule:?}: fixed/f64 = {:.4}, f64/theory = {:.4}",
                e.fixed / e.f64,
                e.f64 / th
            );
            assert!((e.fixed / e.f64 - 1.0).abs() < 0.05, "{start:?} {rule:?}");
            assert!((e.f64 / th - 1.0).abs() < 0.03, "{start:?} {rule:?}");
        }
    }
}

/// The repeating cone of the issue (1°, 10 Hz: 100 samples per period), 60 s. The plain Q1.30
/// attitude locks into a cycle of the same bits here and shows no drift at all (2.6e-10 rad
/// against the 2-sample rule's 2.98e-7, `rounding_causes`); the carried one reproduces f64's
/// drift to 5 %.
#[test]
fn cone_that_repeats() {
    let m = cone(1.0, 10.0, 60.0);
    for (start, rule, e) in check_every_rule(&m) {
        if matches!(rule, ConingRule::OnePlusPrevious | ConingRule::TwoSample) {
            assert!(
                (e.fixed / e.f64 - 1.0).abs() < 0.05,
                "{start:?} {rule:?}: fixed {:e} f64 {:e}",
                e.fixed,
                e.f64
            );
        }
    }
}

/// Constant rates, 60 s, from a base attitude and from the identity: every rule within 1e-7 rad
/// of the exact attitude (plain Q1.30: 2e-6 to 1.4e-5; f32: 2e-6 to 7e-4).
#[test]
fn constant_rates() {
    let (s, c) = 0.4f64.sin_cos();
    let base = [c, 0.6 * s, 0.8 * s, 0.0];
    for w in [[0.3, -0.2, 0.5], [1.0, 0.0, 0.0], [0.05, 0.011, -0.07]] {
        let m = constant_rate(w, base, 60.0);
        for (start, rule, e) in check_every_rule(&m) {
            assert!(e.fixed < 1e-7, "{w:?} {start:?} {rule:?}: {:e}", e.fixed);
        }
    }
}

/// The causes, one at a time, with the carried path as the control:
/// - each increment rounded on its own: a constant rate drifts by the rounding of its increment,
///   as the exact attitude of the rounded increment, `q₀ ⊗ exp(n·round(d))`, predicts (to 2 %);
/// - the plain attitude (rounded to 2⁻³⁰ every update, nothing carried): on the repeating cone
///   the 2-sample attitude returns to the same bits every period and loses the rule's drift
///   (error < 1/10 of f64's); on the cone that does not repeat it ends off f64 by more than 10 %.
///
/// The other two roundings that `CarriedAttitude` carries (the coning term and the rotation
/// increment at 2⁻³³) are inside one update; their effect is in the module docs' table.
#[test]
fn rounding_causes() {
    // Input rounding.
    let (s, c) = 0.4f64.sin_cos();
    let m = constant_rate([0.3, -0.2, 0.5], [c, 0.6 * s, 0.8 * s, 0.0], 60.0);
    let q0 = (m.truth)(0.0);
    let truth = (m.truth)(60.0);
    let d = m.increments[0];
    let rounded = Vec3::<Q30>::try_from_f64(Vec3::from_array(d))
        .unwrap()
        .to_f64()
        .to_array();
    let n = m.increments.len() as f64;
    let exp_n = |v: [f64; 3]| {
        let th = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() * n;
        let (s, c) = (0.5 * th).sin_cos();
        let k = s * n / th;
        qmul(q0, [c, k * v[0], k * v[1], k * v[2]])
    };
    let predicted = quat_angle(exp_n(d), exp_n(rounded));
    let e_rounded = quat_angle(
        truth,
        run_fixed(&m, ConingRule::TwoSample, q0, FixedPath::RoundedInput),
    );
    let e_carried = quat_angle(
        truth,
        run_fixed(&m, ConingRule::TwoSample, q0, FixedPath::Carried),
    );
    println!(
        "constant rate, 60 s, 2-sample: each increment rounded {e_rounded:.3e} rad (predicted {predicted:.3e}), remainder carried {e_carried:.3e}"
    );
    assert!((e_rounded / predicted - 1.0).abs() < 0.02);
    assert!(e_carried < e_rounded / 30.0);

    // Attitude rounding: the repeating cone.
    let m = cone(1.0, 10.0, 60.0);
    let q0 = (m.truth)(0.0);
    let truth = (m.truth)(60.0);
    let e = errors(&m, ConingRule::TwoSample, Start::OnMotion);
    let e_plain = quat_angle(
        truth,
        run_fixed(&m, ConingRule::TwoSample, q0, FixedPath::PlainAttitude),
    );
    println!(
        "cone 1° at 10 Hz, 2-sample: plain attitude {e_plain:.3e} rad, carried {:.3e}, f64 {:.3e}",
        e.fixed, e.f64
    );
    assert!(e_plain < 0.1 * e.f64);

    // Attitude rounding: the cone that does not repeat.
    let m = cone(3.0, 19.37, 20.0);
    let q0 = (m.truth)(0.0);
    let truth = (m.truth)(20.0);
    let e = errors(&m, ConingRule::TwoSample, Start::OnMotion);
    let e_plain = quat_angle(
        truth,
        run_fixed(&m, ConingRule::TwoSample, q0, FixedPath::PlainAttitude),
    );
    println!(
        "cone 3° at 19.37 Hz, 2-sample: plain attitude {e_plain:.3e} rad, carried {:.3e}, f64 {:.3e}",
        e.fixed, e.f64
    );
    assert!((e_plain / e.f64 - 1.0).abs() > 0.1);
}
