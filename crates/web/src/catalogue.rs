//! The law catalogue view: list the named laws, compare chosen ones overlaid with their metrics.

use crate::error::check_count;
use crate::limits::{DEFAULT_SAMPLES, MAX_COMPARE, MAX_SAMPLES, MIN_SAMPLES};
use crate::series::LawSamples;
use crate::{ApiError, ApiJson};
use loomkin_laws::{CATALOGUE, LawSpec, Metrics};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One catalogue entry as the page lists it.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CatalogueItem {
    /// Name to send back in [`LawChoice::name`].
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// Parameters as `key=default (range)`, or empty.
    pub params: &'static str,
}

/// `GET /api/laws`: the catalogue.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CatalogueResponse {
    /// Every named law, in catalogue order.
    pub laws: Vec<CatalogueItem>,
}

/// The catalogue (answer of `GET /api/laws`).
pub fn catalogue() -> CatalogueResponse {
    CatalogueResponse {
        laws: CATALOGUE
            .iter()
            .map(|e| CatalogueItem { name: e.name, description: e.description, params: e.params })
            .collect(),
    }
}

pub use loomkin_laws::ParamValue;

/// One law to compare: a catalogue name and its parameters.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LawChoice {
    /// Catalogue name (`cycloidal`, `modified-trapezoid`, …).
    pub name: String,
    /// Parameters, e.g. `{"ramp": 0.125}`.
    #[serde(default)]
    pub params: BTreeMap<String, ParamValue>,
}

impl LawChoice {
    /// The catalogue law with these parameters.
    pub fn spec(&self) -> Result<LawSpec, loomkin_laws::LawError> {
        let params: Vec<(String, String)> = self.params.iter().map(|(k, v)| (k.clone(), v.text())).collect();
        LawSpec::parse(&self.name, &params)
    }
}

/// `POST /api/laws/compare` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CompareRequest {
    /// The laws, 1 … [`MAX_COMPARE`].
    pub laws: Vec<LawChoice>,
    /// Samples per law, [`MIN_SAMPLES`] … [`MAX_SAMPLES`] (default [`DEFAULT_SAMPLES`]).
    #[serde(default = "default_samples")]
    #[schemars(transform = crate::schema::count(MIN_SAMPLES, MAX_SAMPLES))]
    pub samples: usize,
}

fn default_samples() -> usize {
    DEFAULT_SAMPLES
}

/// One compared law.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ComparedLaw {
    /// Catalogue name.
    pub name: &'static str,
    /// Name with parameters.
    pub label: String,
    /// Exact characteristic values (Cv, Ca, Cj, Cm, Ca,rms and where they occur).
    pub metrics: Metrics,
    /// Smoothness class in a dwell-rise-dwell cycle (2 = continuous acceleration).
    pub continuity_class: i32,
    /// The sampled curves.
    pub samples: LawSamples,
}

/// `POST /api/laws/compare` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CompareResponse {
    /// The laws, in request order.
    pub laws: Vec<ComparedLaw>,
}

/// Builds, measures and samples the chosen laws.
pub fn compare(req: &CompareRequest) -> Result<CompareResponse, ApiError> {
    check_count("laws", req.laws.len(), 1, MAX_COMPARE)?;
    check_count("samples", req.samples, MIN_SAMPLES, MAX_SAMPLES)?;
    let mut laws = Vec::with_capacity(req.laws.len());
    for (i, choice) in req.laws.iter().enumerate() {
        let spec = choice.spec().map_err(|e| ApiError::invalid(format!("laws[{i}]"), e))?;
        let law = spec.build().map_err(|e| ApiError::invalid(format!("laws[{i}]"), e))?;
        laws.push(ComparedLaw {
            name: spec.name(),
            label: spec.label(),
            metrics: law.metrics(),
            continuity_class: law.continuity().class,
            samples: LawSamples::of(&law, req.samples),
        });
    }
    Ok(CompareResponse { laws })
}

pub(crate) async fn get_catalogue() -> ApiJson<CatalogueResponse> {
    ApiJson(catalogue())
}

pub(crate) async fn post_compare(ApiJson(req): ApiJson<CompareRequest>) -> Result<ApiJson<CompareResponse>, ApiError> {
    crate::server::blocking(move || compare(&req)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(json: &str) -> CompareRequest {
        crate::json::parse_json(json.as_bytes()).unwrap()
    }

    #[test]
    fn compares_with_exact_metrics() {
        let r = compare(&req(r#"{"laws":[{"name":"cycloidal"},{"name":"modified-trapezoid","params":{"ramp":0.125}}],
            "samples": 101}"#))
        .unwrap();
        assert_eq!(r.laws.len(), 2);
        assert!((r.laws[0].metrics.ca - 2.0 * std::f64::consts::PI).abs() < 1e-9);
        assert_eq!(r.laws[1].label, "modified-trapezoid (ramp=0.125)");
        assert_eq!(r.laws[1].samples.a.len(), 101);
        // Peak of the sampled acceleration never exceeds the exact Ca.
        let amax = r.laws[1].samples.a.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        assert!(amax <= r.laws[1].metrics.ca + 1e-9 && amax > 0.95 * r.laws[1].metrics.ca);
    }

    #[test]
    fn refuses_bad_requests_naming_the_field() {
        let e = compare(&req(r#"{"laws":[{"name":"cycloidal"}],"samples":100000000}"#)).unwrap_err();
        assert_eq!(e.field(), "samples");
        let e = compare(&req(r#"{"laws":[{"name":"nope"}]}"#)).unwrap_err();
        assert_eq!(e.field(), "laws[0]");
        assert!(e.to_string().contains("unknown law"));
        let e = compare(&req(r#"{"laws":[{"name":"modified-trapezoid","params":{"ramp":0.7}}]}"#)).unwrap_err();
        assert!(e.to_string().contains("ramp"));
        let e = compare(&req(r#"{"laws":[]}"#)).unwrap_err();
        assert_eq!(e.field(), "laws");
    }
}
