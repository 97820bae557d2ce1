//! The names the issues give (docs/design/validation.md): every JSON key and CSV header an issue
//! text names, read from the command the issue names it for. Users' scripts rely on these names;
//! a rename fails here by name (the snapshots show the same as a diff among many).

use crate::common::{loomkin, stdout_json};
use serde_json::Value;

fn ex(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Every key anywhere in `v` (objects inside arrays included).
fn keys(v: &Value, out: &mut std::collections::BTreeSet<String>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                out.insert(k.clone());
                keys(x, out);
            }
        }
        Value::Array(a) => a.iter().for_each(|x| keys(x, out)),
        _ => {}
    }
}

fn has_keys(issue: u32, args: &[&str], names: &[&str]) {
    let v = stdout_json(args);
    let mut ks = std::collections::BTreeSet::new();
    keys(&v, &mut ks);
    for n in names {
        assert!(ks.contains(*n), "issue {issue}: `loomkin {}` lacks the key `{n}`", args.join(" "));
    }
}

fn header_starts(issue: u32, args: &[&str], file: Option<&std::path::Path>, want: &str) {
    let out = loomkin().args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    let text = match file {
        Some(f) => std::fs::read_to_string(f).unwrap(),
        None => String::from_utf8(out.stdout).unwrap(),
    };
    let first = text.lines().find(|l| !l.is_empty() && !l.starts_with('#')).unwrap_or("");
    assert!(
        first.starts_with(want),
        "issue {issue}: `loomkin {}` header {first:?} does not start {want:?}",
        args.join(" ")
    );
}

#[test]
fn json_keys_the_issues_name() {
    let heald = ex("heald-frame-cycle.toml");
    let heald = heald.as_str();
    let loom = ex("rapier-loom.toml");
    let twill = ex("twill-2-2.wif");
    has_keys(
        2,
        &["law", "info", "cycloidal", "--json"],
        &["cv", "ca", "ca_pos", "ca_neg", "cj", "cm", "ca_rms", "continuity"],
    );
    has_keys(3, &["servo", "law", "--json"], &["d", "cv", "ca", "cj", "cm"]);
    has_keys(
        3,
        &["servo", "torque", "--speed-rpm", "600,750", "--json"],
        &["results", "speed_rpm", "peak_torque_nm", "rms_torque_nm", "peak_power_w"],
    );
    let o = stdout_json(&["servo", "optimize", "--speed-rpm", "600", "--starts", "2", "--json"]);
    for side in ["before", "after"] {
        for k in ["peak_torque_nm", "rms_torque_nm"] {
            assert!(o[side][k].is_number(), "issue 3: servo optimize {side}.{k}: {o}");
        }
    }
    assert!(o["def_points"][0].as_array().is_some_and(|p| p.len() == 2), "issue 3: def_points [[x, y], …]");
    let f = std::env::temp_dir().join(format!("loomkin-contracts-{}.json", std::process::id()));
    loomkin().args(["servo", "export", "--format", "json", "-o", f.to_str().unwrap()]).assert().success();
    let e: Value = serde_json::from_str(&std::fs::read_to_string(&f).unwrap()).unwrap();
    let iv = &e["intervals"][0];
    assert!(iv["x_start"].is_number() && iv["x_end"].is_number(), "issue 3: intervals[].x_start/x_end");
    for (k, n) in [("accel", 4), ("velocity", 5), ("position", 6)] {
        assert_eq!(iv[k].as_array().map(Vec::len), Some(n), "issue 3: intervals[].{k}");
    }
    let _ = std::fs::remove_file(&f);
    has_keys(4, &["pick", "design", "--json"], &["a_m_s2", "mu_1_s", "tau_s", "t_end_s", "b_s2", "c", "d_m"]);
    has_keys(
        4,
        &["pick", "simulate", "--play-mm", "15.5", "--json"],
        &["t_end_s", "t0_s", "distance_m", "velocity_m_s", "accel_end_m_s2", "accel_peak_m_s2"],
    );
    has_keys(
        5,
        &["dobby", "analyze", "--step-deg", "10", "--json"],
        &[
            "rows",
            "phi2_deg",
            "phi3_deg",
            "phi6_deg",
            "s53_m",
            "omega3_rad_s",
            "omega6_rad_s",
            "eps6_rad_s2",
            "summary",
        ],
    );
    has_keys(
        5,
        &["dobby", "synthesize", "--step-deg", "10", "--json"],
        &[
            "rows",
            "phi2_deg",
            "phi6_deg",
            "omega6_rad_s",
            "phi3_deg",
            "s53_m",
            "b_x_m",
            "b_y_m",
            "c_x_m",
            "c_y_m",
            "summary",
        ],
    );
    let shed = ["motion_deg", "dwell_deg", "conditional_dwell_deg", "window_deg", "ca", "peak_accel_m_s2"];
    has_keys(6, &["shed", "law", "dobby", "--json"], &shed);
    has_keys(6, &["shed", "best", "--window-deg", "120", "--json"], &shed);
    has_keys(
        12,
        &[
            "cam",
            "profile",
            heald,
            "--follower",
            "translating",
            "--max-pressure-deg",
            "30",
            "--roller-radius-mm",
            "10",
            "--json",
        ],
        &[
            "prime_radius_mm",
            "max_pressure_angle_deg",
            "max_pressure_angle_at_deg",
            "min_convex_radius_pitch_mm",
            "undercut",
            "roller_max_mm",
            "points",
            "angle_deg",
            "x_mm",
            "y_mm",
            "pressure_angle_deg",
        ],
    );
    has_keys(
        13,
        &["dyn", "response", heald, "--speed-rpm", "600", "--natural-hz", "54", "--damping-ratio", "0.05", "--json"],
        &["residual_amplitude_mm", "peak_dynamic_error_mm", "peak_acceleration_m_s2", "rigidity_ratio"],
    );
    has_keys(
        14,
        &["loom", "check", &loom, "--wif", &twill, "--json"],
        &[
            "frames",
            "stroke_mm",
            "max_strain",
            "picks",
            "peak_torque_n_m",
            "rms_torque_n_m",
            "min_clearance_mm",
            "window_deg",
            "max_speed_rpm",
        ],
    );
}

#[test]
fn csv_headers_the_issues_name() {
    let heald = ex("heald-frame-cycle.toml");
    let heald = heald.as_str();
    header_starts(2, &["law", "sample", "cycloidal", "--points", "3", "--csv"], None, "x,s,v,a,j");
    header_starts(3, &["servo", "law", "--sample", "5", "--csv"], None, "x,s,v,a,j");
    let dir = std::env::temp_dir().join(format!("loomkin-contracts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mm = dir.join("mm.csv");
    header_starts(
        12,
        &["cam", "table", heald, "--format", "csv", "-o", mm.to_str().unwrap()],
        Some(&mm),
        "master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3",
    );
    let deg = dir.join("deg.csv");
    header_starts(
        12,
        &["cam", "table", &ex("sley-cycle.toml"), "--format", "csv", "-o", deg.to_str().unwrap()],
        Some(&deg),
        "master_deg,slave_deg,slave_v_deg_per_deg,slave_a_deg_per_deg2,slave_j_deg_per_deg3",
    );
    header_starts(
        13,
        &["dyn", "response", heald, "--speed-rpm", "600", "--natural-hz", "54", "--damping-ratio", "0.05", "--csv"],
        None,
        "angle_deg,s_mm,x_mm,error_mm,a_m_s2",
    );
    header_starts(
        13,
        &[
            "dyn",
            "sweep",
            heald,
            "--natural-hz",
            "54",
            "--damping-ratio",
            "0.05",
            "--speed-rpm",
            "500:700:100",
            "--csv",
        ],
        None,
        "speed_rpm,residual_amplitude_mm",
    );
    header_starts(
        14,
        &["loom", "torque", &ex("rapier-loom.toml"), "--wif", &ex("plain.wif"), "--csv"],
        None,
        "angle_deg,torque_n_m",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Old spellings kept as hidden aliases (CHANGELOG.md) still run.
#[test]
fn renamed_flags_keep_their_old_spelling() {
    for args in [
        &["servo", "law", "--sample", "3", "--csv"][..],
        &["pick", "sweep", "speed", "--from", "160", "--to", "240", "--steps", "2", "--csv"][..],
        &["dobby", "analyze", "--input-rpm", "60", "--step-deg", "30", "--json"][..],
    ] {
        let out = loomkin().args(args).output().unwrap();
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
}
