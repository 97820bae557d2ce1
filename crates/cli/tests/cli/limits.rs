//! Finite by construction and bounded by an estimate: extreme inputs inside the old ranges are
//! either answered with finite numbers or refused in one line naming the input (exit 2), the text
//! and `--json` paths alike; runs estimated beyond about 1 GB or a minute are refused up front
//! with the estimate and the limit.

use crate::common::{loomkin, stdout_json, usage_error};

const HEALD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");

/// Both paths (text and `--json`) refuse, naming every needle.
fn refused_both_ways(args: &[&str], needles: &[&str]) {
    usage_error(args, needles);
    let mut json = args.to_vec();
    json.push("--json");
    usage_error(&json, needles);
}

#[test]
fn tiny_piecewise_levels_give_the_unit_law_in_both_paths() {
    let segs = "segments=0.5:constant:1e-308,0.5:constant:-1e-308";
    let v = stdout_json(&["law", "info", "piecewise", "--param", segs, "--json"]);
    for k in ["cv", "ca", "cj", "cm", "ca_rms"] {
        assert!(v[k].is_number(), "{k}: {v}");
    }
    assert!((v["cv"].as_f64().unwrap() - 2.0).abs() < 1e-12 && (v["ca"].as_f64().unwrap() - 4.0).abs() < 1e-12);
    let out = loomkin().args(["law", "info", "piecewise", "--param", segs]).output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Cv   = max v       = 2.0000000000"), "{text}");
    assert!(text.contains("constant:1e-308") && !text.to_lowercase().contains("inf"), "{text}");
}

#[test]
fn extreme_inputs_inside_the_old_ranges_are_refused_by_name() {
    refused_both_ways(&["law", "info", "modified-trapezoid", "--param", "ramp=1e-20"], &["ramp", "1e-6 ≤ ramp ≤ 0.25"]);
    refused_both_ways(
        &["shed", "law", "dobby", "--motion-deg", "1e-9"],
        &["motion_deg", "allowed 1 ≤ motion_deg ≤ 360 deg"],
    );
    refused_both_ways(&["cycle", HEALD, "--speed-rpm", "5e-324"], &["speed-rpm", "0.001"]);
    // Inside the shaft's range but above the modulator's bound on ω2 (1e4 rad/s): refused by the
    // flag as typed, not by the derived input_speed_rad_s.
    for cmd in ["analyze", "synthesize"] {
        refused_both_ways(
            &["dobby", cmd, "--speed-rpm", "100000"],
            &["--speed-rpm = 100000 is out of range", "≤ --speed-rpm ≤ 95000 rpm"],
        );
    }
}

#[test]
fn runs_beyond_the_budget_are_refused_with_the_estimate() {
    let limit = "the limit is 1 GB and 1 min";
    for (args, field) in [
        (
            &["pick", "sweep", "speed", "--from", "160", "--to", "240", "--points", "1000000000"][..],
            "points = 1000000000",
        ),
        (
            &["dyn", "sweep", HEALD, "--natural-hz", "80", "--speed-rpm", "1:100000:0.01"][..],
            "--speed-rpm = 1:100000:0.01",
        ),
        (&["law", "sample", "cycloidal", "--points", "100000000000", "--json"][..], "points = 100000000000"),
        (&["servo", "law", "--points", "100000000000", "--json"][..], "points = 100000000000"),
        (&["servo", "law", "--sample", "100000000000"][..], "points = 100000000000"),
        (&["cycle", HEALD, "--points", "100000000000", "--csv"][..], "points = 100000000000"),
        (&["cycle", HEALD, "--points", "100000000000", "--json"][..], "points = 100000000000"),
        (&["servo", "optimize", "--starts", "1000000"][..], "starts = 1000000"),
        (&["shed", "table", "--design", "fig1", "--step", "1e-9"][..], "step = 1e-9"),
        (
            &[
                "shed",
                "table",
                "--design",
                "grid",
                "--family",
                "trapezoid",
                "--step",
                "0.1",
                "--motion-deg",
                "1:360:0.00001",
            ][..],
            "--motion-deg = 1:360:0.00001",
        ),
        (&["shed", "pareto", "--design", "fig1", "--step", "1e-9"][..], "step = 1e-9"),
        (&["shed", "best", "--window-deg", "175", "--design", "grid", "--step", "1e-6"][..], "step = 1e-6"),
    ] {
        // The flag as typed, and the flag that lifts the limit.
        usage_error(
            args,
            &[&format!("--{}", field.trim_start_matches('-')), "(estimate)", limit, "(--budget MEMORY,TIME lifts it)"],
        );
    }
}

#[test]
fn streamed_tables_are_the_tables() {
    // CSV and JSON of the same samples carry the same numbers, row for row.
    let out = loomkin().args(["law", "sample", "modified-trapezoid", "--points", "20001"]).output().unwrap();
    assert!(out.status.success());
    let csv = String::from_utf8(out.stdout).unwrap();
    let v = stdout_json(&["law", "sample", "modified-trapezoid", "--points", "20001", "--json"]);
    let pts = v["points"].as_array().unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("x,s,v,a,j"));
    assert_eq!(pts.len(), 20001);
    for (p, line) in pts.iter().zip(lines) {
        let nums: Vec<f64> = line.split(',').map(|t| t.parse().unwrap()).collect();
        for (i, k) in ["x", "s", "v", "a", "j"].iter().enumerate() {
            let j = p[k].as_f64().unwrap();
            assert!((j - nums[i]).abs() <= 1e-15 * j.abs().max(1e-300), "{k}: {j} vs {}", nums[i]);
        }
    }
    assert_eq!(v["law"], "modified-trapezoid");
}

#[test]
fn streamed_shed_tables_are_the_tables() {
    // The table streamed row by row: its JSON, CSV and text agree row for row, and with the
    // shards' concatenation.
    let args = ["shed", "table", "--design", "grid", "--step", "0.1", "--motion-deg", "240,300"];
    let v = stdout_json(&[&args[..], &["--json"]].concat());
    let rows = v["rows"].as_array().unwrap();
    assert!(rows.len() > 20, "{v}");
    let csv = String::from_utf8(loomkin().args(args).arg("--csv").output().unwrap().stdout).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(&header[..5], ["row", "k1", "k2", "k3", "motion_deg"]);
    let body: Vec<&str> = lines.collect();
    assert_eq!(body.len(), rows.len());
    for (r, line) in rows.iter().zip(&body) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells[0], r["row"].to_string());
        let col = |k: &str| cells[header.iter().position(|h| *h == k).unwrap()].parse::<f64>().unwrap();
        for k in ["motion_deg", "window_deg", "peak_accel_m_s2", "peak_jerk_m_s3"] {
            assert_eq!(col(k), r[k].as_f64().unwrap(), "{k}");
        }
    }
    let text = String::from_utf8(loomkin().args(args).output().unwrap().stdout).unwrap();
    assert_eq!(text.lines().count(), rows.len() + 2);
    let mut shards = String::new();
    for i in 1..=3 {
        let out = loomkin().args(args).args(["--csv", "--shard", &format!("{i}/3")]).output().unwrap();
        assert!(out.status.success());
        shards.push_str(&String::from_utf8(out.stdout).unwrap());
    }
    assert_eq!(shards, csv);
}

#[test]
fn studies_of_too_many_draws_are_refused_with_the_estimate() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/");
    for (example, cmd, draws) in
        [("pick-montecarlo.toml", "pick", "100000000"), ("dobby-tolerance.toml", "dobby", "10000000")]
    {
        let text = std::fs::read_to_string(format!("{root}{example}")).unwrap();
        let big: String = text
            .lines()
            .map(|l| if l.starts_with("draws") { format!("draws = {draws}") } else { l.to_string() })
            .collect::<Vec<_>>()
            .join("\n");
        let path = std::env::temp_dir().join(format!("loomkin-limits-{}-{example}", std::process::id()));
        std::fs::write(&path, big).unwrap();
        let sub = if cmd == "pick" { "montecarlo" } else { "tolerance" };
        usage_error(
            &[cmd, sub, path.to_str().unwrap()],
            &[&format!("draws = {draws}"), "(estimate)", "the limit is 1 GB and 1 min"],
        );
        std::fs::remove_file(&path).unwrap();
    }
}

/// Found by the contract audit (docs/design/validation.md): values that reached no check.
#[test]
fn bad_values_are_refused_by_name_not_ignored() {
    // A negative number with a negative exponent is a value, refused by its range, not the
    // short flag `-1`.
    usage_error(&["cycle", HEALD, "--speed-rpm", "-1e-300"], &["--speed-rpm = -1e-300 is out of range", "allowed"]);
    usage_error(&["servo", "torque", "--speed-rpm", "-2.5e-3"], &["--speed-rpm = -0.0025 is out of range"]);
    let v = stdout_json(&["cam", "profile", HEALD, "--follower", "translating", "--offset-mm", "-1.5e-1", "--json"]);
    assert!(v["follower"].as_str().unwrap().contains("offset -0.15 mm"), "{v}");
    // Page settings are read and checked before the run, with or without a plot to write.
    usage_error(&["cycle", HEALD, "--width", "nan"], &["--width is not a finite number", "200 ≤ --width ≤ 8000"]);
    usage_error(
        &["pick", "sweep", "speed", "--from", "160", "--to", "240", "--points", "3", "--dpi", "nan"],
        &["--dpi"],
    );
    usage_error(&["dobby", "plot", "--step-deg", "10", "--height", "0", "-o", "never.svg"], &["--height = 0"]);
    // The rise flags with a cycle file would be ignored: refused.
    // (`--law` itself conflicts with the file in clap.)
    usage_error(&["cam", "table", HEALD, "--format", "csv", "-o", "never.csv", "--law", "harmonic"], &["--law"]);
    for flag in [["--stroke-mm", "50"], ["--motion-deg", "120"], ["--stroke-deg", "20"]] {
        let mut table = vec!["cam", "table", HEALD, "--format", "csv", "-o", "never.csv"];
        table.extend(flag);
        usage_error(&table, &[flag[0], "cannot be combined with a cycle file"]);
        let mut profile = vec!["cam", "profile", HEALD, "--follower", "translating"];
        profile.extend(flag);
        usage_error(&profile, &[flag[0], "cannot be combined with a cycle file"]);
    }
    // Loom data without the carrier speed set no window: refused (with --window-deg clap's
    // `requires` does not fire).
    for flag in ["--reed-width-m", "--cloth-width-m", "--carrier-length-m", "--crossing-range-deg", "--shed-excess"] {
        usage_error(&["shed", "best", "--window-deg", "120", flag, "0.5"], &[flag, "needs --carrier-speed-m-s"]);
    }
    let w = stdout_json(&[
        "shed",
        "best",
        "--carrier-speed-m-s",
        "20",
        "--reed-width-m",
        "1.9",
        "--shed-excess",
        "0.05",
        "--json",
    ]);
    assert!(w["required_window_deg"].as_f64().unwrap() > 0.0, "{w}");
    // A tiny jerk limit is named in short form, not as three hundred zeros.
    let out = loomkin().args(["shed", "best", "--window-deg", "175", "--max-jerk-m-s3", "1e-300"]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("--max-jerk-m-s3 1e-300 (laws") && err.len() < 300, "{err}");
}

/// Options of an output that is not written are refused when given, not ignored.
#[test]
fn options_of_an_output_not_written_are_refused() {
    for flag in [["--chord-tol-mm", "nan"], ["--bore-mm", "20"]] {
        let mut dobby = vec!["dobby", "synthesize", "--step-deg", "10"];
        dobby.extend(flag);
        usage_error(&dobby, &["required", "--dxf"]);
        let mut cam = vec!["cam", "profile", HEALD, "--follower", "translating"];
        cam.extend(flag);
        usage_error(&cam, &["required", "--dxf"]);
    }
    usage_error(
        &["shed", "table", "--design", "table1", "--step", "nan"],
        &["--step applies to --design grid and fig1"],
    );
    usage_error(
        &[
            "dyn",
            "sweep",
            HEALD,
            "--natural-hz",
            "54",
            "--damping-ratio",
            "0.05",
            "--speed-rpm",
            "500:700:100",
            "--residual-limit-pct",
            "nan",
        ],
        &["residual_limit_pct is not a finite number", "0 < residual_limit_pct ≤ 100 %"],
    );
}

/// A command group without its subcommand names the subcommands (clap's own message is the
/// group's description, which reads as if it were the error).
#[test]
fn a_group_without_its_subcommand_names_the_subcommands() {
    usage_error(&[], &["`loomkin` needs a subcommand: one of law, cycle,", "serve"]);
    usage_error(&["law"], &["`loomkin law` needs a subcommand: one of list, info, sample, plot"]);
    usage_error(&["dyn"], &["`loomkin dyn` needs a subcommand", "response", "two-mass"]);
    usage_error(&["shed"], &["`loomkin shed` needs a subcommand", "best", "window"]);
}
