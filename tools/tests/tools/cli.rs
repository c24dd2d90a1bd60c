//! The command-line tools as processes, for the tests of their interfaces: Cargo builds the
//! binaries of this package before its tests and names them in `CARGO_BIN_EXE_<name>`.

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// The path of the tool `name` (`convert`, `propagate`, `simulate`, `estimate` or
/// `characterize`).
pub fn tool(name: &str) -> PathBuf {
    PathBuf::from(match name {
        "convert" => env!("CARGO_BIN_EXE_convert"),
        "propagate" => env!("CARGO_BIN_EXE_propagate"),
        "simulate" => env!("CARGO_BIN_EXE_simulate"),
        "estimate" => env!("CARGO_BIN_EXE_estimate"),
        "synthesize" => env!("CARGO_BIN_EXE_synthesize"),
        "characterize" => env!("CARGO_BIN_EXE_characterize"),
        other => panic!("no tool {other}"),
    })
}

/// What a tool run produced.
#[derive(Debug)]
pub struct Output {
    /// Everything written to stdout.
    pub stdout: String,
    /// Everything written to stderr.
    pub stderr: String,
    /// The exit status (`None` if killed by a signal).
    pub status: Option<i32>,
}

impl Output {
    /// The stdout lines.
    pub fn lines(&self) -> Vec<&str> {
        self.stdout.lines().collect()
    }
}

/// Runs the tool `name` with `args` and `stdin` as its standard input.
pub fn run(name: &str, args: &[&str], stdin: &str) -> Output {
    let args: Vec<OsString> = args.iter().map(OsString::from).collect();
    run_raw(name, &args, stdin.as_bytes().to_vec())
}

/// Runs the tool `name` with arguments and standard input that need not be UTF-8. Stdout must
/// be UTF-8 (the tools write ASCII); stderr is read lossily.
pub fn run_raw(name: &str, args: &[OsString], stdin: Vec<u8>) -> Output {
    let mut child = Command::new(tool(name))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("{name} runs: {e}"));
    let mut input = child.stdin.take().expect("piped stdin");
    // Feed stdin from a thread so a tool that writes before reading all input cannot deadlock.
    let feeder = std::thread::spawn(move || {
        // A tool that stops reading early (a bad row) closes the pipe: not an error here.
        let _ = input.write_all(&stdin);
    });
    let out = child.wait_with_output().expect("the tool finishes");
    feeder.join().expect("stdin feeder");
    Output {
        stdout: String::from_utf8(out.stdout).expect("UTF-8 stdout"),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        status: out.status.code(),
    }
}

/// Which of a tool's output streams [`run_closed`] closes.
#[derive(Clone, Copy, Debug)]
pub enum Closed {
    /// Stdout is a pipe whose reader has gone; stderr is captured.
    Stdout,
    /// Stdout and stderr are both such a pipe.
    Both,
}

/// Runs the tool `name` with `stdin` as input and its stdout (or stdout and stderr) a pipe
/// whose reading end is already closed, as in `tool ... | head -0`: every write fails with
/// `EPIPE`. Returns the exit status and what stderr got (empty with [`Closed::Both`]).
pub fn run_closed(name: &str, args: &[&str], stdin: &str, closed: Closed) -> (Option<i32>, String) {
    let closed_pipe = || {
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        Stdio::from(writer)
    };
    let mut cmd = Command::new(tool(name));
    cmd.args(args).stdin(Stdio::piped()).stdout(closed_pipe());
    match closed {
        Closed::Stdout => cmd.stderr(Stdio::piped()),
        Closed::Both => cmd.stderr(closed_pipe()),
    };
    let mut child = cmd.spawn().unwrap_or_else(|e| panic!("{name} runs: {e}"));
    let mut input = child.stdin.take().expect("piped stdin");
    let text = stdin.to_string();
    let feeder = std::thread::spawn(move || {
        let _ = input.write_all(text.as_bytes());
    });
    let out = child.wait_with_output().expect("the tool finishes");
    feeder.join().expect("stdin feeder");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Parses a CSV row of numbers.
pub fn numbers(line: &str) -> Vec<f64> {
    line.split(',')
        .map(|f| {
            f.trim()
                .parse()
                .unwrap_or_else(|_| panic!("not a number: {f:?} in {line:?}"))
        })
        .collect()
}

/// Formats numbers as a CSV row in the shortest form that round-trips (`{:?}`).
pub fn row(xs: &[f64]) -> String {
    xs.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// `propagate` on a stream of increments: the final attitude (the last row).
pub fn final_attitude(algo: &str, arith: &[&str], q0: [f64; 4], input: &str) -> [f64; 4] {
    let q0 = format!("{:?},{:?},{:?},{:?}", q0[0], q0[1], q0[2], q0[3]);
    let n = input.lines().count().to_string();
    let mut args = vec![
        "--input",
        "increments",
        "--algo",
        algo,
        "--dt",
        "0.001",
        "--q0",
        &q0,
        "--every",
        &n,
    ];
    args.extend_from_slice(arith);
    let out = run("propagate", &args, input);
    assert_eq!(out.status, Some(0), "{algo} {arith:?}: {}", out.stderr);
    let last = out.lines().last().copied().expect("a row");
    let v = numbers(last);
    [v[1], v[2], v[3], v[4]]
}
