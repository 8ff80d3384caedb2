//! Where a mesh's holes may show its inside: the screen rectangles of the
//! cap triangles that face the viewer, each grown by a pixel, kept as the
//! rectangle that holds them all (the window) and a grid of up to 32 x 32
//! cells over it, each cell marked when some cap's rectangle meets it.
//!
//! A back face of a hull closed by caps shows only through a cap: the
//! eye's ray to any point of it that shows passes through a cap triangle
//! facing the viewer, so the point's projection lies in that cap's
//! projection, within its grown rectangle
//! ([`ClosedHull`](crate::ClosedHull)). A back face whose rectangle meets
//! no marked cell meets no cap's rectangle, so it cannot show. The cells
//! only widen the caps' rectangles (each to the cells it meets), never
//! narrow them; the window alone is the same test with one cell.

use crate::raster::vertex::ScreenRect;

/// Cells a side of the grid has at most.
const CELLS: u32 = 32;

/// The window and the grid of cells over it (see the module's notes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CapCover {
    window: ScreenRect,
    /// Each cell is `2^shift` sub-pixel steps wide (`[0]`) and high
    /// (`[1]`): the least that puts the window in 32 cells each way.
    shift: [u32; 2],
    /// Bit `i` of row `j`: cell `(i, j)` meets a cap's rectangle.
    rows: [u32; CELLS as usize],
}

impl CapCover {
    /// An empty grid over `window` (the caps' rectangles are within it).
    pub(crate) fn new(window: ScreenRect) -> Self {
        // The window's sides: below 2^24 sub-pixel steps inside the guard
        // band, so a shift below 24 always puts them in 32 cells.
        let shift_for = |side: i32| {
            let side = side.max(0) as u32;
            (0..31).find(|&s| side >> s < CELLS).unwrap_or(31)
        };
        Self {
            window,
            shift: [
                shift_for(window.x1 - window.x0),
                shift_for(window.y1 - window.y0),
            ],
            rows: [0; CELLS as usize],
        }
    }

    /// The columns and rows of the cells `rect` meets, or `None` when it
    /// misses the window.
    #[inline(always)]
    fn cells(&self, rect: &ScreenRect) -> Option<([u32; 2], [u32; 2])> {
        let w = &self.window;
        if rect.x1 < w.x0 || rect.x0 > w.x1 || rect.y1 < w.y0 || rect.y0 > w.y1 {
            return None;
        }
        // Clamped to the window, each offset is below 32 cells.
        let cell = |v: i32, lo: i32, hi: i32, shift: u32| {
            (((v.clamp(lo, hi) - lo) as u32) >> shift).min(CELLS - 1)
        };
        Some((
            [
                cell(rect.x0, w.x0, w.x1, self.shift[0]),
                cell(rect.x1, w.x0, w.x1, self.shift[0]),
            ],
            [
                cell(rect.y0, w.y0, w.y1, self.shift[1]),
                cell(rect.y1, w.y0, w.y1, self.shift[1]),
            ],
        ))
    }

    /// The bits of columns `first..=last` (`last <= 31`).
    #[inline(always)]
    fn columns([first, last]: [u32; 2]) -> u32 {
        (u32::MAX >> (CELLS - 1 - last)) & (u32::MAX << first)
    }

    /// Marks the cells a cap's rectangle meets.
    pub(crate) fn add(&mut self, rect: &ScreenRect) {
        if let Some((columns, [first, last])) = self.cells(rect) {
            let bits = Self::columns(columns);
            for row in &mut self.rows[first as usize..=last as usize] {
                *row |= bits;
            }
        }
    }

    /// Whether `rect` meets a marked cell: a back face within it may show.
    #[inline(always)]
    pub(crate) fn meets(&self, rect: &ScreenRect) -> bool {
        match self.cells(rect) {
            Some((columns, [first, last])) => {
                let bits = Self::columns(columns);
                self.rows[first as usize..=last as usize]
                    .iter()
                    .any(|row| row & bits != 0)
            }
            None => false,
        }
    }

    /// The window: the rectangle holding every cap's.
    #[cfg(test)]
    pub(crate) fn window(&self) -> &ScreenRect {
        &self.window
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::vec::Vec;

    fn rect(x0: i32, x1: i32, y0: i32, y1: i32) -> ScreenRect {
        ScreenRect { x0, x1, y0, y1 }
    }

    fn overlap(a: &ScreenRect, b: &ScreenRect) -> bool {
        !(a.x1 < b.x0 || a.x0 > b.x1 || a.y1 < b.y0 || a.y0 > b.y1)
    }

    /// Two caps at opposite corners of the window: a rectangle between
    /// them meets neither (the window alone would say it may show), one
    /// touching either does.
    #[test]
    fn the_gap_between_two_caps_is_not_covered() {
        let caps = [rect(0, 100, 0, 100), rect(3000, 3100, 3000, 3100)];
        let mut cover = CapCover::new(rect(0, 3100, 0, 3100));
        for c in &caps {
            cover.add(c);
        }
        assert!(!cover.meets(&rect(1000, 2000, 1000, 2000)));
        assert!(cover.meets(&rect(100, 200, 100, 200)));
        assert!(cover.meets(&rect(2900, 3000, 2000, 3050)));
        assert!(!cover.meets(&rect(-500, -1, 0, 100)));
        assert!(overlap(cover.window(), &rect(1000, 2000, 1000, 2000)));
    }

    proptest! {
        /// Never a false "cannot show": a rectangle that meets a cap's
        /// rectangle meets a marked cell, whatever the window's size.
        #[test]
        fn a_rectangle_meeting_a_cap_meets_the_cover(
            caps in prop::collection::vec((0..5000i32, 0..400i32, 0..5000i32, 0..400i32), 1..12),
            probes in prop::collection::vec((-200..5600i32, 0..600i32, -200..5600i32, 0..600i32), 1..40),
        ) {
            let caps: Vec<ScreenRect> =
                caps.iter().map(|&(x, w, y, h)| rect(x, x + w, y, y + h)).collect();
            let mut window = caps[0];
            for c in &caps {
                (window.x0, window.x1) = (window.x0.min(c.x0), window.x1.max(c.x1));
                (window.y0, window.y1) = (window.y0.min(c.y0), window.y1.max(c.y1));
            }
            let mut cover = CapCover::new(window);
            for c in &caps {
                cover.add(c);
            }
            for &(x, w, y, h) in &probes {
                let probe = rect(x, x + w, y, y + h);
                if caps.iter().any(|c| overlap(c, &probe)) {
                    prop_assert!(cover.meets(&probe), "{:?} {:?}", probe, caps);
                }
                if !overlap(&window, &probe) {
                    prop_assert!(!cover.meets(&probe));
                }
            }
        }
    }
}
