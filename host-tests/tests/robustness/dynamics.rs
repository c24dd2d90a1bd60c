//! The adversarial campaign over the dynamics families (see `host_tests::campaign` and
//! `ROBUSTNESS.md`): inertia and mass properties, the body models, every integrator with and
//! without torque and wheels, the monitors, the exact free body, the elliptic functions, the
//! seed's analysis functions, the Euler-coordinate rotor and the semi-rigid rotors.
//!
//! `cargo test --release -p host-tests --test robustness dynamics:: -- --nocapture` prints the
//! table; `GYROSTAT_CAMPAIGN_N=1000000 GYROSTAT_CAMPAIGN_WRITE=1` is the long setting that
//! writes it into `ROBUSTNESS.md`.

use gyrostat::dynamics::closed_form::analysis::{
    constant_energy_radius, direction, gyro_multipoles, momentum_ellipsoid_radii,
    rotational_energy, separatrix_angle, small_motion, symmetric_top_rates,
    velocity_ellipsoid_radii,
};
use gyrostat::dynamics::closed_form::elliptic::{
    amplitude, carlson_rf, carlson_rj, complete_k, incomplete_f, incomplete_pi, sn_cn_dn,
};
use gyrostat::dynamics::closed_form::euler_coordinates::{
    SymmetricTop, euler_hamiltonian, euler_metric, kinetic_energy, try_euler_momenta,
    try_euler_rates_from_momenta,
};
use gyrostat::dynamics::inertia::symmetric_eigen;
use gyrostat::dynamics::mass::{
    impulse_response, inertia_from_point_masses, parallel_axis_shift, percussion_radius,
    radius_of_gyration, total_mass_and_center,
};
use gyrostat::dynamics::semi_rigid::{
    Arrangement, QuarticBasis, SemiRigidRotor, SpringRotor, StretchMode, radial_stretches,
};
use gyrostat::dynamics::{
    BodyHamiltonian, Control, Drift, DriftMonitor, FreeRigidBody, Gyrostat, Inertia, Integrator,
    Quartic, State, Wheel, WheelCommand, angular_acceleration, lab_momentum, momentum_norm,
};
use gyrostat::rotation::Euler;
use gyrostat::step_limit::MAX_STEP_ANGLE;
use gyrostat::{Axis, Mat3, Real, Vec3};
use host_tests::campaign::*;
use host_tests::family;
use host_tests::tolerance::Tolerance;

/// A finite state-independent check of an `Inertia`: finite entries, positive moments obeying
/// the triangle inequality (to the library's own rounding allowance), a unit principal
/// rotation, and `R(P)·diag(λ)·R(P)ᵀ` reproducing the tensor to 64 ε of its largest entry (the
/// Jacobi decomposition's rounding, a few ε‖I‖, with margin).
fn inertia_ok<T: Tolerance>(i: &Inertia<T>) -> Check {
    finite_mat(&i.tensor())?;
    finite_mat(&i.inverse())?;
    let m = i.principal_moments();
    finite_vec(m)?;
    let eps = T::EPSILON.to_f64();
    let (a, b, c) = (m.x.to_f64(), m.y.to_f64(), m.z.to_f64());
    let slack = 32.0 * eps * (a + b + c) * 1.01;
    ensure(
        a > 0.0
            && b > 0.0
            && c > 0.0
            && a <= b + c + slack
            && b <= a + c + slack
            && c <= a + b + slack,
        || format!("moments {m:?} not physical"),
    )?;
    unit(i.principal_rotation())?;
    rotation_within(&i.principal_axes(), 64.0 * eps)?;
    let v = host_tests::cast::m64(&i.principal_axes());
    let t = host_tests::cast::m64(&i.tensor());
    let d = [a, b, c];
    let scale = t.iter().flatten().fold(0.0f64, |x, y| x.max(y.abs()));
    let mut err: f64 = 0.0;
    for r in 0..3 {
        for s in 0..3 {
            let x: f64 = (0..3).map(|k| v[r][k] * d[k] * v[s][k]).sum();
            err = err.max((x - t[r][s]).abs());
        }
    }
    ensure(err <= 64.0 * eps * scale, || {
        format!("principal frame reproduces the tensor to {err:e} of {scale:e}")
    })
}

/// A state: unit attitude, finite momentum and wheel speeds.
fn state_ok<T: Tolerance, const N: usize>(s: &State<T, N>) -> Check {
    unit(s.attitude)?;
    finite_vec(s.momentum)?;
    finite_all(&s.wheel_speeds)
}

/// An `Ok` step kept to the validity limit: `|ω|·dt ≤ π` before and after (with the rounding
/// of the library's own test, 8 ε relative).
fn within_limit<T: Tolerance, const N: usize>(
    body: &Gyrostat<T, N>,
    before: &State<T, N>,
    after: &State<T, N>,
    dt: T,
) -> Check {
    for (when, s) in [("before", before), ("after", after)] {
        let w = host_tests::cast::v64(body.omega(s)).map(|c| c * dt.to_f64());
        let angle = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        ensure(
            angle <= MAX_STEP_ANGLE * (1.0 + 8.0 * T::EPSILON.to_f64()),
            || format!("Ok step turning {angle} rad per step ({when})"),
        )?;
    }
    Ok(())
}

/// A body model: rigid (any inertia), with a constant rotor spin, or with a quartic term.
fn model<T: Tolerance>(g: &mut Gen<T>) -> BodyHamiltonian<T> {
    match g.rng.below(4) {
        0..=1 => BodyHamiltonian::rigid(g.inertia()),
        2 => {
            let i = g.inertia();
            let spin = g.finite_vec();
            BodyHamiltonian::try_new(i, spin, Quartic::None)
                .unwrap_or_else(|_| BodyHamiltonian::rigid(i))
        }
        _ => {
            let i = g.diagonal_inertia();
            let t = g.finite();
            let q = if g.rng.chance(0.5) {
                Quartic::Octahedral(t)
            } else {
                Quartic::Cubic(t)
            };
            BodyHamiltonian::try_new(i, Vec3::ZERO, q).unwrap_or_else(|_| BodyHamiltonian::rigid(i))
        }
    }
}

/// A step length for a body whose rate is about `rate`: mostly well inside the validity limit,
/// sometimes near it or beyond, sometimes any step at all.
fn step_for<T: Tolerance>(g: &mut Gen<T>, rate: f64) -> T {
    if g.rng.chance(0.6) && rate > 0.0 && rate.is_finite() {
        let angle = match g.rng.below(4) {
            0..=1 => g.magnitude_in(1e-4, 0.3),
            2 => g.rng.range(0.3, MAX_STEP_ANGLE),
            _ => g.rng.range(MAX_STEP_ANGLE, 10.0),
        };
        let dt = angle / rate;
        if dt.is_finite() && dt > 0.0 {
            return T::from_f64(dt);
        }
    }
    g.dt()
}

/// The documented domain of the infallible maps of a momentum (`BodyHamiltonian::energy_with_rotor`):
/// `|J − h|²/I_min`, `|J − h|/I_min`, and with a quartic term `|J|⁴`, `|t|·|J|⁴` and `12|t|·|J|³`
/// below `MAX/8`, evaluated in
/// logarithms (no overflow in the check itself).
fn in_rate_domain<T: Tolerance>(model: &BodyHamiltonian<T>, j: Vec3<T>, h: Vec3<T>) -> bool {
    let lmax = (Limits::of::<T>().max / 8.0).ln();
    let v = host_tests::cast::v64(j);
    let w = host_tests::cast::v64(j - h);
    let (jn, r) = (v[0].hypot(v[1]).hypot(v[2]), w[0].hypot(w[1]).hypot(w[2]));
    let imin = host_tests::cast::v64(model.inertia().principal_moments())
        .iter()
        .fold(f64::MAX, |a, b| a.min(*b));
    let t = match model.quartic() {
        Quartic::None => None,
        Quartic::Octahedral(t) | Quartic::Cubic(t) => Some(t.to_f64().abs()),
    };
    let ok = |ln: f64| ln <= lmax;
    (j - h).is_finite()
        && ok(2.0 * r.ln() - imin.ln())
        && ok(r.ln() - imin.ln())
        && t.is_none_or(|t| {
            ok(4.0 * jn.ln())
                && ok(t.ln() + 4.0 * jn.ln())
                && ok(12f64.ln() + t.ln() + 3.0 * jn.ln())
        })
}

fn g_min_subnormal<T: Tolerance>() -> f64 {
    Limits::of::<T>().min_subnormal
}

fn rate_of<T: Real, const N: usize>(body: &Gyrostat<T, N>, s: &State<T, N>) -> f64 {
    let w = host_tests::cast::v64(body.omega(s));
    (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt()
}

fn families<T: Tolerance>() -> Vec<Family<T>> {
    vec![
        family!("Inertia::try_from_principal", |g| {
            let m = match g.rng.below(3) {
                0 => Vec3::new(g.scalar(), g.scalar(), g.scalar()),
                _ => Vec3::from_array(g.moments_f64().map(T::from_f64)),
            };
            probe(&m, || inertia_ok(&Inertia::try_from_principal(m)?))
        }),
        family!("Inertia::try_from_components, try_from_tensor", |g| {
            let t = match g.rng.below(4) {
                0 => g.mat(),
                _ => g.inertia_tensor(),
            };
            let (d, o) = (t.diagonal(), Vec3::new(t.m[0][1], t.m[0][2], t.m[1][2]));
            probe(&t, || {
                inertia_ok(&Inertia::try_from_tensor(t)?)?;
                inertia_ok(&Inertia::try_from_components(d, o)?)
            })
        }),
        family!(
            "Inertia: mul_vec, solve, energy_from_momentum, radii_of_gyration, radius_of_gyration_about",
            |g| {
                let i = g.inertia();
                // Domain of the infallible maps: |J| with a representable energy |J|²/(2 I_min).
                let imin = host_tests::cast::v64(i.principal_moments())
                    .iter()
                    .fold(f64::MAX, |a, b| a.min(*b));
                let imax = host_tests::cast::v64(i.principal_moments())
                    .iter()
                    .fold(0.0f64, |a, b| a.max(*b));
                let bound = (g.lim.max.sqrt() * imin.sqrt()).min(g.lim.max / imax) / 8.0;
                let j = g.vec_within(bound);
                let (mass, axis) = (g.scalar(), g.vec());
                probe(&(i, j, mass, axis), || {
                    finite_vec(i.mul_vec(i.solve(j)))?;
                    finite(i.energy_from_momentum(j))?;
                    finite_vec(i.radii_of_gyration(mass)?)?;
                    finite(i.radius_of_gyration_about(axis, mass)?)
                })
            }
        ),
        family!("inertia::symmetric_eigen", |g| {
            // Domain: a finite symmetric matrix (entries below MAX/8, so that the rotations'
            // sums stay finite).
            let t = g.inertia_tensor();
            let t = if t.max_abs().to_f64() <= g.lim.max / 8.0 {
                t
            } else {
                Mat3::IDENTITY
            };
            probe(&t, || {
                let (l, v) = symmetric_eigen(&t);
                finite_vec(l)?;
                rotation_within(&v, 64.0 * T::EPSILON.to_f64())
            })
        }),
        family!("Wheel::try_new", |g| {
            let (axis, inertia) = (g.vec(), g.scalar());
            probe(&(axis, inertia), || {
                let w = Wheel::try_new(axis, inertia)?;
                finite_vec(w.axis())?;
                finite(w.inertia())
            })
        }),
        family!(
            "BodyHamiltonian::try_new, energy, omega, hessian, try_momentum_from_omega",
            |g| {
                let i = if g.rng.chance(0.5) {
                    g.diagonal_inertia()
                } else {
                    g.inertia()
                };
                let spin = g.vec();
                let q = match g.rng.below(3) {
                    0 => Quartic::None,
                    1 => Quartic::Octahedral(g.scalar()),
                    _ => Quartic::Cubic(g.scalar()),
                };
                let w = g.vec();
                let j = g.momentum(&i);
                probe(&(i, spin, q, w, j), || {
                    let h = BodyHamiltonian::try_new(i, spin, q)?;
                    let jj = h.try_momentum_from_omega(w)?;
                    finite_vec(jj)?;
                    if j.is_finite() && in_rate_domain(&h, j, h.spin()) {
                        // The infallible maps on their documented domain.
                        finite(h.energy(j))?;
                        finite_vec(h.omega(j))?;
                        finite_mat(&h.hessian(j))?;
                    }
                    Ok(())
                })
            }
        ),
        family!(
            "Gyrostat::step (RK4, Strang, Yoshida4, Suzuki4; rigid, rotor, quartic, full tensor)",
            |g| {
                let body = Gyrostat::from(model(g));
                let s = State::new(g.unit_quat(), g.momentum(body.model().inertia()));
                let integ = *g.rng.pick(&Integrator::ALL);
                let dt = step_for(g, rate_of(&body, &s));
                probe(&(body, s, integ, dt), || {
                    let n = body.step(integ, &s, dt)?;
                    state_ok(&n)?;
                    within_limit(&body, &s, &n, dt)?;
                    if integ.is_splitting() && body.model().spin() == Vec3::ZERO {
                        // The splittings keep |J| to rounding: each sub-step is an exact rotation,
                        // rounding |J| by a few ε (the general-axis Rodrigues form: two cross
                        // products and a sum, up to about 4 ε; measured 80 ε for Suzuki4 on a
                        // full tensor); 21 sub-steps at most (Suzuki4): 128 ε. Plus the absolute
                        // rounding floor of subnormal components (half the smallest subnormal per
                        // operation, 256 of them).
                        // Compared on the momenta divided by their largest component (|J| itself
                        // overflows for components near the type's maximum).
                        let (va, vb) = (
                            host_tests::cast::v64(s.momentum),
                            host_tests::cast::v64(n.momentum),
                        );
                        let m = va
                            .iter()
                            .chain(vb.iter())
                            .fold(0.0f64, |x, y| x.max(y.abs()));
                        let scaled = |v: [f64; 3]| {
                            if m > 0.0 {
                                (v[0] / m).hypot(v[1] / m).hypot(v[2] / m)
                            } else {
                                0.0
                            }
                        };
                        let (a, b) = (scaled(va), scaled(vb));
                        let floor = if m > 0.0 {
                            256.0 * g_min_subnormal::<T>() / m
                        } else {
                            0.0
                        };
                        ensure(
                            (a - b).abs() <= 128.0 * T::EPSILON.to_f64() * a + floor,
                            || format!("|J|/{m:e} {a} -> {b}"),
                        )?;
                    }
                    Ok(())
                })
            }
        ),
        family!(
            "Gyrostat::step_with (held torque and wheel commands, 2 wheels, every integrator)",
            |g| {
                let model = model(g);
                let wheels = [
                    Wheel::try_new(g.vec(), g.positive()),
                    Wheel::try_new(g.vec(), g.positive()),
                ];
                let [Ok(w0), Ok(w1)] = wheels else {
                    return probe(&wheels, || {
                        wheels[0]?;
                        wheels[1]?;
                        Ok(())
                    });
                };
                let body = Gyrostat::new(model, [w0, w1]);
                let mut s: State<T, 2> = State::new(g.unit_quat(), g.momentum(model.inertia()));
                s.wheel_speeds = [g.finite(), g.finite()];
                let integ = *g.rng.pick(&Integrator::ALL);
                let dt = step_for(g, rate_of(&body, &s));
                let torque = if g.rng.chance(0.5) {
                    g.vec_within(1.0)
                } else {
                    g.vec()
                };
                let cmd = match g.rng.below(4) {
                    0 => WheelCommand::Torque([g.uniform(-1.0, 1.0), g.uniform(-1.0, 1.0)]),
                    1 => WheelCommand::Speed([g.uniform(-10.0, 10.0), g.uniform(-10.0, 10.0)]),
                    2 => WheelCommand::Torque([g.scalar(), g.scalar()]),
                    _ => WheelCommand::Speed([g.scalar(), g.scalar()]),
                };
                let t = g.scalar();
                probe(&(body, s, integ, dt, torque, cmd, t), || {
                    let c = body.control(&s, dt, torque, &cmd);
                    let n = body.step_with(integ, &s, t, dt, c)?;
                    state_ok(&n)?;
                    within_limit(&body, &s, &n, dt)
                })
            }
        ),
        family!(
            "Gyrostat::step_with (a control law: rate damping and a lab-fixed torque)",
            |g| {
                let body = Gyrostat::from(model(g));
                let s = State::new(g.unit_quat(), g.momentum(body.model().inertia()));
                let integ = *g.rng.pick(&Integrator::ALL);
                let dt = step_for(g, rate_of(&body, &s));
                let (k, lab) = (g.finite(), g.vec());
                probe(&(body, s, integ, dt, k, lab), || {
                    let law = |_t: T, x: &State<T>| {
                        let damping = body.omega(x).scale(-k);
                        Control::torque(damping + x.attitude.inverse_rotate(lab))
                    };
                    let n = body.step_with(integ, &s, T::ZERO, dt, law)?;
                    state_ok(&n)?;
                    within_limit(&body, &s, &n, dt)
                })
            }
        ),
        family!(
            "Gyrostat: try_state_from_omega, omega, energy, invariants, rotor_momentum; angular_acceleration",
            |g| {
                let body = Gyrostat::from(model(g));
                let (q, w) = (g.unit_quat(), g.vec());
                let i = *body.model().inertia();
                // The infallible maps on a state with a representable energy.
                let j = g.momentum(&i);
                let (h, hd, tau) = (g.finite_vec(), g.finite_vec(), g.finite_vec());
                probe(&(body, q, w, j, h, hd, tau), || {
                    let s = State::new(q, j);
                    if j.is_finite() && in_rate_domain(body.model(), j, body.rotor_momentum(&[])) {
                        finite(body.energy(&s))?;
                        finite_vec(body.omega(&s))?;
                        let inv = body.invariants(&s);
                        finite(inv.momentum_norm)?;
                        finite_vec(inv.lab_momentum)?;
                        finite_vec(body.rotor_momentum(&[]))?;
                    }
                    let wdot = angular_acceleration(&i, w.try_finite()?, h, hd, tau);
                    let _ = wdot; // arithmetic on the caller's magnitudes (domain: see the docs)
                    let s = body.try_state_from_omega(q, w, [])?;
                    state_ok(&s)
                })
            }
        ),
        family!(
            "monitors: Drift::between, DriftMonitor, momentum_norm, lab_momentum",
            |g| {
                let body = Gyrostat::from(model(g));
                let i = *body.model().inertia();
                let (a, b) = (
                    State::new(g.unit_quat(), g.momentum(&i)),
                    State::new(g.unit_quat(), g.momentum(&i)),
                );
                probe(&(body, a, b), || {
                    let fine = |s: &State<T>| {
                        s.momentum.is_finite()
                            && in_rate_domain(body.model(), s.momentum, body.rotor_momentum(&[]))
                    };
                    if !(fine(&a) && fine(&b)) {
                        return Err(gyrostat::Error::NonFinite.into());
                    }
                    finite(momentum_norm(a.momentum))?;
                    finite_vec(lab_momentum(a.attitude, a.momentum))?;
                    let (ia, ib) = (body.invariants(&a), body.invariants(&b));
                    let d = Drift::between(&ia, &ib);
                    finite_all(&[d.energy, d.momentum_norm, d.lab_momentum])?;
                    let mut m = DriftMonitor::new(ia);
                    let d2 = m.record(&ib);
                    finite_all(&[d2.energy, d2.momentum_norm, d2.lab_momentum])
                })
            }
        ),
        family!(
            "FreeRigidBody::try_new, try_state_at, body_momentum_at, body_rates_at, flip_interval",
            |g| {
                let i = g.inertia();
                let s = State::new(g.unit_quat(), g.momentum(&i));
                let t = match g.rng.below(3) {
                    0 => g.uniform(-20.0, 20.0),
                    _ => g.scalar(),
                };
                probe(&(i, s, t), || {
                    let fb = FreeRigidBody::try_new(&i, &s)?;
                    finite_all(&[fb.energy(), fb.momentum_norm()])?;
                    finite_vec(fb.lab_momentum())?;
                    if let Some(m) = fb.parameter_m() {
                        finite(m)?;
                    }
                    if let Some(f) = fb.flip_interval() {
                        finite(f)?;
                    }
                    // At t = 0 the closed form reproduces the initial state.
                    let s0 = fb.try_state_at(T::ZERO)?;
                    state_ok(&s0)?;
                    let j0 = host_tests::cast::v64(s.momentum);
                    let n0 = j0[0].hypot(j0[1]).hypot(j0[2]);
                    let back = host_tests::cast::v64(s0.momentum);
                    let dj = (back[0] - j0[0])
                        .hypot(back[1] - j0[1])
                        .hypot(back[2] - j0[2]);
                    // Relative to |J₀| (see the docs' accuracy table), plus the absolute rounding of
                    // subnormal components (their direction has only a few bits).
                    let tol = T::per_type(1e-4, 1e-9);
                    let floor = 16.0 * g_min_subnormal::<T>();
                    ensure(dj <= tol * n0 + floor, || {
                        format!("J(0) = {back:?} for J0 = {j0:?}: {:e} relative", dj / n0)
                    })?;
                    let st = fb.try_state_at(t)?;
                    state_ok(&st)?;
                    finite_vec(fb.body_momentum_at(t))?;
                    finite_vec(fb.body_rates_at(t))?;
                    // |J| is conserved by the closed form.
                    let nt = {
                        let v = host_tests::cast::v64(st.momentum);
                        v[0].hypot(v[1]).hypot(v[2])
                    };
                    ensure((nt - n0).abs() <= tol * n0 + floor, || {
                        format!("|J(t)| = {nt:e} for |J0| = {n0:e}")
                    })
                })
            }
        ),
        family!(
            "elliptic: complete_k, sn_cn_dn, amplitude, incomplete_f",
            |g| {
                let m = match g.rng.below(4) {
                    0 => g.uniform(0.0, 1.0),
                    1 => T::from_f64(1.0 - g.magnitude_in(g.lim.min_subnormal.max(1e-300), 1.0)),
                    _ => g.scalar(),
                };
                let u = g.scalar();
                probe(&(m, u), || {
                    let (sn, cn, dn) = sn_cn_dn(u, m)?;
                    finite_all(&[sn, cn, dn])?;
                    let r = (sn * sn + cn * cn).to_f64();
                    ensure((r - 1.0).abs() <= 16.0 * T::EPSILON.to_f64(), || {
                        format!("sn² + cn² = {r}")
                    })?;
                    finite(complete_k(m)?)?;
                    finite(amplitude(u, m)?)?;
                    finite(incomplete_f(u, m)?)
                })
            }
        ),
        family!("elliptic: carlson_rf, carlson_rj, incomplete_pi", |g| {
            let (x, y, z, p) = match g.rng.below(3) {
                0 => (g.positive(), g.positive(), g.positive(), g.positive()),
                _ => (g.scalar(), g.scalar(), g.scalar(), g.scalar()),
            };
            let (n, phi, m) = (g.scalar(), g.scalar(), g.uniform(0.0, 1.0));
            probe(&(x, y, z, p, n, phi, m), || {
                finite(carlson_rf(x, y, z)?)?;
                finite(carlson_rj(x, y, z, p)?)?;
                finite(incomplete_pi(n, phi, m)?)
            })
        }),
        family!(
            "analysis: rotational_energy, constant_energy_radius, ellipsoid radii, direction",
            |g| {
                let i = g.inertia();
                let (j, e, beta, gamma) = (g.scalar(), g.scalar(), g.scalar(), g.scalar());
                probe(&(i, j, e, beta, gamma), || {
                    if beta.is_finite() && gamma.is_finite() {
                        finite_vec(direction(beta, gamma))?;
                    }
                    finite(rotational_energy(&i, j, beta, gamma)?)?;
                    finite(constant_energy_radius(&i, e, beta, gamma)?)?;
                    finite_vec(momentum_ellipsoid_radii(&i, e)?)?;
                    finite_vec(velocity_ellipsoid_radii(&i, e)?)
                })
            }
        ),
        family!(
            "analysis: separatrix_angle, small_motion, symmetric_top_rates, gyro_multipoles",
            |g| {
                let i = g.inertia();
                let (j, beta, spin) = (g.scalar(), g.scalar(), g.vec());
                let axis = *g.rng.pick(&Axis::ALL);
                probe(&(i, j, beta, spin, axis), || {
                    if let Ok(a) = separatrix_angle(&i) {
                        finite(a)?;
                    }
                    let sm = small_motion(&i, j, axis)?;
                    finite(sm.rate)?;
                    if let Ok(r) = symmetric_top_rates(&i, j, beta) {
                        finite_all(&[r.lab_precession, r.body_precession, r.axial_rate])?;
                        finite_vec(r.omega_body)?;
                        finite_vec(r.omega_lab)?;
                    }
                    let mp = gyro_multipoles(&i, spin)?;
                    finite_all(&[mp.constant, mp.monopole, mp.q_zz, mp.q_x2_y2])?;
                    finite_vec(mp.dipole)?;
                    Ok(())
                })
            }
        ),
        family!(
            "mass: inertia_from_point_masses, total_mass_and_center, parallel_axis_shift",
            |g| {
                let n = g.rng.below(5);
                let pts: Vec<(T, gyrostat::Vec3<T>)> =
                    (0..n).map(|_| (g.scalar(), g.vec())).collect();
                let (i_cm, m, r) = (g.mat(), g.scalar(), g.vec());
                probe(&(pts.clone(), i_cm, m, r), || {
                    if let Ok(i) = inertia_from_point_masses(&pts) {
                        finite_mat(&i)?;
                    }
                    if let Ok((mt, c)) = total_mass_and_center(&pts) {
                        finite(mt)?;
                        finite_vec(c)?;
                    }
                    finite_mat(&parallel_axis_shift(&i_cm, m, r)?)
                })
            }
        ),
        family!(
            "mass: radius_of_gyration, percussion_radius, impulse_response",
            |g| {
                let (moment, mass, h) = (g.scalar(), g.scalar(), g.scalar());
                let (i, lever, imp) = (g.mat(), g.vec(), g.vec());
                probe(&(moment, mass, h, i, lever, imp), || {
                    if let Ok(r) = radius_of_gyration(moment, mass) {
                        finite(r)?;
                        finite(percussion_radius(r, h)?)?;
                    }
                    let resp = impulse_response(&i, mass, lever, imp)?;
                    finite_vec(resp.delta_omega)?;
                    finite_vec(resp.delta_velocity)?;
                    finite_vec(resp.angular_impulse)
                })
            }
        ),
        family!(
            "euler_coordinates: metric, momenta, kinetic energy, rates from momenta, Hamiltonian",
            |g| {
                let i = g.inertia();
                let seq = g.sequence();
                let e = Euler::new(seq, g.euler_angles(seq));
                let (rates, p) = (
                    [g.scalar(), g.scalar(), g.scalar()],
                    [g.scalar(), g.scalar(), g.scalar()],
                );
                probe(&(i, e, rates, p), || {
                    finite_mat(&euler_metric(&i, &e)?)?;
                    finite_all(&try_euler_momenta(&i, &e, rates)?)?;
                    finite(kinetic_energy(&i, &e, rates)?)?;
                    finite_all(&try_euler_rates_from_momenta(&i, &e, p)?)?;
                    finite(euler_hamiltonian(&i, &e, p)?)
                })
            }
        ),
        family!("euler_coordinates::SymmetricTop", |g| {
            let (it, ia) = if g.rng.chance(0.7) {
                (g.positive(), g.positive())
            } else {
                (g.scalar(), g.scalar())
            };
            let beta = g.scalar();
            let (rates, p) = (
                [g.scalar(), g.scalar(), g.scalar()],
                [g.scalar(), g.scalar(), g.scalar()],
            );
            probe(&(it, ia, beta, rates, p), || {
                let top = SymmetricTop::try_new(it, ia)?;
                finite(top.lagrangian(beta, rates)?)?;
                finite_mat(&top.metric(beta)?)?;
                finite_all(&top.try_momenta(beta, rates)?)?;
                finite(top.beta_torque_from_rates(beta, rates)?)?;
                finite_all(&top.try_rates(beta, p)?)?;
                finite(top.hamiltonian(beta, p)?)?;
                finite(top.beta_torque(beta, p)?)
            })
        }),
        family!("semi_rigid: StretchMode, SpringRotor", |g| {
            let (m, wv, d, r0) = if g.rng.chance(0.7) {
                (g.positive(), g.positive(), g.finite(), g.positive())
            } else {
                (g.scalar(), g.scalar(), g.scalar(), g.scalar())
            };
            let (j, mu0, radius, pv, wj) =
                (g.scalar(), g.scalar(), g.scalar(), g.scalar(), g.scalar());
            probe(&(m, wv, d, r0, j, mu0, radius, pv, wj), || {
                if let Ok(mode) = StretchMode::try_new(m, wv, d) {
                    finite_all(&[mode.stiffness(), mode.quartic_coefficient()])?;
                    finite(mode.stretch(j)?)?;
                    finite(mode.stretched_inverse_inertia(mu0, j)?)?;
                    finite(mode.stretch_energy(j)?)?;
                    finite(mode.effective_energy(mu0, j)?)?;
                }
                let rotor = SpringRotor::try_new(m, wv, r0)?;
                finite(rotor.rest_inverse_inertia())?;
                let mode = rotor.mode();
                finite_all(&[mode.dmu_dr(), mode.quartic_coefficient()])?;
                finite(rotor.energy(radius, pv, j)?)?;
                finite(rotor.stretched_radius(wj)?)?;
                finite(rotor.equilibrium_radius(j)?)?;
                finite(rotor.effective_energy(j)?)
            })
        }),
        family!(
            "semi_rigid: SemiRigidRotor (try_symmetric, try_from_radial_springs), radial_stretches",
            |g| {
                let arr = *g.rng.pick(&[
                    Arrangement::Octahedral,
                    Arrangement::Cubic,
                    Arrangement::Tetrahedral,
                ]);
                let basis = *g.rng.pick(&[QuarticBasis::Octahedral, QuarticBasis::Cubic]);
                let (m, wv, r0) = (g.positive(), g.positive(), g.positive());
                let j = g.vec();
                let elapsed = g.scalar();
                let n = 1 + g.rng.below(6);
                let pts: Vec<(T, gyrostat::Vec3<T>)> =
                    (0..n).map(|_| (g.positive(), g.vec())).collect();
                probe(&(arr, basis, m, wv, r0, j, elapsed, pts.clone()), || {
                    let mut out = [T::ZERO; 8];
                    if radial_stretches(&pts, wv, j, &mut out).is_ok() {
                        finite_all(&out[..n])?;
                    }
                    if let Ok(r) = SemiRigidRotor::try_from_radial_springs(&pts, wv) {
                        inertia_ok(&r.rest_inertia())?;
                    }
                    let r = SemiRigidRotor::try_symmetric(arr, m, wv, r0)?;
                    inertia_ok(&r.rest_inertia())?;
                    finite_all(&[r.t4(), r.isotropic(basis)])?;
                    let _ = r.try_body_hamiltonian(basis)?;
                    finite(r.energy(j)?)?;
                    unit(r.isotropic_turn(basis, j, elapsed)?)
                })
            }
        ),
    ]
}

#[test]
fn campaign() {
    run_campaign("dynamics", families::<f32>(), families::<f64>());
}
