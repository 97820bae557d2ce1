//! The time budget: the lecture example, the converse, energy and power, the bounds.

use loomkin_insertion::{PickBudget, WindowSource, max_speed_rpm, required_speed_m_s, window_needed_deg};
use proptest::prelude::*;

fn lecture() -> PickBudget {
    PickBudget {
        reed_width_mm: 1150.0,
        carrier_length_mm: 300.0,
        window_deg: 135.0,
        window_source: WindowSource::Given,
        speed_m_s: 13.75,
        speed_rpm: None,
        carrier_mass_g: None,
    }
}

/// The lecture example of docs/loom.md: 13.75 m/s, 135°, 1.15 m and 0.30 m give 213 picks/min.
/// Independent route: the flight time across W + L at v̄ against the time the shaft takes to
/// turn through the window at that speed.
#[test]
fn the_lecture_example() {
    let r = lecture().report().unwrap();
    assert_eq!(r.max_picks_per_min.floor(), 213.0);
    assert!((r.max_picks_per_min - 1856.25 / 8.7).abs() < 1e-12);
    let flight_s = (1.15 + 0.30) / 13.75;
    let window_s = 135.0 / 360.0 * 60.0 / r.max_picks_per_min;
    assert!((flight_s / window_s - 1.0).abs() < 1e-15);
    // Without a loom speed the converse is asked at the highest speed: the speed given.
    assert!((r.required_speed_m_s / 13.75 - 1.0).abs() < 1e-15);
    assert_eq!(r.energy_per_pick_j, None);
}

/// At a loom speed: the carrier speed needed, the window that speed needs, energy and power.
#[test]
fn converse_energy_and_power() {
    let b = PickBudget { speed_rpm: Some(180.0), carrier_mass_g: Some(420.0), ..lecture() };
    let r = b.report().unwrap();
    // 180 rpm turns 1080°/s; 135° takes 0.125 s; 1.45 m in 0.125 s is 11.6 m/s.
    assert!((r.required_speed_m_s - 11.6).abs() < 1e-12);
    assert!((window_needed_deg(180.0, 1.45, 11.6) - 135.0).abs() < 1e-12);
    // ½·0.42 kg·(13.75 m/s)² = 39.703125 J, 3 picks per second at 180 rpm.
    assert!((r.energy_per_pick_j.unwrap() - 39.703_125).abs() < 1e-12);
    assert!((r.drive_power_w.unwrap() - 3.0 * 39.703_125).abs() < 1e-10);
}

#[test]
fn bounds_name_the_field() {
    let e = PickBudget { window_deg: 360.0, ..lecture() }.report().unwrap_err();
    assert_eq!(e.to_string(), "window_deg = 360 is out of range: allowed 0.001 ≤ window_deg < 360 deg");
    // At the least reed space and window the results stay finite (5e-324 of either overflowed:
    // `inf` picks/min, `inf` m/s, found by the CLI's range-end sweep).
    let tight = PickBudget { reed_width_mm: 1.0, carrier_length_mm: 0.0, window_deg: 0.001, ..lecture() };
    let r = tight.report().unwrap();
    assert!(r.max_picks_per_min.is_finite() && r.required_speed_m_s.is_finite(), "{r:?}");
    let e = PickBudget { window_deg: 0.001_f64.next_down(), ..lecture() }.report().unwrap_err();
    assert!(e.to_string().starts_with("window_deg"), "{e}");
    let e = PickBudget { reed_width_mm: 0.0, ..lecture() }.report().unwrap_err();
    assert!(e.to_string().starts_with("reed_width_mm = 0 is out of range"), "{e}");
    let e = PickBudget { speed_m_s: f64::NAN, ..lecture() }.report().unwrap_err();
    assert!(e.to_string().starts_with("speed_m_s"), "{e}");
    let e = PickBudget { carrier_mass_g: Some(-1.0), ..lecture() }.report().unwrap_err();
    assert!(e.to_string().starts_with("carrier_mass_g"), "{e}");
    let e = PickBudget { speed_rpm: Some(0.0), ..lecture() }.report().unwrap_err();
    assert!(e.to_string().starts_with("speed_rpm"), "{e}");
}

proptest! {
    /// The highest speed and the required carrier speed are each other's inverse, and at the
    /// highest speed the flight fills the window exactly.
    #[test]
    fn budget_and_converse_are_inverse(v in 1.0..60.0f64, theta in 10.0..300.0f64, w in 0.1..6.0f64, l in 0.0..0.5f64) {
        let n = max_speed_rpm(v, theta, w, l);
        prop_assert!((required_speed_m_s(n, theta, w, l) / v - 1.0).abs() < 1e-14);
        prop_assert!((window_needed_deg(n, w + l, v) / theta - 1.0).abs() < 1e-14);
        // Flight time against the window's time at n.
        prop_assert!(((w + l) / v / (theta / (6.0 * n)) - 1.0).abs() < 1e-14);
    }
}

/// The inputs over a loom file's budget: each given one replaces the file's, a given window is
/// `given`; without a file the first missing input of reed width, carrier length, window, speed
/// is named.
#[test]
fn inputs_over_a_file() {
    use loomkin_insertion::{BudgetInputs, MissingInput};
    let file = PickBudget {
        reed_width_mm: 1900.0,
        carrier_length_mm: 100.0,
        window_deg: 220.0,
        window_source: WindowSource::ClearShed,
        speed_m_s: 20.0,
        speed_rpm: Some(500.0),
        carrier_mass_g: None,
    };
    assert_eq!(BudgetInputs::default().onto(Some(file)), Ok(file));
    let over = BudgetInputs { window_deg: Some(180.0), carrier_mass_g: Some(300.0), ..Default::default() };
    let b = over.onto(Some(file)).unwrap();
    assert_eq!((b.window_deg, b.window_source, b.carrier_mass_g), (180.0, WindowSource::Given, Some(300.0)));
    assert_eq!((b.reed_width_mm, b.speed_rpm), (1900.0, Some(500.0)));
    let alone = BudgetInputs {
        reed_width_mm: Some(1150.0),
        carrier_length_mm: Some(300.0),
        window_deg: Some(135.0),
        speed_m_s: Some(13.75),
        ..Default::default()
    };
    let b = alone.onto(None).unwrap();
    assert_eq!(b.report().unwrap().max_picks_per_min.floor(), 213.0);
    assert_eq!(b.window_source, WindowSource::Given);
    let e = BudgetInputs { window_deg: None, speed_m_s: None, ..alone }.onto(None).unwrap_err();
    assert_eq!(e, MissingInput { field: "window_deg" });
    assert_eq!(e.message("--window-deg"), "--window-deg: required without a loom file");
    let e = BudgetInputs::default().onto(None).unwrap_err();
    assert_eq!(e.field, "reed_width_mm");
}
