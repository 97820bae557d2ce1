//! Text metrics of the embedded font, and the SVG rasterised to PNG.

use epaint_default_fonts::{HACK_REGULAR, UBUNTU_LIGHT};
use loomkin_io::IoError;
use resvg::{tiny_skia, usvg};
use skrifa::instance::{LocationRef, Size};
use skrifa::{FontRef, MetadataProvider};

/// Advance width of `text` at `size` pixels in the embedded font (Hack for glyphs Ubuntu lacks),
/// without kerning (a slight overestimate, which is the safe side for boxes around text).
pub(crate) fn text_width(text: &str, size: f64) -> f64 {
    let fonts: Vec<FontRef<'static>> =
        [UBUNTU_LIGHT, HACK_REGULAR].iter().filter_map(|d| FontRef::new(d).ok()).collect();
    let sz = Size::new(size as f32);
    let tables: Vec<_> = fonts.iter().map(|f| (f.charmap(), f.glyph_metrics(sz, LocationRef::default()))).collect();
    text.chars()
        .map(|c| {
            tables
                .iter()
                .find_map(|(cmap, metrics)| cmap.map(c).and_then(|g| metrics.advance_width(g)))
                .map_or(0.6 * size, f64::from)
        })
        .sum()
}

/// The SVG (of `size` SVG pixels) drawn at `dpi` (96: one PNG pixel per SVG pixel) as PNG bytes
/// carrying that resolution.
pub(crate) fn png(svg: &str, size: (u32, u32), dpi: f64) -> Result<Vec<u8>, IoError> {
    let mut opt = usvg::Options::default();
    let db = opt.fontdb_mut();
    db.load_font_data(UBUNTU_LIGHT.to_vec());
    db.load_font_data(HACK_REGULAR.to_vec());
    let family = db.faces().next().and_then(|f| f.families.first()).map(|f| f.0.clone());
    if let Some(family) = family {
        db.set_sans_serif_family(family.clone());
        opt.font_family = family;
    }
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| IoError::Plot(format!("SVG not rendered: {e}")))?;
    let scale = dpi / 96.0;
    let (w, h) = ((f64::from(size.0) * scale).round() as u32, (f64::from(size.1) * scale).round() as u32);
    let mut pixmap = tiny_skia::Pixmap::new(w.max(1), h.max(1))
        .ok_or_else(|| IoError::Plot(format!("cannot allocate a {w} × {h} image")))?;
    resvg::render(&tree, tiny_skia::Transform::from_scale(scale as f32, scale as f32), &mut pixmap.as_mut());
    let bytes = pixmap.encode_png().map_err(|e| IoError::Plot(format!("PNG not encoded: {e}")))?;
    Ok(with_resolution(bytes, dpi))
}

/// The PNG with a `pHYs` chunk after its header, so a word processor sizes it at `dpi`.
fn with_resolution(png: Vec<u8>, dpi: f64) -> Vec<u8> {
    // Signature (8 bytes), then IHDR: length, type, 13 bytes of data, CRC = 25 bytes.
    const AFTER_IHDR: usize = 33;
    if png.len() < AFTER_IHDR || &png[12..16] != b"IHDR" {
        return png;
    }
    let ppm = (dpi / 0.0254).round() as u32;
    let mut chunk = Vec::with_capacity(21);
    chunk.extend_from_slice(&9u32.to_be_bytes());
    chunk.extend_from_slice(b"pHYs");
    chunk.extend_from_slice(&ppm.to_be_bytes());
    chunk.extend_from_slice(&ppm.to_be_bytes());
    chunk.push(1); // unit: metre
    let crc = crc32(&chunk[4..]);
    chunk.extend_from_slice(&crc.to_be_bytes());
    let mut out = Vec::with_capacity(png.len() + chunk.len());
    out.extend_from_slice(&png[..AFTER_IHDR]);
    out.extend_from_slice(&chunk);
    out.extend_from_slice(&png[AFTER_IHDR..]);
    out
}

/// CRC-32 (ISO 3309, as PNG chunks use it), bit by bit: a chunk of 13 bytes needs no table.
pub(crate) fn crc32(data: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}
