//! The adversarial campaign over the propagation families (see `host_tests::campaign` and
//! `ROBUSTNESS.md`): the exact step, the update kernel, every coning rule, the increment
//! integrator with every rule and normalisation, the two-speed accumulator, the kinematics and
//! rates between attitudes, the normalisation policy, the rate-sample steps and the rate
//! integrator with every method and normalisation.
//!
//! `cargo test --release -p host-tests --test robustness propagation:: -- --nocapture` prints the
//! table; `GYROSTAT_CAMPAIGN_N=1000000 GYROSTAT_CAMPAIGN_WRITE=1` is the long setting that
//! writes it into `ROBUSTNESS.md`.

use gyrostat::propagation::coning::{
    four_sample, one_plus_previous, rotation_vector_for, three_sample, two_sample,
};
use gyrostat::propagation::exponential::step_constant_rate;
use gyrostat::propagation::kernels::{self, cf4_step, coning2_update, magnus4_step, rk4_step};
use gyrostat::propagation::kinematics::{
    body_rate_between, body_rate_from_quat_rate, lab_rate_between, quat_rate_body, quat_rate_lab,
};
use gyrostat::propagation::normalization::norm_deviation;
use gyrostat::propagation::rate_samples::{
    cf4_rotation_vectors, gauss_rates, magnus4_rotation_vector, midpoint_rate,
};
use gyrostat::propagation::{
    ConingAccumulator, ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::step_limit::MAX_STEP_ANGLE;
use gyrostat::{UnitQuat, Vec3};
use host_tests::campaign::*;
use host_tests::family;
use host_tests::tolerance::Tolerance;

const NORMS: [Normalization; 3] = [
    Normalization::Exact,
    Normalization::Fast,
    Normalization::None,
];

/// An increment (rad): inside the validity limit most of the time (ordinary, tiny or right at
/// the limit), otherwise any vector (huge, subnormal, non-finite).
fn increment<T: Tolerance>(g: &mut Gen<T>) -> Vec3<T> {
    match g.rng.below(4) {
        0..=1 => g.vec_within(0.2),
        2 => g.vec_within(MAX_STEP_ANGLE),
        _ => g.vec(),
    }
}

/// A body rate (rad/s) for a sample interval `dt`: inside the validity limit `|ω|·dt ≤ π` most
/// of the time, otherwise any vector.
fn rate<T: Tolerance>(g: &mut Gen<T>, dt: T) -> Vec3<T> {
    let dt = dt.to_f64().abs();
    if g.rng.chance(0.7) && dt > 0.0 && dt.is_finite() {
        let bound = (MAX_STEP_ANGLE / dt).min(g.lim.max / 4.0);
        g.vec_within(bound)
    } else {
        g.vec()
    }
}

/// The check of an attitude a rate integrator returned: unit, except RK4 without
/// renormalisation, the documented drift mode, whose norm leaves 1 by the truncation error (RK4's
/// amplification `|R(iθ/2)|` is in `[½, 1]` for step angles up to the 1.625π the push check
/// allows): finite and `|q|` in `[2^−(k+1), 2]` after `k` steps.
fn rate_attitude<T: Tolerance>(q: UnitQuat<T>, drift_mode: bool, steps: u32) -> Check {
    if drift_mode {
        let n2: f64 = q.to_array().iter().map(|c| c.to_f64() * c.to_f64()).sum();
        let n = n2.sqrt();
        ensure(
            q.as_quat().is_finite() && n <= 2.0 && n >= 0.5f64.powi(steps as i32 + 1),
            || format!("RK4 without renormalisation after {steps} steps: |q| = {n}"),
        )
    } else {
        unit(q)
    }
}

fn families<T: Tolerance>() -> Vec<Family<T>> {
    vec![
        family!("exponential::step_constant_rate", |g| {
            let (q, w, dt) = (g.unit_quat(), g.vec(), g.dt());
            probe(&(q, w, dt), || unit(step_constant_rate(q, w, dt)?))
        }),
        family!(
            "kernels::step_constant_rate, UnitQuat::mul_exp_unchecked",
            |g| {
                // Domain: a representable rotation vector ω·Δt.
                let q = g.unit_quat();
                let phi = g.vec_within(g.lim.max / 4.0);
                let norm = *g.rng.pick(&NORMS);
                probe(&(q, phi, norm), || {
                    unit(kernels::step_constant_rate(q, phi, T::ONE))?;
                    unit(q.mul_exp_unchecked(phi, norm))
                })
            }
        ),
        family!(
            "coning rules (one_plus_previous, two/three/four_sample, rotation_vector_for, coning2_update)",
            |g| {
                // Domain: increments within the validity limit.
                let q = g.unit_quat();
                let t = [
                    g.vec_within(MAX_STEP_ANGLE),
                    g.vec_within(MAX_STEP_ANGLE),
                    g.vec_within(MAX_STEP_ANGLE),
                    g.vec_within(MAX_STEP_ANGLE),
                ];
                let n = g.rng.below(6);
                probe(&(q, t, n), || {
                    finite_vec(one_plus_previous(t[0], t[1]))?;
                    finite_vec(two_sample(t[0], t[1]))?;
                    finite_vec(three_sample(t[0], t[1], t[2]))?;
                    finite_vec(four_sample(t[0], t[1], t[2], t[3]))?;
                    finite_vec(rotation_vector_for(t[0], &t[..n.min(4)]))?;
                    unit(coning2_update(q, t[0], t[1]))
                })
            }
        ),
        family!(
            "IncrementIntegrator (5 rules × 3 normalisations): push, provisional_attitude, flush",
            |g| {
                let q0 = g.unit_quat();
                let rule = *g.rng.pick(&ConingRule::ALL);
                let norm = *g.rng.pick(&NORMS);
                let n = 1 + g.rng.below(9);
                let incs: Vec<Vec3<T>> = (0..n).map(|_| increment(g)).collect();
                probe(&(q0, rule, norm, incs.clone()), || {
                    let mut integ = IncrementIntegrator::new(q0, rule, norm);
                    let mut last_err = None;
                    for v in &incs {
                        match integ.push(*v) {
                            Ok(Some(q)) => unit(q)?,
                            Ok(None) => {}
                            Err(e) => last_err = Some(e),
                        }
                        unit(integ.provisional_attitude())?;
                        ensure(integ.pending() < rule.samples_per_update(), || {
                            format!("{} pending for {rule:?}", integ.pending())
                        })?;
                    }
                    unit(integ.attitude())?;
                    unit(integ.flush())?;
                    match last_err {
                        Some(e) => Err(e.into()),
                        None => Ok(()),
                    }
                })
            }
        ),
        family!("ConingAccumulator: push, rotation_vector, take", |g| {
            let n = 1 + g.rng.below(12);
            let incs: Vec<Vec3<T>> = (0..n).map(|_| increment(g)).collect();
            let q = g.unit_quat();
            probe(&(incs.clone(), q), || {
                let mut acc = ConingAccumulator::new();
                let mut last_err = None;
                for v in &incs {
                    let before = acc;
                    if let Err(e) = acc.push(*v) {
                        ensure(acc == before, || "a rejected push changed the state".into())?;
                        last_err = Some(e);
                    }
                    finite_vec(acc.rotation_vector())?;
                }
                let phi = acc.take();
                finite_vec(phi)?;
                unit(UnitQuat::try_exp(phi)?)?;
                unit(q.mul_exp_unchecked(phi, Normalization::Fast))?;
                match last_err {
                    Some(e) => Err(e.into()),
                    None => Ok(()),
                }
            })
        }),
        family!(
            "kinematics::{quat_rate_body, quat_rate_lab, body_rate_from_quat_rate}",
            |g| {
                // Domain: a unit attitude and a rate whose products stay finite.
                let q = g.unit_quat();
                let w = g.vec_within(g.lim.max / 8.0);
                probe(&(q, w), || {
                    let qb = quat_rate_body(*q.as_quat(), w);
                    let ql = quat_rate_lab(*q.as_quat(), w);
                    finite_all(&qb.to_array())?;
                    finite_all(&ql.to_array())?;
                    finite_vec(body_rate_from_quat_rate(q, qb))
                })
            }
        ),
        family!("kinematics::{body_rate_between, lab_rate_between}", |g| {
            let (q0, q1) = g.unit_quat_pair();
            let dt = g.dt();
            probe(&(q0, q1, dt), || {
                finite_vec(body_rate_between(q0, q1, dt)?)?;
                finite_vec(lab_rate_between(q0, q1, dt)?)
            })
        }),
        family!("normalization: Normalization::apply, norm_deviation", |g| {
            let q = g.unit_quat();
            let norm = *g.rng.pick(&NORMS);
            probe(&(q, norm), || {
                unit(norm.apply(q))?;
                finite(norm_deviation(q))
            })
        }),
        family!(
            "rate-sample steps (gauss_rates, midpoint_rate, Magnus-4, CF4, RK4 + apply_quat_unchecked)",
            |g| {
                // Domain: finite samples with |ω|·h within the validity limit.
                let h = g.ordinary_dt();
                let window = [rate(g, h), rate(g, h), rate(g, h), rate(g, h)];
                let window = window.map(|w| {
                    if w.is_finite() && (w.norm().to_f64() * h.to_f64()) <= MAX_STEP_ANGLE {
                        w
                    } else {
                        Vec3::ZERO
                    }
                });
                let interval = g.rng.below(4);
                let q = g.unit_quat();
                let norm = *g.rng.pick(&[Normalization::Exact, Normalization::Fast]);
                probe(&(h, window, interval, q, norm), || {
                    let (w1, w2) = gauss_rates(&window, interval);
                    finite_vec(w1)?;
                    finite_vec(w2)?;
                    let wm = midpoint_rate(&window, interval);
                    finite_vec(wm)?;
                    finite_vec(magnus4_rotation_vector(w1, w2, h))?;
                    let (p1, p2) = cf4_rotation_vectors(w1, w2, h);
                    finite_vec(p1)?;
                    finite_vec(p2)?;
                    unit(magnus4_step(q, w1, w2, h))?;
                    unit(cf4_step(q, w1, w2, h))?;
                    let raw = rk4_step(*q.as_quat(), window[0], wm, window[3], h);
                    finite_all(&raw.to_array())?;
                    unit(norm.apply_quat_unchecked(raw))
                })
            }
        ),
        family!(
            "RateIntegrator (3 methods × 3 normalisations): new, push, finish",
            |g| {
                let q0 = g.unit_quat();
                let method = *g
                    .rng
                    .pick(&[RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4]);
                let norm = *g.rng.pick(&NORMS);
                let dt = g.dt();
                let n = 1 + g.rng.below(8);
                let samples: Vec<Vec3<T>> = (0..n).map(|_| rate(g, dt)).collect();
                probe(&(q0, method, norm, dt, samples.clone()), || {
                    let drift = method == RateMethod::Rk4 && norm == Normalization::None;
                    let mut integ = RateIntegrator::try_new(q0, method, norm, dt)?;
                    let mut steps = 0u32;
                    let mut last_err = None;
                    for w in &samples {
                        match integ.push(*w) {
                            Ok(qs) => {
                                for q in qs {
                                    steps += 1;
                                    rate_attitude(q, drift, steps)?;
                                }
                            }
                            Err(e) => last_err = Some(e),
                        }
                        rate_attitude(integ.attitude(), drift, steps)?;
                    }
                    for q in integ.finish() {
                        steps += 1;
                        rate_attitude(q, drift, steps)?;
                    }
                    match last_err {
                        Some(e) => Err(e.into()),
                        None => Ok(()),
                    }
                })
            }
        ),
    ]
}

#[test]
fn campaign() {
    run_campaign("propagation", families::<f32>(), families::<f64>());
}
