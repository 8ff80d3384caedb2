//! Rgb565 textures (what [`zline::paint::Texture`] samples): read from
//! PNG files, optionally scaled down by whole box filters for a
//! microcontroller's flash, or made procedurally ([`Rgb565Texture::tiles`]),
//! and written as Rust statics; and the light the lab's tools light
//! textures with ([`white_light`]).

use std::fmt::Write;
use std::path::Path;

/// An Rgb565 texture: `width · height` raw texels, row by row from the
/// top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rgb565Texture {
    /// Raw Rgb565 texels.
    pub texels: Vec<u16>,
    /// Width in texels.
    pub width: u16,
    /// Height in texels.
    pub height: u16,
}

/// 8-bit channels as a raw Rgb565 value, rounded as embedded-graphics
/// converts `Rgb888` to `Rgb565`.
pub fn rgb565(r: u8, g: u8, b: u8) -> u16 {
    let level = |c: u8, max: u32| (u32::from(c) * max + 127) / 255;
    ((level(r, 31) << 11) | (level(g, 63) << 5) | level(b, 31)) as u16
}

/// The 8-bit RGB pixels of a PNG (grey, grey-alpha, RGB, RGBA, palette;
/// 8 or 16 bits a channel; alpha dropped) with its size.
pub fn read_png_rgb(path: &Path) -> Result<(Vec<[u8; 3]>, u32, u32), String> {
    let file = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder
        .read_info()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut buffer = vec![0; reader.output_buffer_size()];
    let info = reader
        .next_frame(&mut buffer)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let channels = info.color_type.samples();
    let pixels = buffer[..info.buffer_size()]
        .chunks_exact(channels)
        .map(|p| match channels {
            1 | 2 => [p[0]; 3],
            _ => [p[0], p[1], p[2]],
        })
        .collect();
    Ok((pixels, info.width, info.height))
}

impl Rgb565Texture {
    /// A PNG as a texture, scaled down by `shrink` (a whole factor: each
    /// texel the mean of a `shrink` x `shrink` box, rounded) when it is
    /// above 1. The size must end up within
    /// [`zline::paint::TEXTURE_SIZE_MAX`].
    pub fn read(path: &Path, shrink: u32) -> Result<Self, String> {
        let (pixels, width, height) = read_png_rgb(path)?;
        let shrink = shrink.max(1);
        if width % shrink != 0 || height % shrink != 0 {
            return Err(format!(
                "{}: {width}x{height} does not divide by {shrink}",
                path.display()
            ));
        }
        let (w, h) = (width / shrink, height / shrink);
        let max = u32::from(zline::paint::TEXTURE_SIZE_MAX);
        if w == 0 || h == 0 || w > max || h > max {
            return Err(format!(
                "{}: a {w}x{h} texture is outside 1..={max} texels a side",
                path.display()
            ));
        }
        let area = shrink * shrink;
        let mut texels = Vec::with_capacity((w * h) as usize);
        for j in 0..h {
            for i in 0..w {
                let mut sum = [0u32; 3];
                for y in j * shrink..(j + 1) * shrink {
                    for x in i * shrink..(i + 1) * shrink {
                        let p = pixels[(y * width + x) as usize];
                        for c in 0..3 {
                            sum[c] += u32::from(p[c]);
                        }
                    }
                }
                let mean = sum.map(|s| ((s + area / 2) / area) as u8);
                texels.push(rgb565(mean[0], mean[1], mean[2]));
            }
        }
        Ok(Self {
            texels,
            width: w as u16,
            height: h as u16,
        })
    }

    /// Tiles for the firmware's textured scenes (no file needed): a
    /// `width` x `height` texture of 8x8-texel tiles, alternately warm and
    /// cool, each shaded from its top-left corner and outlined.
    pub fn tiles(width: u16, height: u16) -> Self {
        let mut texels = Vec::with_capacity(usize::from(width) * usize::from(height));
        for y in 0..height {
            for x in 0..width {
                let (i, j) = (x % 8, y % 8);
                let warm = (x / 8 + y / 8) % 2 == 0;
                let shade = 255 - 8 * (i + j) as u8;
                let [r, g, b] = match (i == 0 || j == 0, warm) {
                    (true, _) => [40, 40, 48],
                    (false, true) => [shade, (shade as u16 * 3 / 4) as u8, 60],
                    (false, false) => [60, (shade as u16 * 3 / 4) as u8, shade],
                };
                texels.push(rgb565(r, g, b));
            }
        }
        Self {
            texels,
            width,
            height,
        }
    }

    /// The texture as zline samples it (repeating, nearest texel).
    pub fn texture(&self) -> Result<zline::paint::Texture<'_>, String> {
        zline::paint::Texture::new(&self.texels, self.width, self.height).map_err(|e| e.to_string())
    }

    /// The texture as Rust source: `pub static NAME: [u16; W·H]` and its
    /// size as `NAME_WIDTH` and `NAME_HEIGHT`, for flash.
    pub fn rust_source(&self, name: &str, origin: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "// {}x{} Rgb565 texels from {origin}, written by zline-lab (Rgb565Texture).",
            self.width, self.height
        );
        let _ = writeln!(s, "pub const {name}_WIDTH: u16 = {};", self.width);
        let _ = writeln!(s, "pub const {name}_HEIGHT: u16 = {};", self.height);
        let _ = writeln!(s, "pub static {name}: [u16; {}] = [", self.texels.len());
        for row in self.texels.chunks(12) {
            let line: Vec<String> = row.iter().map(|t| format!("0x{t:04x}")).collect();
            let _ = writeln!(s, "    {},", line.join(", "));
        }
        let _ = writeln!(s, "];");
        s
    }
}

/// The light textures are lit with in the render tool (`--shade
/// lit-texture`) and the accuracy run: `Shading::lambert()`'s direction
/// and ambient on a white surface, so each vertex's colour is its light
/// alone.
pub fn white_light() -> zline::Lambert {
    use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
    match zline::Shading::lambert() {
        zline::Shading::Lambert(l) => zline::Lambert::new(Rgb888::WHITE, l.light(), l.ambient()),
        other => unreachable!("Shading::lambert() is {other:?}, not Lambert"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::raw::RawU16;
    use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
    use embedded_graphics_core::prelude::RawData;

    /// The conversion is embedded-graphics' for every grey and a spread
    /// of colours.
    #[test]
    fn rgb565_is_embedded_graphics_conversion() {
        for c in 0..=255u8 {
            for (r, g, b) in [(c, c, c), (c, 255 - c, c / 3)] {
                let theirs = RawU16::from(Rgb565::from(Rgb888::new(r, g, b))).into_inner();
                assert_eq!(rgb565(r, g, b), theirs, "{r} {g} {b}");
            }
        }
    }
}
