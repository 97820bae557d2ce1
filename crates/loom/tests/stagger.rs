//! Heald staggering: the optimum beats both baselines and keeps every window; an impossible
//! window is refused.

mod common;
use common::*;
use loomkin_loom::{Loom, LoomError, Objective, optimise_stagger};

#[test]
fn the_optimum_lowers_the_peak_and_keeps_the_windows() {
    let loom = rapier();
    let pat = wif("satin-8.wif");
    let r = optimise_stagger(&loom, &pat, Objective::Peak).unwrap();
    assert!(r.none.window_kept && r.best.window_kept);
    assert!(r.best.peak_torque_n_m < r.none.peak_torque_n_m);
    assert!(r.best.peak_torque_n_m <= r.two_groups.peak_torque_n_m * (1.0 + 1e-3) || !r.two_groups.window_kept);
    assert!(r.best.stagger_deg.iter().all(|s| s.abs() <= loom.shedding.max_stagger_deg));
    assert!(r.best.min_clearance_mm >= 0.0);
    // The figures restated: the stagger read back into a loom gives the same peak.
    let again = loom.with_stagger(&r.best.stagger_deg).unwrap();
    let m = loomkin_loom::Motion::new(&again, &pat).unwrap();
    let p = loomkin_loom::Drive::new(&again, &m, &pat).peak(0.5).torque_n_m.abs();
    assert!((p - r.best.peak_torque_n_m).abs() < 1e-9 * p);
    eprintln!(
        "8 frames: none {:.2}, two groups {:.2} ({:.1} %), best {:.2} N·m ({:.1} %) in {} evaluations",
        r.none.peak_torque_n_m,
        r.two_groups.peak_torque_n_m,
        r.two_groups_peak_reduction_pct,
        r.best.peak_torque_n_m,
        r.peak_reduction_pct,
        r.evaluations
    );
    let rms = optimise_stagger(&loom, &pat, Objective::Rms).unwrap();
    assert!(rms.best.rms_torque_n_m <= rms.none.rms_torque_n_m * (1.0 + 1e-9));
}

#[test]
fn groups_are_searched_as_groups() {
    let loom = shuttle();
    let pat = wif("twill-2-2.wif");
    let r = optimise_stagger(&loom, &pat, Objective::Peak).unwrap();
    let s = &r.best.stagger_deg;
    assert_eq!(s[0], s[2]);
    assert_eq!(s[1], s[3]);
    assert!(r.best.peak_torque_n_m <= r.none.peak_torque_n_m);
}

#[test]
fn a_window_no_stagger_can_give_is_refused() {
    let text = edited(&example("rapier-loom.toml"), "entry_deg = 70", "entry_deg = 10");
    let loom = Loom::from_toml(&text).unwrap();
    let e = optimise_stagger(&loom, &wif("satin-8.wif"), Objective::Peak).unwrap_err();
    assert!(matches!(e, LoomError::Infeasible { .. }));
    assert!(e.to_string().starts_with("insertion.entry_deg: no stagger within ±15°"), "{e}");
}
