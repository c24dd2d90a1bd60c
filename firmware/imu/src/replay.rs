// The driver-free half of `firmware/imu/src/main.rs`: raw registers -> sensor layer -> estimator and
// strapdown, and the replayed log. Included by the firmware (as its `replay` module) and by the
// host test `host-tests/tests/sensor/imu_replay.rs`, which runs it on the host and checks that
// the boards printed the same bits.
//
// The log (`imu_log.bin` beside this file, written by `imu_log.py`, which cites its source): 4000 rows of nine
// little-endian i16 registers (gyro x,y,z at ICM-42670 +-2000 deg/s; accel x,y,z at +-4 g;
// magnetometer x,y,z as an LSM303AGR reads them, in its own axes with a hard-iron offset),
// BROAD trial 07 (CC BY 4.0) quantised, with three faults written in or played by the bus:
//
// | fault | rows | what the firmware does (the documented outcome, checked by the host test) |
// |---|---|---|
// | saturated gyro register (+32767) | SATURATED_ROWS (3 rows) | `ClipGuard` flags each (counter `clipped`); policy `HoldLast`: the clipped axis gets its last unclipped reading |
// | missed data-ready | MISSED_DRDY_ROW | the status bit of that row is never set: its registers are overwritten by the next row before the firmware sees them. The next sample's time stamp (the timer capture) is 7000 us after the previous one: one `Step` of 7000 us (counter `late`: a step longer than 1.5 periods), never the nominal 3500 us twice (here across the timer's wrap); the summed intervals (`time_us`) equal the span of the log |
// | stuck sensor | STUCK_ROWS (40 rows) | the same six IMU registers repeated: from the STUCK_AFTER-th repeat on, a sample is not used (counters `stuck` runs, `skipped` samples) and the clock is not advanced; the first fresh sample is then a `Gap` (counter `gaps`): the estimator integrates it over the whole gap (the rate hold of `gyrostat::sensor::timing`) and the strapdown starts again from the estimator's attitude. The rotation during the run is lost: here 78° in 108 ms of fast rotation, of which the rate hold restores 54°; the estimator's error (BROAD's metric) is 34° over the next 500 rows and falls to 16° over the last 800 as the accelerometer and the magnetometer correct it (host test `the_replay_estimate_tracks_the_optical_reference`) |

use gyrostat::estimation::{Estimator, Params};
use gyrostat::propagation::{CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization};
use gyrostat::sensor::timing::micros_to_seconds;
use gyrostat::sensor::{
    AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration, Interval,
    MagnetometerCalibration, MicrosClock, RawScale,
};
use gyrostat::{Error, Mat3, UnitQuat, Vec3};

/// The replayed registers, nine little-endian i16 per row (see the header).
pub const LOG: &[u8] = include_bytes!("imu_log.bin");
/// Bytes per row.
pub const ROW_BYTES: usize = 18;
/// Rows in the log.
pub const ROWS: usize = LOG.len() / ROW_BYTES;
/// The sample period of the log (BROAD: 285.714 Hz), µs.
pub const PERIOD_US: u32 = 3500;
/// The free-running 1 MHz timer's value at row 0: it wraps through 2³² between rows 2000 and
/// 2001 (`wrapping_sub` intervals make the wrap an ordinary step).
pub const T0_US: u32 = 0u32.wrapping_sub(7_001_234);
/// The magnetometer's registers take a new row every third IMU row (95.2 Hz: an LSM303AGR at
/// its 100 Hz output data rate), on rows `k % MAG_EVERY == 0`.
pub const MAG_EVERY: usize = 3;
/// Rows whose gyro x register is at full scale, +32767 (written by `imu_log.py`).
pub const SATURATED_ROWS: core::ops::Range<usize> = 1500..1503;
/// Rows that repeat the IMU registers of the first of them (written by `imu_log.py`).
pub const STUCK_ROWS: core::ops::Range<usize> = 2500..2540;
/// The row whose data-ready status bit the device model never sets.
pub const MISSED_DRDY_ROW: usize = 2001;
/// A reading equal to the previous one in all six IMU registers this many times in a row is a
/// stuck sensor (a real IMU's noise changes some register from sample to sample).
pub const STUCK_AFTER: u32 = 10;
/// The attitude is printed every this many used samples.
pub const PRINT_EVERY: u32 = 250;

/// ICM-42670 gyro at ±2000 °/s: 16.4 LSB per °/s, as rad/s per LSB.
pub const GYRO_LSB_RAD_S: f64 = core::f64::consts::PI / 180.0 / 16.4;
/// ICM-42670 accelerometer at ±4 g: 8192 LSB per g (9.80665 m/s²), as m/s² per LSB.
pub const ACCEL_LSB_M_S2: f64 = 9.80665 / 8192.0;
/// LSM303AGR magnetometer: 1.5 mgauss = 0.15 µT per LSB.
pub const MAG_LSB_UT: f64 = 0.15;
/// The gyro bias (rad/s) from a rest recording before the replayed rows (`imu_log.py` prints
/// it): the factory/rest calibration a firmware stores.
pub const GYRO_BIAS: [f64; 3] = [3.536603133e-03, 2.089805468e-03, -4.044575684e-03];
/// The magnetometer's hard-iron offset in its own axes, µT (a board's calibration).
pub const MAG_HARD_IRON_UT: [f64; 3] = [12.0, -7.5, 4.5];
/// The magnetometer's mounting on the board: IMU x = −chip y, IMU y = chip x, IMU z = chip z.
pub const MAG_MOUNTING: &str = "-y,x,z";

/// One row of the log: gyro, accel, magnetometer registers.
pub fn row(k: usize) -> Option<[i16; 9]> {
    let bytes = LOG.get(k * ROW_BYTES..(k + 1) * ROW_BYTES)?;
    let mut out = [0i16; 9];
    for (o, pair) in out.iter_mut().zip(bytes.chunks_exact(2)) {
        *o = i16::from_le_bytes([pair[0], pair[1]]);
    }
    Some(out)
}

/// The timer capture at row `k`'s data-ready edge, µs (1 MHz, wrapping).
pub fn row_time_us(k: usize) -> u32 {
    T0_US.wrapping_add((k as u32).wrapping_mul(PERIOD_US))
}

/// One sample as the firmware reads it: the timer capture and the raw registers; the
/// magnetometer only when its status said new data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RawSample {
    /// Timer capture at data-ready, µs (wrapping u32).
    pub t_us: u32,
    /// Gyro registers x, y, z.
    pub gyro: [i16; 3],
    /// Accelerometer registers x, y, z.
    pub accel: [i16; 3],
    /// Magnetometer registers x, y, z (chip axes), when new.
    pub mag: Option<[i16; 3]>,
}

/// The samples the firmware sees, without any bus: every row whose data-ready bit is set, the
/// magnetometer's newest unread row with it (the rule the device model of `main.rs` plays).
pub fn samples(mut f: impl FnMut(&RawSample) -> Result<(), Error>) -> Result<(), Error> {
    let mut mag_unread = None;
    for k in 0..ROWS {
        let r = row(k).ok_or(Error::InvalidArgument)?;
        if k.is_multiple_of(MAG_EVERY) {
            mag_unread = Some([r[6], r[7], r[8]]);
        }
        if k == MISSED_DRDY_ROW {
            continue;
        }
        f(&RawSample {
            t_us: row_time_us(k),
            gyro: [r[0], r[1], r[2]],
            accel: [r[3], r[4], r[5]],
            mag: mag_unread.take(),
        })?;
    }
    Ok(())
}

/// What the replay counted (printed at the end; see the fault table in the header).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Samples used (estimator updates).
    pub samples: u32,
    /// Of those, with a magnetometer reading (9D updates).
    pub mag: u32,
    /// Steps longer than 1.5 periods but not gaps (a missed data-ready).
    pub late: u32,
    /// Gaps (longer than the clock's gap factor, 5 periods).
    pub gaps: u32,
    /// Samples with a clipped gyro axis.
    pub clipped: u32,
    /// Stuck runs detected.
    pub stuck: u32,
    /// Samples not used because the sensor was stuck.
    pub skipped: u32,
    /// Samples refused by the clock (repeated or backwards time stamp) or the estimator.
    pub rejected: u32,
    /// Sum of the intervals integrated, µs.
    pub time_us: u32,
}

/// A line of the replay's output; every float is printed as its raw f32 bits (decimal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Line {
    /// After `n` used samples: the estimator's attitude and the strapdown attitude, w, x, y, z.
    Attitude { n: u32, est: [u32; 4], strapdown: [u32; 4] },
    /// The estimator's gyro bias at the end, rad/s.
    Bias([u32; 3]),
    /// The counters at the end.
    Counters(Counters),
}

impl core::fmt::Display for Line {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Line::Attitude { n, est: e, strapdown: s } => write!(
                f,
                "att {} {} {} {} {} sd {} {} {} {}",
                n, e[0], e[1], e[2], e[3], s[0], s[1], s[2], s[3]
            ),
            Line::Bias(b) => write!(f, "bias {} {} {}", b[0], b[1], b[2]),
            Line::Counters(c) => write!(
                f,
                "count samples {} mag {} late {} gaps {} clipped {} stuck {} skipped {} rejected {} time_us {}",
                c.samples, c.mag, c.late, c.gaps, c.clipped, c.stuck, c.skipped, c.rejected, c.time_us
            ),
        }
    }
}

fn bits4(q: UnitQuat<f32>) -> [u32; 4] {
    q.to_array().map(f32::to_bits)
}

/// The sensor layer, the estimator and the strapdown path, fed one [`RawSample`] at a time.
pub struct Replay {
    gyro_scale: RawScale<f32>,
    accel_scale: RawScale<f32>,
    mag_scale: RawScale<f32>,
    gyro_cal: InertialCalibration<f32>,
    mag_cal: MagnetometerCalibration<f32>,
    mag_mounting: AxisRemap,
    gyro_clip: ClipGuard,
    clock: MicrosClock,
    estimator: Estimator<f32>,
    strapdown: Option<IncrementIntegrator<f32, CompensatedAttitude<f32>>>,
    last_imu: Option<[i16; 6]>,
    repeats: u32,
    counters: Counters,
}

impl Replay {
    /// The pipeline with the constants above and the estimator's default parameters.
    ///
    /// # Errors
    /// A constant the sensor layer refuses (none does).
    pub fn try_new() -> Result<Self, Error> {
        let v = |a: [f64; 3]| Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32);
        Ok(Self {
            gyro_scale: RawScale::<f32>::try_new(GYRO_LSB_RAD_S)?,
            accel_scale: RawScale::<f32>::try_new(ACCEL_LSB_M_S2)?,
            mag_scale: RawScale::<f32>::try_new(MAG_LSB_UT)?,
            gyro_cal: InertialCalibration::try_new(Mat3::IDENTITY, Vec3::new(1.0, 1.0, 1.0), v(GYRO_BIAS))?,
            mag_cal: MagnetometerCalibration::try_new(Mat3::IDENTITY, v(MAG_HARD_IRON_UT))?,
            mag_mounting: AxisRemap::try_parse(MAG_MOUNTING)?,
            gyro_clip: ClipGuard::new(ClipLimit::FULL_REGISTER, ClipPolicy::HoldLast),
            clock: MicrosClock::try_new(PERIOD_US, 5)?,
            estimator: Estimator::try_new(Params::default())?,
            strapdown: None,
            last_imu: None,
            repeats: 0,
            counters: Counters::default(),
        })
    }

    /// The estimator's attitude (sensor → earth, ENU).
    pub fn attitude(&self) -> UnitQuat<f32> {
        self.estimator.attitude()
    }

    /// The counters so far.
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// One sample through the pipeline; `out` gets an [`Line::Attitude`] every
    /// [`PRINT_EVERY`] used samples. Returns whether it printed.
    ///
    /// # Errors
    /// None: a sample the clock or the estimator refuses is counted in `rejected`.
    pub fn push(&mut self, s: &RawSample, out: &mut impl FnMut(Line)) -> Result<bool, Error> {
        // A stuck sensor: the same six registers again and again.
        let imu = [s.gyro[0], s.gyro[1], s.gyro[2], s.accel[0], s.accel[1], s.accel[2]];
        if self.last_imu == Some(imu) {
            self.repeats = self.repeats.saturating_add(1);
        } else {
            self.repeats = 0;
        }
        self.last_imu = Some(imu);
        if self.repeats >= STUCK_AFTER {
            if self.repeats == STUCK_AFTER {
                self.counters.stuck += 1;
            }
            self.counters.skipped += 1;
            return Ok(false);
        }

        // The interval from the timer captures.
        let dt_us = match self.clock.interval(s.t_us) {
            Interval::First => PERIOD_US,
            Interval::Step(dt) => {
                self.counters.time_us = self.counters.time_us.wrapping_add(dt);
                if dt > PERIOD_US + PERIOD_US / 2 {
                    self.counters.late += 1;
                }
                dt
            }
            Interval::Gap(dt) => {
                self.counters.time_us = self.counters.time_us.wrapping_add(dt);
                self.counters.gaps += 1;
                // The rotation in the gap is unknown: the estimator holds this sample's
                // rate over it, the strapdown starts again from the estimator.
                self.strapdown = None;
                dt
            }
            Interval::Repeated | Interval::Backwards(_) => {
                self.counters.rejected += 1;
                return Ok(false);
            }
        };
        let dt: f32 = micros_to_seconds(dt_us);

        // Raw registers -> clipping -> LSB scale -> calibration -> mounting.
        let (gyro_raw, clipped) = self.gyro_clip.filter(s.gyro)?;
        if clipped.any() {
            self.counters.clipped += 1;
        }
        let gyro = self.gyro_cal.apply(self.gyro_scale.apply(gyro_raw));
        let accel = self.accel_scale.apply(s.accel);
        let mag = s
            .mag
            .map(|m| self.mag_mounting.apply(self.mag_cal.apply(self.mag_scale.apply(m))));

        let update = match mag {
            Some(m) => self.estimator.update_9d(gyro, accel, m, dt),
            None => self.estimator.update_6d(gyro, accel, dt),
        };
        if update.is_err() {
            self.counters.rejected += 1;
            return Ok(false);
        }
        if mag.is_some() {
            self.counters.mag += 1;
        }
        self.counters.samples += 1;

        // The strapdown-only path: the calibrated gyro alone, from the estimator's first
        // attitude, started again with it after a gap.
        match &mut self.strapdown {
            Some(sd) => {
                if sd.push(gyro.scale(dt)).is_err() {
                    self.counters.rejected += 1;
                }
            }
            _ => {
                self.strapdown = Some(IncrementIntegrator::new(
                    CompensatedAttitude::new(self.estimator.attitude()),
                    ConingRule::TwoSample,
                    Normalization::Fast,
                ));
            }
        }

        if self.counters.samples.is_multiple_of(PRINT_EVERY) {
            let strapdown = self
                .strapdown
                .as_ref()
                .map_or(UnitQuat::IDENTITY, |sd| sd.provisional_attitude());
            out(Line::Attitude {
                n: self.counters.samples,
                est: bits4(self.estimator.attitude()),
                strapdown: bits4(strapdown),
            });
            return Ok(true);
        }
        Ok(false)
    }

    /// The closing lines: the estimator's bias and the counters.
    pub fn finish(&self, out: &mut impl FnMut(Line)) {
        out(Line::Bias(self.estimator.bias().to_array().map(f32::to_bits)));
        out(Line::Counters(self.counters));
    }
}
