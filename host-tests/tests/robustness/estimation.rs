//! The adversarial campaign over the attitude estimator (issue 29): streams of updates, each
//! stream one input, in six families — garbage bursts, extreme rate × step products, subnormal
//! and huge steps, fields near the vertical, slow steady turns, long disturbances — with the
//! properties checked after every `Ok`:
//!
//! - a finite unit attitude (32 ε, [`unit`]) and a finite bias within its clip
//!   ([`Params::gyro_bias_max`]);
//! - the covariance symmetric and positive semi-definite ([`covariance_ok`]);
//!
//! and, where the stream ends with good data (bursts, slow turns and disturbances):
//!
//! - good accelerometer data used again within [`USED_AGAIN`] s after the garbage or the
//!   disturbance ends (the inertial low-pass, τ = 3 s, forgets a residual of up to
//!   16 g·√3 + g to 0.2 g in 3 s·ln(144) = 14.9 s);
//! - after a garbage burst (default parameters, the online magnetometer-delay estimate on) and
//!   during a slow steady turn (0.01 … 3.5 °/s, about any axis or the vertical: slower than
//!   the largest bias, it is not rest), the attitude error below [`TILT_BACK`] in inclination
//!   and [`TOTAL_BACK`] in all [`GOOD_AFTER`] s after the garbage ends (after 2 s of the turn).
//!   After a long disturbance the error is not bounded (open, ROBUSTNESS.md).
//!
//! An input is one stream of about [`UPDATES`] updates or more; the campaign runs
//! `GYROSTAT_CAMPAIGN_N / UPDATES` streams per family and type, so that its setting counts
//! calls as the other campaigns do. `cargo test --release -p host-tests --test robustness
//! estimation:: -- --nocapture` prints the table.

use gyrostat::estimation::{Estimator, Gains, Params, SensorUse};
use gyrostat::{Real, UnitQuat, Vec3};
use host_tests::campaign::*;
use host_tests::family;
use host_tests::tolerance::Tolerance;

/// The nominal number of updates per stream (the campaign's divisor).
const UPDATES: u64 = 100;
/// Good accelerometer data is used again within this time (s) after garbage or a disturbance.
const USED_AGAIN: f64 = 16.0;
/// Good data after the garbage or the disturbance (s).
const GOOD_AFTER: f64 = 40.0;
/// The inclination error bound (rad) at the end of the good data.
const TILT_BACK: f64 = 2.0 * std::f64::consts::PI / 180.0;
/// The total attitude error bound (rad) at the end of the good data.
const TOTAL_BACK: f64 = 10.0 * std::f64::consts::PI / 180.0;

const UP: [f64; 3] = [0.0, 0.0, 9.81];
const FIELD: [f64; 3] = [0.0, 15.8, -40.7];

type Q = [f64; 4];

fn qmul(a: Q, b: Q) -> Q {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// `q* v q`: an earth-frame vector in the sensor frame.
fn to_sensor(q: Q, v: [f64; 3]) -> [f64; 3] {
    let r = qmul(
        qmul([q[0], -q[1], -q[2], -q[3]], [0.0, v[0], v[1], v[2]]),
        q,
    );
    [r[1], r[2], r[3]]
}

/// `q v q*`: a sensor-frame vector in the earth frame.
fn to_earth(q: Q, v: [f64; 3]) -> [f64; 3] {
    let r = qmul(
        qmul(q, [0.0, v[0], v[1], v[2]]),
        [q[0], -q[1], -q[2], -q[3]],
    );
    [r[1], r[2], r[3]]
}

fn exp(p: [f64; 3]) -> Q {
    let t = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if t == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    let s = (t / 2.0).sin() / t;
    [(t / 2.0).cos(), s * p[0], s * p[1], s * p[2]]
}

fn normalize(q: Q) -> Q {
    let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    q.map(|c| c / n)
}

fn v<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]))
}

/// The total angle (rad) and the inclination error (rad: the angle between the estimated and
/// the true earth vertical in the sensor frame) of an estimate.
fn errors<T: Real>(est: UnitQuat<T>, truth: Q) -> (f64, f64) {
    let e = est.into_quat().to_array().map(|c| c.to_f64());
    let d = qmul([e[0], -e[1], -e[2], -e[3]], truth);
    let s = (d[1] * d[1] + d[2] * d[2] + d[3] * d[3]).sqrt();
    let total = 2.0 * s.atan2(d[0].abs());
    let a = to_sensor(normalize(e), [0.0, 0.0, 1.0]);
    let b = to_sensor(truth, [0.0, 0.0, 1.0]);
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let tilt = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
        .sqrt()
        .atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    (total, tilt)
}

thread_local! {

    /// With `GYROSTAT_ESTIMATION_PROPERTIES=1`: the properties the current stream broke (bits:
    /// 1 attitude, 2 bias, 4 covariance finite and PSD, 8 used again, 16 error bound, 32
    /// covariance exactly symmetric, 64 TRIAD's gravity), each counted instead
    /// of ending the stream, printed per stream (`properties FAMILY TYPE BITS` on stderr) to
    /// count the streams that break each property (ROBUSTNESS.md's before/after table).
    static BROKEN: std::cell::Cell<u8> = const { std::cell::Cell::new(0) };
}

/// Counting mode (see [`BROKEN`]).
fn counting() -> bool {
    std::env::var("GYROSTAT_ESTIMATION_PROPERTIES").as_deref() == Ok("1")
}

/// `check` as it is, or in counting mode recorded under `bit` and passed.
fn property(bit: u8, check: Check) -> Check {
    if counting() && check.is_err() {
        BROKEN.with(|b| b.set(b.get() | bit));
        return Ok(());
    }
    check
}

/// Runs one stream; in counting mode prints the properties it broke.
fn stream<T: Tolerance>(name: &str, f: impl FnOnce() -> Check) -> Check {
    BROKEN.with(|b| b.set(0));
    let r = f();
    if counting() {
        eprintln!("properties {name} {} {}", T::NAME, BROKEN.with(|b| b.get()));
    }
    r
}

/// The state's contract after an `Ok`.
fn state_ok<T: Tolerance>(f: &Estimator<T>) -> Check {
    property(1, unit(f.attitude()))?;
    let m = f.params().gyro_bias_max.to_f64();
    let b = f.bias().to_array().map(|c| c.to_f64());
    property(
        2,
        ensure(b.iter().all(|c| c.is_finite() && c.abs() <= m), || {
            format!("bias {b:?} beyond ±{m}")
        }),
    )?;
    if !counting() {
        return covariance_ok(f.covariance());
    }
    // Counted apart: finite and positive semi-definite (4), exactly symmetric (32).
    let p = f.covariance();
    let m = covariance_dense(p);
    let psd =
        m.iter().flatten().all(|x| x.is_finite()) && psd_within(&m, 64.0 * T::EPSILON.to_f64());
    property(4, ensure(psd, || format!("covariance {m:?}")))?;
    let sym = (0..3).all(|i| {
        (0..3).all(|j| p.attitude.m[i][j] == p.attitude.m[j][i] && p.bias.m[i][j] == p.bias.m[j][i])
    });
    property(32, ensure(sym, || format!("asymmetric covariance {m:?}")))
}

/// The parameters of a stream: the defaults, or (when `wild`) one of unbounded ranges, fixed
/// gains, no delay estimation, a zero bias clip.
fn params<T: Tolerance>(g: &mut Gen<T>, wild: bool) -> Params<T> {
    let mut p = Params::<T>::default();
    if wild {
        match g.rng.below(5) {
            0 => {
                p.gyro_range = T::from_f64(f64::INFINITY);
                p.accel_range = T::from_f64(f64::INFINITY);
            }
            1 => {
                p.gains = Gains::Fixed {
                    heading_time_constant: T::from_f64(9.0),
                }
            }
            2 => p.mag_delay_estimation_time = T::ZERO,
            3 => p.gyro_bias_max = T::ZERO,
            _ => {}
        }
    }
    p
}

/// A true motion: a random start attitude, at rest or turning at a constant body rate.
struct Truth {
    q: Q,
    w: [f64; 3],
}

impl Truth {
    fn new<T: Tolerance>(g: &mut Gen<T>, max_rate: f64) -> Self {
        let q = g.unit_quat_f64();
        let w = if g.rng.chance(0.5) {
            [0.0; 3]
        } else {
            [0, 1, 2].map(|_| g.rng.range(-max_rate, max_rate))
        };
        Truth { q, w }
    }
    fn advance(&mut self, dt: f64) {
        self.q = normalize(qmul(self.q, exp(self.w.map(|c| c * dt))));
    }
    fn accel(&self) -> [f64; 3] {
        to_sensor(self.q, UP)
    }
    fn mag(&self) -> [f64; 3] {
        to_sensor(self.q, FIELD)
    }
}

/// One good sample over `dt`: the truth advances, the estimator is fed the exact sensors.
fn good<T: Tolerance>(f: &mut Estimator<T>, tr: &mut Truth, dt: f64) -> Result<SensorUse, Fail> {
    tr.advance(dt);
    let o = f.update_9d(v(tr.w), v(tr.accel()), v(tr.mag()), T::from_f64(dt))?;
    state_ok(f)?;
    Ok(o.accel)
}

/// Good data for [`GOOD_AFTER`] s at 20 Hz after garbage or a disturbance: the accelerometer is
/// used again within [`USED_AGAIN`] s and the error is back within its bounds at the end.
fn recovery<T: Tolerance>(
    f: &mut Estimator<T>,
    tr: &mut Truth,
    what: &str,
    error_bound: bool,
) -> Check {
    let dt = 0.05;
    let mut used_at = None;
    let steps = (GOOD_AFTER / dt) as usize;
    for k in 1..=steps {
        if good(f, tr, dt)? == SensorUse::Used && used_at.is_none() {
            used_at = Some(k as f64 * dt);
        }
    }
    let used = used_at.unwrap_or(f64::INFINITY);
    property(
        8,
        ensure(used <= USED_AGAIN, || {
            format!("{what}: good accelerometer data used again only after {used} s")
        }),
    )?;
    if !error_bound {
        return Ok(());
    }
    let (total, tilt) = errors(f.attitude(), tr.q);
    property(
        16,
        ensure(tilt <= TILT_BACK && total <= TOTAL_BACK, || {
            format!(
                "{what}: error {:.3}° (inclination {:.3}°) {GOOD_AFTER} s after",
                total.to_degrees(),
                tilt.to_degrees()
            )
        }),
    )
}

/// Garbage as a bus error or a dead sensor gives it: a vector with a NaN or ±∞ component, or
/// components beyond every sensor's range (1e3 … MAX), or (`tiny`) all zero or subnormal.
/// Garbage within a sensor's range cannot be told from motion, and a zero or subnormal rate is
/// within the gyroscope's (a dead gyroscope reading 0 over a long step while the sensor turns:
/// the error it leaves decays at the filter's steady-state rate, see the open findings); the
/// extreme families cover such values (every property but recovery).
fn garbage<T: Tolerance>(g: &mut Gen<T>, tiny: bool) -> Vec3<T> {
    let mut c = || -> f64 {
        match g.rng.below(6) {
            0 => *g.rng.pick(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY]),
            1 if tiny => g.rng.sign() * g.magnitude_in(g.lim.min_subnormal, g.lim.min_positive),
            _ => g.rng.sign() * g.magnitude_in(1e3, g.lim.max),
        }
    };
    let a = [c(), c(), c()];
    if tiny && g.rng.chance(0.1) {
        return Vec3::ZERO;
    }
    v(a)
}

/// Any update's result: an `Ok` must leave a valid state; an error is typed (fine).
fn any_update<T: Tolerance>(
    f: &mut Estimator<T>,
    gyro: Vec3<T>,
    accel: Vec3<T>,
    mag: Option<Vec3<T>>,
    dt: T,
) -> Check {
    match f.update(gyro, accel, mag, dt) {
        Ok(_) => state_ok(f),
        Err(_) => Ok(()),
    }
}

/// One garbage-burst stream: 2 s of good data at 20 Hz from the attitude `q` turning at `w`,
/// `burst` garbage rows drawn from `seed`, then [`recovery`] with its error bound.
fn garbage_burst<T: Tolerance>(q: Q, w: [f64; 3], burst: usize, seed: u64, p: Params<T>) -> Check {
    let mut tr = Truth { q, w };
    let mut f = Estimator::try_new(p)?;
    let mut g = Gen::<T>::new(seed);
    for _ in 0..40 {
        good(&mut f, &mut tr, 0.05)?;
    }
    for _ in 0..burst {
        let dt = if g.rng.chance(0.8) {
            g.ordinary_dt()
        } else {
            g.dt()
        };
        let gyro = garbage(&mut g, false);
        let accel = garbage(&mut g, true);
        let mag = garbage(&mut g, true);
        if f.update_9d(gyro, accel, mag, dt).is_ok() {
            state_ok(&f)?;
            tr.advance(dt.to_f64());
        }
    }
    recovery(&mut f, &mut tr, "after the burst", true)
}

/// One long-disturbance stream: 2 s of good data at 20 Hz from the attitude `q` turning at
/// `w`, `length` s of disturbance `kind` (0: a magnet on the sensor, a constant sensor-frame
/// field `40·size·dir` added; 1: another homogeneous field; 2: a sustained push, an earth-frame
/// specific force `size·dir` added), then [`recovery`], with its error bound when `error_bound`
/// (the family has none: an open finding, ROBUSTNESS.md: a bias learned during a sustained push
/// while the sensor turns).
fn long_disturbance<T: Tolerance>(
    q: Q,
    w: [f64; 3],
    kind: usize,
    length: f64,
    size: f64,
    dir: [f64; 3],
    error_bound: bool,
) -> Check {
    let mut tr = Truth { q, w };
    let mut f = Estimator::try_new(Params::<T>::default())?;
    for _ in 0..40 {
        good(&mut f, &mut tr, 0.05)?;
    }
    let dt = 0.05;
    for _ in 0..(length / dt) as usize {
        tr.advance(dt);
        let (mut a, mut m) = (tr.accel(), tr.mag());
        match kind {
            0 => m = [0, 1, 2].map(|i| m[i] + size * 40.0 * dir[i]),
            1 => {
                let e = [FIELD[0] + size * 10.0 * dir[0], FIELD[1] * size, FIELD[2]];
                m = to_sensor(tr.q, e);
            }
            _ => {
                let push = to_sensor(tr.q, dir.map(|c| c * size));
                a = [0, 1, 2].map(|i| a[i] + push[i]);
            }
        }
        f.update_9d(v(tr.w), v(a), v(m), T::from_f64(dt))?;
        state_ok(&f)?;
    }
    recovery(
        &mut f,
        &mut tr,
        &format!("after the disturbance (kind {kind})"),
        error_bound,
    )
}

fn families<T: Tolerance>() -> Vec<Family<T>> {
    vec![
        family!("estimation: garbage bursts", |g| {
            let tr = Truth::new(g, 0.5);
            let burst = 1 + g.rng.below(100);
            let seed = g.rng.next_u64();
            probe(&(tr.q, tr.w, burst, seed), || {
                stream::<T>("garbage-bursts", || {
                    garbage_burst::<T>(tr.q, tr.w, burst, seed, Params::default())
                })
            })
        }),
        family!("estimation: extreme rate × step", |g| {
            let p = params(g, true);
            let mut tr = Truth::new(g, 1.0);
            let seed = g.rng.next_u64();
            probe(&(tr.q, seed), || {
                stream::<T>("extreme-rate-x-step", || {
                    let mut f = Estimator::try_new(p)?;
                    let mut g = Gen::<T>::new(seed);
                    good(&mut f, &mut tr, 0.01)?;
                    for _ in 0..UPDATES {
                        // |ω|·Δt up to just past π, Δt anywhere from subnormal to 1000 s.
                        let pi = std::f64::consts::PI;
                        let theta = *g.rng.pick(&[0.0, 1e-7, 0.01, 1.0, 3.0, pi, 3.2]);
                        let theta = theta * g.rng.range(0.5, 1.0);
                        let dt = g.magnitude_in(g.lim.min_subnormal, 1000.0);
                        let d = g.finite_vec().to_array().map(|c| c.to_f64());
                        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                        let w = if n.is_finite() && n > 0.0 {
                            d.map(|c| c / n * theta / dt)
                        } else {
                            [theta / dt, 0.0, 0.0]
                        };
                        let (a, m) = if g.rng.chance(0.7) {
                            (v(tr.accel()), Some(v(tr.mag())))
                        } else {
                            (g.vec(), g.rng.chance(0.5).then(|| g.vec()))
                        };
                        any_update(&mut f, v(w), a, m, T::from_f64(dt))?;
                    }
                    Ok(())
                })
            })
        }),
        family!("estimation: subnormal and huge steps", |g| {
            let p = params(g, true);
            let mut tr = Truth::new(g, 1.0);
            let seed = g.rng.next_u64();
            probe(&(tr.q, seed), || {
                stream::<T>("subnormal-and-huge-steps", || {
                    let mut f = Estimator::try_new(p)?;
                    let mut g = Gen::<T>::new(seed);
                    good(&mut f, &mut tr, 0.01)?;
                    for _ in 0..UPDATES {
                        let dt = match g.rng.below(10) {
                            0..=3 => g.magnitude_in(g.lim.min_subnormal, 1e-20),
                            4..=6 => g.magnitude_in(1.0, 1000.0),
                            7 => g.magnitude_in(1000.0, g.lim.max),
                            _ => g.dt().to_f64(),
                        };
                        let gyro = if g.rng.chance(0.8) {
                            v(tr.w)
                        } else {
                            g.finite_vec()
                        };
                        any_update(
                            &mut f,
                            gyro,
                            v(tr.accel()),
                            Some(v(tr.mag())),
                            T::from_f64(dt),
                        )?;
                        if dt.is_finite() && dt > 0.0 && dt <= 1000.0 {
                            tr.advance(dt);
                        }
                    }
                    Ok(())
                })
            })
        }),
        family!("estimation: fields near the vertical", |g| {
            let p = params(g, true);
            let tr = Truth::new(g, 0.0);
            let seed = g.rng.next_u64();
            probe(&(tr.q, seed), || {
                stream::<T>("fields-near-the-vertical", || {
                    let mut f = Estimator::try_new(p)?;
                    let mut g = Gen::<T>::new(seed);
                    let eps = T::EPSILON.to_f64();
                    for k in 0..UPDATES {
                        // The field within 10⁻⁹ … 10⁻¹ rad of the vertical (up or down).
                        let a = g.magnitude_in(1e-9, 0.1);
                        let ph = g.rng.range(0.0, std::f64::consts::TAU);
                        let s = g.rng.sign();
                        let earth = [a.sin() * ph.cos(), a.sin() * ph.sin(), s * a.cos()]
                            .map(|c| c * g.magnitude_in(1.0, 100.0));
                        let acc = tr.accel();
                        let o = f.update_9d(
                            v(tr.w),
                            v(acc),
                            v(to_sensor(tr.q, earth)),
                            T::from_f64(0.01),
                        )?;
                        state_ok(&f)?;
                        if k == 0 && o.initialized {
                            // TRIAD: gravity is the exact direction.
                            let q = f.attitude().into_quat().to_array().map(|c| c.to_f64());
                            let up = to_earth(normalize(q), acc.map(|c| c / 9.81));
                            let tilt = up[0].hypot(up[1]).atan2(up[2]);
                            property(
                                64,
                                ensure(tilt <= 16.0 * eps, || {
                                    format!(
                                        "TRIAD tilts gravity by {tilt:e} rad (field {a:e} rad from the vertical)"
                                    )
                                }),
                            )?;
                        }
                    }
                    Ok(())
                })
            })
        }),
        family!("estimation: slow steady turns", |g| {
            let q = g.unit_quat_f64();
            let vertical = g.rng.chance(0.5);
            let d = if vertical {
                to_sensor(q, [0.0, 0.0, 1.0])
            } else {
                [0, 1, 2].map(|_| g.rng.range(-1.0, 1.0))
            };
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-300);
            // 0.01 … 3.5 °/s, log-uniform: below and just above the largest bias (2 °/s a
            // component).
            let rate = g.magnitude_in(0.01, 3.5).to_radians();
            let w = d.map(|c| c / n * rate);
            probe(&(q, w), || {
                stream::<T>("slow-steady-turns", || {
                    garbage_burst::<T>(q, w, 0, 0, Params::default())
                })
            })
        }),
        family!("estimation: long disturbances", |g| {
            let tr = Truth::new(g, 0.5);
            let kind = g.rng.below(3);
            let length = g.rng.range(5.0, 60.0);
            let size = g.rng.range(0.5, 5.0);
            let dir = [0, 1, 2].map(|_| g.rng.range(-1.0, 1.0));
            probe(&(tr.q, tr.w, kind, length, size, dir), || {
                stream::<T>("long-disturbances", || {
                    long_disturbance::<T>(tr.q, tr.w, kind, length, size, dir, false)
                })
            })
        }),
    ]
}

#[test]
fn campaign() {
    run_stream_campaign("estimation", UPDATES, families::<f32>(), families::<f64>());
}

/// The garbage-burst stream the long setting found (f32, 1 of 10 000; the same stream fails in
/// f64 and without its 57 garbage rows): the sensor turns steadily at 2.5 °/s, every component
/// below the rest detector's largest bias (2 °/s), so the detector took the turn for rest from
/// the first 1.5 s on and the rest updates set the bias to the turn rate with a variance of
/// (0.03 °/s)²; the attitude then stood still while the sensor turned, and the accelerometer's
/// slow gain left the inclination 30.6° off 40 s after the burst.
#[test]
fn garbage_burst_slow_turn_taken_for_rest_f32() {
    let q = [
        -0.6811197291144029,
        0.2270747495999903,
        -0.4508781920931787,
        -0.5303035249741517,
    ];
    let w = [
        0.026593232599919414,
        -0.03396425051683927,
        -0.010085818847169636,
    ];
    let seed = 4489572868979223273;
    let p = Params::<f32> {
        mag_delay_estimation_time: 0.0,
        ..Params::default()
    };
    let r = garbage_burst::<f32>(q, w, 57, seed, p);
    assert!(r.is_ok(), "{r:?}");
    let r = garbage_burst::<f64>(q, w, 0, seed, Params::default());
    assert!(r.is_ok(), "{r:?}");
}

/// Steady turns slower than the largest bias, about a tilted axis and about the vertical (the
/// first found by the specific force, the second by the field's horizontal direction): the
/// error is back within the bounds 40 s after 2 s of the turn. Before the rest detector's drift
/// tests every rate from 0.2 to 2.9 °/s failed (the attitude stood still while the sensor
/// turned).
fn slow_turns<T: Tolerance>() {
    let mut g = Gen::<T>::new(29);
    for i in 0..40 {
        let q = g.unit_quat_f64();
        let vertical = i % 2 == 1;
        let d = if vertical {
            to_sensor(q, [0.0, 0.0, 1.0])
        } else {
            [0, 1, 2].map(|_| g.rng.range(-1.0, 1.0))
        };
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let rate = g.rng.range(0.1, 3.4).to_radians();
        let w = d.map(|c| c / n * rate);
        let r = garbage_burst::<T>(q, w, 0, 1, Params::default());
        assert!(
            r.is_ok(),
            "{} turn at {:.2} °/s ({q:?}, {w:?}): {r:?}",
            if vertical { "vertical" } else { "tilted" },
            rate.to_degrees()
        );
    }
}

#[test]
fn slow_turns_are_not_rest_f32() {
    slow_turns::<f32>();
}

#[test]
fn slow_turns_are_not_rest_f64() {
    slow_turns::<f64>();
}

/// A sustained horizontal push of 3–4 m/s² for 30 s (the low-passed specific force within the
/// 0.2 g gate, so the accelerometer is used and the filter learns the push's tilt), at rest or
/// turning: 40 s after it ends the error is back within the bounds. Before the persistent-
/// disagreement test the tilt learned from the push decayed at the steady-state gain (about
/// 25 s per e-fold) and these three were 9–17° off (inclination 2.1–4.1°).
fn sustained_push<T: Tolerance>() {
    let q = normalize([0.9, 0.2, -0.3, 0.1]);
    for (w, size, dir) in [
        ([0.0, 0.0, 0.0], 3.0, [1.0, 0.0, 0.0]),
        ([0.0, 0.0, 0.0], 4.0, [0.6, 0.8, 0.0]),
        ([0.05, -0.1, 0.2], 3.0, [1.0, 0.0, 0.0]),
    ] {
        let r = long_disturbance::<T>(q, w, 2, 30.0, size, dir, true);
        assert!(
            r.is_ok(),
            "push {size} m/s² along {dir:?}, rate {w:?}: {r:?}"
        );
    }
}

#[test]
fn sustained_push_corrected_after_it_ends_f32() {
    sustained_push::<f32>();
}

#[test]
fn sustained_push_corrected_after_it_ends_f64() {
    sustained_push::<f64>();
}
