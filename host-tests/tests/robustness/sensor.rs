//! The adversarial campaign over the sensor layer and the unequal-interval propagation: the
//! sample clocks, the calibrations, the axis remaps and mountings, clipping, the unequal
//! 2-sample update and Magnus-4 on unequal sample times.
//!
//! `cargo test --release -p host-tests --test robustness sensor:: -- --nocapture` prints the
//! table.

use gyrostat::propagation::coning::{two_sample_unequal_coefficient, two_sample_unequal_terms};
use gyrostat::propagation::kernels::{coning2_update_unequal, magnus4_step_unequal};
use gyrostat::sensor::timing::{micros_to_q30, micros_to_seconds};
use gyrostat::sensor::{
    AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration, Interval,
    MagnetometerCalibration, MicrosClock, Mounting, RawScale, SampleClock,
};
use gyrostat::step_limit::MAX_STEP_ANGLE;
use gyrostat::{Error, Vec3};
use host_tests::campaign::*;
use host_tests::family;
use host_tests::tolerance::Tolerance;

const REMAP_ALPHABET: &[u8] = b"xyzXYZ+-, w";

fn families<T: Tolerance>() -> Vec<Family<T>> {
    vec![
        family!("sensor::SampleClock: try_with_gap_factor, interval", |g| {
            // Half the time an ordinary clock with jitter, gaps, repeats and backwards steps.
            let n = 1 + g.rng.below(8);
            let (nominal, factor, ts) = if g.rng.chance(0.5) {
                let nominal = g.ordinary_dt();
                let factor = T::from_f64(1.0 + 9.0 * g.rng.unit());
                let mut t = g.scalar();
                let ts: Vec<T> = (0..n)
                    .map(|_| {
                        let k = *g.rng.pick(&[0.0, -0.5, 0.6, 1.0, 1.4, 3.0, 12.0]);
                        t += nominal * T::from_f64(k);
                        t
                    })
                    .collect();
                (nominal, factor, ts)
            } else {
                (g.scalar(), g.scalar(), (0..n).map(|_| g.scalar()).collect())
            };
            probe(&(nominal, factor, ts.clone()), || {
                let mut c = SampleClock::try_with_gap_factor(nominal, factor)?;
                let mut last_err = None;
                for t in &ts {
                    let before = c;
                    match c.interval(*t) {
                        Ok(Interval::Step(d)) => {
                            ensure(d.is_finite() && d > T::ZERO && d <= c.max_step(), || {
                                format!("step {d:?}")
                            })?
                        }
                        Ok(Interval::Gap(d)) => {
                            ensure(d.is_finite() && d > c.max_step(), || format!("gap {d:?}"))?
                        }
                        Ok(Interval::Backwards(d)) => {
                            ensure(d.is_finite() && d > T::ZERO && c == before, || {
                                format!("backwards {d:?}")
                            })?
                        }
                        Ok(Interval::Repeated) => {
                            ensure(c == before, || "repeated changed state".into())?
                        }
                        Ok(Interval::First) => {}
                        Err(e) => {
                            ensure(c == before, || {
                                "a rejected timestamp changed the state".into()
                            })?;
                            last_err = Some(e);
                        }
                    }
                }
                last_err.map_or(Ok(()), |e| Err(e.into()))
            })
        }),
        family!(
            "sensor::MicrosClock, micros_to_q30, micros_to_seconds",
            |g| {
                let (nom, k) = (
                    g.rng.next_u64() as u32 >> g.rng.below(32),
                    g.rng.next_u64() as u32 >> g.rng.below(32),
                );
                let ts: Vec<u32> = (0..1 + g.rng.below(8))
                    .map(|_| g.rng.next_u64() as u32)
                    .collect();
                probe(&(nom, k, ts.clone()), || {
                    for t in &ts {
                        let s: T = micros_to_seconds(*t);
                        finite(s)?;
                        match micros_to_q30(*t) {
                            Ok(q) => {
                                ensure(q.to_bits() > 0 || *t == 0, || "nonpositive step".into())?
                            }
                            Err(e) => ensure(e == Error::OutOfRange && *t >= 2_000_000, || {
                                format!("{e:?}")
                            })?,
                        }
                    }
                    let mut c = MicrosClock::try_new(nom, k)?;
                    for t in &ts {
                        if let Interval::Step(d) | Interval::Gap(d) = c.interval(*t) {
                            ensure(d > 0 && d < 1 << 31, || format!("{d}"))?;
                        }
                    }
                    Ok(())
                })
            }
        ),
        family!(
            "sensor::InertialCalibration: try_new, try_apply, apply_increment, raw_from_corrected",
            |g| {
                // Half the time a plausible calibration (near the identity, positive scales).
                let (m, s, b) = if g.rng.chance(0.5) {
                    let e = g.mat();
                    let small = if e.is_finite() && e.max_abs().to_f64() > 0.0 {
                        e.scale(T::from_f64(0.1 * g.rng.unit()) / e.max_abs())
                    } else {
                        gyrostat::Mat3::ZERO
                    };
                    let s = Vec3::new(g.rng.unit(), g.rng.unit(), g.rng.unit())
                        .to_array()
                        .map(|u| T::from_f64(0.5 + 1.5 * u));
                    (
                        gyrostat::Mat3::IDENTITY + small,
                        Vec3::from_array(s),
                        g.vec_within(1.0),
                    )
                } else {
                    (g.mat(), g.vec(), g.vec())
                };
                let v = g.vec();
                let dt = g.dt();
                probe(&(m, s, b, v, dt), || {
                    let c = InertialCalibration::try_new(m, s, b)?;
                    let inv = c.inverse_matrix();
                    ensure(inv.is_finite(), || "non-finite inverse".into())?;
                    let _ = c.apply_increment(v, dt);
                    let _ = c.raw_from_corrected(v);
                    let out = c.try_apply(v)?;
                    finite_vec(out)
                })
            }
        ),
        family!("sensor::MagnetometerCalibration: try_new, try_apply", |g| {
            let (m, h, v) = (g.mat(), g.vec(), g.vec());
            probe(&(m, h, v), || {
                let c = MagnetometerCalibration::try_new(m, h)?;
                let _ = c.raw_from_corrected(v);
                finite_vec(c.try_apply(v)?)
            })
        }),
        family!(
            "sensor::{AxisRemap: try_parse, apply, inverse, to_unit_quat; Mounting}",
            |g| {
                // Half the time three signed axes (a rotation, a reflection or a repeated axis).
                let text: String = if g.rng.chance(0.5) {
                    (0..3)
                        .map(|_| {
                            format!(
                                "{}{}",
                                g.rng.pick(&["", "-", "+"]),
                                g.rng.pick(&["x", "y", "z", "Y"])
                            )
                        })
                        .collect::<Vec<_>>()
                        .join(",")
                } else {
                    let len = g.rng.below(12);
                    (0..len)
                        .map(|_| *g.rng.pick(REMAP_ALPHABET) as char)
                        .collect()
                };
                let v = g.vec();
                let q = g.unit_quat();
                probe(&(text.clone(), v, q), || {
                    let r = AxisRemap::try_parse(&text)?;
                    let back = r.inverse().apply(r.apply(v));
                    ensure(
                        back.to_array()
                            .iter()
                            .zip(v.to_array())
                            .all(|(a, b)| a.to_f64().to_bits() == b.to_f64().to_bits()),
                        || "remap round trip not exact".into(),
                    )?;
                    let m: Mounting<T> = r.into();
                    unit(m.body_from_sensor())?;
                    unit(m.body_attitude(q))
                })
            }
        ),
        family!("sensor::{ClipGuard::filter (3 policies), RawScale}", |g| {
            let limit = if g.rng.chance(0.5) {
                i16::MAX - g.rng.below(20000) as i16
            } else {
                g.rng.next_u64() as u16 as i16
            };
            let policy = *g
                .rng
                .pick(&[ClipPolicy::Pass, ClipPolicy::HoldLast, ClipPolicy::Reject]);
            let raws: Vec<[i16; 3]> = (0..1 + g.rng.below(6))
                .map(|_| [0, 0, 0].map(|_: i16| g.rng.next_u64() as u16 as i16))
                .collect();
            let lsb = if g.rng.chance(0.5) {
                T::from_f64(1e-6 + g.rng.unit())
            } else {
                g.scalar()
            };
            probe(&(limit, policy, raws.clone(), lsb), || {
                let mut guard = ClipGuard::new(ClipLimit::try_new(limit)?, policy);
                for r in &raws {
                    match guard.filter(*r) {
                        Ok((_, flags)) => {
                            ensure(policy != ClipPolicy::Reject || !flags.any(), || {
                                "clipped passed Reject".into()
                            })?
                        }
                        Err(e) => {
                            ensure(e == Error::Clipped && policy == ClipPolicy::Reject, || {
                                format!("{e:?}")
                            })?
                        }
                    }
                }
                // The scale in T (the lsb, drawn in T, widened exactly).
                let l = lsb.to_f64();
                if T::INDEX == 0 {
                    let s = RawScale::<f32>::try_new(l)?;
                    raws.iter().try_for_each(|r| finite_vec(s.apply(*r)))
                } else {
                    let s = RawScale::<f64>::try_new(l)?;
                    raws.iter().try_for_each(|r| finite_vec(s.apply(*r)))
                }
            })
        }),
        family!(
            "unequal intervals: two_sample_unequal_{coefficient, terms}, coning2_update_unequal",
            |g| {
                let (h1, h2) = (g.ordinary_dt(), g.ordinary_dt());
                let (t1, t2) = (g.vec_within(MAX_STEP_ANGLE), g.vec_within(MAX_STEP_ANGLE));
                let q = g.unit_quat();
                probe(&(h1, h2, t1, t2, q), || {
                    let c = two_sample_unequal_coefficient(h1, h2);
                    finite(c)?;
                    finite_vec(two_sample_unequal_terms(t1, t2, c).rotation_vector())?;
                    unit(coning2_update_unequal(q, t1, t2, c))
                })
            }
        ),
        family!(
            "unequal intervals: magnus4_step_unequal (2, 3, 4 samples)",
            |g| {
                // Domain: increasing times, |ω|·h within the validity limit.
                let mut times = [T::ZERO; 4];
                let mut t = g.scalar();
                for slot in times.iter_mut() {
                    *slot = t;
                    t += g.ordinary_dt();
                }
                let h = times[3] - times[0];
                let bound = if h > T::ZERO {
                    MAX_STEP_ANGLE / h.to_f64() / 4.0
                } else {
                    0.0
                };
                let rates = [
                    g.vec_within(bound),
                    g.vec_within(bound),
                    g.vec_within(bound),
                    g.vec_within(bound),
                ];
                let q = g.unit_quat();
                probe(&(times, rates, q), || {
                    let distinct = times.windows(2).all(|w| w[1] > w[0])
                        && times.iter().all(|t| t.is_finite());
                    if !distinct {
                        return Err(Error::InvalidArgument.into());
                    }
                    unit(magnus4_step_unequal(
                        q,
                        &[times[0], times[1]],
                        &[rates[0], rates[1]],
                        times[0],
                        times[1],
                    ))?;
                    unit(magnus4_step_unequal(
                        q,
                        &[times[0], times[1], times[2]],
                        &[rates[0], rates[1], rates[2]],
                        times[1],
                        times[2],
                    ))?;
                    unit(magnus4_step_unequal(q, &times, &rates, times[0], times[1]))?;
                    unit(magnus4_step_unequal(q, &times, &rates, times[2], times[3]).renormalize())
                })
            }
        ),
    ]
}

#[test]
fn campaign() {
    run_campaign("sensor", families::<f32>(), families::<f64>());
}
