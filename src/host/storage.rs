//! The core's storage in ordinary `Vec`s, sized at run time from a
//! [`Capacities`] value: the same capacity-erased tables and scanner as on
//! a microcontroller, with no large value on the stack.

use std::vec::Vec;

use crate::error::Error;
use crate::host::HostMesh;
use crate::limits::{MAX_FRAME_SIZE, MAX_POLYGONS};
use crate::paint::{PaintMode, PaintParts, PaintStorage, PaintedRenderer, SlotPlanes};
use crate::raster::depth::DepthFormat;
use crate::raster::paint::NO_SLOT;
use crate::raster::scan::{ScanParts, ScanStorage};
use crate::raster::tables::{PolygonEntry, TableParts, TablePartsRef, TableStorage};
use crate::raster::vertex::ScreenVertex;
use crate::raster::{ActiveEdge, ActivePolygon, Capacities, EdgeEntry, SmallActive};
use crate::renderer::Renderer;

/// `count` copies of `value`, or `Err(`[`Error::StorageTooLarge`]`)` when
/// they cannot be allocated (instead of aborting).
fn filled<T: Clone>(count: usize, value: T) -> Result<Vec<T>, Error> {
    let mut values = Vec::new();
    values
        .try_reserve_exact(count)
        .map_err(|_| Error::StorageTooLarge)?;
    values.resize(count, value);
    Ok(values)
}

/// `caps` with each count cut to what the core can use: 65,536 vertices
/// (in the table and the vertex cache) and active polygons,
/// [`MAX_POLYGONS`] polygons, rows of [`MAX_FRAME_SIZE`] pixels.
fn within_core(caps: &Capacities) -> Capacities {
    const INDICES: usize = 1 << 16;
    Capacities {
        width: caps.width.min(MAX_FRAME_SIZE),
        vertices: caps.vertices.min(INDICES),
        polygons: caps.polygons.min(MAX_POLYGONS),
        active_polygons: caps.active_polygons.min(INDICES),
        mesh_vertices: caps.mesh_vertices.min(INDICES),
        ..*caps
    }
}

/// Table storage in `Vec`s.
#[derive(Debug, Clone)]
pub struct TableVecs<C> {
    vertices: Vec<ScreenVertex>,
    polygons: Vec<PolygonEntry<C>>,
    corners: Vec<u16>,
    edges: Vec<EdgeEntry>,
}

impl<C: Copy> TableVecs<C> {
    /// Storage for `caps.vertices` vertices, `caps.polygons` polygons and
    /// `caps.corners` corners; `filler` fills the unused polygon slots.
    /// Counts beyond what the core uses (65,536 vertices,
    /// [`MAX_POLYGONS`] polygons) are cut to it;
    /// `Err(`[`Error::StorageTooLarge`]`)` when the rest cannot be
    /// allocated.
    pub fn new(caps: &Capacities, filler: C) -> Result<Self, Error> {
        let caps = within_core(caps);
        Ok(Self {
            vertices: filled(caps.vertices, ScreenVertex::default())?,
            polygons: filled(caps.polygons, PolygonEntry::filler(filler))?,
            corners: filled(caps.corners, 0)?,
            edges: filled(caps.corners, EdgeEntry::ZERO)?,
        })
    }
}

impl<C: Copy> TableStorage for TableVecs<C> {
    type Color = C;

    fn parts_mut(&mut self) -> TableParts<'_, C> {
        TableParts {
            vertices: &mut self.vertices,
            polygons: &mut self.polygons,
            corners: &mut self.corners,
            edges: &mut self.edges,
        }
    }

    fn parts(&self) -> TablePartsRef<'_, C> {
        TablePartsRef {
            vertices: &self.vertices,
            polygons: &self.polygons,
            corners: &self.corners,
            edges: &self.edges,
        }
    }
}

/// Scanner storage in `Vec`s.
#[derive(Debug, Clone)]
pub struct ScanVecs<C, D: DepthFormat> {
    active: Vec<ActivePolygon<C>>,
    order: Vec<u16>,
    pool: Vec<ActiveEdge>,
    small: Vec<SmallActive<C>>,
    depth_row: Vec<D::Value>,
    color_row: Vec<C>,
    key_row: Vec<u32>,
}

/// Most entries of a [`ScanVecs`]' small triangles' table per pixel of a
/// row. The table holds small triangles that cover samples on the next
/// four rows; the bunny at 800x600, not culled, has at most 637 active
/// polygons of both kinds over a turn (`needs`), against 6,400 entries
/// here. A small triangle that finds no room waits in the active polygon
/// table, which has room for all, so the bound decides only where it
/// waits, never whether it is drawn.
pub const SMALL_TABLE_ENTRIES_PER_COLUMN: usize = 8;

impl<C: Copy, D: DepthFormat> ScanVecs<C, D> {
    /// Storage for rows of `caps.width` pixels, `caps.active_polygons`
    /// active polygons and `caps.pooled_edges` pooled edges; the small
    /// triangles' table takes at most [`SMALL_TABLE_ENTRIES_PER_COLUMN`]
    /// entries a pixel of the row (`Capacities::worst_case` gives a mesh
    /// of many faces 65,536 active polygons, which this table need not
    /// match: 3 MB for the bunny). Counts beyond what the core uses
    /// (65,536 active polygons, rows of [`MAX_FRAME_SIZE`] pixels) are cut
    /// to it; `Err(`[`Error::StorageTooLarge`]`)` when the rest cannot be
    /// allocated.
    pub fn new(caps: &Capacities, filler: C) -> Result<Self, Error> {
        let caps = within_core(caps);
        let (active, width) = (caps.active_polygons, caps.width);
        let small = active.min(SMALL_TABLE_ENTRIES_PER_COLUMN * width);
        Ok(Self {
            active: filled(active, ActivePolygon::filler(filler))?,
            order: filled(active, 0)?,
            pool: filled(caps.pooled_edges, ActiveEdge::EMPTY)?,
            small: filled(small, SmallActive::filler(filler))?,
            depth_row: filled(width, D::CLEAR)?,
            color_row: filled(width, filler)?,
            key_row: filled(width, 0)?,
        })
    }
}

impl<C: Copy, D: DepthFormat> ScanStorage for ScanVecs<C, D> {
    type Color = C;
    type Depth = D;

    fn parts_mut(&mut self) -> ScanParts<'_, C, D> {
        ScanParts {
            active: &mut self.active,
            order: &mut self.order,
            pool: &mut self.pool,
            small: &mut self.small,
            depth_row: &mut self.depth_row,
            color_row: &mut self.color_row,
            key_row: &mut self.key_row,
        }
    }
}

/// A [`Renderer`] in `Vec`s: tables, scanner and vertex cache.
pub type HostRenderer<C, D> = Renderer<TableVecs<C>, ScanVecs<C, D>, Vec<u16>>;

/// A renderer over `Vec` storage with capacities `caps` (a vertex cache of
/// `caps.mesh_vertices`) for frames `width` x `height` (`width` at most
/// `caps.width`), clearing to `background`.
pub fn host_renderer<C: Copy, D: DepthFormat>(
    caps: &Capacities,
    width: u16,
    height: u16,
    background: C,
) -> Result<HostRenderer<C, D>, Error> {
    Renderer::from_storage(
        (
            TableVecs::new(caps, background)?,
            ScanVecs::new(caps, background)?,
            filled(within_core(caps).mesh_vertices, 0)?,
        ),
        width,
        height,
        background,
    )
}

impl<C: Copy, D: DepthFormat> HostRenderer<C, D> {
    /// A renderer for frames `width` x `height` of `mesh`, from any view,
    /// culled or not: storage sized from the mesh
    /// ([`HostMesh::capacities`]), clearing to `background`. No frame of
    /// it can overflow a table, short of the core's own limits (see
    /// there).
    ///
    /// ```
    /// use embedded_graphics_core::pixelcolor::Rgb565;
    /// use zline::host::{HostMesh, HostRenderer};
    /// use zline::{Camera, Cull, Depth16, FnSink, Shading, reference_model};
    ///
    /// let mesh = HostMesh::from_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")?;
    /// let mut renderer = HostRenderer::<Rgb565, Depth16>::for_mesh(&mesh, 64, 48, Rgb565::new(0, 0, 0))?;
    /// let model = reference_model(&mesh, 0.0, 0.0)?;
    /// let shading = Shading::lambert();
    /// renderer.draw_mesh(&mesh, &model, &Camera::reference(64, 48), Cull::Back, |f| shading.color(f).into())?;
    /// let mut lit = 0;
    /// renderer.render(&mut FnSink(|_: u16, row: &[Rgb565], _: &[u16]| {
    ///     lit += row.iter().filter(|&&c| c != Rgb565::new(0, 0, 0)).count();
    ///     Ok::<(), ()>(())
    /// }))?;
    /// assert!(lit > 100);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn for_mesh(
        mesh: &HostMesh,
        width: u16,
        height: u16,
        background: C,
    ) -> Result<Self, Error> {
        host_renderer(&mesh.capacities(width), width, height, background)
    }
}

/// A painted renderer's own storage in `Vec`s: values for the vertex
/// table, planes for the active polygons and the painted row.
pub struct PaintVecs<M: PaintMode> {
    vertices: Vec<M::Vertex>,
    slots: Vec<SlotPlanes<M::Planes>>,
    row: Vec<M::Color>,
}

impl<M: PaintMode> PaintVecs<M> {
    /// Storage for `caps.vertices` vertices, `caps.active_polygons` active
    /// polygons and rows of `caps.width` pixels; `color` fills the row.
    /// Counts are cut and storage refused as [`ScanVecs::new`] does.
    pub fn new(caps: &Capacities, color: M::Color) -> Result<Self, Error> {
        let caps = within_core(caps);
        Ok(Self {
            vertices: filled(caps.vertices, M::VERTEX_FILLER)?,
            slots: filled(caps.active_polygons, SlotPlanes::filler(M::PLANES_FILLER))?,
            row: filled(caps.width, color)?,
        })
    }
}

impl<M: PaintMode> PaintStorage for PaintVecs<M> {
    type Mode = M;

    fn parts_mut(&mut self) -> PaintParts<'_, M> {
        PaintParts {
            vertices: &mut self.vertices,
            slots: &mut self.slots,
            row: &mut self.row,
        }
    }
}

/// A [`PaintedRenderer`] in `Vec`s: tables, scanner, vertex cache and
/// paint storage, painting with mode `M`.
pub type HostPaintedRenderer<M, D> =
    PaintedRenderer<TableVecs<u16>, ScanVecs<u16, D>, Vec<u16>, PaintVecs<M>>;

impl<M: PaintMode, D: DepthFormat> HostPaintedRenderer<M, D> {
    /// A painted renderer over `Vec` storage with capacities `caps` for
    /// frames `width` x `height`, painting with `mode` and clearing to
    /// `background`.
    pub fn with_capacities(
        caps: &Capacities,
        (width, height): (u16, u16),
        mode: M,
        background: M::Color,
    ) -> Result<Self, Error> {
        PaintedRenderer::from_storage(
            (
                TableVecs::new(caps, 0)?,
                ScanVecs::new(caps, NO_SLOT)?,
                filled(within_core(caps).mesh_vertices, 0)?,
                PaintVecs::new(caps, background)?,
            ),
            (width, height),
            mode,
            background,
        )
    }

    /// A painted renderer for frames `width` x `height` of `mesh`, from
    /// any view, culled or not, sized as [`HostRenderer::for_mesh`] sizes
    /// a flat one.
    ///
    /// ```
    /// use embedded_graphics_core::pixelcolor::Rgb565;
    /// use zline::host::{DEFAULT_CREASE_DEGREES, HostMesh, HostPaintedRenderer};
    /// use zline::paint::Gouraud;
    /// use zline::{Camera, Cull, Depth16, FnSink, Shading, reference_model};
    ///
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    /// let mesh = HostMesh::from_obj_smooth(obj, DEFAULT_CREASE_DEGREES)?;
    /// let black = Rgb565::new(0, 0, 0);
    /// let mut renderer =
    ///     HostPaintedRenderer::<Gouraud<Rgb565>, Depth16>::for_mesh(&mesh, 64, 48, Gouraud::new(), black)?;
    /// let model = reference_model(&mesh, 0.0, 0.0)?;
    /// let shading = Shading::lambert();
    /// renderer.draw_mesh(&mesh, &model, &Camera::reference(64, 48), Cull::Back, |v| shading.vertex_color(v))?;
    /// let mut lit = 0;
    /// renderer.render(&mut FnSink(|_: u16, row: &[Rgb565], _: &[u16]| {
    ///     lit += row.iter().filter(|&&c| c != black).count();
    ///     Ok::<(), ()>(())
    /// }))?;
    /// assert!(lit > 100);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn for_mesh(
        mesh: &HostMesh,
        width: u16,
        height: u16,
        mode: M,
        background: M::Color,
    ) -> Result<Self, Error> {
        Self::with_capacities(&mesh.capacities(width), (width, height), mode, background)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Depth24;

    /// The small triangles' table takes the active polygons' count up to
    /// its bound a pixel of the row, and never more.
    #[test]
    fn the_small_table_is_bounded_by_the_row() {
        let caps = |width, active_polygons| Capacities {
            width,
            vertices: 3,
            polygons: 1 << 16,
            corners: 3 << 16,
            active_polygons,
            pooled_edges: 0,
            mesh_vertices: 0,
        };
        for (width, active, want) in [(800, 1 << 16, 6400), (800, 637, 637), (240, 1 << 16, 1920)] {
            let mut vecs = ScanVecs::<u16, Depth24>::new(&caps(width, active), 0).unwrap();
            let parts = vecs.parts_mut();
            assert_eq!((parts.small.len(), parts.active.len()), (want, active));
        }
    }
}
