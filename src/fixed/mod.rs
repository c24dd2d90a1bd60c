//! Q-format fixed point for FPU-less cores (Cortex-M0/M0+/M3): the attitude path in integer
//! arithmetic only, bit-identical on every target.
//!
//! [`Fixed<F>`] is a 32-bit signed value with `F` fraction bits (`Q(31−F).F`). It implements
//! [`Ring`], so the attitude hot path runs on it unchanged: the quaternion product, vector
//! rotation, rotation matrix, the exponential map ([`UnitQuat::exp_unchecked`]), fast and exact
//! renormalisation, the health value
//! [`norm_squared_deviation`](crate::propagation::normalization::norm_squared_deviation), the
//! coning rules (one-plus-previous, 2-, 3-, 4-sample), the two-speed
//! [`ConingAccumulator`](crate::propagation::ConingAccumulator) and the
//! [`IncrementIntegrator`](crate::propagation::IncrementIntegrator). It does not implement
//! [`crate::Real`] (no division, square root or trigonometry): Euler angles, the log map and the
//! dynamics stay float.
//!
//! # Formats
//!
//! | quantity | type | Q format | range | resolution | at the edge of the range |
//! |---|---|---|---|---|---|
//! | unit quaternion components | `UnitQuat<Q30>` | Q1.30 | `[−2, 2)`, used `[−1, 1]` | 2⁻³⁰ ≈ 9.3e-10 | cannot overflow: `|qᵢ| ≤ 1 + drift` |
//! | rotation matrix entries, unit vectors | `Mat3<Q30>`, `Vec3<Q30>` | Q1.30 | `[−1, 1]` | 2⁻³⁰ | a diagonal entry of exactly −1 saturates to −1 + 2⁻³⁰ |
//! | gyro increments `Δθ`, rotation vectors `φ` (rad) | `Vec3<Q30>` | Q1.30 | `|·| < 2` rad per component | 2⁻³⁰ rad | conversion: [`Error::OutOfRange`]; sums (coning rules, accumulator): saturate |
//! | raw sensor increments | `[i16; 3]` × [`RawScale<Q30>`](crate::sensor::RawScale) | integer × rad/LSB | any `i16` | the sensor's LSB | the scale is checked once: no `i16` can leave Q1.30 |
//! | body rates (rad/s) | `Vec3<Q24>` | Q7.24 | `[−128, 128)` rad/s | 2⁻²⁴ ≈ 6.0e-8 rad/s | conversion: [`Error::OutOfRange`] |
//! | time steps (s) | `Q30` | Q1.30 | `(0, 2)` s | 2⁻³⁰ s ≈ 0.93 ns | conversion: [`Error::OutOfRange`] |
//! | rate × step → increment | [`increment_from_rate`] | Q7.24 × Q1.30 → Q1.30 | | one rounding | saturates at ±2 rad |
//!
//! Every value is in the symmetric range `[−(2³¹ − 1), 2³¹ − 1]·2⁻ᶠ`: the most negative `i32` is
//! never produced ([`Fixed::from_bits`] clamps it), so negation and `abs` are exact.
//!
//! # Arithmetic
//! - `+`, `−`: saturating (clamp to the range, never wrap, never panic).
//! - `×`: the exact 64-bit product, rounded to nearest with **ties to even**, then saturated.
//!   Unbiased rounding matters: a rounding that always goes one way (the `fixed` crate's
//!   multiplication truncates towards −∞, measured) adds a bias of half a unit per operation,
//!   which a propagated attitude integrates into a linear drift over 10⁶ updates.
//! - [`Ring::dot`] (1 to 4 products, the quaternion product's and the cross product's building
//!   block): exact products summed in 64 bits and rounded once (with 3 or 4 terms the sum is
//!   halved before rounding, so that it cannot overflow; the tie rule then applies to within
//!   2⁻²ᶠ of a tie).
//! - [`Ring::ratio`]: coefficients such as 2/3 or 9/20 are rounded at compile time; a ratio
//!   outside the range is a compile error.
//! - [`Ring::twice`]: saturating shift.
//! - The exponential map: for `θ² = |φ|² ≤ 1/64` (θ ≤ 1/8 rad, the per-update angle of any
//!   gyro at ≥ 300 Hz up to 2000 °/s) the series `cos(θ/2) ≈ 1 − θ²/8 + θ⁴/384`,
//!   `sin(θ/2)/θ ≈ ½ − θ²/48 + θ⁴/3840`, whose first dropped term is ≤ 8.3e-11 < 2⁻³¹; beyond,
//!   scaling and squaring (halve the angle up to five times, double back with
//!   `cos 2x = cos²x − sin²x`), correct for every representable `φ` (`|φ| < 2√3`), including
//!   angles beyond π. No angle is rejected.
//! - The attitude update `q ⊗ exp(φ)` ([`UnitQuat::mul_exp_unchecked`], used by every increment
//!   integrator): fused, so that the small rotation increment `sin(θ/2)/θ·φ` is carried with 3
//!   more fraction bits (2⁻³³) and each output component is rounded once. Without it, a constant
//!   rate would integrate the rounding of its (identical) increment quaternion linearly. A
//!   coning rule's update ([`UnitQuat::mul_exp_unchecked`] of its `ConingTerms`) also forms its cross product exactly
//!   and adds it to the increments at 2⁻³³, so the small coning term is not rounded to 2⁻³⁰.
//! - [`CarriedAttitude`](crate::propagation::CarriedAttitude) carries the residuals of the rotation vector's, the increment's and the
//!   attitude's roundings into the next update and folds the renormalisation into the increment
//!   (see "Rounding bias" below); [`IncrementQuantizer`] converts increments with the remainder
//!   carried.
//! - Renormalisation: [`UnitQuat::renormalize_fast`] is `q + q·(1 − |q|²)/2` (one Newton step of
//!   the inverse square root, no division); [`UnitQuat::renormalize`] iterates that step on the
//!   scale until it stops changing (valid for `|q|² ∈ (½, 2)`: below, the squared scale
//!   `1/|q|²` leaves Q1.30).
//!
//! # Accuracy
//! Measured against the f64 reference (`host-tests/tests/fixed/accuracy.rs`,
//! `firmware.rs`, `carried.rs`; `BENCHMARKS.md` has the tables), in units `u = 2⁻³⁰`: product
//! ≤ 0.5u per component, rotation ≤ 3.4u, matrix ≤ 3.7u, exponential ≤ 0.64u on the series
//! domain and ≤ 32u up to `|φ| = 3.4` rad (worst of 4·10⁶ random `φ`: 31.3u at 2.3 rad; an
//! independent campaign's worst, 31.9u at 2.09 rad; the per-band bound of the accuracy test is
//! `(2ᵏ⁺¹ + 4)u` for `k` halvings, 68u at `k = 5`). The other formats (`Fixed<F>`,
//! `6 ≤ F ≤ 30`, checked at compile time) reduce an angle beyond π modulo 2π first and take the
//! exponential past the series in Q3.28 (Q2.29 for `F = 29`), so theirs is within 80 units of
//! that format plus their own rounding (the `oracles` campaign of `host-tests`). Propagated with [`CarriedAttitude`](crate::propagation::CarriedAttitude) from increments
//! converted by an [`IncrementQuantizer`] (what `propagate --fixed` runs), the attitude has no
//! rounding bias: over 60 s at 1 kHz a constant rate ends within 5e-8 rad of the exact attitude
//! (f32: 1e-6 to 7e-4), and under classical coning every rule reproduces the f64 error, drift
//! included (one-plus-previous and 2-sample within 0.1 % of f64's on a cone that does not repeat
//! and within 1 % on one that does), started on the cone or at the identity.
//!
//! # Rounding bias
//! The plain update (`UnitQuat<Q30>` with [`UnitQuat::mul_exp_unchecked`] of the `ConingTerms` and
//! [`Normalization::Fast`](crate::propagation::Normalization::Fast), each increment converted on
//! its own) rounds to nearest with ties to even, an unbiased rounding of a random value. But an
//! attitude update does not round random values: under a constant rate, or under coning, the
//! same increment, the same coning term and nearly the same attitude come again and again, and
//! so does each rounding error. Measured through `propagate --fixed` (1 kHz, exact increments,
//! error against the closed form; issue 18): the 4-sample rule on a 1° cone at 10 Hz drifted
//! 1.45e-5 rad in 60 s (f64: 2.2e-10), every rule started at the identity 8.5e-6 to 1.7e-5, a
//! constant rate 2e-6 to 1.4e-5; on a 3° cone at 19.37 Hz the 2-sample rule ended 24 % and the
//! one-plus-previous rule 84 % off the drift that f64 reproduces. Five roundings were found to
//! drift, one at a time, by writing the update again in `i128` with each rounding either
//! forgotten or its residual carried and leaving one out at a time
//! (`host-tests/tests/fixed/ablation.rs`; the table is in BENCHMARKS.md):
//!
//! | rounding | left alone it costs | mechanism |
//! |---|---|---|
//! | each increment to 2⁻³⁰ | up to 1.5e-5 rad in 60 s | a constant rate, and the constant axial increment `−Ω(1 − cos α)h` of coning, is rounded the same way every sample: a wrong angle per sample, up to 2⁻³¹ rad (4.7e-7 rad/s at 1 kHz) |
//! | the attitude to 2⁻³⁰ | up to 3e-6 rad; on a repeating input the drift vanishes | the four components repeat their phases; on the 1° cone (100 samples a period) the drift per period is below one step and the integer attitude returns to the same bits every period: the 2-sample rule's drift (2.98e-7 rad) is lost (2.6e-10) |
//! | the coning term `lever × last` to 2⁻³³ | up to 8e-7 rad | under coning the term is nearly constant along the cone axis |
//! | the rotation increment `sin(θ/2)/θ·φ` to 2⁻³³ | up to 3e-6 rad | constant for a constant rate; its axial part constant under coning |
//! | the fast renormalisation as a second rounding of the attitude | up to 5.6e-6 rad | `q + round(q·e)` with `e` a few units: the correction itself is quantised the same way every update |
//!
//! The fix is at each mechanism, exact in integers: [`IncrementQuantizer`] converts increments
//! with the remainder carried (the sum of the converted increments stays within 2⁻³¹ rad of the
//! sum of the given ones); [`CarriedAttitude`](crate::propagation::CarriedAttitude) keeps the residual of each of the three roundings
//! inside an update (10 words beside the attitude) and adds it to the next update's value before
//! rounding, and folds the renormalisation into the increment, `(cos(θ/2), u)·(1 + e)`, so that
//! the attitude is rounded once per update. A wider attitude (an `i64` Q1.62) would remove the
//! attitude's share too, but every product of the update would then be 64 × 32 bits; the
//! carried residuals cost nothing extra (the carried 2-sample update is 1854 instructions on
//! the Cortex-M0 against 1944 for the plain one: the folded renormalisation saves more than the
//! residuals cost). The plain `UnitQuat<Q30>` path stays, bit for bit as before, for callers
//! that need its 4-word state.
//!
//! # Cost
//! The Cortex-M0 has no 32×32 → 64-bit multiply; an `i64` product there is a call of
//! `__aeabi_lmul`. gyrostat forms the exact product from four 16×16-bit `muls` instead (see
//! `real/wide.rs`); the other targets use their widening multiply (`smull`/`smlal` on the M3, M4F
//! and M33, `mul`/`mulh` on RV32IMAC). Products are exact on every target, so the bits are the
//! same everywhere (checked in CI: `examples/fw_fixed.rs` on the five QEMU boards, Cortex-M0,
//! M3, M4F, M33 and RV32IMAC, against the host). Plain `i32`/`i64` was chosen over the `fixed` crate (1.31) by counting
//! instructions: its `I2F30::saturating_mul` compiles on thumbv6m to 71 instructions plus four
//! `__aeabi_lmul` calls, and a quaternion product written with it to 1162 instructions plus 64
//! calls (static counts, `opt-level = 3`), more than the soft-float f32 product; it also
//! truncates products (towards −∞) and, with debug assertions, panics on overflow.
//!
//! Measured cost per call (QEMU guest instructions, `bash benches/icount.sh`):
//!
//! | operation | M0 soft f32 | M0 Q1.30 | M3 soft f32 | M3 Q1.30 | M4F f32 (FPU) | M4F Q1.30 |
//! |---|---:|---:|---:|---:|---:|---:|
//! | quaternion product | 3261 | 606 | 1874 | 175 | 42 | 172 |
//! | 2-sample coning update (rule, exp, product, renormalisation) | 9052 | 1941 | 5143 | 705 | 102 | 702 |
//! | the same, carried ([`CarriedAttitude::coning2_update`](crate::propagation::CarriedAttitude::coning2_update); all six columns from one later image) | 9051 | 1854 | 5150 | 683 | 92 | 670 |
//!
//! # When to choose fixed point
//! On a core without an FPU (Cortex-M0/M0+, M3), for the strapdown attitude update from gyro
//! increments: it is several times cheaper than soft-float f32 there, its step near 1 is 2⁶ to
//! 2⁷ times finer than f32's (2⁻³⁰ against 2⁻²⁴ just below 1 and 2⁻²³ above), and it gives the
//! same bits on the flight computer and on a ground tool replaying the log (`propagate
//! --fixed`). Keep floats for anything with divisions or trigonometry (Euler angles, dynamics),
//! on cores with an FPU (the M4F's hardware f32 is cheaper still), and for rotation vectors or
//! rates beyond the ranges above.
//!
//! ```
//! use gyrostat::sensor::RawScale;
//! use gyrostat::real::Q30;
//! use gyrostat::propagation::kernels::coning2_update;
//! use gyrostat::UnitQuat;
//!
//! // A gyro delivering increments of 2^-20 rad per LSB.
//! let scale = RawScale::<Q30>::try_new(1.0 / 1048576.0)?;
//! let mut q = UnitQuat::<Q30>::IDENTITY;
//! for _ in 0..1000 {
//!     let t1 = scale.apply([1024, 0, 0]); // 2^-10 rad about body x
//!     let t2 = scale.apply([1024, 0, 0]);
//!     q = coning2_update(q, t1, t2);
//! }
//! // 2000 · 2^-10 rad ≈ 1.953 rad about x: cos(θ/2) to within the 1000 updates' roundings
//! // (each exponential is rounded to 2^-31; with a constant input that rounding repeats).
//! let qf = q.to_f64();
//! assert!((qf.w() - (1000.0f64 / 1024.0).cos()).abs() < 1e-6);
//! # Ok::<(), gyrostat::Error>(())
//! ```

mod exp;
pub(crate) mod quantizer;

pub use quantizer::IncrementQuantizer;

#[cfg(doc)]
use crate::Ring;

use crate::real::{Fixed, Q24, Q30};
use crate::{Error, Quat, UnitQuat, Vec3};

impl<const F: u32> Vec3<Fixed<F>> {
    /// Converts each component of an f64 vector (rounded to nearest, ties to even).
    ///
    /// # Errors
    /// [`Error::NonFinite`] or [`Error::OutOfRange`] as [`Fixed::try_from_f64`].
    pub fn try_from_f64(v: Vec3<f64>) -> Result<Self, Error> {
        Ok(Self::new(
            Fixed::try_from_f64(v.x)?,
            Fixed::try_from_f64(v.y)?,
            Fixed::try_from_f64(v.z)?,
        ))
    }

    /// Converts each component of an f32 vector (rounded to nearest, ties to even).
    ///
    /// # Errors
    /// As [`Vec3::try_from_f64`].
    pub fn try_from_f32(v: Vec3<f32>) -> Result<Self, Error> {
        Self::try_from_f64(Vec3::from_array(v.to_array().map(f64::from)))
    }

    /// The exact value as an f64 vector.
    pub fn to_f64(self) -> Vec3<f64> {
        Vec3::new(self.x.to_f64(), self.y.to_f64(), self.z.to_f64())
    }

    /// Rounded to the nearest f32 vector.
    pub fn to_f32(self) -> Vec3<f32> {
        Vec3::new(self.x.to_f32(), self.y.to_f32(), self.z.to_f32())
    }
}

impl<const F: u32> UnitQuat<Fixed<F>> {
    /// Converts a float attitude, rounding each component to nearest (ties to even).
    ///
    /// The result is unit to the format's resolution (`||q|² − 1| ≤ 4·2^−F` from the four
    /// roundings); it is not renormalised, so that converting is the only rounding.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite component (a broken `new_unchecked` promise);
    /// [`Error::OutOfRange`] cannot occur for `F ≤ 30` and a unit input.
    pub fn try_from_f64(q: UnitQuat<f64>) -> Result<Self, Error> {
        let [w, x, y, z] = q.to_array();
        Ok(Self::new_unchecked(Quat::new(
            Fixed::try_from_f64(w)?,
            Fixed::try_from_f64(x)?,
            Fixed::try_from_f64(y)?,
            Fixed::try_from_f64(z)?,
        )))
    }

    /// Converts an f32 attitude (components widened exactly, then as
    /// [`UnitQuat::try_from_f64`]).
    ///
    /// # Errors
    /// As [`UnitQuat::try_from_f64`].
    pub fn try_from_f32(q: UnitQuat<f32>) -> Result<Self, Error> {
        let widened = Quat::from_array(q.to_array().map(f64::from));
        Self::try_from_f64(UnitQuat::new_unchecked(widened))
    }

    /// The exact components as an f64 attitude (not renormalised: unit to the fixed-point
    /// resolution; call [`UnitQuat::renormalize`] for f64-unit norm).
    pub fn to_f64(self) -> UnitQuat<f64> {
        let [w, x, y, z] = self.to_array();
        UnitQuat::new_unchecked(Quat::new(w.to_f64(), x.to_f64(), y.to_f64(), z.to_f64()))
    }

    /// The components rounded to the nearest f32 (not renormalised).
    pub fn to_f32(self) -> UnitQuat<f32> {
        let [w, x, y, z] = self.to_array();
        UnitQuat::new_unchecked(Quat::new(w.to_f32(), x.to_f32(), y.to_f32(), z.to_f32()))
    }

    /// The raw integers `[w, x, y, z]` (each the component times `2^F`): what firmware logs or
    /// sends to compare bit for bit.
    pub fn to_bits(self) -> [i32; 4] {
        self.to_array().map(Fixed::to_bits)
    }
}

/// The increment of a body rate held over a time step: `ω·Δt` from Q7.24 rad/s and a Q1.30
/// step, rounded once to Q1.30 rad (ties to even), saturated at ±2 rad per component.
#[inline]
pub fn increment_from_rate(omega: Vec3<Q24>, dt: Q30) -> Vec3<Q30> {
    Vec3::new(omega.x.mul_to(dt), omega.y.mul_to(dt), omega.z.mul_to(dt))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn rate_times_step() {
        let w = Vec3::<Q24>::try_from_f64(Vec3::new(100.0, -0.5, 3.0)).unwrap();
        let dt = Q30::try_from_f64(1e-3).unwrap();
        let d = increment_from_rate(w, dt).to_f64();
        let dt_q = dt.to_f64();
        assert!((d.x - 100.0 * dt_q).abs() <= 2f64.powi(-31));
        assert!((d.y + 0.5 * dt_q).abs() <= 2f64.powi(-31));
        let big = increment_from_rate(
            Vec3::<Q24>::try_from_f64(Vec3::new(127.0, 0.0, 0.0)).unwrap(),
            Q30::try_from_f64(1.5).unwrap(),
        );
        assert_eq!(big.x, Q30::MAX);
    }
}
