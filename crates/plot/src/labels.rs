//! Every text of a figure, placed: what the SVG draws (as glyph outlines) and what the layout
//! check reads. One list, so the boxes checked are the boxes drawn.

use super::Figure;
use super::font::{fonts, text_width};
use super::layout::{
    FONT_BAND, FONT_LABEL, FONT_LEGEND, FONT_NOTE, FONT_TICK, Layout, Rect, SWATCH, Y_LABEL_LINE, title_baseline,
    title_line,
};

/// Where a label's anchor point is along its text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Anchor {
    Start,
    Middle,
    End,
}

/// What a label is (for the check's messages).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Role {
    Title,
    /// A band's name, in the strip over panel `0`.
    Band(usize),
    Note(usize),
    XTick(usize),
    YTick(usize),
    XLabel(usize),
    YLabel(usize),
    Legend(usize),
}

impl Role {
    fn describe(self) -> String {
        match self {
            Role::Title => "the title".into(),
            Role::Band(i) => format!("a band label of panel {}", i + 1),
            Role::Note(i) => format!("a note of panel {}", i + 1),
            Role::XTick(i) => format!("a horizontal tick label of panel {}", i + 1),
            Role::YTick(i) => format!("a vertical tick label of panel {}", i + 1),
            Role::XLabel(i) => format!("the horizontal axis label of panel {}", i + 1),
            Role::YLabel(i) => format!("the vertical axis label of panel {}", i + 1),
            Role::Legend(i) => format!("a legend entry of panel {}", i + 1),
        }
    }
}

/// One text: its anchor point on the baseline, font size, alignment and look.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Label {
    pub text: String,
    pub x: f64,
    pub y: f64,
    pub size: f64,
    pub anchor: Anchor,
    /// Written upwards (turned 90° anticlockwise), as a vertical axis label.
    pub vertical: bool,
    pub color: [u8; 3],
    /// Drawn over a white outline (a note over the grid).
    pub halo: bool,
    pub role: Role,
}

impl Label {
    fn new(text: &str, (x, y): (f64, f64), size: f64, anchor: Anchor, color: [u8; 3], role: Role) -> Self {
        Self { text: text.to_string(), x, y, size, anchor, vertical: false, color, halo: false, role }
    }

    /// The text's width in pixels.
    pub fn width(&self) -> f64 {
        text_width(&self.text, self.size)
    }

    /// Offset of the text's start from the anchor point, along the text.
    pub fn start_offset(&self) -> f64 {
        match self.anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => -self.width() / 2.0,
            Anchor::End => -self.width(),
        }
    }

    /// The box the text takes: its advance along the line, the font's ascent and descent across.
    pub fn rect(&self) -> Rect {
        let f = fonts();
        let (a, d) = (f.ascent * self.size, f.descent * self.size);
        let (s, w) = (self.start_offset(), self.width());
        if self.vertical {
            // Turned anticlockwise: the text runs up the page, its top towards the left.
            Rect { x0: self.x - a, y0: self.y - s - w, x1: self.x + d, y1: self.y - s }
        } else {
            Rect { x0: self.x + s, y0: self.y - a, x1: self.x + s + w, y1: self.y + d }
        }
    }
}

/// Least distance of an axis label from the canvas' edge.
const MARGIN: f64 = 6.0;
/// Smallest font of an axis label shrunk to fit.
const MIN_FONT: f64 = 10.0;

const TITLE: [u8; 3] = [0x11, 0x11, 0x11];
const TICK: [u8; 3] = [0x33, 0x33, 0x33];
const NOTE: [u8; 3] = [0x22, 0x22, 0x22];

/// A colour mixed towards black (for text on a tinted band).
fn darker([r, g, b]: [u8; 3]) -> [u8; 3] {
    let d = |c: u8| (f64::from(c) * 0.6).round() as u8;
    [d(r), d(g), d(b)]
}

/// The least space between two bands' names in a panel's strip (px).
const BAND_LABEL_GAP: f64 = 6.0;

/// Every text of the figure, in drawing order.
pub(crate) fn labels(fig: &Figure, lay: &Layout) -> Vec<Label> {
    let mut out = Vec::new();
    for (k, line) in lay.title.iter().enumerate() {
        let y = title_baseline(lay.title_font) + title_line(lay.title_font) * k as f64;
        out.push(Label::new(line, (lay.width / 2.0, y), lay.title_font, Anchor::Middle, TITLE, Role::Title));
    }
    for (i, (p, pl)) in fig.panels.iter().zip(&lay.panels).enumerate() {
        let r = pl.plot;
        // Each band's name centred over it; where another band's name already stands there (nested or
        // neighbouring bands), at the band's start or end instead; left out when none is free. The
        // narrowest bands are named first: a wide band has more room to move its name to.
        let mut bands: Vec<(usize, f64, f64, &crate::XBand)> = p
            .x_bands
            .iter()
            .enumerate()
            .filter(|(_, b)| pl.band_strip && !b.label.is_empty())
            .filter_map(|(k, b)| pl.band_px(b).map(|(xa, xz)| (k, xa, xz, b)))
            .filter(|(_, xa, xz, b)| text_width(&b.label, FONT_BAND) + 6.0 <= xz - xa)
            .collect();
        bands.sort_by(|a, b| (a.2 - a.1).total_cmp(&(b.2 - b.1)));
        let mut placed: Vec<(f64, f64)> = Vec::new();
        let mut named: Vec<(usize, Label)> = Vec::new();
        for (k, xa, xz, b) in bands {
            let w = text_width(&b.label, FONT_BAND);
            let mid = (xa + xz) / 2.0;
            let places = [
                (mid - w / 2.0, mid, Anchor::Middle),
                (xa + 3.0, xa + 3.0, Anchor::Start),
                (xz - 3.0 - w, xz - 3.0, Anchor::End),
            ];
            let free = |x0: f64| placed.iter().all(|&(a, z)| x0 + w + BAND_LABEL_GAP <= a || x0 >= z + BAND_LABEL_GAP);
            if let Some(&(x0, x, anchor)) = places.iter().find(|(x0, _, _)| free(*x0)) {
                placed.push((x0, x0 + w));
                let label = Label::new(&b.label, (x, r.y0 - 5.0), FONT_BAND, anchor, darker(b.color), Role::Band(i));
                named.push((k, label));
            }
        }
        // Drawn in the bands' own order.
        named.sort_by_key(|(k, _)| *k);
        out.extend(named.into_iter().map(|(_, l)| l));
        for (n, nl) in p.notes.iter().zip(&pl.notes) {
            if !n.text.is_empty() {
                let at = (nl.text.x0 + 2.0, nl.text.y1 - 4.5);
                let mut l = Label::new(&n.text, at, FONT_NOTE, Anchor::Start, NOTE, Role::Note(i));
                l.halo = true;
                out.push(l);
            }
        }
        for (v, l) in pl.x.ticks.iter().zip(&pl.x.labels) {
            if pl.x_ticks_labelled {
                out.push(Label::new(l, (pl.px(*v), r.y1 + 19.0), FONT_TICK, Anchor::Middle, TICK, Role::XTick(i)));
            }
        }
        for (v, l) in pl.y.ticks.iter().zip(&pl.y.labels) {
            out.push(Label::new(l, (r.x0 - 8.0, pl.py(*v) + 4.5), FONT_TICK, Anchor::End, TICK, Role::YTick(i)));
        }
        if pl.x_ticks_labelled {
            // Centred under the plot; moved (then shrunk) to stay on the canvas.
            let room = lay.width - 2.0 * MARGIN;
            let full = text_width(&pl.x_label, FONT_LABEL);
            let font = if full <= room { FONT_LABEL } else { (FONT_LABEL * room / full).max(MIN_FONT) };
            let half = text_width(&pl.x_label, font) / 2.0;
            let x = ((r.x0 + r.x1) / 2.0).min(lay.width - MARGIN - half).max(MARGIN + half);
            out.push(Label::new(&pl.x_label, (x, r.y1 + 40.0), font, Anchor::Middle, TITLE, Role::XLabel(i)));
        }
        let (ly, font) = pl.y_label_at;
        for (k, line) in pl.y_label_lines.iter().enumerate() {
            let x = 12.0 + FONT_LABEL - 2.0 + Y_LABEL_LINE * k as f64;
            let mut yl = Label::new(line, (x, ly), font, Anchor::Middle, TITLE, Role::YLabel(i));
            yl.vertical = true;
            out.push(yl);
        }
        if pl.legend.is_some() {
            for (e, &(sx, cy)) in pl.entries.iter().zip(&pl.legend_cells) {
                let at = (sx + SWATCH + 7.0, cy + 4.5);
                out.push(Label::new(&e.text, at, FONT_LEGEND, Anchor::Start, TITLE, Role::Legend(i)));
            }
        }
    }
    out.retain(|l| !l.text.trim().is_empty());
    out
}

/// What does not fit: a text outside the canvas, two texts over each other, a text over another
/// panel's legend box or a legend box off the canvas, an axis with fewer than two labelled ticks.
/// Empty when the figure lays out.
pub(crate) fn problems(fig: &Figure, lay: &Layout) -> Vec<String> {
    // Boxes may touch: half a pixel of slack against rounding.
    const SLACK: f64 = 0.5;
    let canvas = Rect { x0: 0.0, y0: 0.0, x1: lay.width, y1: lay.height }.grow(SLACK);
    let labels = labels(fig, lay);
    let rects: Vec<Rect> = labels.iter().map(|l| l.rect().grow(-SLACK)).collect();
    let mut out = Vec::new();
    let name = |l: &Label| format!("{} '{}'", l.role.describe(), l.text);
    for (l, r) in labels.iter().zip(&rects) {
        if !canvas.contains(r) {
            out.push(format!("{} runs off the canvas", name(l)));
        }
    }
    for i in 0..labels.len() {
        for j in i + 1..labels.len() {
            if rects[i].intersects(&rects[j]) {
                out.push(format!("{} meets {}", name(&labels[i]), name(&labels[j])));
            }
        }
    }
    for (k, pl) in lay.panels.iter().enumerate() {
        if let Some(b) = pl.legend {
            if !canvas.contains(&b) {
                out.push(format!("the legend of panel {} runs off the canvas", k + 1));
            }
            for (l, r) in labels.iter().zip(&rects) {
                if l.role != Role::Legend(k) && r.intersects(&b) {
                    out.push(format!("{} meets the legend of panel {}", name(l), k + 1));
                }
            }
        }
        if pl.y.ticks.len() < 2 {
            out.push(format!("the vertical axis of panel {} has {} labelled tick(s)", k + 1, pl.y.ticks.len()));
        }
        if pl.x_ticks_labelled && pl.x.ticks.len() < 2 {
            out.push(format!("the horizontal axis of panel {} has {} labelled tick(s)", k + 1, pl.x.ticks.len()));
        }
    }
    out
}
