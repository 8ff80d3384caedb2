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
use crate::paint::color::{CHANNEL_MAX, PaintColor, bayer_threshold, div255};
use crate::paint::texture::Texture;
use crate::paint::textured::{Textured, TexturedPlanes};
use crate::raster::attribute::{
    ATTRIBUTE_FRAC_BITS, AttributePlane, attribute_planes, box_corners_within, exact_value_at,
    triangle_planes,
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
    /// Whether every pixel the polygon paints has each light plane's value
    /// within [`LIGHT_WRAP`] (see there), so that a run is stepped in
    /// wrapping 32-bit arithmetic: a triangle whose planes the flat
    /// scan's set-up makes, or a polygon whose bounding box allows it.
    wraps: bool,
}

/// Half an 8.8 step in plane units: added before a light is taken.
const HALF: i64 = 1 << (ATTRIBUTE_FRAC_BITS - 1);

/// The plane values a light may take at a pixel for a run to be stepped
/// in wrapping `u32`: with [`HALF`] added they lie in `0..2^32`, so `(v +
/// HALF) >> ATTRIBUTE_FRAC_BITS`, at most [`CHANNEL_MAX`] once limited,
/// is the light the `i64` clamp and rounding give, however the sum
/// wrapped on the way.
const LIGHT_WRAP: core::ops::RangeInclusive<i64> = -HALF..=(1 << 32) - HALF - 1;

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
/// [`CHANNEL_MAX`]): at most `CHANNEL_MAX`. With no division (a
/// Cortex-M0+ has no divider): `CHANNEL_MAX = 256 · 255`, so the quotient
/// is `floor(floor(x / 256) / 255)` for `x = s·l + CHANNEL_MAX / 2`, at
/// most `65,280² + 32,640 < 2^32`; `x / 256` is at most 16,646,527, the
/// largest [`div255`] takes.
#[inline(always)]
fn scaled(s: u32, l: u32) -> u32 {
    div255((s.min(CHANNEL_MAX) * l.min(CHANNEL_MAX) + CHANNEL_MAX / 2) >> 8)
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
        wraps: false,
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
        let lights = corners.clone().map(|(v, c)| (v, light_values(c.light)));
        let mut three = lights.clone();
        if let (Some(o), Some(p), Some(q), None) =
            (three.next(), three.next(), three.next(), three.next())
            && let Some(light) = triangle_planes(o, p, q)
        {
            // Within 2^-8 of a value step (2^8 plane units, far inside
            // LIGHT_WRAP's margin) of the corners' range, 0..=CHANNEL_MAX,
            // at every pixel the triangle paints (see triangle_planes).
            return LitTexturedPlanes {
                texture,
                light,
                wraps: true,
            };
        }
        let light = attribute_planes(lights, width, height).unwrap_or_default();
        // Anything else, where its bounding box allows.
        let wraps = light.iter().all(|p| !p.is_steep())
            && box_corners_within(
                &light,
                |_, _| LIGHT_WRAP,
                corners.map(|(v, _)| v),
                (width, height),
            );
        LitTexturedPlanes {
            texture,
            light,
            wraps,
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
        let n = out.len();
        let tex_corners = || corners().map(|(v, c)| (v, c.tex));
        // Pixel `k` of the run: its texel at `t` times the light `l`.
        let mut put = |k: usize, t: [i64; 2], l: [u32; 3]| {
            let s = self.textured.channels(&planes.texture, t);
            let rgb = [scaled(s[0], l[0]), scaled(s[1], l[1]), scaled(s[2], l[2])];
            let threshold = dither.then(|| bayer_threshold(x0.wrapping_add(k as u16), y));
            if let Some(pixel) = out.get_mut(k) {
                *pixel = C::from_channels(rgb, threshold);
            }
        };
        if planes.wraps {
            // Each light stepped in wrapping u32 with HALF added (see
            // LIGHT_WRAP): the light the i64 path below gives.
            let [r, g, b] = planes
                .light
                .map(|p| p.value_at(x0, y).wrapping_add(HALF) as u32);
            let mut light = [r, g, b];
            let step = planes.light.map(|p| p.dx as u32);
            self.textured
                .coordinates(&planes.texture, tex_corners, (x0, y), n, |k, t| {
                    put(
                        k,
                        t,
                        light.map(|v| (v >> ATTRIBUTE_FRAC_BITS).min(CHANNEL_MAX)),
                    );
                    light = [
                        light[0].wrapping_add(step[0]),
                        light[1].wrapping_add(step[1]),
                        light[2].wrapping_add(step[2]),
                    ];
                });
            return;
        }
        let top = i64::from(CHANNEL_MAX) << ATTRIBUTE_FRAC_BITS;
        // A plane value as an 8.8 light channel: rounded, in range.
        let light_of = |value: i64| ((value.clamp(0, top) + HALF) >> ATTRIBUTE_FRAC_BITS) as u32;
        let steep = planes.light.iter().any(AttributePlane::is_steep);
        // Stepped along the run (values at the run's pixels lie within a
        // plane's error of the corners' range, far inside i64).
        let mut light = planes
            .light
            .map(|p| if steep { 0 } else { p.value_at(x0, y) });
        let step = planes.light.map(|p| if steep { 0 } else { p.dx });
        let lights = || corners().map(|(v, c)| (v, light_values(c.light)));
        self.textured
            .coordinates(&planes.texture, tex_corners, (x0, y), n, |k, t| {
                let x = x0.wrapping_add(k as u16);
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
                put(k, t, l);
                light = [light[0] + step[0], light[1] + step[1], light[2] + step[2]];
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::clip_w::ClipW;
    use crate::limits::SUBPIXEL_STEPS;
    use crate::paint::sample_inside;
    use crate::raster::attribute::pixel_box;
    use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
    use proptest::prelude::*;
    use std::vec;
    use std::vec::Vec;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// Where a triangle's lights take the wrapping 32-bit steps, every
        /// pixel whose sample is inside it gets the light the `i64` clamp
        /// and rounding give (the same run painted both ways).
        #[test]
        fn wrapping_steps_give_the_clamped_light(
            xy in prop::array::uniform3((0..64 * SUBPIXEL_STEPS, 0..64 * SUBPIXEL_STEPS)),
            lights in prop::array::uniform3(prop::array::uniform3(any::<u16>())),
            dither in any::<bool>(),
        ) {
            let white = [0xFFFFu16; 4];
            let texture = Texture::new(&white, 2, 2).unwrap();
            let mode = LitTextured::<Rgb888>::with_dither(texture, dither);
            let corners: [(ScreenVertex, LitTexCoord); 3] = core::array::from_fn(|k| {
                let tex = TexCoord { uv: [0, 0], w: ClipW::ONE };
                let [r, g, b] = lights[k];
                (
                    ScreenVertex::new(xy[k].0, xy[k].1, 0).unwrap(),
                    LitTexCoord::new(tex, Rgb8p8 { r, g, b }),
                )
            });
            let planes = mode.planes(corners.iter().copied(), 64, 64);
            prop_assume!(planes.wraps);
            let clamped = LitTexturedPlanes { wraps: false, ..planes };
            let (x0, x1, y0, y1) = pixel_box(corners.iter().map(|c| c.0), 64, 64);
            for y in y0..=y1 {
                // The row's samples inside the triangle: one run.
                let inside: Vec<u16> = (x0..=x1).filter(|&x| sample_inside(corners.map(|c| c.0), x, y)).collect();
                let (Some(&first), Some(&last)) = (inside.first(), inside.last()) else {
                    continue;
                };
                let n = usize::from(last - first) + 1;
                let (mut a, mut b): (Vec<Rgb888>, Vec<Rgb888>) =
                    (vec![Rgb888::BLACK; n], vec![Rgb888::BLACK; n]);
                mode.paint_run(&(), &planes, || corners.iter().copied(), first, y, &mut a);
                mode.paint_run(&(), &clamped, || corners.iter().copied(), first, y, &mut b);
                prop_assert_eq!(a, b);
            }
        }
    }

    /// The product's rounding at the extremes and its range.
    #[test]
    fn scaling_is_exact_at_the_ends() {
        assert_eq!(scaled(CHANNEL_MAX, CHANNEL_MAX), CHANNEL_MAX);
        assert_eq!(scaled(CHANNEL_MAX, 0), 0);
        assert_eq!(scaled(0, CHANNEL_MAX), 0);
        assert_eq!(scaled(1234, CHANNEL_MAX), 1234);
        // Half a light: half the channel, rounded.
        assert_eq!(scaled(CHANNEL_MAX, CHANNEL_MAX / 2), CHANNEL_MAX / 2);
        // The division it replaces, on a grid and at the top.
        for s in (0..=CHANNEL_MAX)
            .step_by(61)
            .chain([CHANNEL_MAX - 1, CHANNEL_MAX])
        {
            for l in (0..=CHANNEL_MAX)
                .step_by(59)
                .chain([CHANNEL_MAX - 1, CHANNEL_MAX])
            {
                assert_eq!(
                    scaled(s, l),
                    (s * l + CHANNEL_MAX / 2) / CHANNEL_MAX,
                    "{s} {l}"
                );
            }
        }
        for s in (0..=CHANNEL_MAX).step_by(97) {
            for l in (0..=CHANNEL_MAX).step_by(89) {
                let exact = f64::from(s) * f64::from(l) / f64::from(CHANNEL_MAX);
                assert!((f64::from(scaled(s, l)) - exact).abs() <= 0.5, "{s} {l}");
            }
        }
    }
}
