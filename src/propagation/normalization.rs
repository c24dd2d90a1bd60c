//! Renormalisation policy for propagated attitudes, and the `|q|` health value.
//!
//! An exponential-map update multiplies unit quaternions, so `|q|` drifts only by rounding (about
//! one ulp per update, a random walk); a Runge–Kutta update also leaves a truncation error in the
//! norm. Either way the attitude needs an occasional projection back onto `|q| = 1`.

use crate::{Quat, Real, UnitQuat};

/// How an integrator restores `|q| = 1` after each attitude update.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Normalization {
    /// `q / |q|` ([`UnitQuat::renormalize`]): exact to rounding; costs a square root and a
    /// division (a plain square root of `|q|²`: the norm of a propagated attitude is near 1, so
    /// no overflow-safe `hypot` is needed).
    Exact,
    /// `q · (3 − |q|²)/2` ([`UnitQuat::renormalize_fast`]): one Newton step for `1/|q|`, no square
    /// root. If `|q|² = 1 + δ` the result has `|q|² = 1 − 3δ²/4 + O(δ³)`, so it suits per-update
    /// drift (δ of a few ulp for exponential updates, the truncation error of an RK4 step), not
    /// arbitrary input. The default.
    #[default]
    Fast,
    /// No renormalisation: `|q|` random-walks by rounding (and, for RK4, drifts by its
    /// truncation error). For measuring that drift, or when the caller renormalises itself.
    None,
}

impl Normalization {
    /// Applies the policy to an attitude.
    #[inline]
    pub fn apply<T: Real>(self, q: UnitQuat<T>) -> UnitQuat<T> {
        match self {
            Normalization::Exact => q.renormalize(),
            Normalization::Fast => q.renormalize_fast(),
            Normalization::None => q,
        }
    }

    /// Applies the policy to a quaternion that an integrator (RK4) produced off the unit sphere.
    ///
    /// With [`Normalization::None`] the quaternion is wrapped as is: the caller has chosen to let
    /// `|q|` drift, and [`norm_deviation`] measures by how much.
    #[inline]
    pub fn apply_quat<T: Real>(self, q: Quat<T>) -> UnitQuat<T> {
        self.apply(UnitQuat::new_unchecked(q))
    }
}

/// The health value `|q| − 1` of a propagated attitude (signed; 0 for an exact unit quaternion).
///
/// Computed as `(|q|² − 1)/(|q| + 1)`: the subtraction is exact for `|q|² ∈ [½, 2]` (Sterbenz),
/// so the value is accurate to rounding even when it is a few ulp, where `|q| − 1` computed
/// directly would be dominated by the rounding of `|q|`.
#[inline]
pub fn norm_deviation<T: Real>(q: UnitQuat<T>) -> T {
    let n2 = q.as_quat().norm_squared();
    (n2 - T::ONE) / (n2.sqrt() + T::ONE)
}
