//! The ledger's contact sheet: one row per component, columns engine, reference and signed
//! difference (red: the engine brighter, blue: darker), all three at the reference's
//! exposure, with the figures written under each in a built-in 3x5 bitmap font.

use crate::io_err;
use crate::ledger::ComponentLedger;
use engine::EngineError;
use reference::Image;
use std::path::Path;

/// One row of the sheet.
pub struct Tile {
    pub engine: Image,
    pub reference: Image,
    pub figures: ComponentLedger,
}

/// 3x5 glyphs, one row of 3 bits per entry (bit 2 the left column).
fn glyph(c: char) -> [u8; 5] {
    match c.to_ascii_uppercase() {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 1, 1],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        'A' => [2, 5, 7, 5, 5],
        'B' => [6, 5, 6, 5, 6],
        'C' => [3, 4, 4, 4, 3],
        'D' => [6, 5, 5, 5, 6],
        'E' => [7, 4, 6, 4, 7],
        'F' => [7, 4, 6, 4, 4],
        'G' => [3, 4, 5, 5, 3],
        'H' => [5, 5, 7, 5, 5],
        'I' => [7, 2, 2, 2, 7],
        'J' => [1, 1, 1, 5, 2],
        'K' => [5, 5, 6, 5, 5],
        'L' => [4, 4, 4, 4, 7],
        'M' => [5, 7, 7, 5, 5],
        'N' => [6, 5, 5, 5, 5],
        'O' => [2, 5, 5, 5, 2],
        'P' => [6, 5, 6, 4, 4],
        'Q' => [2, 5, 5, 6, 3],
        'R' => [6, 5, 6, 5, 5],
        'S' => [3, 4, 2, 1, 6],
        'T' => [7, 2, 2, 2, 2],
        'U' => [5, 5, 5, 5, 7],
        'V' => [5, 5, 5, 5, 2],
        'W' => [5, 5, 7, 7, 5],
        'X' => [5, 5, 2, 5, 5],
        'Y' => [5, 5, 2, 2, 2],
        'Z' => [7, 1, 2, 4, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        '+' => [0, 2, 7, 2, 0],
        '=' => [0, 7, 0, 7, 0],
        '_' => [0, 0, 0, 0, 7],
        ':' => [0, 2, 0, 2, 0],
        '/' => [1, 1, 2, 4, 4],
        '%' => [5, 1, 2, 4, 5],
        '(' => [1, 2, 2, 2, 1],
        ')' => [4, 2, 2, 2, 4],
        _ => [0; 5],
    }
}

/// An RGB8 canvas.
struct Canvas {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Canvas {
    fn new(width: u32, height: u32) -> Self {
        Self { width, height, rgb: vec![24; (width * height * 3) as usize] }
    }

    fn put(&mut self, x: u32, y: u32, c: [u8; 3]) {
        if x < self.width && y < self.height {
            let i = ((y * self.width + x) * 3) as usize;
            self.rgb[i..i + 3].copy_from_slice(&c);
        }
    }

    fn blit(&mut self, x0: u32, y0: u32, w: u32, rgb: &[u8]) {
        for (i, px) in rgb.chunks_exact(3).enumerate() {
            let (x, y) = (i as u32 % w, i as u32 / w);
            self.put(x0 + x, y0 + y, [px[0], px[1], px[2]]);
        }
    }

    /// Writes `text` at `(x0, y0)`, each font pixel `scale` pixels wide, clipped at `x_end`.
    fn text(&mut self, x0: u32, y0: u32, x_end: u32, scale: u32, text: &str) {
        for (k, ch) in text.chars().enumerate() {
            let cx = x0 + k as u32 * 4 * scale;
            if cx + 3 * scale > x_end {
                break;
            }
            for (row, bits) in glyph(ch).iter().enumerate() {
                for col in 0..3u32 {
                    if bits & (4 >> col) != 0 {
                        for d in 0..scale * scale {
                            let (x, y) =
                                (cx + col * scale + d % scale, y0 + row as u32 * scale + d / scale);
                            self.put(x, y, [235, 235, 235]);
                        }
                    }
                }
            }
        }
    }
}

/// Signed difference as colour: red where `a > b`, blue where `a < b`, at `exposure`.
fn signed_rgb(a: &Image, b: &Image, exposure: f32) -> Vec<u8> {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(&p, &q)| {
            let d = (reference::luminance(p) - reference::luminance(q)) * exposure;
            let m = (d.abs() / (1.0 + d.abs())).sqrt();
            let v = if m.is_finite() { (m * 255.0) as u8 } else { 0 };
            if d >= 0.0 { [v, 0, v / 4] } else { [v / 4, v / 3, v] }
        })
        .collect()
}

fn fmt_ratio(v: f64) -> String {
    if v.is_finite() { format!("{v:.2}") } else { "INF".into() }
}

/// Writes the contact sheet of `tiles` to `path` (PNG).
pub fn write_contact_sheet(path: &Path, tiles: &[Tile]) -> Result<(), EngineError> {
    let Some(first) = tiles.first() else { return Ok(()) };
    let (w, h) = (first.engine.width, first.engine.height);
    let scale = if w >= 300 { 2 } else { 1 };
    let line = 6 * scale;
    let caption = 2 * line + 2 * scale;
    let gap = 2;
    let mut c = Canvas::new(3 * w + 2 * gap, tiles.len() as u32 * (h + caption));
    for (row, t) in tiles.iter().enumerate() {
        let y0 = row as u32 * (h + caption);
        let exposure = t.reference.auto_exposure();
        let all = &t.figures.regions[0];
        let cols: [(Vec<u8>, String, String); 3] = [
            (
                t.engine.to_srgb8(exposure),
                format!("{} ENGINE", t.figures.component),
                format!("Y {:.3} {:.1}MS", all.engine_luminance, t.figures.passes_ms),
            ),
            (
                t.reference.to_srgb8(exposure),
                "REFERENCE".to_string(),
                format!(
                    "Y {:.3} SE {:.1}%",
                    all.reference_luminance,
                    100.0 * all.reference_rel_std_error
                ),
            ),
            (
                signed_rgb(&t.engine, &t.reference, exposure),
                "DIFFERENCE (RED +)".to_string(),
                format!("RATIO {} RMS {}", fmt_ratio(all.luminance_ratio), fmt_ratio(all.rel_rms)),
            ),
        ];
        for (k, (rgb, l1, l2)) in cols.iter().enumerate() {
            let x0 = k as u32 * (w + gap);
            c.blit(x0, y0, w, rgb);
            c.text(x0 + scale, y0 + h + scale, x0 + w, scale, l1);
            c.text(x0 + scale, y0 + h + scale + line, x0 + w, scale, l2);
        }
    }
    image::save_buffer(path, &c.rgb, c.width, c.height, image::ColorType::Rgb8)
        .map_err(|e| io_err(path, e))
}
