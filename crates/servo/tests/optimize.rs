//! The optimiser lowers the torque of the default drive and keeps the points valid.

use loomkin_servo::{Drive, Objective, OptimizeOptions, SplineLaw, check_points, optimize, summary};

#[test]
fn optimiser_lowers_the_peak_torque_of_the_default_drive() {
    let start = SplineLaw::default_law();
    let d = Drive::needle_rack_default();
    let opts = OptimizeOptions { speeds_rpm: vec![600.0, 750.0], ..OptimizeOptions::default() };
    let r = optimize(&start, &d, &opts).unwrap();
    println!("before {:?}\nafter {:?}\npoints {:?}\nevals {}", r.before, r.after, r.law.points(), r.evaluations);
    // The reported objective is the worst peak over the speeds, recomputed by `summary`.
    let worst = |v: &[loomkin_servo::TorqueSummary]| v.iter().map(|s| s.peak_torque_nm).fold(0.0, f64::max);
    assert!((worst(&r.after) - r.objective_after_nm).abs() < 1e-9 * r.objective_after_nm);
    assert!((worst(&r.before) - r.objective_before_nm).abs() < 1e-9 * r.objective_before_nm);
    // At least 15 % lower than the cycloid-like start (a trapezoid-like law has Ca ≈ 4.9 vs 2π).
    assert!(
        r.objective_after_nm < 0.85 * r.objective_before_nm,
        "{} → {}",
        r.objective_before_nm,
        r.objective_after_nm
    );
    // Points valid and within the bounds [0, 1].
    let pts = check_points(r.law.points()).unwrap();
    assert!(pts.iter().all(|p| (0.0..=1.0).contains(&p[1])));
    // Reported with the largest |Y| scaled to 1 (the law is the same for any common factor).
    let y_max = pts.iter().map(|p| p[1].abs()).fold(0.0, f64::max);
    assert!((y_max - 1.0).abs() < 1e-15, "{y_max}");
    // Deterministic.
    let again = optimize(&start, &d, &opts).unwrap();
    assert_eq!(again.law.points(), r.law.points());
}

#[test]
fn rms_objective_lowers_the_rms_torque() {
    let start = SplineLaw::default_law();
    let d = Drive::needle_rack_default();
    let opts = OptimizeOptions { objective: Objective::Rms, starts: 3, move_x: false, ..OptimizeOptions::default() };
    let r = optimize(&start, &d, &opts).unwrap();
    let before = summary(start.law(), &d, 600.0).unwrap().rms_torque_nm;
    let after = summary(r.law.law(), &d, 600.0).unwrap().rms_torque_nm;
    assert!(after < before * 0.99, "{before} → {after}");
    // X fixed when move_x is false.
    for (a, b) in start.points().iter().zip(r.law.points()) {
        assert_eq!(a[0], b[0]);
    }
}

#[test]
fn bad_options_are_errors() {
    let start = SplineLaw::default_law();
    let d = Drive::needle_rack_default();
    let none = OptimizeOptions { speeds_rpm: vec![], ..OptimizeOptions::default() };
    assert!(optimize(&start, &d, &none).is_err());
    let neg = OptimizeOptions { speeds_rpm: vec![-5.0], ..OptimizeOptions::default() };
    assert!(optimize(&start, &d, &neg).unwrap_err().to_string().contains("speed_rpm"));
}

/// A stop flag set from another thread ends every start at once: the result is the starting law
/// (nothing better was found) and far fewer evaluations ran than a full optimisation needs.
#[test]
fn a_stop_flag_ends_the_optimisation_early() {
    let start = SplineLaw::default_law();
    let d = Drive::needle_rack_default();
    let opts = OptimizeOptions { speeds_rpm: vec![600.0], ..OptimizeOptions::default() };
    let full = optimize(&start, &d, &opts).unwrap();
    opts.stop.stop();
    assert!(opts.stop.is_set() && opts.stop == opts.clone().stop);
    let r = optimize(&start, &d, &opts).unwrap();
    assert_eq!(r.objective_after_nm, r.objective_before_nm);
    assert!((r.objective_before_nm - full.objective_before_nm).abs() < 1e-12);
    assert!(full.objective_after_nm < r.objective_after_nm);
}
