//! `loomkin servo check`: a servo axis (motor and load from a TOML file) moving a cycle.

use crate::output::Out;
use crate::{output, util};
use anyhow::Result;
use clap::Args;
use loomkin_plot::{Dash, Figure, Legend, Note, Panel, Rule, Series, sig4};
use loomkin_servo::{Axis, check_axis, envelope_lines, operating_points};
use std::path::PathBuf;

/// `servo check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The axis file: `[motor]` (rated_torque_nm, peak_torque_nm, rated_speed_rpm, max_speed_rpm,
    /// rotor_inertia_kg_m2), `[load]` (moving_mass_kg and travel_mm_per_rev, or load_inertia_kg_m2 and
    /// gear_ratio; efficiency, friction_n, viscous_n_s_m, spring_n_m, constant_force_n,
    /// extra_inertia_kg_m2), optional `[load.crank_lever]` in place of travel_mm_per_rev (a crank and
    /// lever: crank_radius_mm, rod_length_mm, lever_input_arm_mm, lever_output_arm_mm,
    /// rocking_shaft_x_mm, rocking_shaft_y_mm, …; docs/servo-shedding.md), optional `[limits]`
    /// (max_inertia_ratio).
    axis: PathBuf,
    /// The cycle the axis moves (TOML cycle file).
    #[arg(long, required_unless_present = "law", conflicts_with = "law")]
    cycle: Option<PathBuf>,
    // Or a catalogue law: rise over --motion-deg, dwell, return, dwell over one turn.
    #[command(flatten)]
    rise: util::RiseArgs,
    #[arg(
        long,
        allow_hyphen_values = true,
        help = util::speed_help("Main-shaft speed in rpm (left out: the cycle file's, else the default)")
    )]
    speed_rpm: Option<f64>,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
    /// Plot the torque–speed operating points against the motor envelope (.svg or .png).
    #[arg(short, long)]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// Runs `servo check`.
pub fn run(a: CheckArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let (cycle, _) = a.rise.cycle(a.cycle.as_deref())?;
    let text = util::read_input(&a.axis)?;
    let axis = Axis::from_toml(&text, cycle.unit).map_err(|e| anyhow::anyhow!("{}: {e}", a.axis.display()))?;
    let rpm = cycle.speed_rpm_or(a.speed_rpm);
    let r = check_axis(&axis, &cycle, rpm)?;
    if let Some(path) = &a.output {
        let pts = operating_points(&axis, &cycle, rpm, 1441)?;
        let (s1, peak) = envelope_lines(&axis);
        let mirror = |l: &[(f64, f64)], sx: f64, sy: f64| l.iter().map(|&(n, t)| (sx * n, sy * t)).collect::<Vec<_>>();
        let mut series = vec![Series::line(
            "operating points over the cycle",
            pts.iter().map(|p| (p.motor_speed_rpm, p.torque_nm)).collect(),
        )];
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            let first = sx > 0.0 && sy > 0.0;
            series.push(
                Series::line(if first { "peak torque line" } else { "" }, mirror(&peak, sx, sy))
                    .with_color([200, 30, 30]),
            );
            series.push(
                Series::line(if first { "rated (S1) torque" } else { "" }, mirror(&s1, sx, sy))
                    .with_color([30, 120, 30])
                    .with_dashes(),
            );
        }
        let title = format!(
            "servo check at {rpm} rpm: peak {:.3} N·m, RMS {:.3} N·m, inertia ratio {:.2} — {}",
            r.peak_torque_nm,
            r.rms_torque_nm,
            r.inertia_ratio,
            if r.pass { "pass" } else { "FAIL" }
        );
        // The peak torque at the operating point where the check located it, and the RMS torque
        // against the rated (S1) torque it is judged by.
        let at = loomkin_servo::operating_point_at(&axis, &cycle, rpm, r.peak_torque_at_deg)?;
        let panel = Panel::new("motor torque [N·m]", series)
            .with_legend(Legend::Auto)
            .with_notes([Note::new(
                at.motor_speed_rpm,
                at.torque_nm,
                format!("peak {} N·m at {}°", sig4(at.torque_nm), sig4(r.peak_torque_at_deg)),
            )])
            .with_rule(
                Rule::y(r.rms_torque_nm, format!("RMS torque {} N·m", sig4(r.rms_torque_nm)))
                    .with_color([30, 120, 30])
                    .with_dash(Dash::Dotted),
            );
        let fig = Figure::new(title, "motor speed [rpm]", vec![panel]);
        output::figure(&fig, path, &a.plot)?;
    }
    if a.json {
        return output::json(&r);
    }
    if a.output.is_some() {
        return Ok(());
    }
    output::line(format_args!(
        "servo axis {} at {rpm} rpm (cycle {:.6} s): {}",
        a.axis.display(),
        r.cycle_time_s,
        if r.pass { "PASS" } else { "FAIL" }
    ))?;
    output::line(format_args!("  peak torque      {:>12.4} N·m at {:.3} deg", r.peak_torque_nm, r.peak_torque_at_deg))?;
    output::line(format_args!("  RMS torque       {:>12.4} N·m", r.rms_torque_nm))?;
    output::line(format_args!(
        "  peak motor speed {:>12.2} rpm at {:.3} deg",
        r.peak_motor_speed_rpm, r.peak_motor_speed_at_deg
    ))?;
    output::line(format_args!(
        "  envelope ratio   {:>12.4} (|T| over the peak-torque line) at {:.3} deg",
        r.envelope_ratio, r.envelope_ratio_at_deg
    ))?;
    output::line(format_args!("  inertia ratio    {:>12.4}", r.inertia_ratio))?;
    output::line(format_args!("  {:<22} {:>16} {:>16} {:>9}  verdict", "check", "value", "limit", "margin"))?;
    for c in &r.checks {
        let unit = if c.unit.is_empty() { String::new() } else { format!(" {}", c.unit) };
        output::line(format_args!(
            "  {:<22} {:>16} {:>16} {:>8.1}%  {}",
            c.name,
            format!("{:.4}{unit}", c.value),
            format!("{:.4}{unit}", c.limit),
            100.0 * c.margin,
            if c.pass { "pass" } else { "FAIL" }
        ))?;
    }
    Ok(())
}
