//! Three-vectors.

use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use crate::{Error, Real, Ring};

/// A 3-vector `(x, y, z)`. Plain data: which frame it lives in is said by the name of the variable
/// or field holding it (`omega_body`, `j_lab`, ...).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<T> {
    /// x component.
    pub x: T,
    /// y component.
    pub y: T,
    /// z component.
    pub z: T,
}

impl<T: Ring> Vec3<T> {
    /// The zero vector.
    pub const ZERO: Self = Self::new(T::ZERO, T::ZERO, T::ZERO);
    /// Unit vector along x.
    pub const X: Self = Self::new(T::ONE, T::ZERO, T::ZERO);
    /// Unit vector along y.
    pub const Y: Self = Self::new(T::ZERO, T::ONE, T::ZERO);
    /// Unit vector along z.
    pub const Z: Self = Self::new(T::ZERO, T::ZERO, T::ONE);

    /// Builds `(x, y, z)`.
    #[inline]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }

    /// Builds from `[x, y, z]`.
    #[inline]
    pub const fn from_array(a: [T; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// Returns `[x, y, z]`.
    #[inline]
    pub const fn to_array(self) -> [T; 3] {
        [self.x, self.y, self.z]
    }

    /// Dot product (one rounding in fixed point, see [`Ring::dot`]).
    #[inline]
    pub fn dot(self, o: Self) -> T {
        T::dot([self.x, self.y, self.z], [o.x, o.y, o.z])
    }

    /// Cross product `self × o` (right-handed; one rounding per component in fixed point).
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            T::dot([self.y, -self.z], [o.z, o.y]),
            T::dot([self.z, -self.x], [o.x, o.z]),
            T::dot([self.x, -self.y], [o.y, o.x]),
        )
    }

    /// Squared Euclidean norm.
    #[inline]
    pub fn norm_squared(self) -> T {
        self.dot(self)
    }

    /// `self * s`.
    #[inline]
    pub fn scale(self, s: T) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }

    /// Component-wise product.
    #[inline]
    pub fn component_mul(self, o: Self) -> Self {
        Self::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }

    /// Largest absolute component.
    #[inline]
    pub fn max_abs(self) -> T {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }

    /// `true` when every component is finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }

    /// `true` when `self + o` needs no saturation ([`Ring::dot_fits`]; always for the floats).
    #[inline]
    pub(crate) fn add_fits(self, o: Self) -> bool {
        T::dot_fits([self.x, o.x], [T::ONE, T::ONE])
            && T::dot_fits([self.y, o.y], [T::ONE, T::ONE])
            && T::dot_fits([self.z, o.z], [T::ONE, T::ONE])
    }

    /// `true` when `self × o` needs no saturation ([`Ring::dot_fits`]; always for the floats).
    #[inline]
    pub(crate) fn cross_fits(self, o: Self) -> bool {
        T::dot_fits([self.y, -self.z], [o.z, o.y])
            && T::dot_fits([self.z, -self.x], [o.x, o.z])
            && T::dot_fits([self.x, -self.y], [o.y, o.x])
    }

    /// Returns `self` if every component is finite, else [`Error::NonFinite`].
    #[inline]
    pub fn try_finite(self) -> Result<Self, Error> {
        if self.is_finite() {
            Ok(self)
        } else {
            Err(Error::NonFinite)
        }
    }
}

impl<T: Real> Vec3<T> {
    /// Euclidean norm, computed with `hypot` so that it neither overflows nor underflows for
    /// components near the range limits.
    #[inline]
    pub fn norm(self) -> T {
        self.x.hypot(self.y).hypot(self.z)
    }

    /// The unit vector along `self`.
    ///
    /// The vector is first divided by its largest absolute component, so that neither the norm
    /// nor its reciprocal overflows or underflows: any non-zero finite vector is normalised,
    /// however short (subnormal components included) or long.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite component; [`Error::ZeroNorm`] when `|self|` is zero
    /// (no direction).
    pub fn try_normalize(self) -> Result<Self, Error> {
        let v = self.try_finite()?;
        let m = v.max_abs();
        if m == T::ZERO {
            return Err(Error::ZeroNorm);
        }
        // Division, not a reciprocal: 1/m overflows for a subnormal m. |v/m| ∈ [1, √3].
        let s = v / m;
        Ok(s.scale(T::ONE / s.norm_squared().sqrt()))
    }
}

impl<T: Ring> Add for Vec3<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Ring> Sub for Vec3<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Ring> AddAssign for Vec3<T> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<T: Ring> SubAssign for Vec3<T> {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

impl<T: Ring> Neg for Vec3<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl<T: Ring> Mul<T> for Vec3<T> {
    type Output = Self;
    #[inline]
    fn mul(self, s: T) -> Self {
        self.scale(s)
    }
}

impl<T: Real> Div<T> for Vec3<T> {
    type Output = Self;
    #[inline]
    fn div(self, s: T) -> Self {
        Self::new(self.x / s, self.y / s, self.z / s)
    }
}
