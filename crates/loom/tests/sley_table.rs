//! The `[sley]` table of a loom file: read through the drive crate, errors named `sley.…`.

mod common;

use common::{edited, example};
use loomkin_loom::Loom;
use loomkin_units::FieldError;

#[test]
fn the_examples_carry_a_sley_at_their_beat_up() {
    for name in ["rapier-loom.toml", "shuttle-loom.toml"] {
        let loom = Loom::from_toml(&example(name)).unwrap();
        let sley = loom.sley.expect("the example has a [sley] table");
        assert_eq!(sley.front_dead_centre_rad(), loom.beat_up_deg.to_radians());
        // The reed's stroke is the reed's distance from the fell at insertion, within a few mm.
        let stroke_mm = sley.stroke_m() * 1e3;
        assert!((stroke_mm - loom.geometry.reed_m * 1e3).abs() < 5.0, "{name}: {stroke_mm}");
    }
}

#[test]
fn the_sley_takes_the_looms_beat_up_angle_and_refuses_another() {
    let text = example("rapier-loom.toml");
    let moved = edited(&text, "[beat_up]\nangle_deg = 0", "[beat_up]\nangle_deg = 12");
    let loom = Loom::from_toml(&moved).unwrap();
    assert!((loom.sley.unwrap().front_dead_centre_rad().to_degrees() - 12.0).abs() < 1e-12);
    let both = edited(&moved, "[sley]\n", "[sley]\nbeat_up_deg = 5\n");
    let e = Loom::from_toml(&both).unwrap_err();
    assert_eq!(e.field(), Some("sley.beat_up_deg"));
    assert!(e.to_string().contains("angle_deg is 12°"), "{e}");
}

#[test]
fn sley_errors_name_the_sley_fields() {
    // The shuttle loom's crank-rocker sley (the rapier's is a cam sley).
    let text = example("shuttle-loom.toml");
    let e = Loom::from_toml(&edited(&text, "crank_mm = 48", "crank_mm = -4")).unwrap_err();
    assert_eq!(e.to_string(), "sley.crank_mm = -4 is out of range: allowed 0 < sley.crank_mm ≤ 10000 mm");
    let e = Loom::from_toml(&edited(&text, "rod_mm = 250", "rod_mm = 20")).unwrap_err();
    assert!(
        e.to_string().starts_with(
            "sley.crank_mm, sley.rod_mm, sley.sword_mm, sley.pivot_x_mm, sley.pivot_y_mm: the loop does not close"
        ),
        "{e}"
    );
    let e = Loom::from_toml(&edited(&text, "crank_mm = 48", "crank_mm = 48\ncolour = 1")).unwrap_err();
    assert!(e.to_string().contains("unknown field `colour`") && e.to_string().contains("line "), "{e}");
    // Without the table the loom has no sley.
    let start = text.find("\n# The sley").unwrap();
    assert!(Loom::from_toml(&text[..start]).unwrap().sley.is_none());
}
