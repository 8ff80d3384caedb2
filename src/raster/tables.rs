//! The scene-sized tables of the scanline z-buffer: the vertex table, the
//! polygon table (PT) with its corner list, and the edge table (ET).
//!
//! Polygons are offered one by one ([`Tables::push_polygon`],
//! [`Tables::offer_polygon`], or corner by corner); those that can cover no
//! pixel sample are counted and left out. [`Tables::prepare`] then buckets
//! the PT by first row with a stable radix sort (O(n), no comparisons) and
//! builds the ET, and hands out a [`Prepared`] view that any number of
//! [`Scanner`](super::Scanner)s may scan at once.
//!
//! Triangles, nearly every polygon of a mesh, need no ET entry: a triangle
//! switches from its upper to its lower short edge by itself (see
//! `stepping.rs`). The ET holds, for polygons of four or more corners, the
//! rows below their first row where further edges start.
//!
//! All logic is written once against capacity-erased views of the storage
//! ([`TableStorage`]), so it compiles once per colour type.

use core::ops::Range;

use crate::arith::wide::cross;
use crate::error::Error;
use crate::limits::{MAX_FRAME_SIZE, MAX_POLYGON_CORNERS, MAX_POLYGONS};
use crate::raster::edge::EdgeEntry;
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::slots::Slots;
use crate::raster::vertex::{Outline, OutlineBuilder, ScreenRect, ScreenVertex, TriangleTest};

/// A polygon-table entry (opaque: its fields are the core's own).
///
/// A triangle on its own plane, nearly every polygon of a mesh, carries
/// its three vertex-table indices inline: activation reads no corner list
/// (after the sort, the list is read in no order, and each triangle's
/// corners would cost a cache miss). Its corners are in the corner list
/// too, where [`Tables::share_plane`] and the capacity accounting find
/// them. The entry stays 16 bytes with a 2-byte colour: the id, the
/// corner count and the shared-plane flag share one word.
#[derive(Debug, Clone, Copy)]
pub struct PolygonEntry<C> {
    /// A triangle's vertex-table indices ([`Self::triangle`]); for any
    /// other polygon, where its corners start in the corner list: the low
    /// half, then the high half ([`Self::corner_start`]).
    corners: [u16; 3],
    /// First visible row (the bucket).
    pub(crate) first_row: u16,
    /// One past the last visible row.
    pub(crate) end_row: u16,
    /// The order of admission (the low [`ID_BITS`] bits: on equal depth
    /// the polygon added first wins), the number of corners (the next
    /// [`COUNT_BITS`]) and [`SHARED_PLANE`] (the top bit).
    tag: u32,
    pub(crate) color: C,
}

/// Bits of [`PolygonEntry::tag`] holding the id: ids are below
/// [`MAX_POLYGONS`].
const ID_BITS: u32 = MAX_POLYGONS.trailing_zeros();
/// Bits of [`PolygonEntry::tag`] holding the corner count: up to
/// [`MAX_POLYGON_CORNERS`].
const COUNT_BITS: u32 = 11;
const COUNT_MASK: u32 = (1 << COUNT_BITS) - 1;
/// Bit of [`PolygonEntry::tag`] set when the polygon's depth comes from a
/// shared plane: three more corners after its own name it.
const SHARED_PLANE: u32 = 1 << 31;
const _: () = assert!(MAX_POLYGONS.is_power_of_two() && ID_BITS + COUNT_BITS < 32);
const _: () = assert!(MAX_POLYGON_CORNERS <= COUNT_MASK as usize);

impl<C: Copy> PolygonEntry<C> {
    /// A filler for unused slots.
    pub const fn filler(color: C) -> Self {
        Self {
            corners: [0; 3],
            first_row: 0,
            end_row: 0,
            tag: 0,
            color,
        }
    }

    /// A triangle on its own plane, with vertex-table indices `ids`,
    /// covering `rows`, admitted `id`-th (below [`MAX_POLYGONS`]).
    #[inline(always)]
    pub(crate) fn new_triangle(ids: [u16; 3], rows: (u16, u16), id: u32, color: C) -> Self {
        debug_assert!((id as usize) < MAX_POLYGONS);
        Self {
            corners: ids,
            first_row: rows.0,
            end_row: rows.1,
            tag: id | 3 << ID_BITS,
            color,
        }
    }

    /// A polygon of `count` corners (3 to [`MAX_POLYGON_CORNERS`]) from
    /// `start` on in the corner list: a triangle's are read from there
    /// into the entry.
    #[inline]
    pub(crate) fn new_listed(
        corners: &[u16],
        start: usize,
        count: usize,
        rows: (u16, u16),
        id: u32,
        color: C,
    ) -> Self {
        debug_assert!((id as usize) < MAX_POLYGONS && count <= MAX_POLYGON_CORNERS);
        if let (3, Some(&[a, b, c])) = (count, corners.get(start..start + 3)) {
            return Self::new_triangle([a, b, c], rows, id, color);
        }
        let mut entry = Self {
            corners: [0; 3],
            first_row: rows.0,
            end_row: rows.1,
            tag: id | (count as u32) << ID_BITS,
            color,
        };
        entry.set_corner_start(start);
        entry
    }
}

impl<C> PolygonEntry<C> {
    /// The order of admission: on equal depth the polygon added first
    /// wins.
    #[inline(always)]
    pub(crate) fn id(&self) -> u32 {
        self.tag & ((1 << ID_BITS) - 1)
    }

    /// Number of the polygon's own corners.
    #[inline(always)]
    pub(crate) fn corner_count(&self) -> usize {
        ((self.tag >> ID_BITS) & COUNT_MASK) as usize
    }

    /// A triangle on its own plane: its vertex-table indices, read from
    /// the entry with no corner list.
    #[inline(always)]
    pub(crate) fn triangle(&self) -> Option<[u16; 3]> {
        // One comparison: a count of 3 and no shared plane.
        (self.tag & !((1 << ID_BITS) - 1) == 3 << ID_BITS).then_some(self.corners)
    }

    /// Where the polygon's corners start in the corner list, for a polygon
    /// that is not [`Self::triangle`]. (A triangle's inline indices are
    /// its corners; see [`entry_corner_ids`].)
    #[inline(always)]
    fn corner_start(&self) -> usize {
        usize::from(self.corners[0]) | usize::from(self.corners[1]) << 16
    }

    /// Sets where the corners start in the corner list (below `2^32`: the
    /// list is indexed by `u32`).
    #[inline(always)]
    fn set_corner_start(&mut self, start: usize) {
        self.corners = [start as u16, (start >> 16) as u16, 0];
    }

    /// Where the three corners of the plane the polygon shares start in
    /// the corner list (right after its own corners), if it shares one
    /// ([`Tables::share_plane`]).
    #[inline(always)]
    pub(crate) fn shared_plane(&self) -> Option<usize> {
        (self.tag & SHARED_PLANE != 0).then(|| self.corner_start() + self.corner_count())
    }

    /// Marks the polygon as sharing the plane of the three corners after
    /// its own, which start at `start` in the corner list.
    fn share_plane_after(&mut self, start: usize) {
        self.set_corner_start(start);
        self.tag |= SHARED_PLANE;
    }
}

/// The vertex-table indices of a polygon's own corners: a triangle's from
/// its entry, any other polygon's from the corner list.
#[inline]
pub(crate) fn entry_corner_ids<'a, C>(
    polygon: &'a PolygonEntry<C>,
    corners: &'a [u16],
) -> &'a [u16] {
    if polygon.triangle().is_some() {
        return &polygon.corners;
    }
    let start = polygon.corner_start();
    &corners[start..start + polygon.corner_count()]
}

/// An edge-table entry (opaque): 4 bytes holding a row and a polygon's
/// position.
pub type TableEdge = EdgeEntry;

/// How many corners the tables take: the corner list's length, bounded by
/// the edge table's, which serves as the sort's scratch (two entries per
/// polygon) and holds up to one entry per corner. A storage whose edge
/// table is shorter than its corner list thus refuses corners with
/// [`Error::EdgeTableFull`] rather than failing later.
#[inline(always)]
fn corner_room(corners: usize, edges: usize) -> usize {
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

/// The outline of the triangle `a b c`.
fn triangle_outline(a: ScreenVertex, b: ScreenVertex, c: ScreenVertex) -> Outline {
    let (px, py) = (
        i64::from(b.x) - i64::from(a.x),
        i64::from(b.y) - i64::from(a.y),
    );
    let (qx, qy) = (
        i64::from(c.x) - i64::from(a.x),
        i64::from(c.y) - i64::from(a.y),
    );
    Outline {
        corners: 3,
        twice_area: px * qy - py * qx,
        rect: Some(ScreenRect {
            x0: a.x.min(b.x).min(c.x),
            x1: a.x.max(b.x).max(c.x),
            y0: a.y.min(b.y).min(c.y),
            y1: a.y.max(b.y).max(c.y),
        }),
    }
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

/// Counts kept by the tables, beside the lists' lengths.
#[derive(Debug, Clone, Copy)]
struct Counts {
    width: u16,
    height: u16,
    /// Corners of queued polygons (`corners` beyond them are the open
    /// polygon's).
    committed_corners: usize,
    /// `Some(vertex count when it began)` while a polygon is open.
    open_polygon: Option<usize>,
    /// The PT is sorted and the ET built for the polygons now queued.
    prepared: bool,
    next_id: u32,
    /// The polygon queued last was the last thing offered: it may still
    /// be given a shared plane.
    shareable: bool,
    off_screen: u32,
    degenerate: u32,
}

/// Lengths of the four lists and the counts.
#[derive(Debug, Clone, Copy)]
struct TableState {
    vertices: usize,
    polygons: usize,
    corners: usize,
    edges: usize,
    counts: Counts,
}

/// The scene-sized tables over some [`TableStorage`]: build a frame's
/// scene into them, [`Self::prepare`] them, and scan the rows with one or
/// more [`Scanner`](super::Scanner)s.
#[derive(Debug, Clone)]
pub struct Tables<S: TableStorage> {
    storage: S,
    state: TableState,
}

/// The tables, capacity-erased: every operation is written once here.
struct TablesMut<'a, C> {
    vertices: Slots<'a, ScreenVertex>,
    polygons: Slots<'a, PolygonEntry<C>>,
    corners: Slots<'a, u16>,
    edges: Slots<'a, TableEdge>,
    counts: &'a mut Counts,
}

/// Prepared tables: sorted, with their edge table, ready to scan. Many
/// scanners may share one (on several threads, on the host), each over its
/// own band of rows.
#[derive(Debug, Clone, Copy)]
pub struct Prepared<'a, C> {
    pub(crate) vertices: &'a [ScreenVertex],
    pub(crate) polygons: &'a [PolygonEntry<C>],
    pub(crate) corners: &'a [u16],
    pub(crate) edges: &'a [TableEdge],
    pub(crate) width: u16,
    pub(crate) height: u16,
    pub(crate) off_screen: u32,
    pub(crate) degenerate: u32,
}

impl<S: TableStorage> Tables<S> {
    /// Empty tables for frames `width` x `height` (each 1 to 4,096).
    pub fn new(storage: S, width: u16, height: u16) -> Result<Self, Error> {
        check_size(width, height)?;
        Ok(Self::new_unchecked(storage, width, height))
    }

    /// As [`Self::new`], `const`, for statics; an invalid size stops the
    /// build.
    pub const fn new_in_static(storage: S, width: u16, height: u16) -> Self {
        if check_size(width, height).is_err() {
            panic!("zline: frame width and height must be 1..=4096");
        }
        Self::new_unchecked(storage, width, height)
    }

    const fn new_unchecked(storage: S, width: u16, height: u16) -> Self {
        Self {
            storage,
            state: TableState {
                vertices: 0,
                polygons: 0,
                corners: 0,
                edges: 0,
                counts: Counts {
                    width,
                    height,
                    committed_corners: 0,
                    open_polygon: None,
                    prepared: false,
                    next_id: 0,
                    shareable: false,
                    off_screen: 0,
                    degenerate: 0,
                },
            },
        }
    }

    fn view(&mut self) -> TablesMut<'_, S::Color> {
        let parts = self.storage.parts_mut();
        let st = &mut self.state;
        let room = corner_room(parts.corners.len(), parts.edges.len());
        TablesMut {
            vertices: Slots::new(parts.vertices, &mut st.vertices),
            polygons: Slots::new(usable_polygons(parts.polygons), &mut st.polygons),
            corners: Slots::new(&mut parts.corners[..room], &mut st.corners),
            edges: Slots::new(parts.edges, &mut st.edges),
            counts: &mut st.counts,
        }
    }

    /// Frame width in pixels.
    pub fn width(&self) -> u16 {
        self.state.counts.width
    }

    /// Frame height in rows.
    pub fn height(&self) -> u16 {
        self.state.counts.height
    }

    /// Changes the frame size (each 1 to 4,096) and empties the tables.
    pub fn set_size(&mut self, width: u16, height: u16) -> Result<(), Error> {
        check_size(width, height)?;
        self.clear();
        (self.state.counts.width, self.state.counts.height) = (width, height);
        Ok(())
    }

    /// Empties every table for the next frame.
    pub fn clear(&mut self) {
        let counts = &mut self.state.counts;
        (self.state.vertices, self.state.polygons) = (0, 0);
        (self.state.corners, self.state.edges) = (0, 0);
        counts.committed_corners = 0;
        counts.open_polygon = None;
        counts.prepared = false;
        counts.shareable = false;
        (counts.next_id, counts.off_screen, counts.degenerate) = (0, 0, 0);
    }

    /// Number of vertices in the vertex table.
    pub fn vertex_count(&self) -> usize {
        self.state.vertices
    }

    /// Number of polygons in the polygon table.
    pub fn polygon_count(&self) -> usize {
        self.state.polygons
    }

    /// Number of corners stored for the queued polygons.
    pub fn corner_count(&self) -> usize {
        self.state.counts.committed_corners
    }

    /// Vertex `index` of the vertex table.
    pub fn vertex(&self, index: u16) -> Option<ScreenVertex> {
        let parts = self.storage.parts();
        parts.vertices[..self.state.vertices]
            .get(usize::from(index))
            .copied()
    }

    /// Adds a vertex and returns its index for [`Self::push_polygon`].
    #[inline]
    pub fn push_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        vertex.check()?;
        let index = self.state.vertices;
        let slot = self.storage.parts_mut().vertices.get_mut(index);
        match (slot, u16::try_from(index)) {
            (Some(slot), Ok(id)) => {
                *slot = vertex;
                self.state.vertices += 1;
                Ok(id)
            }
            _ => Err(Error::VertexTableFull),
        }
    }

    /// Offers a polygon, given by indices into the vertex table in order
    /// around its boundary (either winding; it may be concave or even
    /// self-intersecting, filled even-odd). Polygons that can cover no
    /// pixel are counted and left out (see [`Admission`]); on `Err` nothing
    /// was added.
    ///
    /// The admission rule, the same for [`Self::push_polygon_vertices`]:
    /// a polygon is judged before it takes room, so one that can cover no
    /// sample is left out whatever room is left; only one that will be
    /// queued needs room in the tables, and it is an error when it does
    /// not fit.
    pub fn push_polygon(&mut self, corners: &[u16], color: S::Color) -> Result<Admission, Error> {
        if corners.len() < 3 {
            return Err(Error::TooFewCorners);
        }
        if corners.len() > MAX_POLYGON_CORNERS {
            return Err(Error::TooManyCorners);
        }
        match *corners {
            [a, b, c] => self.view().offer_triangle([a, b, c], |_| Some(color)),
            _ => self
                .view()
                .offer_polygon(corners.iter().copied(), |_| Some(color)),
        }
    }

    /// Adds the polygon's corners to the vertex table and the polygon to
    /// the polygon table in one step; on `Err` neither table changed.
    ///
    /// The admission rule is [`Self::push_polygon`]'s: bad corners are an
    /// error; then the polygon is judged before it takes any room, so one
    /// that can cover no sample is counted and left out
    /// ([`Admission::OffScreen`], [`Admission::Degenerate`]) however full
    /// the tables are; only a polygon that will be queued needs room for
    /// its corners, in the vertex table and the corner list, and a slot in
    /// the polygon table.
    pub fn push_polygon_vertices(
        &mut self,
        corners: &[ScreenVertex],
        color: S::Color,
    ) -> Result<Admission, Error> {
        if corners.len() < 3 {
            return Err(Error::TooFewCorners);
        }
        if corners.len() > MAX_POLYGON_CORNERS {
            return Err(Error::TooManyCorners);
        }
        for vertex in corners {
            vertex.check()?;
        }
        let mut t = self.view();
        // Judged as the offer below judges it (and counted when left out).
        let verdict = match *corners {
            [a, b, c] => t.judge_triangle(a, b, c)?,
            _ => {
                let mut outline = OutlineBuilder::default();
                corners.iter().for_each(|&v| outline.add(v));
                t.judge(&outline.finish())?.map(|_| ())
            }
        };
        if let Err(admission) = verdict {
            return Ok(admission);
        }
        // Room for all of it, or nothing is added.
        let n = corners.len();
        let index_room = (1usize << 16).saturating_sub(t.vertices.len());
        if t.vertices.room().min(index_room) < n {
            return Err(Error::VertexTableFull);
        }
        if t.polygons.is_full() {
            return Err(Error::PolygonTableFull);
        }
        if t.corners.room() < n {
            return Err(Error::EdgeTableFull);
        }
        let mark = t.vertices.len();
        let result = if let &[a, b, c] = corners {
            let ids = [t.push_vertex(a)?, t.push_vertex(b)?, t.push_vertex(c)?];
            t.offer_triangle(ids, |_| Some(color))
        } else {
            t.begin_polygon();
            corners
                .iter()
                .try_for_each(|&v| t.push_vertex(v).and_then(|index| t.add_corner(index)))
                .and_then(|()| t.finish_polygon(|_| Some(color)))
        };
        if !matches!(result, Ok(Admission::Queued(_))) {
            // Cannot happen (judged and given room above), but nothing is
            // left half-added.
            t.discard_polygon();
            t.vertices.truncate(mark);
        }
        result
    }

    /// Gives the polygon queued last (by the call just before: nothing
    /// offered since) the depth plane through the vertices `plane` instead
    /// of its own. Polygons given one plane hold exactly the same depth at
    /// every pixel, in every method and depth format, so where they overlap
    /// the one added first wins, on every frame and from every camera:
    /// this is how coplanar faces (decals, double-sided cards, overlapping
    /// faces of one plane) keep a steady winner, which planes computed from
    /// each face's own rounded corners cannot promise. The three corners
    /// take room in the corner list.
    ///
    /// `Ok(false)`, with nothing changed, when the three vertices have no
    /// projected area (the plane is edge-on): the polygon keeps its own.
    /// `Err(NoPolygonToShare)` when the last thing offered was not queued.
    pub fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error> {
        self.view().share_plane(plane)
    }

    /// Offers a polygon by an iterator of vertex indices; see
    /// [`PolygonTables::offer_polygon`].
    pub fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<S::Color>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        self.view().offer_polygon(corners.into_iter(), decide)
    }

    /// [`Self::offer_polygon`] for a triangle, with no iterator: the hot
    /// path of every mesh, written straight on the storage.
    #[inline]
    pub fn offer_triangle(
        &mut self,
        ids: [u16; 3],
        decide: impl FnOnce(&Outline) -> Option<S::Color>,
    ) -> Result<Admission, Error> {
        let st = &mut self.state;
        st.counts.shareable = false;
        if st.counts.open_polygon.is_some() || st.corners != st.counts.committed_corners {
            self.view().discard_polygon();
        }
        let parts = self.storage.parts_mut();
        let st = &mut self.state;
        let vertices = &parts.vertices[..st.vertices];
        let vertex = |k: usize| vertices.get(usize::from(ids[k])).copied();
        let (Some(a), Some(b), Some(c)) = (vertex(0), vertex(1), vertex(2)) else {
            return Err(Error::VertexOutOfRange);
        };
        // Table vertices lie inside the guard band: differences below
        // 2^23, products below 2^46.
        let (px, py) = (b.x - a.x, b.y - a.y);
        let (qx, qy) = (c.x - a.x, c.y - a.y);
        let twice_area = cross(px, py, qx, qy);
        if twice_area == 0 {
            st.counts.degenerate += 1;
            return Ok(Admission::Degenerate);
        }
        let rect = ScreenRect {
            x0: a.x.min(b.x).min(c.x),
            x1: a.x.max(b.x).max(c.x),
            y0: a.y.min(b.y).min(c.y),
            y1: a.y.max(b.y).max(c.y),
        };
        let Some((columns, rows)) = rect.samples(st.counts.width, st.counts.height) else {
            st.counts.off_screen += 1;
            return Ok(Admission::OffScreen);
        };
        let Some(rows) = covered_rows(a, b, c, columns, rows) else {
            st.counts.off_screen += 1;
            return Ok(Admission::OffScreen);
        };
        let outline = Outline {
            corners: 3,
            twice_area,
            rect: Some(rect),
        };
        let Some(color) = decide(&outline) else {
            return Ok(Admission::Declined);
        };
        let room = corner_room(parts.corners.len(), parts.edges.len());
        let polygons = usable_polygons(parts.polygons);
        let (Some(entry), Some(slots)) = (
            polygons.get_mut(st.polygons),
            parts.corners[..room].get_mut(st.corners..st.corners + 3),
        ) else {
            return Err(if st.polygons >= polygons.len() {
                Error::PolygonTableFull
            } else {
                Error::EdgeTableFull
            });
        };
        slots.copy_from_slice(&ids);
        *entry = PolygonEntry::new_triangle(ids, (rows.start, rows.end), st.counts.next_id, color);
        st.polygons += 1;
        st.corners += 3;
        st.counts.committed_corners = st.corners;
        st.counts.prepared = false;
        st.counts.shareable = true;
        st.counts.next_id += 1;
        Ok(Admission::Queued(st.counts.next_id - 1))
    }

    /// Sorts the polygon table by first row (stable: polygons starting on
    /// the same row keep the order they were added in), builds the edge
    /// table, and returns the prepared tables for scanning. A polygon left
    /// open is dropped first. Nothing is sorted again until the tables
    /// change.
    #[inline(never)]
    pub fn prepare(&mut self) -> Prepared<'_, S::Color> {
        {
            let mut t = self.view();
            t.discard_polygon();
            t.counts.shareable = false;
            if !t.counts.prepared {
                t.sort_polygons();
                t.build_edge_table();
                t.counts.prepared = true;
            }
        }
        let parts = self.storage.parts();
        let st = &self.state;
        Prepared {
            vertices: &parts.vertices[..st.vertices],
            polygons: &parts.polygons[..st.polygons],
            corners: &parts.corners[..st.corners],
            edges: &parts.edges[..st.edges],
            width: st.counts.width,
            height: st.counts.height,
            off_screen: st.counts.off_screen,
            degenerate: st.counts.degenerate,
        }
    }
}

impl<C> Prepared<'_, C> {
    /// Frame width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Frame height in rows.
    pub fn height(&self) -> u16 {
        self.height
    }
}

impl<S: TableStorage> Tables<S> {
    /// The tables as they are, for the methods that draw polygon after
    /// polygon ([`crate::raster::zbuffer`]): the polygons in the order they
    /// were added (unless [`Self::prepare`] has sorted them since), no edge
    /// table. A polygon left open is dropped first.
    pub fn in_drawing_order(&mut self) -> Prepared<'_, S::Color> {
        self.view().discard_polygon();
        let parts = self.storage.parts();
        let st = &self.state;
        Prepared {
            vertices: &parts.vertices[..st.vertices],
            polygons: &parts.polygons[..st.polygons],
            corners: &parts.corners[..st.corners],
            edges: &[],
            width: st.counts.width,
            height: st.counts.height,
            off_screen: st.counts.off_screen,
            degenerate: st.counts.degenerate,
        }
    }

    /// Whether [`Self::prepare`] has sorted the polygons by first row
    /// since the tables were cleared.
    pub fn is_prepared(&self) -> bool {
        self.state.counts.prepared
    }
}

impl<S: TableStorage> PolygonTables<S::Color> for Tables<S> {
    fn frame_width(&self) -> u16 {
        self.width()
    }

    fn frame_height(&self) -> u16 {
        self.height()
    }

    fn add_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        self.push_vertex(vertex)
    }

    fn get_vertex(&self, index: u16) -> Option<ScreenVertex> {
        self.vertex(index)
    }

    fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<S::Color>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        Tables::offer_polygon(self, corners, decide)
    }

    fn offer_triangle(
        &mut self,
        corners: [u16; 3],
        decide: impl FnOnce(&Outline) -> Option<S::Color>,
    ) -> Result<Admission, Error> {
        Tables::offer_triangle(self, corners, decide)
    }

    fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error> {
        Tables::share_plane(self, plane)
    }

    fn begin_polygon(&mut self) {
        self.view().begin_polygon();
    }

    fn discard_polygon(&mut self) {
        self.view().discard_polygon();
    }

    fn add_corner(&mut self, vertex: u16) -> Result<(), Error> {
        self.view().add_corner(vertex)
    }

    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<S::Color>,
    ) -> Result<Admission, Error> {
        self.view().finish_polygon(decide)
    }
}

impl<C: Copy> TablesMut<'_, C> {
    fn push_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        vertex.check()?;
        let index = u16::try_from(self.vertices.len()).map_err(|_| Error::VertexTableFull)?;
        self.vertices
            .push(vertex)
            .map_err(|_| Error::VertexTableFull)?;
        Ok(index)
    }

    fn offer_polygon(
        &mut self,
        corners: impl Iterator<Item = u16> + Clone,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        self.discard_polygon();
        self.counts.shareable = false;
        let mut outline = OutlineBuilder::default();
        let vertices = self.vertices.as_slice();
        for index in corners.clone() {
            if outline.corners() == MAX_POLYGON_CORNERS {
                return Err(Error::TooManyCorners);
            }
            let vertex = vertices.get(usize::from(index));
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
        if self.corners.room() < outline.corners {
            return Err(Error::EdgeTableFull);
        }
        let start = self.corners.len();
        for index in corners {
            // Room for every corner was checked above.
            self.corners.push(index).map_err(|_| Error::EdgeTableFull)?;
        }
        Ok(self.queue(start, outline.corners, rows, color))
    }

    #[inline]
    fn offer_triangle(
        &mut self,
        ids: [u16; 3],
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        self.counts.shareable = false;
        if self.counts.open_polygon.is_some() || self.corners.len() != self.counts.committed_corners
        {
            self.discard_polygon();
        }
        let vertices = self.vertices.as_slice();
        let vertex = |k: usize| vertices.get(usize::from(ids[k])).copied();
        let (Some(a), Some(b), Some(c)) = (vertex(0), vertex(1), vertex(2)) else {
            return Err(Error::VertexOutOfRange);
        };
        let outline = triangle_outline(a, b, c);
        if let Err(admission) = self.judge(&outline)? {
            return Ok(admission);
        }
        let covered = outline
            .rect
            .and_then(|r| r.samples(self.counts.width, self.counts.height))
            .and_then(|(columns, rows)| covered_rows(a, b, c, columns, rows));
        let Some(rows) = covered else {
            self.counts.off_screen += 1;
            return Ok(Admission::OffScreen);
        };
        let rows = (rows.start, rows.end);
        let Some(color) = decide(&outline) else {
            return Ok(Admission::Declined);
        };
        if self.polygons.is_full() {
            return Err(Error::PolygonTableFull);
        }
        if self.corners.room() < 3 {
            return Err(Error::EdgeTableFull);
        }
        let start = self.corners.len();
        for id in ids {
            self.corners.push(id).map_err(|_| Error::EdgeTableFull)?;
        }
        Ok(self.queue(start, 3, rows, color))
    }

    /// The verdict [`Self::offer_triangle`] gives the triangle `a b c`
    /// (counted when it is left out), with no table touched.
    fn judge_triangle(
        &mut self,
        a: ScreenVertex,
        b: ScreenVertex,
        c: ScreenVertex,
    ) -> Result<Result<(), Admission>, Error> {
        let outline = triangle_outline(a, b, c);
        if let Err(admission) = self.judge(&outline)? {
            return Ok(Err(admission));
        }
        let covered = outline
            .rect
            .and_then(|r| r.samples(self.counts.width, self.counts.height))
            .and_then(|(columns, rows)| covered_rows(a, b, c, columns, rows));
        if covered.is_none() {
            self.counts.off_screen += 1;
            return Ok(Err(Admission::OffScreen));
        }
        Ok(Ok(()))
    }

    /// The core's verdict on an outline: `Ok(Ok(rows))` when it can cover
    /// a pixel sample, `Ok(Err(admission))` (counted) when it cannot.
    fn judge(&mut self, outline: &Outline) -> Result<Result<(u16, u16), Admission>, Error> {
        if outline.corners < 3 {
            return Err(Error::TooFewCorners);
        }
        if outline.twice_area == 0 {
            self.counts.degenerate += 1;
            return Ok(Err(Admission::Degenerate));
        }
        let (width, height) = (self.counts.width, self.counts.height);
        match outline.rect.and_then(|r| r.sample_rows(width, height)) {
            Some(rows) => Ok(Ok(rows)),
            None => {
                self.counts.off_screen += 1;
                Ok(Err(Admission::OffScreen))
            }
        }
    }

    /// Enters the polygon whose corners are `corners[start..start + count]`
    /// (the polygon table has room).
    fn queue(&mut self, start: usize, count: usize, rows: (u16, u16), color: C) -> Admission {
        let entry = PolygonEntry::new_listed(
            self.corners.as_slice(),
            start,
            count,
            rows,
            self.counts.next_id,
            color,
        );
        if self.polygons.push(entry).is_err() {
            // The callers checked for room: cannot happen.
            self.corners.truncate(self.counts.committed_corners);
            return Admission::OffScreen;
        }
        self.counts.committed_corners = self.corners.len();
        self.counts.open_polygon = None;
        self.counts.prepared = false;
        self.counts.shareable = true;
        self.counts.next_id += 1;
        Admission::Queued(self.counts.next_id - 1)
    }

    fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error> {
        let last = self.polygons.len().checked_sub(1);
        if !self.counts.shareable || self.corners.len() != self.counts.committed_corners {
            return Err(Error::NoPolygonToShare);
        }
        let Some(last) = last else {
            return Err(Error::NoPolygonToShare);
        };
        let vertices = self.vertices.as_slice();
        let vertex = |k: usize| vertices.get(usize::from(plane[k])).copied();
        let (Some(a), Some(b), Some(c)) = (vertex(0), vertex(1), vertex(2)) else {
            return Err(Error::VertexOutOfRange);
        };
        // Twice the projected area, as the triangle's plane computes it:
        // below 2^45 inside the guard band.
        let twice_area = (i64::from(b.x) - i64::from(a.x)) * (i64::from(c.y) - i64::from(a.y))
            - (i64::from(b.y) - i64::from(a.y)) * (i64::from(c.x) - i64::from(a.x));
        if twice_area == 0 {
            return Ok(false);
        }
        if self.corners.room() < 3 {
            return Err(Error::EdgeTableFull);
        }
        for id in plane {
            // Room was checked above.
            self.corners.push(id).map_err(|_| Error::EdgeTableFull)?;
        }
        self.counts.committed_corners = self.corners.len();
        self.counts.shareable = false;
        let polygon = &mut self.polygons.as_mut_slice()[last];
        // Its own corners are the last ones before the plane's.
        let start = self.counts.committed_corners - 3 - polygon.corner_count();
        polygon.share_plane_after(start);
        Ok(true)
    }

    fn begin_polygon(&mut self) {
        self.discard_polygon();
        self.counts.shareable = false;
        self.counts.open_polygon = Some(self.vertices.len());
    }

    fn discard_polygon(&mut self) {
        self.corners.truncate(self.counts.committed_corners);
        if let Some(mark) = self.counts.open_polygon.take() {
            self.vertices.truncate(mark);
        }
    }

    fn add_corner(&mut self, vertex: u16) -> Result<(), Error> {
        if usize::from(vertex) >= self.vertices.len() {
            return Err(Error::VertexOutOfRange);
        }
        if self.corners.len() - self.counts.committed_corners >= MAX_POLYGON_CORNERS {
            return Err(Error::TooManyCorners);
        }
        if self.counts.open_polygon.is_none() {
            self.counts.open_polygon = Some(self.vertices.len());
        }
        self.counts.shareable = false;
        self.corners.push(vertex).map_err(|_| Error::EdgeTableFull)
    }

    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        self.counts.shareable = false;
        let start = self.counts.committed_corners;
        let mut outline = OutlineBuilder::default();
        let vertices = self.vertices.as_slice();
        for &index in &self.corners.as_slice()[start..] {
            outline.add(vertices[usize::from(index)]);
        }
        let outline = outline.finish();
        let rows = match self.judge(&outline) {
            Ok(Ok(rows)) => rows,
            Ok(Err(admission)) => {
                self.discard_polygon();
                return Ok(admission);
            }
            Err(e) => {
                self.discard_polygon();
                return Err(e);
            }
        };
        let Some(color) = decide(&outline) else {
            self.discard_polygon();
            return Ok(Admission::Declined);
        };
        if self.polygons.is_full() {
            self.discard_polygon();
            return Err(Error::PolygonTableFull);
        }
        Ok(self.queue(start, outline.corners, rows, color))
    }

    /// Sorts the polygon table by (first row, insertion order): a stable
    /// radix sort of the keys `(row << 20) | index` by their 12 row bits in
    /// two passes of 64 buckets, ping-ponging through the edge table's
    /// storage (it has room for two keys per polygon, since each polygon
    /// has three corners or more), then the permutation is applied in place,
    /// cycle by cycle.
    fn sort_polygons(&mut self) {
        let n = self.polygons.len();
        let scratch = self.edges.all_mut();
        let (keys, spare) = scratch.split_at_mut(n);
        for (index, (key, polygon)) in keys.iter_mut().zip(self.polygons.as_slice()).enumerate() {
            *key = EdgeEntry::new(polygon.first_row, index);
        }
        radix_sort_by_row(keys, &mut spare[..n]);
        // Position k must receive the polygon at `keys[k].position()`.
        let polygons = self.polygons.as_mut_slice();
        for start in 0..n {
            if keys[start].position() == start {
                continue;
            }
            let saved = polygons[start];
            let mut at = start;
            loop {
                let from = keys[at].position();
                keys[at] = EdgeEntry::new(0, at);
                if from == start {
                    polygons[at] = saved;
                    break;
                }
                polygons[at] = polygons[from];
                at = from;
            }
        }
    }

    /// Builds the edge table: for each polygon of four or more corners,
    /// the rows below its first row where some of its edges start (the
    /// others enter the active edge table with their polygon), one entry
    /// per (row, polygon), sorted by row.
    fn build_edge_table(&mut self) {
        self.edges.set_len(0);
        let height = i32::from(self.counts.height);
        let (vertices, corners) = (self.vertices.as_slice(), self.corners.as_slice());
        let mut count = 0usize;
        let capacity = self.edges.capacity();
        let edges = self.edges.all_mut();
        for (position, polygon) in self.polygons.as_slice().iter().enumerate() {
            if polygon.corner_count() <= 3 {
                continue;
            }
            let ring = entry_corner_ids(polygon, corners);
            for (k, &a) in ring.iter().enumerate() {
                let b = ring[(k + 1) % ring.len()];
                let (a, b) = (vertices[usize::from(a)], vertices[usize::from(b)]);
                let (top, bottom) = if a.y < b.y { (a, b) } else { (b, a) };
                let first = first_sample_at_or_after(top.y).max(0);
                let end = first_sample_at_or_after(bottom.y).min(height);
                if first < end && first > i32::from(polygon.first_row) && count < capacity {
                    // At most corners - 2 entries per polygon: room is sure.
                    edges[count] = EdgeEntry::new(first as u16, position);
                    count += 1;
                }
            }
        }
        if 2 * count <= capacity {
            let (entries, spare) = edges.split_at_mut(count);
            radix_sort_by_row(entries, &mut spare[..count]);
        } else {
            edges[..count].sort_unstable();
        }
        // Several edges of one polygon may start on one row: keep one entry.
        let mut kept = 0;
        for k in 0..count {
            if kept == 0 || edges[kept - 1] != edges[k] {
                edges[kept] = edges[k];
                kept += 1;
            }
        }
        self.edges.set_len(kept);
    }
}

/// The polygon slots the tables use: at most [`MAX_POLYGONS`], the most
/// an edge-table entry and the sort can address (a storage with more
/// slots leaves the rest unused, and the polygon past the limit is
/// [`Error::PolygonTableFull`]).
#[inline(always)]
fn usable_polygons<T>(polygons: &mut [T]) -> &mut [T] {
    let usable = polygons.len().min(MAX_POLYGONS);
    &mut polygons[..usable]
}

/// Most samples in a triangle's bounding box for which the core tests
/// them one by one before queuing it; larger triangles are queued whatever
/// they cover.
const TINY_SAMPLES: usize = 4;

/// The rows of a triangle's bounding box (its samples: `columns` x `rows`)
/// that hold a sample it covers. A tiny triangle (at most
/// [`TINY_SAMPLES`] samples) is tested sample by sample: `None` when it
/// covers none, else the rows from its first covered sample's to its last
/// one's (so one covering a single row is known to at activation). Larger
/// triangles keep all of `rows`. Always inline: with a second caller of
/// `offer_triangle` in the front end (convex quads) it was left out of
/// line, and a Cortex-M0+ drawing triangles paid 0.9 % more cycles.
#[inline(always)]
fn covered_rows(
    a: ScreenVertex,
    b: ScreenVertex,
    c: ScreenVertex,
    columns: Range<u16>,
    rows: Range<u16>,
) -> Option<Range<u16>> {
    if columns.len() * rows.len() > TINY_SAMPLES {
        return Some(rows);
    }
    let test = TriangleTest::new(a, b, c);
    // One bit per sample, row by row (at most TINY_SAMPLES bits).
    let (mut mask, mut bit) = (0u32, 0);
    for row in rows.clone() {
        for column in columns.clone() {
            mask |= u32::from(test.covers_pixel(i32::from(column), i32::from(row))) << bit;
            bit += 1;
        }
    }
    if mask == 0 {
        return None;
    }
    let per_row = columns.len() as u32;
    let first = mask.trailing_zeros() / per_row;
    let last = (31 - mask.leading_zeros()) / per_row;
    Some(rows.start + first as u16..rows.start + last as u16 + 1)
}

/// Sorts `keys` by row (their top 12 bits), stably: two passes of 6 bits,
/// through `spare` (as long as `keys`).
fn radix_sort_by_row(keys: &mut [EdgeEntry], spare: &mut [EdgeEntry]) {
    for shift in [EdgeEntry::ROW_SHIFT, EdgeEntry::ROW_SHIFT + 6] {
        let mut counts = [0usize; 65];
        for key in keys.iter() {
            counts[usize::from(key.bucket(shift)) + 1] += 1;
        }
        for b in 1..counts.len() {
            counts[b] += counts[b - 1];
        }
        for key in keys.iter() {
            let bucket = usize::from(key.bucket(shift));
            spare[counts[bucket]] = *key;
            counts[bucket] += 1;
        }
        keys.copy_from_slice(spare);
    }
}

use crate::raster::PolygonTables;

const fn check_size(width: u16, height: u16) -> Result<(), Error> {
    if width == 0
        || width as usize > MAX_FRAME_SIZE
        || height == 0
        || height as usize > MAX_FRAME_SIZE
    {
        Err(Error::BadFrameSize)
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radix_sort_is_stable_and_by_row() {
        let rows = [7u16, 0, 4095, 7, 64, 63, 0, 7, 4032, 1];
        let mut keys: [EdgeEntry; 10] = core::array::from_fn(|k| EdgeEntry::new(rows[k], k));
        let mut spare = [EdgeEntry::ZERO; 10];
        radix_sort_by_row(&mut keys, &mut spare);
        let mut expected: [(u16, usize); 10] = core::array::from_fn(|k| (rows[k], k));
        expected.sort();
        for (key, (row, index)) in keys.iter().zip(expected) {
            assert_eq!((key.row(), key.position()), (row, index));
        }
    }

    /// The packed entry gives back what went in, at the extremes of every
    /// field: the largest id, the most corners, a corner start past
    /// `2^16`, the shared-plane flag, and an inline triangle's indices.
    #[test]
    fn polygon_entries_keep_their_fields() {
        let max_id = MAX_POLYGONS as u32 - 1;
        for id in [0, 1, max_id] {
            let t = PolygonEntry::new_triangle([0, 65_535, 7], (3, 4095), id, 9u8);
            assert_eq!((t.id(), t.corner_count(), t.shared_plane()), (id, 3, None));
            assert_eq!(t.triangle(), Some([0, 65_535, 7]));
            assert_eq!(entry_corner_ids(&t, &[]), &[0, 65_535, 7]);
            assert_eq!((t.first_row, t.end_row, t.color), (3, 4095, 9));
            let list = [5u16; 8];
            let listed = PolygonEntry::new_listed(&list, 2, 3, (0, 1), id, 0u8);
            assert_eq!(
                listed.triangle(),
                Some([5, 5, 5]),
                "a listed triangle goes inline"
            );
            for (start, count) in [
                (0, 4),
                (70_000, MAX_POLYGON_CORNERS),
                (u32::MAX as usize - 2000, 5),
            ] {
                let mut p = PolygonEntry::new_listed(&[], start, count, (1, 2), id, 0u8);
                assert_eq!(
                    (p.id(), p.corner_count(), p.corner_start()),
                    (id, count, start)
                );
                assert_eq!((p.triangle(), p.shared_plane()), (None, None));
                p.share_plane_after(start);
                assert_eq!(p.shared_plane(), Some(start + count));
                assert_eq!((p.id(), p.corner_count(), p.triangle()), (id, count, None));
            }
            // A triangle sharing a plane reads its corners from the list.
            let mut shared = t;
            shared.share_plane_after(70_000);
            assert_eq!(
                (shared.triangle(), shared.shared_plane()),
                (None, Some(70_003))
            );
            assert_eq!((shared.id(), shared.corner_count()), (id, 3));
        }
        assert_eq!(size_of::<PolygonEntry<u16>>(), 16);
    }
}
