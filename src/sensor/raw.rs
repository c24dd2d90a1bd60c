//! Raw `i16` sensor registers: their LSB scale and their clipping.
//!
//! A reading becomes a physical value through one model in every number format:
//! `value = raw · lsb` (rad/s, rad, m/s², … per LSB), then the calibration
//! ([`crate::sensor::InertialCalibration`]) and the mounting ([`crate::sensor::AxisRemap`]).
//! For the floats [`RawScale`] multiplies (one rounding); for Q1.30 increments the scale is an
//! [`IncrementScale`](crate::fixed::IncrementScale) (integer arithmetic, one rounding), converted
//! with the rounding remainder carried by an
//! [`IncrementQuantizer`](crate::fixed::IncrementQuantizer).
//!
//! # Clipping
//! A MEMS sensor that saturates reports its register's limit: the true value is at least that
//! large. [`ClipLimit`] flags a reading whose magnitude reaches the configured full scale
//! (default: `+32767` or `≤ −32767`, so `i16::MIN` too) per axis ([`Clipped`]), and the caller's
//! [`ClipPolicy`] chooses what reaches the core:
//!
//! | policy | the core gets | when |
//! |---|---|---|
//! | [`ClipPolicy::Pass`] | the clipped reading as it is (its magnitude a lower bound) | short excursions where losing the sample is worse; the flags are still returned |
//! | [`ClipPolicy::HoldLast`] | each clipped axis replaced by that axis's last unclipped reading (a rate hold); a clip before any unclipped reading is passed | a gyro that clips briefly while rotating steadily |
//! | [`ClipPolicy::Reject`] | nothing: [`Error::Clipped`] | the caller must re-initialise from an absolute reference |

use crate::{Error, Real, Vec3};

/// Which axes of a reading are at the register's limit.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Clipped {
    /// One flag per axis `x, y, z`.
    pub axes: [bool; 3],
}

impl Clipped {
    /// `true` when any axis is clipped.
    pub fn any(&self) -> bool {
        self.axes.iter().any(|&a| a)
    }
}

/// The full scale at which a register counts as clipped: a reading `r` with `r ≥ limit` or
/// `r ≤ −limit` (so `i16::MIN` is clipped for every limit).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ClipLimit {
    limit: i16,
}

impl Default for ClipLimit {
    fn default() -> Self {
        Self::FULL_REGISTER
    }
}

impl ClipLimit {
    /// The register's own limit: `+32767` and `−32767`, `−32768`.
    pub const FULL_REGISTER: Self = Self { limit: i16::MAX };

    /// A configured full scale (for a sensor that saturates below the register's range).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `limit ≤ 0`.
    pub fn try_new(limit: i16) -> Result<Self, Error> {
        if limit <= 0 {
            return Err(Error::InvalidArgument);
        }
        Ok(Self { limit })
    }

    /// The limit.
    pub fn limit(&self) -> i16 {
        self.limit
    }

    /// The clipped axes of a reading.
    #[inline]
    pub fn check(&self, raw: [i16; 3]) -> Clipped {
        // limit > 0 (checked when built), so the negation is exact; saturating keeps the compiler
        // from seeing an overflow branch it cannot rule out.
        let lo = 0i16.saturating_sub(self.limit);
        Clipped {
            axes: raw.map(|r| r >= self.limit || r <= lo),
        }
    }
}

/// What reaches the core from a clipped reading (see the [module docs](self)).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ClipPolicy {
    /// The clipped reading as it is.
    #[default]
    Pass,
    /// Each clipped axis replaced by the last unclipped reading of that axis.
    HoldLast,
    /// [`Error::Clipped`].
    Reject,
}

/// A clipping guard on a stream of raw readings: the limit, the policy and the last unclipped
/// reading of each axis (for [`ClipPolicy::HoldLast`]).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ClipGuard {
    limit: ClipLimit,
    policy: ClipPolicy,
    last: [Option<i16>; 3],
}

impl ClipGuard {
    /// A guard with the given limit and policy.
    pub fn new(limit: ClipLimit, policy: ClipPolicy) -> Self {
        Self {
            limit,
            policy,
            last: [None; 3],
        }
    }

    /// The reading the core gets and the flags of the original reading.
    ///
    /// # Errors
    /// [`Error::Clipped`] under [`ClipPolicy::Reject`] when an axis is clipped.
    pub fn filter(&mut self, raw: [i16; 3]) -> Result<([i16; 3], Clipped), Error> {
        let clipped = self.limit.check(raw);
        if clipped.any() && self.policy == ClipPolicy::Reject {
            return Err(Error::Clipped);
        }
        let mut out = raw;
        for ((o, last), c) in out.iter_mut().zip(self.last.iter_mut()).zip(clipped.axes) {
            if !c {
                *last = Some(*o);
            } else if let (ClipPolicy::HoldLast, Some(l)) = (self.policy, *last) {
                *o = l;
            }
        }
        Ok((out, clipped))
    }
}

/// The LSB scale of a raw register in a float type: `value = raw · lsb`.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RawScale<T> {
    lsb: T,
}

impl<T: Real> RawScale<T> {
    /// The scale `lsb` (the unit's value of one LSB).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for NaN or ±∞; [`Error::InvalidArgument`] for `lsb ≤ 0` or a full
    /// scale `32768·lsb` that overflows.
    pub fn try_new(lsb: T) -> Result<Self, Error> {
        if !lsb.is_finite() {
            return Err(Error::NonFinite);
        }
        if lsb <= T::ZERO || !(lsb * T::from_f64(32768.0)).is_finite() {
            return Err(Error::InvalidArgument);
        }
        Ok(Self { lsb })
    }

    /// The LSB value.
    pub fn lsb(&self) -> T {
        self.lsb
    }

    /// `raw · lsb` per axis (infallible: the scale was checked).
    #[inline]
    pub fn apply(&self, raw: [i16; 3]) -> Vec3<T> {
        Vec3::from_array(raw.map(|r| T::from_f64(f64::from(r)))) * self.lsb
    }
}
