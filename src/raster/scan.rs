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

use core::ops::Range;

use crate::arith::wide::{cross, mul_i64_small};
use crate::error::{Error, RenderError};
use crate::raster::BRANCH_FREE;
use crate::raster::active::{ActivePolygon, EdgePool, NO_EDGE, NO_ROW, SpanDepth};
use crate::raster::depth::{DepthFormat, IN_RANGE};
use crate::raster::edge::ActiveEdge;
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::lanes::{LANES, block, fill_block};
use crate::raster::plane::{Plane, TrianglePlane};
use crate::raster::slots::{OrderedSlots, Slots};
use crate::raster::tables::{PolygonEntry, Prepared, entry_corner_ids};
use crate::raster::vertex::{ScreenVertex, TriangleTest};
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
/// `static` on a microcontroller (its constructor is `const`).
#[derive(Debug, Clone)]
pub struct ScanArrays<C, D: DepthFormat, const W: usize, const AP: usize, const AE: usize> {
    active: [ActivePolygon<C>; AP],
    order: [u16; AP],
    pool: [ActiveEdge; AE],
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
}

/// Counts for one rendered frame (or band of rows).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrameStats {
    /// Vertices in the vertex table.
    pub vertices: u32,
    /// Polygon corners stored.
    pub corners: u32,
    /// Polygons in the polygon table.
    pub polygons: u32,
    /// Edges that entered the active edge table.
    pub edges: u32,
    /// Largest number of polygons active on one row.
    pub peak_active_polygons: u32,
    /// Largest number of edges active on one row.
    pub peak_active_edges: u32,
    /// Largest number of those held in the edge pool, beyond each
    /// polygon's inline pair (zero for triangles and other convex
    /// polygons). A polygon pools only the edges beyond two that cover
    /// the row, so a scan of any band of the frame's rows needs no more
    /// than one scan of the whole frame.
    pub peak_pooled_edges: u32,
    /// Spans filled.
    pub spans: u32,
    /// Polygons offered but left out as off-screen.
    pub off_screen: u32,
    /// Polygons offered but left out as zero-area.
    pub degenerate: u32,
}

impl FrameStats {
    /// The larger of each peak and count of `self` and `other` (to size
    /// capacities over several frames, or add up bands).
    pub fn max(self, other: Self) -> Self {
        Self {
            vertices: self.vertices.max(other.vertices),
            corners: self.corners.max(other.corners),
            polygons: self.polygons.max(other.polygons),
            edges: self.edges.max(other.edges),
            peak_active_polygons: self.peak_active_polygons.max(other.peak_active_polygons),
            peak_active_edges: self.peak_active_edges.max(other.peak_active_edges),
            peak_pooled_edges: self.peak_pooled_edges.max(other.peak_pooled_edges),
            spans: self.spans.max(other.spans),
            off_screen: self.off_screen.max(other.off_screen),
            degenerate: self.degenerate.max(other.degenerate),
        }
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
    scan_rows::<S::Color, S::Depth, K>(tables, scanner.storage.parts_mut(), background, rows, sink)
}

/// [`scan`], capacity-erased: compiled once per colour, depth format and
/// sink. (With the `profile` feature it is kept out of line: the
/// profile's whole scan.)
#[cfg_attr(feature = "profile", inline(never))]
fn scan_rows<C: Copy, D: DepthFormat, K: RowSink<C, D::Value>>(
    tables: &Prepared<'_, C>,
    parts: ScanParts<'_, C, D>,
    background: C,
    rows: Range<u16>,
    sink: &mut K,
) -> Result<FrameStats, RenderError<K::Error>> {
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
        stats: FrameStats {
            vertices: tables.vertices.len() as u32,
            corners: tables.corners.len() as u32,
            polygons: tables.polygons.len() as u32,
            off_screen: tables.off_screen,
            degenerate: tables.degenerate,
            ..FrameStats::default()
        },
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
    for row in first..end {
        // The key row needs no clearing: a key is compared only where the
        // stored depth equals the new one and is not CLEAR, that is where
        // this row has written it (see `fill_span`).
        depth_row.fill(D::CLEAR);
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
                clear_color_row(own_colors, background);
                &mut *own_colors
            }
        };
        let mut row_buffers = RowBuffers::<C, D> {
            depth: &mut *depth_row,
            color,
            key: &mut *key_row,
            write: PixelWrite::NearerOrFirstAdded,
        };
        if row == first {
            // Polygons that started above the band and reach into it enter
            // at its first row, with the edges covering it.
            for (position, polygon) in polygons[..next_polygon].iter().enumerate() {
                if polygon.end_row > first {
                    state.activate_polygon(position, first, &mut row_buffers)?;
                }
            }
        }
        while polygons
            .get(next_polygon)
            .is_some_and(|p| p.first_row == row)
        {
            state.activate_polygon(next_polygon, row, &mut row_buffers)?;
            next_polygon += 1;
        }
        while let Some(entry) = tables.edges.get(next_edge).filter(|e| e.row() == row) {
            next_edge += 1;
            let position = entry.position() as u32;
            let slot = state
                .active
                .live_slots()
                .iter()
                .map(|&slot| usize::from(slot))
                .find(|&slot| {
                    state
                        .active
                        .get(slot)
                        .is_some_and(|a| a.position == position)
                })
                .ok_or(Error::ActivePolygonsFull { row })?;
            state.activate_edges(slot, row, false)?;
        }
        state.note_peaks();
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

/// Clears the colour row to `background`; out of line so that the colour
/// stays in a register (inlined into the row loop, a Cortex-M0+ reloaded
/// it from the stack every four pixels). The depth row's constant fill is
/// left inline, where it becomes a `memset`.
#[inline(never)]
fn clear_color_row<C: Copy>(row: &mut [C], background: C) {
    row.fill(background);
}

/// The row being built: depth, colour and tie-break key per pixel.
pub(crate) struct RowBuffers<'a, C, D: DepthFormat> {
    pub depth: &'a mut [D::Value],
    pub color: &'a mut [C],
    pub key: &'a mut [u32],
    /// How a covered pixel is written: the scanline's test, or the other
    /// methods' ([`crate::raster::zbuffer`]).
    pub write: PixelWrite,
}

impl<C: Copy, D: DepthFormat> RowBuffers<'_, C, D> {
    /// Fills pixels `[start, end)` (clamped to the row) of a triangle that
    /// stays in range (see [`IN_RANGE`]): depths from the accumulator,
    /// placed at the first pixel from the row's column-0 value
    /// ([`DepthFormat::accumulator_at`]), with no range check, no rounding
    /// and no call per span, on a host in branch-free blocks
    /// ([`crate::raster::lanes`]); whether any pixel was in the row. (With
    /// the `profile` feature it is kept out of line: the profile's "spans"
    /// stage.)
    #[cfg_attr(feature = "profile", inline(never))]
    #[cfg_attr(not(feature = "profile"), inline(always))]
    fn fill_in_range(
        &mut self,
        start: i32,
        end: i32,
        key: u32,
        color: C,
        accumulator_at: impl FnOnce(i32) -> (D::Accum, D::Accum),
    ) -> bool {
        let width = self.depth.len() as i32;
        let (start, end) = (start.max(0), end.min(width));
        if start >= end {
            return false;
        }
        let (first, last) = (start as usize, end as usize);
        let (mut acc, step) = accumulator_at(start);
        if self.write != PixelWrite::NearerOrFirstAdded {
            // The other methods' rules, out of line: the scanline's span
            // loop stays as it was.
            let (depths, colors) = (&mut self.depth[first..last], &mut self.color[first..last]);
            other_rule_in_range::<C, D>(depths, colors, color, (acc, step), self.write);
            return true;
        }
        let mut first = first;
        if BRANCH_FREE {
            // Blocks while the row holds one from `first` (see `lanes`);
            // the scalar loop below finishes a span near the row's end.
            while let Some((depths, keys, colors)) = block(self.depth, self.key, self.color, first)
            {
                fill_block::<C, D>(
                    depths,
                    keys,
                    colors,
                    last - first,
                    (key, color),
                    (acc, step),
                );
                first += LANES;
                if first >= last {
                    return true;
                }
                // Stepped here, not returned by the block: LLVM folds
                // these into one `acc + LANES·step` apart from the lanes'
                // chain, and a returned accumulator measured 10 % slower
                // in the peers bench.
                for _ in 0..LANES {
                    acc = D::advance(acc, step);
                }
            }
        }
        let (depths, keys, colors) = (
            &mut self.depth[first..last],
            &mut self.key[first..last],
            &mut self.color[first..last],
        );
        for ((stored, stored_key), pixel) in depths.iter_mut().zip(keys).zip(colors) {
            let depth = D::value(acc);
            if depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key) {
                *stored = depth;
                *stored_key = key;
                *pixel = color;
            }
            acc = D::advance(acc, step);
        }
        true
    }

    /// Fills pixels `[start, end)` (clamped to the row) of a polygon with a
    /// shared plane: depths from `row_value + dz_dx · x`, each rounded on
    /// its own ([`SpanDepth::Shared`]); whether any pixel was in the row.
    /// Out of line: shared planes are rare, and the other fills stay as
    /// they are.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn fill_shared(
        &mut self,
        start: i32,
        end: i32,
        key: u32,
        color: C,
        row_value: i64,
        dz_dx: i64,
    ) -> bool {
        let width = self.depth.len() as i32;
        let (start, end) = (start.clamp(0, width), end.clamp(0, width));
        if start >= end {
            return false;
        }
        let range = start as usize..end as usize;
        let slices = (
            &mut self.depth[range.clone()],
            &mut self.color[range.clone()],
            &mut self.key[range],
        );
        // |dz_dx| < 2^40, start < 2^12, |row_value| < 2^57: no overflow.
        let value = row_value + mul_i64_small(dz_dx, start);
        let pixel = (key, color);
        match self.write {
            PixelWrite::NearerOrFirstAdded => {
                round_each_pixel::<C, D, NEARER_OR_FIRST_ADDED>(slices, value, dz_dx, pixel)
            }
            PixelWrite::Nearer => round_each_pixel::<C, D, NEARER>(slices, value, dz_dx, pixel),
            PixelWrite::Overwrite => {
                round_each_pixel::<C, D, OVERWRITE>(slices, value, dz_dx, pixel)
            }
        }
        true
    }

    /// Fills pixels `[start, end)` (clamped to the row) of a polygon with
    /// `key` and `color`, depths from `source`; whether any pixel was in
    /// the row. (With the `profile` feature it is kept out of line: the
    /// profile's "spans" stage.)
    #[cfg_attr(feature = "profile", inline(never))]
    fn fill(&mut self, start: i32, end: i32, key: u32, color: C, source: &SpanSource) -> bool {
        let width = self.depth.len() as i32;
        let (start, end) = (start.clamp(0, width), end.clamp(0, width));
        if start >= end {
            return false;
        }
        let range = start as usize..end as usize;
        let (depths, colors, keys) = (
            &mut self.depth[range.clone()],
            &mut self.color[range.clone()],
            &mut self.key[range],
        );
        if self.write == PixelWrite::NearerOrFirstAdded {
            fill_span::<C, D, NEARER_OR_FIRST_ADDED>(
                depths,
                colors,
                keys,
                start,
                (key, color),
                source,
            );
        } else {
            // The other methods' rules, out of line: one copy of the span
            // loops per rule, so no pixel tests it, and the scanline's
            // stays as it was.
            other_rule_span::<C, D>(
                depths,
                colors,
                keys,
                start,
                (key, color),
                source,
                self.write,
            );
        }
        true
    }
}

/// The plane of a polygon that shares one
/// ([`Tables::share_plane`](crate::raster::Tables::share_plane)): the
/// triangle of the three corners after its own.
#[inline(never)]
pub(crate) fn shared_plane_of<C>(
    polygon: &PolygonEntry<C>,
    corners: &[u16],
    vertices: &[ScreenVertex],
) -> Option<Plane> {
    let start = polygon.shared_plane()?;
    let corner = |k: usize| vertices[usize::from(corners[start + k])];
    Plane::triangle(corner(0), corner(1), corner(2))
}

/// The exact plane a polygon's depth comes from: the plane it shares, or
/// Newell's over its own corners.
pub(crate) fn polygon_plane<C>(
    polygon: &PolygonEntry<C>,
    corners: &[u16],
    vertices: &[ScreenVertex],
) -> Option<Plane> {
    match polygon.shared_plane() {
        Some(_) => shared_plane_of(polygon, corners, vertices),
        None => Plane::new(entry_corners(polygon, corners, vertices)),
    }
}

/// The depth set-up of a polygon with a shared plane
/// ([`SpanDepth::Shared`]: the plane's gradients and its value at column 0
/// of row 0); [`SpanDepth::Exact`] when the plane is steep.
#[inline(never)]
pub(crate) fn shared_depth(plane: &Plane, width: u16, height: u16) -> SpanDepth {
    match plane.gradients() {
        Some((dz_dx, dz_dy)) => SpanDepth::Shared {
            dz_dx,
            dz_dy,
            row0_value: plane.shared_row_start((dz_dx, dz_dy), width, height, 0),
        },
        None => SpanDepth::Exact,
    }
}

/// How a covered pixel is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PixelWrite {
    /// Where nearer, or equally near and added earlier (the key row): the
    /// scanline z-buffer, whatever order its polygons are scanned in.
    NearerOrFirstAdded,
    /// Where strictly nearer: the z-buffer, drawing in the order polygons
    /// were added, so the first drawn keeps a tie.
    Nearer,
    /// Always: the painter's pass.
    Overwrite,
}

/// [`RowBuffers::fill_in_range`] for [`PixelWrite::Nearer`] and
/// [`PixelWrite::Overwrite`] (the z-buffer and the painter's pass).
#[inline(never)]
fn other_rule_in_range<C: Copy, D: DepthFormat>(
    depths: &mut [D::Value],
    colors: &mut [C],
    color: C,
    (mut acc, step): (D::Accum, D::Accum),
    write: PixelWrite,
) {
    if write == PixelWrite::Overwrite {
        for (stored, pixel) in depths.iter_mut().zip(colors) {
            (*stored, *pixel) = (D::value(acc), color);
            acc = D::advance(acc, step);
        }
    } else {
        for (stored, pixel) in depths.iter_mut().zip(colors) {
            let depth = D::value(acc);
            if depth < *stored {
                (*stored, *pixel) = (depth, color);
            }
            acc = D::advance(acc, step);
        }
    }
}

/// `fill_span` for [`PixelWrite::Nearer`] and [`PixelWrite::Overwrite`].
#[inline(never)]
fn other_rule_span<C: Copy, D: DepthFormat>(
    depths: &mut [D::Value],
    colors: &mut [C],
    keys: &mut [u32],
    x0: i32,
    pixel: (u32, C),
    source: &SpanSource,
    write: PixelWrite,
) {
    if write == PixelWrite::Overwrite {
        fill_span::<C, D, OVERWRITE>(depths, colors, keys, x0, pixel, source);
    } else {
        fill_span::<C, D, NEARER>(depths, colors, keys, x0, pixel, source);
    }
}

/// [`PixelWrite`]s as `fill_span`'s constant parameter.
const NEARER_OR_FIRST_ADDED: u8 = 0;
const NEARER: u8 = 1;
const OVERWRITE: u8 = 2;

/// The state of one scan.
pub(crate) struct ScanState<'t, 'a, C> {
    pub tables: &'t Prepared<'t, C>,
    pub active: OrderedSlots<'a, ActivePolygon<C>>,
    pub pool: EdgePool<'a>,
    pub stats: FrameStats,
}

impl<C: Copy> ScanState<'_, '_, C> {
    /// The corners of the polygon at `position`, as vertices.
    fn corners(&self, position: usize) -> impl Iterator<Item = ScreenVertex> + Clone + '_ {
        entry_corners(
            &self.tables.polygons[position],
            self.tables.corners,
            self.tables.vertices,
        )
    }

    /// Moves the polygon at `position` into the APT at `row`, with its
    /// plane and the edges covering `row`.
    /// Inline: a triangle goes straight to [`Self::activate_triangle`].
    /// (With the `profile` feature it is kept out of line: the profile's
    /// "activation" stage.)
    #[cfg_attr(feature = "profile", inline(never))]
    #[cfg_attr(not(feature = "profile"), inline(always))]
    pub(crate) fn activate_polygon<D: DepthFormat>(
        &mut self,
        position: usize,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> Result<(), Error> {
        if self.tables.polygons[position].corner_count() == 3 {
            self.activate_triangle(position, row, rows)
        } else {
            self.activate_general(position, row)
        }
    }

    /// [`Self::activate_polygon`] for a polygon of four or more corners,
    /// or a triangle whose plane is shared.
    #[inline(never)]
    fn activate_general(&mut self, position: usize, row: u16) -> Result<(), Error> {
        let polygon = self.tables.polygons[position];
        let (corners, vertices) = (self.tables.corners, self.tables.vertices);
        let (width, height) = (self.tables.width, self.tables.height);
        let depth = match polygon.shared_plane() {
            Some(_) => match shared_plane_of(&polygon, corners, vertices) {
                Some(plane) => shared_depth(&plane, width, height),
                None => SpanDepth::Exact,
            },
            None => self.own_depth(position, row),
        };
        let entry = ActivePolygon::new(
            position as u32,
            polygon.id() + 1,
            polygon.end_row,
            polygon.color,
            depth,
        );
        let slot = self
            .active
            .push(entry)
            .map_err(|_| Error::ActivePolygonsFull { row })?;
        self.activate_edges(slot, row, true)
    }

    /// The depth set-up of a polygon of four or more corners on its own
    /// plane (Newell's).
    #[inline]
    fn own_depth(&self, position: usize, row: u16) -> SpanDepth {
        let polygon = &self.tables.polygons[position];
        match Plane::new(self.corners(position)).map(|p| (p, p.gradients())) {
            Some((plane, Some((dz_dx, dz_dy)))) => SpanDepth::Stepped {
                dz_dx,
                dz_dy,
                row_value: plane.row_start(
                    (dz_dx, dz_dy),
                    self.tables.width,
                    polygon.first_row,
                    row,
                ),
                // A polygon's plane is Newell's fit: its corners may lie
                // off it, so its range is checked span by span.
                accumulator: None,
            },
            // Non-zero area was checked when the polygon entered the table.
            Some((_, None)) | None => SpanDepth::Exact,
        }
    }

    /// [`Self::activate_polygon`] for a triangle: its corners sorted by y,
    /// its long edge and the short edge covering `row` enter at once, and
    /// the lower short edge waits for its `switch_row`. A triangle that
    /// covers this row alone is drawn at once and never enters the APT.
    #[inline(never)]
    fn activate_triangle<D: DepthFormat>(
        &mut self,
        position: usize,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> Result<(), Error> {
        let polygon = self.tables.polygons[position];
        let (corners, vertices) = (self.tables.corners, self.tables.vertices);
        // (Not `let &[..] = entry_corner_ids(..) else`, which reads the
        // same: on a Cortex-M0+ that took 4,720 more instructions a frame
        // of the torus knot.)
        let ids = match polygon.triangle() {
            Some(ids) => ids,
            // A triangle sharing a plane: its corners from the list.
            None => match *entry_corner_ids(&polygon, corners) {
                [a, b, c] => [a, b, c],
                _ => return self.activate_general(position, row),
            },
        };
        // Not `ids.map`: on a Cortex-M0+ that became a loop through
        // `try_from_fn`, 90 cycles for three loads.
        let vertex = |k: usize| vertices[usize::from(ids[k])];
        let [a, b, c] = [vertex(0), vertex(1), vertex(2)];
        let shared = polygon.shared_plane().is_some();
        // Only a triangle of one row, activated on it: one that a band
        // activates on its last row (having started above the band) is
        // stepped from its first row as one scan over the whole frame
        // steps it, where the tiny path's exact values could differ from
        // the stepped ones by one step of the depth format.
        if !shared
            && polygon.end_row == row + 1
            && polygon.first_row == row
            && self.draw_tiny_row(a, b, c, &polygon, row, rows)
        {
            return Ok(());
        }
        // The plane passes through the corners: in range when they are
        // (see IN_RANGE).
        let in_range = [a.z, b.z, c.z].iter().all(|z| IN_RANGE.contains(z));
        // `first` is the plane's value at column 0 of the triangle's first
        // row; each row's is that plus a step of `dz_dy` per row, exactly.
        // A band's scan may activate it further down.
        let rows_below = i32::from(row) - i32::from(polygon.first_row);
        let stepped = |dz_dx: i64, dz_dy: i64, first: i64| {
            if D::NARROW
                && in_range
                && let Some(narrow) = D::narrow_row(first, dz_dx, dz_dy, rows_below)
            {
                return (SpanDepth::Narrow, Some(narrow));
            }
            let depth = SpanDepth::Stepped {
                dz_dx,
                dz_dy,
                // 0 <= rows_below < 2^12, |dz_dy| < 2^40.
                row_value: if rows_below == 0 {
                    first
                } else {
                    first + mul_i64_small(dz_dy, rows_below)
                },
                accumulator: in_range.then(|| D::accumulator_step(dz_dx)).flatten(),
            };
            (depth, None)
        };
        let own_plane = if shared {
            None
        } else {
            TrianglePlane::new(a, b, c)
        };
        let (depth, narrow) = match own_plane {
            // The common case: two exact divisions per gradient.
            Some(plane) => stepped(plane.dz_dx, plane.dz_dy, plane.row_start(polygon.first_row)),
            // Large (256 px or more) or steep: the general plane.
            None if shared => match shared_plane_of(&polygon, corners, vertices) {
                Some(plane) => (
                    shared_depth(&plane, self.tables.width, self.tables.height),
                    None,
                ),
                None => (SpanDepth::Exact, None),
            },
            None => match Plane::triangle(a, b, c) {
                Some(plane) => match plane.gradients() {
                    Some((dz_dx, dz_dy)) => {
                        let (width, first_row) = (self.tables.width, polygon.first_row);
                        let first = plane.row_start((dz_dx, dz_dy), width, first_row, first_row);
                        stepped(dz_dx, dz_dy, first)
                    }
                    None => (SpanDepth::Exact, None),
                },
                None => return Ok(()), // Zero area was left out when it was queued.
            },
        };
        let ([(_, top), (mid_id, mid), (bot_id, bot)], odd) =
            sort_by_y([(ids[0], a), (ids[1], b), (ids[2], c)]);
        let height = i32::from(self.tables.height);
        let row_of = |y: i32| first_sample_at_or_after(y);
        let (mid_row, bot_row) = (row_of(mid.y), row_of(bot.y));
        let r = i32::from(row);
        let clip = |end: i32| end.min(height) as u16;
        let long = ActiveEdge::start(top, bot, row, clip(bot_row), NO_EDGE);
        let mut switch_row = NO_ROW;
        let short = if r < mid_row {
            if mid_row < bot_row.min(height) {
                switch_row = mid_row as u16;
            }
            ActiveEdge::start(top, mid, row, clip(mid_row), NO_EDGE)
        } else {
            ActiveEdge::start(mid, bot, row, clip(bot_row), NO_EDGE)
        };
        // Screen y points down: the middle corner lies left of the long edge
        // when the cross product (bottom - top) x (middle - top) is
        // positive. That is minus twice the signed area of (top, middle,
        // bottom), which is the set-up's `a b c` area, signed by the
        // parity of the sort: no second product when the set-up made it.
        // (Guard-band differences: below 2^23, products below 2^46.)
        let turn = match own_plane {
            Some(plane) if odd => i64::from(plane.twice_area),
            Some(plane) => -i64::from(plane.twice_area),
            None => cross(bot.x - top.x, bot.y - top.y, mid.x - top.x, mid.y - top.y),
        };
        debug_assert_eq!(
            turn,
            cross(bot.x - top.x, bot.y - top.y, mid.x - top.x, mid.y - top.y)
        );
        let set = |entry: &mut ActivePolygon<C>| {
            entry.set_triangle(
                position as u32,
                polygon.id() + 1,
                polygon.end_row,
                switch_row,
                polygon.color,
                (depth, narrow),
                long,
                short,
                turn > 0,
                [mid_id, bot_id],
            )
        };
        self.stats.edges += 2;
        self.pool.live += 2;
        if polygon.end_row == row + 1 {
            // One row: its span now, and no APT entry.
            let mut entry = ActivePolygon::filler(polygon.color);
            set(&mut entry);
            self.fill_and_step(&mut entry, row, rows);
            return Ok(());
        }
        // Written in its slot (see `set_triangle`).
        self.active
            .push_in_place(set)
            .map(|_| ())
            .map_err(|()| Error::ActivePolygonsFull { row })
    }

    /// Draws a triangle that covers `row` alone and spans at most
    /// [`TINY_COLUMNS`] samples of it, with no edges and no gradients: its
    /// covered samples (contiguous, the triangle being convex) come from
    /// the fill rule's sample test, and their depths are the plane's exact
    /// values. Returns `false` (nothing drawn) for a wider triangle.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn draw_tiny_row<D: DepthFormat>(
        &mut self,
        a: ScreenVertex,
        b: ScreenVertex,
        c: ScreenVertex,
        polygon: &PolygonEntry<C>,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> bool {
        let width = i32::from(self.tables.width);
        let first = first_sample_at_or_after(a.x.min(b.x).min(c.x)).max(0);
        let end = first_sample_at_or_after(a.x.max(b.x).max(c.x)).min(width);
        if end - first > TINY_COLUMNS {
            return false;
        }
        let test = TriangleTest::new(a, b, c);
        let (mut start, mut stop) = (end, first);
        for column in first..end {
            if test.covers_pixel(column, i32::from(row)) {
                start = start.min(column);
                stop = column + 1;
            }
        }
        let Some(plane) = Plane::triangle(a, b, c) else {
            return true; // No area: nothing to draw.
        };
        let source = SpanSource::Exact(plane, row);
        if rows.fill(start, stop, polygon.id() + 1, polygon.color, &source) {
            self.stats.spans += 1;
        }
        true
    }

    /// Fills an active polygon's spans on `row` and steps it down to the
    /// next row; returns whether it is still active there.
    #[inline]
    fn fill_and_step<D: DepthFormat>(
        &mut self,
        polygon: &mut ActivePolygon<C>,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> bool {
        fill_and_step(
            polygon,
            self.tables,
            &mut self.pool,
            &mut self.stats,
            row,
            rows,
        )
    }

    /// Starts edges of the active polygon at `slot`: at its activation,
    /// every edge covering `row`; later, those starting on `row`.
    #[inline(never)]
    pub(crate) fn activate_edges(
        &mut self,
        slot: usize,
        row: u16,
        at_activation: bool,
    ) -> Result<(), Error> {
        let Some(&entry) = self.active.get(slot) else {
            return Err(Error::ActivePolygonsFull { row });
        };
        let polygon = &self.tables.polygons[entry.position as usize];
        let end_limit = i32::from(self.tables.height);
        let corners = entry_corners(polygon, self.tables.corners, self.tables.vertices);
        let mut result = Ok(());
        let (active, pool, stats) = (&mut self.active, &mut self.pool, &mut self.stats);
        for_each_edge(corners, |top, bottom| {
            let first = first_sample_at_or_after(top.y);
            let end_row = first_sample_at_or_after(bottom.y).min(end_limit);
            let covers = first <= i32::from(row) && end_row > i32::from(row);
            let wanted = if at_activation {
                covers
            } else {
                covers && first == i32::from(row)
            };
            if wanted && result.is_ok() {
                let edge = ActiveEdge::start(top, bottom, row, end_row as u16, NO_EDGE);
                result = match active.get_mut(slot) {
                    Some(entry) => entry
                        .add_edge(edge, pool)
                        .map_err(|()| Error::ActiveEdgesFull { row }),
                    None => Err(Error::ActivePolygonsFull { row }),
                };
                stats.edges += 1;
            }
        });
        result
    }

    fn note_peaks(&mut self) {
        let s = &mut self.stats;
        s.peak_active_polygons = s.peak_active_polygons.max(self.active.len() as u32);
        s.peak_active_edges = s.peak_active_edges.max(self.pool.live);
        s.peak_pooled_edges = s.peak_pooled_edges.max(self.pool.pooled);
    }

    /// Fills every active polygon's spans on `row` into the row buffers,
    /// then steps each down to the next row: those that end leave the APT
    /// at once (its order does not matter, ties being broken by key).
    #[inline(never)]
    fn scan_row<D: DepthFormat>(
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
        let rows = &mut RowBuffers::<C, D> {
            depth: &mut *rows.depth,
            color,
            key,
            write: rows.write,
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
            if !fill_and_step(polygon, tables, pool, stats, row, rows) {
                live -= 1;
                order.swap(index, live);
            }
        }
        *len = live;
        Ok(())
    }
}

/// [`fill_and_step`] for the common case, a triangle whose depths stay in
/// range: `None` (nothing done) for any other polygon. Kept apart from the
/// general path so that, inlined into the row loop, it holds no more state
/// than it needs (on a Cortex-M0+ the general path's spills cost more than
/// the work).
#[inline(always)]
fn fill_and_step_triangle<C: Copy, D: DepthFormat>(
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
        if rows.fill_in_range(start, end, polygon.key, polygon.color, |column| {
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
    if !polygon.is_triangle() {
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
    if rows.fill_in_range(start, end, polygon.key, polygon.color, |column| {
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
/// out of line.
#[inline(always)]
pub(crate) fn fill_and_step<C: Copy, D: DepthFormat>(
    polygon: &mut ActivePolygon<C>,
    tables: &Prepared<'_, C>,
    pool: &mut EdgePool<'_>,
    stats: &mut FrameStats,
    row: u16,
    rows: &mut RowBuffers<'_, C, D>,
) -> bool {
    match fill_and_step_triangle(polygon, tables, pool, stats, row, rows) {
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
    if polygon.is_triangle() {
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

/// A triangle's corners (with their vertex indices) sorted by y (stable:
/// equal ones keep their order), and whether the sort was an odd
/// permutation.
#[inline]
fn sort_by_y(corners: [(u16, ScreenVertex); 3]) -> ([(u16, ScreenVertex); 3], bool) {
    sort_by_y_as::<BRANCH_FREE>(corners)
}

/// [`sort_by_y`] with or without branches (both are tested on the host).
#[inline(always)]
fn sort_by_y_as<const BRANCH_FREE: bool>(
    corners: [(u16, ScreenVertex); 3],
) -> ([(u16, ScreenVertex); 3], bool) {
    if BRANCH_FREE {
        // The same three compare-and-swaps, always made, on the corners'
        // indices (selects of small integers: the corners come in any
        // order, so each branch would miss often, and selecting whole
        // corners went through the stack). The third swaps nothing when
        // the second did not: the first already ordered that pair.
        let y = |k: usize| corners[k].1.y;
        let sort_pair = |upper: usize, lower: usize| {
            let swap = y(lower) < y(upper);
            let select = core::hint::select_unpredictable;
            (select(swap, lower, upper), select(swap, upper, lower), swap)
        };
        let (top, mid, first) = sort_pair(0, 1);
        let (mid, bot, second) = sort_pair(mid, 2);
        let (top, mid, third) = sort_pair(top, mid);
        return (
            [corners[top], corners[mid], corners[bot]],
            first ^ second ^ third,
        );
    }
    let [mut top, mut mid, mut bot] = corners;
    let mut odd = false;
    if mid.1.y < top.1.y {
        core::mem::swap(&mut top, &mut mid);
        odd = !odd;
    }
    if bot.1.y < mid.1.y {
        core::mem::swap(&mut mid, &mut bot);
        odd = !odd;
        if mid.1.y < top.1.y {
            core::mem::swap(&mut top, &mut mid);
            odd = !odd;
        }
    }
    ([top, mid, bot], odd)
}

/// Calls `f(top, bottom)` for every non-horizontal edge of a polygon, its
/// ends ordered top first.
pub(crate) fn for_each_edge(
    corners: impl Iterator<Item = ScreenVertex> + Clone,
    mut f: impl FnMut(ScreenVertex, ScreenVertex),
) {
    let next = corners.clone().skip(1).chain(corners.clone().take(1));
    for (a, b) in corners.zip(next) {
        if a.y != b.y {
            let (top, bottom) = if a.y < b.y { (a, b) } else { (b, a) };
            f(top, bottom);
        }
    }
}

/// The corners of a polygon-table entry, as vertices.
pub(crate) fn entry_corners<'a, C>(
    polygon: &'a PolygonEntry<C>,
    corners: &'a [u16],
    vertices: &'a [ScreenVertex],
) -> impl Iterator<Item = ScreenVertex> + Clone + 'a {
    entry_corner_ids(polygon, corners)
        .iter()
        .map(move |&i| vertices[usize::from(i)])
}

/// Triangles covering one row and at most this many columns of it are
/// drawn by sample tests and exact plane values, without edges.
const TINY_COLUMNS: i32 = 4;

/// Spans of at most this many pixels round each pixel's plane value; longer
/// ones step the depth format's accumulator.
const SHORT_SPAN: u32 = 4;

/// Where a span's depths come from.
enum SpanSource {
    /// From the row's plane value at column 0 and the gradient; with the
    /// accumulator step when the polygon is known to stay in range.
    Stepped {
        dz_dx: i64,
        row_value: i64,
        accumulator: Option<i64>,
    },
    /// Exactly from the plane, at each pixel of the row.
    Exact(Plane, u16),
}

/// The span loop of [`RowBuffers::fill_shared`]: each pixel's plane
/// value, from `value` stepping by `dz_dx`, rounded on its own, so the
/// stored depth never depends on where the span starts.
///
/// Its write rule is `fill_span`'s, written out again on purpose: routing
/// both loops through one helper changed the Cortex-M0+ code of the hot
/// span loop (boxes, z24: 4,320,920 to 4,453,920 instructions under
/// `cargo qemu`).
#[inline]
fn round_each_pixel<C: Copy, D: DepthFormat, const MODE: u8>(
    (depths, colors, keys): (&mut [D::Value], &mut [C], &mut [u32]),
    mut value: i64,
    dz_dx: i64,
    (key, color): (u32, C),
) {
    let pixels = depths
        .iter_mut()
        .zip(keys.iter_mut())
        .zip(colors.iter_mut());
    for ((stored, stored_key), pixel) in pixels {
        let depth = D::quantize(value);
        let wins = match MODE {
            NEARER_OR_FIRST_ADDED => {
                depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key)
            }
            NEARER => depth < *stored,
            _ => true,
        };
        if wins {
            (*stored, *stored_key, *pixel) = (depth, key, color);
        }
        value += dz_dx;
    }
}

/// Depth-tests and writes one span: pixels `x0 .. x0 + depths.len()`. A
/// pixel is written when its depth is nearer than the row holds, or equal
/// with a smaller key (the polygon added first).
#[inline(always)]
fn fill_span<C: Copy, D: DepthFormat, const MODE: u8>(
    depths: &mut [D::Value],
    colors: &mut [C],
    keys: &mut [u32],
    x0: i32,
    (key, color): (u32, C),
    source: &SpanSource,
) {
    let write = |depth: D::Value, stored: &mut D::Value, stored_key: &mut u32, pixel: &mut C| {
        let wins = match MODE {
            NEARER_OR_FIRST_ADDED => {
                depth < *stored || (depth == *stored && depth != D::CLEAR && key < *stored_key)
            }
            NEARER => depth < *stored,
            _ => true,
        };
        if wins {
            *stored = depth;
            *stored_key = key;
            *pixel = color;
        }
    };
    let len = depths.len() as u32;
    let pixels = depths
        .iter_mut()
        .zip(keys.iter_mut())
        .zip(colors.iter_mut());
    match *source {
        SpanSource::Stepped {
            dz_dx,
            row_value,
            accumulator: Some(step),
        } => {
            // In range (checked once per polygon): the accumulator, with
            // no range check and no rounding per pixel, placed at the plane
            // value of the span's first pixel (|dz_dx| < 2^40, x0 < 2^12).
            let start = row_value + dz_dx * i64::from(x0);
            let (mut acc, step) = D::accumulator_at(start, dz_dx, step, 0);
            for ((stored, stored_key), pixel) in pixels {
                write(D::value(acc), stored, stored_key, pixel);
                acc = D::advance(acc, step);
            }
        }
        SpanSource::Stepped {
            dz_dx, row_value, ..
        } => {
            // Re-evaluated from the plane at every span start: the error
            // is the gradient's rounding times the distance from the
            // polygon's anchor column (see `Plane::row_start`), never drift
            // from earlier spans. |dz_dx| < 2^40 (steeper polygons are
            // `Exact`), x0 < 2^12 and |row_value| < 2^57: no overflow.
            let start = row_value + dz_dx * i64::from(x0);
            if len <= SHORT_SPAN {
                // A few pixels: rounding each plane value costs less than
                // setting up the accumulator.
                let mut value = start;
                for ((stored, stored_key), pixel) in pixels {
                    write(D::quantize(value), stored, stored_key, pixel);
                    value += dz_dx;
                }
            } else if let Some((mut acc, step)) = D::span(start, dz_dx, len) {
                for ((stored, stored_key), pixel) in pixels {
                    write(D::value(acc), stored, stored_key, pixel);
                    acc = D::advance(acc, step);
                }
            } else {
                let mut value = start;
                for ((stored, stored_key), pixel) in pixels {
                    write(D::quantize(value), stored, stored_key, pixel);
                    value = value.saturating_add(dz_dx);
                }
            }
        }
        SpanSource::Exact(plane, row) => {
            for (k, ((stored, stored_key), pixel)) in pixels.enumerate() {
                let value = plane.value_at_pixel(x0 + k as i32, i32::from(row));
                write(D::quantize(value), stored, stored_key, pixel);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both forms of the corner sort agree for every order of three
    /// corners, ties included: sorted by y, stable, and the parity that
    /// of the permutation.
    #[test]
    fn corner_sorts_agree_and_are_stable() {
        for code in 0..27 {
            let ys = [code % 3, code / 3 % 3, code / 9];
            let corners: [(u16, ScreenVertex); 3] = core::array::from_fn(|k| {
                (
                    k as u16,
                    ScreenVertex {
                        x: 0,
                        y: ys[k],
                        z: 0,
                    },
                )
            });
            let (sorted, odd) = sort_by_y_as::<true>(corners);
            assert_eq!((sorted, odd), sort_by_y_as::<false>(corners), "{ys:?}");
            let mut want = corners;
            want.sort_by_key(|&(_, v)| v.y); // stable
            assert_eq!(sorted, want, "{ys:?}");
            let order = sorted.map(|(k, _)| usize::from(k));
            let inversions = (0..3)
                .flat_map(|i| (i + 1..3).map(move |j| (i, j)))
                .filter(|&(i, j)| order[i] > order[j])
                .count();
            assert_eq!(odd, inversions % 2 == 1, "{ys:?}");
        }
    }
}
