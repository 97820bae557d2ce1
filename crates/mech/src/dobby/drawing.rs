//! The drawing of the modulator's cams: the roller-centre curves and groove walls of Γ and Γ′ as
//! polylines within a chord tolerance, with the centre, bore, 0° phase and roller marks — what
//! `dobby synthesize --dxf` writes.

use super::synthesis::Synthesis;
use crate::{MechError, Result};
use loomkin_io::drawing::{Layered, Shape};
use loomkin_units::{Field, Range};

/// Allowed chord tolerance (mm).
pub const DOBBY_CHORD_TOL_RANGE: Range = Range::closed(1e-3, 1.0, "mm");

/// Input step of the dense curves the drawing's vertices are chosen from (deg).
pub(crate) const DRAW_STEP_DEG: f64 = 0.05;

/// The vertices of the closed dense curve `q` (exact curve points every 0.05° of input) kept so
/// that every dropped point lies within `tol − e` of its chord, `e` being the dense polyline's own
/// deviation from the curve (`|q[k+1] − 2q[k] + q[k−1]| / 8`, the chord bound `M h²/8` with
/// `M h²` the second difference): every chord then stays within `tol` of the curve. Returns the
/// indices kept.
pub(crate) fn chord_indices(q: &[[f64; 2]], tol: f64) -> Result<Vec<usize>> {
    let n = q.len();
    if n < 3 {
        return Ok((0..n).collect());
    }
    let at = |k: usize| q[k % n];
    let e = (0..n)
        .map(|k| {
            let (a, b, c) = (at(k + n - 1), at(k), at(k + 1));
            (a[0] - 2.0 * b[0] + c[0]).hypot(a[1] - 2.0 * b[1] + c[1]) / 8.0
        })
        .fold(0.0, f64::max);
    if e >= 0.5 * tol {
        return Err(MechError::Invalid {
            field: "chord_tol_mm".into(),
            reason: format!(
                "{:e} mm is too fine: at least {:.3e} mm (the cam curves are known every 0.05° and deviate up to \
                 {:.3e} mm between those points)",
                1e3 * tol,
                2e3 * e,
                1e3 * e
            ),
        });
    }
    let allow = tol - e;
    let dist = |p: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let l2 = dx * dx + dy * dy;
        let t = if l2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
        (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
    };
    let mut keep = vec![0];
    let mut i = 0;
    while i < n {
        // The farthest j (up to the closing point n ≡ 0) whose chord holds every point between.
        let mut j = i + 1;
        while j < n && (i + 1..=j).all(|k| dist(at(k), at(i), at(j + 1)) <= allow) {
            j += 1;
        }
        if j >= n {
            break;
        }
        keep.push(j);
        i = j;
    }
    Ok(keep)
}

/// The bore diameter's range in the drawing (mm): none (0) … 10 m.
pub const DOBBY_BORE_RANGE: Range = Range::closed(0.0, 1e4, "mm");

impl Synthesis {
    /// `chord_tol_mm` of the cams' drawing (`dobby synthesize --chord-tol-mm`): a micrometre (the
    /// drawing's vertices are picked from curve points every 0.05° of input, finer than that they
    /// run out) … 1 mm; 0.01 mm.
    pub const CHORD_TOL_MM: Field = Field::new(
        "chord_tol_mm",
        DOBBY_CHORD_TOL_RANGE,
        "Chord tolerance of the dobby cams' DXF polylines, mm: 0.001 (the curves are known every 0.05° of input) \
         … 1; 0.01 mm (below a machine shop's tolerance) when left out.",
    )
    .with_default(loomkin_io::drawing::DEFAULT_CHORD_TOL_MM);
    /// `bore_mm` of the cams' drawing (`dobby synthesize --bore-mm`): 0 (none) … 10 m, clearing
    /// the cams; left out, 0.4 × the cams' least radius.
    pub const BORE_MM: Field = Field::new(
        "bore_mm",
        DOBBY_BORE_RANGE,
        "Bore diameter about the crank centre in the dobby cams' DXF, mm: 0 (none) … 10000, below the cams' \
         least diameter; left out, 0.4 × their least radius.",
    );

    /// The drawing of both cams (coordinates in m, the tolerance and bore in mm as the CLI takes them): layers `CAM_CENTRE`, `CAM_WALL_LEFT`, `CAM_WALL_RIGHT` and the
    /// same for `COUNTER_CAM_*` (walls only with a roller), as closed polylines whose chords stay
    /// within `chord_tol_mm` of the curves whatever the table step; `CENTRE` (a cross at the crank
    /// centre O), `BORE` (`bore_mm` diameter about O; none when 0), `PHASE_0` (from O to roller B at
    /// input angle 0°) and `ROLLER` (both rollers at 0°).
    pub fn drawing(&self, chord_tol_mm: f64, bore_mm: f64) -> Result<Vec<Layered>> {
        let tol = 1e-3 * Self::CHORD_TOL_MM.check(chord_tol_mm)?;
        let bore = 1e-3 * Self::BORE_MM.check(bore_mm)?;
        let mut out = Vec::new();
        let mut least = f64::INFINITY;
        let [draw_cam, draw_counter_cam] = self.dense_profiles();
        for (names, p) in [
            (["CAM_CENTRE", "CAM_WALL_LEFT", "CAM_WALL_RIGHT"], draw_cam),
            (["COUNTER_CAM_CENTRE", "COUNTER_CAM_WALL_LEFT", "COUNTER_CAM_WALL_RIGHT"], draw_counter_cam),
        ] {
            for (layer, curve) in names.into_iter().zip([&p.centre, &p.wall_left, &p.wall_right]) {
                if curve.is_empty() {
                    continue;
                }
                least = curve.iter().map(|q| q[0].hypot(q[1])).fold(least, f64::min);
                let points = chord_indices(curve, tol)?.into_iter().map(|k| curve[k]).collect();
                out.push(Layered { layer, shape: Shape::Polyline { points, closed: true } });
            }
        }
        if bore > 0.0 && 0.5 * bore >= least {
            return Err(MechError::Invalid {
                field: "bore_mm".into(),
                reason: format!(
                    "a bore of {} mm does not clear the cams: it must be below {:.3} mm (their least radius is \
                     {:.3} mm)",
                    1e3 * bore,
                    2e3 * least,
                    1e3 * least
                ),
            });
        }
        let arm = 0.15 * least;
        out.push(Layered { layer: "CENTRE", shape: Shape::Line { from: [-arm, 0.0], to: [arm, 0.0] } });
        out.push(Layered { layer: "CENTRE", shape: Shape::Line { from: [0.0, -arm], to: [0.0, arm] } });
        if bore > 0.0 {
            out.push(Layered { layer: "BORE", shape: Shape::Circle { centre: [0.0, 0.0], radius: 0.5 * bore } });
        }
        let (b0, c0) = (draw_cam.centre[0], draw_counter_cam.centre[0]);
        out.push(Layered { layer: "PHASE_0", shape: Shape::Line { from: [0.0, 0.0], to: b0 } });
        let r = self.summary.roller_m;
        if r > 0.0 {
            for c in [b0, c0] {
                out.push(Layered { layer: "ROLLER", shape: Shape::Circle { centre: c, radius: r } });
            }
        }
        Ok(out)
    }

    /// The least distance of the cam curves from the crank centre O (m).
    pub fn least_radius_m(&self) -> f64 {
        self.dense_profiles()
            .iter()
            .flat_map(|p| p.centre.iter().chain(&p.wall_left).chain(&p.wall_right))
            .map(|q| q[0].hypot(q[1]))
            .fold(f64::INFINITY, f64::min)
    }
}
