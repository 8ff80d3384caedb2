//! The interval (span) scanline: visibility without any depth buffer.
//!
//! On each row, every active polygon contributes its spans (its edge
//! crossings paired even-odd, by the core's fill rule). The span ends cut
//! the row into intervals; in each interval the polygons covering it are
//! compared by their planes (in the core's plane units, set up as the core
//! sets them up) at the interval's two ends. The lower envelope of planes
//! is concave, so a polygon nearest at both ends is nearest all the way;
//! otherwise the interval is split in two, recursively, down to the pixel
//! where two polygons cross. On exactly equal depth the polygon added
//! first wins, as in the core.
//!
//! It keeps one row of colour and, per row, the list of spans: no depth is
//! stored. (The depth row it sends with each row is the winning plane
//! value, quantised, for comparison only.) So, unlike the core, it draws a
//! surface lying on the far plane (depth 1, a cleared depth row's value),
//! which the core's strict test hides.

use std::vec::Vec;

use zline::DepthFormat;
use zline::Prepared;
use zline::RowSink;
use zline::inspect::{RowPlane, edge_crossing};

/// One polygon's span on the current row, with its plane on that row.
#[derive(Debug, Clone, Copy)]
struct Segment {
    start: i32,
    end: i32,
    key: u32,
    position: usize,
    plane: RowPlane,
}

/// Counts and sizes of one [`render_intervals`] frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct IntervalStats {
    /// Spans gathered, summed over the rows.
    pub spans: u64,
    /// Intervals resolved, summed over the rows.
    pub intervals: u64,
    /// Most spans on one row.
    pub peak_spans: usize,
    /// Most polygons active on one row.
    pub peak_active: usize,
}

impl IntervalStats {
    /// Bytes the method needs beyond the tables: the peak span list, the
    /// active list and a row of colour.
    pub fn working_bytes<C>(&self, width: usize) -> usize {
        self.peak_spans * core::mem::size_of::<Segment>()
            + self.peak_active * core::mem::size_of::<(usize, Option<RowPlane>)>()
            + width * core::mem::size_of::<C>()
    }
}

/// Draws prepared tables (sorted by first row) row by row with the interval
/// method, clearing to `background`, and sends each row to `sink`.
pub fn render_intervals<C: Copy, D: DepthFormat, K: RowSink<C, D::Value>>(
    tables: &Prepared<'_, C>,
    background: C,
    sink: &mut K,
) -> Result<IntervalStats, zline::RenderError<K::Error>> {
    let (width, height) = (i32::from(tables.width()), tables.height());
    let polygons: Vec<_> = tables.polygons().collect();
    let mut stats = IntervalStats::default();
    let mut active: Vec<(usize, Option<RowPlane>)> = Vec::new();
    let mut next = 0usize;
    let mut segments: Vec<Segment> = Vec::new();
    let mut crossings: Vec<i32> = Vec::new();
    let mut open: Vec<usize> = Vec::new();
    let mut colors = std::vec![background; width as usize];
    let mut depths = std::vec![D::CLEAR; width as usize];
    for row in 0..height {
        active.retain(|&(p, _)| polygons[p].rows().end > row);
        while let Some(polygon) = polygons.get(next).filter(|p| p.rows().start <= row) {
            if polygon.rows().end > row {
                // The plane as the core sets it up, set up again on each
                // row below.
                active.push((next, None));
            }
            next += 1;
        }
        stats.peak_active = stats.peak_active.max(active.len());
        segments.clear();
        for entry in &mut active {
            let position = entry.0;
            let polygon = &polygons[position];
            entry.1 = polygon.row_plane(row);
            let Some(plane) = entry.1 else {
                continue;
            };
            crossings.clear();
            polygon.for_each_edge(|top, bottom| {
                if let Some(x) = edge_crossing(top, bottom, row) {
                    crossings.push(x);
                }
            });
            crossings.sort_unstable();
            for pair in crossings.chunks_exact(2) {
                let (start, end) = (pair[0].max(0), pair[1].min(width));
                if start < end {
                    segments.push(Segment {
                        start,
                        end,
                        key: polygon.id() + 1,
                        position,
                        plane,
                    });
                }
            }
        }
        stats.spans += segments.len() as u64;
        stats.peak_spans = stats.peak_spans.max(segments.len());
        colors.fill(background);
        depths.fill(D::CLEAR);
        // The intervals between consecutive span ends, swept left to
        // right: `open` holds the spans covering the current interval
        // (every span end is a crossing, so a span open at an interval's
        // left end covers all of it).
        crossings.clear();
        crossings.extend(segments.iter().flat_map(|s| [s.start, s.end]));
        crossings.sort_unstable();
        crossings.dedup();
        segments.sort_unstable_by_key(|s| s.start);
        open.clear();
        let mut entering = 0usize;
        for pair in crossings.windows(2) {
            let (left, right) = (pair[0], pair[1]);
            open.retain(|&k| segments[k].end > left);
            while let Some(s) = segments.get(entering).filter(|s| s.start <= left) {
                if s.end > left {
                    open.push(entering);
                }
                entering += 1;
            }
            if open.is_empty() {
                continue;
            }
            stats.intervals += 1;
            // The nearest covering span at pixel x: smallest plane value,
            // then smallest key.
            let nearest = |x: i32| -> Option<(i64, u32, usize)> {
                open.iter()
                    .map(|&k| (segments[k].plane.value(x, row), segments[k].key, k))
                    .min_by_key(|&(value, key, _)| (value, key))
            };
            let value_of = |k: usize, x: i32| segments[k].plane.value(x, row);
            resolve(left, right, &nearest, &value_of, &mut |x, k, value| {
                colors[x as usize] = polygons[segments[k].position].color();
                depths[x as usize] = D::quantize(value);
            });
        }
        sink.write_row(row, &colors, &depths)
            .map_err(zline::RenderError::Sink)?;
    }
    Ok(stats)
}

/// Gives each pixel of `[left, right)` its nearest span, splitting the
/// interval where the nearest at its two ends differ.
fn resolve(
    left: i32,
    right: i32,
    nearest: &dyn Fn(i32) -> Option<(i64, u32, usize)>,
    value_of: &dyn Fn(usize, i32) -> i64,
    paint: &mut dyn FnMut(i32, usize, i64),
) {
    let (Some(a), Some(b)) = (nearest(left), nearest(right - 1)) else {
        return;
    };
    if a.2 == b.2 {
        // One polygon all the way: the lower envelope of planes is
        // concave, so a plane on it at both ends is on it in between.
        for x in left..right {
            paint(x, a.2, value_of(a.2, x));
        }
        return;
    }
    let mid = left + (right - left) / 2;
    resolve(left, mid, nearest, value_of, paint);
    resolve(mid, right, nearest, value_of, paint);
}
