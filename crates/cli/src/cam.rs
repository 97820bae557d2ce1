//! `loomkin cam …`: from a law to a part.

use crate::{output, util};
use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use loomkin_cams::table::{CamTable, Format, Motion, Spacing};
use loomkin_laws::{Cycle, LawSpec, StrokeUnit};
use serde_json::json;
use std::path::PathBuf;

/// Subcommands of `loomkin cam`.
#[derive(Debug, Subcommand)]
pub enum CamCommand {
    /// A controller cam table (xyvaj, poly5, csv, twincat, st) of a cycle file or a single rise,
    /// with its exact re-interpolation error.
    Table(TableArgs),
}

/// `cam table`.
#[derive(Debug, Args)]
pub struct TableArgs {
    /// The cycle file (TOML); or give --law, --stroke-mm (or --stroke-deg) and --motion-deg for a single rise.
    #[arg(required_unless_present = "law", conflicts_with = "law")]
    cycle: Option<PathBuf>,
    /// xyvaj (X,Y,V,A,J points), poly5 (fifth-degree segments), csv, twincat (motion-function point
    /// list), st (IEC 61131-3 ARRAY OF SMC_CAMXYVA).
    #[arg(long, value_name = "xyvaj|poly5|csv|twincat|st")]
    format: String,
    /// Points on every joint of the law and every D degrees from each joint (a shorter last step
    /// before a joint; default 1).
    #[arg(long, value_name = "D", conflicts_with = "tolerance", allow_hyphen_values = true)]
    step_deg: Option<f64>,
    /// Points on every joint and as few in between as keep the re-interpolation error within T
    /// (slave unit: mm, or deg for a swinging follower).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// Output file (`-` for standard output).
    #[arg(short, long)]
    output: String,
    /// A catalogue law for a single rise (see `loomkin law list`).
    #[arg(long)]
    law: Option<String>,
    /// A law parameter KEY=VALUE (repeatable).
    #[arg(long = "param", value_parser = util::parse_key_value, requires = "law")]
    params: Vec<(String, String)>,
    /// Stroke of the single rise in mm (translating follower).
    #[arg(long, requires = "law", conflicts_with = "stroke_deg", allow_hyphen_values = true)]
    stroke_mm: Option<f64>,
    /// Stroke of the single rise in deg (swinging follower).
    #[arg(long, requires = "law", allow_hyphen_values = true)]
    stroke_deg: Option<f64>,
    /// Master angle of the single rise, deg.
    #[arg(long, requires = "law", allow_hyphen_values = true)]
    motion_deg: Option<f64>,
    /// Print the report (points, decimals, exact errors) as JSON.
    #[arg(long)]
    json: bool,
}

/// Runs a `cam` subcommand.
pub fn run(cmd: CamCommand) -> Result<()> {
    match cmd {
        CamCommand::Table(a) => table(a),
    }
}

fn motion(a: &TableArgs) -> Result<(Motion, String)> {
    if let Some(path) = &a.cycle {
        let text = util::read_input(path)?;
        let cycle = Cycle::from_toml(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        return Ok((Motion::from_cycle(&cycle), path.display().to_string()));
    }
    let name = a.law.as_deref().unwrap_or("cycloidal");
    let law = LawSpec::parse(name, &a.params)?.build()?;
    let (stroke, unit) = match (a.stroke_mm, a.stroke_deg) {
        (Some(h), None) => (h, StrokeUnit::Mm),
        (None, Some(h)) => (h, StrokeUnit::Deg),
        _ => bail!("--stroke-mm or --stroke-deg is needed with --law"),
    };
    let Some(b) = a.motion_deg else { bail!("--motion-deg is needed with --law") };
    Ok((Motion::rise(&law, stroke, b, unit)?, format!("law {name}")))
}

fn table(a: TableArgs) -> Result<()> {
    let format = Format::parse(a.format.trim())?;
    let (motion, source) = motion(&a)?;
    let spacing = match a.tolerance {
        Some(t) => Spacing::Tolerance(t),
        None => Spacing::StepDeg(a.step_deg.unwrap_or(1.0)),
    };
    let table = CamTable::new(motion, spacing)?;
    let out = table.export(format)?;
    output::text_to(&a.output, &out.text)?;
    let u = table.unit_name();
    let e = &out.error;
    if a.json {
        let d = table.decimals();
        let report = json!({
            "source": source,
            "format": format.name(),
            "points": out.points,
            "unit": u,
            "spacing": table.spacing(),
            "interpolation": if format == Format::Poly5 { "poly5 segments as written" } else { loomkin_cams::table::INTERPOLATION },
            format!("max_position_error_{u}"): e.max_position_error,
            "max_position_error_at_deg": e.max_position_error_at_deg,
            format!("max_velocity_error_{u}_per_deg"): e.max_velocity_error,
            format!("max_accel_error_{u}_per_deg2"): e.max_accel_error,
            "decimals": {"master": d.master, "y": d.y, "v": d.v, "a": d.a, "j": d.j},
        });
        if a.output == "-" {
            output::note(format_args!("{}", serde_json::to_string_pretty(&report)?));
            return Ok(());
        }
        return output::json(&report);
    }
    output::note(format_args!(
        "cam table of {source}: {} points ({}); exact re-interpolation error {} {u} at {} deg (velocity {} {u}/deg, acceleration {} {u}/deg²)",
        out.points,
        format.name(),
        loomkin_units::compact(e.max_position_error),
        loomkin_units::compact(e.max_position_error_at_deg),
        loomkin_units::compact(e.max_velocity_error),
        loomkin_units::compact(e.max_accel_error),
    ));
    Ok(())
}
