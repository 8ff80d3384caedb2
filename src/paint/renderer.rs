//! The [`PaintedRenderer`]: a [`Renderer`] whose tables and scanner hold
//! slots instead of colours, with the values of its vertices, the planes
//! of its active polygons and a [`PaintMode`] that paints each row.

use crate::error::{Error, RenderError};
use crate::front::geometry::Mat4;
use crate::front::mesh::Mesh;
use crate::front::scene::{
    CacheStorage, Camera, Cull, DrawError, DrawStats, VertexInfo, VertexValues,
    draw_mesh_with_values,
};
use crate::paint::{PaintArrays, PaintMode, PaintStorage, Painter};
use crate::raster::depth::DepthFormat;
use crate::raster::paint::{NO_SLOT, scan_painted_prechecked};
use crate::raster::scan::{ScanArrays, ScanStorage, Scanner};
use crate::raster::stats::FrameStats;
use crate::raster::tables::{Admission, TableArrays, TableStorage, Tables};
use crate::raster::vertex::ScreenVertex;
use crate::renderer::Renderer;
use crate::sink::RowSink;

/// The colour of a painted renderer's mode.
type ColorOf<A> = <<A as PaintStorage>::Mode as PaintMode>::Color;
/// The vertex value of a painted renderer's mode.
type VertexOf<A> = <<A as PaintStorage>::Mode as PaintMode>::Vertex;
/// The vertex source of a painted renderer's mode.
type SourceOf<A> = <<A as PaintStorage>::Mode as PaintMode>::Source;

/// A renderer that shades after visibility: its polygons carry values at
/// their corners (a colour per vertex for [`Gouraud`](crate::paint::Gouraud)
/// shading), and each visible pixel is painted once from the planes of
/// those values over the polygon that wins it.
///
/// It is a [`Renderer`] whose rows hold, while they are scanned, the slot
/// of each pixel's polygon in the active polygon table (`u16`), with the
/// arrays its painting needs ([`PaintStorage`]).
pub struct PaintedRenderer<T, S, K, A>
where
    T: TableStorage<Color = u16>,
    S: ScanStorage<Color = u16>,
    A: PaintStorage,
{
    /// The tables and the scanner, which write slots.
    pub renderer: Renderer<T, S, K>,
    /// The values of the vertices, the planes and the painted row.
    pub paint: A,
    /// How rows are painted.
    pub mode: A::Mode,
    background: ColorOf<A>,
}

impl<T, S, K, A> PaintedRenderer<T, S, K, A>
where
    T: TableStorage<Color = u16>,
    S: ScanStorage<Color = u16>,
    A: PaintStorage,
{
    /// A painted renderer over the given storage for frames `width` x
    /// `height`, painting with `mode` and clearing to `background`. The
    /// paint storage must hold a value for every vertex the tables hold, a
    /// plane entry for every APT slot and a row as wide as the frame.
    pub fn from_storage(
        (tables, scanner, cache, mut paint): (T, S, K, A),
        (width, height): (u16, u16),
        mode: A::Mode,
        background: ColorOf<A>,
    ) -> Result<Self, Error> {
        let (mut tables, mut scanner) = (tables, scanner);
        let vertices = tables.parts_mut().vertices.len();
        let active = scanner.parts_mut().active.len();
        let parts = paint.parts_mut();
        if parts.vertices.len() < vertices.min(1 << 16) || parts.slots.len() < active.min(1 << 16) {
            return Err(Error::PaintStorageTooSmall);
        }
        if parts.row.len() < usize::from(width) {
            return Err(Error::BadFrameSize);
        }
        Ok(Self {
            renderer: Renderer::from_storage((tables, scanner, cache), width, height, NO_SLOT)?,
            paint,
            mode,
            background,
        })
    }

    /// Frame width in pixels.
    pub fn width(&self) -> u16 {
        self.renderer.width()
    }

    /// Frame height in rows.
    pub fn height(&self) -> u16 {
        self.renderer.height()
    }

    /// Colour of pixels no polygon covers.
    pub fn background(&self) -> ColorOf<A> {
        self.background
    }

    /// Sets the colour of pixels no polygon covers.
    pub fn set_background(&mut self, background: ColorOf<A>) {
        self.background = background;
    }

    /// Empties the tables for the next frame.
    pub fn clear(&mut self) {
        self.renderer.clear();
    }

    /// Adds a vertex with its value; see
    /// [`Renderer::push_vertex`](crate::Renderer::push_vertex).
    pub fn push_vertex(&mut self, vertex: ScreenVertex, value: VertexOf<A>) -> Result<u16, Error> {
        let index = self.renderer.push_vertex(vertex)?;
        self.set_value(index, value)?;
        Ok(index)
    }

    /// Offers a polygon of vertices added before, by their indices; see
    /// [`Renderer::push_polygon`](crate::Renderer::push_polygon).
    pub fn push_polygon(&mut self, corners: &[u16]) -> Result<Admission, Error> {
        self.renderer.push_polygon(corners, 0)
    }

    /// Adds a polygon's corners, each with its value, and the polygon in
    /// one step; see
    /// [`Renderer::push_polygon_vertices`](crate::Renderer::push_polygon_vertices).
    pub fn push_polygon_vertices(
        &mut self,
        corners: &[ScreenVertex],
        values: &[VertexOf<A>],
    ) -> Result<Admission, Error> {
        if values.len() != corners.len() {
            return Err(Error::ValueCountMismatch);
        }
        let first = self.renderer.vertex_count();
        let admission = self.renderer.push_polygon_vertices(corners, 0)?;
        if matches!(admission, Admission::Queued(_)) {
            for (k, &value) in values.iter().enumerate() {
                // The tables took the corners as vertices `first..`.
                self.set_value((first + k) as u16, value)?;
            }
        }
        Ok(admission)
    }

    /// Sets the value of vertex `index`.
    fn set_value(&mut self, index: u16, value: VertexOf<A>) -> Result<(), Error> {
        let slot = self
            .paint
            .parts_mut()
            .vertices
            .get_mut(usize::from(index))
            .ok_or(Error::PaintStorageTooSmall)?;
        *slot = value;
        Ok(())
    }

    /// Prepares the tables and scans every row into `sink`, painting each,
    /// one call per row. The tables are kept, so the same scene can be
    /// rendered again.
    pub fn render<R>(&mut self, sink: &mut R) -> Result<FrameStats, RenderError<R::Error>>
    where
        R: RowSink<ColorOf<A>, <S::Depth as DepthFormat>::Value>,
    {
        let height = self.renderer.tables.height();
        let prepared = self.renderer.tables.prepare();
        let parts = self.paint.parts_mut();
        let mut painter = Painter {
            mode: &self.mode,
            vertices: parts.vertices,
            slots: parts.slots,
            background: self.background,
        };
        scan_painted_prechecked(
            &prepared,
            &mut self.renderer.scanner,
            &mut painter,
            parts.row,
            0..height,
            sink,
        )
    }
}

impl<
    M: PaintMode,
    D: DepthFormat,
    const V: usize,
    const P: usize,
    const E: usize,
    const W: usize,
    const AP: usize,
    const AE: usize,
    K: CacheStorage,
>
    PaintedRenderer<
        TableArrays<u16, V, P, E>,
        ScanArrays<u16, D, W, AP, AE>,
        K,
        PaintArrays<M, V, AP, W>,
    >
{
    /// A painted renderer in fixed arrays for frames `width` (at most `W`)
    /// by `height`, painting with `mode` and clearing to `background`.
    pub fn new(width: u16, height: u16, mode: M, background: M::Color) -> Result<Self, Error> {
        Self::from_storage(
            (
                TableArrays::new(0),
                ScanArrays::new(NO_SLOT),
                K::EMPTY,
                PaintArrays::new(background),
            ),
            (width, height),
            mode,
            background,
        )
    }

    /// As [`Self::new`], `const`, for statics (built at compile time,
    /// never copied through the stack); an invalid size stops the build.
    pub const fn new_in_static(width: u16, height: u16, mode: M, background: M::Color) -> Self {
        if width as usize > W {
            panic!("zline: the frame is wider than the scanner's rows");
        }
        Self {
            renderer: Renderer {
                tables: Tables::new_in_static(TableArrays::new(0), width, height),
                scanner: Scanner::new(ScanArrays::new(NO_SLOT), NO_SLOT),
                cache: K::EMPTY,
            },
            paint: PaintArrays::new(background),
            mode,
            background,
        }
    }
}

/// The [`PaintedRenderer`] type in fixed arrays for capacities `$caps` (a
/// [`Capacities`](crate::Capacities) constant), paint mode `$mode` (such
/// as `Gouraud<Rgb565>`) and depth format `$depth`, as
/// [`renderer_type!`](crate::renderer_type) spells a flat one. Its
/// `active_polygons` must count the polygons of one row that the flat scan
/// draws at once (those covering one row): size it from a painted frame's
/// [`FrameStats`](crate::FrameStats).
///
/// ```
/// use embedded_graphics_core::pixelcolor::Rgb565;
/// use zline::paint::Gouraud;
/// use zline::{Capacities, Depth16};
///
/// const CAPS: Capacities = Capacities {
///     width: 16,
///     vertices: 8,
///     polygons: 2,
///     corners: 8,
///     active_polygons: 2,
///     pooled_edges: 0,
///     mesh_vertices: 0,
/// };
/// type Zg = zline::painted_renderer_type!(Gouraud<Rgb565>, Depth16, CAPS);
/// let renderer = Zg::new(16, 16, Gouraud::new(), Rgb565::new(0, 0, 0)).unwrap();
/// assert_eq!(renderer.width(), 16);
/// ```
#[macro_export]
macro_rules! painted_renderer_type {
    ($mode:ty, $depth:ty, $caps:expr $(,)?) => {
        $crate::paint::PaintedRenderer<
            $crate::TableArrays<u16, { $caps.vertices }, { $caps.polygons }, { $caps.corners }>,
            $crate::ScanArrays<
                u16,
                $depth,
                { $caps.width },
                { $caps.active_polygons },
                { $caps.pooled_edges },
            >,
            $crate::VertexCache<{ $caps.mesh_vertices }>,
            $crate::paint::PaintArrays<
                $mode,
                { $caps.vertices },
                { $caps.active_polygons },
                { $caps.width },
            >,
        >
    };
}

impl<T, S, K, A> PaintedRenderer<T, S, K, A>
where
    T: TableStorage<Color = u16>,
    S: ScanStorage<Color = u16>,
    K: CacheStorage,
    A: PaintStorage,
{
    /// Draws `mesh` with the `model` matrix through `camera` into the
    /// tables, as [`Renderer::draw_mesh`] does, each vertex getting its
    /// value from `shade` (for [`Gouraud`](crate::paint::Gouraud), its
    /// colour, for example
    /// [`Shading::vertex_color`](crate::Shading::vertex_color)); a corner
    /// that clipping makes gets its edge's values interpolated. Call
    /// [`Self::render`] afterwards.
    pub fn draw_mesh<M: Mesh>(
        &mut self,
        mesh: &M,
        model: &Mat4,
        camera: &Camera,
        cull: Cull,
        shade: impl Fn(&VertexInfo<'_>) -> SourceOf<A>,
    ) -> Result<DrawStats, DrawError> {
        let parts = self.paint.parts_mut();
        let mut values = PaintValues {
            mode: &self.mode,
            shade,
            vertices: parts.vertices,
        };
        let Renderer { tables, cache, .. } = &mut self.renderer;
        draw_mesh_with_values(tables, cache, mesh, (model, camera, cull), &mut values)
    }
}

/// A painted draw's vertex values: each vertex's source from `shade`, its
/// value stored at its vertex-table index.
struct PaintValues<'a, M: PaintMode, F> {
    mode: &'a M,
    shade: F,
    vertices: &'a mut [M::Vertex],
}

impl<M: PaintMode, F: Fn(&VertexInfo<'_>) -> M::Source> VertexValues for PaintValues<'_, M, F> {
    type Source = M::Source;
    const STORES: bool = true;

    fn split(
        &mut self,
    ) -> (
        impl Fn(&VertexInfo<'_>) -> M::Source + '_,
        impl FnMut(u16, M::Source) -> Result<(), Error> + '_,
    ) {
        let (shade, mode, vertices) = (&self.shade, self.mode, &mut *self.vertices);
        let store = move |id: u16, source: M::Source| {
            let slot = vertices
                .get_mut(usize::from(id))
                .ok_or(Error::PaintStorageTooSmall)?;
            *slot = mode.vertex(source);
            Ok(())
        };
        (shade, store)
    }
}
