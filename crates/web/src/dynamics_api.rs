//! The dynamics view: a cycle (the example heald-frame cycle, a catalogue law as rise–dwell–return–
//! dwell, or a cycle file the user loads) driving an elastic frame (f_n, ζ) at a speed set with a
//! slider — the dwell vibration drawn live — and the speed sweep beside it.

use crate::catalogue::LawChoice;
use crate::error::check_count;
use crate::limits::{DEFAULT_CYCLE_SAMPLES, MAX_SAMPLES, MIN_SAMPLES};
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::{get, post};
use loomkin_dynamics::{Follower, Response, ResponseReport, Start, Units, sweep};
use loomkin_laws::{Cycle, CycleSpec, SegmentKind, StrokeUnit};
use loomkin_units::ShaftSpeed;
use serde::{Deserialize, Serialize};

/// The cycle the view opens with (`examples/heald-frame-cycle.toml`).
pub const EXAMPLE_CYCLE: &str = include_str!("../../../examples/heald-frame-cycle.toml");

/// Most speeds of one sweep.
pub const MAX_SWEEP_POINTS: usize = 2000;

/// Fewest speeds of a sweep: its two ends.
pub const MIN_SWEEP_POINTS: usize = 2;

pub(crate) fn routes() -> Router {
    Router::new()
        .route("/dynamics/example", get(|| async { ApiJson(example()) }))
        .route("/dynamics/response", post(post_response))
}

/// `GET /api/dynamics/example`: the view's starting point.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Example {
    /// The example cycle file's text.
    pub cycle_toml: &'static str,
    /// A heald frame's natural frequency (Hz): an optimised carbon-fibre frame reaches about 54 Hz.
    pub natural_hz: f64,
    /// Damping ratio.
    pub damping_ratio: f64,
    /// Main-shaft speed (rpm).
    pub speed_rpm: f64,
}

/// The view's defaults.
pub fn example() -> Example {
    Example { cycle_toml: EXAMPLE_CYCLE, natural_hz: 54.0, damping_ratio: 0.05, speed_rpm: 300.0 }
}

/// A catalogue law as a rise–dwell–return–dwell cycle over one turn.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LawCycle {
    /// The law of the rise and of the return.
    pub law: LawChoice,
    /// Stroke (mm).
    #[schemars(transform = loomkin_units::schema::bounds(StrokeUnit::Mm.stroke_range()))]
    pub stroke_mm: f64,
    /// Motion angle of the rise and of the return (deg, ≤ 180); the dwells fill the turn.
    #[schemars(transform = loomkin_units::schema::bounds(CycleSpec::RISE_RETURN_MOTION_DEG))]
    pub motion_deg: f64,
}

/// Speeds of the sweep.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SweepRequest {
    /// Lowest speed (rpm).
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::RANGE))]
    pub from_rpm: f64,
    /// Highest speed (rpm).
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::RANGE))]
    pub to_rpm: f64,
    /// Number of speeds, [`MIN_SWEEP_POINTS`] … [`MAX_SWEEP_POINTS`].
    #[schemars(transform = crate::schema::count(MIN_SWEEP_POINTS, MAX_SWEEP_POINTS))]
    pub points: usize,
}

/// `POST /api/dynamics/response` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DynamicsRequest {
    /// A cycle file's text; with neither this nor `law`, the example cycle.
    #[serde(default)]
    pub cycle_toml: Option<String>,
    /// A catalogue law as rise–dwell–return–dwell (instead of `cycle_toml`).
    #[serde(default)]
    pub law: Option<LawCycle>,
    /// Main-shaft speed (rpm).
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::RANGE))]
    pub speed_rpm: f64,
    /// Natural frequency of the frame on its drive (Hz).
    #[schemars(transform = loomkin_units::schema::bounds(Follower::NATURAL_HZ.range))]
    pub natural_hz: f64,
    /// Damping ratio ζ, 0 ≤ ζ < 1.
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(Follower::DAMPING_RATIO.range))]
    pub damping_ratio: f64,
    /// The periodic steady state instead of one cycle from rest.
    #[serde(default)]
    pub steady: bool,
    /// Samples over the cycle, [`MIN_SAMPLES`] … [`MAX_SAMPLES`] (default 721: every half degree).
    #[serde(default = "default_samples")]
    #[schemars(transform = crate::schema::count(MIN_SAMPLES, MAX_SAMPLES))]
    pub samples: usize,
    /// A speed sweep to compute as well.
    #[serde(default)]
    pub sweep: Option<SweepRequest>,
}

fn default_samples() -> usize {
    DEFAULT_CYCLE_SAMPLES
}

/// The response over the cycle in the cycle's units.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct DynamicsCurves {
    /// Main-shaft angle (deg).
    pub angle_deg: Vec<f64>,
    /// Input (rigid-body law) s, in [`DynamicsResponse::unit`].
    pub s: Vec<f64>,
    /// Follower (frame) x.
    pub x: Vec<f64>,
    /// Dynamic error x − s.
    pub error: Vec<f64>,
    /// Follower acceleration x'' (m/s² or rad/s²).
    pub a: Vec<f64>,
}

/// The sweep's curves.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct SweepCurves {
    /// Speeds (rpm).
    pub speed_rpm: Vec<f64>,
    /// Largest residual amplitude over the dwells, in [`DynamicsResponse::unit`].
    pub residual_amplitude: Vec<f64>,
    /// Largest |x − s|.
    pub peak_dynamic_error: Vec<f64>,
}

/// `POST /api/dynamics/response` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct DynamicsResponse {
    /// The figures, with the same keys as `loomkin dyn response --json`.
    pub report: ResponseReport,
    /// Position unit of the curves (`mm` or `deg`).
    pub unit: &'static str,
    /// Acceleration unit (`m/s²` or `rad/s²`).
    pub acceleration_unit: &'static str,
    /// Dwells as `[from_deg, to_deg]` (shaded in the charts).
    pub dwells_deg: Vec<[f64; 2]>,
    /// The response over the cycle.
    pub curves: DynamicsCurves,
    /// The sweep, when asked for.
    pub sweep: Option<SweepCurves>,
}

fn cycle_of(req: &DynamicsRequest) -> Result<Cycle, ApiError> {
    match (&req.cycle_toml, &req.law) {
        (Some(_), Some(_)) => {
            Err(ApiError::BadJson { field: "law".into(), message: "give either cycle_toml or law, not both".into() })
        }
        (Some(text), None) => Cycle::from_toml(text).map_err(|e| ApiError::invalid("cycle_toml", e)),
        (None, Some(lc)) => {
            let spec = lc.law.spec().map_err(|e| ApiError::invalid("law.law", e))?;
            StrokeUnit::Mm.stroke_range().check("law.stroke_mm", lc.stroke_mm)?;
            let spec = CycleSpec::rise_return(&spec, StrokeUnit::Mm, lc.stroke_mm, lc.motion_deg)
                .map_err(|e| ApiError::invalid("law.motion_deg", e))?;
            Cycle::new(&spec).map_err(|e| ApiError::invalid("law", e))
        }
        (None, None) => Cycle::from_toml(EXAMPLE_CYCLE).map_err(|e| ApiError::Internal(e.to_string())),
    }
}

/// Computes the response (and the sweep) for one request.
pub fn respond(req: &DynamicsRequest) -> Result<DynamicsResponse, ApiError> {
    let n = check_count("samples", req.samples, MIN_SAMPLES, MAX_SAMPLES)?;
    let cycle = cycle_of(req)?;
    let speed = ShaftSpeed::from_rpm(req.speed_rpm).map_err(|e| ApiError::from_library(&e, "speed_rpm"))?;
    let follower =
        Follower::new(req.natural_hz, req.damping_ratio).map_err(|e| ApiError::from_library(&e, "natural_hz"))?;
    let start = if req.steady { Start::Steady } else { Start::Rest };
    let r = Response::new(&cycle, speed, &follower, start, 1).map_err(|e| ApiError::from_library(&e, "speed_rpm"))?;
    let units = Units::of(cycle.unit);
    let mut curves = DynamicsCurves::default();
    for p in r.samples(n) {
        curves.angle_deg.push(finite(p[0]));
        curves.s.push(finite(p[1] * units.scale));
        curves.x.push(finite(p[2] * units.scale));
        curves.error.push(finite(p[3] * units.scale));
        curves.a.push(finite(p[4]));
    }
    let sweep = match &req.sweep {
        None => None,
        Some(sw) => {
            let m = check_count("sweep.points", sw.points, MIN_SWEEP_POINTS, MAX_SWEEP_POINTS)?;
            ShaftSpeed::RANGE.check("sweep.from_rpm", sw.from_rpm)?;
            ShaftSpeed::RANGE.check("sweep.to_rpm", sw.to_rpm)?;
            if sw.to_rpm <= sw.from_rpm {
                return Err(ApiError::BadJson {
                    field: "sweep.to_rpm".into(),
                    message: format!(
                        "sweep.to_rpm = {} must be above sweep.from_rpm = {}",
                        loomkin_units::compact(sw.to_rpm),
                        loomkin_units::compact(sw.from_rpm)
                    ),
                });
            }
            let step = (sw.to_rpm - sw.from_rpm) / (m - 1) as f64;
            let speeds: Vec<f64> =
                (0..m).map(|i| if i + 1 == m { sw.to_rpm } else { sw.from_rpm + step * i as f64 }).collect();
            let pts = sweep(&cycle, &follower, &speeds, start).map_err(|e| ApiError::from_library(&e, "sweep"))?;
            Some(SweepCurves {
                speed_rpm: speeds,
                residual_amplitude: pts.iter().map(|q| finite(q.residual_amplitude_si * units.scale)).collect(),
                peak_dynamic_error: pts.iter().map(|q| finite(q.peak_dynamic_error_si * units.scale)).collect(),
            })
        }
    };
    let dwells_deg = cycle
        .segments
        .iter()
        .filter(|s| s.kind == SegmentKind::Dwell)
        .map(|s| [s.start_rad.to_degrees(), (s.start_rad + s.length_rad).to_degrees()])
        .collect();
    let report = ResponseReport {
        summary: r.summary(),
        units,
        speed_rpm: speed.rpm(),
        natural_hz: follower.natural_hz(),
        damping_ratio: follower.damping_ratio(),
        start,
        cycles: 1,
    };
    Ok(DynamicsResponse { report, unit: units.pos, acceleration_unit: units.acc_text(), dwells_deg, curves, sweep })
}

async fn post_response(ApiJson(req): ApiJson<DynamicsRequest>) -> Result<ApiJson<DynamicsResponse>, ApiError> {
    crate::server::blocking(move || respond(&req)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request() -> DynamicsRequest {
        DynamicsRequest {
            cycle_toml: None,
            law: None,
            speed_rpm: 600.0,
            natural_hz: 54.0,
            damping_ratio: 0.05,
            steady: false,
            samples: 361,
            sweep: Some(SweepRequest { from_rpm: 300.0, to_rpm: 900.0, points: 61 }),
        }
    }

    /// The view shows what the CLI computes: the same response, the same keys, the sweep's point at
    /// the current speed equal to the response's own figure.
    #[test]
    fn the_view_answers_what_the_library_computes() {
        let r = respond(&request()).unwrap();
        let cycle = Cycle::from_toml(EXAMPLE_CYCLE).unwrap();
        let f = Follower::new(54.0, 0.05).unwrap();
        let direct = Response::new(&cycle, ShaftSpeed::from_rpm(600.0).unwrap(), &f, Start::Rest, 1).unwrap().summary();
        let v = serde_json::to_value(&r.report).unwrap();
        assert_eq!(v["residual_amplitude_mm"].as_f64().unwrap(), direct.residual_amplitude_si * 1e3);
        assert_eq!(r.curves.angle_deg.len(), 361);
        let want = [[0.0, 60.0], [180.0, 240.0]];
        assert_eq!(r.dwells_deg.len(), 2);
        for (got, want) in r.dwells_deg.iter().zip(want) {
            assert!((got[0] - want[0]).abs() < 1e-9 && (got[1] - want[1]).abs() < 1e-9, "{got:?}");
        }
        // x − s in the curves is the error column.
        for i in 0..361 {
            assert!((r.curves.x[i] - r.curves.s[i] - r.curves.error[i]).abs() < 1e-9);
        }
        let sw = r.sweep.unwrap();
        let i = sw.speed_rpm.iter().position(|&s| (s - 600.0).abs() < 1e-9).unwrap();
        assert!((sw.residual_amplitude[i] - direct.residual_amplitude_si * 1e3).abs() < 1e-12);
    }

    #[test]
    fn a_law_cycle_and_bad_inputs_are_named() {
        let mut q = request();
        q.law = Some(LawCycle {
            law: LawChoice { name: "cycloidal".into(), params: Default::default() },
            stroke_mm: 100.0,
            motion_deg: 120.0,
        });
        q.speed_rpm = 600.0;
        q.natural_hz = 60.0;
        q.damping_ratio = 0.0;
        // 600 rpm, 120°: the rise lasts 1/30 s = two natural periods of 60 Hz, where the undamped
        // cycloidal law leaves no residual vibration.
        let r = respond(&q).unwrap();
        assert!(r.report.summary.residual_amplitude_si < 1e-12, "{}", r.report.summary.residual_amplitude_si);
        q.damping_ratio = 1.0;
        assert_eq!(respond(&q).unwrap_err().field(), "damping_ratio");
        let mut q = request();
        q.speed_rpm = 0.0;
        assert_eq!(respond(&q).unwrap_err().field(), "speed_rpm");
        let mut q = request();
        q.cycle_toml = Some("unit = \"mm\"\n[[segment]]\nkind = \"rise\"\nto_deg = 90\nlaw = \"cycloidal\"\n".into());
        assert_eq!(respond(&q).unwrap_err().field(), "cycle_toml");
        let mut q = request();
        q.sweep = Some(SweepRequest { from_rpm: 500.0, to_rpm: 400.0, points: 10 });
        assert_eq!(respond(&q).unwrap_err().field(), "sweep.to_rpm");
    }
}
