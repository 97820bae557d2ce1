//! `loomkin insert …`: the budget's lecture example and flags, the rapier's contract keys, the plot,
//! the errors.

use crate::common::{loomkin, stdout_json, usage_error};

fn ex(name: &str) -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/").to_string() + name
}

#[test]
fn budget_without_a_file_is_the_lecture_example() {
    let args = [
        "insert",
        "budget",
        "--reed-width-mm",
        "1150",
        "--carrier-length-mm",
        "300",
        "--window-deg",
        "135",
        "--speed-m-s",
        "13.75",
        "--carrier-mass-g",
        "420",
        "--speed-rpm",
        "180",
        "--json",
    ];
    let v = stdout_json(&args);
    assert!((v["max_picks_per_min"].as_f64().unwrap() - 213.362_068_965_517_24).abs() < 1e-9);
    assert!((v["required_speed_m_s"].as_f64().unwrap() - 11.6).abs() < 1e-12);
    assert!((v["energy_per_pick_j"].as_f64().unwrap() - 39.703_125).abs() < 1e-12);
    assert!((v["drive_power_w"].as_f64().unwrap() - 3.0 * 39.703_125).abs() < 1e-10);
    assert_eq!(v["window_source"], "given");
}

#[test]
fn budget_of_a_loom_file_and_its_overrides() {
    let v = stdout_json(&["insert", "budget", &ex("rapier-loom.toml"), "--json"]);
    assert_eq!((v["window_source"].as_str(), v["window_deg"].as_f64()), (Some("entry_exit"), Some(220.0)));
    assert_eq!(v["reed_width_mm"], 1900.0);
    let v = stdout_json(&["insert", "budget", &ex("rapier-loom.toml"), "--wif", &ex("point-24.wif"), "--json"]);
    assert_eq!(v["window_source"], "clear_shed");
    let check = stdout_json(&["loom", "check", &ex("rapier-loom.toml"), "--wif", &ex("point-24.wif"), "--json"]);
    assert_eq!(v["window_deg"], check["window_deg"]);
    let v = stdout_json(&[
        "insert",
        "budget",
        &ex("rapier-loom.toml"),
        "--window-deg",
        "200",
        "--speed-m-s",
        "20",
        "--json",
    ]);
    assert_eq!((v["window_source"].as_str(), v["window_deg"].as_f64()), (Some("given"), Some(200.0)));
    assert!((v["max_picks_per_min"].as_f64().unwrap() - 20.0 * 200.0 / (6.0 * 1.9)).abs() < 1e-9);
}

#[test]
fn budget_errors_name_the_flag() {
    usage_error(
        &["insert", "budget", "--reed-width-mm", "1150"],
        &["--carrier-length-mm: required without a loom file"],
    );
    usage_error(
        &[
            "insert",
            "budget",
            "--reed-width-mm",
            "1150",
            "--carrier-length-mm",
            "0",
            "--window-deg",
            "400",
            "--speed-m-s",
            "10",
        ],
        &["--window-deg = 400 is out of range: allowed 0.001 ≤ --window-deg < 360 deg"],
    );
    usage_error(
        &["insert", "budget", "--wif", &ex("point-24.wif")],
        &["--wif, --lift-plan: the clear-shed window needs a loom file"],
    );
}

#[test]
fn rapier_json_has_the_contract_keys() {
    let v = stdout_json(&["insert", "rapier", &ex("rapier-loom.toml"), "--wif", &ex("point-24.wif"), "--json"]);
    for key in [
        "transfer_overlap_mm",
        "transfer_relative_speed_m_s",
        "peak_head_speed_m_s",
        "peak_head_acceleration_m_s2",
        "min_clearance_mm",
        "worst_angle_deg",
        "worst_position_mm",
    ] {
        assert!(v[key].as_f64().unwrap().is_finite(), "{key}");
    }
    let pick = v["worst_pick"].as_u64().unwrap();
    assert!((1..=48).contains(&pick), "{pick}");
    assert_eq!(v["picks"], 48);
    // The example's offset reversing points: bringer at 182°, taker at 178°.
    assert!((v["bringer"]["inner_deg"].as_f64().unwrap() - 182.0).abs() < 1e-6);
    assert!((v["taker"]["inner_deg"].as_f64().unwrap() - 178.0).abs() < 1e-6);
    // A speed flag scales the peak acceleration by its square.
    let half = stdout_json(&["insert", "rapier", &ex("rapier-loom.toml"), "--speed-rpm", "250", "--json"]);
    let a = |v: &serde_json::Value| v["peak_head_acceleration_m_s2"].as_f64().unwrap();
    assert!((a(&v) / a(&half) - 4.0).abs() < 1e-9);
}

#[test]
fn rapier_plots_and_refuses_a_shuttle() {
    let out = std::env::temp_dir().join(format!("loomkin-insert-{}.svg", std::process::id()));
    let o =
        loomkin().args(["insert", "rapier", &ex("rapier-loom.toml"), "-o", out.to_str().unwrap()]).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("least") && svg.contains("bringer") && svg.contains("taker"));
    std::fs::remove_file(&out).ok();
    usage_error(&["insert", "rapier", &ex("shuttle-loom.toml")], &["insertion.kind: the loom's carrier is a shuttle"]);
    usage_error(
        &["insert", "rapier", &ex("rapier-loom.toml"), "--speed-rpm", "0"],
        &["--speed-rpm = 0 is out of range"],
    );
}

/// The workbench's routes `POST /api/insert/{budget,rapier,projectile,airjet}` answer what
/// `loomkin insert … --json` prints, key for key and bit for bit, for the examples' rapier,
/// projectile and air-jet looms (issue 30 item 6): both call the same library functions.
#[test]
fn the_workbench_routes_answer_the_cli_json() {
    let text = |name: &str| std::fs::read_to_string(ex(name)).expect("example");
    let wif = text("point-24.wif");
    let pattern = loomkin_web::PatternSource { wif: Some(wif.clone()), lift_plan: None };
    for (kind, file) in [("rapier", "rapier-loom.toml"), ("projectile", "projectile-loom.toml")] {
        for speed in [None, Some(350.0)] {
            let req =
                loomkin_web::CarrierRequest { loom_toml: Some(text(file)), pattern: pattern.clone(), speed_rpm: speed };
            let route = match kind {
                "rapier" => serde_json::to_value(loomkin_web::insert_rapier(&req).expect("rapier")),
                _ => serde_json::to_value(loomkin_web::insert_projectile(&req).expect("projectile")),
            }
            .expect("JSON");
            let mut args =
                vec!["insert".to_string(), kind.into(), ex(file), "--wif".into(), ex("point-24.wif"), "--json".into()];
            if let Some(s) = speed {
                args.extend(["--speed-rpm".into(), s.to_string()]);
            }
            let cli = stdout_json(&args.iter().map(String::as_str).collect::<Vec<_>>());
            assert_eq!(route, cli, "{kind} at {speed:?}");
        }
    }
    let req = loomkin_web::AirjetRequest { loom_toml: Some(text("airjet-loom.toml")), speed_rpm: None };
    let route = serde_json::to_value(loomkin_web::insert_airjet(&req).expect("airjet")).expect("JSON");
    assert_eq!(route, stdout_json(&["insert", "airjet", &ex("airjet-loom.toml"), "--json"]));
    // The budget: a file with the pattern's clear-shed window and a flag over it, and flags alone.
    let req = loomkin_web::BudgetRequest {
        loom_toml: Some(text("rapier-loom.toml")),
        pattern: Some(pattern),
        carrier_mass_g: Some(250.0),
        ..Default::default()
    };
    let route = serde_json::to_value(loomkin_web::insert_budget(&req).expect("budget")).expect("JSON");
    let cli = stdout_json(&[
        "insert",
        "budget",
        &ex("rapier-loom.toml"),
        "--wif",
        &ex("point-24.wif"),
        "--carrier-mass-g",
        "250",
        "--json",
    ]);
    assert_eq!(route["window_source"], "clear_shed");
    assert_eq!(route, cli);
    let req = loomkin_web::BudgetRequest {
        reed_width_mm: Some(1150.0),
        carrier_length_mm: Some(300.0),
        window_deg: Some(135.0),
        speed_m_s: Some(13.75),
        ..Default::default()
    };
    let route = serde_json::to_value(loomkin_web::insert_budget(&req).expect("budget")).expect("JSON");
    let cli = stdout_json(&[
        "insert",
        "budget",
        "--reed-width-mm",
        "1150",
        "--carrier-length-mm",
        "300",
        "--window-deg",
        "135",
        "--speed-m-s",
        "13.75",
        "--json",
    ]);
    assert_eq!(route, cli);
}
