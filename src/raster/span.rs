//! Span filling: the row being built (depth, colour and tie-break key per
//! pixel, [`RowBuffers`]) and the loops that depth-test and write a span
//! of a polygon into it, by the scanline's rule or the other methods'
//! ([`PixelWrite`]).

use crate::arith::ARMV6M;
use crate::arith::wide::mul_i64_small;
use crate::raster::BRANCH_FREE;
use crate::raster::depth::DepthFormat;
use crate::raster::lanes::{LANES, Lanes, block, fill_block};
use crate::raster::plane::Plane;
use crate::raster::small::SmallCoverage;

/// The row being built: depth, colour and tie-break key per pixel.
pub(crate) struct RowBuffers<'a, C, D: DepthFormat> {
    pub depth: &'a mut [D::Value],
    pub color: &'a mut [C],
    pub key: &'a mut [u32],
    /// How a covered pixel is written: the scanline's test, or the other
    /// methods' ([`crate::raster::zbuffer`]).
    pub write: PixelWrite,
}

impl<C: Copy, D: DepthFormat> RowBuffers<'_, C, D> {
    /// Fills pixels `[start, end)` (clamped to the row) of a triangle that
    /// stays in range (see [`IN_RANGE`]): depths from the accumulator,
    /// placed at the first pixel from the row's column-0 value
    /// ([`DepthFormat::accumulator_at`]), with no range check, no rounding
    /// and no call per span, on a host in branch-free blocks
    /// ([`crate::raster::lanes`]); whether any pixel was in the row. (With
    /// the `profile` feature it is kept out of line: the profile's "spans"
    /// stage.) With `SCANLINE` the caller knows the row is written by the
    /// scanline's rule, and the row's rule is not looked at. A shared
    /// plane's span at z24 comes here too, its accumulator from
    /// [`DepthFormat::span`] ([`Self::fill_shared`]).
    ///
    /// [`IN_RANGE`]: crate::raster::depth::IN_RANGE
    #[cfg_attr(feature = "profile", inline(never))]
    #[cfg_attr(not(feature = "profile"), inline(always))]
    pub(super) fn fill_in_range<const SCANLINE: bool>(
        &mut self,
        start: i32,
        end: i32,
        key: u32,
        color: C,
        accumulator_at: impl FnOnce(i32) -> (D::Accum, D::Accum),
    ) -> bool {
        let width = self.depth.len() as i32;
        let (start, end) = (start.max(0), end.min(width));
        if start >= end {
            return false;
        }
        let (first, last) = (start as usize, end as usize);
        let (mut acc, step) = accumulator_at(start);
        if !SCANLINE && self.write.in_effect() != PixelWrite::NearerOrFirstAdded {
            // The other methods' rules, out of line: the scanline's span
            // loop stays as it was.
            let (depths, colors) = (&mut self.depth[first..last], &mut self.color[first..last]);
            other_rule_in_range::<C, D>(depths, colors, color, (acc, step), self.write.in_effect());
            return true;
        }
        let mut first = first;
        if BRANCH_FREE {
            // Blocks while the row holds one from `first` (see `lanes`);
            // the scalar loop below finishes a span near the row's end.
            let mut lanes = Lanes::<D>::new(acc, step);
            while let Some((depths, keys, colors)) = block(self.depth, self.key, self.color, first)
            {
                fill_block::<C, D>(
                    depths,
                    keys,
                    colors,
                    last - first,
                    (key, color),
                    &lanes.accumulators,
                );
                first += LANES;
                if first >= last {
                    return true;
                }
                lanes.next_block();
            }
            acc = lanes.accumulators[0];
        }
        if ARMV6M {
            // Zipped iterators: on a Cortex-M0+ (the RP2040's firmware)
            // the indexed loop below took 0.07 % more cycles a frame.
            let (depths, keys, colors) = (
                &mut self.depth[first..last],
                &mut self.key[first..last],
                &mut self.color[first..last],
            );
            for ((stored, stored_key), pixel) in depths.iter_mut().zip(keys).zip(colors) {
                let depth = D::value(acc);
                if depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key) {
                    *stored = depth;
                    *stored_key = key;
                    *pixel = color;
                }
                acc = D::advance(acc, step);
            }
            return true;
        }
        // Indexed, over slices of one length: on a Cortex-M4F a pixel
        // that wins takes 13 instructions instead of 14 (`cargo qemu-m4f`:
        // 21,480 fewer a frame of the torus knot).
        let depths = &mut self.depth[first..last];
        let n = depths.len();
        let (keys, colors) = (
            &mut self.key[first..first + n],
            &mut self.color[first..first + n],
        );
        for i in 0..n {
            let depth = D::value(acc);
            let stored = depths[i];
            if depth < stored || (depth == stored && depth != D::CLEAR && key < keys[i]) {
                depths[i] = depth;
                keys[i] = key;
                colors[i] = color;
            }
            acc = D::advance(acc, step);
        }
        true
    }

    /// Depth-tests and writes the samples a small triangle covers on this
    /// row, by the row's write rule, each sample's depth from the
    /// accumulator at its column (`accumulator_at`, as a span starting
    /// there would take it); whether it covered any.
    #[inline(always)]
    pub(super) fn fill_lanes(
        &mut self,
        coverage: &SmallCoverage,
        key: u32,
        color: C,
        accumulator_at: impl Fn(i32) -> (D::Accum, D::Accum),
    ) -> bool {
        let mut mask = coverage.row_mask();
        if mask == 0 {
            return false;
        }
        let column0 = usize::from(coverage.column0);
        while mask != 0 {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let x = column0 + k;
            let (Some(stored), Some(stored_key), Some(pixel)) = (
                self.depth.get_mut(x),
                self.key.get_mut(x),
                self.color.get_mut(x),
            ) else {
                break;
            };
            let depth = D::value(accumulator_at(x as i32).0);
            let wins = match self.write.in_effect() {
                PixelWrite::NearerOrFirstAdded => {
                    depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key)
                }
                PixelWrite::Nearer => depth < *stored,
                PixelWrite::Overwrite => true,
            };
            if wins {
                (*stored, *stored_key, *pixel) = (depth, key, color);
            }
        }
        true
    }

    /// Fills pixels `[start, end)` (clamped to the row) of a polygon with a
    /// shared plane: depths from `row_value + dz_dx · x`, each rounded on
    /// its own ([`SpanDepth::Shared`]); whether any pixel was in the row.
    /// Out of line: shared planes are rare, and the other fills stay as
    /// they are.
    ///
    /// [`SpanDepth::Shared`]: crate::raster::active::SpanDepth::Shared
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn fill_shared(
        &mut self,
        start: i32,
        end: i32,
        key: u32,
        color: C,
        row_value: i64,
        dz_dx: i64,
    ) -> bool {
        let width = self.depth.len() as i32;
        let (start, end) = (start.clamp(0, width), end.clamp(0, width));
        if start >= end {
            return false;
        }
        // |dz_dx| < 2^40, start < 2^12, |row_value| < 2^57: no overflow.
        let value = row_value + mul_i64_small(dz_dx, start);
        if BRANCH_FREE
            && D::EXACT_SPAN
            && self.write.in_effect() == PixelWrite::NearerOrFirstAdded
            && let Some(accumulator) = D::span(value, dz_dx, (end - start) as u32)
        {
            // Every pixel's rounding, stepped exactly: the blocks of the
            // scanline's span loop, with the same depths.
            return self.fill_in_range::<true>(start, end, key, color, |_| accumulator);
        }
        let range = start as usize..end as usize;
        let slices = (
            &mut self.depth[range.clone()],
            &mut self.color[range.clone()],
            &mut self.key[range],
        );
        let pixel = (key, color);
        match self.write.in_effect() {
            PixelWrite::NearerOrFirstAdded => {
                round_each_pixel::<C, D, NEARER_OR_FIRST_ADDED>(slices, value, dz_dx, pixel)
            }
            PixelWrite::Nearer => round_each_pixel::<C, D, NEARER>(slices, value, dz_dx, pixel),
            PixelWrite::Overwrite => {
                round_each_pixel::<C, D, OVERWRITE>(slices, value, dz_dx, pixel)
            }
        }
        true
    }

    /// Fills pixels `[start, end)` (clamped to the row) of a polygon with
    /// `key` and `color`, depths from `source`; whether any pixel was in
    /// the row. (With the `profile` feature it is kept out of line: the
    /// profile's "spans" stage.)
    #[cfg_attr(feature = "profile", inline(never))]
    pub(super) fn fill(
        &mut self,
        start: i32,
        end: i32,
        key: u32,
        color: C,
        source: &SpanSource,
    ) -> bool {
        let width = self.depth.len() as i32;
        let (start, end) = (start.clamp(0, width), end.clamp(0, width));
        if start >= end {
            return false;
        }
        let range = start as usize..end as usize;
        let (depths, colors, keys) = (
            &mut self.depth[range.clone()],
            &mut self.color[range.clone()],
            &mut self.key[range],
        );
        if self.write.in_effect() == PixelWrite::NearerOrFirstAdded {
            fill_span::<C, D, NEARER_OR_FIRST_ADDED>(
                depths,
                colors,
                keys,
                start,
                (key, color),
                source,
            );
        } else {
            // The other methods' rules, out of line: one copy of the span
            // loops per rule, so no pixel tests it, and the scanline's
            // stays as it was.
            other_rule_span::<C, D>(
                depths,
                colors,
                keys,
                start,
                (key, color),
                source,
                self.write.in_effect(),
            );
        }
        true
    }
}

/// How a covered pixel is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(not(feature = "zbuffer"), allow(dead_code))]
pub(crate) enum PixelWrite {
    /// Where nearer, or equally near and added earlier (the key row): the
    /// scanline z-buffer, whatever order its polygons are scanned in.
    NearerOrFirstAdded,
    /// Where strictly nearer: the z-buffer, drawing in the order polygons
    /// were added, so the first drawn keeps a tie.
    Nearer,
    /// Always: the painter's pass.
    Overwrite,
}

impl PixelWrite {
    /// The rule the span loops take: this one, or without the `zbuffer`
    /// feature (whose methods alone write by the other rules) always the
    /// scanline's, so that the other rules' loops are left out of the code.
    #[inline(always)]
    fn in_effect(self) -> Self {
        if cfg!(feature = "zbuffer") {
            self
        } else {
            PixelWrite::NearerOrFirstAdded
        }
    }
}

/// [`RowBuffers::fill_in_range`] for [`PixelWrite::Nearer`] and
/// [`PixelWrite::Overwrite`] (the z-buffer and the painter's pass).
#[inline(never)]
fn other_rule_in_range<C: Copy, D: DepthFormat>(
    depths: &mut [D::Value],
    colors: &mut [C],
    color: C,
    (mut acc, step): (D::Accum, D::Accum),
    write: PixelWrite,
) {
    if write == PixelWrite::Overwrite {
        for (stored, pixel) in depths.iter_mut().zip(colors) {
            (*stored, *pixel) = (D::value(acc), color);
            acc = D::advance(acc, step);
        }
    } else {
        for (stored, pixel) in depths.iter_mut().zip(colors) {
            let depth = D::value(acc);
            if depth < *stored {
                (*stored, *pixel) = (depth, color);
            }
            acc = D::advance(acc, step);
        }
    }
}

/// `fill_span` for [`PixelWrite::Nearer`] and [`PixelWrite::Overwrite`].
#[inline(never)]
fn other_rule_span<C: Copy, D: DepthFormat>(
    depths: &mut [D::Value],
    colors: &mut [C],
    keys: &mut [u32],
    x0: i32,
    pixel: (u32, C),
    source: &SpanSource,
    write: PixelWrite,
) {
    if write == PixelWrite::Overwrite {
        fill_span::<C, D, OVERWRITE>(depths, colors, keys, x0, pixel, source);
    } else {
        fill_span::<C, D, NEARER>(depths, colors, keys, x0, pixel, source);
    }
}

/// [`PixelWrite`]s as `fill_span`'s constant parameter.
const NEARER_OR_FIRST_ADDED: u8 = 0;
const NEARER: u8 = 1;
const OVERWRITE: u8 = 2;

/// Spans of at most this many pixels round each pixel's plane value; longer
/// ones step the depth format's accumulator.
const SHORT_SPAN: u32 = 4;

/// Where a span's depths come from.
pub(super) enum SpanSource {
    /// From the row's plane value at column 0 and the gradient; with the
    /// accumulator step when the polygon is known to stay in range.
    Stepped {
        dz_dx: i64,
        row_value: i64,
        accumulator: Option<i64>,
    },
    /// Exactly from the plane, at each pixel of the row.
    Exact(Plane, u16),
}

/// The span loop of [`RowBuffers::fill_shared`]: each pixel's plane
/// value, from `value` stepping by `dz_dx`, rounded on its own, so the
/// stored depth never depends on where the span starts.
///
/// Its write rule is `fill_span`'s, written out again on purpose: routing
/// both loops through one helper changed the Cortex-M0+ code of the hot
/// span loop (boxes, z24: 4,320,920 to 4,453,920 instructions under
/// `cargo qemu`).
#[inline]
fn round_each_pixel<C: Copy, D: DepthFormat, const MODE: u8>(
    (depths, colors, keys): (&mut [D::Value], &mut [C], &mut [u32]),
    mut value: i64,
    dz_dx: i64,
    (key, color): (u32, C),
) {
    let pixels = depths
        .iter_mut()
        .zip(keys.iter_mut())
        .zip(colors.iter_mut());
    for ((stored, stored_key), pixel) in pixels {
        let depth = D::quantize(value);
        let wins = match MODE {
            NEARER_OR_FIRST_ADDED => {
                depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key)
            }
            NEARER => depth < *stored,
            _ => true,
        };
        if wins {
            (*stored, *stored_key, *pixel) = (depth, key, color);
        }
        value += dz_dx;
    }
}

/// Depth-tests and writes one span: pixels `x0 .. x0 + depths.len()`. A
/// pixel is written when its depth is nearer than the row holds, or equal
/// with a smaller key (the polygon added first).
#[inline(always)]
fn fill_span<C: Copy, D: DepthFormat, const MODE: u8>(
    depths: &mut [D::Value],
    colors: &mut [C],
    keys: &mut [u32],
    x0: i32,
    (key, color): (u32, C),
    source: &SpanSource,
) {
    let write = |depth: D::Value, stored: &mut D::Value, stored_key: &mut u32, pixel: &mut C| {
        let wins = match MODE {
            NEARER_OR_FIRST_ADDED => {
                depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key)
            }
            NEARER => depth < *stored,
            _ => true,
        };
        if wins {
            *stored = depth;
            *stored_key = key;
            *pixel = color;
        }
    };
    let len = depths.len() as u32;
    let pixels = depths
        .iter_mut()
        .zip(keys.iter_mut())
        .zip(colors.iter_mut());
    match *source {
        SpanSource::Stepped {
            dz_dx,
            row_value,
            accumulator: Some(step),
        } => {
            // In range (checked once per polygon): the accumulator, with
            // no range check and no rounding per pixel, placed at the plane
            // value of the span's first pixel (|dz_dx| < 2^40, x0 < 2^12).
            let start = row_value + dz_dx * i64::from(x0);
            let (mut acc, step) = D::accumulator_at(start, dz_dx, step, 0);
            for ((stored, stored_key), pixel) in pixels {
                write(D::value(acc), stored, stored_key, pixel);
                acc = D::advance(acc, step);
            }
        }
        SpanSource::Stepped {
            dz_dx, row_value, ..
        } => {
            // Re-evaluated from the plane at every span start: the error
            // is the gradient's rounding times the distance from the
            // polygon's anchor column (see `Plane::row_start`), never drift
            // from earlier spans. |dz_dx| < 2^40 (steeper polygons are
            // `Exact`), x0 < 2^12 and |row_value| < 2^57: no overflow.
            let start = row_value + dz_dx * i64::from(x0);
            if len <= SHORT_SPAN {
                // A few pixels: rounding each plane value costs less than
                // setting up the accumulator.
                let mut value = start;
                for ((stored, stored_key), pixel) in pixels {
                    write(D::quantize(value), stored, stored_key, pixel);
                    value += dz_dx;
                }
            } else if let Some((mut acc, step)) = D::span(start, dz_dx, len) {
                for ((stored, stored_key), pixel) in pixels {
                    write(D::value(acc), stored, stored_key, pixel);
                    acc = D::advance(acc, step);
                }
            } else {
                let mut value = start;
                for ((stored, stored_key), pixel) in pixels {
                    write(D::quantize(value), stored, stored_key, pixel);
                    value = value.saturating_add(dz_dx);
                }
            }
        }
        SpanSource::Exact(plane, row) => {
            for (k, ((stored, stored_key), pixel)) in pixels.enumerate() {
                let value = plane.value_at_pixel(x0 + k as i32, i32::from(row));
                write(D::quantize(value), stored, stored_key, pixel);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::{DEPTH_MAX, MAX_POLYGONS};
    use crate::raster::depth::{Depth16, Depth24};
    use proptest::prelude::*;
    use std::vec::Vec;

    /// A row of 40 pixels after `fill_shared` of the span `[start, end)`
    /// with the plane values `row_value + dz_dx·x`, and after the
    /// reference (each pixel's value rounded on its own, the scanline's
    /// rule): they are the same.
    fn shared_span_is_each_pixel_rounded<D: DepthFormat>(
        stored: Vec<D::Value>,
        keys: Vec<u32>,
        (start, end): (i32, i32),
        (row_value, dz_dx): (i64, i64),
        key: u32,
    ) -> Result<(), TestCaseError> {
        let width = stored.len() as i32;
        let colors: Vec<u16> = (0..width as u16).collect();
        let (mut depth, mut key_row, mut color) = (stored.clone(), keys.clone(), colors.clone());
        let mut rows = RowBuffers::<u16, D> {
            depth: &mut depth,
            color: &mut color,
            key: &mut key_row,
            write: PixelWrite::NearerOrFirstAdded,
        };
        rows.fill_shared(start, end, key, 999, row_value, dz_dx);
        let (mut want_depth, mut want_keys, mut want_colors) = (stored, keys, colors);
        let (first, last) = (start.clamp(0, width), end.clamp(0, width));
        if first < last {
            let range = first as usize..last as usize;
            round_each_pixel::<u16, D, NEARER_OR_FIRST_ADDED>(
                (
                    &mut want_depth[range.clone()],
                    &mut want_colors[range.clone()],
                    &mut want_keys[range],
                ),
                row_value + dz_dx * i64::from(first),
                dz_dx,
                (key, 999),
            );
        }
        prop_assert_eq!(
            (depth, key_row, color),
            (want_depth, want_keys, want_colors)
        );
        Ok(())
    }

    /// A case: plane values around depth `top` at some column (often at
    /// either end of the range, where a span may leave it), gradients of
    /// up to 16 depth steps a pixel, and for each of the row's 40 pixels a
    /// stored depth at or next to the span's own (`-1..=1` from it) or
    /// clear, and a key either side of the span's (small, or near the
    /// largest); spans that start and end outside the row.
    #[allow(clippy::type_complexity)]
    fn case() -> impl Strategy<Value = ([i64; 2], Vec<i8>, Vec<bool>, Vec<u32>, u32, (i32, i32))> {
        let top = prop_oneof![
            0i64..1 << 24,
            0i64..4,
            i64::from(DEPTH_MAX) - 3..=i64::from(DEPTH_MAX)
        ];
        (
            (top, 0i64..1 << 16, -(1i64 << 20)..1 << 20),
            0i32..40,
            prop::collection::vec(-1i8..=1, 40),
            prop::collection::vec(proptest::bool::weighted(0.2), 40),
            prop::collection::vec(0u32..4, 40),
            (0u32..4, proptest::bool::ANY),
            (-3i32..43, 0i32..30),
        )
            .prop_map(
                |((top, fraction, dz_dx), at, near, clear, keys, (key, high), (start, len))| {
                    let row_value = (top << 16) + fraction - dz_dx * i64::from(at);
                    let base = if high { MAX_POLYGONS as u32 - 4 } else { 0 };
                    (
                        [row_value, dz_dx],
                        near,
                        clear,
                        keys.iter().map(|k| k + base).collect(),
                        key + base,
                        (start, start + len),
                    )
                },
            )
    }

    proptest! {
        /// Shared planes' spans store each pixel's own rounding, in both
        /// formats (24-bit depth steps them in blocks where the span is in
        /// range).
        #[test]
        fn shared_spans_round_each_pixel(
            ([row_value, dz_dx], near, clear, keys, key, span) in case()
        ) {
            let stored16 = (0..40)
                .map(|x| {
                    let own = i64::from(Depth16::quantize(row_value + dz_dx * x as i64));
                    if clear[x] { u16::MAX } else { (own + i64::from(near[x])).clamp(0, 0xffff) as u16 }
                })
                .collect();
            shared_span_is_each_pixel_rounded::<Depth16>(stored16, keys.clone(), span, (row_value, dz_dx), key)?;
            let stored24 = (0..40)
                .map(|x| {
                    let own = i64::from(Depth24::quantize(row_value + dz_dx * x as i64));
                    if clear[x] {
                        DEPTH_MAX
                    } else {
                        (own + i64::from(near[x])).clamp(0, i64::from(DEPTH_MAX)) as u32
                    }
                })
                .collect();
            shared_span_is_each_pixel_rounded::<Depth24>(stored24, keys, span, (row_value, dz_dx), key)?;
        }
    }
}
