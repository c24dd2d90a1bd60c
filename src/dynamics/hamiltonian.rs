//! Body-frame Hamiltonians: rigid, gyro-rotor and centrifugally distorted (semi-rigid) rotors.
//!
//! Every model is a function `H(J)` of the body-frame total angular momentum `J`, whose motion
//! is the Lie–Poisson flow `J̇ = J × ∇H(J)` with body rate `ω = ∇H(J)` (6.8.5), the attitude
//! co-propagated by `q̇ = ½ q ⊗ (0, ω)`:
//!
//! - rigid: `H = ½ J·I⁻¹·J` (6.5.11), `I` any physical tensor (full, non-diagonal allowed);
//! - gyro-rotor: `H = ½ (J − S)·I⁻¹·(J − S)`, in principal axes `Σ Aᵢ (Jᵢ − Sᵢ)²` with
//!   `Aᵢ = 1/(2Iᵢ)` (6.9.2b), `S` the body-fixed rotor momentum (constant spins and, in a
//!   [`crate::dynamics::gyrostat::Gyrostat`], the reaction wheels);
//! - semi-rigid: the rigid (or gyro-rotor) part plus an octahedral `t₄(J₁⁴ + J₂⁴ + J₃⁴)`
//!   (6.8.20a) or cubic `t₂₂(J₁²J₂² + J₁²J₃² + J₂²J₃²)` (6.8.20b) centrifugal-distortion term.
//!
//! The inverse map, the momentum `J` of a given body rate `ω`, is
//! [`BodyHamiltonian::try_momentum_from_omega`] (linear without a quartic term, Newton's method with
//! the Hessian [`BodyHamiltonian::hessian`] with one).

use crate::dynamics::inertia::Inertia;
use crate::{Error, Mat3, Real, Vec3};

/// Newton steps [`BodyHamiltonian::try_momentum_from_omega`] takes at most. From the linear guess
/// `J = I·ω + S` the iteration converges quadratically while the quartic term is a perturbation
/// of the quadratic one (a handful of steps); the cap bounds the cost when it is not.
pub const MOMENTUM_SOLVE_MAX_STEPS: usize = 50;

/// Relative Newton step `|ΔJ| ≤ tol·(1 + |J|)` at which [`BodyHamiltonian::try_momentum_from_omega`]
/// stops: 1e-14, about 50 f64 ulp, where the quadratic convergence has reached rounding. Below
/// f32's resolution, so an f32 solve runs all [`MOMENTUM_SOLVE_MAX_STEPS`] steps and is then
/// judged by [`MOMENTUM_SOLVE_RESIDUAL`].
pub const MOMENTUM_SOLVE_STEP_TOLERANCE: f64 = 1e-14;

/// Largest accepted residual `|∇H(J) − ω| ≤ tol·(1 + |ω|)` of a solve that did not meet
/// [`MOMENTUM_SOLVE_STEP_TOLERANCE`]: 1e-6, a few f32 ulp of the rate with margin (the rounding
/// floor of evaluating `∇H` in f32).
pub const MOMENTUM_SOLVE_RESIDUAL: f64 = 1e-6;

/// A quartic centrifugal-distortion term added to the quadratic Hamiltonian (6.8.20).
///
/// The polynomials are in the body axes, which must then be the principal axes (the seed's
/// `T⁽⁴⁾` tensors are written in a molecule's symmetry axes); [`BodyHamiltonian::try_new`]
/// rejects a quartic term with a non-diagonal inertia tensor.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Quartic<T> {
    /// No quartic term: a rigid body or gyro-rotor.
    #[default]
    None,
    /// Octahedral `t₄ (J₁⁴ + J₂⁴ + J₃⁴)` (6.8.20a, 6.8.20c).
    Octahedral(T),
    /// Cubic `t₂₂ (J₁²J₂² + J₁²J₃² + J₂²J₃²)` (6.8.20b, 6.8.20d).
    Cubic(T),
}

/// A body-frame Hamiltonian `H(J) = ½ (J − S)·I⁻¹·(J − S) + quartic(J)`.
///
/// `S` is the constant body-fixed rotor momentum (zero for a rigid body). The quadratic part is
/// the gyro-rotor (6.9.2b); with `S = 0` it is the rigid rotor (6.7.27a).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyHamiltonian<T> {
    inertia: Inertia<T>,
    spin: Vec3<T>,
    quartic: Quartic<T>,
    /// `Aᵢ = 1/(2λᵢ)` on the principal axes (6.9.2).
    half_inverse: Vec3<T>,
}

impl<T: Real> BodyHamiltonian<T> {
    /// The rigid rotor `H = ½ J·I⁻¹·J` (6.5.11), infallible because `inertia` is validated.
    pub fn rigid(inertia: Inertia<T>) -> Self {
        let m = inertia.principal_moments();
        Self {
            inertia,
            spin: Vec3::ZERO,
            quartic: Quartic::None,
            half_inverse: Vec3::new(T::HALF / m.x, T::HALF / m.y, T::HALF / m.z),
        }
    }

    /// A rotor with body-fixed constant rotor momentum `spin` (`S`, body frame) and an optional
    /// quartic distortion term.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `spin` or quartic coefficient;
    /// [`Error::InvalidArgument`] for a quartic term with a non-diagonal inertia tensor (the
    /// quartic polynomials are defined on principal axes), or a coefficient so large that the
    /// Hessian's factor `12t` overflows (`|t|` above `MAX/12`: the gradient and Hessian of even
    /// a unit momentum would not be representable).
    pub fn try_new(inertia: Inertia<T>, spin: Vec3<T>, quartic: Quartic<T>) -> Result<Self, Error> {
        let spin = spin.try_finite()?;
        match quartic {
            Quartic::None => {}
            Quartic::Octahedral(t) | Quartic::Cubic(t) => {
                if !t.is_finite() {
                    return Err(Error::NonFinite);
                }
                if !inertia.is_diagonal() || !(T::from_f64(12.0) * t).is_finite() {
                    return Err(Error::InvalidArgument);
                }
            }
        }
        let mut h = Self::rigid(inertia);
        h.spin = spin;
        h.quartic = quartic;
        Ok(h)
    }

    /// The inertia tensor.
    #[inline]
    pub fn inertia(&self) -> &Inertia<T> {
        &self.inertia
    }

    /// The constant rotor momentum `S` (body frame).
    #[inline]
    pub fn spin(&self) -> Vec3<T> {
        self.spin
    }

    /// The quartic term.
    #[inline]
    pub fn quartic(&self) -> Quartic<T> {
        self.quartic
    }

    /// `Aᵢ = 1/(2λᵢ)` on the principal axes (6.9.2).
    #[inline]
    pub(crate) fn half_inverse(&self) -> Vec3<T> {
        self.half_inverse
    }

    /// `H(J)` with the model's own rotor momentum `S`.
    #[inline]
    pub fn energy(&self, j: Vec3<T>) -> T {
        self.energy_with_rotor(j, self.spin)
    }

    /// The body rate `ω = ∇H(J)` with the model's own rotor momentum.
    #[inline]
    pub fn omega(&self, j: Vec3<T>) -> Vec3<T> {
        self.omega_with_rotor(j, self.spin)
    }

    /// `H(J)` with total rotor momentum `s` (the model's spin plus any wheel momentum):
    /// `½ (J − s)·I⁻¹·(J − s) + quartic(J)`.
    ///
    /// Domain (of this and the other maps of `J`: [`BodyHamiltonian::omega_with_rotor`],
    /// [`BodyHamiltonian::hessian`] and the model-spin forms): a finite momentum whose energy and
    /// rate are representable, `|J − s|²/I_min` and `|J − s|/I_min` below `MAX/8`, and with a
    /// quartic term (coefficient `t`) `|J|⁴`, `|t|·|J|⁴` and `12|t|·|J|³` too. Outside it the
    /// arithmetic overflows and the
    /// result is infinite or NaN; the checked steps reject such states
    /// ([`crate::dynamics::Gyrostat::step`]).
    pub fn energy_with_rotor(&self, j: Vec3<T>, s: Vec3<T>) -> T {
        let r = j - s;
        T::HALF * r.dot(self.inertia.solve(r)) + quartic_energy(self.quartic, j)
    }

    /// `ω = ∇H(J) = I⁻¹(J − s) + ∇quartic(J)` with total rotor momentum `s`.
    pub fn omega_with_rotor(&self, j: Vec3<T>, s: Vec3<T>) -> Vec3<T> {
        self.inertia.solve(j - s) + quartic_gradient(self.quartic, j)
    }

    /// The Hessian `∂ω/∂J = ∇²H(J) = I⁻¹ + ∇²quartic(J)` (symmetric; independent of the rotor
    /// momentum): octahedral `12t₄ diag(Jᵢ²)`, cubic `2t₂₂(|J|² − Jᵢ²)` on the diagonal and
    /// `4t₂₂ JᵢJₖ` off it.
    pub fn hessian(&self, j: Vec3<T>) -> Mat3<T> {
        self.inertia.inverse() + quartic_hessian(self.quartic, j)
    }

    /// The momentum `J` with body rate `∇H(J) = ω` at the model's own rotor momentum `S`.
    ///
    /// # Errors
    /// As [`BodyHamiltonian::try_momentum_from_omega_with_rotor`].
    ///
    /// ```
    /// use gyrostat::dynamics::{BodyHamiltonian, Inertia, Quartic};
    /// use gyrostat::Vec3;
    /// let i = Inertia::try_from_principal(Vec3::new(6.0f64, 4.0, 3.0))?;
    /// let h = BodyHamiltonian::try_new(i, Vec3::ZERO, Quartic::Cubic(0.002))?;
    /// let omega = Vec3::new(0.5, 1.0, 0.3);
    /// let j = h.try_momentum_from_omega(omega)?;
    /// assert!((h.omega(j) - omega).norm() < 1e-14);
    /// # Ok::<(), gyrostat::Error>(())
    /// ```
    pub fn try_momentum_from_omega(&self, omega: Vec3<T>) -> Result<Vec3<T>, Error> {
        self.try_momentum_from_omega_with_rotor(omega, self.spin)
    }

    /// The momentum `J` with body rate `∇H(J) = ω` at total rotor momentum `s`: `J = I·ω + s`
    /// without a quartic term; with one, Newton's method from that guess with the Hessian
    /// [`BodyHamiltonian::hessian`], stopped at [`MOMENTUM_SOLVE_STEP_TOLERANCE`] or after
    /// [`MOMENTUM_SOLVE_MAX_STEPS`] steps.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for non-finite input or a non-finite Hessian; [`Error::InvalidArgument`]
    /// when `I·ω + s` overflows the type; [`Error::Singular`] where the Hessian is singular (the
    /// rate does not determine the momentum there); [`Error::NotConverged`] when the iterates
    /// diverge (including to infinity) or the last one misses [`MOMENTUM_SOLVE_RESIDUAL`].
    pub fn try_momentum_from_omega_with_rotor(
        &self,
        omega: Vec3<T>,
        s: Vec3<T>,
    ) -> Result<Vec3<T>, Error> {
        let omega = omega.try_finite()?;
        let mut j = self.inertia.mul_vec(omega) + s.try_finite()?;
        if !j.is_finite() {
            return Err(Error::InvalidArgument);
        }
        if self.quartic == Quartic::None {
            return Ok(j);
        }
        let step_tol = T::from_f64(MOMENTUM_SOLVE_STEP_TOLERANCE);
        for _ in 0..MOMENTUM_SOLVE_MAX_STEPS {
            let residual = self.omega_with_rotor(j, s) - omega;
            let step = self.hessian(j).try_inverse()? * residual;
            j -= step;
            // Written so that an iterate or step that overflowed (∞ or NaN) fails the test.
            if !j.is_finite() || !step.is_finite() {
                return Err(Error::NotConverged);
            }
            if step.norm() <= step_tol * (T::ONE + j.norm()) {
                return Ok(j);
            }
        }
        let residual = (self.omega_with_rotor(j, s) - omega).norm();
        if residual <= T::from_f64(MOMENTUM_SOLVE_RESIDUAL) * (T::ONE + omega.norm()) {
            Ok(j)
        } else {
            Err(Error::NotConverged)
        }
    }
}

/// The quartic energy term (6.8.20).
#[inline]
fn quartic_energy<T: Real>(q: Quartic<T>, j: Vec3<T>) -> T {
    let (x2, y2, z2) = (j.x * j.x, j.y * j.y, j.z * j.z);
    match q {
        Quartic::None => T::ZERO,
        Quartic::Octahedral(t4) => t4 * (x2 * x2 + y2 * y2 + z2 * z2),
        Quartic::Cubic(t22) => t22 * (x2 * y2 + x2 * z2 + y2 * z2),
    }
}

/// Gradient of the quartic term: octahedral `4t₄Jᵢ³`, cubic `2t₂₂Jᵢ(|J|² − Jᵢ²)`.
#[inline]
fn quartic_gradient<T: Real>(q: Quartic<T>, j: Vec3<T>) -> Vec3<T> {
    let (x2, y2, z2) = (j.x * j.x, j.y * j.y, j.z * j.z);
    match q {
        Quartic::None => Vec3::ZERO,
        Quartic::Octahedral(t4) => {
            let k = T::from_f64(4.0) * t4;
            Vec3::new(k * x2 * j.x, k * y2 * j.y, k * z2 * j.z)
        }
        Quartic::Cubic(t22) => {
            let k = T::TWO * t22;
            Vec3::new(
                k * j.x * (y2 + z2),
                k * j.y * (x2 + z2),
                k * j.z * (x2 + y2),
            )
        }
    }
}

/// Hessian of the quartic term: octahedral `12t₄ diag(Jᵢ²)`; cubic `2t₂₂(|J|² − Jᵢ²)` on the
/// diagonal, `4t₂₂ JᵢJₖ` off it.
#[inline]
fn quartic_hessian<T: Real>(q: Quartic<T>, j: Vec3<T>) -> Mat3<T> {
    let Vec3 { x, y, z } = j;
    match q {
        Quartic::None => Mat3::ZERO,
        Quartic::Octahedral(t4) => {
            let k = T::from_f64(12.0) * t4;
            Mat3::from_diagonal(Vec3::new(k * x * x, k * y * y, k * z * z))
        }
        Quartic::Cubic(t22) => {
            let (two, four) = (T::TWO * t22, T::from_f64(4.0) * t22);
            Mat3::from_rows(
                [two * (y * y + z * z), four * x * y, four * x * z],
                [four * x * y, two * (x * x + z * z), four * y * z],
                [four * x * z, four * y * z, two * (x * x + y * y)],
            )
        }
    }
}
