//! Stepping the active polygons from row to row: on each row every active
//! polygon fills its spans and steps its edges down to the next row (a
//! triangle switching to its lower short edge on the way), and those that
//! end leave the active polygon table. [`ScanState`] is what a scan
//! carries from row to row.

use crate::error::Error;
use crate::raster::active::{ActivePolygon, EdgePool, NO_EDGE, NO_ROW, SpanDepth};
use crate::raster::depth::DepthFormat;
use crate::raster::edge::ActiveEdge;
use crate::raster::entry_geometry::polygon_plane;
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::slots::OrderedSlots;
use crate::raster::small::{SMALL_TRIANGLES, SmallCoverage};
use crate::raster::small_table::{SmallRowDepth, SmallTable, fill_small_row};
use crate::raster::span::{PixelWrite, RowBuffers, SpanSource};
use crate::raster::stats::FrameStats;
use crate::raster::tables::Prepared;

/// The state of one scan.
pub(crate) struct ScanState<'t, 'a, C> {
    pub tables: &'t Prepared<'t, C>,
    pub active: OrderedSlots<'a, ActivePolygon<C>>,
    pub pool: EdgePool<'a>,
    pub stats: FrameStats,
    /// Whether small triangles are drawn from coverage masks
    /// ([`SMALL_TRIANGLES`](crate::raster::small::SMALL_TRIANGLES); the
    /// tests take both ways and compare the rows).
    pub small_triangles: bool,
    /// Small triangles waiting for their next rows (see
    /// [`SmallTable`]); one that does not fit waits in the APT.
    pub small: SmallTable<'a, C>,
}

impl<C: Copy> ScanState<'_, '_, C> {
    /// Fills an active polygon's spans on `row` and steps it down to the
    /// next row; returns whether it is still active there.
    #[inline]
    pub(super) fn fill_and_step<D: DepthFormat>(
        &mut self,
        polygon: &mut ActivePolygon<C>,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> bool {
        fill_and_step::<C, D, false>(
            polygon,
            self.tables,
            &mut self.pool,
            &mut self.stats,
            row,
            rows,
        )
    }

    /// The slot of the active polygon at `position` of the polygon
    /// table, if it is active.
    #[inline]
    pub(super) fn find_slot(&self, position: u32) -> Option<usize> {
        self.active
            .live_slots()
            .iter()
            .map(|&slot| usize::from(slot))
            .find(|&slot| {
                self.active
                    .get(slot)
                    .is_some_and(|a| a.position == position)
            })
    }

    /// Whether any polygon is active (large or small): a row scanned with
    /// none writes nothing.
    pub(super) fn any_active(&self) -> bool {
        self.active.len() + self.small.len() > 0
    }

    pub(super) fn note_peaks(&mut self) {
        let s = &mut self.stats;
        let active = self.active.len() + self.small.len();
        s.peak_active_polygons = s.peak_active_polygons.max(active as u32);
        s.peak_active_edges = s.peak_active_edges.max(self.pool.live);
        s.peak_pooled_edges = s.peak_pooled_edges.max(self.pool.pooled);
    }

    /// Fills every active polygon's spans on `row` into the row buffers,
    /// then steps each down to the next row: those that end leave the APT
    /// at once (its order does not matter, ties being broken by key).
    /// Pixels are written by the scanline's rule
    /// ([`PixelWrite::NearerOrFirstAdded`]), which `rows` must have.
    #[inline(never)]
    pub(super) fn scan_row<D: DepthFormat>(
        &mut self,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> Result<(), Error> {
        let (tables, pool, stats) = (self.tables, &mut self.pool, &mut self.stats);
        // The three rows cut to one length here, once a row, so that each
        // span's slices need one bounds check, not three.
        let width = rows.depth.len();
        let (Some(color), Some(key)) = (rows.color.get_mut(..width), rows.key.get_mut(..width))
        else {
            return Err(Error::BadFrameSize);
        };
        // The scanline's rule, which every caller's `rows` has: the loop
        // below is compiled for it alone (with the `zbuffer` feature, one
        // test a span fewer; `cargo qemu-m4f`: 23,200 instructions a frame
        // of the torus knot).
        debug_assert_eq!(rows.write, PixelWrite::NearerOrFirstAdded);
        let rows = &mut RowBuffers::<C, D> {
            depth: &mut *rows.depth,
            color,
            key,
            write: PixelWrite::NearerOrFirstAdded,
        };
        // Entries stay in their slots. The pass runs from the last live
        // index down: one that ends swaps places in the order array with
        // the last live index (an entry already stepped), so nothing is
        // copied and nothing is stepped twice.
        let (items, order, len) = self.active.parts_mut();
        let order = &mut order[..*len];
        let mut live = order.len();
        let mut index = live;
        while index > 0 {
            index -= 1;
            let Some(polygon) = items.get_mut(usize::from(order[index])) else {
                break;
            };
            // (A triangle switches its short edge in there.)
            if !fill_and_step::<C, D, true>(polygon, tables, pool, stats, row, rows) {
                live -= 1;
                order.swap(index, live);
            }
        }
        *len = live;
        self.small.scan_row(rows, stats);
        Ok(())
    }
}

/// [`fill_and_step`] for the common case, a triangle whose depths stay in
/// range: `None` (nothing done) for any other polygon. Kept apart from the
/// general path so that, inlined into the row loop, it holds no more state
/// than it needs (on a Cortex-M0+ the general path's spills cost more than
/// the work).
#[inline(always)]
fn fill_and_step_triangle<C: Copy, D: DepthFormat, const SCANLINE: bool>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    row: u16,
    rows: &mut RowBuffers<'_, C, D>,
) -> Option<bool> {
    if D::NARROW {
        // A 32-bit row accumulator (Depth16): one addition a row. One
        // byte says so (a triangle's, in range), where testing the shape
        // and then the depth's variant took 12 cycles a row on a
        // Cortex-M0+.
        if !polygon.is_narrow_triangle() {
            return None;
        }
        let (start, end) = polygon.triangle_span();
        let narrow = polygon.narrow;
        if rows.fill_in_range::<SCANLINE>(start, end, polygon.key, polygon.color, |column| {
            D::narrow_at(&narrow, column)
        }) {
            stats.spans += 1;
        }
        if !step_triangle(polygon, tables, pool, stats, row) {
            return Some(false);
        }
        polygon.narrow.next_row();
        return Some(true);
    }
    if !polygon.is_plane_stepped_triangle() {
        return None;
    }
    // Fields are read where they are used, not copied out first: on a
    // Cortex-M0+ the copies were spilled to the stack on every row. (One
    // match binding all three by reference measured 0.8 % slower there
    // than this pair: the second match cannot fail.)
    let SpanDepth::Stepped {
        accumulator: Some(step),
        ..
    } = polygon.depth
    else {
        return None;
    };
    let (start, end) = polygon.triangle_span();
    let SpanDepth::Stepped {
        dz_dx, row_value, ..
    } = &polygon.depth
    else {
        return None;
    };
    let (row_value, dz_dx) = (*row_value, *dz_dx);
    if rows.fill_in_range::<SCANLINE>(start, end, polygon.key, polygon.color, |column| {
        D::accumulator_at(row_value, dz_dx, step, column)
    }) {
        stats.spans += 1;
    }
    if !step_triangle(polygon, tables, pool, stats, row) {
        return Some(false);
    }
    if let SpanDepth::Stepped {
        row_value, dz_dy, ..
    } = &mut polygon.depth
    {
        *row_value += *dz_dy;
    }
    Some(true)
}

/// Steps a triangle's edges down from `row`; `false` (its edges freed)
/// when it ends there. On its switch row its lower short edge takes the
/// upper one's place. One comparison a row decides whether either happens
/// (`event_row`).
#[inline(always)]
fn step_triangle<C: Copy>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    row: u16,
) -> bool {
    let next_row = row + 1;
    if polygon.event_row > next_row {
        polygon.advance_triangle(next_row);
        return true;
    }
    triangle_event(polygon, tables, pool, stats, next_row)
}

/// A triangle reaching its `event_row`: its end (`false`, its edges
/// freed), or else its switch row, where it steps and then switches its
/// short edge.
#[inline(always)]
fn triangle_event<C: Copy>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    next_row: u16,
) -> bool {
    if polygon.end_row <= next_row {
        pool.live -= 2;
        return false;
    }
    debug_assert_eq!(polygon.switch_row, next_row);
    polygon.advance_triangle(next_row);
    switch_triangle(polygon, tables, stats, next_row);
    true
}

/// A triangle reaching its middle corner's row: its lower short edge
/// joins the pair (the upper one has just left it).
#[inline(never)]
pub(crate) fn switch_triangle<C: Copy>(
    entry: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    stats: &mut FrameStats,
    row: u16,
) {
    let [mid, bot] = entry.lower.map(|id| tables.vertices[usize::from(id)]);
    let end = first_sample_at_or_after(bot.y).min(i32::from(tables.height));
    entry.switch_row = NO_ROW;
    entry.event_row = entry.end_row;
    if end > i32::from(row) {
        entry.switch_short_edge(ActiveEdge::start(mid, bot, row, end as u16, NO_EDGE));
        stats.edges += 1;
    }
}

/// Fills an active polygon's spans on `row` into the row buffers and steps
/// it down to the next row; returns whether it is still active there. The
/// common case inline ([`fill_and_step_triangle`]), every other polygon
/// out of line. `SCANLINE`: the row is known to be written by the
/// scanline's rule (the row loop's case), so an in-range triangle's span
/// does not look at the row's rule.
#[inline(always)]
pub(crate) fn fill_and_step<C: Copy, D: DepthFormat, const SCANLINE: bool>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    row: u16,
    rows: &mut RowBuffers<'_, C, D>,
) -> bool {
    // A small triangle first, in line: on the host most of the APT's
    // entries are small, and the out-of-line general path's call cost the
    // bunny at 800x600 about 1.7 % of its frame (tools/bench-ab, eleven
    // interleaved runs). A Cortex-M target has none: the test is left out.
    if SMALL_TRIANGLES && polygon.is_small() {
        return fill_and_step_small(polygon, stats, rows);
    }
    match fill_and_step_triangle::<C, D, SCANLINE>(polygon, tables, pool, stats, row, rows) {
        Some(alive) => alive,
        None => fill_and_step_general(polygon, tables, pool, stats, row, rows),
    }
}

/// [`fill_and_step`] for every polygon but an in-range triangle.
#[inline(never)]
fn fill_and_step_general<C: Copy, D: DepthFormat>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    row: u16,
    rows: &mut RowBuffers<'_, C, D>,
) -> bool {
    // (A small triangle never comes here: `fill_and_step` takes it first,
    // and where small triangles are not drawn from masks there are none.)
    let source = match polygon.depth {
        SpanDepth::Stepped {
            dz_dx,
            row_value,
            accumulator,
            ..
        } => SpanSource::Stepped {
            dz_dx,
            row_value,
            accumulator,
        },
        SpanDepth::Shared { .. } => {
            return fill_shared_and_step(polygon, tables, pool, stats, row, rows);
        }
        // A narrow row is only ever a triangle's, which the fast path takes;
        // were one here, the exact plane would still draw it.
        SpanDepth::Narrow | SpanDepth::Exact => {
            // Edge-on: the plane, exactly, at each pixel (rare).
            let entry = &tables.polygons[polygon.position as usize];
            match polygon_plane(entry, tables.corners, tables.vertices) {
                Some(plane) => SpanSource::Exact(plane, row),
                None => return false,
            }
        }
    };
    let (key, color) = (polygon.key, polygon.color);
    let active = fill_spans_and_step(polygon, tables, pool, stats, row, |start, end| {
        rows.fill(start, end, key, color, &source)
    });
    if let SpanDepth::Stepped {
        dz_dy, row_value, ..
    } = &mut polygon.depth
    {
        *row_value += *dz_dy;
    }
    active
}

/// [`fill_and_step`] for a small triangle: the samples it covers on this
/// row, each written with the depth its stepped span would give it (the
/// accumulator at its column); then its masks and its depth step to the
/// next row. Whether it covers a sample on a later row.
#[inline(always)]
fn fill_and_step_small<C: Copy, D: DepthFormat>(
    polygon: &mut ActivePolygon<C>,
    stats: &mut FrameStats,
    rows: &mut RowBuffers<'_, C, D>,
) -> bool {
    let mut coverage = SmallCoverage::from_words(polygon.lower);
    let depth = match polygon.depth {
        SpanDepth::Stepped {
            dz_dx,
            row_value,
            accumulator: Some(step),
            ..
        } => SmallRowDepth::Stepped {
            row_value,
            dz_dx,
            step,
        },
        _ => SmallRowDepth::Narrow(polygon.narrow),
    };
    fill_small_row(rows, (&coverage, polygon.key, polygon.color), depth, stats);
    let alive = !coverage.is_last_row();
    coverage.next_row();
    polygon.lower = coverage.to_words();
    match &mut polygon.depth {
        SpanDepth::Stepped {
            row_value, dz_dy, ..
        } => *row_value += *dz_dy,
        _ => polygon.narrow.next_row(),
    }
    alive
}

/// [`fill_and_step`] for a polygon with a shared plane, out of line: each
/// row's value is the plane's own (`row0_value + row · dz_dy`), nothing
/// is stepped.
#[inline(never)]
fn fill_shared_and_step<C: Copy, D: DepthFormat>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    row: u16,
    rows: &mut RowBuffers<'_, C, D>,
) -> bool {
    let SpanDepth::Shared {
        dz_dx,
        dz_dy,
        row0_value,
    } = polygon.depth
    else {
        return false;
    };
    // |row| < 2^12, |dz_dy| < 2^40: the product is below 2^52.
    let row_value = row0_value + i64::from(row) * dz_dy;
    let (key, color) = (polygon.key, polygon.color);
    fill_spans_and_step(polygon, tables, pool, stats, row, |start, end| {
        rows.fill_shared(start, end, key, color, row_value, dz_dx)
    })
}

/// Fills an active polygon's spans on `row` with `fill(start, end)`
/// (which says whether any pixel was in the row) and steps its edges down
/// to the next row; returns whether it is still active
/// there.
#[inline(always)]
fn fill_spans_and_step<C: Copy>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    row: u16,
    mut fill: impl FnMut(i32, i32) -> bool,
) -> bool {
    let next_row = row + 1;
    // (Without the `polygons` feature the tables hold triangles alone.)
    if !cfg!(feature = "polygons") || polygon.is_triangle() {
        let (start, end) = polygon.triangle_span();
        if fill(start, end) {
            stats.spans += 1;
        }
        return step_triangle(polygon, tables, pool, stats, row);
    } else {
        let spans = &mut stats.spans;
        polygon.for_each_span(pool, |start, end| {
            if fill(start, end) {
                *spans += 1;
            }
        });
        polygon.advance_edges(next_row, pool);
        if polygon.end_row <= next_row {
            return false;
        }
    }
    true
}
