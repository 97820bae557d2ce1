//! `loomkin pick …` run as a user runs it: contract keys, exit codes, error lines, outputs.

use crate::common::*;

use serde_json::Value;

fn num(v: &Value, k: &str) -> f64 {
    v[k].as_f64().unwrap_or_else(|| panic!("key {k} missing or not a number in {v}"))
}

#[test]
fn design_json_has_the_contract_keys_and_the_paper_values() {
    let v = stdout_json(&["pick", "design", "--json"]);
    for k in ["a_m_s2", "mu_1_s", "tau_s", "t_end_s", "b_s2", "c", "d_m"] {
        assert!(v[k].is_f64(), "key {k} missing in {v}");
    }
    assert!((num(&v, "a_m_s2") - 690.0).abs() < 0.5);
    assert!((num(&v, "t_end_s") - 0.033).abs() < 1e-4);
    let text = loomkin().args(["pick", "design"]).output().unwrap();
    assert!(String::from_utf8_lossy(&text.stdout).contains("m/s²"));
}

#[test]
fn simulate_json_has_the_contract_keys_and_both_routes_agree() {
    let args = ["pick", "simulate", "--play-mm", "15.5", "--speed-rpm", "210", "--json"];
    let c = stdout_json(&[&args[..], &["--method", "closed"]].concat());
    let o = stdout_json(&[&args[..], &["--method", "ode"]].concat());
    for k in ["t_end_s", "t0_s", "distance_m", "velocity_m_s", "accel_end_m_s2", "accel_peak_m_s2"] {
        let (a, b) = (num(&c, k), num(&o, k));
        assert!((a - b).abs() <= 1e-7 * a.abs().max(b.abs()).max(1e-3), "{k}: {a} vs {b}");
    }
    assert_eq!(c["method"], "closed");
    assert_eq!(o["method"], "ode");
    assert!(num(&c, "t0_s") > 0.0);
}

#[test]
fn designed_setting_gives_the_design() {
    let v = stdout_json(&["pick", "simulate", "--json"]);
    assert!((num(&v, "velocity_m_s") - 17.0).abs() < 1e-9);
    assert!((num(&v, "distance_m") - 0.22).abs() < 1e-10);
}

#[test]
fn simulate_csv_is_the_time_history() {
    let out = loomkin().args(["pick", "simulate", "--csv", "--points", "11", "--strap-cm", "13"]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "t_s,s_m,v_s_m_s,a_s_m_s2,x_m,v_m_s,a_m_s2");
    assert_eq!(lines.len(), 12);
    let last: Vec<f64> = lines[11].split(',').map(|x| x.parse().unwrap()).collect();
    assert!((last[5] - 15.33).abs() < 0.01, "the paper's Fig. 4 velocity: {}", last[5]);
}

#[test]
fn bad_settings_exit_2_with_a_clear_line() {
    usage_error(&["pick", "simulate", "--shuttle-g", "-5"], &["shuttle_g", "-5", "g"]);
    usage_error(&["pick", "simulate", "--strap-cm", "0"], &["strap_cm", "0 < strap_cm < 74"]);
    usage_error(&["pick", "simulate", "--strap-cm", "74"], &["strap_cm"]);
    usage_error(&["pick", "simulate", "--play-mm", "90"], &["play_mm = 90", "beyond the cam's reach"]);
    usage_error(&["pick", "simulate", "--play-mm", "-1"], &["play_mm"]);
    usage_error(&["pick", "simulate", "--speed-rpm", "nan"], &["speed_rpm", "not a finite number"]);
    usage_error(&["pick", "simulate", "--checking-kgf", "-2"], &["checking_kgf"]);
    usage_error(&["pick", "simulate", "--method", "euler"], &["euler"]);
    usage_error(
        &["pick", "sweep", "weight", "--from", "1", "--to", "2", "--steps", "3"],
        &["unknown setting 'weight'"],
    );
    usage_error(&["pick", "sweep", "play", "--from", "0", "--to", "100", "--steps", "3"], &["beyond the cam's reach"]);
    usage_error(&["pick", "sweep", "play", "--from", "0", "--to", "1", "--steps", "0"], &["--points"]);
    usage_error(&["pick", "simulate", "--law", "no-such-law"], &["no-such-law"]);
    usage_error(&["pick", "simulate", "--law", "compound", "--param", "ramp=0.1"], &["--param"]);
    usage_error(&["pick", "simulate", "--param", "ramp=0.1"], &["--param"]);
    usage_error(&["pick", "simulate", "--mechanism", "/nonexistent/m.toml"], &["/nonexistent/m.toml"]);
}

#[test]
fn sweep_csv_and_json() {
    let out = loomkin()
        .args(["pick", "sweep", "checking", "--from", "0", "--to", "10", "--steps", "3", "--csv"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with("checking_kgf,t_end_s,t0_s,distance_m,velocity_m_s,accel_end_m_s2,accel_peak_m_s2"));
    assert_eq!(lines.len(), 4);
    let v = stdout_json(&["pick", "sweep", "speed", "--from", "160", "--to", "240", "--steps", "5", "--json"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 5);
    assert_eq!(num(&rows[0], "speed_rpm"), 160.0);
    assert!(num(&rows[4], "velocity_m_s") > num(&rows[0], "velocity_m_s"));
    assert_eq!(v["unit"], "rpm");
}

#[test]
fn sweep_through_a_resonance_says_so_and_answers() {
    // ψ/μ·200 ≈ 480.9 rev/min: the closed form's denominator vanishes between these points.
    let d = stdout_json(&["pick", "design", "--json"]);
    let n_res = num(&d, "natural_1_s") / num(&d, "mu_1_s") * 200.0;
    let at = format!("{n_res}");
    let out = loomkin().args(["pick", "simulate", "--speed-rpm", &at, "--json"]).output().unwrap();
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("resonance") && err.contains("numerical integration"), "{err}");
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["method"], "ode");
    assert!(v["note"].as_str().unwrap().contains("resonance"));
}

#[test]
fn plots_are_written() {
    let dir = std::env::temp_dir().join(format!("loomkin-pick-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plot = dir.join("pick.svg");
    let out = loomkin().args(["pick", "plot", "--play-mm", "15.5", "-o"]).arg(&plot).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let svg = std::fs::read_to_string(&plot).unwrap();
    assert!(svg.contains("<svg") && svg.contains("actual x"));
    let sweep = dir.join("sweep.svg");
    let out = loomkin()
        .args(["pick", "sweep", "strap", "--from", "13", "--to", "35", "--steps", "12", "-o"])
        .arg(&sweep)
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(std::fs::read_to_string(&sweep).unwrap().contains("strap-loop position"));
    usage_error(&["pick", "plot", "-o", dir.join("p.txt").to_str().unwrap()], &["p.txt"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_catalogue_law_as_the_cam() {
    let out = loomkin().args(["pick", "simulate", "--law", "modified-sine", "--json"]).output().unwrap();
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["method"], "ode");
    assert_eq!(v["end"], "separation", "a rise-to-rest cam releases the shuttle when the picker slows");
    assert!(String::from_utf8_lossy(&out.stderr).contains("modified-sine"));
    let o = stdout_json(&["pick", "simulate", "--law", "modified-sine", "--method", "ode", "--json"]);
    assert_eq!(o["velocity_m_s"], v["velocity_m_s"]);
}

/// `pick design` at a non-paper V, X, X₁, n₁ (flags in the paper's units) against eqs. 18–20
/// evaluated here, and the mechanism constants unchanged by a redesign.
#[test]
fn design_flags_redesign_the_cam() {
    let v = stdout_json(&[
        "pick",
        "design",
        "--velocity-m-s",
        "19.5",
        "--distance-cm",
        "26",
        "--first-stage-cm",
        "7.25",
        "--design-speed-rpm",
        "230",
        "--json",
    ]);
    let (vel, x, x1) = (19.5f64, 0.26f64, 0.0725f64);
    let pi = std::f64::consts::PI;
    let a = vel * vel / (2.0 * x - (pi - 3.0) / (pi / 2.0 - 1.0) * x1);
    let mu = a * ((pi - 3.0) / (2.0 * a * x - vel * vel)).sqrt(); // the second form of eq. 19
    let t_end = vel / a - 1.0 / mu + pi / (2.0 * mu);
    for (k, want) in [("a_m_s2", a), ("mu_1_s", mu), ("tau_s", pi / (2.0 * mu)), ("t_end_s", t_end)] {
        assert!((num(&v, k) / want - 1.0).abs() < 1e-12, "{k}: {} vs {want}", num(&v, k));
    }
    let paper = stdout_json(&["pick", "design", "--json"]);
    for k in ["b_s2", "c", "d_m"] {
        assert_eq!(v[k], paper[k]);
    }
    // The redesigned cam at its own setting gives back V and X; metres and centimetres agree.
    let s = stdout_json(&[
        "pick",
        "simulate",
        "--velocity-m-s",
        "19.5",
        "--distance-m",
        "0.26",
        "--first-stage-m",
        "0.0725",
        "--design-speed-rpm",
        "230",
        "--json",
    ]);
    assert!((num(&s, "velocity_m_s") - vel).abs() < 1e-9 && (num(&s, "distance_m") - x).abs() < 1e-10);
    assert!((num(&s, "t_end_s") - t_end).abs() < 1e-15);
    usage_error(&["pick", "design", "--distance-cm", "5"], &["first_stage_m", "0 < first_stage_m < 0.05 m"]);
    usage_error(&["pick", "design", "--velocity-m-s", "-3"], &["velocity_m_s = -3"]);
}

/// The required velocity V_r = 100/(100 − p)·6·n·s/φ_s from its flags.
#[test]
fn required_velocity_flags() {
    let v = stdout_json(&[
        "pick",
        "simulate",
        "--speed-rpm",
        "185",
        "--retardation-pct",
        "8",
        "--path-m",
        "1.7",
        "--free-shed-deg",
        "130",
        "--json",
    ]);
    // Independent route: the path over the time the shed is open, raised by the retardation.
    let t_open_s = 130.0 / 360.0 * 60.0 / 185.0;
    assert!((num(&v, "required_velocity_m_s") - 1.7 / t_open_s / 0.92).abs() < 1e-12);
    usage_error(&["pick", "simulate", "--retardation-pct", "100"], &["retardation_pct", "< 100 %"]);
    usage_error(&["pick", "simulate", "--free-shed-deg", "0"], &["free_shed_deg"]);
}

/// Inputs the routes cannot follow, and the equilibrium start beyond the cam: exit 2, one line.
#[test]
fn unfollowable_inputs_exit_2() {
    usage_error(&["pick", "simulate", "--strap-cm", "1e-300", "--json"], &["strap_cm = 1e-300", "not finite"]);
    usage_error(
        &["pick", "simulate", "--start", "equilibrium", "--checking-kgf", "1000"],
        &["checking_kgf = 1000", "beyond the cam's reach"],
    );
    usage_error(&["pick", "simulate", "--speed-rpm", "1e308"], &["speed_rpm = 1e308", "100000 rpm"]);
    let out = loomkin().args(["pick", "simulate", "--velocity-m-s", "1e-6", "--json"]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("oscillations"));
}

/// A design flag in cm or the design speed is named as typed, in its unit; the swept setting's own
/// flag is refused (the sweep would overwrite it).
#[test]
fn design_errors_name_the_flag_as_typed() {
    use crate::common::usage_error;
    usage_error(
        &["pick", "design", "--distance-cm", "-1"],
        &["distance_cm = -1 is out of range", "0 < distance_cm", "cm"],
    );
    usage_error(
        &["pick", "design", "--first-stage-cm", "30"],
        &["first_stage_cm = 30 is out of range", "first_stage_cm < 22 cm"],
    );
    usage_error(&["pick", "design", "--distance-m", "-1"], &["distance_m = -1 is out of range"]);
    usage_error(&["pick", "simulate", "--design-speed-rpm", "0"], &["design_speed_rpm = 0 is out of range"]);
    usage_error(
        &["pick", "sweep", "speed", "--from", "160", "--to", "240", "--points", "3", "--speed-rpm", "nan"],
        &["--speed-rpm is what `pick sweep speed` varies"],
    );
    usage_error(
        &["pick", "sweep", "play", "--from", "0", "--to", "10", "--points", "3", "--play-mm", "5"],
        &["--play-mm is what `pick sweep play` varies"],
    );
}
