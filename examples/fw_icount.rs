//! Firmware: deterministic guest-instruction counts of named operations under QEMU.
//!
//! ```text
//! cargo run --release --example fw_icount --target thumbv7em-none-eabihf   # Cortex-M4F
//! cargo run --release --example fw_icount --target thumbv6m-none-eabi      # Cortex-M0
//! ```
//! The runner (`.cargo/config.toml`) starts QEMU with `-icount shift=7,align=off,sleep=off`: each
//! guest instruction advances virtual time by 128 ns, so SysTick (clock source = core) ticks are
//! a deterministic function of the instructions executed. The 24-bit SysTick down-counter is read
//! around each operation; the tick/instruction ratio is calibrated with a `subs`/`bne` loop of
//! known length (200 000 instructions); each operation runs 64 times in a loop whose empty cost
//! is subtracted, and the count is per call. Counts are guest
//! instructions (QEMU has no cycle model), identical on every run.
//!
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

    /// Ticks of `REPS` calls of `f`.
    #[inline(always)]
    fn ticks_reps<R>(f: impl Fn() -> R) -> u32 {
        ticks(|| {
            for _ in 0..black_box(REPS) {
                black_box(f());
            }
        })
    }

    struct Calibration {
        /// Ticks of `REPS` empty iterations (loop and `black_box` overhead).
        overhead: u32,
        /// Ticks per 200 000 instructions.
        per_200k: u32,
    }

    impl Calibration {
        fn new() -> Self {
            // The first readings after SysTick starts are skewed by the timer's start-up in
            // QEMU; a warm-up run of a few thousand instructions settles it.
            spin(black_box(5000));
            let overhead = ticks_reps(|| ());
            let t0 = ticks(|| spin(black_box(1)));
            let t1 = ticks(|| spin(black_box(100_001)));
            // (t1 − t0) is exactly 200 000 instructions: 100 000 more `subs`/`bne` iterations.
            Self {
                overhead,
                per_200k: t1.saturating_sub(t0).max(1),
            }
        }

        /// Instructions per call for the tick count of `REPS` calls, rounded to nearest.
        fn instructions(&self, t: u32) -> u32 {
            let t = t.saturating_sub(self.overhead) as u64;
            let d = self.per_200k as u64 * REPS as u64;
            ((t * 200_000 + d / 2) / d) as u32
        }
    }

    /// Room for this many named counts.
    const CAP: usize = 64;

    /// Measures everything first and prints at the end: semihosting I/O between measurements
    /// perturbs QEMU's virtual clock on some boards.
    struct Table {
        rows: [(&'static str, u32); CAP],
        len: usize,
    }

    impl Table {
        fn push(&mut self, name: &'static str, ticks: u32) {
            if let Some(row) = self.rows.get_mut(self.len) {
                *row = (name, ticks);
                self.len += 1;
            }
        }
    }

    macro_rules! count {
        ($table:expr, $name:expr, $f:expr) => {{
            let t = ticks_reps($f);
            $table.push($name, t);
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
            rows: [("", 0); CAP],
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
        count!(table, "exp_small_angle_f32", || UnitQuat::exp_unchecked(
            black_box(phi)
        ));
        {
            use gyrostat::propagation::coning::{
                coning2_update, four_sample, one_plus_previous, three_sample,
            };
            use gyrostat::propagation::exponential::{
                apply_rotation_vector, step_constant_rate_unchecked,
            };
            use gyrostat::propagation::rate_samples::{
                cf4_step, gauss_rates, magnus4_step, midpoint_rate, rk4_step,
            };
            use gyrostat::propagation::{ConingAccumulator, Normalization};
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
                one_plus_previous(black_box(t1), black_box(t2)),
                fast
            ));
            count!(table, "prop_coning3_fast_f32", || apply_rotation_vector(
                black_box(a),
                three_sample(black_box(t1), black_box(t2), black_box(t3)),
                fast
            ));
            count!(table, "prop_coning4_fast_f32", || apply_rotation_vector(
                black_box(a),
                four_sample(black_box(t1), black_box(t2), black_box(t3), black_box(t4)),
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
        }

        hprintln!(
            "calibration reps={} overhead_ticks={} ticks_per_200000_instructions={}",
            REPS,
            cal.overhead,
            cal.per_200k
        );
        for (name, t) in table.rows.iter().take(table.len) {
            hprintln!("icount {} {}", name, cal.instructions(*t));
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
