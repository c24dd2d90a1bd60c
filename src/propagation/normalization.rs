//! Renormalisation policy for propagated attitudes, and the `|q|` health value.
//!
//! An exponential-map update multiplies unit quaternions, so `|q|` drifts only by rounding (about
//! one ulp per update, a random walk); a Runge–Kutta update also leaves a truncation error in the
//! norm. Either way the attitude needs an occasional projection back onto `|q| = 1`.

use crate::{Quat, Real, Ring, UnitQuat};

/// How an integrator restores `|q| = 1` after each attitude update.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Normalization {
    /// `q / |q|` ([`UnitQuat::renormalize`]): exact to rounding; the floats pay a square root
    /// and a division (a plain square root of `|q|²`: the norm of a propagated attitude is near 1,
    /// so no overflow-safe `hypot` is needed), fixed point Newton's iteration to convergence (for
    /// `|q|² ∈ (½, 2)`).
    Exact,
    /// `q + q·(1 − |q|²)/2` ([`UnitQuat::renormalize_fast`]): one Newton step for `1/|q|`, no
    /// square root or division. If `|q|² = 1 + δ` the result has `|q|² = 1 − 3δ²/4 + O(δ³)`, so
    /// it suits per-update drift (δ of a few ulp for exponential updates, the truncation error of
    /// an RK4 step), not arbitrary input. The default.
    #[default]
    Fast,
    /// No renormalisation: `|q|` random-walks by rounding (and, for RK4, drifts by its
    /// truncation error). For measuring that drift, or when the caller renormalises itself.
    None,
}

impl Normalization {
    /// Applies the policy to an attitude.
    #[inline]
    pub fn apply<T: Ring>(self, q: UnitQuat<T>) -> UnitQuat<T> {
        match self {
            Normalization::Exact => q.renormalize(),
            Normalization::Fast => q.renormalize_fast(),
            Normalization::None => q,
        }
    }

    /// Applies the policy to a quaternion that an integrator (RK4) produced off the unit sphere.
    ///
    /// [`Normalization::Fast`] is used only while its result is unit to rounding: its error is
    /// `3δ²/4` for `|q|² = 1 + δ`, below `ε/4` for `|δ| ≤ √(ε/3)` (2.0e-4 in f32, 8.6e-9 in f64);
    /// a larger `|δ|` (an RK4 step turning by more than about 0.19 rad in f64, 1 rad in f32: the step's norm
    /// error is `θ⁶/4608` for the angle `θ`) is
    /// renormalised exactly instead. Domain: `|q|²` finite and positive (the RK4 steps of
    /// [`crate::propagation::rate_samples`] within [`crate::step_limit::MAX_STEP_ANGLE`] keep it
    /// above one half). With [`Normalization::None`] the quaternion is wrapped as is: the
    /// caller has chosen to let `|q|` drift, and [`norm_deviation`] measures by how much.
    #[inline]
    pub fn apply_quat_unchecked<T: Real>(self, q: Quat<T>) -> UnitQuat<T> {
        let q = UnitQuat::new_unchecked(q);
        match self {
            Normalization::Fast => {
                let d = q.as_quat().norm_squared() - T::ONE;
                if d.abs() <= fast_range::<T>() {
                    q.renormalize_fast()
                } else {
                    q.renormalize()
                }
            }
            _ => self.apply(q),
        }
    }
}

/// `√(ε/3)`: the largest `||q|² − 1|` for which the fast renormalisation's error `3δ²/4` stays
/// below `ε/4`.
#[inline]
fn fast_range<T: Real>() -> T {
    (T::EPSILON / T::from_f64(3.0)).sqrt()
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

/// The health value `|q|² − 1` of a propagated attitude (signed; `≈ 2(|q| − 1)` for a small
/// deviation): the [`Ring`] form of [`norm_deviation`], for fixed point.
///
/// One [`Ring::dot`] and an exact subtraction: in fixed point the squared norm is formed exactly
/// in 64 bits and rounded once, so the value is accurate to one unit of resolution (2⁻³¹ in
/// Q1.30). [`UnitQuat::renormalize_fast`] brings a deviation `δ` to `−3δ²/4`.
#[inline]
pub fn norm_squared_deviation<T: Ring>(q: UnitQuat<T>) -> T {
    q.as_quat().norm_squared() - T::ONE
}
