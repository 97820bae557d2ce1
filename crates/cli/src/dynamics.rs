//! `loomkin dyn …`: elastic follower dynamics — response, speed sweep, residual spectrum,
//! compensation, quiet laws. Parses, calls `loomkin-dynamics`, prints.

use crate::output::{self, Out, outln};
use crate::util::{self, Format};
use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use loomkin_dynamics::{
    Compensation, Follower, Optimized, Response, ResponseReport, Start, SweepEntry, SweepPoint, SweepReport, Units,
    sweep, sweep_columns, sweep_row,
};
use loomkin_io::Table;
use loomkin_laws::Cycle;
use loomkin_plot::{Figure, Legend, Note, Panel, Rule, Series, XBand, sig4};
use loomkin_units::{ShaftSpeed, Span};
use std::path::{Path, PathBuf};

/// `loomkin dyn` subcommands.
#[derive(Debug, Subcommand)]
pub enum DynCommand {
    /// Exact response of an elastic follower to a cycle at one speed: dynamic error, residual vibration in
    /// the dwells, peak acceleration and force, VDI 2149 rigidity ratio.
    Response(ResponseArgs),
    /// Residual amplitude, peak error and peak force against shaft speed (FROM:TO:STEP rpm).
    Sweep(SweepArgs),
    /// Residual-vibration spectrum of laws: residual amplitude (% of stroke) against motion time / natural
    /// period, for catalogue laws (NAME or NAME:KEY=VALUE) and the rises and returns of cycle files (.toml).
    Spectrum(SpectrumArgs),
    /// Compensation (polydyne): the input law that makes the follower follow the cycle exactly, written
    /// as CSV samples (.csv) or exact pieces (.toml); refuses a cycle whose input would jump.
    Compensate(CompensateArgs),
    #[command(about = format!(
        "Shape the cycle's rises and returns for least residual vibration across a speed band, peak acceleration at \
         most {} % of the modified sine's; compares with modified-sine laws",
        loomkin_units::compact(100.0 * loomkin_dynamics::CA_LIMIT_OF_MODIFIED_SINE)
    ))]
    Optimize(OptimizeArgs),
    /// Two-mass train (drive stiffness to the dobby or cam-box output mass, frame stiffness to the frame):
    /// modal frequencies, the drive's and the frame's peak dynamic errors (located exactly) and the bound
    /// on the frame's residual vibration in the dwells.
    TwoMass(TwoMassArgs),
}

/// `loomkin dyn two-mass`.
#[derive(Debug, Args)]
pub struct TwoMassArgs {
    /// The cycle file (TOML): the motion of the drive's input.
    file: PathBuf,
    #[arg(long, help = util::speed_help("Main-shaft speed in rpm (left out: the file's `speed_rpm`, else the default)"))]
    speed_rpm: Option<f64>,
    /// Mass of the drive's output (dobby or cam-box lever, reduced to the frame's motion), kg.
    #[arg(long)]
    drive_mass_kg: f64,
    /// Stiffness from the input to the drive mass, N/m.
    #[arg(long)]
    drive_stiffness_n_m: f64,
    /// Mass of the heald frame, kg.
    #[arg(long)]
    frame_mass_kg: f64,
    /// Stiffness from the drive mass to the frame, N/m.
    #[arg(long)]
    frame_stiffness_n_m: f64,
    /// Modal damping ratio ζ of both modes (0 ≤ ζ < 1).
    #[arg(long, default_value_t = Follower::DAMPING_RATIO.default_value())]
    damping_ratio: f64,
    /// The periodic steady state instead of one cycle from rest.
    #[arg(long)]
    steady: bool,
    /// Print machine-readable JSON.
    #[arg(long)]
    json: bool,
}

/// `loomkin dyn optimize`.
#[derive(Debug, Args)]
pub struct OptimizeArgs {
    /// The cycle file (TOML).
    file: PathBuf,
    #[arg(long, help = util::speed_help("Design speed in rpm (left out: the file's `speed_rpm`, else the default)"))]
    speed_rpm: Option<f64>,
    #[arg(long, default_value_t = Optimized::BAND_PCT.default_value(), help = util::range_help("Half-width of the speed band around the design speed, in %", &Optimized::BAND_PCT))]
    band_pct: f64,
    #[command(flatten)]
    model: ModelArgs,
    /// Print machine-readable JSON.
    #[arg(long)]
    json: bool,
    /// Write the optimised cycle (TOML) to this file (`-` for standard output).
    #[arg(short, long)]
    output: Option<String>,
}

/// `loomkin dyn compensate`.
#[derive(Debug, Args)]
pub struct CompensateArgs {
    /// The designed cycle (TOML): the motion the follower must make.
    file: PathBuf,
    #[arg(long, help = util::speed_help("Main-shaft speed in rpm (left out: the file's `speed_rpm`, else the default)"))]
    speed_rpm: Option<f64>,
    #[command(flatten)]
    model: ModelArgs,
    /// Samples per cycle in the CSV.
    #[arg(long, default_value_t = Compensation::POINTS.default_count())]
    points: usize,
    /// Output file: OUT.csv (samples) or OUT.toml (exact pieces); `-` prints the CSV.
    #[arg(short, long)]
    output: String,
}

/// `loomkin dyn spectrum`.
#[derive(Debug, Args)]
pub struct SpectrumArgs {
    /// Laws: a catalogue NAME, NAME:KEY=VALUE (e.g. modified-trapezoid:ramp=0.2,
    /// piecewise:segments=…), or a cycle file FILE.toml (each of its rises and returns).
    #[arg(required = true)]
    laws: Vec<String>,
    /// Damping ratios, comma-separated (each 0 ≤ ζ < 1).
    #[arg(long, default_value_t = Follower::DAMPING_RATIO.default_value().to_string())]
    damping_ratio: String,
    /// Ratios of motion time to natural period, FROM:TO:STEP.
    #[arg(long, default_value = loomkin_dynamics::DEFAULT_RATIOS)]
    ratio: String,
    /// Print CSV (one column per law and damping ratio).
    #[arg(long)]
    csv: bool,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with = "csv")]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// The follower model shared by the subcommands.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// Natural frequency of the follower (frame on its drive) in Hz (> 0).
    #[arg(long)]
    natural_hz: f64,
    /// Damping ratio ζ (0 ≤ ζ < 1).
    #[arg(long, default_value_t = Follower::DAMPING_RATIO.default_value())]
    damping_ratio: f64,
    /// Moving mass in kg: enables forces (train/contact force, contact loss).
    #[arg(long)]
    mass_kg: Option<f64>,
    /// Return spring acting on the mass, N/m (needs --mass-kg; f_n is that of the whole follower).
    #[arg(long, default_value_t = Follower::RETURN_SPRING_N_M.default_value(), requires = "mass_kg")]
    return_spring_n_m: f64,
    /// Spring preload pulling the follower onto the cam, N (needs --mass-kg).
    #[arg(long, default_value_t = Follower::PRELOAD_N.default_value(), requires = "mass_kg")]
    preload_n: f64,
    /// Add the follower's weight m·g as a closing force (a follower rising upwards).
    #[arg(long, requires = "mass_kg")]
    weight: bool,
    /// A further constant closing force, N (needs --mass-kg).
    #[arg(long, default_value_t = Follower::FORCE_N.default_value(), requires = "mass_kg")]
    force_n: f64,
}

impl ModelArgs {
    fn follower(&self) -> Result<Follower> {
        Ok(Follower::new(self.natural_hz, self.damping_ratio)?.with_front_loads(
            self.mass_kg,
            self.return_spring_n_m,
            self.preload_n,
            self.weight,
            self.force_n,
        )?)
    }
}

/// `loomkin dyn response`.
#[derive(Debug, Args)]
pub struct ResponseArgs {
    /// The cycle file (TOML, as for `loomkin cycle`).
    file: PathBuf,
    #[arg(long, help = util::speed_help("Main-shaft speed in rpm (left out: the file's `speed_rpm`, else the default)"))]
    speed_rpm: Option<f64>,
    #[command(flatten)]
    model: ModelArgs,
    /// Number of cycles computed from rest at 0° of the cycle.
    #[arg(long, default_value_t = Response::CYCLES.default_count(), conflicts_with = "steady")]
    cycles: usize,
    /// The periodic steady state (the motion that repeats every cycle) instead of starting from rest.
    #[arg(long)]
    steady: bool,
    /// Samples per cycle for CSV, JSON and plots.
    #[arg(long, default_value_t = Response::POINTS.default_count())]
    points: usize,
    #[command(flatten)]
    format: Format,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// `loomkin dyn sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The cycle file (TOML).
    file: PathBuf,
    /// Speeds FROM:TO:STEP in rpm.
    #[arg(long)]
    speed_rpm: String,
    #[command(flatten)]
    model: ModelArgs,
    /// Each speed in its periodic steady state instead of one cycle from rest.
    #[arg(long)]
    steady: bool,
    #[command(flatten)]
    format: Format,
    #[command(flatten)]
    shard: crate::shard::ShardArgs,
    /// Plot to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv", "shard"])]
    output: Option<PathBuf>,
    #[arg(long, default_value_t = SweepPoint::RESIDUAL_LIMIT_PCT.default_value(), value_name = "L", help = util::range_help("Residual amplitude a design accepts, % of the stroke, drawn on the plot, the speeds above it shaded as speeds to avoid", &SweepPoint::RESIDUAL_LIMIT_PCT))]
    residual_limit_pct: f64,
    /// Plot the residual amplitude and the dynamic error on a logarithmic axis (from five decades
    /// under the largest value), so a limit near zero and the speeds around it can be read.
    #[arg(long, requires = "output")]
    log_y: bool,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// Runs `loomkin dyn …`.
pub fn run(cmd: DynCommand) -> Result<()> {
    match cmd {
        DynCommand::Response(a) => response(a),
        DynCommand::Sweep(a) => sweep_cmd(a),
        DynCommand::Spectrum(a) => spectrum_cmd(a),
        DynCommand::Compensate(a) => compensate_cmd(a),
        DynCommand::Optimize(a) => optimize_cmd(a),
        DynCommand::TwoMass(a) => two_mass_cmd(a),
    }
}

fn units(cycle: &Cycle) -> Units {
    Units::of(cycle.unit)
}

fn read_cycle(path: &Path) -> Result<Cycle> {
    let text = util::read_input(path)?;
    Cycle::from_toml(&text).with_context(|| path.display().to_string())
}

fn speed_of(flag: Option<f64>, cycle: &Cycle) -> Result<ShaftSpeed> {
    Ok(ShaftSpeed::from_rpm(cycle.speed_rpm_or(flag))?)
}

fn rigidity_note(s: &loomkin_dynamics::Summary) {
    if s.rigidity_warning {
        output::warning(format!(
            "rigidity ratio f_n/f_shaft = {} is below 10 (VDI 2149 Blatt 1): the rigid-body law does not describe \
             the motion — read the elastic response",
            loomkin_units::compact(s.rigidity_ratio)
        ));
    }
}

fn response(a: ResponseArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let cycle = read_cycle(&a.file)?;
    let speed = speed_of(a.speed_rpm, &cycle)?;
    let follower = a.model.follower()?;
    Response::CYCLES.check_count(a.cycles)?;
    Response::POINTS.check_count(a.points)?;
    let start = if a.steady { Start::Steady } else { Start::Rest };
    // The cycles computed: the steady state's one, else those asked for from rest.
    let cycles = if a.steady { 1 } else { a.cycles };
    // A table or a plot holds every sample of every cycle computed: refused before it starts
    // when estimated beyond the budget (the summary and JSON hold none).
    let samples = Response::sample_count(a.points, cycles);
    let cost = if a.format.csv {
        Some(Response::csv_cost(samples))
    } else if let (false, Some(out)) = (a.format.json, a.output.as_ref()) {
        Some(Response::plot_cost(samples, out.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"))))
    } else {
        None
    };
    if let Some(cost) = cost {
        let value = format!("{} × {cycles}", a.points);
        crate::util::check_budget("--points × --cycles", value, cost)?;
    }
    let r = Response::new(&cycle, speed, &follower, start, cycles)?;
    let u = units(&cycle);
    let summary = r.summary();
    rigidity_note(&summary);
    if a.format.csv {
        let p = u.pos;
        let mut t = Table::new([
            "angle_deg".to_string(),
            format!("s_{p}"),
            format!("x_{p}"),
            format!("error_{p}"),
            format!("a_{}", u.acc),
        ]);
        for s in r.samples(a.points) {
            t.push(vec![s[0], s[1] * u.scale, s[2] * u.scale, s[3] * u.scale, s[4]])?;
        }
        return output::csv(&t);
    }
    if a.format.json {
        return output::json(&ResponseReport {
            summary,
            units: u,
            speed_rpm: speed.rpm(),
            natural_hz: follower.natural_hz(),
            damping_ratio: follower.damping_ratio(),
            start,
            cycles,
        });
    }
    if let Some(out) = a.output {
        let samples = r.samples(a.points);
        let col = |i: usize, k: f64| samples.iter().map(|s| (s[0], s[i] * k)).collect::<Vec<_>>();
        let acc_in: Vec<(f64, f64)> = {
            let total = r.duration_s();
            let n = samples.len();
            (0..n)
                .map(|i| {
                    let t = total * i as f64 / (n - 1) as f64;
                    (r.angle_deg(t), r.state(t)[2])
                })
                .collect()
        };
        let acc_unit = u.acc_text();
        // Dwell / rise / return of every computed cycle, and the located peaks (their sign read
        // from the samples: the peak is of |x − s| and |x''|).
        let period = cycle.period_rad.to_degrees();
        let bands: Vec<XBand> =
            (0..cycles).flat_map(|k| crate::cycle::cycle_bands(&cycle, k as f64 * period)).collect();
        let unlabelled = || bands.iter().map(|b| XBand { label: String::new(), ..b.clone() }).collect::<Vec<_>>();
        let signed = |at: f64, v: f64, col: usize| {
            let near = samples.iter().min_by(|p, q| (p[0] - at).abs().total_cmp(&(q[0] - at).abs()));
            if near.is_some_and(|p| p[col] < 0.0) { -v } else { v }
        };
        let (e, acc) = (summary.peak_dynamic_error, summary.peak_acceleration);
        let e_val = signed(e.angle_deg, e.value * u.scale, 3);
        let a_val = signed(acc.angle_deg, acc.value, 4);
        let panels = vec![
            Panel::new(
                format!("position [{}]", u.pos),
                vec![
                    Series::line("input s", col(1, u.scale)),
                    Series::line("follower x", col(2, u.scale)).with_dashes(),
                ],
            )
            .with_x_bands(bands.clone()),
            Panel::new(format!("dynamic error x − s [{}]", u.pos), vec![Series::line("x − s", col(3, u.scale))])
                .with_x_bands(unlabelled())
                .with_notes([Note::new(
                    e.angle_deg,
                    e_val,
                    format!("|x − s| max {} {} at {}°", sig4(e_val.abs()), u.pos, sig4(e.angle_deg)),
                )]),
            Panel::new(
                format!("acceleration [{acc_unit}]"),
                vec![Series::line("input s''", acc_in), Series::line("follower x''", col(4, 1.0))],
            )
            .with_x_bands(unlabelled())
            .with_notes([Note::new(
                acc.angle_deg,
                a_val,
                format!("|x''| max {} {acc_unit} at {}°", sig4(a_val.abs()), sig4(acc.angle_deg)),
            )]),
        ];
        let title = format!(
            "{} at {} rpm, f_n {} Hz, ζ {}{}: residual {:.4} {} ({:.3} % of stroke)",
            util::file_name(&a.file),
            loomkin_units::compact(speed.rpm()),
            loomkin_units::compact(follower.natural_hz()),
            loomkin_units::compact(follower.damping_ratio()),
            if a.steady { ", steady state" } else { "" },
            summary.residual_amplitude_si * u.scale,
            u.pos,
            summary.residual_pct_of_stroke,
        );
        return output::figure(&Figure::new(title, "main-shaft angle [deg]", panels), &out, &a.plot);
    }
    let p = u.pos;
    outln!(
        "{} at {} rpm, f_n = {} Hz, ζ = {}, {}",
        a.file.display(),
        loomkin_units::compact(speed.rpm()),
        loomkin_units::compact(follower.natural_hz()),
        loomkin_units::compact(follower.damping_ratio()),
        if a.steady { "periodic steady state".to_string() } else { format!("{} cycle(s) from rest", a.cycles) }
    )?;
    outln!(
        "residual vibration (largest over the dwells): {:.6} {p} = {:.4} % of stroke",
        summary.residual_amplitude_si * u.scale,
        summary.residual_pct_of_stroke
    )?;
    for d in &summary.dwells {
        outln!("  dwell at {:>9.3}°: {:.6} {p}", d.angle_deg, d.amplitude_si * u.scale)?;
    }
    outln!(
        "peak dynamic error |x − s|: {:.6} {p} at {:.3}°",
        summary.peak_dynamic_error.value * u.scale,
        summary.peak_dynamic_error.angle_deg
    )?;
    outln!(
        "peak acceleration |x''|: {:.4} {} at {:.3}° (input |s''| {:.4})",
        summary.peak_acceleration.value,
        u.acc.replace('_', "/").replace("s2", "s²"),
        summary.peak_acceleration.angle_deg,
        summary.peak_input_acceleration.value
    )?;
    if let (Some(f), Some(c)) = (summary.peak_force_n, summary.min_contact_force_n) {
        outln!("peak train force |F|: {:.3} N at {:.3}°", f.value, f.angle_deg)?;
        outln!(
            "smallest contact force: {} N at {:.3}°{}",
            // A force that rounds to nothing at three places is given in four digits: a loss of
            // contact is never printed as "0.000 N" or "-0.000 N".
            if loomkin_units::fixed(c.value, 3).trim_start_matches(['0', '.']).is_empty() && c.value != 0.0 {
                loomkin_units::sig4(c.value)
            } else {
                format!("{:.3}", c.value)
            },
            c.angle_deg,
            if summary.loses_contact { " — a force-closed follower LOSES CONTACT" } else { "" }
        )?;
    }
    outln!("rigidity ratio f_n/f_shaft (VDI 2149): {:.3}", summary.rigidity_ratio)?;
    Ok(())
}

fn sweep_cmd(a: SweepArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    // Checked first, with or without a plot to draw it on (refused, not ignored).
    SweepPoint::RESIDUAL_LIMIT_PCT.check(a.residual_limit_pct)?;
    let cycle = read_cycle(&a.file)?;
    let follower = a.model.follower()?;
    let span = Span::parse("speed_rpm", &a.speed_rpm, ShaftSpeed::RANGE)?;
    a.shard.check(a.format)?;
    let items = a.shard.get().items(span.count());
    // Each speed of this shard is one response (closed form per segment of the cycle), in
    // parallel; its row is held until printed (as a JSON object with --json).
    let n = items.len() as f64;
    let row_bytes = if a.format.json { SweepPoint::JSON_ROW_BYTES } else { 0.0 };
    let cost = SweepPoint::cost(n, cycle.segments.len(), util::cores(), row_bytes);
    crate::util::check_budget("--speed-rpm", &a.speed_rpm, cost)?;
    let speeds: Vec<f64> = items.map(|i| span.value(i)).collect();
    let start = if a.steady { Start::Steady } else { Start::Rest };
    let progress = util::Progress::new(speeds.len() as u64, "speeds");
    let mut pts = Vec::with_capacity(speeds.len());
    for chunk in speeds.chunks(1024) {
        pts.extend(sweep(&cycle, &follower, chunk, start)?);
        progress.inc(chunk.len() as u64);
    }
    progress.finish();
    let u = units(&cycle);
    let p = u.pos;
    let forces = follower.mass_kg().is_some();
    let cols = sweep_columns(u, forces);
    let mut t = Table::new(cols);
    for q in &pts {
        t.push(sweep_row(q, u, forces))?;
    }
    if a.format.csv {
        return output::csv_shard(&t, a.shard.header());
    }
    if a.format.json && a.shard.given() {
        return output::json_lines(pts.iter().map(|q| SweepEntry { q, units: u, forces }));
    }
    if a.format.json {
        return output::json(&SweepReport {
            points: &pts,
            units: u,
            forces,
            natural_hz: follower.natural_hz(),
            damping_ratio: follower.damping_ratio(),
            start,
        });
    }
    if let Some(out) = a.output {
        let col = |f: &dyn Fn(&loomkin_dynamics::SweepPoint) -> f64| {
            pts.iter().map(|q| (q.speed_rpm, f(q))).collect::<Vec<_>>()
        };
        // The speeds to avoid: residual above the limit, their ends located on the model.
        let stroke_si = cycle.segments.iter().map(|s| s.stroke_si.abs()).fold(0.0, f64::max);
        let level_si = a.residual_limit_pct / 100.0 * stroke_si;
        let avoid = loomkin_dynamics::speeds_above(&cycle, &follower, &pts, start, level_si)?;
        let bands: Vec<XBand> = avoid.iter().map(|&[from, to]| XBand::new(from, to, "avoid", [200, 30, 30])).collect();
        let limit = Rule::y(
            level_si * u.scale,
            format!("limit {} % of stroke = {} {p}", sig4(a.residual_limit_pct), sig4(level_si * u.scale)),
        );
        // VDI 2149 Blatt 1 accepts the rigid model while f_n/f_shaft ≥ 10, i.e. up to 6·f_n rpm.
        let vdi_rpm = 60.0 * follower.natural_hz() / loomkin_dynamics::VDI_2149_MIN_RATIO;
        let (lo, hi) = (speeds[0], speeds[speeds.len() - 1]);
        let vdi = (vdi_rpm > lo.min(hi) && vdi_rpm < lo.max(hi)).then(|| {
            Rule::x(vdi_rpm, format!("f_n/f_shaft = 10 at {} rpm (VDI 2149)", sig4(vdi_rpm)))
                .with_color([90, 90, 90])
                .with_dash(loomkin_plot::Dash::DashDot)
        });
        let with_vdi = |p: Panel| match &vdi {
            Some(r) => p.with_rule(r.clone()),
            None => p,
        };
        let residual = col(&|q| q.residual_amplitude_si * u.scale);
        let error = col(&|q| q.peak_dynamic_error_si * u.scale);
        // --log-y: each panel from five decades under its largest value (the limit line included).
        let log = |panel: Panel, values: &[(f64, f64)], also: f64| {
            if a.log_y { panel.with_log_y_floor(log_floor(values.iter().map(|v| v.1).chain([also]))) } else { panel }
        };
        let log_note = if a.log_y { ", log" } else { "" };
        let mut panels = vec![
            with_vdi(log(
                Panel::new(
                    format!("residual amplitude{log_note} [{p}]"),
                    vec![Series::line("residual amplitude", residual.clone())],
                )
                .with_x_bands(bands.clone())
                .with_rule(limit),
                &residual,
                level_si * u.scale,
            )),
            with_vdi(log(
                Panel::new(format!("peak |x − s|{log_note} [{p}]"), vec![Series::line("", error.clone())])
                    .with_legend(Legend::Hidden)
                    .with_x_bands(bands.iter().map(|b| XBand { label: String::new(), ..b.clone() })),
                &error,
                0.0,
            )),
        ];
        if forces {
            panels.push(with_vdi(
                Panel::new(
                    "train force [N]",
                    vec![
                        Series::line("peak |F|", col(&|q| q.peak_force_n.unwrap_or(0.0))),
                        Series::line("smallest contact force", col(&|q| q.min_contact_force_n.unwrap_or(0.0)))
                            .with_dashes(),
                    ],
                )
                .with_x_bands(bands.iter().map(|b| XBand { label: String::new(), ..b.clone() })),
            ));
        }
        let title = format!(
            "{}: f_n {} Hz, ζ {}{}",
            util::file_name(&a.file),
            loomkin_units::compact(follower.natural_hz()),
            loomkin_units::compact(follower.damping_ratio()),
            if a.steady { ", steady state" } else { ", one cycle from rest" }
        );
        return output::figure(&Figure::new(title, "main-shaft speed [rpm]", panels), &out, &a.plot);
    }
    let worst = pts.iter().max_by(|x, y| x.residual_amplitude_si.total_cmp(&y.residual_amplitude_si));
    outln!(
        "{} speeds, {} to {} rpm",
        pts.len(),
        loomkin_units::compact(speeds[0]),
        loomkin_units::compact(speeds[speeds.len() - 1])
    )?;
    if let Some(w) = worst {
        outln!(
            "largest residual vibration {:.6} {p} ({:.4} % of stroke) at {} rpm",
            w.residual_amplitude_si * u.scale,
            w.residual_pct_of_stroke,
            loomkin_units::compact(w.speed_rpm)
        )?;
    }
    outln!("(--csv, --json or -o PLOT for the whole sweep)")?;
    Ok(())
}

/// The laws named on the command line: `(label, column key, law)`.
/// The laws of `dyn spectrum`: label, column key and law. The key is the law's name, with the
/// parameters given (`modified-trapezoid_ramp_0.1`) or the cycle file's name and the segment
/// (`heald-frame-cycle_modified-sine_seg1`); a key given twice gets `_2`, `_3`, … so every CSV
/// column has its own name.
fn spectrum_laws(tokens: &[String]) -> Result<Vec<(String, String, loomkin_laws::Law)>> {
    let mut out: Vec<(String, String, loomkin_laws::Law)> = Vec::new();
    for tok in tokens {
        if tok.ends_with(".toml") {
            let path = Path::new(tok);
            let cycle = read_cycle(path)?;
            let stem = path.file_stem().map_or_else(|| tok.clone(), |s| s.to_string_lossy().into_owned());
            for (i, seg) in cycle.segments.iter().enumerate() {
                if let Some((spec, law)) = &seg.law {
                    let key = format!("{stem}_{}_seg{i}", spec.name());
                    out.push((format!("{tok} #{i}: {}", spec.label()), key, law.clone()));
                }
            }
            continue;
        }
        let (name, params) = match tok.split_once(':') {
            Some((n, kv)) => (n, vec![util::parse_key_value(kv).map_err(anyhow::Error::msg)?]),
            None => (tok.as_str(), Vec::new()),
        };
        let (spec, law) = crate::law::build(name, &params)?;
        let key = params.iter().fold(spec.name().to_string(), |k, (p, v)| format!("{k}_{p}_{v}"));
        out.push((spec.label(), key, law));
    }
    let mut seen = std::collections::HashMap::<String, usize>::new();
    for (_, key, _) in &mut out {
        let n = seen.entry(key.clone()).or_insert(0);
        *n += 1;
        if *n > 1 {
            *key = format!("{key}_{n}");
        }
    }
    Ok(out)
}

fn spectrum_cmd(a: SpectrumArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let laws = spectrum_laws(&a.laws)?;
    let mut zetas = Vec::new();
    for z in a.damping_ratio.split(',') {
        let v: f64 = z.trim().parse().map_err(|_| anyhow::anyhow!("damping_ratio: '{z}' is not a number"))?;
        zetas.push(Follower::DAMPING_RATIO.check(v)?);
    }
    let span = Span::parse(loomkin_dynamics::RATIO.name, &a.ratio, loomkin_dynamics::RATIO.range)?;
    loomkin_dynamics::RATIOS.check_count(span.count())?;
    let ratios: Vec<f64> = span.values().collect();
    let mut series = Vec::new();
    for (label, key, law) in &laws {
        for &z in &zetas {
            let pct: Vec<f64> = loomkin_dynamics::spectrum(law, z, &ratios).into_iter().map(|v| 100.0 * v).collect();
            series.push((label.clone(), key.clone(), z, pct));
        }
    }
    if a.csv {
        let mut cols = vec!["motion_time_over_natural_period".to_string()];
        for (_, key, z, _) in &series {
            cols.push(format!("residual_pct_of_stroke_{key}_zeta_{}", loomkin_units::compact(*z)));
        }
        let mut t = Table::new(cols);
        for (i, r) in ratios.iter().enumerate() {
            let mut row = vec![*r];
            row.extend(series.iter().map(|s| s.3[i]));
            t.push(row)?;
        }
        return output::csv(&t);
    }
    if let Some(out) = a.output {
        let lines = series
            .iter()
            .map(|(label, _, z, pct)| {
                let name =
                    if zetas.len() > 1 { format!("{label}, ζ {}", loomkin_units::compact(*z)) } else { label.clone() };
                Series::line(name, ratios.iter().copied().zip(pct.iter().copied()).collect())
            })
            .collect();
        let title = if zetas.len() == 1 {
            format!("residual vibration after a rise, ζ = {}", loomkin_units::compact(zetas[0]))
        } else {
            "residual vibration after a rise".to_string()
        };
        // The log panel starts five decades under the largest value: the exact zeros of the
        // residual (and the rounding noise around them) are not drawn, nor raised to a floor.
        let floor = log_floor(series.iter().flat_map(|s| s.3.iter().copied()));
        let logs = series
            .iter()
            .map(|(label, _, z, pct)| {
                let name =
                    if zetas.len() > 1 { format!("{label}, ζ {}", loomkin_units::compact(*z)) } else { label.clone() };
                Series::line(name, ratios.iter().copied().zip(pct.iter().copied()).collect())
            })
            .collect();
        let title = format!("{title}; log panel from {} % (5 decades under the largest)", sig4(floor));
        let panels = vec![
            Panel::new("residual amplitude [% of stroke]", lines),
            Panel::new("residual amplitude, log [% of stroke]", logs)
                .with_log_y_floor(floor)
                .with_legend(Legend::Hidden),
        ];
        return output::figure(&Figure::new(title, "motion time / natural period  T·f_n [-]", panels), &out, &a.plot);
    }
    // The label column is 44 characters wide, or as wide as the longest label (a cycle file's).
    let w = series.iter().map(|s| s.0.chars().count()).fold(44, usize::max);
    outln!("{:<w$} {:>8} {:>14} {:>8}", "law", "ζ", "max [%]", "at r")?;
    for (label, _, z, pct) in &series {
        let (i, m) = pct.iter().enumerate().fold((0, 0.0), |acc, (i, &v)| if v > acc.1 { (i, v) } else { acc });
        outln!("{:<w$} {:>8} {:>14.6} {:>8.3}", label, loomkin_units::compact(*z), m, ratios[i])?;
    }
    outln!("(--csv or -o PLOT for the whole spectrum)")?;
    Ok(())
}

/// The floor of a log panel: the decade five under the largest finite value (1e-6 when none is
/// above zero), so exact zeros and the rounding noise around them are not drawn.
fn log_floor(values: impl Iterator<Item = f64>) -> f64 {
    let top = values.filter(|v| v.is_finite()).fold(0.0, f64::max);
    if top > 0.0 { 10f64.powf(top.log10().floor() - 5.0) } else { 1e-6 }
}

fn compensate_cmd(a: CompensateArgs) -> Result<()> {
    output::check_outputs([Some(Out::file("--output", &a.output))])?;
    let cycle = read_cycle(&a.file)?;
    let speed = speed_of(a.speed_rpm, &cycle)?;
    let follower = a.model.follower()?;
    Compensation::POINTS.check_count(a.points)?;
    if !(a.output.ends_with(".csv") || a.output.ends_with(".toml") || a.output == "-") {
        anyhow::bail!("output = {}: give OUT.csv, OUT.toml or - (CSV on standard output)", a.output);
    }
    let exc = loomkin_dynamics::Excitation::from_cycle(&cycle, speed);
    let comp = loomkin_dynamics::compensate(&exc, &follower)?;
    let u = units(&cycle);
    let p = u.pos;
    let (vel, acc) = if p == "mm" { ("m_s", "m_s2") } else { ("rad_s", "rad_s2") };
    let smooth = match comp.input_class {
        0 => "continuous, but its velocity jumps (a cam needs a smoother designed law: x''' continuous)",
        1 => "continuous velocity, its acceleration jumps",
        _ => "continuous acceleration",
    };
    output::note(format_args!(
        "designed motion C{}, compensated input C{}: {smooth}{}",
        comp.designed_class,
        comp.input_class,
        if follower.damping_ratio() > 0.0 {
            " (damped: the periodic solution of the first-order input equation)"
        } else {
            ""
        }
    ));
    if a.output.ends_with(".toml") {
        let mut text = format!(
            "# The compensated input of {} (loomkin dyn compensate).\n\
             # Per piece, SI units, t in s from the piece's start:\n\
             # s(t) = sum(poly[k]·t^k) + sin_cos[0]·sin(Ωt) + sin_cos[1]·cos(Ωt) + exp[0]·e^(−exp[1]·t), Ω = omega_rad_s.\n\
             unit = \"{}\"\nspeed_rpm = {}\nnatural_hz = {}\ndamping_ratio = {}\ndesigned_class = {}\ninput_class = {}\n",
            a.file.display(),
            if p == "mm" { "m" } else { "rad" },
            speed.rpm(),
            follower.natural_hz(),
            follower.damping_ratio(),
            comp.designed_class,
            comp.input_class,
        );
        let fmt = |v: &[f64]| v.iter().map(|c| format!("{c:e}")).collect::<Vec<_>>().join(", ");
        for piece in &comp.pieces {
            text.push_str(&format!(
                "\n[[piece]]\nfrom_deg = {}\nto_deg = {}\npoly = [{}]\n",
                exc.angle_deg(piece.t0),
                exc.angle_deg(piece.t0 + piece.duration),
                fmt(&piece.poly)
            ));
            if let Some((bs, bc, w)) = piece.sine {
                text.push_str(&format!("sin_cos = [{}]\nomega_rad_s = {w:e}\n", fmt(&[bs, bc])));
            }
            if let Some((c, r)) = piece.exp {
                text.push_str(&format!("exp = [{}]\n", fmt(&[c, r])));
            }
        }
        return output::text_to(&a.output, &text);
    }
    let mut t = Table::new([
        "angle_deg".to_string(),
        format!("x_{p}"),
        format!("s_{p}"),
        format!("s_velocity_{vel}"),
        format!("s_acceleration_{acc}"),
    ]);
    for [angle, x, s, v, acc] in comp.samples(&exc, a.points) {
        t.push(vec![angle, x * u.scale, s * u.scale, v, acc])?;
    }
    let mut text = Vec::new();
    t.write_csv(&mut text).map_err(util::failure)?;
    output::text_to(&a.output, &String::from_utf8_lossy(&text))
}

fn optimize_cmd(a: OptimizeArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::file("--output", p))])?;
    let text = util::read_input(&a.file)?;
    let cycle = read_cycle(&a.file)?;
    let speed = speed_of(a.speed_rpm, &cycle)?;
    let follower = a.model.follower()?;
    // One step per move shaped and per band response, a count the library estimates until its
    // last call: an open-ended line.
    let bar = util::Progress::open_ended("dyn optimize: steps");
    let opt =
        loomkin_dynamics::optimize_cycle_with(&text, speed, a.band_pct, &follower, &|done, _| bar.set(done as u64))?;
    bar.finish();
    let u = units(&cycle);
    let p = u.pos;
    if let Some(out) = &a.output {
        output::text_to(out, &opt.cycle_toml)?;
    }
    let improvement = opt.improvement_factor();
    if a.json {
        return output::json(&loomkin_dynamics::OptimizeReport {
            optimized: &opt,
            units: u,
            speed_rpm: speed.rpm(),
            band_pct: a.band_pct,
            natural_hz: follower.natural_hz(),
            damping_ratio: follower.damping_ratio(),
        });
    }
    if a.output.as_deref() == Some("-") {
        return Ok(());
    }
    outln!(
        "across {} rpm ± {} %: largest dwell residual {:.6} {p} (modified sine {:.6} {p}): {:.1}× lower",
        loomkin_units::compact(speed.rpm()),
        loomkin_units::compact(a.band_pct),
        opt.cycle_residual_si * u.scale,
        opt.cycle_residual_modified_sine_si * u.scale,
        improvement
    )?;
    outln!("peak input acceleration: {:.3} × the modified sine's", opt.peak_acceleration_ratio)?;
    for s in &opt.segments {
        outln!(
            "  segment {}: T·f_n {:.3}…{:.3}, residual after the motion {:.3e} of stroke (modified sine {:.3e}), Ca ratio {:.4}",
            s.segment,
            s.ratio_band[0],
            s.ratio_band[1],
            s.residual,
            s.residual_modified_sine,
            s.ca_ratio
        )?;
    }
    Ok(())
}

fn two_mass_cmd(a: TwoMassArgs) -> Result<()> {
    let cycle = read_cycle(&a.file)?;
    let speed = speed_of(a.speed_rpm, &cycle)?;
    let tm = loomkin_dynamics::TwoMass::new(
        a.drive_mass_kg,
        a.drive_stiffness_n_m,
        a.frame_mass_kg,
        a.frame_stiffness_n_m,
        a.damping_ratio,
    )?;
    let exc = loomkin_dynamics::Excitation::from_cycle(&cycle, speed);
    let start = if a.steady { Start::Steady } else { Start::Rest };
    let u = units(&cycle);
    let p = u.pos;
    let r = tm.report(&exc, speed, start, u)?;
    if a.json {
        return output::json(&r);
    }
    let hz = r.natural_hz;
    if r.rigidity_ratio < loomkin_dynamics::VDI_2149_MIN_RATIO {
        output::warning(format!(
            "rigidity ratio f_1/f_shaft = {} is below 10 (VDI 2149 Blatt 1): read the elastic response",
            loomkin_units::compact(r.rigidity_ratio)
        ));
    }
    outln!(
        "{} at {} rpm, two masses, ζ = {}, {}",
        a.file.display(),
        loomkin_units::compact(speed.rpm()),
        loomkin_units::compact(a.damping_ratio),
        if a.steady { "periodic steady state" } else { "one cycle from rest" }
    )?;
    outln!("natural frequencies: {:.4} Hz, {:.4} Hz", hz[0], hz[1])?;
    let (d, f) = (r.peak_drive_error, r.peak_frame_error);
    outln!("peak drive error |x1 − s|: {:.6} {p} at {:.3}°", d.value * u.scale, d.angle_deg)?;
    outln!("peak frame error |x2 − s|: {:.6} {p} at {:.3}°", f.value * u.scale, f.angle_deg)?;
    outln!("frame residual vibration in the dwells (bound, largest): {:.6} {p}", r.frame_residual_bound_si * u.scale)?;
    outln!("rigidity ratio f_1/f_shaft (VDI 2149): {:.3}", r.rigidity_ratio)?;
    Ok(())
}
