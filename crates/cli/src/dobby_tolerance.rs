//! `loomkin dobby tolerance`: the modulator's dimensions drawn from stated distributions, the
//! output-angle error, pressure angle and dead-point margin as distributions (library:
//! `loomkin_mech::tolerance`).

use crate::draws;
use crate::output::{self, outln};
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::Result;
use clap::Args;
use loomkin_mech::Tolerance;
use loomkin_mech::tolerance::{Draw, Report};
use loomkin_study::Summary;
use std::path::PathBuf;

/// `dobby tolerance`.
#[derive(Debug, Args)]
pub struct ToleranceArgs {
    /// The study (TOML): draws, seed, `[dimensions]` distributions, `[limits]`; see examples/dobby-tolerance.toml.
    file: PathBuf,
    /// --csv: one row per draw (dimensions and results); --json: the report (with --shard: the draws as JSON Lines).
    #[command(flatten)]
    format: Format,
    #[command(flatten)]
    shard: ShardArgs,
    /// The report of a finished run from its per-draw CSV: the shards' outputs concatenated, a merged file,
    /// the directory of its parts (--parts) or the parts, or - for standard input; read as a stream, any size.
    /// Draws whose manifest names another seed, distributions or model are refused.
    #[arg(long, value_name = "FILE.csv|DIR|-", num_args = 1.., conflicts_with_all = ["csv", "shard", "parts"])]
    from_draws: Option<Vec<PathBuf>>,
    /// Print this shard's (or the whole run's) mergeable summary instead of its draws or report: one line of
    /// JSON with the counts and, per quantity, count, mean, sum of squared deviations, extremes and count
    /// failing. --from-summaries joins the shards' summaries into the report without moving the draws.
    #[arg(long, conflicts_with_all = ["csv", "json", "parts", "from_draws"])]
    summary: bool,
    /// The report of a finished run from its shards' --summary outputs, in any order: files, each holding one
    /// or more, or `-` for standard input. Counts, failing share, extremes as the one-machine report, mean and
    /// sd to rounding (1e-12); no percentiles or histograms, which need the draws (--from-draws).
    #[arg(long, value_name = "FILE|-", num_args = 1.., conflicts_with_all = ["csv", "shard", "parts", "from_draws", "summary"])]
    from_summaries: Option<Vec<PathBuf>>,
}

/// Runs `dobby tolerance`.
pub fn run(a: ToleranceArgs) -> Result<()> {
    if !a.summary {
        a.shard.check(a.format)?;
    }
    let t = Tolerance::from_toml(&util::read_input(&a.file)?)?;
    if a.summary {
        let items = draws::items(t.draws, &a.shard);
        crate::util::check_budget("draws", t.draws, t.cost(items.clone()))?;
        let drawn = t.run(items.clone(), loomkin_study::Progress::Auto);
        return draws::print_summary(&t.summary(items, &drawn));
    }
    let report = match (&a.from_draws, &a.from_summaries) {
        (Some(inputs), _) => {
            let source = draws::source(inputs)?;
            t.report_from(&source).map_err(util::part_error)?
        }
        (None, Some(files)) => t.report_from_summaries(&draws::summaries(files)?).map_err(util::part_error)?,
        (None, None) => {
            let check = |items| Ok(crate::util::check_budget("draws", t.draws, t.cost(items))?);
            let run = |items, progress| t.run(items, progress);
            let refused = "do not run over the turn";
            let Some(draws) = draws::collect::<Draw>(t.draws, a.format, &a.shard, &t.facts(), refused, check, run)?
            else {
                return Ok(());
            };
            t.report(&draws)
        }
    };
    if a.format.json {
        return output::json(&report);
    }
    text_report(&report)
}

fn text_report(r: &Report) -> Result<()> {
    outln!(
        "dobby tolerance: {} draws, seed {}, analysis step {}°, {} not assembled over the turn",
        r.draws,
        r.seed,
        r.step_deg,
        r.not_assembled
    )?;
    outln!("failing a limit or not assembled: {} of {} ({:.3} %)", r.failing, r.draws, 100.0 * r.fail_share)?;
    let dims: Vec<(&str, &Summary)> = r.dimensions.iter().map(|q| (q.name.as_str(), &q.summary)).collect();
    let results: Vec<(&str, &Summary)> = r.results.iter().map(|q| (q.name.as_str(), &q.summary)).collect();
    draws::summary_table(&dims, &results)
}
