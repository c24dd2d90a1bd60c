//! Input and output of the command-line tools: one stream reader and one CSV writer for every
//! tool.
//!
//! - [`Lines`] reads a stream line by line as bytes, numbering the lines from 1: a line that is
//!   not UTF-8 or longer than [`MAX_LINE`] is an error naming that line, and the lines after it
//!   are still read (the tool decides whether to go on).
//! - [`Csv`] buffers the CSV on stdout and flushes it as it goes: at least every
//!   [`Csv::FLUSH_EVERY`] and whenever the tool is about to wait for input, so a long run or a
//!   slow input stream shows its rows promptly.
//! - A closed stdout (`tool ... | head`) is [`is_closed_pipe`]: the tools stop quietly there,
//!   without a panic and without a message. [`print_text`] writes `--help` and summaries that
//!   way, and [`say!`](crate::say) writes diagnostics to stderr ignoring a closed stderr.

use std::io::{self, BufRead, BufReader, Read, Write};
use std::time::{Duration, Instant};

/// The longest input line accepted, in bytes (without its line break). The longest valid row of
/// any tool (19 numbers of `convert --op slerp --from matrix`) is a few hundred bytes; a longer
/// line is garbage, and the cap keeps a line-less stream (`/dev/zero`) from filling the memory.
pub const MAX_LINE: usize = 1 << 20;

/// Writes a diagnostic line to stderr, like `eprintln!`, but ignores a failed write (a closed
/// stderr must not turn a diagnostic into a panic).
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// Like [`say!`](crate::say) without the line break.
#[macro_export]
macro_rules! say_part {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr(), $($arg)*);
    }};
}

/// `true` when `e` says the reader of stdout has gone (a pipe closed early).
pub fn is_closed_pipe(e: &io::Error) -> bool {
    e.kind() == io::ErrorKind::BrokenPipe
}

/// Writes `text` to stdout and flushes it. A closed stdout is not an error (the reader has seen
/// enough); any other failure is.
pub fn print_text(text: &str) -> io::Result<()> {
    let mut out = io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if is_closed_pipe(&e) => Ok(()),
        r => r,
    }
}

/// One line of a stream: its number (from 1) and its text, or why the line has none.
pub type Line<'a> = (u64, Result<&'a str, String>);

/// Lines of a byte stream, numbered from 1. Line breaks are `\n` or `\r\n`; a last line without
/// a break counts.
pub struct Lines<R> {
    reader: BufReader<R>,
    number: u64,
    buf: Vec<u8>,
}

impl<R: Read> Lines<R> {
    /// Lines of `reader`.
    pub fn new(reader: R) -> Self {
        Self {
            reader: BufReader::with_capacity(1 << 16, reader),
            number: 0,
            buf: Vec::new(),
        }
    }

    /// `true` when the next line needs a read from the underlying stream, which may wait: the
    /// moment to flush pending output.
    pub fn will_read(&self) -> bool {
        self.reader.buffer().is_empty()
    }

    /// The next line and its number: `Ok(None)` at the end of the input, `Err(reason)` in place
    /// of the text for a line that is not UTF-8 or longer than [`MAX_LINE`], `Err` outside when
    /// reading fails.
    pub fn next_line(&mut self) -> io::Result<Option<Line<'_>>> {
        self.buf.clear();
        let (mut len, mut any, mut too_long) = (0usize, false, false);
        loop {
            let chunk = match self.reader.fill_buf() {
                Ok(c) => c,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            if chunk.is_empty() {
                break;
            }
            any = true;
            let (take, done) = match chunk.iter().position(|&b| b == b'\n') {
                Some(i) => (i + 1, true),
                None => (chunk.len(), false),
            };
            len += take;
            if len > MAX_LINE + 2 {
                too_long = true;
                self.buf.clear();
            } else {
                self.buf.extend_from_slice(&chunk[..take]);
            }
            self.reader.consume(take);
            if done {
                break;
            }
        }
        if !any {
            return Ok(None);
        }
        self.number += 1;
        if self.buf.last() == Some(&b'\n') {
            self.buf.pop();
            if self.buf.last() == Some(&b'\r') {
                self.buf.pop();
            }
        }
        let n = self.number;
        if too_long || self.buf.len() > MAX_LINE {
            return Ok(Some((
                n,
                Err(format!("the line is longer than {MAX_LINE} bytes")),
            )));
        }
        let text = std::str::from_utf8(&self.buf).map_err(|e| {
            format!(
                "not valid UTF-8 text (byte {} of the line)",
                e.valid_up_to() + 1
            )
        });
        Ok(Some((n, text)))
    }
}

/// Buffered CSV output on stdout that flushes as it goes.
pub struct Csv {
    out: io::BufWriter<io::Stdout>,
    flushed: Instant,
}

impl Csv {
    /// The longest time a written row waits in the buffer while the tool keeps computing.
    pub const FLUSH_EVERY: Duration = Duration::from_millis(100);

    /// CSV on stdout.
    pub fn stdout() -> Self {
        Self {
            out: io::BufWriter::with_capacity(1 << 16, io::stdout()),
            flushed: Instant::now(),
        }
    }

    /// Ends a row: flushes when the last flush is [`Csv::FLUSH_EVERY`] ago.
    pub fn row_done(&mut self) -> io::Result<()> {
        if self.flushed.elapsed() >= Self::FLUSH_EVERY {
            self.flush()?;
        }
        Ok(())
    }
}

/// Rows are written with `write!`; call [`Csv::row_done`] after each.
impl Write for Csv {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.out.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.flushed = Instant::now();
        self.out.flush()
    }
}
