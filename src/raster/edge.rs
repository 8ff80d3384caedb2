//! Edges: the edge-table entry and the exact incremental stepping of an
//! active edge from one scanline to the next.
//!
//! An edge covers the rows whose sample line `yc = row + 0.5` satisfies
//! `y_top <= yc < y_bottom` (top inclusive, bottom exclusive). On each of
//! those rows it stores `x`: the first pixel whose sample point lies at or to
//! the right of the crossing. A span between a left crossing `xl` and a
//! right crossing `xr` then covers pixels `x(xl) .. x(xr)`: samples exactly
//! on a left edge are inside, exactly on a right edge outside. That is the
//! top-left fill rule, applied exactly on the sub-pixel grid, so two
//! polygons sharing an edge cover each pixel along it exactly once.
//!
//! Stepping is exact rational arithmetic (a Bresenham-style DDA): with
//! `N = x·D - r` and `0 <= r < D`, the crossing never drifts, so the edge
//! lands on the same pixels however many rows it is stepped.
//!
//! # Ranges
//! For every edge the API accepts (ends inside the guard band, `|x|, |y| <
//! 2^21` sub-pixel steps) and every row it covers:
//!
//! | quantity | bound | held in |
//! |---|---|---|
//! | `dx`, `dy` | `|dx| < 2^22`, `0 < dy < 2^22` | `i32` |
//! | `den = 256·dy` | `< 2^30` | `i32` |
//! | set-up numerator `s·dy + (y_sample - y_top)·dx`, `s = (x_top - 128) mod 256` (the whole pixels `(x_top - 128) div 256` are added after the division) | `< 2^30 + 2^44` (`0 <= y_sample - y_top < dy`); `< 2^31` when `dy, abs(dx) < 2^15` | `i64`; `i32` when `dy, abs(dx) < 2^15` |
//! | on the first row (`0 <= along = y_sample - y_top < 256`): `a = s + along·step` | `< 2^30 + 2^8` | `i32` |
//! | and `n = dy·(a mod 256) + along·(dx mod dy)` | `[0, 510·dy)`, so `< 2^31` | `i32` |
//! | crossing `x` (pixels) | `|x| <= 2^13 + 1` | `i32` |
//! | `remainder`, `step_remainder` | `[0, den)` | `i32` |
//! | `remainder - step_remainder` while stepping | `(-2^30, 2^30)` | `i32` |
//! | `step = floor(dx / dy)` | `|step| < 2^22` | `i32` |
//!
//! The tests below step edges between the guard band's corners over every
//! row they cover and compare each crossing with the exact `i128` value.

use crate::arith::divide::DIVISION_IS_CHEAP;
use crate::limits::{HALF_PIXEL, MAX_POLYGONS, SUBPIXEL_BITS, SUBPIXEL_STEPS};
use crate::raster::BRANCH_FREE;
use crate::raster::vertex::ScreenVertex;

/// Edge-table entry, packed in 4 bytes: the row where edges of a polygon
/// start below its first row (high 12 bits, the bucket), and the polygon's
/// position in the sorted polygon table (low 20 bits). Sorting the entries
/// as integers sorts them by bucket. One entry stands for every edge of the
/// polygon that starts on that row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct EdgeEntry(u32);

/// Bits of [`EdgeEntry`] holding the polygon's position: enough for
/// [`MAX_POLYGONS`] positions.
const POSITION_BITS: u32 = MAX_POLYGONS.trailing_zeros();
const _: () = assert!(MAX_POLYGONS.is_power_of_two() && POSITION_BITS <= 20);

impl EdgeEntry {
    /// An entry for unused slots.
    pub const ZERO: Self = Self(0);
    /// Lowest bit of the row.
    pub(crate) const ROW_SHIFT: u32 = POSITION_BITS;

    /// Six bits of the row from bit `shift` on: a radix-sort bucket.
    #[inline]
    pub(crate) fn bucket(self, shift: u32) -> u8 {
        ((self.0 >> shift) & 63) as u8
    }

    /// Edges of the polygon at `position` starting on `row` (below 4096).
    pub(crate) fn new(row: u16, position: usize) -> Self {
        debug_assert!(position < MAX_POLYGONS && u32::from(row) < 1 << (32 - POSITION_BITS));
        Self((u32::from(row) << POSITION_BITS) | position as u32)
    }

    /// The row the edges start on.
    pub(crate) fn row(self) -> u16 {
        (self.0 >> POSITION_BITS) as u16
    }

    /// Position of the polygon in the polygon table.
    pub(crate) fn position(self) -> usize {
        (self.0 & ((1 << POSITION_BITS) - 1)) as usize
    }
}

/// `(q, r)` with `q = ceil(num / den)` and `r = q·den - num` in `[0, den)`,
/// for `den > 0`. One division: 32-bit when `num` fits (the usual case on a
/// small screen), else 64-bit. Inside the guard band the quotient (a pixel
/// column) and the remainder fit `i32`.
fn ceil_div_rem(num: i64, den: i32) -> (i32, i32) {
    let (q, r) = match i32::try_from(num) {
        Ok(n) => (n / den, n % den),
        Err(_) => {
            let d = i64::from(den);
            ((num / d) as i32, (num % d) as i32)
        }
    };
    // Truncation rounds towards zero: a positive remainder means one more.
    if r > 0 { (q + 1, den - r) } else { (q, -r) }
}

/// `(floor(n / d), n mod d)` for `d > 0`. Where a division is not cheap
/// (a Cortex-M0+ without a divider) a quotient in `[-4, 4)` is found by at
/// most four additions or subtractions: an edge's step is mostly a pixel
/// or two per row, and a library division costs about 90 instructions.
/// Ranges: `|n| < 2^22`, `0 < d < 2^22`, so `4·d < 2^24` and every partial
/// remainder stays within `(-2^24, 2^24)`.
#[inline]
fn floor_div_rem(n: i32, d: i32) -> (i32, i32) {
    floor_div_rem_by(n, d, !DIVISION_IS_CHEAP)
}

/// [`floor_div_rem`], by additions for a small quotient when `by_steps`.
#[inline(always)]
fn floor_div_rem_by(n: i32, d: i32, by_steps: bool) -> (i32, i32) {
    debug_assert!(d > 0);
    if by_steps && n.unsigned_abs() < 4 * d.unsigned_abs() {
        let (mut q, mut r) = (0, n);
        while r < 0 {
            r += d;
            q -= 1;
        }
        while r >= d {
            r -= d;
            q += 1;
        }
        return (q, r);
    }
    floor_from_truncated(n / d, n % d, d, BRANCH_FREE)
}

/// The floor quotient and remainder from the truncated ones (`q`, `r`,
/// `|r| < d`), with a mask or a branch: the remainder's sign is the
/// edge's slope's, and a branch on it would miss half the time on a host.
#[inline(always)]
fn floor_from_truncated(q: i32, r: i32, d: i32, branch_free: bool) -> (i32, i32) {
    if branch_free {
        let borrow = r >> 31; // -1 or 0
        (q + borrow, r + (d & borrow))
    } else if r < 0 {
        (q - 1, r + d)
    } else {
        (q, r)
    }
}

/// The ceiling of `n / den` for `0 <= n < 2·den` (0, 1 or 2) and what it
/// leaves, `q·den - n`, with masks or branches (which of the three it is
/// depends on a corner's sub-pixel position). `den < 2^30`, so `2·den - n`
/// fits.
#[inline(always)]
fn small_ceil_div_rem(n: i32, den: i32, branch_free: bool) -> (i32, i32) {
    if branch_free {
        let (one, two) = (-i32::from(n > 0), -i32::from(n > den)); // -1 or 0
        (-(one + two), (den & one) + (den & two) - n)
    } else if n == 0 {
        (0, 0)
    } else if n <= den {
        (1, den - n)
    } else {
        (2, 2 * den - n)
    }
}

/// Active-edge-table entry (opaque): an edge crossing the current
/// scanline.
#[derive(Debug, Clone, Copy)]
pub struct ActiveEdge {
    /// Next edge of the same polygon (or next free entry), an index into
    /// the active edge pool.
    pub(crate) next: u32,
    /// First pixel at or right of the crossing on the current row.
    pub(crate) x: i32,
    /// One past the last row the edge covers.
    pub(crate) end_row: u16,
    /// `x·den - numerator`, always in `[0, den)`.
    remainder: i32,
    /// Whole pixels `x` moves per row (`floor(dx / dy)`).
    step: i32,
    /// Fractional part of the per-row move, in units of `1/den`.
    step_remainder: i32,
    /// `SUBPIXEL_STEPS · dy`.
    den: i32,
}

impl ActiveEdge {
    /// A placeholder for unused slots.
    pub const EMPTY: Self = Self {
        next: u32::MAX,
        x: 0,
        end_row: 0,
        remainder: 0,
        step: 0,
        step_remainder: 0,
        den: 1,
    };

    /// Starts stepping an edge at `row` (any row it covers) until
    /// `end_row`, one past its last; `next` links it into its polygon's
    /// list.
    ///
    /// Inside the guard band `dy < 2^22` sub-pixel steps, so `den < 2^30`
    /// and every per-row quantity fits `i32`; the set-up products fit `i64`,
    /// and the divisions are 32-bit whenever the numerator fits.
    #[inline(always)]
    pub fn start(
        top: ScreenVertex,
        bottom: ScreenVertex,
        row: u16,
        end_row: u16,
        next: u32,
    ) -> Self {
        // Inside the guard band |dx|, dy < 2^22: 32-bit, and den < 2^30.
        let dx = bottom.x - top.x;
        let dy = bottom.y - top.y;
        let den = SUBPIXEL_STEPS * dy;
        let sample_y = i32::from(row) * SUBPIXEL_STEPS + HALF_PIXEL;
        // x_top - half a pixel = 256·whole + s, 0 <= s < 256.
        let t = top.x - HALF_PIXEL;
        let (whole, s) = (t >> SUBPIXEL_BITS, t & (SUBPIXEL_STEPS - 1));
        let along = sample_y - top.y;
        debug_assert!(along >= 0, "row {row} lies above the edge's top");
        let stepped = end_row > row + 1;
        // floor(dx / dy) and its remainder; an edge covering one row is
        // never stepped and needs none, unless the crossing below uses it.
        let (step, rest) = if stepped || along < SUBPIXEL_STEPS {
            floor_div_rem(dx, dy)
        } else {
            (0, 0)
        };
        let (x, remainder) = if along < SUBPIXEL_STEPS {
            // The usual case: `row` is the edge's first row, so the sample
            // line lies within a pixel of the top. With dx = step·dy + rest,
            // the numerator s·dy + along·dx is dy·a + along·rest, a = s +
            // along·step (|a| < 2^30 + 2^8); the whole pixels of a come out
            // exactly, leaving n = dy·(a mod 256) + along·rest in [0,
            // 510·dy) (each term below 2^30, so n < 2^31): its ceiling
            // quotient by den = 256·dy is 0, 1 or 2, with no division.
            let a = s + along * step;
            let n = dy * (a & (SUBPIXEL_STEPS - 1)) + along * rest;
            let (q, r) = small_ceil_div_rem(n, den, BRANCH_FREE);
            (whole + (a >> SUBPIXEL_BITS) + q, r)
        } else {
            // Crossing x at the sample line, minus half a pixel, times den:
            // x(row) - 0.5px = (x_top - half)·dy + (yc - y_top)·dx, over dy.
            // With x_top - half = 256·p + s (0 <= s < 256) the whole pixels
            // p come out of the division exactly, leaving s·dy + (yc -
            // y_top)·dx (0 <= yc - y_top < dy): below 2^31 when dy, |dx| <
            // 2^15 (edges under 128 px each way), so a 32-bit product and
            // division do; longer edges take 64 bits.
            let (x, remainder) = if dy < 1 << 15 && dx.unsigned_abs() < 1 << 15 {
                ceil_div_rem(i64::from(s * dy + along * dx), den)
            } else {
                ceil_div_rem(
                    i64::from(s) * i64::from(dy) + i64::from(along) * i64::from(dx),
                    den,
                )
            };
            (x + whole, remainder)
        };
        Self {
            next,
            x,
            end_row,
            remainder,
            step,
            // S·dx - step·S·dy = S·(dx mod dy).
            step_remainder: SUBPIXEL_STEPS * rest,
            den,
        }
    }

    /// Makes the edge move `step` whole pixels per row (unit tests of the
    /// active tables).
    #[cfg(test)]
    pub fn set_step_for_tests(&mut self, step: i32) {
        self.step = step;
        self.step_remainder = 0;
    }

    /// Moves the crossing down one scanline.
    #[inline]
    pub fn advance(&mut self) {
        self.advance_as::<BRANCH_FREE>();
    }

    /// [`Self::advance`], with or without a branch (both are tested on the
    /// host).
    #[inline(always)]
    fn advance_as<const BRANCH_FREE: bool>(&mut self) {
        // 0 <= remainder, step_remainder < den < 2^30: |r| < 2^30.
        let r = self.remainder - self.step_remainder;
        if BRANCH_FREE {
            // Whether the remainder goes below zero depends on the row
            // and the slope, so a predicted branch misses about half the
            // time: the sign becomes a mask instead (-1 or 0).
            let borrow = r >> 31;
            self.x += self.step - borrow;
            self.remainder = r + (self.den & borrow);
        } else if r >= 0 {
            self.x += self.step;
            self.remainder = r;
        } else {
            self.x += self.step + 1;
            self.remainder = r + self.den;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixed::first_sample_at_or_after;

    /// Exact crossing of the edge at `row`: the first pixel whose sample
    /// lies at or right of it.
    fn exact_x(top: ScreenVertex, bottom: ScreenVertex, row: i32) -> i128 {
        let (dx, dy) = (i128::from(bottom.x - top.x), i128::from(bottom.y - top.y));
        let yc = i128::from(row) * 256 + 128;
        let num = (i128::from(top.x) - 128) * dy + (yc - i128::from(top.y)) * dx;
        let den = 256 * dy;
        num.div_euclid(den) + i128::from(num.rem_euclid(den) != 0)
    }

    /// Steps `top`-`bottom` from its first row inside the frame to its
    /// last (at most `rows` of them), checking every crossing.
    fn check_edge(top: ScreenVertex, bottom: ScreenVertex, rows: i32) {
        let first = first_sample_at_or_after(top.y).max(0);
        let end = first_sample_at_or_after(bottom.y).min(rows);
        if first >= end {
            return;
        }
        let mut edge = ActiveEdge::start(top, bottom, first as u16, end as u16, 0);
        for row in first..end {
            assert_eq!(
                i128::from(edge.x),
                exact_x(top, bottom, row),
                "{top:?} {bottom:?} row {row}"
            );
            assert!(edge.x.unsigned_abs() <= (1 << 13) + 1);
            edge.advance();
        }
    }

    const G: i32 = crate::limits::GUARD_BAND - 1;

    #[test]
    fn floor_division_by_steps_is_exact() {
        let limit = (1 << 22) - 1;
        let mut numerators = std::vec![-limit, -limit + 1, -1, 0, 1, limit - 1, limit];
        let mut divisors = std::vec![1, 2, 3, 255, 256, 257, limit - 1, limit];
        for k in 0..=22 {
            numerators.extend([(1 << k) - 1, -(1 << k) + 1]);
            divisors.push((1 << k).min(limit));
        }
        for &d in &divisors {
            // Quotients -5..=5, at and beside every boundary.
            for q in -5..=5i64 {
                for off in [-1, 0, 1, i64::from(d) - 1] {
                    let n = q * i64::from(d) + off;
                    if n.abs() <= i64::from(limit) {
                        numerators.push(n as i32);
                    }
                }
            }
            for &n in &numerators {
                let expected = (n.div_euclid(d), n.rem_euclid(d));
                assert_eq!(floor_div_rem_by(n, d, true), expected, "{n} / {d}");
                assert_eq!(floor_div_rem_by(n, d, false), expected, "{n} / {d}");
            }
        }
    }

    #[test]
    fn extreme_edges_step_exactly() {
        let v = |x, y| ScreenVertex { x, y, z: 0 };
        let ends = [-G, -G + 1, -1, 0, 1, 127, 128, 129, G - 1, G];
        for &x0 in &ends {
            for &x1 in &ends {
                for &(y0, y1) in &[(-G, G), (-G, 1), (0, G), (127, 129), (-G, -G + 300)] {
                    check_edge(v(x0, y0), v(x1, y1), 4096);
                }
            }
        }
    }

    /// The branch-free helpers (hosts) and the branching ones (32-bit
    /// Arm) agree, and give the floor and the small ceiling.
    #[test]
    fn branch_free_divisions_equal_branching_ones() {
        for d in [1i32, 2, 3, 255, 256, 1 << 20, (1 << 30) - 1] {
            for n in [
                -2 * d + 1,
                -d - 1,
                -d,
                -d + 1,
                -1,
                0,
                1,
                d - 1,
                d,
                d + 1,
                2 * d - 1,
            ] {
                let want = (n.div_euclid(d), n.rem_euclid(d));
                for branch_free in [true, false] {
                    if n.abs() < 2 * d {
                        let (q, r) = (n / d, n % d);
                        assert_eq!(
                            floor_from_truncated(q, r, d, branch_free),
                            want,
                            "{n} / {d}"
                        );
                    }
                    if (0..2 * d).contains(&n) {
                        let (wide_n, wide_d) = (i64::from(n), i64::from(d));
                        let q = (wide_n + wide_d - 1) / wide_d;
                        let want = (q as i32, (q * wide_d - wide_n) as i32);
                        assert_eq!(
                            small_ceil_div_rem(n, d, branch_free),
                            want,
                            "ceil {n} / {d}"
                        );
                    }
                }
            }
        }
    }

    proptest::proptest! {
        /// The branch-free step (hosts) and the branching one (32-bit Arm)
        /// agree, over the whole range of the state (`den < 2^30`).
        #[test]
        fn branch_free_steps_equal_branching_ones(
            den in 1..1i32 << 30, remainder in 0..1i32 << 30, step_remainder in 0..1i32 << 30,
            x in -(1i32 << 23)..1 << 23, step in -(1i32 << 22)..1 << 22,
        ) {
            let (remainder, step_remainder) = (remainder % den, step_remainder % den);
            let edge = ActiveEdge { x, remainder, step, step_remainder, den, ..ActiveEdge::EMPTY };
            let (mut branch_free, mut branching) = (edge, edge);
            for _ in 0..3 {
                branch_free.advance_as::<true>();
                branching.advance_as::<false>();
                proptest::prop_assert_eq!(
                    (branch_free.x, branch_free.remainder),
                    (branching.x, branching.remainder)
                );
                proptest::prop_assert!((0..den).contains(&branching.remainder));
            }
        }

        #[test]
        fn random_edges_step_exactly(
            x0 in -G..=G, x1 in -G..=G, y0 in -G..=G, dy in 1..=2 * G,
        ) {
            let y1 = (y0 + dy).min(G);
            if y1 > y0 {
                let v = |x, y| ScreenVertex { x, y, z: 0 };
                check_edge(v(x0, y0), v(x1, y1), 4096);
            }
        }
    }

    #[test]
    fn ceil_division_with_remainder() {
        for (num, den) in [
            (7i64, 2i32),
            (-7, 2),
            (6, 3),
            (-6, 3),
            (0, 5),
            (1 << 40, 1000),
            (-(1 << 40) - 1, 999),
        ] {
            let (q, r) = ceil_div_rem(num, den);
            let d = i64::from(den);
            assert_eq!(
                i64::from(q),
                num.div_euclid(d) + i64::from(num.rem_euclid(d) != 0),
                "{num}/{den}"
            );
            assert_eq!(i64::from(q) * d - num, i64::from(r));
            assert!((0..den).contains(&r));
        }
    }
}
