//! Painted scans: shading after visibility. The scan writes, for each
//! pixel, the slot in the active polygon table of the polygon that wins
//! it (instead of a colour), and once a row's spans are all written a
//! [`RowPainter`] turns each run of pixels one polygon won into colours,
//! from that polygon's attribute planes ([`crate::raster::attribute`]):
//! so each visible pixel is shaded once, however many polygons covered it,
//! and every polygon shape, band and depth format paints alike.
//!
//! A polygon's slot is its own from the row it enters to the row it
//! leaves, and a slot left on one row is reused only when another polygon
//! enters on a later row, after that row has been painted; so a slot
//! written in a row names the polygon that wrote it when the row is
//! painted. Every polygon takes a slot, even one that covers one row (the
//! flat scan draws those at once, with none).

use core::ops::Range;

use crate::error::{Error, RenderError};
use crate::raster::active::EdgePool;
use crate::raster::depth::DepthFormat;
use crate::raster::scan::{ScanParts, ScanStorage, Scanner, columns_written};
use crate::raster::slots::{OrderedSlots, Slots};
use crate::raster::small::SMALL_TRIANGLES;
use crate::raster::small_table::SmallTable;
use crate::raster::span::{PixelWrite, RowBuffers};
use crate::raster::stats::FrameStats;
use crate::raster::stepping::ScanState;
use crate::raster::tables::Prepared;
use crate::sink::{LentRow, RowSink};

/// The value a painted scan's slot row holds where no polygon covers the
/// pixel.
pub const NO_SLOT: u16 = u16::MAX;

/// Turns a painted scan's rows of slots into colours: learns which
/// polygon enters each slot, and paints each row once its spans are
/// written.
pub trait RowPainter {
    /// The colour of the rows the sink receives.
    type Color: Copy;

    /// The polygon at `position` of the prepared tables entered APT slot
    /// `slot` on row `row`: its pixels in the rows it covers from there
    /// are painted from it.
    fn enter(&mut self, slot: usize, position: usize, row: u16, tables: &Prepared<'_, u16>);

    /// Paints row `row`: `out[x]` from the polygon in slot `slots[x]`, or
    /// the background where it is [`NO_SLOT`] (there `out` holds the
    /// background already when `filled`). `slots` and `out` have the
    /// frame's width.
    fn paint(
        &mut self,
        row: u16,
        slots: &[u16],
        tables: &Prepared<'_, u16>,
        out: &mut [Self::Color],
        filled: bool,
    );

    /// [`Self::paint`], told that every slot outside `columns` is
    /// [`NO_SLOT`] (the scan wrote nothing there), so that a painter need
    /// not look at them. The default paints the whole row.
    fn paint_columns(
        &mut self,
        row: u16,
        slots: &[u16],
        tables: &Prepared<'_, u16>,
        out: &mut [Self::Color],
        filled: bool,
        columns: Range<usize>,
    ) {
        let _ = columns;
        self.paint(row, slots, tables, out, filled);
    }

    /// The colour of pixels no polygon covers.
    fn background(&self) -> Self::Color;

    /// How many APT slots and vertex values this painter holds:
    /// [`scan_painted`] refuses a scanner with more slots or tables with
    /// more vertices ([`Error::PaintStorageTooSmall`]). Unbounded unless a
    /// painter says otherwise.
    fn capacity(&self) -> (usize, usize) {
        (usize::MAX, usize::MAX)
    }
}

/// Scans `rows` (clipped to the frame) of prepared tables with `scanner`,
/// whose colour row holds slots, paints each finished row with `painter`
/// into the sink's lent row or `own_row`, and sends it to `sink`: as
/// [`scan`](crate::raster::scan::scan), with shading after visibility.
///
/// Bands scanned by several scanners, each with its own painter, give
/// exactly the rows one scanner over the whole frame gives.
pub fn scan_painted<S, P, K>(
    tables: &Prepared<'_, u16>,
    scanner: &mut Scanner<S>,
    painter: &mut P,
    own_row: &mut [P::Color],
    rows: Range<u16>,
    sink: &mut K,
) -> Result<FrameStats, RenderError<K::Error>>
where
    S: ScanStorage<Color = u16>,
    P: RowPainter,
    K: RowSink<P::Color, <S::Depth as DepthFormat>::Value>,
{
    let parts = scanner.storage_mut().parts_mut();
    // (A slot is a `u16` below NO_SLOT, so no more than 2^16 are used.)
    let (slots, values) = painter.capacity();
    if slots < parts.active.len().min(1 << 16) || values < tables.vertices.len() {
        return Err(RenderError::Table(Error::PaintStorageTooSmall));
    }
    painted_rows::<S::Depth, P, K>(tables, parts, painter, own_row, rows, sink)
}

/// [`scan_painted`] for a painter whose capacity its owner has checked
/// already (a [`PaintedRenderer`](crate::paint::PaintedRenderer), whose
/// storage was checked when it was made).
pub(crate) fn scan_painted_prechecked<S, P, K>(
    tables: &Prepared<'_, u16>,
    scanner: &mut Scanner<S>,
    painter: &mut P,
    own_row: &mut [P::Color],
    rows: Range<u16>,
    sink: &mut K,
) -> Result<FrameStats, RenderError<K::Error>>
where
    S: ScanStorage<Color = u16>,
    P: RowPainter,
    K: RowSink<P::Color, <S::Depth as DepthFormat>::Value>,
{
    let parts = scanner.storage_mut().parts_mut();
    painted_rows::<S::Depth, P, K>(tables, parts, painter, own_row, rows, sink)
}

/// [`scan_painted`], capacity-erased.
fn painted_rows<D: DepthFormat, P: RowPainter, K: RowSink<P::Color, D::Value>>(
    tables: &Prepared<'_, u16>,
    parts: ScanParts<'_, u16, D>,
    painter: &mut P,
    own_row: &mut [P::Color],
    rows: Range<u16>,
    sink: &mut K,
) -> Result<FrameStats, RenderError<K::Error>> {
    if !tables.scannable {
        return Err(RenderError::Table(Error::NotPrepared));
    }
    let width = usize::from(tables.width);
    let too_narrow = [
        parts.depth_row.len(),
        parts.color_row.len(),
        parts.key_row.len(),
        own_row.len(),
    ]
    .iter()
    .any(|&len| width > len);
    if too_narrow {
        return Err(RenderError::Table(Error::BadFrameSize));
    }
    let mut pool_len = 0usize;
    let mut state = ScanState {
        tables,
        active: OrderedSlots::new(parts.active, parts.order),
        pool: EdgePool::new(Slots::new(parts.pool, &mut pool_len)),
        stats: tables.frame_stats(),
        small_triangles: SMALL_TRIANGLES,
        small: SmallTable::new(&mut []),
    };
    let (depth_row, slot_row, key_row, own_row) = (
        &mut parts.depth_row[..width],
        &mut parts.color_row[..width],
        &mut parts.key_row[..width],
        &mut own_row[..width],
    );
    let (first, end) = (rows.start.min(tables.height), rows.end.min(tables.height));
    let polygons = tables.polygons;
    let mut next_polygon = polygons.partition_point(|p| p.first_row < first);
    let mut next_edge = tables.edges.partition_point(|e| e.row() <= first);
    // The columns any polygon can write: outside them every row's slots
    // stay NO_SLOT, which the painter need not look at.
    let columns = columns_written(tables, width);
    // Whether the depth and slot rows may hold anything but CLEAR and
    // NO_SLOT: a row scanned with no polygon active writes neither (here
    // activation draws nothing), so the next row needs no clear.
    let mut rows_dirty = true;
    for row in first..end {
        if rows_dirty {
            depth_row.fill(D::CLEAR);
            slot_row.fill(NO_SLOT);
        }
        let mut row_buffers = RowBuffers::<u16, D> {
            depth: &mut *depth_row,
            color: &mut *slot_row,
            key: &mut *key_row,
            write: PixelWrite::NearerOrFirstAdded,
        };
        // New entries join the live slots at the end of the order array.
        let entered = state.active.len();
        if row == first {
            for (position, polygon) in polygons[..next_polygon].iter().enumerate() {
                if polygon.end_row > first {
                    state.activate_polygon::<D, false>(position, first, &mut row_buffers)?;
                }
            }
        }
        while polygons
            .get(next_polygon)
            .is_some_and(|p| p.first_row == row)
        {
            state.activate_polygon::<D, false>(next_polygon, row, &mut row_buffers)?;
            next_polygon += 1;
        }
        for k in entered..state.active.len() {
            let slot = usize::from(state.active.live_slots()[k]);
            if let Some(entry) = state.active.get_mut(slot) {
                // Its pixels hold its slot.
                entry.color = slot as u16;
                painter.enter(slot, entry.position as usize, row, tables);
            }
        }
        // (Without the `polygons` feature the edge table is empty.)
        while cfg!(feature = "polygons")
            && let Some(entry) = tables.edges.get(next_edge).filter(|e| e.row() == row)
        {
            next_edge += 1;
            let slot = state
                .find_slot(entry.position() as u32)
                .ok_or(Error::ActivePolygonsFull { row })?;
            state.activate_edges(slot, row, false)?;
        }
        state.note_peaks();
        // A row no polygon is active on holds no slot.
        rows_dirty = state.active.len() != 0;
        let painted = if rows_dirty { columns.clone() } else { 0..0 };
        state.scan_row(row, &mut row_buffers)?;
        let lent = sink
            .lend_row(row, width, painter.background())
            .map_err(RenderError::Sink)?;
        match lent {
            Some(LentRow { colors, filled }) => {
                let colors = colors
                    .get_mut(..width)
                    .ok_or(RenderError::Table(Error::BadFrameSize))?;
                painter.paint_columns(row, slot_row, tables, colors, filled, painted);
                sink.send_lent_row(row, depth_row)
            }
            None => {
                painter.paint_columns(row, slot_row, tables, own_row, false, painted);
                sink.write_row(row, own_row, depth_row)
            }
        }
        .map_err(RenderError::Sink)?;
    }
    Ok(state.stats)
}
