//! Attribute planes: a value given at each corner of a polygon (a colour
//! channel, a texture coordinate divided by `w`, `1/w` itself),
//! interpolated over the polygon as a plane in screen space, set up as its
//! depth is: Newell's plane through the corners with the value in place of
//! depth ([`Plane`]), gradients rounded once to plane units
//! (`2^-16` of a value step), and the plane's exactly rounded value at one
//! anchor pixel.
//!
//! A painted row (see [`crate::raster::paint`]) evaluates the plane at the
//! first pixel of each run of pixels its polygon won and steps it along
//! the run. Both are the same sum: the value at pixel `(x, y)` is
//! `at_origin + dx·x + dy·y` in integers, with `at_origin` the anchor's
//! value moved to pixel `(0, 0)` exactly. So it is off the exact plane by
//! at most half a plane unit for the anchor and half a unit per pixel
//! stepped from it in x and in y: `2^-17·(1 + |x - x_a| + |y - y_a|)`
//! value steps, below `2^-4` anywhere in a frame (`|x - x_a|, |y - y_a| <
//! 2^12`, the anchor being the pixel of corner 0 clamped to the frame).
//!
//! A plane whose gradient reaches [`STEEP_GRADIENT`] (the whole value
//! range within one pixel: a sliver narrower than a sub-pixel step) is not
//! stepped: each of its pixels takes the plane's exactly rounded value,
//! recomputed from the corners ([`AttributePlane::STEEP`]).
//!
//! # Ranges
//! Values are `0..=`[`VALUE_MAX`] (`2^24 - 1`), depth's own range, so every
//! bound of [`Plane`] holds as proven there (corners in the guard band):
//!
//! | quantity | bound | held in |
//! |---|---|---|
//! | gradient `dx`, `dy` (else steep) | `< 2^40` plane units per pixel | `i64` |
//! | value at the anchor (within `2^14` px of corner 0, so of a value in range) | `< 2^40 + 2^54` | `i64` |
//! | `at_origin` (anchor `< 2^12`) | `< 2^40 + 2^54 + 2^53` | `i64` |
//! | value at any pixel of the frame | `< 2^56` | `i64` |

use crate::arith::divide::Divisor;
use crate::arith::wide::mul_i64_small;
use crate::limits::{DEPTH_MAX, HALF_PIXEL, PLANE_FRAC_BITS, SUBPIXEL_BITS, SUBPIXEL_STEPS};
use crate::raster::plane::{Plane, STEEP_GRADIENT, TrianglePlane};
use crate::raster::vertex::ScreenVertex;

/// Largest attribute value a corner may have.
pub const VALUE_MAX: u32 = DEPTH_MAX;

/// Fractional bits of an attribute plane's values over a corner's value:
/// a pixel's value is `value · 2^PLANE_FRAC_BITS`.
pub const ATTRIBUTE_FRAC_BITS: u32 = PLANE_FRAC_BITS;

/// One attribute over one polygon: its value at pixel `(x, y)` is
/// `at_origin + dx·x + dy·y` in plane units ([`Self::value_at`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AttributePlane {
    /// The plane's value moved to the sample of pixel `(0, 0)` (it may lie
    /// far outside the polygon; only values at its pixels are used).
    pub at_origin: i64,
    /// Change per pixel to the right.
    pub dx: i64,
    /// Change per row down.
    pub dy: i64,
}

impl AttributePlane {
    /// The plane of value 0 everywhere.
    pub const ZERO: Self = Self {
        at_origin: 0,
        dx: 0,
        dy: 0,
    };

    /// The marker of a steep plane: never a stepped plane (its gradient
    /// would be `2^63 - 1`), it says each pixel's value is to be computed
    /// from the corners ([`exact_value_at`]).
    pub const STEEP: Self = Self {
        at_origin: 0,
        dx: i64::MAX,
        dy: 0,
    };

    /// Whether this is [`Self::STEEP`].
    #[inline(always)]
    pub fn is_steep(&self) -> bool {
        self.dx == i64::MAX
    }

    /// The value at pixel `(x, y)` in plane units (`x, y < 2^12`).
    #[inline(always)]
    pub fn value_at(&self, x: u16, y: u16) -> i64 {
        self.at_origin + mul_i64_small(self.dx, i32::from(x)) + mul_i64_small(self.dy, i32::from(y))
    }
}

/// The planes of `N` attributes over a polygon, from its corners, each
/// with its `N` values (each at most [`VALUE_MAX`]; a larger one is taken
/// as [`VALUE_MAX`]), in a frame `width` x `height`; `None` when the
/// polygon's projected area is zero. A triangle under 256 px each way
/// (and of less than `2^14` px²) takes the flat scan's triangle set-up ([`triangle_planes`]), anything
/// else Newell's ([`polygon_planes`]); both share one division set-up
/// among the `N` planes.
#[inline]
pub fn attribute_planes<const N: usize>(
    corners: impl Iterator<Item = (ScreenVertex, [u32; N])> + Clone,
    width: u16,
    height: u16,
) -> Option<[AttributePlane; N]> {
    let mut three = corners.clone();
    if let (Some(o), Some(p), Some(q), None) =
        (three.next(), three.next(), three.next(), three.next())
        && let Some(planes) = triangle_planes(o, p, q)
    {
        return Some(planes);
    }
    polygon_planes(corners, width, height)
}

/// The planes of a triangle's `N` attributes from [`TrianglePlane`]'s
/// set-up, anchored at corner `o` itself: off the exact plane by at most
/// `2^-17·(1 + |x_s - o_x| + |y_s - o_y|)` value steps at the pixel whose
/// sample is `(x_s, y_s)` (distances in pixels; under `2^-8` inside the
/// triangle). `None` when that set-up does not take the triangle (256 px
/// or more across, twice its area `2^15` px² or more, zero area, or a
/// steep plane).
pub fn triangle_planes<const N: usize>(
    (o, o_values): (ScreenVertex, [u32; N]),
    (p, p_values): (ScreenVertex, [u32; N]),
    (q, q_values): (ScreenVertex, [u32; N]),
) -> Option<[AttributePlane; N]> {
    let values = core::array::from_fn(|k| [o_values[k], p_values[k], q_values[k]]);
    let planes = TrianglePlane::with_values((o, p, q), values)?;
    Some(planes.map(|plane| AttributePlane {
        at_origin: plane.row_start(0),
        dx: plane.dz_dx,
        dy: plane.dz_dy,
    }))
}

/// Largest corner offset (sub-pixel steps, each way from corner `o`) of a
/// triangle [`modular_triangle_planes`] takes: under 64 px.
pub const MODULAR_SPAN: i32 = 1 << 14;

/// Largest corner value [`modular_triangle_planes`] takes.
pub const MODULAR_VALUE_MAX: u32 = 1 << 16;

/// Largest gradient (plane units per pixel) [`modular_triangle_planes`]
/// gives: `2^34`, 2^18 corner value steps a pixel.
pub const MODULAR_GRADIENT_MAX: u64 = 1 << 34;

/// The planes of a small triangle's `N` attributes with one reciprocal of
/// its area and no exact division: each value correct modulo `2^32` only
/// (the low words of [`AttributePlane`]'s fields; use them in wrapping
/// `u32` arithmetic), for a painter whose values stay within 32 bits. The
/// cheapest set-up, for triangles whose corners lie within
/// [`MODULAR_SPAN`] of `o` each way, values at most [`MODULAR_VALUE_MAX`]
/// and gradients below [`MODULAR_GRADIENT_MAX`]; `None` otherwise (and for
/// zero area).
///
/// Bound: each gradient is the exact one, `-a·2^24 / c`, within `e =
/// |g|·2^-28 + 1` plane units ([`Divisor::estimate_scaled`], truncated
/// toward zero), at most `2^6 + 1`; the value at corner `o`'s pixel is
/// within `e + 1/2` (the sample is at most 1/2 px each way from `o`); so the value at
/// a pixel `(x, y)` is within `1/2 + e·(1 + |x - x_o| + |y - y_o|)` plane
/// units of the exact plane, below `2^14` (`2^-2` of a corner value step)
/// at any pixel within 128 px of `o`'s, which includes every pixel whose
/// sample lies inside the triangle.
///
/// Ranges: offsets below `2^14`, values at most `2^16`: each product of a
/// cross term below `2^30`, `a` and `b` below `2^31` (i32, and `|a|` a
/// `u32` for [`Divisor::estimate_scaled`]); the anchor's correction `g·f`
/// below `2^34·2^7`.
pub fn modular_triangle_planes<const N: usize>(
    (o, o_values): (ScreenVertex, [u32; N]),
    (p, p_values): (ScreenVertex, [u32; N]),
    (q, q_values): (ScreenVertex, [u32; N]),
) -> Option<[AttributePlane; N]> {
    let small = |d: i32| d.unsigned_abs() < MODULAR_SPAN as u32;
    let (px, py, qx, qy) = (p.x - o.x, p.y - o.y, q.x - o.x, q.y - o.y);
    if !(small(px) && small(py) && small(qx) && small(qy)) {
        return None;
    }
    // Each product below 2^28: c below 2^29 in magnitude.
    let c = px * qy - py * qx;
    if c == 0 {
        return None;
    }
    let divisor = Divisor::new(c.unsigned_abs());
    // -coef·2^24 / c, truncated toward zero.
    let gradient = |coef: i32| -> Option<i64> {
        let g = divisor.estimate_scaled(coef.unsigned_abs(), SUBPIXEL_BITS + ATTRIBUTE_FRAC_BITS);
        if g >= MODULAR_GRADIENT_MAX {
            return None;
        }
        let g = g as i64;
        Some(if (coef < 0) == (c < 0) { -g } else { g })
    };
    // Corner o's pixel and its sample's offset from o (sub-pixel steps,
    // -127..=128).
    let (xo, yo) = (o.x >> SUBPIXEL_BITS, o.y >> SUBPIXEL_BITS);
    let (fx, fy) = (
        HALF_PIXEL - (o.x & (SUBPIXEL_STEPS - 1)),
        HALF_PIXEL - (o.y & (SUBPIXEL_STEPS - 1)),
    );
    let mut planes = [AttributePlane::ZERO; N];
    for (k, plane) in planes.iter_mut().enumerate() {
        let (vo, vp, vq) = (o_values[k], p_values[k], q_values[k]);
        if vo.max(vp).max(vq) > MODULAR_VALUE_MAX {
            return None;
        }
        let (dp, dq) = (vp as i32 - vo as i32, vq as i32 - vo as i32);
        let dx = gradient(dq * py - dp * qy)?;
        let dy = gradient(dp * qx - dq * px)?;
        let correction = mul_i64_small(dx, fx) + mul_i64_small(dy, fy);
        let at_pixel = (i64::from(vo) << ATTRIBUTE_FRAC_BITS)
            + ((correction + (1 << (SUBPIXEL_BITS - 1))) >> SUBPIXEL_BITS);
        // Moved to pixel (0, 0) modulo 2^32.
        let at_origin = (at_pixel as u32)
            .wrapping_sub((dx as u32).wrapping_mul(xo as u32))
            .wrapping_sub((dy as u32).wrapping_mul(yo as u32));
        *plane = AttributePlane {
            at_origin: i64::from(at_origin),
            dx,
            dy,
        };
    }
    Some(planes)
}

/// The planes of any polygon's `N` attributes from Newell's set-up
/// ([`Plane`]), anchored at corner 0's pixel clamped to the frame (see
/// the module's notes for the bound); `None` when the area is zero.
pub fn polygon_planes<const N: usize>(
    corners: impl Iterator<Item = (ScreenVertex, [u32; N])> + Clone,
    width: u16,
    height: u16,
) -> Option<[AttributePlane; N]> {
    let shape = Plane::new(corners.clone().map(|(v, _)| ScreenVertex { z: 0, ..v }))?;
    let (anchor_x, anchor_y) = anchor(&shape, width, height);
    let mut planes = [AttributePlane::default(); N];
    for (k, plane) in planes.iter_mut().enumerate() {
        let values = corners.clone().map(|(v, values)| ScreenVertex {
            z: values[k].min(VALUE_MAX),
            ..v
        });
        let attribute = shape.with_values(values);
        *plane = match attribute.gradients() {
            Some((dx, dy)) => {
                let anchor = attribute.value_at_pixel(anchor_x, anchor_y);
                AttributePlane {
                    at_origin: anchor - mul_i64_small(dx, anchor_x) - mul_i64_small(dy, anchor_y),
                    dx,
                    dy,
                }
            }
            None => AttributePlane::STEEP,
        };
    }
    Some(planes)
}

/// The pixels of the bounding box of `corners` (sub-pixel positions),
/// clamped to a frame `width` x `height`: `(x0, x1, y0, y1)`, inclusive.
pub fn pixel_box(
    corners: impl Iterator<Item = ScreenVertex>,
    width: u16,
    height: u16,
) -> (u16, u16, u16, u16) {
    let (mut x0, mut y0, mut x1, mut y1) = (i32::MAX, i32::MAX, i32::MIN, i32::MIN);
    for v in corners {
        (x0, y0, x1, y1) = (x0.min(v.x), y0.min(v.y), x1.max(v.x), y1.max(v.y));
    }
    let pixel = |s: i32, size: u16| {
        (s >> crate::limits::SUBPIXEL_BITS).clamp(0, i32::from(size.max(1)) - 1) as u16
    };
    (
        pixel(x0, width),
        pixel(x1, width),
        pixel(y0, height),
        pixel(y1, height),
    )
}

/// Whether each plane's values at the four corners of the pixel box of
/// `corners` (see [`pixel_box`]) lie in the range `within` gives it: then
/// they do over the whole box, since a plane's extremes over a box are at
/// its corners.
pub fn box_corners_within<'p>(
    planes: impl IntoIterator<Item = &'p AttributePlane>,
    within: impl Fn(&AttributePlane, usize) -> core::ops::RangeInclusive<i64>,
    corners: impl Iterator<Item = ScreenVertex>,
    (width, height): (u16, u16),
) -> bool {
    let (x0, x1, y0, y1) = pixel_box(corners, width, height);
    planes.into_iter().enumerate().all(|(k, plane)| {
        let range = within(plane, k);
        [(x0, y0), (x1, y0), (x0, y1), (x1, y1)]
            .iter()
            .all(|&(x, y)| range.contains(&plane.value_at(x, y)))
    })
}

/// The exactly rounded value of attribute `k` at pixel `(x, y)` of the
/// polygon with these corners, in plane units, for a steep plane; 0 when
/// the polygon has no area.
pub fn exact_value_at<const N: usize>(
    corners: impl Iterator<Item = (ScreenVertex, [u32; N])> + Clone,
    k: usize,
    x: u16,
    y: u16,
) -> i64 {
    let values = corners.map(|(v, values)| ScreenVertex {
        z: values.get(k).copied().unwrap_or(0).min(VALUE_MAX),
        ..v
    });
    Plane::new(values).map_or(0, |plane| plane.value_at_pixel(i32::from(x), i32::from(y)))
}

/// The pixel the planes are anchored at: corner 0's, clamped to the frame.
fn anchor(shape: &Plane, width: u16, height: u16) -> (i32, i32) {
    let origin = shape.origin();
    let clamp = |v: i32, size: u16| (v >> SUBPIXEL_BITS).clamp(0, i32::from(size.max(1)) - 1);
    (clamp(origin.x, width), clamp(origin.y, height))
}

const _: () = assert!(STEEP_GRADIENT < i64::MAX);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::{GUARD_BAND, HALF_PIXEL, SUBPIXEL_STEPS};
    use proptest::prelude::*;
    use std::vec::Vec;

    /// Largest coordinate magnitude the guard band admits.
    const G: i32 = GUARD_BAND - 1;

    /// The box check looks at each of the box's four corner pixels, with
    /// each plane's own range, and at the box clamped to the frame.
    #[test]
    fn box_corners_within_checks_each_corner_of_the_clamped_box() {
        // Corners spanning pixels 2..=5 by 1..=3 (and beyond the frame's
        // right edge at width 5, where the box stops at column 4).
        let v =
            |x: i32, y: i32| ScreenVertex::new(x * SUBPIXEL_STEPS, y * SUBPIXEL_STEPS, 0).unwrap();
        let corners = [v(2, 1), v(5, 1), v(5, 3), v(2, 3)];
        let plane = |at_origin, dx, dy| AttributePlane { at_origin, dx, dy };
        // Value x + 10·y: 12 at (2, 1), 35 at (5, 3), 34 at (4, 3).
        let p = plane(0, 1, 10);
        let check = |planes: &[AttributePlane], hi: i64, width: u16| {
            box_corners_within(planes, |_, _| 12..=hi, corners.iter().copied(), (width, 8))
        };
        assert!(check(&[p], 35, 8));
        assert!(!check(&[p], 34, 8), "the bottom-right corner is 35");
        assert!(
            check(&[p], 34, 5),
            "clamped to the frame: column 4 is the last"
        );
        // Value -x - 10·y + 47: 12 at (5, 3), 35 at (2, 1); a low corner
        // out of range fails too.
        let q = plane(47, -1, -10);
        assert!(check(&[p, q], 35, 8));
        let per_plane = |_: &AttributePlane, k: usize| if k == 0 { 12..=35 } else { 13..=35 };
        assert!(!box_corners_within(
            &[p, q],
            per_plane,
            corners.iter().copied(),
            (8, 8)
        ));
    }

    /// The exact value of the plane through three corners at `(x, y)`
    /// (sub-pixel), in plane units, as a rational `num / den`.
    fn exact(corners: &[(ScreenVertex, [u32; 1]); 3], x: i32, y: i32) -> (i128, i128) {
        let p = |k: usize| {
            let (v, [value]) = corners[k];
            (i128::from(v.x), i128::from(v.y), i128::from(value))
        };
        let ((x0, y0, z0), (x1, y1, z1), (x2, y2, z2)) = (p(0), p(1), p(2));
        let (px, py, pz, qx, qy, qz) = (x1 - x0, y1 - y0, z1 - z0, x2 - x0, y2 - y0, z2 - z0);
        let c = px * qy - py * qx;
        let a = py * qz - pz * qy;
        let b = pz * qx - px * qz;
        let (dx, dy) = (i128::from(x) - x0, i128::from(y) - y0);
        // z = z0 - (a·dx + b·dy) / c, times 2^16.
        ((z0 * c - (a * dx + b * dy)) << 16, c)
    }

    /// Checks the planes of `corners` at pixels of a `width` x `height`
    /// frame, from both set-ups: Newell's within half a plane unit per
    /// pixel from its anchor (plus one half for the anchor) of the exact
    /// value, a steep plane's exact values to the half unit; the
    /// triangle's (where it takes the triangle) within half a unit per
    /// pixel of distance from corner 0 (plus one half). Returns whether
    /// the triangle set-up took it.
    fn check(
        corners: [(ScreenVertex, [u32; 1]); 3],
        width: u16,
        height: u16,
        pixels: &[(u16, u16)],
    ) -> bool {
        let Some([plane]) = polygon_planes(corners.iter().copied(), width, height) else {
            assert_eq!(
                attribute_planes(corners.iter().copied(), width, height),
                None
            );
            return false;
        };
        let (ax, ay) = {
            let o = corners[0].0;
            let clamp = |v: i32, size: u16| (v >> SUBPIXEL_BITS).clamp(0, i32::from(size) - 1);
            (clamp(o.x, width), clamp(o.y, height))
        };
        let sample = |x: u16, y: u16| {
            (
                i32::from(x) * SUBPIXEL_STEPS + HALF_PIXEL,
                i32::from(y) * SUBPIXEL_STEPS + HALF_PIXEL,
            )
        };
        for &(x, y) in pixels {
            let (sx, sy) = sample(x, y);
            let (num, den) = exact(&corners, sx, sy);
            let got = if plane.is_steep() {
                exact_value_at(corners.iter().copied(), 0, x, y)
            } else {
                plane.value_at(x, y)
            };
            // |got - num/den| <= bound  <=>  |got·den - num| <= bound·|den|
            let steps = if plane.is_steep() {
                0
            } else {
                (i32::from(x) - ax).abs() + (i32::from(y) - ay).abs()
            };
            let error2 = (2 * i128::from(got) * den - 2 * num).abs();
            let bound2 = i128::from(1 + steps) * den.abs();
            assert!(
                error2 <= bound2,
                "{corners:?} at ({x}, {y}): {got} for {num}/{den}"
            );
        }
        let [o, p, q] = corners;
        let Some([plane]) = triangle_planes(o, p, q) else {
            return false;
        };
        assert_eq!(
            attribute_planes(corners.iter().copied(), width, height),
            Some([plane])
        );
        for &(x, y) in pixels {
            let (sx, sy) = sample(x, y);
            let (num, den) = exact(&corners, sx, sy);
            let got = plane.value_at(x, y);
            // Distances in sub-pixel steps: bound·2^8 = 2^8 + |dx| + |dy|.
            let distance = i128::from((sx - o.0.x).abs() + (sy - o.0.y).abs());
            let error = (i128::from(got) * den - num).abs() << 9;
            let bound = (256 + distance) * den.abs();
            assert!(
                error <= bound,
                "{corners:?} at ({x}, {y}): {got} for {num}/{den} (triangle set-up)"
            );
        }
        true
    }

    fn v(x: i32, y: i32) -> ScreenVertex {
        ScreenVertex { x, y, z: 0 }
    }

    /// Corners on the guard band's edges, values at both ends, a frame of
    /// the largest size: every quantity in range (overflow checks are on)
    /// and every value within its bound, at the frame's corners.
    #[test]
    fn extremes_stay_in_range() {
        let frame = crate::limits::MAX_FRAME_SIZE as u16;
        let pixels = [
            (0, 0),
            (frame - 1, 0),
            (0, frame - 1),
            (frame - 1, frame - 1),
            (17, 4000),
        ];
        let corners = [-G, 0, G];
        for &x0 in &corners {
            for &y1 in &corners {
                for values in [[0, VALUE_MAX, 0], [VALUE_MAX, 0, VALUE_MAX], [VALUE_MAX; 3]] {
                    let tri = [
                        (v(x0, -G), [values[0]]),
                        (v(G, y1), [values[1]]),
                        (v(-G, G), [values[2]]),
                    ];
                    check(tri, frame, frame, &pixels);
                }
            }
        }
    }

    /// Triangles just under the triangle set-up's limits (256 px each way,
    /// twice the area just under `2^15` px²)
    /// at the frame's corners and beyond its edges, values at both ends:
    /// taken by that set-up, in range, within its bound.
    #[test]
    fn triangle_set_up_extremes() {
        let frame = crate::limits::MAX_FRAME_SIZE as u16;
        let span = 256 * SUBPIXEL_STEPS - 1;
        let far = i32::from(frame) * SUBPIXEL_STEPS;
        for (ox, oy) in [
            (0, 0),
            (far - span, far - span),
            (-span / 2, far - span / 2),
        ] {
            for values in [[0, VALUE_MAX, 0], [VALUE_MAX, 0, VALUE_MAX], [VALUE_MAX; 3]] {
                for flip in [false, true] {
                    let (p, q) = ((ox + span, oy + span / 3), (ox + span / 5, oy + span / 2));
                    let (p, q) = if flip { (q, p) } else { (p, q) };
                    let tri = [
                        (v(ox, oy), [values[0]]),
                        (v(p.0, p.1), [values[1]]),
                        (v(q.0, q.1), [values[2]]),
                    ];
                    let inside =
                        |c: i32| (c / SUBPIXEL_STEPS).clamp(0, i32::from(frame) - 1) as u16;
                    let pixels = [
                        (inside(ox), inside(oy)),
                        (inside(p.0), inside(p.1)),
                        (inside(q.0), inside(q.1)),
                    ];
                    assert!(check(tri, frame, frame, &pixels), "{tri:?}");
                }
            }
        }
    }

    /// A sliver one sub-pixel step wide with the whole value range across
    /// it is steep, and its values are exact.
    #[test]
    fn slivers_are_steep_and_exact() {
        let tri = [
            (v(0, 0), [0]),
            (v(4096 * SUBPIXEL_STEPS - 1, 1), [0]),
            (v(0, 1), [VALUE_MAX]),
        ];
        let [plane] = attribute_planes(tri.iter().copied(), 4096, 16).unwrap();
        assert!(plane.is_steep());
        check(tri, 4096, 16, &[(0, 0), (100, 0), (4095, 0)]);
    }

    /// Checks [`modular_triangle_planes`] at every pixel whose sample lies
    /// inside the triangle (or on its edges): the value modulo `2^32`
    /// within `1/2 + e·(1 + |x - x_o| + |y - y_o|)` of the exact plane,
    /// `e = |g|·2^-28 + 1` for each gradient `g`, and that below `2^14`.
    /// Returns whether the set-up took the triangle.
    fn check_modular(corners: [(ScreenVertex, [u32; 1]); 3]) -> bool {
        let [o, p, q] = corners;
        let Some([plane]) = modular_triangle_planes(o, p, q) else {
            return false;
        };
        let e = |g: i64| i128::from(g.unsigned_abs() >> 28) + 2;
        let (ex, ey) = (e(plane.dx), e(plane.dy));
        let (xo, yo) = (o.0.x >> SUBPIXEL_BITS, o.0.y >> SUBPIXEL_BITS);
        let xs: Vec<i32> = corners.iter().map(|c| c.0.x >> SUBPIXEL_BITS).collect();
        let ys: Vec<i32> = corners.iter().map(|c| c.0.y >> SUBPIXEL_BITS).collect();
        let side = |a: ScreenVertex, b: ScreenVertex, x: i32, y: i32| {
            i64::from(b.x - a.x) * i64::from(y - a.y) - i64::from(b.y - a.y) * i64::from(x - a.x)
        };
        let (lo_x, hi_x) = (*xs.iter().min().unwrap(), *xs.iter().max().unwrap());
        let (lo_y, hi_y) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
        for y in lo_y..=hi_y {
            for x in lo_x..=hi_x {
                let (sx, sy) = (
                    x * SUBPIXEL_STEPS + HALF_PIXEL,
                    y * SUBPIXEL_STEPS + HALF_PIXEL,
                );
                let sides = [
                    side(o.0, p.0, sx, sy),
                    side(p.0, q.0, sx, sy),
                    side(q.0, o.0, sx, sy),
                ];
                if !(sides.iter().all(|&s| s >= 0) || sides.iter().all(|&s| s <= 0)) {
                    continue;
                }
                let got = (plane.at_origin as u32)
                    .wrapping_add((plane.dx as u32).wrapping_mul(x as u32))
                    .wrapping_add((plane.dy as u32).wrapping_mul(y as u32));
                let (num, den) = exact(&corners, sx, sy);
                let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
                // The value modulo 2^32 nearest the exact one.
                let floor = num.div_euclid(den);
                let got = i128::from(got);
                let got = got - (got - floor + (1 << 31)).div_euclid(1 << 32) * (1 << 32);
                let error2 = (2 * got * den - 2 * num).abs();
                let steps = i128::from((x - xo).abs() + (y - yo).abs());
                let bound2 = (1 + 2 * ex.max(ey) * (1 + steps)) * den.abs();
                assert!(
                    error2 <= bound2,
                    "{corners:?} at ({x}, {y}): {got} for {num}/{den}"
                );
                assert!(error2 < (1 << 15) * den.abs());
            }
        }
        true
    }

    /// Triangles at the modular set-up's limits (corners just under 64 px
    /// from `o`, values 0 and `2^16`, the largest gradients it takes):
    /// taken, and within the bound; beyond them, refused.
    #[test]
    fn modular_set_up_extremes() {
        let span = MODULAR_SPAN - 1;
        let top = MODULAR_VALUE_MAX;
        let mut taken = 0;
        for (ox, oy) in [(0, 0), (-span / 2, 4000 * SUBPIXEL_STEPS), (12345, 678)] {
            for values in [[0, top, 0], [top, 0, top], [top; 3], [0, 0, top]] {
                for (p, q) in [
                    ((span, span / 3), (span / 5, span)),
                    ((span, 0), (0, span)),
                    ((-span, span), (span, span)),
                    // A sliver: gradients near the limit, or beyond it.
                    ((span, 1), (0, 2)),
                    ((span, 1), (0, 300)),
                ] {
                    let tri = [
                        (v(ox, oy), [values[0]]),
                        (v(ox + p.0, oy + p.1), [values[1]]),
                        (v(ox + q.0, oy + q.1), [values[2]]),
                    ];
                    taken += usize::from(check_modular(tri));
                }
            }
        }
        assert!(taken >= 40, "{taken}");
        let tri = |d: i32, value: u32| [(v(0, 0), [0]), (v(d, 0), [value]), (v(0, d), [0])];
        assert!(check_modular(tri(span, top)));
        let [o, p, q] = tri(span + 1, top);
        assert_eq!(modular_triangle_planes(o, p, q), None);
        let [o, p, q] = tri(span, top + 1);
        assert_eq!(modular_triangle_planes(o, p, q), None);
        // Steep: the whole range across one sub-pixel step.
        let [o, p, q] = [(v(0, 0), [0]), (v(span, 0), [0]), (v(0, 1), [top])];
        assert_eq!(modular_triangle_planes(o, p, q), None);
    }

    proptest! {
        /// Random triangles anywhere in the guard band, any values: every
        /// value of a 64x64 frame's sampled pixels within its bound.
        #[test]
        fn values_are_within_the_bound(
            xy in prop::array::uniform6(-G..=G),
            small in prop::array::uniform6(-2048i32..2048),
            values in prop::array::uniform3(0..=VALUE_MAX),
            local in any::<bool>(),
        ) {
            // Half the cases are small triangles near the frame.
            let c: [i32; 6] = if local {
                core::array::from_fn(|k| small[k] * 8 + 8192)
            } else {
                xy
            };
            let tri = [
                (v(c[0], c[1]), [values[0]]),
                (v(c[2], c[3]), [values[1]]),
                (v(c[4], c[5]), [values[2]]),
            ];
            let pixels: Vec<(u16, u16)> = (0..64).step_by(7).flat_map(|x| (0..64).step_by(9).map(move |y| (x, y))).collect();
            check(tri, 64, 64, &pixels);
        }

        /// Random small triangles anywhere in the guard band, any values
        /// the modular set-up takes: every pixel inside within its bound.
        #[test]
        fn modular_values_are_within_the_bound(
            o in (-G..G - MODULAR_SPAN, -G..G - MODULAR_SPAN),
            d in prop::array::uniform4(-MODULAR_SPAN + 1..MODULAR_SPAN),
            scale in 0u32..5,
            values in prop::array::uniform3(0..=MODULAR_VALUE_MAX),
        ) {
            // Sizes from 1/16 of the span to all of it.
            let d = d.map(|c| c >> (scale * 2));
            let tri = [
                (v(o.0, o.1), [values[0]]),
                (v(o.0 + d[0], o.1 + d[1]), [values[1]]),
                (v(o.0 + d[2], o.1 + d[3]), [values[2]]),
            ];
            check_modular(tri);
        }
    }
}
