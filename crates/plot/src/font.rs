//! The embedded font: glyph lookup, advances and outlines. Text is measured and drawn from the same
//! glyphs, so a label's box in the layout is the box of what the SVG draws.

use epaint_default_fonts::{HACK_REGULAR, UBUNTU_LIGHT};
use skrifa::instance::{LocationRef, Size};
use skrifa::outline::DrawSettings;
use skrifa::outline::pen::SvgPen;
use skrifa::{FontRef, GlyphId, MetadataProvider};
use std::sync::OnceLock;

/// Units per em of the outlines written to the SVG (glyphs are drawn at this size, so their
/// coordinates are whole numbers for Ubuntu, whose em is 1000 units).
pub(crate) const UNITS: f64 = 1000.0;

/// Ubuntu Light first, Hack for the glyphs it lacks.
pub(crate) struct Fonts {
    faces: Vec<FontRef<'static>>,
    /// Top of the alignment box above the baseline, per em (Ubuntu's).
    pub ascent: f64,
    /// Bottom of the alignment box below the baseline, per em (positive).
    pub descent: f64,
}

/// A glyph of one of the fonts: `(face, glyph id)`.
pub(crate) type Glyph = (usize, u32);

pub(crate) fn fonts() -> &'static Fonts {
    static FONTS: OnceLock<Fonts> = OnceLock::new();
    FONTS.get_or_init(|| {
        let faces: Vec<FontRef<'static>> =
            [UBUNTU_LIGHT, HACK_REGULAR].iter().filter_map(|d| FontRef::new(d).ok()).collect();
        let (ascent, descent) = faces.first().map_or((0.93, 0.19), |f| {
            let m = f.metrics(Size::unscaled(), LocationRef::default());
            let em = f64::from(m.units_per_em.max(1));
            (f64::from(m.ascent) / em, -f64::from(m.descent) / em)
        });
        Fonts { faces, ascent, descent }
    })
}

impl Fonts {
    /// The glyph drawing `c` and its advance in [`UNITS`] per em: Ubuntu's, else Hack's, else
    /// Ubuntu's "missing glyph" box (glyph 0).
    pub fn glyph(&self, c: char) -> (Glyph, f64) {
        let size = Size::new(UNITS as f32);
        for (i, f) in self.faces.iter().enumerate() {
            if let Some(g) = f.charmap().map(c) {
                let adv = f.glyph_metrics(size, LocationRef::default()).advance_width(g).unwrap_or(0.0);
                return ((i, g.to_u32()), f64::from(adv));
            }
        }
        let adv = self
            .faces
            .first()
            .and_then(|f| f.glyph_metrics(size, LocationRef::default()).advance_width(GlyphId::new(0)).map(f64::from));
        ((0, 0), adv.unwrap_or(0.6 * UNITS))
    }

    /// The glyph's outline as SVG path data in [`UNITS`] per em, y up (empty for a space).
    pub fn outline(&self, (face, gid): Glyph) -> String {
        let Some(f) = self.faces.get(face) else { return String::new() };
        let Some(glyph) = f.outline_glyphs().get(GlyphId::new(gid)) else { return String::new() };
        let mut pen = SvgPen::with_precision(0);
        let settings = DrawSettings::unhinted(Size::new(UNITS as f32), LocationRef::default());
        if glyph.draw(settings, &mut pen).is_err() {
            return String::new();
        }
        pen.to_string()
    }
}

/// Advance width of `text` at `size` pixels in the embedded font (Hack for glyphs Ubuntu lacks),
/// without kerning: the width the SVG draws, glyph after glyph.
pub(crate) fn text_width(text: &str, size: f64) -> f64 {
    let f = fonts();
    text.chars().map(|c| f.glyph(c).1).sum::<f64>() * size / UNITS
}
