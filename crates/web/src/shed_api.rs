//! The shedding view: a family of heald-frame laws on a grid of relative lengths, its Pareto front
//! (largest weft-crossing window, least peak acceleration), and one chosen law over the cycle.

use crate::error::check_count;
use crate::limits::{DEFAULT_CYCLE_SAMPLES, MAX_SAMPLES, MIN_SAMPLES};
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::post;
use loomkin_shed::{
    Candidate, Conditions, Criteria, DesignKind, Family, GridSpec, JERK_LIMIT_RANGE, MOTION_DEG, Progress, ShedError,
    Study, cycle_accel_jumps, cycle_curve, evaluate, pareto_within, table, within_jerk_limit,
};
use loomkin_units::{FieldError, ShaftSpeed, StopFlag};
use serde::{Deserialize, Serialize};

/// Most laws (grid rows) one Pareto request may evaluate.
pub const MAX_SHED_ROWS: usize = 20_000;
/// Most (law, motion angle) points one Pareto answer may carry.
pub const MAX_SHED_POINTS: usize = 120_000;
/// Most motion angles per request.
pub const MAX_MOTIONS: usize = 12;

pub(crate) fn routes() -> Router {
    Router::new().route("/shed/pareto", post(post_pareto)).route("/shed/law", post(post_law))
}

/// Evaluation conditions shared by both shedding requests.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShedConditions {
    /// Dwell threshold T (fraction of the stroke), [`loomkin_shed::THRESHOLD_RANGE`] (default:
    /// the library's [`Conditions::default`], 0.95).
    #[serde(default = "default_threshold")]
    #[schemars(transform = loomkin_units::schema::bounds(Conditions::THRESHOLD))]
    pub threshold: f64,
    /// Frame stroke h (m), default the library's (0.1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = loomkin_units::schema::bounds(Conditions::STROKE_M))]
    pub stroke_m: Option<f64>,
    /// The same in mm, the unit of `loomkin shed … --stroke-mm` and of the page (give one of the two).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(transform = loomkin_units::schema::bounds_in_unit(Conditions::STROKE_M, loomkin_units::MM_PER_M, "mm"))]
    pub stroke_mm: Option<f64>,
    /// Main-shaft speed n (1/min), default the library's (300).
    #[serde(default = "default_speed")]
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::RANGE))]
    pub speed_rpm: f64,
}

fn default_threshold() -> f64 {
    Conditions::default().threshold()
}
fn default_speed() -> f64 {
    Conditions::default().speed_rpm()
}

impl Default for ShedConditions {
    fn default() -> Self {
        Self { threshold: default_threshold(), stroke_m: None, stroke_mm: None, speed_rpm: default_speed() }
    }
}

impl ShedConditions {
    fn build(&self) -> Result<Conditions, ApiError> {
        // The library checks each value against its one range; the field goes under `conditions.`
        // (a stroke given in mm is named and bounded in mm).
        let stroke_m = match (self.stroke_m, self.stroke_mm) {
            (Some(_), Some(_)) => {
                return Err(ApiError::invalid(
                    "conditions.stroke_mm",
                    "give the stroke as stroke_m or as stroke_mm, not both",
                ));
            }
            (Some(m), None) => m,
            (None, Some(mm)) => loomkin_units::m_from_mm(mm),
            (None, None) => Conditions::default().stroke_m(),
        };
        Conditions::new(self.threshold, stroke_m, self.speed_rpm)
            .map_err(|e| match e {
                ShedError::Range(r) if r.field == "stroke_m" && self.stroke_mm.is_some() => {
                    ShedError::Range(r.in_unit("stroke_mm", loomkin_units::MM_PER_M, "mm"))
                }
                e => e,
            })
            .map_err(|e| ApiError::from_library(&e, "threshold").within("conditions"))
    }
}

/// Maps an error of the shedding crate to the request field: the library's `positive` /
/// `negative` phase is built from the request's `lengths`.
fn shed_error(default_field: &str, e: ShedError) -> ApiError {
    if let ShedError::Stopped(s) = e {
        // The pool words the refusal of a stopped computation; this names no input.
        return ApiError::invalid("body", s);
    }
    let field = e.field().unwrap_or(default_field).to_string();
    if field.starts_with("positive") || field.starts_with("negative") {
        let text = e.to_string();
        let reason = text.strip_prefix(&format!("{field}: ")).unwrap_or(&text);
        return ApiError::invalid("lengths", format!("lengths: {reason}"));
    }
    ApiError::invalid(field, e)
}

/// `POST /api/shed/pareto` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ParetoRequest {
    /// Law family: `trapezoid` (3 parts), `lead-trapezoid` (4), `linear-trapezoid` (3).
    pub family: Family,
    /// Grid step of the relative lengths k_Ti ([`GridSpec::STEP_RANGE`]; at most
    /// [`MAX_SHED_ROWS`] laws).
    #[schemars(transform = loomkin_units::schema::bounds(GridSpec::STEP_RANGE))]
    pub step: f64,
    /// Smallest relative length on the grid (default [`GridSpec::PRACTICAL_MIN_K`], the paper's
    /// practical minimum).
    #[serde(default = "default_min")]
    #[schemars(transform = loomkin_units::schema::bounds(GridSpec::K_RANGE))]
    pub min_length: f64,
    /// Motion angles φ (deg), 1 … [`MAX_MOTIONS`] of them, each in (0, 360].
    #[schemars(transform = loomkin_units::schema::item_bounds(MOTION_DEG))]
    pub motions_deg: Vec<f64>,
    /// Evaluation conditions.
    #[serde(default)]
    pub conditions: ShedConditions,
    /// Jerk limit (m/s³): the front is drawn from the laws whose peak jerk stays within it (a
    /// law whose acceleration steps has no bounded jerk); none when absent.
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(JERK_LIMIT_RANGE))]
    pub max_jerk_m_s3: Option<f64>,
}

fn default_min() -> f64 {
    GridSpec::PRACTICAL_MIN_K
}

/// All evaluated (law, motion angle) points, in columns, in single precision (for drawing; the
/// front carries the exact values).
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct ShedCloud {
    /// Weft-crossing window φ* (deg).
    pub window_deg: Vec<f32>,
    /// Peak frame acceleration (m/s²).
    pub peak_accel_m_s2: Vec<f32>,
    /// Motion angle (deg).
    pub motion_deg: Vec<f32>,
    /// Whether the point keeps the request's jerk limit (all `true` without one).
    pub within_jerk_limit: Vec<bool>,
}

/// `POST /api/shed/pareto` answer.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ParetoResponse {
    /// Number of laws on the grid that make a law.
    pub laws: usize,
    /// Every (law, motion angle) point.
    pub cloud: ShedCloud,
    /// The Pareto front, largest window first.
    pub front: Vec<Candidate>,
}

/// Evaluates the grid of the family and its Pareto front.
pub fn shed_pareto(req: &ParetoRequest) -> Result<ParetoResponse, ApiError> {
    shed_pareto_until(req, &StopFlag::default())
}

/// [`shed_pareto`] that ends early once `stop` is set (the client gone, the budget spent): the
/// laws' evaluation looks at it between chunks of laws, and it is looked at again before the cloud
/// and before the front.
pub(crate) fn shed_pareto_until(req: &ParetoRequest, stop: &StopFlag) -> Result<ParetoResponse, ApiError> {
    let template = req.family.template();
    let cond = req.conditions.build()?;
    check_count("motions_deg", req.motions_deg.len(), 1, MAX_MOTIONS)?;
    for (i, &m) in req.motions_deg.iter().enumerate() {
        MOTION_DEG.check(&format!("motions_deg[{i}]"), m)?;
    }
    let min = GridSpec::K_RANGE.check("min_length", req.min_length)?;
    let step = GridSpec::STEP_RANGE.check("step", req.step)?;
    if min * template.parts() as f64 > 1.0 {
        return Err(ApiError::invalid(
            "min_length",
            format!(
                "min_length = {}: {} parts of at least this length cannot sum to 1",
                loomkin_units::compact(min),
                template.parts()
            ),
        ));
    }
    // Bound the work before building the grid: the generator walks the cube of the free lengths.
    let axis = ((1.0 - min) / step).floor() + 1.0;
    let cube = axis.powi(template.parts() as i32 - 1);
    if cube > 40.0 * MAX_SHED_ROWS as f64 {
        let smallest = (1.0 - min) / ((40.0 * MAX_SHED_ROWS as f64).powf(1.0 / (template.parts() as f64 - 1.0)) - 1.0);
        return Err(ApiError::invalid(
            "step",
            format!(
                "step = {step} gives about {cube:.0} grid points for the {} parts of '{}': use step ≥ {:.3}",
                template.parts(),
                req.family.name(),
                smallest
            ),
        ));
    }
    let study = Study::new(DesignKind::Grid, Some(template), GridSpec { step, min_k: min, max_k: 1.0 })
        .map_err(|e| shed_error("step", e))?;
    let design = &study.design;
    check_count("step", design.len(), 1, MAX_SHED_ROWS).map_err(|_| {
        ApiError::invalid(
            "step",
            format!(
                "step = {step} gives {} laws, at most {MAX_SHED_ROWS} are allowed: use a larger step",
                design.len()
            ),
        )
    })?;
    let rows = study.evaluate_until(cond.threshold(), Progress::Hidden, stop).map_err(|e| shed_error("family", e))?;
    let laws = rows.iter().filter(|r| r.is_some()).count();
    if laws * req.motions_deg.len() > MAX_SHED_POINTS {
        return Err(ApiError::invalid(
            "step",
            format!(
                "{laws} laws × {} motion angles exceed {MAX_SHED_POINTS} points: use a larger step or fewer angles",
                req.motions_deg.len()
            ),
        ));
    }
    if let Some(j) = req.max_jerk_m_s3 {
        JERK_LIMIT_RANGE.check("max_jerk_m_s3", j)?;
    }
    stop.check().map_err(|s| shed_error("body", s.into()))?;
    let all = table(design, &rows, &req.motions_deg, &cond).map_err(|e| shed_error("motions_deg", e))?;
    stop.check().map_err(|s| shed_error("body", s.into()))?;
    let front = pareto_within(design, &rows, &req.motions_deg, &cond, req.max_jerk_m_s3)
        .map_err(|e| shed_error("motions_deg", e))?;
    let within = |c: &Candidate| {
        rows[c.row].as_ref().is_some_and(|d| within_jerk_limit(d, c.criteria.motion_deg, req.max_jerk_m_s3, &cond))
    };
    let cloud = ShedCloud {
        window_deg: all.iter().map(|c| finite(c.criteria.window_deg) as f32).collect(),
        peak_accel_m_s2: all.iter().map(|c| finite(c.criteria.peak_accel_m_s2) as f32).collect(),
        motion_deg: all.iter().map(|c| c.criteria.motion_deg as f32).collect(),
        within_jerk_limit: all.iter().map(within).collect(),
    };
    Ok(ParetoResponse { laws, cloud, front })
}

/// `POST /api/shed/law` request: one law of a family.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShedLawRequest {
    /// Law family (as in [`ParetoRequest::family`]).
    pub family: Family,
    /// Relative lengths k_T1 … k_Tn of the positive phase (sum 1).
    #[schemars(transform = loomkin_units::schema::item_bounds(GridSpec::K_RANGE))]
    pub lengths: Vec<f64>,
    /// Motion angle φ (deg).
    #[schemars(transform = loomkin_units::schema::bounds(MOTION_DEG))]
    pub motion_deg: f64,
    /// Evaluation conditions.
    #[serde(default)]
    pub conditions: ShedConditions,
    /// Samples over the turn (default [`DEFAULT_CYCLE_SAMPLES`]).
    #[serde(default = "default_samples")]
    #[schemars(transform = crate::schema::count(MIN_SAMPLES, MAX_SAMPLES))]
    pub samples: usize,
}

fn default_samples() -> usize {
    DEFAULT_CYCLE_SAMPLES
}

/// `POST /api/shed/law` answer: criteria and the frame's motion over one turn.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ShedLawResponse {
    /// The criteria (window, conditional dwell, Ca, peak acceleration, …).
    pub criteria: Criteria,
    /// Main-shaft angle (deg).
    pub angle_deg: Vec<f64>,
    /// Frame displacement (mm).
    pub s_mm: Vec<f64>,
    /// Frame velocity (m/s).
    pub v_m_s: Vec<f64>,
    /// Frame acceleration (m/s²).
    pub a_m_s2: Vec<f64>,
    /// Frame jerk (m/s³), inside the law's segments; unbounded at the steps of
    /// `accel_jumps_deg`.
    pub j_m_s3: Vec<f64>,
    /// Main-shaft angles (deg) where the acceleration steps (the jerk is unbounded there).
    pub accel_jumps_deg: Vec<f64>,
    /// The steps of the acceleration at those angles (m/s², after less before).
    pub accel_jumps_m_s2: Vec<f64>,
}

/// The chosen law over one turn.
pub fn shed_law(req: &ShedLawRequest) -> Result<ShedLawResponse, ApiError> {
    let template = req.family.template();
    let cond = req.conditions.build()?;
    let n = check_count("samples", req.samples, MIN_SAMPLES, MAX_SAMPLES)?;
    check_count("lengths", req.lengths.len(), template.parts(), template.parts())?;
    for (i, &k) in req.lengths.iter().enumerate() {
        GridSpec::K_RANGE.check(&format!("lengths[{i}]"), k)?;
    }
    MOTION_DEG.check("motion_deg", req.motion_deg)?;
    let law = template.law(req.motion_deg, &req.lengths).map_err(|e| shed_error("lengths", e))?;
    let criteria = evaluate(&law, &cond).map_err(|e| shed_error("lengths", e))?;
    let curve = cycle_curve(&law, &cond, n).map_err(|e| shed_error("lengths", e))?;
    let jumps = cycle_accel_jumps(&law, &cond).map_err(|e| shed_error("lengths", e))?;
    Ok(ShedLawResponse {
        criteria,
        angle_deg: curve.iter().map(|p| finite(p.angle_deg)).collect(),
        s_mm: curve.iter().map(|p| finite(loomkin_units::mm_from_m(p.s_m))).collect(),
        v_m_s: curve.iter().map(|p| finite(p.v_m_s)).collect(),
        a_m_s2: curve.iter().map(|p| finite(p.a_m_s2)).collect(),
        j_m_s3: curve.iter().map(|p| finite(p.j_m_s3)).collect(),
        accel_jumps_deg: jumps.iter().map(|j| finite(j.angle_deg)).collect(),
        accel_jumps_m_s2: jumps.iter().map(|j| finite(j.jump_m_s2)).collect(),
    })
}

async fn post_pareto(ApiJson(req): ApiJson<ParetoRequest>) -> Result<ApiJson<ParetoResponse>, ApiError> {
    crate::pool::heavy(move |stop| shed_pareto_until(&req, stop)).await.map(ApiJson)
}

async fn post_law(ApiJson(req): ApiJson<ShedLawRequest>) -> Result<ApiJson<ShedLawResponse>, ApiError> {
    crate::server::blocking(move || shed_law(&req)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(step: f64) -> ParetoRequest {
        ParetoRequest {
            family: Family::Trapezoid,
            step,
            min_length: 0.005,
            motions_deg: vec![200.0, 300.0],
            conditions: ShedConditions::default(),
            max_jerk_m_s3: None,
        }
    }

    /// A set stop flag ends the Pareto request (issue 27: an abandoned request ran on); an unset
    /// one gives the plain request's answer.
    #[test]
    fn the_pareto_front_stops_when_asked() {
        let r = req(0.05);
        let stop = StopFlag::default();
        assert_eq!(shed_pareto_until(&r, &stop).unwrap(), shed_pareto(&r).unwrap());
        stop.stop();
        let e = shed_pareto_until(&r, &stop).unwrap_err();
        assert_eq!(e.field(), "body", "{e:?}");
    }

    /// With a jerk limit the front keeps it, the cloud flags exactly the points over it, and the
    /// chosen law's jerk curve peaks at the criteria's peak jerk.
    #[test]
    fn a_jerk_limit_keeps_the_front_within_it() {
        let free = shed_pareto(&req(0.05)).unwrap();
        assert!(free.cloud.within_jerk_limit.iter().all(|&b| b));
        let mut r = req(0.05);
        let mut jerks: Vec<f64> = free.front.iter().map(|c| c.criteria.peak_jerk_m_s3).collect();
        jerks.sort_by(f64::total_cmp);
        let limit = jerks[jerks.len() / 2];
        r.max_jerk_m_s3 = Some(limit);
        let lim = shed_pareto(&r).unwrap();
        assert!(!lim.front.is_empty());
        assert!(lim.front.iter().all(|c| c.criteria.peak_jerk_m_s3 <= limit && c.criteria.accel_jump_m_s2 == 0.0));
        let over = lim.cloud.within_jerk_limit.iter().filter(|&&b| !b).count();
        assert!(over > 0 && over < lim.cloud.within_jerk_limit.len());
        r.max_jerk_m_s3 = Some(-1.0);
        assert_eq!(shed_pareto(&r).unwrap_err().field(), "max_jerk_m_s3");
        let f = &lim.front[0];
        let l = shed_law(&ShedLawRequest {
            family: Family::Trapezoid,
            lengths: f.lengths.clone(),
            motion_deg: f.criteria.motion_deg,
            conditions: ShedConditions::default(),
            samples: 2001,
        })
        .unwrap();
        let jmax = l.j_m_s3.iter().fold(0.0f64, |m, j| m.max(j.abs()));
        assert!(jmax <= f.criteria.peak_jerk_m_s3 * (1.0 + 1e-9) && jmax > 0.95 * f.criteria.peak_jerk_m_s3, "{jmax}");
        assert!(l.accel_jumps_deg.is_empty());
    }

    #[test]
    fn front_is_non_dominated_and_its_laws_evaluate_alike() {
        let r = shed_pareto(&req(0.05)).unwrap();
        assert!(r.laws > 10 && !r.front.is_empty());
        assert_eq!(r.cloud.window_deg.len(), r.laws * 2);
        // No cloud point beats a front point in both criteria.
        for f in &r.front {
            let (w, a) = (f.criteria.window_deg, f.criteria.peak_accel_m_s2);
            let beaten = r
                .cloud
                .window_deg
                .iter()
                .zip(&r.cloud.peak_accel_m_s2)
                // The cloud is single precision: a point beats the front only by more than 1e-6.
                .map(|(&cw, &ca)| (f64::from(cw), f64::from(ca)))
                .any(|(cw, ca)| cw >= w && ca <= a && (cw > w * (1.0 + 1e-6) || ca < a * (1.0 - 1e-6)));
            assert!(!beaten, "front point ({w}, {a}) is dominated");
        }
        // The law endpoint, through the generic path, gives the front's numbers (fast path).
        let f = &r.front[0];
        let l = shed_law(&ShedLawRequest {
            family: Family::Trapezoid,
            lengths: f.lengths.clone(),
            motion_deg: f.criteria.motion_deg,
            conditions: ShedConditions::default(),
            samples: 361,
        })
        .unwrap();
        assert!((l.criteria.window_deg - f.criteria.window_deg).abs() < 1e-6);
        assert!((l.criteria.peak_accel_m_s2 - f.criteria.peak_accel_m_s2).abs() < 1e-6 * f.criteria.peak_accel_m_s2);
        let amax = l.a_m_s2.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        assert!(amax <= l.criteria.peak_accel_m_s2 * (1.0 + 1e-9) && amax > 0.97 * l.criteria.peak_accel_m_s2);
    }

    #[test]
    fn fine_grids_and_bad_values_are_refused() {
        assert_eq!(shed_pareto(&req(0.001)).map(|_| ()).unwrap_err().field(), "step");
        let mut r = req(0.05);
        r.family = Family::LeadTrapezoid;
        r.step = 0.005;
        assert_eq!(shed_pareto(&r).unwrap_err().field(), "step");
        let e = crate::parse_json::<ParetoRequest>(br#"{"family": "hexagon", "step": 0.05, "motions_deg": [200]}"#);
        assert_eq!(e.unwrap_err().field(), "family");
        let mut r = req(0.05);
        r.motions_deg = vec![400.0];
        assert_eq!(shed_pareto(&r).unwrap_err().field(), "motions_deg[0]");
        let mut r = req(0.05);
        r.conditions.threshold = 0.5;
        assert_eq!(shed_pareto(&r).unwrap_err().field(), "conditions.threshold");
    }

    #[test]
    fn bad_lengths_are_named_as_in_the_request() {
        let law = |family: Family, lengths: Vec<f64>| ShedLawRequest {
            family,
            lengths,
            motion_deg: 200.0,
            conditions: ShedConditions::default(),
            samples: 11,
        };
        let e = shed_law(&law(Family::Trapezoid, vec![0.5, 0.5, 0.5])).unwrap_err();
        assert_eq!(e.field(), "lengths", "{e}");
        assert!(e.to_string().starts_with("lengths: relative lengths k_Ti sum to 1.5"), "{e}");
        // Only the zero-acceleration lead: no rise.
        let e = shed_law(&law(Family::LeadTrapezoid, vec![1.0, 0.0, 0.0, 0.0])).unwrap_err();
        assert_eq!(e.field(), "lengths", "{e}");
    }
}
