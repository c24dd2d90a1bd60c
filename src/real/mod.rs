//! The scalar layer: two narrow, sealed traits, [`Ring`] and [`Real`], and their
//! implementations for f32, f64 and the fixed-point [`crate::real::Fixed`].
//!
//! This is the bottom of the crate: it depends on nothing else in it. Vectors, quaternions and
//! everything built on them (the exponential map's per-type kernels included) live in the layers
//! above and are generic over these traits.
//!
//! Every algorithm in gyrostat is generic over one of them, and each holds exactly the operations
//! the library needs, so that a Q-format fixed-point type can implement what it can honestly (no
//! `unimplemented!()` bodies), and so that f32 is a first-class citizen rather than an
//! afterthought of f64.
//!
//! - [`Ring`]: `+ − ×`, negation, comparisons, `0`, `1`, `½`, exact ratios of small integers,
//!   sums of products rounded once ([`Ring::dot`]), and the one per-type kernel a unit
//!   quaternion needs beyond a polynomial, the inverse square root of a norm near one.
//!   Implemented for f32, f64 and the fixed-point [`crate::real::Fixed`] (saturating, see
//!   [`crate::fixed`]). Everything on the attitude hot path is generic over `Ring`: `Vec3`/`Quat`
//!   arithmetic, the quaternion product, vector rotation, the rotation matrix, renormalisation,
//!   the coning rules and the two-speed accumulator; the exponential map and the increment
//!   integrator add the rotation layer's per-type kernels ([`crate::rotation::ExpMap`]).
//! - [`Real`]` : Ring`: division, square root, trigonometry, `exp`/`ln`, `2`, `π`, the machine
//!   epsilon, conversions from and to f64. Implemented for f32 and f64. Everything else (Euler
//!   angles, the log map, dynamics, elliptic functions) is generic over `Real`.
//!
//! Rules the library follows so that a non-IEEE type can implement [`Ring`]:
//! - no logic relies on NaN or infinity propagating; finiteness is asked through
//!   [`Ring::is_finite`] and inputs are validated up front;
//! - comparisons go through `PartialOrd` and the trait's `min`/`max`/`abs`;
//! - constants are associated consts or exact ratios ([`Ring::ratio`], evaluated at compile
//!   time), all within `[−2, 2)`; no constant is built at run time from a float;
//! - series thresholds are associated consts per type ([`Ring::EXP_SERIES_MAX_SQ`]), never
//!   derived from the machine epsilon at run time.
//!
//! # Math backend
//! f64 uses [`libm`] (a port of musl's libm). f32 uses libm for `sqrt`, `atan2`, `hypot`,
//! `floor`, `exp`, `ln`, and gyrostat's own f32 kernel for `sin`/`cos` (see `sincos_f32` in
//! this file): libm's `sinf`/`cosf` evaluate in f64, which costs about 2000 instructions per call
//! on a Cortex-M4F whose FPU is single-precision only; the f32 kernel costs about 70 there
//! (BENCHMARKS.md) for an error below one f32 ulp at 1.0. With the `micromath` feature, the f32
//! `sqrt`, `sin`, `cos`, `sin_cos` and `atan2` switch to micromath's fast approximations; f64
//! keeps libm, and `floor`, `exp`, `ln` always come from libm. Worst errors, measured by this
//! module's unit tests (`cargo test -p gyrostat --lib --release [--features micromath] real::`)
//! against f64 libm over dense sweeps:
//!
//! | function | f32 default                        | micromath f32                    |
//! |----------|------------------------------------|----------------------------------|
//! | `sqrt`   | 6.0e-8 relative (libm, 0.5 ulp)    | 1.6e-6 relative (Newton-refined, see below) |
//! | `sin`    | 8.5e-8 absolute (f32 kernel)       | 1.1e-3 absolute                  |
//! | `cos`    | 9.2e-8 absolute (f32 kernel)       | 1.1e-3 absolute                  |
//! | `atan2`  | 2.2e-7 rad (libm)                  | 2.9e-3 rad                       |
//!
//! (sweeps: `sqrt` on [1e-6, 1e4], `sin`/`cos` on [−10, 10] (and ≤ 1.2e-7 on [−6000, 6000]),
//! `atan2` around circles of radius 1e-3 … 7; the tests assert these bounds for the active
//! backend.)
//!
//! micromath's own `sqrt` is a bit-trick estimate with errors of several percent, which would
//! wreck quaternion normalisation; gyrostat therefore refines it with two Newton steps before use
//! and states the refined error above. The micromath backend suits display and coarse control
//! loops; it cannot meet the accuracy contract of the `rotation` module, whose tests run on the
//! default backend.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

pub(crate) mod fixed;
mod float;
pub(crate) mod wide;

pub use fixed::{Fixed, Q24, Q30};

pub(crate) mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
    impl<const F: u32> Sealed for super::fixed::Fixed<F> {}
}

/// The ring layer: what the attitude hot path needs, implemented for f32, f64 and the
/// fixed-point [`crate::real::Fixed`].
///
/// Arithmetic is IEEE for the floats and saturating, round-to-nearest (ties to even) for fixed
/// point (see [`crate::fixed`]). Sealed: only gyrostat implements it, so that the library can
/// rely on every method being exact or documented-accurate for every implementer.
pub trait Ring:
    sealed::Sealed
    + Copy
    + Debug
    + Default
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + 'static
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 1/2.
    const HALF: Self;
    /// The largest squared angle `θ²` for which the exponential map's series
    /// `cos(θ/2) ≈ 1 − θ²/8 + θ⁴/384`, `sin(θ/2)/θ ≈ ½ − θ²/48 + θ⁴/3840` is accurate to the
    /// type's rounding: the first dropped term, `θ⁶/46080` (relative, for the cosine), stays below
    /// half a unit in the last place. f32 (ε = 2⁻²³): `θ² ≤ (23040 ε)^{1/3}` rounded down, 0.14
    /// (θ ≤ 0.37 rad); f64 (ε = 2⁻⁵²): 1.7e-4 (θ ≤ 0.013 rad); Q1.30 (absolute resolution
    /// 2⁻³⁰): 1/64 (θ ≤ 1/8 rad, dropped term ≤ 8.3e-11 < 2⁻³¹).
    const EXP_SERIES_MAX_SQ: Self;

    /// `true` unless the value is NaN or ±∞ (always `true` for fixed point).
    fn is_finite(self) -> bool;
    /// Absolute value.
    fn abs(self) -> Self;
    /// The smaller of two values.
    #[inline]
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }
    /// The larger of two values.
    #[inline]
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }
    /// `2·self`: exact for the floats (`self + self`), saturating for fixed point.
    fn twice(self) -> Self;
    /// The ratio `N/D` of two integers, rounded to nearest, evaluated at compile time. A ratio
    /// outside the type's range (for fixed point: `|N/D| ≥ 2` in Q1.30) is a compile-time error.
    fn ratio<const N: i32, const D: i32>() -> Self;
    /// The sum of products `a₀b₀ + a₁b₁ + …` (1 to 4 terms), left to right.
    ///
    /// The floats round every product and every sum, exactly as the written-out expression.
    /// Fixed point forms every product exactly in 64 bits, accumulates them and rounds once, so
    /// that a quaternion product or a cross product costs one rounding per component.
    #[inline]
    fn dot<const N: usize>(a: [Self; N], b: [Self; N]) -> Self {
        // Over references, not `into_iter()`: the by-value array iterator kept its index range in
        // memory, and the f32 exponential map took 34 instead of 9 ns on x86-64 (stores and loads
        // of different widths). The first product, then the others added left to right.
        let mut products = a.iter().zip(b.iter()).map(|(x, y)| *x * *y);
        let first = products.next().unwrap_or(Self::ZERO);
        products.fold(first, |s, p| s + p)
    }
    /// `true` when [`Ring::dot`] of `a` and `b` is within the type's range: always for the
    /// floats (an overflow there is an infinity, which the finiteness checks catch); for fixed
    /// point, whether the exact sum needs no saturation. The checked entry points use it to
    /// return [`crate::Error::OutOfRange`] where a fixed-point sum would otherwise saturate.
    #[inline]
    fn dot_fits<const N: usize>(a: [Self; N], b: [Self; N]) -> bool {
        let _ = (a, b);
        true
    }
    /// `1/√x` for `x` near one (the squared norm of a drifting unit quaternion): the scale of
    /// [`crate::UnitQuat::renormalize`]. The floats compute `1/√x` for any positive `x`; fixed
    /// point iterates Newton steps and is accurate for `x ∈ (½, 2)`.
    fn inv_sqrt_near_one(x: Self) -> Self;
}

/// The scalar type of every gyrostat algorithm outside the ring layer: implemented for f32 and
/// f64.
///
/// Sealed: only gyrostat implements it, so that the library can rely on every method being exact
/// or documented-accurate for every implementer.
pub trait Real: Ring + Div<Output = Self> + DivAssign {
    /// 2.
    const TWO: Self;
    /// π.
    const PI: Self;
    /// π/2.
    const FRAC_PI_2: Self;
    /// The machine epsilon: the distance from 1 to the next representable value.
    const EPSILON: Self;
    /// The largest `s² = |v|²` (sine of the half angle, squared) for which the logarithm map's
    /// series `2·asin(s)/s ≈ 2(1 + s²/6 + 3s⁴/40)` is accurate to rounding: the dropped
    /// `15 s⁶/336` stays below ε/2. f32: 7e-3 (dropped term ≤ 1.5e-8); f64: 8.5e-6
    /// (≤ 2.7e-17).
    const LOG_SERIES_MAX_SQ: Self;

    /// Converts an f64 literal or reference value, rounding to nearest.
    fn from_f64(x: f64) -> Self;
    /// Widens to f64 (exact for f32 and f64).
    fn to_f64(self) -> f64;

    /// `self` with the sign of `sign` (a zero `sign` counts as positive).
    #[inline]
    fn copysign(self, sign: Self) -> Self {
        if sign < Self::ZERO {
            -self.abs()
        } else {
            self.abs()
        }
    }
    /// Square root; the argument must be non-negative (negative input is the caller's bug and
    /// returns an unspecified value, never a panic).
    fn sqrt(self) -> Self;
    /// Sine of an angle in radians.
    fn sin(self) -> Self;
    /// Cosine of an angle in radians.
    fn cos(self) -> Self;
    /// `(sin, cos)` of an angle in radians, in one call where the backend can share work.
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    /// `([sin xᵢ], [cos xᵢ])` of three angles, bit for bit the values of three
    /// [`Real::sin_cos`] calls; a backend may evaluate the three side by side (f32 on host CPUs
    /// does, in SIMD lanes).
    #[inline]
    fn sin_cos3(x: [Self; 3]) -> ([Self; 3], [Self; 3]) {
        let r = x.map(Self::sin_cos);
        (r.map(|p| p.0), r.map(|p| p.1))
    }
    /// Four-quadrant arctangent of `self / x` in `[-π, π]`; `atan2(0, 0) = 0`.
    fn atan2(self, x: Self) -> Self;
    /// `sqrt(self² + other²)` without undue overflow or underflow.
    fn hypot(self, other: Self) -> Self;
    /// The largest integer value not greater than `self`.
    fn floor(self) -> Self;
    /// `e^self`.
    fn exp(self) -> Self;
    /// Natural logarithm; the argument must be positive (else an unspecified value, no panic).
    fn ln(self) -> Self;
}
