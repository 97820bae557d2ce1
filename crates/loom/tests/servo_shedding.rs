//! The loom file's `[shedding] drive = "servo"`: the plans against the dobby's motion, the table's
//! errors, and the study on the example.

use loomkin_loom::{
    Loom, Motion, Objective, Pattern, ServoMotion, ServoOptions, ShedMotion, Timing, check, optimise_servo,
    optimise_servo_with, reduced_pattern, servo_laws, servo_setups, servo_study, servo_timing,
};

const SERVO: &str = include_str!("../../../examples/servo-shedding-loom.toml");
const CRANK: &str = include_str!("../../../examples/servo-shedding-crank-loom.toml");
const RAPIER: &str = include_str!("../../../examples/rapier-loom.toml");
const POINT: &str = include_str!("../../../examples/point-24.wif");

#[test]
fn without_pass_through_every_frames_plan_is_the_dobby_motion() {
    let loom = Loom::from_toml(SERVO).unwrap();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let motion = Motion::new(&loom, &pattern).unwrap();
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    let laws = servo_laws(&loom);
    for (i, s) in setups.iter().enumerate() {
        // Segment for segment; the stroke the same to its 12 digits (the plan's drops the noise of
        // the loom's way through metres, 89.99999999999999 → 90 mm).
        // Without laws by kind of move in the file, every frame moves by the shedding law.
        assert!(s.laws.rise.0 == laws.rise.0 && s.laws.fall.0 == laws.fall.0 && s.laws.through.is_none());
        let (plan, dobby) = (s.plan.cycle_spec(&s.laws), motion.cycle_spec(i));
        assert_eq!(plan.segment, dobby.segment, "frame {}", i + 1);
        assert_eq!((plan.period_deg, plan.unit), (dobby.period_deg, dobby.unit));
        let (a, b) = (plan.stroke.unwrap(), dobby.stroke.unwrap());
        assert!(a == loomkin_units::to_12_digits(b) && (a - b).abs() <= 1e-14 * a, "frame {}: {a} {b}", i + 1);
        assert_eq!(s.plan.start_level_m(), motion.frame(i, s.plan.start_deg - 1e-6).y_m);
    }
}

#[test]
fn the_dobby_loom_reads_as_before_and_has_no_servo() {
    let loom = Loom::from_toml(RAPIER).unwrap();
    assert!(loom.shedding.servo.is_none());
    let pattern = Pattern::from_wif(POINT).unwrap();
    let e = servo_study(&loom, &pattern).unwrap_err().to_string();
    assert!(e.starts_with("shedding.drive:"), "{e}");
}

#[test]
fn the_servo_table_is_checked_field_by_field() {
    let cases = [
        (
            SERVO.replace("drive = \"servo\"", "drive = \"cam\""),
            "shedding.drive: \"cam\": allowed \"dobby\" or \"servo\"",
        ),
        (SERVO.replace("drive = \"servo\"", ""), "shedding.servo: only with drive = \"servo\""),
        (
            SERVO.replace("peak_torque_nm = 30", "peak_torque_nm = 3"),
            "shedding.servo.motor.peak_torque_nm = 3 is out of range",
        ),
        (
            SERVO.replace("travel_mm_per_rev = 100", "travel_mm_per_rev = 0"),
            "shedding.servo.transmission.travel_mm_per_rev = 0 is out of range",
        ),
        (SERVO.replace("voltage_v = 560", "voltage_v = 0"), "shedding.servo.bus.voltage_v = 0 is out of range"),
        (
            SERVO.replace("regeneration_efficiency = 0.9", "regeneration_efficiency = 1.5"),
            "shedding.servo.bus.regeneration_efficiency = 1.5 is out of range",
        ),
        (
            SERVO.replace("[shedding.servo.bus]", "[[shedding.servo.frame]]\nframes = [25]\n[shedding.servo.bus]"),
            "shedding.servo.frame[0].frames: frame 25: frames are numbered 1 to 24 from the front",
        ),
    ];
    for (text, want) in cases {
        let e = Loom::from_toml(&text).unwrap_err().to_string();
        assert!(e.starts_with(want), "{e}\nwanted: {want}");
    }
    // A frame's own motor and motion angle.
    let text = SERVO.replace(
        "[shedding.servo.bus]",
        "[[shedding.servo.frame]]\nframes = [1, 2]\nmotion_deg = 250\nmotor = { rated_torque_nm = 8, peak_torque_nm = 24, rated_speed_rpm = 3000, max_speed_rpm = 4500, rotor_inertia_kg_m2 = 8e-4 }\n[shedding.servo.bus]",
    );
    let loom = Loom::from_toml(&text).unwrap();
    let s = loom.shedding.servo.as_ref().unwrap();
    assert_eq!(s.frames[0].motor.rated_torque_nm, 8.0);
    assert_eq!(s.frames[1].motion_deg, Some(250.0));
    assert_eq!(s.frames[2].motor.rated_torque_nm, 10.0);
    let pattern = Pattern::from_wif(POINT).unwrap();
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    assert_eq!(setups[0].plan.moves[0].length_deg, 250.0);
    assert_eq!(setups[2].plan.moves[0].length_deg, 280.0);
}

#[test]
fn the_example_study_balances_and_every_motor_passes() {
    let loom = Loom::from_toml(SERVO).unwrap();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let r = servo_study(&loom, &pattern).unwrap();
    assert_eq!(r.frames.len(), 24);
    assert!(r.motors_ok);
    assert!(r.frames.iter().all(|f| f.rest_continuity >= 2));
    // What the supply gives and the resistor takes differ by what the frames draw, less what the
    // regeneration efficiency loses of the energy the frames return.
    let drawn: f64 = r.frames.iter().map(|f| f.energy_j).sum();
    let lost_in_regeneration = r.regenerated_energy_j / 0.9 * (1.0 - 0.9);
    let balance = r.supplied_energy_j - r.braking_energy_j - drawn - lost_in_regeneration;
    assert!(balance.abs() < 1e-9 * r.supplied_energy_j, "{balance}");
    assert!(r.peak_bus_power_w > 0.0 && r.peak_bus_power_w < r.frames.iter().map(|f| f.peak_power_w).sum::<f64>());
}

/// The servo example with consecutive changes laid end to end.
fn pass_through() -> Loom {
    Loom::from_toml(&SERVO.replace("pass_through = false", "pass_through = true")).unwrap()
}

#[test]
fn the_clear_shed_over_plans_equal_to_the_dobby_motion_is_loom_checks() {
    // Without pass-through every frame's plan is the dobby's motion (test above): the window and
    // the clearance over the plans are `loom check`'s, found by the same timing on a second
    // evaluation of the same heights (the law core's cycle against the dobby's closed form).
    let loom = Loom::from_toml(SERVO).unwrap();
    for wif in [POINT, include_str!("../../../examples/satin-8.wif"), include_str!("../../../examples/plain.wif")] {
        let pattern = Pattern::from_wif(wif).unwrap();
        let setups = servo_setups(&loom, &pattern, None, None).unwrap();
        let servo = servo_timing(&loom, &pattern, &setups).unwrap();
        let check = check(&loom, &pattern).unwrap();
        assert!((servo.window_deg - check.window_deg).abs() < 1e-9, "{} {}", servo.window_deg, check.window_deg);
        assert!((servo.open_deg - check.window_open_deg).abs() < 1e-9);
        assert!((servo.close_deg - check.window_close_deg).abs() < 1e-9);
        assert!((servo.min_clearance_mm - check.min_clearance_mm).abs() < 1e-9);
        assert!((servo.max_speed_rpm - check.max_speed_rpm).abs() < 1e-9 * check.max_speed_rpm);
        // And the study reports them.
        let r = servo_study(&loom, &pattern).unwrap();
        let c = r.clear_shed.unwrap();
        assert_eq!((c.window_deg, c.min_clearance_mm), (servo.window_deg, servo.min_clearance_mm));
    }
}

#[test]
fn every_pick_of_a_pass_through_plan_has_the_window_its_class_reports() {
    // The timing works out one pick of each class of equal turns: against every pick worked out
    // on its own, for plans with moves laid end to end (runs of different lengths).
    let loom = pass_through();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    let motion = ServoMotion::new(&setups);
    let timing = Timing::new(&loom, &motion, &pattern).unwrap();
    let report = timing.report().unwrap();
    assert_eq!(report.picks.len(), pattern.picks());
    for (p, w) in report.picks.iter().enumerate() {
        let own = timing.pick_window(p);
        assert!((own.open_deg - w.open_deg).abs() < 1e-9, "pick {}: {} {}", p + 1, own.open_deg, w.open_deg);
        assert!((own.close_deg - w.close_deg).abs() < 1e-9, "pick {}", p + 1);
        assert!((own.min_clearance_mm - w.min_clearance_mm).abs() < 1e-9, "pick {}", p + 1);
    }
}

/// The servo frames' heights without [`ShedMotion::frame_rest_m`]: the timing then evaluates
/// every frame at every angle.
struct EveryFrame<'a>(&'a ServoMotion);

impl ShedMotion for EveryFrame<'_> {
    fn frame_count(&self) -> usize {
        self.0.frame_count()
    }
    fn picks(&self) -> usize {
        self.0.picks()
    }
    fn frame_y_m(&self, i: usize, theta_deg: f64) -> f64 {
        self.0.frame_y_m(i, theta_deg)
    }
    fn turn_key(&self, pick: usize, from_deg: f64, to_deg: f64, key: &mut Vec<u64>) {
        self.0.turn_key(pick, from_deg, to_deg, key);
    }
}

#[test]
fn the_timing_over_resting_frames_is_the_timing_of_every_frame_bit_for_bit() {
    // The frames resting over a pick's span are added to its sheets once; every pick's window,
    // clearance and clear height are those of evaluating every frame at every angle, bit for
    // bit, with and without pass-through, on drafts whose frames rest, move and run.
    let drafts = [POINT, include_str!("../../../examples/plain.wif"), include_str!("../../../examples/satin-8.wif")];
    let mut resting = 0;
    for loom in [Loom::from_toml(SERVO).unwrap(), pass_through()] {
        for wif in drafts {
            let pattern = Pattern::from_wif(wif).unwrap();
            let setups = servo_setups(&loom, &pattern, None, None).unwrap();
            let motion = ServoMotion::new(&setups);
            let every = EveryFrame(&motion);
            let (fast, plain) =
                (Timing::new(&loom, &motion, &pattern).unwrap(), Timing::new(&loom, &every, &pattern).unwrap());
            let (a, b) = (fast.report().unwrap(), plain.report().unwrap());
            assert_eq!(a.picks, b.picks);
            let bits = |r: &loomkin_loom::TimingReport| {
                [r.open_deg, r.close_deg, r.window_deg, r.min_clearance_mm, r.max_speed_rpm, r.max_clear_mm]
                    .map(f64::to_bits)
            };
            assert_eq!(bits(&a), bits(&b));
            // Frames resting over a pick's insertion (the test is not vacuous).
            let ins = &loom.insertion;
            resting += (0..pattern.picks())
                .flat_map(|p| (0..loom.frame_count()).map(move |i| (p, i)))
                .filter(|&(p, i)| {
                    let o = 360.0 * p as f64;
                    motion.frame_rest_m(i, o + ins.entry_deg, o + ins.exit_deg).is_some()
                })
                .count();
        }
    }
    assert!(resting > 100, "{resting}");
}

#[test]
fn the_least_clearance_over_pass_through_plans_bounds_a_dense_scan() {
    // An independent route: the clearance on a 0.01° scan of every pick's insertion, from the
    // frames' heights on the exact cycles and the shed geometry. The timing's least clearance
    // (a 1° grid refined by golden-section search) is no larger than the scan's, and within
    // what the scan can miss between its points (|y''| h²/8 ≪ 1e-6 mm).
    let loom = pass_through();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    let motion = ServoMotion::new(&setups);
    let t = servo_timing(&loom, &pattern, &setups).unwrap();
    let ins = &loom.insertion;
    let x_c = loom.geometry.reed_m - ins.carrier_width_m;
    let mut scan = f64::INFINITY;
    for p in 0..pattern.picks() {
        let upper: Vec<bool> = (0..loom.frame_count()).map(|i| pattern.is_up(p, i)).collect();
        let n = ((ins.exit_deg - ins.entry_deg) / 0.01).round() as usize;
        for k in 0..=n {
            let th = 360.0 * p as f64 + ins.entry_deg + (ins.exit_deg - ins.entry_deg) * k as f64 / n as f64;
            let y: Vec<f64> = (0..loom.frame_count()).map(|i| motion.frame_y_m(i, th)).collect();
            let gap = loom.geometry.clear_height(x_c, &y, &upper).unwrap() - ins.carrier_height_m;
            scan = scan.min(gap * 1e3);
        }
    }
    assert!(t.min_clearance_mm <= scan + 1e-9, "{} {}", t.min_clearance_mm, scan);
    assert!(scan - t.min_clearance_mm < 1e-6, "{} {}", t.min_clearance_mm, scan);
    // Pass-through moves are longer than the motion angle: on a plain weave (every frame changes
    // every pick, oscillating without a stop) the shed is open for less of the turn than the
    // dobby's, whose frames dwell between moves.
    let plain = Pattern::from_wif(include_str!("../../../examples/plain.wif")).unwrap();
    let setups = servo_setups(&loom, &plain, None, None).unwrap();
    let servo = servo_timing(&loom, &plain, &setups).unwrap();
    let dobby = check(&loom, &plain).unwrap();
    assert!(servo.window_deg < dobby.window_deg - 1.0, "{} {}", servo.window_deg, dobby.window_deg);
    assert!(servo.min_clearance_mm < dobby.min_clearance_mm, "{} {}", servo.min_clearance_mm, dobby.min_clearance_mm);
}

#[test]
fn the_optimum_lowers_its_objective_and_keeps_the_carriers_insertion_clear() {
    let loom = Loom::from_toml(SERVO).unwrap();
    let pattern = Pattern::from_wif(include_str!("../../../examples/twill-2-2.wif")).unwrap();
    let before = servo_study(&loom, &pattern).unwrap();
    for objective in [Objective::Peak, Objective::Rms] {
        let o = optimise_servo(&loom, &pattern, objective, &Default::default(), &|_, _| {}).unwrap();
        // The before keys are the loom file's design, worked out by the study.
        assert_eq!(o.peak_bus_power_w_before, before.peak_bus_power_w);
        let c = before.clear_shed.unwrap();
        assert_eq!((o.window_deg_before, o.min_clearance_mm_before), (c.window_deg, c.min_clearance_mm));
        // The report is the study of the plans the optimum names: each frame's moves at its motion
        // angle, centred on the crossing plus its stagger, within the bounds.
        let m = loom.shedding.max_stagger_deg;
        let delta = loomkin_loom::crossing_offset_deg(loom.shedding.crossing_deg);
        for (i, s) in o.setups.iter().enumerate() {
            assert!(o.stagger_deg[i].abs() <= m && o.motion_deg[i] > 0.0 && o.motion_deg[i] <= 360.0);
            for mv in &s.plan.moves {
                assert_eq!(mv.length_deg, o.motion_deg[i]);
                let centre = mv.start_deg + mv.length_deg / 2.0 - 360.0 * mv.pick as f64;
                assert!((centre - (delta + o.stagger_deg[i])).abs() < 1e-9, "frame {}", i + 1);
            }
        }
        let servo = loom.shedding.servo.as_ref().unwrap();
        let again = loomkin_eshed::analyse(&o.setups, &servo.bus, loom.speed.rpm(), false).unwrap();
        assert_eq!(again.peak_bus_power_w, o.peak_bus_power_w_after);
        assert_eq!(o.report.peak_bus_power_w, o.peak_bus_power_w_after);
        // It gains what it minimises.
        match objective {
            Objective::Peak => assert!(o.peak_bus_power_w_after < 0.9 * o.peak_bus_power_w_before, "{o:?}"),
            Objective::Rms => {
                assert!(o.worst_rms_torque_n_m_after < o.worst_rms_torque_n_m_before, "{o:?}");
                let worst = again.frames.iter().map(|f| f.rms_torque_n_m).fold(0.0, f64::max);
                assert_eq!(worst, o.worst_rms_torque_n_m_after);
            }
        }
        // The carrier's insertion stays clear: on the search's grid (what it kept), and on the
        // refined clearance (the grid's 2° can only miss a dip between its points).
        let motion = ServoMotion::new(&o.setups);
        let coarse = Timing::new(&loom, &motion, &pattern).unwrap().min_clearance_coarse(2.0);
        assert!(coarse >= 0.0, "{coarse}");
        assert!(o.min_clearance_mm_after >= 0.0 && o.min_clearance_mm_after <= 1e3 * coarse + 1e-9, "{o:?}");
        assert_eq!(o.min_clearance_kept_mm, 0.0);
    }
}

#[test]
fn the_tables_carry_the_loom_files_strokes_in_mm_without_noise() {
    // The front frame's 90 mm reaches the plan through metres and the clean-lift ratio as
    // 89.99999999999999 mm; the manifest and the cycle files give 90, and every frame's stroke is
    // within 1e-14 of the loom's (that the cycle file is the plan's cycle, segment by segment, is
    // crates/eshed/tests/tables.rs's test).
    let loom = Loom::from_toml(SERVO).unwrap();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let spacing = loomkin_cams::table::Spacing::of(Some(30.0), None);
    let t = loomkin_loom::servo_tables(&loom, &pattern, spacing, &[loomkin_cams::table::Format::Csv]).unwrap();
    assert_eq!(loom.geometry.stroke_m[0] * 1e3, 89.99999999999999);
    assert_eq!(t.manifest.frames[0].stroke_mm, 90.0);
    let cycle = t.files.iter().find(|f| f.name == "frame-01.cycle.toml").unwrap();
    assert!(cycle.text.contains("stroke = 90.0\n"), "{}", cycle.text);
    for (f, m) in t.manifest.frames.iter().zip(&loom.geometry.stroke_m) {
        assert!((f.stroke_mm - m * 1e3).abs() <= 1e-14 * f.stroke_mm, "frame {}", f.frame);
        assert_eq!(f.stroke_mm, loomkin_units::to_12_digits(f.stroke_mm));
    }
}

/// A draft of `len` picks on `shafts` shafts from a fixed LCG, tiled to `picks` picks (runs of
/// consecutive changes of several lengths, no frame changing on every pick).
fn tiled(shafts: usize, len: usize, picks: usize, seed: u64) -> Pattern {
    let mut x = seed;
    let mut draft: Vec<Vec<bool>> = (0..len)
        .map(|_| {
            (0..shafts)
                .map(|_| {
                    x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    x >> 63 == 1
                })
                .collect()
        })
        .collect();
    // Two picks running alike: no shaft changes on every pick.
    draft[1] = draft[0].clone();
    Pattern::new(shafts, (0..picks).map(|p| draft[p % len].clone()).collect()).unwrap()
}

#[test]
fn the_reduced_pattern_gives_the_search_the_whole_repeats_objective_and_clearance() {
    // The search evaluates one pick for every class of picks whose neighbourhoods of lifts agree,
    // on a short pattern of those neighbourhoods. Against the whole repeat, for staggers and
    // motion angles anywhere in the search's box: the scan's peak bus power and the clearance on
    // the 2° grid agree to rounding, with and without pass-through (runs of several lengths); so
    // does every frame's RMS torque, its classes' cells weighted by their picks (1e-12), with a
    // law and an angle per kind of move and with the crank and lever.
    let servo = loom_servo();
    let twill = Pattern::new(24, (0..300).map(|p| (0..24).map(|i| (p + i) % 24 < 12).collect()).collect()).unwrap();
    let laws = Loom::from_toml(LAWS).unwrap();
    let cases = [
        (Loom::from_toml(SERVO).unwrap(), twill.clone()),
        (pass_through(), twill.clone()),
        (pass_through(), tiled(24, 10, 200, 7)),
        (laws.clone(), twill.clone()),
        (laws, tiled(24, 10, 200, 7)),
        (Loom::from_toml(CRANK).unwrap(), twill),
    ];
    for (loom, pattern) in &cases {
        let reduced = reduced_pattern(loom, pattern).unwrap();
        assert!(!reduced.whole && reduced.pattern.picks() < pattern.picks(), "{} rows", reduced.pattern.picks());
        assert_eq!(reduced.counts.len(), reduced.picks.len());
        assert_eq!(reduced.counts.iter().sum::<usize>(), pattern.picks());
        let speed = loom.speed.rpm();
        let n = loom.frame_count();
        let delta = loomkin_loom::crossing_offset_deg(loom.shedding.crossing_deg);
        let m = loom.shedding.max_stagger_deg;
        let mut x = 99u64;
        let mut next = || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..4 {
            let centre: Vec<f64> = (0..n).map(|_| delta + m * (2.0 * next() - 1.0)).collect();
            // Within 1 … 360° both ways (the laws example's moves down are up to 300/260 longer).
            let phi: Vec<f64> = (0..n).map(|_| 120.0 + 180.0 * next()).collect();
            let full = servo_setups(loom, pattern, Some(&phi), Some(&centre)).unwrap();
            let short = servo_setups(loom, &reduced.pattern, Some(&phi), Some(&centre)).unwrap();
            let bus = &servo.bus;
            let a = loomkin_eshed::peak_bus_power_w(&full, bus, loom.speed.rpm(), true).unwrap();
            let b = loomkin_eshed::peak_bus_power_w_at(&short, bus, loom.speed.rpm(), &reduced.picks).unwrap();
            assert!((a - b).abs() <= 1e-9 * a, "{a} {b}");
            let (mf, ms) = (ServoMotion::new(&full), ServoMotion::new(&short));
            let ca = Timing::new(loom, &mf, pattern).unwrap().min_clearance_coarse(2.0);
            let cb = Timing::new(loom, &ms, &reduced.pattern).unwrap().min_clearance_coarse_at(2.0, &reduced.picks);
            assert!((ca - cb).abs() <= 1e-12, "{ca} {cb}");
            for i in 0..n {
                let whole = loomkin_eshed::worst_rms_torque_n_m(&full[i..=i], speed).unwrap();
                let cells = loomkin_eshed::worst_rms_torque_n_m_at(
                    &short[i..=i],
                    speed,
                    &reduced.picks,
                    &reduced.counts,
                    pattern.picks(),
                )
                .unwrap();
                assert!((whole - cells).abs() <= 1e-12 * whole, "frame {}: {whole} {cells}", i + 1);
            }
            let (a, b) = (
                loomkin_eshed::worst_rms_torque_n_m(&full, speed).unwrap(),
                loomkin_eshed::worst_rms_torque_n_m_at(&short, speed, &reduced.picks, &reduced.counts, pattern.picks())
                    .unwrap(),
            );
            assert!((a - b).abs() <= 1e-12 * a, "{a} {b}");
        }
    }
    // The cells' sums over every pick of a plan add up to its whole ∫T² dt, which is the servo
    // check's RMS torque over the repeat.
    let loom = pass_through();
    let pattern = tiled(24, 10, 60, 5);
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    let study = loomkin_eshed::Study::new(&setups, loom.speed.rpm()).unwrap();
    let every: Vec<usize> = (0..60).collect();
    for (i, f) in setups.iter().enumerate() {
        let (d, c) = (&study.drives[i], &study.cycles[i]);
        let t2 = loomkin_servo::torque_squared_by_segment(&d.axis, c, loom.speed.rpm()).unwrap();
        let cells: f64 = f.plan.cell_sums(&t2, &every).iter().sum();
        let whole: f64 = t2.iter().sum();
        assert!((cells - whole).abs() <= 1e-13 * whole, "frame {}: {cells} {whole}", i + 1);
        let rms = loomkin_servo::check_axis(&d.axis, c, loom.speed.rpm()).unwrap().rms_torque_nm;
        let repeat_s = c.period_rad / d.omega;
        assert!(((whole / repeat_s).sqrt() - rms).abs() <= 1e-13 * rms, "frame {}", i + 1);
    }
    // A frame changing on every pick with pass-through: one run around the repeat, no reduction.
    let plain = Pattern::new(24, (0..300).map(|p| (0..24).map(|i| (p + i) % 2 == 0).collect()).collect()).unwrap();
    assert!(reduced_pattern(&pass_through(), &plain).unwrap().whole);
}

/// The example's `[shedding.servo]`.
fn loom_servo() -> loomkin_eshed::ServoShedding {
    Loom::from_toml(SERVO).unwrap().shedding.servo.unwrap()
}

#[test]
fn the_search_leaves_still_frames_out_and_keeps_a_least_clearance() {
    // A 2/2 twill moves 4 of the 24 frames; the others keep the loom file's timing.
    let loom = Loom::from_toml(SERVO).unwrap();
    let pattern = Pattern::from_wif(include_str!("../../../examples/twill-2-2.wif")).unwrap();
    let free = optimise_servo(&loom, &pattern, Objective::Peak, &Default::default(), &|_, _| {}).unwrap();
    assert_eq!(free.frames_searched, 4);
    assert!(free.stagger_deg[4..].iter().all(|&s| s == 0.0) && free.motion_deg[4..].iter().all(|&m| m == 280.0));
    // Asking for more clearance than the free optimum keeps: the search keeps it on its grid.
    let want = free.min_clearance_mm_after + 2.0;
    let options = ServoOptions { objective: Objective::Peak, min_clearance_mm: want };
    let o = optimise_servo_with(&loom, &pattern, &options, &Default::default(), &|_, _| {}).unwrap();
    // What it keeps: the floor asked for, or the design's own clearance (on the grid) when less.
    let grid = |setups: &[loomkin_eshed::FrameSetup]| {
        let motion = ServoMotion::new(setups);
        1e3 * Timing::new(&loom, &motion, &pattern).unwrap().min_clearance_coarse(2.0)
    };
    let design = grid(&servo_setups(&loom, &pattern, None, None).unwrap());
    let kept = if want <= design { want } else { design };
    assert_eq!(o.min_clearance_kept_mm, kept);
    let coarse = grid(&o.setups);
    assert!(coarse >= kept - 1e-9, "{coarse} {kept}");
    assert!(
        o.min_clearance_mm_after > free.min_clearance_mm_after,
        "{} {}",
        o.min_clearance_mm_after,
        free.min_clearance_mm_after
    );
    assert!(o.peak_bus_power_w_after <= o.peak_bus_power_w_before);
    // Out of range: one line naming the field.
    let bad = ServoOptions { objective: Objective::Peak, min_clearance_mm: -1.0 };
    let e = optimise_servo_with(&loom, &pattern, &bad, &Default::default(), &|_, _| {}).unwrap_err().to_string();
    assert!(e.starts_with("min_clearance_mm = -1 is out of range"), "{e}");
}

/// The crank-and-lever example: read, studied, each frame's motor speed from the linkage (not the
/// linear drive's), and its table's errors named field by field.
#[test]
fn the_crank_lever_transmission_is_read_and_checked() {
    let loom = Loom::from_toml(CRANK).unwrap();
    let s = loom.shedding.servo.as_ref().unwrap();
    let cl = s.frames[0].transmission.crank_lever.unwrap();
    assert_eq!((cl.crank_radius_mm, cl.gear_ratio, cl.frame_link_mm), (45.0, 8.0, Some(500.0)));
    let pattern = Pattern::from_wif(POINT).unwrap();
    let study = servo_study(&loom, &pattern).unwrap();
    assert_eq!(study.frames.len(), 24);
    // The same frames through the linear drive of the same ratio at mid-stroke run at other speeds.
    let linear = servo_study(&Loom::from_toml(SERVO).unwrap(), &pattern).unwrap();
    assert!(study.frames.iter().zip(&linear.frames).all(|(a, b)| a.peak_speed_rpm != b.peak_speed_rpm));
    let block = |from: &str, to: &str| CRANK.replace(from, to);
    let cases = [
        (
            block("rod_length_mm = 200\n", ""),
            "shedding.servo: transmission: missing field `rod_length_mm` (kind = \"crank_lever\" needs",
        ),
        (
            block("kind = \"crank_lever\"", ""),
            "shedding.servo: transmission.crank_radius_mm: a key of a crank and lever: give kind = \"crank_lever\"",
        ),
        (
            block("efficiency = 0.95\n", "efficiency = 0.95\ntravel_mm_per_rev = 100\n"),
            "shedding.servo: transmission.travel_mm_per_rev: a key of a linear drive",
        ),
        (
            block("lever_output_arm_mm = 300", "lever_output_arm_mm = 0"),
            "shedding.servo.transmission.lever_output_arm_mm = 0 is out of range",
        ),
        (
            block("rod_length_mm = 200", "rod_length_mm = 50"),
            "shedding.servo.transmission.rod_length_mm: the crank cannot reach the lever with the frame at mid-stroke",
        ),
    ];
    for (text, want) in cases {
        let e = Loom::from_toml(&text).unwrap_err().to_string();
        assert!(e.starts_with(want), "{e}\nwanted: {want}");
    }
    // A crank too short for the back frames' strokes: refused by the study, naming the frame.
    let short = Loom::from_toml(&block("crank_radius_mm = 45", "crank_radius_mm = 30")).unwrap();
    let e = servo_study(&short, &pattern).unwrap_err().to_string();
    assert!(e.starts_with("shedding.servo.transmission.crank_radius_mm: frame "), "{e}");
    assert!(e.contains("the crank and lever move the frame only to "), "{e}");
}

const LAWS: &str = include_str!("../../../examples/servo-shedding-laws-loom.toml");

#[test]
fn the_loom_file_gives_a_law_and_a_motion_angle_per_kind_of_move() {
    let loom = Loom::from_toml(LAWS).unwrap();
    let pattern = Pattern::from_wif(POINT).unwrap();
    let setups = servo_setups(&loom, &pattern, None, None).unwrap();
    let spline = [[0.0, 0.0], [0.1, 0.55], [0.25, 1.0], [0.4, 0.55], [0.5, 0.0]];
    let servo_law = loomkin_servo::SplineLaw::new(&spline, loomkin_servo::SplineEnd::Clamped).unwrap();
    for (i, s) in setups.iter().enumerate() {
        let front = i < 2;
        let l = &s.laws;
        // The two front frames go up by the dobby preset over 280°; the others by the modified
        // trapezoid over 260°; every frame down by the 4-5-6-7 polynomial over 300°.
        assert_eq!(s.plan.motion_deg, [if front { 280.0 } else { 260.0 }, 300.0], "frame {}", i + 1);
        let rise = if front { "shedding.servo.frame[0].rise_law" } else { "shedding.servo.rise_law" };
        assert_eq!(l.fields, [rise, "shedding.servo.fall_law", "shedding.servo.through_law"]);
        if front {
            let dobby = loomkin_shed::preset("dobby").unwrap();
            assert_eq!(l.rise.0, loomkin_laws::LawSpec::Piecewise { segments: dobby.motion_segments().unwrap() });
        } else {
            assert_eq!(l.rise.0, loomkin_laws::LawSpec::ModifiedTrapezoid { ramp: 0.125 });
        }
        assert_eq!(l.fall.0, loomkin_laws::LawSpec::Poly4567);
        // The spline law through the definition points, as the servo law of `loomkin servo`
        // builds it (an independent route: its own cubic spline), to rounding.
        let (_, through) = l.through.as_ref().unwrap();
        for k in 0..=200 {
            let x = k as f64 / 200.0;
            let (a, b) = (through.eval(x), servo_law.law().eval(x));
            assert!((a.s - b.s).abs() < 1e-12 && (a.a - b.a).abs() < 1e-9 * b.a.abs().max(1.0), "x = {x}");
        }
        // Each move by its law and angle: a single move up or down, or laid end to end.
        for m in &s.plan.moves {
            if !m.through {
                assert_eq!(m.length_deg, s.plan.motion_deg[usize::from(!m.rising)]);
            }
        }
    }
    // The 3/1 twill changes on two picks running: those moves are laid end to end, by the spline.
    let twill = Pattern::from_lift_plan(include_str!("../../../examples/twill-3-1.txt")).unwrap();
    let laid = servo_setups(&loom, &twill, None, None).unwrap();
    assert!(laid.iter().any(|s| s.plan.moves.iter().any(|m| m.through)));
    let r = servo_study(&loom, &twill).unwrap();
    assert!(r.frames.iter().all(|f| f.rest_continuity >= 2));
    let r = servo_study(&loom, &pattern).unwrap();
    assert!(r.frames.iter().all(|f| f.rest_continuity >= 2));
    assert_eq!((r.frames[0].motion_deg, r.frames[0].fall_motion_deg), (280.0, Some(300.0)));
    assert_eq!((r.frames[5].motion_deg, r.frames[5].fall_motion_deg), (260.0, Some(300.0)));
    // Each kind's law and angle in words, in the loom file's form.
    assert_eq!(
        setups[0].laws.describe(setups[0].plan.motion_deg),
        "up by dobby preset over 280°, down by poly4567 over 300°, laid end to end by spline (5 points, clamped)"
    );
    assert_eq!(
        setups[5].laws.describe(setups[5].plan.motion_deg),
        "up by modified-trapezoid (ramp=0.125) over 260°, down by poly4567 over 300°, laid end to end by spline \
         (5 points, clamped)"
    );
    let one = servo_setups(&Loom::from_toml(SERVO).unwrap(), &pattern, None, None).unwrap();
    assert_eq!(one[0].laws.describe(one[0].plan.motion_deg), "up and down by dobby preset over 280°");
    // A law by name is the same law as the table naming it.
    let by_table = LAWS.replace("fall_law = \"poly4567\"", "fall_law = { law = \"poly4567\" }");
    let again = servo_study(&Loom::from_toml(&by_table).unwrap(), &pattern).unwrap();
    assert_eq!(again, r);
}

#[test]
fn a_law_not_c2_at_a_rest_transition_is_refused_naming_its_field() {
    let pattern = Pattern::from_wif(POINT).unwrap();
    let refused = |from: &str, to: &str| {
        let loom = Loom::from_toml(&LAWS.replace(from, to)).unwrap();
        servo_study(&loom, &pattern).unwrap_err().to_string()
    };
    let e = refused("fall_law = \"poly4567\"", "fall_law = \"harmonic\"");
    assert!(e.starts_with("shedding.servo.fall_law: harmonic has acceleration −4.935 at its end where frame 1"), "{e}");
    assert!(e.contains("a rest transition must be C²"), "{e}");
    let e = refused("rise_law = { preset = \"dobby\" }", "rise_law = \"constant-acceleration\"");
    assert!(
        e.starts_with("shedding.servo.frame[0].rise_law: constant-acceleration has acceleration 4 at its start"),
        "{e}"
    );
    // The shedding law where the file gives none for a kind: named as the [shedding] law.
    let harmonic = LAWS.replace("preset = \"dobby\"                 #", "law = \"harmonic\"                 #");
    let loom = Loom::from_toml(&harmonic.replace("fall_law = \"poly4567\"\n", "")).unwrap();
    let e = servo_study(&loom, &pattern).unwrap_err().to_string();
    assert!(e.starts_with("shedding: harmonic has acceleration"), "{e}");
    // Bad laws and angles are refused where the file is read, by field.
    for (from, to, field) in [
        ("fall_law = \"poly4567\"", "fall_law = \"nope\"", "shedding.servo.fall_law: unknown law 'nope'"),
        (
            "fall_law = \"poly4567\"",
            "fall_law = { law = \"poly4567\", preset = \"dobby\" }",
            "shedding.servo.fall_law: give one of",
        ),
        (
            "fall_law = \"poly4567\"",
            "fall_law = { spline = [[0, 0], [0.5, 1]] }",
            "shedding.servo.fall_law: def_points",
        ),
        (
            "fall_law = \"poly4567\"",
            "fall_law = { preset = \"dobby\", params = { ramp = 0.1 } }",
            "shedding.servo.fall_law: params only",
        ),
        ("fall_motion_deg = 300", "fall_motion_deg = 361", "shedding.servo.fall_motion_deg = 361 is out of range"),
        (
            "rise_motion_deg = 280",
            "rise_motion_deg = 0.5",
            "shedding.servo.frame[0].rise_motion_deg = 0.5 is out of range",
        ),
    ] {
        let text = LAWS.replace(from, to);
        assert_ne!(text, LAWS, "{from}");
        let e = Loom::from_toml(&text).unwrap_err().to_string();
        assert!(e.starts_with(field), "{e}");
    }
}

#[test]
fn the_search_varies_a_frames_angle_up_and_scales_its_angle_down_with_it() {
    let loom = Loom::from_toml(LAWS).unwrap();
    let pattern = Pattern::from_wif(include_str!("../../../examples/twill-2-2.wif")).unwrap();
    let o = optimise_servo(&loom, &pattern, Objective::Peak, &Default::default(), &|_, _| {}).unwrap();
    let fall = o.fall_motion_deg.as_ref().expect("the file gives the moves down their own angle");
    for (i, s) in o.setups.iter().enumerate() {
        let ratio = if i < 2 { 300.0 / 280.0 } else { 300.0 / 260.0 };
        // The angle down scaled with the angle up, kept to 12 significant digits (half a unit of
        // the twelfth digit at most: 5e-12 relative).
        let scaled = o.motion_deg[i] * ratio;
        assert_eq!(s.plan.motion_deg, [o.motion_deg[i], loomkin_units::to_12_digits(scaled)]);
        assert!((s.plan.motion_deg[1] - scaled).abs() <= 5e-12 * scaled, "frame {}", i + 1);
        assert_eq!(fall[i], s.plan.motion_deg[1]);
        assert!(o.motion_deg[i] >= 1.0 && fall[i] <= 360.0, "frame {}: {} {}", i + 1, o.motion_deg[i], fall[i]);
    }
    // 312° up scales to 360° down (312 × 300/260 is 359.99999999999994 in floating point): the
    // plan moves by 360, the number the report prints.
    let at_312 = servo_setups(&loom, &pattern, Some(&[312.0; 24]), None).unwrap();
    assert_eq!(at_312[3].plan.motion_deg, [312.0, 360.0]);
    // The optimum's angles typed back into the loom file (as the report prints them) give its
    // plans bit for bit: frame 4's (the [shedding.servo] angles of frames 3–24).
    let typed = LAWS
        .replace("rise_motion_deg = 260", &format!("rise_motion_deg = {}", o.motion_deg[3]))
        .replace("fall_motion_deg = 300", &format!("fall_motion_deg = {}", fall[3]));
    let again = servo_setups(&Loom::from_toml(&typed).unwrap(), &pattern, None, None).unwrap();
    let searched = servo_setups(&loom, &pattern, Some(&o.motion_deg), None).unwrap();
    assert_eq!(again[3].plan, searched[3].plan);
    assert!(o.peak_bus_power_w_after <= o.peak_bus_power_w_before);
    assert_eq!(fall.len(), 24);
    // One angle both ways (the example): none of its own.
    let one =
        optimise_servo(&Loom::from_toml(SERVO).unwrap(), &pattern, Objective::Peak, &Default::default(), &|_, _| {})
            .unwrap();
    assert!(one.fall_motion_deg.is_none());
}

/// Two windows alike in everything but the law of one frame's move are not taken for one another:
/// a frame's plain move up (cycloidal) and its move up laid end to end (3-4-5), both 360° long from
/// the same level, each followed by a dwell at the top. The bus's net energy over the repeat
/// (supplied less braked) equals the integral of its sampled power (Simpson's rule on 2·10⁵
/// points), and its peak is ≥ every sample.
#[test]
fn windows_alike_but_for_a_moves_law_are_told_apart() {
    let text = include_str!("../../../examples/servo-shedding-laws-loom.toml")
        .replace(r#"rise_law = { law = "modified-trapezoid", params = { ramp = 0.125 } }"#, r#"rise_law = "cycloidal""#)
        .replace(r#"fall_law = "poly4567""#, r#"fall_law = "cycloidal""#)
        .replace(
            r#"through_law = { spline = [[0, 0], [0.1, 0.55], [0.25, 1], [0.4, 0.55], [0.5, 0]], end = "clamped" }"#,
            r#"through_law = "poly345""#,
        )
        .replace("rise_motion_deg = 260", "rise_motion_deg = 360")
        .replace("fall_motion_deg = 300", "fall_motion_deg = 360")
        .replace("frames = 24", "frames = 2")
        .replace("[[shedding.servo.frame]]", "")
        .replace("frames = [1, 2]\nrise_law = { preset = \"dobby\" }\nrise_motion_deg = 280\n", "");
    let loom = Loom::from_toml(&text).unwrap();
    assert!(loom.shedding.servo.as_ref().unwrap().pass_through);
    // Two frames. The front one: a plain move up into pick 2, a run of two changes into picks 6
    // and 7 (down, then up laid end to end), each move up followed by a dwell at the top of 1080°;
    // the back one the other way. The turns of picks 2 and 7 differ only by the laws of the moves.
    let lifts = [0, 0, 1, 1, 1, 1, 0, 1, 1, 1, 1, 0, 0, 0, 0, 0];
    let rows: Vec<Vec<bool>> = lifts.iter().map(|&u| vec![u == 1, u == 0]).collect();
    let pattern = Pattern::new(2, rows).unwrap();
    let report = loomkin_loom::servo_study(&loom, &pattern).unwrap();
    let n = 200_001;
    let curves = loomkin_loom::servo_curves(&loom, &pattern, n).unwrap();
    let p = &curves.bus_power_w;
    let h = report.repeat_s / (n - 1) as f64;
    let simpson: f64 = (0..(n - 1) / 2).map(|k| h / 3.0 * (p[2 * k] + 4.0 * p[2 * k + 1] + p[2 * k + 2])).sum();
    // The bus's net energy: what the supply gives less what the resistor takes.
    let net = report.supplied_energy_j - report.braking_energy_j;
    assert!(
        (simpson - net).abs() <= 1e-6 * report.supplied_energy_j,
        "net bus energy {net} J from the study, {simpson} J from the samples"
    );
    let top = p.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!(report.peak_bus_power_w >= top * (1.0 - 1e-12), "{} < {top}", report.peak_bus_power_w);
}
