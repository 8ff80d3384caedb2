//! The polygon-table entry, packed in 16 bytes ([`PolygonEntry`]), and
//! where a polygon's corners are: inline for a triangle on its own plane,
//! in the corner list for any other.

use crate::limits::{MAX_POLYGON_CORNERS, MAX_POLYGONS};

/// A polygon-table entry (opaque: its fields are the core's own).
///
/// A triangle on its own plane, nearly every polygon of a mesh, carries
/// its three vertex-table indices inline: activation reads no corner list
/// (after the sort, the list is read in no order, and each triangle's
/// corners would cost a cache miss). Its corners are in the corner list
/// too, where [`Tables::share_plane`] and the capacity accounting find
/// them. The entry stays 16 bytes with a 2-byte colour: the id, the
/// corner count and the shared-plane flag share one word.
///
/// [`Tables::share_plane`]: crate::raster::Tables::share_plane
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
    ///
    /// [`Tables::share_plane`]: crate::raster::Tables::share_plane
    #[inline(always)]
    pub(crate) fn shared_plane(&self) -> Option<usize> {
        (self.tag & SHARED_PLANE != 0).then(|| self.corner_start() + self.corner_count())
    }

    /// Marks the polygon as sharing the plane of the three corners after
    /// its own, which start at `start` in the corner list.
    pub(super) fn share_plane_after(&mut self, start: usize) {
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

#[cfg(test)]
mod tests {
    use super::*;

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
