//! The rotary-dobby modulator's cams for a workshop: both cams as DXF polylines and their point
//! table, the same for `loomkin dobby synthesize --dxf/--points-csv` and the workbench's buttons.

use super::report::CamProfile;
use super::synthesis::Synthesis;
use crate::MechError;
use loomkin_io::drawing::DEFAULT_BORE_FRACTION;
use loomkin_io::dxf::DxfShape;
use loomkin_io::{IoError, Table};
use loomkin_units::mm_from_m;

/// The default chord tolerance of the drawing, mm (`dobby synthesize --chord-tol-mm`).
pub const DEFAULT_CHORD_TOL_MM: f64 = Synthesis::CHORD_TOL_MM.default_value();

/// The drawing of both cams as DXF shapes ([`Synthesis::drawing`]: closed polylines within
/// `chord_tol_mm` of the curves, centre, bore, 0° phase and rollers); the bore defaults to
/// [`DEFAULT_BORE_FRACTION`] × the cams' least radius.
pub fn synthesis_shapes(s: &Synthesis, chord_tol_mm: f64, bore_mm: Option<f64>) -> Result<Vec<DxfShape>, MechError> {
    // The fraction in mm per metre of radius first (0.4 → exactly 400.0), then one product: one rounding.
    let bore_mm = bore_mm.unwrap_or(mm_from_m(DEFAULT_BORE_FRACTION) * s.least_radius_m());
    // The drawing is in metres, as the writer takes it.
    Ok(loomkin_io::drawing::into_dxf(&s.drawing(chord_tol_mm, bore_mm)?, 1.0))
}

/// The cam point table, one row per input angle: centre curve and walls of Γ (`b_…`) and Γ′
/// (`c_…`), in m (walls 0 without a roller).
pub fn synthesis_points_table(s: &Synthesis) -> Result<Table, IoError> {
    let mut t = Table::new([
        "phi2_deg",
        "b_x_m",
        "b_y_m",
        "b_left_x_m",
        "b_left_y_m",
        "b_right_x_m",
        "b_right_y_m",
        "c_x_m",
        "c_y_m",
        "c_left_x_m",
        "c_left_y_m",
        "c_right_x_m",
        "c_right_y_m",
    ]);
    for i in 0..s.cam.centre.len() {
        // Centre and walls of one cam at row i (a wall absent without a roller: 0).
        let cam = |p: &CamProfile| {
            let wall = |v: &[[f64; 2]]| v.get(i).copied().unwrap_or([0.0; 2]);
            [p.centre[i], wall(&p.wall_left), wall(&p.wall_right)]
        };
        let mut row = vec![s.rows[i].phi2_deg];
        row.extend([cam(&s.cam), cam(&s.counter_cam)].iter().flatten().flatten());
        t.push(row)?;
    }
    Ok(t)
}
