//! The small triangles' own active table: a small triangle
//! ([`SmallCoverage`]) waiting for its next rows needs no edges, so it
//! waits in an entry of its own (48 bytes on a 64-bit host, where an
//! active polygon takes 136), walked each row in a loop of its own with
//! no test of the entry's shape. The bunny at 800x600 keeps most of its
//! active triangles here: its frame took 0.94x the time it took with them
//! in the active polygon table (`tools/bench-ab`, eleven interleaved
//! runs), Spot at 240x240 0.96x. The rows are the same, to the bit: each
//! entry holds the depth set-up the APT entry held and steps it the same
//! way (the tests compare both with the stepped edges).

use crate::raster::active::SpanDepth;
use crate::raster::depth::{DepthFormat, NarrowRow};
#[cfg(doc)]
use crate::raster::small::SMALL_TRIANGLES;
use crate::raster::small::SmallCoverage;
use crate::raster::span::RowBuffers;
use crate::raster::stats::FrameStats;

/// An entry of the small triangles' own active table (opaque: its fields
/// are the core's own): a small triangle's depth on the current row, its
/// tie-break key, its colour and its coverage from that row on.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(target_arch = "arm", allow(dead_code))] // (no small table there)
pub struct SmallActive<C> {
    /// A stepped depth's `row_value`, `dz_dx`, `dz_dy` and accumulator
    /// step; for a narrow row, its `acc`, `row_step` and `step`.
    depth: [i64; 4],
    key: u32,
    color: C,
    coverage: [u16; 2],
    /// Whether `depth` is a narrow row.
    narrow: bool,
}

impl<C: Copy> SmallActive<C> {
    /// A filler for unused slots.
    pub const fn filler(color: C) -> Self {
        Self {
            depth: [0; 4],
            key: 0,
            color,
            coverage: [0; 2],
            narrow: false,
        }
    }

    /// The entry of a small triangle: `None` for a depth set-up the small
    /// path does not take.
    #[inline(always)]
    pub(crate) fn new(
        key: u32,
        color: C,
        (depth, narrow): (SpanDepth, Option<NarrowRow>),
        coverage: SmallCoverage,
    ) -> Option<Self> {
        let (depth, narrow) = match (depth, narrow) {
            (SpanDepth::Narrow, Some(n)) => {
                let row = [n.acc, n.row_step, n.step].map(i64::from);
                ([row[0], row[1], row[2], 0], true)
            }
            (
                SpanDepth::Stepped {
                    dz_dx,
                    dz_dy,
                    row_value,
                    accumulator: Some(step),
                },
                None,
            ) => ([row_value, dz_dx, dz_dy, step], false),
            _ => return None,
        };
        Some(Self {
            depth,
            key,
            color,
            coverage: coverage.to_words(),
            narrow,
        })
    }
}

/// A small triangle's depth on its current row, as a narrow row or as the
/// plane's value stepped by an accumulator: what each of its samples'
/// depths comes from.
#[derive(Clone, Copy)]
pub(crate) enum SmallRowDepth {
    /// A narrow row ([`DepthFormat::narrow_at`]).
    Narrow(NarrowRow),
    /// The plane's value at column 0 of the row, its gradient in x and the
    /// accumulator's step ([`DepthFormat::accumulator_at`]).
    Stepped {
        row_value: i64,
        dz_dx: i64,
        step: i64,
    },
}

/// Depth-tests and writes the samples `coverage` gives a small triangle on
/// this row, each with its depth from `depth`, and counts a span when it
/// covers any: the one fill of a small triangle's row, whichever table it
/// waits in.
#[inline(always)]
pub(crate) fn fill_small_row<C: Copy, D: DepthFormat>(
    rows: &mut RowBuffers<'_, C, D>,
    (coverage, key, color): (&SmallCoverage, u32, C),
    depth: SmallRowDepth,
    stats: &mut FrameStats,
) {
    let filled = match depth {
        SmallRowDepth::Narrow(row) => {
            rows.fill_lanes(coverage, key, color, |column| D::narrow_at(&row, column))
        }
        SmallRowDepth::Stepped {
            row_value,
            dz_dx,
            step,
        } => rows.fill_lanes(coverage, key, color, |column| {
            D::accumulator_at(row_value, dz_dx, step, column)
        }),
    };
    if filled {
        stats.spans += 1;
    }
}

/// The small table of one scan: its entries in use are `items[..len]`.
/// On 32-bit Arm, which draws no small triangles from masks
/// ([`SMALL_TRIANGLES`]), it holds nothing: the scan's state keeps the
/// size and layout it has without it (a larger one cost the Cortex-M0+'s
/// row loop 5,000 instructions a frame of the torus knot).
#[cfg(not(target_arch = "arm"))]
pub(crate) struct SmallTable<'a, C> {
    items: &'a mut [SmallActive<C>],
    len: usize,
}

/// See the other target's.
#[cfg(target_arch = "arm")]
pub(crate) struct SmallTable<'a, C> {
    items: core::marker::PhantomData<&'a mut [SmallActive<C>]>,
}

#[cfg(target_arch = "arm")]
impl<'a, C: Copy> SmallTable<'a, C> {
    /// An empty table (`items` unused).
    pub fn new(_items: &'a mut [SmallActive<C>]) -> Self {
        Self {
            items: core::marker::PhantomData,
        }
    }

    /// Entries in use: none.
    pub fn len(&self) -> usize {
        0
    }

    /// Adds nothing.
    pub fn push(&mut self, _entry: SmallActive<C>) -> bool {
        false
    }

    /// Nothing to fill.
    pub fn scan_row<D: DepthFormat>(
        &mut self,
        _rows: &mut RowBuffers<'_, C, D>,
        _stats: &mut FrameStats,
    ) {
    }
}

#[cfg(not(target_arch = "arm"))]
impl<'a, C: Copy> SmallTable<'a, C> {
    /// An empty table over `items`.
    pub fn new(items: &'a mut [SmallActive<C>]) -> Self {
        Self { items, len: 0 }
    }

    /// Entries in use.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Adds an entry; `false` (nothing added) when the table is full.
    #[inline(always)]
    pub fn push(&mut self, entry: SmallActive<C>) -> bool {
        match self.items.get_mut(self.len) {
            Some(slot) => {
                *slot = entry;
                self.len += 1;
                true
            }
            None => false,
        }
    }

    /// Fills every entry's samples on this row, then steps each to the
    /// next: those that cover no later row leave (the last entry takes
    /// the place of one that leaves; order does not matter, ties being
    /// broken by key).
    #[inline(never)]
    pub fn scan_row<D: DepthFormat>(
        &mut self,
        rows: &mut RowBuffers<'_, C, D>,
        stats: &mut FrameStats,
    ) {
        let end = self.len.min(self.items.len());
        let items = &mut self.items[..end];
        let mut len = items.len();
        let mut index = 0;
        while index < len {
            let entry = &mut items[index];
            let mut coverage = SmallCoverage::from_words(entry.coverage);
            let depth = entry.depth;
            let narrow = D::NARROW && entry.narrow;
            let row_depth = if narrow {
                SmallRowDepth::Narrow(NarrowRow {
                    acc: depth[0] as i32,
                    row_step: depth[1] as i32,
                    step: depth[2] as i32,
                })
            } else {
                SmallRowDepth::Stepped {
                    row_value: depth[0],
                    dz_dx: depth[1],
                    step: depth[3],
                }
            };
            fill_small_row(rows, (&coverage, entry.key, entry.color), row_depth, stats);
            if coverage.is_last_row() {
                len -= 1;
                items[index] = items[len];
                continue;
            }
            coverage.next_row();
            entry.coverage = coverage.to_words();
            // The next row's: a narrow row's accumulator plus its row step
            // (modulo 2^32), or the plane's value plus `dz_dy`.
            entry.depth[0] = if narrow {
                i64::from((depth[0] as i32).wrapping_add(depth[1] as i32))
            } else {
                depth[0] + depth[2]
            };
            index += 1;
        }
        self.len = len;
    }
}
