//! Modified Rodrigues parameters with shadow-set switching.

use crate::{Error, Quat, Real, UnitQuat, Vec3};

/// Modified Rodrigues parameters `σ = n̂·tan(Θ/4) = v/(1 + w)` (Schaub & Junkins, *Analytical
/// Mechanics of Space Systems*, §3.5).
///
/// `σ` and its shadow `σˢ = −σ/|σ|²` are the same rotation. Conversions from a quaternion return
/// the set with `|σ| ≤ 1` (rotation angle `≤ π`), computed as `v/(1 + w)` after choosing `w ≥ 0`,
/// so the denominator is in `[1, 2]`: no division by a small number at any angle, and no
/// small-angle series needed (`σ ≈ φ/4` to first order, to full relative precision).
/// [`Mrp::to_unit_quat`] is `((1 − |σ|²), 2σ)/(1 + |σ|²)`, also division-safe.
///
/// At exactly 180° both `σ` and `−σ` have `|σ| = 1`; the one returned follows the sign choice of
/// [`UnitQuat::canonical`].
///
/// ```
/// use gyrostat::{Mrp, UnitQuat, Vec3};
/// // 270° about z is the same rotation as −90°: the returned set has |σ| = tan(22.5°) ≤ 1.
/// let q = UnitQuat::try_from_axis_angle(Vec3::Z, 1.5 * core::f64::consts::PI)?;
/// let s = Mrp::from_unit_quat(q);
/// assert!((s.vector().z + (core::f64::consts::PI / 8.0).tan()).abs() < 1e-15);
/// // Its shadow is the long way round, |σˢ| = 1/|σ| > 1, the same rotation.
/// let sh = s.try_shadow()?;
/// assert!(sh.to_unit_quat().angle_to(q) < 1e-15);
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mrp<T>(Vec3<T>);

impl<T: Real> Mrp<T> {
    /// Wraps `σ` (any finite vector; `|σ| > 1` is the shadow set of a rotation of angle < π).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite component.
    #[inline]
    pub fn try_new(sigma: Vec3<T>) -> Result<Self, Error> {
        Ok(Self(sigma.try_finite()?))
    }

    /// The vector `σ`.
    #[inline]
    pub const fn vector(&self) -> Vec3<T> {
        self.0
    }

    /// The shadow set `−σ/|σ|²`, the same rotation, computed on `σ` scaled to a largest
    /// component of one (no overflow or underflow of `|σ|²`).
    ///
    /// # Errors
    /// [`Error::Singular`] for `σ = 0` (the identity's shadow is at infinity) or when the shadow
    /// overflows the type (`|σ|` below about `1/MAX`).
    pub fn try_shadow(self) -> Result<Self, Error> {
        let m = self.0.max_abs();
        if m == T::ZERO {
            return Err(Error::Singular);
        }
        // −σ/|σ|² = −(σ/m) / (m·|σ/m|²), |σ/m|² ∈ [1, 3]; division, not a reciprocal of m.
        let s = self.0 / m;
        let shadow = -(s / s.norm_squared() / m);
        if shadow.is_finite() {
            Ok(Self(shadow))
        } else {
            Err(Error::Singular)
        }
    }

    /// The set with `|σ| ≤ 1`: `self` if already so, else its shadow (shadow-set switching).
    pub fn switched(self) -> Self {
        let n2 = self.0.norm_squared();
        if n2 > T::ONE {
            // n2 > 1, so the division is safe; an overflowed n2 (|σ| ≳ 1e19 in f32) maps to 0,
            // the limit of the shadow.
            if n2.is_finite() {
                Self(self.0.scale(-T::ONE / n2))
            } else {
                Self(Vec3::ZERO)
            }
        } else {
            self
        }
    }

    /// The rotation: `q = (1 − |σ|², 2σ)/(1 + |σ|²)`, the `w ≥ 0` representative for `|σ| ≤ 1`.
    pub fn to_unit_quat(self) -> UnitQuat<T> {
        let s = self.switched().0;
        let n2 = s.norm_squared();
        let d = T::ONE / (T::ONE + n2);
        UnitQuat::new_unchecked(Quat::from_parts((T::ONE - n2) * d, s.scale(T::TWO * d)))
    }

    /// `σ = v/(1 + w)` with `w ≥ 0`: `|σ| ≤ 1`.
    pub fn from_unit_quat(q: UnitQuat<T>) -> Self {
        let q = q.canonical();
        Self(q.as_quat().vector().scale(T::ONE / (T::ONE + q.w())))
    }
}

impl<T: Real> From<UnitQuat<T>> for Mrp<T> {
    #[inline]
    fn from(q: UnitQuat<T>) -> Self {
        Self::from_unit_quat(q)
    }
}

impl<T: Real> From<Mrp<T>> for UnitQuat<T> {
    #[inline]
    fn from(m: Mrp<T>) -> Self {
        m.to_unit_quat()
    }
}
