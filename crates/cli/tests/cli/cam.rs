//! `loomkin cam table`, `servo check`, `shed … --emit-cycle`: files written and read as a user does.

use crate::common::*;

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("loomkin-cli-cam-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn ok(args: &[&str]) -> String {
    let out = loomkin().args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn cam_table_writes_every_format_with_fixed_decimals() {
    let cycle = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");
    for f in ["xyvaj", "poly5", "csv", "twincat", "st"] {
        let path = tmp(&format!("t.{f}"));
        let p = path.to_str().unwrap();
        let v = stdout_json(&["cam", "table", cycle, "--format", f, "--step-deg", "7", "-o", p, "--json"]);
        assert!(v["max_position_error_mm"].as_f64().unwrap() > 0.0, "{v}");
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(!text.lines().filter(|l| !l.starts_with('#') && !l.starts_with("(*")).any(|l| l.contains("e-")));
    }
    let text = ok(&["cam", "table", cycle, "--format", "csv", "--step-deg", "7", "-o", "-"]);
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3"));
    // Joints at 60, 180, 240 and inside the laws are points; 7° steps from each, shorter before a joint.
    let xs: Vec<f64> = lines.map(|l| l.split(',').next().unwrap().parse().unwrap()).collect();
    for j in [0.0, 60.0, 67.0, 180.0, 240.0, 247.0, 360.0] {
        assert!(xs.contains(&j), "{j} missing");
    }
}

#[test]
fn cam_table_of_a_single_rise_and_bad_input() {
    let v = stdout_json(&[
        "cam",
        "table",
        "--law",
        "modified-trapezoid",
        "--param",
        "ramp=0.125",
        "--stroke-deg",
        "20",
        "--motion-deg",
        "90",
        "--format",
        "st",
        "--tolerance",
        "0.001",
        "-o",
        tmp("r.st").to_str().unwrap(),
        "--json",
    ]);
    assert!(v["max_position_error_deg"].as_f64().unwrap() <= 0.001, "{v}");
    let st = std::fs::read_to_string(tmp("r.st")).unwrap();
    assert!(st.contains("OF SMC_CAMXYVA := [") && st.contains("(dX := 0.000,"), "{st}");
    let out = tmp("x").to_str().unwrap().to_string();
    usage_error(
        &[
            "cam",
            "table",
            "--law",
            "cycloidal",
            "--stroke-mm",
            "10",
            "--motion-deg",
            "90",
            "--format",
            "xyva",
            "-o",
            &out,
        ],
        &["unknown format 'xyva'"],
    );
    usage_error(
        &[
            "cam",
            "table",
            "--law",
            "cycloidal",
            "--stroke-mm",
            "10",
            "--motion-deg",
            "90",
            "--format",
            "csv",
            "--step-deg",
            "-1",
            "-o",
            &out,
        ],
        &["step_deg = -1"],
    );
    usage_error(
        &[
            "cam",
            "table",
            "--law",
            "cycloidal",
            "--stroke-mm",
            "0",
            "--motion-deg",
            "90",
            "--format",
            "csv",
            "-o",
            &out,
        ],
        &["stroke_mm = 0"],
    );
    usage_error(
        &[
            "cam",
            "table",
            "--law",
            "cycloidal",
            "--stroke-mm",
            "10",
            "--motion-deg",
            "90",
            "--format",
            "csv",
            "--step-deg",
            "1",
            "--tolerance",
            "0.1",
            "-o",
            &out,
        ],
        &["cannot be used with"],
    );
}

#[test]
fn emitted_shedding_cycle_is_read_by_cycle_and_cam_table() {
    let path = tmp("frame.toml");
    let p = path.to_str().unwrap();
    let best = stdout_json(&["shed", "best", "--window-deg", "160", "--json", "--emit-cycle", p]);
    let v = stdout_json(&["cycle", p, "--json"]);
    assert_eq!(v["period_deg"], 720.0);
    let segs = v["segments"].as_array().unwrap();
    assert_eq!(segs.len(), 4, "{v}");
    let pv = segs[0]["peak_acceleration_m_s2"].as_f64().unwrap();
    let want = best["peak_accel_m_s2"].as_f64().unwrap();
    assert!((pv - want).abs() < 1e-9 * want, "{pv} vs {want}");
    stdout_json(&["cam", "table", p, "--format", "xyvaj", "-o", tmp("frame.xyvaj").to_str().unwrap(), "--json"]);
    let law = tmp("law.toml");
    ok(&["shed", "law", "smooth", "--emit-cycle", law.to_str().unwrap()]);
    ok(&["cycle", law.to_str().unwrap()]);
}

#[test]
fn servo_check_reports_checks_and_plots() {
    let axis = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/servo-axis.toml");
    let cycle = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/needle-rack-cycle.toml");
    let v = stdout_json(&["servo", "check", axis, "--cycle", cycle, "--json"]);
    assert_eq!(v["pass"], true);
    let names: Vec<&str> = v["checks"].as_array().unwrap().iter().map(|c| c["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["peak_torque", "rms_torque", "peak_speed", "torque_speed_envelope", "inertia_ratio"]);
    let v = stdout_json(&[
        "servo",
        "check",
        axis,
        "--law",
        "cycloidal",
        "--stroke-mm",
        "80",
        "--motion-deg",
        "150",
        "--speed-rpm",
        "900",
        "--json",
    ]);
    assert_eq!(v["pass"], false);
    let png = tmp("axis.png");
    ok(&["servo", "check", axis, "--cycle", cycle, "-o", png.to_str().unwrap()]);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    usage_error(
        &["servo", "check", axis, "--law", "cycloidal", "--stroke-deg", "30", "--motion-deg", "150"],
        &["load.moving_mass_kg"],
    );
    // The spline law's turn as a cycle file feeds the check and the cam table.
    let sp = tmp("spline.toml");
    ok(&["servo", "export", "--format", "cycle", "-o", sp.to_str().unwrap()]);
    stdout_json(&["servo", "check", axis, "--cycle", sp.to_str().unwrap(), "--json"]);
}
