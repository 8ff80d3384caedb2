//! The active tables: the active polygon table (APT), whose entries hold
//! their left/right edge pair inline, and a pool of further active edges
//! for polygons that cross a row more than twice (concave ones).
//!
//! A polygon's pooled edges form a list kept sorted by crossing, so its
//! spans come out of a merge of the inline pair and the list: no buffer
//! per polygon, whatever its number of corners.

use heapless::Vec;

use super::edge::ActiveEdge;

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
    },
    /// Edge-on polygon: its plane is evaluated exactly at each pixel.
    Exact,
}

/// Active-polygon-table entry.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ActivePolygon<C> {
    /// Position in the sorted polygon table: the APT stays sorted by it.
    pub position: u32,
    /// One past the polygon's last row; on and after it the entry is dead
    /// and waits for the next compaction.
    pub end_row: u16,
    pub color: C,
    pub depth: SpanDepth,
    /// The edge pair: up to two active edges held inline.
    pair: [ActiveEdge; 2],
    pair_len: u8,
    /// Further active edges: a list in the [`EdgePool`], sorted by `x`.
    extra: u32,
}

impl<C: Copy> ActivePolygon<C> {
    /// A polygon entering the APT, with no active edges yet.
    pub fn new(position: u32, end_row: u16, color: C, depth: SpanDepth) -> Self {
        Self {
            position,
            end_row,
            color,
            depth,
            pair: [ActiveEdge::EMPTY; 2],
            pair_len: 0,
            extra: NO_EDGE,
        }
    }

    /// Adds an active edge: into the pair if it has room, else the pool.
    pub fn add_edge<const AE: usize>(
        &mut self,
        edge: ActiveEdge,
        pool: &mut EdgePool<AE>,
    ) -> Result<(), ()> {
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
    pub fn for_each_span<const AE: usize>(
        &self,
        pool: &EdgePool<AE>,
        mut fill: impl FnMut(i32, i32),
    ) {
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
        loop {
            let pooled = pool.edges.get(index as usize).map(|e| e.x);
            let x = match (inline_left, pooled) {
                (0, None) => break,
                (0, Some(x)) => {
                    index = pool.edges[index as usize].next;
                    x
                }
                (_, Some(x)) if x < inline[0] => {
                    index = pool.edges[index as usize].next;
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
    pub fn advance_edges<const AE: usize>(&mut self, next_row: u16, pool: &mut EdgePool<AE>) {
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
        }
    }
}

/// Active edges beyond each polygon's pair: a fixed pool with a free list.
#[derive(Debug)]
pub(crate) struct EdgePool<const AE: usize> {
    edges: Vec<ActiveEdge, AE>,
    free: u32,
    /// Active edges in all polygons, pairs included.
    pub live: u32,
    /// Active edges held in the pool.
    pub pooled: u32,
}

impl<const AE: usize> EdgePool<AE> {
    /// An empty pool.
    pub const fn new() -> Self {
        Self {
            edges: Vec::new(),
            free: NO_EDGE,
            live: 0,
            pooled: 0,
        }
    }

    /// Forgets every edge.
    pub fn clear(&mut self) {
        self.edges.clear();
        self.free = NO_EDGE;
        self.live = 0;
        self.pooled = 0;
    }

    /// Stores `edge` in the list starting at `head`, keeping it sorted by
    /// `x`; returns the new head. `Err` when more edges are active than the
    /// capacity.
    fn insert_sorted(&mut self, edge: ActiveEdge, head: u32) -> Result<u32, ()> {
        if self.pooled as usize >= AE {
            return Err(());
        }
        let index = if self.free != NO_EDGE {
            let index = self.free;
            self.free = self.edges[index as usize].next;
            self.edges[index as usize] = edge;
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
        let x = self.edges[index as usize].x;
        match self.edges.get(head as usize) {
            Some(first) if first.x < x => {}
            _ => {
                self.edges[index as usize].next = head;
                return index;
            }
        }
        let mut at = head;
        loop {
            let next = self.edges[at as usize].next;
            match self.edges.get(next as usize) {
                Some(e) if e.x < x => at = next,
                _ => break,
            }
        }
        self.edges[index as usize].next = self.edges[at as usize].next;
        self.edges[at as usize].next = index;
        head
    }

    /// Re-sorts the list starting at `head` by `x` after a step (insertion
    /// sort: linear when the order did not change, as is usual); returns
    /// the new head.
    fn sort_list(&mut self, head: u32) -> u32 {
        let (mut sorted, mut tail, mut index) = (NO_EDGE, NO_EDGE, head);
        while let Some(edge) = self.edges.get(index as usize) {
            let next = edge.next;
            let x = edge.x;
            match self.edges.get(tail as usize) {
                Some(last) if last.x > x => sorted = self.link_sorted(index, sorted),
                Some(_) => {
                    self.edges[tail as usize].next = index;
                    self.edges[index as usize].next = NO_EDGE;
                    tail = index;
                }
                None => {
                    self.edges[index as usize].next = NO_EDGE;
                    (sorted, tail) = (index, index);
                }
            }
            index = next;
        }
        sorted
    }

    /// Steps the list starting at `head` to `next_row`, freeing edges that
    /// ended; returns the new head.
    fn advance_list(&mut self, head: u32, next_row: u16) -> u32 {
        let (mut new_head, mut previous, mut index) = (head, NO_EDGE, head);
        while let Some(edge) = self.edges.get_mut(index as usize) {
            let next = edge.next;
            if edge.end_row > next_row {
                edge.advance();
                previous = index;
            } else {
                edge.next = self.free;
                self.free = index;
                self.live -= 1;
                self.pooled -= 1;
                match self.edges.get_mut(previous as usize) {
                    Some(p) => p.next = next,
                    None => new_head = next,
                }
            }
            index = next;
        }
        new_head
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge(x: i32) -> ActiveEdge {
        let mut e = ActiveEdge::EMPTY;
        e.x = x;
        e.end_row = 100;
        e.set_step_for_tests(0);
        e
    }

    fn spans(p: &ActivePolygon<u8>, pool: &EdgePool<16>) -> Vec<(i32, i32), 8> {
        let mut out = Vec::new();
        p.for_each_span(pool, |l, r| out.push((l, r)).unwrap());
        out
    }

    #[test]
    fn spans_merge_the_pair_with_the_sorted_pool() {
        let mut pool = EdgePool::<16>::new();
        let mut p = ActivePolygon::new(0, 10, 0u8, SpanDepth::Exact);
        for x in [9, 2, 7, 4, 12, 0] {
            p.add_edge(edge(x), &mut pool).unwrap();
        }
        assert_eq!(spans(&p, &pool), [(0, 2), (4, 7), (9, 12)]);
        // Stepping reorders the crossings; the list is sorted again.
        let mut q = ActivePolygon::new(0, 10, 0u8, SpanDepth::Exact);
        let mut pool = EdgePool::<16>::new();
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
