//! The row-sized half of the scanline z-buffer: the active polygon table
//! (APT), the pool of further active edges (AET), and one row of depth and
//! one of colour; and [`scan`], which runs them over [`Prepared`] tables
//! and hands each finished row to a [`RowSink`].
//!
//! For each row `y` of the band scanned:
//! * polygons whose first row is `y` enter the APT with their plane's
//!   gradients `dz/dx = -a/c`, `dz/dy = -b/c` and value at the row, and
//!   the edges covering `y`;
//! * edges of the ET bucket `y` join their polygon; a triangle's lower
//!   short edge joins it by itself on its `switch_row`;
//! * each active polygon fills its spans (crossings paired even-odd), depth
//!   starting from the plane at each span's first pixel and stepping by
//!   `dz/dx`, written where nearer than the row holds; then its edges step
//!   to the next row;
//! * the finished row goes to the sink.
//!
//! A band that starts below a polygon's first row activates it there, with
//! the edges covering that row: so two scanners over one set of tables
//! (two threads, or two cores) produce exactly the rows one would.
//!
//! This file is the driver: the scanner's storage and [`scan`], whose row
//! loop clears each row, activates what starts on it
//! ([`activation`](super::activation)), steps the active polygons through
//! it ([`stepping`](super::stepping), which fills their spans through
//! [`span`](super::span)) and sends it.

use core::ops::Range;

use crate::error::{Error, RenderError};
use crate::raster::active::{ActivePolygon, EdgePool};
use crate::raster::depth::DepthFormat;
use crate::raster::edge::ActiveEdge;
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::slots::{OrderedSlots, Slots};
use crate::raster::small::SMALL_TRIANGLES;
use crate::raster::small_table::{SmallActive, SmallTable};
use crate::raster::span::{PixelWrite, RowBuffers};
use crate::raster::stats::FrameStats;
use crate::raster::stepping::ScanState;
use crate::raster::tables::Prepared;
use crate::sink::{LentRow, RowSink};

/// Where a scanner's arrays live: the active polygon table, the edge pool
/// and the two rows. [`ScanArrays`] holds them in fixed arrays; the host's
/// `zline::host::ScanVecs` in `Vec`s.
pub trait ScanStorage {
    /// The pixel colour.
    type Color: Copy;
    /// The depth format of the depth row.
    type Depth: DepthFormat;
    /// The arrays, mutably.
    fn parts_mut(&mut self) -> ScanParts<'_, Self::Color, Self::Depth>;
}

/// The arrays of a [`ScanStorage`].
#[derive(Debug)]
pub struct ScanParts<'a, C, D: DepthFormat> {
    /// The active polygon table.
    pub active: &'a mut [ActivePolygon<C>],
    /// Which slots of the active polygon table are in use (rewritten at
    /// the start of every scan; as long as `active`). The table has as
    /// many slots as the shorter of the two, and at most 2^16.
    pub order: &'a mut [u16],
    /// Active edges beyond each polygon's first two.
    pub pool: &'a mut [ActiveEdge],
    /// Small triangles waiting for their next rows, on targets that draw
    /// small triangles from coverage masks (not 32-bit Arm). It may be
    /// empty, or shorter than the active polygon table: a small triangle
    /// that finds no room here waits in the active polygon table.
    pub small: &'a mut [SmallActive<C>],
    /// The depth row (its length is the widest frame it can scan).
    pub depth_row: &'a mut [D::Value],
    /// The colour row (as long as the depth row).
    pub color_row: &'a mut [C],
    /// The tie-break keys of the pixels (as long as the depth row).
    pub key_row: &'a mut [u32],
}

/// Fixed-capacity storage for a scanner: rows of `W` pixels, up to `AP`
/// polygons active on one row and `AE` active edges beyond each polygon's
/// first two (none for triangles and convex polygons). Build it in a
/// `static` on a microcontroller (its constructor is `const`). Where small
/// triangles are drawn from coverage masks (every target but 32-bit Arm)
/// it also holds `AP` entries of the small triangles' own table
/// ([`ScanParts::small`]); a Cortex-M build has none.
#[derive(Debug, Clone)]
pub struct ScanArrays<C, D: DepthFormat, const W: usize, const AP: usize, const AE: usize> {
    active: [ActivePolygon<C>; AP],
    order: [u16; AP],
    pool: [ActiveEdge; AE],
    #[cfg(not(target_arch = "arm"))]
    small: [SmallActive<C>; AP],
    depth_row: [D::Value; W],
    color_row: [C; W],
    key_row: [u32; W],
}

impl<C: Copy, D: DepthFormat, const W: usize, const AP: usize, const AE: usize>
    ScanArrays<C, D, W, AP, AE>
{
    /// Empty storage; `filler` fills the unused slots (any colour).
    pub const fn new(filler: C) -> Self {
        Self {
            active: [ActivePolygon::filler(filler); AP],
            order: [0; AP],
            pool: [ActiveEdge::EMPTY; AE],
            #[cfg(not(target_arch = "arm"))]
            small: [SmallActive::filler(filler); AP],
            depth_row: [D::CLEAR; W],
            color_row: [filler; W],
            key_row: [0; W],
        }
    }
}

impl<C: Copy, D: DepthFormat, const W: usize, const AP: usize, const AE: usize> ScanStorage
    for ScanArrays<C, D, W, AP, AE>
{
    type Color = C;
    type Depth = D;

    fn parts_mut(&mut self) -> ScanParts<'_, C, D> {
        ScanParts {
            active: &mut self.active,
            order: &mut self.order,
            pool: &mut self.pool,
            #[cfg(not(target_arch = "arm"))]
            small: &mut self.small,
            #[cfg(target_arch = "arm")]
            small: &mut [],
            depth_row: &mut self.depth_row,
            color_row: &mut self.color_row,
            key_row: &mut self.key_row,
        }
    }
}

/// A scanner: the row-sized state of the scanline z-buffer over some
/// [`ScanStorage`], and the colour of pixels no polygon covers.
#[derive(Clone)]
pub struct Scanner<S: ScanStorage> {
    storage: S,
    background: S::Color,
}

impl<S> core::fmt::Debug for Scanner<S>
where
    S: ScanStorage + core::fmt::Debug,
    S::Color: core::fmt::Debug,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Scanner")
            .field("storage", &self.storage)
            .field("background", &self.background)
            .finish()
    }
}

impl<S: ScanStorage> Scanner<S> {
    /// A scanner over `storage`, clearing to `background`.
    pub const fn new(storage: S, background: S::Color) -> Self {
        Self {
            storage,
            background,
        }
    }

    /// Colour of pixels no polygon covers.
    pub fn set_background(&mut self, background: S::Color) {
        self.background = background;
    }

    /// The widest frame this scanner can scan.
    pub fn row_capacity(&mut self) -> usize {
        self.storage.parts_mut().depth_row.len()
    }

    /// Its storage.
    pub(crate) fn storage_mut(&mut self) -> &mut S {
        &mut self.storage
    }
}

/// Scans `rows` (clipped to the frame) of prepared tables with `scanner`
/// and sends each finished row to `sink`, one call per row, top to bottom.
///
/// Several scanners may scan disjoint bands of the same prepared tables;
/// the rows they send are exactly those one scanner over the whole frame
/// would send.
pub fn scan<S, K>(
    tables: &Prepared<'_, S::Color>,
    scanner: &mut Scanner<S>,
    rows: Range<u16>,
    sink: &mut K,
) -> Result<FrameStats, RenderError<K::Error>>
where
    S: ScanStorage,
    K: RowSink<S::Color, <S::Depth as DepthFormat>::Value>,
{
    let background = scanner.background;
    let parts = scanner.storage.parts_mut();
    scan_rows::<S::Color, S::Depth, K>(tables, parts, background, (rows, SMALL_TRIANGLES), sink)
}

/// [`scan`] with small triangles drawn from coverage masks or not (the
/// rows are the same; the tests compare them).
#[cfg(test)]
pub(crate) fn scan_small_as<S, K>(
    tables: &Prepared<'_, S::Color>,
    scanner: &mut Scanner<S>,
    rows: Range<u16>,
    small_triangles: bool,
    sink: &mut K,
) -> Result<FrameStats, RenderError<K::Error>>
where
    S: ScanStorage,
    K: RowSink<S::Color, <S::Depth as DepthFormat>::Value>,
{
    let background = scanner.background;
    let parts = scanner.storage.parts_mut();
    scan_rows::<S::Color, S::Depth, K>(tables, parts, background, (rows, small_triangles), sink)
}

/// [`scan`], capacity-erased: compiled once per colour, depth format and
/// sink. (With the `profile` feature it is kept out of line: the
/// profile's whole scan.)
#[cfg_attr(feature = "profile", inline(never))]
fn scan_rows<C: Copy, D: DepthFormat, K: RowSink<C, D::Value>>(
    tables: &Prepared<'_, C>,
    parts: ScanParts<'_, C, D>,
    background: C,
    (rows, small_triangles): (Range<u16>, bool),
    sink: &mut K,
) -> Result<FrameStats, RenderError<K::Error>> {
    if !tables.scannable {
        return Err(RenderError::Table(Error::NotPrepared));
    }
    let width = usize::from(tables.width);
    if width > parts.depth_row.len() || width > parts.color_row.len() || width > parts.key_row.len()
    {
        return Err(RenderError::Table(Error::BadFrameSize));
    }
    let mut pool_len = 0usize;
    let mut state = ScanState {
        tables,
        active: OrderedSlots::new(parts.active, parts.order),
        pool: EdgePool::new(Slots::new(parts.pool, &mut pool_len)),
        stats: tables.frame_stats(),
        small_triangles,
        small: SmallTable::new(parts.small),
    };
    let (depth_row, own_colors, key_row) = (
        &mut parts.depth_row[..width],
        &mut parts.color_row[..width],
        &mut parts.key_row[..width],
    );
    let (first, end) = (rows.start.min(tables.height), rows.end.min(tables.height));
    let polygons = tables.polygons;
    let mut next_polygon = polygons.partition_point(|p| p.first_row < first);
    // Edge-table entries at or above the band's first row are covered by
    // the activation there.
    let mut next_edge = tables.edges.partition_point(|e| e.row() <= first);
    // The columns polygons can write (found when first needed: a sink
    // that lends every row never needs them), and the part of the
    // scanner's own colour row that may not hold the background: all of
    // it before its first use, then those columns.
    let mut written = None;
    let mut own_dirty = 0..width;
    // Whether the depth row may hold anything but CLEAR: a row scanned
    // with no polygon active writes no depth, so the next row needs no
    // clear (rows above and below a small object cost no `memset`).
    let mut depth_dirty = true;
    for row in first..end {
        // The key row needs no clearing: a key is compared only where the
        // stored depth equals the new one and is not CLEAR, that is where
        // this row has written it (see `fill_span`).
        if depth_dirty {
            depth_row.fill(D::CLEAR);
        }
        // The sink's own buffer when it lends one (no copy of the row),
        // else the scanner's colour row.
        let lent = sink
            .lend_row(row, width, background)
            .map_err(RenderError::Sink)?;
        let is_lent = lent.is_some();
        let color = match lent {
            Some(LentRow { colors, filled }) => {
                let colors = colors
                    .get_mut(..width)
                    .ok_or(RenderError::Table(Error::BadFrameSize))?;
                if !filled {
                    clear_color_row(colors, background);
                }
                colors
            }
            None => {
                let columns = written.get_or_insert_with(|| columns_written(tables, width));
                clear_color_row(
                    &mut own_colors[core::mem::replace(&mut own_dirty, columns.clone())],
                    background,
                );
                &mut *own_colors
            }
        };
        let mut row_buffers = RowBuffers::<C, D> {
            depth: &mut *depth_row,
            color,
            key: &mut *key_row,
            write: PixelWrite::NearerOrFirstAdded,
        };
        // Activation may draw a polygon's row at once (a one-row or small
        // triangle), so a row that activates any counts as written.
        let mut activated = false;
        if row == first {
            // Polygons that started above the band and reach into it enter
            // at its first row, with the edges covering it.
            for (position, polygon) in polygons[..next_polygon].iter().enumerate() {
                if polygon.end_row > first {
                    activated = true;
                    state.activate_polygon::<D, true>(position, first, &mut row_buffers)?;
                }
            }
        }
        while polygons
            .get(next_polygon)
            .is_some_and(|p| p.first_row == row)
        {
            activated = true;
            state.activate_polygon::<D, true>(next_polygon, row, &mut row_buffers)?;
            next_polygon += 1;
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
        depth_dirty = activated || state.any_active();
        state.scan_row(row, &mut row_buffers)?;
        if is_lent {
            sink.send_lent_row(row, depth_row)
        } else {
            sink.write_row(row, own_colors, depth_row)
        }
        .map_err(RenderError::Sink)?;
    }
    Ok(state.stats)
}

/// The columns of a frame (`width` wide) that polygons of `tables` can
/// write: those whose samples lie between the vertex table's leftmost and
/// rightmost x, as every polygon's corners are there. (A pixel is written
/// only where its sample lies inside a polygon.) Columns outside keep what
/// they were cleared to, so the scanner clears its own colour row only
/// there after its first use: on the torus knot at 240x240, 74 % of the
/// row (`cargo qemu-m4f`: 8,920 fewer instructions a frame, `cargo qemu`
/// 12,080; the icosphere, which fills the frame, 14,680 and 3,880 more).
/// Rows are not bounded as well: on the Cortex-M0+ the pass over the
/// vertices' y cost the icosphere 32,000 more. The depth row is cleared
/// whole: a `memset` from an unaligned column took more instructions than
/// the whole row's.
pub(crate) fn columns_written<C>(tables: &Prepared<'_, C>, width: usize) -> Range<usize> {
    let (mut x0, mut x1) = (i32::MAX, i32::MIN);
    for v in tables.vertices {
        (x0, x1) = (x0.min(v.x), x1.max(v.x));
    }
    // The first sample at or after the leftmost x, and the first after the
    // rightmost. (An empty table leaves the range empty.)
    let column = |x: i32| first_sample_at_or_after(x).clamp(0, width as i32) as usize;
    let start = column(x0);
    start..column(x1.saturating_add(1)).max(start)
}

/// Clears the colour row to `background`; out of line so that the colour
/// stays in a register (inlined into the row loop, a Cortex-M0+ reloaded
/// it from the stack every four pixels). The depth row's constant fill is
/// left inline, where it becomes a `memset`. Copied a block of eight
/// pixels at a time, the loop is unrolled (on the Cortex-M4F, 32 pixel
/// stores a turn), so its counting and branching cost far less a pixel
/// than `fill`'s: 2.1 % of the M4F's torus-knot frame, 0.7-1.3 % of the
/// M0+'s. On 64-bit hosts the block is 32 pixels: half the instructions
/// a row of eight took (callgrind, `zju_planes` at 240x240: 23,000 a
/// frame instead of 50,000).
#[inline(never)]
fn clear_color_row<C: Copy>(row: &mut [C], background: C) {
    const BLOCK: usize = if cfg!(target_pointer_width = "64") {
        32
    } else {
        8
    };
    let block = [background; BLOCK];
    let mut chunks = row.chunks_exact_mut(BLOCK);
    for chunk in &mut chunks {
        chunk.copy_from_slice(&block);
    }
    chunks.into_remainder().fill(background);
}
