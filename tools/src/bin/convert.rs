//! `convert`: a command-line attitude converter for ground tools and scripts.
//!
//! ```text
//! convert --from REP --to REP [--f32] [--degrees] [--normalize]
//! convert --op OP --from REP [--to REP] [...]
//! ```
//!
//! Reads CSV rows from stdin, writes CSV rows to stdout; see `--help` (the `HELP` text below)
//! for the formats. Host-only: the library stays `no_std`, the I/O lives here.

use std::fmt::Debug;
use std::io::{self, Write};
use std::process::ExitCode;
use std::str::FromStr;

use gyrostat::rotation::{
    AxisAngle, Dcm, Euler, EulerSequence, Gibbs, GimbalPolicy, Mrp, RotationVector,
};
use gyrostat::{Error, Mat3, Quat, Real, UnitQuat, Vec3};
use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::stream;

const CLI: Cli = Cli {
    name: "convert",
    help: HELP,
    flags: &[
        Flag::value("--from"),
        Flag::value("--to"),
        Flag::value("--op"),
        Flag::switch("--f32"),
        Flag::switch("--degrees"),
        Flag::switch("--normalize"),
    ],
};

const HELP: &str = "\
convert: convert attitudes between representations (gyrostat)

USAGE:
    convert --from REP --to REP [--f32] [--degrees] [--normalize]
    convert --op OP --from REP [--to REP] [--f32] [--degrees] [--normalize]

    Flags take their value as the next argument or after `=` (--from quat, --from=quat); a flag
    given twice is an error.

Reads CSV rows from stdin and writes CSV rows to stdout, no header either way: one output row
per valid input row, in order. Blank lines (empty or only blanks) are skipped, the last one
too, but counted for line numbers. Rows are written as they are converted (flushed at least
every 0.1 s and whenever the input stalls).

REP (field order of a row):
    quat         w,x,y,z            Hamilton, scalar first; maps body vectors to the lab frame
    quat-xyzw    x,y,z,w            the same quaternion, scalar last (scipy's as_quat/from_quat
                                    default order)
    matrix       r00,r01,r02,r10,r11,r12,r20,r21,r22
                                    rotation matrix, row-major; columns are the body axes
                                    (maps body coordinates to lab coordinates: [NB])
    dcm-bn       r00,...,r22        the transpose of matrix, row-major: the passive (frame-
                                    transformation) matrix [BN] that maps lab (N) coordinates of
                                    a vector to body (B) coordinates (Basilisk's dcm_BN); its
                                    rows are the body axes
    rotvec       x,y,z              rotation vector (angle * unit axis)
    mrp          x,y,z              modified Rodrigues parameters (output has |mrp| <= 1)
    gibbs        x,y,z              Gibbs vector / classical Rodrigues parameters,
                                    axis * tan(angle/2) (Basilisk's CRP); infinite at 180 degrees:
                                    such an output row is an error
    axis-angle   ax,ay,az,angle     axis (normalised on input) and angle
    euler:SEQ    a,b,c              Euler angles; SEQ is three letters from xyz, e.g. ZYX or zyx:
                                    uppercase = intrinsic (R = R_Z(a) R_Y(b) R_X(c)),
                                    lowercase = extrinsic (R = R_x(c) R_y(b) R_z(a)),
                                    exactly the meaning of scipy.spatial.transform.Rotation.
                                    OUTPUT rows get a 4th column: 1 if the attitude is at the
                                    gimbal-lock singularity (middle angle within 2*epsilon of its
                                    pole: 2.2e-16*2 in f64, 1.2e-7*2 with --f32), else 0. At a
                                    gimbal lock the third angle is set to 0 (scipy's choice).

OP (one output row per input row; A and B are attitudes in the --from representation, each
its fields in order, the row holding them one after the other):
    compose      A,B      -> A * B (Hamilton product; A after B, scipy's r_a * r_b), --to REP
    inverse      A        -> A^-1, --to REP
    relative     A,B      -> A^-1 * B, the rotation taking A to B in A's body frame
                             (B = A * relative; scipy's r_a.inv() * r_b), --to REP
    rotate       A,vx,vy,vz
                          -> R(A) v: the body vector v in lab coordinates, vx,vy,vz (no --to)
    slerp        A,B,t    -> the attitude a fraction t of the way from A to B along the shorter
                             great arc (t = 0: A, t = 1: B; other t extrapolate), --to REP
    euler-rates      a,b,c of --from euler:SEQ
                          -> E_body, 9 numbers row-major, with w_body = E_body [a', b', c']
                             (rates in the order of SEQ's letters; seed (6.7.5d) for ZYZ) (no --to)
    euler-rates-lab  a,b,c of --from euler:SEQ
                          -> E_lab, with w_lab = E_lab [a', b', c'] (seed (6.7.5c)) (no --to)

OPTIONS:
    --from REP   input representation (required)
    --to REP     output representation (required, except for --op rotate and the euler-rates ops,
                 which reject it)
    --op OP      an operation instead of a plain conversion (see OP)
    --f32        do the conversion in f32 (inputs are rounded to f32)
    --degrees    angles in degrees instead of radians, on input and output alike: the three
                 euler angles, the axis-angle angle (4th field) and the rotvec length (the whole
                 rotvec is scaled by 180/pi, like scipy's degrees=True); with --op euler-rates the
                 input angles (the matrix itself is dimensionless: rates in deg/s give w in
                 deg/s). Unaffected: quat, quat-xyzw, matrix, dcm-bn, mrp and gibbs (dimensionless),
                 the slerp fraction t and the rotate vector
    --normalize  accept input that is not exactly an attitude, on purpose: a quaternion of any
                 finite non-zero norm is divided by its norm, and a matrix with positive
                 determinant is replaced by the nearest rotation matrix (its orthogonal polar
                 factor, like scipy's from_matrix). Without it the input is checked strictly
                 (see ERRORS)
    -h, --help   print this help

OUTPUT NUMBERS:
    shortest decimal that parses back to the same f64 (or f32 with --f32) value.

Output quaternions are the SO(3) representative with w >= 0 (ties: first non-zero of x, y, z
positive), in both orders; output axis-angle has angle in [0, pi] (axis +x for the identity);
output rotvec has length <= pi.

ERRORS:
    A malformed or invalid row (wrong field count, a field that is not a number, NaN or infinity,
    a zero or far-from-unit quaternion (| |q| - 1 | > 1e-3), a matrix that is not a rotation
    (|R^T R - 1| > 1e-3 or det <= 0), a zero axis, a 180-degree rotation written as gibbs, a
    line that is not UTF-8 text or longer than 1 MiB, values so small or large that the result
    would not be finite) writes
        error: line N: reason
    to stderr and no output row; the run continues with the next line and exits with status 1
    at the end. With --normalize a zero quaternion and a matrix with det <= 0 are still errors.
    Bad command-line arguments print `error: reason` and exit with status 2, before any output.
    When stdout is closed early (a pipe into `head`), the run stops quietly with the status it
    would have had if the input ended there.
";

/// Tolerance on `|q|` and on `‖RᵀR − 1‖` for input rows: data printed with at least 4
/// significant digits passes; anything further off is not an attitude.
const INPUT_TOL: f64 = 1e-3;

#[derive(Clone, Copy, Debug)]
enum Rep {
    Quat,
    QuatXyzw,
    Matrix,
    DcmBn,
    RotVec,
    Mrp,
    Gibbs,
    AxisAngle,
    Euler(EulerSequence),
}

impl Rep {
    fn parse(s: &str) -> Result<Self, String> {
        Ok(match s {
            "quat" => Rep::Quat,
            "quat-xyzw" => Rep::QuatXyzw,
            "matrix" => Rep::Matrix,
            "dcm-bn" => Rep::DcmBn,
            "rotvec" => Rep::RotVec,
            "mrp" => Rep::Mrp,
            "gibbs" => Rep::Gibbs,
            "axis-angle" => Rep::AxisAngle,
            _ => match s.strip_prefix("euler:") {
                Some(seq) => Rep::Euler(
                    EulerSequence::try_from_str(seq)
                        .map_err(|_| format!("invalid Euler sequence '{seq}'"))?,
                ),
                None => return Err(format!("unknown representation '{s}'")),
            },
        })
    }

    fn fields(self) -> usize {
        match self {
            Rep::Quat | Rep::QuatXyzw | Rep::AxisAngle => 4,
            Rep::Matrix | Rep::DcmBn => 9,
            Rep::RotVec | Rep::Mrp | Rep::Gibbs | Rep::Euler(_) => 3,
        }
    }
}

/// What a row is turned into.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    /// A plain conversion `A → A`.
    Convert,
    Compose,
    Inverse,
    Relative,
    Rotate,
    Slerp,
    EulerRates,
    EulerRatesLab,
}

impl Op {
    fn parse(s: &str) -> Result<Self, String> {
        Ok(match s {
            "compose" => Op::Compose,
            "inverse" => Op::Inverse,
            "relative" => Op::Relative,
            "rotate" => Op::Rotate,
            "slerp" => Op::Slerp,
            "euler-rates" => Op::EulerRates,
            "euler-rates-lab" => Op::EulerRatesLab,
            _ => {
                return Err(format!(
                    "unknown operation '{s}' (compose, inverse, relative, rotate, slerp, \
                     euler-rates, euler-rates-lab)"
                ));
            }
        })
    }

    /// `true` when the output is an attitude in the `--to` representation.
    fn writes_attitude(self) -> bool {
        !matches!(self, Op::Rotate | Op::EulerRates | Op::EulerRatesLab)
    }
}

struct Opts {
    from: Rep,
    /// The output representation (`None` for an operation that writes no attitude).
    to: Option<Rep>,
    op: Op,
    f32: bool,
    degrees: bool,
    normalize: bool,
}

impl Opts {
    /// The number of fields of an input row.
    fn fields(&self) -> usize {
        let n = self.from.fields();
        match self.op {
            Op::Convert | Op::Inverse | Op::EulerRates | Op::EulerRatesLab => n,
            Op::Compose | Op::Relative => 2 * n,
            Op::Rotate => n + 3,
            Op::Slerp => 2 * n + 1,
        }
    }
}

/// The options of a run, from the flags given.
fn options(f: &Flags) -> Result<Opts, String> {
    let rep = |flag: &str, v: &str| Rep::parse(v).map_err(|e| format!("{flag}: {e}"));
    let from = f.get("--from", rep)?;
    let to = f.get("--to", rep)?;
    let op = f.get("--op", |flag, v| {
        Op::parse(v).map_err(|e| format!("{flag}: {e}"))
    })?;
    let (f32, degrees, normalize) = (
        f.switch("--f32"),
        f.switch("--degrees"),
        f.switch("--normalize"),
    );
    let Some(op) = op else {
        return match (from, to) {
            (Some(from), Some(to)) => Ok(Opts {
                from,
                to: Some(to),
                op: Op::Convert,
                f32,
                degrees,
                normalize,
            }),
            _ => Err("--from and --to are required".into()),
        };
    };
    let name = format!("{op:?}").to_lowercase();
    let from = from.ok_or_else(|| format!("--op {name} needs --from"))?;
    if matches!(op, Op::EulerRates | Op::EulerRatesLab) && !matches!(from, Rep::Euler(_)) {
        return Err("--op euler-rates and euler-rates-lab need --from euler:SEQ".into());
    }
    match (op.writes_attitude(), to) {
        (true, None) => Err(format!("--op {name} needs --to")),
        (false, Some(_)) => Err(format!(
            "--to does not apply to this --op: it writes {}",
            if op == Op::Rotate {
                "the rotated vector vx,vy,vz"
            } else {
                "a 3x3 matrix, row-major"
            }
        )),
        (_, to) => Ok(Opts {
            from,
            to,
            op,
            f32,
            degrees,
            normalize,
        }),
    }
}

fn err_text(e: Error) -> String {
    e.to_string()
}

/// Parses the numbers of one row (`fields` of them, each finite).
fn read_numbers<T: Real + FromStr>(line: &str, fields: usize) -> Result<Vec<T>, String> {
    let raw: Vec<&str> = line.split(',').map(str::trim).collect();
    if raw.len() != fields {
        return Err(format!("expected {fields} fields, got {}", raw.len()));
    }
    let mut v = Vec::with_capacity(fields);
    for (i, f) in raw.iter().enumerate() {
        let x: T = f
            .parse()
            .map_err(|_| format!("field {}: not a number: '{f}'", i + 1))?;
        if !x.is_finite() {
            return Err(format!("field {}: not finite: '{f}'", i + 1));
        }
        v.push(x);
    }
    Ok(v)
}

/// The attitude written in `v` (exactly `o.from.fields()` numbers), checked to be a finite unit
/// quaternion (values at the ends of the float range can defeat a conversion).
fn read_attitude<T: Real>(v: &[T], o: &Opts) -> Result<UnitQuat<T>, String> {
    let q = attitude_of(v, o)?;
    let c = q.to_array();
    let n2 = c.iter().fold(T::ZERO, |acc, &x| acc + x * x);
    if c.iter().all(|x| x.is_finite()) && (n2 - T::ONE).abs() <= T::from_f64(INPUT_TOL) {
        Ok(q)
    } else {
        Err(format!(
            "the attitude of this row is not a finite unit quaternion ({}): a value too small or \
             too large for {}",
            join_unchecked(&c),
            if o.f32 { "f32" } else { "f64" }
        ))
    }
}

/// The attitude written in `v`, as the library converts it.
fn attitude_of<T: Real>(v: &[T], o: &Opts) -> Result<UnitQuat<T>, String> {
    let deg = T::PI / T::from_f64(180.0);
    let ang = |x: T| if o.degrees { x * deg } else { x };
    let v3 = |k: usize| Vec3::new(v[k], v[k + 1], v[k + 2]);
    let quat = |q: Quat<T>| {
        if q.norm() == T::ZERO {
            return Err("quaternion has zero norm".to_string());
        }
        if o.normalize {
            return UnitQuat::try_new(q).map_err(err_text);
        }
        UnitQuat::try_from_near_unit(q, T::from_f64(INPUT_TOL)).map_err(|e| match e {
            Error::NotUnit => format!(
                "quaternion norm {:?} is not within {INPUT_TOL:e} of 1",
                q.norm()
            ),
            e => err_text(e),
        })
    };
    let matrix = |m: Mat3<T>| {
        if !o.normalize {
            Dcm::try_from_matrix(m, T::from_f64(INPUT_TOL))
                .map_err(|_| "matrix is not a rotation (orthonormal, det +1)".to_string())?;
        }
        Dcm::try_from_matrix_orthonormalized(m)
            .map(|d| d.to_unit_quat())
            .map_err(|e| match e {
                Error::NotRotation if o.normalize => {
                    "matrix has no nearest rotation (det <= 0 or singular)".to_string()
                }
                e => err_text(e),
            })
    };
    match o.from {
        Rep::Quat => quat(Quat::new(v[0], v[1], v[2], v[3])),
        Rep::QuatXyzw => quat(Quat::new(v[3], v[0], v[1], v[2])),
        Rep::Matrix => matrix(Mat3::from_rows(
            [v[0], v[1], v[2]],
            [v[3], v[4], v[5]],
            [v[6], v[7], v[8]],
        )),
        Rep::DcmBn => matrix(Mat3::from_rows(
            [v[0], v[3], v[6]],
            [v[1], v[4], v[7]],
            [v[2], v[5], v[8]],
        )),
        Rep::RotVec => RotationVector::try_new(v3(0).scale(ang(T::ONE)))
            .map(|r| r.to_unit_quat())
            .map_err(err_text),
        Rep::Mrp => Mrp::try_new(v3(0))
            .map(|m| m.to_unit_quat())
            .map_err(err_text),
        Rep::Gibbs => Gibbs::try_new(v3(0))
            .map(|g| g.to_unit_quat())
            .map_err(err_text),
        Rep::AxisAngle => AxisAngle::try_new(v3(0), ang(v[3]))
            .map(|a| a.to_unit_quat())
            .map_err(|e| match e {
                Error::ZeroNorm => "axis has zero norm".to_string(),
                e => err_text(e),
            }),
        Rep::Euler(seq) => Euler::new(seq, [ang(v[0]), ang(v[1]), ang(v[2])])
            .try_to_unit_quat()
            .map_err(err_text),
    }
}

/// The numbers of an output row, each finite.
fn join<T: Real + Debug>(xs: &[T]) -> Result<String, String> {
    if xs.iter().all(|x| x.is_finite()) {
        Ok(join_unchecked(xs))
    } else {
        Err(format!(
            "the result is not finite ({}): the input is beyond the range this conversion handles",
            join_unchecked(xs)
        ))
    }
}

fn join_unchecked<T: Debug>(xs: &[T]) -> String {
    xs.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn rows_of<T: Real>(m: Mat3<T>) -> [T; 9] {
    let m = m.m;
    [
        m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
    ]
}

/// Formats one attitude as an output row in representation `to`.
fn write_attitude<T: Real + Debug>(q: UnitQuat<T>, to: Rep, o: &Opts) -> Result<String, String> {
    let deg = T::from_f64(180.0) / T::PI;
    let ang = |x: T| if o.degrees { x * deg } else { x };
    match to {
        Rep::Quat => join(&q.canonical().to_array()),
        Rep::QuatXyzw => {
            let [w, x, y, z] = q.canonical().to_array();
            join(&[x, y, z, w])
        }
        Rep::Matrix => join(&rows_of(q.to_rotation_matrix())),
        Rep::DcmBn => join(&rows_of(q.to_rotation_matrix().transpose())),
        Rep::RotVec => join(
            &RotationVector::from(q)
                .vector()
                .scale(ang(T::ONE))
                .to_array(),
        ),
        Rep::Mrp => join(&Mrp::from(q).vector().to_array()),
        Rep::Gibbs => match Gibbs::try_from_unit_quat(q) {
            Ok(g) => join(&g.vector().to_array()),
            Err(_) => Err(
                "the Gibbs vector is infinite: the rotation is 180 degrees (within rounding)"
                    .to_string(),
            ),
        },
        Rep::AxisAngle => {
            let a = AxisAngle::from(q);
            let ax = a.axis();
            join(&[ax.x, ax.y, ax.z, ang(a.angle())])
        }
        Rep::Euler(seq) => {
            let sol = q.to_euler(seq, GimbalPolicy::ZeroThird);
            let [a, b, c] = sol.euler.angles;
            let flag = u8::from(sol.singularity.is_some());
            Ok(format!("{},{flag}", join(&[ang(a), ang(b), ang(c)])?))
        }
    }
}

/// One input row to one output row.
fn convert_row<T: Real + FromStr + Debug>(line: &str, o: &Opts) -> Result<String, String> {
    let v = read_numbers::<T>(line, o.fields())?;
    let n = o.from.fields();
    let to = o.to.unwrap_or(o.from);
    let a = || read_attitude(&v[..n], o);
    let b = || read_attitude(&v[n..2 * n], o);
    match o.op {
        Op::Convert => write_attitude(a()?, to, o),
        Op::Inverse => write_attitude(a()?.inverse(), to, o),
        Op::Compose => write_attitude(a()? * b()?, to, o),
        Op::Relative => write_attitude(a()?.inverse() * b()?, to, o),
        Op::Slerp => write_attitude(a()?.slerp(b()?, v[2 * n]), to, o),
        Op::Rotate => join(&a()?.rotate(Vec3::new(v[n], v[n + 1], v[n + 2])).to_array()),
        Op::EulerRates | Op::EulerRatesLab => {
            let Rep::Euler(seq) = o.from else {
                return Err("--op euler-rates needs --from euler:SEQ".into());
            };
            let rad = T::PI / T::from_f64(180.0);
            let ang = |x: T| if o.degrees { x * rad } else { x };
            let e = Euler::new(seq, [ang(v[0]), ang(v[1]), ang(v[2])]);
            let m = if o.op == Op::EulerRates {
                e.rates_to_body_matrix()
            } else {
                e.rates_to_lab_matrix()
            };
            join(&rows_of(m))
        }
    }
}

/// Converts stdin to stdout; `Ok(true)` when every row converted. A closed stdout ends the run
/// as if the input ended there.
fn run<T: Real + FromStr + Debug>(o: &Opts) -> Result<bool, String> {
    let mut out = stream::Csv::stdout();
    let mut all_ok = true;
    let r = (|| -> io::Result<()> {
        let mut lines = stream::Lines::new(io::stdin().lock());
        loop {
            if lines.will_read() {
                out.flush()?;
            }
            let Some((n, line)) = lines
                .next_line()
                .map_err(|e| io::Error::other(format!("reading stdin: {e}")))?
            else {
                break;
            };
            let row = match line {
                Ok(text) if text.trim().is_empty() => continue,
                Ok(text) => convert_row::<T>(text, o),
                Err(reason) => Err(reason),
            };
            match row {
                Ok(row) => {
                    writeln!(out, "{row}")?;
                    out.row_done()?;
                }
                Err(reason) => {
                    all_ok = false;
                    out.flush()?;
                    flags::line_error(n, &reason);
                }
            }
        }
        out.flush()
    })();
    match r {
        Ok(()) => Ok(all_ok),
        Err(e) if stream::is_closed_pipe(&e) => Ok(all_ok),
        Err(e) => Err(e.to_string()),
    }
}

fn main() -> ExitCode {
    let o = match CLI
        .command_line()
        .and_then(|f| options(&f).map_err(|e| flags::usage_error(&e)))
    {
        Ok(o) => o,
        Err(status) => return status,
    };
    let r = if o.f32 {
        run::<f32>(&o)
    } else {
        run::<f64>(&o)
    };
    match r {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            flags::error(&e);
            ExitCode::FAILURE
        }
    }
}
