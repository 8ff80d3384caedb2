//! Capacities by name, and the [`Renderer`]: tables and a scanner in one
//! value, for the common case of one scanner per frame.
//!
//! Fixed-capacity storage takes its capacities as const parameters; name
//! them through a [`Capacities`] constant so nobody counts positions:
//!
//! ```
//! use embedded_graphics_core::pixelcolor::Rgb565;
//! use zline::{Capacities, Renderer, ScanArrays, TableArrays};
//! use zline::Depth16;
//!
//! const CAPS: Capacities = Capacities {
//!     width: 240,
//!     vertices: 600,
//!     polygons: 1000,
//!     corners: 3000,
//!     active_polygons: 256,
//!     pooled_edges: 0,
//! };
//! type Tables = TableArrays<Rgb565, { CAPS.vertices }, { CAPS.polygons }, { CAPS.corners }>;
//! type Rows = ScanArrays<Rgb565, Depth16, { CAPS.width }, { CAPS.active_polygons }, { CAPS.pooled_edges }>;
//! // Built at compile time; in firmware, in a `static` cell.
//! static RENDERER: Renderer<Tables, Rows> = Renderer::new_in_static(240, 240, Rgb565::new(0, 0, 0));
//! assert!(CAPS.ram_bytes::<Rgb565, Depth16>() <= core::mem::size_of::<Renderer<Tables, Rows>>());
//! ```

use core::mem::size_of;

use crate::error::{Error, RenderError};
use crate::raster::PolygonTables;
use crate::raster::active::ActivePolygon;
use crate::raster::depth::DepthFormat;
use crate::raster::edge::{ActiveEdge, EdgeEntry};
use crate::raster::scan::{FrameStats, ScanArrays, ScanStorage, Scanner, scan};
use crate::raster::tables::{Admission, PolygonEntry, TableArrays, TableStorage, Tables};
use crate::raster::vertex::{Outline, ScreenVertex};
use crate::sink::RowSink;

/// How much the tables and a scanner hold, by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Capacities {
    /// Row capacity: the widest frame, in pixels (the scanner's rows).
    pub width: usize,
    /// Vertices in the vertex table (at most 65,536).
    pub vertices: usize,
    /// Polygons in the polygon table (at most
    /// [`MAX_POLYGONS`](crate::limits::MAX_POLYGONS) are used).
    pub polygons: usize,
    /// Corners of all polygons together (3 per triangle); the edge table
    /// has as many entries.
    pub corners: usize,
    /// Polygons active on one row at once.
    pub active_polygons: usize,
    /// Active edges beyond each polygon's first two (zero for triangles and
    /// convex polygons).
    pub pooled_edges: usize,
}

impl Capacities {
    /// The capacities a frame of `width` pixels with these counts needs
    /// (take the [`FrameStats::max`] over every frame to be shown). They
    /// also fit a scanner of any band of the frame's rows, and each band
    /// of a banded renderer: a band holds no more polygons, corners or
    /// vertices than the frame, and needs no more active polygons or
    /// pooled edges on any row than one scan of the frame.
    pub fn from_stats(stats: &FrameStats, width: usize) -> Self {
        let n = |count: u32| count as usize;
        Self {
            width,
            vertices: n(stats.vertices),
            polygons: n(stats.polygons),
            corners: n(stats.corners),
            active_polygons: n(stats.peak_active_polygons),
            pooled_edges: n(stats.peak_pooled_edges),
        }
    }

    /// Bytes of the arrays of tables and a scanner with these capacities,
    /// colour `C` and depth `D`: the three rows (colour, depth, tie-break
    /// key), the vertex, polygon, corner
    /// and edge tables, and the active tables.
    pub fn ram_bytes<C, D: DepthFormat>(&self) -> usize {
        self.width * (size_of::<C>() + size_of::<D::Value>() + size_of::<u32>())
            + self.vertices * size_of::<ScreenVertex>()
            + self.polygons * size_of::<PolygonEntry<C>>()
            + self.corners * (size_of::<u16>() + size_of::<EdgeEntry>())
            + self.active_polygons * (size_of::<ActivePolygon<C>>() + size_of::<u16>())
            + self.pooled_edges * size_of::<ActiveEdge>()
    }
}

impl FrameStats {
    /// Bytes of tables and a scanner sized exactly for these counts in a
    /// frame `width` wide (see [`Capacities::from_stats`] and
    /// [`Capacities::ram_bytes`]).
    pub fn ram_bytes<C, D: DepthFormat>(&self, width: usize) -> usize {
        Capacities::from_stats(self, width).ram_bytes::<C, D>()
    }
}

/// Tables and a scanner in one value: build a frame's scene with the
/// `push_*` methods (or [`crate::front::scene::draw_mesh`]), then
/// [`Self::render`] it; [`Self::clear`] before the next frame.
#[derive(Clone)]
pub struct Renderer<T: TableStorage, S: ScanStorage<Color = T::Color>> {
    /// The scene-sized tables.
    pub tables: Tables<T>,
    /// The row-sized scanner.
    pub scanner: Scanner<S>,
}

impl<T, S> core::fmt::Debug for Renderer<T, S>
where
    T: TableStorage + core::fmt::Debug,
    S: ScanStorage<Color = T::Color> + core::fmt::Debug,
    T::Color: core::fmt::Debug,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Renderer")
            .field("tables", &self.tables)
            .field("scanner", &self.scanner)
            .finish()
    }
}

impl<T: TableStorage, S: ScanStorage<Color = T::Color>> Renderer<T, S> {
    /// A renderer over the given storage for frames `width` x `height`,
    /// clearing to `background`. `width` must fit the scanner's rows.
    pub fn from_storage(
        tables: T,
        scanner: S,
        width: u16,
        height: u16,
        background: T::Color,
    ) -> Result<Self, Error> {
        let mut scanner = Scanner::new(scanner, background);
        if usize::from(width) > scanner.row_capacity() {
            return Err(Error::BadFrameSize);
        }
        Ok(Self {
            tables: Tables::new(tables, width, height)?,
            scanner,
        })
    }

    /// Frame width in pixels.
    pub fn width(&self) -> u16 {
        self.tables.width()
    }

    /// Frame height in rows.
    pub fn height(&self) -> u16 {
        self.tables.height()
    }

    /// Colour of pixels no polygon covers.
    pub fn set_background(&mut self, background: T::Color) {
        self.scanner.set_background(background);
    }

    /// Empties the tables for the next frame.
    pub fn clear(&mut self) {
        self.tables.clear();
    }

    /// Number of vertices in the vertex table.
    pub fn vertex_count(&self) -> usize {
        self.tables.vertex_count()
    }

    /// Number of polygons in the polygon table.
    pub fn polygon_count(&self) -> usize {
        self.tables.polygon_count()
    }

    /// Vertex `index` of the vertex table.
    pub fn vertex(&self, index: u16) -> Option<ScreenVertex> {
        self.tables.vertex(index)
    }

    /// See [`Tables::push_vertex`].
    pub fn push_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        self.tables.push_vertex(vertex)
    }

    /// See [`Tables::push_polygon`].
    pub fn push_polygon(&mut self, corners: &[u16], color: T::Color) -> Result<Admission, Error> {
        self.tables.push_polygon(corners, color)
    }

    /// See [`Tables::push_polygon_vertices`].
    pub fn push_polygon_vertices(
        &mut self,
        corners: &[ScreenVertex],
        color: T::Color,
    ) -> Result<Admission, Error> {
        self.tables.push_polygon_vertices(corners, color)
    }

    /// Gives the polygon queued by the call just before a plane shared
    /// with other polygons; see [`Tables::share_plane`].
    pub fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error> {
        self.tables.share_plane(plane)
    }

    /// Prepares the tables and scans every row into `sink`, one call per
    /// row. The tables are kept, so the same scene can be rendered again.
    pub fn render<K>(&mut self, sink: &mut K) -> Result<FrameStats, RenderError<K::Error>>
    where
        K: RowSink<T::Color, <S::Depth as DepthFormat>::Value>,
    {
        let height = self.tables.height();
        let prepared = self.tables.prepare();
        scan(&prepared, &mut self.scanner, 0..height, sink)
    }
}

impl<
    C: Copy,
    D: DepthFormat,
    const V: usize,
    const P: usize,
    const E: usize,
    const W: usize,
    const AP: usize,
    const AE: usize,
> Renderer<TableArrays<C, V, P, E>, ScanArrays<C, D, W, AP, AE>>
{
    /// A renderer in fixed arrays for frames `width` (at most `W`) by
    /// `height`, clearing to `background`.
    pub fn with_size(width: u16, height: u16, background: C) -> Result<Self, Error> {
        Self::from_storage(
            TableArrays::new(background),
            ScanArrays::new(background),
            width,
            height,
            background,
        )
    }

    /// A renderer in fixed arrays for frames `W` wide and `height` tall.
    pub fn new(height: u16, background: C) -> Result<Self, Error> {
        let width = u16::try_from(W).map_err(|_| Error::BadFrameSize)?;
        Self::with_size(width, height, background)
    }

    /// As [`Self::with_size`], `const`, for statics (built at compile time,
    /// never copied through the stack); an invalid size stops the build.
    pub const fn new_in_static(width: u16, height: u16, background: C) -> Self {
        if width as usize > W {
            panic!("zline: the frame is wider than the scanner's rows");
        }
        Self {
            tables: Tables::new_in_static(TableArrays::new(background), width, height),
            scanner: Scanner::new(ScanArrays::new(background), background),
        }
    }
}

impl<T: TableStorage, S: ScanStorage<Color = T::Color>> PolygonTables<T::Color> for Renderer<T, S> {
    fn frame_width(&self) -> u16 {
        self.tables.width()
    }

    fn frame_height(&self) -> u16 {
        self.tables.height()
    }

    fn add_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        self.tables.push_vertex(vertex)
    }

    fn get_vertex(&self, index: u16) -> Option<ScreenVertex> {
        self.tables.vertex(index)
    }

    fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<T::Color>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        self.tables.offer_polygon(corners, decide)
    }

    fn offer_triangle(
        &mut self,
        corners: [u16; 3],
        decide: impl FnOnce(&Outline) -> Option<T::Color>,
    ) -> Result<Admission, Error> {
        self.tables.offer_triangle(corners, decide)
    }

    fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error> {
        self.tables.share_plane(plane)
    }

    fn begin_polygon(&mut self) {
        PolygonTables::begin_polygon(&mut self.tables);
    }

    fn discard_polygon(&mut self) {
        PolygonTables::discard_polygon(&mut self.tables);
    }

    fn add_corner(&mut self, vertex: u16) -> Result<(), Error> {
        PolygonTables::add_corner(&mut self.tables, vertex)
    }

    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<T::Color>,
    ) -> Result<Admission, Error> {
        PolygonTables::finish_polygon(&mut self.tables, decide)
    }
}
