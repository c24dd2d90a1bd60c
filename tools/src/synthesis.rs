//! Motion → measurements: what a 9-axis sensor of a [`SensorSpec`] reads along a [`Motion`] in
//! a magnetic [`Environment`], sample by sample, seeded and deterministic (`synthesize`).
//!
//! # Sample `k`
//! - Instant: `t = k/rate` (a motion file: its row spacing); the log's time stamp is
//!   `t + e` with `e` drawn from N(0, `clock_jitter`²), clipped to ±0.4/rate (the sensor samples
//!   on its own clock, the host stamps the samples late or early). The truth is at `t`.
//! - Gyro: the body rate `ω(t)`.
//! - Accelerometer: the specific force `R(q)ᵀ(a + g·ẑ) + a_body` (ENU: gravity is `−g·ẑ`,
//!   the sensor at rest reads `+g` up), `a` the linear acceleration, `a_body` vibration and taps.
//! - Magnetometer: `R(q(t − d))ᵀ·B(t − d)` with `d` the spec's `mag_delay`, `B` the earth's
//!   field plus the disturbances of the environment, at the rows of its own `mag_rate`.
//! - Each goes through the spec's error model (`sensor_spec`): `raw = K⁻¹·true + b + noise`
//!   (magnetometer `S⁻¹·true + h + h_fixed(t) + noise`), clipped to ±range, rounded to the LSB.
//!
//! # Magnetic environment (earth frame unless stated)
//! - passing magnet `M,D,V`: in the middle of each movement phase a dipole of moment `M` A·m²
//!   (along the fixed unit axis [`MAGNET_AXIS`]) passes the sensor along the east axis at speed
//!   `V` m/s, at closest distance `D` m (north of it). Its field at the sensor's position `p`:
//!   `B = μ0/(4π)·(3 r̂(r̂·m) − m)/|r|³`, `r = p − r_magnet`, `μ0/(4π) = 0.1 µT·m³/(A·m²)`.
//! - steel `ΔB`: in each movement phase a smooth bump `ΔB·sin²(π u/L)` over the middle half
//!   of the phase (`u` from a quarter of the phase, `L` half the phase): the field near steel.
//! - fixed magnet `H[,T]`: a body-frame offset `H` µT added to the raw reading from time `T`
//!   on (a magnet fixed on the device: extra hard iron).

use gyrostat::Vec3;

use crate::motion::{self, Kinematics, Motion, MotionFile, Rotation, Timeline, rotate_inv};
use crate::noise::{NoiseError, Rng, TriadNoise, axis_seed};
use crate::sensor_spec::{Inertial, SensorSpec};

/// The generator of stream `tag` of `seed`: independent streams for the independent parts of a
/// log (noise, jitter, motion), each unchanged when another part changes.
pub fn stream(seed: u64, tag: u64) -> Rng {
    Rng::new(axis_seed(seed, tag))
}

/// The axis of the passing magnet's moment (unit, earth frame).
pub const MAGNET_AXIS: [f64; 3] = [0.48, -0.6, 0.64];

/// The field of a magnetic dipole `m` (A·m²) at `r` (m) from it, µT.
pub fn dipole_field(m: [f64; 3], r: [f64; 3]) -> [f64; 3] {
    let d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    let d = d2.sqrt();
    let rm = (r[0] * m[0] + r[1] * m[1] + r[2] * m[2]) / d2;
    core::array::from_fn(|k| 0.1 * (3.0 * r[k] * rm - m[k]) / (d2 * d))
}

/// The magnetic disturbances of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Environment {
    /// A passing magnet: moment (A·m²), closest distance (m), speed (m/s).
    pub passing: Option<[f64; 3]>,
    /// The peak field change near steel (µT, earth frame).
    pub steel: Option<[f64; 3]>,
    /// A magnet fixed on the device: its field (µT, body frame) and the time it appears (s).
    pub fixed: Option<([f64; 3], f64)>,
}

impl Environment {
    /// The field in the earth frame at time `t` and position `p`, µT.
    pub fn field(&self, base: [f64; 3], motion: &Motion, t: f64, p: [f64; 3]) -> [f64; 3] {
        let tl = &motion.timeline;
        let mut b = base;
        if tl.phases == 0 {
            return b;
        }
        let i =
            (((t - tl.rest) / (tl.duration + tl.rest)).floor().max(0.0) as u32).min(tl.phases - 1);
        let start = tl.phase_start(i);
        if let Some([m, dist, speed]) = self.passing {
            // The passes of every phase add up (each one's field far away is small).
            for j in 0..tl.phases {
                let tc = tl.phase_start(j) + tl.duration / 2.0;
                let pos = [speed * (t - tc), dist, 0.0];
                let r = [p[0] - pos[0], p[1] - pos[1], p[2] - pos[2]];
                let f = dipole_field(MAGNET_AXIS.map(|x| x * m), r);
                for k in 0..3 {
                    b[k] += f[k];
                }
            }
        }
        if let Some(dv) = self.steel {
            let (a, len) = (start + tl.duration / 4.0, tl.duration / 2.0);
            let u = t - a;
            if (0.0..len).contains(&u) {
                let w = (std::f64::consts::PI * u / len).sin().powi(2);
                for k in 0..3 {
                    b[k] += w * dv[k];
                }
            }
        }
        b
    }

    /// The extra hard iron at time `t` (µT, body frame).
    pub fn extra_hard_iron(&self, t: f64) -> [f64; 3] {
        match self.fixed {
            Some((h, t0)) if t >= t0 => h,
            _ => [0.0; 3],
        }
    }
}

/// One sample of a synthetic log.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The time stamp written (with jitter), s.
    pub stamp: f64,
    /// The true sampling instant, s.
    pub t: f64,
    /// Gyro, rad/s.
    pub gyr: [f64; 3],
    /// Accelerometer, m/s².
    pub acc: [f64; 3],
    /// Magnetometer, µT (`None`: no sample in this row).
    pub mag: Option<[f64; 3]>,
    /// The true attitude, body → earth.
    pub q: [f64; 4],
    /// Inside a movement phase.
    pub moving: bool,
    /// The true motion at `t`.
    pub kin: Kinematics,
}

/// A synthetic log: motion, environment, sensor, rate, seed.
#[derive(Clone, Debug)]
pub struct Synth {
    /// The motion.
    pub motion: Motion,
    /// The magnetic disturbances.
    pub env: Environment,
    /// The sensor.
    pub spec: SensorSpec,
    /// The seed of every random draw.
    pub seed: u64,
}

/// Stream tags of the random draws.
pub mod tags {
    /// Gyro axis noise (+ axis).
    pub const GYRO: u64 = 10;
    /// Accelerometer axis noise (+ axis).
    pub const ACCEL: u64 = 20;
    /// Magnetometer noise.
    pub const MAG: u64 = 30;
    /// Time-stamp jitter.
    pub const JITTER: u64 = 40;
    /// The hand-held rotation.
    pub const ROTATION: u64 = 50;
    /// The translation.
    pub const TRANSLATION: u64 = 60;
    /// Taps.
    pub const TAPS: u64 = 70;
    /// Vibration phases.
    pub const VIBRATION: u64 = 80;
}

fn clip_round(x: f64, range: f64, lsb: f64) -> f64 {
    let x = x.clamp(-range, range);
    if lsb > 0.0 {
        (x / lsb).round() * lsb
    } else {
        x
    }
}

fn measure(
    sensor: &Inertial,
    noise: &mut TriadNoise,
    dt: f64,
    truth: [f64; 3],
) -> Result<[f64; 3], NoiseError> {
    let raw = sensor
        .calibration
        .raw_from_corrected(Vec3::new(truth[0], truth[1], truth[2]))
        .to_array();
    let e = noise.sample(dt)?;
    Ok(core::array::from_fn(|k| {
        clip_round(raw[k] + e[k], sensor.range, sensor.lsb)
    }))
}

/// Why a run stopped.
#[derive(Debug)]
pub enum RunError<E> {
    /// The error of the caller's function.
    Sink(E),
    /// The noise model rejected the spec or the step.
    Noise(NoiseError),
}

impl Synth {
    /// The sample interval, s.
    pub fn step(&self) -> f64 {
        match &self.motion.rotation {
            Rotation::File(f) => f.step,
            _ => 1.0 / self.spec.rate,
        }
    }

    /// The number of samples.
    pub fn len(&self) -> u64 {
        match &self.motion.rotation {
            Rotation::File(f) => self
                .motion
                .file_rest_samples()
                .saturating_add(f.attitudes.len() as u64),
            // `as` saturates: an absurd length is caught by `Options::build`'s limit.
            _ => ((self.motion.timeline.total() * self.spec.rate).floor() as u64).saturating_add(1),
        }
    }

    /// `true` for a log without samples (never: a log has at least its first sample).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The true kinematics at sample instant `t` (for tests and plots).
    pub fn kinematics(&self, t: f64) -> Kinematics {
        self.motion.at(t)
    }

    /// Calls `each` with every sample in order; stops at its first error.
    ///
    /// # Errors
    /// [`RunError::Sink`] with the error of `each`; [`RunError::Noise`] for a noise spec the
    /// noise model rejects.
    pub fn run<E>(
        &self,
        mut each: impl FnMut(&Sample) -> Result<(), E>,
    ) -> Result<(), RunError<E>> {
        let spec = &self.spec;
        let dt = self.step();
        let rate = 1.0 / dt;
        let triad =
            |tag: u64, s: &Inertial| TriadNoise::try_new(s.noise, axis_seed(self.seed, tag));
        let mut gyro_noise = triad(tags::GYRO, &spec.gyro).map_err(RunError::Noise)?;
        let mut accel_noise = triad(tags::ACCEL, &spec.accel).map_err(RunError::Noise)?;
        let mut mag_rng = stream(self.seed, tags::MAG);
        let mut jitter = stream(self.seed, tags::JITTER);
        let mag_rate = spec.mag.rate.unwrap_or(rate).min(rate);
        let g = spec.gravity;
        for k in 0..self.len() {
            let t = k as f64 * dt;
            let kin = self.motion.at(t);
            let gyr = measure(&spec.gyro, &mut gyro_noise, dt, kin.w).map_err(RunError::Noise)?;
            let up = [kin.a[0], kin.a[1], kin.a[2] + g];
            let f = rotate_inv(kin.q, up);
            let f = core::array::from_fn(|j| f[j] + kin.a_body[j]);
            let acc = measure(&spec.accel, &mut accel_noise, dt, f).map_err(RunError::Noise)?;
            let new_mag = k == 0
                || ((k as f64) * mag_rate / rate + 1e-9).floor()
                    > (((k - 1) as f64) * mag_rate / rate + 1e-9).floor();
            let mag = new_mag.then(|| {
                let td = t - spec.mag.delay;
                let kd = if spec.mag.delay == 0.0 {
                    kin
                } else {
                    self.motion.at(td)
                };
                let b = self.env.field(spec.field, &self.motion, td, kd.p);
                let body = rotate_inv(kd.q, b);
                let raw = spec
                    .mag
                    .calibration
                    .raw_from_corrected(Vec3::new(body[0], body[1], body[2]))
                    .to_array();
                let extra = self.env.extra_hard_iron(td);
                core::array::from_fn(|j| {
                    clip_round(
                        raw[j] + extra[j] + spec.mag.noise * mag_rng.normal(),
                        spec.mag.range,
                        spec.mag.lsb,
                    )
                })
            });
            let e = if spec.clock_jitter > 0.0 {
                (spec.clock_jitter * jitter.normal()).clamp(-0.4 * dt, 0.4 * dt)
            } else {
                0.0
            };
            each(&Sample {
                stamp: t + e,
                t,
                gyr,
                acc,
                mag,
                q: kin.q,
                moving: kin.moving,
                kin,
            })
            .map_err(RunError::Sink)?;
        }
        Ok(())
    }
}

/// The motion of [`Options`].
#[derive(Clone, Debug, PartialEq)]
pub enum MotionChoice {
    /// `handheld`.
    Handheld,
    /// `axes`.
    Axes,
    /// `rest`.
    Rest,
    /// `spin:WX,WY,WZ`.
    Spin([f64; 3]),
    /// A motion file, read.
    File(MotionFile),
}

impl MotionChoice {
    /// The built-in motions by name: `handheld`, `axes`, `rest` (`--motion`, Python's
    /// `motion=`); `None` for any other text (`spin:…`, a file).
    pub fn named(name: &str) -> Option<Self> {
        match name {
            "handheld" => Some(MotionChoice::Handheld),
            "axes" => Some(MotionChoice::Axes),
            "rest" => Some(MotionChoice::Rest),
            _ => None,
        }
    }
}

/// A log as `synthesize`'s flags describe it (each optional as on the command line), checked
/// into a [`Synth`] by [`Options::build`]; the Python package builds the same. Error messages
/// name the flags.
#[derive(Clone, Debug)]
pub struct Options {
    /// `--motion`.
    pub motion: MotionChoice,
    /// `--sensor`, read.
    pub sensor: SensorSpec,
    /// `--rate` (default: the spec's).
    pub rate: Option<f64>,
    /// `--duration` (default 30 s).
    pub duration: Option<f64>,
    /// `--rest` (default 5 s).
    pub rest: Option<f64>,
    /// `--phases` (default 2).
    pub phases: Option<u64>,
    /// `--ramp` (default 0.5 s, at most half a phase; 0 for a motion file).
    pub ramp: Option<f64>,
    /// `--q0` (default identity).
    pub q0: Option<[f64; 4]>,
    /// `--translation A`.
    pub translation: Option<f64>,
    /// `--vibration A,F`.
    pub vibration: Option<[f64; 2]>,
    /// `--taps A`.
    pub taps: Option<f64>,
    /// `--magnet-pass M,D,V`.
    pub magnet_pass: Option<[f64; 3]>,
    /// `--magnet-fixed HX,HY,HZ[,T]`.
    pub magnet_fixed: Option<Vec<f64>>,
    /// `--steel DX,DY,DZ`.
    pub steel: Option<[f64; 3]>,
    /// `--seed`.
    pub seed: u64,
}

/// The largest log [`Options::build`] accepts, in samples.
pub const MAX_SAMPLES: u64 = 100_000_000;

impl Options {
    /// Checks the options and builds the log's motion and environment (the seeded parts drawn).
    ///
    /// # Errors
    /// A message naming the flag of a value out of its domain or a combination not allowed.
    pub fn build(self) -> Result<Synth, String> {
        let Options {
            mut sensor, seed, ..
        } = self;
        let finite = |flag: &str, v: &[f64]| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(format!("{flag}: every number must be finite"))
            }
        };
        let positive = |flag: &str, x: Option<f64>| match x {
            Some(v) if !(v.is_finite() && v > 0.0) => {
                Err(format!("{flag}: must be finite and > 0, got {v}"))
            }
            _ => Ok(()),
        };
        let non_negative = |flag: &str, x: Option<f64>| match x {
            Some(v) if !(v.is_finite() && v >= 0.0) => {
                Err(format!("{flag}: must be >= 0, got {v}"))
            }
            _ => Ok(()),
        };
        positive("--rate", self.rate)?;
        positive("--duration", self.duration)?;
        positive("--translation", self.translation)?;
        positive("--taps", self.taps)?;
        non_negative("--rest", self.rest)?;
        non_negative("--ramp", self.ramp)?;
        for (flag, v) in [
            ("--q0", self.q0.as_ref().map(|v| &v[..])),
            ("--vibration", self.vibration.as_ref().map(|v| &v[..])),
            ("--magnet-pass", self.magnet_pass.as_ref().map(|v| &v[..])),
            ("--magnet-fixed", self.magnet_fixed.as_deref()),
            ("--steel", self.steel.as_ref().map(|v| &v[..])),
        ] {
            if let Some(v) = v {
                finite(flag, v)?;
            }
        }
        if let MotionChoice::Spin(w) = &self.motion {
            finite("--motion", w)?;
        }
        let rest = self.rest.unwrap_or(5.0);
        let q0 = match self.q0 {
            None => [1.0, 0.0, 0.0, 0.0],
            Some(q) => {
                let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
                if (n - 1.0).abs() > 1e-6 {
                    return Err(format!(
                        "--q0: must have unit norm within 1e-6, got norm {n}"
                    ));
                }
                q.map(|x| x / n)
            }
        };
        let (rotation, timeline, q0) = if let MotionChoice::File(file) = self.motion {
            for (flag, given) in [
                ("--rate", self.rate.is_some()),
                ("--duration", self.duration.is_some()),
                ("--phases", self.phases.is_some()),
                ("--q0", self.q0.is_some()),
            ] {
                if given {
                    return Err(format!(
                        "{flag}: not with --motion FILE (the file's rows are the samples and \
                         their attitudes)"
                    ));
                }
            }
            let length = (file.attitudes.len() - 1) as f64 * file.step;
            let timeline = Timeline {
                rest: (rest / file.step).round() * file.step,
                duration: length,
                phases: 1,
                ramp: self.ramp.unwrap_or(0.0).min(length / 2.0),
            };
            let q0 = file.attitudes[0];
            (Rotation::File(file), timeline, q0)
        } else {
            if let Some(r) = self.rate {
                sensor.rate = r;
            }
            let duration = self.duration.unwrap_or(30.0);
            let phases = u32::try_from(self.phases.unwrap_or(2))
                .map_err(|_| "--phases: too large".to_string())?;
            let ramp = self.ramp.unwrap_or(0.5_f64.min(duration / 2.0));
            if 2.0 * ramp > duration {
                return Err(format!(
                    "--ramp: two ramps ({ramp} s each) do not fit in a phase of --duration \
                     {duration} s"
                ));
            }
            let rotation = match self.motion {
                MotionChoice::Handheld => Rotation::handheld(&mut stream(seed, tags::ROTATION)),
                MotionChoice::Axes => Rotation::Axes,
                MotionChoice::Rest => Rotation::Rest,
                MotionChoice::Spin(w) => Rotation::Spin(w),
                MotionChoice::File(_) => unreachable!("handled above"),
            };
            let timeline = Timeline {
                rest,
                duration,
                phases,
                ramp,
            };
            (rotation, timeline, q0)
        };
        let translation = self
            .translation
            .map(|a| motion::translation(&mut stream(seed, tags::TRANSLATION), a));
        let vibration = match self.vibration {
            None => None,
            Some([_, hz]) if hz <= 0.0 => {
                return Err(format!("--vibration: the frequency must be > 0, got {hz}"));
            }
            Some([a, hz]) => {
                let mut rng = stream(seed, tags::VIBRATION);
                let two_pi = 2.0 * std::f64::consts::PI;
                Some((a, hz, [(); 3].map(|()| two_pi * rng.uniform())))
            }
        };
        let taps = self
            .taps
            .map(|a| (a, motion::taps(&mut stream(seed, tags::TAPS), &timeline)));
        if let Some([_, d, v]) = self.magnet_pass
            && (d <= 0.0 || v <= 0.0)
        {
            return Err("--magnet-pass: D and V must be > 0".into());
        }
        let fixed = match self.magnet_fixed.as_deref() {
            None => None,
            Some(&[x, y, z]) => Some(([x, y, z], timeline.rest + timeline.duration / 3.0)),
            Some(&[x, y, z, t]) => Some(([x, y, z], t)),
            Some(v) => {
                return Err(format!(
                    "--magnet-fixed: expected 3 or 4 comma-separated numbers HX,HY,HZ[,T], \
                     found {}",
                    v.len()
                ));
            }
        };
        let synth = Synth {
            motion: Motion {
                timeline,
                q0,
                rotation,
                translation,
                vibration,
                taps,
            },
            env: Environment {
                passing: self.magnet_pass,
                steel: self.steel,
                fixed,
            },
            spec: sensor,
            seed,
        };
        if synth.len() > MAX_SAMPLES {
            return Err(format!(
                "the log would have {} samples (more than {MAX_SAMPLES}): shorten --duration or \
                 lower --rate",
                synth.len()
            ));
        }
        Ok(synth)
    }
}
