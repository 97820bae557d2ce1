//! `loomkin cam …`: from a law to a part.

use crate::output::{Out, outln};
use crate::{output, util};
use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use loomkin_cams::profile::{CamDesign, CamPoint, CamProfile, Closure, Curve, DesignInputs, FollowerKind, Size};
use loomkin_cams::table::{CamTable, Format, Motion, Spacing};
use loomkin_plot::{Figure, Legend, Note, Panel, Rule, Series, sig4};
use loomkin_units::compact;
use std::path::PathBuf;

/// Subcommands of `loomkin cam`.
#[derive(Debug, Subcommand)]
pub enum CamCommand {
    /// A controller cam table (xyvaj, poly5, csv, twincat, st, xyva) of a cycle file or a single rise,
    /// with its exact re-interpolation error.
    Table(TableArgs),
    /// A disc cam profile (translating, oscillating or flat-faced follower; single, conjugate or
    /// groove) of a cycle file or a single rise and return: pitch curve, profile, pressure angle,
    /// curvature, undercut, sizing; JSON, CSV, DXF, plot.
    Profile(ProfileArgs),
}

/// `--follower`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FollowerArg {
    /// Translating roller follower (radial, or offset with --offset-mm).
    Translating,
    /// Oscillating (swinging) roller follower: --arm-mm and --pivot-mm; the cycle in deg.
    Oscillating,
    /// Flat-faced translating follower.
    Flat,
}

/// `cam profile`.
#[derive(Debug, Args)]
pub struct ProfileArgs {
    /// The cycle file (TOML); or give --law, --stroke-mm (or --stroke-deg) and --motion-deg for a
    /// rise, dwell, return and dwell over one turn.
    #[arg(required_unless_present = "law", conflicts_with = "law")]
    cycle: Option<PathBuf>,
    /// The follower.
    #[arg(long, value_enum)]
    follower: FollowerArg,
    /// Prime circle radius R in mm (the least radius of the pitch curve: base circle + roller).
    #[arg(long, value_name = "R", conflicts_with = "max_pressure_deg", allow_hyphen_values = true)]
    prime_radius_mm: Option<f64>,
    #[arg(long, value_name = "A", allow_hyphen_values = true, help = util::field_help("Size the cam: the least prime circle whose largest pressure angle is at most A deg (the default applies to a roller follower given no --prime-radius-mm)", &CamDesign::MAX_PRESSURE_DEG))]
    max_pressure_deg: Option<f64>,
    /// Roller radius in mm (0: a knife edge, the profile is the pitch curve).
    #[arg(long, value_name = "r", default_value_t = CamDesign::ROLLER_RADIUS_MM.default_value(), allow_hyphen_values = true)]
    roller_radius_mm: f64,
    /// Offset ε of a translating follower's line of motion in mm (positive: to the right of the
    /// cam centre, seen with the follower above it).
    #[arg(long, value_name = "e", default_value_t = CamDesign::OFFSET_MM.default_value(), allow_hyphen_values = true)]
    offset_mm: f64,
    /// Arm length L of an oscillating follower in mm (pivot to roller centre).
    #[arg(long, value_name = "L", allow_hyphen_values = true)]
    arm_mm: Option<f64>,
    /// Distance d from the cam centre to the pivot of an oscillating follower in mm.
    #[arg(long, value_name = "d", allow_hyphen_values = true)]
    pivot_mm: Option<f64>,
    /// The conjugate pair: a counter-cam and a second roller on the same follower.
    #[arg(long, conflicts_with = "groove")]
    conjugate: bool,
    /// A groove cam: the roller runs between two walls.
    #[arg(long)]
    groove: bool,
    #[command(flatten)]
    format: util::Format,
    /// Write the cam as a DXF drawing (mm; layers CAM_PITCH, CAM_PROFILE, COUNTER_*, GROOVE_OUTER,
    /// BASE_CIRCLE, CENTRE, BORE, PHASE_0).
    #[arg(long, value_name = "FILE")]
    dxf: Option<PathBuf>,
    /// Chord tolerance of the DXF polylines in mm.
    #[arg(long, value_name = "T", default_value_t = CamProfile::CHORD_TOL_MM.default_value(), allow_hyphen_values = true, requires = "dxf")]
    chord_tol_mm: f64,
    #[arg(long, value_name = "D", allow_hyphen_values = true, requires = "dxf", help = format!("{} (left out: {} × the base radius)", util::field_help("Bore diameter drawn in the DXF, mm (0: none)", &CamProfile::BORE_MM), loomkin_cams::profile::DEFAULT_BORE_PER_BASE_RADIUS))]
    bore_mm: Option<f64>,
    /// Main-shaft angle step of the printed points (deg).
    #[arg(long, value_name = "D", default_value_t = CamProfile::STEP_DEG.default_value(), allow_hyphen_values = true)]
    step_deg: f64,
    /// Plot the cam (profile, pitch curve, base circle), its pressure angle and curvature (.svg or .png).
    #[arg(short, long, value_name = "PLOT")]
    output: Option<PathBuf>,
    #[command(flatten)]
    rise: util::RiseArgs,
    #[command(flatten)]
    plot: crate::util::PlotOpts,
}

/// `cam table`.
#[derive(Debug, Args)]
pub struct TableArgs {
    /// The cycle file (TOML); or give --law, --stroke-mm (or --stroke-deg) and --motion-deg for a single rise.
    #[arg(required_unless_present = "law", conflicts_with = "law")]
    cycle: Option<PathBuf>,
    /// xyvaj (X,Y,V,A,J points), poly5 (fifth-degree segments), csv, twincat (motion-function point
    /// list), st (IEC 61131-3 ARRAY OF SMC_CAMXYVA), xyva (X,Y,V,A points).
    #[arg(long, value_enum, ignore_case = true)]
    format: Format,
    #[arg(long, value_name = "D", conflicts_with = "tolerance", allow_hyphen_values = true, help = util::field_help("Points on every joint of the law and every D degrees from each joint (a shorter last step before a joint)", &Spacing::STEP_DEG))]
    step_deg: Option<f64>,
    /// Points on every joint and as few in between as keep the re-interpolation error within T
    /// (slave unit: mm, or deg for a swinging follower).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// Output file (`-` for standard output).
    #[arg(short, long)]
    output: String,
    #[command(flatten)]
    rise: util::RiseArgs,
    /// Print the report (points, decimals, exact errors) as JSON.
    #[arg(long)]
    json: bool,
}

/// Runs a `cam` subcommand.
pub fn run(cmd: CamCommand) -> Result<()> {
    match cmd {
        CamCommand::Table(a) => table(a),
        CamCommand::Profile(a) => profile(a),
    }
}

fn motion(a: &TableArgs) -> Result<(Motion, String)> {
    if let Some(path) = &a.cycle {
        a.rise.none_with_file()?;
        let cycle = util::read_cycle(path)?;
        return Ok((Motion::from_cycle(&cycle), path.display().to_string()));
    }
    let (law, stroke, unit, b) = a.rise.rise()?;
    Ok((Motion::rise(&law.build()?, stroke, b, unit)?, format!("law {}", a.rise.name())))
}

fn table(a: TableArgs) -> Result<()> {
    output::check_outputs([Some(Out::file("--output", &a.output))])?;
    let format = a.format;
    let (motion, source) = motion(&a)?;
    let spacing = Spacing::of(a.step_deg, a.tolerance);
    let table = CamTable::new(motion, spacing)?;
    let out = table.export(format)?;
    output::text_to(&a.output, &out.text)?;
    let u = table.unit_name();
    let e = &out.error;
    if a.json {
        let report = table.report(source, format, &out);
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

fn profile_motion(a: &ProfileArgs) -> Result<(Motion, String)> {
    let (cycle, source) = a.rise.cycle(a.cycle.as_deref())?;
    Ok((Motion::from_cycle(&cycle), source))
}

fn profile_design(a: &ProfileArgs) -> Result<CamDesign> {
    let follower = match a.follower {
        FollowerArg::Translating => FollowerKind::Translating,
        FollowerArg::Oscillating => FollowerKind::Oscillating,
        FollowerArg::Flat => FollowerKind::Flat,
    };
    let closure = match (a.conjugate, a.groove) {
        (true, _) => Closure::Conjugate,
        (_, true) => Closure::Groove,
        _ => Closure::Single,
    };
    let inputs = DesignInputs {
        follower,
        closure,
        prime_radius_mm: a.prime_radius_mm,
        max_pressure_deg: a.max_pressure_deg,
        roller_radius_mm: a.roller_radius_mm,
        offset_mm: a.offset_mm,
        arm_mm: a.arm_mm,
        pivot_mm: a.pivot_mm,
    };
    Ok(inputs.design()?)
}

fn profile(a: ProfileArgs) -> Result<()> {
    output::check_outputs([
        a.dxf.as_ref().map(|p| Out::file("--dxf", p)),
        a.output.as_ref().map(|p| Out::plot("--output", p)),
    ])?;
    CamProfile::STEP_DEG.check(a.step_deg)?;
    let design = profile_design(&a)?;
    let (motion, source) = profile_motion(&a)?;
    let cam = CamProfile::new(&motion, &design)?;
    let undercut = cam.undercut().map(|e| e.to_string());
    // An undercut cam is reported in every output (undercut: true, a warning naming the angle and
    // the largest roller); a drawing of it is never written: with --dxf the report is printed
    // and the command then fails (exit 2) naming the roller.
    match (&a.dxf, &undercut) {
        (Some(_), Some(_)) => {}
        (Some(path), None) => {
            let text = cam.dxf(a.chord_tol_mm, cam.bore_mm_or(a.bore_mm))?;
            output::text_to(&path.display().to_string(), &text)?;
        }
        (None, Some(msg)) => output::warning(msg),
        (None, None) => {}
    }
    print_profile(&a, &cam, &design, undercut.is_some(), &source)?;
    if let (Some(_), Some(msg)) = (&a.dxf, &undercut) {
        bail!("{msg}: no DXF written");
    }
    Ok(())
}

/// Prints the cam's report (JSON, CSV or text) and writes its plot.
fn print_profile(a: &ProfileArgs, cam: &CamProfile, design: &CamDesign, undercut: bool, source: &str) -> Result<()> {
    let step = a.step_deg;
    let points = cam.sample(0, step);
    let counter = (cam.track_count() == 2).then(|| cam.sample(1, step));
    if let Some(path) = &a.output {
        output::figure(&profile_figure(cam, &points, counter.as_deref(), source), path, &a.plot)?;
    }
    let (pmax, pat, _) = cam.max_pressure_angle();
    let (rmin, rat) = cam.min_convex_radius_pitch();
    let r = design.roller_radius_mm;
    if a.format.json {
        return output::json(&cam.report(source, step));
    }
    if a.format.csv {
        let mut head = vec![
            "angle_deg",
            "x_mm",
            "y_mm",
            "pressure_angle_deg",
            "curvature_pitch_per_mm",
            "profile_x_mm",
            "profile_y_mm",
            "curvature_profile_per_mm",
        ];
        if counter.is_some() {
            head.extend([
                "counter_x_mm",
                "counter_y_mm",
                "counter_pressure_angle_deg",
                "counter_profile_x_mm",
                "counter_profile_y_mm",
            ]);
        }
        let mut t = loomkin_io::Table::new(head);
        for (i, p) in points.iter().enumerate() {
            let mut row = vec![
                p.angle_deg,
                p.pitch_mm[0],
                p.pitch_mm[1],
                p.pressure_angle_deg,
                p.curvature_pitch_per_mm,
                p.profile_mm[0],
                p.profile_mm[1],
                p.curvature_profile_per_mm,
            ];
            if let Some(c) = &counter {
                let q = c[i];
                row.extend([q.pitch_mm[0], q.pitch_mm[1], q.pressure_angle_deg, q.profile_mm[0], q.profile_mm[1]]);
            }
            t.push(row).map_err(util::failure)?;
        }
        return output::csv(&t);
    }
    outln!("cam profile of {source}: {}, {}", design.follower.description(), design.closure.description())?;
    let sized = match design.size {
        Size::MaxPressureDeg(p) => format!(" (the least for a pressure angle of {}°)", compact(p)),
        Size::PrimeRadiusMm(_) => String::new(),
    };
    outln!(
        "  prime radius          {} mm{sized}; base radius {} mm",
        compact(cam.prime_radius_mm()),
        compact(cam.base_radius_mm())
    )?;
    outln!("  pressure angle        max {}° at {}°", compact(pmax), compact(pat))?;
    outln!("  pitch curve           least convex radius of curvature {} mm at {}°", compact(rmin), compact(rat))?;
    for c in cam.cam_reports().unwrap_or_default() {
        outln!(
            "  {:<21} pressure angle max {}° at {}°; least convex pitch radius {} mm at {}°",
            c.description(),
            compact(c.max_pressure_angle_deg),
            compact(c.max_pressure_angle_at_deg),
            compact(c.min_convex_radius_pitch_mm),
            compact(c.min_convex_radius_pitch_at_deg)
        )?;
    }
    if let Some(rmax) = cam.roller_max_mm() {
        outln!("  roller                {} mm; largest without undercut {} mm", compact(r), compact(rmax))?;
    }
    if let Some(f) = cam.flat_extremes_report() {
        outln!(
            "  profile               least radius of curvature {} mm at {}°; face from {} to {} mm",
            compact(f.min_radius_profile_mm),
            compact(f.min_radius_profile_at_deg),
            compact(f.face_min_mm),
            compact(f.face_max_mm)
        )?;
    }
    outln!("  undercut              {}", if undercut { "yes" } else { "no" })?;
    Ok(())
}

fn profile_figure(cam: &CamProfile, points: &[CamPoint], counter: Option<&[CamPoint]>, source: &str) -> Figure {
    let closed = |c: Curve| -> Vec<(f64, f64)> {
        let v = cam.polyline(c, 0.01);
        let mut out: Vec<(f64, f64)> = v.iter().map(|p| (p[0], p[1])).collect();
        if let Some(f) = out.first().copied() {
            out.push(f);
        }
        out
    };
    let rb = cam.base_radius_mm();
    let circle: Vec<(f64, f64)> =
        (0..=360).map(|i| (i as f64).to_radians()).map(|t| (rb * t.cos(), rb * t.sin())).collect();
    let mut drawing = vec![Series::line("profile", closed(Curve::Wall(0))).with_color([0, 0, 0])];
    if let Some(w) = cam.walls().iter().position(|w| w.name == "groove_outer") {
        drawing.push(Series::line("groove outer wall", closed(Curve::Wall(w))).with_color([0, 0, 0]));
    }
    drawing.push(Series::line("pitch curve", closed(Curve::Pitch(0))).with_color([0, 114, 178]).with_dashes());
    if counter.is_some() {
        drawing.push(Series::line("counter-cam profile", closed(Curve::Wall(1))).with_color([213, 94, 0]));
        drawing.push(
            Series::line("counter-cam pitch curve", closed(Curve::Pitch(1))).with_color([213, 94, 0]).with_dashes(),
        );
    }
    drawing.push(Series::line("base circle", circle).with_color([120, 120, 120]).with_dashes());
    let ph = cam.phase_point();
    drawing.push(
        Series::line("0° (follower at main-shaft 0°)", vec![(0.0, 0.0), (ph[0], ph[1])]).with_color([0, 158, 115]),
    );
    let mut d = Panel::new("y [mm]", drawing).with_legend(Legend::Auto);
    d.x_label = Some("x [mm]".into());
    d.equal_aspect = true;
    let series = |v: &[CamPoint], f: fn(&CamPoint) -> f64| -> Vec<(f64, f64)> {
        v.iter().map(|p| (p.angle_deg, f(p))).collect()
    };
    let mut pa = vec![Series::line("cam", series(points, |p| p.pressure_angle_deg)).with_color([0, 114, 178])];
    let mut cu = vec![
        Series::line("pitch curve", series(points, |p| p.curvature_pitch_per_mm))
            .with_color([0, 114, 178])
            .with_dashes(),
        Series::line("profile", series(points, |p| p.curvature_profile_per_mm)).with_color([0, 0, 0]),
    ];
    if let Some(c) = counter {
        pa.push(Series::line("counter-cam", series(c, |p| p.pressure_angle_deg)).with_color([213, 94, 0]));
        cu.push(
            Series::line("counter-cam pitch curve", series(c, |p| p.curvature_pitch_per_mm))
                .with_color([213, 94, 0])
                .with_dashes(),
        );
        cu.push(
            Series::line("counter-cam profile", series(c, |p| p.curvature_profile_per_mm)).with_color([213, 94, 0]),
        );
    }
    let (pmax, pat, psigned) = cam.max_pressure_angle();
    // Pressure angle: the design's limit both ways (when the cam was sized by it), the maximum noted.
    let mut pa_panel = Panel::new("pressure angle [deg]", pa).with_notes([Note::new(
        pat,
        psigned,
        format!("max {}° at {}°", sig4(pmax), sig4(pat)),
    )]);
    if let Size::MaxPressureDeg(limit) = cam.design().size {
        pa_panel = pa_panel
            .with_rule(Rule::y(limit, format!("pressure-angle limit ±{}°", sig4(limit))))
            .with_rule(Rule::y(-limit, ""));
    }
    // Curvature: the least convex radius of the pitch curve (and of the profile, a roller's radius
    // less) noted; a roller undercuts where the pitch curvature passes 1/r.
    let (rmin, rat) = cam.min_convex_radius_pitch();
    let r = cam.design().roller_radius_mm;
    let mut notes = Vec::new();
    // The undercut line 1/r is drawn when it is near the data (within twice the largest
    // curvature); farther out the margin is given in the note instead of squashing the curves.
    let kmax = cu.iter().flat_map(|s| s.points.iter().map(|p| p.1.abs())).filter(|v| v.is_finite()).fold(0.0, f64::max);
    let line = r > 0.0 && 1.0 / r <= 2.0 * kmax;
    if rmin.is_finite() && rmin > 0.0 {
        let margin = if r > 0.0 && !line && cam.undercut_at_deg().is_none() {
            format!(" (roller {} mm: no undercut)", sig4(r))
        } else {
            String::new()
        };
        notes.push(Note::new(rat, 1.0 / rmin, format!("pitch ρ min {} mm at {}°{margin}", sig4(rmin), sig4(rat))));
        if r > 0.0 && rmin > r {
            notes.push(Note::new(
                rat,
                1.0 / (rmin - r),
                format!("profile ρ min {} mm at {}°", sig4(rmin - r), sig4(rat)),
            ));
        }
    }
    if let Some(f) = cam.flat_extremes_report() {
        let (rho, at) = (f.min_radius_profile_mm, f.min_radius_profile_at_deg);
        if rho.is_finite() && rho > 0.0 {
            notes.push(Note::new(at, 1.0 / rho, format!("profile ρ min {} mm at {}°", sig4(rho), sig4(at))));
        }
    }
    let mut cu_panel = Panel::new("curvature (convex > 0) [1/mm]", cu).with_notes(notes);
    if line {
        cu_panel = cu_panel.with_rule(Rule::y(1.0 / r, format!("1/r, roller {} mm: undercut above", sig4(r))));
    }
    if let Some(at) = cam.undercut_at_deg() {
        cu_panel = cu_panel.with_rule(Rule::x(at, format!("undercut at {}°", sig4(at))).with_color([120, 0, 160]));
    }
    let name = std::path::Path::new(source).file_name().map_or(source.into(), |n| n.to_string_lossy());
    let title = format!(
        "Cam of {name}: prime radius {:.2} mm, max pressure angle {pmax:.2}° at {pat:.1}°",
        cam.prime_radius_mm()
    );
    let mut fig = Figure::new(title, "main-shaft angle [deg]", vec![d, pa_panel, cu_panel]);
    fig.size = Some((1000, 1500));
    fig
}
