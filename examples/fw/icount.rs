// The instruction-counting machinery of the `fw_icount*` firmware examples (ARM only: SysTick),
// included by each as its `icount` module: `#[macro_use] #[path = "fw/icount.rs"] mod icount;`.
//
// The runner (`.cargo/config.toml`) starts QEMU with `-icount shift=7,align=off,sleep=off`: each
// guest instruction advances virtual time by 128 ns, so SysTick (clock source = core) ticks are a
// deterministic function of the instructions executed. The 24-bit SysTick down-counter is read
// around each operation; the tick/instruction ratio is calibrated with a `subs`/`bne` loop of
// known length (200 000 instructions); each operation runs `REPS` times in a loop whose empty cost
// is subtracted, and the count is per call. Counts are guest instructions (QEMU has no cycle
// model), identical on every run.

use core::hint::black_box;
use core::sync::atomic::{Ordering, compiler_fence};
use cortex_m::peripheral::{SYST, syst::SystClkSource};
use cortex_m_semihosting::{debug, hprintln};

const MASK: u32 = 0x00FF_FFFF;

/// Starts SysTick as a free-running 24-bit down-counter on the core clock; `None` if the core
/// peripherals were already taken.
pub fn start_systick() -> Option<()> {
    let mut cp = cortex_m::Peripherals::take()?;
    cp.SYST.set_clock_source(SystClkSource::Core);
    cp.SYST.set_reload(MASK);
    cp.SYST.clear_current();
    cp.SYST.enable_counter();
    Some(())
}

/// SysTick ticks spent in `f` (valid below 2^24 ticks).
#[inline(always)]
pub fn ticks<R>(f: impl FnOnce() -> R) -> u32 {
    let c0 = SYST::get_current();
    compiler_fence(Ordering::SeqCst);
    black_box(f());
    compiler_fence(Ordering::SeqCst);
    let c1 = SYST::get_current();
    c0.wrapping_sub(c1) & MASK
}

/// A loop of exactly `2·n` instructions (`subs` + `bne` per iteration), plus the `n == 0` test
/// and the move of `n` into a register.
#[inline(always)]
pub fn spin(n: u32) {
    if n == 0 {
        return;
    }
    // SAFETY: pure register arithmetic on a scratch register, no memory access.
    unsafe {
        core::arch::asm!("2:", "subs {0}, #1", "bne 2b", inout(reg) n => _, options(nomem, nostack));
    }
}

/// Repetitions per measurement: QEMU's SysTick on some boards (microbit) jitters by about 2% of
/// a short interval; averaging a long interval makes that negligible.
pub const REPS: u32 = 64;
/// Repetitions for heavy operations (a dynamics step in soft float), so that 4 calls stay below
/// the 2^24-tick range of SysTick.
pub const REPS_HEAVY: u32 = 4;

/// Ticks of `reps` calls of `f`.
#[inline(always)]
pub fn ticks_reps<R>(reps: u32, f: impl Fn() -> R) -> u32 {
    ticks(|| {
        for _ in 0..black_box(reps) {
            black_box(f());
        }
    })
}

pub struct Calibration {
    /// Ticks of `REPS` and of `REPS_HEAVY` empty iterations (loop and `black_box` overhead).
    pub overhead: [u32; 2],
    /// Ticks per 200 000 instructions.
    pub per_200k: u32,
}

impl Calibration {
    /// Measures the loop overheads and the tick rate.
    pub fn measure() -> Self {
        // The first readings after SysTick starts are skewed by the timer's start-up in QEMU; a
        // warm-up run of a few thousand instructions settles it.
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
    pub fn instructions(&self, t: u32, reps: u32) -> u32 {
        // Sequence counts (`reps` = the number of samples) come with their loop already
        // subtracted (`sequence_ticks`).
        let overhead = match reps {
            REPS => self.overhead[0],
            REPS_HEAVY => self.overhead[1],
            _ => 0,
        };
        let t = t.saturating_sub(overhead) as u64;
        let d = self.per_200k as u64 * reps as u64;
        ((t * 200_000 + d / 2) / d) as u32
    }
}

/// Measures everything first and prints at the end: semihosting I/O between measurements
/// perturbs QEMU's virtual clock on some boards. Room for `CAP` named counts.
pub struct Table<const CAP: usize> {
    rows: [(&'static str, u32, u32); CAP],
    len: usize,
}

impl<const CAP: usize> Table<CAP> {
    /// A table with no rows.
    pub fn empty() -> Self {
        Self {
            rows: [("", 0, 0); CAP],
            len: 0,
        }
    }

    /// Records `ticks` for `reps` calls of the operation `name` (a row beyond `CAP` is dropped
    /// and `print` says so).
    pub fn push(&mut self, name: &'static str, ticks: u32, reps: u32) {
        if let Some(row) = self.rows.get_mut(self.len) {
            *row = (name, ticks, reps);
        }
        self.len += 1;
    }

    /// Prints the calibration and one line `icount <name> <instructions>` per row, then `done`
    /// (or `error: table full` if rows were dropped, which the CI's `grep '^done'` catches).
    pub fn print(&self, cal: &Calibration) {
        hprintln!(
            "calibration reps={} overhead_ticks={} ticks_per_200000_instructions={}",
            REPS,
            cal.overhead[0],
            cal.per_200k
        );
        for (name, t, reps) in self.rows.iter().take(self.len) {
            hprintln!("icount {} {}", name, cal.instructions(*t, *reps));
        }
        if self.len > CAP {
            hprintln!("error: table full, {} rows dropped", self.len - CAP);
        } else {
            hprintln!("done");
        }
    }
}

/// `count!(table, "name", || expr)` measures `REPS` calls;
/// `count!(table, "name", heavy, || expr)` measures `REPS_HEAVY` calls.
macro_rules! count {
    ($table:expr, $name:expr, heavy, $f:expr) => {{
        let t = $crate::icount::ticks_reps($crate::icount::REPS_HEAVY, $f);
        $table.push($name, t, $crate::icount::REPS_HEAVY);
    }};
    ($table:expr, $name:expr, $f:expr) => {{
        let t = $crate::icount::ticks_reps($crate::icount::REPS, $f);
        $table.push($name, t, $crate::icount::REPS);
    }};
}

pub fn exit(code: debug::ExitStatus) -> ! {
    debug::exit(code);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    exit(debug::EXIT_FAILURE)
}
