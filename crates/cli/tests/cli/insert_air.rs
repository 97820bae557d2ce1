//! `loomkin insert projectile` and `insert airjet`: the contract keys, the plot, the refusals.

use crate::common::{loomkin, stdout_json, usage_error};

fn ex(name: &str) -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/").to_string() + name
}

#[test]
fn projectile_json_has_the_contract_keys() {
    let v = stdout_json(&["insert", "projectile", &ex("projectile-loom.toml"), "--wif", &ex("point-24.wif"), "--json"]);
    for key in [
        "projectile_speed_m_s",
        "flight_time_ms",
        "arrival_deg",
        "stored_energy_j",
        "brake_force_n",
        "min_clearance_mm",
        "worst_angle_deg",
    ] {
        assert!(v[key].as_f64().unwrap().is_finite(), "{key}");
    }
    assert_eq!(v["picks"], 48);
    assert_eq!(v["fits_sley_dwell"], true);
    // The launch speed does not depend on the loom's speed; the arrival angle's sweep from the
    // launch scales with it.
    let fast = stdout_json(&["insert", "projectile", &ex("projectile-loom.toml"), "--speed-rpm", "600", "--json"]);
    let f = |v: &serde_json::Value, k: &str| v[k].as_f64().unwrap();
    assert_eq!(f(&v, "projectile_speed_m_s"), f(&fast, "projectile_speed_m_s"));
    let sweep = |v: &serde_json::Value| f(v, "arrival_deg") - f(v, "launch_deg");
    assert!((sweep(&fast) / sweep(&v) - 2.0).abs() < 1e-12);
}

#[test]
fn projectile_plots_and_refuses_a_rapier() {
    let out = std::env::temp_dir().join(format!("loomkin-insert-projectile-{}.svg", std::process::id()));
    let o = loomkin()
        .args(["insert", "projectile", &ex("projectile-loom.toml"), "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("least") && svg.contains("sley back dwell"));
    std::fs::remove_file(&out).ok();
    usage_error(
        &["insert", "projectile", &ex("rapier-loom.toml")],
        &["insertion.kind: the loom's carrier is a rapier"],
    );
    usage_error(
        &["insert", "projectile", &ex("projectile-loom.toml"), "--speed-rpm", "-3"],
        &["--speed-rpm = -3 is out of range"],
    );
}

#[test]
fn airjet_json_has_the_contract_keys() {
    let v = stdout_json(&["insert", "airjet", &ex("airjet-loom.toml"), "--json"]);
    for key in ["arrival_deg", "flight_time_ms", "tip_speed_at_exit_m_s", "relay_open_ms"] {
        assert!(v[key].as_f64().unwrap().is_finite(), "{key}");
    }
    let plan = v["relay_plan"].as_array().unwrap();
    assert_eq!(plan.len(), 20);
    for (i, o) in plan.iter().enumerate() {
        assert_eq!(o["group"], i + 1);
        assert!(o["open_deg"].as_f64().unwrap() < o["close_deg"].as_f64().unwrap());
    }
    let out = std::env::temp_dir().join(format!("loomkin-insert-airjet-{}.svg", std::process::id()));
    let o =
        loomkin().args(["insert", "airjet", &ex("airjet-loom.toml"), "-o", out.to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read_to_string(&out).unwrap().contains("air at the tip"));
    std::fs::remove_file(&out).ok();
    usage_error(&["insert", "airjet", &ex("rapier-loom.toml")], &["insertion.kind: the loom's carrier is a rapier"]);
}
