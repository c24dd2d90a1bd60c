//! Rotation vectors (the seed's whirl vector `Θ = Ω τ`).

use crate::{Error, Real, UnitQuat, Vec3};

/// A rotation vector `φ = Θ·n̂`: the rotation by `|φ|` about `φ̂`, the seed's whirl vector
/// `Θ = Ω τ` (6.6.4).
///
/// Built on [`UnitQuat::try_exp`] / [`UnitQuat::log`], which use series below a small-angle threshold
/// (no division by a tiny angle) and `atan2` near π.
///
/// Any finite vector is accepted; `|φ| > π` keeps its spinor meaning through
/// [`RotationVector::to_unit_quat`] (2π gives `−1`). From a quaternion the SO(3) view is returned
/// (`|φ| ≤ π`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationVector<T>(pub(crate) Vec3<T>);

impl<T: Real> RotationVector<T> {
    /// The zero rotation.
    pub const ZERO: Self = Self(Vec3::ZERO);

    /// Wraps a rotation vector (radians).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite component; [`Error::InvalidArgument`] if `|v|`
    /// overflows (components near the type's maximum: no angle is representable).
    #[inline]
    pub fn try_new(v: Vec3<T>) -> Result<Self, Error> {
        let v = v.try_finite()?;
        if !v.norm_squared().is_finite() && !v.norm().is_finite() {
            return Err(Error::InvalidArgument);
        }
        Ok(Self(v))
    }

    /// The vector.
    #[inline]
    pub const fn vector(&self) -> Vec3<T> {
        self.0
    }

    /// The rotation angle `|φ|`.
    #[inline]
    pub fn angle(&self) -> T {
        self.0.norm()
    }

    /// `exp(φ)`, sign kept (see [`UnitQuat::try_exp`]).
    #[inline]
    pub fn to_unit_quat(self) -> UnitQuat<T> {
        UnitQuat::exp_unchecked(self.0)
    }

    /// `log(q)`, angle in `[0, π]` (SO(3) view; see [`UnitQuat::log`]).
    #[inline]
    pub fn from_unit_quat(q: UnitQuat<T>) -> Self {
        Self(q.log())
    }
}

impl<T: Real> From<UnitQuat<T>> for RotationVector<T> {
    #[inline]
    fn from(q: UnitQuat<T>) -> Self {
        Self::from_unit_quat(q)
    }
}

impl<T: Real> From<RotationVector<T>> for UnitQuat<T> {
    #[inline]
    fn from(r: RotationVector<T>) -> Self {
        r.to_unit_quat()
    }
}
