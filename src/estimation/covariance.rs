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
    pub fn predict(&mut self, f: Mat3<T>, q_theta: T, q_bias: T) {
        let fc = f * self.bias;
        let fbt = f * self.cross.transpose();
        let a = self.attitude + fbt + fbt.transpose() + fc * f.transpose();
        self.attitude = symmetric(a) + Mat3::from_diagonal(Vec3::new(q_theta, q_theta, q_theta));
        self.cross = self.cross + fc;
        self.bias = self.bias + Mat3::from_diagonal(Vec3::new(q_bias, q_bias, q_bias));
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

    /// The Kalman update for a scalar measurement of state component `i` with variance `r`:
    /// returns the gain `K = P eᵢ / (Pᵢᵢ + r)` and applies `P ← P − K Pᵢ,:` (the covariance
    /// after the update, symmetric by construction: `Pⱼ,ᵢ Pᵢ,ₖ / s`).
    pub fn update_component(&mut self, i: usize, r: T) -> [T; 6] {
        let p = self.row(i);
        let s = p[i.min(5)] + r;
        let inv = T::ONE / s;
        let k = p.map(|v| v * inv);
        for (row, &kr) in k.iter().enumerate() {
            for (col, &pc) in p.iter().enumerate() {
                self.sub_at(row, col, kr * pc);
            }
        }
        k
    }

    /// The update of the attitude component `i` alone (a gain `k` on `δθᵢ`, none on the others:
    /// the heading update, which must not move inclination or bias), in Joseph form
    /// `P ← (I − K H) P (I − K H)ᵀ + K r Kᵀ`, valid for any gain: row and column `i` scale by
    /// `1 − k`, and `Pᵢᵢ ← (1 − k)² Pᵢᵢ + k² r`.
    pub fn update_attitude_axis_only(&mut self, i: usize, k: T, r: T) {
        let i = i.min(2);
        let s = T::ONE - k;
        let pii = self.attitude.m[i][i];
        for j in 0..3 {
            self.attitude.m[i][j] *= s;
            self.attitude.m[j][i] *= s;
            self.cross.m[i][j] *= s;
        }
        self.attitude.m[i][i] = s * s * pii + k * k * r;
    }

    /// The heading update with the tilt coupling: the measurement `ψ = δθ_z + c·δθ_y + noise`
    /// (`c = tan(dip)`: a tilt error about the earth's north axis turns the field's vertical
    /// part into the horizontal plane), with a gain on `δθ_z` only. The gain minimising the
    /// heading variance is `k = uᵢ/s`, `u = P h`, `s = hᵀ P h + r`, `h = (0, c, 1, 0, 0, 0)`;
    /// then `P ← P − k(e_z uᵀ + u e_zᵀ) + k² s e_z e_zᵀ` (Joseph form for that gain). Returns
    /// `k`.
    pub fn update_heading(&mut self, c: T, r: T) -> T {
        let py = self.row(1);
        let pz = self.row(2);
        // Zipped rather than indexed: no bounds check for the optimiser to remove (at
        // opt-level "s" it stays, a panicking branch in the C interface's size-optimised build).
        let mut u = pz;
        for (uj, &pyj) in u.iter_mut().zip(&py) {
            *uj = c * pyj + *uj;
        }
        let s = c * u[1] + u[2] + r;
        let k = u[2] / s;
        for (j, &uj) in u.iter().enumerate() {
            // Row z and column z, each once (the diagonal below).
            if j != 2 {
                self.sub_at(2, j, k * uj);
                if j < 3 {
                    self.sub_at(j, 2, k * uj);
                }
            }
        }
        self.attitude.m[2][2] = self.attitude.m[2][2] - (k * u[2]).twice() + k * k * s;
        k
    }

    /// Adds `v` to the attitude variance of every axis (an unmodelled extra rotation, such as a
    /// saturated gyroscope sample).
    pub fn inflate_attitude(&mut self, v: T) {
        self.attitude = self.attitude + Mat3::from_diagonal(Vec3::new(v, v, v));
    }

    fn sub_at(&mut self, row: usize, col: usize, d: T) {
        match (row < 3, col < 3) {
            (true, true) => self.attitude.m[row][col] -= d,
            (true, false) => self.cross.m[row][(col - 3).min(2)] -= d,
            (false, true) => {
                // The lower-left block is Bᵀ: the upper-right update covers it.
            }
            (false, false) => self.bias.m[(row - 3).min(2)][(col - 3).min(2)] -= d,
        }
    }
}

/// `(M + Mᵀ)/2`.
fn symmetric<T: Real>(m: Mat3<T>) -> Mat3<T> {
    (m + m.transpose()).scale(T::HALF)
}
