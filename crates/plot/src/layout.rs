//! Where everything goes, in SVG pixels: axes and their ticks, plot rectangles, notes, legends.

use super::font::text_width;
use super::{Dash, Figure, Legend, Panel, RuleAxis, Scale, panel_weight};

pub(crate) const FONT_TITLE: f64 = 20.0;
pub(crate) const FONT_LABEL: f64 = 15.0;
pub(crate) const FONT_TICK: f64 = 13.0;
pub(crate) const FONT_LEGEND: f64 = 13.5;
pub(crate) const FONT_NOTE: f64 = 12.5;
pub(crate) const FONT_BAND: f64 = 12.0;
/// Height of one legend row.
pub(crate) const ROW: f64 = 19.0;
/// Inner margin of the legend box.
pub(crate) const PAD: f64 = 7.0;
/// Length of a legend swatch (long enough to show a dash-dot pattern twice).
pub(crate) const SWATCH: f64 = 34.0;
/// Marker radius.
pub(crate) const MARKER_R: f64 = 4.0;
/// Half the diagonal of an emphasised marker's diamond (px), its white outline included.
pub(crate) const DIAMOND_R: f64 = 7.0;
/// Strip above a plot holding the labels of its shaded intervals.
const BAND_STRIP: f64 = 17.0;

/// Colours of successive series (a palette readable on white and by most colour-blind readers).
pub const PALETTE: [[u8; 3]; 8] = [
    [0, 114, 178],
    [213, 94, 0],
    [0, 158, 115],
    [204, 121, 167],
    [230, 159, 0],
    [86, 180, 233],
    [0, 0, 0],
    [120, 120, 120],
];

/// An axis-aligned rectangle, `y` downwards.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rect {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Rect {
    pub fn new(x0: f64, y0: f64, w: f64, h: f64) -> Self {
        Self { x0, y0, x1: x0 + w, y1: y0 + h }
    }
    pub fn w(&self) -> f64 {
        self.x1 - self.x0
    }
    pub fn h(&self) -> f64 {
        self.y1 - self.y0
    }
    pub fn grow(&self, d: f64) -> Self {
        Self { x0: self.x0 - d, y0: self.y0 - d, x1: self.x1 + d, y1: self.y1 + d }
    }
    pub fn intersects(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }
    pub fn contains(&self, o: &Rect) -> bool {
        o.x0 >= self.x0 && o.x1 <= self.x1 && o.y0 >= self.y0 && o.y1 <= self.y1
    }
    /// Whether the segment `a`–`b` has a point inside (Liang–Barsky clipping).
    pub fn hit_by_segment(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [(-dx, a.0 - self.x0), (dx, self.x1 - a.0), (-dy, a.1 - self.y0), (dy, self.y1 - a.1)] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }
}

/// A scaled axis with its ticks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
    /// Labelled ticks.
    pub ticks: Vec<f64>,
    /// Tick labels.
    pub labels: Vec<String>,
    /// Grid lines without labels (the 2…9 of a decade).
    pub minor: Vec<f64>,
}

impl Axis {
    /// Position of `v` as a fraction of the axis (0 at `lo`, 1 at `hi`).
    pub fn frac(&self, v: f64) -> f64 {
        if self.log {
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }
}

/// What a legend row shows before its text.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Swatch {
    Line { color: [u8; 3], dash: Dash },
    Marker { color: [u8; 3], diamond: bool },
    Fill { color: [u8; 3] },
}

/// One legend row.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Entry {
    pub swatch: Swatch,
    pub text: String,
}

/// A note's dot and the box of its text.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NoteLayout {
    pub at: (f64, f64),
    pub text: Rect,
}

/// One panel in pixels.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PanelLayout {
    pub plot: Rect,
    pub x: Axis,
    pub y: Axis,
    pub x_label: String,
    /// Each series' polylines in pixels (a series breaks where a point is not drawable).
    pub curves: Vec<Vec<Vec<(f64, f64)>>>,
    pub colors: Vec<[u8; 3]>,
    pub notes: Vec<NoteLayout>,
    pub entries: Vec<Entry>,
    pub legend: Option<Rect>,
    /// Where each entry of the legend goes: the left end of its swatch and its centre line.
    pub legend_cells: Vec<(f64, f64)>,
    pub band_strip: bool,
    /// The vertical axis label: its centre line and font size (it stays inside the panel's slot).
    pub y_label_at: (f64, f64),
    /// The vertical axis label's lines, left to right: the label, or the label broken in two
    /// where in one line it does not fit its panel even in the smallest font.
    pub y_label_lines: Vec<String>,
    /// Whether the horizontal tick labels and axis label are drawn (a short panel over another
    /// of the same horizontal axis leaves them to the panel below).
    pub x_ticks_labelled: bool,
}

impl PanelLayout {
    pub fn px(&self, x: f64) -> f64 {
        self.plot.x0 + self.x.frac(x) * self.plot.w()
    }
    pub fn py(&self, y: f64) -> f64 {
        self.plot.y1 - self.y.frac(y) * self.plot.h()
    }
    /// A band's ends in pixels, cut to the axis (`None` when nothing of it is on the axis).
    pub fn band_px(&self, b: &super::XBand) -> Option<(f64, f64)> {
        let (a, z) = (b.from.min(b.to).max(self.x.lo), b.from.max(b.to).min(self.x.hi));
        (a.partial_cmp(&z) == Some(std::cmp::Ordering::Less)).then(|| (self.px(a), self.px(z)))
    }
}

/// The whole figure in pixels.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layout {
    pub width: f64,
    pub height: f64,
    /// The title's lines (none for an empty title) and its font size.
    pub title: Vec<String>,
    pub title_font: f64,
    pub panels: Vec<PanelLayout>,
}

/// Smallest font a long title is shrunk to before it is wrapped onto more lines.
const MIN_FONT_TITLE: f64 = 14.0;
/// Most lines of a wrapped title; the last is cut short (`…`) beyond them.
const MAX_TITLE_LINES: usize = 3;

/// Baseline of the title's first line for a font size (28 px for the usual 20 px).
pub(crate) fn title_baseline(font: f64) -> f64 {
    8.0 + font
}

/// Line spacing of a wrapped title.
pub(crate) fn title_line(font: f64) -> f64 {
    1.2 * font
}

/// The title in lines that fit `width` pixels, and their font: one line at the usual size when it
/// fits, else one line in a smaller font (down to [`MIN_FONT_TITLE`]), else wrapped at spaces (a
/// word longer than a line is broken) onto at most [`MAX_TITLE_LINES`] lines, the last cut short
/// with `…` if the title is longer still.
pub(crate) fn fit_title(title: &str, width: f64) -> (Vec<String>, f64) {
    let title = title.trim();
    if title.is_empty() {
        return (Vec::new(), FONT_TITLE);
    }
    let room = width - 16.0;
    let full = text_width(title, FONT_TITLE);
    if full <= room {
        return (vec![title.to_string()], FONT_TITLE);
    }
    if text_width(title, MIN_FONT_TITLE) <= room {
        let font = (FONT_TITLE * room / full).floor().max(MIN_FONT_TITLE);
        let font = if text_width(title, font) <= room { font } else { MIN_FONT_TITLE };
        return (vec![title.to_string()], font);
    }
    let font = MIN_FONT_TITLE;
    let fits = |s: &str| text_width(s, font) <= room;
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in title.split_whitespace() {
        let joined = if line.is_empty() { word.to_string() } else { format!("{line} {word}") };
        if fits(&joined) {
            line = joined;
            continue;
        }
        if !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        // A word wider than a line: broken where it must be.
        for c in word.chars() {
            line.push(c);
            if !fits(&line) {
                line.pop();
                lines.push(std::mem::take(&mut line));
                line.push(c);
            }
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    if lines.len() > MAX_TITLE_LINES {
        lines.truncate(MAX_TITLE_LINES);
        let last = &mut lines[MAX_TITLE_LINES - 1];
        while !last.is_empty() && !fits(&format!("{last}…")) {
            last.pop();
        }
        last.push('…');
    }
    (lines, font)
}

/// Whether a label names an angle in degrees.
pub(crate) fn is_angle(label: &str) -> bool {
    label.contains("[deg]") || label.contains("[°]")
}

pub(crate) fn layout(fig: &Figure) -> Layout {
    let (w, h) = fig.pixel_size();
    let (w, h) = (f64::from(w), f64::from(h));
    let (title, title_font) = fit_title(&fig.title, w);
    let top = match title.len() {
        0 => 8.0,
        n => title_baseline(title_font) + title_line(title_font) * (n - 1) as f64 + 12.0,
    };
    let total: f64 = fig.panels.iter().map(|p| panel_weight(p.weight)).sum();
    let mut slots = Vec::new();
    let mut y = top;
    for p in &fig.panels {
        let sh = (h - top - 4.0) * panel_weight(p.weight) / total;
        slots.push(Rect::new(0.0, y, w, sh));
        y += sh;
    }
    let entries: Vec<Vec<Entry>> = fig.panels.iter().map(legend_entries).collect();
    let sizes: Vec<(f64, f64)> = entries.iter().map(|e| legend_size(e)).collect();
    let mut outside: Vec<bool> =
        fig.panels.iter().zip(&entries).map(|(p, e)| p.legend == Legend::Outside && !e.is_empty()).collect();
    // A legend with no free place inside its plot goes in rows above that plot (the panel gives
    // up a little height) where that keeps most of the plot's height; else to the right, where
    // every stacked panel gives up the legend's width.
    let mut above = vec![false; fig.panels.len()];
    let mut tops = vec![0.0; fig.panels.len()];
    // Short stacked panels on one horizontal axis leave its ticks and label to the lowest.
    let mut shared = vec![false; fig.panels.len()];
    if slots.iter().any(|s| s.h() < COMPACT_SLOT) {
        let first = place_panels(fig, &slots, 18.0, &tops, &shared);
        for i in 0..first.len().saturating_sub(1) {
            let (a, b) = (&first[i], &first[i + 1]);
            shared[i] = a.x_label == b.x_label && a.x == b.x;
        }
    }
    let mut panels = Vec::new();
    for _ in 0..6 {
        let right = outside.iter().zip(&sizes).filter(|(o, _)| **o).map(|(_, s)| s.0 + 30.0).fold(18.0, f64::max);
        panels = place_panels(fig, &slots, right, &tops, &shared);
        let mut changed = false;
        for (i, (pl, p)) in panels.iter_mut().zip(&fig.panels).enumerate() {
            pl.entries = entries[i].clone();
            if p.legend == Legend::Hidden || entries[i].is_empty() {
                continue;
            }
            let (lw, lh) = sizes[i];
            if above[i] {
                let (rw, rh, cells) = legend_rows(&entries[i], pl.plot.w());
                if (tops[i] - (rh + LEGEND_GAP)).abs() > 0.5 {
                    tops[i] = rh + LEGEND_GAP;
                    changed = true;
                }
                let strip = if pl.band_strip { BAND_STRIP } else { 0.0 };
                let rect = Rect::new(pl.plot.x0, pl.plot.y0 - strip - tops[i], rw, rh);
                pl.legend_cells = cells.iter().map(|&(dx, dy)| (rect.x0 + dx, rect.y0 + dy)).collect();
                pl.legend = Some(rect);
                continue;
            }
            if !outside[i] {
                pl.legend = free_spot(pl, p, lw, lh);
                if pl.legend.is_none() {
                    let (_, rh, _) = legend_rows(&entries[i], pl.plot.w());
                    // On a narrow figure a column on the right would take the plot's width:
                    // rows above then, while the plot keeps some height.
                    let narrow = lw + 30.0 > NARROW_SHARE * w;
                    let rows_fit = rh + LEGEND_GAP <= (1.0 - MAX_HEIGHT_FOR_LEGEND) * pl.plot.h()
                        || (narrow && pl.plot.h() - rh - LEGEND_GAP >= MIN_PLOT_UNDER_LEGEND);
                    if rows_fit {
                        above[i] = true;
                    } else {
                        outside[i] = true;
                    }
                    changed = true;
                    continue;
                }
            }
            if outside[i] {
                pl.legend = Some(Rect::new(pl.plot.x1 + 14.0, pl.plot.y0, lw, lh));
            }
            if let Some(rect) = pl.legend {
                pl.legend_cells =
                    (0..entries[i].len()).map(|k| (rect.x0 + PAD, rect.y0 + PAD + ROW * k as f64 + 7.0)).collect();
            }
        }
        if !changed {
            break;
        }
    }
    Layout { width: w, height: h, title, title_font, panels }
}

/// Room under a plot for its tick labels and axis label.
const X_AXIS_ROOM: f64 = 50.0;
/// Space under a plot whose horizontal axis is labelled by the panel below.
const SHARED_AXIS_GAP: f64 = 14.0;
/// Panels of a figure whose slots are shorter share their horizontal axis (when it is the same).
const COMPACT_SLOT: f64 = 200.0;

/// Space between a legend in rows and the plot below it.
const LEGEND_GAP: f64 = 8.0;
/// Share of a plot's height a legend in rows above it may take; a larger legend goes to the right.
const MAX_HEIGHT_FOR_LEGEND: f64 = 0.35;
/// A legend column wider than this share of the figure makes it narrow: rows above instead.
const NARROW_SHARE: f64 = 0.3;
/// Least plot height left under a legend in rows on a narrow figure.
const MIN_PLOT_UNDER_LEGEND: f64 = 60.0;
/// Space between two entries of a row.
const ENTRY_GAP: f64 = 18.0;

/// Least spacing of two labelled vertical ticks on a short plot (a 13 px tick label's ink is
/// under 15 px tall).
const MIN_TICK_PX: f64 = 16.0;
/// Least gap between two horizontal tick labels.
const TICK_LABEL_GAP: f64 = 8.0;

/// Round ticks as close as their labels allow: vertical ones [`MIN_TICK_PX`] apart, horizontal
/// ones the widest label and [`TICK_LABEL_GAP`] apart (the smallest round step that keeps them so).
fn closest_ticks(lo: f64, hi: f64, len_px: f64, horizontal: bool) -> Axis {
    let span = (hi - lo).max(f64::MIN_POSITIVE);
    let mut step = nice_step(span * MIN_TICK_PX / len_px);
    for _ in 0..8 {
        let axis = ticks_axis(lo, hi, step);
        let widest = axis.labels.iter().map(|l| text_width(l, FONT_TICK)).fold(0.0, f64::max);
        if !horizontal || len_px * step / span >= widest + TICK_LABEL_GAP {
            return axis;
        }
        step = nice_step(step * 1.01);
    }
    ticks_axis(lo, hi, step)
}

/// The axis as laid out at the usual tick spacing, or, where that labels fewer than two ticks (a
/// short or narrow plot), at the least spacing its labels allow. Figures that lay out keep their
/// axes; only those that did not get the closer ticks.
fn two_ticks(axis: Axis, closer: impl FnOnce() -> Axis) -> Axis {
    if axis.ticks.len() < 2 { closer() } else { axis }
}

/// Smallest font of a vertical axis label shortened to fit its panel.
const MIN_FONT_LABEL: f64 = 10.0;

/// Where a vertical axis label goes (its centre, down the page) and its font size: centred on the
/// plot; when longer than the room about that centre (a short panel of a stacked figure), centred
/// on the panel's slot, and, if still too long, in a smaller font (not below [`MIN_FONT_LABEL`]),
/// so it does not run into the next panel's label.
/// The vertical axis label in lines, with its centre line and font ([`y_label_place`] of the
/// longest line): one line where it fits its slot (in a font down to [`MIN_FONT_LABEL`]), else two,
/// broken at the space that makes the longer line shortest (the unit then goes under the
/// quantity: `acceleration a = d²s/dx²` / `[-]`).
fn y_label_lines(label: &str, slot: &Rect, plot: &Rect) -> ((f64, f64), Vec<String>) {
    let one = y_label_place(label, slot, plot);
    // (The font was chosen to fill the room: a rounding's worth over it still fits.)
    if text_width(label, one.1) <= slot.h() - 4.0 + 1e-6 {
        return (one, vec![label.to_string()]);
    }
    let split = label
        .char_indices()
        .filter(|&(_, c)| c == ' ')
        .map(|(i, _)| (label[..i].trim_end(), label[i..].trim_start()))
        .filter(|(a, b)| !a.is_empty() && !b.is_empty())
        .min_by(|x, y| {
            let longer = |(a, b): &(&str, &str)| text_width(a, FONT_LABEL).max(text_width(b, FONT_LABEL));
            longer(x).total_cmp(&longer(y))
        });
    match split {
        Some((a, b)) => {
            let longest = if text_width(a, FONT_LABEL) >= text_width(b, FONT_LABEL) { a } else { b };
            (y_label_place(longest, slot, plot), vec![a.to_string(), b.to_string()])
        }
        None => (one, vec![label.to_string()]),
    }
}

/// Distance between the two lines of a vertical axis label broken in two (at the usual font).
pub(crate) const Y_LABEL_LINE: f64 = 1.15 * FONT_LABEL;

fn y_label_place(label: &str, slot: &Rect, plot: &Rect) -> (f64, f64) {
    let len = text_width(label, FONT_LABEL);
    let centre = (plot.y0 + plot.y1) / 2.0;
    if len <= 2.0 * (centre - slot.y0).min(slot.y1 - centre) - 4.0 {
        return (centre, FONT_LABEL);
    }
    let room = slot.h() - 4.0;
    let font = if len <= room { FONT_LABEL } else { (FONT_LABEL * room / len).max(MIN_FONT_LABEL) };
    ((slot.y0 + slot.y1) / 2.0, font)
}

/// A legend laid out in rows across `width`: its width and height, and each entry's swatch start
/// and centre line relative to the box.
fn legend_rows(e: &[Entry], width: f64) -> (f64, f64, Vec<(f64, f64)>) {
    let mut cells = Vec::new();
    let (mut x, mut row, mut widest) = (0.0f64, 0usize, 0.0f64);
    for entry in e {
        let w = SWATCH + 7.0 + text_width(&entry.text, FONT_LEGEND) * 1.04;
        if x > 0.0 && x + ENTRY_GAP + w > width - 2.0 * PAD {
            row += 1;
            x = 0.0;
        }
        let at = if x > 0.0 { x + ENTRY_GAP } else { 0.0 };
        cells.push((PAD + at, PAD + ROW * row as f64 + 7.0));
        x = at + w;
        widest = widest.max(x);
    }
    (2.0 * PAD + widest, 2.0 * PAD + ROW * (row + 1) as f64 - 4.0, cells)
}

fn legend_entries(p: &Panel) -> Vec<Entry> {
    let mut out = Vec::new();
    for (i, s) in p.series.iter().enumerate() {
        if s.label.is_empty() {
            continue;
        }
        let color = series_color(p, i);
        let swatch = if s.markers {
            Swatch::Marker { color, diamond: s.emphasis }
        } else {
            Swatch::Line { color, dash: s.dash }
        };
        out.push(Entry { swatch, text: s.label.clone() });
    }
    for b in p.y_bands.iter().filter(|b| !b.label.is_empty()) {
        out.push(Entry { swatch: Swatch::Fill { color: b.color }, text: b.label.clone() });
    }
    for r in p.rules.iter().filter(|r| !r.label.is_empty()) {
        out.push(Entry { swatch: Swatch::Line { color: r.color, dash: r.dash }, text: r.label.clone() });
    }
    out
}

pub(crate) fn series_color(p: &Panel, i: usize) -> [u8; 3] {
    p.series[i].color.unwrap_or(PALETTE[i % PALETTE.len()])
}

fn legend_size(e: &[Entry]) -> (f64, f64) {
    let text = e.iter().map(|e| text_width(&e.text, FONT_LEGEND)).fold(0.0, f64::max);
    (2.0 * PAD + SWATCH + 7.0 + text * 1.04, 2.0 * PAD + ROW * e.len() as f64 - 4.0)
}

/// Range of finite values with a margin; a single value gets a band around it.
fn linear_bounds(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span <= 1e-12 * (1.0 + lo.abs().max(hi.abs())) {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return (lo - d, hi + d);
    }
    (lo - pad * span, hi + pad * span)
}

/// Decades around the positive values (at most 15 of them, counted down from the largest value;
/// from the decade of `floor` when one is given).
pub(crate) fn log_bounds(values: impl Iterator<Item = f64>, floor: Option<f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if !lo.is_finite() {
        return (0.1, 10.0);
    }
    let mut k_hi = hi.log10().ceil();
    let mut k_lo = lo.log10().floor();
    if k_hi <= k_lo {
        k_hi = k_lo + 1.0;
    }
    k_lo = k_lo.max(k_hi - 15.0);
    if let Some(f) = floor.filter(|f| f.is_finite() && *f > 0.0) {
        k_lo = f.log10().floor().min(k_hi - 1.0);
    }
    if k_hi - k_lo < 1.0 {
        k_hi = k_lo + 1.0;
    }
    (10f64.powf(k_lo), 10f64.powf(k_hi))
}

/// A round step (1, 2 or 5 × 10^k) at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * mag).find(|s| *s >= raw * (1.0 - 1e-9)).unwrap_or(10.0 * mag)
}

/// Ticks at multiples of `step` inside `[lo, hi]`.
fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last).map(|k| if k == 0 { 0.0 } else { k as f64 * step }).collect()
}

/// A tick label with the decimals `step` needs: no `-0`, no trailing zeros.
pub(crate) fn tick_label(v: f64, step: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    if v.abs() < 1e-9 * step {
        return "0".into();
    }
    let decimals = (-(step.log10() - 1e-9).floor()).clamp(0.0, 15.0) as usize;
    let text = format!("{v:.decimals$}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text };
    if text == "-0" { "0".into() } else { text.replace('-', "−") }
}

/// A decade's label, `10ᵏ` with a superscript exponent (`10⁻⁵`, `10⁰`, `10³`).
pub(crate) fn decade_label(k: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for d in k.unsigned_abs().to_string().bytes() {
        s.push(SUP[usize::from(d - b'0')]);
    }
    s
}

/// Linear ticks at least `min_px` apart on an axis `len_px` long.
fn linear_axis(lo: f64, hi: f64, len_px: f64, min_px: f64) -> Axis {
    let n = (len_px / min_px).floor().max(2.0);
    let mut step = nice_step((hi - lo) / n);
    // At least two labelled ticks: the next smaller round step (50 → 20 → 10) while the labels
    // keep more than half the usual room.
    while multiples(lo, hi, step).len() < 2 {
        let smaller = nice_step(0.39 * step);
        if smaller >= step || len_px * smaller / (hi - lo) < 0.55 * min_px {
            break;
        }
        step = smaller;
    }
    ticks_axis(lo, hi, step)
}

fn ticks_axis(lo: f64, hi: f64, step: f64) -> Axis {
    let ticks = multiples(lo, hi, step);
    let labels = ticks.iter().map(|&v| tick_label(v, step)).collect();
    Axis { lo, hi, log: false, ticks, labels, minor: Vec::new() }
}

/// Angle ticks: every 30°, 45° or 90°, the first at least `min_px` apart (180° or a round number
/// of turns on a long span; ordinary round steps below 60°).
pub(crate) fn angle_axis(lo: f64, hi: f64, len_px: f64, min_px: f64) -> Axis {
    let span = hi - lo;
    if span < 60.0 {
        return linear_axis(lo, hi, len_px, min_px);
    }
    let fits = |step: f64| len_px * step / span >= min_px;
    // Beyond 90°: 180°, then whole turns in round numbers (360°, 720°, 1800°, 3600°, …), so that a
    // pattern repeat of many picks is ticked at picks, not at 1170°.
    let step = [30.0, 45.0, 90.0, 180.0, 360.0]
        .into_iter()
        .find(|s| fits(*s))
        .unwrap_or_else(|| 360.0 * nice_step(span * min_px / len_px / 360.0));
    ticks_axis(lo, hi, step)
}

/// A degree axis ticked at whole turns (labelled with their count, at least `min_px` apart) with
/// minor ticks at degrees within a turn (30°, 45°, 90° or 180°, the first at least
/// [`MIN_MINOR_PX`] apart; none when even 180° is closer). Returns the axis and the minor step.
pub(crate) fn turns_axis(lo: f64, hi: f64, len_px: f64, min_px: f64) -> (Axis, Option<f64>) {
    let span = (hi - lo).max(1e-9);
    let px_per_turn = len_px * 360.0 / span;
    let turns = nice_step((min_px / px_per_turn).max(1.0));
    let ticks = multiples(lo, hi, 360.0 * turns);
    let labels = ticks.iter().map(|t| tick_label(t / 360.0, 1.0)).collect();
    let minor_step = [30.0, 45.0, 90.0, 180.0].into_iter().find(|s| len_px * s / span >= MIN_MINOR_PX);
    let minor = minor_step.map_or_else(Vec::new, |m| {
        multiples(lo, hi, m).into_iter().filter(|v| (v / 360.0 - (v / 360.0).round()).abs() > 1e-9).collect()
    });
    (Axis { lo, hi, log: false, ticks, labels, minor }, minor_step)
}

/// Least spacing of minor ticks within a turn.
const MIN_MINOR_PX: f64 = 6.0;

/// Decade ticks (every k-th labelled if they would crowd) with 2…9 grid lines when few decades.
pub(crate) fn log_axis(lo: f64, hi: f64, len_px: f64, min_px: f64) -> Axis {
    let (k0, k1) = (lo.log10().round() as i32, hi.log10().round() as i32);
    let every = ((f64::from(k1 - k0) * min_px / len_px).ceil() as i32).max(1);
    let ks: Vec<i32> = (k0..=k1).filter(|k| (k - k0) % every == 0).collect();
    let mut minor = Vec::new();
    for k in k0..k1 {
        if every == 1 && k1 - k0 <= 8 {
            minor.extend((2..=9).map(|m| f64::from(m) * 10f64.powi(k)));
        } else if every > 1 && (k - k0) % every != 0 {
            minor.push(10f64.powi(k));
        }
    }
    Axis {
        lo,
        hi,
        log: true,
        ticks: ks.iter().map(|&k| 10f64.powi(k)).collect(),
        labels: ks.iter().map(|&k| decade_label(k)).collect(),
        minor,
    }
}

fn place_panels(fig: &Figure, slots: &[Rect], right: f64, tops: &[f64], shared: &[bool]) -> Vec<PanelLayout> {
    // Vertical axes first (they depend on heights only), so every plot can share one left edge.
    let mut pre = Vec::new();
    for (((p, slot), top), &shared) in fig.panels.iter().zip(slots).zip(tops).zip(shared) {
        let band_strip = p.x_bands.iter().any(|b| !b.label.is_empty());
        let y0 = slot.y0 + 10.0 + top + if band_strip { BAND_STRIP } else { 0.0 };
        let y1 = slot.y1 - if shared { SHARED_AXIS_GAP } else { X_AXIS_ROOM };
        let plot_h = (y1 - y0).max(20.0);
        let ys = || {
            p.series
                .iter()
                .flat_map(|s| s.points.iter().map(|q| q.1))
                .chain(p.notes.iter().map(|n| n.y))
                .chain(p.rules.iter().filter(|r| r.axis == RuleAxis::Y).map(|r| r.value))
                .chain(p.y_bands.iter().flat_map(|b| [b.from, b.to]))
        };
        let y_axis = if p.y_scale == Scale::Log {
            let (lo, hi) = log_bounds(ys(), p.y_floor);
            log_axis(lo, hi, plot_h, 26.0)
        } else {
            let (lo, hi) = linear_bounds(ys(), 0.06);
            let axis =
                if is_angle(&p.y_label) { angle_axis(lo, hi, plot_h, 30.0) } else { linear_axis(lo, hi, plot_h, 28.0) };
            // A plot too short for two labelled ticks at the usual spacing: round steps as close
            // as the tick labels' height allows.
            two_ticks(axis, || {
                if is_angle(&p.y_label) {
                    angle_axis(lo, hi, plot_h, MIN_TICK_PX)
                } else {
                    closest_ticks(lo, hi, plot_h, false)
                }
            })
        };
        pre.push((y0, y0 + plot_h, y_axis, band_strip));
    }
    let y_labels: Vec<((f64, f64), Vec<String>)> = fig
        .panels
        .iter()
        .zip(slots)
        .zip(&pre)
        .map(|((p, slot), (y0, y1, _, _))| {
            y_label_lines(&p.y_label, slot, &Rect { x0: 0.0, y0: *y0, x1: 0.0, y1: *y1 })
        })
        .collect();
    let two_lines = y_labels.iter().any(|(_, l)| l.len() > 1);
    let tick_w = pre.iter().flat_map(|p| p.2.labels.iter()).map(|l| text_width(l, FONT_TICK)).fold(0.0, f64::max);
    let left = 12.0 + FONT_LABEL + 12.0 + tick_w + 8.0 + if two_lines { Y_LABEL_LINE } else { 0.0 };
    let width = slots.first().map_or(0.0, |s| s.w());
    let x1 = (width - right).max(left + 40.0);
    let mut out = Vec::new();
    for ((((p, _), (y0, y1, mut y_axis, band_strip)), &shared), (y_label_at, y_label_lines)) in
        fig.panels.iter().zip(slots).zip(pre).zip(shared).zip(y_labels)
    {
        let plot = Rect { x0: left, y0, x1, y1 };
        let mut x_label = p.x_label.clone().unwrap_or_else(|| fig.x_label.clone());
        let xs = || {
            p.series
                .iter()
                .flat_map(|s| s.points.iter().map(|q| q.0))
                .chain(p.notes.iter().map(|n| n.x))
                .chain(p.rules.iter().filter(|r| r.axis == RuleAxis::X).map(|r| r.value))
        };
        let only_markers = p.series.iter().all(|s| s.markers || s.points.is_empty());
        let (mut lo, mut hi) = linear_bounds(xs(), if only_markers || p.equal_aspect { 0.04 } else { 0.0 });
        let x_axis = if p.equal_aspect && !y_axis.log {
            let (ylo, yhi) = (y_axis.lo, y_axis.hi);
            let scale = ((hi - lo) / plot.w()).max((yhi - ylo) / plot.h());
            let (cx, cy) = ((lo + hi) / 2.0, (ylo + yhi) / 2.0);
            (lo, hi) = (cx - scale * plot.w() / 2.0, cx + scale * plot.w() / 2.0);
            let (a, b) = (cy - scale * plot.h() / 2.0, cy + scale * plot.h() / 2.0);
            y_axis = two_ticks(linear_axis(a, b, plot.h(), 28.0), || closest_ticks(a, b, plot.h(), false));
            two_ticks(linear_axis(lo, hi, plot.w(), 80.0), || closest_ticks(lo, hi, plot.w(), true))
        } else if fig.turns_axis && p.x_label.is_none() {
            let (axis, minor) = turns_axis(lo, hi, plot.w(), 44.0);
            if let Some(m) = minor {
                x_label = format!("{x_label}, minor ticks every {m}°");
            }
            axis
        } else if is_angle(&x_label) {
            angle_axis(lo, hi, plot.w(), 44.0)
        } else {
            two_ticks(linear_axis(lo, hi, plot.w(), 80.0), || closest_ticks(lo, hi, plot.w(), true))
        };
        let mut pl = PanelLayout {
            plot,
            x: x_axis,
            y: y_axis,
            x_label,
            curves: Vec::new(),
            colors: (0..p.series.len()).map(|i| series_color(p, i)).collect(),
            notes: Vec::new(),
            entries: Vec::new(),
            legend: None,
            legend_cells: Vec::new(),
            band_strip,
            y_label_at,
            y_label_lines,
            x_ticks_labelled: !shared,
        };
        pl.curves = p.series.iter().map(|s| polylines(&pl, &s.points)).collect();
        pl.notes = place_notes(&pl, p);
        out.push(pl);
    }
    out
}

/// A series in pixels, split where a point cannot be drawn (not finite, or ≤ 0 on a log axis).
fn polylines(pl: &PanelLayout, points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut run = Vec::new();
    for &(x, y) in points {
        let ok = x.is_finite() && y.is_finite() && (!pl.y.log || y > 0.0) && (!pl.x.log || x > 0.0);
        if ok {
            run.push((pl.px(x), pl.py(y)));
        } else if !run.is_empty() {
            out.push(std::mem::take(&mut run));
        }
    }
    if !run.is_empty() {
        out.push(run);
    }
    out
}

/// Whether a box meets a curve, a marker, a rule, a band edge or an earlier note of the panel.
fn blocked(pl: &PanelLayout, p: &Panel, r: &Rect, notes: &[NoteLayout]) -> bool {
    for (s, curve) in p.series.iter().zip(&pl.curves) {
        for run in curve {
            if s.markers {
                let m = if s.emphasis { DIAMOND_R } else { MARKER_R };
                if run.iter().any(|&(x, y)| r.intersects(&Rect::new(x - m, y - m, 2.0 * m, 2.0 * m))) {
                    return true;
                }
            } else if run.len() == 1 {
                if r.hit_by_segment(run[0], run[0]) {
                    return true;
                }
            } else if run.windows(2).any(|w| r.hit_by_segment(w[0], w[1])) {
                return true;
            }
        }
    }
    for rule in &p.rules {
        let hit = match rule.axis {
            RuleAxis::Y => {
                let y = pl.py(rule.value);
                r.hit_by_segment((pl.plot.x0, y), (pl.plot.x1, y))
            }
            RuleAxis::X => {
                let x = pl.px(rule.value);
                r.hit_by_segment((x, pl.plot.y0), (x, pl.plot.y1))
            }
        };
        if hit {
            return true;
        }
    }
    for b in &p.y_bands {
        for v in [b.from, b.to] {
            let y = pl.py(v);
            if r.hit_by_segment((pl.plot.x0, y), (pl.plot.x1, y)) {
                return true;
            }
        }
    }
    notes.iter().any(|n| r.intersects(&n.text) || r.intersects(&Rect::new(n.at.0 - 4.0, n.at.1 - 4.0, 8.0, 8.0)))
}

fn place_notes(pl: &PanelLayout, p: &Panel) -> Vec<NoteLayout> {
    let mut out: Vec<NoteLayout> = Vec::new();
    for n in &p.notes {
        if !(n.x.is_finite() && n.y.is_finite()) || (pl.y.log && n.y <= 0.0) {
            continue;
        }
        let at = (pl.px(n.x), pl.py(n.y));
        if n.text.is_empty() {
            out.push(NoteLayout { at, text: Rect::new(at.0, at.1, 0.0, 0.0) });
            continue;
        }
        let (w, h) = (text_width(&n.text, FONT_NOTE) * 1.04 + 4.0, FONT_NOTE + 4.0);
        // Beside the dot first, then farther out (the dot stays where the value is).
        let mut candidates = Vec::new();
        for k in [1.0, 2.5, 4.5] {
            let d = 6.0 * k;
            candidates.extend([
                (at.0 + d, at.1 - d - h),
                (at.0 - d - w, at.1 - d - h),
                (at.0 + d, at.1 + d),
                (at.0 - d - w, at.1 + d),
                (at.0 + 1.5 * d, at.1 - h / 2.0),
                (at.0 - 1.5 * d - w, at.1 - h / 2.0),
                (at.0 - w / 2.0, at.1 - 1.5 * d - h),
                (at.0 - w / 2.0, at.1 + 1.5 * d),
            ]);
        }
        let boxes: Vec<Rect> = candidates.iter().map(|&(x, y)| Rect::new(x, y, w, h)).collect();
        let inside = |r: &Rect| pl.plot.contains(r);
        let text = boxes
            .iter()
            .find(|r| inside(r) && !blocked(pl, p, r, &out))
            .or_else(|| boxes.iter().find(|r| inside(r)))
            .copied()
            .unwrap_or_else(|| {
                let x = (at.0 + 6.0).min(pl.plot.x1 - w).max(pl.plot.x0);
                let y = (at.1 - 6.0 - h).max(pl.plot.y0).min(pl.plot.y1 - h);
                Rect::new(x, y, w, h)
            });
        out.push(NoteLayout { at, text });
    }
    out
}

/// A place inside the plot for a `w` × `h` legend where nothing is drawn: the corners and edge
/// middles first, then any free place on a 10-pixel grid (nearest the upper right first).
fn free_spot(pl: &PanelLayout, p: &Panel, w: f64, h: f64) -> Option<Rect> {
    let plot = pl.plot;
    let m = 8.0;
    if w + 2.0 * m > plot.w() || h + 2.0 * m > plot.h() {
        return None;
    }
    let (l, r, t, b) = (plot.x0 + m, plot.x1 - m - w, plot.y0 + m, plot.y1 - m - h);
    let (cx, cy) = ((l + r) / 2.0, (t + b) / 2.0);
    let mut candidates = vec![(r, t), (l, t), (r, b), (l, b), (cx, t), (cx, b), (r, cy), (l, cy)];
    let mut grid = Vec::new();
    let mut y = t;
    while y <= b {
        let mut x = r;
        while x >= l {
            grid.push((x, y));
            x -= 10.0;
        }
        y += 10.0;
    }
    grid.sort_by(|a, b| {
        let d = |q: &(f64, f64)| (r - q.0).hypot(q.1 - t);
        d(a).total_cmp(&d(b))
    });
    candidates.extend(grid);
    candidates.into_iter().map(|(x, y)| Rect::new(x, y, w, h)).find(|rect| !blocked(pl, p, &rect.grow(3.0), &pl.notes))
}
