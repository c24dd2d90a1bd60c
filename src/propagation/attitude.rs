//! The attitude an increment or rate integrator carries: [`PropagatedAttitude`], implemented by
//! the plain [`UnitQuat`] (the kernels of [`crate::propagation::kernels`]) and by the
//! [`CompensatedAttitude`] (its compensated updates). The integrators are generic over it, so
//! one integrator serves both.

use crate::propagation::compensated_attitude::{
    CompensatedAttitude, advance_compensated, rule_vector,
};
use crate::propagation::coning::ConingRule;
use crate::propagation::kernels::{advance_plain, apply_rule};
use crate::propagation::normalization::Normalization;
use crate::propagation::rate_samples::{RateMethod, Weights};
use crate::rotation::ExpMap;
use crate::{Real, UnitQuat, Vec3};

/// The attitude an increment or rate integrator carries: a [`UnitQuat`] (the plain update, for
/// every [`ExpMap`] type, fixed point included) or a [`CompensatedAttitude`] (the compensated
/// update, [`Real`] types). Sealed.
pub trait PropagatedAttitude<T>: sealed::Propagate<T> {}

impl<T: ExpMap> PropagatedAttitude<T> for UnitQuat<T> {}
impl<T: Real> PropagatedAttitude<T> for CompensatedAttitude<T> {}

pub(crate) mod sealed {
    use super::*;

    /// The updates of an attitude kind (crate-internal: the methods of
    /// [`super::PropagatedAttitude`]).
    pub trait Propagate<T>: Copy {
        /// The attitude, rounded to `T`.
        fn attitude(&self) -> UnitQuat<T>;
        /// Starts at `q` (the compensated attitude: low part zero).
        fn from_unit(q: UnitQuat<T>) -> Self;
        /// `q ⊗ exp(φ)`, then `norm`: the update kernel `mul_exp_unchecked` of the kind (the
        /// estimator's prediction).
        fn mul_exp_vector(self, phi: Vec3<T>, norm: Normalization) -> Self;
        /// [`Propagate::mul_exp_vector`] given `phi_sq = |φ|²` as `phi.norm_squared()` forms
        /// it (a caller that has it: the light estimator's step): the plain float update takes
        /// it for its own (the same bits, three products and two sums fewer), the other kinds
        /// form their update from `φ` alone.
        #[inline(always)]
        fn mul_exp_vector_sq(self, phi: Vec3<T>, _phi_sq: T, norm: Normalization) -> Self
        where
            T: Real,
        {
            self.mul_exp_vector(phi, norm)
        }
        /// One update by `rule` from `samples` (1 to 4 increments; `previous` the increment
        /// before them).
        fn increments(
            self,
            rule: ConingRule,
            previous: Vec3<T>,
            samples: &[Vec3<T>],
            norm: Normalization,
        ) -> Self;
        /// One step of `method` over one interval of an `M`-sample window (`weights`: that
        /// interval's interpolation rows), step `h + h_lo`.
        fn rates<const M: usize>(
            self,
            method: RateMethod,
            window: &[Vec3<T>; M],
            weights: &Weights<M>,
            h: T,
            h_lo: T,
            norm: Normalization,
        ) -> Self
        where
            T: Real;
    }

    impl<T: ExpMap> Propagate<T> for UnitQuat<T> {
        #[inline(always)]
        fn attitude(&self) -> UnitQuat<T> {
            *self
        }
        #[inline(always)]
        fn from_unit(q: UnitQuat<T>) -> Self {
            q
        }
        #[inline(always)]
        fn mul_exp_vector(self, phi: Vec3<T>, norm: Normalization) -> Self {
            self.mul_exp_unchecked(phi, norm)
        }
        /// The floats' `ExpMap::mul_exp`, `q ⊗ exp(φ)`, with the exponential's `|φ|²` given.
        #[inline(always)]
        fn mul_exp_vector_sq(self, phi: Vec3<T>, phi_sq: T, norm: Normalization) -> Self
        where
            T: Real,
        {
            let e = UnitQuat::exp_unchecked_sq(phi, phi_sq);
            norm.apply(UnitQuat::new_unchecked(self.into_quat() * *e.as_quat()))
        }
        #[inline(always)]
        fn increments(
            self,
            rule: ConingRule,
            previous: Vec3<T>,
            samples: &[Vec3<T>],
            norm: Normalization,
        ) -> Self {
            apply_rule(self, rule, previous, samples, norm)
        }
        #[inline(always)]
        fn rates<const M: usize>(
            self,
            method: RateMethod,
            window: &[Vec3<T>; M],
            weights: &Weights<M>,
            h: T,
            _h_lo: T,
            norm: Normalization,
        ) -> Self
        where
            T: Real,
        {
            advance_plain(self, method, window, weights, h, norm)
        }
    }

    impl<T: Real> Propagate<T> for CompensatedAttitude<T> {
        #[inline(always)]
        fn attitude(&self) -> UnitQuat<T> {
            CompensatedAttitude::attitude(self)
        }
        #[inline(always)]
        fn from_unit(q: UnitQuat<T>) -> Self {
            CompensatedAttitude::new(q)
        }
        #[inline(always)]
        fn mul_exp_vector(self, phi: Vec3<T>, norm: Normalization) -> Self {
            self.mul_exp_pair(phi, Vec3::ZERO, norm)
        }
        #[inline(always)]
        fn increments(
            self,
            rule: ConingRule,
            previous: Vec3<T>,
            samples: &[Vec3<T>],
            norm: Normalization,
        ) -> Self {
            let (phi, phi_lo) = rule_vector(rule, previous, samples);
            self.mul_exp_pair(phi, phi_lo, norm)
        }
        #[inline(always)]
        fn rates<const M: usize>(
            self,
            method: RateMethod,
            window: &[Vec3<T>; M],
            weights: &Weights<M>,
            h: T,
            h_lo: T,
            norm: Normalization,
        ) -> Self {
            advance_compensated(self, method, window, weights, h, h_lo, norm)
        }
    }
}
