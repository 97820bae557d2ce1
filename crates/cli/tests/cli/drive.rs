//! `loomkin drive …`: the contract keys and headers, the plot written, the errors.

use crate::common::{loomkin, stdout_json, usage_error};

fn ex(name: &str) -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/").to_string() + name
}

/// The rapier loom with its `[drive]` table replaced by `drive` (a file in the temporary folder).
fn rapier_with_drive_table(tag: &str, drive: &str) -> String {
    // One file per call: tests run in parallel, and a file rewritten while another test reads it
    // reads as cut short.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!("loomkin-drive-{tag}-{}-{n}.toml", std::process::id()));
    let text = std::fs::read_to_string(ex("rapier-loom.toml")).unwrap();
    let text = text[..text.find("\n# The main-shaft drive").unwrap()].to_string() + drive;
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// The rapier loom with rotating parts and friction on its main shaft, constant torque.
fn rapier_with_drive() -> String {
    rapier_with_drive_table("constant", "\n[drive]\nrotating_inertia_kg_m2 = 0.8\nfriction_torque_n_m = 4\n")
}

#[test]
fn inertia_json_has_the_total_and_every_mechanism() {
    let loom = rapier_with_drive();
    let v = stdout_json(&["drive", "inertia", &loom, "--wif", &ex("point-24.wif"), "--json"]);
    for key in ["j_min_kg_m2", "j_max_kg_m2", "j_mean_kg_m2"] {
        assert_eq!(v[key], v["total"][key], "{key}");
        let m = v["mechanisms"].as_array().unwrap();
        assert_eq!(m.len(), 24 + 2);
        assert!(m.iter().all(|x| x[key].as_f64().unwrap() >= 0.0));
    }
    assert_eq!(v["mechanisms"][24]["name"], "sley");
    // The example's own drive table (induction motor, Kloss) runs as shipped.
    let e = stdout_json(&["drive", "ripple", &ex("rapier-loom.toml"), "--json"]);
    assert_eq!(e["motor"], "induction");
    assert_eq!(v["mechanisms"][25]["j_mean_kg_m2"], 0.8);
    let out = loomkin().args(["drive", "inertia", &loom, "--csv", "--step-deg", "10"]).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    let header = text.lines().next().unwrap();
    assert!(header.starts_with("angle_deg,j_frame1_kg_m2,dj_frame1_kg_m2_per_rad,"), "{header}");
    assert!(header.ends_with("j_sley_kg_m2,dj_sley_kg_m2_per_rad,j_rotating_kg_m2,dj_rotating_kg_m2_per_rad,j_total_kg_m2,dj_total_kg_m2_per_rad"), "{header}");
    assert_eq!(text.lines().count(), 1 + 72);
}

#[test]
fn ripple_json_has_the_contract_keys_and_a_flywheel_holds_its_target() {
    let loom = rapier_with_drive();
    let v = stdout_json(&["drive", "ripple", &loom, "--json"]);
    for key in [
        "mean_speed_rpm",
        "min_speed_rpm",
        "max_speed_rpm",
        "speed_ripple_pct",
        "energy_swing_j",
        "peak_motor_torque_n_m",
        "rms_motor_torque_n_m",
    ] {
        assert!(v[key].as_f64().unwrap().is_finite(), "{key}");
    }
    assert!((v["mean_speed_rpm"].as_f64().unwrap() - 500.0).abs() < 1e-9);
    let f = stdout_json(&["drive", "ripple", &loom, "--target-ripple-pct", "2", "--json"]);
    assert!((f["speed_ripple_pct"].as_f64().unwrap() - 2.0).abs() < 1e-8, "{f}");
    assert!(f["flywheel_kg_m2"].as_f64().unwrap() > 0.0);
    assert_eq!(f["target_ripple_pct"], 2.0);
    let i = stdout_json(&["drive", "ripple", &loom, "--motor", "induction", "--rated-power-kw", "5.5", "--json"]);
    assert_eq!(i["motor"], "induction");
    let dir = std::env::temp_dir().join(format!("loomkin-ripple-{}.svg", std::process::id()));
    let out = loomkin().args(["drive", "ripple", &loom, "-o", dir.to_str().unwrap()]).output().unwrap();
    assert!(out.status.success() && std::fs::metadata(&dir).unwrap().len() > 1000);
}

#[test]
fn ripple_refuses_bad_input_naming_the_field() {
    let loom = rapier_with_drive();
    usage_error(&["drive", "ripple", &rapier_with_drive_table("none", "")], &["error: drive.rotating_inertia_kg_m2:"]);
    usage_error(&["drive", "ripple", &loom, "--motor", "induction"], &["drive.rated_power_kw", "required"]);
    usage_error(&["drive", "ripple", &loom, "--flywheel-kg-m2", "-1"], &["--flywheel-kg-m2 = -1 is out of range"]);
    usage_error(&["drive", "ripple", &loom, "--target-ripple-pct", "0"], &["target_ripple_pct = 0 is out of range"]);
    usage_error(&["drive", "ripple", &loom, "--step-deg", "20"], &["--step-deg = 20 is out of range"]);
}

#[test]
fn correct_writes_cycle_files_that_cam_and_dyn_read() {
    let dir = std::env::temp_dir().join(format!("loomkin-drive-correct-{}", std::process::id()));
    let d = dir.to_str().unwrap();
    let v = stdout_json(&[
        "drive",
        "correct",
        &ex("rapier-loom.toml"),
        "--wif",
        &ex("twill-2-2.wif"),
        "-o",
        d,
        "--natural-hz",
        "80",
        "--damping-ratio",
        "0.05",
        "--json",
    ]);
    let before = v["max_timing_error_deg_before"].as_f64().unwrap();
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 24);
    // The frames come time-true; the cam sley (one cam for every pick) keeps its pick-to-pick spread.
    let after = frames.iter().map(|f| f["max_timing_error_deg_after"].as_f64().unwrap()).fold(0.0, f64::max);
    assert!(before > 0.1 && after < 1e-5, "{before} {after}");
    assert!(
        v["sley"]["max_timing_error_deg_after"].as_f64().unwrap()
            < v["sley"]["max_timing_error_deg_before"].as_f64().unwrap()
    );
    // twill-2-2 moves frames 1-4 only: one file each, and the cam sley's.
    let files = v["files"].as_array().unwrap();
    assert_eq!(files.len(), 5);
    assert!(files[4].as_str().unwrap().ends_with("sley.toml"), "{files:?}");
    for f in &frames[..4] {
        for key in [
            "max_timing_error_deg_before",
            "max_timing_error_deg_after",
            "residual_vibration_mm_before",
            "residual_vibration_mm_after",
            "residual_vibration_constant_speed_mm",
        ] {
            assert!(f[key].as_f64().unwrap() >= 0.0, "{key}");
        }
    }
    assert_eq!(v["not_corrected"].as_array().unwrap().len(), 0, "{v}");
    // The shuttle loom's crank-rocker sley is not a cam: named as not corrected.
    let shuttle = dir.join("shuttle");
    let s = stdout_json(&[
        "drive",
        "correct",
        &ex("shuttle-loom.toml"),
        "--wif",
        &ex("twill-2-2.wif"),
        "-o",
        shuttle.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(s["not_corrected"][0], "sley (a four-bar linkage, not a cam)");
    let file = files[0].as_str().unwrap();
    let r = stdout_json(&["dyn", "response", file, "--natural-hz", "80", "--json"]);
    assert!(r["residual_amplitude_mm"].as_f64().unwrap().is_finite());
    let out = loomkin().args(["cam", "profile", file, "--follower", "translating", "--json"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).ok();
    // The residual vibration needs a valid natural frequency; the error names the flag's field.
    usage_error(
        &["drive", "correct", &ex("rapier-loom.toml"), "--wif", &ex("twill-2-2.wif"), "-o", d, "--natural-hz", "0"],
        &["natural_hz"],
    );
}

/// A motor flag the motor in force does not read, and `--damping-ratio` without `--natural-hz`,
/// are refused in one line naming the flag and what it needs (they were ignored unchecked); with
/// what they need they run.
#[test]
fn motor_flags_without_their_motor_are_refused() {
    // A constant-torque motor in the file.
    let loom = rapier_with_drive();
    let pattern = ex("point-24.wif");
    let out = std::env::temp_dir().join(format!("loomkin-drive-motor-flags-{}", std::process::id()));
    let out = out.to_str().unwrap().to_string();
    for command in ["ripple", "correct"] {
        let with_pattern = |extra: &[&str]| {
            let mut args = vec!["drive", command, loom.as_str()];
            if command == "correct" {
                args.extend(["--wif", pattern.as_str(), "-o", out.as_str()]);
            }
            args.extend(extra);
            args.into_iter().map(str::to_string).collect::<Vec<_>>()
        };
        let refused = |extra: &[&str], needles: &[&str]| {
            let args = with_pattern(extra);
            usage_error(&args.iter().map(String::as_str).collect::<Vec<_>>(), needles);
        };
        refused(&["--servo-gain-n-m-s", "100"], &["--servo-gain-n-m-s", "--motor servo", "the motor here is constant"]);
        refused(&["--servo-integral-s", "1e9"], &["--servo-integral-s", "--motor servo"]);
        refused(&["--gear-ratio", "3"], &["--gear-ratio", "--motor induction"]);
        refused(&["--motor-curve", "kloss"], &["--motor-curve", "--motor induction"]);
        refused(
            &["--motor", "induction", "--rated-power-kw", "5.5", "--breakdown-ratio", "2.5"],
            &["--breakdown-ratio", "--motor-curve kloss"],
        );
        refused(
            &[
                "--motor",
                "servo",
                "--servo-gain-n-m-s",
                "100",
                "--servo-torque-limit-n-m",
                "1000",
                "--rated-rpm",
                "1400",
            ],
            &["--rated-rpm", "--motor induction", "the motor here is servo"],
        );
    }
    usage_error(
        &["drive", "correct", &loom, "--wif", &pattern, "-o", &out, "--damping-ratio", "0.05"],
        &["--damping-ratio", "--natural-hz"],
    );
    // With what they need they are read (and checked: an out-of-range gain is refused by its range).
    usage_error(
        &["drive", "ripple", &loom, "--motor", "servo", "--servo-gain-n-m-s", "-1", "--servo-torque-limit-n-m", "1000"],
        &["servo_gain_n_m_s", "out of range"],
    );
    let ok = loomkin()
        .args(["drive", "ripple", &loom, "--motor", "induction", "--rated-power-kw", "5.5"])
        .args(["--motor-curve", "kloss", "--breakdown-ratio", "2.5", "--json"])
        .output()
        .unwrap();
    assert!(ok.status.success(), "{}", String::from_utf8_lossy(&ok.stderr));
}
