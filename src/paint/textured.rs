//! Perspective-correct texture mapping: each polygon's texture coordinates
//! interpolated as `u/w`, `v/w` and `1/w`, which are affine in screen space
//! and so are attribute planes like depth, then divided back.
//!
//! # Set-up (once per polygon)
//! The corners' coordinates are taken to texel units with
//! [`TEXEL_FRAC_BITS`] fractional bits and moved by the smallest, so each
//! is from 0 (`t_i`, at most `2^36`; a polygon whose corners share a
//! coordinate interpolates 0 exactly). Each
//! corner's weight is `q_i = floor(2^b · w_min / w_i)` ([`ClipW::ratio`]),
//! `b = min(23, 46 - bits(max t_i))`, so `q_i · t_i < 2^46`; the planes
//! interpolate `q`, `(t_u·q) >> s_u` and `(t_v·q) >> s_v`, each shift the
//! least that keeps `max t · 2^b`, a bound of the corner values, below
//! `2^24`
//! ([`VALUE_MAX`](crate::raster::attribute::VALUE_MAX)). At a pixel,
//! `t = floor((T << s) / Q)` with `T`, `Q` the planes' values there.
//!
//! A triangle thinner than a pixel whose values span most of that range
//! across it has steep planes (the whole range within a pixel), which
//! would be evaluated exactly at every pixel. Its `s_u`, `s_v` are raised
//! instead until neither plane is steep, where the coarser values cost at
//! most one more unit (`2^-8` texel) at any pixel, and only then: on
//! Spot at 240x240 about one painted triangle in fifteen.
//!
//! # Spans (the division, bounded)
//! A run of pixels is cut into spans of [`SPAN`] pixels or fewer (powers
//! of two); the coordinates are divided out exactly at the ends of each and
//! stepped linearly between. Along a row, `t(x) = (a + b·x) / (c + d·x)`
//! departs from its chord over a span by at most
//! `|Δt| · |ΔQ| / (4 · min Q)` (`Δ` over the span); a span whose bound
//! exceeds [`CHORD_TOLERANCE`] is halved, down to single pixels, which are
//! exact. So every pixel's coordinates are within
//! `CHORD_TOLERANCE + 1` units (`2^-8` texel) of the division of the
//! planes' values, which are themselves within the planes' stated error
//! (see [`crate::raster::attribute`]) of the exact `u/w`, `v/w`, `1/w`.

use core::marker::PhantomData;

use crate::arith::wide::cross;
use crate::front::clip_w::ClipW;
use crate::front::tex_coord::TexCoord;
use crate::paint::PaintMode;
use crate::paint::color::{PaintColor, bayer_threshold};
use crate::paint::texture::{
    Filter, TEXEL_FRAC_BITS, TEXEL_MAX, Texture, Wrap, channels as texel_channels,
    levels as texel_levels,
};
use crate::raster::attribute::{AttributePlane, attribute_planes, exact_value_at, triangle_planes};
use crate::raster::vertex::ScreenVertex;

/// The largest texel coordinate a pixel takes (`2^-8` texel, from its
/// polygon's smallest corner coordinate): beyond every corner's (`2^36`).
const COORDINATE_MAX: i64 = 1 << 40;

/// The longest span whose coordinates are stepped between two divisions.
pub const SPAN: usize = 16;

/// The largest error (units of `2^-8` texel) a span's linear steps may add
/// to its divided ends: `1/64` texel.
pub const CHORD_TOLERANCE: u64 = 4;

/// A textured polygon's planes: `1/w`, `u/w` and `v/w` (scaled; see the
/// module's notes) and what turns their quotients back into texels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TexturedPlanes {
    /// `q`, `u·q`, `v·q`.
    planes: [AttributePlane; 3],
    /// `s_u`, `s_v`.
    shifts: [u8; 2],
    /// What the interpolated coordinates are added to (`2^-8` texel): the
    /// smallest corner's, taken modulo the texture's size when it repeats.
    offset: [i64; 2],
}

/// A textured polygon's coordinates at one pixel: `u`, `v` in texel units
/// (`2^-8`, from the polygon's base) and the plane value `Q`.
#[derive(Debug, Clone, Copy)]
struct Point {
    t: [i64; 2],
    q: i64,
}

/// Perspective-correct texture mapping from a [`Texture`] into colours
/// `C`: nearest texels are copied exactly; bilinear blends are dithered
/// where `C` has fewer than 8 bits a channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Textured<'a, C> {
    texture: Texture<'a>,
    dither: bool,
    color: PhantomData<C>,
}

impl<'a, C: PaintColor> Textured<'a, C> {
    /// Texture mapping from `texture`, dithered when it blends
    /// ([`Filter::Bilinear`]) into a colour of fewer than 8 bits a
    /// channel.
    pub const fn new(texture: Texture<'a>) -> Self {
        let blends = matches!(texture.filter(), Filter::Bilinear);
        Self::with_dither(texture, blends && C::COARSE)
    }

    /// Texture mapping, dithered or not.
    pub const fn with_dither(texture: Texture<'a>, dither: bool) -> Self {
        Self {
            texture,
            dither,
            color: PhantomData,
        }
    }

    /// The texture.
    pub const fn texture(&self) -> &Texture<'a> {
        &self.texture
    }

    /// Whether it dithers.
    pub const fn dithers(&self) -> bool {
        self.dither
    }

    /// The coordinates at pixel `(x, y)` from the three plane values there
    /// (plane units).
    #[inline(always)]
    fn point(planes: &TexturedPlanes, [q, u, v]: [i64; 3]) -> Point {
        let q = q.max(1);
        let divide = |value: i64, shift: u8| {
            // value <= 2^41 and shift <= 22 (module notes): at most 2^63.
            // A quotient beyond any corner's (t < 2^36), where Q is near 0
            // at the edge of a polygon of extreme w ratio, is held at
            // COORDINATE_MAX, so sums and steps of coordinates stay far
            // inside i64.
            let value = value.clamp(0, 1 << 41) as u64;
            let quotient = (value << shift) / q as u64;
            quotient.min(COORDINATE_MAX as u64) as i64
        };
        Point {
            t: [divide(u, planes.shifts[0]), divide(v, planes.shifts[1])],
            q,
        }
    }

    /// The colour at texel coordinates `t` (`2^-8` texel, from the
    /// polygon's offset).
    #[inline(always)]
    fn color(&self, planes: &TexturedPlanes, t: [i64; 2], threshold: Option<u32>) -> C {
        let [u, v] = self.texel_position(planes, t);
        if threshold.is_none() && C::MAX == TEXEL_MAX && self.texture.filter() == Filter::Nearest {
            // A texel of the colour's own levels, undithered: the levels it
            // has (the channels' round trip gives them back, as the
            // texture's tests check for every texel).
            return C::from_levels(texel_levels(self.texture.nearest(u, v)));
        }
        C::from_channels(self.texture.sample(u, v), threshold)
    }

    /// The texel nearest texel coordinates `t` (`2^-8` texel, from the
    /// polygon's offset): by the texture's [`Texture::repeat_masks`]
    /// (`masks`) where it has them, else through [`Self::texel_position`].
    #[inline(always)]
    fn nearest_texel(&self, planes: &TexturedPlanes, t: [i64; 2], masks: Option<[u16; 2]>) -> u16 {
        match masks {
            Some(masks) => {
                let [du, dv] = planes.offset;
                self.texture.masked_nearest(masks, t[0] + du, t[1] + dv)
            }
            None => {
                let [u, v] = self.texel_position(planes, t);
                self.texture.nearest(u, v)
            }
        }
    }

    /// The texture's 8.8 channels at texel coordinates `t` (`2^-8` texel,
    /// from the polygon's offset), by its filter.
    #[inline(always)]
    pub(super) fn channels(&self, planes: &TexturedPlanes, t: [i64; 2]) -> [u32; 3] {
        if self.texture.filter() == Filter::Nearest {
            let masks = self.texture.repeat_masks();
            return texel_channels(self.nearest_texel(planes, t, masks));
        }
        let [u, v] = self.texel_position(planes, t);
        self.texture.sample(u, v)
    }

    /// Texel coordinates `t` (`2^-8` texel, from the polygon's offset) as
    /// the texture takes them: absolute, in `i32`.
    #[inline(always)]
    fn texel_position(&self, planes: &TexturedPlanes, t: [i64; 2]) -> [i32; 2] {
        let sizes = [self.texture.width(), self.texture.height()];
        core::array::from_fn(|a| {
            let c = t[a] + planes.offset[a];
            if let Ok(c) = i32::try_from(c) {
                return c;
            }
            // Far from the texture (a polygon across more than 2^23
            // texels): the coordinate that samples the same texels.
            let period = i64::from(sizes[a]) << TEXEL_FRAC_BITS;
            match self.texture.wrap() {
                Wrap::Repeat => c.rem_euclid(period) as i32,
                Wrap::Clamp => c.clamp(-period, 2 * period) as i32,
            }
        })
    }

    /// The plane values at pixel `(x, y)`, each steep plane's computed
    /// from the corners.
    fn values_at(
        planes: &TexturedPlanes,
        corners: impl Iterator<Item = (ScreenVertex, [u32; 3])> + Clone,
        x: u16,
        y: u16,
    ) -> [i64; 3] {
        core::array::from_fn(|k| {
            if planes.planes[k].is_steep() {
                exact_value_at(corners.clone(), k, x, y)
            } else {
                planes.planes[k].value_at(x, y)
            }
        })
    }
}

/// The corner values of a textured polygon and how they were scaled.
struct CornerValues {
    /// The smallest corner coordinates (`2^-8` texel).
    base: [i64; 2],
    bits: u32,
    shifts: [u32; 2],
    w_min: ClipW,
}

/// A corner's coordinates in texel units (`2^-8`): below `2^35` in
/// magnitude (`|uv| < 2^31`, sizes at most `2^12`).
#[inline]
fn texel_units(texture: &Texture<'_>, c: TexCoord) -> [i64; 2] {
    let sizes = [texture.width(), texture.height()];
    core::array::from_fn(|a| (i64::from(c.uv[a]) * i64::from(sizes[a])) >> (16 - TEXEL_FRAC_BITS))
}

impl CornerValues {
    /// Chosen from the corners (see the module's notes).
    fn new(texture: &Texture<'_>, corners: impl Iterator<Item = TexCoord> + Clone) -> Self {
        // The smallest `w` and coordinates, from the first corner on (no
        // `i64::MAX` start: the emulated RP2040, rp2040js 1.4.1, sets the
        // overflow flag wrongly when a 64-bit signed comparison's high word
        // is 0x7FFFFFFF, so `i64::MAX.min(t)` gave `i64::MAX` there).
        let mut w_min = ClipW::ONE;
        let mut base = [0i64; 2];
        for (k, c) in corners.clone().enumerate() {
            let t = texel_units(texture, c);
            if k == 0 {
                (w_min, base) = (c.w, t);
            } else {
                if c.w.at_most(w_min) {
                    w_min = c.w;
                }
                base = [base[0].min(t[0]), base[1].min(t[1])];
            }
        }
        let this = Self {
            base,
            bits: 23,
            shifts: [0; 2],
            w_min,
        };
        // The largest coordinate of each axis from the smallest.
        let mut ranges = [0u64; 2];
        for c in corners {
            let t = this.texels(texture, c);
            ranges = [ranges[0].max(t[0]), ranges[1].max(t[1])];
        }
        Self::from_parts(this.base, this.w_min, ranges)
    }

    /// The scaling of a polygon whose smallest coordinates are `base` and
    /// smallest `w` is `w_min`, its coordinates spanning `ranges` from
    /// `base` (see the module's notes).
    #[inline(always)]
    fn from_parts(base: [i64; 2], w_min: ClipW, ranges: [u64; 2]) -> Self {
        let bits_of = |v: u64| 64 - v.leading_zeros();
        let bits = 23.min(46u32.saturating_sub(bits_of(ranges[0].max(ranges[1]))));
        Self {
            base,
            bits,
            // Each `t·q` is below `2^(bits(range) + bits)` (`q <= 2^bits`):
            // the shift that brings that bound below `2^24` (no division
            // per corner to find the largest product itself).
            shifts: ranges.map(|r| (bits_of(r) + bits).saturating_sub(24)),
            w_min,
        }
    }

    /// A corner's coordinates from the smallest (`2^-8` texel, `< 2^36`).
    fn texels(&self, texture: &Texture<'_>, c: TexCoord) -> [u64; 2] {
        let t = texel_units(texture, c);
        core::array::from_fn(|a| (t[a] - self.base[a]).max(0) as u64)
    }

    /// A corner's plane values: `q`, `t_u·q >> s_u`, `t_v·q >> s_v`.
    fn values(&self, texture: &Texture<'_>, c: TexCoord) -> [u32; 3] {
        self.values_of(c.w, self.texels(texture, c))
    }

    /// The plane values of a corner whose `w` is `w` and whose coordinates
    /// from the smallest are `t` ([`Self::texels`]).
    #[inline(always)]
    fn values_of(&self, w: ClipW, t: [u64; 2]) -> [u32; 3] {
        let q = self.w_min.ratio(w, self.bits);
        [
            q,
            ((t[0] * u64::from(q)) >> self.shifts[0]) as u32,
            ((t[1] * u64::from(q)) >> self.shifts[1]) as u32,
        ]
    }
}

impl<C: PaintColor> PaintMode for Textured<'_, C> {
    type Source = TexCoord;
    type Vertex = TexCoord;
    type Row = ();
    type Planes = TexturedPlanes;
    type Color = C;
    const VERTEX_FILLER: TexCoord = TexCoord {
        uv: [0; 2],
        w: ClipW::ONE,
    };
    const PLANES_FILLER: TexturedPlanes = TexturedPlanes {
        planes: [AttributePlane::ZERO; 3],
        shifts: [0; 2],
        offset: [0; 2],
    };

    fn vertex(&self, source: TexCoord) -> TexCoord {
        source
    }

    fn planes(
        &self,
        corners: impl Iterator<Item = (ScreenVertex, TexCoord)> + Clone,
        width: u16,
        height: u16,
    ) -> TexturedPlanes {
        let mut three = corners.clone();
        if let (Some(a), Some(b), Some(c), None) =
            (three.next(), three.next(), three.next(), three.next())
            && let Some(planes) = self.triangle_planes([a, b, c])
        {
            return planes;
        }
        let scale = CornerValues::new(&self.texture, corners.clone().map(|(_, c)| c));
        let values = corners.map(|(v, c)| (v, scale.values(&self.texture, c)));
        TexturedPlanes {
            planes: attribute_planes(values, width, height).unwrap_or_default(),
            shifts: scale.shifts.map(|s| s as u8),
            offset: self.offset(scale.base),
        }
    }

    fn row(&self, _y: u16) {}

    fn paint_run<I: Iterator<Item = (ScreenVertex, TexCoord)> + Clone>(
        &self,
        _row: &(),
        planes: &TexturedPlanes,
        corners: impl Fn() -> I,
        x0: u16,
        y: u16,
        out: &mut [C],
    ) {
        if !self.dither && C::MAX == TEXEL_MAX && self.texture.filter() == Filter::Nearest {
            // Texels copied as they are: the decisions made once a run, so
            // that each pixel's closure is small enough to inline (a test
            // of `masks` a pixel cost Spot's frame 1 %).
            if let Some(masks) = self.texture.repeat_masks() {
                self.coordinates(planes, &corners, (x0, y), out.len(), |k, t| {
                    if let Some(pixel) = out.get_mut(k) {
                        let texel = self.nearest_texel(planes, t, Some(masks));
                        *pixel = C::from_levels(texel_levels(texel));
                    }
                });
                return;
            }
            self.coordinates(planes, &corners, (x0, y), out.len(), |k, t| {
                if let Some(pixel) = out.get_mut(k) {
                    let texel = self.nearest_texel(planes, t, None);
                    *pixel = C::from_levels(texel_levels(texel));
                }
            });
            return;
        }
        let threshold = |x: u16| self.dither.then(|| bayer_threshold(x, y));
        self.coordinates(planes, &corners, (x0, y), out.len(), |k, t| {
            if let Some(pixel) = out.get_mut(k) {
                *pixel = self.color(planes, t, threshold(x0.wrapping_add(k as u16)));
            }
        });
    }
}

impl<C: PaintColor> Textured<'_, C> {
    /// A triangle's planes as [`PaintMode::planes`] sets them up (the same
    /// values), each corner's coordinates computed once: `None` where the
    /// triangle set-up does not take it ([`triangle_planes`]), which the
    /// general set-up then does.
    #[inline(always)]
    fn triangle_planes(&self, corners: [(ScreenVertex, TexCoord); 3]) -> Option<TexturedPlanes> {
        let t = corners.map(|(_, c)| texel_units(&self.texture, c));
        let base: [i64; 2] = core::array::from_fn(|a| t[0][a].min(t[1][a]).min(t[2][a]));
        // The last corner of the smallest `w`, as `CornerValues::new` takes.
        let mut w_min = corners[0].1.w;
        for (_, c) in &corners[1..] {
            if c.w.at_most(w_min) {
                w_min = c.w;
            }
        }
        let texels = t.map(|t| [0, 1].map(|a| (t[a] - base[a]).max(0) as u64));
        let ranges: [u64; 2] =
            core::array::from_fn(|a| texels[0][a].max(texels[1][a]).max(texels[2][a]));
        let mut scale = CornerValues::from_parts(base, w_min, ranges);
        let corner = |k: usize| (corners[k].0, scale.values_of(corners[k].1.w, texels[k]));
        let planes = match triangle_planes(corner(0), corner(1), corner(2)) {
            Some(planes) => planes,
            None => coarser_planes(&mut scale, corners.map(|(v, c)| (v, c.w)), texels)?,
        };
        Some(TexturedPlanes {
            planes,
            shifts: scale.shifts.map(|s| s as u8),
            offset: self.offset(base),
        })
    }

    /// What a polygon's coordinates (from `base`, its smallest) are added
    /// to: `base` itself, or modulo the texture's size when it repeats (a
    /// mask when the size is a power of two).
    #[inline(always)]
    fn offset(&self, base: [i64; 2]) -> [i64; 2] {
        let sizes = [self.texture.width(), self.texture.height()];
        core::array::from_fn(|a| {
            let period = i64::from(sizes[a]) << TEXEL_FRAC_BITS;
            match self.texture.wrap() {
                Wrap::Repeat if sizes[a].is_power_of_two() => base[a] & (period - 1),
                Wrap::Repeat => base[a].rem_euclid(period),
                Wrap::Clamp => base[a],
            }
        })
    }

    /// The texel coordinates (from the polygon's base, `2^-8` texel) of
    /// the `n` pixels of row `y` from column `x0` on, given to `pixel` with
    /// each pixel's index in the run, in order: divided at the ends of
    /// spans and stepped between (the module's notes).
    #[inline(always)]
    pub(super) fn coordinates<I: Iterator<Item = (ScreenVertex, TexCoord)> + Clone>(
        &self,
        planes: &TexturedPlanes,
        corners: impl FnOnce() -> I,
        (x0, y): (u16, u16),
        n: usize,
        mut pixel: impl FnMut(usize, [i64; 2]),
    ) {
        if planes.planes.iter().any(AttributePlane::is_steep) {
            // The corners are looked up only here: most runs never ask.
            let corners = corners();
            let scale = CornerValues::new(&self.texture, corners.clone().map(|(_, c)| c));
            let values = corners.map(|(v, c)| (v, scale.values(&self.texture, c)));
            for k in 0..n {
                let x = x0.wrapping_add(k as u16);
                pixel(
                    k,
                    Self::point(planes, Self::values_at(planes, values.clone(), x, y)).t,
                );
            }
            return;
        }
        let [pq, pu, pv] = planes.planes;
        let at = |i: usize| {
            let x = x0.wrapping_add(i as u16);
            Self::point(planes, [pq, pu, pv].map(|p| p.value_at(x, y)))
        };
        let Some(last) = n.checked_sub(1) else {
            return;
        };
        let mut i = 0;
        let mut start = at(0);
        while i < last {
            let mut length = SPAN.min(1 << (usize::BITS - 1 - (last - i).leading_zeros()));
            let end = loop {
                let end = at(i + length);
                if length == 1 || chord_within_tolerance(&start, &end) {
                    break end;
                }
                length /= 2;
            };
            let log = length.trailing_zeros();
            // Coordinates below 2^26 at both ends are stepped in 32 bits
            // (every sum below 2^31): the same values as the 64-bit steps,
            // without a 64-bit product and shift a pixel on a 32-bit core.
            let small = |t: i64| (0..1 << 26).contains(&t);
            if start.t.iter().chain(&end.t).all(|&t| small(t)) {
                let step = [0, 1].map(|a| (end.t[a] - start.t[a]) as i32);
                let mut at = start.t.map(|t| (t as i32) << log);
                for k in 0..length {
                    pixel(i + k, at.map(|v| i64::from(v >> log)));
                    at = [at[0] + step[0], at[1] + step[1]];
                }
            } else {
                for k in 0..length {
                    let t: [i64; 2] = core::array::from_fn(|a| {
                        start.t[a] + (((end.t[a] - start.t[a]) * k as i64) >> log)
                    });
                    pixel(i + k, t);
                }
            }
            i += length;
            start = end;
        }
        pixel(last, start.t);
    }
}

/// The planes of a triangle the triangle set-up did not take at the
/// shifts of `scale` (corners: position and `w`; coordinates from the
/// smallest, `texels`): with coarser values where a thin triangle's
/// planes were steep and that costs at most a unit ([`coarser_shifts`],
/// whose shifts `scale` then takes); `None` otherwise. Out of line: few
/// triangles come here, and the usual set-up stays as compiled without it.
#[cold]
#[inline(never)]
fn coarser_planes(
    scale: &mut CornerValues,
    corners: [(ScreenVertex, ClipW); 3],
    texels: [[u64; 2]; 3],
) -> Option<[AttributePlane; 3]> {
    let values = |scale: &CornerValues| [0, 1, 2].map(|k| scale.values_of(corners[k].1, texels[k]));
    let positions = corners.map(|(v, _)| v);
    let shifts = coarser_shifts(positions, &values(scale), scale.shifts)?;
    scale.shifts = shifts;
    let values = values(scale);
    let corner = |k: usize| (positions[k], values[k]);
    triangle_planes(corner(0), corner(1), corner(2))
}

/// The shifts of a triangle's `u·q` and `v·q` planes (`shifts`, the
/// module's `s_u`, `s_v`) raised so that neither plane is steep, for a
/// triangle whose corners are `positions` and whose corner values at
/// those shifts are `values` (`q`, `u·q`, `v·q`); `None` where no raise
/// is needed, or where it would cost more than a unit (`2^-8` texel).
///
/// A plane's gradient is `-(a, b)/c` per sub-pixel step, with `c` twice
/// the triangle's area (sub-pixel units) and each of `|a|`, `|b|` at most
/// `V·E`, where `V` bounds its corner values (all from 0) and `E` is the
/// larger of `|p_x - o_x| + |q_x - o_x|` and the same in `y`. Raising a
/// shift by `e` takes each value to `value >> e` (the floor of a floor),
/// so below `2^(bits(V) - e)`; with `e >= bits(V) + bits(E) - 14 -
/// bits(c)` each gradient is at most `2^15` values a sub-pixel step,
/// `2^23` a pixel: half the whole range in one pixel (a steep plane's),
/// with room for the gradient's rounding. A value step of `u·q` is
/// `2^s / Q` of a coordinate unit at a pixel whose `1/w` value is `Q`
/// (at least the smallest corner's `q`); the raise is taken only while
/// `3 · 2^(s + e)` is at most that `q`, so the values' rounding costs at
/// most a unit more than the module's bound.
fn coarser_shifts(
    positions: [ScreenVertex; 3],
    values: &[[u32; 3]; 3],
    shifts: [u32; 2],
) -> Option<[u32; 2]> {
    let bits = |v: u64| 64 - v.leading_zeros();
    let [o, p, q] = positions;
    // Inside the guard band each difference is below 2^23.
    let (px, py, qx, qy) = (p.x - o.x, p.y - o.y, q.x - o.x, q.y - o.y);
    let c = cross(px, py, qx, qy).unsigned_abs();
    let extent = u64::from(
        (px.unsigned_abs() + qx.unsigned_abs()).max(py.unsigned_abs() + qy.unsigned_abs()),
    );
    // Corners within 2^16 sub-pixel steps of `o`, or the triangle set-up
    // does not take it anyway.
    if c == 0 || extent >= 1 << 17 {
        return None;
    }
    let q_min = values.iter().map(|v| v[0]).min().unwrap_or(0);
    let raised: [u32; 2] = core::array::from_fn(|a| {
        let top = values.iter().map(|v| v[a + 1]).max().unwrap_or(0);
        let e = (bits(u64::from(top)) + bits(extent)).saturating_sub(14 + bits(c));
        shifts[a] + e
    });
    let raises = raised != shifts;
    let costs_a_unit_at_most = raised
        .iter()
        .all(|&s| s < 32 && 3u64 << s <= u64::from(q_min));
    (raises && costs_a_unit_at_most).then_some(raised)
}

/// Whether the coordinates stepped linearly from `a` to `b` stay within
/// [`CHORD_TOLERANCE`] of their exact (divided) values: `|Δt| · |ΔQ| <=
/// 4 · tolerance · min Q` (the module's notes).
#[inline(always)]
fn chord_within_tolerance(a: &Point, b: &Point) -> bool {
    let dt = (b.t[0] - a.t[0])
        .unsigned_abs()
        .max((b.t[1] - a.t[1]).unsigned_abs());
    let dq = (b.q - a.q).unsigned_abs();
    let min_q = a.q.min(b.q) as u64;
    u128::from(dt) * u128::from(dq) <= u128::from(4 * CHORD_TOLERANCE) * u128::from(min_q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::tex_coord::UV_ONE;
    use crate::limits::{HALF_PIXEL, SUBPIXEL_STEPS};
    use crate::paint::sample_inside;
    use embedded_graphics_core::pixelcolor::Rgb565;
    use proptest::prelude::*;
    use std::vec;
    use std::vec::Vec;

    /// The exact perspective-correct texel coordinates (units of `2^-8`
    /// texel, absolute) of a triangle at pixel `(x, y)`'s sample.
    fn exact(
        corners: &[(ScreenVertex, TexCoord, f64); 3],
        size: [u16; 2],
        x: u16,
        y: u16,
    ) -> [f64; 2] {
        let (px, py) = (
            f64::from(i32::from(x) * SUBPIXEL_STEPS + HALF_PIXEL),
            f64::from(i32::from(y) * SUBPIXEL_STEPS + HALF_PIXEL),
        );
        let p = |k: usize| (f64::from(corners[k].0.x), f64::from(corners[k].0.y));
        let ((x0, y0), (x1, y1), (x2, y2)) = (p(0), p(1), p(2));
        let area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        let l1 = ((px - x0) * (y2 - y0) - (x2 - x0) * (py - y0)) / area;
        let l2 = ((x1 - x0) * (py - y0) - (px - x0) * (y1 - y0)) / area;
        let l = [1.0 - l1 - l2, l1, l2];
        let inv_w: f64 = (0..3).map(|k| l[k] / corners[k].2).sum();
        core::array::from_fn(|a| {
            let t: f64 = (0..3)
                .map(|k| l[k] * f64::from(corners[k].1.uv[a]) / corners[k].2)
                .sum::<f64>()
                / inv_w;
            t * f64::from(size[a]) / f64::from(UV_ONE) * 256.0
        })
    }

    /// The largest error, in `2^-8` texel, of any pixel's coordinates
    /// against the exact ones over the samples the triangle covers, and
    /// the module's bound for the triangle.
    fn largest_error(corners: [(ScreenVertex, TexCoord, f64); 3], size: [u16; 2]) -> (f64, f64) {
        let texels = vec![0u16; usize::from(size[0]) * usize::from(size[1])];
        let texture = Texture::new(&texels, size[0], size[1]).unwrap();
        let mode = Textured::<Rgb565>::new(texture);
        let values = corners.map(|(v, c, _)| (v, c));
        let planes = mode.planes(values.iter().copied(), 64, 64);
        let scale = CornerValues::new(&texture, values.iter().map(|&(_, c)| c));
        let texel_range = (0..2)
            .map(|a| {
                let t = values.map(|(_, c)| scale.texels(&texture, c)[a]);
                t.iter().max().unwrap() - t.iter().min().unwrap()
            })
            .max()
            .unwrap();
        let q_min = values
            .iter()
            .map(|&(_, c)| scale.w_min.ratio(c.w, scale.bits))
            .min()
            .unwrap();
        // A unit more where a thin triangle's values were made coarser.
        let coarser = planes.shifts != scale.shifts.map(|s| s as u8);
        let bound = (CHORD_TOLERANCE + 2 + u64::from(coarser)) as f64
            + 3.0 * texel_range as f64 / f64::from(q_min);
        let mut worst = 0.0f64;
        for y in 0..64u16 {
            // The row's samples inside the triangle.
            let inside: Vec<u16> = (0..64u16)
                .filter(|&x| sample_inside([corners[0].0, corners[1].0, corners[2].0], x, y))
                .collect();
            let (Some(&first), Some(&last)) = (inside.first(), inside.last()) else {
                continue;
            };
            let n = usize::from(last - first) + 1;
            mode.coordinates(
                &planes,
                || values.iter().copied(),
                (first, y),
                n,
                |k, t| {
                    let x = first + k as u16;
                    let want = exact(&corners, size, x, y);
                    for a in 0..2 {
                        let got = (t[a] + planes.offset[a]) as f64;
                        let moved = (want[a] - got).abs();
                        // Compare modulo the base's whole repeats.
                        let period = f64::from(size[a]) * 256.0;
                        let err = moved - (moved / period).round() * period;
                        worst = worst.max(err.abs());
                    }
                },
            );
        }
        (worst, bound)
    }

    fn corner(x: i32, y: i32, uv: [i32; 2], w: f32) -> (ScreenVertex, TexCoord, f64) {
        (
            ScreenVertex::new(x, y, 0).unwrap(),
            TexCoord {
                uv,
                w: ClipW::from_f32(w),
            },
            f64::from(w),
        )
    }

    /// A floor seen at a grazing angle (`w` from 1 to 50 across it): the
    /// coordinates stay within the stated bound, and spans were halved to
    /// get there (a fixed 16-pixel span would miss it).
    #[test]
    fn a_grazing_floor_stays_within_the_bound() {
        const S: i32 = SUBPIXEL_STEPS;
        let corners = [
            corner(0, 0, [0, 0], 50.0),
            corner(64 * S, 2 * S, [8 * UV_ONE, 0], 50.0),
            corner(10 * S, 60 * S, [0, 8 * UV_ONE], 1.0),
        ];
        let (error, bound) = largest_error(corners, [256, 256]);
        assert!(error <= bound, "{error} > {bound}");
    }

    /// A sliver a tenth of a pixel thick whose coordinates span 16 texels
    /// each way: its planes are stepped (with coarser values), not
    /// evaluated exactly at each pixel, and within the bound; one whose
    /// coordinates span the whole texture would lose more than a unit so,
    /// and stays exact.
    #[test]
    fn a_sliver_is_stepped_within_the_bound() {
        const S: i32 = SUBPIXEL_STEPS;
        let sliver = |span: i32| {
            [
                corner(2 * S, 2 * S, [0, 0], 1.0),
                corner(40 * S, 6 * S, [span, 0], 1.5),
                corner(2 * S + S / 10, 2 * S + S / 10, [0, span], 1.2),
            ]
        };
        let texels = vec![0u16; 256 * 256];
        let texture = Texture::new(&texels, 256, 256).unwrap();
        for (span, stepped) in [(UV_ONE / 16, true), (UV_ONE, false)] {
            let corners = sliver(span);
            let values = corners.map(|(v, c, _)| (v, c));
            let planes = Textured::<Rgb565>::new(texture).planes(values.iter().copied(), 64, 64);
            assert_eq!(!planes.planes.iter().any(AttributePlane::is_steep), stepped);
            let (error, bound) = largest_error(corners, [256, 256]);
            assert!(error <= bound, "{error} > {bound}");
        }
    }

    /// The proptests' check: the triangle of these corners (sub-pixel
    /// positions, coordinates, `w`) on a texture of `size` keeps every
    /// covered pixel within the bound.
    fn within_the_bound(
        xy: [(i32, i32); 3],
        uv: [[i32; 2]; 3],
        w: [f32; 3],
        size: (u16, u16),
    ) -> Result<(), TestCaseError> {
        let corners = core::array::from_fn(|k| corner(xy[k].0, xy[k].1, uv[k], w[k]));
        let (error, bound) = largest_error(corners, [size.0, size.1]);
        prop_assert!(error <= bound, "{} > {}", error, bound);
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]
        /// Triangles of at most two pixels each way, coordinates over
        /// many repeats: every covered pixel within the bound, the
        /// thinnest stepped with coarser values.
        #[test]
        fn small_triangles_are_within_the_bound(
            xy in prop::array::uniform3((30 * SUBPIXEL_STEPS..32 * SUBPIXEL_STEPS, 30 * SUBPIXEL_STEPS..32 * SUBPIXEL_STEPS)),
            uv in prop::array::uniform3(prop::array::uniform2(-300 * UV_ONE..300 * UV_ONE)),
            w in prop::array::uniform3(0.01f32..100.0),
            size in (1u16..=1024, 1u16..=1024),
        ) {
            within_the_bound(xy, uv, w, size)?;
        }

        /// Random triangles with random coordinates (up to a few hundred
        /// repeats) and `w` over four decades: every covered pixel's
        /// coordinates within the module's bound of exact.
        #[test]
        fn coordinates_are_within_the_bound(
            xy in prop::array::uniform3((0..64 * SUBPIXEL_STEPS, 0..64 * SUBPIXEL_STEPS)),
            uv in prop::array::uniform3(prop::array::uniform2(-300 * UV_ONE..300 * UV_ONE)),
            w in prop::array::uniform3(0.01f32..100.0),
            size in (1u16..=1024, 1u16..=1024),
        ) {
            within_the_bound(xy, uv, w, size)?;
        }
    }
}
