//! The adversarial campaign over the rotation and linear-algebra families (see
//! `host_tests::campaign` and `ROBUSTNESS.md`): constructors of every representation, the
//! conversions, Euler angles in all 24 conventions with every gimbal policy, the Euler rate and
//! Euler momentum matrices, the double-cover algebra, slerp and nlerp.
//!
//! `cargo test --release -p host-tests --test robustness rotation:: -- --nocapture` prints the
//! table; `GYROSTAT_CAMPAIGN_N=1000000 GYROSTAT_CAMPAIGN_WRITE=1` is the long setting that
//! writes it into `ROBUSTNESS.md`.

use gyrostat::rotation::{
    AxisAngle, Dcm, Euler, EulerSequence, Frame, Gibbs, GimbalPolicy, Mrp, PolarAxisAngle,
    RotationVector, Su2,
};
use gyrostat::{Axis, Complex, Quat, Real, UnitQuat};
use host_tests::campaign::*;
use host_tests::family;
use host_tests::tolerance::Tolerance;

/// The geodesic angle (rad, f64) between the rotations of two attitudes of any type.
fn angle64<T: Real>(a: UnitQuat<T>, b: UnitQuat<T>) -> f64 {
    let w = |q: UnitQuat<T>| {
        UnitQuat::try_new(Quat::from_array(q.to_array().map(|c| c.to_f64())))
            .unwrap_or(UnitQuat::IDENTITY)
    };
    w(a).angle_to(w(b))
}

/// Euler angles in their documented ranges: first and third in `(−π, π]`, middle in `[0, π]`
/// (proper) or `[−π/2, π/2]` (Tait–Bryan), each to a few ulp of π.
fn euler_ranges<T: Tolerance>(e: &Euler<T>) -> Check {
    let [a, b, c] = e.angles.map(|x| x.to_f64());
    finite_all(&e.angles)?;
    let pi = std::f64::consts::PI;
    let slack = 4.0 * T::EPSILON.to_f64() * pi;
    let (lo, hi) = if e.sequence.is_proper() {
        (0.0, pi)
    } else {
        (-pi / 2.0, pi / 2.0)
    };
    ensure(
        a.abs() <= pi + slack && c.abs() <= pi + slack && b >= lo - slack && b <= hi + slack,
        || {
            format!(
                "Euler angles {:?} outside their ranges for {}",
                e.angles, e.sequence
            )
        },
    )
}

fn families<T: Tolerance>() -> Vec<Family<T>> {
    vec![
        family!("Vec3::try_normalize", |g| {
            let v = g.vec();
            probe(&v, || {
                let n = v.try_normalize()?;
                finite_vec(n)?;
                let e = (n.norm().to_f64() - 1.0).abs();
                ensure(e <= unit_tolerance::<T>(), || {
                    format!("|n| − 1 = {e:e} for {n:?}")
                })
            })
        }),
        family!("Mat3::try_inverse", |g| {
            let m = g.mat();
            probe(&m, || finite_mat(&m.try_inverse()?))
        }),
        family!("Quat::try_inverse", |g| {
            let q = g.quat();
            probe(&q, || {
                let i = q.try_inverse()?;
                ensure(i.is_finite(), || format!("non-finite inverse {i:?}"))
            })
        }),
        family!("UnitQuat::try_new, Quat::try_normalize", |g| {
            let q = g.quat();
            probe(&q, || {
                unit(UnitQuat::try_new(q)?)?;
                unit(q.try_normalize()?)
            })
        }),
        family!("UnitQuat::try_from_near_unit", |g| {
            let q = g.quat();
            let tol = match g.rng.below(4) {
                0 => g.scalar(),
                _ => T::from_f64(g.magnitude_in(g.lim.eps, 0.5)),
            };
            probe(&(q, tol), || unit(UnitQuat::try_from_near_unit(q, tol)?))
        }),
        family!("UnitQuat::try_from_axis_angle", |g| {
            let (axis, angle) = (g.vec(), g.scalar());
            probe(&(axis, angle), || {
                unit(UnitQuat::try_from_axis_angle(axis, angle)?)
            })
        }),
        family!("UnitQuat::try_exp, log, angle", |g| {
            let v = g.vec();
            probe(&v, || {
                let q = UnitQuat::try_exp(v)?;
                unit(q)?;
                finite_vec(q.log())?;
                finite(q.angle())
            })
        }),
        family!(
            "UnitQuat algebra (product, inverse, rotate, matrix, renormalize, canonical, angle_to, similarity)",
            |g| {
                let (a, b) = g.unit_quat_pair();
                let v = g.vec_within(g.lim.sqrt_max / 4.0);
                probe(&(a, b, v), || {
                    unit(a * b)?;
                    unit(a.inverse())?;
                    unit(-a)?;
                    unit(a.renormalize())?;
                    unit(a.renormalize_fast())?;
                    unit(a.canonical())?;
                    unit(a.closest_sign_to(b))?;
                    unit(a.similarity_transform(b))?;
                    finite_vec(a.rotate(v))?;
                    finite_vec(a.inverse_rotate(v))?;
                    finite_vec(a * v)?;
                    rotation_within(&a.to_rotation_matrix(), unit_tolerance::<T>() * 4.0)?;
                    finite(a.angle_to(b))?;
                    finite(a.dot(b))?;
                    let _ = a.same_rotation(b, T::EPSILON);
                    Ok(())
                })
            }
        ),
        family!("UnitQuat::slerp, nlerp", |g| {
            let (a, b) = g.unit_quat_pair();
            let t = match g.rng.below(3) {
                0 => g.uniform(0.0, 1.0),
                _ => g.finite(),
            };
            probe(&(a, b, t), || {
                unit(a.slerp(b, t))?;
                unit(a.nlerp(b, t))
            })
        }),
        family!("Su2::try_new and its algebra", |g| {
            let q = g.quat();
            let (a, b) = (Complex::new(q.w, q.x), Complex::new(q.y, q.z));
            let v = g.vec_within(g.lim.sqrt_max / 4.0);
            let other = Su2::from(g.unit_quat());
            probe(&(a, b, v), || {
                let u = Su2::try_new(a, b)?;
                unit(UnitQuat::from(u))?;
                unit(UnitQuat::from(u * other))?;
                unit(UnitQuat::from(u.inverse()))?;
                unit(UnitQuat::from(-u))?;
                finite_vec(u.rotate(v))?;
                let m = u.matrix();
                ensure(
                    m.iter()
                        .flatten()
                        .all(|c| c.re.is_finite() && c.im.is_finite()),
                    || format!("non-finite SU(2) matrix {m:?}"),
                )
            })
        }),
        family!("Dcm::try_from_matrix", |g| {
            let m = g.mat();
            let tol = match g.rng.below(4) {
                0 => g.scalar(),
                1 => Dcm::<T>::default_tolerance(),
                _ => T::from_f64(g.magnitude_in(g.lim.eps, 0.99)),
            };
            probe(&(m, tol), || {
                let d = Dcm::try_from_matrix(m, tol)?;
                // The library measures ‖mᵀm − 1‖ in T: each entry of mᵀm is a three-term sum of
                // products of entries ≤ 1 in magnitude, rounded at most 3 times by ½ ulp of a value
                // near 1 (plus the subtraction of 1): 2 ε covers that rounding.
                rotation_within(d.matrix(), tol.to_f64() + 2.0 * T::EPSILON.to_f64())?;
                unit(d.to_unit_quat())
            })
        }),
        family!("Dcm::try_from_matrix_orthonormalized", |g| {
            let m = g.mat();
            probe(&m, || {
                let d = Dcm::try_from_matrix_orthonormalized(m)?;
                rotation(&d)?;
                unit(d.to_unit_quat())
            })
        }),
        family!("Dcm from and to UnitQuat, product, rotate", |g| {
            let (a, b) = g.unit_quat_pair();
            let v = g.vec_within(g.lim.sqrt_max / 4.0);
            probe(&(a, b, v), || {
                let (da, db) = (Dcm::from(a), Dcm::from(b));
                rotation(&da)?;
                rotation(&(da * db))?;
                rotation(&da.inverse())?;
                unit(da.to_unit_quat())?;
                unit(UnitQuat::from(da * db))?;
                finite_vec(da.rotate(v))?;
                let back = angle64(UnitQuat::from(da), a);
                ensure(back <= T::CONTRACT * 4.0, || {
                    format!("quaternion → matrix → quaternion is {back:e} rad off")
                })
            })
        }),
        family!(
            "AxisAngle::try_new, to_unit_quat, to_rotation_vector",
            |g| {
                let (axis, angle) = (g.vec(), g.scalar());
                probe(&(axis, angle), || {
                    let a = AxisAngle::try_new(axis, angle)?;
                    let e = (a.axis().norm().to_f64() - 1.0).abs();
                    ensure(e <= unit_tolerance::<T>(), || {
                        format!("axis {:?} not unit", a.axis())
                    })?;
                    unit(a.to_unit_quat())?;
                    finite_vec(a.to_rotation_vector().vector())
                })
            }
        ),
        family!("AxisAngle from UnitQuat (SO(3) and spinor)", |g| {
            let q = g.unit_quat();
            probe(&q, || {
                for a in [AxisAngle::from(q), AxisAngle::from_unit_quat(q)] {
                    finite_vec(a.axis())?;
                    finite(a.angle())?;
                    let e = (a.axis().norm().to_f64() - 1.0).abs();
                    ensure(e <= unit_tolerance::<T>(), || {
                        format!("axis {:?} not unit", a.axis())
                    })?;
                    unit(a.to_unit_quat())?;
                }
                let back = angle64(AxisAngle::from(q).to_unit_quat(), q);
                ensure(back <= T::CONTRACT * 4.0, || {
                    format!("quaternion → axis-angle → quaternion is {back:e} rad off")
                })
            })
        }),
        family!("PolarAxisAngle to and from UnitQuat and Su2", |g| {
            let p = PolarAxisAngle::new(g.scalar(), g.scalar(), g.scalar());
            let q = g.unit_quat();
            probe(&(p, q), || {
                let back = PolarAxisAngle::from(q);
                finite_all(&[back.phi, back.theta, back.angle])?;
                unit(back.try_to_unit_quat()?)?;
                let u = p.try_to_su2()?;
                unit(UnitQuat::from(u))?;
                unit(p.try_to_unit_quat()?)
            })
        }),
        family!("RotationVector::try_new, to and from UnitQuat", |g| {
            let v = g.vec();
            let q = g.unit_quat();
            probe(&(v, q), || {
                let back = RotationVector::from(q);
                finite_vec(back.vector())?;
                finite(back.angle())?;
                let r = RotationVector::try_new(v)?;
                finite(r.angle())?;
                unit(r.to_unit_quat())
            })
        }),
        family!(
            "Mrp::try_new, try_shadow, switched, to and from UnitQuat",
            |g| {
                let v = g.vec();
                let q = g.unit_quat();
                probe(&(v, q), || {
                    let back = Mrp::from(q);
                    finite_vec(back.vector())?;
                    ensure(
                        back.vector().norm().to_f64() <= 1.0 + 4.0 * T::EPSILON.to_f64(),
                        || format!("MRP {back:?} of {q:?} has |σ| > 1"),
                    )?;
                    let m = Mrp::try_new(v)?;
                    finite_vec(m.switched().vector())?;
                    unit(m.to_unit_quat())?;
                    let s = m.try_shadow()?;
                    finite_vec(s.vector())?;
                    unit(s.to_unit_quat())
                })
            }
        ),
        family!("Gibbs::try_new, try_from_unit_quat, to_unit_quat", |g| {
            let v = g.vec();
            let q = g.unit_quat();
            probe(&(v, q), || {
                unit(Gibbs::try_new(v)?.to_unit_quat())?;
                let gq = Gibbs::try_from_unit_quat(q)?;
                finite_vec(gq.vector())?;
                unit(gq.to_unit_quat())
            })
        }),
        family!(
            "Euler::try_to_unit_quat, Dcm::try_from(Euler) (24 conventions)",
            |g| {
                let seq = g.sequence();
                let e = Euler::new(seq, g.euler_angles(seq));
                probe(&e, || {
                    let q = e.try_to_unit_quat()?;
                    unit(q)?;
                    rotation(&Dcm::try_from(e)?)
                })
            }
        ),
        family!(
            "UnitQuat::to_euler (24 conventions × ZeroFirst, ZeroThird, ClosestTo)",
            |g| {
                let (q, seq) = if g.rng.chance(0.4) {
                    g.pole_attitude()
                } else {
                    (g.unit_quat(), g.sequence())
                };
                let policy = match g.rng.below(4) {
                    0 => GimbalPolicy::ZeroFirst,
                    1 => GimbalPolicy::ZeroThird,
                    2 => GimbalPolicy::ClosestTo(g.euler_angles(seq)),
                    _ => GimbalPolicy::ClosestTo([g.finite(), g.finite(), g.finite()]),
                };
                probe(&(q, seq, policy), || {
                    let sol = q.to_euler(seq, policy);
                    euler_ranges(&sol.euler)?;
                    finite(sol.distance_to_pole)?;
                    if let Some(lock) = sol.singularity {
                        finite_all(&[lock.sign, lock.combined_angle, lock.distance_to_pole])?;
                    }
                    // The angles encode the input rotation (checked in f64, as an effect).
                    let angles = sol.euler.angles.map(|a| a.to_f64());
                    let back = Euler::new(seq, angles).to_unit_quat_unchecked();
                    let w = UnitQuat::try_new(Quat::from_array(q.to_array().map(|c| c.to_f64())))
                        .unwrap_or(UnitQuat::IDENTITY);
                    let err = back.angle_to(w);
                    ensure(err <= T::CONTRACT, || {
                        format!("angles {angles:?} encode a rotation {err:e} rad from the input")
                    })
                })
            }
        ),
        family!("EulerSequence::try_from_str, try_new", |g| {
            let letters = ['X', 'Y', 'Z', 'x', 'y', 'z', 'q', '1', ' ', 'é'];
            let len = g.rng.below(5);
            let s: String = (0..len).map(|_| *g.rng.pick(&letters)).collect();
            let axes = [
                *g.rng.pick(&Axis::ALL),
                *g.rng.pick(&Axis::ALL),
                *g.rng.pick(&Axis::ALL),
            ];
            let frame = *g.rng.pick(&[Frame::Intrinsic, Frame::Extrinsic]);
            probe(&(s.clone(), axes), || {
                if let Ok(seq) = EulerSequence::try_from_str(&s) {
                    ensure(seq.to_string() == s, || format!("{s:?} parsed as {seq}"))?;
                }
                let seq = EulerSequence::try_new(axes[0], axes[1], axes[2], frame)?;
                ensure(seq.axes() == axes, || format!("{seq} from {axes:?}"))
            })
        }),
        family!(
            "Euler rate matrices (E_body, E_lab and their inverses, rates from ω)",
            |g| {
                let seq = g.sequence();
                let e = Euler::new(seq, g.euler_angles(seq));
                let w = g.vec();
                probe(&(e, w), || {
                    let finite_angles = e.angles.iter().all(|a| a.is_finite());
                    if finite_angles {
                        finite_mat(&e.rates_to_body_matrix())?;
                        finite_mat(&e.rates_to_lab_matrix())?;
                    }
                    finite_mat(&e.try_body_to_rates_matrix()?)?;
                    finite_mat(&e.try_lab_to_rates_matrix()?)?;
                    finite_all(&e.try_rates_from_body(w)?)?;
                    finite_all(&e.try_rates_from_lab(w)?)
                })
            }
        ),
        family!(
            "Euler momenta maps (to and from body and lab momentum)",
            |g| {
                let seq = g.sequence();
                let e = Euler::new(seq, g.euler_angles(seq));
                let j = g.vec();
                let p = [g.scalar(), g.scalar(), g.scalar()];
                probe(&(e, j, p), || {
                    if e.angles.iter().all(|a| a.is_finite()) {
                        finite_mat(&e.body_to_euler_momenta_matrix())?;
                        finite_mat(&e.lab_to_euler_momenta_matrix())?;
                    }
                    finite_mat(&e.try_euler_momenta_to_body_matrix()?)?;
                    finite_mat(&e.try_euler_momenta_to_lab_matrix()?)?;
                    finite_all(&e.try_euler_momenta_from_body(j)?)?;
                    finite_all(&e.try_euler_momenta_from_lab(j)?)?;
                    finite_vec(e.try_body_momentum_from_euler_momenta(p)?)?;
                    finite_vec(e.try_lab_momentum_from_euler_momenta(p)?)
                })
            }
        ),
        family!("interop: mint and nalgebra conversions", |g| {
            let q = g.quat();
            let u = g.unit_quat();
            let v = g.vec();
            probe(&(q, u, v), || {
                let m: mint::Quaternion<T> = q.into();
                let na: nalgebra::UnitQuaternion<T> = u.into();
                unit(UnitQuat::from(na))?;
                let back: gyrostat::Vec3<T> = nalgebra::Vector3::from(v).into();
                ensure(back == v || !v.is_finite(), || format!("{v:?} -> {back:?}"))?;
                unit(UnitQuat::try_from(m)?)
            })
        }),
    ]
}

#[test]
fn campaign() {
    run_campaign("rotation", families::<f32>(), families::<f64>());
}
