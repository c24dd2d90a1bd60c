//! `propagate`: integrate gyro increments or rate samples from stdin into attitudes on stdout.
//!
//! ```text
//! cargo run --release --example propagate -- --input increments|rates --algo ALGO --dt SECONDS \
//!     [--q0 w,x,y,z] [--f32 | --fixed] [--every N]
//! ```
//! Run with `--help` for the full description of the input and output formats.

use std::fmt::Debug;
use std::io::{self, BufRead, BufWriter, Write};
use std::process::ExitCode;
use std::str::FromStr;

use gyrostat::fixed::Q30;
use gyrostat::propagation::{
    ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::{Quat, Real, UnitQuat, Vec3};

const HELP: &str = "\
propagate: integrate gyro increments or rate samples into attitude quaternions

USAGE:
    propagate --input increments|rates --algo ALGO --dt SECONDS [--q0 w,x,y,z] [--f32 | --fixed]
              [--every N]

INPUT (stdin): one sample per line, three comma-separated numbers `dx,dy,dz` (body frame).
    --input increments   line k (0-based) is the integral of omega over [k*dt, (k+1)*dt], rad
    --input rates        line k is omega(k*dt), rad/s
    Blanks around numbers are allowed; a bad row stops the run with
    `error: line N: reason` on stderr (N is 1-based) and exit status 1.

ALGO for --input increments:
    exp       one exponential per increment, no coning correction
    coning1   one increment per update with the previous-interval correction dth(k-1) x dth(k) / 12
    coning2   2-sample rule, one attitude update per 2 increments
    coning3   3-sample rule, one attitude update per 3 increments
    coning4   4-sample rule, one attitude update per 4 increments
ALGO for --input rates (each integrates from t = 0 to the last sample's time):
    magnus4   4th-order Magnus (one exponential per sample interval)
    cf4       commutator-free 4th order (two exponentials, weights 1/4 +- sqrt(3)/6)
    rk4       classical RK4 on the quaternion, renormalised
    The rates at the Gauss nodes / midpoints come from the cubic interpolant through four
    consecutive samples (quadratic for a 3-sample record, linear for a 2-sample one).

OPTIONS:
    --dt SECONDS   sample interval, finite and > 0 (required)
    --q0 w,x,y,z   initial attitude (scalar first, maps body to lab), default 1,0,0,0;
                   its norm must be within 1e-3 of 1 (it is then normalised exactly)
    --f32          run the propagation in f32 (default f64)
    --fixed        run the propagation in Q1.30 fixed point, the integer code of the firmware
                   (--input increments only): each number is rounded to the nearest multiple of
                   2^-30 rad (ties to even; |value| < 2 rad, else a row error), q0 likewise after
                   its exact normalisation in f64, and the attitude gets the fast
                   renormalisation q + q(1 - |q|^2)/2 after every update, as on the firmware.
                   The output is bit for bit what gyrostat's fixed-point firmware computes from
                   the same increments: every printed number is an exact multiple of 2^-30.
    --every N      print every N-th sample (N >= 1, default 1)
    --help         print this text

OUTPUT (stdout): `k,qw,qx,qy,qz` after sample k (0-based) whenever k is a multiple of N, and
    always after the last sample consumed. Numbers are printed in the shortest form that
    round-trips to the same f64 (or f32 with --f32). The attitude is renormalised exactly after
    every update (with --fixed: the fast renormalisation, see above).
    increments: the line for sample k is the attitude at time (k+1)*dt, after increments 0..=k.
        coningN updates the attitude once per N increments (after samples N-1, 2N-1, ...). A
        line printed inside a group, and the final line if the input ends inside a group,
        applies the pending increments with the highest-order rule that fits them (1 pending:
        coning1 with the increment before it; 2: coning2; 3: coning3), so every increment
        consumed is integrated; inside-group lines are not fed back into later updates.
    rates: the line for sample k is the attitude at time k*dt (k = 0 prints q0).
";

#[derive(Clone, Copy)]
enum Algo {
    Increments(ConingRule),
    Rates(RateMethod),
}

/// The arithmetic a run uses.
#[derive(Clone, Copy, PartialEq)]
enum Arith {
    F64,
    F32,
    Fixed,
}

struct Args {
    algo: Algo,
    dt: f64,
    q0: [f64; 4],
    arith: Arith,
    every: u64,
}

fn parse_args() -> Result<Option<Args>, String> {
    let mut input: Option<String> = None;
    let mut algo: Option<String> = None;
    let mut dt: Option<f64> = None;
    let mut q0 = [1.0, 0.0, 0.0, 0.0];
    let mut arith = Arith::F64;
    let mut every = 1u64;
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().ok_or_else(|| format!("{name} needs a value"));
        match a.as_str() {
            "--help" | "-h" => return Ok(None),
            "--input" => input = Some(value("--input")?),
            "--algo" => algo = Some(value("--algo")?),
            "--dt" => {
                let v = value("--dt")?;
                let x: f64 = v
                    .trim()
                    .parse()
                    .map_err(|_| format!("--dt: invalid number '{v}'"))?;
                if !x.is_finite() || x <= 0.0 {
                    return Err(format!("--dt: must be finite and > 0, got {v}"));
                }
                dt = Some(x);
            }
            "--q0" => {
                let v = value("--q0")?;
                let parts: Vec<&str> = v.split(',').collect();
                if parts.len() != 4 {
                    return Err(format!(
                        "--q0: expected 4 comma-separated numbers w,x,y,z, found {}",
                        parts.len()
                    ));
                }
                for (slot, p) in q0.iter_mut().zip(&parts) {
                    *slot = p
                        .trim()
                        .parse()
                        .map_err(|_| format!("--q0: invalid number '{}'", p.trim()))?;
                }
            }
            "--f32" | "--fixed" => {
                if arith != Arith::F64 {
                    return Err("--f32 and --fixed exclude each other".into());
                }
                arith = if a == "--f32" {
                    Arith::F32
                } else {
                    Arith::Fixed
                };
            }
            "--every" => {
                let v = value("--every")?;
                every = v
                    .trim()
                    .parse()
                    .map_err(|_| format!("--every: invalid count '{v}'"))?;
                if every == 0 {
                    return Err("--every: must be at least 1".into());
                }
            }
            other => return Err(format!("unknown argument '{other}' (see --help)")),
        }
    }
    let input = input.ok_or("--input is required (increments or rates)")?;
    let algo_name = algo.ok_or("--algo is required")?;
    let dt = dt.ok_or("--dt is required")?;
    let algo = match (input.as_str(), algo_name.as_str()) {
        ("increments", "exp") => Algo::Increments(ConingRule::Exp),
        ("increments", "coning1") => Algo::Increments(ConingRule::OnePlusPrevious),
        ("increments", "coning2") => Algo::Increments(ConingRule::TwoSample),
        ("increments", "coning3") => Algo::Increments(ConingRule::ThreeSample),
        ("increments", "coning4") => Algo::Increments(ConingRule::FourSample),
        ("rates", "magnus4") => Algo::Rates(RateMethod::Magnus4),
        ("rates", "cf4") => Algo::Rates(RateMethod::Cf4),
        ("rates", "rk4") => Algo::Rates(RateMethod::Rk4),
        ("increments", a) => {
            return Err(format!(
                "--algo '{a}' is not an increments algorithm (exp, coning1, coning2, coning3, coning4)"
            ));
        }
        ("rates", a) => {
            return Err(format!(
                "--algo '{a}' is not a rates algorithm (magnus4, cf4, rk4)"
            ));
        }
        (i, _) => return Err(format!("--input must be increments or rates, got '{i}'")),
    };
    if arith == Arith::Fixed && matches!(algo, Algo::Rates(_)) {
        return Err("--fixed supports --input increments only".into());
    }
    Ok(Some(Args {
        algo,
        dt,
        q0,
        arith,
        every,
    }))
}

/// Parses one `dx,dy,dz` row.
fn parse_row<T: Real + FromStr>(line: &str) -> Result<Vec3<T>, String> {
    let parts: Vec<&str> = line.split(',').collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected 3 comma-separated numbers dx,dy,dz, found {}",
            parts.len()
        ));
    }
    let mut v = [T::ZERO; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        let p = p.trim();
        let x: T = p.parse().map_err(|_| format!("invalid number '{p}'"))?;
        if !x.is_finite() {
            return Err(format!("non-finite value '{p}'"));
        }
        *slot = x;
    }
    Ok(Vec3::new(v[0], v[1], v[2]))
}

struct Printer<W: Write> {
    out: W,
    every: u64,
    last_printed: Option<u64>,
}

impl<W: Write> Printer<W> {
    fn print<T: Debug>(&mut self, k: u64, [w, x, y, z]: [T; 4]) -> io::Result<()> {
        self.last_printed = Some(k);
        writeln!(self.out, "{k},{w:?},{x:?},{y:?},{z:?}")
    }
    fn due(&self, k: u64) -> bool {
        k.is_multiple_of(self.every)
    }
}

enum Failure {
    Usage(String),
    Row(u64, String),
    Io(io::Error),
}

impl From<io::Error> for Failure {
    fn from(e: io::Error) -> Self {
        Failure::Io(e)
    }
}

fn run<T: Real + FromStr + Debug>(args: &Args) -> Result<(), Failure> {
    let t = |x: f64| T::from_f64(x);
    let q0 = UnitQuat::try_from_near_unit(
        Quat::new(t(args.q0[0]), t(args.q0[1]), t(args.q0[2]), t(args.q0[3])),
        t(1e-3),
    )
    .map_err(|e| Failure::Usage(format!("--q0: {e}: its norm must be within 1e-3 of 1")))?;
    let norm = Normalization::Exact;
    let stdin = io::stdin().lock();
    let mut p = Printer {
        out: BufWriter::new(io::stdout().lock()),
        every: args.every,
        last_printed: None,
    };
    let mut k: u64 = 0; // samples consumed
    let result = (|| -> Result<(), Failure> {
        match args.algo {
            Algo::Increments(rule) => {
                let mut integ = IncrementIntegrator::new(q0, rule, norm);
                for line in stdin.lines() {
                    let line = line?;
                    let v = parse_row::<T>(&line).map_err(|e| Failure::Row(k + 1, e))?;
                    integ
                        .push(v)
                        .map_err(|e| Failure::Row(k + 1, e.to_string()))?;
                    if p.due(k) {
                        p.print(k, integ.provisional_attitude().to_array())?;
                    }
                    k += 1;
                }
                if k > 0 && p.last_printed != Some(k - 1) {
                    p.print(k - 1, integ.flush().to_array())?;
                }
            }
            Algo::Rates(method) => {
                let mut integ = RateIntegrator::new(q0, method, norm, t(args.dt))
                    .map_err(|e| Failure::Usage(format!("--dt: {e}")))?;
                let mut reached: u64 = 0; // next sample index whose attitude is due
                let mut last = q0;
                for line in stdin.lines() {
                    let line = line?;
                    let v = parse_row::<T>(&line).map_err(|e| Failure::Row(k + 1, e))?;
                    for q in integ
                        .push(v)
                        .map_err(|e| Failure::Row(k + 1, e.to_string()))?
                    {
                        if p.due(reached) {
                            p.print(reached, q.to_array())?;
                        }
                        last = q;
                        reached += 1;
                    }
                    k += 1;
                }
                for q in integ.finish() {
                    if p.due(reached) {
                        p.print(reached, q.to_array())?;
                    }
                    last = q;
                    reached += 1;
                }
                if k > 0 && p.last_printed != Some(k - 1) {
                    p.print(k - 1, last.to_array())?;
                }
            }
        }
        Ok(())
    })();
    p.out.flush()?;
    result
}

/// `--fixed`: the increment path in Q1.30, the firmware's integer code.
fn run_fixed(args: &Args) -> Result<(), Failure> {
    let Algo::Increments(rule) = args.algo else {
        return Err(Failure::Usage(
            "--fixed supports --input increments only".into(),
        ));
    };
    let [w, x, y, z] = args.q0;
    let q0 = UnitQuat::try_from_near_unit(Quat::new(w, x, y, z), 1e-3)
        .map_err(|e| Failure::Usage(format!("--q0: {e}: its norm must be within 1e-3 of 1")))?;
    let q0 = UnitQuat::<Q30>::try_from_f64(q0).map_err(|e| Failure::Usage(format!("--q0: {e}")))?;
    let mut integ = IncrementIntegrator::new(q0, rule, Normalization::Fast);
    let stdin = io::stdin().lock();
    let mut p = Printer {
        out: BufWriter::new(io::stdout().lock()),
        every: args.every,
        last_printed: None,
    };
    let exact = |q: UnitQuat<Q30>| q.to_f64().to_array();
    let mut k: u64 = 0;
    let result = (|| -> Result<(), Failure> {
        for line in stdin.lines() {
            let line = line?;
            let v = parse_row::<f64>(&line).map_err(|e| Failure::Row(k + 1, e))?;
            let v = Vec3::<Q30>::try_from_f64(v)
                .map_err(|e| Failure::Row(k + 1, format!("{e} (Q1.30 holds |value| < 2 rad)")))?;
            integ
                .push(v)
                .map_err(|e| Failure::Row(k + 1, e.to_string()))?;
            if p.due(k) {
                p.print(k, exact(integ.provisional_attitude()))?;
            }
            k += 1;
        }
        if k > 0 && p.last_printed != Some(k - 1) {
            p.print(k - 1, exact(integ.flush()))?;
        }
        Ok(())
    })();
    p.out.flush()?;
    result
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(Some(a)) => a,
        Ok(None) => {
            print!("{HELP}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let r = match args.arith {
        Arith::F64 => run::<f64>(&args),
        Arith::F32 => run::<f32>(&args),
        Arith::Fixed => run_fixed(&args),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        Err(Failure::Row(n, e)) => {
            eprintln!("error: line {n}: {e}");
            ExitCode::from(1)
        }
        Err(Failure::Io(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
