//! `loomkin shed …`: heald-frame laws, dwell criteria, experiment tables, Pareto choice.

use crate::output::{self, Out, outln};
use crate::util::{self, failure};
use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use loomkin_plot::{Figure, Legend, Note, PALETTE, Panel, Series, XBand, YBand, sig4};
use loomkin_shed::{
    BestReport, BestSearch, Conditions, Criteria, DesignKind, Family, GridSpec, LawReport, LoomRequirement, PRESETS,
    PresetReport, Progress, ShedLaw, Study, StudyRow, StudyTable, Template, WindowReport, evaluate, preset,
    preset_table, preset_table_in,
};
use loomkin_units::{Cost, ShaftSpeed, compact};
use serde::Serialize;
use std::fmt::Write;
use std::path::PathBuf;

/// Subcommands of `loomkin shed`.
#[derive(Debug, Subcommand)]
pub enum ShedCommand {
    /// The named laws of the paper (Tables 2 and 3).
    List(ListArgs),
    /// All criteria of one law: a preset or a TOML definition.
    Law(LawArgs),
    /// An experiment table: the presets, Table 1, the Fig. 1 family or a full grid over k_T1…k_Tn.
    Table(TableArgs),
    /// The Pareto front (largest window, least peak acceleration) of an experiment table.
    Pareto(ParetoArgs),
    /// The law of least peak acceleration whose window is at least W.
    Best(BestArgs),
    /// The window a loom needs, from its carrier, widths, crossing-point range and speed.
    Window(WindowArgs),
    /// Displacement and acceleration over the frame's cycle (two picks) for several laws.
    Plot(PlotArgs),
}

/// Physical conditions shared by the subcommands.
#[derive(Debug, Args, Clone)]
pub struct Physical {
    /// Frame stroke, mm.
    #[arg(long, default_value_t = Conditions::STROKE_MM.default_value(), allow_hyphen_values = true)]
    stroke_mm: f64,
    /// Main-shaft speed, rpm (one pick per turn).
    #[arg(long, default_value_t = ShaftSpeed::DEFAULT_RPM, allow_hyphen_values = true)]
    speed_rpm: f64,
}

/// The dwell threshold.
#[derive(Debug, Args, Clone)]
pub struct Threshold {
    #[arg(long, default_value_t = Conditions::THRESHOLD_FIELD.default_value(), allow_hyphen_values = true, help = util::range_help("Dwell threshold T: the frame counts as still within (1 − T) of its stroke from an extreme (the default reproduces the paper's Table 3)", &Conditions::THRESHOLD_FIELD))]
    threshold: f64,
}

fn conditions(p: &Physical, t: f64) -> Result<Conditions> {
    Ok(Conditions::from_stroke_mm(t, p.stroke_mm, p.speed_rpm)?)
}

/// `shed list`.
#[derive(Debug, Args)]
pub struct ListArgs {
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `shed law`.
#[derive(Debug, Args)]
pub struct LawArgs {
    /// Preset name (basic, traditional, dobby, semi-smooth, smooth).
    #[arg(required_unless_present = "spec", conflicts_with = "spec")]
    name: Option<String>,
    /// A law defined in TOML (motion_deg, positive, optional negative and positive_fraction).
    #[arg(long, value_name = "FILE.toml")]
    spec: Option<PathBuf>,
    /// Override the motion angle φ_дв, deg (1 ≤ φ ≤ 360).
    #[arg(long, allow_hyphen_values = true)]
    motion_deg: Option<f64>,
    #[command(flatten)]
    threshold: Threshold,
    #[command(flatten)]
    physical: Physical,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Also write the frame's full cycle (rise, dwell, return, dwell over two picks) as a cycle file.
    #[arg(long, value_name = "FILE.toml")]
    emit_cycle: Option<PathBuf>,
}

/// The experiment design and the family of laws it runs over.
#[derive(Debug, Args, Clone)]
pub struct DesignArgs {
    /// Family of shapes of the positive phase: trapezoid (rise, plateau, fall), lead-trapezoid
    /// (zero, rise, plateau, fall) or linear-trapezoid.
    #[arg(long, value_enum, ignore_case = true)]
    family: Option<Family>,
    /// Custom shapes of the positive phase instead of a family, e.g. "sine-ramp:0:1,constant:1,cosine-ramp:1:0".
    #[arg(long, conflicts_with = "family")]
    shapes: Option<String>,
    #[arg(long, allow_hyphen_values = true, help = format!("Grid step of k (grid and fig1 designs; default {}; {} for best)", GridSpec::TABLE.step, GridSpec::BEST.step))]
    step: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = format!("Least relative length in the grid (default {}; {} for best; the paper's practical least part is {})", GridSpec::TABLE.min_k, GridSpec::BEST.min_k, GridSpec::PRACTICAL_MIN_K))]
    min_k: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = format!("Largest relative length in the grid (default {}; {} for best)", GridSpec::TABLE.max_k, GridSpec::BEST.max_k))]
    max_k: Option<f64>,
    /// Motion angles φ_дв, deg: DEG, DEG,DEG,… or MIN:MAX:STEP.
    #[arg(long, allow_hyphen_values = true)]
    motion_deg: Option<String>,
}

/// `shed table`.
#[derive(Debug, Args)]
pub struct TableArgs {
    /// Experiment design.
    #[arg(long, value_enum, default_value_t = DesignKind::Presets)]
    design: DesignKind,
    #[command(flatten)]
    d: DesignArgs,
    #[command(flatten)]
    threshold: Threshold,
    #[command(flatten)]
    physical: Physical,
    #[command(flatten)]
    format: util::Format,
    #[command(flatten)]
    shard: crate::shard::ShardArgs,
}

/// `shed pareto`.
#[derive(Debug, Args)]
pub struct ParetoArgs {
    /// Experiment design (default: the grid over the motion angles of --motion-deg's default).
    #[arg(long, value_enum, default_value_t = DesignKind::Grid)]
    design: DesignKind,
    #[command(flatten)]
    d: DesignArgs,
    #[command(flatten)]
    threshold: Threshold,
    #[command(flatten)]
    physical: Physical,
    #[command(flatten)]
    format: util::Format,
    /// Plot the front (with the presets for reference) to an .svg or .png file.
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
    /// The front of a table made before (shed table --csv, at the same --threshold, --stroke-mm and --speed-rpm):
    /// one file, the shards' outputs in order, the directory of its parts (--parts) or the parts, or - for
    /// standard input; read as a stream (memory: the front), the same front as the one-machine run.
    #[arg(long, value_name = "FILE|DIR|-", num_args = 1..)]
    from: Option<Vec<PathBuf>>,
}

/// Loom data that set the required window (and the threshold) in loom terms.
#[derive(Debug, Args, Clone)]
pub struct LoomArgs {
    /// Mean speed of the weft carrier, m/s.
    #[arg(long, allow_hyphen_values = true)]
    carrier_speed_m_s: Option<f64>,
    /// Reed (working) width of the loom, m.
    #[arg(long, requires = "carrier_speed_m_s", allow_hyphen_values = true)]
    reed_width_m: Option<f64>,
    /// Cloth width in the reed, m (default: the reed width).
    #[arg(long, requires = "carrier_speed_m_s", allow_hyphen_values = true)]
    cloth_width_m: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Carrier length, m", &LoomRequirement::CARRIER_LENGTH_M))]
    carrier_length_m: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Range of the crossing-point (заступ) setting, deg", &LoomRequirement::CROSSING_RANGE_DEG))]
    crossing_range_deg: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Shed-height excess over the necessary opening, a fraction (0.05 = 5 %); sets T = 1/(1 + excess)", &LoomRequirement::SHED_EXCESS))]
    shed_excess: Option<f64>,
}

impl LoomArgs {
    fn requirement(&self, speed_rpm: f64) -> Result<Option<LoomRequirement>> {
        let Some(v) = self.carrier_speed_m_s else {
            // Loom data without the carrier speed set nothing: refused, not silently ignored
            // (clap's `requires` does not fire while `--window-deg`, which conflicts with the
            // carrier speed, is given).
            let given = [
                ("--reed-width-m", self.reed_width_m.is_some()),
                ("--cloth-width-m", self.cloth_width_m.is_some()),
                ("--carrier-length-m", self.carrier_length_m.is_some()),
                ("--crossing-range-deg", self.crossing_range_deg.is_some()),
                ("--shed-excess", self.shed_excess.is_some()),
            ];
            if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
                bail!(
                    "{}: {flag} is loom data for the required window: it needs --carrier-speed-m-s (and then no --window-deg)",
                    flag.trim_start_matches("--").replace('-', "_")
                );
            }
            return Ok(None);
        };
        let Some(reed) = self.reed_width_m else { bail!("--reed-width-m is needed with --carrier-speed-m-s") };
        let r = LoomRequirement::from_inputs(
            v,
            reed,
            self.cloth_width_m,
            self.carrier_length_m,
            self.crossing_range_deg,
            self.shed_excess,
            speed_rpm,
        );
        r.required_window_deg()?;
        Ok(Some(r))
    }
}

/// `shed best`.
#[derive(Debug, Args)]
pub struct BestArgs {
    /// Required window φ_пп*, deg (0 < W < 360); or give the loom data instead.
    #[arg(
        long,
        required_unless_present = "carrier_speed_m_s",
        conflicts_with = "carrier_speed_m_s",
        allow_hyphen_values = true
    )]
    window_deg: Option<f64>,
    #[command(flatten)]
    loom: LoomArgs,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Dwell threshold T (left out with loom data: 1/(1 + shed excess))", &Conditions::THRESHOLD_FIELD))]
    threshold: Option<f64>,
    /// Upper limit on the peak frame jerk, m/s³ (least acceleration alone favours constant
    /// acceleration with its jerk peaks).
    #[arg(long, allow_hyphen_values = true)]
    max_jerk_m_s3: Option<f64>,
    /// Experiment design searched (default: the grid of the trapezoid family at best's step).
    #[arg(long, value_enum, default_value_t = DesignKind::Grid)]
    design: DesignKind,
    #[command(flatten)]
    d: DesignArgs,
    #[command(flatten)]
    physical: Physical,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Also write the chosen law's full frame cycle (rise, dwell, return, dwell over two picks) as a
    /// cycle file.
    #[arg(long, value_name = "FILE.toml")]
    emit_cycle: Option<PathBuf>,
}

/// `shed window`.
#[derive(Debug, Args)]
pub struct WindowArgs {
    #[command(flatten)]
    loom: LoomArgs,
    /// Main-shaft speed, rpm.
    #[arg(long, default_value_t = ShaftSpeed::DEFAULT_RPM, allow_hyphen_values = true)]
    speed_rpm: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `shed plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// Preset names to overlay.
    laws: Vec<String>,
    /// Laws defined in TOML files (repeatable).
    #[arg(long, value_name = "FILE.toml")]
    spec: Vec<PathBuf>,
    /// Output file, .svg or .png.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
    /// Points per curve.
    #[arg(long, default_value_t = loomkin_shed::PLOT_POINTS.default_count())]
    points: usize,
    #[command(flatten)]
    threshold: Threshold,
    #[command(flatten)]
    physical: Physical,
}

/// Runs a `shed` subcommand.
pub fn run(cmd: ShedCommand) -> Result<()> {
    match cmd {
        ShedCommand::List(a) => list(a),
        ShedCommand::Law(a) => law(a),
        ShedCommand::Table(a) => table(a),
        ShedCommand::Pareto(a) => pareto(a),
        ShedCommand::Best(a) => best(a),
        ShedCommand::Window(a) => window(a),
        ShedCommand::Plot(a) => plot(a),
    }
}

fn load(name: Option<&str>, spec: Option<&PathBuf>) -> Result<(String, ShedLaw)> {
    match (name, spec) {
        (_, Some(path)) => {
            let text = util::read_input(path)?;
            let law = ShedLaw::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
            Ok((path.display().to_string(), law))
        }
        (Some(n), None) => Ok((n.to_string(), preset(n)?)),
        (None, None) => bail!("give a law name or --spec FILE.toml"),
    }
}

/// `shed list --json`.
#[derive(Serialize)]
struct ListJson {
    laws: Vec<PresetReport>,
}

fn list(a: ListArgs) -> Result<()> {
    if a.json {
        let laws = PresetReport::all();
        return output::json(&ListJson { laws });
    }
    outln!("{:<12} {:>10} {:>9}  positive phase of the acceleration", "law", "motion_deg", "dwell_deg")?;
    for p in PRESETS {
        outln!("{:<12} {:>10} {:>9}  {} = {}", p.name, p.motion_deg, 360.0 - p.motion_deg, p.table_shape, p.positive)?;
    }
    Ok(())
}

fn law(a: LawArgs) -> Result<()> {
    output::check_outputs([a.emit_cycle.as_ref().map(|p| Out::file("--emit-cycle", p))])?;
    let (name, mut law) = load(a.name.as_deref(), a.spec.as_ref())?;
    if let Some(m) = a.motion_deg {
        law = law.with_motion_deg(m)?;
    }
    let cond = conditions(&a.physical, a.threshold.threshold)?;
    let c = evaluate(&law, &cond)?;
    if let Some(path) = &a.emit_cycle {
        emit_cycle(&law, &a.physical, path, &format!("loomkin shed law {name}"))?;
    }
    if a.json {
        return output::json(&LawReport::new(name, &law, &c, &cond));
    }
    outln!("law {name}: motion {} deg, positive phase {}", law.motion_deg(), law.positive_text())?;
    print_criteria(&c, &cond)?;
    Ok(())
}

fn print_criteria(c: &Criteria, cond: &Conditions) -> Result<()> {
    outln!(
        "  at T = {} (frame within {:.1} % of its stroke), stroke {} mm, {} rpm",
        c.threshold,
        100.0 * (1.0 - c.threshold),
        loomkin_units::mm_from_m(cond.stroke_m()),
        cond.speed_rpm()
    )?;
    outln!("  motion angle             = {:>10.3} deg", c.motion_deg)?;
    outln!("  absolute dwell           = {:>10.3} deg", c.dwell_deg)?;
    outln!("  conditional dwell        = {:>10.3} deg", c.conditional_dwell_deg)?;
    outln!("  window = dwell + cond.    = {:>10.3} deg", c.window_deg)?;
    outln!(
        "  Cv = {:.6}  Ca = {:.6}  Cj = {:.4}  Cm = {:.6}  Ca_rms = {:.6}  (dimensionless)",
        c.cv,
        c.ca,
        c.cj,
        c.cm,
        c.ca_rms
    )?;
    outln!("  Ca·(360/motion)²         = {:>10.4} (peak acceleration on the scale of a turn)", c.ca_turn)?;
    outln!("  peak velocity            = {:>10.4} m/s", c.peak_velocity_m_s)?;
    outln!("  peak acceleration        = {:>10.4} m/s²", c.peak_accel_m_s2)?;
    outln!("  RMS acceleration         = {:>10.4} m/s² (over the motion)", c.rms_accel_m_s2)?;
    outln!("  peak jerk                = {:>10.2} m/s³", c.peak_jerk_m_s3)?;
    outln!("  peak v·a                 = {:>10.4} W/kg", c.peak_power_w_kg)?;
    if c.accel_jump_m_s2 > 0.0 {
        outln!("  acceleration jump        = {:>10.4} m/s² (unbounded jerk there)", c.accel_jump_m_s2)?;
    }
    Ok(())
}

fn template(d: &DesignArgs) -> Result<Option<Template>> {
    Ok(match (&d.shapes, d.family) {
        (Some(s), _) => Some(Template::parse("custom", s)?),
        (None, Some(f)) => Some(f.template()),
        (None, None) => None,
    })
}

/// The grid of a study from the flags and the defaults `g`.
fn grid_of(d: &DesignArgs, g: GridSpec) -> GridSpec {
    GridSpec { step: d.step.unwrap_or(g.step), min_k: d.min_k.unwrap_or(g.min_k), max_k: d.max_k.unwrap_or(g.max_k) }
}

/// Refuses a study estimated beyond the budget before its design is made: the laws of the design
/// (counted, not made), a shard's share of them evaluated, each at `motions` angles with `bytes_per_row`
/// held per row. The input blamed is the motion angles when they outnumber the laws, else the step.
fn check_budget(
    kind: DesignKind,
    d: &DesignArgs,
    g: GridSpec,
    motions: usize,
    shard: Option<loomkin_units::Shard>,
    row: Cost,
) -> Result<()> {
    let parts = template(d)?.map_or(if kind == DesignKind::Fig1 { 4 } else { 3 }, |t| t.parts());
    let grid = grid_of(d, g);
    let cores = crate::util::cores() as usize;
    let whole = Study::estimate(kind, parts, grid, motions, 1.0, row, cores);
    // A shard evaluates and lists its share of the laws (the design is made whole).
    let share = match shard {
        Some(s) if whole.laws >= 1.0 && whole.laws < u32::MAX as f64 => {
            s.items(whole.laws as usize).len() as f64 / whole.laws
        }
        _ => 1.0,
    };
    let e = Study::estimate(kind, parts, grid, motions, share, row, cores);
    let what = format!("{} laws × {motions} motion angles", loomkin_units::compact(e.laws));
    if motions > 1 && motions as f64 > e.laws {
        crate::util::check_budget(
            "--motion-deg",
            format!("{} ({what})", d.motion_deg.as_deref().unwrap_or("")),
            e.cost,
        )?;
    } else {
        crate::util::check_budget("--step", format!("{} ({what})", loomkin_units::compact(grid.step)), e.cost)?;
    }
    Ok(())
}

fn study_design(kind: DesignKind, d: &DesignArgs, g: GridSpec) -> Result<Study> {
    if kind != DesignKind::Grid && (d.min_k.is_some() || d.max_k.is_some()) {
        bail!("--min-k and --max-k apply to --design grid only");
    }
    if matches!(kind, DesignKind::Presets | DesignKind::Table1) && d.step.is_some() {
        bail!("step: --step applies to --design grid and fig1 only (the presets and Table 1 are fixed laws)");
    }
    Ok(Study::new(kind, template(d)?, grid_of(d, g))?)
}

/// One row of `shed table | pareto --json`, owned (rows are made as they are printed).
struct RowOut<'c>(StudyRow, &'c Conditions);

impl Serialize for RowOut<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.report(self.1).serialize(s)
    }
}

/// `shed table | pareto --json`, the rows written as they are made.
#[derive(Serialize)]
struct RowsOut<'a> {
    rows: output::Streamed<'a, RowOut<'a>>,
}

/// How [`print_rows`] prints a table.
#[derive(Clone, Copy)]
struct Form<'a> {
    format: util::Format,
    /// A shard (`Some`, holding whether its CSV starts with the header: shard 1, or a part of
    /// `--parts`), or JSON Lines.
    shard: Option<bool>,
    /// The text form's title.
    title: &'a str,
}

/// Prints the rows of a table as they are made (nothing held per row): JSON, JSON Lines, CSV or
/// text, with `k_names` the length columns (empty for named laws).
fn print_rows(
    k_names: &[String],
    rows: impl Iterator<Item = StudyRow>,
    form: Form<'_>,
    cond: &Conditions,
    progress: &util::Progress,
) -> Result<()> {
    let rows = rows.inspect(|_| progress.inc(1));
    if form.format.json {
        let rows = rows.map(|r| RowOut(r, cond));
        return match form.shard {
            Some(_) => output::json_lines(rows),
            None => output::json_streamed(&RowsOut { rows: output::Streamed::new(rows) }),
        };
    }
    let named = k_names.is_empty();
    let mut out = String::with_capacity(CHUNK + 1024);
    let flush = |out: &mut String, at_least: usize| -> Result<()> {
        if out.len() >= at_least {
            output::text_to("-", out)?;
            out.clear();
        }
        Ok(())
    };
    if form.format.csv {
        if form.shard.is_none_or(|header| header) {
            out.push_str(&loomkin_shed::csv_header(k_names));
        }
        for r in rows {
            let c = &r.candidate;
            if let Some(bad) =
                c.lengths.iter().chain(&[c.criteria.window_deg, c.criteria.peak_accel_m_s2]).find(|v| !v.is_finite())
            {
                return Err(failure(anyhow::anyhow!("internal: non-finite value {bad} in row {}", c.row)));
            }
            loomkin_shed::csv_line(&r, named, &mut out);
            flush(&mut out, CHUNK)?;
        }
        return flush(&mut out, 1);
    }
    writeln!(
        out,
        "{} (T = {}, stroke {} mm, {} rpm)",
        form.title,
        cond.threshold(),
        loomkin_units::mm_from_m(cond.stroke_m()),
        cond.speed_rpm()
    )
    .map_err(failure)?;
    let first = if named { "law".to_string() } else { "lengths k_T".to_string() };
    writeln!(
        out,
        "{first:<28} {:>9} {:>9} {:>9} {:>9} {:>8} {:>10} {:>11}",
        "motion°", "dwell°", "cond°", "window°", "Ca", "Ca_turn", "a_max m/s²"
    )
    .map_err(failure)?;
    for r in rows {
        let c = &r.candidate;
        let label =
            r.law.clone().unwrap_or_else(|| c.lengths.iter().map(|k| format!("{k:.3}")).collect::<Vec<_>>().join(" "));
        let k = &c.criteria;
        writeln!(
            out,
            "{label:<28} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>8.4} {:>10.3} {:>11.3}",
            k.motion_deg, k.dwell_deg, k.conditional_dwell_deg, k.window_deg, k.ca, k.ca_turn, k.peak_accel_m_s2
        )
        .map_err(failure)?;
        flush(&mut out, CHUNK)?;
    }
    flush(&mut out, 1)
}

/// What one row of a streamed table costs: nothing held, and the time to make and print it,
/// measured end to end with the release binary on the reference machine (2 cores, loaded by
/// other builds: load average 15) over 1.6 M rows (`shed table --design grid --step 0.1
/// --motion-deg 1:360:0.01`, `/usr/bin/time -v`): CSV 3.9 µs, text 13.4 µs, JSON 41 µs a row.
/// Taken as measured under that load, without a further margin.
fn row_cost(format: util::Format) -> Cost {
    let seconds = if format.json {
        41e-6
    } else if format.csv {
        3.9e-6
    } else {
        13.4e-6
    };
    Cost { bytes: 0.0, seconds }
}

/// Bytes of text gathered before a write to standard output.
const CHUNK: usize = 1 << 16;

/// A whole table (a front, the presets) printed as text, CSV or JSON.
fn emit(rows: StudyTable, format: util::Format, cond: &Conditions, title: &str) -> Result<()> {
    let progress = util::Progress::new(rows.rows.len() as u64, "rows");
    print_rows(&rows.k_names, rows.rows.into_iter(), Form { format, shard: None, title }, cond, &progress)
}

fn table(a: TableArgs) -> Result<()> {
    a.shard.check(a.format)?;
    let cond = conditions(&a.physical, a.threshold.threshold)?;
    let shard = a.shard.get();
    let form = Form { format: a.format, shard: a.shard.given().then_some(a.shard.header()), title: "experiment table" };
    if a.design == DesignKind::Presets {
        let d = &a.d;
        if d.family.is_some() || d.shapes.is_some() || d.motion_deg.is_some() || d.step.is_some() {
            bail!("--design presets takes no --family, --shapes, --step or --motion-deg");
        }
        let t = preset_table_in(&cond, shard.items(PRESETS.len()))?;
        let progress = util::Progress::new(t.rows.len() as u64, "rows");
        return print_rows(&t.k_names, t.rows.into_iter(), form, &cond, &progress);
    }
    // The rows are streamed: what is held is the design and one set of criteria per law.
    let motions =
        loomkin_shed::parse_motion_angles(a.d.motion_deg.as_deref().unwrap_or(loomkin_shed::TABLE_MOTION_DEG))?;
    check_budget(a.design, &a.d, GridSpec::TABLE, motions.len(), Some(shard), row_cost(a.format))?;
    let study = study_design(a.design, &a.d, GridSpec::TABLE)?;
    let items = shard.items(study.design.len());
    let rows = study.rows_in(&motions, &cond, Progress::Auto, items.clone())?;
    let progress = util::Progress::new((items.len() * motions.len()) as u64, "rows");
    print_rows(study.design.names(), rows, form, &cond, &progress)?;
    progress.finish();
    Ok(())
}

fn pareto(a: ParetoArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let cond = conditions(&a.physical, a.threshold.threshold)?;
    let front = if let Some(inputs) = &a.from {
        let d = &a.d;
        if d.family.is_some()
            || d.shapes.is_some()
            || d.motion_deg.is_some()
            || d.step.is_some()
            || d.min_k.is_some()
            || d.max_k.is_some()
        {
            bail!(
                "--from reads the table made before: it takes no --family, --shapes, --step, --min-k, --max-k or --motion-deg"
            );
        }
        // Named part files may be some of a run's parts (a task's own front); a directory is the run.
        let lines = loomkin_study::parts::Lines::open_some(inputs).map_err(util::part_error)?;
        loomkin_shed::front_of_table(&lines, &cond).map_err(util::part_error)?
    } else if a.design == DesignKind::Presets {
        let d = &a.d;
        if d.family.is_some() || d.shapes.is_some() || d.motion_deg.is_some() || d.step.is_some() {
            bail!("--design presets takes no --family, --shapes, --step or --motion-deg");
        }
        let all = preset_table(&cond)?;
        let pts: Vec<[f64; 2]> =
            all.rows.iter().map(|r| [r.candidate.criteria.window_deg, r.candidate.criteria.peak_accel_m_s2]).collect();
        all.select(&loomkin_shed::pareto_indices(&pts)?)
    } else {
        let motions =
            loomkin_shed::parse_motion_angles(a.d.motion_deg.as_deref().unwrap_or(loomkin_shed::PARETO_MOTION_DEG))?;
        // What is held per law and angle is its point (window, acceleration) and its index.
        check_budget(a.design, &a.d, GridSpec::TABLE, motions.len(), None, Cost { bytes: 32.0, seconds: 0.0 })?;
        let study = study_design(a.design, &a.d, GridSpec::TABLE)?;
        study.pareto(&motions, &cond, Progress::Auto)?
    };
    if let Some(path) = &a.output {
        let line: Vec<(f64, f64)> = front
            .rows
            .iter()
            .map(|r| (r.candidate.criteria.window_deg, r.candidate.criteria.peak_accel_m_s2))
            .collect();
        // The two ends of the front, annotated: the least acceleration and the largest window.
        let mut notes = Vec::new();
        if let (Some(lo), Some(hi)) = (
            line.iter().min_by(|p, q| p.1.total_cmp(&q.1)).copied(),
            line.iter().max_by(|p, q| p.0.total_cmp(&q.0)).copied(),
        ) {
            notes.push(Note::new(lo.0, lo.1, format!("{} m/s², window {}°", sig4(lo.1), sig4(lo.0))));
            if hi != lo {
                notes.push(Note::new(hi.0, hi.1, format!("{} m/s², window {}°", sig4(hi.1), sig4(hi.0))));
            }
        }
        let mut series = vec![Series { markers: true, ..Series::line("Pareto front", line) }];
        for p in PRESETS {
            let c = evaluate(&p.law()?, &cond)?;
            series.push(Series::markers(p.name, vec![(c.window_deg, c.peak_accel_m_s2)]).emphasised());
        }
        let (lo, hi) = series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .filter(|v| v.is_finite() && *v > 0.0)
            .fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
        let mut panel =
            Panel::new("peak frame acceleration [m/s²]", series).with_legend(Legend::Auto).with_notes(notes);
        // A front spanning more than two decades (the lead-trapezoid family reaches 10⁵ m/s²) is
        // read on a log axis: on a linear one everything but its steep end sits on the floor.
        if hi > 100.0 * lo {
            panel = panel.with_log_y();
        }
        let fig = Figure::new(
            format!(
                "Pareto front: window vs peak acceleration (T = {}, stroke {} mm, {} rpm)",
                cond.threshold(),
                loomkin_units::mm_from_m(cond.stroke_m()),
                cond.speed_rpm()
            ),
            "weft-insertion window [deg]",
            vec![panel],
        );
        return output::figure(&fig, path, &a.plot);
    }
    emit(front, a.format, &cond, "Pareto front: largest window, least peak acceleration")
}

fn best(a: BestArgs) -> Result<()> {
    output::check_outputs([a.emit_cycle.as_ref().map(|p| Out::file("--emit-cycle", p))])?;
    let req = a.loom.requirement(a.physical.speed_rpm)?;
    let (w, t) = match (&req, a.window_deg) {
        (Some(r), _) => (r.required_window_deg()?, a.threshold.unwrap_or(r.threshold())),
        (None, Some(w)) => (w, a.threshold.unwrap_or(loomkin_shed::TABLE3_THRESHOLD)),
        (None, None) => bail!("give --window-deg or the loom data (--carrier-speed-m-s, --reed-width-m, …)"),
    };
    let cond = conditions(&a.physical, t)?;
    loomkin_shed::check_window_deg(w)?;
    if a.design == DesignKind::Presets {
        bail!("--design presets is not searched by best; use table1, fig1 or grid");
    }
    let d = &a.d;
    let motions = match &d.motion_deg {
        Some(m) => Some(loomkin_shed::parse_motion_angles(m)?),
        None => None,
    };
    // Each law is checked at each angle (or at its best angle): nothing is held per angle.
    check_budget(a.design, d, GridSpec::BEST, motions.as_ref().map_or(1, Vec::len), None, Cost::default())?;
    let study = study_design(a.design, d, GridSpec::BEST)?;
    let (tpl, design) = (&study.template, &study.design);
    let dims = study.evaluate(t, Progress::Auto)?;
    let Some(b) = loomkin_shed::best(design, &dims, motions.as_deref(), w, a.max_jerk_m_s3, &cond)? else {
        // Blame the constraint that fails: the window alone, or the jerk limit on top of it.
        if let Some(j) = a.max_jerk_m_s3
            && loomkin_shed::best(design, &dims, motions.as_deref(), w, None, &cond)?.is_some()
        {
            bail!(
                "no law of the family '{}' with a window of {} deg at T = {} keeps the peak jerk within \
                 --max-jerk-m-s3 {} (laws with that window exist without the jerk limit)",
                tpl.name(),
                compact(w),
                compact(t),
                compact(j)
            );
        }
        bail!("no law of the family '{}' gives a window of {} deg at T = {}", tpl.name(), compact(w), compact(t));
    };
    let law = tpl.law(b.criteria.motion_deg, &b.lengths)?;
    if let Some(path) = &a.emit_cycle {
        emit_cycle(&law, &a.physical, path, &format!("loomkin shed best --window-deg {w} (family {})", tpl.name()))?;
    }
    if a.json {
        let search = BestSearch {
            template: tpl,
            laws_searched: design.len(),
            required_window_deg: w,
            max_jerk_m_s3: a.max_jerk_m_s3,
            loom: req.as_ref(),
        };
        return output::json(&BestReport::new(search, &b, &law, &cond));
    }
    outln!(
        "least peak acceleration with a window ≥ {w:.3} deg ({} laws of the family '{}' searched{})",
        design.len(),
        tpl.name(),
        if motions.is_some() { "" } else { ", motion angle free" }
    )?;
    outln!("  motion {:.3} deg, positive phase {}", b.criteria.motion_deg, law.positive_text())?;
    print_criteria(&b.criteria, &cond)?;
    Ok(())
}

/// Writes the frame's full cycle to `path` (`-`: standard output).
fn emit_cycle(law: &ShedLaw, p: &Physical, path: &std::path::Path, source: &str) -> Result<()> {
    let text = loomkin_shed::frame_cycle_toml(law, p.stroke_mm, Some(p.speed_rpm), source)?;
    crate::output::text_to(&path.display().to_string(), &text)
}

fn window(a: WindowArgs) -> Result<()> {
    let Some(r) = a.loom.requirement(a.speed_rpm)? else {
        bail!("--carrier-speed-m-s and --reed-width-m are required");
    };
    let w = r.required_window_deg()?;
    if a.json {
        return output::json(&WindowReport::of(&r)?);
    }
    outln!("flight in the warp   φ_flight = 6n(L_cloth + l_carrier)/v = {:.3} deg", r.flight_deg())?;
    outln!("required window      φ_req = φ_flight + D_crossing      = {w:.3} deg")?;
    outln!("dwell threshold      T = 1/(1 + ΔA_S)                    = {:.4}", r.threshold())?;
    outln!("  (both sheets moving: T = 1 − ΔA_S/(2(1 + ΔA_S))         = {:.4})", r.threshold_both_sheets())?;
    Ok(())
}

fn plot(a: PlotArgs) -> Result<()> {
    output::check_outputs([Some(Out::plot("--output", &a.output))])?;
    if a.laws.is_empty() && a.spec.is_empty() {
        bail!("give at least one law name or --spec FILE.toml");
    }
    loomkin_shed::PLOT_POINTS.check_count_as("--points", a.points)?;
    let cond = conditions(&a.physical, a.threshold.threshold)?;
    let mut laws = Vec::new();
    for n in &a.laws {
        laws.push(load(Some(n), None)?);
    }
    for s in &a.spec {
        laws.push(load(None, Some(s))?);
    }
    let one = laws.len() == 1;
    let (mut s_series, mut a_series, mut windows, mut notes) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut edges = Vec::new();
    let h = a.physical.stroke_mm;
    let mut band_mm = 0.0;
    for (i, (name, law)) in laws.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let pts = loomkin_shed::cycle_curve(law, &cond, a.points)?;
        let marks = loomkin_shed::cycle_marks(law, &cond)?;
        let window = evaluate(law, &cond)?.window_deg;
        band_mm = loomkin_units::mm_from_m(marks.band_m);
        let (amax, amin) = (marks.accel_max, marks.accel_min);
        // One law: the window shaded and labelled, the peaks noted with their values; several:
        // each law's window edges marked on the band in its colour (shaded windows would pile
        // up), its peaks dotted and given in the legend.
        let label = if one {
            format!("{name} ({}°)", law.motion_deg())
        } else {
            format!("{name} {}°: window {}°, |a| {} m/s²", law.motion_deg(), sig4(window), sig4(amax.1.max(-amin.1)))
        };
        s_series.push(
            Series::line(label.clone(), pts.iter().map(|p| (p.angle_deg, loomkin_units::mm_from_m(p.s_m))).collect())
                .with_color(color),
        );
        a_series.push(Series::line(label, pts.iter().map(|p| (p.angle_deg, p.a_m_s2)).collect()).with_color(color));
        if one {
            windows.extend(
                marks
                    .windows_deg
                    .iter()
                    .filter(|w| w[1] > w[0])
                    .map(|&[from, to]| XBand::new(from, to, format!("window {}°", sig4(window)), XBand::WINDOW)),
            );
        } else {
            // A window starts where the frame enters the band around an extreme and ends where it
            // leaves it: the windows are bottom, top, bottom (see `cycle_marks`); the top band's
            // edge is T·h, the bottom band's (1 − T)·h. The cuts at 0° and 720° are no edges.
            let pts: Vec<(f64, f64)> = marks
                .windows_deg
                .iter()
                .enumerate()
                .flat_map(|(k, w)| {
                    let level = if k == 1 { h - band_mm } else { band_mm };
                    w.iter().map(move |&e| (e, level))
                })
                .filter(|p| p.0 > 0.0 && p.0 < 720.0)
                .collect();
            edges.push(Series::markers("", pts).with_color(color));
        }
        for (at, v) in [amax, amin] {
            notes.push(Note::new(
                at,
                v,
                if one { format!("{} m/s² at {}°", sig4(v), sig4(at)) } else { String::new() },
            ));
        }
    }
    s_series.extend(edges);
    let t = a.threshold.threshold;
    let band = |from: f64, to: f64, label: &str| YBand::new(from, to, label, [200, 30, 30]);
    let band_text = format!("threshold band T = {t}: within {} mm of an end", sig4(band_mm));
    let s_panel = Panel::new("frame position [mm]", s_series)
        .with_legend(Legend::Auto)
        .with_x_bands(windows.clone())
        .with_y_band(band(h - band_mm, h, &band_text))
        .with_y_band(band(0.0, band_mm, ""));
    let a_panel = Panel::new("frame acceleration [m/s²]", a_series)
        .with_legend(Legend::Hidden)
        .with_x_bands(windows.into_iter().map(|b| XBand { label: String::new(), ..b }))
        .with_notes(notes);
    let fig = Figure::new(
        format!(
            "Heald frame over two picks (stroke {h} mm, {} rpm, T = {t}){}",
            a.physical.speed_rpm,
            if one { "" } else { "; dots: window edges" }
        ),
        "main-shaft angle [deg]",
        vec![s_panel, a_panel],
    );
    output::figure(&fig, &a.output, &a.plot)
}
