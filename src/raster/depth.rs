//! Depth formats: what one entry of the depth row stores and how a span
//! steps it.
//!
//! The renderer evaluates each polygon's plane in *plane units*: an `i64`
//! holding the input depth (Q0.24, see [`crate::raster::fixed`]) with
//! [`PLANE_FRAC_BITS`] extra fractional bits. A depth format turns a span's
//! start value and per-pixel step, both in plane units, into its own
//! accumulator, and the accumulator into the stored value.
//!
//! Convention for every format: **smaller is nearer**, the depth test is
//! strict (`new < stored`), and the row is cleared to [`DepthFormat::CLEAR`]
//! (the far plane), so a surface whose quantised depth is the far plane is
//! not drawn. On exactly equal depth the polygon added to the tables first
//! keeps the pixel, whatever the order polygons are scanned in (the
//! scanner keeps a row of tie-break keys beside the depth row).
//!
//! Every format stores the plane value rounded to the nearest step of its
//! resolution, within one step (1 LSB) of the exactly rounded value of the
//! exact plane; `tests/depth_bound.rs` checks this over full-width spans.

use crate::arith::wide::mul_i64_small;
use crate::limits::PLANE_FRAC_BITS;

/// A depth-row format: what one entry of the depth row stores, and how a
/// span steps it from a polygon's plane. Implemented by [`Depth16`] and
/// [`Depth24`], and sealed: the scanner relies on each format's stepping
/// arithmetic and its stated error bound, so no other type implements it.
pub trait DepthFormat: sealed::Sealed {
    /// What one depth-row entry stores.
    type Value: Copy + Ord + core::fmt::Debug;
    #[doc(hidden)]
    /// The per-pixel accumulator stepped along a span.
    type Accum: Copy + From<i32>;
    /// Value the row is cleared to: the far plane.
    const CLEAR: Self::Value;
    /// Short name used in reports ("z16", "z24").
    const NAME: &'static str;
    /// Resolution of the stored value, in bits.
    const BITS: u32;

    #[doc(hidden)]
    /// Accumulator and per-pixel step for a span of `len >= 1` pixels whose
    /// first pixel has plane value `start` and which steps by `step` per
    /// pixel. `None` when some pixel of the span would leave the format's
    /// range; the renderer then quantises pixel by pixel with
    /// [`DepthFormat::quantize`].
    fn span(start: i64, step: i64, len: u32) -> Option<(Self::Accum, Self::Accum)>;
    #[doc(hidden)]
    /// The stored value for the current pixel.
    fn value(acc: Self::Accum) -> Self::Value;
    #[doc(hidden)]
    /// A stored value as an `i32` of the same order (every value is below
    /// `2^24`): what a host's blocks of pixels compare, with no unsigned
    /// comparison to emulate ([`crate::raster::lanes`]).
    fn ordered(value: Self::Value) -> i32;
    #[doc(hidden)]
    /// Advances the accumulator by one pixel.
    fn advance(acc: Self::Accum, step: Self::Accum) -> Self::Accum;
    /// Rounds a plane value to the nearest stored value, clamped to the
    /// format's range.
    fn quantize(plane_value: i64) -> Self::Value;
    #[doc(hidden)]
    /// A polygon's per-pixel plane step (`abs(step) < 2^40`) as this
    /// format's accumulator step, computed once per polygon; `None` when it
    /// does not fit the accumulator.
    fn accumulator_step(step: i64) -> Option<i64>;
    #[doc(hidden)]
    /// The accumulator at pixel `column` of a row whose plane value at
    /// column 0 is `row_value` (the polygon's gradient `dz_dx`, its
    /// accumulator step `step` from [`DepthFormat::accumulator_step`]),
    /// and that step, for a span of a polygon whose every value lies in
    /// [`IN_RANGE`] depth steps: no per-span range check (the caller has
    /// made it once per polygon).
    ///
    /// Ranges: `|row_value| < 2^62`, `|dz_dx| < 2^40`, `0 <= column <
    /// 2^12`. Column 0 may lie far outside the polygon, so the value there
    /// may not fit the accumulator: a format may compute modulo the
    /// accumulator's width, since the value at `column` does fit.
    fn accumulator_at(
        row_value: i64,
        dz_dx: i64,
        step: i64,
        column: i32,
    ) -> (Self::Accum, Self::Accum);

    #[doc(hidden)]
    /// Whether [`DepthFormat::span`]'s accumulator gives at every pixel
    /// exactly [`DepthFormat::quantize`] of that pixel's plane value: its
    /// step is the plane's, unrounded, so a span it accepts stores what
    /// rounding each pixel on its own stores.
    const EXACT_SPAN: bool = false;

    #[doc(hidden)]
    /// Whether an in-range triangle steps a 32-bit row accumulator
    /// ([`NarrowRow`], from [`DepthFormat::narrow_row`]) rather than its
    /// plane value in plane units: a format whose accumulator is an `i32`.
    const NARROW: bool = false;

    #[doc(hidden)]
    /// The [`NarrowRow`] of an in-range triangle (every value it covers in
    /// [`IN_RANGE`] depth steps) on the row `rows` rows below its first,
    /// the plane value at column 0 of that first row being `first_value`
    /// and the gradients `dz_dx`, `dz_dy` (`|first_value| < 2^62`,
    /// `|dz_dx|, |dz_dy| < 2^40`, `0 <= rows < 2^12`); `None` when a
    /// gradient does not fit, or for a format that is not
    /// [`NARROW`](DepthFormat::NARROW). The result depends on the first
    /// row's value and `rows` only, so a scan that starts below a
    /// triangle's first row (a band) steps it exactly as one that starts
    /// there.
    fn narrow_row(first_value: i64, dz_dx: i64, dz_dy: i64, rows: i32) -> Option<NarrowRow> {
        let _ = (first_value, dz_dx, dz_dy, rows);
        None
    }

    #[doc(hidden)]
    /// The accumulator at `column` of a [`NarrowRow`], and its step.
    #[inline(always)]
    fn narrow_at(row: &NarrowRow, column: i32) -> (Self::Accum, Self::Accum) {
        (
            Self::Accum::from(row.acc.wrapping_add(row.step.wrapping_mul(column))),
            Self::Accum::from(row.step),
        )
    }
}

/// A `NARROW` format's row state for an in-range
/// triangle: the accumulator at column 0 of the current row and its steps
/// per row and per pixel, all modulo 2^32 (column 0 may lie far outside
/// the triangle; the value at a covered pixel is in range). Stepping it
/// costs one 32-bit addition a row, where the plane value in plane units
/// takes 64-bit arithmetic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NarrowRow {
    /// The accumulator at column 0 of the current row.
    pub(crate) acc: i32,
    /// Its step from one row to the next.
    pub(crate) row_step: i32,
    /// Its step from one pixel to the next.
    pub(crate) step: i32,
}

impl NarrowRow {
    /// All zero (an unused entry's).
    pub(crate) const ZERO: Self = Self {
        acc: 0,
        row_step: 0,
        step: 0,
    };

    /// Steps down one row.
    #[inline(always)]
    pub(crate) fn next_row(&mut self) {
        self.acc = self.acc.wrapping_add(self.row_step);
    }
}

/// Depths (input steps) of a triangle's corners for which its spans take
/// the accumulator with no per-span range check: a pixel covered by the
/// triangle lies inside it, so its exact plane value is a convex
/// combination of the corners' depths, and the stepped value is within an
/// sixteenth of a step of it ([`Depth16::narrow_row`]); the margin of 256
/// steps covers that and the [`Depth16`] rounding (a depth above
/// `2^24 - 128` would round to 2^16).
pub const IN_RANGE: core::ops::RangeInclusive<u32> = 1..=crate::limits::DEPTH_MAX - 256;

/// 16-bit depth: `u16` entries (480 bytes for a 240-pixel row); one step is
/// 2^-16 of the depth range. The span accumulator is a 32-bit word in
/// Q16.16 (held in an `i32`, read as unsigned): the stored value is its
/// high half, one shift on a Cortex-M0+.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Depth16;

/// 24-bit depth in `u32` entries; one step is one input-depth step (2^-24
/// of the range). The span accumulator is an `i64` in Q24.32, so the stored
/// value is the accumulator's high word.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Depth24;

/// Fractional bits of the [`Depth16`] accumulator.
const Z16_ACC_FRAC: u32 = 16;
/// Plane units per [`Depth16`] accumulator unit, as a shift.
const Z16_SHIFT: u32 = PLANE_FRAC_BITS + 8 - Z16_ACC_FRAC;
/// Fractional bits of the [`Depth24`] accumulator.
const Z24_ACC_FRAC: u32 = 32;

/// `value / 2^shift` rounded to nearest (ties up).
#[inline(always)]
fn shift_round(value: i64, shift: u32) -> i64 {
    (value + (1 << (shift - 1))) >> shift
}

impl DepthFormat for Depth16 {
    type Value = u16;
    type Accum = i32;
    const CLEAR: u16 = u16::MAX;
    const NAME: &'static str = "z16";
    const BITS: u32 = 16;

    #[inline]
    fn span(start: i64, step: i64, len: u32) -> Option<(i32, i32)> {
        // Bias by half a step so that truncation rounds to nearest.
        let first = shift_round(start, Z16_SHIFT) + (1 << (Z16_ACC_FRAC - 1));
        // The step fits i32 (|step| < 2^40 plane units) and len <= 4096,
        // so the product cannot overflow i64.
        let step = i32::try_from(shift_round(step, Z16_SHIFT)).ok()?;
        let last = first + i64::from(step) * (i64::from(len) - 1);
        let in_range = |v: i64| (0..1i64 << 32).contains(&v);
        if in_range(first) && in_range(last) {
            // Both ends fit the unsigned word, and the accumulator is
            // affine in the pixel index, so every pixel in between fits as
            // well. (The advance past the last pixel wraps, unstored.)
            Some((first as u32 as i32, step))
        } else {
            None
        }
    }

    #[inline(always)]
    fn value(acc: i32) -> u16 {
        ((acc as u32) >> Z16_ACC_FRAC) as u16
    }

    #[inline(always)]
    fn ordered(value: u16) -> i32 {
        i32::from(value)
    }

    #[inline(always)]
    fn advance(acc: i32, step: i32) -> i32 {
        // The advance past a span's last pixel is never stored, and may
        // leave the range: it wraps rather than overflowing.
        acc.wrapping_add(step)
    }

    #[inline]
    fn quantize(plane_value: i64) -> u16 {
        shift_round(plane_value, PLANE_FRAC_BITS + 8).clamp(0, i64::from(u16::MAX)) as u16
    }

    #[inline]
    fn accumulator_step(step: i64) -> Option<i64> {
        // |step| < 2^40 plane units: the shifted step is below 2^31 only
        // for the gentler gradients, which is every polygon in practice.
        i32::try_from(shift_round(step, Z16_SHIFT))
            .ok()
            .map(i64::from)
    }

    /// The value at column 0, rounded to the accumulator's unit, plus
    /// `column` accumulator steps, in 32-bit words (one `muls` on a
    /// Cortex-M0+, not a 64-bit product).
    ///
    /// Error: the column-0 value is off by at most half a unit (2^-16
    /// step) and each step by at most half a unit, so the value at
    /// `column` is within `(1 + column)·2^-17` steps of the exact plane, as
    /// the accumulator is after `column` pixels of a span; with the
    /// span's own pixels, below `2^-4` steps in a row of up to 2^12
    /// pixels. That lies inside [`IN_RANGE`]'s margin, so the exact sum
    /// `round(row_value / 2^8) + column·step + 2^15` is in `[0, 2^32)`:
    /// computed modulo 2^32 (wrapping), it is exact as an unsigned word.
    #[inline]
    fn accumulator_at(row_value: i64, _dz_dx: i64, step: i64, column: i32) -> (i32, i32) {
        let step = step as i32;
        let at_zero =
            (shift_round(row_value, Z16_SHIFT) as i32).wrapping_add(1 << (Z16_ACC_FRAC - 1));
        (at_zero.wrapping_add(step.wrapping_mul(column)), step)
    }

    const NARROW: bool = true;

    /// The first row's column-0 value rounded to the accumulator's unit,
    /// plus `rows` row steps, each step rounded to the unit too.
    ///
    /// Error: at `column` of the row `rows` below the first, the
    /// accumulator is the exact `plane / 2^8 + 2^15` off by at most half a
    /// unit for the first value, half a unit per row step and half a unit
    /// per pixel step: `(1 + rows + column)/2` units, below `2^12` units,
    /// which is `2^-4` step, for rows and columns below 2^12. Inside
    /// [`IN_RANGE`] the exact accumulator lies in `[2^15 + 2^8, 2^32 -
    /// 2^15 - 2^8]`, more than `2^15` units from either end of `[0,
    /// 2^32)`: so the value at a covered pixel, computed modulo 2^32, is in
    /// range as an unsigned word, and the stored depth is within `1/2 +
    /// 1/16` step of the exact plane.
    #[inline]
    fn narrow_row(first_value: i64, dz_dx: i64, dz_dy: i64, rows: i32) -> Option<NarrowRow> {
        let step = i32::try_from(shift_round(dz_dx, Z16_SHIFT)).ok()?;
        let row_step = i32::try_from(shift_round(dz_dy, Z16_SHIFT)).ok()?;
        let first =
            (shift_round(first_value, Z16_SHIFT) as i32).wrapping_add(1 << (Z16_ACC_FRAC - 1));
        Some(NarrowRow {
            acc: first.wrapping_add(row_step.wrapping_mul(rows)),
            row_step,
            step,
        })
    }
}

impl DepthFormat for Depth24 {
    type Value = u32;
    type Accum = i64;
    const CLEAR: u32 = crate::limits::DEPTH_MAX;
    const NAME: &'static str = "z24";
    const BITS: u32 = 24;

    /// The accumulator is `plane·2^16 + 2^31` and its step the plane's
    /// times `2^16`, both exact, so its top word `floor((plane + 2^15) /
    /// 2^16)` is `quantize`'s rounding, and in range no clamp applies.
    const EXACT_SPAN: bool = true;

    #[inline]
    fn span(start: i64, step: i64, len: u32) -> Option<(i64, i64)> {
        // In plane units: the accumulator is `plane · 2^16 + 2^31`, and it
        // lies in [0, DEPTH_MAX · 2^32) exactly when the plane value lies
        // in [-2^15, DEPTH_MAX · 2^16 - 2^15). With |step| < 2^40 and
        // len <= 2^12 the last value is within 2^52 of the first, and with
        // |start| < 2^57 nothing overflows; other input is refused. (No
        // checked multiplications: on a Cortex-M0+ each costs a call.)
        let widen = Z24_ACC_FRAC - PLANE_FRAC_BITS;
        if step.unsigned_abs() >= 1 << 40 || start.unsigned_abs() >= 1 << 57 || len > 1 << 12 {
            return None;
        }
        let last = start + step * (i64::from(len) - 1);
        let (lo, hi) = (
            -(1i64 << 15),
            (i64::from(crate::limits::DEPTH_MAX) << widen) - (1 << 15),
        );
        let in_range = |v: i64| (lo..hi).contains(&v);
        (in_range(start) && in_range(last))
            .then_some(((start << widen) + (1 << (Z24_ACC_FRAC - 1)), step << widen))
    }

    #[inline(always)]
    fn value(acc: i64) -> u32 {
        (acc >> Z24_ACC_FRAC) as u32
    }

    #[inline(always)]
    fn ordered(value: u32) -> i32 {
        // Stored values are at most DEPTH_MAX < 2^24.
        value as i32
    }

    #[inline(always)]
    fn advance(acc: i64, step: i64) -> i64 {
        acc.wrapping_add(step)
    }

    #[inline]
    fn quantize(plane_value: i64) -> u32 {
        shift_round(plane_value, PLANE_FRAC_BITS).clamp(0, i64::from(crate::limits::DEPTH_MAX))
            as u32
    }

    #[inline]
    fn accumulator_step(step: i64) -> Option<i64> {
        // |step| < 2^40: times 2^16, below 2^56.
        if step.unsigned_abs() < 1 << 40 {
            Some(step << (Z24_ACC_FRAC - PLANE_FRAC_BITS))
        } else {
            None
        }
    }

    /// Exact: the plane value at `column` (`|dz_dx·column| < 2^52`,
    /// and in range below 2^40), shifted into the accumulator (below
    /// 2^56).
    #[inline]
    fn accumulator_at(row_value: i64, dz_dx: i64, step: i64, column: i32) -> (i64, i64) {
        let start = row_value + mul_i64_small(dz_dx, column);
        (
            (start << (Z24_ACC_FRAC - PLANE_FRAC_BITS)) + (1 << (Z24_ACC_FRAC - 1)),
            step,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane(units: f64) -> i64 {
        (units * f64::from(1u32 << PLANE_FRAC_BITS)) as i64
    }

    #[test]
    fn quantize_rounds_and_clamps() {
        assert_eq!(Depth24::quantize(plane(10.49)), 10);
        assert_eq!(Depth24::quantize(plane(10.5)), 11);
        assert_eq!(Depth24::quantize(plane(-3.0)), 0);
        assert_eq!(Depth24::quantize(plane(1e9)), crate::limits::DEPTH_MAX);
        assert_eq!(Depth16::quantize(plane(256.0 * 7.49)), 7);
        assert_eq!(Depth16::quantize(plane(256.0 * 7.5)), 8);
        assert_eq!(Depth16::quantize(plane(-1.0)), 0);
        assert_eq!(Depth16::quantize(plane(1e9)), u16::MAX);
    }

    #[test]
    fn span_matches_quantize_and_rejects_out_of_range() {
        let start = plane(1000.3);
        let step = plane(-2.75);
        let (mut a16, s16) = Depth16::span(start * 256, step * 256, 100).unwrap();
        let (mut a24, s24) = Depth24::span(start, step, 100).unwrap();
        for k in 0..100 {
            assert_eq!(Depth24::value(a24), Depth24::quantize(start + k * step));
            assert_eq!(
                Depth16::value(a16),
                Depth16::quantize(256 * (start + k * step))
            );
            a24 = Depth24::advance(a24, s24);
            a16 = Depth16::advance(a16, s16);
        }
        // 1000.3 - 2.75 * 400 < 0: the span leaves the range.
        assert!(Depth24::span(start, step, 401).is_none());
        assert!(Depth16::span(start * 256, step * 256, 401).is_none());
    }

    /// A plane value (with a random fraction) whose depth step is in
    /// `IN_RANGE`: its lower end, its upper end or between, by `round`.
    fn in_range_value(round: u64, next: &mut impl FnMut() -> u64) -> i64 {
        let (lo, hi) = (*IN_RANGE.start(), *IN_RANGE.end());
        let depth = match round % 4 {
            0 => lo,
            1 => hi,
            _ => lo + (next() % u64::from(hi - lo)) as u32,
        };
        (i64::from(depth) << PLANE_FRAC_BITS) + (next() % (1 << 16)) as i64
    }

    /// A xorshift64 generator from `seed`.
    fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        }
    }

    /// `accumulator_at` against the exact plane, at the extremes: steep
    /// gradients, far columns (where the column-0 value is far outside the
    /// accumulator's range), both ends of `IN_RANGE`. The Depth16
    /// accumulator is within its stated `(1 + column)/2` units of the exact
    /// value; the Depth24 one is exact.
    #[test]
    fn accumulator_at_is_within_its_bound_where_column_zero_overflows() {
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        let mut cases = 0;
        for round in 0..200_000u64 {
            // The value at `column`, in plane units.
            let value = in_range_value(round, &mut next);
            let column = match round % 3 {
                0 => 4095,
                1 => 0,
                _ => (next() % 4096) as i32,
            };
            // The steepest gradients the Depth16 step takes (2^39 plane
            // units, half the depth range a pixel), and any gradient the
            // API accepts (below 2^40).
            let dz_dx = match round % 5 {
                0 => (1i64 << 39) - 1 - (next() % 512) as i64,
                1 => -(1i64 << 39) + 1 + (next() % 512) as i64,
                _ => (next() % (1 << 41)) as i64 - (1 << 40),
            };
            let row_value = value - dz_dx * i64::from(column);
            if let Some(step) = Depth16::accumulator_step(dz_dx) {
                let (acc, s) = Depth16::accumulator_at(row_value, dz_dx, step, column);
                assert_eq!(i64::from(s), step);
                // Exact accumulator, times 2^8: value / 2^8 + 2^15.
                let exact = i128::from(value) + (1 << (Z16_SHIFT + Z16_ACC_FRAC - 1));
                let error = (i128::from(acc as u32) << Z16_SHIFT) - exact;
                let bound = (1 + i128::from(column)) << (Z16_SHIFT - 1);
                assert!(
                    error.abs() <= bound,
                    "{row_value} {dz_dx} {column}: off by {error}"
                );
                cases += 1;
            }
            let step = Depth24::accumulator_step(dz_dx).unwrap();
            let (acc, _) = Depth24::accumulator_at(row_value, dz_dx, step, column);
            assert_eq!(acc, (value << 16) + (1 << 31));
        }
        // Most random gradients fit the Depth16 step: the bound was tested.
        assert!(cases > 100_000, "{cases}");
    }

    /// `Depth16::narrow_row` against the exact plane, at the extremes: the
    /// value at `column` of the row `rows` below the first is within the
    /// stated `(1 + rows + column)/2` units, inside `[0, 2^32)` wherever the
    /// exact depth is in `IN_RANGE`, even where column 0 of the first row
    /// is far outside the accumulator's range; and entering `rows` below
    /// the first row gives the state that stepping `rows` times gives.
    #[test]
    fn narrow_rows_are_within_their_bound_and_step_like_a_late_start() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        // As in the test above: the steepest gradients the step takes, and
        // any the API accepts.
        let gradient = |round: u64, r: u64| match round % 5 {
            0 => (1i64 << 39) - 1 - (r % 512) as i64,
            1 => -(1i64 << 39) + 1 + (r % 512) as i64,
            _ => (r % (1 << 41)) as i64 - (1 << 40),
        };
        let mut cases = 0;
        for round in 0..200_000u64 {
            let value = in_range_value(round, &mut next);
            let (column, rows) = match round % 3 {
                0 => (4095, 4095),
                1 => (0, (next() % 4096) as i32),
                _ => ((next() % 4096) as i32, (next() % 4096) as i32),
            };
            let (dz_dx, dz_dy) = (gradient(round, next()), gradient(round / 5, next()));
            // The first row's column-0 value that puts `value` there.
            let first = value - dz_dx * i64::from(column) - dz_dy * i64::from(rows);
            let Some(narrow) = Depth16::narrow_row(first, dz_dx, dz_dy, rows) else {
                continue;
            };
            let (acc, step) = Depth16::narrow_at(&narrow, column);
            assert_eq!(i64::from(step), Depth16::accumulator_step(dz_dx).unwrap());
            let exact = i128::from(value) + (1 << (Z16_SHIFT + Z16_ACC_FRAC - 1));
            // Read as the unsigned word it is: an error within the bound
            // means the true accumulator did not wrap.
            let error = (i128::from(acc as u32) << Z16_SHIFT) - exact;
            let bound = (1 + i128::from(rows) + i128::from(column)) << (Z16_SHIFT - 1);
            assert!(
                error.abs() <= bound,
                "{first} {dz_dx} {dz_dy} {rows} {column}: {error}"
            );
            // The stored depth: within 1/2 + 1/16 step of the exact one.
            let stored = f64::from(Depth16::value(acc));
            let exact_depth = value as f64 / f64::from(1u32 << (PLANE_FRAC_BITS + 8));
            assert!(
                (stored - exact_depth).abs() <= 0.5625,
                "{stored} {exact_depth}"
            );
            // A late start (a band) equals stepping from the first row.
            if round % 16 == 0 {
                let mut stepped = Depth16::narrow_row(first, dz_dx, dz_dy, 0).unwrap();
                for _ in 0..rows {
                    stepped.next_row();
                }
                assert_eq!(stepped, narrow);
            }
            cases += 1;
        }
        assert!(cases > 50_000, "{cases}");
        // Depth24 keeps the exact plane value: no narrow rows.
        assert_eq!(Depth24::narrow_row(0, 1, 1, 0), None);
    }
}

/// Keeps [`DepthFormat`] to this crate's formats.
mod sealed {
    /// The seal.
    pub trait Sealed {}
    impl Sealed for super::Depth16 {}
    impl Sealed for super::Depth24 {}
}
