//! The integer front end for [quantized meshes](crate::front::quantized):
//! model to clip space, the clip tests, the projection to the core's
//! sub-pixel grid and depth, and face normals in view space, all in integer
//! arithmetic. Nothing per vertex or per face touches floating point, so a
//! core without an FPU (the RP2040's Cortex-M0+) pays no software floats
//! there.
//!
//! The matrices are turned into integers once per draw, exactly: each
//! `f32` entry is read from its bits and every product, sum, quotient and
//! square root after that is integer arithmetic. So every target computes
//! the same integers, and the same frames, bit for bit, whatever its
//! floating-point unit or library would round (the RP2040's ROM `f64`
//! routines, for one, do not round as the host does).
//!
//! # Units and ranges
//!
//! `A` is the matrix from a quantized position `(q, 1)` to clip space: the
//! `f32` product `projection · view · model` (as the `f32` front end
//! computes it) times the dequantization `centre + radius · q / 32767`,
//! in exact rational arithmetic. It is stored as integers scaled by `2^T`,
//! `T` chosen per draw so that every stored coefficient is at most `2^30`
//! in magnitude:
//!
//! | quantity | definition | bound | held in |
//! |---|---|---|---|
//! | `a[i][j]`, `j < 3` | `round(A[i][j] · 2^T)` | `<= 2^30` | `i32` |
//! | `b[i]` | `round(A[i][3] · 2^(T - 15))` | `<= 2^30` | `i32` |
//! | `q[j]` | quantized coordinate | `<= 2^15` | `i16` |
//! | clip coordinate `c[i]` | `sum a[i][j]·q[j] + b[i]·2^15` (clip value `· 2^T`) | `< 2^47` | `i64` |
//! | guard test products | `abs(c_x) · W`, `(8192 - W) · c_w` | `< 2^60` | `i64` |
//! | `w'` | `c_w` shifted right until below `2^31` | `< 2^31` | `i64` |
//! | projection numerators | `x'·128W`, `y'·128H` (`abs(x') <= 8192·w'/W`); `z'·2^23` (`abs(z') <= w'`) | `< 2^52`, `< 2^55` | `i64` |
//! | rotation `r[i][j]` | `round(R[i][j] · 2^15)` for the view rotation `R` | `<= 2^15` | `i32` |
//! | rotated normal sum | `sum r[i][j]·n[j]` (`abs(n) <= 32776`, rows of `r` unit to `2^-14`) | `< 2^30 · (1 + 2^-11)` | `i32` |
//!
//! # Error
//!
//! Each stored coefficient is off by at most half a unit of `2^-T`, so
//! each clip coordinate is off the exact `A · (q, 1)` by at most
//! `4 · 2^15 / 2 = 2^16` units, `2^(16 - T)` in clip space; shifting `w`
//! into 31 bits adds less than one unit of `w'`. The projection's
//! reciprocal and final rounding add at most `0.5 + 2^-8` (see
//! [`FixedFrame::project`]). So a projected coordinate is within
//! `0.5 + 2^-8 + 128·W·2^(16 - T)·(1 + g) / w` sub-pixel steps of the exact
//! projection of the quantized position, `g` being how far outside the
//! frame the vertex lies (`abs(x_ndc)`), and depth within
//! `0.5 + 2^-8 + 2^23·2^(17 - T) / w` units. With the reference camera and any
//! mesh normalised to its bounding sphere `T` is about 43 and `w` about
//! 3: a millionth of a sub-pixel step. `T` below [`MIN_SCALE_BITS`] (a
//! matrix scaling a quantized unit beyond `2^13`) falls back to the `f32`
//! front end. The tests check the bound against `f64` for random
//! matrices and positions.

use crate::arith::divide::{div_round_away_i128, reciprocal62};
use crate::arith::wide::{
    DOT3_COEFFICIENT_MAX, dot3_plus, leading_zeros_u64, mul_i64_i32, mul_u32_i32, shl_i64, shr_i64,
};
use crate::front::geometry::Mat4;
use crate::limits::CLIP_BAND_PX;
use crate::limits::{DEPTH_MAX, SUBPIXEL_STEPS};
use crate::limits::{NORMAL_SCALE, POSITION_SCALE};
use crate::raster::vertex::ScreenVertex;

/// Smallest scale exponent `T` the integer front end works with: below it
/// the clip coordinates would be coarser than `2^-16` and the `f32` front
/// end is used instead.
pub const MIN_SCALE_BITS: i32 = 16;
/// Largest scale exponent `T`: far beyond what any matrix needs, it keeps
/// the shifts of the set-up in range.
const MAX_SCALE_BITS: i32 = 60;

/// A point in clip space, scaled by `2^T` (see the module's table).
pub type FixedClip = [i64; 4];

/// The integer transform and projection of one draw.
#[derive(Debug, Clone, Copy)]
pub struct FixedFrame {
    a: [[i32; 3]; 4],
    /// `b[i] · 2^15`, the translation column in clip units.
    offset: [i64; 4],
    width: i64,
    height: i64,
    /// `2 · CLIP_BAND_PX - width`: `abs(x) · width <= guard_x · w` inside
    /// the clipping band.
    guard_x: i64,
    guard_y: i64,
    /// The view rotation of normals in units of `2^-15`, when the
    /// model-view matrix is a rotation times a uniform scale.
    rotation: Option<[[i32; 3]; 3]>,
    /// The scale exponent `T` (the tests read it).
    #[cfg_attr(not(test), allow(dead_code))]
    scale_bits: i32,
}

/// A finite `f32`, exactly: `m · 2^e` with `abs(m) < 2^24`, or a product
/// of two (`abs(m) < 2^48`): `i64`, whose arithmetic a 32-bit core makes
/// in far less code than `i128`'s.
#[derive(Debug, Clone, Copy)]
struct Exact {
    m: i64,
    e: i32,
}

impl Exact {
    /// `None` for NaN and infinities. Read from the bits, so the value is
    /// the same on every target whatever its floating-point unit (or ROM
    /// routines) would round.
    #[inline(never)]
    fn of(v: f32) -> Option<Self> {
        if !v.is_finite() {
            return None;
        }
        let bits = v.to_bits();
        let biased = ((bits >> 23) & 0xff) as i32;
        let fraction = i64::from(bits & 0x7f_ffff);
        let (m, e) = if biased == 0 {
            (fraction, -149)
        } else {
            (fraction | 0x80_0000, biased - 150)
        };
        Some(Self {
            m: if bits >> 31 == 1 { -m } else { m },
            e,
        })
    }

    /// The product, exactly (`abs(m) < 2^48`).
    fn mul(self, other: Self) -> Self {
        Self {
            m: self.m * other.m,
            e: self.e + other.e,
        }
    }

    /// Exponent bound: `abs(value) < 2^top` (`i32::MIN / 2` for zero).
    fn top(self) -> i32 {
        if self.m == 0 {
            i32::MIN / 2
        } else {
            bit_length(u128::from(self.m.unsigned_abs())) + self.e
        }
    }
}

/// Bits of `v`: `v < 2^bit_length(v)`.
fn bit_length(v: u128) -> i32 {
    128 - v.leading_zeros() as i32
}

/// `v · 2^k`, rounded to nearest (ties away from zero) when `k < 0`; the
/// caller keeps `v · 2^k` below `2^126`.
#[inline(never)]
fn scale_round(v: i128, k: i32) -> i128 {
    if v == 0 {
        0
    } else if k >= 0 {
        v << k
    } else if k <= -126 {
        0
    } else {
        let half = 1i128 << (-k - 1);
        if v >= 0 {
            (v + half) >> -k
        } else {
            -((-v + half) >> -k)
        }
    }
}

/// The exact sum of `terms` (at most four of at most 48 bits), as an
/// integer at scale `2^base`, `base` 100 bits below the largest term (so
/// the sum stays below `2^103`); smaller bits are dropped (rounded), the
/// same way on every target.
#[inline(never)]
fn exact_sum(terms: &[Exact]) -> (i128, i32) {
    let top = terms.iter().map(|t| t.top()).max().unwrap_or(i32::MIN / 2);
    let base = top - 100;
    let sum = terms
        .iter()
        .filter(|t| t.m != 0)
        .map(|t| scale_round(i128::from(t.m), t.e - base))
        .sum();
    (sum, base)
}

/// `floor(sqrt(v))`, bit by bit.
#[inline(never)]
fn isqrt(v: u128) -> u128 {
    let mut root = 0u128;
    let mut bit = 1u128 << ((bit_length(v).max(1) - 1) & !1);
    let mut rest = v;
    while bit != 0 {
        if rest >= root + bit {
            rest -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

/// `n / d` rounded to the nearest integer (ties up), for `d > 0`.
fn div_round(n: i64, d: i64) -> i64 {
    (2 * n + d).div_euclid(2 * d)
}

impl FixedFrame {
    /// The integer frame for the `f32` matrix `mvp` (model space to clip
    /// space), a mesh quantized in the sphere `centre`, `radius`, a frame
    /// `width` x `height`, and the `f32` model-view matrix (for normals).
    /// Every step after reading the `f32` values is exact integer
    /// arithmetic, so the integers are the same on every target. `None`
    /// when an input is not finite or the matrix scales a quantized unit
    /// beyond `2^13`: the caller then uses the `f32` front end.
    #[inline(never)]
    pub fn new(
        mvp: &Mat4,
        model_view: &Mat4,
        centre: [f32; 3],
        radius: f32,
        width: u16,
        height: u16,
    ) -> Option<Self> {
        let radius = Exact::of(radius)?;
        let centre = [
            Exact::of(centre[0])?,
            Exact::of(centre[1])?,
            Exact::of(centre[2])?,
        ];
        let mut linear = [[Exact { m: 0, e: 0 }; 3]; 4];
        let mut offset = [(0i128, 0i32); 4];
        for (i, row) in mvp.m.iter().enumerate() {
            let m = [
                Exact::of(row[0])?,
                Exact::of(row[1])?,
                Exact::of(row[2])?,
                Exact::of(row[3])?,
            ];
            // A[i][j] = m[j] · radius / 32767 (the division comes with T).
            for j in 0..3 {
                linear[i][j] = m[j].mul(radius);
            }
            // A[i][3] = m · centre + m[3], summed exactly.
            offset[i] = exact_sum(&[
                m[0].mul(centre[0]),
                m[1].mul(centre[1]),
                m[2].mul(centre[2]),
                m[3],
            ]);
        }
        // T: every |a| (below 2^(top - 14), the division by 32767 taking
        // more than 2^14) and every |b| (2^-15 of the offset) at most 2^30.
        let mut largest = i32::MIN / 2;
        for i in 0..4 {
            for l in &linear[i] {
                largest = largest.max(l.top() - 14);
            }
            let (sum, base) = offset[i];
            if sum != 0 {
                largest = largest.max(bit_length(sum.unsigned_abs()) + base - 15);
            }
        }
        let t = (30 - largest).min(MAX_SCALE_BITS);
        if t < MIN_SCALE_BITS {
            return None;
        }
        let scale = i128::from(POSITION_SCALE);
        let coefficient = |l: Exact| {
            if l.m == 0 {
                return 0;
            }
            let k = l.e + t;
            let q = if k >= 0 {
                div_round_away_i128(i128::from(l.m) << k, scale)
            } else if k > -80 {
                div_round_away_i128(i128::from(l.m), scale << -k)
            } else {
                0
            };
            q as i32
        };
        let a = linear.map(|row| row.map(coefficient));
        // At most 2^44 / 32767 < 2^30 by the choice of T; `clip` relies on
        // it, so it is checked rather than only argued.
        if a.iter()
            .flatten()
            .any(|c| c.unsigned_abs() > DOT3_COEFFICIENT_MAX.unsigned_abs())
        {
            return None;
        }
        let b = offset.map(|(sum, base)| scale_round(sum, base + t - 15) as i32);
        let (w, h) = (i64::from(width), i64::from(height));
        let band = 2 * CLIP_BAND_PX as i64;
        // `inside` relies on the band holding the frame: true for every
        // frame the core accepts (at most MAX_FRAME_SIZE each way).
        if w > band - w || h > band - h {
            return None;
        }
        Some(Self {
            a,
            offset: b.map(|b| i64::from(b) << 15),
            width: w,
            height: h,
            guard_x: band - w,
            guard_y: band - h,
            rotation: view_rotation(model_view),
            scale_bits: t,
        })
    }

    /// The scale exponent `T` of this draw's coefficients.
    #[cfg(test)]
    pub fn scale_bits(&self) -> i32 {
        self.scale_bits
    }

    /// The rows that give clip `x`, `y` and `w`: coefficients (each at most
    /// `2^30`) and offsets (`b · 2^15`, at most `2^45`).
    pub(crate) fn xyw_rows(&self) -> ([[i32; 3]; 3], [i64; 3]) {
        (
            [self.a[0], self.a[1], self.a[3]],
            [self.offset[0], self.offset[1], self.offset[3]],
        )
    }

    /// Clip coordinates of a quantized position (units of `2^-T`).
    #[inline]
    pub fn clip(&self, q: [i16; 3]) -> FixedClip {
        // Each coefficient is at most 2^30 = DOT3_COEFFICIENT_MAX, so each
        // product is at most 2^45, and each row below 2^47.
        let row = |i: usize| dot3_plus(self.a[i], q, self.offset[i]);
        [row(0), row(1), row(2), row(3)]
    }

    /// Whether the point lies in front of the eye, inside the near and far
    /// planes and inside the clipping band, so it can be projected as it
    /// is (the same planes as the `f32` front end's test).
    #[inline]
    pub fn inside(&self, c: &FixedClip) -> bool {
        let [x, y, z, w] = *c;
        w > 0
            && z >= -w
            && z <= w
            // The band holds the frame (guard >= size), so a point of the
            // frame (|x| <= w) passes with no product. Frame sizes and
            // guard bands fit i32; clip coordinates are below 2^48 (see
            // `clip`): each product is below 2^61.
            && (x.abs() <= w
                || mul_i64_i32(x.abs(), self.width as i32) <= mul_i64_i32(w, self.guard_x as i32))
            && (y.abs() <= w
                || mul_i64_i32(y.abs(), self.height as i32) <= mul_i64_i32(w, self.guard_y as i32))
    }

    /// The screen vertex of a point [`Self::inside`] the clipping band:
    /// sub-pixel `x`, `y` and Q0.24 depth.
    ///
    /// `w` is normalised into `[2^30, 2^31)` (x, y and z shifted with it),
    /// and `R ~ 2^62 / w` comes from [`reciprocal62`]: one 32-bit division
    /// and one Newton step, no 64-bit division. A point within twice the
    /// frame (`abs(x'), abs(y') < 2^31`, so `abs(x_ndc) < 2`) then costs
    /// two 64-bit products per coordinate: `x'·R` (`< 2^63`), shifted to
    /// `x_ndc · 2^31`, times `128·W` (`< 2^51`), rounded. Its error is the
    /// final rounding plus `128·W·(2^-28·abs(x_ndc) + 2^-31)`, below
    /// `0.5 + 2^-8` sub-pixel steps and depth units. Points further out (in
    /// the clipping band beyond the frame) take exact 64-bit divisions.
    #[inline]
    pub fn project(&self, c: &FixedClip) -> Option<ScreenVertex> {
        let [x, y, z, w] = *c;
        if w <= 0 {
            return None;
        }
        // Normalise w to 31 bits; |x|, |y| <= 2^13·w and |z| <= w keep
        // every shifted value below 2^44.
        // (w > 0 and below 2^48: the shift is in (-31, 17], and each shift
        // takes the two words, not a library call, on ARMv6-M.)
        let shift = 64 - leading_zeros_u64(w as u64) as i32 - 31;
        let (x, y, z, w) = if shift >= 0 {
            let s = shift as u32;
            (shr_i64(x, s), shr_i64(y, s), shr_i64(z, s), shr_i64(w, s))
        } else {
            let s = shift.unsigned_abs();
            (shl_i64(x, s), shl_i64(y, s), shl_i64(z, s), shl_i64(w, s))
        };
        let half = i64::from(SUBPIXEL_STEPS / 2);
        let (hw, hh) = (half * self.width, half * self.height);
        let r = reciprocal62(w as u32) as i64;
        let near = |v: i64| v.unsigned_abs() < 1 << 31;
        let (sx, sy) = if near(x) && near(y) {
            // v·R ~ (v/w)·2^62 with |v/w| < 2: below 2^63; shifted, below
            // 2^32, and times half the frame (below 2^20) below 2^52. (R <
            // 2^32 and |v| < 2^31: 32-bit operands.)
            let scaled = |v: i64, half_size: i64| {
                let ndc = mul_u32_i32(r as u32, v as i32) >> 31;
                (mul_i64_i32(ndc, half_size as i32) + (1 << 30)) >> 31
            };
            (hw + scaled(x, hw), hh - scaled(y, hh))
        } else {
            (hw + div_round(x * hw, w), hh - div_round(y * hh, w))
        };
        // |z| <= w: z·R ~ (z/w)·2^62, below 2^63.
        // (|z| <= w < 2^31 inside the band: a 32-bit operand.)
        let sz = (1 << 23) + (((mul_u32_i32(r as u32, z as i32) >> 38) + 1) >> 1);
        let sz = sz.clamp(0, i64::from(DEPTH_MAX));
        ScreenVertex::new(i32::try_from(sx).ok()?, i32::try_from(sy).ok()?, sz as u32).ok()
    }

    /// A face's normal (units of `1/32767`, as stored) rotated into view
    /// space, in the same units; `None` when the model-view matrix is not a
    /// rotation times a uniform scale (normals then come from the `f32`
    /// path). For the normals a [`QuantizedMesh`] accepts (length at most
    /// `32776`), each sum is below `2^30 · (1 + 2^-11)` by Cauchy-Schwarz
    /// (the rows of the rotation are unit to `2^-13`), so `i32` holds it
    /// and each component is below `2^15 · (1 + 2^-11)`; for any other
    /// `i16` input the arithmetic wraps: some normal, never a panic.
    ///
    /// [`QuantizedMesh`]: crate::front::quantized::QuantizedMesh
    #[inline]
    pub fn view_normal(&self, n: [i16; 3]) -> Option<[i32; 3]> {
        let r = self.rotation.as_ref()?;
        let n = n.map(i32::from);
        Some(core::array::from_fn(|i| {
            let [r0, r1, r2] = r[i];
            r0.wrapping_mul(n[0])
                .wrapping_add(r1.wrapping_mul(n[1]))
                .wrapping_add(r2.wrapping_mul(n[2]))
                .wrapping_add(1 << 14)
                >> 15
        }))
    }
}

/// The unit vector along `v` in units of `1/32767` (`round(32767 · v /
/// abs(v))` per component), in exact integer arithmetic from the `f32`
/// bits with an integer square root: the same on every target. `None` for
/// a zero or non-finite vector.
#[inline(never)]
pub fn unit_q15(v: [f32; 3]) -> Option<[i32; 3]> {
    let e = [Exact::of(v[0])?, Exact::of(v[1])?, Exact::of(v[2])?];
    let top = e.iter().map(|x| x.top()).max()?;
    if top == i32::MIN / 2 {
        return None;
    }
    // Each entry to about 30 bits: far finer than the 2^-15 result, and
    // the quotients below then take 64-bit divisions (`x·2^15 < 2^46`,
    // the length below 2^32).
    let base = top - 30;
    // At most 2^30 each (as in `view_rotation`): the squares' sum is below
    // 2^62, exact in `i64`.
    let mut x = [0i64; 3];
    for (c, e) in x.iter_mut().zip(&e) {
        *c = i64::try_from(scale_round(i128::from(e.m), e.e - base)).ok()?;
    }
    let length = isqrt(u128::from(
        (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).unsigned_abs(),
    )) as i128;
    if length == 0 {
        return None;
    }
    Some(x.map(|c| div_round_away_i128(i128::from(c) * i128::from(NORMAL_SCALE), length) as i32))
}

/// `round(v · 2^bits)` for a finite `f32` `v` with `abs(v) <= 1`, exactly
/// (from its bits); 0 for anything else.
pub fn fraction_bits(v: f32, bits: i32) -> i32 {
    match Exact::of(v) {
        Some(x) if v.abs() <= 1.0 => scale_round(i128::from(x.m), x.e + bits) as i32,
        _ => 0,
    }
}

/// The rotation of a model-view matrix that is a rotation times a uniform
/// scale (columns of equal length and orthogonal, to `2^-14` of their
/// squared length), in units of `2^-15`; `None` for any other matrix. In
/// integer arithmetic from the `f32` entries (each rounded to a multiple
/// of `2^-30` of the largest: well below the result's `2^-15`), with an
/// integer square root: the same on every target.
#[inline(never)]
fn view_rotation(m: &Mat4) -> Option<[[i32; 3]; 3]> {
    let mut entries = [[Exact { m: 0, e: 0 }; 3]; 3];
    for (i, row) in entries.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = Exact::of(m.m[i][j])?;
        }
    }
    let top = entries.iter().flatten().map(|x| x.top()).max()?;
    if top == i32::MIN / 2 {
        return None;
    }
    // Each entry to about 30 bits: far finer than the 2^-15 result, and
    // the quotients below then take 64-bit divisions (`x·2^15 < 2^46`,
    // the length below 2^32).
    let base = top - 30;
    // Each entry is below 2^top, so at most 2^30 scaled: its products at
    // most 2^60 and their sums of three below 2^62, exact in `i64` (whose
    // products a 32-bit core makes far more cheaply than `i128`'s: 3.5 KB
    // less of a Cortex-M0+ firmware's flash).
    let mut v = [[0i64; 3]; 3];
    for (row, exact) in v.iter_mut().zip(&entries) {
        for (x, e) in row.iter_mut().zip(exact) {
            *x = i64::try_from(scale_round(i128::from(e.m), e.e - base)).ok()?;
        }
    }
    let col = |j: usize| [v[0][j], v[1][j], v[2][j]];
    let dot = |a: [i64; 3], b: [i64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (c0, c1, c2) = (col(0), col(1), col(2));
    let n0 = dot(c0, c0);
    let tolerance = n0 >> 14;
    let similar = (dot(c1, c1) - n0).abs() <= tolerance
        && (dot(c2, c2) - n0).abs() <= tolerance
        && dot(c0, c1).abs() <= tolerance
        && dot(c0, c2).abs() <= tolerance
        && dot(c1, c2).abs() <= tolerance;
    if !similar || n0 == 0 {
        return None;
    }
    let length = isqrt(u128::from(n0.unsigned_abs())) as i128;
    Some(v.map(|row| row.map(|x| div_round_away_i128(i128::from(x) << 15, length) as i32)))
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::front::geometry::{Vec3, radians};
    use crate::front::scene::Camera;
    use proptest::prelude::*;

    fn to64(m: &Mat4) -> [[f64; 4]; 4] {
        m.m.map(|row| row.map(f64::from))
    }

    fn mvp(yaw: f32, pitch: f32, camera: &Camera) -> (Mat4, Mat4) {
        let model = Mat4::rotation_x(radians(pitch)).mul(&Mat4::rotation_y(radians(yaw)));
        let mv = camera.view.mul(&model);
        (camera.projection.mul(&mv), mv)
    }

    /// The exact projection of a quantized position through the `f32`
    /// matrix `m` (its entries exact in `f64`), in `f64`.
    fn exact(
        m: &[[f64; 4]; 4],
        centre: [f32; 3],
        radius: f32,
        q: [i16; 3],
        w: u16,
        h: u16,
    ) -> Option<(f64, f64, f64)> {
        let s = f64::from(radius) / f64::from(POSITION_SCALE);
        let p = [0, 1, 2].map(|k| f64::from(centre[k]) + f64::from(q[k]) * s);
        let c = m.map(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3]);
        (c[3] > 0.0).then(|| {
            (
                (c[0] / c[3] + 1.0) * 0.5 * f64::from(w) * 256.0,
                (1.0 - c[1] / c[3]) * 0.5 * f64::from(h) * 256.0,
                ((c[2] / c[3] + 1.0) * 0.5 * 16_777_216.0).clamp(0.0, f64::from(DEPTH_MAX)),
            )
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        /// Every projected vertex is within the stated bound of the exact
        /// projection, for random views, sphere sizes, frames and points.
        #[test]
        fn projection_within_the_bound(
            yaw in -180.0f32..180.0,
            pitch in -90.0f32..90.0,
            radius in 0.01f32..1000.0,
            centre in prop::array::uniform3(-100.0f32..100.0),
            size in (1u16..=4096, 1u16..=4096),
            q in prop::array::uniform3(-32767i16..=32767),
            distance in 1.5f32..50.0,
        ) {
            // The mesh normalised to its sphere, then pushed `distance`
            // away: the reference camera sees it whole when distance > 1.
            let camera = Camera::perspective(
                Mat4::translation(Vec3::new(0.0, 0.0, -distance)),
                45.0, size.0, size.1, 0.1, 100.0,
            );
            let s = 1.0 / radius;
            let normalise = Mat4::scale(Vec3::new(s, s, s))
                .mul(&Mat4::translation(-Vec3::new(centre[0], centre[1], centre[2])));
            let (m32, mv) = mvp(yaw, pitch, &camera);
            let m32 = m32.mul(&normalise);
            let m = to64(&m32);
            let frame = FixedFrame::new(&m32, &mv.mul(&normalise), centre, radius, size.0, size.1).unwrap();
            let c = frame.clip(q);
            // Points outside the clipping band are the f64 clipper's.
            prop_assume!(frame.inside(&c));
            {
                let v = frame.project(&c).unwrap();
                let (ex, ey, ez) = exact(&m, centre, radius, q, size.0, size.1).unwrap();
                let w = {
                    let sc = f64::from(radius) / f64::from(POSITION_SCALE);
                    let p = [0, 1, 2].map(|k| f64::from(centre[k]) + f64::from(q[k]) * sc);
                    m[3][0] * p[0] + m[3][1] * p[1] + m[3][2] * p[2] + m[3][3]
                };
                // The bound of the module's notes, with this draw's T, plus
                // the f64 reference's own rounding.
                let t = frame.scale_bits();
                let unit = 2f64.powi(16 - t);
                let g = |e: f64, size: u16| (e / (128.0 * f64::from(size)) - 1.0).abs();
                let bound = |size: u16, gg: f64| 0.5 + 2f64.powi(-8) + 128.0 * f64::from(size) * unit * (1.0 + gg) / w + 1e-6;
                prop_assert!((f64::from(v.x) - ex).abs() <= bound(size.0, g(ex, size.0)), "x {} vs {}", v.x, ex);
                prop_assert!((f64::from(v.y) - ey).abs() <= bound(size.1, g(ey, size.1)), "y {} vs {}", v.y, ey);
                let zb = 0.5 + 2f64.powi(-8) + 2f64.powi(23) * 2.0 * unit / w + 1e-6;
                prop_assert!((f64::from(v.z) - ez).abs() <= zb, "z {} vs {}", v.z, ez);
            }
        }
    }

    /// `round(n / d)`, ties away from zero, straight from the definition
    /// in `i128` (no fast path).

    #[test]
    fn extremes_stay_in_range() {
        // The largest coefficients T allows, the largest quantized
        // coordinates: no overflow (overflow checks are on in tests).
        let camera = Camera::reference(4096, 4096);
        let (m, mv) = mvp(45.0, 45.0, &camera);
        let frame = FixedFrame::new(&m, &mv, [0.0; 3], 1.0, 4096, 4096).unwrap();
        for q in [
            [32767, 32767, 32767],
            [-32767, -32767, -32767],
            [32767, -32767, 32767],
        ] {
            let c = frame.clip(q);
            assert!(c.iter().all(|v| v.abs() < 1 << 47));
            if frame.inside(&c) {
                assert!(frame.project(&c).is_some());
            }
        }
        // A coefficient at the 2^30 limit on every entry.
        let f = FixedFrame {
            a: [[1 << 30; 3]; 4],
            offset: [1 << 45; 4],
            width: 1,
            height: 1,
            guard_x: 8191,
            guard_y: 8191,
            rotation: None,
            scale_bits: 30,
        };
        let c = f.clip([32767; 3]);
        assert!(c.iter().all(|v| v.abs() < 1 << 47));
        assert!(f.inside(&c) && f.project(&c).is_some());
        let c = f.clip([-32767; 3]);
        assert!(!f.inside(&c));
    }

    /// `unit_q15` as it was written in `i128` throughout.
    fn unit_q15_wide(v: [f32; 3]) -> Option<[i32; 3]> {
        let e = [Exact::of(v[0])?, Exact::of(v[1])?, Exact::of(v[2])?];
        let top = e.iter().map(|x| x.top()).max()?;
        if top == i32::MIN / 2 {
            return None;
        }
        let x = e.map(|x| scale_round(i128::from(x.m), x.e - (top - 30)));
        let length = isqrt((x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).unsigned_abs()) as i128;
        if length == 0 {
            return None;
        }
        Some(x.map(|c| div_round_away_i128(c * i128::from(NORMAL_SCALE), length) as i32))
    }

    /// `view_rotation` as it was written in `i128` throughout.
    fn view_rotation_wide(m: &Mat4) -> Option<[[i32; 3]; 3]> {
        let mut entries = [[Exact { m: 0, e: 0 }; 3]; 3];
        for (i, row) in entries.iter_mut().enumerate() {
            for (j, entry) in row.iter_mut().enumerate() {
                *entry = Exact::of(m.m[i][j])?;
            }
        }
        let top = entries.iter().flatten().map(|x| x.top()).max()?;
        if top == i32::MIN / 2 {
            return None;
        }
        let v = entries.map(|row| row.map(|x| scale_round(i128::from(x.m), x.e - (top - 30))));
        let col = |j: usize| [v[0][j], v[1][j], v[2][j]];
        let dot = |a: [i128; 3], b: [i128; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (c0, c1, c2) = (col(0), col(1), col(2));
        let n0 = dot(c0, c0);
        let tolerance = n0 >> 14;
        let similar = (dot(c1, c1) - n0).abs() <= tolerance
            && (dot(c2, c2) - n0).abs() <= tolerance
            && dot(c0, c1).abs() <= tolerance
            && dot(c0, c2).abs() <= tolerance
            && dot(c1, c2).abs() <= tolerance;
        if !similar || n0 == 0 {
            return None;
        }
        let length = isqrt(n0.unsigned_abs()) as i128;
        Some(v.map(|row| row.map(|x| div_round_away_i128(x << 15, length) as i32)))
    }

    /// Any `f32` from its bits, NaN and infinities included.
    fn any_f32() -> impl Strategy<Value = f32> {
        any::<u32>().prop_map(f32::from_bits)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// `unit_q15` in `i64` is its `i128` form, over every `f32`
        /// (the largest and smallest magnitudes, subnormals, mixed scales).
        #[test]
        fn unit_q15_is_its_wide_form(v in prop::array::uniform3(any_f32())) {
            prop_assert_eq!(unit_q15(v), unit_q15_wide(v));
        }

        /// `view_rotation` in `i64` is its `i128` form: for rotations
        /// scaled by any power of two (up to the `f32` range's ends) and
        /// nudged off orthogonal, and for any entries at all.
        #[test]
        fn view_rotation_is_its_wide_form(
            yaw in -180.0f32..180.0,
            pitch in -90.0f32..90.0,
            scale_bits in -140i32..=125,
            nudge in prop::array::uniform3(-1.0e-3f32..1.0e-3),
            raw in prop::array::uniform16(any_f32()),
        ) {
            let rotation = Mat4::rotation_x(radians(pitch)).mul(&Mat4::rotation_y(radians(yaw)));
            let mut m = rotation;
            let scale = 2.0f64.powi(scale_bits) as f32;
            for (k, row) in m.m.iter_mut().take(3).enumerate() {
                for (j, x) in row.iter_mut().take(3).enumerate() {
                    *x = (*x + if j == k { nudge[k] } else { 0.0 }) * scale;
                }
            }
            prop_assert_eq!(view_rotation(&m), view_rotation_wide(&m));
            let arbitrary = Mat4 { m: core::array::from_fn(|i| core::array::from_fn(|j| raw[4 * i + j])) };
            prop_assert_eq!(view_rotation(&arbitrary), view_rotation_wide(&arbitrary));
        }
    }

    proptest! {
        /// The clip-band test against its definition in i128, around the
        /// frame's edge and the band's, for any frame the core accepts.
        #[test]
        fn inside_is_the_band_test(
            width in 1u16..=4096,
            height in 1u16..=4096,
            w in 1i64..(1 << 47),
            fx in -3.0f64..3.0,
            fy in -3.0f64..3.0,
            fz in -1.5f64..1.5,
            frame_units: bool,
        ) {
            let camera = Camera::reference(width, height);
            let (m, mv) = mvp(30.0, 20.0, &camera);
            let frame = FixedFrame::new(&m, &mv, [0.0; 3], 1.0, width, height).unwrap();
            // Points at multiples of the frame's half-width or of the
            // band's.
            let band = |size: u16| if frame_units {
                1.0
            } else {
                (2.0 * CLIP_BAND_PX as f64 - f64::from(size)) / f64::from(size)
            };
            let (x, y) = ((fx * band(width) * w as f64) as i64, (fy * band(height) * w as f64) as i64);
            let z = (fz * w as f64) as i64;
            let c = [x, y, z, w];
            let wide = |v: i64| i128::from(v);
            let expected = z >= -w
                && z <= w
                && wide(x.abs()) * wide(frame.width) <= wide(frame.guard_x) * wide(w)
                && wide(y.abs()) * wide(frame.height) <= wide(frame.guard_y) * wide(w);
            prop_assert_eq!(frame.inside(&c), expected);
        }
    }

    #[test]
    fn frames_larger_than_the_core_takes_fall_back() {
        let camera = Camera::reference(240, 240);
        let (m, mv) = mvp(0.0, 0.0, &camera);
        assert!(FixedFrame::new(&m, &mv, [0.0; 3], 1.0, 4096, 4096).is_some());
        assert!(FixedFrame::new(&m, &mv, [0.0; 3], 1.0, 4097, 240).is_none());
        assert!(FixedFrame::new(&m, &mv, [0.0; 3], 1.0, 240, 4097).is_none());
    }

    #[test]
    fn huge_scales_fall_back() {
        let camera = Camera::reference(240, 240);
        let (m, mv) = mvp(0.0, 0.0, &camera);
        assert!(FixedFrame::new(&m, &mv, [0.0; 3], 1.0e9, 240, 240).is_none());
        let mut nan = m;
        nan.m[0][0] = f32::NAN;
        assert!(FixedFrame::new(&nan, &mv, [0.0; 3], 1.0, 240, 240).is_none());
        assert!(FixedFrame::new(&m, &mv, [f32::INFINITY, 0.0, 0.0], 1.0, 240, 240).is_none());
    }

    #[test]
    fn normals_rotate_and_stay_unit() {
        let camera = Camera::reference(240, 240);
        let (m, mv) = mvp(30.0, 20.0, &camera);
        let mv_scaled = mv.mul(&Mat4::scale(Vec3::new(0.01, 0.01, 0.01)));
        let frame = FixedFrame::new(&m, &mv_scaled, [0.0; 3], 1.0, 240, 240).unwrap();
        let n = frame.view_normal([0, 0, 32767]).unwrap();
        let expect = mv.transform_vector(Vec3::new(0.0, 0.0, 1.0));
        for (got, want) in n.iter().zip([expect.x, expect.y, expect.z]) {
            assert!((f64::from(*got) / 32767.0 - f64::from(want)).abs() < 1e-4);
        }
        // Any i16 input rotates without overflow, even one no mesh stores.
        let _ = frame.view_normal([32767, 32767, 32767]);
        let _ = frame.view_normal([-32768, -32768, -32768]);
        // A shear is not a similarity: no integer normals.
        let mut shear = mv;
        shear.m[0][1] += 0.5;
        let f = FixedFrame::new(&m, &shear, [0.0; 3], 1.0, 240, 240).unwrap();
        assert!(f.view_normal([0, 0, 32767]).is_none());
    }

    #[test]
    fn a_shear_keeps_integers_without_normals_and_a_huge_scale_leaves_them() {
        // A unit sphere at the reference view, sheared: the transform stays
        // integer, the normals do not (not a rotation times a scale).
        let camera = Camera::reference(240, 240);
        let model = Mat4::rotation_y(radians(30.0));
        let mut shear = Mat4::IDENTITY;
        shear.m[0][1] = 0.4;
        let shear = shear.mul(&model);
        let (mv, mvp) = {
            let mv = camera.view.mul(&shear);
            (mv, camera.projection.mul(&mv))
        };
        let frame = FixedFrame::new(&mvp, &mv, [0.0; 3], 1.0, 240, 240).expect("integer ranges");
        assert!(frame.view_normal([0, 0, 32767]).is_none());
        // A billion times larger and further: the same picture, with
        // coefficients beyond the integer ranges.
        let far = Camera::perspective(
            Mat4::translation(Vec3::new(0.0, 0.0, -3.0e9)),
            45.0,
            240,
            240,
            1.0e8,
            1.0e10,
        );
        let huge = Mat4::scale(Vec3::new(1.0e9, 1.0e9, 1.0e9)).mul(&model);
        let mv = far.view.mul(&huge);
        let mvp = far.projection.mul(&mv);
        assert!(FixedFrame::new(&mvp, &mv, [0.0; 3], 1.0, 240, 240).is_none());
    }
}
