//! Independent closed forms for attitude propagation.
//!
//! Plain f64 `std` code that never calls gyrostat. Quaternions here are `[w, x, y, z]` arrays
//! (Hamilton, scalar first, attitude maps body → lab, as the crate), written out by hand.
//!
//! # Classical coning motion
//! The body is rotated by the FIXED angle `α` (the half-cone angle) about an axis in the lab
//! x–y plane that turns at the rate `Ω` about lab z:
//!
//! `u(t) = (cos Ωt, sin Ωt, 0)`,  `R(t) = Rodrigues(u(t), α)`,
//! `q(t) = (cos(α/2), sin(α/2) cos Ωt, sin(α/2) sin Ωt, 0)`.
//!
//! The body z axis sweeps a cone of half-angle `α` about lab z. The body rate, from
//! `ω = 2 vec(q* ⊗ q̇)` with `q* = (c, −s cos Ωt, −s sin Ωt, 0)`, `q̇ = (0, −sΩ sin Ωt,
//! sΩ cos Ωt, 0)` (`s = sin(α/2)`, `c = cos(α/2)`): the scalar part cancels, the vector part is
//! `c q̇_v + q*_v × q̇_v = (−csΩ sin Ωt, csΩ cos Ωt, −s²Ω)`, so
//!
//! `ω(t) = (−Ω sin α sin Ωt, Ω sin α cos Ωt, −Ω (1 − cos α))`.
//!
//! The transverse part rotates at `Ω` with amplitude `Ω sin α`; the constant axial part
//! `−Ω(1 − cos α) ≈ −α²Ω/2` is the true coning rate that the algorithms must reproduce from the
//! increments. The exact increments over `[a, b]` integrate the sinusoids:
//!
//! `Δθ = (sin α (cos Ωb − cos Ωa), sin α (sin Ωb − sin Ωa), −Ω(1 − cos α)(b − a))`,
//!
//! evaluated with the product forms `cos B − cos A = −2 sin((A+B)/2) sin((B−A)/2)` and
//! `sin B − sin A = 2 cos((A+B)/2) sin((B−A)/2)` to avoid cancellation for short intervals.

use crate::reference::{M3, Q, V3, qconj, qmul, rodrigues};

/// Classical coning motion with half-cone angle `alpha` (rad) and coning rate `omega_c` (rad/s).
#[derive(Clone, Copy, Debug)]
pub struct Coning {
    /// Half-cone angle α.
    pub alpha: f64,
    /// Coning frequency Ω (rad/s).
    pub omega_c: f64,
}

impl Coning {
    /// The exact attitude `q(t)`.
    pub fn attitude(&self, t: f64) -> Q {
        let (s, c) = (0.5 * self.alpha).sin_cos();
        let (sw, cw) = (self.omega_c * t).sin_cos();
        [c, s * cw, s * sw, 0.0]
    }

    /// The exact rotation matrix `R(t)` (Rodrigues about the turning axis, seed (6.6.15)).
    pub fn matrix(&self, t: f64) -> M3 {
        let (sw, cw) = (self.omega_c * t).sin_cos();
        rodrigues([cw, sw, 0.0], self.alpha)
    }

    /// The exact body rate `ω(t)`.
    pub fn body_rate(&self, t: f64) -> V3 {
        let (sa, ca) = self.alpha.sin_cos();
        let w = self.omega_c;
        let (sw, cw) = (w * t).sin_cos();
        [-w * sa * sw, w * sa * cw, -w * (1.0 - ca)]
    }

    /// The exact increment `∫ₐᵇ ω dt`.
    pub fn increment(&self, a: f64, b: f64) -> V3 {
        let w = self.omega_c;
        let sa = self.alpha.sin();
        // 1 − cos α = 2 sin²(α/2), without cancellation for small α.
        let one_minus_ca = 2.0 * (0.5 * self.alpha).sin().powi(2);
        let mid = 0.5 * w * (a + b);
        let half = (0.5 * w * (b - a)).sin();
        [
            -2.0 * sa * mid.sin() * half,
            2.0 * sa * mid.cos() * half,
            -w * one_minus_ca * (b - a),
        ]
    }

    /// The true coning rate along the body z axis: `−Ω(1 − cos α)`.
    pub fn axial_rate(&self) -> f64 {
        -self.omega_c * 2.0 * (0.5 * self.alpha).sin().powi(2)
    }
}

/// The body-frame attitude error `e = q_true* ⊗ q_est` as a small rotation vector
/// `2 sign(e_w) e_v` (valid for small errors, which is all the drift tests produce; exact to
/// relative `O(|e|²)`).
pub fn body_error(q_true: Q, q_est: Q) -> V3 {
    let e = qmul(qconj(q_true), q_est);
    let s = if e[0] < 0.0 { -2.0 } else { 2.0 };
    [s * e[1], s * e[2], s * e[3]]
}

/// Least-squares slope of `ys` against `ts`.
pub fn fit_slope(ts: &[f64], ys: &[f64]) -> f64 {
    let n = ts.len() as f64;
    let tm = ts.iter().sum::<f64>() / n;
    let ym = ys.iter().sum::<f64>() / n;
    let mut num = 0.0;
    let mut den = 0.0;
    for (t, y) in ts.iter().zip(ys) {
        num += (t - tm) * (y - ym);
        den += (t - tm) * (t - tm);
    }
    num / den
}

/// Spin precession about a fixed crank axis, seed (6.6.16a–c).
///
/// A body turns at the constant rate `Ω` about the lab-fixed crank axis
/// `Ω̂ = (cos φ sin ϑ, sin φ sin ϑ, cos ϑ)` (polar angle ϑ from the A = Z axis, azimuth φ),
/// starting from the identity. The unit spin vector `S` that starts along A = Z (the body z
/// axis) is, with `Θ = Ωt`:
///
/// - `S_A = S_Z = 1 − 2 sin²ϑ sin²(Θ/2)`  (6.6.16a)
/// - for `φ = 0`: `S_B = S_X = sin 2ϑ sin²(Θ/2)` (6.6.16b), `S_C = S_Y = −sin ϑ sin Θ` (6.6.16c)
/// - for any `φ`: `(S_X, S_Y)` is `(S_B, S_C)` of `φ = 0` rotated by `φ` about Z (the seed's
///   azimuth matrix after (6.6.16c)).
///
/// Returns the lab coordinates `[S_X, S_Y, S_Z]`.
pub fn spin_precession(theta_polar: f64, phi_azimuth: f64, big_omega: f64, t: f64) -> V3 {
    let th = big_omega * t;
    let s2 = (0.5 * th).sin().powi(2);
    let sa = 1.0 - 2.0 * theta_polar.sin().powi(2) * s2;
    let sb = (2.0 * theta_polar).sin() * s2;
    let sc = -theta_polar.sin() * th.sin();
    let (sp, cp) = phi_azimuth.sin_cos();
    [cp * sb - sp * sc, sp * sb + cp * sc, sa]
}

/// The crank axis `Ω̂ = (cos φ sin ϑ, sin φ sin ϑ, cos ϑ)` of [`spin_precession`].
pub fn crank_axis(theta_polar: f64, phi_azimuth: f64) -> V3 {
    let (st, ct) = theta_polar.sin_cos();
    let (sp, cp) = phi_azimuth.sin_cos();
    [cp * st, sp * st, ct]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{mat_mul, transpose};

    /// The closed-form body rate satisfies `Rᵀ Ṙ = [ω×]` with `Ṙ` by central differences of the
    /// Rodrigues matrix (an independent route to the same ω).
    #[test]
    fn coning_body_rate_matches_rodrigues_derivative() {
        let c = Coning {
            alpha: 0.3,
            omega_c: 2.0,
        };
        for &t in &[0.0, 0.4, 1.3, 2.9] {
            let h = 1e-5;
            let (rp, rm) = (c.matrix(t + h), c.matrix(t - h));
            let mut rdot = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    rdot[i][j] = (rp[i][j] - rm[i][j]) / (2.0 * h);
                }
            }
            let s = mat_mul(&transpose(&c.matrix(t)), &rdot);
            let w = c.body_rate(t);
            let from_skew = [s[2][1], s[0][2], s[1][0]];
            for k in 0..3 {
                assert!((from_skew[k] - w[k]).abs() < 1e-8, "t={t} k={k}");
            }
        }
    }

    /// The increment equals a fine Simpson quadrature of the body rate.
    #[test]
    fn coning_increment_matches_quadrature() {
        let c = Coning {
            alpha: 0.2,
            omega_c: 3.0,
        };
        let (a, b) = (0.7, 0.95);
        let n = 200;
        let h = (b - a) / n as f64;
        let mut s = [0.0; 3];
        for i in 0..=n {
            let wgt = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let w = c.body_rate(a + i as f64 * h);
            for k in 0..3 {
                s[k] += wgt * w[k] * h / 3.0;
            }
        }
        let d = c.increment(a, b);
        for k in 0..3 {
            assert!((s[k] - d[k]).abs() < 1e-12);
        }
    }

    /// (6.6.16) agrees with the z column of the Rodrigues matrix (6.6.15) about the crank axis.
    #[test]
    fn spin_precession_matches_rodrigues_column() {
        for &(th, ph, t) in &[(0.4, 0.0, 0.7), (1.1, 0.6, 2.3), (0.955, 0.785, 5.0)] {
            let r = rodrigues(crank_axis(th, ph), 1.7 * t);
            let s = spin_precession(th, ph, 1.7, t);
            for k in 0..3 {
                assert!((r[k][2] - s[k]).abs() < 1e-14);
            }
        }
    }
}
