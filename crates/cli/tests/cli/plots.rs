//! Every plot kind at sizes from the least `--width/--height` accept to a poster: each run either
//! draws a figure whose texts (read back from the SVG's glyph outlines, not from the layout) stay
//! on the canvas and off each other, or is refused in one line naming the size that lays out.

use crate::common::loomkin;

fn ex(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// One command per plot kind, without `-o` (light inputs: the layout is what is tested).
fn kinds() -> Vec<Vec<String>> {
    let v = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    vec![
        v(&["law", "plot", "cycloidal", "modified-sine", "poly345"]),
        v(&["cycle", &ex("heald-frame-cycle.toml")]),
        v(&["servo", "plot", "--speed-rpm", "600,750"]),
        v(&["servo", "check", &ex("servo-axis.toml"), "--cycle", &ex("needle-rack-cycle.toml")]),
        v(&["pick", "plot", "--play-mm", "15.5"]),
        v(&["pick", "sweep", "play", "--from", "0", "--to", "60", "--points", "25"]),
        v(&["dobby", "plot", "--what", "law", "--step-deg", "10"]),
        v(&["dobby", "plot", "--what", "cams", "--step-deg", "10"]),
        v(&["shed", "plot", "basic", "traditional", "dobby", "semi-smooth", "smooth"]),
        v(&["shed", "pareto"]),
        v(&["loom", "timing", &ex("shuttle-loom.toml"), "--wif", &ex("twill-2-2.wif")]),
        v(&["loom", "torque", &ex("shuttle-loom.toml"), "--wif", &ex("twill-2-2.wif")]),
        v(&["drive", "ripple", &ex("shuttle-loom.toml"), "--wif", &ex("twill-2-2.wif")]),
        v(&["sley", "analyze", &ex("rapier-loom.toml")]),
        v(&["cam", "profile", &ex("heald-frame-cycle.toml"), "--follower", "translating", "--prime-radius-mm", "90"]),
        v(&["dyn", "response", &ex("heald-frame-cycle.toml"), "--speed-rpm", "600", "--natural-hz", "54"]),
        v(&["dyn", "sweep", &ex("heald-frame-cycle.toml"), "--natural-hz", "54", "--speed-rpm", "200:1000:20"]),
        v(&["dyn", "spectrum", "cycloidal", "poly345", "--ratio", "0.5:8:0.05"]),
    ]
}

/// Runs `args` at `w × h`; on success the drawn texts are checked, on refusal the message is one
/// line naming the flag, and the least size it names is drawn (and checked) in turn.
fn draw(args: &[String], w: u32, h: u32, dir: &std::path::Path) -> bool {
    let file = dir.join(format!("{}-{w}x{h}.svg", args[..2].join("-").replace(['/', '.'], "_")));
    let out = loomkin()
        .args(args)
        .args(["--width", &w.to_string(), "--height", &h.to_string(), "-o"])
        .arg(&file)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    if out.status.success() {
        let svg = std::fs::read_to_string(&file).unwrap();
        let bad = loomkin_plot::drawn_text_problems(&svg).unwrap();
        assert!(bad.is_empty(), "{args:?} at {w} × {h}: {bad:?}");
        return true;
    }
    assert_eq!(out.status.code(), Some(2), "{args:?} at {w} × {h}: {err}");
    // One error line, the last (after the run's own warnings: the figure exists only after the run).
    let last = err.trim_end().lines().last().unwrap_or("");
    assert!(last.starts_with("loomkin: error:"), "{args:?} at {w} × {h}: {err}");
    assert_eq!(err.matches("error:").count(), 1, "{args:?} at {w} × {h}: {err}");
    let err = last.to_string();
    assert!(err.contains("--width") || err.contains("--height"), "{err}");
    if err.contains("are too small") {
        // Neither alone: the size named (`it lays out at W × H px`) is drawn.
        let at = err.rsplit("lays out at ").next().unwrap();
        let mut it = at.split(|c: char| !c.is_ascii_digit()).filter(|t| !t.is_empty());
        let (w2, h2) = (it.next().unwrap().parse().unwrap(), it.next().unwrap().parse().unwrap());
        assert!(draw(args, w2, h2, dir), "{args:?}: the size named, {w2} × {h2}, is refused");
        return false;
    }
    // `--height = 300 is out of range: allowed 578 ≤ --height ≤ 8000 px`: 578 lays out.
    if let Some(least) = err.split("allowed ").nth(1).and_then(|r| r.split(' ').next()) {
        let least: u32 = least.parse().unwrap();
        let (w2, h2) = if err.contains("--width =") { (least, h) } else { (w, least) };
        assert!(least > w.min(h), "{err}");
        assert!(draw(args, w2, h2, dir), "{args:?}: the least size named, {w2} × {h2}, is refused");
    }
    false
}

#[test]
fn every_plot_kind_lays_out_at_every_accepted_size() {
    let dir = std::env::temp_dir().join(format!("loomkin-plot-sizes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for args in kinds() {
        // Each kind at its default size, and at the sizes of the report (issue 27) that broke.
        let out = loomkin().args(&args).arg("-o").arg(dir.join("default.svg")).output().unwrap();
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        let svg = std::fs::read_to_string(dir.join("default.svg")).unwrap();
        let bad = loomkin_plot::drawn_text_problems(&svg).unwrap();
        assert!(bad.is_empty(), "{args:?} at its default size: {bad:?}");
        for (w, h) in [(200, 200), (400, 400), (500, 500), (600, 700), (1000, 260), (330, 1200), (4000, 600)] {
            draw(&args, w, h, &dir);
        }
        assert!(draw(&args, 1000, 900, &dir), "{args:?} refused at 1000 × 900");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The marks issue 27 asked for, read back from the SVG: `shed pareto` draws each preset as a
/// white-edged diamond above the front's dots (and in the legend); `pick plot` marks the end of
/// the pick and the end velocity; `dyn sweep --log-y` draws its residual on a log axis (and wants
/// a plot file).
#[test]
fn presets_pick_end_and_log_sweep_are_drawn() {
    let dir = std::env::temp_dir().join(format!("loomkin-plot-marks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = |args: &[&str], name: &str| {
        let file = dir.join(name);
        let out = loomkin().args(args).arg("-o").arg(&file).output().unwrap();
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        std::fs::read_to_string(&file).unwrap()
    };
    let pareto = svg(&["shed", "pareto"], "pareto.svg");
    // Five presets, each drawn once on the plot and once in the legend.
    assert_eq!(pareto.matches(r#"stroke="white" stroke-width="1.5""#).count(), 10);
    let pick = svg(&["pick", "plot"], "pick.svg");
    assert!(pick.contains(r#"aria-label="end of the pick, "#), "no end-of-pick mark");
    assert!(pick.contains(r#"aria-label="end velocity "#), "no end-velocity note");
    let sweep = svg(
        &["dyn", "sweep", &ex("heald-frame-cycle.toml"), "--natural-hz", "54", "--speed-rpm", "200:1000:20", "--log-y"],
        "sweep.svg",
    );
    assert!(sweep.contains(r#"aria-label="residual amplitude, log [mm]""#));
    assert!(loomkin_plot::drawn_text_problems(&sweep).unwrap().is_empty());
    let out = loomkin()
        .args([
            "dyn",
            "sweep",
            &ex("heald-frame-cycle.toml"),
            "--natural-hz",
            "54",
            "--speed-rpm",
            "200:400:100",
            "--log-y",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}
