//! `loomkin loom servo`: electronic shedding — one servo per heald frame on a shared DC bus.

use crate::loom::PatternArgs;
use crate::output::{self, Out, outln};
use anyhow::Result;
use clap::Args;
use loomkin_cams::table::{Format, Spacing};
use std::path::{Path, PathBuf};

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
    /// Write one cam table per frame over the pattern repeat (frame-01.csv, …), the frames' cycle
    /// files where the repeat fits one, and manifest.json (the master axis, offsets, errors) to DIR.
    #[arg(long, value_name = "DIR")]
    emit_tables: Option<PathBuf>,
    /// The table formats, comma-separated or repeated, as `cam table --format` takes them (default:
    /// csv, xyvaj, poly5, twincat, st).
    #[arg(long, value_enum, ignore_case = true, value_delimiter = ',', requires = "emit_tables")]
    format: Vec<Format>,
    #[arg(long, value_name = "D", conflicts_with = "tolerance", requires = "emit_tables", allow_hyphen_values = true, help = crate::util::field_help("Table points on every joint of the law and every D degrees from each joint (a shorter last step before a joint)", &Spacing::STEP_DEG))]
    step_deg: Option<f64>,
    /// Table points on every joint and as few in between as keep the re-interpolation error within
    /// T mm (as `cam table --tolerance`).
    #[arg(long, value_name = "T", requires = "emit_tables", allow_hyphen_values = true)]
    tolerance: Option<f64>,
}

/// Runs `loomkin loom servo`.
pub fn run(a: ServoArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let spacing = table_spacing(&a)?;
    let (loom, pattern) = crate::loom::read(&a.loom, &a.pattern)?;
    let r = loomkin_loom::servo_study(&loom, &pattern)?;
    if let Some(out) = &a.output {
        output::figure(&loomkin_loom::servo_figure(&loom, &pattern, &r)?, out, &a.plot)?;
    }
    if let Some(dir) = &a.emit_tables {
        emit_tables(&loom, &pattern, dir, spacing, &a.format)?;
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

/// The tables' spacing, checked before anything is computed; and `--emit-tables` must name a
/// folder (or nothing yet).
fn table_spacing(a: &ServoArgs) -> Result<Spacing> {
    let step = a.step_deg.map(|s| Spacing::STEP_DEG.check_as("--step-deg", s)).transpose()?;
    let tolerance = a.tolerance.map(|t| Spacing::TOLERANCE.check_as("--tolerance", t)).transpose()?;
    if let Some(dir) = &a.emit_tables
        && dir.exists()
        && !dir.is_dir()
    {
        let cause = std::io::Error::new(std::io::ErrorKind::NotADirectory, "it is not a folder");
        return Err(output::WriteError::file(&dir.display().to_string(), cause).into());
    }
    Ok(Spacing::of(step, tolerance))
}

/// `--emit-tables DIR`: every file of [`loomkin_loom::servo_tables`] into `dir`.
fn emit_tables(
    loom: &loomkin_loom::Loom,
    pattern: &loomkin_loom::Pattern,
    dir: &Path,
    spacing: Spacing,
    formats: &[Format],
) -> Result<()> {
    let tables = loomkin_loom::servo_tables(loom, pattern, spacing, formats)?;
    std::fs::create_dir_all(dir).map_err(|e| output::WriteError::file(&dir.display().to_string(), e))?;
    for f in &tables.files {
        let path = dir.join(&f.name);
        std::fs::write(&path, &f.text).map_err(|e| output::WriteError::file(&path.display().to_string(), e))?;
    }
    let m = &tables.manifest;
    let worst = m.frames.iter().flat_map(|f| &f.tables).map(|t| t.report.error.max_position_error).fold(0.0, f64::max);
    output::note(format_args!(
        "wrote {} files to {}: {} frames' cam tables over a master axis of {}° ({} picks) and {}; worst re-interpolation error {} mm",
        tables.files.len(),
        dir.display(),
        m.frames.len(),
        loomkin_units::compact(m.master_axis_deg),
        m.picks,
        loomkin_eshed::MANIFEST_FILE,
        loomkin_units::compact(worst)
    ));
    Ok(())
}
