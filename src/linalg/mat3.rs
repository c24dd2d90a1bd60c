//! 3×3 matrices.

use core::ops::{Add, Mul, Neg, Sub};

use crate::{Error, Real, Ring, Vec3};

/// A 3×3 matrix stored row-major: `m[row][col]`.
///
/// Used for rotation matrices (columns = body axes in lab coordinates, see the crate docs),
/// inertia tensors and kinematic Jacobians.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Mat3<T> {
    /// Entries, `m[row][col]`.
    pub m: [[T; 3]; 3],
}

impl<T: Ring> Mat3<T> {
    /// The zero matrix.
    pub const ZERO: Self = Self {
        m: [[T::ZERO; 3]; 3],
    };
    /// The identity matrix.
    pub const IDENTITY: Self = Self {
        m: [
            [T::ONE, T::ZERO, T::ZERO],
            [T::ZERO, T::ONE, T::ZERO],
            [T::ZERO, T::ZERO, T::ONE],
        ],
    };

    /// Builds from rows.
    #[inline]
    pub const fn from_rows(r0: [T; 3], r1: [T; 3], r2: [T; 3]) -> Self {
        Self { m: [r0, r1, r2] }
    }

    /// Builds from three column vectors.
    #[inline]
    pub const fn from_cols(c0: Vec3<T>, c1: Vec3<T>, c2: Vec3<T>) -> Self {
        Self::from_rows([c0.x, c1.x, c2.x], [c0.y, c1.y, c2.y], [c0.z, c1.z, c2.z])
    }

    /// The diagonal matrix `diag(d.x, d.y, d.z)`.
    #[inline]
    pub fn from_diagonal(d: Vec3<T>) -> Self {
        let z = T::ZERO;
        Self::from_rows([d.x, z, z], [z, d.y, z], [z, z, d.z])
    }

    /// The cross-product matrix `[v]×`, so that `[v]× u = v × u`.
    #[inline]
    pub fn skew(v: Vec3<T>) -> Self {
        let z = T::ZERO;
        Self::from_rows([z, -v.z, v.y], [v.z, z, -v.x], [-v.y, v.x, z])
    }

    /// Column `j` (0, 1, anything else → 2).
    #[inline]
    pub fn col(&self, j: usize) -> Vec3<T> {
        let j = if j > 2 { 2 } else { j };
        Vec3::new(self.m[0][j], self.m[1][j], self.m[2][j])
    }

    /// Row `i` (0, 1, anything else → 2).
    #[inline]
    pub fn row(&self, i: usize) -> Vec3<T> {
        let i = if i > 2 { 2 } else { i };
        Vec3::from_array(self.m[i])
    }

    /// The diagonal `(m00, m11, m22)`.
    #[inline]
    pub fn diagonal(&self) -> Vec3<T> {
        Vec3::new(self.m[0][0], self.m[1][1], self.m[2][2])
    }

    /// Transpose.
    #[inline]
    pub fn transpose(&self) -> Self {
        Self::from_cols(self.row(0), self.row(1), self.row(2))
    }

    /// Trace.
    #[inline]
    pub fn trace(&self) -> T {
        self.m[0][0] + self.m[1][1] + self.m[2][2]
    }

    /// Determinant (triple product of the rows).
    #[inline]
    pub fn determinant(&self) -> T {
        self.row(0).dot(self.row(1).cross(self.row(2)))
    }

    /// `self * s`.
    #[inline]
    pub fn scale(&self, s: T) -> Self {
        Self::from_cols(self.col(0) * s, self.col(1) * s, self.col(2) * s)
    }

    /// Largest absolute entry.
    #[inline]
    pub fn max_abs(&self) -> T {
        self.row(0)
            .max_abs()
            .max(self.row(1).max_abs())
            .max(self.row(2).max_abs())
    }

    /// `true` when every entry is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.row(0).is_finite() && self.row(1).is_finite() && self.row(2).is_finite()
    }
}

impl<T: Real> Mat3<T> {
    /// The inverse, by the adjugate over the determinant of the matrix scaled to a largest entry
    /// of one (so that the cofactors neither overflow nor underflow for entries anywhere in the
    /// type's range).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite entry; [`Error::Singular`] when, for the scaled
    /// matrix, `|det| ≤ 8·ε·‖row0‖‖row1‖‖row2‖` (Hadamard's bound scaled by the rounding of the
    /// triple product: below it the determinant's sign is not even known), or when an entry of the
    /// inverse overflows the type (the matrix is singular at the type's range).
    pub fn try_inverse(&self) -> Result<Self, Error> {
        if !self.is_finite() {
            return Err(Error::NonFinite);
        }
        let s = self.max_abs();
        if s == T::ZERO {
            return Err(Error::Singular);
        }
        // Division, not a reciprocal: 1/s overflows for a subnormal s. Entries now in [−1, 1].
        let (r0, r1, r2) = (self.row(0) / s, self.row(1) / s, self.row(2) / s);
        let c0 = r1.cross(r2);
        let c1 = r2.cross(r0);
        let c2 = r0.cross(r1);
        let det = r0.dot(c0);
        let bound = T::from_f64(8.0) * T::EPSILON * r0.norm() * r1.norm() * r2.norm();
        if det.abs() <= bound {
            return Err(Error::Singular);
        }
        // (M/s)⁻¹ = s·M⁻¹: divide the adjugate by det, then by s.
        let inv = Self::from_cols(c0 / det / s, c1 / det / s, c2 / det / s);
        if inv.is_finite() {
            Ok(inv)
        } else {
            Err(Error::Singular)
        }
    }
}

impl<T: Ring> Mul<Vec3<T>> for Mat3<T> {
    type Output = Vec3<T>;
    #[inline]
    fn mul(self, v: Vec3<T>) -> Vec3<T> {
        Vec3::new(self.row(0).dot(v), self.row(1).dot(v), self.row(2).dot(v))
    }
}

impl<T: Ring> Mul for Mat3<T> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self::from_cols(self * o.col(0), self * o.col(1), self * o.col(2))
    }
}

impl<T: Ring> Add for Mat3<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::from_cols(
            self.col(0) + o.col(0),
            self.col(1) + o.col(1),
            self.col(2) + o.col(2),
        )
    }
}

impl<T: Ring> Sub for Mat3<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::from_cols(
            self.col(0) - o.col(0),
            self.col(1) - o.col(1),
            self.col(2) - o.col(2),
        )
    }
}

impl<T: Ring> Neg for Mat3<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self.scale(-T::ONE)
    }
}
