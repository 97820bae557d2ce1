//! The curvature of the cams at every traced input angle, for plots and tables. Kept apart from
//! the analysis and synthesis (which only locate the least radius, [`crate::CamChecks`]): it is
//! computed on request from the states they return, so the traced revolution costs nothing more.

use super::kinematics::ModulatorState;
use serde::Serialize;

/// The cams' curvature at one input angle.
///
/// The roller-centre curves are traced by B (cam Γ) and C (counter-cam Γ′) as the input turns, so
/// their curvature follows from the states' exact φ2-derivatives of B and C:
/// `κ = (P′ × P″) / |P′|³` (1/m, positive where the curve turns left along the travel). A groove
/// wall a roller radius `r` to the left of the centre curve has the radius of curvature
/// `1/κ − r` (signed, with the centre curve's sense); the roller undercuts that wall where the
/// centre curve's convex radius `1/|κ|` is below `r`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CamCurvaturePoint {
    /// Input angle φ2 (deg).
    pub phi2_deg: f64,
    /// Signed curvature of Γ's roller-centre curve at B (1/m).
    pub kappa_b_per_m: f64,
    /// Signed curvature of Γ′'s roller-centre curve at C (1/m).
    pub kappa_c_per_m: f64,
    /// Radius of curvature of Γ's roller-centre curve, `1/|κ_B|` (m); `None` where it is straight
    /// (or at a cusp, where B stands still).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rho_b_m: Option<f64>,
    /// Radius of curvature of Γ′'s roller-centre curve, `1/|κ_C|` (m); `None` where straight.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rho_c_m: Option<f64>,
}

fn radius(kappa: f64) -> Option<f64> {
    let r = 1.0 / kappa.abs();
    (kappa != 0.0 && r.is_finite()).then_some(r)
}

/// The curvature of both cams at every state (the analysis' or the synthesis' `states`), in order.
pub fn cam_curvature(states: &[ModulatorState]) -> Vec<CamCurvaturePoint> {
    states
        .iter()
        .map(|s| {
            let (kb, kc) = (s.kappa_b(), s.kappa_c());
            CamCurvaturePoint {
                phi2_deg: s.phi2.to_degrees(),
                kappa_b_per_m: kb,
                kappa_c_per_m: kc,
                rho_b_m: radius(kb),
                rho_c_m: radius(kc),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planar::Vec2;
    use crate::{AnalysisOptions, Cam, ModulatorGeometry, analyze};

    /// Radius of the circle through three points (∞ when they are collinear).
    fn circle_radius(p: Vec2, q: Vec2, r: Vec2) -> f64 {
        let (a, b, c) = ((q - r).norm(), (p - r).norm(), (p - q).norm());
        let area2 = crate::planar::cross(q - p, r - p).abs();
        a * b * c / (2.0 * area2)
    }

    /// The exact curvature (from B′, B″ and C′, C″) against the circle through each state's
    /// neighbours (an independent, derivative-free route): its error is O(h²), so halving the step
    /// divides the largest difference by about four — the exact curvature is the circles' limit.
    /// Γ's radius also against the paper ellipse's closed form `ρ = (a² sin²p + b² cos²p)^{3/2}/(ab)`
    /// at the parameter of B. The least radius found equals the analysis' own `rho_b_min_m`.
    #[test]
    fn curvature_matches_three_point_circles_and_the_ellipse() {
        let g = ModulatorGeometry::PAPER;
        let (a, b) = (0.366, 0.577);
        let worst = |step_deg: f64| -> f64 {
            let opts = AnalysisOptions { step_deg, ..AnalysisOptions::default() };
            let an = analyze(&g, &Cam::paper(), &opts).expect("analysis");
            let k = cam_curvature(&an.states);
            assert_eq!(k.len(), an.states.len());
            let mut worst: f64 = 0.0;
            for i in 1..an.states.len() - 1 {
                let (s0, s1, s2) = (&an.states[i - 1], &an.states[i], &an.states[i + 1]);
                for (exact, three) in [
                    (k[i].kappa_b_per_m, circle_radius(s0.b[0], s1.b[0], s2.b[0])),
                    (k[i].kappa_c_per_m, circle_radius(s0.c[0], s1.c[0], s2.c[0])),
                ] {
                    worst = worst.max((exact.abs() - 1.0 / three).abs());
                }
                // B runs on the ellipse: its parameter p gives the closed-form radius.
                let p = (s1.b[0].y / b).atan2(s1.b[0].x / a);
                assert!(((s1.b[0].x / a).powi(2) + (s1.b[0].y / b).powi(2) - 1.0).abs() < 1e-9, "B on Γ");
                let (sp, cp) = p.sin_cos();
                let rho = (a * a * sp * sp + b * b * cp * cp).powf(1.5) / (a * b);
                let exact = k[i].rho_b_m.expect("Γ is curved everywhere");
                assert!((exact - rho).abs() < 1e-9 * rho, "φ2 {}°: {exact} vs ellipse {rho}", k[i].phi2_deg);
            }
            if step_deg == 0.05 {
                let least = k.iter().filter_map(|p| p.rho_b_m).fold(f64::INFINITY, f64::min);
                let located = an.summary.checks.rho_b_min_m.expect("Γ is curved");
                // The located minimum is at most the grid's least, which comes within O(h²) of it.
                assert!(located <= least * (1.0 + 1e-12) && least - located < 1e-5 * located, "{least} vs {located}");
            }
            worst
        };
        let (coarse, fine) = (worst(0.1), worst(0.05));
        // κ of the paper's Γ is at most b/a² = 4.3 1/m.
        assert!(fine < 2e-5, "three-point circles within {fine} 1/m");
        let ratio = coarse / fine;
        assert!((3.5..4.5).contains(&ratio), "O(h²): halving the step divides the error by {ratio}");
    }
}
