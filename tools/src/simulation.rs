//! The scenarios of `simulate`, for the tool and for the Python package: a body (rigid, with a
//! gyro-rotor, a quartic term or a semi-rigid rotor), its reaction wheels and inputs (wheel
//! torques or speeds, a constant or scheduled external torque), the integrator, and the run that
//! steps it with its conserved-quantity monitors; and the built-in default scenario (the
//! intermediate-axis flip).
//!
//! A run is described by a [`Spec`] (the values of `simulate`'s flags, each optional as on the
//! command line), checked once into a [`Config`] ([`Spec::try_into_config`]); [`setup`] builds
//! the body and its initial state in a scalar type `T` with `N` wheels (the
//! [`with_wheels!`](crate::with_wheels) macro picks `N` at run time), and [`Sim::run`] steps
//! it, handing every state to the caller.
//! Error messages name the command-line flags (`--inertia`, `--wheel-torque`); the Python
//! package names its keyword arguments in their place.

use gyrostat::dynamics::semi_rigid::{Arrangement, QuarticBasis, SemiRigidRotor};
use gyrostat::dynamics::{
    BodyHamiltonian, CompensatedState, Control, DriftMonitor, FreeRigidBody, Gyrostat, Inertia,
    Integrator, Invariants, Quartic, State, StepState, Wheel, WheelCommand,
};
use gyrostat::{Error, Quat, Real, UnitQuat, Vec3};

use crate::torque::{ExternalTorque, Schedule};

/// The most wheels a run takes. The library's wheel count is a compile-time constant; the tool
/// and the package instantiate it for 0 to 4 wheels (three orthogonal wheels plus a skewed
/// spare, or a four-wheel pyramid).
pub const MAX_WHEELS: usize = 4;

/// Calls `f::<T, N>(args)` with the wheel count `N` a constant: one instance per count up to
/// [`MAX_WHEELS`]; more wheels are an `Err(String)`.
#[macro_export]
macro_rules! with_wheels {
    ($n:expr, $f:ident :: <$t:ty> ($($arg:expr),*)) => {
        match $n {
            0 => $f::<$t, 0>($($arg),*),
            1 => $f::<$t, 1>($($arg),*),
            2 => $f::<$t, 2>($($arg),*),
            3 => $f::<$t, 3>($($arg),*),
            4 => $f::<$t, 4>($($arg),*),
            n => Err(format!("at most {} --wheel, got {n}", $crate::simulation::MAX_WHEELS)),
        }
    };
}

// ---------------------------------------------------------------------------------------------
// The scenario

/// How the run is integrated (`--integrator`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// A step of the library's integrators.
    Step(Integrator),
    /// The closed-form torque-free rigid body (`exact`).
    Exact,
}

impl Method {
    /// The name `--integrator` takes: the integrator's [`Integrator::name`], or `exact`.
    pub const fn name(self) -> &'static str {
        match self {
            Method::Step(i) => i.name(),
            Method::Exact => "exact",
        }
    }
}

/// The initial condition: the body rate or the total body momentum.
#[derive(Debug, Clone, Copy)]
pub enum Initial {
    /// `--omega w1,w2,w3` (rad/s, body frame).
    Omega([f64; 3]),
    /// `--momentum J1,J2,J3` (N m s, body frame).
    Momentum([f64; 3]),
}

/// One `--wheel`.
#[derive(Debug, Clone, Copy)]
pub struct WheelSpec {
    /// Spin axis in the body frame (not zero; normalised by the library).
    pub axis: [f64; 3],
    /// Axial inertia, kg m^2, > 0.
    pub inertia: f64,
    /// Initial speed relative to the body, rad/s.
    pub speed0: f64,
}

impl WheelSpec {
    /// The `index`-th wheel (1-based) from `AX,AY,AZ,INERTIA[,SPEED0]`.
    ///
    /// # Errors
    /// A message naming `--wheel` for a wrong count, a zero axis or an inertia that is not > 0.
    pub fn try_new(index: usize, v: &[f64]) -> Result<Self, String> {
        if v.len() != 4 && v.len() != 5 {
            return Err(format!(
                "--wheel {index} takes AX,AY,AZ,INERTIA[,SPEED0] (4 or 5 numbers), got {}",
                v.len()
            ));
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(format!("--wheel {index}: every number must be finite"));
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
}

/// `--wheel-torque` or `--wheel-speed`.
#[derive(Debug, Clone)]
pub enum WheelInput {
    /// Constant motor torque per wheel, N m.
    Torque(Vec<f64>),
    /// Commanded speed per wheel (rad/s, relative to the body): an ideal speed loop.
    Speed(Vec<f64>),
}

/// The schedule of a `--torque-file`.
///
/// # Errors
/// `--torque-file FILE: reason` for a file that cannot be read or is not a schedule.
pub fn read_torque_file(path: &str) -> Result<Schedule, String> {
    let file = std::fs::File::open(path).map_err(|e| format!("--torque-file {path}: {e}"))?;
    Schedule::parse(crate::stream::Lines::new(file))
        .map_err(|e| format!("--torque-file {path}: {e}"))
}

/// The semi-rigid rotor `KIND` with `MASS,OMEGA_V,R0` (`--semi-rigid`): the kind named
/// octahedral, cubic or tetrahedral, the three numbers > 0.
///
/// # Errors
/// A message starting with `flag` for an unknown kind or a number that is not > 0.
pub fn semi_rigid(flag: &str, kind: &str, v: [f64; 3]) -> Result<(Arrangement, [f64; 3]), String> {
    let kind = match kind.trim() {
        "octahedral" => Arrangement::Octahedral,
        "cubic" => Arrangement::Cubic,
        "tetrahedral" => Arrangement::Tetrahedral,
        other => {
            return Err(format!(
                "{flag}: unknown kind {other:?} (octahedral, cubic or tetrahedral)"
            ));
        }
    };
    if v.iter().any(|&x| !(x > 0.0 && x.is_finite())) {
        return Err(format!(
            "{flag}: MASS, OMEGA_V and R0 must be finite and > 0, got {v:?}"
        ));
    }
    Ok((kind, v))
}

/// The quartic term `KIND` with coefficient `t` (`--quartic`): (octahedral?, coefficient).
///
/// # Errors
/// A message starting with `flag` for an unknown kind.
pub fn quartic(flag: &str, kind: &str, t: f64) -> Result<(bool, f64), String> {
    match kind.trim() {
        "octahedral" => Ok((true, t)),
        "cubic" => Ok((false, t)),
        other => Err(format!(
            "{flag}: unknown kind {other:?} (octahedral or cubic)"
        )),
    }
}

/// The integrator named `value` (`--integrator`): rk4, strang, yoshida4, suzuki4 or exact.
///
/// # Errors
/// A message starting with `flag` for any other name.
pub fn integrator(flag: &str, value: &str) -> Result<Method, String> {
    match value.trim() {
        e if e == Method::Exact.name() => Ok(Method::Exact),
        other => other.parse().map(Method::Step).map_err(|_| {
            let names = Integrator::ALL.map(Integrator::name).join(", ");
            format!("{flag}: unknown {other:?} ({names}, exact)")
        }),
    }
}

/// The values of `simulate`'s flags for a run, each as given (`None`: not given); checked
/// together by [`Spec::try_into_config`]. Each single value is already valid on its own
/// (positive `dt`, a known integrator, wheels checked by [`WheelSpec::try_new`]).
#[derive(Debug, Clone, Default)]
pub struct Spec {
    /// `--inertia I1,I2,I3`.
    pub inertia: Option<[f64; 3]>,
    /// `--inertia-offdiag I12,I13,I23`.
    pub inertia_offdiag: Option<[f64; 3]>,
    /// `--omega w1,w2,w3`.
    pub omega: Option<[f64; 3]>,
    /// `--momentum J1,J2,J3`.
    pub momentum: Option<[f64; 3]>,
    /// `--spin S1,S2,S3`.
    pub spin: Option<[f64; 3]>,
    /// `--quartic KIND:T`, see [`quartic`].
    pub quartic: Option<(bool, f64)>,
    /// `--semi-rigid KIND:MASS,OMEGA_V,R0`, see [`semi_rigid`].
    pub semi_rigid: Option<(Arrangement, [f64; 3])>,
    /// `--q0 w,x,y,z`.
    pub q0: Option<[f64; 4]>,
    /// The `--wheel`s, in order.
    pub wheels: Vec<WheelSpec>,
    /// `--wheel-torque T1,...`.
    pub wheel_torque: Option<Vec<f64>>,
    /// `--wheel-speed W1,...`.
    pub wheel_speed: Option<Vec<f64>>,
    /// `--torque TX,TY,TZ`.
    pub torque: Option<[f64; 3]>,
    /// `--torque-file FILE`, or a schedule given as rows.
    pub torque_schedule: Option<TorqueSchedule>,
    /// `--dt H` (> 0).
    pub dt: Option<f64>,
    /// `--steps N`.
    pub steps: Option<u64>,
    /// `--every K` (≥ 1).
    pub every: Option<u64>,
    /// `--integrator NAME`.
    pub method: Option<Method>,
    /// `--f32`.
    pub f32: bool,
    /// `--compensated`: step a [`CompensatedState`] (every integrator but `exact`).
    pub compensated: bool,
}

/// A torque schedule: a file to read (`--torque-file`) or rows at hand.
#[derive(Debug, Clone)]
pub enum TorqueSchedule {
    /// The CSV file of `--torque-file` (read by [`Spec::try_into_config`], after every other
    /// check).
    File(String),
    /// Rows `t, tx, ty, tz` checked by [`Schedule::try_new`].
    Rows(Schedule),
}

/// A checked run: a [`Spec`] whose values go together.
#[derive(Debug, Clone)]
pub struct Config {
    /// `--inertia` (`None` with `--semi-rigid`).
    pub inertia: Option<[f64; 3]>,
    /// `--inertia-offdiag` (zeros by default).
    pub offdiag: [f64; 3],
    /// `--omega` or `--momentum`.
    pub initial: Initial,
    /// `--spin` (zeros by default).
    pub spin: [f64; 3],
    /// `--quartic`: (octahedral?, coefficient).
    pub quartic: Option<(bool, f64)>,
    /// `--semi-rigid KIND:MASS,OMEGA_V,R0`.
    pub semi_rigid: Option<(Arrangement, [f64; 3])>,
    /// `--q0` (identity by default), unit within 1e-6.
    pub q0: [f64; 4],
    /// The wheels.
    pub wheels: Vec<WheelSpec>,
    /// `--wheel-torque` or `--wheel-speed`, one number per wheel.
    pub wheel_input: Option<WheelInput>,
    /// `--torque` or `--torque-file`.
    pub torque: ExternalTorque,
    /// Where the torque came from, for the summary.
    pub torque_source: String,
    /// `--dt`.
    pub dt: f64,
    /// `--steps`.
    pub steps: u64,
    /// `--every` (1 by default).
    pub every: u64,
    /// `--integrator`.
    pub method: Method,
    /// `--f32`.
    pub f32: bool,
    /// `--compensated`: the run steps a [`CompensatedState`]; the states handed out are its
    /// rounded part [`CompensatedState::state`].
    pub compensated: bool,
}

impl Config {
    /// `"f32"` or `"f64"`, with `" compensated"` for a compensated run.
    pub fn precision(&self) -> &'static str {
        match (self.f32, self.compensated) {
            (true, false) => "f32",
            (true, true) => "f32 compensated",
            (false, false) => "f64",
            (false, true) => "f64 compensated",
        }
    }

    /// `true` when a step needs an input (external or wheel torque).
    pub fn has_input(&self) -> bool {
        self.torque.is_some() || self.wheel_input.is_some()
    }

    /// `true` for the new physics (wheels, torques) whose monitors are summarised on stderr.
    pub fn has_actuators(&self) -> bool {
        !self.wheels.is_empty() || self.torque.is_some()
    }
}

impl Spec {
    /// The run these values describe, or why they do not go together (a missing value, two
    /// that exclude each other, a value another one rules out).
    ///
    /// # Errors
    /// One line naming the flags concerned.
    pub fn try_into_config(self) -> Result<Config, String> {
        let Spec {
            inertia,
            inertia_offdiag: offdiag,
            omega,
            momentum,
            spin,
            quartic,
            semi_rigid,
            q0,
            wheels,
            wheel_torque,
            wheel_speed,
            torque,
            torque_schedule,
            dt,
            steps,
            every,
            method,
            f32,
            compensated,
        } = self;
        if wheels.len() > MAX_WHEELS {
            return Err(format!(
                "at most {MAX_WHEELS} --wheel (the capacity of this tool)"
            ));
        }
        let initial = match (omega, momentum) {
            (Some(w), None) => Initial::Omega(w),
            (None, Some(j)) => Initial::Momentum(j),
            (Some(_), Some(_)) => {
                return Err("give either --omega or --momentum, not both".into());
            }
            (None, None) => return Err("missing --omega or --momentum".into()),
        };
        let dt = dt.ok_or("missing --dt")?;
        let every = every.unwrap_or(1);
        let spin = spin.unwrap_or([0.0; 3]);
        let method = method.ok_or("missing --integrator")?;
        if compensated && method == Method::Exact {
            return Err(
                "--compensated needs a stepping integrator (rk4, strang, yoshida4, suzuki4); \
                 --integrator exact is the closed form, it has no compensated form"
                    .into(),
            );
        }
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
                    torque.is_some() || torque_schedule.is_some(),
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
                    "--integrator exact is for torque-free rigid bodies only (no --semi-rigid)"
                        .into(),
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
        if (n - 1.0).abs() > 1e-6 || n.is_nan() {
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
        let (torque, torque_source) = match (torque, torque_schedule) {
            (Some(_), Some(_)) => {
                return Err("give either --torque or --torque-file, not both".into());
            }
            (Some(t), None) => (ExternalTorque::Constant(t), "--torque".to_string()),
            (None, Some(TorqueSchedule::File(path))) => (
                ExternalTorque::Schedule(read_torque_file(&path)?),
                format!("--torque-file {path}"),
            ),
            (None, Some(TorqueSchedule::Rows(schedule))) => (
                ExternalTorque::Schedule(schedule),
                "a torque schedule".to_string(),
            ),
            (None, None) => (ExternalTorque::None, String::new()),
        };
        if method == Method::Exact && (!wheels.is_empty() || torque.is_some()) {
            return Err(
                "--integrator exact is for torque-free rigid bodies only (no --wheel, no \
                 --torque, no --torque-file)"
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
            dt,
            steps: steps.ok_or("missing --steps")?,
            every,
            method,
            f32,
            compensated,
        })
    }
}

// ---------------------------------------------------------------------------------------------
// The body and its run

/// Three numbers as a vector of `T`.
pub fn v3<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]))
}

/// A vector of `T` as three f64 numbers.
pub fn f3<T: Real>(v: Vec3<T>) -> [f64; 3] {
    v.to_array().map(|c| c.to_f64())
}

/// A semi-rigid rotor and the basis its quartic is split in (the anisotropic part in the
/// [`BodyHamiltonian`], the isotropic `t|J|⁴` applied as its exact turn).
#[derive(Clone, Copy)]
pub struct Semi<T> {
    /// The rotor.
    pub rotor: SemiRigidRotor<T>,
    /// The basis of its quartic.
    pub basis: QuarticBasis,
}

/// The body model of `cfg`.
pub struct Model<T> {
    /// The Hamiltonian of the body (with the anisotropic quartic of a semi-rigid rotor).
    pub hamiltonian: BodyHamiltonian<T>,
    /// The semi-rigid rotor, if any.
    pub semi: Option<Semi<T>>,
}

/// The body model of `cfg` in `T`.
///
/// # Errors
/// A message naming the flags of a non-physical body.
pub fn build<T: Real>(cfg: &Config) -> Result<Model<T>, String> {
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
pub struct Sim<T, const N: usize> {
    /// The body.
    pub body: Gyrostat<T, N>,
    /// The initial state.
    pub start: State<T, N>,
    /// The closed-form motion (`--integrator exact`).
    pub exact: Option<FreeRigidBody<T>>,
    /// The semi-rigid rotor, if any.
    pub semi: Option<Semi<T>>,
}

/// The body of `cfg` with `N` wheels in `T`, and its initial state.
///
/// # Errors
/// A message naming the flags of a body, wheel or initial condition the library rejects.
pub fn setup<T: Real, const N: usize>(cfg: &Config) -> Result<Sim<T, N>, String> {
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

/// A state a run steps: a plain [`State`] or a [`CompensatedState`] (`--compensated`).
pub trait Carry<T: Real, const N: usize>: StepState<T, N> + Copy {
    /// The state starting at `s` (for a compensated state, every low-order part zero).
    fn from_state(s: State<T, N>) -> Self;
    /// The state rounded to `T`: the state itself, or [`CompensatedState::state`].
    fn rounded(&self) -> &State<T, N>;
}

impl<T: Real, const N: usize> Carry<T, N> for State<T, N> {
    fn from_state(s: State<T, N>) -> Self {
        s
    }
    fn rounded(&self) -> &State<T, N> {
        self
    }
}

impl<T: Real, const N: usize> Carry<T, N> for CompensatedState<T, N> {
    fn from_state(s: State<T, N>) -> Self {
        CompensatedState::new(s)
    }
    fn rounded(&self) -> &State<T, N> {
        self.state()
    }
}

/// What a run failed on: the caller's handling of a state (`Sink`), or the simulation itself.
#[derive(Debug)]
pub enum Fail<E> {
    /// The error the caller's function returned.
    Sink(E),
    /// A step the library rejected or a state that is no longer finite (the message says which).
    Msg(String),
}

/// The integrated external torque of a run so far: `∫R(q)τ dt` (lab frame) and `∫|τ| dt`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Impulse {
    /// `∫R(q)τ dt`, N m s (lab frame).
    pub lab: [f64; 3],
    /// `∫|τ| dt`, N m s.
    pub magnitude: f64,
}

/// The monitors of a run, in f64.
#[derive(Clone, Copy, Debug)]
pub struct Outcome {
    /// Lab-frame total momentum `R(q)J` at the start.
    pub lab0: [f64; 3],
    /// ... and at the end.
    pub lab_end: [f64; 3],
    /// The integrated external torque.
    pub impulse: Impulse,
    /// The largest relative drift of the lab-frame momentum over the run.
    pub lab_drift_max: f64,
    /// The largest relative drift of `|J|` over the run.
    pub norm_drift_max: f64,
    /// The energy `H(J)` at the start.
    pub energy0: f64,
    /// ... and at the end.
    pub energy_end: f64,
}

/// `|v|`.
pub fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// `a − b`.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

impl<T: Real, const N: usize> Sim<T, N> {
    /// The attitude written out at time `t`: the state's, followed by the isotropic turn of a
    /// semi-rigid rotor (the exact flow of `t|J|⁴`, which commutes with the rest).
    pub fn attitude_at(&self, s: &State<T, N>, t: T) -> UnitQuat<T> {
        match &self.semi {
            None => s.attitude,
            Some(semi) => semi
                .rotor
                .isotropic_turn(semi.basis, s.momentum, t)
                .map_or(s.attitude, |turn| s.attitude * turn),
        }
    }

    /// The body rate `∇H(J)`, with `4t|J|²J` of a semi-rigid rotor's isotropic term.
    pub fn omega(&self, s: &State<T, N>) -> Vec3<T> {
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
    pub fn energy(&self, s: &State<T, N>) -> T {
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
    pub fn invariants(&self, s: &State<T, N>) -> Invariants<T> {
        Invariants {
            energy: self.energy(s),
            ..self.body.invariants(s)
        }
    }

    /// The state after step `k` (from `(k−1)·dt` to `k·dt`); adds the step's external torque to
    /// `impulse` (`∫R(q)τ dt` by the trapezoid rule on each piece of constant torque).
    pub fn advance<S: Carry<T, N>>(
        &self,
        cfg: &Config,
        state: &S,
        k: u64,
        impulse: &mut Impulse,
    ) -> Result<S, String> {
        // The library's checked steps reject a step that turns the body by more than half a
        // turn (`|w| dt` at either end, `MAX_STEP_ANGLE`) with `StepTooLong`.
        let fail = |e: Error| format!("step {k}: {e} (the step is too long for these rates?)");
        let integ = match (cfg.method, &self.exact) {
            (Method::Exact, Some(x)) => {
                let s = x.state_at_unchecked(T::from_f64(k as f64 * cfg.dt));
                return Ok(S::from_state(State {
                    attitude: s.attitude,
                    momentum: s.momentum,
                    wheel_speeds: state.rounded().wheel_speeds,
                }));
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
                    .control(state.rounded(), dt, Vec3::ZERO, &command)
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
            let before = widen(s.rounded().attitude);
            s = self
                .body
                .step_with(integ, &s, T::from_f64(lo), T::from_f64(h), control)
                .map_err(fail)?;
            if tau != [0.0; 3] {
                let tau = Vec3::new(tau[0], tau[1], tau[2]);
                let avg =
                    (before.rotate(tau) + widen(s.rounded().attitude).rotate(tau)).scale(0.5 * h);
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
    pub fn check(&self, cfg: &Config, k: u64, s: &State<T, N>) -> Result<(), String> {
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

    /// Runs `cfg`: calls `each(k, state, impulse)` with the initial state (`k = 0`) and with
    /// the state after every step `k = 1..=steps` (the caller keeps what it wants: every K-th
    /// row, a plot's samples), and returns the monitors. Stops at the first error of a step, a
    /// state check or `each`.
    ///
    /// # Errors
    /// [`Fail::Msg`] for a step the library rejects or a state that is not finite (the states
    /// before it were handed to `each`); [`Fail::Sink`] with the error of `each`.
    ///
    /// With [`Config::compensated`] the run steps a [`CompensatedState`] and hands out its
    /// rounded part [`CompensatedState::state`] (each component the pair's value rounded to
    /// `T`); the monitors are those of the rounded part.
    pub fn run<E>(
        &self,
        cfg: &Config,
        each: impl FnMut(u64, &State<T, N>, &Impulse) -> Result<(), E>,
    ) -> Result<Outcome, Fail<E>> {
        if cfg.compensated {
            self.run_with::<CompensatedState<T, N>, E>(cfg, each)
        } else {
            self.run_with::<State<T, N>, E>(cfg, each)
        }
    }

    /// [`Sim::run`] stepping states of type `S`.
    fn run_with<S: Carry<T, N>, E>(
        &self,
        cfg: &Config,
        mut each: impl FnMut(u64, &State<T, N>, &Impulse) -> Result<(), E>,
    ) -> Result<Outcome, Fail<E>> {
        let mut state = S::from_state(self.start);
        self.check(cfg, 0, state.rounded()).map_err(Fail::Msg)?;
        let inv0 = self.invariants(state.rounded());
        let mut monitor = DriftMonitor::new(inv0);
        let mut impulse = Impulse::default();
        each(0, state.rounded(), &impulse).map_err(Fail::Sink)?;
        for k in 1..=cfg.steps {
            state = self
                .advance(cfg, &state, k, &mut impulse)
                .and_then(|s| self.check(cfg, k, s.rounded()).map(|()| s))
                .map_err(Fail::Msg)?;
            monitor.record(&self.invariants(state.rounded()));
            each(k, state.rounded(), &impulse).map_err(Fail::Sink)?;
        }
        let end = self.invariants(state.rounded());
        Ok(Outcome {
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

// ---------------------------------------------------------------------------------------------
// Default scenario

/// The default initial body rate: mostly about the intermediate axis, off the separatrix (with
/// these moments the separatrix is |J₁| = |J₃|, the seed's γ_B = 45° of (6.8.10)).
pub const DEFAULT_OMEGA0: [f64; 3] = [0.05, 1.0, 0.01];

/// The default scenario's principal moments (seed Fig. 6.8.1), kg m^2.
pub const DEFAULT_MOMENTS: [f64; 3] = [6.0, 4.0, 3.0];

/// The default scenario's step (s), number of steps and sample interval (steps).
pub const DEFAULT_RUN: (f64, usize, usize) = (0.01, 20_000, 10);

/// The integrator of the built-in scenario.
pub const DEFAULT_INTEGRATOR: Integrator = Integrator::Yoshida4;

/// One run of the default scenario in one scalar type, in f64.
#[derive(Clone, Debug)]
pub struct Run {
    /// The times of the flips: the zero crossings of `J₂` (linearly interpolated).
    pub flips: Vec<f64>,
    /// The largest relative energy drift over the run.
    pub energy_drift: f64,
    /// The largest relative drift of `|J|`.
    pub norm_drift: f64,
    /// The largest relative drift of the lab-frame momentum.
    pub lab_drift: f64,
    /// Per sample (every `every` steps, from step `every` on): the attitude.
    pub attitudes: Vec<UnitQuat<f64>>,
    /// Per sample: the body rate.
    pub rates: Vec<[f64; 3]>,
    /// Per sample: the body momentum.
    pub momenta: Vec<[f64; 3]>,
    /// Per sample: the relative drift of energy, |J| and lab momentum.
    pub drifts: Vec<[f64; 3]>,
}

/// The default scenario in `T`: the body of [`DEFAULT_MOMENTS`] spun at [`DEFAULT_OMEGA0`],
/// `steps` steps of `dt` with `integ`, sampled every `every` steps; with `compensated` the
/// steps advance a [`CompensatedState`] and the run records its rounded part.
///
/// # Errors
/// The library's error of a step (none with the default run: it is part of the tests).
pub fn simulate_default<T: Real>(
    integ: Integrator,
    dt: f64,
    steps: usize,
    every: usize,
    compensated: bool,
) -> Result<Run, Error> {
    if compensated {
        simulate_default_with::<T, CompensatedState<T>>(integ, dt, steps, every)
    } else {
        simulate_default_with::<T, State<T>>(integ, dt, steps, every)
    }
}

/// [`simulate_default`] stepping states of type `S`.
fn simulate_default_with<T: Real, S: Carry<T, 0>>(
    integ: Integrator,
    dt: f64,
    steps: usize,
    every: usize,
) -> Result<Run, Error> {
    let inertia = Inertia::try_from_principal(v3::<T>(DEFAULT_MOMENTS))?;
    let body = Gyrostat::rigid(inertia);
    let mut carried =
        S::from_state(body.try_state_from_omega(UnitQuat::IDENTITY, v3(DEFAULT_OMEGA0), [])?);
    let mut s = *carried.rounded();
    let mut monitor = DriftMonitor::new(body.invariants(&s));
    let mut flips = Vec::new();
    let mut attitudes = Vec::new();
    let (mut rates, mut momenta, mut drifts) = (Vec::new(), Vec::new(), Vec::new());
    let mut prev = s.momentum.y.to_f64();
    for k in 1..=steps {
        carried = body.step(integ, &carried, T::from_f64(dt))?;
        s = *carried.rounded();
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
    Ok(Run {
        flips,
        energy_drift: drift.energy.to_f64(),
        norm_drift: drift.momentum_norm.to_f64(),
        lab_drift: drift.lab_momentum.to_f64(),
        attitudes,
        rates,
        momenta,
        drifts,
    })
}

/// The built-in scenario of `simulate`: the intermediate-axis flip run with yoshida4 in f32
/// (compensated and plain) beside f64, and the closed form (exact free rigid body) as the reference.
pub struct DefaultScenario {
    /// The step (s), number of steps and sample interval ([`DEFAULT_RUN`]).
    pub run: (f64, usize, usize),
    /// The body's inertia.
    pub inertia: Inertia<f64>,
    /// The f32 run, plain.
    pub f32: Run,
    /// The f32 run, compensated ([`CompensatedState`]).
    pub f32_compensated: Run,
    /// The f64 run.
    pub f64: Run,
    /// The closed-form flip interval `2K(m)/λ` (s).
    pub flip_interval: Option<f64>,
    /// The closed-form attitude at each sample time.
    pub exact: Vec<UnitQuat<f64>>,
}

/// Runs the built-in scenario.
///
/// # Errors
/// The library's error (none: the scenario is fixed and tested).
pub fn default_scenario() -> Result<DefaultScenario, String> {
    let (dt, steps, every) = DEFAULT_RUN;
    let integ = DEFAULT_INTEGRATOR;
    let e = |e: Error| e.to_string();
    let r32 = simulate_default::<f32>(integ, dt, steps, every, false).map_err(e)?;
    let r32c = simulate_default::<f32>(integ, dt, steps, every, true).map_err(e)?;
    let r64 = simulate_default::<f64>(integ, dt, steps, every, false).map_err(e)?;
    // The closed-form solution (Jacobi elliptic functions, Landau–Lifshitz §37) is the
    // reference for the flip interval 2K(m)/λ and for the attitude.
    let inertia = Inertia::try_from_principal(v3::<f64>(DEFAULT_MOMENTS)).map_err(e)?;
    let start = Gyrostat::rigid(inertia)
        .try_state_from_omega(UnitQuat::IDENTITY, v3(DEFAULT_OMEGA0), [])
        .map_err(e)?;
    let exact = FreeRigidBody::try_new(&inertia, &start).map_err(e)?;
    let exact_attitudes: Vec<UnitQuat<f64>> = (1..=steps / every)
        .map(|k| exact.state_at_unchecked((k * every) as f64 * dt).attitude)
        .collect();
    Ok(DefaultScenario {
        run: DEFAULT_RUN,
        inertia,
        f32: r32,
        f32_compensated: r32c,
        f64: r64,
        flip_interval: exact.flip_interval(),
        exact: exact_attitudes,
    })
}

/// An attitude of any scalar type in f64.
pub fn widen<T: Real>(q: UnitQuat<T>) -> UnitQuat<f64> {
    UnitQuat::new_unchecked(Quat::from_array(q.to_array().map(|c| c.to_f64())))
}

/// The largest geodesic angle (degrees) between two attitude sequences.
pub fn max_angle_deg(a: &[UnitQuat<f64>], b: &[UnitQuat<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.angle_to(*y))
        .fold(0.0f64, f64::max)
        .to_degrees()
}

/// The mean interval between successive times (`None` for fewer than two).
pub fn mean_interval(t: &[f64]) -> Option<f64> {
    if t.len() < 2 {
        return None;
    }
    Some((t[t.len() - 1] - t[0]) / (t.len() - 1) as f64)
}
