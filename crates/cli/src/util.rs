//! Shared plumbing of the subcommands: output format flags, exit codes, `KEY=VALUE` params, input files.

use anyhow::Context;
use clap::Args;

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
    if e.chain().any(|c| c.is::<Failure>() || c.is::<crate::output::WriteError>()) { 1 } else { 2 }
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

/// Splits `KEY=VALUE`.
pub fn parse_key_value(s: &str) -> Result<(String, String), String> {
    let (k, v) = s.split_once('=').ok_or_else(|| format!("'{s}' is not KEY=VALUE"))?;
    Ok((k.trim().to_string(), v.trim().to_string()))
}

/// Largest input file read (16 MiB): every input of loomkin (a cycle, a drive, a mechanism, a
/// point table, a shedding spec) is a few KiB; a larger one (or `/dev/zero`) is refused before it
/// fills the memory.
pub const MAX_INPUT_BYTES: u64 = 16 * 1024 * 1024;

/// Reads a whole input file of at most [`MAX_INPUT_BYTES`], naming it in the error (a missing,
/// unreadable, oversized or non-UTF-8 input is a usage error: exit 2).
pub fn read_input(path: &std::path::Path) -> anyhow::Result<String> {
    use std::io::Read;
    let name = path.display();
    let file = std::fs::File::open(path).with_context(|| format!("cannot read {name}"))?;
    let mut bytes = Vec::new();
    file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes).with_context(|| format!("cannot read {name}"))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        anyhow::bail!("cannot read {name}: larger than the input limit of 16 MiB");
    }
    String::from_utf8(bytes)
        .map_err(|e| anyhow::anyhow!("cannot read {name}: not UTF-8 text (byte {})", e.utf8_error().valid_up_to()))
}
