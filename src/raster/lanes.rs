//! The span loop without branches, for processors that predict them.
//!
//! Most spans are short (at 800x600 the duck's frame fills 50,777 spans
//! and shows 79,680 pixels, the bunny's 124,902 and 82,008). A loop over
//! such a span ends after a different number of pixels each time, and a
//! depth test with no culling goes either way, so a processor that
//! predicts branches (any host) mispredicts about once a span, and more
//! often in the test. Here a span is filled in blocks of [`LANES`]
//! pixels: every pixel of a block is computed, tested and written back,
//! with the depth test and the span's end as selects
//! (`core::hint::select_unpredictable`), so a span of up to [`LANES`]
//! pixels takes no data-dependent branch at all. A pixel past the span's
//! end, or one whose test fails, is written back unchanged. (Blocks of 4,
//! or a block of 4 for spans of up to 4 and of 8 for longer ones, measured
//! slower in the peers bench.)
//!
//! The depths are the scalar loop's, from the same accumulator stepped the
//! same way, and the write rule is the same, so the row comes out
//! identical bit for bit (tested against the scalar loop below, and across
//! targets by the firmware runs, whose frames are compared with the
//! host's). A Cortex-M0+ has no branch predictor and keeps the scalar loop
//! ([`BRANCH_FREE`](super::BRANCH_FREE)).

use super::depth::DepthFormat;

/// Pixels per block.
pub(crate) const LANES: usize = 8;

/// A block's pixels in the three rows.
pub(crate) type Block<'r, C, V> = (&'r mut [V; LANES], &'r mut [u32; LANES], &'r mut [C; LANES]);

/// The block starting at pixel `first` of the depth, key and colour rows,
/// if each holds `LANES` pixels from there.
#[inline(always)]
pub(crate) fn block<'r, C, V>(
    depths: &'r mut [V],
    keys: &'r mut [u32],
    colors: &'r mut [C],
    first: usize,
) -> Option<Block<'r, C, V>> {
    let end = first.checked_add(LANES)?;
    Some((
        depths.get_mut(first..end)?.try_into().ok()?,
        keys.get_mut(first..end)?.try_into().ok()?,
        colors.get_mut(first..end)?.try_into().ok()?,
    ))
}

/// Tests and writes the first `left.min(LANES)` pixels of a block as the
/// scanline's span loop does (nearer, or as near and added first), the
/// first with the accumulator `acc`, each next one step on; the other
/// pixels stay as they were.
///
/// The three rows come as three arguments, not one struct: the compiler
/// knows that arguments do not overlap, and only then keeps the block in
/// registers (with the rows in one struct, zline's frames in the peers
/// bench took about 20 % longer).
#[inline(always)]
pub(crate) fn fill_block<C: Copy, D: DepthFormat>(
    depths: &mut [D::Value; LANES],
    keys: &mut [u32; LANES],
    colors: &mut [C; LANES],
    left: usize,
    (key, color): (u32, C),
    (acc, lane_steps): (D::Accum, &[D::Accum; LANES]),
) {
    use core::hint::select_unpredictable as select;
    for k in 0..LANES {
        let depth = D::value(D::advance(acc, lane_steps[k]));
        let stored = depths[k];
        // `&` and `|`, not `&&` and `||`: no branch.
        let wins = (k < left)
            & ((depth < stored) | ((depth == stored) & (depth != D::CLEAR) & (key < keys[k])));
        depths[k] = select(wins, depth, stored);
        keys[k] = select(wins, key, keys[k]);
        colors[k] = select(wins, color, colors[k]);
    }
}

/// `k · step` for each lane `k`, as the accumulator's wrapping steps
/// make it: lane `k` of a block is the block's first accumulator advanced
/// by `lane_steps[k]`, the same value as `k` advances one after another,
/// and every lane's depth is computed at once.
#[inline(always)]
pub(crate) fn lane_steps<D: DepthFormat>(step: D::Accum) -> [D::Accum; LANES] {
    let mut steps = [D::Accum::from(0); LANES];
    for k in 1..LANES {
        steps[k] = D::advance(steps[k - 1], step);
    }
    steps
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::depth::{Depth16, Depth24};
    use proptest::prelude::*;

    /// The scalar span loop's rule, pixel by pixel: the reference.
    fn fill_scalar<D: DepthFormat>(
        rows: (&mut [D::Value], &mut [u32], &mut [u16]),
        (key, color): (u32, u16),
        (mut acc, step): (D::Accum, D::Accum),
    ) {
        let (depths, keys, colors) = rows;
        for ((stored, stored_key), pixel) in depths.iter_mut().zip(keys).zip(colors) {
            let depth = D::value(acc);
            if depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key) {
                (*stored, *stored_key, *pixel) = (depth, key, color);
            }
            acc = D::advance(acc, step);
        }
    }

    /// A block equals the scalar loop over its first `left` pixels and
    /// leaves the rest as it was.
    fn check<D: DepthFormat>(
        stored: [D::Value; LANES],
        keys: [u32; LANES],
        left: usize,
        pixel: (u32, u16),
        accumulator: (D::Accum, D::Accum),
    ) -> Result<(), TestCaseError> {
        let colors: [u16; LANES] = core::array::from_fn(|k| 100 + k as u16);
        let (mut d, mut k, mut c) = (stored, keys, colors);
        fill_block::<u16, D>(
            &mut d,
            &mut k,
            &mut c,
            left,
            pixel,
            (accumulator.0, &lane_steps::<D>(accumulator.1)),
        );
        let (mut want_d, mut want_k, mut want_c) = (stored, keys, colors);
        let n = left.min(LANES);
        fill_scalar::<D>(
            (&mut want_d[..n], &mut want_k[..n], &mut want_c[..n]),
            pixel,
            accumulator,
        );
        prop_assert_eq!((d, k, c), (want_d, want_k, want_c));
        Ok(())
    }

    proptest! {
        /// 16-bit depth: stored depths near the span's own (ties, the
        /// clear value), keys either side of the polygon's, every length.
        #[test]
        fn blocks_equal_the_scalar_loop_z16(
            near in proptest::array::uniform8(0u16..4),
            far in proptest::array::uniform8(proptest::bool::ANY),
            keys in proptest::array::uniform8(0u32..6),
            left in 0usize..12, key in 0u32..6,
            top in 0u16..=u16::MAX, step in -3i32..=3,
        ) {
            // The accumulator at the first pixel gives depth `top`; each
            // pixel moves by `step` units of depth (plus a fraction).
            let acc = (u32::from(top) << 16) as i32;
            let step = (step << 16) + 0x1234;
            let stored = core::array::from_fn(|k| {
                if far[k] { u16::MAX } else { top.saturating_add(near[k]).saturating_sub(2) }
            });
            check::<Depth16>(stored, keys, left, (key, 7), (acc, step))?;
        }

        /// 24-bit depth, the same cases.
        #[test]
        fn blocks_equal_the_scalar_loop_z24(
            near in proptest::array::uniform8(0u32..4),
            far in proptest::array::uniform8(proptest::bool::ANY),
            keys in proptest::array::uniform8(0u32..6),
            left in 0usize..12, key in 0u32..6,
            top in 0u32..1 << 24, step in -3i64..=3,
        ) {
            let acc = i64::from(top) << 32;
            let step = (step << 32) + 0x1234_5678;
            let stored = core::array::from_fn(|k| {
                if far[k] { Depth24::CLEAR } else { (top + near[k]).saturating_sub(2) }
            });
            check::<Depth24>(stored, keys, left, (key, 7), (acc, step))?;
        }
    }

    #[test]
    fn a_block_of_a_short_span_writes_only_its_pixels() {
        let (mut d, mut k, mut c) = ([u16::MAX; LANES], [0u32; LANES], [0u16; LANES]);
        fill_block::<u16, Depth16>(
            &mut d,
            &mut k,
            &mut c,
            3,
            (5, 9),
            (10 << 16, &lane_steps::<Depth16>(1 << 16)),
        );
        assert_eq!(
            d,
            [10, 11, 12, u16::MAX, u16::MAX, u16::MAX, u16::MAX, u16::MAX]
        );
        assert_eq!(k, [5, 5, 5, 0, 0, 0, 0, 0]);
        assert_eq!(c, [9, 9, 9, 0, 0, 0, 0, 0]);
    }
}
