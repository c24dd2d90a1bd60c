//! The validated inertia tensor and its principal axes.
//!
//! [`Inertia`] holds a full symmetric body-frame tensor `I` (seed (6.5.4)–(6.5.5)), its inverse,
//! and its principal moments and axes from a symmetric 3×3 eigen-decomposition
//! ([`symmetric_eigen`], cyclic Jacobi with a fixed sweep cap). The rotation from the principal
//! frame to the body frame is kept as a [`UnitQuat`] too, so that closed forms stated in
//! principal axes (the exact free body, the seed's analysis) apply to any body.
//!
//! A tensor is accepted only if it is physical: finite, symmetric, positive definite, and its
//! principal moments obey the triangle inequality `I_a ≤ I_b + I_c` (a consequence of
//! `I_a = Σ m (r_b² + r_c²)`, with equality for a flat lamina). This is the one place where
//! moments are validated: everything that takes principal moments takes an [`Inertia`].

use crate::{Dcm, Error, Mat3, Real, UnitQuat, Vec3};

/// Sweeps of the cyclic Jacobi method before it stops regardless of convergence.
///
/// Jacobi converges quadratically once the off-diagonal part is small; for a 3×3 matrix 4–6
/// sweeps reach the rounding floor in f64 (fewer in f32). Twelve is a safe cap that bounds the
/// worst-case cost (12 × 3 plane rotations) for firmware, and is never reached in the tests.
pub const JACOBI_MAX_SWEEPS: usize = 12;

/// Symmetry tolerance of [`Inertia::try_from_tensor`], in units of machine epsilon times the
/// largest absolute entry: `|I_ij − I_ji| ≤ 64 ε · max|I|`.
///
/// A tensor computed in floating point (for example by rotating a diagonal one,
/// `R·diag·Rᵀ`, about 20 roundings per entry) is symmetric to a few ulp of its largest entry;
/// 64 ulp accepts that with margin and rejects a genuinely asymmetric matrix (a typo, a
/// transposed off-diagonal sign). The accepted tensor is symmetrised by averaging.
pub const SYMMETRY_TOLERANCE_EPS: f64 = 64.0;

/// Rounding allowance, in units of machine epsilon times the trace, of the positive-definiteness
/// and triangle-inequality checks: `λ_min > 32 ε · tr I` and `λ_a ≤ λ_b + λ_c + 32 ε · tr I`.
///
/// The Jacobi eigenvalues carry an absolute error of a few `ε · ‖I‖`; below this margin the sign
/// of `λ_min` (or of `λ_b + λ_c − λ_a`) is not known. The triangle allowance accepts a flat
/// lamina (`I_3 = I_1 + I_2` exactly); the definiteness margin rejects a thin rod (`I_3 = 0`),
/// whose `I⁻¹` does not exist.
pub const EIGEN_TOLERANCE_EPS: f64 = 32.0;

/// A physical rigid-body inertia tensor in the body frame, with its inverse and principal axes.
///
/// # Invariant
/// Finite, symmetric, positive definite, principal moments satisfying `I_a ≤ I_b + I_c`; built
/// only by the checked constructors.
///
/// # Principal frame
/// [`Inertia::principal_moments`] `(λ₁, λ₂, λ₃)` and [`Inertia::principal_rotation`] `P` satisfy
/// `I = R(P) · diag(λ) · R(P)ᵀ`: `P` maps principal-frame vectors to body-frame vectors
/// (`v_body = P ⊗ v_principal ⊗ P*`), so an attitude `q` (body → lab) becomes `q ⊗ P` in the
/// principal frame. The moments are in the order the decomposition produces them, which for a
/// diagonal tensor is the body-axis order with `P` the identity exactly (no reordering).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertia<T> {
    tensor: Mat3<T>,
    inverse: Mat3<T>,
    moments: Vec3<T>,
    axes: Mat3<T>,
    rotation: UnitQuat<T>,
    diagonal: bool,
}

impl<T: Real> Inertia<T> {
    /// The inertia of a body whose principal axes are its body axes: `diag(I₁, I₂, I₃)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite moment; [`Error::NonPhysicalInertia`] for a moment
    /// that is not positive or a triple that violates `I_a ≤ I_b + I_c`.
    ///
    /// ```
    /// use gyrostat::{Error, Vec3, dynamics::inertia::Inertia};
    /// let i = Inertia::try_from_principal(Vec3::new(6.0f64, 4.0, 3.0))?;
    /// assert_eq!(i.principal_moments(), Vec3::new(6.0, 4.0, 3.0));
    /// // A "body" with I₁ > I₂ + I₃ cannot be built from masses.
    /// assert_eq!(
    ///     Inertia::try_from_principal(Vec3::new(8.0f64, 4.0, 3.0)),
    ///     Err(Error::NonPhysicalInertia)
    /// );
    /// # Ok::<(), Error>(())
    /// ```
    pub fn try_from_principal(moments: Vec3<T>) -> Result<Self, Error> {
        if !moments.is_finite() {
            return Err(Error::NonFinite);
        }
        Self::from_checked_diagonal(moments)
    }

    /// The inertia from its six independent components: the diagonal `(I₁₁, I₂₂, I₃₃)` and the
    /// off-diagonal products `(I₁₂, I₁₃, I₂₃)` (entries of the tensor itself, so a point mass
    /// contributes `I₁₂ = −m x y` by (6.5.5)).
    ///
    /// # Errors
    /// As [`Inertia::try_from_tensor`].
    pub fn try_from_components(diagonal: Vec3<T>, off_diagonal: Vec3<T>) -> Result<Self, Error> {
        let (d, o) = (diagonal, off_diagonal);
        Self::try_from_tensor(Mat3::from_rows(
            [d.x, o.x, o.y],
            [o.x, d.y, o.z],
            [o.y, o.z, d.z],
        ))
    }

    /// Validates a full body-frame tensor (seed (6.5.5b)) and computes its principal frame.
    ///
    /// The checks and the eigen-decomposition run on the tensor divided by its largest entry, so
    /// that entries anywhere in the type's range are handled without overflow or underflow.
    /// Domain: a tensor whose inverse is representable too (principal moments above about
    /// `3/MAX`, so that `I⁻¹` and the body rates `I⁻¹J` of ordinary momenta are finite).
    ///
    /// # Errors
    /// - [`Error::NonFinite`]: an entry is NaN or infinite;
    /// - [`Error::NonPhysicalInertia`]: not symmetric within [`SYMMETRY_TOLERANCE_EPS`], not
    ///   positive definite, or principal moments violating `I_a ≤ I_b + I_c` (both within
    ///   [`EIGEN_TOLERANCE_EPS`]);
    /// - [`Error::InvalidArgument`]: a physical tensor whose inverse overflows the type
    ///   (moments below the domain).
    pub fn try_from_tensor(tensor: Mat3<T>) -> Result<Self, Error> {
        if !tensor.is_finite() {
            return Err(Error::NonFinite);
        }
        let m = tensor.m;
        let diagonal = m[0][1] == T::ZERO
            && m[1][0] == T::ZERO
            && m[0][2] == T::ZERO
            && m[2][0] == T::ZERO
            && m[1][2] == T::ZERO
            && m[2][1] == T::ZERO;
        if diagonal {
            return Self::from_checked_diagonal(tensor.diagonal());
        }
        let scale = tensor.max_abs();
        // Divided (not multiplied by a reciprocal, which overflows for a subnormal scale): the
        // largest entry is now ±1.
        let m = m.map(|row| row.map(|x| x / scale));
        let sym_tol = T::from_f64(SYMMETRY_TOLERANCE_EPS) * T::EPSILON;
        if (m[0][1] - m[1][0]).abs() > sym_tol
            || (m[0][2] - m[2][0]).abs() > sym_tol
            || (m[1][2] - m[2][1]).abs() > sym_tol
        {
            return Err(Error::NonPhysicalInertia);
        }
        let o01 = (m[0][1] + m[1][0]) * T::HALF;
        let o02 = (m[0][2] + m[2][0]) * T::HALF;
        let o12 = (m[1][2] + m[2][1]) * T::HALF;
        let unit_sym = Mat3::from_rows(
            [m[0][0], o01, o02],
            [o01, m[1][1], o12],
            [o02, o12, m[2][2]],
        );
        let (unit_moments, axes) = symmetric_eigen(&unit_sym);
        check_moments(unit_moments)?;
        let sym = Mat3::from_rows(
            [tensor.m[0][0], o01 * scale, o02 * scale],
            [o01 * scale, tensor.m[1][1], o12 * scale],
            [o02 * scale, o12 * scale, tensor.m[2][2]],
        );
        // `axes` is a proper rotation (orthonormal columns to rounding, det +1 by construction):
        // Shepperd's method of `Dcm` applies.
        let rotation = Dcm::from_matrix_unchecked(axes).to_unit_quat();
        Self::assemble(sym, unit_moments.scale(scale), axes, rotation, false)
    }

    /// A diagonal tensor of finite moments: principal frame = body frame, no decomposition (so
    /// that code building bodies only from principal moments links no eigen-solver).
    fn from_checked_diagonal(d: Vec3<T>) -> Result<Self, Error> {
        let scale = d.max_abs();
        if scale == T::ZERO {
            return Err(Error::NonPhysicalInertia);
        }
        check_moments(d / scale)?;
        Self::assemble(
            Mat3::from_diagonal(d),
            d,
            Mat3::IDENTITY,
            UnitQuat::IDENTITY,
            true,
        )
    }

    /// The inertia of a validated principal frame, rejected with [`Error::InvalidArgument`] if
    /// its inverse (or, scaled back, a moment) is not representable.
    fn assemble(
        tensor: Mat3<T>,
        moments: Vec3<T>,
        axes: Mat3<T>,
        rotation: UnitQuat<T>,
        diagonal: bool,
    ) -> Result<Self, Error> {
        let inv = Vec3::new(T::ONE / moments.x, T::ONE / moments.y, T::ONE / moments.z);
        let inverse = if diagonal {
            Mat3::from_diagonal(inv)
        } else {
            axes * Mat3::from_diagonal(inv) * axes.transpose()
        };
        if !(inverse.is_finite() && moments.is_finite() && tensor.is_finite()) {
            return Err(Error::InvalidArgument);
        }
        Ok(Self {
            tensor,
            inverse,
            moments,
            axes,
            rotation,
            diagonal,
        })
    }

    /// The (symmetrised) body-frame tensor `I`.
    #[inline]
    pub fn tensor(&self) -> Mat3<T> {
        self.tensor
    }

    /// The inverse tensor `I⁻¹ = R(P)·diag(1/λ)·R(P)ᵀ`.
    #[inline]
    pub fn inverse(&self) -> Mat3<T> {
        self.inverse
    }

    /// The principal moments `(λ₁, λ₂, λ₃)` (see the type docs for their order).
    #[inline]
    pub fn principal_moments(&self) -> Vec3<T> {
        self.moments
    }

    /// The principal axes as the columns of a proper rotation matrix, in body coordinates.
    #[inline]
    pub fn principal_axes(&self) -> Mat3<T> {
        self.axes
    }

    /// The rotation `P` from the principal frame to the body frame (`v_body = P ⊗ v_p ⊗ P*`).
    #[inline]
    pub fn principal_rotation(&self) -> UnitQuat<T> {
        self.rotation
    }

    /// `true` when the tensor was exactly diagonal: principal frame = body frame, `P = 1`.
    #[inline]
    pub fn is_diagonal(&self) -> bool {
        self.diagonal
    }

    /// Angular momentum of a rigid rotation, `L = I·ω` (6.5.3). For a diagonal tensor only the
    /// diagonal is multiplied (the same result: the products with the zero entries add nothing).
    #[inline]
    pub fn mul_vec(&self, omega: Vec3<T>) -> Vec3<T> {
        if self.diagonal {
            self.moments.component_mul(omega)
        } else {
            self.tensor * omega
        }
    }

    /// Angular velocity from angular momentum, `ω = I⁻¹·J` (6.5.14a). For a diagonal tensor
    /// only the diagonal of `I⁻¹` is multiplied (as [`Inertia::mul_vec`]).
    #[inline]
    pub fn solve(&self, momentum: Vec3<T>) -> Vec3<T> {
        if self.diagonal {
            self.inverse.diagonal().component_mul(momentum)
        } else {
            self.inverse * momentum
        }
    }

    /// Rotational kinetic energy `½ J·I⁻¹·J` (6.5.11).
    #[inline]
    pub fn energy_from_momentum(&self, momentum: Vec3<T>) -> T {
        T::HALF * momentum.dot(self.solve(momentum))
    }

    /// Principal radii of gyration `kᵢ = √(λᵢ / M)` for a body of mass `mass`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite mass, [`Error::InvalidArgument`] for `mass ≤ 0` or
    /// a radius that overflows the type (a mass far below the moments).
    pub fn radii_of_gyration(&self, mass: T) -> Result<Vec3<T>, Error> {
        check_mass(mass)?;
        let m = self.moments;
        let k = Vec3::new(
            (m.x / mass).sqrt(),
            (m.y / mass).sqrt(),
            (m.z / mass).sqrt(),
        );
        representable_vec(k)
    }

    /// Radius of gyration about a body-frame axis through the reference point:
    /// `k = √(n̂·I·n̂ / M)`.
    ///
    /// # Errors
    /// As [`Inertia::radii_of_gyration`], plus the errors of normalising `axis`
    /// ([`Error::ZeroNorm`], [`Error::NonFinite`]).
    pub fn radius_of_gyration_about(&self, axis: Vec3<T>, mass: T) -> Result<T, Error> {
        check_mass(mass)?;
        let n = axis.try_normalize()?;
        let k = (n.dot(self.tensor * n) / mass).sqrt();
        if k.is_finite() {
            Ok(k)
        } else {
            Err(Error::InvalidArgument)
        }
    }
}

/// The checks of principal moments (scaled to a largest magnitude of about one, so that the
/// trace cannot overflow): positive definite and obeying the triangle inequality, both within
/// [`EIGEN_TOLERANCE_EPS`].
fn check_moments<T: Real>(moments: Vec3<T>) -> Result<(), Error> {
    let (a, b, c) = (moments.x, moments.y, moments.z);
    let tol = T::from_f64(EIGEN_TOLERANCE_EPS) * T::EPSILON * (a + b + c).abs();
    let min = a.min(b).min(c);
    // Written so that a NaN fails.
    let positive = min > tol;
    if !positive || a > b + c + tol || b > a + c + tol || c > a + b + tol {
        return Err(Error::NonPhysicalInertia);
    }
    Ok(())
}

fn check_mass<T: Real>(mass: T) -> Result<(), Error> {
    if !mass.is_finite() {
        return Err(Error::NonFinite);
    }
    if mass <= T::ZERO {
        return Err(Error::InvalidArgument);
    }
    Ok(())
}

/// A result computed from finite input, rejected with [`Error::InvalidArgument`] if it
/// overflowed (an input outside the documented domain of magnitudes).
fn representable_vec<T: Real>(v: Vec3<T>) -> Result<Vec3<T>, Error> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::InvalidArgument)
    }
}

/// Eigen-decomposition of a symmetric 3×3 matrix by the cyclic Jacobi method.
///
/// Returns `(λ, V)` with `A ≈ V·diag(λ)·Vᵀ`, `V` a proper rotation (its columns the unit
/// eigenvectors, the third negated if needed so that `det V = +1`). Only the upper triangle of
/// `a` is read. No reordering: a diagonal input returns its diagonal and `V = 1` exactly.
///
/// Each plane rotation uses the stable small-angle form `t = sgn θ / (|θ| + √(θ² + 1))`,
/// `θ = (a_qq − a_pp)/(2 a_pq)` (Rutishauser; Golub & Van Loan §8.5), with `√(θ²+1)` as a
/// `hypot` so that a tiny `a_pq` cannot overflow it. Sweeps stop when the off-diagonal part is
/// below `ε²` of the diagonal, or after [`JACOBI_MAX_SWEEPS`]. Eigenvalue error ≈ a few
/// `ε·‖A‖`. Never panics; a non-finite input gives a non-finite output.
pub fn symmetric_eigen<T: Real>(a: &Mat3<T>) -> (Vec3<T>, Mat3<T>) {
    let m = a.m;
    let mut s = Sym {
        d: Vec3::new(m[0][0], m[1][1], m[2][2]),
        o01: m[0][1],
        o02: m[0][2],
        o12: m[1][2],
    };
    let mut v = [Vec3::X, Vec3::Y, Vec3::Z];
    for _ in 0..JACOBI_MAX_SWEEPS {
        let off = s.o01.abs() + s.o02.abs() + s.o12.abs();
        let diag = s.d.x.abs() + s.d.y.abs() + s.d.z.abs();
        if off <= T::EPSILON * T::EPSILON * diag {
            break;
        }
        // Pair (0, 1), third index 2.
        if let Some((c, sn, t)) = jacobi_angle(s.d.x, s.d.y, s.o01) {
            s.d.x -= t * s.o01;
            s.d.y += t * s.o01;
            s.o01 = T::ZERO;
            let (r_p, r_q) = (s.o02, s.o12);
            s.o02 = c * r_p - sn * r_q;
            s.o12 = sn * r_p + c * r_q;
            let [vp, vq, vr] = v;
            v = [vp * c - vq * sn, vp * sn + vq * c, vr];
        }
        // Pair (0, 2), third index 1.
        if let Some((c, sn, t)) = jacobi_angle(s.d.x, s.d.z, s.o02) {
            s.d.x -= t * s.o02;
            s.d.z += t * s.o02;
            s.o02 = T::ZERO;
            let (r_p, r_q) = (s.o01, s.o12);
            s.o01 = c * r_p - sn * r_q;
            s.o12 = sn * r_p + c * r_q;
            let [vp, vr, vq] = v;
            v = [vp * c - vq * sn, vr, vp * sn + vq * c];
        }
        // Pair (1, 2), third index 0.
        if let Some((c, sn, t)) = jacobi_angle(s.d.y, s.d.z, s.o12) {
            s.d.y -= t * s.o12;
            s.d.z += t * s.o12;
            s.o12 = T::ZERO;
            let (r_p, r_q) = (s.o01, s.o02);
            s.o01 = c * r_p - sn * r_q;
            s.o02 = sn * r_p + c * r_q;
            let [vr, vp, vq] = v;
            v = [vr, vp * c - vq * sn, vp * sn + vq * c];
        }
    }
    let [v0, v1, mut v2] = v;
    if v0.cross(v1).dot(v2) < T::ZERO {
        v2 = -v2;
    }
    (s.d, Mat3::from_cols(v0, v1, v2))
}

/// The working symmetric matrix of [`symmetric_eigen`], by named entries (no indexing).
struct Sym<T> {
    d: Vec3<T>,
    o01: T,
    o02: T,
    o12: T,
}

/// `(c, s, t)` of the Jacobi rotation that zeroes `a_pq`, or `None` if it is already zero.
#[inline]
fn jacobi_angle<T: Real>(app: T, aqq: T, apq: T) -> Option<(T, T, T)> {
    if apq == T::ZERO {
        return None;
    }
    let theta = (aqq - app) / (T::TWO * apq);
    let t = T::ONE.copysign(theta) / (theta.abs() + theta.hypot(T::ONE));
    let c = T::ONE / t.hypot(T::ONE);
    Some((c, t * c, t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_is_identity_frame() {
        let i = Inertia::try_from_principal(Vec3::new(6.0f64, 4.0, 3.0)).unwrap();
        assert_eq!(i.principal_rotation(), UnitQuat::IDENTITY);
        assert!(i.is_diagonal());
        assert_eq!(i.solve(Vec3::new(6.0, 4.0, 3.0)), Vec3::new(1.0, 1.0, 1.0));
    }

    #[test]
    fn reconstructs_rotated_tensor() {
        let q = UnitQuat::try_from_axis_angle(Vec3::new(1.0f64, 2.0, -0.5), 0.9).unwrap();
        let r = q.to_rotation_matrix();
        let a = r * Mat3::from_diagonal(Vec3::new(2.0, 3.0, 4.0)) * r.transpose();
        let i = Inertia::try_from_tensor(a).unwrap();
        let v = i.principal_axes();
        let back = v * Mat3::from_diagonal(i.principal_moments()) * v.transpose();
        assert!((back - a).max_abs() < 1e-14);
        let p = i.principal_rotation().to_rotation_matrix();
        assert!((p - v).max_abs() < 1e-15);
        assert!((i.inverse() * a - Mat3::IDENTITY).max_abs() < 1e-14);
    }

    #[test]
    fn rejects_non_physical() {
        let e = Err(Error::NonPhysicalInertia);
        assert_eq!(Inertia::try_from_principal(Vec3::new(1.0f32, 1.0, 0.0)), e);
        assert_eq!(Inertia::try_from_principal(Vec3::new(1.0f32, 1.0, -1.0)), e);
        assert_eq!(Inertia::try_from_principal(Vec3::new(3.0f32, 1.0, 1.5)), e);
        let flat = Inertia::try_from_principal(Vec3::new(1.0f32, 2.0, 3.0));
        assert!(flat.is_ok());
        let asym = Mat3::from_rows([2.0f64, 0.1, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]);
        assert_eq!(
            Inertia::try_from_tensor(asym),
            Err(Error::NonPhysicalInertia)
        );
        let nan = Vec3::new(f64::NAN, 1.0, 1.0);
        assert_eq!(Inertia::try_from_principal(nan), Err(Error::NonFinite));
    }
}
