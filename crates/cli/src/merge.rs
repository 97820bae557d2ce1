//! `loomkin merge`: the parts of a sharded run (`--parts DIR`) checked and joined into the
//! one-machine output (library: [`loomkin_study::parts`]).

use crate::output::{self, Out};
use crate::util;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

/// `merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The parts: a directory of parts (--parts DIR), or part files (or their manifests).
    #[arg(required = true, value_name = "DIR|PART")]
    parts: Vec<PathBuf>,
    /// The merged file (written under a temporary name and renamed when every part has been checked,
    /// with its manifest beside it), or - for standard output.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
}

/// Runs `merge`: exit 1 naming the missing or damaged parts when the check fails.
pub fn run(a: MergeArgs) -> Result<()> {
    output::check_outputs([Some(Out::file("--output", &a.output))])?;
    let set = loomkin_study::parts::find(&a.parts).map_err(util::part_error)?.check().map_err(util::part_error)?;
    let m = set.manifest();
    let (count, rows) = (m.shard.count, set.rows());
    if a.output.as_os_str() == "-" {
        let mut out = std::io::BufWriter::with_capacity(1 << 16, output::sink());
        set.merge_into(&mut out).map_err(util::part_error)?;
        return std::io::Write::flush(&mut out).map_err(|e| output::WriteError::stdout(e).into());
    }
    set.merge_to(&a.output).map_err(util::part_error)?;
    output::note(format_args!("wrote {} ({rows} rows from {count} parts)", a.output.display()));
    Ok(())
}
