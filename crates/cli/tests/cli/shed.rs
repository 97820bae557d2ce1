//! `loomkin shed …`: exit codes, stderr lines and the JSON keys of the contract.

use crate::common::*;

use serde_json::Value;

fn json(args: &[&str]) -> Value {
    let out = loomkin().args(args).output().expect("runs");
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

fn fails_with_2(args: &[&str], needle: &str) {
    let out = loomkin().args(args).output().expect("runs");
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(needle), "{args:?}: stderr {err:?} lacks {needle:?}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: one line on stderr, got {err:?}");
    assert!(out.stdout.is_empty(), "{args:?}: nothing on stdout");
}

const KEYS: [&str; 6] = ["motion_deg", "dwell_deg", "conditional_dwell_deg", "window_deg", "ca", "peak_accel_m_s2"];

#[test]
fn law_json_keys_and_values() {
    let v = json(&["shed", "law", "dobby", "--json"]);
    for k in KEYS {
        assert!(v[k].is_number(), "missing {k}");
    }
    assert_eq!(v["motion_deg"], 300.0);
    assert_eq!(v["dwell_deg"], 60.0);
    let w = v["window_deg"].as_f64().unwrap();
    assert!((w - v["dwell_deg"].as_f64().unwrap() - v["conditional_dwell_deg"].as_f64().unwrap()).abs() < 1e-9);
    // Modified trapezoid: Ca = 4.888; a = Ca·h·(ω/Φ)² with h = 0.1 m, ω = 10π rad/s, Φ = 5π/3.
    assert!((v["ca"].as_f64().unwrap() - 4.8881).abs() < 1e-3);
    let a = 4.888_124_5 * 0.1 * (10.0f64 / (5.0 / 3.0)).powi(2);
    assert!((v["peak_accel_m_s2"].as_f64().unwrap() - a).abs() < 1e-3 * a);
    // Stroke and speed scale the acceleration as h·n².
    let v2 = json(&["shed", "law", "dobby", "--json", "--stroke-mm", "50", "--speed-rpm", "600"]);
    let r = v2["peak_accel_m_s2"].as_f64().unwrap() / v["peak_accel_m_s2"].as_f64().unwrap();
    assert!((r - 2.0).abs() < 1e-9);
    // A lower threshold gives a longer conditional dwell.
    let v3 = json(&["shed", "law", "dobby", "--json", "--threshold", "0.85"]);
    assert!(v3["conditional_dwell_deg"].as_f64().unwrap() > v["conditional_dwell_deg"].as_f64().unwrap());
}

#[test]
fn law_from_a_spec_file() {
    let dir = std::env::temp_dir().join(format!("loomkin-shed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("good.toml");
    std::fs::write(&good, "motion_deg = 180\npositive = \"0.5:sine-ramp:0:1,0.5:cosine-ramp:1:0\"\n").unwrap();
    let v = json(&["shed", "law", "--spec", good.to_str().unwrap(), "--json"]);
    // Same as the basic preset (cycloidal, 180°).
    let b = json(&["shed", "law", "basic", "--json"]);
    for k in KEYS {
        assert!((v[k].as_f64().unwrap() - b[k].as_f64().unwrap()).abs() < 1e-9, "{k}");
    }
    let bad_sum = dir.join("bad_sum.toml");
    std::fs::write(&bad_sum, "motion_deg = 180\npositive = \"0.4:sine-ramp:0:1,0.5:cosine-ramp:1:0\"\n").unwrap();
    fails_with_2(&["shed", "law", "--spec", bad_sum.to_str().unwrap()], "sum to");
    let bad_motion = dir.join("bad_motion.toml");
    std::fs::write(&bad_motion, "motion_deg = 400\npositive = \"1:constant:1\"\n").unwrap();
    fails_with_2(&["shed", "law", "--spec", bad_motion.to_str().unwrap()], "motion_deg");
    fails_with_2(&["shed", "law", "--spec", dir.join("missing.toml").to_str().unwrap()], "cannot read");
    // Inside (0, 360] but so small that the physical peaks overflow: exit 2, never inf in the output.
    let tiny = dir.join("tiny.toml");
    std::fs::write(&tiny, "motion_deg = 1e-300\npositive = \"1:constant:1\"\n").unwrap();
    fails_with_2(&["shed", "law", "--spec", tiny.to_str().unwrap(), "--json"], "motion_deg = 1e-300");
    fails_with_2(&["shed", "table", "--design", "grid", "--motion-deg", "1e-300", "--csv"], "motion_deg = 1e-300");
    let bad_table = dir.join("bad_table.toml");
    std::fs::write(&bad_table, "motion_deg = 300\npositive = [ { length = 1.0, shape = \"linear\" } ]\n").unwrap();
    fails_with_2(&["shed", "law", "--spec", bad_table.to_str().unwrap()], "positive[0]: missing field `from`");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_input_exits_2() {
    fails_with_2(&["shed", "law", "dobby", "--threshold", "0.7"], "threshold");
    fails_with_2(&["shed", "law", "dobby", "--threshold", "0.995"], "threshold");
    fails_with_2(&["shed", "law", "dobby", "--motion-deg", "0"], "motion_deg");
    fails_with_2(&["shed", "law", "dobby", "--motion-deg", "361"], "motion_deg");
    fails_with_2(&["shed", "law", "nonesuch"], "unknown shedding law");
    fails_with_2(&["shed", "best", "--window-deg", "360"], "window_deg");
    fails_with_2(&["shed", "table", "--design", "grid", "--motion-deg", "0:360:30"], "motion_deg");
    fails_with_2(&["shed", "table", "--design", "table1", "--family", "lead-trapezoid"], "parts");
    fails_with_2(&["shed", "plot", "-o", "x.txt", "basic"], "x.txt");
}

#[test]
fn hostile_numbers_name_the_flag_in_one_line() {
    // Negative values reach the range check (not clap's "unexpected argument" with a usage block).
    fails_with_2(&["shed", "law", "dobby", "--threshold", "-1"], "threshold = -1");
    fails_with_2(&["shed", "law", "dobby", "--motion-deg", "-5"], "motion_deg = -5");
    fails_with_2(&["shed", "law", "dobby", "--stroke-mm", "-1"], "stroke_mm = -1");
    fails_with_2(&["shed", "law", "dobby", "--speed-rpm", "-300"], "speed_rpm = -300");
    fails_with_2(&["shed", "law", "dobby", "--threshold", "NaN"], "threshold is not a finite number");
    fails_with_2(&["shed", "law", "dobby", "--speed-rpm", "inf"], "speed_rpm is not a finite number");
    fails_with_2(&["shed", "best", "--window-deg", "-5"], "window_deg = -5");
    fails_with_2(&["shed", "table", "--design", "grid", "--step", "-0.1"], "k.step = -0.1");
    fails_with_2(&["shed", "table", "--design", "grid", "--motion-deg", "-10"], "motion_deg = -10");
    fails_with_2(&["shed", "window", "--carrier-speed-m-s", "-24", "--reed-width-m", "1.8"], "carrier_speed_m_s");
    // Huge values and open bounds print compactly, in the unit of the flag.
    let out = loomkin().args(["shed", "law", "dobby", "--stroke-mm", "1e300"]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("stroke_mm = 1e300") && err.contains("1000 mm") && err.len() < 200, "{err}");
    let out = loomkin().args(["shed", "table", "--design", "grid", "--step", "0"]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("k.step > 0") && err.len() < 200, "{err}");
}

/// `best` over a list of motion angles against brute force over the same family: every row of
/// `shed table` at those angles, the least peak acceleration among those with a window ≥ W.
#[test]
fn best_agrees_with_brute_force_over_the_table() {
    let common = ["--family", "trapezoid", "--step", "0.05", "--min-k", "0.05", "--max-k", "0.9", "--threshold", "0.9"];
    let motions = "200:360:20";
    let mut args = vec!["shed", "table", "--design", "grid", "--motion-deg", motions, "--json"];
    args.extend(common);
    let table = json(&args);
    let rows = table["rows"].as_array().unwrap();
    for w in [120.0, 160.0, 200.0, 240.0] {
        let brute = rows
            .iter()
            .filter(|r| r["window_deg"].as_f64().unwrap() >= w)
            .map(|r| r["peak_accel_m_s2"].as_f64().unwrap())
            .fold(f64::INFINITY, f64::min);
        let ws = format!("{w}");
        let mut args = vec!["shed", "best", "--window-deg", &ws, "--motion-deg", motions, "--json"];
        args.extend(common);
        let b = json(&args);
        assert!(b["window_deg"].as_f64().unwrap() >= w);
        assert_eq!(b["peak_accel_m_s2"].as_f64().unwrap(), brute, "W = {w}");
        // With the angle free the optimum is at least as good, and its window is exactly W
        // unless the angle hits 360°.
        let mut args = vec!["shed", "best", "--window-deg", &ws, "--json"];
        args.extend(common);
        let f = json(&args);
        assert!(f["peak_accel_m_s2"].as_f64().unwrap() <= brute);
        let (fw, fm) = (f["window_deg"].as_f64().unwrap(), f["motion_deg"].as_f64().unwrap());
        assert!((fw - w).abs() < 1e-9 || (fm == 360.0 && fw >= w), "W = {w}: window {fw} at {fm}°");
    }
}

#[test]
fn table_of_presets_reproduces_table3() {
    let v = json(&["shed", "table", "--json"]);
    let rows = v["rows"].as_array().unwrap();
    let paper = [70.0, 105.0, 115.0, 125.0, 140.0];
    assert_eq!(rows.len(), 5);
    for (r, p) in rows.iter().zip(paper) {
        assert!((r["conditional_dwell_deg"].as_f64().unwrap() - p).abs() < 4.2, "{r}");
    }
    let out = loomkin().args(["shed", "table", "--design", "table1", "--csv"]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("row,k1,k2,k3,motion_deg,dwell_deg,conditional_dwell_deg,window_deg"));
    assert!(header.contains("peak_accel_m_s2"));
    assert_eq!(lines.count(), 8);
}

#[test]
fn pareto_and_best() {
    let v = json(&["shed", "pareto", "--json", "--step", "0.1", "--motion-deg", "180:360:30"]);
    let rows = v["rows"].as_array().unwrap();
    assert!(!rows.is_empty());
    // Along the front the window falls and so does the acceleration.
    for w in rows.windows(2) {
        assert!(w[0]["window_deg"].as_f64() >= w[1]["window_deg"].as_f64());
        assert!(w[0]["peak_accel_m_s2"].as_f64() > w[1]["peak_accel_m_s2"].as_f64());
    }
    let b = json(&["shed", "best", "--window-deg", "175", "--json"]);
    for k in KEYS {
        assert!(b[k].is_number(), "missing {k}");
    }
    assert!(b["window_deg"].as_f64().unwrap() >= 175.0 - 1e-9);
    assert!(b["segments"].is_string() && b["definition"]["positive"].is_string());
    assert!(b["definition"]["motion_deg"].is_number());
    // At the dobby preset's own window the optimum needs no more acceleration than the preset.
    let d = json(&["shed", "law", "dobby", "--json"]);
    let dw = format!("{}", d["window_deg"].as_f64().unwrap() - 1e-9);
    let b2 = json(&["shed", "best", "--window-deg", &dw, "--json"]);
    assert!(b2["peak_accel_m_s2"].as_f64().unwrap() <= d["peak_accel_m_s2"].as_f64().unwrap());
    // With a jerk limit the choice respects it.
    let b3 = json(&["shed", "best", "--window-deg", "175", "--max-jerk-m-s3", "3000", "--json"]);
    assert!(b3["peak_jerk_m_s3"].as_f64().unwrap() <= 3000.0);
    assert!(b3["peak_accel_m_s2"].as_f64().unwrap() > b["peak_accel_m_s2"].as_f64().unwrap());
    fails_with_2(&["shed", "best", "--window-deg", "175", "--max-jerk-m-s3", "0"], "max_jerk_m_s3");
    // In loom terms.
    let l = json(&[
        "shed",
        "best",
        "--carrier-speed-m-s",
        "24",
        "--reed-width-m",
        "1.8",
        "--carrier-length-m",
        "0.09",
        "--crossing-range-deg",
        "15",
        "--speed-rpm",
        "250",
        "--json",
    ]);
    let need = l["required_window_deg"].as_f64().unwrap();
    assert!((need - (6.0 * 250.0 * 1.89 / 24.0 + 15.0)).abs() < 1e-9);
    assert!(l["window_deg"].as_f64().unwrap() >= need - 1e-9);
}

#[test]
fn plots_are_written() {
    let dir = std::env::temp_dir().join(format!("loomkin-shed-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("cycle.svg");
    loomkin().args(["shed", "plot", "basic", "smooth", "-o", f.to_str().unwrap()]).assert().success();
    assert!(std::fs::read_to_string(&f).unwrap().contains("<svg"));
    let p = dir.join("front.svg");
    loomkin()
        .args(["shed", "pareto", "--step", "0.1", "--motion-deg", "180:360:30", "-o", p.to_str().unwrap()])
        .assert()
        .success();
    assert!(std::fs::read_to_string(&p).unwrap().contains("<svg"));
    std::fs::remove_dir_all(&dir).ok();
}
