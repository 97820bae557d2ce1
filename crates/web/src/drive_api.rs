//! The drive view (issue 29): the loom's main shaft — the reduced inertia J(φ) of every mechanism
//! and the total, the shaft's speed ω(φ) and the motor and load torques under the loom file's motor
//! with a flywheel, the speed ripple against the loom's speed, and the loom seen from the side (crank,
//! rod, sword and reed, the heald frames, the shed) at every angle of the animation. The numbers are
//! those of `loomkin drive inertia` and `drive ripple` ([`loomkin_loom::LoomShaft`],
//! [`loomkin_drive::solve`]); the positions of the side view are the library's exact kinematics
//! ([`loomkin_loom::LoomShaft::side_view`]), sampled here, never recomputed in the page.

use crate::loom_api::{LoomSource, PatternSource};
use crate::series::finite;
use crate::{ApiError, ApiJson};
use axum::Router;
use axum::routing::post;
use loomkin_drive::ripple::{FLYWHEEL_KG_M2, STEP_DEG, SWEEP_SPEED_RATIO, SWEEP_STEP_DEG};
use loomkin_drive::{RippleReport, Table, solve};
use loomkin_loom::{InertiaReport, Loom, LoomShaft, Motion};
use loomkin_units::StopFlag;
use serde::{Deserialize, Serialize};

/// Most points of the curves over the repeat sent to the page (the report's extremes are located
/// on the solver's own grid whatever this).
pub const MAX_DRIVE_POINTS: usize = 2000;

/// Most angles of the side view's animation over the repeat.
pub const MAX_SIDE_ANGLES: usize = 1440;

/// Fewest speeds of the ripple-against-speed sweep (its two ends).
pub const MIN_DRIVE_SWEEP: usize = 2;

/// Most speeds of the ripple-against-speed sweep.
pub const MAX_DRIVE_SWEEP: usize = 41;

/// Speeds of the sweep when a request does not say.
pub const DEFAULT_DRIVE_SWEEP: usize = 11;

pub(crate) fn routes() -> Router {
    Router::new().route("/drive/evaluate", post(post_evaluate))
}

/// `POST /api/drive/evaluate` request.
#[derive(Debug, Clone, Deserialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DriveRequest {
    /// A loom file's text (default: `examples/rapier-loom.toml`); its `[drive]` table gives the
    /// rotating parts, the friction and the motor.
    #[serde(default)]
    pub loom_toml: Option<String>,
    /// The weave pattern (default: plain weave on the loom's frames).
    #[serde(default)]
    pub pattern: PatternSource,
    /// Inertia added to the main shaft (kg·m²; default: the file's `[drive] flywheel_kg_m2`).
    #[serde(default)]
    #[schemars(transform = loomkin_units::schema::bounds(FLYWHEEL_KG_M2.range))]
    pub flywheel_kg_m2: Option<f64>,
    /// Step of the speed-ripple grid (deg).
    #[serde(default = "default_step")]
    #[schemars(transform = loomkin_units::schema::bounds(STEP_DEG.range))]
    pub step_deg: f64,
    /// Speeds of the ripple-against-speed sweep, [`MIN_DRIVE_SWEEP`] … [`MAX_DRIVE_SWEEP`]: evenly
    /// over [`SWEEP_SPEED_RATIO`] of the loom's speed, on a grid of [`SWEEP_STEP_DEG`] (or this
    /// request's `step_deg` when coarser).
    #[serde(default = "default_sweep")]
    #[schemars(transform = crate::schema::count(MIN_DRIVE_SWEEP, MAX_DRIVE_SWEEP))]
    pub sweep_points: usize,
    /// Whether to send the side view's animation (it does not depend on the flywheel: a page moving
    /// the flywheel leaves it out).
    #[serde(default = "default_side")]
    pub side: bool,
}

fn default_step() -> f64 {
    STEP_DEG.default_value()
}

fn default_sweep() -> usize {
    DEFAULT_DRIVE_SWEEP
}

fn default_side() -> bool {
    true
}

/// The curves over the repeat, at most [`MAX_DRIVE_POINTS`] angles.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct DriveCurves {
    /// Main-shaft angle over the repeat (deg).
    pub angle_deg: Vec<f64>,
    /// Each mechanism's J (kg·m²), in the order of the report's `mechanisms`.
    pub j_kg_m2: Vec<Vec<f64>>,
    /// The total J, flywheel included (kg·m²).
    pub j_total_kg_m2: Vec<f64>,
    /// The total dJ/dφ (kg·m²/rad).
    pub dj_total_kg_m2_per_rad: Vec<f64>,
    /// The shaft's speed (rpm).
    pub speed_rpm: Vec<f64>,
    /// The motor's torque at the main shaft (N·m).
    pub motor_torque_n_m: Vec<f64>,
    /// The load torque of the mechanisms' non-inertial forces (N·m).
    pub load_torque_n_m: Vec<f64>,
}

/// The speed ripple against the loom's speed, the flywheel kept.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct RippleSweep {
    /// Loom speed the motor is built for (rpm).
    pub speed_rpm: Vec<f64>,
    /// The mean speed the shaft runs at (rpm; `null` where the motor cannot keep it turning).
    pub mean_speed_rpm: Vec<Option<f64>>,
    /// The speed ripple (%; `null` where the motor cannot keep the shaft turning).
    pub speed_ripple_pct: Vec<Option<f64>>,
}

/// The sley's joints over the animation's angles (mm behind and over the fell).
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct SleyPath {
    /// The crank centre (fixed).
    pub crank_centre: [f64; 2],
    /// The rocking shaft (fixed).
    pub rocking_shaft: [f64; 2],
    /// The crank pin at each angle.
    pub crank_pin: Vec<[f64; 2]>,
    /// The sword's pin at each angle.
    pub sword_pin: Vec<[f64; 2]>,
    /// The reed's beating point at each angle.
    pub reed: Vec<[f64; 2]>,
}

/// The loom seen from the side over the repeat ([`LoomShaft::side_view`]), mm: x behind the fell,
/// y over it.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct SideAnimation {
    /// The animation's main-shaft angles over the repeat (deg).
    pub angle_deg: Vec<f64>,
    /// The sley, when the loom file has one.
    pub sley: Option<SleyPath>,
    /// Each frame's heald eyes: distance behind the fell.
    pub heald_x_mm: Vec<f64>,
    /// Each frame's heald eyes' height over the fell at each angle (frame-major).
    pub heald_y_mm: Vec<Vec<f64>>,
    /// The back rest: distance behind the fell and height over it.
    pub back_rest_mm: [f64; 2],
    /// The reed's distance from the fell at weft insertion (the loom file's geometry), mm.
    pub reed_mm: f64,
}

/// `POST /api/drive/evaluate` answer.
#[derive(Debug, Clone, Serialize)]
pub struct DriveResponse {
    /// The loom's name (the file's `name`).
    pub loom: String,
    /// The loom's speed (rpm).
    pub speed_rpm: f64,
    /// `loomkin drive inertia --json`.
    pub inertia: InertiaReport,
    /// `loomkin drive ripple --json` at this flywheel.
    pub ripple: RippleReport,
    /// The curves over the repeat.
    pub curves: DriveCurves,
    /// The ripple against the loom's speed.
    pub sweep: RippleSweep,
    /// The side view's animation, when asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side: Option<SideAnimation>,
}

/// `n` angles evenly over `[0, period)`, `n` the fewest whose step is at least `min_step_deg` and
/// at most `max` of them.
fn grid(period: f64, max: usize, min_step_deg: f64) -> Vec<f64> {
    let n = ((period / min_step_deg).floor() as usize).clamp(1, max);
    (0..n).map(|k| period * k as f64 / n as f64).collect()
}

/// The stop flag's refusal.
fn stopped(stop: &StopFlag) -> Result<(), ApiError> {
    stop.check().map_err(|e| ApiError::invalid("body", e))
}

/// Evaluates the drive.
pub fn evaluate(req: &DriveRequest) -> Result<DriveResponse, ApiError> {
    evaluate_until(req, &StopFlag::default())
}

/// [`evaluate`] that ends early once `stop` is set: checked between its parts and between the
/// sweep's speeds.
pub(crate) fn evaluate_until(req: &DriveRequest, stop: &StopFlag) -> Result<DriveResponse, ApiError> {
    let (loom, pattern) = LoomSource { loom_toml: req.loom_toml.clone(), pattern: req.pattern.clone() }.read()?;
    STEP_DEG.check(req.step_deg)?;
    let points = crate::error::check_count("sweep_points", req.sweep_points, MIN_DRIVE_SWEEP, MAX_DRIVE_SWEEP)?;
    let flywheel = match req.flywheel_kg_m2 {
        Some(v) => FLYWHEEL_KG_M2.check(v)?,
        None => loom.drive.flywheel_kg_m2,
    };
    let lib = |e: loomkin_loom::LoomError| ApiError::from_library(&e, "loom_toml");
    let motion = Motion::new(&loom, &pattern).map_err(lib)?;
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let inertia = shaft.report(loomkin_loom::Drive::STEP_DEG.default_value()).map_err(lib)?;
    stopped(stop)?;
    let table = Table::new(&shaft, req.step_deg).map_err(|e| ApiError::from_library(&e, "step_deg"))?;
    let motor_at =
        |rpm: f64| loom.drive.motor.build(rpm, "drive.").map_err(|e| ApiError::from_library(&e, "loom_toml"));
    let sol =
        solve(&table, &motor_at(loom.speed.rpm())?, flywheel).map_err(|e| ApiError::from_library(&e, "loom_toml"))?;
    stopped(stop)?;
    let period = motion.repeat_deg();
    let mut curves = DriveCurves { j_kg_m2: vec![Vec::new(); shaft.mechanism_names().len()], ..DriveCurves::default() };
    for th in grid(period, MAX_DRIVE_POINTS, req.step_deg) {
        let phi = th.to_radians();
        curves.angle_deg.push(th);
        for (k, (j, _)) in shaft.mechanism_inertia(th).into_iter().enumerate() {
            curves.j_kg_m2[k].push(finite(j));
        }
        let (j, dj) = shaft.inertia_at(th);
        curves.j_total_kg_m2.push(finite(j + flywheel));
        curves.dj_total_kg_m2_per_rad.push(finite(dj));
        curves.speed_rpm.push(finite(loomkin_units::rpm_from_rad_per_s(sol.omega_at(phi))));
        curves.motor_torque_n_m.push(finite(sol.motor_torque_at(phi)));
        curves.load_torque_n_m.push(finite(shaft.load_at(th)));
    }
    // The sweep on its own grid (coarser unless the request's is): the same J and load.
    let coarse =
        Table::new(&shaft, SWEEP_STEP_DEG.max(req.step_deg)).map_err(|e| ApiError::from_library(&e, "step_deg"))?;
    let sweep = ripple_sweep(&loom, &coarse, flywheel, points, stop)?;
    let side = if req.side { Some(side_animation(&loom, &shaft, period)) } else { None };
    Ok(DriveResponse {
        loom: loom.name.clone(),
        speed_rpm: loom.speed.rpm(),
        inertia,
        ripple: sol.report.clone(),
        curves,
        sweep,
        side,
    })
}

/// The ripple at `points` loom speeds over [`SWEEP_SPEED_RATIO`] of the loom's, the motor built for
/// each (the table of J and the load does not depend on the speed: it is built once).
fn ripple_sweep(
    loom: &Loom,
    table: &Table<'_, LoomShaft<'_>>,
    flywheel: f64,
    points: usize,
    stop: &StopFlag,
) -> Result<RippleSweep, ApiError> {
    let [lo, hi] = SWEEP_SPEED_RATIO.map(|r| r * loom.speed.rpm());
    let mut out = RippleSweep::default();
    for k in 0..points {
        stopped(stop)?;
        let rpm = if k + 1 == points { hi } else { lo + (hi - lo) * k as f64 / (points - 1) as f64 };
        let r = loom.drive.motor.build(rpm, "drive.").ok().and_then(|m| solve(table, &m, flywheel).ok());
        out.speed_rpm.push(rpm);
        out.mean_speed_rpm.push(r.as_ref().map(|s| finite(s.report.mean_speed_rpm)));
        out.speed_ripple_pct.push(r.as_ref().map(|s| finite(s.report.speed_ripple_pct)));
    }
    Ok(out)
}

/// The side view at the animation's angles over the repeat (a degree apart at least).
fn side_animation(loom: &Loom, shaft: &LoomShaft<'_>, period: f64) -> SideAnimation {
    let angles = grid(period, MAX_SIDE_ANGLES, 1.0);
    let views: Vec<_> = angles.iter().map(|&th| shaft.side_view(th)).collect();
    let frames = loom.frame_count();
    let first = views.first().cloned();
    let sley = first.as_ref().and_then(|v| v.sley).map(|s0| SleyPath {
        crank_centre: s0.crank_centre,
        rocking_shaft: s0.rocking_shaft,
        crank_pin: views.iter().filter_map(|v| v.sley.map(|s| s.crank_pin)).collect(),
        sword_pin: views.iter().filter_map(|v| v.sley.map(|s| s.sword_pin)).collect(),
        reed: views.iter().filter_map(|v| v.sley.map(|s| s.reed)).collect(),
    });
    SideAnimation {
        heald_x_mm: first.as_ref().map_or_else(Vec::new, |v| v.heald_eyes_mm.iter().map(|e| e[0]).collect()),
        heald_y_mm: (0..frames).map(|i| views.iter().map(|v| finite(v.heald_eyes_mm[i][1])).collect()).collect(),
        back_rest_mm: first.as_ref().map_or([0.0, 0.0], |v| v.back_rest_mm),
        reed_mm: loomkin_units::mm_from_m(loom.geometry.reed_m),
        angle_deg: angles,
        sley,
    }
}

async fn post_evaluate(ApiJson(req): ApiJson<DriveRequest>) -> Result<ApiJson<DriveResponse>, ApiError> {
    crate::pool::heavy(move |stop| evaluate_until(&req, stop)).await.map(ApiJson)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loom_api::{LOOM_EXAMPLES, PATTERN_EXAMPLES};
    use loomkin_loom::Pattern;

    fn rapier_point() -> DriveRequest {
        DriveRequest {
            loom_toml: Some(LOOM_EXAMPLES[0].1.into()),
            pattern: PatternSource { wif: Some(PATTERN_EXAMPLES[4].1.into()), lift_plan: None },
            flywheel_kg_m2: None,
            step_deg: default_step(),
            sweep_points: 5,
            side: true,
        }
    }

    /// The view answers what `drive inertia` and `drive ripple` compute, and its curves agree with
    /// the reports (the sampled extremes within the located ones).
    #[test]
    fn the_view_answers_what_the_library_computes() {
        let q = rapier_point();
        let r = evaluate(&q).unwrap();
        let loom = Loom::from_toml(LOOM_EXAMPLES[0].1).unwrap();
        let pattern = Pattern::from_wif(PATTERN_EXAMPLES[4].1).unwrap();
        let motion = Motion::new(&loom, &pattern).unwrap();
        let shaft = LoomShaft::new(&loom, &motion, &pattern);
        assert_eq!(r.inertia, shaft.report(loomkin_loom::Drive::STEP_DEG.default_value()).unwrap());
        let table = Table::new(&shaft, q.step_deg).unwrap();
        let motor = loom.drive.motor.build(loom.speed.rpm(), "drive.").unwrap();
        let direct = solve(&table, &motor, loom.drive.flywheel_kg_m2).unwrap();
        assert_eq!(r.ripple, direct.report);
        let c = &r.curves;
        let (lo, hi) = c.speed_rpm.iter().fold((f64::INFINITY, 0.0f64), |(a, b), w| (a.min(*w), b.max(*w)));
        assert!(lo >= r.ripple.min_speed_rpm - 1e-9 && hi <= r.ripple.max_speed_rpm + 1e-9, "{lo} {hi}");
        // The total is the mechanisms' sum (with the flywheel, here none).
        for k in 0..c.angle_deg.len() {
            let sum: f64 = c.j_kg_m2.iter().map(|j| j[k]).sum();
            assert!((sum - c.j_total_kg_m2[k]).abs() <= 1e-12 * sum);
        }
        // The sweep's point at the loom's speed is the report's (on its coarser grid: within 2e-8;
        // the rapier's cam sley, 70° moves at 500 rpm, puts the 1° grid 1.4e-8 from the 0.1° one).
        let mid = r.sweep.speed_rpm.iter().position(|s| (s - loom.speed.rpm()).abs() < 1e-9).unwrap();
        let at = r.sweep.speed_ripple_pct[mid].unwrap();
        assert!((at - r.ripple.speed_ripple_pct).abs() <= 2e-8 * at, "{at} vs {}", r.ripple.speed_ripple_pct);
        // The side view: the reed at the fell at beat-up, the heald eyes at their frames' lifts.
        let side = r.side.unwrap();
        let sley = side.sley.unwrap();
        let k0 = side.angle_deg.iter().position(|a| *a == 0.0).unwrap();
        assert!(sley.reed[k0][0].abs() < 1e-9 && sley.reed[k0][1].abs() < 1e-9);
        let k = side.angle_deg.len() / 3;
        let v = shaft.side_view(side.angle_deg[k]);
        assert_eq!(sley.crank_pin[k], v.sley.unwrap().crank_pin);
        assert_eq!(side.heald_y_mm[5][k], v.heald_eyes_mm[5][1]);
        // A flywheel lowers the ripple, and the answer leaves the animation out when asked.
        let f = evaluate(&DriveRequest { flywheel_kg_m2: Some(2.0), side: false, ..q }).unwrap();
        assert!(f.ripple.speed_ripple_pct < r.ripple.speed_ripple_pct && f.side.is_none());
    }

    #[test]
    fn bad_inputs_are_named() {
        let e = evaluate(&DriveRequest { flywheel_kg_m2: Some(-1.0), ..rapier_point() }).unwrap_err();
        assert_eq!(e.field(), "flywheel_kg_m2", "{e}");
        let e = evaluate(&DriveRequest { step_deg: 0.0, ..rapier_point() }).unwrap_err();
        assert_eq!(e.field(), "step_deg", "{e}");
        let e = evaluate(&DriveRequest { sweep_points: 1, ..rapier_point() }).unwrap_err();
        assert_eq!(e.field(), "sweep_points", "{e}");
        // A stopped computation ends with the stop's refusal.
        let stop = StopFlag::default();
        stop.stop();
        assert_eq!(evaluate_until(&rapier_point(), &stop).unwrap_err().field(), "body");
    }
}
