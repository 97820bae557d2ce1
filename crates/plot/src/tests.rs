use super::layout::{Rect, angle_axis, layout, log_axis, tick_label};
use super::*;

fn sine(n: usize, x1: f64, amp: f64) -> Vec<(f64, f64)> {
    (0..=n).map(|i| i as f64 * x1 / n as f64).map(|x| (x, amp * (x * std::f64::consts::TAU / x1).sin())).collect()
}

#[test]
fn svg_has_labels_legend_and_dash_swatches() {
    let fig = Figure::new(
        "test",
        "x [-]",
        vec![Panel::new(
            "s [-]",
            vec![
                Series::line("one", vec![(0.0, 0.0), (1.0, 1.0)]),
                Series::line("two", vec![(0.0, 1.0), (1.0, 0.0)]).with_dash(Dash::DashDot).with_color([1, 2, 3]),
            ],
        )],
    );
    let svg = fig.to_svg().unwrap();
    assert!(svg.contains("#010203"), "the chosen colour is used");
    for text in ["x [-]", "s [-]", "one", "two", "test"] {
        assert!(svg.contains(&format!(r#"aria-label="{text}""#)), "{text} missing");
    }
    // The dash-dot pattern appears twice: on the curve and on its legend swatch.
    assert_eq!(svg.matches(r#"stroke-dasharray="10 4 2 4""#).count(), 2);
}

#[test]
fn tick_labels_are_compact() {
    assert_eq!(tick_label(-1e-17, 2.0), "0");
    assert_eq!(tick_label(250.0, 50.0), "250");
    assert_eq!(tick_label(0.1, 0.1), "0.1");
    assert_eq!(tick_label(-0.0005, 0.0005), "−0.0005");
    assert_eq!(tick_label(0.30000000000000004, 0.1), "0.3");
}

#[test]
fn angle_ticks_are_multiples_of_30_45_or_90() {
    for (lo, hi, len) in [
        (0.0, 360.0, 900.0),
        (0.0, 360.0, 400.0),
        (0.0, 360.0, 150.0),
        (-20.0, 300.0, 700.0),
        (0.0, 7200.0, 500.0),
        (10.0, 190.0, 300.0),
    ] {
        let a = angle_axis(lo, hi, len, 44.0);
        let step = a.ticks[1] - a.ticks[0];
        assert!([30.0, 45.0, 90.0].contains(&step) || (step % 90.0 == 0.0), "{lo}..{hi} on {len} px: step {step}");
        assert!(a.ticks.iter().all(|t| (t / step).fract().abs() < 1e-9 && *t >= lo && *t <= hi));
        assert!(a.ticks.len() >= 2);
        // Labels at least 44 px apart.
        assert!(len * step / (hi - lo) >= 44.0 - 1e-9);
    }
    assert_eq!(angle_axis(0.0, 360.0, 900.0, 44.0).ticks.len(), 13, "a long 360° axis every 30°");
    // A pattern repeat of 48 picks: ticked at a round number of turns (5 turns = 1800°).
    let a = angle_axis(0.0, 17_280.0, 900.0, 44.0);
    assert_eq!(a.ticks[1] - a.ticks[0], 1800.0);
}

#[test]
fn log_ticks_are_decades() {
    let a = log_axis(1e-6, 1e2, 300.0, 26.0);
    assert!(a.log);
    for t in &a.ticks {
        let k = t.log10();
        assert!((k - k.round()).abs() < 1e-12, "{t} is not a decade");
    }
    assert!(a.ticks.len() >= 3);
    assert_eq!(a.labels.last().map(String::as_str), Some("10²"));
    // A spectrum spanning 1e-12 … 1: the axis stops at 15 decades, labels thinned, still decades.
    let fig = Figure::new(
        "",
        "f [Hz]",
        vec![
            Panel::new(
                "|X| [m]",
                vec![Series::line("", (1..200).map(|i| (i as f64, 10f64.powf(-(i as f64) / 16.0))).collect())],
            )
            .with_log_y(),
        ],
    );
    let lay = layout(&fig);
    let y = &lay.panels[0].y;
    assert!(y.lo >= 1e-15 * y.hi * 0.999 && y.hi == 1.0, "{} … {}", y.lo, y.hi);
    assert!(y.ticks.iter().all(|t| (t.log10() - t.log10().round()).abs() < 1e-12));
}

/// Whether a polyline enters the rectangle anywhere.
fn crosses(r: &Rect, run: &[(f64, f64)]) -> bool {
    run.windows(2).any(|w| r.hit_by_segment(w[0], w[1]))
}

#[test]
fn legend_avoids_every_curve() {
    // Curves that fill the corners: the legend must find a free place or go outside.
    let cases = vec![
        vec![Series::line("sine", sine(200, 360.0, 1.0)), Series::line("cosine", sine(200, 360.0, -1.0)).with_dashes()],
        vec![
            Series::line("ramp up", vec![(0.0, 0.0), (1.0, 1.0)]),
            Series::line("ramp down", vec![(0.0, 1.0), (1.0, 0.0)]),
            Series::line("top", vec![(0.0, 1.0), (1.0, 1.0)]),
            Series::line("bottom", vec![(0.0, 0.0), (1.0, 0.0)]),
            Series::line("middle", vec![(0.0, 0.5), (1.0, 0.5)]),
        ],
        vec![Series::markers("points", (0..40).map(|i| (i as f64, ((i * 7) % 11) as f64)).collect())],
    ];
    let mut outside = 0;
    for series in cases {
        let markers = series[0].markers;
        let fig = Figure::new("t", "x [deg]", vec![Panel::new("y [m]", series).with_rule(Rule::y(0.9, "limit"))]);
        let lay = layout(&fig);
        let pl = &lay.panels[0];
        let legend = pl.legend.expect("a legend");
        for curve in &pl.curves {
            for run in curve {
                // Lines must not cross the box; markers (r = 4 px) must not touch it.
                assert!(markers || !crosses(&legend, run), "legend {legend:?} on a curve");
                let keep = if markers { 4.0 } else { 2.0 };
                assert!(!run.iter().any(|&(x, y)| legend.grow(keep).contains(&Rect::new(x, y, 0.0, 0.0))));
            }
        }
        let ry = pl.py(0.9);
        assert!(!legend.hit_by_segment((pl.plot.x0, ry), (pl.plot.x1, ry)), "legend on the limit line");
        if legend.x0 >= pl.plot.x1 || legend.y1 <= pl.plot.y0 {
            outside += 1;
        } else {
            assert!(pl.plot.contains(&legend));
        }
    }
    assert!(outside >= 1, "the crossing ramps leave no room inside");
}

fn sine_series() -> Vec<Series> {
    vec![Series::line("", sine(50, 1.0, 1.0))]
}

/// Curves through every corner and edge of a plot: no free place for a legend inside.
fn crowded(n: usize, name: &str) -> Vec<Series> {
    (0..n)
        .map(|i| {
            let k = i as f64 / n as f64;
            Series::line(format!("{name} {i}"), vec![(0.0, k), (0.25, 1.0 - k), (0.5, k), (0.75, 1.0 - k), (1.0, k)])
        })
        .collect()
}

#[test]
fn a_legend_with_no_room_inside_goes_in_rows_above_its_plot() {
    let bare = |series: Vec<Series>| {
        Figure::new("t", "x", vec![Panel::new("y", series).with_legend(Legend::Hidden), Panel::new("z", sine_series())])
    };
    let fig = Figure::new(
        "t",
        "x",
        vec![Panel::new("y", crowded(10, "curve with a long name")), Panel::new("z", sine_series())],
    );
    let lay = layout(&fig);
    let without = layout(&bare(crowded(10, "curve with a long name")));
    let pl = &lay.panels[0];
    let legend = pl.legend.expect("a legend");
    // Above the plot, inside the figure, in rows: the plots keep the full width (no panel gives
    // up width to a column on the right); only this panel gives up height.
    assert!(legend.y1 <= pl.plot.y0 && legend.y0 >= 40.0, "{legend:?} {:?}", pl.plot);
    assert!(legend.x0 >= pl.plot.x0 && legend.x1 <= lay.width, "{legend:?}");
    assert_eq!(pl.plot.x1, without.panels[0].plot.x1);
    assert_eq!(lay.panels[1].plot.x1, without.panels[1].plot.x1);
    assert!(pl.plot.h() < without.panels[0].plot.h() && pl.plot.h() >= 0.65 * without.panels[0].plot.h());
    assert_eq!(lay.panels[1].plot, without.panels[1].plot);
    // More than one row, and no two entries on one spot.
    let cells = &pl.legend_cells;
    assert_eq!(cells.len(), 10);
    assert!(cells.iter().any(|c| c.1 > cells[0].1), "one row only: {cells:?}");
    for (i, a) in cells.iter().enumerate() {
        assert!(legend.contains(&Rect::new(a.0, a.1, 0.0, 0.0)));
        for b in &cells[i + 1..] {
            assert!((a.1 - b.1).abs() > 1.0 || (a.0 - b.0).abs() > 40.0, "{a:?} {b:?}");
        }
    }
    // The SVG draws every entry.
    let svg = fig.to_svg().unwrap();
    for i in 0..10 {
        assert!(svg.contains(&format!(r#"aria-label="curve with a long name {i}""#)), "curve {i}");
    }
}

#[test]
fn a_legend_too_tall_for_rows_above_goes_to_the_right() {
    // Forty long entries in a short panel would take most of its height in rows: a column on the
    // right instead.
    let fig = Figure::new("t", "x", vec![Panel::new("y", crowded(40, "a rather long curve name"))]);
    let lay = layout(&fig);
    let pl = &lay.panels[0];
    let legend = pl.legend.expect("a legend");
    assert!(legend.x0 >= pl.plot.x1, "{legend:?} {:?}", pl.plot);
}

#[test]
fn stacked_panels_share_the_plot_width_when_a_legend_goes_outside() {
    let full = vec![
        Series::line("a", vec![(0.0, 0.0), (1.0, 1.0)]),
        Series::line("b", vec![(0.0, 1.0), (1.0, 0.0)]),
        Series::line("c", vec![(0.0, 0.5), (1.0, 0.5)]),
    ];
    let fig =
        Figure::new("", "x", vec![Panel::new("y", full), Panel::new("z", vec![Series::line("d", sine(50, 1.0, 1.0))])]);
    let lay = layout(&fig);
    assert_eq!(lay.panels[0].plot.x1, lay.panels[1].plot.x1);
    assert_eq!(lay.panels[0].plot.x0, lay.panels[1].plot.x0);
}

#[test]
fn notes_stay_in_the_plot_and_off_the_curves() {
    let pts = sine(400, 360.0, 2.0);
    let fig = Figure::new(
        "",
        "angle [deg]",
        vec![
            Panel::new("a [m/s²]", vec![Series::line("a", pts)])
                .with_notes([Note::new(90.0, 2.0, "peak 2 m/s² at 90°"), Note::new(270.0, -2.0, "−2 m/s² at 270°")]),
        ],
    );
    let lay = layout(&fig);
    let pl = &lay.panels[0];
    assert_eq!(pl.notes.len(), 2);
    for n in &pl.notes {
        assert!(pl.plot.contains(&n.text));
        for run in &pl.curves[0] {
            assert!(!crosses(&n.text, run));
        }
    }
}

#[test]
fn page_settings_are_checked_and_applied() {
    let fig = || Figure::new("own", "x", vec![Panel::new("y", vec![Series::line("", vec![(0.0, 0.0), (1.0, 1.0)])])]);
    let f = fig()
        .with_page(&Page { width: Some(640.0), height: Some(480.0), dpi: Some(150.0), title: Some("mine".into()) })
        .unwrap();
    assert_eq!(f.pixel_size(), (640, 480));
    assert_eq!(f.dpi, 150.0);
    assert_eq!(f.title, "mine");
    let err = |p: Page| fig().with_page(&p).unwrap_err().to_string();
    assert_eq!(
        err(Page { width: Some(50.0), ..Page::default() }),
        "width = 50 is out of range: allowed 200 ≤ width ≤ 8000 px"
    );
    assert_eq!(err(Page { dpi: Some(0.0), ..Page::default() }), "dpi = 0 is out of range: allowed 24 ≤ dpi ≤ 1200 dpi");
    assert!(err(Page { height: Some(f64::NAN), ..Page::default() }).starts_with("height is not a finite number"));
    assert!(err(Page { title: Some("a\nb".into()), ..Page::default() }).contains("one line"));
    // 8000 × 8000 at 1200 dpi would be 10¹⁰ pixels: the message names the largest DPI allowed.
    let big = err(Page { width: Some(8000.0), height: Some(8000.0), dpi: Some(1200.0), ..Page::default() });
    assert!(big.starts_with("dpi = 1200 is out of range: allowed 24 ≤ dpi ≤ 120 dpi"), "{big}");
    assert!(!big.contains('\n'));
}

#[test]
fn png_is_antialiased_sized_by_dpi_and_tagged() {
    let fig =
        Figure::new("t", "x [deg]", vec![Panel::new("y [m]", vec![Series::line("cycloidal", sine(60, 360.0, 1.0))])])
            .with_page(&Page { width: Some(320.0), height: Some(220.0), dpi: Some(144.0), title: None })
            .unwrap();
    let bytes = fig.to_png().unwrap();
    let pix = resvg::tiny_skia::Pixmap::decode_png(&bytes).unwrap();
    assert_eq!((pix.width(), pix.height()), (480, 330));
    // Antialiased edges: many grey levels between white and the darkest line pixel, not two.
    let mut levels = std::collections::BTreeSet::new();
    for p in pix.pixels() {
        let c = p.demultiply();
        levels.insert(c.red() / 4 * 4);
    }
    assert!(levels.len() > 30, "only {} levels of red", levels.len());
    // The resolution chunk: 144 dpi = 5669 pixels per metre, unit metre, with a valid CRC.
    let i = bytes.windows(4).position(|w| w == b"pHYs").unwrap();
    assert_eq!(&bytes[i + 4..i + 13], &[0, 0, 0x16, 0x25, 0, 0, 0x16, 0x25, 1]);
    let crc = u32::from_be_bytes(bytes[i + 13..i + 17].try_into().unwrap());
    assert_eq!(crc, super::raster::crc32(&bytes[i..i + 13]));
}

#[test]
fn crc32_matches_the_check_value() {
    // The standard check value of CRC-32 over "123456789".
    assert_eq!(super::raster::crc32(b"123456789"), 0xCBF4_3926);
}

#[test]
fn text_is_measured_with_the_embedded_font() {
    let w = super::font::text_width("cycloidal", 15.0);
    assert!(w > 40.0 && w < 80.0, "{w}");
    assert!(super::font::text_width("ii", 15.0) < super::font::text_width("MM", 15.0));
}

#[test]
fn save_writes_both_formats_and_refuses_others() {
    let dir = std::env::temp_dir().join(format!("loomkin-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fig = Figure::new("t", "x", vec![Panel::new("y", vec![Series::line("", vec![(0.0, 2.0), (1.0, 2.0)])])]);
    fig.save(&dir.join("a.png")).unwrap();
    assert_eq!(&std::fs::read(dir.join("a.png")).unwrap()[1..4], b"PNG");
    fig.save(&dir.join("a.svg")).unwrap();
    assert!(std::fs::read_to_string(dir.join("a.svg")).unwrap().starts_with("<svg"));
    assert!(matches!(fig.save(&dir.join("a.pdf")), Err(IoError::PlotFormat { .. })));
    assert!(Figure::new("t", "x", vec![]).to_svg().is_err());
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn note_values_have_four_significant_digits() {
    assert_eq!(sig4(12.3456), "12.35");
    assert_eq!(sig4(-0.0012346), "−0.001235");
    assert_eq!(sig4(128_000.0), "128000");
    assert_eq!(sig4(2.5e-7), "2.500e−7");
    assert_eq!(sig4(3.0), "3");
    assert_eq!(sig4(0.0), "0");
}

#[test]
fn decade_labels_are_powers_of_ten() {
    use super::layout::decade_label;
    assert_eq!(decade_label(-5), "10⁻⁵");
    assert_eq!(decade_label(0), "10⁰");
    assert_eq!(decade_label(3), "10³");
    assert_eq!(decade_label(12), "10¹²");
    assert_eq!(decade_label(-10), "10⁻¹⁰");
}

/// A spectrum with exact zeros and values far below the floor: the axis starts at the floor's
/// decade, is ticked at decades, and the drawn polylines are exactly the positive data points
/// (none raised to the floor, no point invented), broken at the zeros.
#[test]
fn log_floor_moves_no_point_and_breaks_at_zeros() {
    // |sin πr| / (πr |r² − 1|), the cycloid's residual, with its exact zeros at r = 2, 3, … put in
    // as zeros (1/2 at r = 1), and a tiny value (1e-13) that must stay where it is.
    let mut pts: Vec<(f64, f64)> = (50..=600)
        .map(|i| {
            let r = f64::from(i) / 100.0;
            let v = if i % 100 == 0 && i > 100 {
                0.0
            } else if i == 100 {
                0.5
            } else {
                (std::f64::consts::PI * r).sin().abs() / (std::f64::consts::PI * r * (r * r - 1.0).abs())
            };
            (r, v)
        })
        .collect();
    pts[300].1 = 1e-13;
    let floor = 1e-4;
    let fig = Figure::new(
        "",
        "T·f_n [-]",
        vec![Panel::new("A/h [-]", vec![Series::line("cycloidal", pts.clone())]).with_log_y_floor(floor)],
    );
    let lay = layout(&fig);
    let pl = &lay.panels[0];
    assert!(pl.y.log);
    assert!((pl.y.lo - 1e-4).abs() < 1e-18, "axis floor {}", pl.y.lo);
    assert!(pl.y.ticks.iter().all(|t| (t.log10() - t.log10().round()).abs() < 1e-12));
    assert_eq!(pl.y.ticks.first().copied(), Some(pl.y.lo));
    // Minor ticks at 2…9 × 10ᵏ inside the axis.
    assert!(pl.y.minor.iter().any(|m| (m / 2e-4 - 1.0).abs() < 1e-12));
    // Every drawn point is a positive data point, in order; the zeros break the line.
    let drawn: Vec<(f64, f64)> = pl.curves[0].iter().flatten().copied().collect();
    let positive: Vec<(f64, f64)> = pts.iter().filter(|p| p.1 > 0.0).map(|&(x, y)| (pl.px(x), pl.py(y))).collect();
    assert_eq!(drawn, positive);
    // One run per stretch of positive values between the zeros (the last point is a zero).
    let runs = pts.iter().enumerate().filter(|(i, p)| p.1 > 0.0 && (*i == 0 || pts[i - 1].1 == 0.0)).count();
    assert_eq!(runs, 5);
    assert_eq!(pl.curves[0].len(), runs, "the line breaks at every zero");
    // Below the floor only data points: the 1e-13 point is drawn at its own (off-plot) height.
    let floor_px = pl.py(floor);
    let below: Vec<_> = drawn.iter().filter(|p| p.1 > floor_px + 1e-9).collect();
    assert!(!below.is_empty());
    for b in below {
        assert!(positive.contains(b));
    }
    assert!(drawn.contains(&(pl.px(pts[300].0), pl.py(1e-13))));
    // The decade labels are written as 10ᵏ in the SVG.
    let svg = fig.to_svg().unwrap();
    assert!(svg.contains(r#"aria-label="10⁻⁴""#) && svg.contains(r#"aria-label="10⁰""#), "decade labels");
}

/// The shaded intervals and bands are drawn at their data coordinates.
#[test]
fn bands_are_drawn_at_their_data_coordinates() {
    let fig = Figure::new(
        "",
        "angle [deg]",
        vec![
            Panel::new("s [mm]", vec![Series::line("s", sine(100, 720.0, 50.0))])
                .with_x_bands([XBand::new(100.0, 460.0, "window", XBand::WINDOW)])
                .with_y_band(YBand::new(45.0, 50.0, "threshold band", [200, 30, 30])),
        ],
    );
    let lay = layout(&fig);
    let pl = &lay.panels[0];
    let svg = fig.to_svg().unwrap();
    let rect =
        |x: f64, y: f64, w: f64, h: f64| format!(r#"<rect x="{x:.2}" y="{y:.2}" width="{w:.2}" height="{h:.2}""#);
    let (xa, xz) = (pl.px(100.0), pl.px(460.0));
    assert!(svg.contains(&rect(xa, pl.plot.y0, xz - xa, pl.plot.h())), "window rectangle");
    let (ya, yz) = (pl.py(45.0), pl.py(50.0));
    assert!(svg.contains(&rect(pl.plot.x0, yz, pl.plot.w(), ya - yz)), "threshold band rectangle");
    assert!(svg.contains(r#"aria-label="window""#) && svg.contains(r#"aria-label="threshold band""#));
}

/// Nested and neighbouring bands name themselves without one name over another: the narrow band's
/// name stays centred, the wide band's moves to its start (the projectile's "in the shed" around
/// the sley's "back dwell" wrote one over the other).
#[test]
fn names_of_nested_bands_do_not_overlap() {
    let fig = Figure::new(
        "",
        "angle [deg]",
        vec![Panel::new("s [mm]", vec![Series::line("s", sine(100, 360.0, 50.0))]).with_x_bands([
            XBand::new(40.0, 320.0, "in the shed", XBand::WINDOW),
            XBand::new(160.0, 200.0, "sley back dwell", XBand::DWELL),
        ])],
    );
    let svg = fig.to_svg().unwrap();
    assert!(svg.contains(r#"aria-label="in the shed""#) && svg.contains(r#"aria-label="sley back dwell""#));
    let problems = crate::drawn_text_problems(&svg).unwrap();
    assert!(problems.is_empty(), "{problems:?}");
    assert!(fig.layout_problems().is_empty(), "{:?}", fig.layout_problems());
}

#[test]
fn vertical_labels_of_short_stacked_panels_do_not_overlap() {
    use super::font::text_width;
    // Labels longer than a short panel at the usual size, short enough at 10 px (what the
    // seven-law `law plot --width 700 --height 600` draws).
    let label = |q: &str| format!("{q}: a = d²s/dx² [m/s²]");
    let panels: Vec<Panel> =
        ["first", "second", "third", "fourth"].iter().map(|q| Panel::new(label(q), sine_series())).collect();
    let mut fig = Figure::new("t", "x", panels);
    fig.size = Some((700, 600));
    let lay = layout(&fig);
    let extent = |i: usize| {
        let (c, font) = lay.panels[i].y_label_at;
        let half = text_width(&label(["first", "second", "third", "fourth"][i]), 15.0) * font / 15.0 / 2.0;
        (c - half, c + half)
    };
    assert!(lay.panels[0].y_label_at.1 < 15.0, "the label was not long enough to test");
    for i in 0..3 {
        assert!(
            extent(i).1 <= extent(i + 1).0,
            "labels {i} and {} overlap: {:?} {:?}",
            i + 1,
            extent(i),
            extent(i + 1)
        );
    }
    // A label that fits stays centred on its plot at the usual size.
    let tall = layout(&Figure::new("t", "x", vec![Panel::new("y [m]", sine_series())]));
    let pl = &tall.panels[0];
    assert_eq!(pl.y_label_at, ((pl.plot.y0 + pl.plot.y1) / 2.0, 15.0));
}

/// A figure with every kind of text: a title, band labels, notes, legends inside and crowded,
/// a log axis, a long vertical label.
fn every_text(panels: usize) -> Figure {
    let mut out = vec![
        Panel::new("displacement s [mm]", sine_series())
            .with_x_bands([
                XBand::new(0.0, 120.0, "rise", XBand::RISE),
                XBand::new(120.0, 360.0, "dwell", XBand::DWELL),
            ])
            .with_notes([Note::new(90.0, 1.0, "peak 1 mm at 90°")]),
        Panel::new("spectrum |X| [m]", vec![Series::line("", (1..200).map(|i| (i as f64, 1.0 / i as f64)).collect())])
            .with_log_y()
            .with_x_label("frequency f [Hz]"),
        Panel::new("acceleration a = d²s/dx² [m/s²]", crowded(5, "a curve with a long legend entry"))
            .with_rule(Rule::y(0.5, "limit 0.5 m/s²")),
        Panel::new("torque M [N·m]", sine_series()).with_y_band(YBand::new(-0.2, 0.2, "threshold band", [200, 0, 0])),
    ];
    out.truncate(panels);
    Figure::new("A long title naming the input file, the speed and every setting of this run", "angle [deg]", out)
}

#[test]
fn text_is_drawn_as_glyph_outlines_once_each() {
    let svg = every_text(4).to_svg().unwrap();
    assert!(!svg.contains("<text") && !svg.contains("font-family"), "no text element, no font named");
    let lay = layout(&every_text(4));
    let labels = super::labels::labels(&every_text(4), &lay);
    let mut glyphs = std::collections::HashSet::new();
    for l in &labels {
        assert!(svg.contains(&format!(r#"aria-label="{}""#, l.text.replace('&', "&amp;"))), "{}", l.text);
        glyphs.extend(l.text.chars().filter(|c| !c.is_whitespace()));
    }
    // Each character's outline is written once (a character Ubuntu lacks maps to Hack's glyph).
    assert_eq!(svg.matches(r#"<path id="g"#).count(), glyphs.len());
}

#[test]
fn layout_boxes_hold_the_drawn_ink() {
    // The boxes the layout checks against each other hold what a renderer draws (read back from
    // the SVG by usvg, not from the layout).
    for (fig, size) in [(every_text(4), None), (every_text(2), Some((420, 520))), (every_text(1), Some((300, 260)))] {
        let mut fig = fig;
        fig.size = size;
        let lay = layout(&fig);
        let labels = super::labels::labels(&fig, &lay);
        let drawn = drawn_texts(&fig.to_svg().unwrap()).unwrap();
        assert_eq!(drawn.len(), labels.len());
        for (l, (text, b)) in labels.iter().zip(&drawn) {
            assert_eq!(&l.text, text);
            let r = l.rect().grow(1.0);
            assert!(r.contains(&Rect { x0: b[0], y0: b[1], x1: b[2], y1: b[3] }), "{text}: ink {b:?} outside {r:?}");
            // And the box is not loose: the ink spans most of the advance.
            let along = if l.vertical { b[3] - b[1] } else { b[2] - b[0] };
            let advance = if l.vertical { l.rect().h() } else { l.rect().w() };
            assert!(along > 0.5 * advance || text.chars().count() < 3, "{text}: ink {along} of {advance}");
        }
    }
}

#[test]
fn every_accepted_size_lays_out_and_a_refusal_names_a_size_that_does() {
    let sizes = [200.0, 260.0, 330.0, 400.0, 500.0, 600.0, 700.0, 850.0, 1000.0, 1600.0, 8000.0];
    for panels in 1..=4 {
        let fig = every_text(panels);
        assert!(fig.layout_problems().is_empty(), "{panels} panels at the default size: {:?}", fig.layout_problems());
        let mut accepted = 0;
        for &w in &sizes {
            for &h in &sizes {
                if w * h > 4e7 {
                    continue; // a poster both ways: nothing new, and slow to read back
                }
                let page = Page { width: Some(w), height: Some(h), ..Page::default() };
                match fig.clone().with_page(&page) {
                    Ok(f) => {
                        accepted += 1;
                        assert!(f.layout_problems().is_empty());
                        let clashes = drawn_text_problems(&f.to_svg().unwrap()).unwrap();
                        assert!(clashes.is_empty(), "{panels} panels at {w} × {h}: {clashes:?}");
                    }
                    Err(IoError::TooSmall { range: e, reason }) => {
                        // What does not fit is said, at the size given.
                        let mut at = fig.clone();
                        at.size = Some((w as u32, h as u32));
                        assert_eq!(Some(&reason), at.layout_problems().first(), "{e}");
                        // The least size named lays out.
                        let least = match &e.range.lo {
                            loomkin_units::Bound::Closed(v) | loomkin_units::Bound::Open(v) => *v,
                            other => panic!("{other:?}"),
                        };
                        let page = match e.field.as_str() {
                            "width" => Page { width: Some(least), height: Some(h), ..Page::default() },
                            "height" => Page { width: Some(w), height: Some(least), ..Page::default() },
                            other => panic!("{other}"),
                        };
                        assert!(least > w.min(h), "{e}");
                        let f = fig.clone().with_page(&page).unwrap_or_else(|e| panic!("{panels} at {w} × {h}: {e}"));
                        assert!(f.layout_problems().is_empty());
                    }
                    Err(e) => assert!(e.to_string().contains("too small for this figure"), "{e}"),
                }
            }
        }
        assert!(accepted > 20, "{panels} panels: only {accepted} sizes accepted");
    }
}

#[test]
fn a_long_title_shrinks_then_wraps_and_stays_on_the_canvas() {
    use super::layout::fit_title;
    let (lines, font) = fit_title("Normalised motion laws", 1000.0);
    assert_eq!((lines.len(), font), (1, 20.0));
    let long = "Servo motion law from definition points and motor torque over one turn";
    let (lines, font) = fit_title(long, 600.0);
    assert_eq!(lines.len(), 1);
    assert!((14.0..20.0).contains(&font) && super::font::text_width(long, font) <= 584.0);
    let (lines, font) = fit_title(long, 300.0);
    assert_eq!(font, 14.0);
    assert!(lines.len() > 1 && lines.iter().all(|l| super::font::text_width(l, font) <= 284.0));
    assert_eq!(lines.join(" "), long, "wrapped at spaces, nothing lost");
    let (lines, _) = fit_title(&"word ".repeat(200), 200.0);
    assert_eq!(lines.len(), 3);
    assert!(lines[2].ends_with('…'));
}

#[test]
fn a_turns_axis_is_ticked_at_whole_turns_with_degrees_as_minor_ticks() {
    use super::layout::turns_axis;
    // 48 picks on 900 px: 18.75 px a turn, labels every 5 turns (≥ 44 px), minor ticks every 180°.
    let (a, minor) = turns_axis(0.0, 17_280.0, 900.0, 44.0);
    assert_eq!(
        a.ticks.iter().map(|t| t / 360.0).collect::<Vec<_>>(),
        (0..=9).map(|k| 5.0 * k as f64).collect::<Vec<_>>()
    );
    assert_eq!(a.labels[1], "5");
    assert_eq!(minor, Some(180.0));
    assert!(a.minor.iter().all(|m| (m % 180.0).abs() < 1e-9 && (m % 360.0).abs() > 1e-9));
    assert_eq!(a.minor.len(), 48);
    // 4 picks: every turn labelled, minor ticks every 30°, none on a whole turn.
    let (a, minor) = turns_axis(0.0, 1440.0, 900.0, 44.0);
    assert_eq!(a.labels, ["0", "1", "2", "3", "4"]);
    assert_eq!(minor, Some(30.0));
    assert_eq!(a.minor.len(), 4 * 11);
    // The figure says the minor step in its horizontal label.
    let fig = Figure::new("", "picks", vec![Panel::new("M [N·m]", vec![Series::line("", sine(400, 1440.0, 1.0))])])
        .with_turns_axis();
    assert!(fig.to_svg().unwrap().contains(r#"aria-label="picks, minor ticks every 30°""#));
}

/// Every vertex of a circle lies on it (radius checked by distance, not by the formula that made
/// it), each circle closes on itself and the circles are parted by one break; the SVG draws one
/// path per circle, and a radius of zero or not finite draws nothing.
#[test]
fn circles_are_closed_polygons_on_the_circle_parted_by_breaks() {
    let centres = [(1.0, -2.0), (-0.5, 0.25)];
    let s = Series::circles("rollers", &centres, 0.3);
    let breaks: Vec<usize> = (0..s.points.len()).filter(|&i| !s.points[i].0.is_finite()).collect();
    assert_eq!(breaks, vec![crate::CIRCLE_SIDES + 1]);
    for (k, run) in s.points.split(|p| !p.0.is_finite()).enumerate() {
        assert_eq!(run.len(), crate::CIRCLE_SIDES + 1);
        assert_eq!(run.first(), run.last());
        let (cx, cy) = centres[k];
        for &(x, y) in run {
            assert!(((x - cx).hypot(y - cy) - 0.3).abs() < 1e-12);
        }
        // The polygon's area is the circle's within the chord error (n/2 sin(2π/n) r²).
        let area: f64 =
            run.windows(2).map(|w| (w[0].0 - cx) * (w[1].1 - cy) - (w[1].0 - cx) * (w[0].1 - cy)).sum::<f64>() / 2.0;
        assert!((area / (std::f64::consts::PI * 0.09) - 1.0).abs() < 1e-3, "{area}");
    }
    let mut p = Panel::new("y [m]", vec![s]);
    p.equal_aspect = true;
    let svg = Figure::new("", "x [m]", vec![p]).to_svg().unwrap();
    let paths = svg.lines().filter(|l| l.starts_with("<path d=\"M") && l.contains("stroke-width=\"2\"")).count();
    assert_eq!(paths, 2, "{svg}");
    for r in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(Series::circles("", &centres, r).points.is_empty());
    }
}

/// A vertical label too long for its short panel even in the smallest font is broken in two at a
/// space (the drawn ink read back from the SVG: each line inside the panel's height, none over
/// another text), and a plot too short for two ticks at the usual spacing gets closer round ticks;
/// a figure that lays out as it is keeps one line and its ticks.
#[test]
fn a_label_too_long_for_a_short_panel_takes_two_lines() {
    let label = |q: &str| format!("{q}: acceleration a = d²s/dx² [m/s²]");
    let names = ["first", "second", "third", "fourth"];
    let panels: Vec<Panel> = names.iter().map(|q| Panel::new(label(q), sine_series())).collect();
    let mut fig = Figure::new("t", "x", panels);
    fig.size = Some((1000, 560));
    let lay = layout(&fig);
    for (i, pl) in lay.panels.iter().enumerate() {
        assert_eq!(pl.y_label_lines.len(), 2, "panel {i}: {:?}", pl.y_label_lines);
        assert_eq!(pl.y_label_lines.join(" "), label(names[i]));
        assert!(pl.y.ticks.len() >= 2, "panel {i}");
    }
    let svg = fig.to_svg().unwrap();
    assert_eq!(crate::drawn_text_problems(&svg).unwrap(), Vec::<String>::new());
    assert!(fig.layout_problems().is_empty(), "{:?}", fig.layout_problems());
    // At the default size the same figure keeps one line per label.
    fig.size = None;
    assert!(layout(&fig).panels.iter().all(|pl| pl.y_label_lines.len() == 1));
}
