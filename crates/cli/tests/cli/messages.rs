//! Messages that say what they mean (issue 27): numbers in the library's number format, the key
//! and line of a file's mistake, the unit the user typed, only the part of an estimate that passes
//! the limit.

use crate::common::*;

fn examples(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str, text: &str) -> String {
    let path = std::env::temp_dir().join(format!("loomkin-messages-{}-{name}", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

/// The longest run of digits in `text`.
fn longest_digits(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit()).map(str::len).max().unwrap_or(0)
}

/// A streamed table's estimate passes the time limit only: its memory (a buffer) is not printed
/// as "needs about 0 bytes of memory" (read as an overflow on main).
#[test]
fn an_estimate_names_only_what_passes_the_limit() {
    for args in
        [&["law", "sample", "cycloidal", "--points", "4294967297"][..], &["servo", "law", "--points", "4294967297"][..]]
    {
        usage_error(
            args,
            &[
                "--points = 4294967297 needs about",
                "h (estimate); the limit is 1 GB and 1 min (--budget MEMORY,TIME lifts it)",
            ],
        );
        let err = String::from_utf8(loomkin().args(args).output().unwrap().stderr).unwrap();
        assert!(!err.contains("0 bytes") && !err.contains("of memory"), "{err}");
    }
}

/// A key given twice in a study file is named, with its line (on main: "tolerance study:
/// duplicate key", no key, no line).
#[test]
fn a_duplicate_key_is_named_with_its_line() {
    for (cmd, example) in
        [(["dobby", "tolerance"], "dobby-tolerance.toml"), (["pick", "montecarlo"], "pick-montecarlo.toml")]
    {
        let text = std::fs::read_to_string(examples(example)).unwrap();
        let line = text.lines().position(|l| l.starts_with("seed")).unwrap() + 2;
        let doubled = text.replacen("\nseed", "\nseed = 1\nseed", 1);
        let path = scratch(example, &doubled);
        usage_error(&[cmd[0], cmd[1], &path], &[&format!("line {line}, column 1: duplicate key `seed`")]);
        std::fs::remove_file(path).unwrap();
    }
}

/// A cycle's angles in an error are in the number format (on main: a 61-digit length).
#[test]
fn cycle_errors_print_numbers_in_the_number_format() {
    let text = std::fs::read_to_string(examples("heald-frame-cycle.toml")).unwrap();
    for (from, to, words) in [
        ("to_deg = 180", "to_deg = 1e60", vec!["segment[2].to_deg", "length is -1e60°"]),
        ("to_deg = 360", "to_deg = 359.99990000000001", vec!["segment[3].to_deg", "span 359.9999°"]),
    ] {
        assert!(text.contains(from));
        let path = scratch("cycle.toml", &text.replace(from, to));
        let out = loomkin().args(["cycle", &path]).output().unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{err}");
        for w in words {
            assert!(err.contains(w), "lacks {w}: {err}");
        }
        assert!(longest_digits(&err) <= 12, "{err}");
        std::fs::remove_file(path).unwrap();
    }
}

/// `--roller-mm 400` is answered in mm (on main: "a 0.4 m roller … 0.05267 m").
#[test]
fn a_refused_roller_is_named_in_the_unit_typed() {
    let dir = std::env::temp_dir().join(format!("loomkin-messages-{}-cams.dxf", std::process::id()));
    let dxf = dir.to_str().unwrap();
    for (flag, value, words) in [
        ("--roller-mm", "400", ["roller_mm: a 400 mm roller", "the largest roller without undercut is 52.67 mm"]),
        ("--roller-m", "0.4", ["roller_m: a 0.4 m roller", "the largest roller without undercut is 0.05267 m"]),
    ] {
        let out =
            loomkin().args(["dobby", "synthesize", "--dwell-deg", "30", flag, value, "--dxf", dxf]).output().unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{err}");
        let last = err.lines().last().unwrap();
        for w in words {
            assert!(last.contains(w), "lacks {w}: {last}");
        }
        assert!(!std::path::Path::new(dxf).exists(), "an undercut cam is never drawn");
    }
}

/// `loom check` prints the insertion angles as it prints the window's, to 0.01° (on main:
/// `insertion 126.13003095975229° to 233.86996904024772°`).
#[test]
fn loom_check_rounds_the_insertion_angles() {
    let out = loomkin()
        .args(["loom", "check", &examples("shuttle-loom.toml"), "--wif", &examples("twill-2-2.wif")])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let line = text.lines().find(|l| l.starts_with("shed clears the carrier")).expect("the window line");
    assert!(line.contains("insertion 126.13° to 233.87°"), "{line}");
    assert!(longest_digits(line) <= 3, "{line}");
}

/// A plot size that no single flag fixes names both flags (`--width = 200 and --height = 200 px
/// are too small …`; the second lacked its `--`).
#[test]
fn a_size_too_small_both_ways_names_both_flags() {
    let out = std::env::temp_dir().join(format!("loomkin-messages-{}-laws.svg", std::process::id()));
    usage_error(
        &[
            "law",
            "plot",
            "cycloidal",
            "modified-sine",
            "poly345",
            "-o",
            out.to_str().unwrap(),
            "--width",
            "200",
            "--height",
            "200",
        ],
        &["--width = 200 and --height = 200 px are too small for this figure"],
    );
    assert!(!out.exists());
}

/// A plot size one flag fixes names the least size that lays out and, as the two-flag message
/// does, what does not fit at the size given (issue 27: it named only the size).
#[test]
fn a_size_too_small_one_way_says_what_does_not_fit() {
    let out = std::env::temp_dir().join(format!("loomkin-messages-{}-one.svg", std::process::id()));
    let o = out.to_str().unwrap();
    usage_error(
        &["law", "plot", "cycloidal", "modified-sine", "poly345", "-o", o, "--height", "200"],
        &["--height = 200 is out of range: allowed 435 ≤ --height ≤ 8000 px (at 200 px, ", "runs off the canvas)"],
    );
    usage_error(
        &["dyn", "response", &examples("heald-frame-cycle.toml"), "--natural-hz", "80", "-o", o, "--height", "300"],
        &["--height = 300 is out of range: allowed 436 ≤ --height ≤ 8000 px (at 300 px, the vertical axis of panel"],
    );
    assert!(!out.exists());
}

/// Every output name of a command is checked before anything runs or is written: a bad plot
/// name beside a DXF writes no DXF (`cam profile`), and `drive ripple` refuses a folder that is
/// not there before its run (one line, exit 1).
#[test]
fn outputs_are_checked_before_anything_is_written() {
    let dir = std::env::temp_dir().join(format!("loomkin-messages-{}-outs", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let dxf = dir.join("side.dxf");
    usage_error(
        &[
            "cam",
            "profile",
            &examples("heald-frame-cycle.toml"),
            "--follower",
            "translating",
            "--dxf",
            dxf.to_str().unwrap(),
            "-o",
            dir.join("plot.jpg").to_str().unwrap(),
        ],
        &["--output", "plot.jpg", ".svg or .png"],
    );
    assert!(!dxf.exists(), "the DXF was written before the plot name was refused");
    let missing = dir.join("no-such-folder").join("r.svg");
    let args = [
        "drive",
        "ripple",
        &examples("shuttle-loom.toml"),
        "--wif",
        &examples("twill-2-2.wif"),
        "-o",
        missing.to_str().unwrap(),
    ];
    let out = loomkin().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains("cannot write") && err.contains("r.svg"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A refusal names the flag the user typed and the flag that lifts the limit (`--budget`); a
/// refused value is printed as typed, in its shortest round-trip form, not rounded onto the bound
/// it passes (issue 27).
#[test]
fn a_refusal_names_budget_and_prints_the_value_as_typed() {
    usage_error(
        &["pick", "sweep", "play", "--from", "0", "--to", "60", "--points", "100000000"],
        &["--points = 100000000 needs about", "(--budget MEMORY,TIME lifts it)"],
    );
    usage_error(
        &["dyn", "sweep", &examples("heald-frame-cycle.toml"), "--natural-hz", "54", "--speed-rpm", "1:100000:0.001"],
        &["--speed-rpm = 1:100000:0.001 needs about", "(--budget MEMORY,TIME lifts it)"],
    );
    // The value as typed: 9.999999999999998e-4 is below 0.001, and 1000.0000000000001 above 1000.
    usage_error(
        &["dobby", "analyze", "--speed-rpm", "9.999999999999998e-4"],
        &["--speed-rpm = 0.0009999999999999998 is out of range: allowed 0.001 ≤ --speed-rpm"],
    );
    usage_error(
        &["pick", "simulate", "--checking-kgf", "1000.0000000000001"],
        &["checking_kgf = 1000.0000000000001 is out of range: allowed 0 ≤ checking_kgf ≤ 1000 kgf"],
    );
}

/// `dyn response` holds every sample of every cycle for a table or a plot: a plot of 10⁴ cycles
/// (7.2 million samples, 3.1 GB and a minute measured) and a table of 10⁶ points over 10⁴ cycles are
/// refused by the budget before anything is computed or written, naming both flags (issue 27: the
/// plot ran to 2.8 GB; the table would abort allocating). The summary and JSON hold no samples.
#[test]
fn dyn_response_tables_and_plots_are_held_to_the_budget() {
    let dir = std::env::temp_dir().join(format!("loomkin-dyn-budget-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("r.png");
    let cycle = examples("heald-frame-cycle.toml");
    let base = ["dyn", "response", cycle.as_str(), "--natural-hz", "80"];
    fn with<'a>(base: &[&'a str], more: &[&'a str]) -> Vec<&'a str> {
        base.iter().chain(more).copied().collect()
    }
    usage_error(
        &with(&base, &["--cycles", "10000", "-o", png.to_str().unwrap()]),
        &["--points × --cycles = 721 × 10000 needs about", "(--budget MEMORY,TIME lifts it)"],
    );
    assert!(!png.exists(), "nothing is written when the run is refused");
    usage_error(
        &with(&base, &["--cycles", "10000", "--points", "1000000", "--csv"]),
        &["--points × --cycles = 1000000 × 10000 needs about", "(--budget MEMORY,TIME lifts it)"],
    );
    // Within the budget the same flags run; the summary of 10⁴ cycles holds no samples.
    let out = loomkin().args(with(&base, &["--cycles", "10", "-o", png.to_str().unwrap()])).output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(png.exists());
    let out = loomkin().args(with(&base, &["--cycles", "10000", "--json"])).output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).ok();
}
