//! `synthesize`: a synthetic IMU log with exact truth, from a motion and a sensor spec.
//!
//! ```text
//! synthesize [--motion handheld|axes|rest|spin:WX,WY,WZ|FILE|-] [--sensor NAME|FILE]
//!     [--rate HZ] [--duration S] [--rest S] [--phases N] [--ramp S] [--q0 w,x,y,z]
//!     [--translation A] [--vibration A,F] [--taps A] [--magnet-pass M,D,V]
//!     [--magnet-fixed HX,HY,HZ[,T]] [--steel DX,DY,DZ] [--seed N] [--print-sensor]
//! ```
//! Run with `--help` for the full description.

use std::io::{self, Read, Write};
use std::process::ExitCode;

use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::motion::{Motion, MotionFile, Rotation, Timeline};
use gyrostat_tools::sensor_spec::{self, PRESETS, SensorSpec};
use gyrostat_tools::stream::{self, Csv};
use gyrostat_tools::synthesis::{Environment, MotionChoice, Options, RunError, Sample, Synth};

const CLI: Cli = Cli {
    name: "synthesize",
    help: HELP,
    flags: &[
        Flag::value("--motion"),
        Flag::value("--sensor"),
        Flag::value("--rate"),
        Flag::value("--duration"),
        Flag::value("--rest"),
        Flag::value("--phases"),
        Flag::value("--ramp"),
        Flag::value("--q0"),
        Flag::value("--translation"),
        Flag::value("--vibration"),
        Flag::value("--taps"),
        Flag::value("--magnet-pass"),
        Flag::value("--magnet-fixed"),
        Flag::value("--steel"),
        Flag::value("--seed"),
        Flag::switch("--print-sensor"),
        Flag::switch("--kinematics"),
    ],
};

const HELP: &str = "\
synthesize: a synthetic IMU log with exact truth (what a sensor of a given spec reads along a
closed-form or simulated motion)

USAGE:
    synthesize [--motion handheld|axes|rest|spin:WX,WY,WZ|FILE|-] [--sensor NAME|FILE]
               [--rate HZ] [--duration S] [--rest S] [--phases N] [--ramp S] [--q0 w,x,y,z]
               [--translation A] [--vibration A,F] [--taps A] [--magnet-pass M,D,V]
               [--magnet-fixed HX,HY,HZ[,T]] [--steel DX,DY,DZ] [--seed N] [--kinematics]
    synthesize --sensor NAME|FILE --print-sensor

    Writes CSV to stdout in BROAD's columns, so that `estimate --truth` and BROAD's score.py
    score it as they are:
        t_s,gyr_x_rad_s,gyr_y_rad_s,gyr_z_rad_s,acc_x_m_s2,acc_y_m_s2,acc_z_m_s2,
        mag_x_uT,mag_y_uT,mag_z_uT,opt_qw,opt_qx,opt_qy,opt_qz,movement
    t_s: the sample's time stamp (k/rate plus the clock jitter); gyro and accelerometer in the
    sensor frame (the specific force: +g up at rest); the magnetometer (empty between the
    samples of a slower mag_rate); opt_q: the true attitude at k/rate, sensor -> earth (ENU:
    x east, y magnetic north, z up; v_earth = q v q*); movement: 1 inside a movement phase.
    Same flags and seed: the same bytes. --kinematics appends the true motion at each row:
        true_gyr_x_rad_s,...  the body rate (sensor frame, before the sensor's errors)
        pos_x_m,...           the position (earth frame, m; the translation)
        lin_acc_x_m_s2,...    the linear acceleration (earth frame, without gravity)
        body_acc_x_m_s2,...   vibration and taps (sensor frame)
    so that the accelerometer's truth is R(q)^T (lin_acc + g z) + body_acc.

MOTION:
    The log is a rest phase (--rest, default 5 s), then --phases (default 2) movement phases
    of --duration seconds (default 30) with --rest seconds of rest between them; each phase
    starts and ends with a raised-cosine ramp of --ramp seconds (default 0.5, 0 allowed).
    --motion handheld   (default) a smooth, non-repeating hand-held rotation: yaw, pitch and
                        roll each a sum of three seeded sines (|pitch| < 70 deg, rates up to
                        about 4 rad/s), exact body rates in closed form
    --motion axes       phase i turns once about the sensor's x, y, z axis (i mod 3)
    --motion rest       no rotation (with --translation, --vibration, --taps: those alone)
    --motion spin:WX,WY,WZ
                        a constant body rate (rad/s) during the movement phases
    --motion FILE|-     a motion file (stdin for -): simulate's CSV (a header with
                        t,qw,qx,qy,qz,w1,w2,w3; any scenario: `simulate ... | synthesize
                        --motion -`). Its rows, uniformly spaced, are the samples (the rate is
                        theirs: --rate, --duration, --phases not allowed) after --rest seconds
                        at the first attitude; the magnetometer's delay interpolates by slerp.
    --q0 w,x,y,z        the attitude at the start (default 1,0,0,0; unit norm within 1e-6;
                        not with a motion file, which has its own)
    --translation A     a translation of amplitude scale A metres during the movement phases
                        (three seeded sines per earth axis, 0.6 A + 0.3 A + 0.15 A, 1-7 rad/s:
                        about 15 A m/s^2 peak acceleration), exact in closed form
    --vibration A,F     vibration: a body-frame acceleration of amplitude A m/s^2 near F Hz
                        (F, 1.13 F, 0.89 F on x, y, z) during the movement phases
    --taps A            taps: every 1.5-3 s of a movement phase, a body-frame acceleration
                        A e^(-u/10 ms) sin(2 pi 60 Hz u) for 0.1 s along a seeded direction
                        (its peak is 0.68 A, 3.5 ms after the tap)

MAGNETIC DISTURBANCES:
    --magnet-pass M,D,V  in the middle of each movement phase a magnetic dipole of M A m^2
                        passes along the east axis at V m/s, D m north of the sensor at its
                        closest (a 1 cm^3 NdFeB magnet is about 1 A m^2: 25 uT at 0.2 m)
    --steel DX,DY,DZ    the field changes by up to (DX,DY,DZ) uT (earth frame), a smooth bump
                        over the middle half of each movement phase (near steel)
    --magnet-fixed HX,HY,HZ[,T]
                        a magnet fixed on the device from time T on (default: a third into
                        the first movement phase): HX,HY,HZ uT of extra hard iron

SENSOR:
    --sensor NAME|FILE  the sensor spec: a preset (ideal, consumer, industrial, tactical; each
                        cites its datasheet figures: see --print-sensor) or a spec file
                        (`key = value[, value...]  # comment`; the keys rate, clock_jitter,
                        gyro_/accel_ noise_density, bias_instability, rate_random_walk, bias,
                        scale, misalignment, range, lsb; mag_noise, mag_hard_iron,
                        mag_soft_iron, mag_delay, mag_range, mag_lsb, mag_rate; field (ENU uT),
                        gravity; every key optional and ideal by default). Default: ideal.
                        The error keys are the calibration that undoes the sensor (the format
                        of `estimate --calibration`): the sensor reads raw = (M diag(s))^-1
                        true + b + noise (magnetometer S^-1 true + h + noise), clipped to
                        +-range, rounded to a multiple of lsb.
    --rate HZ           the output data rate (default: the spec's rate)
    --print-sensor      print the spec's text (a preset's with its sources) and exit
    --seed N            the seed of the motion, the noise and the jitter (default 0)
    --kinematics        append the true motion's columns (see above)

ERRORS:
    A bad command line, spec file or motion file: `error: reason` on stderr (a file's line
    named: `error: --sensor F: line N: reason`), exit status 2, no output.
";

fn main() -> ExitCode {
    let f = match CLI.command_line() {
        Ok(f) => f,
        Err(status) => return status,
    };
    let (synth, text) = match arguments(&f) {
        Ok(x) => x,
        Err(e) => return flags::usage_error(&e),
    };
    if f.switch("--print-sensor") {
        return match stream::print_text(&text) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                flags::error(&format!("writing stdout: {e}"));
                ExitCode::FAILURE
            }
        };
    }
    match write_log(&synth, f.switch("--kinematics")) {
        Ok(()) => ExitCode::SUCCESS,
        Err(RunError::Sink(e)) if stream::is_closed_pipe(&e) => ExitCode::SUCCESS,
        Err(RunError::Sink(e)) => {
            flags::error(&format!("writing stdout: {e}"));
            ExitCode::FAILURE
        }
        Err(RunError::Noise(e)) => flags::usage_error(&format!("--sensor: {e}")),
    }
}

fn three(flag: &str, v: &str, fields: &str) -> Result<[f64; 3], String> {
    flags::numbers::<3>(flag, v, fields)
}

fn non_negative(flag: &str, v: &str) -> Result<f64, String> {
    let x = flags::number(flag, v)?;
    if x < 0.0 {
        return Err(format!("{flag}: must be >= 0, got {}", v.trim()));
    }
    Ok(x)
}

/// The log of the flags given, and the sensor spec's text.
fn arguments(f: &Flags) -> Result<(Synth, String), String> {
    let (sensor, text): (SensorSpec, String) = match f.value("--sensor") {
        Some(v) => sensor_spec::read("--sensor", v.trim())?,
        None => sensor_spec::read("--sensor", "ideal")?,
    };
    if f.switch("--print-sensor") {
        if let Some(other) = f
            .names()
            .find(|n| *n != "--sensor" && *n != "--print-sensor")
        {
            return Err(format!("--print-sensor takes only --sensor, not {other}"));
        }
        return Ok((placeholder(sensor), text));
    }
    let motion_arg = f.value("--motion").map(str::trim).unwrap_or("handheld");
    let motion = match MotionChoice::named(motion_arg).ok_or(motion_arg) {
        Ok(named) => named,
        Err(spin) if spin.starts_with("spin:") => {
            MotionChoice::Spin(three("--motion", &spin["spin:".len()..], "WX,WY,WZ")?)
        }
        Err(path) => {
            let text = if path == "-" {
                let mut s = String::new();
                io::stdin()
                    .read_to_string(&mut s)
                    .map_err(|e| format!("--motion -: reading stdin: {e}"))?;
                s
            } else {
                std::fs::read_to_string(path).map_err(|e| format!("--motion {path}: {e}"))?
            };
            MotionChoice::File(
                MotionFile::parse(&text).map_err(|e| format!("--motion {path}: {e}"))?,
            )
        }
    };
    let options = Options {
        motion,
        sensor,
        rate: f.get("--rate", flags::positive)?,
        duration: f.get("--duration", flags::positive)?,
        rest: f.get("--rest", non_negative)?,
        phases: f.get("--phases", flags::count)?,
        ramp: f.get("--ramp", non_negative)?,
        q0: f.get("--q0", |fl, v| flags::numbers::<4>(fl, v, "w,x,y,z"))?,
        translation: f.get("--translation", flags::positive)?,
        vibration: f.get("--vibration", |fl, v| flags::numbers::<2>(fl, v, "A,F"))?,
        taps: f.get("--taps", flags::positive)?,
        magnet_pass: f.get("--magnet-pass", |fl, v| three(fl, v, "M,D,V"))?,
        magnet_fixed: f.get("--magnet-fixed", flags::list)?,
        steel: f.get("--steel", |fl, v| three(fl, v, "DX,DY,DZ"))?,
        seed: f.get("--seed", flags::count)?.unwrap_or(0),
    };
    Ok((options.build()?, text))
}

fn placeholder(spec: SensorSpec) -> Synth {
    Synth {
        motion: Motion {
            timeline: Timeline {
                rest: 0.0,
                duration: 1.0,
                phases: 0,
                ramp: 0.0,
            },
            q0: [1.0, 0.0, 0.0, 0.0],
            rotation: Rotation::Rest,
            translation: None,
            vibration: None,
            taps: None,
        },
        env: Environment::default(),
        spec,
        seed: 0,
    }
}

/// The CSV header of a log (BROAD's columns).
pub const HEADER: &str = "t_s,gyr_x_rad_s,gyr_y_rad_s,gyr_z_rad_s,acc_x_m_s2,acc_y_m_s2,acc_z_m_s2,mag_x_uT,mag_y_uT,mag_z_uT,opt_qw,opt_qx,opt_qy,opt_qz,movement";

/// The columns `--kinematics` appends.
pub const KINEMATICS: &str = ",true_gyr_x_rad_s,true_gyr_y_rad_s,true_gyr_z_rad_s,pos_x_m,pos_y_m,pos_z_m,lin_acc_x_m_s2,lin_acc_y_m_s2,lin_acc_z_m_s2,body_acc_x_m_s2,body_acc_y_m_s2,body_acc_z_m_s2";

fn write_log(synth: &Synth, kinematics: bool) -> Result<(), RunError<io::Error>> {
    let mut out = Csv::stdout();
    let extra = if kinematics { KINEMATICS } else { "" };
    writeln!(out, "{HEADER}{extra}").map_err(RunError::Sink)?;
    synth.run(|s: &Sample| {
        write!(out, "{:.9},", s.stamp)?;
        for x in s.gyr.iter().chain(&s.acc) {
            write!(out, "{x:?},")?;
        }
        match s.mag {
            Some(m) => write!(out, "{:?},{:?},{:?},", m[0], m[1], m[2])?,
            None => write!(out, ",,,")?,
        }
        write!(
            out,
            "{:?},{:?},{:?},{:?},{}",
            s.q[0],
            s.q[1],
            s.q[2],
            s.q[3],
            u8::from(s.moving)
        )?;
        if kinematics {
            let k = &s.kin;
            for x in k.w.iter().chain(&k.p).chain(&k.a).chain(&k.a_body) {
                write!(out, ",{:?}", x + 0.0)?;
            }
        }
        writeln!(out)?;
        out.row_done()
    })?;
    out.flush().map_err(RunError::Sink)
}

// The preset names appear in the help text; keep them in step.
const _: () = assert!(PRESETS.len() == 4);
