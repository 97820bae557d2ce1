//! The ends of accepted ranges (issue 27): values a fuzz found accepted that printed NaN are now
//! either computed finitely or refused with the library's range; a small bounded property test
//! walks the corners of the options touched.

use crate::common::*;

const HEALD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml");

/// A mass of 5e-324 kg with a preload printed NaN with exit 0 (on main); it is refused naming the
/// mass and its range, and every corner of (mass, natural frequency, preload) within the ranges
/// answers with finite numbers (the JSON writer refuses a non-finite one with exit 1).
#[test]
fn dyn_response_is_finite_at_every_corner_of_its_ranges() {
    usage_error(
        &[
            "dyn",
            "response",
            HEALD,
            "--speed-rpm",
            "600",
            "--natural-hz",
            "54",
            "--mass-kg",
            "5e-324",
            "--preload-n",
            "300",
        ],
        &["mass_kg = 5e-324", "1e-6 ≤ mass_kg < 1000000 kg"],
    );
    // Corners and a few points between, drawn by a fixed linear congruential sequence.
    let mut seed: u64 = 27;
    let mut next = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let log_between = |u: f64, lo: f64, hi: f64| 10f64.powf(lo.log10() + u * (hi.log10() - lo.log10()));
    let mut cases: Vec<[f64; 3]> = Vec::new();
    for m in [1e-6, 999_999.0] {
        for f in [1e-3, 1e6] {
            for p in [-1e9, 0.0, 1e9] {
                cases.push([m, f, p]);
            }
        }
    }
    for _ in 0..6 {
        let (u, v, w) = (next(), next(), next());
        cases.push([log_between(u, 1e-6, 1e5), log_between(v, 1e-3, 1e6), (2.0 * w - 1.0) * 1e9]);
    }
    for [m, f, p] in cases {
        let (m, f, p) = (format!("{m:e}"), format!("{f:e}"), format!("{p:e}"));
        let args = [
            "dyn",
            "response",
            HEALD,
            "--speed-rpm",
            "600",
            "--natural-hz",
            &f,
            "--mass-kg",
            &m,
            "--preload-n",
            &p,
            "--json",
        ];
        let out = loomkin().args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        // A train stiffness out of range is a usage error naming its field; never NaN, never exit 1.
        assert!(out.status.code() == Some(0) || out.status.code() == Some(2), "{args:?}: {err}");
        assert!(!err.contains("NaN") && !err.contains("internal"), "{args:?}: {err}");
        if out.status.success() {
            let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            assert!(v["summary"].is_object() || v.is_object(), "{args:?}");
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(!text.contains("null") && !text.contains("NaN"), "{args:?}");
        }
    }
}

/// A roller of 1e-308 m drew NaN into the curvature plot (on main); a roller is 0 (a knife edge)
/// or at least a micrometre, said in the unit typed, and the plots at the ends are finite.
#[test]
fn dobby_rollers_at_the_ends_draw_finite_plots() {
    let svg = std::env::temp_dir().join(format!("loomkin-ends-{}.svg", std::process::id()));
    let s = svg.to_str().unwrap();
    usage_error(&["dobby", "plot", "--roller-m", "1e-308", "-o", s], &["roller_m = 1e-308", "1e-6 ≤ roller_m ≤ 10 m"]);
    usage_error(&["dobby", "plot", "--roller-mm", "1e-308", "-o", s], &["--roller-mm = 1e-308", "0.001 ≤ --roller-mm"]);
    for r in ["0", "1e-6", "0.03"] {
        let out = loomkin().args(["dobby", "plot", "--roller-m", r, "-o", s]).output().unwrap();
        assert!(out.status.success(), "{r}: {}", String::from_utf8_lossy(&out.stderr));
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(!text.contains("NaN") && !text.contains("inf"), "roller {r} m: a non-finite number in the SVG");
        std::fs::remove_file(&svg).unwrap();
    }
}

/// A mechanism file's `[required] path_m` of 1e-300 printed `inf` and 310-digit numbers in
/// `pick montecarlo` (issue 27's second fuzz pass); it is refused naming the key and its range in
/// every command that reads the file, and at the range's ends the study prints only finite numbers
/// of at most 17 significant digits (text and JSON).
#[test]
fn a_mechanism_path_at_the_ends_gives_finite_monte_carlo_studies() {
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples");
    let base = std::fs::read_to_string(format!("{examples}/picking-mechanism.toml")).unwrap();
    let study = format!("{examples}/pick-montecarlo.toml");
    assert!(base.contains("\npath_m = 1.53"), "the example's path changed");
    let file = std::env::temp_dir().join(format!("loomkin-ends-mech-{}.toml", std::process::id()));
    let m = file.to_str().unwrap();
    for bad in ["1e-300", "5e-324", "0.0099999", "100.0001"] {
        std::fs::write(&file, base.replace("\npath_m = 1.53", &format!("\npath_m = {bad}"))).unwrap();
        let needles = [format!("path_m = {bad}"), "0.01 ≤ path_m ≤ 100 m".to_string()];
        let needles: Vec<&str> = needles.iter().map(String::as_str).collect();
        usage_error(&["pick", "montecarlo", &study, "--mechanism", m], &needles);
        usage_error(&["pick", "simulate", "--mechanism", m], &needles);
    }
    for end in ["0.01", "100"] {
        std::fs::write(&file, base.replace("\npath_m = 1.53", &format!("\npath_m = {end}"))).unwrap();
        for json in [false, true] {
            let mut args = vec!["pick", "montecarlo", study.as_str(), "--mechanism", m];
            if json {
                args.push("--json");
            }
            let out = loomkin().args(&args).output().unwrap();
            assert!(out.status.success(), "path_m = {end}: {}", String::from_utf8_lossy(&out.stderr));
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(!text.contains("inf") && !text.contains("NaN"), "path_m = {end}: a non-finite number");
            // Significant digits of every number written: at most the 17 of a shortest f64.
            let digits = text
                .split(|c: char| !(c.is_ascii_digit() || c == '.'))
                .map(|t| t.chars().filter(char::is_ascii_digit).skip_while(|c| *c == '0').count())
                .max()
                .unwrap_or(0);
            assert!(digits <= 17, "path_m = {end}: a number of {digits} digits");
        }
    }
    std::fs::remove_file(&file).unwrap();
}
