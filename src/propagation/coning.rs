//! The gyro-increment path: rotation-vector updates with coning compensation.
//!
//! Rate-integrating gyros (and most navigation-grade IMUs) deliver increments
//! `Δθₖ = ∫ω dt` over `[tₖ, tₖ₊₁]`, one per sample interval `h`. The body-frame rotation over
//! an attitude update interval `T` is the rotation vector `φ` with `q ← q ⊗ exp(φ)`, and `φ` is
//! NOT the sum of the increments when the rate changes direction: the non-commutativity
//! (Bortz) term `½ ∫ α × ω dt` has a secular part under coning motion, which a rule must
//! approximate from the increments. The rules here, for `N` increments `θ₁ … θ_N` in
//! time order (earlier × later):
//!
//! | rule | rotation vector | residual drift under coning (half-angle `α`, rate `Ω`) |
//! |---|---|---|
//! | [`ConingRule::Exp`] | `θ` | `α²Ω (Ωh)²/12` |
//! | [`ConingRule::OnePlusPrevious`] | `θₖ + (1/12) θₖ₋₁ × θₖ` | `α²Ω (Ωh)⁴/60` |
//! | [`ConingRule::TwoSample`] | `θ₁+θ₂ + ⅔ θ₁ × θ₂` | `α²Ω (ΩT)⁴/960` |
//! | [`ConingRule::ThreeSample`] | `Σθ + (9/20 θ₁ + 27/20 θ₂) × θ₃` | `α²Ω (ΩT)⁶/204120` |
//! | [`ConingRule::FourSample`] | `Σθ + (54 θ₁ + 92 θ₂ + 214 θ₃)/105 × θ₄` | `α²Ω (ΩT)⁸/82575360` |
//!
//! The `N`-sample coefficients are the ones that cancel the coning error to the highest order
//! in `ΩT` for pure coning motion (Miller 1983, *J. Guidance* 6(4); Ignagni 1990, *J. Guidance*
//! 13(2); Lee, Yoon, Lee & Lee 1990, *IEEE Trans. AES* 26(5), the forms with every cross
//! product taken with the last increment). The drifts are measured in
//! `host-tests/tests/propagation/coning.rs` (the 4-sample constant is derived there from the
//! series of the rule minus the exact coning term, `−x⁹/315` per update with `x = Ωh`).
//!
//! The drifts are the leading terms in `α²`: every rule approximates only the `½ α × ω` part of
//! the rotation-vector rate, so terms of order `α⁴` remain, and they grow with the update
//! interval. With `α = 0.05` they already exceed the 4-sample `α²` term a hundredfold
//! (measured); the higher-order rules pay off for small cone angles (vibration), where coning
//! drift matters most.
//!
//! For strapdown systems that update the attitude more slowly than the gyro samples,
//! [`ConingAccumulator`] is the two-speed form (Savage 1998, *J. Guidance* 21(1)): at the gyro
//! rate it accumulates the increment sum `α` and the coning term `β` with the one-plus-previous
//! correction; at the attitude rate `φ = α + β` goes through one exponential.

use crate::step_limit::within_step_limit;
use crate::{Error, Real, Ring, Vec3};

/// An increment (coning) rule: how the rotation vector of one attitude update is formed.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConingRule {
    /// One exponential per increment, no coning correction: `φ = θ`.
    Exp,
    /// One increment per update with the previous-interval correction
    /// `φ = θₖ + (1/12) θₖ₋₁ × θₖ` (the first increment has no predecessor and uses `θₖ₋₁ = 0`).
    OnePlusPrevious,
    /// Two increments per update: `φ = θ₁ + θ₂ + ⅔ θ₁ × θ₂`.
    TwoSample,
    /// Three increments per update: `φ = θ₁ + θ₂ + θ₃ + (9/20 θ₁ + 27/20 θ₂) × θ₃`.
    ThreeSample,
    /// Four increments per update: `φ = Σθ + (54 θ₁ + 92 θ₂ + 214 θ₃)/105 × θ₄`.
    FourSample,
}

impl ConingRule {
    /// Every rule, in order of increasing samples per update.
    pub const ALL: [ConingRule; 5] = [
        ConingRule::Exp,
        ConingRule::OnePlusPrevious,
        ConingRule::TwoSample,
        ConingRule::ThreeSample,
        ConingRule::FourSample,
    ];

    /// Increments consumed by one attitude update (1 to 4).
    pub const fn samples_per_update(self) -> usize {
        match self {
            ConingRule::Exp | ConingRule::OnePlusPrevious => 1,
            ConingRule::TwoSample => 2,
            ConingRule::ThreeSample => 3,
            ConingRule::FourSample => 4,
        }
    }

    /// The rule's name in the tools, Python and the benchmarks: `exp`, `coning1` (one plus
    /// previous), `coning2`, `coning3`, `coning4` (the samples per update).
    pub const fn name(self) -> &'static str {
        match self {
            ConingRule::Exp => "exp",
            ConingRule::OnePlusPrevious => "coning1",
            ConingRule::TwoSample => "coning2",
            ConingRule::ThreeSample => "coning3",
            ConingRule::FourSample => "coning4",
        }
    }
}

impl core::str::FromStr for ConingRule {
    type Err = Error;
    /// The rule of [`ConingRule::name`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for any other text.
    fn from_str(s: &str) -> Result<Self, Error> {
        Self::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or(Error::InvalidArgument)
    }
}

impl core::fmt::Display for ConingRule {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// A rule's rotation vector in the form every rule shares, `φ = sum + lever × last`: the sum of
/// the increments, the (scaled) earlier increments, and the last increment.
///
/// [`crate::UnitQuat::mul_exp_unchecked`] takes this form, so that fixed point can form the coning term
/// `lever × last` (small, and nearly constant under coning) at a finer resolution than the
/// format instead of rounding it to 2⁻³⁰ every update.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConingTerms<T> {
    /// `Σθ`.
    pub sum: Vec3<T>,
    /// The combination of earlier increments that multiplies the last one.
    pub lever: Vec3<T>,
    /// The last increment `θ_N`.
    pub last: Vec3<T>,
}

impl<T: Ring> ConingTerms<T> {
    /// `φ = sum + lever × last`.
    #[inline]
    pub fn rotation_vector(self) -> Vec3<T> {
        self.sum + self.lever.cross(self.last)
    }
}

/// One increment with the previous-interval correction, `θₖ + (1/12) θₖ₋₁ × θₖ`, as
/// [`ConingTerms`].
///
/// Every rule scales the earlier operands of its cross product before multiplying: the
/// coefficient's rounding then lands on an increment-sized value (negligible after the product).
#[inline]
pub fn one_plus_previous_terms<T: Ring>(previous: Vec3<T>, current: Vec3<T>) -> ConingTerms<T> {
    ConingTerms {
        sum: current,
        lever: previous.scale(T::ratio::<1, 12>()),
        last: current,
    }
}

/// The coefficient of the 2-sample rule for unequal sub-intervals `h₁`, `h₂` (see
/// [`two_sample_unequal_terms`]): `c = (h₁ + h₂)² / (6 h₁ h₂)`, `⅔` for `h₁ = h₂`. Formed as
/// `(r + 2 + 1/r)/6` with `r = h₁/h₂` for ratios within `[10⁻⁶, 10⁶]`; beyond them that sum
/// overflows (or `r` is subnormal) before the division by 6 although `c` is representable, so
/// there `c = u·((H/6)/h + 1/6)` with `H ≥ h` the two intervals and `u = (h₁ + h₂)/H ∈ [1, 2]`
/// (`H/6` stays normal for `H ≥ 10⁻³⁰`; below, both intervals are tiny and `u·(H/h + 1)/6`
/// cannot overflow). Finite wherever `c` is, to a few ulps. Domain: `h₁, h₂ > 0` (unchecked: a
/// zero interval gives an infinite or NaN coefficient).
#[inline]
pub fn two_sample_unequal_coefficient<T: Real>(h1: T, h2: T) -> T {
    let r = h1 / h2;
    let six = T::from_f64(6.0);
    if r >= T::from_f64(1e-6) && r <= T::from_f64(1e6) {
        return (r + T::TWO + T::ONE / r) / six;
    }
    let (small, big) = if h1 <= h2 { (h1, h2) } else { (h2, h1) };
    let u = (h1 + h2) / big;
    if big >= T::from_f64(1e-30) {
        u * ((big / six) / small + T::ONE / six)
    } else {
        u * (big / small + T::ONE) / six
    }
}

/// The 2-sample rule for two increments over unequal sub-intervals `h₁` then `h₂`:
/// `θ₁ + θ₂ + c · θ₁ × θ₂` with `c` = [`two_sample_unequal_coefficient`]`(h₁, h₂)`
/// `= (h₁ + h₂)²/(6 h₁ h₂)`, given as `coefficient` so that fixed point can take it precomputed
/// (in Q1.30 it fits for `h₁/h₂ ∈ (0.102, 9.9)`; from microsecond intervals in integer
/// arithmetic: [`crate::sensor::timing::unequal_coefficient_q30`]).
///
/// Derivation (the order kept): the rotation vector over `[0, T]`, `T = h₁ + h₂`, to second
/// order in the rates (Bortz, truncated after the single commutator) is
/// `φ = α(T) + ½ ∫₀ᵀ α(t) × ω(t) dt`, `α(t) = ∫₀ᵗ ω`. For a linearly varying rate
/// `ω = a + b t`: `α × ω = (a t + b t²/2) × (a + b t) = (a × b) t²/2`, so the coning term is
/// `(a × b) T³/12`. The increments are `θ₁ = a h₁ + b h₁²/2`,
/// `θ₂ = a h₂ + b (T² − h₁²)/2`, whose cross product is `θ₁ × θ₂ = (a × b) h₁ h₂ T / 2`; hence
/// `φ = θ₁ + θ₂ + T²/(6 h₁ h₂) · θ₁ × θ₂`, which for `h₁ = h₂` is the classical `⅔`. Like the
/// equal-interval rule, it is exact for a rate linear in time through the single-commutator
/// term; under classical coning its drift error is of fourth order in `Ω T` (the equal rule's
/// `(ΩT)⁴` behaviour, measured with jittered intervals in `host-tests/tests/sensor/`).
#[inline]
pub fn two_sample_unequal_terms<T: Ring>(
    t1: Vec3<T>,
    t2: Vec3<T>,
    coefficient: T,
) -> ConingTerms<T> {
    ConingTerms {
        sum: t1 + t2,
        lever: t1.scale(coefficient),
        last: t2,
    }
}

/// The 2-sample rule `θ₁ + θ₂ + ⅔ θ₁ × θ₂` as [`ConingTerms`].
#[inline]
pub fn two_sample_terms<T: Ring>(t1: Vec3<T>, t2: Vec3<T>) -> ConingTerms<T> {
    ConingTerms {
        sum: t1 + t2,
        lever: t1.scale(T::ratio::<2, 3>()),
        last: t2,
    }
}

/// The 3-sample rule `Σθ + (9/20 θ₁ + 27/20 θ₂) × θ₃` as [`ConingTerms`].
#[inline]
pub fn three_sample_terms<T: Ring>(t1: Vec3<T>, t2: Vec3<T>, t3: Vec3<T>) -> ConingTerms<T> {
    ConingTerms {
        sum: t1 + t2 + t3,
        lever: t1.scale(T::ratio::<9, 20>()) + t2.scale(T::ratio::<27, 20>()),
        last: t3,
    }
}

/// The 4-sample rule `Σθ + (54 θ₁ + 92 θ₂ + 214 θ₃)/105 × θ₄` as [`ConingTerms`].
///
/// The lever is formed as `2·(27 θ₁ + 46 θ₂ + 107 θ₃)/105`, so that every coefficient lies in
/// `[−2, 2)` (214/105 does not fit Q1.30); for the floats the halving and doubling are exact and
/// the result is the same as with the written coefficients.
#[inline]
pub fn four_sample_terms<T: Ring>(
    t1: Vec3<T>,
    t2: Vec3<T>,
    t3: Vec3<T>,
    t4: Vec3<T>,
) -> ConingTerms<T> {
    let h = t1.scale(T::ratio::<27, 105>())
        + t2.scale(T::ratio::<46, 105>())
        + t3.scale(T::ratio::<107, 105>());
    ConingTerms {
        sum: t1 + t2 + t3 + t4,
        lever: Vec3::new(h.x.twice(), h.y.twice(), h.z.twice()),
        last: t4,
    }
}

/// `θₖ + (1/12) θₖ₋₁ × θₖ`: one increment with the previous-interval coning correction.
///
/// Domain (of this and the other rule functions): finite increments of at most
/// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) rad each; the result is then finite (at most a few times `π`).
#[inline]
pub fn one_plus_previous<T: Ring>(previous: Vec3<T>, current: Vec3<T>) -> Vec3<T> {
    one_plus_previous_terms(previous, current).rotation_vector()
}

/// `θ₁ + θ₂ + ⅔ θ₁ × θ₂`: the 2-sample coning rule.
#[inline]
pub fn two_sample<T: Ring>(t1: Vec3<T>, t2: Vec3<T>) -> Vec3<T> {
    two_sample_terms(t1, t2).rotation_vector()
}

/// `θ₁ + θ₂ + θ₃ + (9/20 θ₁ + 27/20 θ₂) × θ₃`: the 3-sample coning rule.
#[inline]
pub fn three_sample<T: Ring>(t1: Vec3<T>, t2: Vec3<T>, t3: Vec3<T>) -> Vec3<T> {
    three_sample_terms(t1, t2, t3).rotation_vector()
}

/// `Σθ + (54 θ₁ + 92 θ₂ + 214 θ₃)/105 × θ₄`: the 4-sample coning rule (see
/// [`four_sample_terms`] for how the coefficients are applied).
#[inline]
pub fn four_sample<T: Ring>(t1: Vec3<T>, t2: Vec3<T>, t3: Vec3<T>, t4: Vec3<T>) -> Vec3<T> {
    four_sample_terms(t1, t2, t3, t4).rotation_vector()
}

/// The [`ConingTerms`] of `samples` (1 to 4 increments in time order) by the highest-order rule
/// that fits their number (see [`rotation_vector_for`]); all zero for an empty slice.
pub fn coning_terms_for<T: Ring>(previous: Vec3<T>, samples: &[Vec3<T>]) -> ConingTerms<T> {
    match samples {
        [] => ConingTerms {
            sum: Vec3::ZERO,
            lever: Vec3::ZERO,
            last: Vec3::ZERO,
        },
        [a] => one_plus_previous_terms(previous, *a),
        [a, b] => two_sample_terms(*a, *b),
        [a, b, c] => three_sample_terms(*a, *b, *c),
        [a, b, c, d, ..] => four_sample_terms(*a, *b, *c, *d),
    }
}

/// The rotation vector of `samples` (1 to 4 increments in time order) by the highest-order rule
/// that fits their number: 1 → [`one_plus_previous`] with `previous`, 2 → [`two_sample`],
/// 3 → [`three_sample`], 4 → [`four_sample`]. Zero for an empty slice; a slice longer than 4
/// uses its first four. This is how a partial group (the end of a record, or a provisional
/// attitude inside a group) is integrated.
pub fn rotation_vector_for<T: Ring>(previous: Vec3<T>, samples: &[Vec3<T>]) -> Vec3<T> {
    coning_terms_for(previous, samples).rotation_vector()
}

/// Two-speed coning integration (Savage 1998): high-rate accumulation, low-rate update.
///
/// At the gyro rate, [`ConingAccumulator::push`] updates the increment sum and the coning term
/// with the one-plus-previous correction,
///
/// `αₗ = αₗ₋₁ + Δθₗ`,  `βₗ = βₗ₋₁ + ½ (αₗ₋₁ + Δθₗ₋₁/6) × Δθₗ`,
///
/// (a handful of multiply-adds per sample, no exponential); at the attitude rate,
/// [`ConingAccumulator::take`] returns `φ = α + β` for one update `q ⊗ exp(φ)` (see
/// [`crate::UnitQuat::mul_exp_unchecked`]) and restarts the sums. `Δθₗ₋₁`
/// carries across update boundaries. The residual coning drift is that of the one-plus-previous
/// rule at the SAMPLE interval, `α²Ω (Ωh)⁴/60`, whatever the update interval (to leading order
/// in `α`: the neglected `O(α⁴)` terms grow with the update interval, measured +18% over the
/// `α²` term at α = 0.05 with 8 samples per update, +0.9% at α = 0.01).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ConingAccumulator<T> {
    alpha: Vec3<T>,
    beta: Vec3<T>,
    previous: Vec3<T>,
    count: u32,
}

impl<T: Ring> ConingAccumulator<T> {
    /// An empty accumulator with no previous increment.
    pub const fn new() -> Self {
        Self {
            alpha: Vec3::ZERO,
            beta: Vec3::ZERO,
            previous: Vec3::ZERO,
            count: 0,
        }
    }

    /// Accumulates one increment (the high-rate step).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite component; [`Error::StepTooLong`] when the
    /// increment, or the increment sum `α` of the interval with it, is longer than
    /// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE): the two-speed correction is a truncated series
    /// in `α` (take the rotation vector more often). In fixed point, [`Error::OutOfRange`] when a
    /// sum of the update (`α`, the lever `α + Δθₗ₋₁/6`, the cross product, `β`, `α + β`) would
    /// saturate the format. Either way the increment is discarded and the state is unchanged.
    #[inline]
    pub fn push(&mut self, dtheta: Vec3<T>) -> Result<(), Error> {
        let dtheta = dtheta.try_finite()?;
        if !within_step_limit(dtheta) {
            return Err(Error::StepTooLong);
        }
        if !self.alpha.add_fits(dtheta) {
            return Err(Error::OutOfRange);
        }
        if !within_step_limit(self.alpha + dtheta) {
            return Err(Error::StepTooLong);
        }
        if !self.update_fits(dtheta) {
            return Err(Error::OutOfRange);
        }
        self.push_unchecked(dtheta);
        Ok(())
    }

    /// `true` when no sum of [`ConingAccumulator::push_unchecked`] with `dtheta` saturates
    /// (always for the floats).
    #[inline]
    fn update_fits(&self, dtheta: Vec3<T>) -> bool {
        let sixth = self.previous.scale(T::ratio::<1, 6>());
        let half = (self.alpha + sixth).scale(T::HALF);
        let dbeta = half.cross(dtheta);
        self.alpha.add_fits(sixth)
            && half.cross_fits(dtheta)
            && self.beta.add_fits(dbeta)
            && (self.alpha + dtheta).add_fits(self.beta + dbeta)
    }

    /// [`ConingAccumulator::push`] without the checks. Domain: finite increments whose interval
    /// sum stays within [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE); then `α` and `β` stay finite.
    #[inline]
    pub fn push_unchecked(&mut self, dtheta: Vec3<T>) {
        let lever = self.alpha + self.previous.scale(T::ratio::<1, 6>());
        self.beta += lever.scale(T::HALF).cross(dtheta);
        self.alpha += dtheta;
        self.previous = dtheta;
        self.count = self.count.saturating_add(1);
    }

    /// Increments accumulated since the last [`ConingAccumulator::take`].
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The rotation vector `φ = α + β` accumulated so far, without resetting.
    pub fn rotation_vector(&self) -> Vec3<T> {
        self.alpha + self.beta
    }

    /// Returns `φ = α + β` and restarts the interval (the low-rate step). The previous increment
    /// is kept for the next interval's first correction.
    pub fn take(&mut self) -> Vec3<T> {
        let phi = self.rotation_vector();
        self.alpha = Vec3::ZERO;
        self.beta = Vec3::ZERO;
        self.count = 0;
        phi
    }
}

#[cfg(feature = "defmt")]
impl<T: Ring + defmt::Format> defmt::Format for ConingAccumulator<T> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "ConingAccumulator(alpha={}, beta={}, count={})",
            self.alpha,
            self.beta,
            self.count
        )
    }
}
