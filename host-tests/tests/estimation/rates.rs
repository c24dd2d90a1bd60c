//! The estimator's rate path (`Params::rate_rule`): rate samples at jittered, unequal times
//! through the propagation module's unequal-interval Magnus-4 and CF4 (the Gauss-node rates of
//! the backward cubic interpolant) converge with order 4, the trapezoid with order 2. Checked
//! against a closed-form attitude (independent of the library: two rotations with known angle
//! histories, `host_tests::reference` quaternion algebra), with the accelerometer unusable
//! after the first sample so that only the prediction moves the attitude; and the compensated
//! strapdown attitude (`Estimator::try_new_compensated`) against the f64 filter. The light mode
//! (`Mode::Light`) takes the same rule by its own arithmetic (Magnus-4 from cached weights, the
//! commutator from the step's end samples) and converges with the same orders.

use gyrostat::estimation::{Estimator, Mode, Params, RateRule};
use gyrostat::{Error, Real};
use host_tests::cast::{q64, vec3};
use host_tests::reference::{Q, qconj, qmul, quat_angle};

use super::Lcg;

/// `α(t)`, `β(t)` and their rates: incommensurate frequencies, so the motion never repeats.
fn angles(t: f64) -> (f64, f64, f64, f64) {
    let (f1, f2) = (5f64.sqrt() * 2.3, 2f64.sqrt() * 4.1);
    let a = 0.9 * t + 1.1 * (1.7 * t).sin() + 0.5 * (f1 * t).sin();
    let da = 0.9 + 1.1 * 1.7 * (1.7 * t).cos() + 0.5 * f1 * (f1 * t).cos();
    let b = 0.6 * (2.9 * t + 0.3).sin() + 0.35 * (f2 * t).sin();
    let db = 0.6 * 2.9 * (2.9 * t + 0.3).cos() + 0.35 * f2 * (f2 * t).cos();
    (a, da, b, db)
}

/// The true attitude `q(t) = R_z(α) ⊗ R_x(β)` (body → earth).
fn attitude(t: f64) -> Q {
    let (a, _, b, _) = angles(t);
    let qz = [(a / 2.0).cos(), 0.0, 0.0, (a / 2.0).sin()];
    let qx = [(b / 2.0).cos(), (b / 2.0).sin(), 0.0, 0.0];
    qmul(qz, qx)
}

/// Its body rate: `ω = R_x(β)ᵀ (0, 0, α̇) + (β̇, 0, 0) = (β̇, α̇ sin β, α̇ cos β)`.
fn body_rate(t: f64) -> [f64; 3] {
    let (_, da, b, db) = angles(t);
    [db, da * b.sin(), da * b.cos()]
}

/// The largest angle (rad) between the estimator's attitude change since its first sample and
/// the true one (from the 8th sample on), over `duration` s of samples at `h` s ± 25 % (non-repeating jitter; the ratio
/// of consecutive intervals stays within 0.6…1.67, inside the window's gap ratio 2, except at
/// `gap`, a sample index where one interval is 5 h long). Gyroscope delay 0 (the output is the
/// attitude of the samples' own time).
fn run<T: Real>(rule: RateRule, h: f64, duration: f64, gap: Option<usize>) -> f64 {
    run_in::<T>(Mode::Full, 0.25, rule, h, duration, gap)
}

/// [`run`] in `mode`, the intervals `h·(1 + jitter·u)` with `u` uniform in `[−1, 1)` (0: a
/// regular clock).
fn run_in<T: Real>(
    mode: Mode<f64>,
    jitter_amplitude: f64,
    rule: RateRule,
    h: f64,
    duration: f64,
    gap: Option<usize>,
) -> f64 {
    let p = Params {
        gyro_delay: 0.0,
        rate_rule: rule,
        mode,
        ..Params::default()
    };
    let mut f = Estimator::<T>::try_new(p.map(T::from_f64)).unwrap();
    let cast = |v: [f64; 3]| vec3::<T>(v);
    let mut jitter = Lcg(0x5eed_0027);
    let mut t = 0.3;
    let first = f
        .update_6d(cast(body_rate(t)), cast([0.0, 0.0, 9.81]), T::from_f64(h))
        .unwrap();
    assert!(first.initialized);
    // Compared from the 8th sample on: the first steps fall back to the linear interpolant
    // (local error of order 3), one-off errors that would hide the order of the rest.
    let (mut start, mut truth0) = (q64(f.attitude()), attitude(t));
    let mut worst: f64 = 0.0;
    let mut k = 0;
    while t < duration {
        let dt = if gap == Some(k) {
            5.0 * h
        } else {
            h * (1.0 + jitter_amplitude * jitter.next())
        };
        // The interval as the filter's type holds it: the true time advances by exactly that.
        let dt_t = T::from_f64(dt);
        t += dt_t.to_f64();
        let out = f
            .update_6d(cast(body_rate(t)), cast([0.0; 3]), dt_t)
            .unwrap();
        assert!(!out.at_rest && out.accel != gyrostat::estimation::SensorUse::Used);
        let est = qmul(qconj(start), q64(f.attitude()));
        let truth = qmul(qconj(truth0), attitude(t));
        worst = worst.max(quat_angle(est, truth));
        k += 1;
        if k == 8 {
            (start, truth0, worst) = (q64(f.attitude()), attitude(t), 0.0);
        }
    }
    worst
}

/// f64: Magnus-4 and CF4 converge with order 4 on jittered times (halving the step divides
/// the error by 12 or more, 16 in theory; measured 15.9: Magnus-4 1.15e-6 → 7.2e-8 rad from
/// 100 to 200 Hz), the trapezoid with order 2 (by 3.5 to 4.5; measured 3.9, 1.68e-3 →
/// 4.3e-4 rad); at 100 Hz the 4th-order rules are more than 100× closer to the closed form.
#[test]
fn fourth_order_on_jittered_rate_samples_f64() {
    let trap = [0.01, 0.005].map(|h| run::<f64>(RateRule::Trapezoid, h, 10.0, None));
    let ratio = trap[0] / trap[1];
    assert!((3.5..4.5).contains(&ratio), "trapezoid {trap:?}");
    for rule in [RateRule::Magnus4, RateRule::Cf4] {
        let e = [0.01, 0.005].map(|h| run::<f64>(rule, h, 10.0, None));
        let ratio = e[0] / e[1];
        assert!(ratio > 12.0, "{rule}: {e:?}, ratio {ratio}");
        assert!(e[0] < trap[0] / 100.0, "{rule}: {e:?} against {trap:?}");
    }
}

/// The light mode's rules, f64 and f32, on the same closed-form stream (corrections every
/// 25 ms find no usable accelerometer sample, so only the prediction moves the attitude), on
/// jittered times (the cached Magnus-4 weights recomputed at every sample) and on a regular
/// clock (computed once): Magnus-4 (the light mode's default, as the full mode's) converges
/// with order 4 (halving the step divides the error by 12 or more, 16 in theory), the
/// trapezoid with order 2 (by 3.5 to 4.5); Magnus-4 at 100 Hz more than 100× closer to the
/// closed form than the trapezoid; the f32 filter within 1e-5 rad of the closed form at 100 Hz
/// over 10 s (the f32 tolerance of the full mode's rule above). Measured: Magnus-4 1.06e-6 →
/// 6.6e-8 rad jittered (16.0), 1.15e-6 → 7.3e-8 regular (15.8) (with the Gauss nodes' rates
/// in the commutator, as the full mode: 1.15e-6 → 7.2e-8 and 1.23e-6 → 7.8e-8); the
/// trapezoid 1.68e-3 → 4.3e-4 (3.9); f32 3.3e-6 and 2.0e-6 rad.
#[test]
fn light_mode_rule_orders() {
    assert_eq!(Params::<f64>::light().rate_rule, RateRule::Magnus4);
    for jitter in [0.25, 0.0] {
        let light = |rule, h| run_in::<f64>(Mode::light(), jitter, rule, h, 10.0, None);
        let trap = [0.01, 0.005].map(|h| light(RateRule::Trapezoid, h));
        let ratio = trap[0] / trap[1];
        assert!((3.5..4.5).contains(&ratio), "jitter {jitter}: {trap:?}");
        let e = [0.01, 0.005].map(|h| light(RateRule::Magnus4, h));
        let ratio = e[0] / e[1];
        assert!(ratio > 12.0, "jitter {jitter}: {e:?}, ratio {ratio}");
        assert!(
            e[0] < trap[0] / 100.0,
            "jitter {jitter}: {e:?} against {trap:?}"
        );
        let e32 = run_in::<f32>(Mode::light(), jitter, RateRule::Magnus4, 0.01, 10.0, None);
        assert!(e32 < 1e-5, "jitter {jitter}: f32 {e32}");
    }
    // The window restarts over a gap in the light mode too (then four samples again).
    let gap = run_in::<f64>(
        Mode::light(),
        0.25,
        RateRule::Magnus4,
        0.01,
        10.0,
        Some(400),
    );
    let trap = run_in::<f64>(
        Mode::light(),
        0.25,
        RateRule::Trapezoid,
        0.01,
        10.0,
        Some(400),
    );
    assert!(gap < trap, "{gap} against {trap}");
}

/// A gap (one interval of 5 h, past the window's ratio 2) restarts the window: the step over
/// it and the next two take the linear interpolant (the trapezoid's order), then four. The
/// gap's own step then dominates the error (its local error grows as the step cubed), and the
/// 4th-order rules still end below the trapezoid over the whole run (measured at 100 Hz with
/// the gap at sample 400: 1.16e-3 rad, without it 1.15e-6, the trapezoid 2.26e-3).
#[test]
fn fourth_order_falls_back_over_a_gap() {
    let trap = run::<f64>(RateRule::Trapezoid, 0.01, 10.0, Some(400));
    for rule in [RateRule::Magnus4, RateRule::Cf4] {
        let e = run::<f64>(rule, 0.01, 10.0, Some(400));
        let clean = run::<f64>(rule, 0.01, 10.0, None);
        assert!(e < trap, "{rule}: {e} against {trap}");
        assert!(
            e > 100.0 * clean,
            "{rule}: {e} against {clean} without the gap"
        );
    }
}

/// f32: the same stream, tolerance per type: the 4th-order rules stay within 1e-5 rad of the
/// closed form at 100 Hz over 10 s (measured 2.2e-6 Magnus-4, 3.0e-6 CF4: the f32 rounding of
/// about 1000 updates over the f64 rules' 1.2e-6), the trapezoid 1.68e-3 rad off (its
/// truncation, within 1 % of f64's).
#[test]
fn fourth_order_on_jittered_rate_samples_f32() {
    let trap = run::<f32>(RateRule::Trapezoid, 0.01, 10.0, None);
    let trap64 = run::<f64>(RateRule::Trapezoid, 0.01, 10.0, None);
    assert!((trap - trap64).abs() < 0.01 * trap64, "{trap} {trap64}");
    for rule in [RateRule::Magnus4, RateRule::Cf4] {
        let e = run::<f32>(rule, 0.01, 10.0, None);
        assert!(e < 1e-5, "{rule}: {e}");
        assert!(e < trap / 100.0, "{rule}: {e} against {trap}");
    }
}

/// The names of the rules, as the tools and Python spell them (the 4th-order ones are the
/// propagation module's `RateMethod` names).
#[test]
fn rate_rule_names() {
    for (rule, name) in [
        (RateRule::Trapezoid, "trapezoid"),
        (RateRule::Magnus4, "magnus4"),
        (RateRule::Cf4, "cf4"),
    ] {
        assert_eq!(rule.name(), name);
        assert_eq!(rule.to_string(), name);
        assert_eq!(name.parse::<RateRule>(), Ok(rule));
    }
    for bad in ["", "rk4", "Magnus4", "trapezoid "] {
        assert_eq!(
            bad.parse::<RateRule>(),
            Err(Error::InvalidArgument),
            "{bad:?}"
        );
    }
    assert_eq!(Params::<f64>::default().rate_rule, RateRule::default());
}

/// The estimator's attitude change over `duration` s of the closed-form motion at `h` s ±25 %,
/// the rates and intervals rounded to f32 (so that the f32 and f64 filters see the same numbers),
/// accelerometer unusable after the first sample: `(plain f32, compensated f32, f64)`.
fn long_run(rule: RateRule, h: f64, duration: f64) -> (Q, Q, Q) {
    let p = Params {
        gyro_delay: 0.0,
        rate_rule: rule,
        ..Params::default()
    };
    let p32 = p.map(|x| x as f32);
    let mut plain = Estimator::<f32>::try_new(p32).unwrap();
    let mut comp = Estimator::<f32, _>::try_new_compensated(p32).unwrap();
    let mut wide = Estimator::<f64>::try_new(p).unwrap();
    let mut jitter = Lcg(0x1a7e_0027);
    let mut t = 0.0f64;
    let mut k = 0u64;
    while t < duration {
        let dt = (h * (1.0 + 0.25 * jitter.next())) as f32;
        let w = body_rate(t).map(|c| c as f32);
        let a = if k == 0 { [0.0, 0.0, 9.81] } else { [0.0; 3] };
        let (w32, a32) = (gyrostat::Vec3::from_array(w), vec3::<f32>(a));
        plain.update_6d(w32, a32, dt).unwrap();
        comp.update_6d(w32, a32, dt).unwrap();
        wide.update_6d(vec3(w.map(f64::from)), vec3(a), f64::from(dt))
            .unwrap();
        t += f64::from(dt);
        k += 1;
    }
    (
        q64(plain.attitude()),
        q64(comp.attitude()),
        q64(wide.attitude()),
    )
}

/// The compensated strapdown attitude (`Estimator::try_new_compensated`): 10 minutes of the
/// non-repeating motion at 200 Hz ± 25 % without corrections (1.2·10⁵ predictions), the f32
/// filter against the f64 one fed the same numbers. Tolerances: the compensated f32 within
/// 2e-7 rad of f64 with the trapezoid (twice the f32 floor, 1.03e-7 rad: one rounding of a
/// unit quaternion's components; measured 6.5e-8), within 1e-6 rad with Magnus-4 and CF4
/// (measured 1.5e-7 and 4.0e-7: the f32 rounding of the Gauss-node interpolation, which the
/// compensated attitude takes as exact); the plain f32 measurably off with every rule (more
/// than 2e-6 rad; measured 1.4e-5, 4.1e-6, 2.6e-5). What is left grows as a random walk of
/// the rotation vector's own f32 rounding (about 1e-9 rad per step: the trapezoid's
/// compensated error is 5.9e-7 after 30 minutes), which no carried attitude removes.
#[test]
fn compensated_f32_follows_f64() {
    for (rule, tol) in [
        (RateRule::Trapezoid, 2e-7),
        (RateRule::Magnus4, 1e-6),
        (RateRule::Cf4, 1e-6),
    ] {
        let (plain, comp, wide) = long_run(rule, 0.005, 600.0);
        let (e_plain, e_comp) = (quat_angle(plain, wide), quat_angle(comp, wide));
        assert!(e_comp < tol, "{rule}: compensated {e_comp:e}");
        assert!(e_plain > 2e-6, "{rule}: plain {e_plain:e}");
    }
}

/// `max | |q| − 1 |` of the light mode's attitude over `n` samples of the closed-form stream at
/// 100 Hz ± 25 % without corrections (a correction period longer than the run) and without the
/// output lead (`gyro_delay` 0: the attitude is the strapdown product as it is), so that only
/// the predictions' renormalisation keeps `|q|` at 1. `compensated`: the strapdown attitude
/// carried compensated ([`Estimator::try_new_compensated`]).
fn light_norm_drift<T: Real>(n: usize, compensated: bool) -> f64 {
    let p = Params {
        gyro_delay: 0.0,
        mode: Mode::Light {
            correction_period: 1e9,
        },
        ..Params::default()
    };
    let p = p.map(T::from_f64);
    if compensated {
        let f = Estimator::<T, _>::try_new_compensated(p).unwrap();
        drift_over(f, n)
    } else {
        drift_over(Estimator::<T>::try_new(p).unwrap(), n)
    }
}

/// [`light_norm_drift`] on the estimator `f`.
fn drift_over<T: Real, A: gyrostat::propagation::PropagatedAttitude<T>>(
    mut f: Estimator<T, A>,
    n: usize,
) -> f64 {
    let mut jitter = Lcg(0x5eed_0028);
    let mut t = 0.3;
    f.update_6d(
        vec3(body_rate(t)),
        vec3([0.0, 0.0, 9.81]),
        T::from_f64(0.01),
    )
    .unwrap();
    let mut worst: f64 = 0.0;
    for _ in 0..n {
        let dt = T::from_f64(0.01 * (1.0 + 0.25 * jitter.next()));
        t += dt.to_f64();
        f.update_6d(vec3(body_rate(t)), vec3([0.0; 3]), dt).unwrap();
        let q = q64(f.attitude());
        let norm = q.iter().map(|c| c * c).sum::<f64>().sqrt();
        worst = worst.max((norm - 1.0).abs());
    }
    worst
}

/// The light mode renormalises its strapdown attitude every 8th prediction only: between two,
/// `|q|` drifts by the rounding of at most seven products, and it does not accumulate over a
/// long run without corrections (200 000 samples, 33 min at 100 Hz): within 16 ulp of 1 in f32
/// (2e-6), 8 ulp in f64 (2e-15), the strapdown attitude plain or compensated. Measured (plain):
/// f32 3.9e-7, f64 8.9e-16 (compensated 1.3e-7, 3.3e-16); the same run without any
/// renormalisation drifts to 8.5e-6 in f32.
#[test]
fn light_mode_attitude_stays_unit() {
    for compensated in [false, true] {
        let d32 = light_norm_drift::<f32>(200_000, compensated);
        assert!(d32 < 2e-6, "f32 (compensated {compensated}): {d32:e}");
        let d64 = light_norm_drift::<f64>(200_000, compensated);
        assert!(d64 < 2e-15, "f64 (compensated {compensated}): {d64:e}");
    }
}

/// The light mode skips the per-sample test of the shared step limit for a step length over
/// which no clipped rate can exceed it (`3·(range·Δt)² ≤ π²`), and keeps it for longer steps:
/// at 2000 °/s (34.9 rad/s) the limit is reached at `Δt` = 52 ms. At 50 ms the largest rate
/// (clipped) is accepted; at 60 ms a slow rate is, and the largest one is `StepTooLong` (the
/// state unchanged: the next slow sample is accepted again), also after a run of 60 ms steps
/// with slow rates.
#[test]
fn light_mode_step_limit() {
    let p = Params::<f64> {
        mode: Mode::light(),
        ..Params::default()
    };
    let fast = vec3::<f64>([40.0, -40.0, 40.0]);
    let slow = vec3::<f64>([0.3, -0.2, 0.1]);
    let accel = vec3::<f64>([0.0, 0.0, 9.81]);
    let mut f = Estimator::<f64>::try_new(p).unwrap();
    f.update_6d(slow, accel, 0.05).unwrap();
    for _ in 0..10 {
        assert!(f.update_6d(fast, accel, 0.05).is_ok());
    }
    let mut f = Estimator::<f64>::try_new(p).unwrap();
    f.update_6d(slow, accel, 0.06).unwrap();
    for _ in 0..10 {
        assert!(f.update_6d(slow, accel, 0.06).is_ok());
        assert_eq!(f.update_6d(fast, accel, 0.06), Err(Error::StepTooLong));
    }
    // A safe step length first, then a longer one: the test is back.
    let mut f = Estimator::<f64>::try_new(p).unwrap();
    f.update_6d(slow, accel, 0.05).unwrap();
    f.update_6d(fast, accel, 0.05).unwrap();
    assert_eq!(f.update_6d(fast, accel, 0.06), Err(Error::StepTooLong));
}
