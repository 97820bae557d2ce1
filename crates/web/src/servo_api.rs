//! The servo law editor's endpoints: evaluate (one drag update), optimise, export, save, load.

use crate::error::check_count;
use crate::limits::{DEFAULT_CAM_ROWS, DEFAULT_SAMPLES, MAX_CAM_ROWS, MAX_SAMPLES, MIN_CAM_ROWS, MIN_SAMPLES};
use crate::series::{LawSamples, finite};
use crate::servo_design::{DesignFormat, ServoDesign, design_from_text, design_spline, design_text, servo_error};
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::{get, post};
use loomkin_laws::Metrics;
pub use loomkin_servo::ExportFormat;
use loomkin_servo::{
    Interpolation, Objective, OptimizeOptions, ReinterpolationRow, TorqueSummary, optimize, summary, torque_curve,
};
use serde::{Deserialize, Serialize};
use std::time::Instant;

pub(crate) fn routes() -> Router {
    Router::new()
        .route("/servo/default", get(|| async { ApiJson(DesignResponse { design: ServoDesign::default() }) }))
        .route("/servo/evaluate", post(post_evaluate))
        .route("/servo/optimize", post(post_optimize))
        .route("/servo/export", post(post_export))
        .route("/servo/design/save", post(post_save))
        .route("/servo/design/load", post(post_load))
}

/// `{"design": …}`: answer of `GET /api/servo/default` and `POST /api/servo/design/load`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq, schemars::JsonSchema)]
pub struct DesignResponse {
    /// The design.
    pub design: ServoDesign,
}

/// `POST /api/servo/evaluate` request: one redraw of the editor.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EvaluateRequest {
    /// The design.
    pub design: ServoDesign,
    /// Samples per curve, [`MIN_SAMPLES`] … [`MAX_SAMPLES`] (default [`DEFAULT_SAMPLES`]).
    #[serde(default = "default_samples")]
    #[schemars(transform = crate::schema::count(MIN_SAMPLES, MAX_SAMPLES))]
    pub samples: usize,
}

fn default_samples() -> usize {
    DEFAULT_SAMPLES
}

/// The spline `f(x)` through the definition points (definition units), sampled on `[0, 1]`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SplineSamples {
    /// Positions (fraction of the motion angle).
    pub x: Vec<f64>,
    /// `f(x)`; the law's acceleration is `a = scale·f`.
    pub f: Vec<f64>,
}

/// The normalised law of the design.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct LawReport {
    /// Exact characteristic values.
    pub metrics: Metrics,
    /// Smoothness class in a dwell-rise-dwell cycle.
    pub continuity_class: i32,
    /// `s, v, a, j` of the unit rise.
    pub samples: LawSamples,
}

/// The drive at one main-shaft speed: summary and curves over one turn.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SpeedReport {
    /// Peak / RMS torque, peak power and more (see `loomkin_servo::TorqueSummary`).
    #[serde(flatten)]
    pub summary: TorqueSummary,
    /// Main-shaft angle (deg), 0 … 360.
    pub angle_deg: Vec<f64>,
    /// Motor torque M (N·m).
    pub torque_nm: Vec<f64>,
    /// Motor power P (W).
    pub power_w: Vec<f64>,
    /// Rack position u (m).
    pub u_m: Vec<f64>,
}

/// `POST /api/servo/evaluate` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct EvaluateResponse {
    /// The checked definition points (ends snapped to exactly 0 and 0.5).
    pub points: Vec<[f64; 2]>,
    /// Slope D of f at x = 0.5.
    pub d: f64,
    /// Scale from f to the unit law's acceleration, `a = scale·f`.
    pub scale: f64,
    /// The spline through the points.
    pub spline: SplineSamples,
    /// The normalised law.
    pub law: LawReport,
    /// The drive at each speed, in request order.
    pub speeds: Vec<SpeedReport>,
    /// Server time spent on the computation (ms).
    pub compute_ms: f64,
}

/// One redraw of the editor: rebuild the law, sample it, the torque curves at every speed.
pub fn evaluate(req: &EvaluateRequest) -> Result<EvaluateResponse, ApiError> {
    let t0 = Instant::now();
    let n = check_count("samples", req.samples, MIN_SAMPLES, MAX_SAMPLES)?;
    let spline = design_spline(&req.design).map_err(|e| e.within("design"))?;
    let law = spline.law();
    let samples = LawSamples::of(law, n);
    let f = samples.a.iter().map(|a| finite(a / spline.scale())).collect();
    let mut speeds = Vec::with_capacity(req.design.speeds_rpm.len());
    for (i, &rpm) in req.design.speeds_rpm.iter().enumerate() {
        let field = |e| match servo_error(e) {
            ApiError::Invalid { field, message } if field == "speed_rpm" => {
                ApiError::invalid(format!("speeds_rpm[{i}]"), message).within("design")
            }
            e => e.within("design"),
        };
        let s = summary(law, &req.design.drive, rpm).map_err(field)?;
        let curve = torque_curve(law, &req.design.drive, rpm, n).map_err(field)?;
        speeds.push(SpeedReport {
            summary: s,
            angle_deg: curve.iter().map(|p| finite(p.angle_deg)).collect(),
            torque_nm: curve.iter().map(|p| finite(p.torque_nm)).collect(),
            power_w: curve.iter().map(|p| finite(p.power_w)).collect(),
            u_m: curve.iter().map(|p| finite(p.u_m)).collect(),
        });
    }
    Ok(EvaluateResponse {
        points: spline.points().to_vec(),
        d: spline.d(),
        scale: spline.scale(),
        spline: SplineSamples { x: samples.x.clone(), f },
        law: LawReport { metrics: law.metrics(), continuity_class: law.continuity().class, samples },
        speeds,
        compute_ms: loomkin_units::ms_from_s(t0.elapsed().as_secs_f64()),
    })
}

/// `POST /api/servo/optimize` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OptimizeRequest {
    /// The starting design (its speeds are the optimiser's speeds).
    pub design: ServoDesign,
    /// `peak` (default) or `rms` torque.
    #[serde(default)]
    pub objective: Objective,
    /// Move the X of the free points too (default true).
    #[serde(default = "yes")]
    pub move_x: bool,
}

fn yes() -> bool {
    true
}

/// Torques of one law at one speed, before or after optimisation.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TorquePair {
    /// Main-shaft speed (1/min).
    pub speed_rpm: f64,
    /// Peak torque (N·m).
    pub peak_torque_nm: f64,
    /// RMS torque over the turn (N·m).
    pub rms_torque_nm: f64,
    /// Peak power (W).
    pub peak_power_w: f64,
}

impl From<&TorqueSummary> for TorquePair {
    fn from(s: &TorqueSummary) -> Self {
        Self {
            speed_rpm: s.speed_rpm,
            peak_torque_nm: s.peak_torque_nm,
            rms_torque_nm: s.rms_torque_nm,
            peak_power_w: s.peak_power_w,
        }
    }
}

/// `POST /api/servo/optimize` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct OptimizeResponse {
    /// `peak` or `rms`.
    pub objective: Objective,
    /// The starting law at each speed.
    pub before: Vec<TorquePair>,
    /// The optimised law at each speed.
    pub after: Vec<TorquePair>,
    /// The optimised definition points `[[X, Y], …]`.
    pub def_points: Vec<[f64; 2]>,
    /// Objective evaluations spent.
    pub evaluations: usize,
    /// Wall time (ms).
    pub elapsed_ms: f64,
}

/// Moves the free points to lower the worst peak (or RMS) torque over the design's speeds.
pub fn optimize_design(req: &OptimizeRequest) -> Result<OptimizeResponse, ApiError> {
    optimize_until(req, &loomkin_servo::StopFlag::default())
}

/// [`optimize_design`] that stops early when `stop` is set (the caller then discards the result).
pub(crate) fn optimize_until(
    req: &OptimizeRequest,
    stop: &loomkin_servo::StopFlag,
) -> Result<OptimizeResponse, ApiError> {
    let t0 = Instant::now();
    let spline = design_spline(&req.design).map_err(|e| e.within("design"))?;
    let opts = OptimizeOptions {
        objective: req.objective,
        speeds_rpm: req.design.speeds_rpm.clone(),
        move_x: req.move_x,
        stop: stop.clone(),
        ..OptimizeOptions::default()
    };
    let r = optimize(&spline, &req.design.drive, &opts).map_err(|e| servo_error(e).within("design"))?;
    Ok(OptimizeResponse {
        objective: r.objective,
        before: r.before.iter().map(TorquePair::from).collect(),
        after: r.after.iter().map(TorquePair::from).collect(),
        def_points: r.law.points().to_vec(),
        evaluations: r.evaluations,
        elapsed_ms: loomkin_units::ms_from_s(t0.elapsed().as_secs_f64()),
    })
}

/// `POST /api/servo/export` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ExportRequest {
    /// The design.
    pub design: ServoDesign,
    /// What to export.
    pub format: ExportFormat,
    /// Rows of a cam table over 0 … 360°, [`MIN_CAM_ROWS`] … [`MAX_CAM_ROWS`] (default
    /// [`DEFAULT_CAM_ROWS`]: a 1° step): the step is `360/(rows − 1)` degrees from each joint of
    /// the law, and the table also has a point on every joint (the cam-table engine of `loomkin cam
    /// table`), so it has a few more rows.
    #[serde(default = "default_rows")]
    #[schemars(transform = crate::schema::count(MIN_CAM_ROWS, MAX_CAM_ROWS))]
    pub rows: usize,
}

fn default_rows() -> usize {
    DEFAULT_CAM_ROWS
}

/// `POST /api/servo/export` answer: a file for the browser to save.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ExportResponse {
    /// Suggested file name.
    pub filename: String,
    /// Media type.
    pub media_type: &'static str,
    /// The file's text.
    pub text: String,
    /// For cam tables: what re-interpolating the table as a controller would loses (rows with the
    /// mode as `mode` and as `interpolation`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub interpolation: Vec<ReinterpolationRow>,
    /// The same rows under the key of `loomkin servo export --json`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub reinterpolation: Vec<ReinterpolationRow>,
    /// A one-line summary for the status bar.
    pub note: String,
}

/// Writes the export file (the servo crate's exporter; cam tables with `rows` rows over a turn).
pub fn export(req: &ExportRequest) -> Result<ExportResponse, ApiError> {
    export_until(req, &loomkin_servo::StopFlag::default())
}

/// [`export`] that ends early once `stop` is set (the client gone, the budget spent).
pub(crate) fn export_until(req: &ExportRequest, stop: &loomkin_servo::StopFlag) -> Result<ExportResponse, ApiError> {
    let spline = design_spline(&req.design).map_err(|e| e.within("design"))?;
    let step = if req.format.is_cam_table() {
        // At least MIN_CAM_ROWS rows: a step of at most 90°.
        let rows = check_count("rows", req.rows, MIN_CAM_ROWS, MAX_CAM_ROWS)?;
        360.0 / (rows - 1) as f64
    } else {
        1.0
    };
    let file =
        loomkin_servo::export_until(&spline, &req.design.drive, req.format, step, stop).map_err(|e| {
            match req.format {
                ExportFormat::Csv | ExportFormat::Xyva => servo_error(e),
                _ => servo_error(e).within("design"),
            }
        })?;
    let (interpolation, note) = match file.table {
        Some(t) => {
            let mode =
                if req.format == ExportFormat::Csv { Interpolation::Linear } else { Interpolation::QuinticHermite };
            let worst = t.reinterpolation.iter().find(|e| e.mode == mode).map_or(0.0, |e| e.max_position_error_m);
            let note = format!(
                "{} rows, step {:.4}°; re-interpolated {}: worst position error {:.3e} m",
                t.points,
                t.step_deg,
                mode.name(),
                worst
            );
            (t.reinterpolation.iter().map(ReinterpolationRow::from).collect::<Vec<_>>(), note)
        }
        None => (Vec::new(), String::new()),
    };
    Ok(ExportResponse {
        filename: file.filename.into(),
        media_type: file.media_type,
        text: file.text,
        reinterpolation: interpolation.clone(),
        interpolation,
        note,
    })
}

/// `POST /api/servo/design/save` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SaveRequest {
    /// The design.
    pub design: ServoDesign,
    /// `json` (default) or `toml`.
    #[serde(default)]
    pub format: DesignFormat,
}

/// Writes the design file (checked first, so a saved file always loads).
pub fn save(req: &SaveRequest) -> Result<ExportResponse, ApiError> {
    design_spline(&req.design).map_err(|e| e.within("design"))?;
    let (filename, media_type) = match req.format {
        DesignFormat::Toml => ("servo-design.toml", "application/toml"),
        _ => ("servo-design.json", "application/json"),
    };
    Ok(ExportResponse {
        filename: filename.into(),
        media_type,
        text: design_text(&req.design, req.format)?,
        interpolation: Vec::new(),
        reinterpolation: Vec::new(),
        note: String::new(),
    })
}

/// `POST /api/servo/design/load` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadRequest {
    /// The file's text.
    pub text: String,
    /// `json`, `toml` or `auto` (default).
    #[serde(default = "auto")]
    pub format: DesignFormat,
}

fn auto() -> DesignFormat {
    DesignFormat::Auto
}

/// Reads a design file.
pub fn load(req: &LoadRequest) -> Result<DesignResponse, ApiError> {
    design_from_text(&req.text, req.format).map(|design| DesignResponse { design })
}

async fn post_evaluate(ApiJson(req): ApiJson<EvaluateRequest>) -> Result<ApiJson<EvaluateResponse>, ApiError> {
    crate::server::blocking(move || evaluate(&req)).await.map(ApiJson)
}

async fn post_optimize(ApiJson(req): ApiJson<OptimizeRequest>) -> Result<ApiJson<OptimizeResponse>, ApiError> {
    crate::pool::heavy(move |stop| optimize_until(&req, stop)).await.map(ApiJson)
}

async fn post_export(ApiJson(req): ApiJson<ExportRequest>) -> Result<ApiJson<ExportResponse>, ApiError> {
    crate::pool::heavy(move |stop| export_until(&req, stop)).await.map(ApiJson)
}

async fn post_save(ApiJson(req): ApiJson<SaveRequest>) -> Result<ApiJson<ExportResponse>, ApiError> {
    crate::server::blocking(move || save(&req)).await.map(ApiJson)
}

async fn post_load(ApiJson(req): ApiJson<LoadRequest>) -> Result<ApiJson<DesignResponse>, ApiError> {
    crate::server::blocking(move || load(&req)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_servo::{Drive, SplineLaw};

    fn eval_default(samples: usize) -> EvaluateResponse {
        evaluate(&EvaluateRequest { design: ServoDesign::default(), samples }).unwrap()
    }

    #[test]
    fn evaluate_matches_the_servo_library() {
        let r = eval_default(1001);
        let spline = SplineLaw::default_law();
        let drive = Drive::needle_rack_default();
        assert_eq!(r.speeds.len(), 2);
        for s in &r.speeds {
            let lib = summary(spline.law(), &drive, s.summary.speed_rpm).unwrap();
            assert_eq!(s.summary, lib);
            // The sampled curve never exceeds the exact peak and comes close to it.
            let pk = s.torque_nm.iter().fold(0.0f64, |m, t| m.max(t.abs()));
            assert!(pk <= lib.peak_torque_nm * (1.0 + 1e-9) && pk > 0.98 * lib.peak_torque_nm, "{pk} {lib:?}");
            assert_eq!(s.angle_deg.len(), 1001);
            assert_eq!(*s.angle_deg.last().unwrap(), 360.0);
        }
        // The spline passes through the definition points: f(X_j) = Y_j.
        for &[x, y] in &r.points {
            let i = (x * 1000.0).round() as usize;
            if (r.spline.x[i] - x).abs() < 1e-12 {
                assert!((r.spline.f[i] - y).abs() < 1e-9, "f({x}) = {} ≠ {y}", r.spline.f[i]);
            }
            assert!((spline.accel_image(x) - y).abs() < 1e-12);
        }
        // f·scale = a, checked at an independent point through the law.
        let k = spline.law().eval(0.3);
        assert!((spline.accel_image(0.3) * r.scale - k.a).abs() < 1e-9);
    }

    #[test]
    fn moving_a_point_changes_the_torque() {
        let base = eval_default(200);
        let mut d = ServoDesign::default();
        d.points[2][1] = 0.3;
        let moved = evaluate(&EvaluateRequest { design: d, samples: 200 }).unwrap();
        let (a, b) = (base.speeds[0].summary.peak_torque_nm, moved.speeds[0].summary.peak_torque_nm);
        assert!((a - b).abs() > 1e-3 * a, "{a} {b}");
    }

    #[test]
    fn bad_requests_name_the_field() {
        let e = evaluate(&EvaluateRequest { design: ServoDesign::default(), samples: 10_000_000 }).unwrap_err();
        assert_eq!(e.field(), "samples");
        let d = ServoDesign { speeds_rpm: vec![600.0, -5.0], ..Default::default() };
        assert_eq!(evaluate(&EvaluateRequest { design: d, samples: 10 }).unwrap_err().field(), "design.speeds_rpm[1]");
        let mut d = ServoDesign::default();
        d.drive.efficiency = 2.0;
        let e = evaluate(&EvaluateRequest { design: d, samples: 10 }).unwrap_err();
        assert_eq!(e.field(), "design.drive.efficiency");
        assert!(e.to_string().starts_with("design.drive.efficiency = 2 is out of range"), "{e}");
        let req = ExportRequest { design: ServoDesign::default(), format: ExportFormat::Csv, rows: 10_000_000 };
        assert_eq!(export(&req).unwrap_err().field(), "rows");
    }

    /// A set stop flag ends the export (issue 27: `servo/export` ran on after its client left);
    /// an unset one gives the plain export's file.
    #[test]
    fn an_export_stops_when_asked() {
        let req = ExportRequest { design: ServoDesign::default(), format: ExportFormat::Csv, rows: MAX_CAM_ROWS };
        let stop = loomkin_servo::StopFlag::default();
        assert_eq!(export_until(&req, &stop).unwrap().text, export(&req).unwrap().text);
        stop.stop();
        assert!(export_until(&req, &stop).is_err());
    }

    #[test]
    fn exports_read_back() {
        let design = ServoDesign::default();
        let spline = design_spline(&design).unwrap();
        let r = export(&ExportRequest { design: design.clone(), format: ExportFormat::Json, rows: 0 }).unwrap();
        let back = loomkin_servo::read_json(&r.text).unwrap();
        assert_eq!(back.def_points, spline.points());
        let r = export(&ExportRequest { design: design.clone(), format: ExportFormat::Csv, rows: 73 }).unwrap();
        // A 5° step from each joint of the law, and the joints: a header and more than 73 rows.
        assert!(r.text.lines().count() > 74 && r.note.starts_with(&format!("{} rows", r.text.lines().count() - 1)));
        assert!(r.text.starts_with("master_deg,slave_mm,"), "{}", r.text);
        assert_eq!(r.interpolation.len(), 3);
        // Position at 0° and 360° (start dwell) is 0, at the end of the rise the stroke.
        let cells: Vec<f64> = r.text.lines().nth(1).unwrap().split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(cells[..2], [0.0, 0.0]);
        let r = export(&ExportRequest { design, format: ExportFormat::Coeffs, rows: 0 }).unwrap();
        // One interval per pair of points on each half of the rise.
        assert_eq!(loomkin_servo::read_coeffs_text(&r.text).unwrap().len(), 2 * (spline.points().len() - 1));
    }

    #[test]
    fn save_then_load_gives_the_same_design() {
        let mut design = ServoDesign::default();
        design.points[1] = [0.07, 0.41];
        for format in [DesignFormat::Json, DesignFormat::Toml] {
            let saved = save(&SaveRequest { design: design.clone(), format }).unwrap();
            let loaded = load(&LoadRequest { text: saved.text, format: DesignFormat::Auto }).unwrap();
            assert_eq!(loaded.design, design);
        }
    }
}
