//! Firmware: the fixed-point (Q1.30) coning propagation on a Cortex-M or RISC-V core under QEMU.
//!
//! ```text
//! cargo run --profile firmware --example fw_fixed --target thumbv6m-none-eabi           # M0, microbit
//! cargo run --profile firmware --example fw_fixed --target thumbv7m-none-eabi           # M3, lm3s6965evb
//! cargo run --profile firmware --example fw_fixed --target thumbv7em-none-eabihf        # M4F, mps2-an386
//! cargo run --profile firmware --example fw_fixed --target thumbv8m.main-none-eabihf    # M33, mps2-an505
//! cargo run --profile firmware --example fw_fixed --target riscv32imac-unknown-none-elf # RV32IMAC, virt
//! ```
//! Runs the built-in coning scenario of `examples/fw/fixed_scenario.rs` (2400 gyro increments of
//! classical coning into the 2-sample hot path, every coning rule and the two-speed accumulator)
//! and prints its lines over semihosting, every number as the hex of its raw Q1.30 integer, then
//! `done` and exit 0 (any library error exits 1). The host test
//! `host-tests/tests/fixed/firmware.rs` runs the same scenario on the host and checks that the
//! boards printed the same bits, and checks the numbers against the closed-form coning
//! attitude in f64.
//!
//! The hot-path entry points are also compiled as separate unmangled functions
//! (`gyrostat_fixed_hot_*`), called once each on opaque inputs: `.ci/check-integer-only`
//! disassembles them and their callees and fails on any soft-float call (M0, M3 and RV32IMAC
//! images) or any floating-point instruction (M4F and M33 images). On the host this example is
//! an empty program.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod firmware {
    use board::{entry, hprintln};
    use core::hint::black_box;
    use gyrostat::fixed::IncrementQuantizer;
    use gyrostat::propagation::CarriedAttitude;
    use gyrostat::propagation::coning::{
        four_sample_terms, one_plus_previous_terms, three_sample_terms,
    };
    use gyrostat::propagation::kernels::coning2_update;
    use gyrostat::propagation::normalization::norm_squared_deviation;
    use gyrostat::propagation::{ConingAccumulator, IncrementIntegrator, Normalization};
    use gyrostat::real::Q30;
    use gyrostat::sensor::RawScale;
    use gyrostat::{Mat3, UnitQuat, Vec3};

    mod board {
        include!("fw/board.rs");
    }

    include!("fw/fixed_scenario.rs");

    // The integer-only hot path, one unmangled function per entry point (see the module docs).

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_quat_product(a: &UnitQuat<Q30>, b: &UnitQuat<Q30>) -> UnitQuat<Q30> {
        *a * *b
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_rotate(q: &UnitQuat<Q30>, v: &Vec3<Q30>) -> Vec3<Q30> {
        q.rotate(*v)
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_matrix(q: &UnitQuat<Q30>) -> Mat3<Q30> {
        q.to_rotation_matrix()
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_exp(phi: &Vec3<Q30>) -> UnitQuat<Q30> {
        UnitQuat::exp_unchecked(*phi)
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_coning2_update(
        q: &UnitQuat<Q30>,
        t1: &Vec3<Q30>,
        t2: &Vec3<Q30>,
    ) -> UnitQuat<Q30> {
        coning2_update(*q, *t1, *t2)
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_coning2_carried(
        q: &CarriedAttitude<30>,
        t1: &Vec3<Q30>,
        t2: &Vec3<Q30>,
    ) -> CarriedAttitude<30> {
        q.coning2_update(*t1, *t2)
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_quantize(
        quant: &mut IncrementQuantizer<30>,
        v: &Vec3<f64>,
    ) -> Option<Vec3<Q30>> {
        quant.try_quantize(*v).ok()
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_quantize_raw(
        quant: &mut IncrementQuantizer<30>,
        s: &RawScale<Q30>,
        raw: &[i16; 3],
    ) -> Vec3<Q30> {
        quant.quantize_raw(s, *raw)
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_coning_rules(q: &UnitQuat<Q30>, t: &[Vec3<Q30>; 4]) -> UnitQuat<Q30> {
        let n = black_box(Normalization::Fast);
        let q = (*q).mul_exp_unchecked(one_plus_previous_terms(t[0], t[1]), n);
        let q = q.mul_exp_unchecked(three_sample_terms(t[0], t[1], t[2]), n);
        q.mul_exp_unchecked(four_sample_terms(t[0], t[1], t[2], t[3]), n)
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_accumulator(
        acc: &mut ConingAccumulator<Q30>,
        q: &UnitQuat<Q30>,
        t: &Vec3<Q30>,
    ) -> UnitQuat<Q30> {
        acc.push_unchecked(*t);
        (*q).mul_exp_unchecked(acc.take(), Normalization::Fast)
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_integrator(
        integ: &mut IncrementIntegrator<Q30>,
        t: &Vec3<Q30>,
    ) -> Option<UnitQuat<Q30>> {
        integ.push(*t).ok().flatten()
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_renormalize(q: &UnitQuat<Q30>) -> (UnitQuat<Q30>, UnitQuat<Q30>, Q30) {
        (
            q.renormalize_fast(),
            q.renormalize(),
            norm_squared_deviation(*q),
        )
    }

    #[unsafe(no_mangle)]
    #[inline(never)]
    fn gyrostat_fixed_hot_raw_increment(s: &RawScale<Q30>, raw: &[i16; 3]) -> Vec3<Q30> {
        s.apply(*raw)
    }

    /// Calls every hot-path function once on opaque inputs (so that each is linked).
    fn exercise_hot_path() -> Result<(), gyrostat::Error> {
        let q = black_box(UnitQuat::<Q30>::IDENTITY);
        let t = black_box(Vec3::<Q30>::try_from_f64(Vec3::new(1e-3, -2e-3, 5e-4))?);
        let scale = black_box(RawScale::<Q30>::try_new(1e-6)?);
        black_box(gyrostat_fixed_hot_quat_product(&q, &q));
        black_box(gyrostat_fixed_hot_rotate(&q, &t));
        black_box(gyrostat_fixed_hot_matrix(&q));
        black_box(gyrostat_fixed_hot_exp(&t));
        black_box(gyrostat_fixed_hot_coning2_update(&q, &t, &t));
        black_box(gyrostat_fixed_hot_coning2_carried(
            &CarriedAttitude::new(q),
            &t,
            &t,
        ));
        let mut quant = black_box(IncrementQuantizer::new());
        black_box(gyrostat_fixed_hot_quantize(
            &mut quant,
            &black_box(Vec3::new(1e-3, -2e-3, 5e-4)),
        ));
        black_box(gyrostat_fixed_hot_coning_rules(&q, &[t, t, t, t]));
        let mut acc = black_box(ConingAccumulator::new());
        black_box(gyrostat_fixed_hot_accumulator(&mut acc, &q, &t));
        let rule = black_box(gyrostat::propagation::ConingRule::TwoSample);
        let mut integ = IncrementIntegrator::new(q, rule, black_box(Normalization::Fast));
        black_box(gyrostat_fixed_hot_integrator(&mut integ, &t));
        black_box(gyrostat_fixed_hot_renormalize(&q));
        black_box(gyrostat_fixed_hot_raw_increment(&scale, &[1, -2, 3]));
        black_box(gyrostat_fixed_hot_quantize_raw(
            &mut quant,
            &scale,
            &[1, -2, 3],
        ));
        Ok(())
    }

    #[entry]
    fn main() -> ! {
        let r = exercise_hot_path().and_then(|()| run_scenario(&mut |line| hprintln!("{}", line)));
        board::finish(r, format_args!("done"))
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        board::exit(false)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
