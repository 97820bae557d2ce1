//! What a drawing of the cam holds, layer by layer, with the curves within a chord tolerance.

use super::cam::{CamProfile, Curve};
use super::design::Closure;
use crate::Result;
use loomkin_io::drawing::{Layered, Shape};
use loomkin_units::{Field, Range};

/// Allowed chord tolerance (mm).
pub const CHORD_TOL_RANGE: Range = Range::closed(1e-6, 10.0, "mm");
/// Allowed bore diameter (mm).
pub const BORE_RANGE: Range = Range::closed(0.0, 1e5, "mm");
/// The chord tolerance of a drawing when none is given (mm): a hundredth of a millimetre, within
/// the accuracy of a machined cam.
pub const DEFAULT_CHORD_TOL_MM: f64 = loomkin_io::drawing::DEFAULT_CHORD_TOL_MM;
/// The bore diameter drawn when none is given, as a fraction of the base circle radius.
pub const DEFAULT_BORE_PER_BASE_RADIUS: f64 = loomkin_io::drawing::DEFAULT_BORE_FRACTION;

impl CamProfile {
    /// `chord_tol_mm`: how far a drawing's polyline chords may leave the curve: a nanometre … 10 mm;
    /// 0.01 mm (below a machine shop's tolerance) when left out.
    pub const CHORD_TOL_MM: Field = Field::new(
        "chord_tol_mm",
        CHORD_TOL_RANGE,
        "Chord tolerance of the drawing's polylines: 1e-6 … 10 mm; 0.01 mm (below a machine shop's \
         tolerance) when left out.",
    )
    .with_default(DEFAULT_CHORD_TOL_MM);
    /// `bore_mm`: the bore diameter drawn (0: none); left out, 0.4 × the base radius.
    pub const BORE_MM: Field = Field::new(
        "bore_mm",
        BORE_RANGE,
        "Bore diameter drawn: 0 (none) … 100 m, inside the base circle; left out, 0.4 × the base radius.",
    );

    /// The bore diameter to draw: `given`, else 0.4 × the base radius ([`CamProfile::BORE_MM`]).
    pub fn bore_mm_or(&self, given: Option<f64>) -> f64 {
        given.unwrap_or_else(|| self.default_bore_mm())
    }

    /// The drawing of the cam (mm, cam frame: the cam centre at the origin, the follower at
    /// main-shaft angle 0° along the phase mark): layers `CAM_PITCH`, `CAM_PROFILE` (and `COUNTER_PITCH`,
    /// `COUNTER_PROFILE` for a conjugate pair — the counter-cam on its own layers, same centre and
    /// phase — or `GROOVE_OUTER` for a groove cam), `BASE_CIRCLE`, `CENTRE` (a cross), `BORE`
    /// (`bore_mm` diameter; none when 0) and `PHASE_0` (from the centre to the pitch point at
    /// main-shaft angle 0°). Curves are polylines whose chords stay within `tol_mm` of the curve.
    pub fn drawing(&self, tol_mm: f64, bore_mm: f64) -> Result<Vec<Layered>> {
        let tol = CHORD_TOL_RANGE.check("chord_tol_mm", tol_mm)?;
        let bore = BORE_RANGE.check("bore_mm", bore_mm)?;
        let rb = self.base_radius_mm();
        if bore > 0.0 && 0.5 * bore >= rb {
            return Err(crate::CamError::Usage {
                field: "bore_mm".into(),
                reason: format!(
                    "a bore of {} mm does not fit inside the base circle of {} mm diameter",
                    loomkin_units::compact(bore),
                    loomkin_units::compact(2.0 * rb)
                ),
            });
        }
        let poly = |c: Curve| Shape::Polyline { points: self.polyline(c, tol), closed: true };
        let mut out = vec![
            Layered { layer: "CAM_PITCH", shape: poly(Curve::Pitch(0)) },
            Layered { layer: "CAM_PROFILE", shape: poly(Curve::Wall(0)) },
        ];
        match self.design().closure {
            Closure::Conjugate => {
                out.push(Layered { layer: "COUNTER_PITCH", shape: poly(Curve::Pitch(1)) });
                out.push(Layered { layer: "COUNTER_PROFILE", shape: poly(Curve::Wall(1)) });
            }
            Closure::Groove => out.push(Layered { layer: "GROOVE_OUTER", shape: poly(Curve::Wall(1)) }),
            Closure::Single => {}
        }
        out.push(Layered { layer: "BASE_CIRCLE", shape: Shape::Circle { centre: [0.0, 0.0], radius: rb } });
        let arm = 0.15 * rb;
        out.push(Layered { layer: "CENTRE", shape: Shape::Line { from: [-arm, 0.0], to: [arm, 0.0] } });
        out.push(Layered { layer: "CENTRE", shape: Shape::Line { from: [0.0, -arm], to: [0.0, arm] } });
        if bore > 0.0 {
            out.push(Layered { layer: "BORE", shape: Shape::Circle { centre: [0.0, 0.0], radius: 0.5 * bore } });
        }
        out.push(Layered { layer: "PHASE_0", shape: Shape::Line { from: [0.0, 0.0], to: self.phase_point() } });
        Ok(out)
    }

    /// The [`drawing`](Self::drawing) as the text of a complete DXF file in millimetres
    /// (`loomkin_io::dxf`: AutoCAD 2000, every section, byte-identical for identical input) — the
    /// one route of `cam profile --dxf` and of the workbench's download.
    pub fn dxf(&self, tol_mm: f64, bore_mm: f64) -> Result<String> {
        use loomkin_io::dxf::{DxfUnit, dxf_text};
        // The drawing is in mm, the writer takes metres.
        let shapes = loomkin_io::drawing::into_dxf(&self.drawing(tol_mm, bore_mm)?, 1e-3);
        dxf_text(&shapes, DxfUnit::Millimetre)
            .map_err(|e| crate::CamError::Usage { field: "dxf".into(), reason: e.to_string() })
    }

    /// The bore diameter drawn when none is given (mm): [`DEFAULT_BORE_PER_BASE_RADIUS`] of the
    /// base circle radius.
    pub fn default_bore_mm(&self) -> f64 {
        DEFAULT_BORE_PER_BASE_RADIUS * self.base_radius_mm()
    }
}
