//! `loomkin pick …`: shuttle picking dynamics of an elastic under-pick mechanism (Jederán 1959).

use crate::output::{self, Out, outln};
use crate::shard::ShardArgs;
use crate::util::{self, Format};
use anyhow::{Result, bail};
use clap::{Args, Subcommand, ValueEnum};
use loomkin_io::Table;
use loomkin_laws::LawSpec;
use loomkin_picking::units::M_PER_CM;
use loomkin_picking::{
    DesignSpec, History, Mechanism, Method, Outcome, PickError, RequiredVelocity, Setting, Settings, StartRule, Sweep,
    SweepRow, history, required_velocity_crossings, simulate, sweep_observed,
};
use loomkin_plot::{Figure, Legend, Note, Panel, Rule, Series, XBand, sig4};
use std::path::PathBuf;

/// Subcommands of `loomkin pick`.
#[derive(Debug, Subcommand)]
pub enum PickCommand {
    /// The designed compound law (eqs. 18–20) and the mechanism constants B, C, D (eq. 4).
    Design(DesignArgs),
    /// The actual motion under loom settings: end-of-pick values, or the time history (--csv).
    Simulate(SimulateArgs),
    /// One setting over a range (the paper's Figs. 5–8, 10), evaluated in parallel.
    Sweep(SweepArgs),
    /// Tolerance study: loom settings drawn from stated distributions (TOML), the results' percentiles,
    /// histograms and share failing a limit; seeded, reproducible, shardable.
    Montecarlo(crate::pick_montecarlo::MonteCarloArgs),
    /// Nominal and actual motion over the pick, like the paper's Fig. 2.
    Plot(PlotArgs),
}

/// The mechanism and its cam.
#[derive(Debug, Args, Clone, Default)]
pub struct ModelArgs {
    /// A mechanism described in TOML (`[mechanism]`, `[design]`, optional `[required]`; SI units).
    /// Without it: the paper's mechanism.
    #[arg(long, value_name = "FILE")]
    mechanism: Option<PathBuf>,
    /// A law of the catalogue as the nominal cam law instead of the compound law (same stroke
    /// and rise time; numerical route), e.g. `--law modified-sine`.
    #[arg(long)]
    law: Option<String>,
    /// A parameter of --law, e.g. `--param ramp=0.1`.
    #[arg(long = "param", value_name = "KEY=VALUE", value_parser = util::parse_key_value)]
    params: Vec<(String, String)>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Design: shuttle velocity V at the end of the pick, m/s; redesigns the cam", &DesignSpec::VELOCITY_M_S))]
    velocity_m_s: Option<f64>,
    /// Design: pick distance X, cm (the same as --distance-m, in centimetres).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "distance_m")]
    distance_cm: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Design: pick distance X, m", &DesignSpec::DISTANCE_M))]
    distance_m: Option<f64>,
    /// Design: distance X1 of the first (sine) stage, cm (the same as --first-stage-m, in centimetres).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "first_stage_m")]
    first_stage_cm: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Design: distance X1 of the first (sine) stage, m (X1 < X)", &DesignSpec::FIRST_STAGE_M))]
    first_stage_m: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Design: loom speed n1 the cam is designed for, rpm", &DesignSpec::SPEED_RPM))]
    design_speed_rpm: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Required velocity V_r: retardation p of the shuttle in the shed, %", &RequiredVelocity::RETARDATION_PCT))]
    retardation_pct: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Required velocity V_r: shuttle length plus shuttle race s, m", &RequiredVelocity::PATH_M))]
    path_m: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Required velocity V_r: free shed opening φ_s as crank angle, degrees", &RequiredVelocity::FREE_SHED_DEG))]
    free_shed_deg: Option<f64>,
}

/// Loom settings in the paper's practical units; without them the designed setting applies.
#[derive(Debug, Args, Clone, Default)]
pub struct SettingsArgs {
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Loom speed, rpm (left out: the speed the cam is designed for)", &Settings::SPEED_RPM))]
    speed_rpm: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Play of the picking-strap loop s'₀, mm (at most the stick length)", &Settings::PLAY_MM))]
    play_mm: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Height k of the strap loop on the picking stick, cm (k < l, the stick length; left out: the mechanism's)", &Settings::STRAP_CM))]
    strap_cm: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Shuttle weight, g (left out: the mechanism's)", &Settings::SHUTTLE_G))]
    shuttle_g: Option<f64>,
    #[arg(long, allow_hyphen_values = true, help = util::field_help("Checking force, kgf (left out: the mechanism's)", &Settings::CHECKING_KGF))]
    checking_kgf: Option<f64>,
    /// Where the shuttle starts on the nominal curve: the paper's rule or force equilibrium.
    #[arg(long, value_enum, default_value_t = StartArg::Paper)]
    start: StartArg,
}

/// `--start`.
#[derive(Debug, Clone, Copy, ValueEnum, Default)]
pub enum StartArg {
    /// t₀ from the play alone (the paper's §2.2).
    #[default]
    Paper,
    /// The shuttle starts when the picker force balances the checking force.
    Equilibrium,
}

/// `--method`.
#[derive(Debug, Clone, Copy, ValueEnum, Default)]
pub enum MethodArg {
    /// The paper's closed form (corrected); falls back to integration at a resonance.
    #[default]
    Closed,
    /// Numerical integration (DOP853).
    Ode,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Self {
        match m {
            MethodArg::Closed => Method::Closed,
            MethodArg::Ode => Method::Ode,
        }
    }
}

/// `pick design`.
#[derive(Debug, Args)]
pub struct DesignArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `pick simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    settings: SettingsArgs,
    /// Route: closed form or numerical integration.
    #[arg(long, value_enum, default_value_t = MethodArg::Closed)]
    method: MethodArg,
    #[command(flatten)]
    format: Format,
    /// Samples of the time history for --csv (both ends included).
    #[arg(long, default_value_t = History::POINTS.default_count())]
    points: usize,
}

/// `pick sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The setting to sweep: speed (rpm), play (mm), strap (cm), shuttle (g), checking (kgf).
    setting: String,
    /// First value, in the setting's unit.
    #[arg(long, allow_hyphen_values = true)]
    from: f64,
    /// Last value, in the setting's unit.
    #[arg(long, allow_hyphen_values = true)]
    to: f64,
    /// Number of points, both ends included.
    #[arg(long, alias = "steps")]
    points: usize,
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    settings: SettingsArgs,
    /// Route: closed form or numerical integration.
    #[arg(long, value_enum, default_value_t = MethodArg::Closed)]
    method: MethodArg,
    #[command(flatten)]
    format: Format,
    #[command(flatten)]
    shard: ShardArgs,
    /// Plot velocity, distance and accelerations against the setting to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv", "shard"])]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// `pick plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    settings: SettingsArgs,
    /// Route: closed form or numerical integration.
    #[arg(long, value_enum, default_value_t = MethodArg::Closed)]
    method: MethodArg,
    /// Output file, .svg or .png.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
    /// Points per curve.
    #[arg(long, default_value_t = History::PLOT_POINTS.default_count())]
    points: usize,
}

/// Runs a `pick` subcommand.
pub fn run(cmd: PickCommand) -> Result<()> {
    match cmd {
        PickCommand::Design(a) => design(a),
        PickCommand::Simulate(a) => simulate_cmd(a),
        PickCommand::Sweep(a) => sweep_cmd(a),
        PickCommand::Montecarlo(a) => crate::pick_montecarlo::run(a),
        PickCommand::Plot(a) => plot(a),
    }
}

/// A library error: solver failures are run failures (exit 1), everything else is bad input (exit 2).
pub(crate) fn lib_err(e: PickError) -> anyhow::Error {
    match e {
        PickError::Solver { .. } => util::failure(e),
        e => e.into(),
    }
}

pub(crate) fn mechanism(m: &ModelArgs) -> Result<Mechanism> {
    let mech = match &m.mechanism {
        Some(path) => Mechanism::from_toml(&util::read_input(path)?).map_err(lib_err)?,
        None => Mechanism::paper_default(),
    };
    let design = [m.velocity_m_s, m.distance_cm, m.distance_m, m.first_stage_cm, m.first_stage_m, m.design_speed_rpm];
    let mech = if design.iter().any(Option::is_some) {
        let mut spec = *mech.design_spec();
        spec.velocity_m_s = m.velocity_m_s.unwrap_or(spec.velocity_m_s);
        spec.distance_m = m.distance_cm.map(|v| v * M_PER_CM).or(m.distance_m).unwrap_or(spec.distance_m);
        spec.first_stage_m = m.first_stage_cm.map(|v| v * M_PER_CM).or(m.first_stage_m).unwrap_or(spec.first_stage_m);
        spec.speed_rpm = m.design_speed_rpm.unwrap_or(spec.speed_rpm);
        let required = *mech.required();
        // A range error names the flag the user typed, in its unit (not the library's `distance_m`
        // for a `--distance-cm`, nor the setting `speed_rpm` for `--design-speed-rpm`).
        let named = |e: PickError| match e {
            PickError::Range(r) if r.field == "distance_m" && m.distance_cm.is_some() => {
                PickError::Range(r.in_unit("distance_cm", 1.0 / M_PER_CM, "cm"))
            }
            PickError::Range(r) if r.field == "first_stage_m" && m.first_stage_cm.is_some() => {
                PickError::Range(r.in_unit("first_stage_cm", 1.0 / M_PER_CM, "cm"))
            }
            PickError::Range(r) if r.field == "speed_rpm" && m.design_speed_rpm.is_some() => {
                PickError::Range(r.renamed("design_speed_rpm"))
            }
            e => e,
        };
        Mechanism::new(*mech.params(), spec).and_then(|n| n.with_required(required)).map_err(named).map_err(lib_err)?
    } else {
        mech
    };
    let mech = if m.retardation_pct.is_some() || m.path_m.is_some() || m.free_shed_deg.is_some() {
        let mut r = *mech.required();
        r.retardation_pct = m.retardation_pct.unwrap_or(r.retardation_pct);
        r.path_m = m.path_m.unwrap_or(r.path_m);
        r.free_shed_deg = m.free_shed_deg.unwrap_or(r.free_shed_deg);
        mech.with_required(r).map_err(lib_err)?
    } else {
        mech
    };
    if m.law.as_deref().is_none_or(|l| l == "compound") && !m.params.is_empty() {
        bail!("--param needs a catalogue --law: the compound law has no parameters (it is designed from V, X, X1)");
    }
    match &m.law {
        Some(name) if name != "compound" => Ok(mech.with_law(LawSpec::parse(name, &m.params)?).map_err(lib_err)?),
        _ => Ok(mech),
    }
}

fn settings(mech: &Mechanism, a: &SettingsArgs) -> Result<Settings> {
    let mut st = Settings::designed(mech);
    let flags = [
        (Setting::Speed, a.speed_rpm),
        (Setting::Play, a.play_mm),
        (Setting::Strap, a.strap_cm),
        (Setting::Shuttle, a.shuttle_g),
        (Setting::Checking, a.checking_kgf),
    ];
    for (s, v) in flags {
        if let Some(v) = v {
            st = s.set(st, v, mech)?;
        }
    }
    Ok(st.with_start(match a.start {
        StartArg::Paper => StartRule::Paper,
        StartArg::Equilibrium => StartRule::Equilibrium,
    }))
}

fn note(o: &Outcome) {
    if let Some(n) = &o.note {
        output::note(format_args!("loomkin: note: {n}"));
    }
}

fn design(a: DesignArgs) -> Result<()> {
    let mech = mechanism(&a.model)?;
    let d = mech.design();
    let k = d.constants;
    let spec = d.spec;
    if a.json {
        return output::json(&mech.design_report());
    }
    if matches!(mech.cam(), loomkin_picking::Cam::Compound) {
        outln!("compound picking law (sine, then constant acceleration), eqs. 18–20")?;
    } else {
        outln!(
            "cam law {} (the stroke and rise time of the compound law designed by eqs. 18–20 below)",
            mech.cam().label()
        )?;
    }
    outln!(
        "  for V = {} m/s, X = {} m, X1 = {} m at n = {} rpm",
        spec.velocity_m_s,
        spec.distance_m,
        spec.first_stage_m,
        spec.speed_rpm
    )?;
    outln!("  A   = {:.4} m/s²   peak shuttle acceleration (eq. 20)", d.a_m_s2)?;
    outln!("  μ   = {:.4} 1/s    sine-stage frequency (eq. 19)", d.mu_1_s)?;
    outln!("  τ   = {:.6} s    end of the sine stage, π/(2μ)", d.tau_s)?;
    outln!("  T'  = {:.6} s    end of the pick (eq. 18)", d.t_end_s)?;
    outln!("  nominal stroke s(T') − D = {:.6} m", d.stroke_m())?;
    outln!("mechanism constants (eq. 4): B·ẍ + (C+1)·x = s − D")?;
    outln!("  B   = {:.6e} s²", k.b_s2)?;
    outln!("  C   = {:.6e}", k.c)?;
    outln!("  D   = {:.6e} m", k.d_m)?;
    outln!("  ψ   = √((C+1)/B) = {:.4} 1/s (natural frequency)", k.natural_1_s())?;
    Ok(())
}

fn history_table(h: &History) -> Result<Table> {
    let mut t = Table::new(["t_s", "s_m", "v_s_m_s", "a_s_m_s2", "x_m", "v_m_s", "a_m_s2"]);
    for s in &h.samples {
        let (n, x) = (s.nominal, s.actual);
        t.push(vec![s.t_s, n.s_m, n.v_m_s, n.a_m_s2, x.x_m, x.v_m_s, x.a_m_s2])?;
    }
    Ok(t)
}

fn simulate_cmd(a: SimulateArgs) -> Result<()> {
    let mech = mechanism(&a.model)?;
    let st = settings(&mech, &a.settings)?;
    let method = a.method.into();
    // Checked whether or not the samples are printed: a value out of range is never taken in silence.
    History::POINTS.check_count_as("--points", a.points)?;
    if a.format.csv {
        let h = history(&mech, &st, method, a.points).map_err(lib_err)?;
        note(&h.outcome);
        return output::csv(&history_table(&h)?);
    }
    let o = simulate(&mech, &st, method).map_err(lib_err)?;
    note(&o);
    if a.format.json {
        return output::json(&o);
    }
    outln!("pick with cam '{}' by the {} route", mech.cam().label(), o.method.name())?;
    outln!(
        "  speed {} rpm, play {} mm, strap k = {} cm, shuttle {} g, checking {} kgf",
        loomkin_units::compact(Setting::Speed.value(&st)),
        loomkin_units::compact(Setting::Play.value(&st)),
        loomkin_units::compact(Setting::Strap.value(&st)),
        loomkin_units::compact(Setting::Shuttle.value(&st)),
        loomkin_units::compact(Setting::Checking.value(&st))
    )?;
    outln!("  t0           = {:.6} s   (delay taking up the play)", o.t0_s)?;
    outln!(
        "  t_end        = {:.6} s   ({})",
        o.t_end_s,
        if o.end == loomkin_picking::PickEnd::CamEnd { "end of the cam's rise" } else { "the shuttle left the picker" }
    )?;
    outln!("  distance     = {:.6} m", o.distance_m)?;
    outln!(
        "  velocity     = {:.4} m/s  (required {:.4} m/s, {} %)",
        o.velocity_m_s,
        o.required_velocity_m_s,
        signed(o.velocity_vs_required_pct)
    )?;
    outln!("  accel at end = {:.3} m/s²", o.accel_end_m_s2)?;
    outln!("  accel peak   = {:.3} m/s² at t = {:.6} s", o.accel_peak_m_s2, o.t_peak_s)?;
    outln!("  B' = {:.6e} s², C' = {:.6e}, D' = {:.6e} m, ψ = {:.3} 1/s", o.b_s2, o.c, o.d_m, o.natural_1_s)?;
    Ok(())
}

const SWEEP_COLUMNS: [&str; 10] = [
    "t_end_s",
    "t0_s",
    "distance_m",
    "velocity_m_s",
    "accel_end_m_s2",
    "accel_peak_m_s2",
    "t_peak_s",
    "required_velocity_m_s",
    "velocity_vs_required_pct",
    "ode_fallback",
];

/// A point of the sweep as its CSV row (the setting's value, then [`SWEEP_COLUMNS`]).
fn sweep_row(r: &SweepRow) -> [f64; 11] {
    let o = &r.outcome;
    [
        r.value,
        o.t_end_s,
        o.t0_s,
        o.distance_m,
        o.velocity_m_s,
        o.accel_end_m_s2,
        o.accel_peak_m_s2,
        o.t_peak_s,
        o.required_velocity_m_s,
        o.velocity_vs_required_pct,
        if o.note.is_some() { 1.0 } else { 0.0 },
    ]
}

/// Points computed (in parallel) and printed at a time by `pick sweep --csv`: the memory held is
/// one block's rows, whatever `--points` (10⁶ points held 450 MB before they were streamed).
const SWEEP_BLOCK: usize = 1 << 14;

/// `pick sweep --csv`: the rows printed a block at a time as they are computed (the first rows
/// of 10⁶ points after a fraction of a second, not after the whole sweep); the same bytes as the
/// whole table printed at once. The note on the points where the closed form fell back to
/// numerical integration follows the output. A point refused inside the range (its ends are
/// checked first) ends the output there with the one error line.
#[allow(clippy::too_many_arguments)]
fn sweep_csv(
    mech: &Mechanism,
    st: &Settings,
    setting: Setting,
    a: &SweepArgs,
    method: Method,
    items: std::ops::Range<usize>,
    progress: &util::Progress,
) -> Result<()> {
    let mut columns = vec![setting.key()];
    columns.extend(SWEEP_COLUMNS.iter().map(|c| c.to_string()));
    let (mut fallbacks, mut first, mut failed) = (0usize, None::<SweepRow>, None::<anyhow::Error>);
    let n = items.len();
    // The ends of the range first: a setting beyond what the model takes (a play beyond the cam's
    // reach) is refused there before a row is printed, as when the whole table was made first.
    for i in [items.start, items.end.saturating_sub(1)].into_iter().filter(|&i| i < items.end) {
        sweep_observed(mech, st, setting, a.from, a.to, a.points, method, i..i + 1, &|| {}).map_err(lib_err)?;
    }
    let blocks = items.clone().step_by(SWEEP_BLOCK).map(|lo| lo..(lo + SWEEP_BLOCK).min(items.end));
    let rows = blocks
        .map_while(|b| {
            match sweep_observed(mech, st, setting, a.from, a.to, a.points, method, b, &|| progress.inc(1)) {
                Ok(s) => Some(s.rows),
                Err(e) => {
                    failed = Some(lib_err(e));
                    None
                }
            }
        })
        .flatten()
        .inspect(|r| {
            if r.outcome.note.is_some() {
                fallbacks += 1;
                if first.is_none() {
                    first = Some(r.clone());
                }
            }
        })
        .map(|r| sweep_row(&r));
    output::csv_rows(&columns, a.shard.header(), rows)?;
    progress.finish();
    if let Some(e) = failed {
        return Err(e);
    }
    if let Some(first) = &first {
        output::note_after_output(format_args!("{}", fallback_note(setting, fallbacks, n, first)))?;
    }
    Ok(())
}

/// The note on the points where the closed form fell back to numerical integration.
fn fallback_note(setting: Setting, fallbacks: usize, points: usize, first: &SweepRow) -> String {
    format!(
        "loomkin: note: at {fallbacks} of {points} points (first at {} = {} {}) {}",
        setting.name(),
        first.value,
        setting.unit(),
        first.outcome.note.as_deref().unwrap_or("")
    )
}

fn sweep_cmd(a: SweepArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let setting = Setting::parse(&a.setting)?;
    Sweep::POINTS.check_count_as("--points", a.points)?;
    a.shard.check(a.format)?;
    let method: Method = a.method.into();
    let items = a.shard.get().items(a.points);
    // This shard's points run in parallel; each is held as a row (and again as a row of the output).
    let n = items.len() as f64;
    let output_bytes = if a.format.json { 1500.0 } else { 300.0 };
    let cost = Sweep::cost(n, method, util::cores(), output_bytes);
    crate::util::check_budget("--points", a.points, cost)?;
    // The swept setting's own flag would be overwritten by the sweep: refused, not ignored.
    let own = [
        (Setting::Speed, "--speed-rpm", a.settings.speed_rpm),
        (Setting::Play, "--play-mm", a.settings.play_mm),
        (Setting::Strap, "--strap-cm", a.settings.strap_cm),
        (Setting::Shuttle, "--shuttle-g", a.settings.shuttle_g),
        (Setting::Checking, "--checking-kgf", a.settings.checking_kgf),
    ];
    if let Some((_, flag, _)) = own.iter().find(|(s, _, v)| *s == setting && v.is_some()) {
        bail!(
            "{}: {flag} is what `pick sweep {}` varies (from --from to --to): leave it out",
            flag.trim_start_matches("--").replace('-', "_"),
            a.setting
        );
    }
    let mech = mechanism(&a.model)?;
    let st = settings(&mech, &a.settings)?;
    let progress = util::Progress::new(items.len() as u64, "points");
    if a.format.csv {
        return sweep_csv(&mech, &st, setting, &a, method, items, &progress);
    }
    let s = sweep_observed(&mech, &st, setting, a.from, a.to, a.points, method, items, &|| progress.inc(1))
        .map_err(lib_err)?;
    progress.finish();
    let fallbacks: Vec<f64> = s.fallbacks().map(|r| r.value).collect();
    if let Some(first) = s.fallbacks().next() {
        output::note(format_args!("{}", fallback_note(setting, fallbacks.len(), s.rows.len(), first)));
    }
    if let Some(path) = &a.output {
        let crossings = required_velocity_crossings(&mech, &st, &s, method).map_err(lib_err)?;
        return output::figure(&sweep_figure(&s, &crossings), path, &a.plot);
    }
    if a.format.json {
        if a.shard.given() {
            return output::json_lines(s.rows.iter().map(|r| r.report(setting)));
        }
        return output::json(&s.report(method));
    }
    outln!(
        "{:>14} {:>10} {:>10} {:>12} {:>14} {:>15} {:>13} {:>9}",
        setting.key(),
        "t_end_s",
        "distance_m",
        "velocity_m_s",
        "accel_end_m_s2",
        "accel_peak_m_s2",
        "V_r_m_s",
        "V/V_r-1_%"
    )?;
    for r in &s.rows {
        let o = &r.outcome;
        outln!(
            "{:>14.4} {:>10.6} {:>10.6} {:>12.4} {:>14.3} {:>15.3} {:>13.4} {:>9}",
            r.value,
            o.t_end_s,
            o.distance_m,
            o.velocity_m_s,
            o.accel_end_m_s2,
            o.accel_peak_m_s2,
            o.required_velocity_m_s,
            loomkin_units::fixed(o.velocity_vs_required_pct, 2)
        )?;
    }
    Ok(())
}

/// A percentage with two places and its sign (`+1.25`, `-0.40`, `+0.00` for a shortfall that
/// rounds to nothing).
fn signed(pct: f64) -> String {
    let text = loomkin_units::fixed(pct, 2);
    if text.starts_with('-') { text } else { format!("+{text}") }
}

/// The sweep's end-of-pick values; where the velocity is below the required V_r the setting range
/// is shaded red, its ends (located on the model) marked.
fn sweep_figure(s: &Sweep, crossings: &[f64]) -> Figure {
    let pts = |f: &dyn Fn(&Outcome) -> f64| s.rows.iter().map(|r| (r.value, f(&r.outcome))).collect::<Vec<_>>();
    let unit = s.setting.unit();
    // The intervals of the swept range between crossings where the margin V − V_r is negative.
    let mut edges = vec![s.rows.first().map_or(0.0, |r| r.value)];
    edges.extend_from_slice(crossings);
    edges.push(s.rows.last().map_or(0.0, |r| r.value));
    let below: Vec<XBand> = edges
        .windows(2)
        .filter(|w| w[1] > w[0])
        .filter(|w| {
            let mid = 0.5 * (w[0] + w[1]);
            let near = s.rows.iter().min_by(|a, b| (a.value - mid).abs().total_cmp(&(b.value - mid).abs()));
            near.is_some_and(|r| r.outcome.velocity_m_s < r.outcome.required_velocity_m_s)
        })
        .map(|w| XBand::new(w[0], w[1], "V below V_r", [200, 30, 30]))
        .collect();
    let unlabelled = || below.iter().map(|b| XBand { label: String::new(), ..b.clone() }).collect::<Vec<_>>();
    let notes = crossings.iter().filter_map(|&x| {
        let near = s.rows.iter().min_by(|a, b| (a.value - x).abs().total_cmp(&(b.value - x).abs()))?;
        Some(Note::new(x, near.outcome.required_velocity_m_s, format!("V = V_r at {} {unit}", sig4(x))))
    });
    let panels = vec![
        Panel::new(
            "velocity [m/s]",
            vec![
                Series::line("shuttle velocity at the end of the pick", pts(&|o| o.velocity_m_s)),
                Series::line("required velocity V_r", pts(&|o| o.required_velocity_m_s)).with_dashes(),
            ],
        )
        .with_x_bands(below.clone())
        .with_notes(notes),
        Panel::new("distance [cm]", vec![Series::line("path of the pick X", pts(&|o| o.distance_m * 100.0))])
            .with_x_bands(unlabelled()),
        Panel::new(
            "acceleration [m/s²]",
            vec![
                Series::line("at the end of the pick", pts(&|o| o.accel_end_m_s2)),
                Series::line("peak during the pick", pts(&|o| o.accel_peak_m_s2)).with_dashes(),
            ],
        )
        .with_x_bands(unlabelled()),
    ];
    Figure::new(
        format!("Effect of the {} on the end of the pick", s.setting.description()),
        format!("{} [{unit}]", s.setting.description()),
        panels,
    )
}

fn plot(a: PlotArgs) -> Result<()> {
    output::check_outputs([Some(Out::plot("--output", &a.output))])?;
    History::PLOT_POINTS.check_count_as("--points", a.points)?;
    let mech = mechanism(&a.model)?;
    let st = settings(&mech, &a.settings)?;
    let method = a.method.into();
    let h = history(&mech, &st, method, a.points).map_err(lib_err)?;
    note(&h.outcome);
    let designed = Settings::designed(&mech).with_start(st.start);
    let reference =
        if st != designed { Some(history(&mech, &designed, method, a.points).map_err(lib_err)?) } else { None };
    let ms = loomkin_units::ms_from_s;
    let curve = |h: &History, f: &dyn Fn(&loomkin_picking::Sample) -> f64| {
        h.samples.iter().map(|s| (ms(s.t_s), f(s))).collect::<Vec<_>>()
    };
    let mut panels = vec![
        Panel::new(
            "displacement [mm]",
            vec![
                Series::line("nominal s", curve(&h, &|s| loomkin_units::mm_from_m(s.nominal.s_m))),
                Series::line("actual x", curve(&h, &|s| loomkin_units::mm_from_m(s.actual.x_m))),
            ],
        )
        .with_legend(Legend::Auto),
        Panel::new(
            "velocity [m/s]",
            vec![
                Series::line("nominal v_s", curve(&h, &|s| s.nominal.v_m_s)),
                Series::line("actual v", curve(&h, &|s| s.actual.v_m_s)),
            ],
        )
        .with_legend(Legend::Auto),
        Panel::new(
            "acceleration [m/s²]",
            vec![
                Series::line("nominal a_s", curve(&h, &|s| s.nominal.a_m_s2)),
                Series::line("actual a", curve(&h, &|s| s.actual.a_m_s2)),
            ],
        )
        .with_legend(Legend::Auto),
    ];
    if let Some(r) = &reference {
        panels[0]
            .series
            .push(Series::line("actual x, designed setting", curve(r, &|s| loomkin_units::mm_from_m(s.actual.x_m))));
        panels[1].series.push(Series::line("actual v, designed setting", curve(r, &|s| s.actual.v_m_s)));
        panels[2].series.push(Series::line("actual a, designed setting", curve(r, &|s| s.actual.a_m_s2)));
    }
    // The end of the pick on every panel (labelled once) and the velocity the shuttle leaves with.
    let o = &h.outcome;
    let end = ms(o.t_end_s);
    let mark = |label: String| Rule::x(end, label).with_color([90, 90, 90]).with_dash(loomkin_plot::Dash::DashDot);
    let panels: Vec<Panel> = panels
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            p.with_rule(mark(if i == 0 { format!("end of the pick, {} ms", sig4(end)) } else { String::new() }))
        })
        .collect();
    let mut panels = panels;
    panels[1] = panels[1].clone().with_notes([Note::new(
        end,
        o.velocity_m_s,
        format!("end velocity {} m/s (V_r {} m/s)", sig4(o.velocity_m_s), sig4(o.required_velocity_m_s)),
    )]);
    let title = format!(
        "Picking: nominal and actual motion (cam {}, {} rpm, play {} mm, k = {} cm)",
        mech.cam().label(),
        loomkin_units::compact(Setting::Speed.value(&st)),
        loomkin_units::compact(Setting::Play.value(&st)),
        loomkin_units::compact(Setting::Strap.value(&st))
    );
    output::figure(&Figure::new(title, "time from the shuttle's start t [ms]", panels), &a.output, &a.plot)
}
