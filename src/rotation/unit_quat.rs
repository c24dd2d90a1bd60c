//! Unit quaternions: the attitude type.

use core::ops::{Mul, Neg};

use crate::{Error, Mat3, Quat, Real, Ring, Vec3};

/// A unit Hamilton quaternion: an attitude, or a rotation.
///
/// # Convention
/// `q` maps body-frame vectors to the lab frame, `v_lab = q ⊗ (0, v_body) ⊗ q*`
/// ([`UnitQuat::rotate`]); its matrix [`UnitQuat::to_rotation_matrix`] has the body axes as
/// columns, in lab coordinates. This is the seed's active rotation `R(αβγ)` taking lab axes to
/// body axes (6.6.1b). For an axis `n̂` and angle `Θ`, `q = (cos Θ/2, sin Θ/2 · n̂)`, the
/// quaternion form of seed (6.6.4). Composition `q₁ ⊗ q₂` applies `q₂` first:
/// `R(q₁ q₂) = R(q₁) R(q₂)`.
///
/// `q` and `−q` rotate vectors identically but are different spinors; this type never changes
/// the sign behind the caller's back (see [`crate::Su2`]).
///
/// # Invariant
/// `|q| = 1` up to rounding. Built only by [`UnitQuat::try_new`] (normalises),
/// [`UnitQuat::try_from_near_unit`] (checks, then normalises) or [`UnitQuat::new_unchecked`]
/// (caller's promise). Products drift from unit norm by about one ulp per operation; call
/// [`UnitQuat::renormalize`] or [`UnitQuat::renormalize_fast`] periodically in long loops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitQuat<T>(Quat<T>);

impl<T: Ring> Default for UnitQuat<T> {
    /// The identity rotation.
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl<T: Ring> UnitQuat<T> {
    /// The identity rotation `(1, 0, 0, 0)`.
    pub const IDENTITY: Self = Self(Quat::IDENTITY);

    /// Wraps `q` without checking. The caller promises `|q| = 1` up to rounding; breaking the
    /// promise gives wrong rotations (scaled by `|q|²`), never undefined behaviour.
    #[inline]
    pub const fn new_unchecked(q: Quat<T>) -> Self {
        Self(q)
    }
    /// The underlying quaternion.
    #[inline]
    pub const fn as_quat(&self) -> &Quat<T> {
        &self.0
    }

    /// The underlying quaternion, by value.
    #[inline]
    pub const fn into_quat(self) -> Quat<T> {
        self.0
    }

    /// Scalar part.
    #[inline]
    pub const fn w(&self) -> T {
        self.0.w
    }
    /// `i` component.
    #[inline]
    pub const fn x(&self) -> T {
        self.0.x
    }
    /// `j` component.
    #[inline]
    pub const fn y(&self) -> T {
        self.0.y
    }
    /// `k` component.
    #[inline]
    pub const fn z(&self) -> T {
        self.0.z
    }

    /// `[w, x, y, z]`.
    #[inline]
    pub const fn to_array(&self) -> [T; 4] {
        self.0.to_array()
    }

    /// The inverse rotation, which for a unit quaternion is the conjugate.
    #[inline]
    pub fn inverse(self) -> Self {
        Self(self.0.conjugate())
    }

    /// Four-dimensional dot product; `|dot| = cos(θ/2)` for the angle θ between two attitudes.
    #[inline]
    pub fn dot(self, o: Self) -> T {
        self.0.dot(o.0)
    }

    /// Rotates a body-frame vector into the lab frame: `q ⊗ (0, v) ⊗ q*`.
    ///
    /// Evaluated as `v + 2(w·s + u × s)` with `u = (x, y, z)` and `s = u × v` (15
    /// multiplications), algebraically equal to the sandwich product for unit `q`; in fixed point
    /// `s` and each component of `w·s + u × s` are rounded once. Fixed point: for `|v| ≤ 1`
    /// nothing saturates beyond one unit of resolution (`|w·s + u × s| ≤ |v|`).
    #[inline]
    pub fn rotate(self, v: Vec3<T>) -> Vec3<T> {
        let Quat { w, x, y, z } = self.0;
        let s = self.0.vector().cross(v);
        let inner = Vec3::new(
            T::dot([w, y, -z], [s.x, s.z, s.y]),
            T::dot([w, z, -x], [s.y, s.x, s.z]),
            T::dot([w, x, -y], [s.z, s.y, s.x]),
        );
        v + Vec3::new(inner.x.twice(), inner.y.twice(), inner.z.twice())
    }

    /// Rotates a lab-frame vector into the body frame: `q* ⊗ (0, v) ⊗ q`.
    #[inline]
    pub fn inverse_rotate(self, v: Vec3<T>) -> Vec3<T> {
        self.inverse().rotate(v)
    }

    /// The rotation matrix `R(q)`: columns are the body axes in lab coordinates, so that
    /// `R(q)·v = q ⊗ v ⊗ q*`. Equal to the Rodrigues form (6.6.15) for the same axis and angle.
    ///
    /// Each entry is `1 − 2(a² + b²)` or `2(ab ± cd)`, formed as one [`Ring::dot`] with the
    /// doubled components `2b`, `2d` (shared by the entries): `1 − (a·2a + b·2b)`,
    /// `a·2b ± c·2d`. For the floats doubling is exact and commutes with rounding, so the
    /// entries are bit for bit those of `2·(ab ± cd)` written out, in 21 operations instead of
    /// 30; fixed point rounds each entry once (the doubled product summed exactly).
    #[inline]
    pub fn to_rotation_matrix(self) -> Mat3<T> {
        let Quat { w, x, y, z } = self.0;
        let (x2, y2, z2) = (x.twice(), y.twice(), z.twice());
        let d = |a: T, b2: T, c: T, e2: T| T::dot([a, c], [b2, e2]);
        let diag = |a: T, a2: T, b: T, b2: T| T::ONE - T::dot([a, b], [a2, b2]);
        // `ab − wc` as `a·2b + w·(−2c)`: each negated factor has one use, so that the floats'
        // `w·2c` is shared with the `ab + wc` entry. Negation is exact: the same bits.
        Mat3::from_rows(
            [diag(y, y2, z, z2), d(x, y2, w, -z2), d(x, z2, w, y2)],
            [d(x, y2, w, z2), diag(x, x2, z, z2), d(y, z2, w, -x2)],
            [d(x, z2, w, -y2), d(y, z2, w, x2), diag(x, x2, y, y2)],
        )
    }

    /// Restores unit norm exactly: `q / |q|`.
    ///
    /// Call after many compositions or an integration step. Infallible: the invariant keeps `|q|`
    /// near one, so `√(w² + x² + y² + z²)` cannot overflow or underflow and the division is safe
    /// (no `hypot` needed, which keeps this cheap on an MCU). The scale is
    /// [`Ring::inv_sqrt_near_one`]: `1/√|q|²` for the floats, Newton's iteration to convergence in
    /// fixed point (no division; valid for `|q|² ∈ (½, 2)`).
    #[inline]
    pub fn renormalize(self) -> Self {
        Self(self.0.scale(T::inv_sqrt_near_one(self.0.norm_squared())))
    }

    /// Restores unit norm to first order without a square root or a division:
    /// `q + q·(1 − |q|²)/2`.
    ///
    /// One Newton step for `1/|q|`: if `|q|² = 1 + δ`, the result has `|q|² = 1 − 3δ²/4 + O(δ³)`,
    /// so it suits the small drift of a per-step update (δ of a few ulp), not arbitrary input.
    /// Written as a correction added to `q` (rather than `q·(3 − |q|²)/2`), so that the small
    /// factor `(1 − |q|²)/2` keeps its precision and no constant outside `[−2, 2)` is needed.
    #[inline]
    pub fn renormalize_fast(self) -> Self {
        let e = (T::ONE - self.0.norm_squared()) * T::HALF;
        Self(self.0 + self.0.scale(e))
    }
}

impl<T: Real> UnitQuat<T> {
    /// Norms at or below this are rejected as zero by [`UnitQuat::try_new`]: machine epsilon.
    ///
    /// A quaternion that short cannot have come from an attitude computation (those stay within
    /// a few ulp of unit norm); it is a cancelled difference or uninitialised data, and its
    /// direction is noise.
    pub const MIN_NORM: T = T::EPSILON;

    /// Normalises `q` into a unit quaternion.
    ///
    /// The norm is computed on `q` scaled by its largest component, so components near the
    /// overflow or underflow limits normalise correctly.
    ///
    /// # Errors
    /// [`Error::NonFinite`] if a component is NaN or infinite; [`Error::ZeroNorm`] if
    /// `|q| ≤` [`UnitQuat::MIN_NORM`].
    ///
    /// ```
    /// use gyrostat::{Error, Quat, UnitQuat};
    /// let q = UnitQuat::try_new(Quat::new(2.0f32, 0.0, 0.0, 0.0)).unwrap();
    /// assert_eq!(q, UnitQuat::IDENTITY);
    /// assert_eq!(UnitQuat::try_new(Quat::<f64>::ZERO), Err(Error::ZeroNorm));
    /// assert_eq!(UnitQuat::try_new(Quat::new(f32::NAN, 0.0, 0.0, 1.0)), Err(Error::NonFinite));
    /// ```
    pub fn try_new(q: Quat<T>) -> Result<Self, Error> {
        if !q.is_finite() {
            return Err(Error::NonFinite);
        }
        let m = q.w.abs().max(q.x.abs()).max(q.y.abs()).max(q.z.abs());
        // |q| ≤ 2m: a largest component at or below MIN_NORM/2 is rejected here, which also keeps
        // the reciprocal 1/m below (2/ε) finite (for a subnormal m it would overflow).
        if m <= Self::MIN_NORM * T::HALF {
            return Err(Error::ZeroNorm);
        }
        let scaled = q.scale(T::ONE / m);
        let n_scaled = scaled.norm(); // in [1, 2]
        if n_scaled * m <= Self::MIN_NORM {
            return Err(Error::ZeroNorm);
        }
        Ok(Self(scaled.scale(T::ONE / n_scaled)))
    }

    /// Accepts `q` as an attitude only if `||q| − 1| ≤ tolerance`, then normalises it exactly.
    ///
    /// For data that claims to be an attitude (files, telemetry, user input), where a norm far
    /// from one means the data is wrong rather than slightly rounded.
    ///
    /// `tolerance` must be in `[0, 1)`: a tolerance of one or more would accept the zero
    /// quaternion, which has no direction.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite component or tolerance; [`Error::InvalidArgument`]
    /// for a tolerance outside `[0, 1)`; [`Error::NotUnit`] if the norm is outside
    /// `1 ± tolerance`.
    pub fn try_from_near_unit(q: Quat<T>, tolerance: T) -> Result<Self, Error> {
        if !q.is_finite() || !tolerance.is_finite() {
            return Err(Error::NonFinite);
        }
        if !(tolerance >= T::ZERO && tolerance < T::ONE) {
            return Err(Error::InvalidArgument);
        }
        // |q| ≥ 1 − tolerance > 0 once accepted, so 1/|q| is finite.
        let n = q.norm();
        if (n - T::ONE).abs() > tolerance {
            return Err(Error::NotUnit);
        }
        Ok(Self(q.scale(T::ONE / n)))
    }

    /// The rotation by `angle` (radians, right-handed) about `axis`:
    /// `q = (cos(angle/2), sin(angle/2)·axis/|axis|)`, seed (6.6.4).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite input; [`Error::ZeroNorm`] for a zero axis.
    pub fn try_from_axis_angle(axis: Vec3<T>, angle: T) -> Result<Self, Error> {
        if !angle.is_finite() {
            return Err(Error::NonFinite);
        }
        let n = axis.try_normalize()?;
        Ok(Self::from_axis_angle_unchecked(n, angle))
    }

    /// The rotation by `angle` about a unit `axis` the caller has already normalised, unchecked:
    /// [`UnitQuat::try_from_axis_angle`] without the normalisation and the finiteness check.
    #[inline]
    pub fn from_axis_angle_unchecked(axis: Vec3<T>, angle: T) -> Self {
        let (s, c) = (angle * T::HALF).sin_cos();
        Self(Quat::from_parts(c, axis.scale(s)))
    }
}

/// Composition: `(q₁ * q₂)` applies `q₂` first, then `q₁` (Hamilton product).
impl<T: Ring> Mul for UnitQuat<T> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self(self.0 * o.0)
    }
}

/// `q * v` rotates `v` (body → lab), as [`UnitQuat::rotate`].
impl<T: Ring> Mul<Vec3<T>> for UnitQuat<T> {
    type Output = Vec3<T>;
    #[inline]
    fn mul(self, v: Vec3<T>) -> Vec3<T> {
        self.rotate(v)
    }
}

/// `−q`: the same rotation of vectors, the opposite spinor (a 2π turn away in SU(2)).
impl<T: Ring> Neg for UnitQuat<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self(-self.0)
    }
}

impl<T: Ring> From<UnitQuat<T>> for Quat<T> {
    #[inline]
    fn from(q: UnitQuat<T>) -> Self {
        q.0
    }
}
