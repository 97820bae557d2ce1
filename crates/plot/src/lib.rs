//! # loomkin-plot — stacked line plots for reports, written as SVG and rasterised to PNG
//!
//! A [`Figure`] is a column of [`Panel`]s; each panel overlays [`Series`] (lines in solid, dashed,
//! dotted or dash-dot strokes, or markers) and marks what matters: shaded angle intervals
//! ([`XBand`], e.g. dwell / rise / return), horizontal bands ([`YBand`], e.g. a threshold band),
//! limit lines ([`Rule`]) and annotated points ([`Note`], e.g. a peak and its value). Axis labels
//! are written `quantity [unit]`; an axis in degrees is ticked at 30°, 45° or 90° (whichever its
//! length in pixels allows), a [`Scale::Log`] axis at decades.
//!
//! The legend is placed where no curve, limit line or note is: the first free corner or edge of
//! the plot, else outside it on the right (all panels then share the narrower plot width, so
//! stacked panels keep one horizontal scale). Its swatches draw each line's own dash pattern.
//!
//! The figure is written as SVG by this crate; a PNG is that SVG rasterised by `resvg`
//! (antialiased, with shaped text), scaled by the figure's DPI (96 = one pixel per SVG unit) and
//! tagged with that DPI. The text font is Ubuntu Light (Ubuntu Font Licence 1.0), with Hack (MIT
//! and Bitstream Vera licence) for glyphs it lacks, both embedded from the `epaint_default_fonts`
//! crate, so plotting needs no system fonts and no C library.

mod font;
mod labels;
mod layout;
mod raster;
mod svg;

pub use layout::PALETTE;

use loomkin_io::IoError;
use loomkin_units::{Field, Range, RangeError};
use std::path::Path;

/// Stroke pattern of a line (drawn the same in the legend swatch).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Dash {
    /// A continuous line.
    #[default]
    Solid,
    /// Long dashes.
    Dashed,
    /// Dots.
    Dotted,
    /// Dash and dot.
    DashDot,
}

impl Dash {
    /// The SVG `stroke-dasharray` (`None` for a solid line).
    pub(crate) fn dasharray(self) -> Option<&'static str> {
        match self {
            Dash::Solid => None,
            Dash::Dashed => Some("9 5"),
            Dash::Dotted => Some("2 4"),
            Dash::DashDot => Some("10 4 2 4"),
        }
    }
}

/// One curve.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Legend text (none: not in the legend).
    pub label: String,
    /// Points `(x, y)`; a non-finite point breaks the line.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points instead of a line.
    pub markers: bool,
    /// Colour as RGB; `None` takes the series' place in the palette.
    pub color: Option<[u8; 3]>,
    /// Stroke pattern.
    pub dash: Dash,
    /// Markers drawn as larger diamonds with a white outline (see [`Series::emphasised`]).
    pub emphasis: bool,
}

impl Series {
    /// The same markers drawn as larger diamonds with a white outline, so a point of reference
    /// (a preset beside a Pareto front's dots) stands out wherever it falls; draw it after the
    /// series it may cover.
    pub fn emphasised(mut self) -> Self {
        self.emphasis = true;
        self
    }

    /// A line through the points.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { label: label.into(), points, ..Self::default() }
    }

    /// Markers at the points.
    pub fn markers(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { label: label.into(), points, markers: true, ..Self::default() }
    }

    /// Circles of radius `r` about each centre (a roller drawn to scale in an equal-aspect
    /// drawing), as one line: each circle a closed polygon of [`CIRCLE_SIDES`] sides, the circles
    /// parted by a break. A radius that is not positive and finite draws nothing.
    pub fn circles(label: impl Into<String>, centres: &[(f64, f64)], r: f64) -> Self {
        let mut points = Vec::new();
        if r.is_finite() && r > 0.0 {
            for (k, &(cx, cy)) in centres.iter().enumerate() {
                if k > 0 {
                    points.push((f64::NAN, f64::NAN));
                }
                let start = points.len();
                points.extend((0..CIRCLE_SIDES).map(|i| {
                    let t = std::f64::consts::TAU * i as f64 / CIRCLE_SIDES as f64;
                    (cx + r * t.cos(), cy + r * t.sin())
                }));
                points.push(points[start]);
            }
        }
        Self::line(label, points)
    }

    /// The same series in a given colour.
    pub fn with_color(mut self, rgb: [u8; 3]) -> Self {
        self.color = Some(rgb);
        self
    }

    /// The same series drawn dashed.
    pub fn with_dashes(self) -> Self {
        self.with_dash(Dash::Dashed)
    }

    /// The same series drawn with a stroke pattern.
    pub fn with_dash(mut self, dash: Dash) -> Self {
        self.dash = dash;
        self
    }
}

/// Sides of the polygon that draws a circle ([`Series::circles`]): its chord error is
/// 1 − cos(π/96) ≈ 0.05 % of the radius, under a pixel for a circle up to 2,000 px across.
pub const CIRCLE_SIDES: usize = 96;

/// A shaded interval of the horizontal axis, labelled above the plot (a dwell, a rise, a window).
#[derive(Debug, Clone, PartialEq)]
pub struct XBand {
    /// Start, in horizontal-axis units.
    pub from: f64,
    /// End.
    pub to: f64,
    /// Label over the band (left out where the band is too narrow for it).
    pub label: String,
    /// Fill colour (drawn translucent).
    pub color: [u8; 3],
}

impl XBand {
    /// Grey: nothing moves.
    pub const DWELL: [u8; 3] = [150, 150, 150];
    /// Green: a rise.
    pub const RISE: [u8; 3] = [0, 158, 115];
    /// Orange: a return.
    pub const RETURN: [u8; 3] = [230, 159, 0];
    /// Blue: a window (a time or angle where something must happen).
    pub const WINDOW: [u8; 3] = [86, 180, 233];

    /// A band from `from` to `to`.
    pub fn new(from: f64, to: f64, label: impl Into<String>, color: [u8; 3]) -> Self {
        Self { from, to, label: label.into(), color }
    }
}

/// A shaded interval of the vertical axis, named in the legend (a threshold band).
#[derive(Debug, Clone, PartialEq)]
pub struct YBand {
    /// Lower edge, in vertical-axis units.
    pub from: f64,
    /// Upper edge.
    pub to: f64,
    /// Legend text.
    pub label: String,
    /// Fill colour (drawn translucent).
    pub color: [u8; 3],
}

impl YBand {
    /// A band from `from` to `to`.
    pub fn new(from: f64, to: f64, label: impl Into<String>, color: [u8; 3]) -> Self {
        Self { from, to, label: label.into(), color }
    }
}

/// Which axis a [`Rule`] gives a value of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RuleAxis {
    /// A horizontal line at a vertical value (a torque or pressure-angle limit).
    Y,
    /// A vertical line at a horizontal value (an angle, a speed).
    X,
}

/// A straight reference line across the plot (a limit), named in the legend.
#[derive(Debug, Clone, PartialEq)]
pub struct Rule {
    /// The axis the value is on.
    pub axis: RuleAxis,
    /// The value.
    pub value: f64,
    /// Legend text.
    pub label: String,
    /// Colour.
    pub color: [u8; 3],
    /// Stroke pattern.
    pub dash: Dash,
}

impl Rule {
    /// Red, for a limit that must not be crossed.
    pub const LIMIT: [u8; 3] = [200, 30, 30];

    /// A horizontal limit line at `value`, red and dashed.
    pub fn y(value: f64, label: impl Into<String>) -> Self {
        Self { axis: RuleAxis::Y, value, label: label.into(), color: Self::LIMIT, dash: Dash::Dashed }
    }

    /// A vertical line at `value`, red and dashed.
    pub fn x(value: f64, label: impl Into<String>) -> Self {
        Self { axis: RuleAxis::X, value, label: label.into(), color: Self::LIMIT, dash: Dash::Dashed }
    }

    /// The same line in another colour.
    pub fn with_color(mut self, rgb: [u8; 3]) -> Self {
        self.color = rgb;
        self
    }

    /// The same line with another stroke pattern.
    pub fn with_dash(mut self, dash: Dash) -> Self {
        self.dash = dash;
        self
    }
}

/// An annotated point: a dot and its text, placed beside it where no curve is (an empty text
/// draws the dot only, for a value given in the legend).
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// Horizontal position.
    pub x: f64,
    /// Vertical position.
    pub y: f64,
    /// The text (e.g. `peak 12.3 m/s² at 47°`).
    pub text: String,
}

impl Note {
    /// A note at `(x, y)`.
    pub fn new(x: f64, y: f64, text: impl Into<String>) -> Self {
        Self { x, y, text: text.into() }
    }
}

/// Scale of the vertical axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scale {
    /// Linear.
    #[default]
    Linear,
    /// Logarithmic, ticked at decades and labelled `10ᵏ`; values ≤ 0 are not drawn (the line
    /// breaks there) and no value is moved: a value below the axis floor (see
    /// [`Panel::with_log_y_floor`]) runs off the bottom of the plot where it is.
    Log,
}

/// Where a panel's legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Inside the plot where nothing is drawn, else outside on the right.
    #[default]
    Auto,
    /// Outside the plot, on the right.
    Outside,
    /// No legend on this panel.
    Hidden,
}

/// One chart of a figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Vertical axis label, `quantity [unit]`.
    pub y_label: String,
    /// Horizontal axis label for this panel (defaults to the figure's).
    pub x_label: Option<String>,
    /// The curves.
    pub series: Vec<Series>,
    /// Same scale on both axes (for drawings such as cam profiles).
    pub equal_aspect: bool,
    /// Where the legend goes.
    pub legend: Legend,
    /// Vertical scale.
    pub y_scale: Scale,
    /// Lowest value of a logarithmic vertical axis (rounded down to a decade); `None`: the
    /// decade of the smallest positive value, at most 15 decades below the largest.
    pub y_floor: Option<f64>,
    /// Shaded intervals of the horizontal axis.
    pub x_bands: Vec<XBand>,
    /// Shaded intervals of the vertical axis.
    pub y_bands: Vec<YBand>,
    /// Reference lines.
    pub rules: Vec<Rule>,
    /// Annotated points.
    pub notes: Vec<Note>,
    /// Height relative to the other panels (1 by default).
    pub weight: f64,
}

impl Default for Panel {
    fn default() -> Self {
        Self {
            y_label: String::new(),
            x_label: None,
            series: Vec::new(),
            equal_aspect: false,
            legend: Legend::Auto,
            y_scale: Scale::Linear,
            y_floor: None,
            x_bands: Vec::new(),
            y_bands: Vec::new(),
            rules: Vec::new(),
            notes: Vec::new(),
            weight: 1.0,
        }
    }
}

impl Panel {
    /// A panel with a label and curves.
    pub fn new(y_label: impl Into<String>, series: Vec<Series>) -> Self {
        Self { y_label: y_label.into(), series, ..Self::default() }
    }

    /// The same panel with its legend placed otherwise (or hidden).
    pub fn with_legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
        self
    }

    /// The same panel with a logarithmic vertical axis.
    pub fn with_log_y(mut self) -> Self {
        self.y_scale = Scale::Log;
        self
    }

    /// The same panel with a logarithmic vertical axis starting at the decade of `floor` (> 0):
    /// for values that reach exact zeros (a residual-vibration spectrum), whose decades below a
    /// few under the largest value say nothing. Points below the floor are drawn where they are
    /// (clipped by the plot), never raised to it.
    pub fn with_log_y_floor(mut self, floor: f64) -> Self {
        self.y_scale = Scale::Log;
        self.y_floor = (floor.is_finite() && floor > 0.0).then_some(floor);
        self
    }

    /// The same panel with its own horizontal label.
    pub fn with_x_label(mut self, x_label: impl Into<String>) -> Self {
        self.x_label = Some(x_label.into());
        self
    }

    /// The same panel with shaded intervals added.
    pub fn with_x_bands(mut self, bands: impl IntoIterator<Item = XBand>) -> Self {
        self.x_bands.extend(bands);
        self
    }

    /// The same panel with a horizontal band added.
    pub fn with_y_band(mut self, band: YBand) -> Self {
        self.y_bands.push(band);
        self
    }

    /// The same panel with a reference line added.
    pub fn with_rule(mut self, rule: Rule) -> Self {
        self.rules.push(rule);
        self
    }

    /// The same panel with annotated points added.
    pub fn with_notes(mut self, notes: impl IntoIterator<Item = Note>) -> Self {
        self.notes.extend(notes);
        self
    }

    /// The same panel drawn `weight` times as tall as a panel of weight 1.
    pub fn with_weight(mut self, weight: f64) -> Self {
        self.weight = weight;
        self
    }
}

/// A column of panels.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title over the first panel.
    pub title: String,
    /// Horizontal axis label, `quantity [unit]`.
    pub x_label: String,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
    /// Size in SVG pixels (1/96 in); `None` picks 1000 × (280 per panel + 50).
    pub size: Option<(u32, u32)>,
    /// Resolution of a PNG: 96 draws one PNG pixel per SVG pixel, 192 two.
    pub dpi: f64,
    /// The horizontal axis, in main-shaft degrees, is ticked at whole turns (picks) with the
    /// degrees within a turn as minor ticks (see [`Figure::with_turns_axis`]).
    pub turns_axis: bool,
}

/// Allowed figure width and height in SVG pixels (a figure may need more than the lower bound to
/// lay out: see [`Figure::with_page`]).
pub const SIZE_PX: Range = Range::closed(SIZE_MIN, SIZE_MAX, "px");
const SIZE_MIN: f64 = 200.0;
const SIZE_MAX: f64 = 8000.0;
/// Allowed PNG resolution.
pub const DPI: Range = Range::closed(DPI_MIN, 1200.0, "dpi");
const DPI_MIN: f64 = 24.0;
/// The resolution at which one SVG pixel is one PNG pixel.
const DPI_NATIVE: f64 = 96.0;
/// The page fields of this crate (for the field reference and the front ends).
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![Page::WIDTH, Page::HEIGHT, Page::DPI];

/// Largest PNG drawn, in pixels (a 10 000 × 10 000 image takes 400 MB while drawn).
pub const MAX_PNG_PIXELS: f64 = 1e8;
/// Longest title, in characters.
pub const MAX_TITLE_CHARS: usize = 200;

/// Page settings a user gives for a figure: size, resolution and title (all optional).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Page {
    /// Width in SVG pixels.
    pub width: Option<f64>,
    /// Height in SVG pixels.
    pub height: Option<f64>,
    /// PNG resolution.
    pub dpi: Option<f64>,
    /// Title replacing the figure's own.
    pub title: Option<String>,
}

impl Page {
    /// The figure's width in SVG pixels (1/96 in). Below 200 px no plot has room for its axes;
    /// 8000 px is a poster's width at 96 dpi. A figure refuses a width at which its own labels
    /// and legends do not fit, naming the least that does.
    pub const WIDTH: Field = Field::new(
        "width",
        SIZE_PX,
        "Figure width in SVG pixels (1/96 in): from the least that holds a plot's axes to a poster's width; a figure refuses a width at which its texts do not fit and names the least that does.",
    )
    .with_default(1000.0);
    /// The figure's height in SVG pixels; left out, 280 px per panel and 50 px for the title.
    pub const HEIGHT: Field = Field::new(
        "height",
        SIZE_PX,
        "Figure height in SVG pixels (1/96 in; left out: 280 per panel plus 50): a figure refuses a height at which its panels and texts do not fit and names the least that does.",
    );
    /// The PNG's resolution: 96 dpi draws one PNG pixel per SVG pixel.
    pub const DPI: Field = Field::new(
        "dpi",
        DPI,
        "PNG resolution in dots per inch (96 draws one pixel per SVG pixel): from a thumbnail's to a print's, the image at most 10⁸ pixels.",
    )
    .with_default(DPI_NATIVE);

    /// Checks each setting against its range: [`SIZE_PX`], [`DPI`], at most
    /// [`MAX_TITLE_CHARS`] characters of title on one line.
    pub fn check(&self) -> Result<(), IoError> {
        for (field, v) in [(Self::WIDTH, self.width), (Self::HEIGHT, self.height), (Self::DPI, self.dpi)] {
            if let Some(v) = v {
                field.check(v)?;
            }
        }
        if let Some(t) = &self.title {
            let n = t.chars().count();
            if n > MAX_TITLE_CHARS || t.contains(['\n', '\r']) {
                return Err(IoError::Plot(format!(
                    "title: {n} characters{}: allowed one line of at most {MAX_TITLE_CHARS}",
                    if t.contains(['\n', '\r']) { " on several lines" } else { "" }
                )));
            }
        }
        Ok(())
    }
}

impl Figure {
    /// A figure with a title, a horizontal label and panels.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, panels: Vec<Panel>) -> Self {
        Self { title: title.into(), x_label: x_label.into(), panels, size: None, dpi: DPI_NATIVE, turns_axis: false }
    }

    /// The same figure with its horizontal axis (main-shaft degrees, counted from 0) ticked at
    /// whole turns — one pick per turn — labelled with the number of turns, and the degrees within
    /// a turn as minor ticks (every 30°, 45°, 90° or 180°, as the width allows; the horizontal
    /// label says which). For a repeat of many picks, where a degree axis reads "17280°".
    pub fn with_turns_axis(mut self) -> Self {
        self.turns_axis = true;
        self
    }

    /// The size in SVG pixels.
    pub fn pixel_size(&self) -> (u32, u32) {
        let weights: f64 = self.panels.iter().map(|p| panel_weight(p.weight)).sum();
        self.size.unwrap_or((Page::WIDTH.default_value() as u32, (280.0 * weights.max(1.0)).round() as u32 + 50))
    }

    /// The same figure with a user's page settings applied (checked first, see [`Page::check`]).
    /// The PNG's pixel count (size × DPI / 96, squared) must stay within [`MAX_PNG_PIXELS`].
    pub fn with_page(mut self, page: &Page) -> Result<Self, IoError> {
        page.check()?;
        let (w, h) = self.pixel_size();
        let (w, h) = (page.width.map_or(w, |v| v.round() as u32), page.height.map_or(h, |v| v.round() as u32));
        self.size = Some((w, h));
        if let Some(dpi) = page.dpi {
            self.dpi = dpi;
        }
        if let Some(t) = &page.title {
            self.title = t.clone();
        }
        if page.width.is_some() || page.height.is_some() {
            self.check_size(page)?;
        }
        let px = f64::from(w) * f64::from(h) * (self.dpi / DPI_NATIVE).powi(2);
        if px > MAX_PNG_PIXELS {
            let most = DPI_NATIVE * (MAX_PNG_PIXELS / (f64::from(w) * f64::from(h))).sqrt();
            let range = Range::closed(DPI_MIN, most.floor().max(DPI_MIN), "dpi");
            return Err(RangeError::new("dpi", self.dpi, range).into());
        }
        Ok(self)
    }

    /// What does not fit at the figure's size: a text outside the canvas, two texts over each
    /// other, a text over a legend, an axis with fewer than two labelled ticks. Empty when the
    /// figure lays out (every figure does at its default size; [`Figure::with_page`] refuses a
    /// size at which it does not).
    pub fn layout_problems(&self) -> Vec<String> {
        if self.panels.is_empty() {
            return vec!["a figure needs at least one panel".into()];
        }
        labels::problems(self, &layout::layout(self))
    }

    fn fits(&self, w: u32, h: u32) -> bool {
        let mut f = self.clone();
        f.size = Some((w, h));
        f.layout_problems().is_empty()
    }

    /// Refuses a size the user chose at which the figure does not lay out, naming the smallest
    /// width or height that does (the figure's own lower bound: it depends on its panels, legends
    /// and labels, so it is found by laying the figure out, bisecting between the size asked for
    /// and [`SIZE_PX`]'s upper bound).
    fn check_size(&self, page: &Page) -> Result<(), IoError> {
        let (w, h) = self.pixel_size();
        let problems = self.layout_problems();
        let Some(first) = problems.first() else { return Ok(()) };
        let most = SIZE_MAX as u32;
        let least = |fits: &dyn Fn(u32) -> bool, from: u32, to: u32| {
            let (mut lo, mut hi) = (from, to);
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if fits(mid) { hi = mid } else { lo = mid }
            }
            hi
        };
        if page.height.is_some() && h < most && self.fits(w, most) {
            let min = least(&|v| self.fits(w, v), h, most);
            let range = Range::closed(f64::from(min), SIZE_MAX, "px");
            let range = RangeError::new("height", f64::from(h), range);
            return Err(IoError::TooSmall { range, reason: first.clone() });
        }
        if page.width.is_some() && w < most && self.fits(most, h) {
            let min = least(&|v| self.fits(v, h), w, most);
            let range = Range::closed(f64::from(min), SIZE_MAX, "px");
            let range = RangeError::new("width", f64::from(w), range);
            return Err(IoError::TooSmall { range, reason: first.clone() });
        }
        // Neither alone: both grown in proportion up to the largest size.
        let grow = |t: u32| {
            let at = |v: u32| v + ((most - v) as u64 * u64::from(t) / 1000) as u32;
            (at(w), at(h))
        };
        let t = least(&|t| self.fits(grow(t).0, grow(t).1), 0, 1000);
        let (lw, lh) = grow(t);
        Err(IoError::Plot(format!(
            "width = {w} and height = {h} px are too small for this figure ({first}); it lays out at {lw} × {lh} px"
        )))
    }

    /// Renders to `path`; the extension (`.svg` or `.png`) chooses the format (see [`plot_format`]).
    pub fn save(&self, path: &Path) -> Result<(), IoError> {
        let bytes = match plot_format(path)? {
            PlotFormat::Svg => self.to_svg()?.into_bytes(),
            PlotFormat::Png => self.to_png()?,
        };
        std::fs::write(path, bytes).map_err(|cause| IoError::File { path: path.display().to_string(), cause })
    }

    /// Renders to an SVG document.
    pub fn to_svg(&self) -> Result<String, IoError> {
        if self.panels.is_empty() {
            return Err(IoError::Plot("a figure needs at least one panel".into()));
        }
        let lay = layout::layout(self);
        Ok(svg::write(self, &lay))
    }

    /// Renders to a PNG file's bytes (the SVG rasterised, antialiased, at the figure's DPI).
    pub fn to_png(&self) -> Result<Vec<u8>, IoError> {
        raster::png(&self.to_svg()?, self.pixel_size(), self.dpi)
    }
}

/// The texts of an SVG written by [`Figure::to_svg`] as a renderer draws them: each text (its
/// `aria-label`) with the box `[x0, y0, x1, y1]` (SVG pixels, y down) that its glyph outlines
/// fill, read back by usvg. A check of a figure's layout that does not trust the layout's own
/// boxes: tests use it to find texts that overlap or leave the canvas.
pub fn drawn_texts(svg: &str) -> Result<Vec<(String, [f64; 4])>, IoError> {
    raster::drawn_texts(svg)
}

/// What [`drawn_texts`] finds wrong with an SVG written by [`Figure::to_svg`]: a text whose ink
/// leaves the canvas or meets another text's. Empty for a figure that lays out.
pub fn drawn_text_problems(svg: &str) -> Result<Vec<String>, IoError> {
    let (w, h) = raster::canvas(svg)?;
    let drawn = drawn_texts(svg)?;
    let mut out = Vec::new();
    for (i, (a, ab)) in drawn.iter().enumerate() {
        if ab[0] < -0.5 || ab[1] < -0.5 || ab[2] > w + 0.5 || ab[3] > h + 0.5 {
            out.push(format!("'{a}' leaves the {w} × {h} canvas: {ab:?}"));
        }
        for (b, bb) in &drawn[i + 1..] {
            if ab[0] < bb[2] && bb[0] < ab[2] && ab[1] < bb[3] && bb[1] < ab[3] {
                out.push(format!("'{a}' meets '{b}'"));
            }
        }
    }
    Ok(out)
}

/// The file format of a plot, chosen by the file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlotFormat {
    /// `.svg` (any case).
    Svg,
    /// `.png` (any case).
    Png,
}

/// The format [`Figure::save`] writes to `path`, or [`IoError::PlotFormat`] for an extension other
/// than `.svg` or `.png`: a front end checks every output's name with it before any work is done.
pub fn plot_format(path: &Path) -> Result<PlotFormat, IoError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => Ok(PlotFormat::Svg),
        Some("png") => Ok(PlotFormat::Png),
        _ => Err(IoError::PlotFormat { path: path.display().to_string() }),
    }
}

/// A value for a note or a title: four significant digits ([`loomkin_units::sig4`], the one
/// format of figures and messages; re-exported here where figures are made).
pub use loomkin_units::sig4;

fn panel_weight(w: f64) -> f64 {
    if w.is_finite() && w > 0.0 { w.clamp(0.1, 10.0) } else { 1.0 }
}

#[cfg(test)]
mod tests;
