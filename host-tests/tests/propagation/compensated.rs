//! The compensated attitude (`CompensatedAttitude`) over one hour at 1 kHz (3.6·10⁶ updates), for
//! every increment rule and rate method, in f32: steady rotation (exact answer known) and
//! coning motion (closed form in `ref_propagation`, rates up to 0.9 rad/s, the attitude passing
//! through the same values every period, where rounding errors pile up most).
//!
//! The target is the error the f32 arithmetic adds: at most 1.7e-4 rad (0.01°/h, the drift of a
//! navigation-grade gyro) after the hour. For steady motion every rule's rotation vector is
//! exact, so the error against the exact attitude is the arithmetic's. For coning motion the
//! rules also have their own (coning) truncation error, the same in any precision; the
//! arithmetic's share is the distance to the same rule run in f64 on the same f32 inputs, which
//! is what is asserted (the distance to the closed form is printed beside it). The inputs are
//! rounded to f32 before either run, so the exact answer is the one for the rounded inputs.
//!
//! A second, much tighter bound holds for the increment rules and the Magnus-4 and CF4 rate
//! methods: the f32 floor [`F32_FLOOR`], the turn of a unit quaternion by rounding its
//! components to f32 once. An f32 attitude cannot be reported closer than that; the compensated
//! one ends within it after the hour.

use gyrostat::propagation::{
    CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization, PropagatedAttitude,
    RateIntegrator, RateMethod,
};
use gyrostat::{Real, UnitQuat, Vec3};
use host_tests::ref_propagation::Coning;
use host_tests::reference::{F32_FLOOR, Q, quat_angle, quat_exp};

/// Updates in one hour at 1 kHz.
const N: usize = 3_600_000;
/// The sample interval, s.
const DT: f64 = 1e-3;
/// The target: 0.01°/h.
const TARGET: f64 = 1.7e-4;

/// Steady body rates, rad/s: the case, the same direction at 0.11 rad/s, a single axis.
const STEADY: [[f64; 3]; 3] = [[0.5, -0.8, 0.6], [0.05, -0.08, 0.06], [0.0, 0.0, 0.1]];

/// Coning with half-cone angle 0.6 rad at 1.5 rad/s: body rate 0.89 rad/s.
const CONING: Coning = Coning {
    alpha: 0.6,
    omega_c: 1.5,
};

fn q64<T: Real>(q: UnitQuat<T>) -> Q {
    q.to_array().map(|c| c.to_f64())
}

fn v32(v: [f64; 3]) -> Vec3<f32> {
    Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

fn widen(v: Vec3<f32>) -> Vec3<f64> {
    Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}
/// Runs `n` increments from `inc(k)` through an increment integrator carrying `A`, returns the
/// final attitude.
fn run_increments<T: Real, A: PropagatedAttitude<T>>(
    q0: A,
    rule: ConingRule,
    norm: Normalization,
    n: usize,
    inc: &(dyn Fn(usize) -> Vec3<T> + Sync),
) -> Q {
    let mut integ = IncrementIntegrator::new(q0, rule, norm);
    for k in 0..n {
        integ.push(inc(k)).unwrap();
    }
    q64(integ.flush())
}

/// Every rule, steady rates, one hour in f32: compensated within the f32 floor (1.03e-7 rad) of
/// the exact attitude `exp(N·θ)` (measured ≤ 6.3e-8; the plain f32 path, printed beside it,
/// 1.7e-6…2.4e-2).
#[test]
fn compensated_increments_steady_one_hour() {
    for w in STEADY {
        let theta = v32(w.map(|c| c * DT));
        let exact = quat_exp(widen(theta).scale(N as f64).to_array());
        std::thread::scope(|scope| {
            let runs: Vec<_> = ConingRule::ALL
                .iter()
                .map(|&rule| {
                    scope.spawn(move || {
                        let inc = move |_| theta;
                        let norm = Normalization::Exact;
                        let q0 = UnitQuat::IDENTITY;
                        let comp =
                            run_increments(CompensatedAttitude::new(q0), rule, norm, N, &inc);
                        let plain = run_increments(q0, rule, norm, N, &inc);
                        (rule, quat_angle(exact, comp), quat_angle(exact, plain))
                    })
                })
                .collect();
            for run in runs {
                let (rule, comp, plain) = run.join().unwrap();
                println!("steady {w:?} {rule:?}: compensated {comp:.2e} rad, plain {plain:.2e}");
                assert!(comp <= F32_FLOOR, "{w:?} {rule:?}: {comp:.2e}");
            }
        });
    }
}

/// Every rule, coning motion, one hour in f32: the compensated f32 run within the f32 floor
/// (1.03e-7 rad) of the same rule in f64 on the same f32 increments and the same f32-rounded
/// start, with both normalisation policies (measured ≤ 2.4e-8; plain f32 up to 1.1e-4). The
/// attitude passes through the same values every period here, so an increment rounded as a
/// function of the attitude piles up: with the increment's product `q ⊗ exp(φ) − q` rounded
/// instead of carried, this was 2.6e-6.
#[test]
fn compensated_increments_coning_one_hour() {
    let incs: Vec<Vec3<f32>> = (0..N)
        .map(|k| v32(CONING.increment(k as f64 * DT, (k + 1) as f64 * DT)))
        .collect();
    let truth = CONING.attitude(N as f64 * DT);
    let q0_64 = CONING.attitude(0.0);
    let q0 = UnitQuat::try_new(gyrostat::Quat::from_array(q0_64.map(|c| c as f32))).unwrap();
    let q0_wide = UnitQuat::new_unchecked(gyrostat::Quat::from_array(q64(q0)));
    std::thread::scope(|scope| {
        let incs = &incs;
        let runs: Vec<_> = ConingRule::ALL
            .iter()
            .flat_map(|&rule| [(rule, Normalization::Exact), (rule, Normalization::Fast)])
            .map(|(rule, norm)| {
                scope.spawn(move || {
                    let inc32 = |k: usize| incs[k];
                    let inc64 = |k: usize| widen(incs[k]);
                    let comp = run_increments(CompensatedAttitude::new(q0), rule, norm, N, &inc32);
                    let plain = run_increments(q0, rule, norm, N, &inc32);
                    let f64_run = run_increments(q0_wide, rule, norm, N, &inc64);
                    (rule, norm, comp, plain, f64_run)
                })
            })
            .collect();
        for run in runs {
            let (rule, norm, comp, plain, f64_run) = run.join().unwrap();
            let e = quat_angle(f64_run, comp);
            println!(
                "coning {rule:?} {norm:?}: compensated f32 − f64 {e:.2e} rad, plain f32 − f64 {:.2e}; \
                 f64 rule − closed form {:.2e}",
                quat_angle(f64_run, plain),
                quat_angle(truth, f64_run)
            );
            assert!(e <= F32_FLOOR, "{rule:?} {norm:?}: {e:.2e}");
        }
    });
}

/// Runs the rate samples `rate(k)`, `k = 0..=n`, through a rate integrator carrying `A`, step
/// `dt` with remainder `dt_lo`; returns the attitude at the last sample.
fn run_rates<T: Real, A: PropagatedAttitude<T>>(
    q0: A,
    method: RateMethod,
    dt: T,
    dt_lo: T,
    n: usize,
    rate: &(dyn Fn(usize) -> Vec3<T> + Sync),
) -> Q {
    let mut integ = RateIntegrator::try_new(q0, method, Normalization::Exact, dt)
        .unwrap()
        .try_with_step_remainder(dt_lo)
        .unwrap();
    for k in 0..=n {
        integ.push(rate(k)).unwrap();
    }
    q64(integ.attitude())
}

/// Every rate method, one hour at 1 kHz in f32, the step given as f32 `dt` plus its remainder:
/// steady rates within 1.7e-4 rad of `exp(ω t)` (ω the f32 samples, t = 3600 s exactly) and
/// coning within 1.7e-4 rad of the same method in f64 (`dt = 10⁻³` in f64) on the same f32
/// samples (measured ≤ 1.1e-5, RK4; plain f32 up to 6.8e-2). Magnus-4 and CF4, which update
/// through the compensated exponential, end within the f32 floor (measured ≤ 5.9e-8); RK4 adds
/// its slope sum, rounded, to the attitude.
#[test]
fn compensated_rates_one_hour() {
    let dt = DT as f32;
    let dt_lo = (DT - f64::from(dt)) as f32;
    let coning: Vec<Vec3<f32>> = (0..=N)
        .map(|k| v32(CONING.body_rate(k as f64 * DT)))
        .collect();
    std::thread::scope(|scope| {
        let coning = &coning;
        let mut runs = Vec::new();
        for method in [RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4] {
            for w in STEADY {
                runs.push(scope.spawn(move || {
                    let omega = v32(w);
                    let exact = quat_exp(widen(omega).scale(N as f64 * DT).to_array());
                    let rate = move |_| omega;
                    let q0 = UnitQuat::IDENTITY;
                    let comp = run_rates(CompensatedAttitude::new(q0), method, dt, dt_lo, N, &rate);
                    let plain = run_rates(q0, method, dt, 0.0, N, &rate);
                    (
                        format!("steady {w:?} {method:?}"),
                        quat_angle(exact, comp),
                        quat_angle(exact, plain),
                    )
                }));
            }
            runs.push(scope.spawn(move || {
                let q0 = UnitQuat::IDENTITY;
                let rate32 = |k: usize| coning[k];
                let rate64 = |k: usize| widen(coning[k]);
                let comp = run_rates(CompensatedAttitude::new(q0), method, dt, dt_lo, N, &rate32);
                let plain = run_rates(q0, method, dt, 0.0, N, &rate32);
                let f64_run = run_rates(UnitQuat::<f64>::IDENTITY, method, DT, 0.0, N, &rate64);
                (
                    format!("coning {method:?} (against f64)"),
                    quat_angle(f64_run, comp),
                    quat_angle(f64_run, plain),
                )
            }));
        }
        for run in runs {
            let (name, comp, plain) = run.join().unwrap();
            println!("{name}: compensated {comp:.2e} rad, plain {plain:.2e}");
            assert!(comp <= TARGET, "{name}: {comp:.2e}");
            if !name.contains("Rk4") {
                assert!(comp <= F32_FLOOR, "{name}: {comp:.2e}");
            }
        }
    });
}

/// The compensated attitude works the same way in f64: 10⁵ steady updates of each rule end
/// within 1e-14 rad of the exact attitude (the plain f64 path: a few 1e-14).
#[test]
fn compensated_increments_in_f64() {
    let theta = Vec3::new(5e-4, -8e-4, 6e-4);
    let n = 100_000;
    let exact = quat_exp(theta.scale(n as f64).to_array());
    for rule in ConingRule::ALL {
        let inc = move |_| theta;
        let q0 = UnitQuat::<f64>::IDENTITY;
        let comp = run_increments(
            CompensatedAttitude::new(q0),
            rule,
            Normalization::Fast,
            n,
            &inc,
        );
        let plain = run_increments(q0, rule, Normalization::Fast, n, &inc);
        let (e, p) = (quat_angle(exact, comp), quat_angle(exact, plain));
        println!("f64 {rule:?}: compensated {e:.1e}, plain {p:.1e}");
        assert!(e <= 1e-14, "{rule:?}: {e:.1e}");
    }
}
