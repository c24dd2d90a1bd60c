//! Firmware: compose and apply a fixed set of rotations in f32 on a Cortex-M or RISC-V core
//! under QEMU.
//!
//! ```text
//! cargo run --profile firmware --example fw_rotations --target thumbv7em-none-eabihf        # M4F, mps2-an386
//! cargo run --profile firmware --example fw_rotations --target thumbv7m-none-eabi          # M3, lm3s6965evb
//! cargo run --profile firmware --example fw_rotations --target thumbv6m-none-eabi          # M0, microbit
//! cargo run --profile firmware --example fw_rotations --target thumbv8m.main-none-eabihf   # M33, mps2-an505
//! cargo run --profile firmware --example fw_rotations --target riscv32imac-unknown-none-elf # RV32IMAC, virt
//! ```
//! For each case of `examples/fw/rotation_cases.rs` it builds `q₁`, `q₂` from axis-angle, the
//! product `q = q₁ ⊗ q₂`, its rotation matrix and the rotated vector, and prints one line
//! `case I q W X Y Z m R00 … R22 v X Y Z` (f32, shortest round-trip form) over semihosting, then
//! exits 0. Any library error exits 1. The host test `host-tests/tests/rotation/firmware.rs` checks
//! the printed numbers against the independent f64 reference. On the host this example is an
//! empty program.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod firmware {
    use board::{entry, hprintln};
    use gyrostat::{Error, UnitQuat, Vec3};

    mod board {
        include!("fw/board.rs");
    }

    include!("fw/rotation_cases.rs");

    fn run() -> Result<(), Error> {
        for (i, (a1, t1, a2, t2, v)) in CASES.iter().enumerate() {
            let q1 = UnitQuat::try_from_axis_angle(Vec3::from_array(*a1), *t1)?;
            let q2 = UnitQuat::try_from_axis_angle(Vec3::from_array(*a2), *t2)?;
            let q = q1 * q2;
            let m = q.to_rotation_matrix().m;
            let r = q.rotate(Vec3::from_array(*v));
            hprintln!(
                "case {} q {:?} {:?} {:?} {:?} m {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} {:?} v {:?} {:?} {:?}",
                i,
                q.w(),
                q.x(),
                q.y(),
                q.z(),
                m[0][0],
                m[0][1],
                m[0][2],
                m[1][0],
                m[1][1],
                m[1][2],
                m[2][0],
                m[2][1],
                m[2][2],
                r.x,
                r.y,
                r.z
            );
        }
        Ok(())
    }

    #[entry]
    fn main() -> ! {
        board::finish(run(), format_args!("done {}", N_CASES))
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        board::exit(false)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
