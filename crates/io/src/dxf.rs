//! DXF export of polylines (cam profiles, groove walls) for CAD and CAM.
//!
//! Each [`DxfPolyline`] becomes one `LWPOLYLINE` entity on its named layer (AutoCAD 2000 format,
//! readable by every current CAD package). Coordinates are given in metres and written in the
//! chosen [`DxfUnit`], which is also recorded in the header (`$INSUNITS`).
//!
//! ```
//! use loomkin_io::dxf::{DxfPolyline, DxfUnit, write_dxf};
//!
//! let square = DxfPolyline::closed("CAM", vec![[0.0, 0.0], [0.1, 0.0], [0.1, 0.1], [0.0, 0.1]]);
//! let mut out = Vec::new();
//! write_dxf(&[square], DxfUnit::Millimetre, &mut out)?;
//! let text = String::from_utf8(out).unwrap();
//! assert!(text.contains("LWPOLYLINE") && text.contains("CAM"));
//! # Ok::<(), loomkin_io::IoError>(())
//! ```

use crate::IoError;
use dxf::entities::{Entity, EntityType, LwPolyline};
use dxf::enums::{AcadVersion, DrawingUnits, Units};
use dxf::tables::Layer;
use dxf::{Color, Drawing, LwPolylineVertex, Point};
use std::io::Write;
use std::path::Path;

/// Length unit of the coordinates written to the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DxfUnit {
    /// Millimetres (coordinates × 1000), the usual unit of mechanical drawings.
    #[default]
    Millimetre,
    /// Metres (coordinates as given).
    Metre,
}

impl DxfUnit {
    fn scale(self) -> f64 {
        match self {
            DxfUnit::Millimetre => 1000.0,
            DxfUnit::Metre => 1.0,
        }
    }

    fn units(self) -> Units {
        match self {
            DxfUnit::Millimetre => Units::Millimeters,
            DxfUnit::Metre => Units::Meters,
        }
    }
}

/// A polyline on a layer, with points `[x, y]` in metres.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DxfPolyline {
    /// Layer name (letters, digits, `_`, `-`; created if absent).
    pub layer: String,
    /// Vertices `[x, y]` (m).
    pub points: Vec<[f64; 2]>,
    /// Join the last vertex to the first.
    pub closed: bool,
}

impl DxfPolyline {
    /// A closed polyline (the last point must not repeat the first).
    pub fn closed(layer: impl Into<String>, points: Vec<[f64; 2]>) -> Self {
        Self { layer: layer.into(), points, closed: true }
    }

    /// An open polyline.
    pub fn open(layer: impl Into<String>, points: Vec<[f64; 2]>) -> Self {
        Self { layer: layer.into(), points, closed: false }
    }
}

fn check(polylines: &[DxfPolyline]) -> Result<(), IoError> {
    for (i, p) in polylines.iter().enumerate() {
        let name_ok = !p.layer.is_empty() && p.layer.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !name_ok {
            return Err(IoError::Plot(format!(
                "dxf polyline {i}: layer name '{}' must be non-empty ASCII letters, digits, '_' or '-'",
                p.layer
            )));
        }
        if p.points.len() < 2 {
            return Err(IoError::Plot(format!("dxf polyline {i} (layer {}): needs at least 2 points", p.layer)));
        }
        if let Some(row) = p.points.iter().position(|q| !(q[0].is_finite() && q[1].is_finite())) {
            return Err(IoError::NotFinite { column: format!("{} x/y", p.layer), row, value: f64::NAN });
        }
    }
    Ok(())
}

fn drawing(polylines: &[DxfPolyline], unit: DxfUnit) -> Result<Drawing, IoError> {
    check(polylines)?;
    let mut d = Drawing::new();
    d.header.version = AcadVersion::R2000;
    d.header.default_drawing_units = unit.units();
    // Metric drawing ($MEASUREMENT = 1) and the true extents and limits, so that CAD packages open
    // the drawing zoomed on the cams instead of on the default 12 × 9 inch sheet at the origin.
    d.header.drawing_units = DrawingUnits::Metric;
    let k = unit.scale();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in polylines.iter().flat_map(|p| &p.points) {
        for i in 0..2 {
            lo[i] = lo[i].min(q[i] * k);
            hi[i] = hi[i].max(q[i] * k);
        }
    }
    if lo[0].is_finite() {
        d.header.minimum_drawing_extents = Point::new(lo[0], lo[1], 0.0);
        d.header.maximum_drawing_extents = Point::new(hi[0], hi[1], 0.0);
        d.header.minimum_drawing_limits = Point::new(lo[0], lo[1], 0.0);
        d.header.maximum_drawing_limits = Point::new(hi[0], hi[1], 0.0);
    }
    let mut layers: Vec<&str> = Vec::new();
    for p in polylines {
        if !layers.contains(&p.layer.as_str()) {
            layers.push(&p.layer);
        }
    }
    for (i, name) in layers.iter().enumerate() {
        // AutoCAD colour indices 1…6: red, yellow, green, cyan, blue, magenta.
        let layer = Layer { name: name.to_string(), color: Color::from_index((i % 6 + 1) as u8), ..Default::default() };
        d.add_layer(layer);
    }
    for p in polylines {
        let mut poly = LwPolyline::default();
        poly.set_is_closed(p.closed);
        poly.vertices =
            p.points.iter().map(|q| LwPolylineVertex { x: q[0] * k, y: q[1] * k, ..Default::default() }).collect();
        let mut e = Entity::new(EntityType::LwPolyline(poly));
        e.common.layer = p.layer.clone();
        d.add_entity(e);
    }
    Ok(d)
}

/// Writes the polylines as an ASCII DXF drawing to `w`.
pub fn write_dxf(polylines: &[DxfPolyline], unit: DxfUnit, w: &mut dyn Write) -> Result<(), IoError> {
    let d = drawing(polylines, unit)?;
    let mut buf = Vec::new();
    d.save(&mut buf).map_err(|e| IoError::Plot(format!("dxf: {e}")))?;
    w.write_all(&buf)?;
    Ok(())
}

/// Writes the polylines to the file `path`.
pub fn save_dxf(polylines: &[DxfPolyline], unit: DxfUnit, path: &Path) -> Result<(), IoError> {
    let mut f = crate::create_file(path)?;
    write_dxf(polylines, unit, &mut f)?;
    f.flush().map_err(|cause| IoError::File { path: path.display().to_string(), cause })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_through_the_dxf_reader() {
        let circle: Vec<[f64; 2]> = (0..36)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 36.0;
                [0.2 * t.cos(), 0.3 * t.sin()]
            })
            .collect();
        let polys =
            [DxfPolyline::closed("CAM_G", circle.clone()), DxfPolyline::open("WALL", vec![[0.0, 0.0], [0.5, 0.25]])];
        let mut out = Vec::new();
        write_dxf(&polys, DxfUnit::Millimetre, &mut out).unwrap();
        let back = Drawing::load(&mut out.as_slice()).unwrap();
        let ents: Vec<_> = back.entities().collect();
        assert_eq!(ents.len(), 2);
        let EntityType::LwPolyline(p) = &ents[0].specific else { panic!("not a polyline") };
        assert!(p.is_closed());
        assert_eq!(ents[0].common.layer, "CAM_G");
        assert_eq!(p.vertices.len(), 36);
        for (v, q) in p.vertices.iter().zip(&circle) {
            assert!((v.x - q[0] * 1000.0).abs() < 1e-9 && (v.y - q[1] * 1000.0).abs() < 1e-9);
        }
        let EntityType::LwPolyline(w) = &ents[1].specific else { panic!("not a polyline") };
        assert!(!w.is_closed());
        assert!(back.layers().any(|l| l.name == "WALL"));
        assert_eq!(back.header.default_drawing_units, Units::Millimeters);
        assert_eq!(back.header.drawing_units, DrawingUnits::Metric);
        // Extents from the points themselves (mm): x ∈ [−200, 500], y ∈ [−300, 300].
        let xs = circle.iter().map(|q| q[0]).chain([0.0, 0.5]);
        let (xmin, xmax) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
        let (lo, hi) = (&back.header.minimum_drawing_extents, &back.header.maximum_drawing_extents);
        assert!((lo.x - 1000.0 * xmin).abs() < 1e-9 && (hi.x - 1000.0 * xmax).abs() < 1e-9, "{lo:?} {hi:?}");
        assert!((lo.y + 300.0).abs() < 1e-9 && (hi.y - 300.0).abs() < 1e-9, "{lo:?} {hi:?}");
    }

    #[test]
    fn bad_input_is_refused() {
        let mut out = Vec::new();
        assert!(
            write_dxf(&[DxfPolyline::open("A B", vec![[0.0, 0.0], [1.0, 1.0]])], DxfUnit::Metre, &mut out).is_err()
        );
        assert!(write_dxf(&[DxfPolyline::open("A", vec![[0.0, 0.0]])], DxfUnit::Metre, &mut out).is_err());
        assert!(
            write_dxf(&[DxfPolyline::open("A", vec![[0.0, f64::NAN], [1.0, 1.0]])], DxfUnit::Metre, &mut out).is_err()
        );
    }
}
