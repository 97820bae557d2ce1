//! The front end every Monte-Carlo study shares (`pick montecarlo`, `dobby tolerance`): run this
//! shard's draws, print them (`--csv`, or JSON Lines with `--shard`), name a finished run's draws
//! for `--from-draws`, and print the summary table of a report. The runner, the per-draw row, the
//! reader of a finished run and the report are the library's ([`loomkin_study::run_draws`],
//! [`DrawRow`], [`DrawSource`], [`loomkin_study::tally`], [`loomkin_study::draws::tally_stream`]).

use crate::output::{self, outln};
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::Result;
use loomkin_study::draws::DrawSource;
use loomkin_study::summary::DrawSummary;
use loomkin_study::{DrawEntry, DrawRow, Progress, Summary};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Draws computed (in parallel) and printed at a time by `--csv` and JSON Lines: the memory held
/// is one block's rows, whatever the number of draws (10⁶ draws of `pick montecarlo --csv` held
/// 536 MB before they were streamed).
const BLOCK: u64 = 1 << 14;

/// The draws of a study for its report, run on this shard's indices (`check` refuses them first
/// if their cost passes the budget; `run` computes a range of them, showing its own progress bar
/// when told `Progress::Auto`). `None` when they were printed instead (`--csv`, or `--json` with
/// `--shard`/`--parts`): then they are computed and printed a block at a time.
/// `refused` says what a refused draw is (`not simulated`); `facts` go into a part's manifest.
pub fn collect<D: DrawRow>(
    study_draws: u64,
    format: Format,
    shard: &ShardArgs,
    facts: &BTreeMap<String, String>,
    refused: &str,
    check: impl FnOnce(std::ops::Range<u64>) -> Result<()>,
    run: impl Fn(std::ops::Range<u64>, Progress) -> Vec<D>,
) -> Result<Option<Vec<D>>> {
    shard.check(format)?;
    output::part_facts(facts);
    let items = shard.get().items(study_draws as usize);
    let items = items.start as u64..items.end as u64;
    check(items.clone())?;
    let streamed = format.csv || shard.given();
    if !streamed {
        let draws = run(items, Progress::Auto);
        let failed = draws.iter().filter(|d| d.results().is_none());
        note_refused(failed.clone().count(), draws.len(), failed.clone().next(), refused);
        return Ok(Some(draws));
    }
    // A block at a time: the rows are printed as they are made; the refused draws are counted
    // and the first one kept for the note, printed once the output is written.
    let progress = util::Progress::new(items.end - items.start, "draws");
    let (mut failed, mut first) = (0usize, None::<(u64, String)>);
    let blocks = (items.start..items.end).step_by(BLOCK as usize).map(|lo| lo..(lo + BLOCK).min(items.end));
    let mut tally = |block: &[D]| {
        for d in block.iter().filter(|d| d.results().is_none()) {
            failed += 1;
            first.get_or_insert_with(|| (d.index(), d.error().unwrap_or("").to_string()));
        }
        progress.inc(block.len() as u64);
    };
    let mut block_rows = blocks.map(|b| run(b, Progress::Hidden)).inspect(|block| tally(block));
    if format.csv {
        let columns = D::columns();
        let rows = block_rows.by_ref().flat_map(|block| block.into_iter().map(|d| d.row()));
        output::csv_rows(&columns, shard.header(), rows)?;
    } else {
        output::json_lines(block_rows.by_ref().flat_map(|block| block.into_iter().map(Owned)))?;
    }
    drop(block_rows);
    progress.finish();
    if let Some((index, error)) = &first {
        output::note_after_output(format_args!(
            "loomkin: note: {failed} of {} draws {refused} (counted as failing); first, draw {index}: {error}",
            items.end - items.start
        ))?;
    }
    Ok(None)
}

/// A draw printed as its JSON Lines entry ([`DrawEntry`]), owned: a block's draws are moved out
/// as they are printed.
struct Owned<D>(D);

impl<D: DrawRow> serde::Serialize for Owned<D> {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        DrawEntry(&self.0).serialize(ser)
    }
}

/// The note on the draws refused (`3 of 1000 draws not simulated …; first, draw 17: …`).
fn note_refused<D: DrawRow>(failed: usize, of: usize, first: Option<&D>, refused: &str) {
    if let Some(first) = first {
        output::note(format_args!(
            "loomkin: note: {failed} of {of} draws {refused} (counted as failing); first, draw {}: {}",
            first.index(),
            first.error().unwrap_or("")
        ));
    }
}

/// The draws of `--from-draws`: a finished run's per-draw CSV (the shards' outputs concatenated,
/// or a merged file), the directory of its parts or the parts themselves, or `-` for standard
/// input; read by the library as the report is made, at any size.
pub fn source(inputs: &[PathBuf]) -> Result<DrawSource> {
    DrawSource::open(inputs).map_err(util::part_error)
}

/// This shard's draw indices (all of them without `--shard`).
pub fn items(study_draws: u64, shard: &ShardArgs) -> std::ops::Range<u64> {
    let items = shard.get().items(study_draws as usize);
    items.start as u64..items.end as u64
}

/// Prints a run's mergeable summary ([`loomkin_study::summary`]) as one line of JSON, so the
/// shards' outputs concatenated are what `--from-summaries` reads.
pub fn print_summary(s: &DrawSummary) -> Result<()> {
    outln!("{}", serde_json::to_string(s)?)
}

/// The summaries of `--from-summaries` (files, or `-` for standard input).
pub fn summaries(inputs: &[PathBuf]) -> Result<Vec<DrawSummary>> {
    loomkin_study::summary::read_summaries(inputs).map_err(util::part_error)
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
    if first.histogram.is_none() {
        return outln!("(from per-shard summaries: percentiles and histograms need the draws, --from-draws)");
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
