//! Task 2, synthesis: the output law φ6(φ2) is given; find the roller-centre curves of cam Γ and
//! counter-cam Γ′ and their groove walls.
//!
//! Everything is closed form: `S53·e(φ3) = l2·e(φ2) − l6·e(φ6)` gives φ3 and S53, then
//! `B = A − l3·e(φ3 + α)` and `C = A + l3′·e(φ3 + π − θ)` (eqs. (2), (8), (9)).

use super::analysis::{check_common, grid_units, grid_units_iter, input_grid};
use super::checks::{Warning, WarningCode, counter_cam_fold, deviation_range, fold_at, slot_deviation};
use super::geometry::ModulatorGeometry;
use super::kinematics::{ArmAngles, ModulatorState, state_from_phi6};
use super::law::{OutputLaw, OutputLawSpec, max_dwell_deg};
use super::refine::{CHECK_STEP_DEG, Revolution, check_grid, refined_turn_max};
use super::report::{CamChecks, CamProfile, check_states, undercut, wall_crossings};
use crate::planar::{Vec2, e, wrap_pi};
use crate::{MechError, Result};
use serde::Serialize;
use std::sync::OnceLock;

/// Settings of a synthesis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SynthesisOptions {
    /// Step of the input angle (deg), 0.01…30, rounded to a whole number of steps per turn.
    pub step_deg: f64,
    /// Constant input speed ω2 (rad/s).
    pub input_speed_rad_s: f64,
    /// Roller radius (m) of both rollers, for the groove walls and the undercut check; 0…10.
    pub roller_m: f64,
    /// Pressure angles above this (deg) raise a warning.
    pub pressure_limit_deg: f64,
}

impl Default for SynthesisOptions {
    fn default() -> Self {
        Self { step_deg: 1.0, input_speed_rad_s: 1.0, roller_m: 0.03, pressure_limit_deg: 60.0 }
    }
}

/// One row of a synthesis (time rates at the constant input speed).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SynthesisRow {
    /// Input angle φ2 (deg).
    pub phi2_deg: f64,
    /// Output angle φ6 (deg), continuous.
    pub phi6_deg: f64,
    /// ω6 (rad/s).
    pub omega6_rad_s: f64,
    /// ε6 (rad/s²).
    pub eps6_rad_s2: f64,
    /// Slot angle φ3 (deg), continuous.
    pub phi3_deg: f64,
    /// ω3 (rad/s).
    pub omega3_rad_s: f64,
    /// Slider position S53 (m).
    pub s53_m: f64,
    /// Roller centre B on Γ, x (m).
    pub b_x_m: f64,
    /// Roller centre B on Γ, y (m).
    pub b_y_m: f64,
    /// Roller centre C on Γ′, x (m).
    pub c_x_m: f64,
    /// Roller centre C on Γ′, y (m).
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

impl SynthesisRow {
    /// The row of state `s`, whose crank pin is `a` ([`ModulatorState::a`]).
    fn new(s: &ModulatorState, a: Vec2, w2: f64) -> Self {
        let mu_bc = s.mu_bc_deg_at(a);
        Self {
            phi2_deg: s.phi2.to_degrees(),
            phi6_deg: s.phi6[0].to_degrees(),
            omega6_rad_s: s.phi6[1] * w2,
            eps6_rad_s2: s.phi6[2] * w2 * w2,
            phi3_deg: s.phi3[0].to_degrees(),
            omega3_rad_s: s.phi3[1] * w2,
            s53_m: s.s53[0],
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

/// Summary of a synthesis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SynthesisSummary {
    /// The output law, e.g. `2 × (dwell 40°, cycloidal rise)`.
    pub law: String,
    /// Geometry used.
    pub geometry: ModulatorGeometry,
    /// Roller radius (m).
    pub roller_m: f64,
    /// Input speed ω2 (rad/s).
    pub input_speed_rad_s: f64,
    /// Input step used (deg).
    pub step_deg: f64,
    /// Largest |φ6 − φ2| (deg).
    pub lag_max_deg: f64,
    /// Its limit `arccos(l6/l2)` (deg), where the output pressure angle reaches 90°.
    pub lag_limit_deg: f64,
    /// Open range of α (deg) free of a fold at roller B for this law: `(−min δ, 180° − max δ)`,
    /// `δ = φ3 − φ2`.
    pub admissible_alpha_deg: [f64; 2],
    /// Open range of θ (deg) free of a fold at roller C: `(max δ, 180° + min δ)`.
    pub admissible_theta_deg: [f64; 2],
    /// Roller radius exceeds Γ's smallest radius of curvature.
    pub undercut_b: bool,
    /// Roller radius exceeds Γ′'s smallest radius of curvature.
    pub undercut_c: bool,
    /// Either cam undercut.
    pub undercut: bool,
    /// Self-crossings of Γ's groove walls (both).
    pub wall_self_intersections_b: usize,
    /// Self-crossings of Γ′'s groove walls (both).
    pub wall_self_intersections_c: usize,
    /// The checks of the revolution.
    #[serde(flatten)]
    pub checks: CamChecks,
}

/// The result of a synthesis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Synthesis {
    /// One row per input step, the last one closing the revolution.
    pub rows: Vec<SynthesisRow>,
    /// Summary.
    pub summary: SynthesisSummary,
    /// Warnings (pressure angles, undercut, self-crossings).
    pub warnings: Vec<Warning>,
    /// Cam Γ: roller-centre curve and groove walls.
    pub cam: CamProfile,
    /// Counter-cam Γ′: roller-centre curve and groove walls.
    pub counter_cam: CamProfile,
    /// Full states, parallel to `rows`.
    #[serde(skip)]
    pub states: Vec<ModulatorState>,
    /// The drawing's dense curves, computed when first asked for ([`Synthesis::dense_profiles`]).
    #[serde(skip)]
    dense: DenseCurves,
}

/// What the drawing's dense curves are computed from: the law and the turn of φ3 on the check
/// grid. They are computed on demand (7200 states, more than the rest of a synthesis at 0.1°) and
/// kept once computed.
#[derive(Debug, Clone)]
struct DenseCurves {
    law: OutputLaw,
    refs: Vec<f64>,
    curves: OnceLock<[CamProfile; 2]>,
}

/// Equal when computed from the same law and turns, whether or not the curves were asked for yet.
impl PartialEq for DenseCurves {
    fn eq(&self, other: &Self) -> bool {
        self.law == other.law && self.refs == other.refs
    }
}

/// The state at input angle `x` (rad) from the law in closed form, φ3 on the turn of the nearest
/// check-grid point (`cx`, turns `refs`), and with `units` (their `e(φ3)`) as a small angle from
/// it; `e2 = e(x)`.
fn law_state(
    g: &ModulatorGeometry,
    arms: &ArmAngles,
    out: &OutputLaw,
    (cx, refs, units): (&[f64], &[f64], Option<&[Vec2]>),
    x: f64,
    e2: Vec2,
) -> ModulatorState {
    let o = out.eval(x);
    let j = Revolution::nearest(cx, x);
    state_from_phi6(g, arms, x, e2, [o.phi6, o.d1, o.d2], (refs[j], units.map(|u| u[j]))).0
}

/// What `loomkin dobby synthesize --json` prints of a [`Synthesis`]: the rows, summary and
/// warnings (the cams and the states are left out: `--dxf` and `--points-csv` write the cams).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SynthesisReport<'a> {
    /// The summary.
    pub summary: &'a SynthesisSummary,
    /// The warnings.
    pub warnings: &'a [Warning],
    /// The rows.
    pub rows: &'a [SynthesisRow],
}

/// The unit a length was given in, so that a message answers in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GivenLength {
    /// Metres (`--roller-m`, the workbench's `roller_m`).
    Metre,
    /// Millimetres (`--roller-mm`).
    Millimetre,
}

impl Synthesis {
    /// The report of this synthesis ([`SynthesisReport`]).
    pub fn report(&self) -> SynthesisReport<'_> {
        SynthesisReport { summary: &self.summary, warnings: &self.warnings, rows: &self.rows }
    }

    /// Why these cams cannot be drawn, in words, when the roller undercuts them (`None` otherwise):
    /// the roller, where the undercut begins and the largest roller without undercut, the lengths in
    /// the unit the roller was given in (`--roller-mm 400` → "a 400 mm roller"). The one wording of
    /// the refusal: the CLI's `dobby synthesize --dxf` and the workbench's export both give it.
    pub fn undercut_refusal(&self, unit: GivenLength) -> Option<String> {
        if !self.summary.undercut {
            return None;
        }
        let (symbol, scale) = match unit {
            GivenLength::Metre => ("m", 1.0),
            GivenLength::Millimetre => ("mm", loomkin_units::mm_from_m(1.0)),
        };
        let length = |m: f64| format!("{} {symbol}", loomkin_units::sig4(m * scale));
        let at = self
            .warnings
            .iter()
            .find(|w| w.code == WarningCode::Undercut)
            .and_then(|w| w.phi2_deg)
            .map_or(String::new(), |a| format!(" at φ2 = {a:.2} deg"));
        let largest = self
            .summary
            .checks
            .roller_max_m
            .map_or(String::new(), |r| format!("; the largest roller without undercut is {}", length(r)));
        Some(format!("a {} roller undercuts the cams{at}{largest}", length(self.summary.roller_m)))
    }

    /// Cam Γ and counter-cam Γ′ every 0.05° of input, whatever the step: the drawing's dense
    /// curves ([`Synthesis::drawing`]), in closed form from the law; computed on the first call.
    pub fn dense_profiles(&self) -> &[CamProfile; 2] {
        self.dense.curves.get_or_init(|| {
            let g = &self.summary.geometry;
            let arms = ArmAngles::new(g);
            let cx = check_grid(0.0);
            let (dxs, h) = input_grid(0.0, super::drawing::DRAW_STEP_DEG);
            let units = grid_units(0.0, h, dxs.len());
            let draw: Vec<ModulatorState> = dxs[..dxs.len() - 1]
                .iter()
                .zip(&units)
                .map(|(&x, &e2)| law_state(g, &arms, &self.dense.law, (&cx, &self.dense.refs, None), x, e2))
                .collect();
            let r = self.summary.roller_m;
            [
                CamProfile::from_points(draw.iter().map(|s| (s.b[0], s.b[1])), r),
                CamProfile::from_points(draw.iter().map(|s| (s.c[0], s.c[1])), r),
            ]
        })
    }
}

fn law_label(spec: &OutputLawSpec) -> String {
    format!(
        "{} × (dwell {}° centred at {}°, {} rise of {}°)",
        spec.cycles,
        loomkin_units::compact(spec.dwell_deg),
        loomkin_units::compact(spec.dwell_centre_deg),
        spec.rise.label(),
        360.0 / f64::from(spec.cycles)
    )
}

/// Synthesises the cams for the output law `law`.
///
/// Errors, each naming the input angle: the law leaves the admissible range
/// `|φ6 − φ2| < arccos(l6/l2)` (with the largest admissible dwell); a fold at roller B or C (an arm
/// normal to its cam), with the admissible range of α or θ. Undercut, high pressure angles and
/// crossing walls are warnings.
pub fn synthesize(g: &ModulatorGeometry, law: &OutputLawSpec, opts: &SynthesisOptions) -> Result<Synthesis> {
    synthesize_in(g, law, opts, Vec::new(), Vec::new())
}

/// [`synthesize`] into an earlier result `out`, whose tables' memory is reused (a loop of
/// syntheses then allocates, and the system maps, no fresh memory for them). The result is the
/// same as [`synthesize`]'s; on an error `out` is left with empty tables.
pub fn synthesize_into(
    g: &ModulatorGeometry,
    law: &OutputLawSpec,
    opts: &SynthesisOptions,
    out: &mut Synthesis,
) -> Result<()> {
    let (rows, states) = (std::mem::take(&mut out.rows), std::mem::take(&mut out.states));
    *out = synthesize_in(g, law, opts, rows, states)?;
    Ok(())
}

/// [`synthesize`] filling the (cleared) vectors `rows` and `states`.
fn synthesize_in(
    g: &ModulatorGeometry,
    law: &OutputLawSpec,
    opts: &SynthesisOptions,
    mut rows: Vec<SynthesisRow>,
    mut states: Vec<ModulatorState>,
) -> Result<Synthesis> {
    g.validate()?;
    check_common(opts.step_deg, opts.input_speed_rad_s, Some(opts.roller_m), opts.pressure_limit_deg)?;
    let out = law.build()?;
    let (xs, step) = input_grid(0.0, opts.step_deg);
    let w2 = opts.input_speed_rad_s;

    // The law must keep the output pressure angle below 90°: |φ6 − φ2| < arccos(l6/l2), checked
    // with the largest lag refined between the points of the check grid.
    let lag_limit = (g.l6_m / g.l2_m).acos();
    let cx = check_grid(0.0);
    let lag = |x: f64| wrap_pi(out.eval(x).phi6 - x).abs();
    // The law on the check grid, evaluated once for the lag and for the states.
    let grid_out: Vec<[f64; 3]> = cx
        .iter()
        .map(|&x| {
            let o = out.eval(x);
            [o.phi6, o.d1, o.d2]
        })
        .collect();
    let lag_vals: Vec<f64> = cx.iter().zip(&grid_out).map(|(&x, o)| wrap_pi(o[0] - x).abs()).collect();
    let worst_lag = refined_turn_max(&cx, &lag_vals, &lag);
    if worst_lag.value >= lag_limit {
        let dmax = max_dwell_deg(law, lag_limit.to_degrees())?;
        let admissible = match dmax {
            Some(d) => format!(
                "admissible |φ6 − φ2| < {:.3}°; with this rise law and {} cycle(s) the dwell must be < {d:.2}°",
                lag_limit.to_degrees(),
                law.cycles
            ),
            None => format!("admissible |φ6 − φ2| < {:.3}°; no dwell works with this rise law", lag_limit.to_degrees()),
        };
        return Err(MechError::CannotBuild {
            phi2_deg: worst_lag.at_deg(),
            condition: format!(
                "the output law leaves the admissible range: |φ6 − φ2| = {:.3}° ≥ arccos(l6/l2) = {:.3}° (the slot \
                 is normal to OD, output pressure angle 90°)",
                worst_lag.value.to_degrees(),
                lag_limit.to_degrees()
            ),
            admissible: Some(admissible),
            parameter: Some("dwell_deg"),
        });
    }

    // The revolution on the check grid (φ3 kept continuous) and in closed form between its points.
    let arms = ArmAngles::new(g);
    let mut fine = Vec::with_capacity(cx.len());
    let mut pins = Vec::with_capacity(cx.len());
    // e(φ3) of the grid states, for states solved near them (φ3 of the grid states themselves by
    // atan2, not by small angles from each other: no accumulation).
    let mut units = Vec::with_capacity(cx.len());
    let mut phi3_ref = cx[0];
    for ((&x, e2), &o) in cx.iter().zip(grid_units_iter(0.0, CHECK_STEP_DEG, cx.len())).zip(&grid_out) {
        let (s, e3) = state_from_phi6(g, &arms, x, e2, o, (phi3_ref, None));
        fine.push(s);
        units.push(e3);
        phi3_ref = fine[fine.len() - 1].phi3[0];
        pins.push(g.l2_m * e2);
    }
    let refs: Vec<f64> = fine.iter().map(|s| s.phi3[0]).collect();
    let at = |x: f64| law_state(g, &arms, &out, (&cx, &refs, Some(&units)), x, e(x));
    // The table: each state and its row share e(φ2); a row on a point of the check grid is its
    // state there (as in analysis).
    states.clear();
    rows.clear();
    states.reserve(xs.len());
    rows.reserve(xs.len());
    for (&x, e2) in xs.iter().zip(grid_units_iter(0.0, step, xs.len())) {
        let j = Revolution::nearest(&cx, x);
        // The state goes into its table first and the row reads it there (no copy in between).
        let a = if x.to_bits() == cx[j].to_bits() {
            states.push(fine[j]);
            pins[j]
        } else {
            let o = out.eval(x);
            states.push(state_from_phi6(g, &arms, x, e2, [o.phi6, o.d1, o.d2], (refs[j], Some(units[j]))).0);
            g.l2_m * e2
        };
        rows.push(SynthesisRow::new(&states[states.len() - 1], a, w2));
    }
    // The output rates' extremes need the law alone, not the state.
    let law_output = |x: f64| {
        let o = out.eval(x);
        [o.phi6, o.d1, o.d2]
    };
    let rev = Revolution {
        xs: cx.clone(),
        states: fine,
        pins,
        eval: Box::new(|x| Some(at(x))),
        output: Some(Box::new(law_output)),
    };

    // Folds: B′·(B − A) ∝ sin(α + δ), C′·(C − A) ∝ sin(θ − δ) with δ = φ3 − φ2.
    let dev = deviation_range(&rev);
    let (dmin, dmax) = (dev[0].value, dev[1].value);
    // sin(α + δ) ≠ 0 for every φ2 ⇔ α ∈ (−min δ, 180° − max δ); likewise θ − δ ∈ (0°, 180°).
    // Both within the valid (0°, 180°); an empty range (lower ≥ upper) means no angle works.
    let alpha_range = [(-dmin).to_degrees().max(0.0), (180.0 - dmax.to_degrees()).min(180.0)];
    let theta_range = [dmax.to_degrees().max(0.0), (180.0 + dmin.to_degrees()).min(180.0)];
    if let Some(fold) = fold_at(&rev, g.alpha_rad(), 1.0, dev) {
        let d = slot_deviation(&at(fold.to_radians()));
        return Err(MechError::CannotBuild {
            phi2_deg: fold,
            condition: format!(
                "fold at roller B: the arm AB is normal to cam Γ (φ3 − φ2 = {:.3}°, α = {:.3}°), the cam cannot \
                 drive the lever past it",
                d.to_degrees(),
                g.alpha_deg
            ),
            admissible: Some(if alpha_range[0] < alpha_range[1] {
                format!("admissible α ∈ ({:.3}, {:.3})° for this law", alpha_range[0], alpha_range[1])
            } else {
                format!("no α works for this law: φ3 − φ2 spans {:.3}°, not less than 180°", (dmax - dmin).to_degrees())
            }),
            parameter: Some("alpha_deg"),
        });
    }
    let mut warnings = Vec::new();
    counter_cam_fold(g, &rev, dev, theta_range, &mut warnings);
    let checks = check_states(g, &rev, w2, opts.pressure_limit_deg, &mut warnings);
    let (ub, uc) = undercut(&checks, opts.roller_m, &mut warnings);
    let n = states.len() - 1;
    let cam = CamProfile::from_points(states[..n].iter().map(|s| (s.b[0], s.b[1])), opts.roller_m);
    let counter_cam = CamProfile::from_points(states[..n].iter().map(|s| (s.c[0], s.c[1])), opts.roller_m);
    // Wall crossings are counted on the check grid, independent of the output step.
    let fine = &rev.states[..rev.states.len() - 1];
    let wb = wall_crossings(fine.iter().map(|s| (s.b[0], s.b[1])), opts.roller_m);
    let wc = wall_crossings(fine.iter().map(|s| (s.c[0], s.c[1])), opts.roller_m);
    for (name, n) in [("cam Γ", wb), ("counter-cam Γ′", wc)] {
        if n > 0 {
            warnings.push(Warning {
                code: WarningCode::SelfIntersection,
                phi2_deg: None,
                message: format!(
                    "the groove walls of {name} cross themselves {n} time(s) (roller {} m)",
                    opts.roller_m
                ),
            });
        }
    }
    let summary = SynthesisSummary {
        law: law_label(law),
        geometry: *g,
        roller_m: opts.roller_m,
        input_speed_rad_s: w2,
        step_deg: step,
        lag_max_deg: worst_lag.value.to_degrees(),
        lag_limit_deg: lag_limit.to_degrees(),
        admissible_alpha_deg: alpha_range,
        admissible_theta_deg: theta_range,
        undercut_b: ub,
        undercut_c: uc,
        undercut: ub || uc,
        wall_self_intersections_b: wb,
        wall_self_intersections_c: wc,
        checks,
    };
    // The drawing's curves every 0.05° (closed form, whatever the step; between those points the
    // curves deviate from their chords by a few tenths of a micrometre at most) are left for
    // `dense_profiles` to compute when a drawing asks for them.
    drop(rev);
    let dense = DenseCurves { law: out, refs, curves: OnceLock::new() };
    Ok(Synthesis { rows, summary, warnings, cam, counter_cam, states, dense })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dense curves, computed on demand, are the closed-form curves: at 0.1° every second
    /// dense point is the table's point (same input angle, bit for bit), walls included; a clone
    /// and an equal synthesis compare equal whether or not their curves were computed yet.
    /// A synthesis into an earlier result equals a fresh one, whatever the earlier result held.
    #[test]
    fn synthesis_into_an_earlier_result_equals_a_fresh_one() {
        let g = ModulatorGeometry::PAPER;
        let law = OutputLawSpec::default();
        let other = OutputLawSpec { dwell_deg: 30.0, rise: loomkin_laws::LawSpec::ModifiedSine, ..law.clone() };
        let (fine, coarse) = (SynthesisOptions { step_deg: 0.5, ..Default::default() }, SynthesisOptions::default());
        let mut out = synthesize(&g, &other, &fine).unwrap();
        for o in [coarse, fine, coarse] {
            synthesize_into(&g, &law, &o, &mut out).unwrap();
            let fresh = synthesize(&g, &law, &o).unwrap();
            assert_eq!(out, fresh);
            assert_eq!(out.dense_profiles(), fresh.dense_profiles());
        }
    }

    #[test]
    fn dense_curves_on_demand_pass_through_the_table_points() {
        let g = ModulatorGeometry::PAPER;
        let o = SynthesisOptions { step_deg: 0.1, ..Default::default() };
        let s = synthesize(&g, &OutputLawSpec::default(), &o).unwrap();
        let fresh = s.clone();
        let [cam, counter] = s.dense_profiles();
        assert_eq!(cam.centre.len(), 7200);
        for (dense, table) in [(cam, &s.cam), (counter, &s.counter_cam)] {
            for (i, p) in table.centre.iter().enumerate() {
                assert_eq!(dense.centre[2 * i], *p, "point {i}");
                assert_eq!(dense.wall_left[2 * i], table.wall_left[i]);
                assert_eq!(dense.wall_right[2 * i], table.wall_right[i]);
            }
        }
        assert_eq!(s, fresh);
        assert_eq!(fresh.dense_profiles(), s.dense_profiles());
    }
}
