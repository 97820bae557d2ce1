//! A long repeat is checked turn by turn, once per distinct turn: the numbers of a draft repeated
//! many times are those of the draft itself, every pick's window is what a direct evaluation of
//! that pick gives, and the streamed peak is the whole curve's (the memory `loom check` holds is
//! measured by the CLI's tests).

mod common;
use common::*;
use loomkin_loom::{Drive, Loom, Motion, Pattern, Timing, check, check_with};
/// `pattern` repeated `times` times.
fn repeated(pattern: &Pattern, shafts: usize, times: usize) -> Pattern {
    let rows: Vec<Vec<bool>> = (0..times)
        .flat_map(|_| (0..pattern.picks()).map(|p| (0..shafts).map(|s| pattern.is_up(p, s)).collect::<Vec<bool>>()))
        .collect();
    Pattern::new(shafts, rows).unwrap()
}

/// A lift plan whose picks (nearly) all differ: shaft s up at pick p when bit s of a mixed p is set.
fn scrambled(picks: usize, shafts: usize) -> Pattern {
    let rows = (0..picks)
        .map(|p| {
            let x = (p as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15).rotate_left(17);
            (0..shafts).map(|s| x >> (s % 64) & 1 == 1).collect()
        })
        .collect();
    Pattern::new(shafts, rows).unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// The draft repeated 40 times: the same peak (at the same angle: the earliest) and RMS to
/// rounding, the same window, clearance and speed — the repeat is periodic.
#[test]
fn a_repeated_draft_checks_as_the_draft() {
    for (loom, pattern) in [(rapier(), wif("point-24.wif")), (shuttle(), wif("twill-2-2.wif"))] {
        let shafts = pattern.shafts().max(1);
        let long = repeated(&pattern, shafts, 40);
        let (a, b) = (check(&loom, &pattern).unwrap(), check(&loom, &long).unwrap());
        assert_eq!(b.picks, 40 * a.picks);
        // Peaks within 1e-13 of each other are one peak (a symmetric draft's mirror images, the
        // copies in later repeats): the long repeat's is where the draft's torque is as high.
        assert!(close(a.peak_torque_n_m, b.peak_torque_n_m, 1e-13), "{} vs {}", a.peak_torque_n_m, b.peak_torque_n_m);
        let motion = Motion::new(&loom, &pattern).unwrap();
        let at = Drive::new(&loom, &motion, &pattern).torque_at(b.peak_angle_deg.rem_euclid(360.0 * a.picks as f64));
        assert!(close(at.abs(), a.peak_torque_n_m, 1e-12), "{at} at {} vs {}", b.peak_angle_deg, a.peak_torque_n_m);
        assert!(close(a.rms_torque_n_m, b.rms_torque_n_m, 1e-13), "{} vs {}", a.rms_torque_n_m, b.rms_torque_n_m);
        assert_eq!(
            (a.min_clearance_mm, a.window_open_deg, a.window_close_deg, a.max_speed_rpm),
            (b.min_clearance_mm, b.window_open_deg, b.window_close_deg, b.max_speed_rpm)
        );
        for (fa, fb) in a.frames.iter().zip(&b.frames) {
            assert_eq!((fa.max_strain, 40 * fa.moves), (fb.max_strain, fb.moves));
        }
    }
}

/// Every pick's window, taken from the first pick of its kind, against the pick computed on its
/// own — with the frames staggered to the ends of their range and the crossing at both ends of
/// its, so that the window of picks that decides a turn is tested where it is widest.
#[test]
fn every_pick_window_is_the_picks_own() {
    let text = example("rapier-loom.toml");
    let stagger: Vec<String> = (0..24)
        .map(|i| {
            if i % 3 == 0 {
                "15".into()
            } else if i % 3 == 1 {
                "-15".into()
            } else {
                "0".into()
            }
        })
        .collect();
    let staggered = format!("{text}\n").replacen(
        "max_stagger_deg = 15",
        &format!("max_stagger_deg = 15\nstagger_deg = [{}]", stagger.join(", ")),
        1,
    );
    for crossing in ["crossing_deg = 350", "crossing_deg = 180", "crossing_deg = 179.9", "crossing_deg = 0"] {
        let loom = Loom::from_toml(&edited(&staggered, "crossing_deg = 350", crossing)).unwrap();
        let pattern = repeated(&wif("point-24.wif"), 24, 3);
        let motion = Motion::new(&loom, &pattern).unwrap();
        let timing = Timing::new(&loom, &motion, &pattern).unwrap();
        let Ok(report) = timing.report() else { continue };
        assert_eq!(report.picks.len(), pattern.picks());
        for (p, w) in report.picks.iter().enumerate() {
            let own = timing.pick_window(p);
            assert_eq!(w.pick, own.pick);
            for (x, y) in
                [(w.open_deg, own.open_deg), (w.close_deg, own.close_deg), (w.min_clearance_mm, own.min_clearance_mm)]
            {
                assert!((x - y).abs() <= 1e-9, "{crossing}, pick {}: {w:?} vs {own:?}", p + 1);
            }
        }
        // The torque's square, turn by turn against the whole repeat on a dense grid.
        let d = Drive::new(&loom, &motion, &pattern);
        let curve = d.torque_curve(0.05);
        let dense = (curve.iter().map(|(_, t)| t * t).sum::<f64>() / curve.len() as f64).sqrt();
        assert!(close(d.rms(), dense, 1e-5), "{crossing}: {} vs {dense}", d.rms());
    }
}

/// The streamed peak is the peak of the whole curve, bit for bit.
#[test]
fn the_streamed_peak_is_the_curves() {
    for (loom, pattern) in
        [(rapier(), wif("point-24.wif")), (rapier(), scrambled(200, 24)), (shuttle(), wif("twill-2-2.wif"))]
    {
        let motion = Motion::new(&loom, &pattern).unwrap();
        let d = Drive::new(&loom, &motion, &pattern);
        for step in [0.5, 0.7, 2.0] {
            assert_eq!(d.peak(step), d.peak_of(&d.torque_curve(step)), "step {step}");
        }
    }
}

/// The streamed curve (`loom torque --csv/--json` of a long repeat) is the whole curve, point for
/// point and bit for bit, at steps that divide 360° (a turn at a time from the power tables) and
/// steps that do not (each point evaluated); its report is the whole curve's report; its cost is
/// counted before any point is made.
#[test]
fn the_streamed_curve_is_the_curve() {
    for (loom, pattern) in
        [(rapier(), wif("point-24.wif")), (rapier(), scrambled(60, 24)), (shuttle(), wif("twill-2-2.wif"))]
    {
        let motion = Motion::new(&loom, &pattern).unwrap();
        let d = Drive::new(&loom, &motion, &pattern);
        for step in [0.1, 0.5, 0.7, 2.0, 10.0] {
            let curve = d.torque_curve(step);
            let points = d.torque_points(step);
            assert_eq!(points.len(), curve.len(), "step {step}");
            assert_eq!(d.curve_len(step), curve.len(), "step {step}");
            let streamed: Vec<(f64, f64)> = points.collect();
            assert_eq!(streamed.len(), curve.len());
            for (k, (s, c)) in streamed.iter().zip(&curve).enumerate() {
                assert_eq!(s.0.to_bits(), c.0.to_bits(), "step {step}, point {k}: angle");
                assert_eq!(s.1.to_bits(), c.1.to_bits(), "step {step}, point {k}: torque");
            }
            let whole = d.torque_report(&curve);
            let summary = d.torque_summary(step, whole.points.clone());
            assert_eq!(summary, whole, "step {step}");
            // Streamed, a turn is held; drawn, every point.
            let (table, plot) = (d.curve_cost(step, false), d.curve_cost(step, true));
            let n = motion.repeat_deg() / step;
            assert_eq!(table.bytes, 0.0);
            assert!(close(plot.bytes, n * Drive::PLOT_BYTES_PER_POINT, 1e-12));
            assert!(close(table.seconds, loomkin_units::Cost::SHARED * n * Drive::CPU_S_PER_POINT, 1e-12));
        }
    }
}

/// `check_with`'s progress counts every pick's turn, ends at `done == all` (the picks and 2), and
/// the report is `check`'s.
#[test]
fn check_progress_counts_the_picks() {
    let (loom, pattern) = (rapier(), scrambled(120, 24));
    let calls = std::cell::RefCell::new(Vec::new());
    let with = check_with(&loom, &pattern, &|d, a| calls.borrow_mut().push((d, a))).unwrap();
    assert_eq!(format!("{with:?}"), format!("{:?}", check(&loom, &pattern).unwrap()));
    let calls = calls.into_inner();
    assert!(calls.iter().all(|&(_, a)| a == 122));
    assert!(calls.windows(2).all(|w| w[1].0 == w[0].0 + 1), "{calls:?}");
    assert_eq!(calls.first(), Some(&(1, 122)));
    assert_eq!(calls.last(), Some(&(122, 122)));
}
