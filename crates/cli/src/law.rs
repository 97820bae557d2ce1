//! `loomkin law …`: the catalogue of normalised laws.

use crate::output::{self, Out, outln};
use crate::util::{self, Format};
use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use loomkin_laws::{CATALOGUE, InfoReport, Kinematics, Law, LawSpec, ListedLaw};
use loomkin_plot::{Figure, Legend, Panel, Series};
use loomkin_units::{Cost, Shard};
use serde::Serialize;
use std::path::PathBuf;

/// Subcommands of `loomkin law`.
#[derive(Debug, Subcommand)]
pub enum LawCommand {
    /// The catalogue, one line per law with its metrics.
    List(ListArgs),
    /// Exact metrics and the continuity report of one law.
    Info(InfoArgs),
    /// N evenly spaced samples of x, s, v, a, j (both ends included).
    Sample(SampleArgs),
    /// s, v, a, j stacked in one figure; several laws overlaid.
    Plot(PlotArgs),
}

/// Law parameters given as `--param KEY=VALUE`.
#[derive(Debug, Args, Clone, Default)]
pub struct Params {
    /// A law parameter, e.g. `--param ramp=0.1` or `--param segments=0.5:constant:1,0.5:constant:-1`.
    #[arg(long = "param", value_name = "KEY=VALUE", value_parser = util::parse_key_value)]
    pub params: Vec<(String, String)>,
}

/// `law list`.
#[derive(Debug, Args)]
pub struct ListArgs {
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `law info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// Law name (see `loomkin law list`).
    law: String,
    #[command(flatten)]
    params: Params,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `law sample`.
#[derive(Debug, Args)]
pub struct SampleArgs {
    /// Law name.
    law: String,
    /// Number of points (≥ 2), both ends included.
    #[arg(long, short = 'n')]
    points: usize,
    #[command(flatten)]
    params: Params,
    #[command(flatten)]
    format: Format,
    #[command(flatten)]
    shard: crate::shard::ShardArgs,
}

/// `law plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// Law names to overlay.
    #[arg(required = true)]
    laws: Vec<String>,
    /// Parameters, applied to every listed law that has the key.
    #[command(flatten)]
    params: Params,
    /// Output file, .svg or .png.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
    /// Points per curve.
    #[arg(long, default_value_t = Law::PLOT_POINTS.default_count())]
    points: usize,
}

/// Runs a `law` subcommand.
pub fn run(cmd: LawCommand) -> Result<()> {
    match cmd {
        LawCommand::List(a) => list(a),
        LawCommand::Info(a) => info(a),
        LawCommand::Sample(a) => sample(a),
        LawCommand::Plot(a) => plot(a),
    }
}

/// Builds a law from its name and parameters.
pub fn build(name: &str, params: &[(String, String)]) -> Result<(LawSpec, Law)> {
    let spec = LawSpec::parse(name, params)?;
    let law = spec.build().with_context(|| format!("law '{name}'"))?;
    Ok((spec, law))
}

fn list(a: ListArgs) -> Result<()> {
    let laws = ListedLaw::catalogue()?;
    if a.json {
        return output::json(&ListJson { laws });
    }
    outln!("Normalised rise laws (x: fraction of the motion angle, s: fraction of the stroke; values dimensionless)")?;
    outln!("{:<22} {:>8} {:>8} {:>9} {:>8} {:>8} {:>5}  description", "law", "Cv", "Ca", "Cj", "Cm", "Ca_rms", "C^k")?;
    for l in &laws {
        let (e, m) = (l, &l.metrics);
        let params = if e.params.is_empty() { String::new() } else { format!(" [{}]", e.params) };
        outln!(
            "{:<22} {:>8.4} {:>8.4} {:>9.3} {:>8.4} {:>8.4} {:>5}  {}{}",
            e.name,
            m.cv,
            m.ca,
            m.cj,
            m.cm,
            m.ca_rms,
            class_text(l.continuity_class),
            e.description,
            params
        )?;
    }
    outln!(
        "{:<22} {:>8} {:>8} {:>9} {:>8} {:>8} {:>5}  general piecewise acceleration [segments=LEN:SHAPE[:LEVEL…],…]",
        "piecewise",
        "-",
        "-",
        "-",
        "-",
        "-",
        "-"
    )?;
    outln!(
        "{:<22} {:>8} {:>8} {:>9} {:>8} {:>8} {:>5}  polynomial acceleration per segment [segments=LEN:c0[:c1…],…]",
        "polynomial",
        "-",
        "-",
        "-",
        "-",
        "-",
        "-"
    )?;
    outln!("C^k: continuity in a dwell-rise-dwell cycle (C1: s, v continuous; C2: also a; C3: also j).")?;
    Ok(())
}

fn class_text(c: i32) -> String {
    if c < 0 { "none".into() } else { format!("C{c}") }
}

/// `law list --json`.
#[derive(Serialize)]
struct ListJson {
    laws: Vec<ListedLaw>,
}

fn info(a: InfoArgs) -> Result<()> {
    let (spec, law) = build(&a.law, &a.params.params)?;
    let r = InfoReport::new(spec.name(), spec.param_values(), &law);
    if a.json {
        return output::json(&r);
    }
    let (m, c) = (r.metrics, law.continuity());
    outln!("law {}", spec.label())?;
    outln!("  values per unit stroke and unit motion angle (dimensionless)")?;
    outln!("  Cv   = max v       = {:.10}   at x = {:.6}", m.cv, m.x_cv)?;
    outln!("  Ca   = max |a|     = {:.10}", m.ca)?;
    outln!("  Ca+  = max a       = {:.10}   at x = {:.6}", m.ca_pos, m.x_ca_pos)?;
    outln!("  Ca-  = min a       = {:.10}   at x = {:.6}", m.ca_neg, m.x_ca_neg)?;
    outln!("  Cj   = max |j|     = {:.10}   at x = {:.6}  (inside segments)", m.cj, m.x_cj)?;
    outln!("  Cm   = max v·a     = {:.10}   at x = {:.6}", m.cm, m.x_cm)?;
    outln!("  Ca_rms = √∫a²dx    = {:.10}", m.ca_rms)?;
    outln!(
        "continuity ({} segments; jumps right − left; dwells at s = 0 before and s = 1 after):",
        law.segments().len()
    )?;
    outln!("  {:>10} {:>12} {:>12} {:>12} {:>12}  continuous", "x", "Δs", "Δv", "Δa", "Δj")?;
    for j in std::iter::once(&c.start).chain(&c.joints).chain(std::iter::once(&c.end)) {
        let f = j.flags();
        let names: Vec<&str> = ["s", "v", "a", "j"].iter().zip(f).filter(|(_, ok)| *ok).map(|(n, _)| *n).collect();
        outln!(
            "  {:>10.6} {:>12.4e} {:>12.4e} {:>12.4e} {:>12.4e}  {}",
            j.x,
            j.ds,
            j.dv,
            j.da,
            j.dj,
            if names.is_empty() { "none".into() } else { names.join(", ") }
        )?;
    }
    outln!("  class in a dwell-rise-dwell cycle: {}", class_text(c.class))?;
    Ok(())
}

fn sample(a: SampleArgs) -> Result<()> {
    Law::SAMPLE_POINTS.check_count_as("--points", a.points)?;
    a.shard.check(a.format)?;
    let shard = a.shard.get();
    check_sample_budget(a.points, shard.items(a.points).len(), a.format.json)?;
    let (spec, law) = build(&a.law, &a.params.params)?;
    let form = if !a.format.json {
        SampleForm::Csv { header: a.shard.header() }
    } else if a.shard.given() {
        SampleForm::JsonLines
    } else {
        SampleForm::Json
    };
    print_samples(&law, a.points, shard, form, Some(spec.name().to_string()))
}

/// How [`print_samples`] prints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleForm {
    /// CSV, with or without its header line (a later shard has none).
    Csv {
        /// Whether to print the header line.
        header: bool,
    },
    /// One JSON document `{"law"?, "points", "units"}`.
    Json,
    /// JSON Lines, one sample a line (a shard's form).
    JsonLines,
}

/// Refuses `--points N` of a streamed sample table (`rows` of them printed here, a shard's share)
/// estimated beyond the budget: one block of samples is held in memory, so the time of
/// formatting the numbers is what limits N.
pub fn check_sample_budget(points: usize, rows: usize, json: bool) -> Result<()> {
    let per_row = if json { SAMPLE_JSON_S_PER_ROW } else { SAMPLE_CSV_S_PER_ROW };
    crate::util::check_budget("--points", points, Cost::cpu_items(rows as f64, 0.0, per_row))?;
    Ok(())
}

/// Prints shard `shard` of `n` samples of x, s, v, a, j, streamed: one block of samples is in
/// memory at a time, whatever `n`; each sample is the whole run's, bit for bit.
pub fn print_samples(law: &Law, n: usize, shard: Shard, form: SampleForm, name: Option<String>) -> Result<()> {
    let items = shard.items(n);
    let share = || law.samples(n).skip(items.start).take(items.len());
    // The law's values are checked finite before a byte is written (sampling is cheap beside
    // printing), so the streamed output never stops half-way.
    if let Some((x, _)) = share().find(|(_, k)| ![k.s, k.v, k.a, k.j].iter().all(|v| v.is_finite())) {
        return Err(util::failure(anyhow::anyhow!("internal: the law is not finite at x = {x}")));
    }
    let progress = util::Progress::new(items.len() as u64, "samples");
    let rows = share().inspect(|_| progress.inc(1));
    /// One sample, keys in the order they always had.
    #[derive(serde::Serialize)]
    struct P {
        a: f64,
        j: f64,
        s: f64,
        v: f64,
        x: f64,
    }
    if form == SampleForm::JsonLines {
        output::json_lines(rows.map(|(x, k)| P { a: k.a, j: k.j, s: k.s, v: k.v, x }))?;
    } else if form == SampleForm::Json {
        #[derive(serde::Serialize)]
        #[serde(bound = "I: Iterator<Item = (f64, Kinematics)>")]
        struct Out<I: Iterator<Item = (f64, Kinematics)>> {
            #[serde(skip_serializing_if = "Option::is_none")]
            law: Option<String>,
            points: Points<I>,
            units: &'static str,
        }
        /// The samples, serialised as they are made (keys in the order they always had).
        struct Points<I>(std::cell::RefCell<Option<I>>);
        impl<I: Iterator<Item = (f64, Kinematics)>> serde::Serialize for Points<I> {
            fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
                let rows = self.0.borrow_mut().take().into_iter().flatten();
                ser.collect_seq(rows.map(|(x, k)| P { a: k.a, j: k.j, s: k.s, v: k.v, x }))
            }
        }
        let units = "dimensionless (per unit stroke, per unit motion angle)";
        output::json_streamed(&Out { law: name, points: Points(std::cell::RefCell::new(Some(rows))), units })?;
    } else {
        let header = form == SampleForm::Csv { header: true };
        output::csv_rows(&["x", "s", "v", "a", "j"], header, rows.map(|(x, k)| [x, k.s, k.v, k.a, k.j]))?;
    }
    progress.finish();
    Ok(())
}

/// CPU seconds per row of `law sample --json` (five numbers with their keys, pretty-printed): the
/// `cycle_json_rows` bench of loomkin-laws (release, fastest of 10: 0.92 µs a row of six keyed
/// numbers).
const SAMPLE_JSON_S_PER_ROW: f64 = 0.92e-6;

/// CPU seconds per row of `law sample --csv` (five numbers in shortest round-trip form): the
/// `law_sample_csv_rows` bench (fastest of 10: 1.83 µs).
const SAMPLE_CSV_S_PER_ROW: f64 = 1.83e-6;

fn plot(a: PlotArgs) -> Result<()> {
    output::check_outputs([Some(Out::plot("--output", &a.output))])?;
    Law::PLOT_POINTS.check_count_as("--points", a.points)?;
    for (k, _) in &a.params.params {
        let known = a.laws.iter().any(|l| CATALOGUE.iter().any(|e| e.name == l && e.has_param(k)));
        if !known {
            bail!("--param {k}: none of the laws {} has this parameter", a.laws.join(", "));
        }
    }
    let mut panels: Vec<Panel> =
        ["displacement s [-]", "velocity v = ds/dx [-]", "acceleration a = d²s/dx² [-]", "jerk j = d³s/dx³ [-]"]
            .iter()
            .map(|l| Panel::new(*l, Vec::new()))
            .collect();
    for name in &a.laws {
        let applicable: Vec<(String, String)> = a
            .params
            .params
            .iter()
            .filter(|(k, _)| CATALOGUE.iter().any(|e| e.name == name && e.has_param(k)))
            .cloned()
            .collect();
        let (spec, law) = build(name, &applicable)?;
        let samples = law.sample(a.points);
        for (i, p) in panels.iter_mut().enumerate() {
            p.series.push(Series::line(spec.label(), samples.iter().map(|(x, k)| (*x, k.order(i))).collect()));
        }
    }
    for (i, p) in panels.iter_mut().enumerate() {
        p.legend = if i == 0 { Legend::Auto } else { Legend::Hidden };
    }
    let fig = Figure::new("Normalised motion laws", "x = fraction of the motion angle [-]", panels);
    output::figure(&fig, &a.output, &a.plot)
}
