//! `simulate`: rigid-body and gyrostat dynamics from the command line.
//!
//! With no arguments it runs the built-in scenario (a tumbling body showing the
//! intermediate-axis flip, f32 core beside the f64 reference), prints a short summary and writes
//! a plot. With flags it runs any case, reaction wheels and external torques included, and
//! writes CSV; see `--help`.

mod plot;

use std::fmt::{Display, Write as _};
use std::io::{self, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use gyrostat::dynamics::semi_rigid::Arrangement;
use gyrostat::dynamics::{BodyHamiltonian, FreeRigidBody, Quartic, State};
use gyrostat::{Real, UnitQuat};
use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::simulation::{
    self, Config, Fail, Impulse, MAX_WHEELS, Method, Outcome, Run, Semi, Sim, Spec, TorqueSchedule,
    WheelSpec, build, f3, max_angle_deg, mean_interval, norm, setup, sub, widen,
};
use gyrostat_tools::stream::{self, Csv};
use gyrostat_tools::{say, say_part, with_wheels};

use plot::{Figure, Series};

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
        Flag::switch("--compensated"),
    ],
};

const HELP: &str = "\
simulate: rigid-body / gyrostat attitude dynamics (gyrostat crate)

USAGE:
    simulate [--plot FILE.svg]
        Runs the built-in scenario: a body with the seed's inertia (6, 4, 3) spinning near its
        intermediate axis (the Dzhanibekov flip), integrated in f32 (compensated, and plain)
        beside the f64 reference, and prints a summary: flip interval vs the closed form 2K(m)/lambda, conserved-quantity
        drift, attitude error. It also writes a plot (SVG, see --plot) and prints its path:
        FILE.svg, or by default simulate-default.svg in the Cargo target directory the binary
        was built in (the current directory if it was not built in one).

    simulate (--inertia I1,I2,I3 [--inertia-offdiag I12,I13,I23] | --semi-rigid KIND:M,WV,R0)
             (--omega w1,w2,w3 | --momentum J1,J2,J3) [--spin S1,S2,S3]
             [--quartic octahedral:T4|cubic:T22] [--q0 w,x,y,z]
             [--wheel AX,AY,AZ,INERTIA[,SPEED0]]... [--wheel-torque T1,..,TN | --wheel-speed W1,..,WN]
             [--torque TX,TY,TZ | --torque-file FILE] [--plot FILE.svg]
             --dt H --steps N [--every K] --integrator rk4|strang|yoshida4|suzuki4|exact
             [--f32] [--compensated]
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
    --compensated               compensated steps: the state carries the rounding error of
                                each component beside it (f32 or f64), so the rounding of the
                                updates does not accumulate; every integrator but exact, with
                                wheels, wheel inputs and torques. The CSV shows the state's
                                rounded part (each value rounded to f32 or f64), as without
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

fn main() -> ExitCode {
    let f = match CLI.command_line() {
        Ok(f) => f,
        Err(status) => return status,
    };
    // No flags, or only --plot: the built-in scenario.
    let result = if f.names().all(|n| n == "--plot") {
        default_scenario(f.value("--plot").map(PathBuf::from))
    } else {
        config(&f).and_then(|(cfg, plot)| {
            let plot = plot.as_deref();
            if cfg.f32 {
                with_wheels!(cfg.wheels.len(), run_csv::<f32>(&cfg, plot))
            } else {
                with_wheels!(cfg.wheels.len(), run_csv::<f64>(&cfg, plot))
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

/// `--wheel AX,AY,AZ,INERTIA[,SPEED0]`, the `index`-th (1-based).
fn parse_wheel(index: usize, s: &str) -> Result<WheelSpec, String> {
    let v = flags::list("--wheel", s)?;
    if v.len() != 4 && v.len() != 5 {
        return Err(format!(
            "--wheel takes AX,AY,AZ,INERTIA[,SPEED0] (4 or 5 comma-separated numbers), got {s:?}"
        ));
    }
    WheelSpec::try_new(index, &v)
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
    if !matches!(kind.trim(), "octahedral" | "cubic" | "tetrahedral") {
        return Err(usage());
    }
    let v = flags::numbers::<3>(flag, numbers, "MASS,OMEGA_V,R0")?;
    if v.iter().any(|&x| x <= 0.0) {
        return Err(format!(
            "{flag}: MASS, OMEGA_V and R0 must be > 0, got {numbers:?}"
        ));
    }
    simulation::semi_rigid(flag, kind, v)
}

/// `--quartic octahedral:T4|cubic:T22`: (octahedral?, coefficient).
fn quartic(flag: &str, value: &str) -> Result<(bool, f64), String> {
    let (kind, t) = value
        .split_once(':')
        .ok_or_else(|| format!("{flag} takes octahedral:T4 or cubic:T22, got {value:?}"))?;
    let t = flags::number(flag, t)?;
    simulation::quartic(flag, kind, t)
}

/// The configuration of a CSV run and its `--plot`, from the flags given.
fn config(f: &Flags) -> Result<(Config, Option<PathBuf>), String> {
    let three =
        |fields: &'static str| move |flag: &str, v: &str| flags::numbers::<3>(flag, v, fields);
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
    let cfg = Spec {
        inertia: f.get("--inertia", three("I1,I2,I3"))?,
        inertia_offdiag: f.get("--inertia-offdiag", three("I12,I13,I23"))?,
        omega: f.get("--omega", three("w1,w2,w3"))?,
        momentum: f.get("--momentum", three("J1,J2,J3"))?,
        spin: f.get("--spin", three("S1,S2,S3"))?,
        quartic: f.get("--quartic", quartic)?,
        semi_rigid: f.get("--semi-rigid", semi_rigid)?,
        q0: f.get("--q0", |flag, v| flags::numbers::<4>(flag, v, "w,x,y,z"))?,
        dt: f.get("--dt", flags::positive)?,
        steps: f.get("--steps", flags::count)?,
        every: f.get("--every", flags::at_least_one)?,
        method: f.get("--integrator", simulation::integrator)?,
        wheels,
        wheel_torque: f.get("--wheel-torque", flags::list)?,
        wheel_speed: f.get("--wheel-speed", flags::list)?,
        torque: f.get("--torque", three("TX,TY,TZ"))?,
        torque_schedule: f
            .value("--torque-file")
            .map(|path| TorqueSchedule::File(path.to_string())),
        f32: f.switch("--f32"),
        compensated: f.switch("--compensated"),
    }
    .try_into_config()?;
    Ok((cfg, f.value("--plot").map(PathBuf::from)))
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

/// What a CSV run failed on: writing the CSV, or the simulation itself.
type RunFail = Fail<io::Error>;

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

/// One row of samples every this many steps in the plot (about 2000 samples per run).
fn plot_stride(steps: u64) -> u64 {
    steps.div_ceil(2000).max(1)
}

fn write_row<T: Real + Display, const N: usize>(
    sim: &Sim<T, N>,
    out: &mut dyn Write,
    cfg: &Config,
    k: u64,
    s: &State<T, N>,
) -> io::Result<()> {
    let t = T::from_f64(k as f64 * cfg.dt);
    let q = sim.attitude_at(s, t);
    let w = sim.omega(s);
    let j = s.momentum;
    let e = sim.energy(s);
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

/// Runs `cfg`, writing CSV to `csv` if given and sampling every `stride` steps if given (the
/// plot's trajectory).
fn run<T: Real + Display, const N: usize>(
    sim: &Sim<T, N>,
    cfg: &Config,
    mut csv: Option<&mut Csv>,
    stride: Option<u64>,
) -> Result<(Outcome, Trajectory), RunFail> {
    let mut traj = Trajectory::default();
    let mut progress = Progress::new(cfg.steps);
    let outcome = sim.run(cfg, |k, s: &State<T, N>, impulse: &Impulse| {
        if let Some(out) = csv.as_deref_mut() {
            if k == 0 {
                write!(out, "t,qw,qx,qy,qz,w1,w2,w3,J1,J2,J3,energy")?;
                for i in 1..=N {
                    write!(out, ",wheel{i}")?;
                }
                writeln!(out)?;
                write_row(sim, out, cfg, 0, s)?;
                out.flush()?;
            } else if k % cfg.every == 0 {
                write_row(sim, out, cfg, k, s)?;
                out.row_done()?;
            }
        }
        if let Some(n) = stride
            && (k % n == 0 || k == cfg.steps)
        {
            let t = k as f64 * cfg.dt;
            traj.t.push(t);
            traj.attitude
                .push(widen(sim.attitude_at(s, T::from_f64(t))));
            traj.omega.push(f3(sim.omega(s)));
            traj.momentum.push(f3(s.momentum));
            traj.wheels
                .push(s.wheel_speeds.iter().map(|w| w.to_f64()).collect());
            traj.energy.push(sim.energy(s).to_f64());
            let lab = f3(sim.body.invariants(s).lab_momentum);
            traj.lab_balance.push(sub(lab, impulse.lab));
        }
        progress.tick(k);
        Ok(())
    })?;
    if let Some(out) = csv {
        out.flush().map_err(Fail::Sink)?;
    }
    Ok((outcome, traj))
}

fn run_csv<T: Real + Display, const N: usize>(
    cfg: &Config,
    plot: Option<&Path>,
) -> Result<(), String> {
    let sim = setup::<T, N>(cfg)?;
    if cfg.semi_rigid.is_some() {
        let model = build::<f64>(cfg)?;
        if let Some(semi) = &model.semi {
            say_part!("{}", describe_semi(cfg, semi, &model.hamiltonian));
        }
    }
    if let Some(path) = plot {
        // Fail before any output when the plot cannot be written.
        std::fs::File::create(path).map_err(|e| format!("--plot {}: {e}", path.display()))?;
    }
    let mut out = Csv::stdout();
    let stride = plot.map(|_| plot_stride(cfg.steps));
    let (outcome, trajectory) = match run(&sim, cfg, Some(&mut out), stride) {
        Ok(o) => o,
        // A closed pipe (`simulate ... | head`) is not an error of the simulation; the run
        // stops there, and the plot file made empty above goes.
        Err(Fail::Sink(e)) if stream::is_closed_pipe(&e) => {
            if let Some(path) = plot {
                let _ = std::fs::remove_file(path);
            }
            return Ok(());
        }
        Err(Fail::Sink(e)) => return Err(format!("writing output: {e}")),
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
    if let Some(path) = plot {
        let figure = csv_figure::<N>(cfg, &trajectory)?;
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
    let integ = cfg.method.name();
    let what = match (N, cfg.torque.is_some()) {
        (0, _) => format!("external torque from {}", cfg.torque_source),
        (n, false) => format!("{n} wheel(s), no external torque"),
        (n, true) => format!("{n} wheel(s), external torque from {}", cfg.torque_source),
    };
    s += &format!(
        "simulate: monitors: {what}; {} steps of {} s ({integ}, {})\n",
        cfg.steps,
        cfg.dt,
        cfg.precision()
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
fn csv_figure<const N: usize>(cfg: &Config, tr: &Trajectory) -> Result<Figure, String> {
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
                    cfg.precision(),
                    degrees(&tr.attitude, &|i| x.state_at_unchecked(tr.t[i]).attitude),
                )],
            )),
            Err(_) => None,
        }
    } else if cfg.f32 {
        let reference = setup::<f64, N>(cfg)?;
        match run(&reference, cfg, None, Some(plot_stride(cfg.steps))) {
            Ok((_, r)) => Some((
                "attitude difference f32 vs the same run in f64".to_string(),
                vec![Series::new(
                    "f32 - f64",
                    degrees(&tr.attitude, &|i| r.attitude[i]),
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
    let precision = cfg.precision();
    let integ = cfg.method.name();
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

/// What the default scenario's numbers show (measured: the attitude errors against time and
/// E, |J| against time of the same runs through the CSV, BENCHMARKS.md).
const EXPLANATION: &str = "  \
  (plain f32: each step's rounding is kept, so E and |J| wander by about 1e-5 (100 f32 ulp);
   near the separatrix the flip time depends on E logarithmically, the flips drift, and the
   attitude error peaks during the flips, where the attitude moves fastest. Compensated f32
   carries each rounding error into the next step: E and |J| stay within a few ulp of the
   start, and its attitude error is the first column's)";

fn default_scenario(plot_path: Option<PathBuf>) -> Result<(), String> {
    // The closed-form solution (Jacobi elliptic functions, Landau–Lifshitz §37) is the
    // reference for the flip interval 2K(m)/λ and for the attitude.
    let scenario = simulation::default_scenario()?;
    let (dt, steps, every) = scenario.run;
    let (r32c, r32, r64) = (scenario.f32_compensated, scenario.f32, scenario.f64);
    let closed = scenario.flip_interval;
    let exact_attitudes = &scenario.exact;
    let inertia = scenario.inertia;
    let err_vs_exact = |r: &Run| max_angle_deg(&r.attitudes, exact_attitudes);
    let vs_f64 = |r: &Run| max_angle_deg(&r.attitudes, &r64.attitudes);
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
        "                          f32 compensated  f32 plain        f64 reference    closed form"
    );
    let _ = writeln!(
        text,
        "  flip interval (mean)    {:<16} {:<16} {:<16} {}",
        fmt_opt(mean_interval(&r32c.flips)),
        fmt_opt(mean_interval(&r32.flips)),
        fmt_opt(mean_interval(&r64.flips)),
        closed.map_or("-".into(), |v| format!("{v:.4} s  (2K(m)/lambda)"))
    );
    let _ = writeln!(
        text,
        "  flips seen              {:<16} {:<16} {:<16}",
        r32c.flips.len(),
        r32.flips.len(),
        r64.flips.len()
    );
    let row = |text: &mut String, label: &str, f: &dyn Fn(&Run) -> f64, note: &str| {
        let _ = writeln!(
            text,
            "  {label:<22}  {:<16.2e} {:<16.2e} {:<16.2e} {note}",
            f(&r32c),
            f(&r32),
            f(&r64)
        );
    };
    row(&mut text, "max |dE/E|", &|r| r.energy_drift, "");
    row(&mut text, "max |d|J|/|J||", &|r| r.norm_drift, "");
    row(&mut text, "max |dJ_lab|/|J|", &|r| r.lab_drift, "");
    row(
        &mut text,
        "attitude error (deg)",
        &err_vs_exact,
        "(max over the run, vs the closed form)",
    );
    let _ = writeln!(
        text,
        "  vs f64 attitude (deg)   {:<16.2e} {:<16.2e} {:<16} (max over the run)",
        vs_f64(&r32c),
        vs_f64(&r32),
        "-"
    );
    let _ = writeln!(text, "{}", EXPLANATION);
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
            .zip(exact_attitudes)
            .map(|(a, b)| a.angle_to(*b).to_degrees())
            .collect()
    };
    let figure = Figure {
        title: "simulate: the intermediate-axis flip, inertia (6, 4, 3), yoshida4, dt = 0.01 s"
            .to_string(),
        t: times,
        rates: r64.rates.clone(),
        drift: vec![
            Series::new("energy, f32 compensated", column(&r32c, 0)),
            Series::new("|J|, f32 compensated", column(&r32c, 1)),
            Series::new("energy, f32", column(&r32, 0)),
            Series::new("|J|, f32", column(&r32, 1)),
            Series::new("energy, f64", column(&r64, 0)),
            Series::new("|J|, f64", column(&r64, 1)),
        ],
        attitude: Some((
            "attitude error vs the closed form (exact free rigid body)".to_string(),
            vec![
                Series::new("f32 compensated", angles(&r32c)),
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
/// the nearest directory above the binary holding Cargo's `CACHEDIR.TAG` or `.rustc_info.json`:
/// Cargo writes the tag only into a target directory it creates itself), so that running it
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
        .find(|dir| dir.join("CACHEDIR.TAG").is_file() || dir.join(".rustc_info.json").is_file())
        .map_or_else(|| PathBuf::from(name), |target| target.join(name))
}

/// `path` relative to the current directory when it lies below it.
fn shown(path: &Path) -> PathBuf {
    std::env::current_dir()
        .ok()
        .and_then(|cwd| path.strip_prefix(cwd).ok().map(Path::to_path_buf))
        .unwrap_or_else(|| path.to_path_buf())
}
