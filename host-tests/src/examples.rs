//! The repository's example programs as the tests use them: the bare-metal targets whose
//! firmware output CI hands to the tests, and the host tools, built on demand.

use std::path::PathBuf;
use std::process::Command;

/// The bare-metal targets `.ci/run` runs the firmware examples on (Cortex-M0, M3, M4F, M33,
/// RV32IMAC); their output files are named after them.
pub const FIRMWARE_TARGETS: [&str; 5] = [
    "thumbv6m-none-eabi",
    "thumbv7m-none-eabi",
    "thumbv7em-none-eabihf",
    "thumbv8m.main-none-eabihf",
    "riscv32imac-unknown-none-elf",
];

/// The firmware output `.ci/run` wrote for each of [`FIRMWARE_TARGETS`]:
/// `$GYROSTAT_FIRMWARE_OUTPUT/<prefix><target>.txt`, as `(target, text)`. Panics (failing the
/// test) when the variable is unset or a file is missing: a check of firmware output must not
/// pass without it.
pub fn firmware_output(prefix: &str) -> Vec<(&'static str, String)> {
    let dir = std::env::var("GYROSTAT_FIRMWARE_OUTPUT")
        .expect("GYROSTAT_FIRMWARE_OUTPUT must name the directory of the firmware output");
    FIRMWARE_TARGETS
        .iter()
        .map(|&target| {
            let path = std::path::Path::new(&dir).join(format!("{prefix}{target}.txt"));
            let text = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            (target, text)
        })
        .collect()
}

/// Builds the host example `name` of the gyrostat package with the profile of the calling test
/// (release when the test is optimised) and returns the path of its binary.
pub fn build_example(name: &str) -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let release = !cfg!(debug_assertions);
    let mut cmd = Command::new(env!("CARGO"));
    cmd.current_dir(&root)
        .args(["build", "-q", "-p", "gyrostat", "--example", name]);
    if release {
        cmd.arg("--release");
    }
    let status = cmd.status().expect("cargo runs");
    assert!(status.success(), "building the {name} example failed");
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    target
        .join(if release { "release" } else { "debug" })
        .join("examples")
        .join(name)
}
