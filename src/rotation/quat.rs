//! General (not necessarily unit) Hamilton quaternions.

use core::ops::{Add, Mul, Neg, Sub};

use crate::{Error, Real, Ring, UnitQuat, Vec3};

/// A Hamilton quaternion `w + x·i + y·j + z·k` with `i·j = k`, stored scalar-first.
///
/// No invariant: use [`UnitQuat`] for attitudes. Fields are public and named so that nobody has
/// to guess where the scalar part is.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quat<T> {
    /// Scalar part.
    pub w: T,
    /// `i` component.
    pub x: T,
    /// `j` component.
    pub y: T,
    /// `k` component.
    pub z: T,
}

impl<T: Ring> Quat<T> {
    /// The multiplicative identity `1`.
    pub const IDENTITY: Self = Self::new(T::ONE, T::ZERO, T::ZERO, T::ZERO);
    /// The zero quaternion.
    pub const ZERO: Self = Self::new(T::ZERO, T::ZERO, T::ZERO, T::ZERO);

    /// Builds `w + x·i + y·j + z·k`.
    #[inline]
    pub const fn new(w: T, x: T, y: T, z: T) -> Self {
        Self { w, x, y, z }
    }

    /// Builds from a scalar part and a vector part.
    #[inline]
    pub const fn from_parts(w: T, v: Vec3<T>) -> Self {
        Self::new(w, v.x, v.y, v.z)
    }

    /// Builds from `[w, x, y, z]`.
    #[inline]
    pub const fn from_array(a: [T; 4]) -> Self {
        Self::new(a[0], a[1], a[2], a[3])
    }

    /// Returns `[w, x, y, z]`.
    #[inline]
    pub const fn to_array(self) -> [T; 4] {
        [self.w, self.x, self.y, self.z]
    }

    /// The vector part `(x, y, z)`.
    #[inline]
    pub const fn vector(self) -> Vec3<T> {
        Vec3::new(self.x, self.y, self.z)
    }

    /// Conjugate `w − x·i − y·j − z·k`.
    #[inline]
    pub fn conjugate(self) -> Self {
        Self::new(self.w, -self.x, -self.y, -self.z)
    }

    /// Four-dimensional dot product (one rounding in fixed point, see [`Ring::dot`]).
    #[inline]
    pub fn dot(self, o: Self) -> T {
        T::dot([self.w, self.x, self.y, self.z], [o.w, o.x, o.y, o.z])
    }

    /// Squared norm `w² + x² + y² + z²`.
    #[inline]
    pub fn norm_squared(self) -> T {
        self.dot(self)
    }

    /// `self · s` for a real `s`.
    #[inline]
    pub fn scale(self, s: T) -> Self {
        Self::new(self.w * s, self.x * s, self.y * s, self.z * s)
    }

    /// `true` when every component is finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.w.is_finite() && self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
}

impl<T: Real> Quat<T> {
    /// Norm, computed with `hypot` (no overflow or underflow for extreme components).
    #[inline]
    pub fn norm(self) -> T {
        self.w.hypot(self.x).hypot(self.y.hypot(self.z))
    }

    /// The multiplicative inverse `conj(q)/|q|²`, computed on `q` scaled to a largest component
    /// of one (no overflow or underflow of `|q|²`).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite component, [`Error::ZeroNorm`] for a zero quaternion
    /// or one so short that its inverse overflows the type (`|q|` below about `1/MAX`).
    pub fn try_inverse(self) -> Result<Self, Error> {
        if !self.is_finite() {
            return Err(Error::NonFinite);
        }
        let m = self
            .w
            .abs()
            .max(self.x.abs())
            .max(self.y.abs())
            .max(self.z.abs());
        if m == T::ZERO {
            return Err(Error::ZeroNorm);
        }
        // q⁻¹ = conj(q/m) / (m·|q/m|²), |q/m|² ∈ [1, 4]; division, not a reciprocal of m.
        let s = Self::new(self.w / m, self.x / m, self.y / m, self.z / m);
        let d = s.norm_squared();
        let c = s.conjugate();
        let inv = Self::new(c.w / d / m, c.x / d / m, c.y / d / m, c.z / d / m);
        if inv.is_finite() {
            Ok(inv)
        } else {
            Err(Error::ZeroNorm)
        }
    }

    /// The unit quaternion along `self`; see [`UnitQuat::try_new`].
    ///
    /// # Errors
    /// As [`UnitQuat::try_new`].
    #[inline]
    pub fn try_normalize(self) -> Result<UnitQuat<T>, Error> {
        UnitQuat::try_new(self)
    }
}

/// The Hamilton product (`i·j = k`): `(w₁w₂ − v₁·v₂, w₁v₂ + w₂v₁ + v₁ × v₂)`.
///
/// Each component is one [`Ring::dot`] of four products: for the floats the same roundings as
/// the expression written out left to right, for fixed point one rounding per component.
impl<T: Ring> Mul for Quat<T> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let a = [self.w, self.x, self.y, self.z];
        Self::new(
            T::dot(a, [o.w, -o.x, -o.y, -o.z]),
            T::dot(a, [o.x, o.w, o.z, -o.y]),
            T::dot(a, [o.y, -o.z, o.w, o.x]),
            T::dot(a, [o.z, o.y, -o.x, o.w]),
        )
    }
}

impl<T: Ring> Mul<T> for Quat<T> {
    type Output = Self;
    #[inline]
    fn mul(self, s: T) -> Self {
        self.scale(s)
    }
}

impl<T: Ring> Add for Quat<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.w + o.w, self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Ring> Sub for Quat<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.w - o.w, self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Ring> Neg for Quat<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.w, -self.x, -self.y, -self.z)
    }
}
