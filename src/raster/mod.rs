//! The core: the scanline z-buffer. Screen-space polygons in, finished
//! rows out.
//!
//! * [`fixed`]: the sub-pixel grid, the input depth format, the guard band
//!   and the exact rounding helpers.
//! * [`vertex`]: [`ScreenVertex`], the core's input, and the outline and
//!   bounding rectangle the core judges a polygon by.
//! * [`depth`]: the depth formats a row can store.
//! * [`tables`]: the scene-sized tables (vertices, polygons, corners, edge
//!   table), sorted by first row in O(n).
//! * [`scan`](mod@scan): the row-sized scanner (active polygon table, active edge
//!   pool, the depth row and the colour row) and [`scan()`](scan::scan),
//!   the driver of the row loop; [`stats`]: the counts it reports.
//! * `activation`, `stepping`, `span`: the scan's three jobs: polygons
//!   and edges entering the active tables; each active polygon stepped
//!   from row to row; its spans depth-tested and written into the row.
//!   `entry_geometry`: a queued polygon's corners, edges and plane, as
//!   they all read them (internal).
//! * [`capacities`]: the capacities, named, and the [`Renderer`](crate::Renderer) bundle of
//!   tables and scanner.
//! * [`zbuffer`]: the z-buffer methods it is compared with (a full-frame
//!   or banded depth buffer, and the painter's pass), on the same tables.
//! * `plane`, `edge`, `active`, `lanes`, `slots`: the plane set-up, the
//!   exact edge DDA, the active tables, the branch-free span blocks for
//!   hosts, and the capacity-erased lists every table is written on
//!   (internal). The exact wide products they share with the front end
//!   live below both, in `crate::arith`.
//!
//! Only one row of depth and one of colour exist: nothing is frame-sized.

pub(crate) mod activation;
pub(crate) mod active;
pub(crate) mod attribute;
pub(crate) mod capacities;
pub(crate) mod depth;
pub(crate) mod edge;
pub(crate) mod entry_geometry;
pub(crate) mod fixed;
pub mod inspect;
pub(crate) mod lanes;
pub mod paint;
pub(crate) mod plane;
pub(crate) mod scan;
pub(crate) mod slots;
pub(crate) mod small;
pub(crate) mod small_table;
pub(crate) mod span;
pub(crate) mod stats;
pub(crate) mod stepping;
pub(crate) mod tables;
pub(crate) mod vertex;
#[cfg(feature = "zbuffer")]
pub mod zbuffer;

pub use active::ActivePolygon;
pub use capacities::{Capacities, MeshCounts};
pub use depth::{Depth16, Depth24, DepthFormat};
pub use edge::{ActiveEdge, EdgeEntry};
pub use scan::{ScanArrays, ScanParts, ScanStorage, Scanner, scan};
pub use small_table::SmallActive;
pub use stats::FrameStats;
pub use tables::{
    Admission, PolygonEntry, Prepared, TableArrays, TableParts, TablePartsRef, TableStorage, Tables,
};
pub use vertex::{Outline, OutlineBuilder, ScreenRect, ScreenVertex};

use crate::error::Error;

/// Whether the hot loops avoid data-dependent branches: on every target
/// but 32-bit Arm. A host predicts branches and pays 15-20 cycles for each
/// miss, and the edge steps, the short spans' ends, the depth test, the
/// corner sort and the quotients' signs go either way about half the
/// time: branch-free, the peers bench's frames took a third less time
/// while running more instructions (docs/results/speed.md). A
/// Cortex-M0+ predicts nothing, and there the branching code is as short
/// or shorter (`cargo qemu`: branch-free edge steps took 0.3 % more
/// instructions with 16-bit depth), so it keeps it. Each branch-free form
/// is tested against its branching one on the host.
pub(crate) const BRANCH_FREE: bool = !cfg!(target_arch = "arm");

/// What scene building needs from a renderer: its frame, its vertex table
/// and its polygon table. [`Renderer`](crate::Renderer) implements it for every
/// configuration, so [`draw_mesh`](crate::draw_mesh) needs none of the capacities.
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
    /// Adds a vertex; see [`Renderer::push_vertex`](crate::Renderer::push_vertex).
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
    /// [`Self::offer_polygon`] for a triangle: the common case, with no
    /// iterator.
    fn offer_triangle(
        &mut self,
        corners: [u16; 3],
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        self.offer_polygon(corners, decide)
    }
    /// Gives the polygon queued by the call just before the depth plane
    /// through three vertices; see [`Tables::share_plane`].
    fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error>;
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
