//! `loomkin law …` and `loomkin cycle …` run as a user runs them.

use crate::common::*;

#[test]
fn info_json_has_the_contract_keys() {
    let v = stdout_json(&["law", "info", "cycloidal", "--json"]);
    for k in ["cv", "ca", "ca_pos", "ca_neg", "cj", "cm", "ca_rms", "continuity"] {
        assert!(v.get(k).is_some(), "key {k} missing in {v}");
    }
    assert!((v["ca"].as_f64().unwrap() - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    assert_eq!(v["continuity"]["class"], 2);
    let v = stdout_json(&["law", "info", "modified-trapezoid", "--param", "ramp=0.25", "--json"]);
    assert!((v["cv"].as_f64().unwrap() - 2.0).abs() < 1e-12, "ramp 1/4 gives the cycloid");
}

#[test]
fn sample_csv_has_n_rows_and_both_ends() {
    let out = loomkin().args(["law", "sample", "poly345", "--points", "5", "--csv"]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("x,s,v,a,j"));
    assert_eq!(lines.len(), 6);
    assert_eq!(lines[1], "0,0,0,0,60");
    assert!(lines[5].starts_with("1,1,0,"));
    let v = stdout_json(&["law", "sample", "harmonic", "--points", "3", "--json"]);
    assert_eq!(v["points"].as_array().unwrap().len(), 3);
    assert!((v["points"][1]["s"].as_f64().unwrap() - 0.5).abs() < 1e-15);
}

#[test]
fn list_covers_the_catalogue() {
    let v = stdout_json(&["law", "list", "--json"]);
    let names: Vec<&str> = v["laws"].as_array().unwrap().iter().map(|l| l["name"].as_str().unwrap()).collect();
    for n in
        ["constant-acceleration", "harmonic", "cycloidal", "poly345", "poly4567", "modified-trapezoid", "modified-sine"]
    {
        assert!(names.contains(&n), "{n}");
    }
}

#[test]
fn plots_are_written() {
    let dir = std::env::temp_dir().join(format!("loomkin-cli-law-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("laws.svg");
    loomkin().args(["law", "plot", "cycloidal", "poly345", "-o"]).arg(&svg).assert().success();
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("poly345") && text.contains("acceleration"));
    let png = dir.join("cycle.png");
    let cycle = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");
    loomkin().args(["cycle", cycle, "-o"]).arg(&png).assert().success();
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn cycle_reports_physical_units() {
    let cycle = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");
    let v = stdout_json(&["cycle", cycle, "--speed-rpm", "600", "--json"]);
    assert_eq!(v["speed_rpm"], 600.0);
    assert!((v["cycle_time_s"].as_f64().unwrap() - 0.1).abs() < 1e-12);
    // Modified-sine rise of 100 mm over 120° at 600 rpm: Cv·h·ω/β.
    let omega = 600.0 * std::f64::consts::TAU / 60.0;
    let want = 4.0 * std::f64::consts::PI / (4.0 + std::f64::consts::PI) * 0.1 * omega / 120f64.to_radians();
    let got = v["segments"][1]["peak_velocity_m_s"].as_f64().unwrap();
    assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
    let out = loomkin().args(["cycle", cycle, "--csv", "--points", "5"]).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("angle_deg,time_s,s_m,v_m_s,a_m_s2,j_m_s3\n"), "{text}");
}

#[test]
fn bad_input_exits_2_with_a_clear_line() {
    usage_error(&["law", "info", "zigzag"], &["unknown law 'zigzag'", "cycloidal"]);
    usage_error(&["law", "info", "modified-trapezoid", "--param", "ramp=0.4"], &["ramp", "0.25"]);
    usage_error(&["law", "info", "cycloidal", "--param", "ramp=0.1"], &["no parameter 'ramp'"]);
    usage_error(&["law", "sample", "cycloidal", "--points", "1"], &["--points", "--points ≥ 2"]);
    usage_error(&["law", "info", "piecewise", "--param", "segments=0.5:constant:1,0.4:constant:-1"], &["sum to 0.9"]);
    usage_error(
        &["law", "info", "piecewise", "--param", "segments=0.5:bogus:1,0.5:constant:-1"],
        &["segments[0]", "sine-ramp"],
    );
    usage_error(&["law", "plot", "cycloidal", "-o", "x.pdf"], &[".svg or .png"]);
    usage_error(&["law", "frobnicate"], &["frobnicate"]);
    usage_error(&["cycle", "/nonexistent/cycle.toml"], &["cannot read"]);
    let dir = std::env::temp_dir().join(format!("loomkin-cli-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("open.toml");
    std::fs::write(
        &f,
        "stroke = 10\n[[segment]]\nkind = \"rise\"\nto_deg = 180\n[[segment]]\nkind = \"return\"\nto_deg = 350\n",
    )
    .unwrap();
    usage_error(&["cycle", f.to_str().unwrap()], &["segment[1].to_deg", "close the cycle"]);
    std::fs::write(&f, "stroke = [").unwrap();
    usage_error(&["cycle", f.to_str().unwrap()], &["cycle file"]);
    std::fs::remove_dir_all(dir).ok();
}
