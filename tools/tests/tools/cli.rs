//! The host command-line tools (`examples/convert.rs`, `examples/propagate.rs`,
//! `examples/simulate/`) as processes, for the tests of their interfaces.
//!
//! Cargo tells integration tests where the workspace's *binaries* are (`CARGO_BIN_EXE_<name>`),
//! not its examples. `cargo test --workspace` builds the examples too, as plain executables in
//! `<target>/<profile dir>/examples/`. So the first call of [`example`] in a test process runs
//! the same build again with the cargo that runs the tests, for the target directory of the
//! running test executable (`<target>/<profile dir>/deps/<test>`):
//! `cargo test --workspace --no-run [--release] --target-dir <target>`. Under the README test
//! command (`cargo test --workspace --release`) every unit is fresh and this is a check of a
//! second or two; a targeted run (`cargo test --release -p host-tests --test cli_simulate`)
//! builds what is missing first, so a test never runs a stale tool. The command must be the
//! workspace test build itself: `cargo build -p gyrostat --example ...` resolves other features
//! (gyrostat without the `nalgebra`/`mint` features host-tests enables) and would compile a
//! second copy of the library and the tools. A `OnceLock` makes the build happen once per test
//! process; concurrent cargo processes are serialised by cargo's own lock on the target
//! directory.

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

/// The three command-line tools.
pub const TOOLS: [&str; 3] = ["convert", "propagate", "simulate"];

/// `(target directory, profile directory)` of the running test executable.
fn target_of_this_test() -> (PathBuf, PathBuf) {
    let exe = std::env::current_exe().expect("the test knows its executable");
    // <target>/<profile dir>/deps/<test executable>
    let profile_dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("test executables live in <target>/<profile>/deps")
        .to_path_buf();
    let target = profile_dir
        .parent()
        .expect("a profile directory has a parent")
        .to_path_buf();
    (target, profile_dir)
}

/// The path of the built example `name` (one of [`TOOLS`]), building the tools on first use.
pub fn example(name: &str) -> PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    let dir = DIR.get_or_init(|| {
        let (target, profile_dir) = target_of_this_test();
        let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut cmd = Command::new(env!("CARGO"));
        cmd.current_dir(&root)
            .args(["test", "-q", "--workspace", "--no-run", "--target-dir"])
            .arg(&target);
        // The same profile as the running test: `--release` when it is optimised.
        if !cfg!(debug_assertions) {
            cmd.arg("--release");
        }
        // Cargo's "Executable ..." lines go to stderr; keep the test's output readable.
        let out = cmd.output().expect("cargo runs");
        assert!(
            out.status.success(),
            "building the command-line tools failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        profile_dir.join("examples")
    });
    dir.join(name)
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
    let mut child = Command::new(example(name))
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
    let mut cmd = Command::new(example(name));
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
