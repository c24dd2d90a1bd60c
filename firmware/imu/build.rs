//! Link setup of the firmware binary (nothing on the host): the runtime's `link.x` (cortex-m-rt
//! on ARM, riscv-rt on RISC-V) with the repository's `memory.x` (origins and lengths per board
//! as in the root `build.rs`), and defmt's `defmt.x` on ARM (its output goes over semihosting).
use std::{env, fs, path::PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=../../memory.x");
    let target = env::var("TARGET").unwrap_or_default();
    let (flash_origin, flash, ram_origin, ram) = if target.starts_with("thumbv7em") {
        ("0x00000000", "4M", "0x20000000", "4M") // mps2-an386 (Cortex-M4F)
    } else if target.starts_with("riscv32") && target.ends_with("-none-elf") {
        ("0x80000000", "4M", "0x80400000", "4M") // QEMU virt, DRAM
    } else {
        return; // the host (and boards this example does not run on): no link setup
    };
    let out = PathBuf::from(env::var("OUT_DIR").unwrap_or_default());
    if fs::copy("../../memory.x", out.join("memory.x")).is_ok() {
        println!("cargo:rustc-link-search={}", out.display());
    }
    println!("cargo:rustc-link-arg-bins=-Tlink.x");
    if target.starts_with("thumb") {
        println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
    }
    for (sym, value) in [
        ("flash_origin", flash_origin),
        ("flash_len", flash),
        ("ram_origin", ram_origin),
        ("ram_len", ram),
    ] {
        println!("cargo:rustc-link-arg-bins=--defsym=_gyrostat_{sym}={value}");
    }
}
