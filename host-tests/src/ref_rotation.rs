//! Independent f64 reference for rotations: Euler matrices as products of elementary
//! rotation matrices (scipy's definition), representation maps through axis and angle
//! (Rodrigues), and an accurate geodesic distance between rotation matrices. Quaternion matrices
//! come from explicit Hamilton sandwich products ([`crate::reference::quat_matrix`]).
//!
//! Nothing here calls gyrostat. Everything goes through 3×3 matrices, so that gyrostat's
//! quaternion kernels (Bernardes–Viollet, Shepperd, exp/log series) are checked against a
//! computation that shares none of their formulas.

use crate::reference::{M3, V3, mat_mul, rodrigues, transpose};

/// The elementary active rotation about coordinate axis `axis` (0 = x, 1 = y, 2 = z) by `t`, as
/// in seed (6.6.1a): `R_z(t) = [[c, −s, 0], [s, c, 0], [0, 0, 1]]`, `R_y(t) = [[c, 0, s], [0, 1, 0],
/// [−s, 0, c]]`, `R_x(t) = [[1, 0, 0], [0, c, −s], [0, s, c]]`.
pub fn elementary(axis: usize, t: f64) -> M3 {
    let (s, c) = t.sin_cos();
    match axis {
        0 => [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]],
        1 => [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
        _ => [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
    }
}

/// Axis index of a letter of an Euler sequence.
pub fn axis_of(letter: char) -> usize {
    match letter.to_ascii_lowercase() {
        'x' => 0,
        'y' => 1,
        _ => 2,
    }
}

/// The Euler matrix in scipy's meaning: uppercase `"ABC"` (intrinsic) is `R_A(a)·R_B(b)·R_C(c)`,
/// lowercase `"abc"` (extrinsic) is `R_c(c)·R_b(b)·R_a(a)`.
pub fn euler_matrix(seq: &str, angles: [f64; 3]) -> M3 {
    let letters: Vec<char> = seq.chars().collect();
    let m: Vec<M3> = (0..3)
        .map(|i| elementary(axis_of(letters[i]), angles[i]))
        .collect();
    if letters[0].is_ascii_uppercase() {
        mat_mul(&mat_mul(&m[0], &m[1]), &m[2])
    } else {
        mat_mul(&mat_mul(&m[2], &m[1]), &m[0])
    }
}

/// The 24 convention strings: 12 intrinsic (uppercase), then the same 12 extrinsic.
pub fn all_sequences() -> Vec<String> {
    let base = [
        "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
    ];
    base.iter()
        .map(|s| s.to_string())
        .chain(base.iter().map(|s| s.to_lowercase()))
        .collect()
}

/// `true` for a proper (symmetric) sequence like `ZYZ`.
pub fn is_proper(seq: &str) -> bool {
    let b = seq.as_bytes();
    b[0].eq_ignore_ascii_case(&b[2])
}

/// The rotation matrix of a rotation vector: Rodrigues (6.6.15) of its direction and length.
pub fn rotvec_matrix(v: V3) -> M3 {
    let t = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if t == 0.0 {
        crate::reference::IDENTITY
    } else {
        rodrigues(v, t)
    }
}

/// The rotation matrix of modified Rodrigues parameters: angle `4·atan|σ|` about `σ̂`.
pub fn mrp_matrix(s: V3) -> M3 {
    let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    if n == 0.0 {
        crate::reference::IDENTITY
    } else {
        rodrigues(s, 4.0 * n.atan())
    }
}

/// The rotation matrix of a Gibbs vector: angle `2·atan|g|` about `ĝ`.
pub fn gibbs_matrix(g: V3) -> M3 {
    let n = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
    if n == 0.0 {
        crate::reference::IDENTITY
    } else {
        rodrigues(g, 2.0 * n.atan())
    }
}

/// The geodesic angle between two rotation matrices: the angle of `aᵀb`, as
/// `atan2(|vee(M − Mᵀ)|/2, (tr M − 1)/2)` — accurate for tiny angles (the sine comes from the
/// antisymmetric part directly) and near π.
pub fn rot_dist(a: &M3, b: &M3) -> f64 {
    let m = mat_mul(&transpose(a), b);
    let sx = m[2][1] - m[1][2];
    let sy = m[0][2] - m[2][0];
    let sz = m[1][0] - m[0][1];
    let s = 0.5 * (sx * sx + sy * sy + sz * sz).sqrt();
    let c = 0.5 * (m[0][0] + m[1][1] + m[2][2] - 1.0);
    s.atan2(c)
}

/// Angular velocity from a matrix-valued function of time by central differences of
/// `R(t+h)·R(t−h)ᵀ` (lab) or `R(t−h)ᵀ·R(t+h)` (body): the vee of the antisymmetric part over `2h`.
pub fn omega_from_matrices(r_minus: &M3, r_plus: &M3, h: f64, body: bool) -> V3 {
    let m = if body {
        mat_mul(&transpose(r_minus), r_plus)
    } else {
        mat_mul(r_plus, &transpose(r_minus))
    };
    let v = [
        0.5 * (m[2][1] - m[1][2]),
        0.5 * (m[0][2] - m[2][0]),
        0.5 * (m[1][0] - m[0][1]),
    ];
    v.map(|c| c / (2.0 * h))
}

/// The singular value of the middle angle nearest `b` for a sequence: `0` or `π` for proper,
/// `±π/2` for Tait–Bryan. Returns the two poles.
pub fn poles(seq: &str) -> [f64; 2] {
    if is_proper(seq) {
        [0.0, std::f64::consts::PI]
    } else {
        [-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2]
    }
}
