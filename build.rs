//! Link setup for the firmware examples only: the library itself needs no build step.
//!
//! For bare-metal ARM targets, the examples link with cortex-m-rt's `link.x`, which includes the
//! top-level `memory.x`. One `memory.x` serves every board: its lengths default to the
//! Cortex-M4F board (mps2-an386, 4 MiB + 4 MiB) and this script overrides them per target.
use std::env;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=memory.x");
    let target = env::var("TARGET").unwrap_or_default();
    if !target.starts_with("thumb") {
        return;
    }
    println!("cargo:rustc-link-arg-examples=-Tlink.x");
    // (flash, ram) of the QEMU board each target runs on (README, "Firmware under QEMU").
    let (flash, ram) = if target.starts_with("thumbv6m") {
        ("256K", "16K") // microbit (nRF51, Cortex-M0)
    } else if target.starts_with("thumbv7m") {
        ("256K", "64K") // lm3s6965evb (Cortex-M3)
    } else {
        ("4M", "4M") // mps2-an386 (Cortex-M4F)
    };
    println!("cargo:rustc-link-arg-examples=--defsym=_gyrostat_flash_len={flash}");
    println!("cargo:rustc-link-arg-examples=--defsym=_gyrostat_ram_len={ram}");
}
