//! `loomkin dobby …`: the modulator of a Stäubli-type rotary dobby (series 2600): analysis of a
//! given cam (task 1), synthesis of the conjugate cams for an output law (task 2), plots, α sweep.

use crate::output::{self, Out, outln};
use crate::util::{self, Format};
use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand, ValueEnum};
use loomkin_io::Table;
use loomkin_io::dxf::{DxfShape, DxfUnit, save_shapes};
use loomkin_laws::LawSpec;
use loomkin_mech::{
    AlphaSweep, Analysis, AnalysisOptions, Cam, CamProfile, DobbyInputs, GivenLength, MechError, ModulatorGeometry,
    ModulatorState, OutputLawSpec, Synthesis, SynthesisOptions, Warning, alpha_sweep, analyze, nearest_state,
    parse_point_table, synthesize,
};
use loomkin_plot::{Dash, Figure, Legend, Note, PALETTE, Panel, Rule, Series, sig4};
use std::path::PathBuf;

/// Subcommands of `loomkin dobby`.
#[derive(Debug, Subcommand)]
pub enum DobbyCommand {
    /// Task 1: the motion produced by a given cam Γ (roller-centre curve) over one input turn.
    Analyze(AnalyzeArgs),
    /// Task 2: cam Γ and counter-cam Γ′ (roller-centre curves and groove walls) for an output law.
    Synthesize(SynthesizeArgs),
    /// The law (φ6, ω6, ε6 against φ2) or the cams with the mechanism drawn at an angle.
    Plot(PlotArgs),
    /// The α sweep of the paper: analysis of the cam and synthesis of the law for each α (θ = α).
    Sweep(SweepArgs),
    /// Tolerance study: link lengths, lever angles and cam semi-axes drawn from stated distributions (TOML);
    /// output-angle error, pressure angle, dead-point margin as percentiles, histograms, share failing.
    Tolerance(crate::dobby_tolerance::ToleranceArgs),
}

/// Link lengths and lever angles; defaults are the paper's (eq. 10).
#[derive(Debug, Args, Clone)]
pub struct GeometryArgs {
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Angle α between the slot and the arm AB, deg (the paper studies 30…60; its figures and the default are at 47)", &ModulatorGeometry::ALPHA_DEG))]
    alpha_deg: Option<f64>,
    /// Angle θ between the slot and the arm AC, deg (default: θ = α, a symmetric lever).
    #[arg(long, allow_hyphen_values = true)]
    theta_deg: Option<f64>,
    /// Input crank OA, m.
    #[arg(long, default_value_t = ModulatorGeometry::L2_M.default_value(), allow_hyphen_values = true)]
    l2_m: f64,
    /// Arm AB to the cam roller, m.
    #[arg(long, default_value_t = ModulatorGeometry::L3_M.default_value(), allow_hyphen_values = true)]
    l3_m: f64,
    /// Arm AC to the counter-cam roller, m.
    #[arg(long, default_value_t = ModulatorGeometry::L3P_M.default_value(), allow_hyphen_values = true)]
    l3p_m: f64,
    /// Output crank OD, m (< l2).
    #[arg(long, default_value_t = ModulatorGeometry::L6_M.default_value(), allow_hyphen_values = true)]
    l6_m: f64,
    #[arg(long, alias = "input-rpm", allow_hyphen_values = true, help = util::field_help("Input (main-shaft) speed, rpm (left out: ω2 = 1 rad/s as in the paper, so rates read as ratios)", &DobbyInputs::SPEED_RPM))]
    speed_rpm: Option<f64>,
    /// Pressure angles above this raise a warning, deg.
    #[arg(long, default_value_t = DobbyInputs::PRESSURE_LIMIT_DEG.default_value(), allow_hyphen_values = true)]
    pressure_limit_deg: f64,
}

impl GeometryArgs {
    fn geometry(&self) -> Result<ModulatorGeometry> {
        Ok(ModulatorGeometry::from_inputs(self.l2_m, self.l3_m, self.l3p_m, self.l6_m, self.alpha_deg, self.theta_deg)?)
    }

    fn speed_rad_s(&self) -> Result<f64> {
        Ok(DobbyInputs::speed_rad_s("--speed-rpm", self.speed_rpm)?)
    }
}

/// The cam of task 1.
#[derive(Debug, Args, Clone)]
pub struct CamArgs {
    #[arg(long, value_name = "ellipse:a=…,b=…", help = format!("The cam's roller-centre curve, `ellipse:a=A,b=B` (m); default the paper's a={}, b={}", loomkin_units::compact(loomkin_mech::Ellipse::PAPER.a_m), loomkin_units::compact(loomkin_mech::Ellipse::PAPER.b_m)))]
    cam: Option<String>,
    /// The cam as a point table of roller-centre points in metres, in order around the curve (≥ 8
    /// distinct points, a repeated closing point is dropped): one point per line, separated by
    /// commas, semicolons or blanks, `#` comments; a header picks the columns x_m,y_m (or x,y or
    /// b_x_m,b_y_m as written by `synthesize --csv`), else the first two. Fitted by a periodic
    /// cubic spline in chord length.
    #[arg(long, value_name = "FILE", conflicts_with = "cam")]
    cam_file: Option<PathBuf>,
}

impl CamArgs {
    fn cam(&self) -> Result<Cam> {
        if let Some(path) = &self.cam_file {
            let text = util::read_input(path)?;
            let pts = parse_point_table(&text).with_context(|| format!("{}", path.display()))?;
            return Cam::from_points(&pts).with_context(|| format!("{}", path.display()));
        }
        match &self.cam {
            None => Ok(Cam::paper()),
            Some(spec) => parse_ellipse(spec),
        }
    }
}

fn parse_ellipse(spec: &str) -> Result<Cam> {
    let usage = "expected --cam ellipse:a=A,b=B with the semi-axes in m, e.g. ellipse:a=0.366,b=0.577";
    let Some(rest) = spec.trim().strip_prefix("ellipse:") else { bail!("--cam '{spec}': {usage}") };
    let (mut a, mut b) = (None, None);
    for kv in rest.split(',') {
        let (k, v) = util::parse_key_value(kv).map_err(|e| anyhow::anyhow!("--cam '{spec}': {e}; {usage}"))?;
        let v: f64 = v.parse().map_err(|_| anyhow::anyhow!("--cam '{spec}': '{v}' is not a number; {usage}"))?;
        match k.as_str() {
            "a" => a = Some(v),
            "b" => b = Some(v),
            _ => bail!("--cam '{spec}': unknown key '{k}'; {usage}"),
        }
    }
    let (Some(a), Some(b)) = (a, b) else { bail!("--cam '{spec}': {usage}") };
    Ok(Cam::ellipse(a, b)?)
}

/// The output law of task 2.
#[derive(Debug, Args, Clone)]
pub struct LawArgs {
    /// Dwell of the output per cycle, deg of input.
    #[arg(long, default_value_t = OutputLawSpec::DWELL_DEG.default_value(), allow_hyphen_values = true)]
    dwell_deg: f64,
    /// Input angle at the centre of the first dwell, also the output angle held there, deg.
    #[arg(long, default_value_t = OutputLawSpec::DWELL_CENTRE_DEG.default_value(), allow_hyphen_values = true)]
    dwell_centre_deg: f64,
    /// Cycles (dwell + rise of 360°/cycles) per input turn.
    #[arg(long, default_value_t = OutputLawSpec::CYCLES.default_count() as u32)]
    cycles: u32,
    /// Shape of each rise: a law of the catalogue (see `loomkin law list`).
    #[arg(long, default_value = OutputLawSpec::DEFAULT_LAW)]
    law: String,
    /// A parameter of --law, e.g. `--param ramp=0.1`.
    #[arg(long = "param", value_name = "KEY=VALUE", value_parser = util::parse_key_value)]
    params: Vec<(String, String)>,
}

impl LawArgs {
    fn spec(&self) -> Result<OutputLawSpec> {
        let rise = LawSpec::parse(&self.law, &self.params)?;
        Ok(OutputLawSpec {
            cycles: self.cycles,
            dwell_deg: self.dwell_deg,
            dwell_centre_deg: self.dwell_centre_deg,
            rise,
        })
    }
}

/// The radius of both rollers (groove walls, undercut check), in mm as the workbench and `cam
/// profile --roller-radius-mm`, or in m (`--roller-m`, the first flag, kept).
#[derive(Debug, Args)]
pub struct RollerArgs {
    #[arg(long, value_name = "MM", allow_hyphen_values = true, conflicts_with = "roller_m", help = util::field_help("Roller radius, mm (the default where the cams are synthesised; none for a given cam)", &DobbyInputs::ROLLER_MM))]
    roller_mm: Option<f64>,
    #[arg(long, value_name = "M", allow_hyphen_values = true, help = util::field_help("Roller radius, m (as --roller-mm)", &DobbyInputs::ROLLER_M))]
    roller_m: Option<f64>,
}

impl RollerArgs {
    /// The roller radius in m, if given; the library checks either flag against its descriptor
    /// ([`DobbyInputs::ROLLER_MM`], [`DobbyInputs::ROLLER_M`]), naming the flag and the range in its unit.
    fn metres(&self) -> Result<Option<f64>> {
        Ok(DobbyInputs::roller_m("--roller-mm", self.roller_mm, self.roller_m)?)
    }

    /// The roller radius in m, [`DobbyInputs::ROLLER_M`]'s default unless given (the cams are
    /// synthesised with a roller).
    fn metres_or_default(&self) -> Result<f64> {
        Ok(self.metres()?.unwrap_or(DobbyInputs::ROLLER_M.default_value()))
    }
}

/// `dobby analyze`.
#[derive(Debug, Args)]
pub struct AnalyzeArgs {
    #[command(flatten)]
    geometry: GeometryArgs,
    #[command(flatten)]
    cam: CamArgs,
    #[arg(long, default_value_t = DobbyInputs::STEP_DEG.default_value(), allow_hyphen_values = true, help = util::range_help("Input step, deg", &DobbyInputs::STEP_DEG))]
    step_deg: f64,
    #[command(flatten)]
    roller: RollerArgs,
    #[command(flatten)]
    format: Format,
}

/// `dobby synthesize`.
#[derive(Debug, Args)]
pub struct SynthesizeArgs {
    #[command(flatten)]
    geometry: GeometryArgs,
    #[command(flatten)]
    law: LawArgs,
    #[command(flatten)]
    roller: RollerArgs,
    #[arg(long, default_value_t = DobbyInputs::STEP_DEG.default_value(), allow_hyphen_values = true, help = util::range_help("Input step, deg", &DobbyInputs::STEP_DEG))]
    step_deg: f64,
    #[command(flatten)]
    format: Format,
    /// Write the cams (roller-centre curves and groove walls) as DXF polylines to this file.
    #[arg(long, value_name = "FILE")]
    dxf: Option<PathBuf>,
    /// Unit of the DXF coordinates.
    #[arg(long, value_enum, default_value_t = UnitArg::Mm)]
    dxf_unit: UnitArg,
    /// Chord tolerance of the DXF polylines, mm (the curves are drawn within it whatever --step-deg).
    #[arg(
        long,
        value_name = "T",
        default_value_t = loomkin_mech::Synthesis::CHORD_TOL_MM.default_value(),
        allow_hyphen_values = true,
        requires = "dxf"
    )]
    chord_tol_mm: f64,
    #[arg(long, value_name = "D", allow_hyphen_values = true, requires = "dxf", help = format!("Bore diameter about the crank centre drawn in the DXF, mm (0: none; left out: {} × the cams' least radius)", loomkin_io::drawing::DEFAULT_BORE_FRACTION))]
    bore_mm: Option<f64>,
    /// Write the cam point tables (centre curves and walls of Γ and Γ′) as CSV to this file.
    #[arg(long, value_name = "FILE")]
    points_csv: Option<PathBuf>,
}

/// `--dxf-unit`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum UnitArg {
    /// Millimetres.
    Mm,
    /// Metres.
    M,
}

/// `--what` of `dobby plot`.
#[derive(Debug, Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum WhatArg {
    /// φ6, ω6, ε6 (and φ3) against φ2.
    Law,
    /// The cams with the mechanism drawn at `--at-deg`.
    Cams,
}

/// `--task` of `dobby plot`.
#[derive(Debug, Clone, Copy, ValueEnum, PartialEq, Eq)]
pub enum TaskArg {
    /// Task 1: the given cam (`--cam`, `--cam-file`).
    Analyze,
    /// Task 2: the output law (`--dwell-deg`, `--law`, …).
    Synthesize,
}

/// `dobby plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// Which task to plot.
    #[arg(long, value_enum, default_value_t = TaskArg::Synthesize)]
    task: TaskArg,
    /// What to draw.
    #[arg(long, value_enum, default_value_t = WhatArg::Law)]
    what: WhatArg,
    /// Input angle at which the mechanism is drawn (with --what cams), deg.
    #[arg(long, default_value_t = DobbyInputs::AT_DEG.default_value(), allow_hyphen_values = true)]
    at_deg: f64,
    #[command(flatten)]
    geometry: GeometryArgs,
    #[command(flatten)]
    cam: CamArgs,
    #[command(flatten)]
    law: LawArgs,
    #[command(flatten)]
    roller: RollerArgs,
    /// Input step, deg.
    #[arg(long, default_value_t = DobbyInputs::PLOT_STEP_DEG.default_value(), allow_hyphen_values = true)]
    step_deg: f64,
    /// Output file, .svg or .png.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// `dobby sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// First α, deg.
    #[arg(long, default_value_t = AlphaSweep::FROM.default_value(), allow_hyphen_values = true)]
    from: f64,
    /// Last α, deg.
    #[arg(long, default_value_t = AlphaSweep::TO.default_value(), allow_hyphen_values = true)]
    to: f64,
    /// α step, deg.
    #[arg(long, default_value_t = AlphaSweep::BY.default_value(), allow_hyphen_values = true)]
    by: f64,
    #[command(flatten)]
    geometry: GeometryArgs,
    #[command(flatten)]
    cam: CamArgs,
    #[command(flatten)]
    law: LawArgs,
    #[command(flatten)]
    roller: RollerArgs,
    /// Input step, deg.
    #[arg(long, default_value_t = DobbyInputs::STEP_DEG.default_value(), allow_hyphen_values = true)]
    step_deg: f64,
    #[command(flatten)]
    format: Format,
    #[command(flatten)]
    shard: crate::shard::ShardArgs,
}

/// Runs a `dobby` subcommand.
pub fn run(cmd: DobbyCommand) -> Result<()> {
    match cmd {
        DobbyCommand::Analyze(a) => analyze_cmd(a),
        DobbyCommand::Synthesize(a) => synthesize_cmd(a),
        DobbyCommand::Plot(a) => plot_cmd(a),
        DobbyCommand::Sweep(a) => sweep_cmd(a),
        DobbyCommand::Tolerance(a) => crate::dobby_tolerance::run(a),
    }
}

fn warn(ws: &[Warning]) {
    for w in ws {
        output::warning(&w.message);
    }
}

fn analysis_options(g: &GeometryArgs, step_deg: f64, roller_m: Option<f64>) -> Result<AnalysisOptions> {
    Ok(AnalysisOptions {
        step_deg,
        input_speed_rad_s: g.speed_rad_s()?,
        roller_m,
        pressure_limit_deg: g.pressure_limit_deg,
        ..AnalysisOptions::default()
    })
}

fn synthesis_options(g: &GeometryArgs, step_deg: f64, roller_m: f64) -> Result<SynthesisOptions> {
    Ok(SynthesisOptions {
        step_deg,
        input_speed_rad_s: g.speed_rad_s()?,
        roller_m,
        pressure_limit_deg: g.pressure_limit_deg,
    })
}

const ANALYSIS_COLUMNS: [&str; 21] = [
    "phi2_deg",
    "t_s",
    "phi3_deg",
    "phi6_deg",
    "s53_m",
    "omega3_rad_s",
    "omega6_rad_s",
    "v53_m_s",
    "eps3_rad_s2",
    "eps6_rad_s2",
    "a53_m_s2",
    "b_x_m",
    "b_y_m",
    "c_x_m",
    "c_y_m",
    "mu_out_deg",
    "mu_b_deg",
    "mu_c_deg",
    "kappa_b_1_m",
    "kappa_c_1_m",
    "cam_param",
];

fn analysis_table(a: &Analysis) -> Result<Table> {
    let mut t = Table::new(ANALYSIS_COLUMNS);
    for r in &a.rows {
        t.push(vec![
            r.phi2_deg,
            r.t_s,
            r.phi3_deg,
            r.phi6_deg,
            r.s53_m,
            r.omega3_rad_s,
            r.omega6_rad_s,
            r.v53_m_s,
            r.eps3_rad_s2,
            r.eps6_rad_s2,
            r.a53_m_s2,
            r.b_x_m,
            r.b_y_m,
            r.c_x_m,
            r.c_y_m,
            r.mu_out_deg,
            r.mu_b_deg,
            r.mu_c_deg,
            r.kappa_b_1_m,
            r.kappa_c_1_m,
            r.cam_param,
        ])?;
    }
    Ok(t)
}

const SYNTHESIS_COLUMNS: [&str; 16] = [
    "phi2_deg",
    "phi6_deg",
    "omega6_rad_s",
    "eps6_rad_s2",
    "phi3_deg",
    "omega3_rad_s",
    "s53_m",
    "b_x_m",
    "b_y_m",
    "c_x_m",
    "c_y_m",
    "mu_out_deg",
    "mu_b_deg",
    "mu_c_deg",
    "kappa_b_1_m",
    "kappa_c_1_m",
];

fn synthesis_table(s: &Synthesis) -> Result<Table> {
    let mut t = Table::new(SYNTHESIS_COLUMNS);
    for r in &s.rows {
        t.push(vec![
            r.phi2_deg,
            r.phi6_deg,
            r.omega6_rad_s,
            r.eps6_rad_s2,
            r.phi3_deg,
            r.omega3_rad_s,
            r.s53_m,
            r.b_x_m,
            r.b_y_m,
            r.c_x_m,
            r.c_y_m,
            r.mu_out_deg,
            r.mu_b_deg,
            r.mu_c_deg,
            r.kappa_b_1_m,
            r.kappa_c_1_m,
        ])?;
    }
    Ok(t)
}

fn analyze_cmd(a: AnalyzeArgs) -> Result<()> {
    let g = a.geometry.geometry()?;
    let cam = a.cam.cam()?;
    let res = analyze(&g, &cam, &analysis_options(&a.geometry, a.step_deg, a.roller.metres()?)?)?;
    warn(&res.warnings);
    if a.format.csv {
        return output::csv(&analysis_table(&res)?);
    }
    if a.format.json {
        return output::json(&res.report());
    }
    let s = &res.summary;
    let c = &s.checks;
    outln!("rotary-dobby modulator, task 1 (analysis): cam {}", s.cam)?;
    print_geometry(&g, s.input_speed_rad_s, s.step_deg)?;
    // At a crawl (0.001 rpm) the rates round to zero: no sign on a zero.
    let f = loomkin_units::fixed;
    outln!(
        "  output speed ω6      {} … {} rad/s ({:.4} … {:.4} × ω2)",
        f(c.omega6_min_rad_s, 5),
        f(c.omega6_max_rad_s, 5),
        c.omega6_min_rad_s / s.input_speed_rad_s,
        c.omega6_max_rad_s / s.input_speed_rad_s
    )?;
    outln!("  output accel. ε6     {} … {} rad/s²", f(c.eps6_min_rad_s2, 5), f(c.eps6_max_rad_s2, 5))?;
    print_checks(c)?;
    outln!(
        "  |φ3 − φ2| max        {:.3}° (limit arcsin(l6/l2) = {:.3}°); admissible α for this cam: {:.3}° … {:.3}°",
        s.slot_deviation_max_deg,
        s.slot_deviation_limit_deg,
        s.admissible_alpha_deg[0],
        s.admissible_alpha_deg[1]
    )?;
    Ok(())
}

fn print_geometry(g: &ModulatorGeometry, w2: f64, step: f64) -> Result<()> {
    use loomkin_units::compact;
    outln!(
        "  l2 = {} m, l3 = {} m, l3′ = {} m, l6 = {} m, α = {}°, θ = {}°, ω2 = {:.6} rad/s, step {:.4}°",
        compact(g.l2_m),
        compact(g.l3_m),
        compact(g.l3p_m),
        compact(g.l6_m),
        compact(g.alpha_deg),
        compact(g.theta_deg),
        w2,
        step
    )
}

fn print_checks(c: &loomkin_mech::CamChecks) -> Result<()> {
    let rho = |v: Option<f64>| v.map(|r| format!("{r:.5} m")).unwrap_or_else(|| "straight".into());
    outln!("  output turn          {:.6}° per input turn", c.phi6_turn_deg)?;
    outln!("  pressure angle μ6    max {:.2}° at φ2 = {:.2}° (output)", c.mu_out_max_deg, c.mu_out_max_at_phi2_deg)?;
    outln!("  pressure angle μB    max {:.2}° at φ2 = {:.2}° (roller B on Γ)", c.mu_b_max_deg, c.mu_b_max_at_phi2_deg)?;
    outln!(
        "  pressure angle μC    max {:.2}° at φ2 = {:.2}° (roller C on Γ′)",
        c.mu_c_max_deg,
        c.mu_c_max_at_phi2_deg
    )?;
    outln!("  min radius of curv.  Γ {} at φ2 = {:.2}°", rho(c.rho_b_min_m), c.rho_b_min_at_phi2_deg)?;
    outln!("                       Γ′ {} at φ2 = {:.2}°", rho(c.rho_c_min_m), c.rho_c_min_at_phi2_deg)?;
    outln!(
        "  closure              Γ {:.3e} m, Γ′ {:.3e} m; self-crossings Γ {}, Γ′ {}",
        c.closure_gap_b_m,
        c.closure_gap_c_m,
        c.self_intersections_b,
        c.self_intersections_c
    )
}

fn synthesize_cmd(a: SynthesizeArgs) -> Result<()> {
    output::check_outputs([
        a.dxf.as_ref().map(|p| Out::file("--dxf", p)),
        a.points_csv.as_ref().map(|p| Out::file("--points-csv", p)),
    ])?;
    let g = a.geometry.geometry()?;
    let law = a.law.spec()?;
    let res = synthesize(&g, &law, &synthesis_options(&a.geometry, a.step_deg, a.roller.metres_or_default()?)?)?;
    warn(&res.warnings);
    // As `cam profile`: an undercut cam is reported (the warning above names the angle and the
    // admissible roller) but never drawn; with --dxf the report is printed, then exit 2.
    let refused = a.dxf.is_some() && res.summary.undercut;
    if let Some(path) = a.dxf.as_ref().filter(|_| !refused) {
        let shapes: Vec<DxfShape> = loomkin_mech::dobby_export::synthesis_shapes(&res, a.chord_tol_mm, a.bore_mm)?;
        let unit = match a.dxf_unit {
            UnitArg::Mm => DxfUnit::Millimetre,
            UnitArg::M => DxfUnit::Metre,
        };
        save_shapes(&shapes, unit, path).map_err(util::failure)?;
        output::note(format_args!("wrote {}", path.display()));
    }
    if let Some(path) = &a.points_csv {
        let mut f = loomkin_io::create_file(path).map_err(util::failure)?;
        loomkin_mech::dobby_export::synthesis_points_table(&res)?.write_csv(&mut f).map_err(util::failure)?;
        output::note(format_args!("wrote {}", path.display()));
    }
    let report = || -> Result<()> {
        if a.format.csv {
            return output::csv(&synthesis_table(&res)?);
        }
        if a.format.json {
            return output::json(&res.report());
        }
        if (a.dxf.is_some() && !refused) || a.points_csv.is_some() {
            return Ok(());
        }
        let s = &res.summary;
        outln!("rotary-dobby modulator, task 2 (synthesis): {}", s.law)?;
        print_geometry(&g, s.input_speed_rad_s, s.step_deg)?;
        outln!("  roller radius        {} mm", loomkin_units::compact(loomkin_units::mm_from_m(s.roller_m)))?;
        outln!(
            "  output speed ω6      max {} rad/s; ε6 {} … {} rad/s²",
            loomkin_units::fixed(s.checks.omega6_max_rad_s, 5),
            loomkin_units::fixed(s.checks.eps6_min_rad_s2, 5),
            loomkin_units::fixed(s.checks.eps6_max_rad_s2, 5)
        )?;
        outln!("  |φ6 − φ2| max        {:.3}° (limit arccos(l6/l2) = {:.3}°)", s.lag_max_deg, s.lag_limit_deg)?;
        print_checks(&s.checks)?;
        outln!(
            "  undercut             Γ {}, Γ′ {}; largest roller without undercut {}",
            yes_no(s.undercut_b),
            yes_no(s.undercut_c),
            s.checks
                .roller_max_m
                .map(|r| format!("{:.2} mm", loomkin_units::mm_from_m(r)))
                .unwrap_or_else(|| "any".into())
        )?;
        outln!(
            "  admissible α         ({:.3}°, {:.3}°) for this law (no fold at roller B)",
            s.admissible_alpha_deg[0],
            s.admissible_alpha_deg[1]
        )?;
        Ok(())
    };
    report()?;
    if refused {
        // Said in the unit the roller was given in (`--roller-mm 400`: a 400 mm roller).
        let (flag, unit) = if a.roller.roller_mm.is_some() {
            ("roller_mm", GivenLength::Millimetre)
        } else {
            ("roller_m", GivenLength::Metre)
        };
        if let Some(why) = res.undercut_refusal(unit) {
            bail!("{flag}: {why}: no DXF written");
        }
    }
    Ok(())
}

fn yes_no(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

fn law_panels(states: &[ModulatorState], w2: f64) -> Vec<Panel> {
    let pts = |f: &dyn Fn(&ModulatorState) -> f64| -> Vec<(f64, f64)> {
        states.iter().map(|s| (s.phi2.to_degrees(), f(s))).collect()
    };
    vec![
        Panel::new(
            "angle [deg]",
            vec![
                Series::line("output φ6", pts(&|s| s.phi6[0].to_degrees())),
                Series::line("slot φ3", pts(&|s| s.phi3[0].to_degrees())),
                Series::line("input φ2", pts(&|s| s.phi2.to_degrees())),
            ],
        )
        .with_legend(Legend::Auto),
        Panel::new("speed ω6 [rad/s]", vec![Series::line("ω6", pts(&|s| s.phi6[1] * w2))]),
        Panel::new("acceleration ε6 [rad/s²]", vec![Series::line("ε6", pts(&|s| s.phi6[2] * w2 * w2))]),
    ]
}

/// Pressure angles at the output (μ6) and at the rollers (μB on Γ, μC on Γ′) with the limit line
/// and each one's maximum (as the analysis located it) marked.
fn pressure_panel(g: &ModulatorGeometry, states: &[ModulatorState], c: &loomkin_mech::CamChecks, limit: f64) -> Panel {
    let pts = |f: &dyn Fn(&ModulatorState) -> f64| -> Vec<(f64, f64)> {
        states.iter().map(|s| (s.phi2.to_degrees(), f(s))).collect()
    };
    let mut notes = Vec::new();
    let mut max_text = Vec::new();
    for (v, at) in [
        (c.mu_out_max_deg, c.mu_out_max_at_phi2_deg),
        (c.mu_b_max_deg, c.mu_b_max_at_phi2_deg),
        (c.mu_c_max_deg, c.mu_c_max_at_phi2_deg),
    ] {
        if v.is_finite() && at.is_finite() {
            notes.push(Note::new(at.rem_euclid(360.0), v, ""));
            max_text.push(format!(" {v:.1}° at {:.1}°", at.rem_euclid(360.0)));
        } else {
            max_text.push(String::new());
        }
    }
    Panel::new(
        "pressure angle [deg]",
        vec![
            Series::line(format!("μ6 slot, max{}", max_text[0]), pts(&|s| s.mu_out_deg())),
            Series::line(format!("μB roller B, max{}", max_text[1]), pts(&|s| s.mu_b_deg(g))).with_dash(Dash::Dashed),
            Series::line(format!("μC roller C, max{}", max_text[2]), pts(&|s| s.mu_c_deg(g))).with_dash(Dash::Dotted),
        ],
    )
    .with_rule(Rule::y(limit, format!("limit {limit}°")))
    .with_notes(notes)
}

/// Curvature of the roller-centre curves of Γ and Γ′ at every state (from the states' exact
/// derivatives, [`loomkin_mech::cam_curvature`]), each least radius (as the checks located it)
/// noted, and ±1/r of the roller: a groove wall is undercut where |κ| passes it.
fn curvature_panel(states: &[ModulatorState], c: &loomkin_mech::CamChecks, roller_m: Option<f64>) -> Panel {
    let k = loomkin_mech::cam_curvature(states);
    let mut notes = Vec::new();
    type Kappa = fn(&loomkin_mech::CamCurvaturePoint) -> f64;
    let (kb, kc): (Kappa, Kappa) = (|p| p.kappa_b_per_m, |p| p.kappa_c_per_m);
    for (rho, at, curve, cam) in
        [(c.rho_b_min_m, c.rho_b_min_at_phi2_deg, kb, "Γ"), (c.rho_c_min_m, c.rho_c_min_at_phi2_deg, kc, "Γ'")]
    {
        let Some(rho) = rho.filter(|r| r.is_finite() && *r > 0.0) else { continue };
        // The sign of κ at the located angle, from the nearest state.
        let at = at.rem_euclid(360.0);
        let sign = k
            .iter()
            .min_by(|p, q| {
                (p.phi2_deg.rem_euclid(360.0) - at).abs().total_cmp(&(q.phi2_deg.rem_euclid(360.0) - at).abs())
            })
            .map_or(1.0, |p| curve(p).signum());
        notes.push(Note::new(at, sign / rho, format!("{cam}: ρ min {} m at {}°", sig4(rho), sig4(at))));
    }
    let pts = |f: &dyn Fn(&loomkin_mech::CamCurvaturePoint) -> f64| -> Vec<(f64, f64)> {
        k.iter().map(|p| (p.phi2_deg, f(p))).collect()
    };
    let mut panel = Panel::new(
        "curvature κ [1/m]",
        vec![
            Series::line("cam Γ (roller centre B)", pts(&|p| p.kappa_b_per_m)),
            Series::line("counter-cam Γ' (roller centre C)", pts(&|p| p.kappa_c_per_m)).with_dash(Dash::Dashed),
        ],
    )
    .with_notes(notes);
    if let Some(r) = roller_m.filter(|r| *r > 0.0) {
        panel = panel
            .with_rule(Rule::y(1.0 / r, format!("±1/r, roller {} m: undercut beyond", sig4(r))))
            .with_rule(Rule::y(-1.0 / r, ""));
    }
    panel
}

fn xy(p: &[[f64; 2]], close: bool) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = p.iter().map(|q| (q[0], q[1])).collect();
    if close && let Some(f) = v.first().copied() {
        v.push(f);
    }
    v
}

/// Both walls of a groove as one line (parted by a break), so a cam reads as one colour.
fn walls(left: &[[f64; 2]], right: &[[f64; 2]]) -> Vec<(f64, f64)> {
    let mut v = xy(left, true);
    v.push((f64::NAN, f64::NAN));
    v.extend(xy(right, true));
    v
}

/// The cams with the mechanism at one state, as the workbench draws them: each cam in its own
/// colour (with a roller its two groove walls and, dashed, the roller-centre curve; else the
/// roller-centre curve), the rollers as circles at B and C, the links, and the joints lettered
/// O, A, B, C, D. Every point is the library's ([`loomkin_mech::MechanismPose::joints`]); links
/// are separate series: a polyline that doubles back on itself draws a miter spike in the bitmap
/// backend. (The plot font has no prime, so Γ′ is written Γ'.)
fn cams_panel(
    g: &ModulatorGeometry,
    gamma: &CamProfile,
    gamma_p: &CamProfile,
    st: &ModulatorState,
    roller_m: Option<f64>,
) -> Panel {
    let [cam, counter, lever, crank, out, slot] =
        [PALETTE[0], PALETTE[2], PALETTE[1], PALETTE[6], PALETTE[3], PALETTE[7]];
    let mut series = Vec::new();
    for (name, c, colour, at) in [("cam Γ", gamma, cam, "B"), ("counter-cam Γ'", gamma_p, counter, "C")] {
        if c.wall_left.is_empty() {
            series.push(Series::line(format!("{name} (roller centre {at})"), xy(&c.centre, true)).with_color(colour));
        } else {
            series.push(
                Series::line(format!("{name}: groove walls"), walls(&c.wall_left, &c.wall_right)).with_color(colour),
            );
            series.push(Series::line("", xy(&c.centre, true)).with_color(colour).with_dash(Dash::Dotted));
        }
    }
    let p = st.pose(g);
    let t = |q: [f64; 2]| (q[0], q[1]);
    // The slot runs from A through D and a little beyond.
    let beyond = [p.d[0] + 0.25 * (p.d[0] - p.a[0]), p.d[1] + 0.25 * (p.d[1] - p.a[1])];
    series.push(Series::line("slot of lever 3", vec![t(p.a), t(beyond)]).with_color(slot));
    series
        .push(Series::line(format!("crank 2 (OA) at φ2 = {:.1}°", p.phi2_deg), vec![t(p.o), t(p.a)]).with_color(crank));
    series.push(Series::line("crank 6 (OD)", vec![t(p.o), t(p.d)]).with_color(out));
    series.push(Series::line("lever 3: arms AB, AC", vec![t(p.b), t(p.a), t(p.c)]).with_color(lever));
    if let Some(r) = roller_m.filter(|r| *r > 0.0) {
        let rollers = p.rollers().map(t);
        series.push(
            Series::circles(format!("rollers at B, C (r = {} mm)", sig4(loomkin_units::mm_from_m(r))), &rollers, r)
                .with_color(lever),
        );
    }
    let notes = p.joints().map(|(letter, q)| Note::new(q[0], q[1], letter));
    let mut panel = Panel::new("y [m]", series).with_legend(Legend::Auto).with_notes(notes);
    panel.x_label = Some("x [m]".into());
    panel.equal_aspect = true;
    panel
}

fn plot_cmd(a: PlotArgs) -> Result<()> {
    output::check_outputs([Some(Out::plot("--output", &a.output))])?;
    DobbyInputs::AT_DEG.check_as("--at-deg", a.at_deg)?;
    let g = a.geometry.geometry()?;
    let w2 = a.geometry.speed_rad_s()?;
    let (states, gamma, gamma_p, title, checks) = match a.task {
        TaskArg::Analyze => {
            let cam = a.cam.cam()?;
            let roller_m = a.roller.metres()?;
            let r = analyze(&g, &cam, &analysis_options(&a.geometry, a.step_deg, roller_m)?)?;
            warn(&r.warnings);
            let gamma = r.cam_profile(roller_m.unwrap_or(0.0));
            let title = format!("Modulator, task 1: cam {}, α = {}°", cam.label(), g.alpha_deg);
            (r.states, gamma, r.counter_cam, title, r.summary.checks)
        }
        TaskArg::Synthesize => {
            let law = a.law.spec()?;
            let r = synthesize(&g, &law, &synthesis_options(&a.geometry, a.step_deg, a.roller.metres_or_default()?)?)?;
            warn(&r.warnings);
            let title = format!("Modulator, task 2: {}, α = {}°", r.summary.law, g.alpha_deg);
            (r.states, r.cam, r.counter_cam, title, r.summary.checks)
        }
    };
    let roller = match a.task {
        TaskArg::Analyze => a.roller.metres()?,
        TaskArg::Synthesize => Some(a.roller.metres_or_default()?),
    };
    let fig = match a.what {
        WhatArg::Law => {
            let mut panels = law_panels(&states, w2);
            panels.push(pressure_panel(&g, &states, &checks, a.geometry.pressure_limit_deg));
            panels.push(curvature_panel(&states, &checks, roller));
            // The pressure angles fill their panel, so its legend goes beside it: a wider page
            // keeps the plots as wide as a figure without one.
            let mut f = Figure::new(title, "input angle φ2 [deg]", panels);
            let (_, h) = f.pixel_size();
            f.size = Some((1250, h));
            f
        }
        WhatArg::Cams => {
            let st = nearest_state(&states, a.at_deg).context("no state to draw")?;
            let mut f = Figure::new(title, "x [m]", vec![cams_panel(&g, &gamma, &gamma_p, st, roller)]);
            f.size = Some((1000, 1000));
            f
        }
    };
    output::figure(&fig, &a.output, &a.plot)
}

fn sweep_cmd(a: SweepArgs) -> Result<()> {
    // The sweep sets α = θ itself: a lever angle given as well would be silently ignored.
    if a.geometry.alpha_deg.is_some() || a.geometry.theta_deg.is_some() {
        bail!("--alpha-deg and --theta-deg do not apply to dobby sweep: it sweeps α = θ over --from … --to by --by");
    }
    let all = AlphaSweep::values(["--from", "--to", "--by"], a.from, a.to, a.by)?;
    a.shard.check(a.format)?;
    let alphas: Vec<f64> = a.shard.get().items(all.len()).map(|i| all[i]).collect();
    let g = a.geometry.geometry()?;
    let rows = alpha_sweep(
        &g,
        &a.cam.cam()?,
        &a.law.spec()?,
        &alphas,
        &analysis_options(&a.geometry, a.step_deg, None)?,
        &synthesis_options(&a.geometry, a.step_deg, a.roller.metres_or_default()?)?,
    )
    .map_err(|e: MechError| anyhow::Error::from(e))?;
    if a.format.json && a.shard.given() {
        return output::json_lines(rows.iter());
    }
    if a.format.json {
        return output::json(&loomkin_mech::SweepReport { rows: &rows });
    }
    let cols = [
        "alpha_deg",
        "an_ok",
        "an_omega6_min_rad_s",
        "an_omega6_max_rad_s",
        "an_mu_out_max_deg",
        "an_mu_b_max_deg",
        "an_mu_c_max_deg",
        "syn_ok",
        "syn_mu_b_max_deg",
        "syn_mu_c_max_deg",
        "syn_rho_b_min_m",
        "syn_rho_c_min_m",
        "syn_undercut",
    ];
    let mut t = Table::new(cols);
    // A task that failed at this α has 0 in its *_ok column and 0 in its values.
    for r in &rows {
        let z = |v: Option<f64>| v.unwrap_or(0.0);
        t.push(vec![
            r.alpha_deg,
            if r.an_error.is_none() { 1.0 } else { 0.0 },
            z(r.an_omega6_min_rad_s),
            z(r.an_omega6_max_rad_s),
            z(r.an_mu_out_max_deg),
            z(r.an_mu_b_max_deg),
            z(r.an_mu_c_max_deg),
            if r.syn_error.is_none() { 1.0 } else { 0.0 },
            z(r.syn_mu_b_max_deg),
            z(r.syn_mu_c_max_deg),
            z(r.syn_rho_b_min_m),
            z(r.syn_rho_c_min_m),
            if r.syn_undercut == Some(true) { 1.0 } else { 0.0 },
        ])?;
    }
    if a.format.csv {
        return output::csv_shard(&t, a.shard.header());
    }
    outln!("α sweep (θ = α): analysis of the cam | synthesis of the law")?;
    outln!(
        "{:>8} {:>12} {:>12} {:>10} {:>10} {:>10} | {:>10} {:>10} {:>12}",
        "α_deg",
        "ω6_min_rad_s",
        "ω6_max_rad_s",
        "μ6_max_deg",
        "μB_max_deg",
        "μC_max_deg",
        "μB_max_deg",
        "μC_max_deg",
        "ρ_min_m"
    )?;
    let f =
        |v: Option<f64>, w: usize, p: usize| v.map(|x| format!("{x:>w$.p$}")).unwrap_or_else(|| format!("{:>w$}", "—"));
    for r in &rows {
        outln!(
            "{:>8.2} {} {} {} {} {} | {} {} {}",
            r.alpha_deg,
            f(r.an_omega6_min_rad_s, 12, 5),
            f(r.an_omega6_max_rad_s, 12, 5),
            f(r.an_mu_out_max_deg, 10, 2),
            f(r.an_mu_b_max_deg, 10, 2),
            f(r.an_mu_c_max_deg, 10, 2),
            f(r.syn_mu_b_max_deg, 10, 2),
            f(r.syn_mu_c_max_deg, 10, 2),
            f(r.syn_rho_b_min_m.zip(r.syn_rho_c_min_m).map(|(a, b)| a.min(b)), 12, 5),
        )?;
        for e in [&r.an_error, &r.syn_error].into_iter().flatten() {
            outln!("{:>8}   {e}", "")?;
        }
    }
    Ok(())
}
