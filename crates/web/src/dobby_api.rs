//! The dobby view: conjugate cams of a rotary-dobby modulator synthesised for an output law, and
//! the mechanism's joints at every input angle (the page draws it at the angle of a slider).

use crate::catalogue::LawChoice;
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::{get, post};
use loomkin_io::dxf::{DxfUnit, write_shapes};
use loomkin_mech::dobby_export::{DEFAULT_CHORD_TOL_MM, synthesis_points_table, synthesis_shapes};
use loomkin_mech::{
    CamProfile, GivenLength, MechError, MechanismPose, ModulatorGeometry, OutputLawSpec, ROLLER_M_RANGE,
    STEP_DEG_RANGE, Synthesis, SynthesisOptions, SynthesisSummary, Warning, synthesize,
};
use loomkin_units::{FieldError, compact};
use serde::{Deserialize, Serialize};

pub(crate) fn routes() -> Router {
    Router::new()
        .route("/dobby/default", get(|| async { ApiJson(DobbyRequest::default()) }))
        .route("/dobby/synthesize", post(post_synthesize))
        .route("/dobby/export", post(post_export))
}

/// The output law of the modulator.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DobbyLaw {
    /// Cycles per input revolution, [`OutputLawSpec::CYCLES_RANGE`].
    #[schemars(transform = loomkin_units::schema::bounds(OutputLawSpec::CYCLES_RANGE))]
    pub cycles: u32,
    /// Output dwell per cycle (deg of input).
    pub dwell_deg: f64,
    /// Input angle at the centre of the first dwell (deg).
    pub dwell_centre_deg: f64,
    /// Shape of each rise: a law of the catalogue.
    pub rise: LawChoice,
}

/// `POST /api/dobby/synthesize` request (and `GET /api/dobby/default` answer: the paper's case).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DobbyRequest {
    /// The output law.
    pub law: DobbyLaw,
    /// The modulator's links (m) and angles (deg).
    pub geometry: ModulatorGeometry,
    /// Roller radius (m), [`ROLLER_M_RANGE`].
    #[schemars(transform = loomkin_units::schema::bounds(ROLLER_M_RANGE))]
    pub roller_m: f64,
    /// Step of the input angle (deg), [`STEP_DEG_RANGE`], at most [`MAX_DOBBY_ROWS`] rows a turn.
    #[schemars(transform = loomkin_units::schema::bounds(STEP_DEG_RANGE))]
    pub step_deg: f64,
}

/// Most input angles of a synthesis answer (a 0.25° step): each carries the mechanism's pose, so a
/// finer step is refused by the workbench (`loomkin dobby synthesize` goes to
/// [`STEP_DEG_RANGE`]'s lower end).
pub const MAX_DOBBY_ROWS: usize = 1441;

impl Default for DobbyRequest {
    /// The paper's geometry and its task 2: two dwells of 40° centred at 90° and 270°, cycloidal rises.
    fn default() -> Self {
        let spec = OutputLawSpec::default();
        Self {
            law: DobbyLaw {
                cycles: spec.cycles,
                dwell_deg: spec.dwell_deg,
                dwell_centre_deg: spec.dwell_centre_deg,
                rise: LawChoice { name: spec.rise.name().into(), params: Default::default() },
            },
            geometry: ModulatorGeometry::default(),
            roller_m: SynthesisOptions::default().roller_m,
            step_deg: SynthesisOptions::default().step_deg,
        }
    }
}

/// Per input angle, in columns.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct DobbyCurves {
    /// Input angle φ2 (deg).
    pub phi2_deg: Vec<f64>,
    /// Output angle φ6 (deg).
    pub phi6_deg: Vec<f64>,
    /// Output speed ω6 at ω2 = 1 rad/s (rad/s).
    pub omega6_rad_s: Vec<f64>,
    /// Output acceleration ε6 at ω2 = 1 rad/s (rad/s²).
    pub eps6_rad_s2: Vec<f64>,
    /// Pressure angle at the cam roller B (deg).
    pub mu_b_deg: Vec<f64>,
    /// Pressure angle at the counter-cam roller C (deg).
    pub mu_c_deg: Vec<f64>,
    /// Output pressure angle (deg).
    pub mu_out_deg: Vec<f64>,
}

/// `POST /api/dobby/synthesize` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct DobbyResponse {
    /// Summary and checks.
    pub summary: SynthesisSummary,
    /// Warnings (pressure angles, undercut, crossing walls).
    pub warnings: Vec<Warning>,
    /// The cam Γ (roller B): roller-centre curve and groove walls (m).
    pub cam: CamProfile,
    /// The counter-cam Γ′ (roller C).
    pub counter_cam: CamProfile,
    /// The curves.
    pub curves: DobbyCurves,
    /// Joint positions at every input angle of `curves` (m).
    pub poses: Vec<MechanismPose>,
    /// The pressure angle the checks warn above (deg), drawn as the limit line of the pressure plot.
    pub pressure_limit_deg: f64,
}

/// Maps an error of the mechanisms crate to the request field it concerns: the library's own
/// names (`l6_m`, `dwell_deg`) are placed under `geometry.` or `law.` as in the request.
fn mech_error(e: MechError) -> ApiError {
    const GEOMETRY: [&str; 6] = ["l2_m", "l3_m", "l3p_m", "l6_m", "alpha_deg", "theta_deg"];
    const LAW: [&str; 3] = ["cycles", "dwell_deg", "dwell_centre_deg"];
    let (field, prefix) = match &e {
        MechError::Law(_) => ("rise".to_string(), Some("law")),
        e => match e.field() {
            Some(f) if GEOMETRY.contains(&f) => (f.to_string(), Some("geometry")),
            Some(f) if LAW.contains(&f) => (f.to_string(), Some("law")),
            Some(f) => (f.to_string(), None),
            None => ("law".to_string(), None),
        },
    };
    let err = ApiError::invalid(field, e);
    match prefix {
        Some(p) => err.within(p),
        None => err,
    }
}

/// The options of a synthesis: the request's step and roller, the library's other defaults.
fn options(req: &DobbyRequest) -> Result<SynthesisOptions, ApiError> {
    let step = STEP_DEG_RANGE.check("step_deg", req.step_deg)?;
    let roller = ROLLER_M_RANGE.check("roller_m", req.roller_m)?;
    if 360.0 / step + 1.0 > MAX_DOBBY_ROWS as f64 {
        return Err(ApiError::invalid(
            "step_deg",
            format!(
                "step_deg = {}: the workbench draws at most {MAX_DOBBY_ROWS} input angles a turn (a step of {} deg at the \
                 finest)",
                compact(step),
                compact(360.0 / (MAX_DOBBY_ROWS - 1) as f64)
            ),
        ));
    }
    Ok(SynthesisOptions { step_deg: step, roller_m: roller, ..SynthesisOptions::default() })
}

fn synthesis(req: &DobbyRequest) -> Result<Synthesis, ApiError> {
    let opts = options(req)?;
    OutputLawSpec::CYCLES_RANGE.check("law.cycles", f64::from(req.law.cycles))?;
    let rise = req.law.rise.spec().map_err(|e| ApiError::invalid("law.rise", e))?;
    let spec = OutputLawSpec {
        cycles: req.law.cycles,
        dwell_deg: req.law.dwell_deg,
        dwell_centre_deg: req.law.dwell_centre_deg,
        rise,
    };
    synthesize(&req.geometry, &spec, &opts).map_err(mech_error)
}

/// Synthesises the cams and samples the mechanism.
pub fn dobby_synthesize(req: &DobbyRequest) -> Result<DobbyResponse, ApiError> {
    let s = synthesis(req)?;
    let pressure_limit_deg = options(req)?.pressure_limit_deg;
    let col = |f: &dyn Fn(&loomkin_mech::SynthesisRow) -> f64| s.rows.iter().map(|r| finite(f(r))).collect::<Vec<_>>();
    let curves = DobbyCurves {
        phi2_deg: col(&|r| r.phi2_deg),
        phi6_deg: col(&|r| r.phi6_deg),
        omega6_rad_s: col(&|r| r.omega6_rad_s),
        eps6_rad_s2: col(&|r| r.eps6_rad_s2),
        mu_b_deg: col(&|r| r.mu_b_deg),
        mu_c_deg: col(&|r| r.mu_c_deg),
        mu_out_deg: col(&|r| r.mu_out_deg),
    };
    let poses = s.states.iter().map(|st| st.pose(&req.geometry)).collect();
    Ok(DobbyResponse {
        summary: s.summary,
        warnings: s.warnings,
        cam: s.cam,
        counter_cam: s.counter_cam,
        curves,
        poses,
        pressure_limit_deg,
    })
}

/// What `POST /api/dobby/export` writes.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum DobbyExportFormat {
    /// The drawing of both cams in mm, as `loomkin dobby synthesize --dxf` writes it.
    Dxf,
    /// The cam point table as CSV in m (as `loomkin dobby synthesize --points-csv`).
    Csv,
}

/// `POST /api/dobby/export` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DobbyExportRequest {
    /// The synthesis, as for `/api/dobby/synthesize`.
    pub request: DobbyRequest,
    /// The file to write.
    pub format: DobbyExportFormat,
}

/// `POST /api/dobby/export` answer: a file for the browser to save.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct DobbyExportResponse {
    /// Suggested file name.
    pub filename: &'static str,
    /// Media type.
    pub media_type: &'static str,
    /// The file's text.
    pub text: String,
}

/// The cams of a synthesis as a file, through the same writers as the CLI.
pub fn dobby_export(req: &DobbyExportRequest) -> Result<DobbyExportResponse, ApiError> {
    let s = synthesis(&req.request).map_err(|e| e.within("request"))?;
    // As the CLI: an undercut cam is reported, never drawn.
    if let Some(why) = s.undercut_refusal(GivenLength::Metre) {
        return Err(ApiError::invalid("request.roller_m", why));
    }
    let mut out = Vec::new();
    let (filename, media_type) = match req.format {
        DobbyExportFormat::Dxf => {
            // The CLI's defaults: chord tolerance 0.01 mm, bore 0.4 × the cams' least radius.
            let shapes = synthesis_shapes(&s, DEFAULT_CHORD_TOL_MM, None).map_err(mech_error)?;
            write_shapes(&shapes, DxfUnit::Millimetre, &mut out).map_err(|e| ApiError::Internal(e.to_string()))?;
            ("dobby-cams.dxf", "image/vnd.dxf")
        }
        DobbyExportFormat::Csv => {
            synthesis_points_table(&s)
                .and_then(|t| t.write_csv(&mut out))
                .map_err(|e| ApiError::Internal(e.to_string()))?;
            ("dobby-cams.csv", "text/csv")
        }
    };
    let text = String::from_utf8(out).map_err(|e| ApiError::Internal(e.to_string()))?;
    Ok(DobbyExportResponse { filename, media_type, text })
}

async fn post_export(ApiJson(req): ApiJson<DobbyExportRequest>) -> Result<ApiJson<DobbyExportResponse>, ApiError> {
    crate::server::blocking(move || dobby_export(&req)).await.map(ApiJson)
}

async fn post_synthesize(ApiJson(req): ApiJson<DobbyRequest>) -> Result<ApiJson<DobbyResponse>, ApiError> {
    crate::server::blocking(move || dobby_synthesize(&req)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
        (a[0] - b[0]).hypot(a[1] - b[1])
    }

    #[test]
    fn poses_keep_the_link_lengths_and_rollers_ride_the_cams() {
        let req = DobbyRequest { step_deg: 2.0, ..DobbyRequest::default() };
        let r = dobby_synthesize(&req).unwrap();
        let g = &req.geometry;
        assert_eq!(r.poses.len(), r.curves.phi2_deg.len());
        for (k, p) in r.poses.iter().enumerate() {
            assert!((dist(p.o, p.a) - g.l2_m).abs() < 1e-9);
            assert!((dist(p.a, p.b) - g.l3_m).abs() < 1e-9);
            assert!((dist(p.a, p.c) - g.l3p_m).abs() < 1e-9);
            assert!((dist(p.o, p.d) - g.l6_m).abs() < 1e-9);
            // Roller B's centre is on the cam's roller-centre curve.
            assert!(r.cam.centre.iter().any(|q| dist(*q, p.b) < 1e-9), "pose {k}");
        }
        // Dwell: φ6 is held at the dwell centre (90°) around φ2 = 90°.
        let i = r.curves.phi2_deg.iter().position(|&x| (x - 90.0).abs() < 1e-9).unwrap();
        assert!((r.curves.phi6_deg[i] - 90.0).abs() < 1e-9 && r.curves.omega6_rad_s[i].abs() < 1e-9);
    }

    /// The DXF holds the six closed polylines of both cams in mm, the CSV one row per input angle
    /// whose cam points are the synthesis's (m); a bad request names its field under `request`.
    #[test]
    fn exports_are_the_cams_of_the_synthesis() {
        let request = DobbyRequest { step_deg: 2.0, ..DobbyRequest::default() };
        let r = dobby_synthesize(&request).unwrap();
        let dxf =
            dobby_export(&DobbyExportRequest { request: request.clone(), format: DobbyExportFormat::Dxf }).unwrap();
        assert_eq!(dxf.text.matches("\nLWPOLYLINE\r\n").count() + dxf.text.matches("\nLWPOLYLINE\n").count(), 6);
        for layer in ["CAM_CENTRE", "CAM_WALL_LEFT", "COUNTER_CAM_WALL_RIGHT"] {
            assert!(dxf.text.contains(layer), "{layer}");
        }
        // $INSUNITS 4 = millimetres, and a point of the cam's centre curve appears scaled to mm.
        assert!(dxf.text.contains("$INSUNITS"));
        let csv =
            dobby_export(&DobbyExportRequest { request: request.clone(), format: DobbyExportFormat::Csv }).unwrap();
        let lines: Vec<&str> = csv.text.lines().collect();
        assert!(lines[0].starts_with("phi2_deg,b_x_m,b_y_m"));
        assert_eq!(lines.len() - 1, r.cam.centre.len());
        let row: Vec<f64> = lines[1].split(',').map(|v| v.parse().unwrap()).collect();
        assert!((row[1] - r.cam.centre[0][0]).abs() < 1e-12 && (row[2] - r.cam.centre[0][1]).abs() < 1e-12);
        let mut big = request.clone();
        big.roller_m = 0.19;
        assert!(dobby_synthesize(&big).unwrap().summary.undercut, "a 190 mm roller undercuts the paper's cams");
        {
            let e = dobby_export(&DobbyExportRequest { request: big, format: DobbyExportFormat::Dxf }).unwrap_err();
            assert_eq!(e.field(), "request.roller_m", "{e}");
            assert!(e.to_string().contains("undercuts"), "{e}");
        }
        let mut bad = request;
        bad.roller_m = -1.0;
        let e = dobby_export(&DobbyExportRequest { request: bad, format: DobbyExportFormat::Dxf }).unwrap_err();
        assert_eq!(e.field(), "request.roller_m");
    }

    #[test]
    fn bad_requests_name_the_field() {
        let mut req = DobbyRequest { step_deg: 0.001, ..DobbyRequest::default() };
        assert_eq!(dobby_synthesize(&req).unwrap_err().field(), "step_deg");
        req.step_deg = 2.0;
        req.law.rise.name = "zigzag".into();
        assert_eq!(dobby_synthesize(&req).unwrap_err().field(), "law.rise");
        req.law.rise.name = "cycloidal".into();
        req.law.dwell_deg = 170.0;
        let e = dobby_synthesize(&req).unwrap_err();
        assert!(e.status().is_client_error(), "{e}");
        req.law.dwell_deg = -10.0;
        let e = dobby_synthesize(&req).unwrap_err();
        assert_eq!(e.field(), "law.dwell_deg", "{e}");
        req.law.dwell_deg = 40.0;
        req.geometry.l6_m = 1.0;
        let e = dobby_synthesize(&req).unwrap_err();
        assert_eq!(e.field(), "geometry.l6_m", "{e}");
        assert!(e.to_string().starts_with("geometry.l6_m = 1 is out of range"), "{e}");
        req.geometry.l6_m = 0.4;
        req.geometry.alpha_deg = 179.0;
        req.geometry.theta_deg = 179.0;
        let e = dobby_synthesize(&req).unwrap_err();
        assert_eq!(e.field(), "geometry.alpha_deg", "{e}");
        assert!(e.to_string().contains("admissible α"), "{e}");
    }
}
