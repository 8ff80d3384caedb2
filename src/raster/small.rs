//! Small triangles' coverage: a triangle at most [`LANES`] sample columns
//! wide and less than [`MAX_ROWS`] pixels tall is drawn from a coverage
//! mask per row, made from its edge functions when it is activated,
//! instead of from two stepped edges.
//!
//! A mesh seen small (the bunny at 800x600: 62,000 triangles, most of
//! them covering one to four pixels on two or three rows) is mostly such
//! triangles. Its edges would cost each a division to start, a step a row
//! and a span a row; its masks cost a few additions a sample of its box,
//! and each covered sample is written on its own. Its depths are the
//! stepped triangle's, from the same plane set-up stepped the same way
//! (its entry in the active polygon table holds both, the masks where a
//! stepped triangle keeps its lower corners), so the rows are the stepped
//! triangle's, bit for bit: a target may take either path
//! ([`SMALL_TRIANGLES`]), and the tests compare the two.
//!
//! **Coverage.** Each edge's function `E = A·x + B·y + C`, signed so that
//! the inside is positive, is evaluated at the samples of the triangle's
//! box. A sample is covered when every function is positive, or zero on
//! an edge that is a left edge (`A > 0`) or a top edge (`A = 0`, `B >
//! 0`): the top-left rule, which gives exactly the samples the stepped
//! edges give (the tests compare the two, and the even-odd sample test,
//! on random and degenerate triangles). The tie is folded into the value
//! (`F = E - 1` on a right or bottom edge), so the test is the sign of
//! `F0 | F1 | F2`. Row `i` of the box is [`LANES`] bits of one mask.
//!
//! # Ranges
//! A small triangle's corners lie less than 5 px apart in x (at most
//! [`LANES`] sample columns) and less than [`MAX_ROWS`] = 4 px in y:
//!
//! | quantity | bound | held in |
//! |---|---|---|
//! | an edge's `dx` / `dy` (sub-pixel) | `< 2^11` / `< 2^10` | `i32` |
//! | a box sample's offset from a corner, in x / in y | `< 2^11` / `< 2^10 + 2^8` | `i32` |
//! | an edge function `E`, `F` at the box's samples | `< 2^11·2^10.4 + 2^10·2^11 < 2^22.3` | `i32` |
//! | its steps per column and per row, `256·A`, `256·B` | `< 2^19` | `i32` |

use crate::limits::{HALF_PIXEL, SUBPIXEL_STEPS};
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::vertex::ScreenVertex;

/// Whether small triangles are drawn from coverage masks: on every target
/// but 32-bit Arm. A host pays for each division and for each
/// mispredicted branch of a stepped edge's set-up and span; a Cortex-M0+,
/// which predicts nothing and whose stepped edges avoid its library
/// division, draws small triangles from stepped edges in fewer
/// instructions (`cargo qemu`: the torus knot took 0.8 % more with masks).
/// The rows are the same either way.
pub(crate) const SMALL_TRIANGLES: bool = !cfg!(target_arch = "arm");

/// Most sample columns a small triangle spans: one row's coverage is this
/// many bits of its masks.
pub(crate) const LANES: usize = 4;

/// A small triangle is less than this many pixels tall, so it covers at
/// most this many rows (the ranges above depend on it): its masks fill
/// 16 bits.
pub(crate) const MAX_ROWS: usize = 4;

/// The samples a small triangle covers, row by row from the current one,
/// in two words (an active polygon table entry's, see
/// [`Self::from_words`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SmallCoverage {
    /// Bit `k` of the `i`-th group of [`LANES`] bits: the sample of column
    /// `column0 + k` on the row `i` below the current one.
    masks: u16,
    /// First column of the lanes.
    pub column0: u16,
}

/// One edge's biased function at a sample, and its steps per column and
/// per row (see [`edge_function`]).
type EdgeFunction = (i32, i32, i32);

/// The biased edge function of the edge `p → q` at sample `(xs, ys)`, its
/// steps per column and per row, all signed by `sign` (the inside
/// positive): `F = E - 1` on a right or bottom edge, so that a sample is
/// covered where all three are at least 0.
#[inline(always)]
fn edge_function(
    p: ScreenVertex,
    q: ScreenVertex,
    (xs, ys): (i32, i32),
    sign: i32,
) -> EdgeFunction {
    let (dx, dy) = ((q.x - p.x) * sign, (q.y - p.y) * sign);
    // E = dx·(ys - p.y) - dy·(xs - p.x): A = -dy, B = dx. Left (A > 0) or
    // top (A = 0, B > 0) edges are inclusive.
    let e = dx * (ys - p.y) - dy * (xs - p.x);
    let inclusive = (dy < 0) | ((dy == 0) & (dx > 0));
    (
        e + i32::from(inclusive) - 1,
        -dy * SUBPIXEL_STEPS,
        dx * SUBPIXEL_STEPS,
    )
}

impl SmallCoverage {
    /// The samples triangle `a b c` covers on `rows` rows from `row` (the
    /// rows of its box it may cover from the one it is activated on; at
    /// most [`MAX_ROWS`] are looked at) of a frame `width` pixels wide;
    /// `None` unless it is small (see the module's notes), has area and
    /// has a sample column in the frame.
    #[inline(always)]
    pub fn new([a, b, c]: [ScreenVertex; 3], row: u16, rows: u16, width: u16) -> Option<Self> {
        let first = first_sample_at_or_after(a.x.min(b.x).min(c.x));
        let end = first_sample_at_or_after(a.x.max(b.x).max(c.x));
        let height = a.y.max(b.y).max(c.y) - a.y.min(b.y).min(c.y);
        if end - first > LANES as i32 || height >= MAX_ROWS as i32 * SUBPIXEL_STEPS {
            return None;
        }
        // Every difference below is of corners less than 5 px apart in x
        // and 4 px in y: see the ranges.
        let twice_area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        let column0 = first.max(0);
        let columns = end.min(i32::from(width)) - column0;
        if twice_area == 0 || columns <= 0 {
            // No area, or no sample column in the frame (the tables leave
            // both out): for the latter the lanes' first column would lie
            // outside the box, and the ranges with it.
            return None;
        }
        let sign = if twice_area > 0 { 1 } else { -1 };
        let sample = (
            column0 * SUBPIXEL_STEPS + HALF_PIXEL,
            i32::from(row) * SUBPIXEL_STEPS + HALF_PIXEL,
        );
        let masks = coverage(
            [
                edge_function(a, b, sample, sign),
                edge_function(b, c, sample, sign),
                edge_function(c, a, sample, sign),
            ],
            columns as u32,
            usize::from(rows).min(MAX_ROWS),
        );
        Some(Self {
            masks,
            column0: column0 as u16,
        })
    }

    /// The coverage kept as two words ([`Self::to_words`]).
    #[inline(always)]
    pub fn from_words([masks, column0]: [u16; 2]) -> Self {
        Self { masks, column0 }
    }

    /// The coverage as two words.
    #[inline(always)]
    pub fn to_words(self) -> [u16; 2] {
        [self.masks, self.column0]
    }

    /// The covered samples of the current row: bit `k` for column
    /// `column0 + k`.
    #[inline(always)]
    pub fn row_mask(&self) -> u32 {
        u32::from(self.masks) & ((1 << LANES) - 1)
    }

    /// Whether it covers no sample below the current row.
    #[inline(always)]
    pub fn is_last_row(&self) -> bool {
        self.masks >> LANES == 0
    }

    /// Whether it covers no sample at all from the current row on.
    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.masks == 0
    }

    /// Steps to the next row.
    #[inline(always)]
    pub fn next_row(&mut self) {
        self.masks >>= LANES;
    }
}

/// The coverage of `rows` rows of `columns` samples (at most [`MAX_ROWS`]
/// and [`LANES`]), from the three edge functions at the first sample: row
/// `i`'s mask in bits `LANES·i..LANES·(i + 1)`. Every row tests all
/// [`LANES`] lanes, with no branch, and keeps the first `columns`.
#[inline(always)]
fn coverage(edges: [EdgeFunction; 3], columns: u32, rows: usize) -> u16 {
    let [(mut f0, x0, y0), (mut f1, x1, y1), (mut f2, x2, y2)] = edges;
    let lanes = (1 << columns) - 1;
    let mut masks = 0u16;
    for i in 0..rows {
        let mut mask = 0u16;
        for k in 0..LANES as i32 {
            let any_negative = (f0 + k * x0) | (f1 + k * x1) | (f2 + k * x2);
            mask |= u16::from(any_negative >= 0) << k;
        }
        masks |= (mask & lanes) << (LANES * i);
        (f0, f1, f2) = (f0 + y0, f1 + y1, f2 + y2);
    }
    masks
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::vertex::TriangleTest;

    fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        }
    }

    /// Checks a small triangle's masks against the sample test on every
    /// row of its box; returns the samples it covers, or `None` when it is
    /// not small.
    fn check(corners: [ScreenVertex; 3], width: u16) -> Option<u32> {
        let [a, b, c] = corners;
        let first_row = first_sample_at_or_after(a.y.min(b.y).min(c.y)).max(0);
        let end_row = first_sample_at_or_after(a.y.max(b.y).max(c.y));
        if end_row <= first_row {
            return None;
        }
        let rows = (end_row - first_row) as u16;
        let mut small = SmallCoverage::new(corners, first_row as u16, rows, width)?;
        let test = TriangleTest::new(a, b, c);
        let mut covered = 0;
        for row in first_row..end_row {
            let mask = small.row_mask();
            for k in 0..u32::BITS {
                let column = i32::from(small.column0) + k as i32;
                let want =
                    k < LANES as u32 && column < i32::from(width) && test.covers_pixel(column, row);
                assert_eq!(
                    mask >> k & 1 == 1,
                    want,
                    "{corners:?}: row {row}, column {column}"
                );
                covered += u32::from(want);
            }
            assert_eq!(small.is_last_row(), small.masks >> LANES == 0);
            small.next_row();
        }
        assert!(small.is_empty());
        Some(covered)
    }

    /// Random small triangles, some on coarse grids (corners on samples,
    /// horizontal and vertical edges, shared columns), some off the frame's
    /// left side: the covered samples are the sample test's.
    #[test]
    fn coverage_is_the_sample_tests() {
        let mut next = xorshift(0x1234_5678_9abc_def1);
        let (mut small, mut covered) = (0, 0);
        for round in 0..300_000 {
            let grid = [1, 128, 64][round % 3];
            let mut corner = || {
                let x = -700 + (next() % (256 * LANES as u64 + 900)) as i32;
                let y = -300 + (next() % (256 * MAX_ROWS as u64 + 200)) as i32;
                ScreenVertex {
                    x: x / grid * grid,
                    y: y / grid * grid,
                    z: 0,
                }
            };
            let corners = [corner(), corner(), corner()];
            if let Some(n) = check(corners, [64, 5, 3][round % 3]) {
                small += 1;
                covered += n;
            }
        }
        assert!(small > 50_000 && covered > 50_000, "{small} {covered}");
    }

    /// Triangles at the size limits.
    #[test]
    fn the_largest_small_triangles() {
        let (lanes, rows) = (LANES as i32, MAX_ROWS as i32);
        let w = lanes * 256 + 127;
        let h = rows * 256 - 1;
        for (a, b, c) in [
            ((0, 0), (w, 0), (0, h)),
            ((w, h), (0, h), (w, 0)),
            ((128, 128), (127 + lanes * 256, 128 + h), (128, 128 + h)),
            ((5, 0), (128 + lanes * 256, h / 2), (5, h)),
        ] {
            let v = |(x, y): (i32, i32)| ScreenVertex { x, y, z: 0 };
            let n = check([v(a), v(b), v(c)], 64).expect("small");
            assert!(n >= (lanes * rows / 2 - 2) as u32, "{n}");
        }
        // Just too wide, too tall.
        let v = |x: i32, y: i32| ScreenVertex { x, y, z: 0 };
        let small = |corners| SmallCoverage::new(corners, 0, 9, 64);
        assert!(small([v(0, 0), v((lanes + 1) * 256, 0), v(0, 256)]).is_none());
        assert!(small([v(0, 0), v(256, 0), v(0, rows * 256)]).is_none());
    }

    use crate::raster::depth::{Depth16, Depth24, DepthFormat};
    use crate::raster::scan::{ScanArrays, ScanParts, ScanStorage, Scanner, scan_small_as};
    use crate::raster::tables::{TableArrays, Tables};
    use crate::sink::FnSink;
    use proptest::prelude::*;
    use std::vec::Vec;

    /// A scanner's storage whose small triangles' table holds at most
    /// `.1` entries: the others wait in the active polygon table.
    struct SmallRoom<S>(S, usize);

    impl<S: ScanStorage> ScanStorage for SmallRoom<S> {
        type Color = S::Color;
        type Depth = S::Depth;

        fn parts_mut(&mut self) -> ScanParts<'_, S::Color, S::Depth> {
            let mut parts = self.0.parts_mut();
            let room = self.1.min(parts.small.len());
            parts.small = &mut core::mem::take(&mut parts.small)[..room];
            parts
        }
    }

    /// The rows (colours as face keys, depths) of `scene` on a `width` x
    /// `height` frame, rows `band` only, small triangles drawn from masks
    /// (waiting in a table of their own of `small_room` entries, then in
    /// the active polygon table) or from stepped edges.
    fn rows<D: DepthFormat>(
        scene: &[[ScreenVertex; 3]],
        (width, height): (u16, u16),
        band: core::ops::Range<u16>,
        (small, small_room): (bool, usize),
    ) -> Vec<(u16, Vec<u32>, Vec<D::Value>)> {
        let mut tables =
            Tables::new(TableArrays::<u32, 192, 64, 192>::new(0), width, height).expect("size");
        for (k, corners) in scene.iter().enumerate() {
            let ids = corners.map(|v| tables.push_vertex(v).expect("vertex"));
            tables.push_polygon(&ids, k as u32 + 1).expect("polygon");
        }
        let prepared = tables.prepare();
        let storage = SmallRoom(ScanArrays::<u32, D, 48, 64, 8>::new(0), small_room);
        let mut scanner = Scanner::new(storage, 0);
        let mut out = Vec::new();
        let mut sink = FnSink(|y: u16, colors: &[u32], depths: &[D::Value]| {
            out.push((y, colors.to_vec(), depths.to_vec()));
            Ok::<(), ()>(())
        });
        scan_small_as(&prepared, &mut scanner, band, small, &mut sink).expect("scan");
        out
    }

    /// The two scans' rows are the same (the first pixel that differs,
    /// if not).
    fn same<Z: PartialEq + core::fmt::Debug>(
        masks: Vec<(u16, Vec<u32>, Vec<Z>)>,
        edges: Vec<(u16, Vec<u32>, Vec<Z>)>,
    ) -> Result<(), TestCaseError> {
        prop_assert_eq!(masks.len(), edges.len());
        for ((y, colors, depths), (_, want_colors, want_depths)) in masks.iter().zip(&edges) {
            for x in 0..colors.len() {
                prop_assert_eq!(
                    (colors[x], &depths[x]),
                    (want_colors[x], &want_depths[x]),
                    "row {}, column {}",
                    y,
                    x
                );
            }
        }
        Ok(())
    }

    fn corner() -> impl Strategy<Value = ScreenVertex> {
        // Depths anywhere, near both ends of the range often: triangles in
        // range take the masks, the others their edges.
        let depth = prop_oneof![0u32..1 << 24, 0u32..600, (1u32 << 24) - 600..1 << 24,];
        (-300i32..48 * 256 + 300, -300i32..40 * 256 + 300, depth)
            .prop_map(|(x, y, z)| ScreenVertex { x, y, z })
    }

    /// A triangle of the scene: small ones mostly (around a corner, within
    /// a few pixels), some large, some on a coarse grid.
    fn triangle() -> impl Strategy<Value = [ScreenVertex; 3]> {
        (
            corner(),
            (-1400i32..1400, -2200i32..2200, 0u32..1 << 24),
            (-1400i32..1400, -2200i32..2200, 0u32..1 << 24),
            0u32..4,
            prop::bool::ANY,
        )
            .prop_map(|(a, (bx, by, bz), (cx, cy, cz), grid, large)| {
                let scale = if large { 8 } else { 1 };
                let snap = |v: i32| if grid == 0 { v / 64 * 64 } else { v };
                let at = |dx: i32, dy: i32, z: u32| ScreenVertex {
                    x: snap(a.x + dx * scale),
                    y: snap(a.y + dy * scale),
                    z: if grid == 1 { a.z } else { z },
                };
                [a, at(bx, by, bz), at(cx, cy, cz)]
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// Small triangles drawn from their masks give the rows the
        /// stepped edges give, to the bit (colour and depth), in both
        /// formats, whole frames and bands that start inside triangles,
        /// whether they wait in their own table, in the active polygon
        /// table, or some in each (a table of `room` entries).
        #[test]
        fn masks_draw_the_rows_edges_draw(
            scene in prop::collection::vec(triangle(), 1..40),
            cut in 0u16..40,
            room in 0usize..4,
        ) {
            let size = (48, 40);
            for band in [0..40, cut..40, 0..cut] {
                for room in [64, 0, room] {
                    same(
                        rows::<Depth16>(&scene, size, band.clone(), (true, room)),
                        rows::<Depth16>(&scene, size, band.clone(), (false, room)),
                    )?;
                    same(
                        rows::<Depth24>(&scene, size, band.clone(), (true, room)),
                        rows::<Depth24>(&scene, size, band.clone(), (false, room)),
                    )?;
                }
            }
        }
    }
}
