//! The front end every Monte-Carlo study shares (`pick montecarlo`, `dobby tolerance`): run this
//! shard's draws, print them (`--csv`, or JSON Lines with `--shard`), name a finished run's draws
//! for `--from-draws`, and print the summary table of a report. The runner, the per-draw row, the
//! reader of a finished run and the report are the library's ([`loomkin_study::run_draws`],
//! [`DrawRow`], [`DrawSource`], [`loomkin_study::tally`], [`loomkin_study::draws::tally_stream`]).

use crate::output::{self, outln};
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::Result;
use loomkin_io::Table;
use loomkin_study::draws::DrawSource;
use loomkin_study::{DrawEntry, DrawRow, Summary};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The draws of a study for its report, run on this shard's indices (`run` checks their cost
/// first). `None` when they were printed instead (`--csv`, or `--json` with `--shard`/`--parts`).
/// `refused` says what a refused draw is (`not simulated`); `facts` go into a part's manifest.
pub fn collect<D: DrawRow>(
    study_draws: u64,
    format: Format,
    shard: &ShardArgs,
    facts: &BTreeMap<String, String>,
    refused: &str,
    run: impl FnOnce(std::ops::Range<u64>) -> Result<Vec<D>>,
) -> Result<Option<Vec<D>>> {
    shard.check(format)?;
    output::part_facts(facts);
    let items = shard.get().items(study_draws as usize);
    let draws = run(items.start as u64..items.end as u64)?;
    let failed: Vec<&D> = draws.iter().filter(|d| d.results().is_none()).collect();
    if let Some(first) = failed.first() {
        output::note(format_args!(
            "loomkin: note: {} of {} draws {refused} (counted as failing); first, draw {}: {}",
            failed.len(),
            draws.len(),
            first.index(),
            first.error().unwrap_or("")
        ));
    }
    if format.csv {
        let mut table = Table::new(D::columns());
        for d in &draws {
            table.push(d.row())?;
        }
        output::csv_shard(&table, shard.header())?;
        return Ok(None);
    }
    if shard.given() {
        output::json_lines(draws.iter().map(DrawEntry))?;
        return Ok(None);
    }
    Ok(Some(draws))
}

/// The draws of `--from-draws`: a finished run's per-draw CSV (the shards' outputs concatenated,
/// or a merged file), the directory of its parts or the parts themselves, or `-` for standard
/// input; read by the library as the report is made, at any size.
pub fn source(inputs: &[PathBuf]) -> Result<DrawSource> {
    DrawSource::open(inputs).map_err(util::part_error)
}

/// The summaries as a table (mean, sd, percentiles, count failing) and the results' histograms as bars.
pub fn summary_table(inputs: &[(&str, &Summary)], results: &[(&str, &Summary)]) -> Result<()> {
    let Some((_, first)) = results.first() else {
        return Ok(());
    };
    let mut head = format!("{:<26} {:>12} {:>11}", "quantity", "mean", "sd");
    for p in &first.percentiles {
        head.push_str(&format!(" {:>11}", format!("p{}", p.p)));
    }
    head.push_str(&format!(" {:>9}", "failing"));
    outln!("{head}")?;
    for (name, s) in inputs.iter().chain(results) {
        let mut line = format!("{name:<26} {:>12.6} {:>11.4e}", s.mean, s.sd);
        for p in &s.percentiles {
            line.push_str(&format!(" {:>11.6}", p.value));
        }
        let failing = if s.limit.is_some() { s.failing.to_string() } else { "—".into() };
        line.push_str(&format!(" {failing:>9}"));
        outln!("{line}")?;
    }
    outln!(
        "histograms, smallest to largest value ({} bins; edges and counts with --json):",
        first.histogram.counts.len()
    )?;
    for (name, s) in results {
        let h = &s.histogram;
        outln!("{name:<26} {:>11.6} |{}| {:.6}", h.edges[0], bars(&h.counts), h.edges[h.edges.len() - 1])?;
    }
    Ok(())
}

/// Eight-level bars of a histogram's counts.
fn bars(counts: &[u64]) -> String {
    let top = counts.iter().copied().max().unwrap_or(0).max(1);
    counts
        .iter()
        .map(|&c| {
            if c == 0 {
                ' '
            } else {
                ['▁', '▂', '▃', '▄', '▅', '▆', '▇', '█'][((c * 8 - 1) / top) as usize]
            }
        })
        .collect()
}
