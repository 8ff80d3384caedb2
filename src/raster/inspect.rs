//! Read access to prepared tables, for a renderer of one's own over the
//! same tables, sub-pixel grid and fill rule (the comparison methods of
//! `zline-lab`, the interval scanline and the painter's algorithm, are
//! written on it): each polygon's rows, key, colour, corners and edges;
//! where an edge crosses a row, as the scanner finds it; and the depth
//! plane a polygon is drawn with on a row, set up as the scanner sets it
//! up.

use core::ops::Range;

use crate::raster::active::SpanDepth;
use crate::raster::edge::ActiveEdge;
use crate::raster::entry_geometry::{entry_corners, for_each_edge, shared_depth, shared_plane_of};
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::plane::{Plane, TrianglePlane};
use crate::raster::tables::{PolygonEntry, Prepared};
use crate::raster::vertex::ScreenVertex;

impl<'a, C: Copy> Prepared<'a, C> {
    /// The polygons in the order the scanner activates them: by first
    /// row, and in the order they were added within a row.
    pub fn polygons(&self) -> impl ExactSizeIterator<Item = PreparedPolygon<'a, C>> + Clone + 'a {
        let tables = *self;
        (0..self.polygons.len()).map(move |position| PreparedPolygon { tables, position })
    }

    /// The polygon at `position` in that order.
    pub fn polygon(&self, position: usize) -> Option<PreparedPolygon<'a, C>> {
        (position < self.polygons.len()).then_some(PreparedPolygon {
            tables: *self,
            position,
        })
    }
}

/// One polygon of [`Prepared`] tables.
#[derive(Debug, Clone, Copy)]
pub struct PreparedPolygon<'a, C> {
    tables: Prepared<'a, C>,
    position: usize,
}

impl<'a, C: Copy> PreparedPolygon<'a, C> {
    fn entry(&self) -> &'a PolygonEntry<C> {
        &self.tables.polygons[self.position]
    }

    /// Its position in [`Prepared::polygons`].
    pub fn position(&self) -> usize {
        self.position
    }

    /// The order it was added in (from 0): on equal depth the polygon
    /// added first wins.
    pub fn id(&self) -> u32 {
        self.entry().id()
    }

    /// Its colour.
    pub fn color(&self) -> C {
        self.entry().color
    }

    /// The rows whose sample it can cover: its first row to one past its
    /// last.
    pub fn rows(&self) -> Range<u16> {
        let entry = self.entry();
        entry.first_row..entry.end_row
    }

    /// Its corners, in order around it.
    pub fn corners(&self) -> impl Iterator<Item = ScreenVertex> + Clone + 'a {
        entry_corners(self.entry(), self.tables.corners, self.tables.vertices)
    }

    /// Calls `f(top, bottom)` for each of its edges that is not
    /// horizontal, its upper end first.
    pub fn for_each_edge(&self, f: impl FnMut(ScreenVertex, ScreenVertex)) {
        for_each_edge(self.corners(), f);
    }

    /// The depth plane it is drawn with on `row`, set up as the scanner
    /// sets it up there; `None` for a polygon of no area.
    pub fn row_plane(&self, row: u16) -> Option<RowPlane> {
        let tables = &self.tables;
        let polygon = self.entry();
        if polygon.shared_plane().is_some() {
            let plane = shared_plane_of(polygon, tables.corners, tables.vertices)?;
            return Some(match shared_depth(&plane, tables.width, tables.height) {
                SpanDepth::Shared {
                    dz_dx,
                    dz_dy,
                    row0_value,
                } => RowPlane(RowPlaneKind::Stepped {
                    dz_dx,
                    row_value: row0_value + i64::from(row) * dz_dy,
                }),
                _ => RowPlane(RowPlaneKind::Exact(plane)),
            });
        }
        if polygon.corner_count() == 3 {
            let mut c = self.corners();
            let (a, b, cc) = (c.next()?, c.next()?, c.next()?);
            if let Some(plane) = TrianglePlane::new(a, b, cc) {
                return Some(RowPlane(RowPlaneKind::Stepped {
                    dz_dx: plane.dz_dx,
                    row_value: plane.row_start(row),
                }));
            }
        }
        let plane = Plane::new(self.corners())?;
        Some(RowPlane(match plane.gradients() {
            Some((dz_dx, dz_dy)) => RowPlaneKind::Stepped {
                dz_dx,
                row_value: plane.row_start((dz_dx, dz_dy), tables.width, polygon.first_row, row),
            },
            None => RowPlaneKind::Exact(plane),
        }))
    }
}

/// Where the edge from `top` down to `bottom` crosses `row`: the first
/// pixel whose sample lies right of it (or on it, by the top-left rule),
/// as the scanner finds it; `None` when the edge does not reach the row's
/// sample line.
pub fn edge_crossing(top: ScreenVertex, bottom: ScreenVertex, row: u16) -> Option<i32> {
    let (first, end) = (
        first_sample_at_or_after(top.y),
        first_sample_at_or_after(bottom.y),
    );
    let covers = first <= i32::from(row) && end > i32::from(row);
    covers.then(|| ActiveEdge::start(top, bottom, row, row + 1, u32::MAX).x)
}

/// The depth plane of a polygon on one row ([`PreparedPolygon::row_plane`]).
#[derive(Debug, Clone, Copy)]
pub struct RowPlane(RowPlaneKind);

#[derive(Debug, Clone, Copy)]
enum RowPlaneKind {
    /// The gradient and the value at column 0 of the row, in plane units.
    Stepped { dz_dx: i64, row_value: i64 },
    /// A steep plane, evaluated exactly at each pixel.
    Exact(Plane),
}

impl RowPlane {
    /// The plane's value at pixel `x` of `row` (the row it was set up
    /// for), in plane units: input depth steps
    /// ([`DEPTH_ONE`](crate::limits::DEPTH_ONE) a unit of depth)
    /// times `2^`[`PLANE_FRAC_BITS`](crate::limits::PLANE_FRAC_BITS).
    pub fn value(&self, x: i32, row: u16) -> i64 {
        match self.0 {
            RowPlaneKind::Stepped { dz_dx, row_value } => row_value + dz_dx * i64::from(x),
            RowPlaneKind::Exact(plane) => plane.value_at_pixel(x, i32::from(row)),
        }
    }
}
