//! The checked streaming integrator of gyro increments: [`IncrementIntegrator`].

use heapless::Vec as HVec;

#[cfg(doc)]
use crate::propagation::CompensatedAttitude;
use crate::propagation::attitude::PropagatedAttitude;
use crate::propagation::coning::ConingRule;
#[cfg(doc)]
use crate::propagation::coning::rotation_vector_for;
use crate::propagation::normalization::Normalization;
use crate::rotation::ExpMap;
use crate::step_limit::within_step_limit;
use crate::{Error, UnitQuat, Vec3};

/// Buffer of the increments of the current update group.
pub type IncrementBuffer<T> = HVec<Vec3<T>, 4>;

/// Increment integrator: owns the attitude and the increments of the current update group.
///
/// Plain data (no allocation, fixed capacity), so an interrupt handler can own it. Feed one
/// increment per sample with [`IncrementIntegrator::push`]; every
/// [`ConingRule::samples_per_update`] increments it performs one attitude update
/// `q ← normalise(q ⊗ exp(φ))`.
///
/// The attitude it carries is a [`UnitQuat`] (the plain update) or, when it is started from a
/// [`CompensatedAttitude`], the compensated pair (see [`crate::propagation::compensated_attitude`]: the
/// f32 attitude then does not drift from rounding over hours).
///
/// ```
/// use gyrostat::{UnitQuat, Vec3};
/// use gyrostat::propagation::{ConingRule, IncrementIntegrator, Normalization};
/// let mut integ = IncrementIntegrator::new(UnitQuat::<f32>::IDENTITY, ConingRule::TwoSample, Normalization::Fast);
/// assert_eq!(integ.push(Vec3::new(0.001, 0.0, 0.0))?, None); // first of the pair
/// assert!(integ.push(Vec3::new(0.0, 0.001, 0.0))?.is_some()); // update done
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct IncrementIntegrator<T, A = UnitQuat<T>> {
    q: A,
    rule: ConingRule,
    norm: Normalization,
    group: IncrementBuffer<T>,
    /// The increment just before the current group (zero before the first).
    previous: Vec3<T>,
}

impl<T: ExpMap, A: PropagatedAttitude<T>> IncrementIntegrator<T, A> {
    /// Starts at attitude `q0`: a [`UnitQuat`] (plain) or a [`CompensatedAttitude`].
    pub fn new(q0: A, rule: ConingRule, norm: Normalization) -> Self {
        Self {
            q: q0,
            rule,
            norm,
            group: HVec::new(),
            previous: Vec3::ZERO,
        }
    }

    /// Adds one increment `Δθ` (rad, body frame, the integral of `ω` over one sample interval).
    /// Returns the new attitude when it completes an update group, `None` otherwise.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite component. With a coning rule,
    /// [`Error::StepTooLong`] for an increment larger than
    /// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) (the coning rules are truncated series in the
    /// increments, see there) and, in fixed point, [`Error::OutOfRange`] for an increment
    /// component of a quarter of the format's range or more (0.25 rad in Q1.30: below it a group
    /// of four increments, its rule's lever and cross product cannot saturate). With
    /// [`ConingRule::Exp`] (the exact exponential of each increment, no series) any increment
    /// whose squared norm is finite is taken, so that a rotation vector of any length is applied
    /// as given; [`Error::InvalidArgument`] when the square overflows. Either way the increment
    /// is discarded and the state is unchanged.
    pub fn push(&mut self, dtheta: Vec3<T>) -> Result<Option<UnitQuat<T>>, Error> {
        let dtheta = dtheta.try_finite()?;
        if self.rule == ConingRule::Exp {
            if !dtheta.norm_squared().is_finite() {
                return Err(Error::InvalidArgument);
            }
        } else {
            if !within_step_limit(dtheta) {
                return Err(Error::StepTooLong);
            }
            // 8·|Δθᵢ| within the range (always for the floats).
            let fits = |c: T| T::dot_fits([c.twice(); 4], [T::ONE; 4]);
            if !(fits(dtheta.x) && fits(dtheta.y) && fits(dtheta.z)) {
                return Err(Error::OutOfRange);
            }
        }
        let n = self.rule.samples_per_update();
        if self.group.push(dtheta).is_err() {
            // Unreachable: the group is cleared whenever it reaches n ≤ 4 = capacity. Handled
            // without panicking by committing the full group and starting a new one.
            self.commit();
            let _ = self.group.push(dtheta);
        }
        if self.group.len() >= n {
            self.commit();
            return Ok(Some(self.q.attitude()));
        }
        Ok(None)
    }

    fn commit(&mut self) {
        if let Some(last) = self.group.last().copied() {
            self.q = self
                .q
                .increments(self.rule, self.previous, self.group.as_slice(), self.norm);
            self.previous = last;
            self.group.clear();
        }
    }

    /// The attitude after the last completed update group.
    pub fn attitude(&self) -> UnitQuat<T> {
        self.q.attitude()
    }

    /// The carried attitude (for a [`CompensatedAttitude`], with its low part).
    pub fn carried_attitude(&self) -> A {
        self.q
    }

    /// Increments received since the last update (0 to `samples_per_update − 1`).
    pub fn pending(&self) -> usize {
        self.group.len()
    }

    /// The attitude after every increment received so far, without committing: the pending
    /// increments of an incomplete group are applied with the highest-order rule that fits
    /// their number (see [`rotation_vector_for`]). Equal to [`IncrementIntegrator::attitude`]
    /// when nothing is pending.
    pub fn provisional_attitude(&self) -> UnitQuat<T> {
        if self.group.is_empty() {
            self.q.attitude()
        } else {
            self.q
                .increments(self.rule, self.previous, self.group.as_slice(), self.norm)
                .attitude()
        }
    }

    /// Commits a trailing partial group (end of a record) with the highest-order rule that fits
    /// it, and returns the attitude after every increment received.
    pub fn flush(&mut self) -> UnitQuat<T> {
        self.commit();
        self.q.attitude()
    }
}

#[cfg(feature = "defmt")]
impl<T: ExpMap + defmt::Format> defmt::Format for IncrementIntegrator<T> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "IncrementIntegrator(q={}, rule={}, norm={}, pending={})",
            self.q,
            self.rule,
            self.norm,
            self.group.len()
        )
    }
}
