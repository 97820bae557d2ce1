//! The controllers' cam tables (`--emit-tables`) against independent routes: each file read back
//! and re-interpolated against the frame's exact law, the frame's place at every pick against the
//! lift plan, the plan's cycle against the law core's cycle-file reader bit for bit.

mod common;

use loomkin_cams::table::{Format, Spacing};
use loomkin_eshed::{FrameInput, FrameLoad, FramePlan, FrameSetup, MoveLaws, TABLE_FORMATS, frame_tables};
use loomkin_laws::{Cycle, LawSpec};

const SPEED_RPM: f64 = 500.0;

fn laws(rise: LawSpec, fall: LawSpec) -> MoveLaws {
    MoveLaws::new((rise.clone(), rise.build().unwrap()), (fall.clone(), fall.build().unwrap()))
}

/// Three laws: up, down, and the moves laid end to end by pass-through.
fn laws3(rise: LawSpec, fall: LawSpec, through: LawSpec) -> MoveLaws {
    MoveLaws { through: Some((through.clone(), through.build().unwrap())), ..laws(rise, fall) }
}

/// A pseudo-random lift plan, `frames × picks`; the last frame never moves.
fn lift_plan(frames: usize, picks: usize, seed: u64) -> Vec<Vec<bool>> {
    let mut x = seed;
    (0..frames)
        .map(|i| {
            (0..picks)
                .map(|_| {
                    x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    i + 1 < frames && (x >> 33) % 2 == 1
                })
                .collect()
        })
        .collect()
}

/// Frame `i`'s move centre, deg.
fn centre(i: usize) -> f64 {
    -10.0 + 7.5 * i as f64
}

/// Every frame's plan moving by `l`, its moves down 17° longer than its moves up (at most 360°).
fn setups(plan: &[Vec<bool>], pass_through: bool, l: &MoveLaws) -> Vec<FrameSetup> {
    plan.iter()
        .enumerate()
        .map(|(i, up)| {
            let stroke = 0.09 + 0.0041 * i as f64;
            let phi = 250.0 + 9.0 * i as f64;
            let input = FrameInput {
                up,
                stroke_m: stroke,
                centre_deg: centre(i),
                motion_deg: phi,
                fall_motion_deg: (phi + 17.0).min(360.0),
            };
            let p = FramePlan::new(&input, pass_through).unwrap();
            let load = FrameLoad {
                mass_kg: 5.0,
                spring_n_m: 0.0,
                preload_n: 0.0,
                stroke_m: stroke,
                start_level_m: p.start_level_m(),
            };
            FrameSetup { plan: p, laws: l.clone(), load, servo: common::servo() }
        })
        .collect()
}

#[test]
fn the_plans_cycle_is_the_cycle_files_cycle_bit_for_bit() {
    let plan = lift_plan(5, 17, 3);
    let l = laws3(LawSpec::ModifiedSine, LawSpec::Cycloidal, LawSpec::Poly4567);
    for pass in [false, true] {
        for f in setups(&plan, pass, &l) {
            let built = f.plan.cycle(&l);
            let spec = f.plan.cycle_spec(&l);
            let read = Cycle::from_toml(&spec.to_toml().unwrap()).unwrap();
            assert_eq!(built.period_rad.to_bits(), read.period_rad.to_bits());
            assert_eq!(built.segments.len(), read.segments.len());
            for (a, b) in built.segments.iter().zip(&read.segments) {
                assert_eq!(a.kind, b.kind);
                for (x, y) in [(a.start_rad, b.start_rad), (a.length_rad, b.length_rad), (a.base_si, b.base_si)] {
                    assert_eq!(x.to_bits(), y.to_bits());
                }
                assert_eq!(a.stroke_si.to_bits(), b.stroke_si.to_bits());
                assert_eq!(a.law.as_ref().map(|l| &l.0), b.law.as_ref().map(|l| &l.0));
            }
        }
    }
}

/// The table file re-read and re-interpolated as the controller does, against the exact cycle at
/// `n` angles over the repeat: the largest position error, mm.
fn grid_error(format: Format, text: &str, cycle: &Cycle, n: usize) -> f64 {
    let intervals = format.read(text).unwrap();
    let (x0, x1) = (intervals[0].start_deg, intervals.last().unwrap().end_deg);
    let mut worst = 0.0f64;
    let mut j = 0;
    for k in 0..=n {
        let x = x0 + (x1 - x0) * k as f64 / n as f64;
        while j + 1 < intervals.len() && x > intervals[j].end_deg {
            j += 1;
        }
        let y = intervals[j].eval(x)[0];
        let exact_mm = cycle.eval(x.to_radians(), SPEED_RPM).s * 1e3;
        worst = worst.max((y - exact_mm).abs());
    }
    worst
}

#[test]
fn every_table_re_read_follows_the_frames_exact_law_within_its_reported_error() {
    let plan = lift_plan(4, 9, 21);
    let l = laws3(LawSpec::Poly345, LawSpec::ModifiedSine, LawSpec::Cycloidal);
    for pass in [false, true] {
        let fs = setups(&plan, pass, &l);
        for spacing in [Spacing::StepDeg(1.0), Spacing::StepDeg(7.0), Spacing::Tolerance(1e-3)] {
            let t = frame_tables(&fs, spacing, &[], SPEED_RPM).unwrap();
            for (i, f) in fs.iter().enumerate() {
                let cycle = f.plan.cycle(&l);
                let entry = &t.manifest.frames[i];
                assert_eq!(entry.tables.len(), TABLE_FORMATS.len());
                for (e, &format) in entry.tables.iter().zip(&TABLE_FORMATS) {
                    let file = t.files.iter().find(|x| x.name == e.file).unwrap();
                    let reported = e.report.error.max_position_error;
                    // A dense scan of the file as read back never beats the engine's exact maximum
                    // (its root-found location is between the scan's points) ...
                    let scan = grid_error(format, &file.text, &cycle, 20 * 9 * 360);
                    assert!(
                        scan <= reported * (1.0 + 1e-9) + 1e-12,
                        "{format:?}: scan {scan:e} > reported {reported:e}"
                    );
                    // ... and comes within a few per cent of it.
                    assert!(scan >= 0.5 * reported - 1e-12, "{format:?}: scan {scan:e}, reported {reported:e}");
                    if let Spacing::Tolerance(tol) = spacing {
                        assert!(reported <= tol, "{format:?}: {reported:e} over the tolerance");
                    }
                }
            }
        }
    }
}

#[test]
fn the_manifest_gives_the_master_axis_and_every_frames_place_at_every_pick() {
    let (frames, picks) = (5, 13);
    let plan = lift_plan(frames, picks, 5);
    let l = laws(LawSpec::Cycloidal, LawSpec::Cycloidal);
    let fs = setups(&plan, false, &l);
    let t = frame_tables(&fs, Spacing::StepDeg(1.0), &[Format::Csv], SPEED_RPM).unwrap();
    let m = &t.manifest;
    assert_eq!(m.picks, picks);
    assert_eq!(m.master_axis_deg, 360.0 * picks as f64);
    assert_eq!(t.files.last().unwrap().name, "manifest.json");
    let json: serde_json::Value = serde_json::from_str(&t.files.last().unwrap().text).unwrap();
    assert_eq!(json["master_axis_deg"].as_f64().unwrap(), 360.0 * picks as f64);
    for (i, entry) in m.frames.iter().enumerate() {
        let csv = &t.files.iter().find(|x| x.name == entry.tables[0].file).unwrap().text;
        let intervals = Format::Csv.read(csv).unwrap();
        // The table covers one repeat from the frame's first move's start.
        assert_eq!(intervals[0].start_deg, entry.master_start_deg);
        assert!((intervals.last().unwrap().end_deg - entry.master_start_deg - m.master_axis_deg).abs() < 1e-9);
        // Midway between two moves (no pass-through, motion < 360°) the frame rests where the lift
        // plan puts it for that pick: slave offset + table position = ±H/2 over mid-stroke.
        for p in 0..picks {
            let mut x = 360.0 * p as f64 + centre(i) + 180.0;
            while x < entry.master_start_deg {
                x += m.master_axis_deg;
            }
            while x > entry.master_start_deg + m.master_axis_deg {
                x -= m.master_axis_deg;
            }
            let iv = intervals.iter().find(|v| v.start_deg <= x && x <= v.end_deg).unwrap();
            let height = entry.slave_offset_mm + iv.eval(x)[0];
            let want = if plan[i][p] { entry.stroke_mm / 2.0 } else { -entry.stroke_mm / 2.0 };
            assert!((height - want).abs() < 1e-6, "frame {} pick {p}: {height} mm, lift plan {want} mm", i + 1);
        }
    }
    // The frame that never moves: one dwell, a table at its place.
    assert_eq!(m.frames[frames - 1].moves, 0);
}

#[test]
fn a_repeat_longer_than_a_cycle_file_has_tables_but_no_cycle_file() {
    let plan = lift_plan(2, 120, 8);
    let l = laws(LawSpec::Cycloidal, LawSpec::Cycloidal);
    let fs = setups(&plan, true, &l);
    let t = frame_tables(&fs, Spacing::StepDeg(10.0), &[Format::Xyvaj], SPEED_RPM).unwrap();
    assert!(t.manifest.frames.iter().all(|f| f.cycle_file.is_none()));
    assert!(t.files.iter().all(|f| !f.name.ends_with(".cycle.toml")));
    assert_eq!(t.manifest.master_axis_deg, 360.0 * 120.0);
    for (i, f) in fs.iter().enumerate() {
        let e = &t.manifest.frames[i].tables[0];
        assert_eq!(e.report.source, format!("frame {}", i + 1));
        let text = &t.files.iter().find(|x| x.name == e.file).unwrap().text;
        let scan = grid_error(Format::Xyvaj, text, &f.plan.cycle(&l), 120 * 360);
        assert!(scan <= e.report.error.max_position_error * (1.0 + 1e-9) + 1e-12);
    }
}

#[test]
fn a_table_past_the_engines_point_limit_names_the_frame() {
    let plan = lift_plan(1, 3000, 4);
    let l = laws(LawSpec::Cycloidal, LawSpec::Cycloidal);
    let fs = setups(&plan, false, &l);
    let e = frame_tables(&fs, Spacing::StepDeg(1.0), &[Format::Csv], SPEED_RPM).unwrap_err().to_string();
    assert!(e.contains("frame 1"), "{e}");
}

/// With a crank and lever a frame's tables hold its motor's angle (deg from where it stands at
/// mid-stroke): every file read back, re-interpolated as the controller does and pushed through the
/// linkage's forward map `y(θ)` gives the frame's exact law, within the table's reported error (deg)
/// times the largest frame mm per motor degree over the stroke.
#[test]
fn a_crank_levers_tables_in_motor_degrees_give_the_frames_law_through_the_linkage() {
    use loomkin_cams::profile::Jet;
    let plan = lift_plan(4, 9, 21);
    let l = laws(LawSpec::Poly345, LawSpec::ModifiedSine);
    for pass in [false, true] {
        let fs: Vec<FrameSetup> = setups(&plan, pass, &l)
            .into_iter()
            .map(|mut f| {
                f.servo.transmission.crank_lever = Some(common::crank_lever());
                f
            })
            .collect();
        for spacing in [Spacing::StepDeg(1.0), Spacing::Tolerance(1e-3)] {
            // A point format and a segment format (the others read back as one of these).
            let formats = [Format::Csv, Format::Poly5];
            let t = frame_tables(&fs, spacing, &formats, SPEED_RPM).unwrap();
            assert_eq!(t.manifest.slave_unit, "deg");
            for (i, f) in fs.iter().enumerate() {
                let entry = &t.manifest.frames[i];
                assert_eq!(entry.slave_unit, Some("deg"));
                let link = loomkin_eshed::axis(&f.servo.motor, &f.servo.transmission, &f.load).linkage().unwrap();
                assert_eq!(entry.crank_mid_stroke_deg, Some(link.alpha_mid.to_degrees()));
                // The frame's height over mid-stroke (mm) at a motor angle (deg from mid-stroke's).
                let crank = |m: f64| link.alpha_mid + m.to_radians() / link.gear;
                let height_mm = |m: f64| link.height(Jet::cst(crank(m))).0.v() * 1e3;
                // The largest |dy/dθ_motor| over the stroke, mm per motor degree.
                let h = f.plan.stroke_m / 2.0;
                let slope = (0..=400)
                    .map(|k| {
                        let a = link.motor_angle(-h + 2.0 * h * k as f64 / 400.0).unwrap();
                        (link.height(Jet::var(a)).0.d(1) * 1e3 / link.gear).to_radians().abs()
                    })
                    .fold(0.0, f64::max);
                let cycle = f.plan.cycle(&l);
                let level_mm = f.plan.start_level_m() * 1e3;
                for (e, &format) in entry.tables.iter().zip(&formats) {
                    assert_eq!(e.report.unit, "deg");
                    let file = t.files.iter().find(|x| x.name == e.file).unwrap();
                    let reported = e.report.error.max_position_error;
                    let intervals = format.read(&file.text).unwrap();
                    let (x0, x1) = (intervals[0].start_deg, intervals.last().unwrap().end_deg);
                    let n = 9 * 360 * 4;
                    let (mut worst, mut j) = (0.0f64, 0);
                    for k in 0..=n {
                        let x = x0 + (x1 - x0) * k as f64 / n as f64;
                        while j + 1 < intervals.len() && x > intervals[j].end_deg {
                            j += 1;
                        }
                        let y = height_mm(intervals[j].eval(x)[0]);
                        let exact = level_mm + cycle.eval(x.to_radians(), SPEED_RPM).s * 1e3;
                        worst = worst.max((y - exact).abs());
                    }
                    assert!(
                        worst <= slope * reported * (1.0 + 1e-6) + 1e-9,
                        "frame {} {format:?}: {worst:e} mm > {slope} mm/deg × {reported:e} deg",
                        i + 1
                    );
                    if let Spacing::Tolerance(tol) = spacing {
                        assert!(reported <= tol, "{format:?}: {reported:e} over the tolerance");
                    }
                }
            }
        }
    }
}
