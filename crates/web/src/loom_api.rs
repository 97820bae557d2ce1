//! The loom view: a loom file (the examples or one the user loads) weaving a pattern (a WIF draft
//! or a lift plan, from the examples or uploaded) — the pattern grid, every frame's lift over the
//! main-shaft angle, the shedding torque over the repeat (with and without stagger) and the timing
//! diagram (shed open to the carrier against the insertion window). The figures are those of
//! `loomkin loom check`, `loom torque`, `loom stagger` and `loom timing`.

use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::{get, post};
use loomkin_loom::{
    CheckReport, DEFAULT_TIMING_PICKS, DEFAULT_TIMING_STEP_DEG, Drive, Loom, Motion, Objective, Pattern,
    StaggerOptions, StaggerResult, TimingCurves, check, optimise_stagger_with, timing_curves,
};
use loomkin_units::{StopFlag, compact};
use serde::{Deserialize, Serialize};

/// The loom files the view offers (`examples/`).
pub const LOOM_EXAMPLES: &[(&str, &str)] = &[
    ("rapier-loom.toml", include_str!("../../../examples/rapier-loom.toml")),
    ("shuttle-loom.toml", include_str!("../../../examples/shuttle-loom.toml")),
    ("projectile-loom.toml", include_str!("../../../examples/projectile-loom.toml")),
    ("airjet-loom.toml", include_str!("../../../examples/airjet-loom.toml")),
    ("servo-shedding-loom.toml", include_str!("../../../examples/servo-shedding-loom.toml")),
    ("servo-shedding-laws-loom.toml", include_str!("../../../examples/servo-shedding-laws-loom.toml")),
];

/// The weave patterns the view offers (`examples/`): WIF drafts and a lift plan.
pub const PATTERN_EXAMPLES: &[(&str, &str)] = &[
    ("plain.wif", include_str!("../../../examples/plain.wif")),
    ("twill-2-2.wif", include_str!("../../../examples/twill-2-2.wif")),
    ("satin-8.wif", include_str!("../../../examples/satin-8.wif")),
    ("twill-16.wif", include_str!("../../../examples/twill-16.wif")),
    ("point-24.wif", include_str!("../../../examples/point-24.wif")),
    ("dobby-24.wif", include_str!("../../../examples/dobby-24.wif")),
    ("twill-3-1.txt", include_str!("../../../examples/twill-3-1.txt")),
];

/// Most picks of a pattern the workbench evaluates (the CLI takes up to
/// [`loomkin_loom::MAX_PICKS`]; an answer should come in a second or two).
pub const MAX_WEB_PICKS: usize = 1000;

/// Most picks drawn in the timing diagram at once.
pub const MAX_TIMING_PICKS: usize = 8;

/// Most points of the torque curve sent to the page (the peak and RMS are exact whatever this).
const MAX_TORQUE_POINTS: usize = 8000;

pub(crate) fn routes() -> Router {
    Router::new()
        .route("/loom/examples", get(|| async { ApiJson(examples()) }))
        .route("/loom/evaluate", post(post_evaluate))
        .route("/loom/stagger", post(post_stagger))
}

/// A named example file.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct LoomExample {
    /// File name in `examples/`.
    pub name: &'static str,
    /// Its text.
    pub text: &'static str,
}

/// `GET /api/loom/examples`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct LoomExamples {
    /// Loom files.
    pub looms: Vec<LoomExample>,
    /// WIF drafts (`.wif`) and lift plans (`.txt`).
    pub patterns: Vec<LoomExample>,
}

/// The view's starting point.
pub fn examples() -> LoomExamples {
    let list = |v: &[(&'static str, &'static str)]| v.iter().map(|&(name, text)| LoomExample { name, text }).collect();
    LoomExamples { looms: list(LOOM_EXAMPLES), patterns: list(PATTERN_EXAMPLES) }
}

/// The weave pattern: a WIF draft or a lift plan (neither: plain weave on the loom's frames).
#[derive(Debug, Clone, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PatternSource {
    /// A WIF 1.1 file's text.
    #[serde(default)]
    pub wif: Option<String>,
    /// A plain lift plan: one line per pick, the raised shafts.
    #[serde(default)]
    pub lift_plan: Option<String>,
}

/// The loom and the pattern of a request.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LoomSource {
    /// A loom file's text (default: `examples/rapier-loom.toml`).
    pub loom_toml: Option<String>,
    /// The weave pattern.
    pub pattern: PatternSource,
}

impl LoomSource {
    pub(crate) fn read(&self) -> Result<(Loom, Pattern), ApiError> {
        let loom = match &self.loom_toml {
            Some(t) => Loom::from_toml(t).map_err(|e| ApiError::invalid("loom_toml", e))?,
            None => Loom::from_toml(LOOM_EXAMPLES[0].1).map_err(|e| ApiError::Internal(e.to_string()))?,
        };
        let pattern = match (&self.pattern.wif, &self.pattern.lift_plan) {
            (Some(_), Some(_)) => {
                return Err(ApiError::BadJson {
                    field: "pattern".into(),
                    message: "pattern: give wif or lift_plan, not both".into(),
                });
            }
            (Some(w), None) => Pattern::from_wif(w).map_err(|e| ApiError::invalid("pattern.wif", e))?,
            (None, Some(l)) => Pattern::from_lift_plan(l).map_err(|e| ApiError::invalid("pattern.lift_plan", e))?,
            (None, None) => Pattern::plain(loom.frame_count()).map_err(|e| ApiError::invalid("loom_toml", e))?,
        };
        if pattern.picks() > MAX_WEB_PICKS {
            return Err(ApiError::invalid(
                "pattern",
                format!(
                    "pattern: {} picks in the repeat; the workbench takes at most {MAX_WEB_PICKS} (use loomkin loom \
                     check for longer repeats)",
                    pattern.picks()
                ),
            ));
        }
        Ok((loom, pattern))
    }
}

/// `POST /api/loom/evaluate` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoomRequest {
    /// A loom file's text (default: `examples/rapier-loom.toml`).
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// The weave pattern (default: plain weave on the loom's frames).
    #[serde(default)]
    pub pattern: PatternSource,
    /// Another stagger (deg per frame, front first) than the file's, e.g. the optimised one.
    #[serde(default)]
    pub stagger_deg: Option<Vec<f64>>,
    /// First pick of the timing diagram (0-based, within the repeat).
    #[serde(default)]
    pub from_pick: usize,
    /// Picks in the timing diagram, 1 … [`MAX_TIMING_PICKS`].
    #[serde(default = "default_picks")]
    #[schemars(transform = crate::schema::count(1, MAX_TIMING_PICKS))]
    pub picks: usize,
    /// Angle step of the timing curves (deg), [`loomkin_loom::TIMING_STEP_RANGE`].
    #[serde(default = "default_step")]
    #[schemars(transform = loomkin_units::schema::bounds(loomkin_loom::TIMING_STEP_RANGE))]
    pub step_deg: f64,
}

fn default_picks() -> usize {
    DEFAULT_TIMING_PICKS
}

fn default_step() -> f64 {
    DEFAULT_TIMING_STEP_DEG
}

/// The weave pattern as a grid.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct PatternGrid {
    /// Shafts (frames) the pattern uses.
    pub shafts: usize,
    /// Picks in the repeat.
    pub picks: usize,
    /// `rows[p][i]`: shaft `i` (front first) raised at pick `p`.
    pub rows: Vec<Vec<bool>>,
}

/// The shedding torque over the repeat.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct TorqueCurve {
    /// Main-shaft angle over the repeat (deg).
    pub angle_deg: Vec<f64>,
    /// Torque the main shaft delivers to the shedding (N·m).
    pub torque_n_m: Vec<f64>,
}

/// `POST /api/loom/evaluate` answer.
#[derive(Debug, Clone, Serialize)]
pub struct LoomResponse {
    /// The figures of `loomkin loom check --json`.
    pub report: CheckReport,
    /// The pattern.
    pub pattern: PatternGrid,
    /// The torque over the repeat.
    pub torque: TorqueCurve,
    /// The stagger used (deg per frame).
    pub stagger_deg: Vec<f64>,
    /// The timing diagram's numbers.
    pub timing: TimingCurves,
}

fn torque_curve(loom: &Loom, pattern: &Pattern) -> Result<TorqueCurve, ApiError> {
    let motion = Motion::new(loom, pattern).map_err(|e| ApiError::from_library(&e, "loom_toml"))?;
    let drive = Drive::new(loom, &motion, pattern);
    let step = (motion.repeat_deg() / MAX_TORQUE_POINTS as f64).max(0.5);
    let mut t = TorqueCurve::default();
    for (a, q) in drive.torque_curve(step) {
        t.angle_deg.push(crate::series::finite(a));
        t.torque_n_m.push(crate::series::finite(q));
    }
    // Close the repeat.
    if let Some(&q) = t.torque_n_m.first() {
        t.angle_deg.push(motion.repeat_deg());
        t.torque_n_m.push(q);
    }
    Ok(t)
}

/// Evaluates the loom weaving the pattern.
pub fn evaluate(req: &LoomRequest) -> Result<LoomResponse, ApiError> {
    evaluate_until(req, &StopFlag::default())
}

/// A set stop flag, as the refusal of a stopped computation (the pool words it; see
/// [`crate::pool`]).
fn stopped(stop: &StopFlag) -> Result<(), ApiError> {
    stop.check().map_err(|e| ApiError::invalid("body", e))
}

/// [`evaluate`] that ends early once `stop` is set: the flag is checked between its parts (the
/// check, the timing curves, the torque curve; at [`MAX_WEB_PICKS`] each takes under a second).
pub(crate) fn evaluate_until(req: &LoomRequest, stop: &StopFlag) -> Result<LoomResponse, ApiError> {
    let (mut loom, pattern) = LoomSource { loom_toml: req.loom_toml.clone(), pattern: req.pattern.clone() }.read()?;
    if let Some(s) = &req.stagger_deg {
        loom = loom.with_stagger(s).map_err(|e| stagger_error(&e))?;
    }
    let picks = crate::error::check_count("picks", req.picks, 1, MAX_TIMING_PICKS)?;
    let report = check(&loom, &pattern).map_err(|e| ApiError::from_library(&e, "loom_toml"))?;
    stopped(stop)?;
    let timing = timing_curves(&loom, &pattern, req.from_pick % pattern.picks(), picks, req.step_deg)
        .map_err(|e| ApiError::from_library(&e, "loom_toml"))?;
    stopped(stop)?;
    let torque = torque_curve(&loom, &pattern)?;
    let grid = PatternGrid { shafts: pattern.shafts(), picks: pattern.picks(), rows: pattern.rows().to_vec() };
    Ok(LoomResponse { report, pattern: grid, torque, stagger_deg: loom.shedding.stagger_deg.clone(), timing })
}

/// What the stagger minimises (`--objective`).
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ObjectiveKind {
    /// Peak |torque|.
    #[default]
    Peak,
    /// RMS torque.
    Rms,
}

/// `POST /api/loom/stagger` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StaggerRequest {
    /// A loom file's text (default: `examples/rapier-loom.toml`).
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// The weave pattern (default: plain weave on the loom's frames).
    #[serde(default)]
    pub pattern: PatternSource,
    /// What to minimise.
    #[serde(default)]
    pub objective: ObjectiveKind,
    /// The least clearance to the carrier every pick must keep from entry to exit (mm;
    /// [`StaggerOptions::MIN_CLEARANCE_MM`], `loom stagger --min-clearance-mm`).
    #[serde(default = "default_min_clearance")]
    #[schemars(transform = loomkin_units::schema::bounds(StaggerOptions::MIN_CLEARANCE_MM.range))]
    pub min_clearance_mm: f64,
}

fn default_min_clearance() -> f64 {
    StaggerOptions::MIN_CLEARANCE_MM.default_value()
}

/// `POST /api/loom/stagger` answer.
#[derive(Debug, Clone, Serialize)]
pub struct StaggerResponse {
    /// The figures of `loomkin loom stagger --json`.
    pub result: StaggerResult,
    /// Torque over the repeat without stagger …
    pub torque_none: TorqueCurve,
    /// … with the two-group baseline (odd frames 0°, even frames 7.5°) …
    pub torque_two_groups: TorqueCurve,
    /// … and with the optimised stagger.
    pub torque_best: TorqueCurve,
    /// The loom file with the optimised stagger (`loom stagger -o`), when a loom file was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loom_toml: Option<String>,
    /// One line on the result.
    pub note: String,
}

/// A request's `stagger_deg` refused by the library, named by the request's key (`stagger_deg[2]`)
/// rather than the loom file's (`shedding.stagger_deg[2]`).
fn stagger_error(e: &loomkin_loom::LoomError) -> ApiError {
    use loomkin_units::FieldError;
    let file_key = "shedding.stagger_deg";
    let field = e.field().unwrap_or(file_key).replacen(file_key, "stagger_deg", 1);
    ApiError::invalid(field, e.to_string().replace(file_key, "stagger_deg"))
}

/// The stagger optimisation and its baselines.
pub fn stagger(req: &StaggerRequest) -> Result<StaggerResponse, ApiError> {
    stagger_until(req, &StopFlag::default())
}

/// [`stagger`] that ends early once `stop` is set: the search checks it before every evaluation
/// ([`loomkin_loom::optimise_stagger_with`], keeping the request's least clearance), and it is
/// checked before each torque curve.
pub(crate) fn stagger_until(req: &StaggerRequest, stop: &StopFlag) -> Result<StaggerResponse, ApiError> {
    let (loom, pattern) = LoomSource { loom_toml: req.loom_toml.clone(), pattern: req.pattern.clone() }.read()?;
    let objective = match req.objective {
        ObjectiveKind::Peak => Objective::Peak,
        ObjectiveKind::Rms => Objective::Rms,
    };
    let options = StaggerOptions { objective, min_clearance_mm: req.min_clearance_mm };
    let r = optimise_stagger_with(&loom, &pattern, &options, stop, &|_, _| {})
        .map_err(|e| ApiError::from_library(&e, "loom_toml"))?;
    let with = |s: &[f64]| -> Result<TorqueCurve, ApiError> {
        stopped(stop)?;
        let l = loom.with_stagger(s).map_err(|e| ApiError::from_library(&e, "stagger_deg"))?;
        torque_curve(&l, &pattern)
    };
    let text = req.loom_toml.as_deref().unwrap_or(LOOM_EXAMPLES[0].1);
    let loom_toml = Loom::stagger_toml(text, &r.best.stagger_deg, r.groups.as_deref())
        .map_err(|e| ApiError::from_library(&e, "loom_toml"))?;
    let note = format!(
        "peak {} → {} N·m ({} % lower; two groups 7.5°: {} %), {} evaluations",
        compact((r.none.peak_torque_n_m * 100.0).round() / 100.0),
        compact((r.best.peak_torque_n_m * 100.0).round() / 100.0),
        compact((r.peak_reduction_pct * 10.0).round() / 10.0),
        compact((r.two_groups_peak_reduction_pct * 10.0).round() / 10.0),
        r.evaluations
    );
    Ok(StaggerResponse {
        torque_none: with(&r.none.stagger_deg)?,
        torque_two_groups: with(&r.two_groups.stagger_deg)?,
        torque_best: with(&r.best.stagger_deg)?,
        loom_toml: Some(loom_toml),
        result: r,
        note,
    })
}

async fn post_evaluate(ApiJson(req): ApiJson<LoomRequest>) -> Result<ApiJson<LoomResponse>, ApiError> {
    crate::pool::heavy(move |stop| evaluate_until(&req, stop)).await.map(ApiJson)
}

async fn post_stagger(ApiJson(req): ApiJson<StaggerRequest>) -> Result<ApiJson<StaggerResponse>, ApiError> {
    crate::pool::heavy(move |stop| stagger_until(&req, stop)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(loom_toml: Option<&str>, pattern: PatternSource) -> LoomRequest {
        LoomRequest {
            loom_toml: loom_toml.map(Into::into),
            pattern,
            stagger_deg: None,
            from_pick: 0,
            picks: 2,
            step_deg: 1.0,
        }
    }

    fn twill() -> PatternSource {
        PatternSource { wif: Some(PATTERN_EXAMPLES[1].1.into()), lift_plan: None }
    }

    fn shuttle_twill() -> LoomRequest {
        req(Some(LOOM_EXAMPLES[1].1), twill())
    }

    /// The view shows what `loom check` computes, and its curves agree with the report.
    #[test]
    fn the_view_answers_what_the_library_computes() {
        let r = evaluate(&LoomRequest { picks: 4, step_deg: 0.5, ..shuttle_twill() }).unwrap();
        let loom = Loom::from_toml(LOOM_EXAMPLES[1].1).unwrap();
        let pattern = Pattern::from_wif(PATTERN_EXAMPLES[1].1).unwrap();
        let direct = check(&loom, &pattern).unwrap();
        assert_eq!(r.report.peak_torque_n_m, direct.peak_torque_n_m);
        assert_eq!(r.report.window_deg, direct.window_deg);
        assert_eq!(r.pattern.picks, 4);
        assert_eq!(r.pattern.rows, pattern.rows());
        // The sampled torque never exceeds the refined peak, and comes within 1 % of it.
        let sampled = r.torque.torque_n_m.iter().fold(0.0f64, |m, t| m.max(t.abs()));
        assert!(sampled <= r.report.peak_torque_n_m * (1.0 + 1e-9), "{sampled}");
        assert!(sampled >= 0.99 * r.report.peak_torque_n_m, "{sampled}");
        // Timing: four picks at 0.5°, every frame within half its stroke of the level shed, the shed open to the
        // carrier throughout each pick's common window.
        assert_eq!(r.timing.angle_deg.len(), 4 * 720 + 1);
        for (i, f) in r.report.frames.iter().enumerate() {
            let h = f.stroke_mm / 2.0 + 1e-9;
            assert!(r.timing.lift_mm[i].iter().all(|&y| (-h..=h).contains(&y)), "frame {i}");
        }
        for w in &r.timing.clear_window_deg {
            for (k, &t) in r.timing.angle_deg.iter().enumerate() {
                if t > w[0] + 0.5 && t < w[1] - 0.5 {
                    assert!(r.timing.open[k], "closed at {t}° inside the window {w:?}");
                }
            }
        }
    }

    /// The least clearance asked for is kept (issue 27: the optimum spent it), and one outside its
    /// range is refused naming the request's key; without it the answer is the one before.
    #[test]
    fn the_stagger_keeps_the_least_clearance_asked_for() {
        // The rapier loom weaving the 8-end satin: its free optimum spends 45 % of the clearance.
        let satin = PatternSource { wif: Some(PATTERN_EXAMPLES[2].1.into()), lift_plan: None };
        let q = |min_clearance_mm: f64| StaggerRequest {
            loom_toml: Some(LOOM_EXAMPLES[0].1.into()),
            pattern: satin.clone(),
            objective: ObjectiveKind::Peak,
            min_clearance_mm,
        };
        let free = stagger(&q(default_min_clearance())).unwrap();
        let keep = free.result.none.min_clearance_mm * 0.9;
        assert!(free.result.best.min_clearance_mm < keep, "the free optimum spends the clearance: {keep}");
        let kept = stagger(&q(keep)).unwrap();
        assert!(kept.result.best.min_clearance_mm >= keep - 1e-9, "{} < {keep}", kept.result.best.min_clearance_mm);
        assert!(kept.result.best.peak_torque_n_m >= free.result.best.peak_torque_n_m - 1e-9);
        let e = stagger(&q(-1.0)).unwrap_err();
        assert_eq!(e.field(), "min_clearance_mm", "{e}");
    }

    #[test]
    fn stagger_and_bad_inputs_are_named() {
        let q = shuttle_twill();
        let s = stagger(&StaggerRequest {
            loom_toml: q.loom_toml.clone(),
            pattern: twill(),
            objective: ObjectiveKind::Peak,
            min_clearance_mm: default_min_clearance(),
        })
        .unwrap();
        assert!(s.result.best.peak_torque_n_m <= s.result.none.peak_torque_n_m + 1e-9);
        // The stagger sent back evaluates to the optimum's peak.
        let r =
            evaluate(&LoomRequest { stagger_deg: Some(s.result.best.stagger_deg.clone()), ..shuttle_twill() }).unwrap();
        assert!(
            (r.report.peak_torque_n_m - s.result.best.peak_torque_n_m).abs() < 1e-6 * s.result.best.peak_torque_n_m
        );
        let back = Loom::from_toml(s.loom_toml.as_deref().unwrap()).unwrap();
        assert_eq!(back.frame_count(), 4);
        // A WIF whose sections disagree, both a WIF and a lift plan, a stagger of the wrong length,
        // too many picks drawn, a repeat longer than the workbench takes.
        let bad = PatternSource { wif: Some("[WIF]\nVersion=1.1\n".into()), lift_plan: None };
        let e = evaluate(&req(q.loom_toml.as_deref(), bad)).unwrap_err();
        assert_eq!(e.field(), "pattern.wif", "{e}");
        let both = PatternSource { lift_plan: Some("1\n2\n".into()), ..twill() };
        assert_eq!(evaluate(&req(None, both)).unwrap_err().field(), "pattern");
        let e = evaluate(&LoomRequest { stagger_deg: Some(vec![0.0; 3]), ..shuttle_twill() }).unwrap_err();
        assert_eq!(e.field(), "stagger_deg", "{e}");
        assert!(!e.to_string().contains("shedding."), "named by the request's key: {e}");
        let mut far = vec![0.0; 4];
        far[2] = 1e9;
        let e = evaluate(&LoomRequest { stagger_deg: Some(far), ..shuttle_twill() }).unwrap_err();
        assert_eq!(e.field(), "stagger_deg[2]", "{e}");
        assert!(e.to_string().starts_with("stagger_deg[2] = 1e9 is out of range"), "{e}");
        assert_eq!(evaluate(&LoomRequest { picks: 9, ..shuttle_twill() }).unwrap_err().field(), "picks");
        let long = PatternSource { wif: None, lift_plan: Some("1\n".repeat(1001)) };
        assert_eq!(evaluate(&req(None, long)).unwrap_err().field(), "pattern");
    }
}
