//! The error covariance of the attitude-and-bias filter: a symmetric 6×6 matrix kept as three
//! 3×3 blocks, `P = [[A, B], [Bᵀ, C]]`, over the error state `x = (δθ, δb)`: `δθ` the attitude
//! error in the earth frame (`q_true = exp(δθ) ⊗ q̂`, rad) and `δb` the gyroscope bias error in
//! the sensor frame (rad/s).

use crate::{Mat3, Real, Vec3};

/// `P = [[A, B], [Bᵀ, C]]` (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Covariance<T> {
    /// `A = E[δθ δθᵀ]` (rad²), earth frame.
    pub attitude: Mat3<T>,
    /// `B = E[δθ δbᵀ]` (rad²/s).
    pub cross: Mat3<T>,
    /// `C = E[δb δbᵀ]` (rad²/s²), sensor frame.
    pub bias: Mat3<T>,
}

impl<T: Real> Covariance<T> {
    /// `diag(σ_θ², σ_θ², σ_θ², σ_b², σ_b², σ_b²)`.
    pub fn diagonal(attitude_var: T, bias_var: T) -> Self {
        Self {
            attitude: Mat3::from_diagonal(Vec3::new(attitude_var, attitude_var, attitude_var)),
            cross: Mat3::ZERO,
            bias: Mat3::from_diagonal(Vec3::new(bias_var, bias_var, bias_var)),
        }
    }

    /// The prediction `P ← Φ P Φᵀ + Q` over one step with the closed-form transition of the
    /// error state, `Φ = [[I, F], [0, I]]`, `F = −R̂·Δt`: a bias error `δb` turns the estimate
    /// by `−R̂ δb Δt` in the earth frame (`R̂` the estimated attitude, sensor → earth), and an
    /// earth-frame attitude error is not turned by the motion (it is the same rotation in the
    /// earth frame whatever the body does). `Q = diag(q_θ I, q_b I)`: the gyroscope's white
    /// noise (`σ_g²·Δt`, isotropic, so the same in every frame) and the bias random walk.
    ///
    /// `A' = A + F Bᵀ + B Fᵀ + F C Fᵀ + q_θ I`, `B' = B + F C`, `C' = C + q_b I`.
    ///
    /// `A'` is formed in its upper triangle and mirrored (`(F C Fᵀ)ⱼₖ = (F C)ⱼ · Fₖ` for `j ≤ k`
    /// only), so it is symmetric by construction.
    pub fn predict(&mut self, f: Mat3<T>, q_theta: T, q_bias: T) {
        let fc = f * self.bias;
        let fbt = f * self.cross.transpose();
        let a = &mut self.attitude.m;
        #[allow(
            clippy::needless_range_loop,
            reason = "a triangle: each a[j][c] is written with its mirror a[c][j]"
        )]
        for j in 0..3 {
            let fcj = fc.row(j);
            for c in j..3 {
                let v = a[j][c] + fbt.m[j][c] + fbt.m[c][j] + fcj.dot(f.row(c));
                let v = if j == c { v + q_theta } else { v };
                a[j][c] = v;
                a[c][j] = v;
            }
        }
        self.cross = self.cross + fc;
        for j in 0..3 {
            self.bias.m[j][j] += q_bias;
        }
    }

    /// Row `i` of `P` (0–2 attitude, 3–5 bias; larger indices read as 5).
    pub fn row(&self, i: usize) -> [T; 6] {
        if i < 3 {
            let a = self.attitude.row(i);
            let b = self.cross.row(i);
            [a.x, a.y, a.z, b.x, b.y, b.z]
        } else {
            let b = self.cross.col(i - 3);
            let c = self.bias.row(i - 3);
            [b.x, b.y, b.z, c.x, c.y, c.z]
        }
    }

    /// Entry `(j, k)` of `P` (indices as in [`Covariance::row`]).
    fn at(&self, j: usize, k: usize) -> T {
        self.row(j).get(k.min(5)).copied().unwrap_or(T::ZERO)
    }

    /// Sets entry `(j, k)` and its mirror `(k, j)` (one stored number for the cross block).
    fn set_sym(&mut self, j: usize, k: usize, v: T) {
        let (j, k) = (j.min(5), k.min(5));
        match (j < 3, k < 3) {
            (true, true) => {
                self.attitude.m[j][k] = v;
                self.attitude.m[k][j] = v;
            }
            (true, false) => self.cross.m[j][k - 3] = v,
            (false, true) => self.cross.m[k][j - 3] = v,
            (false, false) => {
                self.bias.m[j - 3][k - 3] = v;
                self.bias.m[k - 3][j - 3] = v;
            }
        }
    }

    /// The Kalman update for a scalar measurement of state component `i` with variance `r`:
    /// returns the gain `K = p/s`, `p = P eᵢ`, `s = pᵢ + r`, and sets `P` to the covariance
    /// after the update, `P − p pᵀ/s`, in a form that stays symmetric and positive
    /// semi-definite in floating point:
    ///
    /// - row and column `i` in Joseph form, `(I − K eᵢᵀ) P (I − K eᵢᵀ)ᵀ + K r Kᵀ`, with the
    ///   factor `1 − Kᵢ = r/s` formed as that quotient (not as a difference): `P'ᵢₖ = g² pₖ +
    ///   r Kᵢ Kₖ`, `g = r/s`, so the measured variance `P'ᵢᵢ = g² pᵢ + r Kᵢ² = pᵢ r/s` is
    ///   positive and at most `r` however much larger `pᵢ` is (the plain `pᵢ − pᵢ²/s` cancels
    ///   to rounding noise there);
    /// - every other entry as `Pⱼₖ − (pⱼ pₖ)/s`, the product formed before the division so
    ///   that `(j, k)` and `(k, j)` are the same number; each is written once for both
    ///   triangles. A variance that rounding takes below zero is set to zero.
    ///
    /// A measurement that carries no information (`s` not finite or not positive: an infinite
    /// `r`, or `pᵢ = r = 0`) leaves `P` unchanged and returns a zero gain.
    pub fn update_component(&mut self, i: usize, r: T) -> [T; 6] {
        let i = i.min(5);
        let p = self.row(i);
        let pi = p[i];
        let s = pi + r;
        if !(s.is_finite() && s > T::ZERO) {
            return [T::ZERO; 6];
        }
        let inv = T::ONE / s;
        let k = p.map(|v| v * inv);
        // Every entry of the upper triangle off row and column `i` as `Pⱼₖ − (pⱼ pₖ)/s`,
        // written to both triangles (each block read in its upper triangle only, before it is
        // written), then row and column `i` in Joseph form (from `p` and `K`, which the
        // entries written first do not enter: row and column `i` are not formed twice).
        let a = &mut self.attitude.m;
        for j in 0..3 {
            for c in j..3 {
                if j != i && c != i {
                    let v = a[j][c] - p[j] * p[c] * inv;
                    let v = if j == c { v.max(T::ZERO) } else { v };
                    a[j][c] = v;
                    a[c][j] = v;
                }
            }
        }
        let b = &mut self.cross.m;
        for j in 0..3 {
            for c in 0..3 {
                if j != i && c + 3 != i {
                    b[j][c] -= p[j] * p[c + 3] * inv;
                }
            }
        }
        let cb = &mut self.bias.m;
        for j in 0..3 {
            for c in j..3 {
                if j + 3 != i && c + 3 != i {
                    let v = cb[j][c] - p[j + 3] * p[c + 3] * inv;
                    let v = if j == c { v.max(T::ZERO) } else { v };
                    cb[j][c] = v;
                    cb[c][j] = v;
                }
            }
        }
        let g = r * inv;
        let gg = g * g;
        let ki = k[i];
        for (j, (&pj, &kj)) in p.iter().zip(&k).enumerate() {
            // `r Kⱼ Kᵢ` in the order of the lower triangle's loop (`j` the row).
            let rk = if j < i { r * kj * ki } else { r * ki * kj };
            let v = gg * pj + rk;
            self.set_sym(i, j, if j == i { v.max(T::ZERO) } else { v });
        }
        k
    }

    /// The update of the attitude component `i` alone (a gain `k` on `δθᵢ`, none on the others:
    /// the heading update, which must not move inclination or bias), in Joseph form
    /// `P ← (I − K H) P (I − K H)ᵀ + K r Kᵀ`, valid for any gain: row and column `i` scale by
    /// `1 − k`, and `Pᵢᵢ ← (1 − k)² Pᵢᵢ + k² r`. Returns the gain applied: `k`, or 0 (and `P`
    /// unchanged) when `r` is not finite (a measurement without information).
    pub fn update_attitude_axis_only(&mut self, i: usize, k: T, r: T) -> T {
        if !r.is_finite() {
            return T::ZERO;
        }
        let i = i.min(2);
        let s = T::ONE - k;
        let pii = self.attitude.m[i][i];
        for j in 0..3 {
            self.attitude.m[i][j] *= s;
            self.attitude.m[j][i] *= s;
            self.cross.m[i][j] *= s;
        }
        self.attitude.m[i][i] = s * s * pii + k * k * r;
        k
    }

    /// The heading update with the tilt coupling: the measurement `ψ = δθ_z + c·δθ_y + noise`
    /// (`c = tan(dip)`: a tilt error about the earth's north axis turns the field's vertical
    /// part into the horizontal plane), with a gain on `δθ_z` only. The gain minimising the
    /// heading variance is `k = u_z/s`, `u = P h`, `s = hᵀ P h + r`, `h = (0, c, 1, 0, 0, 0)`;
    /// `P` is updated in Joseph form, `P ← A P Aᵀ + k² r e_z e_zᵀ` with `A = I − k e_z hᵀ`:
    /// only row and column `z` change, `P'_zj = (1 − k) P_zj − k c P_yj` and `P'_zz` the
    /// quadratic form `(1 − k)² P_zz − 2(1 − k) k c P_yz + k² c² P_yy + k² r`, with `1 − k =
    /// (c u_y + r)/s` formed as that quotient (no cancellation when `r ≪ s`). Returns `k`; 0,
    /// with `P` unchanged, when `s` is not finite and positive (no information: an infinite
    /// `r` or a field at the vertical).
    pub fn update_heading(&mut self, c: T, r: T) -> T {
        let py = self.row(1);
        let pz = self.row(2);
        let u1 = c * py[1] + pz[1];
        let u2 = c * py[2] + pz[2];
        let s = c * u1 + u2 + r;
        if !(s.is_finite() && s > T::ZERO) {
            return T::ZERO;
        }
        let k = u2 / s;
        let g = (c * u1 + r) / s;
        let kc = k * c;
        // Zipped rather than indexed: no bounds check for the optimiser to remove (at
        // opt-level "s" it stays, a panicking branch in the C interface's size-optimised build).
        for (j, (&pyj, &pzj)) in py.iter().zip(&pz).enumerate() {
            if j != 2 {
                self.set_sym(2, j, g * pzj - kc * pyj);
            }
        }
        let zz = g * g * pz[2] - (g * kc * py[2]).twice() + kc * kc * py[1] + k * k * r;
        self.attitude.m[2][2] = zz.max(k * k * r);
        k
    }

    /// Adds `v` to the attitude variance of every axis (an unmodelled extra rotation, such as a
    /// saturated gyroscope sample).
    pub fn inflate_attitude(&mut self, v: T) {
        self.attitude = self.attitude + Mat3::from_diagonal(Vec3::new(v, v, v));
    }

    /// Adds `v` to the heading variance (earth `z` axis) alone: `P ← P + v e_z e_zᵀ`.
    pub fn inflate_heading(&mut self, v: T) {
        self.attitude.m[2][2] += v;
    }

    /// Bounds the variances: every attitude variance at most `attitude_max` and every bias
    /// variance at most `bias_max`, by the congruence `P ← D P D` with `D` diagonal, `Dⱼ =
    /// √(max/Pⱼⱼ)` for a variance above its bound and 1 otherwise. A congruence keeps `P`
    /// symmetric and positive semi-definite and its correlations unchanged; it only says that
    /// an error cannot be larger than its physical bound (an attitude error is within ±π,
    /// a bias within the filter's clip).
    pub fn bound(&mut self, attitude_max: T, bias_max: T) {
        let scale = |v: T, max: T| if v > max { (max / v).sqrt() } else { T::ONE };
        let (a, c) = (&self.attitude.m, &self.bias.m);
        let d = [
            scale(a[0][0], attitude_max),
            scale(a[1][1], attitude_max),
            scale(a[2][2], attitude_max),
            scale(c[0][0], bias_max),
            scale(c[1][1], bias_max),
            scale(c[2][2], bias_max),
        ];
        if d.iter().all(|&x| x == T::ONE) {
            return;
        }
        for j in 0..6 {
            for c in j..6 {
                if let (Some(&dj), Some(&dc)) = (d.get(j), d.get(c)) {
                    let v = self.at(j, c) * dj * dc;
                    self.set_sym(j, c, v);
                }
            }
        }
    }
}
