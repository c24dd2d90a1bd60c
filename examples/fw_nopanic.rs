//! Firmware: proof that gyrostat's firmware path links with no panicking branch.
//!
//! ```text
//! cargo run --profile firmware --example fw_nopanic --target thumbv7em-none-eabihf
//! ```
//! (and the same for every firmware target: thumbv6m-none-eabi, thumbv7m-none-eabi,
//! thumbv8m.main-none-eabihf, riscv32imac-unknown-none-elf). The `firmware` profile (LTO, one
//! codegen unit) lets the optimiser see through every call; a build without LTO keeps calls it
//! cannot prove panic-free and does not link.
//! Every library entry point a firmware calls is fed opaque inputs (`core::hint::black_box`), so
//! the optimiser must keep all of their branches, error paths included. The `#[panic_handler]`
//! calls an `extern "C"` function that exists nowhere: if any panicking branch (an index out of
//! bounds, an `unwrap`, an overflow check, a failed assertion) survived optimisation in the code
//! reachable from `main`, the link fails with an undefined reference to
//! `gyrostat_firmware_path_contains_a_panicking_branch`. A successful link is the proof; running
//! the image under QEMU then checks that the calls also behave (exit 0).
//!
//! Later modules add their entry points to `exercise` in one line each.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod firmware {
    use board::entry;
    use core::hint::black_box;
    use gyrostat::{Mat3, Quat, Su2, UnitQuat, Vec3};

    mod board {
        include!("fw/board.rs");
    }

    /// Folds any result into a checksum the optimiser cannot see through.
    fn sink<T>(x: T) {
        black_box(x);
    }

    /// Every coning rule's integrator in scalar type `T` carrying attitude kind `A` (plain or
    /// compensated), fed `d` seven times (complete and partial groups, the provisional attitude,
    /// the flush).
    fn every_rule<T: gyrostat::ExpMap, A: gyrostat::propagation::PropagatedAttitude<T>>(
        q: A,
        d: Vec3<T>,
        norm: gyrostat::propagation::Normalization,
    ) {
        use gyrostat::propagation::{ConingRule, IncrementIntegrator};
        for rule in ConingRule::ALL {
            let mut integ = IncrementIntegrator::new(q, black_box(rule), norm);
            for _ in 0..black_box(7) {
                sink(integ.push(d));
                sink(integ.provisional_attitude());
            }
            sink(integ.flush());
        }
    }

    /// The estimator's entry points on opaque samples (6D, 9D, increments, initialisation,
    /// errors), and its outputs.
    fn estimator<T: gyrostat::Real>() {
        use gyrostat::estimation::{
            Estimator, Params, attitude_from_gravity, attitude_from_gravity_and_field,
        };
        let c = |x: f64| black_box(T::from_f64(x));
        let g = Vec3::new(c(0.01), c(-0.02), c(0.3));
        let a = Vec3::new(c(0.1), c(-0.2), c(9.8));
        let m = Vec3::new(c(0.2), c(15.8), c(-40.7));
        let dt = c(0.0035);
        sink(attitude_from_gravity(a));
        sink(attitude_from_gravity_and_field(a, m));
        // The online magnetometer delay on (and settling within the loop).
        let params = Params::<T> {
            mag_delay_estimation_time: c(0.01),
            ..Params::default()
        };
        if let Ok(mut f) = Estimator::try_new(black_box(params)) {
            for _ in 0..black_box(12) {
                sink(f.update_9d(g, a, m, dt));
                sink(f.update_6d(g, a, dt));
                sink(f.update_increment(g.scale(dt), a, Some(m), dt));
                sink(f.update(g, a, black_box(None), dt));
            }
            sink(f.attitude());
            sink(f.bias());
            sink(f.attitude_std());
            sink(f.covariance());
            sink(f.field_reference());
            sink(f.mag_delay());
        }
    }

    /// The light mode's entry points (`Mode::Light`, corrections within the loop), f32 (the
    /// f64 light code is linked by `estimator::<f64>` too, the mode being a runtime parameter).
    fn estimator_light() {
        use gyrostat::estimation::{Estimator, Mode, Params};
        type T = f32;
        let c = |x: f64| black_box(x as T);
        let g = Vec3::new(c(0.01), c(-0.02), c(0.3));
        let a = Vec3::new(c(0.1), c(-0.2), c(9.8));
        let m = Vec3::new(c(0.2), c(15.8), c(-40.7));
        let dt = c(0.0035);
        let params = Params::<T> {
            mode: Mode::Light {
                correction_period: c(0.007),
            },
            ..Params::light()
        };
        if let Ok(mut f) = Estimator::try_new(black_box(params)) {
            for _ in 0..black_box(12) {
                sink(f.update_9d(g, a, m, dt));
                sink(f.update_6d(g, a, dt));
                sink(f.update_increment(g.scale(dt), a, Some(m), dt));
                sink(f.update(g, a, black_box(None), dt));
            }
            sink(f.attitude());
            sink(f.bias());
            sink(f.attitude_std());
            sink(f.covariance());
        }
    }

    fn exercise() -> bool {
        let v = black_box(Vec3::new(0.3f32, -0.2, 0.9));
        let raw = black_box(Quat::new(0.9f32, 0.1, -0.3, 0.2));
        let angle = black_box(0.7f32);
        let mut ok = true;
        let q = match UnitQuat::try_new(raw) {
            Ok(q) => q,
            Err(_) => return false,
        };
        ok &= UnitQuat::try_new(black_box(Quat::<f32>::ZERO)).is_err();
        sink(UnitQuat::try_from_near_unit(raw, black_box(1e-3)));
        sink(UnitQuat::try_from_axis_angle(v, angle));
        sink(raw.try_inverse());
        sink(q * q.inverse());
        sink(q.rotate(v));
        sink(q.inverse_rotate(v));
        sink(q.to_rotation_matrix());
        sink(q.renormalize());
        sink(q.renormalize_fast());
        sink(UnitQuat::try_exp(v));
        sink(q.log());
        sink(q.angle());
        let u = Su2::from(q);
        sink(u * u.inverse());
        sink(u.rotate(v));
        sink(UnitQuat::from(u));
        let m = black_box(Mat3::from_rows(
            [2.0f32, 0.1, 0.0],
            [0.1, 3.0, 0.2],
            [0.0, 0.2, 4.0],
        ));
        sink(m.try_inverse());
        sink(m * v);
        sink(v.try_normalize());
        {
            use gyrostat::propagation::coning::rotation_vector_for;
            use gyrostat::propagation::exponential::step_constant_rate;
            use gyrostat::propagation::kernels::coning2_update;
            use gyrostat::propagation::kinematics::{
                body_rate_between, lab_rate_between, quat_rate_body,
            };
            use gyrostat::propagation::normalization::norm_deviation;
            use gyrostat::propagation::{
                CompensatedAttitude, ConingAccumulator, Normalization, RateIntegrator, RateMethod,
            };
            let d = black_box(Vec3::new(1e-3f32, -2e-3, 5e-4));
            let dt = black_box(1e-3f32);
            let norm = black_box(Normalization::Fast);
            sink(coning2_update(q, d, d));
            sink(rotation_vector_for(d, black_box(&[d, d, d, d, d][..])));
            sink(step_constant_rate(q, v, dt));
            sink(q.mul_exp_unchecked(d, norm));
            sink(body_rate_between(q, q, dt));
            sink(lab_rate_between(q, q, dt));
            sink(quat_rate_body(raw, v));
            sink(norm_deviation(q));
            every_rule(q, d, norm);
            every_rule(CompensatedAttitude::new(q), d, norm);
            for n in [
                Normalization::Exact,
                Normalization::Fast,
                Normalization::None,
            ] {
                sink(CompensatedAttitude::new(q).mul_exp_unchecked(d, black_box(n)));
            }
            let mut acc = ConingAccumulator::new();
            sink(acc.push(d));
            sink(acc.take());
            for m in [RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4] {
                if let Ok(mut integ) = RateIntegrator::try_new(q, black_box(m), norm, dt) {
                    for _ in 0..black_box(6) {
                        sink(integ.push(v));
                    }
                    sink(integ.finish());
                }
                let ca = CompensatedAttitude::new(q);
                if let Ok(mut integ) = RateIntegrator::try_new(ca, black_box(m), norm, dt)
                    .and_then(|i| i.try_with_step_remainder(black_box(4.7e-11)))
                {
                    for _ in 0..black_box(6) {
                        sink(integ.push(v));
                    }
                    sink(integ.finish());
                }
            }
        }
        {
            use gyrostat::rotation::{Euler, EulerSequence, GimbalPolicy};
            for seq in EulerSequence::ALL {
                let e = Euler::new(seq, black_box([0.3f32, -0.5, 1.2]));
                let qe = e.to_unit_quat_unchecked();
                sink(e.try_to_unit_quat());
                for policy in [
                    GimbalPolicy::ZeroFirst,
                    GimbalPolicy::ZeroThird,
                    GimbalPolicy::ClosestTo(black_box([0.1, 0.2, 0.3])),
                ] {
                    sink(black_box(qe).to_euler(seq, policy));
                }
            }
        }
        {
            use gyrostat::dynamics::{
                CompensatedState, Control, FreeRigidBody, Gyrostat, Inertia, Integrator, State,
                Wheel, WheelCommand,
            };
            let moments = black_box(Vec3::new(6.0f32, 4.0, 3.0));
            let j0 = black_box(Vec3::new(0.3f32, 4.0, 0.05));
            if let (Ok(inertia), Ok(w)) = (
                Inertia::try_from_components(moments, black_box(Vec3::new(-0.4, 0.25, 0.3))),
                Wheel::try_new(black_box(Vec3::Z), black_box(0.02f32)),
            ) {
                let body = Gyrostat::rigid(inertia);
                let s = State::new(q, j0);
                for integ in Integrator::ALL {
                    sink(body.step(black_box(integ), &s, black_box(0.01)));
                    sink(body.step_with(
                        black_box(integ),
                        &s,
                        black_box(0.0),
                        black_box(0.01),
                        Control::torque(v),
                    ));
                    let cs = CompensatedState::new(s);
                    sink(body.step(black_box(integ), &cs, black_box(0.01)));
                    sink(body.step_with(
                        black_box(integ),
                        &cs,
                        black_box(0.0),
                        black_box(0.01),
                        Control::torque(v),
                    ));
                }
                let g = Gyrostat::new(*body.model(), [w]);
                if let Ok(gs) = g.try_state_from_omega(q, v, [0.0]) {
                    for command in [
                        WheelCommand::Torque([black_box(0.001)]),
                        WheelCommand::Speed([black_box(10.0)]),
                    ] {
                        let held = g.control(&gs, black_box(0.01), v, &command);
                        sink(g.step_with(Integrator::Strang, &gs, 0.0, black_box(0.01), held));
                        let gc = CompensatedState::new(gs);
                        sink(g.step_with(Integrator::Strang, &gc, 0.0, black_box(0.01), held));
                    }
                }
                if let Ok(exact) = FreeRigidBody::try_new(&inertia, &s) {
                    sink(exact.try_state_at(black_box(7.5)));
                    sink(exact.flip_interval());
                }
            }
            if let Ok(diagonal) = Inertia::try_from_principal(moments) {
                let body = Gyrostat::rigid(diagonal);
                let s = State::new(q, j0);
                for integ in Integrator::ALL {
                    sink(body.step(black_box(integ), &s, black_box(0.01)));
                    sink(body.step(black_box(integ), &CompensatedState::new(s), black_box(0.01)));
                }
                if let Ok(exact) = FreeRigidBody::try_new(&diagonal, &s) {
                    sink(exact.try_state_at(black_box(7.5)));
                }
            }
        }
        {
            // Fixed point (Q1.30): conversions with their typed errors, the integer hot path,
            // the raw-register scale, every rule, the accumulator.
            use gyrostat::Ring;
            use gyrostat::fixed::increment_from_rate;
            use gyrostat::propagation::coning::rotation_vector_for;
            use gyrostat::propagation::kernels::coning2_update;
            use gyrostat::propagation::normalization::norm_squared_deviation;
            use gyrostat::propagation::{ConingAccumulator, Normalization};
            use gyrostat::real::{Q24, Q30};
            use gyrostat::sensor::RawScale;
            let norm = black_box(Normalization::Fast);
            sink(Q30::try_from_f64(black_box(3.0)));
            sink(Q30::try_from_f32(black_box(f32::NAN)));
            sink(Q30::from_bits(black_box(i32::MIN)).to_f32());
            let qx = match UnitQuat::<Q30>::try_from_f32(q) {
                Ok(qx) => qx,
                Err(_) => return false,
            };
            sink(UnitQuat::<Q30>::try_from_f64(black_box(UnitQuat::IDENTITY)));
            let dx = match Vec3::<Q30>::try_from_f32(black_box(Vec3::new(1e-3f32, -2e-3, 5e-4))) {
                Ok(dx) => dx,
                Err(_) => return false,
            };
            let big = black_box(Vec3::new(Q30::MAX, Q30::MIN, Q30::MAX));
            let vx = black_box(Vec3::new(Q30::HALF, Q30::ZERO, Q30::MIN));
            sink(qx * qx.inverse());
            sink(qx.rotate(vx));
            sink(qx.to_rotation_matrix());
            sink(qx.renormalize());
            sink(qx.renormalize_fast());
            sink(norm_squared_deviation(qx));
            sink(UnitQuat::exp_unchecked(dx));
            sink(UnitQuat::exp_unchecked(big));
            sink(qx.mul_exp_unchecked(big, Normalization::None));
            sink(coning2_update(qx, dx, dx));
            sink(rotation_vector_for(
                dx,
                black_box(&[dx, dx, dx, dx, dx][..]),
            ));
            sink(qx.mul_exp_unchecked(big, black_box(Normalization::Exact)));
            sink(qx.to_f64());
            sink(vx.to_f32());
            every_rule(qx, dx, norm);
            let mut acc = ConingAccumulator::<Q30>::new();
            sink(acc.push(big));
            acc.push_unchecked(big);
            sink(acc.take());
            if let Ok(scale) = RawScale::<Q30>::try_new(black_box(1e-6)) {
                sink(scale.apply(black_box([i16::MIN, -1, i16::MAX])));
            }
            sink(RawScale::<Q30>::try_from_rate(
                black_box(1e-3),
                black_box(1.0),
            ));
            if let (Ok(w), Ok(h)) = (
                Vec3::<Q24>::try_from_f64(black_box(Vec3::new(100.0, -1.0, 0.5))),
                Q30::try_from_f64(black_box(1e-3)),
            ) {
                sink(increment_from_rate(w, h));
            }
        }
        {
            // The sensor layer (`gyrostat::sensor`) and the unequal-interval kernels: every
            // entry point with its typed errors, f32 and Q1.30.
            use gyrostat::Mat3;
            use gyrostat::fixed::IncrementQuantizer;
            use gyrostat::propagation::coning::{
                two_sample_unequal_coefficient, two_sample_unequal_terms,
            };
            use gyrostat::propagation::kernels::{coning2_update_unequal, magnus4_step_unequal};
            use gyrostat::real::Q30;
            use gyrostat::sensor::timing::{micros_to_q30, micros_to_seconds};
            use gyrostat::sensor::{
                AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration,
                MagnetometerCalibration, MicrosClock, Mounting, RawScale, SampleClock,
            };
            if let Ok(mut c) = SampleClock::try_with_gap_factor(black_box(0.01f32), black_box(5.0))
            {
                for t in [0.0f32, 0.01, 0.01, 0.005, 0.2, f32::NAN] {
                    sink(c.interval(black_box(t)));
                }
                c.restart(black_box(None));
            }
            if let Ok(mut c) = MicrosClock::try_new(black_box(1000), black_box(5)) {
                for t in [u32::MAX, 3, 3, 1, 1 << 31] {
                    sink(c.interval(black_box(t)));
                }
            }
            sink(micros_to_q30(black_box(u32::MAX)));
            sink(gyrostat::sensor::timing::unequal_coefficient_q30(
                black_box(0),
                black_box(u32::MAX),
            ));
            sink(gyrostat::sensor::timing::unequal_coefficient_q30(
                black_box(900),
                black_box(1100),
            ));
            sink(micros_to_seconds::<f32>(black_box(u32::MAX)));
            let m = black_box(Mat3::from_rows(
                [1.0f32, 0.01, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ));
            let s = black_box(Vec3::new(1.0f32, 1.01, 0.99));
            if let Ok(cal) = InertialCalibration::try_new(m, s, v) {
                sink(cal.try_apply(v));
                sink(cal.apply_increment(v, black_box(1e-3)));
                sink(cal.raw_from_corrected(v));
            }
            if let Ok(cal) = InertialCalibration::try_new(m.scale(0.5f64 as f32), s, v) {
                sink(cal.apply(v));
            }
            if let Ok(cal64) = InertialCalibration::try_new(
                black_box(Mat3::<f64>::IDENTITY),
                black_box(Vec3::new(1.0, 1.0, 1.0)),
                black_box(Vec3::new(0.01, 0.0, 0.0)),
            ) && let (Ok(calq), Ok(scale), Ok(dt)) = (
                cal64.try_to_q30(),
                RawScale::<Q30>::try_new(black_box(1e-6)),
                Q30::try_from_f64(black_box(1e-3)),
            ) {
                let mut quant = IncrementQuantizer::<30>::new();
                let inc = quant.quantize_raw(&scale, black_box([i16::MIN, 0, i16::MAX]));
                sink(calq.apply_increment(inc, dt));
                if let Ok(r) = AxisRemap::try_parse(black_box("-y,x,z")) {
                    sink(r.apply(inc));
                }
            }
            if let Ok(mag) = MagnetometerCalibration::try_new(m, v) {
                sink(mag.try_apply(black_box(Vec3::new(f32::MAX, 0.0, 1.0))));
                sink(mag.raw_from_corrected(v));
            }
            for text in ["x,-z,y", "y,x,z", "x,x,z", "", "q,r,s,t"] {
                if let Ok(r) = AxisRemap::try_parse(black_box(text)) {
                    sink(r.apply(v));
                    sink(r.inverse());
                    let mount: Mounting<f32> = r.into();
                    sink(mount.to_body(v));
                    sink(mount.body_attitude(q));
                    sink(mount.sensor_attitude(q));
                }
            }
            sink(AxisRemap::all());
            for policy in [ClipPolicy::Pass, ClipPolicy::HoldLast, ClipPolicy::Reject] {
                if let Ok(limit) = ClipLimit::try_new(black_box(30000)) {
                    let mut g = ClipGuard::new(limit, black_box(policy));
                    sink(g.filter(black_box([i16::MIN, 5, i16::MAX])));
                    sink(g.filter(black_box([1, 5, 2])));
                }
            }
            if let Ok(sc) = RawScale::<f32>::try_new(black_box(1e-3)) {
                sink(sc.apply(black_box([i16::MIN, 0, i16::MAX])));
            }
            let d = black_box(Vec3::new(1e-3f32, -2e-3, 5e-4));
            let c = two_sample_unequal_coefficient(black_box(1e-3f32), black_box(0.0));
            sink(two_sample_unequal_terms(d, d, c));
            sink(coning2_update_unequal(q, d, d, c));
            if let (Ok(qq), Ok(dq)) = (
                UnitQuat::<Q30>::try_from_f32(q),
                Vec3::<Q30>::try_from_f32(d),
            ) {
                sink(coning2_update_unequal(qq, dq, dq, black_box(Q30::MAX)));
            }
            let times = black_box([0.0f32, 1e-3, 1e-3, 3e-3]);
            let rates = black_box([d, d, v, v]);
            sink(magnus4_step_unequal(
                q,
                &times,
                &rates,
                black_box(1e-3),
                black_box(3e-3),
            ));
            sink(magnus4_step_unequal(
                q,
                &[0.0f32; 0],
                &[],
                black_box(0.0),
                black_box(1.0),
            ));
        }
        // The attitude estimator (`gyrostat::estimation`): every entry point, f32 and f64.
        estimator::<f32>();
        // The f64 estimator (both modes: the mode is a runtime parameter) does not fit the
        // 256 KiB of the M0 and M3 boards beside the rest of the library (`build.rs` sets the
        // cfg): they check it in f32 only, the M4F, M33 and RISC-V boards in both precisions.
        #[cfg(not(gyrostat_board_small_flash))]
        estimator::<f64>();
        estimator_light();
        // f64 (soft float on every Cortex-M) goes through the same paths.
        let q64 =
            UnitQuat::try_from_axis_angle(black_box(Vec3::new(1.0f64, 2.0, 3.0)), black_box(0.5));
        sink(q64.map(|q| q.rotate(Vec3::X)));
        ok
    }

    #[entry]
    fn main() -> ! {
        board::exit(exercise())
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        unsafe extern "C" {
            fn gyrostat_firmware_path_contains_a_panicking_branch() -> !;
        }
        // SAFETY: the symbol does not exist; reaching this line at link time is the failure
        // this example exists to detect.
        unsafe { gyrostat_firmware_path_contains_a_panicking_branch() }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
