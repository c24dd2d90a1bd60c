//! Firmware: guest-instruction counts of attitude-filter updates under QEMU — gyrostat's
//! estimator beside the peers a firmware engineer would pick instead (uf-ahrs 0.2.2: VQF,
//! Madgwick, Mahony), compiled into the same image and fed the same samples.
//!
//! ```text
//! cargo run --release --example fw_icount_estimation --target thumbv7em-none-eabihf   # M4F
//! cargo run --release --example fw_icount_estimation --target thumbv6m-none-eabi      # M0
//! ```
//! The method is `fw_icount`'s (`fw/icount.rs`). A filter's state carries from one sample to the
//! next as in firmware, so each row is the average cost of one update over a run of `N` samples
//! of a synthetic, non-repeating IMU stream ([`Motion`]), each filter started fresh at its first
//! sample: gyrostat's estimator initialises from that sample (accelerometer and magnetometer,
//! BROAD's rule), the peers from the true initial attitude (uf-ahrs's Madgwick and Mahony take
//! one; its VQF initialises itself from the first samples). Rows: `est_<filter>_<6d|9d>_<type>`.
//! `calibration_check_sequence_1000` runs a known 1000-instruction loop through the same
//! per-sample measure.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[allow(
    unused_macros,
    reason = "this image counts sequences, not `count!` calls"
)]
#[macro_use]
#[path = "fw/icount.rs"]
mod icount;

#[cfg(target_os = "none")]
mod firmware {
    use crate::icount::{Calibration, Table, exit, spin, start_systick, ticks};
    use core::hint::black_box;
    use cortex_m_rt::entry;
    use cortex_m_semihosting::debug;
    use gyrostat::estimation::{
        Covariance, Estimator, LowPass, Mode, Params, RateRule, RestDetector,
    };
    use gyrostat::propagation::Normalization;
    use gyrostat::{Real, UnitQuat, Vec3};

    /// Sample period (s): 285.7 Hz, BROAD's rate.
    const DT: f32 = 0.0035;
    /// Samples per run.
    const N: usize = 256;
    /// Samples fed before the timed ones (3.6 s): past the estimator's first
    /// `accel_time_constant` (3 s by default), whose updates take the inclination from the
    /// low-pass's running mean without the Kalman update, so that the steady state is counted.
    const WARM: usize = 1024;
    /// Updates per timed chunk: a chunk of the heaviest update (gyrostat's f64 9D in soft float
    /// on the M0, about 3.5·10⁵ instructions) stays far below SysTick's 2^24-tick range.
    const CHUNK: usize = 8;

    /// A synthetic IMU in fast rotation, sampled every `DT`: the body rate is a sum of sinusoids
    /// of incommensurate frequencies (up to about 3 rad/s per axis, so the motion never
    /// repeats), integrated exactly enough for a cost measurement by one midpoint exponential
    /// per sample; the gyroscope adds a bias and noise, the accelerometer reads gravity plus a
    /// bounded translation acceleration and noise, the magnetometer a Berlin-like field (15.8 µT
    /// north, 40.7 µT down, ENU) plus noise, all in the sensor frame. Noise is uniform from a
    /// 32-bit xorshift generator.
    pub struct Motion {
        q: UnitQuat<f32>,
        t: f32,
        state: u32,
    }

    impl Motion {
        pub fn new() -> Self {
            Self {
                q: UnitQuat::from_axis_angle_unchecked(Vec3::new(0.36f32, -0.48, 0.8), 2.6),
                t: 0.0,
                state: 0x9E37_79B9,
            }
        }

        /// The true attitude, sensor → ENU.
        pub fn attitude(&self) -> UnitQuat<f32> {
            self.q
        }

        fn noise(&mut self, amplitude: f32) -> f32 {
            self.state ^= self.state << 13;
            self.state ^= self.state >> 17;
            self.state ^= self.state << 5;
            // Uniform in [-1, 1).
            let u = (self.state >> 8) as f32 * (2.0 / 16_777_216.0) - 1.0;
            amplitude * u
        }

        fn rate(t: f32) -> Vec3<f32> {
            Vec3::new(
                2.1 * sin(1.3 * t) + 0.9 * sin(3.7 * t + 0.4),
                1.7 * sin(2.2 * t + 1.0) + 0.6 * sin(5.3 * t),
                2.5 * sin(0.9 * t + 2.0) + 0.8 * sin(4.1 * t + 0.7),
            )
        }

        /// The next sample `[gx, gy, gz, ax, ay, az, mx, my, mz]` (rad/s, m/s², µT).
        pub fn sample(&mut self) -> [f32; 9] {
            let w = Self::rate(self.t + 0.5 * DT);
            self.q = (self.q * UnitQuat::exp_unchecked(w.scale(DT))).renormalize_fast();
            self.t += DT;
            let t = self.t;
            let bias = Vec3::new(0.011f32, -0.023, 0.007);
            let gravity = Vec3::new(0.0f32, 0.0, 9.81);
            let translation = Vec3::new(
                0.6 * sin(2.9 * t),
                0.5 * cos(1.9 * t + 0.3),
                0.4 * sin(3.3 * t),
            );
            let field = Vec3::new(0.0f32, 15.8, -40.7);
            let g = Self::rate(t) + bias;
            let a = self.q.inverse_rotate(gravity + translation);
            let m = self.q.inverse_rotate(field);
            [
                g.x + self.noise(0.004),
                g.y + self.noise(0.004),
                g.z + self.noise(0.004),
                a.x + self.noise(0.05),
                a.y + self.noise(0.05),
                a.z + self.noise(0.05),
                m.x + self.noise(0.3),
                m.y + self.noise(0.3),
                m.z + self.noise(0.3),
            ]
        }
    }

    /// Net ticks of one `update` per sample over `N` samples of a fresh [`Motion`], in order,
    /// after its first `WARM` samples (updated, not timed): the samples of each chunk of
    /// `CHUNK` are made first (not timed), then the updates are timed, minus the same loop
    /// over the same samples without the update.
    fn sequence_ticks(mut update: impl FnMut(&[f32; 9])) -> u32 {
        let mut motion = Motion::new();
        for _ in 0..WARM {
            let s = motion.sample();
            update(black_box(&s));
        }
        let mut net: u32 = 0;
        for _ in 0..N / CHUNK {
            let mut chunk = [[0.0f32; 9]; CHUNK];
            for s in chunk.iter_mut() {
                *s = motion.sample();
            }
            let t = ticks(|| {
                for s in &chunk {
                    update(black_box(s));
                }
            });
            let base = ticks(|| {
                for s in &chunk {
                    black_box(s);
                }
            });
            net = net.saturating_add(t.saturating_sub(base));
        }
        net
    }

    /// Net ticks of `update` over the inputs `xs` (made before), minus the same loop without it.
    fn array_ticks<V: Copy, R>(xs: &[V], mut update: impl FnMut(V) -> R) -> u32 {
        let t = ticks(|| {
            for &x in xs {
                black_box(update(black_box(x)));
            }
        });
        let base = ticks(|| {
            for &x in xs {
                black_box(x);
            }
        });
        t.saturating_sub(base)
    }

    fn sin(x: f32) -> f32 {
        Real::sin(x)
    }

    fn cos(x: f32) -> f32 {
        Real::cos(x)
    }

    fn vec<T: Real>(s: &[f32; 9], i: usize) -> Vec3<T> {
        let c = |x: f32| T::from_f64(f64::from(x));
        Vec3::new(c(s[i]), c(s[i + 1]), c(s[i + 2]))
    }

    /// gyrostat's estimator, default parameters, one update per sample: 9D (`mag = true`) or
    /// 6D. An update that fails leaves the filter as it was (and shows as a cheap update).
    fn gyrostat_ticks<T: Real>(mag: bool) -> u32 {
        gyrostat_ticks_with::<T>(mag, Params::default())
    }

    /// [`gyrostat_ticks`] with the parameters `params`.
    fn gyrostat_ticks_with<T: Real>(mag: bool, params: Params<T>) -> u32 {
        let Ok(mut f) = Estimator::<T>::try_new(params) else {
            exit(debug::EXIT_FAILURE)
        };
        let dt = T::from_f64(f64::from(DT));
        sequence_ticks(|s| {
            let (g, a) = (vec::<T>(s, 0), vec::<T>(s, 3));
            let out = if mag {
                f.update_9d(g, a, vec::<T>(s, 6), dt)
            } else {
                f.update_6d(g, a, dt)
            };
            black_box(out.is_ok());
        })
    }

    /// [`gyrostat_ticks_with`] (9D, f32) with the strapdown attitude carried compensated
    /// ([`Estimator::try_new_compensated`]).
    fn compensated_ticks(params: Params<f32>) -> u32 {
        let Ok(mut f) = Estimator::try_new_compensated(params) else {
            exit(debug::EXIT_FAILURE)
        };
        sequence_ticks(|s| {
            let (g, a, m) = (vec::<f32>(s, 0), vec::<f32>(s, 3), vec::<f32>(s, 6));
            black_box(f.update_9d(g, a, m, DT).is_ok());
        })
    }

    #[entry]
    fn main() -> ! {
        if start_systick().is_none() {
            exit(debug::EXIT_FAILURE);
        }
        let cal = Calibration::measure();
        let mut table = Table::<32>::empty();
        let n = N as u32;

        // The sequence measure on a known cost: 1000 loop instructions plus about 3 of set-up
        // per sample, as `calibration_check_1000` in fw_icount.
        let t = sequence_ticks(|_| spin(black_box(500)));
        table.push("calibration_check_sequence_1000", t, n);

        table.push("est_gyrostat_9d_f32", gyrostat_ticks::<f32>(true), n);
        table.push("est_gyrostat_6d_f32", gyrostat_ticks::<f32>(false), n);
        table.push("est_gyrostat_9d_f64", gyrostat_ticks::<f64>(true), n);

        // The full mode's rate rules (the default is Magnus-4) and the compensated strapdown
        // attitude.
        let rule = |rate_rule: RateRule| Params::<f32> {
            rate_rule,
            ..Params::default()
        };
        let t = gyrostat_ticks_with::<f32>(true, rule(RateRule::Trapezoid));
        table.push("est_gyrostat_9d_trapezoid_f32", t, n);
        let t = gyrostat_ticks_with::<f32>(true, rule(RateRule::Cf4));
        table.push("est_gyrostat_9d_cf4_f32", t, n);
        let t = compensated_ticks(Params::default());
        table.push("est_gyrostat_9d_compensated_f32", t, n);

        // The light mode (Mode::Light, default correction period 25 ms, and 50 ms).
        let light = |period: f32| Params::<f32> {
            mode: Mode::Light {
                correction_period: period,
            },
            ..Params::default()
        };
        let t = gyrostat_ticks_with::<f32>(true, light(0.025));
        table.push("est_gyrostat_light_9d_f32", t, n);
        let t = gyrostat_ticks_with::<f32>(false, light(0.025));
        table.push("est_gyrostat_light_6d_f32", t, n);
        let t = gyrostat_ticks_with::<f32>(true, light(0.05));
        table.push("est_gyrostat_light50ms_9d_f32", t, n);

        // Where the full update's instructions go: ablations (the difference of two rows is a
        // part) and the parts alone, fed the same samples.
        let no_lag = Params::<f32> {
            mag_delay_estimation_time: 0.0,
            ..Params::default()
        };
        let t = gyrostat_ticks_with::<f32>(true, no_lag);
        table.push("part_full_9d_without_delay_statistics_f32", t, n);
        // The light mode without corrections: prediction, rest detector, low-pass, checks.
        let t = gyrostat_ticks_with::<f32>(true, light(f32::MAX));
        table.push("part_per_sample_only_f32", t, n);
        {
            let mut q = Motion::new().attitude();
            let t = sequence_ticks(|s| {
                let w = vec::<f32>(s, 0);
                q = black_box(q.mul_exp_unchecked(w.scale(DT), Normalization::Fast));
            });
            table.push("part_prediction_f32", t, n);
            let mut p = Covariance::<f32>::diagonal(1e-4, 1e-5);
            let t = sequence_ticks(|s| {
                let r = q.to_rotation_matrix().scale(-s[0] * 1e-3);
                p.predict(black_box(r), 1e-9, 1e-12);
                black_box(&p);
            });
            table.push("part_covariance_propagation_f32", t, n);
            let mut lp = LowPass::at(Vec3::new(0.0f32, 0.0, 9.81));
            let t = sequence_ticks(|s| {
                let a = q.rotate(vec::<f32>(s, 3));
                let k = LowPass::gain(3.0f32, DT);
                black_box(lp.update(a, k));
            });
            table.push("part_lowpass_inertial_f32", t, n);
            let mut rest = RestDetector::new(Vec3::ZERO, Vec3::new(0.0f32, 0.0, 9.81));
            let th = Params::<f32>::default().rest;
            let t = sequence_ticks(|s| {
                black_box(rest.update(vec::<f32>(s, 0), vec::<f32>(s, 3), DT, &th));
            });
            table.push("part_rest_detector_f32", t, n);
        }
        {
            // Fixed point against soft float on one per-sample piece (issue 30, item 1): the
            // low-pass's two stages `y ← y + k·(x − y)` alone on the same specific forces,
            // f32 and Q7.24 (m/s², range ±128; the gain 0.0023 quantised to 2⁻²⁴). The inputs
            // are converted before the timed loop, as a fixed-point path would get them from
            // the sensor's integers.
            use gyrostat::Ring;
            use gyrostat::real::Q24;
            let mut motion = Motion::new();
            let mut a32 = [Vec3::<f32>::ZERO; N];
            let mut a24 = [Vec3::new(Q24::ZERO, Q24::ZERO, Q24::ZERO); N];
            for (x, y) in a32.iter_mut().zip(a24.iter_mut()) {
                *x = vec::<f32>(&motion.sample(), 3);
                *y = Vec3::<Q24>::try_from_f32(*x).unwrap_or(*y);
            }
            let k = LowPass::gain(3.0f32, DT);
            let kq = Q24::try_from_f32(k).unwrap_or(Q24::ZERO);
            let mut lp = LowPass::at(a32[0]);
            let t = array_ticks(&a32, |x| black_box(lp.update(x, k)));
            table.push("part_lowpass_stages_f32", t, n);
            let (mut s1, mut s2) = (a24[0], a24[0]);
            let t = array_ticks(&a24, |x| {
                s1 += (x - s1).scale(kq);
                s2 += (s1 - s2).scale(kq);
                black_box(s2)
            });
            table.push("part_lowpass_stages_q24", t, n);
        }

        {
            // The peers: uf-ahrs 0.2.2 (f32, nalgebra types), updated through its `Ahrs` trait
            // as a user would (`update`: gyroscope + accelerometer + magnetometer, `update_imu`:
            // gyroscope + accelerometer; each returns the attitude); Madgwick with BROAD's best
            // common beta 0.12, Mahony and VQF with uf-ahrs's defaults (Mahony's are BROAD's
            // best common gains kp 0.74, ki 0.0012). uf-ahrs's attitudes are sensor → NWU
            // (x towards magnetic north): the true initial attitude turned by −90° about z.
            use core::time::Duration;
            use nalgebra::{Quaternion, UnitQuaternion, Vector3};
            use uf_ahrs::{Ahrs, Madgwick, MadgwickParams, Mahony, MahonyParams, Vqf, VqfParams};
            let dt = Duration::from_secs_f32(DT);
            let enu_to_nwu =
                UnitQuat::from_axis_angle_unchecked(Vec3::Z, -core::f32::consts::FRAC_PI_2);
            let q0 = *(enu_to_nwu * Motion::new().attitude()).as_quat();
            let q0_nwu = UnitQuaternion::from_quaternion(Quaternion::new(q0.w, q0.x, q0.y, q0.z));
            let split = |s: &[f32; 9]| {
                let [gx, gy, gz, ax, ay, az, mx, my, mz] = *s;
                (
                    Vector3::new(gx, gy, gz),
                    Vector3::new(ax, ay, az),
                    Vector3::new(mx, my, mz),
                )
            };

            let mut f = Vqf::new(dt, VqfParams::default());
            let t = sequence_ticks(|s| {
                let (g, a, m) = split(s);
                black_box(f.update(g, a, m));
            });
            table.push("est_ufahrs_vqf_9d_f32", t, n);
            let mut f = Vqf::new(dt, VqfParams::default());
            let t = sequence_ticks(|s| {
                let (g, a, _) = split(s);
                black_box(f.update_imu(g, a));
            });
            table.push("est_ufahrs_vqf_6d_f32", t, n);

            let beta = MadgwickParams { beta: 0.12 };
            let mut f = Madgwick::new_with_orientation(dt, beta, q0_nwu);
            let t = sequence_ticks(|s| {
                let (g, a, m) = split(s);
                black_box(f.update(g, a, m));
            });
            table.push("est_ufahrs_madgwick_9d_f32", t, n);
            let mut f = Madgwick::new_with_orientation(dt, beta, q0_nwu);
            let t = sequence_ticks(|s| {
                let (g, a, _) = split(s);
                black_box(f.update_imu(g, a));
            });
            table.push("est_ufahrs_madgwick_6d_f32", t, n);

            let gains = MahonyParams::default();
            let mut f = Mahony::new_with_orientation(dt, gains, q0_nwu);
            let t = sequence_ticks(|s| {
                let (g, a, m) = split(s);
                black_box(f.update(g, a, m));
            });
            table.push("est_ufahrs_mahony_9d_f32", t, n);
            let mut f = Mahony::new_with_orientation(dt, gains, q0_nwu);
            let t = sequence_ticks(|s| {
                let (g, a, _) = split(s);
                black_box(f.update_imu(g, a));
            });
            table.push("est_ufahrs_mahony_6d_f32", t, n);
        }

        table.print(&cal);
        exit(debug::EXIT_SUCCESS)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
