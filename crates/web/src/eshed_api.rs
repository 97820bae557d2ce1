//! The servo shedding view (issue 31): one servo motor per heald frame on a shared DC bus — the
//! frames × picks lift grid from the pattern, every frame's motor torque and the bus power over the
//! repeat, the per-frame table (peak and RMS torque, peak speed, `motor_ok` with its margins) and the
//! optimiser of `loom servo --optimize` with the design before and after. `POST /api/loom/servo`
//! answers exactly what `loomkin loom servo --json [--optimize]` prints (the same library calls);
//! `POST /api/loom/servo/view` is the view's: the same figures under `result`, with the curves.

use crate::loom_api::{LoomSource, ObjectiveKind, PatternSource};
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::post;
use loomkin_eshed::{Curves, FrameSetup, ServoReport};
use loomkin_loom::{
    Loom, Motion, Objective, Pattern, ServoOptimum, ServoOptions, StaggerOptions, optimise_servo_with, servo_curves_of,
    servo_setups, servo_study,
};
use loomkin_units::StopFlag;
use serde::{Deserialize, Serialize};

/// The servo-shedding example loom the routes use when a request gives no loom file
/// (`examples/servo-shedding-loom.toml`).
pub const SERVO_SHED_EXAMPLE: &str = include_str!("../../../examples/servo-shedding-loom.toml");

/// Most points of the curves over the repeat sent to the page (the report's extremes are located
/// exactly whatever this).
pub const MAX_SERVO_SHED_POINTS: usize = 4000;

pub(crate) fn routes() -> Router {
    Router::new().route("/loom/servo", post(post_servo)).route("/loom/servo/view", post(post_view))
}

/// `POST /api/loom/servo` and `/api/loom/servo/view` request: `loomkin loom servo LOOM.toml
/// [--wif|--lift-plan] [--optimize [--objective]]`.
#[derive(Debug, Clone, Deserialize, PartialEq, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ServoShedRequest {
    /// A loom file's text with `[shedding] drive = "servo"` (default:
    /// `examples/servo-shedding-loom.toml`).
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// The weave pattern (default: plain weave on the loom's frames).
    #[serde(default)]
    pub pattern: PatternSource,
    /// Search every frame's stagger and motion angle (`--optimize`): a heavy computation.
    #[serde(default)]
    pub optimize: bool,
    /// What the search minimises (`--objective`): the peak bus power or the worst frame's RMS torque.
    #[serde(default)]
    pub objective: ObjectiveKind,
    /// The least clearance to the carrier the search keeps in every pick from entry to exit, mm
    /// (`--min-clearance-mm`; [`loomkin_loom::StaggerOptions::MIN_CLEARANCE_MM`]; the design's own
    /// when it keeps less).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(loomkin_loom::StaggerOptions::MIN_CLEARANCE_MM.range))]
    pub min_clearance_mm: Option<f64>,
}

/// `loomkin loom servo --json`: the study, or with `optimize` the optimum (its gain, then the study
/// of the optimised plans).
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum ServoShedResult {
    /// The study of the loom file's design.
    Study(Box<ServoReport>),
    /// The optimum (`--optimize`).
    Optimum(Box<ServoOptimum>),
}

/// The frames' lifts over the repeat, as the servos follow them.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct LiftGrid {
    /// Frames (front first).
    pub frames: usize,
    /// Picks in the repeat.
    pub picks: usize,
    /// `up[i][p]`: frame `i` (front first) raised at pick `p`.
    pub up: Vec<Vec<bool>>,
}

/// Every frame's motor torque and the bus power over the repeat.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ServoShedCurves {
    /// Main-shaft angle over the repeat, deg (0 = the first pick's beat-up).
    pub angle_deg: Vec<f64>,
    /// Per frame (front first): the motor torque, N·m.
    pub torque_n_m: Vec<Vec<f64>>,
    /// The bus power, W.
    pub bus_power_w: Vec<f64>,
}

/// `POST /api/loom/servo/view` answer.
#[derive(Debug, Clone, Serialize)]
pub struct ServoShedView {
    /// The loom's name (the file's `name`).
    pub loom: String,
    /// `loomkin loom servo --json` (with `optimize`: `--optimize --json`).
    pub result: ServoShedResult,
    /// The frames' lifts.
    pub lifts: LiftGrid,
    /// The curves of the design shown (the optimum when optimised).
    pub curves: ServoShedCurves,
    /// With `optimize`: the curves of the loom file's design, before the search.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curves_before: Option<ServoShedCurves>,
}

fn lib(e: loomkin_loom::LoomError) -> ApiError {
    ApiError::from_library(&e, "loom_toml")
}

fn read(req: &ServoShedRequest) -> Result<(Loom, Pattern), ApiError> {
    let text = req.loom_toml.clone().unwrap_or_else(|| SERVO_SHED_EXAMPLE.to_string());
    LoomSource { loom_toml: Some(text), pattern: req.pattern.clone() }.read()
}

/// The study, or the optimum, and the plans it shows.
fn study(
    loom: &Loom,
    pattern: &Pattern,
    req: &ServoShedRequest,
    stop: &StopFlag,
) -> Result<(ServoShedResult, Vec<FrameSetup>), ApiError> {
    if req.optimize {
        let objective = match req.objective {
            ObjectiveKind::Peak => Objective::Peak,
            ObjectiveKind::Rms => Objective::Rms,
        };
        // Stopped (the client went away, or the budget is spent): the stop's refusal, as every heavy route's.
        let mut options = ServoOptions::new(objective);
        if let Some(v) = req.min_clearance_mm {
            options.min_clearance_mm = StaggerOptions::MIN_CLEARANCE_MM.check(v)?;
        }
        let o = optimise_servo_with(loom, pattern, &options, stop, &|_, _| {})
            .map_err(|e| if stop.is_set() { ApiError::invalid("body", e) } else { lib(e) })?;
        let setups = o.setups.clone();
        return Ok((ServoShedResult::Optimum(Box::new(o)), setups));
    }
    let r = servo_study(loom, pattern).map_err(lib)?;
    Ok((ServoShedResult::Study(Box::new(r)), servo_setups(loom, pattern, None, None).map_err(lib)?))
}

/// `loomkin loom servo --json [--optimize]`.
pub fn loom_servo(req: &ServoShedRequest) -> Result<ServoShedResult, ApiError> {
    servo_until(req, &StopFlag::default())
}

fn servo_until(req: &ServoShedRequest, stop: &StopFlag) -> Result<ServoShedResult, ApiError> {
    let (loom, pattern) = read(req)?;
    Ok(study(&loom, &pattern, req, stop)?.0)
}

/// The view's answer: [`loom_servo`] with the lifts and the curves.
pub fn loom_servo_view(req: &ServoShedRequest) -> Result<ServoShedView, ApiError> {
    view_until(req, &StopFlag::default())
}

/// The curves of `setups`: one a degree of the repeat, at most [`MAX_SERVO_SHED_POINTS`].
fn curves_of(loom: &Loom, setups: &[FrameSetup], repeat_deg: f64) -> Result<ServoShedCurves, ApiError> {
    let points = ((repeat_deg as usize) + 1).clamp(2, MAX_SERVO_SHED_POINTS);
    let c: Curves = servo_curves_of(loom, setups, points).map_err(lib)?;
    let clean = |v: Vec<f64>| v.into_iter().map(finite).collect::<Vec<_>>();
    Ok(ServoShedCurves {
        angle_deg: c.angle_deg,
        torque_n_m: c.torque_n_m.into_iter().map(clean).collect(),
        bus_power_w: clean(c.bus_power_w),
    })
}

/// [`loom_servo_view`] that ends early once `stop` is set (the optimiser checks it before every
/// evaluation; it is checked between the parts).
pub(crate) fn view_until(req: &ServoShedRequest, stop: &StopFlag) -> Result<ServoShedView, ApiError> {
    let (loom, pattern) = read(req)?;
    let (result, setups) = study(&loom, &pattern, req, stop)?;
    stop.check().map_err(|e| ApiError::invalid("body", e))?;
    let report = match &result {
        ServoShedResult::Study(r) => r.as_ref(),
        ServoShedResult::Optimum(o) => &o.report,
    };
    let curves = curves_of(&loom, &setups, report.repeat_deg)?;
    let curves_before = if req.optimize {
        let before = servo_setups(&loom, &pattern, None, None).map_err(lib)?;
        Some(curves_of(&loom, &before, report.repeat_deg)?)
    } else {
        None
    };
    let motion = Motion::new(&loom, &pattern).map_err(lib)?;
    let picks = motion.picks();
    let up = (0..loom.frame_count()).map(|i| (0..picks).map(|p| motion.is_up(i, p as i64)).collect()).collect();
    Ok(ServoShedView {
        loom: loom.name.clone(),
        result,
        lifts: LiftGrid { frames: loom.frame_count(), picks, up },
        curves,
        curves_before,
    })
}

async fn post_servo(ApiJson(req): ApiJson<ServoShedRequest>) -> Result<ApiJson<ServoShedResult>, ApiError> {
    crate::pool::heavy(move |stop| servo_until(&req, stop)).await.map(ApiJson)
}

async fn post_view(ApiJson(req): ApiJson<ServoShedRequest>) -> Result<ApiJson<ServoShedView>, ApiError> {
    crate::pool::heavy(move |stop| view_until(&req, stop)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loom_api::{LOOM_EXAMPLES, PATTERN_EXAMPLES};

    fn twill() -> ServoShedRequest {
        ServoShedRequest {
            pattern: PatternSource { wif: Some(PATTERN_EXAMPLES[1].1.into()), lift_plan: None },
            ..Default::default()
        }
    }

    /// The view answers what `loom servo` computes, and its curves agree with the report: no
    /// sampled torque above a frame's located peak nor sampled bus power above the located peak,
    /// the lift grid the pattern's on the loom's frames.
    #[test]
    fn the_view_answers_what_the_library_computes() {
        let v = loom_servo_view(&twill()).unwrap();
        let loom = Loom::from_toml(SERVO_SHED_EXAMPLE).unwrap();
        let pattern = loomkin_loom::Pattern::from_wif(PATTERN_EXAMPLES[1].1).unwrap();
        let direct = servo_study(&loom, &pattern).unwrap();
        let ServoShedResult::Study(r) = &v.result else { panic!("a study was asked for") };
        assert_eq!(serde_json::to_value(r).unwrap(), serde_json::to_value(&direct).unwrap());
        assert!(v.curves_before.is_none());
        let c = &v.curves;
        assert_eq!(c.torque_n_m.len(), direct.frames.len());
        for (f, t) in direct.frames.iter().zip(&c.torque_n_m) {
            let sampled = t.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(
                sampled <= f.peak_torque_n_m * (1.0 + 1e-9) + 1e-12,
                "frame {}: {sampled} > {}",
                f.frame,
                f.peak_torque_n_m
            );
        }
        let bus = c.bus_power_w.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(bus <= direct.peak_bus_power_w * (1.0 + 1e-9), "{bus} > {}", direct.peak_bus_power_w);
        assert!(bus >= 0.95 * direct.peak_bus_power_w, "{bus} far below {}", direct.peak_bus_power_w);
        assert_eq!((c.angle_deg[0], *c.angle_deg.last().unwrap()), (0.0, direct.repeat_deg));
        // The lifts: the twill's four shafts on the loom's frames, each pick's raised frames.
        let motion = Motion::new(&loom, &pattern).unwrap();
        assert_eq!((v.lifts.frames, v.lifts.picks), (loom.frame_count(), 4));
        for (i, row) in v.lifts.up.iter().enumerate() {
            assert!(row.iter().enumerate().all(|(p, &u)| u == motion.is_up(i, p as i64)));
        }
    }

    /// The optimum: its figures are `optimise_servo`'s, it lowers the objective, and the view
    /// sends the design before it as well.
    #[test]
    fn the_optimum_before_and_after() {
        let req = ServoShedRequest { optimize: true, ..twill() };
        let v = loom_servo_view(&req).unwrap();
        let ServoShedResult::Optimum(o) = &v.result else { panic!("an optimum was asked for") };
        assert!(o.peak_bus_power_w_after <= o.peak_bus_power_w_before);
        let before = v.curves_before.as_ref().unwrap();
        let study = loom_servo_view(&twill()).unwrap();
        assert_eq!(before, &study.curves, "the curves before are the loom file's design");
        let peak = |c: &ServoShedCurves| c.bus_power_w.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(peak(&v.curves) <= o.peak_bus_power_w_after * (1.0 + 1e-9));
        assert_eq!(serde_json::to_value(&v.result).unwrap(), serde_json::to_value(loom_servo(&req).unwrap()).unwrap());
    }

    #[test]
    fn bad_inputs_are_named() {
        let dobby = ServoShedRequest { loom_toml: Some(LOOM_EXAMPLES[0].1.into()), ..twill() };
        let e = loom_servo_view(&dobby).unwrap_err();
        assert_eq!(e.field(), "shedding.drive", "{e}");
        let e = loom_servo(&ServoShedRequest { loom_toml: Some("[shedding]".into()), ..twill() }).unwrap_err();
        assert_eq!(e.field(), "loom_toml", "{e}");
        let stop = StopFlag::default();
        stop.stop();
        let e = view_until(&ServoShedRequest { optimize: true, ..twill() }, &stop).unwrap_err();
        assert_eq!(e.field(), "body", "{e}");
    }
}
