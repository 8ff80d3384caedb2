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

use crate::fixed::{HALF_PIXEL, SUBPIXEL_STEPS, div_ceil_i64, first_sample_at_or_after};
use crate::vertex::ScreenVertex;

/// Edge-table entry: an edge of a polygon, bucketed by its first visible row.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EdgeEntry {
    /// Upper end (smaller y), index into the vertex table.
    pub top: u16,
    /// Lower end, index into the vertex table.
    pub bottom: u16,
    /// Id of the polygon the edge belongs to.
    pub polygon: u32,
    /// First visible row (the bucket).
    pub first_row: u16,
    /// One past the last visible row.
    pub end_row: u16,
}

/// Rows `[first, end)` that an edge from `a` to `b` covers, unclipped, with
/// its ends ordered top first. `None` for horizontal edges.
pub(crate) fn edge_rows(
    a: ScreenVertex,
    b: ScreenVertex,
) -> Option<(ScreenVertex, ScreenVertex, i32, i32)> {
    let (top, bottom) = if a.y < b.y { (a, b) } else { (b, a) };
    let first = first_sample_at_or_after(top.y);
    let end = first_sample_at_or_after(bottom.y);
    (first < end).then_some((top, bottom, first, end))
}

/// Active-edge-table entry: an edge crossing the current scanline.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ActiveEdge {
    /// Id of the polygon the edge belongs to.
    pub polygon: u32,
    /// First pixel at or right of the crossing on the current row.
    pub x: i32,
    /// One past the last row the edge covers.
    pub end_row: u16,
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
    /// Starts stepping `entry` at `row` (its first visible row).
    ///
    /// Inside the guard band `dy < 2^22` sub-pixel steps, so `den < 2^30`
    /// and every per-row quantity fits `i32`; the set-up products fit `i64`.
    pub fn start(entry: &EdgeEntry, top: ScreenVertex, bottom: ScreenVertex) -> Self {
        let dx = i64::from(bottom.x) - i64::from(top.x);
        let dy = i64::from(bottom.y) - i64::from(top.y);
        let s = i64::from(SUBPIXEL_STEPS);
        let den = s * dy;
        let sample_y = i64::from(entry.first_row) * s + i64::from(HALF_PIXEL);
        // Crossing x at the sample line, minus half a pixel, times den:
        // x(row) - 0.5px = (x_top - half)·dy + (yc - y_top)·dx, over dy.
        let numerator =
            (i64::from(top.x) - i64::from(HALF_PIXEL)) * dy + (sample_y - i64::from(top.y)) * dx;
        let x = div_ceil_i64(numerator, den);
        let remainder = x * den - numerator;
        let step = dx.div_euclid(dy);
        let step_remainder = s * dx - step * den;
        Self {
            polygon: entry.polygon,
            x: x as i32,
            end_row: entry.end_row,
            remainder: remainder as i32,
            step: step as i32,
            step_remainder: step_remainder as i32,
            den: den as i32,
        }
    }

    /// Moves the crossing down one scanline.
    #[inline]
    pub fn advance(&mut self) {
        let r = self.remainder - self.step_remainder;
        if r >= 0 {
            self.x += self.step;
            self.remainder = r;
        } else {
            self.x += self.step + 1;
            self.remainder = r + self.den;
        }
    }
}
