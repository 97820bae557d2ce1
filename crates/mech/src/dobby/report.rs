//! Checks over a traced revolution: extremes of rates, pressure angles, curvature, closure,
//! self-intersection, undercut; shared by analysis and synthesis.

use super::checks::{
    Crossing, Warning, WarningCode, roller_pressure_angle_deg, roller_pressure_order, self_intersections,
    winds_once_about,
};
use super::geometry::ModulatorGeometry;
use super::kinematics::ModulatorState;
use super::refine::{Extreme, Revolution};
use crate::planar::{Vec2, perp};
use serde::Serialize;

/// The checks of one revolution (all angles in deg, lengths in m, rates at the input speed).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CamChecks {
    /// Smallest output speed ω6 (rad/s).
    pub omega6_min_rad_s: f64,
    /// Largest output speed ω6 (rad/s).
    pub omega6_max_rad_s: f64,
    /// Smallest output acceleration ε6 (rad/s²).
    pub eps6_min_rad_s2: f64,
    /// Largest output acceleration ε6 (rad/s²).
    pub eps6_max_rad_s2: f64,
    /// Output turn over the revolution, φ6(end) − φ6(start) (deg); 360 for one revolution.
    pub phi6_turn_deg: f64,
    /// Largest output pressure angle μ6 (deg).
    pub mu_out_max_deg: f64,
    /// Input angle φ2 of the largest μ6 (deg).
    pub mu_out_max_at_phi2_deg: f64,
    /// Largest pressure angle at roller B on cam Γ (deg).
    pub mu_b_max_deg: f64,
    /// Input angle φ2 of the largest μB (deg).
    pub mu_b_max_at_phi2_deg: f64,
    /// Largest pressure angle at roller C on counter-cam Γ′ (deg).
    pub mu_c_max_deg: f64,
    /// Input angle φ2 of the largest μC (deg).
    pub mu_c_max_at_phi2_deg: f64,
    /// Smallest radius of curvature of Γ's roller-centre curve (m); `None` if it is straight.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rho_b_min_m: Option<f64>,
    /// Input angle φ2 of the smallest radius of curvature of Γ (deg).
    pub rho_b_min_at_phi2_deg: f64,
    /// Smallest radius of curvature of Γ′'s roller-centre curve (m); `None` if it is straight.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rho_c_min_m: Option<f64>,
    /// Input angle φ2 of the smallest radius of curvature of Γ′ (deg).
    pub rho_c_min_at_phi2_deg: f64,
    /// Largest roller radius (m) that undercuts neither groove: `min(ρB_min, ρC_min)`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roller_max_m: Option<f64>,
    /// Distance between the first and last point of B's path (m): 0 for a closed revolution.
    pub closure_gap_b_m: f64,
    /// Distance between the first and last point of C's path (m).
    pub closure_gap_c_m: f64,
    /// Self-crossings of the roller-centre curve of Γ.
    pub self_intersections_b: usize,
    /// Self-crossings of the roller-centre curve of Γ′.
    pub self_intersections_c: usize,
}

/// Polylines of one cam: its roller-centre curve and the two groove walls offset by the roller
/// radius `r` along the left normal `n̂ = perp(B′)/|B′|` of the direction of travel (`+r`) and
/// against it (`−r`). No point is repeated at the end: the polylines are closed.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct CamProfile {
    /// Roller-centre curve (m).
    pub centre: Vec<[f64; 2]>,
    /// Groove wall `centre + r·n̂` (m).
    pub wall_left: Vec<[f64; 2]>,
    /// Groove wall `centre − r·n̂` (m).
    pub wall_right: Vec<[f64; 2]>,
}

impl CamProfile {
    /// The profile of a path `(point, tangent)` for roller radius `r_m` (0 gives empty walls), its
    /// points taken as they come (no table of them first).
    pub(crate) fn from_points(path: impl ExactSizeIterator<Item = (Vec2, Vec2)>, r_m: f64) -> Self {
        let walls = if r_m > 0.0 { path.len() } else { 0 };
        let mut out = CamProfile {
            centre: Vec::with_capacity(path.len()),
            wall_left: Vec::with_capacity(walls),
            wall_right: Vec::with_capacity(walls),
        };
        let mut normals = WallNormals::default();
        for (p, t) in path {
            let n = normals.next(t);
            out.centre.push([p.x, p.y]);
            if r_m > 0.0 {
                let (l, r) = (p + r_m * n, p - r_m * n);
                out.wall_left.push([l.x, l.y]);
                out.wall_right.push([r.x, r.y]);
            }
        }
        out
    }
}

/// The unit normals of the groove walls along a path: the left normal `perp(t)/|t|` of each tangent
/// `t`, the last one kept where the tangent (nearly) vanishes.
struct WallNormals(Vec2);

impl Default for WallNormals {
    fn default() -> Self {
        Self(Vec2::new(0.0, 1.0))
    }
}

impl WallNormals {
    fn next(&mut self, t: Vec2) -> Vec2 {
        let n = t.norm();
        if n > 1e-12 {
            self.0 = perp(t) / n;
        }
        self.0
    }
}

/// Self-crossings of both groove walls of the closed path `(point, tangent)` for roller radius
/// `r_m` (0: no walls, none), as [`CamProfile::from_points`] would draw them and
/// [`self_intersections`] count them; the two walls are formed in one pass (one normal a point).
pub(crate) fn wall_crossings(path: impl ExactSizeIterator<Item = (Vec2, Vec2)>, r_m: f64) -> usize {
    if r_m <= 0.0 {
        return 0;
    }
    let (mut left, mut right) = (Vec::with_capacity(path.len()), Vec::with_capacity(path.len()));
    let mut normals = WallNormals::default();
    for (p, t) in path {
        let n = normals.next(t);
        left.push(p + r_m * n);
        right.push(p + (-r_m) * n);
    }
    self_intersections(&left, true, 1000).len() + self_intersections(&right, true, 1000).len()
}

/// Runs every check over one revolution: each extreme is refined between the points of the check
/// grid ([`Revolution::max`]), so that none depends on the output step.
pub(crate) fn check_states(
    g: &ModulatorGeometry,
    rev: &Revolution<'_>,
    w2: f64,
    pressure_limit_deg: f64,
    warnings: &mut Vec<Warning>,
) -> CamChecks {
    let states = &rev.states;
    let w6max = rev.max_output(&|p| p[1] * w2);
    let w6min = rev.min_output(&|p| p[1] * w2);
    let e6max = rev.max_output(&|p| p[2] * w2 * w2);
    let e6min = rev.min_output(&|p| p[2] * w2 * w2);
    let mo = rev.max(&|s| s.mu_out_deg());
    // The grid's largest roller pressure angles are chosen by tan μ, μ formed only where read.
    let mb = rev.max_with_pin_ordered(g, &|s, a| roller_pressure_order(s.b[1], s.b[0] - a), &|s, a| {
        roller_pressure_angle_deg(s.b[1], s.b[0] - a)
    });
    let mc = rev.max_with_pin_ordered(g, &|s, a| roller_pressure_order(s.c[1], s.c[0] - a), &|s, a| {
        roller_pressure_angle_deg(s.c[1], s.c[0] - a)
    });
    let kb = rev.max(&|s| s.kappa_b().abs());
    let kc = rev.max(&|s| s.kappa_c().abs());
    // A stationary point of C (|C′| = 0) is a cusp of Γ′.
    let c_speed = rev.min(&|s| s.c[1].norm());
    let cusp_c = (c_speed.value < 1e-9 * g.l2_m).then(|| c_speed.at_deg());
    let (first, last) = (states[0], states[states.len() - 1]);
    let rho = |k: &Extreme| (k.value.is_finite() && k.value > 0.0).then(|| 1.0 / k.value);
    let (rho_b, rho_c) = (rho(&kb), rho(&kc));
    // The roller-centre curves on the check grid (the last state repeats the first).
    let n = states.len() - 1;
    let gather = |f: &dyn Fn(&ModulatorState) -> Vec2| -> Vec<Crossing> {
        if winds_once_about(n, |i| f(&states[i])) {
            return Vec::new();
        }
        let points: Vec<Vec2> = states[..n].iter().map(f).collect();
        self_intersections(&points, true, 1000)
    };
    let (xb, xc) = (gather(&|s| s.b[0]), gather(&|s| s.c[0]));
    for (name, peak) in
        [("the output (slot on crank 6)", mo), ("roller B on cam Γ", mb), ("roller C on counter-cam Γ′", mc)]
    {
        if peak.value > pressure_limit_deg {
            warnings.push(Warning {
                code: WarningCode::PressureAngle,
                phi2_deg: Some(peak.at_deg()),
                message: format!(
                    "pressure angle at {name} reaches {:.2}° at φ2 = {:.2}°, above the limit {}°",
                    peak.value,
                    peak.at_deg(),
                    loomkin_units::compact(pressure_limit_deg)
                ),
            });
        }
    }
    if let Some(at) = cusp_c {
        warnings.push(Warning {
            code: WarningCode::Cusp,
            phi2_deg: Some(at),
            message: format!("the counter-cam curve Γ′ has a stationary point (cusp) at φ2 = {at:.2}°"),
        });
    }
    for (name, x) in [("cam Γ", &xb), ("counter-cam Γ′", &xc)] {
        if let Some(c) = x.first() {
            warnings.push(Warning {
                code: WarningCode::SelfIntersection,
                phi2_deg: None,
                message: format!(
                    "the roller-centre curve of {name} crosses itself {} time(s), first at ({:.6}, {:.6}) m",
                    x.len(),
                    c.x_m,
                    c.y_m
                ),
            });
        }
    }
    CamChecks {
        omega6_min_rad_s: w6min.value_or(0.0),
        omega6_max_rad_s: w6max.value_or(0.0),
        eps6_min_rad_s2: e6min.value_or(0.0),
        eps6_max_rad_s2: e6max.value_or(0.0),
        phi6_turn_deg: (last.phi6[0] - first.phi6[0]).to_degrees(),
        mu_out_max_deg: mo.value_or(0.0),
        mu_out_max_at_phi2_deg: mo.at_deg(),
        mu_b_max_deg: mb.value_or(0.0),
        mu_b_max_at_phi2_deg: mb.at_deg(),
        mu_c_max_deg: mc.value_or(0.0),
        mu_c_max_at_phi2_deg: mc.at_deg(),
        rho_b_min_m: rho_b,
        rho_b_min_at_phi2_deg: kb.at_deg(),
        rho_c_min_m: rho_c,
        rho_c_min_at_phi2_deg: kc.at_deg(),
        roller_max_m: match (rho_b, rho_c) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        },
        closure_gap_b_m: (last.b[0] - first.b[0]).norm(),
        closure_gap_c_m: (last.c[0] - first.c[0]).norm(),
        self_intersections_b: xb.len(),
        self_intersections_c: xc.len(),
    }
}

/// Undercut flags and warnings for a roller radius against the smallest radii of curvature.
pub(crate) fn undercut(checks: &CamChecks, roller_m: f64, warnings: &mut Vec<Warning>) -> (bool, bool) {
    let mut flag = |rho: Option<f64>, at: f64, name: &str| -> bool {
        match rho {
            Some(r) if r < roller_m => {
                warnings.push(Warning {
                    code: WarningCode::Undercut,
                    phi2_deg: Some(at),
                    message: format!(
                        "undercut of {name}: roller radius {roller_m} m exceeds the smallest radius of curvature \
                         {r:.6} m at φ2 = {at:.2}°; admissible roller radius < {r:.6} m"
                    ),
                });
                true
            }
            _ => false,
        }
    };
    let b = flag(checks.rho_b_min_m, checks.rho_b_min_at_phi2_deg, "cam Γ");
    let c = flag(checks.rho_c_min_m, checks.rho_c_min_at_phi2_deg, "counter-cam Γ′");
    (b, c)
}
