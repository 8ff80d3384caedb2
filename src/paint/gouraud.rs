//! Gouraud shading: a colour at each vertex, each channel interpolated
//! over the polygon as an attribute plane (affine in screen space, as
//! classic Gouraud shading is: no division per pixel), then quantised to
//! the row's colour, with an ordered dither where it has fewer than 8
//! bits a channel (on by default there).

use core::marker::PhantomData;

pub use crate::front::rgb8p8::Rgb8p8;
use crate::paint::PaintMode;
use crate::paint::color::{PaintColor, bayer_index, level_units};
use crate::raster::BRANCH_FREE;
use crate::raster::attribute::{
    ATTRIBUTE_FRAC_BITS, AttributePlane, attribute_planes, box_corners_within, exact_value_at,
    modular_triangle_planes,
};
use crate::raster::lanes::LANES;
use crate::raster::vertex::ScreenVertex;

/// Gouraud shading into colours `C`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Gouraud<C> {
    dither: bool,
    color: PhantomData<C>,
}

impl<C: PaintColor> Gouraud<C> {
    /// Gouraud shading, dithered where `C` has fewer than 8 bits a channel
    /// (`Rgb565`: gradients would band visibly), not where it has 8.
    pub const fn new() -> Self {
        Self::with_dither(C::COARSE)
    }

    /// Gouraud shading, dithered or not.
    pub const fn with_dither(dither: bool) -> Self {
        Self {
            dither,
            color: PhantomData,
        }
    }

    /// Whether it dithers.
    pub const fn dithers(&self) -> bool {
        self.dither
    }
}

impl<C: PaintColor> Default for Gouraud<C> {
    fn default() -> Self {
        Self::new()
    }
}

/// The planes of a Gouraud-shaded polygon: one per channel, in units of
/// `2^-24` of a level of the painted colour's channel (each corner's value
/// is its 8.8 channel scaled to the colour's levels and rounded to 1/256
/// of a level, then interpolated at `2^-16` of that).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GouraudPlanes {
    channels: [AttributePlane; 3],
    /// Whether every pixel the polygon can paint has each channel's plane
    /// value within 1/32 of a level of `0..=max` (see [`WRAP_MARGIN`]), so
    /// that a run is painted in wrapping 32-bit arithmetic.
    wraps: bool,
}

/// Fractional bits of a level in a Gouraud plane's units: corners carry
/// 8 bits below the level, planes 16 more.
const LEVEL_SHIFT: u32 = 8 + ATTRIBUTE_FRAC_BITS;

/// How far (plane units, 1/32 of a level) a painted pixel's value may lie
/// outside `0..=max` for a run to be painted in wrapping 32-bit
/// arithmetic: then `value + t`, with a dither threshold or rounding
/// offset `t` in `1/32..=31/32` of a level, lies in `0..(max + 1)·2^24`,
/// below `2^32` as `max <= 255`, and its level is `(value + t) >> 24`
/// however the sum wrapped on the way.
const WRAP_MARGIN: i64 = 1 << (LEVEL_SHIFT - 5);

/// The offsets added to a plane value before its level is taken, for
/// pixels `x & 3 = 0..4` of row `y`: the 4x4 Bayer thresholds
/// ([`bayer_threshold`](crate::paint::bayer_threshold)) as `(2b + 1)/32` of a level, or half a level
/// (rounding) without dither.
#[inline(always)]
fn offsets(dither: bool, y: u16) -> [u32; 4] {
    core::array::from_fn(|k| {
        if dither {
            (2 * bayer_index(k as u16, y) + 1) << (LEVEL_SHIFT - 5)
        } else {
            1 << (LEVEL_SHIFT - 1)
        }
    })
}

impl<C: PaintColor> PaintMode for Gouraud<C> {
    type Source = Rgb8p8;
    type Vertex = Rgb8p8;
    type Planes = GouraudPlanes;
    type Color = C;
    /// The offsets added before a level is taken, for pixels `x & 3 =
    /// 0..4`: dither thresholds `(2b + 1)/32` of a level, or a half.
    type Row = [u32; 4];
    const VERTEX_FILLER: Rgb8p8 = Rgb8p8::BLACK;
    const PLANES_FILLER: GouraudPlanes = GouraudPlanes {
        channels: [AttributePlane::ZERO; 3],
        wraps: false,
    };

    fn vertex(&self, source: Rgb8p8) -> Rgb8p8 {
        source
    }

    fn planes(
        &self,
        corners: impl Iterator<Item = (ScreenVertex, Rgb8p8)> + Clone,
        width: u16,
        height: u16,
    ) -> GouraudPlanes {
        let levels = corners.map(|(v, c)| (v, corner_levels::<C>(c)));
        let mut three = levels.clone();
        if let (Some(o), Some(p), Some(q), None) =
            (three.next(), three.next(), three.next(), three.next())
            && let Some(channels) = modular_triangle_planes(o, p, q)
        {
            // Within 2^-10 of a level of the exact plane at its pixels
            // (see modular_triangle_planes), whose values there lie in
            // 0..=max: within WRAP_MARGIN.
            return GouraudPlanes {
                channels,
                wraps: true,
            };
        }
        let Some(channels) = attribute_planes(levels.clone(), width, height) else {
            return Self::PLANES_FILLER;
        };
        let wraps = !channels.iter().any(AttributePlane::is_steep)
            && (levels.clone().nth(3).is_none()
                || within_margin::<C>(&channels, levels, width, height));
        GouraudPlanes { channels, wraps }
    }

    fn row(&self, y: u16) -> [u32; 4] {
        offsets(self.dither, y)
    }

    #[inline]
    fn paint_run<I: Iterator<Item = (ScreenVertex, Rgb8p8)> + Clone>(
        &self,
        offsets: &[u32; 4],
        planes: &GouraudPlanes,
        corners: impl Fn() -> I,
        x0: u16,
        y: u16,
        out: &mut [C],
    ) {
        if !planes.wraps {
            return self.paint_clamped(offsets, planes, corners(), x0, y, out);
        }
        paint_wrapping::<C, BRANCH_FREE>(offsets, planes, x0, y, out);
    }
}

/// Paints a run of a polygon whose planes wrap ([`GouraudPlanes::wraps`]):
/// each channel's value stepped in wrapping 32-bit arithmetic, its level
/// taken after adding the pixel's offset. With `BLOCKS` (hosts: see
/// [`crate::raster::lanes`]) the run goes [`LANES`] pixels at a time, each
/// lane's values carried from block to block (eight steps added at once,
/// which wrap to the same values as eight single steps), so that the
/// compiler keeps a block's channels in vector registers; the rest, and
/// every pixel without `BLOCKS`, one at a time. Both give the same pixels.
#[inline(always)]
fn paint_wrapping<C: PaintColor, const BLOCKS: bool>(
    offsets: &[u32; 4],
    planes: &GouraudPlanes,
    x0: u16,
    y: u16,
    out: &mut [C],
) {
    let start = |p: &AttributePlane| {
        (p.at_origin as u32)
            .wrapping_add((p.dx as u32).wrapping_mul(u32::from(x0)))
            .wrapping_add((p.dy as u32).wrapping_mul(u32::from(y)))
    };
    let [r, g, b] = &planes.channels;
    let mut values = [start(r), start(g), start(b)];
    let steps = [r.dx as u32, g.dx as u32, b.dx as u32];
    let level = |v: u32, t: u32| v.wrapping_add(t) >> LEVEL_SHIFT;
    let mut out = out;
    if BLOCKS && out.len() >= LANES {
        // Lane `k` holds pixel `k` of the block; a block starts at a
        // multiple of LANES (itself a multiple of 4) from `x0`, so each
        // lane keeps its dither offset, and the pixels after the blocks
        // take theirs as if counted from `x0`.
        let mut lanes: [[u32; LANES]; 3] = core::array::from_fn(|c| {
            core::array::from_fn(|k| values[c].wrapping_add(steps[c].wrapping_mul(k as u32)))
        });
        let block_steps = steps.map(|d| d.wrapping_mul(LANES as u32));
        let t: [u32; LANES] = core::array::from_fn(|k| offsets[(usize::from(x0) + k) & 3]);
        let mut blocks = out.chunks_exact_mut(LANES);
        for block in &mut blocks {
            let [lr, lg, lb] = &lanes;
            for (k, pixel) in block.iter_mut().enumerate() {
                *pixel =
                    C::from_levels([level(lr[k], t[k]), level(lg[k], t[k]), level(lb[k], t[k])]);
            }
            for (lane, step) in lanes.iter_mut().zip(block_steps) {
                for v in lane {
                    *v = v.wrapping_add(step);
                }
            }
        }
        values = lanes.map(|lane| lane[0]);
        out = blocks.into_remainder();
    }
    let [mut vr, mut vg, mut vb] = values;
    let [dr, dg, db] = steps;
    for (x, pixel) in (x0..).zip(out) {
        let t = offsets[usize::from(x & 3)];
        *pixel = C::from_levels([level(vr, t), level(vg, t), level(vb, t)]);
        vr = vr.wrapping_add(dr);
        vg = vg.wrapping_add(dg);
        vb = vb.wrapping_add(db);
    }
}

/// A corner's channels in 1/256 of a level of `C`'s channels.
#[inline]
fn corner_levels<C: PaintColor>(c: Rgb8p8) -> [u32; 3] {
    let [r, g, b] = c.values();
    let max = C::MAX;
    [
        level_units(r, max[0]),
        level_units(g, max[1]),
        level_units(b, max[2]),
    ]
}

/// Whether each plane's values over the pixels of the polygon's bounding
/// box (clamped to the frame) lie within [`WRAP_MARGIN`] of `0..=max`: a
/// plane's extremes over a box are at its corners. (A triangle needs no
/// check: its painted pixels' samples lie inside it, where each plane is
/// within its error bound, below `2^-8` of a corner value step, of the
/// range of the corners' values.)
fn within_margin<C: PaintColor>(
    channels: &[AttributePlane; 3],
    corners: impl Iterator<Item = (ScreenVertex, [u32; 3])>,
    width: u16,
    height: u16,
) -> bool {
    let range = |_: &AttributePlane, k: usize| {
        let top = i64::from(C::MAX[k]) << LEVEL_SHIFT;
        -WRAP_MARGIN..=top + WRAP_MARGIN
    };
    box_corners_within(channels, range, corners.map(|(v, _)| v), (width, height))
}

impl<C: PaintColor> Gouraud<C> {
    /// [`PaintMode::paint_run`] for a polygon whose values may stray
    /// further from their range (a polygon of more than three corners
    /// whose corner values are not coplanar, or a steep plane, whose
    /// channels take their exact values at each pixel: slivers narrower
    /// than a sub-pixel step): each value in `i64`, clamped to its range.
    #[inline(never)]
    fn paint_clamped(
        &self,
        offsets: &[u32; 4],
        planes: &GouraudPlanes,
        corners: impl Iterator<Item = (ScreenVertex, Rgb8p8)> + Clone,
        x0: u16,
        y: u16,
        out: &mut [C],
    ) {
        let values = corners.map(|(v, c)| (v, corner_levels::<C>(c)));
        for (x, pixel) in (x0..).zip(out) {
            let t = i64::from(offsets[usize::from(x & 3)]);
            let levels: [u32; 3] = core::array::from_fn(|k| {
                let plane = &planes.channels[k];
                let value = if plane.is_steep() {
                    exact_value_at(values.clone(), k, x, y)
                } else {
                    plane.value_at(x, y)
                };
                let top = i64::from(C::MAX[k]) << LEVEL_SHIFT;
                ((value.clamp(0, top) + t) >> LEVEL_SHIFT).min(i64::from(C::MAX[k])) as u32
            });
            *pixel = C::from_levels(levels);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
    use proptest::prelude::*;
    use std::vec;

    /// Both ways of painting a wrapping run, into colours `C`.
    fn both<C: PaintColor + Default + PartialEq + core::fmt::Debug>(
        planes: &GouraudPlanes,
        dither: bool,
        (x0, y, n): (u16, u16, usize),
    ) {
        let offsets = offsets(dither, y);
        let (mut blocks, mut pixels) = (vec![C::default(); n], vec![C::default(); n]);
        paint_wrapping::<C, true>(&offsets, planes, x0, y, &mut blocks);
        paint_wrapping::<C, false>(&offsets, planes, x0, y, &mut pixels);
        assert_eq!(blocks, pixels);
    }

    proptest! {
        /// Blocks of lanes paint the pixels one at a time paints, for any
        /// plane values (they wrap alike), run start, row and length.
        #[test]
        fn blocks_paint_as_pixels(
            at_origin in any::<[u32; 3]>(),
            dx in any::<[u32; 3]>(),
            dy in any::<[u32; 3]>(),
            x0 in 0u16..4096,
            y in 0u16..4096,
            n in 0usize..40,
            dither in any::<bool>(),
        ) {
            let planes = GouraudPlanes {
                channels: core::array::from_fn(|c| AttributePlane {
                    at_origin: i64::from(at_origin[c]),
                    dx: i64::from(dx[c]),
                    dy: i64::from(dy[c]),
                }),
                wraps: true,
            };
            both::<Rgb565>(&planes, dither, (x0, y, n));
            both::<Rgb888>(&planes, dither, (x0, y, n));
        }
    }
}
