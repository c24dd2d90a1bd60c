//! The IMU firmware (`firmware/imu`, `fw_imu`): its driver-free half on the host, the faults'
//! documented outcomes, the replayed table against the shared BROAD trial, and bit-identity
//! of the boards' output with the host's.
//!
//! `firmware/imu/src/replay.rs` (included here) is the path raw registers → sensor layer →
//! estimator and strapdown that the firmware runs after its drivers have read the registers
//! over the device model's I²C bus. `.ci/run` runs the firmware on the Cortex-M4F (defmt,
//! decoded with `defmt-print`) and on RISC-V (semihosting text), writes
//! `$GYROSTAT_FIRMWARE_OUTPUT/imu-<target>.txt`, and runs the ignored test below: the boards'
//! lines must equal the host's character for character (every float is printed as its f32
//! bits), which holds only if the drivers, the bus model and the timer delivered exactly the
//! registers and time stamps of [`samples`] (the host's driver-free sequence).
//!
//! The expected counters are derived from the fault definitions (rows, rules), not from a run.

#[allow(dead_code)]
mod replay {
    include!("../../../firmware/imu/src/replay.rs");
}
use replay::*;

/// The host's output lines.
fn host_lines() -> Vec<String> {
    let mut lines = Vec::new();
    let mut replay = Replay::try_new().expect("constants accepted");
    samples(|s| {
        replay
            .push(s, &mut |l| lines.push(l.to_string()))
            .map(|_| ())
    })
    .expect("replay runs");
    replay.finish(&mut |l| lines.push(l.to_string()));
    lines
}

/// The counters the faults must produce, from their definitions.
fn expected_counters() -> Counters {
    // Stuck: the first row of STUCK_ROWS is the frozen value itself; the following rows
    // repeat it 1, 2, … times; from the STUCK_AFTER-th repeat on a sample is skipped.
    let first_skipped = STUCK_ROWS.start + STUCK_AFTER as usize;
    let skipped_rows = first_skipped..STUCK_ROWS.end;
    let skipped = skipped_rows.len() as u32;
    // Used: every row but the missed one and the skipped ones.
    let samples = ROWS as u32 - 1 - skipped;
    // 9D updates: every magnetometer row, except those arriving with a skipped sample (the
    // missed row's field is read with the next row).
    let mag = (0..ROWS)
        .filter(|k| k.is_multiple_of(MAG_EVERY) && !skipped_rows.contains(k))
        .count() as u32;
    Counters {
        samples,
        mag,
        // One step of two periods (the missed data-ready) ...
        late: 1,
        // ... and one gap: the stuck run's skipped rows plus one period.
        gaps: 1,
        clipped: SATURATED_ROWS.len() as u32,
        stuck: 1,
        skipped,
        rejected: 0,
        // The whole log's span, each µs once.
        time_us: (ROWS as u32 - 1) * PERIOD_US,
    }
}

#[test]
fn the_faults_have_their_documented_outcomes() {
    let mut replay = Replay::try_new().unwrap();
    let mut lines = 0;
    samples(|s| replay.push(s, &mut |_| lines += 1).map(|_| ())).unwrap();
    let c = replay.counters();
    assert_eq!(c, expected_counters());
    assert_eq!(lines, c.samples / PRINT_EVERY);
    // The gap is the stuck run: from the last used row before it to the first fresh row.
    let gap = (STUCK_ROWS.end - (STUCK_ROWS.start + STUCK_AFTER as usize - 1)) as u32 * PERIOD_US;
    assert!(gap > 5 * PERIOD_US, "the stuck run must be a gap: {gap} us");
    println!("{c:?}");
}

/// The table holds the three faults where they are documented, and nothing else that looks
/// like one: real noise never repeats all six IMU registers, and the motion stays within
/// ±2000 °/s.
#[test]
fn the_table_has_exactly_the_documented_faults() {
    let rows: Vec<[i16; 9]> = (0..ROWS).map(|k| row(k).unwrap()).collect();
    assert_eq!(rows.len(), 4000);
    for (k, r) in rows.iter().enumerate() {
        let full_scale = r[..6].iter().any(|&v| v == i16::MAX || v <= -i16::MAX);
        assert_eq!(full_scale, SATURATED_ROWS.contains(&k), "row {k}: {r:?}");
        if SATURATED_ROWS.contains(&k) {
            assert_eq!(r[0], i16::MAX);
        }
        let repeat = k > 0 && r[..6] == rows[k - 1][..6];
        let in_stuck = k > STUCK_ROWS.start && STUCK_ROWS.contains(&k);
        assert_eq!(repeat, in_stuck, "row {k}");
    }
    assert!(!SATURATED_ROWS.contains(&MISSED_DRDY_ROW) && !STUCK_ROWS.contains(&MISSED_DRDY_ROW));
    // The missed row carries a magnetometer field, read with the next row.
    assert!(MISSED_DRDY_ROW.is_multiple_of(MAG_EVERY));
}

/// The timer wraps within the log, and the firmware's intervals do not see it.
#[test]
fn the_timer_wraps_during_the_replay() {
    let wraps = (1..ROWS)
        .filter(|&k| row_time_us(k) < row_time_us(k - 1))
        .count();
    assert_eq!(wraps, 1);
    // The missed data-ready's long step is the one across the wrap.
    assert!(row_time_us(MISSED_DRDY_ROW) < row_time_us(MISSED_DRDY_ROW - 1));
}

/// The table is BROAD trial 07, rows 6700.., quantised as `imu_log.py` documents (requantised
/// here independently from the shared CSV); skipped when the shared folder is absent.
#[test]
fn the_table_is_the_quantised_broad_trial() {
    let Some(path) = host_tests::broad::trial_path("07_undisturbed_fast_rotation_B") else {
        eprintln!("skipped: {}", host_tests::broad::BROAD_DIR_HELP);
        return;
    };
    let log = host_tests::broad::open_log(&path, host_tests::broad::Units::SI).unwrap();
    let q = |x: f64| (x + 0.5).floor().clamp(-32768.0, 32767.0) as i16;
    let mut worst = [0.0f64; 3];
    for k in 0..ROWS {
        if SATURATED_ROWS.contains(&k) || STUCK_ROWS.contains(&k) {
            continue;
        }
        let src = &log.rows[6700 + k];
        let r = row(k).unwrap();
        let gyro = src.gyro.map(|w| q(w.to_degrees() * 16.4));
        let accel = src.accel.map(|a| q(a / 9.80665 * 8192.0));
        let [bx, by, bz] = src.mag.unwrap();
        let chip = [by, -bx, bz];
        let mag: Vec<i16> = (0..3)
            .map(|i| q((chip[i] + MAG_HARD_IRON_UT[i]) / MAG_LSB_UT))
            .collect();
        assert_eq!(r[..3], gyro, "row {k} gyro");
        assert_eq!(r[3..6], accel, "row {k} accel");
        assert_eq!(r[6..], mag[..], "row {k} mag");
        // Dequantised through the firmware's scales: within half an LSB of the source.
        for i in 0..3 {
            worst[0] = worst[0].max((f64::from(r[i]) * GYRO_LSB_RAD_S - src.gyro[i]).abs());
            worst[1] = worst[1].max((f64::from(r[3 + i]) * ACCEL_LSB_M_S2 - src.accel[i]).abs());
        }
        worst[2] = worst[2].max((f64::from(r[6]) * MAG_LSB_UT - MAG_HARD_IRON_UT[0] - by).abs());
    }
    assert!(worst[0] <= 0.5 * GYRO_LSB_RAD_S * (1.0 + 1e-9));
    assert!(worst[1] <= 0.5 * ACCEL_LSB_M_S2 * (1.0 + 1e-9));
    assert!(worst[2] <= 0.5 * MAG_LSB_UT * (1.0 + 1e-9));
    println!(
        "worst dequantisation error: gyro {:.2e} rad/s, accel {:.2e} m/s², mag {:.3} uT",
        worst[0], worst[1], worst[2]
    );
}

/// The replay's estimate against BROAD's optical reference (BROAD's metric over the rows in
/// motion), beside the same estimator fed the trial's own f64 samples of the same rows (no
/// quantisation, no faults, no calibration, the field in the IMU's axes): the registers, the
/// sensor layer and the three faults may cost at most 1° of total RMS error. Skipped when the
/// shared folder is absent.
#[test]
fn the_replay_estimate_tracks_the_optical_reference() {
    use gyrostat::Vec3;
    use gyrostat::estimation::{Estimator, Params};
    use host_tests::broad::{Log, Units, open_log, score, trial_path};
    let Some(path) = trial_path("07_undisturbed_fast_rotation_B") else {
        eprintln!("skipped: {}", host_tests::broad::BROAD_DIR_HELP);
        return;
    };
    let full = open_log(&path, Units::SI).unwrap();
    let window = Log {
        rows: full.rows[6700..6700 + ROWS].to_vec(),
        ..full.clone()
    };
    // The replay: the estimate after each used sample, at that row's time.
    let mut replay = Replay::try_new().unwrap();
    let mut estimate = Vec::new();
    let mut k = 0;
    samples(|s| {
        while row_time_us(k) != s.t_us {
            k += 1;
        }
        let used = replay.counters().samples;
        replay.push(s, &mut |_| ())?;
        if replay.counters().samples > used {
            let q = replay.attitude().to_array().map(f64::from);
            estimate.push((window.rows[k].t, q));
        }
        Ok(())
    })
    .unwrap();
    let fw = score(&window, &estimate);
    // The reference run: every row, as the trial gives it.
    let mut f = Estimator::<f32>::try_new(Params::default()).unwrap();
    let v = |a: [f64; 3]| Vec3::new(a[0] as f32, a[1] as f32, a[2] as f32);
    let plain: Vec<(f64, [f64; 4])> = window
        .rows
        .iter()
        .map(|r| {
            f.update_9d(
                v(r.gyro),
                v(r.accel),
                v(r.mag.unwrap()),
                PERIOD_US as f32 * 1e-6,
            )
            .unwrap();
            (r.t, f.attitude().to_array().map(f64::from))
        })
        .collect();
    let reference = score(&window, &plain);
    println!("replay: {fw:?}\ntrial samples: {reference:?}");
    let part = |a: usize, b: usize| {
        let rows = Log {
            rows: window.rows[a..b].to_vec(),
            ..full.clone()
        };
        let (r, p) = (score(&rows, &estimate), score(&rows, &plain));
        println!(
            "rows {a}..{b}: replay {:.2}°, trial samples {:.2}°",
            r.total, p.total
        );
        (r.total, p.total)
    };
    assert!(fw.n > 2000 && reference.n == fw.n + fw.missing);
    // Before the stuck run: the registers, the sensor layer, the saturated register and the
    // missed data-ready cost at most 1°.
    let (before, plain_before) = part(0, STUCK_ROWS.start);
    assert!(before < plain_before + 1.0, "{before} vs {plain_before}");
    // After it: the lost rotation shows, and the corrections take it out.
    let (after, _) = part(STUCK_ROWS.end, STUCK_ROWS.end + 500);
    let (end, _) = part(ROWS - 800, ROWS);
    assert!(after > 10.0 && end < 0.6 * after, "{after} then {end}");
}

/// The firmware's targets and the names of their output files.
const TARGETS: [&str; 2] = ["thumbv7em-none-eabihf", "riscv32imac-unknown-none-elf"];

#[test]
#[ignore = "needs the fw_imu output of .ci/run in $GYROSTAT_FIRMWARE_OUTPUT"]
fn boards_print_the_same_bits_as_the_host() {
    let dir = std::env::var("GYROSTAT_FIRMWARE_OUTPUT")
        .expect("GYROSTAT_FIRMWARE_OUTPUT must name the directory of the firmware output");
    let host = host_lines();
    assert_eq!(
        host.len(),
        (expected_counters().samples / PRINT_EVERY) as usize + 2
    );
    let expected = expected_counters();
    assert!(host.last().unwrap().starts_with("count "));
    for target in TARGETS {
        let path = std::path::Path::new(&dir).join(format!("imu-{target}.txt"));
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            text.lines().any(|l| l == "done"),
            "{target}: no `done` line"
        );
        let fw: Vec<String> = text
            .lines()
            .filter(|l| ["att ", "bias ", "count "].iter().any(|p| l.starts_with(p)))
            .map(str::to_owned)
            .collect();
        assert_eq!(fw, host, "{target}: output differs from the host's");
        println!(
            "{target}: {} lines identical to the host's; {expected:?}",
            fw.len()
        );
    }
}
