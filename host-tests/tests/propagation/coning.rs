//! Coning drift of the gyro-increment rules against the closed-form coning motion.
//!
//! The body turns by the fixed half-cone angle α about an axis rotating at Ω
//! (`host_tests::ref_propagation::Coning`); the exact increments feed each rule, and the
//! attitude error `q_true* ⊗ q_est` is sampled at every cone period. Its component along the
//! cone axis (body z) grows linearly: the fitted slope is the drift rate, compared with the
//! published leading term within 5%.
//!
//! All drift tests run in f64, because the drifts are tiny by design (down to ~1e-9 rad/s for
//! the 3-sample rule): f32 rounding of the attitude (≈ 6e-8 per update, thousands of updates)
//! would swamp them, while f64 rounding (≈ 1e-16 per update) stays six orders below.
//! The half-cone angle is small (α = 0.02–0.05) so that the `O(α⁴)` terms are below 0.3% of
//! the `α²` leading term, and Ωh (or ΩT) small enough that the next term in the expansion in
//! Ωh stays below ~2%; both are stated per test.

use gyrostat::propagation::kernels::coning2_update;
use gyrostat::propagation::{ConingAccumulator, ConingRule, IncrementIntegrator, Normalization};
use gyrostat::{Quat, UnitQuat, Vec3};
use host_tests::cast::{q64, unit_quat, vec3};
use host_tests::ref_propagation::{Coning, body_error, fit_slope};
use host_tests::reference::quat_angle;

fn start(c: &Coning) -> UnitQuat<f64> {
    let a = c.attitude(0.0);
    UnitQuat::try_new(Quat::new(a[0], a[1], a[2], a[3])).unwrap()
}

/// Runs `rule` on `per_cycle` increments per cone period for `cycles` periods; returns the
/// fitted drift rate (rad/s) of the body-z error.
fn measure(c: &Coning, rule: ConingRule, per_cycle: usize, cycles: usize) -> f64 {
    let period = 2.0 * std::f64::consts::PI / c.omega_c;
    let h = period / per_cycle as f64;
    let mut integ = IncrementIntegrator::new(start(c), rule, Normalization::Exact);
    let (mut ts, mut ys) = (vec![0.0], vec![0.0]);
    for cyc in 0..cycles {
        for i in 0..per_cycle {
            let k = (cyc * per_cycle + i) as f64;
            integ.push(vec3(c.increment(k * h, (k + 1.0) * h))).unwrap();
        }
        assert_eq!(
            integ.pending(),
            0,
            "per_cycle must be a multiple of the group size"
        );
        let t = (cyc + 1) as f64 * period;
        ts.push(t);
        ys.push(body_error(c.attitude(t), q64(integ.attitude()))[2]);
    }
    fit_slope(&ts, &ys)
}

/// Compares a measured drift with the theoretical magnitude (5%). The sign is checked too: every
/// rule under-compensates the coning term (positive along body z in this motion), so the error
/// has the sign of the true axial rate `−Ω(1 − cos α)`: negative.
fn check(name: &str, measured: f64, theory: f64) {
    let rel = (measured.abs() - theory).abs() / theory;
    println!(
        "{name}: measured drift {measured:.6e} rad/s, theory {theory:.6e}, rel. diff {rel:.2e}"
    );
    assert!(
        measured < 0.0,
        "{name}: drift has the wrong sign: {measured:e}"
    );
    assert!(
        rel < 0.05,
        "{name}: measured {measured:e} vs theory {theory:e}"
    );
}

#[test]
fn exp_per_increment_drift_is_alpha2_omega_omegah2_over_12() {
    // α = 0.02, Ωh = 2π/60 ≈ 0.105: the next term of ½(1 − sin x / x) is x²/20 ≈ 0.05% relative.
    let c = Coning {
        alpha: 0.02,
        omega_c: 2.0 * std::f64::consts::PI,
    };
    let per = 60;
    let x = c.omega_c * (2.0 * std::f64::consts::PI / c.omega_c) / per as f64;
    let d = measure(&c, ConingRule::Exp, per, 50);
    check("exp", d, c.alpha.powi(2) * c.omega_c * x.powi(2) / 12.0);
}

#[test]
fn one_plus_previous_drift_is_alpha2_omega_omegah4_over_60() {
    // Ωh = 2π/48 ≈ 0.131.
    let c = Coning {
        alpha: 0.05,
        omega_c: 2.0 * std::f64::consts::PI,
    };
    let per = 48;
    let x = 2.0 * std::f64::consts::PI / per as f64;
    let d = measure(&c, ConingRule::OnePlusPrevious, per, 100);
    check(
        "one+previous",
        d,
        c.alpha.powi(2) * c.omega_c * x.powi(4) / 60.0,
    );
}

#[test]
fn two_sample_drift_is_alpha2_omega_omegat4_over_960() {
    // ΩT = 2·2π/48 ≈ 0.262.
    let c = Coning {
        alpha: 0.05,
        omega_c: 2.0 * std::f64::consts::PI,
    };
    let per = 48;
    let x = 2.0 * 2.0 * std::f64::consts::PI / per as f64;
    let d = measure(&c, ConingRule::TwoSample, per, 100);
    check(
        "2-sample",
        d,
        c.alpha.powi(2) * c.omega_c * x.powi(4) / 960.0,
    );
}

#[test]
fn three_sample_drift_is_alpha2_omega_omegat6_over_204120() {
    // ΩT = 3·2π/36 ≈ 0.524.
    let c = Coning {
        alpha: 0.05,
        omega_c: 2.0 * std::f64::consts::PI,
    };
    let per = 36;
    let x = 3.0 * 2.0 * std::f64::consts::PI / per as f64;
    let d = measure(&c, ConingRule::ThreeSample, per, 200);
    check(
        "3-sample",
        d,
        c.alpha.powi(2) * c.omega_c * x.powi(6) / 204120.0,
    );
}

#[test]
fn four_sample_is_measurably_better_than_three_sample() {
    // The 4-sample residual is α²Ω(ΩT)⁸/82575360 (series of the rule minus the exact coning
    // term for pure coning: −x⁹/315 per update with x = Ωh, i.e. α²Ω x⁸/1260 per unit time).
    // It is so small that the O(α⁴) terms every rule neglects (the rules are derived to O(α²))
    // dominate it unless α is tiny: at α = 0.05 they are 100× larger. With α = 0.001 and
    // Ωh = 2π/24 the α² term dominates both rules; measured ratio ≈ 64.
    let c = Coning {
        alpha: 0.001,
        omega_c: 2.0 * std::f64::consts::PI,
    };
    let per = 24;
    let x = 2.0 * std::f64::consts::PI / per as f64;
    let d3 = measure(&c, ConingRule::ThreeSample, per, 100);
    let d4 = measure(&c, ConingRule::FourSample, per, 100);
    println!("same sample interval h = period/24: 3-sample {d3:e}, 4-sample {d4:e} rad/s");
    check(
        "3-sample (α = 0.001)",
        d3,
        c.alpha.powi(2) * c.omega_c * (3.0 * x).powi(6) / 204120.0,
    );
    check(
        "4-sample (α = 0.001)",
        d4,
        c.alpha.powi(2) * c.omega_c * (4.0 * x).powi(8) / 82_575_360.0,
    );
    assert!(d4.abs() * 20.0 < d3.abs());
}

/// The two-speed form (8 increments per attitude update) keeps the one-plus-previous drift at
/// the SAMPLE interval: α²Ω(Ωh)⁴/60, not a drift set by the update interval.
#[test]
fn two_speed_accumulator_drift_is_one_plus_previous_at_sample_rate() {
    // α = 0.01: the O(α⁴) terms the rule neglects (Bortz terms beyond ½ α × ω, which grow with
    // the update interval, here ΩT ≈ 1.05) add a relative ≈ 70 α²: 18% at α = 0.05 (measured),
    // 0.9% at α = 0.01.
    let c = Coning {
        alpha: 0.01,
        omega_c: 2.0 * std::f64::consts::PI,
    };
    let per = 48;
    let per_update = 8;
    let period = 1.0;
    let h = period / per as f64;
    let x = c.omega_c * h;
    let mut q = start(&c);
    let mut acc = ConingAccumulator::new();
    let (mut ts, mut ys) = (vec![0.0], vec![0.0]);
    for cyc in 0..100 {
        for i in 0..per {
            let k = (cyc * per + i) as f64;
            acc.push(vec3(c.increment(k * h, (k + 1.0) * h))).unwrap();
            if acc.count() == per_update {
                q = q.mul_exp_unchecked(acc.take(), Normalization::Exact);
            }
        }
        let t = (cyc + 1) as f64 * period;
        ts.push(t);
        ys.push(body_error(c.attitude(t), q64(q))[2]);
    }
    check(
        "two-speed, 8 samples/update",
        fit_slope(&ts, &ys),
        c.alpha.powi(2) * c.omega_c * x.powi(4) / 60.0,
    );
}

host_tests::per_type! {
    /// The hot-path `coning2_update` is the TwoSample rule with fast renormalisation: over one
    /// coning period it tracks the closed form. Bounds: f64 5e-8 (the algorithmic drift
    /// α²Ω(ΩT)⁴/960·period ≈ 1.4e-8 rad, plus transverse periodic error of the same order);
    /// f32 2e-6 (~100 updates of a few ulp, 6e-8, each).
    #[test]
    fn coning2_update_tracks_closed_form() {
        let c = Coning {
            alpha: 0.1,
            omega_c: 3.0,
        };
        let n = 200;
        let h = 2.0 * std::f64::consts::PI / c.omega_c / n as f64;
        let mut q = unit_quat::<T>(c.attitude(0.0));
        for k in (0..n).step_by(2) {
            let kf = k as f64;
            let d1 = c.increment(kf * h, (kf + 1.0) * h);
            let d2 = c.increment((kf + 1.0) * h, (kf + 2.0) * h);
            q = coning2_update(q, vec3(d1), vec3(d2));
        }
        let e = quat_angle(c.attitude(n as f64 * h), q64(q));
        println!("one period, 100 updates: {} error {e:e} rad", T::NAME);
        assert!(e < T::per_type(2e-6, 5e-8), "{e}");
    }
}

/// A trailing partial group is integrated with the highest-order rule that fits it, and the
/// provisional attitude inside a group equals what `flush` commits.
#[test]
fn partial_groups_use_lower_order_rules() {
    let th: Vec<Vec3<f64>> = (0..7)
        .map(|k| {
            let t = k as f64;
            Vec3::new(
                0.01 * (0.3 * t).cos(),
                0.012 * (0.5 * t).sin(),
                0.004 + 0.001 * t,
            )
        })
        .collect();
    let q0 = UnitQuat::try_from_axis_angle(Vec3::new(1.0, 2.0, 3.0), 0.4).unwrap();
    let mut integ = IncrementIntegrator::new(q0, ConingRule::FourSample, Normalization::None);
    for t in &th {
        integ.push(*t).unwrap();
    }
    assert_eq!(integ.pending(), 3);
    let prov = integ.provisional_attitude();
    let done = integ.flush();
    assert_eq!(prov, done);
    // Manual: 4-sample rule on the first group, then the 3-sample rule on the last three.
    let first = th[0]
        + th[1]
        + th[2]
        + th[3]
        + (th[0].scale(54.0 / 105.0) + th[1].scale(92.0 / 105.0) + th[2].scale(214.0 / 105.0))
            .cross(th[3]);
    let last =
        th[4] + th[5] + th[6] + (th[4].scale(9.0 / 20.0) + th[5].scale(27.0 / 20.0)).cross(th[6]);
    let manual = q0 * UnitQuat::try_exp(first).unwrap() * UnitQuat::try_exp(last).unwrap();
    assert!((manual.dot(done) - 1.0).abs() < 1e-15);
    // A single trailing sample uses the one-plus-previous correction with the sample before it.
    let mut one = IncrementIntegrator::new(q0, ConingRule::TwoSample, Normalization::None);
    for t in &th {
        one.push(*t).unwrap();
    }
    let q = one.flush();
    let g = |a: Vec3<f64>, b: Vec3<f64>| a + b + a.cross(b).scale(2.0 / 3.0);
    let m = q0
        * UnitQuat::try_exp(g(th[0], th[1])).unwrap()
        * UnitQuat::try_exp(g(th[2], th[3])).unwrap()
        * UnitQuat::try_exp(g(th[4], th[5])).unwrap()
        * UnitQuat::try_exp(th[6] + th[5].cross(th[6]).scale(1.0 / 12.0)).unwrap();
    assert!((m.dot(q) - 1.0).abs() < 1e-15);
}

/// Non-finite increments are rejected with a typed error and leave the state unchanged.
#[test]
fn non_finite_increment_is_rejected() {
    let mut integ = IncrementIntegrator::new(
        UnitQuat::<f32>::IDENTITY,
        ConingRule::TwoSample,
        Normalization::Fast,
    );
    integ.push(Vec3::new(0.01, 0.0, 0.0)).unwrap();
    assert_eq!(
        integ.push(Vec3::new(f32::NAN, 0.0, 0.0)),
        Err(gyrostat::Error::NonFinite)
    );
    assert_eq!(
        integ.push(Vec3::new(0.0, f32::INFINITY, 0.0)),
        Err(gyrostat::Error::NonFinite)
    );
    assert_eq!(integ.pending(), 1);
    let mut acc = ConingAccumulator::<f64>::new();
    assert_eq!(
        acc.push(Vec3::new(0.0, 0.0, f64::NAN)),
        Err(gyrostat::Error::NonFinite)
    );
    assert_eq!(acc.count(), 0);
}

/// The rules' names as the `propagate` tool (`--algo`) and Python (`rule=`) spell them.
#[test]
fn rule_names() {
    let names = ["exp", "coning1", "coning2", "coning3", "coning4"];
    for (rule, name) in ConingRule::ALL.into_iter().zip(names) {
        assert_eq!(rule.name(), name);
        assert_eq!(rule.to_string(), name);
        assert_eq!(name.parse::<ConingRule>(), Ok(rule));
    }
    for bad in ["", "Exp", "coning5", "coning2 "] {
        assert_eq!(
            bad.parse::<ConingRule>(),
            Err(gyrostat::Error::InvalidArgument),
            "{bad:?}"
        );
    }
}
