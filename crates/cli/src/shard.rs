//! `--shard I/N` and `--parts DIR`: one machine's share of a sweep, table or Monte-Carlo run (see
//! docs/scale.md and docs/design/shards.md).
//!
//! Shard `I` of `N` computes and prints only the rows `⌊(I−1)·len/N⌋ .. ⌊I·len/N⌋` of the whole
//! output ([`loomkin_units::Shard::items`]). On standard output, CSV has the header only in shard
//! 1 and JSON is JSON Lines, so the N outputs concatenated in order are byte-identical to the
//! one-machine output. With `--parts DIR` the shard is written as a part of the library's
//! [`loomkin_study::parts`] instead: atomically, with a manifest, a header in every CSV part;
//! `loomkin merge` checks and joins them.

use crate::util::Format;
use clap::Args;
use loomkin_study::parts::{Fnv64, Manifest};
use loomkin_units::Shard;
use std::path::PathBuf;

/// The `--shard` and `--parts` flags shared by the sweep, table and Monte-Carlo commands.
#[derive(Debug, Clone, Args, Default)]
pub struct ShardArgs {
    /// Compute and print only shard I of N of the rows (1 ≤ I ≤ N): CSV has its header in shard 1 only,
    /// JSON is JSON Lines; the N outputs concatenated in order are the whole output. Needs --csv or --json.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Write the shard as a part in DIR instead of standard output: DIR/part-IIIII-of-NNNNN.csv (or .jsonl),
    /// a header in every CSV part, a manifest beside it, written under a temporary name and renamed when
    /// complete. `loomkin merge DIR -o FILE` checks the N parts and writes the one-machine output.
    #[arg(long, value_name = "DIR")]
    pub parts: Option<PathBuf>,
}

fn parse_shard(text: &str) -> Result<Shard, String> {
    Shard::parse("shard", text).map_err(|e| e.to_string())
}

impl ShardArgs {
    /// The shard asked for, or the whole run.
    pub fn get(&self) -> Shard {
        self.shard.unwrap_or(Shard::WHOLE)
    }

    /// Whether the output is a shard (`--shard` or `--parts`): JSON output is then JSON Lines.
    pub fn given(&self) -> bool {
        self.shard.is_some() || self.parts.is_some()
    }

    /// Whether a CSV output starts with its header: in shard 1, and in every part of `--parts`.
    pub fn header(&self) -> bool {
        self.get().is_first() || self.parts.is_some()
    }

    /// A sharded run writes a table that concatenates: CSV or JSON Lines, not the text report.
    /// With `--parts`, the part is started here (the output goes to it from now on).
    pub fn check(&self, format: Format) -> anyhow::Result<()> {
        if self.given() && !format.csv && !format.json {
            let flag = if self.shard.is_some() { "--shard" } else { "--parts" };
            anyhow::bail!("{flag} needs --csv or --json (JSON Lines): the text report does not concatenate");
        }
        if let Some(dir) = &self.parts {
            let ext = if format.csv { "csv" } else { "jsonl" };
            let (study, command) = study();
            crate::output::start_part(dir, Manifest::head(&study, command, self.get()), ext)?;
        }
        Ok(())
    }
}

/// Largest input file hashed into a study's fingerprint (a larger one counts by its size).
const MAX_HASHED_BYTES: u64 = 64 << 20;

/// The study of this run: the command line without `--shard` and `--parts`, and its fingerprint
/// (that line and the contents of the files it names), the same in every shard of one run.
fn study() -> (String, Vec<String>) {
    let mut command = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--shard" || a == "--parts" {
            args.next();
        } else if !a.starts_with("--shard=") && !a.starts_with("--parts=") {
            command.push(a);
        }
    }
    let mut h = Fnv64::default();
    for a in &command {
        h.update(a.as_bytes());
        h.update(&[0]);
        let path = std::path::Path::new(a);
        if let Ok(meta) = std::fs::metadata(path)
            && meta.is_file()
        {
            match std::fs::read(path) {
                Ok(bytes) if meta.len() <= MAX_HASHED_BYTES => h.update(&bytes),
                _ => h.update(&meta.len().to_le_bytes()),
            }
        }
    }
    (h.hex(), command)
}
