//! The painter's algorithm: sort the polygons far to near, reorder pairs
//! the depth sort gets wrong with Newell's cheap tests, then draw them in
//! that order, each covering what was drawn before, with no depth buffer.
//!
//! It is expected to fail where no drawing order is right: cyclic overlap
//! (three polygons each in front of the next) and interpenetration (two
//! polygons crossing each other). Newell's method splits polygons there;
//! this one does not, so the catalogue and the charts show how often the
//! order is wrong.
//!
//! For each polygon `P`, in order of its farthest depth, it looks at the
//! polygons after it whose depth range overlaps `P`'s (at most
//! [`NEWELL_WINDOW`] of them). `P` may be drawn before `Q` when their
//! screen boxes are apart in x or in y, when every corner of `P` lies
//! behind `Q`'s plane, or when every corner of `Q` lies in front of `P`'s
//! plane; else `Q` moves before `P` (once: a second move means a cycle,
//! and the order stays as it is).
//!
//! The drawing itself is the core's band method with no depth test
//! ([`zline::zbuffer`]), so the fill rule is the core's.

use std::vec::Vec;

use zline::Prepared;

/// Most later polygons each polygon is compared with.
pub const NEWELL_WINDOW: usize = 64;

/// Counts of one ordering.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PainterStats {
    /// Pairs compared.
    pub comparisons: u64,
    /// Polygons moved before another.
    pub moves: u64,
    /// Pairs left in an order the tests could not confirm (a cycle).
    pub unresolved: u64,
}

/// What the ordering knows of one polygon.
#[derive(Debug, Clone, Copy)]
struct Extent {
    position: u32,
    z_min: f64,
    z_max: f64,
    x: (f64, f64),
    y: (f64, f64),
    /// Screen-space plane `z = z0 + gx·(x - x0) + gy·(y - y0)`, when it has
    /// one.
    plane: Option<(f64, f64, f64, f64, f64)>,
}

impl Extent {
    fn plane_depth(&self, x: f64, y: f64) -> Option<f64> {
        self.plane
            .map(|(x0, y0, z0, gx, gy)| z0 + gx * (x - x0) + gy * (y - y0))
    }
}

/// The drawing order (positions in `tables`), far to near, and its counts.
pub fn painter_order<C: Copy>(tables: &Prepared<'_, C>) -> (Vec<u32>, PainterStats) {
    let mut stats = PainterStats::default();
    let polygons: Vec<_> = tables.polygons().collect();
    let corners_of = |position: usize| {
        polygons[position]
            .corners()
            .map(|v| (f64::from(v.x), f64::from(v.y), f64::from(v.z)))
    };
    let mut extents: Vec<Extent> = (0..polygons.len())
        .map(|position| {
            let mut e = Extent {
                position: position as u32,
                z_min: f64::INFINITY,
                z_max: f64::NEG_INFINITY,
                x: (f64::INFINITY, f64::NEG_INFINITY),
                y: (f64::INFINITY, f64::NEG_INFINITY),
                plane: None,
            };
            let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
            let points: Vec<(f64, f64, f64)> = corners_of(position).collect();
            for (k, &(x, y, z)) in points.iter().enumerate() {
                e.z_min = e.z_min.min(z);
                e.z_max = e.z_max.max(z);
                e.x = (e.x.0.min(x), e.x.1.max(x));
                e.y = (e.y.0.min(y), e.y.1.max(y));
                let (qx, qy, qz) = points[(k + 1) % points.len()];
                a += (y - qy) * (z + qz);
                b += (z - qz) * (x + qx);
                c += (x - qx) * (y + qy);
            }
            if c != 0.0 {
                let (x0, y0, z0) = points[0];
                e.plane = Some((x0, y0, z0, -a / c, -b / c));
            }
            e
        })
        .collect();
    // Far to near: the largest farthest depth first (larger is farther).
    extents.sort_by(|p, q| q.z_max.total_cmp(&p.z_max));
    let corners = |e: &Extent| corners_of(e.position as usize).collect::<Vec<_>>();
    // Relative tolerance of the plane tests, in depth steps.
    const SLACK: f64 = 0.5;
    let mut moved = std::vec![false; polygons.len()];
    let mut i = 0;
    while i < extents.len() {
        let p = extents[i];
        let mut swapped = false;
        let end = (i + 1 + NEWELL_WINDOW).min(extents.len());
        for j in i + 1..end {
            let q = extents[j];
            if q.z_max <= p.z_min {
                break; // Depth ranges apart: sorted, so all later ones too.
            }
            stats.comparisons += 1;
            let apart = p.x.1 <= q.x.0 || q.x.1 <= p.x.0 || p.y.1 <= q.y.0 || q.y.1 <= p.y.0;
            let p_behind_q = corners(&p)
                .iter()
                .all(|&(x, y, z)| q.plane_depth(x, y).is_some_and(|d| z >= d - SLACK));
            let q_before_p = || {
                corners(&q)
                    .iter()
                    .all(|&(x, y, z)| p.plane_depth(x, y).is_some_and(|d| z <= d + SLACK))
            };
            if apart || p_behind_q || q_before_p() {
                continue;
            }
            if moved[q.position as usize] {
                stats.unresolved += 1;
                continue;
            }
            moved[q.position as usize] = true;
            stats.moves += 1;
            let q = extents.remove(j);
            extents.insert(i, q);
            swapped = true;
            break;
        }
        if !swapped {
            i += 1;
        }
    }
    (extents.iter().map(|e| e.position).collect(), stats)
}
