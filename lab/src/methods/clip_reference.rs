//! An independent reference for the front end's clipping: a face's
//! corners transformed, clipped to the near, far and clip-band planes and
//! projected in double-double arithmetic (about 106 bits, twice `f64`'s
//! precision), written apart from [`zline::front::clip`] and
//! [`zline::front::scene`]. At the clipper's whole range
//! ([`CLIP_RANGE`](zline::CLIP_RANGE)) its own error is far
//! below what it judges (`2^-53` of the front end's).
//!
//! [`compare_face`] judges what the pipeline made of one face against it:
//! the corners' positions and depths, and which pixel samples are covered.

use std::vec::Vec;

use zline::Camera;
use zline::Mat4;
use zline::ScreenVertex;
use zline::limits::CLIP_BAND_PX;
use zline::limits::{DEPTH_ONE, SUBPIXEL_STEPS};

/// A double-double number: `hi + lo`, `|lo| <= ulp(hi) / 2`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Dd {
    hi: f64,
    lo: f64,
}

/// `a + b` exactly, as a double-double (Knuth's two-sum).
fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd {
        hi: s,
        lo: (a - (s - bb)) + (b - bb),
    }
}

/// `a + b` exactly when `|a| >= |b|`.
fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

impl Dd {
    fn new(v: f64) -> Self {
        Self { hi: v, lo: 0.0 }
    }

    fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    fn add(self, o: Self) -> Self {
        let s = two_sum(self.hi, o.hi);
        let t = two_sum(self.lo, o.lo);
        let r = quick_two_sum(s.hi, s.lo + t.hi);
        quick_two_sum(r.hi, r.lo + t.lo)
    }

    fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }

    fn sub(self, o: Self) -> Self {
        self.add(o.neg())
    }

    fn mul(self, o: Self) -> Self {
        let p = self.hi * o.hi;
        let e = self.hi.mul_add(o.hi, -p) + (self.hi * o.lo + self.lo * o.hi);
        quick_two_sum(p, e)
    }

    fn div(self, o: Self) -> Self {
        let q1 = self.hi / o.hi;
        let r = self.sub(o.mul(Self::new(q1)));
        let q2 = r.hi / o.hi;
        let r = r.sub(o.mul(Self::new(q2)));
        let q3 = r.hi / o.hi;
        quick_two_sum(q1, q2).add(Self::new(q3))
    }

    fn is_nonnegative(self) -> bool {
        self.hi > 0.0 || (self.hi == 0.0 && self.lo >= 0.0)
    }
}

type Point = [Dd; 4];

fn transform(m: &Mat4, p: Point) -> Point {
    core::array::from_fn(|i| {
        (0..4).fold(Dd::default(), |sum, k| {
            sum.add(Dd::new(f64::from(m.m[i][k])).mul(p[k]))
        })
    })
}

fn dot(q: [f64; 4], p: Point) -> Dd {
    (0..4).fold(Dd::default(), |sum, k| sum.add(Dd::new(q[k]).mul(p[k])))
}

/// The face's corners (model space) through `model` and `camera`,
/// clipped and projected: the clipped polygon's corners on screen as
/// `[x, y, depth]`, pixels and `[0, 1]` (empty when nothing is left).
pub fn clipped_face(model: &Mat4, camera: &Camera, corners: &[[f32; 3]]) -> Vec<[f64; 3]> {
    let (width, height) = (f32::from(camera.width), f32::from(camera.height));
    // The clip band's planes, at the positions the front end puts them
    // (computed in f32 as it computes them).
    let gx = f64::from(2.0 * CLIP_BAND_PX / width - 1.0);
    let gy = f64::from(2.0 * CLIP_BAND_PX / height - 1.0);
    let planes = [
        [1.0, 0.0, 0.0, gx],
        [-1.0, 0.0, 0.0, gx],
        [0.0, 1.0, 0.0, gy],
        [0.0, -1.0, 0.0, gy],
        [0.0, 0.0, 1.0, 1.0],
        [0.0, 0.0, -1.0, 1.0],
    ];
    let mut polygon: Vec<Point> = corners
        .iter()
        .map(|p| {
            let p = [
                Dd::new(f64::from(p[0])),
                Dd::new(f64::from(p[1])),
                Dd::new(f64::from(p[2])),
                Dd::new(1.0),
            ];
            transform(
                &camera.projection,
                transform(&camera.view, transform(model, p)),
            )
        })
        .collect();
    // Sutherland and Hodgman, one plane after the other, with buffers.
    for q in planes {
        let mut out = Vec::new();
        for k in 0..polygon.len() {
            let (a, b) = (polygon[k], polygon[(k + 1) % polygon.len()]);
            let (da, db) = (dot(q, a), dot(q, b));
            if da.is_nonnegative() {
                out.push(a);
            }
            if da.is_nonnegative() != db.is_nonnegative() {
                let t = da.div(da.sub(db));
                out.push(core::array::from_fn(|i| a[i].add(b[i].sub(a[i]).mul(t))));
            }
        }
        polygon = out;
    }
    let (w2, h2) = (
        Dd::new(f64::from(width) / 2.0),
        Dd::new(f64::from(height) / 2.0),
    );
    let one = Dd::new(1.0);
    polygon
        .into_iter()
        .map(|[x, y, z, w]| {
            [
                x.div(w).add(one).mul(w2).to_f64(),
                one.sub(y.div(w)).mul(h2).to_f64(),
                z.div(w).add(one).mul(Dd::new(0.5)).to_f64(),
            ]
        })
        .collect()
}

/// The clipper's size of a face ([`CLIP_RANGE`](zline::CLIP_RANGE):
/// the largest sum of the absolute terms of a corner's transform by
/// `|projection| · |view| · |model|`), and how much its corners'
/// transforms cancel (the largest ratio of a corner's sum of terms to its
/// largest clip-space coordinate); `None` when either is not finite.
pub fn transform_terms(model: &Mat4, camera: &Camera, corners: &[[f32; 3]]) -> Option<(f64, f64)> {
    let abs = |m: &Mat4| Mat4 {
        m: m.m.map(|row| row.map(f32::abs)),
    };
    let (mut size, mut cancellation) = (0.0f64, 0.0f64);
    for p in corners {
        let point = |p: [f32; 3], abs_value: bool| {
            let f = |v: f32| Dd::new(f64::from(if abs_value { v.abs() } else { v }));
            [f(p[0]), f(p[1]), f(p[2]), Dd::new(1.0)]
        };
        let terms = transform(
            &abs(&camera.projection),
            transform(&abs(&camera.view), transform(&abs(model), point(*p, true))),
        );
        let clip = transform(
            &camera.projection,
            transform(&camera.view, transform(model, point(*p, false))),
        );
        let largest = |v: Point| v.iter().map(|c| c.to_f64().abs()).fold(0.0, f64::max);
        let (t, c) = (largest(terms), largest(clip));
        size = size.max(t);
        cancellation = cancellation.max(t / c);
    }
    (size.is_finite() && cancellation.is_finite()).then_some((size, cancellation))
}

/// How far the pipeline's polygon for one face lies from the reference's
/// ([`compare_face`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FaceError {
    /// The largest distance, in pixels, from a drawn corner to the
    /// reference's boundary (infinite when something was drawn where the
    /// reference has nothing), divided for a corner outside the frame
    /// by one plus its distance from the frame in half-frames (the larger
    /// half): a corner's precision is relative to its distance from the
    /// frame's centre.
    pub position_px: f64,
    /// The largest difference between a drawn corner's depth and the
    /// reference polygon's depth plane at the corner, beyond what the
    /// corner's distance from the reference boundary (and its rounding to
    /// the sub-pixel grid) accounts for on that plane, divided as
    /// [`Self::position_px`] is for a corner outside the frame.
    pub depth: f64,
    /// Pixel samples covered by one polygon and not the other, farther
    /// than `margin_px` from the reference's boundary.
    pub wrong_samples: usize,
}

/// Distance from `p` to the segment `a`–`b`.
fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
    (x * x + y * y).sqrt()
}

/// Distance from `p` to the boundary of `polygon` (infinite when it has
/// no corner).
fn boundary_distance(p: [f64; 2], polygon: &[[f64; 3]]) -> f64 {
    (0..polygon.len())
        .map(|k| {
            let (a, b) = (polygon[k], polygon[(k + 1) % polygon.len()]);
            segment_distance(p, [a[0], a[1]], [b[0], b[1]])
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether `p` is inside `polygon` (even-odd).
fn inside(p: [f64; 2], polygon: &[[f64; 3]]) -> bool {
    let mut odd = false;
    for k in 0..polygon.len() {
        let (a, b) = (polygon[k], polygon[(k + 1) % polygon.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if p[0] < x {
                odd = !odd;
            }
        }
    }
    odd
}

/// The depth plane through the three corners of `polygon` that span the
/// largest area: `(z at the origin, dz/dx, dz/dy)`, or `None` for a
/// polygon of (nearly) no area.
fn depth_plane(polygon: &[[f64; 3]]) -> Option<(f64, f64, f64)> {
    let n = polygon.len();
    let mut best = (0.0f64, 0, 0, 0);
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let (a, b, c) = (polygon[i], polygon[j], polygon[k]);
                let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
                if area.abs() > best.0.abs() {
                    best = (area, i, j, k);
                }
            }
        }
    }
    let (area, i, j, k) = best;
    if area.abs() < 1e-6 {
        return None;
    }
    let (a, b, c) = (polygon[i], polygon[j], polygon[k]);
    let dzdx = ((b[2] - a[2]) * (c[1] - a[1]) - (c[2] - a[2]) * (b[1] - a[1])) / area;
    let dzdy = ((c[2] - a[2]) * (b[0] - a[0]) - (b[2] - a[2]) * (c[0] - a[0])) / area;
    Some((a[2] - dzdx * a[0] - dzdy * a[1], dzdx, dzdy))
}

/// Judges `drawn` (the polygons the pipeline queued for one face, in the
/// core's units) against `reference` (the [`clipped_face`] of each
/// polygon the face is drawn as: the face, or the triangles of its fan)
/// on a `width` x `height` frame: see [`FaceError`]. A sample is covered
/// when it lies inside (even-odd) any polygon of a set; samples within
/// `margin_px` of a reference polygon's boundary are not counted. (A
/// reference corner nothing was drawn near is not counted: a sliver that
/// covers no sample is rightly left out; the samples judge what shows.)
pub fn compare_face(
    drawn: &[Vec<ScreenVertex>],
    reference: &[Vec<[f64; 3]>],
    (width, height): (u16, u16),
    margin_px: f64,
) -> FaceError {
    let step = 1.0 / f64::from(SUBPIXEL_STEPS);
    let polygons: Vec<Vec<[f64; 3]>> = drawn
        .iter()
        .map(|p| {
            p.iter()
                .map(|v| {
                    [
                        f64::from(v.x) * step,
                        f64::from(v.y) * step,
                        f64::from(v.z) / f64::from(DEPTH_ONE),
                    ]
                })
                .collect()
        })
        .collect();
    let reference: Vec<&Vec<[f64; 3]>> = reference.iter().filter(|p| p.len() >= 3).collect();
    let planes: Vec<_> = reference.iter().map(|p| depth_plane(p)).collect();
    let mut error = FaceError::default();
    for &[x, y, z] in polygons.iter().flatten() {
        // The reference polygon whose boundary is nearest to the drawn
        // corner.
        let (distance, k) = reference
            .iter()
            .enumerate()
            .map(|(k, q)| (boundary_distance([x, y], q), k))
            .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a });
        // Outside the frame, in units that grow by one per half-frame of
        // distance from it (the precision of a projected corner is
        // relative to its distance from the frame's centre).
        let outside = (-x).max(x - f64::from(width)).max(0.0);
        let outside = outside.hypot((-y).max(y - f64::from(height)).max(0.0));
        let half = f64::from(width.max(height)) / 2.0;
        let scale = 1.0 + outside / half;
        error.position_px = error.position_px.max(distance / scale);
        if let Some(Some((z0, dx, dy))) = planes.get(k) {
            // What the corner's distance from the boundary (and its
            // rounding to the grid) accounts for on the polygon's plane.
            let moved = (dx.abs() + dy.abs()) * (distance + step / 2.0);
            let off = (z - (z0 + dx * x + dy * y)).abs() - moved;
            error.depth = error.depth.max(off / scale);
        }
    }
    let margin = |p: [f64; 2]| {
        reference
            .iter()
            .map(|q| boundary_distance(p, q))
            .fold(f64::INFINITY, f64::min)
    };
    for j in 0..height {
        for i in 0..width {
            let p = [f64::from(i) + 0.5, f64::from(j) + 0.5];
            if margin(p) <= margin_px {
                continue;
            }
            let expected = reference.iter().any(|q| inside(p, q));
            let covered = polygons.iter().any(|q| inside(p, q));
            if covered != expected {
                error.wrong_samples += 1;
            }
        }
    }
    error
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_double_keeps_what_f64_loses() {
        let big = Dd::new(1e16);
        let sum = big.add(Dd::new(1.0)).sub(big);
        assert_eq!(sum.to_f64(), 1.0);
        let third = Dd::new(1.0).div(Dd::new(3.0));
        let back = third.mul(Dd::new(3.0)).sub(Dd::new(1.0));
        assert!(back.to_f64().abs() < 1e-30);
    }
}
