//! `loomkin drive …`: the main shaft — reduced inertia of the loom's mechanisms, speed ripple, flywheel.

use crate::loom::{PatternArgs, read};
use crate::output::{self, outln};
use crate::util::{self, Format};
use anyhow::Result;
use clap::{Args, Subcommand, ValueEnum};
use loomkin_drive::ripple::{FLYWHEEL_KG_M2, STEP_DEG};
use loomkin_drive::{MotorCurve, MotorKind, MotorSpec, Table, flywheel_for, solve};
use loomkin_dynamics::Follower;
use loomkin_io::Table as Csv;
use loomkin_loom::{Drive, LoomShaft, Motion, ripple_figure};
use serde::Serialize;
use std::path::PathBuf;

/// `loomkin drive`.
#[derive(Debug, Subcommand)]
pub enum DriveCommand {
    /// The reduced moment of inertia J(φ) of every mechanism on the main shaft over the repeat.
    Inertia(InertiaArgs),
    /// The main shaft's periodic speed under a motor: speed ripple, energy swing, motor torque, flywheel.
    Ripple(Box<RippleArgs>),
    /// Time-true cams: the frames' laws corrected for the shaft's speed ripple, written as cycle files.
    Correct(Box<CorrectArgs>),
}

/// `loomkin drive inertia`.
#[derive(Debug, Args)]
pub struct InertiaArgs {
    /// The loom file (TOML).
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    /// Angle step of the grid (CSV rows; the extremes are located between its points), deg.
    #[arg(long, default_value_t = Drive::STEP_DEG.default_value())]
    step_deg: f64,
    #[command(flatten)]
    format: Format,
}

/// The motor model.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum MotorArg {
    /// An ideal constant torque holding the loom's speed as the mean.
    Constant,
    /// An induction motor through a gear.
    Induction,
    /// A speed-controlled servo drive (PI loop, torque limit).
    Servo,
}

/// The induction motor's curve.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum CurveArg {
    /// The straight slip line through the rated point.
    Linear,
    /// Kloss's curve with the breakdown torque.
    Kloss,
}

/// The motor flags of `drive ripple` and `drive correct`.
#[derive(Debug, Args)]
pub struct MotorArgs {
    /// The motor (default: the file's `[drive]` motor, else constant).
    #[arg(long, value_enum)]
    motor: Option<MotorArg>,
    /// The induction motor's torque curve (default: the file's, else linear).
    #[arg(long, value_enum)]
    motor_curve: Option<CurveArg>,
    /// Induction motor: synchronous speed of the motor, rpm.
    #[arg(long, allow_hyphen_values = true)]
    synchronous_rpm: Option<f64>,
    /// Induction motor: rated speed of the motor, rpm.
    #[arg(long, allow_hyphen_values = true)]
    rated_rpm: Option<f64>,
    /// Induction motor: rated power, kW.
    #[arg(long, allow_hyphen_values = true)]
    rated_power_kw: Option<f64>,
    /// Induction motor (Kloss): breakdown torque over rated torque.
    #[arg(long, allow_hyphen_values = true)]
    breakdown_ratio: Option<f64>,
    /// Induction motor: motor speed over main-shaft speed.
    #[arg(long, allow_hyphen_values = true)]
    gear_ratio: Option<f64>,
    /// Servo: proportional gain at the main shaft, N·m per rad/s.
    #[arg(long, allow_hyphen_values = true)]
    servo_gain_n_m_s: Option<f64>,
    /// Servo: integral time, s.
    #[arg(long, allow_hyphen_values = true)]
    servo_integral_s: Option<f64>,
    /// Servo: torque limit at the main shaft, N·m.
    #[arg(long, allow_hyphen_values = true)]
    servo_torque_limit_n_m: Option<f64>,
}

impl MotorArgs {
    /// The loom file's `[drive]` motor with these flags over it.
    fn motor(&self, loom: &loomkin_loom::Loom) -> Result<loomkin_drive::Motor> {
        let over = MotorSpec {
            motor: self.motor.map(|m| match m {
                MotorArg::Constant => MotorKind::Constant,
                MotorArg::Induction => MotorKind::Induction,
                MotorArg::Servo => MotorKind::Servo,
            }),
            motor_curve: self.motor_curve.map(|c| match c {
                CurveArg::Linear => MotorCurve::Linear,
                CurveArg::Kloss => MotorCurve::Kloss,
            }),
            synchronous_rpm: self.synchronous_rpm,
            rated_rpm: self.rated_rpm,
            rated_power_kw: self.rated_power_kw,
            breakdown_ratio: self.breakdown_ratio,
            gear_ratio: self.gear_ratio,
            servo_gain_n_m_s: self.servo_gain_n_m_s,
            servo_integral_s: self.servo_integral_s,
            servo_torque_limit_n_m: self.servo_torque_limit_n_m,
        };
        let spec = loom.drive.motor.overridden(&over);
        spec.check_read(&over, |key| format!("--{}", key.replace('_', "-")))?;
        Ok(spec.build(loom.speed.rpm(), "drive.")?)
    }
}

/// `loomkin drive ripple`.
#[derive(Debug, Args)]
pub struct RippleArgs {
    /// The loom file (TOML).
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    #[command(flatten)]
    motor: MotorArgs,
    /// Inertia added to the main shaft, kg·m² (default: the file's `[drive] flywheel_kg_m2`, else 0).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "target_ripple_pct")]
    flywheel_kg_m2: Option<f64>,
    /// Size the least flywheel that holds the speed ripple at this value, %.
    #[arg(long, allow_hyphen_values = true)]
    target_ripple_pct: Option<f64>,
    /// Step of the integration grid, deg.
    #[arg(long, default_value_t = STEP_DEG.default_value())]
    step_deg: f64,
    #[command(flatten)]
    format: Format,
    /// Plot ω(φ) and the torques to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: util::PlotOpts,
}

/// `loomkin drive correct`.
#[derive(Debug, Args)]
pub struct CorrectArgs {
    /// The loom file (TOML).
    loom: PathBuf,
    #[command(flatten)]
    pattern: PatternArgs,
    #[command(flatten)]
    motor: MotorArgs,
    /// Inertia added to the main shaft, kg·m² (default: the file's `[drive] flywheel_kg_m2`, else 0).
    #[arg(long, allow_hyphen_values = true)]
    flywheel_kg_m2: Option<f64>,
    /// Step of the speed-ripple grid, deg.
    #[arg(long, default_value_t = STEP_DEG.default_value())]
    step_deg: f64,
    /// The frames' natural frequency on their drive, Hz: the residual vibration before and after
    /// through the elastic model (left out: not computed).
    #[arg(long, allow_hyphen_values = true)]
    natural_hz: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("The frames' damping ratio ζ (with --natural-hz)", &Follower::DAMPING_RATIO))]
    damping_ratio: Option<f64>,
    /// Directory for the cycle files, one per moving frame (frame-01.toml …), read by `cam` and `dyn`.
    #[arg(short, long)]
    output: PathBuf,
    /// Print machine-readable JSON.
    #[arg(long)]
    json: bool,
}

/// Runs `loomkin drive …`.
pub fn run(cmd: DriveCommand) -> Result<()> {
    match cmd {
        DriveCommand::Inertia(a) => run_inertia(a),
        DriveCommand::Ripple(a) => run_ripple(*a),
        DriveCommand::Correct(a) => run_correct(*a),
    }
}

fn run_inertia(a: InertiaArgs) -> Result<()> {
    let (loom, pattern) = read(&a.loom, &a.pattern)?;
    Drive::STEP_DEG.check_as("--step-deg", a.step_deg)?;
    let motion = Motion::new(&loom, &pattern)?;
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    if a.format.csv {
        // Row by row: a long repeat's table is never held whole.
        return output::csv_rows(&shaft.inertia_header(), true, shaft.inertia_rows(a.step_deg)?);
    }
    let r = shaft.report(a.step_deg)?;
    if a.format.json {
        return output::json(&r);
    }
    outln!("reduced inertia on the main shaft over {} picks ({}°), kg·m²:", r.picks, r.repeat_deg)?;
    outln!("{:<16} {:>14} {:>14} {:>14}", "mechanism", "J min", "J max", "J mean")?;
    for m in &r.mechanisms {
        outln!("{:<16} {:>14.6} {:>14.6} {:>14.6}", m.name, m.j_min_kg_m2, m.j_max_kg_m2, m.j_mean_kg_m2)?;
    }
    outln!("{:<16} {:>14.6} {:>14.6} {:>14.6}", "total", r.j_min_kg_m2, r.j_max_kg_m2, r.j_mean_kg_m2)?;
    outln!("total least at {:.3}°, largest at {:.3}° of the repeat", r.total.j_min_angle_deg, r.total.j_max_angle_deg)
}

/// `drive ripple --json`: the report, and the target when a flywheel was sized.
#[derive(Debug, Serialize)]
struct RippleJson<'a> {
    #[serde(flatten)]
    report: &'a loomkin_drive::RippleReport,
    #[serde(skip_serializing_if = "Option::is_none")]
    target_ripple_pct: Option<f64>,
}

fn run_ripple(a: RippleArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| output::Out::plot("--output", p))])?;
    let (loom, pattern) = read(&a.loom, &a.pattern)?;
    STEP_DEG.check_as("--step-deg", a.step_deg)?;
    let motor = a.motor.motor(&loom)?;
    let motion = Motion::new(&loom, &pattern)?;
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let table = Table::new(&shaft, a.step_deg)?;
    let sol = match a.target_ripple_pct {
        Some(target) => flywheel_for(&table, &motor, target)?.1,
        None => {
            let jf = match a.flywheel_kg_m2 {
                Some(v) => FLYWHEEL_KG_M2.check_as("--flywheel-kg-m2", v)?,
                None => loom.drive.flywheel_kg_m2,
            };
            solve(&table, &motor, jf)?
        }
    };
    let r = &sol.report;
    if let Some(out) = &a.output {
        let title = if loom.name.is_empty() { util::file_name(&a.loom) } else { loom.name.clone() };
        return output::figure(&ripple_figure(&sol, &title), out, &a.plot);
    }
    if a.format.csv {
        let cols = sol.columns();
        let mut t = Csv::new(cols.iter().map(|(name, _)| *name));
        for k in 0..cols[0].1.len() {
            t.push(cols.iter().map(|(_, c)| c[k]).collect())?;
        }
        return output::csv(&t);
    }
    if a.format.json {
        return output::json(&RippleJson { report: r, target_ripple_pct: a.target_ripple_pct });
    }
    outln!(
        "main shaft over {} picks ({}°), {} motor: mean {:.3} rpm, {:.3} to {:.3} rpm (at {:.2}° and {:.2}°), ripple {:.4} %",
        pattern.picks(),
        motion.repeat_deg(),
        r.motor,
        r.mean_speed_rpm,
        r.min_speed_rpm,
        r.max_speed_rpm,
        r.min_speed_angle_deg,
        r.max_speed_angle_deg,
        r.speed_ripple_pct
    )?;
    outln!(
        "energy swing {:.4} J; motor torque peak {:.3} N·m, RMS {:.3} N·m; mean load {:.3} N·m",
        r.energy_swing_j,
        r.peak_motor_torque_n_m,
        r.rms_motor_torque_n_m,
        r.mean_load_torque_n_m
    )?;
    match a.target_ripple_pct {
        Some(t) => outln!("flywheel {:.6} kg·m² holds the ripple at {t} %", r.flywheel_kg_m2),
        None => outln!("flywheel {} kg·m²", loomkin_units::compact(r.flywheel_kg_m2)),
    }
}

/// `drive correct --json`: the report and the files written.
#[derive(Debug, Serialize)]
struct CorrectJson<'a> {
    #[serde(flatten)]
    report: &'a loomkin_loom::CorrectionReport,
    files: Vec<String>,
}

fn run_correct(a: CorrectArgs) -> Result<()> {
    let (loom, pattern) = read(&a.loom, &a.pattern)?;
    STEP_DEG.check_as("--step-deg", a.step_deg)?;
    let motor = a.motor.motor(&loom)?;
    let jf = match a.flywheel_kg_m2 {
        Some(v) => FLYWHEEL_KG_M2.check_as("--flywheel-kg-m2", v)?,
        None => loom.drive.flywheel_kg_m2,
    };
    if a.damping_ratio.is_some() && a.natural_hz.is_none() {
        anyhow::bail!("--damping-ratio: read only with --natural-hz (the elastic model it damps)");
    }
    let zeta = Follower::DAMPING_RATIO.or_default(a.damping_ratio)?;
    let follower = a.natural_hz.map(|f| Follower::new(f, zeta)).transpose()?;
    let motion = Motion::new(&loom, &pattern)?;
    let c = loomkin_loom::correct(&loom, &motion, &pattern, &motor, jf, a.step_deg, follower.as_ref())?;
    std::fs::create_dir_all(&a.output)
        .map_err(|e| anyhow::anyhow!("-o {}: cannot create the directory: {e}", a.output.display()))?;
    let title = if loom.name.is_empty() { util::file_name(&a.loom) } else { loom.name.clone() };
    let mut files = Vec::new();
    for (name, text) in c.cycle_files(&title)? {
        let path = a.output.join(&name);
        std::fs::write(&path, text).map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", path.display()))?;
        files.push(path.display().to_string());
    }
    let r = &c.report;
    if let Some(w) = r.sley.as_ref().and_then(|s| s.warning()) {
        output::warning(w);
    }
    if a.json {
        return output::json(&CorrectJson { report: r, files });
    }
    outln!(
        "time-true cams over {} picks, {} motor, mean {:.3} rpm: ripple {:.4} % with the design cams, {:.4} % with the corrected ({} rounds)",
        r.picks,
        r.motor,
        r.mean_speed_rpm,
        r.speed_ripple_pct,
        r.speed_ripple_pct_after,
        r.rounds
    )?;
    let vib = follower.is_some();
    if vib {
        outln!(
            "{:<10} {:>6} {:>14} {:>14} {:>15} {:>15} {:>15}",
            "frame",
            "moves",
            "timing before",
            "timing after",
            "residual before",
            "residual after",
            "at const speed"
        )?;
    } else {
        outln!("{:<10} {:>6} {:>14} {:>14}", "frame", "moves", "timing before", "timing after")?;
    }
    let mm = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6} mm"));
    for f in &r.frames {
        let (b, af) =
            (format!("{:.4}°", f.max_timing_error_deg_before), format!("{:.2e}°", f.max_timing_error_deg_after));
        if vib {
            outln!(
                "{:<10} {:>6} {:>14} {:>14} {:>15} {:>15} {:>15}",
                f.name,
                f.moves,
                b,
                af,
                mm(f.residual_vibration_mm_before),
                mm(f.residual_vibration_mm_after),
                mm(f.residual_vibration_constant_speed_mm)
            )?;
        } else {
            outln!("{:<10} {:>6} {:>14} {:>14}", f.name, f.moves, b, af)?;
        }
    }
    if let Some(s) = &r.sley {
        // One cam for every pick: after, the worst pick against the pick-mean correction.
        let (b, af) =
            (format!("{:.4}°", s.max_timing_error_deg_before), format!("{:.2e}°", s.max_timing_error_deg_after));
        outln!(
            "{:<10} {:>6} {:>14} {:>14}  (corrected for the pick-mean speed; after: the worst pick)",
            s.name,
            s.moves,
            b,
            af
        )?;
        outln!(
            "sley cam on its follower: largest pressure angle {:.3}° before, {:.3}° after (limit {}°); least radius of curvature {:.3} mm before, {:.3} mm after (roller {} mm)",
            s.max_pressure_angle_deg_before,
            s.max_pressure_angle_deg_after,
            loomkin_units::compact(s.pressure_angle_limit_deg),
            s.min_curvature_radius_mm_before,
            s.min_curvature_radius_mm_after,
            loomkin_units::compact(s.roller_radius_mm)
        )?;
    }
    outln!(
        "largest timing error {:.4}° before, {:.2e}° after; {} cycle files in {}",
        r.max_timing_error_deg_before,
        r.max_timing_error_deg_after,
        files.len(),
        a.output.display()
    )?;
    for n in &r.not_corrected {
        outln!("not corrected: {n}")?;
    }
    if !vib {
        outln!("(give --natural-hz for the frames' residual vibration before and after)")?;
    }
    Ok(())
}
