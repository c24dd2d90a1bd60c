//! The calibration file of the tools (`propagate --calibration FILE`): one small text format for
//! the sensor model of `gyrostat::sensor::calibration`.
//!
//! ```text
//! # comments run from '#' to the end of the line; blank lines are skipped
//! gyro_bias = 0.001, -0.002, 0.0005          # rad/s (after --gyro-unit conversion)
//! gyro_scale = 1.01, 0.99, 1.0               # per axis, > 0
//! gyro_misalignment = 1,0.001,0, 0,1,0, 0,0,1   # 9 numbers, row-major
//! accel_bias = 0.01, 0, -0.02                # in the accelerometer's unit after conversion
//! accel_scale = 1, 1, 1
//! accel_misalignment = 1,0,0, 0,1,0, 0,0,1
//! mag_hard_iron = 12.5, -3.0, 40.1           # in the magnetometer's unit after conversion
//! mag_soft_iron = 1,0,0, 0,1,0, 0,0,1        # 9 numbers, row-major
//! ```
//!
//! The model (`gyrostat::sensor::calibration`): `corrected = M · diag(s) · (raw − b)` for the
//! gyro and the accelerometer (`M` the misalignment, `s` the scale, `b` the bias),
//! `corrected = S · (raw − h)` for the magnetometer. Every key is optional (a missing key is its
//! identity value: zero bias, unit scale, identity matrix); a key given twice, an unknown key, a
//! line without `=`, a wrong count of numbers or a non-finite number is an error naming its line.
//! The assembled calibrations are validated by the library (`try_new`: positive scales, an
//! invertible, well-conditioned matrix with positive determinant); such an error names the
//! sensor and the lines of its keys.

use gyrostat::sensor::{InertialCalibration, MagnetometerCalibration};
use gyrostat::{Mat3, Vec3};

/// The three calibrations of a file (identities for the sensors it does not mention).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CalibrationFile {
    /// Gyro: `M·diag(s)·(raw − b)`, `b` in rad/s.
    pub gyro: InertialCalibration<f64>,
    /// Accelerometer: `M·diag(s)·(raw − b)`.
    pub accel: InertialCalibration<f64>,
    /// Magnetometer: `S·(raw − h)`.
    pub mag: MagnetometerCalibration<f64>,
}

const KEYS: [(&str, usize); 8] = [
    ("gyro_bias", 3),
    ("gyro_scale", 3),
    ("gyro_misalignment", 9),
    ("accel_bias", 3),
    ("accel_scale", 3),
    ("accel_misalignment", 9),
    ("mag_hard_iron", 3),
    ("mag_soft_iron", 9),
];

/// Parses the text of a calibration file. Errors read `line N: reason` (or, for a model the
/// library rejects, `gyro (lines …): reason`).
pub fn parse(text: &str) -> Result<CalibrationFile, String> {
    let values = crate::key_values::parse(text, &KEYS, |_, _, _| Ok(()))?;
    let get = |i: usize| values.get(i).and_then(|v| v.as_ref());
    let vec3 = |i: usize, default: f64| {
        get(i).map_or(Vec3::new(default, default, default), |(_, v)| {
            Vec3::new(v[0], v[1], v[2])
        })
    };
    let mat3 = |i: usize| {
        get(i).map_or(Mat3::IDENTITY, |(_, v)| {
            Mat3::from_rows([v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]])
        })
    };
    let lines = |range: std::ops::Range<usize>| {
        let ls: Vec<String> = range
            .filter_map(|i| get(i).map(|(n, _)| n.to_string()))
            .collect();
        if ls.is_empty() {
            String::new()
        } else {
            format!(" (lines {})", ls.join(", "))
        }
    };
    let gyro = InertialCalibration::try_new(mat3(2), vec3(1, 1.0), vec3(0, 0.0))
        .map_err(|e| format!("gyro{}: {e}", lines(0..3)))?;
    let accel = InertialCalibration::try_new(mat3(5), vec3(4, 1.0), vec3(3, 0.0))
        .map_err(|e| format!("accel{}: {e}", lines(3..6)))?;
    let mag = MagnetometerCalibration::try_new(mat3(7), vec3(6, 0.0))
        .map_err(|e| format!("mag{}: {e}", lines(6..8)))?;
    Ok(CalibrationFile { gyro, accel, mag })
}

/// Reads and parses a calibration file; errors name the file.
pub fn read(path: &str) -> Result<CalibrationFile, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("--calibration {path}: {e}"))?;
    parse(&text).map_err(|e| format!("--calibration {path}: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_reports_lines() {
        let c = parse("# x\n\ngyro_bias = 0.1, -0.2, 0.3 # rad/s\nmag_hard_iron=1,2,3\n").unwrap();
        assert_eq!(c.gyro.bias().to_array(), [0.1, -0.2, 0.3]);
        assert_eq!(c.mag.hard_iron().to_array(), [1.0, 2.0, 3.0]);
        assert_eq!(c.accel, InertialCalibration::IDENTITY);
        let e = |t: &str| parse(t).unwrap_err();
        assert_eq!(
            e("\ngyro_bias 1,2,3"),
            "line 2: expected 'key = numbers', found 'gyro_bias 1,2,3'"
        );
        assert!(e("gyro_bias = 1,2").starts_with("line 1: gyro_bias: expected 3"));
        assert!(e("gyro_bias = 1,2,x").starts_with("line 1: gyro_bias: invalid number 'x'"));
        assert!(e("gyro_bias = 1,2,inf").starts_with("line 1: gyro_bias: not a finite"));
        assert!(
            e("gyro_bias=1,2,3\n\ngyro_bias=1,2,3")
                .starts_with("line 3: 'gyro_bias' given twice (first on line 1)")
        );
        assert!(e("gyro_offset=1,2,3").starts_with("line 1: unknown key 'gyro_offset'"));
        assert!(e("#\ngyro_scale = 1,0,1").starts_with("gyro (lines 2): "));
        assert!(e("mag_soft_iron = 1,0,0, 0,1,0, 0,0,-1").starts_with("mag (lines 1): "));
    }
}
