//! `convert`: a command-line attitude converter for ground tools and scripts.
//!
//! ```text
//! cargo run --release --example convert -- --from REP --to REP [--f32] [--degrees]
//! ```
//!
//! Reads CSV rows from stdin, writes CSV rows to stdout; see `--help` (the `HELP` text below)
//! for the formats. Host-only: the library stays `no_std`, the I/O lives here.

use std::fmt::Debug;
use std::io::{self, BufRead, BufWriter, Write};
use std::process::ExitCode;
use std::str::FromStr;

use gyrostat::rotation::{AxisAngle, Dcm, Euler, EulerSequence, GimbalPolicy, Mrp, RotationVector};
use gyrostat::{Error, Mat3, Quat, Real, UnitQuat, Vec3};

const HELP: &str = "\
convert: convert attitudes between representations (gyrostat)

USAGE:
    cargo run --release --example convert -- --from REP --to REP [--f32] [--degrees]

Reads CSV rows from stdin and writes CSV rows to stdout, no header either way: one output row
per valid input row, in order. Blank lines are skipped (but counted for line numbers).

REP (field order of a row):
    quat         w,x,y,z            Hamilton, scalar first; maps body vectors to the lab frame
    matrix       r00,r01,r02,r10,r11,r12,r20,r21,r22
                                    rotation matrix, row-major; columns are the body axes
    rotvec       x,y,z              rotation vector (angle * unit axis)
    mrp          x,y,z              modified Rodrigues parameters (output has |mrp| <= 1)
    axis-angle   ax,ay,az,angle     axis (normalised on input) and angle
    euler:SEQ    a,b,c              Euler angles; SEQ is three letters from xyz, e.g. ZYX or zyx:
                                    uppercase = intrinsic (R = R_Z(a) R_Y(b) R_X(c)),
                                    lowercase = extrinsic (R = R_x(c) R_y(b) R_z(a)),
                                    exactly the meaning of scipy.spatial.transform.Rotation.
                                    OUTPUT rows get a 4th column: 1 if the attitude is at the
                                    gimbal-lock singularity (middle angle within 2*epsilon of its
                                    pole: 2.2e-16*2 in f64, 1.2e-7*2 with --f32), else 0. At a
                                    gimbal lock the third angle is set to 0 (scipy's choice).

OPTIONS:
    --from REP   input representation (required)
    --to REP     output representation (required)
    --f32        do the conversion in f32 (inputs are rounded to f32)
    --degrees    angles in degrees instead of radians, for euler angles, the axis-angle angle
                 and the rotvec length (like scipy's degrees=True); mrp, quat and matrix are
                 dimensionless
    -h, --help   print this help

OUTPUT NUMBERS:
    shortest decimal that parses back to the same f64 (or f32 with --f32) value.

Output quaternions are the SO(3) representative with w >= 0 (ties: first non-zero of x, y, z
positive); output axis-angle has angle in [0, pi] (axis +x for the identity); output rotvec has
length <= pi.

ERRORS:
    A malformed or invalid row (wrong field count, a field that is not a number, NaN or infinity,
    a zero or far-from-unit quaternion (| |q| - 1 | > 1e-3), a matrix that is not a rotation
    (|R^T R - 1| > 1e-3 or det <= 0), a zero axis) writes
        error: line N: reason
    to stderr and no output row; the run continues and exits with status 1 at the end.
    Bad command-line arguments exit with status 2.
";

/// Tolerance on `|q|` and on `‖RᵀR − 1‖` for input rows: data printed with at least 4
/// significant digits passes; anything further off is not an attitude.
const INPUT_TOL: f64 = 1e-3;

#[derive(Clone, Copy, Debug)]
enum Rep {
    Quat,
    Matrix,
    RotVec,
    Mrp,
    AxisAngle,
    Euler(EulerSequence),
}

impl Rep {
    fn parse(s: &str) -> Result<Self, String> {
        Ok(match s {
            "quat" => Rep::Quat,
            "matrix" => Rep::Matrix,
            "rotvec" => Rep::RotVec,
            "mrp" => Rep::Mrp,
            "axis-angle" => Rep::AxisAngle,
            _ => match s.strip_prefix("euler:") {
                Some(seq) => Rep::Euler(
                    EulerSequence::parse(seq)
                        .map_err(|_| format!("invalid Euler sequence '{seq}'"))?,
                ),
                None => return Err(format!("unknown representation '{s}'")),
            },
        })
    }

    fn fields(self) -> usize {
        match self {
            Rep::Quat | Rep::AxisAngle => 4,
            Rep::Matrix => 9,
            Rep::RotVec | Rep::Mrp | Rep::Euler(_) => 3,
        }
    }
}

struct Opts {
    from: Rep,
    to: Rep,
    f32: bool,
    degrees: bool,
}

fn parse_args() -> Result<Option<Opts>, String> {
    let mut from = None;
    let mut to = None;
    let (mut f32, mut degrees) = (false, false);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "-h" | "--help" => return Ok(None),
            "--f32" => f32 = true,
            "--degrees" => degrees = true,
            "--from" | "--to" => {
                let v = args.next().ok_or_else(|| format!("{a} needs a value"))?;
                let r = Rep::parse(&v)?;
                if a == "--from" {
                    from = Some(r);
                } else {
                    to = Some(r);
                }
            }
            _ => {
                if let Some(v) = a.strip_prefix("--from=") {
                    from = Some(Rep::parse(v)?);
                } else if let Some(v) = a.strip_prefix("--to=") {
                    to = Some(Rep::parse(v)?);
                } else {
                    return Err(format!("unknown argument '{a}'"));
                }
            }
        }
    }
    match (from, to) {
        (Some(from), Some(to)) => Ok(Some(Opts {
            from,
            to,
            f32,
            degrees,
        })),
        _ => Err("--from and --to are required".into()),
    }
}

fn err_text(e: Error) -> String {
    e.to_string()
}

/// Parses one row into an attitude.
fn read_row<T: Real + FromStr>(line: &str, o: &Opts) -> Result<UnitQuat<T>, String> {
    let raw: Vec<&str> = line.split(',').map(str::trim).collect();
    let n = o.from.fields();
    if raw.len() != n {
        return Err(format!("expected {n} fields, got {}", raw.len()));
    }
    let mut v = Vec::with_capacity(n);
    for (i, f) in raw.iter().enumerate() {
        let x: T = f
            .parse()
            .map_err(|_| format!("field {}: not a number: '{f}'", i + 1))?;
        if !x.is_finite() {
            return Err(format!("field {}: not finite: '{f}'", i + 1));
        }
        v.push(x);
    }
    let deg = T::PI / T::from_f64(180.0);
    let ang = |x: T| if o.degrees { x * deg } else { x };
    let v3 = |k: usize| Vec3::new(v[k], v[k + 1], v[k + 2]);
    match o.from {
        Rep::Quat => {
            let q = Quat::new(v[0], v[1], v[2], v[3]);
            if q.norm() == T::ZERO {
                return Err("quaternion has zero norm".into());
            }
            UnitQuat::try_from_near_unit(q, T::from_f64(INPUT_TOL)).map_err(|e| match e {
                Error::NotUnit => format!(
                    "quaternion norm {:?} is not within {INPUT_TOL:e} of 1",
                    q.norm()
                ),
                e => err_text(e),
            })
        }
        Rep::Matrix => {
            let m = Mat3::from_rows([v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]);
            Dcm::try_from_matrix(m, T::from_f64(INPUT_TOL))
                .map_err(|_| "matrix is not a rotation (orthonormal, det +1)".to_string())?;
            Dcm::from_matrix_orthonormalized(m)
                .map(|d| d.to_unit_quat())
                .map_err(err_text)
        }
        Rep::RotVec => RotationVector::try_new(v3(0).scale(ang(T::ONE)))
            .map(|r| r.to_unit_quat())
            .map_err(err_text),
        Rep::Mrp => Mrp::try_new(v3(0))
            .map(|m| m.to_unit_quat())
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

/// Formats one attitude as an output row.
fn write_row<T: Real + Debug>(q: UnitQuat<T>, o: &Opts) -> String {
    let deg = T::from_f64(180.0) / T::PI;
    let ang = |x: T| if o.degrees { x * deg } else { x };
    let join = |xs: &[T]| {
        xs.iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    match o.to {
        Rep::Quat => join(&q.canonical().to_array()),
        Rep::Matrix => {
            let m = q.to_rotation_matrix().m;
            join(&[
                m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
            ])
        }
        Rep::RotVec => join(
            &RotationVector::from(q)
                .vector()
                .scale(ang(T::ONE))
                .to_array(),
        ),
        Rep::Mrp => join(&Mrp::from(q).vector().to_array()),
        Rep::AxisAngle => {
            let a = AxisAngle::from(q);
            let ax = a.axis();
            join(&[ax.x, ax.y, ax.z, ang(a.angle())])
        }
        Rep::Euler(seq) => {
            let sol = q.to_euler(seq, GimbalPolicy::ZeroThird);
            let [a, b, c] = sol.euler.angles;
            let flag = u8::from(sol.singularity.is_some());
            format!("{},{flag}", join(&[ang(a), ang(b), ang(c)]))
        }
    }
}

fn run<T: Real + FromStr + Debug>(o: &Opts) -> io::Result<bool> {
    let stdin = io::stdin();
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let mut all_ok = true;
    for (i, line) in stdin.lock().lines().enumerate() {
        let line = line?;
        if line.trim().is_empty() {
            continue;
        }
        match read_row::<T>(&line, o) {
            Ok(q) => writeln!(out, "{}", write_row(q, o))?,
            Err(reason) => {
                all_ok = false;
                out.flush()?;
                eprintln!("error: line {}: {reason}", i + 1);
            }
        }
    }
    out.flush()?;
    Ok(all_ok)
}

fn main() -> ExitCode {
    let o = match parse_args() {
        Ok(Some(o)) => o,
        Ok(None) => {
            print!("{HELP}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("error: {e}\n\n{HELP}");
            return ExitCode::from(2);
        }
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
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
