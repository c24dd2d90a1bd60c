//! The estimator's parameter file: one text format, read by [`Params::set_from_text`] (no
//! allocation, `no_std`) in the tools, the Python binding and the research runner, and written
//! by [`Params::write_text`] (and by the characterisation tool from a rest log).
//!
//! ```text
//! # comments run from '#' to the end of the line; blank lines are skipped
//! gyro_noise_density = 1.75e-4     # rad/s/√Hz
//! gyro_bias_stability = 8.7e-5     # rad/s
//! field.norm = 0.1                 # a threshold of the disturbance monitor
//! ```
//!
//! One `name = value` per line: `name` one of [`Params::NAMES`] (or `heading_time_constant`,
//! which selects [`super::Gains::Fixed`]), `value` one number in SI units (angles in rad,
//! times in s; `inf` for an unlimited range). A missing name keeps its value (the defaults, or
//! whatever the parameters held); a name given twice, an unknown name, a line without `=` or a
//! value that is not one number is an error naming its line ([`ParamsTextError`]). The values
//! are checked as a whole by [`super::Estimator::try_new`].

use core::fmt;

use super::params::{PARAMETER_COUNT, Params};
use crate::Real;

/// Why a line of a parameter file was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ParamsTextErrorKind {
    /// The line has no `=`.
    MissingEquals,
    /// The name is none of [`Params::NAMES`] (nor `heading_time_constant`).
    UnknownName,
    /// The value is not one number (or is NaN).
    BadNumber,
    /// The name was given on an earlier line.
    Repeated,
}

/// A rejected line of a parameter file: its number (from 1) and why.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ParamsTextError {
    /// The line, counted from 1.
    pub line: usize,
    /// Why it was rejected.
    pub kind: ParamsTextErrorKind,
}

impl fmt::Display for ParamsTextError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let why = match self.kind {
            ParamsTextErrorKind::MissingEquals => "expected `name = value`",
            ParamsTextErrorKind::UnknownName => "unknown parameter name",
            ParamsTextErrorKind::BadNumber => "the value is not one number",
            ParamsTextErrorKind::Repeated => "the parameter was already given",
        };
        write!(f, "line {}: {why}", self.line)
    }
}

/// The one name of the format outside [`Params::NAMES`].
const HEADING_TIME_CONSTANT: &str = "heading_time_constant";

impl<T: Real> Params<T> {
    /// Sets the parameters named in `text` (the format of the module docs), line by line. On
    /// an error the lines before it have been applied: start from a copy to keep the
    /// parameters unchanged.
    ///
    /// # Errors
    /// [`ParamsTextError`] naming the first rejected line.
    pub fn set_from_text(&mut self, text: &str) -> Result<(), ParamsTextError> {
        let mut seen = [false; PARAMETER_COUNT + 1];
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let err = |kind| ParamsTextError { line, kind };
            let content = raw.split('#').next().unwrap_or("").trim();
            if content.is_empty() {
                continue;
            }
            let (name, value) = content
                .split_once('=')
                .ok_or(err(ParamsTextErrorKind::MissingEquals))?;
            let (name, value) = (name.trim(), value.trim());
            let index = if name == HEADING_TIME_CONSTANT {
                Self::NAMES.len()
            } else {
                Self::NAMES
                    .iter()
                    .position(|n| *n == name)
                    .ok_or(err(ParamsTextErrorKind::UnknownName))?
            };
            let v: f64 = value
                .parse()
                .map_err(|_| err(ParamsTextErrorKind::BadNumber))?;
            if v.is_nan() {
                return Err(err(ParamsTextErrorKind::BadNumber));
            }
            let slot = seen
                .get_mut(index)
                .ok_or(err(ParamsTextErrorKind::UnknownName))?;
            if *slot {
                return Err(err(ParamsTextErrorKind::Repeated));
            }
            *slot = true;
            if !self.set_by_name(name, T::from_f64(v)) {
                return Err(err(ParamsTextErrorKind::UnknownName));
            }
        }
        Ok(())
    }

    /// Writes every numeric parameter as `name = value` lines ([`Params::NAMES`] in order,
    /// shortest round-trip decimal of the f64 value), the text [`Params::set_from_text`] reads
    /// back to the same numbers. The choice of gains and the frame are not written.
    ///
    /// # Errors
    /// Whatever `out` returns.
    pub fn write_text(&self, out: &mut impl fmt::Write) -> fmt::Result {
        for (name, v) in Self::NAMES.iter().zip(self.values()) {
            writeln!(out, "{name} = {:?}", v.to_f64())?;
        }
        Ok(())
    }
}
