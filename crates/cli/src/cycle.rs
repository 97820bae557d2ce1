//! `loomkin cycle FILE.toml`: a machine cycle in physical units.

use crate::output::{self, outln};
use crate::util::{self, Format};
use anyhow::{Result, bail};
use clap::Args;
use loomkin_io::Table;
use loomkin_io::plot::{Figure, Panel, Series};
use loomkin_laws::{Cycle, SegmentKind, StrokeUnit};
use loomkin_units::ShaftSpeed;
use serde_json::{Value, json};
use std::path::PathBuf;

/// `loomkin cycle`.
#[derive(Debug, Args)]
pub struct CycleArgs {
    /// The cycle file (TOML: `unit`, `stroke`, `[[segment]]` tables).
    file: PathBuf,
    /// Main-shaft speed in rpm (overrides the file's `speed_rpm`; default 300).
    #[arg(long)]
    speed_rpm: Option<f64>,
    /// Number of samples over the cycle for CSV, JSON and plots.
    #[arg(long, default_value_t = 721)]
    points: usize,
    #[command(flatten)]
    format: Format,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
}

/// Runs `loomkin cycle`.
pub fn run(a: CycleArgs) -> Result<()> {
    let text = util::read_input(&a.file)?;
    let cycle = Cycle::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", a.file.display()))?;
    let rpm = a.speed_rpm.or(cycle.speed_rpm).unwrap_or(300.0);
    ShaftSpeed::from_rpm_field("--speed-rpm", rpm)?;
    if a.points < 2 || a.points > 10_000_000 {
        bail!("--points {} out of range: allowed 2 ≤ N ≤ 10000000", a.points);
    }
    let [pu, vu, au, ju] = cycle.unit.key_units();
    let samples = cycle.sample(a.points, rpm);
    if a.format.csv {
        let mut t = Table::new([
            "angle_deg".to_string(),
            "time_s".into(),
            format!("s_{pu}"),
            format!("v_{vu}"),
            format!("a_{au}"),
            format!("j_{ju}"),
        ]);
        for p in &samples {
            t.push(vec![p.angle_deg, p.time_s, p.kin.s, p.kin.v, p.kin.a, p.kin.j])?;
        }
        return output::csv(&t);
    }
    let summary = summarise(&cycle, rpm);
    if a.format.json {
        let pts: Vec<Value> = samples
            .iter()
            .map(|p| {
                json!({"angle_deg": p.angle_deg, "time_s": p.time_s, format!("s_{pu}"): p.kin.s, format!("v_{vu}"): p.kin.v,
                       format!("a_{au}"): p.kin.a, format!("j_{ju}"): p.kin.j})
            })
            .collect();
        return output::json(&json!({
            "speed_rpm": rpm,
            "period_deg": cycle.period_rad.to_degrees(),
            "cycle_time_s": cycle.period_rad / (rpm * std::f64::consts::TAU / 60.0),
            "unit": if cycle.unit == StrokeUnit::Mm { "m" } else { "rad" },
            "segments": summary,
            "samples": pts,
        }));
    }
    if let Some(out) = a.output {
        let [su, vs, as_, js] = cycle.unit.si_units();
        let col = |f: fn(&loomkin_laws::Kinematics) -> f64| {
            samples.iter().map(|p| (p.angle_deg, f(&p.kin))).collect::<Vec<_>>()
        };
        let panels = vec![
            Panel::new(format!("position [{su}]"), vec![Series::line("", col(|k| k.s))]),
            Panel::new(format!("velocity [{vs}]"), vec![Series::line("", col(|k| k.v))]),
            Panel::new(format!("acceleration [{as_}]"), vec![Series::line("", col(|k| k.a))]),
            Panel::new(format!("jerk [{js}]"), vec![Series::line("", col(|k| k.j))]),
        ];
        let title = format!("{} at {rpm} rpm", a.file.display());
        return output::figure(&Figure::new(title, "main-shaft angle [deg]", panels), &out);
    }
    let [su, vs, as_, _] = cycle.unit.si_units();
    outln!(
        "cycle {} at {rpm} rpm (one cycle {:.6} s)",
        a.file.display(),
        cycle.period_rad / (rpm * std::f64::consts::TAU / 60.0)
    )?;
    outln!(
        "{:>3} {:<7} {:>9} {:>9} {:<36} {:>12} {:>14} {:>14}",
        "#",
        "kind",
        "from[deg]",
        "to[deg]",
        "law",
        format!("stroke[{su}]"),
        format!("max|v|[{vs}]"),
        format!("max|a|[{as_}]")
    )?;
    let [pk, vk, ak, _] = cycle.unit.key_units();
    for (i, s) in summary.iter().enumerate() {
        outln!(
            "{:>3} {:<7} {:>9.3} {:>9.3} {:<36} {:>12.6} {:>14.6} {:>14.4}",
            i,
            s["kind"].as_str().unwrap_or(""),
            s["from_deg"].as_f64().unwrap_or(0.0),
            s["to_deg"].as_f64().unwrap_or(0.0),
            s["law"].as_str().unwrap_or("-"),
            s[format!("stroke_{pk}")].as_f64().unwrap_or(0.0),
            s[format!("peak_velocity_{vk}")].as_f64().unwrap_or(0.0),
            s[format!("peak_acceleration_{ak}")].as_f64().unwrap_or(0.0),
        )?;
    }
    Ok(())
}

/// Per-segment peaks from the laws' exact metrics and the chain rule.
fn summarise(cycle: &Cycle, rpm: f64) -> Vec<Value> {
    let [pu, vu, au, ju] = cycle.unit.key_units();
    let omega = rpm * std::f64::consts::TAU / 60.0;
    cycle
        .segments
        .iter()
        .map(|s| {
            let kind = match s.kind {
                SegmentKind::Dwell => "dwell",
                SegmentKind::Rise => "rise",
                SegmentKind::Return => "return",
            };
            let (law, pv, pa, pj) = match &s.law {
                Some((spec, law)) => {
                    let m = law.metrics();
                    let r = omega / s.length_rad;
                    let h = s.stroke_si.abs();
                    (json!(spec.label()), h * m.cv * r, h * m.ca * r * r, h * m.cj * r * r * r)
                }
                None => (json!("-"), 0.0, 0.0, 0.0),
            };
            json!({
                "kind": kind,
                "from_deg": s.start_rad.to_degrees(),
                "to_deg": (s.start_rad + s.length_rad).to_degrees(),
                "law": law,
                format!("stroke_{pu}"): s.stroke_si.abs(),
                format!("peak_velocity_{vu}"): pv,
                format!("peak_acceleration_{au}"): pa,
                format!("peak_jerk_{ju}"): pj,
            })
        })
        .collect()
}
