//! The z-buffer methods the scanline z-buffer is compared with, on the same
//! tables, fill rule, plane set-up and depth formats, so their pictures
//! differ only where the methods do.
//!
//! [`render_bands`] keeps a depth buffer and a colour buffer of `K` rows
//! (a *band*) and draws polygon after polygon into each band, in the order
//! the tables hold them, with the strict depth test: on equal depth the
//! polygon drawn first keeps the pixel, which in the order polygons were
//! added is the scanline's rule too. With `K` the frame's height it is the
//! classic full-frame z-buffer (a 240x240 z16 depth buffer is 115,200
//! bytes, which an RP2040's 264 KB holds); with `K = 1` it keeps one row,
//! as the scanline does, but visits every polygon for every row instead of
//! keeping active tables. In between, memory trades for speed. Nothing
//! here allocates: the caller lends the buffers.
//!
//! With [`DepthTest::Overwrite`] every covered pixel takes the polygon's
//! colour, whatever its depth: the painter's pass, drawing the polygons in
//! the order given.

use core::ops::Range;

use crate::error::{Error, RenderError};
use crate::raster::active::{ActivePolygon, EdgePool};
use crate::raster::depth::DepthFormat;
use crate::raster::edge::ActiveEdge;
use crate::raster::slots::{OrderedSlots, Slots};
use crate::raster::small::SMALL_TRIANGLES;
use crate::raster::small_table::SmallTable;
use crate::raster::span::{PixelWrite, RowBuffers};
use crate::raster::stats::FrameStats;
use crate::raster::stepping::{ScanState, fill_and_step};
use crate::raster::tables::Prepared;
use crate::sink::RowSink;

/// How a band method writes a covered pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthTest {
    /// Where the polygon is strictly nearer than the buffer holds: the
    /// z-buffer.
    Nearer,
    /// Always: the painter's pass (the last polygon drawn wins).
    Overwrite,
}

/// The buffers of [`render_bands`], lent by the caller: depth and colour for
/// `K` rows, and one row of scratch.
#[derive(Debug)]
pub struct BandBuffers<'a, C, D: DepthFormat> {
    /// At least `K` rows of the frame's width.
    pub depth: &'a mut [D::Value],
    /// As long as `depth`.
    pub color: &'a mut [C],
    /// One row (the frame's width) of scratch.
    pub scratch: &'a mut [u32],
    /// Room for one active polygon.
    pub active: &'a mut [ActivePolygon<C>],
    /// Room for the edges of a concave polygon beyond its first two (as
    /// many as its corners); empty for triangles and convex polygons.
    pub pool: &'a mut [ActiveEdge],
}

/// Counts of one [`render_bands`] frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BandStats {
    /// Bands drawn.
    pub bands: u32,
    /// Polygons visited, summed over the bands (each band looks at every
    /// polygon of the tables).
    pub visits: u32,
    /// Polygons drawn into a band, summed over the bands.
    pub drawn: u32,
    /// What the shared scan machinery counted (spans, edges).
    pub scan: FrameStats,
}

/// Draws the tables band by band, `band_rows` rows at a time, and sends
/// every row to `sink`, top to bottom. `order`, when given, lists the
/// polygons (positions in the tables) in the order to draw them; otherwise
/// they are drawn in the order the tables hold them
/// ([`Tables::in_drawing_order`](crate::raster::Tables::in_drawing_order)).
#[allow(clippy::too_many_arguments)]
pub fn render_bands<C: Copy, D: DepthFormat, K: RowSink<C, D::Value>>(
    tables: &Prepared<'_, C>,
    buffers: BandBuffers<'_, C, D>,
    band_rows: u16,
    background: C,
    test: DepthTest,
    order: Option<&[u32]>,
    sink: &mut K,
) -> Result<BandStats, RenderError<K::Error>> {
    let width = usize::from(tables.width);
    let band_rows = band_rows.clamp(1, tables.height.max(1));
    let band_len = usize::from(band_rows) * width;
    if buffers.depth.len() < band_len
        || buffers.color.len() < band_len
        || buffers.scratch.len() < width
        || buffers.active.is_empty()
    {
        return Err(RenderError::Table(Error::BandBuffersTooSmall));
    }
    let mut pool_len = 0usize;
    // One polygon at a time: one slot, and its order entry.
    let mut slot_order = [0u16; 1];
    let mut state = ScanState {
        tables,
        active: OrderedSlots::new(buffers.active, &mut slot_order),
        pool: EdgePool::new(Slots::new(buffers.pool, &mut pool_len)),
        stats: FrameStats::default(),
        small_triangles: SMALL_TRIANGLES,
        small: SmallTable::new(&mut []),
    };
    let mut stats = BandStats::default();
    let count = order.map_or(tables.polygons.len(), <[u32]>::len);
    let mut y0 = 0u16;
    while y0 < tables.height {
        let y1 = y0.saturating_add(band_rows).min(tables.height);
        let rows = usize::from(y1 - y0) * width;
        buffers.depth[..rows].fill(D::CLEAR);
        buffers.color[..rows].fill(background);
        stats.bands += 1;
        for k in 0..count {
            let position = order.map_or(k, |o| o[k] as usize);
            let Some(polygon) = tables.polygons.get(position) else {
                return Err(RenderError::Table(Error::VertexOutOfRange));
            };
            stats.visits += 1;
            let (r0, r1) = (polygon.first_row.max(y0), polygon.end_row.min(y1));
            if r0 >= r1 {
                continue;
            }
            stats.drawn += 1;
            draw_rows::<C, D>(
                &mut state,
                position,
                r0..r1,
                y0,
                (
                    &mut *buffers.depth,
                    &mut *buffers.color,
                    &mut *buffers.scratch,
                ),
                width,
                test,
            )?;
        }
        for y in y0..y1 {
            let at = usize::from(y - y0) * width;
            sink.write_row(
                y,
                &buffers.color[at..at + width],
                &buffers.depth[at..at + width],
            )
            .map_err(RenderError::Sink)?;
        }
        y0 = y1;
    }
    stats.scan = state.stats;
    Ok(stats)
}

/// The band's row starting at `at`, `width` pixels, as the scanline's row
/// buffers (the scratch row serves as the key row).
fn band_row<'r, C, D: DepthFormat>(
    (depth, color, scratch): (&'r mut [D::Value], &'r mut [C], &'r mut [u32]),
    at: usize,
    width: usize,
    write: PixelWrite,
) -> RowBuffers<'r, C, D> {
    RowBuffers {
        depth: &mut depth[at..at + width],
        color: &mut color[at..at + width],
        key: &mut scratch[..width],
        write,
    }
}

/// Draws rows `rows` of the polygon at `position` into the band starting at
/// row `y0`, with the scanline's own activation and stepping.
fn draw_rows<C: Copy, D: DepthFormat>(
    state: &mut ScanState<'_, '_, C>,
    position: usize,
    rows: Range<u16>,
    y0: u16,
    (depth, color, scratch): (&mut [D::Value], &mut [C], &mut [u32]),
    width: usize,
    test: DepthTest,
) -> Result<(), Error> {
    state.active.clear();
    state.pool.reset();
    let write = match test {
        DepthTest::Nearer => PixelWrite::Nearer,
        DepthTest::Overwrite => PixelWrite::Overwrite,
    };
    // Row `y` of the band, as the scanline's row buffers.
    let at = |y: u16| usize::from(y - y0) * width;
    let mut y = rows.start;
    state.activate_polygon::<D, true>(
        position,
        y,
        &mut band_row::<C, D>((depth, color, scratch), at(y), width, write),
    )?;
    let Some(is_triangle) = state.active.first_mut().map(|entry| entry.is_triangle()) else {
        // A triangle covering one row was drawn at activation.
        return Ok(());
    };
    while y < rows.end {
        let mut buffers = band_row::<C, D>((depth, color, scratch), at(y), width, write);
        let next = y + 1;
        let (tables, pool, stats) = (state.tables, &mut state.pool, &mut state.stats);
        let Some(entry) = state.active.first_mut() else {
            break;
        };
        let alive = fill_and_step::<C, D, false>(entry, tables, pool, stats, y, &mut buffers);
        if !alive || next >= rows.end {
            break;
        }
        // A triangle switched its short edge in `fill_and_step`; another
        // polygon takes the edge table's work: edges starting on the next
        // row join.
        if !is_triangle {
            state.activate_edges(0, next, false)?;
        }
        y = next;
    }
    Ok(())
}
