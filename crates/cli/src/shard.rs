//! `--shard I/N`: one machine's share of a sweep, table or Monte-Carlo run (see docs/scale.md).
//!
//! Shard `I` of `N` computes and prints only the rows `⌊(I−1)·len/N⌋ .. ⌊I·len/N⌋` of the whole
//! output ([`loomkin_units::Shard::items`]). CSV: the header only in shard 1. JSON: sharded output
//! is JSON Lines, one compact object per row (`--shard 1/1 --json` is the whole run in that form).
//! So the N outputs concatenated in order are byte-identical to the one-machine output.

use crate::util::Format;
use clap::Args;
use loomkin_units::Shard;

/// The `--shard` flag shared by the sweep, table and Monte-Carlo commands.
#[derive(Debug, Clone, Copy, Args, Default)]
pub struct ShardArgs {
    /// Compute and print only shard I of N of the rows (1 ≤ I ≤ N): CSV has its header in shard 1 only,
    /// JSON is JSON Lines; the N outputs concatenated in order are the whole output. Needs --csv or --json.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
}

fn parse_shard(text: &str) -> Result<Shard, String> {
    Shard::parse("shard", text).map_err(|e| e.to_string())
}

impl ShardArgs {
    /// The shard asked for, or the whole run.
    pub fn get(&self) -> Shard {
        self.shard.unwrap_or(Shard::WHOLE)
    }

    /// Whether `--shard` was given (JSON output is then JSON Lines).
    pub fn given(&self) -> bool {
        self.shard.is_some()
    }

    /// A sharded run writes a table that concatenates: CSV or JSON Lines, not the text report.
    pub fn check(&self, format: Format) -> anyhow::Result<()> {
        if self.given() && !format.csv && !format.json {
            anyhow::bail!("--shard needs --csv or --json (JSON Lines): the text report does not concatenate");
        }
        Ok(())
    }
}
