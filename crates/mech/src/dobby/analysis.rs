//! Task 1, analysis: the cam Γ is given; find φ3, S53, φ6 and their rates over a revolution.
//!
//! Loop (2), `r(p) + l3·e(φ3 + α) = l2·e(φ2)` with the roller centre B = r(p) on Γ, has no closed
//! form for a general cam: it is traced by Newton with continuation ([`LoopSystem::trace`]) in the
//! unknowns `(p, φ3)`. Loop (3) then follows in closed form ([`ModulatorState`]).

use super::cam::Cam;
use super::checks::{Warning, counter_cam_fold};
use super::geometry::ModulatorGeometry;
use super::kinematics::{ArmAngles, ModulatorState, state_from_phi3};
use super::refine::{CHECK_STEP_DEG, Extreme, Revolution, check_grid, refined_turn_max};
use super::report::{CamChecks, CamProfile, check_states, undercut};
use crate::newton::{LoopState, NewtonOptions};
use crate::planar::{Vec2, e, wrap_pi};
use crate::vloop::{LoopSystem, Scalar, VectorLoop};
use crate::{MechError, Result};
use loomkin_units::{Field, Range, ShaftSpeed};
use nalgebra::SVector;
use serde::Serialize;

/// Settings of an analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisOptions {
    /// Step of the input angle (deg), 0.01…30; rounded so that a whole number of steps makes 360°.
    pub step_deg: f64,
    /// First input angle (deg); the paper starts at 0.
    pub start_deg: f64,
    /// Constant input speed ω2 (rad/s); the paper's 1 rad/s makes rates read as ratios.
    pub input_speed_rad_s: f64,
    /// Roller radius (m) for the undercut check and the groove walls, if any.
    pub roller_m: Option<f64>,
    /// Pressure angles above this (deg) raise a warning.
    pub pressure_limit_deg: f64,
    /// Newton settings.
    pub newton: NewtonOptions,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        Self {
            step_deg: 1.0,
            start_deg: 0.0,
            input_speed_rad_s: 1.0,
            roller_m: None,
            pressure_limit_deg: 60.0,
            newton: NewtonOptions::default(),
        }
    }
}

/// One row of an analysis (time rates at the constant input speed).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AnalysisRow {
    /// Input angle φ2 (deg).
    pub phi2_deg: f64,
    /// Time since the start (s).
    pub t_s: f64,
    /// Parameter p of the cam curve at B: the angle p (rad) of `x = a cos p, y = b sin p` for an
    /// ellipse, the chord length (m) from the first point for a point table.
    pub cam_param: f64,
    /// Slot angle φ3 (deg), continuous.
    pub phi3_deg: f64,
    /// Output angle φ6 (deg), continuous.
    pub phi6_deg: f64,
    /// Slider position S53 = |AD| (m).
    pub s53_m: f64,
    /// ω3 (rad/s).
    pub omega3_rad_s: f64,
    /// ω6 (rad/s).
    pub omega6_rad_s: f64,
    /// Slider speed dS53/dt (m/s).
    pub v53_m_s: f64,
    /// ε3 (rad/s²).
    pub eps3_rad_s2: f64,
    /// ε6 (rad/s²).
    pub eps6_rad_s2: f64,
    /// Slider acceleration (m/s²).
    pub a53_m_s2: f64,
    /// Roller centre B x (m).
    pub b_x_m: f64,
    /// Roller centre B y (m).
    pub b_y_m: f64,
    /// Roller centre C x (m).
    pub c_x_m: f64,
    /// Roller centre C y (m).
    pub c_y_m: f64,
    /// Output pressure angle (deg).
    pub mu_out_deg: f64,
    /// Pressure angle at roller B (deg).
    pub mu_b_deg: f64,
    /// Pressure angle at roller C (deg).
    pub mu_c_deg: f64,
    /// Signed curvature of Γ at B along the travel (1/m).
    pub kappa_b_1_m: f64,
    /// Signed curvature of Γ′ at C along the travel (1/m).
    pub kappa_c_1_m: f64,
}

impl AnalysisRow {
    /// The row of state `s`, whose crank pin is `a` ([`ModulatorState::a`]).
    pub(crate) fn new(s: &ModulatorState, a: Vec2, cam_param: f64, t_s: f64, w2: f64) -> Self {
        let mu_bc = s.mu_bc_deg_at(a);
        Self {
            phi2_deg: s.phi2.to_degrees(),
            t_s,
            cam_param,
            phi3_deg: s.phi3[0].to_degrees(),
            phi6_deg: s.phi6[0].to_degrees(),
            s53_m: s.s53[0],
            omega3_rad_s: s.phi3[1] * w2,
            omega6_rad_s: s.phi6[1] * w2,
            v53_m_s: s.s53[1] * w2,
            eps3_rad_s2: s.phi3[2] * w2 * w2,
            eps6_rad_s2: s.phi6[2] * w2 * w2,
            a53_m_s2: s.s53[2] * w2 * w2,
            b_x_m: s.b[0].x,
            b_y_m: s.b[0].y,
            c_x_m: s.c[0].x,
            c_y_m: s.c[0].y,
            mu_out_deg: s.mu_out_deg(),
            mu_b_deg: mu_bc[0],
            mu_c_deg: mu_bc[1],
            kappa_b_1_m: s.kappa_b(),
            kappa_c_1_m: s.kappa_c(),
        }
    }
}

/// Summary of an analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AnalysisSummary {
    /// The cam.
    pub cam: String,
    /// Geometry used.
    pub geometry: ModulatorGeometry,
    /// Input speed ω2 (rad/s).
    pub input_speed_rad_s: f64,
    /// Input step used (deg).
    pub step_deg: f64,
    /// Largest |φ3 − φ2| over the revolution (deg); the slot meets crank 6 while it is below
    /// `arcsin(l6/l2)`.
    pub slot_deviation_max_deg: f64,
    /// The limit `arcsin(l6/l2)` (deg).
    pub slot_deviation_limit_deg: f64,
    /// Range of α (deg) for which the slot meets crank 6 over the whole revolution with this cam
    /// (the roller path does not depend on α).
    pub admissible_alpha_deg: [f64; 2],
    /// Open range of θ (deg) for which the arm AC is never normal to the derived counter-cam Γ′:
    /// `(max δ, 180° + min δ)`, `δ = φ3 − φ2`.
    pub admissible_theta_deg: [f64; 2],
    /// Undercut of Γ by the roller, if a roller radius was given.
    pub undercut_b: bool,
    /// Undercut of Γ′ by the roller, if a roller radius was given.
    pub undercut_c: bool,
    /// The checks of the revolution.
    #[serde(flatten)]
    pub checks: CamChecks,
}

/// The result of an analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Analysis {
    /// One row per input step, the last one closing the revolution.
    pub rows: Vec<AnalysisRow>,
    /// Summary.
    pub summary: AnalysisSummary,
    /// Warnings (pressure angles, undercut, cusps, self-crossings).
    pub warnings: Vec<Warning>,
    /// The counter-cam Γ′ derived from the motion (roller-centre curve and, with a roller, walls).
    pub counter_cam: CamProfile,
    /// Full states (positions and φ2-derivatives), parallel to `rows`.
    #[serde(skip)]
    pub states: Vec<ModulatorState>,
}

/// What `loomkin dobby analyze --json` prints of an [`Analysis`]: the rows, summary and warnings
/// (the counter-cam and the states are left out).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AnalysisReport<'a> {
    /// The summary.
    pub summary: &'a AnalysisSummary,
    /// The warnings.
    pub warnings: &'a [Warning],
    /// The rows.
    pub rows: &'a [AnalysisRow],
}

impl Analysis {
    /// The report of this analysis ([`AnalysisReport`]).
    pub fn report(&self) -> AnalysisReport<'_> {
        AnalysisReport { summary: &self.summary, warnings: &self.warnings, rows: &self.rows }
    }

    /// Cam Γ (the roller-centre curve of B over one revolution) as a profile, with groove walls
    /// for a roller of radius `roller_m` > 0, built as the counter-cam Γ′ is.
    pub fn cam_profile(&self, roller_m: f64) -> CamProfile {
        let n = self.states.len().saturating_sub(1);
        CamProfile::from_points(self.states[..n].iter().map(|s| (s.b[0], s.b[1])), roller_m)
    }
}

/// Loop (2) alone, unknowns `q = (p, φ3)`: `r(p) + l3·e(φ3 + α) − l2·e(φ2) = 0`.
pub fn cam_loop(g: &ModulatorGeometry, cam: &Cam) -> Result<LoopSystem<2>> {
    let l = VectorLoop::new()
        .plus_curve(cam.curve().clone(), Scalar::unknown(0))
        .plus_polar(Scalar::constant(g.l3_m), Scalar::unknown_plus(1, g.alpha_rad()))
        .minus_polar(Scalar::constant(g.l2_m), Scalar::input_plus(0.0));
    LoopSystem::new(vec![l])
}

/// Both loops (2) and (3), unknowns `q = (p, φ3, S53, φ6)`:
/// `r(p) + l3·e(φ3 + α) − l2·e(φ2) = 0` and `l6·e(φ6) + S53·e(φ3) − l2·e(φ2) = 0`.
pub fn modulator_loops(g: &ModulatorGeometry, cam: &Cam) -> Result<LoopSystem<4>> {
    let l1 = VectorLoop::new()
        .plus_curve(cam.curve().clone(), Scalar::unknown(0))
        .plus_polar(Scalar::constant(g.l3_m), Scalar::unknown_plus(1, g.alpha_rad()))
        .minus_polar(Scalar::constant(g.l2_m), Scalar::input_plus(0.0));
    let l2 = VectorLoop::new()
        .plus_polar(Scalar::constant(g.l6_m), Scalar::unknown(3))
        .plus_polar(Scalar::unknown(2), Scalar::unknown(1))
        .minus_polar(Scalar::constant(g.l2_m), Scalar::input_plus(0.0));
    LoopSystem::new(vec![l1, l2])
}

/// Loop (2) solved as one equation in the cam parameter: with `w = A − r(p)`, `|w| = l3` and
/// `φ3 = atan2 w − α`. One continuation step is a scalar Newton iteration on `|w(p)| − l3` from the
/// second-order prediction, then the rates in closed form from `w·w′ = 0` and its derivative:
/// `p′ = (w·A′)/(w·r′)`, `p″ = (|w′|² + w·(A″ − r″p′²))/(w·r′)`, `φ3′ = (w × w′)/|w|²`,
/// `φ3″ = (w × w″)/|w|² − 2(w × w′)(w·w′)/|w|⁴`, where `w·r′` is det J_q of the vector form.
/// It accepts a step under the same conditions as [`LoopSystem::advance`] (residual, no jump to
/// another branch, det J_q keeping its sign) and declines anything else, which the caller then
/// hands to the general solver (step halving, fold location, messages).
///
/// The slot direction comes with the state: `w = l3·e(φ3 + α)`, so `e(φ3) = w/|w|` turned by −α
/// (no `sin_cos` of φ3). Given `e(φ3)` of the state stepped from, φ3 is that state's φ3 plus the
/// small angle between the two slot directions ([`crate::planar::angle_near`], no `atan2`).
struct CamLoop<'a> {
    curve: &'a dyn crate::curve::PlaneCurve,
    l2: f64,
    l3: f64,
    alpha: f64,
    /// `e(−α)` and `e(α)`.
    minus_alpha: Vec2,
    plus_alpha: Vec2,
    tol: f64,
}

impl<'a> CamLoop<'a> {
    fn new(g: &ModulatorGeometry, cam: &'a Cam, tol: f64) -> Self {
        let alpha = g.alpha_rad();
        let (minus_alpha, plus_alpha) = (e(-alpha), e(alpha));
        Self { curve: cam.curve().as_ref(), l2: g.l2_m, l3: g.l3_m, alpha, minus_alpha, plus_alpha, tol }
    }

    /// The state at input `x1`, given `ea = e(x1)`, and `e(φ3)`; or `None` (declined).
    /// `from_e3`: `e(φ3)` of `from`, if φ3 is to be taken as a small angle from it.
    fn step(&self, from: &LoopState<2>, from_e3: Option<Vec2>, x1: f64, ea: Vec2) -> Option<(LoopState<2>, Vec2)> {
        let h = x1 - from.input;
        let pred = from.q + from.dq * h + from.ddq * (h * h / 2.0);
        let (a0, a1) = (self.l2 * ea, self.l2 * crate::planar::perp(ea));
        let a2 = -a0;
        let mut p = pred[0];
        let mut c = self.curve.eval(p);
        let mut converged = false;
        for _ in 0..12 {
            let w = a0 - c.r;
            let n = w.norm();
            let d = n - self.l3;
            if !d.is_finite() {
                return None;
            }
            if d.abs() <= self.tol {
                converged = true;
                break;
            }
            let slope = -w.dot(&c.d1) / n;
            if slope == 0.0 || !slope.is_finite() {
                return None;
            }
            p -= d / slope;
            c = self.curve.eval(p);
        }
        if !converged {
            return None;
        }
        let w = a0 - c.r;
        let det = w.dot(&c.d1);
        if !(det.is_finite() && det != 0.0) || det.signum() != from.det.signum() {
            return None;
        }
        let ww = w.norm_squared();
        // The slot direction w is at φ3 + α; from `from`'s direction e(φ3 + α) by a small angle.
        let phi3 = from_e3
            .and_then(|u| crate::planar::angle_near(from.q[1], crate::planar::rotate(u, self.plus_alpha), w))
            .unwrap_or_else(|| pred[1] + wrap_pi(w.y.atan2(w.x) - self.alpha - pred[1]));
        let e3 = crate::planar::rotate(w / ww.sqrt(), self.minus_alpha);
        let p1 = w.dot(&a1) / det;
        let w1 = a1 - c.d1 * p1;
        let p2 = (w1.norm_squared() + w.dot(&(a2 - c.d2 * (p1 * p1)))) / det;
        let w2 = a2 - c.d2 * (p1 * p1) - c.d1 * p2;
        let cr1 = crate::planar::cross(w, w1);
        let phi3_1 = cr1 / ww;
        let phi3_2 = crate::planar::cross(w, w2) / ww - 2.0 * cr1 * w.dot(&w1) / (ww * ww);
        let q = SVector::<f64, 2>::new(p, phi3);
        let change = (from.dq * h).amax() + (from.ddq * (h * h / 2.0)).amax();
        if (q - pred).amax() > 1e-6 + 0.2 * change {
            return None;
        }
        let (dq, ddq) = (SVector::<f64, 2>::new(p1, phi3_1), SVector::<f64, 2>::new(p2, phi3_2));
        [p1, phi3_1, p2, phi3_2].iter().all(|v| v.is_finite()).then_some((LoopState { input: x1, q, dq, ddq, det }, e3))
    }
}

/// Range `[min, max]` (m) of the distance from A to the cam curve at φ2 (sampled, 2048 points).
fn reach(g: &ModulatorGeometry, cam: &Cam, phi2: f64) -> (f64, f64) {
    let a = g.l2_m * e(phi2);
    let c = cam.curve();
    let n = 2048;
    (0..n)
        .map(|i| (c.eval(c.period() * i as f64 / n as f64).r - a).norm())
        .fold((f64::INFINITY, 0.0), |(lo, hi), d| (lo.min(d), hi.max(d)))
}

/// Range of l3 (m) for which roller B reaches Γ at every input angle: `[max min|A − Γ|, min max|A − Γ|]`
/// over the turn (360 input angles), or `None` if it is empty.
fn reach_over_turn(g: &ModulatorGeometry, cam: &Cam) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    for k in 0..360 {
        let (a, b) = reach(g, cam, (k as f64).to_radians());
        lo = lo.max(a);
        hi = hi.min(b);
    }
    (lo < hi).then_some((lo, hi))
}

fn no_reach(g: &ModulatorGeometry, cam: &Cam, phi2: f64, lo: f64, hi: f64) -> MechError {
    let condition = if g.l3_m < lo || g.l3_m > hi {
        format!(
            "roller B cannot reach cam Γ: the distance from A to Γ spans [{lo:.6}, {hi:.6}] m but the arm AB is \
             l3 = {} m",
            loomkin_units::compact(g.l3_m)
        )
    } else {
        format!(
            "roller B only touches cam Γ (the circle of radius l3 = {} m about A is tangent to Γ; the distance from A \
             to Γ spans [{lo:.6}, {hi:.6}] m): the arm AB is normal to Γ there",
            loomkin_units::compact(g.l3_m)
        )
    };
    let admissible = match reach_over_turn(g, cam) {
        Some((a, b)) => format!("the roller reaches this cam over the whole turn for l3 ∈ ({a:.6}, {b:.6}) m"),
        None => "no l3 reaches this cam over the whole turn; change the cam or l2 (point tables are in metres)".into(),
    };
    MechError::CannotBuild {
        phi2_deg: phi2.to_degrees(),
        condition,
        admissible: Some(admissible),
        parameter: Some("l3_m"),
    }
}

/// The assembly `(p, φ3)` at input angle `phi2` (rad): among the points of Γ at distance l3 from A,
/// the one whose slot angle φ3 is closest to φ2 (the slot best aligned with OA, so that it can meet
/// crank 6). Roots are bracketed on 2048 samples of the curve and refined by bisection and Newton.
pub fn assemble(g: &ModulatorGeometry, cam: &Cam, phi2: f64) -> Result<[f64; 2]> {
    let a = g.l2_m * e(phi2);
    let c = cam.curve();
    let n = 2048;
    let per = c.period();
    let f = |p: f64| (a - c.eval(p).r).norm_squared() - g.l3_m * g.l3_m;
    // The scan's values (their signs bracket the roots; each root is then bisected on `f`).
    let scan: Vec<f64> = c.scan(n).iter().map(|r| (a - r).norm_squared() - g.l3_m * g.l3_m).collect();
    let mut best: Option<(f64, [f64; 2])> = None;
    let mut prev = scan[0];
    for i in 1..=n {
        let (p0, p1) = (per * (i - 1) as f64 / n as f64, per * i as f64 / n as f64);
        let cur = scan[i];
        if prev == 0.0 || prev.signum() != cur.signum() {
            let side = prev.signum();
            let p = loomkin_numeric::bisect(p0, p1, |mid| f(mid).signum() == side);
            let ab = a - c.eval(p).r;
            let phi3 = phi2 + wrap_pi(ab.y.atan2(ab.x) - g.alpha_rad() - phi2);
            let score = (phi3 - phi2).abs();
            if best.is_none_or(|(s, _)| score < s) {
                best = Some((score, [p, phi3]));
            }
        }
        prev = cur;
    }
    let Some((_, q)) = best else {
        let (lo, hi) = reach(g, cam, phi2);
        return Err(no_reach(g, cam, phi2, lo, hi));
    };
    let sys = cam_loop(g, cam)?;
    let pos = sys.solve_position(phi2, SVector::<f64, 2>::new(q[0], q[1]), &NewtonOptions::default())?;
    Ok([pos.q[0], pos.q[1]])
}

/// The input grid (rad): `n = ⌈360/step⌉` equal steps from `start_deg`, both ends included.
pub(crate) fn input_grid(start_deg: f64, step_deg: f64) -> (Vec<f64>, f64) {
    let n = ((360.0 / step_deg) - 1e-9).ceil().max(1.0) as usize;
    let h = 360.0 / n as f64;
    ((0..=n).map(|i| (start_deg + i as f64 * h).to_radians()).collect(), h)
}

/// Spacing (deg) of the exact anchors of [`grid_units`].
const ANCHOR_DEG: f64 = 5.0;

/// `e(xᵢ)` for the points `xᵢ = (start_deg + i·h_deg)` (deg, as rad) of an [`input_grid`] of
/// `len` points, without a `sin_cos` per point: every `K ≈ 5°/h`-th point (an anchor) is `e(x)`
/// itself, and the points after it are the anchor turned by the offsets `e(k·h)`, `k < K`, each
/// computed once (`e(a + b)` by angle addition). One rotation of two correctly rounded unit
/// vectors: within 1e-15 of `e(xᵢ)` (a few units in the last place, not accumulated along the
/// grid), the rounding of xᵢ itself being of the same order.
///
/// The anchors sit at whole multiples of 5° from the start whenever 5° is a whole number of steps,
/// so two grids whose steps are in a whole ratio (0.1° and 0.05°) give the same bits at the same
/// angle.
pub(crate) fn grid_units(start_deg: f64, h_deg: f64, len: usize) -> Vec<Vec2> {
    let mut out = Vec::with_capacity(len);
    out.extend(grid_units_iter(start_deg, h_deg, len));
    out
}

/// The points of [`grid_units`] one by one, without their table.
pub(crate) fn grid_units_iter(start_deg: f64, h_deg: f64, len: usize) -> impl Iterator<Item = Vec2> {
    let k = crate::planar::round(ANCHOR_DEG / h_deg).clamp(1.0, len.max(1) as f64) as usize;
    let offsets: Vec<Vec2> = (0..k).map(|j| e((j as f64 * h_deg).to_radians())).collect();
    // (the current anchor, the offset index of the next point)
    (0..len).scan((Vec2::zeros(), 0usize), move |(anchor, j), i| {
        let u = if *j == 0 {
            *anchor = e((start_deg + i as f64 * h_deg).to_radians());
            *anchor
        } else {
            crate::planar::rotate(*anchor, offsets[*j])
        };
        *j = if *j + 1 == k { 0 } else { *j + 1 };
        Some(u)
    })
}

/// The largest input speed ω2 (rad/s) the analysis and the synthesis accept (95 493 rev/min).
pub const MAX_INPUT_SPEED_RAD_S: f64 = 1e4;

/// The largest main-shaft speed (rpm) a front end's `speed_rpm` takes: a round number in the unit
/// typed, inside [`MAX_INPUT_SPEED_RAD_S`] (95 000 rpm is ω2 = 9 948 rad/s), so the rpm check is the
/// one a user meets (it printed the rad/s bound converted, `95492.9658551 rpm`).
pub const MAX_INPUT_SPEED_RPM: f64 = 95_000.0;

/// The allowed step of the input angle of an analysis or a synthesis (deg): a hundredth of a
/// degree (36 000 positions a turn) to 30°.
pub const STEP_DEG_RANGE: Range = Range::closed(0.01, 30.0, "°");
/// The allowed roller radius of a synthesis or an analysis (m): a knife edge to 10 m.
pub const ROLLER_M_RANGE: Range = Range::closed(0.0, 10.0, "m");

/// The modulator's inputs that are not its dimensions: steps, the speed, the roller, the warning limit.
pub struct DobbyInputs;

impl DobbyInputs {
    /// `step_deg`: the input step of an analysis or synthesis, 0.01 … 30°; 1°.
    pub const STEP_DEG: Field = Field::new(
        "step_deg",
        STEP_DEG_RANGE,
        "Input step of the analysis or synthesis rows: 0.01 … 30° (the extremes are refined between rows); \
         1° when left out.",
    )
    .with_default(1.0);
    /// [`DobbyInputs::STEP_DEG`] of a plot: 0.5°.
    pub const PLOT_STEP_DEG: Field = Self::STEP_DEG.with_default(0.5);
    /// `speed_rpm`: the input (main-shaft) speed, the shaft range up to the modulator's bound on ω2
    /// ([`MAX_INPUT_SPEED_RPM`], within ω2 ≤ [`MAX_INPUT_SPEED_RAD_S`]); left out, ω2 = 1 rad/s
    /// (rates read as ratios).
    pub const SPEED_RPM: Field = Field::new(
        "speed_rpm",
        Range::closed(1e-3, MAX_INPUT_SPEED_RPM, "rpm"),
        "Input (main-shaft) speed: 0.001 … 95 000 rpm (within the modulator's bound ω2 ≤ 10⁴ rad/s); left \
         out, ω2 = 1 rad/s as in the paper, so rates read as ratios.",
    );
    /// `pressure_limit_deg`: pressure angles above it raise a warning, 0 … 90°; 60°.
    pub const PRESSURE_LIMIT_DEG: Field = Field::new(
        "pressure_limit_deg",
        Range::closed(0.0, 90.0, "°"),
        "Pressure angles above this raise a warning: 0 … 90°; 60° (the paper's limit) when left out.",
    )
    .with_default(60.0);
    /// `roller_m`: the radius of both rollers, 0 … 10 m; 0.03 m where cams are synthesised.
    pub const ROLLER_M: Field = Field::new(
        "roller_m",
        ROLLER_M_RANGE,
        "Roller radius of both rollers (groove walls, undercut): 0 … 10 m; 0.03 m where the cams are \
         synthesised, none for a given cam.",
    )
    .with_default(0.03);
    /// `roller_mm`: [`DobbyInputs::ROLLER_M`] in mm (the workbench's and `cam profile`'s unit).
    pub const ROLLER_MM: Field = Field::new(
        "roller_mm",
        Range::closed(0.0, 10_000.0, "mm"),
        "Roller radius in mm (as roller_m): 0 … 10 000 mm; 30 mm where the cams are synthesised.",
    )
    .with_default(30.0);
    /// `at_deg`: the input angle a plot draws the mechanism at, ±360°; 0°.
    pub const AT_DEG: Field = Field::new(
        "at_deg",
        Range::closed(-360.0, 360.0, "deg"),
        "Input angle at which the mechanism is drawn: ±360°; 0° when left out.",
    )
    .with_default(0.0);

    /// The input speed ω2 (rad/s) of a front end's `speed_rpm` under `field` (its flag or key):
    /// the shaft-speed range, then the modulator's bound [`DobbyInputs::SPEED_RPM`], both named
    /// by the input as typed; left out, 1 rad/s.
    pub fn speed_rad_s(field: &str, speed_rpm: Option<f64>) -> Result<f64> {
        match speed_rpm {
            None => Ok(1.0),
            Some(n) => {
                // The modulator's range first: it lies inside the shaft's, so one message names it.
                Self::SPEED_RPM.check_as(field, n)?;
                Ok(ShaftSpeed::from_rpm_field(field, n)?.rad_per_s())
            }
        }
    }

    /// The roller radius in m of `roller_mm` (checked in mm, named `field`) or `roller_m`.
    pub fn roller_m(field_mm: &str, roller_mm: Option<f64>, roller_m: Option<f64>) -> Result<Option<f64>> {
        match roller_mm {
            Some(mm) => {
                let mm = Self::ROLLER_MM.check_as(field_mm, mm)?;
                check_least_roller(field_mm, mm, 1e3)?;
                Ok(Some(loomkin_units::m_from_mm(mm)))
            }
            None => Ok(roller_m),
        }
    }

    /// The least roller radius other than 0 (a knife edge), m: 1 µm. A roller's curvature 1/r is
    /// drawn and compared with the cams'; below a micrometre it is 10⁶ 1/m and more (the cams'
    /// is below 10³ 1/m), and 10⁻³⁰⁸ m overflowed the curvature plot's axis (NaN in the SVG).
    pub const LEAST_ROLLER_M: f64 = 1e-6;
}

/// A roller radius `r` (in m × `per_m`: 1 for m, 10³ for mm) of 0 (a knife edge) or at least
/// [`DobbyInputs::LEAST_ROLLER_M`], else the error naming `field` with the range in its unit.
fn check_least_roller(field: &str, r: f64, per_m: f64) -> Result<()> {
    let least = DobbyInputs::LEAST_ROLLER_M * per_m;
    if r > 0.0 && r < least {
        let most = match ROLLER_M_RANGE.hi {
            loomkin_units::Bound::Closed(v) | loomkin_units::Bound::Open(v) => v * per_m,
            loomkin_units::Bound::Unbounded => f64::MAX,
        };
        let unit = if per_m == 1.0 { "m (or 0: a knife edge)" } else { "mm (or 0: a knife edge)" };
        return Err(loomkin_units::RangeError::new(field, r, Range::closed(least, most, unit)).into());
    }
    Ok(())
}

pub(crate) fn check_common(step_deg: f64, speed: f64, roller: Option<f64>, limit: f64) -> Result<()> {
    DobbyInputs::STEP_DEG.check(step_deg)?;
    Range::closed(1e-6, MAX_INPUT_SPEED_RAD_S, "rad/s").check("input_speed_rad_s", speed)?;
    DobbyInputs::PRESSURE_LIMIT_DEG.check(limit)?;
    if let Some(r) = roller {
        DobbyInputs::ROLLER_M.check(r)?;
        check_least_roller("roller_m", r, 1.0)?;
    }
    Ok(())
}

/// Analyses the modulator with cam Γ over one input revolution.
///
/// Errors, each naming the input angle: the roller cannot reach Γ; a fold where the arm AB is normal
/// to Γ (the cam cannot drive the lever); the slot misses the output crank
/// (`|φ3 − φ2| > arcsin(l6/l2)`), with the admissible range of α for this cam.
pub fn analyze(g: &ModulatorGeometry, cam: &Cam, opts: &AnalysisOptions) -> Result<Analysis> {
    analyze_in(g, cam, opts, Vec::new(), Vec::new())
}

/// [`analyze`] into an earlier result `out`, whose tables' memory is reused (a loop of analyses
/// then allocates, and the system maps, no fresh memory for them). The result is the same as
/// [`analyze`]'s; on an error `out` is left with empty tables.
pub fn analyze_into(g: &ModulatorGeometry, cam: &Cam, opts: &AnalysisOptions, out: &mut Analysis) -> Result<()> {
    let (rows, states) = (std::mem::take(&mut out.rows), std::mem::take(&mut out.states));
    *out = analyze_in(g, cam, opts, rows, states)?;
    Ok(())
}

/// [`analyze`] filling the (cleared) vectors `rows` and `states`.
fn analyze_in(
    g: &ModulatorGeometry,
    cam: &Cam,
    opts: &AnalysisOptions,
    mut rows: Vec<AnalysisRow>,
    mut states: Vec<ModulatorState>,
) -> Result<Analysis> {
    g.validate()?;
    check_common(opts.step_deg, opts.input_speed_rad_s, opts.roller_m, opts.pressure_limit_deg)?;
    Range::closed(-360.0, 360.0, "°").check("start_deg", opts.start_deg)?;
    let (xs, step) = input_grid(opts.start_deg, opts.step_deg);
    // The cam loop is traced on the check grid, whatever the output step, and solved between its
    // points by continuation from the nearest traced state.
    let cx = check_grid(opts.start_deg);
    let cx_e2 = grid_units(opts.start_deg, CHECK_STEP_DEG, cx.len());
    let q0 = assemble(g, cam, cx[0])?;
    let sys = cam_loop(g, cam)?;
    let newton = &opts.newton;
    let fail = |err: MechError| match err {
        MechError::Singular { input, .. } | MechError::NoConvergence { input, .. } => {
            diagnose_cam(g, cam, input, input)
        }
        other => other,
    };
    let p0 = sys.solve_position(cx[0], SVector::<f64, 2>::new(q0[0], q0[1]), newton).map_err(fail)?;
    let mut traced = Vec::with_capacity(cx.len());
    traced.push(sys.rates(cx[0], p0.q).map_err(fail)?);
    // e(φ3) of each traced state, which loop (3) and the checks reuse with e(φ2) of the grid.
    let mut traced_e3 = Vec::with_capacity(cx.len());
    traced_e3.push(e(traced[0].q[1]));
    let fast = CamLoop::new(g, cam, newton.residual_tol);
    // One continuation step to input x, `ea = e(x)`: the scalar form where it applies, the general
    // solver otherwise; with e(φ3) of the new state.
    let advance = |from: &LoopState<2>, from_e3: Option<Vec2>, x: f64, ea: Vec2| match fast.step(from, from_e3, x, ea) {
        Some(st) => Ok(st),
        None => sys.advance(from, x, newton).map(|st| (st, e(st.q[1]))),
    };
    for (&x, &ea) in cx[1..].iter().zip(&cx_e2[1..]) {
        let last = traced[traced.len() - 1];
        // (φ3 of the traced states by atan2, not by small angles from each other: no accumulation.)
        match advance(&last, None, x, ea) {
            Ok((st, e3)) => {
                traced.push(st);
                traced_e3.push(e3);
            }
            Err(_) => return Err(locate_fold(g, cam, &sys, &last, x, newton)),
        }
    }
    // The state at any input x with e(x) and e(φ3).
    let loop_at = |x: f64| {
        let ea = e(x);
        let j = Revolution::nearest(&cx, x);
        advance(&traced[j], Some(traced_e3[j]), x, ea).ok().map(|(st, e3)| (st, ea, e3))
    };

    // The slot must meet crank 6: |φ3 − φ2| ≤ arcsin(l6/l2). η = φ3 − φ2 + α does not depend on α.
    // The extremes of δ = φ3 − φ2 are refined between the points of the check grid.
    let sigma = (g.l6_m / g.l2_m).asin();
    let dev_of = |st: &LoopState<2>| wrap_pi(st.q[1] - st.input);
    let dvals: Vec<f64> = traced.iter().map(dev_of).collect();
    let neg: Vec<f64> = dvals.iter().map(|d| -d).collect();
    let dmax = refined_turn_max(&cx, &dvals, &|x| loop_at(x).map_or(f64::NEG_INFINITY, |st| dev_of(&st.0)));
    let dmin = refined_turn_max(&cx, &neg, &|x| loop_at(x).map_or(f64::NEG_INFINITY, |st| -dev_of(&st.0)));
    let dev = [Extreme { value: -dmin.value, at: dmin.at }, dmax];
    let worst = if dmax.value.abs() >= dmin.value.abs() { dev[1] } else { dev[0] };
    let (eta_min, eta_max) = (dev[0].value + g.alpha_rad(), dev[1].value + g.alpha_rad());
    // |φ3 − φ2| ≤ σ for every φ2 ⇔ α ∈ [max η − σ, min η + σ], within the valid (0°, 180°).
    let alpha_range = [(eta_max - sigma).to_degrees().max(0.0), (eta_min + sigma).to_degrees().min(180.0)];
    if worst.value.abs() > sigma {
        let d = worst.value;
        let admissible = if alpha_range[0] < alpha_range[1] {
            // α = 0° and 180° themselves are not valid levers: the bound is open there.
            let open = |v: f64| v <= 0.0 || v >= 180.0;
            format!(
                "admissible α ∈ {}{:.3}, {:.3}{}° for this cam",
                if open(alpha_range[0]) { '(' } else { '[' },
                alpha_range[0],
                alpha_range[1],
                if open(alpha_range[1]) { ')' } else { ']' }
            )
        } else {
            format!(
                "no α works for this cam: φ3 − φ2 + α spans {:.3}°, more than 2·arcsin(l6/l2) = {:.3}°",
                (eta_max - eta_min).to_degrees(),
                2.0 * sigma.to_degrees()
            )
        };
        let condition = if d.cos() > 0.0 {
            format!(
                "the slot misses the output crank: |sin(φ3 − φ2)| = {:.5} > l6/l2 = {:.5} (φ3 − φ2 = {:.3}°, \
                 |φ3 − φ2| must stay ≤ arcsin(l6/l2) = {:.3}°)",
                d.sin().abs(),
                g.l6_m / g.l2_m,
                d.to_degrees(),
                sigma.to_degrees()
            )
        } else {
            format!(
                "the slot misses the output crank: φ3 − φ2 = {:.3}°, so the slot from A points away from O and meets \
                 the circle of crank 6 only behind A (|φ3 − φ2| must stay ≤ arcsin(l6/l2) = {:.3}°)",
                d.to_degrees(),
                sigma.to_degrees()
            )
        };
        return Err(MechError::CannotBuild {
            phi2_deg: worst.at_deg(),
            condition,
            admissible: Some(admissible),
            parameter: Some("alpha_deg"),
        });
    }

    let arms = ArmAngles::new(g);
    let close3 = |st: &LoopState<2>, e2: Vec2, e3: Vec2, near6: (f64, Option<Vec2>)| {
        state_from_phi3(g, &arms, st.input, e2, e3, [st.q[1], st.dq[1], st.ddq[1]], near6).map_err(|e| {
            MechError::CannotBuild {
                phi2_deg: st.input.to_degrees(),
                condition: format!("loop (3) cannot close: {e}"),
                admissible: None,
                parameter: None,
            }
        })
    };
    let mut fine = Vec::with_capacity(traced.len());
    let mut phi6_ref = traced[0].input;
    for ((st, &e2), &e3) in traced.iter().zip(&cx_e2).zip(&traced_e3) {
        // (φ6 of the grid states by atan2, not by small angles from each other: no accumulation.)
        fine.push(close3(st, e2, e3, (phi6_ref, None))?);
        phi6_ref = fine[fine.len() - 1].phi6[0];
    }
    let refs: Vec<f64> = fine.iter().map(|s| s.phi6[0]).collect();
    // e(φ6) of the grid states, D/|D| as loop (3) forms it, for states solved near them.
    let refs_e6: Vec<Vec2> = fine
        .iter()
        .zip(&cx_e2)
        .zip(&traced_e3)
        .map(|((s, &e2), &e3)| {
            let d = g.l2_m * e2 - s.s53[0] * e3;
            d / d.norm()
        })
        .collect();
    let near6 = |j: usize| (refs[j], Some(refs_e6[j]));

    let w2 = opts.input_speed_rad_s;
    states.clear();
    rows.clear();
    states.reserve(xs.len());
    rows.reserve(xs.len());
    for (&x, e2) in xs.iter().zip(grid_units_iter(opts.start_deg, step, xs.len())) {
        let j = Revolution::nearest(&cx, x);
        // A row on a point of the check grid is its traced state.
        let (p, e2) = if x.to_bits() == cx[j].to_bits() {
            states.push(fine[j]);
            (traced[j].q[0], cx_e2[j])
        } else {
            let (st, e3) = advance(&traced[j], Some(traced_e3[j]), x, e2)?;
            states.push(close3(&st, e2, e3, near6(j))?);
            (st.q[0], e2)
        };
        // The state went into its table first and the row reads it there (no copy in between).
        rows.push(AnalysisRow::new(&states[states.len() - 1], g.l2_m * e2, p, (x - xs[0]) / w2, w2));
    }
    let rev = Revolution {
        xs: cx.clone(),
        states: fine,
        pins: cx_e2.iter().map(|&e2| g.l2_m * e2).collect(),
        eval: Box::new(|x| {
            let (st, e2, e3) = loop_at(x)?;
            close3(&st, e2, e3, near6(Revolution::nearest(&cx, x))).ok()
        }),
        output: None,
    };
    let mut warnings = Vec::new();
    let theta_range = [dev[1].value.to_degrees().max(0.0), (180.0 + dev[0].value.to_degrees()).min(180.0)];
    counter_cam_fold(g, &rev, dev, theta_range, &mut warnings);
    let checks = check_states(g, &rev, w2, opts.pressure_limit_deg, &mut warnings);
    let (ub, uc) = match opts.roller_m {
        Some(r) => undercut(&checks, r, &mut warnings),
        None => (false, false),
    };
    let path = states[..states.len() - 1].iter().map(|s| (s.c[0], s.c[1]));
    let counter_cam = CamProfile::from_points(path, opts.roller_m.unwrap_or(0.0));
    let summary = AnalysisSummary {
        cam: cam.label().to_string(),
        geometry: *g,
        input_speed_rad_s: w2,
        step_deg: step,
        slot_deviation_max_deg: worst.value.abs().to_degrees(),
        slot_deviation_limit_deg: sigma.to_degrees(),
        admissible_alpha_deg: alpha_range,
        admissible_theta_deg: theta_range,
        undercut_b: ub,
        undercut_c: uc,
        checks,
    };
    Ok(Analysis { rows, summary, warnings, counter_cam, states })
}

/// Names the reason the cam loop could not be followed from the state `from` to input `to` (rad):
/// the roller out of reach, or a fold located by bisection on the input angle (the largest angle
/// the branch can still be followed to, to adjacent doubles).
fn locate_fold(
    g: &ModulatorGeometry,
    cam: &Cam,
    sys: &LoopSystem<2>,
    from: &LoopState<2>,
    to: f64,
    newton: &NewtonOptions,
) -> MechError {
    let (lo, hi) = loomkin_numeric::bisect_bracket(from.input, to, |mid| sys.advance(from, mid, newton).is_ok());
    match diagnose_cam(g, cam, from.input, hi) {
        MechError::CannotBuild { condition, .. } if condition.starts_with("fold") => MechError::CannotBuild {
            phi2_deg: lo.to_degrees(),
            condition: format!(
                "fold at φ2 = {:.3}°: the arm AB becomes normal to cam Γ (pressure angle at roller B reaches 90°), so \
                 the cam cannot drive the lever past it",
                lo.to_degrees()
            ),
            admissible: Some("the fold does not depend on α; change the cam, l2 or l3".into()),
            parameter: None,
        },
        other => other,
    }
}

/// Names the reason the cam loop could not be followed between `from` and `to` (rad).
fn diagnose_cam(g: &ModulatorGeometry, cam: &Cam, from: f64, to: f64) -> MechError {
    for k in 0..=16 {
        let x = from + (to - from) * k as f64 / 16.0;
        let (lo, hi) = reach(g, cam, x);
        if g.l3_m < lo || g.l3_m > hi {
            return no_reach(g, cam, x, lo, hi);
        }
    }
    MechError::CannotBuild {
        phi2_deg: from.to_degrees(),
        condition: format!(
            "fold between φ2 = {:.3}° and {:.3}°: the arm AB becomes normal to cam Γ (pressure angle at roller B \
             reaches 90°), so the cam cannot drive the lever past it",
            from.to_degrees(),
            to.to_degrees()
        ),
        admissible: Some("the fold does not depend on α; change the cam, l2 or l3".into()),
        parameter: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{OutputLawSpec, SynthesisOptions, synthesize};

    /// The rpm bound a user meets is round (issue 27: `95492.9658551 rpm`) and inside the rad/s
    /// bound the analysis checks: the top speed typed passes both, one past it is refused by the
    /// rpm check naming 95000 rpm.
    #[test]
    fn the_speed_bound_is_round_in_rpm_and_inside_the_rad_s_bound() {
        let w = DobbyInputs::speed_rad_s("--speed-rpm", Some(MAX_INPUT_SPEED_RPM)).unwrap();
        assert_eq!(w, MAX_INPUT_SPEED_RPM * std::f64::consts::TAU / 60.0);
        assert!(w <= MAX_INPUT_SPEED_RAD_S, "{w}");
        check_common(1.0, w, None, 60.0).unwrap();
        let e = DobbyInputs::speed_rad_s("--speed-rpm", Some(95_000.1)).unwrap_err().to_string();
        assert!(e.contains("0.001 ≤ --speed-rpm ≤ 95000 rpm"), "{e}");
    }

    /// An analysis into an earlier result equals a fresh one, whatever the earlier result held
    /// (another step, another cam); an error leaves empty tables.
    #[test]
    fn analysis_into_an_earlier_result_equals_a_fresh_one() {
        let g = ModulatorGeometry::PAPER;
        let fine = AnalysisOptions { step_deg: 0.5, ..Default::default() };
        let coarse = AnalysisOptions { step_deg: 5.0, roller_m: Some(0.03), ..Default::default() };
        let mut out = analyze(&g, &Cam::ellipse(0.36, 0.58).unwrap(), &fine).unwrap();
        for o in [coarse, fine, coarse] {
            analyze_into(&g, &Cam::paper(), &o, &mut out).unwrap();
            assert_eq!(out, analyze(&g, &Cam::paper(), &o).unwrap());
        }
        let bad = ModulatorGeometry { alpha_deg: 10.0, ..g };
        assert!(analyze_into(&bad, &Cam::paper(), &fine, &mut out).is_err());
        assert!(out.rows.is_empty() && out.states.is_empty());
    }

    /// Independent route for the grid's unit vectors: `sin_cos` of every grid angle, over a whole
    /// revolution, for steps that divide 5° and steps that do not, from several starts; anchors
    /// are exact, and a 0.05° grid repeats a 0.1° grid's bits at the shared angles.
    #[test]
    fn grid_unit_vectors_match_sin_cos() {
        let mut worst = 0.0f64;
        for start in [0.0, 12.5, -90.0, 359.0] {
            for step in [0.01, 0.05, 0.07, 0.1, 0.25, 0.3, 1.0, 7.3, 30.0] {
                let (xs, h) = input_grid(start, step);
                let units = grid_units(start, h, xs.len());
                assert_eq!(units.len(), xs.len());
                for (&x, u) in xs.iter().zip(&units) {
                    let d = (u - e(x)).amax();
                    // The grid angle, its anchor and its offset are each rounded in degrees and in
                    // radians (½ ulp of |x| each: 2ε|x| in all, the same order as the rounding
                    // of xᵢ that direct sin_cos carries), then three unit components and one
                    // rotation (4ε).
                    let tol = f64::EPSILON * (2.0 * x.abs() + 4.0);
                    assert!(d <= tol, "start {start}°, step {step}°, x = {x}: {u:?} vs {:?}", e(x));
                    if start == 0.0 {
                        worst = worst.max(d);
                    }
                }
                assert_eq!(units[0], e(xs[0]));
            }
        }
        // Over the turn from 0° (|x| ≤ 2π): within 1.6e-15 (the rounding of x there is 4.4e-16).
        assert!(worst > 0.0 && worst <= 1.6e-15, "{worst:e}");
        let (coarse, h) = input_grid(0.0, 0.1);
        let (fine, hf) = input_grid(0.0, 0.05);
        let (uc, uf) = (grid_units(0.0, h, coarse.len()), grid_units(0.0, hf, fine.len()));
        for i in 0..coarse.len() {
            assert_eq!(coarse[i].to_bits(), fine[2 * i].to_bits());
            assert_eq!(uc[i], uf[2 * i], "point {i}");
        }
    }

    /// Independent route for the scalar cam-loop step: the general Newton continuation of the
    /// vector loop ([`LoopSystem::advance`]) from the same states, over a revolution at 0.25°, for
    /// the paper's ellipse and for a point-table cam.
    #[test]
    fn scalar_cam_loop_step_matches_the_vector_loop() {
        let g = ModulatorGeometry::PAPER;
        let s = synthesize(&g, &OutputLawSpec::default(), &SynthesisOptions { step_deg: 1.0, ..Default::default() })
            .unwrap();
        let pts: Vec<Vec2> = s.cam.centre.iter().map(|p| Vec2::new(p[0], p[1])).collect();
        for cam in [Cam::paper(), Cam::from_points(&pts).unwrap()] {
            let sys = cam_loop(&g, &cam).unwrap();
            let newton = NewtonOptions::default();
            let fast = CamLoop::new(&g, &cam, newton.residual_tol);
            let xs = check_grid(0.0);
            let q0 = assemble(&g, &cam, xs[0]).unwrap();
            let mut st = sys.rates(xs[0], SVector::<f64, 2>::new(q0[0], q0[1])).unwrap();
            let mut fast_steps = 0;
            for &x in &xs[1..] {
                let slow = sys.advance(&st, x, &newton).unwrap();
                if let Some((f, e3)) = fast.step(&st, None, x, e(x)) {
                    // φ3 as a small angle from the state stepped from: atan2's value to rounding,
                    // everything else the same bits.
                    let (near, e3_near) = fast.step(&st, Some(e(st.q[1])), x, e(x)).unwrap();
                    assert!((near.q[1] - f.q[1]).abs() <= 8.0 * f64::EPSILON * (f.q[1].abs() + 1.0), "{x}: φ3");
                    assert_eq!((near.q[0], near.dq, near.ddq, e3_near), (f.q[0], f.dq, f.ddq, e3));
                    // e(φ3) from the loop vector against sin_cos of φ3: φ3 carries the rounding of
                    // atan2, of α and of its own value (ε|φ3| each), w its components' rounding.
                    let tol = f64::EPSILON * (2.0 * f.q[1].abs() + 8.0);
                    assert!((e3 - e(f.q[1])).amax() <= tol, "{x}: e(φ3) {e3:?} vs {:?}", e(f.q[1]));
                    fast_steps += 1;
                    assert!((f.q - slow.q).amax() < 1e-11, "{x}: q {:?} vs {:?}", f.q, slow.q);
                    assert!((f.dq - slow.dq).amax() < 1e-9 * slow.dq.amax().max(1.0), "{x}: q′");
                    assert!((f.ddq - slow.ddq).amax() < 1e-8 * slow.ddq.amax().max(1.0), "{x}: q″");
                    assert!(f.det.signum() == slow.det.signum() && (f.det - slow.det).abs() < 1e-9 * slow.det.abs());
                }
                st = slow;
            }
            assert_eq!(fast_steps, xs.len() - 1, "the scalar step declined a regular step");
        }
    }
}
