//! Axis–angle forms: a unit axis and an angle, and the seed's polar axis angles `[φ, ϑ, Θ]`.

use crate::{Error, Real, RotationVector, Su2, UnitQuat, Vec3};

/// A rotation by `angle` (radians, right-handed) about a unit `axis`: `q = (cos Θ/2, sin Θ/2·n̂)`,
/// seed (6.6.4) and the Rodrigues matrix (6.6.13–15).
///
/// # Invariant
/// `|axis| = 1` to rounding; built by [`AxisAngle::try_new`] (normalises) or
/// [`AxisAngle::new_unchecked`].
///
/// Conversions from a quaternion: [`AxisAngle::from`] is the SO(3) view (angle in `[0, π]`);
/// [`AxisAngle::from_unit_quat`] keeps the spinor sign (angle in `[0, 2π]`), so that converting back
/// gives the same SU(2) element.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisAngle<T> {
    axis: Vec3<T>,
    angle: T,
}

impl<T: Real> AxisAngle<T> {
    /// Normalises `axis` and pairs it with `angle` (any finite value; `> 2π` is allowed and
    /// keeps its spinor meaning).
    ///
    /// # Errors
    /// [`Error::NonFinite`], or [`Error::ZeroNorm`] for a zero axis.
    pub fn try_new(axis: Vec3<T>, angle: T) -> Result<Self, Error> {
        if !angle.is_finite() {
            return Err(Error::NonFinite);
        }
        Ok(Self {
            axis: axis.try_normalize()?,
            angle,
        })
    }

    /// Pairs an axis the caller promises is unit with `angle`.
    #[inline]
    pub const fn new_unchecked(axis: Vec3<T>, angle: T) -> Self {
        Self { axis, angle }
    }

    /// The unit axis.
    #[inline]
    pub const fn axis(&self) -> Vec3<T> {
        self.axis
    }

    /// The angle, radians.
    #[inline]
    pub const fn angle(&self) -> T {
        self.angle
    }

    /// `(cos(Θ/2), sin(Θ/2)·n̂)`, sign kept (an angle of 2π gives `−1`).
    #[inline]
    pub fn to_unit_quat(self) -> UnitQuat<T> {
        UnitQuat::from_axis_angle_unchecked(self.axis, self.angle)
    }

    /// The sign-keeping inverse of [`AxisAngle::to_unit_quat`]: angle `2·atan2(|v|, w)` in
    /// `[0, 2π]`, axis `v/|v|`. For the identity (and `−1`), where the axis is undefined, the axis
    /// is `+x` by convention.
    pub fn from_unit_quat(q: UnitQuat<T>) -> Self {
        let v = q.as_quat().vector();
        let angle = T::TWO * v.norm().atan2(q.w());
        Self {
            axis: v.try_normalize().unwrap_or(Vec3::X),
            angle,
        }
    }

    /// The rotation vector `angle·axis` (the whirl vector of (6.6.4)), spinor meaning kept (an
    /// angle beyond π stays beyond π).
    #[inline]
    pub fn to_rotation_vector(self) -> RotationVector<T> {
        // A unit axis times a finite angle: finite, with the angle's magnitude as its norm.
        RotationVector(self.axis.scale(self.angle))
    }
}

impl<T: Real> From<UnitQuat<T>> for AxisAngle<T> {
    /// SO(3) view: `q` is first made `w ≥ 0`; the angle `2·atan2(|v|, w)` is in `[0, π]`. The
    /// identity gets axis `+x`. A half-turn keeps the axis direction of `q` after the sign choice
    /// of [`UnitQuat::canonical`].
    fn from(q: UnitQuat<T>) -> Self {
        Self::from_unit_quat(q.canonical())
    }
}

impl<T: Real> From<AxisAngle<T>> for UnitQuat<T> {
    #[inline]
    fn from(a: AxisAngle<T>) -> Self {
        a.to_unit_quat()
    }
}

/// The seed's axis angles `[φ, ϑ, Θ]` (§6.6.b, (6.6.5)): the whirl axis in polar coordinates,
/// `Θ̂ = (cos φ sin ϑ, sin φ sin ϑ, cos ϑ)`, and the whirl angle `Θ = Ω t`.
///
/// Conversions keep the spinor sign (Θ in `[0, 2π]` from a quaternion), so `Θ = 360°` is `−1` in
/// SU(2) and `489° = 129° + 360°` is the negative of `129°`, as in the 4π sequence (6.6.6c–d).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolarAxisAngle<T> {
    /// Azimuth φ of the axis, radians.
    pub phi: T,
    /// Polar angle ϑ of the axis from +z, radians.
    pub theta: T,
    /// Whirl angle Θ, radians (any value; spinor meaning kept).
    pub angle: T,
}

impl<T: Real> PolarAxisAngle<T> {
    /// `[φ, ϑ, Θ]`.
    #[inline]
    pub const fn new(phi: T, theta: T, angle: T) -> Self {
        Self { phi, theta, angle }
    }

    /// The unit whirl axis `(cos φ sin ϑ, sin φ sin ϑ, cos ϑ)`.
    #[inline]
    pub fn axis(&self) -> Vec3<T> {
        let (sp, cp) = self.phi.sin_cos();
        let (st, ct) = self.theta.sin_cos();
        Vec3::new(cp * st, sp * st, ct)
    }

    /// `R[φ, ϑ, Θ] = cos(Θ/2)·1 − i·sin(Θ/2)·Θ̂·σ` (6.6.4) as a unit quaternion, sign kept.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite angle.
    pub fn try_to_unit_quat(&self) -> Result<UnitQuat<T>, Error> {
        if !(self.phi.is_finite() && self.theta.is_finite() && self.angle.is_finite()) {
            return Err(Error::NonFinite);
        }
        Ok(UnitQuat::from_axis_angle_unchecked(self.axis(), self.angle))
    }

    /// The spinor `R[φ, ϑ, Θ]` of (6.6.4).
    ///
    /// # Errors
    /// As [`PolarAxisAngle::try_to_unit_quat`].
    pub fn try_to_su2(&self) -> Result<Su2<T>, Error> {
        self.try_to_unit_quat().map(Su2::from)
    }

    /// Axis angles of a spinor, sign kept: `Θ = 2·atan2(|v|, w) ∈ [0, 2π]`,
    /// `ϑ = atan2(hypot(x, y), z) ∈ [0, π]`, `φ = atan2(y, x) ∈ (−π, π]` — the inverse of (6.6.5a)
    /// with atan2 in place of the seed's `cos⁻¹`/`tan⁻¹` (6.6.5c). For the identity and `−1`,
    /// where the axis is undefined, `φ = ϑ = 0`.
    pub fn from_unit_quat(q: UnitQuat<T>) -> Self {
        let v = q.as_quat().vector();
        Self {
            phi: v.y.atan2(v.x),
            theta: v.x.hypot(v.y).atan2(v.z),
            angle: T::TWO * v.norm().atan2(q.w()),
        }
    }
}

impl<T: Real> From<UnitQuat<T>> for PolarAxisAngle<T> {
    /// Sign kept: see [`PolarAxisAngle::from_unit_quat`].
    #[inline]
    fn from(q: UnitQuat<T>) -> Self {
        Self::from_unit_quat(q)
    }
}

impl<T: Real> From<Su2<T>> for PolarAxisAngle<T> {
    #[inline]
    fn from(u: Su2<T>) -> Self {
        Self::from_unit_quat(UnitQuat::from(u))
    }
}
