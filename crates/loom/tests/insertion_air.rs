//! The projectile on the loom: the example file, the refusals, its clearance over the repeat
//! against a brute-force scan, the sley's dwell against the sley's own analysis.

mod common;
use common::*;
use loomkin_insertion::Projectile;
use loomkin_loom::insertion::{CarrierPath, CarrierShed, clearance};
use loomkin_loom::insertion_air::{dwell_fit, projectile_check};
use loomkin_loom::{InsertionKind, Loom, Motion};
use loomkin_units::ShaftSpeed;

fn projectile_loom() -> Loom {
    Loom::from_toml(&example("projectile-loom.toml")).unwrap()
}

fn the_projectile(loom: &Loom) -> &Projectile {
    match &loom.insertion.kind {
        InsertionKind::Projectile(p) => p,
        other => panic!("not a projectile: {other:?}"),
    }
}

#[test]
fn the_example_is_a_projectile() {
    let loom = projectile_loom();
    assert_eq!(loom.insertion.kind.name(), "projectile");
    let p = the_projectile(&loom);
    // The file's carrier length is the projectile's; the reed space the file's.
    assert_eq!((p.length_m, p.reed_width_m), (loom.insertion.carrier_length_m, loom.insertion.reed_width_m));
    let text = example("projectile-loom.toml");
    let e = Loom::from_toml(&edited(&text, "kind = \"projectile\"", "kind = \"rapier\"")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "insertion.projectile: [insertion.projectile] goes with kind = \"projectile\" (the file's kind is \"rapier\")"
    );
    let e = Loom::from_toml(&edited(&text, "twist_deg = 30", "twist_deg = 3")).unwrap_err();
    assert!(e.to_string().starts_with("insertion.projectile.twist_deg: the projectile stops"), "{e}");
    let e = Loom::from_toml(&edited(&text, "efficiency = 0.5", "efficiency = 0")).unwrap_err();
    assert!(e.to_string().starts_with("insertion.projectile.efficiency = 0 is out of range"), "{e}");
    let e = Loom::from_toml(&edited(&text, "brake_mm = 80", "brake = 80")).unwrap_err();
    assert!(e.to_string().starts_with("insertion.projectile:"), "{e}");
    let e = loomkin_loom::insertion::rapier_of(&loom).unwrap_err();
    assert!(e.to_string().starts_with("insertion.kind: the loom's carrier is a projectile"), "{e}");
    let e = loomkin_loom::insertion_air::projectile_of(&rapier()).unwrap_err();
    assert!(e.to_string().starts_with("insertion.kind: the loom's carrier is a rapier"), "{e}");
}

/// The guide teeth's least clearance over the repeat: no 0.01° scan point of any pick is lower,
/// and the best scan point is within the scan's resolution of it; at 300 and 350 rpm (the latter
/// touches at the far selvedge).
#[test]
fn clearance_against_a_brute_force_scan() {
    let loom = projectile_loom();
    let pat = wif("point-24.wif");
    let p = the_projectile(&loom);
    for rpm in [300.0, 350.0] {
        let path = p.path(ShaftSpeed::from_rpm(rpm).unwrap());
        let c = clearance(&loom, &pat, &path).unwrap();
        let motion = Motion::new(&loom, &pat).unwrap();
        let shed = CarrierShed::new(&loom, &motion, &pat).unwrap();
        let (from, to) = CarrierPath::in_shed_deg(&path);
        let n = ((to - from) / 0.01).ceil() as usize;
        let mut best = f64::INFINITY;
        for pick in 0..pat.picks() {
            for k in 0..=n {
                best = best.min(shed.clearance_m(pick, from + (to - from) * k as f64 / n as f64) * 1e3);
            }
        }
        assert!(c.min_clearance_mm <= best + 1e-9, "{rpm}: {} vs scan {best}", c.min_clearance_mm);
        assert!(c.min_clearance_mm >= best - 1e-3, "{rpm}: {} vs scan {best}", c.min_clearance_mm);
        assert!((c.worst_position_mm - CarrierPath::position_m(&path, c.worst_angle_deg) * 1e3).abs() < 1e-12);
    }
}

/// The dwell is the sley's own (`sley analyze`'s 1 mm dwell), in the flight's turn; a span inside
/// it fits, one a degree longer does not; the example's flight fits (its cam sley dwells 215°, the
/// flight takes 157°; a four-bar's 26° would not hold it).
#[test]
fn the_sley_dwell() {
    let loom = projectile_loom();
    let a = loom.sley.as_ref().unwrap().analyze(loom.speed, 1.0).unwrap();
    let c = projectile_check(&loom, &wif("point-24.wif"), loom.speed).unwrap();
    let d = c.dwell.unwrap();
    assert!((d.sley_back_dwell_deg[0] - a.dwell_start_deg).abs() < 1e-9, "{d:?} vs {a:?}");
    assert!((d.sley_back_dwell_deg[1] - d.sley_back_dwell_deg[0] - a.back_dwell_deg).abs() < 1e-9);
    assert!(d.fits_sley_dwell);
    let [s, e] = d.sley_back_dwell_deg;
    assert!(!dwell_fit(&loom, s - 1.0, e).unwrap().unwrap().fits_sley_dwell);
    let inside = dwell_fit(&loom, s + 1.0, e - 1.0).unwrap().unwrap();
    assert!(inside.fits_sley_dwell);
    // A turn later is the same dwell a turn later.
    let later = dwell_fit(&loom, s + 361.0, e + 359.0).unwrap().unwrap();
    assert!(later.fits_sley_dwell && (later.sley_back_dwell_deg[0] - s - 360.0).abs() < 1e-9);
    // Without a [sley], no dwell.
    let text = example("projectile-loom.toml");
    let cut = text.find("[sley]").unwrap();
    let end = text.find("[drive]").unwrap();
    let no_sley = Loom::from_toml(&format!("{}{}", &text[..cut], &text[end..])).unwrap();
    assert_eq!(dwell_fit(&no_sley, s, e).unwrap(), None);
}

/// The air-jet example reads as one; its report is the library's; the refusals name the field.
#[test]
fn the_airjet_example() {
    let text = example("airjet-loom.toml");
    let loom = Loom::from_toml(&text).unwrap();
    assert_eq!(loom.insertion.kind.name(), "airjet");
    let r = loomkin_loom::insertion_air::airjet_check(&loom, loom.speed).unwrap();
    assert_eq!(r.relay_plan.len(), 20);
    assert!(r.arrival_deg > r.launch_deg && r.tip_speed_at_exit_m_s > 0.0);
    let e = Loom::from_toml(&edited(&text, "groups = 20", "groups = 0")).unwrap_err();
    assert!(e.to_string().starts_with("insertion.airjet.groups = 0 is out of range"), "{e}");
    let e = Loom::from_toml(&edited(&text, "kind = \"airjet\"", "kind = \"projectile\"")).unwrap_err();
    assert!(e.to_string().starts_with("insertion.airjet: [insertion.airjet] goes with kind = \"airjet\""), "{e}");
    let e = loomkin_loom::insertion_air::airjet_check(&rapier(), loom.speed).unwrap_err();
    assert!(e.to_string().starts_with("insertion.kind: the loom's carrier is a rapier"), "{e}");
}
