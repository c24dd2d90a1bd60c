//! Firmware: deterministic guest-instruction counts of named operations under QEMU.
//!
//! ```text
//! cargo run --profile firmware --example fw_icount --target thumbv7em-none-eabihf   # Cortex-M4F
//! cargo run --profile firmware --example fw_icount --target thumbv6m-none-eabi      # Cortex-M0
//! ```
//! The runner (`.cargo/config.toml`) starts QEMU with `-icount shift=7,align=off,sleep=off`: each
//! guest instruction advances virtual time by 128 ns, so SysTick (clock source = core) ticks are
//! a deterministic function of the instructions executed. The 24-bit SysTick down-counter is read
//! around each operation; the tick/instruction ratio is calibrated with a `subs`/`bne` loop of
//! known length (200 000 instructions); each operation runs 64 times in a loop whose empty cost
//! is subtracted, and the count is per call. Counts are guest
//! instructions (QEMU has no cycle model), identical on every run.
//!
//! Rows ending in `_q30` are the fixed-point (Q1.30) path on the same operands as the f32 rows.
//! Each operation is one line in `main` (`count!("name", || expression)`); operands go through
//! `black_box`, so the count includes loading them, as in real firmware. Output, one line each:
//! `icount <name> <instructions>`. `calibration_check_1000` (1000 loop instructions plus about 3
//! of call set-up) shows the accuracy of the method.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;
    use core::sync::atomic::{Ordering, compiler_fence};
    use cortex_m::peripheral::{SYST, syst::SystClkSource};
    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, hprintln};
    use gyrostat::{Quat, UnitQuat, Vec3};

    const MASK: u32 = 0x00FF_FFFF;

    /// SysTick ticks spent in `f` (valid below 2^24 ticks).
    #[inline(always)]
    fn ticks<R>(f: impl FnOnce() -> R) -> u32 {
        let c0 = SYST::get_current();
        compiler_fence(Ordering::SeqCst);
        black_box(f());
        compiler_fence(Ordering::SeqCst);
        let c1 = SYST::get_current();
        c0.wrapping_sub(c1) & MASK
    }

    /// A loop of exactly `2·n` instructions (`subs` + `bne` per iteration), plus the `n == 0`
    /// test and the move of `n` into a register.
    #[inline(always)]
    fn spin(n: u32) {
        if n == 0 {
            return;
        }
        // SAFETY: pure register arithmetic on a scratch register, no memory access.
        unsafe {
            core::arch::asm!("2:", "subs {0}, #1", "bne 2b", inout(reg) n => _, options(nomem, nostack));
        }
    }

    /// Repetitions per measurement: QEMU's SysTick on some boards (microbit) jitters by about
    /// 2% of a short interval; averaging a long interval makes that negligible.
    const REPS: u32 = 64;
    /// Repetitions for heavy operations (a dynamics step in soft float), so that 4 calls stay
    /// below the 2^24-tick range of SysTick.
    const REPS_HEAVY: u32 = 4;

    /// Ticks of `reps` calls of `f`.
    #[inline(always)]
    fn ticks_reps<R>(reps: u32, f: impl Fn() -> R) -> u32 {
        ticks(|| {
            for _ in 0..black_box(reps) {
                black_box(f());
            }
        })
    }

    struct Calibration {
        /// Ticks of `REPS` and of `REPS_HEAVY` empty iterations (loop and `black_box` overhead).
        overhead: [u32; 2],
        /// Ticks per 200 000 instructions.
        per_200k: u32,
    }

    impl Calibration {
        fn new() -> Self {
            // The first readings after SysTick starts are skewed by the timer's start-up in
            // QEMU; a warm-up run of a few thousand instructions settles it.
            spin(black_box(5000));
            let overhead = [ticks_reps(REPS, || ()), ticks_reps(REPS_HEAVY, || ())];
            let t0 = ticks(|| spin(black_box(1)));
            let t1 = ticks(|| spin(black_box(100_001)));
            // (t1 − t0) is exactly 200 000 instructions: 100 000 more `subs`/`bne` iterations.
            Self {
                overhead,
                per_200k: t1.saturating_sub(t0).max(1),
            }
        }

        /// Instructions per call for the tick count of `reps` calls, rounded to nearest.
        fn instructions(&self, t: u32, reps: u32) -> u32 {
            let overhead = if reps == REPS {
                self.overhead[0]
            } else {
                self.overhead[1]
            };
            let t = t.saturating_sub(overhead) as u64;
            let d = self.per_200k as u64 * reps as u64;
            ((t * 200_000 + d / 2) / d) as u32
        }
    }

    /// Room for this many named counts.
    const CAP: usize = 64;

    /// Measures everything first and prints at the end: semihosting I/O between measurements
    /// perturbs QEMU's virtual clock on some boards.
    struct Table {
        rows: [(&'static str, u32, u32); CAP],
        len: usize,
    }

    impl Table {
        fn push(&mut self, name: &'static str, ticks: u32, reps: u32) {
            if let Some(row) = self.rows.get_mut(self.len) {
                *row = (name, ticks, reps);
                self.len += 1;
            }
        }
    }

    /// `count!(table, "name", || expr)` measures `REPS` calls;
    /// `count!(table, "name", heavy, || expr)` measures `REPS_HEAVY` calls.
    macro_rules! count {
        ($table:expr, $name:expr, heavy, $f:expr) => {{
            let t = ticks_reps(REPS_HEAVY, $f);
            $table.push($name, t, REPS_HEAVY);
        }};
        ($table:expr, $name:expr, $f:expr) => {{
            let t = ticks_reps(REPS, $f);
            $table.push($name, t, REPS);
        }};
    }

    #[entry]
    fn main() -> ! {
        let mut cp = match cortex_m::Peripherals::take() {
            Some(p) => p,
            None => exit(debug::EXIT_FAILURE),
        };
        cp.SYST.set_clock_source(SystClkSource::Core);
        cp.SYST.set_reload(MASK);
        cp.SYST.clear_current();
        cp.SYST.enable_counter();

        let cal = Calibration::new();
        let mut table = Table {
            rows: [("", 0, 0); CAP],
            len: 0,
        };

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
                coning2_update, four_sample_terms, one_plus_previous_terms, three_sample_terms,
            };
            use gyrostat::propagation::exponential::{
                apply_rotation_vector, step_constant_rate_unchecked,
            };
            use gyrostat::propagation::rate_samples::{
                cf4_step, gauss_rates, magnus4_step, midpoint_rate, rk4_step,
            };
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
            count!(table, "prop_exp_step_fast_f32", || fast.apply(
                step_constant_rate_unchecked(black_box(a), black_box(w), black_box(dt))
            ));
            count!(table, "prop_coning1_fast_f32", || apply_rotation_vector(
                black_box(a),
                one_plus_previous_terms(black_box(t1), black_box(t2)),
                fast
            ));
            count!(table, "prop_coning3_fast_f32", || apply_rotation_vector(
                black_box(a),
                three_sample_terms(black_box(t1), black_box(t2), black_box(t3)),
                fast
            ));
            count!(table, "prop_coning4_fast_f32", || apply_rotation_vector(
                black_box(a),
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
                apply_rotation_vector(black_box(a), x.take(), fast)
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
                fast.apply_quat(rk4_step(
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
            .rotated(black_box(w).scale(black_box(dt)), fast));
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
                    RateIntegrator::new(a, method, fast, dt),
                    RateIntegrator::new(ca, method, fast, dt),
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
            use gyrostat::fixed::Q30;
            use gyrostat::propagation::coning::{
                coning2_update, four_sample_terms, one_plus_previous_terms,
            };
            use gyrostat::propagation::exponential::apply_rotation_vector;
            use gyrostat::propagation::{ConingAccumulator, Normalization};
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
            count!(table, "prop_coning1_fast_q30", || apply_rotation_vector(
                black_box(aq),
                one_plus_previous_terms(black_box(t1), black_box(t2)),
                fast
            ));
            count!(table, "prop_coning4_fast_q30", || apply_rotation_vector(
                black_box(aq),
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
            let qe = Euler::new(EulerSequence::ZYX, e).to_unit_quat();
            let lock = Euler::new(
                EulerSequence::ZYX,
                [0.3f32, core::f32::consts::FRAC_PI_2, 0.1],
            )
            .to_unit_quat();
            let zyx = EulerSequence::ZYX;
            let zyz = EulerSequence::ZYZ;
            count!(table, "rot_euler_to_quat_zyx_f32", || Euler::new(
                zyx,
                black_box(e)
            )
            .to_unit_quat());
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
                    g.state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.1, 0.5, 0.2), [0.0; 4])
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
                    g.state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.1, 0.5, 0.2), [0.0; 4])
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
                        .state_at(black_box(7.5f32)));
                }
            }
        }

        hprintln!(
            "calibration reps={} overhead_ticks={} ticks_per_200000_instructions={}",
            REPS,
            cal.overhead[0],
            cal.per_200k
        );
        for (name, t, reps) in table.rows.iter().take(table.len) {
            hprintln!("icount {} {}", name, cal.instructions(*t, *reps));
        }
        hprintln!("done");
        exit(debug::EXIT_SUCCESS)
    }

    fn exit(code: debug::ExitStatus) -> ! {
        debug::exit(code);
        loop {
            cortex_m::asm::wfi();
        }
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        debug::exit(debug::EXIT_FAILURE);
        loop {
            cortex_m::asm::wfi();
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
