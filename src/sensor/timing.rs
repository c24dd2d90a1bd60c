//! Per-sample intervals from timestamps, with a stated policy for gaps and for timestamps that do
//! not increase.
//!
//! A real sample clock jitters (the x-io Fusion log: 7.56 ms to 30.24 ms around a 10 ms
//! nominal), drops samples, repeats a timestamp, and — for a 32-bit microsecond counter — wraps
//! every 2³² µs ≈ 71.6 min. [`SampleClock`] (timestamps in seconds, f32 or f64) and
//! [`MicrosClock`] (a `u32` microsecond counter, differences taken `wrapping_sub`) turn each
//! timestamp into an [`Interval`]: the elapsed time since the previous accepted sample, or one of
//! the cases below. Nothing is ever silently jumped over.
//!
//! # Policy
//! With `h` the nominal interval and `k` the gap factor (default [`DEFAULT_GAP_FACTOR`] = 5):
//!
//! | elapsed `dt` | result | what the caller should do |
//! |---|---|---|
//! | first timestamp | [`Interval::First`] | nothing to integrate yet (or integrate from a known `t0`) |
//! | `0 < dt ≤ k·h` | [`Interval::Step`] | integrate the sample over `dt` |
//! | `dt > k·h` | [`Interval::Gap`] | samples were lost: the coning history spans the gap, so flush and restart it (a rule's pending samples, a rate method's node history); an increment gyro's new increment still covers only its own sensor interval, not the gap, so the rotation during the gap is unknown: integrate it with a rate hold (the last rate over `dt`) if that is acceptable, or re-initialise the attitude from an absolute reference |
//! | `dt = 0` | [`Interval::Repeated`] | a duplicate row: skip the sample (the clock keeps the earlier timestamp) |
//! | `dt < 0` | [`Interval::Backwards`] | an out-of-order sample: skip it (the clock keeps the earlier timestamp); if the source restarted, call [`SampleClock::restart`] |
//!
//! A gap and a backwards step are decided on the elapsed time only; for the wrapping counter a
//! wrapped difference of `2³¹` µs (≈ 35.8 min) or more is read as backwards (a forward step that
//! long is not distinguishable from a backwards one in 32 bits).

use crate::real::Q30;
use crate::{Error, Real};

/// The default gap factor: an interval longer than 5 nominal intervals is a [`Interval::Gap`].
pub const DEFAULT_GAP_FACTOR: f64 = 5.0;

/// The elapsed time since the previous accepted sample, classified by the clock's policy (see the
/// [module docs](self)). `D` is the duration type: seconds in `T` for [`SampleClock`], `u32`
/// microseconds for [`MicrosClock`].
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interval<D> {
    /// The first timestamp the clock sees (or the first after [`SampleClock::restart`]): no
    /// interval yet.
    First,
    /// A regular step `0 < dt ≤ gap_factor · nominal`.
    Step(D),
    /// A step longer than `gap_factor · nominal`: samples were lost. The clock accepts the
    /// timestamp (the next interval is measured from it).
    Gap(D),
    /// The same timestamp as the previous accepted sample. The clock keeps its state.
    Repeated,
    /// A timestamp before the previous accepted one, by the duration given (positive). The clock
    /// keeps its state.
    Backwards(D),
}

impl<D: Copy> Interval<D> {
    /// The elapsed time of a [`Interval::Step`] or a [`Interval::Gap`], `None` otherwise.
    pub fn elapsed(self) -> Option<D> {
        match self {
            Interval::Step(d) | Interval::Gap(d) => Some(d),
            _ => None,
        }
    }
}

/// A sample clock on timestamps in seconds (f32 or f64): the interval policy of the
/// [module docs](self).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleClock<T> {
    nominal: T,
    max_step: T,
    last: Option<T>,
}

impl<T: Real> SampleClock<T> {
    /// A clock with nominal interval `nominal` (s) and the default gap factor
    /// ([`DEFAULT_GAP_FACTOR`]).
    ///
    /// # Errors
    /// As [`SampleClock::try_with_gap_factor`].
    pub fn try_new(nominal: T) -> Result<Self, Error> {
        Self::try_with_gap_factor(nominal, T::from_f64(DEFAULT_GAP_FACTOR))
    }

    /// A clock with nominal interval `nominal` (s): an elapsed time beyond
    /// `gap_factor · nominal` is a [`Interval::Gap`].
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite argument; [`Error::InvalidArgument`] for
    /// `nominal ≤ 0`, `gap_factor < 1` or a product `gap_factor · nominal` that overflows.
    pub fn try_with_gap_factor(nominal: T, gap_factor: T) -> Result<Self, Error> {
        if !nominal.is_finite() || !gap_factor.is_finite() {
            return Err(Error::NonFinite);
        }
        let max_step = nominal * gap_factor;
        if nominal <= T::ZERO || gap_factor < T::ONE || !max_step.is_finite() {
            return Err(Error::InvalidArgument);
        }
        Ok(Self {
            nominal,
            max_step,
            last: None,
        })
    }

    /// The nominal interval (s).
    pub fn nominal(&self) -> T {
        self.nominal
    }

    /// The longest interval that is still a [`Interval::Step`] (s).
    pub fn max_step(&self) -> T {
        self.max_step
    }

    /// The last accepted timestamp, if any.
    pub fn last(&self) -> Option<T> {
        self.last
    }

    /// Forgets the last timestamp and starts again at `t` (after a source restart, or to give the
    /// start `t0` of the first interval). `None`: the next timestamp is [`Interval::First`].
    pub fn restart(&mut self, t: Option<T>) {
        self.last = t;
    }

    /// Classifies the timestamp `t` (s) against the last accepted one (see the
    /// [module docs](self)); a [`Interval::First`], [`Interval::Step`] or [`Interval::Gap`]
    /// accepts `t`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite timestamp, or an elapsed time that overflows
    /// (the clock keeps its state).
    pub fn interval(&mut self, t: T) -> Result<Interval<T>, Error> {
        if !t.is_finite() {
            return Err(Error::NonFinite);
        }
        let Some(last) = self.last else {
            self.last = Some(t);
            return Ok(Interval::First);
        };
        let dt = t - last;
        if !dt.is_finite() {
            return Err(Error::NonFinite);
        }
        if dt == T::ZERO {
            return Ok(Interval::Repeated);
        }
        if dt < T::ZERO {
            return Ok(Interval::Backwards(-dt));
        }
        self.last = Some(t);
        Ok(if dt > self.max_step {
            Interval::Gap(dt)
        } else {
            Interval::Step(dt)
        })
    }
}

/// A sample clock on a free-running 32-bit microsecond counter that wraps at 2³² µs
/// (≈ 71.6 min): elapsed times are `t.wrapping_sub(last)`, so a wrap between two samples is an
/// ordinary step. A wrapped difference of 2³¹ µs or more is [`Interval::Backwards`] (see the
/// [module docs](self)).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MicrosClock {
    nominal_us: u32,
    max_step_us: u32,
    last: Option<u32>,
}

impl MicrosClock {
    /// A clock with nominal interval `nominal_us` µs and gap factor `gap_factor` (an elapsed time
    /// beyond `gap_factor · nominal_us` is a [`Interval::Gap`]).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `nominal_us = 0`, `gap_factor = 0`, or a product of `2³¹`
    /// µs or more (not distinguishable from a backwards step).
    pub fn try_new(nominal_us: u32, gap_factor: u32) -> Result<Self, Error> {
        let max_step_us = nominal_us
            .checked_mul(gap_factor)
            .ok_or(Error::InvalidArgument)?;
        if nominal_us == 0 || gap_factor == 0 || max_step_us >= 1 << 31 {
            return Err(Error::InvalidArgument);
        }
        Ok(Self {
            nominal_us,
            max_step_us,
            last: None,
        })
    }

    /// The nominal interval (µs).
    pub fn nominal_us(&self) -> u32 {
        self.nominal_us
    }

    /// The longest interval that is still a [`Interval::Step`] (µs).
    pub fn max_step_us(&self) -> u32 {
        self.max_step_us
    }

    /// Forgets the last timestamp and starts again at `t_us` (`None`: the next timestamp is
    /// [`Interval::First`]).
    pub fn restart(&mut self, t_us: Option<u32>) {
        self.last = t_us;
    }

    /// Classifies the counter value `t_us` against the last accepted one (infallible: every
    /// `u32` is a timestamp). A [`Interval::First`], [`Interval::Step`] or [`Interval::Gap`]
    /// accepts it.
    pub fn interval(&mut self, t_us: u32) -> Interval<u32> {
        let Some(last) = self.last else {
            self.last = Some(t_us);
            return Interval::First;
        };
        let dt = t_us.wrapping_sub(last);
        if dt == 0 {
            return Interval::Repeated;
        }
        if dt >= 1 << 31 {
            return Interval::Backwards(last.wrapping_sub(t_us));
        }
        self.last = Some(t_us);
        if dt > self.max_step_us {
            Interval::Gap(dt)
        } else {
            Interval::Step(dt)
        }
    }
}

/// Microseconds as seconds in a float type: `us · 10⁻⁶`, one rounding for f64 (exact integer,
/// then one multiply by the rounded 10⁻⁶: relative error ≤ 2 ulp).
#[inline]
pub fn micros_to_seconds<T: Real>(us: u32) -> T {
    T::from_f64(f64::from(us) * 1e-6)
}

/// Microseconds as a Q1.30 time step (s), in integer arithmetic:
/// `round(us · 2³⁰ / 10⁶)` (ties away from zero), error ≤ 2⁻³¹ s.
///
/// # Errors
/// [`Error::OutOfRange`] for `us ≥ 2·10⁶` (2 s, beyond Q1.30).
#[inline]
pub fn micros_to_q30(us: u32) -> Result<Q30, Error> {
    if us >= 2_000_000 {
        return Err(Error::OutOfRange);
    }
    // us < 2·10⁶ < 2²¹: us·2³⁰ < 2⁵¹ fits in u64; the quotient < 2³¹ fits in i32.
    let q = ((u64::from(us) << 30) + 500_000) / 1_000_000;
    Ok(Q30::from_bits(q as i32))
}

/// The coefficient `(h₁ + h₂)²/(6 h₁ h₂)` of the 2-sample rule for unequal sub-intervals
/// ([`crate::propagation::coning::two_sample_unequal_terms`]) from two intervals in
/// microseconds, in Q1.30 and integer arithmetic only (for
/// [`crate::propagation::kernels::coning2_update_unequal`] with `T = Q30`): an exact quotient
/// by long division, rounded to nearest (ties up), error ≤ 2⁻³¹.
///
/// # Errors
/// [`Error::InvalidArgument`] for an interval of 0 or above 2²⁰ µs (1.05 s);
/// [`Error::OutOfRange`] when the coefficient reaches 2 (the intervals' ratio outside about
/// `(0.102, 9.9)`).
pub fn unequal_coefficient_q30(h1_us: u32, h2_us: u32) -> Result<Q30, Error> {
    if h1_us == 0 || h2_us == 0 || h1_us > 1 << 20 || h2_us > 1 << 20 {
        return Err(Error::InvalidArgument);
    }
    let s = u64::from(h1_us) + u64::from(h2_us); // ≤ 2²¹
    let num = s * s; // ≤ 2⁴²
    let den = 6 * u64::from(h1_us) * u64::from(h2_us); // in [6, 6·2⁴⁰]
    let (Some(mut q), Some(mut rem)) = (num.checked_div(den), num.checked_rem(den)) else {
        return Err(Error::InvalidArgument);
    };
    if q >= 2 {
        return Err(Error::OutOfRange);
    }
    // 30 fraction bits, 10 per step: rem < den < 2⁴³, so rem·2¹⁰ < 2⁵³.
    for _ in 0..3 {
        rem <<= 10;
        let (Some(d), Some(r)) = (rem.checked_div(den), rem.checked_rem(den)) else {
            return Err(Error::InvalidArgument);
        };
        q = (q << 10) | d;
        rem = r;
    }
    if 2 * rem >= den {
        q += 1;
    }
    if q >= 1 << 31 {
        return Err(Error::OutOfRange);
    }
    Ok(Q30::from_bits(q as i32))
}
