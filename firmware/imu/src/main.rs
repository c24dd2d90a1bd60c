//! From an IMU's registers to an attitude on a microcontroller: an ICM-42670 (gyro and
//! accelerometer) and an LSM303AGR (its magnetometer) on one I²C bus, read through their
//! embedded-hal 1.0 drivers, stamped by a 1 MHz timer, turned into an attitude by gyrostat's
//! sensor layer, estimator and strapdown path.
//!
//! ```sh
//! cargo run --profile firmware -p gyrostat-fw-imu --target thumbv7em-none-eabihf > imu.defmt   # M4F, defmt
//! defmt-print -e target/thumbv7em-none-eabihf/firmware/fw_imu --log-format '{s}' < imu.defmt
//! cargo run --profile firmware -p gyrostat-fw-imu --target riscv32imac-unknown-none-elf        # RV32IMAC, text
//! ```
//!
//! Under QEMU there is no sensor: the I²C bus is `ImuBoard`, a device model of the two chips
//! behind the `embedded_hal::i2c::I2c` trait, and the timer is `CaptureTimer`, a model of a
//! free-running 1 MHz counter that latches its value at the IMU's data-ready edge (a timer input
//! capture on the INT1 pin). The model answers the drivers' register accesses with the rows of a
//! real log (`src/replay.rs`: BROAD trial 07, quantised to the chips' LSB and full scale, with a
//! saturated register, a missed data-ready and a stuck sensor). On a board, these two are the
//! HAL's I²C peripheral and timer: nothing else changes (README, "On a microcontroller").
//!
//! The output: an attitude line every 250 samples (the estimator's and the strapdown's
//! quaternion as raw f32 bits), the estimator's gyro bias and the counters of the faults, then
//! `done`; with defmt over semihosting on ARM, as text over semihosting on RISC-V. The host test
//! `host-tests/tests/sensor/imu_replay.rs` runs the driver-free half (`src/replay.rs`) on the
//! host and checks that both boards printed the same bits. On ARM the image also prints the
//! instructions per sample (QEMU `-icount`, SysTick) and the stack high-water mark (painted
//! stack), for the README. On the host this program is empty.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod firmware {
    use core::cell::RefCell;
    use embedded_hal::i2c::{ErrorKind, ErrorType, I2c, NoAcknowledgeSource, Operation};
    use embedded_hal_bus::i2c::RefCellDevice;
    use gyrostat::UnitQuat;
    use icm42670::prelude::*;
    use icm42670::{AccelOdr, AccelRange, Address, GyroOdr, GyroRange, Icm42670};
    use lsm303agr::{Lsm303agr, MagMode, MagOutputDataRate};
    use replay::{Line, MAG_EVERY, MISSED_DRDY_ROW, ROWS, RawSample, Replay, row, row_time_us};

    mod board {
        include!("../../../examples/fw/board.rs");
    }

    #[allow(dead_code)] // the host test uses the rest
    mod replay {
        include!("replay.rs");
    }

    /// ICM-42670 I²C address (AP_AD0 low) and the registers the model implements.
    const ICM: u8 = 0x68;
    const ICM_ACCEL_DATA_X1: u8 = 0x0B;
    const ICM_GYRO_DATA_X1: u8 = 0x11;
    const ICM_PWR_MGMT0: u8 = 0x1F;
    const ICM_GYRO_CONFIG0: u8 = 0x20;
    const ICM_ACCEL_CONFIG0: u8 = 0x21;
    /// INT_STATUS_DRDY: bit 0 DATA_RDY_INT, cleared by the read. The driver has no call for
    /// it; the firmware reads it directly on the shared bus.
    const ICM_INT_STATUS_DRDY: u8 = 0x39;
    const ICM_WHO_AM_I: u8 = 0x75;
    /// LSM303AGR accelerometer and magnetometer I²C addresses and magnetometer registers.
    const LSM_ACCEL: u8 = 0x19;
    const LSM_MAG: u8 = 0x1E;
    const LSM_WHO_AM_I_A: u8 = 0x0F;
    const LSM_WHO_AM_I_M: u8 = 0x4F;
    const LSM_CFG_REG_A_M: u8 = 0x60;
    const LSM_STATUS_REG_M: u8 = 0x67;
    const LSM_OUTX_L_REG_M: u8 = 0x68;
    /// STATUS_REG_M: ZYXDA (new data), ZYXOR (overrun: new data over unread data).
    const ZYXDA: u8 = 0x08;
    const ZYXOR: u8 = 0x80;

    /// A bus access the model does not answer: no device at that address.
    #[derive(Debug, Clone, Copy)]
    pub struct Nack;

    impl embedded_hal::i2c::Error for Nack {
        fn kind(&self) -> ErrorKind {
            ErrorKind::NoAcknowledge(NoAcknowledgeSource::Address)
        }
    }

    /// One chip's register file and its address pointer (auto-increment on every access).
    struct Chip {
        regs: [u8; 128],
        pointer: u8,
    }

    impl Chip {
        fn new(reset: &[(u8, u8)]) -> Self {
            let mut regs = [0u8; 128];
            for &(r, v) in reset {
                regs[usize::from(r & 0x7F)] = v;
            }
            Self { regs, pointer: 0 }
        }

        fn reg(&mut self, r: u8) -> &mut u8 {
            &mut self.regs[usize::from(r & 0x7F)]
        }
    }

    /// The device model of the board's I²C bus: an ICM-42670 at 0x68 and an LSM303AGR at 0x19
    /// (accelerometer, configured by the driver's `init`, otherwise unused) and 0x1E
    /// (magnetometer), answering with the rows of the replayed log.
    ///
    /// Time advances with the firmware's polls of INT_STATUS_DRDY: each poll is one sample
    /// period, in which the next row arrives: its gyro and accelerometer registers (big-endian,
    /// as the ICM-42670 stores them) and, on every third row, the magnetometer's (little-endian,
    /// status ZYXDA set, ZYXOR too if the previous field was not read). The poll returns
    /// DATA_RDY_INT set, except for `MISSED_DRDY_ROW` (its registers are there, overwritten by the
    /// next row before the firmware reads them). After the last row every poll returns 0.
    /// Data registers read −32768 (the ICM-42670's "no data") unless the sensors are on in
    /// low-noise mode at the full scales the log was quantised to (±2000 °/s, ±4 g); the
    /// magnetometer gives new data only in continuous mode.
    pub struct ImuBoard {
        icm: Chip,
        lsm_accel: Chip,
        lsm_mag: Chip,
        next_row: usize,
        capture_us: u32,
    }

    impl ImuBoard {
        pub fn new() -> Self {
            Self {
                icm: Chip::new(&[
                    (ICM_WHO_AM_I, 0x67),
                    (ICM_GYRO_CONFIG0, 0x06),
                    (ICM_ACCEL_CONFIG0, 0x06),
                ]),
                lsm_accel: Chip::new(&[(LSM_WHO_AM_I_A, 0x33)]),
                lsm_mag: Chip::new(&[(LSM_WHO_AM_I_M, 0x40), (LSM_CFG_REG_A_M, 0x03)]),
                next_row: 0,
                capture_us: 0,
            }
        }

        /// One sample period: the next row arrives. Returns INT_STATUS_DRDY.
        fn advance(&mut self) -> u8 {
            let k = self.next_row;
            let Some(r) = row(k) else {
                return 0;
            };
            self.next_row += 1;
            self.capture_us = row_time_us(k);
            let imu_on = *self.icm.reg(ICM_PWR_MGMT0) & 0x0F == 0x0F
                && *self.icm.reg(ICM_GYRO_CONFIG0) >> 5 & 3 == 0
                && *self.icm.reg(ICM_ACCEL_CONFIG0) >> 5 & 3 == 2;
            for (i, &v) in r[..6].iter().enumerate() {
                let base = if i < 3 {
                    ICM_GYRO_DATA_X1
                } else {
                    ICM_ACCEL_DATA_X1
                };
                let [hi, lo] = (if imu_on { v } else { i16::MIN }).to_be_bytes();
                let at = base + 2 * (i as u8 % 3);
                *self.icm.reg(at) = hi;
                *self.icm.reg(at + 1) = lo;
            }
            let mag_on = *self.lsm_mag.reg(LSM_CFG_REG_A_M) & 0x03 == 0;
            if mag_on && k.is_multiple_of(MAG_EVERY) {
                for (i, &v) in r[6..].iter().enumerate() {
                    let [lo, hi] = v.to_le_bytes();
                    *self.lsm_mag.reg(LSM_OUTX_L_REG_M + 2 * i as u8) = lo;
                    *self.lsm_mag.reg(LSM_OUTX_L_REG_M + 2 * i as u8 + 1) = hi;
                }
                let status = self.lsm_mag.reg(LSM_STATUS_REG_M);
                *status = if *status & ZYXDA != 0 {
                    ZYXDA | ZYXOR
                } else {
                    ZYXDA
                };
            }
            u8::from(k != MISSED_DRDY_ROW)
        }

        /// The timer's value latched at the last data-ready edge, µs.
        fn capture_us(&self) -> u32 {
            self.capture_us
        }

        fn read(&mut self, address: u8, buf: &mut [u8]) {
            for b in buf {
                *b = match address {
                    ICM => {
                        let p = self.icm.pointer;
                        self.icm.pointer = p.wrapping_add(1) & 0x7F;
                        if p == ICM_INT_STATUS_DRDY {
                            self.advance()
                        } else {
                            *self.icm.reg(p)
                        }
                    }
                    LSM_ACCEL => {
                        let p = self.lsm_accel.pointer;
                        self.lsm_accel.pointer = p.wrapping_add(1) & 0x7F;
                        *self.lsm_accel.reg(p)
                    }
                    _ => {
                        let p = self.lsm_mag.pointer;
                        self.lsm_mag.pointer = p.wrapping_add(1) & 0x7F;
                        if p == LSM_OUTX_L_REG_M {
                            *self.lsm_mag.reg(LSM_STATUS_REG_M) = 0;
                        }
                        *self.lsm_mag.reg(p)
                    }
                };
            }
        }

        fn write(&mut self, address: u8, bytes: &[u8]) {
            let chip = match address {
                ICM => &mut self.icm,
                LSM_ACCEL => &mut self.lsm_accel,
                _ => &mut self.lsm_mag,
            };
            if let Some((&r, data)) = bytes.split_first() {
                // Bit 7 of the LSM303AGR's sub-address asks for auto-increment, which the
                // model always does.
                chip.pointer = r & 0x7F;
                for &v in data {
                    let p = chip.pointer;
                    *chip.reg(p) = v;
                    chip.pointer = p.wrapping_add(1) & 0x7F;
                }
            }
        }
    }

    impl ErrorType for ImuBoard {
        type Error = Nack;
    }

    impl I2c for ImuBoard {
        fn transaction(
            &mut self,
            address: u8,
            operations: &mut [Operation<'_>],
        ) -> Result<(), Nack> {
            if ![ICM, LSM_ACCEL, LSM_MAG].contains(&address) {
                return Err(Nack);
            }
            for op in operations {
                match op {
                    Operation::Write(bytes) => self.write(address, bytes),
                    Operation::Read(buf) => self.read(address, buf),
                }
            }
            Ok(())
        }
    }

    /// A model of a free-running 1 MHz hardware counter with input capture on the IMU's INT1
    /// pin: [`CaptureTimer::capture_us`] is the counter's value at the last data-ready edge.
    /// On a board: the HAL's timer in input-capture mode (or a counter read in the data-ready
    /// interrupt).
    pub struct CaptureTimer<'a>(&'a RefCell<ImuBoard>);

    impl CaptureTimer<'_> {
        pub fn capture_us(&self) -> u32 {
            self.0.borrow().capture_us()
        }
    }

    /// The drivers need a delay for the magnetometer's turn-on; the model is ready at once.
    struct NoDelay;

    impl embedded_hal::delay::DelayNs for NoDelay {
        fn delay_ns(&mut self, _: u32) {}
    }

    /// Why the firmware stopped.
    #[derive(Clone, Copy, Debug)]
    pub enum Stop {
        /// The IMU's driver failed (bus error or wrong chip).
        Imu,
        /// The magnetometer's driver failed (bus error or wrong chip).
        Mag,
        /// The sensor layer or the estimator refused its constants.
        Filter,
    }

    /// Consecutive polls without data-ready after which the replay is over (the sensor went
    /// silent).
    const SILENT_POLLS: u32 = 3;

    /// Per-sample measurement hooks (ARM: SysTick instruction counts).
    pub trait Meter {
        fn start(&mut self);
        fn read_done(&mut self);
        fn filter_done(&mut self, printed: bool);
    }

    /// The whole application: bring the chips up, then one loop iteration per data-ready.
    /// Not inlined, so that its state (bus model, drivers, filter) counts in the measured stack.
    #[inline(never)]
    pub fn run(
        emit: &mut impl FnMut(Line),
        meter: &mut impl Meter,
    ) -> Result<(u32, UnitQuat<f32>), Stop> {
        let bus = RefCell::new(ImuBoard::new());
        let timer = CaptureTimer(&bus);

        // The IMU: ±2000 °/s, ±4 g, 400 Hz (the model replays the log at its own 285.7 Hz).
        let mut imu =
            Icm42670::new(RefCellDevice::new(&bus), Address::Primary).map_err(|_| Stop::Imu)?;
        imu.set_gyro_range(GyroRange::Deg2000)
            .map_err(|_| Stop::Imu)?;
        imu.set_accel_range(AccelRange::G4).map_err(|_| Stop::Imu)?;
        imu.set_gyro_odr(GyroOdr::Hz400).map_err(|_| Stop::Imu)?;
        imu.set_accel_odr(AccelOdr::Hz400).map_err(|_| Stop::Imu)?;
        // The magnetometer: continuous, high resolution, 100 Hz.
        let mut mag = Lsm303agr::new_with_i2c(RefCellDevice::new(&bus));
        if !mag.magnetometer_id().map_err(|_| Stop::Mag)?.is_correct() {
            return Err(Stop::Mag);
        }
        mag.init().map_err(|_| Stop::Mag)?;
        mag.set_mag_mode_and_odr(
            &mut NoDelay,
            MagMode::HighResolution,
            MagOutputDataRate::Hz100,
        )
        .map_err(|_| Stop::Mag)?;
        let mut mag = mag.into_mag_continuous().map_err(|_| Stop::Mag)?;
        // The data-ready status, read on the same bus beside the driver.
        let mut status_reg = RefCellDevice::new(&bus);

        let mut replay = Replay::try_new().map_err(|_| Stop::Filter)?;
        let mut silent = 0;
        let mut polls = 0u32;
        while silent < SILENT_POLLS {
            meter.start();
            let mut status = [0u8];
            status_reg
                .write_read(ICM, &[ICM_INT_STATUS_DRDY], &mut status)
                .map_err(|_| Stop::Imu)?;
            polls += 1;
            if status[0] & 1 == 0 {
                silent += 1;
                continue;
            }
            silent = 0;
            let t_us = timer.capture_us();
            let g = imu.gyro_raw().map_err(|_| Stop::Imu)?;
            let a = imu.accel_raw().map_err(|_| Stop::Imu)?;
            let m = if mag.mag_status().map_err(|_| Stop::Mag)?.xyz_new_data() {
                let f = mag.magnetic_field().map_err(|_| Stop::Mag)?;
                Some([f.x_raw() as i16, f.y_raw() as i16, f.z_raw() as i16])
            } else {
                None
            };
            meter.read_done();
            let sample = RawSample {
                t_us,
                gyro: [g.x, g.y, g.z],
                accel: [a.x, a.y, a.z],
                mag: m,
            };
            let printed = replay.push(&sample, emit).map_err(|_| Stop::Filter)?;
            meter.filter_done(printed);
        }
        replay.finish(emit);
        Ok((polls, replay.attitude()))
    }

    /// Polls expected: one per row, then the silent ones.
    pub const EXPECTED_POLLS: u32 = ROWS as u32 + SILENT_POLLS;

    #[cfg(target_arch = "arm")]
    mod arm {
        use super::{Line, Meter, board, run};
        use core::sync::atomic::{Ordering, compiler_fence};
        use cortex_m::peripheral::{SYST, syst::SystClkSource};
        use defmt_semihosting as _;

        const MASK: u32 = 0x00FF_FFFF;
        /// The word painted over the free stack.
        const PAINT: u32 = 0xCCCC_CCCC;

        unsafe extern "C" {
            /// Lowest address of the stack (cortex-m-rt's linker script).
            static _stack_end: u32;
        }

        /// SysTick instruction counts of the loop (`-icount shift=7`: deterministic), in ticks.
        #[derive(Default)]
        struct SysTickMeter {
            t0: u32,
            t1: u32,
            samples: u32,
            read_ticks: u64,
            filter_ticks: u64,
            filter_max: u32,
        }

        impl Meter for SysTickMeter {
            fn start(&mut self) {
                compiler_fence(Ordering::SeqCst);
                self.t0 = SYST::get_current();
                compiler_fence(Ordering::SeqCst);
            }
            fn read_done(&mut self) {
                compiler_fence(Ordering::SeqCst);
                self.t1 = SYST::get_current();
                compiler_fence(Ordering::SeqCst);
            }
            fn filter_done(&mut self, printed: bool) {
                compiler_fence(Ordering::SeqCst);
                let t2 = SYST::get_current();
                compiler_fence(Ordering::SeqCst);
                // Samples that printed are left out: semihosting I/O is not the loop's cost.
                if !printed {
                    let read = self.t0.wrapping_sub(self.t1) & MASK;
                    let filter = self.t1.wrapping_sub(t2) & MASK;
                    self.samples += 1;
                    self.read_ticks += u64::from(read);
                    self.filter_ticks += u64::from(filter);
                    self.filter_max = self.filter_max.max(filter);
                }
            }
        }

        /// `2·n` instructions (`subs` + `bne`).
        #[inline(always)]
        fn spin(n: u32) {
            // SAFETY: register arithmetic only.
            unsafe {
                core::arch::asm!("2:", "subs {0}, #1", "bne 2b", inout(reg) n => _, options(nomem, nostack));
            }
        }

        /// SysTick ticks per 200 000 instructions.
        fn calibrate() -> u32 {
            let ticks = |n: u32| {
                let c0 = SYST::get_current();
                compiler_fence(Ordering::SeqCst);
                spin(core::hint::black_box(n));
                compiler_fence(Ordering::SeqCst);
                c0.wrapping_sub(SYST::get_current()) & MASK
            };
            spin(5000);
            let t0 = ticks(1);
            ticks(100_001).wrapping_sub(t0).max(1)
        }

        fn per_sample(ticks: u64, samples: u32, per_200k: u32) -> u32 {
            let d = u64::from(per_200k) * u64::from(samples.max(1));
            ((ticks * 200_000 + d / 2) / d) as u32
        }

        #[inline(always)]
        fn stack_pointer() -> usize {
            let sp: usize;
            // SAFETY: reads the stack pointer; no memory access.
            unsafe { core::arch::asm!("mov {}, sp", out(reg) sp, options(nomem, nostack)) };
            sp
        }

        fn emit(line: Line) {
            match line {
                Line::Attitude {
                    n,
                    est: e,
                    strapdown: s,
                } => defmt::println!(
                    "att {=u32} {=u32} {=u32} {=u32} {=u32} sd {=u32} {=u32} {=u32} {=u32}",
                    n,
                    e[0],
                    e[1],
                    e[2],
                    e[3],
                    s[0],
                    s[1],
                    s[2],
                    s[3]
                ),
                Line::Bias(b) => defmt::println!("bias {=u32} {=u32} {=u32}", b[0], b[1], b[2]),
                Line::Counters(c) => defmt::println!(
                    "count samples {=u32} mag {=u32} late {=u32} gaps {=u32} clipped {=u32} stuck {=u32} skipped {=u32} rejected {=u32} time_us {=u32}",
                    c.samples,
                    c.mag,
                    c.late,
                    c.gaps,
                    c.clipped,
                    c.stuck,
                    c.skipped,
                    c.rejected,
                    c.time_us
                ),
            }
        }

        #[board::entry]
        fn main() -> ! {
            let Some(mut cp) = cortex_m::Peripherals::take() else {
                board::exit(false)
            };
            cp.SYST.set_clock_source(SystClkSource::Core);
            cp.SYST.set_reload(MASK);
            cp.SYST.clear_current();
            cp.SYST.enable_counter();
            let per_200k = calibrate();

            // Paint the free stack below this frame; the replay's deepest use shows after it.
            let top = stack_pointer() - 64;
            let mut p = core::ptr::addr_of!(_stack_end) as usize;
            while p < top {
                // SAFETY: [_stack_end, top) is free stack below the live frames, word-aligned.
                unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
                p += 4;
            }
            let mut meter = SysTickMeter::default();
            let result = run(&mut emit, &mut meter);
            let mut p = core::ptr::addr_of!(_stack_end) as usize;
            // SAFETY: the painted range; nothing else writes it now.
            while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
                p += 4;
            }
            match result {
                Ok((polls, attitude)) => {
                    // The library's `defmt::Format` (feature `defmt`), for reading, not compared.
                    defmt::println!("final attitude {}", attitude);
                    defmt::println!(
                        "loop instructions per data-ready sample: read {=u32} filter {=u32} (max {=u32}), over {=u32} samples without output; stack {=u32} bytes",
                        per_sample(meter.read_ticks, meter.samples, per_200k),
                        per_sample(meter.filter_ticks, meter.samples, per_200k),
                        per_sample(u64::from(meter.filter_max), 1, per_200k),
                        meter.samples,
                        (stack_pointer() - p) as u32
                    );
                    defmt::println!("polls {=u32}", polls);
                    defmt::println!("done");
                    board::exit(polls == super::EXPECTED_POLLS)
                }
                Err(e) => {
                    defmt::println!("error {}", e as u8);
                    board::exit(false)
                }
            }
        }

        #[panic_handler]
        fn panic(_: &core::panic::PanicInfo) -> ! {
            board::exit(false)
        }
    }

    #[cfg(target_arch = "riscv32")]
    mod riscv {
        use super::{Meter, board, run};
        use board::hprintln;

        struct NoMeter;

        impl Meter for NoMeter {
            fn start(&mut self) {}
            fn read_done(&mut self) {}
            fn filter_done(&mut self, _: bool) {}
        }

        #[board::entry]
        fn main() -> ! {
            match run(&mut |line| hprintln!("{}", line), &mut NoMeter) {
                Ok((polls, attitude)) => {
                    hprintln!("final attitude {:?}", attitude.to_array());
                    hprintln!("polls {}", polls);
                    hprintln!("done");
                    board::exit(polls == super::EXPECTED_POLLS)
                }
                Err(e) => {
                    hprintln!("error {:?}", e);
                    board::exit(false)
                }
            }
        }

        #[panic_handler]
        fn panic(_: &core::panic::PanicInfo) -> ! {
            board::exit(false)
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
