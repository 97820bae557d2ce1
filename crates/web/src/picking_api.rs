//! The picking view: the paper's under-pick mechanism run under loom settings set with sliders.

use crate::error::check_count;
use crate::limits::{DEFAULT_PICK_SAMPLES, MAX_SAMPLES, MIN_SAMPLES};
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::{get, post};
use loomkin_picking::{Mechanism, Method, Outcome, PickError, Setting, Settings, history};
use loomkin_units::FieldError;
use serde::{Deserialize, Serialize};

pub(crate) fn routes() -> Router {
    Router::new()
        .route("/picking/settings", get(|| async { ApiJson(settings_info()) }))
        .route("/picking/simulate", post(post_simulate))
}

/// One slider of the picking view.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SettingInfo {
    /// Key in [`PickingRequest::settings`], with its unit (`play_mm`).
    pub key: String,
    /// Human description.
    pub description: &'static str,
    /// Unit of the value.
    pub unit: &'static str,
    /// The range the paper studies (the slider's range).
    pub min: f64,
    /// Upper end of the slider.
    pub max: f64,
    /// The designed value.
    pub designed: f64,
}

/// `GET /api/picking/settings` answer: the sliders of the paper's mechanism.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SettingsInfo {
    /// One per setting, in the paper's order of figures.
    pub settings: Vec<SettingInfo>,
    /// Designed shuttle velocity at the end of the pick (m/s).
    pub design_velocity_m_s: f64,
    /// Designed picking distance (m).
    pub design_distance_m: f64,
}

/// The sliders of the paper's mechanism.
pub fn settings_info() -> SettingsInfo {
    let mech = Mechanism::paper_default();
    let designed = Settings::designed(&mech);
    SettingsInfo {
        settings: Setting::ALL
            .iter()
            .map(|s| {
                let (min, max) = s.paper_range();
                SettingInfo {
                    key: s.key(),
                    description: s.description(),
                    unit: s.unit(),
                    min,
                    max,
                    designed: s.value(&designed),
                }
            })
            .collect(),
        design_velocity_m_s: mech.design().spec.velocity_m_s,
        design_distance_m: mech.design().spec.distance_m,
    }
}

/// `POST /api/picking/simulate` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PickingRequest {
    /// Setting values by key (`speed_rpm`, `play_mm`, `strap_cm`, `shuttle_g`, `checking_kgf`);
    /// a key left out keeps the designed value.
    #[serde(default)]
    #[schemars(schema_with = "crate::schema::picking_settings")]
    pub settings: std::collections::BTreeMap<String, f64>,
    /// `closed` (default: the paper's closed form, corrected) or `ode`.
    #[serde(default)]
    pub method: Method,
    /// Samples over the pick, [`MIN_SAMPLES`] … [`MAX_SAMPLES`] (default [`DEFAULT_PICK_SAMPLES`]).
    #[serde(default = "default_samples")]
    #[schemars(transform = crate::schema::count(MIN_SAMPLES, MAX_SAMPLES))]
    pub samples: usize,
}

fn default_samples() -> usize {
    DEFAULT_PICK_SAMPLES
}

/// Nominal (cam) and actual (shuttle) motion over the pick.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct PickingCurves {
    /// Time from the shuttle's start (ms).
    pub t_ms: Vec<f64>,
    /// Nominal displacement s (mm).
    pub nominal_mm: Vec<f64>,
    /// Shuttle displacement x (mm).
    pub actual_mm: Vec<f64>,
    /// Nominal velocity (m/s).
    pub nominal_v_m_s: Vec<f64>,
    /// Shuttle velocity (m/s).
    pub actual_v_m_s: Vec<f64>,
    /// Nominal acceleration (m/s²).
    pub nominal_a_m_s2: Vec<f64>,
    /// Shuttle acceleration (m/s²).
    pub actual_a_m_s2: Vec<f64>,
}

/// `POST /api/picking/simulate` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PickingResponse {
    /// End-of-pick values (velocity, distance, peak acceleration, what ended the pick, …).
    pub outcome: Outcome,
    /// The curves.
    pub curves: PickingCurves,
}

fn pick_error(e: PickError) -> ApiError {
    let field = match e.field() {
        Some(f) if Setting::ALL.iter().any(|s| s.key() == f) => format!("settings.{f}"),
        _ => "settings".into(),
    };
    ApiError::invalid(field, e)
}

/// Runs the pick under the requested settings.
pub fn simulate(req: &PickingRequest) -> Result<PickingResponse, ApiError> {
    let n = check_count("samples", req.samples, MIN_SAMPLES, MAX_SAMPLES)?;
    let mech = Mechanism::paper_default();
    let mut st = Settings::designed(&mech);
    for (key, &value) in &req.settings {
        let setting = Setting::ALL.iter().find(|s| s.key() == *key).ok_or_else(|| ApiError::BadJson {
            field: format!("settings.{key}"),
            message: "unknown setting: known are speed_rpm, play_mm, strap_cm, shuttle_g, checking_kgf".into(),
        })?;
        // The library checks every setting against its range ([`Setting::range`]).
        st = setting.set(st, value, &mech).map_err(pick_error)?;
    }
    let h = history(&mech, &st, req.method, n).map_err(pick_error)?;
    let s = &h.samples;
    let curves = PickingCurves {
        t_ms: s.iter().map(|p| finite(loomkin_units::ms_from_s(p.t_s))).collect(),
        nominal_mm: s.iter().map(|p| finite(loomkin_units::mm_from_m(p.nominal.s_m))).collect(),
        actual_mm: s.iter().map(|p| finite(loomkin_units::mm_from_m(p.actual.x_m))).collect(),
        nominal_v_m_s: s.iter().map(|p| finite(p.nominal.v_m_s)).collect(),
        actual_v_m_s: s.iter().map(|p| finite(p.actual.v_m_s)).collect(),
        nominal_a_m_s2: s.iter().map(|p| finite(p.nominal.a_m_s2)).collect(),
        actual_a_m_s2: s.iter().map(|p| finite(p.actual.a_m_s2)).collect(),
    };
    Ok(PickingResponse { outcome: h.outcome, curves })
}

async fn post_simulate(ApiJson(req): ApiJson<PickingRequest>) -> Result<ApiJson<PickingResponse>, ApiError> {
    crate::server::blocking(move || simulate(&req)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn designed_setting_gives_the_designed_pick() {
        let info = settings_info();
        assert_eq!(info.settings.len(), 5);
        let r =
            simulate(&PickingRequest { settings: Default::default(), method: Method::Closed, samples: 50 }).unwrap();
        assert!((r.outcome.velocity_m_s - info.design_velocity_m_s).abs() < 1e-9);
        assert!((r.curves.actual_mm.last().unwrap() - info.design_distance_m * 1e3).abs() < 1e-6);
        assert!((r.curves.actual_v_m_s.last().unwrap() - r.outcome.velocity_m_s).abs() < 1e-9);
    }

    #[test]
    fn play_speeds_the_shuttle_up_and_bad_values_are_named() {
        let settings = [("play_mm".to_string(), 15.5)].into_iter().collect();
        let r = simulate(&PickingRequest { settings, method: Method::Closed, samples: 20 }).unwrap();
        assert!((r.outcome.velocity_m_s - 17.0 - 3.88).abs() < 0.05, "{}", r.outcome.velocity_m_s);
        let settings = [("play_mm".to_string(), -3.0)].into_iter().collect();
        let e = simulate(&PickingRequest { settings, method: Method::Closed, samples: 20 }).unwrap_err();
        assert_eq!(e.field(), "settings.play_mm");
        let settings = [("speed".to_string(), 200.0)].into_iter().collect();
        let e = simulate(&PickingRequest { settings, method: Method::Closed, samples: 20 }).unwrap_err();
        assert_eq!(e.field(), "settings.speed");
    }
}
