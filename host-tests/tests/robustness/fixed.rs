//! The adversarial campaign over the fixed-point API (`gyrostat::fixed`, see
//! `host_tests::campaign` and `ROBUSTNESS.md`): conversions from f32 and f64 (NaN, ±∞,
//! subnormals, values at and beyond the range), increment scales and rate × step increments,
//! the coning updates on `UnitQuat<Q30>` with raw increments anywhere in Q1.30 (saturated sums
//! included), the checked integrators and the two-speed accumulator, and renormalisation health.
//!
//! The type column is the float type the inputs are drawn in and converted from (f32 data and
//! f64 data take different conversion paths). Every check is against an f64 computation written
//! here from the formulas (exact products of the Q1.30 values, the rule coefficients, the
//! exponential by `sin`/`cos`), not against gyrostat's own float path.
//!
//! Integer overflow: the fixed-point code saturates or works in 64 bits by design; the library is
//! built with overflow checks in the host test profiles (release: `Cargo.toml`; debug: always),
//! so an overflowing `i32`/`i64` operation would panic and be reported as a panic.

use gyrostat::fixed::increment_from_rate;
use gyrostat::propagation::coning::{four_sample, one_plus_previous, three_sample, two_sample};
use gyrostat::propagation::kernels::coning2_update;
use gyrostat::propagation::normalization::norm_squared_deviation;
use gyrostat::propagation::{ConingAccumulator, ConingRule, IncrementIntegrator, Normalization};
use gyrostat::real::{Fixed, Q24, Q30};
use gyrostat::sensor::RawScale;
use gyrostat::{Error, Quat, Ring, UnitQuat, Vec3};
use host_tests::campaign::*;
use host_tests::family;
use host_tests::reference::{Q, V3, add, cross, qmul, quat_angle, quat_exp, scale};
use host_tests::tolerance::Tolerance;

/// The resolution of Q1.30, 2⁻³⁰.
const U: f64 = 1.0 / (1u64 << 30) as f64;

const NORMS: [Normalization; 3] = [
    Normalization::Exact,
    Normalization::Fast,
    Normalization::None,
];

/// A raw Q1.30 value anywhere in the range: the extremes, zero, small, or uniform bits.
fn raw_q30<T: Tolerance>(g: &mut Gen<T>) -> Q30 {
    let r = match g.rng.below(8) {
        0 => *g
            .rng
            .pick(&[i32::MAX, -i32::MAX, i32::MIN, 0, 1, -1, 1 << 30, -(1 << 30)]),
        1..=2 => (g.rng.next_u64() as i32) >> g.rng.below(31),
        _ => g.rng.next_u64() as i32,
    };
    Q30::from_bits(r)
}

/// An increment vector: raw anywhere in Q1.30 (sums of such saturate), or converted from an
/// ordinary or small float increment of type `T`.
fn increment<T: Tolerance>(g: &mut Gen<T>) -> Vec3<Q30> {
    match g.rng.below(4) {
        0 => Vec3::new(raw_q30(g), raw_q30(g), raw_q30(g)),
        _ => {
            let m = *g.rng.pick(&[1e-6, 1e-3, 0.05, 0.24, 0.3, 1.0]);
            let v = [0; 3].map(|_| T::from_f64(g.rng.range(-m, m)));
            Vec3::new(
                Q30::try_from_f64(v[0].to_f64()).unwrap_or(Q30::ZERO),
                Q30::try_from_f64(v[1].to_f64()).unwrap_or(Q30::ZERO),
                Q30::try_from_f64(v[2].to_f64()).unwrap_or(Q30::ZERO),
            )
        }
    }
}

/// A unit attitude converted from a float unit quaternion of type `T`.
fn attitude<T: Tolerance>(g: &mut Gen<T>) -> UnitQuat<Q30> {
    let q = g.unit_quat_f64().map(|c| T::from_f64(c).to_f64());
    let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let q = UnitQuat::try_new(Quat::from_array(q.map(|c| c / n))).unwrap();
    UnitQuat::<Q30>::try_from_f64(q).expect("a unit quaternion converts")
}

fn v64(v: Vec3<Q30>) -> V3 {
    v.to_f64().to_array()
}

fn q64(q: UnitQuat<Q30>) -> Q {
    q.to_f64().to_array()
}

/// `|q|² − 1` in f64 (exact for Q1.30 components).
fn health(q: UnitQuat<Q30>) -> f64 {
    q64(q).iter().map(|c| c * c).sum::<f64>() - 1.0
}
/// The rule's rotation vector in f64 from its written coefficients.
fn rule64(rule: ConingRule, previous: V3, g: &[V3]) -> V3 {
    match rule {
        ConingRule::Exp => g[0],
        ConingRule::OnePlusPrevious => add(g[0], scale(cross(previous, g[0]), 1.0 / 12.0)),
        ConingRule::TwoSample => add(add(g[0], g[1]), scale(cross(g[0], g[1]), 2.0 / 3.0)),
        ConingRule::ThreeSample => {
            let lever = add(scale(g[0], 9.0 / 20.0), scale(g[1], 27.0 / 20.0));
            add(add(add(g[0], g[1]), g[2]), cross(lever, g[2]))
        }
        ConingRule::FourSample => {
            let lever = add(
                add(scale(g[0], 54.0 / 105.0), scale(g[1], 92.0 / 105.0)),
                scale(g[2], 214.0 / 105.0),
            );
            add(add(add(add(g[0], g[1]), g[2]), g[3]), cross(lever, g[3]))
        }
    }
}

/// The unit-norm health a checked or in-domain update keeps: `||q|² − 1| ≤ 16u` after an exact
/// or fast renormalisation (a few roundings of the product and of the renormalisation, each at
/// most u/2 per component), `≤ 128u` without one (the exponential is accurate to 29u up to
/// 3.4 rad per the fixed-point docs, twice that on `|q|²`, plus the product's roundings).
fn health_bound(norm: Normalization) -> f64 {
    match norm {
        Normalization::None => 128.0 * U,
        _ => 16.0 * U,
    }
}

fn healthy(q: UnitQuat<Q30>, norm: Normalization, what: &str) -> Check {
    healthy_after(q, norm, 1, what)
}

/// As [`healthy`] after `updates` updates: without renormalisation the norm errors of the
/// updates add up (the bound is per update).
fn healthy_after(q: UnitQuat<Q30>, norm: Normalization, updates: u32, what: &str) -> Check {
    let h = health(q);
    let bound = match norm {
        Normalization::None => health_bound(norm) * f64::from(updates.max(1)),
        _ => health_bound(norm),
    };
    ensure(h.abs() <= bound, || {
        format!("{what}: |q|² − 1 = {h:e} ({:.1} u) for {norm:?}", h / U)
    })
}

fn families<T: Tolerance>() -> Vec<Family<T>> {
    vec![
        family!(
            "Fixed::try_from_f32/f64 (Q1.30, Q7.24), to_f64, Vec3 and UnitQuat conversions",
            |g| {
                let x = g.scalar();
                probe(&x, || {
                    let xf = x.to_f64();
                    // Q1.30 and Q7.24 of a scalar of type T: f32 data through try_from_f32.
                    let conv30 = |x: T| {
                        if T::INDEX == 0 {
                            Q30::try_from_f32(x.to_f64() as f32)
                        } else {
                            Q30::try_from_f64(x.to_f64())
                        }
                    };
                    for (r, max, d) in [
                        (conv30(x).map(Fixed::to_f64), Q30::MAX.to_f64(), U),
                        (
                            Q24::try_from_f64(xf).map(Fixed::to_f64),
                            Q24::MAX.to_f64(),
                            Q24::DELTA.to_f64(),
                        ),
                    ] {
                        match r {
                            Ok(v) => ensure((v - xf).abs() <= d / 2.0 && v.abs() <= max, || {
                                format!("{xf:e} converted to {v:e}")
                            })?,
                            Err(Error::NonFinite) => {
                                ensure(!xf.is_finite(), || format!("{xf:e}: NonFinite"))?
                            }
                            Err(Error::OutOfRange) => {
                                ensure(xf.abs() > max, || format!("{xf:e}: OutOfRange"))?
                            }
                            Err(e) => return Err(e.into()),
                        }
                    }
                    // A vector converts component by component.
                    if let Ok(v) = Vec3::<Q30>::try_from_f64(Vec3::new(xf, xf / 2.0, 0.0)) {
                        let v = v64(v);
                        ensure(
                            (v[0] - xf).abs() <= U / 2.0 && (v[1] - xf / 2.0).abs() <= U / 2.0,
                            || format!("vector ({xf:e}, {:e}, 0) converted to {v:?}", xf / 2.0),
                        )?;
                    }
                    Ok(())
                })
            }
        ),
        family!("UnitQuat<Q30>::try_from_f32/f64, to_f64, to_f32", |g| {
            let q = g.unit_quat();
            probe(&q, || {
                let r = if T::INDEX == 0 {
                    let q32 = UnitQuat::try_new(Quat::from_array(
                        q.to_array().map(|c| c.to_f64() as f32),
                    ))?;
                    UnitQuat::<Q30>::try_from_f32(q32)?
                } else {
                    let q64 =
                        UnitQuat::try_new(Quat::from_array(q.to_array().map(|c| c.to_f64())))?;
                    UnitQuat::<Q30>::try_from_f64(q64)?
                };
                // Four roundings of at most u/2 on components ≤ 1, the input a few ε off unit.
                let h = health(r);
                let bound = 4.0 * U + 8.0 * T::EPSILON.to_f64();
                ensure(h.abs() <= bound, || format!("|q|² − 1 = {h:e}"))?;
                let back = r.to_f32().to_array();
                finite_all(&back)
            })
        }),
        family!("RawScale<Q30>::try_new, try_from_rate, increment", |g| {
            let s = match g.rng.below(3) {
                0 => g.scalar().to_f64(),
                _ => g.magnitude_in(U / 4.0, 1e-3),
            };
            let dt = g.scalar().to_f64();
            let raw = [0; 3].map(|_| match g.rng.below(3) {
                0 => *g.rng.pick(&[i16::MIN, i16::MAX, 0, -1, 1]),
                _ => g.rng.next_u64() as i16,
            });
            probe(&(s, dt, raw), || {
                let _ = RawScale::<Q30>::try_from_rate(s, dt);
                let sc = match RawScale::<Q30>::try_new(s) {
                    Err(Error::NonFinite) => return ensure(!s.is_finite(), || "NonFinite".into()),
                    Err(Error::InvalidArgument) => return ensure(s <= 0.0, || "InvalidArg".into()),
                    Err(Error::OutOfRange) => {
                        // Documented: s ≥ 2⁻¹⁴ or below 2⁻³⁰ (to the scale's own rounding).
                        let r = 2f64.powi(-14);
                        return ensure(s >= r * (1.0 - 1e-9) || s < U * (1.0 + 1e-9), || {
                            format!("scale {s:e}: OutOfRange")
                        });
                    }
                    Err(e) => return Err(e.into()),
                    Ok(sc) => sc,
                };
                let r = sc.lsb();
                ensure((r - s).abs() <= s * 2f64.powi(-30), || {
                    format!("scale {s:e} stored as {r:e}")
                })?;
                let inc = v64(sc.apply(raw));
                for (c, &n) in inc.iter().zip(&raw) {
                    let exact = f64::from(n) * r;
                    ensure((c - exact).abs() <= U / 2.0 && c.abs() < 2.0, || {
                        format!("raw {n} × {r:e} gave {c:e}")
                    })?;
                }
                Ok(())
            })
        }),
        family!("increment_from_rate (Q7.24 × Q1.30, saturating)", |g| {
            let w = Vec3::new(
                Q24::from_bits(g.rng.next_u64() as i32 >> g.rng.below(31)),
                Q24::from_bits(g.rng.next_u64() as i32),
                Q24::from_bits(*g.rng.pick(&[i32::MAX, i32::MIN, 0, 1])),
            );
            let dt = raw_q30(g);
            probe(&(w, dt), || {
                let inc = v64(increment_from_rate(w, dt));
                let max = Q30::MAX.to_f64();
                for (c, wi) in inc.iter().zip(w.to_array()) {
                    let exact = (wi.to_f64() * dt.to_f64()).clamp(-max, max);
                    ensure((c - exact).abs() <= U / 2.0, || {
                        format!("{wi:?} × {dt:?} gave {c:e}, exact {exact:e}")
                    })?;
                }
                Ok(())
            })
        }),
        family!(
            "coning updates on UnitQuat<Q30> (coning2_update, 4 rules × 3 normalisations, mul_exp_unchecked, exp_unchecked), raw increments",
            |g| {
                let q = attitude(g);
                let t = [0; 4].map(|_| increment(g));
                let norm = *g.rng.pick(&NORMS);
                probe(&(q, t, norm), || {
                    // The hot path: any raw increments (saturated sums included) keep the
                    // attitude unit; the result is a rotation, not necessarily the exact one.
                    healthy(
                        coning2_update(q, t[0], t[1]),
                        Normalization::Fast,
                        "coning2",
                    )?;
                    let phis = [
                        one_plus_previous(t[0], t[1]),
                        two_sample(t[0], t[1]),
                        three_sample(t[0], t[1], t[2]),
                        four_sample(t[0], t[1], t[2], t[3]),
                        t[0],
                    ];
                    for phi in phis {
                        healthy(q.mul_exp_unchecked(phi, norm), norm, "rule")?;
                    }
                    healthy(
                        q.mul_exp_unchecked(t[0], Normalization::None),
                        Normalization::None,
                        "mul_exp_unchecked",
                    )?;
                    healthy(
                        UnitQuat::exp_unchecked(t[0]),
                        Normalization::None,
                        "exp_unchecked",
                    )?;
                    // Where no sum saturates (increments below 0.25 rad per component), the
                    // 2-sample update is the exact one to a few u.
                    let small = t[..2]
                        .iter()
                        .all(|v| v.to_f64().to_array().iter().all(|c| c.abs() < 0.25));
                    if small {
                        let (a, b) = (v64(t[0]), v64(t[1]));
                        let phi = rule64(ConingRule::TwoSample, [0.0; 3], &[a, b]);
                        let want = qmul(q64(q), quat_exp(phi));
                        let got = q64(coning2_update(q, t[0], t[1]));
                        let err = quat_angle(want, got);
                        ensure(err <= 64.0 * U, || format!("coning2 {err:e} rad off"))?;
                    }
                    Ok(())
                })
            }
        ),
        family!(
            "IncrementIntegrator<Q30> (5 rules × 3 normalisations): push, provisional_attitude, flush",
            |g| {
                let q0 = attitude(g);
                let rule = *g.rng.pick(&ConingRule::ALL);
                let norm = *g.rng.pick(&NORMS);
                let k = 1 + g.rng.below(8);
                let incs: Vec<Vec3<Q30>> = (0..k).map(|_| increment(g)).collect();
                probe(&(q0, rule, norm, &incs), || {
                    let mut it = IncrementIntegrator::new(q0, rule, norm);
                    let mut q = q64(q0);
                    let mut previous = [0.0; 3];
                    let mut group: Vec<V3> = Vec::new();
                    let mut outcome: Result<(), Error> = Ok(());
                    let mut updates = 0u32;
                    for &d in &incs {
                        match it.push(d) {
                            Ok(done) => {
                                let d64 = v64(d);
                                group.push(d64);
                                if let Some(att) = done {
                                    q = qmul(q, quat_exp(rule64(rule, previous, &group)));
                                    previous = d64;
                                    group.clear();
                                    updates += 1;
                                    healthy_after(att, norm, updates, "push")?;
                                    // Per update ≤ 29u (exponential) plus a few roundings;
                                    // eight updates at most: 1e-6 rad is ~1000u, with margin.
                                    let err = quat_angle(q, q64(att));
                                    ensure(err <= 1e-6, || {
                                        format!("attitude {err:e} rad from the reference")
                                    })?;
                                }
                            }
                            Err(e @ (Error::StepTooLong | Error::OutOfRange)) => {
                                let m = v64(d).iter().fold(0.0f64, |a, c| a.max(c.abs()));
                                ensure(m >= 0.25 - U, || {
                                    format!("{e:?} for an increment of {m} rad")
                                })?;
                                outcome = Err(e);
                            }
                            Err(e) => return Err(e.into()),
                        }
                    }
                    healthy_after(it.provisional_attitude(), norm, updates + 1, "provisional")?;
                    healthy_after(it.flush(), norm, updates + 1, "flush")?;
                    outcome.map_err(Fail::from)
                })
            }
        ),
        family!("ConingAccumulator<Q30>: push, rotation_vector, take", |g| {
            let k = 1 + g.rng.below(16);
            let incs: Vec<Vec3<Q30>> = (0..k).map(|_| increment(g)).collect();
            probe(&incs, || {
                let mut acc = ConingAccumulator::<Q30>::new();
                let (mut alpha, mut beta, mut prev) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                let mut outcome: Result<(), Error> = Ok(());
                let mut pushed = 0u32;
                for &d in &incs {
                    match acc.push(d) {
                        Ok(()) => {
                            let d64 = v64(d);
                            let lever = add(alpha, scale(prev, 1.0 / 6.0));
                            beta = add(beta, scale(cross(lever, d64), 0.5));
                            alpha = add(alpha, d64);
                            prev = d64;
                            pushed += 1;
                        }
                        Err(e @ (Error::StepTooLong | Error::OutOfRange)) => outcome = Err(e),
                        Err(e) => return Err(e.into()),
                    }
                }
                let phi = v64(acc.rotation_vector());
                let want = add(alpha, beta);
                // Per push: the lever's 1/6 (u/2), the cross product (u/2), exact sums;
                // each rounding is carried into β through products with |Δθ| < 2: 4u per push.
                let err = (0..3).fold(0.0f64, |m, i| m.max((phi[i] - want[i]).abs()));
                ensure(err <= 4.0 * U * f64::from(pushed.max(1)), || {
                    format!("φ off by {err:e} after {pushed} pushes")
                })?;
                let rv = acc.rotation_vector();
                ensure(acc.take() == rv && acc.count() == 0, || {
                    "take differs from rotation_vector".into()
                })?;
                outcome.map_err(Fail::from)
            })
        }),
        family!(
            "renormalisation health: renormalize, renormalize_fast, norm_squared_deviation",
            |g| {
                // A drifted attitude: |q|² anywhere in (½, 2) (the documented domain of the
                // exact renormalisation), or raw bits anywhere (no panic, value unspecified).
                let q = attitude(g);
                let in_domain = g.rng.chance(0.8);
                let raw = if in_domain {
                    let s = if g.rng.chance(0.5) {
                        1.0 + g.rng.range(-1e-3, 1e-3)
                    } else {
                        // |q|² = s² in (½, 2), a hair inside both ends.
                        let r = std::f64::consts::SQRT_2;
                        g.rng.range(1.0001 / r, 0.9999 * r)
                    };
                    q.to_f64()
                        .to_array()
                        .map(|c| Q30::try_from_f64(c * s).unwrap())
                } else {
                    [0; 4].map(|_| raw_q30(g))
                };
                let d = UnitQuat::new_unchecked(Quat::from_array(raw));
                probe(&d, || {
                    let exact = d.renormalize();
                    let fast = d.renormalize_fast();
                    let dev = norm_squared_deviation(d).to_f64();
                    if !in_domain {
                        return Ok(());
                    }
                    let h0 = health(d);
                    ensure((dev - h0).abs() <= U, || {
                        format!("norm_squared_deviation {dev:e}, exact {h0:e}")
                    })?;
                    healthy(exact, Normalization::Exact, "renormalize")?;
                    if h0.abs() <= 1e-3 * 2.1 {
                        // One Newton step: 3δ²/4 ≤ 3.3e-6 for |δ| ≤ 2.1e-3, plus roundings.
                        let h = health(fast);
                        ensure(h.abs() <= 0.75 * h0 * h0 + 16.0 * U, || {
                            format!("renormalize_fast: |q|² − 1 = {h:e} from {h0:e}")
                        })?;
                    }
                    Ok(())
                })
            }
        ),
    ]
}

#[test]
fn campaign() {
    run_campaign("fixed", families::<f32>(), families::<f64>());
}
