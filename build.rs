//! Link setup for the firmware examples only: the library itself needs no build step.
//!
//! Bare-metal examples link with their runtime's `link.x` (cortex-m-rt on ARM, riscv-rt on
//! RISC-V), which includes the top-level `memory.x`. One `memory.x` serves every board: its
//! origins and lengths default to the Cortex-M4F board (mps2-an386, 4 MiB + 4 MiB) and this
//! script overrides them per target; the board table and the reasons for each map are in
//! `memory.x`.
use std::env;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=memory.x");
    // `gyrostat_board_small_flash`: the example's board has 256 KiB of flash (Cortex-M0 and M3):
    // `fw_nopanic` checks the f64 estimator only on the larger boards.
    println!("cargo::rustc-check-cfg=cfg(gyrostat_board_small_flash)");
    let target = env::var("TARGET").unwrap_or_default();
    // (FLASH origin, length, RAM origin, length) of the QEMU board each target runs on.
    let (flash_origin, flash, ram_origin, ram) = if target.starts_with("thumbv6m") {
        ("0x00000000", "256K", "0x20000000", "16K") // microbit (nRF51, Cortex-M0)
    } else if target.starts_with("thumbv7m") {
        ("0x00000000", "256K", "0x20000000", "64K") // lm3s6965evb (Cortex-M3)
    } else if target.starts_with("thumbv8m") {
        ("0x10000000", "4M", "0x38000000", "4M") // mps2-an505 (Cortex-M33), secure aliases
    } else if target.starts_with("thumb") {
        ("0x00000000", "4M", "0x20000000", "4M") // mps2-an386 (Cortex-M4F)
    } else if target.starts_with("riscv32") && target.ends_with("-none-elf") {
        ("0x80000000", "4M", "0x80400000", "4M") // QEMU virt, DRAM
    } else {
        return;
    };
    if flash == "256K" {
        println!("cargo::rustc-cfg=gyrostat_board_small_flash");
    }
    println!("cargo:rustc-link-arg-examples=-Tlink.x");
    for (sym, value) in [
        ("flash_origin", flash_origin),
        ("flash_len", flash),
        ("ram_origin", ram_origin),
        ("ram_len", ram),
    ] {
        println!("cargo:rustc-link-arg-examples=--defsym=_gyrostat_{sym}={value}");
    }
}
