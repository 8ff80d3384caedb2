//! Admission: vertices and polygons offered to the tables, judged before
//! they take any room (a polygon that can cover no pixel sample is counted
//! and left out, [`Admission`]), and queued in the polygon table with
//! their corners; the corner-by-corner way in, and a shared plane.

use core::ops::Range;

use crate::arith::wide::cross;
use crate::error::Error;
use crate::limits::MAX_POLYGON_CORNERS;
use crate::raster::PolygonTables;
use crate::raster::tables::entry::PolygonEntry;
use crate::raster::tables::state::{Tables, TablesMut};
use crate::raster::tables::storage::{TableStorage, corner_room, usable_polygons};
use crate::raster::vertex::{Outline, OutlineBuilder, ScreenRect, ScreenVertex, TriangleTest};

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

impl<S: TableStorage> Tables<S> {
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
        if !cfg!(feature = "polygons") && outline.corners > 3 {
            return Err(Error::NeedsPolygons);
        }
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

    pub(super) fn discard_polygon(&mut self) {
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
        if !cfg!(feature = "polygons") && self.corners.len() - start > 3 {
            self.discard_polygon();
            return Err(Error::NeedsPolygons);
        }
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
