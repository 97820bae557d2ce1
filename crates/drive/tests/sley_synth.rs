//! The sley synthesis: targets met exactly, and no linkage found by an independent search meets
//! them with a better least transmission angle.

use std::f64::consts::{FRAC_PI_2, TAU};

use loomkin_drive::{Assembly, FourBarSley, SleyError, SleyTable, SleyTarget};
use loomkin_units::FieldError;

fn target(stroke_mm: f64, back_dwell_deg: f64) -> SleyTarget {
    SleyTarget { stroke_mm, back_dwell_deg, dwell_tolerance_mm: 1.0, reed_height_mm: 400.0, sword_mm: None }
}

#[test]
fn the_targets_are_met_exactly() {
    for (s, d) in [(70.0, 25.0), (110.0, 35.0), (110.0, 20.0), (130.0, 50.0), (300.0, 30.0)] {
        let r = target(s, d).synthesize().unwrap();
        // Rebuilt from its table alone (mass and gyration do not enter the kinematics).
        let sley = FourBarSley::new(r.table).unwrap();
        assert!((sley.stroke_m() * 1e3 - s).abs() < 1e-12 * s, "{s} {d}: stroke {}", sley.stroke_m() * 1e3);
        let (a, b) = sley.back_dwell_rad(1e-3).unwrap();
        assert!(((b - a).to_degrees() - d).abs() < 1e-9 * d, "{s} {d}: dwell {}", (b - a).to_degrees());
        assert_eq!(r.min_transmission_angle_deg, sley.min_transmission_rad().to_degrees());
        assert!(r.min_transmission_angle_deg > 0.0 && r.min_transmission_angle_deg <= 90.0);
        // The sword is 0.7 of the reed height when left out; another sword scales the linkage only.
        assert_eq!(r.sword_mm, 280.0);
        let big = SleyTarget { sword_mm: Some(560.0), ..target(s, d) }.synthesize().unwrap();
        assert!((big.crank_mm / r.crank_mm - 2.0).abs() < 1e-6, "{} {}", big.crank_mm, r.crank_mm);
        assert!((big.min_transmission_angle_deg - r.min_transmission_angle_deg).abs() < 1e-6);
    }
}

/// An independent search: crank centres on 360 rays from the middle of the sword pin's chord, each
/// ray scanned at 240 distances (geometric, 0.01 … 4 swords) for crossings of the target dwell,
/// each crossing located by regula falsi (loomkin_numeric::illinois_root, not the synthesis's
/// bisection); the best least transmission angle of the linkages found.
fn independent_best(t: &SleyTarget) -> f64 {
    let c = 0.7 * t.reed_height_mm;
    let swing = t.stroke_mm / t.reed_height_mm;
    let front = (c * (FRAC_PI_2 - swing / 2.0).cos(), c * (FRAC_PI_2 - swing / 2.0).sin());
    let back = (c * (FRAC_PI_2 + swing / 2.0).cos(), c * (FRAC_PI_2 + swing / 2.0).sin());
    let mid = ((front.0 + back.0) / 2.0, (front.1 + back.1) / 2.0);
    // Both branches at every crank centre: each is a crank-rocker of the stroke (the one the
    // synthesis does not construct there is, turned about the rocking shaft, one it constructs at
    // another centre), so the best over both bounds the synthesis from above.
    let linkage = |u: f64, rho: f64, assembly: Assembly| -> Option<FourBarSley> {
        let o = (mid.0 + rho * u.cos(), mid.1 + rho * u.sin());
        let (lf, lb) = ((front.0 - o.0).hypot(front.1 - o.1), (back.0 - o.0).hypot(back.1 - o.1));
        {
            let table = SleyTable {
                crank_mm: (lf - lb).abs() / 2.0,
                rod_mm: (lf + lb) / 2.0,
                sword_mm: c,
                pivot_x_mm: -o.0,
                pivot_y_mm: -o.1,
                reed_height_mm: t.reed_height_mm,
                mass_kg: 1.0,
                gyration_mm: c,
                centre_mm: None,
                beat_up_deg: 0.0,
                beat_up_force_n: 0.0,
                beat_up_range_deg: 0.0,
                assembly,
            };
            FourBarSley::new(table).ok().filter(|s| (s.stroke_m() * 1e3 - t.stroke_mm).abs() < 1e-9 * t.stroke_mm)
        }
    };
    let dwell = |u: f64, rho: f64, assembly: Assembly| {
        linkage(u, rho, assembly)
            .and_then(|s| s.back_dwell_rad(t.dwell_tolerance_mm * 1e-3).ok())
            .map(|(a, b)| (b - a).to_degrees())
    };
    let mut best = f64::NEG_INFINITY;
    for (k, assembly) in (0..360).flat_map(|k| [(k, Assembly::Left), (k, Assembly::Right)]) {
        let u = TAU * k as f64 / 360.0;
        let rho = |i: usize| 0.01 * c * 400f64.powf(i as f64 / 240.0);
        let mut prev: Option<(f64, f64)> = None;
        for i in 0..=240 {
            let r1 = rho(i);
            let g1 = dwell(u, r1, assembly).map(|d| d - t.back_dwell_deg);
            if let (Some((r0, g0)), Some(g1)) = (prev, g1)
                && (g0 < 0.0) != (g1 < 0.0)
            {
                let root = loomkin_numeric::illinois_root(r0, r1, g0, g1, |r| {
                    dwell(u, r, assembly).map_or(g1, |d| d - t.back_dwell_deg)
                });
                if let Some(s) = linkage(u, root, assembly)
                    && let Some(d) = dwell(u, root, assembly)
                    && (d - t.back_dwell_deg).abs() < 1e-6
                {
                    best = best.max(s.min_transmission_rad().to_degrees());
                }
            }
            prev = g1.map(|g| (r1, g));
        }
    }
    best
}

#[test]
fn no_linkage_of_an_independent_search_transmits_better() {
    for (s, d) in [(110.0, 40.0), (70.0, 25.0), (500.0, 30.0)] {
        let t = target(s, d);
        let r = t.synthesize().unwrap();
        let other = independent_best(&t);
        assert!(other.is_finite(), "{s} {d}: the independent search finds linkages");
        assert!(other <= r.min_transmission_angle_deg + 1e-6, "{s} {d}: {other} > {}", r.min_transmission_angle_deg);
        // And the synthesis is not worse than the search's grid by more than its resolution.
        assert!(r.min_transmission_angle_deg - other < 0.5, "{s} {d}: {} vs {other}", r.min_transmission_angle_deg);
    }
}

#[test]
fn infeasible_targets_are_refused_with_one_line() {
    let e = target(110.0, 300.0).synthesize().unwrap_err();
    assert_eq!(e.field(), Some("back_dwell_deg"));
    assert!(e.to_string().contains("no crank-rocker gives a back dwell of 300°"), "{e}");
    let e = target(900.0, 30.0).synthesize().unwrap_err();
    assert!(matches!(e, SleyError::Infeasible { ref fields, .. } if fields == "reed_stroke_mm, reed_height_mm"), "{e}");
    let e = SleyTarget { dwell_tolerance_mm: 110.0, ..target(110.0, 30.0) }.synthesize().unwrap_err();
    assert_eq!(e.field(), Some("dwell_tolerance_mm"));
    let e = target(110.0, 0.0).synthesize().unwrap_err();
    assert_eq!(e.to_string(), "back_dwell_deg = 0 is out of range: allowed 0 < back_dwell_deg < 360 deg");
}
