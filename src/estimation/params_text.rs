//! The estimator's parameter file: one text format, read by [`Params::set_from_text`] (no
//! allocation, `no_std`) in the tools, the Python binding and the research runner, and written
//! by [`Params::write_text`] (and by the characterisation tool from a rest log).
//!
//! ```text
//! # comments run from '#' to the end of the line; blank lines are skipped
//! gyro_noise_density = 1.75e-4     # rad/s/√Hz
//! gyro_bias_stability = 8.7e-5     # rad/s
//! field.norm = 0.1                 # a threshold of the disturbance monitor
//! rate_rule = cf4                  # how rate samples become a step's rotation
//! ```
//!
//! One `name = value` per line: `name` one of [`Params::NAMES`] (or `heading_time_constant`,
//! which selects [`super::Gains::Fixed`]), `value` one number in SI units (angles in rad,
//! times in s; `inf` for an unlimited range); or `rate_rule = NAME`, the choice
//! [`Params::rate_rule`] by its name ([`RateRule::name`]: `trapezoid`, `magnus4`, `cf4`). A
//! missing name keeps its value (the defaults, or whatever the parameters held: without a
//! `rate_rule` line the rule stays the one of the parameters the file is applied to); a name
//! given twice, an unknown name, a line without `=`, a value that is not one number or a rate
//! rule that is none of [`RateRule::ALL`] is an error naming its line ([`ParamsTextError`]).
//! The values are checked as a whole by [`super::Estimator::try_new`].

use core::fmt;

use super::params::{PARAMETER_COUNT, Params, RateRule};
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
    /// `rate_rule` names none of [`RateRule::ALL`].
    UnknownRateRule,
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
        write!(f, "line {}: ", self.line)?;
        match self.kind {
            ParamsTextErrorKind::MissingEquals => f.write_str("expected `name = value`"),
            ParamsTextErrorKind::UnknownName => f.write_str("unknown parameter name"),
            ParamsTextErrorKind::BadNumber => f.write_str("the value is not one number"),
            ParamsTextErrorKind::Repeated => f.write_str("the parameter was already given"),
            ParamsTextErrorKind::UnknownRateRule => {
                f.write_str("unknown rate rule (")?;
                for (i, r) in RateRule::ALL.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    f.write_str(r.name())?;
                }
                f.write_str(")")
            }
        }
    }
}

/// The numeric name of the format outside [`Params::NAMES`].
const HEADING_TIME_CONSTANT: &str = "heading_time_constant";

/// The name of the choice [`Params::rate_rule`] in the format.
const RATE_RULE: &str = "rate_rule";

impl<T: Real> Params<T> {
    /// Sets the parameters named in `text` (the format of the module docs), line by line. On
    /// an error the lines before it have been applied: start from a copy to keep the
    /// parameters unchanged.
    ///
    /// # Errors
    /// [`ParamsTextError`] naming the first rejected line.
    pub fn set_from_text(&mut self, text: &str) -> Result<(), ParamsTextError> {
        // The numeric parameters, then `heading_time_constant`, then `rate_rule`.
        let mut seen = [false; PARAMETER_COUNT + 2];
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
            } else if name == RATE_RULE {
                Self::NAMES.len() + 1
            } else {
                Self::NAMES
                    .iter()
                    .position(|n| *n == name)
                    .ok_or(err(ParamsTextErrorKind::UnknownName))?
            };
            if name == RATE_RULE {
                let rule: RateRule = value
                    .parse()
                    .map_err(|_| err(ParamsTextErrorKind::UnknownRateRule))?;
                mark(&mut seen, index, err)?;
                self.rate_rule = rule;
                continue;
            }
            let v: f64 = value
                .parse()
                .map_err(|_| err(ParamsTextErrorKind::BadNumber))?;
            if v.is_nan() {
                return Err(err(ParamsTextErrorKind::BadNumber));
            }
            mark(&mut seen, index, err)?;
            if !self.set_by_name(name, T::from_f64(v)) {
                return Err(err(ParamsTextErrorKind::UnknownName));
            }
        }
        Ok(())
    }

    /// Writes the rate rule (`rate_rule = NAME`, [`RateRule::name`]) and every numeric
    /// parameter as `name = value` lines ([`Params::NAMES`] in order, shortest round-trip
    /// decimal of the f64 value), the text [`Params::set_from_text`] reads back to the same
    /// rule and numbers. The choice of gains, the mode and the frame are not written.
    ///
    /// # Errors
    /// Whatever `out` returns.
    pub fn write_text(&self, out: &mut impl fmt::Write) -> fmt::Result {
        writeln!(out, "{RATE_RULE} = {}", self.rate_rule.name())?;
        for (name, v) in Self::NAMES.iter().zip(self.values()) {
            writeln!(out, "{name} = {:?}", v.to_f64())?;
        }
        Ok(())
    }
}

/// Marks the name of index `index` as given (`seen`), or the error `err` of a name given twice.
fn mark(
    seen: &mut [bool],
    index: usize,
    err: impl Fn(ParamsTextErrorKind) -> ParamsTextError,
) -> Result<(), ParamsTextError> {
    let slot = seen
        .get_mut(index)
        .ok_or(err(ParamsTextErrorKind::UnknownName))?;
    if *slot {
        return Err(err(ParamsTextErrorKind::Repeated));
    }
    *slot = true;
    Ok(())
}
