//! The IMU logs the tools read (`estimate`, `characterize`): one stream (gzip recognised by its
//! first bytes), one vocabulary of column names, one set of unit flags.
//!
//! Columns (a header is the first line that is not all numbers; columns are found by name and
//! others are ignored):
//!
//! ```text
//! time           t | t_s (s) | Time (s)
//! gyroscope      gx,gy,gz | gyr_x_rad_s,... (rad/s) | Gyroscope X (deg/s),...
//! accelerometer  ax,ay,az | acc_x_m_s2,... (m/s^2) | Accelerometer X (g),...
//! magnetometer   mx,my,mz | mag_x_uT,... (uT) | Magnetometer X (uT),...      (optional)
//! reference      qw,qx,qy,qz | opt_qw,...                                     (optional)
//! movement       movement (0/1, BROAD's scored phase)                         (optional)
//! ```
//!
//! Without a header the fields are positional: `t,gx,gy,gz,ax,ay,az` (7 fields), `+ mx,my,mz`
//! (10), `+ qw,qx,qy,qz` after them (11 or 14). A unit in a column's name is the data's unit: a
//! unit flag that contradicts it is an error ([`Scales::resolve`]).

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

use crate::units::{AccelUnit, GyroUnit, MagUnit, TimeUnit};

/// Why the input cannot be opened.
#[derive(Debug)]
pub enum OpenError {
    /// The file cannot be opened: `PATH: reason`.
    File(String),
    /// Reading its first bytes failed.
    Io(io::Error),
}

/// The input (stdin without a file), decompressed when it starts with gzip's magic bytes.
pub fn open_input(file: Option<&Path>) -> Result<Box<dyn Read>, OpenError> {
    let mut raw: Box<dyn Read> = match file {
        Some(path) => Box::new(
            File::open(path).map_err(|e| OpenError::File(format!("{}: {e}", path.display())))?,
        ),
        None => Box::new(io::stdin().lock()),
    };
    // The first two bytes decide (a pipe may deliver them in separate reads).
    let mut magic = Vec::with_capacity(2);
    while magic.len() < 2 {
        let mut byte = [0u8; 1];
        match raw.read(&mut byte) {
            Ok(0) => break,
            Ok(_) => magic.extend_from_slice(&byte),
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(OpenError::Io(e)),
        }
    }
    let gzip = magic == [0x1f, 0x8b];
    let whole = io::Cursor::new(magic).chain(raw);
    Ok(if gzip {
        Box::new(flate2::read::MultiGzDecoder::new(whole))
    } else {
        Box::new(whole)
    })
}

/// A group of columns: its names in the header and the unit the names state.
pub struct Names<const N: usize, U> {
    /// The column names.
    pub names: [&'static str; N],
    /// The unit the names state (None: the unit flags decide).
    pub unit: Option<U>,
}

/// The spellings of the time columns.
pub const TIME: [Names<1, TimeUnit>; 3] = [
    Names {
        names: ["t"],
        unit: None,
    },
    Names {
        names: ["t_s"],
        unit: Some(TimeUnit::Second),
    },
    Names {
        names: ["Time (s)"],
        unit: Some(TimeUnit::Second),
    },
];
/// The spellings of the gyro columns.
pub const GYRO: [Names<3, GyroUnit>; 3] = [
    Names {
        names: ["gx", "gy", "gz"],
        unit: None,
    },
    Names {
        names: ["gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s"],
        unit: Some(GyroUnit::RadPerSecond),
    },
    Names {
        names: [
            "Gyroscope X (deg/s)",
            "Gyroscope Y (deg/s)",
            "Gyroscope Z (deg/s)",
        ],
        unit: Some(GyroUnit::DegPerSecond),
    },
];
/// The spellings of the accel columns.
pub const ACCEL: [Names<3, AccelUnit>; 3] = [
    Names {
        names: ["ax", "ay", "az"],
        unit: None,
    },
    Names {
        names: ["acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"],
        unit: Some(AccelUnit::MeterPerSecondSquared),
    },
    Names {
        names: [
            "Accelerometer X (g)",
            "Accelerometer Y (g)",
            "Accelerometer Z (g)",
        ],
        unit: Some(AccelUnit::StandardGravity),
    },
];
/// The spellings of the mag columns.
pub const MAG: [Names<3, MagUnit>; 3] = [
    Names {
        names: ["mx", "my", "mz"],
        unit: None,
    },
    Names {
        names: ["mag_x_uT", "mag_y_uT", "mag_z_uT"],
        unit: Some(MagUnit::MicroTesla),
    },
    Names {
        names: [
            "Magnetometer X (uT)",
            "Magnetometer Y (uT)",
            "Magnetometer Z (uT)",
        ],
        unit: Some(MagUnit::MicroTesla),
    },
];
/// The spellings of the truth columns.
pub const TRUTH: [Names<4, ()>; 2] = [
    Names {
        names: ["qw", "qx", "qy", "qz"],
        unit: None,
    },
    Names {
        names: ["opt_qw", "opt_qx", "opt_qy", "opt_qz"],
        unit: None,
    },
];

/// The first group of `options` whose names are all in `head`: their positions and unit.
pub fn find<const N: usize, U: Copy>(
    head: &[&str],
    options: &[Names<N, U>],
) -> Option<([usize; N], Option<U>)> {
    options.iter().find_map(|o| {
        let mut idx = [0; N];
        for (slot, name) in idx.iter_mut().zip(o.names) {
            *slot = head.iter().position(|h| *h == name)?;
        }
        Some((idx, o.unit))
    })
}

/// Where a row's fields are.
pub struct Layout {
    /// Column names (for messages); positional input has the short names.
    pub names: Vec<String>,
    pub time: usize,
    pub gyro: [usize; 3],
    pub accel: [usize; 3],
    pub mag: Option<[usize; 3]>,
    pub truth: Option<[usize; 4]>,
    pub movement: Option<usize>,
    /// The units the column names state.
    pub time_unit: Option<TimeUnit>,
    pub gyro_unit: Option<GyroUnit>,
    pub accel_unit: Option<AccelUnit>,
    pub mag_unit: Option<MagUnit>,
    /// Whether the first line was a header (not a sample).
    pub header: bool,
}

impl Layout {
    /// The layout from the first non-blank line (a header, or the first sample).
    pub fn from_first_line(text: &str) -> Result<Layout, String> {
        let fields: Vec<&str> = text.split(',').map(str::trim).collect();
        let header = fields.iter().any(|f| f.parse::<f64>().is_err());
        if header {
            let missing = |what: &str| format!("the header names no {what} columns (see --help)");
            let (t, time_unit) =
                find(&fields, &TIME).ok_or_else(|| missing("time (t, t_s or Time (s))"))?;
            let (gyro, gyro_unit) = find(&fields, &GYRO).ok_or_else(|| missing("gyroscope"))?;
            let (accel, accel_unit) =
                find(&fields, &ACCEL).ok_or_else(|| missing("accelerometer"))?;
            let (mag, mag_unit) = match find(&fields, &MAG) {
                Some((i, u)) => (Some(i), u),
                None => (None, None),
            };
            return Ok(Layout {
                names: fields.iter().map(|s| s.to_string()).collect(),
                time: t[0],
                gyro,
                accel,
                mag,
                truth: find(&fields, &TRUTH).map(|(i, _)| i),
                movement: fields.iter().position(|h| *h == "movement"),
                time_unit,
                gyro_unit,
                accel_unit,
                mag_unit,
                header: true,
            });
        }
        let (mag, truth) = match fields.len() {
            7 => (None, None),
            10 => (Some([7, 8, 9]), None),
            11 => (None, Some([7, 8, 9, 10])),
            14 => (Some([7, 8, 9]), Some([10, 11, 12, 13])),
            n => {
                return Err(format!(
                    "expected 7, 10, 11 or 14 comma-separated fields without a header \
                     (t,gx,gy,gz,ax,ay,az[,mx,my,mz][,qw,qx,qy,qz]), found {n}"
                ));
            }
        };
        let short = [
            "t", "gx", "gy", "gz", "ax", "ay", "az", "mx", "my", "mz", "qw", "qx", "qy", "qz",
        ];
        let mut names: Vec<&str> = short.iter().take(7).copied().collect();
        if mag.is_some() {
            names.extend(short.iter().skip(7).take(3));
        }
        if truth.is_some() {
            names.extend(short.iter().skip(10));
        }
        Ok(Layout {
            names: names.into_iter().map(|s| s.to_string()).collect(),
            time: 0,
            gyro: [1, 2, 3],
            accel: [4, 5, 6],
            mag,
            truth,
            movement: None,
            time_unit: None,
            gyro_unit: None,
            accel_unit: None,
            mag_unit: None,
            header: false,
        })
    }
}

/// A unit flag against the unit a column name states: the flag's, the name's, or the default.
pub fn unit<U: Copy + PartialEq + Default>(
    flag: &str,
    given: Option<U>,
    named: Option<U>,
    name: fn(U) -> &'static str,
    column: &str,
) -> Result<U, String> {
    match (given, named) {
        (Some(g), Some(n)) if g != n => Err(format!(
            "{flag} {}: the input's column '{column}' is in {}",
            name(g),
            name(n)
        )),
        (Some(u), _) | (None, Some(u)) => Ok(u),
        (None, None) => Ok(U::default()),
    }
}

/// The conversion of the input to SI units (the magnetometer to µT).
pub struct Scales {
    /// Time stamps to s.
    pub time: f64,
    /// Rates to rad/s.
    pub gyro: f64,
    /// Specific force to m/s².
    pub accel: f64,
    /// Field to µT (1 for `--mag-unit any`).
    pub mag: f64,
}

impl Scales {
    /// The scales of a layout and the unit flags given (None: not given): a flag against the
    /// unit a column's name states is an error (a usage error of the tool).
    pub fn resolve(
        layout: &Layout,
        time: Option<TimeUnit>,
        gyro: Option<GyroUnit>,
        accel: Option<AccelUnit>,
        mag: Option<MagUnit>,
    ) -> Result<Scales, String> {
        let column = |i: usize| layout.names.get(i).cloned().unwrap_or_default();
        Ok(Scales {
            time: unit(
                "--time-unit",
                time,
                layout.time_unit,
                TimeUnit::name,
                &column(layout.time),
            )?
            .to_si(),
            gyro: unit(
                "--gyro-unit",
                gyro,
                layout.gyro_unit,
                GyroUnit::name,
                &column(layout.gyro[0]),
            )?
            .to_si(),
            accel: unit(
                "--accel-unit",
                accel,
                layout.accel_unit,
                AccelUnit::name,
                &column(layout.accel[0]),
            )?
            .to_si(),
            mag: match (mag, layout.mag_unit) {
                (Some(MagUnit::Any), _) => 1.0,
                (given, named) => unit(
                    "--mag-unit",
                    given,
                    named,
                    MagUnit::name,
                    &column(layout.mag.map_or(0, |m| m[0])),
                )?
                .to_micro_tesla(),
            },
        })
    }
}

/// One parsed sample (SI units, the magnetometer in µT).
pub struct Sample<'a> {
    /// The time stamp as written.
    pub t_text: &'a str,
    /// The time stamp in the input's unit.
    pub t: f64,
    /// Rate, rad/s.
    pub gyro: [f64; 3],
    /// Specific force, m/s².
    pub accel: [f64; 3],
    /// Field, µT (None: the row has no magnetometer sample).
    pub mag: Option<[f64; 3]>,
    /// The reference attitude (read only when asked for).
    pub truth: Option<[f64; 4]>,
    /// `movement` is 1, or the input has no movement column.
    pub scored: bool,
}

/// A row that cannot be used: the reason, and whether it is a glitch (a non-finite time stamp
/// or gyroscope value) that a reader may turn into a gap (`estimate --skip-bad-rows`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BadRow {
    /// Why the row cannot be used, as the tools print it after `line N: `.
    pub reason: String,
    /// Whether the row is a glitch: a non-finite time stamp or gyroscope value.
    pub glitch: bool,
}

impl From<String> for BadRow {
    fn from(reason: String) -> Self {
        BadRow {
            reason,
            glitch: false,
        }
    }
}

/// Parses one row by `layout` (the reference only when `truth`).
pub fn parse_row<'a>(
    text: &'a str,
    layout: &Layout,
    s: &Scales,
    truth: bool,
) -> Result<Sample<'a>, BadRow> {
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    if fields.len() != layout.names.len() {
        return Err(format!(
            "expected {} comma-separated fields ({}), found {}",
            layout.names.len(),
            if layout.header {
                "as the header"
            } else {
                "as the first row"
            },
            fields.len()
        )
        .into());
    }
    let field = |i: usize| fields.get(i).copied().unwrap_or("");
    let number = |i: usize| -> Result<f64, String> {
        let f = field(i);
        f.parse::<f64>().map_err(|_| {
            format!(
                "column {} ({}): invalid number '{f}'",
                i + 1,
                layout.names.get(i).map_or("", String::as_str)
            )
        })
    };
    let finite = |i: usize, what: &str| -> Result<f64, String> {
        let x = number(i)?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(format!(
                "column {} ({}): non-finite {what} '{}'{}",
                i + 1,
                layout.names.get(i).map_or("", String::as_str),
                field(i),
                if what == "gyroscope value" {
                    " (the estimator cannot propagate across it)"
                } else {
                    ""
                }
            ))
        }
    };
    let glitch = |i: usize, what: &str| -> Result<f64, BadRow> {
        let x = number(i)?;
        finite(i, what).map_err(|reason| BadRow {
            reason,
            glitch: !x.is_finite(),
        })
    };
    let t = glitch(layout.time, "time stamp")?;
    let mut gyro = [0.0; 3];
    for (g, &i) in gyro.iter_mut().zip(&layout.gyro) {
        *g = glitch(i, "gyroscope value")? * s.gyro;
    }
    let mut accel = [0.0; 3];
    for (a, &i) in accel.iter_mut().zip(&layout.accel) {
        *a = number(i)? * s.accel;
    }
    let mag = match layout.mag {
        Some(idx) if idx.iter().all(|&i| field(i).is_empty()) => None,
        Some(idx) => {
            let mut m = [0.0; 3];
            for (m, &i) in m.iter_mut().zip(&idx) {
                *m = number(i)? * s.mag;
            }
            Some(m)
        }
        None => None,
    };
    let truth_q = match layout.truth {
        Some(idx) if truth && !field(idx[0]).is_empty() => {
            let mut q = [0.0; 4];
            for (q, &i) in q.iter_mut().zip(&idx) {
                *q = finite(i, "reference")?;
            }
            Some(q)
        }
        _ => None,
    };
    let scored = layout.movement.is_none_or(|i| field(i) == "1");
    Ok(Sample {
        t_text: field(layout.time),
        t,
        gyro,
        accel,
        mag,
        truth: truth_q,
        scored,
    })
}
