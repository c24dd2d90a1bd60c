//! The propagation loops over gyro samples, once for the `propagate` tool and Python's
//! `propagate_increments` / `propagate_rates`: the library's integrators with the checks the
//! faces apply to every sample and every attitude.
//!
//! - [`Increments`]: gyro increments `Δθ` (rad) with a coning rule; after each sample the
//!   provisional attitude (a rule of `N` samples updates once per `N` increments, and a sample
//!   inside a group applies the pending increments with the highest-order rule that fits them,
//!   not fed back), at the end [`Increments::flush`].
//! - [`Rates`]: rate samples (rad/s) at a fixed step with an integration method: the attitudes
//!   at the sample times as they become due, then [`Rates::finish`].
//! - [`FixedIncrements`]: the increment path in Q1.30 (the firmware's integer code): each
//!   increment quantised with its rounding remainder carried into the next, the attitude a
//!   `CarriedAttitude` renormalised with the fast rule.
//!
//! Checks ([`PropagateError`]): a non-finite sample; for the `exp` rule an increment whose turn
//! is too large to be known to [`TURN_RESOLUTION`] in the run's type; the library's errors
//! (a sample beyond half a turn for the coning rules and the rate methods); an attitude that is
//! not a finite unit quaternion to 1e-3 (a collapsed or overflowed norm: samples too large for
//! the step). A sample that fails leaves the integrator as it was.

use gyrostat::fixed::IncrementQuantizer;
use gyrostat::propagation::CarriedAttitude;
use gyrostat::propagation::{
    ConingRule, IncrementIntegrator, Normalization, PropagatedAttitude, RateIntegrator, RateMethod,
};
use gyrostat::real::Q30;
use gyrostat::{Error, Real, UnitQuat, Vec3};

/// The largest rounding of one increment's turn angle the `exp` rule accepts (rad). An angle
/// `θ` is held to `θ·ε` of the run's type, and the attitude of that sample can be no better:
/// beyond `θ > 1e-3/ε` (4.5e12 rad in f64, 8.4e3 rad in f32) its rows would be noise however
/// exactly the rule computes. Only `exp` needs the check: the library applies an exact
/// exponential to an increment of any length, while the coning rules and the rate methods
/// reject a sample beyond half a turn themselves (`StepTooLong`).
pub const TURN_RESOLUTION: f64 = 1e-3;

/// Why a sample stops a propagation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PropagateError {
    /// A sample with a NaN or infinite component.
    NonFinite,
    /// An `exp` increment turning by `turn` rad, beyond `limit` = [`TURN_RESOLUTION`]`/ε`.
    Unresolvable {
        /// The increment's angle, rad.
        turn: f64,
        /// The largest angle accepted in the run's type, rad.
        limit: f64,
    },
    /// The library rejected the sample (a step beyond half a turn, ...).
    Library(Error),
    /// The increment is outside Q1.30's range (`|value| < 2` rad).
    Quantize(Error),
    /// The attitude is not a finite unit quaternion (its components as f64).
    NotUnit([f64; 4]),
}

/// Whether `q` is a finite unit quaternion to 1e-3 (the attitude is renormalised exactly after
/// every update: anything visibly off unit norm is a failed update).
pub fn is_unit<T: Real>(q: UnitQuat<T>) -> bool {
    let c = q.to_array();
    let n2 = c.iter().fold(T::ZERO, |acc, &x| acc + x * x);
    c.iter().all(|x| x.is_finite()) && (n2 - T::ONE).abs() <= T::from_f64(1e-3)
}

fn checked<T: Real>(q: UnitQuat<T>) -> Result<UnitQuat<T>, PropagateError> {
    if is_unit(q) {
        Ok(q)
    } else {
        Err(PropagateError::NotUnit(q.to_array().map(T::to_f64)))
    }
}

/// Checks that the increment `v` turns the body by an angle whose rounding in `T` stays within
/// [`TURN_RESOLUTION`].
///
/// # Errors
/// [`PropagateError::Unresolvable`].
pub fn resolvable<T: Real>(v: Vec3<T>) -> Result<(), PropagateError> {
    let [x, y, z] = v.to_array().map(|c| c.to_f64());
    let turn = x.hypot(y).hypot(z);
    let limit = TURN_RESOLUTION / T::EPSILON.to_f64();
    if turn <= limit {
        Ok(())
    } else {
        Err(PropagateError::Unresolvable { turn, limit })
    }
}

/// Increments through a coning rule (see the module docs), the attitude carried as `A` (a
/// plain `UnitQuat<T>` or a compensated attitude).
pub struct Increments<T: Real, A> {
    integ: IncrementIntegrator<T, A>,
    rule: ConingRule,
}

impl<T: Real, A: PropagatedAttitude<T> + From<UnitQuat<T>>> Increments<T, A> {
    /// Starts at `q0` with `rule` (exact renormalisation).
    pub fn new(q0: UnitQuat<T>, rule: ConingRule) -> Self {
        Self {
            integ: IncrementIntegrator::new(A::from(q0), rule, Normalization::Exact),
            rule,
        }
    }

    /// One increment: the provisional attitude after it.
    ///
    /// # Errors
    /// [`PropagateError`] (the integrator unchanged for a rejected sample; after
    /// [`PropagateError::NotUnit`] it is spoilt: stop).
    pub fn push(&mut self, v: Vec3<T>) -> Result<UnitQuat<T>, PropagateError> {
        if !v.is_finite() {
            return Err(PropagateError::NonFinite);
        }
        if self.rule == ConingRule::Exp {
            resolvable(v)?;
        }
        self.integ.push(v).map_err(PropagateError::Library)?;
        checked(self.integ.provisional_attitude())
    }

    /// The attitude after every increment so far (a partial group applied).
    ///
    /// # Errors
    /// [`PropagateError::NotUnit`].
    pub fn flush(&mut self) -> Result<UnitQuat<T>, PropagateError> {
        checked(self.integ.flush())
    }
}

/// Rate samples at a fixed step through a method (see the module docs).
pub struct Rates<T: Real, A> {
    integ: RateIntegrator<T, A>,
}

impl<T: Real, A: PropagatedAttitude<T> + From<UnitQuat<T>>> Rates<T, A> {
    /// Starts at `q0` with `method` and the step `dt` (s, given in f64: its rounding remainder
    /// in `T` is carried, so a step not exact in `T` does not drift the time base).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] or [`Error::NonFinite`] for a step that is not a positive
    /// finite number of `T` (the library's `RateIntegrator::try_new`).
    pub fn try_new(q0: UnitQuat<T>, method: RateMethod, dt: f64) -> Result<Self, Error> {
        let step = T::from_f64(dt);
        if !step.is_finite() {
            return Err(Error::NonFinite);
        }
        if step <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
        let dt_lo = T::from_f64(dt - step.to_f64());
        let integ = RateIntegrator::try_new(A::from(q0), method, Normalization::Exact, step)
            .and_then(|i| i.try_with_step_remainder(dt_lo))?;
        Ok(Self { integ })
    }

    /// One rate sample: the attitudes that became due (at the sample times, in order), each
    /// checked ([`PropagateError::NotUnit`] for one that is not a finite unit quaternion: stop
    /// there, the integrator is spoilt).
    ///
    /// # Errors
    /// [`PropagateError`]: a non-finite sample or the library's error (the integrator
    /// unchanged).
    #[allow(clippy::type_complexity)]
    pub fn push(
        &mut self,
        v: Vec3<T>,
    ) -> Result<Vec<Result<UnitQuat<T>, PropagateError>>, PropagateError> {
        if !v.is_finite() {
            return Err(PropagateError::NonFinite);
        }
        let qs = self.integ.push(v).map_err(PropagateError::Library)?;
        Ok(qs.into_iter().map(checked).collect())
    }

    /// The attitudes still due after the last sample.
    pub fn finish(self) -> Vec<Result<UnitQuat<T>, PropagateError>> {
        self.integ.finish().into_iter().map(checked).collect()
    }
}

/// The increment path in Q1.30 (see the module docs).
pub struct FixedIncrements {
    integ: IncrementIntegrator<Q30, CarriedAttitude<30>>,
    quantizer: IncrementQuantizer<30>,
}

impl FixedIncrements {
    /// Starts at `q0` with `rule`.
    pub fn new(q0: UnitQuat<Q30>, rule: ConingRule) -> Self {
        Self {
            integ: IncrementIntegrator::new(CarriedAttitude::new(q0), rule, Normalization::Fast),
            quantizer: IncrementQuantizer::<30>::new(),
        }
    }

    /// One increment (rad, f64), quantised: the provisional attitude after it.
    ///
    /// # Errors
    /// [`PropagateError::Quantize`]: a value outside Q1.30 (the state unchanged);
    /// [`PropagateError::Library`]: the integrator's error.
    pub fn push(&mut self, v: Vec3<f64>) -> Result<UnitQuat<Q30>, PropagateError> {
        let v = self
            .quantizer
            .try_quantize(v)
            .map_err(PropagateError::Quantize)?;
        self.integ.push(v).map_err(PropagateError::Library)?;
        Ok(self.integ.provisional_attitude())
    }

    /// The attitude after every increment so far.
    pub fn flush(&mut self) -> UnitQuat<Q30> {
        self.integ.flush()
    }
}
