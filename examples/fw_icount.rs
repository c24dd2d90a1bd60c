//! Firmware: deterministic guest-instruction counts of named operations under QEMU.
//!
//! ```text
//! cargo run --profile firmware --example fw_icount --target thumbv7em-none-eabihf   # Cortex-M4F
//! cargo run --profile firmware --example fw_icount --target thumbv6m-none-eabi      # Cortex-M0
//! ```
//! The method (QEMU `-icount`, SysTick, a calibrated loop, `REPS` calls per count) is in
//! `fw/icount.rs`, shared with `fw_icount_estimation` (the attitude filters beside their peers,
//! in an image of their own, so that the peers' code does not change how the library's own
//! operations below are inlined). Counts are guest instructions (QEMU has no cycle model),
//! identical on every run.
//!
//! Rows ending in `_q30` are the fixed-point (Q1.30) path on the same operands as the f32 rows.
//! Each operation is one line in `main` (`count!("name", || expression)`); operands go through
//! `black_box`, so the count includes loading them, as in real firmware. Passed by value, a
//! constant operand is also rebuilt and stored at every call, which firmware does not do:
//! `prop_coning2_update_in_place_f32` is the 2-sample update as a firmware loop runs it (the
//! attitude updated in place in RAM, the increments read from a buffer), 20–25 instructions
//! below the by-value `prop_coning2_update_f32` on the M4F. Output, one line each:
//! `icount <name> <instructions>`. `calibration_check_1000` (1000 loop instructions plus about 3
//! of call set-up) shows the accuracy of the method.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[macro_use]
#[path = "fw/icount.rs"]
mod icount;

#[cfg(target_os = "none")]
mod firmware {
    use crate::icount::{Calibration, Table, exit, spin, start_systick};
    use core::hint::black_box;
    use cortex_m_rt::entry;
    use cortex_m_semihosting::debug;
    use gyrostat::{Quat, UnitQuat, Vec3};

    #[entry]
    fn main() -> ! {
        if start_systick().is_none() {
            exit(debug::EXIT_FAILURE);
        }
        let cal = Calibration::measure();
        let mut table = Table::<96>::empty();

        let a = UnitQuat::new_unchecked(Quat::new(0.9f32, 0.1, -0.3, 0.2)).renormalize();
        let b = UnitQuat::new_unchecked(Quat::new(0.5f32, 0.5, 0.5, -0.5));
        let v = Vec3::new(0.3f32, -0.2, 0.9);
        let phi = Vec3::new(1e-3f32, -2e-3, 5e-4);

        // One line per operation.
        count!(table, "calibration_check_1000", || spin(black_box(500)));
        count!(table, "quat_product_f32", || black_box(a) * black_box(b));
        count!(table, "vector_rotation_f32", || black_box(a)
            .rotate(black_box(v)));
        count!(table, "quat_to_matrix_f32", || black_box(a)
            .to_rotation_matrix());
        count!(table, "renormalize_fast_f32", || black_box(a)
            .renormalize_fast());
        count!(table, "renormalize_exact_f32", || black_box(a)
            .renormalize());
        count!(table, "sin_cos_f32", || gyrostat::Real::sin_cos(black_box(
            0.7f32
        )));
        count!(table, "sin_cos_f64", || gyrostat::Real::sin_cos(black_box(
            0.7f64
        )));
        count!(table, "exp_small_angle_f32", || UnitQuat::exp_unchecked(
            black_box(phi)
        ));
        {
            use gyrostat::propagation::coning::{
                four_sample_terms, one_plus_previous_terms, three_sample_terms,
            };
            use gyrostat::propagation::kernels::{
                self, cf4_step, coning2_update, magnus4_step, rk4_step,
            };
            use gyrostat::propagation::rate_samples::{gauss_rates, midpoint_rate};
            use gyrostat::propagation::{
                CompensatedAttitude, ConingAccumulator, ConingRule, IncrementIntegrator,
                Normalization, RateIntegrator, RateMethod,
            };
            let t1 = Vec3::new(1.0e-3f32, -2.0e-3, 0.5e-3);
            let t2 = Vec3::new(1.2e-3f32, -1.9e-3, 0.6e-3);
            let t3 = Vec3::new(1.4e-3f32, -1.7e-3, 0.7e-3);
            let t4 = Vec3::new(1.5e-3f32, -1.4e-3, 0.8e-3);
            let win = [
                t1.scale(1000.0),
                t2.scale(1000.0),
                t3.scale(1000.0),
                t4.scale(1000.0),
            ];
            let w = Vec3::new(0.3f32, -0.2, 0.5);
            let dt = 1e-3f32;
            let fast = Normalization::Fast;
            count!(table, "prop_coning2_update_f32", || coning2_update(
                black_box(a),
                black_box(t1),
                black_box(t2)
            ));
            // The same update as a firmware loop runs it: the attitude kept in RAM and updated in
            // place, the two increments read from the sample buffer. The row above passes every
            // operand through `black_box` by value, which re-materialises the ten constant
            // operands on the stack at every call; here only the two addresses go through it.
            let state = core::cell::Cell::new(a);
            let samples = [t1, t2];
            count!(table, "prop_coning2_update_in_place_f32", || {
                let (q, t) = (black_box(&state), black_box(&samples));
                q.set(coning2_update(q.get(), t[0], t[1]));
            });
            count!(table, "prop_exp_step_fast_f32", || fast.apply(
                kernels::step_constant_rate(black_box(a), black_box(w), black_box(dt))
            ));
            count!(table, "prop_coning1_fast_f32", || black_box(a)
                .mul_exp_unchecked(
                    one_plus_previous_terms(black_box(t1), black_box(t2)),
                    fast
                ));
            count!(table, "prop_coning3_fast_f32", || black_box(a)
                .mul_exp_unchecked(
                    three_sample_terms(black_box(t1), black_box(t2), black_box(t3)),
                    fast
                ));
            count!(table, "prop_coning4_fast_f32", || black_box(a)
                .mul_exp_unchecked(
                    four_sample_terms(black_box(t1), black_box(t2), black_box(t3), black_box(t4)),
                    fast
                ));
            let mut acc = ConingAccumulator::<f32>::new();
            count!(table, "prop_two_speed_push_f32", || {
                let mut x = black_box(acc);
                x.push_unchecked(black_box(t3));
                x
            });
            acc.push_unchecked(t1);
            count!(table, "prop_two_speed_take_update_f32", || {
                let mut x = black_box(acc);
                black_box(a).mul_exp_unchecked(x.take(), fast)
            });
            count!(table, "prop_magnus4_fast_f32", || {
                let (w1, w2) = gauss_rates(black_box(&win), 2);
                fast.apply(magnus4_step(black_box(a), w1, w2, black_box(dt)))
            });
            count!(table, "prop_cf4_fast_f32", || {
                let (w1, w2) = gauss_rates(black_box(&win), 2);
                fast.apply(cf4_step(black_box(a), w1, w2, black_box(dt)))
            });
            count!(table, "prop_rk4_fast_f32", || {
                let x = black_box(&win);
                let m = midpoint_rate(x, 2);
                fast.apply_quat_unchecked(rk4_step(
                    *black_box(a).as_quat(),
                    x[2],
                    m,
                    x[3],
                    black_box(dt),
                ))
            });
            // The compensated attitude, and the integrators carrying a plain or a compensated
            // attitude (one update each: two increments for coning2, one sample once the rate
            // window is full; the integrator is copied in through black_box in both).
            let ca = CompensatedAttitude::new(a);
            count!(table, "prop_exp_step_fast_compensated_f32", || black_box(
                ca
            )
            .mul_exp_unchecked(black_box(w).scale(black_box(dt)), fast));
            let inc_plain = IncrementIntegrator::new(a, ConingRule::TwoSample, fast);
            let inc_comp = IncrementIntegrator::new(ca, ConingRule::TwoSample, fast);
            count!(table, "prop_integrator_coning2_f32", || {
                let mut x = black_box(&inc_plain).clone();
                let _ = x.push(black_box(t1));
                x.push(black_box(t2))
            });
            count!(table, "prop_integrator_coning2_compensated_f32", || {
                let mut x = black_box(&inc_comp).clone();
                let _ = x.push(black_box(t1));
                x.push(black_box(t2))
            });
            for (method, plain_name, comp_name) in [
                (
                    RateMethod::Magnus4,
                    "prop_integrator_magnus4_f32",
                    "prop_integrator_magnus4_compensated_f32",
                ),
                (
                    RateMethod::Cf4,
                    "prop_integrator_cf4_f32",
                    "prop_integrator_cf4_compensated_f32",
                ),
                (
                    RateMethod::Rk4,
                    "prop_integrator_rk4_f32",
                    "prop_integrator_rk4_compensated_f32",
                ),
            ] {
                if let (Ok(mut plain), Ok(mut comp)) = (
                    RateIntegrator::try_new(a, method, fast, dt),
                    RateIntegrator::try_new(ca, method, fast, dt),
                ) {
                    for v in win {
                        let _ = plain.push(v);
                        let _ = comp.push(v);
                    }
                    count!(table, plain_name, || black_box(&plain)
                        .clone()
                        .push(black_box(t3)));
                    count!(table, comp_name, || black_box(&comp)
                        .clone()
                        .push(black_box(t3)));
                }
            }
        }

        {
            // Fixed point (Q1.30), the same operations and operands as the f32 rows above.
            use gyrostat::propagation::CarriedAttitude;
            use gyrostat::propagation::coning::{four_sample_terms, one_plus_previous_terms};
            use gyrostat::propagation::kernels::coning2_update;
            use gyrostat::propagation::{ConingAccumulator, Normalization};
            use gyrostat::real::Q30;
            let q = |q: UnitQuat<f32>| UnitQuat::<Q30>::try_from_f32(q).unwrap_or_default();
            let v3 = |v: Vec3<f32>| Vec3::<Q30>::try_from_f32(v).unwrap_or_default();
            let (aq, bq, vq, phiq) = (q(a), q(b), v3(v), v3(phi));
            let t1 = v3(Vec3::new(1.0e-3f32, -2.0e-3, 0.5e-3));
            let t2 = v3(Vec3::new(1.2e-3f32, -1.9e-3, 0.6e-3));
            let t3 = v3(Vec3::new(1.4e-3f32, -1.7e-3, 0.7e-3));
            let t4 = v3(Vec3::new(1.5e-3f32, -1.4e-3, 0.8e-3));
            let big = v3(Vec3::new(0.9f32, -0.6, 0.3));
            let fast = Normalization::Fast;
            count!(table, "quat_product_q30", || black_box(aq) * black_box(bq));
            count!(table, "vector_rotation_q30", || black_box(aq)
                .rotate(black_box(vq)));
            count!(table, "quat_to_matrix_q30", || black_box(aq)
                .to_rotation_matrix());
            count!(table, "renormalize_fast_q30", || black_box(aq)
                .renormalize_fast());
            count!(table, "renormalize_exact_q30", || black_box(aq)
                .renormalize());
            count!(table, "exp_small_angle_q30", || UnitQuat::exp_unchecked(
                black_box(phiq)
            ));
            count!(table, "exp_large_angle_q30", || UnitQuat::exp_unchecked(
                black_box(big)
            ));
            count!(table, "prop_coning2_update_q30", || coning2_update(
                black_box(aq),
                black_box(t1),
                black_box(t2)
            ));
            // The carried attitude (rounding residuals carried, the renormalisation folded in):
            // what `propagate --fixed` runs. Its residuals as a running update leaves them.
            let carried = CarriedAttitude::new(aq)
                .coning2_update(t1, t2)
                .coning2_update(t3, t4);
            count!(table, "prop_coning2_update_carried_q30", || black_box(
                carried
            )
            .coning2_update(black_box(t1), black_box(t2)));
            count!(table, "prop_coning1_fast_q30", || black_box(aq)
                .mul_exp_unchecked(
                    one_plus_previous_terms(black_box(t1), black_box(t2)),
                    fast
                ));
            count!(table, "prop_coning4_fast_q30", || black_box(aq)
                .mul_exp_unchecked(
                    four_sample_terms(black_box(t1), black_box(t2), black_box(t3), black_box(t4)),
                    fast
                ));
            let acc = ConingAccumulator::<Q30>::new();
            count!(table, "prop_two_speed_push_q30", || {
                let mut x = black_box(acc);
                x.push_unchecked(black_box(t3));
                x
            });
        }

        {
            use gyrostat::rotation::{Euler, EulerSequence, GimbalPolicy};
            let e = [0.3f32, -0.5, 1.2];
            let qe = Euler::new(EulerSequence::ZYX, e).to_unit_quat_unchecked();
            let lock = Euler::new(
                EulerSequence::ZYX,
                [0.3f32, core::f32::consts::FRAC_PI_2, 0.1],
            )
            .to_unit_quat_unchecked();
            let zyx = EulerSequence::ZYX;
            let zyz = EulerSequence::ZYZ;
            count!(table, "rot_euler_to_quat_zyx_f32", || Euler::new(
                zyx,
                black_box(e)
            )
            .to_unit_quat_unchecked());
            count!(table, "rot_quat_to_euler_zyx_f32", || black_box(qe)
                .to_euler(zyx, GimbalPolicy::ZeroThird));
            count!(table, "rot_quat_to_euler_zyz_f32", || black_box(qe)
                .to_euler(zyz, GimbalPolicy::ZeroThird));
            count!(table, "rot_quat_to_euler_zyx_at_lock_closest_f32", || {
                black_box(lock).to_euler(zyx, GimbalPolicy::ClosestTo(black_box([0.2, 1.5, 0.0])))
            });
        }
        {
            use gyrostat::dynamics::{
                CompensatedState, FreeRigidBody, Gyrostat, Inertia, Integrator, State, Wheel,
                WheelCommand,
            };
            let principal = Inertia::try_from_principal(Vec3::new(6.0f32, 4.0, 3.0));
            let full = Inertia::try_from_components(
                Vec3::new(3.0f32, 4.0, 5.0),
                Vec3::new(-0.4, 0.25, 0.3),
            );
            let wheels = [
                Wheel::try_new(Vec3::X, 0.02f32),
                Wheel::try_new(Vec3::Y, 0.02),
                Wheel::try_new(Vec3::Z, 0.02),
                Wheel::try_new(Vec3::new(1.0, 1.0, 1.0), 0.02),
            ];
            let s = State::new(UnitQuat::IDENTITY, Vec3::new(0.3f32, 4.0, 0.05));
            if let (Ok(principal), Ok(full), [Ok(w0), Ok(w1), Ok(w2), Ok(w3)]) =
                (principal, full, wheels)
            {
                let body = Gyrostat::rigid(principal);
                let full_body = Gyrostat::rigid(full);
                let h = 0.01f32;
                count!(table, "dyn_rk4_step_f32", heavy, || body.step(
                    Integrator::Rk4,
                    black_box(&s),
                    black_box(h)
                ));
                count!(table, "dyn_strang_step_f32", heavy, || body.step(
                    Integrator::Strang,
                    black_box(&s),
                    black_box(h)
                ));
                count!(table, "dyn_yoshida4_step_f32", heavy, || body.step(
                    Integrator::Yoshida4,
                    black_box(&s),
                    black_box(h)
                ));
                count!(table, "dyn_suzuki4_step_f32", heavy, || body.step(
                    Integrator::Suzuki4,
                    black_box(&s),
                    black_box(h)
                ));
                count!(table, "dyn_strang_step_full_tensor_f32", heavy, || {
                    full_body.step(Integrator::Strang, black_box(&s), black_box(h))
                });
                let g = Gyrostat::new(*full_body.model(), [w0, w1, w2, w3]);
                let tau = Vec3::new(0.01f32, 0.0, -0.005);
                let cmd = WheelCommand::Torque([0.001f32, -0.002, 0.0005, 0.0]);
                if let Ok(gs) =
                    g.try_state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.1, 0.5, 0.2), [0.0; 4])
                {
                    count!(
                        table,
                        "dyn_gyrostat_4_wheels_strang_step_f32",
                        heavy,
                        || {
                            let gs = black_box(&gs);
                            let h = black_box(h);
                            let held = g.control(gs, h, black_box(tau), &cmd);
                            g.step_with(Integrator::Strang, gs, 0.0, h, held)
                        }
                    );
                }
                // The same steps on a CompensatedState (rounding errors carried).
                let cs = CompensatedState::new(s);
                count!(table, "dyn_rk4_step_compensated_f32", heavy, || body.step(
                    Integrator::Rk4,
                    black_box(&cs),
                    black_box(h)
                ));
                count!(table, "dyn_strang_step_compensated_f32", heavy, || body
                    .step(Integrator::Strang, black_box(&cs), black_box(h)));
                count!(table, "dyn_yoshida4_step_compensated_f32", heavy, || body
                    .step(Integrator::Yoshida4, black_box(&cs), black_box(h)));
                count!(table, "dyn_suzuki4_step_compensated_f32", heavy, || body
                    .step(Integrator::Suzuki4, black_box(&cs), black_box(h)));
                count!(
                    table,
                    "dyn_strang_step_full_tensor_compensated_f32",
                    heavy,
                    || full_body.step(Integrator::Strang, black_box(&cs), black_box(h))
                );
                if let Ok(gs) =
                    g.try_state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.1, 0.5, 0.2), [0.0; 4])
                {
                    let gc = CompensatedState::new(gs);
                    count!(
                        table,
                        "dyn_gyrostat_4_wheels_strang_step_compensated_f32",
                        heavy,
                        || {
                            let gc = black_box(&gc);
                            let h = black_box(h);
                            let held = g.control(gc.state(), h, black_box(tau), &cmd);
                            g.step_with(Integrator::Strang, gc, 0.0, h, held)
                        }
                    );
                }
                if let Ok(exact) = FreeRigidBody::try_new(&principal, &s) {
                    count!(table, "dyn_exact_free_body_state_at_f32", heavy, || exact
                        .state_at_unchecked(black_box(7.5f32)));
                }
            }
        }

        {
            // The sensor layer per sample (gyrostat::sensor): raw i16 increment registers →
            // LSB scale → calibration K·(raw − b·dt) → axis remap, in f32 and Q1.30; the clocks;
            // clipping; the unequal-interval propagation kernels.
            use gyrostat::Mat3;
            use gyrostat::fixed::IncrementQuantizer;
            use gyrostat::propagation::coning::two_sample_unequal_coefficient;
            use gyrostat::propagation::kernels::{coning2_update_unequal, magnus4_step_unequal};
            use gyrostat::real::Q30;
            use gyrostat::sensor::timing::micros_to_q30;
            use gyrostat::sensor::{
                AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration, MicrosClock,
                RawScale, SampleClock,
            };
            let m = Mat3::from_rows(
                [1.0, 0.004, -0.002],
                [-0.003, 1.0, 0.001],
                [0.002, -0.001, 1.0],
            );
            let sc = Vec3::new(1.01, 0.995, 1.003);
            let bias = Vec3::new(0.002, -0.001, 0.0005);
            let remap = AxisRemap::try_parse("x,-z,y");
            let cal64 = InertialCalibration::try_new(m, sc, bias);
            let m32 = Mat3::from_rows(
                m.m[0].map(|x| x as f32),
                m.m[1].map(|x| x as f32),
                m.m[2].map(|x| x as f32),
            );
            let cal32 = InertialCalibration::try_new(
                m32,
                Vec3::new(1.01f32, 0.995, 1.003),
                Vec3::new(0.002f32, -0.001, 0.0005),
            );
            let lsb32 = RawScale::<f32>::try_new(1.0653e-6);
            let lsbq = RawScale::<Q30>::try_new(1.0653e-6);
            let raw = [1200i16, -4321, 77];
            let dtq = Q30::try_from_f64(1e-3);
            if let (Ok(remap), Ok(cal64), Ok(cal32), Ok(lsb32), Ok(lsbq), Ok(dtq)) =
                (remap, cal64, cal32, lsb32, lsbq, dtq)
                && let Ok(calq) = cal64.try_to_q30()
            {
                count!(table, "sensor_raw_calibrate_remap_f32", || black_box(remap)
                    .apply(black_box(&cal32).apply_increment(
                        black_box(lsb32).apply(black_box(raw)),
                        black_box(1e-3f32)
                    )));
                let quant = IncrementQuantizer::<30>::new();
                count!(table, "sensor_raw_calibrate_remap_q30", || {
                    let mut qz = black_box(quant);
                    let v = qz.quantize_raw(black_box(&lsbq), black_box(raw));
                    black_box(remap).apply(black_box(&calq).apply_increment(v, black_box(dtq)))
                });
            }
            if let Ok(mut clock) = SampleClock::try_new(0.01f32) {
                clock.restart(Some(1.0));
                count!(table, "sensor_sample_clock_interval_f32", || {
                    let mut c = black_box(clock);
                    c.interval(black_box(1.0102f32))
                });
            }
            if let Ok(mut mc) = MicrosClock::try_new(1000, 5) {
                mc.restart(Some(u32::MAX - 400));
                count!(table, "sensor_micros_clock_interval_to_q30", || {
                    let mut c = black_box(mc);
                    let i = c.interval(black_box(612u32));
                    (i, micros_to_q30(black_box(1013)))
                });
            }
            if let Ok(limit) = ClipLimit::try_new(32000) {
                let guard = ClipGuard::new(limit, ClipPolicy::HoldLast);
                count!(table, "sensor_clip_guard_hold_last", || {
                    let mut g = black_box(guard);
                    g.filter(black_box([32100i16, -5, 17]))
                });
            }
            let a = UnitQuat::new_unchecked(Quat::new(0.9f32, 0.1, -0.3, 0.2)).renormalize();
            let t1 = Vec3::new(1.0e-3f32, -2.0e-3, 0.5e-3);
            let t2 = Vec3::new(1.2e-3f32, -1.9e-3, 0.6e-3);
            count!(table, "prop_coning2_unequal_with_coefficient_f32", || {
                let c = two_sample_unequal_coefficient(black_box(0.8e-3f32), black_box(1.3e-3));
                coning2_update_unequal(black_box(a), black_box(t1), black_box(t2), c)
            });
            if let (Ok(aq), Ok(t1q), Ok(t2q), Ok(cq)) = (
                UnitQuat::<Q30>::try_from_f32(a),
                Vec3::<Q30>::try_from_f32(t1),
                Vec3::<Q30>::try_from_f32(t2),
                Q30::try_from_f64(two_sample_unequal_coefficient(0.8e-3, 1.3e-3)),
            ) {
                count!(
                    table,
                    "prop_coning2_unequal_q30",
                    || coning2_update_unequal(
                        black_box(aq),
                        black_box(t1q),
                        black_box(t2q),
                        black_box(cq)
                    )
                );
            }
            let times = [0.0f32, 0.9e-3, 2.1e-3, 3.0e-3];
            let rates = [
                Vec3::new(1.0f32, -2.0, 0.5),
                Vec3::new(1.2f32, -1.9, 0.6),
                Vec3::new(1.4f32, -1.7, 0.7),
                Vec3::new(1.5f32, -1.4, 0.8),
            ];
            count!(table, "prop_magnus4_unequal_4_samples_f32", || {
                magnus4_step_unequal(
                    black_box(a),
                    black_box(&times),
                    black_box(&rates),
                    black_box(2.1e-3f32),
                    black_box(3.0e-3f32),
                )
            });
        }

        table.print(&cal);
        exit(debug::EXIT_SUCCESS)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
