//! `loomkin insert …`: weft insertion beyond the shuttle — the time budget of any carrier, and
//! the carriers' own models (rapier here; projectile and air jet in `insert_air.rs`).

use crate::loom::PatternArgs;
use crate::output::{self, Out, outln};
use anyhow::{Result, anyhow};
use clap::{Args, Subcommand};
use loomkin_insertion::{BudgetInputs, WindowSource};
use loomkin_loom::Loom;
use loomkin_units::ShaftSpeed;
use std::path::{Path, PathBuf};

/// `loomkin insert`.
#[derive(Debug, Subcommand)]
pub enum InsertCommand {
    /// The time budget of a carrier: the highest loom speed for a reed width, the carrier speed a loom speed needs,
    /// energy and drive power per pick.
    Budget(BudgetArgs),
    /// A double rapier (`[insertion] kind = "rapier"`): the transfer, the heads' peaks, their clearance in the shed
    /// over every pick of the pattern.
    Rapier(RapierArgs),
    /// Torsion-bar projectile picking (`[insertion] kind = "projectile"`): the bar's energy, the launch speed, the
    /// flight and arrival angle, the brake, the sley's dwell, the guide teeth's clearance over every pick.
    Projectile(crate::insert_air::ProjectileArgs),
    /// An air jet (`[insertion] kind = "airjet"`): the yarn tip's flight on the main nozzle's and the relay
    /// nozzles' air, its arrival, and the relay plan that opens each group least.
    Airjet(crate::insert_air::AirjetArgs),
}

/// `loomkin insert budget`.
#[derive(Debug, Args)]
pub struct BudgetArgs {
    /// The loom file (TOML); without it every quantity comes from the flags.
    loom: Option<PathBuf>,
    /// The pattern whose clear-shed window (as `loom check` finds it) is the insertion window; without it the
    /// file's entry and exit angles.
    #[command(flatten)]
    pattern: PatternArgs,
    /// Reed space, mm (overrides the file's `[insertion] reed_width_mm`).
    #[arg(long)]
    reed_width_mm: Option<f64>,
    /// Carrier length along the weft, mm (overrides the file's).
    #[arg(long)]
    carrier_length_mm: Option<f64>,
    /// The insertion window, deg of main shaft (overrides the file's entry-to-exit or clear-shed window).
    #[arg(long)]
    window_deg: Option<f64>,
    /// The carrier's mean speed across the shed, m/s (overrides the file's).
    #[arg(long)]
    speed_m_s: Option<f64>,
    /// Loom speed for the required carrier speed and the drive power, rpm (default: the file's `speed_rpm`; without a
    /// file, the highest speed).
    #[arg(long)]
    speed_rpm: Option<f64>,
    /// The carrier's mass, g: energy per pick (½·m·v̄² at the mean speed) and drive power.
    #[arg(long)]
    carrier_mass_g: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Runs `loomkin insert …`.
pub fn run(cmd: InsertCommand) -> Result<()> {
    match cmd {
        InsertCommand::Budget(a) => run_budget(a),
        InsertCommand::Rapier(a) => run_rapier(a),
        InsertCommand::Projectile(a) => crate::insert_air::run_projectile(a),
        InsertCommand::Airjet(a) => crate::insert_air::run_airjet(a),
    }
}

/// The loom file, read and checked.
fn read_loom(path: &Path) -> Result<Loom> {
    let text = crate::util::read_input(path)?;
    Loom::from_toml(&text).map_err(|e| anyhow!("{}: {e}", path.display()))
}

fn run_budget(a: BudgetArgs) -> Result<()> {
    let base = match &a.loom {
        Some(path) => {
            let loom = read_loom(path)?;
            let given = a.pattern.given();
            let pattern = if given { Some(crate::loom::read(path, &a.pattern)?.1) } else { None };
            let b = loomkin_loom::insertion::budget_of(&loom, pattern.as_ref()).map_err(crate::loom::in_file(path))?;
            Some(b)
        }
        None => {
            if a.pattern.given() {
                return Err(anyhow!("--wif, --lift-plan: {}", loomkin_insertion::budget::PATTERN_NEEDS_LOOM));
            }
            None
        }
    };
    let flag_name = |field: &str| format!("--{}", field.replace('_', "-"));
    let flag = |e: loomkin_units::RangeError| -> anyhow::Error {
        let name = flag_name(&e.field);
        e.renamed(name).into()
    };
    let inputs = BudgetInputs {
        reed_width_mm: a.reed_width_mm,
        carrier_length_mm: a.carrier_length_mm,
        window_deg: a.window_deg,
        speed_m_s: a.speed_m_s,
        speed_rpm: a.speed_rpm,
        carrier_mass_g: a.carrier_mass_g,
    };
    let b = inputs.onto(base).map_err(|m| anyhow!(m.message(&flag_name(m.field))))?;
    let r = b.report().map_err(flag)?;
    if a.json {
        return output::json(&r);
    }
    let source = match r.window_source {
        WindowSource::Given => "given",
        WindowSource::EntryExit => "from the entry and exit angles",
        WindowSource::ClearShed => "the clear-shed window of the pattern",
    };
    outln!(
        "reed space {} mm, carrier {} mm, window {:.3}° ({source}), carrier mean speed {:.3} m/s",
        loomkin_units::compact(r.reed_width_mm),
        loomkin_units::compact(r.carrier_length_mm),
        r.window_deg,
        r.speed_m_s
    )?;
    outln!("highest loom speed {:.2} picks/min", r.max_picks_per_min)?;
    outln!("at {:.2} rpm the carrier needs a mean speed of {:.3} m/s", r.speed_rpm, r.required_speed_m_s)?;
    if let (Some(m), Some(e), Some(p)) = (r.carrier_mass_g, r.energy_per_pick_j, r.drive_power_w) {
        outln!(
            "a {} g carrier takes {:.4} J per pick at its mean speed: {:.2} W at {:.2} rpm",
            loomkin_units::compact(m),
            e,
            p,
            r.speed_rpm
        )?;
    }
    Ok(())
}

/// `loomkin insert rapier`.
#[derive(Debug, Args)]
pub struct RapierArgs {
    /// The loom file (TOML) with `[insertion] kind = "rapier"` and its `[insertion.rapier.bringer]` and `.taker]`.
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
    /// Plot the tips across the reed, the heads' speeds and the worst pick's clearance (.svg or .png).
    #[arg(short, long, conflicts_with = "json")]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// What a carrier's command does first and last: its output path checked, the loom file and the
/// pattern read, the speed (the flag's, else the file's); then the check run and, when asked, its
/// plot written or its JSON printed.
pub(crate) struct CarrierRun<'a> {
    pub(crate) loom_path: &'a Path,
    pub(crate) output: Option<&'a PathBuf>,
    pub(crate) plot: &'a crate::util::PlotOpts,
    pub(crate) json: bool,
}

impl CarrierRun<'_> {
    /// The loom, the pattern and the speed.
    pub(crate) fn read(
        &self,
        pattern: &PatternArgs,
        speed_rpm: Option<f64>,
    ) -> Result<(Loom, loomkin_loom::Pattern, ShaftSpeed)> {
        output::check_outputs([self.output.map(|p| Out::plot("--output", p))])?;
        let (loom, pattern) = crate::loom::read(self.loom_path, pattern)?;
        let speed = Self::speed(&loom, speed_rpm)?;
        Ok((loom, pattern, speed))
    }

    /// The loom and the speed, for a carrier whose figures do not depend on the pattern.
    pub(crate) fn read_without_pattern(&self, speed_rpm: Option<f64>) -> Result<(Loom, ShaftSpeed)> {
        output::check_outputs([self.output.map(|p| Out::plot("--output", p))])?;
        let loom = read_loom(self.loom_path)?;
        let speed = Self::speed(&loom, speed_rpm)?;
        Ok((loom, speed))
    }

    fn speed(loom: &Loom, speed_rpm: Option<f64>) -> Result<ShaftSpeed> {
        Ok(match speed_rpm {
            Some(v) => ShaftSpeed::from_rpm_field("--speed-rpm", v)?,
            None => loom.speed,
        })
    }

    /// A loom error, named with the file where it is about the file ([`crate::loom::in_file`]).
    pub(crate) fn named(&self, e: loomkin_loom::LoomError) -> anyhow::Error {
        crate::loom::in_file(self.loom_path)(e)
    }

    /// The plot (with `-o`) or the JSON (with `--json`) of `check`; `false` when neither was asked.
    pub(crate) fn plot_or_json<T: serde::Serialize>(
        &self,
        check: &T,
        figure: impl FnOnce() -> loomkin_loom::Result<loomkin_plot::Figure>,
    ) -> Result<bool> {
        if let Some(out) = self.output {
            let fig = figure().map_err(|e| self.named(e))?;
            output::figure(&fig, out, self.plot)?;
            return Ok(true);
        }
        if self.json {
            output::json(check)?;
            return Ok(true);
        }
        Ok(false)
    }
}

fn run_rapier(a: RapierArgs) -> Result<()> {
    let run = CarrierRun { loom_path: &a.loom, output: a.output.as_ref(), plot: &a.plot, json: a.json };
    let (loom, pattern, speed) = run.read(&a.pattern, a.speed_rpm)?;
    let c = loomkin_loom::insertion::rapier_check(&loom, &pattern, speed).map_err(|e| run.named(e))?;
    if run.plot_or_json(&c, || loomkin_loom::insertion::rapier_figure(&loom, &pattern, &c, speed))? {
        return Ok(());
    }
    let r = &c.rapier;
    outln!(
        "rapier at {} rpm: transfer overlap {:.3} mm at {:.3}°, the tips meet {:.3} mm from the bringer's selvedge \
         at {:.3}° closing at {:.3} m/s; heads moving together at {:.3} m/s at the transfer",
        r.speed_rpm,
        r.transfer_overlap_mm,
        r.transfer_deg,
        r.transfer_position_mm,
        r.meet_deg,
        r.transfer_relative_speed_m_s,
        r.transfer_speed_m_s
    )?;
    for (name, h) in [("bringer", &r.bringer), ("taker", &r.taker)] {
        outln!(
            "{name}: stroke {:.3} mm, inner reversing point at {:.3}° ({:.3} mm inside its selvedge), in the shed \
             from {:.3}° to {:.3}°, peak speed {:.3} m/s, peak acceleration {:.1} m/s²",
            h.stroke_mm,
            h.inner_deg,
            h.inner_position_mm,
            h.entry_deg,
            h.exit_deg,
            h.peak_speed_m_s,
            h.peak_acceleration_m_s2
        )?;
    }
    let cl = &c.clearance;
    outln!(
        "least clearance {:.3} mm at pick {} of {}, {:.3}°, {:.1} mm from the bringer's selvedge{}",
        cl.min_clearance_mm,
        cl.worst_pick,
        c.picks,
        cl.worst_angle_deg,
        cl.worst_position_mm,
        if cl.min_clearance_mm < 0.0 { ": the head touches the warp" } else { "" }
    )
}
