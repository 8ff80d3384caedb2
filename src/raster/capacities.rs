//! Capacities by name: one value sizes a renderer's every array, and
//! [`renderer_type!`](crate::renderer_type) spells out the storage types
//! from it.
//!
//! ```
//! use embedded_graphics_core::pixelcolor::Rgb565;
//! use zline::{Capacities, Depth16};
//!
//! // As `needs` prints it for a mesh and a frame (or
//! // `Capacities::worst_case(&counts, 240)`).
//! const CAPS: Capacities = Capacities {
//!     width: 240,
//!     vertices: 600,
//!     polygons: 1000,
//!     corners: 3000,
//!     active_polygons: 256,
//!     pooled_edges: 0,
//!     mesh_vertices: 500,
//! };
//! type Zr = zline::renderer_type!(Rgb565, Depth16, CAPS);
//! // Built at compile time; in firmware, in a `static` cell.
//! static RENDERER: Zr = Zr::new_in_static(240, 240, Rgb565::new(0, 0, 0));
//! assert!(CAPS.ram_bytes::<Rgb565, Depth16>() <= core::mem::size_of::<Zr>());
//! ```

use core::mem::size_of;

use crate::limits::MAX_POLYGONS;
use crate::raster::active::ActivePolygon;
use crate::raster::depth::DepthFormat;
use crate::raster::edge::{ActiveEdge, EdgeEntry};
#[cfg(doc)]
use crate::raster::small_table::SmallActive;
use crate::raster::stats::FrameStats;
use crate::raster::tables::PolygonEntry;
use crate::raster::vertex::ScreenVertex;

/// How much a renderer holds, by name: its tables, its scanner and its
/// vertex cache. The storage types follow from one such value
/// ([`renderer_type!`](crate::renderer_type)); a renderer too small for a
/// frame refuses it with the [`Error`](crate::Error) naming what did not
/// fit.
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
    /// Vertices of the largest mesh drawn with
    /// [`Renderer::draw_mesh`](crate::Renderer::draw_mesh): its vertex
    /// cache (2 bytes a vertex). Zero for a renderer of screen polygons
    /// only.
    pub mesh_vertices: usize,
}

impl Capacities {
    /// The capacities a frame of `width` pixels with these counts needs
    /// (take the [`FrameStats::max`] over every frame to be shown), with
    /// no vertex cache: set [`Self::mesh_vertices`] to the mesh's vertex
    /// count to draw it with [`Renderer::draw_mesh`](crate::Renderer::draw_mesh).
    ///
    /// They also fit a scanner of any band of the frame's rows, and each
    /// band of a banded renderer: a band holds no more polygons, corners
    /// or vertices than the frame, and needs no more active polygons or
    /// pooled edges on any row than one scan of the frame.
    pub const fn from_stats(stats: &FrameStats, width: usize) -> Self {
        Self {
            width,
            vertices: stats.vertices as usize,
            polygons: stats.polygons as usize,
            corners: stats.corners as usize,
            active_polygons: stats.peak_active_polygons as usize,
            pooled_edges: stats.peak_pooled_edges as usize,
            mesh_vertices: 0,
        }
    }

    /// Capacities that hold a mesh of these counts from **any** view,
    /// culled or not, in frames `width` pixels wide: every face at its
    /// worst, clipped by all six of the front end's planes. For a mesh of
    /// triangles only (`corners == 3 · faces`): 9 corners a face, each
    /// possibly a vertex of its own, and no pooled edge. For any other: up
    /// to 12 corners per corner (a face that is not planar is its fan of
    /// triangles, 9 corners each; a polygon clipped by Sutherland and
    /// Hodgman grows by at most half a plane, six times over). A face with
    /// a shared plane takes three corners more per polygon. Every polygon
    /// may be active on one row.
    ///
    /// An upper bound, and far more than most views need (a 1,024-triangle
    /// mesh gets 9,216 corners): where RAM is short, size from the views a
    /// firmware shows instead (`needs`). Counts beyond the core's limits
    /// are capped at them (65,536 vertices,
    /// [`MAX_POLYGONS`](crate::limits::MAX_POLYGONS) polygons, 65,536
    /// active polygons).
    pub const fn worst_case(mesh: &MeshCounts, width: usize) -> Self {
        let (faces, corners) = (mesh.faces, mesh.corners);
        let triangles_only = matches!(faces.checked_mul(3), Some(c) if c == corners);
        // Counts past usize saturate (the storage then refuses them).
        let clipped = if triangles_only {
            faces.saturating_mul(9)
        } else {
            corners.saturating_mul(12)
        };
        // A face of n corners: at most n - 2 triangles (its fan, or a
        // convex quad's two), or one polygon.
        let fan = corners.saturating_sub(faces.saturating_mul(2));
        let polygons = min(if fan > faces { fan } else { faces }, MAX_POLYGONS);
        let shared = if mesh.shared_plane_faces > 0 {
            polygons.saturating_mul(3)
        } else {
            0
        };
        Self {
            width,
            vertices: min(mesh.vertices.saturating_add(clipped), 1 << 16),
            polygons,
            corners: clipped.saturating_add(shared),
            active_polygons: min(polygons, 1 << 16),
            pooled_edges: if triangles_only { 0 } else { clipped },
            mesh_vertices: mesh.vertices,
        }
    }

    /// Bytes of the arrays of a renderer with these capacities, colour
    /// `C` and depth `D`: the three rows (colour, depth, tie-break key),
    /// the vertex, polygon, corner and edge tables, the active tables and
    /// the vertex cache: what a Cortex-M build holds. A build for a
    /// target that draws small triangles from coverage masks (every
    /// target but 32-bit Arm) also holds the small triangles' table, up
    /// to `active_polygons` entries of [`SmallActive`] (48 bytes each on
    /// a 64-bit host; the host's `ScanVecs` bounds it by the row's
    /// width), not counted here, so that a firmware sized on a desktop
    /// gets its own figure. Saturates at `usize::MAX`.
    pub fn ram_bytes<C, D: DepthFormat>(&self) -> usize {
        [
            (
                self.width,
                size_of::<C>() + size_of::<D::Value>() + size_of::<u32>(),
            ),
            (self.vertices, size_of::<ScreenVertex>()),
            (self.polygons, size_of::<PolygonEntry<C>>()),
            (self.corners, size_of::<u16>() + size_of::<EdgeEntry>()),
            (
                self.active_polygons,
                size_of::<ActivePolygon<C>>() + size_of::<u16>(),
            ),
            (self.pooled_edges, size_of::<ActiveEdge>()),
            (self.mesh_vertices, size_of::<u16>()),
        ]
        .iter()
        .fold(0usize, |sum, &(count, size)| {
            sum.saturating_add(count.saturating_mul(size))
        })
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

/// The [`Renderer`](crate::Renderer) type in fixed arrays for capacities
/// `$caps` (a [`Capacities`] constant), colour `$color` and depth format
/// `$depth`: every capacity in its place, so none is typed twice. With
/// `mesh_vertices: 0` it has no vertex cache and draws screen polygons
/// only.
///
/// ```
/// use embedded_graphics_core::pixelcolor::BinaryColor;
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
/// type Zr = zline::renderer_type!(BinaryColor, Depth16, CAPS);
/// let renderer = Zr::new(16, 16, BinaryColor::Off).unwrap();
/// assert_eq!(renderer.width(), 16);
/// ```
#[macro_export]
macro_rules! renderer_type {
    ($color:ty, $depth:ty, $caps:expr $(,)?) => {
        $crate::Renderer<
            $crate::TableArrays<$color, { $caps.vertices }, { $caps.polygons }, { $caps.corners }>,
            $crate::ScanArrays<
                $color,
                $depth,
                { $caps.width },
                { $caps.active_polygons },
                { $caps.pooled_edges },
            >,
            $crate::VertexCache<{ $caps.mesh_vertices }>,
        >
    };
}

/// The smaller of `a` and `b`, in a `const fn`.
const fn min(a: usize, b: usize) -> usize {
    if a < b { a } else { b }
}

/// A mesh's counts, for [`Capacities::worst_case`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MeshCounts {
    /// Vertex positions.
    pub vertices: usize,
    /// Faces.
    pub faces: usize,
    /// Corners of all faces together.
    pub corners: usize,
    /// Faces that share a plane with others
    /// ([`SharedPlane`](crate::SharedPlane)).
    pub shared_plane_faces: usize,
}
