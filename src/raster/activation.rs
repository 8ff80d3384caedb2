//! Activation: a polygon entering the active polygon table on its first
//! row (or on the first row of a band it reaches into), with its depth
//! set-up and the edges covering that row; and the further edges of a
//! polygon joining it on the rows the edge table names. A triangle that
//! covers one row is drawn there and never enters the table.

use crate::arith::wide::{cross, mul_i64_small};
use crate::error::Error;
use crate::raster::BRANCH_FREE;
use crate::raster::active::{ActivePolygon, NO_EDGE, NO_ROW, SpanDepth};
use crate::raster::depth::{DepthFormat, IN_RANGE, NarrowRow};
use crate::raster::edge::ActiveEdge;
use crate::raster::entry_geometry::{entry_corners, for_each_edge, shared_depth, shared_plane_of};
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::plane::{Plane, TrianglePlane};
use crate::raster::small::{SMALL_TRIANGLES, SmallCoverage};
use crate::raster::small_table::SmallActive;
use crate::raster::span::{RowBuffers, SpanSource};
use crate::raster::stepping::ScanState;
use crate::raster::tables::entry::{PolygonEntry, entry_corner_ids};
use crate::raster::vertex::{ScreenVertex, TriangleTest};

impl<C: Copy> ScanState<'_, '_, C> {
    /// The corners of the polygon at `position`, as vertices.
    fn corners(&self, position: usize) -> impl Iterator<Item = ScreenVertex> + Clone + '_ {
        entry_corners(
            &self.tables.polygons[position],
            self.tables.corners,
            self.tables.vertices,
        )
    }

    /// Moves the polygon at `position` into the APT at `row`, with its
    /// plane and the edges covering `row`.
    /// Inline: a triangle goes straight to [`Self::activate_triangle`].
    /// (With the `profile` feature it is kept out of line: the profile's
    /// "activation" stage.)
    #[cfg_attr(feature = "profile", inline(never))]
    #[cfg_attr(not(feature = "profile"), inline(always))]
    pub(crate) fn activate_polygon<D: DepthFormat, const AT_ONCE: bool>(
        &mut self,
        position: usize,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> Result<(), Error> {
        // (Without the `polygons` feature the tables hold triangles alone.)
        if !cfg!(feature = "polygons") || self.tables.polygons[position].corner_count() == 3 {
            self.activate_triangle::<D, AT_ONCE>(position, row, rows)
        } else {
            self.activate_general(position, row)
        }
    }

    /// [`Self::activate_polygon`] for a polygon of four or more corners,
    /// or a triangle whose plane is shared.
    #[inline(never)]
    fn activate_general(&mut self, position: usize, row: u16) -> Result<(), Error> {
        let polygon = self.tables.polygons[position];
        let (corners, vertices) = (self.tables.corners, self.tables.vertices);
        let (width, height) = (self.tables.width, self.tables.height);
        let depth = match polygon.shared_plane() {
            Some(_) => match shared_plane_of(&polygon, corners, vertices) {
                Some(plane) => shared_depth(&plane, width, height),
                None => SpanDepth::Exact,
            },
            None => self.own_depth(position, row),
        };
        let entry = ActivePolygon::new(
            position as u32,
            polygon.id() + 1,
            polygon.end_row,
            polygon.color,
            depth,
        );
        let slot = self
            .active
            .push(entry)
            .map_err(|_| Error::ActivePolygonsFull { row })?;
        self.activate_edges(slot, row, true)
    }

    /// The depth set-up of a polygon of four or more corners on its own
    /// plane (Newell's).
    #[inline]
    fn own_depth(&self, position: usize, row: u16) -> SpanDepth {
        let polygon = &self.tables.polygons[position];
        match Plane::new(self.corners(position)).map(|p| (p, p.gradients())) {
            Some((plane, Some((dz_dx, dz_dy)))) => SpanDepth::Stepped {
                dz_dx,
                dz_dy,
                row_value: plane.row_start(
                    (dz_dx, dz_dy),
                    self.tables.width,
                    polygon.first_row,
                    row,
                ),
                // A polygon's plane is Newell's fit: its corners may lie
                // off it, so its range is checked span by span.
                accumulator: None,
            },
            // Non-zero area was checked when the polygon entered the table.
            Some((_, None)) | None => SpanDepth::Exact,
        }
    }

    /// [`Self::activate_polygon`] for a triangle: its corners sorted by y,
    /// its long edge and the short edge covering `row` enter at once, and
    /// the lower short edge waits for its `switch_row`. A triangle that
    /// covers this row alone is drawn at once and never enters the APT.
    #[inline(never)]
    fn activate_triangle<D: DepthFormat, const AT_ONCE: bool>(
        &mut self,
        position: usize,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> Result<(), Error> {
        let polygon = self.tables.polygons[position];
        let (corners, vertices) = (self.tables.corners, self.tables.vertices);
        // (Not `let &[..] = entry_corner_ids(..) else`, which reads the
        // same: on a Cortex-M0+ that took 4,720 more instructions a frame
        // of the torus knot.)
        let ids = match polygon.triangle() {
            Some(ids) => ids,
            // A triangle sharing a plane: its corners from the list.
            None => match *entry_corner_ids(&polygon, corners) {
                [a, b, c] => [a, b, c],
                _ if cfg!(feature = "polygons") => return self.activate_general(position, row),
                // (Three corners: the tables hold triangles alone.)
                _ => return Err(Error::NeedsPolygons),
            },
        };
        // Not `ids.map`: on a Cortex-M0+ that became a loop through
        // `try_from_fn`, 90 cycles for three loads.
        let vertex = |k: usize| vertices[usize::from(ids[k])];
        let [a, b, c] = [vertex(0), vertex(1), vertex(2)];
        let shared = polygon.shared_plane().is_some();
        // Only a triangle of one row, activated on it: one that a band
        // activates on its last row (having started above the band) is
        // stepped from its first row as one scan over the whole frame
        // steps it, where the tiny path's exact values could differ from
        // the stepped ones by one step of the depth format.
        if AT_ONCE
            && !shared
            && polygon.end_row == row + 1
            && polygon.first_row == row
            && self.draw_tiny_row(a, b, c, &polygon, row, rows)
        {
            return Ok(());
        }
        if SMALL_TRIANGLES
            && self.small_triangles
            && !shared
            && let Some(done) =
                self.activate_small::<D, AT_ONCE>(position, &polygon, [a, b, c], row, rows)
        {
            return done;
        }
        // The plane passes through the corners: in range when they are
        // (see IN_RANGE).
        let in_range = [a.z, b.z, c.z].iter().all(|z| IN_RANGE.contains(z));
        // `first` is the plane's value at column 0 of the triangle's first
        // row; each row's is that plus a step of `dz_dy` per row, exactly.
        // A band's scan may activate it further down.
        let rows_below = i32::from(row) - i32::from(polygon.first_row);
        let stepped = |dz_dx: i64, dz_dy: i64, first: i64| {
            stepped_depth::<D>((dz_dx, dz_dy, first), in_range, rows_below)
        };
        let own_plane = if shared {
            None
        } else {
            TrianglePlane::new(a, b, c)
        };
        let (depth, narrow) = match own_plane {
            // The common case: two exact divisions per gradient.
            Some(plane) => stepped(plane.dz_dx, plane.dz_dy, plane.row_start(polygon.first_row)),
            // Large (256 px or more) or steep: the general plane.
            None if shared => match shared_plane_of(&polygon, corners, vertices) {
                Some(plane) => (
                    shared_depth(&plane, self.tables.width, self.tables.height),
                    None,
                ),
                None => (SpanDepth::Exact, None),
            },
            None => match Plane::triangle(a, b, c) {
                Some(plane) => match plane.gradients() {
                    Some((dz_dx, dz_dy)) => {
                        let (width, first_row) = (self.tables.width, polygon.first_row);
                        let first = plane.row_start((dz_dx, dz_dy), width, first_row, first_row);
                        stepped(dz_dx, dz_dy, first)
                    }
                    None => (SpanDepth::Exact, None),
                },
                None => return Ok(()), // Zero area was left out when it was queued.
            },
        };
        let ([(_, top), (mid_id, mid), (bot_id, bot)], odd) =
            sort_by_y([(ids[0], a), (ids[1], b), (ids[2], c)]);
        let height = i32::from(self.tables.height);
        let row_of = |y: i32| first_sample_at_or_after(y);
        let (mid_row, bot_row) = (row_of(mid.y), row_of(bot.y));
        let r = i32::from(row);
        let clip = |end: i32| end.min(height) as u16;
        let long = ActiveEdge::start(top, bot, row, clip(bot_row), NO_EDGE);
        let mut switch_row = NO_ROW;
        let short = if r < mid_row {
            if mid_row < bot_row.min(height) {
                switch_row = mid_row as u16;
            }
            ActiveEdge::start(top, mid, row, clip(mid_row), NO_EDGE)
        } else {
            ActiveEdge::start(mid, bot, row, clip(bot_row), NO_EDGE)
        };
        // Screen y points down: the middle corner lies left of the long edge
        // when the cross product (bottom - top) x (middle - top) is
        // positive. That is minus twice the signed area of (top, middle,
        // bottom), which is the set-up's `a b c` area, signed by the
        // parity of the sort: no second product when the set-up made it.
        // (Guard-band differences: below 2^23, products below 2^46.)
        let turn = match own_plane {
            Some(plane) if odd => i64::from(plane.twice_area),
            Some(plane) => -i64::from(plane.twice_area),
            None => cross(bot.x - top.x, bot.y - top.y, mid.x - top.x, mid.y - top.y),
        };
        debug_assert_eq!(
            turn,
            cross(bot.x - top.x, bot.y - top.y, mid.x - top.x, mid.y - top.y)
        );
        let set = |entry: &mut ActivePolygon<C>| {
            entry.set_triangle(
                position as u32,
                polygon.id() + 1,
                polygon.end_row,
                switch_row,
                polygon.color,
                (depth, narrow),
                long,
                short,
                turn > 0,
                [mid_id, bot_id],
            )
        };
        self.stats.edges += 2;
        self.pool.live += 2;
        if AT_ONCE && polygon.end_row == row + 1 {
            // One row: its span now, and no APT entry.
            let mut entry = ActivePolygon::filler(polygon.color);
            set(&mut entry);
            self.fill_and_step(&mut entry, row, rows);
            return Ok(());
        }
        // Written in its slot (see `set_triangle`).
        self.active
            .push_in_place(set)
            .map(|_| ())
            .map_err(|()| Error::ActivePolygonsFull { row })
    }

    /// Draws a triangle that covers `row` alone and spans at most
    /// [`TINY_COLUMNS`] samples of it, with no edges and no gradients: its
    /// covered samples (contiguous, the triangle being convex) come from
    /// the fill rule's sample test, and their depths are the plane's exact
    /// values. Returns `false` (nothing drawn) for a wider triangle.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn draw_tiny_row<D: DepthFormat>(
        &mut self,
        a: ScreenVertex,
        b: ScreenVertex,
        c: ScreenVertex,
        polygon: &PolygonEntry<C>,
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> bool {
        let width = i32::from(self.tables.width);
        let first = first_sample_at_or_after(a.x.min(b.x).min(c.x)).max(0);
        let end = first_sample_at_or_after(a.x.max(b.x).max(c.x)).min(width);
        if end - first > TINY_COLUMNS {
            return false;
        }
        let test = TriangleTest::new(a, b, c);
        let (mut start, mut stop) = (end, first);
        for column in first..end {
            if test.covers_pixel(column, i32::from(row)) {
                start = start.min(column);
                stop = column + 1;
            }
        }
        let Some(plane) = Plane::triangle(a, b, c) else {
            return true; // No area: nothing to draw.
        };
        let source = SpanSource::Exact(plane, row);
        if rows.fill(start, stop, polygon.id() + 1, polygon.color, &source) {
            self.stats.spans += 1;
        }
        true
    }

    /// Enters a small triangle ([`SmallCoverage`]) activated on `row`,
    /// with the depth set-up its edges would step, when it is in range:
    /// drawn at once when that is the last row it covers, else into the
    /// APT. `None` (nothing done) for a triangle that is not small, or
    /// whose depth set-up is not a triangle's in range: its edges take it.
    /// Out of line: the stepped path's state stays out of its registers.
    #[inline(never)]
    fn activate_small<D: DepthFormat, const AT_ONCE: bool>(
        &mut self,
        position: usize,
        polygon: &PolygonEntry<C>,
        corners: [ScreenVertex; 3],
        row: u16,
        rows: &mut RowBuffers<'_, C, D>,
    ) -> Option<Result<(), Error>> {
        let width = self.tables.width;
        let coverage = SmallCoverage::new(corners, row, polygon.end_row - row, width)?;
        if coverage.is_empty() {
            return Some(Ok(()));
        }
        let [a, b, c] = corners;
        let plane = TrianglePlane::new(a, b, c)?;
        let in_range = [a.z, b.z, c.z].iter().all(|z| IN_RANGE.contains(z));
        if !in_range {
            return None;
        }
        let rows_below = i32::from(row) - i32::from(polygon.first_row);
        let first = plane.row_start(polygon.first_row);
        let depth = stepped_depth::<D>((plane.dz_dx, plane.dz_dy, first), true, rows_below);
        // Only the set-ups whose spans the stepped path draws from the same
        // accumulator: a narrow row, or (in a format with no narrow rows)
        // the stepped plane's accumulator. A `NARROW` format's triangle
        // whose row step does not fit a narrow row takes the general
        // path, which rounds each span's first value on its own.
        let masked = match depth {
            (SpanDepth::Narrow, Some(_)) => true,
            (
                SpanDepth::Stepped {
                    accumulator: Some(_),
                    ..
                },
                None,
            ) => !D::NARROW,
            _ => false,
        };
        if !masked {
            return None;
        }
        // One that covers a later row waits in the small triangles' own
        // table while it has room, else in the APT as any triangle does.
        if !(AT_ONCE && coverage.is_last_row())
            && let Some(entry) = SmallActive::new(polygon.id() + 1, polygon.color, depth, coverage)
            && self.small.push(entry)
        {
            return Some(Ok(()));
        }
        let set = |entry: &mut ActivePolygon<C>| {
            let at = (position as u32, polygon.id() + 1, polygon.end_row);
            entry.set_small(at, polygon.color, depth, coverage)
        };
        if AT_ONCE && coverage.is_last_row() {
            // Its one row now, and no APT entry.
            let mut entry = ActivePolygon::filler(polygon.color);
            set(&mut entry);
            self.fill_and_step(&mut entry, row, rows);
            return Some(Ok(()));
        }
        Some(
            self.active
                .push_in_place(set)
                .map(|_| ())
                .map_err(|()| Error::ActivePolygonsFull { row }),
        )
    }

    /// Starts edges of the active polygon at `slot`: at its activation,
    /// every edge covering `row`; later, those starting on `row`.
    #[inline(never)]
    pub(crate) fn activate_edges(
        &mut self,
        slot: usize,
        row: u16,
        at_activation: bool,
    ) -> Result<(), Error> {
        let Some(&entry) = self.active.get(slot) else {
            return Err(Error::ActivePolygonsFull { row });
        };
        let polygon = &self.tables.polygons[entry.position as usize];
        let end_limit = i32::from(self.tables.height);
        let corners = entry_corners(polygon, self.tables.corners, self.tables.vertices);
        let mut result = Ok(());
        let (active, pool, stats) = (&mut self.active, &mut self.pool, &mut self.stats);
        for_each_edge(corners, |top, bottom| {
            let first = first_sample_at_or_after(top.y);
            let end_row = first_sample_at_or_after(bottom.y).min(end_limit);
            let covers = first <= i32::from(row) && end_row > i32::from(row);
            let wanted = if at_activation {
                covers
            } else {
                covers && first == i32::from(row)
            };
            if wanted && result.is_ok() {
                let edge = ActiveEdge::start(top, bottom, row, end_row as u16, NO_EDGE);
                result = match active.get_mut(slot) {
                    Some(entry) => entry
                        .add_edge(edge, pool)
                        .map_err(|()| Error::ActiveEdgesFull { row }),
                    None => Err(Error::ActivePolygonsFull { row }),
                };
                stats.edges += 1;
            }
        });
        result
    }
}

/// A stepped triangle's depth set-up on the row `rows_below` rows under
/// its first, from its gradients and its plane's value at column 0 of its
/// first row, `(dz_dx, dz_dy, first)`, and whether its corners are in
/// range: a narrow row when the format has one and the triangle is in
/// range, else the stepped plane (with the accumulator's step when in
/// range). The one set-up both a triangle's edges and a small triangle's
/// masks draw with.
#[inline(always)]
fn stepped_depth<D: DepthFormat>(
    (dz_dx, dz_dy, first): (i64, i64, i64),
    in_range: bool,
    rows_below: i32,
) -> (SpanDepth, Option<NarrowRow>) {
    if D::NARROW
        && in_range
        && let Some(narrow) = D::narrow_row(first, dz_dx, dz_dy, rows_below)
    {
        return (SpanDepth::Narrow, Some(narrow));
    }
    let depth = SpanDepth::Stepped {
        dz_dx,
        dz_dy,
        // 0 <= rows_below < 2^12, |dz_dy| < 2^40.
        row_value: if rows_below == 0 {
            first
        } else {
            first + mul_i64_small(dz_dy, rows_below)
        },
        accumulator: in_range.then(|| D::accumulator_step(dz_dx)).flatten(),
    };
    (depth, None)
}

/// A triangle's corners (with their vertex indices) sorted by y (stable:
/// equal ones keep their order), and whether the sort was an odd
/// permutation.
#[inline]
fn sort_by_y(corners: [(u16, ScreenVertex); 3]) -> ([(u16, ScreenVertex); 3], bool) {
    sort_by_y_as::<BRANCH_FREE>(corners)
}

/// [`sort_by_y`] with or without branches (both are tested on the host).
#[inline(always)]
fn sort_by_y_as<const BRANCH_FREE: bool>(
    corners: [(u16, ScreenVertex); 3],
) -> ([(u16, ScreenVertex); 3], bool) {
    if BRANCH_FREE {
        // The same three compare-and-swaps, always made, on the corners'
        // indices (selects of small integers: the corners come in any
        // order, so each branch would miss often, and selecting whole
        // corners went through the stack). The third swaps nothing when
        // the second did not: the first already ordered that pair.
        let y = |k: usize| corners[k].1.y;
        let sort_pair = |upper: usize, lower: usize| {
            let swap = y(lower) < y(upper);
            let select = core::hint::select_unpredictable;
            (select(swap, lower, upper), select(swap, upper, lower), swap)
        };
        let (top, mid, first) = sort_pair(0, 1);
        let (mid, bot, second) = sort_pair(mid, 2);
        let (top, mid, third) = sort_pair(top, mid);
        return (
            [corners[top], corners[mid], corners[bot]],
            first ^ second ^ third,
        );
    }
    let [mut top, mut mid, mut bot] = corners;
    let mut odd = false;
    if mid.1.y < top.1.y {
        core::mem::swap(&mut top, &mut mid);
        odd = !odd;
    }
    if bot.1.y < mid.1.y {
        core::mem::swap(&mut mid, &mut bot);
        odd = !odd;
        if mid.1.y < top.1.y {
            core::mem::swap(&mut top, &mut mid);
            odd = !odd;
        }
    }
    ([top, mid, bot], odd)
}

/// Triangles covering one row and at most this many columns of it are
/// drawn by sample tests and exact plane values, without edges.
const TINY_COLUMNS: i32 = 4;

#[cfg(test)]
mod tests {
    use super::*;

    /// Both forms of the corner sort agree for every order of three
    /// corners, ties included: sorted by y, stable, and the parity that
    /// of the permutation.
    #[test]
    fn corner_sorts_agree_and_are_stable() {
        for code in 0..27 {
            let ys = [code % 3, code / 3 % 3, code / 9];
            let corners: [(u16, ScreenVertex); 3] = core::array::from_fn(|k| {
                (
                    k as u16,
                    ScreenVertex {
                        x: 0,
                        y: ys[k],
                        z: 0,
                    },
                )
            });
            let (sorted, odd) = sort_by_y_as::<true>(corners);
            assert_eq!((sorted, odd), sort_by_y_as::<false>(corners), "{ys:?}");
            let mut want = corners;
            want.sort_by_key(|&(_, v)| v.y); // stable
            assert_eq!(sorted, want, "{ys:?}");
            let order = sorted.map(|(k, _)| usize::from(k));
            let inversions = (0..3)
                .flat_map(|i| (i + 1..3).map(move |j| (i, j)))
                .filter(|&(i, j)| order[i] > order[j])
                .count();
            assert_eq!(odd, inversions % 2 == 1, "{ys:?}");
        }
    }
}
