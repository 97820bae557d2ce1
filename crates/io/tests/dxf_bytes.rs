//! The DXF writer's bytes are fixed: a drawing with every entity kind (open and closed polylines,
//! circles, lines) on several layers, in millimetres and in metres, is compared with the files
//! written by the writer before its entity header groups were shared by one helper (the
//! refactoring must not move a byte). `LOOMKIN_BLESS=1` rewrites the files (only for a deliberate
//! change of the format).

use loomkin_io::dxf::{DxfPolyline, DxfShape, DxfUnit, dxf_text};

fn drawing() -> Vec<DxfShape> {
    let ring: Vec<[f64; 2]> = (0..24)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 24.0;
            [0.05 * t.cos() + 0.001 * (3.0 * t).sin(), 0.04 * t.sin()]
        })
        .collect();
    vec![
        DxfShape::Polyline(DxfPolyline::closed("CAM_PROFILE", ring.clone())),
        DxfShape::Polyline(DxfPolyline::open("CAM_PITCH", ring[..7].to_vec())),
        DxfShape::Circle { layer: "BASE_CIRCLE".into(), centre: [0.0, 0.0], radius: 0.0375 },
        DxfShape::Circle { layer: "BORE".into(), centre: [-0.0, 1e-3], radius: 0.01 },
        DxfShape::Line { layer: "CENTRE".into(), from: [-0.006, 0.0], to: [0.006, 0.0] },
        DxfShape::Line { layer: "PHASE_0".into(), from: [0.0, 0.0], to: [0.0, 0.0425] },
        DxfShape::Polyline(DxfPolyline::closed("OTHER-layer_1", vec![[0.1, 0.1], [0.2, 0.1], [0.15, 0.2]])),
    ]
}

fn compare(unit: DxfUnit, file: &str) {
    let text = dxf_text(&drawing(), unit).unwrap();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(file);
    if std::env::var_os("LOOMKIN_BLESS").is_some() {
        std::fs::write(&path, &text).unwrap();
    }
    let want = std::fs::read_to_string(&path).unwrap();
    assert!(text == want, "{file}: the DXF bytes changed (first difference at byte {})", {
        text.bytes().zip(want.bytes()).position(|(a, b)| a != b).unwrap_or(text.len().min(want.len()))
    });
}

#[test]
fn the_bytes_of_a_drawing_in_mm_are_unchanged() {
    compare(DxfUnit::Millimetre, "drawing-mm.dxf");
}

#[test]
fn the_bytes_of_a_drawing_in_m_are_unchanged() {
    compare(DxfUnit::Metre, "drawing-m.dxf");
}
