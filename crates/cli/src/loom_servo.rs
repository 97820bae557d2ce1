//! `loomkin loom servo`: electronic shedding — one servo per heald frame on a shared DC bus.

use crate::loom::PatternArgs;
use crate::output::{self, Out, outln};
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

/// `loomkin loom servo`.
#[derive(Debug, Args)]
pub struct ServoArgs {
    /// The loom file (TOML) with `[shedding] drive = "servo"` and `[shedding.servo]`.
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    /// Print JSON (the `frames` list in shaft order, front first).
    #[arg(long)]
    json: bool,
    /// Plot every frame's motor torque and the bus power to this file (.svg or .png).
    #[arg(short, long)]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// Runs `loomkin loom servo`.
pub fn run(a: ServoArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let (loom, pattern) = crate::loom::read(&a.loom, &a.pattern)?;
    let r = loomkin_loom::servo_study(&loom, &pattern)?;
    if let Some(out) = &a.output {
        output::figure(&loomkin_loom::servo_figure(&loom, &pattern, &r)?, out, &a.plot)?;
    }
    if a.json {
        return output::json(&r);
    }
    outln!(
        "{} frames on one bus at {} rpm, {} picks ({} s a repeat){}",
        r.frames.len(),
        r.speed_rpm,
        r.picks,
        loomkin_plot::sig4(r.repeat_s),
        if r.pass_through { ", consecutive changes without a stop" } else { "" }
    )?;
    outln!(
        "bus: peak {:.1} W at {:.2}° ({:.2} A), mean {:.1} W; regenerated {:.3} J, to the braking resistor {:.3} J per repeat (peak {:.1} W)",
        r.peak_bus_power_w,
        r.peak_bus_power_at_deg,
        r.peak_bus_current_a,
        r.mean_bus_power_w,
        r.regenerated_energy_j,
        r.braking_energy_j,
        r.peak_braking_power_w
    )?;
    if let (Some(max), Some(ok)) = (r.braking_resistor_max_w, r.braking_resistor_ok) {
        outln!("braking resistor takes up to {:.1} W: {}", max, if ok { "enough" } else { "TOO SMALL" })?;
    }
    outln!(
        "{:>5} {:>6} {:>12} {:>12} {:>12} {:>12} {:>12} {:>6} {:>9}",
        "frame",
        "moves",
        "peak[N·m]",
        "RMS[N·m]",
        "speed[rpm]",
        "power[W]",
        "energy[J]",
        "motor",
        "min margin"
    )?;
    for f in &r.frames {
        let worst = f.checks.iter().min_by(|x, y| x.margin.total_cmp(&y.margin));
        outln!(
            "{:>5} {:>6} {:>12.3} {:>12.3} {:>12.1} {:>12.1} {:>12.4} {:>6} {:>9}",
            f.frame,
            f.moves,
            f.peak_torque_n_m,
            f.rms_torque_n_m,
            f.peak_speed_rpm,
            f.peak_power_w,
            f.energy_j,
            if f.motor_ok { "ok" } else { "FAILS" },
            worst.map_or(String::new(), |c| format!("{:.1}% {}", 100.0 * c.margin, c.name))
        )?;
    }
    if !r.motors_ok {
        output::warning("a frame's motor fails the servo check (see its margins; `--json` lists every check)");
    }
    Ok(())
}
