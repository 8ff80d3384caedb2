//! The first frame's cut between the cores (feature `dual-core`): before
//! any buffer of rows has a time, each buffer's time is estimated from the
//! prepared tables, by the polygons whose rows fall in it and the pixels
//! they cover, and [`lcd::choose_cut`](crate::lcd::choose_cut) balances the
//! estimate as it balances the times of later frames. Without it the
//! first frame's rows were halved, as if each took as long, while the
//! torus knot's costly rows are in its middle. Made once, at start-up,
//! from frame 0's tables (about 3 ms on the RP2040).

use zline::{OutlineBuilder, Prepared};

use crate::lcd::PROFILE_BUFFERS as BUFFERS;
use crate::sizes::{ROWS_PER_BUFFER, WIDTH};

/// Cycles a row costs with no polygon on it (its colour and depth rows
/// cleared, its buffer's upkeep).
const ROW_CYCLES: u32 = 600;

/// Cycles to activate a polygon (its edges and planes set up), charged to
/// the buffer of its first row.
const ACTIVATION_CYCLES: u32 = if cfg!(any(feature = "gouraud", feature = "textured")) {
    1_300
} else {
    700
};

/// Cycles a polygon costs on each row it spans (its span found and its
/// edges stepped).
const POLYGON_ROW_CYCLES: u32 = 170;

/// Cycles a pixel costs: the depth test and write, plus the painting of
/// the winners with `gouraud` or `textured` (measured under QEMU on the
/// torus knot: about 13, 100 and 900 instructions).
const PIXEL_CYCLES: u32 = if cfg!(feature = "textured") {
    900
} else if cfg!(feature = "gouraud") {
    100
} else {
    15
};

/// Cycles in a microsecond at the 125 MHz system clock: the estimate is
/// in microseconds, as the buffers' times are.
const CYCLES_PER_MICROSECOND: u32 = 125;

/// Each buffer's estimated time in microseconds, from the polygons of
/// `prepared`. Sums over a buffer saturate.
pub fn estimate<C: Copy>(prepared: &Prepared<'_, C>) -> [u32; BUFFERS] {
    let mut cycles = [ROW_CYCLES * ROWS_PER_BUFFER as u32; BUFFERS];
    for polygon in prepared.polygons() {
        let rows = polygon.rows();
        let height = u32::from(rows.end.saturating_sub(rows.start));
        if height == 0 {
            continue;
        }
        // Pixels a row, at most the frame's width: below 2^16, so each
        // product below stays far inside a `u32`.
        let pixels = area_pixels(polygon.corners())
            .div_ceil(height)
            .min(u32::from(WIDTH));
        let per_row = POLYGON_ROW_CYCLES + PIXEL_CYCLES * pixels;
        let first = usize::from(rows.start) / ROWS_PER_BUFFER;
        if let Some(slot) = cycles.get_mut(first) {
            *slot = slot.saturating_add(ACTIVATION_CYCLES);
        }
        let mut row = rows.start;
        while row < rows.end {
            let buffer = usize::from(row) / ROWS_PER_BUFFER;
            let buffer_end = ((buffer + 1) * ROWS_PER_BUFFER).min(usize::from(rows.end)) as u16;
            if let Some(slot) = cycles.get_mut(buffer) {
                let n = u32::from(buffer_end - row);
                *slot = slot.saturating_add(per_row * n);
            }
            row = buffer_end;
        }
    }
    cycles.map(|c| c / CYCLES_PER_MICROSECOND)
}

/// A polygon's area in whole pixels, whichever way it winds, from the
/// twice-area `OutlineBuilder` gathers (in square 1/256 pixels: below
/// 2^55 for the corners a polygon may have).
fn area_pixels(corners: impl Iterator<Item = zline::ScreenVertex>) -> u32 {
    let mut outline = OutlineBuilder::default();
    corners.for_each(|v| outline.add(v));
    let square_steps = outline.finish().twice_area.unsigned_abs() / 2;
    u32::try_from(square_steps >> 16).unwrap_or(u32::MAX)
}
