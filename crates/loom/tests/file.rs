//! The loom file: the examples read, every bad field named.

mod common;
use common::*;
use loomkin_loom::{CarrierSpeed, Lifts, Loom, LoomError};

#[test]
fn the_examples_read() {
    let r = rapier();
    assert_eq!(r.frame_count(), 24);
    assert!((r.geometry.frame_m[23] - 0.476).abs() < 1e-12);
    assert_eq!(r.geometry.lifts, Lifts::Clean);
    assert!((r.geometry.stroke_m[23] - 0.09 * 476.0 / 200.0).abs() < 1e-12);
    assert_eq!((r.insertion.entry_deg, r.insertion.exit_deg), (70.0, 290.0));
    assert_eq!(r.shedding.law.motion_deg(), 280.0);
    let s = shuttle();
    assert_eq!(s.shedding.stagger_deg, vec![0.0, 7.5, 0.0, 7.5]);
    let CarrierSpeed::Shuttle { release_m_s, retardation_pct } = s.insertion.speed else { panic!() };
    // The paper's mechanism at its designed 200 rpm releases the shuttle at 17 m/s.
    assert!((release_m_s - 17.0).abs() < 1e-9 && retardation_pct == 10.0);
    let flight = 6.0 * 200.0 * 1.45 / (17.0 * 0.95);
    assert!((s.insertion.exit_deg - s.insertion.entry_deg - flight).abs() < 1e-9);
}

fn err(text: &str) -> String {
    Loom::from_toml(text).unwrap_err().to_string()
}

#[test]
fn bad_fields_are_named() {
    let r = example("rapier-loom.toml");
    let s = example("shuttle-loom.toml");
    let e = err(&edited(&s, "frame_distances_mm = [230,", "frame_distances_mm = [-5,"));
    assert!(e.starts_with("geometry.frame_distances_mm[0]: -5 mm puts frame 1 in front of the fell"), "{e}");
    let e = err(&edited(&s, "270, 290]", "270, 990]"));
    assert!(e.starts_with("geometry.frame_distances_mm[3]: 990 mm puts frame 4 behind the back rest"), "{e}");
    let e = err(&edited(&s, "[230, 250,", "[230, 220,"));
    assert!(e.starts_with("geometry.frame_distances_mm[1]"), "{e}");
    let e = err(&edited(&r, "reed_mm = 110", "reed_mm = 250"));
    assert!(e.starts_with("geometry.reed_mm = 250 is out of range"), "{e}");
    let e = err(&edited(&r, "speed_rpm = 500", "speed_rpm = -1"));
    assert!(e.starts_with("speed_rpm = -1 is out of range"), "{e}");
    let e = err(&edited(&r, "mass_kg = 5.5", "mass_kg = 0"));
    assert!(e.starts_with("frames.mass_kg = 0 is out of range"), "{e}");
    let e = err(&edited(&s, "mass_kg = [3.0, 3.0, 3.0, 3.0]", "mass_kg = [3.0, 3.0]"));
    assert!(e.starts_with("frames.mass_kg: 2 values for 4 frames"), "{e}");
    let e = err(&edited(&r, "preset = \"dobby\"", "preset = \"dobby\"\nlaw = \"cycloidal\""));
    assert!(e.starts_with("shedding.preset: give exactly one law"), "{e}");
    let e = err(&edited(&r, "preset = \"dobby\"", "preset = \"nope\""));
    assert!(e.contains("unknown shedding law 'nope'"), "{e}");
    let e = err(&edited(&r, "motion_deg = 280", "motion_deg = 400"));
    assert!(e.contains("motion_deg = 400 is out of range"), "{e}");
    let e = err(&edited(&r, "crossing_deg = 350", "crossing_deg = 360"));
    assert!(e.starts_with("shedding.crossing_deg = 360 is out of range"), "{e}");
    let e = err(&edited(&s, "stagger_deg = [0, 7.5]", "stagger_deg = [0, 25]"));
    assert!(e.starts_with("shedding.stagger_deg[1] = 25 is out of range"), "{e}");
    let e = err(&edited(&s, "groups = [[1, 3], [2, 4]]", "groups = [[1, 3], [2, 3]]"));
    assert!(e.starts_with("shedding.groups[1]: frame 3 is in two groups"), "{e}");
    let e = err(&edited(&s, "groups = [[1, 3], [2, 4]]", "groups = [[1, 3], [2, 5]]"));
    assert!(e.starts_with("shedding.groups[1]: frame 5"), "{e}");
    let e = err(&edited(&r, "exit_deg = 290", "exit_deg = 60"));
    assert!(e.starts_with("insertion.exit_deg = 60 is out of range"), "{e}");
    let e = err(&edited(&r, "carrier_width_mm = 25", "carrier_width_mm = 110"));
    assert!(e.starts_with("insertion.carrier_width_mm = 110 is out of range"), "{e}");
    let e = err(&edited(&r, "[beat_up]", "[beat_up]\nspeed = 3"));
    // Placed by line and column, as every file reader words a TOML error (loomkin_units::toml_reason).
    assert!(e.starts_with("loom file: line 75, column 1: unknown field `speed`"), "{e}");
    let e = err(&edited(&r, "lifts = \"clean\"", "lifts = \"nice\""));
    assert!(e.starts_with("geometry.lifts: 'nice'"), "{e}");
    let e = err(&edited(&s, "centre_deg = 180", "centre_deg = 340"));
    assert!(e.starts_with("insertion.exit_deg: the carrier needs"), "{e}");
}

#[test]
fn laws_of_every_kind_read() {
    let r = example("rapier-loom.toml");
    let law = edited(&r, "preset = \"dobby\"", "law = \"modified-trapezoid\"\nparams = { ramp = 0.1 }");
    assert_eq!(Loom::from_toml(&law).unwrap().shedding.law.motion_deg(), 280.0);
    let pw = edited(&r, "preset = \"dobby\"", "positive = \"0.5:sine-ramp:0:1,0.5:cosine-ramp:1:0\"");
    Loom::from_toml(&pw).unwrap();
    let cyc = edited(&r, "motion_deg = 280\n", "").replace("preset = \"dobby\"", "").replace(
        "[insertion]",
        "[shedding.cycle]\nperiod_deg = 720\nstroke = 1\n[[shedding.cycle.segment]]\nkind = \"rise\"\nlength_deg = 260\nlaw = \"poly345\"\n\
         [[shedding.cycle.segment]]\nkind = \"dwell\"\nlength_deg = 100\n[[shedding.cycle.segment]]\nkind = \"return\"\n\
         length_deg = 260\nlaw = \"cycloidal\"\n[[shedding.cycle.segment]]\nkind = \"dwell\"\nlength_deg = 100\n\n[insertion]",
    );
    let l = Loom::from_toml(&cyc).unwrap();
    assert_eq!(l.shedding.law.motion_deg(), 260.0);
    assert_eq!(l.shedding.law.label(), "rise poly345, return cycloidal");
    let eq = edited(&r, "lifts = \"clean\"", "lifts = \"equal-strain\"");
    let l = Loom::from_toml(&eq).unwrap();
    assert_eq!(l.geometry.lifts, Lifts::EqualStrain);
    assert!(l.geometry.stroke_m[23] < rapier().geometry.stroke_m[23]);
}

#[test]
fn the_stagger_file_reads_back() {
    let s = example("shuttle-loom.toml");
    let out = Loom::stagger_toml(&s, &[1.0, -2.5, 1.0, -2.5], Some(&[vec![0, 2], vec![1, 3]])).unwrap();
    let l = Loom::from_toml(&out).unwrap();
    assert_eq!(l.shedding.stagger_deg, vec![1.0, -2.5, 1.0, -2.5]);
    let out = Loom::stagger_toml(&s, &[1.0, -2.5, 3.0, 0.5], None).unwrap();
    assert_eq!(Loom::from_toml(&out).unwrap().shedding.stagger_deg, vec![1.0, -2.5, 3.0, 0.5]);
}

/// The loom file's top-level keys ([`loomkin_loom::LOOM_FILE_KEYS`]) are the reader's: it names
/// them when it refuses an unknown one, and every example's keys are among them. A refusal of a
/// field read from the file is the file's ([`LoomError::in_loom_file`]); a study's option is not.
#[test]
fn the_loom_file_keys_are_the_readers() {
    let e = err(&format!("unheard_of = 1\n{}", example("rapier-loom.toml")));
    let listed: Vec<&str> = e.split('`').skip(3).step_by(2).collect();
    let mut keys = loomkin_loom::LOOM_FILE_KEYS.to_vec();
    keys.sort_unstable();
    let mut named = listed.clone();
    named.sort_unstable();
    assert_eq!(named, keys, "{e}");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for f in std::fs::read_dir(dir).unwrap().map(|f| f.unwrap().path()) {
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        if !name.ends_with("-loom.toml") {
            continue;
        }
        let t: toml::Table = std::fs::read_to_string(&f).unwrap().parse().unwrap();
        for k in t.keys() {
            assert!(keys.contains(&k.as_str()), "{name}: {k}");
        }
    }
    let bad = Loom::from_toml(&edited(&example("rapier-loom.toml"), "mass_kg = 5.5", "mass_kg = 0")).unwrap_err();
    assert!(bad.in_loom_file(), "{bad}");
    let option = LoomError::Infeasible { field: "min_clearance_mm".into(), reason: "no stagger keeps it".into() };
    assert!(!option.in_loom_file());
    let top =
        LoomError::Range(loomkin_units::RangeError::new("speed_rpm", -1.0, loomkin_units::Range::above(0.0, "rpm")));
    assert!(top.in_loom_file());
}
