//! The shedding torque: power balance against the energy's derivative, the fast curve against
//! direct evaluation, the refined peak against a dense grid, the quadrature RMS against a dense sum.

mod common;
use common::*;
use loomkin_loom::{Drive, Loom, Motion, Pattern};

fn setups() -> Vec<(Loom, Pattern)> {
    vec![(rapier(), wif("point-24.wif")), (rapier(), wif("satin-8.wif")), (shuttle(), wif("twill-2-2.wif"))]
}

/// Power balance `T = Σ F·y′ / η` against virtual work `T = dE/dθ / η` (central differences of
/// the stored energy), away from the joints where the acceleration may jump.
#[test]
fn torque_is_the_derivative_of_the_stored_energy() {
    for (loom, pat) in setups() {
        let m = Motion::new(&loom, &pat).unwrap();
        let d = Drive::new(&loom, &m, &pat);
        let joints = m.joints();
        let h = 1e-3;
        let scale = d.peak(1.0).torque_n_m.abs();
        let mut checked = 0;
        for k in 0..400 {
            let th = m.repeat_deg() * (k as f64 + 0.31) / 400.0;
            if joints.iter().any(|j| (j - th).abs() < 2.0 * h) {
                continue;
            }
            let fd = (d.energy_j(th + h) - d.energy_j(th - h)) / (2.0 * h.to_radians()) / loom.efficiency;
            let t = d.torque_at(th);
            assert!((t - fd).abs() < 1e-6 * scale, "{th}: {t} vs {fd}");
            checked += 1;
        }
        assert!(checked > 300);
    }
}

#[test]
fn the_fast_curve_is_the_direct_evaluation() {
    for (loom, pat) in setups() {
        let m = Motion::new(&loom, &pat).unwrap();
        let d = Drive::new(&loom, &m, &pat);
        let scale = d.peak(1.0).torque_n_m.abs();
        for step in [0.5, 1.0, 0.7] {
            let c = d.torque_curve(step);
            assert_eq!(c.len(), (m.repeat_deg() / step).round() as usize);
            for (th, t) in c.iter().step_by(7) {
                let direct = d.torque_at(*th);
                assert!((t - direct).abs() < 1e-9 * scale, "step {step} at {th}: {t} vs {direct}");
            }
        }
    }
}

#[test]
fn the_peak_is_refined_and_the_rms_exact() {
    for (loom, pat) in setups() {
        let m = Motion::new(&loom, &pat).unwrap();
        let d = Drive::new(&loom, &m, &pat);
        let p = d.peak(0.5);
        let dense = d.torque_curve(0.01);
        let dense_max = dense.iter().map(|(_, t)| t.abs()).fold(0.0, f64::max);
        // The refined peak is at least the dense grid's and exceeds it by no more than the
        // curvature allows over half a step of 0.01°.
        assert!(p.torque_n_m.abs() >= dense_max * (1.0 - 1e-12), "{} < {dense_max}", p.torque_n_m);
        assert!(p.torque_n_m.abs() <= dense_max * (1.0 + 1e-5), "{} vs {dense_max}", p.torque_n_m);
        assert!((d.torque_at(p.angle_deg) - p.torque_n_m).abs() < 1e-9 * dense_max);
        let rms = d.rms();
        let sum: f64 = dense.iter().map(|(_, t)| t * t).sum::<f64>() / dense.len() as f64;
        // A rectangle sum of a periodic piecewise-smooth function: error O(h²) at the kinks.
        assert!((rms / sum.sqrt() - 1.0).abs() < 1e-6, "{rms} vs {}", sum.sqrt());
        eprintln!(
            "{} × {} picks: peak {:.3} N·m at {:.3}°, rms {:.3} N·m",
            loom.frame_count(),
            pat.picks(),
            p.torque_n_m,
            p.angle_deg,
            rms
        );
    }
}

/// A back frame 0.1 mm before the back rest: its warp pull `∂L/∂y` turns from −1 to +1 while
/// the eye crosses the back rest's level, within a fraction of a degree. One 16-point rule per
/// 20° panel missed the RMS by 1.4e-4; the halving quadrature meets a 0.01° rectangle sum (the
/// torque is continuous and periodic, so the sum's error is O(h²) at the kinks) to 1e-6, and a
/// scipy Gauss–Legendre sum on 0.02° panels (docs/design/loom.md) to 1e-15.
#[test]
fn the_rms_follows_a_frame_at_the_back_rest() {
    let text = edited(
        &example("shuttle-loom.toml"),
        "frame_distances_mm = [230, 250, 270, 290]",
        "frame_distances_mm = [230, 250, 270, 899.9]",
    );
    let text = edited(&text, "front_stroke_mm = 100", "front_stroke_mm = 10");
    let loom = Loom::from_toml(&text).unwrap();
    let pat = wif("twill-2-2.wif");
    let m = Motion::new(&loom, &pat).unwrap();
    let d = Drive::new(&loom, &m, &pat);
    let dense = d.torque_curve(0.01);
    let sum: f64 = dense.iter().map(|(_, t)| t * t).sum::<f64>() / dense.len() as f64;
    let rms = d.rms();
    assert!((rms / sum.sqrt() - 1.0).abs() < 1e-6, "{rms} vs {}", sum.sqrt());
}

#[test]
fn forces_have_the_expected_parts() {
    let loom = rapier();
    let pat = wif("twill-2-2.wif");
    let m = Motion::new(&loom, &pat).unwrap();
    let d = Drive::new(&loom, &m, &pat);
    // The threading puts the warp on the draft's 4 shafts only.
    assert!((d.ends()[..4].iter().sum::<f64>() - 7600.0).abs() < 1e-9 && d.ends()[4] == 0.0);
    // A frame at rest at the bottom: its weight and the spring preload; at mid-stroke no warp force.
    let k = m.frame(10, 100.0);
    let f = d.force(10, &k);
    assert_eq!(f.inertia_n, 0.0);
    assert!((f.total_n - (5.5 * 9.80665 + 120.0)).abs() < 1e-9);
    let mid = loomkin_loom::FrameKin { y_m: 0.0, ..Default::default() };
    assert!(d.force(0, &mid).warp_n.abs() < 1e-12);
    let up = loomkin_loom::FrameKin { y_m: 0.04, ..Default::default() };
    assert!(d.force(0, &up).warp_n > 0.0);
}

/// An efficiency near the bottom of its range: T = Σ F·y′ / η stays finite down to η ~ 1e-300
/// while T² overflows below η ~ 1e-150, and the RMS then comes from the exactly scaled torque:
/// `rms(T/η) = rms(T)/η` against the same loom at η = 1 (to the rounding of the division in each
/// torque value). Where the torque itself overflows (η = 1e-310, subnormal) the quadrature takes
/// each panel as it is and the RMS is +∞, which the CLI refuses to print, instead of halving every
/// panel to its depth limit (2³⁰ panels each: the command hung, and so would this test).
#[test]
fn a_tiny_efficiency_keeps_the_rms_finite_while_the_torque_is() {
    let pat = wif("twill-2-2.wif");
    let with = |eta: &str| {
        let text = edited(
            &example("shuttle-loom.toml"),
            "speed_rpm = 200\n",
            &format!("speed_rpm = 200\nefficiency = {eta}\n"),
        );
        Loom::from_toml(&text).unwrap()
    };
    let one = with("1");
    let m = Motion::new(&one, &pat).unwrap();
    let rms1 = Drive::new(&one, &m, &pat).rms();
    for (eta, text) in [(1e-100, "1e-100"), (1e-200, "1e-200"), (1e-300, "1e-300")] {
        let loom = with(text);
        let d = Drive::new(&loom, &m, &pat);
        let rms = d.rms();
        assert!(rms.is_finite(), "η = {eta}: {rms}");
        let want = rms1 / eta;
        assert!((rms - want).abs() <= 1e-12 * want, "η = {eta}: {rms} against {want}");
    }
    let loom = with("1e-310");
    let rms = Drive::new(&loom, &m, &pat).rms();
    assert!(rms.is_infinite(), "{rms}");
}

/// A loom of micrometres with a million ends: the torque's rounding noise stays above the halving
/// tolerance, and the halvings stop at [`loomkin_loom::MAX_RMS_SPLITS`] (every panel to the depth
/// limit hung the command); the RMS still meets a 0.01° rectangle sum.
#[test]
fn a_noisy_torque_does_not_stall_the_rms() {
    let text = r#"name = "micro"
speed_rpm = 100.0
efficiency = 0.5
[geometry]
frame_distances_mm = [1e-3, 2e-3]
reed_mm = 5e-4
back_rest_mm = 3e-3
warp_line_mm = -3e-3
front_stroke_mm = 1e-6
lifts = "clean"
[frames]
mass_kg = 1.0
spring_n_per_mm = 1.0
spring_preload_n = 1.0
[warp]
ends = 1e6
tension_per_end_n = 1e3
stiffness_per_end_n = 1e7
[shedding]
law = "cycloidal"
motion_deg = 200.0
crossing_deg = 0.0
[insertion]
carrier_height_mm = 1e-9
carrier_width_mm = 0.0
reed_width_mm = 1000.0
carrier_length_mm = 10.0
entry_deg = 170.0
exit_deg = 190.0
"#;
    let loom = Loom::from_toml(text).unwrap();
    let pat = Pattern::plain(2).unwrap();
    let m = Motion::new(&loom, &pat).unwrap();
    let d = Drive::new(&loom, &m, &pat);
    let rms = d.rms();
    let dense = d.torque_curve(0.01);
    let sum: f64 = dense.iter().map(|(_, t)| t * t).sum::<f64>() / dense.len() as f64;
    assert!((rms / sum.sqrt() - 1.0).abs() < 1e-6, "{rms} vs {}", sum.sqrt());
}

/// A lift plan of `picks` picks: shaft 4 alone, then the heaviest changes (shafts 1–3 up, shaft 4
/// up) in the last ten picks.
fn heavy_last(picks: usize) -> Pattern {
    let rows: Vec<Vec<bool>> = (0..picks)
        .map(|p| {
            if p + 10 >= picks && p % 2 == 0 { vec![true, true, true, false] } else { vec![false, false, false, true] }
        })
        .collect();
    Pattern::new(4, rows).unwrap()
}

/// The torque peak of a long repeat lies at ~7.2·10⁵°, where the doubles are 1.2·10⁻¹⁰ apart: the
/// peak's refinement (a golden-section search that stopped on an absolute 1e-10°, and never ended
/// there) ends, and finds what the same ten picks give at the start of a short repeat (the torque
/// depends on the frames' motion in and around each pick only): the same peak, 1,980 turns later.
/// No point of a dense grid around it is higher.
#[test]
fn a_peak_late_in_a_long_repeat_is_refined() {
    let loom = shuttle();
    let (long, short) = (heavy_last(2000), heavy_last(20));
    let (ml, ms) = (Motion::new(&loom, &long).unwrap(), Motion::new(&loom, &short).unwrap());
    let (dl, ds) = (Drive::new(&loom, &ml, &long), Drive::new(&loom, &ms, &short));
    let (pl, ps) = (dl.peak(0.5), ds.peak(0.5));
    assert!(pl.angle_deg > 5e5, "{pl:?}");
    assert!((pl.torque_n_m - ps.torque_n_m).abs() <= 1e-9 * ps.torque_n_m.abs(), "{pl:?} vs {ps:?}");
    assert!((pl.angle_deg - ps.angle_deg - 1980.0 * 360.0).abs() < 1e-6, "{pl:?} vs {ps:?}");
    let dense = (-500..=500).map(|k| dl.torque_at(pl.angle_deg + 1e-3 * f64::from(k)).abs()).fold(0.0, f64::max);
    assert!(dense <= pl.torque_n_m.abs() * (1.0 + 1e-12), "{dense} above {pl:?}");
}
