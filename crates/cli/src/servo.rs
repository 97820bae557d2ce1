//! `loomkin servo …`: servo motion laws from definition points (Sivčák 2017), drive torque,
//! controller export, optimisation.

use crate::output::{self, Out, outln};
use crate::util::{self, Format};
use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use loomkin_plot::{Figure, Legend, Note, Panel, Series, sig4};
use loomkin_servo::{
    Drive, ExportFormat, LawReport, Objective, OptimizeOptions, ReinterpolationRow, SplineEnd, SplineLaw, TorqueReport,
    format_points, parse_points, torque_curve,
};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Subcommands of `loomkin servo`.
#[derive(Debug, Subcommand)]
pub enum ServoCommand {
    /// The law through the definition points: D, metrics (Cv, Ca, Cj, Cm…), samples.
    Law(LawArgs),
    /// Peak torque, RMS torque over the turn and peak power of the drive at one or more speeds.
    Torque(TorqueArgs),
    /// Move the free definition points to minimise the peak (or RMS) motor torque.
    Optimize(OptimizeArgs),
    /// Write coefficients (text/JSON), a cam table (CSV), XYVA points or quintic segments.
    Export(ExportArgs),
    /// Acceleration image with its definition points, and the motor torque over the turn (Fig. 3).
    Plot(PlotArgs),
    /// Check a servo axis (motor and load from a TOML file) moving a cycle: peak and RMS torque,
    /// speed, torque–speed envelope, inertia ratio, pass or fail with margins.
    Check(crate::servo_check::CheckArgs),
}

/// The definition points and the spline's start condition.
#[derive(Debug, Args, Clone)]
pub struct DefArgs {
    /// Definition points "X:Y,X:Y,…": X from 0 to 0.5 increasing, Y₁ = Y_N = 0, other Y in
    /// [-1, 1]. Default: the cycloid's acceleration sampled at X = j/12 (7 points).
    #[arg(long = "def", value_name = "X:Y,…", default_value = loomkin_servo::DEFAULT_DEF, hide_default_value = true)]
    def: String,
    /// Condition of the acceleration spline at x = 0: natural (f'' = 0) or clamped (f' = 0).
    #[arg(long, value_enum, ignore_case = true, default_value_t = SplineEnd::Natural)]
    end: SplineEnd,
}

impl DefArgs {
    fn build(&self) -> Result<SplineLaw> {
        let pts = parse_points(&self.def)?;
        SplineLaw::new(&pts, self.end).context("--def")
    }
}

/// The drive file.
#[derive(Debug, Args, Clone)]
pub struct DriveArgs {
    /// Drive file: TOML with a `[drive]` table, or a design file saved by the workbench (TOML or
    /// JSON; only its drive is read). Default: the built-in needle-rack drive.
    #[arg(long, value_name = "FILE")]
    drive: Option<PathBuf>,
}

impl DriveArgs {
    fn load(&self) -> Result<Drive> {
        match &self.drive {
            None => Ok(Drive::needle_rack_default()),
            Some(p) => {
                let text = util::read_input(p)?;
                Drive::from_text(&text).map_err(|e| anyhow::anyhow!("{}: {e}", p.display()))
            }
        }
    }
}

/// `servo law`.
#[derive(Debug, Args)]
pub struct LawArgs {
    #[command(flatten)]
    def: DefArgs,
    /// Print N samples of x, s, v, a, j instead of the metrics (with --csv or --json).
    #[arg(long, alias = "sample", value_name = "N")]
    points: Option<usize>,
    #[command(flatten)]
    format: Format,
}

/// `servo torque`.
#[derive(Debug, Args)]
pub struct TorqueArgs {
    #[command(flatten)]
    def: DefArgs,
    #[command(flatten)]
    drive: DriveArgs,
    /// Main-shaft speeds in 1/min, comma separated.
    #[arg(long, value_delimiter = ',', default_value = loomkin_servo::ServoInputs::TORQUE_SPEEDS_RPM)]
    speed_rpm: Vec<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `servo optimize`.
#[derive(Debug, Args)]
pub struct OptimizeArgs {
    #[command(flatten)]
    def: DefArgs,
    #[command(flatten)]
    drive: DriveArgs,
    /// Main-shaft speeds in 1/min (comma separated): the worst value over them is minimised.
    #[arg(long, value_delimiter = ',', default_value = loomkin_servo::ServoInputs::DESIGN_SPEEDS_RPM)]
    speed_rpm: Vec<f64>,
    /// Quantity to minimise: peak or rms motor torque.
    #[arg(long, value_enum, ignore_case = true, default_value_t = Objective::Peak)]
    objective: Objective,
    /// Number of Nelder–Mead starts (the given points, then pseudo-random ones).
    #[arg(long, default_value_t = loomkin_servo::ServoInputs::STARTS.default_count())]
    starts: usize,
    /// Keep the X of the points and move only their Y.
    #[arg(long)]
    fixed_x: bool,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `servo export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    #[command(flatten)]
    def: DefArgs,
    #[command(flatten)]
    drive: DriveArgs,
    /// coeffs (documented text), json (intervals), csv (cam table in mm), xyva (PLCopen-style
    /// points in mm), poly5 (the law's fifth-degree segments, b0…b5 in mm), cycle (the drive's
    /// turn as a cycle file, for `loomkin cam table` and `servo check`). The tables are those of
    /// `loomkin cam table` on that cycle file.
    #[arg(long, value_enum, ignore_case = true)]
    format: ExportFormat,
    /// Output file (`-` for standard output).
    #[arg(short, long)]
    output: String,
    /// Cam table step in degrees of the main shaft (csv, xyva): a point on every joint of the law
    /// and every STEP_DEG from each joint, as `loomkin cam table --step-deg`.
    #[arg(long, default_value_t = loomkin_servo::ServoInputs::EXPORT_STEP_DEG.default_value())]
    step_deg: f64,
    /// Print the re-interpolation report as JSON.
    #[arg(long)]
    json: bool,
}

/// `servo plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    #[command(flatten)]
    def: DefArgs,
    #[command(flatten)]
    drive: DriveArgs,
    /// Main-shaft speeds in 1/min, comma separated.
    #[arg(long, value_delimiter = ',', default_value = loomkin_servo::ServoInputs::DESIGN_SPEEDS_RPM)]
    speed_rpm: Vec<f64>,
    /// A second set of definition points to overlay (e.g. the optimised one).
    #[arg(long, value_name = "X:Y,…")]
    compare: Option<String>,
    /// Output file, .svg or .png.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// Runs a `servo` subcommand.
pub fn run(cmd: ServoCommand) -> Result<()> {
    match cmd {
        ServoCommand::Law(a) => law(a),
        ServoCommand::Torque(a) => torque(a),
        ServoCommand::Optimize(a) => optimize(a),
        ServoCommand::Export(a) => export(a),
        ServoCommand::Plot(a) => plot(a),
        ServoCommand::Check(a) => crate::servo_check::run(a),
    }
}

fn check_speeds(speeds: &[f64]) -> Result<()> {
    if speeds.is_empty() {
        bail!("--speed-rpm: give at least one speed");
    }
    for &n in speeds {
        loomkin_units::ShaftSpeed::from_rpm_field("--speed-rpm", n)?;
    }
    Ok(())
}

/// One sample of a normalised law (`servo law --points N --json`).
#[derive(Serialize)]
struct Sample {
    x: f64,
    s: f64,
    v: f64,
    a: f64,
    j: f64,
}

/// `servo law --points N --json` (the points streamed as they are made).
#[derive(Serialize)]
struct SamplesJson<'a> {
    units: &'static str,
    points: output::Streamed<'a, Sample>,
}

fn law(a: LawArgs) -> Result<()> {
    let sl = a.def.build()?;
    let law = sl.law();
    if let Some(n) = a.points {
        loomkin_laws::Law::SAMPLE_POINTS.check_count_as("--points", n)?;
        crate::law::check_sample_budget(n, n, a.format.json)?;
        // Checked finite first (sampling is cheap beside printing), then streamed: one block of
        // samples in memory whatever N.
        if let Some((x, _)) = law.samples(n).find(|(_, k)| ![k.s, k.v, k.a, k.j].iter().all(|v| v.is_finite())) {
            return Err(util::failure(anyhow::anyhow!("internal: the law is not finite at x = {x}")));
        }
        let progress = util::Progress::new(n as u64, "samples");
        let rows = law.samples(n).inspect(|_| progress.inc(1));
        if a.format.json {
            let points = output::Streamed::new(rows.map(|(x, k)| Sample { x, s: k.s, v: k.v, a: k.a, j: k.j }));
            output::json_streamed(&SamplesJson {
                units: "dimensionless (per unit stroke, per unit motion angle)",
                points,
            })?;
        } else {
            output::csv_rows(&["x", "s", "v", "a", "j"], true, rows.map(|(x, k)| [x, k.s, k.v, k.a, k.j]))?;
        }
        progress.finish();
        return Ok(());
    }
    if a.format.csv {
        bail!("--csv needs --sample N (the metrics are printed as text or --json)");
    }
    let r = LawReport::of(&sl);
    if a.format.json {
        return output::json(&r);
    }
    let m = r.metrics;
    outln!(
        "servo law through {} definition points ({} start), unit stroke on x = 0…1",
        sl.points().len(),
        sl.end().name()
    )?;
    outln!("  def = {}", format_points(sl.points()))?;
    outln!("  D = f'(0.5) = {:.10}   (slope of the acceleration image at the middle)", sl.d())?;
    outln!("  scale 1/F(1) = {:.10}  (unit-law acceleration = scale · f)", sl.scale())?;
    outln!("  values per unit stroke and unit motion angle (dimensionless)")?;
    outln!("  Cv   = max v     = {:.10}   at x = {:.6}", m.cv, m.x_cv)?;
    outln!(
        "  Ca   = max |a|   = {:.10}   (a+ {:.6} at x = {:.6}, a- {:.6} at x = {:.6})",
        m.ca,
        m.ca_pos,
        m.x_ca_pos,
        m.ca_neg,
        m.x_ca_neg
    )?;
    outln!("  Cj   = max |j|   = {:.10}   at x = {:.6}", m.cj, m.x_cj)?;
    outln!("  Cm   = max v·a   = {:.10}   at x = {:.6}", m.cm, m.x_cm)?;
    outln!("  Ca_rms = √∫a²dx  = {:.10}", m.ca_rms)?;
    let ck = if r.continuity_class < 0 { "none".to_string() } else { format!("C{}", r.continuity_class) };
    outln!("  continuity in a dwell-rise-dwell cycle: {ck}")?;
    Ok(())
}

/// `servo export --json` (cam tables): the re-interpolation report. The rows are given twice,
/// as `reinterpolation` (this command's key since issue 3) and as `interpolation` (the key of
/// `/api/servo/export`), so a script written against either front end reads this one.
#[derive(Serialize)]
struct ExportJson {
    format: ExportFormat,
    points: usize,
    reinterpolation: Vec<ReinterpolationRow>,
    interpolation: Vec<ReinterpolationRow>,
}

fn print_drive(d: &Drive) -> Result<()> {
    let lay = d.layout()?;
    outln!(
        "drive: stroke {} mm over {}°, mass {} kg, pinion r {} mm, i {}, J_m {:e} kg·m², k {} N/m, F_pre {} N, c {} N·s/m, F_c {} N, η {}",
        loomkin_units::mm_from_m(d.stroke_m),
        d.motion_angle_deg,
        d.moving_mass_kg,
        loomkin_units::mm_from_m(d.pinion_radius_m),
        d.gear_ratio,
        d.motor_inertia_kg_m2,
        d.spring_n_m,
        d.spring_preload_n,
        d.damping_n_s_m,
        d.constant_force_n,
        d.efficiency
    )?;
    outln!(
        "cycle (deg of the main shaft): rise {} | dwell {} | return {} | dwell {}",
        lay.rise_deg,
        lay.dwell_after_rise_deg,
        lay.return_deg,
        lay.dwell_after_return_deg
    )?;
    Ok(())
}

fn torque(a: TorqueArgs) -> Result<()> {
    check_speeds(&a.speed_rpm)?;
    let sl = a.def.build()?;
    let d = a.drive.load()?;
    let report = TorqueReport::compute(&sl, &d, &a.speed_rpm)?;
    if a.json {
        return output::json(&report);
    }
    print_drive(&d)?;
    outln!(
        "{:>12} {:>16} {:>14} {:>14} {:>14} {:>16}",
        "speed rpm",
        "peak torque N·m",
        "at angle deg",
        "RMS torque N·m",
        "peak power W",
        "motor max rpm"
    )?;
    for s in &report.results {
        outln!(
            "{:>12.1} {:>16.4} {:>14.2} {:>14.4} {:>14.1} {:>16.0}",
            s.speed_rpm,
            s.peak_torque_nm,
            s.peak_torque_angle_deg,
            s.rms_torque_nm,
            s.peak_power_w,
            s.peak_motor_speed_rpm
        )?;
    }
    Ok(())
}

fn optimize(a: OptimizeArgs) -> Result<()> {
    check_speeds(&a.speed_rpm)?;
    loomkin_servo::ServoInputs::STARTS.check_count_as("--starts", a.starts)?;
    let sl = a.def.build()?;
    let d = a.drive.load()?;
    let opts = OptimizeOptions {
        objective: a.objective,
        speeds_rpm: a.speed_rpm.clone(),
        starts: a.starts,
        move_x: !a.fixed_x,
        ..OptimizeOptions::default()
    };
    // Refused up front if the most evaluations it may make would pass the budget.
    let cores = crate::util::cores() as usize;
    crate::util::check_budget("--starts", a.starts, opts.cost(sl.points().len(), cores))?;
    let t0 = Instant::now();
    let total = (a.starts * opts.max_evals_per_start) as u64;
    let progress = util::Progress::new(total, "evaluations");
    let done = std::sync::atomic::AtomicBool::new(false);
    // A watcher passes the optimiser's evaluation count to the bar (drawn only on a terminal).
    let r = std::thread::scope(|scope| {
        scope.spawn(|| {
            while !done.load(std::sync::atomic::Ordering::Relaxed) {
                progress.set(opts.evaluated.get() as u64);
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
        });
        let r = loomkin_servo::optimize(&sl, &d, &opts);
        done.store(true, std::sync::atomic::Ordering::Relaxed);
        r
    })?;
    progress.finish();
    let elapsed = t0.elapsed().as_secs_f64();
    // The elapsed time goes to stderr only (identical input gives byte-identical output), and only
    // once the output is written: after a closed or failed standard output it is not printed.
    print_optimized(&a, &d, &opts, &r)?;
    output::note_after_output(format_args!("loomkin: optimised in {elapsed:.3} s"))
}

/// The result of `servo optimize` on standard output.
fn print_optimized(
    a: &OptimizeArgs,
    d: &Drive,
    opts: &OptimizeOptions,
    r: &loomkin_servo::OptimizeReport,
) -> Result<()> {
    let pts = r.law.points();
    if a.json {
        return output::json(&r.summary(&a.speed_rpm));
    }
    print_drive(d)?;
    outln!(
        "minimised the {} motor torque (worst over {} speed(s)), {} evaluations",
        opts.objective.name(),
        a.speed_rpm.len(),
        r.evaluations
    )?;
    outln!(
        "{:>12} {:>18} {:>18} {:>16} {:>16} {:>9}",
        "speed rpm",
        "peak before N·m",
        "peak after N·m",
        "RMS before N·m",
        "RMS after N·m",
        "peak Δ %"
    )?;
    for (b, f) in r.before.iter().zip(&r.after) {
        outln!(
            "{:>12.1} {:>18.4} {:>18.4} {:>16.4} {:>16.4} {:>9.1}",
            b.speed_rpm,
            b.peak_torque_nm,
            f.peak_torque_nm,
            b.rms_torque_nm,
            f.rms_torque_nm,
            100.0 * (f.peak_torque_nm / b.peak_torque_nm - 1.0)
        )?;
    }
    outln!("optimised definition points (use with --def):")?;
    outln!("  {}", format_points(pts))?;
    Ok(())
}

fn export(a: ExportArgs) -> Result<()> {
    output::check_outputs([Some(Out::file("--output", &a.output))])?;
    let sl = a.def.build()?;
    let d = a.drive.load()?;
    let file = loomkin_servo::export(&sl, &d, a.format, a.step_deg)?;
    output::text_to(&a.output, &file.text)?;
    // What a cam table loses when the controller interpolates between its points.
    let Some(table) = file.table else { return Ok(()) };
    if a.json {
        let rows: Vec<ReinterpolationRow> = table.reinterpolation.iter().map(ReinterpolationRow::from).collect();
        let report =
            ExportJson { format: a.format, points: table.points, interpolation: rows.clone(), reinterpolation: rows };
        if a.output == "-" {
            // The table went to stdout: keep it clean, the report goes to stderr.
            output::note(format_args!("{}", serde_json::to_string_pretty(&report)?));
            return Ok(());
        }
        return output::json(&report);
    }
    let mut report = format!(
        "cam table: {} points, step {:.6}° of the main shaft; worst errors when re-interpolated:\n",
        table.points, table.step_deg
    );
    report += &format!(
        "{:>16} {:>14} {:>18} {:>20} {:>10} {:>10} {:>10}\n",
        "interpolation", "position m", "velocity m/deg", "accel m/deg²", "pos/H", "vel/max", "acc/max"
    );
    for e in &table.reinterpolation {
        report += &format!(
            "{:>16} {:>14.3e} {:>18.3e} {:>20.3e} {:>10.2e} {:>10.2e} {:>10.2e}\n",
            e.mode.name(),
            e.max_position_error_m,
            e.max_velocity_error_m_per_deg,
            e.max_accel_error_m_per_deg2,
            e.rel_position_error,
            e.rel_velocity_error,
            e.rel_accel_error
        );
    }
    report +=
        "(xyva points are meant for quintic-Hermite interpolation; csv positions alone give the linear or cubic rows)";
    // With `-o -` the table is on stdout: the report goes to stderr.
    if a.output == "-" {
        output::note(format_args!("{report}"));
    } else {
        outln!("{report}")?;
    }
    Ok(())
}

fn plot(a: PlotArgs) -> Result<()> {
    output::check_outputs([Some(Out::plot("--output", &a.output))])?;
    check_speeds(&a.speed_rpm)?;
    let d = a.drive.load()?;
    let mut laws = vec![("given", a.def.build()?)];
    if let Some(c) = &a.compare {
        let other = DefArgs { def: c.clone(), end: a.def.end };
        laws.push(("compare", other.build().context("--compare")?));
    }
    let n = 721;
    let mut image = Panel::new("acceleration image f(x) [-]", Vec::new());
    image.x_label = Some("x = fraction of the motion angle [-]".into());
    let mut unit = Panel::new("unit law u°(x) [-]", Vec::new()).with_legend(Legend::Auto);
    unit.x_label = Some("x = fraction of the motion angle [-]".into());
    let mut torque = Panel::new("motor torque M [N·m]", Vec::new()).with_legend(Legend::Auto);
    // As the paper's Fig. 3: the given law solid, the compared one dashed; the points in the colour
    // of their curve; one colour per speed in the torque panel.
    const PALETTE: [[u8; 3]; 6] =
        [[0, 114, 178], [213, 94, 0], [0, 158, 115], [204, 121, 167], [86, 180, 233], [0, 0, 0]];
    for (i, (name, sl)) in laws.iter().enumerate() {
        let style = |s: Series, colour: [u8; 3]| {
            let s = s.with_color(colour);
            if i == 0 { s } else { s.with_dashes() }
        };
        let f: Vec<(f64, f64)> = (0..n).map(|i| i as f64 / (n - 1) as f64).map(|x| (x, sl.accel_image(x))).collect();
        image.series.push(style(Series::line(format!("{name}: f(x)"), f), PALETTE[i]));
        image.series.push(
            Series::markers(format!("{name}: definition points"), sl.points().iter().map(|p| (p[0], p[1])).collect())
                .with_color(PALETTE[i]),
        );
        let s: Vec<(f64, f64)> = sl.law().sample(n).into_iter().map(|(x, k)| (x, k.s)).collect();
        unit.series.push(style(Series::line(*name, s), PALETTE[i]));
        for (k, &rpm) in a.speed_rpm.iter().enumerate() {
            let c = torque_curve(sl.law(), &d, rpm, 1441)?;
            // The peak located on the closed form; its sign read from the nearest drawn point.
            let peak = loomkin_servo::summary(sl.law(), &d, rpm)?;
            let near = c.iter().min_by(|p, q| {
                (p.angle_deg - peak.peak_torque_angle_deg)
                    .abs()
                    .total_cmp(&(q.angle_deg - peak.peak_torque_angle_deg).abs())
            });
            let signed = peak.peak_torque_nm.copysign(near.map_or(1.0, |p| p.torque_nm));
            torque.notes.push(Note::new(peak.peak_torque_angle_deg, signed, ""));
            let label = format!(
                "{name}, {rpm} rpm: |M| max {} N·m at {:.1}°",
                sig4(peak.peak_torque_nm),
                peak.peak_torque_angle_deg
            );
            let line = Series::line(label, c.iter().map(|p| (p.angle_deg, p.torque_nm)).collect());
            // Every law and speed its own colour; the compared law dashed as well.
            torque.series.push(style(line, PALETTE[(i * a.speed_rpm.len() + k) % PALETTE.len()]));
        }
    }
    let fig = Figure::new(
        "Servo motion law from definition points and motor torque over one turn",
        "main-shaft angle [deg]",
        vec![image, unit, torque],
    );
    output::figure(&fig, &a.output, &a.plot)
}
