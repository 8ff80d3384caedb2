//! The depth plane of a polygon in screen space and its fixed-point
//! gradients.
//!
//! With the polygon's normal `(a, b, c)` from Newell's method over its
//! corners, depth is `z(x, y) = z0 - (a·(x - x0) + b·(y - y0)) / c` through
//! the first corner, so `dz/dx = -a/c` and `dz/dy = -b/c`.
//!
//! Values are *plane units*: input depth steps with
//! [`PLANE_FRAC_BITS`] fractional bits. The gradients are rounded to the
//! nearest plane unit once per polygon; the renderer then steps them, so a
//! stored value differs from the exact plane by at most
//! `2^-17 · (1 + rows stepped + pixels stepped)` input steps plus the
//! format's final rounding (see [`crate::raster::depth`]).
//!
//! # Ranges
//! For every input the API accepts (corners inside the guard band, so
//! coordinate differences `|dx|, |dy| < 2^22` sub-pixel steps; depths
//! `0..=DEPTH_MAX`, so `|dz| < 2^24`; at most [`MAX_POLYGON_CORNERS`]
//! `< 2^10` corners, so at most `2^10` fan triangles):
//!
//! | quantity | bound | held in |
//! |---|---|---|
//! | one fan triangle's `a`, `b` term (`py·qz - pz·qy`) | `< 2^47` | `i64` |
//! | one fan triangle's `c` term (`px·qy - py·qx`) | `< 2^45` | `i64` |
//! | Newell `a`, `b` | [`NEWELL_AB_BOUND`] `= 2^57` | `i64` |
//! | Newell `c` (twice the area, also [`OutlineBuilder`](crate::raster::vertex::OutlineBuilder)'s sum) | [`NEWELL_C_BOUND`] `= 2^55` | `i64` |
//! | gradient numerator `-a · 2^8` | `< 2^65` | `i128` |
//! | `a·dx + b·dy` in [`Plane::value_at`] | `< 2^80` (`< 2^62` on its `i64` path, taken when `|a|, |b| < 2^39`) | `i128` / `i64` |
//! | quotient of `div_round_q16` (by [`Reciprocal`] when both operands are below `2^45`: `|N| < 2^63`, `D < 2^46`) | `< 2^97` | `i128` |
//! | plane value returned by [`Plane::value_at`] | clamped to `±`[`PLANE_VALUE_LIMIT`] `= 2^60` | `i64` |
//! | stepped gradient (else the polygon is `Exact`) | `< 2^40` per pixel | `i64` |
//! | plane value of a stepped polygon anywhere in the guard band | `< 2^56 + 2^40` (so never clamped) | `i64` |
//!
//! The tests in this module build the extremes (corners on the guard
//! band, depths at both ends, 1,024-corner polygons winding as often as
//! they can) and check each bound and each result against `i128`
//! arithmetic, with overflow checks on.

use crate::arith::divide::{DIVISION_IS_CHEAP, Divisor, Reciprocal};
use crate::arith::wide::{cross, mul_i64_i32, mul_sub_small};
use crate::limits::{
    DEPTH_MAX, HALF_PIXEL, MAX_POLYGON_CORNERS, PLANE_FRAC_BITS, SUBPIXEL_BITS, SUBPIXEL_STEPS,
};
use crate::raster::vertex::ScreenVertex;

/// A gradient of this magnitude (plane units per pixel) or more changes
/// depth by the whole depth range within one pixel: such a polygon is
/// (nearly) edge-on and its depth is evaluated exactly per pixel instead.
pub(crate) const STEEP_GRADIENT: i64 = 1 << (crate::limits::DEPTH_BITS + PLANE_FRAC_BITS);

/// Bound on `|a|` and `|b|` of Newell's normal.
pub(crate) const NEWELL_AB_BOUND: u64 = 1 << 57;
/// Bound on `|c|` of Newell's normal (twice the projected area).
pub(crate) const NEWELL_C_BOUND: u64 = 1 << 55;
/// Plane values are clamped to `±PLANE_VALUE_LIMIT`: far beyond the depth
/// range (`2^40` plane units), so clamping never changes a stored depth,
/// and far enough from `i64::MAX` that rounding cannot overflow.
pub(crate) const PLANE_VALUE_LIMIT: i64 = 1 << 60;

const _: () = assert!(MAX_POLYGON_CORNERS <= 1 << 10);

/// Exact plane of a polygon: normal from Newell's method, through corner 0.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Plane {
    a: i64,
    b: i64,
    #[cfg_attr(not(test), allow(dead_code))]
    c: i64,
    /// Dividing by `c`, three times or more: by multiplication.
    recip: Reciprocal,
    origin: ScreenVertex,
}

/// Newell's normal `(a, b, c)` of the corners, relative to corner 0 so
/// every product stays small, and corner 0. For a triangle it is the cross
/// product of two edges.
fn newell(corners: impl IntoIterator<Item = ScreenVertex>) -> (i64, i64, i64, ScreenVertex) {
    let mut corners = corners.into_iter();
    let origin = corners.next().unwrap_or_default();
    let rel = |v: ScreenVertex| {
        (
            i64::from(v.x) - i64::from(origin.x),
            i64::from(v.y) - i64::from(origin.y),
            i64::from(v.z) - i64::from(origin.z),
        )
    };
    let (mut a, mut b, mut c) = (0i64, 0i64, 0i64);
    let Some(second) = corners.next() else {
        return (0, 0, 0, origin);
    };
    // With corner 0 at the origin, Newell's sum is the fan of cross
    // products p_k × p_(k+1).
    let (mut px, mut py, mut pz) = rel(second);
    for q in corners {
        let (qx, qy, qz) = rel(q);
        a += py * qz - pz * qy;
        b += pz * qx - px * qz;
        c += px * qy - py * qx;
        (px, py, pz) = (qx, qy, qz);
    }
    debug_assert!(a.unsigned_abs() < NEWELL_AB_BOUND && b.unsigned_abs() < NEWELL_AB_BOUND);
    debug_assert!(c.unsigned_abs() < NEWELL_C_BOUND);
    (a, b, c, origin)
}

impl Plane {
    /// The plane of a polygon; `None` when its projected area is zero.
    pub fn new(corners: impl IntoIterator<Item = ScreenVertex>) -> Option<Self> {
        let (a, b, c, origin) = newell(corners);
        (c != 0).then(|| Self {
            a,
            b,
            c,
            recip: Reciprocal::new(c),
            origin,
        })
    }

    /// The plane through the same corners (the same `x` and `y`, in the
    /// same order) with other values in place of depth: Newell's `a` and
    /// `b` anew, `c` and its reciprocal kept (they depend on `x` and `y`
    /// alone). The ranges are depth's: values `0..=DEPTH_MAX`.
    pub fn with_values(&self, corners: impl IntoIterator<Item = ScreenVertex>) -> Self {
        let (a, b, c, origin) = newell(corners);
        debug_assert_eq!(
            (c, origin.x, origin.y),
            (self.c, self.origin.x, self.origin.y)
        );
        Self {
            a,
            b,
            c: self.c,
            recip: self.recip,
            origin,
        }
    }

    /// Corner 0, where the plane is anchored.
    pub fn origin(&self) -> ScreenVertex {
        self.origin
    }

    /// The plane of a triangle through corner `o` (the same arithmetic as
    /// [`Self::new`] over `[o, p, q]`); `None` when its area is zero.
    #[inline]
    pub fn triangle(o: ScreenVertex, p: ScreenVertex, q: ScreenVertex) -> Option<Self> {
        let rel = |v: ScreenVertex| {
            (
                i64::from(v.x) - i64::from(o.x),
                i64::from(v.y) - i64::from(o.y),
                i64::from(v.z) - i64::from(o.z),
            )
        };
        let ((px, py, pz), (qx, qy, qz)) = (rel(p), rel(q));
        let c = px * qy - py * qx;
        (c != 0).then(|| Self {
            a: py * qz - pz * qy,
            b: pz * qx - px * qz,
            c,
            recip: Reciprocal::new(c),
            origin: o,
        })
    }

    /// Exact plane value at sub-pixel point `(x, y)` (inside the guard
    /// band), rounded to the nearest plane unit and clamped to
    /// `±PLANE_VALUE_LIMIT`.
    pub fn value_at(&self, x: i32, y: i32) -> i64 {
        // Inside the guard band both offsets are below 2^22.
        let dx = i64::from(x) - i64::from(self.origin.x);
        let dy = i64::from(y) - i64::from(self.origin.y);
        // On a 32-bit MCU i128 products are slow: use i64 when |a|, |b| <
        // 2^39 (then each product is below 2^61), which is every polygon of
        // ordinary size.
        const SMALL: u64 = 1 << 39;
        let offset = if self.a.unsigned_abs() < SMALL && self.b.unsigned_abs() < SMALL {
            let num = -(self.a * dx + self.b * dy);
            match self.recip.div_round_q16_small(num) {
                Some(q) => i128::from(q),
                None => self.recip.div_round_q16(i128::from(num)),
            }
        } else {
            let num = -(i128::from(self.a) * i128::from(dx) + i128::from(self.b) * i128::from(dy));
            self.recip.div_round_q16(num)
        };
        let value = (i128::from(self.origin.z) << PLANE_FRAC_BITS) + offset;
        let limit = i128::from(PLANE_VALUE_LIMIT);
        value.clamp(-limit, limit) as i64
    }

    /// Plane value at the sample point of pixel `(column, row)`.
    pub fn value_at_pixel(&self, column: i32, row: i32) -> i64 {
        self.value_at(
            column * SUBPIXEL_STEPS + HALF_PIXEL,
            row * SUBPIXEL_STEPS + HALF_PIXEL,
        )
    }

    /// The column whose plane value anchors a stepped row: the pixel of
    /// corner 0, clamped to the frame's `width` columns. Near the polygon
    /// the set-up product `a·dx` stays small (the one-multiplication path
    /// of [`Reciprocal`]), and the gradient's rounding is multiplied only
    /// by the distance from this column.
    #[inline]
    fn anchor_column(&self, width: u16) -> i32 {
        (self.origin.x >> SUBPIXEL_BITS).clamp(0, i32::from(width.max(1)) - 1)
    }

    /// The value a stepped polygon holds for column 0 of `row`:
    /// `V(anchor, first_row) - dz_dx·anchor + (row - first_row)·dz_dy`,
    /// with `V` the exact (rounded) plane value at the anchor column's
    /// sample. It is exactly what stepping from `first_row` by `dz_dy`
    /// gives, so a band that starts below `first_row` writes the depths
    /// one scan would; a span starting at column `x` then adds
    /// `dz_dx·x`, which cancels the anchor term exactly, so a stored value
    /// is off the exact plane by at most `2^-17·(1 + rows stepped + |x -
    /// anchor|)` depth steps before the format's rounding.
    ///
    /// Ranges (`dz_dx`, `dz_dy` stepped, so below `2^40`; columns and rows
    /// below `2^12`): `dz_dx·anchor` and `(row - first_row)·dz_dy` are
    /// below `2^52`; the result is the plane value at column 0 within
    /// `2^12` plane units, so below `2^56 + 2^41`.
    #[inline]
    pub fn row_start(&self, gradients: (i64, i64), width: u16, first_row: u16, row: u16) -> i64 {
        let (dz_dx, dz_dy) = gradients;
        let anchor = self.anchor_column(width);
        let steps = i64::from(row.saturating_sub(first_row));
        self.value_at_pixel(anchor, i32::from(first_row)) - dz_dx * i64::from(anchor)
            + steps * dz_dy
    }

    /// The value a polygon sharing this plane holds for column 0 of `row`
    /// ([`Tables::share_plane`](crate::raster::Tables::share_plane)):
    /// [`Self::row_start`] anchored at the pixel of corner 0, clamped to
    /// the `width` x `height` frame, rather than at a polygon's first row,
    /// so that it is a function of the plane, the frame and the row alone.
    /// A pixel `x` then holds this plus `dz_dx·x`, off the exact plane by
    /// at most `2^-17·(1 + |x - anchor column| + |row - anchor row|)`
    /// depth steps, below `2^-4` in any frame.
    ///
    /// Ranges: as [`Self::row_start`], with `|row - anchor row| < 2^12`,
    /// so `(row - anchor row)·dz_dy` is below `2^52` in magnitude.
    #[inline]
    pub fn shared_row_start(
        &self,
        gradients: (i64, i64),
        width: u16,
        height: u16,
        row: u16,
    ) -> i64 {
        let (dz_dx, dz_dy) = gradients;
        let column = self.anchor_column(width);
        let anchor_row = (self.origin.y >> SUBPIXEL_BITS).clamp(0, i32::from(height.max(1)) - 1);
        let steps = i64::from(row) - i64::from(anchor_row);
        self.value_at_pixel(column, anchor_row) - dz_dx * i64::from(column) + steps * dz_dy
    }

    /// `-coef / c` per pixel in plane units, rounded; `None` when steep.
    #[inline]
    fn gradient(&self, coef: i64) -> Option<i64> {
        // |coef| < 2^57, so coef · 2^8 fits i64 only when small: try the
        // reciprocal on i64 first.
        let g = match coef.checked_mul(-(1 << SUBPIXEL_BITS)) {
            Some(n) => match self.recip.div_round_q16_small(n) {
                Some(g) => i128::from(g),
                None => self.recip.div_round_q16(i128::from(n)),
            },
            None => self.recip.div_round_q16(-i128::from(coef) << SUBPIXEL_BITS),
        };
        (g.abs() < i128::from(STEEP_GRADIENT)).then_some(g as i64)
    }

    /// `(dz/dx, dz/dy)` per pixel in plane units, or `None` when either is
    /// steep (at least the whole depth range per pixel).
    pub fn gradients(&self) -> Option<(i64, i64)> {
        Some((self.gradient(self.a)?, self.gradient(self.b)?))
    }
}

/// How [`TrianglePlane`] divides by a triangle's doubled area. Every path
/// gives the same results exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DivisionPath {
    /// The reciprocal of a [`Divisor`]: products only, for a core whose
    /// division is a library routine (a Cortex-M0+ without a divider).
    Reciprocal,
    /// 32-bit divisions, eight bits of quotient per step after the first,
    /// when `d < 2^23`; else the reciprocal. For a 32-bit core that divides
    /// 32-bit words in hardware (the RP2040's SIO divider, a Cortex-M3's
    /// `udiv`) but 64-bit ones in a library routine.
    Words,
    /// The target's own 64-bit division: a 64-bit core.
    Native,
}

/// Whether [`TrianglePlane::new`] takes its gradients from
/// [`float_gradient`]: on a 64-bit host (x86-64, AArch64), where one
/// `f64` division takes less time than the two 64-bit integer divisions
/// of [`DivisionPath::Native`]. A microcontroller never does.
pub(crate) const FLOAT_GRADIENTS: bool = cfg!(any(target_arch = "x86_64", target_arch = "aarch64"));

/// This target's [`DivisionPath`].
pub(crate) const DIVISION_PATH: DivisionPath = if cfg!(target_pointer_width = "64") {
    DivisionPath::Native
} else if DIVISION_IS_CHEAP {
    DivisionPath::Words
} else {
    DivisionPath::Reciprocal
};

/// Division by a small triangle's `d = |c|` (`0 < d < 2^31`) for
/// [`TrianglePlane`]'s gradients, by a [`DivisionPath`]. The reciprocal of
/// a [`Divisor`] is made the first time a path needs it.
struct GradientDivisor {
    d: u32,
    divisor: Option<Divisor>,
    path: DivisionPath,
}

impl GradientDivisor {
    /// Division by `d` on `path`. The reciprocal path makes its
    /// [`Divisor`] at once: each of its divisions needs it.
    #[inline(always)]
    fn with_path(d: u32, path: DivisionPath) -> Self {
        debug_assert!(d > 0 && d < 1 << 31);
        Self {
            d,
            divisor: (path == DivisionPath::Reciprocal).then(|| Divisor::new(d)),
            path,
        }
    }

    #[inline(always)]
    fn divisor(&mut self) -> &Divisor {
        let d = self.d;
        self.divisor.get_or_insert_with(|| Divisor::new(d))
    }

    /// Whether `d` is small enough for the 32-bit steps of
    /// [`DivisionPath::Words`].
    fn bytewise(&self) -> bool {
        self.path == DivisionPath::Words && self.d < 1 << 23
    }

    /// `(n / d, n mod d)` for `n < 2^57`; `None` when the quotient is
    /// [`Divisor::QUOTIENT_LIMIT`] or more (as [`Divisor::div_rem`]).
    ///
    /// Always inline, as [`Self::fraction`]: the path is a constant
    /// ([`DIVISION_PATH`]) and only its arm is compiled. Out of line (as
    /// `#[inline]` left them on Arm), each call matched the path at run
    /// time and linked every path's code: `cargo qemu`'s torus knot took
    /// 71,040 more instructions a frame, `cargo qemu-m4f`'s 27,440 more.
    #[inline(always)]
    fn div_rem(&mut self, n: u64) -> Option<(u64, u64)> {
        let d = self.d;
        let (q, r) = match self.path {
            DivisionPath::Reciprocal => return self.divisor().div_rem_short(n),
            DivisionPath::Native => (n / u64::from(d), n % u64::from(d)),
            DivisionPath::Words => match u32::try_from(n) {
                Ok(n) => ((n / d).into(), (n % d).into()),
                Err(_) if self.bytewise() => div_rem_by_bytes(n, d),
                Err(_) => return self.divisor().div_rem_short(n),
            },
        };
        (q < Divisor::QUOTIENT_LIMIT).then_some((q, r))
    }

    /// `floor((rest·2^16 + floor(d / 2)) / d)` for `rest < d`: the
    /// fraction of a gradient, rounded (below `2^16 + 1`).
    ///
    /// With `d < 2^23`, in two 32-bit steps of 8 bits: `rest·2^8 < 2^31`
    /// gives `q1 < 2^8` and `r1 < d`; then `r1·2^8 + floor(d / 2) < 2^31 +
    /// 2^22`, and the fraction is `q1·2^8 + floor(that / d)`, since
    /// `rest·2^16 + h = q1·2^8·d + (r1·2^8 + h)`.
    #[inline(always)]
    fn fraction(&mut self, rest: u64) -> Option<u64> {
        let (d, half) = (self.d, self.d >> 1);
        if self.bytewise() {
            let a = (rest as u32) << 8;
            let (q1, r1) = (a / d, a % d);
            let q2 = ((r1 << 8) + half) / d;
            return Some(u64::from((q1 << 8) + q2));
        }
        // rest < 2^31: the numerator is below 2^47.
        let n = (rest << PLANE_FRAC_BITS) + u64::from(half);
        if self.path == DivisionPath::Native {
            return Some(n / u64::from(d));
        }
        Some(self.divisor().div_rem_short(n)?.0)
    }
}

/// `round(-coef·2^8·2^16 / c)` (a gradient in plane units per pixel),
/// exactly, in two divisions by `divisor` (of `d = |c|`): `|n| = whole·d +
/// rest`, then the fraction; `None` when steep or beyond the divisor's
/// quotients. (`|coef| < 2^41`, so `|n| < 2^49`.)
#[inline(always)]
fn exact_gradient(divisor: &mut GradientDivisor, c: i64, coef: i64) -> Option<i64> {
    let d = c.unsigned_abs();
    let n = if c < 0 { coef } else { -coef } << SUBPIXEL_BITS;
    let (whole, rest) = divisor.div_rem(n.unsigned_abs())?;
    let (whole, rest) = (whole as i64, rest as i64);
    // floor for a negative numerator: -(whole + 1) and d - rest.
    let (whole, rest) = if n < 0 && rest != 0 {
        (-whole - 1, d as i64 - rest)
    } else if n < 0 {
        (-whole, 0)
    } else {
        (whole, rest)
    };
    let fraction = divisor.fraction(rest as u64)?;
    let g = (whole << PLANE_FRAC_BITS) + fraction as i64;
    (g.abs() < STEEP_GRADIENT).then_some(g)
}

/// What [`float_gradient`] takes for its divisor `d`: `1 / d` in `f64` on
/// the hosts that take that path ([`FLOAT_GRADIENTS`]), where one division
/// serves all of a triangle's gradients; nothing elsewhere, where the path
/// is compiled but never taken (so that a microcontroller's code stays as
/// it was: with the `f64` captured, the Cortex-M0+'s textured frame took
/// 17,240 more instructions).
#[cfg(any(target_arch = "x86_64", target_arch = "aarch64"))]
pub(crate) type GradientInverse = f64;
/// See the host's `GradientInverse`.
#[cfg(not(any(target_arch = "x86_64", target_arch = "aarch64")))]
#[derive(Debug, Clone, Copy)]
pub(crate) struct GradientInverse;

/// The [`GradientInverse`] of `d`.
#[inline(always)]
pub(crate) fn gradient_inverse(d: u32) -> GradientInverse {
    #[cfg(any(target_arch = "x86_64", target_arch = "aarch64"))]
    return 1.0 / f64::from(d);
    #[cfg(not(any(target_arch = "x86_64", target_arch = "aarch64")))]
    {
        let _ = d;
        GradientInverse
    }
}

/// `floor((n·2^16 + floor(d / 2)) / d)`, a gradient rounded to the unit,
/// for `|n| < 2^57` and `0 < d < 2^31`, from one `f64` product by
/// `inverse`, the `f64` value of `1 / d` ([`gradient_inverse`], one
/// division for every gradient of a triangle); `None` when `|n| / d` is
/// [`Divisor::QUOTIENT_LIMIT`] or more, as the integer paths. The same
/// value as `(n div d)·2^16 + floor(((n mod d)·2^16 + floor(d / 2)) / d)`
/// (floored division), which those paths compute.
///
/// Ranges: with `|n| < 2^26·d`, the quotient `Q = (n·2^16 + h) / d`
/// (`h = floor(d / 2)`) is below `2^42 + 1` in magnitude. `n as f64`, the
/// product by `2^16` (exact), the sum with `h`, `1 / d` and the product
/// by it each round by at most half an ulp (four roundings, relative
/// `2^-53` each), so the estimate is within `2^-51·2^43 = 2^-8` of `Q`,
/// and its truncation `g` within 2 of `floor(Q)`. The remainder
/// `n·2^16 + h - g·d` is then below `3d < 2^33` in magnitude, so
/// computing it modulo `2^64` (wrapping: `n·2^16` itself needs 73 bits)
/// gives it exactly, and at most two steps of `d` bring it into `[0, d)`.
#[inline(always)]
pub(crate) fn float_gradient(n: i64, d: u32, inverse: GradientInverse) -> Option<i64> {
    if n.unsigned_abs() >= Divisor::QUOTIENT_LIMIT * u64::from(d) {
        return None;
    }
    let (d, half) = (i64::from(d), i64::from(d >> 1));
    let numerator = (n as f64) * 65536.0 + half as f64;
    #[cfg(any(target_arch = "x86_64", target_arch = "aarch64"))]
    let estimate = numerator * inverse;
    #[cfg(not(any(target_arch = "x86_64", target_arch = "aarch64")))]
    let estimate = {
        let GradientInverse = inverse;
        numerator / d as f64
    };
    // Truncation, not `floor` (a library call without SSE4.1).
    let mut g = estimate as i64;
    let mut rest = n
        .wrapping_shl(PLANE_FRAC_BITS)
        .wrapping_add(half)
        .wrapping_sub(g.wrapping_mul(d));
    // A negative estimate's truncation is mostly one above the floor, a
    // positive one's mostly the floor: a branch on the gradient's sign
    // would miss half the time, so the first step down is a mask (-1 or
    // 0), and the loops after it mostly run no step. (|rest| < 3d stays
    // below 2^34.)
    let borrow = rest >> 63;
    g += borrow;
    rest += d & borrow;
    while rest < 0 {
        g -= 1;
        rest += d;
    }
    while rest >= d {
        g += 1;
        rest -= d;
    }
    Some(g)
}

/// `(n / d, n mod d)` for `n < 2^57` and `0 < d < 2^23` by 32-bit
/// divisions only.
///
/// The first dividend is `n`'s top bits: its high word `hi` with as many
/// whole bytes of its low word as fit 32 bits beside it (`bytes` bytes of
/// the low word are left; `hi < 2^25`, so `bytes <= 4`). Each later step
/// divides `r·2^8 + the next byte`, below `2^31` since `r < d < 2^23`,
/// and appends eight bits to the quotient, which stays below `n < 2^57`.
/// After each step `q·d + r` equals the bits of `n` taken so far.
fn div_rem_by_bytes(n: u64, d: u32) -> (u64, u64) {
    let (hi, lo) = ((n >> 32) as u32, n as u32);
    let bytes: u32 = match hi {
        0 => 0,
        1..0x100 => 1,
        0x100..0x1_0000 => 2,
        0x1_0000..0x100_0000 => 3,
        _ => 4,
    };
    let top = match bytes {
        0 => lo,
        4 => hi,
        _ => (hi << (32 - 8 * bytes)) | (lo >> (8 * bytes)),
    };
    let (mut q, mut r) = (u64::from(top / d), top % d);
    for k in (0..bytes).rev() {
        let dividend = (r << 8) | ((lo >> (8 * k)) & 0xFF);
        q = (q << 8) | u64::from(dividend / d);
        r = dividend % d;
    }
    (q, u64::from(r))
}

/// A triangle's depth gradients and the corner they are anchored at: the
/// set-up the scanner steps, made with no reciprocal and no 128-bit
/// product, so that it is cheap on a 32-bit core without a divider.
///
/// With the corners relative to `o`, `c = px·qy - py·qx` (twice the area),
/// `a = py·qz - pz·qy`, `b = pz·qx - px·qz`, and each gradient
/// `round(-a·2^24 / c)` (plane units per pixel) comes from two exact
/// divisions by `c`: `-a·2^8 = n·c + r` (`0 <= r < c`), then
/// `n·2^16 + round(r·2^16 / c)`. That is the same rounding as
/// [`Plane::gradients`], to the unit. On a 64-bit host each gradient is
/// instead one `f64` product by `1 / c` corrected exactly
/// ([`float_gradient`]; one division for all a triangle's gradients):
/// the same values.
///
/// The row value at column 0 is anchored at `o` itself, where the plane's
/// value is `z_o` exactly: `z_o·2^16 + round((dz_dx·(128 - o.x) +
/// dz_dy·(y_s - o.y)) / 256)` for the sample line `y_s` of the row. A
/// pixel `x` then stores `row value + dz_dx·x`, off the exact plane by at
/// most `2^-17·(1 + |x - o_x| + |y - o_y|)` depth steps (pixels from the
/// corner), plus `2^-17` for the final shift; and the value at a row is
/// exactly the value at an earlier row plus `dz_dy` per row, so stepping
/// and bands agree.
///
/// # Ranges
/// Taken when the triangle fits (else [`Plane`] does it):
/// | quantity | bound | held in |
/// |---|---|---|
/// | `px, py, qx, qy` | `< 2^16` (triangles under 256 px each way) | `i32` |
/// | `c` | `< 2^31`, non-zero | `i32` / `i64` |
/// | `a, b` (`|dz| < 2^24`) | `< 2^41` | `i64` |
/// | `-a·2^8`, `-b·2^8` | `< 2^49` | `i64` |
/// | `r·2^17 + c` | `< 2^48` | `i64` |
/// | gradient (else steep: `None`) | `< 2^40` | `i64` |
/// | `dz_dx·(128 - o.x)`, `dz_dy·(y_s - o.y)` (`|o| < 2^21`) | `< 2^61.01` each, `< 2^62.01` summed | `i64` |
#[derive(Debug, Clone, Copy)]
pub(crate) struct TrianglePlane {
    pub dz_dx: i64,
    pub dz_dy: i64,
    /// `c`: twice the signed area of `o p q` (non-zero, below `2^31`).
    pub twice_area: i32,
    origin: ScreenVertex,
}

impl TrianglePlane {
    /// The plane of triangle `o p q`; `None` when its area is zero, when
    /// it is too large for this set-up (256 px or more each way) or when a
    /// gradient is steep.
    #[inline]
    pub fn new(o: ScreenVertex, p: ScreenVertex, q: ScreenVertex) -> Option<Self> {
        if FLOAT_GRADIENTS {
            Self::with_float_division(o, p, q)
        } else {
            Self::with_division(o, p, q, DIVISION_PATH)
        }
    }

    /// [`Self::new`] with each gradient from [`float_gradient`]: the same
    /// values as [`Self::with_division`] on every path (the tests compare
    /// them).
    #[inline(always)]
    fn with_float_division(o: ScreenVertex, p: ScreenVertex, q: ScreenVertex) -> Option<Self> {
        let (c, a, b) = Self::coefficients(o, p, q)?;
        let d = c.unsigned_abs() as u32;
        let inverse = gradient_inverse(d);
        let gradient = |coef: i64| {
            let n = if c < 0 { coef } else { -coef } << SUBPIXEL_BITS;
            float_gradient(n, d, inverse).filter(|g| g.abs() < STEEP_GRADIENT)
        };
        Some(Self {
            dz_dx: gradient(a)?,
            dz_dy: gradient(b)?,
            twice_area: c as i32,
            origin: o,
        })
    }

    /// The plane's `c`, `a` and `b` (see the type's notes), or `None` when
    /// the triangle is too large for this set-up or its area is zero.
    /// ([`Self::with_division`] keeps its own copy of these lines: calling
    /// this from it changed the Cortex-M0+ build's code, and `cargo qemu`
    /// counted 1,760 more instructions a frame.)
    #[inline(always)]
    fn coefficients(o: ScreenVertex, p: ScreenVertex, q: ScreenVertex) -> Option<(i64, i64, i64)> {
        let small = |d: i32| d.unsigned_abs() < 1 << 16;
        let (px, py, qx, qy) = (p.x - o.x, p.y - o.y, q.x - o.x, q.y - o.y);
        if !(small(px) && small(py) && small(qx) && small(qy)) {
            return None;
        }
        // Each product below 2^32 in magnitude: i64, but no overflow check
        // needed.
        let c = cross(px, py, qx, qy);
        if c == 0 || c.unsigned_abs() >= 1 << 31 {
            return None;
        }
        // Depths are below 2^24: their differences fit i32, and each
        // product is below 2^40.
        let (pz, qz) = (p.z as i32 - o.z as i32, q.z as i32 - o.z as i32);
        let a = mul_sub_small(qz, py, pz, qy);
        let b = mul_sub_small(pz, qx, qz, px);
        Some((c, a, b))
    }

    /// [`Self::new`] on a given [`DivisionPath`] (the tests compare them).
    #[inline(always)]
    fn with_division(
        o: ScreenVertex,
        p: ScreenVertex,
        q: ScreenVertex,
        path: DivisionPath,
    ) -> Option<Self> {
        let small = |d: i32| d.unsigned_abs() < 1 << 16;
        let (px, py, qx, qy) = (p.x - o.x, p.y - o.y, q.x - o.x, q.y - o.y);
        if !(small(px) && small(py) && small(qx) && small(qy)) {
            return None;
        }
        // Each product below 2^32 in magnitude: i64, but no overflow check
        // needed.
        let c = cross(px, py, qx, qy);
        if c == 0 || c.unsigned_abs() >= 1 << 31 {
            return None;
        }
        // Depths are below 2^24: their differences fit i32, and each
        // product is below 2^40.
        let (pz, qz) = (p.z as i32 - o.z as i32, q.z as i32 - o.z as i32);
        let a = mul_sub_small(qz, py, pz, qy);
        let b = mul_sub_small(pz, qx, qz, px);
        let d = c.unsigned_abs();
        let mut divisor = GradientDivisor::with_path(d as u32, path);
        Some(Self {
            dz_dx: exact_gradient(&mut divisor, c, a)?,
            dz_dy: exact_gradient(&mut divisor, c, b)?,
            twice_area: c as i32,
            origin: o,
        })
    }

    /// The planes of `N` values over the triangle `o p q` (`values[k]` at
    /// the three corners, each at most `DEPTH_MAX`, in place of depth),
    /// with one division set-up for all: the same gradients and row values
    /// as [`Self::new`] of each (the tests compare them). `None` as
    /// [`Self::new`]: zero area, too large, or a steep plane.
    #[inline]
    pub fn with_values<const N: usize>(
        (o, p, q): (ScreenVertex, ScreenVertex, ScreenVertex),
        values: [[u32; 3]; N],
    ) -> Option<[Self; N]> {
        let small = |d: i32| d.unsigned_abs() < 1 << 16;
        let (px, py, qx, qy) = (p.x - o.x, p.y - o.y, q.x - o.x, q.y - o.y);
        if !(small(px) && small(py) && small(qx) && small(qy)) {
            return None;
        }
        let c = cross(px, py, qx, qy);
        if c == 0 || c.unsigned_abs() >= 1 << 31 {
            return None;
        }
        let d = c.unsigned_abs();
        let mut planes = [Self {
            dz_dx: 0,
            dz_dy: 0,
            twice_area: c as i32,
            origin: o,
        }; N];
        // Each plane's corner value and its two cross terms.
        let terms = values.map(|[vo, vp, vq]| {
            let (vo, vp, vq) = (vo.min(DEPTH_MAX), vp.min(DEPTH_MAX), vq.min(DEPTH_MAX));
            let (pz, qz) = (vp as i32 - vo as i32, vq as i32 - vo as i32);
            (
                vo,
                mul_sub_small(qz, py, pz, qy),
                mul_sub_small(pz, qx, qz, px),
            )
        });
        // One loop per division path, so that the host's (every gradient
        // from one product by `1 / d`) is straight-line code.
        if FLOAT_GRADIENTS {
            let inverse = gradient_inverse(d as u32);
            let gradient = |coef: i64| {
                let n = if c < 0 { coef } else { -coef } << SUBPIXEL_BITS;
                float_gradient(n, d as u32, inverse).filter(|g| g.abs() < STEEP_GRADIENT)
            };
            for (plane, (vo, a, b)) in planes.iter_mut().zip(terms) {
                (plane.dz_dx, plane.dz_dy) = (gradient(a)?, gradient(b)?);
                plane.origin.z = vo;
            }
        } else {
            let mut divisor = GradientDivisor::with_path(d as u32, DIVISION_PATH);
            for (plane, (vo, a, b)) in planes.iter_mut().zip(terms) {
                plane.dz_dx = exact_gradient(&mut divisor, c, a)?;
                plane.dz_dy = exact_gradient(&mut divisor, c, b)?;
                plane.origin.z = vo;
            }
        }
        Some(planes)
    }

    /// The value at column 0 of `row` (see the type's notes).
    #[inline(always)]
    pub fn row_start(&self, row: u16) -> i64 {
        let o = self.origin;
        let sample_y = i32::from(row) * SUBPIXEL_STEPS + HALF_PIXEL;
        let sum =
            mul_i64_i32(self.dz_dx, HALF_PIXEL - o.x) + mul_i64_i32(self.dz_dy, sample_y - o.y);
        (i64::from(o.z) << PLANE_FRAC_BITS) + ((sum + (1 << (SUBPIXEL_BITS - 1))) >> SUBPIXEL_BITS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arith::divide::div_round_i128;
    use crate::limits::{DEPTH_MAX, GUARD_BAND};
    use proptest::prelude::*;
    use std::vec::Vec;

    /// Largest coordinate magnitude the guard band admits.
    const G: i32 = GUARD_BAND - 1;

    fn v(x: i32, y: i32, z: u32) -> ScreenVertex {
        ScreenVertex::new(x, y, z).unwrap()
    }

    /// Newell's normal in i128, straight from the cyclic definition.
    fn newell_i128(poly: &[ScreenVertex]) -> (i128, i128, i128) {
        let (mut a, mut b, mut c) = (0i128, 0i128, 0i128);
        for k in 0..poly.len() {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            let (px, py, pz) = (i128::from(p.x), i128::from(p.y), i128::from(p.z));
            let (qx, qy, qz) = (i128::from(q.x), i128::from(q.y), i128::from(q.z));
            a += (py - qy) * (pz + qz);
            b += (pz - qz) * (px + qx);
            c += (px - qx) * (py + qy);
        }
        // Expanded, each sum is the fan form's: (y_i - y_j)(z_i + z_j)
        // sums to y_i·z_j - z_i·y_j over the cycle.
        (a, b, c)
    }

    /// Checks every set-up quantity of `poly` against its bound and its
    /// exact value (overflow checks are on in tests).
    fn check(poly: &[ScreenVertex]) {
        let (a, b, c) = newell_i128(poly);
        assert!(a.unsigned_abs() < u128::from(NEWELL_AB_BOUND), "a = {a}");
        assert!(b.unsigned_abs() < u128::from(NEWELL_AB_BOUND), "b = {b}");
        assert!(c.unsigned_abs() < u128::from(NEWELL_C_BOUND), "c = {c}");
        let mut outline = crate::raster::vertex::OutlineBuilder::default();
        poly.iter().for_each(|&v| outline.add(v));
        assert_eq!(i128::from(outline.finish().twice_area), c);
        let Some(plane) = Plane::new(poly.iter().copied()) else {
            assert_eq!(c, 0);
            return;
        };
        assert_eq!(
            (plane.a as i128, plane.b as i128, plane.c as i128),
            (a, b, c)
        );
        // Gradients: exactly rounded, or steep.
        for (coef, got) in [(a, plane.gradient(plane.a)), (b, plane.gradient(plane.b))] {
            let exact = div_round_i128(-coef << (SUBPIXEL_BITS + PLANE_FRAC_BITS), c);
            match got {
                Some(g) => assert_eq!(i128::from(g), exact),
                None => assert!(exact.abs() >= i128::from(STEEP_GRADIENT)),
            }
        }
        // Plane values at the guard band's corners and centre, and at the
        // frame's far corner, against the exactly rounded, clamped value.
        let o = poly[0];
        for (x, y) in [
            (-G, -G),
            (G, -G),
            (-G, G),
            (G, G),
            (0, 0),
            (4095 * 256, 4095 * 256),
        ] {
            let num =
                -(a * (i128::from(x) - i128::from(o.x)) + b * (i128::from(y) - i128::from(o.y)));
            let exact =
                (i128::from(o.z) << PLANE_FRAC_BITS) + div_round_i128(num << PLANE_FRAC_BITS, c);
            let limit = i128::from(PLANE_VALUE_LIMIT);
            let got = plane.value_at(x, y);
            assert_eq!(i128::from(got), exact.clamp(-limit, limit));
            if plane.gradients().is_some() {
                // A stepped polygon's plane never reaches the clamp.
                assert!(exact.abs() < (1 << 56) + (1 << 40), "stepped value {exact}");
            }
        }
    }

    #[test]
    fn extreme_triangles() {
        let xs = [-G, G];
        let zs = [0, DEPTH_MAX];
        let mut corners = Vec::new();
        for x in xs {
            for y in xs {
                for z in zs {
                    corners.push(v(x, y, z));
                }
            }
        }
        for &p in &corners {
            for &q in &corners {
                for &r in &corners {
                    check(&[p, q, r]);
                }
            }
        }
    }

    #[test]
    fn extreme_polygons_winding_many_times() {
        // 1,024 corners running round the guard band's corners 256 times:
        // |c| is 256 times twice the band's area, the largest a polygon of
        // this many corners can reach. The same in the depth planes.
        let ring = [(-G, -G), (G, -G), (G, G), (-G, G)];
        let flat: Vec<ScreenVertex> = (0..MAX_POLYGON_CORNERS)
            .map(|k| {
                let (x, y) = ring[k % 4];
                v(x, y, DEPTH_MAX / 2)
            })
            .collect();
        check(&flat);
        let depth_ring = [(-G, 0), (G, 0), (G, DEPTH_MAX), (-G, DEPTH_MAX)];
        for &(flip, y_step) in &[(false, 1), (true, 1), (false, 0)] {
            let poly: Vec<ScreenVertex> = (0..MAX_POLYGON_CORNERS)
                .map(|k| {
                    let (x, z) = depth_ring[k % 4];
                    // A small y offset gives the polygon some area.
                    let y = if (k / 2) % 2 == 0 {
                        -G
                    } else {
                        -G + y_step * 2 * G
                    };
                    if flip { v(y, x, z) } else { v(x, y, z) }
                })
                .collect();
            check(&poly);
        }
    }

    #[test]
    fn issue_7_item_1_gradient_has_the_right_sign() {
        // The x-gradient numerator is 2^46 - 256: the one-division shortcut
        // used to overflow and return a gradient of the wrong sign.
        let tri = [
            v(5120, 2560, 1_000_000),
            v(7680, 2560, 6_242_860),
            v(5120, 54_989, 1_000_000),
        ];
        check(&tri);
        let plane = Plane::new(tri).unwrap();
        let (dz_dx, _) = plane.gradients().unwrap();
        assert!(dz_dx > 0, "depth grows to the right: {dz_dx}");
    }

    fn extreme_coordinate() -> impl Strategy<Value = i32> {
        prop_oneof![
            Just(-G),
            Just(G),
            -G..=G,
            -G..-G + 512,
            G - 512..=G,
            -512..512
        ]
    }

    fn extreme_depth() -> impl Strategy<Value = u32> {
        prop_oneof![
            Just(0),
            Just(DEPTH_MAX),
            0..=DEPTH_MAX,
            0u32..16,
            DEPTH_MAX - 16..=DEPTH_MAX
        ]
    }

    /// Every division path.
    const PATHS: [DivisionPath; 3] = [
        DivisionPath::Reciprocal,
        DivisionPath::Words,
        DivisionPath::Native,
    ];

    /// A triangle's set-up against the general plane's (the same rounding,
    /// to the unit), on every division path; whether it had one.
    fn check_triangle_plane(o: ScreenVertex, p: ScreenVertex, q: ScreenVertex) -> bool {
        let fast = TrianglePlane::with_division(o, p, q, DivisionPath::Words);
        let gradients = |t: Option<TrianglePlane>| t.map(|t| (t.dz_dx, t.dz_dy));
        for path in PATHS {
            let other = TrianglePlane::with_division(o, p, q, path);
            assert_eq!(
                gradients(fast),
                gradients(other),
                "{o:?} {p:?} {q:?} {path:?}"
            );
        }
        let float = TrianglePlane::with_float_division(o, p, q);
        assert_eq!(gradients(fast), gradients(float), "{o:?} {p:?} {q:?} f64");
        if let Some(t) = fast {
            let plane = Plane::triangle(o, p, q).expect("a triangle with a set-up has area");
            assert_eq!(
                plane.gradients(),
                Some((t.dz_dx, t.dz_dy)),
                "{o:?} {p:?} {q:?}"
            );
        }
        // Two value planes at once (the second with the depths rotated)
        // are the two planes set up alone, row values too.
        let second = TrianglePlane::new(v(o.x, o.y, q.z), v(p.x, p.y, o.z), v(q.x, q.y, p.z));
        let both = TrianglePlane::with_values((o, p, q), [[o.z, p.z, q.z], [q.z, o.z, p.z]]);
        let planes = |t: Option<TrianglePlane>| t.map(|t| (t.dz_dx, t.dz_dy, t.row_start(3)));
        match (TrianglePlane::new(o, p, q), second) {
            (Some(first), Some(second)) => {
                let [a, b] = both.expect("both planes set up alone");
                assert_eq!(planes(Some(a)), planes(Some(first)), "{o:?} {p:?} {q:?}");
                assert_eq!(planes(Some(b)), planes(Some(second)), "{o:?} {p:?} {q:?}");
            }
            _ => assert!(both.is_none(), "{o:?} {p:?} {q:?}"),
        }
        fast.is_some()
    }

    /// Every division path against `u128` arithmetic.
    fn check_division(d: u32, n: u64, rest: u64) {
        for path in PATHS {
            let mut divisor = GradientDivisor::with_path(d, path);
            let (q, r) = (n / u64::from(d), n % u64::from(d));
            let expected = (q < Divisor::QUOTIENT_LIMIT).then_some((q, r));
            assert_eq!(divisor.div_rem(n), expected, "{n} / {d} ({path:?})");
            let exact = (u128::from(rest) << 16) + u128::from(d / 2);
            let fraction = (exact / u128::from(d)) as u64;
            assert_eq!(
                divisor.fraction(rest),
                Some(fraction),
                "{rest} / {d} ({path:?})"
            );
        }
        // The f64 path's gradient against i128, both signs: floored.
        for signed in [n as i64, -(n as i64)] {
            let exact = ((i128::from(signed) << 16) + i128::from(d / 2)).div_euclid(i128::from(d));
            let expected = (signed.unsigned_abs() / u64::from(d) < Divisor::QUOTIENT_LIMIT)
                .then_some(exact as i64);
            assert_eq!(
                float_gradient(signed, d, gradient_inverse(d)),
                expected,
                "{signed} / {d}"
            );
        }
        if d < 1 << 23 && n < 1 << 57 {
            // The byte steps themselves, past the quotient limit too.
            let expected = (n / u64::from(d), n % u64::from(d));
            assert_eq!(div_rem_by_bytes(n, d), expected, "{n} / {d}");
        }
    }

    /// The f64 path where its estimate is most likely to miss: numerators
    /// whose quotient `(n·2^16 + floor(d / 2)) / d` is an integer, or an
    /// integer plus `1 / d` or minus `1 / d`, for large `|n|` (where `n as
    /// f64` rounds) and odd `d` of every size, both signs.
    #[test]
    fn float_gradient_at_exact_quotients() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        // The inverse of an odd d modulo 2^16 (Newton: each step doubles
        // the correct bits).
        let inverse = |d: i128| {
            let mut v = d;
            for _ in 0..4 {
                v = (v * (2 - d * v)).rem_euclid(1 << 16);
            }
            v
        };
        for round in 0..200_000 {
            let d = (((next() as u32) >> (next() % 31)) | 1).min((1 << 31) - 1);
            let (di, h) = (i128::from(d), i128::from(d / 2));
            let r = [0, 1, di - 1][round % 3].min(di - 1);
            // g·d + r = n·2^16 + h needs g ≡ (h - r)·d^-1 (mod 2^16).
            let low = ((h - r) * inverse(di)).rem_euclid(1 << 16);
            let high = i128::from(next() % (1 << 26)) - (1 << 25);
            let g = high * (1 << 16) + low;
            let numerator = g * di + r - h;
            assert_eq!(numerator.rem_euclid(1 << 16), 0);
            let n = numerator >> 16;
            let limit = i128::from(Divisor::QUOTIENT_LIMIT) * di;
            let expected = (n.abs() < limit).then_some(g as i64);
            assert_eq!(
                float_gradient(n as i64, d, gradient_inverse(d)),
                expected,
                "{n} / {d}"
            );
        }
    }

    #[test]
    fn gradient_division_is_exact() {
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for round in 0..300_000 {
            // Divisors of every size, small ones often (where the rounding
            // boundaries are dense), and both sides of the 2^23 switch.
            let d = match round % 4 {
                0 => (next() % 1000 + 1) as u32,
                1 => ((1 << 23) - 2 + next() % 4) as u32,
                _ => ((next() as u32) >> (next() % 31)).clamp(1, (1 << 31) - 1),
            };
            let n = match round % 5 {
                0 => next() % (1 << 32),
                1 => u64::from(d) * (next() % (1 << 10)) + next() % 3,
                // Around the largest quotient computed.
                2 => u64::from(d) * Divisor::QUOTIENT_LIMIT - 1 + next() % 3,
                // Where the byte steps' first dividend changes width.
                3 => (1u64 << (32 + 8 * (next() % 4))) - 1 + next() % 3,
                _ => next() >> (7 + next() % 57),
            };
            let rest = match round % 2 {
                0 => next() % u64::from(d),
                // Just below a multiple of d after the shift: the boundary.
                _ => ((u64::from(d) * (next() % (1 << 16))) >> 16).min(u64::from(d) - 1),
            };
            check_division(d, n, rest);
        }
    }

    #[test]
    fn triangle_planes_at_the_extremes() {
        let depths = [0, DEPTH_MAX, DEPTH_MAX / 2, 1];
        let offsets = [
            0,
            1,
            255,
            256,
            4095,
            (1 << 15) - 1,
            (1 << 16) - 1,
            -(1 << 16) + 1,
        ];
        let (mut count, mut set_up) = (0, 0);
        for &(ox, oy) in &[(0, 0), (-G, -G), (G - (1 << 16), 17)] {
            for &px in &offsets {
                for &qy in &offsets {
                    let (p, q) = ((ox + px, oy + 3), (ox + 5, oy + qy));
                    if [p.0, p.1, q.0, q.1].iter().any(|c| c.abs() > G) {
                        continue;
                    }
                    for k in 0..depths.len() {
                        let z = |j: usize| depths[(k + j) % depths.len()];
                        set_up += usize::from(check_triangle_plane(
                            v(ox, oy, z(0)),
                            v(p.0, p.1, z(1)),
                            v(q.0, q.1, z(2)),
                        ));
                        count += 1;
                    }
                }
            }
        }
        assert!(
            count > 500 && set_up > count / 4,
            "{set_up} of {count} set up"
        );
    }

    proptest! {
        #[test]
        fn triangle_planes_match_the_general_plane(
            o in (extreme_coordinate(), extreme_coordinate(), extreme_depth()),
            p in (-(1i32 << 16) + 1..1 << 16, -(1i32 << 16) + 1..1 << 16, extreme_depth()),
            q in (-(1i32 << 12)..1 << 12, -(1i32 << 12)..1 << 12, extreme_depth()),
        ) {
            let o = v(o.0.clamp(-G + (1 << 16), G - (1 << 16)), o.1.clamp(-G + (1 << 16), G - (1 << 16)), o.2);
            check_triangle_plane(o, v(o.x + p.0, o.y + p.1, p.2), v(o.x + q.0, o.y + q.1, q.2));
        }

        #[test]
        fn random_polygons_near_the_limits(
            poly in prop::collection::vec((extreme_coordinate(), extreme_coordinate(), extreme_depth()), 3..40)
        ) {
            let poly: Vec<ScreenVertex> = poly.into_iter().map(|(x, y, z)| v(x, y, z)).collect();
            check(&poly);
        }
    }
}
