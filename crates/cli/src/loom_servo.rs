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
    /// Search every frame's stagger (within ±shedding.max_stagger_deg) and motion angle for the
    /// least peak bus power (or `--objective rms`: the worst frame's RMS torque), keeping the
    /// carrier's insertion clear in every pick; report the gain and what it cost in window and
    /// clearance; the plot and `--emit-tables` then show the optimised plans.
    #[arg(long)]
    optimize: bool,
    /// What `--optimize` minimises (the names of `loom stagger --objective`).
    #[arg(long, value_enum, default_value = "peak", requires = "optimize")]
    objective: ObjectiveArg,
    #[arg(
        long,
        value_name = "MM",
        requires = "optimize",
        default_value_t = loomkin_loom::StaggerOptions::MIN_CLEARANCE_MM.default_value(),
        help = crate::util::field_help(
            "Least clearance to the carrier that --optimize keeps in every pick from entry to exit (the design's own when it keeps less), mm",
            &loomkin_loom::StaggerOptions::MIN_CLEARANCE_MM
        )
    )]
    min_clearance_mm: f64,
}

/// What `--optimize` minimises.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
enum ObjectiveArg {
    /// The peak bus power.
    Peak,
    /// The worst frame's RMS motor torque.
    Rms,
}

impl From<ObjectiveArg> for loomkin_loom::Objective {
    fn from(a: ObjectiveArg) -> Self {
        match a {
            ObjectiveArg::Peak => Self::Peak,
            ObjectiveArg::Rms => Self::Rms,
        }
    }
}

/// Runs `loomkin loom servo`.
pub fn run(a: ServoArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let spacing = table_spacing(&a)?;
    let options = loomkin_loom::ServoOptions {
        objective: a.objective.into(),
        min_clearance_mm: loomkin_loom::StaggerOptions::MIN_CLEARANCE_MM
            .check_as("--min-clearance-mm", a.min_clearance_mm)?,
    };
    let (loom, pattern) = crate::loom::read(&a.loom, &a.pattern)?;
    // A refusal of the loom file found while the plans are studied (a rest transition less smooth
    // than C², a crank and lever's dead centre, a carrier taller than the shed) names the file, as
    // the refusals found while it is read do.
    let in_file = crate::loom::in_file(&a.loom);
    let optimum = if a.optimize {
        let bar = crate::util::Progress::new(0, "servo search");
        let o = loomkin_loom::optimise_servo_with(&loom, &pattern, &options, &Default::default(), &|done, all| {
            bar.set_length(all as u64);
            bar.set(done as u64);
        })
        .map_err(in_file)?;
        bar.finish();
        Some(o)
    } else {
        None
    };
    let (r, setups) = match &optimum {
        Some(o) => (o.report.clone(), o.setups.clone()),
        None => {
            let setups = loomkin_loom::servo_setups(&loom, &pattern, None, None).map_err(in_file)?;
            (loomkin_loom::servo_study_of(&loom, &pattern, &setups).map_err(in_file)?, setups)
        }
    };
    if let Some(out) = &a.output {
        output::figure(&loomkin_loom::servo_figure_of(&loom, &setups, &r).map_err(in_file)?, out, &a.plot)?;
    }
    if let Some(dir) = &a.emit_tables {
        emit_tables(&loom, &setups, dir, spacing, &a.format)?;
    }
    if a.json {
        return match &optimum {
            Some(o) => output::json(o),
            None => output::json(&r),
        };
    }
    if let Some(o) = &optimum {
        let what = match o.objective {
            loomkin_loom::Objective::Peak => "the peak bus power",
            loomkin_loom::Objective::Rms => "the worst frame's RMS torque",
        };
        outln!(
            "optimised for {what} ({} evaluations, {} clearance checks; {} moving frames, {} picks standing for the repeat's {}):",
            o.evaluations,
            o.clearance_checks,
            o.frames_searched,
            o.picks_searched,
            o.report.picks
        )?;
        outln!(
            "  peak bus power {:.1} W -> {:.1} W; worst RMS torque {:.3} -> {:.3} N·m",
            o.peak_bus_power_w_before,
            o.peak_bus_power_w_after,
            o.worst_rms_torque_n_m_before,
            o.worst_rms_torque_n_m_after
        )?;
        outln!(
            "  clear-shed window {:.2}° -> {:.2}°; least clearance {:.2} -> {:.2} mm (kept at least {} mm)",
            o.window_deg_before,
            o.window_deg_after,
            o.min_clearance_mm_before,
            o.min_clearance_mm_after,
            loomkin_units::compact(o.min_clearance_kept_mm)
        )?;
        let list = |v: &[f64]| v.iter().map(|&x| loomkin_units::compact(x)).collect::<Vec<_>>().join(", ");
        outln!("  stagger [deg], front frame first: {}", list(&o.stagger_deg))?;
        match &o.fall_motion_deg {
            Some(fall) => {
                outln!("  motion angle up [deg], front frame first: {}", list(&o.motion_deg))?;
                outln!("  motion angle down [deg], front frame first: {}", list(fall))?;
            }
            None => outln!("  motion angle [deg], front frame first: {}", list(&o.motion_deg))?,
        }
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
    if let Some(c) = &r.clear_shed {
        outln!(
            "shed clears the carrier from {:.2}° to {:.2}° in every pick ({:.2}°); insertion {:.2}° to {:.2}°, least clearance {:.2} mm; highest loom speed {:.1} rpm",
            c.window_open_deg,
            c.window_close_deg,
            c.window_deg,
            loom.insertion.entry_deg,
            loom.insertion.exit_deg,
            c.min_clearance_mm,
            c.max_speed_rpm
        )?;
        crate::loom::warn_interference(c.min_clearance_mm);
    }
    // Each run of frames that move alike: the laws and motion angles by kind of move.
    let moves: Vec<String> = setups.iter().map(|s| s.laws.describe(s.plan.motion_deg)).collect();
    let mut first = 0;
    for i in 1..=moves.len() {
        if i == moves.len() || moves[i] != moves[first] {
            let frames =
                if i - first == 1 { format!("frame {}", first + 1) } else { format!("frames {}–{i}", first + 1) };
            outln!("{} {frames}: {}", if first == 0 { "moves:" } else { "      " }, moves[first])?;
            first = i;
        }
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

/// `--emit-tables DIR`: every file of [`loomkin_loom::servo_tables_of`] the plans into `dir`.
fn emit_tables(
    loom: &loomkin_loom::Loom,
    setups: &[loomkin_eshed::FrameSetup],
    dir: &Path,
    spacing: Spacing,
    formats: &[Format],
) -> Result<()> {
    let tables = loomkin_loom::servo_tables_of(loom, setups, spacing, formats)?;
    std::fs::create_dir_all(dir).map_err(|e| output::WriteError::file(&dir.display().to_string(), e))?;
    for f in &tables.files {
        let path = dir.join(&f.name);
        std::fs::write(&path, &f.text).map_err(|e| output::WriteError::file(&path.display().to_string(), e))?;
    }
    let m = &tables.manifest;
    // The worst error per slave unit (a crank-and-lever frame's tables are in motor degrees).
    let worst_in = |unit: Option<&str>| {
        m.frames
            .iter()
            .filter(|f| f.slave_unit == unit)
            .flat_map(|f| &f.tables)
            .map(|t| t.report.error.max_position_error)
            .fold(0.0, f64::max)
    };
    let worst = match m.slave_unit {
        "mm" => format!("{} mm", loomkin_units::compact(worst_in(None))),
        "deg" => format!("{} deg", loomkin_units::compact(worst_in(Some("deg")))),
        _ => format!(
            "{} mm (linear drives), {} deg (cranks and levers)",
            loomkin_units::compact(worst_in(None)),
            loomkin_units::compact(worst_in(Some("deg")))
        ),
    };
    output::note(format_args!(
        "wrote {} files to {}: {} frames' cam tables over a master axis of {}° ({} picks) and {}; worst re-interpolation error {}",
        tables.files.len(),
        dir.display(),
        m.frames.len(),
        loomkin_units::compact(m.master_axis_deg),
        m.picks,
        loomkin_eshed::MANIFEST_FILE,
        worst
    ));
    Ok(())
}
