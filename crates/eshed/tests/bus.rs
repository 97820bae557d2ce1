//! Electronic shedding against independent routes: the servo axis model point by point, the energy
//! balance over the repeat in closed form, the bus peaks against dense scans, the C² claim.

mod common;

use loomkin_eshed::{
    Bus, DriveMemo, FrameInput, FrameLoad, FramePlan, FrameServo, FrameSetup, MoveLaws, Study, Transmission, Winding,
    analyse, curves, joint_class, peak_bus_power_w, peak_bus_power_w_at, peak_bus_power_w_memo,
};
use loomkin_laws::{Cycle, LawSpec};
use loomkin_servo::operating_point_at;

const SPEED_RPM: f64 = 500.0;

fn laws(spec: LawSpec) -> MoveLaws {
    let law = spec.build().unwrap();
    MoveLaws::new((spec.clone(), law.clone()), (spec, law))
}

/// A law up, another down and a third for the moves laid end to end, each named by a field.
fn mixed(rise: LawSpec, fall: LawSpec, through: LawSpec) -> MoveLaws {
    let b = |s: LawSpec| {
        let l = s.build().unwrap();
        (s, l)
    };
    MoveLaws {
        rise: b(rise),
        fall: b(fall),
        through: Some(b(through)),
        fields: ["servo.rise_law".into(), "servo.fall_law".into(), "servo.through_law".into()],
        labels: ["rise".into(), "fall".into(), "through".into()],
    }
}

/// The law sets the closed-form checks run on: one law both ways and one angle; then three laws
/// (up, down, laid end to end) with the moves down 23° longer than the moves up.
fn law_sets(one: LawSpec) -> [(MoveLaws, f64); 2] {
    [(laws(one), 0.0), (mixed(LawSpec::ModifiedSine, LawSpec::Poly4567, LawSpec::Cycloidal), 23.0)]
}

/// `∫₀¹ v̂(x)² dx` of a law: 8-point Gauss–Legendre on 4000 equal pieces (the laws' joints at
/// multiples of 1/8 fall on piece ends).
fn integral_v2(law: &loomkin_laws::Law) -> f64 {
    let rule = loomkin_laws::gauss_legendre(8);
    let n = 4000;
    let h = 1.0 / n as f64;
    (0..n)
        .map(|k| {
            let (a, b) = (k as f64 * h, (k + 1) as f64 * h);
            rule.iter()
                .map(|&(x, w)| {
                    let v = law.eval(0.5 * (a + b) + 0.5 * (b - a) * x).v;
                    0.5 * (b - a) * w * v * v
                })
                .sum::<f64>()
        })
        .sum()
}

fn servo(efficiency: f64, friction_n: f64, viscous_n_s_m: f64, resistance_ohm: f64) -> FrameServo {
    servo_by(efficiency, friction_n, viscous_n_s_m, resistance_ohm, None)
}

/// The transmissions every bus test runs with: the linear drive and the crank and lever.
const CRANK: [bool; 2] = [false, true];

fn servo_by(
    efficiency: f64,
    friction_n: f64,
    viscous_n_s_m: f64,
    resistance_ohm: f64,
    crank_lever: Option<loomkin_servo::CrankLever>,
) -> FrameServo {
    FrameServo {
        motor: common::motor(),
        transmission: Transmission {
            travel_mm_per_rev: if crank_lever.is_some() { 0.0 } else { 100.0 },
            efficiency,
            friction_n,
            viscous_n_s_m,
            extra_inertia_kg_m2: 2e-4,
            crank_lever,
        },
        winding: Winding { resistance_ohm, torque_constant_n_m_a: 1.7 },
        motion_deg: None,
        moves: Default::default(),
    }
}

/// A pseudo-random lift plan, `frames × picks`, every frame changing at least twice.
fn lift_plan(frames: usize, picks: usize, seed: u64) -> Vec<Vec<bool>> {
    let mut x = seed;
    (0..frames)
        .map(|i| {
            let mut row: Vec<bool> = (0..picks)
                .map(|_| {
                    x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    (x >> 33) % 2 == 1
                })
                .collect();
            row[i % picks] = true;
            row[(i + 1) % picks] = false;
            row
        })
        .collect()
}

fn setups(plan: &[Vec<bool>], pass_through: bool, s: &FrameServo, stagger: f64, l: &MoveLaws) -> Vec<FrameSetup> {
    setups_at(plan, pass_through, s, stagger, l, 0.0)
}

/// [`setups`] with every frame's moves down `fall_extra_deg` longer than its moves up.
fn setups_at(
    plan: &[Vec<bool>],
    pass_through: bool,
    s: &FrameServo,
    stagger: f64,
    l: &MoveLaws,
    fall_extra_deg: f64,
) -> Vec<FrameSetup> {
    plan.iter()
        .enumerate()
        .map(|(i, up)| {
            let stroke = 0.09 + 0.005 * i as f64;
            let p = FramePlan::new(
                &FrameInput {
                    up,
                    stroke_m: stroke,
                    centre_deg: -10.0 + stagger * (i as f64 - 1.5),
                    motion_deg: 250.0 + 5.0 * i as f64,
                    fall_motion_deg: 250.0 + 5.0 * i as f64 + fall_extra_deg,
                },
                pass_through,
            )
            .unwrap();
            let load = FrameLoad {
                mass_kg: 5.0 + 0.3 * i as f64,
                spring_n_m: 300.0 * (i % 2) as f64,
                preload_n: 40.0,
                stroke_m: stroke,
                start_level_m: p.start_level_m(),
            };
            FrameSetup { plan: p, laws: l.clone(), load, servo: s.clone() }
        })
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

#[test]
fn each_frames_torque_is_the_servo_axis_model_run_on_its_own_cycle() {
    let plan = lift_plan(4, 12, 7);
    for (pass, crank) in [false, true].into_iter().flat_map(|p| CRANK.map(|c| (p, c))) {
        for (l, extra) in law_sets(LawSpec::Poly345) {
            let cl = crank.then(common::crank_lever);
            let fs = setups_at(&plan, pass, &servo_by(0.93, 6.0, 15.0, 1.5, cl), 4.0, &l, extra);
            let c = curves(&fs, &Bus::default(), SPEED_RPM, 2001).unwrap();
            let study = Study::new(&fs, SPEED_RPM).unwrap();
            let mut worst = 0.0f64;
            for i in 0..fs.len() {
                for (k, &a) in c.angle_deg.iter().enumerate() {
                    let op = operating_point_at(
                        &study.drives[i].axis,
                        &study.cycles[i],
                        SPEED_RPM,
                        a.to_radians().to_degrees(),
                    )
                    .unwrap();
                    let scale = c.torque_n_m[i].iter().fold(0.0f64, |m, t| m.max(t.abs()));
                    worst = worst.max((op.torque_nm - c.torque_n_m[i][k]).abs() / scale);
                    assert!((op.motor_speed_rpm - c.speed_rpm[i][k]).abs() <= 1e-9 * op.motor_speed_rpm.abs().max(1.0));
                }
            }
            // The same model (loomkin_servo::Axis::torque_at) on the same closed form: rounding only
            // (the two locate the angle in the cycle through degrees and through radians).
            assert!(worst <= 1e-12, "largest difference {worst:e} of the peak torque");
        }
    }
}

#[test]
fn energy_drawn_over_the_repeat_is_the_losses_in_closed_form() {
    // Over a periodic repeat the kinetic and potential energy return to their start, so the
    // electrical energy drawn is the losses: the copper loss R/k_t²·∫T² dt (∫T² from the servo
    // check's own RMS), and per move the Coulomb friction F_μ·H and the viscous c·H²/τ·∫v̂²dx
    // (∫v̂²dx of the move's law, 3/2 for the cycloid), both divided by η (the model's transmission), and the
    // transmission loss of the conservative rule, (1/η − 1)∫F·v dt, which is zero over the repeat.
    let plan = lift_plan(5, 16, 11);
    let (eta, fmu, c, r) = (0.9, 8.0, 25.0, 2.0);
    assert!((integral_v2(&LawSpec::Cycloidal.build().unwrap()) - 1.5).abs() < 1e-13);
    for (pass, crank) in [false, true].into_iter().flat_map(|p| CRANK.map(|c| (p, c))) {
        for (l, extra) in law_sets(LawSpec::Cycloidal) {
            let fs = setups_at(&plan, pass, &servo_by(eta, fmu, c, r, crank.then(common::crank_lever)), 6.0, &l, extra);
            let rep = analyse(&fs, &Bus { regeneration_efficiency: 1.0, ..Bus::default() }, SPEED_RPM, pass).unwrap();
            let omega = loomkin_units::rad_per_s_from_rpm(SPEED_RPM);
            let mut expected_total = 0.0;
            for (i, f) in fs.iter().enumerate() {
                let copper = r / (1.7 * 1.7) * rep.frames[i].rms_torque_n_m.powi(2) * rep.repeat_s;
                let h = f.plan.stroke_m;
                let moves: f64 = f
                    .plan
                    .moves
                    .iter()
                    .map(|m| {
                        let tau = m.length_deg.to_radians() / omega;
                        (fmu * h + c * h * h / tau * integral_v2(&l.of(m.rising, m.through).1)) / eta
                    })
                    .sum();
                let expected = copper + moves;
                assert!(
                    rel(rep.frames[i].energy_j, expected) < 1e-9,
                    "frame {i}: {} vs {expected}",
                    rep.frames[i].energy_j
                );
                expected_total += expected;
            }
            // With every braking watt returned (η_r = 1) the bus balances: supplied − braking = Σ drawn.
            assert!(rel(rep.supplied_energy_j - rep.braking_energy_j, expected_total) < 1e-9);
            assert!(rel(rep.mean_bus_power_w * rep.repeat_s, rep.supplied_energy_j) < 1e-12);
        }
    }
}

#[test]
fn peaks_are_at_least_every_point_of_a_dense_scan_and_close_to_its_best() {
    let plan = lift_plan(6, 10, 3);
    for (pass, crank) in [false, true].into_iter().flat_map(|p| CRANK.map(|c| (p, c))) {
        let servo = servo_by(0.95, 3.0, 10.0, 1.2, crank.then(common::crank_lever));
        let l = laws(LawSpec::ModifiedSine);
        let fs = setups(&plan, pass, &servo, 5.0, &l);
        let bus = Bus { regeneration_efficiency: 0.8, ..Bus::default() };
        let rep = analyse(&fs, &bus, SPEED_RPM, pass).unwrap();
        let c = curves(&fs, &bus, SPEED_RPM, 3600 * 10 + 1).unwrap();
        let scan_max = c.bus_power_w.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let scan_min = c.bus_power_w.iter().copied().fold(f64::INFINITY, f64::min);
        let tol = 1e-12 * scan_max.abs();
        assert!(rep.peak_bus_power_w >= scan_max - tol, "{} < {scan_max}", rep.peak_bus_power_w);
        assert!(rel(rep.peak_bus_power_w, scan_max) < 1e-4, "{} vs {scan_max}", rep.peak_bus_power_w);
        assert!(rep.peak_braking_power_w >= -scan_min - tol);
        for (i, f) in rep.frames.iter().enumerate() {
            let m = c.power_w[i].iter().fold(0.0f64, |m, p| m.max(p.abs()));
            assert!(f.peak_power_w >= m - 1e-12 * m, "frame {i}: {} < {m}", f.peak_power_w);
            assert!(rel(f.peak_power_w, m) < 1e-4);
            let t = c.torque_n_m[i].iter().fold(0.0f64, |m, p| m.max(p.abs()));
            assert!(f.peak_torque_n_m >= t - 1e-12 * t);
        }
        // The peak's place: the curve there is the peak.
        let at = rep.peak_bus_power_at_deg;
        let c1 = curves(&fs, &bus, SPEED_RPM, 2).unwrap();
        assert_eq!(c1.angle_deg.len(), 2);
        assert!(at >= 0.0 && at < rep.repeat_deg);
    }
}

#[test]
fn rest_transitions_are_c2_for_rest_laws_and_refused_otherwise() {
    let plan = lift_plan(3, 8, 5);
    let omega = loomkin_units::rad_per_s_from_rpm(SPEED_RPM);
    for pass in [false, true] {
        let fs = setups(&plan, pass, &servo(1.0, 0.0, 0.0, 0.0), 0.0, &laws(LawSpec::Cycloidal));
        for spec in [LawSpec::Cycloidal, LawSpec::Poly345, LawSpec::Poly4567, LawSpec::ModifiedSine] {
            let l = laws(spec.clone());
            for f in &fs {
                let cyc: Cycle = f.plan.cycle(&l);
                let class = joint_class(&cyc, &l, omega);
                assert!(class.rest >= 2, "{spec:?}: rest class {}", class.rest);
            }
        }
        // The harmonic law starts and stops with a jump of acceleration: C1, refused.
        let l = laws(LawSpec::Harmonic);
        let cyc = fs[0].plan.cycle(&l);
        assert_eq!(joint_class(&cyc, &l, omega).rest, 1);
        let fs = setups(&plan, pass, &servo(1.0, 0.0, 0.0, 0.0), 0.0, &l);
        let e = analyse(&fs, &Bus::default(), SPEED_RPM, pass).unwrap_err().to_string();
        assert!(e.contains("C²") && e.contains("harmonic"), "{e}");
    }
}

#[test]
fn pass_through_lays_runs_end_to_end() {
    // Frame up on pick 1 only, then on picks 3 and 4, then a run 5-6-7 of changes.
    let up = [false, true, false, true, true, false, true, false];
    let p = FramePlan::new(
        &FrameInput { up: &up, stroke_m: 0.1, centre_deg: -20.0, motion_deg: 240.0, fall_motion_deg: 240.0 },
        true,
    )
    .unwrap();
    // Changes at picks 1, 2 (a run of 2), 3, 5, 6, 7 (a run of 3 with 3: picks 5, 6, 7; pick 3 is a run of 1 from pick 3? no: 2→3 also a change).
    let starts: Vec<f64> = p.moves.iter().map(|m| m.start_deg).collect();
    for w in p.moves.windows(2) {
        let end = w[0].start_deg + w[0].length_deg;
        assert!(w[1].start_deg >= end - 1e-9, "{starts:?}");
    }
    // Every run covers from its first change's start to its last change's end, equally split.
    let mut i = 0;
    while i < p.moves.len() {
        let mut j = i;
        while j + 1 < p.moves.len()
            && (p.moves[j + 1].start_deg - p.moves[j].start_deg - p.moves[j].length_deg).abs() < 1e-9
        {
            j += 1;
        }
        let k = (j - i) as f64;
        let first = p.moves[i].pick as f64;
        assert!((p.moves[i].start_deg - (360.0 * first - 20.0 - 120.0)).abs() < 1e-9);
        let end = p.moves[j].start_deg + p.moves[j].length_deg;
        assert!((end - (360.0 * (first + k) - 20.0 + 120.0)).abs() < 1e-9);
        for m in &p.moves[i..=j] {
            assert!((m.length_deg - (360.0 * k + 240.0) / (k + 1.0)).abs() < 1e-9);
        }
        i = j + 1;
    }
    // Without pass-through: one move per change, each 240°.
    let q = FramePlan::new(
        &FrameInput { up: &up, stroke_m: 0.1, centre_deg: -20.0, motion_deg: 240.0, fall_motion_deg: 240.0 },
        false,
    )
    .unwrap();
    assert_eq!(q.moves.len(), p.moves.len());
    assert!(q.moves.iter().all(|m| m.length_deg == 240.0));
    // A plain weave: every move a full turn, no dwell at all.
    let plain = [true, false, true, false];
    let p = FramePlan::new(
        &FrameInput { up: &plain, stroke_m: 0.1, centre_deg: 0.0, motion_deg: 200.0, fall_motion_deg: 200.0 },
        true,
    )
    .unwrap();
    assert!(p.moves.iter().all(|m| m.length_deg == 360.0));
    assert_eq!(p.segments().len(), 4);
}

#[test]
fn a_law_not_c2_where_the_frame_rests_is_refused_naming_its_field() {
    let plan = lift_plan(3, 8, 5);
    let s = servo(1.0, 0.0, 0.0, 0.0);
    let harmonic_a0 = std::f64::consts::PI.powi(2) / 2.0;
    assert!((LawSpec::Harmonic.build().unwrap().eval(0.0).a - harmonic_a0).abs() < 1e-9);
    for pass in [false, true] {
        // Up by the harmonic law (acceleration π²/2 at both ends), down by the cycloid.
        let mut l = mixed(LawSpec::Harmonic, LawSpec::Cycloidal, LawSpec::Cycloidal);
        l.through = None;
        let e = analyse(&setups(&plan, pass, &s, 0.0, &l), &Bus::default(), SPEED_RPM, pass).unwrap_err().to_string();
        assert!(e.starts_with("servo.rise_law: harmonic has acceleration "), "{e}");
        assert!(e.contains(&loomkin_units::sig4(harmonic_a0)) && e.contains("C²"), "{e}");
        // Down by the harmonic law: its end (−π²/2) or its start.
        let mut l = mixed(LawSpec::Cycloidal, LawSpec::Harmonic, LawSpec::Cycloidal);
        l.through = None;
        let e = analyse(&setups(&plan, pass, &s, 0.0, &l), &Bus::default(), SPEED_RPM, pass).unwrap_err().to_string();
        assert!(e.starts_with("servo.fall_law: harmonic has acceleration "), "{e}");
    }
    // The harmonic law for the moves laid end to end: a run that starts from a dwell starts by it.
    let l = mixed(LawSpec::Cycloidal, LawSpec::Cycloidal, LawSpec::Harmonic);
    let e = analyse(&setups(&plan, true, &s, 0.0, &l), &Bus::default(), SPEED_RPM, true).unwrap_err().to_string();
    assert!(e.starts_with("servo.through_law: harmonic has acceleration "), "{e}");
    // Without pass-through no move is laid end to end: the through law is never used.
    let r = analyse(&setups(&plan, false, &s, 0.0, &l), &Bus::default(), SPEED_RPM, false).unwrap();
    assert!(r.frames.iter().all(|f| f.rest_continuity >= 2));
}

#[test]
fn a_pass_through_joint_matches_acceleration_across_it() {
    // A plain weave on every frame with pass-through: the frames oscillate without a stop, every
    // joint a pass-through joint.
    let plain: Vec<Vec<bool>> = (0..2).map(|i| (0..6).map(|p| (p + i) % 2 == 0).collect()).collect();
    let s = servo(1.0, 0.0, 0.0, 0.0);
    let omega = loomkin_units::rad_per_s_from_rpm(SPEED_RPM);
    // Harmonic both ways (through): the acceleration −π²/2·H/L² at the end of a move up is the
    // start of the move down — a cosine oscillation, C² (and C³) everywhere.
    let l = mixed(LawSpec::Cycloidal, LawSpec::Cycloidal, LawSpec::Harmonic);
    let fs = setups(&plain, true, &s, 0.0, &l);
    for f in &fs {
        assert!(f.plan.moves.iter().all(|m| m.through && m.length_deg == 360.0));
        let c = f.plan.cycle(&l);
        assert!(joint_class(&c, &l, omega).rest >= 2);
        // The accelerations either side of every joint, in time, agree to rounding.
        for w in c.segments.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            let r = omega / a.length_rad;
            let end = a.stroke_si * a.law.as_ref().unwrap().1.eval(1.0).a * r * r;
            let start = b.stroke_si * b.law.as_ref().unwrap().1.eval(0.0).a * r * r;
            assert!((end - start).abs() <= 1e-9 * end.abs(), "{end} vs {start}");
        }
    }
    let r = analyse(&fs, &Bus::default(), SPEED_RPM, true).unwrap();
    assert!(r.frames.iter().all(|f| f.rest_continuity >= 2));
    // Harmonic up, cycloid down, no law of their own for the moves laid end to end: the move up
    // ends with acceleration −π²/2·H/L², the move down starts with 0: refused at the joint.
    let mut l = mixed(LawSpec::Harmonic, LawSpec::Cycloidal, LawSpec::Cycloidal);
    l.through = None;
    let e = analyse(&setups(&plain, true, &s, 0.0, &l), &Bus::default(), SPEED_RPM, true).unwrap_err().to_string();
    assert!(e.contains("a pass-through joint must match velocity and acceleration"), "{e}");
    assert!(
        e.starts_with("servo.fall_law: cycloidal starts") || e.starts_with("servo.rise_law: harmonic starts"),
        "{e}"
    );
}

#[test]
fn moves_up_and_down_take_their_own_motion_angles() {
    // Single moves into picks 1 (up) and 4 (down), a run of two into picks 6 and 7.
    let up = [false, true, true, true, false, false, true, false, false, false];
    let (c, phi_r, phi_f) = (-20.0, 220.0, 300.0);
    let input = FrameInput { up: &up, stroke_m: 0.1, centre_deg: c, motion_deg: phi_r, fall_motion_deg: phi_f };
    // Without pass-through: every move centred on its pick's centre, up by φ_r, down by φ_f.
    let q = FramePlan::new(&input, false).unwrap();
    assert_eq!(q.motion_deg, [phi_r, phi_f]);
    for m in &q.moves {
        let phi = if m.rising { phi_r } else { phi_f };
        assert_eq!(m.length_deg, phi);
        assert!((m.start_deg + phi / 2.0 - (360.0 * m.pick as f64 + c)).abs() < 1e-12);
        assert!(!m.through);
    }
    // With pass-through: a run goes from its first move's start (by that move's angle) to its last
    // move's end (by its own), split equally; only the moves of a run of two or more are through.
    let p = FramePlan::new(&input, true).unwrap();
    let mut i = 0;
    while i < p.moves.len() {
        let mut j = i;
        while j + 1 < p.moves.len() && p.moves[j + 1].pick == (p.moves[j].pick + 1) % up.len() {
            j += 1;
        }
        let (first, last) = (&p.moves[i], &p.moves[j]);
        let phi = |m: &loomkin_eshed::PlannedMove| if m.rising { phi_r } else { phi_f };
        let k = (j - i) as f64;
        assert!((first.start_deg - (360.0 * first.pick as f64 + c - phi(first) / 2.0)).abs() < 1e-9);
        let end = last.start_deg + last.length_deg;
        assert!((end - (360.0 * (first.pick as f64 + k) + c + phi(last) / 2.0)).abs() < 1e-9);
        for m in &p.moves[i..=j] {
            assert!((m.length_deg - (end - first.start_deg) / (k + 1.0)).abs() < 1e-9);
            assert_eq!(m.through, j > i);
        }
        i = j + 1;
    }
    assert!(p.moves.iter().any(|m| m.through) && p.moves.iter().any(|m| !m.through));
    // An angle out of (0, 360] is refused by name.
    let bad = FrameInput { fall_motion_deg: 361.0, ..input };
    assert!(FramePlan::new(&bad, false).unwrap_err().to_string().starts_with("fall_motion_deg: 361°"));
}

/// The drive points remembered across calls (what the optimiser's search does) give the scan's
/// peak bit for bit as without: over a sequence of staggers and motion angles (the memo's blocks
/// met again, in part), over a few picks, after a change of the drive (the memo starts afresh),
/// after a change of the laws (its pick windows are dropped), and with a memo so small that a
/// frame's blocks outgrow a generation within one call.
#[test]
fn remembered_drive_points_give_the_same_scan_bit_for_bit() {
    let plan = lift_plan(4, 24, 11);
    let l = laws(LawSpec::ModifiedSine);
    for crank in CRANK {
        let mut memo = DriveMemo::default();
        for (k, &(stagger, friction)) in
            [(0.0, 0.0), (3.0, 0.0), (0.0, 0.0), (-2.0, 0.0), (-2.0, 6.0), (3.0, 6.0), (0.0, 0.0)].iter().enumerate()
        {
            let s = servo_by(0.93, friction, 15.0, 1.5, crank.then(common::crank_lever));
            let fs = setups(&plan, k % 2 == 1, &s, stagger, &l);
            let bus = Bus::default();
            let want = peak_bus_power_w(&fs, &bus, SPEED_RPM, true).unwrap();
            let got = peak_bus_power_w_memo(&fs, &bus, SPEED_RPM, None, &mut memo).unwrap();
            assert_eq!(got.to_bits(), want.to_bits(), "crank {crank}, step {k}: {got} vs {want}");
            let picks = [1, 5, 6, 17];
            let want = peak_bus_power_w_at(&fs, &bus, SPEED_RPM, &picks).unwrap();
            let got = peak_bus_power_w_memo(&fs, &bus, SPEED_RPM, Some(&picks), &mut memo).unwrap();
            assert_eq!(got.to_bits(), want.to_bits(), "crank {crank}, step {k}, picks: {got} vs {want}");
        }
    }
    // The same frames by other laws, the same memo: its windows are not taken for theirs.
    let mut memo = DriveMemo::default();
    for spec in [LawSpec::Cycloidal, LawSpec::Poly345, LawSpec::Poly4567, LawSpec::Cycloidal] {
        let fs = setups(&plan, true, &servo_by(0.93, 0.0, 15.0, 1.5, None), 2.0, &laws(spec.clone()));
        let want = peak_bus_power_w(&fs, &Bus::default(), SPEED_RPM, true).unwrap();
        let got = peak_bus_power_w_memo(&fs, &Bus::default(), SPEED_RPM, None, &mut memo).unwrap();
        assert_eq!(got.to_bits(), want.to_bits(), "{spec:?}: {got} vs {want}");
    }
    // A memo of 3 blocks a frame: the blocks outgrow a generation within each call.
    let fs = setups(&plan, false, &servo_by(0.93, 0.0, 15.0, 1.5, Some(common::crank_lever())), 1.0, &l);
    let mut memo = DriveMemo::with_blocks(12);
    let want = peak_bus_power_w(&fs, &Bus::default(), SPEED_RPM, true).unwrap();
    for _ in 0..2 {
        let got = peak_bus_power_w_memo(&fs, &Bus::default(), SPEED_RPM, None, &mut memo).unwrap();
        assert_eq!(got.to_bits(), want.to_bits());
    }
    // Bad picks are refused as without the memo.
    assert!(peak_bus_power_w_memo(&fs, &Bus::default(), SPEED_RPM, Some(&[3, 2]), &mut memo).is_err());
}
