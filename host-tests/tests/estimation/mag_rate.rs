//! The magnetometer's time scales are in seconds whatever its rate beside the gyroscope's: the
//! same motion and the same field events, with a field sample on every gyroscope row and on
//! every 10th row only (a magnetometer at a tenth of the gyroscope's rate, as a 100 Hz
//! magnetometer beside a 1 kHz gyroscope), give the same times in seconds, in the full and
//! the light mode. The times are the disturbance monitor's (`FieldMonitor`): how long after a
//! disturbance ends the field is used again (`field.min_undisturbed`, 0.5 s), and how long after
//! the field changes for good, while the sensor turns, the new field becomes the reference
//! (`field.new_field_time`, 20 s of turning faster than `field.new_field_min_rate`).

use super::{FIELD, Motion, qexp, qrotate};
use gyrostat::estimation::{Estimator, Mode as FilterMode, Params, SensorUse};
use host_tests::cast::vec3;

/// The gyroscope's step, s (200 Hz).
const DT: f64 = 0.005;

/// Which rows carry a field sample.
#[derive(Clone, Copy, Debug)]
enum Mag {
    /// Every `n`th row.
    Every(usize),
    /// Every 5th row, every other one of those not finite (a rejected sample between two
    /// good ones: a good sample every 10th row).
    EveryFifthHalfBad,
}

impl Mag {
    /// The field sample of row `k` (`m` the sensor's reading), if any.
    fn sample(self, k: usize, m: [f64; 3]) -> Option<[f64; 3]> {
        match self {
            Mag::Every(n) => k.is_multiple_of(n).then_some(m),
            Mag::EveryFifthHalfBad => match k % 10 {
                0 => Some(m),
                5 => Some([f64::NAN, m[1], m[2]]),
                _ => None,
            },
        }
    }
}

/// The field event.
#[derive(Clone, Copy, Debug)]
enum Event {
    /// A field added in the earth frame (µT) from 20 s to 25 s: the norm 34 % larger.
    Disturbance,
    /// From 20 s on, the earth's field 25 % stronger (the sensor carried to another place).
    NewField,
}

/// Runs the motion of the estimation tests (non-repeating rates up to about 60 °/s) for 60 s
/// with the event and returns the time (s) from the event's end (25 s for the disturbance, 20 s
/// for the new field) to the first row whose field sample is reported as used after one was
/// reported as disturbed.
fn time_to_use<T: gyrostat::Real>(params: Params<T>, mag: Mag, event: Event) -> f64 {
    let mut motion = Motion {
        t: 0.0,
        q: qexp([0.2, -0.4, 0.7]),
        amp: 0.6,
    };
    let mut f = Estimator::<T>::try_new(params).unwrap();
    // Row k ends at (k + 1)·DT: rows 4000.. are from 20 s on, rows 5000.. from 25 s on.
    let mut seen_disturbed = false;
    let end = match event {
        Event::Disturbance => 5000,
        Event::NewField => 4000,
    };
    for k in 0..12_000usize {
        let w = motion.step(DT);
        let row = k + 1;
        let earth = match event {
            Event::Disturbance if (4000..5000).contains(&row) => {
                [FIELD[0], FIELD[1], FIELD[2] - 15.0]
            }
            Event::NewField if row >= 4000 => FIELD.map(|v| 1.25 * v),
            _ => FIELD,
        };
        let (acc, _) = motion.sensors();
        let m = qrotate(super::qconj(motion.q), earth);
        let o = f
            .update(
                vec3::<T>(w),
                vec3::<T>(acc),
                mag.sample(k, m).map(vec3::<T>),
                T::from_f64(DT),
            )
            .unwrap();
        // The light mode reports a valid sample between corrections as the last correction
        // did: the time counts from a report of the event (a disturbed field) on.
        if mag.sample(k, m).is_some() && row >= 4000 {
            seen_disturbed |= o.mag == SensorUse::Disturbed;
            if row >= end && seen_disturbed && o.mag == SensorUse::Used {
                return (row - end) as f64 * DT;
            }
        }
    }
    f64::INFINITY
}

host_tests::per_type! {
    /// The disturbance's end: used again `min_undisturbed` (0.5 s) after it at the full rate
    /// (within a row; the light mode within one correction period more, the sample that ends
    /// the wait standing for the time since the last one taken to a correction); the times at a
    /// tenth of the rate (with and without rejected samples between the good ones) within one
    /// field interval (50 ms) and one row of the time at the full rate.
    #[test]
    fn disturbance_recovery_is_in_seconds() {
        for mode in [FilterMode::Full, FilterMode::light()] {
            let params = Params::<T> { mode, ..Params::default() };
            let fast = time_to_use(params, Mag::Every(1), Event::Disturbance);
            let light_wait = if mode == FilterMode::Full { 0.0 } else { FilterMode::<T>::LIGHT_PERIOD };
            assert!(
                (0.5 - DT - light_wait..0.5 + DT + light_wait).contains(&fast),
                "{} {mode:?}: used again {fast} s after the disturbance",
                T::NAME
            );
            for mag in [Mag::Every(10), Mag::EveryFifthHalfBad] {
                let slow = time_to_use(params, mag, Event::Disturbance);
                assert!(
                    (slow - fast).abs() <= 10.0 * DT + DT + light_wait,
                    "{} {mode:?} {mag:?}: {slow} s against {fast} s at the full rate",
                    T::NAME
                );
            }
        }
    }

    /// A new field while turning: replaces the reference after `new_field_time` (20 s) of
    /// turning faster than 20 °/s; at a tenth of the rate within 0.25 s of the full rate's time
    /// (the turning time summed on coarser samples, one field interval per crossing of the rate
    /// threshold), in both modes.
    #[test]
    fn new_field_acceptance_is_in_seconds() {
        for mode in [FilterMode::Full, FilterMode::light()] {
            let params = Params::<T> { mode, ..Params::default() };
            let fast = time_to_use(params, Mag::Every(1), Event::NewField);
            assert!(
                (20.0..40.0).contains(&fast),
                "{} {mode:?}: the new field used {fast} s after it appeared",
                T::NAME
            );
            for mag in [Mag::Every(10), Mag::EveryFifthHalfBad] {
                let slow = time_to_use(params, mag, Event::NewField);
                assert!(
                    (slow - fast).abs() <= 0.25,
                    "{} {mode:?} {mag:?}: {slow} s against {fast} s at the full rate",
                    T::NAME
                );
            }
        }
    }
}
