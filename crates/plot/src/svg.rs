//! The figure as an SVG document.

use super::layout::{
    FONT_BAND, FONT_LABEL, FONT_LEGEND, FONT_NOTE, FONT_TICK, FONT_TITLE, Layout, MARKER_R, PanelLayout, SWATCH, Swatch,
};
use super::raster::text_width;
use super::{Dash, Figure, Panel, RuleAxis};
use std::fmt::Write;

/// Fonts named in the document: the embedded one first (the PNG renderer has only that one),
/// then common ones for other SVG viewers.
const FONT_FAMILY: &str = "Ubuntu, 'Ubuntu Light', 'DejaVu Sans', Arial, sans-serif";

fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// A colour mixed towards black (for text on a tinted band).
fn darker([r, g, b]: [u8; 3]) -> [u8; 3] {
    let d = |c: u8| (f64::from(c) * 0.6).round() as u8;
    [d(r), d(g), d(b)]
}

fn dash_attr(d: Dash) -> String {
    d.dasharray().map_or(String::new(), |a| format!(r#" stroke-dasharray="{a}""#))
}

pub(crate) fn write(fig: &Figure, lay: &Layout) -> String {
    let mut s = String::new();
    let (w, h) = (lay.width, lay.height);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="{FONT_FAMILY}">"#
    );
    let _ = writeln!(s, r##"<rect width="{w}" height="{h}" fill="#ffffff"/>"##);
    if !fig.title.trim().is_empty() {
        let _ = writeln!(
            s,
            r##"<text x="{:.1}" y="28" font-size="{FONT_TITLE}" text-anchor="middle" fill="#111111">{}</text>"##,
            w / 2.0,
            esc(&fig.title)
        );
    }
    for (i, (p, pl)) in fig.panels.iter().zip(&lay.panels).enumerate() {
        panel(&mut s, i, p, pl);
    }
    s.push_str("</svg>\n");
    s
}

fn panel(s: &mut String, i: usize, p: &Panel, pl: &PanelLayout) {
    let r = pl.plot;
    let _ = writeln!(
        s,
        r#"<defs><clipPath id="plot{i}"><rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}"/></clipPath></defs>"#,
        r.x0,
        r.y0,
        r.w(),
        r.h()
    );
    // Shaded intervals, under everything.
    for b in &p.x_bands {
        let (a, z) = (b.from.min(b.to).max(pl.x.lo), b.from.max(b.to).min(pl.x.hi));
        if a.partial_cmp(&z) != Some(std::cmp::Ordering::Less) {
            continue;
        }
        let (xa, xz) = (pl.px(a), pl.px(z));
        let _ = writeln!(
            s,
            r#"<rect x="{xa:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}" fill-opacity="0.13"/>"#,
            r.y0,
            xz - xa,
            r.h(),
            hex(b.color)
        );
        if pl.band_strip && !b.label.is_empty() && text_width(&b.label, FONT_BAND) + 6.0 <= xz - xa {
            let _ = writeln!(
                s,
                r#"<text x="{:.2}" y="{:.2}" font-size="{FONT_BAND}" text-anchor="middle" fill="{}">{}</text>"#,
                (xa + xz) / 2.0,
                r.y0 - 5.0,
                hex(darker(b.color)),
                esc(&b.label)
            );
        }
    }
    for b in &p.y_bands {
        let (ya, yz) = (pl.py(b.from.min(b.to)), pl.py(b.from.max(b.to)));
        if !(ya.is_finite() && yz.is_finite()) {
            continue;
        }
        let (top, bottom) = (yz.max(r.y0), ya.min(r.y1));
        if top < bottom {
            let _ = writeln!(
                s,
                r#"<rect x="{:.2}" y="{top:.2}" width="{:.2}" height="{:.2}" fill="{}" fill-opacity="0.16"/>"#,
                r.x0,
                r.w(),
                bottom - top,
                hex(b.color)
            );
        }
    }
    // Grid.
    for v in &pl.x.minor {
        vline(s, pl.px(*v), r.y0, r.y1, "#f1f1f1");
    }
    for v in &pl.y.minor {
        hline(s, pl.py(*v), r.x0, r.x1, "#f1f1f1");
    }
    for v in &pl.x.ticks {
        vline(s, pl.px(*v), r.y0, r.y1, "#dddddd");
    }
    for v in &pl.y.ticks {
        hline(s, pl.py(*v), r.x0, r.x1, "#dddddd");
    }
    if !pl.y.log && pl.y.lo < 0.0 && pl.y.hi > 0.0 {
        hline(s, pl.py(0.0), r.x0, r.x1, "#a8a8a8");
    }
    // Curves, limit lines and notes, clipped to the plot.
    let _ = writeln!(s, r#"<g clip-path="url(#plot{i})" fill="none" stroke-linejoin="round">"#);
    for (k, (ser, curve)) in p.series.iter().zip(&pl.curves).enumerate() {
        let color = hex(pl.colors[k]);
        for run in curve {
            if ser.markers {
                for (x, y) in run {
                    let _ = writeln!(s, r#"<circle cx="{x:.2}" cy="{y:.2}" r="{MARKER_R}" fill="{color}"/>"#);
                }
                continue;
            }
            let mut d = String::with_capacity(run.len() * 16);
            for (j, (x, y)) in run.iter().enumerate() {
                let _ = write!(d, "{}{x:.2} {y:.2}", if j == 0 { "M" } else { " L" });
            }
            if run.len() == 1 {
                let _ = write!(d, " L{:.2} {:.2}", run[0].0 + 0.01, run[0].1);
            }
            let _ = writeln!(s, r#"<path d="{d}" stroke="{color}" stroke-width="2"{}/>"#, dash_attr(ser.dash));
        }
    }
    for rule in &p.rules {
        let (a, b) = match rule.axis {
            RuleAxis::Y => ((r.x0, pl.py(rule.value)), (r.x1, pl.py(rule.value))),
            RuleAxis::X => ((pl.px(rule.value), r.y0), (pl.px(rule.value), r.y1)),
        };
        if a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite() {
            let _ = writeln!(
                s,
                r#"<path d="M{:.2} {:.2} L{:.2} {:.2}" stroke="{}" stroke-width="1.6"{}/>"#,
                a.0,
                a.1,
                b.0,
                b.1,
                hex(rule.color),
                dash_attr(rule.dash)
            );
        }
    }
    s.push_str("</g>\n");
    for (n, nl) in p.notes.iter().zip(&pl.notes) {
        if n.text.is_empty() {
            let _ = writeln!(s, r##"<circle cx="{:.2}" cy="{:.2}" r="3.5" fill="#222222"/>"##, nl.at.0, nl.at.1);
            continue;
        }
        let _ = writeln!(
            s,
            r##"<circle cx="{:.2}" cy="{:.2}" r="3.5" fill="#222222"/><text x="{:.2}" y="{:.2}" font-size="{FONT_NOTE}" fill="#222222" stroke="#ffffff" stroke-width="3" stroke-linejoin="round" paint-order="stroke">{}</text>"##,
            nl.at.0,
            nl.at.1,
            nl.text.x0 + 2.0,
            nl.text.y1 - 4.5,
            esc(&n.text)
        );
    }
    // Frame, ticks and labels.
    let _ = writeln!(
        s,
        r##"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="none" stroke="#777777"/>"##,
        r.x0,
        r.y0,
        r.w(),
        r.h()
    );
    for (v, l) in pl.x.ticks.iter().zip(&pl.x.labels) {
        let x = pl.px(*v);
        vline(s, x, r.y1, r.y1 + 5.0, "#777777");
        let _ = writeln!(
            s,
            r##"<text x="{x:.2}" y="{:.2}" font-size="{FONT_TICK}" text-anchor="middle" fill="#333333">{}</text>"##,
            r.y1 + 19.0,
            esc(l)
        );
    }
    if pl.y.log {
        // Short unlabelled ticks at the 2…9 of each decade.
        for v in &pl.y.minor {
            hline(s, pl.py(*v), r.x0 - 3.0, r.x0, "#777777");
        }
    }
    for (v, l) in pl.y.ticks.iter().zip(&pl.y.labels) {
        let y = pl.py(*v);
        hline(s, y, r.x0 - 5.0, r.x0, "#777777");
        let _ = writeln!(
            s,
            r##"<text x="{:.2}" y="{:.2}" font-size="{FONT_TICK}" text-anchor="end" fill="#333333">{}</text>"##,
            r.x0 - 8.0,
            y + 4.5,
            esc(l)
        );
    }
    let _ = writeln!(
        s,
        r##"<text x="{:.2}" y="{:.2}" font-size="{FONT_LABEL}" text-anchor="middle" fill="#111111">{}</text>"##,
        (r.x0 + r.x1) / 2.0,
        r.y1 + 40.0,
        esc(&pl.x_label)
    );
    let (ly, font) = pl.y_label_at;
    let lx = 12.0 + FONT_LABEL - 2.0;
    // The usual size written as before (the SVG of a figure whose labels fit is unchanged).
    let font = if font == FONT_LABEL { format!("{FONT_LABEL}") } else { format!("{font:.2}") };
    let _ = writeln!(
        s,
        r##"<text x="{lx:.2}" y="{ly:.2}" font-size="{}" text-anchor="middle" fill="#111111" transform="rotate(-90 {lx:.2} {ly:.2})">{}</text>"##,
        font,
        esc(&p.y_label)
    );
    if let Some(box_) = pl.legend {
        let _ = writeln!(
            s,
            r##"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" rx="3" fill="#ffffff" fill-opacity="0.94" stroke="#aaaaaa"/>"##,
            box_.x0,
            box_.y0,
            box_.w(),
            box_.h()
        );
        for (e, &(sx, cy)) in pl.entries.iter().zip(&pl.legend_cells) {
            let tx = sx + SWATCH + 7.0;
            match &e.swatch {
                Swatch::Line { color, dash } => {
                    let _ = writeln!(
                        s,
                        r#"<path d="M{sx:.2} {cy:.2} h{SWATCH}" stroke="{}" stroke-width="2.2" fill="none"{}/>"#,
                        hex(*color),
                        dash_attr(*dash)
                    );
                }
                Swatch::Marker { color } => {
                    let _ = writeln!(
                        s,
                        r#"<circle cx="{:.2}" cy="{cy:.2}" r="{MARKER_R}" fill="{}"/>"#,
                        sx + SWATCH / 2.0,
                        hex(*color)
                    );
                }
                Swatch::Fill { color } => {
                    let _ = writeln!(
                        s,
                        r#"<rect x="{sx:.2}" y="{:.2}" width="{SWATCH}" height="11" fill="{}" fill-opacity="0.3"/>"#,
                        cy - 5.5,
                        hex(*color)
                    );
                }
            }
            let _ = writeln!(
                s,
                r##"<text x="{tx:.2}" y="{:.2}" font-size="{FONT_LEGEND}" fill="#111111">{}</text>"##,
                cy + 4.5,
                esc(&e.text)
            );
        }
    }
}

fn vline(s: &mut String, x: f64, y0: f64, y1: f64, color: &str) {
    let _ = writeln!(s, r#"<path d="M{x:.2} {y0:.2} V{y1:.2}" stroke="{color}" stroke-width="1"/>"#);
}

fn hline(s: &mut String, y: f64, x0: f64, x1: f64, color: &str) {
    let _ = writeln!(s, r#"<path d="M{x0:.2} {y:.2} H{x1:.2}" stroke="{color}" stroke-width="1"/>"#);
}
