//! The cam view: from a cycle file, a catalogue law or a shedding law to a disc cam — pitch curve,
//! working profile(s), pressure angle and curvature over the cycle with their limits — and the DXF
//! drawing and controller cam tables to download, written by the cams library's own exporters
//! (`CamProfile::dxf`, `CamTable::export`: the same bytes as `loomkin cam profile --dxf` and
//! `loomkin cam table`).

use crate::catalogue::LawChoice;
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::{get, post};
use loomkin_cams::profile::{
    BORE_RANGE, CHORD_TOL_RANGE, CamDesign, CamPoint, CamProfile, Closure, Curve, DEFAULT_CHORD_TOL_MM,
    DEFAULT_MAX_PRESSURE_DEG, DEFAULT_SAMPLE_STEP_DEG, Follower, LENGTH_RANGE, OFFSET_RANGE, PRESSURE_RANGE,
    ProfileExtremes, ProfileReport, ROLLER_RANGE, SAMPLE_STEP_RANGE, Size,
};
use loomkin_cams::table::{CamTable, DEFAULT_STEP_DEG, Format, Motion, STEP_RANGE, Spacing, TOLERANCE_RANGE};
use loomkin_laws::{Cycle, CycleSpec, StrokeUnit};
use loomkin_units::compact;
use serde::{Deserialize, Serialize};

/// The cycle files the view offers (`examples/`).
pub const CAM_EXAMPLES: &[(&str, &str)] = &[
    ("heald-frame-cycle.toml", include_str!("../../../examples/heald-frame-cycle.toml")),
    ("sley-cycle.toml", include_str!("../../../examples/sley-cycle.toml")),
    ("needle-rack-cycle.toml", include_str!("../../../examples/needle-rack-cycle.toml")),
];

/// Most points of a cam table written by the workbench.
pub const MAX_CAM_TABLE_POINTS: usize = 100_000;

/// Most sampled angles of a profile answer (a finer step than the cycle's span over this is
/// refused by the workbench, not by the library: the answer would be megabytes of curves).
pub const MAX_CAM_POINTS: usize = 20_000;

/// The finest re-interpolation tolerance of a table the workbench computes (slave unit): the
/// answer stays quick. The library (and `loomkin cam table --tolerance`) goes to
/// [`TOLERANCE_RANGE`]'s lower end.
pub const MIN_WEB_TOLERANCE: f64 = 1e-6;

/// The chord tolerance of the drawing sent to the page (mm): finer than a pixel at any zoom the
/// page offers.
const SCREEN_TOL_MM: f64 = 0.02;

pub(crate) fn routes() -> Router {
    Router::new()
        .route("/cam/examples", get(|| async { ApiJson(examples()) }))
        .route("/cam/profile", post(post_profile))
        .route("/cam/dxf", post(post_dxf))
        .route("/cam/table", post(post_table))
}

/// One example cycle file.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CamExample {
    /// File name in `examples/`.
    pub name: &'static str,
    /// Its text.
    pub cycle_toml: &'static str,
}

/// `GET /api/cam/examples`: the example cycles and the shedding presets.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CamExamples {
    /// Example cycle files.
    pub cycles: Vec<CamExample>,
    /// Names of the shedding-law presets (`loomkin shed list`).
    pub shed_presets: Vec<&'static str>,
    /// The table formats (`loomkin cam table --format`).
    pub formats: Vec<&'static str>,
}

/// The view's starting point.
pub fn examples() -> CamExamples {
    CamExamples {
        cycles: CAM_EXAMPLES.iter().map(|&(name, cycle_toml)| CamExample { name, cycle_toml }).collect(),
        shed_presets: loomkin_shed::PRESETS.iter().map(|p| p.name).collect(),
        formats: Format::ALL.iter().map(|f| f.name()).collect(),
    }
}

/// A catalogue law as rise, dwell, return, dwell over one turn (`cam profile --law`).
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CamLaw {
    /// The law of the rise and of the return.
    pub law: LawChoice,
    /// Stroke (mm) of a translating or flat-faced follower.
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(StrokeUnit::Mm.stroke_range()))]
    pub stroke_mm: Option<f64>,
    /// Swing (deg) of an oscillating follower.
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(StrokeUnit::Deg.stroke_range()))]
    pub stroke_deg: Option<f64>,
    /// Master angle of the rise and of the return (deg, at most 180).
    #[schemars(transform = loomkin_units::schema::bounds(CycleSpec::RISE_RETURN_MOTION_DEG))]
    pub motion_deg: f64,
}

/// A shedding law's full frame cycle (`shed law NAME --emit-cycle`).
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShedSource {
    /// Preset name (`loomkin shed list`).
    pub preset: String,
    /// The frame's stroke (mm).
    #[schemars(transform = loomkin_units::schema::bounds(loomkin_shed::FRAME_STROKE_MM_RANGE))]
    pub stroke_mm: f64,
    /// Another motion angle than the preset's (deg).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(loomkin_shed::MOTION_DEG))]
    pub motion_deg: Option<f64>,
}

/// Where the motion comes from: exactly one of the three, or none for the heald-frame example.
#[derive(Debug, Clone, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CamSource {
    /// A cycle file's text.
    #[serde(default)]
    pub cycle_toml: Option<String>,
    /// The cycle file's name, for the report.
    #[serde(default)]
    pub name: Option<String>,
    /// A catalogue law.
    #[serde(default)]
    pub law: Option<CamLaw>,
    /// A shedding law.
    #[serde(default)]
    pub shed: Option<ShedSource>,
}

impl CamSource {
    /// The motion (as `cam profile` and `cam table` read it) and a name for it.
    pub fn motion(&self) -> Result<(Motion, String), ApiError> {
        let given = [self.cycle_toml.is_some(), self.law.is_some(), self.shed.is_some()];
        if given.iter().filter(|&&g| g).count() > 1 {
            return Err(ApiError::BadJson {
                field: "source".into(),
                message: "source: give one of cycle_toml, law and shed".into(),
            });
        }
        let (cycle, name) = if let Some(text) = &self.cycle_toml {
            (
                Cycle::from_toml(text).map_err(|e| ApiError::invalid("source.cycle_toml", e))?,
                self.name.clone().unwrap_or_else(|| "cycle file".into()),
            )
        } else if let Some(l) = &self.law {
            let spec = l.law.spec().map_err(|e| ApiError::invalid("source.law.law", e))?;
            let (stroke, unit, field) = match (l.stroke_mm, l.stroke_deg) {
                (Some(h), None) => (h, StrokeUnit::Mm, "source.law.stroke_mm"),
                (None, Some(h)) => (h, StrokeUnit::Deg, "source.law.stroke_deg"),
                _ => {
                    return Err(ApiError::BadJson {
                        field: "source.law.stroke_mm".into(),
                        message: "source.law: give stroke_mm (translating, flat) or stroke_deg (oscillating)".into(),
                    });
                }
            };
            unit.stroke_range().check(field, stroke)?;
            let spec = CycleSpec::rise_return(&spec, unit, stroke, l.motion_deg)
                .map_err(|e| ApiError::invalid("source.law.motion_deg", e))?;
            let cycle = Cycle::new(&spec).map_err(|e| ApiError::invalid("source.law", e))?;
            (cycle, format!("law {} (rise, dwell, return, dwell)", l.law.name))
        } else if let Some(s) = &self.shed {
            let mut law = loomkin_shed::preset(&s.preset).map_err(|e| ApiError::invalid("source.shed.preset", e))?;
            if let Some(m) = s.motion_deg {
                law = law.with_motion_deg(m).map_err(|e| ApiError::from_library(&e, "source.shed.motion_deg"))?;
            }
            let spec = loomkin_shed::frame_cycle(&law, s.stroke_mm, None)
                .map_err(|e| ApiError::from_library(&e, "stroke_mm").within("source.shed"))?;
            let cycle = Cycle::new(&spec).map_err(|e| ApiError::invalid("source.shed", e))?;
            (cycle, format!("shedding law {} (rise, dwell, return, dwell over 720°)", s.preset))
        } else {
            let cycle = Cycle::from_toml(CAM_EXAMPLES[0].1).map_err(|e| ApiError::Internal(e.to_string()))?;
            (cycle, CAM_EXAMPLES[0].0.to_string())
        };
        Ok((Motion::from_cycle(&cycle), name))
    }
}

/// The follower (`--follower`).
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum FollowerKind {
    /// Translating roller follower.
    #[default]
    Translating,
    /// Oscillating roller follower.
    Oscillating,
    /// Flat-faced translating follower.
    Flat,
}

/// How the follower is held (`--conjugate`, `--groove`).
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ClosureKind {
    /// One cam, force closure.
    #[default]
    Single,
    /// The conjugate pair.
    Conjugate,
    /// A groove cam.
    Groove,
}

/// The cam: the flags of `loomkin cam profile`.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CamDesignRequest {
    /// The follower.
    #[serde(default)]
    pub follower: FollowerKind,
    /// Single, conjugate or groove.
    #[serde(default)]
    pub closure: ClosureKind,
    /// Prime circle radius (mm); with neither this nor `max_pressure_deg`, sized for
    /// [`DEFAULT_MAX_PRESSURE_DEG`].
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(LENGTH_RANGE))]
    pub prime_radius_mm: Option<f64>,
    /// Size for this largest pressure angle (deg).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PRESSURE_RANGE))]
    pub max_pressure_deg: Option<f64>,
    /// Roller radius (mm; 0 a knife edge).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(ROLLER_RANGE))]
    pub roller_radius_mm: f64,
    /// Offset of a translating follower (mm).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(OFFSET_RANGE))]
    pub offset_mm: f64,
    /// Arm length of an oscillating follower (mm).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(LENGTH_RANGE))]
    pub arm_mm: Option<f64>,
    /// Pivot distance of an oscillating follower (mm).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(LENGTH_RANGE))]
    pub pivot_mm: Option<f64>,
}

impl CamDesignRequest {
    /// The library's design, refusing the combinations the CLI refuses, naming the field.
    pub fn design(&self) -> Result<CamDesign, ApiError> {
        let bad = |field: &str, message: &str| ApiError::BadJson {
            field: format!("design.{field}"),
            message: format!("design.{field}: {message}"),
        };
        let follower = match self.follower {
            FollowerKind::Translating => Follower::Translating { offset_mm: self.offset_mm },
            FollowerKind::Oscillating => match (self.arm_mm, self.pivot_mm) {
                (Some(arm_mm), Some(pivot_mm)) => Follower::Oscillating { arm_mm, pivot_mm },
                (None, _) => return Err(bad("arm_mm", "an oscillating follower needs arm_mm and pivot_mm")),
                (_, None) => return Err(bad("pivot_mm", "an oscillating follower needs arm_mm and pivot_mm")),
            },
            FollowerKind::Flat => Follower::Flat,
        };
        if self.follower == FollowerKind::Flat && self.roller_radius_mm != 0.0 {
            return Err(bad("roller_radius_mm", "a flat-faced follower has no roller"));
        }
        let size = match (self.prime_radius_mm, self.max_pressure_deg) {
            (Some(_), Some(_)) => return Err(bad("max_pressure_deg", "give prime_radius_mm or max_pressure_deg")),
            (Some(r), None) => Size::PrimeRadiusMm(r),
            (None, Some(p)) => Size::MaxPressureDeg(p),
            (None, None) if self.follower == FollowerKind::Flat => {
                return Err(bad("prime_radius_mm", "a flat-faced follower needs prime_radius_mm"));
            }
            (None, None) => Size::DEFAULT,
        };
        let closure = match self.closure {
            ClosureKind::Single => Closure::Single,
            ClosureKind::Conjugate => Closure::Conjugate,
            ClosureKind::Groove => Closure::Groove,
        };
        Ok(CamDesign { follower, closure, roller_radius_mm: self.roller_radius_mm, size })
    }
}

/// `POST /api/cam/profile` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CamProfileRequest {
    /// The motion.
    #[serde(default)]
    pub source: CamSource,
    /// The cam.
    pub design: CamDesignRequest,
    /// Main-shaft angle step of the sampled curves (deg).
    #[serde(default = "default_sample_step")]
    #[schemars(transform = loomkin_units::schema::bounds(SAMPLE_STEP_RANGE))]
    pub step_deg: f64,
}

fn default_sample_step() -> f64 {
    DEFAULT_SAMPLE_STEP_DEG
}

/// The figures of the cam, with the keys of `loomkin cam profile --json`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CamReport {
    /// What the motion is.
    pub source: String,
    /// The follower, in words.
    pub follower: String,
    /// `single`, `conjugate` or `groove`.
    pub closure: &'static str,
    /// Slave unit of the motion (`mm` or `deg`).
    pub unit: &'static str,
    /// Stroke (mm) or swing (deg).
    pub stroke: f64,
    /// Prime circle radius (mm).
    pub prime_radius_mm: f64,
    /// Base circle radius (mm).
    pub base_radius_mm: f64,
    /// Roller radius (mm; 0 for a knife edge or a flat face).
    pub roller_radius_mm: f64,
    /// The pressure angle asked for when sizing (deg), else absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sized_for_pressure_deg: Option<f64>,
    /// The extremes and the undercut, as the library's report states them (a non-finite least
    /// convex radius as 0).
    #[serde(flatten)]
    pub extremes: ProfileExtremes,
    /// Where the undercut begins (deg).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub undercut_at_deg: Option<f64>,
    /// The undercut, in words naming the field (as `cam profile` warns).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub undercut_message: Option<String>,
    /// The largest roller without undercut (mm; roller followers).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roller_max_mm: Option<f64>,
    /// Largest pressure angle of the counter-cam (deg; conjugate pair).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counter_max_pressure_angle_deg: Option<f64>,
    /// Least radius of curvature of a flat-faced follower's profile (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_radius_profile_mm: Option<f64>,
    /// The least prime radius without a cusp (mm; flat face).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub least_prime_radius_no_cusp_mm: Option<f64>,
    /// The face must reach from here (mm; flat face) …
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face_min_mm: Option<f64>,
    /// … to here (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face_max_mm: Option<f64>,
}

/// One track's curves over the cycle.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct CamCurves {
    /// Main-shaft angle (deg).
    pub angle_deg: Vec<f64>,
    /// Pitch point, cam frame (mm).
    pub x_mm: Vec<f64>,
    /// Pitch point, cam frame (mm).
    pub y_mm: Vec<f64>,
    /// The follower's motion (mm or deg).
    pub lift: Vec<f64>,
    /// Signed pressure angle (deg).
    pub pressure_angle_deg: Vec<f64>,
    /// Curvature of the pitch curve, convex > 0 (1/mm).
    pub curvature_pitch_per_mm: Vec<f64>,
    /// Curvature of the working profile, convex > 0 (1/mm).
    pub curvature_profile_per_mm: Vec<f64>,
}

/// The cam drawn (mm, cam frame), each curve within 0.02 mm.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct CamDrawing {
    /// Pitch curve of the cam.
    pub pitch: Vec<[f64; 2]>,
    /// Working profile of the cam.
    pub profile: Vec<[f64; 2]>,
    /// Pitch curve of the counter-cam (conjugate pair), else empty.
    pub counter_pitch: Vec<[f64; 2]>,
    /// Profile of the counter-cam (conjugate), or the groove's outer wall (groove), else empty.
    pub counter_profile: Vec<[f64; 2]>,
    /// Base circle radius (mm).
    pub base_radius_mm: f64,
    /// The pitch point at main-shaft 0° (the 0° phase mark).
    pub phase_point: [f64; 2],
}

/// `POST /api/cam/profile` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CamProfileResponse {
    /// The figures.
    pub report: CamReport,
    /// Limits for the panels: the largest pressure angle allowed (deg) …
    pub pressure_limit_deg: f64,
    /// … and the pitch curve's largest convex curvature before the roller undercuts, 1/r (1/mm;
    /// absent for a knife edge or a flat face).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curvature_limit_per_mm: Option<f64>,
    /// The motion's joints (deg).
    pub joints_deg: Vec<f64>,
    /// The cam's curves.
    pub cam: CamCurves,
    /// The counter-cam's curves (conjugate pair).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counter: Option<CamCurves>,
    /// The drawing.
    pub drawing: CamDrawing,
    /// The library's report of the cam, keyed as `loomkin cam profile --json` (and the Python
    /// package's `loomkin.cams.profile`), without its points: `cam` and `counter` carry the curves.
    pub profile_report: ProfileReport,
}

fn closure_name(c: Closure) -> &'static str {
    match c {
        Closure::Single => "single",
        Closure::Conjugate => "conjugate",
        Closure::Groove => "groove",
    }
}

/// The profile, refusing a sampling step that would answer more than [`MAX_CAM_POINTS`] angles.
fn build(source: &CamSource, design: &CamDesignRequest) -> Result<(CamProfile, CamDesign, Motion, String), ApiError> {
    let d = design.design()?;
    let (motion, name) = source.motion()?;
    let cam = CamProfile::new(&motion, &d).map_err(|e| ApiError::from_library(&e, "design").within("design"))?;
    Ok((cam, d, motion, name))
}

/// The undercut, refused at its design field (`design.roller_radius_mm`, `design.prime_radius_mm`)
/// taken from the library's error, in the library's words (as `loomkin cam profile` warns).
fn undercut_error(cam: &CamProfile) -> Option<ApiError> {
    cam.undercut().map(|u| ApiError::from_library(&u, "roller_radius_mm").within("design"))
}

fn curves(cam: &CamProfile, pts: &[CamPoint], unit: StrokeUnit) -> CamCurves {
    // The lift is in mm, or in rad for a swinging follower (shown in deg).
    let k = if unit == StrokeUnit::Deg { 180.0 / std::f64::consts::PI } else { 1.0 };
    let mut c = CamCurves::default();
    for p in pts {
        c.angle_deg.push(finite(p.angle_deg));
        c.x_mm.push(finite(p.pitch_mm[0]));
        c.y_mm.push(finite(p.pitch_mm[1]));
        c.lift.push(finite(k * cam.lift_at(p.angle_deg)));
        c.pressure_angle_deg.push(finite(p.pressure_angle_deg));
        c.curvature_pitch_per_mm.push(finite(p.curvature_pitch_per_mm));
        c.curvature_profile_per_mm.push(finite(p.curvature_profile_per_mm));
    }
    c
}

/// Computes the cam of one request.
pub fn cam_profile(req: &CamProfileRequest) -> Result<CamProfileResponse, ApiError> {
    let step = SAMPLE_STEP_RANGE.check("step_deg", req.step_deg)?;
    let (cam, d, motion, source) = build(&req.source, &req.design)?;
    let span = motion.end_deg() - motion.start_deg();
    if span / step > MAX_CAM_POINTS as f64 {
        return Err(ApiError::invalid(
            "step_deg",
            format!(
                "step_deg: {} deg over the cycle's {} deg gives more than {MAX_CAM_POINTS} points; use a larger step",
                compact(step),
                compact(span)
            ),
        ));
    }
    let mut pts = cam.sample(0, step);
    // The curves close: the last angle repeats the first (one turn of the cam).
    let close = |v: &mut Vec<CamPoint>| {
        if let Some(mut f) = v.first().copied() {
            f.angle_deg = motion.end_deg();
            v.push(f);
        }
    };
    close(&mut pts);
    let counter = (cam.track_count() == 2).then(|| {
        let mut c = cam.sample(1, step);
        close(&mut c);
        c
    });
    let (sized, limit) = match d.size {
        Size::MaxPressureDeg(p) => (Some(p), p),
        Size::PrimeRadiusMm(_) => (None, DEFAULT_MAX_PRESSURE_DEG),
    };
    let mut profile_report = cam.report(source, step);
    profile_report.points.clear();
    profile_report.counter_points = None;
    let pr = &profile_report;
    let report = CamReport {
        source: pr.source.clone(),
        follower: pr.follower.clone(),
        closure: closure_name(d.closure),
        unit: if motion.unit() == StrokeUnit::Deg { "deg" } else { "mm" },
        stroke: cam.stroke(),
        prime_radius_mm: pr.prime_radius_mm,
        base_radius_mm: pr.base_radius_mm,
        roller_radius_mm: pr.roller_radius_mm,
        sized_for_pressure_deg: sized,
        extremes: ProfileExtremes {
            min_convex_radius_pitch_mm: finite(pr.extremes.min_convex_radius_pitch_mm),
            ..pr.extremes
        },
        undercut_at_deg: pr.undercut_at_deg,
        undercut_message: undercut_error(&cam).map(|e| e.to_string()),
        roller_max_mm: pr.roller_max_mm.map(finite),
        counter_max_pressure_angle_deg: pr.counter_max_pressure_angle_deg,
        min_radius_profile_mm: pr.min_radius_profile_mm,
        least_prime_radius_no_cusp_mm: pr.least_prime_radius_no_cusp_mm,
        face_min_mm: pr.face_min_mm,
        face_max_mm: pr.face_max_mm,
    };
    let wall = |name: &str| cam.walls().iter().position(|w| w.name == name);
    let counter_profile = match d.closure {
        Closure::Conjugate => cam.polyline(Curve::Wall(1), SCREEN_TOL_MM),
        Closure::Groove => {
            wall("groove_outer").map(|w| cam.polyline(Curve::Wall(w), SCREEN_TOL_MM)).unwrap_or_default()
        }
        Closure::Single => Vec::new(),
    };
    let drawing = CamDrawing {
        pitch: cam.polyline(Curve::Pitch(0), SCREEN_TOL_MM),
        profile: cam.polyline(Curve::Wall(0), SCREEN_TOL_MM),
        counter_pitch: if cam.track_count() == 2 { cam.polyline(Curve::Pitch(1), SCREEN_TOL_MM) } else { Vec::new() },
        counter_profile,
        base_radius_mm: cam.base_radius_mm(),
        phase_point: cam.phase_point(),
    };
    let roller = d.roller_radius_mm;
    Ok(CamProfileResponse {
        report,
        pressure_limit_deg: limit,
        curvature_limit_per_mm: (d.follower != Follower::Flat && roller > 0.0).then(|| 1.0 / roller),
        joints_deg: cam.joints_deg(),
        cam: curves(&cam, &pts, motion.unit()),
        counter: counter.map(|c| curves(&cam, &c, motion.unit())),
        drawing,
        profile_report,
    })
}

/// `POST /api/cam/dxf` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CamDxfRequest {
    /// The motion.
    #[serde(default)]
    pub source: CamSource,
    /// The cam.
    pub design: CamDesignRequest,
    /// Chord tolerance of the polylines (mm).
    #[serde(default = "default_tol")]
    #[schemars(transform = loomkin_units::schema::bounds(CHORD_TOL_RANGE))]
    pub chord_tol_mm: f64,
    /// Bore diameter (mm; 0 none; default [`loomkin_cams::profile::DEFAULT_BORE_PER_BASE_RADIUS`] × base
    /// radius).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(BORE_RANGE))]
    pub bore_mm: Option<f64>,
}

fn default_tol() -> f64 {
    DEFAULT_CHORD_TOL_MM
}

/// A file to download.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CamFile {
    /// Suggested file name.
    pub filename: String,
    /// Media type.
    pub media_type: &'static str,
    /// The file's text.
    pub text: String,
    /// One line on what was written.
    pub note: String,
}

/// The DXF drawing of the cam (`cam profile --dxf`); an undercut cam is refused, naming the field.
pub fn cam_dxf(req: &CamDxfRequest) -> Result<CamFile, ApiError> {
    let (cam, _, _, _) = build(&req.source, &req.design)?;
    if let Some(e) = undercut_error(&cam) {
        return Err(ApiError::invalid(e.field(), format!("{e}: no DXF written")));
    }
    let bore = req.bore_mm.unwrap_or_else(|| cam.default_bore_mm());
    let text = cam.dxf(req.chord_tol_mm, bore).map_err(|e| ApiError::from_library(&e, "chord_tol_mm"))?;
    Ok(CamFile {
        filename: "cam.dxf".into(),
        media_type: "image/vnd.dxf",
        text,
        note: format!("chord tolerance {} mm, units mm", compact(req.chord_tol_mm)),
    })
}

/// `POST /api/cam/table` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CamTableRequest {
    /// The motion.
    #[serde(default)]
    pub source: CamSource,
    /// `xyvaj`, `poly5`, `csv`, `twincat` or `st`.
    pub format: String,
    /// Points on the joints and every `step_deg` from each (default 1 when no tolerance).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(STEP_RANGE))]
    pub step_deg: Option<f64>,
    /// Fewest points for this re-interpolation error (slave unit), instead of a step; at least
    /// [`MIN_WEB_TOLERANCE`].
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(TOLERANCE_RANGE))]
    pub tolerance: Option<f64>,
}

/// A cam table written and its exact re-interpolation error.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CamTableResponse {
    /// The file.
    pub file: CamFile,
    /// Points written (poly5: segments + 1).
    pub points: usize,
    /// Slave unit.
    pub unit: &'static str,
    /// Largest position error of the table as the controller interpolates it (slave unit).
    pub max_position_error: f64,
    /// Where (deg).
    pub max_position_error_at_deg: f64,
    /// Largest velocity error (slave unit per deg).
    pub max_velocity_error: f64,
    /// Largest acceleration error (slave unit per deg²).
    pub max_accel_error: f64,
}

/// A controller cam table (`cam table`), its text and exact error.
pub fn cam_table(req: &CamTableRequest) -> Result<CamTableResponse, ApiError> {
    cam_table_until(req, &loomkin_units::StopFlag::default())
}

/// [`cam_table`] that ends early once `stop` is set (the client gone, the budget spent): the
/// table's error comparison looks at it as it goes.
pub(crate) fn cam_table_until(
    req: &CamTableRequest,
    stop: &loomkin_units::StopFlag,
) -> Result<CamTableResponse, ApiError> {
    let format = Format::parse(&req.format).map_err(|e| ApiError::from_library(&e, "format"))?;
    let (motion, _) = req.source.motion()?;
    let span = motion.end_deg() - motion.start_deg();
    let spacing = match (req.step_deg, req.tolerance) {
        (Some(_), Some(_)) => {
            return Err(ApiError::BadJson {
                field: "tolerance".into(),
                message: "tolerance: give step_deg or tolerance, not both".into(),
            });
        }
        (_, Some(t)) => {
            let t = TOLERANCE_RANGE.check("tolerance", t)?;
            if t < MIN_WEB_TOLERANCE {
                return Err(ApiError::invalid(
                    "tolerance",
                    format!(
                        "tolerance = {}: the workbench computes tables to a tolerance of {} at the finest (the \
                         answer stays quick); loomkin cam table takes {}",
                        compact(t),
                        compact(MIN_WEB_TOLERANCE),
                        TOLERANCE_RANGE.describe("--tolerance")
                    ),
                ));
            }
            Spacing::Tolerance(t)
        }
        (s, None) => {
            let s = STEP_RANGE.check("step_deg", s.unwrap_or(DEFAULT_STEP_DEG))?;
            if span / s > MAX_CAM_TABLE_POINTS as f64 {
                return Err(ApiError::invalid(
                    "step_deg",
                    format!(
                        "step_deg: {} deg over {} deg makes more than {MAX_CAM_TABLE_POINTS} points; use a larger step",
                        compact(s),
                        compact(span)
                    ),
                ));
            }
            Spacing::StepDeg(s)
        }
    };
    let table = CamTable::new(motion, spacing).map_err(|e| ApiError::from_library(&e, "step_deg"))?;
    let out = table.export_until(format, stop).map_err(|e| ApiError::from_library(&e, "format"))?;
    let ext = match format {
        Format::Xyvaj => "txt",
        Format::Poly5 => "txt",
        Format::Csv => "csv",
        Format::Twincat => "txt",
        Format::St => "st",
        Format::Xyva => "txt",
    };
    let e = &out.error;
    let unit = table.unit_name();
    let note = format!(
        "{} points; exact re-interpolation error {} {unit} at {} deg",
        out.points,
        compact(e.max_position_error),
        compact(e.max_position_error_at_deg)
    );
    Ok(CamTableResponse {
        file: CamFile {
            filename: format!("cam-table-{}.{ext}", format.name()),
            media_type: if ext == "csv" { "text/csv" } else { "text/plain" },
            text: out.text,
            note,
        },
        points: out.points,
        unit,
        max_position_error: e.max_position_error,
        max_position_error_at_deg: e.max_position_error_at_deg,
        max_velocity_error: e.max_velocity_error,
        max_accel_error: e.max_accel_error,
    })
}

async fn post_profile(ApiJson(req): ApiJson<CamProfileRequest>) -> Result<ApiJson<CamProfileResponse>, ApiError> {
    crate::server::blocking(move || cam_profile(&req)).await.map(ApiJson)
}

async fn post_dxf(ApiJson(req): ApiJson<CamDxfRequest>) -> Result<ApiJson<CamFile>, ApiError> {
    crate::server::blocking(move || cam_dxf(&req)).await.map(ApiJson)
}

async fn post_table(ApiJson(req): ApiJson<CamTableRequest>) -> Result<ApiJson<CamTableResponse>, ApiError> {
    crate::pool::heavy(move |stop| cam_table_until(&req, stop)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn design() -> CamDesignRequest {
        CamDesignRequest {
            follower: FollowerKind::Translating,
            closure: ClosureKind::Single,
            prime_radius_mm: None,
            max_pressure_deg: Some(30.0),
            roller_radius_mm: 15.0,
            offset_mm: 0.0,
            arm_mm: None,
            pivot_mm: None,
        }
    }

    /// The view shows what `cam profile` computes, and its downloads are the library's exporters'
    /// bytes.
    #[test]
    fn the_view_answers_what_the_library_computes() {
        let req = CamProfileRequest { source: CamSource::default(), design: design(), step_deg: 1.0 };
        let r = cam_profile(&req).unwrap();
        let cycle = Cycle::from_toml(CAM_EXAMPLES[0].1).unwrap();
        let motion = Motion::from_cycle(&cycle);
        let d = design().design().unwrap();
        let cam = CamProfile::new(&motion, &d).unwrap();
        assert_eq!(r.report.prime_radius_mm, cam.prime_radius_mm());
        assert_eq!(r.report.extremes.max_pressure_angle_deg, cam.max_pressure_angle().0);
        // The embedded library report is the CLI's `--json` without its points; the web's own
        // keys agree with it.
        let mut cli = cam.report(r.report.source.clone(), 1.0);
        cli.points.clear();
        cli.counter_points = None;
        assert_eq!(r.profile_report, cli);
        assert_eq!(r.profile_report.base_radius_mm, r.report.base_radius_mm);
        assert_eq!(r.profile_report.roller_max_mm, r.report.roller_max_mm);
        // Sized for 30°: the largest pressure angle is the limit drawn.
        assert!((r.report.extremes.max_pressure_angle_deg - 30.0).abs() < 1e-9);
        assert_eq!(r.pressure_limit_deg, 30.0);
        assert_eq!(r.curvature_limit_per_mm, Some(1.0 / 15.0));
        // 0 … 360 inclusive, closed.
        assert_eq!(r.cam.angle_deg.len(), 361);
        assert_eq!(r.cam.angle_deg[360], 360.0);
        // No sampled pressure angle exceeds the located maximum.
        assert!(r.cam.pressure_angle_deg.iter().all(|p| p.abs() <= r.report.extremes.max_pressure_angle_deg + 1e-9));
        let dxf = cam_dxf(&CamDxfRequest {
            source: CamSource::default(),
            design: design(),
            chord_tol_mm: 0.01,
            bore_mm: None,
        })
        .unwrap();
        assert_eq!(dxf.text, cam.dxf(0.01, 0.4 * cam.base_radius_mm()).unwrap());
        let t = cam_table(&CamTableRequest {
            source: CamSource::default(),
            format: "csv".into(),
            step_deg: Some(7.0),
            tolerance: None,
        })
        .unwrap();
        let direct = CamTable::new(motion, Spacing::StepDeg(7.0)).unwrap().export(Format::Csv).unwrap();
        assert_eq!(t.file.text, direct.text);
        assert_eq!(t.max_position_error, direct.error.max_position_error);
        assert!(
            t.file.text.starts_with("master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3")
        );
    }

    /// A set stop flag ends the table request (issue 27: an abandoned request ran on); an unset
    /// one gives the plain request's file.
    #[test]
    fn the_table_stops_when_asked() {
        let req = CamTableRequest {
            source: CamSource::default(),
            format: "xyvaj".into(),
            step_deg: Some(0.01),
            tolerance: None,
        };
        let stop = loomkin_units::StopFlag::default();
        assert_eq!(cam_table_until(&req, &stop).unwrap().file.text, cam_table(&req).unwrap().file.text);
        stop.stop();
        assert!(cam_table_until(&req, &stop).is_err());
    }

    #[test]
    fn sources_and_bad_inputs_are_named() {
        // A shedding preset: its full frame cycle over 720°.
        let shed = CamSource {
            shed: Some(ShedSource { preset: "dobby".into(), stroke_mm: 100.0, motion_deg: None }),
            ..Default::default()
        };
        let r = cam_profile(&CamProfileRequest { source: shed, design: design(), step_deg: 2.0 }).unwrap();
        assert_eq!(*r.cam.angle_deg.last().unwrap(), 720.0);
        assert!((r.report.stroke - 100.0).abs() < 1e-9);
        // A catalogue law swinging an oscillating follower.
        let law = CamSource {
            law: Some(CamLaw {
                law: LawChoice { name: "cycloidal".into(), params: Default::default() },
                stroke_mm: None,
                stroke_deg: Some(15.0),
                motion_deg: 120.0,
            }),
            ..Default::default()
        };
        let mut osc = design();
        osc.follower = FollowerKind::Oscillating;
        osc.arm_mm = Some(120.0);
        osc.pivot_mm = Some(150.0);
        osc.roller_radius_mm = 10.0;
        osc.max_pressure_deg = Some(40.0);
        let r = cam_profile(&CamProfileRequest { source: law.clone(), design: osc.clone(), step_deg: 1.0 }).unwrap();
        assert_eq!(r.report.unit, "deg");
        // A roller too large (above the largest without undercut, inside the prime circle):
        // reported, and the DXF refused naming the roller and the largest one.
        let steep = CamSource {
            law: Some(CamLaw {
                law: LawChoice { name: "cycloidal".into(), params: Default::default() },
                stroke_mm: Some(40.0),
                stroke_deg: None,
                motion_deg: 60.0,
            }),
            ..Default::default()
        };
        let mut big = design();
        big.max_pressure_deg = None;
        big.prime_radius_mm = Some(80.0);
        let r = cam_profile(&CamProfileRequest { source: steep.clone(), design: big.clone(), step_deg: 1.0 }).unwrap();
        let rmax = r.report.roller_max_mm.unwrap();
        assert!(rmax < 70.0, "{rmax}");
        big.roller_radius_mm = rmax + 1.0;
        let r = cam_profile(&CamProfileRequest { source: steep.clone(), design: big.clone(), step_deg: 1.0 }).unwrap();
        assert!(r.report.extremes.undercut && r.report.undercut_at_deg.is_some());
        let e = cam_dxf(&CamDxfRequest { source: steep, design: big, chord_tol_mm: 0.01, bore_mm: None }).unwrap_err();
        assert_eq!(e.field(), "design.roller_radius_mm", "{e}");
        assert!(e.to_string().contains("largest roller"), "{e}");
        let mut no_arm = osc;
        no_arm.arm_mm = None;
        assert_eq!(
            cam_profile(&CamProfileRequest { source: law, design: no_arm, step_deg: 1.0 }).unwrap_err().field(),
            "design.arm_mm"
        );
        let both = CamSource { cycle_toml: Some(CAM_EXAMPLES[0].1.into()), ..shed_dobby() };
        assert_eq!(
            cam_profile(&CamProfileRequest { source: both, design: design(), step_deg: 1.0 }).unwrap_err().field(),
            "source"
        );
        let e = cam_table(&CamTableRequest {
            source: CamSource::default(),
            format: "xyvb".into(),
            step_deg: None,
            tolerance: None,
        })
        .unwrap_err();
        assert_eq!(e.field(), "format");
        let e = cam_table(&CamTableRequest {
            source: CamSource::default(),
            format: "st".into(),
            step_deg: Some(0.001),
            tolerance: None,
        })
        .unwrap_err();
        assert_eq!(e.field(), "step_deg");
    }

    fn shed_dobby() -> CamSource {
        CamSource {
            shed: Some(ShedSource { preset: "dobby".into(), stroke_mm: 100.0, motion_deg: None }),
            ..Default::default()
        }
    }
}
