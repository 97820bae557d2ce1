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

/// A lift plan of `picks` picks on 24 shafts: at pick p, the 12 shafts (7p + 5j) mod 24 + 1 for
/// j = 0 … 11 are raised (every shaft changes often, so the search has work at every pick).
fn long_lift_plan(picks: usize) -> loomkin_loom::Pattern {
    let rows: Vec<String> = (0..picks)
        .map(|p| {
            let mut raised: Vec<usize> = (0..12).map(|j| (7 * p + 5 * j) % 24 + 1).collect();
            raised.sort_unstable();
            raised.dedup();
            raised.iter().map(usize::to_string).collect::<Vec<_>>().join(" ")
        })
        .collect();
    loomkin_loom::Pattern::from_lift_plan(&(rows.join("\n") + "\n")).unwrap()
}

#[test]
fn a_stop_ends_the_search_with_stopped() {
    use loomkin_loom::optimise_stagger_until;
    use loomkin_units::StopFlag;
    let loom = rapier();
    // Not set: the same result as the search without a flag, to the bit.
    let pat = wif("satin-8.wif");
    let free = optimise_stagger_until(&loom, &pat, Objective::Peak, &StopFlag::default()).unwrap();
    assert_eq!(free, optimise_stagger(&loom, &pat, Objective::Peak).unwrap());
    // Set before the start: nothing is evaluated.
    let set = StopFlag::default();
    set.stop();
    let e = optimise_stagger_until(&loom, &pat, Objective::Peak, &set).unwrap_err();
    assert_eq!(e, LoomError::Stopped(loomkin_units::Stopped));
    assert_eq!(loomkin_units::FieldError::field(&e), None);
    // Set from another thread while a long search runs (100 picks on 24 frames; the full search takes
    // tens of seconds): the search ends with Stopped instead of a result, so it checked the flag mid-way.
    let long = long_lift_plan(100);
    let stop = StopFlag::default();
    let setter = {
        let stop = stop.clone();
        std::thread::spawn(move || {
            std::thread::sleep(std::time::Duration::from_millis(200));
            stop.stop();
        })
    };
    let e = optimise_stagger_until(&loom, &long, Objective::Peak, &stop).unwrap_err();
    setter.join().unwrap();
    assert_eq!(e, LoomError::Stopped(loomkin_units::Stopped));
}

/// A least clearance to keep (issue 27: the optimum spent 5.29 → 0.03 mm of clearance, 27° of
/// clear shed and 62 rpm of top speed without saying so): with 3 mm asked the optimum keeps 3 mm
/// (checked exactly on the result, not on the search's grid), lowers the peak less, and every
/// case reports its window and top speed — the top speed the timing's own formula of the window.
#[test]
fn a_least_clearance_is_kept_and_the_cost_reported() {
    use loomkin_loom::{Objective, StaggerOptions, max_speed_rpm, optimise_stagger, optimise_stagger_with};
    let loom = rapier();
    let pattern = wif("twill-16.wif");
    let free = optimise_stagger(&loom, &pattern, Objective::Peak).unwrap();
    let options = StaggerOptions { objective: Objective::Peak, min_clearance_mm: 3.0 };
    let kept = optimise_stagger_with(&loom, &pattern, &options, &Default::default(), &|_, _| {}).unwrap();
    assert!(kept.best.min_clearance_mm >= 3.0 - 1e-9, "{:?}", kept.best);
    assert!(free.best.min_clearance_mm < 3.0, "{:?}", free.best);
    assert!(
        kept.best.peak_torque_n_m >= free.best.peak_torque_n_m,
        "{} vs {}",
        kept.best.peak_torque_n_m,
        free.best.peak_torque_n_m
    );
    assert_eq!(kept.min_clearance_kept_mm, 3.0);
    let v = loom.insertion.mean_speed_m_s(loom.speed.rpm());
    for c in [&free.none, &free.best, &kept.best] {
        let want = max_speed_rpm(v, c.window_deg, loom.insertion.reed_width_m, loom.insertion.carrier_length_m);
        assert!((c.max_speed_rpm - want).abs() <= 1e-12 * want, "{c:?}");
    }
    // The optimum's cost: less window and top speed than no stagger.
    assert!(free.best.window_deg < free.none.window_deg && free.best.max_speed_rpm < free.none.max_speed_rpm);
    // More than the shed ever gives is refused, naming the option.
    let options = StaggerOptions { objective: Objective::Peak, min_clearance_mm: 500.0 };
    let e = optimise_stagger_with(&loom, &pattern, &options, &Default::default(), &|_, _| {}).unwrap_err();
    assert!(e.to_string().contains("min_clearance_mm") || e.to_string().contains("500 mm"), "{e}");
}
