//! Stacked line plots rendered to SVG or PNG.
//!
//! A [`Figure`] is a column of [`Panel`]s sharing a horizontal quantity; each panel overlays any
//! number of [`Series`] with a legend. Axis labels are written as `quantity [unit]`. The text font is
//! embedded (Ubuntu Light, from the `epaint_default_fonts` crate), so plotting needs no system fonts.

use crate::IoError;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// One curve.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Points `(x, y)`; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points instead of a line.
    pub markers: bool,
    /// Colour as RGB; `None` takes the next colour of the palette.
    pub color: Option<[u8; 3]>,
    /// Draw the line dashed.
    pub dashed: bool,
}

impl Series {
    /// A line through the points.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { label: label.into(), points, ..Self::default() }
    }

    /// Markers at the points.
    pub fn markers(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { label: label.into(), points, markers: true, ..Self::default() }
    }

    /// The same series in a given colour.
    pub fn with_color(mut self, rgb: [u8; 3]) -> Self {
        self.color = Some(rgb);
        self
    }

    /// The same series drawn dashed.
    pub fn with_dashes(mut self) -> Self {
        self.dashed = true;
        self
    }
}

/// One chart of a figure.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Panel {
    /// Vertical axis label, `quantity [unit]`.
    pub y_label: String,
    /// Horizontal axis label for this panel (defaults to the figure's).
    pub x_label: Option<String>,
    /// The curves.
    pub series: Vec<Series>,
    /// Same scale on both axes (for drawings such as cam profiles).
    pub equal_aspect: bool,
    /// Where the legend goes (upper right by default).
    pub legend: Legend,
}

/// Placement of a panel's legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Upper right corner.
    #[default]
    UpperRight,
    /// Upper left corner.
    UpperLeft,
    /// Lower right corner.
    LowerRight,
    /// Lower left corner.
    LowerLeft,
    /// No legend on this panel.
    Hidden,
}

impl Panel {
    /// A panel with a label and curves.
    pub fn new(y_label: impl Into<String>, series: Vec<Series>) -> Self {
        Self { y_label: y_label.into(), series, ..Self::default() }
    }

    /// The same panel with its legend placed elsewhere (or hidden).
    pub fn with_legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
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
    /// Size in pixels; `None` picks 1000 × (260 per panel + 60).
    pub size: Option<(u32, u32)>,
}

/// Colours of successive series (a palette readable on white and by most colour-blind readers).
const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(120, 120, 120),
];

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is a compile-time constant of a published crate: it cannot fail to parse.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT);
    });
}

impl Figure {
    /// A figure with a title, a horizontal label and panels.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, panels: Vec<Panel>) -> Self {
        Self { title: title.into(), x_label: x_label.into(), panels, size: None }
    }

    /// Renders to `path`; the extension (`.svg` or `.png`) chooses the format.
    pub fn save(&self, path: &Path) -> Result<(), IoError> {
        register_font();
        if self.panels.is_empty() {
            return Err(IoError::Plot("a figure needs at least one panel".into()));
        }
        let size = self.size.unwrap_or((1000, 260 * self.panels.len() as u32 + 60));
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        if matches!(ext.as_deref(), Some("svg" | "png")) {
            // Fail early, with the OS's words, if the file cannot be written at all.
            std::fs::File::create(path).map_err(|cause| IoError::File { path: path.display().to_string(), cause })?;
        }
        match ext.as_deref() {
            Some("svg") => self.draw(SVGBackend::new(path, size).into_drawing_area()),
            Some("png") => self.draw(BitMapBackend::new(path, size).into_drawing_area()),
            _ => Err(IoError::PlotFormat { path: path.display().to_string() }),
        }
        .map_err(|e| match e {
            IoError::Plot(m) => IoError::Plot(format!("{}: {m}", path.display())),
            other => other,
        })
    }

    /// Renders to an SVG string (for the web workbench and for tests).
    pub fn to_svg(&self) -> Result<String, IoError> {
        register_font();
        let size = self.size.unwrap_or((1000, 260 * self.panels.len().max(1) as u32 + 60));
        let mut buf = String::new();
        self.draw(SVGBackend::with_string(&mut buf, size).into_drawing_area())?;
        Ok(buf)
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), IoError> {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| IoError::Plot(e.to_string());
        root.fill(&WHITE).map_err(err)?;
        let root = root.titled(&self.title, ("sans-serif", 24)).map_err(err)?;
        let areas = root.split_evenly((self.panels.len(), 1));
        for (area, panel) in areas.iter().zip(&self.panels) {
            draw_panel(area, panel, &self.x_label).map_err(err)?;
        }
        root.present().map_err(err)
    }
}

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span <= 1e-12 * (1.0 + lo.abs().max(hi.abs())) {
        let pad = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return (lo - pad, hi + pad);
    }
    (lo - 0.05 * span, hi + 0.05 * span)
}

/// A tick label with as many decimals as the axis span needs, no `-0`, no trailing zeros.
fn tick_label(v: f64, span: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    if span > 0.0 && v.abs() < 1e-9 * span {
        return "0".into();
    }
    let decimals = if span > 0.0 { (3.0 - span.log10().floor()).clamp(0.0, 15.0) as usize } else { 3 };
    let text = format!("{v:.decimals$}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text };
    if text == "-0" { "0".into() } else { text }
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    fig_x_label: &str,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let pts = || panel.series.iter().flat_map(|s| s.points.iter().copied());
    let (mut x0, mut x1) = bounds(pts().map(|p| p.0));
    let (mut y0, mut y1) = bounds(pts().map(|p| p.1));
    if panel.series.iter().all(|s| s.points.is_empty()) {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if panel.equal_aspect {
        let (w, h) = area.dim_in_pixel();
        let (pw, ph) = ((w as f64 - 90.0).max(10.0), (h as f64 - 60.0).max(10.0));
        let scale = ((x1 - x0) / pw).max((y1 - y0) / ph);
        let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        (x0, x1) = (cx - scale * pw / 2.0, cx + scale * pw / 2.0);
        (y0, y1) = (cy - scale * ph / 2.0, cy + scale * ph / 2.0);
    }
    let mut chart = ChartBuilder::on(area)
        .margin(8)
        .margin_right(20)
        .x_label_area_size(42)
        .y_label_area_size(78)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    let (xspan, yspan) = (x1 - x0, y1 - y0);
    let fx = move |v: &f64| tick_label(*v, xspan);
    let fy = move |v: &f64| tick_label(*v, yspan);
    chart
        .configure_mesh()
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_desc(panel.x_label.as_deref().unwrap_or(fig_x_label))
        .y_desc(&panel.y_label)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .light_line_style(RGBColor(246, 246, 246))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()?;
    for (i, s) in panel.series.iter().enumerate() {
        let color = s.color.map_or(PALETTE[i % PALETTE.len()], |[r, g, b]| RGBColor(r, g, b));
        let finite: Vec<(f64, f64)> = s.points.iter().copied().filter(|p| p.0.is_finite() && p.1.is_finite()).collect();
        let drawn = if s.markers {
            chart.draw_series(finite.iter().map(|&p| Circle::new(p, 5, color.filled())))?
        } else if s.dashed {
            chart.draw_series(DashedLineSeries::new(finite, 8, 5, color.stroke_width(2)))?
        } else {
            chart.draw_series(LineSeries::new(finite, color.stroke_width(2)))?
        };
        if !s.label.is_empty() {
            drawn
                .label(s.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], color.stroke_width(3)));
        }
    }
    let position = match panel.legend {
        Legend::UpperRight => SeriesLabelPosition::UpperRight,
        Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
        Legend::LowerRight => SeriesLabelPosition::LowerRight,
        Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
        Legend::Hidden => return Ok(()),
    };
    if panel.series.iter().any(|s| !s.label.is_empty()) {
        chart
            .configure_series_labels()
            .position(position)
            .label_font(("sans-serif", 15))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_has_labels_and_legend() {
        let fig = Figure::new(
            "test",
            "x [-]",
            vec![Panel::new(
                "s [-]",
                vec![
                    Series::line("one", vec![(0.0, 0.0), (1.0, 1.0)]),
                    Series::line("two", vec![(0.0, 1.0), (1.0, 0.0)]).with_dashes().with_color([1, 2, 3]),
                ],
            )],
        );
        let svg = fig.to_svg().unwrap();
        assert!(svg.contains("#010203"), "the chosen colour is used");
        for text in ["x [-]", "s [-]", "one", "two", "test"] {
            assert!(svg.contains(text), "{text} missing");
        }
    }

    #[test]
    fn tick_labels_are_compact() {
        assert_eq!(tick_label(-1e-17, 2.0), "0");
        assert_eq!(tick_label(250.0, 400.0), "250");
        assert_eq!(tick_label(0.1, 1.0), "0.1");
        assert_eq!(tick_label(-0.0005, 0.004), "-0.0005");
        assert_eq!(tick_label(-0.00001, 1.0), "0");
    }

    #[test]
    fn png_renders_and_bad_extension_is_refused() {
        let dir = std::env::temp_dir().join(format!("loomkin-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fig = Figure::new("t", "x", vec![Panel::new("y", vec![Series::line("", vec![(0.0, 2.0), (1.0, 2.0)])])]);
        let png = dir.join("a.png");
        fig.save(&png).unwrap();
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        assert!(matches!(fig.save(&dir.join("a.pdf")), Err(IoError::PlotFormat { .. })));
        std::fs::remove_dir_all(dir).ok();
    }
}
