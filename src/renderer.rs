//! The [`Renderer`]: a scene's tables, a scanner and a vertex cache in
//! one value, for the common case of one scanner per frame. It sits above
//! the core and the front end, and joins them: [`Renderer::draw_mesh`]
//! draws a mesh into its tables, [`Renderer::render`] scans them into a
//! [`RowSink`].

use crate::error::{Error, RenderError};
use crate::front::geometry::Mat4;
use crate::front::mesh::Mesh;
use crate::front::scene::{
    CacheStorage, Camera, Cull, DrawError, DrawStats, FaceInfo, NoVertexCache, draw_mesh,
};
use crate::raster::PolygonTables;
use crate::raster::depth::DepthFormat;
use crate::raster::scan::{ScanArrays, ScanStorage, Scanner, scan};
use crate::raster::stats::FrameStats;
use crate::raster::tables::{Admission, TableArrays, TableStorage, Tables};
use crate::raster::vertex::{Outline, ScreenVertex};
use crate::sink::RowSink;

/// Tables, a scanner and a vertex cache in one value: build a frame's
/// scene with [`Self::draw_mesh`] (or the `push_*` methods, for screen
/// polygons), then [`Self::render`] it; [`Self::clear`] before the next
/// frame.
///
/// In fixed arrays its type comes from one [`Capacities`](crate::Capacities)
/// value, [`renderer_type!`](crate::renderer_type); on a desktop,
/// `Renderer::for_mesh` (in `zline::host`, feature `std`) sizes it from the mesh.
#[derive(Clone)]
pub struct Renderer<T: TableStorage, S: ScanStorage<Color = T::Color>, K = NoVertexCache> {
    /// The scene-sized tables.
    pub tables: Tables<T>,
    /// The row-sized scanner.
    pub scanner: Scanner<S>,
    /// Where [`Self::draw_mesh`] remembers each mesh vertex's entry in the
    /// vertex table.
    pub cache: K,
}

impl<T, S, K> core::fmt::Debug for Renderer<T, S, K>
where
    T: TableStorage + core::fmt::Debug,
    S: ScanStorage<Color = T::Color> + core::fmt::Debug,
    T::Color: core::fmt::Debug,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Renderer")
            .field("tables", &self.tables)
            .field("scanner", &self.scanner)
            .finish_non_exhaustive()
    }
}

impl<T: TableStorage, S: ScanStorage<Color = T::Color>, K> Renderer<T, S, K> {
    /// A renderer over the given storage for frames `width` x `height`,
    /// clearing to `background`. `width` must fit the scanner's rows.
    pub fn from_storage(
        (tables, scanner, cache): (T, S, K),
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
            cache,
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
    pub fn render<R>(&mut self, sink: &mut R) -> Result<FrameStats, RenderError<R::Error>>
    where
        R: RowSink<T::Color, <S::Depth as DepthFormat>::Value>,
    {
        let height = self.tables.height();
        let prepared = self.tables.prepare();
        scan(&prepared, &mut self.scanner, 0..height, sink)
    }
}

impl<T, S, K> Renderer<T, S, K>
where
    T: TableStorage,
    S: ScanStorage<Color = T::Color>,
    K: CacheStorage,
{
    /// Draws `mesh` with the `model` matrix through `camera` into the
    /// tables, as [`draw_mesh`](crate::draw_mesh) does with this
    /// renderer's own vertex cache (it must hold the mesh's vertices:
    /// [`Capacities::mesh_vertices`](crate::Capacities::mesh_vertices)).
    /// Call [`Self::render`] afterwards; several meshes may be drawn into
    /// one frame first.
    pub fn draw_mesh<M: Mesh>(
        &mut self,
        mesh: &M,
        model: &Mat4,
        camera: &Camera,
        cull: Cull,
        shade: impl FnMut(&FaceInfo) -> T::Color,
    ) -> Result<DrawStats, DrawError> {
        let Self { tables, cache, .. } = self;
        draw_mesh(tables, cache, mesh, model, camera, cull, shade)
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
    K: CacheStorage,
> Renderer<TableArrays<C, V, P, E>, ScanArrays<C, D, W, AP, AE>, K>
{
    /// A renderer in fixed arrays for frames `width` (at most `W`) by
    /// `height`, clearing to `background`.
    pub fn new(width: u16, height: u16, background: C) -> Result<Self, Error> {
        Self::from_storage(
            (
                TableArrays::new(background),
                ScanArrays::new(background),
                K::EMPTY,
            ),
            width,
            height,
            background,
        )
    }

    /// A renderer in fixed arrays for frames as wide as its rows (`W`),
    /// `height` tall.
    pub fn with_height(height: u16, background: C) -> Result<Self, Error> {
        let width = u16::try_from(W).map_err(|_| Error::BadFrameSize)?;
        Self::new(width, height, background)
    }

    /// As [`Self::new`], `const`, for statics (built at compile time,
    /// never copied through the stack); an invalid size stops the build.
    pub const fn new_in_static(width: u16, height: u16, background: C) -> Self {
        if width as usize > W {
            panic!("zline: the frame is wider than the scanner's rows");
        }
        Self {
            tables: Tables::new_in_static(TableArrays::new(background), width, height),
            scanner: Scanner::new(ScanArrays::new(background), background),
            cache: K::EMPTY,
        }
    }
}

impl<T, S, K> PolygonTables<T::Color> for Renderer<T, S, K>
where
    T: TableStorage,
    S: ScanStorage<Color = T::Color>,
{
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
