//! `--shard I/N`: the N outputs of every sharded command, concatenated in order, are byte-identical
//! to the one-machine output (CSV: header in shard 1 only; JSON: JSON Lines), for N = 1, 3, 7
//! (7 is more shards than some of these runs have rows, so some shards are empty).

use crate::common::{loomkin, usage_error};
use std::path::Path;

fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn run(args: &[String]) -> Vec<u8> {
    let out = loomkin().current_dir(repo()).args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    out.stdout
}

fn with(args: &[&str], more: &[&str]) -> Vec<String> {
    args.iter().chain(more).map(|s| s.to_string()).collect()
}

/// Concatenated shards equal the whole, for CSV and JSON Lines; CSV equals the unsharded CSV.
fn check(args: &[&str], rows: usize) {
    for format in ["--csv", "--json"] {
        let whole = run(&with(args, &[format, "--shard", "1/1"]));
        let lines = whole.iter().filter(|&&b| b == b'\n').count();
        let expected = if format == "--csv" { rows + 1 } else { rows };
        assert_eq!(lines, expected, "{args:?} {format}: {}", String::from_utf8_lossy(&whole));
        if format == "--csv" {
            assert_eq!(run(&with(args, &[format])), whole, "{args:?}: --shard 1/1 differs from the plain CSV");
        } else {
            // Every line is one JSON object.
            for l in String::from_utf8(whole.clone()).unwrap().lines() {
                assert!(serde_json::from_str::<serde_json::Value>(l).unwrap().is_object(), "{l}");
            }
        }
        for n in [3, 7] {
            let mut cat = Vec::new();
            for i in 1..=n {
                cat.extend(run(&with(args, &[format, "--shard", &format!("{i}/{n}")])));
            }
            assert_eq!(
                String::from_utf8_lossy(&cat),
                String::from_utf8_lossy(&whole),
                "{args:?} {format}: {n} shards concatenated differ from the whole"
            );
        }
    }
}

#[test]
fn pick_sweep_shards_concatenate() {
    check(&["pick", "sweep", "play", "--from", "0", "--to", "20", "--points", "5"], 5);
}

#[test]
fn dobby_sweep_shards_concatenate() {
    check(&["dobby", "sweep", "--from", "40", "--to", "50", "--by", "5", "--step-deg", "10"], 3);
}

#[test]
fn shed_table_shards_concatenate() {
    check(&["shed", "table"], 5);
    // fig1 at step 0.1: k1 = 0, 0.1, …, 0.5, each at two motion angles (a law's rows stay together).
    check(&["shed", "table", "--design", "fig1", "--step", "0.1", "--motion-deg", "300,330"], 12);
}

#[test]
fn dyn_sweep_shards_concatenate() {
    check(
        &[
            "dyn",
            "sweep",
            "examples/heald-frame-cycle.toml",
            "--natural-hz",
            "54",
            "--damping-ratio",
            "0.05",
            "--speed-rpm",
            "300:600:100",
        ],
        4,
    );
}

#[test]
fn law_sample_shards_concatenate() {
    check(&["law", "sample", "cycloidal", "--points", "6"], 6);
}

#[test]
fn pick_montecarlo_shards_concatenate_and_merge() {
    let dir = std::env::temp_dir().join(format!("loomkin-mc-shard-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let study = dir.join("study.toml");
    std::fs::write(
        &study,
        "draws = 6\nseed = 3\n[settings]\nspeed_rpm = { dist = \"normal\", mean = 200, sd = 4 }\n\
         play_mm = { dist = \"uniform\", min = 0, max = 10 }\n[limits]\nvelocity_m_s = { max = 19 }\n",
    )
    .unwrap();
    let s = study.to_str().unwrap();
    check(&["pick", "montecarlo", s], 6);
    // The merge: the report from the concatenated shards' CSV is the one-machine report, byte for byte.
    let mut cat = Vec::new();
    for i in 1..=3 {
        cat.extend(run(&with(&["pick", "montecarlo", s, "--csv", "--shard"], &[&format!("{i}/3")])));
    }
    let draws = dir.join("draws.csv");
    std::fs::write(&draws, &cat).unwrap();
    let direct = run(&with(&["pick", "montecarlo", s, "--json"], &[]));
    let merged = run(&with(&["pick", "montecarlo", s, "--json", "--from-draws"], &[draws.to_str().unwrap()]));
    assert_eq!(String::from_utf8_lossy(&merged), String::from_utf8_lossy(&direct));
    let text = run(&with(&["pick", "montecarlo", s], &[]));
    assert_eq!(run(&with(&["pick", "montecarlo", s, "--from-draws"], &[draws.to_str().unwrap()])), text);
    // A missing shard is refused, naming the file.
    std::fs::write(&draws, &cat[..cat.len() / 2]).unwrap();
    let d = draws.to_str().unwrap();
    let out = loomkin().args(["pick", "montecarlo", s, "--from-draws", d]).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("draws.csv"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_shards_are_usage_errors() {
    usage_error(
        &["pick", "sweep", "speed", "--from", "160", "--to", "240", "--points", "3", "--csv", "--shard", "0/3"],
        &["--shard", "I/N"],
    );
    usage_error(&["law", "sample", "cycloidal", "--points", "5", "--csv", "--shard", "4/3"], &["shard"]);
    usage_error(&["shed", "table", "--shard", "1/2"], &["--shard needs --csv or --json"]);
    usage_error(&["dobby", "sweep", "--shard", "x"], &["I/N"]);
}

/// With no spread, every draw of `pick montecarlo` is `pick simulate` at the same settings, exactly.
#[test]
fn montecarlo_with_zero_spread_is_pick_simulate() {
    let dir = std::env::temp_dir().join(format!("loomkin-mc-zero-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let study = dir.join("study.toml");
    std::fs::write(
        &study,
        "draws = 4\nseed = 9\n[settings]\nspeed_rpm = { dist = \"normal\", mean = 220, sd = 0 }\n\
         play_mm = { dist = \"uniform\", min = 15.5, max = 15.5 }\nshuttle_g = 440\n",
    )
    .unwrap();
    let report: serde_json::Value =
        serde_json::from_slice(&run(&with(&["pick", "montecarlo", study.to_str().unwrap(), "--json"], &[]))).unwrap();
    let sim: serde_json::Value = serde_json::from_slice(&run(&with(
        &["pick", "simulate", "--speed-rpm", "220", "--play-mm", "15.5", "--shuttle-g", "440", "--json"],
        &[],
    )))
    .unwrap();
    let results = report["results"].as_array().unwrap();
    for key in ["velocity_m_s", "distance_m", "t_end_s", "accel_peak_m_s2"] {
        let q = results.iter().find(|q| q["name"] == key).unwrap();
        let want = sim[key].as_f64().unwrap();
        for p in q["percentiles"].as_array().unwrap() {
            assert_eq!(p["value"].as_f64().unwrap(), want, "{key}");
        }
        assert_eq!(q["mean"].as_f64().unwrap(), want, "{key}");
        assert_eq!(q["sd"].as_f64().unwrap(), 0.0, "{key}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn dobby_tolerance_shards_concatenate_and_merge() {
    let dir = std::env::temp_dir().join(format!("loomkin-tol-shard-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let study = dir.join("tol.toml");
    std::fs::write(
        &study,
        "draws = 5\nseed = 8\nstep_deg = 10\n[dimensions]\nl6_m = { dist = \"normal\", mean = 0.4, sd = 0.001 }\n\
         cam_a_m = { dist = \"uniform\", min = 0.365, max = 0.367 }\n[limits]\noutput_angle_error_deg = { max = 0.2 }\n",
    )
    .unwrap();
    let s = study.to_str().unwrap();
    check(&["dobby", "tolerance", s], 5);
    let mut cat = Vec::new();
    for i in 1..=7 {
        cat.extend(run(&with(&["dobby", "tolerance", s, "--csv", "--shard"], &[&format!("{i}/7")])));
    }
    let draws = dir.join("draws.csv");
    std::fs::write(&draws, &cat).unwrap();
    let direct = run(&with(&["dobby", "tolerance", s, "--json"], &[]));
    let merged = run(&with(&["dobby", "tolerance", s, "--json", "--from-draws"], &[draws.to_str().unwrap()]));
    assert_eq!(String::from_utf8_lossy(&merged), String::from_utf8_lossy(&direct));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// With no spread the made mechanism is the nominal one: zero output-angle error, and the pressure
/// angle of `dobby analyze` at the same step.
#[test]
fn dobby_tolerance_with_zero_spread_is_the_analysis() {
    let dir = std::env::temp_dir().join(format!("loomkin-tol-zero-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let study = dir.join("tol.toml");
    std::fs::write(
        &study,
        "draws = 2\nseed = 1\nstep_deg = 5\n[dimensions]\nl2_m = { dist = \"normal\", mean = 0.66, sd = 0 }\n",
    )
    .unwrap();
    let r: serde_json::Value =
        serde_json::from_slice(&run(&with(&["dobby", "tolerance", study.to_str().unwrap(), "--json"], &[]))).unwrap();
    let a: serde_json::Value =
        serde_json::from_slice(&run(&with(&["dobby", "analyze", "--step-deg", "5", "--json"], &[]))).unwrap();
    let checks = &a["summary"];
    let want = checks["mu_out_max_deg"].as_f64().unwrap().max(checks["mu_b_max_deg"].as_f64().unwrap());
    let res = r["results"].as_array().unwrap();
    assert_eq!(res[0]["name"], "output_angle_error_deg");
    assert_eq!(res[0]["max"].as_f64().unwrap(), 0.0);
    assert_eq!(res[1]["mean"].as_f64().unwrap(), want);
    std::fs::remove_dir_all(&dir).unwrap();
}
