//! The carrier on the timing diagram (`loom timing`): every kind's tracks against the carrier's own
//! model read another way (the rapier's tips, the projectile's closed-form flight, the air jet's
//! report), the sley's dwell against the reed's position, and the figure's layout.

mod common;
use common::*;
use loomkin_loom::insertion_air::airjet_check;
use loomkin_loom::insertion_timing::{CarrierTiming, carrier_timing};
use loomkin_loom::{InsertionKind, Loom, Pattern, timing_diagram};

fn loom(name: &str) -> Loom {
    Loom::from_toml(&example(name)).unwrap()
}

/// The track labelled `label`.
fn track<'a>(ct: &'a CarrierTiming, label: &str) -> &'a loomkin_loom::insertion_timing::CarrierTrack {
    ct.tracks.iter().find(|t| t.label == label).unwrap_or_else(|| panic!("no track {label}"))
}

#[test]
fn rapier_heads_transfer_and_span() {
    let l = loom("rapier-loom.toml");
    let InsertionKind::Rapier(r) = &l.insertion.kind else { panic!("not a rapier") };
    let ct = carrier_timing(&l).unwrap();
    assert_eq!(ct.kind, "rapier");
    let (b, t) = (track(&ct, "bringer"), track(&ct, "taker"));
    let w = r.reed_width_m;
    // Every point is the head's tip as the drive gives it (the taker measured from the bringer's selvedge).
    for (k, &a) in b.angle_deg.iter().enumerate() {
        assert_eq!(b.position_m[k], r.tip(0, a.to_radians()).u_m);
        assert_eq!(t.position_m[k], w - r.tip(1, a.to_radians()).u_m);
    }
    assert_eq!((b.angle_deg[0], *b.angle_deg.last().unwrap()), (0.0, 360.0));
    // The transfer is where the tips overlap most: the bringer past the taker by the report's overlap.
    let tr = ct.transfer.unwrap();
    let rep = r.report(l.speed).unwrap();
    let overlap = r.tip(0, tr.angle_deg.to_radians()).u_m - (w - r.tip(1, tr.angle_deg.to_radians()).u_m);
    assert!((overlap * 1e3 - rep.transfer_overlap_mm).abs() < 1e-9, "{overlap} vs {}", rep.transfer_overlap_mm);
    // The span in the shed: at its ends a head is at its selvedge; inside it a head is inside the reed.
    let [from, to] = ct.in_shed_deg;
    let at_selvedge = |a: f64| {
        let (u0, u1) = (r.tip(0, a.to_radians()).u_m, r.tip(1, a.to_radians()).u_m);
        u0.abs().min(u1.abs())
    };
    assert!(at_selvedge(from) < 1e-9 && at_selvedge(to) < 1e-9);
    for k in 1..100 {
        let a = from + (to - from) * k as f64 / 100.0;
        assert!(r.tip(0, a.to_radians()).u_m > 0.0 || r.tip(1, a.to_radians()).u_m > 0.0, "{a}");
    }
    assert!(ct.relay_plan.is_empty());
}

#[test]
fn projectile_track_is_its_flight() {
    let l = loom("projectile-loom.toml");
    let InsertionKind::Projectile(p) = &l.insertion.kind else { panic!("not a projectile") };
    let ct = carrier_timing(&l).unwrap();
    let r = p.report(l.speed);
    let tr = track(&ct, "projectile");
    assert_eq!((tr.angle_deg[0], *tr.angle_deg.last().unwrap()), (r.launch_deg, r.arrival_deg));
    // Independent reading: the closed-form flight x(t) at t = (φ − launch)/(6n), less the run-in.
    for (a, x) in tr.angle_deg.iter().zip(&tr.position_m) {
        let t = (a - r.launch_deg) / (6.0 * l.speed.rpm());
        assert!((x - (p.flight.x_at(t) - p.run_in_m)).abs() < 1e-12, "{a}: {x}");
    }
    // From the launch to the brake: the whole flight distance.
    let d = tr.position_m.last().unwrap() - tr.position_m[0];
    assert!((d - p.flight_distance_m()).abs() < 1e-9, "{d}");
    assert_eq!(ct.in_shed_deg, [r.shed_entry_deg, r.shed_exit_deg]);
    let path = p.path(l.speed);
    assert_eq!(path.position_m(ct.in_shed_deg[0]), 0.0);
    assert!(ct.transfer.is_none() && ct.relay_plan.is_empty());
}

#[test]
fn airjet_track_and_relay_plan() {
    let l = loom("airjet-loom.toml");
    let ct = carrier_timing(&l).unwrap();
    let rep = airjet_check(&l, l.speed).unwrap();
    assert_eq!(ct.relay_plan, rep.relay_plan);
    assert_eq!(ct.in_shed_deg, [rep.reed_entry_deg, rep.arrival_deg]);
    let tip = track(&ct, "yarn tip");
    // The tip reaches the far selvedge at the report's arrival angle.
    assert!((tip.angle_deg.last().unwrap() - rep.arrival_deg).abs() < 1e-9);
    assert!((tip.position_m.last().unwrap() - l.insertion.reed_width_m).abs() < 1e-9);
    assert!((tip.angle_deg[0] - rep.launch_deg).abs() < 1e-12);
    // The tip never goes back, and the angles rise.
    assert!(tip.position_m.windows(2).all(|w| w[1] >= w[0]));
    assert!(tip.angle_deg.windows(2).all(|w| w[1] > w[0]));
    assert!(tip.angle_deg.len() <= 2 * 720 + 2);
}

#[test]
fn sley_dwell_is_where_the_reed_stays_back() {
    for name in ["shuttle-loom.toml", "rapier-loom.toml"] {
        let l = loom(name);
        let sley = l.sley.as_ref().unwrap();
        let [s, e] = carrier_timing(&l).unwrap().sley_back_dwell_deg.unwrap();
        let tol = loomkin_drive::SleyAnalysis::DWELL_TOLERANCE_MM.default_value() * 1e-3;
        let x = |a: f64| sley.reed(f64::to_radians(a)).x_m;
        // At the ends the reed is at the tolerance from its back dead centre; between them within it.
        assert!((x(s) - tol).abs() < 1e-12 && (x(e) - tol).abs() < 1e-12, "{name}: {} {}", x(s), x(e));
        for k in 1..50 {
            assert!(x(s + (e - s) * k as f64 / 50.0) < tol, "{name}");
        }
        assert!(x(s - 0.5) > tol && x(e + 0.5) > tol);
    }
    // Without a [sley], no dwell.
    let text = example("shuttle-loom.toml");
    let cut = &text[..text.find("[sley]").unwrap()];
    let l = Loom::from_toml(cut).unwrap();
    let ct = carrier_timing(&l).unwrap();
    assert_eq!(ct.sley_back_dwell_deg, None);
    assert_eq!(ct.in_shed_deg, [l.insertion.entry_deg, l.insertion.exit_deg]);
}

#[test]
fn the_diagram_draws_each_kind_and_lays_out() {
    for (name, panels) in
        [("shuttle-loom.toml", 3), ("rapier-loom.toml", 3), ("projectile-loom.toml", 3), ("airjet-loom.toml", 4)]
    {
        let l = loom(name);
        let fig = timing_diagram(&l, &Pattern::plain(l.frame_count()).unwrap()).unwrap();
        assert_eq!(fig.panels.len(), panels, "{name}");
        assert!(fig.layout_problems().is_empty(), "{name}: {:?}", fig.layout_problems());
        let labels: Vec<&str> = fig.panels.iter().flat_map(|p| p.series.iter().map(|s| s.label.as_str())).collect();
        assert!(labels.contains(&"sley back dwell"), "{name}");
        let svg = fig.to_svg().unwrap();
        assert!(loomkin_plot::drawn_text_problems(&svg).unwrap().is_empty(), "{name}");
    }
}
