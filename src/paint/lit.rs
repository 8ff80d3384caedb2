//! Lit texture mapping: a [`Textured`] polygon's texel scaled, channel by
//! channel, by a light given at each corner (for example Lambert lighting
//! of the vertex's normal, [`Lambert::vertex_color`] of a white base) and
//! interpolated as Gouraud's colours are.
//!
//! # Planes and error
//! The texture coordinates are [`Textured`]'s (perspective-correct, within
//! its stated bound). The light's three channels, 8.8 values from 0 to
//! [`CHANNEL_MAX`] (1.0), are attribute planes affine in screen space, as
//! Gouraud shading interpolates (each within `2^-8` of a value step of
//! the exact plane inside a triangle; a steep plane's values are exact at
//! every pixel). A pixel's channel is the texel's 8.8 channel `s` times
//! the light's `l` over `CHANNEL_MAX`, rounded: `(s·l + 32,640) / 65,280`,
//! within half a step of 8.8 of the exact product, then quantised to the
//! painted colour as [`PaintColor::from_channels`] does (dithered by
//! default where the colour has fewer than 8 bits a channel, since the
//! light's gradients would band there).
//!
//! [`Lambert::vertex_color`]: crate::Lambert::vertex_color

use crate::front::clip::ClipValue;
use crate::front::rgb8p8::Rgb8p8;
use crate::front::tex_coord::TexCoord;
use crate::paint::PaintMode;
use crate::paint::color::{CHANNEL_MAX, PaintColor, bayer_threshold};
use crate::paint::texture::Texture;
use crate::paint::textured::{Textured, TexturedPlanes};
use crate::raster::attribute::{
    ATTRIBUTE_FRAC_BITS, AttributePlane, attribute_planes, exact_value_at,
};
use crate::raster::vertex::ScreenVertex;

/// What a vertex of a lit textured polygon carries: its texture
/// coordinates and the light (8.8 channels, [`CHANNEL_MAX`] for 1.0) its
/// texel is scaled by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LitTexCoord {
    /// Texture coordinates and clip `w`.
    pub tex: TexCoord,
    /// The light at the vertex.
    pub light: Rgb8p8,
}

impl LitTexCoord {
    /// A vertex's coordinates with its light.
    pub const fn new(tex: TexCoord, light: Rgb8p8) -> Self {
        Self { tex, light }
    }
}

impl ClipValue for LitTexCoord {
    /// The coordinates as [`TexCoord`] cuts them, the light as [`Rgb8p8`]
    /// does.
    fn lerp(self, other: Self, t: f64) -> Self {
        Self {
            tex: self.tex.lerp(other.tex, t),
            light: self.light.lerp(other.light, t),
        }
    }
}

/// A lit textured polygon's planes: the texture's and the light's three
/// channels (plane units: `2^-ATTRIBUTE_FRAC_BITS` of an 8.8 step).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LitTexturedPlanes {
    texture: TexturedPlanes,
    light: [AttributePlane; 3],
}

/// Texture mapping lit per vertex, into colours `C` (see the module's
/// notes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LitTextured<'a, C> {
    textured: Textured<'a, C>,
}

impl<'a, C: PaintColor> LitTextured<'a, C> {
    /// Lit texture mapping from `texture`, dithered where `C` has fewer
    /// than 8 bits a channel.
    pub const fn new(texture: Texture<'a>) -> Self {
        Self::with_dither(texture, C::COARSE)
    }

    /// Lit texture mapping, dithered or not.
    pub const fn with_dither(texture: Texture<'a>, dither: bool) -> Self {
        Self {
            textured: Textured::with_dither(texture, dither),
        }
    }

    /// The texture.
    pub const fn texture(&self) -> &Texture<'a> {
        self.textured.texture()
    }

    /// Whether it dithers.
    pub const fn dithers(&self) -> bool {
        self.textured.dithers()
    }
}

/// A corner's light channels as attribute values (8.8, at most
/// [`CHANNEL_MAX`]).
#[inline(always)]
fn light_values(light: Rgb8p8) -> [u32; 3] {
    light.values().map(|c| c.min(CHANNEL_MAX))
}

/// `s·l / CHANNEL_MAX`, rounded, for 8.8 channels `s`, `l` (each at most
/// [`CHANNEL_MAX`]): at most `CHANNEL_MAX`; the product is below `2^32`.
#[inline(always)]
fn scaled(s: u32, l: u32) -> u32 {
    (s * l + CHANNEL_MAX / 2) / CHANNEL_MAX
}

impl<'a, C: PaintColor> PaintMode for LitTextured<'a, C> {
    type Source = LitTexCoord;
    type Vertex = LitTexCoord;
    type Row = ();
    type Planes = LitTexturedPlanes;
    type Color = C;
    const VERTEX_FILLER: LitTexCoord = LitTexCoord {
        tex: <Textured<'a, C> as PaintMode>::VERTEX_FILLER,
        light: Rgb8p8::BLACK,
    };
    const PLANES_FILLER: LitTexturedPlanes = LitTexturedPlanes {
        texture: <Textured<'a, C> as PaintMode>::PLANES_FILLER,
        light: [AttributePlane::ZERO; 3],
    };

    fn vertex(&self, source: LitTexCoord) -> LitTexCoord {
        source
    }

    fn planes(
        &self,
        corners: impl Iterator<Item = (ScreenVertex, LitTexCoord)> + Clone,
        width: u16,
        height: u16,
    ) -> LitTexturedPlanes {
        let texture = self
            .textured
            .planes(corners.clone().map(|(v, c)| (v, c.tex)), width, height);
        let lights = corners.map(|(v, c)| (v, light_values(c.light)));
        LitTexturedPlanes {
            texture,
            light: attribute_planes(lights, width, height).unwrap_or_default(),
        }
    }

    fn row(&self, _y: u16) {}

    fn paint_run<I: Iterator<Item = (ScreenVertex, LitTexCoord)> + Clone>(
        &self,
        _row: &(),
        planes: &LitTexturedPlanes,
        corners: impl Fn() -> I,
        x0: u16,
        y: u16,
        out: &mut [C],
    ) {
        let dither = self.textured.dithers();
        let top = i64::from(CHANNEL_MAX) << ATTRIBUTE_FRAC_BITS;
        let half = 1i64 << (ATTRIBUTE_FRAC_BITS - 1);
        // A plane value as an 8.8 light channel: rounded, in range.
        let light_of = |value: i64| ((value.clamp(0, top) + half) >> ATTRIBUTE_FRAC_BITS) as u32;
        let steep = planes.light.iter().any(AttributePlane::is_steep);
        // Stepped along the run (values at the run's pixels lie within a
        // plane's error of the corners' range, far inside i64).
        let mut light = planes
            .light
            .map(|p| if steep { 0 } else { p.value_at(x0, y) });
        let step = planes.light.map(|p| if steep { 0 } else { p.dx });
        let lights = || corners().map(|(v, c)| (v, light_values(c.light)));
        let tex_corners = corners().map(|(v, c)| (v, c.tex));
        self.textured
            .coordinates(&planes.texture, tex_corners, (x0, y), out.len(), |k, t| {
                let x = x0 + k as u16;
                let l: [u32; 3] = if steep {
                    core::array::from_fn(|c| {
                        let plane = &planes.light[c];
                        light_of(if plane.is_steep() {
                            exact_value_at(lights(), c, x, y)
                        } else {
                            plane.value_at(x, y)
                        })
                    })
                } else {
                    light.map(light_of)
                };
                let s = self.textured.channels(&planes.texture, t);
                let rgb = [scaled(s[0], l[0]), scaled(s[1], l[1]), scaled(s[2], l[2])];
                if let Some(pixel) = out.get_mut(k) {
                    *pixel = C::from_channels(rgb, dither.then(|| bayer_threshold(x, y)));
                }
                light = [light[0] + step[0], light[1] + step[1], light[2] + step[2]];
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The product's rounding at the extremes and its range.
    #[test]
    fn scaling_is_exact_at_the_ends() {
        assert_eq!(scaled(CHANNEL_MAX, CHANNEL_MAX), CHANNEL_MAX);
        assert_eq!(scaled(CHANNEL_MAX, 0), 0);
        assert_eq!(scaled(0, CHANNEL_MAX), 0);
        assert_eq!(scaled(1234, CHANNEL_MAX), 1234);
        // Half a light: half the channel, rounded.
        assert_eq!(scaled(CHANNEL_MAX, CHANNEL_MAX / 2), CHANNEL_MAX / 2);
        for s in (0..=CHANNEL_MAX).step_by(97) {
            for l in (0..=CHANNEL_MAX).step_by(89) {
                let exact = f64::from(s) * f64::from(l) / f64::from(CHANNEL_MAX);
                assert!((f64::from(scaled(s, l)) - exact).abs() <= 0.5, "{s} {l}");
            }
        }
    }
}
