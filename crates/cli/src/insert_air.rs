//! `loomkin insert projectile` and `loomkin insert airjet`: the carriers that fly freely.

use crate::insert::CarrierRun;
use crate::loom::PatternArgs;
use crate::output::outln;
use anyhow::Result;
use clap::Args;
use loomkin_loom::insertion_air;
use std::path::PathBuf;

/// `loomkin insert projectile`.
#[derive(Debug, Args)]
pub struct ProjectileArgs {
    /// The loom file (TOML) with `[insertion] kind = "projectile"` and its `[insertion.projectile]`.
    loom: PathBuf,
    /// The pattern whose every pick the clearance covers (default: plain weave on the loom's frames).
    #[command(flatten)]
    pattern: PatternArgs,
    /// Main-shaft speed in rpm (default: the loom file's `speed_rpm`).
    #[arg(long)]
    speed_rpm: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Plot the head across the reed, its speed and the worst pick's clearance (.svg or .png).
    #[arg(short, long, conflicts_with = "json")]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

pub(crate) fn run_projectile(a: ProjectileArgs) -> Result<()> {
    let run = CarrierRun { loom_path: &a.loom, output: a.output.as_ref(), plot: &a.plot, json: a.json };
    let (loom, pattern, speed) = run.read(&a.pattern, a.speed_rpm)?;
    let c = insertion_air::projectile_check(&loom, &pattern, speed).map_err(|e| run.named(e))?;
    if run.plot_or_json(&c, || insertion_air::projectile_figure(&loom, &pattern, &c, speed))? {
        return Ok(());
    }
    let r = &c.projectile;
    outln!(
        "projectile at {} rpm: bar {:.3} N·m/rad stores {:.3} J; launched at {:.3} m/s ({:.3} J) at {:.3}°",
        r.speed_rpm,
        r.bar_stiffness_n_m_per_rad,
        r.stored_energy_j,
        r.projectile_speed_m_s,
        r.launch_energy_j,
        r.launch_deg
    )?;
    outln!(
        "flight {:.3} mm in {:.3} ms: in the shed from {:.3}° to {:.3}° (mean {:.3} m/s), into the brake at {:.3}° \
         and {:.3} m/s (friction took {:.4} J, air drag {:.4} J)",
        r.flight_distance_mm,
        r.flight_time_ms,
        r.shed_entry_deg,
        r.shed_exit_deg,
        r.mean_speed_in_shed_m_s,
        r.arrival_deg,
        r.arrival_speed_m_s,
        r.friction_energy_j,
        r.drag_energy_j
    )?;
    outln!(
        "brake: {:.1} N over {} mm, {:.3} J in {:.3} ms",
        r.brake_force_n,
        loomkin_units::compact(r.brake_mm),
        r.brake_energy_j,
        r.brake_time_ms
    )?;
    if let Some(d) = &c.dwell {
        outln!(
            "sley back dwell {:.3}° to {:.3}° (within {} mm): the flight in the shed {}",
            d.sley_back_dwell_deg[0],
            d.sley_back_dwell_deg[1],
            loomkin_units::compact(d.dwell_tolerance_mm),
            if d.fits_sley_dwell { "fits in it" } else { "does not fit in it" }
        )?;
    }
    let cl = &c.clearance;
    outln!(
        "least clearance {:.3} mm at pick {} of {}, {:.3}°, {:.1} mm from the entering selvedge{}",
        cl.min_clearance_mm,
        cl.worst_pick,
        c.picks,
        cl.worst_angle_deg,
        cl.worst_position_mm,
        if cl.min_clearance_mm < 0.0 { ": the guide teeth touch the warp" } else { "" }
    )
}

/// `loomkin insert airjet`.
#[derive(Debug, Args)]
pub struct AirjetArgs {
    /// The loom file (TOML) with `[insertion] kind = "airjet"` and its `[insertion.airjet]`.
    loom: PathBuf,
    /// Main-shaft speed in rpm (default: the loom file's `speed_rpm`).
    #[arg(long)]
    speed_rpm: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Plot the tip across the reed and its speed with the relay groups' openings (.svg or .png).
    #[arg(short, long, conflicts_with = "json")]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

pub(crate) fn run_airjet(a: AirjetArgs) -> Result<()> {
    let run = CarrierRun { loom_path: &a.loom, output: a.output.as_ref(), plot: &a.plot, json: a.json };
    let (loom, speed) = run.read_without_pattern(a.speed_rpm)?;
    let r = insertion_air::airjet_check(&loom, speed).map_err(|e| run.named(e))?;
    if run.plot_or_json(&r, || insertion_air::airjet_figure(&loom, &r, speed))? {
        return Ok(());
    }
    outln!(
        "air jet at {} rpm: launched at {:.3}°, the tip enters the reed at {:.3}° and reaches the far selvedge at \
         {:.3}° after {:.3} ms at {:.3} m/s (peak {:.3} m/s)",
        r.speed_rpm,
        r.launch_deg,
        r.reed_entry_deg,
        r.arrival_deg,
        r.flight_time_ms,
        r.tip_speed_at_exit_m_s,
        r.peak_tip_speed_m_s
    )?;
    outln!(
        "relay plan: {} of {} groups open {:.3} ms ({:.3}°) in all",
        r.relay_plan.len(),
        r.groups,
        r.relay_open_ms,
        r.relay_open_deg
    )?;
    for o in &r.relay_plan {
        outln!("  group {:>3}: open {:.3}° to {:.3}°", o.group, o.open_deg, o.close_deg)?;
    }
    Ok(())
}
