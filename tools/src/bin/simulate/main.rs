//! `simulate`: rigid-body and gyrostat dynamics from the command line.
//!
//! With no arguments it runs the built-in scenario (a tumbling body showing the
//! intermediate-axis flip, f32 core beside the f64 reference), prints a short summary and writes
//! a plot. With flags it runs any case, reaction wheels and external torques included, and
//! writes CSV; see `--help`.

mod plot;
mod torque;

use std::fmt::{Display, Write as _};
use std::io::{self, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use gyrostat::dynamics::semi_rigid::{Arrangement, QuarticBasis, SemiRigidRotor};
use gyrostat::dynamics::{
    BodyHamiltonian, Control, DriftMonitor, FreeRigidBody, Gyrostat, Inertia, Integrator,
    Invariants, Quartic, State, Wheel, WheelCommand,
};
use gyrostat::{Error, Quat, Real, UnitQuat, Vec3};
use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::stream::{self, Csv};
use gyrostat_tools::{say, say_part};

use plot::{Figure, Series};
use torque::{ExternalTorque, Schedule};

const CLI: Cli = Cli {
    name: "simulate",
    help: HELP,
    flags: &[
        Flag::value("--inertia"),
        Flag::value("--inertia-offdiag"),
        Flag::value("--omega"),
        Flag::value("--momentum"),
        Flag::value("--spin"),
        Flag::value("--quartic"),
        Flag::value("--semi-rigid"),
        Flag::value("--q0"),
        Flag::repeated("--wheel"),
        Flag::value("--wheel-torque"),
        Flag::value("--wheel-speed"),
        Flag::value("--torque"),
        Flag::value("--torque-file"),
        Flag::value("--plot"),
        Flag::value("--dt"),
        Flag::value("--steps"),
        Flag::value("--every"),
        Flag::value("--integrator"),
        Flag::switch("--f32"),
    ],
};

/// The most `--wheel`s a run takes. The library's wheel count is a compile-time constant; this
/// tool instantiates it for 0 to 4 wheels (three orthogonal wheels plus a skewed spare, or a
/// four-wheel pyramid).
const MAX_WHEELS: usize = 4;

const HELP: &str = "\
simulate: rigid-body / gyrostat attitude dynamics (gyrostat crate)

USAGE:
    simulate [--plot FILE.svg]
        Runs the built-in scenario: a body with the seed's inertia (6, 4, 3) spinning near its
        intermediate axis (the Dzhanibekov flip), integrated in f32 beside the f64 reference,
        and prints a summary: flip interval vs the closed form 2K(m)/lambda, conserved-quantity
        drift, attitude error. It also writes a plot (SVG, see --plot) and prints its path:
        FILE.svg, or by default simulate-default.svg in the Cargo target directory the binary
        was built in (the current directory if it was not built in one).

    simulate (--inertia I1,I2,I3 [--inertia-offdiag I12,I13,I23] | --semi-rigid KIND:M,WV,R0)
             (--omega w1,w2,w3 | --momentum J1,J2,J3) [--spin S1,S2,S3]
             [--quartic octahedral:T4|cubic:T22] [--q0 w,x,y,z]
             [--wheel AX,AY,AZ,INERTIA[,SPEED0]]... [--wheel-torque T1,..,TN | --wheel-speed W1,..,WN]
             [--torque TX,TY,TZ | --torque-file FILE] [--plot FILE.svg]
             --dt H --steps N [--every K] --integrator rk4|strang|yoshida4|exact [--f32]
        Writes CSV to stdout: the header
            t,qw,qx,qy,qz,w1,w2,w3,J1,J2,J3,energy
        then one row at step 0 and one after every K-th step. With N wheels the header and
        every row go on with N more columns, wheel1,...,wheelN.

    Flags take their value as the next argument or after `=` (--dt 0.01, --dt=0.01); a flag
    given twice is an error, except --wheel (one per wheel).

OPTIONS:
    --inertia I1,I2,I3          diagonal of the body inertia tensor (kg m^2)
    --inertia-offdiag I12,I13,I23
                                off-diagonal entries of the tensor itself (default 0,0,0);
                                the tensor must be symmetric positive definite with principal
                                moments obeying I_a <= I_b + I_c
    --omega w1,w2,w3            initial body rate (rad/s, body frame)
    --momentum J1,J2,J3         initial total body angular momentum J = I w + S instead
                                (with --quartic, --omega is solved for J with dH/dJ = w)
    --spin S1,S2,S3             constant body-fixed rotor momentum S (gyro-rotor, seed 6.9.2)
    --quartic octahedral:T4     add T4 (J1^4 + J2^4 + J3^4) to the Hamiltonian (seed 6.8.20a)
    --quartic cubic:T22         add T22 (J1^2 J2^2 + J1^2 J3^2 + J2^2 J3^2) (seed 6.8.20b);
                                quartic terms need a diagonal inertia tensor
    --semi-rigid KIND:MASS,OMEGA_V,R0
                                a semi-rigid rotor instead of --inertia (seed 6.8.c): equal
                                point masses MASS (kg) on radial springs of frequency OMEGA_V
                                (rad/s) at rest radius R0 (m), KIND octahedral (6 masses on
                                +-x, +-y, +-z), cubic (8 on the cube diagonals) or tetrahedral
                                (4 on alternate cube corners). The Hamiltonian is the rest
                                inertia I0 plus the centrifugal-stretch quartic (6.8.18)-(6.8.20):
                                an anisotropic term (octahedral T4 for the octahedron, cubic
                                T22 for the others) and an isotropic t|J|^4, whose exact flow
                                (a turn about J at 4 t |J|^3) is applied to the attitude, the
                                rate and the energy columns. Conflicts with --inertia,
                                --inertia-offdiag, --quartic, --torque and --torque-file (the
                                turn is exact only without external torque); stderr shows I0
                                and the coefficients
    --q0 w,x,y,z                initial attitude, body -> lab, scalar first (default 1,0,0,0);
                                must have unit norm within 1e-6
    --wheel AX,AY,AZ,INERTIA[,SPEED0]
                                a reaction wheel: spin axis in the body frame (normalised
                                here), axial inertia (kg m^2, > 0) and initial speed relative to
                                the body (rad/s, default 0). Repeat for more wheels, at most 4.
                                --inertia is the whole body's tensor with the wheels locked;
                                it must exceed the wheels' own axial inertia (I - sum Iw g g^T
                                positive definite). Then J = I w + S + sum Iw W g, and --omega
                                is the body rate at the initial wheel speeds.
    --wheel-torque T1,...,TN    constant motor torque on each wheel (N m, one per --wheel):
                                internal, it moves momentum between wheels and body
    --wheel-speed W1,...,WN     commanded wheel speeds (rad/s, relative to the body): an ideal
                                speed loop reaching them at the end of the first step and
                                holding them (each step the torque Iw (W_cmd - W)/H)
                                (without either the wheels coast at constant relative speed)
    --torque TX,TY,TZ           constant external torque, body frame (N m)
    --torque-file FILE          external body-frame torque from a CSV file: the header line
                                t,tx,ty,tz, then rows with times strictly ascending (blank lines
                                skipped); each row's torque holds from its time until the next
                                row's (zero-order hold), the last row for ever, zero before the
                                first. A step that contains a switching time is split there.
                                A bad file prints `error: --torque-file FILE: line N: reason`
                                and exits with status 2 before any output.
    --plot FILE.svg             also write a plot: body rates, relative drift of the conserved
                                quantities (log scale), attitude error against the closed form
                                (torque-free rigid body) or, with --f32, against the same run in
                                f64, wheel speeds, and the polhode on the angular-momentum
                                sphere with the rigid rotor's constant-energy curves and
                                separatrices (seed Fig. 6.8.1)
    --dt H                      time step (s), > 0
    --steps N                   number of steps
    --every K                   write a row every K steps (default 1)
    --integrator NAME           rk4      classical Runge-Kutta, renormalised (order 4)
                                strang   Lie-Poisson splitting (order 2, exact |J|)
                                yoshida4 Yoshida composition of strang (order 4, exact |J|)
                                suzuki4  Suzuki 5-stage composition (order 4, smaller error)
                                exact    closed-form torque-free rigid body (no --spin, no
                                         --quartic, no --semi-rigid, no wheels, no torque)
    --f32                       run the core in f32 (default f64)
    -h, --help                  this text

Columns: t (s); q = attitude body -> lab (w,x,y,z); w = body rate dH/dJ (rad/s); J = total
body angular momentum (body plus wheels: R(q) J is the lab-frame total momentum); energy = H(J)
(with wheels, at their current speeds; their own spin energy is not included); wheelI = speed
of wheel I relative to the body (rad/s). Rows are written as they are computed (flushed at
least every 0.1 s).

Errors print `error: reason` on stderr and exit with status 2: invalid input (before
any output), and a run that cannot go on, after the rows written so far: a step the library
rejects (a step that turns the body by more than half a turn, |w| dt > pi at either end of the
step, is too long for every integrator; --integrator exact has no such limit), and a state that is no longer finite (values too large for f64, or f32 with --f32; checked at step 0
too, before any output). When stdout is closed early (a pipe into `head`), the run stops
quietly with status 0.

With wheels or an external torque, a summary of the conserved-quantity monitors goes to stderr
after the CSV: without external torque the lab-frame total momentum is conserved (its drift is
printed); with one, its change is compared with the integrated lab-frame torque.

A run that lasts longer than about a second shows its progress on stderr when stderr is a
terminal and stdout is not (the CSV goes to a file or a pipe), and nothing otherwise.
";

/// Calls `f::<T, N>(args)` with the wheel count `N` a constant: one instance per count up to
/// [`MAX_WHEELS`].
macro_rules! with_wheels {
    ($n:expr, $f:ident :: <$t:ty> ($($arg:expr),*)) => {
        match $n {
            0 => $f::<$t, 0>($($arg),*),
            1 => $f::<$t, 1>($($arg),*),
            2 => $f::<$t, 2>($($arg),*),
            3 => $f::<$t, 3>($($arg),*),
            4 => $f::<$t, 4>($($arg),*),
            n => Err(format!("at most {MAX_WHEELS} --wheel, got {n}")),
        }
    };
}

fn main() -> ExitCode {
    let f = match CLI.command_line() {
        Ok(f) => f,
        Err(status) => return status,
    };
    // No flags, or only --plot: the built-in scenario.
    let result = if f.names().all(|n| n == "--plot") {
        default_scenario(f.value("--plot").map(PathBuf::from))
    } else {
        config(&f).and_then(|cfg| {
            if cfg.f32 {
                with_wheels!(cfg.wheels.len(), run_csv::<f32>(&cfg))
            } else {
                with_wheels!(cfg.wheels.len(), run_csv::<f64>(&cfg))
            }
        })
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // Every error of simulate exits with the status of a bad command line.
        Err(e) => flags::usage_error(&e),
    }
}

// ---------------------------------------------------------------------------------------------
// Command line

#[derive(Clone, Copy, Debug, PartialEq)]
enum Method {
    Step(Integrator),
    Exact,
}

#[derive(Debug)]
enum Initial {
    Omega([f64; 3]),
    Momentum([f64; 3]),
}

/// One `--wheel`.
#[derive(Debug, Clone, Copy)]
struct WheelSpec {
    axis: [f64; 3],
    inertia: f64,
    speed0: f64,
}

/// `--wheel-torque` or `--wheel-speed`.
#[derive(Debug, Clone)]
enum WheelInput {
    Torque(Vec<f64>),
    Speed(Vec<f64>),
}

#[derive(Debug)]
struct Config {
    /// `--inertia` (`None` with `--semi-rigid`).
    inertia: Option<[f64; 3]>,
    offdiag: [f64; 3],
    initial: Initial,
    spin: [f64; 3],
    quartic: Option<(bool, f64)>, // (octahedral?, coefficient)
    /// `--semi-rigid KIND:MASS,OMEGA_V,R0`.
    semi_rigid: Option<(Arrangement, [f64; 3])>,
    q0: [f64; 4],
    wheels: Vec<WheelSpec>,
    wheel_input: Option<WheelInput>,
    torque: ExternalTorque,
    /// Where the torque came from, for the summary.
    torque_source: String,
    plot: Option<PathBuf>,
    dt: f64,
    steps: u64,
    every: u64,
    method: Method,
    f32: bool,
}

impl Config {
    /// `true` when a step needs an input (external or wheel torque).
    fn has_input(&self) -> bool {
        self.torque.is_some() || self.wheel_input.is_some()
    }

    /// `true` for the new physics (wheels, torques) whose monitors are summarised on stderr.
    fn has_actuators(&self) -> bool {
        !self.wheels.is_empty() || self.torque.is_some()
    }
}

/// `--wheel AX,AY,AZ,INERTIA[,SPEED0]`, the `index`-th (1-based).
fn parse_wheel(index: usize, s: &str) -> Result<WheelSpec, String> {
    let v = flags::list("--wheel", s)?;
    if v.len() != 4 && v.len() != 5 {
        return Err(format!(
            "--wheel takes AX,AY,AZ,INERTIA[,SPEED0] (4 or 5 comma-separated numbers), got {s:?}"
        ));
    }
    let axis = [v[0], v[1], v[2]];
    if axis.iter().all(|&c| c == 0.0) {
        return Err(format!("--wheel {index}: the axis must not be zero"));
    }
    if v[3] <= 0.0 {
        return Err(format!(
            "--wheel {index}: the wheel inertia must be > 0, got {}",
            v[3]
        ));
    }
    Ok(WheelSpec {
        axis,
        inertia: v[3],
        speed0: v.get(4).copied().unwrap_or(0.0),
    })
}

fn read_torque_file(path: &str) -> Result<Schedule, String> {
    let file = std::fs::File::open(path).map_err(|e| format!("--torque-file {path}: {e}"))?;
    Schedule::parse(stream::Lines::new(file)).map_err(|e| format!("--torque-file {path}: {e}"))
}

/// `--semi-rigid KIND:MASS,OMEGA_V,R0`.
fn semi_rigid(flag: &str, value: &str) -> Result<(Arrangement, [f64; 3]), String> {
    let usage = || {
        format!(
            "{flag} takes KIND:MASS,OMEGA_V,R0 with KIND octahedral, cubic or tetrahedral, got \
             {value:?}"
        )
    };
    let (kind, numbers) = value.split_once(':').ok_or_else(usage)?;
    let kind = match kind.trim() {
        "octahedral" => Arrangement::Octahedral,
        "cubic" => Arrangement::Cubic,
        "tetrahedral" => Arrangement::Tetrahedral,
        _ => return Err(usage()),
    };
    let v = flags::numbers::<3>(flag, numbers, "MASS,OMEGA_V,R0")?;
    if v.iter().any(|&x| x <= 0.0) {
        return Err(format!(
            "{flag}: MASS, OMEGA_V and R0 must be > 0, got {numbers:?}"
        ));
    }
    Ok((kind, v))
}

/// `--quartic octahedral:T4|cubic:T22`: (octahedral?, coefficient).
fn quartic(flag: &str, value: &str) -> Result<(bool, f64), String> {
    let (kind, t) = value
        .split_once(':')
        .ok_or_else(|| format!("{flag} takes octahedral:T4 or cubic:T22, got {value:?}"))?;
    let t = flags::number(flag, t)?;
    match kind.trim() {
        "octahedral" => Ok((true, t)),
        "cubic" => Ok((false, t)),
        other => Err(format!(
            "{flag}: unknown kind {other:?} (octahedral or cubic)"
        )),
    }
}

/// `--integrator NAME`.
fn integrator(flag: &str, value: &str) -> Result<Method, String> {
    Ok(match value.trim() {
        "rk4" => Method::Step(Integrator::Rk4),
        "strang" => Method::Step(Integrator::Strang),
        "yoshida4" => Method::Step(Integrator::Yoshida4),
        "suzuki4" => Method::Step(Integrator::Suzuki4),
        "exact" => Method::Exact,
        other => {
            return Err(format!(
                "{flag}: unknown {other:?} (rk4, strang, yoshida4, suzuki4, exact)"
            ));
        }
    })
}

/// The configuration of a CSV run, from the flags given.
fn config(f: &Flags) -> Result<Config, String> {
    let three =
        |fields: &'static str| move |flag: &str, v: &str| flags::numbers::<3>(flag, v, fields);
    let inertia = f.get("--inertia", three("I1,I2,I3"))?;
    let offdiag = f.get("--inertia-offdiag", three("I12,I13,I23"))?;
    let omega = f.get("--omega", three("w1,w2,w3"))?;
    let momentum = f.get("--momentum", three("J1,J2,J3"))?;
    let spin = f.get("--spin", three("S1,S2,S3"))?;
    let quartic = f.get("--quartic", quartic)?;
    let semi_rigid = f.get("--semi-rigid", semi_rigid)?;
    let q0 = f.get("--q0", |flag, v| flags::numbers::<4>(flag, v, "w,x,y,z"))?;
    let dt = f.get("--dt", flags::positive)?;
    let steps = f.get("--steps", flags::count)?;
    let every = f.get("--every", flags::at_least_one)?;
    let method = f.get("--integrator", integrator)?;
    let given_wheels: Vec<&str> = f.values("--wheel").collect();
    if given_wheels.len() > MAX_WHEELS {
        return Err(format!(
            "at most {MAX_WHEELS} --wheel (the capacity of this tool)"
        ));
    }
    let wheels = given_wheels
        .iter()
        .enumerate()
        .map(|(i, v)| parse_wheel(i + 1, v))
        .collect::<Result<Vec<_>, _>>()?;
    let wheel_torque = f.get("--wheel-torque", flags::list)?;
    let wheel_speed = f.get("--wheel-speed", flags::list)?;
    let torque = f.get("--torque", three("TX,TY,TZ"))?;
    let torque_file = f.value("--torque-file");
    let plot = f.value("--plot").map(PathBuf::from);
    let f32 = f.switch("--f32");
    let initial = match (omega, momentum) {
        (Some(w), None) => Initial::Omega(w),
        (None, Some(j)) => Initial::Momentum(j),
        (Some(_), Some(_)) => return Err("give either --omega or --momentum, not both".into()),
        (None, None) => return Err("missing --omega or --momentum".into()),
    };
    let dt = dt.ok_or("missing --dt")?;
    let every = every.unwrap_or(1);
    let spin = spin.unwrap_or([0.0; 3]);
    let method = method.ok_or("missing --integrator")?;
    if semi_rigid.is_some() {
        for (given, flag) in [
            (
                inertia.is_some(),
                "--inertia (the rotor's rest inertia I0 is the body's)",
            ),
            (offdiag.is_some(), "--inertia-offdiag"),
            (
                quartic.is_some(),
                "--quartic (the rotor has its own quartic term)",
            ),
            (
                torque.is_some() || torque_file.is_some(),
                "--torque and --torque-file (the isotropic |J|^4 turn is exact only without \
                 external torque)",
            ),
        ] {
            if given {
                return Err(format!("--semi-rigid conflicts with {flag}"));
            }
        }
        if method == Method::Exact {
            return Err(
                "--integrator exact is for torque-free rigid bodies only (no --semi-rigid)".into(),
            );
        }
    }
    if method == Method::Exact && (spin != [0.0; 3] || quartic.is_some()) {
        return Err(
            "--integrator exact is for torque-free rigid bodies only (no --spin, no --quartic)"
                .into(),
        );
    }
    let q0 = q0.unwrap_or([1.0, 0.0, 0.0, 0.0]);
    let n = q0.iter().map(|c| c * c).sum::<f64>().sqrt();
    if (n - 1.0).abs() > 1e-6 {
        return Err(format!("--q0 must be a unit quaternion (norm {n})"));
    }
    let wheel_input = match (wheel_torque, wheel_speed) {
        (Some(_), Some(_)) => {
            return Err("give either --wheel-torque or --wheel-speed, not both".into());
        }
        (Some(u), None) => Some(("--wheel-torque", WheelInput::Torque(u))),
        (None, Some(w)) => Some(("--wheel-speed", WheelInput::Speed(w))),
        (None, None) => None,
    };
    let wheel_input = match wheel_input {
        None => None,
        Some((flag, input)) => {
            let len = match &input {
                WheelInput::Torque(v) | WheelInput::Speed(v) => v.len(),
            };
            if wheels.is_empty() {
                return Err(format!("{flag} needs at least one --wheel"));
            }
            if len != wheels.len() {
                return Err(format!(
                    "{flag} takes one number per --wheel ({}), got {len}",
                    wheels.len()
                ));
            }
            Some(input)
        }
    };
    let (torque, torque_source) = match (torque, torque_file) {
        (Some(_), Some(_)) => return Err("give either --torque or --torque-file, not both".into()),
        (Some(t), None) => (ExternalTorque::Constant(t), "--torque".to_string()),
        (None, Some(path)) => (
            ExternalTorque::Schedule(read_torque_file(path)?),
            format!("--torque-file {path}"),
        ),
        (None, None) => (ExternalTorque::None, String::new()),
    };
    if method == Method::Exact && (!wheels.is_empty() || torque.is_some()) {
        return Err(
            "--integrator exact is for torque-free rigid bodies only (no --wheel, no --torque, \
             no --torque-file)"
                .into(),
        );
    }
    if inertia.is_none() && semi_rigid.is_none() {
        return Err("missing --inertia".into());
    }
    Ok(Config {
        inertia,
        offdiag: offdiag.unwrap_or([0.0; 3]),
        initial,
        spin,
        quartic,
        semi_rigid,
        q0,
        wheels,
        wheel_input,
        torque,
        torque_source,
        plot,
        dt,
        steps: steps.ok_or("missing --steps")?,
        every,
        method,
        f32,
    })
}

// ---------------------------------------------------------------------------------------------
// Progress

/// Progress on stderr for a run longer than [`Progress::QUIET`], only when stderr is a terminal
/// and stdout is not (CSV rows on a terminal are never interleaved with a progress line).
struct Progress {
    enabled: bool,
    start: Instant,
    last: Option<Instant>,
    total: u64,
}

impl Progress {
    /// Runs shorter than this show nothing.
    const QUIET: Duration = Duration::from_secs(1);
    /// The clock is read once per this many steps (a step costs well under a microsecond).
    const CHECK_EVERY: u64 = 4096;

    fn new(total: u64) -> Self {
        Self {
            enabled: io::stderr().is_terminal() && !io::stdout().is_terminal(),
            start: Instant::now(),
            last: None,
            total,
        }
    }

    fn tick(&mut self, k: u64) {
        if !self.enabled || !k.is_multiple_of(Self::CHECK_EVERY) {
            return;
        }
        let now = Instant::now();
        let elapsed = now - self.start;
        let due = self
            .last
            .is_none_or(|l| now - l >= Duration::from_millis(250));
        if elapsed >= Self::QUIET && due {
            self.last = Some(now);
            let pct = 100.0 * k as f64 / self.total.max(1) as f64;
            say_part!(
                "\rsimulate: step {k} of {} ({pct:.0}%), {:.0} s",
                self.total,
                elapsed.as_secs_f64()
            );
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if self.last.is_some() {
            // Clear the progress line.
            say_part!("\r\x1b[2K");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// CSV run

fn v3<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]))
}

fn f3<T: Real>(v: Vec3<T>) -> [f64; 3] {
    v.to_array().map(|c| c.to_f64())
}

/// A semi-rigid rotor and the basis its quartic is split in (the anisotropic part in the
/// [`BodyHamiltonian`], the isotropic `t|J|⁴` applied as its exact turn).
#[derive(Clone, Copy)]
struct Semi<T> {
    rotor: SemiRigidRotor<T>,
    basis: QuarticBasis,
}

/// The body model of `cfg`.
struct Model<T> {
    hamiltonian: BodyHamiltonian<T>,
    semi: Option<Semi<T>>,
}

fn build<T: Real>(cfg: &Config) -> Result<Model<T>, String> {
    if let Some((kind, [m, wv, r0])) = cfg.semi_rigid {
        let rotor =
            SemiRigidRotor::try_symmetric(kind, T::from_f64(m), T::from_f64(wv), T::from_f64(r0))
                .map_err(|e| format!("--semi-rigid: {e}"))?;
        let basis = kind.natural_basis();
        let hamiltonian =
            BodyHamiltonian::try_new(rotor.rest_inertia(), v3(cfg.spin), rotor.quartic(basis))
                .map_err(|e| format!("--semi-rigid: {e}"))?;
        return Ok(Model {
            hamiltonian,
            semi: Some(Semi { rotor, basis }),
        });
    }
    let moments = cfg.inertia.unwrap_or([0.0; 3]);
    let inertia = Inertia::try_from_components(v3(moments), v3(cfg.offdiag)).map_err(|e| {
        format!(
            "--inertia {:?} with off-diagonal {:?}: {e} (must be symmetric positive definite with \
             principal moments I_a <= I_b + I_c)",
            moments, cfg.offdiag
        )
    })?;
    let quartic = match cfg.quartic {
        None => Quartic::None,
        Some((true, t)) => Quartic::Octahedral(T::from_f64(t)),
        Some((false, t)) => Quartic::Cubic(T::from_f64(t)),
    };
    let hamiltonian =
        BodyHamiltonian::try_new(inertia, v3(cfg.spin), quartic).map_err(|e| match e {
            Error::InvalidArgument => {
                "--quartic needs a diagonal inertia tensor (the quartic polynomials are defined \
                 on principal axes); drop --inertia-offdiag"
                    .to_string()
            }
            e => format!("model: {e}"),
        })?;
    Ok(Model {
        hamiltonian,
        semi: None,
    })
}

/// What stderr shows of a semi-rigid rotor: `I₀`, the quartic term and the isotropic term.
fn describe_semi(cfg: &Config, semi: &Semi<f64>, h: &BodyHamiltonian<f64>) -> String {
    let Some((kind, [m, wv, r0])) = cfg.semi_rigid else {
        return String::new();
    };
    let i0 = h.inertia().tensor().m;
    let quartic = match h.quartic() {
        Quartic::Octahedral(t) => format!("octahedral {t:e} (J1^4 + J2^4 + J3^4)"),
        Quartic::Cubic(t) => format!("cubic {t:e} (J1^2 J2^2 + J1^2 J3^2 + J2^2 J3^2)"),
        Quartic::None => "none".to_string(),
    };
    let kind = match kind {
        Arrangement::Octahedral => "octahedral (6 masses)",
        Arrangement::Cubic => "cubic (8 masses)",
        Arrangement::Tetrahedral => "tetrahedral (4 masses)",
    };
    format!(
        "simulate: semi-rigid {kind} rotor: masses {m} kg on springs of {wv} rad/s at {r0} m\n  \
         rest inertia I0 = [{:?}, {:?}, {:?}] kg m^2\n  \
         quartic term    {quartic}\n  \
         isotropic term  {:e} |J|^4 (applied as its exact turn about J)\n",
        i0[0],
        i0[1],
        i0[2],
        semi.rotor.isotropic(semi.basis)
    )
}

/// The wheels of `cfg`, checked against the body: the tensor without the wheels' axial inertia,
/// `I − Σ I_w g gᵀ`, must stay positive definite (a wheel cannot hold more axial inertia than
/// the body it is part of).
fn wheels<T: Real, const N: usize>(
    cfg: &Config,
    inertia: &Inertia<T>,
) -> Result<[Wheel<T>; N], String> {
    let mut platform = inertia.tensor().m.map(|row| row.map(|x| x.to_f64()));
    let mut out = Vec::with_capacity(N);
    for (i, w) in cfg.wheels.iter().enumerate() {
        let n = w.axis.iter().map(|c| c * c).sum::<f64>().sqrt();
        let g = w.axis.map(|c| c / n);
        for (r, row) in platform.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                *x -= w.inertia * g[r] * g[c];
            }
        }
        out.push(
            Wheel::try_new(v3(w.axis), T::from_f64(w.inertia))
                .map_err(|e| format!("--wheel {}: {e}", i + 1))?,
        );
    }
    // Sylvester's criterion: the leading principal minors are positive.
    let m = platform;
    let d1 = m[0][0];
    let d2 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let d3 = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if N > 0 && !(d1 > 0.0 && d2 > 0.0 && d3 > 0.0) {
        return Err(
            "--wheel: the wheels' axial inertia exceeds the body's (--inertia is the whole \
             body with the wheels locked, so I - sum Iw g g^T must be positive definite)"
                .into(),
        );
    }
    out.try_into()
        .map_err(|_| "internal error: wheel count".to_string())
}

/// A body, its initial state and (for `--integrator exact`) its closed-form motion.
struct Sim<T, const N: usize> {
    body: Gyrostat<T, N>,
    start: State<T, N>,
    exact: Option<FreeRigidBody<T>>,
    semi: Option<Semi<T>>,
}

fn setup<T: Real, const N: usize>(cfg: &Config) -> Result<Sim<T, N>, String> {
    let dt = T::from_f64(cfg.dt);
    if !(dt.is_finite() && dt > T::ZERO) {
        return Err(format!(
            "--dt {:?} is not a positive finite {}",
            cfg.dt,
            if cfg.f32 { "f32" } else { "f64" }
        ));
    }
    let Model {
        hamiltonian: model,
        semi,
    } = build::<T>(cfg)?;
    let q0 = UnitQuat::try_new(Quat::from_array(cfg.q0.map(T::from_f64)))
        .map_err(|e| format!("--q0: {e}"))?;
    let body = Gyrostat::new(model, wheels::<T, N>(cfg, model.inertia())?);
    let speeds: [T; N] = core::array::from_fn(|i| T::from_f64(cfg.wheels[i].speed0));
    let start = match cfg.initial {
        Initial::Omega(w) => body
            .try_state_from_omega(q0, v3(w), speeds)
            .map_err(|e| match e {
                Error::NotConverged => {
                    "--omega with --quartic: Newton's method did not converge; give --momentum"
                        .to_string()
                }
                e => format!("--omega with --quartic: no momentum found ({e}); give --momentum"),
            })?,
        Initial::Momentum(j) => State {
            attitude: q0,
            momentum: v3(j),
            wheel_speeds: speeds,
        },
    };
    let start = match (&cfg.initial, &semi) {
        (Initial::Omega(w), Some(semi)) => State {
            momentum: momentum_with_isotropic(&body, semi, &start, v3(*w))?,
            ..start
        },
        _ => start,
    };
    let exact = match cfg.method {
        Method::Exact => Some(
            FreeRigidBody::try_new(model.inertia(), &State::new(start.attitude, start.momentum))
                .map_err(|e| format!("--integrator exact: {e}"))?,
        ),
        Method::Step(_) => None,
    };
    Ok(Sim {
        body,
        start,
        exact,
        semi,
    })
}

/// The momentum whose full semi-rigid body rate `∇H(J) + 4t|J|²J` is `omega`, by Newton's method
/// from `start` (the solution without the isotropic term), with the Hessian
/// `∇²H(J) + 4t(|J|²·1 + 2JJᵀ)`; stopped as [`BodyHamiltonian::try_momentum_from_omega`] is.
fn momentum_with_isotropic<T: Real, const N: usize>(
    body: &Gyrostat<T, N>,
    semi: &Semi<T>,
    start: &State<T, N>,
    omega: Vec3<T>,
) -> Result<Vec3<T>, String> {
    use gyrostat::dynamics::hamiltonian::{
        MOMENTUM_SOLVE_MAX_STEPS, MOMENTUM_SOLVE_RESIDUAL, MOMENTUM_SOLVE_STEP_TOLERANCE,
    };
    let four_t = T::from_f64(4.0) * semi.rotor.isotropic(semi.basis);
    let hessian = |j: Vec3<T>| {
        let ja = j.to_array();
        let mut hess = body.model().hessian(j);
        for (r, row) in hess.m.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                let diag = if r == c { j.norm_squared() } else { T::ZERO };
                *x += four_t * (diag + T::TWO * ja[r] * ja[c]);
            }
        }
        hess
    };
    let residual = |j: Vec3<T>| {
        let s = State {
            momentum: j,
            ..*start
        };
        body.omega(&s) + j.scale(four_t * j.norm_squared()) - omega
    };
    let fail = || "--omega with --semi-rigid: Newton's method did not converge; give --momentum";
    let mut j = start.momentum;
    let mut converged = false;
    for _ in 0..MOMENTUM_SOLVE_MAX_STEPS {
        let step = hessian(j).try_inverse().map_err(|_| fail().to_string())? * residual(j);
        j -= step;
        if !j.is_finite() {
            return Err(fail().into());
        }
        if step.norm() <= T::from_f64(MOMENTUM_SOLVE_STEP_TOLERANCE) * (T::ONE + j.norm()) {
            converged = true;
            break;
        }
    }
    if !converged
        && residual(j).norm() > T::from_f64(MOMENTUM_SOLVE_RESIDUAL) * (T::ONE + omega.norm())
    {
        return Err(fail().into());
    }
    // The physical root has ∂ω/∂J positive definite (the energy is a minimum there at fixed
    // direction); past the quartic model's largest rate Newton can only land on the far branch.
    let m = hessian(j).m.map(|row| row.map(|x| x.to_f64()));
    let minors = [
        m[0][0],
        m[0][0] * m[1][1] - m[0][1] * m[1][0],
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]),
    ];
    if minors.iter().any(|&d| d <= 0.0) {
        return Err(
            "--omega with --semi-rigid: this rate is beyond the quartic model's reach (no \
             momentum with a positive definite Hessian gives it); give a smaller rate or \
             --momentum"
                .into(),
        );
    }
    Ok(j)
}

/// What a run failed on: writing the CSV, or the simulation itself.
enum Fail {
    Io(io::Error),
    Msg(String),
}

impl From<io::Error> for Fail {
    fn from(e: io::Error) -> Self {
        Fail::Io(e)
    }
}

/// Samples of a run for the plot, in f64.
#[derive(Default)]
struct Trajectory {
    t: Vec<f64>,
    attitude: Vec<UnitQuat<f64>>,
    omega: Vec<[f64; 3]>,
    momentum: Vec<[f64; 3]>,
    wheels: Vec<Vec<f64>>,
    energy: Vec<f64>,
    /// Lab-frame momentum minus the integrated lab torque, `L − ∫R(q)τ dt` (constant exactly).
    lab_balance: Vec<[f64; 3]>,
}

/// The integrated external torque of a run so far: `∫R(q)τ dt` (lab frame) and `∫|τ| dt`.
#[derive(Clone, Copy, Default)]
struct Impulse {
    lab: [f64; 3],
    magnitude: f64,
}

/// The monitors of a run, in f64.
struct Outcome {
    trajectory: Trajectory,
    lab0: [f64; 3],
    lab_end: [f64; 3],
    impulse: Impulse,
    lab_drift_max: f64,
    norm_drift_max: f64,
    energy0: f64,
    energy_end: f64,
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// One row of samples every this many steps in the plot (about 2000 samples per run).
fn plot_stride(steps: u64) -> u64 {
    steps.div_ceil(2000).max(1)
}

impl<T: Real + Display, const N: usize> Sim<T, N> {
    /// The attitude written out at time `t`: the state's, followed by the isotropic turn of a
    /// semi-rigid rotor (the exact flow of `t|J|⁴`, which commutes with the rest).
    fn attitude_at(&self, s: &State<T, N>, t: T) -> UnitQuat<T> {
        match &self.semi {
            None => s.attitude,
            Some(semi) => semi
                .rotor
                .isotropic_turn(semi.basis, s.momentum, t)
                .map_or(s.attitude, |turn| s.attitude * turn),
        }
    }

    /// The body rate `∇H(J)`, with `4t|J|²J` of a semi-rigid rotor's isotropic term.
    fn omega(&self, s: &State<T, N>) -> Vec3<T> {
        let w = self.body.omega(s);
        match &self.semi {
            None => w,
            Some(semi) => {
                let four_t = T::from_f64(4.0) * semi.rotor.isotropic(semi.basis);
                w + s.momentum.scale(four_t * s.momentum.norm_squared())
            }
        }
    }

    /// The energy `H(J)`, with `t|J|⁴` of a semi-rigid rotor's isotropic term.
    fn energy(&self, s: &State<T, N>) -> T {
        let e = self.body.energy(s);
        match &self.semi {
            None => e,
            Some(semi) => {
                let j2 = s.momentum.norm_squared();
                e + semi.rotor.isotropic(semi.basis) * j2 * j2
            }
        }
    }

    /// The monitored invariants (energy with the isotropic term; `|J|` and the lab momentum
    /// are those of the state: the isotropic turn is about `J`).
    fn invariants(&self, s: &State<T, N>) -> Invariants<T> {
        Invariants {
            energy: self.energy(s),
            ..self.body.invariants(s)
        }
    }

    /// The state after step `k` (from `(k−1)·dt` to `k·dt`); adds the step's external torque to
    /// `impulse` (`∫R(q)τ dt` by the trapezoid rule on each piece of constant torque).
    fn advance(
        &self,
        cfg: &Config,
        state: &State<T, N>,
        k: u64,
        impulse: &mut Impulse,
    ) -> Result<State<T, N>, String> {
        // The library's checked steps reject a step that turns the body by more than half a
        // turn (`|w| dt` at either end, `MAX_STEP_ANGLE`) with `StepTooLong`.
        let fail = |e: Error| format!("step {k}: {e} (the step is too long for these rates?)");
        let integ = match (cfg.method, &self.exact) {
            (Method::Exact, Some(x)) => {
                let s = x.state_at_unchecked(T::from_f64(k as f64 * cfg.dt));
                return Ok(State {
                    attitude: s.attitude,
                    momentum: s.momentum,
                    wheel_speeds: state.wheel_speeds,
                });
            }
            (Method::Exact, None) => return Err("internal error: no closed form".into()),
            (Method::Step(integ), _) => integ,
        };
        let dt = T::from_f64(cfg.dt);
        if !cfg.has_input() {
            return self.body.step(integ, state, dt).map_err(fail);
        }
        // The wheel torques are set once per step (a speed command reaches its target at the end
        // of the whole step even when a torque switch splits it).
        let wheel_torques = match &cfg.wheel_input {
            None => [T::ZERO; N],
            Some(input) => {
                let v = |x: &[f64]| core::array::from_fn(|i| T::from_f64(x[i]));
                let command = match input {
                    WheelInput::Torque(u) => WheelCommand::Torque(v(u)),
                    WheelInput::Speed(w) => WheelCommand::Speed(v(w)),
                };
                self.body
                    .control(state, dt, Vec3::ZERO, &command)
                    .wheel_torques
            }
        };
        let (a, b) = ((k - 1) as f64 * cfg.dt, k as f64 * cfg.dt);
        let pieces = cfg.torque.pieces(a, b);
        let whole = pieces.len() == 1;
        let mut s = *state;
        for (lo, hi, tau) in pieces {
            let h = if whole { cfg.dt } else { hi - lo };
            let control = Control {
                torque: v3::<T>(tau),
                wheel_torques,
            };
            let before = widen(s.attitude);
            s = self
                .body
                .step_with(integ, &s, T::from_f64(lo), T::from_f64(h), control)
                .map_err(fail)?;
            if tau != [0.0; 3] {
                let tau = Vec3::new(tau[0], tau[1], tau[2]);
                let avg = (before.rotate(tau) + widen(s.attitude).rotate(tau)).scale(0.5 * h);
                for (acc, x) in impulse.lab.iter_mut().zip(avg.to_array()) {
                    *acc += x;
                }
                impulse.magnitude += tau.norm() * h;
            }
        }
        Ok(s)
    }

    /// Checks that the state after step `k` (0: the initial state) is finite and its attitude
    /// a unit quaternion, as written: time, attitude, rate, momentum, energy, wheel speeds.
    fn check(&self, cfg: &Config, k: u64, s: &State<T, N>) -> Result<(), String> {
        let t = T::from_f64(k as f64 * cfg.dt);
        let q = self.attitude_at(s, t).to_array();
        let n2 = q.iter().fold(T::ZERO, |acc, &x| acc + x * x);
        let (w, e) = (self.omega(s), self.energy(s));
        // The integrators renormalise the attitude: a norm visibly off 1 is a collapsed step.
        let unit = (n2 - T::ONE).abs() <= T::from_f64(1e-3);
        if t.is_finite()
            && q.iter().all(|x| x.is_finite())
            && unit
            && w.is_finite()
            && s.momentum.is_finite()
            && e.is_finite()
            && s.wheel_speeds.iter().all(|x| x.is_finite())
        {
            return Ok(());
        }
        let at = if k == 0 {
            "the initial state".to_string()
        } else {
            format!("step {k}: the state")
        };
        let g = |x: T| format!("{:.6e}", x.to_f64());
        let v = |v: Vec3<T>| format!("({}, {}, {})", g(v.x), g(v.y), g(v.z));
        let speeds: Vec<String> = s.wheel_speeds.iter().map(|&x| g(x)).collect();
        Err(format!(
            "{at} is not finite or its attitude not a unit quaternion (t = {}, q = ({}, {}, {}, \
             {}), w = {}, J = {}, energy = {}{}): the values are too large for {}",
            g(t),
            g(q[0]),
            g(q[1]),
            g(q[2]),
            g(q[3]),
            v(w),
            v(s.momentum),
            g(e),
            if speeds.is_empty() {
                String::new()
            } else {
                format!(", wheels ({})", speeds.join(", "))
            },
            if cfg.f32 { "f32" } else { "f64" }
        ))
    }

    fn write_row(
        &self,
        out: &mut dyn Write,
        cfg: &Config,
        k: u64,
        s: &State<T, N>,
    ) -> io::Result<()> {
        let t = T::from_f64(k as f64 * cfg.dt);
        let q = self.attitude_at(s, t);
        let w = self.omega(s);
        let j = s.momentum;
        let e = self.energy(s);
        write!(
            out,
            "{t},{},{},{},{},{},{},{},{},{},{},{e}",
            q.w(),
            q.x(),
            q.y(),
            q.z(),
            w.x,
            w.y,
            w.z,
            j.x,
            j.y,
            j.z
        )?;
        for speed in &s.wheel_speeds {
            write!(out, ",{speed}")?;
        }
        writeln!(out)
    }

    /// Runs `cfg`, writing CSV to `csv` if given and sampling every `stride` steps if given.
    fn run(
        &self,
        cfg: &Config,
        mut csv: Option<&mut Csv>,
        stride: Option<u64>,
    ) -> Result<Outcome, Fail> {
        let mut state = self.start;
        self.check(cfg, 0, &state).map_err(Fail::Msg)?;
        let inv0 = self.invariants(&state);
        let mut monitor = DriftMonitor::new(inv0);
        let mut impulse = Impulse::default();
        let mut traj = Trajectory::default();
        let record = |traj: &mut Trajectory, k: u64, s: &State<T, N>, impulse: &Impulse| {
            traj.t.push(k as f64 * cfg.dt);
            traj.attitude
                .push(widen(self.attitude_at(s, T::from_f64(k as f64 * cfg.dt))));
            traj.omega.push(f3(self.omega(s)));
            traj.momentum.push(f3(s.momentum));
            traj.wheels
                .push(s.wheel_speeds.iter().map(|w| w.to_f64()).collect());
            traj.energy.push(self.energy(s).to_f64());
            let lab = f3(self.body.invariants(s).lab_momentum);
            traj.lab_balance.push(sub(lab, impulse.lab));
        };
        if let Some(out) = csv.as_deref_mut() {
            write!(out, "t,qw,qx,qy,qz,w1,w2,w3,J1,J2,J3,energy")?;
            for i in 1..=N {
                write!(out, ",wheel{i}")?;
            }
            writeln!(out)?;
            self.write_row(out, cfg, 0, &state)?;
            out.flush()?;
        }
        if stride.is_some() {
            record(&mut traj, 0, &state, &impulse);
        }
        let mut progress = Progress::new(cfg.steps);
        for k in 1..=cfg.steps {
            state = self
                .advance(cfg, &state, k, &mut impulse)
                .and_then(|s| self.check(cfg, k, &s).map(|()| s))
                .map_err(Fail::Msg)?;
            monitor.record(&self.invariants(&state));
            if k % cfg.every == 0
                && let Some(out) = csv.as_deref_mut()
            {
                self.write_row(out, cfg, k, &state)?;
                out.row_done()?;
            }
            if let Some(n) = stride
                && (k % n == 0 || k == cfg.steps)
            {
                record(&mut traj, k, &state, &impulse);
            }
            progress.tick(k);
        }
        if let Some(out) = csv {
            out.flush()?;
        }
        let end = self.invariants(&state);
        Ok(Outcome {
            trajectory: traj,
            lab0: f3(inv0.lab_momentum),
            lab_end: f3(end.lab_momentum),
            impulse,
            lab_drift_max: monitor.worst().lab_momentum.to_f64(),
            norm_drift_max: monitor.worst().momentum_norm.to_f64(),
            energy0: inv0.energy.to_f64(),
            energy_end: end.energy.to_f64(),
        })
    }
}

fn run_csv<T: Real + Display, const N: usize>(cfg: &Config) -> Result<(), String> {
    let sim = setup::<T, N>(cfg)?;
    if cfg.semi_rigid.is_some() {
        let model = build::<f64>(cfg)?;
        if let Some(semi) = &model.semi {
            say_part!("{}", describe_semi(cfg, semi, &model.hamiltonian));
        }
    }
    if let Some(path) = &cfg.plot {
        // Fail before any output when the plot cannot be written.
        std::fs::File::create(path).map_err(|e| format!("--plot {}: {e}", path.display()))?;
    }
    let mut out = Csv::stdout();
    let stride = cfg.plot.as_ref().map(|_| plot_stride(cfg.steps));
    let outcome = match sim.run(cfg, Some(&mut out), stride) {
        Ok(o) => o,
        // A closed pipe (`simulate ... | head`) is not an error of the simulation; the run
        // stops there, and the plot file made empty above goes.
        Err(Fail::Io(e)) if stream::is_closed_pipe(&e) => {
            if let Some(path) = &cfg.plot {
                let _ = std::fs::remove_file(path);
            }
            return Ok(());
        }
        Err(Fail::Io(e)) => return Err(format!("writing output: {e}")),
        Err(Fail::Msg(m)) => {
            // The rows before the failed step stay.
            return match out.flush() {
                Err(e) if !stream::is_closed_pipe(&e) => Err(format!("{m}; writing output: {e}")),
                _ => Err(m),
            };
        }
    };
    drop(out);
    if cfg.has_actuators() {
        say_part!("{}", summary::<N>(cfg, &outcome));
    }
    if let Some(path) = &cfg.plot {
        let figure = csv_figure::<N>(cfg, &outcome)?;
        plot::write_svg(path, &figure)?;
        say!("simulate: plot written to {}", path.display());
    }
    Ok(())
}

fn fmt3(v: [f64; 3]) -> String {
    format!("({:.6e}, {:.6e}, {:.6e})", v[0], v[1], v[2])
}

/// The monitors of a run with wheels or torques (stderr).
fn summary<const N: usize>(cfg: &Config, o: &Outcome) -> String {
    let mut s = String::new();
    let integ = match cfg.method {
        Method::Step(i) => format!("{i:?}").to_lowercase(),
        Method::Exact => "exact".into(),
    };
    let what = match (N, cfg.torque.is_some()) {
        (0, _) => format!("external torque from {}", cfg.torque_source),
        (n, false) => format!("{n} wheel(s), no external torque"),
        (n, true) => format!("{n} wheel(s), external torque from {}", cfg.torque_source),
    };
    s += &format!(
        "simulate: monitors: {what}; {} steps of {} s ({integ}, {})\n",
        cfg.steps,
        cfg.dt,
        if cfg.f32 { "f32" } else { "f64" }
    );
    s += &format!(
        "  lab-frame total momentum L = R(q) J: L(0) = {} N m s\n",
        fmt3(o.lab0)
    );
    if cfg.torque.is_some() {
        let change = sub(o.lab_end, o.lab0);
        // The momentum the torque can move is ∫|τ| dt: the scale of the comparison.
        let scale = norm(o.lab0).max(o.impulse.magnitude);
        s += &format!(
            "  change L(T) - L(0)                  {} N m s\n",
            fmt3(change)
        );
        s += &format!(
            "  integrated torque int R(q) tau dt   {} N m s (trapezoid rule per step)\n",
            fmt3(o.impulse.lab)
        );
        s += &format!(
            "  |change - integrated| / max(|L(0)|, int |tau| dt)   {:.2e}\n",
            if scale > 0.0 {
                norm(sub(change, o.impulse.lab)) / scale
            } else {
                0.0
            }
        );
    } else {
        s += &format!(
            "  max |L - L(0)|/|L(0)| over the run   {:.2e} (internal torques only: conserved)\n",
            o.lab_drift_max
        );
        s += &format!(
            "  max ||J| - |J(0)||/|J(0)| over the run   {:.2e} (conserved)\n",
            o.norm_drift_max
        );
    }
    let note = if cfg.has_input() {
        "torques do work on the body"
    } else {
        "conserved: wheels coasting"
    };
    s += &format!(
        "  energy H(J): {:.9e} -> {:.9e} ({note})\n",
        o.energy0, o.energy_end
    );
    s
}

/// The figure of a CSV run.
fn csv_figure<const N: usize>(cfg: &Config, o: &Outcome) -> Result<Figure, String> {
    let tr = &o.trajectory;
    let rel = |x: f64, x0: f64| {
        if x0 != 0.0 {
            (x - x0).abs() / x0.abs()
        } else {
            x.abs()
        }
    };
    let e0 = tr.energy.first().copied().unwrap_or(0.0);
    let j0 = tr.momentum.first().map(|&j| norm(j)).unwrap_or(0.0);
    let b0 = tr.lab_balance.first().copied().unwrap_or([0.0; 3]);
    let scale = if j0 > 0.0 { j0 } else { 1.0 };
    let energy_label = if cfg.has_input() {
        "energy (changed by the torques)"
    } else {
        "energy"
    };
    let mut drift = vec![Series::new(
        energy_label,
        tr.energy.iter().map(|&e| rel(e, e0)).collect(),
    )];
    if !cfg.torque.is_some() {
        drift.push(Series::new(
            "|J|",
            tr.momentum.iter().map(|&j| rel(norm(j), j0)).collect(),
        ));
    }
    drift.push(Series::new(
        if cfg.torque.is_some() {
            "lab momentum minus integrated torque"
        } else {
            "lab momentum"
        },
        tr.lab_balance
            .iter()
            .map(|&b| norm(sub(b, b0)) / scale)
            .collect(),
    ));
    let rigid_free = cfg.spin == [0.0; 3]
        && cfg.quartic.is_none()
        && cfg.semi_rigid.is_none()
        && cfg.wheels.is_empty()
        && !cfg.torque.is_some()
        && matches!(cfg.method, Method::Step(_));
    let degrees = |a: &[UnitQuat<f64>], b: &dyn Fn(usize) -> UnitQuat<f64>| -> Vec<f64> {
        a.iter()
            .enumerate()
            .map(|(i, q)| q.angle_to(b(i)).to_degrees())
            .collect()
    };
    let attitude = if rigid_free {
        let exact = setup::<f64, 0>(cfg).and_then(|sim| {
            FreeRigidBody::try_new(sim.body.model().inertia(), &sim.start)
                .map_err(|e| e.to_string())
        });
        match exact {
            Ok(x) => Some((
                "attitude error vs the closed form (exact free rigid body)".to_string(),
                vec![Series::new(
                    if cfg.f32 { "f32" } else { "f64" },
                    degrees(&tr.attitude, &|i| x.state_at_unchecked(tr.t[i]).attitude),
                )],
            )),
            Err(_) => None,
        }
    } else if cfg.f32 {
        let reference = setup::<f64, N>(cfg)?;
        match reference.run(cfg, None, Some(plot_stride(cfg.steps))) {
            Ok(r) => Some((
                "attitude difference f32 vs the same run in f64".to_string(),
                vec![Series::new(
                    "f32 - f64",
                    degrees(&tr.attitude, &|i| r.trajectory.attitude[i]),
                )],
            )),
            Err(_) => None,
        }
    } else {
        None
    };
    let wheels = (0..N)
        .map(|i| {
            Series::new(
                format!("wheel{}", i + 1),
                tr.wheels.iter().map(|w| w[i]).collect(),
            )
        })
        .collect();
    let inertia = *build::<f64>(cfg)?.hamiltonian.inertia();
    let m = inertia.principal_moments();
    let precision = if cfg.f32 { "f32" } else { "f64" };
    let integ = match cfg.method {
        Method::Step(i) => format!("{i:?}").to_lowercase(),
        Method::Exact => "exact".into(),
    };
    Ok(Figure {
        title: format!(
            "simulate: {}{}, {integ}, dt = {} s, {} steps, {precision}{}",
            if cfg.semi_rigid.is_some() {
                "semi-rigid rotor, rest "
            } else {
                ""
            },
            format_args!("inertia ({}, {}, {})", m.x, m.y, m.z),
            cfg.dt,
            cfg.steps,
            match N {
                0 => String::new(),
                n => format!(", {n} wheel(s)"),
            }
        ),
        t: tr.t.clone(),
        rates: tr.omega.clone(),
        drift,
        attitude,
        wheels,
        momentum: tr.momentum.clone(),
        inertia,
        polhode_note: (N > 0
            || cfg.torque.is_some()
            || cfg.spin != [0.0; 3]
            || cfg.quartic.is_some()
            || cfg.semi_rigid.is_some())
        .then(|| {
            "curves: the rigid rotor of the (rest) inertia; rotors, quartic terms, wheels and \
             torques move J across them"
                .to_string()
        }),
    })
}

// ---------------------------------------------------------------------------------------------
// Default scenario

/// The default initial body rate: mostly about the intermediate axis, off the separatrix (with
/// these moments the separatrix is |J₁| = |J₃|, the seed's γ_B = 45° of (6.8.10)).
const DEFAULT_OMEGA0: [f64; 3] = [0.05, 1.0, 0.01];

struct Run {
    flips: Vec<f64>,
    energy_drift: f64,
    norm_drift: f64,
    lab_drift: f64,
    attitudes: Vec<UnitQuat<f64>>,
    /// Per sample (every `every` steps): body rate, body momentum, relative drift of energy,
    /// |J| and lab momentum.
    rates: Vec<[f64; 3]>,
    momenta: Vec<[f64; 3]>,
    drifts: Vec<[f64; 3]>,
}

fn simulate_default<T: Real>(integ: Integrator, dt: f64, steps: usize, every: usize) -> Run {
    let moments = [6.0, 4.0, 3.0];
    let inertia = Inertia::try_from_principal(v3::<T>(moments)).expect("physical");
    let body = Gyrostat::rigid(inertia);
    let mut s = body
        .try_state_from_omega(UnitQuat::IDENTITY, v3(DEFAULT_OMEGA0), [])
        .expect("finite");
    let mut monitor = DriftMonitor::new(body.invariants(&s));
    let mut flips = Vec::new();
    let mut attitudes = Vec::new();
    let (mut rates, mut momenta, mut drifts) = (Vec::new(), Vec::new(), Vec::new());
    let mut prev = s.momentum.y.to_f64();
    for k in 1..=steps {
        s = body.step(integ, &s, T::from_f64(dt)).expect("finite step");
        let jy = s.momentum.y.to_f64();
        if (jy > 0.0) != (prev > 0.0) {
            // Linear interpolation of the zero crossing of J₂.
            let t = (k as f64 - 1.0 + prev / (prev - jy)) * dt;
            flips.push(t);
        }
        prev = jy;
        let d = monitor.record(&body.invariants(&s));
        if k % every == 0 {
            attitudes.push(widen(s.attitude));
            rates.push(f3(body.omega(&s)));
            momenta.push(f3(s.momentum));
            drifts.push([d.energy, d.momentum_norm, d.lab_momentum].map(|x| x.to_f64()));
        }
    }
    let drift = monitor.worst();
    Run {
        flips,
        energy_drift: drift.energy.to_f64(),
        norm_drift: drift.momentum_norm.to_f64(),
        lab_drift: drift.lab_momentum.to_f64(),
        attitudes,
        rates,
        momenta,
        drifts,
    }
}

/// An attitude of any scalar type in f64.
fn widen<T: Real>(q: UnitQuat<T>) -> UnitQuat<f64> {
    UnitQuat::new_unchecked(Quat::from_array(q.to_array().map(|c| c.to_f64())))
}

/// The largest geodesic angle (degrees) between two attitude sequences.
fn max_angle_deg(a: &[UnitQuat<f64>], b: &[UnitQuat<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.angle_to(*y))
        .fold(0.0f64, f64::max)
        .to_degrees()
}

fn mean_interval(t: &[f64]) -> Option<f64> {
    if t.len() < 2 {
        return None;
    }
    Some((t[t.len() - 1] - t[0]) / (t.len() - 1) as f64)
}

fn default_scenario(plot_path: Option<PathBuf>) -> Result<(), String> {
    let (dt, steps, every) = (0.01, 20_000, 10);
    let integ = Integrator::Yoshida4;
    let r32 = simulate_default::<f32>(integ, dt, steps, every);
    let r64 = simulate_default::<f64>(integ, dt, steps, every);
    // The closed-form solution (Jacobi elliptic functions, Landau–Lifshitz §37) is the
    // reference for the flip interval 2K(m)/λ and for the attitude.
    let moments = [6.0, 4.0, 3.0];
    let inertia = Inertia::try_from_principal(v3::<f64>(moments)).map_err(|e| e.to_string())?;
    let start = Gyrostat::rigid(inertia)
        .try_state_from_omega(UnitQuat::IDENTITY, v3(DEFAULT_OMEGA0), [])
        .map_err(|e| e.to_string())?;
    let exact = FreeRigidBody::try_new(&inertia, &start).map_err(|e| e.to_string())?;
    let closed = exact.flip_interval();
    let exact_attitudes: Vec<UnitQuat<f64>> = (1..=steps / every)
        .map(|k| exact.state_at_unchecked((k * every) as f64 * dt).attitude)
        .collect();
    let err_vs_exact = |r: &Run| max_angle_deg(&r.attitudes, &exact_attitudes);
    let f32_vs_f64 = max_angle_deg(&r32.attitudes, &r64.attitudes);
    let mut text = String::new();
    let fmt_opt = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.4} s"));
    let _ = writeln!(
        text,
        "gyrostat simulate: the intermediate-axis (Dzhanibekov) flip"
    );
    let _ = writeln!(
        text,
        "  body: principal moments (6, 4, 3) kg m^2 (seed Fig. 6.8.1), spin w0 = (0.05, 1, 0.01) rad/s"
    );
    let _ = writeln!(
        text,
        "  integrator: yoshida4 (Lie-Poisson splitting), dt = {dt} s, {steps} steps ({:.0} s)",
        dt * steps as f64
    );
    let _ = writeln!(text);
    let _ = writeln!(
        text,
        "                          f32 core        f64 reference   closed form"
    );
    let _ = writeln!(
        text,
        "  flip interval (mean)    {:<15} {:<15} {}",
        fmt_opt(mean_interval(&r32.flips)),
        fmt_opt(mean_interval(&r64.flips)),
        closed.map_or("-".into(), |v| format!("{v:.4} s  (2K(m)/lambda)"))
    );
    let _ = writeln!(
        text,
        "  flips seen              {:<15} {:<15}",
        r32.flips.len(),
        r64.flips.len()
    );
    let _ = writeln!(
        text,
        "  max |dE/E|              {:<15.2e} {:<15.2e}",
        r32.energy_drift, r64.energy_drift
    );
    let _ = writeln!(
        text,
        "  max |d|J|/|J||          {:<15.2e} {:<15.2e}",
        r32.norm_drift, r64.norm_drift
    );
    let _ = writeln!(
        text,
        "  max |dJ_lab|/|J|        {:<15.2e} {:<15.2e}",
        r32.lab_drift, r64.lab_drift
    );
    let _ = writeln!(
        text,
        "  attitude error (deg)    {:<15.2e} {:<15.2e} (max over the run, vs the closed form)",
        err_vs_exact(&r32),
        err_vs_exact(&r64)
    );
    let _ = writeln!(
        text,
        "  f32 vs f64 attitude     {f32_vs_f64:.2e} deg (max over the run)"
    );
    let _ = writeln!(
        text,
        "  (near the separatrix the flip time depends on E logarithmically: the f32 rounding of E\n   \
         shifts the flips, which is most of the f32 attitude error; |J| and E stay bounded)"
    );
    if let (Some(c), Some(m)) = (closed, mean_interval(&r64.flips)) {
        let _ = writeln!(text);
        let _ = writeln!(
            text,
            "  f64 flip interval vs closed form: {:.2e} relative",
            (m - c).abs() / c
        );
    }
    let _ = writeln!(text);
    let _ = writeln!(
        text,
        "  run any case with flags; `simulate --help` lists them (CSV output)."
    );
    print_quietly(&text)?;
    let times: Vec<f64> = (1..=steps / every)
        .map(|k| (k * every) as f64 * dt)
        .collect();
    let column = |r: &Run, i: usize| r.drifts.iter().map(|d| d[i]).collect::<Vec<f64>>();
    let angles = |r: &Run| -> Vec<f64> {
        r.attitudes
            .iter()
            .zip(&exact_attitudes)
            .map(|(a, b)| a.angle_to(*b).to_degrees())
            .collect()
    };
    let figure = Figure {
        title: "simulate: the intermediate-axis flip, inertia (6, 4, 3), yoshida4, dt = 0.01 s"
            .to_string(),
        t: times,
        rates: r64.rates.clone(),
        drift: vec![
            Series::new("energy, f32", column(&r32, 0)),
            Series::new("|J|, f32", column(&r32, 1)),
            Series::new("energy, f64", column(&r64, 0)),
            Series::new("|J|, f64", column(&r64, 1)),
        ],
        attitude: Some((
            "attitude error vs the closed form (exact free rigid body)".to_string(),
            vec![
                Series::new("f32", angles(&r32)),
                Series::new("f64", angles(&r64)),
            ],
        )),
        wheels: Vec::new(),
        momentum: r64.momenta.clone(),
        inertia,
        polhode_note: None,
    };
    let path = plot_path.unwrap_or_else(default_plot_path);
    plot::write_svg(&path, &figure)?;
    print_quietly(&format!("  plot: {}\n", shown(&path).display()))
}

/// Writes `text` to stdout; a closed stdout is not an error.
fn print_quietly(text: &str) -> Result<(), String> {
    stream::print_text(text).map_err(|e| format!("writing stdout: {e}"))
}

/// Where the default scenario's plot goes: `simulate-default.svg` in the Cargo target directory
/// the binary was built in (`<target>/<profile>/simulate`, or `<target>/<triple>/<profile>/...`:
/// the nearest directory above the binary holding Cargo's `CACHEDIR.TAG`), so that running it
/// from a checkout leaves the work tree clean; the current directory otherwise (an installed
/// binary).
fn default_plot_path() -> PathBuf {
    let name = "simulate-default.svg";
    let exe = std::env::current_exe().ok();
    exe.as_deref()
        .into_iter()
        .flat_map(Path::ancestors)
        .skip(1)
        .take(3)
        .find(|dir| dir.join("CACHEDIR.TAG").is_file())
        .map_or_else(|| PathBuf::from(name), |target| target.join(name))
}

/// `path` relative to the current directory when it lies below it.
fn shown(path: &Path) -> PathBuf {
    std::env::current_dir()
        .ok()
        .and_then(|cwd| path.strip_prefix(cwd).ok().map(Path::to_path_buf))
        .unwrap_or_else(|| path.to_path_buf())
}
