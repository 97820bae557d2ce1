//! The insertion view (issue 30): the loom file's weft carrier — the time budget of any carrier
//! (`loomkin insert budget`), the rapier's heads, the projectile's flight and the air jet's yarn tip
//! across the reed against the main-shaft angle, the carrier's clearance in the shed over the
//! pattern's worst pick with its least value, the rapier's transfer and the air jet's relay plan.
//! The routes `POST /api/insert/{budget,rapier,projectile,airjet}` answer exactly what
//! `loomkin insert … --json` prints (the same library calls); `POST /api/insert/evaluate` is the
//! view's: all of it for the carrier the file names, with the curves to draw.

use crate::loom_api::{LoomSource, PatternSource};
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::post;
use loomkin_insertion::{AirjetReport, BudgetInputs, BudgetReport, PickBudget, RelayOpen};
use loomkin_loom::insertion::{CarrierShed, Clearance, RapierCheck, rapier_check, worst_pick_clearance};
use loomkin_loom::insertion_air::{ProjectileCheck, airjet_check, projectile_check};
use loomkin_loom::insertion_timing::{CarrierTiming, carrier_timing_at};
use loomkin_loom::{InsertionKind, Loom, Motion, Pattern};
use loomkin_units::{ShaftSpeed, StopFlag, mm_from_m};
use serde::{Deserialize, Serialize};

/// The example loom of each carrier the routes use when a request gives no loom file:
/// `examples/rapier-loom.toml`, `projectile-loom.toml`, `airjet-loom.toml`.
pub const INSERTION_EXAMPLES: [(&str, &str); 3] = [
    ("rapier", include_str!("../../../examples/rapier-loom.toml")),
    ("projectile", include_str!("../../../examples/projectile-loom.toml")),
    ("airjet", include_str!("../../../examples/airjet-loom.toml")),
];

pub(crate) fn routes() -> Router {
    Router::new()
        .route("/insert/budget", post(post_budget))
        .route("/insert/rapier", post(post_rapier))
        .route("/insert/projectile", post(post_projectile))
        .route("/insert/airjet", post(post_airjet))
        .route("/insert/evaluate", post(post_evaluate))
}

/// The budget's inputs a request may give over the loom file's (`loomkin insert budget`'s flags).
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BudgetOverrides {
    /// Reed space, mm ([`PickBudget::REED_WIDTH_MM`]; default: the loom file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::REED_WIDTH_MM.range))]
    pub reed_width_mm: Option<f64>,
    /// Carrier length along the weft, mm ([`PickBudget::CARRIER_LENGTH_MM`]; default: the file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::CARRIER_LENGTH_MM.range))]
    pub carrier_length_mm: Option<f64>,
    /// The insertion window, deg ([`PickBudget::WINDOW_DEG`]; default: the file's entry-to-exit or
    /// the pattern's clear-shed window).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::WINDOW_DEG.range))]
    pub window_deg: Option<f64>,
    /// The carrier's mean speed across the shed, m/s ([`PickBudget::SPEED_M_S`]; default: the file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::SPEED_M_S.range))]
    pub speed_m_s: Option<f64>,
    /// The carrier's mass, g ([`PickBudget::CARRIER_MASS_G`]): energy per pick and drive power.
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::CARRIER_MASS_G.range))]
    pub carrier_mass_g: Option<f64>,
}

/// `POST /api/insert/budget` request: `loomkin insert budget [LOOM.toml] [--wif|--lift-plan] [flags]`.
#[derive(Debug, Clone, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BudgetRequest {
    /// A loom file's text; without it the reed width, carrier length, window and speed must all be given.
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// A pattern whose clear-shed window (as `loom check` finds it) is the insertion window (needs
    /// a loom file; `{}`: plain weave on the loom's frames); without it the file's entry and exit angles.
    #[serde(default)]
    pub pattern: Option<PatternSource>,
    /// Reed space, mm (over the file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::REED_WIDTH_MM.range))]
    pub reed_width_mm: Option<f64>,
    /// Carrier length along the weft, mm (over the file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::CARRIER_LENGTH_MM.range))]
    pub carrier_length_mm: Option<f64>,
    /// The insertion window, deg (over the file's entry-to-exit or the pattern's clear-shed window).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::WINDOW_DEG.range))]
    pub window_deg: Option<f64>,
    /// The carrier's mean speed across the shed, m/s (over the file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::SPEED_M_S.range))]
    pub speed_m_s: Option<f64>,
    /// The carrier's mass, g: energy per pick and drive power.
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(PickBudget::CARRIER_MASS_G.range))]
    pub carrier_mass_g: Option<f64>,
    /// Loom speed for the required carrier speed and the drive power, rpm (default: the file's;
    /// without a file, the highest speed).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::SPEED.range))]
    pub speed_rpm: Option<f64>,
}

/// `POST /api/insert/rapier` and `/api/insert/projectile` request: `loomkin insert rapier|projectile
/// LOOM.toml [--wif|--lift-plan] [--speed-rpm]`.
#[derive(Debug, Clone, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CarrierRequest {
    /// A loom file's text (default: the route's example, `examples/rapier-loom.toml` or
    /// `projectile-loom.toml`).
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// The pattern whose every pick the clearance covers (default: plain weave on the loom's frames).
    #[serde(default)]
    pub pattern: PatternSource,
    /// Main-shaft speed, rpm (default: the loom file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::SPEED.range))]
    pub speed_rpm: Option<f64>,
}

/// `POST /api/insert/airjet` request: `loomkin insert airjet LOOM.toml [--speed-rpm]` (the flight
/// does not depend on the pattern).
#[derive(Debug, Clone, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AirjetRequest {
    /// A loom file's text (default: `examples/airjet-loom.toml`).
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// Main-shaft speed, rpm (default: the loom file's).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::SPEED.range))]
    pub speed_rpm: Option<f64>,
}

/// `POST /api/insert/evaluate` request: the view's loom, pattern, speed and budget inputs.
#[derive(Debug, Clone, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InsertRequest {
    /// A loom file's text (default: `examples/rapier-loom.toml`); its `[insertion] kind` names the carrier.
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// The weave pattern (default: plain weave on the loom's frames).
    #[serde(default)]
    pub pattern: PatternSource,
    /// Main-shaft speed, rpm (default: the loom file's): the carrier's figures and the budget's
    /// required speed.
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(ShaftSpeed::SPEED.range))]
    pub speed_rpm: Option<f64>,
    /// The budget's inputs given over the file's.
    #[serde(default)]
    pub budget: BudgetOverrides,
    /// Whether the budget's window is the pattern's clear-shed window (as `insert budget --wif`);
    /// otherwise the file's entry and exit angles.
    #[serde(default)]
    pub clear_shed_window: bool,
}

/// The carrier's figures, keyed as `loomkin insert rapier|projectile|airjet --json`.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum CarrierCheck {
    /// `insert rapier --json`.
    Rapier(Box<RapierCheck>),
    /// `insert projectile --json`.
    Projectile(Box<ProjectileCheck>),
    /// `insert airjet --json`.
    Airjet(Box<AirjetReport>),
}

/// One carrier's (or rapier head's) position across the reed against the main-shaft angle.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TrackCurve {
    /// `shuttle`, `bringer`, `taker`, `projectile` or `yarn tip`.
    pub label: &'static str,
    /// Main-shaft angle in a pick's turn, deg (0° = the previous beat-up).
    pub angle_deg: Vec<f64>,
    /// mm from the selvedge where the weft enters (outside 0 … the reed width: a head at rest).
    pub position_mm: Vec<f64>,
}

/// The carrier over one turn ([`CarrierTiming`], positions in mm).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TimingCurves {
    /// Every carrier's track.
    pub tracks: Vec<TrackCurve>,
    /// The angles between which a carrier is in the shed, deg.
    pub in_shed_deg: [f64; 2],
    /// The rapier's transfer: its angle (deg) and the bringer's tip then (mm from its selvedge).
    pub transfer: Option<[f64; 2]>,
    /// The air jet's relay groups' openings (empty for other carriers).
    pub relay_plan: Vec<RelayOpen>,
    /// The sley's back dwell, deg (none without a `[sley]`).
    pub sley_back_dwell_deg: Option<[f64; 2]>,
}

/// The clearance of the pattern's worst pick while the carrier is in the shed.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ClearanceCurve {
    /// The pick (1 = first), the report's `worst_pick`.
    pub pick: usize,
    /// Main-shaft angle in that pick's turn, deg.
    pub angle_deg: Vec<f64>,
    /// The clearance, mm (negative: the carrier touches the warp).
    pub clearance_mm: Vec<f64>,
}

/// `POST /api/insert/evaluate` answer.
#[derive(Debug, Clone, Serialize)]
pub struct InsertResponse {
    /// The loom's name (the file's `name`).
    pub loom: String,
    /// The `[insertion] kind`: `shuttle`, `rapier`, `projectile` or `airjet`.
    pub kind: &'static str,
    /// The main-shaft speed of the figures, rpm.
    pub speed_rpm: f64,
    /// Reed space, mm.
    pub reed_width_mm: f64,
    /// `loomkin insert budget LOOM.toml --json` with the request's inputs.
    pub budget: BudgetReport,
    /// The carrier's figures (`insert rapier|projectile|airjet --json`; none for a shuttle).
    pub check: Option<CarrierCheck>,
    /// The carrier over a turn.
    pub timing: TimingCurves,
    /// The worst pick's clearance (rapier and projectile).
    pub clearance: Option<ClearanceCurve>,
}

/// The stop flag's refusal.
fn stopped(stop: &StopFlag) -> Result<(), ApiError> {
    stop.check().map_err(|e| ApiError::invalid("body", e))
}

fn lib(e: loomkin_loom::LoomError) -> ApiError {
    ApiError::from_library(&e, "loom_toml")
}

/// The speed asked for (checked under the request's key), else the loom file's.
fn speed_of(loom: &Loom, speed_rpm: Option<f64>) -> Result<ShaftSpeed, ApiError> {
    match speed_rpm {
        Some(v) => Ok(ShaftSpeed::from_rpm_field("speed_rpm", v)?),
        None => Ok(loom.speed),
    }
}

/// The loom and pattern of a carrier's request, the route's example when no loom file is given.
fn read(loom_toml: &Option<String>, pattern: &PatternSource, example: &str) -> Result<(Loom, Pattern), ApiError> {
    LoomSource { loom_toml: Some(loom_toml.clone().unwrap_or_else(|| example.to_string())), pattern: pattern.clone() }
        .read()
}

/// The budget of `base` (a loom file's, or none) with the request's inputs over it, as
/// `insert budget` computes it.
fn budget_report(
    base: Option<PickBudget>,
    o: &BudgetOverrides,
    speed_rpm: Option<f64>,
) -> Result<BudgetReport, ApiError> {
    let inputs = BudgetInputs {
        reed_width_mm: o.reed_width_mm,
        carrier_length_mm: o.carrier_length_mm,
        window_deg: o.window_deg,
        speed_m_s: o.speed_m_s,
        speed_rpm,
        carrier_mass_g: o.carrier_mass_g,
    };
    let b = inputs.onto(base).map_err(|m| ApiError::invalid(m.field, m.message(m.field)))?;
    Ok(b.report()?)
}

/// `loomkin insert budget --json`.
pub fn insert_budget(req: &BudgetRequest) -> Result<BudgetReport, ApiError> {
    let base = match (&req.loom_toml, &req.pattern) {
        (Some(text), pattern) => {
            let (loom, pattern) = match pattern {
                Some(p) => {
                    let (l, p) = LoomSource { loom_toml: Some(text.clone()), pattern: p.clone() }.read()?;
                    (l, Some(p))
                }
                None => (Loom::from_toml(text).map_err(|e| ApiError::invalid("loom_toml", e))?, None),
            };
            Some(loomkin_loom::insertion::budget_of(&loom, pattern.as_ref()).map_err(lib)?)
        }
        (None, Some(_)) => {
            return Err(ApiError::invalid(
                "pattern",
                format!("pattern: {}", loomkin_insertion::budget::PATTERN_NEEDS_LOOM),
            ));
        }
        (None, None) => None,
    };
    let o = BudgetOverrides {
        reed_width_mm: req.reed_width_mm,
        carrier_length_mm: req.carrier_length_mm,
        window_deg: req.window_deg,
        speed_m_s: req.speed_m_s,
        carrier_mass_g: req.carrier_mass_g,
    };
    budget_report(base, &o, req.speed_rpm)
}

/// `loomkin insert rapier --json`.
pub fn insert_rapier(req: &CarrierRequest) -> Result<RapierCheck, ApiError> {
    let (loom, pattern) = read(&req.loom_toml, &req.pattern, INSERTION_EXAMPLES[0].1)?;
    let speed = speed_of(&loom, req.speed_rpm)?;
    rapier_check(&loom, &pattern, speed).map_err(lib)
}

/// `loomkin insert projectile --json`.
pub fn insert_projectile(req: &CarrierRequest) -> Result<ProjectileCheck, ApiError> {
    let (loom, pattern) = read(&req.loom_toml, &req.pattern, INSERTION_EXAMPLES[1].1)?;
    let speed = speed_of(&loom, req.speed_rpm)?;
    projectile_check(&loom, &pattern, speed).map_err(lib)
}

/// `loomkin insert airjet --json`.
pub fn insert_airjet(req: &AirjetRequest) -> Result<AirjetReport, ApiError> {
    let text = req.loom_toml.as_deref().unwrap_or(INSERTION_EXAMPLES[2].1);
    let loom = Loom::from_toml(text).map_err(|e| ApiError::invalid("loom_toml", e))?;
    let speed = speed_of(&loom, req.speed_rpm)?;
    airjet_check(&loom, speed).map_err(lib)
}

/// Evaluates the loom file's carrier for the view.
pub fn insert_evaluate(req: &InsertRequest) -> Result<InsertResponse, ApiError> {
    evaluate_until(req, &StopFlag::default())
}

/// [`insert_evaluate`] that ends early once `stop` is set: checked between its parts.
pub(crate) fn evaluate_until(req: &InsertRequest, stop: &StopFlag) -> Result<InsertResponse, ApiError> {
    let (loom, pattern) = LoomSource { loom_toml: req.loom_toml.clone(), pattern: req.pattern.clone() }.read()?;
    let speed = speed_of(&loom, req.speed_rpm)?;
    let window_pattern = req.clear_shed_window.then_some(&pattern);
    let base = loomkin_loom::insertion::budget_of(&loom, window_pattern).map_err(lib)?;
    // The budget's own inputs are named under `budget` (the request's keys); the speed is the request's.
    let budget = budget_report(Some(base), &req.budget, req.speed_rpm)
        .map_err(|e| if e.field() == "speed_rpm" { e } else { e.within("budget") })?;
    stopped(stop)?;
    let check = match &loom.insertion.kind {
        InsertionKind::Rapier(_) => {
            Some(CarrierCheck::Rapier(Box::new(rapier_check(&loom, &pattern, speed).map_err(lib)?)))
        }
        InsertionKind::Projectile(_) => {
            Some(CarrierCheck::Projectile(Box::new(projectile_check(&loom, &pattern, speed).map_err(lib)?)))
        }
        InsertionKind::Airjet(_) => Some(CarrierCheck::Airjet(Box::new(airjet_check(&loom, speed).map_err(lib)?))),
        // The shuttle (and a carrier this view does not know yet): the budget and the track only.
        _ => None,
    };
    let clearance: Option<&Clearance> = match &check {
        Some(CarrierCheck::Rapier(c)) => Some(&c.clearance),
        Some(CarrierCheck::Projectile(c)) => Some(&c.clearance),
        _ => None,
    };
    stopped(stop)?;
    let clearance = match clearance {
        Some(cl) => {
            let motion = Motion::new(&loom, &pattern).map_err(lib)?;
            let shed = CarrierShed::new(&loom, &motion, &pattern).map_err(lib)?;
            let (angle_deg, clearance_mm) =
                worst_pick_clearance(&shed, cl).into_iter().map(|(a, c)| (a, finite(c))).unzip();
            Some(ClearanceCurve { pick: cl.worst_pick, angle_deg, clearance_mm })
        }
        None => None,
    };
    stopped(stop)?;
    let t = carrier_timing_at(&loom, speed).map_err(lib)?;
    Ok(InsertResponse {
        loom: loom.name.clone(),
        kind: loom.insertion.kind.name(),
        speed_rpm: speed.rpm(),
        reed_width_mm: loom.insertion.written_mm[0],
        budget,
        check,
        timing: timing_curves(t),
        clearance,
    })
}

/// The timing's tracks in mm.
fn timing_curves(t: CarrierTiming) -> TimingCurves {
    TimingCurves {
        tracks: t
            .tracks
            .into_iter()
            .map(|k| TrackCurve {
                label: k.label,
                position_mm: k.position_m.iter().map(|&p| finite(mm_from_m(p))).collect(),
                angle_deg: k.angle_deg,
            })
            .collect(),
        in_shed_deg: t.in_shed_deg,
        transfer: t.transfer.map(|p| [p.angle_deg, mm_from_m(p.position_m)]),
        relay_plan: t.relay_plan,
        sley_back_dwell_deg: t.sley_back_dwell_deg,
    }
}

async fn post_budget(ApiJson(req): ApiJson<BudgetRequest>) -> Result<ApiJson<BudgetReport>, ApiError> {
    crate::pool::heavy(move |_| insert_budget(&req)).await.map(ApiJson)
}

async fn post_rapier(ApiJson(req): ApiJson<CarrierRequest>) -> Result<ApiJson<RapierCheck>, ApiError> {
    crate::pool::heavy(move |_| insert_rapier(&req)).await.map(ApiJson)
}

async fn post_projectile(ApiJson(req): ApiJson<CarrierRequest>) -> Result<ApiJson<ProjectileCheck>, ApiError> {
    crate::pool::heavy(move |_| insert_projectile(&req)).await.map(ApiJson)
}

async fn post_airjet(ApiJson(req): ApiJson<AirjetRequest>) -> Result<ApiJson<AirjetReport>, ApiError> {
    crate::server::blocking(move || insert_airjet(&req)).await.map(ApiJson)
}

async fn post_evaluate(ApiJson(req): ApiJson<InsertRequest>) -> Result<ApiJson<InsertResponse>, ApiError> {
    crate::pool::heavy(move |stop| evaluate_until(&req, stop)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loom_api::{LOOM_EXAMPLES, PATTERN_EXAMPLES};

    fn point24() -> PatternSource {
        PatternSource { wif: Some(PATTERN_EXAMPLES[4].1.into()), lift_plan: None }
    }

    fn view(kind: usize) -> InsertRequest {
        InsertRequest { loom_toml: Some(INSERTION_EXAMPLES[kind].1.into()), pattern: point24(), ..Default::default() }
    }

    /// The view answers what the CLI's routes answer, and its curves agree with the figures: the
    /// located least clearance is at or below every sample of the worst pick's curve and within a
    /// sample step's reach of the lowest; the tracks are the library's in mm.
    #[test]
    fn the_view_answers_what_the_library_computes() {
        for kind in 0..2 {
            let r = insert_evaluate(&view(kind)).unwrap();
            let carrier = CarrierRequest { loom_toml: view(kind).loom_toml, pattern: point24(), speed_rpm: None };
            let (cl, direct) = match (&r.check, kind) {
                (Some(CarrierCheck::Rapier(c)), 0) => {
                    let d = insert_rapier(&carrier).unwrap();
                    (c.clearance, serde_json::to_value(d).unwrap())
                }
                (Some(CarrierCheck::Projectile(c)), 1) => {
                    let d = insert_projectile(&carrier).unwrap();
                    (c.clearance, serde_json::to_value(d).unwrap())
                }
                other => panic!("kind {kind}: {other:?}"),
            };
            assert_eq!(serde_json::to_value(r.check.as_ref().unwrap()).unwrap(), direct);
            let k = r.clearance.as_ref().unwrap();
            assert_eq!(k.pick, cl.worst_pick);
            let lowest = k.clearance_mm.iter().copied().fold(f64::INFINITY, f64::min);
            assert!(cl.min_clearance_mm <= lowest + 1e-9, "located {} above sampled {lowest}", cl.min_clearance_mm);
            assert!(lowest - cl.min_clearance_mm < 1.0, "located {} far below sampled {lowest}", cl.min_clearance_mm);
            assert_eq!((k.angle_deg[0], *k.angle_deg.last().unwrap()), (cl.in_shed_deg[0], cl.in_shed_deg[1]));
            // The tracks: the library's timing in mm.
            let loom = Loom::from_toml(INSERTION_EXAMPLES[kind].1).unwrap();
            let t = carrier_timing_at(&loom, loom.speed).unwrap();
            assert_eq!(r.timing.tracks.len(), t.tracks.len());
            for (a, b) in r.timing.tracks.iter().zip(&t.tracks) {
                assert_eq!(a.angle_deg, b.angle_deg);
                assert!(
                    a.position_mm.iter().zip(&b.position_m).all(|(x, y)| (x - y * 1e3).abs() <= 1e-9 * (1.0 + x.abs()))
                );
            }
            // The budget: the file's, from its entry and exit angles.
            let b = BudgetRequest { loom_toml: view(kind).loom_toml, ..Default::default() };
            assert_eq!(r.budget, insert_budget(&b).unwrap());
            assert_eq!(r.budget.window_source, loomkin_insertion::WindowSource::EntryExit);
        }
        // The rapier's transfer is on the bringer's track.
        let r = insert_evaluate(&view(0)).unwrap();
        let [at, y] = r.timing.transfer.unwrap();
        let b = &r.timing.tracks[0];
        let k = b.angle_deg.iter().position(|a| (a - at).abs() <= 0.25).unwrap();
        assert!((b.position_mm[k] - y).abs() < 5.0, "{} vs {y}", b.position_mm[k]);
        // The air jet: no clearance, the relay plan of `insert airjet`.
        let r = insert_evaluate(&view(2)).unwrap();
        let direct = insert_airjet(&AirjetRequest { loom_toml: view(2).loom_toml, speed_rpm: None }).unwrap();
        assert!(r.clearance.is_none() && !r.timing.relay_plan.is_empty());
        assert_eq!(r.timing.relay_plan, direct.relay_plan);
        // The shuttle: the budget and its straight track only.
        let r = insert_evaluate(&InsertRequest { loom_toml: Some(LOOM_EXAMPLES[1].1.into()), ..Default::default() })
            .unwrap();
        assert_eq!((r.kind, r.check.is_none(), r.timing.tracks.len()), ("shuttle", true, 1));
    }

    /// The budget's inputs given over the file's, the clear-shed window and the speed move the
    /// answer as `insert budget` says: n ∝ v̄ at a fixed window, the pattern's window replaces the file's.
    #[test]
    fn the_budget_inputs_and_the_speed() {
        let base = insert_evaluate(&view(0)).unwrap().budget;
        let q = InsertRequest {
            budget: BudgetOverrides {
                speed_m_s: Some(2.0 * base.speed_m_s),
                carrier_mass_g: Some(300.0),
                ..Default::default()
            },
            speed_rpm: Some(400.0),
            ..view(0)
        };
        let r = insert_evaluate(&q).unwrap();
        assert!((r.budget.max_picks_per_min - 2.0 * base.max_picks_per_min).abs() < 1e-9 * base.max_picks_per_min);
        assert_eq!((r.speed_rpm, r.budget.speed_rpm), (400.0, 400.0));
        let e = r.budget.energy_per_pick_j.unwrap();
        assert!((e - 0.5 * 0.3 * r.budget.speed_m_s.powi(2)).abs() < 1e-12 * e);
        let w = insert_evaluate(&InsertRequest { clear_shed_window: true, ..view(0) }).unwrap().budget;
        assert_eq!(w.window_source, loomkin_insertion::WindowSource::ClearShed);
        let b = BudgetRequest { loom_toml: view(0).loom_toml, pattern: Some(point24()), ..Default::default() };
        assert_eq!(w, insert_budget(&b).unwrap());
    }

    #[test]
    fn bad_inputs_are_named() {
        let e = insert_evaluate(&InsertRequest {
            budget: BudgetOverrides { reed_width_mm: Some(0.0), ..Default::default() },
            ..view(0)
        })
        .unwrap_err();
        assert_eq!(e.field(), "budget.reed_width_mm", "{e}");
        assert!(e.to_string().starts_with("budget.reed_width_mm = 0 is out of range"), "{e}");
        let e = insert_evaluate(&InsertRequest { speed_rpm: Some(-1.0), ..view(0) }).unwrap_err();
        assert_eq!(e.field(), "speed_rpm", "{e}");
        let e = insert_rapier(&CarrierRequest { loom_toml: view(2).loom_toml, ..Default::default() }).unwrap_err();
        assert_eq!(e.field(), "insertion.kind", "{e}");
        let e = insert_budget(&BudgetRequest { pattern: Some(point24()), ..Default::default() }).unwrap_err();
        assert_eq!(e.field(), "pattern", "{e}");
        let e = insert_budget(&BudgetRequest { reed_width_mm: Some(1000.0), ..Default::default() }).unwrap_err();
        assert_eq!(e.field(), "carrier_length_mm", "{e}");
        let e = insert_airjet(&AirjetRequest { loom_toml: Some("name = 1".into()), speed_rpm: None }).unwrap_err();
        assert_eq!(e.field(), "loom_toml", "{e}");
        // A stopped computation ends with the stop's refusal.
        let stop = StopFlag::default();
        stop.stop();
        assert_eq!(evaluate_until(&view(0), &stop).unwrap_err().field(), "body");
    }
}
