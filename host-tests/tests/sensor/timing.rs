//! Sample clocks: every classification checked against the elapsed time computed here.

use super::Rng;
use gyrostat::Error;
use gyrostat::sensor::timing::{micros_to_q30, micros_to_seconds};
use gyrostat::sensor::{Interval, MicrosClock, SampleClock};

#[test]
fn seconds_clock_policy() {
    let mut c = SampleClock::try_new(0.01f64).unwrap();
    assert_eq!(c.max_step(), 0.05);
    assert_eq!(c.interval(1.0), Ok(Interval::First));
    let mut rng = Rng::new(1);
    let mut t = 1.0;
    for _ in 0..1000 {
        let dt = rng.range(0.006, 0.03);
        let before = t;
        t += dt;
        let want = t - before; // the rounded elapsed time
        assert_eq!(c.interval(t), Ok(Interval::Step(want)));
    }
    // A repeated timestamp: skipped, the clock keeps the earlier one.
    assert_eq!(c.interval(t), Ok(Interval::Repeated));
    // Backwards: skipped, then the next regular timestamp is measured from `t`.
    assert_eq!(
        c.interval(t - 0.004),
        Ok(Interval::Backwards(t - (t - 0.004)))
    );
    assert_eq!(c.last(), Some(t));
    assert_eq!(c.interval(t + 0.01), Ok(Interval::Step((t + 0.01) - t)));
    let t = t + 0.01;
    assert!(matches!(c.interval(t + 0.0501), Ok(Interval::Gap(_))));
    let t = t + 0.0501;
    assert_eq!(c.last(), Some(t));
    assert_eq!(c.interval(f64::NAN), Err(Error::NonFinite));
    assert_eq!(c.interval(f64::INFINITY), Err(Error::NonFinite));
    assert_eq!(c.last(), Some(t));
    // Exactly 5× is a step, beyond it a gap (dyadic values: no rounding); the gap's timestamp
    // is accepted.
    let mut c = SampleClock::try_new(0.25f64).unwrap();
    assert_eq!(c.max_step(), 1.25);
    c.restart(Some(1.0));
    assert_eq!(c.interval(2.25), Ok(Interval::Step(1.25)));
    assert_eq!(
        c.interval(3.5 + 2f64.powi(-40)),
        Ok(Interval::Gap(1.25 + 2f64.powi(-40)))
    );
    assert_eq!(c.last(), Some(3.5 + 2f64.powi(-40)));
    c.restart(None);
    assert_eq!(c.interval(0.0), Ok(Interval::First));
    // Configurable factor, f32.
    let mut c = SampleClock::try_with_gap_factor(0.001f32, 2.0).unwrap();
    c.restart(Some(0.0));
    assert_eq!(c.interval(0.002), Ok(Interval::Step(0.002)));
    assert!(matches!(c.interval(0.0041), Ok(Interval::Gap(_))));
    for (nom, k) in [(0.0, 5.0), (-1.0, 5.0), (0.01, 0.5), (1e300, 1e10)] {
        assert_eq!(
            SampleClock::try_with_gap_factor(nom, k),
            Err(Error::InvalidArgument)
        );
    }
    assert_eq!(SampleClock::try_new(f64::NAN), Err(Error::NonFinite));
}

#[test]
fn micros_clock_wraps_at_2_pow_32() {
    // The true time in i64 µs; the counter is its low 32 bits. Start 3 ms before a wrap and run
    // through three wraps with a jittered ~1 s step.
    let nominal = 1_000_000u32;
    let mut c = MicrosClock::try_new(nominal, 5).unwrap();
    let mut rng = Rng::new(2);
    let mut t: i64 = (1i64 << 32) - 3000;
    assert_eq!(c.interval(t as u32), Interval::First);
    let mut wraps = 0;
    for _ in 0..13_000 {
        let dt = rng.range(600_000.0, 1_400_000.0) as i64;
        let next = t + dt;
        if next >> 32 != t >> 32 {
            wraps += 1;
        }
        t = next;
        assert_eq!(
            c.interval((t & 0xFFFF_FFFF) as u32),
            Interval::Step(dt as u32)
        );
    }
    assert!(wraps >= 3, "{wraps}");
    let now = (t & 0xFFFF_FFFF) as u32;
    assert_eq!(c.interval(now), Interval::Repeated);
    assert_eq!(c.interval(now.wrapping_sub(7)), Interval::Backwards(7));
    let gap = 5 * nominal + 1;
    assert_eq!(c.interval(now.wrapping_add(gap)), Interval::Gap(gap));
    let now = now.wrapping_add(gap);
    // 2³¹ µs or more forward cannot be told from backwards.
    assert_eq!(
        c.interval(now.wrapping_add(1 << 31)),
        Interval::Backwards(1 << 31)
    );
    assert_eq!(
        c.interval(now.wrapping_add((1 << 31) - 1)),
        Interval::Gap((1 << 31) - 1)
    );
    // A wrap right at the boundary: u32::MAX then 0 is one microsecond.
    let mut c = MicrosClock::try_new(1, 1).unwrap();
    c.restart(Some(u32::MAX));
    assert_eq!(c.interval(0), Interval::Step(1));
    assert_eq!(MicrosClock::try_new(0, 5), Err(Error::InvalidArgument));
    assert_eq!(MicrosClock::try_new(1, 0), Err(Error::InvalidArgument));
    assert_eq!(
        MicrosClock::try_new(1 << 30, 2),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        MicrosClock::try_new(u32::MAX, 2),
        Err(Error::InvalidArgument)
    );
}

#[test]
fn micros_to_seconds_in_every_format() {
    let mut rng = Rng::new(3);
    for _ in 0..100_000 {
        let us = (rng.uniform() * 1_999_999.0) as u32;
        let s = us as f64 / 1e6;
        let q = micros_to_q30(us).unwrap().to_f64();
        assert!((q - s).abs() <= 2f64.powi(-31) * (1.0 + 1e-9), "{us}");
        assert!((micros_to_seconds::<f64>(us) - s).abs() <= 2.0 * f64::EPSILON * s);
        let f: f32 = micros_to_seconds(us);
        assert!((f as f64 - s).abs() <= f32::EPSILON as f64 * s);
    }
    assert_eq!(micros_to_q30(1_999_999).map(|q| q.to_bits() > 0), Ok(true));
    assert_eq!(micros_to_q30(2_000_000), Err(Error::OutOfRange));
    assert_eq!(micros_to_q30(u32::MAX), Err(Error::OutOfRange));
}
