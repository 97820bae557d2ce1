//! `loomkin dobby …` run as a user runs it: contract keys, exit codes, error lines, files.

use crate::common::*;

use serde_json::Value;

fn num(v: &Value, k: &str) -> f64 {
    v[k].as_f64().unwrap_or_else(|| panic!("key {k} missing or not a number in {v}"))
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("loomkin-dobby-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn analyze_json_has_the_contract_keys() {
    let v = stdout_json(&["dobby", "analyze", "--json", "--step-deg", "2"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 181);
    for k in ["phi2_deg", "phi3_deg", "phi6_deg", "s53_m", "omega3_rad_s", "omega6_rad_s", "eps6_rad_s2"] {
        assert!(rows[0][k].is_f64() || rows[0][k].is_i64(), "key {k} missing in {}", rows[0]);
    }
    let s = &v["summary"];
    for k in ["omega6_min_rad_s", "omega6_max_rad_s", "mu_out_max_deg", "mu_b_max_deg", "mu_c_max_deg"] {
        assert!(s[k].is_f64(), "summary key {k} missing");
    }
    // The paper's cam at α = 47°: the output turns once, at 0.598…1.470 × ω2.
    assert!((num(s, "phi6_turn_deg") - 360.0).abs() < 1e-6);
    assert!((num(s, "omega6_min_rad_s") - 0.598).abs() < 1e-3 && (num(s, "omega6_max_rad_s") - 1.470).abs() < 1e-3);
}

#[test]
fn input_rpm_scales_the_rates() {
    let base = stdout_json(&["dobby", "analyze", "--json", "--step-deg", "5"]);
    let fast = stdout_json(&["dobby", "analyze", "--json", "--step-deg", "5", "--input-rpm", "60"]);
    let w2 = std::f64::consts::TAU; // 60 rpm
    let (r0, r1) = (&base["rows"][7], &fast["rows"][7]);
    assert!((num(r1, "omega6_rad_s") - w2 * num(r0, "omega6_rad_s")).abs() < 1e-9);
    assert!((num(r1, "eps6_rad_s2") - w2 * w2 * num(r0, "eps6_rad_s2")).abs() < 1e-8);
    assert_eq!(num(r1, "phi6_deg"), num(r0, "phi6_deg"));
    // Synthesis: the same law at 200 rpm, every row, ω ∝ n and ε ∝ n².
    let base = stdout_json(&["dobby", "synthesize", "--json", "--step-deg", "5", "--law", "poly345"]);
    let fast =
        stdout_json(&["dobby", "synthesize", "--json", "--step-deg", "5", "--law", "poly345", "--input-rpm", "200"]);
    let w2 = 200.0 * std::f64::consts::TAU / 60.0;
    let (r0, r1) = (base["rows"].as_array().unwrap(), fast["rows"].as_array().unwrap());
    for (a, b) in r0.iter().zip(r1) {
        assert_eq!(num(a, "phi6_deg"), num(b, "phi6_deg"));
        for (k, p) in [("omega6_rad_s", 1), ("omega3_rad_s", 1), ("eps6_rad_s2", 2)] {
            assert!((num(b, k) - w2.powi(p) * num(a, k)).abs() <= 1e-12 * w2.powi(p) * (1.0 + num(a, k).abs()), "{k}");
        }
    }
}

#[test]
fn synthesize_json_has_the_contract_keys_and_the_paper_start() {
    let v = stdout_json(&["dobby", "synthesize", "--json"]);
    let rows = v["rows"].as_array().unwrap();
    for k in ["phi2_deg", "phi6_deg", "omega6_rad_s", "phi3_deg", "s53_m", "b_x_m", "b_y_m", "c_x_m", "c_y_m"] {
        assert!(rows[0][k].is_number(), "key {k} missing");
    }
    let r = &rows[90];
    assert!((num(r, "phi6_deg") - 90.0).abs() < 1e-9 && (num(r, "phi3_deg") - 90.0).abs() < 1e-9);
    assert!((num(r, "s53_m") - 0.26).abs() < 1e-12);
    let s = &v["summary"];
    for k in ["rho_b_min_m", "rho_c_min_m", "mu_out_max_deg", "mu_b_max_deg", "mu_c_max_deg", "undercut"] {
        assert!(!s[k].is_null(), "summary key {k} missing");
    }
    assert_eq!(s["undercut"], false);
}

#[test]
fn synthesize_csv_round_trips_through_analyze() {
    let out = loomkin().args(["dobby", "synthesize", "--csv", "--step-deg", "0.5"]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("phi2_deg,phi6_deg,omega6_rad_s"));
    let path = tmp("cam.csv");
    std::fs::write(&path, &text).unwrap();
    let v = stdout_json(&["dobby", "analyze", "--cam-file", path.to_str().unwrap(), "--json"]);
    // The dwell comes back: ω6 ≈ 0 between φ2 = 70° and 110°.
    let rows = v["rows"].as_array().unwrap();
    for r in &rows[72..=108] {
        assert!(num(r, "omega6_rad_s").abs() < 1e-3, "{r}");
        assert!((num(r, "phi6_deg") - 90.0).abs() < 1e-3);
    }
}

#[test]
fn dxf_and_point_files_are_written() {
    let (dxf, pts) = (tmp("cams.dxf"), tmp("pts.csv"));
    let out = loomkin()
        .args(["dobby", "synthesize", "--dxf", dxf.to_str().unwrap(), "--points-csv", pts.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let d = std::fs::read_to_string(&dxf).unwrap();
    assert_eq!(d.matches("LWPOLYLINE").count(), 6);
    // Read as group-code/value pairs: every polyline is closed (flag 70 bit 1) with its vertices
    // chosen for the 0.01 mm chord tolerance, not the 1° table step (code 90: more than 360), units
    // mm ($INSUNITS 4) in a metric drawing ($MEASUREMENT 1).
    let lines: Vec<&str> = d.lines().map(str::trim).collect();
    let pairs: Vec<(&str, &str)> = lines.chunks(2).map(|c| (c[0], c.get(1).copied().unwrap_or(""))).collect();
    let header = |name: &str| pairs.iter().position(|p| p == &("9", name)).map(|i| pairs[i + 1].1);
    assert_eq!(header("$INSUNITS"), Some("4"));
    assert_eq!(header("$MEASUREMENT"), Some("1"));
    let mut polys = 0;
    for (i, p) in pairs.iter().enumerate() {
        if *p == ("0", "LWPOLYLINE") {
            polys += 1;
            let body = pairs[i + 1..].iter().take_while(|q| q.0 != "0");
            let (mut flag, mut n) = (None, None);
            for q in body {
                match q.0 {
                    "70" if flag.is_none() => flag = q.1.parse::<u32>().ok(),
                    "90" => n = q.1.parse::<usize>().ok(),
                    _ => {}
                }
            }
            assert_eq!(flag.map(|f| f & 1), Some(1), "polyline {polys} not closed");
            assert!(n.is_some_and(|n| n > 360 && n < 7200), "polyline {polys}: {n:?} vertices");
        }
    }
    assert_eq!(polys, 6);
    for layer in ["CAM_CENTRE", "CAM_WALL_LEFT", "COUNTER_CAM_WALL_RIGHT", "CENTRE", "BORE", "PHASE_0", "ROLLER"] {
        assert!(d.contains(layer), "{layer}");
    }
    let p = std::fs::read_to_string(&pts).unwrap();
    assert!(p.starts_with("phi2_deg,b_x_m,b_y_m,b_left_x_m"));
    assert_eq!(p.lines().count(), 361);
}

#[test]
fn plots_are_written() {
    for (what, task) in [("law", "synthesize"), ("cams", "synthesize"), ("cams", "analyze")] {
        let path = tmp(&format!("{what}-{task}.svg"));
        let out = loomkin()
            .args(["dobby", "plot", "--what", what, "--task", task, "--at-deg", "30", "-o", path.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("<svg") && svg.contains(if what == "law" { "ω6" } else { "aria-label=\"D\"" }));
    }
}

#[test]
fn sweep_reports_the_fold_below_the_admissible_alpha() {
    let v = stdout_json(&["dobby", "sweep", "--json", "--step-deg", "2"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 7);
    assert!(rows[0]["syn_error"].as_str().unwrap().contains("fold at roller B"));
    assert!(rows[6]["syn_mu_b_max_deg"].is_f64() && rows[6]["an_omega6_max_rad_s"].is_f64());
}

#[test]
fn bad_input_is_one_line_with_exit_code_2() {
    usage_error(&["dobby", "analyze", "--l6-m", "0.2"], &["slot misses the output crank", "φ2 ="]);
    usage_error(&["dobby", "analyze", "--l6-m", "0.3", "--alpha-deg", "60"], &["admissible α ∈ ["]);
    usage_error(&["dobby", "analyze", "--cam", "ellipse:a=0.1,b=0.1"], &["cannot reach cam Γ"]);
    usage_error(&["dobby", "analyze", "--cam", "circle:r=1"], &["ellipse:a="]);
    usage_error(&["dobby", "synthesize", "--dwell-deg", "120"], &["admissible range", "dwell must be <"]);
    usage_error(&["dobby", "synthesize", "--alpha-deg", "30"], &["fold at roller B", "admissible α ∈ (35.8"]);
    usage_error(&["dobby", "synthesize", "--step-deg", "0"], &["step_deg"]);
    usage_error(&["dobby", "synthesize", "--law", "nope"], &["unknown law"]);
    usage_error(&["dobby", "analyze", "--input-rpm", "-5"], &["--speed-rpm"]);
    usage_error(&["dobby", "analyze", "--cam-file", "/nonexistent/cam.csv"], &["cannot read"]);
    let bad = tmp("bad.csv");
    std::fs::write(&bad, "x_m,y_m\n0,0\n1,zz\n").unwrap();
    usage_error(&["dobby", "analyze", "--cam-file", bad.to_str().unwrap()], &["line 3"]);
    // Malformed or hostile point tables: each exit 2 with the reason.
    for (name, text, needle) in [
        ("empty.csv", "", "at least 8 distinct points"),
        ("few.csv", "0.3,0\n0,0.5\n-0.3,0\n", "at least 8 distinct points"),
        ("nan.csv", "x_m,y_m\n0.3,nan\n", "not a finite number"),
        ("onecol.csv", "0.1\n0.2\n", "column 2"),
        ("mm.csv", "x_m,y_m\n366,0\n0,577\n", "metres"),
    ] {
        let f = tmp(name);
        std::fs::write(&f, text).unwrap();
        usage_error(&["dobby", "analyze", "--cam-file", f.to_str().unwrap()], &[needle]);
    }
    usage_error(&["dobby", "analyze", "--input-rpm", "nan"], &["--speed-rpm is not a finite number"]);
    usage_error(&["dobby", "sweep", "--by", "nan"], &["--by is not a finite number"]);
    // Ends outside the lever-angle range are refused before the values are counted (an end of
    // 1e308 overflowed the count and panicked).
    usage_error(&["dobby", "sweep", "--to", "1e308"], &["--to = 1e308 is out of range", "0 < --to < 180"]);
    usage_error(&["dobby", "sweep", "--from", "-1"], &["--from = -1 is out of range"]);
    usage_error(&["dobby", "sweep", "--by", "1e-300"], &["values of α: allowed at most 1000"]);
    for v in ["nan", "inf", "1e300"] {
        usage_error(&["dobby", "plot", "--what", "cams", "--at-deg", v, "-o", "never.svg"], &["--at-deg"]);
    }
    // A slot turned away from O is named as such, with the admissible α.
    usage_error(&["dobby", "analyze", "--alpha-deg", "170"], &["points away from O", "admissible α ∈ [23.4"]);
    for v in ["nan", "inf", "-1", "0"] {
        usage_error(&["dobby", "analyze", "--alpha-deg", v], &["alpha_deg"]);
        usage_error(&["dobby", "synthesize", "--dwell-deg", if v == "0" { "-0.5" } else { v }], &["dwell_deg"]);
        if v != "0" {
            usage_error(&["dobby", "synthesize", "--roller-m", v], &["roller_m"]);
        }
    }
}

#[test]
fn an_unwritable_output_file_is_exit_code_1() {
    let out = loomkin().args(["dobby", "synthesize", "--dxf", "/nonexistent/dir/cams.dxf"]).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("/nonexistent/dir/cams.dxf") && !err.contains("panicked"), "{err}");
}

#[test]
fn undercut_is_a_warning_not_an_error() {
    let out = loomkin().args(["dobby", "synthesize", "--roller-m", "0.08", "--json"]).output().unwrap();
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("warning: undercut of cam Γ"), "{err}");
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["summary"]["undercut"], true);
}

#[test]
fn an_undercut_cam_is_reported_but_never_drawn() {
    // As `cam profile`: with --dxf the report is still printed, the drawing refused (exit 2)
    // naming the roller, the angle and the largest roller.
    let dir = std::env::temp_dir().join(format!("loomkin-dobby-undercut-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let dxf = dir.join("cams.dxf");
    let out =
        loomkin().args(["dobby", "synthesize", "--roller-m", "0.08", "--json", "--dxf"]).arg(&dxf).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("roller_m") && err.contains("φ2 =") && err.contains("largest roller") && err.contains("no DXF"),
        "{err}"
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["summary"]["undercut"], true);
    assert!(!dxf.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_roller_in_mm_is_the_roller_in_m() {
    // `--roller-mm` (the workbench's unit) and `--roller-m` (the first flag) give the same report,
    // for the synthesis, the analysis, the sweep and the plot; both at once is a usage error.
    let mm = stdout_json(&["dobby", "synthesize", "--json", "--step-deg", "5", "--roller-mm", "40"]);
    let m = stdout_json(&["dobby", "synthesize", "--json", "--step-deg", "5", "--roller-m", "0.04"]);
    assert_eq!(mm, m);
    assert_eq!(num(&mm["summary"], "roller_m"), 0.04);
    let default = stdout_json(&["dobby", "synthesize", "--json", "--step-deg", "5"]);
    let thirty = stdout_json(&["dobby", "synthesize", "--json", "--step-deg", "5", "--roller-mm", "30"]);
    assert_eq!(default, thirty, "the default roller is 30 mm");
    let a_mm = stdout_json(&["dobby", "analyze", "--json", "--step-deg", "5", "--roller-mm", "25"]);
    let a_m = stdout_json(&["dobby", "analyze", "--json", "--step-deg", "5", "--roller-m", "0.025"]);
    assert_eq!(a_mm, a_m);
    let s_mm = stdout_json(&["dobby", "sweep", "--json", "--step-deg", "5", "--by", "15", "--roller-mm", "20"]);
    let s_m = stdout_json(&["dobby", "sweep", "--json", "--step-deg", "5", "--by", "15", "--roller-m", "0.02"]);
    assert_eq!(s_mm, s_m);
    let text = loomkin().args(["dobby", "synthesize", "--step-deg", "5", "--roller-mm", "40"]).output().unwrap();
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("roller radius        40 mm"), "{text}");
    for cmd in ["analyze", "synthesize", "sweep"] {
        usage_error(&["dobby", cmd, "--roller-mm", "30", "--roller-m", "0.03"], &["cannot be used with"]);
    }
    usage_error(
        &["dobby", "plot", "--roller-mm", "30", "--roller-m", "0.03", "-o", "never.svg"],
        &["cannot be used with"],
    );
    for v in ["nan", "inf", "-1", "1e300"] {
        for cmd in ["analyze", "synthesize", "sweep"] {
            usage_error(&["dobby", cmd, "--roller-mm", v], &["--roller-mm", "mm"]);
        }
        usage_error(&["dobby", "plot", "--roller-mm", v, "-o", "never.svg"], &["--roller-mm"]);
    }
}
