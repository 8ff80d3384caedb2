//! Preparing the tables for scanning: the polygon table bucketed by first
//! row (a stable radix sort, O(n)), the edge table built, and the
//! [`Prepared`] view scanners read.

use crate::raster::edge::EdgeEntry;
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::stats::FrameStats;
use crate::raster::tables::entry::{PolygonEntry, entry_corner_ids};
use crate::raster::tables::state::{Tables, TablesMut};
use crate::raster::tables::storage::{TableEdge, TableStorage};
use crate::raster::vertex::ScreenVertex;

/// Prepared tables: sorted, with their edge table, ready to scan. Many
/// scanners may share one (on several threads, on the host), each over its
/// own band of rows. (The same view of the tables in drawing order,
/// [`Tables::in_drawing_order`], is for the polygon-after-polygon methods
/// only: a scan of it is [`Error::NotPrepared`](crate::Error::NotPrepared).)
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
    /// Whether [`Tables::prepare`] made it (sorted, with its edge table),
    /// so that the scanline methods may scan it.
    pub(crate) scannable: bool,
}

impl<C> Prepared<'_, C> {
    /// A frame's statistics before its scan: the tables' own counts.
    pub(crate) fn frame_stats(&self) -> FrameStats {
        FrameStats {
            vertices: self.vertices.len() as u32,
            corners: self.corners.len() as u32,
            polygons: self.polygons.len() as u32,
            off_screen: self.off_screen,
            degenerate: self.degenerate,
            ..FrameStats::default()
        }
    }
}

impl<S: TableStorage> Tables<S> {
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
            scannable: true,
        }
    }

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
            scannable: false,
        }
    }

    /// Whether [`Self::prepare`] has sorted the polygons by first row
    /// since the tables were cleared.
    pub fn is_prepared(&self) -> bool {
        self.state.counts.prepared
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

impl<C: Copy> TablesMut<'_, C> {
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
        if !cfg!(feature = "polygons") {
            // Triangles alone: every edge enters with its polygon.
            return;
        }
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
            heap_sort(&mut edges[..count]);
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

/// Sorts `keys` in place by heapsort, for an edge table too full to lend
/// the radix sort its spare half: `O(n log n)` with no buffer, in a few
/// hundred bytes of code (the library's `sort_unstable` took 2.9 KB of a
/// Cortex-M0+ firmware's flash for this rare path).
fn heap_sort(keys: &mut [EdgeEntry]) {
    let n = keys.len();
    for root in (0..n / 2).rev() {
        sift_down(keys, root, n);
    }
    for end in (1..n).rev() {
        keys.swap(0, end);
        sift_down(keys, 0, end);
    }
}

/// Restores the max-heap order of `keys[..end]` below `root`, whose
/// children are heaps.
fn sift_down(keys: &mut [EdgeEntry], mut root: usize, end: usize) {
    loop {
        let mut child = 2 * root + 1;
        if child >= end {
            return;
        }
        if child + 1 < end && keys[child] < keys[child + 1] {
            child += 1;
        }
        if keys[root] >= keys[child] {
            return;
        }
        keys.swap(root, child);
        root = child;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heap_sort_sorts_like_the_library() {
        // Every length to 40, rows and positions from a simple generator
        // with repeats, against `sort_unstable`.
        let mut seed = 12345u32;
        for len in 0..=40 {
            for _ in 0..20 {
                let mut keys: [EdgeEntry; 40] = core::array::from_fn(|_| {
                    seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                    EdgeEntry::new(((seed >> 20) % 9) as u16, (seed >> 8) as usize % 5)
                });
                let mut expected = keys;
                expected[..len].sort_unstable();
                heap_sort(&mut keys[..len]);
                assert_eq!(keys[..len], expected[..len], "length {len}");
            }
        }
    }

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
}
