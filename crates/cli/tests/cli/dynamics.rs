//! `loomkin dyn …` run as a user runs it.

use crate::common::*;

const HEALD: &str = "../../examples/heald-frame-cycle.toml";

#[test]
fn response_json_has_the_contract_keys() {
    let v = stdout_json(&[
        "dyn",
        "response",
        HEALD,
        "--speed-rpm",
        "600",
        "--natural-hz",
        "54",
        "--damping-ratio",
        "0.05",
        "--json",
    ]);
    for k in ["residual_amplitude_mm", "peak_dynamic_error_mm", "peak_acceleration_m_s2", "rigidity_ratio"] {
        assert!(v[k].as_f64().is_some_and(f64::is_finite), "key {k} missing in {v}");
    }
    assert!((v["rigidity_ratio"].as_f64().unwrap() - 5.4).abs() < 1e-12);
    assert_eq!(v["rigidity_warning"], true);
    let steady = stdout_json(&[
        "dyn",
        "response",
        HEALD,
        "--speed-rpm",
        "600",
        "--natural-hz",
        "54",
        "--damping-ratio",
        "0.05",
        "--steady",
        "--json",
    ]);
    assert_eq!(steady["start"], "steady");
}

#[test]
fn response_csv_and_sweep_csv_headers() {
    let out = loomkin()
        .args(["dyn", "response", HEALD, "--speed-rpm", "300", "--natural-hz", "60", "--points", "5", "--csv"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("angle_deg,s_mm,x_mm,error_mm,a_m_s2\n"), "{text}");
    assert_eq!(text.lines().count(), 6);
    let out = loomkin()
        .args([
            "dyn",
            "sweep",
            HEALD,
            "--speed-rpm",
            "300:400:50",
            "--natural-hz",
            "60",
            "--damping-ratio",
            "0.1",
            "--csv",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("speed_rpm,residual_amplitude_mm"), "{text}");
    assert_eq!(text.lines().count(), 4);
}

#[test]
fn bad_input_is_one_line_exit_2() {
    let base = ["dyn", "response", HEALD, "--speed-rpm", "600"];
    let with = |extra: &[&'static str]| base.iter().copied().chain(extra.iter().copied()).collect::<Vec<&str>>();
    usage_error(&with(&["--natural-hz", "0"]), &["natural_hz", "natural_hz ≤"]);
    usage_error(&with(&["--natural-hz", "50", "--damping-ratio", "1"]), &["damping_ratio", "< 1"]);
    usage_error(&with(&["--natural-hz", "50", "--steady"]), &["no periodic steady state", "5 ×"]);
    usage_error(&["dyn", "sweep", HEALD, "--speed-rpm", "300:200:10", "--natural-hz", "50"], &["speed_rpm"]);
}

#[test]
fn spectrum_and_compensate() {
    let out = loomkin()
        .args(["dyn", "spectrum", "cycloidal", "modified-trapezoid:ramp=0.2", "--ratio", "1:3:1", "--csv"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 3);
    assert!((rows[0][1] - 50.0).abs() < 1e-9, "cycloid at r = 1: half the stroke");
    assert!(rows[1][1].abs() < 1e-9 && rows[2][1].abs() < 1e-9, "cycloid: zero at r = 2, 3");
    let out = loomkin()
        .args(["dyn", "compensate", HEALD, "--speed-rpm", "600", "--natural-hz", "54", "-o", "-", "--points", "3"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8(out.stdout).unwrap().starts_with("angle_deg,x_mm,s_mm,"));
    let harmonic = std::env::temp_dir().join("loomkin-dyn-harmonic.toml");
    std::fs::write(
        &harmonic,
        std::fs::read_to_string(HEALD).unwrap().replace("law = \"modified-sine\"", "law = \"harmonic\""),
    )
    .unwrap();
    usage_error(
        &["dyn", "compensate", harmonic.to_str().unwrap(), "--speed-rpm", "600", "--natural-hz", "54", "-o", "-"],
        &[
            "no compensating input",
            "x'' jumps",
            "60.0000°",
            "laws of class C2 or higher (cycloidal, poly345, poly4567, modified-trapezoid, modified-sine)",
        ],
    );
    // A 4-5-6-7 rise/dwell/return (C3) at 700 rpm, f_n 40 Hz, ζ 0: rounding at its joints is no jump
    // (it was refused, "x' jumps by 8.7e-14 at 120°").
    let poly4567 = std::env::temp_dir().join("loomkin-dyn-poly4567.toml");
    std::fs::write(
        &poly4567,
        "unit = \"mm\"\nstroke = 50\n[[segment]]\nkind = \"rise\"\nto_deg = 120\nlaw = \"poly4567\"\n[[segment]]\nkind = \
         \"dwell\"\nto_deg = 180\n[[segment]]\nkind = \"return\"\nto_deg = 300\nlaw = \"poly4567\"\n[[segment]]\nkind = \
         \"dwell\"\nto_deg = 360\n",
    )
    .unwrap();
    let out = loomkin()
        .args(["dyn", "compensate", poly4567.to_str().unwrap(), "--speed-rpm", "700", "--natural-hz", "40", "-o", "-"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8(out.stderr).unwrap().contains("designed motion C3, compensated input C1"));
}

#[test]
fn optimize_meets_the_goal_at_300_rpm() {
    let v = stdout_json(&[
        "dyn",
        "optimize",
        HEALD,
        "--speed-rpm",
        "300",
        "--band-pct",
        "10",
        "--natural-hz",
        "54",
        "--damping-ratio",
        "0.05",
        "--json",
    ]);
    assert!(v["improvement_factor"].as_f64().unwrap() >= 10.0, "{v}");
    assert!(v["peak_acceleration_ratio"].as_f64().unwrap() <= 1.1, "{v}");
    assert!(v["residual_amplitude_mm"].as_f64().is_some());
}

/// A two-mass train whose drive is nearly rigid is the single-mass follower of the frame: the frame's
/// peak error agrees with `dyn response` at f_n = √(k₂/m₂)/2π (an independent route through the
/// single-mass solution).
#[test]
fn two_mass_with_a_rigid_drive_is_the_single_mass_frame() {
    let fn_hz = (2.2e6f64 / 20.0).sqrt() / std::f64::consts::TAU;
    let single = stdout_json(&[
        "dyn",
        "response",
        HEALD,
        "--speed-rpm",
        "500",
        "--natural-hz",
        &fn_hz.to_string(),
        "--damping-ratio",
        "0.05",
        "--json",
    ]);
    let two = stdout_json(&[
        "dyn",
        "two-mass",
        HEALD,
        "--speed-rpm",
        "500",
        "--drive-mass-kg",
        "1",
        "--drive-stiffness-n-m",
        "1e12",
        "--frame-mass-kg",
        "20",
        "--frame-stiffness-n-m",
        "2.2e6",
        "--damping-ratio",
        "0.05",
        "--json",
    ]);
    let (a, b) = (single["peak_dynamic_error_mm"].as_f64().unwrap(), two["peak_frame_error_mm"].as_f64().unwrap());
    assert!((a - b).abs() < 1e-4 * a, "single {a} mm vs two-mass {b} mm");
    assert!((two["natural_hz"][0].as_f64().unwrap() - fn_hz).abs() < 1e-4 * fn_hz);
    assert!(two["peak_drive_error_mm"].as_f64().unwrap() < 1e-3 * b);
}

/// A mass so light that the second mode leaves the model's frequency range is refused by name,
/// in one line, with the least mass allowed for the stiffnesses given.
#[test]
fn a_tiny_two_mass_mass_is_named() {
    let run = |m1: &str, m2: &str| {
        vec![
            "dyn".to_string(),
            "two-mass".into(),
            HEALD.into(),
            "--drive-mass-kg".into(),
            m1.into(),
            "--drive-stiffness-n-m".into(),
            "1e6".into(),
            "--frame-mass-kg".into(),
            m2.into(),
            "--frame-stiffness-n-m".into(),
            "1e6".into(),
        ]
    };
    let args = run("1e-300", "10");
    usage_error(&args.iter().map(String::as_str).collect::<Vec<_>>(), &["drive_mass_kg = 1e-300", "allowed", "10⁶ Hz"]);
    let args = run("10", "1e-12");
    usage_error(&args.iter().map(String::as_str).collect::<Vec<_>>(), &["frame_mass_kg = ", "allowed", "kg"]);
}

/// Every `dyn spectrum --csv` column has its own name (issue 27: two parameters of one law, or
/// two cycle files, gave the same name): the parameters given and the file's name are in it, a
/// law given twice is numbered; a plain catalogue law keeps its name.
#[test]
fn spectrum_columns_are_unique_and_say_which_law() {
    let out = loomkin()
        .args([
            "dyn",
            "spectrum",
            "modified-trapezoid:ramp=0.1",
            "modified-trapezoid:ramp=0.2",
            "cycloidal",
            "cycloidal",
            HEALD,
            "--ratio",
            "1:2:1",
            "--damping-ratio",
            "0,0.1",
            "--csv",
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let head: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let unique: std::collections::BTreeSet<&str> = head.iter().copied().collect();
    assert_eq!(unique.len(), head.len(), "{head:?}");
    assert_eq!(head.len(), 1 + 2 * 6);
    for name in [
        "residual_pct_of_stroke_modified-trapezoid_ramp_0.1_zeta_0",
        "residual_pct_of_stroke_modified-trapezoid_ramp_0.2_zeta_0.1",
        "residual_pct_of_stroke_cycloidal_zeta_0",
        "residual_pct_of_stroke_cycloidal_2_zeta_0",
        "residual_pct_of_stroke_heald-frame-cycle_modified-sine_seg1_zeta_0",
        "residual_pct_of_stroke_heald-frame-cycle_modified-trapezoid_seg3_zeta_0.1",
    ] {
        assert!(head.contains(&name), "{name} not in {head:?}");
    }
    // The two parameters give two curves.
    let rows: Vec<Vec<f64>> =
        text.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert!(rows.iter().any(|r| (r[1] - r[3]).abs() > 1e-6), "{rows:?}");
}

/// `dyn spectrum`'s text table keeps its columns aligned for a label longer than the usual 44
/// characters (a cycle file's segment, issue 27): in every line the ζ column ends where the
/// header's does, counted in characters.
#[test]
fn spectrum_text_columns_stay_aligned_for_long_labels() {
    let out = loomkin().args(["dyn", "spectrum", HEALD, "cycloidal"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('(')).collect();
    assert!(lines.iter().any(|l| l.contains("heald-frame-cycle.toml #3: modified-trapezoid (ramp=0.125)")), "{text}");
    let widths: Vec<usize> = lines.iter().map(|l| l.chars().count()).collect();
    assert!(widths.iter().all(|w| *w == widths[0]), "{widths:?}\n{text}");
    // The ζ column: the header's "ζ" and each row's value end at the same character.
    let end_of = |l: &str, at: usize| l.chars().take(at).collect::<String>().trim_end().chars().count();
    let zeta_end = lines[0].chars().position(|c| c == 'ζ').unwrap() + 1;
    for l in &lines[1..] {
        assert_eq!(end_of(l, zeta_end), zeta_end, "{l}");
    }
}
