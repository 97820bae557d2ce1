//! `GET /api/schema`: the JSON Schema (2020-12) of every request the API checks, generated from
//! the request types — their serde attributes (required keys, defaults, enumerations, unknown keys
//! refused) and the library ranges their fields carry (`minimum`, `exclusiveMinimum`, …, with the
//! unit as `x-unit`) — with an example request of each route. The page builds its fields' limits
//! from it; docs/design/schema.md says how.

use crate::{ApiJson, ServoDesign};
use crate::{
    CamDxfRequest, CamProfileRequest, CamTableRequest, CompareRequest, DobbyExportRequest, DobbyRequest,
    DynamicsRequest, EvaluateRequest, ExportRequest, LoadRequest, LoomRequest, OptimizeRequest, ParetoRequest,
    PickingRequest, SaveRequest, ShedLawRequest, StaggerRequest,
};
use axum::Router;
use axum::routing::get;
use loomkin_picking::{Mechanism, Setting, Settings};
use loomkin_units::schema::apply_bounds;
use schemars::generate::SchemaSettings;
use schemars::{JsonSchema, Schema, SchemaGenerator};
use serde::Serialize;
use serde_json::{Value, json};
use std::collections::BTreeMap;

pub(crate) fn routes() -> Router {
    Router::new().route("/schema", get(|| async { ApiJson(api_schema()) }))
}

/// One route's request: its schema and an example the route accepts.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct RouteSchema {
    /// The method (`POST`).
    pub method: &'static str,
    /// JSON Schema of the request body, with its own `$defs`.
    pub request: Schema,
    /// A request the route answers with 200.
    pub example: Value,
}

/// `GET /api/schema` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ApiSchema {
    /// The JSON Schema dialect of every request schema.
    pub dialect: &'static str,
    /// Every route that takes a request body, by path (`/api/cam/profile`).
    pub routes: BTreeMap<&'static str, RouteSchema>,
    /// The units a front end shows a quantity in other than the unit the API speaks, by name
    /// (`mm`): how many of them make one of the API's unit ([`unit_scales`]).
    pub units: BTreeMap<&'static str, UnitScale>,
}

/// A display unit as a multiple of the unit a request or an answer speaks: `factor` of it make
/// one `of` (1000 mm make one m). The page converts with these, never with a number of its own.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct UnitScale {
    /// The unit of the API (`m`, `s`).
    pub of: &'static str,
    /// How many of the display unit make one of `of`.
    pub factor: f64,
}

/// The display units the page converts to and from, with their factors from `loomkin_units`
/// (`mm_from_m`, `ms_from_s`): the one place a factor lives.
pub fn unit_scales() -> BTreeMap<&'static str, UnitScale> {
    BTreeMap::from([
        ("mm", UnitScale { of: "m", factor: loomkin_units::mm_from_m(1.0) }),
        ("ms", UnitScale { of: "s", factor: loomkin_units::ms_from_s(1.0) }),
    ])
}

/// The JSON Schema dialect the request schemas are written in.
pub const SCHEMA_DIALECT: &str = "https://json-schema.org/draft/2020-12/schema";

/// The request schema of `T`, with its own `$defs`.
pub fn request_schema<T: JsonSchema>() -> Schema {
    SchemaSettings::draft2020_12().into_generator().into_root_schema_for::<T>()
}

fn post<T: JsonSchema>(example: Value) -> RouteSchema {
    RouteSchema { method: "POST", request: request_schema::<T>(), example }
}

/// The schema of every request and an example of each (answer of `GET /api/schema`).
pub fn api_schema() -> ApiSchema {
    let design = serde_json::to_value(ServoDesign::default()).unwrap_or(Value::Null);
    let dobby = serde_json::to_value(DobbyRequest::default()).unwrap_or(Value::Null);
    let example = crate::dynamics_api::example();
    let routes = BTreeMap::from([
        ("/api/laws/compare", post::<CompareRequest>(json!({"laws": [{"name": "cycloidal"}]}))),
        ("/api/servo/evaluate", post::<EvaluateRequest>(json!({"design": design}))),
        ("/api/servo/optimize", post::<OptimizeRequest>(json!({"design": design}))),
        ("/api/servo/export", post::<ExportRequest>(json!({"design": design, "format": "csv"}))),
        ("/api/servo/design/save", post::<SaveRequest>(json!({"design": design}))),
        (
            "/api/servo/design/load",
            post::<LoadRequest>(json!({"text": serde_json::to_string(&design).unwrap_or_default()})),
        ),
        ("/api/picking/simulate", post::<PickingRequest>(json!({"settings": {"play_mm": 15.5}}))),
        (
            "/api/shed/pareto",
            post::<ParetoRequest>(json!({"family": "trapezoid", "step": 0.05, "motions_deg": [240, 300]})),
        ),
        (
            "/api/shed/law",
            post::<ShedLawRequest>(json!({"family": "trapezoid", "lengths": [0.25, 0.5, 0.25], "motion_deg": 300})),
        ),
        ("/api/dobby/synthesize", post::<DobbyRequest>(dobby.clone())),
        ("/api/dobby/export", post::<DobbyExportRequest>(json!({"request": dobby, "format": "csv"}))),
        ("/api/cam/profile", post::<CamProfileRequest>(json!({"design": {"roller_radius_mm": 15}}))),
        ("/api/cam/dxf", post::<CamDxfRequest>(json!({"design": {"roller_radius_mm": 15}}))),
        ("/api/cam/table", post::<CamTableRequest>(json!({"format": "csv"}))),
        (
            "/api/dynamics/response",
            post::<DynamicsRequest>(json!({
                "speed_rpm": example.speed_rpm, "natural_hz": example.natural_hz, "damping_ratio": example.damping_ratio
            })),
        ),
        ("/api/loom/evaluate", post::<LoomRequest>(json!({}))),
        ("/api/loom/stagger", post::<StaggerRequest>(json!({}))),
        ("/api/drive/evaluate", post::<crate::DriveRequest>(json!({"sweep_points": 5}))),
        (
            "/api/insert/budget",
            post::<crate::BudgetRequest>(
                json!({"reed_width_mm": 1900, "carrier_length_mm": 100, "window_deg": 220, "speed_m_s": 20}),
            ),
        ),
        ("/api/insert/rapier", post::<crate::CarrierRequest>(json!({}))),
        ("/api/insert/projectile", post::<crate::CarrierRequest>(json!({}))),
        ("/api/insert/airjet", post::<crate::AirjetRequest>(json!({}))),
        ("/api/insert/evaluate", post::<crate::InsertRequest>(json!({}))),
        ("/api/loom/servo", post::<crate::ServoShedRequest>(json!({}))),
        ("/api/loom/servo/view", post::<crate::ServoShedRequest>(json!({}))),
    ]);
    ApiSchema { dialect: SCHEMA_DIALECT, routes, units: unit_scales() }
}

/// A count's bounds as a schemars transform (`#[schemars(transform = count(1, MAX))]`): the
/// request's own limits on how much it may ask for.
pub(crate) fn count(min: usize, max: usize) -> impl FnMut(&mut Schema) {
    move |schema: &mut Schema| {
        schema.insert("minimum".into(), min.into());
        schema.insert("maximum".into(), max.into());
    }
}

/// The schema of [`crate::PickingRequest::settings`]: one optional number per setting, bounded by
/// the library's [`Setting::range`] on the paper's mechanism, defaulting to its designed value.
pub(crate) fn picking_settings(_: &mut SchemaGenerator) -> Schema {
    let mech = Mechanism::paper_default();
    let designed = Settings::designed(&mech);
    let mut properties = serde_json::Map::new();
    for s in Setting::ALL {
        let mut p = Schema::default();
        p.insert("type".into(), "number".into());
        p.insert("description".into(), s.description().into());
        p.insert("default".into(), s.value(&designed).into());
        apply_bounds(&mut p, &s.range(&mech));
        properties.insert(s.key(), p.into());
    }
    let mut schema = Schema::default();
    schema.insert("type".into(), "object".into());
    schema.insert("properties".into(), properties.into());
    schema.insert("additionalProperties".into(), false.into());
    schema
}
