//! Elliptic integrals and Jacobi elliptic functions, `no_std`, allocation-free, panic-free.
//!
//! These are the special functions of the exact torque-free rigid body
//! ([`crate::dynamics::closed_form::free_rigid_body`]): the body momentum is a triple `(cn, sn, dn)` of Jacobi
//! functions (Landau & Lifshitz, *Mechanics*, §37) and the attitude angle about the fixed lab
//! momentum is an incomplete elliptic integral of the third kind.
//!
//! # Conventions
//! The **parameter** `m = k²` is used throughout (Abramowitz & Stegun ch. 16–17; DLMF 22.2 with
//! `k² = m`), never the modulus `k` or the modular angle:
//! - `K(m) = ∫₀^{π/2} dθ / √(1 − m sin²θ)` ([`complete_k`]);
//! - `F(φ|m) = ∫₀^φ dθ / √(1 − m sin²θ)` ([`incomplete_f`]), and the amplitude `φ = am(u|m)` is
//!   its inverse;
//! - `sn u = sin φ`, `cn u = cos φ`, `dn u = √(1 − m sn² u)` ([`sn_cn_dn`]);
//! - `Π(n; φ|m) = ∫₀^φ dθ / ((1 − n sin²θ) √(1 − m sin²θ))` ([`incomplete_pi`]; A&S 17.2.14
//!   sign convention, so `n < 0` has no pole).
//!
//! # Algorithms
//! - `K(m)`: the arithmetic–geometric mean, `K = π / (2·AGM(1, √(1 − m)))` (A&S 17.6).
//! - `sn, cn, dn`: the descending Landen (AGM) scheme of A&S 16.4: the AGM sequence
//!   `aₙ, bₙ, cₙ` is run to convergence, `φ_N = 2^N a_N u`, and the amplitude is recovered by
//!   `φₙ₋₁ = (φₙ + arcsin((cₙ/aₙ) sin φₙ))/2` with the arcsine evaluated as an `atan2`. The
//!   argument is first reduced to `|u| ≤ K` with the quasi-periodicity
//!   `am(u + 2K) = am(u) + π`, so accuracy does not decay with the number of periods spanned
//!   beyond the rounding of the reduction itself. `dn` is formed as `√(cn² + (1 − m) sn²)`,
//!   a sum of non-negative terms (no cancellation even for `m → 1`).
//! - `F` and `Π`: Carlson's symmetric integrals `R_F`, `R_J` (and `R_C`) by the duplication
//!   theorem (B. C. Carlson, "Numerical computation of real or complex elliptic integrals",
//!   *Numer. Algorithms* 10 (1995) 13–26; DLMF 19.25.5, 19.25.14, 19.36), with the 5th/6th-order
//!   Taylor terms of that paper and a stopping test chosen so the truncation is below machine
//!   epsilon of the type.
//!
//! Every loop has a fixed iteration cap (the AGM converges quadratically, Carlson's duplication
//! divides the spread by 4 per step), so the cost is bounded for every input.
//!
//! # Accuracy (measured)
//! `cargo test --release -p host-tests --test dynamics elliptic:: -- --nocapture` compares against
//! an independent f64 reference (Gauss–Legendre quadrature of the defining integrals, Jacobi
//! functions by bisection/Newton inversion of `F`, in `host-tests/src/ref_exact.rs`) over
//! `m ∈ {0, 10⁻⁶, 0.1, 0.5, 0.8, 0.9, 0.99, 0.9999, 1 − 10⁻⁶}` and `|u| ≤ 4K(m)`, and `K` against
//! 30-digit values (mpmath):
//!
//! | quantity                                   | f64        | f32      |
//! |--------------------------------------------|------------|----------|
//! | `K(m)`, relative                            | ≤ 4e-16 (vs 30-digit values) | 1.3e-7 |
//! | `sn, cn, dn`, absolute                      | 2.4e-13    | 2.6e-6   |
//! | `F(φ|m)`, relative / (1 + condition number) | 6.4e-15 (reference-limited) | 1.1e-7 |
//! | `Π(n; φ|m)`, relative (n ∈ [−30, 0.999])    | 4.8e-15    | —        |
//! | `sn² + cn² − 1`, `dn² + m sn² − 1`          | 3.3e-16    | 1.6e-7   |
//!
//! The `sn, cn, dn` error is dominated by `m = 1 − 10⁻⁶`, `|u| ≈ 4K ≈ 33`: it grows like
//! `ε·|u|` (the reduction `u − 2kK` rounds) times the slope of the functions, which is as large
//! as `1/√(1 − m)`-scaled near the separatrix; for `m ≤ 0.99` it is below 1e-14 (f64).

//! # Errors
//! Non-finite arguments give [`Error::NonFinite`]; a parameter outside the documented domain
//! gives [`Error::InvalidArgument`]. No function panics or returns NaN for any input.
//!
//! # Domain of the arguments
//! The periodic reductions (`u − 2kK`, `φ − kπ`) are exact only while the argument's own
//! rounding is small against the period: an argument of magnitude `x` is known to `ε·x`, so
//! beyond `1/ε` (8.4e6 in f32, 4.5e15 in f64) not even its quarter period is determined, and
//! the product `k·2K` can overflow. [`sn_cn_dn`] (for `m < 1`), [`amplitude`], [`incomplete_f`]
//! and [`incomplete_pi`] reject `|u|`, `|φ|` beyond `1/ε` with [`Error::InvalidArgument`].
//! Carlson's integrals are homogeneous (`R_F(λx, λy, λz) = λ^{−1/2} R_F(x, y, z)`), so
//! [`carlson_rf`] and [`carlson_rj`] evaluate on arguments scaled by a power of two to a
//! largest value of order one (exact) and scale back: any finite arguments in their domain,
//! `R_J` giving [`Error::InvalidArgument`] only when its value overflows the type.

use crate::{Error, Real};

/// Iteration cap of the AGM / descending Landen scheme.
///
/// The AGM converges quadratically once `cₙ/aₙ < 1/2`; starting from `b₀ = √(1 − m)` as small as
/// the smallest positive f64 (≈ 1e-154 after the square root of a subnormal-free `1 − m`) it needs
/// about 12 steps to reach f64 rounding, so 24 is a safe cap for both f32 and f64.
const AGM_MAX_STEPS: usize = 24;

/// Iteration cap of Carlson's duplication loops.
///
/// Each duplication divides the relative spread of the arguments by 4. The stopping threshold
/// (see [`carlson_tolerance`]) is ≥ 6e-4; from a spread of 1 that takes 6 steps, and arguments
/// that differ by a factor 10³⁰⁰ need about 250/ln 4·… in practice ≤ 40. 64 covers every finite
/// f64 input ratio this module produces (`R_F(cos²φ, dn², 1)` with `dn² ≥ 1 − m`).
const CARLSON_MAX_STEPS: usize = 64;

/// The stopping threshold of Carlson's duplication: `½·ε^{1/6}` for the type's epsilon `ε`.
///
/// The truncation error of the series after stopping is of order `tol⁶` (Carlson 1995), so `(½ ε^{1/6})⁶ = ε/64`, below the type's rounding: 1.2e-3 for f64, 3.5e-2 for f32.
fn carlson_tolerance<T: Real>() -> T {
    (T::EPSILON.ln() * T::from_f64(1.0 / 6.0)).exp() * T::HALF
}

/// Checks that an argument to be reduced by a period is finite and at most `1/ε` in magnitude
/// (see the module docs).
fn check_argument<T: Real>(x: T) -> Result<(), Error> {
    if !x.is_finite() {
        return Err(Error::NonFinite);
    }
    if x.abs() > T::ONE / T::EPSILON {
        return Err(Error::InvalidArgument);
    }
    Ok(())
}

/// A power of two `s` with `x/s` in `[1, 2)`, for a finite `x > 0` whose scale is representable
/// (every normal value and most subnormals), built from exact multiplications by the squares
/// `2, 4, 16, 256, …` of two: dividing by it changes no digit of `x` (or of anything scaled
/// with it).
pub(crate) fn pow2_scale<T: Real>(x: T) -> T {
    // 2^(2^k) for k = 0, 1, …, as long as finite: 7 factors in f32, 10 in f64.
    let mut factors = [T::ONE; 11];
    let mut n = 0;
    let mut f = T::TWO;
    for slot in factors.iter_mut() {
        if !f.is_finite() {
            break;
        }
        *slot = f;
        n += 1;
        f = f * f;
    }
    let (mut y, mut s) = (x, T::ONE);
    // Greedy on the binary digits of the exponent, largest first.
    for &f in factors.iter().take(n).rev() {
        if y >= f {
            y /= f;
            s *= f;
        }
    }
    for &f in factors.iter().take(n).rev() {
        if y * f < T::TWO {
            y *= f;
            s /= f;
        }
    }
    s
}

/// Checks `m` is finite and in `[0, 1)`.
fn check_parameter<T: Real>(m: T) -> Result<(), Error> {
    if !m.is_finite() {
        return Err(Error::NonFinite);
    }
    if m < T::ZERO || m >= T::ONE {
        return Err(Error::InvalidArgument);
    }
    Ok(())
}

/// `arcsin(x)` for `|x| ≤ 1` as an `atan2` (no loss of accuracy near `|x| = 1`).
#[inline]
fn asin_atan2<T: Real>(x: T) -> T {
    let c = ((T::ONE - x) * (T::ONE + x)).max(T::ZERO).sqrt();
    x.atan2(c)
}

/// The result of the AGM run shared by [`complete_k`] and [`sn_cn_dn`].
struct Agm<T> {
    /// `cₙ / aₙ` for `n = 1..=steps` (index `n − 1`).
    ratios: [T; AGM_MAX_STEPS],
    /// Number of AGM steps taken.
    steps: usize,
    /// `a_N`, the AGM of `1` and `√(1 − m)`.
    a: T,
    /// `2^N`.
    two_pow: T,
}

/// Runs the AGM of `(1, √m₁)` with `c₀ = √m`, recording `cₙ/aₙ` (A&S 16.4.2, 17.6.1).
fn agm<T: Real>(m: T, m1: T) -> Agm<T> {
    let mut ratios = [T::ZERO; AGM_MAX_STEPS];
    let mut a = T::ONE;
    let mut b = m1.max(T::ZERO).sqrt();
    let mut c = m.max(T::ZERO).sqrt();
    let mut steps = 0;
    let mut two_pow = T::ONE;
    // Stop when cₙ is below one ulp of aₙ: the next step would change nothing representable.
    let tol = T::EPSILON;
    for slot in ratios.iter_mut() {
        if c <= tol * a {
            break;
        }
        let a_next = (a + b) * T::HALF;
        let b_next = (a * b).sqrt();
        c = (a - b) * T::HALF;
        a = a_next;
        b = b_next;
        *slot = c / a;
        steps += 1;
        two_pow *= T::TWO;
    }
    Agm {
        ratios,
        steps,
        a,
        two_pow,
    }
}

/// The complete elliptic integral of the first kind `K(m)`, `m ∈ [0, 1)`, by the AGM:
/// `K(m) = π / (2·AGM(1, √(1 − m)))` (A&S 17.6.1).
///
/// `K(0) = π/2`; `K` grows like `½ ln(16/(1 − m))` as `m → 1`.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite `m`; [`Error::InvalidArgument`] for `m < 0` or `m ≥ 1`
/// (`K(1)` is infinite).
///
/// ```
/// use gyrostat::dynamics::closed_form::elliptic::complete_k;
/// assert!((complete_k(0.0f64)? - core::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// // K(1/2) = Γ(1/4)² / (4√π)
/// assert!((complete_k(0.5f64)? - 1.854_074_677_301_372).abs() < 1e-15);
/// assert!(complete_k(1.0f32).is_err());
/// # Ok::<(), gyrostat::Error>(())
/// ```
pub fn complete_k<T: Real>(m: T) -> Result<T, Error> {
    check_parameter(m)?;
    Ok(complete_k_unchecked(m, T::ONE - m))
}

/// `K(m)` given `m` and `m₁ = 1 − m` (callers that know `m₁` more accurately than `1 − m` pass
/// it), no domain check; `m₁ > 0`.
pub(crate) fn complete_k_unchecked<T: Real>(m: T, m1: T) -> T {
    let g = agm(m, m1);
    T::FRAC_PI_2 / g.a
}

/// `(φ, sn, cn, dn)` with `φ = am(u)` at a reduced argument `|u| ≤ K`, by the descending Landen
/// scheme: `φ_N = 2^N a_N u`, then `φ_{n−1} = (φ_n + asin(c_n/a_n · sin φ_n))/2`.
fn landen_reduced<T: Real>(u: T, m1: T, g: &Agm<T>) -> (T, T, T, T) {
    let mut phi = g.two_pow * g.a * u;
    let mut n = g.steps;
    while n > 0 {
        n -= 1;
        let r = match g.ratios.get(n) {
            Some(r) => *r,
            None => T::ZERO,
        };
        phi = (phi + asin_atan2(r * phi.sin())) * T::HALF;
    }
    let (sn, cn) = phi.sin_cos();
    let dn = (cn * cn + m1 * sn * sn).sqrt();
    (phi, sn, cn, dn)
}

/// `(sn, cn, dn)` at a reduced argument `|u| ≤ K`.
fn sn_cn_dn_reduced<T: Real>(u: T, m1: T, g: &Agm<T>) -> (T, T, T) {
    let (_, sn, cn, dn) = landen_reduced(u, m1, g);
    (sn, cn, dn)
}

/// Reduces `u` to `u − 2kK ∈ [−K, K]`; returns `(u_r, k, k odd)`.
fn reduce<T: Real>(u: T, k_complete: T) -> (T, T, bool) {
    let two_k = k_complete * T::TWO;
    let k = (u / two_k + T::HALF).floor();
    let ur = u - k * two_k;
    let half = (k * T::HALF).floor();
    let odd = k - half * T::TWO != T::ZERO;
    (ur, k, odd)
}

/// `sech u` and `tanh u` without overflow (for the `m = 1` limit).
pub(crate) fn sech_tanh<T: Real>(u: T) -> (T, T) {
    let e = (-(u.abs()) * T::TWO).exp(); // e^{-2|u|} ∈ (0, 1]
    let tanh = ((T::ONE - e) / (T::ONE + e)).copysign(u);
    let sech = T::TWO * (-(u.abs())).exp() / (T::ONE + e);
    (sech, tanh)
}

/// Jacobi elliptic functions `(sn u, cn u, dn u)` for parameter `m ∈ [0, 1]`.
///
/// Descending Landen / AGM scheme (A&S 16.4) after reduction of `u` by the quasi-period `2K`;
/// the `m = 1` limit is the hyperbolic one, `sn = tanh u`, `cn = dn = sech u` (A&S 16.6).
/// Accuracy: see the [module docs](self).
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite `u` or `m`; [`Error::InvalidArgument`] for `m < 0` or
/// `m > 1`, or `|u| > 1/ε` with `m < 1` (see the module docs).
///
/// ```
/// use gyrostat::dynamics::closed_form::elliptic::{complete_k, sn_cn_dn};
/// let m = 0.7f64;
/// let (sn, cn, dn) = sn_cn_dn(complete_k(m)?, m)?;
/// assert!((sn - 1.0).abs() < 1e-14 && cn.abs() < 1e-14 && (dn - (1.0 - m).sqrt()).abs() < 1e-14);
/// # Ok::<(), gyrostat::Error>(())
/// ```
pub fn sn_cn_dn<T: Real>(u: T, m: T) -> Result<(T, T, T), Error> {
    if !u.is_finite() || !m.is_finite() {
        return Err(Error::NonFinite);
    }
    if m < T::ZERO || m > T::ONE {
        return Err(Error::InvalidArgument);
    }
    if m == T::ONE {
        let (sech, tanh) = sech_tanh(u);
        return Ok((tanh, sech, sech));
    }
    check_argument(u)?;
    Ok(sn_cn_dn_unchecked(u, m, T::ONE - m))
}

/// `(sn, cn, dn)` for `m ∈ [0, 1)` given `m₁ = 1 − m > 0`; no domain checks.
pub(crate) fn sn_cn_dn_unchecked<T: Real>(u: T, m: T, m1: T) -> (T, T, T) {
    let g = agm(m, m1);
    let kc = T::FRAC_PI_2 / g.a;
    let (ur, _, odd) = reduce(u, kc);
    let (sn, cn, dn) = sn_cn_dn_reduced(ur, m1, &g);
    if odd { (-sn, -cn, dn) } else { (sn, cn, dn) }
}

/// The Jacobi amplitude `am(u|m)`, continuous and increasing in `u` (not wrapped to
/// `[−π, π]`): `am(u + 2K) = am(u) + π`. `m ∈ [0, 1)`; `sn = sin am`, `cn = cos am`.
///
/// # Errors
/// As [`complete_k`], plus [`Error::NonFinite`] for a non-finite `u` and
/// [`Error::InvalidArgument`] for `|u| > 1/ε` (see the module docs).
pub fn amplitude<T: Real>(u: T, m: T) -> Result<T, Error> {
    check_parameter(m)?;
    check_argument(u)?;
    let (phi, _, _, _) = amplitude_unchecked(u, m, T::ONE - m);
    Ok(phi)
}

/// `(am u, sn u, cn u, dn u)` for `m ∈ [0, 1)`, `m₁ = 1 − m`; no checks. The amplitude is
/// returned as `(k·π + φ_r)` with `|φ_r| ≤ π/2`, in two parts `(k, φ_r)` folded into the first
/// element; the parts are also available through [`amplitude_parts`].
pub(crate) fn amplitude_unchecked<T: Real>(u: T, m: T, m1: T) -> (T, T, T, T) {
    let (k, phi_r, sn, cn, dn) = amplitude_parts(u, m, m1);
    (k * T::PI + phi_r, sn, cn, dn)
}

/// `(k, φ_r, sn, cn, dn)` with `am(u) = k·π + φ_r`, `|φ_r| ≤ π/2`; `m ∈ [0, 1)`, no checks.
pub(crate) fn amplitude_parts<T: Real>(u: T, m: T, m1: T) -> (T, T, T, T, T) {
    let g = agm(m, m1);
    let kc = T::FRAC_PI_2 / g.a;
    let (ur, k, odd) = reduce(u, kc);
    let (phi, sn_r, cn_r, dn) = landen_reduced(ur, m1, &g);
    let (sn, cn) = if odd { (-sn_r, -cn_r) } else { (sn_r, cn_r) };
    (k, phi, sn, cn, dn)
}

/// Carlson's symmetric integral of the first kind
/// `R_F(x, y, z) = ½ ∫₀^∞ dt / √((t + x)(t + y)(t + z))` (DLMF 19.16.1), by duplication
/// (Carlson 1995; DLMF 19.36.1 for the series).
///
/// # Errors
/// [`Error::NonFinite`] for non-finite input; [`Error::InvalidArgument`] if an argument is
/// negative or more than one is zero.
pub fn carlson_rf<T: Real>(x: T, y: T, z: T) -> Result<T, Error> {
    if !(x.is_finite() && y.is_finite() && z.is_finite()) {
        return Err(Error::NonFinite);
    }
    if x < T::ZERO || y < T::ZERO || z < T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let zeros = [x, y, z].iter().filter(|v| **v == T::ZERO).count();
    if zeros > 1 {
        return Err(Error::InvalidArgument);
    }
    // Homogeneity: R_F(x, y, z) = R_F(x/s, y/s, z/s)/√s, s an exact power of two.
    let s = pow2_scale(x.max(y).max(z));
    let r = rf_unchecked(x / s, y / s, z / s) / s.sqrt();
    if r.is_finite() {
        Ok(r)
    } else {
        Err(Error::InvalidArgument)
    }
}

/// `R_F` without checks (arguments ≥ 0, at most one zero).
pub(crate) fn rf_unchecked<T: Real>(mut x: T, mut y: T, mut z: T) -> T {
    let tol = carlson_tolerance::<T>();
    let three = T::from_f64(3.0);
    let mut ave = (x + y + z) / three;
    let (mut dx, mut dy, mut dz) = (T::ZERO, T::ZERO, T::ZERO);
    for _ in 0..CARLSON_MAX_STEPS {
        ave = (x + y + z) / three;
        if ave <= T::ZERO {
            return T::ZERO;
        }
        dx = (ave - x) / ave;
        dy = (ave - y) / ave;
        dz = (ave - z) / ave;
        if dx.abs().max(dy.abs()).max(dz.abs()) <= tol {
            break;
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        let quarter = T::HALF * T::HALF;
        x = (x + lambda) * quarter;
        y = (y + lambda) * quarter;
        z = (z + lambda) * quarter;
    }
    // DLMF 19.36.1 with E2, E3 of the deviations.
    let e2 = dx * dy - dz * dz;
    let e3 = dx * dy * dz;
    let c1 = T::from_f64(1.0 / 24.0);
    let c2 = T::from_f64(0.1);
    let c3 = T::from_f64(3.0 / 44.0);
    let c4 = T::from_f64(1.0 / 14.0);
    (T::ONE + (c1 * e2 - c2 - c3 * e3) * e2 + c4 * e3) / ave.sqrt()
}

/// Carlson's degenerate integral `R_C(x, y) = R_F(x, y, y)` for `x ≥ 0`, `y > 0` (DLMF 19.2.17),
/// by duplication; no checks.
fn rc_unchecked<T: Real>(mut x: T, mut y: T) -> T {
    let tol = carlson_tolerance::<T>();
    let three = T::from_f64(3.0);
    let quarter = T::HALF * T::HALF;
    let mut ave = (x + y + y) / three;
    let mut s = T::ZERO;
    for _ in 0..CARLSON_MAX_STEPS {
        ave = (x + y + y) / three;
        if ave <= T::ZERO {
            return T::ZERO;
        }
        s = (y - ave) / ave;
        if s.abs() <= tol {
            break;
        }
        let lambda = T::TWO * x.sqrt() * y.sqrt() + y;
        x = (x + lambda) * quarter;
        y = (y + lambda) * quarter;
    }
    // Carlson 1995, series for R_C: 1 + 3s²/10 + s³/7 + 3s⁴/8 + 9s⁵/22.
    let c1 = T::from_f64(0.3);
    let c2 = T::from_f64(1.0 / 7.0);
    let c3 = T::from_f64(0.375);
    let c4 = T::from_f64(9.0 / 22.0);
    (T::ONE + s * s * (c1 + s * (c2 + s * (c3 + s * c4)))) / ave.sqrt()
}

/// Carlson's symmetric integral of the third kind
/// `R_J(x, y, z, p) = (3/2) ∫₀^∞ dt / ((t + p) √((t + x)(t + y)(t + z)))` (DLMF 19.16.2) for
/// `p > 0`, by duplication (Carlson 1995, with `R_C` for the correction sums).
///
/// # Errors
/// [`Error::NonFinite`] for non-finite input; [`Error::InvalidArgument`] unless `x, y, z ≥ 0`
/// with at most one zero and `p > 0`, or when the value overflows the type (`p` and two of
/// `x, y, z` tiny against the type's range).
pub fn carlson_rj<T: Real>(x: T, y: T, z: T, p: T) -> Result<T, Error> {
    if !(x.is_finite() && y.is_finite() && z.is_finite() && p.is_finite()) {
        return Err(Error::NonFinite);
    }
    if x < T::ZERO || y < T::ZERO || z < T::ZERO || p <= T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let zeros = [x, y, z].iter().filter(|v| **v == T::ZERO).count();
    if zeros > 1 {
        return Err(Error::InvalidArgument);
    }
    // Homogeneity: R_J(x, y, z, p) = R_J(x/s, y/s, z/s, p/s)/s^{3/2}, s an exact power of two.
    let s = pow2_scale(x.max(y).max(z).max(p));
    let r = rj_unchecked(x / s, y / s, z / s, p / s) / s / s.sqrt();
    if r.is_finite() {
        Ok(r)
    } else {
        Err(Error::InvalidArgument)
    }
}

/// `R_J` without checks (`x, y, z ≥ 0`, at most one zero, `p > 0`).
pub(crate) fn rj_unchecked<T: Real>(mut x: T, mut y: T, mut z: T, mut p: T) -> T {
    let tol = carlson_tolerance::<T>();
    let quarter = T::HALF * T::HALF;
    let five = T::from_f64(5.0);
    let mut sum = T::ZERO;
    let mut fac = T::ONE;
    let mut ave = (x + y + z + p + p) / five;
    let (mut dx, mut dy, mut dz, mut dp) = (T::ZERO, T::ZERO, T::ZERO, T::ZERO);
    for _ in 0..CARLSON_MAX_STEPS {
        ave = (x + y + z + p + p) / five;
        if ave <= T::ZERO {
            break;
        }
        dx = (ave - x) / ave;
        dy = (ave - y) / ave;
        dz = (ave - z) / ave;
        dp = (ave - p) / ave;
        if dx.abs().max(dy.abs()).max(dz.abs()).max(dp.abs()) <= tol {
            break;
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        let alpha = p * (sx + sy + sz) + sx * sy * sz;
        let alpha = alpha * alpha;
        let beta = p * (p + lambda) * (p + lambda);
        sum += fac * rc_unchecked(alpha, beta);
        fac *= quarter;
        x = (x + lambda) * quarter;
        y = (y + lambda) * quarter;
        z = (z + lambda) * quarter;
        p = (p + lambda) * quarter;
    }
    // DLMF 19.36.2 series in the elementary symmetric functions of the deviations.
    let c1 = T::from_f64(3.0 / 14.0);
    let c2 = T::from_f64(1.0 / 3.0);
    let c3 = T::from_f64(3.0 / 22.0);
    let c4 = T::from_f64(3.0 / 26.0);
    let c5 = T::from_f64(0.75 * 3.0 / 22.0);
    let c6 = T::from_f64(1.5 * 3.0 / 26.0);
    let c7 = T::from_f64(0.5 / 3.0);
    let c8 = T::from_f64(6.0 / 22.0);
    let ea = dx * (dy + dz) + dy * dz;
    let eb = dx * dy * dz;
    let ec = dp * dp;
    let ed = ea - T::from_f64(3.0) * ec;
    let ee = eb + T::TWO * dp * (ea - ec);
    let series = T::ONE
        + ed * (-c1 + c5 * ed - c6 * ee)
        + eb * (c7 + dp * (-c8 + dp * c4))
        + dp * ea * (c2 - dp * c3)
        - c2 * dp * ec;
    T::from_f64(3.0) * sum + fac * series / (ave * ave.sqrt())
}

/// The incomplete elliptic integral of the first kind `F(φ|m)` for any real `φ`, `m ∈ [0, 1)`:
/// `F(φ|m) = sin φ · R_F(cos²φ, 1 − m sin²φ, 1)` for `|φ| ≤ π/2` (DLMF 19.25.5), extended by
/// `F(φ + kπ|m) = F(φ|m) + 2kK(m)`. It inverts the amplitude: `F(am(u|m)|m) = u`.
///
/// # Errors
/// [`Error::NonFinite`] for non-finite input; [`Error::InvalidArgument`] for `m ∉ [0, 1)` or
/// `|φ| > 1/ε` (see the module docs).
pub fn incomplete_f<T: Real>(phi: T, m: T) -> Result<T, Error> {
    check_parameter(m)?;
    check_argument(phi)?;
    let m1 = T::ONE - m;
    let (k, phi_r) = reduce_angle(phi);
    let kc = complete_k_unchecked(m, m1);
    Ok(k * T::TWO * kc + f_reduced(phi_r, m1))
}

/// `φ = kπ + φ_r` with `|φ_r| ≤ π/2`.
fn reduce_angle<T: Real>(phi: T) -> (T, T) {
    let k = (phi / T::PI + T::HALF).floor();
    (k, phi - k * T::PI)
}

/// `F(φ|m)` for `|φ| ≤ π/2`, given the complementary parameter `m₁ = 1 − m ∈ (0, 1]` (pass it
/// accurately: near `m → 1` it sets `Δ²` and hence the result).
pub(crate) fn f_reduced<T: Real>(phi: T, m1: T) -> T {
    let (s, c) = phi.sin_cos();
    // Δ² = 1 − m sin²φ = cos²φ + (1 − m) sin²φ: a sum of non-negative terms, no cancellation
    // as m → 1.
    let y = c * c + m1 * s * s;
    s * rf_unchecked(c * c, y, T::ONE)
}

/// The incomplete elliptic integral of the third kind
/// `Π(n; φ|m) = ∫₀^φ dθ / ((1 − n sin²θ) √(1 − m sin²θ))` for any real `φ`, `n < 1`,
/// `m ∈ [0, 1)` (no pole on the real axis). For `|φ| ≤ π/2`
/// `Π = sin φ R_F(c², Δ², 1) + (n/3) sin³φ R_J(c², Δ², 1, 1 − n sin²φ)` with `c = cos φ`,
/// `Δ² = 1 − m sin²φ` (DLMF 19.25.14, sign convention of A&S 17.2.14), extended by
/// `Π(n; φ + kπ|m) = Π(n; φ|m) + 2k Π(n|m)`.
///
/// # Errors
/// [`Error::NonFinite`] for non-finite input; [`Error::InvalidArgument`] for `m ∉ [0, 1)`,
/// `n ≥ 1`, `|φ| > 1/ε` (see the module docs), or a value that overflows the type (`n` just
/// below 1 and `|φ|` large).
pub fn incomplete_pi<T: Real>(n: T, phi: T, m: T) -> Result<T, Error> {
    check_parameter(m)?;
    if !n.is_finite() {
        return Err(Error::NonFinite);
    }
    check_argument(phi)?;
    if n >= T::ONE {
        return Err(Error::InvalidArgument);
    }
    let (k, phi_r) = reduce_angle(phi);
    let r = pi_parts(n, T::ONE - n, k, phi_r, T::ONE - m);
    if r.is_finite() {
        Ok(r)
    } else {
        Err(Error::InvalidArgument)
    }
}

/// `Π(n; kπ + φ_r|m)` for `|φ_r| ≤ π/2`, `n < 1` (with `n₁ = 1 − n`), `m₁ = 1 − m ∈ (0, 1]`;
/// no checks.
fn pi_parts<T: Real>(n: T, n1: T, k: T, phi_r: T, m1: T) -> T {
    let partial = pi_reduced(n, n1, phi_r, m1);
    if k == T::ZERO {
        partial
    } else {
        partial + k * T::TWO * pi_reduced(n, n1, T::FRAC_PI_2, m1)
    }
}

/// The complete `Π(n|m) = Π(n; π/2|m)`, `n < 1` given with `n₁ = 1 − n` (pass it accurately
/// when `n → 1`) and `m₁ = 1 − m ∈ (0, 1]` (likewise); no checks.
pub(crate) fn pi_complete_unchecked<T: Real>(n: T, n1: T, m1: T) -> T {
    pi_reduced(n, n1, T::FRAC_PI_2, m1)
}

/// `Π(n; kπ + φ_r|m)` given the complete integral `Π(n|m)` and `n₁ = 1 − n`; no checks.
pub(crate) fn pi_with_complete<T: Real>(n: T, n1: T, k: T, phi_r: T, m1: T, complete: T) -> T {
    pi_reduced(n, n1, phi_r, m1) + k * T::TWO * complete
}

/// `Π(n; φ|m)` for `|φ| ≤ π/2`, with `n₁ = 1 − n`, `m₁ = 1 − m`.
fn pi_reduced<T: Real>(n: T, n1: T, phi: T, m1: T) -> T {
    let (s, c) = phi.sin_cos();
    let s2 = s * s;
    let c2 = (c * c).max(T::ZERO);
    let d2 = c2 + m1 * s2; // 1 − m sin²φ without cancellation
    // 1 − n sin²φ = (1 − n) + n cos²φ: no cancellation as n → 1 and φ → π/2 (where the
    // integrand peaks and R_J is most sensitive to p).
    let p = if n > T::ZERO {
        n1 + n * c2
    } else {
        T::ONE - n * s2
    };
    let rf = rf_unchecked(c2, d2, T::ONE);
    if n == T::ZERO || s == T::ZERO {
        return s * rf;
    }
    let rj = rj_unchecked(c2, d2, T::ONE, p);
    s * rf + n / T::from_f64(3.0) * s * s2 * rj
}
