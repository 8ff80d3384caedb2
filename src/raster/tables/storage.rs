//! Where the tables live: the [`TableStorage`] trait, which lends the four
//! arrays as slices, its fixed-array form [`TableArrays`], and how much of
//! a storage the tables use.

use crate::limits::MAX_POLYGONS;
use crate::raster::edge::EdgeEntry;
use crate::raster::tables::entry::PolygonEntry;
use crate::raster::vertex::ScreenVertex;

/// An edge-table entry (opaque): 4 bytes holding a row and a polygon's
/// position.
pub type TableEdge = EdgeEntry;

/// How many corners the tables take: the corner list's length, bounded by
/// the edge table's, which serves as the sort's scratch (two entries per
/// polygon) and holds up to one entry per corner. A storage whose edge
/// table is shorter than its corner list thus refuses corners with
/// [`Error::EdgeTableFull`] rather than failing later.
///
/// [`Error::EdgeTableFull`]: crate::Error::EdgeTableFull
#[inline(always)]
pub(super) fn corner_room(corners: usize, edges: usize) -> usize {
    corners.min(edges)
}

/// Where the tables live: anything that lends the four arrays as slices.
/// [`TableArrays`] holds them in fixed arrays (for statics on a
/// microcontroller); the host's `zline::host::TableVecs` in `Vec`s.
pub trait TableStorage {
    /// The pixel colour stored with each polygon.
    type Color: Copy;
    /// The arrays, mutably: vertices, polygons, corners, edges.
    fn parts_mut(&mut self) -> TableParts<'_, Self::Color>;
    /// The arrays.
    fn parts(&self) -> TablePartsRef<'_, Self::Color>;
}

/// The arrays of a [`TableStorage`], mutably.
#[derive(Debug)]
pub struct TableParts<'a, C> {
    /// The vertex table.
    pub vertices: &'a mut [ScreenVertex],
    /// The polygon table.
    pub polygons: &'a mut [PolygonEntry<C>],
    /// Every polygon's corners, as vertex indices.
    pub corners: &'a mut [u16],
    /// The edge table, and scratch space for sorting: as long as
    /// `corners` (the tables take no more corners than it has entries).
    pub edges: &'a mut [TableEdge],
}

/// The arrays of a [`TableStorage`].
#[derive(Debug, Clone, Copy)]
pub struct TablePartsRef<'a, C> {
    /// The vertex table.
    pub vertices: &'a [ScreenVertex],
    /// The polygon table.
    pub polygons: &'a [PolygonEntry<C>],
    /// Every polygon's corners, as vertex indices.
    pub corners: &'a [u16],
    /// The edge table.
    pub edges: &'a [TableEdge],
}

/// Fixed-capacity storage for the tables: up to `V` vertices, `P`
/// polygons and `E` corners in all (so `E >= 3·P` for triangles; the edge
/// table has the same capacity). Its size is
/// `12·V + (12 + size_of C)·P + 6·E` bytes or so; build it in a `static`
/// on a microcontroller (its constructor is `const`).
#[derive(Debug, Clone)]
pub struct TableArrays<C, const V: usize, const P: usize, const E: usize> {
    vertices: [ScreenVertex; V],
    polygons: [PolygonEntry<C>; P],
    corners: [u16; E],
    edges: [TableEdge; E],
}

impl<C: Copy, const V: usize, const P: usize, const E: usize> TableArrays<C, V, P, E> {
    /// Empty storage; `filler` fills the unused polygon slots (any colour).
    pub const fn new(filler: C) -> Self {
        const {
            assert!(V <= 1 << 16, "at most 65,536 vertices (indices are u16)");
            assert!(P <= MAX_POLYGONS, "at most 2^20 polygons");
        }
        Self {
            vertices: [ScreenVertex { x: 0, y: 0, z: 0 }; V],
            polygons: [PolygonEntry::filler(filler); P],
            corners: [0; E],
            edges: [EdgeEntry::ZERO; E],
        }
    }
}

impl<C: Copy, const V: usize, const P: usize, const E: usize> TableStorage
    for TableArrays<C, V, P, E>
{
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

/// The polygon slots the tables use: at most [`MAX_POLYGONS`], the most
/// an edge-table entry and the sort can address (a storage with more
/// slots leaves the rest unused, and the polygon past the limit is
/// [`Error::PolygonTableFull`]).
///
/// [`Error::PolygonTableFull`]: crate::Error::PolygonTableFull
#[inline(always)]
pub(super) fn usable_polygons<T>(polygons: &mut [T]) -> &mut [T] {
    let usable = polygons.len().min(MAX_POLYGONS);
    &mut polygons[..usable]
}
