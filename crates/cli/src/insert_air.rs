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
