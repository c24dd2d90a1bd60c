//! The units of sensor data on the command line: `--gyro-unit`, `--accel-unit`, `--mag-unit`,
//! `--time-unit`, one spelling for every tool.
//!
//! Each flag's value names a unit; [`GyroUnit::parse`] and its siblings are value parsers for
//! `gyrostat_tools::flags::Flags::get` (`f.get("--gyro-unit", GyroUnit::parse)`), and each unit gives
//! the factor that converts a value in it to SI (`to_si`). A value outside the vocabulary is
//! `FLAG: unknown unit 'TEXT' (one of ...)`.

/// Standard gravity, m/s² (the `g` of `--accel-unit g`).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Finds `text` among `(name, unit)` pairs, or the flag's error listing the names.
fn lookup<U: Copy>(flag: &str, text: &str, table: &[(&str, U)]) -> Result<U, String> {
    let t = text.trim();
    table
        .iter()
        .find(|(name, _)| *name == t)
        .map(|(_, u)| *u)
        .ok_or_else(|| {
            let names: Vec<&str> = table.iter().map(|(n, _)| *n).collect();
            format!("{flag}: unknown unit '{t}' (one of {})", names.join(", "))
        })
}

/// The unit of angular rates (`--gyro-unit rad/s|deg/s`, default rad/s).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GyroUnit {
    /// rad/s.
    #[default]
    RadPerSecond,
    /// °/s.
    DegPerSecond,
}

impl GyroUnit {
    /// The value parser of `--gyro-unit`.
    pub fn parse(flag: &str, text: &str) -> Result<Self, String> {
        lookup(
            flag,
            text,
            &[("rad/s", Self::RadPerSecond), ("deg/s", Self::DegPerSecond)],
        )
    }

    /// The factor from this unit to rad/s.
    pub fn to_si(self) -> f64 {
        match self {
            Self::RadPerSecond => 1.0,
            Self::DegPerSecond => core::f64::consts::PI / 180.0,
        }
    }

    /// The unit's spelling on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::RadPerSecond => "rad/s",
            Self::DegPerSecond => "deg/s",
        }
    }
}

/// The unit of specific force (`--accel-unit m/s^2|g`, default m/s²).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AccelUnit {
    /// m/s².
    #[default]
    MeterPerSecondSquared,
    /// Standard gravity, [`STANDARD_GRAVITY`] m/s².
    StandardGravity,
}

impl AccelUnit {
    /// The value parser of `--accel-unit`.
    pub fn parse(flag: &str, text: &str) -> Result<Self, String> {
        lookup(
            flag,
            text,
            &[
                ("m/s^2", Self::MeterPerSecondSquared),
                ("g", Self::StandardGravity),
            ],
        )
    }

    /// The factor from this unit to m/s².
    pub fn to_si(self) -> f64 {
        match self {
            Self::MeterPerSecondSquared => 1.0,
            Self::StandardGravity => STANDARD_GRAVITY,
        }
    }

    /// The unit's spelling on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::MeterPerSecondSquared => "m/s^2",
            Self::StandardGravity => "g",
        }
    }
}

/// The unit of magnetic flux density (`--mag-unit uT|nT|G|any`, default `any`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MagUnit {
    /// µT.
    MicroTesla,
    /// nT.
    NanoTesla,
    /// gauss (100 µT).
    Gauss,
    /// Whatever the data holds: the values are used as they are.
    #[default]
    Any,
}

impl MagUnit {
    /// The value parser of `--mag-unit`.
    pub fn parse(flag: &str, text: &str) -> Result<Self, String> {
        lookup(
            flag,
            text,
            &[
                ("uT", Self::MicroTesla),
                ("nT", Self::NanoTesla),
                ("G", Self::Gauss),
                ("any", Self::Any),
            ],
        )
    }

    /// The factor from this unit to µT (1 for [`MagUnit::Any`]: no conversion).
    pub fn to_micro_tesla(self) -> f64 {
        match self {
            Self::MicroTesla | Self::Any => 1.0,
            Self::NanoTesla => 1e-3,
            Self::Gauss => 100.0,
        }
    }

    /// The unit's spelling on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::MicroTesla => "uT",
            Self::NanoTesla => "nT",
            Self::Gauss => "G",
            Self::Any => "any",
        }
    }
}

/// The unit of time stamps (`--time-unit s|ms|us`, default s).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TimeUnit {
    /// Seconds.
    #[default]
    Second,
    /// Milliseconds.
    Millisecond,
    /// Microseconds.
    Microsecond,
}

impl TimeUnit {
    /// The value parser of `--time-unit`.
    pub fn parse(flag: &str, text: &str) -> Result<Self, String> {
        lookup(
            flag,
            text,
            &[
                ("s", Self::Second),
                ("ms", Self::Millisecond),
                ("us", Self::Microsecond),
            ],
        )
    }

    /// The factor from this unit to seconds.
    pub fn to_si(self) -> f64 {
        match self {
            Self::Second => 1.0,
            Self::Millisecond => 1e-3,
            Self::Microsecond => 1e-6,
        }
    }

    /// The unit's spelling on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Second => "s",
            Self::Millisecond => "ms",
            Self::Microsecond => "us",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spellings_and_factors() {
        assert_eq!(
            GyroUnit::parse("--gyro-unit", "deg/s"),
            Ok(GyroUnit::DegPerSecond)
        );
        assert_eq!(
            GyroUnit::DegPerSecond.to_si() * 180.0,
            core::f64::consts::PI
        );
        assert_eq!(
            AccelUnit::parse("--accel-unit", " g "),
            Ok(AccelUnit::StandardGravity)
        );
        assert_eq!(AccelUnit::StandardGravity.to_si(), 9.80665);
        assert_eq!(
            MagUnit::parse("--mag-unit", "G").map(MagUnit::to_micro_tesla),
            Ok(100.0)
        );
        assert_eq!(
            MagUnit::parse("--mag-unit", "nT").map(MagUnit::to_micro_tesla),
            Ok(1e-3)
        );
        assert_eq!(
            TimeUnit::parse("--time-unit", "us").map(TimeUnit::to_si),
            Ok(1e-6)
        );
        for u in [GyroUnit::RadPerSecond, GyroUnit::DegPerSecond] {
            assert_eq!(GyroUnit::parse("--x", u.name()), Ok(u));
        }
        assert_eq!(
            GyroUnit::parse("--gyro-unit", "dps"),
            Err("--gyro-unit: unknown unit 'dps' (one of rad/s, deg/s)".into())
        );
        assert_eq!(
            TimeUnit::parse("--time-unit", "S"),
            Err("--time-unit: unknown unit 'S' (one of s, ms, us)".into())
        );
    }
}
