//! `propagate`: integrate gyro increments or rate samples from stdin into attitudes on stdout.
//!
//! ```text
//! propagate --input increments|rates --algo ALGO --dt SECONDS [--q0 w,x,y,z] [--f32 | --fixed] \
//!     [--compensated] [--every N]
//! ```
//! Run with `--help` for the full description of the input and output formats.

use std::fmt::Debug;
use std::io::{self, Write};
use std::process::ExitCode;
use std::str::FromStr;

use gyrostat::fixed::{CarriedAttitude, IncrementQuantizer, Q30};
use gyrostat::propagation::{
    CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization, PropagatedAttitude,
    RateIntegrator, RateMethod,
};
use gyrostat::{Quat, Real, UnitQuat, Vec3};
use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::stream::{self, Csv, Lines};

const CLI: Cli = Cli {
    name: "propagate",
    help: HELP,
    flags: &[
        Flag::value("--input"),
        Flag::value("--algo"),
        Flag::value("--dt"),
        Flag::value("--q0"),
        Flag::switch("--f32"),
        Flag::switch("--fixed"),
        Flag::switch("--compensated"),
        Flag::value("--every"),
    ],
};

const HELP: &str = "\
propagate: integrate gyro increments or rate samples into attitude quaternions

USAGE:
    propagate --input increments|rates --algo ALGO --dt SECONDS [--q0 w,x,y,z] [--f32 | --fixed]
              [--compensated] [--every N]

    Flags take their value as the next argument or after `=` (--dt 0.01, --dt=0.01); a flag
    given twice is an error.

INPUT (stdin): one sample per line, three comma-separated numbers `dx,dy,dz` (body frame).
    --input increments   sample k (0-based) is the integral of omega over [k*dt, (k+1)*dt], rad
    --input rates        sample k is omega(k*dt), rad/s
    Blanks around numbers are allowed. Blank lines (empty or only blanks) are skipped, the last
    one too; they count for line numbers but are not samples.

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
                   (--input increments only): each number is converted to the nearest multiple
                   of 2^-30 rad with the remainder of the previous rows added and the new
                   remainder carried to the next row (gyrostat::fixed::IncrementQuantizer: the
                   sum of the converted increments stays within 2^-31 of the sum of the given
                   ones; |value| < 2 rad, else a row error), q0 is rounded likewise (after its
                   exact normalisation in f64), and the attitude is a
                   gyrostat::fixed::CarriedAttitude: every update carries the low bits its
                   roundings discard into the next one and folds the fast renormalisation
                   q + q(1 - |q|^2)/2 into the increment, so the rounding does not drift.
                   The output is bit for bit what gyrostat's fixed-point firmware computes from
                   the same increments: every printed number is an exact multiple of 2^-30.
    --compensated  carry the attitude's rounding error beside it (compensated accumulation,
                   gyrostat::propagation::compensated): every update adds its increment
                   without losing its rounding, so an f32 attitude stays within about 1e-5 rad
                   over an hour at 1 kHz where the plain f32 attitude drifts up to 2e-2 rad (it
                   rounds q the same way again and again); the rate methods also take --dt's
                   f32 rounding into account. Without --f32 it does the same in f64 (not with
                   --fixed). Costs more per update; the output format is unchanged.
    --every N      print every N-th sample (N >= 1, default 1)
    --help         print this text

OUTPUT (stdout): `k,qw,qx,qy,qz` after sample k (0-based) whenever k is a multiple of N, and
    always after the last sample consumed (the last valid one when the run stops at an error).
    Rows are written as they are computed (flushed at least every 0.1 s and whenever the input
    stalls). Numbers are printed in the shortest form that
    round-trips to the same f64 (or f32 with --f32). The attitude is renormalised exactly after
    every update (with --compensated: the compensated pair is, and the line is its part rounded
    to f64 or f32, unit within a few ulp; with --fixed: the fast renormalisation folded into each update, see above).
    increments: the line for sample k is the attitude at time (k+1)*dt, after increments 0..=k.
        coningN updates the attitude once per N increments (after samples N-1, 2N-1, ...). A
        line printed inside a group, and the final line if the input ends inside a group,
        applies the pending increments with the highest-order rule that fits them (1 pending:
        coning1 with the increment before it; 2: coning2; 3: coning3), so every increment
        consumed is integrated; inside-group lines are not fed back into later updates.
    rates: the line for sample k is the attitude at time k*dt (k = 0 prints q0).

ERRORS (stderr, nothing else on stdout after them):
    error: line N: reason      (N counts every line from 1, blank ones too) exit status 1
        A line that is not three finite numbers, not UTF-8 text, or longer than 1 MiB, a sample
        that turns the body by more than half a turn (coning rules and rate methods: their
        series are meaningless there), an --algo exp increment so long that its angle is not
        known to 1e-3 rad (beyond 4.5e12 rad in f64, 8.4e3 rad with --f32), and a sample whose
        attitude would not be a finite unit quaternion stop the run there. The rows before it are kept, and the attitude
        after the last valid sample is printed as promised above (after a malformed line the
        samples before it are integrated to their end, as if the input ended there).
    error: reason              bad command-line arguments: exit status 2, no output
    When stdout is closed early (a pipe into `head`), the run stops quietly with status 0.
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
    compensated: bool,
    every: u64,
}

/// The arguments of a run, from the flags given.
fn arguments(f: &Flags) -> Result<Args, String> {
    let input = f.value("--input");
    let algo = f.value("--algo");
    let dt = f.get("--dt", flags::positive)?;
    let q0 = f
        .get("--q0", |flag, v| flags::numbers::<4>(flag, v, "w,x,y,z"))?
        .unwrap_or([1.0, 0.0, 0.0, 0.0]);
    let arith = match (f.switch("--f32"), f.switch("--fixed")) {
        (true, true) => return Err("--f32 and --fixed exclude each other".into()),
        (true, false) => Arith::F32,
        (false, true) => Arith::Fixed,
        (false, false) => Arith::F64,
    };
    let compensated = f.switch("--compensated");
    let every = f.get("--every", flags::at_least_one)?.unwrap_or(1);
    let input = input.ok_or("--input is required (increments or rates)")?;
    let algo_name = algo.ok_or("--algo is required")?;
    let dt = dt.ok_or("--dt is required")?;
    let algo = match (input, algo_name) {
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
    if arith == Arith::Fixed && compensated {
        return Err(
            "--compensated needs floating point (--f32 or the default f64), not --fixed".into(),
        );
    }
    Ok(Args {
        algo,
        dt,
        q0,
        arith,
        compensated,
        every,
    })
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

/// The rows on stdout.
struct Printer {
    out: Csv,
    every: u64,
    last_printed: Option<u64>,
}

impl Printer {
    fn print<T: Debug>(&mut self, k: u64, [w, x, y, z]: [T; 4]) -> io::Result<()> {
        self.last_printed = Some(k);
        writeln!(self.out, "{k},{w:?},{x:?},{y:?},{z:?}")?;
        self.out.row_done()
    }
    fn due(&self, k: u64) -> bool {
        k.is_multiple_of(self.every)
    }
    /// Prints `q` as the attitude after sample `k` unless that row is out already.
    fn print_last<T: Debug>(&mut self, k: u64, q: [T; 4]) -> io::Result<()> {
        if self.last_printed == Some(k) {
            return Ok(());
        }
        self.print(k, q)
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

/// The next sample of the input with its line number, skipping blank lines; `Ok(None)` at the
/// end. Pending output is flushed before a read that may wait.
fn next_sample<T: Real + FromStr, R: io::Read>(
    lines: &mut Lines<R>,
    out: &mut Csv,
) -> Result<Option<(u64, Vec3<T>)>, Failure> {
    loop {
        if lines.will_read() {
            out.flush()?;
        }
        let Some((n, line)) = lines.next_line()? else {
            return Ok(None);
        };
        match line {
            Ok(text) if text.trim().is_empty() => continue,
            Ok(text) => {
                return parse_row(text)
                    .map(|v| Some((n, v)))
                    .map_err(|e| Failure::Row(n, e));
            }
            Err(reason) => return Err(Failure::Row(n, reason)),
        }
    }
}

/// `q` when it is a finite unit quaternion; otherwise the error of the sample on line `n`.
fn checked<T: Real + Debug>(q: UnitQuat<T>, n: u64, what: &str) -> Result<UnitQuat<T>, Failure> {
    let c = q.to_array();
    let n2 = c.iter().fold(T::ZERO, |acc, &x| acc + x * x);
    // The attitude is renormalised exactly after every update: anything visibly off unit norm
    // (a collapsed or overflowed norm) is a failed update.
    if c.iter().all(|x| x.is_finite()) && (n2 - T::ONE).abs() <= T::from_f64(1e-3) {
        return Ok(q);
    }
    Err(Failure::Row(
        n,
        format!(
            "the attitude {what} is not a finite unit quaternion ({:?}): the {} too large for \
             this step",
            c,
            if what.contains("time") {
                "rates or --dt are"
            } else {
                "increments are"
            }
        ),
    ))
}

/// The largest rounding of one increment's turn angle the tool accepts (rad). An angle `θ` is
/// held to `θ·ε` of the run's type, and the attitude of that sample can be no better: beyond
/// this (`θ > 1e-3/ε`: 4.5e12 rad in f64, 8.4e3 rad in f32) its rows would be noise however
/// exactly the rule computes. Only `--algo exp` needs the check: the library applies an exact
/// exponential to an increment of any length, while the coning rules and the rate methods
/// reject a sample beyond half a turn themselves (`StepTooLong`).
const TURN_RESOLUTION: f64 = 1e-3;

/// Checks that the increment `v` turns the body by an angle whose rounding in `T` stays within
/// [`TURN_RESOLUTION`].
fn resolvable<T: Real>(v: Vec3<T>, n: u64) -> Result<(), Failure> {
    let [x, y, z] = v.to_array().map(|c| c.to_f64());
    let turn = x.hypot(y).hypot(z);
    let limit = TURN_RESOLUTION / T::EPSILON.to_f64();
    if turn <= limit {
        return Ok(());
    }
    Err(Failure::Row(
        n,
        format!(
            "the increment turns the body {turn:.3e} rad in one sample: beyond {limit:.2e} rad \
             the angle itself is not known to {TURN_RESOLUTION:e} rad in {}",
            if T::EPSILON.to_f64() < 1e-10 {
                "f64"
            } else {
                "f32"
            }
        ),
    ))
}

/// Integrates increments; the outcome of the input (`Err(Failure::Row)` at a bad line) after the
/// rows it allows are printed.
fn increments<T, A, R>(
    lines: &mut Lines<R>,
    p: &mut Printer,
    q0: UnitQuat<T>,
    rule: ConingRule,
) -> Result<(), Failure>
where
    T: Real + FromStr + Debug,
    A: PropagatedAttitude<T> + From<UnitQuat<T>>,
    R: io::Read,
{
    let mut integ = IncrementIntegrator::new(A::from(q0), rule, Normalization::Exact);
    let mut k: u64 = 0; // samples consumed
    let mut last = q0; // the attitude after sample k - 1
    let mut n = 0; // the line of the latest sample
    let stop = loop {
        let v = match next_sample::<T, R>(lines, &mut p.out) {
            Ok(Some((line, v))) => {
                n = line;
                v
            }
            Ok(None) => break None,
            // A rejected line leaves the integrator as it was: end the record there.
            Err(Failure::Row(n, e)) => break Some(Failure::Row(n, e)),
            Err(e) => return Err(e),
        };
        if rule == ConingRule::Exp
            && let Err(e) = resolvable(v, n)
        {
            break Some(e);
        }
        let q = integ
            .push(v)
            .map_err(|e| Failure::Row(n, e.to_string()))
            .and_then(|_| checked(integ.provisional_attitude(), n, "after this sample"));
        let q = match q {
            Ok(q) => q,
            Err(e) => {
                // The integrator is spoilt: the attitude after the previous sample is the last.
                if k > 0 {
                    p.print_last(k - 1, last.to_array())?;
                }
                return Err(e);
            }
        };
        if p.due(k) {
            p.print(k, q.to_array())?;
        }
        last = q;
        k += 1;
    };
    if k > 0 {
        p.print_last(
            k - 1,
            checked(integ.flush(), n, "after the last sample")?.to_array(),
        )?;
    }
    stop.map_or(Ok(()), Err)
}

/// Integrates rate samples; like [`increments`].
fn rates<T, A, R>(
    lines: &mut Lines<R>,
    p: &mut Printer,
    q0: UnitQuat<T>,
    method: RateMethod,
    args_dt: f64,
) -> Result<(), Failure>
where
    T: Real + FromStr + Debug,
    A: PropagatedAttitude<T> + From<UnitQuat<T>>,
    R: io::Read,
{
    let dt = T::from_f64(args_dt);
    // The step's rounding remainder in T (zero when --dt is exact in T).
    let dt_lo = T::from_f64(args_dt - dt.to_f64());
    let mut integ = RateIntegrator::try_new(A::from(q0), method, Normalization::Exact, dt)
        .and_then(|i| i.try_with_step_remainder(dt_lo))
        .map_err(|e| Failure::Usage(format!("--dt: {e}")))?;
    let mut reached: u64 = 0; // the next sample index whose attitude is due
    let mut last = q0;
    let mut n = 0; // the line of the latest sample
    let mut emit = |p: &mut Printer, q: UnitQuat<T>, n: u64| -> Result<(), Failure> {
        let q = checked(q, n, &format!("at the time of sample {reached}"))?;
        if p.due(reached) {
            p.print(reached, q.to_array())?;
        }
        last = q;
        reached += 1;
        Ok(())
    };
    let stop = loop {
        let v = match next_sample::<T, R>(lines, &mut p.out) {
            Ok(Some((line, v))) => {
                n = line;
                v
            }
            Ok(None) => break None,
            // A rejected line leaves the integrator as it was: end the record there.
            Err(Failure::Row(n, e)) => break Some(Failure::Row(n, e)),
            Err(e) => return Err(e),
        };
        let pushed = integ
            .push(v)
            .map_err(|e| Failure::Row(n, e.to_string()))
            .and_then(|qs| qs.into_iter().try_for_each(|q| emit(p, q, n)));
        if let Err(e) = pushed {
            if reached > 0 {
                p.print_last(reached - 1, last.to_array())?;
            }
            return Err(e);
        }
    };
    let finished = integ.finish().into_iter().try_for_each(|q| emit(p, q, n));
    if reached > 0 {
        p.print_last(reached - 1, last.to_array())?;
    }
    finished?;
    stop.map_or(Ok(()), Err)
}

/// Runs the propagation in `T`, the integrators carrying the attitude as `A` (a plain
/// `UnitQuat<T>` or a `CompensatedAttitude<T>`).
fn run<T: Real + FromStr + Debug, A: PropagatedAttitude<T> + From<UnitQuat<T>>>(
    args: &Args,
) -> Result<(), Failure> {
    let t = |x: f64| T::from_f64(x);
    let q0 = UnitQuat::try_from_near_unit(
        Quat::new(t(args.q0[0]), t(args.q0[1]), t(args.q0[2]), t(args.q0[3])),
        t(1e-3),
    )
    .map_err(|e| Failure::Usage(format!("--q0: {e}: its norm must be within 1e-3 of 1")))?;
    let dt = t(args.dt);
    if !(dt.is_finite() && dt > T::ZERO) {
        return Err(Failure::Usage(format!(
            "--dt: {:?} is not a positive finite f32",
            args.dt
        )));
    }
    let mut p = Printer {
        out: Csv::stdout(),
        every: args.every,
        last_printed: None,
    };
    let mut lines = Lines::new(io::stdin().lock());
    let result = match args.algo {
        Algo::Increments(rule) => increments::<T, A, _>(&mut lines, &mut p, q0, rule),
        Algo::Rates(method) => rates::<T, A, _>(&mut lines, &mut p, q0, method, args.dt),
    };
    finish(result, &mut p)
}

/// `--fixed`: the increment path in Q1.30, the firmware's integer code; lines, errors and the
/// last attitude as [`increments`] (a Q1.30 attitude is always finite: no check of it).
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
    let mut integ = IncrementIntegrator::new(CarriedAttitude::new(q0), rule, Normalization::Fast);
    let mut quantizer = IncrementQuantizer::<30>::new();
    let mut p = Printer {
        out: Csv::stdout(),
        every: args.every,
        last_printed: None,
    };
    let mut lines = Lines::new(io::stdin().lock());
    let exact = |q: UnitQuat<Q30>| q.to_f64().to_array();
    let mut k: u64 = 0; // samples consumed
    let mut last = q0; // the attitude after sample k - 1
    let result = (|| -> Result<(), Failure> {
        let stop = loop {
            let (n, v) = match next_sample::<f64, _>(&mut lines, &mut p.out) {
                Ok(Some(s)) => s,
                Ok(None) => break None,
                Err(Failure::Row(n, e)) => break Some(Failure::Row(n, e)),
                Err(e) => return Err(e),
            };
            let v = quantizer
                .try_quantize(v)
                .map_err(|e| Failure::Row(n, format!("{e} (Q1.30 holds |value| < 2 rad)")));
            let v = match v {
                Ok(v) => v,
                Err(e) => break Some(e),
            };
            if let Err(e) = integ.push(v) {
                if k > 0 {
                    p.print_last(k - 1, exact(last))?;
                }
                return Err(Failure::Row(n, e.to_string()));
            }
            last = integ.provisional_attitude();
            if p.due(k) {
                p.print(k, exact(last))?;
            }
            k += 1;
        };
        if k > 0 {
            p.print_last(k - 1, exact(integ.flush()))?;
        }
        stop.map_or(Ok(()), Err)
    })();
    finish(result, &mut p)
}

/// Flushes the rows; a closed stdout is a quiet end, as if the input ended there.
fn finish(result: Result<(), Failure>, p: &mut Printer) -> Result<(), Failure> {
    let flushed = p.out.flush();
    match (result, flushed) {
        (Err(Failure::Io(e)), _) | (Ok(()), Err(e)) if stream::is_closed_pipe(&e) => Ok(()),
        (Err(e), _) => Err(e),
        (Ok(()), Err(e)) => Err(Failure::Io(e)),
        (Ok(()), Ok(())) => Ok(()),
    }
}

fn main() -> ExitCode {
    let args = match CLI
        .command_line()
        .and_then(|f| arguments(&f).map_err(|e| flags::usage_error(&e)))
    {
        Ok(a) => a,
        Err(status) => return status,
    };
    let r = match (args.arith, args.compensated) {
        (Arith::F64, false) => run::<f64, UnitQuat<f64>>(&args),
        (Arith::F64, true) => run::<f64, CompensatedAttitude<f64>>(&args),
        (Arith::F32, false) => run::<f32, UnitQuat<f32>>(&args),
        (Arith::F32, true) => run::<f32, CompensatedAttitude<f32>>(&args),
        (Arith::Fixed, _) => run_fixed(&args),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(e)) => flags::usage_error(&e),
        Err(Failure::Row(n, e)) => {
            flags::line_error(n, &e);
            ExitCode::FAILURE
        }
        Err(Failure::Io(e)) => {
            flags::error(&e.to_string());
            ExitCode::FAILURE
        }
    }
}
