//! The shared f64 toolkit of the independent reference: vectors, 3×3 matrices, quaternions as
//! plain arrays, Rodrigues rotations and SU(2) matrices. Every reference module and test builds
//! on these; none of them calls gyrostat.
//!
//! Written from the seed's formulas, not from gyrostat's code: rotation matrices come from the
//! Rodrigues form (6.6.13)–(6.6.15) of an axis and angle, spinors from the 2×2 matrix (6.6.4),
//! quaternion products from the Hamilton rule written out.

/// A 3×3 matrix, `m[row][col]`.
pub type M3 = [[f64; 3]; 3];
/// A 3-vector.
pub type V3 = [f64; 3];
/// A quaternion `[w, x, y, z]` (Hamilton, scalar first; an attitude maps body → lab).
pub type Q = [f64; 4];

/// `a + b`.
pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `s·a`.
pub fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Dot product.
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product.
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Euclidean norm.
pub fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// Hamilton product `a ⊗ b`, written out.
pub fn qmul(a: Q, b: Q) -> Q {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// Conjugate.
pub fn qconj(a: Q) -> Q {
    [a[0], -a[1], -a[2], -a[3]]
}

/// Rotates `v` by the unit quaternion `q`: the vector part of `q ⊗ (0, v) ⊗ q*`.
pub fn qrotate(q: Q, v: V3) -> V3 {
    let r = qmul(qmul(q, [0.0, v[0], v[1], v[2]]), qconj(q));
    [r[1], r[2], r[3]]
}

/// The rotation matrix of a quaternion `[w, x, y, z]` (normalised here): column `j` is
/// `q ⊗ (0, e_j) ⊗ q*`, by explicit Hamilton products.
pub fn quat_matrix(q: Q) -> M3 {
    let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let q = q.map(|c| c / n);
    let qc = qconj(q);
    let mut r = [[0.0; 3]; 3];
    for j in 0..3 {
        let mut e = [0.0; 4];
        e[j + 1] = 1.0;
        let v = qmul(qmul(q, e), qc);
        for i in 0..3 {
            r[i][j] = v[i + 1];
        }
    }
    r
}

/// `exp(φ) = (cos(θ/2), sin(θ/2)·φ/θ)`, `θ = |φ|`, by `sin`/`cos` of the half angle (the
/// identity for `φ = 0`).
pub fn quat_exp(phi: V3) -> Q {
    let t = norm(phi);
    if t == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    let (s, c) = (0.5 * t).sin_cos();
    [c, s * phi[0] / t, s * phi[1] / t, s * phi[2] / t]
}

/// The f32 floor of an attitude: rounding each component of a unit quaternion to f32 moves it by
/// at most half an ulp below 1, 2⁻²⁵, and turns it by at most `2·√3·2⁻²⁵ ≈ 1.03e-7` rad.
pub const F32_FLOOR: f64 = 2.0 * 1.732_050_808 / 33_554_432.0;

/// The rotation angle between two attitudes in `[0, π]` (SO(3) view: `q` and `−q` agree):
/// `2 atan2(|v|, |w|)` of `a* ⊗ b`, accurate for tiny angles (unlike `acos` of the dot
/// product).
pub fn quat_angle(a: Q, b: Q) -> f64 {
    let e = qmul(qconj(a), b);
    let v = (e[1] * e[1] + e[2] * e[2] + e[3] * e[3]).sqrt();
    2.0 * v.atan2(e[0].abs())
}

/// A complex number `(re, im)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct C {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

// Plain named methods (not operator traits) keep the reference code explicit about every
// complex operation it performs.
#[allow(clippy::should_implement_trait)]
impl C {
    /// Builds `re + i·im`.
    pub const fn new(re: f64, im: f64) -> Self {
        Self { re, im }
    }
    /// Product.
    pub fn mul(self, o: C) -> C {
        C::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    /// Sum.
    pub fn add(self, o: C) -> C {
        C::new(self.re + o.re, self.im + o.im)
    }
    /// Modulus of the difference.
    pub fn dist(self, o: C) -> f64 {
        (self.re - o.re).hypot(self.im - o.im)
    }
}

/// A 2×2 complex matrix.
pub type U2 = [[C; 2]; 2];

/// Matrix product.
pub fn mat_mul(a: &M3, b: &M3) -> M3 {
    let mut r = [[0.0; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().enumerate() {
            *e = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}

/// Matrix times vector.
pub fn mat_vec(a: &M3, v: &V3) -> V3 {
    [0, 1, 2].map(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

/// Transpose.
pub fn transpose(a: &M3) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[j][i]))
}

/// Determinant by cofactor expansion along the first row.
pub fn det(a: &M3) -> f64 {
    a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
}

/// Largest absolute entry of `a − b`.
pub fn mat_dist(a: &M3, b: &M3) -> f64 {
    (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| (a[i][j] - b[i][j]).abs())
        .fold(0.0, f64::max)
}

/// Largest absolute component of `a − b`.
pub fn vec_dist(a: &V3, b: &V3) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// The identity matrix.
pub const IDENTITY: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The rotation matrix of seed (6.6.14)–(6.6.15) for angle `theta` about `axis` (normalised
/// here): `R_ML = δ_ML cos Θ − ε_LKM Θ̂_K sin Θ + (1 − cos Θ) Θ̂_M Θ̂_L`.
pub fn rodrigues(axis: V3, theta: f64) -> M3 {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let a = axis.map(|c| c / n);
    let (s, c) = theta.sin_cos();
    let mut r = [[0.0; 3]; 3];
    for (m, row) in r.iter_mut().enumerate() {
        for (l, e) in row.iter_mut().enumerate() {
            let delta = if m == l { 1.0 } else { 0.0 };
            let eps_term: f64 = (0..3).map(|k| levi_civita(l, k, m) * a[k]).sum();
            *e = delta * c - eps_term * s + (1.0 - c) * a[m] * a[l];
        }
    }
    r
}

/// The Levi-Civita symbol ε_ijk.
pub fn levi_civita(i: usize, j: usize, k: usize) -> f64 {
    match (i, j, k) {
        (0, 1, 2) | (1, 2, 0) | (2, 0, 1) => 1.0,
        (0, 2, 1) | (2, 1, 0) | (1, 0, 2) => -1.0,
        _ => 0.0,
    }
}

/// The spinor matrix of seed (6.6.4) for angle `theta` about `axis` (normalised here):
/// `R[Θ] = [[cos Θ/2 − iΘ̂z sin Θ/2, −i sin Θ/2 (Θ̂x − iΘ̂y)], [−i sin Θ/2 (Θ̂x + iΘ̂y), cos Θ/2 + iΘ̂z sin Θ/2]]`.
pub fn su2_matrix(axis: V3, theta: f64) -> U2 {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let [x, y, z] = axis.map(|c| c / n);
    let (s, c) = (theta / 2.0).sin_cos();
    let minus_i_s = C::new(0.0, -s);
    [
        [C::new(c, -z * s), minus_i_s.mul(C::new(x, -y))],
        [minus_i_s.mul(C::new(x, y)), C::new(c, z * s)],
    ]
}

/// 2×2 complex matrix product.
pub fn u2_mul(a: &U2, b: &U2) -> U2 {
    let e = |i: usize, j: usize| a[i][0].mul(b[0][j]).add(a[i][1].mul(b[1][j]));
    [[e(0, 0), e(0, 1)], [e(1, 0), e(1, 1)]]
}

/// Largest modulus of an entry of `a − b`.
pub fn u2_dist(a: &U2, b: &U2) -> f64 {
    (0..2)
        .flat_map(|i| (0..2).map(move |j| (i, j)))
        .map(|(i, j)| a[i][j].dist(b[i][j]))
        .fold(0.0, f64::max)
}

/// The SO(3) matrix a spinor matrix represents, from the adjoint action on Pauli matrices:
/// `R_ij = ½ tr(σ_i U σ_j U†)`. Independent of any quaternion formula.
pub fn su2_to_so3(u: &U2) -> M3 {
    let sigma: [U2; 3] = [
        [
            [C::new(0.0, 0.0), C::new(1.0, 0.0)],
            [C::new(1.0, 0.0), C::new(0.0, 0.0)],
        ],
        [
            [C::new(0.0, 0.0), C::new(0.0, -1.0)],
            [C::new(0.0, 1.0), C::new(0.0, 0.0)],
        ],
        [
            [C::new(1.0, 0.0), C::new(0.0, 0.0)],
            [C::new(0.0, 0.0), C::new(-1.0, 0.0)],
        ],
    ];
    let dagger = |m: &U2| -> U2 {
        [
            [
                C::new(m[0][0].re, -m[0][0].im),
                C::new(m[1][0].re, -m[1][0].im),
            ],
            [
                C::new(m[0][1].re, -m[0][1].im),
                C::new(m[1][1].re, -m[1][1].im),
            ],
        ]
    };
    let ud = dagger(u);
    let mut r = [[0.0; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().enumerate() {
            let p = u2_mul(&u2_mul(&sigma[i], u), &u2_mul(&sigma[j], &ud));
            *e = 0.5 * (p[0][0].re + p[1][1].re);
        }
    }
    r
}
