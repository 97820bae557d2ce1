//! `loomkin cycle FILE.toml`: a machine cycle in physical units.

use crate::output::{self, outln};
use crate::util::{self, Format};
use anyhow::{Result, bail};
use clap::Args;
use loomkin_io::Table;
use loomkin_io::plot::{Figure, Panel, Series};
use loomkin_laws::Cycle;
use loomkin_units::ShaftSpeed;
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
    let speed = ShaftSpeed::from_rpm_field("--speed-rpm", rpm)?;
    if a.points < 2 || a.points > 10_000_000 {
        bail!("--points {} out of range: allowed 2 ≤ N ≤ 10000000", a.points);
    }
    let [pu, vu, au, ju] = cycle.unit.key_units();
    if a.format.json {
        return output::json(&cycle.report(speed, a.points));
    }
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
    for (i, s) in cycle.segment_peaks(speed).iter().enumerate() {
        outln!(
            "{:>3} {:<7} {:>9.3} {:>9.3} {:<36} {:>12.6} {:>14.6} {:>14.4}",
            i,
            s.kind.name(),
            s.from_deg,
            s.to_deg,
            s.law.as_deref().unwrap_or("-"),
            s.stroke,
            s.peak_velocity,
            s.peak_acceleration,
        )?;
    }
    Ok(())
}
