//! SU(2): rotations as 2×2 complex unitary matrices (spinors).

use core::ops::{Mul, Neg};

use crate::{Complex, Error, Quat, Real, UnitQuat, Vec3};

/// A rotation as the 2×2 complex unitary matrix of seed (6.6.4):
///
/// ```text
/// U = w·1 − i(x·σx + y·σy + z·σz) = ⎡ a  −ā₂ ⎤ ,  a = w − i·z,  b = y − i·x
///                                   ⎣ b   ā  ⎦    (ā₂ = conj(b))
/// ```
///
/// For an axis `Θ̂` and angle `Θ`: `U = cos(Θ/2)·1 − i·sin(Θ/2)·Θ̂·σ`, the seed's `R[Θ]`. Stored as
/// the Cayley–Klein pair `(a, b)` with `|a|² + |b|² = 1`.
///
/// The sign is physical: a rotation by 2π is `U = −1` and only 4π returns to `+1` (seed §6.6.b.1,
/// (6.6.6c–d)). Conversions to and from [`UnitQuat`] keep the sign; nothing here canonicalises it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Su2<T> {
    a: Complex<T>,
    b: Complex<T>,
}

impl<T: Real> Su2<T> {
    /// The identity `1`.
    pub const IDENTITY: Self = Self {
        a: Complex::new(T::ONE, T::ZERO),
        b: Complex::new(T::ZERO, T::ZERO),
    };

    /// Builds `[[a, −conj(b)], [b, conj(a)]]`, normalising `(a, b)` to `|a|² + |b|² = 1`.
    ///
    /// # Errors
    /// As [`UnitQuat::try_new`]: [`Error::NonFinite`] or [`Error::ZeroNorm`].
    pub fn try_new(a: Complex<T>, b: Complex<T>) -> Result<Self, Error> {
        UnitQuat::try_new(Quat::new(a.re, -b.im, b.re, -a.im)).map(Self::from)
    }

    /// The Cayley–Klein parameter `a = U₀₀ = w − i·z`.
    #[inline]
    pub const fn a(&self) -> Complex<T> {
        self.a
    }

    /// The Cayley–Klein parameter `b = U₁₀ = y − i·x`.
    #[inline]
    pub const fn b(&self) -> Complex<T> {
        self.b
    }

    /// The full matrix `[[U₀₀, U₀₁], [U₁₀, U₁₁]]`.
    #[inline]
    pub fn matrix(&self) -> [[Complex<T>; 2]; 2] {
        [[self.a, -self.b.conj()], [self.b, self.a.conj()]]
    }

    /// The inverse `U† = U⁻¹`.
    #[inline]
    pub fn inverse(self) -> Self {
        // U† = [[ā, b̄], [−b, a]] → a' = ā, b' = −b.
        Self {
            a: self.a.conj(),
            b: -self.b,
        }
    }

    /// Rotates a vector by the similarity transform `U (v·σ) U†`, seed (6.6.8): the result's
    /// Pauli components are the rotated vector. Equal to [`UnitQuat::rotate`] for the same
    /// rotation; both signs of `U` give the same result.
    pub fn rotate(self, v: Vec3<T>) -> Vec3<T> {
        // v·σ = [[z, x − i y], [x + i y, −z]]
        let p = [
            [Complex::new(v.z, T::ZERO), Complex::new(v.x, -v.y)],
            [Complex::new(v.x, v.y), Complex::new(-v.z, T::ZERO)],
        ];
        let u = self.matrix();
        let ud = self.inverse().matrix();
        let up = mul2(&u, &p);
        let r = mul2(&up, &ud);
        // r = [[z', x' − i y'], [x' + i y', −z']]
        Vec3::new(r[1][0].re, r[1][0].im, r[0][0].re)
    }
}

fn mul2<T: Real>(l: &[[Complex<T>; 2]; 2], r: &[[Complex<T>; 2]; 2]) -> [[Complex<T>; 2]; 2] {
    [
        [
            l[0][0] * r[0][0] + l[0][1] * r[1][0],
            l[0][0] * r[0][1] + l[0][1] * r[1][1],
        ],
        [
            l[1][0] * r[0][0] + l[1][1] * r[1][0],
            l[1][0] * r[0][1] + l[1][1] * r[1][1],
        ],
    ]
}

/// The U(2) product (6.6.10): `U₁U₂` applies `U₂` first. Corresponds to the Hamilton product
/// of the quaternions.
impl<T: Real> Mul for Su2<T> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        // [[a1, −b̄1], [b1, ā1]] · [[a2, −b̄2], [b2, ā2]]: first column is (a, b) of the product.
        Self {
            a: self.a * o.a - self.b.conj() * o.b,
            b: self.b * o.a + self.a.conj() * o.b,
        }
    }
}

/// `−U`: the same rotation of vectors, the other spinor.
impl<T: Real> Neg for Su2<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            a: -self.a,
            b: -self.b,
        }
    }
}

/// `U = w·1 − i(x σx + y σy + z σz)`: `a = w − i z`, `b = y − i x`. Sign kept.
impl<T: Real> From<UnitQuat<T>> for Su2<T> {
    #[inline]
    fn from(q: UnitQuat<T>) -> Self {
        Self {
            a: Complex::new(q.w(), -q.z()),
            b: Complex::new(q.y(), -q.x()),
        }
    }
}

/// The inverse map of `From<UnitQuat> for Su2`. Sign kept.
impl<T: Real> From<Su2<T>> for UnitQuat<T> {
    #[inline]
    fn from(u: Su2<T>) -> Self {
        UnitQuat::new_unchecked(Quat::new(u.a.re, -u.b.im, u.b.re, -u.a.im))
    }
}
