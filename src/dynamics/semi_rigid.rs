//! Semi-rigid rotors: centrifugal stretching of springs, and the quartic (centrifugal-distortion)
//! Hamiltonian it produces (seed §6.8.c, (6.8.11)–(6.8.20)).
//!
//! A rotor whose masses sit on springs stretches as it spins; at fixed angular momentum `J` the
//! springs settle where the spring force balances the centrifugal force, and the energy at that
//! equilibrium is the rigid energy minus a term of order `J⁴`. That term is what makes the
//! quartic coefficients of [`Quartic`] physical.
//!
//! # One mode
//! [`SpringRotor`] is the seed's Fig. 6.8.3: one mass `m` on a spring of frequency `ω_v`
//! (stiffness `k = mω_v²`), rest radius `r₀`, turning in a plane. Its energy is
//! `E = p_v²/2m + ½mω_v²(r − r₀)² + ½μJ²`, `μ = 1/(mr²)` (6.8.11). The exact equilibrium is
//! `r = r₀ω_v²/(ω_v² − ω_J²)` with `ω_J = J/(mr²)` the turning rate (6.8.12). To first order in
//! `J²` the stretch is `d = −J²(∂μ/∂r)/(2mω_v²)` (6.8.13) and the effective energy is
//! `E = ½μ₀J² − J⁴(∂μ/∂r)²/(8mω_v²) + O(J⁶)` (6.8.15): the quartic term is the leading correction.
//! [`StretchMode`] is the same for any body with one stretch coordinate `r` of mass `m`, given
//! the slope `∂μ/∂r` of its inverse inertia (the seed's "for a body" form).
//!
//! The seed prints (6.8.13) as `d = +J²(∂μ/∂r)/(2mω_v²)`. The sign is a misprint: the
//! equilibrium condition printed in the same line, `mω_v²(r − r₀) + ½J²∂μ/∂r = 0`, gives the
//! minus sign; `∂μ/∂r = −2/(mr³) < 0` so the spring stretches (`d > 0`), as (6.8.12) says; and
//! (6.8.14a) and (6.8.17) use the minus sign. This module uses the minus sign.
//!
//! # Many modes: a body of masses on radial springs
//! [`SemiRigidRotor`] is a rigid frame carrying point masses, each free to slide along its own
//! body-fixed radial rod and held there by a spring of frequency `ω_v` (the rods do not bend).
//! Each radius `r_j` is a normal coordinate of frequency `ω_v` (6.8.16); the inverse inertia
//! `μ = I⁻¹` depends on them through `∂I/∂r_j = 2m_j r_j (1 − n̂_j n̂_jᵀ)`,
//! `∂μ/∂r_j = −μ₀ (∂I/∂r_j) μ₀`. At fixed body momentum `J` the radii shift by
//! `δr_j = −J·(∂μ/∂r_j)·J / (2m_jω_v²)` (6.8.17), and the effective Hamiltonian is (6.8.18)
//!
//! `H = ½ J·μ₀·J − Σ_j (J·(∂μ/∂r_j)·J)² / (8 m_j ω_v²) + O(J⁶)`.
//!
//! When the masses have cubic symmetry about the body axes the quartic part has only two
//! independent coefficients (6.8.19): `t₀|J|⁴ + t₄(J₁⁴ + J₂⁴ + J₃⁴)` (the octahedral form
//! (6.8.20a) with the seed's scalar `t₀J⁴` of `H₀`), or equivalently, by
//! `|J|⁴ = T⁽⁴⁾ + 2T⁽²²⁾`, `(t₀ + t₄)|J|⁴ − 2t₄(J₁²J₂² + J₁²J₃² + J₂²J₃²)` (the cubic form
//! (6.8.20b) with `t₂₂ = −2t₄`).
//!
//! Which arrangement gives which term (equal masses `m`, rest radius `r₀`, `ω_v`;
//! `c = 1/(m³ω_v²r₀⁶)`):
//!
//! | [`Arrangement`] | masses | quartic (exact sum of (6.8.18)) | natural form |
//! |---|---|---|---|
//! | `Octahedral` (SF₆-like) | 6, on `±x, ±y, ±z` | `−(c/256)(|J|⁴ + T⁽⁴⁾)` | (6.8.20a), `t₄ = t₀ = −c/256` |
//! | `Cubic` (C₈H₈-like) | 8, on the cube diagonals | `−(9c/4096)(|J|⁴ + T⁽²²⁾)` | (6.8.20b), `t₂₂ = −9c/4096` |
//! | `Tetrahedral` (CF₄-like) | 4, alternate cube corners | `−(9c/512)(|J|⁴ + T⁽²²⁾)` | (6.8.20b), `t₂₂ = −9c/512` |
//!
//! Radial stretching alone lowers the energy most for rotation about the axes that stretch the
//! most springs: the octahedron's energy valleys are at the `(100)` axes, the cube's and the
//! tetrahedron's at `(111)`. The seed's SF₆ and C₈H₈ surfaces (Fig. 6.8.4) have the opposite
//! topography because there the bending bonds are the soft ones; bending is not modelled here.
//!
//! # Using the coefficients
//! [`BodyHamiltonian`] takes the rigid part (the rest inertia) and one anisotropic [`Quartic`]
//! term; the isotropic `t|J|⁴` has no place there. It is a Casimir: it leaves the body momentum
//! `J(t)` unchanged, adds the constant `t|J|⁴` to the energy, and turns the attitude about `J` at
//! the rate `4t|J|³`. That flow commutes with every body Hamiltonian, so the exact state is the
//! state of the [`Gyrostat`](crate::dynamics::Gyrostat) of that [`BodyHamiltonian`] followed by
//! [`SemiRigidRotor::isotropic_turn`]:
//!
//! ```
//! use gyrostat::dynamics::semi_rigid::{Arrangement, SemiRigidRotor};
//! use gyrostat::dynamics::{Gyrostat, Integrator, State};
//! use gyrostat::{UnitQuat, Vec3};
//!
//! // Six 1 kg masses at 0.5 m on springs of 20 rad/s: an octahedral rotor.
//! let rotor = SemiRigidRotor::try_symmetric(Arrangement::Octahedral, 1.0f64, 20.0, 0.5)?;
//! let basis = Arrangement::Octahedral.natural_basis();
//! let h = rotor.try_body_hamiltonian(basis)?; // rest inertia + Quartic::Octahedral(t₄)
//! let body = Gyrostat::from(h);
//! let mut s = State::new(UnitQuat::IDENTITY, Vec3::new(0.3, 0.2, 0.1));
//! let dt = 0.01;
//! for _ in 0..100 {
//!     s = body.step(Integrator::Yoshida4, &s, dt)?;
//! }
//! // The full semi-rigid state at t = 1 s: add the isotropic turn; the energy likewise.
//! let attitude = s.attitude * rotor.isotropic_turn(basis, s.momentum, 100.0 * dt)?;
//! let j2 = s.momentum.norm_squared();
//! let energy = h.energy(s.momentum) + rotor.isotropic(basis) * j2 * j2;
//! assert!((energy - rotor.energy(s.momentum)?).abs() < 1e-15);
//! # let _ = attitude;
//! # Ok::<(), gyrostat::Error>(())
//! ```

use crate::dynamics::hamiltonian::{BodyHamiltonian, Quartic};
use crate::dynamics::inertia::Inertia;
use crate::dynamics::mass::inertia_from_point_masses;
use crate::{Error, Mat3, Real, UnitQuat, Vec3};

fn finite<T: Real>(xs: &[T]) -> Result<(), Error> {
    if xs.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

fn positive<T: Real>(xs: &[T]) -> Result<(), Error> {
    finite(xs)?;
    if xs.iter().all(|x| *x > T::ZERO) {
        Ok(())
    } else {
        Err(Error::InvalidArgument)
    }
}

/// `true` for a finite value at least the type's smallest normal number in magnitude: a derived
/// constant that keeps its relative precision (a subnormal one has lost digits, and products
/// and quotients with it lose more).
fn normal<T: Real>(x: T) -> bool {
    let min = if T::EPSILON.to_f64() > 1e-10 {
        T::from_f64(f64::from(f32::MIN_POSITIVE))
    } else {
        T::from_f64(f64::MIN_POSITIVE)
    };
    x.is_finite() && x.abs() >= min
}

/// A result computed from finite input: [`Error::InvalidArgument`] if it overflowed (an input
/// outside the documented domain of magnitudes, see the module docs).
fn representable<T: Real>(x: T) -> Result<T, Error> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(Error::InvalidArgument)
    }
}

/// One centrifugal-stretch mode of a rotor (6.8.13)–(6.8.15): a stretch coordinate `r` of mass
/// `m` held by a spring of frequency `ω_v`, on which the inverse inertia `μ = 1/I` depends with
/// slope `∂μ/∂r` at rest.
///
/// # Invariant
/// `m > 0`, `ω_v > 0`, `∂μ/∂r` finite, with the stiffness `mω_v²` positive and finite and the
/// quartic coefficient `(∂μ/∂r)²/(8mω_v²)` finite; built by [`StretchMode::try_new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StretchMode<T> {
    mass: T,
    omega_v: T,
    dmu_dr: T,
}

impl<T: Real> StretchMode<T> {
    /// A mode of mass `mass`, spring frequency `omega_v` (rad/s) and inverse-inertia slope
    /// `dmu_dr` (`∂μ/∂r`, 1/(kg m³) for a radius).
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] unless `mass > 0` and `omega_v > 0`, or
    /// when the stiffness or the quartic coefficient is not representable (overflows, or the
    /// stiffness underflows to zero).
    pub fn try_new(mass: T, omega_v: T, dmu_dr: T) -> Result<Self, Error> {
        finite(&[dmu_dr])?;
        positive(&[mass, omega_v])?;
        let mode = Self {
            mass,
            omega_v,
            dmu_dr,
        };
        mode.check()?;
        Ok(mode)
    }

    /// The invariant's representability: a positive finite stiffness, a finite quartic
    /// coefficient.
    fn check(&self) -> Result<(), Error> {
        let k = self.stiffness();
        if k > T::ZERO && k.is_finite() && self.quartic_coefficient().is_finite() {
            Ok(())
        } else {
            Err(Error::InvalidArgument)
        }
    }

    /// The mass `m` of the stretch coordinate.
    #[inline]
    pub fn mass(&self) -> T {
        self.mass
    }

    /// The spring frequency `ω_v`, rad/s.
    #[inline]
    pub fn omega_v(&self) -> T {
        self.omega_v
    }

    /// The slope `∂μ/∂r` of the inverse inertia.
    #[inline]
    pub fn dmu_dr(&self) -> T {
        self.dmu_dr
    }

    /// The spring stiffness `k = mω_v²`.
    #[inline]
    pub fn stiffness(&self) -> T {
        self.mass * self.omega_v * self.omega_v
    }

    /// The stretch at momentum `j`, to first order in `J²`: `d = −J²(∂μ/∂r)/(2mω_v²)` (6.8.13,
    /// with the sign of its own equilibrium condition; see the module docs).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `j`; [`Error::InvalidArgument`] when the stretch
    /// overflows the type (likewise for the other functions of this type).
    pub fn stretch(&self, j: T) -> Result<T, Error> {
        finite(&[j])?;
        representable(-j * j * self.dmu_dr / (T::TWO * self.stiffness()))
    }

    /// The inverse inertia of the stretched rotor, `μ ≈ μ₀ + (∂μ/∂r)·d` (6.8.14a).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite input.
    pub fn stretched_inverse_inertia(&self, mu0: T, j: T) -> Result<T, Error> {
        finite(&[mu0])?;
        representable(mu0 + self.dmu_dr * self.stretch(j)?)
    }

    /// The quartic coefficient of the effective energy, `−(∂μ/∂r)²/(8mω_v²)` (6.8.15): the
    /// `t` in `E = ½μ₀J² + tJ⁴`.
    #[inline]
    pub fn quartic_coefficient(&self) -> T {
        -self.dmu_dr * self.dmu_dr / (T::from_f64(8.0) * self.stiffness())
    }

    /// The spring energy at the stretched equilibrium, `½mω_v²d²`: the energy the rotor loses by
    /// stretching (6.8.15), `−tJ⁴`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `j`.
    pub fn stretch_energy(&self, j: T) -> Result<T, Error> {
        let d = self.stretch(j)?;
        representable(T::HALF * self.stiffness() * d * d)
    }

    /// The effective (vibrationless, `p_v = 0`) energy at momentum `j` for rest inverse inertia
    /// `mu0`: `E = ½μ₀J² − J⁴(∂μ/∂r)²/(8mω_v²)` (6.8.15); the error is `O(J⁶)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite input.
    pub fn effective_energy(&self, mu0: T, j: T) -> Result<T, Error> {
        finite(&[mu0, j])?;
        let j2 = j * j;
        representable(T::HALF * mu0 * j2 + self.quartic_coefficient() * j2 * j2)
    }
}

/// Newton iterations allowed for [`SpringRotor::equilibrium_radius`]. From its starting point
/// (a lower bound of the root within `1 + √|b|` of it, see there) the iterates increase
/// monotonically to the root with quadratic convergence from the start: a handful are used; a
/// run that does not converge within the cap is an error, never an `Ok`.
pub const EQUILIBRIUM_MAX_ITERATIONS: usize = 64;

/// The seed's spring-mass rotor (Fig. 6.8.3, (6.8.11)–(6.8.15)): a mass `m` on a spring of
/// frequency `ω_v` and rest radius `r₀`, turning in a plane with angular momentum `J`; inertia
/// `I = mr² = 1/μ`.
///
/// # Invariant
/// `m, ω_v, r₀ > 0` and finite, with `1/(mr₀²)` and the stretch mode ([`SpringRotor::mode`])
/// representable; built by [`SpringRotor::try_new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpringRotor<T> {
    mass: T,
    omega_v: T,
    rest_radius: T,
}

impl<T: Real> SpringRotor<T> {
    /// A rotor of mass `mass` (kg), spring frequency `omega_v` (rad/s) and rest radius
    /// `rest_radius` (m).
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] unless all three are positive, or when
    /// a derived constant — the rest inverse inertia `1/(mr₀²)`, the slope `∂μ/∂r`, `ω_v²`, the
    /// stiffness `mω_v²`, the quartic coefficient — overflows or underflows below the type's
    /// smallest normal number (magnitudes near the ends of the type's range: every method's
    /// result is then computed from full-precision constants).
    pub fn try_new(mass: T, omega_v: T, rest_radius: T) -> Result<Self, Error> {
        positive(&[mass, omega_v, rest_radius])?;
        let rotor = Self {
            mass,
            omega_v,
            rest_radius,
        };
        let mode = rotor.mode();
        if !(normal(rotor.rest_inverse_inertia())
            && normal(mode.dmu_dr)
            && normal(omega_v * omega_v)
            && normal(mode.stiffness()))
        {
            return Err(Error::InvalidArgument);
        }
        mode.check()?;
        Ok(rotor)
    }

    /// The mass `m`, kg.
    #[inline]
    pub fn mass(&self) -> T {
        self.mass
    }

    /// The spring frequency `ω_v`, rad/s.
    #[inline]
    pub fn omega_v(&self) -> T {
        self.omega_v
    }

    /// The rest radius `r₀`, m.
    #[inline]
    pub fn rest_radius(&self) -> T {
        self.rest_radius
    }

    /// The rest inverse inertia `μ₀ = 1/(mr₀²)`.
    #[inline]
    pub fn rest_inverse_inertia(&self) -> T {
        T::ONE / (self.mass * self.rest_radius * self.rest_radius)
    }

    /// The stretch mode: `∂μ/∂r = −2/(mr₀³)` at rest.
    pub fn mode(&self) -> StretchMode<T> {
        let r0 = self.rest_radius;
        StretchMode {
            mass: self.mass,
            omega_v: self.omega_v,
            dmu_dr: -T::TWO / (self.mass * r0 * r0 * r0),
        }
    }

    /// The energy (6.8.11) `E = p_v²/2m + ½mω_v²(r − r₀)² + J²/(2mr²)` at radius `radius`,
    /// radial momentum `p_v` and angular momentum `j`.
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] for `radius ≤ 0`.
    pub fn energy(&self, radius: T, p_v: T, j: T) -> Result<T, Error> {
        finite(&[p_v, j])?;
        positive(&[radius])?;
        let (m, w) = (self.mass, self.omega_v);
        let d = radius - self.rest_radius;
        representable(
            p_v * p_v / (T::TWO * m)
                + T::HALF * m * w * w * d * d
                + j * j / (T::TWO * m * radius * radius),
        )
    }

    /// The centrifugal equilibrium radius at turning rate `ω_J` (6.8.12):
    /// `r = r₀ω_v²/(ω_v² − ω_J²)`, where the spring force `mω_v²(r − r₀)` balances the
    /// centrifugal force `mω_J²r`. Computed as `r₀/(1 − x²)` with `x = ω_J/ω_v`: no square of a
    /// rate (which under- or overflows at the ends of the range), and `r ≥ r₀` always (the
    /// denominator is at most 1 and rounding is monotonic).
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] for `|ω_J| ≥ ω_v` (no equilibrium: the
    /// radius "blows up") or a radius that overflows.
    pub fn stretched_radius(&self, omega_j: T) -> Result<T, Error> {
        finite(&[omega_j])?;
        let x = omega_j / self.omega_v;
        let denom = T::ONE - x * x;
        if denom <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
        representable(self.rest_radius / denom)
    }

    /// The exact equilibrium radius at angular momentum `j`: the root `r ≥ r₀` of
    /// `mω_v²(r − r₀) = J²/(mr³)`, i.e. (6.8.12) with the rate `ω_J = J/(mr²)` of that radius.
    ///
    /// Solved in the stretch ratio `x = r/r₀`: `x − 1 = b²/x³` with `b = J/(mω_v r₀²)`. The
    /// balance `g(x) = x − 1 − b²/x³` is increasing and concave, and its root lies in
    /// `[max(1, √|b|), 1 + √|b|]` (`x⁴ > x³(x − 1) = b²`), so Newton's iteration from
    /// `max(1, √|b|)` increases monotonically to the root and converges quadratically from the
    /// start (a few steps; at most [`EQUILIBRIUM_MAX_ITERATIONS`]). `b²/x³` is formed as
    /// `(b/x²)(b/x)`, which does not overflow. The `Ok` value satisfies the equation: the
    /// residual `|x − 1 − b²/x³|` is checked to be at most `16ε·x` before it is returned.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `j`, or when `b` or the radius overflows;
    /// [`Error::NotConverged`] if the iteration does not reach the residual bound.
    pub fn equilibrium_radius(&self, j: T) -> Result<T, Error> {
        finite(&[j])?;
        let r0 = self.rest_radius;
        // b = J·μ₀/ω_v from the normal constant μ₀ = 1/(mr₀²) (a chain of divisions by m, ω_v,
        // r₀ can pass through a subnormal and lose b's digits); the other order if J·μ₀
        // overflows or underflows.
        let mu0 = self.rest_inverse_inertia();
        let b = (j * mu0) / self.omega_v;
        let b = if b.is_finite() && (b != T::ZERO || j == T::ZERO) && normal(j * mu0) {
            b
        } else {
            (j / self.omega_v) * mu0
        };
        if !b.is_finite() {
            return Err(Error::NonFinite);
        }
        let excess = |x: T| (b / (x * x)) * (b / x);
        let three = T::from_f64(3.0);
        let mut x = T::ONE.max(b.abs().sqrt());
        let mut converged = false;
        for _ in 0..EQUILIBRIUM_MAX_ITERATIONS {
            let t = excess(x);
            let step = (x - T::ONE - t) / (T::ONE + three * t / x);
            if !step.is_finite() {
                break;
            }
            x -= step;
            if step.abs() <= T::from_f64(4.0) * T::EPSILON * x {
                converged = true;
                break;
            }
        }
        let residual = (x - T::ONE - excess(x)).abs();
        let satisfied = converged && residual <= T::from_f64(16.0) * T::EPSILON * x;
        if !satisfied {
            return Err(Error::NotConverged);
        }
        let r = r0 * x;
        if r.is_finite() {
            Ok(r)
        } else {
            Err(Error::NonFinite)
        }
    }

    /// The effective energy at momentum `j` to order `J⁴` (6.8.15):
    /// `½μ₀J² − J⁴/(2m³ω_v²r₀⁶)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `j`.
    pub fn effective_energy(&self, j: T) -> Result<T, Error> {
        self.mode().effective_energy(self.rest_inverse_inertia(), j)
    }
}

/// The symmetric arrangements of equal masses of [`SemiRigidRotor::try_symmetric`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Arrangement {
    /// Six masses on `±x, ±y, ±z` (SF₆-like): octahedral quartic (6.8.20a).
    Octahedral,
    /// Eight masses on the cube diagonals `(±1, ±1, ±1)/√3` (C₈H₈-like): cubic quartic (6.8.20b).
    Cubic,
    /// Four masses on alternate cube corners `(1,1,1), (1,−1,−1), (−1,1,−1), (−1,−1,1)` over `√3`
    /// (CF₄-like): cubic quartic (6.8.20b).
    Tetrahedral,
}

impl Arrangement {
    /// The basis in which the arrangement's quartic is a single seed term: octahedral for the
    /// octahedron, cubic for the cube and the tetrahedron (see the module table).
    pub fn natural_basis(self) -> QuarticBasis {
        match self {
            Arrangement::Octahedral => QuarticBasis::Octahedral,
            Arrangement::Cubic | Arrangement::Tetrahedral => QuarticBasis::Cubic,
        }
    }
}

/// Which anisotropic polynomial of (6.8.20) carries the quartic's anisotropy; the rest is the
/// isotropic `t|J|⁴`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QuarticBasis {
    /// `t₄(J₁⁴ + J₂⁴ + J₃⁴) + t₀|J|⁴` (6.8.20a).
    Octahedral,
    /// `t₂₂(J₁²J₂² + J₁²J₃² + J₂²J₃²) + (t₀ + t₄)|J|⁴`, `t₂₂ = −2t₄` (6.8.20b), (6.8.19).
    Cubic,
}

/// Allowed deviation from cubic symmetry of a radial-spring quartic, in units of machine
/// epsilon times its largest coefficient; also bounds the rest tensor's off-diagonal entries
/// (relative to its trace).
///
/// Why: the coefficients of an exactly symmetric arrangement differ only by rounding — each is a
/// sum over masses of products of about ten rounded factors (the directions, `μ₀`, `∂I/∂r`),
/// a few tens of ulp. 1024 ulp (1.2e-4 in f32, 2.3e-13 in f64) accepts that with margin and
/// rejects an arrangement that is not cubic (one mass moved by 1e-3 of its radius).
pub const CUBIC_SYMMETRY_TOLERANCE_EPS: f64 = 1024.0;

/// A semi-rigid rotor: point masses on radial springs (6.8.16)–(6.8.18), reduced at fixed body
/// momentum to the rest inertia plus the quartic `t₀|J|⁴ + t₄(J₁⁴ + J₂⁴ + J₃⁴)` (6.8.19),
/// (6.8.20). See the module docs for the model, the table of arrangements and how to simulate it.
///
/// # Invariant
/// The rest inertia is physical and diagonal; `t₀`, `t₄` are finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SemiRigidRotor<T> {
    rest_inertia: Inertia<T>,
    t0: T,
    t4: T,
}

/// `(∂μ/∂r_j, 1/(8 m_j ω_v²))` of one mass at rest position `r` (see the module docs).
fn mode_of<T: Real>(mu0: &Mat3<T>, mass: T, r: Vec3<T>, omega_v: T) -> Result<(Mat3<T>, T), Error> {
    let rho = r.norm();
    let n = r.try_normalize()?;
    let nn = Mat3::from_rows(
        [n.x * n.x, n.x * n.y, n.x * n.z],
        [n.y * n.x, n.y * n.y, n.y * n.z],
        [n.z * n.x, n.z * n.y, n.z * n.z],
    );
    let di = (Mat3::IDENTITY - nn).scale(T::TWO * mass * rho);
    let dmu = -(*mu0 * di * *mu0);
    let weight = T::ONE / (T::from_f64(8.0) * mass * omega_v * omega_v);
    Ok((dmu, weight))
}

fn check_masses<T: Real>(masses: &[(T, Vec3<T>)], omega_v: T) -> Result<(), Error> {
    positive(&[omega_v])?;
    if masses.is_empty() {
        return Err(Error::InvalidArgument);
    }
    for (m, r) in masses {
        finite(&[*m])?;
        r.try_finite()?;
        if *m <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
    }
    Ok(())
}

/// The rest inverse inertia `μ₀ = I₀⁻¹` of point masses.
fn rest_inverse<T: Real>(masses: &[(T, Vec3<T>)]) -> Result<(Mat3<T>, Mat3<T>), Error> {
    let i0 = inertia_from_point_masses(masses)?;
    Ok((i0, i0.try_inverse()?))
}

impl<T: Real> SemiRigidRotor<T> {
    /// The rotor of point masses `(m_j, r_j)` (rest positions in the body frame, about the
    /// centre of mass), each on its own radial spring of frequency `omega_v`: rest inertia
    /// `I₀ = Σ m_j[(r_j·r_j)1 − r_j r_jᵀ]` (6.5.4) and the quartic of (6.8.18).
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] for an empty slice, a mass `≤ 0`,
    /// `omega_v ≤ 0`, or an arrangement whose quartic is not of the form (6.8.20) on the body
    /// axes (not cubic-symmetric about them within [`CUBIC_SYMMETRY_TOLERANCE_EPS`], or a rest
    /// tensor that is not diagonal); [`Error::ZeroNorm`] for a mass at the origin (no radial
    /// direction); [`Error::Singular`] or [`Error::NonPhysicalInertia`] for a rest inertia that
    /// is not invertible or not physical (masses on a line); [`Error::InvalidArgument`] also
    /// when a quartic coefficient overflows or is too large for [`BodyHamiltonian::try_new`]
    /// in either basis (so that [`SemiRigidRotor::try_body_hamiltonian`] cannot fail).
    pub fn try_from_radial_springs(masses: &[(T, Vec3<T>)], omega_v: T) -> Result<Self, Error> {
        check_masses(masses, omega_v)?;
        let (i0, mu0) = rest_inverse(masses)?;
        // Quartic coefficients of −Σ w (J·D·J)², D symmetric (see `coefficients`).
        let mut c = [T::ZERO; 15];
        for (m, r) in masses {
            let (d, w) = mode_of(&mu0, *m, *r, omega_v)?;
            let q = coefficients(&d);
            for (acc, x) in c.iter_mut().zip(q.iter()) {
                *acc -= w * *x;
            }
        }
        let scale = c.iter().fold(T::ZERO, |a, x| a.max(x.abs()));
        let tol = T::from_f64(CUBIC_SYMMETRY_TOLERANCE_EPS) * T::EPSILON;
        let three = T::from_f64(3.0);
        let a = (c[0] + c[1] + c[2]) / three;
        let b = (c[3] + c[4] + c[5]) / three;
        let cubic = c[..3].iter().all(|x| (*x - a).abs() <= tol * scale)
            && c[3..6].iter().all(|x| (*x - b).abs() <= tol * scale)
            && c[6..].iter().all(|x| x.abs() <= tol * scale);
        let trace = i0.trace();
        let off = i0.m[0][1].abs().max(i0.m[0][2].abs()).max(i0.m[1][2].abs());
        if !cubic || off > tol * trace {
            return Err(Error::InvalidArgument);
        }
        let rest_inertia = Inertia::try_from_principal(i0.diagonal())?;
        // a T⁽⁴⁾ + b T⁽²²⁾ = t₀|J|⁴ + t₄T⁽⁴⁾ with |J|⁴ = T⁽⁴⁾ + 2T⁽²²⁾ (6.8.19).
        let t0 = b * T::HALF;
        let t4 = a - t0;
        finite(&[t0, t4, t0 + t4])?;
        let rotor = Self {
            rest_inertia,
            t0,
            t4,
        };
        // Every basis's Hamiltonian exists (`try_body_hamiltonian` is then total): its quartic
        // coefficient, `t₄` or `−2t₄`, within `MAX/12`.
        for basis in [QuarticBasis::Octahedral, QuarticBasis::Cubic] {
            rotor
                .try_body_hamiltonian(basis)
                .map_err(|_| Error::InvalidArgument)?;
        }
        Ok(rotor)
    }

    /// The rotor of equal masses `mass` at rest radius `rest_radius` in a symmetric
    /// `arrangement`, springs of frequency `omega_v` (the module table gives the closed forms).
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::InvalidArgument`] unless `mass`, `omega_v`,
    /// `rest_radius` are positive.
    pub fn try_symmetric(
        arrangement: Arrangement,
        mass: T,
        omega_v: T,
        rest_radius: T,
    ) -> Result<Self, Error> {
        positive(&[mass, omega_v, rest_radius])?;
        let (o, p) = (T::ZERO, rest_radius);
        let d = rest_radius / T::from_f64(3.0).sqrt();
        let at = |x: T, y: T, z: T| (mass, Vec3::new(x, y, z));
        match arrangement {
            Arrangement::Octahedral => Self::try_from_radial_springs(
                &[
                    at(p, o, o),
                    at(-p, o, o),
                    at(o, p, o),
                    at(o, -p, o),
                    at(o, o, p),
                    at(o, o, -p),
                ],
                omega_v,
            ),
            Arrangement::Cubic => Self::try_from_radial_springs(
                &[
                    at(d, d, d),
                    at(d, d, -d),
                    at(d, -d, d),
                    at(d, -d, -d),
                    at(-d, d, d),
                    at(-d, d, -d),
                    at(-d, -d, d),
                    at(-d, -d, -d),
                ],
                omega_v,
            ),
            Arrangement::Tetrahedral => Self::try_from_radial_springs(
                &[at(d, d, d), at(d, -d, -d), at(-d, d, -d), at(-d, -d, d)],
                omega_v,
            ),
        }
    }

    /// The rest inertia `I₀` (the rigid part: `H₀ = ½ J·I₀⁻¹·J`).
    #[inline]
    pub fn rest_inertia(&self) -> Inertia<T> {
        self.rest_inertia
    }

    /// The octahedral coefficient `t₄` of `t₀|J|⁴ + t₄(J₁⁴ + J₂⁴ + J₃⁴)` (6.8.20a).
    #[inline]
    pub fn t4(&self) -> T {
        self.t4
    }

    /// The anisotropic term in `basis`: [`Quartic::Octahedral`]`(t₄)` or
    /// [`Quartic::Cubic`]`(−2t₄)` (6.8.19), (6.8.20).
    pub fn quartic(&self, basis: QuarticBasis) -> Quartic<T> {
        match basis {
            QuarticBasis::Octahedral => Quartic::Octahedral(self.t4),
            QuarticBasis::Cubic => Quartic::Cubic(-T::TWO * self.t4),
        }
    }

    /// The isotropic coefficient `t` of `t|J|⁴` that goes with [`SemiRigidRotor::quartic`] in
    /// `basis`: the seed's `t₀` of `H₀ = BJ² + t₀J⁴` (6.8.20): `t₀` (octahedral) or `t₀ + t₄`
    /// (cubic).
    pub fn isotropic(&self, basis: QuarticBasis) -> T {
        match basis {
            QuarticBasis::Octahedral => self.t0,
            QuarticBasis::Cubic => self.t0 + self.t4,
        }
    }

    /// The [`BodyHamiltonian`] `½ J·I₀⁻¹·J + quartic(basis)`: everything but the isotropic
    /// `t|J|⁴` (apply that with [`SemiRigidRotor::isotropic_turn`]).
    ///
    /// # Errors
    /// As [`BodyHamiltonian::try_new`] (none for a rotor built by this type's constructors).
    pub fn try_body_hamiltonian(&self, basis: QuarticBasis) -> Result<BodyHamiltonian<T>, Error> {
        BodyHamiltonian::try_new(self.rest_inertia, Vec3::ZERO, self.quartic(basis))
    }

    /// The full effective energy `½ J·I₀⁻¹·J + t₀|J|⁴ + t₄(J₁⁴ + J₂⁴ + J₃⁴)` at body momentum `j`
    /// (6.8.18)–(6.8.20); the error against the exact spring equilibrium is `O(J⁶)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `j`; [`Error::InvalidArgument`] when the energy
    /// overflows the type.
    pub fn energy(&self, j: Vec3<T>) -> Result<T, Error> {
        let j = j.try_finite()?;
        let (x2, y2, z2) = (j.x * j.x, j.y * j.y, j.z * j.z);
        let n2 = x2 + y2 + z2;
        representable(
            self.rest_inertia.energy_from_momentum(j)
                + self.t0 * n2 * n2
                + self.t4 * (x2 * x2 + y2 * y2 + z2 * z2),
        )
    }

    /// The exact flow of the isotropic term `t|J|⁴` of `basis` over `elapsed` seconds, as a
    /// body-frame turn: `exp(4t|J|²·elapsed·J)` — the rotation by `4t|J|³·elapsed` about `Ĵ`.
    ///
    /// The term is a Casimir (it Poisson-commutes with every `H(J)`), so the semi-rigid state
    /// at time `t` is the state `(q, J)` at `t` of the [`Gyrostat`](crate::dynamics::Gyrostat) of
    /// [`SemiRigidRotor::try_body_hamiltonian`], with attitude
    /// `q ⊗ isotropic_turn(basis, J, t)`, whatever the integrator and whenever it is applied.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite input; [`Error::InvalidArgument`] when the turn's
    /// angle overflows the type.
    pub fn isotropic_turn(
        &self,
        basis: QuarticBasis,
        momentum: Vec3<T>,
        elapsed: T,
    ) -> Result<UnitQuat<T>, Error> {
        finite(&[elapsed])?;
        let j = momentum.try_finite()?;
        let rate = T::from_f64(4.0) * self.isotropic(basis) * j.norm_squared();
        let phi = j.scale(rate * elapsed);
        if !phi.is_finite() {
            return Err(Error::InvalidArgument);
        }
        UnitQuat::try_exp(phi)
    }
}

/// The equilibrium shifts of the spring radii at body momentum `j` (6.8.17):
/// `δr_j = −J·(∂μ/∂r_j)·J / (2 m_j ω_v²)`, written into `out` in the order of `masses`
/// (first order in `J²`; the model of [`SemiRigidRotor::try_from_radial_springs`], any arrangement).
///
/// # Errors
/// As [`SemiRigidRotor::try_from_radial_springs`] for the masses (without the symmetry
/// requirement); [`Error::NonFinite`] for a non-finite `j`; [`Error::InvalidArgument`] if `out`
/// is shorter than `masses` or a shift overflows the type (then `out` holds the shifts
/// computed before it).
pub fn radial_stretches<T: Real>(
    masses: &[(T, Vec3<T>)],
    omega_v: T,
    j: Vec3<T>,
    out: &mut [T],
) -> Result<(), Error> {
    check_masses(masses, omega_v)?;
    let j = j.try_finite()?;
    if out.len() < masses.len() {
        return Err(Error::InvalidArgument);
    }
    let (_, mu0) = rest_inverse(masses)?;
    for ((m, r), o) in masses.iter().zip(out.iter_mut()) {
        let (d, _) = mode_of(&mu0, *m, *r, omega_v)?;
        *o = representable(-j.dot(d * j) / (T::TWO * *m * omega_v * omega_v))?;
    }
    Ok(())
}

/// The 15 coefficients of `(J·D·J)²` for symmetric `D`, in the order
/// `J₁⁴, J₂⁴, J₃⁴; J₁²J₂², J₁²J₃², J₂²J₃²; J₁³J₂, J₁J₂³, J₁³J₃, J₁J₃³, J₂³J₃, J₂J₃³;
/// J₁²J₂J₃, J₂²J₁J₃, J₃²J₁J₂`.
fn coefficients<T: Real>(d: &Mat3<T>) -> [T; 15] {
    let (a, b, c) = (d.m[0][0], d.m[1][1], d.m[2][2]);
    let (p, q, r) = (d.m[0][1], d.m[0][2], d.m[1][2]);
    let (two, four, eight) = (T::TWO, T::from_f64(4.0), T::from_f64(8.0));
    [
        a * a,
        b * b,
        c * c,
        two * a * b + four * p * p,
        two * a * c + four * q * q,
        two * b * c + four * r * r,
        four * a * p,
        four * b * p,
        four * a * q,
        four * c * q,
        four * b * r,
        four * c * r,
        four * a * r + eight * p * q,
        four * b * q + eight * p * r,
        four * c * p + eight * q * r,
    ]
}
