//! # loomkin-web — the local workbench
//!
//! `loomkin serve` runs this crate: a page of HTML, CSS and JavaScript embedded in the binary and
//! a JSON API behind it, on 127.0.0.1 only. The page draws its charts itself on `<canvas>`.
//!
//! The API is an ordinary [`axum::Router`]; every answer is JSON, every refusal a 4xx with
//! `{"error": "...", "field": "..."}` naming the offending field. Bodies are limited to
//! [`MAX_BODY_BYTES`], sample counts to [`MAX_SAMPLES`].
//!
//! The computations behind each endpoint are plain functions, usable without a server:
//!
//! ```
//! use loomkin_web::{CompareRequest, compare, parse_json};
//!
//! let req: CompareRequest = parse_json(br#"{"laws": [{"name": "cycloidal"}], "samples": 5}"#)?;
//! let answer = compare(&req)?;
//! let law = &answer.laws[0];
//! assert!((law.metrics.cv - 2.0).abs() < 1e-12);      // cycloidal: Cv = 2
//! assert_eq!(law.samples.s, law.samples.s.iter().map(|s| s.clamp(0.0, 1.0)).collect::<Vec<_>>());
//! assert_eq!(law.samples.x, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
//! # Ok::<(), loomkin_web::ApiError>(())
//! ```
//!
//! Serving (what `loomkin serve` does):
//!
//! ```no_run
//! # async fn f() -> std::io::Result<()> {
//! let bound = loomkin_web::bind(8080).await?;   // 127.0.0.1:8080; 0 picks a free port
//! println!("loomkin workbench at {}", bound.url());
//! bound.run().await                              // until Ctrl-C
//! # }
//! ```
#![deny(missing_docs)]

mod assets;
mod cam_api;
mod catalogue;
mod dobby_api;
mod drive_api;
mod dynamics_api;
mod error;
mod eshed_api;
mod insertion_api;
mod json;
mod limits;
mod loom_api;
mod picking_api;
mod pool;
mod schema;
mod series;
mod server;
mod servo_api;
mod servo_design;
mod shed_api;

pub use assets::{APP_JS, CAM_JS, CHARTS_JS, DRIVE_JS, ESHED_JS, INDEX_HTML, INSERTION_JS, LOOM_JS, STYLE_CSS};
pub use cam_api::{
    CAM_EXAMPLES, CamDesignRequest, CamDxfRequest, CamExamples, CamFile, CamLaw, CamProfileRequest, CamProfileResponse,
    CamReport, CamSource, CamTableRequest, CamTableResponse, ClosureKind, FollowerKind, MIN_WEB_TOLERANCE, ShedSource,
    cam_dxf, cam_profile, cam_table,
};
pub use catalogue::{
    CatalogueItem, CatalogueResponse, CompareRequest, CompareResponse, ComparedLaw, LawChoice, ParamValue, catalogue,
    compare,
};
pub use dobby_api::{
    DobbyCurves, DobbyExportFormat, DobbyExportRequest, DobbyExportResponse, DobbyLaw, DobbyRequest, DobbyResponse,
    MAX_DOBBY_ROWS, dobby_export, dobby_synthesize,
};
pub use drive_api::{
    DEFAULT_DRIVE_SWEEP, DriveCurves, DriveRequest, DriveResponse, MAX_DRIVE_POINTS, MAX_DRIVE_SWEEP, MAX_SIDE_ANGLES,
    MIN_DRIVE_SWEEP, RippleSweep, SideAnimation, SleyPath, evaluate as drive_evaluate,
};
pub use dynamics_api::{
    DynamicsCurves, DynamicsRequest, DynamicsResponse, EXAMPLE_CYCLE, Example, LawCycle, MAX_SWEEP_POINTS,
    MIN_SWEEP_POINTS, SweepCurves, SweepRequest, respond as dynamics_response,
};
pub use error::{ApiError, check_count};
pub use eshed_api::{
    LiftGrid, MAX_SERVO_SHED_POINTS, SERVO_SHED_EXAMPLE, ServoShedCurves, ServoShedRequest, ServoShedResult,
    ServoShedView, loom_servo, loom_servo_view,
};
pub use insertion_api::{
    AirjetRequest, BudgetOverrides, BudgetRequest, CarrierCheck, CarrierRequest, ClearanceCurve, INSERTION_EXAMPLES,
    InsertRequest, InsertResponse, TimingCurves as InsertTiming, TrackCurve, insert_airjet, insert_budget,
    insert_evaluate, insert_projectile, insert_rapier,
};
pub use json::{ApiJson, parse_json, parse_toml};
pub use limits::{
    DEFAULT_CAM_ROWS, DEFAULT_CYCLE_SAMPLES, DEFAULT_PICK_SAMPLES, DEFAULT_SAMPLES, MAX_BODY_BYTES, MAX_CAM_ROWS,
    MAX_COMPARE, MAX_DEF_POINTS, MAX_SAMPLES, MAX_SPEEDS, MIN_CAM_ROWS, MIN_SAMPLES,
};
pub use loom_api::{
    LOOM_EXAMPLES, LoomExamples, LoomRequest, LoomResponse, MAX_TIMING_PICKS, MAX_WEB_PICKS, ObjectiveKind,
    PATTERN_EXAMPLES, PatternGrid, PatternSource, StaggerRequest, StaggerResponse, TorqueCurve,
    evaluate as loom_evaluate, stagger as loom_stagger,
};
pub use picking_api::{
    PickingCurves, PickingRequest, PickingResponse, SettingInfo, SettingsInfo, settings_info, simulate as simulate_pick,
};
pub use pool::{HEAVY_BUDGET, RETRY_AFTER_S, heavy_slots};
pub use schema::{ApiSchema, RouteSchema, SCHEMA_DIALECT, UnitScale, api_schema, request_schema, unit_scales};
pub use series::{LawSamples, finite};
pub use server::{
    BODY_READ_TIMEOUT, Bound, DEFAULT_PORT, HEADER_READ_TIMEOUT, Info, Limits, MAX_CONNECTIONS, bind, info_value,
    open_browser, router, serve_blocking,
};
pub use servo_api::{
    DesignResponse, EvaluateRequest, EvaluateResponse, ExportFormat, ExportRequest, ExportResponse, LawReport,
    LoadRequest, OptimizeRequest, OptimizeResponse, SaveRequest, SpeedReport, SplineSamples, TorquePair, evaluate,
    export, load, optimize_design, save,
};
pub use servo_design::{DesignFormat, ServoDesign, servo_error};
pub use shed_api::{
    MAX_MOTIONS, MAX_SHED_POINTS, MAX_SHED_ROWS, ParetoRequest, ParetoResponse, ShedCloud, ShedConditions,
    ShedLawRequest, ShedLawResponse, shed_law, shed_pareto,
};

/// The views this build serves, in tab order.
pub const VIEWS: &[&str] =
    &["servo", "catalogue", "shed", "picking", "dobby", "dynamics", "cam", "loom", "drive", "insertion", "eshed"];
