// The runtime items of the portable firmware examples, one set per architecture: cortex-m-rt and
// cortex-m-semihosting on ARM, riscv-rt and riscv-semihosting on RISC-V (the two semihosting
// crates share one API). An example includes this file as its `board` module:
// `mod board { include!("fw/board.rs"); }`.

#[cfg(target_arch = "arm")]
pub use cortex_m_rt::entry;
#[cfg(target_arch = "arm")]
pub use cortex_m_semihosting::debug;
#[cfg(target_arch = "arm")]
#[allow(unused_imports)] // for the examples that print
pub use cortex_m_semihosting::hprintln;
#[cfg(target_arch = "riscv32")]
pub use riscv_rt::entry;
#[cfg(target_arch = "riscv32")]
pub use riscv_semihosting::debug;
#[cfg(target_arch = "riscv32")]
#[allow(unused_imports)] // for the examples that print
pub use riscv_semihosting::hprintln;

/// Ends the program with QEMU exit status 0 (`true`) or 1 (`false`) through semihosting; waits
/// for ever where no host answers the request.
pub fn exit(success: bool) -> ! {
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        #[cfg(target_arch = "arm")]
        cortex_m::asm::wfi();
        #[cfg(target_arch = "riscv32")]
        riscv::asm::wfi();
    }
}

/// Ends a run that prints: `done` (the given line) and exit status 0 after success, `error <e>`
/// and exit status 1 after a library error.
#[allow(dead_code)] // for the examples that print
pub fn finish(result: Result<(), gyrostat::Error>, done: core::fmt::Arguments<'_>) -> ! {
    match result {
        Ok(()) => {
            hprintln!("{}", done);
            exit(true)
        }
        Err(e) => {
            hprintln!("error {}", e);
            exit(false)
        }
    }
}
