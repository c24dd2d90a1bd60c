//! The floats' scalar layer: [`Ring`] and [`Real`] for f32 and f64, and the f32 math backend
//! (gyrostat's own f32 `sin`/`cos` kernel by default, micromath's approximations with the
//! `micromath` feature). The measured errors are in the [module docs](super).

use super::{Real, Ring};

macro_rules! float_ring {
    ($t:ident, $series:expr) => {
        impl Ring for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const HALF: Self = 0.5;
            const EXP_SERIES_MAX_SQ: Self = $series;
            #[inline]
            fn is_finite(self) -> bool {
                $t::is_finite(self)
            }
            #[inline]
            fn abs(self) -> Self {
                $t::abs(self)
            }
            #[inline]
            fn twice(self) -> Self {
                self + self
            }
            #[inline]
            fn ratio<const N: i32, const D: i32>() -> Self {
                // Rounded once to f64, then to the type, as `from_f64(N as f64 / D as f64)`.
                const { (N as f64 / D as f64) as $t }
            }
            #[inline]
            fn inv_sqrt_near_one(x: Self) -> Self {
                1.0 / Real::sqrt(x)
            }
        }
    };
}

float_ring!(f32, 0.14);
float_ring!(f64, 1.7e-4);

macro_rules! consts {
    ($t:ident, $log:expr) => {
        const TWO: Self = 2.0;
        const PI: Self = core::$t::consts::PI;
        const FRAC_PI_2: Self = core::$t::consts::FRAC_PI_2;
        const EPSILON: Self = $t::EPSILON;
        const LOG_SERIES_MAX_SQ: Self = $log;
    };
}

impl Real for f64 {
    consts!(f64, 8.5e-6);
    #[inline]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
    #[inline]
    fn sin(self) -> Self {
        libm::sin(self)
    }
    #[inline]
    fn cos(self) -> Self {
        libm::cos(self)
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        libm::sincos(self)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        libm::atan2(self, x)
    }
    #[inline]
    fn hypot(self, other: Self) -> Self {
        libm::hypot(self, other)
    }
    #[inline]
    fn floor(self) -> Self {
        libm::floor(self)
    }
    #[inline]
    fn exp(self) -> Self {
        libm::exp(self)
    }
    #[inline]
    fn ln(self) -> Self {
        libm::log(self)
    }
}

impl Real for f32 {
    consts!(f32, 7e-3);
    #[inline]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn sqrt(self) -> Self {
        f32_backend::sqrt(self)
    }
    #[inline]
    fn sin(self) -> Self {
        f32_backend::sin(self)
    }
    #[inline]
    fn cos(self) -> Self {
        f32_backend::cos(self)
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        f32_backend::sin_cos(self)
    }
    #[inline]
    fn sin_cos3(x: [Self; 3]) -> ([Self; 3], [Self; 3]) {
        f32_backend::sin_cos3(x)
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        f32_backend::atan2(self, x)
    }
    #[inline]
    fn hypot(self, other: Self) -> Self {
        f32_backend::hypot(self, other)
    }
    #[inline]
    fn floor(self) -> Self {
        libm::floorf(self)
    }
    #[inline]
    fn exp(self) -> Self {
        libm::expf(self)
    }
    #[inline]
    fn ln(self) -> Self {
        libm::logf(self)
    }
}

/// f32 transcendental functions (default): `sin`/`cos` from gyrostat's own f32 kernel, the rest
/// from libm.
#[cfg(not(feature = "micromath"))]
mod f32_backend {
    #[inline]
    pub fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    #[inline]
    pub fn sin(x: f32) -> f32 {
        super::sincos_f32(x).0
    }
    #[inline]
    pub fn cos(x: f32) -> f32 {
        super::sincos_f32(x).1
    }
    #[inline]
    pub fn sin_cos(x: f32) -> (f32, f32) {
        super::sincos_f32(x)
    }
    /// Four lanes on CPUs with 128-bit SIMD (one kernel evaluation for three angles), three calls
    /// elsewhere (a microcontroller would pay for the unused fourth lane).
    #[inline]
    pub fn sin_cos3(x: [f32; 3]) -> ([f32; 3], [f32; 3]) {
        if cfg!(any(
            target_arch = "x86_64",
            target_arch = "x86",
            target_arch = "aarch64"
        )) {
            let (s, c) = super::sincos_f32_x4([x[0], x[1], x[2], 0.0]);
            ([s[0], s[1], s[2]], [c[0], c[1], c[2]])
        } else {
            let r = x.map(super::sincos_f32);
            (r.map(|p| p.0), r.map(|p| p.1))
        }
    }
    #[inline]
    pub fn atan2(y: f32, x: f32) -> f32 {
        libm::atan2f(y, x)
    }
    #[inline]
    pub fn hypot(a: f32, b: f32) -> f32 {
        libm::hypotf(a, b)
    }
}

/// Largest `|x|` (rad) that [`sincos_f32`] reduces in f32: `k = round(x·2/π)` stays below 2¹²,
/// so `k·P1` and `k·P2` are exact (P1 has 8 and P2 has 12 significant bits). Beyond it, libm's
/// exact reduction takes over.
#[cfg(not(feature = "micromath"))]
const SINCOS_F32_LIMIT: f32 = 6000.0;

/// `(sin x, cos x)` evaluated entirely in f32.
///
/// The `libm` crate's `sinf`/`cosf` (musl's algorithm) evaluate their kernels in f64, which a
/// Cortex-M4F (single-precision FPU) runs in software at about 2000 instructions per call. This
/// kernel stays in f32:
/// - Cody–Waite reduction `r = ((x − k·P1) − k·P2) − k·P3`, `k = round(x·2/π)` (nearest,
///   by adding and subtracting 1.5·2²³), with
///   `P1 + P2 + P3 = π/2` split into 8, 12 and 24 significant bits, so that `|r| ≤ π/4` carries
///   no reduction error beyond the last product's rounding for `|x| ≤` 6000 rad;
/// - `sin r = r + r³(s₁ + r²(s₂ + r² s₃))`, `cos r = 1 − r²/2 + r⁴(c₁ + r²(c₂ + r² c₃))`, with
///   coefficients fitted by gyrostat (weighted least squares iterated towards minimax on
///   `|r| ≤ π/4`): approximation errors 3.8e-9 relative (sin) and 9.5e-11 absolute (cos), far
///   below an f32 ulp, so the result's error is the f32 evaluation's rounding;
/// - the quadrant `k mod 4` swaps and negates the pair (on the bits, no branch).
///
/// Measured against f64 (`real::float::tests`, the figures of the module docs): sin ≤ 8.5e-8 and
/// cos ≤ 9.2e-8 absolute on [−10, 10], both ≤ 1.2e-7 up to 6000 rad. Non-finite input gives NaN
/// (as libm).
#[cfg(not(feature = "micromath"))]
fn sincos_f32(x: f32) -> (f32, f32) {
    if !x.is_finite() || libm::fabsf(x) > SINCOS_F32_LIMIT {
        return libm::sincosf(x);
    }
    let (shifted, s, c) = sincos_f32_reduced(x);
    quadrant(shifted.to_bits(), s, c)
}

/// The in-range part of [`sincos_f32`]: the shifted `x·2/π` (its low bits are the quadrant) and
/// `(sin r, cos r)` of the reduced angle.
#[cfg(not(feature = "micromath"))]
#[inline(always)]
fn sincos_f32_reduced(x: f32) -> (f32, f32, f32) {
    let shifted = x * k::FRAC_2_PI + k::SHIFT;
    let kf = shifted - k::SHIFT;
    let r = ((x - kf * k::P1) - kf * k::P2) - kf * k::P3;
    let r2 = r * r;
    let s = r + r * r2 * (k::S1 + r2 * (k::S2 + r2 * k::S3));
    let c = 1.0 - 0.5 * r2 + r2 * r2 * (k::C1 + r2 * (k::C2 + r2 * k::C3));
    (shifted, s, c)
}

/// The constants of [`sincos_f32_reduced`] and [`sincos_f32_x4`].
#[cfg(not(feature = "micromath"))]
mod k {
    pub const FRAC_2_PI: f32 = core::f32::consts::FRAC_2_PI;
    pub const P1: f32 = 1.570_312_5;
    pub const P2: f32 = 4.838_705e-4; // = 0.000483870506286621093750 exactly (12 bits)
    pub const P3: f32 = -4.371_139e-8;
    pub const S1: f32 = -0.166_666_55;
    pub const S2: f32 = 0.008_332_16;
    pub const S3: f32 = -1.951_528_2e-4;
    pub const C1: f32 = 0.041_666_646;
    pub const C2: f32 = -0.001_388_736_8;
    pub const C3: f32 = 2.443_845e-5;
    /// k = x·2/π rounded to the nearest integer by the 1.5·2²³ shift (exact for
    /// |x·2/π| < 2²²; no libm floorf call, about 20 instructions fewer on a Cortex-M4F); the
    /// shifted value's two lowest mantissa bits are k mod 4.
    pub const SHIFT: f32 = 12_582_912.0;
}

/// [`sincos_f32`] of four angles, lane by lane the same operations (so the same bits, see the
/// test), written statement by statement over the four lanes so that the compiler evaluates them
/// in one SIMD register, with the quadrant selected on the bits. The range check is one integer
/// comparison per lane (`|x|`'s bits above the limit's: also true for NaN and infinity); any
/// lane out of range sends all four through the scalar path. Inlined into its caller: called,
/// the four angles go through memory, stored one by one and loaded as one vector (a failed
/// store-to-load forwarding on x86-64).
///
/// Measured on the Euler → quaternion row of `benches/rotation.rs` (f32, fastest batch, the same
/// machine and run): one scalar chain per lane, called, 15.2 ns until the crate grew (the sensor
/// layer) and the vectoriser then mixed scalar and shuffled vector code, 30.0 ns; statement by
/// statement, called, 17–27 ns; statement by statement, inlined, 17.8 ns; three scalar calls
/// 22 ns.
#[cfg(not(feature = "micromath"))]
#[inline(always)]
fn sincos_f32_x4(x: [f32; 4]) -> ([f32; 4], [f32; 4]) {
    let mut out_of_range = 0u32;
    for v in x {
        out_of_range |= ((v.to_bits() & 0x7fff_ffff) > SINCOS_F32_LIMIT.to_bits()) as u32;
    }
    if out_of_range != 0 {
        let r = x.map(sincos_f32);
        return (r.map(|p| p.0), r.map(|p| p.1));
    }
    // Statement by statement over the four lanes (the operations of `sincos_f32_reduced` and
    // `quadrant_bits`, in their order): each statement is four like operations on adjacent
    // values, one SIMD instruction.
    let shifted = lanes(|i| x[i] * k::FRAC_2_PI + k::SHIFT);
    let kf = lanes(|i| shifted[i] - k::SHIFT);
    let r = lanes(|i| ((x[i] - kf[i] * k::P1) - kf[i] * k::P2) - kf[i] * k::P3);
    let r2 = lanes(|i| r[i] * r[i]);
    let s = lanes(|i| r[i] + r[i] * r2[i] * (k::S1 + r2[i] * (k::S2 + r2[i] * k::S3)));
    let c =
        lanes(|i| 1.0 - 0.5 * r2[i] + r2[i] * r2[i] * (k::C1 + r2[i] * (k::C2 + r2[i] * k::C3)));
    let q = lanes_u32(|i| shifted[i].to_bits());
    let swap = lanes_u32(|i| 0u32.wrapping_sub(q[i] & 1));
    let (sb, cb) = (s.map(f32::to_bits), c.map(f32::to_bits));
    let first = lanes_u32(|i| (sb[i] & !swap[i]) | (cb[i] & swap[i]));
    let second = lanes_u32(|i| (cb[i] & !swap[i]) | (sb[i] & swap[i]));
    (
        lanes(|i| f32::from_bits(first[i] ^ ((q[i] & 2) << 30))),
        lanes(|i| f32::from_bits(second[i] ^ ((q[i].wrapping_add(1) & 2) << 30))),
    )
}

/// `[f(0), f(1), f(2), f(3)]`.
#[cfg(not(feature = "micromath"))]
#[inline(always)]
fn lanes(f: impl Fn(usize) -> f32) -> [f32; 4] {
    [f(0), f(1), f(2), f(3)]
}

/// `[f(0), f(1), f(2), f(3)]` for integer lanes.
#[cfg(not(feature = "micromath"))]
#[inline(always)]
fn lanes_u32(f: impl Fn(usize) -> u32) -> [u32; 4] {
    [f(0), f(1), f(2), f(3)]
}

/// `(sin x, cos x)` from `(s, c) = (sin r, cos r)` and the quadrant `q mod 4` of
/// `x = r + q·π/2`: `(s, c)`, `(c, −s)`, `(−s, −c)`, `(−c, s)`.
///
/// Two forms that select the same values (bit for bit, see the test): on a deep-pipelined host
/// CPU the quadrant of arbitrary angles is unpredictable, and a mispredicted branch cost a third
/// of the kernel's time (11 ns against 6 ns per call on x86-64), so the swap and the sign flips
/// are done on the bits; on a microcontroller a branch costs a cycle or two and moving values
/// between the FPU and the core registers costs more (Cortex-M4F: 78 against 62 instructions per
/// call), so there it is a match.
#[cfg(not(feature = "micromath"))]
#[inline(always)]
fn quadrant(q: u32, s: f32, c: f32) -> (f32, f32) {
    if cfg!(any(
        target_arch = "x86_64",
        target_arch = "x86",
        target_arch = "aarch64"
    )) {
        quadrant_bits(q, s, c)
    } else {
        quadrant_match(q, s, c)
    }
}

/// [`quadrant`] on the bits: swap on odd `q`, then flip the sign bits.
#[cfg(not(feature = "micromath"))]
#[inline(always)]
fn quadrant_bits(q: u32, s: f32, c: f32) -> (f32, f32) {
    let swap = 0u32.wrapping_sub(q & 1);
    let (sb, cb) = (s.to_bits(), c.to_bits());
    let first = (sb & !swap) | (cb & swap);
    let second = (cb & !swap) | (sb & swap);
    (
        f32::from_bits(first ^ ((q & 2) << 30)),
        f32::from_bits(second ^ (((q.wrapping_add(1)) & 2) << 30)),
    )
}

/// [`quadrant`] by a match.
#[cfg(not(feature = "micromath"))]
#[inline(always)]
fn quadrant_match(q: u32, s: f32, c: f32) -> (f32, f32) {
    match q & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// f32 transcendental functions from micromath (feature `micromath`).
#[cfg(feature = "micromath")]
mod f32_backend {
    use micromath::F32Ext;

    /// micromath's estimate refined by two Newton steps `s ← (s + x/s)/2`: the raw estimate is off
    /// by a few percent, each step squares the relative error.
    #[inline]
    pub fn sqrt(x: f32) -> f32 {
        if x <= 0.0 {
            return 0.0;
        }
        let s = F32Ext::sqrt(x);
        let s = 0.5 * (s + x / s);
        0.5 * (s + x / s)
    }
    #[inline]
    pub fn sin(x: f32) -> f32 {
        F32Ext::sin(x)
    }
    #[inline]
    pub fn cos(x: f32) -> f32 {
        F32Ext::cos(x)
    }
    #[inline]
    pub fn sin_cos(x: f32) -> (f32, f32) {
        (F32Ext::sin(x), F32Ext::cos(x))
    }
    #[inline]
    pub fn sin_cos3(x: [f32; 3]) -> ([f32; 3], [f32; 3]) {
        (x.map(F32Ext::sin), x.map(F32Ext::cos))
    }
    /// micromath returns NaN for `(0, 0)`; the trait promises 0 there.
    #[inline]
    pub fn atan2(y: f32, x: f32) -> f32 {
        if y == 0.0 && x == 0.0 {
            0.0
        } else {
            F32Ext::atan2(y, x)
        }
    }
    /// Scaled so that the squares neither overflow nor underflow.
    #[inline]
    pub fn hypot(a: f32, b: f32) -> f32 {
        let (a, b) = (libm::fabsf(a), libm::fabsf(b));
        let m = if a > b { a } else { b };
        if m == 0.0 {
            return 0.0;
        }
        let (ra, rb) = (a / m, b / m);
        m * sqrt(ra * ra + rb * rb)
    }
}

#[cfg(test)]
mod tests {
    //! Measures the active f32 backend against f64 libm. The bounds asserted here are the ones the
    //! module docs state for the active backend.
    extern crate std;
    use super::Real;
    use std::println;

    struct Worst {
        abs: f64,
        rel: f64,
    }

    fn sweep(
        n: usize,
        lo: f64,
        hi: f64,
        f32f: impl Fn(f32) -> f32,
        f64f: impl Fn(f64) -> f64,
    ) -> Worst {
        let mut w = Worst { abs: 0.0, rel: 0.0 };
        for i in 0..=n {
            let x = lo + (hi - lo) * (i as f64) / (n as f64);
            let xf = x as f32;
            let got = f32f(xf) as f64;
            let want = f64f(xf as f64);
            let e = (got - want).abs();
            w.abs = w.abs.max(e);
            if want != 0.0 {
                w.rel = w.rel.max(e / want.abs());
            }
        }
        w
    }

    #[test]
    fn f32_backend_errors() {
        let sqrt = sweep(200_000, 1e-6, 1e4, <f32 as Real>::sqrt, libm::sqrt);
        let sin = sweep(200_000, -10.0, 10.0, <f32 as Real>::sin, libm::sin);
        let cos = sweep(200_000, -10.0, 10.0, <f32 as Real>::cos, libm::cos);
        let mut atan2_abs: f64 = 0.0;
        for i in 0..2000 {
            let t = (i as f64) / 2000.0 * core::f64::consts::TAU;
            for r in [1e-3, 0.5, 1.0, 7.0] {
                let (y, x) = ((r * t.sin()) as f32, (r * t.cos()) as f32);
                let got = <f32 as Real>::atan2(y, x) as f64;
                let want = libm::atan2(y as f64, x as f64);
                let mut e = (got - want).abs();
                if e > core::f64::consts::PI {
                    e = (e - core::f64::consts::TAU).abs();
                }
                atan2_abs = atan2_abs.max(e);
            }
        }
        println!(
            "f32 backend worst errors: sqrt rel {:.2e}, sin abs {:.2e}, cos abs {:.2e}, atan2 abs {:.2e}",
            sqrt.rel, sin.abs, cos.abs, atan2_abs
        );
        if cfg!(feature = "micromath") {
            // The measured values the module docs state (rounded up in the second digit).
            assert!(sqrt.rel <= 1.6e-6, "sqrt rel {}", sqrt.rel);
            assert!(sin.abs <= 1.1e-3, "sin abs {}", sin.abs);
            assert!(cos.abs <= 1.1e-3, "cos abs {}", cos.abs);
            assert!(atan2_abs <= 2.9e-3, "atan2 abs {}", atan2_abs);
        } else {
            // 0.5 ulp of sqrt is 2^-24 relative; 1 ulp of a value in [-1, 1] is at most 2^-23 ≈ 1.2e-7;
            // 2 ulp of a value in [-π, π] is at most 2·2^-22 ≈ 4.8e-7.
            assert!(sqrt.rel <= 6.0e-8, "sqrt rel {}", sqrt.rel);
            assert!(sin.abs <= 1.2e-7, "sin abs {}", sin.abs);
            assert!(cos.abs <= 1.2e-7, "cos abs {}", cos.abs);
            assert!(atan2_abs <= 4.8e-7, "atan2 abs {}", atan2_abs);
            // The measured values stated in the module docs.
            assert!(sin.abs <= 8.5e-8 && cos.abs <= 9.2e-8 && atan2_abs <= 2.2e-7);
        }
    }

    /// The f32-native kernel over its whole reduced range and across the libm fallback.
    #[cfg(not(feature = "micromath"))]
    #[test]
    fn sincos_f32_kernel_wide_range() {
        let sin = sweep(400_000, -6000.0, 6000.0, <f32 as Real>::sin, libm::sin);
        let cos = sweep(400_000, -6000.0, 6000.0, <f32 as Real>::cos, libm::cos);
        let far = sweep(1000, 6000.0, 1e6, <f32 as Real>::sin, libm::sin);
        let tiny = sweep(1000, -1e-6, 1e-6, <f32 as Real>::sin, libm::sin);
        println!(
            "sincos_f32: |x| <= 6000: sin {:.2e}, cos {:.2e}; libm beyond: {:.2e}; tiny rel {:.2e}",
            sin.abs, cos.abs, far.abs, tiny.rel
        );
        assert!(
            sin.abs <= 1.2e-7 && cos.abs <= 1.2e-7,
            "{} {}",
            sin.abs,
            cos.abs
        );
        assert!(far.abs <= 1.2e-7);
        assert!(tiny.rel <= 6.0e-8);
        let (s, c) = super::sincos_f32(f32::NAN);
        assert!(s.is_nan() && c.is_nan());
    }

    /// The two quadrant selections of the f32 kernel give the same bits for every quadrant,
    /// signed zeros included (the firmware uses one, a host the other).
    #[cfg(not(feature = "micromath"))]
    #[test]
    fn sincos_f32_quadrant_forms_agree() {
        for q in 0u32..8 {
            for (s, c) in [(0.3f32, 0.95), (-0.0, 1.0), (0.0, -0.0), (-0.7, 0.7)] {
                let (a, b) = super::quadrant_bits(q, s, c);
                let (x, y) = super::quadrant_match(q, s, c);
                assert_eq!(
                    (a.to_bits(), b.to_bits()),
                    (x.to_bits(), y.to_bits()),
                    "{q}"
                );
            }
        }
    }

    /// `sin_cos3` (four SIMD lanes on host CPUs) gives the bits of three `sin_cos` calls, for
    /// angles over the kernel's whole range, mixed with out-of-range and non-finite lanes.
    #[test]
    fn sin_cos3_equals_three_calls_bit_for_bit() {
        fn check<T: Real>(x: [T; 3], bits: impl Fn(T) -> u64) {
            let (s, c) = T::sin_cos3(x);
            for i in 0..3 {
                let (si, ci) = x[i].sin_cos();
                assert_eq!((bits(s[i]), bits(c[i])), (bits(si), bits(ci)), "{:?}", x);
            }
        }
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let special = [7000.0f64, -1e30, f64::NAN, f64::INFINITY, 0.0, -0.0];
        for n in 0..300_000 {
            let mut x = [0.0f64; 3];
            for v in &mut x {
                let r = next();
                // Mostly half angles of Euler angles, some over the whole kernel range.
                let u = (r >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
                *v = if r & 7 == 0 { u * 6000.0 } else { u * 3.2 };
            }
            if n % 1000 == 0 {
                x[n / 1000 % 3] = special[n / 3000 % special.len()];
            }
            check(x.map(|v| v as f32), |v: f32| v.to_bits() as u64);
            check(x, f64::to_bits);
        }
    }

    #[test]
    fn min_max_copysign_do_not_depend_on_nan_semantics() {
        assert_eq!(super::Ring::min(1.0f32, 2.0), 1.0);
        assert_eq!(super::Ring::max(1.0f64, 2.0), 2.0);
        assert_eq!(Real::copysign(3.0f32, -0.5), -3.0);
        assert_eq!(Real::copysign(-3.0f64, 0.0), 3.0);
        assert_eq!(Real::atan2(0.0f32, 0.0), 0.0);
    }
}
