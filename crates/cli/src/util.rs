//! Shared plumbing of the subcommands: output formats, JSON printing, exit codes, `KEY=VALUE` params.

use anyhow::{Context, anyhow};
use clap::Args;
use std::io::Write;

/// An error that is a failure of the run (exit 1), not of the user's input (exit 2).
#[derive(Debug)]
pub struct Failure(String);

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Failure {}

/// Exit code for an error: 1 if it is a [`Failure`], else 2 (bad input or usage).
pub fn exit_code(e: &anyhow::Error) -> u8 {
    if e.chain().any(|c| c.is::<Failure>()) { 1 } else { 2 }
}

/// Wraps an output error (writing a file or stdout) as a run failure, exit code 1.
pub fn failure(e: impl Into<anyhow::Error>) -> anyhow::Error {
    let e: anyhow::Error = e.into();
    anyhow::Error::new(Failure(format!("{e:#}")))
}

/// `--json` / `--csv` choice shared by the subcommands.
#[derive(Debug, Clone, Copy, Args, Default)]
pub struct Format {
    /// Print machine-readable JSON.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print CSV (header with units, one row per sample).
    #[arg(long)]
    pub csv: bool,
}

/// Prints a JSON value (pretty) to stdout; refuses non-finite numbers anywhere in it.
pub fn print_json(value: &serde_json::Value) -> anyhow::Result<()> {
    check_finite(value, "")?;
    let mut out = std::io::stdout().lock();
    serde_json::to_writer_pretty(&mut out, value).map_err(failure)?;
    writeln!(out).map_err(failure)?;
    Ok(())
}

fn check_finite(v: &serde_json::Value, path: &str) -> anyhow::Result<()> {
    match v {
        serde_json::Value::Null => Err(anyhow!("internal: '{path}' is not a finite number")).map_err(failure),
        serde_json::Value::Array(a) => {
            a.iter().enumerate().try_for_each(|(i, x)| check_finite(x, &format!("{path}[{i}]")))
        }
        serde_json::Value::Object(o) => o.iter().try_for_each(|(k, x)| check_finite(x, &format!("{path}.{k}"))),
        _ => Ok(()),
    }
}

/// Prints a table as CSV to stdout.
pub fn print_csv(table: &loomkin_io::Table) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    table.write_csv(&mut out).map_err(failure)
}

/// Splits `KEY=VALUE`.
pub fn parse_key_value(s: &str) -> Result<(String, String), String> {
    let (k, v) = s.split_once('=').ok_or_else(|| format!("'{s}' is not KEY=VALUE"))?;
    Ok((k.trim().to_string(), v.trim().to_string()))
}

/// Reads a whole input file, naming it in the error (a missing input is a usage error: exit 2).
pub fn read_input(path: &std::path::Path) -> anyhow::Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}

/// Saves a figure, naming the file in the error.
pub fn save_figure(fig: &loomkin_io::plot::Figure, path: &std::path::Path) -> anyhow::Result<()> {
    match fig.save(path) {
        Ok(()) => {
            eprintln!("wrote {}", path.display());
            Ok(())
        }
        // A wrong extension is the user's mistake; a drawing or file error is a failure.
        Err(e @ loomkin_io::IoError::PlotFormat { .. }) => Err(e.into()),
        Err(e) => Err(failure(e)),
    }
}
