//! The unit flags of `propagate`: `--gyro-unit rad/s|deg/s` and `--time-unit s|ms|us`, each a
//! factor to the SI unit the library uses (rad/s, s).

/// The factor from a `--gyro-unit` to rad/s (for increments: from rad or deg to rad, the same
/// factor).
pub fn gyro_unit(flag: &str, text: &str) -> Result<f64, String> {
    match text.trim() {
        "rad/s" => Ok(1.0),
        "deg/s" => Ok(std::f64::consts::PI / 180.0),
        t => Err(format!("{flag}: expected rad/s or deg/s, got '{t}'")),
    }
}

/// The factor from a `--time-unit` to seconds.
pub fn time_unit(flag: &str, text: &str) -> Result<f64, String> {
    match text.trim() {
        "s" => Ok(1.0),
        "ms" => Ok(1e-3),
        "us" => Ok(1e-6),
        t => Err(format!("{flag}: expected s, ms or us, got '{t}'")),
    }
}
