//! `loomkin pick montecarlo`: loom settings drawn from stated distributions, the end-of-pick
//! results as distributions (library: `loomkin_picking::montecarlo`).

use crate::draws;
use crate::output::{self, outln};
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::Result;
use clap::Args;
use loomkin_picking::montecarlo::{Draw, Report};
use loomkin_picking::{Mechanism, MonteCarlo};
use loomkin_study::Summary;
use std::path::PathBuf;

/// `pick montecarlo`.
#[derive(Debug, Args)]
pub struct MonteCarloArgs {
    /// The study (TOML): draws, seed, `[settings]` distributions, `[limits]`; see examples/pick-montecarlo.toml.
    file: PathBuf,
    #[command(flatten)]
    model: super::pick::ModelArgs,
    /// --csv: one row per draw (settings and results); --json: the report (with --shard: the draws as JSON Lines).
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

/// Runs `pick montecarlo`.
pub fn run(a: MonteCarloArgs) -> Result<()> {
    if !a.summary {
        a.shard.check(a.format)?;
    }
    let mc = MonteCarlo::from_toml(&util::read_input(&a.file)?)?;
    let mech: Mechanism = super::pick::mechanism(&a.model)?;
    if a.summary {
        let items = draws::items(mc.draws, &a.shard);
        crate::util::check_budget("draws", mc.draws, mc.cost(items.clone()))?;
        let drawn = mc.run(&mech, items.clone(), loomkin_study::Progress::Auto);
        return draws::print_summary(&mc.summary(&mech, items, &drawn));
    }
    let report = match (&a.from_draws, &a.from_summaries) {
        (Some(inputs), _) => {
            let source = draws::source(inputs)?;
            mc.report_from(&mech, &source).map_err(util::part_error)?
        }
        (None, Some(files)) => mc.report_from_summaries(&mech, &draws::summaries(files)?).map_err(util::part_error)?,
        (None, None) => {
            let check = |items| Ok(crate::util::check_budget("draws", mc.draws, mc.cost(items))?);
            let run = |items, progress| mc.run(&mech, items, progress);
            let facts = mc.facts(&mech);
            let collected = draws::collect::<Draw>(mc.draws, a.format, &a.shard, &facts, "not simulated", check, run)?;
            let Some(draws) = collected else { return Ok(()) };
            mc.report(&draws)
        }
    };
    if a.format.json {
        return output::json(&report);
    }
    text_report(&report)
}

fn text_report(r: &Report) -> Result<()> {
    outln!(
        "pick Monte-Carlo: {} draws, seed {}, route {} ({} by numerical integration), {} not simulated, {} separated early",
        r.draws,
        r.seed,
        r.method.name(),
        r.ode_draws,
        r.not_simulated,
        r.separation_draws
    )?;
    outln!("failing a limit or not simulated: {} of {} ({:.3} %)", r.failing, r.draws, 100.0 * r.fail_share)?;
    let inputs: Vec<(&str, &Summary)> = r.inputs.iter().map(|q| (q.name.as_str(), &q.summary)).collect();
    let results: Vec<(&str, &Summary)> = r.results.iter().map(|q| (q.name.as_str(), &q.summary)).collect();
    draws::summary_table(&inputs, &results)
}
