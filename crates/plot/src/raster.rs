//! The SVG rasterised to PNG.

use loomkin_io::IoError;
use resvg::{tiny_skia, usvg};

/// The SVG (of `size` SVG pixels) drawn at `dpi` (96: one PNG pixel per SVG pixel) as PNG bytes
/// carrying that resolution.
pub(crate) fn png(svg: &str, size: (u32, u32), dpi: f64) -> Result<Vec<u8>, IoError> {
    // The SVG draws its text as glyph outlines (see `svg.rs`): no font is loaded here.
    let opt = usvg::Options::default();
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

/// The texts of an SVG this crate wrote, as a renderer draws them: each text's glyph outlines,
/// read back by usvg, bounded by their ink box `[x0, y0, x1, y1]` in SVG pixels, with the text
/// (its group's `aria-label`), in drawing order.
pub(crate) fn drawn_texts(svg: &str) -> Result<Vec<(String, [f64; 4])>, IoError> {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| IoError::Plot(format!("SVG not read: {e}")))?;
    let mut out = Vec::new();
    collect(tree.root(), svg, &mut out);
    Ok(out)
}

fn collect(g: &usvg::Group, svg: &str, out: &mut Vec<(String, [f64; 4])>) {
    for node in g.children() {
        if let usvg::Node::Group(child) = node {
            let id = child.id();
            if id.len() > 1 && id.starts_with('t') && id[1..].bytes().all(|b| b.is_ascii_digit()) {
                let b = child.abs_bounding_box();
                let b = [b.left(), b.top(), b.right(), b.bottom()].map(f64::from);
                out.push((aria_label(svg, id), b));
            } else {
                collect(child, svg, out);
            }
        }
    }
}

/// The `aria-label` written beside `id="…"`, unescaped.
fn aria_label(svg: &str, id: &str) -> String {
    let key = format!(r#"id="{id}" aria-label=""#);
    let Some(at) = svg.find(&key) else { return String::new() };
    let rest = &svg[at + key.len()..];
    let text = &rest[..rest.find('"').unwrap_or(rest.len())];
    text.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&apos;", "'").replace("&amp;", "&")
}

/// The SVG's canvas, width and height in SVG pixels.
pub(crate) fn canvas(svg: &str) -> Result<(f64, f64), IoError> {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| IoError::Plot(format!("SVG not read: {e}")))?;
    Ok((f64::from(tree.size().width()), f64::from(tree.size().height())))
}
