//! Frame motions over the repeat: against the law core's cycles, the shed crate's single-frame
//! law, and finite differences.

mod common;
use common::*;
use loomkin_laws::Cycle;
use loomkin_loom::{Motion, Pattern};
use loomkin_shed::{Conditions, cycle_curve};

/// Every frame's motion equals the machine cycle of the law core built from its moves.
#[test]
fn frames_follow_their_law_core_cycles() {
    for (loom, pat) in
        [(rapier(), wif("point-24.wif")), (shuttle(), wif("twill-2-2.wif")), (rapier(), wif("satin-8.wif"))]
    {
        let m = Motion::new(&loom, &pat).unwrap();
        for i in 0..m.frames() {
            let spec = m.cycle_spec(i);
            let cycle = Cycle::new(&spec).unwrap();
            let moves = m.moves(i);
            let base = match moves.first() {
                Some(first) => {
                    if first.rising {
                        -m.stroke_m(i) / 2.0
                    } else {
                        m.stroke_m(i) / 2.0
                    }
                }
                None => m.frame(i, 0.0).y_m,
            };
            let w = loom.speed.rad_per_s();
            for k in 0..2000 {
                let th = m.repeat_deg() * (k as f64 + 0.37) / 2000.0;
                let ours = m.frame(i, th);
                let c = cycle.eval(th.to_radians(), loom.speed.rpm());
                let h = m.stroke_m(i);
                assert!(
                    (ours.y_m - (base + c.s)).abs() < 1e-12 * h,
                    "frame {i} at {th}: {} vs {}",
                    ours.y_m,
                    base + c.s
                );
                assert!((ours.dy * w - c.v).abs() < 1e-9 * (1.0 + c.v.abs()), "v frame {i} at {th}");
                assert!((ours.d2y * w * w - c.a).abs() < 1e-9 * (1.0 + c.a.abs()), "a frame {i} at {th}");
            }
        }
    }
}

/// Plain weave on one frame: the frame's motion is the shed crate's frame cycle (rise, dwell,
/// return, dwell over two picks) shifted to start where the move into pick 0 starts.
#[test]
fn a_plain_weave_frame_moves_as_the_shed_crate_says() {
    let loom = shuttle();
    let loom = loom.with_stagger(&[0.0; 4]).unwrap();
    let pat = Pattern::new(4, vec![vec![true, false, true, false], vec![false, true, false, true]]).unwrap();
    let m = Motion::new(&loom, &pat).unwrap();
    let law = loomkin_shed::preset("basic").unwrap();
    let h = m.stroke_m(1);
    let cond = Conditions::new(0.95, h, loom.speed.rpm()).unwrap();
    let curve = cycle_curve(&law, &cond, 721).unwrap();
    // Frame 2 (index 1) rises into pick 1: its move starts at 360 + 0 − 90 = 270°.
    let rise = m.moves(1).into_iter().find(|mv| mv.rising).unwrap();
    let start = rise.start_deg;
    assert_eq!(start, 270.0);
    let w = loom.speed.rad_per_s();
    for p in &curve[..720] {
        let k = m.frame(1, start + p.angle_deg);
        assert!((k.y_m + h / 2.0 - p.s_m).abs() < 1e-12, "{}: {} vs {}", p.angle_deg, k.y_m + h / 2.0, p.s_m);
        assert!((k.dy * w - p.v_m_s).abs() < 1e-9 * (1.0 + p.v_m_s.abs()));
        assert!((k.d2y * w * w - p.a_m_s2).abs() < 1e-9 * (1.0 + p.a_m_s2.abs()));
    }
}

#[test]
fn frames_keeping_their_place_dwell() {
    let loom = rapier();
    let pat = wif("twill-2-2.wif");
    let m = Motion::new(&loom, &pat).unwrap();
    // Frame 2 is up at picks 1 and 2 (0-based 0, 1): it dwells through the change between them.
    assert!(pat.is_up(0, 1) && pat.is_up(1, 1));
    let top = m.stroke_m(1) / 2.0;
    for th in [300.0, 350.0, 360.0, 400.0, 500.0] {
        let k = m.frame(1, th);
        assert_eq!((k.y_m, k.dy, k.d2y), (top, 0.0, 0.0), "{th}");
    }
    // Frames beyond the draft's shafts stay down.
    let k = m.frame(10, 1000.0);
    assert_eq!(k.y_m, -m.stroke_m(10) / 2.0);
    // Every move is centred on the crossing angle (350° → δ = −10°).
    for mv in m.moves(0) {
        assert!((mv.start_deg + 140.0 - (360.0 * mv.pick as f64 - 10.0)).abs() < 1e-12);
    }
}

#[test]
fn derivatives_match_finite_differences() {
    let loom = rapier();
    let m = Motion::new(&loom, &wif("satin-8.wif")).unwrap();
    let h = 1e-4;
    for i in [0, 3, 7] {
        for k in 0..200 {
            let th = m.repeat_deg() * (k as f64 + 0.5) / 200.0;
            let f = |t: f64| m.frame(i, t);
            let (a, b) = (f(th - h), f(th + h));
            let hr = h.to_radians();
            let (fd1, fd2) = ((b.y_m - a.y_m) / (2.0 * hr), (b.dy - a.dy) / (2.0 * hr));
            let c = f(th);
            // Skip the points next to a joint of the law or a move end.
            if m.joints().iter().any(|j| (j - th).abs() < 2.0 * h) {
                continue;
            }
            assert!((c.dy - fd1).abs() < 1e-7 * (1.0 + c.dy.abs()), "{i} {th}: {} {fd1}", c.dy);
            assert!((c.d2y - fd2).abs() < 1e-6 * (1.0 + c.d2y.abs()), "{i} {th}: {} {fd2}", c.d2y);
        }
    }
}

#[test]
fn a_draft_wider_than_the_loom_is_refused() {
    let loom = shuttle();
    let e = Motion::new(&loom, &wif("satin-8.wif")).unwrap_err().to_string();
    assert_eq!(e, "pattern: the draft has 8 shafts but the loom has 4 frames (geometry.frame_distances_mm)");
}
