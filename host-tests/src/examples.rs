//! The repository's firmware examples as the tests use them: the bare-metal targets whose
//! firmware output CI hands to the tests.

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
