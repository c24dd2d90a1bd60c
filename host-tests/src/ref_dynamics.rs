//! Independent f64 reference for rigid-body dynamics.
//!
//! Written without gyrostat and differently from it on purpose:
//! - the attitude is a 3×3 rotation matrix `R` (body axes as columns, body → lab) integrated by
//!   `Ṙ = R·[ω]×`, not a quaternion;
//! - the Euler equations are integrated in the body-rate form
//!   `ω̇ = I⁻¹(τ − ḣ − ω × (Iω + h))` with `I⁻¹` from the cofactor formula, by classical RK4 with
//!   a step much smaller than the library's (so its error, `O(h⁴)`, is far below the tolerances);
//! - Hamiltonian models with a quartic term are integrated in the momentum form `J̇ = J × ∇H`
//!   with the gradient written out per component;
//! - the eigen-decomposition of a symmetric 3×3 matrix uses the closed trigonometric formula for
//!   the roots of the characteristic cubic (Smith 1961) and eigenvectors from cross products of
//!   the rows of `A − λ·1`, not Jacobi rotations.

#![allow(clippy::needless_range_loop)] // explicit indices mirror the formulas

use crate::reference::{M3, V3, add, cross, det, mat_mul, mat_vec, norm, scale, transpose};

fn madd(a: &M3, b: &M3, s: f64) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[i][j] + s * b[i][j]))
}

/// The cross-product matrix `[v]×`.
pub fn skew(v: V3) -> M3 {
    [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]
}

/// Inverse by cofactors over the determinant.
pub fn inverse(a: &M3) -> M3 {
    let d = det(a);
    let c = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]
    };
    // inverse[j][i] = cofactor(i, j) / det (cyclic indices give the signs).
    [0, 1, 2].map(|j| [0, 1, 2].map(|i| c(i, j) / d))
}

/// `R^T·v`: lab → body.
pub fn to_body(r: &M3, v: V3) -> V3 {
    mat_vec(&transpose(r), &v)
}

/// A torque law `τ(t, R, ω)` (body frame).
pub type TorqueLaw<'a> = &'a dyn Fn(f64, &M3, V3) -> V3;
/// A rotor momentum profile `t → (h, ḣ)` (body frame).
pub type RotorLaw<'a> = &'a dyn Fn(f64) -> (V3, V3);

/// Integrates the Euler equations `I ω̇ = −ω × (Iω + h) + τ − ḣ` with `Ṙ = R[ω]×` by RK4 with
/// `n` steps over `[0, t_end]`. Returns `(R, ω)` at `t_end`.
pub fn euler_rk4(
    inertia: &M3,
    r0: &M3,
    w0: V3,
    t_end: f64,
    n: usize,
    torque: TorqueLaw<'_>,
    rotor: RotorLaw<'_>,
) -> (M3, V3) {
    let inv = inverse(inertia);
    let f = |t: f64, r: &M3, w: V3| -> (M3, V3) {
        let (h, hd) = rotor(t);
        let l = add(mat_vec(inertia, &w), h);
        let rhs = [0, 1, 2].map(|i| torque(t, r, w)[i] - hd[i] - cross(w, l)[i]);
        (mat_mul(r, &skew(w)), mat_vec(&inv, &rhs))
    };
    let dt = t_end / n as f64;
    let (mut r, mut w) = (*r0, w0);
    for k in 0..n {
        let t = k as f64 * dt;
        let (a1, b1) = f(t, &r, w);
        let (a2, b2) = f(
            t + dt / 2.0,
            &madd(&r, &a1, dt / 2.0),
            add(w, scale(b1, dt / 2.0)),
        );
        let (a3, b3) = f(
            t + dt / 2.0,
            &madd(&r, &a2, dt / 2.0),
            add(w, scale(b2, dt / 2.0)),
        );
        let (a4, b4) = f(t + dt, &madd(&r, &a3, dt), add(w, scale(b3, dt)));
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] += dt / 6.0 * (a1[i][j] + 2.0 * a2[i][j] + 2.0 * a3[i][j] + a4[i][j]);
            }
            w[i] += dt / 6.0 * (b1[i] + 2.0 * b2[i] + 2.0 * b3[i] + b4[i]);
        }
    }
    (r, w)
}

/// A body-frame Hamiltonian in principal axes with rotor spin and a quartic term:
/// `H = Σ (Jᵢ − Sᵢ)²/(2Iᵢ) + t₄ ΣJᵢ⁴ + t₂₂ Σ_{i<j} Jᵢ²Jⱼ²`.
#[derive(Clone, Copy, Debug)]
pub struct RefModel {
    /// Principal moments.
    pub moments: V3,
    /// Rotor spin `S`.
    pub spin: V3,
    /// Octahedral coefficient `t₄`.
    pub t4: f64,
    /// Cubic coefficient `t₂₂`.
    pub t22: f64,
}

impl RefModel {
    /// The model with principal moments `moments`, rotor spin `spin` and quartic coefficients
    /// `t4` (octahedral), `t22` (cubic).
    pub const fn new(moments: V3, spin: V3, t4: f64, t22: f64) -> Self {
        Self {
            moments,
            spin,
            t4,
            t22,
        }
    }

    /// The energy.
    pub fn energy(&self, j: V3) -> f64 {
        let mut e = 0.0;
        for i in 0..3 {
            e += (j[i] - self.spin[i]).powi(2) / (2.0 * self.moments[i]) + self.t4 * j[i].powi(4);
        }
        e + self.t22
            * (j[0].powi(2) * j[1].powi(2)
                + j[0].powi(2) * j[2].powi(2)
                + j[1].powi(2) * j[2].powi(2))
    }

    /// The gradient `ω = ∂H/∂J`, component by component.
    pub fn gradient(&self, j: V3) -> V3 {
        [0, 1, 2].map(|i| {
            let others: f64 = (0..3).filter(|&k| k != i).map(|k| j[k] * j[k]).sum();
            (j[i] - self.spin[i]) / self.moments[i]
                + 4.0 * self.t4 * j[i].powi(3)
                + 2.0 * self.t22 * j[i] * others
        })
    }
}

/// Integrates `J̇ = J × ∇H(J)`, `Ṙ = R[∇H]×` by RK4 with `n` steps. Returns `(R, J)`.
pub fn lie_poisson_rk4(model: &RefModel, r0: &M3, j0: V3, t_end: f64, n: usize) -> (M3, V3) {
    let f = |r: &M3, j: V3| -> (M3, V3) {
        let w = model.gradient(j);
        (mat_mul(r, &skew(w)), cross(j, w))
    };
    let dt = t_end / n as f64;
    let (mut r, mut j) = (*r0, j0);
    for _ in 0..n {
        let (a1, b1) = f(&r, j);
        let (a2, b2) = f(&madd(&r, &a1, dt / 2.0), add(j, scale(b1, dt / 2.0)));
        let (a3, b3) = f(&madd(&r, &a2, dt / 2.0), add(j, scale(b2, dt / 2.0)));
        let (a4, b4) = f(&madd(&r, &a3, dt), add(j, scale(b3, dt)));
        for i in 0..3 {
            for k in 0..3 {
                r[i][k] += dt / 6.0 * (a1[i][k] + 2.0 * a2[i][k] + 2.0 * a3[i][k] + a4[i][k]);
            }
            j[i] += dt / 6.0 * (b1[i] + 2.0 * b2[i] + 2.0 * b3[i] + b4[i]);
        }
    }
    (r, j)
}

/// Eigenvalues of a symmetric 3×3 matrix, ascending, by the trigonometric solution of the
/// characteristic cubic (O. K. Smith, CACM 4(4), 1961).
pub fn sym_eigenvalues(a: &M3) -> V3 {
    let p1 = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
    let q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    if p1 == 0.0 {
        let mut d = [a[0][0], a[1][1], a[2][2]];
        d.sort_by(|x, y| x.total_cmp(y));
        return d;
    }
    let p2 = (a[0][0] - q).powi(2) + (a[1][1] - q).powi(2) + (a[2][2] - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let b = [0, 1, 2].map(|i| [0, 1, 2].map(|j| (a[i][j] - if i == j { q } else { 0.0 }) / p));
    let r = (det(&b) / 2.0).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let e1 = q + 2.0 * p * phi.cos();
    let e3 = q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos();
    let e2 = 3.0 * q - e1 - e3;
    [e3, e2, e1]
}

/// A unit eigenvector for a simple eigenvalue `lambda`: the longest cross product of two rows
/// of `A − λ·1`.
pub fn sym_eigenvector(a: &M3, lambda: f64) -> V3 {
    let m = [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[i][j] - if i == j { lambda } else { 0.0 }));
    let c = [cross(m[0], m[1]), cross(m[0], m[2]), cross(m[1], m[2])];
    let best = c
        .iter()
        .copied()
        .max_by(|x, y| norm(*x).total_cmp(&norm(*y)))
        .unwrap_or([1.0, 0.0, 0.0]);
    scale(best, 1.0 / norm(best))
}

/// Least-squares slope of `log(y)` against `log(x)`: a measured convergence order.
pub fn log_log_slope(x: &[f64], y: &[f64]) -> f64 {
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = y.iter().map(|v| v.ln()).collect();
    linear_fit(&lx, &ly).0
}

/// Least-squares line `y ≈ slope·x + intercept`; returns `(slope, intercept)`.
pub fn linear_fit(x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let my = y.iter().sum::<f64>() / n;
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    let slope = sxy / sxx;
    (slope, my - slope * mx)
}
