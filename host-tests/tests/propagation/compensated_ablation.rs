//! Why the compensated f32 attitude drifted under coning, and what removed it (issue 18): a
//! replica of the compensated increment update (`CompensatedAttitude` driven by
//! `IncrementIntegrator`, exact renormalisation), bit for bit the library's in its `Library`
//! setting, with one part at a time changed.
//!
//! The motion is the classical coning of `host_tests::ref_propagation::Coning`, 1° half-angle at
//! 10 Hz, 1 kHz, 60 s: the input repeats every 100 increments, so an error that is a function of
//! the attitude and the increment repeats too and piles up. Every run is fed the same
//! f32-rounded increments and the same f32-rounded start; the measure is the distance to the
//! same rule run in f64 (`IncrementIntegrator<f64>`), the share of the f32 arithmetic.
//!
//! The settings (each "exact" part computed in f64 from the f32 operands and split back into an
//! f32 pair):
//! - `RoundedProduct`: the update before the fix, the increment's large part
//!   `q ⊗ (cos(θ/2) − 1, φ/2)` rounded to f32;
//! - `RoundedProduct` with the rule's rotation vector exact, or with the renormalisation exact;
//! - `RoundedProduct` with the large part exact;
//! - `Library`: the large part added through Veltkamp halves and TwoSum (the library's
//!   `add_product_compensated`);
//! - `ExactUpdate`: the whole update `(q + q_lo) ⊗ exp(φ)` and its renormalisation in f64.
//!
//! Measured (4-sample rule, the carried pair `q + q_lo` against f64; `cargo test --release -p
//! host-tests --test propagation ablation -- --nocapture`): `RoundedProduct` 5.6e-7 rad, with
//! the rule vector exact 5.6e-7, with the renormalisation exact 5.9e-7, with the large part exact
//! 1.1e-9, `Library` 1.1e-10, `ExactUpdate` 4e-15.

use gyrostat::propagation::{CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization};
use gyrostat::{Quat, UnitQuat, Vec3};
use host_tests::ref_propagation::Coning;
use host_tests::reference::{Q, qmul, quat_angle, quat_exp};

/// The setting of [`Replica::update`].
#[derive(Clone, Copy, Debug, PartialEq)]
enum Setting {
    Library,
    RoundedProduct,
    RoundedProductExactRule,
    RoundedProductExactRenormalisation,
    RoundedProductExactLargePart,
    ExactUpdate,
}

type Q32 = [f32; 4];
type V32 = [f32; 3];

fn two_sum(a: f32, b: f32) -> (f32, f32) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn fast_two_sum(a: f32, b: f32) -> (f32, f32) {
    let s = a + b;
    (s, b - (s - a))
}

fn veltkamp(a: f32) -> (f32, f32) {
    let c = 4097.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// The Hamilton product in f32, each component `a₀b₀ + a₁b₁ + a₂b₂ + a₃b₃` left to right (as
/// `Quat::mul`).
fn qmul32(a: Q32, o: Q32) -> Q32 {
    let d = |b: Q32| a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    [
        d([o[0], -o[1], -o[2], -o[3]]),
        d([o[1], o[0], o[3], -o[2]]),
        d([o[2], -o[3], o[0], o[1]]),
        d([o[3], o[2], -o[1], o[0]]),
    ]
}

fn wide3(v: V32) -> [f64; 3] {
    v.map(f64::from)
}

/// `(hi, lo)` with `hi = fl32(v)`, `lo = fl32(v − hi)`.
fn split3(v: [f64; 3]) -> (V32, V32) {
    let h = v.map(|c| c as f32);
    (h, [0, 1, 2].map(|i| (v[i] - f64::from(h[i])) as f32))
}

fn split4(v: Q) -> (Q32, Q32) {
    let h = v.map(|c| c as f32);
    (h, [0, 1, 2, 3].map(|i| (v[i] - f64::from(h[i])) as f32))
}

fn pair64(q: Q32, lo: Q32) -> Q {
    [0, 1, 2, 3].map(|i| f64::from(q[i]) + f64::from(lo[i]))
}
/// The 4-sample rule's lever `2·(27 t₁ + 46 t₂ + 107 t₃)/105` in f32, as `four_sample_terms`.
fn lever4(s: &[V32]) -> V32 {
    let r = |n: f64| (n / 105.0) as f32;
    let h = [0, 1, 2].map(|i| s[0][i] * r(27.0) + s[1][i] * r(46.0) + s[2][i] * r(107.0));
    h.map(|c| c + c)
}

/// The 4-sample lever in f64 (exact but for the final roundings of f64).
fn exact_lever(s: &[V32]) -> [f64; 3] {
    [0, 1, 2].map(|i| {
        2.0 * (f64::from(s[0][i]) * 27.0 + f64::from(s[1][i]) * 46.0 + f64::from(s[2][i]) * 107.0)
            / 105.0
    })
}

/// `(cos(θ/2) − 1, sin(θ/2)/θ − ½)` from `θ²`, the library's f32 series (`exp_terms`).
fn exp_terms(theta_sq: f32) -> (f32, f32) {
    let c = |v: f64| v as f32;
    let x2 = theta_sq * 0.25;
    assert!(x2 <= 0.25, "series range");
    let sin_tail =
        c(-1.0 / 6.0) + x2 * (c(1.0 / 120.0) + x2 * (c(-1.0 / 5040.0) + x2 * c(1.0 / 362_880.0)));
    let cos_tail = c(-0.5) + x2 * (c(1.0 / 24.0) + x2 * (c(-1.0 / 720.0) + x2 * c(1.0 / 40_320.0)));
    (x2 * cos_tail, 0.5 * x2 * sin_tail)
}

struct Replica {
    q: Q32,
    lo: Q32,
    setting: Setting,
}

impl Replica {
    /// One 4-sample update from the samples `s`.
    fn update(&mut self, s: &[V32]) {
        use Setting::*;
        if self.setting == ExactUpdate {
            let mut sum = [0.0; 3];
            for t in s {
                for i in 0..3 {
                    sum[i] += f64::from(t[i]);
                }
            }
            let l = exact_lever(s);
            let last = wide3(s[3]);
            let phi = [
                sum[0] + (l[1] * last[2] - l[2] * last[1]),
                sum[1] + (l[2] * last[0] - l[0] * last[2]),
                sum[2] + (l[0] * last[1] - l[1] * last[0]),
            ];
            let q = qmul(pair64(self.q, self.lo), quat_exp(phi));
            let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
            (self.q, self.lo) = split4(q.map(|c| c / n));
            return;
        }
        // The rule's rotation vector as a pair: the sum by TwoSum, the coning term into the low
        // part (`rule_vector`), or exact.
        let (phi, phi_lo) = if self.setting == RoundedProductExactRule {
            let mut sum = [0.0; 3];
            for t in s {
                for i in 0..3 {
                    sum[i] += f64::from(t[i]);
                }
            }
            let (l, t) = (exact_lever(s), wide3(s[3]));
            split3([
                sum[0] + (l[1] * t[2] - l[2] * t[1]),
                sum[1] + (l[2] * t[0] - l[0] * t[2]),
                sum[2] + (l[0] * t[1] - l[1] * t[0]),
            ])
        } else {
            let (mut sum, mut lo) = ([0f32; 3], [0f32; 3]);
            for t in s {
                for i in 0..3 {
                    let (a, e) = two_sum(sum[i], t[i]);
                    sum[i] = a;
                    lo[i] += e;
                }
            }
            let (l, t) = (lever4(s), s[3]);
            let cross = [
                l[1] * t[2] + (-l[2]) * t[1],
                l[2] * t[0] + (-l[0]) * t[2],
                l[0] * t[1] + (-l[1]) * t[0],
            ];
            (sum, [0, 1, 2].map(|i| lo[i] + cross[i]))
        };
        // `rotate_compensated`.
        let mut p = [0f32; 3];
        let mut pl = [0f32; 3];
        for i in 0..3 {
            (p[i], pl[i]) = two_sum(phi[i], phi_lo[i]);
        }
        let (m, sh) = exp_terms(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        let v = p.map(|c| c * 0.5);
        let v_lo = [0, 1, 2].map(|i| pl[i] * 0.5 + p[i] * sh);
        let a = qmul32(self.q, [0.0, v_lo[0], v_lo[1], v_lo[2]]);
        let b = qmul32(self.lo, [0.0, v[0], v[1], v[2]]);
        let small = [0, 1, 2, 3].map(|i| a[i] + b[i]);
        let w = [m, v[0], v[1], v[2]];
        match self.setting {
            Library => {
                let (qh, ql) = (self.q.map(|c| veltkamp(c).0), self.q.map(|c| veltkamp(c).1));
                let (wh, wl) = (w.map(|c| veltkamp(c).0), w.map(|c| veltkamp(c).1));
                let (c, d) = (qmul32(self.q, wl), qmul32(ql, wh));
                let rows = [
                    [wh[0], -wh[1], -wh[2], -wh[3]],
                    [wh[1], wh[0], wh[3], -wh[2]],
                    [wh[2], -wh[3], wh[0], wh[1]],
                    [wh[3], wh[2], -wh[1], wh[0]],
                ];
                for i in 0..4 {
                    let (mut acc, mut e) = (self.q[i], 0.0f32);
                    for k in 0..4 {
                        let (t, r) = two_sum(acc, qh[k] * rows[i][k]);
                        acc = t;
                        e += r;
                    }
                    let rest = (small[i] + c[i]) + d[i];
                    (self.q[i], self.lo[i]) = fast_two_sum(acc, e + (rest + self.lo[i]));
                }
            }
            _ => {
                let (large, small) = if self.setting == RoundedProductExactLargePart {
                    let (h, l) = split4(qmul(self.q.map(f64::from), w.map(f64::from)));
                    (h, [0, 1, 2, 3].map(|i| small[i] + l[i]))
                } else {
                    (qmul32(self.q, w), small)
                };
                for i in 0..4 {
                    // `add_pair`.
                    let (s, e) = fast_two_sum(self.q[i], large[i]);
                    (self.q[i], self.lo[i]) = fast_two_sum(s, e + (small[i] + self.lo[i]));
                }
            }
        }
        // The exact renormalisation (`CompensatedAttitude::normalized`), or exact in f64.
        if self.setting == RoundedProductExactRenormalisation {
            let p = pair64(self.q, self.lo);
            let n = p.iter().map(|c| c * c).sum::<f64>().sqrt();
            (self.q, self.lo) = split4(p.map(|c| c / n));
        } else {
            let q = self.q;
            let n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
            let n = n2.sqrt();
            let f = (1.0 - n2) / (n * (1.0 + n));
            for (i, qi) in q.iter().enumerate() {
                let (s, e) = fast_two_sum(self.q[i], qi * f);
                (self.q[i], self.lo[i]) = fast_two_sum(s, e + (0.0 + self.lo[i]));
            }
        }
    }
}

const CONE: Coning = Coning {
    alpha: 1.0 * core::f64::consts::PI / 180.0,
    omega_c: 2.0 * core::f64::consts::PI * 10.0,
};

/// The f32 increments and the f32 start.
fn inputs(n: usize) -> (Vec<V32>, Q32) {
    let h = 1e-3;
    let inc = (0..n)
        .map(|k| {
            CONE.increment(k as f64 * h, (k + 1) as f64 * h)
                .map(|c| c as f32)
        })
        .collect();
    (inc, CONE.attitude(0.0).map(|c| c as f32))
}

fn replica(setting: Setting, inc: &[V32], q0: Q32) -> (Q32, Q32) {
    let mut r = Replica {
        q: q0,
        lo: [0.0; 4],
        setting,
    };
    for g in inc.chunks_exact(4) {
        r.update(g);
    }
    (r.q, r.lo)
}

fn library(inc: &[V32], q0: Q32) -> (Q32, Q32) {
    let q0 = CompensatedAttitude::new(UnitQuat::new_unchecked(Quat::from_array(q0)));
    let mut integ = IncrementIntegrator::new(q0, ConingRule::FourSample, Normalization::Exact);
    for t in inc {
        integ.push(Vec3::from_array(*t)).unwrap();
    }
    let a = integ.carried_attitude();
    (a.attitude().to_array(), a.low().to_array())
}

fn f64_run(inc: &[V32], q0: Q32) -> Q {
    let q0 = UnitQuat::new_unchecked(Quat::from_array(q0.map(f64::from)));
    let mut integ = IncrementIntegrator::new(q0, ConingRule::FourSample, Normalization::Exact);
    for t in inc {
        integ.push(Vec3::from_array(wide3(*t))).unwrap();
    }
    integ.attitude().to_array()
}

/// The replica's `Library` setting is the library, bit for bit, attitude and low part (10 s).
#[test]
fn replica_reproduces_the_library() {
    let (inc, q0) = inputs(10_000);
    assert_eq!(replica(Setting::Library, &inc, q0), library(&inc, q0));
}

/// The rounded increment product is the whole of the drift: made exact alone it goes, while the
/// rule's rotation vector or the renormalisation made exact change nothing (numbers in the
/// module docs).
#[test]
fn ablation_rounded_increment_product_is_the_cause() {
    use Setting::*;
    let (inc, q0) = inputs(60_000);
    let reference = f64_run(&inc, q0);
    let distance = |s: Setting| {
        let (q, lo) = replica(s, &inc, q0);
        quat_angle(reference, pair64(q, lo))
    };
    let d: Vec<(Setting, f64)> = [
        RoundedProduct,
        RoundedProductExactRule,
        RoundedProductExactRenormalisation,
        RoundedProductExactLargePart,
        Library,
        ExactUpdate,
    ]
    .into_iter()
    .map(|s| (s, distance(s)))
    .collect();
    for (s, e) in &d {
        println!("{s:?}: {e:.2e} rad from f64");
    }
    let of = |s: Setting| d.iter().find(|(t, _)| *t == s).map(|(_, e)| *e).unwrap();
    for s in [
        RoundedProduct,
        RoundedProductExactRule,
        RoundedProductExactRenormalisation,
    ] {
        assert!(of(s) > 1e-7, "{s:?}: {:.2e}", of(s));
    }
    for s in [RoundedProductExactLargePart, Library, ExactUpdate] {
        assert!(of(s) < 5e-9, "{s:?}: {:.2e}", of(s));
    }
}
