//! DXF export (AutoCAD 2000, `AC1015`) of polylines, circles and lines for CAD and CAM.
//!
//! The file is complete, as strict CAD readers expect it: a `HEADER` (`$ACADVER`, `$HANDSEED`,
//! `$INSUNITS`, `$MEASUREMENT`, extents and limits), empty `CLASSES`, `TABLES` (`VPORT`, `LTYPE`,
//! `LAYER`, `STYLE`, `VIEW`, `UCS`, `APPID`, `DIMSTYLE`, `BLOCK_RECORD`, every table and record with
//! its handle and owner), `BLOCKS` (`*Model_Space`, `*Paper_Space`), `ENTITIES` and `OBJECTS` (the
//! root dictionary with `ACAD_GROUP` and `ACAD_LAYOUT`, and the `Model` and `Layout1` layouts).
//! Handles are numbered in a fixed order and no time or GUID is written, so the same drawing
//! gives the same bytes. Coordinates are given in metres and written in the chosen [`DxfUnit`].
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
use std::fmt::Write as _;
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

    /// The `$INSUNITS` code: 4 millimetres, 6 metres.
    fn insunits(self) -> i32 {
        match self {
            DxfUnit::Millimetre => 4,
            DxfUnit::Metre => 6,
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

/// A drawn shape, coordinates in metres.
#[derive(Debug, Clone, PartialEq)]
pub enum DxfShape {
    /// `LWPOLYLINE`.
    Polyline(DxfPolyline),
    /// `CIRCLE`: centre `[x, y]` and radius (m).
    Circle {
        /// Layer name.
        layer: String,
        /// Centre (m).
        centre: [f64; 2],
        /// Radius (m, > 0).
        radius: f64,
    },
    /// `LINE` from `from` to `to` (m).
    Line {
        /// Layer name.
        layer: String,
        /// Start (m).
        from: [f64; 2],
        /// End (m).
        to: [f64; 2],
    },
}

impl DxfShape {
    fn layer(&self) -> &str {
        match self {
            DxfShape::Polyline(p) => &p.layer,
            DxfShape::Circle { layer, .. } | DxfShape::Line { layer, .. } => layer,
        }
    }

    /// Points that bound the shape (for the extents).
    fn bounds(&self) -> Vec<[f64; 2]> {
        match self {
            DxfShape::Polyline(p) => p.points.clone(),
            DxfShape::Circle { centre: c, radius: r, .. } => vec![[c[0] - r, c[1] - r], [c[0] + r, c[1] + r]],
            DxfShape::Line { from, to, .. } => vec![*from, *to],
        }
    }
}

fn check(shapes: &[DxfShape]) -> Result<(), IoError> {
    for (i, s) in shapes.iter().enumerate() {
        let layer = s.layer();
        let name_ok = !layer.is_empty()
            && layer.len() <= 255
            && layer.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !name_ok {
            return Err(IoError::Plot(format!(
                "dxf shape {i}: layer name '{layer}' must be non-empty ASCII letters, digits, '_' or '-'"
            )));
        }
        if let DxfShape::Polyline(p) = s
            && p.points.len() < 2
        {
            return Err(IoError::Plot(format!("dxf polyline {i} (layer {layer}): needs at least 2 points")));
        }
        if let DxfShape::Circle { radius, .. } = s
            && !(radius.is_finite() && *radius > 0.0)
        {
            return Err(IoError::NotFinite { column: format!("{layer} radius"), row: i, value: *radius });
        }
        if let Some(row) = s.bounds().iter().position(|q| !(q[0].is_finite() && q[1].is_finite())) {
            return Err(IoError::NotFinite { column: format!("{layer} x/y"), row, value: f64::NAN });
        }
    }
    Ok(())
}

/// AutoCAD colour index of a layer: fixed for the cam layers, else by order (1…6).
fn colour(name: &str, index: usize) -> i32 {
    match name {
        "CAM_PROFILE" => 7,
        "CAM_PITCH" => 3,
        "COUNTER_PROFILE" => 1,
        "COUNTER_PITCH" => 6,
        "GROOVE_OUTER" => 5,
        "BASE_CIRCLE" => 8,
        "CENTRE" | "PHASE_0" => 2,
        "BORE" => 4,
        _ => (index % 6 + 1) as i32,
    }
}

/// Group-code writer with sequential handles.
struct Out {
    text: String,
    next: u32,
}

impl Out {
    fn pair(&mut self, code: i32, value: impl std::fmt::Display) {
        let _ = write!(self.text, "{code:>3}\n{value}\n");
    }

    fn num(&mut self, code: i32, v: f64) {
        // Shortest round-trip decimal, no exponent, no negative zero: the same drawing, the same bytes.
        let v = if v == 0.0 { 0.0 } else { v };
        self.pair(code, v);
    }

    fn point(&mut self, code: i32, p: [f64; 2]) {
        self.num(code, p[0]);
        self.num(code + 10, p[1]);
        self.num(code + 20, 0.0);
    }

    /// The header groups every entity (and `BLOCK`/`ENDBLK`) starts with: type, handle, owner,
    /// `AcDbEntity`, paper space flag (`67 1`, paper space only) and layer.
    fn entity(&mut self, kind: &str, handle: u32, owner: u32, paper: bool, layer: &str) {
        self.pair(0, kind);
        self.pair(5, hex(handle));
        self.pair(330, hex(owner));
        self.pair(100, "AcDbEntity");
        if paper {
            self.pair(67, 1);
        }
        self.pair(8, layer);
    }

    fn handle(&mut self) -> u32 {
        let h = self.next;
        self.next += 1;
        h
    }
}

fn hex(h: u32) -> String {
    format!("{h:X}")
}

/// The drawing as DXF text: shapes in metres written in `unit`.
pub fn dxf_text(shapes: &[DxfShape], unit: DxfUnit) -> Result<String, IoError> {
    check(shapes)?;
    let k = unit.scale();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in shapes.iter().flat_map(DxfShape::bounds) {
        for i in 0..2 {
            lo[i] = lo[i].min(q[i] * k);
            hi[i] = hi[i].max(q[i] * k);
        }
    }
    if !lo[0].is_finite() {
        (lo, hi) = ([0.0; 2], [0.0; 2]);
    }
    let mut layers: Vec<&str> = vec!["0"];
    for s in shapes {
        if !layers.contains(&s.layer()) {
            layers.push(s.layer());
        }
    }

    // Handles, in a fixed order.
    let mut o = Out { text: String::new(), next: 1 };
    let root = o.handle();
    let group_dict = o.handle();
    let layout_dict = o.handle();
    let t_vport = o.handle();
    let vport = o.handle();
    let t_ltype = o.handle();
    let ltypes = [o.handle(), o.handle(), o.handle()];
    let t_layer = o.handle();
    let layer_h: Vec<u32> = layers.iter().map(|_| o.handle()).collect();
    let t_style = o.handle();
    let style = o.handle();
    let t_view = o.handle();
    let t_ucs = o.handle();
    let t_appid = o.handle();
    let appid = o.handle();
    let t_dimstyle = o.handle();
    let dimstyle = o.handle();
    let t_brec = o.handle();
    let (br_ms, br_ps) = (o.handle(), o.handle());
    let (blk_ms, end_ms, blk_ps, end_ps) = (o.handle(), o.handle(), o.handle(), o.handle());
    let (layout_ms, layout_ps) = (o.handle(), o.handle());
    let entity_h: Vec<u32> = shapes.iter().map(|_| o.handle()).collect();
    let seed = o.next;

    // HEADER
    o.pair(0, "SECTION");
    o.pair(2, "HEADER");
    o.pair(9, "$ACADVER");
    o.pair(1, "AC1015");
    o.pair(9, "$ACADMAINTVER");
    o.pair(70, 6);
    o.pair(9, "$DWGCODEPAGE");
    o.pair(3, "ANSI_1252");
    o.pair(9, "$INSBASE");
    o.point(10, [0.0, 0.0]);
    o.pair(9, "$EXTMIN");
    o.point(10, lo);
    o.pair(9, "$EXTMAX");
    o.point(10, hi);
    o.pair(9, "$LIMMIN");
    o.num(10, lo[0]);
    o.num(20, lo[1]);
    o.pair(9, "$LIMMAX");
    o.num(10, hi[0]);
    o.num(20, hi[1]);
    o.pair(9, "$HANDSEED");
    o.pair(5, hex(seed));
    o.pair(9, "$INSUNITS");
    o.pair(70, unit.insunits());
    o.pair(9, "$MEASUREMENT");
    o.pair(70, 1);
    o.pair(0, "ENDSEC");

    o.pair(0, "SECTION");
    o.pair(2, "CLASSES");
    o.pair(0, "ENDSEC");

    // TABLES
    o.pair(0, "SECTION");
    o.pair(2, "TABLES");
    let table = |o: &mut Out, name: &str, h: u32, n: usize| {
        o.pair(0, "TABLE");
        o.pair(2, name);
        o.pair(5, hex(h));
        o.pair(330, 0);
        o.pair(100, "AcDbSymbolTable");
        o.pair(70, n);
    };
    let record = |o: &mut Out, kind: &str, h: u32, owner: u32, sub: &str, name: &str| {
        o.pair(0, kind);
        o.pair(if kind == "DIMSTYLE" { 105 } else { 5 }, hex(h));
        o.pair(330, hex(owner));
        o.pair(100, "AcDbSymbolTableRecord");
        o.pair(100, sub);
        o.pair(2, name);
        o.pair(70, 0);
    };
    table(&mut o, "VPORT", t_vport, 1);
    record(&mut o, "VPORT", vport, t_vport, "AcDbViewportTableRecord", "*Active");
    let (cx, cy) = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
    let height = ((hi[1] - lo[1]).max((hi[0] - lo[0]) / 1.5) * 1.1).max(1.0);
    for (c, v) in [(10, 0.0), (20, 0.0), (11, 1.0), (21, 1.0), (12, cx), (22, cy), (13, 0.0), (23, 0.0)] {
        o.num(c, v);
    }
    for (c, v) in [(14, 10.0), (24, 10.0), (15, 10.0), (25, 10.0), (16, 0.0), (26, 0.0), (36, 1.0)] {
        o.num(c, v);
    }
    for (c, v) in [(17, 0.0), (27, 0.0), (37, 0.0), (40, height), (41, 1.5), (42, 50.0), (43, 0.0), (44, 0.0)] {
        o.num(c, v);
    }
    o.num(50, 0.0);
    o.num(51, 0.0);
    for (c, v) in [(71, 0), (72, 100), (73, 1), (74, 3), (75, 0), (76, 0), (77, 0), (78, 0), (281, 0), (65, 1)] {
        o.pair(c, v);
    }
    for (c, v) in [(110, 0.0), (120, 0.0), (130, 0.0), (111, 1.0), (121, 0.0), (131, 0.0)] {
        o.num(c, v);
    }
    for (c, v) in [(112, 0.0), (122, 1.0), (132, 0.0)] {
        o.num(c, v);
    }
    o.pair(79, 0);
    o.num(146, 0.0);
    o.pair(0, "ENDTAB");

    table(&mut o, "LTYPE", t_ltype, 3);
    for (h, name) in ltypes.iter().zip(["ByBlock", "ByLayer", "Continuous"]) {
        record(&mut o, "LTYPE", *h, t_ltype, "AcDbLinetypeTableRecord", name);
        o.pair(3, if name == "Continuous" { "Solid line" } else { "" });
        o.pair(72, 65);
        o.pair(73, 0);
        o.num(40, 0.0);
    }
    o.pair(0, "ENDTAB");

    table(&mut o, "LAYER", t_layer, layers.len());
    for (i, (name, h)) in layers.iter().zip(&layer_h).enumerate() {
        record(&mut o, "LAYER", *h, t_layer, "AcDbLayerTableRecord", name);
        o.pair(62, if i == 0 { 7 } else { colour(name, i - 1) });
        o.pair(6, "Continuous");
        o.pair(370, -3);
    }
    o.pair(0, "ENDTAB");

    table(&mut o, "STYLE", t_style, 1);
    record(&mut o, "STYLE", style, t_style, "AcDbTextStyleTableRecord", "Standard");
    o.num(40, 0.0);
    o.num(41, 1.0);
    o.num(50, 0.0);
    o.pair(71, 0);
    o.num(42, 2.5);
    o.pair(3, "txt");
    o.pair(4, "");
    o.pair(0, "ENDTAB");

    table(&mut o, "VIEW", t_view, 0);
    o.pair(0, "ENDTAB");
    table(&mut o, "UCS", t_ucs, 0);
    o.pair(0, "ENDTAB");

    table(&mut o, "APPID", t_appid, 1);
    record(&mut o, "APPID", appid, t_appid, "AcDbRegAppTableRecord", "ACAD");
    o.pair(0, "ENDTAB");

    table(&mut o, "DIMSTYLE", t_dimstyle, 1);
    o.pair(100, "AcDbDimStyleTable");
    o.pair(71, 0);
    record(&mut o, "DIMSTYLE", dimstyle, t_dimstyle, "AcDbDimStyleTableRecord", "Standard");
    o.pair(0, "ENDTAB");

    table(&mut o, "BLOCK_RECORD", t_brec, 2);
    for (h, name, layout) in [(br_ms, "*Model_Space", layout_ms), (br_ps, "*Paper_Space", layout_ps)] {
        o.pair(0, "BLOCK_RECORD");
        o.pair(5, hex(h));
        o.pair(330, hex(t_brec));
        o.pair(100, "AcDbSymbolTableRecord");
        o.pair(100, "AcDbBlockTableRecord");
        o.pair(2, name);
        o.pair(340, hex(layout));
    }
    o.pair(0, "ENDTAB");
    o.pair(0, "ENDSEC");

    // BLOCKS
    o.pair(0, "SECTION");
    o.pair(2, "BLOCKS");
    for (b, e, owner, name, paper) in
        [(blk_ms, end_ms, br_ms, "*Model_Space", false), (blk_ps, end_ps, br_ps, "*Paper_Space", true)]
    {
        o.entity("BLOCK", b, owner, paper, "0");
        o.pair(100, "AcDbBlockBegin");
        o.pair(2, name);
        o.pair(70, 0);
        o.point(10, [0.0, 0.0]);
        o.pair(3, name);
        o.pair(1, "");
        o.entity("ENDBLK", e, owner, paper, "0");
        o.pair(100, "AcDbBlockEnd");
    }
    o.pair(0, "ENDSEC");

    // ENTITIES
    o.pair(0, "SECTION");
    o.pair(2, "ENTITIES");
    for (s, h) in shapes.iter().zip(&entity_h) {
        let head = |o: &mut Out, kind: &str, sub: &str| {
            o.entity(kind, *h, br_ms, false, s.layer());
            o.pair(100, sub);
        };
        match s {
            DxfShape::Polyline(p) => {
                head(&mut o, "LWPOLYLINE", "AcDbPolyline");
                o.pair(90, p.points.len());
                o.pair(70, if p.closed { 1 } else { 0 });
                o.num(43, 0.0);
                for q in &p.points {
                    o.num(10, q[0] * k);
                    o.num(20, q[1] * k);
                }
            }
            DxfShape::Circle { centre, radius, .. } => {
                head(&mut o, "CIRCLE", "AcDbCircle");
                o.point(10, [centre[0] * k, centre[1] * k]);
                o.num(40, radius * k);
            }
            DxfShape::Line { from, to, .. } => {
                head(&mut o, "LINE", "AcDbLine");
                o.point(10, [from[0] * k, from[1] * k]);
                o.point(11, [to[0] * k, to[1] * k]);
            }
        }
    }
    o.pair(0, "ENDSEC");

    // OBJECTS
    o.pair(0, "SECTION");
    o.pair(2, "OBJECTS");
    let dict = |o: &mut Out, h: u32, owner: u32, entries: &[(&str, u32)]| {
        o.pair(0, "DICTIONARY");
        o.pair(5, hex(h));
        o.pair(330, hex(owner));
        o.pair(100, "AcDbDictionary");
        o.pair(281, 1);
        for (name, e) in entries {
            o.pair(3, name);
            o.pair(350, hex(*e));
        }
    };
    dict(&mut o, root, 0, &[("ACAD_GROUP", group_dict), ("ACAD_LAYOUT", layout_dict)]);
    dict(&mut o, group_dict, root, &[]);
    dict(&mut o, layout_dict, root, &[("Layout1", layout_ps), ("Model", layout_ms)]);
    for (h, name, owner, order) in [(layout_ms, "Model", br_ms, 0), (layout_ps, "Layout1", br_ps, 1)] {
        o.pair(0, "LAYOUT");
        o.pair(5, hex(h));
        o.pair(330, hex(layout_dict));
        o.pair(100, "AcDbPlotSettings");
        o.pair(1, "");
        o.pair(2, "none_device");
        o.pair(4, "");
        o.pair(6, "");
        for c in [40, 41, 42, 43, 44, 45, 46, 47, 48, 49, 140, 141] {
            o.num(c, 0.0);
        }
        o.num(142, 1.0);
        o.num(143, 1.0);
        o.pair(70, if order == 0 { 1024 } else { 0 });
        o.pair(72, 1);
        o.pair(73, 0);
        o.pair(74, 5);
        o.pair(7, "");
        o.pair(75, 16);
        o.num(147, 1.0);
        o.num(148, 0.0);
        o.num(149, 0.0);
        o.pair(100, "AcDbLayout");
        o.pair(1, name);
        o.pair(70, 1);
        o.pair(71, order);
        o.num(10, 0.0);
        o.num(20, 0.0);
        o.num(11, 420.0);
        o.num(21, 297.0);
        o.point(12, [0.0, 0.0]);
        o.point(14, lo);
        o.point(15, hi);
        o.num(146, 0.0);
        o.point(13, [0.0, 0.0]);
        o.point(16, [1.0, 0.0]);
        o.point(17, [0.0, 1.0]);
        o.pair(76, 0);
        o.pair(330, hex(owner));
    }
    o.pair(0, "ENDSEC");
    o.pair(0, "EOF");
    Ok(o.text)
}

/// Writes the shapes as an ASCII DXF drawing to `w`.
pub fn write_shapes(shapes: &[DxfShape], unit: DxfUnit, w: &mut dyn Write) -> Result<(), IoError> {
    w.write_all(dxf_text(shapes, unit)?.as_bytes())?;
    Ok(())
}

/// Writes the shapes to the file `path`.
pub fn save_shapes(shapes: &[DxfShape], unit: DxfUnit, path: &Path) -> Result<(), IoError> {
    let text = dxf_text(shapes, unit)?;
    let mut f = crate::create_file(path)?;
    f.write_all(text.as_bytes())
        .and_then(|()| f.flush())
        .map_err(|cause| IoError::File { path: path.display().to_string(), cause })
}

/// Writes the polylines as an ASCII DXF drawing to `w`.
pub fn write_dxf(polylines: &[DxfPolyline], unit: DxfUnit, w: &mut dyn Write) -> Result<(), IoError> {
    let shapes: Vec<DxfShape> = polylines.iter().cloned().map(DxfShape::Polyline).collect();
    write_shapes(&shapes, unit, w)
}

/// Writes the polylines to the file `path`.
pub fn save_dxf(polylines: &[DxfPolyline], unit: DxfUnit, path: &Path) -> Result<(), IoError> {
    let shapes: Vec<DxfShape> = polylines.iter().cloned().map(DxfShape::Polyline).collect();
    save_shapes(&shapes, unit, path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ::dxf::Drawing;
    use ::dxf::entities::EntityType;
    use ::dxf::enums::{DrawingUnits, Units};

    fn sample() -> (Vec<[f64; 2]>, Vec<DxfShape>) {
        let ellipse: Vec<[f64; 2]> = (0..36)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 36.0;
                [0.2 * t.cos(), 0.3 * t.sin()]
            })
            .collect();
        let shapes = vec![
            DxfShape::Polyline(DxfPolyline::closed("CAM_G", ellipse.clone())),
            DxfShape::Polyline(DxfPolyline::open("WALL", vec![[0.0, 0.0], [0.5, 0.25]])),
            DxfShape::Circle { layer: "BORE".into(), centre: [0.0, 0.0], radius: 0.01 },
            DxfShape::Line { layer: "PHASE_0".into(), from: [0.0, 0.0], to: [0.0, -0.3] },
        ];
        (ellipse, shapes)
    }

    #[test]
    fn round_trip_through_the_dxf_reader() {
        let (ellipse, shapes) = sample();
        let text = dxf_text(&shapes, DxfUnit::Millimetre).unwrap();
        let back = Drawing::load(&mut text.as_bytes()).unwrap();
        let ents: Vec<_> = back.entities().collect();
        assert_eq!(ents.len(), 4);
        let EntityType::LwPolyline(p) = &ents[0].specific else { panic!("not a polyline") };
        assert!(p.is_closed());
        assert_eq!(ents[0].common.layer, "CAM_G");
        assert_eq!(p.vertices.len(), 36);
        for (v, q) in p.vertices.iter().zip(&ellipse) {
            assert!((v.x - q[0] * 1000.0).abs() < 1e-9 && (v.y - q[1] * 1000.0).abs() < 1e-9);
        }
        let EntityType::LwPolyline(w) = &ents[1].specific else { panic!("not a polyline") };
        assert!(!w.is_closed());
        let EntityType::Circle(c) = &ents[2].specific else { panic!("not a circle") };
        assert!((c.radius - 10.0).abs() < 1e-12);
        let EntityType::Line(l) = &ents[3].specific else { panic!("not a line") };
        assert!((l.p2.y + 300.0).abs() < 1e-12);
        for name in ["0", "WALL", "CAM_G", "BORE", "PHASE_0"] {
            assert!(back.layers().any(|l| l.name == name), "layer {name}");
        }
        assert_eq!(back.header.default_drawing_units, Units::Millimeters);
        assert_eq!(back.header.drawing_units, DrawingUnits::Metric);
        let (lo, hi) = (&back.header.minimum_drawing_extents, &back.header.maximum_drawing_extents);
        assert!((lo.x + 200.0).abs() < 1e-9 && (hi.x - 500.0).abs() < 1e-9, "{lo:?} {hi:?}");
        assert!((lo.y + 300.0).abs() < 1e-9 && (hi.y - 300.0).abs() < 1e-9, "{lo:?} {hi:?}");
        assert!(back.block_records().any(|b| b.name == "*Model_Space"));
        assert!(back.blocks().any(|b| b.name == "*Paper_Space"));
        let m = dxf_text(&shapes, DxfUnit::Metre).unwrap();
        assert!(m.contains("$INSUNITS\n 70\n6\n"));
    }

    /// The same drawing gives the same bytes.
    #[test]
    fn byte_identical() {
        let (_, shapes) = sample();
        assert_eq!(dxf_text(&shapes, DxfUnit::Millimetre).unwrap(), dxf_text(&shapes, DxfUnit::Millimetre).unwrap());
    }

    /// The structure a strict reader checks: sections in order, every handle unique and below
    /// `$HANDSEED`, every owner (330) an existing handle, table counts equal to their records.
    #[test]
    fn structure_is_complete() {
        let (_, shapes) = sample();
        let text = dxf_text(&shapes, DxfUnit::Millimetre).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len() % 2, 0);
        let pairs: Vec<(i32, &str)> = lines.chunks(2).map(|c| (c[0].trim().parse().unwrap(), c[1])).collect();
        let sections: Vec<&str> = pairs.windows(2).filter(|w| w[0] == (0, "SECTION")).map(|w| w[1].1).collect();
        assert_eq!(sections, ["HEADER", "CLASSES", "TABLES", "BLOCKS", "ENTITIES", "OBJECTS"]);
        assert_eq!(pairs.last(), Some(&(0, "EOF")));
        let handles: Vec<u32> = pairs
            .iter()
            .filter(|(c, _)| *c == 5 || *c == 105)
            .filter_map(|(_, v)| u32::from_str_radix(v, 16).ok())
            .collect();
        let mut sorted = handles.clone();
        sorted.sort_unstable();
        sorted.dedup();

        let seed_at = pairs.iter().position(|p| *p == (9, "$HANDSEED")).unwrap();
        let seed = u32::from_str_radix(pairs[seed_at + 1].1, 16).unwrap();
        let real: Vec<u32> = handles.iter().copied().filter(|h| *h != seed).collect();
        assert!(real.iter().all(|h| *h < seed));
        for (c, v) in &pairs {
            if *c == 330 || *c == 340 || *c == 350 {
                let h = u32::from_str_radix(v, 16).unwrap();
                assert!(h == 0 && *c == 330 || real.contains(&h), "dangling {c} → {v}");
            }
        }
        // table counts
        let mut i = 0;
        while i < pairs.len() {
            if pairs[i] == (0, "TABLE") {
                let name = pairs[i + 1].1;
                let count: usize = pairs[i..].iter().find(|p| p.0 == 70).unwrap().1.parse().unwrap();
                let end = i + pairs[i..].iter().position(|p| *p == (0, "ENDTAB")).unwrap();
                let records = pairs[i + 1..end].iter().filter(|p| p.0 == 0 && p.1 == name).count();
                assert_eq!(records, count, "table {name}");
                i = end;
            }
            i += 1;
        }
        assert!(!text.contains("-0\n") && !text.contains("e-") && !text.contains("NaN"));
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
        let c = DxfShape::Circle { layer: "C".into(), centre: [0.0, 0.0], radius: 0.0 };
        assert!(write_shapes(&[c], DxfUnit::Metre, &mut out).is_err());
    }
}
