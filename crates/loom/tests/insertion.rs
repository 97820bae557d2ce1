//! The carrier on the loom: the budget of a loom file, the rapier's clearance over a repeat
//! against a brute-force scan, the cache of frame states against the direct computation.

mod common;
use common::*;
use loomkin_insertion::{Rapier, WindowSource};
use loomkin_loom::insertion::{CarrierPath, CarrierShed, budget_of, clearance};
use loomkin_loom::{InsertionKind, Loom, Motion, Pattern};

fn the_rapier(loom: &Loom) -> &Rapier {
    match &loom.insertion.kind {
        InsertionKind::Rapier(r) => r,
        other => panic!("not a rapier: {other:?}"),
    }
}

#[test]
fn the_example_is_a_rapier_and_its_budget_reads_the_file() {
    let loom = rapier();
    assert_eq!(loom.insertion.kind.name(), "rapier");
    let b = budget_of(&loom, None).unwrap();
    assert_eq!(b.window_source, WindowSource::EntryExit);
    assert_eq!((b.window_deg, b.speed_rpm), (220.0, Some(500.0)));
    // The file gives no carrier speed: it is the one the window implies at 500 rpm, so the
    // highest speed is the loom's own.
    let r = b.report().unwrap();
    assert!((r.max_picks_per_min - 500.0).abs() < 1e-9, "{}", r.max_picks_per_min);
    // With a pattern, the clear-shed window loom check finds.
    let pat = wif("point-24.wif");
    let b = budget_of(&loom, Some(&pat)).unwrap();
    assert_eq!(b.window_source, WindowSource::ClearShed);
    let check = loomkin_loom::check(&loom, &pat).unwrap();
    assert_eq!(b.window_deg, check.window_deg);
}

#[test]
fn a_sub_table_goes_with_its_kind() {
    let text = example("rapier-loom.toml");
    let e = Loom::from_toml(&edited(&text, "kind = \"rapier\"", "kind = \"shuttle\"")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "insertion.rapier: [insertion.rapier] goes with kind = \"rapier\" (the file's kind is \"shuttle\")"
    );
    let e = Loom::from_toml(&edited(&text, "kind = \"rapier\"", "kind = \"belt\"")).unwrap_err();
    assert_eq!(e.to_string(), "insertion.kind: 'belt': expected one of shuttle, rapier, projectile, airjet");
    let e = Loom::from_toml(&edited(&text, "rod_mm = 400", "rod_mm = -4")).unwrap_err();
    assert!(e.to_string().starts_with("insertion.rapier.bringer.rod_mm = -4 is out of range"), "{e}");
    // The shuttle loom keeps its kind by default.
    assert_eq!(shuttle().insertion.kind, InsertionKind::Shuttle);
}

/// The least clearance over the repeat: no 0.01° scan point of any pick is lower (the refined
/// extreme is at least as bad), and the best scan point is within the scan's resolution of it.
#[test]
fn clearance_against_a_brute_force_scan() {
    for (file, pattern) in [("rapier-loom.toml", "point-24.wif"), ("rapier-loom.toml", "twill-2-2.wif")] {
        let loom = Loom::from_toml(&example(file)).unwrap();
        let pat = wif(pattern);
        let r = the_rapier(&loom);
        let c = clearance(&loom, &pat, r).unwrap();
        let motion = Motion::new(&loom, &pat).unwrap();
        let shed = CarrierShed::new(&loom, &motion, &pat).unwrap();
        let (from, to) = r.in_shed_deg();
        assert_eq!(c.in_shed_deg, [from, to]);
        let n = ((to - from) / 0.01).ceil() as usize;
        let mut best = (f64::INFINITY, 0, 0.0);
        for p in 0..pat.picks() {
            for k in 0..=n {
                let t = from + (to - from) * k as f64 / n as f64;
                let v = shed.clearance_m(p, t) * 1e3;
                if v < best.0 {
                    best = (v, p, t);
                }
            }
        }
        assert!(c.min_clearance_mm <= best.0 + 1e-9, "{pattern}: {} vs scan {}", c.min_clearance_mm, best.0);
        // Within the scan's resolution: the clearance's slope is at most a few mm per degree.
        assert!(c.min_clearance_mm >= best.0 - 1e-3, "{pattern}: {} vs scan {}", c.min_clearance_mm, best.0);
        assert_eq!(shed.clearance_m(c.worst_pick - 1, c.worst_angle_deg) * 1e3, c.min_clearance_mm);
        // The example's cam sley dwells at the back while the heads are in the shed: they clear the
        // warp (the scan's least point, not the refined figure).
        assert!(best.0 > 5.0, "{pattern}: the heads touch the warp: {}", best.0);
        assert!((c.worst_position_mm - r.position_m(c.worst_angle_deg) * 1e3).abs() < 1e-12);
    }
}

/// The cache of distinct frame states gives what each pick computed alone gives: a repeat of
/// about 2 000 picks (the 24-frame point twill repeated) has the states of one repeat.
#[test]
fn the_state_cache_is_exact() {
    let loom = rapier();
    let one = wif("point-24.wif");
    let lines: Vec<String> = (0..one.picks())
        .map(|p| (0..24).filter(|&i| one.is_up(p, i)).map(|i| (i + 1).to_string()).collect::<Vec<_>>().join(" "))
        .collect();
    let picks = lines.len() * (2000 / lines.len());
    let long: Vec<String> = (0..picks).map(|p| lines[p % lines.len()].clone()).collect();
    let pat = Pattern::from_lift_plan(&long.join("\n")).unwrap();
    let r = the_rapier(&loom);
    let c = clearance(&loom, &pat, r).unwrap();
    let c1 = clearance(&loom, &one, r).unwrap();
    assert!(c.distinct_states <= one.picks(), "{}", c.distinct_states);
    assert!((c.min_clearance_mm - c1.min_clearance_mm).abs() < 1e-9);
    assert_eq!(c.worst_pick, c1.worst_pick);
    // Direct: each pick scanned alone at its own absolute angles.
    let motion = Motion::new(&loom, &pat).unwrap();
    let shed = CarrierShed::new(&loom, &motion, &pat).unwrap();
    let (from, to) = r.in_shed_deg();
    for p in [0, 1, 47, picks - 1] {
        let m = loomkin_numeric::scan_max(from, to, ((to - from).ceil()) as usize, |t| -shed.clearance_m(p, t));
        assert!(-m.value * 1e3 >= c.min_clearance_mm - 1e-9);
    }
}

/// A repeat whose picks are drawn at random (no state repeats, so the shared rows, the reach's
/// pruning and the searches shared by equal brackets carry the result): the least clearance is
/// that of each pick scanned alone and refined everywhere (`scan_max`, the direct route), and the
/// worst pick is the first pick that reaches it. The rapier's least is at its entry (a grid end),
/// the projectile's at its flight's end; a carrier in the shed around the crossing (a stand-in path)
/// meets its least between grid points (refined).
#[test]
fn a_random_repeat_against_each_pick_scanned_alone() {
    let projectile = Loom::from_toml(&example("projectile-loom.toml")).unwrap();
    let path = loomkin_loom::insertion_air::projectile_of(&projectile).unwrap().path(projectile.speed);
    let rapier = rapier();
    against_each_pick_alone(&rapier, the_rapier(&rapier));
    against_each_pick_alone(&projectile, &path);
    against_each_pick_alone(&rapier, &Span(-20.0, 60.0));
    against_each_pick_alone(&projectile, &Span(300.0, 380.0));
}

fn against_each_pick_alone(loom: &Loom, path: &impl CarrierPath) {
    let (from, to) = path.in_shed_deg();
    for seed in [1u64, 7, 42] {
        let pat = random_plan(seed, 120, loom.frame_count());
        let c = clearance(loom, &pat, path).unwrap();
        let motion = Motion::new(loom, &pat).unwrap();
        let shed = CarrierShed::new(loom, &motion, &pat).unwrap();
        let n = (to - from).ceil() as usize;
        let per_pick: Vec<f64> = (0..pat.picks())
            .map(|p| -loomkin_numeric::scan_max(from, to, n, |t| -shed.clearance_m(p, t)).value * 1e3)
            .collect();
        let least = per_pick.iter().copied().fold(f64::INFINITY, f64::min);
        let case = format!("{from}..{to}° seed {seed}");
        assert!((c.min_clearance_mm - least).abs() < 1e-9, "{case}: {} vs {least}", c.min_clearance_mm);
        let first = per_pick.iter().position(|&v| v < least + 1e-9).unwrap();
        assert_eq!(c.worst_pick, first + 1, "{case}: {c:?}");
        assert_eq!(c.distinct_states, pat.picks(), "{case}: random picks share no state");
    }
}

/// A carrier in the shed from one angle to another, at the entering selvedge.
struct Span(f64, f64);

impl CarrierPath for Span {
    fn in_shed_deg(&self) -> (f64, f64) {
        (self.0, self.1)
    }

    fn position_m(&self, _: f64) -> f64 {
        0.0
    }
}
