//! The one output path of the binary: everything a command prints goes through these functions.
//!
//! Standard output is written with checked writes: a closed pipe (`loomkin law list | head -1`)
//! ends the program quietly with exit code 0, as ripgrep does; any other failure (a full disk,
//! `> /dev/full`) is one line naming the file or "standard output", exit code 1. Messages for the
//! user (`wrote FILE`, warnings, notes) go to standard error; a failure to write them is ignored,
//! since there is nowhere left to report it.

use anyhow::anyhow;
use loomkin_study::parts::PartWriter;
use serde::Serialize;
use std::fmt;
use std::io::{self, Write};
use std::path::Path;

/// Writes one line to standard output through [`fn@line`]; evaluates to `anyhow::Result<()>`.
macro_rules! outln {
    () => {
        $crate::output::line(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::output::line(format_args!($($arg)*))
    };
}
pub(crate) use outln;

/// Writing the output (standard output or a file) failed: a run failure, exit code 1.
#[derive(Debug)]
pub struct WriteError {
    /// The file, or "standard output".
    target: String,
    /// The cause, printed in the message (not chained, so it is said once).
    cause: io::Error,
}

impl WriteError {
    /// A failure to write standard output.
    pub fn stdout(cause: io::Error) -> Self {
        Self { target: "standard output".into(), cause }
    }

    /// A failure to create or write a file.
    pub fn file(path: &str, cause: io::Error) -> Self {
        Self { target: path.into(), cause }
    }

    /// The reader went away (EPIPE): not an error for a command-line filter.
    pub fn is_broken_pipe(&self) -> bool {
        self.cause.kind() == io::ErrorKind::BrokenPipe
    }
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write {}: {}", self.target, self.cause)
    }
}

impl std::error::Error for WriteError {}

/// True if the error is a closed pipe on the output, which ends the program quietly.
pub fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| c.downcast_ref::<WriteError>().is_some_and(WriteError::is_broken_pipe))
}

/// The part a sharded run writes instead of standard output (`--parts DIR`), once started.
static PART: std::sync::Mutex<Option<PartWriter>> = std::sync::Mutex::new(None);

/// Where the output goes: standard output, or the part being written.
pub enum Sink {
    /// Standard output.
    Stdout(io::StdoutLock<'static>),
    /// The part of `--parts DIR`.
    Part(std::sync::MutexGuard<'static, Option<PartWriter>>),
}

/// The output of the command: the part of `--parts DIR` when one was started, else standard output.
pub fn sink() -> Sink {
    let part = PART.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if part.is_some() { Sink::Part(part) } else { Sink::Stdout(io::stdout().lock()) }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Sink::Stdout(o) => o.write(buf),
            Sink::Part(p) => p.as_mut().map_or(Ok(buf.len()), |p| p.write(buf)),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match self {
            Sink::Stdout(o) => o.flush(),
            Sink::Part(p) => p.as_mut().map_or(Ok(()), |p| p.flush()),
        }
    }
}

/// Sends the output to a new part in `dir` (see [`loomkin_study::parts`]) until [`finish`].
pub fn start_part(dir: &Path, manifest: loomkin_study::parts::Manifest, ext: &str) -> anyhow::Result<()> {
    let mut part = PART.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if part.is_none() {
        *part = Some(PartWriter::create(dir, manifest, ext).map_err(crate::util::part_error)?);
    }
    Ok(())
}

/// Adds facts to the manifest of the part being written (none without `--parts`).
pub fn part_facts(facts: &std::collections::BTreeMap<String, String>) {
    let mut part = PART.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(p) = part.as_mut() {
        for (k, v) in facts {
            p.fact(k, v.clone());
        }
    }
}

/// Drops an unfinished part (the command failed): its temporary file is removed, no part appears.
pub fn abandon_part() {
    let mut part = PART.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    part.take();
}

/// Writes one line (the formatted text and a newline) to standard output.
pub fn line(args: fmt::Arguments<'_>) -> anyhow::Result<()> {
    let mut out = sink();
    out.write_fmt(args).and_then(|()| out.write_all(b"\n")).map_err(|e| WriteError::stdout(e).into())
}

/// Writes text as it is to `path`, `-` meaning standard output.
pub fn text_to(path: &str, text: &str) -> anyhow::Result<()> {
    if path == "-" {
        let mut out = sink();
        return out.write_all(text.as_bytes()).and_then(|()| out.flush()).map_err(|e| WriteError::stdout(e).into());
    }
    if path.trim().is_empty() {
        // An empty name is the user's mistake (exit 2), not a failed write.
        anyhow::bail!("--output is empty: give a file name, or - for standard output");
    }
    std::fs::write(path, text).map_err(|e| WriteError::file(path, e))?;
    note(format_args!("wrote {path}"));
    Ok(())
}

/// Prints a value as pretty JSON on standard output; refuses non-finite numbers anywhere in it.
///
/// Streamed: a first pass serialises into a scanner that only looks for `null` (serde's form of a
/// non-finite number) outside strings, a second writes to standard output through a buffer, so
/// the memory needed is that of `value` alone (10⁶ samples: 2.7 GB through a `Value` before).
/// Only when a `null` is seen is the value converted to find and name its path.
pub fn json(value: &impl Serialize) -> anyhow::Result<()> {
    let mut scan = NullScan::default();
    serde_json::to_writer(&mut scan, value).map_err(|e| crate::util::failure(anyhow!("internal: {e}")))?;
    if scan.found {
        let value = serde_json::to_value(value).map_err(|e| crate::util::failure(anyhow!("internal: {e}")))?;
        check_finite(&value, "")?;
    }
    let mut out = io::BufWriter::with_capacity(1 << 16, sink());
    serde_json::to_writer_pretty(&mut out, value)
        .map_err(io::Error::from)
        .and_then(|()| out.write_all(b"\n"))
        .and_then(|()| out.flush())
        .map_err(|e| WriteError::stdout(e).into())
}

/// A writer that keeps nothing and notes whether the JSON written holds a `null` outside strings.
#[derive(Default)]
struct NullScan {
    in_string: bool,
    escaped: bool,
    last: [u8; 4],
    found: bool,
}

impl Write for NullScan {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        for &b in buf {
            if self.in_string {
                match (self.escaped, b) {
                    (true, _) => self.escaped = false,
                    (false, b'\\') => self.escaped = true,
                    (false, b'"') => self.in_string = false,
                    _ => {}
                }
                continue;
            }
            if b == b'"' {
                self.in_string = true;
            }
            self.last = [self.last[1], self.last[2], self.last[3], b];
            self.found |= &self.last == b"null";
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

fn check_finite(v: &serde_json::Value, path: &str) -> anyhow::Result<()> {
    match v {
        serde_json::Value::Null => Err(crate::util::failure(anyhow!("internal: '{path}' is not a finite number"))),
        serde_json::Value::Array(a) => {
            a.iter().enumerate().try_for_each(|(i, x)| check_finite(x, &format!("{path}[{i}]")))
        }
        serde_json::Value::Object(o) => o.iter().try_for_each(|(k, x)| check_finite(x, &format!("{path}.{k}"))),
        _ => Ok(()),
    }
}

/// Prints a large value as pretty JSON on standard output as it is serialised, in one pass: the
/// memory needed is a buffer, whatever the size (`law sample --points 10000000 --json`). For values
/// whose numbers the command has checked finite; should a non-finite one slip through anyway, the
/// output stops at it with an internal error (exit 1) rather than print `null`.
pub fn json_streamed(value: &impl Serialize) -> anyhow::Result<()> {
    let mut out = Checked { scan: NullScan::default(), out: io::BufWriter::with_capacity(1 << 16, sink()) };
    match serde_json::to_writer_pretty(&mut out, value) {
        Ok(()) => out.out.write_all(b"\n").and_then(|()| out.out.flush()).map_err(|e| WriteError::stdout(e).into()),
        Err(_) if out.scan.found => {
            Err(crate::util::failure(anyhow!("internal: a number in the output is not finite")))
        }
        Err(e) => Err(WriteError::stdout(io::Error::from(e)).into()),
    }
}

/// An iterator serialised as a JSON array as it runs, for [`json_streamed`]: nothing is held per
/// item. It is consumed by the first serialisation (a second one writes `[]`).
pub struct Streamed<'a, T>(std::cell::RefCell<Option<Box<dyn Iterator<Item = T> + 'a>>>);

impl<'a, T> Streamed<'a, T> {
    /// The items of `items`, to be serialised once.
    pub fn new(items: impl Iterator<Item = T> + 'a) -> Self {
        Self(std::cell::RefCell::new(Some(Box::new(items))))
    }
}

impl<T: Serialize> Serialize for Streamed<'_, T> {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        ser.collect_seq(self.0.borrow_mut().take().into_iter().flatten())
    }
}

/// Standard output behind a [`NullScan`]: a `null` outside strings fails the write.
struct Checked<W: Write> {
    scan: NullScan,
    out: W,
}

impl<W: Write> Write for Checked<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.scan.write_all(buf)?;
        if self.scan.found {
            return Err(io::Error::other("a non-finite number"));
        }
        self.out.write_all(buf)?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

/// Prints a table as CSV on standard output.
pub fn csv(table: &loomkin_io::Table) -> anyhow::Result<()> {
    csv_rows(table.columns(), true, table.rows().iter())
}

/// Prints CSV on standard output row by row as `rows` makes them (a buffer in memory, whatever the
/// number of rows), with the header line unless `header` is false (a later shard of a table); a
/// non-finite number is an internal error (exit 1) at its row.
pub fn csv_rows<S: AsRef<str>, R: AsRef<[f64]>>(
    columns: &[S],
    header: bool,
    rows: impl Iterator<Item = R>,
) -> anyhow::Result<()> {
    let out = io::BufWriter::with_capacity(1 << 16, sink());
    let fail = |e: loomkin_io::IoError| match e {
        loomkin_io::IoError::Write(e) => WriteError::stdout(e).into(),
        e => crate::util::failure(anyhow!("internal: {e}")),
    };
    let mut w =
        if header { loomkin_io::CsvRows::new(out, columns) } else { loomkin_io::CsvRows::continuing(out, columns) }
            .map_err(fail)?;
    for row in rows {
        w.push(row.as_ref()).map_err(fail)?;
    }
    w.finish().map_err(fail).map(drop)
}

/// Prints a shard of a table as CSV: the header if `header` (the first shard, or every part of
/// `--parts`: [`crate::shard::ShardArgs::header`]), then the rows the table holds (the caller
/// computed only this shard's rows), so the shards' outputs concatenated in order are the whole
/// table's CSV byte for byte.
pub fn csv_shard(table: &loomkin_io::Table, header: bool) -> anyhow::Result<()> {
    let mut text = Vec::new();
    table.write_csv(&mut text).map_err(crate::util::failure)?;
    let body = if header {
        &text[..]
    } else {
        let header_end = text.iter().position(|&b| b == b'\n').map_or(text.len(), |i| i + 1);
        &text[header_end..]
    };
    let mut out = sink();
    out.write_all(body).and_then(|()| out.flush()).map_err(|e| WriteError::stdout(e).into())
}

/// Prints JSON Lines: each value on one line of compact JSON. This is the form of sharded JSON
/// output (`--shard I/N --json`): lines concatenate where JSON documents do not. Refuses a
/// non-finite number (a `null`) anywhere, naming its line.
pub fn json_lines<I>(values: I) -> anyhow::Result<()>
where
    I: IntoIterator,
    I::Item: Serialize,
{
    let mut out = io::BufWriter::with_capacity(1 << 16, sink());
    let mut line = Vec::new();
    for (i, v) in values.into_iter().enumerate() {
        line.clear();
        serde_json::to_writer(&mut line, &v).map_err(|e| crate::util::failure(anyhow!("internal: {e}")))?;
        let mut scan = NullScan::default();
        scan.write_all(&line).map_err(|e| crate::util::failure(anyhow!("internal: {e}")))?;
        if scan.found {
            let value = serde_json::to_value(&v).map_err(|e| crate::util::failure(anyhow!("internal: {e}")))?;
            check_finite(&value, &format!("line {}", i + 1))?;
        }
        line.push(b'\n');
        out.write_all(&line).map_err(WriteError::stdout)?;
    }
    out.flush().map_err(|e| WriteError::stdout(e).into())
}

/// A file a command is to write, named by its option (`--output`, `--dxf`), for [`check_outputs`].
pub enum Out<'a> {
    /// A plot: `.svg` or `.png`.
    Plot(&'static str, &'a Path),
    /// A file of any name, `-` meaning standard output.
    File(&'static str, &'a Path),
}

impl<'a> Out<'a> {
    /// A plot file given with `option`.
    pub fn plot(option: &'static str, path: &'a (impl AsRef<Path> + ?Sized)) -> Self {
        Out::Plot(option, path.as_ref())
    }

    /// A file (or `-`) given with `option`.
    pub fn file(option: &'static str, path: &'a (impl AsRef<Path> + ?Sized)) -> Self {
        Out::File(option, path.as_ref())
    }

    fn parts(&self) -> (&'static str, &'a Path) {
        match self {
            Out::Plot(o, p) | Out::File(o, p) => (o, p),
        }
    }
}

/// Checks every output of a command before anything is computed or written, so a bad name is the
/// one line the run prints (not a line after warnings, nor after another output was written): a
/// plot's extension and an empty name are the user's mistake (exit 2), as is one file named by two
/// options; a folder that does not exist, or a name that is a folder, cannot be written (exit 1,
/// the message the write itself would give).
pub fn check_outputs<'a>(outs: impl IntoIterator<Item = Option<Out<'a>>>) -> anyhow::Result<()> {
    let outs: Vec<Out<'a>> = outs.into_iter().flatten().collect();
    for (i, out) in outs.iter().enumerate() {
        let (option, path) = out.parts();
        if path.to_string_lossy().trim().is_empty() {
            let or_stdout = if matches!(out, Out::File(..)) { ", or - for standard output" } else { "" };
            anyhow::bail!("{option} is empty: give a file name{or_stdout}");
        }
        if matches!(out, Out::File(..)) && path.as_os_str() == "-" {
            continue;
        }
        if let Out::Plot(..) = out {
            loomkin_plot::plot_format(path).map_err(|e| anyhow!("{option}: {e}"))?;
        }
        if let Some((other, _)) = outs[..i].iter().map(Out::parts).find(|(_, p)| *p == path) {
            anyhow::bail!("{option}: {} is also the file of {other}: give each output its own name", path.display());
        }
        let name = path.display().to_string();
        if path.is_dir() {
            return Err(WriteError::file(&name, io::Error::new(io::ErrorKind::IsADirectory, "it is a folder")).into());
        }
        let folder = path.parent().filter(|f| !f.as_os_str().is_empty()).unwrap_or(Path::new("."));
        match std::fs::metadata(folder) {
            Ok(m) if m.is_dir() => {}
            Ok(_) => {
                let cause =
                    io::Error::new(io::ErrorKind::NotADirectory, format!("{} is not a folder", folder.display()));
                return Err(WriteError::file(&name, cause).into());
            }
            Err(cause) => return Err(WriteError::file(&name, cause).into()),
        }
    }
    Ok(())
}

/// Saves a figure with the user's size, resolution and title, naming the file in the error.
pub fn figure(fig: &loomkin_plot::Figure, path: &Path, opts: &crate::util::PlotOpts) -> anyhow::Result<()> {
    let fig = fig.clone().with_page(&opts.page()?).map_err(crate::util::page_error)?;
    match fig.save(path) {
        Ok(()) => {
            note(format_args!("wrote {}", path.display()));
            Ok(())
        }
        // A wrong extension is the user's mistake; a drawing or file error is a failure.
        Err(e @ loomkin_io::IoError::PlotFormat { .. }) => Err(e.into()),
        Err(e) => Err(crate::util::failure(e)),
    }
}

/// A message for the user on standard error (`wrote FILE`, a report beside a table on stdout).
pub fn note(args: fmt::Arguments<'_>) {
    let mut err = io::stderr().lock();
    let _ = err.write_fmt(args).and_then(|()| err.write_all(b"\n"));
}

/// A message for the user that follows the output (`optimised in 0.05 s`): standard output is
/// flushed first, so after a closed pipe or a failed write the message is not printed (the run
/// ends quietly, or with the one error line).
pub fn note_after_output(args: fmt::Arguments<'_>) -> anyhow::Result<()> {
    sink().flush().map_err(WriteError::stdout)?;
    note(args);
    Ok(())
}

/// A warning on standard error, prefixed `loomkin: warning:`.
pub fn warning(message: impl fmt::Display) {
    note(format_args!("loomkin: warning: {message}"));
}

/// Ends the output: flushes standard output, so a late write failure is reported too; a part
/// being written is completed (renamed into place, its manifest beside it).
pub fn finish() -> anyhow::Result<()> {
    let part = PART.lock().unwrap_or_else(std::sync::PoisonError::into_inner).take();
    if let Some(p) = part {
        let path = p.path().display().to_string();
        let m = p.finish().map_err(crate::util::part_error)?;
        note(format_args!("wrote {path} ({} rows, shard {}/{})", m.rows, m.shard.index, m.shard.count));
    }
    io::stdout().flush().map_err(|e| WriteError::stdout(e).into())
}
