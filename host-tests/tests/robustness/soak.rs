//! The soak: long f32 runs of the hot paths, watching the invariants.
//!
//! - **Propagation**: `coning2_update` (the complete 2-sample gyro update with fast
//!   renormalisation, the firmware hot path) on classical coning motion, half-cone angle
//!   0.01 rad at 1 Hz, 1 kHz gyro increments computed exactly in f64 and rounded to f32: the
//!   largest `||q| − 1|` over every update, and the attitude error against the closed form at
//!   each decade.
//! - **Dynamics**: `Gyrostat::step` with the Strang and Yoshida4 splittings, the seed's body
//!   (6, 4, 3) tumbling near its intermediate axis, `dt = 0.01 s`: the largest `||q| − 1|`,
//!   relative `|J|` drift, relative energy error and lab-momentum drift over every step.
//!
//! `cargo test --release -p host-tests --test robustness soak:: -- --nocapture` runs the shortened setting
//! (10⁶ updates, 10⁵ steps per method, as in CI); `GYROSTAT_SOAK=full` runs the full one
//! (10⁸ updates, 10⁷ steps per method), whose numbers BENCHMARKS.md ("Soak") quotes.

use gyrostat::dynamics::{Gyrostat, Inertia, Integrator};
use gyrostat::propagation::kernels::coning2_update;
use gyrostat::{UnitQuat, Vec3};
use host_tests::ref_propagation::Coning;
use host_tests::reference::{qrotate, quat_angle};

/// `(propagation updates, splitting steps per method)`.
fn lengths() -> (u64, u64) {
    if std::env::var("GYROSTAT_SOAK").as_deref() == Ok("full") {
        (100_000_000, 10_000_000)
    } else {
        (1_000_000, 100_000)
    }
}

/// `||q| − 1|` in f64 from the f32 components (exact squares).
fn norm_error(q: UnitQuat<f32>) -> f64 {
    let n2: f64 = q.to_array().iter().map(|c| f64::from(*c).powi(2)).sum();
    (n2.sqrt() - 1.0).abs()
}

#[test]
fn coning2_update_soak_f32() {
    let (updates, _) = lengths();
    let c = Coning {
        alpha: 0.01,
        omega_c: 2.0 * std::f64::consts::PI,
    };
    let h = 1e-3;
    let q0 = c.attitude(0.0);
    let mut q = UnitQuat::try_new(gyrostat::Quat::from_array(q0.map(|x| x as f32))).unwrap();
    let inc = |k: u64| {
        let a = c.increment(k as f64 * h, (k + 1) as f64 * h);
        Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32)
    };
    let mut worst_norm: f64 = 0.0;
    let mut log = Vec::new();
    let mut next_log = 1_000u64;
    let start = std::time::Instant::now();
    for u in 1..=updates {
        let k = 2 * (u - 1);
        q = coning2_update(q, inc(k), inc(k + 1));
        worst_norm = worst_norm.max(norm_error(q));
        if u == next_log || u == updates {
            let t = (2 * u) as f64 * h;
            let e = quat_angle(c.attitude(t), q.to_array().map(f64::from));
            log.push((u, e));
            next_log *= 10;
        }
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "soak coning2_update f32: {updates} updates ({} increments, {:.0} s simulated) in {secs:.1} s",
        2 * updates,
        2.0 * updates as f64 * h
    );
    println!("  max ||q| - 1| = {worst_norm:.2e}");
    for (u, e) in &log {
        println!("  after {u:>10} updates: attitude error {e:.2e} rad");
    }
    // The fast renormalisation removes each update's drift to second order: |q| stays within
    // a few ulp of 1 (f32 ulp at 1: 6e-8 below, 1.2e-7 above), whatever the run length.
    assert!(worst_norm < 4.0 * f64::from(f32::EPSILON), "{worst_norm}");
    // The attitude error grows from the rounding of each update (see propagation/long_run.rs:
    // worst case 1.2e-7 rad per update if every rounding had the same sign).
    let (_, last) = log[log.len() - 1];
    assert!(last < 1.2e-7 * updates as f64, "{last}");
}

#[test]
fn splitting_soak_f32() {
    let (_, steps) = lengths();
    let inertia = Inertia::try_from_principal(Vec3::new(6.0f32, 4.0, 3.0)).unwrap();
    let body = Gyrostat::rigid(inertia);
    let dt = 0.01f32;
    for integ in [Integrator::Strang, Integrator::Yoshida4] {
        let mut s = body
            .try_state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.05, 1.0, 0.01), [])
            .unwrap();
        let j0 = s.momentum.to_array().map(f64::from);
        let n0 = (j0[0] * j0[0] + j0[1] * j0[1] + j0[2] * j0[2]).sqrt();
        let e0 = f64::from(body.energy(&s));
        let l0 = qrotate(s.attitude.to_array().map(f64::from), j0);
        let (mut dq, mut dj, mut de, mut dl) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let start = std::time::Instant::now();
        for _ in 0..steps {
            s = body.step(integ, &s, dt).unwrap();
            let j = s.momentum.to_array().map(f64::from);
            let n = (j[0] * j[0] + j[1] * j[1] + j[2] * j[2]).sqrt();
            // The energy from the f32 state, evaluated in f64 (the model's ½ Σ J²/I).
            let e = 0.5 * (j[0] * j[0] / 6.0 + j[1] * j[1] / 4.0 + j[2] * j[2] / 3.0);
            let l = qrotate(s.attitude.to_array().map(f64::from), j);
            dq = dq.max(norm_error(s.attitude));
            dj = dj.max((n - n0).abs() / n0);
            de = de.max((e - e0).abs() / e0);
            let d = [l[0] - l0[0], l[1] - l0[1], l[2] - l0[2]];
            dl = dl.max((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() / n0);
        }
        let secs = start.elapsed().as_secs_f64();
        println!(
            "soak {integ:?} f32: {steps} steps ({:.0} s simulated) in {secs:.1} s",
            steps as f64 * f64::from(dt)
        );
        println!(
            "  max ||q| - 1| = {dq:.2e}, max |d|J||/|J| = {dj:.2e}, max |dE|/E = {de:.2e}, max |dL|/|J| = {dl:.2e}"
        );
        // Every step renormalises the attitude exactly: a few ulp.
        assert!(dq < 4.0 * f64::from(f32::EPSILON), "{dq}");
        // |J|: each sub-step is an exact rotation, its rounding an unbiased random walk of a
        // few ε per step: √steps·ε-scale growth (measured: see BENCHMARKS.md "Soak").
        let walk = 16.0 * f64::from(f32::EPSILON) * (steps as f64).sqrt();
        assert!(dj < walk, "{dj} vs {walk}");
        // The energy error of a symplectic splitting stays bounded (its size is the method's
        // truncation at dt = 0.01, about 1e-5 for Strang), plus the same rounding walk.
        assert!(de < 1e-4 + walk, "{de}");
        let _ = e0;
    }
}
