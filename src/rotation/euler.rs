//! Euler angles in all 24 conventions, with gimbal lock reported as a first-class result.
//!
//! # Conventions
//! A sequence is three axes, adjacent ones distinct (12 axis sequences: 6 Tait–Bryan such as
//! `XYZ`, 6 proper such as `ZYZ`), read intrinsic or extrinsic (24 conventions), exactly as
//! `scipy.spatial.transform.Rotation.from_euler`:
//! - uppercase `"ABC"` is **intrinsic**: `R = R_A(a)·R_B(b)·R_C(c)`, rotations about the moving
//!   axes A, B′, C″;
//! - lowercase `"abc"` is **extrinsic**: `R = R_c(c)·R_b(b)·R_a(a)`, rotations about the fixed
//!   axes, first a, then b, then c.
//!
//! `R` is the attitude matrix of the crate (body axes as columns, body → lab). The seed's
//! `R(αβγ) = R_z(α)·R_y(β)·R_z(γ)` (6.6.1a) is intrinsic `ZYZ`; aerospace yaw–pitch–roll is
//! intrinsic `ZYX`.
//!
//! Angle ranges of an extracted solution: first and third in `(−π, π]`; middle in `[0, π]` for
//! proper sequences and `[−π/2, π/2]` for Tait–Bryan sequences.
//!
//! # Extraction from the quaternion
//! [`UnitQuat::to_euler`] follows Bernardes & Viollet, *Quaternion to Euler angles conversion: a
//! direct, general and computationally efficient method*, PLoS ONE 17(11) e0276302 (2022) — the
//! method scipy uses. The quaternion is permuted (and, for Tait–Bryan sequences, combined as
//! `(w ∓ q_j, …)`, a 45° change of frame) so that every sequence becomes the proper sequence
//! about its own axes; then with the four permuted components `(a, b, c, d)`:
//!
//! ```text
//! middle = 2·atan2(√(c² + d²), √(a² + b²))   (never asin/acos of a clamped entry)
//! θ± = atan2(b, a) ± atan2(d, c)                  (half-sum and half-difference of the outer angles)
//! ```
//!
//! Every step is an `atan2` or `hypot` of quaternion components, so the result is accurate to a
//! few ulp of the rotation at every attitude, including at and next to the poles: near a pole
//! `atan2(d, c)` is noise, but the rotation depends on it only through terms multiplied by
//! `hypot(c, d)`, so the rebuilt rotation stays accurate (this is what the accuracy contract of
//! the module docs checks, as an effect, not as raw angles).
//!
//! # Gimbal lock
//! At the poles (middle angle `0`/`π` for proper sequences, `∓π/2` for Tait–Bryan) the rotation
//! depends only on `first + s·third` for a sign `s = ±1` ([`GimbalLock::sign`]); the split between
//! the two is undetermined. [`EulerSolution`] always carries the distance to the nearest pole and,
//! within [`GIMBAL_LOCK_THRESHOLD`], a [`GimbalLock`] record; the split is then chosen by a
//! [`GimbalPolicy`]. The seed states the same equivalence: `(α, 0, γ) ≡ (α − φ, 0, γ + φ)` (§6.6.a,
//! Fig. 6.6.2d).

use core::fmt;
use core::str::FromStr;

use crate::{Axis, Error, Quat, Real, UnitQuat};

/// The letter of an axis in scipy's notation: uppercase for intrinsic, lowercase for extrinsic.
const fn letter(axis: Axis, upper: bool) -> char {
    match (axis, upper) {
        (Axis::X, true) => 'X',
        (Axis::Y, true) => 'Y',
        (Axis::Z, true) => 'Z',
        (Axis::X, false) => 'x',
        (Axis::Y, false) => 'y',
        (Axis::Z, false) => 'z',
    }
}

/// Whether the axes of an Euler sequence move with the body or stay fixed in the lab.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Frame {
    /// Rotations about the moving (body) axes: `R = R_A(a)·R_B(b)·R_C(c)`. Written uppercase.
    Intrinsic,
    /// Rotations about the fixed (lab) axes, first a: `R = R_c(c)·R_b(b)·R_a(a)`. Written lowercase.
    Extrinsic,
}

/// One of the 24 Euler conventions: three axes (adjacent ones distinct) and a [`Frame`].
///
/// Parsed from scipy's strings: `"ZYX"` (intrinsic), `"zyx"` (extrinsic); mixed case is
/// rejected. Displayed the same way.
///
/// ```
/// use gyrostat::rotation::{EulerSequence, Frame};
/// let s: EulerSequence = "ZYZ".parse()?;
/// assert_eq!(s, EulerSequence::ZYZ);
/// assert!(s.is_proper() && s.frame() == Frame::Intrinsic);
/// assert!("zxx".parse::<EulerSequence>().is_err());
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EulerSequence {
    axes: [Axis; 3],
    frame: Frame,
}

impl EulerSequence {
    /// Intrinsic `ZYX`: aerospace yaw, pitch, roll.
    pub const ZYX: Self = Self {
        axes: [Axis::Z, Axis::Y, Axis::X],
        frame: Frame::Intrinsic,
    };
    /// Intrinsic `ZYZ`: the seed's `R(αβγ) = R_z(α)·R_y(β)·R_z(γ)` (6.6.1a).
    pub const ZYZ: Self = Self {
        axes: [Axis::Z, Axis::Y, Axis::Z],
        frame: Frame::Intrinsic,
    };
    /// Intrinsic `ZXZ`: the classical (Goldstein) Euler angles.
    pub const ZXZ: Self = Self {
        axes: [Axis::Z, Axis::X, Axis::Z],
        frame: Frame::Intrinsic,
    };

    /// All 24 conventions: the 12 axis sequences intrinsic, then the same 12 extrinsic.
    pub const ALL: [Self; 24] = {
        use Axis::{X, Y, Z};
        const AX: [[Axis; 3]; 12] = [
            [X, Y, Z],
            [X, Z, Y],
            [Y, X, Z],
            [Y, Z, X],
            [Z, X, Y],
            [Z, Y, X],
            [X, Y, X],
            [X, Z, X],
            [Y, X, Y],
            [Y, Z, Y],
            [Z, X, Z],
            [Z, Y, Z],
        ];
        let mut out = [Self::ZYX; 24];
        let mut i = 0;
        while i < 12 {
            out[i] = Self {
                axes: AX[i],
                frame: Frame::Intrinsic,
            };
            out[i + 12] = Self {
                axes: AX[i],
                frame: Frame::Extrinsic,
            };
            i += 1;
        }
        out
    };

    /// The sequence `first, second, third` in `frame`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] if two adjacent axes are equal (`XXY`, `ZYY`).
    pub const fn try_new(
        first: Axis,
        second: Axis,
        third: Axis,
        frame: Frame,
    ) -> Result<Self, Error> {
        if first.index() == second.index() || second.index() == third.index() {
            return Err(Error::InvalidArgument);
        }
        Ok(Self {
            axes: [first, second, third],
            frame,
        })
    }

    /// Parses scipy's notation: three letters from `xyz`, all uppercase (intrinsic) or all
    /// lowercase (extrinsic).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for anything else.
    pub fn try_from_str(s: &str) -> Result<Self, Error> {
        let b = s.as_bytes();
        let [c0, c1, c2] = match b {
            [c0, c1, c2] => [*c0, *c1, *c2],
            _ => return Err(Error::InvalidArgument),
        };
        let upper = |c: u8| c.is_ascii_uppercase();
        let frame = if upper(c0) && upper(c1) && upper(c2) {
            Frame::Intrinsic
        } else if !upper(c0) && !upper(c1) && !upper(c2) {
            Frame::Extrinsic
        } else {
            return Err(Error::InvalidArgument);
        };
        let ax = |c: u8| match c.to_ascii_lowercase() {
            b'x' => Ok(Axis::X),
            b'y' => Ok(Axis::Y),
            b'z' => Ok(Axis::Z),
            _ => Err(Error::InvalidArgument),
        };
        Self::try_new(ax(c0)?, ax(c1)?, ax(c2)?, frame)
    }

    /// The three axes in the order the angles are given.
    #[inline]
    pub const fn axes(&self) -> [Axis; 3] {
        self.axes
    }

    /// Intrinsic or extrinsic.
    #[inline]
    pub const fn frame(&self) -> Frame {
        self.frame
    }

    /// `true` for a proper (symmetric) sequence such as `ZYZ` (first axis = third axis), `false`
    /// for a Tait–Bryan sequence such as `ZYX`.
    #[inline]
    pub const fn is_proper(&self) -> bool {
        self.axes[0].index() == self.axes[2].index()
    }

    /// The axes in the order their rotation matrices appear in the product `R = R₁·R₂·R₃`, with
    /// the angle index each one takes: intrinsic keeps the order, extrinsic reverses it.
    #[inline]
    pub(crate) const fn product_order(&self) -> ([Axis; 3], [usize; 3]) {
        let [a, b, c] = self.axes;
        match self.frame {
            Frame::Intrinsic => ([a, b, c], [0, 1, 2]),
            Frame::Extrinsic => ([c, b, a], [2, 1, 0]),
        }
    }
}

impl FromStr for EulerSequence {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self, Error> {
        Self::try_from_str(s)
    }
}

impl fmt::Display for EulerSequence {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let upper = matches!(self.frame, Frame::Intrinsic);
        for a in self.axes {
            fmt::Write::write_char(f, letter(a, upper))?;
        }
        Ok(())
    }
}

/// Euler angles `[first, second, third]` (radians) in a given [`EulerSequence`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Euler<T> {
    /// The angles in the order of the sequence's letters.
    pub angles: [T; 3],
    /// The convention.
    pub sequence: EulerSequence,
}

/// Which pole of the middle angle a gimbal lock is at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pole {
    /// Middle angle `0` (proper sequences) or `−π/2` (Tait–Bryan).
    Lower,
    /// Middle angle `π` (proper sequences) or `+π/2` (Tait–Bryan).
    Upper,
}

/// The record of a gimbal lock: the rotation is (to working precision) at a pole, where only one
/// combination of the outer angles is determined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GimbalLock<T> {
    /// Which pole.
    pub pole: Pole,
    /// The sign `s = ±1` of the determined combination `first + s·third`.
    ///
    /// Proper sequences: `+1` at the lower pole, `−1` at the upper. Tait–Bryan sequences with the
    /// matrices multiplied as `R_i R_j R_k`: `s = ±ε_ijk` at middle angle `±π/2` (for extrinsic
    /// sequences `i, j, k` are the letters reversed).
    pub sign: T,
    /// The determined combination `first + s·third`, wrapped to `(−π, π]`.
    pub combined_angle: T,
    /// Distance of the middle angle from the pole, radians (`≤` [`GIMBAL_LOCK_THRESHOLD`]).
    pub distance_to_pole: T,
}

/// How the undetermined split of the outer angles is resolved at a gimbal lock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GimbalPolicy<T> {
    /// First angle `0`, third angle carries the combination (`third = s·combined`).
    ZeroFirst,
    /// Third angle `0`, first angle carries the combination (scipy's choice).
    ZeroThird,
    /// The split closest (Euclidean, with angles taken modulo 2π) to a previous solution
    /// `[first, second, third]`, for continuity of telemetry and control loops. A non-finite
    /// previous angle makes it behave as [`GimbalPolicy::ZeroThird`].
    ClosestTo([T; 3]),
}

/// The result of an Euler extraction: the angles, the distance to the nearest pole, and the gimbal
/// lock record when within [`GIMBAL_LOCK_THRESHOLD`] of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EulerSolution<T> {
    /// The angles; at a gimbal lock, split according to the [`GimbalPolicy`].
    pub euler: Euler<T>,
    /// Distance (radians) of the middle angle from the nearest pole, always reported.
    pub distance_to_pole: T,
    /// `Some` when the rotation is at a pole to working precision.
    pub singularity: Option<GimbalLock<T>>,
}

/// Distance of the middle angle from its pole (radians) at or below which an extraction is
/// reported as gimbal-locked: `2·T::EPSILON` (2.4e-7 for f32, 4.4e-16 for f64).
///
/// Why this value: moving the split of the outer angles by `δ` while the middle angle is `d` away
/// from the pole changes the rotation by at most `2·sin(d/2)·2·|sin(δ/2)| ≤ 2d`. At `d ≤ 2ε` that
/// is `≤ 4ε`, a few roundings of a unit quaternion's components: the split is undetermined at
/// working precision, and re-choosing it by a [`GimbalPolicy`] keeps the accuracy contract. The
/// factor 2 (rather than 1) is what it takes for angles set exactly at the pole (`±π/2`, `0`, `π`
/// as constants of the type) to be flagged: rounding in the constant and the quaternion puts the
/// computed distance at up to about `1.0·ε` to `1.1·ε` (measured over all 24 conventions). A
/// larger threshold would trade accuracy for the choice; callers who want a wider "near gimbal
/// lock" warning read [`EulerSolution::distance_to_pole`].
pub fn gimbal_lock_threshold<T: Real>() -> T {
    T::TWO * T::EPSILON
}

/// See [`gimbal_lock_threshold`]; the f64 value, for documentation links and f64 callers.
pub const GIMBAL_LOCK_THRESHOLD: f64 = 2.0 * f64::EPSILON;

/// The part of `2π` below the f64 constant `TAU` (`2π − fl64(2π)`).
const TAU_F64_REMAINDER: f64 = 2.449_293_598_294_706_4e-16;

/// Wraps an angle in `[−3π, 3π]` into `(−π, π]`.
///
/// `2π` is subtracted in two parts, `hi` (`2π` rounded to `T`) and `lo = 2π − hi` (−1.7e-7 in f32,
/// 2.4e-16 in f64): `x − hi` is exact for `|x|` in `[π, 3π]` (Sterbenz), so the result carries
/// one rounding instead of the error of the rounded `2π`, which in f32 alone is 1.7e-7 rad.
#[inline]
pub(crate) fn wrap<T: Real>(x: T) -> T {
    let hi = T::PI + T::PI;
    let lo = T::from_f64(TAU_F64_REMAINDER + (core::f64::consts::TAU - hi.to_f64()));
    if x > T::PI {
        (x - hi) - lo
    } else if x <= -T::PI {
        (x + hi) + lo
    } else {
        x
    }
}

/// Parity `ε_ijk` of a permutation of `(0, 1, 2)`: `+1` even, `−1` odd.
#[inline]
pub(crate) fn parity(i: Axis, j: Axis) -> i8 {
    // For distinct i, j the permutation is even iff j follows i cyclically.
    if i.next() == j { 1 } else { -1 }
}

/// The elementary rotation about coordinate axis `axis` by an angle `θ` given as
/// `(s, c) = (sin(θ/2), cos(θ/2))`: `(c, s·e_axis)`.
#[inline]
pub(crate) fn elementary<T: Real>(axis: Axis, s: T, c: T) -> Quat<T> {
    let z = T::ZERO;
    match axis {
        Axis::X => Quat::new(c, s, z, z),
        Axis::Y => Quat::new(c, z, s, z),
        Axis::Z => Quat::new(c, z, z, s),
    }
}

/// `q ⊗ (c, s·e_axis)` with `(s, c) = (sin(θ/2), cos(θ/2))`: the Hamilton product with an
/// elementary rotation, using its sparsity (8 multiplications instead of 16).
#[inline]
pub(crate) fn mul_elementary<T: Real>(q: Quat<T>, axis: Axis, s: T, c: T) -> Quat<T> {
    let Quat { w, x, y, z } = q;
    match axis {
        Axis::X => Quat::new(c * w - s * x, c * x + s * w, c * y + s * z, c * z - s * y),
        Axis::Y => Quat::new(c * w - s * y, c * x - s * z, c * y + s * w, c * z + s * x),
        Axis::Z => Quat::new(c * w - s * z, c * x + s * y, c * y - s * x, c * z + s * w),
    }
}

#[inline]
fn comp<T: Real>(q: &Quat<T>, i: Axis) -> T {
    match i {
        Axis::X => q.x,
        Axis::Y => q.y,
        Axis::Z => q.z,
    }
}

impl<T: Real> Euler<T> {
    /// Angles in a convention.
    #[inline]
    pub const fn new(sequence: EulerSequence, angles: [T; 3]) -> Self {
        Self { angles, sequence }
    }

    /// The rotation as a unit quaternion: the Hamilton product of the three elementary rotations
    /// in matrix order (intrinsic `q_A(a)·q_B(b)·q_C(c)`, extrinsic `q_c(c)·q_b(b)·q_a(a)`).
    ///
    /// The sign is that of the spinor product, not canonicalised: seed's intrinsic `ZYZ` gives the
    /// SU(2) matrix (6.6.3), so `(α, β, γ)` and `(α + 2π, β, γ)` give opposite quaternions, as the
    /// 4π sequence (6.6.6c–d) requires. Use [`UnitQuat::canonical`] for an SO(3) representative.
    ///
    /// Unchecked: angles are not range-checked, and a non-finite angle gives a non-finite
    /// quaternion (use [`Euler::try_to_unit_quat`] for untrusted input).
    #[inline]
    pub fn to_unit_quat_unchecked(&self) -> UnitQuat<T> {
        let (axes, _) = self.sequence.product_order();
        let [a0, a1, a2] = self.angles;
        let (p0, p2) = match self.sequence.frame() {
            Frame::Intrinsic => (a0, a2),
            Frame::Extrinsic => (a2, a0),
        };
        // The three half-angle sines and cosines in one call (side by side where the backend can).
        let (s, c) = T::sin_cos3([p0 * T::HALF, a1 * T::HALF, p2 * T::HALF]);
        let q = mul_elementary(elementary(axes[0], s[0], c[0]), axes[1], s[1], c[1]);
        UnitQuat::new_unchecked(mul_elementary(q, axes[2], s[2], c[2]))
    }

    /// [`Euler::to_unit_quat_unchecked`] with a finiteness check.
    ///
    /// # Errors
    /// [`Error::NonFinite`] if an angle is NaN or infinite.
    pub fn try_to_unit_quat(&self) -> Result<UnitQuat<T>, Error> {
        if self.angles.iter().all(|a| a.is_finite()) {
            Ok(self.to_unit_quat_unchecked())
        } else {
            Err(Error::NonFinite)
        }
    }
}

impl<T: Real> UnitQuat<T> {
    /// Euler angles of this attitude in `sequence`, gimbal lock resolved by
    /// [`GimbalPolicy::ZeroThird`]. See [`UnitQuat::to_euler`].
    #[inline]
    pub fn to_euler_angles(self, sequence: EulerSequence) -> [T; 3] {
        self.to_euler(sequence, GimbalPolicy::ZeroThird)
            .euler
            .angles
    }

    /// Euler angles of this attitude in `sequence` (any of the 24 conventions), by the direct
    /// quaternion method of Bernardes & Viollet (2022) (see the module docs), with gimbal lock
    /// reported and resolved by `policy`.
    ///
    /// Infallible for a unit quaternion: only `atan2` and `hypot` of its components, no division.
    /// `q` and `−q` give the same angles.
    ///
    /// ```
    /// use gyrostat::rotation::{Euler, EulerSequence, GimbalPolicy, Pole};
    /// let seq = EulerSequence::ZYX;
    /// // Pitch exactly +90°: yaw and roll are not separately determined.
    /// let q = Euler::new(seq, [0.3f64, core::f64::consts::FRAC_PI_2, 0.1]).try_to_unit_quat()?;
    /// let sol = q.to_euler(seq, GimbalPolicy::ZeroThird);
    /// let lock = sol.singularity.expect("at the pole");
    /// assert_eq!(lock.pole, Pole::Upper);
    /// // Only yaw − roll is determined (s = −1 for ZYX at +90°): 0.3 − 0.1.
    /// assert!((lock.combined_angle - 0.2).abs() < 1e-15);
    /// assert!((sol.euler.angles[0] - 0.2).abs() < 1e-15 && sol.euler.angles[2] == 0.0);
    /// # Ok::<(), gyrostat::Error>(())
    /// ```
    pub fn to_euler(self, sequence: EulerSequence, policy: GimbalPolicy<T>) -> EulerSolution<T> {
        let q = self.as_quat();
        // Bernardes & Viollet work with extrinsic sequences: reverse an intrinsic one.
        let (axes, _) = sequence.product_order();
        // Extrinsic order e1, e2, e3 (first applied first) = product order reversed.
        let (i, j, k0) = (axes[2], axes[1], axes[0]);
        let proper = i == k0;
        let k = if proper { i.remaining(j) } else { k0 };
        // Parity of the permutation (i, j, k): +1 even, −1 odd.
        let sign = if parity(i, j) > 0 { T::ONE } else { -T::ONE };
        let (qi, qj, qk) = (comp(q, i), comp(q, j), comp(q, k) * sign);
        let (a, b, c, d) = if proper {
            (q.w, qi, qj, qk)
        } else {
            (q.w - qj, qi + qk, qj + q.w, qk - qi)
        };
        // |a|, |b|, |c|, |d| ≤ √2 for a unit quaternion, so the squares cannot overflow; an
        // underflow (components below 1e-19 in f32) changes the angle by less than that value.
        // Plain sqrt is several times faster than a scaling hypot.
        let n_ab = (a * a + b * b).sqrt();
        let n_cd = (c * c + d * d).sqrt();
        // Middle angle (raw, in [0, π]) and its distance to π, from one atan2 of the smaller
        // norm over the larger: that angle is the one near its pole's 0, accurate without a
        // π − x cancellation; the other is π minus it (far from its pole, where the cancellation
        // costs nothing).
        let near_upper = n_ab < n_cd;
        let (small, large) = if near_upper {
            (n_ab, n_cd)
        } else {
            (n_cd, n_ab)
        };
        let near = T::TWO * small.atan2(large);
        let (mid_raw, to_upper) = if near_upper {
            (T::PI - near, near)
        } else {
            (near, T::PI - near)
        };
        let half_sum = b.atan2(a);
        let half_diff = d.atan2(c);
        // The outer angles in the caller's order (extrinsic (θ1, θ3), intrinsic reversed), not
        // yet wrapped, from the two half-angles.
        let outer = |hs: T, hd: T| {
            let t1 = hs - hd;
            let t3 = if proper { hs + hd } else { (hs + hd) * sign };
            match sequence.frame() {
                Frame::Extrinsic => (t1, t3),
                Frame::Intrinsic => (t3, t1),
            }
        };
        let (first, third) = outer(half_sum, half_diff);
        let (mut first, mut third) = (wrap(first), wrap(third));
        let mid = if proper {
            mid_raw
        } else {
            mid_raw - T::FRAC_PI_2
        };
        let (pole, distance) = if n_ab >= n_cd {
            (Pole::Lower, mid_raw)
        } else {
            (Pole::Upper, to_upper)
        };
        let mut singularity = None;
        if distance <= gimbal_lock_threshold::<T>() {
            let s = lock_sign::<T>(sequence, pole);
            // `first + s·third` depends on one half-angle alone (the other one's terms cancel):
            // `half_diff` at the upper pole, `half_sum` at the lower, where the other is the
            // atan2 of two near-zero numbers. Evaluated from that half-angle with the other set
            // to zero it is `±2·half-angle` exactly, rounded once by the wrap; summing the
            // wrapped outer angles instead would add four roundings of angles up to π (about
            // 5e-7 rad in f32, half the accuracy contract).
            let (f0, t0) = match pole {
                Pole::Upper => outer(T::ZERO, half_diff),
                Pole::Lower => outer(half_sum, T::ZERO),
            };
            let combined = wrap(f0 + s * t0);
            match policy {
                GimbalPolicy::ZeroFirst => {
                    first = T::ZERO;
                    third = wrap(s * combined);
                }
                GimbalPolicy::ZeroThird => {
                    first = combined;
                    third = T::ZERO;
                }
                GimbalPolicy::ClosestTo([pa, _, pc]) if !(pa.is_finite() && pc.is_finite()) => {
                    // A non-finite previous solution carries no information: as ZeroThird.
                    first = combined;
                    third = T::ZERO;
                }
                GimbalPolicy::ClosestTo([pa, _, pc]) => {
                    // Minimise (first − pa)² + (third − pc)² on first + s·third = combined (mod 2π).
                    // Previous angles are wrapped first (their size would otherwise add rounding),
                    // and third is derived from first so the constraint holds to one rounding.
                    let (pa, pc) = (wrap_any(pa), wrap_any(pc));
                    let lambda = wrap(combined - pa - s * pc) * T::HALF;
                    first = wrap(pa + lambda);
                    third = wrap(s * (combined - first));
                }
            }
            singularity = Some(GimbalLock {
                pole,
                sign: s,
                combined_angle: combined,
                distance_to_pole: distance,
            });
        }
        EulerSolution {
            euler: Euler::new(sequence, [first, mid, third]),
            distance_to_pole: distance,
            singularity,
        }
    }
}

/// Wraps any finite angle into `(−π, π]` (for caller-provided angles of unknown range).
///
/// Within `[−3π, 3π]` one subtraction of `2π` does it. Beyond, `x − n·2π` would round (for
/// `|x|` of 1e12 in f32 the product `n·2π` is off by thousands of radians), so the residue is
/// taken as `atan2(sin x, cos x)`, whose argument reduction is exact.
#[inline]
pub(crate) fn wrap_any<T: Real>(x: T) -> T {
    let three_pi = T::from_f64(3.0) * T::PI;
    if x.abs() <= three_pi {
        wrap(x)
    } else {
        let (s, c) = x.sin_cos();
        let r = s.atan2(c);
        if r <= -T::PI { T::PI } else { r }
    }
}

/// The sign `s` with `first + s·third` determined at `pole` (see [`GimbalLock::sign`]).
fn lock_sign<T: Real>(sequence: EulerSequence, pole: Pole) -> T {
    let (axes, _) = sequence.product_order();
    let pole_sign: i8 = match pole {
        Pole::Lower => -1,
        Pole::Upper => 1,
    };
    let s = if sequence.is_proper() {
        // R_B(0)·e_A = e_A (s = +1); R_B(π)·e_A = −e_A (s = −1).
        -pole_sign
    } else {
        // R_j(±π/2)·e_k · e_i = ±ε_ijk for the product order (i, j, k).
        pole_sign * parity(axes[0], axes[1])
    };
    if s > 0 { T::ONE } else { -T::ONE }
}

impl<T: Real> TryFrom<Euler<T>> for UnitQuat<T> {
    type Error = Error;
    /// [`Euler::try_to_unit_quat`] (spinor sign of the elementary product kept).
    #[inline]
    fn try_from(e: Euler<T>) -> Result<Self, Error> {
        e.try_to_unit_quat()
    }
}

impl<T: Real> TryFrom<Euler<T>> for super::Dcm<T> {
    type Error = Error;
    /// The Euler matrix, through the quaternion ([`Euler::try_to_unit_quat`]).
    #[inline]
    fn try_from(e: Euler<T>) -> Result<Self, Error> {
        e.try_to_unit_quat().map(super::Dcm::from)
    }
}
