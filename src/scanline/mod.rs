//! The scanline z-buffer: polygon table, edge table, active polygon table,
//! active edge table, and one row of depth and colour.
//!
//! # The algorithm
//! 1. **Table building** ([`Renderer::push_vertex`], [`Renderer::push_polygon`]):
//!    each polygon that can cover a pixel enters the *polygon table* (PT)
//!    with its colour, its corners and its rows; polygons off-screen or of
//!    zero area are counted and left out.
//! 2. **Bucketing** (start of [`Renderer::render`]): the PT is sorted by first
//!    row and the *edge table* (ET) is built from it, one entry per
//!    non-horizontal visible edge, sorted by first row. Each table is a
//!    compact bucket list: the entries of bucket `y` are one contiguous run.
//! 3. **Scanning**, for each row `y`:
//!    * polygons of bucket `y` enter the *active polygon table* (APT) with
//!      their plane gradients `dz/dx = -a/c`, `dz/dy = -b/c` and the plane's
//!      value at the start of the row;
//!    * edges of bucket `y` enter the *active edge table* (AET);
//!    * the AET is kept sorted by (polygon, crossing); each polygon's
//!      crossings are paired even-odd into spans (left/right pairs for
//!      convex polygons, correct for concave ones too);
//!    * along each span, depth starts from the plane at the span's first
//!      pixel and steps by `dz/dx`; a pixel is written when its depth is
//!      nearer than the row's;
//!    * the finished row goes to the [`RowSink`];
//!    * edges and polygons whose last row this was leave; the others step
//!      (`x += dx/dy` exactly, row depth `+= dz/dy`).
//!
//! Only one row of depth and one of colour exist: nothing is frame-sized.

mod active;
mod edge;
mod plane;

use heapless::Vec;

use crate::depth::DepthFormat;
use crate::error::{Error, RenderError};
use crate::fixed::{MAX_FRAME_SIZE, MAX_POLYGON_CORNERS, first_sample_at_or_after};
use crate::sink::RowSink;
use crate::vertex::{Outline, OutlineBuilder, ScreenVertex};
use active::{ActivePolygon, EdgePool, SpanDepth};
use edge::{ActiveEdge, EdgeEntry, edge_rows};
use plane::Plane;

/// What scene building needs from a renderer: its frame, its vertex table
/// and its polygon table. [`Renderer`] implements it for every
/// configuration, so [`crate::scene`] needs none of the capacities.
///
/// A polygon enters in one of two ways, neither needing a buffer per
/// polygon:
/// * [`Self::offer_polygon`] takes its corners as an iterator of vertex
///   indices, judges it and copies the corners only if it is queued;
/// * corner by corner: [`Self::begin_polygon`], [`Self::add_corner`] for
///   each corner (vertices may be added in between: they belong to the
///   polygon), then [`Self::finish_polygon`], which either queues it or
///   removes its corners and the vertices added since `begin_polygon`.
///   The corners occupy table space while the polygon is open, so callers
///   judge it first (the pipeline does, for the clipped faces that use
///   this way in).
pub trait PolygonTables<C> {
    /// Frame width in pixels.
    fn frame_width(&self) -> u16;
    /// Frame height in pixels.
    fn frame_height(&self) -> u16;
    /// Adds a vertex; see [`Renderer::push_vertex`].
    fn add_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error>;
    /// A vertex added before.
    fn get_vertex(&self, index: u16) -> Option<ScreenVertex>;
    /// Offers a polygon by its corners' vertex indices. Polygons of zero
    /// area or covering no pixel sample are counted and left out (see
    /// [`Admission`]); otherwise `decide` sees its [`Outline`] and gives
    /// its colour, or `None` to leave it out ([`Admission::Declined`]).
    /// Nothing is stored unless it is queued; on `Err` nothing was added.
    fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone;
    /// Opens a new polygon, dropping any polygon left open.
    fn begin_polygon(&mut self);
    /// Drops the open polygon, if any: its corners and the vertices added
    /// since [`Self::begin_polygon`]. No polygon is open afterwards.
    fn discard_polygon(&mut self);
    /// Appends a corner (a vertex index) to the open polygon. On `Err`
    /// the open polygon stays as it was.
    fn add_corner(&mut self, vertex: u16) -> Result<(), Error>;
    /// Closes the open polygon and offers it as [`Self::offer_polygon`]
    /// does; whatever the outcome it is closed, and if it was not queued
    /// its corners and the vertices added since [`Self::begin_polygon`]
    /// are removed.
    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error>;
}

/// What happened to a polygon offered to the tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Admission {
    /// It entered the polygon table; its id is the given value.
    Queued(u32),
    /// It covers no pixel sample of the frame (bounding-box test).
    OffScreen,
    /// Its projected area is zero: it cannot cover a sample.
    Degenerate,
    /// The caller's `decide` closure declined it (for example a back face).
    Declined,
}

/// Counts for one rendered frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrameStats {
    /// Vertices in the vertex table.
    pub vertices: u32,
    /// Polygon corners stored (the edge-table capacity they need).
    pub corners: u32,
    /// Polygons in the polygon table.
    pub polygons: u32,
    /// Edges in the edge table (non-horizontal, visible).
    pub edges: u32,
    /// Largest number of polygons active on one row.
    pub peak_active_polygons: u32,
    /// Largest number of edges active on one row.
    pub peak_active_edges: u32,
    /// Largest number of those held in the edge pool, beyond each
    /// polygon's inline pair: what the capacity `AE` must hold (zero for
    /// triangles and other convex polygons).
    pub peak_pooled_edges: u32,
    /// Spans filled.
    pub spans: u32,
    /// Polygons offered but left out as off-screen.
    pub off_screen: u32,
    /// Polygons offered but left out as zero-area.
    pub degenerate: u32,
}

impl FrameStats {
    /// Bytes a renderer with colour `C` and depth `D` needs for a scene with
    /// these counts in a frame `width` wide: the two rows, the vertex,
    /// polygon, corner and edge tables, and the active tables at their
    /// peaks. Capacities set to these counts make a renderer of about this
    /// size (plus a few bytes of bookkeeping).
    pub fn ram_bytes<C, D: DepthFormat>(&self, width: usize) -> usize {
        use core::mem::size_of;
        let n = |count: u32| count as usize;
        width * (size_of::<C>() + size_of::<D::Value>())
            + n(self.vertices) * size_of::<ScreenVertex>()
            + n(self.polygons) * size_of::<PolygonEntry<C>>()
            + n(self.corners) * (size_of::<u16>() + size_of::<EdgeEntry>())
            + n(self.peak_active_polygons) * size_of::<ActivePolygon<C>>()
            + n(self.peak_pooled_edges) * size_of::<ActiveEdge>()
    }
}

/// Polygon-table entry.
#[derive(Debug, Clone, Copy)]
struct PolygonEntry<C> {
    /// First corner in the corner list.
    corner_start: u32,
    /// Number of corners.
    corner_count: u16,
    /// First visible row (the bucket).
    first_row: u16,
    /// One past the last visible row.
    end_row: u16,
    color: C,
}

/// A scanline z-buffer renderer with fixed capacities.
///
/// * `C`: the pixel colour (any `Copy` type; an embedded-graphics
///   `PixelColor` for [`DrawTargetSink`](crate::DrawTargetSink)).
/// * `D`: the depth format ([`Depth16`](crate::Depth16),
///   [`Depth24`](crate::Depth24)).
/// * `W`: the row capacity in pixels (at most [`MAX_FRAME_SIZE`]); the
///   frame width is `W` or, with [`Renderer::with_size`], any width up to it.
/// * `V`: vertex-table capacity (at most 65,536).
/// * `P`: polygon-table capacity.
/// * `E`: edge-table capacity; it also bounds the total number of polygon
///   corners, so a mesh of `T` triangles needs `E >= 3·T`.
/// * `AP`, `AE`: active polygon and active edge capacities (largest number
///   crossing one row; `AE` counts only the edges beyond each polygon's
///   first two, so triangles and convex polygons need none).
///
/// A polygon has 3 to [`MAX_POLYGON_CORNERS`] corners.
///
/// Exceeding any capacity is an [`Error`] naming it. The whole renderer
/// lives in one value of `core::mem::size_of::<Self>()` bytes; it allocates
/// nothing.
#[derive(Debug)]
pub struct Renderer<
    C,
    D: DepthFormat,
    const W: usize,
    const V: usize,
    const P: usize,
    const E: usize,
    const AP: usize,
    const AE: usize,
> {
    width: u16,
    height: u16,
    background: C,
    vertices: Vec<ScreenVertex, V>,
    polygons: Vec<PolygonEntry<C>, P>,
    corners: Vec<u16, E>,
    edges: Vec<EdgeEntry, E>,
    active_polygons: Vec<ActivePolygon<C>, AP>,
    /// Active edges beyond each active polygon's pair.
    edge_pool: EdgePool<AE>,
    /// APT entries whose polygon has finished, awaiting compaction.
    dead_polygons: usize,
    /// The row being scanned (compaction keeps entries live on it).
    current_row: u16,
    depth_row: [D::Value; W],
    color_row: [C; W],
    /// Corners of queued polygons; `corners` beyond it belong to the open
    /// polygon.
    committed_corners: usize,
    /// `Some(vertex count when it began)` while a polygon is open: vertices
    /// beyond it are removed with it if it is not queued.
    open_polygon: Option<usize>,
    next_id: u32,
    off_screen: u32,
    degenerate: u32,
}

impl<
    C: Copy,
    D: DepthFormat,
    const W: usize,
    const V: usize,
    const P: usize,
    const E: usize,
    const AP: usize,
    const AE: usize,
> Renderer<C, D, W, V, P, E, AP, AE>
{
    /// An empty renderer for frames `W` wide and `height` tall, clearing
    /// to `background`.
    pub const fn new(height: u16, background: C) -> Result<Self, Error> {
        Self::with_size(W as u16, height, background)
    }

    /// An empty renderer for frames `width` (at most `W`) by `height`
    /// pixels, clearing to `background`.
    pub const fn with_size(width: u16, height: u16, background: C) -> Result<Self, Error> {
        match Self::check_size(width, height) {
            Ok(()) => Ok(Self::empty(width, height, background)),
            Err(e) => Err(e),
        }
    }

    /// As [`Self::with_size`], for `static` and `const` items (for
    /// example with `static_cell::ConstStaticCell`), so that a large
    /// renderer is built at compile time and never copied through the
    /// stack. An invalid size stops the build.
    pub const fn new_in_static(width: u16, height: u16, background: C) -> Self {
        if Self::check_size(width, height).is_err() {
            panic!("zline: frame width must be 1..=W and height 1..=4096");
        }
        Self::empty(width, height, background)
    }

    const fn check_size(width: u16, height: u16) -> Result<(), Error> {
        const {
            assert!(W > 0 && W <= MAX_FRAME_SIZE, "W must be 1..=4096");
            assert!(V <= 1 << 16, "V must be at most 65536");
            assert!(P <= edge::MAX_POLYGONS, "P must be at most 2^20");
        }
        if width == 0 || width as usize > W || height == 0 || height as usize > MAX_FRAME_SIZE {
            Err(Error::BadFrameSize)
        } else {
            Ok(())
        }
    }

    const fn empty(width: u16, height: u16, background: C) -> Self {
        Self {
            width,
            height,
            background,
            vertices: Vec::new(),
            polygons: Vec::new(),
            corners: Vec::new(),
            edges: Vec::new(),
            active_polygons: Vec::new(),
            edge_pool: EdgePool::new(),
            dead_polygons: 0,
            current_row: 0,
            depth_row: [D::CLEAR; W],
            color_row: [background; W],
            committed_corners: 0,
            open_polygon: None,
            next_id: 0,
            off_screen: 0,
            degenerate: 0,
        }
    }

    /// Frame width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Frame height in rows.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// Colour of pixels no polygon covers.
    pub fn set_background(&mut self, background: C) {
        self.background = background;
    }

    /// Empties the vertex and polygon tables for the next frame.
    pub fn clear(&mut self) {
        self.vertices.clear();
        self.polygons.clear();
        self.corners.clear();
        self.edges.clear();
        self.committed_corners = 0;
        self.open_polygon = None;
        self.next_id = 0;
        self.off_screen = 0;
        self.degenerate = 0;
    }

    /// Number of vertices in the vertex table.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Number of polygons in the polygon table.
    pub fn polygon_count(&self) -> usize {
        self.polygons.len()
    }

    /// Vertex `index` of the vertex table.
    pub fn vertex(&self, index: u16) -> Option<ScreenVertex> {
        self.vertices.get(usize::from(index)).copied()
    }

    /// Adds a vertex and returns its index for [`Self::push_polygon`].
    pub fn push_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        vertex.check()?;
        let index = u16::try_from(self.vertices.len()).map_err(|_| Error::VertexTableFull)?;
        self.vertices
            .push(vertex)
            .map_err(|_| Error::VertexTableFull)?;
        Ok(index)
    }

    /// Offers a polygon, given by indices into the vertex table in order
    /// around its boundary (either winding; it may be concave or even
    /// self-intersecting, filled even-odd). Polygons that can cover no
    /// pixel are counted and left out (see [`Admission`]); on `Err` nothing
    /// was added.
    pub fn push_polygon(&mut self, corners: &[u16], color: C) -> Result<Admission, Error> {
        if corners.len() < 3 {
            return Err(Error::TooFewCorners);
        }
        if corners.len() > MAX_POLYGON_CORNERS {
            return Err(Error::TooManyCorners);
        }
        self.offer_polygon(corners.iter().copied(), |_| Some(color))
    }

    /// Adds the polygon's corners to the vertex table and the polygon to
    /// the polygon table in one step; on `Err` neither table changed.
    pub fn push_polygon_vertices(
        &mut self,
        corners: &[ScreenVertex],
        color: C,
    ) -> Result<Admission, Error> {
        if corners.len() < 3 {
            return Err(Error::TooFewCorners);
        }
        if corners.len() > MAX_POLYGON_CORNERS {
            return Err(Error::TooManyCorners);
        }
        self.begin_polygon();
        for &v in corners {
            if let Err(e) = self.push_vertex(v).and_then(|index| self.add_corner(index)) {
                self.discard_open_polygon();
                return Err(e);
            }
        }
        self.finish_polygon(|_| Some(color))
    }

    /// Offers a polygon by an iterator of vertex indices; see
    /// [`PolygonTables::offer_polygon`].
    pub fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        let corners = corners.into_iter();
        let mut outline = OutlineBuilder::default();
        for index in corners.clone() {
            if outline.corners() == MAX_POLYGON_CORNERS {
                return Err(Error::TooManyCorners);
            }
            let vertex = self.vertices.get(usize::from(index));
            outline.add(*vertex.ok_or(Error::VertexOutOfRange)?);
        }
        let outline = outline.finish();
        let rows = match self.judge(&outline)? {
            Ok(rows) => rows,
            Err(admission) => return Ok(admission),
        };
        let Some(color) = decide(&outline) else {
            return Ok(Admission::Declined);
        };
        if self.polygons.is_full() {
            return Err(Error::PolygonTableFull);
        }
        if self.corners.capacity() - self.corners.len() < outline.corners {
            return Err(Error::EdgeTableFull);
        }
        let start = self.corners.len();
        for index in corners {
            // Room for every corner was checked above.
            self.corners.push(index).map_err(|_| Error::EdgeTableFull)?;
        }
        self.committed_corners = self.corners.len();
        Ok(self.queue(start, outline.corners, rows, color))
    }

    /// The core's verdict on an outline: `Ok(Ok(rows))` when it can cover
    /// a pixel sample, `Ok(Err(admission))` (counted) when it cannot.
    fn judge(&mut self, outline: &Outline) -> Result<Result<(u16, u16), Admission>, Error> {
        if outline.corners < 3 {
            return Err(Error::TooFewCorners);
        }
        if outline.twice_area == 0 {
            self.degenerate += 1;
            return Ok(Err(Admission::Degenerate));
        }
        match outline
            .rect
            .and_then(|r| r.sample_rows(self.width, self.height))
        {
            Some(rows) => Ok(Ok(rows)),
            None => {
                self.off_screen += 1;
                Ok(Err(Admission::OffScreen))
            }
        }
    }

    /// Enters a polygon whose corners are `corners[start..start + count]`
    /// in the polygon table (which has room).
    fn queue(&mut self, start: usize, count: usize, rows: (u16, u16), color: C) -> Admission {
        let entry = PolygonEntry {
            corner_start: start as u32,
            corner_count: count as u16,
            first_row: rows.0,
            end_row: rows.1,
            color,
        };
        if self.polygons.push(entry).is_err() {
            // The callers checked for room: cannot happen.
            return Admission::OffScreen;
        }
        self.next_id += 1;
        Admission::Queued(self.next_id - 1)
    }

    /// Opens a polygon; see [`PolygonTables`].
    pub fn begin_polygon(&mut self) {
        self.discard_open_polygon();
        self.open_polygon = Some(self.vertices.len());
    }

    /// Drops the open polygon; see [`PolygonTables::discard_polygon`].
    pub fn discard_polygon(&mut self) {
        self.discard_open_polygon();
    }

    /// Appends a corner to the open polygon; see [`PolygonTables`].
    pub fn add_corner(&mut self, vertex: u16) -> Result<(), Error> {
        if usize::from(vertex) >= self.vertices.len() {
            return Err(Error::VertexOutOfRange);
        }
        if self.corners.len() - self.committed_corners >= MAX_POLYGON_CORNERS {
            return Err(Error::TooManyCorners);
        }
        if self.open_polygon.is_none() {
            self.open_polygon = Some(self.vertices.len());
        }
        self.corners.push(vertex).map_err(|_| Error::EdgeTableFull)
    }

    /// Closes the open polygon; see [`PolygonTables::finish_polygon`].
    pub fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        let start = self.committed_corners;
        let mut outline = OutlineBuilder::default();
        for &index in &self.corners[start..] {
            outline.add(self.vertices[usize::from(index)]);
        }
        let outline = outline.finish();
        let verdict = self.judge(&outline);
        let rows = match verdict {
            Ok(Ok(rows)) => rows,
            other => {
                self.discard_open_polygon();
                return other.map(|v| v.err().unwrap_or(Admission::Declined));
            }
        };
        let Some(color) = decide(&outline) else {
            self.discard_open_polygon();
            return Ok(Admission::Declined);
        };
        if self.polygons.is_full() {
            self.discard_open_polygon();
            return Err(Error::PolygonTableFull);
        }
        self.committed_corners = self.corners.len();
        self.open_polygon = None;
        Ok(self.queue(start, outline.corners, rows, color))
    }

    /// Removes the open polygon's corners and the vertices added since it
    /// began.
    fn discard_open_polygon(&mut self) {
        self.corners.truncate(self.committed_corners);
        if let Some(mark) = self.open_polygon.take() {
            self.vertices.truncate(mark);
        }
    }

    fn polygon_corners<'a>(
        &'a self,
        polygon: &PolygonEntry<C>,
    ) -> impl Iterator<Item = ScreenVertex> + Clone + 'a {
        entry_corners(polygon, &self.corners, &self.vertices)
    }

    /// Sorts the polygon table by first row and builds the edge table:
    /// for each polygon, the rows below its first row where some of its
    /// edges start (the others enter the active edge table with their
    /// polygon), sorted by row.
    fn build_edge_table(&mut self) -> Result<(), Error> {
        self.sort_polygon_table()?;
        self.edges.clear();
        let height = i32::from(self.height);
        for (position, polygon) in self.polygons.iter().enumerate() {
            for corner in 0..usize::from(polygon.corner_count) {
                let (top, bottom) = edge_ends(polygon, &self.corners, &self.vertices, corner);
                let Some((_, _, first, end)) = edge_rows(top, bottom) else {
                    continue;
                };
                let first = first.max(0);
                if first < end.min(height) && first > i32::from(polygon.first_row) {
                    let entry = EdgeEntry::new(first as u16, position);
                    self.edges.push(entry).map_err(|_| Error::EdgeTableFull)?;
                }
            }
        }
        self.edges.sort_unstable();
        Ok(())
    }

    /// Sorts the polygon table by (first row, insertion order). The keys
    /// `(row << 20) | index` are sorted as integers in the edge table's
    /// storage (not built yet; it holds at least one entry per polygon,
    /// since each has three corners or more), then the permutation is
    /// applied in place, cycle by cycle.
    fn sort_polygon_table(&mut self) -> Result<(), Error> {
        self.edges.clear();
        for (index, polygon) in self.polygons.iter().enumerate() {
            let key = EdgeEntry::new(polygon.first_row, index);
            self.edges.push(key).map_err(|_| Error::EdgeTableFull)?;
        }
        self.edges.sort_unstable();
        // Position k must receive the polygon at `edges[k].position()`.
        for start in 0..self.polygons.len() {
            if self.edges[start].position() == start {
                continue;
            }
            let saved = self.polygons[start];
            let mut at = start;
            loop {
                let from = self.edges[at].position();
                self.edges[at] = EdgeEntry::new(0, at);
                if from == start {
                    self.polygons[at] = saved;
                    break;
                }
                self.polygons[at] = self.polygons[from];
                at = from;
            }
        }
        Ok(())
    }

    /// Scans the frame top to bottom and sends every row to `sink`, one
    /// call per row. The tables are kept, so the same scene can be
    /// rendered again; call [`Self::clear`] before building the next one.
    pub fn render<S>(&mut self, sink: &mut S) -> Result<FrameStats, RenderError<S::Error>>
    where
        S: RowSink<C, D::Value>,
    {
        // A polygon left open is not part of the scene.
        self.discard_open_polygon();
        self.build_edge_table()?;
        self.active_polygons.clear();
        self.edge_pool.clear();
        self.dead_polygons = 0;
        self.current_row = 0;
        let mut stats = FrameStats {
            vertices: self.vertices.len() as u32,
            corners: self.corners.len() as u32,
            polygons: self.polygons.len() as u32,
            edges: 0,
            off_screen: self.off_screen,
            degenerate: self.degenerate,
            ..FrameStats::default()
        };
        let (mut next_polygon, mut next_edge) = (0usize, 0usize);
        for row in 0..self.height {
            while self
                .polygons
                .get(next_polygon)
                .is_some_and(|p| p.first_row == row)
            {
                stats.edges += self.activate_polygon(next_polygon, row)?;
                next_polygon += 1;
            }
            let mut previous = None;
            while let Some(&entry) = self.edges.get(next_edge).filter(|e| e.row() == row) {
                next_edge += 1;
                if previous == Some(entry) {
                    continue; // Several edges of one polygon start on this row.
                }
                previous = Some(entry);
                let position = entry.position() as u32;
                let slot = self
                    .active_polygons
                    .binary_search_by_key(&position, |a| a.position)
                    .map_err(|_| Error::ActivePolygonsFull { row })?;
                stats.edges += self.activate_edges(slot, row)?;
            }
            let live_polygons = (self.active_polygons.len() - self.dead_polygons) as u32;
            stats.peak_active_polygons = stats.peak_active_polygons.max(live_polygons);
            stats.peak_active_edges = stats.peak_active_edges.max(self.edge_pool.live);
            stats.peak_pooled_edges = stats.peak_pooled_edges.max(self.edge_pool.pooled);

            stats.spans += self.scan_row(row);
            let width = usize::from(self.width);
            sink.write_row(row, &self.color_row[..width], &self.depth_row[..width])
                .map_err(RenderError::Sink)?;
            self.advance(row + 1);
        }
        Ok(stats)
    }

    /// Moves the polygon at `position` in the polygon table into the APT at
    /// `row`, with its plane gradients and the edges that start on this
    /// row; returns how many edges entered.
    fn activate_polygon(&mut self, position: usize, row: u16) -> Result<u32, Error> {
        let polygon = self.polygons[position];
        let depth = match self.plane(&polygon).map(|p| (p, p.gradients())) {
            Some((plane, Some((dz_dx, dz_dy)))) => SpanDepth::Stepped {
                dz_dx,
                dz_dy,
                row_value: plane.value_at_pixel(0, i32::from(row)),
            },
            // Non-zero area was checked when the polygon entered the table.
            Some((_, None)) | None => SpanDepth::Exact,
        };
        if self.active_polygons.is_full() {
            self.compact_active_polygons();
        }
        let entry = ActivePolygon::new(position as u32, polygon.end_row, polygon.color, depth);
        self.active_polygons
            .push(entry)
            .map_err(|_| Error::ActivePolygonsFull { row })?;
        self.activate_edges(self.active_polygons.len() - 1, row)
    }

    /// The exact plane of a polygon-table entry; `None` for zero area.
    fn plane(&self, polygon: &PolygonEntry<C>) -> Option<Plane> {
        Plane::new(self.polygon_corners(polygon))
    }

    /// Starts every edge of the active polygon at `slot` whose first
    /// visible row is `row`; returns how many.
    fn activate_edges(&mut self, slot: usize, row: u16) -> Result<u32, Error> {
        let polygon = &self.polygons[self.active_polygons[slot].position as usize];
        let corners = entry_corners(polygon, &self.corners, &self.vertices);
        let end_limit = i32::from(self.height);
        let mut entered = 0;
        let next = corners.clone().skip(1).chain(corners.clone().take(1));
        for (a, b) in corners.zip(next) {
            let (top, bottom) = if a.y < b.y { (a, b) } else { (b, a) };
            let starts_here = top.y != bottom.y && EdgeEntry::first_row(top.y) == row;
            let end_row = first_sample_at_or_after(bottom.y).min(end_limit);
            if starts_here && end_row > i32::from(row) {
                let edge = ActiveEdge::start(top, bottom, row, end_row as u16, active::NO_EDGE);
                self.active_polygons[slot]
                    .add_edge(edge, &mut self.edge_pool)
                    .map_err(|()| Error::ActiveEdgesFull { row })?;
                entered += 1;
            }
        }
        Ok(entered)
    }

    /// Drops the APT entries of finished polygons, keeping the order.
    fn compact_active_polygons(&mut self) {
        if self.dead_polygons > 0 {
            let row = self.current_row;
            self.active_polygons.retain(|p| p.end_row > row);
            self.dead_polygons = 0;
        }
    }

    /// Resolves visibility on one row into the row buffers; returns the
    /// number of spans filled.
    fn scan_row(&mut self, row: u16) -> u32 {
        let width = usize::from(self.width);
        self.depth_row[..width].fill(D::CLEAR);
        self.color_row[..width].fill(self.background);
        let mut spans = 0;
        let (depth_row, color_row) = (&mut self.depth_row, &mut self.color_row);
        for polygon in &self.active_polygons {
            if polygon.end_row <= row {
                continue;
            }
            let source = match polygon.depth {
                SpanDepth::Stepped {
                    dz_dx, row_value, ..
                } => SpanSource::Stepped { dz_dx, row_value },
                SpanDepth::Exact => {
                    let entry = &self.polygons[polygon.position as usize];
                    match Plane::new(entry_corners(entry, &self.corners, &self.vertices)) {
                        Some(plane) => SpanSource::Exact(plane, row),
                        None => continue,
                    }
                }
            };
            let mut fill = |start: i32, end: i32| {
                let (start, end) = (
                    start.clamp(0, width as i32) as usize,
                    end.clamp(0, width as i32) as usize,
                );
                if start < end {
                    spans += 1;
                    fill_span::<C, D>(
                        &mut depth_row[start..end],
                        &mut color_row[start..end],
                        start as i32,
                        polygon.color,
                        &source,
                    );
                }
            };
            polygon.for_each_span(&self.edge_pool, &mut fill);
        }
        spans
    }

    /// Steps the active tables down to `next_row`: edges that ended are
    /// dropped, the others step; finished polygons are counted dead and
    /// swept out once they are half the table (or when it fills up).
    fn advance(&mut self, next_row: u16) {
        self.current_row = next_row;
        for polygon in &mut self.active_polygons {
            if polygon.end_row < next_row {
                continue; // Already dead.
            }
            polygon.advance_edges(next_row, &mut self.edge_pool);
            if polygon.end_row == next_row {
                self.dead_polygons += 1;
            } else if let SpanDepth::Stepped {
                dz_dy, row_value, ..
            } = &mut polygon.depth
            {
                *row_value += *dz_dy;
            }
        }
        if self.dead_polygons * 2 > self.active_polygons.len() {
            self.compact_active_polygons();
        }
    }
}

impl<
    C: Copy,
    D: DepthFormat,
    const W: usize,
    const V: usize,
    const P: usize,
    const E: usize,
    const AP: usize,
    const AE: usize,
> PolygonTables<C> for Renderer<C, D, W, V, P, E, AP, AE>
{
    fn frame_width(&self) -> u16 {
        self.width
    }

    fn frame_height(&self) -> u16 {
        self.height
    }

    fn add_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        self.push_vertex(vertex)
    }

    fn get_vertex(&self, index: u16) -> Option<ScreenVertex> {
        self.vertex(index)
    }

    fn begin_polygon(&mut self) {
        Renderer::begin_polygon(self);
    }

    fn discard_polygon(&mut self) {
        Renderer::discard_polygon(self);
    }

    fn add_corner(&mut self, vertex: u16) -> Result<(), Error> {
        Renderer::add_corner(self, vertex)
    }

    fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        Renderer::offer_polygon(self, corners, decide)
    }

    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        Renderer::finish_polygon(self, decide)
    }
}

/// The corners of a polygon-table entry, as vertices.
fn entry_corners<'a, C>(
    polygon: &PolygonEntry<C>,
    corners: &'a [u16],
    vertices: &'a [ScreenVertex],
) -> impl Iterator<Item = ScreenVertex> + Clone + 'a {
    let start = polygon.corner_start as usize;
    corners[start..start + usize::from(polygon.corner_count)]
        .iter()
        .map(move |&i| vertices[usize::from(i)])
}

/// Upper and lower end of the edge leaving corner `corner` of `polygon`.
fn edge_ends<C>(
    polygon: &PolygonEntry<C>,
    corners: &[u16],
    vertices: &[ScreenVertex],
    corner: usize,
) -> (ScreenVertex, ScreenVertex) {
    let start = polygon.corner_start as usize;
    let count = usize::from(polygon.corner_count);
    let a = vertices[usize::from(corners[start + corner])];
    let b = vertices[usize::from(corners[start + (corner + 1) % count])];
    if a.y < b.y { (a, b) } else { (b, a) }
}

/// Where a span's depths come from.
enum SpanSource {
    /// From the row's plane value at column 0 and the gradient.
    Stepped { dz_dx: i64, row_value: i64 },
    /// Exactly from the plane, at each pixel of the row.
    Exact(Plane, u16),
}

/// Depth-tests and writes one span: pixels `x0 .. x0 + depths.len()`.
fn fill_span<C: Copy, D: DepthFormat>(
    depths: &mut [D::Value],
    colors: &mut [C],
    x0: i32,
    color: C,
    source: &SpanSource,
) {
    let write = |depth: D::Value, stored: &mut D::Value, pixel: &mut C| {
        if depth < *stored {
            *stored = depth;
            *pixel = color;
        }
    };
    let len = depths.len() as u32;
    let pixels = depths.iter_mut().zip(colors.iter_mut());
    match *source {
        SpanSource::Stepped { dz_dx, row_value } => {
            // Re-evaluated from the plane at every span start: the error
            // is the gradient's rounding times the column, never drift from
            // earlier spans.
            // |dz_dx| < 2^40 (steeper polygons are `Exact`) and x0 < 2^12,
            // and row_value stays within 2^54 of the depth range: no
            // overflow is possible.
            let start = row_value + dz_dx * i64::from(x0);
            if let Some((mut acc, step)) = D::span(start, dz_dx, len) {
                for (stored, pixel) in pixels {
                    write(D::value(acc), stored, pixel);
                    acc = D::advance(acc, step);
                }
            } else {
                let mut value = start;
                for (stored, pixel) in pixels {
                    write(D::quantize(value), stored, pixel);
                    value = value.saturating_add(dz_dx);
                }
            }
        }
        SpanSource::Exact(plane, row) => {
            for (k, (stored, pixel)) in pixels.enumerate() {
                let value = plane.value_at_pixel(x0 + k as i32, i32::from(row));
                write(D::quantize(value), stored, pixel);
            }
        }
    }
}
