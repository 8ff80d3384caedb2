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
/// scanline's span loop does (nearer, or as near and added first), pixel
/// `k` with the accumulator `lanes[k]` (see [`Lanes`]); the other pixels
/// stay as they were. Keys are a polygon's (at most
/// [`MAX_POLYGONS`](crate::limits::MAX_POLYGONS)) and the stored depths
/// the format's (at most `DEPTH_MAX`).
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
    lanes: &[D::Accum; LANES],
) {
    use core::hint::select_unpredictable as select;
    // Which lanes the span reaches, as bits: one mask for the block, not a
    // comparison of `left` per lane (on x86-64, eight scalar comparisons
    // gathered into a vector).
    let in_span: u32 = if left >= LANES { 0xff } else { (1 << left) - 1 };
    // Signed 32-bit comparisons: stored depths are below 2^24 and keys
    // below 2^21 ([`MAX_POLYGONS`](crate::limits::MAX_POLYGONS) plus one),
    // so each orders as its unsigned self, and SSE2 compares signed words
    // in one instruction (an unsigned comparison takes a bias each side).
    let (key, clear) = (key as i32, D::ordered(D::CLEAR));
    for k in 0..LANES {
        let value = D::value(lanes[k]);
        let (depth, stored) = (D::ordered(value), D::ordered(depths[k]));
        // `&` and `|`, not `&&` and `||`: no branch. (Where the two are
        // equal, the stored depth is tested against the clear value: a
        // word of the row, not a lane's accumulator narrowed again.)
        let wins = (in_span & (1 << k) != 0)
            & ((depth < stored) | ((depth == stored) & (stored != clear) & (key < keys[k] as i32)));
        depths[k] = select(wins, value, depths[k]);
        keys[k] = select(wins, key as u32, keys[k]);
        colors[k] = select(wins, color, colors[k]);
    }
}

/// A span's accumulators lane by lane: lane `k` of the block in hand
/// holds the accumulator of its pixel `k`, the value `k` advances one
/// after another would give (the advances wrap, so adding their sum once
/// is the same), and [`Lanes::next_block`] moves every lane on by
/// [`LANES`] pixels at once. Every lane's depth is then computed together,
/// and nothing a lane needs is recomputed from the span's first pixel.
pub(crate) struct Lanes<D: DepthFormat> {
    /// Each lane's accumulator in the block in hand.
    pub accumulators: [D::Accum; LANES],
    /// `LANES · step`.
    block_step: D::Accum,
}

impl<D: DepthFormat> Lanes<D> {
    /// The lanes of a block whose first pixel has the accumulator `acc`,
    /// stepping `step` a pixel.
    #[inline(always)]
    pub(crate) fn new(acc: D::Accum, step: D::Accum) -> Self {
        let mut accumulators = [acc; LANES];
        for k in 1..LANES {
            accumulators[k] = D::advance(accumulators[k - 1], step);
        }
        let mut block_step = D::Accum::from(0);
        for _ in 0..LANES {
            block_step = D::advance(block_step, step);
        }
        Self {
            accumulators,
            block_step,
        }
    }

    /// Moves every lane on to the next block.
    #[inline(always)]
    pub(crate) fn next_block(&mut self) {
        for lane in &mut self.accumulators {
            *lane = D::advance(*lane, self.block_step);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::MAX_POLYGONS;
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
            &Lanes::<D>::new(accumulator.0, accumulator.1).accumulators,
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

    /// Where the keys of a case start: at 0, or near the largest key (a
    /// table's last polygon, `MAX_POLYGONS`), which the block compares as
    /// a signed word.
    fn base(high: bool) -> u32 {
        if high { MAX_POLYGONS as u32 - 5 } else { 0 }
    }

    proptest! {
        /// 16-bit depth: stored depths near the span's own (ties, the
        /// clear value, often a span at the clear value itself), keys
        /// either side of the polygon's (small, or near the largest), every
        /// length.
        #[test]
        fn blocks_equal_the_scalar_loop_z16(
            near in proptest::array::uniform8(0u16..4),
            far in proptest::array::uniform8(proptest::bool::ANY),
            keys in proptest::array::uniform8(0u32..6),
            left in 0usize..12, key in 0u32..6, high in proptest::bool::ANY,
            top in prop_oneof![0u16..=u16::MAX, u16::MAX - 3..=u16::MAX], step in -3i32..=3,
        ) {
            // The accumulator at the first pixel gives depth `top`; each
            // pixel moves by `step` units of depth (plus a fraction).
            let acc = (u32::from(top) << 16) as i32;
            let step = (step << 16) + 0x1234;
            let stored = core::array::from_fn(|k| {
                if far[k] { u16::MAX } else { top.saturating_add(near[k]).saturating_sub(2) }
            });
            let (keys, key) = (keys.map(|k| k + base(high)), key + base(high));
            check::<Depth16>(stored, keys, left, (key, 7), (acc, step))?;
        }

        /// 24-bit depth, the same cases.
        #[test]
        fn blocks_equal_the_scalar_loop_z24(
            near in proptest::array::uniform8(0u32..4),
            far in proptest::array::uniform8(proptest::bool::ANY),
            keys in proptest::array::uniform8(0u32..6),
            left in 0usize..12, key in 0u32..6, high in proptest::bool::ANY,
            top in prop_oneof![0u32..1 << 24, (1u32 << 24) - 4..1 << 24], step in -3i64..=3,
        ) {
            let acc = i64::from(top) << 32;
            let step = (step << 32) + 0x1234_5678;
            let stored = core::array::from_fn(|k| {
                if far[k] { Depth24::CLEAR } else { (top + near[k]).saturating_sub(2) }
            });
            let (keys, key) = (keys.map(|k| k + base(high)), key + base(high));
            check::<Depth24>(stored, keys, left, (key, 7), (acc, step))?;
        }
    }

    /// Lane `k` of block `n` holds the accumulator `LANES·n + k` advances
    /// one after another give, wrapping included.
    fn lanes_follow_the_scalar_steps<D: DepthFormat>(
        acc: D::Accum,
        step: D::Accum,
        blocks: usize,
    ) -> Result<(), TestCaseError>
    where
        D::Accum: PartialEq + core::fmt::Debug,
    {
        let mut lanes = Lanes::<D>::new(acc, step);
        let mut scalar = acc;
        for n in 0..blocks {
            if n > 0 {
                lanes.next_block();
            }
            for k in 0..LANES {
                prop_assert_eq!(lanes.accumulators[k], scalar);
                scalar = D::advance(scalar, step);
            }
        }
        Ok(())
    }

    proptest! {
        /// Any accumulator and step of 16-bit depth, past the ends.
        #[test]
        fn lanes_step_as_the_scalar_loop_z16(acc in any::<i32>(), step in any::<i32>(), blocks in 1usize..6) {
            lanes_follow_the_scalar_steps::<Depth16>(acc, step, blocks)?;
        }

        /// Any accumulator and step of 24-bit depth, past the ends.
        #[test]
        fn lanes_step_as_the_scalar_loop_z24(acc in any::<i64>(), step in any::<i64>(), blocks in 1usize..6) {
            lanes_follow_the_scalar_steps::<Depth24>(acc, step, blocks)?;
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
            &Lanes::<Depth16>::new(10 << 16, 1 << 16).accumulators,
        );
        assert_eq!(
            d,
            [10, 11, 12, u16::MAX, u16::MAX, u16::MAX, u16::MAX, u16::MAX]
        );
        assert_eq!(k, [5, 5, 5, 0, 0, 0, 0, 0]);
        assert_eq!(c, [9, 9, 9, 0, 0, 0, 0, 0]);
    }
}
