//! Textures: a grid of Rgb565 texels (an array in flash on a
//! microcontroller), how coordinates outside it are taken ([`Wrap`]) and
//! how a texel is picked or blended ([`Filter`]).
//!
//! Texture coordinates reach a texture in *texel units* with
//! [`TEXEL_FRAC_BITS`] fractional bits: `u = 0` is the left edge of texel
//! column 0 and `u = width` the right edge of the last, so the centre of
//! column `i` is at `i + 0.5`. [`Filter::Nearest`] takes the texel that
//! holds the point (`floor(u)`, `floor(v)`); [`Filter::Bilinear`] blends the
//! four texels whose centres surround it, with 8-bit weights.

use crate::error::Error;

/// Fractional bits of a texture coordinate in texel units.
pub const TEXEL_FRAC_BITS: u32 = 8;

/// Largest texture width or height in texels.
pub const TEXTURE_SIZE_MAX: u16 = 4096;

/// What a coordinate outside the texture takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Wrap {
    /// The texture repeats (coordinates taken modulo its size).
    #[default]
    Repeat,
    /// The edge texels extend outward.
    Clamp,
}

/// How a texel is picked.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Filter {
    /// The texel holding the point.
    #[default]
    Nearest,
    /// The four texels whose centres surround the point, blended by
    /// distance (8-bit weights).
    Bilinear,
}

/// An Rgb565 texture: `width · height` texels, row by row from the top
/// (the row of OBJ's `v = 1`), each a raw Rgb565 value
/// (`embedded_graphics::pixelcolor::raw::RawU16`'s bits: red in the top 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Texture<'a> {
    texels: &'a [u16],
    width: u16,
    height: u16,
    /// `width - 1` when the width is a power of two (a mask replaces the
    /// remainder), else 0.
    mask_x: u16,
    mask_y: u16,
    wrap: Wrap,
    filter: Filter,
}

impl<'a> Texture<'a> {
    /// A texture of `width` x `height` texels (each 1 to
    /// [`TEXTURE_SIZE_MAX`]), repeating, nearest texel.
    /// `Err(`[`Error::BadTextureSize`]`)` when a size is out of range or
    /// `texels` holds other than `width · height` values.
    pub const fn new(texels: &'a [u16], width: u16, height: u16) -> Result<Self, Error> {
        if width == 0
            || height == 0
            || width > TEXTURE_SIZE_MAX
            || height > TEXTURE_SIZE_MAX
            || texels.len() != width as usize * height as usize
        {
            return Err(Error::BadTextureSize);
        }
        Ok(Self {
            texels,
            width,
            height,
            mask_x: power_of_two_mask(width),
            mask_y: power_of_two_mask(height),
            wrap: Wrap::Repeat,
            filter: Filter::Nearest,
        })
    }

    /// The same texture with coordinates outside it taken by `wrap`.
    pub const fn with_wrap(mut self, wrap: Wrap) -> Self {
        self.wrap = wrap;
        self
    }

    /// The same texture sampled with `filter`.
    pub const fn with_filter(mut self, filter: Filter) -> Self {
        self.filter = filter;
        self
    }

    /// Width in texels.
    pub const fn width(&self) -> u16 {
        self.width
    }

    /// Height in texels.
    pub const fn height(&self) -> u16 {
        self.height
    }

    /// How coordinates outside the texture are taken.
    pub const fn wrap(&self) -> Wrap {
        self.wrap
    }

    /// How texels are picked.
    pub const fn filter(&self) -> Filter {
        self.filter
    }

    /// The texels, row by row.
    pub const fn texels(&self) -> &'a [u16] {
        self.texels
    }

    /// Texel column (or row) `i` of a texture `size` wide with power-of-two
    /// `mask` (else 0), wrapped or clamped.
    #[inline(always)]
    fn index(&self, i: i32, size: u16, mask: u16) -> usize {
        match self.wrap {
            Wrap::Repeat if mask != 0 => (i & i32::from(mask)) as usize,
            Wrap::Repeat => i.rem_euclid(i32::from(size)) as usize,
            Wrap::Clamp => i.clamp(0, i32::from(size) - 1) as usize,
        }
    }

    /// The texel at column `i`, row `j`, wrapped or clamped.
    #[inline(always)]
    fn texel(&self, i: i32, j: i32) -> u16 {
        let x = self.index(i, self.width, self.mask_x);
        let y = self.index(j, self.height, self.mask_y);
        // In range by construction; 0 (black) would show a mistake.
        self.texels
            .get(y * usize::from(self.width) + x)
            .copied()
            .unwrap_or(0)
    }

    /// The index masks of a repeating texture whose sides are both powers
    /// of two (2 or more), for [`Self::masked_nearest`]; `None` for any
    /// other.
    #[inline(always)]
    pub(crate) fn repeat_masks(&self) -> Option<[u16; 2]> {
        (self.wrap == Wrap::Repeat && self.mask_x != 0 && self.mask_y != 0)
            .then_some([self.mask_x, self.mask_y])
    }

    /// The texel nearest `(u, v)` (texel units with [`TEXEL_FRAC_BITS`]
    /// fractional bits, any values) of a texture with these
    /// [`Self::repeat_masks`]: each index's low bits are its value modulo
    /// the side, whatever its high bits, so no coordinate needs narrowing
    /// first. The same texel as [`Self::nearest`] of the coordinates
    /// reduced modulo the sides.
    #[inline(always)]
    pub(crate) fn masked_nearest(&self, [mask_x, mask_y]: [u16; 2], u: i64, v: i64) -> u16 {
        let x = (u >> TEXEL_FRAC_BITS) as usize & usize::from(mask_x);
        let y = (v >> TEXEL_FRAC_BITS) as usize & usize::from(mask_y);
        // In range by construction; 0 (black) would show a mistake.
        self.texels
            .get(y * usize::from(self.width) + x)
            .copied()
            .unwrap_or(0)
    }

    /// The texel nearest `(u, v)` (texel units with [`TEXEL_FRAC_BITS`]
    /// fractional bits), as stored.
    #[inline(always)]
    pub(crate) fn nearest(&self, u: i32, v: i32) -> u16 {
        self.texel(u >> TEXEL_FRAC_BITS, v >> TEXEL_FRAC_BITS)
    }

    /// The colour at `(u, v)` (texel units with [`TEXEL_FRAC_BITS`]
    /// fractional bits) as 8.8 channels.
    #[inline(always)]
    pub(crate) fn sample(&self, u: i32, v: i32) -> [u32; 3] {
        match self.filter {
            Filter::Nearest => channels(self.nearest(u, v)),
            Filter::Bilinear => {
                // The texel centres around the point: `u - 1/2`'s floor and
                // the next, weighted by its fraction.
                let half = 1 << (TEXEL_FRAC_BITS - 1);
                let (u, v) = (u.wrapping_sub(half), v.wrapping_sub(half));
                let (i, j) = (u >> TEXEL_FRAC_BITS, v >> TEXEL_FRAC_BITS);
                let fraction = (1 << TEXEL_FRAC_BITS) - 1;
                let (fu, fv) = ((u & fraction) as u32, (v & fraction) as u32);
                let corners = [
                    channels(self.texel(i, j)),
                    channels(self.texel(i.wrapping_add(1), j)),
                    channels(self.texel(i, j.wrapping_add(1))),
                    channels(self.texel(i.wrapping_add(1), j.wrapping_add(1))),
                ];
                core::array::from_fn(|k| {
                    let top = corners[0][k] * (256 - fu) + corners[1][k] * fu;
                    let bottom = corners[2][k] * (256 - fu) + corners[3][k] * fu;
                    // 8.8 channels times two 8-bit weights: below 2^32.
                    (top * (256 - fv) + bottom * fv + (1 << 15)) >> 16
                })
            }
        }
    }
}

/// `size - 1` for a power of two, else 0.
const fn power_of_two_mask(size: u16) -> u16 {
    if size.is_power_of_two() { size - 1 } else { 0 }
}

/// A channel of `max + 1` levels widened to 8 bits as embedded-graphics
/// widens it: `(c·255 + max/2) / max`.
const fn widened<const N: usize>(max: u32) -> [u8; N] {
    let mut table = [0; N];
    let mut c = 0;
    while c < N {
        table[c] = ((c as u32 * 255 + max / 2) / max) as u8;
        c += 1;
    }
    table
}

/// 5-bit channels widened to 8 bits.
const WIDE5: [u8; 32] = widened(31);
/// 6-bit channels widened to 8 bits.
const WIDE6: [u8; 64] = widened(63);

/// An Rgb565 texel's own levels (0..=31, 0..=63, 0..=31).
#[inline(always)]
pub(crate) fn levels(texel: u16) -> [u32; 3] {
    let texel = u32::from(texel);
    [texel >> 11, (texel >> 5) & 0x3F, texel & 0x1F]
}

/// The levels of an Rgb565 texel's channels ([`levels`]).
pub(crate) const TEXEL_MAX: [u32; 3] = [31, 63, 31];

/// An Rgb565 texel's channels in 8.8, each widened to 8 bits as
/// embedded-graphics converts `Rgb565` to `Rgb888`.
#[inline(always)]
pub(crate) fn channels(texel: u16) -> [u32; 3] {
    let wide = |table: &[u8], c: u16| u32::from(table[usize::from(c) % table.len()]) << 8;
    [
        wide(&WIDE5, texel >> 11),
        wide(&WIDE6, (texel >> 5) & 0x3F),
        wide(&WIDE5, texel & 0x1F),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paint::PaintColor;
    use embedded_graphics_core::pixelcolor::raw::RawU16;
    use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
    use embedded_graphics_core::prelude::RawData;

    /// A texel's channels are embedded-graphics' Rgb888 of it, and painted
    /// into an Rgb565 row without dither they give the texel back: a
    /// nearest-sampled texture is copied exactly.
    #[test]
    fn texels_round_trip() {
        for raw in 0..=u16::MAX {
            let c = Rgb565::from(RawU16::new(raw));
            let wide = Rgb888::from(c);
            let ch = channels(raw);
            use embedded_graphics_core::pixelcolor::RgbColor;
            assert_eq!(
                ch,
                [wide.r(), wide.g(), wide.b()].map(|v| u32::from(v) << 8),
                "{raw:#06x}"
            );
            assert_eq!(Rgb565::from_channels(ch, None), c, "{raw:#06x}");
            // So a colour of the texels' levels takes them as they are.
            assert_eq!(Rgb565::MAX, TEXEL_MAX);
            assert_eq!(Rgb565::from_levels(levels(raw)), c, "{raw:#06x}");
            type Bgr = embedded_graphics_core::pixelcolor::Bgr565;
            let bgr = Bgr::from_channels(ch, None);
            assert_eq!(Bgr::from_levels(levels(raw)), bgr, "{raw:#06x}");
            assert_eq!(RawU16::from(c).into_inner(), raw);
        }
    }

    fn grid() -> [u16; 12] {
        core::array::from_fn(|k| k as u16 * 0x0841)
    }

    #[test]
    fn sizes_are_checked() {
        let t = grid();
        assert!(Texture::new(&t, 4, 3).is_ok());
        assert_eq!(Texture::new(&t, 3, 3), Err(Error::BadTextureSize));
        assert_eq!(Texture::new(&t, 0, 3), Err(Error::BadTextureSize));
        assert_eq!(Texture::new(&[], 0, 0), Err(Error::BadTextureSize));
    }

    /// The masked lookup of a repeating power-of-two texture picks the
    /// texel the general one does, for coordinates of either sign, far
    /// beyond `i32` too (reduced modulo the sides for the general one);
    /// other textures have no masks.
    #[test]
    fn masked_nearest_is_nearest() {
        let texels: [u16; 32] = core::array::from_fn(|k| k as u16 * 0x0841 + 7);
        let texture = Texture::new(&texels, 8, 4).unwrap();
        let masks = texture.repeat_masks().unwrap();
        let period = [8i64 << TEXEL_FRAC_BITS, 4 << TEXEL_FRAC_BITS];
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        for k in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Small coordinates around 0, then any up to 2^40.
            let span = if k < 10_000 { 1 << 12 } else { 1 << 40 };
            let u = (x % (2 * span)) as i64 - span as i64;
            let v = ((x >> 20) % (2 * span)) as i64 - span as i64;
            let general = texture.nearest(
                u.rem_euclid(period[0]) as i32,
                v.rem_euclid(period[1]) as i32,
            );
            assert_eq!(texture.masked_nearest(masks, u, v), general, "{u} {v}");
        }
        assert_eq!(Texture::new(&texels, 32, 1).unwrap().repeat_masks(), None);
        let twelve = grid();
        assert_eq!(Texture::new(&twelve, 4, 3).unwrap().repeat_masks(), None);
        assert_eq!(texture.with_wrap(Wrap::Clamp).repeat_masks(), None);
    }

    /// Nearest: the texel holding the point; repeat wraps both ways
    /// (power-of-two width and not); clamp extends the edges.
    #[test]
    fn nearest_wraps_and_clamps() {
        let t = grid();
        let at = |u: f32, v: f32| ((u * 256.0) as i32, (v * 256.0) as i32);
        let repeat = Texture::new(&t, 4, 3).unwrap();
        for (u, v, texel) in [
            (0.0, 0.0, 0),
            (3.99, 0.5, 3),
            (4.0, 0.0, 0),
            (-0.01, 0.0, 3),
            (1.5, 2.99, 9),
            (1.5, 3.0, 1),
            (1.5, -0.5, 9),
        ] {
            let (u, v) = at(u, v);
            assert_eq!(repeat.sample(u, v), channels(t[texel]), "{u} {v}");
        }
        let clamp = repeat.with_wrap(Wrap::Clamp);
        for (u, v, texel) in [
            (-5.0, -5.0, 0),
            (100.0, 1.0, 7),
            (2.5, 1.5, 6),
            (-9.5, 10.5, 8),
        ] {
            let (u, v) = at(u, v);
            assert_eq!(clamp.sample(u, v), channels(t[texel]), "{u} {v}");
        }
    }

    /// Bilinear: a texel's centre gives the texel; half-way between two
    /// gives their mean; the blend wraps across the edge.
    #[test]
    fn bilinear_blends_between_centres() {
        let t = grid();
        let bilinear = Texture::new(&t, 4, 3)
            .unwrap()
            .with_filter(Filter::Bilinear);
        let centre = |i: i32, j: i32| (i * 256 + 128, j * 256 + 128);
        for k in 0..12 {
            let (u, v) = centre(k % 4, k / 4);
            assert_eq!(bilinear.sample(u, v), channels(t[k as usize]), "{k}");
        }
        let (u, v) = centre(1, 1);
        let mean: [u32; 3] = core::array::from_fn(|c| (channels(t[5])[c] + channels(t[6])[c]) / 2);
        assert_eq!(bilinear.sample(u + 128, v), mean);
        // Between column 3 and column 0 (wrapped).
        let (u, v) = centre(3, 0);
        let wrapped: [u32; 3] =
            core::array::from_fn(|c| (channels(t[3])[c] + channels(t[0])[c]) / 2);
        assert_eq!(bilinear.sample(u + 128, v), wrapped);
    }
}
