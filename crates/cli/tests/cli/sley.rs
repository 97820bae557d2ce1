//! `loomkin sley …`: the contract keys, the plot, the errors.

use crate::common::{loomkin, stdout_json, usage_error};
use std::path::PathBuf;

fn ex(name: &str) -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/").to_string() + name
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("loomkin-sley-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn analyze_json_has_the_contract_keys() {
    let v = stdout_json(&["sley", "analyze", &ex("rapier-loom.toml"), "--json"]);
    for key in [
        "reed_stroke_mm",
        "back_dwell_deg",
        "dwell_tolerance_mm",
        "peak_reed_acceleration_m_s2",
        "max_inertia_force_n",
        "min_inertia_force_n",
        "peak_crank_torque_n_m",
        "min_transmission_angle_deg",
        "front_dead_centre_deg",
        "back_dead_centre_deg",
    ] {
        assert!(v[key].as_f64().unwrap().is_finite(), "{key}");
    }
    assert_eq!(v["dwell_tolerance_mm"], 1.0);
    assert_eq!(v["speed_rpm"], 500.0);
    // Signed along the reed's path: the sley decelerates into beat-up.
    assert!(v["min_inertia_force_n"].as_f64().unwrap() < 0.0 && v["max_inertia_force_n"].as_f64().unwrap() > 0.0);
    // A wider tolerance, a longer dwell; a speed flag scales the forces by its square (no beat-up
    // force changes with speed, so the inertia force alone does).
    let wide = stdout_json(&["sley", "analyze", &ex("rapier-loom.toml"), "--dwell-tolerance-mm", "3", "--json"]);
    assert!(wide["back_dwell_deg"].as_f64().unwrap() > v["back_dwell_deg"].as_f64().unwrap());
    let slow = stdout_json(&["sley", "analyze", &ex("rapier-loom.toml"), "--speed-rpm", "250", "--json"]);
    let ratio = slow["max_inertia_force_n"].as_f64().unwrap() / v["max_inertia_force_n"].as_f64().unwrap();
    assert!((ratio - 0.25).abs() < 1e-9, "{ratio}");
    assert_eq!(slow["reed_stroke_mm"], v["reed_stroke_mm"]);
}

#[test]
fn analyze_text_csv_and_plot() {
    let out = loomkin().args(["sley", "analyze", &ex("shuttle-loom.toml")]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("sley at 200 rpm: reed stroke 130.785 mm"), "{text}");
    assert!(text.contains("peak crank torque"), "{text}");
    let out = loomkin().args(["sley", "analyze", &ex("shuttle-loom.toml"), "--csv", "--points", "8"]).output().unwrap();
    let csv = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "angle_deg,reed_mm,velocity_m_s,acceleration_m_s2,jerk_m_s3,inertia_force_n,rod_force_n,crank_torque_n_m"
    );
    assert_eq!(lines.len(), 10);
    assert!(lines[1].starts_with("0,130.78"), "{}", lines[1]);
    let dir = scratch("plot");
    for ext in ["svg", "png"] {
        let path = dir.join(format!("sley.{ext}"));
        let out = loomkin()
            .args(["sley", "analyze", &ex("shuttle-loom.toml"), "-o", path.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        assert!(std::fs::metadata(&path).unwrap().len() > 1000);
    }
    let svg = std::fs::read_to_string(dir.join("sley.svg")).unwrap();
    let dwell =
        stdout_json(&["sley", "analyze", &ex("shuttle-loom.toml"), "--json"])["back_dwell_deg"].as_f64().unwrap();
    let band = format!("dwell {dwell:.2}°");
    assert!(svg.contains("crank torque [N·m]") && svg.contains(&band), "the panels and the dwell band {band}");
}

#[test]
fn analyze_errors_are_one_line() {
    let dir = scratch("errors");
    // The shuttle loom's crank-rocker sley (the rapier's is a cam sley).
    let text = std::fs::read_to_string(ex("shuttle-loom.toml")).unwrap();
    let bare = dir.join("no-sley.toml");
    std::fs::write(&bare, &text[..text.find("\n# The sley").unwrap()]).unwrap();
    usage_error(&["sley", "analyze", bare.to_str().unwrap()], &["no [sley] table"]);
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, text.replace("rod_mm = 250", "rod_mm = 20")).unwrap();
    usage_error(&["sley", "analyze", bad.to_str().unwrap()], &["sley.crank_mm, sley.rod_mm", "does not close"]);
    std::fs::write(&bad, text.replace("crank_mm = 48", "crank_mm = 0")).unwrap();
    usage_error(
        &["sley", "analyze", bad.to_str().unwrap()],
        &["sley.crank_mm = 0 is out of range: allowed 0 < sley.crank_mm ≤ 10000 mm"],
    );
    let r = ex("shuttle-loom.toml");
    usage_error(
        &["sley", "analyze", &r, "--dwell-tolerance-mm", "0"],
        &["--dwell-tolerance-mm = 0", "0 < --dwell-tolerance-mm"],
    );
    // Past the reed's stroke (130.785 mm, read from the analysis).
    let stroke = stdout_json(&["sley", "analyze", &r, "--json"])["reed_stroke_mm"].as_f64().unwrap();
    let below = format!("< {:.2}", (stroke * 100.0).floor() / 100.0);
    usage_error(&["sley", "analyze", &r, "--dwell-tolerance-mm", "131"], &["--dwell-tolerance-mm = 131", &below]);
    usage_error(&["sley", "analyze", &r, "--speed-rpm", "-5"], &["--speed-rpm = -5"]);
    usage_error(&["sley", "analyze", &r, "--points", "1"], &["--points = 1"]);
    usage_error(&["sley", "analyze", &bare.to_string_lossy(), "-o", "plot.jpg"], &["plot.jpg"]);
}

#[test]
fn synthesize_prints_a_table_that_analyze_reads_back() {
    let out = loomkin().args(["sley", "synthesize", "--stroke-mm", "110", "--back-dwell-deg", "40"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("least transmission angle"), "{text}");
    let table = &text[text.find("[sley]").unwrap()..];
    // The table pasted into a loom file with the sley's mass: the targets come back.
    let loom = std::fs::read_to_string(ex("rapier-loom.toml")).unwrap();
    let loom =
        loom[..loom.find("\n# The sley").unwrap()].to_string() + "\n" + table + "mass_kg = 20\ngyration_mm = 300\n";
    let dir = scratch("synth");
    let path = dir.join("loom.toml");
    std::fs::write(&path, loom).unwrap();
    let v = stdout_json(&["sley", "analyze", path.to_str().unwrap(), "--json"]);
    // Six decimals of a millimetre in the table: the targets to about 1e-6 of themselves.
    assert!((v["reed_stroke_mm"].as_f64().unwrap() - 110.0).abs() < 1e-4, "{v}");
    assert!((v["back_dwell_deg"].as_f64().unwrap() - 40.0).abs() < 1e-3, "{v}");
    let j = stdout_json(&["sley", "synthesize", "--reed-stroke-mm", "110", "--back-dwell-deg", "40", "--json"]);
    for key in [
        "crank_mm",
        "rod_mm",
        "sword_mm",
        "pivot_x_mm",
        "pivot_y_mm",
        "min_transmission_angle_deg",
        "reed_stroke_mm",
        "back_dwell_deg",
    ] {
        assert!(j[key].as_f64().unwrap().is_finite(), "{key}");
    }
    let (a, b) = (j["min_transmission_angle_deg"].as_f64().unwrap(), v["min_transmission_angle_deg"].as_f64().unwrap());
    assert!((a - b).abs() < 1e-4, "{a} vs {b}");
}

#[test]
fn synthesize_refuses_infeasible_targets() {
    usage_error(
        &["sley", "synthesize", "--stroke-mm", "110", "--back-dwell-deg", "300"],
        &["--back-dwell-deg: no crank-rocker gives a back dwell of 300°"],
    );
    usage_error(
        &["sley", "synthesize", "--stroke-mm", "0", "--back-dwell-deg", "30"],
        &["--reed-stroke-mm = 0 is out of range"],
    );
    usage_error(
        &["sley", "synthesize", "--stroke-mm", "900", "--back-dwell-deg", "30"],
        &["--reed-stroke-mm, --reed-height-mm", "120°"],
    );
    usage_error(
        &["sley", "synthesize", "--stroke-mm", "110", "--back-dwell-deg", "30", "--dwell-tolerance-mm", "110"],
        &["--dwell-tolerance-mm = 110", "< 110 mm"],
    );
    usage_error(&["sley", "synthesize", "--stroke-mm", "110"], &["--back-dwell-deg"]);
}

/// The projectile example's cam-driven sley: `sley analyze` reports the four-bar's keys (the crank
/// torque is the cam shaft's), names the drive and the cams' sizing, leaves the rod out; `drive
/// inertia` and `drive ripple` take it; its table's errors name the field.
#[test]
fn a_cam_sley_reports_the_same_keys() {
    let p = ex("projectile-loom.toml");
    let v = stdout_json(&["sley", "analyze", &p, "--json"]);
    for key in [
        "reed_stroke_mm",
        "back_dwell_deg",
        "dwell_tolerance_mm",
        "peak_reed_acceleration_m_s2",
        "max_inertia_force_n",
        "min_inertia_force_n",
        "peak_crank_torque_n_m",
        "min_transmission_angle_deg",
        "max_pressure_angle_deg",
        "prime_radius_mm",
        "peak_contact_force_n",
        "max_contact_force_n",
        "min_contact_force_n",
        "peak_rocking_shaft_force_n",
    ] {
        assert!(v[key].as_f64().unwrap().is_finite(), "{key}: {v}");
    }
    assert_eq!(v["drive"], "cam");
    // Conjugate cams: the return cam carries the negative part, and the sley is both thrown forward
    // and pulled back.
    assert!(v["contact_force_sign"].as_str().unwrap().contains("return cam"), "{v}");
    assert!(v["min_contact_force_n"].as_f64().unwrap() < 0.0, "{v}");
    assert!(v.get("peak_rod_force_n").is_none());
    // The 200° dwell of the cam law and its near-dwell within 1 mm: the projectile's flight fits.
    assert!(v["back_dwell_deg"].as_f64().unwrap() > 200.0, "{v}");
    assert!(v["max_inertia_force_n"].as_f64().unwrap() > 0.0 && v["min_inertia_force_n"].as_f64().unwrap() < 0.0);
    let out = loomkin().args(["sley", "analyze", &p, "--csv", "--points", "4"]).output().unwrap();
    let csv = String::from_utf8(out.stdout).unwrap();
    assert!(
        csv.starts_with(
            "angle_deg,reed_mm,velocity_m_s,acceleration_m_s2,jerk_m_s3,inertia_force_n,crank_torque_n_m\n"
        ),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 6);
    let text = String::from_utf8(loomkin().args(["sley", "analyze", &p]).output().unwrap().stdout).unwrap();
    assert!(text.contains("peak cam-shaft torque") && text.contains("largest pressure angle 35.000°"), "{text}");
    assert!(text.contains("cam contact force: max "), "{text}");
    let wif = ex("point-24.wif");
    let j = stdout_json(&["drive", "inertia", &p, "--wif", &wif, "--json"]);
    let sley = j["mechanisms"].as_array().unwrap().iter().find(|m| m["name"] == "sley").unwrap().clone();
    assert!(sley["j_max_kg_m2"].as_f64().unwrap() > 0.0 && sley["j_min_kg_m2"].as_f64().unwrap() == 0.0, "{sley}");
    let r = stdout_json(&["drive", "ripple", &p, "--wif", &wif, "--json"]);
    assert!(r["speed_ripple_pct"].as_f64().unwrap() > 0.0);
    // drive correct corrects the frames and the cam sley (for the pick-mean speed): its timing
    // under `sley`, its cam in sley.toml, which `cam profile` and `dyn response` read.
    let dir = scratch("correct");
    let c = stdout_json(&["drive", "correct", &p, "--wif", &wif, "-o", dir.to_str().unwrap(), "--json"]);
    assert_eq!(c["not_corrected"].as_array().unwrap().len(), 0, "{c}");
    let (before, after) = (
        c["sley"]["max_timing_error_deg_before"].as_f64().unwrap(),
        c["sley"]["max_timing_error_deg_after"].as_f64().unwrap(),
    );
    assert!(c["sley"]["moves"] == 2 && before > 0.5 && after > 0.0 && after < before / 2.0, "{c}");
    assert!(c["max_timing_error_deg_before"].as_f64().unwrap() >= before, "{c}");
    // The corrected cam re-checked on the follower the cam was sized for (35°): past it, one
    // warning line on standard error.
    let (p_before, p_after) = (
        c["sley"]["max_pressure_angle_deg_before"].as_f64().unwrap(),
        c["sley"]["max_pressure_angle_deg_after"].as_f64().unwrap(),
    );
    assert!((p_before - 35.0).abs() < 1e-6 && p_after > 35.0 && c["sley"]["pressure_angle_limit_deg"] == 35.0, "{c}");
    for key in ["min_curvature_radius_mm_before", "min_curvature_radius_mm_after", "roller_radius_mm"] {
        assert!(c["sley"][key].as_f64().unwrap() > 0.0, "{key}: {c}");
    }
    let out = loomkin().args(["drive", "correct", &p, "--wif", &wif, "-o", dir.to_str().unwrap()]).output().unwrap();
    let (text, err) = (String::from_utf8(out.stdout).unwrap(), String::from_utf8(out.stderr).unwrap());
    assert!(
        out.status.success() && text.contains("sley cam on its follower: largest pressure angle 35.000° before"),
        "{text}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("loomkin: warning: sley: the time-true cam needs a pressure angle of "), "{err}");
    let file = dir.join("sley.toml");
    assert!(c["files"].as_array().unwrap().iter().any(|f| f.as_str() == file.to_str()), "{c}");
    let f = file.to_str().unwrap();
    let cam = stdout_json(&[
        "cam",
        "profile",
        f,
        "--follower",
        "oscillating",
        "--arm-mm",
        "200",
        "--pivot-mm",
        "250",
        "--roller-radius-mm",
        "20",
        "--max-pressure-deg",
        "36",
        "--json",
    ]);
    assert!(cam.is_object(), "{cam}");
    let text = String::from_utf8(loomkin().args(["dyn", "response", f, "--natural-hz", "60"]).output().unwrap().stdout)
        .unwrap();
    assert!(text.contains("residual vibration"), "{text}");
    let text = String::from_utf8(
        loomkin().args(["drive", "correct", &p, "--wif", &wif, "-o", dir.to_str().unwrap()]).output().unwrap().stdout,
    )
    .unwrap();
    assert!(text.contains("\nsley            2 ") && text.contains("pick-mean speed"), "{text}");
    // Errors in the cam sley's table: one line naming the key.
    let text = std::fs::read_to_string(&p).unwrap();
    let dir = scratch("cam");
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        text.replace("unit = \"deg\"                     # the rocking", "unit = \"mm\" # the rocking"),
    )
    .unwrap();
    usage_error(&["sley", "analyze", bad.to_str().unwrap()], &["sley.cycle.unit", "unit = \"deg\""]);
    std::fs::write(&bad, text.replace("back_angle_deg = 100", "back_angle_deg = 190")).unwrap();
    usage_error(&["sley", "analyze", bad.to_str().unwrap()], &["sley.back_angle_deg = 190 is out of range"]);
    std::fs::write(&bad, text.replace("drive = \"cam\"", "drive = \"belt\"")).unwrap();
    usage_error(&["sley", "analyze", bad.to_str().unwrap()], &["unknown variant `belt`", "line "]);
}
