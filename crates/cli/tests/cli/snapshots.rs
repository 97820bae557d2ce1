//! Snapshots of every command's `--help`, of each command's `--json`, of every export format and of
//! a DXF drawing's geometry, so a change of wording or format is a diff someone reviews
//! (`crates/cli/tests/snapshots/`).
//!
//! After an intended change (a new flag or command included): `INSTA_UPDATE=always cargo test -p
//! loomkin-cli --test cli snapshots` (or `cargo insta review`), then read the diff of the `.snap`
//! files before committing. The commands below print no paths and no times, so the snapshots are
//! the same on every machine of this kind.

use crate::common::loomkin;
use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// Runs `loomkin ARGS` from the repository root; expects success; returns stdout.
fn stdout(args: &[&str]) -> String {
    // Help is wrapped to the terminal width, read from COLUMNS without a terminal: fix it.
    let out = loomkin().current_dir(repo_root()).env("COLUMNS", "100").args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

fn snap(name: &str, text: &str) {
    insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false, omit_expression => true }, {
        insta::assert_snapshot!(name, text);
    });
}

/// The subcommands listed under `Commands:` in a help text (without `help`).
fn subcommands(help: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in help.lines() {
        if line.starts_with("Commands:") {
            inside = true;
        } else if inside && line.trim().is_empty() {
            break;
        } else if inside
            && let Some(name) = line.split_whitespace().next()
            && name != "help"
            && line.starts_with("  ")
            && !line.starts_with("    ")
        {
            out.push(name.to_string());
        }
    }
    out
}

/// `--help` of every command, found by walking `Commands:` from `loomkin --help` (wrapped at
/// COLUMNS=100). A new command or flag is a new or changed snapshot.
#[test]
fn help_of_every_command() {
    let mut todo = vec![Vec::<String>::new()];
    let mut seen = 0;
    while let Some(path) = todo.pop() {
        let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
        args.push("--help");
        let help = stdout(&args);
        let name = if path.is_empty() { "help".to_string() } else { format!("help__{}", path.join("__")) };
        snap(&name, &help);
        seen += 1;
        for sub in subcommands(&help) {
            let mut p = path.clone();
            p.push(sub);
            todo.push(p);
        }
    }
    assert!(seen > 30, "only {seen} help texts found");
}

/// The geometry of a cam's DXF drawing (its ENTITIES section: layers, polylines, circles), which
/// the writer numbers in a fixed order.
#[test]
fn dxf_geometry() {
    let file = std::env::temp_dir().join(format!("loomkin-snapshot-{}.dxf", std::process::id()));
    let f = file.to_str().unwrap();
    let args = ["cam", "profile", "examples/heald-frame-cycle.toml", "--follower", "translating"];
    stdout(&[&args[..], &["--roller-radius-mm", "15", "--chord-tol-mm", "0.5", "--dxf", f]].concat());
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::remove_file(&file).ok();
    let start = text.find("ENTITIES").expect("an ENTITIES section");
    let end = start + text[start..].find("ENDSEC").expect("its end");
    snap("export__cam_dxf_entities", &text[start..end]);
}

/// `--json` of each command (small inputs; deterministic: optimisers with one start).
#[test]
fn json_of_each_command() {
    let cases: &[(&str, &[&str])] = &[
        ("law_list", &["law", "list", "--json"]),
        ("law_info", &["law", "info", "modified-trapezoid", "--param", "ramp=0.1", "--json"]),
        ("law_sample", &["law", "sample", "cycloidal", "--points", "5", "--json"]),
        ("cycle", &["cycle", "examples/heald-frame-cycle.toml", "--points", "5", "--json"]),
        ("servo_law", &["servo", "law", "--def", "0:0,0.1:0.9,0.25:1,0.4:0.6,0.5:0", "--json"]),
        ("servo_law_points", &["servo", "law", "--points", "5", "--json"]),
        ("servo_torque", &["servo", "torque", "--drive", "examples/needle-rack-drive.toml", "--json"]),
        ("servo_optimize", &["servo", "optimize", "--starts", "1", "--fixed-x", "--json"]),
        (
            "servo_check",
            &[
                "servo",
                "check",
                "examples/servo-axis.toml",
                "--law",
                "cycloidal",
                "--stroke-mm",
                "80",
                "--motion-deg",
                "150",
                "--speed-rpm",
                "750",
                "--json",
            ],
        ),
        ("shed_list", &["shed", "list", "--json"]),
        ("shed_law", &["shed", "law", "dobby", "--json"]),
        ("shed_law_spec", &["shed", "law", "--spec", "examples/shedding-law.toml", "--json"]),
        ("shed_table", &["shed", "table", "--json"]),
        ("shed_pareto", &["shed", "pareto", "--design", "table1", "--motion-deg", "300", "--json"]),
        ("shed_best", &["shed", "best", "--window-deg", "175", "--design", "table1", "--json"]),
        ("shed_window", &["shed", "window", "--carrier-speed-m-s", "20", "--reed-width-m", "1.9", "--json"]),
        ("pick_design", &["pick", "design", "--json"]),
        ("pick_simulate", &["pick", "simulate", "--json"]),
        ("pick_sweep", &["pick", "sweep", "shuttle", "--from", "380", "--to", "520", "--points", "3", "--json"]),
        ("dobby_analyze", &["dobby", "analyze", "--alpha-deg", "47", "--step-deg", "30", "--json"]),
        ("dobby_synthesize", &["dobby", "synthesize", "--dwell-deg", "30", "--law", "modified-sine", "--json"]),
        ("dobby_sweep", &["dobby", "sweep", "--from", "40", "--to", "60", "--by", "10", "--step-deg", "10", "--json"]),
        (
            "cam_profile",
            &[
                "cam",
                "profile",
                "examples/sley-cycle.toml",
                "--follower",
                "oscillating",
                "--arm-mm",
                "100",
                "--pivot-mm",
                "150",
                "--conjugate",
                "--roller-radius-mm",
                "10",
                "--step-deg",
                "45",
                "--json",
            ],
        ),
        (
            "cam_profile_flat",
            &[
                "cam",
                "profile",
                "--law",
                "cycloidal",
                "--stroke-mm",
                "20",
                "--motion-deg",
                "120",
                "--follower",
                "flat",
                "--prime-radius-mm",
                "60",
                "--step-deg",
                "45",
                "--json",
            ],
        ),
        (
            "dyn_sweep",
            &["dyn", "sweep", HEALD, "--speed-rpm", "300:400:50", "--natural-hz", "60", "--mass-kg", "20", "--json"],
        ),
        (
            "dyn_two_mass",
            &[
                "dyn",
                "two-mass",
                HEALD,
                "--speed-rpm",
                "500",
                "--drive-mass-kg",
                "1",
                "--drive-stiffness-n-m",
                "1e8",
                "--frame-mass-kg",
                "20",
                "--frame-stiffness-n-m",
                "2.2e6",
                "--json",
            ],
        ),
        (
            "loom_torque",
            &[
                "loom",
                "torque",
                "examples/shuttle-loom.toml",
                "--lift-plan",
                "examples/twill-3-1.txt",
                "--step-deg",
                "10",
                "--json",
            ],
        ),
    ];
    for (name, args) in cases {
        snap(&format!("json__{name}"), &stdout(args));
    }
    // A cam table's report names no path; the table goes to a file.
    let file = std::env::temp_dir().join(format!("loomkin-snapshot-cam-{}.csv", std::process::id()));
    let args = [
        "cam",
        "table",
        "--law",
        "cycloidal",
        "--stroke-mm",
        "80",
        "--motion-deg",
        "120",
        "--step-deg",
        "30",
        "--format",
    ];
    let report = stdout(&[&args[..], &["csv", "-o", file.to_str().unwrap(), "--json"]].concat());
    snap("json__cam_table", &report);
    std::fs::remove_file(&file).ok();
}

const HEALD: &str = "examples/heald-frame-cycle.toml";

/// Every export format, written to a file and read back.
#[test]
fn every_export_format() {
    let dir = std::env::temp_dir().join(format!("loomkin-snapshots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for format in ["coeffs", "json", "csv", "xyva", "poly5", "cycle"] {
        let file = dir.join(format!("servo.{format}"));
        stdout(&["servo", "export", "--format", format, "--step-deg", "30", "-o", file.to_str().unwrap()]);
        snap(&format!("export__servo_{format}"), &std::fs::read_to_string(&file).unwrap());
    }
    for format in ["xyvaj", "poly5", "csv", "twincat", "st"] {
        let text = stdout(&[
            "cam",
            "table",
            "--law",
            "cycloidal",
            "--stroke-mm",
            "80",
            "--motion-deg",
            "120",
            "--step-deg",
            "30",
            "--format",
            format,
            "-o",
            "-",
        ]);
        snap(&format!("export__cam_{format}"), &text);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
