//! The depth plane of a polygon in screen space and its fixed-point
//! gradients.
//!
//! With the polygon's normal `(a, b, c)` from Newell's method over its
//! corners, depth is `z(x, y) = z0 - (a·(x - x0) + b·(y - y0)) / c` through
//! the first corner, so `dz/dx = -a/c` and `dz/dy = -b/c`. Coordinates are
//! relative to the first corner, so inside the guard band `|a|, |b| < 2^57`
//! and `|c| < 2^55` for up to 256 corners, all in `i64`.
//!
//! Values are *plane units*: input depth steps with
//! [`PLANE_FRAC_BITS`] fractional bits. The gradients are rounded to the
//! nearest plane unit once per polygon; the renderer then steps them, so a
//! stored value differs from the exact plane by at most
//! `2^-17 · (1 + rows stepped + pixels stepped)` input steps plus the
//! format's final rounding (see [`crate::depth`]).

use crate::fixed::{HALF_PIXEL, PLANE_FRAC_BITS, SUBPIXEL_BITS, SUBPIXEL_STEPS, div_round_q16};
use crate::vertex::ScreenVertex;

/// A gradient of this magnitude (plane units per pixel) or more changes
/// depth by the whole depth range within one pixel: such a polygon is
/// (nearly) edge-on and its depth is evaluated exactly per pixel instead.
pub(crate) const STEEP_GRADIENT: i64 = 1 << (crate::fixed::DEPTH_BITS + PLANE_FRAC_BITS);

/// Exact plane of a polygon: normal from Newell's method, through corner 0.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Plane {
    a: i64,
    b: i64,
    c: i64,
    origin: ScreenVertex,
}

/// Twice the signed area of the polygon projected on the screen (`c` of
/// Newell's normal), in square sub-pixel steps; positive when the corners
/// run counter-clockwise with y pointing up.
pub(crate) fn twice_area(corners: &[ScreenVertex]) -> i64 {
    let Some(&origin) = corners.first() else {
        return 0;
    };
    let mut area = 0i64;
    let (x0, y0) = (i64::from(origin.x), i64::from(origin.y));
    for pair in corners.windows(2).skip(1) {
        // Fan from corner 0: the sum of the triangles' cross products.
        let (ax, ay) = (i64::from(pair[0].x) - x0, i64::from(pair[0].y) - y0);
        let (bx, by) = (i64::from(pair[1].x) - x0, i64::from(pair[1].y) - y0);
        area += ax * by - bx * ay;
    }
    area
}

/// Newell's normal `(a, b, c)` of the corners, relative to corner 0 so
/// every product stays small. For a triangle it is the cross product of
/// two edges.
fn newell(corners: &[ScreenVertex]) -> (i64, i64, i64, ScreenVertex) {
    let origin = corners.first().copied().unwrap_or_default();
    let rel = |v: ScreenVertex| {
        (
            i64::from(v.x) - i64::from(origin.x),
            i64::from(v.y) - i64::from(origin.y),
            i64::from(v.z) - i64::from(origin.z),
        )
    };
    let (mut a, mut b, mut c) = (0i64, 0i64, 0i64);
    // With corner 0 at the origin, Newell's sum is the fan of cross
    // products p_k × p_(k+1).
    for pair in corners.windows(2).skip(1) {
        let (px, py, pz) = rel(pair[0]);
        let (qx, qy, qz) = rel(pair[1]);
        a += py * qz - pz * qy;
        b += pz * qx - px * qz;
        c += px * qy - py * qx;
    }
    (a, b, c, origin)
}

impl Plane {
    /// The plane of a polygon; `None` when its projected area is zero.
    pub fn new(corners: &[ScreenVertex]) -> Option<Self> {
        let (a, b, c, origin) = newell(corners);
        (c != 0).then_some(Self { a, b, c, origin })
    }

    /// Exact plane value at sub-pixel point `(x, y)`, rounded to the nearest
    /// plane unit.
    pub fn value_at(&self, x: i32, y: i32) -> i64 {
        // Inside the guard band both offsets are below 2^23.
        let dx = i64::from(x) - i64::from(self.origin.x);
        let dy = i64::from(y) - i64::from(self.origin.y);
        // On a 32-bit MCU i128 products are slow: use i64 when |a|, |b| <
        // 2^39 (then each product is below 2^62), which is every polygon of
        // ordinary size.
        const SMALL: u64 = 1 << 39;
        let num = if self.a.unsigned_abs() < SMALL && self.b.unsigned_abs() < SMALL {
            i128::from(-(self.a * dx + self.b * dy))
        } else {
            -(i128::from(self.a) * i128::from(dx) + i128::from(self.b) * i128::from(dy))
        };
        let offset = div_round_q16(num, self.c);
        let value = (i128::from(self.origin.z) << PLANE_FRAC_BITS) + offset;
        value.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
    }

    /// Plane value at the sample point of pixel `(column, row)`.
    pub fn value_at_pixel(&self, column: i32, row: i32) -> i64 {
        self.value_at(
            column * SUBPIXEL_STEPS + HALF_PIXEL,
            row * SUBPIXEL_STEPS + HALF_PIXEL,
        )
    }

    /// `-coef / c` per pixel in plane units, rounded; `None` when steep.
    fn gradient(&self, coef: i64) -> Option<i64> {
        let g = div_round_q16(-i128::from(coef) << SUBPIXEL_BITS, self.c);
        (g.abs() < i128::from(STEEP_GRADIENT)).then_some(g as i64)
    }

    /// `(dz/dx, dz/dy)` per pixel in plane units, or `None` when either is
    /// steep (at least the whole depth range per pixel).
    pub fn gradients(&self) -> Option<(i64, i64)> {
        Some((self.gradient(self.a)?, self.gradient(self.b)?))
    }
}
