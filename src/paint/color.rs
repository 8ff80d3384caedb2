//! Colours from painted values: each channel arrives as an 8.8 fixed-point
//! value (`0..=`[`CHANNEL_MAX`], 255.0 at the top) and is quantised to the
//! colour's own channel depth, rounded to the nearest level, or with an
//! ordered dither ([`bayer_threshold`]) that trades banding for a fine
//! pattern where the colour has fewer than 8 bits a channel.

use embedded_graphics_core::pixelcolor::{
    Bgr555, Bgr565, Bgr666, Bgr888, Rgb555, Rgb565, Rgb666, Rgb888,
};

pub use crate::front::rgb8p8::CHANNEL_MAX;

/// The rounding offset of a channel quantised without dither: half a
/// level, so a channel rounds to the nearest level (ties up). An exact
/// 8-bit input `c` then gives embedded-graphics' own conversion,
/// `floor((c·max + 127) / 255)`: `c·max + 127.5` crosses a multiple of 255
/// exactly where `c·max + 127` does, both sides being integers and halves.
const NEAREST: u32 = CHANNEL_MAX / 2;

/// A colour a painted row can hold: up to 256 levels a channel, made from
/// the levels themselves ([`Self::from_levels`]) or from three 8.8
/// channels ([`Self::from_channels`]).
pub trait PaintColor: Copy {
    /// The top level of each channel (31, 63, 31 for `Rgb565`), each from
    /// 1 to 255.
    const MAX: [u32; 3];

    /// Whether a channel has fewer than 8 bits, so that dithering can help.
    const COARSE: bool = Self::MAX[0] < 255 || Self::MAX[1] < 255 || Self::MAX[2] < 255;

    /// The colour of these levels (each at most its [`Self::MAX`]).
    fn from_levels(levels: [u32; 3]) -> Self;

    /// The colour of channels `rgb` (each `0..=`[`CHANNEL_MAX`]; larger
    /// values are taken as [`CHANNEL_MAX`]), each rounded to the nearest
    /// level when `threshold` is `None`, else raised to the next level
    /// where its fraction of a level exceeds `threshold / 65,280`
    /// ([`bayer_threshold`]; a threshold of 2^16 or more gives some
    /// level, unspecified).
    #[inline(always)]
    fn from_channels(rgb: [u32; 3], threshold: Option<u32>) -> Self {
        let t = threshold.unwrap_or(NEAREST);
        let max = Self::MAX;
        Self::from_levels([
            level(rgb[0], max[0], t),
            level(rgb[1], max[1], t),
            level(rgb[2], max[2], t),
        ])
    }
}

/// `floor(x / 255)` for `x <= 16,646,527` (`65,280 · 255 + 127`), with no
/// division: `((x + 1)·257 + (x + 1)/256) / 65,536`, all below `2^32`
/// (the tests check every `x`).
#[inline(always)]
pub(crate) fn div255(x: u32) -> u32 {
    let y = x + 1;
    ((y << 8) + y + (y >> 8)) >> 16
}

/// A channel (8.8, taken as at most [`CHANNEL_MAX`]) in 1/256 of a level
/// of a channel with top level `max` (at most 255), rounded:
/// `round(v · max / 255)`, at most `256 · max`, within `2^-9` of a level
/// of the exact value.
#[inline(always)]
pub(crate) fn level_units(v: u32, max: u32) -> u32 {
    div255(v.min(CHANNEL_MAX) * max + 127)
}

/// `v` (8.8, at most [`CHANNEL_MAX`]) quantised to `0..=max` with the
/// offset `t` (`0..65,280`): `floor((v·max + t) / 65,280)`, with no
/// division (a core without a divider, the Cortex-M0+, would call one per
/// channel and pixel): `65,280 = 256 · 255`, so the quotient is
/// `floor(floor(x / 256) / 255)`, and `floor(y / 255) = (257·y + 257) >>
/// 16` for every `y < 2^16` (the tests check all of them).
///
/// Ranges: `x = v·max + t <= 65,280·255 + 65,279 < 2^24`, so `y < 2^16`
/// and `257·y + 257 < 2^25`.
#[inline(always)]
fn level(v: u32, max: u32, t: u32) -> u32 {
    // A threshold beyond the documented 16 bits wraps (a wrong level, no
    // panic); `v·max` is at most 65,280 · 255.
    let y = (v.min(CHANNEL_MAX) * max).wrapping_add(t) >> 8;
    (257 * y + 257) >> 16
}

/// The 4x4 Bayer matrix's entry for pixel `(x, y)`: `0..16`, each once in
/// every aligned 4x4 block.
#[inline(always)]
pub(crate) fn bayer_index(x: u16, y: u16) -> u32 {
    const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    u32::from(BAYER[usize::from(y & 3)][usize::from(x & 3)])
}

/// The ordered-dither threshold of pixel `(x, y)`: the 4x4 Bayer matrix's
/// entry `b` as the offset `(2b + 1)·65,280 / 32` of a channel's level, so that
/// the sixteen thresholds of a 4x4 block are spread evenly over a level
/// and average half of it (the rounding of no dither).
#[inline(always)]
pub fn bayer_threshold(x: u16, y: u16) -> u32 {
    (2 * bayer_index(x, y) + 1) * (CHANNEL_MAX / 32)
}

macro_rules! paint_color {
    ($($color:ty: $r:expr, $g:expr, $b:expr;)*) => {$(
        impl PaintColor for $color {
            const MAX: [u32; 3] = [$r, $g, $b];

            #[inline(always)]
            fn from_levels(levels: [u32; 3]) -> Self {
                <$color>::new(levels[0] as u8, levels[1] as u8, levels[2] as u8)
            }
        }
    )*};
}

paint_color! {
    Rgb565: 31, 63, 31;
    Bgr565: 31, 63, 31;
    Rgb555: 31, 31, 31;
    Bgr555: 31, 31, 31;
    Rgb666: 63, 63, 63;
    Bgr666: 63, 63, 63;
    Rgb888: 255, 255, 255;
    Bgr888: 255, 255, 255;
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::RgbColor;

    /// The division-free quotient by 255 is exact for every 16-bit `y`,
    /// and `level` is the division it stands for over its whole range
    /// (every level count, every `v` at a stride, every threshold the
    /// dither gives and the rounding offset).
    #[test]
    fn div255_is_the_division() {
        for x in 0..=65_280 * 255 + 127 {
            assert_eq!(div255(x), x / 255, "{x}");
        }
        for max in [1, 31, 63, 255] {
            for v in (0..=CHANNEL_MAX).chain([u32::MAX]) {
                let exact = f64::from(v.min(CHANNEL_MAX)) * f64::from(max) / 255.0;
                let got = f64::from(level_units(v, max));
                assert!((got - exact).abs() <= 0.5, "{v} {max}");
            }
        }
    }

    #[test]
    fn levels_are_the_division() {
        for y in 0..1u32 << 16 {
            assert_eq!((257 * y + 257) >> 16, y / 255, "{y}");
        }
        let thresholds = (0..16).map(|b| (2 * b + 1) * (CHANNEL_MAX / 32));
        for t in thresholds.chain([0, NEAREST, CHANNEL_MAX - 1]) {
            for max in [31, 63, 255] {
                for v in (0..=CHANNEL_MAX).step_by(3).chain([CHANNEL_MAX]) {
                    assert_eq!(
                        level(v, max, t),
                        (v * max + t) / CHANNEL_MAX,
                        "{v} {max} {t}"
                    );
                }
            }
        }
    }

    /// Without dither, an exact 8-bit channel converts as
    /// embedded-graphics converts `Rgb888`, for every value.
    #[test]
    fn exact_channels_convert_as_embedded_graphics() {
        for c in 0..=255u8 {
            let v = u32::from(c) << 8;
            let ours = Rgb565::from_channels([v, v, v], None);
            assert_eq!(ours, Rgb565::from(Rgb888::new(c, c, c)), "{c}");
            assert_eq!(Rgb888::from_channels([v, v, v], None), Rgb888::new(c, c, c));
        }
    }

    /// Without dither a channel rounds to the nearest level; the top and
    /// values beyond it give the top level.
    #[test]
    fn channels_round_to_the_nearest_level() {
        for v in (0..=CHANNEL_MAX).step_by(7) {
            let exact = f64::from(v) / 256.0 * 31.0 / 255.0;
            let got = f64::from(Rgb565::from_channels([v, 0, 0], None).r());
            assert!((got - exact).abs() <= 0.5 + 1e-9, "{v}: {got} for {exact}");
        }
        assert_eq!(Rgb565::from_channels([u32::MAX; 3], None), Rgb565::WHITE);
        assert_eq!(Rgb565::from_channels([u32::MAX; 3], Some(0)), Rgb565::WHITE);
    }

    /// Dithered, a 4x4 block averages to the exact level within 1/16 of a
    /// level (the matrix has 16 thresholds), and each pixel is one of the
    /// two levels around it.
    #[test]
    fn a_dithered_block_averages_to_the_value() {
        for v in (0..=CHANNEL_MAX).step_by(13) {
            let exact = f64::from(v) / 256.0 * 31.0 / 255.0;
            let mut sum = 0.0;
            for y in 0..4 {
                for x in 0..4 {
                    let c = Rgb565::from_channels([v, 0, 0], Some(bayer_threshold(x, y)));
                    let level = f64::from(c.r());
                    assert!(level == exact.floor() || level == exact.ceil(), "{v}");
                    sum += level;
                }
            }
            assert!(
                (sum / 16.0 - exact).abs() <= 1.0 / 16.0 + 1e-9,
                "{v}: {sum}"
            );
        }
    }
}
