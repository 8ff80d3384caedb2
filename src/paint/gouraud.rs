//! Gouraud shading: a colour at each vertex, each channel interpolated
//! over the polygon as an attribute plane (affine in screen space, as
//! classic Gouraud shading is: no division per pixel), then quantised to
//! the row's colour, with an ordered dither where it has fewer than 8
//! bits a channel (on by default there).

use core::marker::PhantomData;

use crate::arith::wide::mul_i64_small;
pub use crate::front::rgb8p8::Rgb8p8;
use crate::paint::PaintMode;
use crate::paint::color::{CHANNEL_MAX, PaintColor, bayer_threshold};
use crate::raster::attribute::{
    ATTRIBUTE_FRAC_BITS, AttributePlane, attribute_planes, exact_value_at,
};
use crate::raster::vertex::ScreenVertex;

/// The planes of a Gouraud-shaded polygon: one per channel.
pub type GouraudPlanes = [AttributePlane; 3];

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

/// A plane value (plane units) as a channel: rounded to 8.8, clamped to
/// `0..=`[`CHANNEL_MAX`] (a pixel inside the polygon is off its corners'
/// range by at most the plane's error, below 2^-4 of a value step).
#[inline(always)]
fn channel(value: i64) -> u32 {
    let rounded = (value + (1 << (ATTRIBUTE_FRAC_BITS - 1))) >> ATTRIBUTE_FRAC_BITS;
    rounded.clamp(0, i64::from(CHANNEL_MAX)) as u32
}

impl<C: PaintColor> PaintMode for Gouraud<C> {
    type Source = Rgb8p8;
    type Vertex = Rgb8p8;
    type Planes = GouraudPlanes;
    type Color = C;
    const VERTEX_FILLER: Rgb8p8 = Rgb8p8::BLACK;
    const PLANES_FILLER: GouraudPlanes = [AttributePlane::ZERO; 3];

    fn vertex(&self, source: Rgb8p8) -> Rgb8p8 {
        source
    }

    fn planes(
        &self,
        corners: impl Iterator<Item = (ScreenVertex, Rgb8p8)> + Clone,
        width: u16,
        height: u16,
    ) -> GouraudPlanes {
        attribute_planes(corners.map(|(v, c)| (v, c.values())), width, height).unwrap_or_default()
    }

    #[inline]
    fn paint_run(
        &self,
        planes: &GouraudPlanes,
        corners: impl Iterator<Item = (ScreenVertex, Rgb8p8)> + Clone,
        x0: u16,
        y: u16,
        out: &mut [C],
    ) {
        if planes.iter().any(AttributePlane::is_steep) {
            return self.paint_steep(planes, corners, x0, y, out);
        }
        let [r, g, b] = planes;
        let (vr, vg, vb) = (r.value_at(x0, y), g.value_at(x0, y), b.value_at(x0, y));
        // The run's last values: the values are linear along it, so when
        // both ends of each channel lie in `0..RUN_LIMIT`, every value
        // between does, and 32-bit wrapping steps give them exactly.
        let steps = out.len().saturating_sub(1) as i32;
        let in_range = |v: i64, dx: i64| {
            let last = v + mul_i64_small(dx, steps);
            (0..RUN_LIMIT).contains(&v) && (0..RUN_LIMIT).contains(&last)
        };
        if in_range(vr, r.dx) && in_range(vg, g.dx) && in_range(vb, b.dx) {
            return self.paint_run_32([vr, vg, vb], [r.dx, g.dx, b.dx], x0, y, out);
        }
        let (mut vr, mut vg, mut vb) = (vr, vg, vb);
        for (x, pixel) in (x0..).zip(out) {
            let threshold = self.dither.then(|| bayer_threshold(x, y));
            *pixel = C::from_channels([channel(vr), channel(vg), channel(vb)], threshold);
            (vr, vg, vb) = (vr + r.dx, vg + g.dx, vb + b.dx);
        }
    }
}

/// Values (plane units) below which a run is stepped in 32 bits: rounding
/// adds `2^15`, which must not carry out of 32 bits.
const RUN_LIMIT: i64 = (1 << 32) - (1 << (ATTRIBUTE_FRAC_BITS - 1));

impl<C: PaintColor> Gouraud<C> {
    /// A run whose values all lie in `0..RUN_LIMIT` (`start`, the values at
    /// its first pixel, and the run's last, checked by the caller): each
    /// value and step taken modulo `2^32`, which gives the exact values,
    /// rounded as [`channel`] rounds them (no clamp at 0 is needed). The
    /// same pixels as the `i64` loop, in a third of the registers (the
    /// Cortex-M0+ has eight it can add in).
    #[inline(always)]
    fn paint_run_32(&self, start: [i64; 3], dx: [i64; 3], x0: u16, y: u16, out: &mut [C]) {
        let [mut vr, mut vg, mut vb] = start.map(|v| v as u32);
        let [dr, dg, db] = dx.map(|d| d as u32);
        let half = 1u32 << (ATTRIBUTE_FRAC_BITS - 1);
        let ch = |v: u32| ((v + half) >> ATTRIBUTE_FRAC_BITS).min(CHANNEL_MAX);
        let thresholds: [Option<u32>; 4] =
            core::array::from_fn(|k| self.dither.then(|| bayer_threshold(k as u16, y)));
        for (x, pixel) in (x0..).zip(out) {
            let threshold = thresholds[usize::from(x & 3)];
            *pixel = C::from_channels([ch(vr), ch(vg), ch(vb)], threshold);
            vr = vr.wrapping_add(dr);
            vg = vg.wrapping_add(dg);
            vb = vb.wrapping_add(db);
        }
    }
}

impl<C: PaintColor> Gouraud<C> {
    /// [`PaintMode::paint_run`] for a polygon with a steep plane: its
    /// channels' exact values at each pixel (rare: slivers narrower than
    /// a sub-pixel step).
    #[inline(never)]
    fn paint_steep(
        &self,
        planes: &GouraudPlanes,
        corners: impl Iterator<Item = (ScreenVertex, Rgb8p8)> + Clone,
        x0: u16,
        y: u16,
        out: &mut [C],
    ) {
        let values = corners.map(|(v, c)| (v, c.values()));
        for (x, pixel) in (x0..).zip(out) {
            let rgb: [u32; 3] = core::array::from_fn(|k| {
                let value = if planes[k].is_steep() {
                    exact_value_at(values.clone(), k, x, y)
                } else {
                    planes[k].value_at(x, y)
                };
                channel(value)
            });
            let threshold = self.dither.then(|| bayer_threshold(x, y));
            *pixel = C::from_channels(rgb, threshold);
        }
    }
}
