//! The integration methods of a step ([`Integrator`]): classical RK4 and the Lie–Poisson
//! splittings (Strang, Yoshida, Suzuki), each on a plain [`State`] and on a
//! [`CompensatedState`] (the state with its rounding errors carried).
//!
//! Each method depends on the body ([`crate::dynamics::Gyrostat`], its Hamiltonian and its
//! state) and on nothing else of the dynamics: the step ([`crate::dynamics::Gyrostat::step`])
//! checks its input and result and calls them. The splittings' composition (the stages of a
//! method, the merging of the same-axis rotations and of the half-kicks at stage boundaries) is
//! written once, over the one-axis flows of a state kind: the plain flows and the compensated
//! ones implement the same trait.
//!
//! # RK4
//! The classical Runge–Kutta step on the whole state `(q, J, wheel speeds)`:
//! `q̇ = ½ q ⊗ (0, ω)`, `J̇ = J × ω + τ`, `Ω̇ᵢ = ḣᵢ / I_wᵢ`, with `ω = ∇H(J)` (6.8.5). The
//! intermediate quaternions leave the unit sphere by the truncation error; the step
//! renormalises the result. The baseline of Basilisk and NASA 42: order 4, but its energy and
//! `|J|` errors grow linearly with time.
//!
//! # The Lie–Poisson splittings
//! The quadratic Hamiltonian in principal axes is a sum `Σ Hᵢ(Jᵢ)` of one-axis pieces; the flow
//! of `Hᵢ` keeps `Jᵢ` fixed and rotates `J` about `eᵢ` at the constant rate
//! `ωᵢ = H′ᵢ(Jᵢ) = 2Aᵢ(Jᵢ − Sᵢ)` (6.9.2), while the attitude turns about the same body axis by the
//! same angle, `q ← q ⊗ exp(θ eᵢ/2)`. Each sub-step is an exact rotation, so `|J|` and the lab
//! momentum `q J q*` are conserved to rounding and the energy error stays bounded (the method is
//! symplectic on the coadjoint orbit). The Strang step is `A₁(h/2) A₂(h/2) A₃(h) A₂(h/2)
//! A₁(h/2)` (order 2); Yoshida (1990, three stages) and Suzuki (1990, five-stage "fractal")
//! compose it symmetrically to order 4, Suzuki with a leading error constant ~100× smaller for
//! the rigid body of the tests, for 5/3 of the cost.
//!
//! External torque `τ` and reaction-wheel torques `ḣ` enter by splitting too: a "kick"
//! `J ← J + τ·h/2`, `Ωᵢ ← Ωᵢ + (ḣᵢ/I_wᵢ)·h/2` before and after the Hamiltonian flow (the wheel
//! torque is internal and does not change the total momentum `J`; it changes the rotor momentum
//! inside `H`). For a torque that depends on time and attitude only the kicks are exact flows and
//! the orders above hold; a torque that depends on `J` or `ω` (rate damping) makes the kick an
//! explicit Euler sub-step and the splitting first order — use RK4 for such laws.
//!
//! Quartic models (6.8.20) keep the structure: the octahedral term `t₄Jᵢ⁴` is a function of `Jᵢ`
//! alone, so it joins the i-th piece (rate `+4t₄Jᵢ³`); the cubic term is reduced with `|J|²`,
//! `J₁²J₂² + J₁²J₃² + J₂²J₃² = ½|J|⁴ − ½ΣJᵢ⁴`, into one-axis pieces (rate `−2t₂₂Jᵢ³`) plus the
//! Casimir `½t₂₂|J|⁴`, whose flow leaves `J` fixed and turns the attitude about `J` at the rate
//! `2t₂₂|J|²·|J|` (it commutes with every other piece). Every piece is again an exact rotation.
//!
//! A non-diagonal inertia tensor is handled by rotating about its principal axes expressed in
//! the body frame (the columns of [`crate::dynamics::Inertia::principal_axes`]): the same exact
//! one-axis flows, with the Rodrigues form for a general axis.
//!
//! # In f32: the compensated step
//! ## Why a plain f32 splitting loses to RK4
//! Every sub-step of a splitting method is an exact rotation, yet in f32 the plain Yoshida4 and
//! Suzuki4 steps end 2.9–108× further from the truth than a plain f32 RK4 at the same step
//! (`dt = 0.004`, horizons 12–60, eight well-conditioned torque-free cases), and 1300–2900×
//! further with a constant torque. The causes, found by changing one thing at a time in a
//! replica of these flows that reproduces the library bit for bit
//! (`host-tests/tests/dynamics/compensated.rs`, `cause_experiment`; the table is in
//! BENCHMARKS.md, "Dynamics in f32"):
//!
//! - *Rounding the value at every sub-step.* Each of the 13 (Yoshida) or 21 (Suzuki) rotations
//!   of a step rounds `J` and `q` to f32, where RK4 rounds them once per step. An error in `J`
//!   changes the rates, so the phase error it causes keeps growing after it is made: the errors
//!   are amplified, not just added. Carrying each rounding error instead of dropping it (below)
//!   takes the errors from 2.9–108× RK4's to 0.01–2.3×. Making the roundings unbiased (stochastic
//!   rounding in the replica) does not: 0.4–97×, worse than round-to-nearest on the symmetric
//!   tops, where nearest rounding happens to return the spin component to the same value.
//! - *Rounding the same way every time.* A constant kick `J ← J + τh` rounds with the same sign
//!   while `J` stays in one binade (mean signed error −0.43 … +0.34 ulp per kick, as large as
//!   its magnitude): a bias. The half angle of a sub-step, `ψ = rate·h/2`, and `sin ψ` are
//!   rounded to f32 the same way at every sub-step when the rate is constant (a symmetric top
//!   about its axis): the body turns by the same wrong angle each time, a phase error growing
//!   with the total angle turned. It is what is left after the carry (oblate top 2.2×) and it
//!   is not the `sin` kernel: f64-rounded `sin`/`cos` give the same numbers to three digits.
//!
//! Ruled out by the same experiment: the f32 `sin`/`cos` kernel, the merging of same-axis
//! rotations at stage boundaries, and, alone, the multiplicative form of the co-rotation
//! (`q·cos ψ + sin ψ·(q ⊗ eᵢ)`; the increment form alone changes the errors by 0.3–1.4×).
//!
//! ## The compensated step
//! 1. *Increment form*: every update is `x ← x + d` with a small increment `d`: the co-rotation
//!    `q ← q + q ⊗ (cos ψ − 1, sin ψ·eᵢ)`, the momentum `J ← J + (R − 1)J`, the kick
//!    `J ← J + τh`, the renormalisation `q ← q + q·(1 − |q|²)/2`.
//! 2. *Compensated sums*: each increment is added through Fast2Sum and the rounding error is
//!    carried to the next update, `(x, e) ← Fast2Sum(x, d + e)`, the increment computed from
//!    the carried value (`d = (R − 1)(J + e_J)`, `d = (q + e_q) ⊗ (…)`);
//! 3. *the carry kept across steps* in the [`CompensatedState`];
//! 4. *exact half angles*: `ψ = rate·(h/2)` is formed exactly as a pair (Dekker's product) and
//!    `sin ψ = ψ + ψ³·(…)` by its Taylor series, so that only the small tail is rounded; the
//!    kicks' `τh` and RK4's `h/6` are exact pairs too.
//!
//! Each increment is added as a double-f32 sum (the crate's error-free transformations): its
//! small parts (the low part of `sin ψ`, the carried errors' share) below an ulp of the
//! increment would otherwise round away the same way every time.
//!
//! With all four, the f32 Yoshida4 and Suzuki4 errors are 0.002–0.11× those of a plain f32 RK4
//! at the same step on the eight cases, 0.16× with a constant torque; over 10⁶ steps `|J|`
//! drifts ≤ 2.1e-7 relative and the lab momentum ≤ 2.7e-7 (plain: 8e-6…1e-3 and 2e-4…1e-2);
//! the energy error is the random walk of the increments' roundings (1.0e-6 after 10⁶ steps at
//! `dt = 0.1`, against a drift to 2.5e-4 for the plain step); RK4 on a compensated state is
//! 0.001–0.12× the plain RK4. Costs are in BENCHMARKS.md (Cortex-M4F
//! instruction counts beside the plain rows, host times). The plain [`State`] keeps the plain,
//! cheaper flows: use it for short horizons (a control loop whose state is reset from sensors),
//! the compensated state for propagating a model for long (a simulator, a predictor without
//! measurements).
//!
//! In f64 the compensated step works the same way and is accurate to about `u²` per sub-step;
//! the plain f64 splitting is already accurate to its truncation error on every horizon tested,
//! so there the compensation buys little.

pub(crate) mod compensated_flows;
pub(crate) mod rk4;
pub(crate) mod splitting;

#[cfg(doc)]
use crate::dynamics::{CompensatedState, State};

/// The integration method of a step.
///
/// - [`Integrator::Rk4`]: the classical Runge–Kutta method on `(q, J, wheel speeds)`, the
///   quaternion renormalised after each step. The baseline of Basilisk and NASA 42: order 4, but
///   its energy and `|J|` errors grow linearly with time.
/// - The Lie–Poisson splittings (see the [module docs](self)): every sub-step an exact
///   rotation, so `|J|` and the lab momentum are conserved to rounding and the energy error stays
///   bounded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Integrator {
    /// Classical Runge–Kutta, order 4, quaternion renormalised each step.
    Rk4,
    /// Lie–Poisson splitting, Strang composition, order 2 (5 exact one-axis rotations).
    Strang,
    /// Yoshida's 3-stage symmetric composition of Strang steps, order 4.
    Yoshida4,
    /// Suzuki's 5-stage symmetric composition of Strang steps, order 4, smaller error constant.
    Suzuki4,
}

impl Integrator {
    /// Every method, in the order above.
    pub const ALL: [Integrator; 4] = [
        Integrator::Rk4,
        Integrator::Strang,
        Integrator::Yoshida4,
        Integrator::Suzuki4,
    ];

    /// The method's name in the tools and Python: `rk4`, `strang`, `yoshida4`, `suzuki4`.
    pub const fn name(self) -> &'static str {
        match self {
            Integrator::Rk4 => "rk4",
            Integrator::Strang => "strang",
            Integrator::Yoshida4 => "yoshida4",
            Integrator::Suzuki4 => "suzuki4",
        }
    }

    /// `true` for the Lie–Poisson splitting methods (exact `|J|`, bounded energy error).
    #[inline]
    pub fn is_splitting(self) -> bool {
        !matches!(self, Integrator::Rk4)
    }
}

impl core::str::FromStr for Integrator {
    type Err = crate::Error;
    /// The method of [`Integrator::name`].
    ///
    /// # Errors
    /// [`crate::Error::InvalidArgument`] for any other text.
    fn from_str(s: &str) -> Result<Self, crate::Error> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or(crate::Error::InvalidArgument)
    }
}

impl core::fmt::Display for Integrator {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}
