//! The oracle campaign (issue 19): properties that a finite, unit-looking `Ok` can still break.
//! Each family checks a result against an independent computation of what it must be, on
//! generators built to reach the intermediate overflows and the extremes of const parameters:
//!
//! - the compensated paths equal the plain f64 path fed the same (rounded) inputs within a few
//!   ulp of the type (the update is the rule's composition of exponentials);
//! - `CompensatedAttitude::mul_exp_unchecked((φ, φ_lo))` is `q ⊗ exp(φ + φ_lo)` by the closed form in
//!   f64, for angles of any size;
//! - the rate integrator's inputs are in range while their products are not (`dt` from 10⁻³⁰⁰
//!   to 10³⁰⁰ with rates scaled inversely), with adversarial step remainders;
//! - a solver's `Ok` satisfies its equation (`SpringRotor::equilibrium_radius`), a constructor's
//!   derived constants are representable, documented-total functions do not fail;
//! - a splitting step agrees with RK4 at small `|ω|dt` (cubic quartic at high spin);
//! - `rk4_step` at `h = 0` is `q`, `Drift::between` is finite in its domain;
//! - the fixed-point exponential in formats at the extremes of `Fixed<F>` (6 … 30).
//!
//! `cargo test --release -p host-tests --test robustness oracles:: -- --nocapture` prints the
//! table; `GYROSTAT_CAMPAIGN_N=1000000` is the long setting.

use gyrostat::dynamics::semi_rigid::{Arrangement, QuarticBasis, SemiRigidRotor, SpringRotor};
use gyrostat::dynamics::state::CompensatedState;
use gyrostat::dynamics::{
    BodyHamiltonian, Drift, Gyrostat, Inertia, Integrator, Invariants, Quartic, State,
};
use gyrostat::propagation::kernels::rk4_step;
use gyrostat::propagation::{
    CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::real::Fixed;
use gyrostat::{Error, Quat, UnitQuat, Vec3};
use host_tests::campaign::*;
use host_tests::family;
use host_tests::tolerance::Tolerance;

/// The rotation angle between two quaternions given in f64 (normalised here; sign-insensitive):
/// `2·atan2(|vec(a*⊗b)|, |scalar(a*⊗b)|)`, accurate at small angles.
fn angle(a: [f64; 4], b: [f64; 4]) -> f64 {
    let n = |q: [f64; 4]| q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let (a, b) = (a.map(|x| x / n(a)), b.map(|x| x / n(b)));
    let d = mul([a[0], -a[1], -a[2], -a[3]], b);
    let s = (d[1] * d[1] + d[2] * d[2] + d[3] * d[3]).sqrt();
    2.0 * s.atan2(d[0].abs())
}

/// The Hamilton product in f64.
fn mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// `exp(φ)` by its closed form in f64 (the angle as given, no range limit).
fn exp_ref(p: [f64; 3]) -> [f64; 4] {
    let t = p.iter().map(|x| x * x).sum::<f64>().sqrt();
    if t == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    let s = (t / 2.0).sin() / t;
    [(t / 2.0).cos(), s * p[0], s * p[1], s * p[2]]
}

fn q64<T: Tolerance>(q: Quat<T>) -> [f64; 4] {
    q.to_array().map(|c| c.to_f64())
}

fn v64<T: Tolerance>(v: Vec3<T>) -> Vec3<f64> {
    Vec3::from_array(v.to_array().map(|c| c.to_f64()))
}

/// The direction `q + q_lo` of a compensated attitude, in f64.
fn carried<T: Tolerance>(c: CompensatedAttitude<T>) -> [f64; 4] {
    let (q, lo) = (q64(c.attitude().into_quat()), q64(c.low()));
    [q[0] + lo[0], q[1] + lo[1], q[2] + lo[2], q[3] + lo[3]]
}

fn unit_f64(q: UnitQuat<f64>) -> [f64; 4] {
    q.into_quat().to_array()
}

fn t<T: Tolerance>(x: f64) -> T {
    T::from_f64(x)
}

/// A rotation vector for an update: ordinary (≤ 0.5 rad), near the limit, or of any size.
fn rotation_vector<T: Tolerance>(g: &mut Gen<T>) -> Vec3<T> {
    match g.rng.below(4) {
        0 | 1 => g.vec_within(0.5),
        2 => g.vec_within(3.0),
        _ => {
            let m = g.magnitude_in(3.0, g.lim.sqrt_max);
            g.vec_within(m)
        }
    }
}

/// The oracle tolerance of an update of total angle `theta`: the angle's own rounding (`ε·θ`,
/// it is an input rounded to `T`), a few ulp of the type per operation.
fn update_tolerance<T: Tolerance>(theta: f64, steps: f64) -> f64 {
    T::EPSILON.to_f64() * (64.0 * steps + 8.0 * theta)
}

fn families<T: Tolerance>() -> Vec<Family<T>> {
    vec![
        family!(
            "oracle: CompensatedAttitude::mul_exp_unchecked((φ, φ_lo)) = q ⊗ exp(φ + φ_lo)",
            |g| {
                let q = g.unit_quat();
                let phi = rotation_vector(g);
                // φ_lo: a rounding remainder, or a coning-sized term, or zero.
                let lo = match g.rng.below(3) {
                    0 => Vec3::ZERO,
                    1 => phi.scale(t::<T>(g.rng.range(-1.0, 1.0) * 1e-3 * g.lim.eps)),
                    _ => g.vec_within(0.3 * v64(phi).norm().min(1e3)),
                };
                let norm = *g.rng.pick(&[Normalization::Exact, Normalization::Fast]);
                probe(&(q, phi, lo, norm), || {
                    let c = CompensatedAttitude::new(q).mul_exp_unchecked((phi, lo), norm);
                    let a = c.attitude();
                    ensure(a.into_quat().is_finite(), || format!("non-finite {c:?}"))?;
                    let p = v64(phi) + v64(lo);
                    let theta = p.norm();
                    if theta <= 1.0 / g_eps::<T>() {
                        let want = mul(q64(q.into_quat()), exp_ref(p.to_array()));
                        let e = angle(carried(c), want);
                        let tol = update_tolerance::<T>(theta, 1.0);
                        ensure(e <= tol, || {
                            format!("{e:e} rad from exp(φ + φ_lo), tol {tol:e}")
                        })?;
                    }
                    unit(a)
                })
            }
        ),
        family!(
            "oracle: compensated IncrementIntegrator = plain f64 (same increments)",
            |g| {
                let rule = *g.rng.pick(&[
                    ConingRule::Exp,
                    ConingRule::OnePlusPrevious,
                    ConingRule::TwoSample,
                    ConingRule::ThreeSample,
                    ConingRule::FourSample,
                ]);
                let norm = *g.rng.pick(&[Normalization::Exact, Normalization::Fast]);
                let big = rule == ConingRule::Exp && g.rng.chance(0.3);
                let incs: Vec<Vec3<T>> = (0..8)
                    .map(|_| {
                        if big {
                            let m = g.magnitude_in(3.0, g.lim.sqrt_max);
                            g.vec_within(m)
                        } else {
                            let b = *g.rng.pick(&[1e-3, 0.1, 0.5, 1.5]);
                            g.vec_within(b)
                        }
                    })
                    .collect();
                probe(&(rule, norm, &incs), || {
                    let q0 = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY);
                    let mut c = IncrementIntegrator::new(q0, rule, norm);
                    let mut p = IncrementIntegrator::new(UnitQuat::<f64>::IDENTITY, rule, norm);
                    let mut theta = 0.0;
                    for d in &incs {
                        let r = c.push(*d);
                        let rp = p.push(v64(*d));
                        match (r, rp) {
                            (Ok(_), Ok(_)) => {}
                            (Err(e), _) => return Err(Fail::Error(e)),
                            (Ok(_), Err(e)) => {
                                return bad(format!("plain f64 {e:?}, compensated Ok"));
                            }
                        }
                        theta += v64(*d).norm();
                        unit(c.attitude())?;
                    }
                    let e = angle(carried(c.carried_attitude()), unit_f64(p.attitude()));
                    if theta <= 1.0 / g_eps::<T>() {
                        let tol = update_tolerance::<T>(theta, 8.0);
                        ensure(e <= tol, || {
                            format!("{e:e} rad from the plain f64 update, tol {tol:e}")
                        })?;
                    }
                    Ok(())
                })
            }
        ),
        family!(
            "oracle: compensated RateIntegrator = plain f64 (inputs in range, products not)",
            |g| {
                let method = *g
                    .rng
                    .pick(&[RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4]);
                let norm = *g.rng.pick(&[Normalization::Exact, Normalization::Fast]);
                // dt = s·u and rates (1/s)·v: the angles u·v are ordinary, dt and the rates may
                // be at either end of the range.
                let e10 = g.lim.max.log10() - 2.0;
                let s = 10f64.powf(g.rng.range(-e10, e10));
                let u = g.rng.range(0.1, 1.0);
                let dt: T = t(s * u);
                let bound = *g.rng.pick(&[0.1, 1.0, 1.9]);
                let samples: Vec<Vec3<T>> = (0..6)
                    .map(|_| {
                        let v = g.vec_within(bound / u);
                        Vec3::from_array(v.to_array().map(|c| t::<T>(c.to_f64() / s)))
                    })
                    .collect();
                let rem = match g.rng.below(4) {
                    0 => dt.to_f64() * g.lim.eps * g.rng.range(-0.5, 0.5),
                    1 => *g.rng.pick(&[1e300, -1.0, 1e-3]) * g.rng.range(0.5, 1.0),
                    _ => 0.0,
                };
                let rem: T = t(rem);
                probe(&(method, norm, dt, rem, &samples), || {
                    let q0 = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY);
                    let mut c = RateIntegrator::try_new(q0, method, norm, dt)?
                        .try_with_step_remainder(rem)?;
                    let dt64 = dt.to_f64() + rem.to_f64();
                    let mut p =
                        RateIntegrator::try_new(UnitQuat::<f64>::IDENTITY, method, norm, dt64)?;
                    let mut theta = 0.0;
                    for w in &samples {
                        let r = c.push(*w);
                        let rp = p.push(v64(*w));
                        match (r, rp) {
                            (Ok(a), Ok(b)) => {
                                for (x, y) in a.into_iter().zip(b) {
                                    unit(x)?;
                                    let e = angle(q64(x.into_quat()), unit_f64(y));
                                    let tol = update_tolerance::<T>(theta, 8.0) + 1e-9 * theta;
                                    ensure(e <= tol.max(T::per_type(2e-6, 1e-13)), || {
                                        format!("{e:e} rad from the plain f64 integrator")
                                    })?;
                                }
                            }
                            (Err(e), _) => return Err(Fail::Error(e)),
                            (Ok(_), Err(e)) => {
                                return bad(format!("plain f64 {e:?}, compensated Ok"));
                            }
                        }
                        theta += v64(*w).norm() * dt64.abs();
                    }
                    Ok(())
                })
            }
        ),
        family!(
            "oracle: compensated Gyrostat::step = plain f64 step (RK4 and splittings)",
            |g| {
                let m = g.moments_f64();
                let integ = *g.rng.pick(&Integrator::ALL);
                let quartic_t = g.rng.range(-1.0, 1.0) * 10f64.powf(g.rng.range(-6.0, 0.0));
                let kind = g.rng.below(3);
                let j = [
                    g.rng.range(-4.0, 4.0),
                    g.rng.range(-4.0, 4.0),
                    g.rng.range(-4.0, 4.0),
                ];
                // RK4 up to the limit (its polynomial is the same in both types); the splittings
                // at small angles, where the quartic flows are not ill-conditioned (at 2–3 rad
                // an f32 rounding of J moves a Yoshida step by up to 2e-3 rad in either path).
                let angle_target = if integ == Integrator::Rk4 {
                    *g.rng.pick(&[0.01, 0.5, 2.0, 3.0])
                } else {
                    *g.rng.pick(&[0.001, 0.01, 0.1, 0.5])
                };
                probe(&(m, integ, kind, quartic_t, j, angle_target), || {
                    let build = |m: [f64; 3]| -> Result<(Gyrostat<T>, Gyrostat<f64>), Error> {
                        let it = Inertia::try_from_principal(Vec3::from_array(m.map(t::<T>)))?;
                        let m64 = it.principal_moments().to_array().map(|c| c.to_f64());
                        let i64_ = Inertia::try_from_principal(Vec3::from_array(m64))?;
                        let (qt, q64_) = match kind {
                            0 => (Quartic::None, Quartic::None),
                            1 => (
                                Quartic::Octahedral(t(quartic_t)),
                                Quartic::Octahedral(t::<T>(quartic_t).to_f64()),
                            ),
                            _ => (
                                Quartic::Cubic(t(quartic_t)),
                                Quartic::Cubic(t::<T>(quartic_t).to_f64()),
                            ),
                        };
                        Ok((
                            Gyrostat::from(BodyHamiltonian::try_new(it, Vec3::ZERO, qt)?),
                            Gyrostat::from(BodyHamiltonian::try_new(i64_, Vec3::ZERO, q64_)?),
                        ))
                    };
                    let (bt, b64) = build(m)?;
                    let jt = Vec3::from_array(j.map(t::<T>));
                    let s = State::new(UnitQuat::<T>::IDENTITY, jt);
                    let w = v64(bt.omega(&s)).norm();
                    let dt: T = t(angle_target / w.max(1e-300));
                    let c = bt.step(integ, &CompensatedState::new(s), dt)?;
                    let s64 = State::new(UnitQuat::<f64>::IDENTITY, v64(jt));
                    let p = match b64.step(integ, &s64, dt.to_f64()) {
                        Ok(p) => p,
                        Err(e) => return bad(format!("plain f64 {e:?}, compensated Ok")),
                    };
                    unit(c.state().attitude)?;
                    let got = q64(c.state().attitude.into_quat());
                    let lo = q64(c.attitude_low());
                    let got = [
                        got[0] + lo[0],
                        got[1] + lo[1],
                        got[2] + lo[2],
                        got[3] + lo[3],
                    ];
                    let e = angle(got, unit_f64(p.attitude));
                    // The compensated step's own rounding and the rounding of J's rate in T;
                    // the RK4 step's truncation is the same polynomial in both. Compared for RK4
                    // and for the rigid splittings, on normal moments. A quartic splitting step
                    // is ill-conditioned in its rounding (measured: plain f32 and compensated
                    // f32 agree to 1e-6 while both are 1.6e-5 from f64 on the same input at
                    // 0.5 rad), and a subnormal moment has lost digits of `1/I` in `T`: there
                    // only the unit norm is checked; likewise beyond 0.5 rad, where an RK4 step's
                    // polynomial amplifies the rounding of its stages (6e-5 rad in f32 at 2 rad
                    // on a body with moments 3e31, 1e36, 1e36), though not its norm.
                    let normal_moments =
                        m.iter().all(|x| t::<T>(*x).to_f64().abs() >= g_min::<T>());
                    if (integ == Integrator::Rk4 || kind == 0)
                        && normal_moments
                        && angle_target <= 0.5
                    {
                        let tol = T::per_type(3e-6, 2e-13) * (1.0 + angle_target);
                        ensure(e <= tol, || {
                            format!("{e:e} rad from the plain f64 step, tol {tol:e}")
                        })?;
                    }
                    Ok(())
                })
            }
        ),
        family!(
            "oracle: splitting step agrees with RK4 at small |ω|dt (cubic quartic, high spin)",
            |g| {
                let i = 10f64.powf(g.rng.range(0.0, 12.0));
                let aniso = [
                    1.0,
                    1.0 + g.rng.range(0.0, 1e-3),
                    1.0 + g.rng.range(0.0, 2e-3),
                ];
                let t22 = g.rng.sign() * 10f64.powf(g.rng.range(-6.0, 0.0));
                let jn = 10f64.powf(g.rng.range(0.0, 8.0));
                let axis = g.rng.below(3);
                let mut j = [
                    g.rng.range(-1e-3, 1e-3),
                    g.rng.range(-1e-3, 1e-3),
                    g.rng.range(-1e-3, 1e-3),
                ];
                j[axis] = 1.0;
                let j = j.map(|c| c * jn);
                let net = 10f64.powf(g.rng.range(-6.0, -3.0));
                let integ = *g.rng.pick(&[
                    Integrator::Strang,
                    Integrator::Yoshida4,
                    Integrator::Suzuki4,
                ]);
                probe(&(i, aniso, t22, j, net, integ), || {
                    let it = Inertia::try_from_principal(Vec3::from_array(
                        aniso.map(|a| t::<T>(a * i)),
                    ))?;
                    let h = BodyHamiltonian::try_new(it, Vec3::ZERO, Quartic::Cubic(t(t22)))?;
                    let body = Gyrostat::from(h);
                    let s = State::new(UnitQuat::<T>::IDENTITY, Vec3::from_array(j.map(t::<T>)));
                    let w = v64(body.omega(&s)).norm();
                    let dt: T = t(net / w.max(1e-300));
                    let rk4 = body.step(Integrator::Rk4, &s, dt)?;
                    // The largest piece of the splitting: one-axis rates 2Aᵢ|J| + 2|t₂₂||J|³ and
                    // the Casimir 2|t₂₂||J|³, over the longest stage (≤ 1.71·dt).
                    let jm = v64(s.momentum).norm();
                    let piece = (1.0 / aniso[0].min(aniso[1]).min(aniso[2]) / i * jm
                        + 2.0 * t22.abs() * jm.powi(3))
                        * 1.71
                        * dt.to_f64();
                    match body.step(integ, &s, dt) {
                        Ok(n) => {
                            unit(n.attitude)?;
                            let e =
                                angle(q64(n.attitude.into_quat()), q64(rk4.attitude.into_quat()));
                            let tol = 0.05 * net + 1e3 * g_eps::<T>();
                            // Asserted where the bound holds: pieces small (the method's error is
                            // of their order cubed) or beyond the limit (then only a typed error
                            // is right); between, the method is valid but not this accurate.
                            if piece <= 0.05 || piece > 4.0 * std::f64::consts::PI {
                                ensure(e <= tol, || {
                                    format!(
                                        "{e:e} rad from RK4 at |ω|dt = {net:e} (largest piece {piece:e} rad)"
                                    )
                                })?;
                            }
                            Ok(())
                        }
                        Err(e) => Err(Fail::Error(e)),
                    }
                })
            }
        ),
        family!(
            "oracle: SpringRotor::equilibrium_radius solves its equation; constants representable",
            |g| {
                let (m, w, r0) = (g.positive(), g.positive(), g.positive());
                let j = match g.rng.below(3) {
                    0 => g.scalar(),
                    _ => t(g.rng.sign() * g.any_magnitude()),
                };
                probe(&(m, w, r0, j), || {
                    let rotor = SpringRotor::try_new(m, w, r0)?;
                    let mu = rotor.rest_inverse_inertia();
                    ensure(mu.is_finite() && mu > T::ZERO, || format!("μ₀ = {mu:?}"))?;
                    let r = rotor.equilibrium_radius(j)?;
                    ensure(r >= r0 && r.is_finite(), || {
                        format!("radius {r:?} below r₀ {r0:?}")
                    })?;
                    // x − 1 = b²/x³ in f64 from the rounded parameters, b = J/(mω r₀²).
                    let (m, w, r0, j) = (m.to_f64(), w.to_f64(), r0.to_f64(), j.to_f64());
                    // In mantissa–exponent form: b²/x³ is formed without overflow even where
                    // b itself is not an f64.
                    let (fj, fm, fw, fr) = (frexp(j), frexp(m), frexp(w), frexp(r0));
                    let bm = fj.0 / (fm.0 * fw.0 * fr.0 * fr.0);
                    let be = fj.1 - fm.1 - fw.1 - 2 * fr.1;
                    let b = ldexp(bm, be);
                    let x = r.to_f64() / r0;
                    let (xm, xe) = frexp(x);
                    let excess = ldexp(bm * bm / (xm * xm * xm), 2 * be - 3 * xe);
                    let res = (x - 1.0 - excess).abs() / x;
                    let tol = 64.0 * g_eps::<T>();
                    ensure(res <= tol, || {
                        format!("residual {res:e} at r = {r:?} (x = {x:e}, b = {b:e})")
                    })
                })
            }
        ),
        family!("oracle: SpringRotor::stretched_radius ≥ r₀", |g| {
            let (m, w, r0) = (g.positive(), g.positive(), g.positive());
            let frac: T = t(g.rng.range(-0.999, 0.999));
            probe(&(m, w, r0, frac), || {
                let rotor = SpringRotor::try_new(m, w, r0)?;
                let rs = rotor.stretched_radius(w * frac)?;
                ensure(rs >= r0, || format!("stretched radius {rs:?} < r₀"))
            })
        }),
        family!(
            "oracle: SemiRigidRotor try_body_hamiltonian total for constructed rotors",
            |g| {
                let a = *g.rng.pick(&[
                    Arrangement::Octahedral,
                    Arrangement::Cubic,
                    Arrangement::Tetrahedral,
                ]);
                let (m, w, r) = (g.positive(), g.positive(), g.positive());
                probe(&(a, m, w, r), || {
                    let rotor = SemiRigidRotor::try_symmetric(a, m, w, r)?;
                    for basis in [QuarticBasis::Octahedral, QuarticBasis::Cubic] {
                        if let Err(e) = rotor.try_body_hamiltonian(basis) {
                            return bad(format!("{basis:?}: {e:?} for a constructed rotor"));
                        }
                    }
                    Ok(())
                })
            }
        ),
        family!("oracle: rk4_step(h = 0) = q", |g| {
            let q = g.unit_quat().into_quat();
            let w = [g.vec(), g.vec(), g.vec()];
            probe(&(q, w), || {
                let [a, b, c] = w;
                if !(a.is_finite() && b.is_finite() && c.is_finite()) {
                    return Ok(());
                }
                let r = rk4_step(q, a, b, c, T::ZERO);
                ensure(r == q, || format!("rk4_step(h = 0) = {r:?}"))
            })
        }),
        family!(
            "oracle: Drift::between finite for representable differences",
            |g| {
                let half = g.lim.max / 2.0;
                let mut big = || {
                    let v = [
                        g.rng.range(-1.0, 1.0),
                        g.rng.range(-1.0, 1.0),
                        g.rng.range(-1.0, 1.0),
                    ];
                    let s = *g.rng.pick(&[1.0, 1e10, half]);
                    Vec3::from_array(v.map(|c| t::<T>(c * s)))
                };
                let (l0, l1) = (big(), big());
                probe(&(l0, l1), || {
                    let norm = |l: Vec3<T>| t::<T>(v64(l).norm());
                    let inv = |l| Invariants {
                        energy: T::ONE,
                        momentum_norm: norm(l),
                        lab_momentum: l,
                    };
                    let d = Drift::between(&inv(l0), &inv(l1));
                    ensure(
                        d.energy.is_finite()
                            && d.momentum_norm.is_finite()
                            && d.lab_momentum.is_finite(),
                        || format!("{d:?}"),
                    )
                })
            }
        ),
        family!(
            "oracle: Fixed<F> exponential at the format extremes (F = 6 … 30)",
            |g| {
                // f32 row: the wide formats; f64 row: the narrow ones.
                let f = if T::INDEX == 0 {
                    *g.rng.pick(&[6u32, 10, 16])
                } else {
                    *g.rng.pick(&[24u32, 29, 30])
                };
                let range = 2f64.powi(31 - f as i32);
                let mag = match g.rng.below(3) {
                    0 => g.rng.range(0.0, 4.0),
                    1 => g.rng.range(0.0, range),
                    _ => range * g.rng.range(0.9, 1.0),
                };
                let dir = [
                    g.rng.range(-1.0, 1.0),
                    g.rng.range(-1.0, 1.0),
                    g.rng.range(-1.0, 1.0),
                ];
                let n = dir.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-3);
                let p = dir.map(|c| (c / n * mag).clamp(-range * 0.999, range * 0.999));
                probe(&(f, p), || match f {
                    6 => fixed_exp::<6>(p),
                    10 => fixed_exp::<10>(p),
                    16 => fixed_exp::<16>(p),
                    24 => fixed_exp::<24>(p),
                    29 => fixed_exp::<29>(p),
                    _ => fixed_exp::<30>(p),
                })
            }
        ),
    ]
}

/// The smallest normal number of `T` as f64.
fn g_min<T: Tolerance>() -> f64 {
    T::per_type(f64::from(f32::MIN_POSITIVE), f64::MIN_POSITIVE)
}

/// `x = m·2ᵉ` with `|m| ∈ [1, 2)` (0 for 0): products and quotients of such pairs do not
/// overflow or underflow, for the reference computations of the solver oracle.
fn frexp(x: f64) -> (f64, i32) {
    if x == 0.0 || !x.is_finite() {
        return (x, 0);
    }
    let e = x.abs().log2().floor() as i32;
    let m = x / 2f64.powi(e / 2) / 2f64.powi(e - e / 2);
    (m, e)
}

/// `m·2ᵉ` as an f64 (∞ or 0 beyond the range).
fn ldexp(m: f64, e: i32) -> f64 {
    m * 2f64.powi(e / 2) * 2f64.powi(e - e / 2)
}

/// The machine epsilon of `T` as f64.
fn g_eps<T: Tolerance>() -> f64 {
    T::EPSILON.to_f64()
}

/// `UnitQuat::<Fixed<F>>::exp_unchecked` against the closed form of the converted `φ`: within
/// `2·2⁻ᶠ + 80·2⁻ᴳ` per component, `G = max(F, 28)` the format the exponential is taken in (the
/// rounding back to `Fixed<F>`, and the accuracy test's bound of 68 units at 5 halvings).
fn fixed_exp<const F: u32>(p: [f64; 3]) -> Check {
    let c = |x: f64| Fixed::<F>::try_from_f64(x);
    let phi = Vec3::new(c(p[0])?, c(p[1])?, c(p[2])?);
    let exact = [phi.x.to_f64(), phi.y.to_f64(), phi.z.to_f64()];
    let q = UnitQuat::<Fixed<F>>::exp_unchecked(phi).into_quat();
    let got = [q.w.to_f64(), q.x.to_f64(), q.y.to_f64(), q.z.to_f64()];
    let want = exp_ref(exact);
    let g = F.max(28) as i32;
    let tol = 2.0 * 2f64.powi(-(F as i32)) + 80.0 * 2f64.powi(-g);
    let err = (0..4).map(|i| (got[i] - want[i]).abs()).fold(0.0, f64::max);
    ensure(err <= tol, || {
        format!("Fixed<{F}> exp: component error {err:e} (tol {tol:e}), got {got:?}")
    })
}

#[test]
fn campaign() {
    run_campaign("oracles", families::<f32>(), families::<f64>());
}
