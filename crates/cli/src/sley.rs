//! `loomkin sley …`: the sley (batten) linkage of a loom file — reed motion, back dwell, forces,
//! crank torque — and the synthesis of a four-bar for a target stroke and back dwell.

use crate::output::{self, Out, outln};
use crate::util::{self, Format};
use anyhow::{Result, anyhow};
use clap::{Args, Subcommand};
use loomkin_drive::{Assembly, Sley, SleyAnalysis, SleyError, SleyRow, SleyTarget};
use loomkin_io::Table;
use loomkin_loom::Loom;
use loomkin_plot::{Figure, Note, Panel, Series, XBand, sig4};
use loomkin_units::ShaftSpeed;
use std::path::{Path, PathBuf};

/// `loomkin sley`.
#[derive(Debug, Subcommand)]
pub enum SleyCommand {
    /// The sley of a loom file: reed stroke and back dwell, reed motion, inertia force, rod and bearing forces, crank torque.
    Analyze(AnalyzeArgs),
    /// A crank-rocker four-bar for a target reed stroke and back dwell, with the largest least transmission angle.
    Synthesize(SynthesizeArgs),
}

/// `loomkin sley synthesize`.
#[derive(Debug, Args)]
pub struct SynthesizeArgs {
    /// The reed's stroke, mm (arc of the beating point between its dead centres).
    #[arg(long = "reed-stroke-mm", visible_alias = "stroke-mm")]
    stroke_mm: f64,
    /// The back dwell wanted, deg of main shaft (about 25° for a projectile loom, longer for a rapier loom).
    #[arg(long)]
    back_dwell_deg: f64,
    /// How near its back position the reed counts as dwelling, mm (below the stroke).
    #[arg(long, default_value_t = SleyAnalysis::DWELL_TOLERANCE_MM.default_value())]
    dwell_tolerance_mm: f64,
    /// Rocking shaft to the reed's beating point, mm.
    #[arg(long, default_value_t = SleyTarget::REED_HEIGHT_MM.default_value())]
    reed_height_mm: f64,
    #[arg(long, help = format!("{} (left out: {} of the reed height; it scales crank, rod and pivot only)", util::field_help("Rocking shaft to the rod's pin, mm", &SleyTarget::SWORD_MM), SleyTarget::SWORD_SHARE))]
    sword_mm: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// `loomkin sley analyze`.
#[derive(Debug, Args)]
pub struct AnalyzeArgs {
    /// The loom file (TOML) with a `[sley]` table.
    loom: PathBuf,
    /// Main-shaft speed in rpm (default: the loom file's `speed_rpm`).
    #[arg(long)]
    speed_rpm: Option<f64>,
    /// How near its back position the reed counts as dwelling, mm (below the reed's stroke).
    #[arg(long, default_value_t = SleyAnalysis::DWELL_TOLERANCE_MM.default_value())]
    dwell_tolerance_mm: f64,
    /// Curve rows of --csv and the plot over one turn.
    #[arg(long, default_value_t = SleyAnalysis::POINTS.default_count())]
    points: usize,
    #[command(flatten)]
    format: Format,
    /// Plot reed displacement, velocity, acceleration and the crank torque to this file (.svg or .png).
    #[arg(short, long, conflicts_with_all = ["json", "csv"])]
    output: Option<PathBuf>,
    #[command(flatten)]
    plot: util::PlotOpts,
}

/// Runs `loomkin sley …`.
pub fn run(cmd: SleyCommand) -> Result<()> {
    match cmd {
        SleyCommand::Analyze(a) => run_analyze(a),
        SleyCommand::Synthesize(a) => run_synthesize(a),
    }
}

/// The loom file's sley and speed.
fn read_sley(path: &Path) -> Result<(Sley, Loom)> {
    let text = util::read_input(path)?;
    let loom = Loom::from_toml(&text).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    let sley = loom.sley.clone().ok_or_else(|| {
        anyhow!(
            "{}: sley: the loom file has no [sley] table (crank_mm, rod_mm, sword_mm, …; see docs/drive.md)",
            path.display()
        )
    })?;
    Ok((sley, loom))
}

/// A library error about the dwell tolerance, named by the flag.
fn flag_named(e: SleyError) -> anyhow::Error {
    match e {
        SleyError::Range(r) if r.field == SleyAnalysis::DWELL_TOLERANCE_MM.name => {
            r.renamed("--dwell-tolerance-mm").into()
        }
        e => e.into(),
    }
}

fn run_analyze(a: AnalyzeArgs) -> Result<()> {
    output::check_outputs([a.output.as_ref().map(|p| Out::plot("--output", p))])?;
    let (sley, loom) = read_sley(&a.loom)?;
    let speed = match a.speed_rpm {
        Some(v) => ShaftSpeed::from_rpm_field("--speed-rpm", v)?,
        None => loom.speed,
    };
    SleyAnalysis::DWELL_TOLERANCE_MM.check_as("--dwell-tolerance-mm", a.dwell_tolerance_mm)?;
    SleyAnalysis::POINTS.check_count_as("--points", a.points)?;
    let r = sley.analyze(speed, a.dwell_tolerance_mm).map_err(flag_named)?;
    let omega = speed.rad_per_s();
    if let Some(out) = &a.output {
        let name = if loom.name.is_empty() { util::file_name(&a.loom) } else { loom.name.clone() };
        return output::figure(&figure(&name, &sley, &r, &sley.curve(a.points, omega), omega), out, &a.plot);
    }
    if a.format.csv {
        // A cam sley has no rod: its table leaves that column out.
        let rows = sley.curve(a.points, omega);
        let rod = rows.first().is_some_and(|r| r.rod_force_n.is_some());
        let mut head =
            vec!["angle_deg", "reed_mm", "velocity_m_s", "acceleration_m_s2", "jerk_m_s3", "inertia_force_n"];
        if rod {
            head.push("rod_force_n");
        }
        head.push("crank_torque_n_m");
        let mut t = Table::new(head);
        for row in rows {
            let mut v = vec![
                row.angle_deg,
                row.reed_mm,
                row.velocity_m_s,
                row.acceleration_m_s2,
                row.jerk_m_s3,
                row.inertia_force_n,
            ];
            v.extend(row.rod_force_n);
            v.push(row.crank_torque_n_m);
            t.push(v)?;
        }
        return output::csv(&t);
    }
    if a.format.json {
        return output::json(&r);
    }
    outln!(
        "sley at {} rpm: reed stroke {:.3} mm, back dwell {:.3}° within {} mm ({:.3}° to {:.3}°)",
        r.speed_rpm,
        r.reed_stroke_mm,
        r.back_dwell_deg,
        r.dwell_tolerance_mm,
        r.dwell_start_deg,
        r.dwell_end_deg
    )?;
    outln!(
        "front dead centre at {:.3}°, back dead centre at {:.3}°; least transmission angle {:.3}°",
        r.front_dead_centre_deg,
        r.back_dead_centre_deg,
        r.min_transmission_angle_deg
    )?;
    outln!(
        "reed: peak velocity {:.4} m/s, peak acceleration {:.4} m/s² at {:.3}°, peak jerk {:.4e} m/s³",
        r.peak_reed_velocity_m_s,
        r.peak_reed_acceleration_m_s2,
        r.peak_reed_acceleration_deg,
        r.peak_reed_jerk_m_s3
    )?;
    outln!(
        "inertia force along the reed's path (J = {:.4} kg·m²): max {} N at {:.3}°, min {} N at {:.3}°",
        r.inertia_kg_m2,
        loomkin_units::fixed(r.max_inertia_force_n, 3),
        r.max_inertia_force_deg,
        loomkin_units::fixed(r.min_inertia_force_n, 3),
        r.min_inertia_force_deg
    )?;
    match (r.peak_rod_force_n, r.peak_rocking_shaft_force_n, r.max_pressure_angle_deg, r.prime_radius_mm) {
        (Some(rod), Some(shaft), _, _) => outln!(
            "peak crank torque {:.3} N·m at {:.3}°; peak rod force {:.3} N, peak rocking-shaft force {:.3} N",
            r.peak_crank_torque_n_m,
            r.peak_crank_torque_deg,
            rod,
            shaft
        ),
        (_, _, Some(pressure), Some(prime)) => outln!(
            "peak cam-shaft torque {:.3} N·m at {:.3}°; cams: largest pressure angle {:.3}°, prime circle radius {:.3} mm",
            r.peak_crank_torque_n_m,
            r.peak_crank_torque_deg,
            pressure,
            prime
        ),
        _ => Ok(()),
    }?;
    match (r.max_contact_force_n, r.max_contact_force_deg, r.min_contact_force_n, r.min_contact_force_deg) {
        (Some(most), Some(most_at), Some(least), Some(least_at)) => outln!(
            "cam contact force: max {:.3} N at {:.3}°, min {:.3} N at {:.3}° ({}); peak rocking-shaft force {:.3} N",
            most,
            most_at,
            least,
            least_at,
            r.contact_force_sign.unwrap_or_default(),
            r.peak_rocking_shaft_force_n.unwrap_or_default()
        ),
        _ => Ok(()),
    }
}

/// Library errors named by the synthesis's flags.
fn synth_flag_named(e: SleyError) -> anyhow::Error {
    match e {
        SleyError::Range(r) => {
            let flag = format!("--{}", r.field.replace('_', "-"));
            r.renamed(flag).into()
        }
        SleyError::Infeasible { fields, reason } => {
            let flags: Vec<String> = fields.split(", ").map(|f| format!("--{}", f.replace('_', "-"))).collect();
            anyhow!("{}: {reason}", flags.join(", "))
        }
        e => e.into(),
    }
}

fn run_synthesize(a: SynthesizeArgs) -> Result<()> {
    let target = SleyTarget {
        stroke_mm: a.stroke_mm,
        back_dwell_deg: a.back_dwell_deg,
        dwell_tolerance_mm: a.dwell_tolerance_mm,
        reed_height_mm: a.reed_height_mm,
        sword_mm: a.sword_mm,
    };
    let r = target.synthesize().map_err(synth_flag_named)?;
    if a.json {
        return output::json(&r);
    }
    outln!(
        "sley for a stroke of {} mm and a back dwell of {}° within {} mm (reed height {} mm): stroke {:.6} mm, \
         back dwell {:.6}°",
        a.stroke_mm,
        a.back_dwell_deg,
        r.dwell_tolerance_mm,
        r.reed_height_mm,
        r.reed_stroke_mm,
        r.back_dwell_deg
    )?;
    outln!(
        "least transmission angle {:.3}° (the largest any crank-rocker of the search gives); back dead centre at \
         {:.3}°; rod {:.3} crank radii ({} linkages evaluated)",
        r.min_transmission_angle_deg,
        r.back_dead_centre_deg,
        r.rod_mm / r.crank_mm,
        r.evaluations
    )?;
    outln!()?;
    outln!("[sley]")?;
    outln!("crank_mm = {:.6}", r.crank_mm)?;
    outln!("rod_mm = {:.6}", r.rod_mm)?;
    outln!("sword_mm = {:.6}", r.sword_mm)?;
    outln!("pivot_x_mm = {:.6}", r.pivot_x_mm)?;
    outln!("pivot_y_mm = {:.6}", r.pivot_y_mm)?;
    outln!("reed_height_mm = {}", r.reed_height_mm)?;
    outln!("assembly = \"{}\"", if r.assembly == Assembly::Left { "left" } else { "right" })?;
    outln!("# mass_kg = …      the sley's moving mass (the synthesis is kinematic: add it)")?;
    outln!("# gyration_mm = …  its radius of gyration about the rocking shaft")
}

/// Four panels over the turn: the reed's displacement (the back dwell shaded), velocity,
/// acceleration, and the crank torque; peaks noted.
fn figure(name: &str, sley: &Sley, r: &SleyAnalysis, rows: &[SleyRow], omega: f64) -> Figure {
    let pts = |f: &dyn Fn(&SleyRow) -> f64| rows.iter().map(|q| (q.angle_deg, f(q))).collect::<Vec<_>>();
    let label = format!("dwell {}°", sig4(r.back_dwell_deg));
    let dwell =
        r.dwell_bands_deg().into_iter().enumerate().map(|(i, (from, to))| {
            XBand::new(from, to, if i == 0 { label.clone() } else { String::new() }, XBand::DWELL)
        });
    let acc_at = r.peak_reed_acceleration_deg;
    let acc = sley.reed(acc_at.to_radians()).acceleration_m_s2(omega);
    let torque_at = r.peak_crank_torque_deg;
    let torque = sley.forces(torque_at.to_radians(), omega).crank_torque_n_m;
    let torque_name = if sley.cam().is_some() { "cam-shaft torque" } else { "crank torque" };
    let panels = vec![
        Panel::new("reed [mm]", vec![Series::line("displacement from the back dead centre", pts(&|q| q.reed_mm))])
            .with_x_bands(dwell),
        Panel::new("velocity [m/s]", vec![Series::line("reed velocity", pts(&|q| q.velocity_m_s))]),
        Panel::new("acceleration [m/s²]", vec![Series::line("reed acceleration", pts(&|q| q.acceleration_m_s2))])
            .with_notes([Note::new(acc_at, acc, format!("peak {} m/s² at {}°", sig4(acc), sig4(acc_at)))]),
        Panel::new(format!("{torque_name} [N·m]"), vec![Series::line(torque_name, pts(&|q| q.crank_torque_n_m))])
            .with_notes([Note::new(torque_at, torque, format!("peak {} N·m at {}°", sig4(torque), sig4(torque_at)))]),
    ];
    let title = format!(
        "{name}: sley at {} rpm, stroke {} mm, back dwell {}°",
        sig4(r.speed_rpm),
        sig4(r.reed_stroke_mm),
        sig4(r.back_dwell_deg)
    );
    Figure::new(title, "main-shaft angle [deg]", panels)
}
