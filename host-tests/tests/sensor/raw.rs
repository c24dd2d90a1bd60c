//! Raw registers: clipping flags and policies, the LSB scale in f32, f64 and Q1.30, and the
//! whole raw → scale → calibration → remap chain agreeing across the formats.

use super::Rng;
use gyrostat::fixed::IncrementQuantizer;
use gyrostat::real::Q30;
use gyrostat::sensor::{
    AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration, RawScale,
};
use gyrostat::{Error, Mat3, Vec3};

#[test]
fn clipping_flags() {
    let full = ClipLimit::default();
    assert_eq!(full.check([32767, 0, -32768]).axes, [true, false, true]);
    assert_eq!(
        full.check([32766, -32767, -32766]).axes,
        [false, true, false]
    );
    let l = ClipLimit::try_new(16000).unwrap();
    // Every i16 against the rule written here: |r| ≥ 16000.
    for r in i16::MIN..=i16::MAX {
        let want = (r as i32).abs() >= 16000;
        assert_eq!(l.check([r, 0, r]).axes, [want, false, want], "{r}");
    }
    assert_eq!(ClipLimit::try_new(0), Err(Error::InvalidArgument));
    assert_eq!(ClipLimit::try_new(-5), Err(Error::InvalidArgument));
}

#[test]
fn clipping_policies() {
    let seq = [
        [10i16, -20, 30],
        [32767, -21, 31],
        [11, -32768, 32],
        [32767, 32767, 32767],
        [12, -22, 33],
    ];
    let mut pass = ClipGuard::new(ClipLimit::default(), ClipPolicy::Pass);
    let mut hold = ClipGuard::new(ClipLimit::default(), ClipPolicy::HoldLast);
    let mut reject = ClipGuard::new(ClipLimit::default(), ClipPolicy::Reject);
    let want_hold = [
        [10, -20, 30],
        [10, -21, 31],
        [11, -21, 32],
        [11, -21, 32],
        [12, -22, 33],
    ];
    for (k, raw) in seq.iter().enumerate() {
        let (p, flags) = pass.filter(*raw).unwrap();
        assert_eq!(p, *raw);
        assert_eq!(flags.axes, raw.map(|r| r == 32767 || r <= -32767));
        assert_eq!(hold.filter(*raw).unwrap().0, want_hold[k]);
        let rj = reject.filter(*raw);
        if flags.any() {
            assert_eq!(rj, Err(Error::Clipped));
        } else {
            assert_eq!(rj, Ok((*raw, flags)));
        }
    }
    // A clip before any unclipped reading of that axis is passed under HoldLast.
    let mut hold = ClipGuard::new(ClipLimit::default(), ClipPolicy::HoldLast);
    assert_eq!(hold.filter([32767, 5, 5]).unwrap().0, [32767, 5, 5]);
}

#[test]
fn lsb_scale_in_every_format() {
    let lsb = 1.0653e-6; // rad per LSB of an increment register
    let s64 = RawScale::<f64>::try_new(lsb).unwrap();
    let s32 = RawScale::<f32>::try_new(lsb).unwrap();
    let sq = RawScale::<Q30>::try_new(lsb).unwrap();
    for r in (i16::MIN..=i16::MAX).step_by(7) {
        let exact = r as f64 * lsb;
        assert_eq!(s64.apply([r, 0, 0]).x, exact);
        let f = s32.apply([r, 0, 0]).x as f64;
        assert!((f - exact).abs() <= exact.abs() * 1.5 * f32::EPSILON as f64);
        let q = sq.reading(r).to_f64();
        // One rounding to 2⁻³¹ plus the scale's own relative 2⁻³¹.
        assert!((q - exact).abs() <= 2f64.powi(-31) + exact.abs() * 2f64.powi(-31));
    }
    assert_eq!(RawScale::<f64>::try_new(0.0), Err(Error::InvalidArgument));
    assert_eq!(RawScale::<f32>::try_new(-1.0), Err(Error::InvalidArgument));
    assert_eq!(RawScale::<f64>::try_new(f64::NAN), Err(Error::NonFinite));
    assert_eq!(RawScale::<Q30>::try_new(f64::NAN), Err(Error::NonFinite));
    // A full scale 32768·lsb beyond the type's range, or an lsb that rounds to 0 in it.
    assert_eq!(
        RawScale::<f32>::try_new(f64::from(f32::MAX)),
        Err(Error::InvalidArgument)
    );
    assert_eq!(RawScale::<f32>::try_new(1e-50), Err(Error::InvalidArgument));
    assert_eq!(
        RawScale::<Q30>::try_new(2f64.powi(-14)),
        Err(Error::OutOfRange)
    );
    // The stored LSB: rounded to f32 once, exact in f64, to 31 bits in Q1.30.
    assert_eq!(s32.lsb(), f64::from(lsb as f32));
    assert_eq!(s64.lsb(), lsb);
    assert!((sq.lsb() / lsb - 1.0).abs() <= 2f64.powi(-31));
}

/// raw i16 increments → LSB scale → calibration (bias over the step) → remap, in f64, f32 and
/// Q1.30, over a stream that does not repeat; the Q1.30 sums stay within a few 2⁻³⁰ per sample of
/// f64 (quantizer remainder carried).
#[test]
fn chain_agrees_across_formats() {
    let mut rng = Rng::new(30);
    let lsb = 1.0653e-6;
    let dt = 1e-3;
    let m = Mat3::from_rows(
        [1.0, 0.004, -0.002],
        [-0.003, 1.0, 0.001],
        [0.002, -0.001, 1.0],
    );
    let s = Vec3::new(1.01, 0.995, 1.003);
    let b = Vec3::new(0.002, -0.001, 0.0005); // rad/s
    let cal = InertialCalibration::try_new(m, s, b).unwrap();
    let cal32 = InertialCalibration::try_new(
        Mat3::from_rows(
            m.m[0].map(|x| x as f32),
            m.m[1].map(|x| x as f32),
            m.m[2].map(|x| x as f32),
        ),
        Vec3::from_array(s.to_array().map(|x| x as f32)),
        Vec3::from_array(b.to_array().map(|x| x as f32)),
    )
    .unwrap();
    let calq = cal.try_to_q30().unwrap();
    let remap = AxisRemap::try_parse("y,-x,z").unwrap();
    let (s64, s32, sq) = (
        RawScale::<f64>::try_new(lsb).unwrap(),
        RawScale::<f32>::try_new(lsb).unwrap(),
        RawScale::<Q30>::try_new(lsb).unwrap(),
    );
    let dtq = Q30::try_from_f64(dt).unwrap();
    let mut quant = IncrementQuantizer::new();
    let (mut sum64, mut sum32, mut sumq) = ([0.0f64; 3], [0.0f64; 3], [0.0f64; 3]);
    let n = 10_000;
    for _ in 0..n {
        let raw = [0, 0, 0].map(|_: i32| rng.range(-30000.0, 30000.0) as i16);
        let v64 = remap
            .apply(cal.apply_increment(s64.apply(raw), dt))
            .to_array();
        let v32 = remap
            .apply(cal32.apply_increment(s32.apply(raw), dt as f32))
            .to_array();
        let vq = remap
            .apply(calq.apply_increment(quant.quantize_raw(&sq, raw), dtq))
            .to_f64()
            .to_array();
        for k in 0..3 {
            // Each sample, against the f64 model on the same raw reading.
            assert!((v32[k] as f64 - v64[k]).abs() <= 4.0 * f32::EPSILON as f64 * 0.04);
            sum64[k] += v64[k];
            sum32[k] += v32[k] as f64;
            sumq[k] += vq[k];
        }
    }
    for k in 0..3 {
        // The Q1.30 sum: the quantizer's remainder is carried (≤ 2⁻³¹ in the sum of the
        // increments); the calibration's roundings (K to 2⁻³¹ relative, the dot product to 2⁻³¹
        // per sample) do not carry, and are bounded by 2⁻³⁰ per sample.
        assert!(
            (sumq[k] - sum64[k]).abs() <= n as f64 * 2f64.powi(-30),
            "{k} {:e}",
            sumq[k] - sum64[k]
        );
        assert!((sum32[k] - sum64[k]).abs() <= n as f64 * 4.0 * f32::EPSILON as f64 * 0.04);
    }
}

/// One clip policy for every reading type: f32 and f64 values against a range in physical units
/// (as the estimator's gyroscope samples), with the same flags and policies as the registers.
#[test]
fn clipping_is_generic_over_the_reading() {
    // f64: a range of 34.9 rad/s (2000 °/s).
    let range = 2000f64.to_radians();
    let limit = ClipLimit::<f64>::try_new(range).unwrap();
    let (out, c) = limit.saturate([40.0, -35.0, 1.0]);
    assert_eq!(c.axes, [true, true, false]);
    assert_eq!(out, [range, -range, 1.0]);
    // Exactly at the limit counts as clipped (as a register at its full scale).
    assert_eq!(limit.check([range, 0.0, -range]).axes, [true, false, true]);
    assert_eq!(ClipLimit::<f64>::try_new(0.0), Err(Error::InvalidArgument));
    assert_eq!(
        ClipLimit::<f32>::try_new(f32::NAN),
        Err(Error::InvalidArgument)
    );
    // The floats' default limit is none (∞): nothing clips.
    let none = ClipLimit::<f32>::default();
    assert!(!none.check([f32::MAX, -f32::MAX, 0.0]).any());
    // The stateful guard in f32, the four policies on the same stream.
    let l32 = ClipLimit::<f32>::try_new(10.0).unwrap();
    let stream = [[1.0f32, 2.0, 3.0], [12.0, 2.5, -11.0], [4.0, 10.0, 3.5]];
    let run = |policy| {
        let mut g = ClipGuard::new(l32, policy);
        stream.map(|r| g.filter(r).map(|(o, _)| o))
    };
    let pass = run(ClipPolicy::Pass);
    assert_eq!(pass[1], Ok([12.0, 2.5, -11.0]));
    let sat = run(ClipPolicy::Saturate);
    assert_eq!(sat[1], Ok([10.0, 2.5, -10.0]));
    assert_eq!(sat[2], Ok([4.0, 10.0, 3.5]));
    let hold = run(ClipPolicy::HoldLast);
    assert_eq!(hold[1], Ok([1.0, 2.5, 3.0]));
    assert_eq!(hold[2], Ok([4.0, 2.5, 3.5]));
    let reject = run(ClipPolicy::Reject);
    assert_eq!(reject[1], Err(Error::Clipped));
    assert_eq!(reject[0], Ok([1.0, 2.0, 3.0]));
    // Registers: Saturate sets a clipped axis to ±limit (i16::MIN to −limit).
    let l16 = ClipLimit::<i16>::try_new(30000).unwrap();
    let (out, c) = l16.saturate([31000, i16::MIN, 5]);
    assert_eq!((out, c.axes), ([30000, -30000, 5], [true, true, false]));
}

/// Increments over their own intervals hold the rate, not the reading: a steady 2 rad/s about x
/// read as `θ = 2·h` over h = 1/4 s, then clipped at 1 rad over h = 3/4 s, is held at
/// `2·(3/4) = 3/2` rad (the steady rotation), where holding the reading gives the 1/2 rad of the
/// shorter interval. Dyadic values: every product is exact.
#[test]
fn clipped_increments_hold_the_rate() {
    let limit = ClipLimit::<f64>::try_new(1.0).unwrap();
    let stream = [([0.5, 0.25, 0.0], 0.25), ([1.0, 0.75, -0.5], 0.75)];
    let mut g = ClipGuard::new(limit, ClipPolicy::HoldLast);
    let out = stream.map(|(r, h)| g.filter_increment(r, h));
    assert_eq!(out[0].map(|o| o.0), Ok([0.5, 0.25, 0.0]));
    let (held, c) = out[1].unwrap();
    assert_eq!(c.axes, [true, false, false]);
    assert_eq!(held, [1.5, 0.75, -0.5]);
    // Holding the reading is the fixed-interval answer, wrong here by h_last / h = 1/3.
    let mut reading = ClipGuard::new(limit, ClipPolicy::HoldLast);
    let out = stream.map(|(r, _)| reading.filter(r).map(|o| o.0));
    assert_eq!(out[1], Ok([0.5, 0.75, -0.5]));
    // At a fixed interval the two agree.
    let mut a = ClipGuard::new(limit, ClipPolicy::HoldLast);
    let mut b = ClipGuard::new(limit, ClipPolicy::HoldLast);
    for r in [[0.5, 0.25, 0.0], [1.0, 0.75, -0.5], [0.25, 1.5, 0.0]] {
        assert_eq!(a.filter_increment(r, 0.25), b.filter(r));
    }
    // Reject, Saturate and Pass as for readings; an interval that is not positive and finite
    // is an error and leaves the guard as it was.
    let mut reject = ClipGuard::new(limit, ClipPolicy::Reject);
    assert_eq!(
        reject.filter_increment([0.0, -1.0, 0.0], 0.5),
        Err(Error::Clipped)
    );
    let mut sat = ClipGuard::new(limit, ClipPolicy::Saturate);
    assert_eq!(
        sat.filter_increment([-3.0, 0.5, 0.0], 0.5).map(|o| o.0),
        Ok([-1.0, 0.5, 0.0])
    );
    for h in [0.0, -0.25, f64::NAN, f64::INFINITY] {
        assert_eq!(
            g.filter_increment([0.5, 0.0, 0.0], h),
            Err(Error::InvalidArgument)
        );
    }
    assert_eq!(
        g.filter_increment([2.0, 0.0, 0.0], 0.5).map(|o| o.0),
        Ok([1.0, 0.0, 0.0])
    );
    assert_eq!(g.limit(), limit);
    assert_eq!(g.policy(), ClipPolicy::HoldLast);
}
