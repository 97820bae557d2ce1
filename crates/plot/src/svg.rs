//! The figure as an SVG document.

use super::font::{Glyph, UNITS, fonts};
use super::labels::{Label, labels};
use super::layout::{DIAMOND_R, Layout, MARKER_R, PanelLayout, SWATCH, Swatch};
use super::{Dash, Figure, Panel, RuleAxis};
use std::collections::HashMap;
use std::fmt::Write;

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

fn dash_attr(d: Dash) -> String {
    d.dasharray().map_or(String::new(), |a| format!(r#" stroke-dasharray="{a}""#))
}

/// The SVG document. Text is drawn as the embedded font's glyph outlines (each glyph once, in
/// `<defs>`, placed with `<use>`), so every viewer draws what the PNG shows without the font;
/// each text's group carries the text as its `aria-label`.
pub(crate) fn write(fig: &Figure, lay: &Layout) -> String {
    let mut body = String::new();
    let (w, h) = (lay.width, lay.height);
    let _ = writeln!(body, r##"<rect width="{w}" height="{h}" fill="#ffffff"/>"##);
    for (i, (p, pl)) in fig.panels.iter().zip(&lay.panels).enumerate() {
        panel(&mut body, i, p, pl);
    }
    let mut glyphs = Glyphs::default();
    for (k, l) in labels(fig, lay).iter().enumerate() {
        text(&mut body, k, l, &mut glyphs);
    }
    let mut s = String::with_capacity(body.len() + glyphs.defs.len() + 200);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    if !glyphs.defs.is_empty() {
        let _ = writeln!(s, "<defs>\n{}</defs>", glyphs.defs);
    }
    s.push_str(&body);
    s.push_str("</svg>\n");
    s
}

/// The glyphs written so far: each outline once, under a short id.
#[derive(Default)]
struct Glyphs {
    ids: HashMap<Glyph, Option<usize>>,
    defs: String,
}

impl Glyphs {
    /// The id of the glyph's outline (`None` for a glyph that draws nothing, a space).
    fn id(&mut self, g: Glyph) -> Option<usize> {
        let next = self.ids.values().filter(|v| v.is_some()).count();
        let defs = &mut self.defs;
        *self.ids.entry(g).or_insert_with(|| {
            let d = fonts().outline(g);
            if d.is_empty() {
                return None;
            }
            let _ = writeln!(defs, r#"<path id="g{next}" d="{d}"/>"#);
            Some(next)
        })
    }
}

/// One text as a group of glyphs: placed at its anchor, in font units (y up) scaled to its size.
fn text(s: &mut String, k: usize, l: &Label, glyphs: &mut Glyphs) {
    let f = fonts();
    let scale = l.size / UNITS;
    let (x, y, d) = (l.x, l.y, l.start_offset());
    let place = if l.vertical {
        format!("translate({x:.2} {y:.2}) rotate(-90) translate({d:.2} 0)")
    } else {
        format!("translate({:.2} {y:.2})", x + d)
    };
    let halo = if l.halo {
        format!(r##" stroke="#ffffff" stroke-width="{:.0}" stroke-linejoin="round" paint-order="stroke""##, 3.0 / scale)
    } else {
        String::new()
    };
    let _ = write!(
        s,
        r#"<g id="t{k}" aria-label="{}" transform="{place} scale({scale:.5} -{scale:.5})" fill="{}"{halo}>"#,
        esc(&l.text),
        hex(l.color)
    );
    let mut at = 0.0;
    for c in l.text.chars() {
        let (g, advance) = f.glyph(c);
        if let Some(id) = glyphs.id(g) {
            let _ = write!(s, r##"<use xlink:href="#g{id}" x="{at:.0}"/>"##);
        }
        at += advance;
    }
    s.push_str("</g>\n");
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
        if let Some((xa, xz)) = pl.band_px(b) {
            let _ = writeln!(
                s,
                r#"<rect x="{xa:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}" fill-opacity="0.13"/>"#,
                r.y0,
                xz - xa,
                r.h(),
                hex(b.color)
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
                for &(x, y) in run {
                    marker(s, x, y, &color, ser.emphasis);
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
    for nl in &pl.notes {
        let _ = writeln!(s, r##"<circle cx="{:.2}" cy="{:.2}" r="3.5" fill="#222222"/>"##, nl.at.0, nl.at.1);
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
    for v in &pl.x.ticks {
        let x = pl.px(*v);
        vline(s, x, r.y1, r.y1 + 5.0, "#777777");
    }
    // Short unlabelled ticks within a turn.
    for v in &pl.x.minor {
        vline(s, pl.px(*v), r.y1, r.y1 + 3.0, "#777777");
    }
    if pl.y.log {
        // Short unlabelled ticks at the 2…9 of each decade.
        for v in &pl.y.minor {
            hline(s, pl.py(*v), r.x0 - 3.0, r.x0, "#777777");
        }
    }
    for v in &pl.y.ticks {
        hline(s, pl.py(*v), r.x0 - 5.0, r.x0, "#777777");
    }
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
            match &e.swatch {
                Swatch::Line { color, dash } => {
                    let _ = writeln!(
                        s,
                        r#"<path d="M{sx:.2} {cy:.2} h{SWATCH}" stroke="{}" stroke-width="2.2" fill="none"{}/>"#,
                        hex(*color),
                        dash_attr(*dash)
                    );
                }
                Swatch::Marker { color, diamond } => marker(s, sx + SWATCH / 2.0, cy, &hex(*color), *diamond),
                Swatch::Fill { color } => {
                    let _ = writeln!(
                        s,
                        r#"<rect x="{sx:.2}" y="{:.2}" width="{SWATCH}" height="11" fill="{}" fill-opacity="0.3"/>"#,
                        cy - 5.5,
                        hex(*color)
                    );
                }
            }
        }
    }
}

fn vline(s: &mut String, x: f64, y0: f64, y1: f64, color: &str) {
    let _ = writeln!(s, r#"<path d="M{x:.2} {y0:.2} V{y1:.2}" stroke="{color}" stroke-width="1"/>"#);
}

fn hline(s: &mut String, y: f64, x0: f64, x1: f64, color: &str) {
    let _ = writeln!(s, r#"<path d="M{x0:.2} {y:.2} H{x1:.2}" stroke="{color}" stroke-width="1"/>"#);
}

/// A marker at `(x, y)`: a dot, or (`diamond`) a larger diamond with a white outline.
fn marker(s: &mut String, x: f64, y: f64, color: &str, diamond: bool) {
    if diamond {
        let d = DIAMOND_R - 1.0;
        let _ = writeln!(
            s,
            r#"<path d="M{x:.2} {:.2} L{:.2} {y:.2} L{x:.2} {:.2} L{:.2} {y:.2} Z" fill="{color}" stroke="white" stroke-width="1.5"/>"#,
            y - d,
            x + d,
            y + d,
            x - d
        );
    } else {
        let _ = writeln!(s, r#"<circle cx="{x:.2}" cy="{y:.2}" r="{MARKER_R}" fill="{color}"/>"#);
    }
}
