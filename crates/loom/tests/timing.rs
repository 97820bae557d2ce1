//! Shed timing: the textbook speed example, the clear shed by construction, windows at roots.

mod common;
use common::*;
use loomkin_loom::{Loom, LoomError, Motion, Timing, max_speed_rpm};

/// The lecture example: n = v̄·θ/(6·(K_b + L_s)) = 13.75·135/(6·1.45) ≈ 213 picks/min.
#[test]
fn the_textbook_speed_example() {
    let n = max_speed_rpm(13.75, 135.0, 1.15, 0.30);
    assert_eq!(n.round(), 213.0);
    assert!((n - 213.362_068_965_517_24).abs() < 1e-9);
    // Independent route: the flight time at that speed fills the window exactly.
    let flight_s = (1.15 + 0.30) / 13.75;
    let window_s = 135.0 / 360.0 * 60.0 / n;
    assert!((flight_s - window_s).abs() < 1e-15);
}

#[test]
fn the_clear_shed_in_the_dwell_is_the_clean_shed() {
    let loom = rapier();
    let pat = wif("twill-2-2.wif");
    let m = Motion::new(&loom, &pat).unwrap();
    let t = Timing::new(&loom, &m, &pat).unwrap();
    // At 180° of a pick every frame dwells (motion 280° centred on −10°): a clean shed of the
    // front frame's angle, x·H₁/d₁ at the carrier's front edge.
    let x = t.carrier_edge_m();
    assert!((x - 0.085).abs() < 1e-15);
    for p in 0..4 {
        let clear = t.clear_m(p, x, 360.0 * p as f64 + 180.0);
        assert!((clear - x * 0.09 / 0.2).abs() < 1e-15, "{clear}");
    }
    let r = t.report().unwrap();
    for w in &r.picks {
        assert!(t.clearance_m(w.pick - 1, w.open_deg).abs() < 1e-12);
        assert!(t.clearance_m(w.pick - 1, w.close_deg).abs() < 1e-12);
        assert!(w.open_deg < loom.insertion.entry_deg && w.close_deg > loom.insertion.exit_deg);
    }
    assert!((r.window_deg - (r.close_deg - r.open_deg)).abs() < 1e-12);
    assert!((r.max_speed_rpm - 500.0 * r.window_deg / 220.0).abs() < 1e-9);
    // The least clearance over the insertion is at its ends (the shed opens then closes) and
    // no less than a dense scan finds.
    let dense = (0..=22_000).map(|k| t.clearance_m(0, 70.0 + k as f64 * 0.01)).fold(f64::INFINITY, f64::min);
    assert!(r.picks[0].min_clearance_mm <= dense * 1e3 + 1e-9);
    assert!(r.picks[0].min_clearance_mm >= dense * 1e3 - 1e-6);
    eprintln!("{r:?}");
}

#[test]
fn a_carrier_taller_than_the_shed_is_refused() {
    let text = edited(&example("rapier-loom.toml"), "carrier_height_mm = 22", "carrier_height_mm = 60");
    let loom = Loom::from_toml(&text).unwrap();
    let pat = wif("plain.wif");
    let m = Motion::new(&loom, &pat).unwrap();
    let e = Timing::new(&loom, &m, &pat).unwrap().report().unwrap_err();
    assert!(matches!(e, LoomError::Infeasible { .. }));
    assert!(
        e.to_string().starts_with("insertion.carrier_height_mm: the carrier (60.0 mm) is taller than the shed"),
        "{e}"
    );
    // A refusal of the loom file's field: a front end names the file before it.
    assert!(e.in_loom_file());
}

#[test]
fn a_pick_without_a_shed_is_refused() {
    let loom = shuttle();
    let pat = loomkin_loom::Pattern::from_lift_plan("1 2\n1 2 3 4\n").unwrap();
    // The one check of a pattern against a loom: the motion (behind every command) refuses it, and
    // the timing of another motion refuses it alike.
    let e = Motion::new(&loom, &pat).unwrap_err().to_string();
    assert_eq!(e, "pattern pick 2: raises all of the loom's 4 frames: a shed needs warp above and below the carrier");
    assert!(!Motion::new(&loom, &pat).unwrap_err().in_loom_file(), "the pattern's, not the loom file's");
    let plain = Motion::new(&loom, &wif("twill-2-2.wif")).unwrap();
    assert_eq!(Timing::new(&loom, &plain, &pat).unwrap_err().to_string(), e);
}

#[test]
fn the_shuttle_loom_times_its_shuttle() {
    let loom = shuttle();
    let pat = wif("twill-2-2.wif");
    let m = Motion::new(&loom, &pat).unwrap();
    let r = Timing::new(&loom, &m, &pat).unwrap().report().unwrap();
    assert!((r.mean_speed_m_s - 17.0 * 0.95).abs() < 1e-9);
    eprintln!("{r:?}");
}
