//! The command line of every tool: one flag dialect, one error style.
//!
//! # Dialect
//!
//! - Flags are long, `--name`; `-h` is short for `--help`.
//! - A flag with a value takes the next argument, whatever it starts with (`--dt 0.01`,
//!   `--wheel-torque -0.015`), or the text after `=` in the same argument (`--dt=0.01`).
//! - A switch takes no value: `--f32`, never `--f32=yes`.
//! - A flag given twice is an error, unless the tool declares it repeatable (`simulate --wheel`,
//!   one per wheel).
//! - There are no positional arguments: anything that is not a declared flag (or the value of
//!   one) is an unknown argument. A tool that reads a file (`estimate [FILE]`) parses with
//!   [`Cli::parse_with_operands`] instead: there an argument that does not start with `-`, or
//!   is exactly `-`, is an operand (a file named `-x` is given as `./-x`).
//! - Every argument must be UTF-8 text.
//! - `-h` or `--help` where a flag may stand (not as the value of another flag) prints the help on
//!   stdout and exits with status 0, whatever else the command line holds.
//!
//! # Errors
//!
//! Every error of every tool is one line on stderr, `error: REASON`; a problem of an input line
//! names it, `error: line N: REASON`. A bad command line (an unknown or repeated flag, a missing
//! or invalid value, a combination the tool rejects) prints its reason, `error: --dt: must be
//! finite and > 0, got -1`, writes nothing on stdout and exits with status [`USAGE`] (2). A
//! reason about a flag's value starts with the flag.
//!
//! # Adding a flag or a tool
//!
//! A tool declares its interface once, a [`Cli`]: its name, its help text and its flags, each a
//! [`Flag::value`], [`Flag::switch`] or [`Flag::repeated`]. [`Cli::command_line`] reads the
//! process arguments into [`Flags`] (or prints the help or the error and gives the exit status),
//! and the tool takes each flag from there with a value parser: [`number`], [`positive`],
//! [`count`], [`at_least_one`], [`numbers`], [`list`], or its own `Fn(&str, &str) -> Result<V,
//! String>` (the flag, its text) for a flag with its own vocabulary.
//!
//! ```
//! use gyrostat_tools::flags::{self, Cli, Flag, Parsed};
//!
//! const CLI: Cli = Cli {
//!     name: "example",
//!     help: "example --dt SECONDS [--f32]\n",
//!     flags: &[Flag::value("--dt"), Flag::switch("--f32")],
//! };
//! let Ok(Parsed::Flags(f)) = CLI.parse(["--dt=0.01", "--f32"].map(Into::into)) else {
//!     panic!("a valid command line")
//! };
//! assert_eq!(f.get("--dt", flags::positive), Ok(Some(0.01)));
//! assert!(f.switch("--f32"));
//! let again = CLI.parse(["--dt", "1", "--dt", "2"].map(Into::into));
//! assert_eq!(again.err().as_deref(), Some("--dt given more than once"));
//! ```

use std::ffi::OsString;
use std::process::ExitCode;

use crate::stream::print_text;

/// The exit status of a bad command line.
pub const USAGE: u8 = 2;

/// What a flag takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// No value: present or not (`--f32`).
    Switch,
    /// One value, given at most once (`--dt 0.01`).
    Value,
    /// One value per occurrence, any number of occurrences (`--wheel A,B,C,D --wheel ...`).
    Repeated,
}

/// One flag of a tool.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Flag {
    /// The flag as typed, `--name`.
    pub name: &'static str,
    /// What it takes.
    pub kind: Kind,
}

impl Flag {
    /// A flag without a value.
    pub const fn switch(name: &'static str) -> Self {
        Self {
            name,
            kind: Kind::Switch,
        }
    }

    /// A flag with one value, given at most once.
    pub const fn value(name: &'static str) -> Self {
        Self {
            name,
            kind: Kind::Value,
        }
    }

    /// A flag with one value per occurrence, which may be repeated.
    pub const fn repeated(name: &'static str) -> Self {
        Self {
            name,
            kind: Kind::Repeated,
        }
    }
}

/// A tool's command-line interface.
#[derive(Clone, Copy, Debug)]
pub struct Cli {
    /// The tool's name, as installed.
    pub name: &'static str,
    /// The text `--help` prints.
    pub help: &'static str,
    /// Every flag the tool takes (`--help` and `-h` are implied).
    pub flags: &'static [Flag],
}

/// What a command line asks for.
#[derive(Debug)]
pub enum Parsed {
    /// `-h` or `--help`.
    Help,
    /// A run with these flags.
    Flags(Flags),
}

impl Cli {
    /// Reads `args` (the arguments after the program name) by the rules of the module docs: the
    /// flags given, [`Parsed::Help`], or the reason the command line is bad.
    pub fn parse<I>(&self, args: I) -> Result<Parsed, String>
    where
        I: IntoIterator<Item = OsString>,
    {
        self.parse_inner(args, None)
    }

    /// Like [`Cli::parse`], and the operands (the arguments that are not flags or their values:
    /// those not starting with `-`, and `-` itself), in order, beside the flags.
    pub fn parse_with_operands<I>(&self, args: I) -> Result<(Parsed, Vec<String>), String>
    where
        I: IntoIterator<Item = OsString>,
    {
        let mut operands = Vec::new();
        let parsed = self.parse_inner(args, Some(&mut operands))?;
        Ok((parsed, operands))
    }

    fn parse_inner<I>(
        &self,
        args: I,
        mut operands: Option<&mut Vec<String>>,
    ) -> Result<Parsed, String>
    where
        I: IntoIterator<Item = OsString>,
    {
        let mut given: Vec<(&'static str, Option<String>)> = Vec::new();
        let mut first_error: Option<String> = None;
        let mut fail = |e: String| {
            first_error.get_or_insert(e);
        };
        let mut args = args.into_iter().enumerate().map(|(i, a)| {
            a.into_string().map_err(|a| {
                format!(
                    "argument {} is not valid UTF-8: {:?}",
                    i + 1,
                    a.to_string_lossy()
                )
            })
        });
        while let Some(arg) = args.next() {
            let arg = match arg {
                Ok(a) => a,
                Err(e) => {
                    fail(e);
                    continue;
                }
            };
            if arg == "-h" || arg == "--help" {
                return Ok(Parsed::Help);
            }
            if let Some(list) = operands.as_deref_mut()
                && (arg == "-" || !arg.starts_with('-'))
            {
                list.push(arg);
                continue;
            }
            let (name, inline) = match arg.split_once('=') {
                Some((name, value)) if name.starts_with("--") => (name, Some(value.to_string())),
                _ => (arg.as_str(), None),
            };
            let Some(flag) = self.flags.iter().find(|f| f.name == name) else {
                fail(format!("unknown argument '{arg}' (see --help)"));
                continue;
            };
            let value = match (flag.kind, inline) {
                (Kind::Switch, None) => None,
                (Kind::Switch, Some(_)) => {
                    fail(format!("{name} takes no value"));
                    continue;
                }
                (_, Some(v)) => Some(v),
                (_, None) => match args.next() {
                    Some(Ok(v)) => Some(v),
                    Some(Err(e)) => {
                        fail(e);
                        continue;
                    }
                    None => {
                        fail(format!("{name} needs a value"));
                        continue;
                    }
                },
            };
            if flag.kind != Kind::Repeated && given.iter().any(|(n, _)| *n == flag.name) {
                fail(format!("{name} given more than once"));
                continue;
            }
            given.push((flag.name, value));
        }
        match first_error {
            Some(e) => Err(e),
            None => Ok(Parsed::Flags(Flags {
                spec: self.flags,
                given,
            })),
        }
    }

    /// The flags of this process's command line. `Err` holds the exit status when the run is
    /// over already: the help printed (0), or the error of a bad command line ([`USAGE`]).
    pub fn command_line(&self) -> Result<Flags, ExitCode> {
        self.finish(self.parse(std::env::args_os().skip(1)))
    }

    /// [`Cli::command_line`] with the operands (see [`Cli::parse_with_operands`]).
    pub fn command_line_with_operands(&self) -> Result<(Flags, Vec<String>), ExitCode> {
        match self.parse_with_operands(std::env::args_os().skip(1)) {
            Ok((parsed, operands)) => Ok((self.finish(Ok(parsed))?, operands)),
            Err(reason) => Err(usage_error(&reason)),
        }
    }

    fn finish(&self, parsed: Result<Parsed, String>) -> Result<Flags, ExitCode> {
        match parsed {
            Ok(Parsed::Flags(flags)) => Ok(flags),
            Ok(Parsed::Help) => Err(match print_text(self.help) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    error(&format!("writing stdout: {e}"));
                    ExitCode::FAILURE
                }
            }),
            Err(reason) => Err(usage_error(&reason)),
        }
    }
}

/// Reports an error: `error: REASON` on stderr.
pub fn error(reason: &str) {
    crate::say!("error: {reason}");
}

/// Reports a problem of input line `line` (counted from 1): `error: line N: REASON` on stderr.
pub fn line_error(line: u64, reason: &str) {
    error(&format!("line {line}: {reason}"));
}

/// Reports a bad command line and returns its exit status, [`USAGE`].
pub fn usage_error(reason: &str) -> ExitCode {
    error(reason);
    ExitCode::from(USAGE)
}

/// The flags of a command line, in the order given.
#[derive(Debug)]
pub struct Flags {
    spec: &'static [Flag],
    given: Vec<(&'static str, Option<String>)>,
}

impl Flags {
    /// `true` when no flag was given.
    pub fn is_empty(&self) -> bool {
        self.given.is_empty()
    }

    /// The flags given, in order (a repeated flag once per occurrence).
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.given.iter().map(|(n, _)| *n)
    }

    /// `true` when the switch (or any flag) `name` was given.
    pub fn switch(&self, name: &str) -> bool {
        self.declared(name);
        self.given.iter().any(|(n, _)| *n == name)
    }

    /// The text of the flag `name`, if given.
    pub fn value(&self, name: &str) -> Option<&str> {
        self.declared(name);
        self.given
            .iter()
            .find(|(n, _)| *n == name)
            .and_then(|(_, v)| v.as_deref())
    }

    /// The texts of every occurrence of the flag `name`, in order.
    pub fn values<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a str> + 'a {
        self.declared(name);
        self.given
            .iter()
            .filter(move |(n, _)| *n == name)
            .filter_map(|(_, v)| v.as_deref())
    }

    /// The flag `name` read by `parse(name, text)`: `Ok(None)` when it is not given.
    pub fn get<V>(
        &self,
        name: &str,
        parse: impl FnOnce(&str, &str) -> Result<V, String>,
    ) -> Result<Option<V>, String> {
        self.value(name).map(|v| parse(name, v)).transpose()
    }

    /// A tool asks only for the flags it declared: a misspelt name would never be given, and its
    /// flag would be ignored without a word. A programming error, not an input error: the
    /// interface tests, which give every flag, find it.
    fn declared(&self, name: &str) {
        assert!(
            self.spec.iter().any(|f| f.name == name),
            "{name} is not a declared flag"
        );
    }
}

/// A finite number: `FLAG: invalid number 'TEXT'` or `FLAG: not a finite number 'TEXT'`
/// otherwise. Blanks around it are allowed.
pub fn number(flag: &str, text: &str) -> Result<f64, String> {
    let t = text.trim();
    let x: f64 = t
        .parse()
        .map_err(|_| format!("{flag}: invalid number '{t}'"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("{flag}: not a finite number '{t}'"))
    }
}

/// A finite number `> 0` (a time step, a duration): `FLAG: must be finite and > 0, got TEXT`.
pub fn positive(flag: &str, text: &str) -> Result<f64, String> {
    let t = text.trim();
    let x: f64 = t
        .parse()
        .map_err(|_| format!("{flag}: invalid number '{t}'"))?;
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(format!("{flag}: must be finite and > 0, got {t}"))
    }
}

/// A whole number `>= 0`: `FLAG: invalid count 'TEXT'` otherwise.
pub fn count(flag: &str, text: &str) -> Result<u64, String> {
    let t = text.trim();
    t.parse()
        .map_err(|_| format!("{flag}: invalid count '{t}' (a whole number >= 0)"))
}

/// A whole number `>= 1`: like [`count`], and `FLAG: must be at least 1` for 0.
pub fn at_least_one(flag: &str, text: &str) -> Result<u64, String> {
    match count(flag, text)? {
        0 => Err(format!("{flag}: must be at least 1")),
        n => Ok(n),
    }
}

/// Exactly `N` comma-separated finite numbers, named `fields` in the message (`"w,x,y,z"`):
/// `FLAG: expected N comma-separated numbers FIELDS, found M`, or a field's [`number`] error.
pub fn numbers<const N: usize>(flag: &str, text: &str, fields: &str) -> Result<[f64; N], String> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != N {
        return Err(format!(
            "{flag}: expected {N} comma-separated numbers {fields}, found {}",
            parts.len()
        ));
    }
    let mut out = [0.0; N];
    for (slot, p) in out.iter_mut().zip(&parts) {
        *slot = number(flag, p)?;
    }
    Ok(out)
}

/// Any number of comma-separated finite numbers (at least one).
pub fn list(flag: &str, text: &str) -> Result<Vec<f64>, String> {
    text.split(',').map(|p| number(flag, p)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const CLI: Cli = Cli {
        name: "t",
        help: "",
        flags: &[
            Flag::value("--dt"),
            Flag::switch("--f32"),
            Flag::repeated("--wheel"),
        ],
    };

    fn parse(args: &[&str]) -> Result<Parsed, String> {
        CLI.parse(args.iter().map(OsString::from))
    }

    fn flags(args: &[&str]) -> Flags {
        match parse(args) {
            Ok(Parsed::Flags(f)) => f,
            other => panic!("{args:?}: {other:?}"),
        }
    }

    #[test]
    fn values_separate_or_after_an_equals_sign() {
        for args in [&["--dt", "0.5"][..], &["--dt=0.5"][..]] {
            assert_eq!(flags(args).value("--dt"), Some("0.5"));
        }
        // A value may look like a flag or a negative number; `=` may be empty or repeat.
        assert_eq!(flags(&["--dt", "-1"]).value("--dt"), Some("-1"));
        assert_eq!(flags(&["--dt", "--f32"]).value("--dt"), Some("--f32"));
        assert_eq!(flags(&["--dt="]).value("--dt"), Some(""));
        assert_eq!(flags(&["--dt=a=b"]).value("--dt"), Some("a=b"));
        assert!(flags(&["--dt", "--help"]).value("--dt") == Some("--help"));
    }

    #[test]
    fn switches_repeats_and_order() {
        let f = flags(&["--wheel", "1", "--f32", "--wheel=2"]);
        assert!(f.switch("--f32") && !f.switch("--dt"));
        assert_eq!(f.values("--wheel").collect::<Vec<_>>(), ["1", "2"]);
        assert_eq!(
            f.names().collect::<Vec<_>>(),
            ["--wheel", "--f32", "--wheel"]
        );
        assert!(flags(&[]).is_empty());
    }

    #[test]
    fn errors_name_the_argument() {
        let err = |args: &[&str]| parse(args).err().unwrap_or_default();
        assert_eq!(err(&["--dt"]), "--dt needs a value");
        assert_eq!(err(&["--dt", "1", "--dt=2"]), "--dt given more than once");
        assert_eq!(err(&["--f32", "--f32"]), "--f32 given more than once");
        assert_eq!(err(&["--f32=yes"]), "--f32 takes no value");
        assert_eq!(err(&["--bogus"]), "unknown argument '--bogus' (see --help)");
        assert_eq!(err(&["-x"]), "unknown argument '-x' (see --help)");
        assert_eq!(err(&["0.1"]), "unknown argument '0.1' (see --help)");
        assert_eq!(err(&["--"]), "unknown argument '--' (see --help)");
        assert_eq!(
            err(&["--bogus", "--dt"]),
            "unknown argument '--bogus' (see --help)",
            "the first error"
        );
    }

    #[test]
    fn help_wins_where_a_flag_stands() {
        for args in [
            &["-h"][..],
            &["--bogus", "--help"][..],
            &["--dt", "1", "-h"][..],
        ] {
            assert!(matches!(parse(args), Ok(Parsed::Help)), "{args:?}");
        }
    }

    #[test]
    #[should_panic(expected = "--df is not a declared flag")]
    fn asking_for_an_undeclared_flag_is_a_programming_error() {
        flags(&["--dt", "1"]).value("--df");
    }

    #[test]
    fn operands_where_the_tool_takes_them() {
        let args = ["a.csv", "--dt", "-1", "-", "--f32", "b"].map(OsString::from);
        let (parsed, ops) = CLI.parse_with_operands(args.clone()).unwrap();
        let Parsed::Flags(f) = parsed else {
            panic!("flags")
        };
        assert_eq!(ops, ["a.csv", "-", "b"]);
        assert_eq!(
            f.value("--dt"),
            Some("-1"),
            "a flag's value is not an operand"
        );
        assert!(f.switch("--f32"));
        let e = CLI.parse_with_operands(["-x"].map(OsString::from));
        assert_eq!(
            e.err().as_deref(),
            Some("unknown argument '-x' (see --help)")
        );
        // Without operands the same argument is an error.
        assert!(CLI.parse(args).is_err());
    }

    #[test]
    fn non_utf8_arguments_are_errors() {
        use std::os::unix::ffi::OsStringExt;
        let bad = OsString::from_vec(b"--\xff".to_vec());
        let e = CLI.parse([OsString::from("--f32"), bad]).unwrap_err();
        assert!(e.starts_with("argument 2 is not valid UTF-8"), "{e}");
    }

    #[test]
    fn value_parsers() {
        assert_eq!(number("--x", " 2.5 "), Ok(2.5));
        assert_eq!(number("--x", "x"), Err("--x: invalid number 'x'".into()));
        assert_eq!(
            number("--x", "inf"),
            Err("--x: not a finite number 'inf'".into())
        );
        assert_eq!(positive("--dt", "1e-3"), Ok(1e-3));
        for bad in ["0", "-1", "nan", "1e400"] {
            let e = positive("--dt", bad).unwrap_err();
            assert_eq!(e, format!("--dt: must be finite and > 0, got {bad}"));
        }
        assert_eq!(count("--n", "0"), Ok(0));
        assert!(
            count("--n", "-1")
                .unwrap_err()
                .starts_with("--n: invalid count '-1'")
        );
        assert_eq!(
            at_least_one("--n", "0"),
            Err("--n: must be at least 1".into())
        );
        assert_eq!(numbers::<2>("--v", "1, 2", "a,b"), Ok([1.0, 2.0]));
        assert_eq!(
            numbers::<3>("--v", "1,2", "a,b,c"),
            Err("--v: expected 3 comma-separated numbers a,b,c, found 2".into())
        );
        assert_eq!(list("--l", "1,-2"), Ok(vec![1.0, -2.0]));
        assert!(list("--l", "").is_err());
    }
}
