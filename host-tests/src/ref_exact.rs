//! Independent f64 references for the exact free rigid body and its elliptic functions.
//!
//! Written without gyrostat and by different methods than the library:
//! - elliptic integrals by adaptive Gauss–Legendre quadrature of their defining integrals (the
//!   library uses the AGM and Carlson's duplication);
//! - Jacobi functions by Newton inversion of the quadrature of `F(φ|m)` (the library uses the
//!   descending Landen transformation);
//! - the free rigid body by a tiny-step classical RK4 of Euler's equations `J̇ = J × ω`,
//!   `ω = I⁻¹J`, together with the attitude kinematics `q̇ = ½ q ⊗ (0, ω)` on plain arrays (the
//!   library uses the closed-form elliptic solution).

use std::f64::consts::{FRAC_PI_2, PI};

use crate::reference::qmul;

/// Gauss–Legendre nodes and weights on `[−1, 1]`, by Newton's method on `P_n`.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        // Tricomi's initial guess.
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            // P_n(x) = p1, P_{n-1}(x) = p0.
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// Gauss–Legendre quadrature of `f` on `[a, b]` with `panels` equal panels of 20 points.
fn gl_panels(f: &dyn Fn(f64) -> f64, a: f64, b: f64, panels: usize, gl: &[(f64, f64)]) -> f64 {
    let w = (b - a) / panels as f64;
    (0..panels)
        .map(|p| {
            let (lo, hi) = (a + w * p as f64, a + w * (p + 1) as f64);
            let (c, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            gl.iter().map(|(x, wt)| wt * f(c + h * x)).sum::<f64>() * h
        })
        .sum()
}

/// Integral of `f` over `[a, b]` (`b > a`) where `f` may have a sharp peak of width about `w` at
/// the end point `peak` (`a` or `b`): geometrically graded panels (widths w, w, 2w, 4w, …) from
/// the peak, each with 20-point Gauss–Legendre.
fn graded(
    f: &dyn Fn(f64) -> f64,
    a: f64,
    b: f64,
    peak_at_b: bool,
    w: f64,
    gl: &[(f64, f64)],
) -> f64 {
    let len = b - a;
    let mut edges = vec![0.0];
    let mut x = w.min(len);
    while x < len {
        edges.push(x);
        x = (2.0 * x).max(w);
    }
    edges.push(len);
    let mut sum = 0.0;
    for e in edges.windows(2) {
        let (lo, hi) = if peak_at_b {
            (b - e[1], b - e[0])
        } else {
            (a + e[0], a + e[1])
        };
        sum += gl_panels(f, lo, hi, 2, gl);
    }
    sum
}

/// `∫₀^φ g(θ) dθ` for an integrand with period π, even about 0 and sharply peaked (width `w`)
/// at the odd multiples of π/2: split at multiples of π/2, graded meshes toward the peaks.
fn periodic_peaked(g: &dyn Fn(f64) -> f64, phi: f64, w: f64) -> f64 {
    if phi < 0.0 {
        return -periodic_peaked(g, -phi, w);
    }
    let gl = gauss_legendre(20);
    let mut sum = 0.0;
    let mut lo = 0.0;
    let mut k = 0usize;
    while lo < phi {
        let hi = ((k + 1) as f64 * FRAC_PI_2).min(phi);
        // Segment k spans [kπ/2, (k+1)π/2]; the peak is at its odd-multiple end.
        let peak_at_b = k.is_multiple_of(2);
        sum += graded(g, lo, hi, peak_at_b, w, &gl);
        lo = hi;
        k += 1;
    }
    sum
}

/// `F(φ|m) = ∫₀^φ dθ/√(1 − m sin²θ)` by Gauss–Legendre quadrature: reduced to
/// `|φ| ≤ π/2` by `F(φ + kπ) = F(φ) + 2kK`; on `[0, min(φ, 1)]` directly, and on `[1, φ]` in the
/// variable `c = cos θ`, `∫_{cos φ}^{cos 1} dc / (√(1 − c²) √((1 − m) + m c²))`, with a mesh graded
/// towards the peak at `c = 0` (width `√(1 − m)`). Using `cos φ` from libm keeps the reference
/// accurate relative to the exact input `φ` near `π/2`.
pub fn ell_f(phi: f64, m: f64) -> f64 {
    let k = (phi / PI).round();
    let pr = phi - k * PI;
    let f = if k != 0.0 {
        2.0 * k * ell_f_reduced(FRAC_PI_2, m)
    } else {
        0.0
    };
    f + pr.signum() * ell_f_reduced(pr.abs(), m)
}

fn ell_f_reduced(phi: f64, m: f64) -> f64 {
    let gl = gauss_legendre(20);
    let m1 = 1.0 - m;
    let a_end = phi.min(1.0);
    let part_a = gl_panels(
        &|t: f64| 1.0 / (m1 + m * t.cos().powi(2)).sqrt(),
        0.0,
        a_end,
        4,
        &gl,
    );
    if phi <= 1.0 {
        return part_a;
    }
    let (c_lo, c_hi) = (phi.cos().max(0.0), 1.0f64.cos());
    let w = (m1.sqrt() / 8.0).clamp(1e-12, 0.05);
    let g = |c: f64| 1.0 / (((1.0 - c) * (1.0 + c)).sqrt() * (m1 + m * c * c).sqrt());
    part_a + graded(&g, c_lo, c_hi, false, w, &gl)
}

/// `K(m)` by quadrature.
pub fn ell_k(m: f64) -> f64 {
    ell_f(FRAC_PI_2, m)
}

/// `Π(n; φ|m) = ∫₀^φ dθ/((1 − n sin²θ)√(1 − m sin²θ))` by graded quadrature.
pub fn ell_pi(n: f64, phi: f64, m: f64) -> f64 {
    let w = ((1.0 - m).sqrt().min((1.0 - n).abs().sqrt()) / 8.0).clamp(1e-12, 0.2);
    periodic_peaked(
        &|t: f64| {
            let (s, c) = t.sin_cos();
            1.0 / ((1.0 - n * s * s) * ((1.0 - m) + m * c * c).sqrt())
        },
        phi,
        w,
    )
}

/// Jacobi `(sn, cn, dn)` by inverting `F(φ|m) = u` with a safeguarded Newton iteration.
pub fn sn_cn_dn(u: f64, m: f64) -> (f64, f64, f64) {
    // Reduce with the quasi-period: am(u + 2K) = am(u) + π.
    let k = ell_k(m);
    let n = (u / (2.0 * k)).round();
    let ur = u - 2.0 * k * n;
    // dF/dφ ∈ [1, 1/√(1−m)] brackets φ between ur·√(1−m) and ur.
    let (mut lo, mut hi) = if ur >= 0.0 {
        (ur * (1.0 - m).sqrt(), ur)
    } else {
        (ur, ur * (1.0 - m).sqrt())
    };
    // Bisection to the resolution of f64, then two Newton polishing steps.
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if ell_f(mid, m) > ur {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let mut phi = 0.5 * (lo + hi);
    for _ in 0..2 {
        phi -= (ell_f(phi, m) - ur) * (1.0 - m * phi.sin().powi(2)).sqrt();
    }
    let phi = phi + n * PI;
    let (s, c) = phi.sin_cos();
    // dn² = 1 − m s² = c² + (1 − m) s², written without cancellation.
    (s, c, (c * c + (1.0 - m) * s * s).sqrt())
}

/// State of the reference rigid body: body momentum `j` and attitude `q = (w, x, y, z)`
/// (body → lab, Hamilton).
#[derive(Clone, Copy, Debug)]
pub struct RigidState {
    /// Body-frame angular momentum.
    pub j: [f64; 3],
    /// Attitude quaternion, scalar first.
    pub q: [f64; 4],
}

fn deriv(inertia: [f64; 3], s: &RigidState) -> RigidState {
    let w = [
        s.j[0] / inertia[0],
        s.j[1] / inertia[1],
        s.j[2] / inertia[2],
    ];
    let j = s.j;
    // J̇ = J × ω
    let dj = [
        j[1] * w[2] - j[2] * w[1],
        j[2] * w[0] - j[0] * w[2],
        j[0] * w[1] - j[1] * w[0],
    ];
    let dq = qmul(s.q, [0.0, w[0], w[1], w[2]]);
    RigidState {
        j: dj,
        q: [0.5 * dq[0], 0.5 * dq[1], 0.5 * dq[2], 0.5 * dq[3]],
    }
}

fn axpy(s: &RigidState, h: f64, d: &RigidState) -> RigidState {
    let mut o = *s;
    for i in 0..3 {
        o.j[i] += h * d.j[i];
    }
    for i in 0..4 {
        o.q[i] += h * d.q[i];
    }
    o
}

/// One classical RK4 step of the torque-free rigid body with principal moments `inertia`.
pub fn rk4_step(inertia: [f64; 3], s: &RigidState, h: f64) -> RigidState {
    let k1 = deriv(inertia, s);
    let k2 = deriv(inertia, &axpy(s, 0.5 * h, &k1));
    let k3 = deriv(inertia, &axpy(s, 0.5 * h, &k2));
    let k4 = deriv(inertia, &axpy(s, h, &k3));
    let mut o = *s;
    for i in 0..3 {
        o.j[i] += h / 6.0 * (k1.j[i] + 2.0 * k2.j[i] + 2.0 * k3.j[i] + k4.j[i]);
    }
    for i in 0..4 {
        o.q[i] += h / 6.0 * (k1.q[i] + 2.0 * k2.q[i] + 2.0 * k3.q[i] + k4.q[i]);
    }
    let n = o.q.iter().map(|x| x * x).sum::<f64>().sqrt();
    for x in o.q.iter_mut() {
        *x /= n;
    }
    o
}

/// Integrates from `s0` to each time in `times` (ascending, ≥ 0) with steps of at most `h`;
/// returns the states at those times.
pub fn integrate_rigid(
    inertia: [f64; 3],
    s0: RigidState,
    times: &[f64],
    h: f64,
) -> Vec<RigidState> {
    let mut out = Vec::with_capacity(times.len());
    let mut s = s0;
    let mut t = 0.0;
    for &target in times {
        let span = target - t;
        let n = (span / h).ceil().max(0.0) as usize;
        if n > 0 {
            let step = span / n as f64;
            for _ in 0..n {
                s = rk4_step(inertia, &s, step);
            }
        }
        t = target;
        out.push(s);
    }
    out
}

/// Measures the mean time between successive sign changes of body-momentum component `axis`
/// over `[0, t_end]`, with crossing times located by linear interpolation between RK4 steps of
/// size `h`. Returns `(mean interval, number of intervals)`.
pub fn measured_sign_change_interval(
    inertia: [f64; 3],
    s0: RigidState,
    axis: usize,
    t_end: f64,
    h: f64,
) -> (f64, usize) {
    let mut s = s0;
    let mut t = 0.0;
    let mut crossings = Vec::new();
    while t < t_end {
        let next = rk4_step(inertia, &s, h);
        let (a, b) = (s.j[axis], next.j[axis]);
        if a != 0.0 && (a < 0.0) != (b < 0.0) {
            crossings.push(t + h * a / (a - b));
        }
        s = next;
        t += h;
    }
    if crossings.len() < 2 {
        return (f64::NAN, 0);
    }
    let n = crossings.len() - 1;
    ((crossings[n] - crossings[0]) / n as f64, n)
}
