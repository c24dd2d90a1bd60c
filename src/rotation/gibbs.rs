//! Classical Rodrigues parameters (the Gibbs vector).

use crate::{Error, Quat, Real, UnitQuat, Vec3};

/// The Gibbs vector (classical Rodrigues parameters) `g = n̂·tan(Θ/2) = v/w`.
///
/// Infinite at Θ = 180°: [`Gibbs::try_from_unit_quat`] returns [`Error::Singular`] there, within
/// [`Gibbs::min_w`]. The same rotation for `q` and `−q` (`v/w` is sign-invariant).
///
/// ```
/// use gyrostat::{Error, Gibbs, UnitQuat, Vec3};
/// let half_turn = UnitQuat::try_from_axis_angle(Vec3::Z, core::f64::consts::PI)?;
/// assert_eq!(Gibbs::try_from_unit_quat(half_turn), Err(Error::Singular));
/// let q = UnitQuat::try_from_axis_angle(Vec3::Z, core::f64::consts::FRAC_PI_2)?;
/// assert!((Gibbs::try_from_unit_quat(q)?.vector().z - 1.0).abs() < 1e-15); // tan(45°)
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gibbs<T>(Vec3<T>);

impl<T: Real> Gibbs<T> {
    /// `|w|` at or below which the Gibbs vector is reported singular: `ε` (1.2e-7 f32,
    /// 2.2e-16 f64). Below it `|g| ≥ 1/ε`, and the rounding of `w` (about `ε/2` absolute in a
    /// unit quaternion) is at least half of `w` itself, so `g`'s magnitude has no correct digit.
    pub fn min_w() -> T {
        T::EPSILON
    }

    /// Wraps `g` (any finite vector).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite component.
    #[inline]
    pub fn try_new(g: Vec3<T>) -> Result<Self, Error> {
        Ok(Self(g.try_finite()?))
    }

    /// The vector `g`.
    #[inline]
    pub const fn vector(&self) -> Vec3<T> {
        self.0
    }

    /// `g = v/w`.
    ///
    /// # Errors
    /// [`Error::Singular`] when `|w| ≤` [`Gibbs::min_w`] (rotation within about `2ε` of 180°).
    pub fn try_from_unit_quat(q: UnitQuat<T>) -> Result<Self, Error> {
        let w = q.w();
        if w.abs() <= Self::min_w() {
            return Err(Error::Singular);
        }
        Ok(Self(q.as_quat().vector().scale(T::ONE / w)))
    }

    /// `q = (1, g)/√(1 + |g|²)` with `w > 0`, normalised with scaling so that a huge `g` (near
    /// 180°) neither overflows nor loses the direction.
    pub fn to_unit_quat(self) -> UnitQuat<T> {
        // (1, g) has a component ≥ 1, so it never has zero norm; try_new cannot fail on finite g.
        UnitQuat::try_new(Quat::from_parts(T::ONE, self.0)).unwrap_or(UnitQuat::IDENTITY)
    }
}

impl<T: Real> From<Gibbs<T>> for UnitQuat<T> {
    #[inline]
    fn from(g: Gibbs<T>) -> Self {
        g.to_unit_quat()
    }
}

impl<T: Real> TryFrom<UnitQuat<T>> for Gibbs<T> {
    type Error = Error;
    #[inline]
    fn try_from(q: UnitQuat<T>) -> Result<Self, Error> {
        Self::try_from_unit_quat(q)
    }
}
