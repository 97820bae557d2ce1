//! A drawing as the libraries make it: shapes on named layers, in the unit the drawing states (the
//! dobby's cams in m, a cam profile in mm), and the same drawing as the DXF writer's shapes in
//! metres ([`into_dxf`]).

use crate::dxf::{DxfPolyline, DxfShape};

/// A drawn shape, coordinates in the unit of its drawing.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A polyline; `closed` joins the last point to the first.
    Polyline {
        /// The vertices.
        points: Vec<[f64; 2]>,
        /// Closed.
        closed: bool,
    },
    /// A circle.
    Circle {
        /// Centre.
        centre: [f64; 2],
        /// Radius.
        radius: f64,
    },
    /// A line segment.
    Line {
        /// Start.
        from: [f64; 2],
        /// End.
        to: [f64; 2],
    },
}

/// A shape on a named layer.
#[derive(Debug, Clone, PartialEq)]
pub struct Layered {
    /// Layer name.
    pub layer: &'static str,
    /// The shape.
    pub shape: Shape,
}

impl Layered {
    /// The shape for the DXF writer, which takes metres: every coordinate and radius times
    /// `metres_per_unit` (1 for a drawing in m, 1e-3 for one in mm).
    pub fn to_dxf(&self, metres_per_unit: f64) -> DxfShape {
        let k = metres_per_unit;
        let m = |p: &[f64; 2]| [p[0] * k, p[1] * k];
        let layer = self.layer.to_string();
        match &self.shape {
            Shape::Polyline { points, closed } => {
                DxfShape::Polyline(DxfPolyline { layer, points: points.iter().map(m).collect(), closed: *closed })
            }
            Shape::Circle { centre, radius } => DxfShape::Circle { layer, centre: m(centre), radius: radius * k },
            Shape::Line { from, to } => DxfShape::Line { layer, from: m(from), to: m(to) },
        }
    }
}

/// How far a drawing's polyline chords may leave the curve when none is given, mm: 10 µm, below a
/// machine shop's tolerance. The cam profile's and the dobby cams' drawings take it from here.
pub const DEFAULT_CHORD_TOL_MM: f64 = 0.01;

/// The bore drawn about a cam's centre when none is given, as a fraction of the cam's least
/// radius (a cam profile's base circle, the dobby cams' least radius): a hub that leaves the cam's
/// web wider than the bore's radius. Both cam drawings take it from here.
pub const DEFAULT_BORE_FRACTION: f64 = 0.4;

/// A drawing as the DXF writer's shapes in metres ([`Layered::to_dxf`] of each).
pub fn into_dxf(drawing: &[Layered], metres_per_unit: f64) -> Vec<DxfShape> {
    drawing.iter().map(|l| l.to_dxf(metres_per_unit)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn millimetres_become_metres_and_layers_stay() {
        let d = [
            Layered { layer: "CAM", shape: Shape::Polyline { points: vec![[1.0, 2.0], [3.0, -4.0]], closed: true } },
            Layered { layer: "BORE", shape: Shape::Circle { centre: [0.0, 5.0], radius: 10.0 } },
            Layered { layer: "PHASE_0", shape: Shape::Line { from: [0.0, 0.0], to: [0.0, -250.0] } },
        ];
        let s = into_dxf(&d, 1e-3);
        assert_eq!(s[0], DxfShape::Polyline(DxfPolyline::closed("CAM", vec![[1e-3, 2e-3], [3e-3, -4e-3]])));
        assert_eq!(s[1], DxfShape::Circle { layer: "BORE".into(), centre: [0.0, 5e-3], radius: 1e-2 });
        assert_eq!(s[2], DxfShape::Line { layer: "PHASE_0".into(), from: [0.0, 0.0], to: [0.0, -0.25] });
        // A drawing in metres passes bit for bit (× 1 is exact), the sign of a zero included.
        let m = Layered { layer: "L", shape: Shape::Line { from: [-0.0, 0.1], to: [1e-300, 7.25] } };
        let DxfShape::Line { from, to, .. } = m.to_dxf(1.0) else { panic!("not a line") };
        assert_eq!((from[0].to_bits(), from[1].to_bits()), ((-0.0f64).to_bits(), 0.1f64.to_bits()));
        assert_eq!((to[0].to_bits(), to[1].to_bits()), (1e-300f64.to_bits(), 7.25f64.to_bits()));
    }
}
