//! `loomkin dobby tolerance`: the modulator's dimensions drawn from stated distributions, the
//! output-angle error, pressure angle and dead-point margin as distributions (library:
//! `loomkin_mech::tolerance`).

use crate::output::{self, outln};
use crate::pick_montecarlo::summary_table;
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::{Result, bail};
use clap::Args;
use loomkin_io::Table;
use loomkin_mech::Tolerance;
use loomkin_mech::tolerance::{DIMENSIONS, Draw, RESULTS, Report};
use loomkin_study::{Progress, Summary};
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
    /// The report of a finished run from its per-draw CSV (the shards' outputs concatenated).
    #[arg(long, value_name = "FILE.csv", conflicts_with_all = ["csv", "shard"])]
    from_draws: Option<PathBuf>,
}

fn columns() -> Vec<String> {
    let mut c = vec!["draw".to_string()];
    c.extend(DIMENSIONS.iter().map(|s| s.to_string()));
    c.push("assembled".into());
    c.extend(RESULTS.iter().map(|s| s.to_string()));
    c
}

fn row(d: &Draw) -> Vec<f64> {
    let mut r = vec![d.index as f64];
    r.extend(d.dimensions);
    match &d.result {
        Ok(x) => {
            r.push(1.0);
            r.extend(x);
        }
        Err(_) => r.extend(std::iter::repeat_n(0.0, RESULTS.len() + 1)),
    }
    r
}

fn draw_json(d: &Draw) -> serde_json::Value {
    let mut v = serde_json::Map::new();
    v.insert("draw".into(), d.index.into());
    for (k, x) in DIMENSIONS.iter().zip(d.dimensions) {
        v.insert(k.to_string(), x.into());
    }
    match &d.result {
        Ok(x) => {
            for (k, y) in RESULTS.iter().zip(x) {
                v.insert(k.to_string(), (*y).into());
            }
        }
        Err(e) => {
            v.insert("error".into(), e.clone().into());
        }
    }
    serde_json::Value::Object(v)
}

fn read_draws(path: &std::path::Path, draws: u64) -> Result<Vec<Draw>> {
    let text = util::read_input(path)?;
    let name = path.display();
    let mut lines = text.lines();
    let want = columns().join(",");
    if lines.next() != Some(want.as_str()) {
        bail!("{name}: the first line is not the header of dobby tolerance --csv ({want})");
    }
    let width = columns().len();
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
        let n = DIMENSIONS.len();
        let dimensions: [f64; 8] = std::array::from_fn(|k| v[1 + k]);
        let result =
            if v[1 + n] == 1.0 { Ok(std::array::from_fn(|k| v[2 + n + k])) } else { Err("not assembled".to_string()) };
        out.push(Draw { index: i as u64, dimensions, result });
    }
    if out.len() as u64 != draws {
        bail!("{name}: {} draws where the study has {draws}: concatenate every shard's --csv output", out.len());
    }
    Ok(out)
}

/// Runs `dobby tolerance`.
pub fn run(a: ToleranceArgs) -> Result<()> {
    a.shard.check(a.format)?;
    let t = Tolerance::from_toml(&util::read_input(&a.file)?)?;
    let draws = match &a.from_draws {
        Some(path) => read_draws(path, t.draws)?,
        None => {
            let items = a.shard.get().items(t.draws as usize);
            let cost = t.cost(items.start as u64..items.end as u64);
            loomkin_units::Budget::DEFAULT.check("draws", t.draws, cost)?;
            let draws = t.run(items.start as u64..items.end as u64, Progress::Auto);
            let refused: Vec<&Draw> = draws.iter().filter(|d| d.result.is_err()).collect();
            if let Some(first) = refused.first() {
                output::note(format_args!(
                    "loomkin: note: {} of {} draws do not run over the turn (counted as failing); first, draw {}: {}",
                    refused.len(),
                    draws.len(),
                    first.index,
                    first.result.as_ref().err().map_or("", String::as_str)
                ));
            }
            if a.format.csv {
                let mut table = Table::new(columns());
                for d in &draws {
                    table.push(row(d))?;
                }
                return output::csv_shard(&table, a.shard.get());
            }
            if a.shard.given() {
                return output::json_lines(draws.iter().map(draw_json));
            }
            draws
        }
    };
    let report = t.report(&draws);
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
    let dims: Vec<(&str, &Summary)> = r.dimensions.iter().map(|q| (q.name, &q.summary)).collect();
    let results: Vec<(&str, &Summary)> = r.results.iter().map(|q| (q.name, &q.summary)).collect();
    summary_table(&dims, &results)
}
