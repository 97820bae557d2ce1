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

/// `dobby plot --what cams` draws what the workbench draws (issue 27): the rollers as circles at
/// B and C of the roller radius (read back from the SVG: two closed paths in the lever's colour
/// whose vertices lie on a circle, of equal radius in pixels), the joints lettered O, A, B, C, D,
/// and each cam in its own colour (two groove walls and a dotted centre curve), with every text on
/// the canvas and off the others. Without a roller (a given cam) no circle is drawn.
#[test]
fn dobby_cams_draw_rollers_joint_letters_and_a_colour_per_cam() {
    let dir = std::env::temp_dir().join(format!("loomkin-plot-cams-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = |args: &[&str], name: &str| {
        let file = dir.join(name);
        let out = loomkin().args(["dobby", "plot", "--what", "cams"]).args(args).arg("-o").arg(&file).output().unwrap();
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        std::fs::read_to_string(&file).unwrap()
    };
    // The vertices of each path of a colour (`<path d="M… L…" stroke="#rrggbb" …>`).
    let paths = |svg: &str, colour: &str| -> Vec<Vec<(f64, f64)>> {
        svg.lines()
            .filter(|l| l.starts_with("<path d=\"M") && l.contains(&format!("stroke=\"{colour}\" stroke-width=\"2\"")))
            .map(|l| {
                let d = l.split('"').nth(1).unwrap();
                let n: Vec<f64> =
                    d.split([' ', 'M', 'L']).filter(|t| !t.is_empty()).map(|t| t.parse().unwrap()).collect();
                n.chunks(2).map(|c| (c[0], c[1])).collect()
            })
            .collect()
    };
    let hex = |c: [u8; 3]| format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
    let (cam, counter, lever) =
        (hex(loomkin_plot::PALETTE[0]), hex(loomkin_plot::PALETTE[2]), hex(loomkin_plot::PALETTE[1]));
    for at in ["0", "60", "200"] {
        let s = svg(&["--step-deg", "2", "--at-deg", at, "--roller-mm", "30"], &format!("cams-{at}.svg"));
        assert!(loomkin_plot::drawn_text_problems(&s).unwrap().is_empty(), "at {at}°");
        for letter in ["O", "A", "B", "C", "D"] {
            assert!(s.contains(&format!("aria-label=\"{letter}\"")), "no joint letter {letter} at {at}°");
        }
        // Each cam: two walls and the centre curve, closed, in its own colour.
        for colour in [&cam, &counter] {
            let runs = paths(&s, colour);
            assert_eq!(runs.len(), 3, "{colour} at {at}°");
            assert!(runs.iter().all(|r| r.len() > 100 && r.first() == r.last()), "{colour} at {at}°");
        }
        assert!(
            s.contains("aria-label=\"cam Γ: groove walls\"")
                && s.contains("aria-label=\"counter-cam Γ&apos;: groove walls\"")
        );
        // The rollers: closed 96-gons on circles of one radius (in pixels).
        let rollers: Vec<_> = paths(&s, &lever).into_iter().filter(|r| r.len() == 97).collect();
        assert_eq!(rollers.len(), 2, "rollers at {at}°");
        let radius = |r: &Vec<(f64, f64)>| {
            let c = r[..96].iter().fold((0.0, 0.0), |a, p| (a.0 + p.0 / 96.0, a.1 + p.1 / 96.0));
            let d: Vec<f64> = r.iter().map(|p| (p.0 - c.0).hypot(p.1 - c.1)).collect();
            let (lo, hi) = d.iter().fold((f64::MAX, 0.0f64), |(l, h), v| (l.min(*v), h.max(*v)));
            assert!(hi - lo < 0.05 * hi + 0.02, "not a circle: {lo}..{hi}");
            hi
        };
        let (r0, r1) = (radius(&rollers[0]), radius(&rollers[1]));
        // The drawing's scale from the joint dots (O, A, B, C, D in order): AB is the arm l3 =
        // 0.36 m (the default geometry), so a 30 mm roller is 1/12 of AB on the page.
        let dots: Vec<(f64, f64)> = s
            .lines()
            .filter(|l| l.starts_with("<circle") && l.contains("r=\"3.5\""))
            .map(|l| {
                let v = |k: &str| {
                    l.split(&format!("{k}=\"")).nth(1).unwrap().split('"').next().unwrap().parse::<f64>().unwrap()
                };
                (v("cx"), v("cy"))
            })
            .collect();
        assert_eq!(dots.len(), 5);
        let ab = (dots[1].0 - dots[2].0).hypot(dots[1].1 - dots[2].1);
        for r in [r0, r1] {
            assert!((r / ab - 0.030 / 0.36).abs() < 0.01 * 0.030 / 0.36 + 0.02 / ab, "roller {r} px, AB {ab} px");
        }
    }
    let s = svg(&["--task", "analyze", "--step-deg", "2"], "given.svg");
    assert!(paths(&s, &lever).iter().all(|r| r.len() != 97), "a roller drawn without a roller radius");
    assert!(s.contains("aria-label=\"cam Γ (roller centre B)\""));
    std::fs::remove_dir_all(&dir).ok();
}
