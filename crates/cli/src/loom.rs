//! `loomkin loom …`: the whole loom — pattern, shed geometry, shedding torque, stagger, timing.

use crate::output::{self, Out, outln};
use crate::util::{self, Format};
use anyhow::{Result, anyhow};
use clap::{Args, Subcommand, ValueEnum};
use loomkin_loom::{
    Drive, Loom, Motion, Objective, Pattern, StaggerOptions, check_with, optimise_stagger_with, timing_diagram,
    torque_figure,
};
use std::path::{Path, PathBuf};

/// `loomkin loom`.
#[derive(Debug, Subcommand)]
pub enum LoomCommand {
    /// Geometry per frame, peak and RMS shedding torque, clearance, window and highest speed.
    Check(CheckArgs),
    /// The shedding torque over the whole pattern repeat.
    Torque(TorqueArgs),
    /// Crossing-angle offsets (stagger) that lower the peak or RMS torque with every window kept.
    Stagger(StaggerArgs),
    /// The classic timing diagram (frame lifts, shed, insertion window, carrier path, beat-up).
    Timing(TimingArgs),
    /// Electronic shedding: one servo per frame, laws per pick, per-frame torques and the shared DC bus.
    Servo(crate::loom_servo::ServoArgs),
}

/// The weave pattern: a WIF file or a plain lift plan (default: plain weave on the loom's frames).
#[derive(Debug, Args)]
pub struct PatternArgs {
    /// A WIF 1.1 draft (lift plan, or tie-up with treadling; shafts numbered from the front).
    #[arg(long, value_name = "FILE.wif")]
    wif: Option<PathBuf>,
    /// A plain lift plan: one line per pick, the raised shafts.
    #[arg(long, value_name = "FILE.txt", conflicts_with = "wif")]
    lift_plan: Option<PathBuf>,
}

impl PatternArgs {
    /// Whether a pattern file is given.
    pub(crate) fn given(&self) -> bool {
        self.wif.is_some() || self.lift_plan.is_some()
    }
}

/// `loomkin loom check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The loom file (TOML).
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `loomkin loom torque`.
#[derive(Debug, Args)]
pub struct TorqueArgs {
    /// The loom file (TOML).
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    /// Angle step of the curve, deg.
    #[arg(long, default_value_t = Drive::STEP_DEG.default_value())]
    step_deg: f64,
    #[command(flatten)]
    format: Format,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// What the stagger minimises.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum ObjectiveArg {
    /// The largest |torque|.
    Peak,
    /// The RMS torque.
    Rms,
}

impl From<ObjectiveArg> for Objective {
    fn from(a: ObjectiveArg) -> Self {
        match a {
            ObjectiveArg::Peak => Objective::Peak,
            ObjectiveArg::Rms => Objective::Rms,
        }
    }
}

/// `loomkin loom stagger`.
#[derive(Debug, Args)]
pub struct StaggerArgs {
    /// The loom file (TOML).
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    /// What to minimise.
    #[arg(long, value_enum, default_value = "peak")]
    objective: ObjectiveArg,
    #[arg(
        long,
        value_name = "MM",
        default_value_t = StaggerOptions::MIN_CLEARANCE_MM.default_value(),
        help = util::field_help(
            "Least clearance to the carrier to keep in every pick from entry to exit, mm",
            &StaggerOptions::MIN_CLEARANCE_MM
        )
    )]
    min_clearance_mm: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write the loom file with the optimised stagger to this file (TOML).
    #[arg(short, long)]
    output: Option<String>,
}

/// `loomkin loom timing`.
#[derive(Debug, Args)]
pub struct TimingArgs {
    /// The loom file (TOML).
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    /// The diagram (.svg or .png).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// Runs `loomkin loom …`.
pub fn run(cmd: LoomCommand) -> Result<()> {
    match cmd {
        LoomCommand::Check(a) => run_check(a),
        LoomCommand::Torque(a) => run_torque(a),
        LoomCommand::Stagger(a) => run_stagger(a),
        LoomCommand::Servo(a) => crate::loom_servo::run(a),
        LoomCommand::Timing(a) => {
            output::check_outputs([Some(Out::plot("--output", &a.output))])?;
            let (loom, pattern) = read(&a.loom, &a.pattern)?;
            output::figure(&timing_diagram(&loom, &pattern).map_err(in_file(&a.loom))?, &a.output, &a.plot)
        }
    }
}

/// A loom error, named with the loom file's path where it is about the file
/// ([`loomkin_loom::LoomError::in_loom_file`]: a field of it, found while it is read or while a
/// study runs, such as a carrier taller than the shed), as the file's read-time refusals are; a
/// pattern's or an option's error as it is.
pub(crate) fn in_file(path: &Path) -> impl Fn(loomkin_loom::LoomError) -> anyhow::Error + Copy + '_ {
    move |e| if e.in_loom_file() { anyhow!("{}: {e}", path.display()) } else { e.into() }
}

fn read_loom(path: &Path) -> Result<(Loom, String)> {
    let text = util::read_input(path)?;
    let loom = Loom::from_toml(&text).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    Ok((loom, text))
}

pub(crate) fn read(path: &Path, p: &PatternArgs) -> Result<(Loom, Pattern)> {
    let (loom, _) = read_loom(path)?;
    Ok((loom.clone(), read_pattern(&loom, p)?))
}

fn read_pattern(loom: &Loom, p: &PatternArgs) -> Result<Pattern> {
    let named = |path: &Path, e: loomkin_loom::LoomError| anyhow!("{}: {e}", path.display());
    match (&p.wif, &p.lift_plan) {
        (Some(w), _) => {
            let (pattern, note) = Pattern::from_wif_bytes(&util::read_input_bytes(w)?).map_err(|e| named(w, e))?;
            if let Some(note) = note {
                output::note(format_args!("loomkin: note: {}: {note}", w.display()));
            }
            Ok(pattern)
        }
        (None, Some(l)) => Pattern::from_lift_plan(&util::read_input(l)?).map_err(|e| named(l, e)),
        (None, None) => Ok(Pattern::plain(loom.frame_count())?),
    }
}

fn run_check(a: CheckArgs) -> Result<()> {
    let (loom, pattern) = read(&a.loom, &a.pattern)?;
    let bar = util::Progress::new(0, "loom check: picks");
    let r = check_with(&loom, &pattern, &|done, all| {
        bar.set_length(all as u64);
        bar.set(done as u64);
    })
    .map_err(in_file(&a.loom))?;
    bar.finish();
    if a.json {
        return output::json(&r);
    }
    outln!(
        "{} at {} rpm, {} picks, law {} over {}°",
        if r.loom.is_empty() { a.loom.display().to_string() } else { r.loom.clone() },
        r.speed_rpm,
        r.picks,
        r.law,
        r.motion_deg
    )?;
    outln!(
        "{:>5} {:>12} {:>12} {:>10} {:>10} {:>11} {:>16} {:>8} {:>6}",
        "frame",
        "fell[mm]",
        "back[mm]",
        "stroke[mm]",
        "angle[deg]",
        "max strain",
        "equal-strain[mm]",
        "ends",
        "moves"
    )?;
    for f in &r.frames {
        outln!(
            "{:>5} {:>12.1} {:>12.1} {:>10.2} {:>10.3} {:>11.3e} {:>16.2} {:>8.0} {:>6}",
            f.frame,
            f.distance_mm,
            f.back_depth_mm,
            f.stroke_mm,
            f.shed_angle_deg,
            f.max_strain,
            f.equal_strain_stroke_mm,
            f.ends,
            f.moves
        )?;
    }
    outln!("largest strain: frame {}", r.max_strain_frame)?;
    outln!(
        "peak shedding torque {:.3} N·m at {:.3}° of the repeat, RMS {:.3} N·m",
        r.peak_torque_n_m,
        r.peak_angle_deg,
        r.rms_torque_n_m
    )?;
    outln!(
        "shed clears the carrier from {:.2}° to {:.2}° in every pick ({:.2}°); insertion {:.2}° to {:.2}°, least clearance {:.2} mm",
        r.window_open_deg,
        r.window_close_deg,
        r.window_deg,
        r.insertion_deg[0],
        r.insertion_deg[1],
        r.min_clearance_mm
    )?;
    outln!("carrier mean speed {:.3} m/s: highest loom speed {:.1} rpm", r.mean_speed_m_s, r.max_speed_rpm)?;
    warn_interference(r.min_clearance_mm);
    Ok(())
}

/// The warning when the carrier touches the warp (a least clearance below zero, mm).
pub(crate) fn warn_interference(min_clearance_mm: f64) {
    if min_clearance_mm < 0.0 {
        output::warning(format_args!(
            "the carrier touches the warp: {:.2} mm of interference between entry and exit (insertion.entry_deg, insertion.exit_deg)",
            -min_clearance_mm
        ));
    }
}

fn run_torque(a: TorqueArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let (loom, pattern) = read(&a.loom, &a.pattern)?;
    Drive::STEP_DEG.check_as("--step-deg", a.step_deg)?;
    let motion = Motion::new(&loom, &pattern).map_err(in_file(&a.loom))?;
    let drive = Drive::new(&loom, &motion, &pattern);
    // A table streams a turn at a time (its time is the limit); a plot holds every point.
    let tabled = a.format.csv || a.format.json;
    if tabled || a.output.is_some() {
        let points = format!("{} ({} points)", loomkin_units::compact(a.step_deg), drive.curve_len(a.step_deg));
        util::check_budget("--step-deg", points, drive.curve_cost(a.step_deg, !tabled))?;
    }
    if let Some(out) = &a.output {
        return output::figure(&torque_figure(&loom, &pattern, a.step_deg).map_err(in_file(&a.loom))?, out, &a.plot);
    }
    if a.format.csv {
        let w = loom.speed.rad_per_s();
        let rows = drive.torque_points(a.step_deg).map(|(th, tq)| [th, tq, tq * w]);
        return output::csv_rows(&["angle_deg", "torque_n_m", "power_w"], true, rows);
    }
    if a.format.json {
        let points = drive
            .torque_points(a.step_deg)
            .map(|(angle_deg, torque_n_m)| loomkin_loom::TorquePoint { angle_deg, torque_n_m });
        return output::json_streamed(&drive.torque_summary(a.step_deg, output::Streamed::new(points)));
    }
    let peak = drive.peak(a.step_deg);
    let rms = drive.rms();
    outln!(
        "shedding torque over {} picks ({}°) at {} rpm: peak {:.3} N·m at {:.3}°, RMS {:.3} N·m",
        pattern.picks(),
        motion.repeat_deg(),
        loom.speed.rpm(),
        peak.torque_n_m,
        peak.angle_deg,
        rms
    )
}

fn run_stagger(a: StaggerArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::file("--output", p))])?;
    let (loom, text) = read_loom(&a.loom)?;
    let pattern = read_pattern(&loom, &a.pattern)?;
    let objective = a.objective.into();
    StaggerOptions::MIN_CLEARANCE_MM.check_as("--min-clearance-mm", a.min_clearance_mm)?;
    let options = StaggerOptions { objective, min_clearance_mm: a.min_clearance_mm };
    // The search's stages grow as it goes (a count not known ahead): an open-ended line.
    let bar = util::Progress::open_ended("stagger search: stages");
    let r = optimise_stagger_with(&loom, &pattern, &options, &Default::default(), &|done, _| bar.set(done as u64))
        .map_err(in_file(&a.loom))?;
    bar.finish();
    if let Some(out) = &a.output {
        let toml = Loom::stagger_toml(&text, &r.best.stagger_deg, r.groups.as_deref())?;
        output::text_to(out, &toml)?;
    }
    if a.json {
        return output::json(&r);
    }
    outln!(
        "{:<40} {:>12} {:>12} {:>15} {:>7} {:>13} {:>14}",
        "stagger",
        "peak[N·m]",
        "RMS[N·m]",
        "clearance[mm]",
        "window",
        "clear[deg]",
        "top speed[rpm]"
    )?;
    for c in [&r.none, &r.two_groups, &r.best] {
        outln!(
            "{:<40} {:>12.3} {:>12.3} {:>15.2} {:>7} {:>13.2} {:>14.1}",
            c.label,
            c.peak_torque_n_m,
            c.rms_torque_n_m,
            c.min_clearance_mm,
            if c.window_kept { "kept" } else { "LOST" },
            c.window_deg,
            c.max_speed_rpm
        )?;
    }
    let list: Vec<String> = r.best.stagger_deg.iter().map(|s| format!("{s}")).collect();
    outln!("optimised stagger [deg], front frame first: {}", list.join(", "))?;
    outln!(
        "peak torque reduction: optimised {:.1} %, two groups 7.5° {:.1} % ({} evaluations)",
        r.peak_reduction_pct,
        r.two_groups_peak_reduction_pct,
        r.evaluations
    )?;
    let (n, b) = (&r.none, &r.best);
    outln!(
        "what the optimum costs against no stagger: least clearance {:.2} → {:.2} mm (kept ≥ {} mm), clear shed {:.2}° → {:.2}°, top speed {:.1} → {:.1} rpm",
        n.min_clearance_mm,
        b.min_clearance_mm,
        loomkin_units::compact(r.min_clearance_kept_mm),
        n.window_deg,
        b.window_deg,
        n.max_speed_rpm,
        b.max_speed_rpm
    )
}
