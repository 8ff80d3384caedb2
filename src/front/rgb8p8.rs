//! Vertex colours with 8 bits below the 8-bit step ([`Rgb8p8`]), which
//! vertex shading gives and Gouraud shading interpolates.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use crate::front::clip::ClipValue;

/// 255.0 in a channel's 8.8 fixed point.
pub const CHANNEL_MAX: u32 = 255 << 8;

/// A vertex colour in 8.8 fixed point per channel: `0x0000` is 0 and
/// `0xFF00` is 255 (values above are taken as 255), so shading computed
/// per vertex keeps 8 bits below the 8-bit step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Rgb8p8 {
    /// Red.
    pub r: u16,
    /// Green.
    pub g: u16,
    /// Blue.
    pub b: u16,
}

impl Rgb8p8 {
    /// Black.
    pub const BLACK: Self = Self { r: 0, g: 0, b: 0 };

    /// An 8-bit colour, exactly.
    pub fn from_rgb888(c: Rgb888) -> Self {
        Self {
            r: (c.r() as u16) << 8,
            g: (c.g() as u16) << 8,
            b: (c.b() as u16) << 8,
        }
    }

    /// Channels in `[0, 1]` (values beyond are clamped; NaN is 0), rounded
    /// to the nearest 1/256 of an 8-bit step.
    pub fn from_unit(rgb: [f32; 3]) -> Self {
        let channel = |v: f32| {
            let scaled = v.clamp(0.0, 1.0) * CHANNEL_MAX as f32 + 0.5;
            // `as` saturates, and NaN becomes 0.
            scaled as u16
        };
        Self {
            r: channel(rgb[0]),
            g: channel(rgb[1]),
            b: channel(rgb[2]),
        }
    }

    /// The channels as attribute values.
    pub(crate) fn values(self) -> [u32; 3] {
        [u32::from(self.r), u32::from(self.g), u32::from(self.b)]
    }
}

impl ClipValue for Rgb8p8 {
    /// Each channel interpolated and rounded.
    fn lerp(self, other: Self, t: f64) -> Self {
        let channel = |a: u16, b: u16| {
            let (a, b) = (f64::from(a), f64::from(b));
            // Between a and b for t in [0, 1]; `as` saturates otherwise.
            (a + (b - a) * t + 0.5) as u16
        };
        Self {
            r: channel(self.r, other.r),
            g: channel(self.g, other.g),
            b: channel(self.b, other.b),
        }
    }
}

impl From<Rgb888> for Rgb8p8 {
    fn from(c: Rgb888) -> Self {
        Self::from_rgb888(c)
    }
}
