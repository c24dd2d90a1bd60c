//! The sensor spec file of `synthesize` (and of the Allan characterisation tool, which writes
//! one): what a 9-axis sensor measures beside the truth, in the syntax of the calibration file
//! ([`crate::calibration`]).
//!
//! ```text
//! # comments run from '#' to the end of the line; blank lines are skipped
//! rate = 100                         # Hz, the accelerometer and gyro output data rate
//! clock_jitter = 20e-6               # s, standard deviation of each time stamp
//! gyro_noise_density = 4.9e-5        # rad/s/√Hz (white noise: angle random walk)
//! gyro_bias_instability = 2.4e-5     # rad/s (the flat floor of the Allan deviation)
//! gyro_rate_random_walk = 1e-6       # rad/s/√s (the +1/2 slope)
//! gyro_bias = 0.005, -0.003, 0.002   # rad/s
//! gyro_scale = 1.002, 0.998, 1.0     # per axis, > 0
//! gyro_misalignment = 1,0.001,0, 0,1,0, 0,0,1   # 9 numbers, row-major
//! gyro_range = 34.9                  # rad/s, saturation at ± this
//! gyro_lsb = 1.06e-3                 # rad/s, the register's step (0: no quantisation)
//! accel_...                          # the same eight keys in m/s² units
//! mag_noise = 0.3                    # µT rms per sample
//! mag_hard_iron = 5, -3, 12          # µT
//! mag_soft_iron = 1,0,0, 0,1,0, 0,0,1
//! mag_delay = 0.01                   # s, how long the magnetometer's sample is behind the gyro's
//! mag_range = 1300                   # µT
//! mag_lsb = 0.3                      # µT
//! mag_rate = 25                      # Hz (at most `rate`: the other rows have no field)
//! field = 0, 15.8, -40.7             # µT, the earth's field, ENU (x east, y north, z up)
//! gravity = 9.81                     # m/s²
//! ```
//!
//! # The model
//! The error keys mean what they mean in the calibration file: the calibration
//! `corrected = M·diag(s)·(raw − b)` (gyro, accelerometer) and `corrected = S·(raw − h)`
//! (magnetometer) with the spec's `M`, `s`, `b`, `S`, `h` undoes the sensor exactly, so the
//! sensor reads `raw = (M·diag(s))⁻¹·true + b + noise` and `raw = S⁻¹·true + h + noise`
//! (`InertialCalibration::raw_from_corrected`), then saturates at `±range` and rounds to a
//! multiple of `lsb`. Noise: white (`noise_density/√Δt` per sample), bias instability and rate
//! random walk per axis, seeded.
//!
//! Every key is optional; a missing key is ideal (no noise, no error, no saturation, no
//! quantisation, no delay), except `rate` (100 Hz), `mag_rate` (= `rate`), `field` (Berlin's,
//! as BROAD's trials measure it: (0, 15.8, −40.7) µT) and `gravity` (9.81 m/s²). A key given
//! twice, an unknown key, a line without `=`, a wrong count of numbers, a non-finite number or
//! a value out of its domain is an error naming its line.

use gyrostat::sensor::{InertialCalibration, MagnetometerCalibration};
use gyrostat::{Mat3, Vec3};

use crate::noise::NoiseSpec;

/// The errors of one 3-axis inertial sensor (gyro or accelerometer), SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertial {
    /// The stochastic errors of each axis.
    pub noise: NoiseSpec,
    /// The calibration that undoes the deterministic errors: `M·diag(s)·(raw − b)`.
    pub calibration: InertialCalibration<f64>,
    /// Saturation: the output is clipped to `±range` (infinite: none).
    pub range: f64,
    /// The register's step (0: no quantisation).
    pub lsb: f64,
}

/// The errors of the magnetometer, µT.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Magnetometer {
    /// White noise, µT rms per sample and axis.
    pub noise: f64,
    /// The calibration that undoes hard and soft iron: `S·(raw − h)`.
    pub calibration: MagnetometerCalibration<f64>,
    /// How long the field's sample is behind the gyro's, s.
    pub delay: f64,
    /// Saturation, µT.
    pub range: f64,
    /// The register's step, µT (0: none).
    pub lsb: f64,
    /// The output data rate, Hz (`None`: every row).
    pub rate: Option<f64>,
}

/// A sensor spec file, read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorSpec {
    /// The output data rate of the gyro and accelerometer, Hz.
    pub rate: f64,
    /// The standard deviation of the time stamps around `k / rate`, s.
    pub clock_jitter: f64,
    /// Gyro, rad/s.
    pub gyro: Inertial,
    /// Accelerometer, m/s².
    pub accel: Inertial,
    /// Magnetometer, µT.
    pub mag: Magnetometer,
    /// The earth's field in the earth frame (ENU), µT.
    pub field: [f64; 3],
    /// The magnitude of gravity, m/s².
    pub gravity: f64,
}

/// The domain of a key's numbers.
#[derive(Clone, Copy)]
enum Domain {
    Any,
    NonNegative,
    Positive,
}

const KEYS: [(&str, usize, Domain); 27] = [
    ("rate", 1, Domain::Positive),
    ("clock_jitter", 1, Domain::NonNegative),
    ("gyro_noise_density", 1, Domain::NonNegative),
    ("gyro_bias_instability", 1, Domain::NonNegative),
    ("gyro_rate_random_walk", 1, Domain::NonNegative),
    ("gyro_bias", 3, Domain::Any),
    ("gyro_scale", 3, Domain::Any),
    ("gyro_misalignment", 9, Domain::Any),
    ("gyro_range", 1, Domain::Positive),
    ("gyro_lsb", 1, Domain::NonNegative),
    ("accel_noise_density", 1, Domain::NonNegative),
    ("accel_bias_instability", 1, Domain::NonNegative),
    ("accel_rate_random_walk", 1, Domain::NonNegative),
    ("accel_bias", 3, Domain::Any),
    ("accel_scale", 3, Domain::Any),
    ("accel_misalignment", 9, Domain::Any),
    ("accel_range", 1, Domain::Positive),
    ("accel_lsb", 1, Domain::NonNegative),
    ("mag_noise", 1, Domain::NonNegative),
    ("mag_hard_iron", 3, Domain::Any),
    ("mag_soft_iron", 9, Domain::Any),
    ("mag_delay", 1, Domain::NonNegative),
    ("mag_range", 1, Domain::Positive),
    ("mag_lsb", 1, Domain::NonNegative),
    ("mag_rate", 1, Domain::Positive),
    ("field", 3, Domain::Any),
    ("gravity", 1, Domain::Positive),
];

/// The names of the built-in presets, for `--sensor NAME`.
pub const PRESETS: [&str; 4] = ["ideal", "consumer", "industrial", "tactical"];

/// The text of a built-in preset (a spec file with its sources in comments).
pub fn preset_text(name: &str) -> Option<&'static str> {
    match name {
        "ideal" => Some(IDEAL),
        "consumer" => Some(CONSUMER),
        "industrial" => Some(INDUSTRIAL),
        "tactical" => Some(TACTICAL),
        _ => None,
    }
}

const IDEAL: &str = "\
# ideal: no noise, no error, no saturation, no quantisation (every key at its default)
rate = 100
";

const CONSUMER: &str = "\
# consumer: a 6-axis MEMS IMU of the InvenSense ICM-42688-P class with a Bosch BMM150
# magnetometer. Typical values of the public datasheets (InvenSense ICM-42688-P, Bosch BMM150),
# quoted from them without a revision number (check a figure against the current sheet before
# relying on it), converted to SI (1 deg = pi/180 rad, 1 g = 9.80665 m/s^2):
rate = 100
clock_jitter = 20e-6              # host time stamps, not a datasheet figure
# gyro: rate noise spectral density 0.0028 dps/sqrt(Hz) = 4.89e-5 rad/s/sqrt(Hz); the datasheet
# gives no bias instability: 5 deg/h = 2.4e-5 rad/s is the Allan floor typical of this class;
# rate random walk not specified (a small 2e-5 deg/s/sqrt(s) = 3.5e-7 rad/s/sqrt(s));
# zero-rate offset +-0.5 dps (here 0.3, -0.2, 0.1 dps); sensitivity error +-0.5 %;
# cross-axis sensitivity +-1.25 % (here 0.5 %); full scale +-2000 dps = 34.9 rad/s at
# 16.4 LSB/dps = 1.064e-3 rad/s per LSB
gyro_noise_density = 4.89e-5
gyro_bias_instability = 2.4e-5
gyro_rate_random_walk = 3.5e-7
gyro_bias = 5.24e-3, -3.49e-3, 1.75e-3
gyro_scale = 1.004, 0.997, 1.002
gyro_misalignment = 1,0.005,-0.003, -0.004,1,0.005, 0.003,-0.005,1
gyro_range = 34.9
gyro_lsb = 1.064e-3
# accelerometer: noise spectral density 70 ug/sqrt(Hz) = 6.86e-4 m/s^2/sqrt(Hz); bias
# instability not specified: 0.04 mg = 3.9e-4 m/s^2 (class typical); random walk 4e-5
# m/s^2/sqrt(s) (assumed); zero-g offset +-20 mg (here 15, -10, 20 mg); sensitivity error
# +-0.5 %; full scale +-16 g = 156.9 m/s^2 at 2048 LSB/g = 4.79e-3 m/s^2 per LSB
accel_noise_density = 6.86e-4
accel_bias_instability = 3.9e-4
accel_rate_random_walk = 4e-5
accel_bias = 0.147, -0.098, 0.196
accel_scale = 0.996, 1.003, 1.005
accel_misalignment = 1,0.004,0.002, -0.003,1,-0.004, 0.002,0.003,1
accel_range = 156.9
accel_lsb = 4.79e-3
# magnetometer (BMM150): rms noise 0.6 uT in the regular preset (0.3 uT resolution), range
# +-1300 uT (x, y), data rate 25 Hz (regular preset up to 30 Hz); hard and soft iron: what is
# left after a board's hard/soft-iron calibration (not datasheet figures; uncalibrated boards
# have tens of uT and several %, which no attitude filter can undo)
mag_noise = 0.6
mag_hard_iron = 1.0, -0.6, 1.5
mag_soft_iron = 1.01,0.005,-0.003, 0.005,0.99,0.004, -0.003,0.004,1.005
mag_delay = 0.01
mag_range = 1300
mag_lsb = 0.3
mag_rate = 25
";

const INDUSTRIAL: &str = "\
# industrial: an Analog Devices ADIS16470-class tactical-MEMS IMU (no magnetometer of its own)
# with a PNI RM3100-class magnetometer. Typical values of the public datasheets (Analog Devices
# ADIS16470, PNI RM3100), quoted without a revision number, converted to SI:
rate = 200
clock_jitter = 5e-6
# gyro: angle random walk 0.34 deg/sqrt(h) = 0.34/60 deg/s/sqrt(Hz) = 9.9e-5 rad/s/sqrt(Hz)
# (the rate noise density 0.008 dps/sqrt(Hz) rms of the same sheet is about 1.4x this);
# in-run bias stability 8 deg/h = 3.9e-5 rad/s; rate random walk not specified (assumed
# 3e-7 rad/s/sqrt(s)); bias repeatability +-0.2 dps (here 0.05, -0.04, 0.03 dps); misalignment
# +-0.05 deg = 8.7e-4 rad; range +-2000 dps = 34.9 rad/s; 16-bit output 0.1 dps/LSB =
# 1.745e-3 rad/s
gyro_noise_density = 9.9e-5
gyro_bias_instability = 3.9e-5
gyro_rate_random_walk = 3e-7
gyro_bias = 8.7e-4, -7.0e-4, 5.2e-4
gyro_scale = 1.001, 0.9995, 1.0005
gyro_misalignment = 1,8.7e-4,-5e-4, -6e-4,1,8e-4, 4e-4,-7e-4,1
gyro_range = 34.9
gyro_lsb = 1.745e-3
# accelerometer: velocity random walk 0.037 m/s/sqrt(h) = 6.2e-4 m/s^2/sqrt(Hz); in-run bias
# stability 13 ug = 1.27e-4 m/s^2; random walk assumed 1e-5 m/s^2/sqrt(s); bias repeatability
# +-50 mg (here 3, -2, 4 mg after the factory calibration's residual); range +-40 g = 392 m/s^2;
# 16-bit output 1.25 mg/LSB = 1.226e-2 m/s^2
accel_noise_density = 6.2e-4
accel_bias_instability = 1.27e-4
accel_rate_random_walk = 1e-5
accel_bias = 0.0294, -0.0196, 0.0392
accel_scale = 1.0005, 0.9995, 1.001
accel_misalignment = 1,5e-4,-3e-4, 4e-4,1,-5e-4, -2e-4,6e-4,1
accel_range = 392
accel_lsb = 1.226e-2
# magnetometer (RM3100 at cycle count 200): noise 15 nT = 0.015 uT, resolution 13 nT, range
# +-800 uT, single-axis rate about 440 Hz (3 axes about 147 Hz: here 100 Hz)
mag_noise = 0.015
# (hard and soft iron: the residual after a board calibration, as for the consumer preset)
mag_hard_iron = 0.3, -0.2, 0.4
mag_soft_iron = 1.003,0.001,0, 0.001,0.998,0.001, 0,0.001,1.0
mag_delay = 0.005
mag_range = 800
mag_lsb = 0.013
mag_rate = 100
";

const TACTICAL: &str = "\
# tactical: a KVH 1750-class fibre-optic gyro IMU with a fluxgate-class magnetometer. Figures
# of the public KVH 1750 IMU datasheet (limits, used as typical values), quoted without a
# revision number, converted to SI:
rate = 1000
clock_jitter = 1e-6
# gyro: angle random walk <= 0.012 deg/sqrt(h) = 0.012/60 deg/s/sqrt(Hz) = 3.5e-6
# rad/s/sqrt(Hz); bias instability <= 0.05 deg/h = 2.4e-7 rad/s; rate random walk not
# specified (assumed 1e-8 rad/s/sqrt(s)); bias offset +-2 deg/h (here 1, -1.5, 0.5 deg/h);
# scale factor nonlinearity 50 ppm; input range +-490 dps = 8.55 rad/s; the output is an
# integrated angle: no quantisation at the rate's scale
gyro_noise_density = 3.5e-6
gyro_bias_instability = 2.4e-7
gyro_rate_random_walk = 1e-8
gyro_bias = 4.85e-6, -7.27e-6, 2.42e-6
gyro_scale = 1.00005, 0.99995, 1.00003
gyro_misalignment = 1,1e-4,-5e-5, -8e-5,1,1e-4, 6e-5,-1e-4,1
gyro_range = 8.55
# accelerometer (+-10 g version): velocity random walk 0.12 mg/sqrt(Hz) = 1.18e-3
# m/s^2/sqrt(Hz); bias instability <= 0.05 mg = 4.9e-4 m/s^2; random walk assumed 5e-6
# m/s^2/sqrt(s); bias offset +-1 mg (here 0.5, -0.3, 0.8 mg); range +-10 g = 98.1 m/s^2
accel_noise_density = 1.18e-3
accel_bias_instability = 4.9e-4
accel_rate_random_walk = 5e-6
accel_bias = 4.9e-3, -2.9e-3, 7.8e-3
accel_scale = 1.0001, 0.9999, 1.0002
accel_misalignment = 1,1e-4,-1e-4, 1e-4,1,1e-4, -1e-4,1e-4,1
accel_range = 98.1
# magnetometer: a fluxgate-class three-axis sensor (not part of the KVH 1750): noise 0.01 uT,
# range +-100 uT, 100 Hz
mag_noise = 0.01
mag_hard_iron = 0.1, -0.05, 0.15
mag_soft_iron = 1.001,0.0005,0, 0.0005,0.999,0.0003, 0,0.0003,1.0
mag_range = 100
mag_rate = 100
";

/// Parses the text of a sensor spec file. Errors read `line N: reason` (or, for a matrix the
/// library rejects, `gyro (lines …): reason`).
pub fn parse(text: &str) -> Result<SensorSpec, String> {
    let names: Vec<(&str, usize)> = KEYS.iter().map(|&(k, c, _)| (k, c)).collect();
    let values = crate::key_values::parse(text, &names, |p, x, part| match KEYS[p].2 {
        Domain::NonNegative if x < 0.0 => Err(format!("must be >= 0, got {part}")),
        Domain::Positive if x <= 0.0 => Err(format!("must be > 0, got {part}")),
        _ => Ok(()),
    })?;
    let get = |key: &str| {
        KEYS.iter()
            .position(|(k, _, _)| *k == key)
            .and_then(|p| values[p].as_ref())
    };
    let one = |key: &str, default: f64| get(key).map_or(default, |(_, v)| v[0]);
    let vec3 = |key: &str, default: f64| {
        get(key).map_or(Vec3::new(default, default, default), |(_, v)| {
            Vec3::new(v[0], v[1], v[2])
        })
    };
    let mat3 = |key: &str| {
        get(key).map_or(Mat3::IDENTITY, |(_, v)| {
            Mat3::from_rows([v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]])
        })
    };
    let lines = |keys: &[&str]| {
        let ls: Vec<String> = keys
            .iter()
            .filter_map(|k| get(k).map(|(n, _)| n.to_string()))
            .collect();
        if ls.is_empty() {
            String::new()
        } else {
            format!(" (lines {})", ls.join(", "))
        }
    };
    let inertial = |s: &str| -> Result<Inertial, String> {
        let key = |k: &str| format!("{s}_{k}");
        let calibration = InertialCalibration::try_new(
            mat3(&key("misalignment")),
            vec3(&key("scale"), 1.0),
            vec3(&key("bias"), 0.0),
        )
        .map_err(|e| {
            format!(
                "{s}{}: {e}",
                lines(&[&key("bias"), &key("scale"), &key("misalignment")])
            )
        })?;
        Ok(Inertial {
            noise: NoiseSpec {
                noise_density: one(&key("noise_density"), 0.0),
                bias_instability: one(&key("bias_instability"), 0.0),
                rate_random_walk: one(&key("rate_random_walk"), 0.0),
            },
            calibration,
            range: one(&key("range"), f64::INFINITY),
            lsb: one(&key("lsb"), 0.0),
        })
    };
    let gyro = inertial("gyro")?;
    let accel = inertial("accel")?;
    let mag_cal =
        MagnetometerCalibration::try_new(mat3("mag_soft_iron"), vec3("mag_hard_iron", 0.0))
            .map_err(|e| format!("mag{}: {e}", lines(&["mag_hard_iron", "mag_soft_iron"])))?;
    let field = get("field").map_or([0.0, 15.8, -40.7], |(_, v)| [v[0], v[1], v[2]]);
    Ok(SensorSpec {
        rate: one("rate", 100.0),
        clock_jitter: one("clock_jitter", 0.0),
        gyro,
        accel,
        mag: Magnetometer {
            noise: one("mag_noise", 0.0),
            calibration: mag_cal,
            delay: one("mag_delay", 0.0),
            range: one("mag_range", f64::INFINITY),
            lsb: one("mag_lsb", 0.0),
            rate: get("mag_rate").map(|(_, v)| v[0]),
        },
        field,
        gravity: one("gravity", 9.81),
    })
}

/// `--sensor NAME|FILE`: a preset by name, else a spec file; errors name the flag and file.
pub fn read(flag: &str, name_or_path: &str) -> Result<(SensorSpec, String), String> {
    let text = match preset_text(name_or_path) {
        Some(t) => t.to_string(),
        None => std::fs::read_to_string(name_or_path).map_err(|e| {
            format!(
                "{flag} {name_or_path}: not a preset ({}) and not a readable file: {e}",
                PRESETS.join(", ")
            )
        })?,
    };
    let spec = parse(&text).map_err(|e| format!("{flag} {name_or_path}: {e}"))?;
    Ok((spec, text))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_parse() {
        for p in PRESETS {
            let s = parse(preset_text(p).unwrap()).unwrap_or_else(|e| panic!("{p}: {e}"));
            assert!(s.rate > 0.0);
        }
    }

    #[test]
    fn defaults_are_ideal_and_errors_name_lines() {
        let s = parse("\n# nothing\n").unwrap();
        assert_eq!(s.rate, 100.0);
        assert_eq!(s.gyro.noise.noise_density, 0.0);
        assert_eq!(s.gyro.range, f64::INFINITY);
        assert_eq!(s.mag.rate, None);
        let e = |t: &str| parse(t).unwrap_err();
        assert_eq!(
            e("rate = 1\nrate = 2"),
            "line 2: 'rate' given twice (first on line 1)"
        );
        assert!(e("\nwobble = 1").starts_with("line 2: unknown key 'wobble'"));
        assert_eq!(e("rate = 0"), "line 1: rate: must be > 0, got 0");
        assert_eq!(
            e("mag_noise = -1"),
            "line 1: mag_noise: must be >= 0, got -1"
        );
        assert!(e("field = 1,2").starts_with("line 1: field: expected 3"));
        assert!(e("#\ngyro_scale = 1,0,1").starts_with("gyro (lines 2): "));
    }
}
