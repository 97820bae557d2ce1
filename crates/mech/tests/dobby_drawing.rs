//! The dobby's drawing: its polylines stay within the chord tolerance of the cam curves, checked
//! against exact curve points of an independent synthesis at a 0.01° step (five times denser than
//! the dense curves the vertices are chosen from); marks where they belong.

use loomkin_io::drawing::Shape;
use loomkin_mech::{ModulatorGeometry, OutputLawSpec, SynthesisOptions, synthesize};

fn dist_to_polygon(p: [f64; 2], poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let l2 = dx * dx + dy * dy;
            let t = if l2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
            (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn the_polylines_stay_within_the_chord_tolerance_whatever_the_step() {
    let g = ModulatorGeometry::PAPER;
    let law = OutputLawSpec::default();
    // A coarse table step: the drawing does not follow it.
    let s = synthesize(&g, &law, &SynthesisOptions { step_deg: 5.0, ..Default::default() }).unwrap();
    let exact = synthesize(&g, &law, &SynthesisOptions { step_deg: 0.01, ..Default::default() }).unwrap();
    for tol_mm in [0.1, 0.01] {
        let d = s.drawing(tol_mm, 20.0).unwrap();
        let poly = |layer: &str| -> Vec<[f64; 2]> {
            d.iter()
                .find_map(|l| match (&l.shape, l.layer == layer) {
                    (Shape::Polyline { points, closed: true }, true) => Some(points.clone()),
                    _ => None,
                })
                .unwrap_or_else(|| panic!("no closed polyline on {layer}"))
        };
        for (layer, curve) in [
            ("CAM_CENTRE", &exact.cam.centre),
            ("CAM_WALL_LEFT", &exact.cam.wall_left),
            ("CAM_WALL_RIGHT", &exact.cam.wall_right),
            ("COUNTER_CAM_CENTRE", &exact.counter_cam.centre),
            ("COUNTER_CAM_WALL_RIGHT", &exact.counter_cam.wall_right),
        ] {
            let p = poly(layer);
            let worst = curve.iter().map(|&q| dist_to_polygon(q, &p)).fold(0.0, f64::max);
            assert!(worst <= tol_mm * 1e-3, "{layer} at {tol_mm} mm: {worst:e} m off ({} vertices)", p.len());
            // Not every dense point: the tolerance is used.
            assert!(p.len() < 7200 / 2, "{layer}: {} vertices", p.len());
        }
    }
    // Fewer vertices for a looser tolerance.
    let count = |tol: f64| -> usize {
        s.drawing(tol, 0.0)
            .unwrap()
            .iter()
            .map(|l| if let Shape::Polyline { points, .. } = &l.shape { points.len() } else { 0 })
            .sum()
    };
    assert!(count(0.1) < count(0.01));
    // Marks: the centre cross and bore about O, the phase line to roller B at 0°, both rollers.
    let d = s.drawing(0.01, 20.0).unwrap();
    let b0 = exact.cam.centre[0];
    let r = s.summary.roller_m;
    assert!(d.iter().any(|l| l.layer == "PHASE_0" && l.shape == Shape::Line { from: [0.0, 0.0], to: b0 }));
    assert!(d.iter().any(|l| l.layer == "BORE" && l.shape == Shape::Circle { centre: [0.0, 0.0], radius: 0.01 }));
    assert_eq!(d.iter().filter(|l| l.layer == "ROLLER").count(), 2);
    assert!(d.iter().any(|l| l.layer == "ROLLER" && l.shape == Shape::Circle { centre: b0, radius: r }));
    assert_eq!(d.iter().filter(|l| l.layer == "CENTRE").count(), 2);
    // Bad input names the field.
    assert!(s.drawing(0.0, 0.0).unwrap_err().to_string().contains("chord_tol_mm"));
    assert!(s.drawing(0.01, 1e4).unwrap_err().to_string().contains("bore_mm"));
}
