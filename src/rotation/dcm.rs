//! Direction-cosine matrices (rotation matrices) with an orthonormality invariant.

use core::ops::Mul;

use crate::{Error, Mat3, Quat, Real, UnitQuat, Vec3};

/// A rotation matrix (direction-cosine matrix): orthonormal, determinant `+1`.
///
/// # Convention
/// Columns are the body axes in lab coordinates, `R·v_body = v_lab`, the same `R(q)` as
/// [`UnitQuat::to_rotation_matrix`]; entries `R_ML = e_M · ē_L` are the direction cosines of seed
/// (6.6.14). Composition `R₁·R₂` applies `R₂` first.
///
/// # Invariant
/// `‖RᵀR − 1‖_max ≤` the tolerance given to [`Dcm::try_from_matrix`] and `det R > 0`; or the
/// matrix was orthonormalised by [`Dcm::try_from_matrix_orthonormalized`]; or the caller promised it
/// ([`Dcm::from_matrix_unchecked`]).
///
/// ```
/// use gyrostat::{Dcm, Error, Mat3};
/// let noisy = Mat3::from_rows([1.001, 0.002, 0.0], [-0.001, 0.999, 0.0], [0.0, 0.0, 1.0f64]);
/// assert_eq!(Dcm::try_from_matrix(noisy, 1e-6), Err(Error::NotRotation));
/// let r = Dcm::try_from_matrix_orthonormalized(noisy)?.into_matrix();
/// assert!((r.transpose() * r - Mat3::IDENTITY).max_abs() < 1e-15);
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dcm<T>(Mat3<T>);

/// Largest Newton steps of the polar iteration in [`Dcm::try_from_matrix_orthonormalized`]. With
/// Higham's norm scaling the iteration converges in under 10 steps for condition numbers up to
/// 1e16 (Higham, *Functions of Matrices*, §8.6); 30 leaves a wide margin.
const POLAR_MAX_STEPS: usize = 30;

impl<T: Real> Default for Dcm<T> {
    /// The identity.
    fn default() -> Self {
        Self(Mat3::IDENTITY)
    }
}

impl<T: Real> Dcm<T> {
    /// The identity rotation.
    pub const IDENTITY: Self = Self(Mat3::IDENTITY);

    /// Default tolerance for [`Dcm::try_from_matrix`] on `‖RᵀR − 1‖_max`: `1000·ε`
    /// (1.2e-4 for f32, 2.2e-13 for f64). Generous enough for a matrix written with full
    /// precision and read back, or computed by a short chain of products; anything further off is
    /// not a rotation matrix but data needing [`Dcm::try_from_matrix_orthonormalized`].
    pub fn default_tolerance() -> T {
        T::from_f64(1000.0) * T::EPSILON
    }

    /// Accepts `m` as a rotation matrix if `‖mᵀm − 1‖_max ≤ tolerance` and `det m > 0`.
    ///
    /// `tolerance` must be in `[0, 1)`: with one or more, columns of any length up to `√2` and
    /// beyond pass, which are not near a rotation; below it every entry of an accepted matrix is
    /// below `√2` in magnitude, which keeps [`Dcm::to_unit_quat`] and the other conversions
    /// finite and unit.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite entry or tolerance; [`Error::InvalidArgument`] for a
    /// tolerance outside `[0, 1)`; [`Error::NotRotation`] if the test fails (including
    /// reflections, `det < 0`, and entries so large that `mᵀm` overflows).
    pub fn try_from_matrix(m: Mat3<T>, tolerance: T) -> Result<Self, Error> {
        if !m.is_finite() || !tolerance.is_finite() {
            return Err(Error::NonFinite);
        }
        if !(tolerance >= T::ZERO && tolerance < T::ONE) {
            return Err(Error::InvalidArgument);
        }
        let e = (m.transpose() * m - Mat3::IDENTITY).max_abs();
        // Written so that a NaN (∞ − ∞ of huge entries) fails the test.
        if !(e <= tolerance && m.determinant() > T::ZERO) {
            return Err(Error::NotRotation);
        }
        Ok(Self(m))
    }

    /// The nearest rotation matrix to a noisy `m` (in the Frobenius norm): the orthogonal polar
    /// factor, by the scaled Newton iteration `X ← (γX + (γX)⁻ᵀ)/2` (Higham, *Functions of
    /// Matrices*, §8.3, §8.6),
    /// which converges quadratically and is symmetric in the three axes (unlike Gram–Schmidt).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite entry; [`Error::NotRotation`] when `det m ≤ 0` (a
    /// reflection or rank-deficient matrix has no nearest rotation in this sense), when `m` is
    /// numerically singular, or if the iteration has not converged within its step budget.
    pub fn try_from_matrix_orthonormalized(m: Mat3<T>) -> Result<Self, Error> {
        if !m.is_finite() {
            return Err(Error::NonFinite);
        }
        // Scale to unit max entry first so that huge or tiny inputs invert safely.
        let s = m.max_abs();
        if s == T::ZERO {
            return Err(Error::NotRotation);
        }
        let mut x = m.scale(T::ONE / s);
        if x.determinant() <= T::ZERO {
            return Err(Error::NotRotation);
        }
        // Stop once a step changes no entry by more than 8ε (converged to rounding).
        let tol = T::from_f64(8.0) * T::EPSILON;
        let frob = |m: &Mat3<T>| m.m.iter().flatten().fold(T::ZERO, |a, &e| a + e * e).sqrt();
        let mut converged = false;
        for _ in 0..POLAR_MAX_STEPS {
            let inv = x.try_inverse().map_err(|_| Error::NotRotation)?;
            // Higham's Frobenius-norm scaling γ = (‖X⁻¹‖/‖X‖)^½ makes the iteration converge in
            // a handful of steps even for badly conditioned input; γ → 1 near convergence.
            let gamma = (frob(&inv) / frob(&x)).sqrt();
            let next = (x.scale(gamma) + inv.transpose().scale(T::ONE / gamma)).scale(T::HALF);
            let change = (next - x).max_abs();
            x = next;
            if change <= tol {
                converged = true;
                break;
            }
        }
        if !converged || !x.is_finite() {
            return Err(Error::NotRotation);
        }
        Ok(Self(x))
    }

    /// Wraps `m` without checking; the caller promises it is a rotation matrix. Breaking the
    /// promise gives wrong results from the conversions, never undefined behaviour or a panic.
    #[inline]
    pub const fn from_matrix_unchecked(m: Mat3<T>) -> Self {
        Self(m)
    }

    /// The matrix.
    #[inline]
    pub const fn matrix(&self) -> &Mat3<T> {
        &self.0
    }

    /// The matrix, by value.
    #[inline]
    pub const fn into_matrix(self) -> Mat3<T> {
        self.0
    }

    /// The inverse rotation: the transpose.
    #[inline]
    pub fn inverse(self) -> Self {
        Self(self.0.transpose())
    }

    /// Rotates a body vector into the lab frame: `R·v`.
    #[inline]
    pub fn rotate(self, v: Vec3<T>) -> Vec3<T> {
        self.0 * v
    }

    /// The unit quaternion of this matrix, by Shepperd's method (J. Guidance Control 1(3), 1978)
    /// with Day's choice of the pivot (*Converting a rotation matrix to a quaternion*, 2015): one
    /// of `4w² = 1 + tr R`, `4x² = 1 + 2R₀₀ − tr R`, `4y²…`, `4z²…` that is at least 1, picked by
    /// two comparisons (`R₂₂ < 0`, then `R₀₀ > R₁₁` or `R₀₀ < −R₁₁`); the other three
    /// components come from sums and differences of off-diagonal entries, and the four are
    /// divided by their norm (at least the pivot `t ≥ 1`: never a division by a small number). Result has
    /// `w ≥ 0` when `w` is the pivot, else the pivot component positive; call
    /// [`UnitQuat::canonical`] for the documented SO(3) representative.
    ///
    /// The result is a unit quaternion to rounding for every matrix a `Dcm` holds (also one
    /// accepted with a loose tolerance).
    #[inline]
    pub fn to_unit_quat(self) -> UnitQuat<T> {
        let m = &self.0.m;
        let (r00, r01, r02) = (m[0][0], m[0][1], m[0][2]);
        let (r10, r11, r12) = (m[1][0], m[1][1], m[1][2]);
        let (r20, r21, r22) = (m[2][0], m[2][1], m[2][2]);
        let one = T::ONE;
        // Each branch's pivot t is ≥ 1: e.g. R₂₂ < 0 and R₀₀ > R₁₁ give
        // t = 1 + (R₀₀ − R₁₁) − R₂₂ > 1.
        let q = if r22 < T::ZERO {
            if r00 > r11 {
                let t = one + r00 - r11 - r22;
                Quat::new(r21 - r12, t, r01 + r10, r02 + r20)
            } else {
                let t = one - r00 + r11 - r22;
                Quat::new(r02 - r20, r01 + r10, t, r12 + r21)
            }
        } else if r00 < -r11 {
            let t = one - r00 - r11 + r22;
            Quat::new(r10 - r01, r02 + r20, r12 + r21, t)
        } else {
            let t = one + r00 + r11 + r22;
            Quat::new(t, r21 - r12, r02 - r20, r10 - r01)
        };
        // q = 4c·(w, x, y, z) with c = √t/2 the pivot component. Dividing by |q| (≥ t ≥ 1, never
        // small; entries ≤ 4, so no overflow) keeps the result unit for every matrix a `Dcm`
        // accepts; the cheaper 1/(2√t) is exact only for an orthogonal matrix (|q| − 1 reaches
        // 3e-2 at the tolerance 1e-1).
        UnitQuat::new_unchecked(q.scale(one / q.norm_squared().sqrt()))
    }
}

/// Composition: `R₁·R₂` applies `R₂` first.
impl<T: Real> Mul for Dcm<T> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self(self.0 * o.0)
    }
}

impl<T: Real> From<UnitQuat<T>> for Dcm<T> {
    /// `R(q)`, see [`UnitQuat::to_rotation_matrix`].
    #[inline]
    fn from(q: UnitQuat<T>) -> Self {
        Self(q.to_rotation_matrix())
    }
}

impl<T: Real> From<Dcm<T>> for UnitQuat<T> {
    /// Shepperd's method, see [`Dcm::to_unit_quat`].
    #[inline]
    fn from(d: Dcm<T>) -> Self {
        d.to_unit_quat()
    }
}

impl<T: Real> From<Dcm<T>> for Mat3<T> {
    #[inline]
    fn from(d: Dcm<T>) -> Self {
        d.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shepperd_every_branch_round_trips() {
        // Near-π turns about each axis select the x, y, z branches; a small turn the w branch.
        for (axis, angle) in [
            (Vec3::new(1.0f64, 0.1, -0.2), 3.1),
            (Vec3::new(0.1, 1.0, 0.2), 3.0),
            (Vec3::new(-0.2, 0.1, 1.0), 3.13),
            (Vec3::new(0.3, -0.5, 0.8), 0.4),
        ] {
            let q = UnitQuat::try_from_axis_angle(axis, angle).unwrap();
            let back = Dcm::from(q).to_unit_quat();
            assert!(back.dot(q).abs() > 1.0 - 1e-15, "{axis:?} {angle}");
            assert!((back.as_quat().norm() - 1.0).abs() < 1e-15);
        }
    }
}
