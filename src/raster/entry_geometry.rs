//! A queued polygon read back from the tables as geometry: its corners as
//! vertices, its edges top end first, its exact depth plane (its own or
//! the one it shares) and a shared plane's depth set-up. Activation, the
//! general span path and [`inspect`](super::inspect) all read a polygon
//! through these.

use crate::raster::active::SpanDepth;
use crate::raster::plane::Plane;
use crate::raster::tables::entry::{PolygonEntry, entry_corner_ids};
use crate::raster::vertex::ScreenVertex;

/// The plane of a polygon that shares one
/// ([`Tables::share_plane`](crate::raster::Tables::share_plane)): the
/// triangle of the three corners after its own.
#[inline(never)]
pub(crate) fn shared_plane_of<C>(
    polygon: &PolygonEntry<C>,
    corners: &[u16],
    vertices: &[ScreenVertex],
) -> Option<Plane> {
    let start = polygon.shared_plane()?;
    let corner = |k: usize| vertices[usize::from(corners[start + k])];
    Plane::triangle(corner(0), corner(1), corner(2))
}

/// The exact plane a polygon's depth comes from: the plane it shares, or
/// Newell's over its own corners.
pub(crate) fn polygon_plane<C>(
    polygon: &PolygonEntry<C>,
    corners: &[u16],
    vertices: &[ScreenVertex],
) -> Option<Plane> {
    match polygon.shared_plane() {
        Some(_) => shared_plane_of(polygon, corners, vertices),
        None => Plane::new(entry_corners(polygon, corners, vertices)),
    }
}

/// The depth set-up of a polygon with a shared plane
/// ([`SpanDepth::Shared`]: the plane's gradients and its value at column 0
/// of row 0); [`SpanDepth::Exact`] when the plane is steep.
#[inline(never)]
pub(crate) fn shared_depth(plane: &Plane, width: u16, height: u16) -> SpanDepth {
    match plane.gradients() {
        Some((dz_dx, dz_dy)) => SpanDepth::Shared {
            dz_dx,
            dz_dy,
            row0_value: plane.shared_row_start((dz_dx, dz_dy), width, height, 0),
        },
        None => SpanDepth::Exact,
    }
}

/// Calls `f(top, bottom)` for every non-horizontal edge of a polygon, its
/// ends ordered top first.
pub(crate) fn for_each_edge(
    corners: impl Iterator<Item = ScreenVertex> + Clone,
    mut f: impl FnMut(ScreenVertex, ScreenVertex),
) {
    let next = corners.clone().skip(1).chain(corners.clone().take(1));
    for (a, b) in corners.zip(next) {
        if a.y != b.y {
            let (top, bottom) = if a.y < b.y { (a, b) } else { (b, a) };
            f(top, bottom);
        }
    }
}

/// The corners of a polygon-table entry, as vertices.
pub(crate) fn entry_corners<'a, C>(
    polygon: &'a PolygonEntry<C>,
    corners: &'a [u16],
    vertices: &'a [ScreenVertex],
) -> impl Iterator<Item = ScreenVertex> + Clone + 'a {
    entry_corner_ids(polygon, corners)
        .iter()
        .map(move |&i| vertices[usize::from(i)])
}
