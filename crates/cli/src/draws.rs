//! The front end every Monte-Carlo study shares (`pick montecarlo`, `dobby tolerance`): run this
//! shard's draws or read a finished run's per-draw CSV back, print the draws (`--csv`, or JSON
//! Lines with `--shard`), and the summary table of a report. The runner, the per-draw row and the
//! report are the library's ([`loomkin_study::run_draws`], [`DrawRow`], [`loomkin_study::tally`]).

use crate::output::{self, outln};
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::{Result, bail};
use loomkin_io::Table;
use loomkin_study::{DrawEntry, DrawRow, Summary};
use std::path::Path;

/// The draws of a study for its report: read from `from_draws` (a finished run's per-draw CSV),
/// or run (`run` on this shard's indices, which checks their cost first). `None` when they were printed instead (`--csv`, or
/// `--json` with `--shard`). `refused` says what a refused draw is (`not simulated`).
pub fn collect<D: DrawRow>(
    command: &str,
    study_draws: u64,
    format: Format,
    shard: &ShardArgs,
    from_draws: Option<&Path>,
    refused: &str,
    run: impl FnOnce(std::ops::Range<u64>) -> Result<Vec<D>>,
) -> Result<Option<Vec<D>>> {
    shard.check(format)?;
    if let Some(path) = from_draws {
        return read_draws(command, path, study_draws).map(Some);
    }
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
        output::csv_shard(&table, shard.get())?;
        return Ok(None);
    }
    if shard.given() {
        output::json_lines(draws.iter().map(DrawEntry))?;
        return Ok(None);
    }
    Ok(Some(draws))
}

/// Reads a per-draw CSV back: the header as written, rows numbered 0, 1, … in order, every draw
/// of the study.
fn read_draws<D: DrawRow>(command: &str, path: &Path, draws: u64) -> Result<Vec<D>> {
    let text = util::read_input(path)?;
    let name = path.display();
    let mut lines = text.lines();
    let want = D::columns().join(",");
    if lines.next() != Some(want.as_str()) {
        bail!("{name}: the first line is not the header of {command} --csv ({want})");
    }
    let width = D::columns().len();
    let mut out = Vec::new();
    for (i, line) in lines.enumerate() {
        let v: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| anyhow::anyhow!("{name}: line {}: not {width} numbers", i + 2))?;
        if v.len() != width || v.iter().any(|x| !x.is_finite()) {
            bail!("{name}: line {}: not {width} finite numbers", i + 2);
        }
        if v[0] != i as f64 {
            bail!("{name}: line {}: draw {} where draw {i} belongs: concatenate every shard, in order", i + 2, v[0]);
        }
        out.push(D::from_row(&v));
    }
    if out.len() as u64 != draws {
        bail!("{name}: {} draws where the study has {draws}: concatenate every shard's --csv output", out.len());
    }
    Ok(out)
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
