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
            "xyvb",
            "-o",
            &out,
        ],
        &["invalid value 'xyvb' for '--format", "possible values: xyvaj, poly5, csv, twincat, st, xyva"],
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

#[test]
fn cam_profile_json_keys_sizing_and_points() {
    let cycle = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");
    let v = stdout_json(&[
        "cam",
        "profile",
        cycle,
        "--follower",
        "translating",
        "--max-pressure-deg",
        "30",
        "--roller-radius-mm",
        "15",
        "--json",
    ]);
    for key in [
        "prime_radius_mm",
        "max_pressure_angle_deg",
        "max_pressure_angle_at_deg",
        "min_convex_radius_pitch_mm",
        "undercut",
        "roller_max_mm",
        "points",
    ] {
        assert!(v.get(key).is_some(), "{key} missing: {v}");
    }
    assert!((v["max_pressure_angle_deg"].as_f64().unwrap() - 30.0).abs() < 1e-9);
    assert_eq!(v["undercut"], false);
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 360);
    let rp = v["prime_radius_mm"].as_f64().unwrap();
    for p in pts {
        for k in ["angle_deg", "x_mm", "y_mm", "pressure_angle_deg"] {
            assert!(p[k].as_f64().is_some(), "{k}");
        }
        // the pitch curve never comes inside the prime circle, and reaches it on the first dwell
        let r = p["x_mm"].as_f64().unwrap().hypot(p["y_mm"].as_f64().unwrap());
        assert!(r >= rp - 1e-9);
        assert!(p["pressure_angle_deg"].as_f64().unwrap().abs() <= 30.0 + 1e-9);
    }
    assert!((pts[0]["y_mm"].as_f64().unwrap() - rp).abs() < 1e-9);
    // The same cam from its prime radius has the same largest pressure angle.
    let v2 = stdout_json(&[
        "cam",
        "profile",
        cycle,
        "--follower",
        "translating",
        "--prime-radius-mm",
        &rp.to_string(),
        "--roller-radius-mm",
        "15",
        "--json",
    ]);
    assert!((v2["max_pressure_angle_deg"].as_f64().unwrap() - 30.0).abs() < 1e-9);
}

#[test]
fn cam_profile_csv_dxf_plot_and_law() {
    let cycle = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");
    let text =
        ok(&["cam", "profile", cycle, "--follower", "flat", "--prime-radius-mm", "150", "--csv", "--step-deg", "10"]);
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some(
            "angle_deg,x_mm,y_mm,pressure_angle_deg,curvature_pitch_per_mm,profile_x_mm,profile_y_mm,curvature_profile_per_mm"
        )
    );
    assert_eq!(lines.count(), 36);
    let (d1, d2) = (tmp("p1.dxf"), tmp("p2.dxf"));
    for d in [&d1, &d2] {
        ok(&[
            "cam",
            "profile",
            "--law",
            "cycloidal",
            "--stroke-deg",
            "20",
            "--motion-deg",
            "120",
            "--follower",
            "oscillating",
            "--arm-mm",
            "100",
            "--pivot-mm",
            "120",
            "--roller-radius-mm",
            "8",
            "--conjugate",
            "--dxf",
            d.to_str().unwrap(),
            "-o",
            tmp("p.svg").to_str().unwrap(),
        ]);
    }
    let (a, b) = (std::fs::read(&d1).unwrap(), std::fs::read(&d2).unwrap());
    assert_eq!(a, b, "the same cam must give the same bytes");
    let text = String::from_utf8(a).unwrap();
    for layer in
        ["CAM_PITCH", "CAM_PROFILE", "COUNTER_PITCH", "COUNTER_PROFILE", "BASE_CIRCLE", "CENTRE", "BORE", "PHASE_0"]
    {
        assert!(text.contains(&format!("  8\n{layer}\n")), "{layer}");
    }
    assert!(std::fs::read_to_string(tmp("p.svg")).unwrap().contains("<svg"));
}

#[test]
fn cam_profile_bad_input_names_the_field() {
    let cycle = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");
    let fails = |args: &[&str], field: &str| {
        let out = loomkin().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(field), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    };
    let base = ["cam", "profile", cycle, "--follower"];
    fails(&[&base[..], &["translating", "--prime-radius-mm", "20", "--offset-mm", "25"]].concat(), "prime_radius_mm");
    fails(
        &[&base[..], &["translating", "--prime-radius-mm", "40", "--roller-radius-mm", "40"]].concat(),
        "roller_radius_mm",
    );
    fails(&[&base[..], &["oscillating", "--arm-mm", "100", "--pivot-mm", "120"]].concat(), "unit");
    fails(&[&base[..], &["flat"]].concat(), "prime_radius_mm");
    // a prime radius too small to be represented (was NaN in the JSON before the range floor)
    fails(&[&base[..], &["translating", "--prime-radius-mm", "1e-300", "--json"]].concat(), "prime_radius_mm");
    fails(&[&base[..], &["translating", "--max-pressure-deg", "95"]].concat(), "max_pressure_deg");
    // A roller that undercuts: the angle and the largest roller are named, no DXF is written.
    let out = loomkin()
        .args([
            "cam",
            "profile",
            "--law",
            "cycloidal",
            "--stroke-mm",
            "50",
            "--motion-deg",
            "60",
            "--follower",
            "translating",
            "--prime-radius-mm",
            "40",
            "--roller-radius-mm",
            "30",
            "--json",
            "--dxf",
        ])
        .arg(tmp("u.dxf"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("roller_radius_mm") && err.contains("deg") && err.contains("largest roller"), "{err}");
    // The report is printed all the same (undercut: true), the drawing is not written.
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["undercut"], true);
    assert!(v["undercut_at_deg"].is_number() && v["roller_max_mm"].as_f64().unwrap() < 30.0, "{v}");
    assert!(!tmp("u.dxf").exists());
    // A cycle that does not close.
    let open = tmp("open.toml");
    std::fs::write(&open, "unit = \"mm\"\nstroke = 10\n[[segment]]\nkind = \"rise\"\nto_deg = 360\n").unwrap();
    fails(&["cam", "profile", open.to_str().unwrap(), "--follower", "translating"], "segment");
}

/// Issue 26: sizing an oscillating follower for a largest pressure angle finds a minimum of the
/// pressure angle narrower than the 200-step grid. On the sley example the least reached is
/// 38.35343° near a prime radius of 93.2 mm (between grid points); a target of 38.35344° was refused.
#[test]
fn oscillating_sizing_finds_a_narrow_minimum() {
    let sley = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/sley-cycle.toml");
    let v = stdout_json(&[
        "cam",
        "profile",
        sley,
        "--follower",
        "oscillating",
        "--arm-mm",
        "160",
        "--pivot-mm",
        "190",
        "--roller-radius-mm",
        "20",
        "--conjugate",
        "--max-pressure-deg",
        "38.35344",
        "--json",
    ]);
    let rp = v["prime_radius_mm"].as_f64().unwrap();
    assert!(rp > 93.0 && rp < 93.4, "{rp}");
    // Within the target to the rounding of the bisection's last bracket.
    let p = v["max_pressure_angle_deg"].as_f64().unwrap();
    assert!(p <= 38.35344 + 1e-12 && p > 38.3534, "{p}");
}

/// `cam profile --conjugate` reports each cam (issue 27: one pressure angle and radius for the
/// pair, the main cam's own nowhere): `cams` in JSON, the cam then the counter-cam, whose values
/// the pair's keys are the larger / smaller of; a line per cam in the text.
#[test]
fn a_conjugate_pair_reports_each_cam() {
    let args = [
        "cam",
        "profile",
        "../../examples/heald-frame-cycle.toml",
        "--follower",
        "translating",
        "--offset-mm",
        "10",
        "--conjugate",
        "--prime-radius-mm",
        "60",
        "--roller-radius-mm",
        "6",
    ];
    let mut json = args.to_vec();
    json.push("--json");
    let v = stdout_json(&json);
    let cams = v["cams"].as_array().unwrap();
    assert_eq!(cams.len(), 2);
    assert_eq!((cams[0]["cam"].as_str(), cams[1]["cam"].as_str()), (Some("cam"), Some("counter")));
    let f = |c: &serde_json::Value, k: &str| c[k].as_f64().unwrap();
    let pmax = f(&cams[0], "max_pressure_angle_deg").max(f(&cams[1], "max_pressure_angle_deg"));
    assert_eq!(f(&v, "max_pressure_angle_deg"), pmax);
    assert_eq!(f(&v, "counter_max_pressure_angle_deg"), f(&cams[1], "max_pressure_angle_deg"));
    let rmin = f(&cams[0], "min_convex_radius_pitch_mm").min(f(&cams[1], "min_convex_radius_pitch_mm"));
    assert_eq!(f(&v, "min_convex_radius_pitch_mm"), rmin);
    for c in cams {
        assert_eq!(f(c, "min_convex_radius_profile_mm"), f(c, "min_convex_radius_pitch_mm") - 6.0);
    }
    let out = loomkin().args(args).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("  main cam              pressure angle max"), "{text}");
    assert!(text.contains("  counter-cam           pressure angle max"), "{text}");
    // A single cam has no `cams`.
    let single = stdout_json(&[
        "cam",
        "profile",
        "../../examples/heald-frame-cycle.toml",
        "--follower",
        "translating",
        "--json",
    ]);
    assert!(single.get("cams").is_none());
}
