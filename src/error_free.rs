//! Compensated arithmetic: the error-free transformations of f32/f64 sums and products, and the
//! compensated rotation update built on them.
//!
//! A compensated quantity is a pair `(x, e)`: `x` the value rounded to the type and `e` the
//! rounding error carried beside it (`|e| ≲ ½ ulp(x)`), so that `x + e` holds the value to about
//! `u²` relative (`u` = half an ulp at 1: 2⁻²⁴ in f32). An increment `d` is added as
//! `(x, e) ← Fast2Sum(x, d + e)`: the rounding of the new `x` is not lost but lands, exactly,
//! in the new `e`. Only the rounding of the small sum `d + e` (about `u·|d|`) and of the
//! increment's own computation remain, so a long accumulation of small increments keeps the
//! accuracy of the increments instead of losing half an ulp of `x` at each addition — and, what
//! matters more, instead of losing it with the same sign every time when `x` passes through the
//! same values again and again (see `crate::dynamics::integrators`).
//!
//! Requirements, met by every target gyrostat supports (thumbv6m/7m/7em/8m, RISC-V, x86-64 with
//! SSE, aarch64): IEEE binary floating point, round to nearest, no extended-precision
//! intermediates. No fused multiply-add is used (products are split à la Veltkamp), so the
//! results are bit-identical whether or not the target has an FMA instruction.

use crate::{Quat, Real, Vec3};

/// Dekker's Fast2Sum: `(s, e)` with `s = fl(a + b)` and `e = a + b − s` exactly when
/// `|a| ≥ |b|` (or `a = 0`). Three operations.
///
/// Used where `a` is the accumulated value and `b` a small increment. When an accumulated
/// component passes near zero, `|b|` can exceed `|a|`; then `e` is no longer exact but its error
/// is below `u·|b|` (Boldo, Graillat & Muller 2017, *ACM TOMS* 44(1)), the size of the rounding
/// already committed in computing the increment, so the carried value stays as accurate.
#[inline(always)]
pub(crate) fn fast_two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let s = a + b;
    (s, b - (s - a))
}

/// Knuth's TwoSum: `(s, e)` with `s = fl(a + b)` and `e = a + b − s` exactly, whatever the
/// magnitudes. Six operations.
#[inline(always)]
pub(crate) fn two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Veltkamp's split `a = hi + lo` with `hi`, `lo` of at most half the significand each, so that
/// their products are exact. The factor is `2^⌈p/2⌉ + 1`: f32 (p = 24) 4097, f64 (p = 53)
/// 134 217 729. `factor·a` overflows for `|a|` within that factor of the type's maximum, so
/// above [`split_max`] `a` is split scaled by 2⁻²⁸ and the parts scaled back (both scalings by a
/// power of two, exact): the split is total on every finite `a`.
#[inline(always)]
fn split<T: Real>(a: T) -> (T, T) {
    if a.abs() <= split_max::<T>() {
        veltkamp(a)
    } else {
        let (hi, lo) = veltkamp(a * T::from_f64(TWO_POW_M28));
        (hi * T::from_f64(TWO_POW_28), lo * T::from_f64(TWO_POW_28))
    }
}

/// Veltkamp's split itself, for `|a| ≤` [`split_max`] (there `factor·a` does not overflow):
/// `c = factor·a`, `hi = c − (c − a)`, `lo = a − hi`.
#[inline(always)]
fn veltkamp<T: Real>(a: T) -> (T, T) {
    let factor = if is_single::<T>() {
        T::from_f64(4097.0)
    } else {
        T::from_f64(134_217_729.0)
    };
    let c = factor * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

const TWO_POW_28: f64 = 268_435_456.0;
const TWO_POW_M28: f64 = 1.0 / TWO_POW_28;

/// The largest `|a|` that [`split`] splits directly: 2¹⁰⁰ in f32, 2⁹⁹⁶ in f64 (the overflow of
/// `factor·a` starts at `MAX/4097 ≈ 2¹¹⁶`, `MAX/(2²⁷ + 1) ≈ 2⁹⁹⁷`); above it `a·2⁻²⁸` is below it.
#[inline(always)]
fn split_max<T: Real>() -> T {
    if is_single::<T>() {
        T::from_f64(1.267_650_600_228_229_4e30)
    } else {
        T::from_f64(6.696_928_794_914_171e299)
    }
}

/// Dekker's TwoProduct: `(p, e)` with `p = fl(a·b)` and `e = a·b − p` exactly (no FMA).
#[inline(always)]
pub(crate) fn two_product<T: Real>(a: T, b: T) -> (T, T) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// `h/6` as a compensated pair `(h₆, h₆_lo)`: `h₆ = fl(h/6)` and the rest, from the exact
/// remainder `h − 6h₆` (a constant step's `h/6` would otherwise scale every RK4 increment by the
/// same rounding, `u` relative: a time-scale error). `6·fl(h/6)` can round past the type's
/// largest value for `|h|` near it, so above `MAX/8` (taken as 2¹²⁴ in f32, 2¹⁰²⁰ in f64) the
/// pair is formed for `h/8` and scaled back by 8 (both exact: powers of two).
#[inline(always)]
pub(crate) fn sixth_pair<T: Real>(h: T) -> (T, T) {
    let big = if is_single::<T>() {
        T::from_f64(2.126_764_793_255_865e37) // 2¹²⁴
    } else {
        T::from_f64(f64::MAX / 8.0)
    };
    if h.abs() > big {
        let (h6, lo) = sixth_pair_direct(h * T::from_f64(0.125));
        let eight = T::from_f64(8.0);
        (h6 * eight, lo * eight)
    } else {
        sixth_pair_direct(h)
    }
}

#[inline(always)]
fn sixth_pair_direct<T: Real>(h: T) -> (T, T) {
    let six = T::from_f64(6.0);
    let h6 = h / six;
    let (p, e) = two_product(h6, six);
    (h6, ((h - p) - e) / six)
}

/// `true` for f32 (the only sealed `Real` with a machine epsilon above 1e-10).
#[inline(always)]
fn is_single<T: Real>() -> bool {
    T::EPSILON.to_f64() > 1e-10
}

/// Largest `ψ²` for which the degree-9 Taylor polynomials of [`HalfTurn::series`] are used:
/// the first dropped term of `sin ψ`, `ψ¹¹/39916800`, is then below `u/16` of `ψ` (f32:
/// `ψ² ≤ 0.25`, dropped term ≤ 2.4e-11 relative; f64: `ψ² ≤ 0.01`, ≤ 2.5e-18). Above it the
/// type's `sin_cos` is used.
#[inline(always)]
fn series_max_sq<T: Real>() -> T {
    if is_single::<T>() {
        T::from_f64(0.25)
    } else {
        T::from_f64(0.01)
    }
}

/// `sin ψ − ψ = ψ³·sin_tail(ψ²)`: `−1/6 + ψ²/120 − ψ⁴/5040 + ψ⁶/362880`.
#[inline(always)]
fn sin_tail<T: Real>(x2: T) -> T {
    let c = |v: f64| T::from_f64(v);
    c(-1.0 / 6.0) + x2 * (c(1.0 / 120.0) + x2 * (c(-1.0 / 5040.0) + x2 * c(1.0 / 362_880.0)))
}

/// `cos ψ − 1 = ψ²·cos_tail(ψ²)`: `−1/2 + ψ²/24 − ψ⁴/720 + ψ⁶/40320`.
#[inline(always)]
fn cos_tail<T: Real>(x2: T) -> T {
    let c = |v: f64| T::from_f64(v);
    c(-0.5) + x2 * (c(1.0 / 24.0) + x2 * (c(-1.0 / 720.0) + x2 * c(1.0 / 40_320.0)))
}

/// `cos ψ − 1` from `sin ψ` and `cos ψ`, without the cancellation of `c − 1` near 0:
/// `−sin²ψ/(1 + cos ψ)` (for `cos ψ > 0`; `c − 1` is accurate otherwise).
#[inline(always)]
fn cos_minus_one<T: Real>(s: T, c: T) -> T {
    if c > T::ZERO {
        -(s * s) / (T::ONE + c)
    } else {
        c - T::ONE
    }
}

/// The terms of a rotation by the half angle `ψ`, the sine as a compensated pair:
/// `sin ψ = sin + sin_lo` (to about `u²` relative), `cos ψ − 1 = cos_m1` (to `u` relative,
/// which is all its uses need: see [`rotate_compensated`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct HalfTurn<T> {
    /// `sin ψ`, rounded.
    pub(crate) sin: T,
    /// The rest of `sin ψ`.
    pub(crate) sin_lo: T,
    /// `cos ψ − 1`.
    pub(crate) cos_m1: T,
}

impl<T: Real> HalfTurn<T> {
    /// The half turn `ψ = a·b`, the product taken exactly ([`two_product`]).
    ///
    /// Why exactly: in a splitting step the half angle of a sub-step is `rate·h/2`; when the rate
    /// is constant (a body spinning about a symmetry axis) `fl(rate·h/2)` and `fl(sin ψ)` round
    /// the same way at every sub-step, and the attitude turns by the same wrong angle each time —
    /// a phase error growing linearly with time. Below the series threshold, `sin ψ` is
    /// `ψ + ψ³·sin_tail(ψ²)`: the exact `ψ = p + p_lo` passes into `(sin, sin_lo)` unrounded and
    /// the tail, `ψ²/6` of the value, is rounded at `u·ψ³/6`.
    #[inline(always)]
    pub(crate) fn of_product(a: T, b: T) -> Self {
        let (p, p_lo) = two_product(a, b);
        let p2 = p * p;
        if p2 <= series_max_sq::<T>() {
            Self {
                sin: p,
                sin_lo: p_lo + p * p2 * sin_tail(p2),
                cos_m1: p2 * cos_tail(p2),
            }
        } else {
            let (s, c) = p.sin_cos();
            Self {
                sin: s,
                sin_lo: p_lo * c,
                cos_m1: cos_minus_one(s, c),
            }
        }
    }

    /// The plane-rotation terms of the full angle `θ = 2ψ`: `(sin θ − 2·sin, 1 − cos θ)`, i.e.
    /// `sin θ = 2·self.sin + first` (`2 sin ψ cos ψ` with the pair), `1 − cos θ = 2 sin²ψ`.
    #[inline(always)]
    pub(crate) fn full_angle_terms(&self) -> (T, T) {
        let s = self.sin + self.sin_lo;
        (T::TWO * (self.sin_lo + s * self.cos_m1), T::TWO * s * s)
    }
}

/// `(cos(θ/2) − 1, sin(θ/2)/θ − ½)` for the squared angle `θ² = theta_sq` of a rotation vector:
/// the exponential map `exp(φ) = (1 + cos_m1, φ/2 + sinc_m_half·φ)` split so that its large
/// parts (`1`, `φ/2`) are exact and only small corrections are rounded.
#[inline(always)]
pub(crate) fn exp_terms<T: Real>(theta_sq: T) -> (T, T) {
    // With ψ = θ/2: cos ψ − 1 = ψ²·cos_tail(ψ²), sin ψ/θ − ½ = ½·ψ²·sin_tail(ψ²).
    let x2 = theta_sq * T::from_f64(0.25);
    if x2 <= series_max_sq::<T>() {
        (x2 * cos_tail(x2), T::HALF * x2 * sin_tail(x2))
    } else {
        let theta = theta_sq.sqrt();
        let (s, c) = (theta * T::HALF).sin_cos();
        (cos_minus_one(s, c), s / theta - T::HALF)
    }
}

/// The compensated update `(q, q_lo) ← (q + q_lo) ⊗ exp(φ + φ_lo)`, in increment form.
///
/// The rotation vector is first brought to a normalised pair, `(φ, φ_lo) ← TwoSum(φ, φ_lo)`
/// per component, so that the whole angle `φ + φ_lo` is in the exponential: a caller's low part
/// may be large (a rule's coning term, the Magnus commutator, the CF4 difference), and an
/// exponential taken of `φ` alone with `φ_lo` added linearly would be off by `O(|φ|²|φ_lo|)`.
/// After the TwoSum `|φ_lo| ≤ ½ ulp(φ)` and its first-order treatment is exact to `u²`.
///
/// `exp(φ) = 1 + (m, v)` with `m = cos(θ/2) − 1` and `v = φ/2 + (s − ½)φ` ([`exp_terms`]); the
/// increment `(q + q_lo) ⊗ (m, v + φ_lo/2)` is added component by component, its large part
/// `q ⊗ (m, φ/2)` and its small part (the rest) kept apart until then. Terms below `u²` are
/// dropped: `q_lo ⊗ (m, v_lo)`, and `q_lo`'s share of the small corrections.
///
/// The large part is added without rounding ([`add_product_compensated`]): `q` and `(m, φ/2)` are
/// split into halves (Veltkamp), the sixteen products of the high halves are exact, and each is
/// added into `q` by TwoSum with its rounding carried; the products with a low half, at most
/// `2⁻¹¹` (f32) of the increment, join the small part. Rounded instead (`fl(q ⊗ (m, φ/2))`, `u·|φ|/2`
/// per component and update), the increment's rounding is a function of `q` and `φ` alone, so on
/// a repeating motion it repeats update after update and piles up: measured on the classical
/// coning motion (1° half-angle at 10 Hz, 1 kHz, 60 s, the same f32-rounded increments in f32 and
/// f64, exact normalisation), the 4-sample rule ended 5.6e-7 rad from the f64 run with the
/// rounded product and 8.8e-11 with this one (the attitude rounded to f32); made exact in f64
/// instead, the rule's rotation vector (5.6e-7) or the renormalisation (5.9e-7) alone changed
/// nothing (`host-tests/tests/propagation/compensated_ablation.rs`). TwoSum, not Fast2Sum:
/// components of `q` pass through zero (near the identity three of them are small), where
/// Fast2Sum's error is not exact; with it the same rule on a 3° cone ended 4.8e-8 rad from f64,
/// with TwoSum 2.5e-9.
///
/// Beyond half a turn (`θ² > π²`, or a `θ²` that overflows) the split `φ/2 + (s − ½)φ` cancels
/// (at `θ = 10¹⁶` both terms are 5·10¹⁵ and their difference is noise) and `θ²` may not be
/// representable: there the exponential is the plain one ([`UnitQuat::exp_unchecked`], total on
/// every finite `φ`) and the increment `(q + q_lo) ⊗ (exp(φ) − 1)` is added the same way, with
/// the plain update's accuracy (`u`). Increments of an integrator's step are far below that.
#[inline(always)]
pub(crate) fn rotate_compensated<T: Real>(
    q: &mut Quat<T>,
    q_lo: &mut Quat<T>,
    phi: Vec3<T>,
    phi_lo: Vec3<T>,
) {
    let (x, ex) = two_sum(phi.x, phi_lo.x);
    let (y, ey) = two_sum(phi.y, phi_lo.y);
    let (z, ez) = two_sum(phi.z, phi_lo.z);
    let (phi, phi_lo) = (Vec3::new(x, y, z), Vec3::new(ex, ey, ez));
    let theta_sq = phi.norm_squared();
    if theta_sq <= T::PI * T::PI {
        let (m, sh) = exp_terms(theta_sq);
        let v = phi.scale(T::HALF);
        let v_lo = phi_lo.scale(T::HALF) + phi.scale(sh);
        let small = *q * Quat::from_parts(T::ZERO, v_lo) + *q_lo * Quat::from_parts(T::ZERO, v);
        add_product_compensated(q, q_lo, Quat::from_parts(m, v), small);
    } else {
        let e = crate::UnitQuat::exp_unchecked(phi).into_quat();
        let (m, v) = (e.w - T::ONE, Vec3::new(e.x, e.y, e.z));
        let large = *q * Quat::from_parts(m, v);
        let small = *q_lo * Quat::from_parts(m, v);
        add_compensated(q, q_lo, large, small);
    }
}

/// `(q, q_lo) ← (q + q_lo) + (q ⊗ w + small)` with the product `q ⊗ w` added unrounded.
///
/// `q = q_h + q_l`, `w = w_h + w_l` by Veltkamp's split ([`veltkamp`]: halves of at most 12 bits in
/// f32, 26 in f64), so that every product of high halves `q_h,i·w_h,j` is exact. Each component of
/// `q_h ⊗ w_h` is four such products; they are added into the component one by one through
/// TwoSum, their roundings summed beside, and the rest of the product, `q ⊗ w_l + q_l ⊗ w_h`
/// (below `2⁻¹¹·|w|`, so rounded at `2⁻¹¹·u·|w|`), goes with `small` into the low part as in
/// [`add_pair`]. Products with a low half are formed with the rounded `q`, as the high ones: the
/// whole of `q ⊗ w` is added, and the dropped `q_lo ⊗ w` is the caller's `small` business.
///
/// For components of `q` and `w` below [`split_max`] in magnitude (2¹⁰⁰ in f32): the split is
/// taken without its range check. [`rotate_compensated`] passes a unit `q` and `|w| ≤ π/2`.
#[inline(always)]
pub(crate) fn add_product_compensated<T: Real>(
    q: &mut Quat<T>,
    q_lo: &mut Quat<T>,
    w: Quat<T>,
    small: Quat<T>,
) {
    let halves = |a: Quat<T>| {
        let [w, x, y, z] = a.to_array().map(veltkamp);
        (Quat::new(w.0, x.0, y.0, z.0), Quat::new(w.1, x.1, y.1, z.1))
    };
    let (qh, ql) = halves(*q);
    let (wh, wl) = halves(w);
    let small = small + *q * wl + ql * wh;
    let a = [qh.w, qh.x, qh.y, qh.z];
    // The rows of the Hamilton product, as in `Quat::mul`; negation is exact.
    let rows = [
        [wh.w, -wh.x, -wh.y, -wh.z],
        [wh.x, wh.w, wh.z, -wh.y],
        [wh.y, -wh.z, wh.w, wh.x],
        [wh.z, wh.y, -wh.x, wh.w],
    ];
    let mut x = q.to_array();
    let mut x_lo = q_lo.to_array();
    let small = small.to_array();
    for (i, row) in rows.iter().enumerate() {
        let (mut s, mut e) = (x[i], T::ZERO);
        for (ak, rk) in a.iter().zip(row) {
            let (t, r) = two_sum(s, *ak * *rk);
            s = t;
            e += r;
        }
        (x[i], x_lo[i]) = fast_two_sum(s, e + (small[i] + x_lo[i]));
    }
    *q = Quat::from_array(x);
    *q_lo = Quat::from_array(x_lo);
}

/// `(x, x_lo) ← (x + x_lo) + (large + small)`: a compensated increment, its large part (an
/// increment rounded to `T`) and its small part (the corrections below its ulp) kept apart.
///
/// Double-f32 addition: `(s, e) = Fast2Sum(x, large)`, the small terms folded into the error,
/// `e + (small + x_lo)`, and the pair renormalised by Fast2Sum. The low part then carries digits
/// far below an ulp of the increment. (Fast2Sum rather than TwoSum for the first sum: `x` is the
/// accumulated value, larger than its increment but for the moments a component passes near
/// zero, where the error is still below `u·|large|`, the size of the rounding `large` itself
/// carries; measured no difference in the tests, three operations fewer.) The simpler `Fast2Sum(x, large + (small + x_lo))`
/// is not enough: `x_lo` (a rounding error of earlier sums of the same size) lies on the grid of
/// the increment's ulp, so a `small` below half that ulp rounds away every time, the same way —
/// measured: a constant sub-ulp part of the rotation vector (a rate step's product remainder)
/// lost systematically, 2.5e-5 rad an hour in f32 at 1.1 rad/s, against 2e-6 with this form.
#[inline(always)]
pub(crate) fn add_pair<T: Real>(x: T, x_lo: T, large: T, small: T) -> (T, T) {
    let (s, e) = fast_two_sum(x, large);
    fast_two_sum(s, e + (small + x_lo))
}

/// [`add_pair`] for each component of a quaternion.
#[inline(always)]
pub(crate) fn add_compensated<T: Real>(
    q: &mut Quat<T>,
    q_lo: &mut Quat<T>,
    large: Quat<T>,
    small: Quat<T>,
) {
    let (w, w_lo) = add_pair(q.w, q_lo.w, large.w, small.w);
    let (x, x_lo) = add_pair(q.x, q_lo.x, large.x, small.x);
    let (y, y_lo) = add_pair(q.y, q_lo.y, large.y, small.y);
    let (z, z_lo) = add_pair(q.z, q_lo.z, large.z, small.z);
    *q = Quat::new(w, x, y, z);
    *q_lo = Quat::new(w_lo, x_lo, y_lo, z_lo);
}

/// [`add_pair`] for each component of a vector.
#[inline(always)]
pub(crate) fn add_compensated_vec<T: Real>(
    v: &mut Vec3<T>,
    v_lo: &mut Vec3<T>,
    large: Vec3<T>,
    small: Vec3<T>,
) {
    let (x, x_lo) = add_pair(v.x, v_lo.x, large.x, small.x);
    let (y, y_lo) = add_pair(v.y, v_lo.y, large.y, small.y);
    let (z, z_lo) = add_pair(v.z, v_lo.z, large.z, small.z);
    *v = Vec3::new(x, y, z);
    *v_lo = Vec3::new(x_lo, y_lo, z_lo);
}

/// The fast renormalisation `q ← q + q·(1 − |q|²)/2` in compensated form: the correction scales
/// `q + q_lo` as a whole (its rounding moves `|q|`, not the attitude), and each component's new
/// rounding is carried. `|q|²` is taken from the rounded `q`, so the norm settles within a few
/// `u` of 1 (not exactly: it does not need to, only the direction of `q + q_lo` is the attitude).
///
/// One Newton step leaves `3δ²/4` of a deviation `|q|² = 1 + δ`; as on the plain path
/// ([`crate::propagation::Normalization::apply_quat_unchecked`]) it is used only while that is
/// below `ε/4` (`|δ| ≤ √(ε/3)`), and a larger deviation (an RK4 step turning by more than about
/// 0.19 rad in f64, 1 rad in f32) gets the exact correction `q·(1/|q| − 1)` instead.
#[inline(always)]
pub(crate) fn renormalize_compensated<T: Real>(q: &mut Quat<T>, q_lo: &mut Quat<T>) {
    let n2 = q.norm_squared();
    let d = T::ONE - n2;
    let r = if d.abs() <= (T::EPSILON / T::from_f64(3.0)).sqrt() {
        d * T::HALF
    } else {
        renormalize_exact_factor(n2)
    };
    add_compensated(q, q_lo, q.scale(r), Quat::ZERO);
}

/// `1/|q| − 1` for `n2 = |q|²`, in the form `(1 − |q|²)/(|q|(1 + |q|))` that keeps its digits when
/// `|q|` is near 1: the exact renormalisation's scale correction.
#[inline(always)]
pub(crate) fn renormalize_exact_factor<T: Real>(n2: T) -> T {
    let n = n2.sqrt();
    (T::ONE - n2) / (n * (T::ONE + n))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The error-free transformations are exact: checked against f64 arithmetic, which holds
    /// every f32 sum and product exactly.
    #[test]
    fn error_free_transformations_are_exact_in_f32() {
        let mut s: u32 = 0x1234_5678;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            (s as f32 / u32::MAX as f32 - 0.5) * 8.0
        };
        for _ in 0..100_000 {
            let (a, b) = (next(), next() * 1e-3);
            let (p, e) = two_product(a, b);
            assert_eq!(f64::from(p) + f64::from(e), f64::from(a) * f64::from(b));
            let (t, f) = two_sum(b, a);
            assert_eq!(f64::from(t) + f64::from(f), f64::from(a) + f64::from(b));
            let (t, f) = fast_two_sum(a, b);
            assert_eq!(f64::from(t) + f64::from(f), f64::from(a) + f64::from(b));
        }
    }

    /// `sin ψ = sin + sin_lo` and `cos ψ − 1` against f64 libm for `ψ = a·b`, below and above
    /// the series threshold (f32). Below it the pair is exact but for the rounding of the tail
    /// `ψ³/6·(…)` and of its sum with the product's error: a few `u·ψ²/6` relative (the
    /// tail's relative error of about 5u, the sum's u; bound `8u·ψ²/6 = 8e-8·ψ²`, 0.33 u at the
    /// threshold ψ = 0.5, 8e-12 at ψ = 0.01); above it, the kernel's
    /// `sin` (≤ 2 u). `cos ψ − 1` within 6u relative (measured 4.6u: the rounding of `ψ²` and
    /// of the tail, or of the kernel's `sin²ψ/(1 + cos ψ)`), all that its uses need.
    ///
    /// With the `micromath` backend the pair above the threshold is micromath's `sin`/`cos`
    /// (1.1e-3 absolute each, module docs of `real`): `sin ψ` within that, and
    /// `cos ψ − 1 = −sin²/(1 + cos)` within `(2 sin/(1 + cos) + sin²/(1 + cos)²)·1.1e-3 ≤ 1.0 ×
    /// 1.1e-3` for `ψ ≤ π/4`; below the threshold no backend function is used and the bounds
    /// are the default's.
    #[test]
    fn half_turn_is_accurate_in_f32() {
        for k in 1..2000 {
            let a = 0.37f32 + k as f32 * 1.3e-3;
            let b = 1e-4f32 * k as f32;
            let t = HalfTurn::of_product(a, b);
            let psi = f64::from(a) * f64::from(b);
            let sin = f64::from(t.sin) + f64::from(t.sin_lo);
            let err = (sin - psi.sin()).abs() / psi;
            let below = psi * psi <= 0.25;
            let m = psi.cos() - 1.0;
            let em = (f64::from(t.cos_m1) - m).abs() / m.abs();
            if cfg!(feature = "micromath") && !below {
                assert!(err * psi <= 1.1e-3, "ψ = {psi}: sin abs {}", err * psi);
                assert!(
                    em * m.abs() <= 1.2e-3,
                    "ψ = {psi}: cos − 1 abs {}",
                    em * m.abs()
                );
                continue;
            }
            let bound = if below {
                8e-8 * psi * psi + 1e-15
            } else {
                1.2e-7
            };
            assert!(err < bound, "ψ = {psi}: {err}");
            assert!(em <= 3.6e-7, "ψ = {psi}: {em}");
        }
    }
}
