//! `loomkin dyn …`: elastic follower dynamics — response, speed sweep, residual spectrum,
//! compensation, quiet laws. Parses, calls `loomkin-dynamics`, prints.

use crate::output::{self, outln};
use crate::util::{self, Format};
use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use loomkin_dynamics::{Follower, Response, STANDARD_GRAVITY, Start, Summary, sweep};
use loomkin_io::Table;
use loomkin_io::plot::{Figure, Panel, Series};
use loomkin_laws::{Cycle, StrokeUnit};
use loomkin_units::{ShaftSpeed, Span};
use serde_json::json;
use std::path::{Path, PathBuf};

/// `loomkin dyn` subcommands.
#[derive(Debug, Subcommand)]
pub enum DynCommand {
    /// Exact response of an elastic follower to a cycle at one speed: dynamic error, residual vibration in
    /// the dwells, peak acceleration and force, VDI 2149 rigidity ratio.
    Response(ResponseArgs),
    /// Residual amplitude, peak error and peak force against shaft speed (FROM:TO:STEP rpm).
    Sweep(SweepArgs),
}

/// The follower model shared by the subcommands.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// Natural frequency of the follower (frame on its drive) in Hz (> 0).
    #[arg(long)]
    natural_hz: f64,
    /// Damping ratio ζ (0 ≤ ζ < 1).
    #[arg(long, default_value_t = 0.0)]
    damping_ratio: f64,
    /// Moving mass in kg: enables forces (train/contact force, contact loss).
    #[arg(long)]
    mass_kg: Option<f64>,
    /// Return spring acting on the mass, N/m (needs --mass-kg; f_n is that of the whole follower).
    #[arg(long, default_value_t = 0.0, requires = "mass_kg")]
    return_spring_n_m: f64,
    /// Spring preload pulling the follower onto the cam, N (needs --mass-kg).
    #[arg(long, default_value_t = 0.0, requires = "mass_kg")]
    preload_n: f64,
    /// Add the follower's weight m·g as a closing force (a follower rising upwards).
    #[arg(long, requires = "mass_kg")]
    weight: bool,
    /// A further constant closing force, N (needs --mass-kg).
    #[arg(long, default_value_t = 0.0, requires = "mass_kg")]
    force_n: f64,
}

impl ModelArgs {
    fn follower(&self) -> Result<Follower> {
        let f = Follower::new(self.natural_hz, self.damping_ratio)?;
        Ok(match self.mass_kg {
            Some(m) => {
                let weight = if self.weight { m * STANDARD_GRAVITY } else { 0.0 };
                f.with_loads(m, self.return_spring_n_m, self.preload_n + weight + self.force_n)?
            }
            None => f,
        })
    }
}

/// `loomkin dyn response`.
#[derive(Debug, Args)]
pub struct ResponseArgs {
    /// The cycle file (TOML, as for `loomkin cycle`).
    file: PathBuf,
    /// Main-shaft speed in rpm (default: the file's `speed_rpm`, else 300).
    #[arg(long)]
    speed_rpm: Option<f64>,
    #[command(flatten)]
    model: ModelArgs,
    /// Number of cycles computed from rest at 0° of the cycle.
    #[arg(long, default_value_t = 1, conflicts_with = "steady")]
    cycles: usize,
    /// The periodic steady state (the motion that repeats every cycle) instead of starting from rest.
    #[arg(long)]
    steady: bool,
    /// Samples per cycle for CSV, JSON and plots.
    #[arg(long, default_value_t = 721)]
    points: usize,
    #[command(flatten)]
    format: Format,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
}

/// `loomkin dyn sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The cycle file (TOML).
    file: PathBuf,
    /// Speeds FROM:TO:STEP in rpm.
    #[arg(long)]
    speed_rpm: String,
    #[command(flatten)]
    model: ModelArgs,
    /// Each speed in its periodic steady state instead of one cycle from rest.
    #[arg(long)]
    steady: bool,
    #[command(flatten)]
    format: Format,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
}

/// Runs `loomkin dyn …`.
pub fn run(cmd: DynCommand) -> Result<()> {
    match cmd {
        DynCommand::Response(a) => response(a),
        DynCommand::Sweep(a) => sweep_cmd(a),
    }
}

/// Display units of a cycle: factor from SI, the position unit, and key suffixes.
struct Units {
    scale: f64,
    pos: &'static str,
    acc: &'static str,
}

fn units(cycle: &Cycle) -> Units {
    match cycle.unit {
        StrokeUnit::Mm => Units { scale: 1e3, pos: "mm", acc: "m_s2" },
        StrokeUnit::Deg => Units { scale: 180.0 / std::f64::consts::PI, pos: "deg", acc: "rad_s2" },
    }
}

fn read_cycle(path: &Path) -> Result<Cycle> {
    let text = util::read_input(path)?;
    Cycle::from_toml(&text).with_context(|| path.display().to_string())
}

fn speed_of(flag: Option<f64>, cycle: &Cycle) -> Result<ShaftSpeed> {
    Ok(ShaftSpeed::from_rpm(flag.or(cycle.speed_rpm).unwrap_or(300.0))?)
}

fn summary_json(s: &Summary, u: &Units) -> serde_json::Value {
    let p = u.pos;
    let mut v = json!({
        format!("residual_amplitude_{p}"): s.residual_amplitude_si * u.scale,
        "residual_amplitude_pct_of_stroke": s.residual_pct_of_stroke,
        format!("peak_dynamic_error_{p}"): s.peak_dynamic_error.value * u.scale,
        "peak_dynamic_error_at_deg": s.peak_dynamic_error.angle_deg,
        format!("peak_acceleration_{}", u.acc): s.peak_acceleration.value,
        "peak_acceleration_at_deg": s.peak_acceleration.angle_deg,
        format!("peak_input_acceleration_{}", u.acc): s.peak_input_acceleration.value,
        "rigidity_ratio": s.rigidity_ratio,
        "rigidity_warning": s.rigidity_warning,
        "dwells": s.dwells.iter().map(|d| json!({
            "segment": d.segment, "cycle": d.cycle, "angle_deg": d.angle_deg,
            format!("residual_amplitude_{p}"): d.amplitude_si * u.scale,
        })).collect::<Vec<_>>(),
    });
    if let (Some(f), Some(c)) = (s.peak_force_n, s.min_contact_force_n) {
        v["peak_force_n"] = json!(f.value);
        v["peak_force_at_deg"] = json!(f.angle_deg);
        v["min_contact_force_n"] = json!(c.value);
        v["min_contact_force_at_deg"] = json!(c.angle_deg);
        v["loses_contact"] = json!(s.loses_contact);
    }
    v
}

fn rigidity_note(s: &Summary) {
    if s.rigidity_warning {
        output::warning(format!(
            "rigidity ratio f_n/f_shaft = {} is below 10 (VDI 2149 Blatt 1): the rigid-body law does not describe \
             the motion — read the elastic response",
            loomkin_units::compact(s.rigidity_ratio)
        ));
    }
}

fn response(a: ResponseArgs) -> Result<()> {
    let cycle = read_cycle(&a.file)?;
    let speed = speed_of(a.speed_rpm, &cycle)?;
    let follower = a.model.follower()?;
    if !(1..=10_000).contains(&a.cycles) {
        anyhow::bail!("cycles = {} is out of range: allowed 1 ≤ cycles ≤ 10000", a.cycles);
    }
    if !(2..=1_000_000).contains(&a.points) {
        anyhow::bail!("points = {} is out of range: allowed 2 ≤ points ≤ 1000000", a.points);
    }
    let start = if a.steady { Start::Steady } else { Start::Rest };
    let r = Response::new(&cycle, speed, &follower, start, a.cycles)?;
    let u = units(&cycle);
    let summary = r.summary();
    rigidity_note(&summary);
    if a.format.csv {
        let p = u.pos;
        let mut t = Table::new([
            "angle_deg".to_string(),
            format!("s_{p}"),
            format!("x_{p}"),
            format!("error_{p}"),
            format!("a_{}", u.acc),
        ]);
        for s in r.samples(a.points) {
            t.push(vec![s[0], s[1] * u.scale, s[2] * u.scale, s[3] * u.scale, s[4]])?;
        }
        return output::csv(&t);
    }
    if a.format.json {
        let mut v = summary_json(&summary, &u);
        v["speed_rpm"] = json!(speed.rpm());
        v["natural_hz"] = json!(follower.natural_hz());
        v["damping_ratio"] = json!(follower.damping_ratio());
        v["start"] = json!(if a.steady { "steady" } else { "rest" });
        v["cycles"] = json!(if a.steady { 1 } else { a.cycles });
        return output::json(&v);
    }
    if let Some(out) = a.output {
        let samples = r.samples(a.points);
        let col = |i: usize, k: f64| samples.iter().map(|s| (s[0], s[i] * k)).collect::<Vec<_>>();
        let acc_in: Vec<(f64, f64)> = {
            let total = r.duration_s();
            let n = samples.len();
            (0..n)
                .map(|i| {
                    let t = total * i as f64 / (n - 1) as f64;
                    (r.angle_deg(t), r.state(t)[2])
                })
                .collect()
        };
        let acc_unit = if u.pos == "mm" { "m/s²" } else { "rad/s²" };
        let panels = vec![
            Panel::new(
                format!("position [{}]", u.pos),
                vec![
                    Series::line("input s", col(1, u.scale)),
                    Series::line("follower x", col(2, u.scale)).with_dashes(),
                ],
            ),
            Panel::new(format!("dynamic error x − s [{}]", u.pos), vec![Series::line("x − s", col(3, u.scale))]),
            Panel::new(
                format!("acceleration [{acc_unit}]"),
                vec![Series::line("input s''", acc_in), Series::line("follower x''", col(4, 1.0))],
            ),
        ];
        let title = format!(
            "{} at {} rpm, f_n {} Hz, ζ {}{}: residual {:.4} {} ({:.3} % of stroke)",
            a.file.display(),
            loomkin_units::compact(speed.rpm()),
            loomkin_units::compact(follower.natural_hz()),
            loomkin_units::compact(follower.damping_ratio()),
            if a.steady { ", steady state" } else { "" },
            summary.residual_amplitude_si * u.scale,
            u.pos,
            summary.residual_pct_of_stroke,
        );
        return output::figure(&Figure::new(title, "main-shaft angle [deg]", panels), &out);
    }
    let p = u.pos;
    outln!(
        "{} at {} rpm, f_n = {} Hz, ζ = {}, {}",
        a.file.display(),
        loomkin_units::compact(speed.rpm()),
        loomkin_units::compact(follower.natural_hz()),
        loomkin_units::compact(follower.damping_ratio()),
        if a.steady { "periodic steady state".to_string() } else { format!("{} cycle(s) from rest", a.cycles) }
    )?;
    outln!(
        "residual vibration (largest over the dwells): {:.6} {p} = {:.4} % of stroke",
        summary.residual_amplitude_si * u.scale,
        summary.residual_pct_of_stroke
    )?;
    for d in &summary.dwells {
        outln!("  dwell at {:>9.3}°: {:.6} {p}", d.angle_deg, d.amplitude_si * u.scale)?;
    }
    outln!(
        "peak dynamic error |x − s|: {:.6} {p} at {:.3}°",
        summary.peak_dynamic_error.value * u.scale,
        summary.peak_dynamic_error.angle_deg
    )?;
    outln!(
        "peak acceleration |x''|: {:.4} {} at {:.3}° (input |s''| {:.4})",
        summary.peak_acceleration.value,
        u.acc.replace('_', "/").replace("s2", "s²"),
        summary.peak_acceleration.angle_deg,
        summary.peak_input_acceleration.value
    )?;
    if let (Some(f), Some(c)) = (summary.peak_force_n, summary.min_contact_force_n) {
        outln!("peak train force |F|: {:.3} N at {:.3}°", f.value, f.angle_deg)?;
        outln!(
            "smallest contact force: {:.3} N at {:.3}°{}",
            c.value,
            c.angle_deg,
            if summary.loses_contact { " — a force-closed follower LOSES CONTACT" } else { "" }
        )?;
    }
    outln!("rigidity ratio f_n/f_shaft (VDI 2149): {:.3}", summary.rigidity_ratio)?;
    Ok(())
}

fn sweep_cmd(a: SweepArgs) -> Result<()> {
    let cycle = read_cycle(&a.file)?;
    let follower = a.model.follower()?;
    let span = Span::parse("speed_rpm", &a.speed_rpm, ShaftSpeed::RANGE)?;
    if span.count() > 10_000_000 {
        anyhow::bail!("speed_rpm: {} speeds is too many: allowed at most 10000000", span.count());
    }
    let speeds: Vec<f64> = span.values().collect();
    let start = if a.steady { Start::Steady } else { Start::Rest };
    let pts = sweep(&cycle, &follower, &speeds, start)?;
    let u = units(&cycle);
    let p = u.pos;
    let forces = follower.mass_kg().is_some();
    let mut cols = vec![
        "speed_rpm".to_string(),
        format!("residual_amplitude_{p}"),
        "residual_amplitude_pct_of_stroke".into(),
        format!("peak_dynamic_error_{p}"),
        "rigidity_ratio".into(),
    ];
    if forces {
        cols.push("peak_force_n".into());
        cols.push("min_contact_force_n".into());
    }
    let row = |q: &loomkin_dynamics::SweepPoint| {
        let mut r = vec![
            q.speed_rpm,
            q.residual_amplitude_si * u.scale,
            q.residual_pct_of_stroke,
            q.peak_dynamic_error_si * u.scale,
            q.rigidity_ratio,
        ];
        if forces {
            r.push(q.peak_force_n.unwrap_or(0.0));
            r.push(q.min_contact_force_n.unwrap_or(0.0));
        }
        r
    };
    let mut t = Table::new(cols);
    for q in &pts {
        t.push(row(q))?;
    }
    if a.format.csv {
        return output::csv(&t);
    }
    if a.format.json {
        return output::json(&json!({
            "natural_hz": follower.natural_hz(),
            "damping_ratio": follower.damping_ratio(),
            "start": if a.steady { "steady" } else { "rest" },
            "points": t.to_json_rows(),
        }));
    }
    if let Some(out) = a.output {
        let col = |f: &dyn Fn(&loomkin_dynamics::SweepPoint) -> f64| {
            pts.iter().map(|q| (q.speed_rpm, f(q))).collect::<Vec<_>>()
        };
        let mut panels = vec![
            Panel::new(
                format!("residual amplitude [{p}]"),
                vec![Series::line("", col(&|q| q.residual_amplitude_si * u.scale))],
            ),
            Panel::new(
                format!("peak |x − s| [{p}]"),
                vec![Series::line("", col(&|q| q.peak_dynamic_error_si * u.scale))],
            ),
        ];
        if forces {
            panels.push(Panel::new(
                "train force [N]",
                vec![
                    Series::line("peak |F|", col(&|q| q.peak_force_n.unwrap_or(0.0))),
                    Series::line("smallest contact force", col(&|q| q.min_contact_force_n.unwrap_or(0.0)))
                        .with_dashes(),
                ],
            ));
        }
        let title = format!(
            "{}: f_n {} Hz, ζ {}{}",
            a.file.display(),
            loomkin_units::compact(follower.natural_hz()),
            loomkin_units::compact(follower.damping_ratio()),
            if a.steady { ", steady state" } else { ", one cycle from rest" }
        );
        return output::figure(&Figure::new(title, "main-shaft speed [rpm]", panels), &out);
    }
    let worst = pts.iter().max_by(|x, y| x.residual_amplitude_si.total_cmp(&y.residual_amplitude_si));
    outln!(
        "{} speeds, {} to {} rpm",
        pts.len(),
        loomkin_units::compact(speeds[0]),
        loomkin_units::compact(speeds[speeds.len() - 1])
    )?;
    if let Some(w) = worst {
        outln!(
            "largest residual vibration {:.6} {p} ({:.4} % of stroke) at {} rpm",
            w.residual_amplitude_si * u.scale,
            w.residual_pct_of_stroke,
            loomkin_units::compact(w.speed_rpm)
        )?;
    }
    outln!("(--csv, --json or -o PLOT for the whole sweep)")?;
    Ok(())
}
