//! The active tables: the active polygon table (APT), whose entries hold
//! their left/right edge pair inline, and a pool of further active edges
//! for polygons that cross a row more than twice (concave ones).
//!
//! A polygon's pooled edges form a list kept sorted by crossing, so its
//! spans come out of a merge of the inline pair and the list: no buffer
//! per polygon, whatever its number of corners.

use super::depth::NarrowRow;
use super::edge::ActiveEdge;
use super::slots::Slots;
use super::small::SmallCoverage;

/// End of an edge list in the pool.
pub(crate) const NO_EDGE: u32 = u32::MAX;

/// How an active polygon produces depth along a span.
#[derive(Debug, Clone, Copy)]
pub(crate) enum SpanDepth {
    /// Gradients in plane units per pixel and the plane value at the sample
    /// point of column 0 on the current row (it may lie outside the polygon;
    /// only its sum with `dz_dx · x` at a covered pixel is stored).
    Stepped {
        dz_dx: i64,
        dz_dy: i64,
        row_value: i64,
        /// The depth format's accumulator step for `dz_dx`, when the
        /// polygon stays in [`IN_RANGE`](crate::raster::depth::IN_RANGE)
        /// and its spans need no range check.
        accumulator: Option<i64>,
    },
    /// An in-range triangle of a [`NARROW`](crate::raster::depth::DepthFormat::NARROW)
    /// depth format: its 32-bit accumulator at column 0 of the current row
    /// and its steps, stepped once a row, are the entry's `narrow` row.
    Narrow,
    /// A polygon sharing a plane with others
    /// ([`Tables::share_plane`](crate::raster::Tables::share_plane)): the
    /// plane's own affine function in plane units, anchored where the
    /// plane is (not where the polygon starts), each pixel rounded on its
    /// own, so every polygon of the plane stores the same depth at a pixel.
    Shared {
        dz_dx: i64,
        dz_dy: i64,
        /// The plane's value at the sample point of column 0 of row 0
        /// (each row's is this plus `row · dz_dy`, so nothing is stepped).
        row0_value: i64,
    },
    /// Edge-on polygon: its plane is evaluated exactly at each pixel.
    Exact,
}

/// Active-polygon-table entry (opaque).
#[derive(Debug, Clone, Copy)]
pub struct ActivePolygon<C> {
    /// Position in the sorted polygon table (edge-table entries name it).
    pub(crate) position: u32,
    /// The tie-break key: the polygon's id + 1 (background is 0): on equal
    /// depth the smaller key wins, so the polygon added first.
    pub(crate) key: u32,
    /// One past the polygon's last row: there the entry leaves.
    pub(crate) end_row: u16,
    /// For a triangle, the row where its lower short edge starts (it then
    /// joins the pair by itself, with no edge-table entry); `NO_ROW` when
    /// no edge is left to start.
    pub(crate) switch_row: u16,
    /// For a triangle, the first row where the row loop has more to do
    /// than step its edges: the smaller of `end_row` and `switch_row`, so
    /// that one comparison a row covers both.
    pub(crate) event_row: u16,
    pub(crate) color: C,
    pub(crate) depth: SpanDepth,
    /// A narrow triangle's row state (see [`SpanDepth::Narrow`]).
    pub(crate) narrow: NarrowRow,
    /// The edge pair: up to two active edges held inline. For a triangle,
    /// always two: the left edge, then the right one.
    pair: [ActiveEdge; 2],
    pair_len: u8,
    /// Whether a triangle (its pair is ordered and it has no pooled
    /// edges), and whether its depth is a narrow row.
    shape: Shape,
    /// For a triangle, which of the pair is the short edge (the other is
    /// the long one, from the top corner to the bottom one).
    short_side: u8,
    /// Further active edges: a list in the [`EdgePool`], sorted by `x`.
    extra: u32,
    /// For a triangle waiting for its `switch_row`: the vertex-table
    /// indices of its middle and bottom corners, the ends of the lower
    /// short edge. For a small triangle, which has no edges: its coverage
    /// ([`SmallCoverage::to_words`]).
    pub(crate) lower: [u16; 2],
}

/// What the row loop does with an active polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shape {
    /// Any polygon: its spans come from the edge pair and the pool.
    Polygon,
    /// A triangle: its two edges, ordered.
    Triangle,
    /// A triangle whose depth is a narrow row (the common case).
    NarrowTriangle,
    /// A small triangle: no edges; its coverage masks in `lower`, its
    /// depth a triangle's in range (a narrow row, or stepped with an
    /// accumulator).
    Small,
}

/// No row: a triangle with no edge left to start.
pub(crate) const NO_ROW: u16 = u16::MAX;

impl<C: Copy> ActivePolygon<C> {
    /// A filler for unused slots.
    pub const fn filler(color: C) -> Self {
        Self::new(0, 0, 0, color, SpanDepth::Exact)
    }

    /// A polygon entering the APT, with no active edges yet.
    pub(crate) const fn new(
        position: u32,
        key: u32,
        end_row: u16,
        color: C,
        depth: SpanDepth,
    ) -> Self {
        Self {
            position,
            key,
            end_row,
            switch_row: NO_ROW,
            event_row: end_row,
            color,
            depth,
            narrow: NarrowRow::ZERO,
            pair: [ActiveEdge::EMPTY; 2],
            pair_len: 0,
            shape: Shape::Polygon,
            short_side: 0,
            extra: NO_EDGE,
            lower: [0; 2],
        }
    }

    /// Makes this entry a triangle entering the APT: its two edges ordered
    /// left then right (`short_left` says where the short one goes), and
    /// the ends of its lower short edge. Written field by field, so that it
    /// can fill a table slot in place: a Cortex-M0+ would copy a finished
    /// entry (over 100 bytes) with a call to memcpy.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn set_triangle(
        &mut self,
        position: u32,
        key: u32,
        end_row: u16,
        switch_row: u16,
        color: C,
        (depth, narrow): (SpanDepth, Option<NarrowRow>),
        long: ActiveEdge,
        short: ActiveEdge,
        short_left: bool,
        lower: [u16; 2],
    ) {
        self.position = position;
        self.key = key;
        self.end_row = end_row;
        self.switch_row = switch_row;
        self.event_row = end_row.min(switch_row);
        self.color = color;
        self.depth = depth;
        self.shape = match narrow {
            Some(row) => {
                self.narrow = row;
                Shape::NarrowTriangle
            }
            None => Shape::Triangle,
        };
        let (left, right) = if short_left {
            (short, long)
        } else {
            (long, short)
        };
        self.pair[0] = left;
        self.pair[1] = right;
        self.pair_len = 2;
        self.short_side = if short_left { 0 } else { 1 };
        self.extra = NO_EDGE;
        self.lower = lower;
    }

    /// Makes this entry a small triangle entering the APT: its depth
    /// set-up (a triangle's in range) and its coverage. Written field by
    /// field, as [`Self::set_triangle`].
    #[inline]
    pub(crate) fn set_small(
        &mut self,
        (position, key, end_row): (u32, u32, u16),
        color: C,
        (depth, narrow): (SpanDepth, Option<NarrowRow>),
        coverage: SmallCoverage,
    ) {
        self.position = position;
        self.key = key;
        self.end_row = end_row;
        self.color = color;
        self.depth = depth;
        if let Some(row) = narrow {
            self.narrow = row;
        }
        self.shape = Shape::Small;
        self.lower = coverage.to_words();
    }

    /// Whether this is a small triangle ([`Self::set_small`]).
    #[inline]
    pub(crate) fn is_small(&self) -> bool {
        self.shape == Shape::Small
    }

    /// A triangle's lower short edge taking the place of the upper one.
    #[inline]
    pub(crate) fn switch_short_edge(&mut self, lower: ActiveEdge) {
        self.pair[usize::from(self.short_side)] = lower;
    }

    /// Whether this is a triangle (two ordered edges, or a small one with
    /// none; no pool).
    #[inline]
    pub(crate) fn is_triangle(&self) -> bool {
        self.shape != Shape::Polygon
    }

    /// Whether this is a triangle stepped by its two edges whose depth
    /// steps its plane's value (not a narrow row).
    #[inline]
    pub(crate) fn is_plane_stepped_triangle(&self) -> bool {
        self.shape == Shape::Triangle
    }

    /// Whether this is a triangle whose depth is its `narrow` row.
    #[inline]
    pub(crate) fn is_narrow_triangle(&self) -> bool {
        self.shape == Shape::NarrowTriangle
    }

    /// A triangle's span on this row: from its left edge's crossing to its
    /// right edge's.
    #[inline]
    pub(crate) fn triangle_span(&self) -> (i32, i32) {
        (self.pair[0].x, self.pair[1].x)
    }

    /// Steps a triangle's two edges to `next_row`, with no test of their
    /// own end rows: while the triangle goes on (it ends at its `end_row`,
    /// and is not stepped then), an edge ends before it only at the switch
    /// row, where
    /// [`switch_triangle`](crate::raster::stepping::switch_triangle)
    /// replaces the upper short edge with the lower one right after this
    /// step. The long edge and the lower short edge end with the triangle,
    /// and the upper short edge does too when there is no switch (the
    /// middle corner lies at or below the last row). The one extra step of
    /// an edge that has ended stays in range: inside the guard band
    /// `|step| < 2^22` pixels and `|x| <= 2^13 + 1`, so the crossing stays
    /// below 2^23 in magnitude, and it is never used.
    #[inline]
    pub(crate) fn advance_triangle(&mut self, next_row: u16) {
        for edge in &mut self.pair {
            debug_assert!(
                edge.end_row > next_row || self.switch_row == next_row,
                "an edge ends at row {next_row} before its triangle"
            );
            edge.advance();
        }
    }

    /// Adds an active edge: into the pair if it has room, else the pool.
    pub(crate) fn add_edge(&mut self, edge: ActiveEdge, pool: &mut EdgePool<'_>) -> Result<(), ()> {
        if usize::from(self.pair_len) < self.pair.len() {
            self.pair[usize::from(self.pair_len)] = edge;
            self.pair_len += 1;
            pool.live += 1;
        } else {
            self.extra = pool.insert_sorted(edge, self.extra)?;
        }
        Ok(())
    }

    /// Calls `fill(left, right)` for each span of this row: the crossings
    /// in increasing order, paired even-odd. `left` and `right` are the
    /// first pixel inside and the first pixel after the span.
    #[inline]
    pub(crate) fn for_each_span(&self, pool: &EdgePool<'_>, mut fill: impl FnMut(i32, i32)) {
        let (a, b) = (self.pair[0].x, self.pair[1].x);
        if self.pair_len == 2 && self.extra == NO_EDGE {
            fill(a.min(b), a.max(b));
            return;
        }
        // Merge the (sorted) inline pair with the sorted pool list.
        let mut inline = match self.pair_len {
            2 => [a.min(b), a.max(b)],
            _ => [a, a],
        };
        let mut inline_left = usize::from(self.pair_len);
        let mut pending: Option<i32> = None;
        let mut index = self.extra;
        let edges = pool.edges.as_slice();
        loop {
            let pooled = edges.get(index as usize).map(|e| e.x);
            let x = match (inline_left, pooled) {
                (0, None) => break,
                (0, Some(x)) => {
                    index = edges[index as usize].next;
                    x
                }
                (_, Some(x)) if x < inline[0] => {
                    index = edges[index as usize].next;
                    x
                }
                _ => {
                    let x = inline[0];
                    inline[0] = inline[1];
                    inline_left -= 1;
                    x
                }
            };
            match pending.take() {
                Some(left) => fill(left, x),
                None => pending = Some(x),
            }
        }
    }

    /// Steps every edge to `next_row`, dropping those that ended there.
    /// Where an edge of the pair ended, the pool's first edge takes its
    /// place: so a polygon holds in the pool only the edges beyond two
    /// that cover the row, whatever its history, and a band that starts
    /// inside a polygon (activating it with the edges crossing its first
    /// row) pools no more than one scan over the whole frame does on that
    /// row ([`FrameStats::peak_pooled_edges`](crate::raster::FrameStats::peak_pooled_edges)
    /// covers every band).
    #[inline]
    pub(crate) fn advance_edges(&mut self, next_row: u16, pool: &mut EdgePool<'_>) {
        let mut k = 0;
        while k < usize::from(self.pair_len) {
            if self.pair[k].end_row > next_row {
                self.pair[k].advance();
                k += 1;
            } else {
                self.pair_len -= 1;
                self.pair[k] = self.pair[usize::from(self.pair_len)];
                pool.live -= 1;
            }
        }
        if self.extra != NO_EDGE {
            let head = pool.advance_list(self.extra, next_row);
            self.extra = pool.sort_list(head);
            while usize::from(self.pair_len) < self.pair.len() {
                let Some((edge, rest)) = pool.pop_front(self.extra) else {
                    break;
                };
                self.extra = rest;
                self.pair[usize::from(self.pair_len)] = edge;
                self.pair_len += 1;
            }
        }
    }
}

/// Active edges beyond each polygon's pair: a fixed pool with a free list.
#[derive(Debug)]
pub(crate) struct EdgePool<'a> {
    edges: Slots<'a, ActiveEdge>,
    free: u32,
    /// Active edges in all polygons, pairs included.
    pub live: u32,
    /// Active edges held in the pool.
    pub pooled: u32,
}

impl<'a> EdgePool<'a> {
    /// An empty pool over `edges`.
    pub fn new(edges: Slots<'a, ActiveEdge>) -> Self {
        let mut edges = edges;
        edges.truncate(0);
        Self {
            edges,
            free: NO_EDGE,
            live: 0,
            pooled: 0,
        }
    }

    /// Empties the pool: every list in it is forgotten.
    #[cfg(feature = "zbuffer")]
    pub fn reset(&mut self) {
        self.edges.truncate(0);
        self.free = NO_EDGE;
        self.live = 0;
        self.pooled = 0;
    }

    /// Stores `edge` in the list starting at `head`, keeping it sorted by
    /// `x`; returns the new head. `Err` when more edges are active than the
    /// capacity.
    fn insert_sorted(&mut self, edge: ActiveEdge, head: u32) -> Result<u32, ()> {
        if self.pooled as usize >= self.edges.capacity() {
            return Err(());
        }
        let index = if self.free != NO_EDGE {
            let index = self.free;
            let edges = self.edges.as_mut_slice();
            self.free = edges[index as usize].next;
            edges[index as usize] = edge;
            index
        } else {
            let index = self.edges.len() as u32;
            self.edges.push(edge).map_err(|_| ())?;
            index
        };
        self.live += 1;
        self.pooled += 1;
        Ok(self.link_sorted(index, head))
    }

    /// Links entry `index` into the sorted list starting at `head`; returns
    /// the new head.
    fn link_sorted(&mut self, index: u32, head: u32) -> u32 {
        link_sorted(self.edges.as_mut_slice(), index, head)
    }

    /// Re-sorts the list starting at `head` by `x` after a step (insertion
    /// sort: linear when the order did not change, as is usual); returns
    /// the new head.
    fn sort_list(&mut self, head: u32) -> u32 {
        let edges = self.edges.as_mut_slice();
        let (mut sorted, mut tail, mut index) = (NO_EDGE, NO_EDGE, head);
        while let Some(edge) = edges.get(index as usize) {
            let next = edge.next;
            let x = edge.x;
            match edges.get(tail as usize) {
                Some(last) if last.x > x => sorted = link_sorted(edges, index, sorted),
                Some(_) => {
                    edges[tail as usize].next = index;
                    edges[index as usize].next = NO_EDGE;
                    tail = index;
                }
                None => {
                    edges[index as usize].next = NO_EDGE;
                    (sorted, tail) = (index, index);
                }
            }
            index = next;
        }
        sorted
    }

    /// Takes the first edge of the list starting at `head` out of the pool
    /// (it stays live, held by its polygon's pair); returns it and the new
    /// head, or `None` for an empty list.
    fn pop_front(&mut self, head: u32) -> Option<(ActiveEdge, u32)> {
        let edges = self.edges.as_mut_slice();
        let entry = edges.get_mut(head as usize)?;
        let (edge, next) = (*entry, entry.next);
        entry.next = self.free;
        self.free = head;
        self.pooled -= 1;
        Some((edge, next))
    }

    /// Steps the list starting at `head` to `next_row`, freeing edges that
    /// ended; returns the new head.
    fn advance_list(&mut self, head: u32, next_row: u16) -> u32 {
        let edges = self.edges.as_mut_slice();
        let (mut new_head, mut previous, mut index) = (head, NO_EDGE, head);
        while let Some(edge) = edges.get_mut(index as usize) {
            let next = edge.next;
            if edge.end_row > next_row {
                edge.advance();
                previous = index;
            } else {
                edge.next = self.free;
                self.free = index;
                self.live -= 1;
                self.pooled -= 1;
                match edges.get_mut(previous as usize) {
                    Some(p) => p.next = next,
                    None => new_head = next,
                }
            }
            index = next;
        }
        new_head
    }
}

/// Links entry `index` into the sorted list starting at `head`; returns the
/// new head.
fn link_sorted(edges: &mut [ActiveEdge], index: u32, head: u32) -> u32 {
    let x = edges[index as usize].x;
    match edges.get(head as usize) {
        Some(first) if first.x < x => {}
        _ => {
            edges[index as usize].next = head;
            return index;
        }
    }
    let mut at = head;
    loop {
        let next = edges[at as usize].next;
        match edges.get(next as usize) {
            Some(e) if e.x < x => at = next,
            _ => break,
        }
    }
    edges[index as usize].next = edges[at as usize].next;
    edges[at as usize].next = index;
    head
}

#[cfg(test)]
mod tests {
    use super::*;
    use heapless::Vec;

    fn edge(x: i32) -> ActiveEdge {
        let mut e = ActiveEdge::EMPTY;
        e.x = x;
        e.end_row = 100;
        e.set_step_for_tests(0);
        e
    }

    fn spans(p: &ActivePolygon<u8>, pool: &EdgePool<'_>) -> Vec<(i32, i32), 8> {
        let mut out = Vec::new();
        p.for_each_span(pool, |l, r| out.push((l, r)).unwrap());
        out
    }

    #[test]
    fn spans_merge_the_pair_with_the_sorted_pool() {
        let (mut buf, mut len) = ([ActiveEdge::EMPTY; 16], 0);
        let mut pool = EdgePool::new(Slots::new(&mut buf, &mut len));
        let mut p = ActivePolygon::new(0, 1, 10, 0u8, SpanDepth::Exact);
        for x in [9, 2, 7, 4, 12, 0] {
            p.add_edge(edge(x), &mut pool).unwrap();
        }
        assert_eq!(spans(&p, &pool), [(0, 2), (4, 7), (9, 12)]);
        // Stepping reorders the crossings; the list is sorted again.
        let mut q = ActivePolygon::new(0, 1, 10, 0u8, SpanDepth::Exact);
        let (mut buf, mut len) = ([ActiveEdge::EMPTY; 16], 0);
        let mut pool = EdgePool::new(Slots::new(&mut buf, &mut len));
        q.add_edge(edge(5), &mut pool).unwrap();
        q.add_edge(edge(6), &mut pool).unwrap();
        for (x, step) in [(1, 10), (3, 0), (8, -10)] {
            let mut e = edge(x);
            e.set_step_for_tests(step);
            q.add_edge(e, &mut pool).unwrap();
        }
        q.advance_edges(1, &mut pool);
        // Crossings now 5, 6, 11, 3, -2: sorted -2, 3, 5, 6, 11 (odd count:
        // the last is unpaired, as a polygon's never is).
        assert_eq!(spans(&q, &pool), [(-2, 3), (5, 6)]);
    }
}
