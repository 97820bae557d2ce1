//! The modulator's position and its derivatives with respect to the input angle, in closed form
//! where one exists.
//!
//! Loop (3), `l6·e(φ6) + S53·e(φ3) = l2·e(φ2)`, is solved directly both ways: from φ3 (analysis) as
//! a line–circle intersection, from φ6 (synthesis) as `S53·e(φ3) = l2·e(φ2) − l6·e(φ6)`. The lever
//! points B and C follow from φ2 and φ3 alone.

use super::checks::{output_pressure_angle_deg, roller_pressure_angle_deg};
use super::geometry::ModulatorGeometry;
use crate::dyad::line_circle;
use crate::planar::{Vec2, cross, curvature, e, perp, rotate};
use crate::{MechError, Result};
use std::f64::consts::PI;

/// The full state of the modulator at one input angle; `d…`/`dd…` are first and second
/// derivatives with respect to φ2 (multiply by ω2 and ω2² for time rates at constant input speed).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ModulatorState {
    /// Input angle φ2 (rad).
    pub phi2: f64,
    /// Slot angle φ3 (rad) and its derivatives.
    pub phi3: [f64; 3],
    /// Slider position S53 = |AD| (m) and its derivatives.
    pub s53: [f64; 3],
    /// Output angle φ6 (rad) and its derivatives.
    pub phi6: [f64; 3],
    /// Roller centre B on cam Γ (m) and its derivatives.
    pub b: [Vec2; 3],
    /// Roller centre C on counter-cam Γ′ (m) and its derivatives.
    pub c: [Vec2; 3],
}

impl ModulatorState {
    /// Crank pin A (m).
    pub fn a(&self, g: &ModulatorGeometry) -> Vec2 {
        g.l2_m * e(self.phi2)
    }

    /// Slider pin D (m).
    pub fn d(&self, g: &ModulatorGeometry) -> Vec2 {
        g.l6_m * e(self.phi6[0])
    }

    /// Output pressure angle μ6 (deg).
    pub fn mu_out_deg(&self) -> f64 {
        output_pressure_angle_deg(self.phi3[0], self.phi6[0])
    }

    /// Pressure angle at roller B (deg): cam tangent `B′` against the arm AB.
    pub fn mu_b_deg(&self, g: &ModulatorGeometry) -> f64 {
        roller_pressure_angle_deg(self.b[1], self.b[0] - self.a(g))
    }

    /// Pressure angle at roller C (deg): counter-cam tangent `C′` against the arm AC.
    pub fn mu_c_deg(&self, g: &ModulatorGeometry) -> f64 {
        roller_pressure_angle_deg(self.c[1], self.c[0] - self.a(g))
    }

    /// Pressure angles at rollers B and C (deg), [`Self::mu_b_deg`] and [`Self::mu_c_deg`] with
    /// the crank pin `a` = [`Self::a`] given (the caller has `e(φ2)`).
    pub(crate) fn mu_bc_deg_at(&self, a: Vec2) -> [f64; 2] {
        [roller_pressure_angle_deg(self.b[1], self.b[0] - a), roller_pressure_angle_deg(self.c[1], self.c[0] - a)]
    }

    /// Signed curvature of Γ at B along the direction of travel (1/m); 0 at a cusp.
    pub fn kappa_b(&self) -> f64 {
        curvature(self.b[1], self.b[2]).unwrap_or(0.0)
    }

    /// Signed curvature of Γ′ at C along the direction of travel (1/m); 0 at a cusp.
    pub fn kappa_c(&self) -> f64 {
        curvature(self.c[1], self.c[2]).unwrap_or(0.0)
    }
}

/// The lever arms' fixed angles from the slot as unit vectors, `e(α)` and `e(π − θ)`, computed
/// once per geometry so that a state needs no `sin_cos` of its own for them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ArmAngles {
    ab: Vec2,
    ac: Vec2,
}

impl ArmAngles {
    pub(crate) fn new(g: &ModulatorGeometry) -> Self {
        Self { ab: e(g.alpha_rad()), ac: e(PI - g.theta_rad()) }
    }
}

/// B = A − l3·e(φ3 + α) and C = A + l3′·e(φ3 + π − θ) with their first two φ2-derivatives:
/// `B′ = A′ − l3 φ3′ e⊥(β)`, `B″ = A″ − l3 (φ3″ e⊥(β) − φ3′² e(β))`, `A′ = l2 e⊥(φ2)`, `A″ = −l2 e(φ2)`.
/// `e2 = e(φ2)` and `e3 = e(φ3)` are given, the arms' directions follow by angle addition.
pub(crate) fn lever_points(
    g: &ModulatorGeometry,
    arms: &ArmAngles,
    e2: Vec2,
    e3: Vec2,
    phi3: [f64; 3],
) -> ([Vec2; 3], [Vec2; 3]) {
    let a = [g.l2_m * e2, g.l2_m * perp(e2), -g.l2_m * e2];
    let arm = |len: f64, u: Vec2| -> [Vec2; 3] {
        let n = perp(u);
        [len * u, len * phi3[1] * n, len * (phi3[2] * n - phi3[1] * phi3[1] * u)]
    };
    let ab = arm(g.l3_m, rotate(e3, arms.ab));
    let ac = arm(g.l3p_m, rotate(e3, arms.ac));
    ([a[0] - ab[0], a[1] - ab[1], a[2] - ab[2]], [a[0] + ac[0], a[1] + ac[1], a[2] + ac[2]])
}

/// Loop (3) from φ3 (analysis): D = A − S53·e(φ3) on the circle |D| = l6, the near intersection
/// `S53 = l2 cos(φ2 − φ3) − √(l6² − l2² sin²(φ3 − φ2))`; then the rates from the differentiated loop
/// `[l6 e⊥(φ6), e(φ3)]·(φ6′, S53′) = l2 e⊥(φ2) − S53 φ3′ e⊥(φ3)` and likewise for the second
/// derivatives. `near6 = (φ6_ref, unit)`: `φ6_ref` picks the turn of φ6 (the result is within π
/// of it); with `unit = e(φ6_ref)` (a nearby state's `D/|D|`) φ6 is `φ6_ref` plus the small angle
/// from it ([`crate::planar::angle_near`], no `atan2`) where that angle is small. `e2 = e(φ2)`,
/// `e3 = e(φ3)`; `e(φ6)` is `D/|D|`.
pub(crate) fn slot_from_phi3(
    g: &ModulatorGeometry,
    phi2: f64,
    e2: Vec2,
    phi3: [f64; 3],
    e3: Vec2,
    (phi6_ref, phi6_unit): (f64, Option<Vec2>),
) -> Result<([f64; 3], [f64; 3])> {
    let a = g.l2_m * e2;
    let [s_near, _] = line_circle(a, -e3, Vec2::zeros(), g.l6_m, "slot 5 on output crank 6")?;
    if s_near <= 0.0 {
        return Err(MechError::NoIntersection {
            what: "slot 5 on output crank 6".into(),
            reason: format!("the near intersection lies behind A (S53 = {s_near:.6} m)"),
        });
    }
    let d = a - s_near * e3;
    let phi6 = phi6_unit
        .and_then(|u| crate::planar::angle_near(phi6_ref, u, d))
        .unwrap_or_else(|| crate::planar::unwrap_near(d.y.atan2(d.x), phi6_ref));
    let e6 = d / d.norm();
    let (c1, c2) = (g.l6_m * perp(e6), e3);
    let det = cross(c1, c2);
    let solve = |r: Vec2| (cross(r, c2) / det, cross(c1, r) / det);
    let s = s_near;
    let p3 = perp(e3);
    let r1 = g.l2_m * perp(e2) - s * phi3[1] * p3;
    let (w6, ds) = solve(r1);
    let r2 =
        -g.l2_m * e2 + g.l6_m * w6 * w6 * e6 - 2.0 * ds * phi3[1] * p3 - s * phi3[2] * p3 + s * phi3[1] * phi3[1] * e3;
    let (e6dd, dds) = solve(r2);
    if !(w6.is_finite() && e6dd.is_finite() && ds.is_finite() && dds.is_finite()) {
        return Err(MechError::Singular { input: phi2, det });
    }
    Ok(([s, ds, dds], [phi6, w6, e6dd]))
}

/// Loop (3) from φ6 (synthesis): `w = A − D = S53·e(φ3)`, so `S53 = |w|`, `φ3 = atan2 w`,
/// `φ3′ = (w × w′)/S²`, `S′ = (w·w′)/S`,
/// `φ3″ = (w × w″)/S² − 2(w × w′)(w·w′)/S⁴`, `S″ = (|w′|² + w·w″)/S − (w·w′)²/S³`.
/// `near3 = (φ3_ref, unit)`: `φ3_ref` picks the turn of φ3; with `unit = e(φ3_ref)` (a nearby
/// state's `w/S`) φ3 is `φ3_ref` plus the small angle from it ([`crate::planar::angle_near`], no
/// `atan2`) where that angle is small. S53 ≥ l2 − l6 > 0, so this never fails. Also returns
/// `e(φ3) = w/S`.
pub(crate) fn slot_from_phi6(
    g: &ModulatorGeometry,
    e2: Vec2,
    phi6: [f64; 3],
    (phi3_ref, phi3_unit): (f64, Option<Vec2>),
) -> ([f64; 3], [f64; 3], Vec2) {
    let e6 = e(phi6[0]);
    let p6 = perp(e6);
    let w0 = g.l2_m * e2 - g.l6_m * e6;
    let w1 = g.l2_m * perp(e2) - g.l6_m * phi6[1] * p6;
    let w2 = -g.l2_m * e2 - g.l6_m * (phi6[2] * p6 - phi6[1] * phi6[1] * e6);
    let s2 = w0.norm_squared();
    let s = s2.sqrt();
    let (cr1, dt1) = (cross(w0, w1), w0.dot(&w1));
    let phi3 = phi3_unit
        .and_then(|u| crate::planar::angle_near(phi3_ref, u, w0))
        .unwrap_or_else(|| crate::planar::unwrap_near(w0.y.atan2(w0.x), phi3_ref));
    let d3 = cr1 / s2;
    let dd3 = cross(w0, w2) / s2 - 2.0 * cr1 * dt1 / (s2 * s2);
    let ds = dt1 / s;
    let dds = (w1.norm_squared() + w0.dot(&w2)) / s - dt1 * dt1 / (s2 * s);
    ([phi3, d3, dd3], [s, ds, dds], w0 / s)
}

/// The state at φ2 from the slot angle φ3 and its derivatives (analysis); `e2 = e(φ2)` and
/// `e3 = e(φ3)` come from the caller (the input grid and the cam-loop step have them); φ6 near
/// `near6` ([`slot_from_phi3`]).
pub(crate) fn state_from_phi3(
    g: &ModulatorGeometry,
    arms: &ArmAngles,
    phi2: f64,
    e2: Vec2,
    e3: Vec2,
    phi3: [f64; 3],
    near6: (f64, Option<Vec2>),
) -> Result<ModulatorState> {
    let (s53, phi6) = slot_from_phi3(g, phi2, e2, phi3, e3, near6)?;
    let (b, c) = lever_points(g, arms, e2, e3, phi3);
    Ok(ModulatorState { phi2, phi3, s53, phi6, b, c })
}

/// The state at φ2 from the output angle φ6 and its derivatives (synthesis), with `e(φ3)`;
/// `e2 = e(φ2)`, φ3 near `near3` ([`slot_from_phi6`]).
pub(crate) fn state_from_phi6(
    g: &ModulatorGeometry,
    arms: &ArmAngles,
    phi2: f64,
    e2: Vec2,
    phi6: [f64; 3],
    near3: (f64, Option<Vec2>),
) -> (ModulatorState, Vec2) {
    let (phi3, s53, e3) = slot_from_phi6(g, e2, phi6, near3);
    let (b, c) = lever_points(g, arms, e2, e3, phi3);
    (ModulatorState { phi2, phi3, s53, phi6, b, c }, e3)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two closed forms of loop (3) are inverses, derivatives included.
    #[test]
    fn slot_closed_forms_are_inverse() {
        let g = ModulatorGeometry::PAPER;
        for (phi2, phi6) in [(1.2, [1.0, 0.7, -0.4]), (3.0, [3.3, 1.9, 2.1]), (5.5, [5.6, 0.0, 0.0])] {
            let (phi3, s53, e3) = slot_from_phi6(&g, e(phi2), phi6, (phi2, None));
            assert!((e3 - e(phi3[0])).norm() < 1e-15);
            let (s_back, phi6_back) = slot_from_phi3(&g, phi2, e(phi2), phi3, e(phi3[0]), (phi6[0], None)).unwrap();
            for k in 0..3 {
                assert!((phi6_back[k] - phi6[k]).abs() < 1e-9, "φ6 order {k}: {} vs {}", phi6_back[k], phi6[k]);
                assert!((s_back[k] - s53[k]).abs() < 1e-9, "S53 order {k}");
            }
        }
    }

    #[test]
    fn lever_derivatives_match_finite_differences() {
        let g = ModulatorGeometry::PAPER;
        // φ3(φ2) = 0.3 + 1.1 φ2 + 0.2 sin φ2, an arbitrary smooth motion.
        let f = |x: f64| [0.3 + 1.1 * x + 0.2 * x.sin(), 1.1 + 0.2 * x.cos(), -0.2 * x.sin()];
        let h = 1e-5;
        let arms = ArmAngles::new(&g);
        let lp = |x: f64| lever_points(&g, &arms, e(x), e(f(x)[0]), f(x));
        for x in [0.2, 2.0, 4.4] {
            let (b, c) = lp(x);
            let (bp, cp) = lp(x + h);
            let (bm, cm) = lp(x - h);
            assert!(((bp[0] - bm[0]) / (2.0 * h) - b[1]).norm() < 1e-9);
            assert!(((cp[0] - cm[0]) / (2.0 * h) - c[1]).norm() < 1e-9);
            assert!(((bp[1] - bm[1]) / (2.0 * h) - b[2]).norm() < 1e-8);
            assert!(((cp[1] - cm[1]) / (2.0 * h) - c[2]).norm() < 1e-8);
            // The direct forms of B and C (angle addition against sin_cos of the summed angles).
            let (phi3, a) = (f(x)[0], g.l2_m * e(x));
            assert!((b[0] - (a - g.l3_m * e(phi3 + g.alpha_rad()))).norm() < 1e-15);
            assert!((c[0] - (a + g.l3p_m * e(phi3 + PI - g.theta_rad()))).norm() < 1e-15);
            // The arms keep their lengths.
            assert!(((b[0] - g.l2_m * e(x)).norm() - g.l3_m).abs() < 1e-14);
            assert!(((c[0] - g.l2_m * e(x)).norm() - g.l3p_m).abs() < 1e-14);
        }
    }
}
