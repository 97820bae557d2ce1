//! `loomkin servo …` run as a user runs it: contract keys, exit codes, files.

use crate::common::*;

use serde_json::Value;

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("loomkin-servo-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

const DEF: &str = "0:0,0.1:0.9,0.25:1,0.4:0.6,0.5:0";

#[test]
fn law_json_has_the_contract_keys() {
    let v = stdout_json(&["servo", "law", "--def", DEF, "--json"]);
    for k in ["d", "cv", "ca", "cj", "cm", "ca_rms", "def_points", "continuity_class"] {
        assert!(v.get(k).is_some(), "key {k} missing in {v}");
    }
    // The default points (cycloid acceleration sampled at j/12) give nearly the cycloid's values.
    let v = stdout_json(&["servo", "law", "--json"]);
    assert!((v["cv"].as_f64().unwrap() - 2.0).abs() < 1e-3);
    assert!((v["ca"].as_f64().unwrap() - 2.0 * std::f64::consts::PI).abs() < 1e-2);
    let c = stdout_json(&["servo", "law", "--end", "clamped", "--json"]);
    assert_eq!(c["continuity_class"], 3, "clamped start: jerk continuous against the dwells");
}

#[test]
fn law_sample_csv_prints_x_s_v_a_j() {
    let out = loomkin().args(["servo", "law", "--def", DEF, "--sample", "11", "--csv"]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "x,s,v,a,j");
    assert_eq!(lines.len(), 12);
    let last: Vec<f64> = lines[11].split(',').map(|t| t.parse().unwrap()).collect();
    assert_eq!(last[0], 1.0);
    assert!((last[1] - 1.0).abs() < 1e-12);
}

#[test]
fn torque_json_has_one_result_per_speed() {
    let v = stdout_json(&["servo", "torque", "--speed-rpm", "600,750", "--json"]);
    let r = v["results"].as_array().unwrap();
    assert_eq!(r.len(), 2);
    for (o, n) in r.iter().zip([600.0, 750.0]) {
        assert_eq!(o["speed_rpm"].as_f64().unwrap(), n);
        for k in ["peak_torque_nm", "rms_torque_nm", "peak_power_w"] {
            assert!(o[k].as_f64().unwrap() > 0.0, "{k}");
        }
    }
    assert!(r[1]["peak_torque_nm"].as_f64().unwrap() > r[0]["peak_torque_nm"].as_f64().unwrap());
}

#[test]
fn torque_reads_a_drive_file_and_checks_the_pure_inertia_formula() {
    let f = tmp("drive.toml");
    std::fs::write(&f, "[drive]\nstroke_m = 0.1\nmotion_angle_deg = 180\nmoving_mass_kg = 1\npinion_radius_m = 0.02\n")
        .unwrap();
    let v = stdout_json(&["servo", "torque", "--drive", f.to_str().unwrap(), "--speed-rpm", "600", "--json"]);
    let ca = stdout_json(&["servo", "law", "--json"])["ca"].as_f64().unwrap();
    let t = 0.5 * 60.0 / 600.0;
    let expected = 0.02 * 1.0 * ca * 0.1 / (t * t);
    let got = v["results"][0]["peak_torque_nm"].as_f64().unwrap();
    assert!((got - expected).abs() < 1e-9 * expected, "{got} vs {expected}");
    std::fs::write(&f, "[drive]\nstroke_m = 0.1\nmotion_angle_deg = 180\n").unwrap();
    usage_error(&["servo", "torque", "--drive", f.to_str().unwrap()], &["pinion_radius_m"]);
    std::fs::write(&f, "[drive]\nstroke_mm = 100\n").unwrap();
    usage_error(&["servo", "torque", "--drive", f.to_str().unwrap()], &["drive.toml", "stroke_mm"]);
}

#[test]
fn optimize_json_reports_before_and_after() {
    let v = stdout_json(&["servo", "optimize", "--speed-rpm", "600", "--starts", "2", "--json"]);
    let before = v["before"]["peak_torque_nm"].as_f64().unwrap();
    let after = v["after"]["peak_torque_nm"].as_f64().unwrap();
    assert!(after < 0.9 * before, "{before} → {after}");
    assert!(v["before"]["rms_torque_nm"].as_f64().is_some() && v["after"]["rms_torque_nm"].as_f64().is_some());
    let pts = v["def_points"].as_array().unwrap();
    assert_eq!(pts.len(), 7);
    assert_eq!(pts[0][0].as_f64().unwrap(), 0.0);
    assert_eq!(pts[6][0].as_f64().unwrap(), 0.5);
    // The optimised points feed back into --def and give the reported torque.
    let def = v["def"].as_str().unwrap();
    let t = stdout_json(&["servo", "torque", "--def", def, "--speed-rpm", "600", "--json"]);
    let again = t["results"][0]["peak_torque_nm"].as_f64().unwrap();
    assert!((again - after).abs() < 1e-6 * after, "{again} vs {after}");
    let r = stdout_json(&["servo", "optimize", "--objective", "rms", "--starts", "1", "--fixed-x", "--json"]);
    assert!(r["after"]["rms_torque_nm"].as_f64().unwrap() < r["before"]["rms_torque_nm"].as_f64().unwrap());
}

#[test]
fn export_writes_every_format() {
    for (fmt, first) in [
        ("coeffs", "# loomkin servo"),
        ("json", "{"),
        ("csv", "master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3"),
        ("xyva", "# loomkin cam table"),
        ("poly5", "# loomkin cam table"),
    ] {
        let f = tmp(&format!("out.{fmt}"));
        let out = loomkin()
            .args(["servo", "export", "--def", DEF, "--format", fmt, "-o", f.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(out.status.success(), "{fmt}: {}", String::from_utf8_lossy(&out.stderr));
        let text = std::fs::read_to_string(&f).unwrap();
        assert!(text.starts_with(first), "{fmt}: {}", &text[..60.min(text.len())]);
    }
    let f = tmp("table.csv");
    let v =
        stdout_json(&["servo", "export", "--format", "csv", "--step-deg", "0.5", "-o", f.to_str().unwrap(), "--json"]);
    assert_eq!(v["points"], 721);
    let r = v["reinterpolation"].as_array().unwrap();
    assert_eq!(r.len(), 3);
    let q = r.iter().find(|e| e["interpolation"] == "quintic-hermite").unwrap();
    assert!(q["max_position_error_m"].as_f64().unwrap() < 1e-12);
    // The workbench's names read the same rows: `interpolation[].mode` (the API's
    // `/api/servo/export`) beside `reinterpolation[].interpolation` (this command's).
    assert_eq!(v["interpolation"], v["reinterpolation"]);
    for row in r {
        assert_eq!(row["mode"], row["interpolation"], "{row}");
    }
    let modes: Vec<&str> = v["interpolation"].as_array().unwrap().iter().map(|e| e["mode"].as_str().unwrap()).collect();
    assert_eq!(modes, ["linear", "cubic-spline", "quintic-hermite"]);
    let j = tmp("c.json");
    loomkin().args(["servo", "export", "--format", "json", "-o", j.to_str().unwrap()]).assert().success();
    let e: Value = serde_json::from_str(&std::fs::read_to_string(&j).unwrap()).unwrap();
    let iv = &e["intervals"][0];
    assert_eq!(iv["accel"].as_array().unwrap().len(), 4);
    assert_eq!(iv["velocity"].as_array().unwrap().len(), 5);
    assert_eq!(iv["position"].as_array().unwrap().len(), 6);
    assert!(iv["x_start"].is_number() && iv["x_end"].is_number());
    assert_eq!(e["intervals"].as_array().unwrap().len(), 12);
}

#[test]
fn plot_writes_an_svg() {
    let f = tmp("servo.svg");
    loomkin()
        .args(["servo", "plot", "--speed-rpm", "600,750", "--compare", DEF, "-o", f.to_str().unwrap()])
        .assert()
        .success();
    let svg = std::fs::read_to_string(&f).unwrap();
    assert!(svg.contains("motor torque M [N·m]") && svg.contains("definition points"));
}

#[test]
fn bad_input_is_a_one_line_usage_error() {
    usage_error(&["servo", "law", "--def", "0:0,0.3:0.5,0.2:1,0.5:0"], &["definition point 3", "X must increase"]);
    usage_error(&["servo", "law", "--def", "0:0,0.2:1.5,0.3:1,0.5:0"], &["definition point 2", "[-1, 1]"]);
    usage_error(&["servo", "law", "--def", "0:0,0.2:1,0.5:0"], &["at least 4"]);
    usage_error(&["servo", "law", "--def", "0:0,0.2:1,0.3:x,0.5:0"], &["0.3:x"]);
    usage_error(&["servo", "law", "--def", "0:0,0.2:1,0.3:1,0.5:0.2"], &["definition point 4", "Y = 0"]);
    usage_error(&["servo", "law", "--end", "loose"], &["--end", "possible values: natural, clamped"]);
    usage_error(&["servo", "torque", "--speed-rpm=-600"], &["speed"]);
    usage_error(&["servo", "torque", "--speed-rpm", "0"], &["speed"]);
    usage_error(&["servo", "torque", "--speed-rpm", "nan"], &["speed"]);
    usage_error(&["servo", "optimize", "--objective", "mean"], &["--objective", "possible values: peak, rms"]);
    usage_error(&["servo", "export", "--format", "pdf", "-o", "-"], &["pdf", "coeffs"]);
    usage_error(&["servo", "export", "--format", "csv", "--step-deg", "0", "-o", "-"], &["step_deg"]);
    usage_error(&["servo", "torque", "--drive", "/nonexistent/drive.toml"], &["/nonexistent/drive.toml"]);
}

/// A design saved by the workbench (TOML or JSON) serves as `--drive FILE`: its drive is read
/// (here a non-default one, checked against the pure-inertia closed form), its points ignored.
#[test]
fn a_workbench_design_file_serves_as_drive_file() {
    use loomkin_web::{DesignFormat, ServoDesign};
    let design =
        ServoDesign { drive: loomkin_servo::Drive::pure_inertia(0.06, 140.0, 0.8, 0.03), ..ServoDesign::default() };
    let ca = stdout_json(&["servo", "law", "--json"])["ca"].as_f64().unwrap();
    let t = (140.0 / 360.0) * 60.0 / 700.0;
    let expected = 0.03 * 0.8 * ca * 0.06 / (t * t);
    for (format, name) in [(DesignFormat::Toml, "design.toml"), (DesignFormat::Json, "design.json")] {
        let f = tmp(name);
        std::fs::write(&f, design.to_text(format).unwrap()).unwrap();
        let v = stdout_json(&["servo", "torque", "--drive", f.to_str().unwrap(), "--speed-rpm", "700", "--json"]);
        let got = v["results"][0]["peak_torque_nm"].as_f64().unwrap();
        assert!((got - expected).abs() < 1e-9 * expected, "{name}: {got} vs {expected}");
        assert_eq!(v["drive"]["stroke_m"].as_f64().unwrap(), 0.06);
    }
}

/// Drive files: keys left out are 0 (gear ratio and efficiency 1); every bad key or value is one
/// line naming the key.
#[test]
fn bad_drive_files_name_the_key() {
    let f = tmp("bad-drive.toml");
    let path = f.to_str().unwrap();
    let base = "[drive]\nstroke_m = 0.1\nmotion_angle_deg = 150\npinion_radius_m = 0.02\nmoving_mass_kg = 1\n";
    for (extra, needles) in [
        ("damping = 3\n", &["drive.damping", "unknown key", "damping_n_s_m"][..]),
        ("efficiency = \"high\"\n", &["drive.efficiency", "a number"][..]),
        ("efficiency = 0\n", &["drive.efficiency = 0", "0.001"][..]),
        ("efficiency = nan\n", &["drive.efficiency is not a finite number"][..]),
        ("gear_ratio = -2\n", &["drive.gear_ratio = -2"][..]),
        ("return_angle_deg = 250\n", &["return 250"][..]),
        ("stroke_m = 0.2\n", &["line 6"][..]),
        ("[extra]\nx = 1\n", &["extra", "unknown top-level key"][..]),
        ("motor_inertia_kg_m2 = inf\n", &["drive.motor_inertia_kg_m2 is not a finite number"][..]),
    ] {
        std::fs::write(&f, format!("{base}{extra}")).unwrap();
        usage_error(&["servo", "torque", "--drive", path], needles);
    }
    std::fs::write(&f, "").unwrap();
    usage_error(&["servo", "torque", "--drive", path], &["no [drive] table"]);
    std::fs::write(&f, "[drive]\nstroke_m = 0.1\nmotion_angle_deg = 150\n").unwrap();
    usage_error(&["servo", "torque", "--drive", path], &["drive.pinion_radius_m = 0"]);
    std::fs::write(&f, "{\"drive\": {\"stroke_m\": \"x\"}}").unwrap();
    usage_error(&["servo", "torque", "--drive", path], &["drive.stroke_m", "a number in m"]);
    std::fs::write(&f, [0xff, 0xfe, 0x00]).unwrap();
    usage_error(&["servo", "torque", "--drive", path], &["bad-drive.toml"]);
    // Left-out keys: no damping, no inertia, gear ratio and efficiency 1 → the pure-inertia torque.
    std::fs::write(&f, base).unwrap();
    let v = stdout_json(&["servo", "torque", "--drive", path, "--speed-rpm", "600", "--json"]);
    let ca = stdout_json(&["servo", "law", "--json"])["ca"].as_f64().unwrap();
    let t = (150.0 / 360.0) * 60.0 / 600.0;
    let expected = 0.02 * 1.0 * ca * 0.1 / (t * t);
    assert!((v["results"][0]["peak_torque_nm"].as_f64().unwrap() - expected).abs() < 1e-9 * expected);
    assert_eq!(v["drive"]["gear_ratio"], 1.0);
    assert_eq!(v["drive"]["efficiency"], 1.0);
}

/// Extreme definition points: readable one-line messages, never a panic or an internal error.
#[test]
fn extreme_points_are_refused_with_readable_messages() {
    usage_error(&["servo", "law", "--def", "0:0,0.1:1e308,0.3:1,0.5:0"], &["definition point 2 [0.1, 1e308]"]);
    usage_error(&["servo", "law", "--def", "0:0,0.2:1e-320,0.3:1e-320,0.5:0", "--json"], &["largest |Y|"]);
    usage_error(&["servo", "law", "--def", "0:0,0.1:0.5,0.10001:1,0.5:0"], &["at least X2 + 0.0001 = 0.1001"]);
    usage_error(&["servo", "law", "--def", "0:0,0.272:0.052,0.353:0.68,0.5:0"], &["net displacement", "f = -0.3"]);
    usage_error(&["servo", "law", "--def", "0:0,0.1:inf,0.3:1,0.5:0"], &["definition point 2", "finite"]);
    // Tiny but valid Y give the same law as Y of order 1.
    let a = stdout_json(&["servo", "law", "--def", "0:0,0.2:1e-9,0.3:1e-9,0.5:0", "--json"]);
    let b = stdout_json(&["servo", "law", "--def", "0:0,0.2:1,0.3:1,0.5:0", "--json"]);
    assert!((a["ca"].as_f64().unwrap() - b["ca"].as_f64().unwrap()).abs() < 1e-9);
    // An unwritable output is exit 1 with the cause once.
    let out =
        loomkin().args(["servo", "export", "--format", "json", "-o", "/nonexistent/dir/x.json"]).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.matches("No such file").count(), 1, "{err}");
}

/// `-o -` puts the table alone on stdout (every line parses as numbers); the report goes to stderr.
#[test]
fn export_to_stdout_keeps_the_table_clean() {
    for extra in [&[][..], &["--json"][..]] {
        let mut args = vec!["servo", "export", "--format", "csv", "--step-deg", "10", "-o", "-"];
        args.extend_from_slice(extra);
        let out = loomkin().args(&args).output().unwrap();
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3")
        );
        // Fixed decimals: no exponent, no negative zero (issue 26).
        let data = text.split_once('\n').unwrap().1;
        assert!(!data.contains('e') && !data.contains("-0,") && !data.contains("-0.0,"), "{data}");
        let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|c| c.parse().unwrap()).collect()).collect();
        // Every 10° from each joint of the law (every 12.5° in the 150° rise and return) and the
        // joints: 0, 10, 12.5, 22.5, 25, … — more than the 37 of a plain 10° grid.
        assert!(rows.len() > 37 && rows.iter().any(|r| r[0] == 12.5), "{}", rows.len());
        assert!(String::from_utf8_lossy(&out.stderr).contains("quintic-hermite"));
    }
}
