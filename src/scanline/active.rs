//! The active tables: the active polygon table (APT), whose entries hold
//! their left/right edge pair inline, and a pool of further active edges
//! for polygons that cross a row more than twice (concave ones).

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
    /// Further active edges, a list in the [`EdgePool`].
    extra: u32,
}

/// Crossings of one polygon with the current row.
pub(crate) enum Crossings<const N: usize> {
    /// The common case: one left/right pair.
    Pair(i32, i32),
    /// Any other number, sorted; pair them even-odd.
    Sorted(Vec<i32, N>),
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
            Ok(())
        } else {
            self.extra = pool.insert(edge, self.extra)?;
            Ok(())
        }
    }

    /// This row's crossings.
    pub fn crossings<const N: usize, const AE: usize>(&self, pool: &EdgePool<AE>) -> Crossings<N> {
        if self.pair_len == 2 && self.extra == NO_EDGE {
            let (a, b) = (self.pair[0].x, self.pair[1].x);
            return Crossings::Pair(a.min(b), a.max(b));
        }
        let mut xs: Vec<i32, N> = self.pair[..usize::from(self.pair_len)]
            .iter()
            .map(|e| e.x)
            .collect();
        let mut index = self.extra;
        while let Some(edge) = pool.edges.get(index as usize) {
            // A polygon of at most N corners has at most N active edges.
            if xs.push(edge.x).is_err() {
                break;
            }
            index = edge.next;
        }
        xs.sort_unstable();
        Crossings::Sorted(xs)
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
            self.extra = pool.advance_list(self.extra, next_row);
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

    /// Stores `edge` at the head of the list starting at `head`; returns
    /// the new head. `Err` when more edges are active than the capacity.
    fn insert(&mut self, mut edge: ActiveEdge, head: u32) -> Result<u32, ()> {
        if self.pooled as usize >= AE {
            return Err(());
        }
        edge.next = head;
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
        Ok(index)
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
