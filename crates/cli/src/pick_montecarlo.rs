//! `loomkin pick montecarlo`: loom settings drawn from stated distributions, the end-of-pick
//! results as distributions (library: `loomkin_picking::montecarlo`).

use crate::output::{self, outln};
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::{Result, bail};
use clap::Args;
use loomkin_io::Table;
use loomkin_picking::montecarlo::{Draw, DrawResult, INPUTS, RESULTS, Report};
use loomkin_picking::{Mechanism, MonteCarlo};
use loomkin_study::{Progress, Summary};
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
    /// The report of a finished run from its per-draw CSV (the shards' outputs concatenated).
    #[arg(long, value_name = "FILE.csv", conflicts_with_all = ["csv", "shard"])]
    from_draws: Option<PathBuf>,
}

/// The per-draw table's columns.
fn columns() -> Vec<String> {
    let mut c = vec!["draw".to_string()];
    c.extend(INPUTS.iter().map(|s| s.key()));
    c.push("simulated".into());
    c.extend(RESULTS.iter().map(|s| s.to_string()));
    c.push("ode".into());
    c.push("separation".into());
    c
}

fn flag(b: bool) -> f64 {
    if b { 1.0 } else { 0.0 }
}

/// A draw as a table row; a refused draw has 0 in `simulated` and in its results.
fn row(d: &Draw) -> Vec<f64> {
    let mut r = vec![d.index as f64];
    r.extend(d.inputs);
    match &d.result {
        Ok(x) => {
            r.push(1.0);
            r.extend(x.values);
            r.push(flag(x.ode));
            r.push(flag(x.separation));
        }
        Err(_) => r.extend(std::iter::repeat_n(0.0, RESULTS.len() + 3)),
    }
    r
}

/// A draw as a JSON Lines object (a refused draw carries its error text).
fn draw_json(d: &Draw) -> serde_json::Value {
    let mut v = serde_json::Map::new();
    v.insert("draw".into(), d.index.into());
    for (s, x) in INPUTS.iter().zip(d.inputs) {
        v.insert(s.key(), x.into());
    }
    match &d.result {
        Ok(x) => {
            for (k, y) in RESULTS.iter().zip(x.values) {
                v.insert(k.to_string(), y.into());
            }
            v.insert("ode".into(), x.ode.into());
            v.insert("separation".into(), x.separation.into());
        }
        Err(e) => {
            v.insert("error".into(), e.clone().into());
        }
    }
    serde_json::Value::Object(v)
}

/// Reads the per-draw CSV back: the header as written, rows numbered 0, 1, … in order.
fn read_draws(path: &std::path::Path, draws: u64) -> Result<Vec<Draw>> {
    let text = util::read_input(path)?;
    let name = path.display();
    let mut lines = text.lines();
    let want = columns().join(",");
    if lines.next() != Some(want.as_str()) {
        bail!("{name}: the first line is not the header of pick montecarlo --csv ({want})");
    }
    let mut out = Vec::new();
    for (i, line) in lines.enumerate() {
        let v: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| anyhow::anyhow!("{name}: line {}: not {} numbers", i + 2, columns().len()))?;
        if v.len() != columns().len() || v.iter().any(|x| !x.is_finite()) {
            bail!("{name}: line {}: not {} finite numbers", i + 2, columns().len());
        }
        if v[0] != i as f64 {
            bail!("{name}: line {}: draw {} where draw {i} belongs: concatenate every shard, in order", i + 2, v[0]);
        }
        let n_in = INPUTS.len();
        let inputs: [f64; 5] = std::array::from_fn(|k| v[1 + k]);
        let result = if v[1 + n_in] == 1.0 {
            let at = 2 + n_in;
            Ok(DrawResult {
                values: std::array::from_fn(|k| v[at + k]),
                ode: v[at + RESULTS.len()] == 1.0,
                separation: v[at + RESULTS.len() + 1] == 1.0,
            })
        } else {
            Err("not simulated".to_string())
        };
        out.push(Draw { index: i as u64, inputs, result });
    }
    if out.len() as u64 != draws {
        bail!("{name}: {} draws where the study has {draws}: concatenate every shard's --csv output", out.len());
    }
    Ok(out)
}

/// Runs `pick montecarlo`.
pub fn run(a: MonteCarloArgs) -> Result<()> {
    a.shard.check(a.format)?;
    let mc = MonteCarlo::from_toml(&util::read_input(&a.file)?)?;
    let mech: Mechanism = super::pick::mechanism(&a.model)?;
    let draws = match &a.from_draws {
        Some(path) => read_draws(path, mc.draws)?,
        None => {
            let items = a.shard.get().items(mc.draws as usize);
            let cost = mc.cost(items.start as u64..items.end as u64);
            loomkin_units::Budget::DEFAULT.check("draws", mc.draws, cost)?;
            let draws = mc.run(&mech, items.start as u64..items.end as u64, Progress::Auto);
            let refused: Vec<&Draw> = draws.iter().filter(|d| d.result.is_err()).collect();
            if let Some(first) = refused.first() {
                output::note(format_args!(
                    "loomkin: note: {} of {} draws not simulated (counted as failing); first, draw {}: {}",
                    refused.len(),
                    draws.len(),
                    first.index,
                    first.result.as_ref().err().map_or("", String::as_str)
                ));
            }
            if a.format.csv {
                let mut t = Table::new(columns());
                for d in &draws {
                    t.push(row(d))?;
                }
                return output::csv_shard(&t, a.shard.get());
            }
            if a.shard.given() {
                return output::json_lines(draws.iter().map(draw_json));
            }
            draws
        }
    };
    let report = mc.report(&draws);
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
    let results: Vec<(&str, &Summary)> = r.results.iter().map(|q| (q.name, &q.summary)).collect();
    summary_table(&inputs, &results)
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
