//! The exact torque-free rigid body: body momentum by Jacobi elliptic functions and attitude by
//! the elliptic integral of the third kind. An oracle for the integrators and a step in its own
//! right (evaluate at any `t`, no accumulation).
//!
//! # Model and conventions
//! The closed forms below are stated in the principal frame, where the inertia tensor is
//! `diag(I₁, I₂, I₃)` (any order). A body with a non-diagonal tensor is solved in its principal
//! frame and mapped back: with `P` the rotation from principal to body axes
//! ([`Inertia::principal_rotation`]), the principal-frame momentum is `P* ⊗ J ⊗ P` and attitude
//! `q ⊗ P`, and the results return by the inverse maps. For a diagonal tensor `P = 1` and no
//! mapping is done. The body angular momentum `J` obeys `J̇ = J × ω`, `ω = I⁻¹J` (seed (6.8.5), Euler's equations
//! (6.7.50)); the attitude `q` maps body to lab (crate conventions) and obeys
//! `q̇ = ½ q ⊗ (0, ω)`; the lab momentum `q J q*` is constant.
//!
//! # Body momentum (Landau & Lifshitz, *Mechanics*, §37)
//! Label the axes `(a₁, a₂, a₃)` so that `a₂` is the intermediate axis and `J` circulates around
//! `a₃`: the major axis when `J² > 2E·I_mid`, the minor one when `J² < 2E·I_mid` (Landau–Lifshitz
//! exchange the labels 1 ↔ 3 in the second case; here a sign on the `a₂` component keeps the
//! relabelled frame right-handed). With `s₁ = sign J_{a₁}(0)`, `s₃ = sign J_{a₃}(0)`:
//!
//! `J_{a₁} = s₁ A₁ cn u`, `J_{a₂} = s₁ A₂ sn u`, `J_{a₃} = s₃ A₃ dn u`, `u = λt + u₀`,
//!
//! `A₁² = I₁(2EI₃ − J²)/(I₃ − I₁)`, `A₂² = I₂(2EI₃ − J²)/(I₃ − I₂)`,
//! `A₃² = I₃(J² − 2EI₁)/(I₃ − I₁)`, `m = (I₂ − I₁)(2EI₃ − J²) / ((I₃ − I₂)(J² − 2EI₁))`,
//! `|λ| = (A₃/I₃)·√((I₃ − I₂)(I₃ − I₁)/(I₁I₂))` (Landau–Lifshitz §37; indices are
//! the relabelled ones). Every difference is evaluated from the components of `J` as a sum of
//! same-signed terms, except `J² − 2E·I₂`, the distance to the separatrix.
//!
//! # Attitude (the elliptic integral of the third kind)
//! The attitude is `q(t) = q₀ ⊗ B₀⁻¹ ⊗ R_b(ψ(t)) ⊗ B(t)` where `B(t)` is the rotation built from the
//! body direction `ĵ = J/|J|` by spherical angles about the *intermediate* axis `e_b`
//! (`θ` = polar angle of `ĵ` from `e_b`, `χ` = its azimuth, measured from `e_c₁ = e_c₂ × e_b`
//! towards `e_c₂ = s₃ e_{a₃}`): `B⁻¹ = R_b(χ) R_{c₂}(θ) [R_z(π) in that frame]`. Because `J` never
//! reaches `±e_b` off the separatrix and `ĵ·e_c₂ > 0` throughout, `θ, χ ∈ (0, π)` are continuous
//! and the quaternion is continuous in `t`. The rotation angle `ψ` about the fixed lab momentum
//! obeys `ψ̇ = (2E/|J| − |J| ĵ_b²/I_b) / (1 − ĵ_b²)` (the Euler-angle precession rate of
//! Landau–Lifshitz §37, with the intermediate axis as pole), which with
//! `ĵ_b = (A₂/|J|) sn u` integrates in closed form:
//!
//! `ψ(t) = |J| t / I_b + (C/λ) [Π(n; am u | m) − Π(n; am u₀ | m)]`, `n = A₂²/J² < 1`,
//! `C = 2E/|J| − |J|/I_b`,
//!
//! with `Π` the incomplete elliptic integral of the third kind, evaluated by Carlson's `R_F`,
//! `R_J` ([`super::elliptic::incomplete_pi`]). Celledoni, Fassò, Säfström & Zanna ("The exact
//! computation of the free rigid body motion and its use in splitting methods", SIAM J. Sci.
//! Comput. 30(4), 2008) discuss both closed forms of this angle, the elliptic integral of the
//! third kind and Jacobi's theta functions; this module uses the former. Choosing the intermediate axis as pole
//! keeps `n` in `[0, 1)`, with no cancellation near the stable axes (where spin-stabilised
//! craft live).
//!
//! # Special cases (typed, never NaN)
//! - **Sphere** (`I₁ = I₂ = I₃`): `J` constant, `q(t) = q₀ ⊗ exp(ω t)`.
//! - **Symmetric top** (two equal moments): `J` precesses about the symmetry axis `e_s` at
//!   `−Ω_b`, `Ω_b = (1/I_s − 1/I_⊥) J_s` (the seed's body rate `γ̇`, (6.7.39)), and
//!   `q(t) = q₀ ⊗ R(ĵ₀, |J| t/I_⊥) ⊗ R(e_s, Ω_b t)` (lab rate `α̇ = J/I_⊥`, (6.7.43a)).
//! - **Stationary** (`J` along a principal axis, including the unstable intermediate one): `J`
//!   and `ω` constant.
//! - **Separatrix** (`|J² − 2E·I_mid| ≤` [`SEPARATRIX_TOLERANCE`]`·J²`): the `m → 1` limit,
//!   `sn → tanh`, `cn, dn → sech`, and `C = 0` so `ψ = |J| t / I_b`: `J` approaches the saddle
//!   on the intermediate axis asymptotically and never flips.
//!
//! Thresholds deciding these cases are named constants below.
//!
//! # Accuracy (measured)
//! Against a tiny-step RK4 integration of Euler's equations and `q̇ = ½ q ⊗ (0, ω)` over
//! `t ≤ 20` for 13 cases (all regimes, both circulation sides, permuted axes, a near-saddle
//! flip with `1 − m = 10⁻⁴`) — `cargo test --release -p host-tests --test dynamics
//! free_rigid_body:: -- --nocapture`:
//!
//! | | f64 | f32 |
//! |---|---|---|
//! | body momentum, `|ΔJ|/|J|` | 9.4e-14 | 9.4e-7 |
//! | attitude, rotation angle | 2.2e-13 rad | 3.0e-6 rad (1.9e-5 for the near-saddle flip) |
//! | `flip_interval` vs measured sign-change interval, relative | 6.5e-10 (the measurement's own resolution) | 1.0e-7 |
//!
//! The near-separatrix accuracy rests on computing `1 − m`, `1 − n` and `J² − 2E·I₂` from the
//! components (never as `1 − m`), on the complementary-angle form of `u₀` near `|φ₀| = π/2`,
//! and on `Δ² = cos²φ + m₁ sin²φ`, `1 − n sin²φ = n₁ + n cos²φ` inside `F` and `Π`.

use super::elliptic::{
    amplitude_parts, complete_k_unchecked, f_reduced, pi_complete_unchecked, pi_with_complete,
    pow2_scale, sech_tanh,
};
use crate::dynamics::inertia::Inertia;
use crate::dynamics::state::State;
use crate::step_limit::exact_step_angle_limit;
use crate::{Axis, Error, Real, UnitQuat, Vec3};

/// Two principal moments within this relative distance (`|Iₐ − I_b| ≤ tol·max`) are treated as
/// equal: 16 ulp. Beyond it the asymmetric (elliptic) solution is used and is accurate; below
/// it the asymmetry is at the rounding level of the input and the symmetric closed form is the
/// exact solution of the rounded problem.
pub const EQUAL_MOMENTS_TOLERANCE: f64 = 16.0;

/// Motion with `|J² − 2E·I_mid| ≤ SEPARATRIX_TOLERANCE · ε · (J_hi²(I_hi − I_mid)/I_hi +
/// J_lo²(I_mid − I_lo)/I_lo)` (ε the type's epsilon) is treated as lying on the separatrix
/// (`m = 1`): `J² − 2E·I_mid` is computed as the difference of those two non-negative terms, and
/// the value is the rounding budget of each (two products and a quotient, ≤ 4 ulp, doubled).
/// The budget is relative to the terms, not to `J²`: for nearly equal moments both terms are
/// tiny next to `J²`, and a tolerance on `J²` would call every such motion a separatrix.
pub const SEPARATRIX_TOLERANCE: f64 = 8.0;

/// The qualitative kind of torque-free motion, decided once by [`FreeRigidBody::try_new`]. Axes
/// are principal axes: for a diagonal tensor the body axes, otherwise the columns of
/// [`Inertia::principal_axes`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Regime {
    /// All three moments equal: rotation at constant `ω` about the fixed `J`.
    Sphere,
    /// Two moments equal: regular precession (6.7.39)–(6.7.43). `axis` is the principal axis
    /// of the distinct (symmetry) moment.
    SymmetricTop {
        /// The symmetry axis.
        axis: Axis,
    },
    /// `J` along a principal axis: steady rotation about `axis`.
    Stationary {
        /// The rotation axis.
        axis: Axis,
    },
    /// Asymmetric top, `J` circulating around the principal axis `axis` (the major or minor
    /// axis) with parameter `m ∈ [0, 1)`.
    Circulating {
        /// The axis `J` circulates around.
        axis: Axis,
    },
    /// Asymmetric top exactly on the separatrix (`m = 1`): `J` tends to the intermediate axis.
    Separatrix,
}

/// Data of the asymmetric (elliptic or separatrix) motion.
#[derive(Clone, Copy, Debug)]
struct Asymmetric<T> {
    /// Axes `(a₁, a₂, a₃)`: `a₂` intermediate, `a₃` the axis circulated.
    idx: [Axis; 3],
    /// `s₁ A₁`, `s₁ A₂`, `s₃ A₃`: signed amplitudes.
    amp: [T; 3],
    m: T,
    m1: T,
    /// `λ` (signed).
    lambda: T,
    u0: T,
    separatrix: bool,
    /// `K(m)` (unused on the separatrix).
    kc: T,
    /// `n = A₂²/J²`.
    n: T,
    /// `1 − n`, computed without cancellation.
    n1: T,
    /// `C/λ`.
    c_over_lambda: T,
    /// `|J|/I_b`.
    psi_rate: T,
    /// `Π(n|m)` complete.
    pi_complete: T,
    /// `Π(n; am u₀|m)`.
    pi0: T,
    /// Intermediate axis `e_b` and `e_c₂ = s₃ e_{a₃}` (body frame).
    e_b: Vec3<T>,
    e_c2: Vec3<T>,
    /// `q₀ ⊗ R_b(χ₀) ⊗ R_{c₂}(θ₀)`.
    g0: UnitQuat<T>,
}

#[derive(Clone, Copy, Debug)]
enum Motion<T> {
    /// Constant `J`; attitude `q₀ ⊗ R(ĵ₀, rate·t)`.
    Steady {
        rate: T,
    },
    /// Symmetric top.
    Symmetric {
        e_s: Vec3<T>,
        /// `|J|/I_⊥`.
        lab_rate: T,
        /// `Ω_b`.
        body_rate: T,
    },
    Asymmetric(Asymmetric<T>),
}

/// The exact torque-free motion of a rigid body, evaluated in closed form at any time.
///
/// ```
/// use gyrostat::dynamics::{FreeRigidBody, Inertia, State};
/// use gyrostat::{UnitQuat, Vec3};
/// // A box spun near its intermediate axis: the Dzhanibekov flip.
/// let inertia = Inertia::try_from_principal(Vec3::new(1.0f64, 2.0, 3.0))?;
/// let start = State::new(UnitQuat::IDENTITY, Vec3::new(0.01, 2.0, 0.01));
/// let body = FreeRigidBody::try_new(&inertia, &start)?;
/// let half = body.flip_interval().unwrap();
/// let s = body.try_state_at(half)?;
/// assert!(s.momentum.y < -1.9); // J has flipped to the other end of the intermediate axis
/// // The lab momentum is unchanged.
/// let j_lab = s.attitude.rotate(s.momentum);
/// assert!((j_lab - Vec3::new(0.01, 2.0, 0.01)).norm() < 1e-9);
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FreeRigidBody<T> {
    moments: Vec3<T>,
    /// `P`, principal → body; `None` for a diagonal tensor (`P = 1`).
    principal: Option<UnitQuat<T>>,
    /// Initial momentum divided by `j_scale`, principal frame.
    j0: Vec3<T>,
    /// `|j0|` (in `[1, 2)`).
    j0_norm: T,
    /// Initial attitude of the principal frame, `q₀ ⊗ P`.
    q0: UnitQuat<T>,
    j_norm: T,
    energy: T,
    /// The power of two `s_J` near `|J₀|` by which the momentum is divided.
    j_scale: T,
    /// `s_J/s_I` (rad/s), `s_I` the power of two near `I_max` by which the moments are divided:
    /// the motion is solved for those scaled moments and momenta (of order one, so that no
    /// product of moments or momenta can overflow or underflow; the scaling by powers of two is
    /// exact and changes no digit), whose rates are in units of this scale; time enters as
    /// `t·rate_scale`.
    rate_scale: T,
    /// `max(|λ|, ψ̇, …)` of the normalised motion: the fastest phase, for the precision limit of
    /// [`FreeRigidBody::try_state_at`].
    max_rate: T,
    regime: Regime,
    motion: Motion<T>,
}

fn sign<T: Real>(x: T) -> T {
    if x < T::ZERO { -T::ONE } else { T::ONE }
}

impl<T: Real> FreeRigidBody<T> {
    /// Sets up the motion of a body with inertia `inertia` from its initial state (attitude
    /// body → lab, body momentum).
    ///
    /// The motion is solved for the moments divided by the largest one and the momentum divided
    /// by its norm, so that the closed forms' products of moments and momenta stay of order one
    /// for bodies and momenta anywhere in the type's range. Domain: a state whose body rate
    /// `I⁻¹J` and energy `½ J·I⁻¹J` are representable.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite state; [`Error::ZeroNorm`] for `J = 0`;
    /// [`Error::InvalidArgument`] for a state outside the domain (rates or energy overflow).
    pub fn try_new(inertia: &Inertia<T>, initial: &State<T>) -> Result<Self, Error> {
        let (q0, j0) = (initial.attitude, initial.momentum);
        if !j0.is_finite() || !q0.as_quat().is_finite() {
            return Err(Error::NonFinite);
        }
        let principal = if inertia.is_diagonal() {
            None
        } else {
            Some(inertia.principal_rotation())
        };
        let (q0, j0) = match principal {
            None => (q0, j0),
            Some(p) => (q0 * p, p.inverse_rotate(j0)),
        };
        Self::in_principal_frame(inertia.principal_moments(), j0, q0, principal)
    }

    /// The motion from principal moments (validated by [`Inertia`]) and the initial momentum and
    /// attitude of the principal frame.
    fn in_principal_frame(
        i: Vec3<T>,
        j0_body: Vec3<T>,
        q0: UnitQuat<T>,
        principal: Option<UnitQuat<T>>,
    ) -> Result<Self, Error> {
        let j_norm = j0_body.norm();
        if j_norm <= T::ZERO {
            return Err(Error::ZeroNorm);
        }
        let omega = Vec3::new(j0_body.x / i.x, j0_body.y / i.y, j0_body.z / i.z);
        let energy = T::HALF * j0_body.dot(omega);
        if !(j_norm.is_finite() && energy.is_finite() && omega.is_finite()) {
            return Err(Error::InvalidArgument);
        }
        let i_scale = pow2_scale(i.x.max(i.y).max(i.z));
        let j_scale = pow2_scale(j_norm);
        let rate_scale = j_scale / i_scale;
        let (true_moments, true_j_norm, true_energy) = (i, j_norm, energy);
        // The scaled problem (exact: powers of two): largest moment and |J| in [1, 2), rates in
        // units of `rate_scale`.
        let i = i / i_scale;
        let j0_body = j0_body / j_scale;
        let j_norm = j0_body.norm();
        let omega = Vec3::new(j0_body.x / i.x, j0_body.y / i.y, j0_body.z / i.z);
        if !(omega.is_finite() && rate_scale.is_finite() && rate_scale > T::ZERO) {
            return Err(Error::InvalidArgument);
        }

        // Sort the axes by moment: lo, mid, hi (a 3-element network; no slice sort, whose
        // total-order check has a panic path).
        let (mut lo, mut mid, mut hi) = (Axis::X, Axis::Y, Axis::Z);
        if i[mid] < i[lo] {
            core::mem::swap(&mut lo, &mut mid);
        }
        if i[hi] < i[mid] {
            core::mem::swap(&mut mid, &mut hi);
        }
        if i[mid] < i[lo] {
            core::mem::swap(&mut lo, &mut mid);
        }
        let (i_lo, i_mid, i_hi) = (i[lo], i[mid], i[hi]);
        let eq_tol = T::from_f64(EQUAL_MOMENTS_TOLERANCE) * T::EPSILON;
        let lo_eq_mid = i_mid - i_lo <= eq_tol * i_mid;
        let mid_eq_hi = i_hi - i_mid <= eq_tol * i_hi;

        let rate = omega.norm();
        let mut this = Self {
            moments: true_moments,
            principal,
            j0: j0_body,
            j0_norm: j_norm,
            q0,
            j_norm: true_j_norm,
            energy: true_energy,
            j_scale,
            rate_scale,
            max_rate: rate,
            regime: Regime::Sphere,
            motion: Motion::Steady { rate },
        };
        if lo_eq_mid && mid_eq_hi {
            return Ok(this);
        }
        // Stationary: J exactly along one principal axis.
        for ax in Axis::ALL {
            let others = j0_body[ax.next()] == T::ZERO && j0_body[ax.next().next()] == T::ZERO;
            if others {
                this.regime = Regime::Stationary { axis: ax };
                return Ok(this);
            }
        }
        if lo_eq_mid || mid_eq_hi {
            let (ax, i_s, i_p) = if lo_eq_mid {
                (hi, i_hi, (i_lo + i_mid) * T::HALF)
            } else {
                (lo, i_lo, (i_mid + i_hi) * T::HALF)
            };
            let e_s = Vec3::unit(ax);
            let j_s = j0_body[ax];
            this.regime = Regime::SymmetricTop { axis: ax };
            let (lab_rate, body_rate) = (j_norm / i_p, j_s * (T::ONE / i_s - T::ONE / i_p));
            this.max_rate = lab_rate.max(body_rate.abs());
            this.motion = Motion::Symmetric {
                e_s,
                lab_rate,
                body_rate,
            };
            return Ok(this);
        }

        // Asymmetric top. d = J² − 2E·I_mid from the components, as the difference of two
        // non-negative terms; the moment differences are exact (Sterbenz) for moments within a
        // factor 2 of each other, so d is known to the rounding of those terms.
        let j_lo = j0_body[lo];
        let j_hi = j0_body[hi];
        let term_hi = j_hi * j_hi * ((i_hi - i_mid) / i_hi);
        let term_lo = j_lo * j_lo * ((i_mid - i_lo) / i_lo);
        let d = term_hi - term_lo;
        let j2 = j_norm * j_norm;
        let sep_tol = T::from_f64(SEPARATRIX_TOLERANCE) * T::EPSILON * (term_hi + term_lo);
        let separatrix = d.abs() <= sep_tol;
        let (a1, a3) = if d >= T::ZERO { (lo, hi) } else { (hi, lo) };
        if separatrix && (j0_body[a1] == T::ZERO || j0_body[a3] == T::ZERO) {
            // On the separatrix with J₁ = 0 or J₃ = 0 means at the saddle (within rounding).
            this.regime = Regime::Stationary { axis: mid };
            return Ok(this);
        }
        let a2 = mid;
        let e1 = Vec3::unit(a1);
        let e2 = Vec3::unit(a2);
        let e3 = Vec3::unit(a3);
        let (i1, i2, i3) = (i[a1], i[a2], i[a3]);
        // The relabelled frame (e_{a₁}, h·e_{a₂}, e_{a₃}) is right-handed: h = ±1.
        let h = sign(e1.cross(e2).dot(e3));
        // Components in that frame, where J̇ = J × ω keeps the cyclic form of (6.8.5d).
        let (jj1, jj2, jj3) = (j0_body[a1], h * j0_body[a2], j0_body[a3]);
        // Same-signed ratios in both labelings.
        let r21 = (i3 - i2) / (i3 - i1); // ∈ (0, 1)
        let r31 = (i2 - i1) / (i3 - i1); // ∈ (0, 1)
        let amp1_sq = jj1 * jj1 + jj2 * jj2 * (i1 / i2) * r21;
        let amp2_sq = jj1 * jj1 * (i2 / i1) / r21 + jj2 * jj2;
        let amp3_sq = jj3 * jj3 + jj2 * jj2 * (i3 / i2) * r31;
        let (amp1, amp2, amp3) = (amp1_sq.sqrt(), amp2_sq.sqrt(), amp3_sq.sqrt());
        let s1 = sign(jj1);
        let s3 = sign(jj3);
        // λ = s₃ sign(I₃ − I₂) (A₃/I₃) √((I₃ − I₂)(I₃ − I₁)/(I₁ I₂))
        let lam_mag = amp3 / i3 * ((i3 - i2) * (i3 - i1) / (i1 * i2)).abs().sqrt();
        let lambda = s3 * sign(i3 - i2) * lam_mag;
        // m = ρ A₁²/A₃², m₁ = d·I₃ / ((I₃ − I₂) A₃²)
        let rho = i3 * (i2 - i1) / (i1 * (i3 - i2));
        let (m, m1) = if separatrix {
            (T::ONE, T::ZERO)
        } else {
            let m = (rho * amp1_sq / amp3_sq).max(T::ZERO).min(T::ONE);
            let m1 = (d * i3 / ((i3 - i2) * amp3_sq)).max(T::ZERO).min(T::ONE);
            (m, m1)
        };
        if !(amp1 > T::ZERO && amp2 > T::ZERO) {
            // The components off the circulation axis underflowed in their squares: J is on
            // the a₃ axis to the type's resolution.
            this.regime = Regime::Stationary { axis: a3 };
            this.motion = Motion::Steady { rate };
            this.max_rate = rate;
            return Ok(this);
        }
        // Initial phase: cn u₀ = |J₁|/A₁, sn u₀ = s₁ J₂/A₂ ⇒ φ₀ ∈ [−π/2, π/2] (the ratios, not
        // the products J₂A₁ and J₁A₂, which underflow together for J near the a₃ axis).
        let sn_scaled = s1 * (jj2 / amp2); // sin φ₀
        let cn_scaled = jj1.abs() / amp1; // cos φ₀ ≥ 0
        let phi0 = sn_scaled.atan2(cn_scaled);
        let (u0, kc) = if separatrix {
            // u₀ = atanh(sin φ₀) = sign·ln((1 + |sin φ₀|)/cos φ₀)
            let h = sn_scaled.hypot(cn_scaled);
            let (sphi, cphi) = (sn_scaled / h, cn_scaled / h);
            let u0 = ((T::ONE + sphi.abs()) / cphi).ln().copysign(sphi);
            (u0, T::ZERO)
        } else {
            let kc = complete_k_unchecked(m, m1);
            // u₀ = F(φ₀|m). Near |φ₀| = π/2 with m → 1 (J near the separatrix, crossing the
            // intermediate axis region) F is ill-conditioned in φ (slope 1/dn); there use
            // F(φ₀) = K − F(φ'), tan φ' = cot φ₀ / √m₁ (from sn(K − u) = cn u/dn u, A&S §16.8),
            // whose slope is dn(φ₀)/√m₁. Pick the smaller slope: direct iff dn²(φ₀) ≥ √m₁.
            let h = sn_scaled.hypot(cn_scaled);
            let (sphi, cphi) = (sn_scaled / h, cn_scaled / h);
            let dn0_sq = cphi * cphi + m1 * sphi * sphi;
            let sqrt_m1 = m1.sqrt();
            let u0 = if dn0_sq >= sqrt_m1 {
                f_reduced(phi0, m1)
            } else {
                let phi_c = cphi.atan2(sqrt_m1 * sphi.abs());
                (kc - f_reduced(phi_c, m1)).copysign(sphi)
            };
            (u0, kc)
        };
        // Attitude data.
        // n = A₂²/J² and, accurately, n₁ = 1 − n = I₃ d / ((I₃ − I₂) J²) > 0.
        let (n, n1) = if separatrix {
            (T::ONE, T::ZERO)
        } else {
            let n1 = (d * i3 / ((i3 - i2) * j2)).max(T::EPSILON);
            ((amp2_sq / j2).min(T::ONE - n1), n1)
        };
        let c_coef = if separatrix {
            T::ZERO
        } else {
            -d / (j_norm * i2)
        };
        let c_over_lambda = c_coef / lambda;
        let (pi_complete, pi0) = if separatrix {
            (T::ZERO, T::ZERO)
        } else {
            let pc = pi_complete_unchecked(n, n1, m1);
            let (k, phi_r, _, _, _) = amplitude_parts(u0, m, m1);
            (pc, pi_with_complete(n, n1, k, phi_r, m1, pc))
        };
        let e_b = e2;
        let e_c2 = e3.scale(s3);
        let (theta0, chi0) = gauge_angles(j0_body.scale(T::ONE / j_norm), e_b, e_c2);
        let g0 = q0
            * UnitQuat::from_axis_angle_unchecked(e_b, chi0)
            * UnitQuat::from_axis_angle_unchecked(e_c2, theta0);
        this.regime = if separatrix {
            Regime::Separatrix
        } else {
            Regime::Circulating { axis: a3 }
        };
        this.max_rate = lambda.abs().max(j_norm / i2);
        this.motion = Motion::Asymmetric(Asymmetric {
            idx: [a1, a2, a3],
            amp: [s1 * amp1, h * s1 * amp2, s3 * amp3],
            m,
            m1,
            lambda,
            u0,
            separatrix,
            kc,
            n,
            n1,
            c_over_lambda,
            psi_rate: j_norm / i2,
            pi_complete,
            pi0,
            e_b,
            e_c2,
            g0,
        });
        Ok(this)
    }

    /// The regime of the motion (sphere, symmetric top, stationary, circulating, separatrix).
    pub fn regime(&self) -> Regime {
        self.regime
    }

    /// The principal moments (those of [`Inertia::principal_moments`]).
    pub fn principal_moments(&self) -> Vec3<T> {
        self.moments
    }

    /// Rotational energy `E = ½ Σ Jᵢ²/Iᵢ` (6.5.12), conserved.
    pub fn energy(&self) -> T {
        self.energy
    }

    /// `|J|`, conserved (the Casimir).
    pub fn momentum_norm(&self) -> T {
        self.j_norm
    }

    /// The lab-frame angular momentum `q₀ J₀ q₀*`, conserved.
    pub fn lab_momentum(&self) -> Vec3<T> {
        self.q0.rotate(self.j0).scale(self.j_scale)
    }

    /// The elliptic parameter `m ∈ [0, 1]` of an asymmetric top (1 on the separatrix); `None`
    /// for the sphere, symmetric top and stationary cases.
    pub fn parameter_m(&self) -> Option<T> {
        match &self.motion {
            Motion::Asymmetric(a) => Some(a.m),
            _ => None,
        }
    }

    /// The time between successive flips of the body momentum through the intermediate-axis
    /// region: `2K(m)/|λ|` (Landau & Lifshitz §37: the Jacobi functions have real period `4K`
    /// in `u = λt + u₀`, so the body momentum is periodic with period `T = 4K/|λ|` and this is
    /// `T/2`).
    ///
    /// Precisely: the time between successive sign changes of the intermediate-axis component
    /// `J_b ∝ sn u` (equivalently between its successive extremes `J_b = ±A₂`). For motion
    /// started near the intermediate axis (the Dzhanibekov / tennis-racket flip) it is the time
    /// between the body's successive turn-overs. `None` where there is no flip: sphere, symmetric
    /// top, stationary rotation about a principal axis, and the separatrix (the time is
    /// infinite there).
    ///
    /// Also `None` when the interval overflows the type (a body turning so slowly that the
    /// time is not representable).
    pub fn flip_interval(&self) -> Option<T> {
        match &self.motion {
            Motion::Asymmetric(a) if !a.separatrix => {
                let t = T::TWO * a.kc / a.lambda.abs() / self.rate_scale;
                if t.is_finite() { Some(t) } else { None }
            }
            _ => None,
        }
    }

    /// Body angular momentum at time `t` (domain as [`FreeRigidBody::state_at_unchecked`]).
    pub fn body_momentum_at(&self, t: T) -> Vec3<T> {
        self.principal_to_body(self.principal_momentum_at(t * self.rate_scale))
    }

    /// A principal-frame vector in the body frame.
    #[inline]
    fn principal_to_body(&self, v: Vec3<T>) -> Vec3<T> {
        match self.principal {
            None => v,
            Some(p) => p.rotate(v),
        }
    }

    /// Principal-frame angular momentum at the normalised time `t` (`t·rate_scale`).
    fn principal_momentum_at(&self, t: T) -> Vec3<T> {
        let j = match &self.motion {
            Motion::Steady { .. } => self.j0,
            Motion::Symmetric { e_s, body_rate, .. } => {
                UnitQuat::from_axis_angle_unchecked(*e_s, -*body_rate * t).rotate(self.j0)
            }
            Motion::Asymmetric(a) => {
                let (sn, cn, dn) = self.jacobi(a, t);
                self.assemble(a, sn, cn, dn)
            }
        };
        j.scale(self.j_scale)
    }

    fn jacobi(&self, a: &Asymmetric<T>, t: T) -> (T, T, T) {
        let u = a.lambda * t + a.u0;
        if a.separatrix {
            let (sech, tanh) = sech_tanh(u);
            (tanh, sech, sech)
        } else {
            let (_, _, sn, cn, dn) = amplitude_parts(u, a.m, a.m1);
            (sn, cn, dn)
        }
    }

    fn assemble(&self, a: &Asymmetric<T>, sn: T, cn: T, dn: T) -> Vec3<T> {
        let [a1, a2, a3] = a.idx;
        let [p1, p2, p3] = a.amp;
        let mut j = Vec3::ZERO;
        j[a1] = p1 * cn;
        j[a2] = p2 * sn;
        j[a3] = p3 * dn;
        j
    }

    /// Body angular velocity `ω = I⁻¹ J` at time `t` (rad/s, body frame; domain as
    /// [`FreeRigidBody::state_at_unchecked`]).
    pub fn body_rates_at(&self, t: T) -> Vec3<T> {
        let j = self.principal_momentum_at(t * self.rate_scale);
        self.principal_to_body(Vec3::new(
            j.x / self.moments.x,
            j.y / self.moments.y,
            j.z / self.moments.z,
        ))
    }

    /// [`FreeRigidBody::state_at_unchecked`] with a check of `t`.
    ///
    /// Validity limit: the phases of the motion (the Jacobi argument `λt` and the angle about
    /// the lab momentum) may reach at most [`exact_step_angle_limit`] (`1/ε`): beyond it their
    /// rounding alone exceeds half a radian and the state has no correct digit, as for the exact
    /// exponential step.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `t`; [`Error::StepTooLong`] beyond the validity
    /// limit.
    pub fn try_state_at(&self, t: T) -> Result<State<T>, Error> {
        if !t.is_finite() {
            return Err(Error::NonFinite);
        }
        let phase = (t * self.rate_scale).abs() * self.max_rate;
        // A NaN or infinite phase (an overflowed product) is not within the limit either.
        let within = phase <= exact_step_angle_limit::<T>();
        if !within {
            return Err(Error::StepTooLong);
        }
        Ok(self.state_at_unchecked(t))
    }

    /// The state at time `t`: attitude (body → lab) and body angular momentum `J`.
    ///
    /// Closed form for every `t` within the validity limit of [`FreeRigidBody::try_state_at`]
    /// (negative too); cost independent of `t`. Accuracy of the attitude degrades like
    /// `ε·|ψ(t)|` (the angle about `J` is evaluated, not accumulated). Domain: a finite `t`
    /// within that limit; outside it the result is unspecified (NaN components for a NaN or
    /// infinite `t` or a phase that overflows), never a panic. Use
    /// [`FreeRigidBody::try_state_at`] to have `t` checked.
    pub fn state_at_unchecked(&self, t: T) -> State<T> {
        let (q, j) = self.principal_state_at(t * self.rate_scale);
        let j = j.scale(self.j_scale);
        match self.principal {
            None => State::new(q, j),
            Some(p) => State::new(q * p.inverse(), p.rotate(j)),
        }
    }

    /// The attitude and the scaled momentum (`J/j_scale`) of the principal frame at the
    /// scaled time `t` (`t·rate_scale`).
    fn principal_state_at(&self, t: T) -> (UnitQuat<T>, Vec3<T>) {
        match &self.motion {
            Motion::Steady { rate } => {
                let axis = self.j0.scale(T::ONE / self.j0_norm);
                let q = self.q0 * UnitQuat::from_axis_angle_unchecked(axis, *rate * t);
                (q, self.j0)
            }
            Motion::Symmetric {
                e_s,
                lab_rate,
                body_rate,
            } => {
                let axis = self.j0.scale(T::ONE / self.j0_norm);
                let q = self.q0
                    * UnitQuat::from_axis_angle_unchecked(axis, *lab_rate * t)
                    * UnitQuat::from_axis_angle_unchecked(*e_s, *body_rate * t);
                let j = UnitQuat::from_axis_angle_unchecked(*e_s, -*body_rate * t).rotate(self.j0);
                (q, j)
            }
            Motion::Asymmetric(a) => {
                let u = a.lambda * t + a.u0;
                let (j, psi) = if a.separatrix {
                    let (sech, tanh) = sech_tanh(u);
                    (self.assemble(a, tanh, sech, sech), a.psi_rate * t)
                } else {
                    let (k, phi_r, sn, cn, dn) = amplitude_parts(u, a.m, a.m1);
                    let pi = pi_with_complete(a.n, a.n1, k, phi_r, a.m1, a.pi_complete);
                    (
                        self.assemble(a, sn, cn, dn),
                        a.psi_rate * t + a.c_over_lambda * (pi - a.pi0),
                    )
                };
                let (theta, chi) = gauge_angles(j.scale(T::ONE / self.j0_norm), a.e_b, a.e_c2);
                let q = a.g0
                    * UnitQuat::from_axis_angle_unchecked(a.e_b, psi)
                    * UnitQuat::from_axis_angle_unchecked(a.e_c2, -theta)
                    * UnitQuat::from_axis_angle_unchecked(a.e_b, -chi);
                (q.renormalize_fast(), j)
            }
        }
    }
}

/// Spherical angles `(θ, χ)` of the unit vector `j` with pole `e_b` and azimuth measured from
/// `e_c₁ = e_c₂ × e_b` towards `e_c₂`.
fn gauge_angles<T: Real>(j: Vec3<T>, e_b: Vec3<T>, e_c2: Vec3<T>) -> (T, T) {
    let e_c1 = e_c2.cross(e_b);
    let x = j.dot(e_c1);
    let y = j.dot(e_c2);
    let z = j.dot(e_b);
    (x.hypot(y).atan2(z), y.atan2(x))
}
