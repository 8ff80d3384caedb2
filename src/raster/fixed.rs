//! Fixed-point number formats shared by the whole pipeline: the sub-pixel
//! grid for screen coordinates, the input depth format, the guard band and
//! the exact rounding helpers used during polygon setup.
//!
//! # Coordinates
//! Screen x and y are `i32` on a grid of [`SUBPIXEL_STEPS`] steps per pixel
//! (8 fractional bits). Pixel `(i, j)` is sampled at its centre
//! `(i + 0.5, j + 0.5)`; x grows to the right and y grows downwards.
//!
//! # Depth
//! Vertex depth is unsigned Q0.24 ([`DEPTH_ONE`] is 1.0): `0` is the near
//! plane, [`DEPTH_MAX`] the far plane, and the **smaller value is nearer**.
//! It must be a quantity that is affine in screen space (`z_ndc` mapped to
//! `[0, 1]`, or `1 - 1/w` scaled), never view-space z.
//!
//! # Guard band
//! Every vertex must satisfy `|x|, |y| < GUARD_BAND_PX` pixels. Inside that
//! band every intermediate of edge and plane setup fits its integer type on
//! a 32-bit MCU (64-bit products at setup, 32-bit stepping per row); a
//! vertex outside it is rejected with
//! [`Error::OutsideGuardBand`](crate::Error::OutsideGuardBand).

use crate::raster::wide::{mul_u32, mul_u32_by_size, shr_u64};

/// Fractional bits of the sub-pixel grid.
pub const SUBPIXEL_BITS: u32 = 8;
/// Sub-pixel steps per pixel (256).
pub const SUBPIXEL_STEPS: i32 = 1 << SUBPIXEL_BITS;
/// Half a pixel in sub-pixel steps: the offset of a pixel's sample point.
pub const HALF_PIXEL: i32 = SUBPIXEL_STEPS / 2;

/// Largest frame width or height, in pixels, that the renderer accepts.
pub const MAX_FRAME_SIZE: usize = 4096;
/// Most corners one polygon may have. It bounds the integer ranges of
/// polygon set-up (see `src/raster/plane.rs`); it costs no memory.
pub const MAX_POLYGON_CORNERS: usize = 1024;
/// Most polygons the tables hold (2^20): an edge-table entry packs a
/// polygon's position into 20 bits. A storage with more polygon slots
/// uses this many; the next polygon is
/// [`Error::PolygonTableFull`](crate::Error::PolygonTableFull).
pub const MAX_POLYGONS: usize = 1 << 20;
/// Vertices must lie strictly inside `(-GUARD_BAND_PX, GUARD_BAND_PX)` on
/// both axes, in pixels.
pub const GUARD_BAND_PX: i32 = 8192;
/// [`GUARD_BAND_PX`] in sub-pixel steps.
pub const GUARD_BAND: i32 = GUARD_BAND_PX * SUBPIXEL_STEPS;

/// Fractional bits of the input depth (Q0.24).
pub const DEPTH_BITS: u32 = 24;
/// 1.0 in the input depth format.
pub const DEPTH_ONE: u32 = 1 << DEPTH_BITS;
/// Largest valid vertex depth: the far plane.
pub const DEPTH_MAX: u32 = DEPTH_ONE - 1;

/// Extra fractional bits carried by plane values and gradients during
/// rasterisation: a plane value is an `i64` in units of
/// `2^-PLANE_FRAC_BITS` input-depth steps.
pub const PLANE_FRAC_BITS: u32 = 16;

/// Converts pixels (any real value) to the sub-pixel grid, rounding to the
/// nearest step. Returns `None` for NaN, infinities and values outside the
/// guard band.
pub fn subpixel_from_f32(pixels: f32) -> Option<i32> {
    let scaled = pixels * SUBPIXEL_STEPS as f32;
    // Also rejects NaN: every comparison with NaN is false.
    if scaled > -(GUARD_BAND as f32) && scaled < GUARD_BAND as f32 {
        // Round half away from zero without libm.
        let rounded = if scaled >= 0.0 {
            scaled + 0.5
        } else {
            scaled - 0.5
        };
        let value = rounded as i32;
        if value.unsigned_abs() < GUARD_BAND as u32 {
            return Some(value);
        }
    }
    None
}

/// [`subpixel_from_f32`] for an `f64` (the clipped path of the pipeline).
pub fn subpixel_from_f64(pixels: f64) -> Option<i32> {
    let scaled = pixels * f64::from(SUBPIXEL_STEPS);
    let rounded = if scaled >= 0.0 {
        scaled + 0.5
    } else {
        scaled - 0.5
    };
    // Also rejects NaN: every comparison with NaN is false.
    (rounded > -f64::from(GUARD_BAND) && rounded < f64::from(GUARD_BAND)).then_some(rounded as i32)
}

/// [`depth_from_f32`] for an `f64`.
pub fn depth_from_f64(depth: f64) -> Option<u32> {
    if (0.0..=1.0).contains(&depth) {
        let value = (depth * f64::from(DEPTH_ONE) + 0.5) as u32;
        Some(value.min(DEPTH_MAX))
    } else {
        None
    }
}

/// Converts a depth in `[0, 1]` (0 near, 1 far) to Q0.24, rounding to the
/// nearest step and mapping 1.0 to [`DEPTH_MAX`]. Returns `None` for NaN and
/// values outside `[0, 1]`.
pub fn depth_from_f32(depth: f32) -> Option<u32> {
    if (0.0..=1.0).contains(&depth) {
        let value = (depth * DEPTH_ONE as f32 + 0.5) as u32;
        Some(value.min(DEPTH_MAX))
    } else {
        None
    }
}

/// `num / den` rounded to the nearest integer (ties towards +inf), for any
/// non-zero `den`.
pub(crate) fn div_round_i128(num: i128, den: i128) -> i128 {
    debug_assert!(den != 0);
    let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
    (2 * num + den).div_euclid(2 * den)
}

/// `num · 2^16 / den` rounded to the nearest integer (ties towards +inf),
/// exactly, for any non-zero `den` and any `|num| < 2^100`.
///
/// Three paths, each exact:
/// * `|num| < 2^45` and `|den| < 2^45` (nearly every polygon): one `i64`
///   division of `2·num·2^16 + den`, whose magnitude is below
///   `2^62 + 2^45 < 2^63`;
/// * `num` fits `i64`, `|den| < 2^45`: the quotient `num / den`, then the
///   fraction `round(r · 2^16 / den)` from the remainder `0 <= r < den`, with
///   `2·r·2^16 + den < 2^63`;
/// * otherwise one `i128` division of `num · 2^16` (below `2^116`).
pub(crate) fn div_round_q16(num: i128, den: i64) -> i128 {
    debug_assert!(den != 0 && num.unsigned_abs() < 1 << 100);
    if let Ok(n) = i64::try_from(num)
        && den.unsigned_abs() < FAST_BOUND
        && den != 0
    {
        let (n, d) = if den < 0 { (-n, -den) } else { (n, den) };
        if n.unsigned_abs() < FAST_BOUND {
            return i128::from(((n << 17) + d).div_euclid(2 * d));
        }
        let (q, r) = (n.div_euclid(d), n.rem_euclid(d));
        let fraction = ((r << 17) + d).div_euclid(2 * d);
        return (i128::from(q) << 16) + i128::from(fraction);
    }
    div_round_i128(num << 16, i128::from(den))
}

/// Operands below this magnitude take the one-division path of
/// [`div_round_q16`]: `2·|num|·2^16 + |den| < 2^62 + 2^45`.
const FAST_BOUND: u64 = 1 << 45;

/// Division by one divisor many times, exactly: [`div_round_q16`] by a
/// multiplication with a precomputed reciprocal instead of a division
/// (a polygon's plane divides three quotients by its `c`).
///
/// For `0 < |den| < 2^45` and `|num| < 2^45` the quotient is
/// `floor(N / D)` with `N = 2·num·2^16 + |den|` (`|N| < 2^63`) and
/// `D = 2·|den|` (`< 2^46`): the estimate `(|N|·m) >> 64` with
/// `m = floor((2^64 - 1) / D)` is low by less than one (the error is
/// `|N|·(2^64/D - m)/2^64 < 2^63·2/2^64`), so one check of the remainder
/// makes it exact. Other operands take [`div_round_q16`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reciprocal {
    den: i64,
    /// `2·|den|`.
    d: u64,
    /// `floor((2^64 - 1) / d)`; 0 when the reciprocal path is off.
    m: u64,
}

impl Reciprocal {
    /// The reciprocal of `den` (non-zero).
    #[inline]
    pub fn new(den: i64) -> Self {
        debug_assert!(den != 0);
        let d = 2 * den.unsigned_abs();
        let m = if den.unsigned_abs() < FAST_BOUND && den != 0 {
            u64::MAX / d
        } else {
            0
        };
        Self { den, d, m }
    }

    /// `floor(u / d)` for `u < 2^63`, by the reciprocal.
    #[inline]
    fn floor_div(&self, u: u64) -> u64 {
        let mut q = ((u128::from(u) * u128::from(self.m)) >> 64) as u64;
        // The estimate is low by at most one.
        if u - q * self.d >= self.d {
            q += 1;
        }
        q
    }

    /// [`div_round_q16`]`(num, den)`, exactly.
    #[inline]
    pub fn div_round_q16(&self, num: i128) -> i128 {
        match i64::try_from(num)
            .ok()
            .and_then(|n| self.div_round_q16_small(n))
        {
            Some(q) => i128::from(q),
            None => div_round_q16(num, self.den),
        }
    }

    /// [`div_round_q16`]`(num, den)` by the reciprocal alone: `None` unless
    /// `|num| < 2^45` and `|den| < 2^45` (the reciprocal path).
    #[inline]
    pub fn div_round_q16_small(&self, num: i64) -> Option<i64> {
        if self.m == 0 || num.unsigned_abs() >= FAST_BOUND {
            return None;
        }
        let n = if self.den < 0 { -num } else { num };
        // N = 2·n·2^16 + |den|, |N| < 2^63.
        let big_n = (n << 17) + (self.d / 2) as i64;
        Some(if big_n >= 0 {
            self.floor_div(big_n as u64) as i64
        } else {
            // floor(-u / d) = -ceil(u / d) = -(floor((u - 1) / d) + 1).
            let u = big_n.unsigned_abs();
            -(self.floor_div(u - 1) as i64) - 1
        })
    }
}

/// Whether a 32-bit division is cheap on this target: everywhere but on
/// ARMv6-M (a Cortex-M0+ has no divide instruction, and compiler-builtins'
/// division takes about 70 instructions), unless the `hardware-divider`
/// feature says the chip has one of its own (the RP2040's SIO divider,
/// which rp2040-hal uses for `/`). Where it is not, exact divisions that
/// can take a [`Divisor`]'s reciprocal do.
pub(crate) const DIVISION_IS_CHEAP: bool = cfg!(feature = "hardware-divider")
    || !cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// Exact division by one 31-bit divisor, several times, without a 64-bit
/// division (a Cortex-M0+ has no divide instruction, and compiler-builtins'
/// 64-bit division costs hundreds of instructions there): a 32-bit
/// reciprocal from one 32-bit division and a Newton step
/// ([`crate::front::fixed_point::reciprocal62`]), a quotient estimate from
/// two 64-bit products, and at most a few corrections against the exact
/// remainder. For quotients below `2^26`; larger ones are refused.
///
/// Ranges: `0 < d < 2^31`, normalised to `dn = d·2^(s-1)` in `[2^30,
/// 2^31)` (`s` its leading zeros, at least 1); `R ~ 2^62 / dn` within 8
/// and never above it (one Newton step from either side lands below, and
/// the truncations only lower it), so `R < 2^32` (`2^32 - 1` at `dn = 2^30`);
/// for `n < 2^57`: `(n >> 32)·R < 2^57` and `(n mod 2^32)·R < 2^64`; the
/// estimate `q` is within `q·2^-28 + 2 < 3` of `n / d`, so each correction
/// loop runs at most 3 times; `q·d < 2^57`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Divisor {
    d: u64,
    recip: u64,
    /// `63 - s`: the estimate is `(n·R) >> shift`.
    shift: u32,
}

impl Divisor {
    /// Largest quotient [`Self::div_rem`] computes.
    pub const QUOTIENT_LIMIT: u64 = 1 << 26;

    /// Division by `d` (`0 < d < 2^31`).
    #[inline]
    pub fn new(d: u32) -> Self {
        debug_assert!(d > 0 && d < 1 << 31);
        let s = d.leading_zeros();
        let recip = crate::front::fixed_point::reciprocal62(d << (s - 1));
        debug_assert!(recip < 1 << 32);
        Self {
            d: u64::from(d),
            recip,
            shift: 63 - s,
        }
    }

    /// `(n / d, n mod d)` exactly, for `n < 2^57`; `None` when the quotient
    /// is [`Self::QUOTIENT_LIMIT`] or more.
    #[inline]
    pub fn div_rem(&self, n: u64) -> Option<(u64, u64)> {
        debug_assert!(n < 1 << 57);
        // n < 2^57, R < 2^32 and d < 2^31 (see the type's notes): every
        // product has 32-bit operands.
        let (high, low) = ((n >> 32) as u32, n as u32);
        let recip = self.recip as u32;
        let product = mul_u32_by_size(recip, high) + (mul_u32(low, recip) >> 32);
        // shift - 32 = 31 - s, below 32.
        let mut q = shr_u64(product, self.shift - 32);
        if q >= Self::QUOTIENT_LIMIT + 4 {
            return None;
        }
        let mut qd = mul_u32_by_size(self.d as u32, q as u32);
        while qd > n {
            q -= 1;
            qd -= self.d;
        }
        let mut r = n - qd;
        while r >= self.d {
            q += 1;
            r -= self.d;
        }
        (q < Self::QUOTIENT_LIMIT).then_some((q, r))
    }

    /// [`Self::div_rem`], by one 32x32→64 product when `d < 2^28` and the
    /// quotient is below `2^17` (a gradient's fraction always, its whole
    /// part mostly); otherwise by [`Self::div_rem`].
    ///
    /// Ranges: with `s - 1 = 62 - shift` (at least 3, as `d < 2^28`), `nn =
    /// n·2^(s-1) < dn·2^17 < 2^48`, so `top = nn >> 16` fits 32 bits (when
    /// `s - 1 >= 16`, `d < 2^15` and `n < 2^32`, so the left shift is of a
    /// 32-bit word and exact); `top·R < 2^64`. As `top·2^16 <= nn` and `R
    /// <= 2^62 / dn`, the estimate `(top·R) >> 46` is at most `n / d`; as
    /// `nn - top·2^16 < 2^16` and `R >= 2^62 / dn - 8`, it falls short by
    /// less than `2^-14 + 2^-11` before its floor, so by at most one. The
    /// remainder `n - q·d` is then in `[0, 2d)`, below `2^29`: computed
    /// modulo `2^32` it is exact, and one correction finishes.
    #[inline(always)]
    pub fn div_rem_short(&self, n: u64) -> Option<(u64, u64)> {
        if self.d < 1 << 28 && n < self.d << 17 {
            let s1 = 62 - self.shift;
            let top = if s1 >= 16 {
                (n as u32) << (s1 - 16)
            } else {
                shr_u64(n, 16 - s1) as u32
            };
            let d = self.d as u32;
            let mut q = (mul_u32(top, self.recip as u32) >> 46) as u32;
            let mut r = (n as u32).wrapping_sub(q.wrapping_mul(d));
            if r >= d {
                q += 1;
                r -= d;
            }
            debug_assert!(r < d);
            return Some((u64::from(q), u64::from(r)));
        }
        self.div_rem_long(n)
    }

    /// [`Self::div_rem`] out of line: the rare case of
    /// [`Self::div_rem_short`], kept from crowding its fast path.
    #[cold]
    #[inline(never)]
    fn div_rem_long(&self, n: u64) -> Option<(u64, u64)> {
        self.div_rem(n)
    }
}

/// First pixel whose sample point lies at or to the right of sub-pixel
/// coordinate `x` (`ceil((x - HALF_PIXEL) / SUBPIXEL_STEPS)`). The same
/// function gives the first row at or below a sub-pixel y.
///
/// With `x = 256·q + r` (`q = x >> 8`, `0 <= r < 256`), `(x - 128) / 256`
/// is `q + (r - 128) / 256`, whose second term lies in `[-1/2, 1/2)`: the
/// ceiling is `q`, plus one when `r > 128`. A shift, a mask and a
/// comparison, with no overflow for any `i32`.
#[inline]
pub(crate) fn first_sample_at_or_after(x: i32) -> i32 {
    (x >> SUBPIXEL_BITS) + i32::from(x & (SUBPIXEL_STEPS - 1) > HALF_PIXEL)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::strategy::Strategy;

    #[test]
    fn divisor_is_exact() {
        let check = |n: u64, d: u32| {
            let divisor = Divisor::new(d);
            let (q, r) = (n / u64::from(d), n % u64::from(d));
            let expected = (q < Divisor::QUOTIENT_LIMIT).then_some((q, r));
            assert_eq!(divisor.div_rem(n), expected, "{n} / {d}");
            assert_eq!(divisor.div_rem_short(n), expected, "short {n} / {d}");
        };
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for _ in 0..200_000 {
            let d = (next() as u32 >> (next() % 31)).max(1) & 0x7FFF_FFFF;
            let d = d.max(1);
            // Quotients on both sides of the limit.
            let q = next() % (Divisor::QUOTIENT_LIMIT * 2);
            let n = (q * u64::from(d) + next() % u64::from(d)).min((1 << 57) - 1);
            check(n, d);
            check(next() >> 7, d);
        }
        for d in [1u32, 2, 3, (1 << 30) - 1, 1 << 30, (1 << 31) - 1] {
            for n in [0u64, 1, u64::from(d) - 1, u64::from(d), (1 << 57) - 1] {
                check(n, d);
            }
        }
        // The short path's edges: divisors at every power of two up to and
        // beyond 2^28 (and beside them), quotients at and beside 2^17.
        for k in 0..31 {
            for d in [(1u32 << k).saturating_sub(1), 1 << k, (1 << k) + 1] {
                let d = d.clamp(1, (1 << 31) - 1);
                let d64 = u64::from(d);
                for n in [
                    0,
                    d64 - 1,
                    d64,
                    (d64 << 17) - 1,
                    d64 << 17,
                    (d64 << 17) - d64,
                    (d64 << 17) - d64 - 1,
                    (d64 << 16) + d64 / 2,
                ] {
                    check(n, d);
                }
                for _ in 0..2_000 {
                    check(next() % (d64 << 17), d);
                }
            }
        }
    }

    #[test]
    fn first_sample_is_the_exact_ceiling() {
        let exact = |x: i32| {
            let v = i64::from(x) - i64::from(HALF_PIXEL);
            v.div_euclid(i64::from(SUBPIXEL_STEPS))
                + i64::from(v.rem_euclid(i64::from(SUBPIXEL_STEPS)) != 0)
        };
        let mut values: std::vec::Vec<i32> = (-2000..2000).collect();
        for base in [i32::MIN, -GUARD_BAND, GUARD_BAND, i32::MAX - 600] {
            values.extend((0..600).map(|k| base.saturating_add(k)));
        }
        values.extend([i32::MAX, i32::MAX - 127, i32::MAX - 128, i32::MAX - 129]);
        for x in values {
            assert_eq!(i64::from(first_sample_at_or_after(x)), exact(x), "x = {x}");
        }
    }

    #[test]
    fn sample_rounding() {
        // Pixel 0 samples at 128; a boundary exactly there includes pixel 0.
        assert_eq!(first_sample_at_or_after(128), 0);
        assert_eq!(first_sample_at_or_after(129), 1);
        assert_eq!(first_sample_at_or_after(127), 0);
        assert_eq!(first_sample_at_or_after(-128), -1);
        assert_eq!(first_sample_at_or_after(-129), -1);
        assert_eq!(first_sample_at_or_after(-127), 0);
    }

    #[test]
    fn rounding_helpers() {
        assert_eq!(div_round_i128(5, 2), 3);
        assert_eq!(div_round_i128(-5, 2), -2);
        assert_eq!(div_round_i128(5, -2), -2);
        assert_eq!(div_round_i128(7, 3), 2);
        // The i64 path agrees with the i128 one, ties and signs included.
        for (num, den) in [
            (5i128, 2i64),
            (-5, 2),
            (5, -2),
            (7, 3),
            (-(1 << 61), 12345),
            (1 << 70, 3),
            (3, -(1 << 50)),
            (-1, 1 << 17),
            ((1 << 46) - 1, 7),
            (-(1 << 46) + 1, 7),
            (1 << 46, 7),
            (-(1 << 46), -7),
            (123_456_789_012, -98_765_432_109),
            // Issue 7, item 1: the x-gradient numerator 2^46 - 256 of a
            // 10 x 205 px triangle used to overflow `(n << 17) + d`.
            ((1 << 46) - 256, 134_218_240),
            (-(1 << 46) + 256, 134_218_240),
            ((1 << 45) - 1, (1 << 45) - 1),
            (-(1 << 45) + 1, (1 << 45) - 1),
            (1 << 45, (1 << 45) - 1),
            ((1 << 45) - 1, -(1 << 45) + 1),
            (i128::from(i64::MAX), (1 << 45) - 1),
            (i128::from(i64::MIN), (1 << 45) - 1),
            (i128::from(i64::MIN), 1),
            (i128::from(i64::MAX), i64::MAX),
            (i128::from(i64::MIN), i64::MIN),
            ((1 << 99) + 12345, 3),
            (-(1 << 99), -(1 << 62)),
        ] {
            assert_eq!(
                div_round_q16(num, den),
                div_round_i128(num << 16, i128::from(den)),
                "{num} / {den}"
            );
        }
    }

    proptest::proptest! {
        /// The reciprocal gives the same quotient as the division, on both
        /// of its paths.
        #[test]
        fn reciprocal_division_is_exact(
            num in proptest::prop_oneof![
                -(1i128 << 45) + 1..(1i128 << 45),
                -1000i128..1000,
                -(1i128 << 70)..(1i128 << 70),
            ],
            den in proptest::prop_oneof![
                -(1i64 << 45) + 1..(1i64 << 45),
                -1000i64..1000,
                proptest::num::i64::ANY,
            ].prop_filter("non-zero", |d| *d != 0),
        ) {
            proptest::prop_assert_eq!(Reciprocal::new(den).div_round_q16(num), div_round_i128(num << 16, i128::from(den)));
        }

        /// Every path of `div_round_q16` is exact over its whole domain:
        /// operands drawn near each path's limits and anywhere else.
        #[test]
        fn q16_division_is_exact(
            num in proptest::prop_oneof![
                -(1i128 << 46)..(1i128 << 46),
                proptest::num::i64::ANY.prop_map(i128::from),
                -(1i128 << 99)..(1i128 << 99),
            ],
            den in proptest::prop_oneof![
                proptest::num::i64::ANY,
                -(1i64 << 46)..(1i64 << 46),
                -1000i64..1000,
            ].prop_filter("non-zero", |d| *d != 0),
        ) {
            proptest::prop_assert_eq!(div_round_q16(num, den), div_round_i128(num << 16, i128::from(den)));
        }
    }

    #[test]
    fn reciprocal_division_at_the_limits() {
        let limit = (1i64 << 45) - 1;
        for den in [1, -1, 2, 3, 7, limit, -limit, 1 << 44, limit - 1, 12345] {
            for num in [
                0i128,
                1,
                -1,
                2,
                -2,
                65535,
                -65536,
                limit.into(),
                (-limit).into(),
                (limit - 1).into(),
                1 << 45,
                -(1 << 45),
            ] {
                assert_eq!(
                    Reciprocal::new(den).div_round_q16(num),
                    div_round_i128(num << 16, i128::from(den)),
                    "{num} / {den}"
                );
            }
        }
    }

    #[test]
    fn float_conversions_reject_bad_values() {
        assert_eq!(subpixel_from_f32(1.5), Some(384));
        assert_eq!(subpixel_from_f32(-1.5), Some(-384));
        assert_eq!(subpixel_from_f32(f32::NAN), None);
        assert_eq!(subpixel_from_f32(f32::INFINITY), None);
        assert_eq!(subpixel_from_f32(GUARD_BAND_PX as f32), None);
        assert_eq!(depth_from_f32(1.0), Some(DEPTH_MAX));
        assert_eq!(depth_from_f32(0.5), Some(DEPTH_ONE / 2));
        assert_eq!(depth_from_f32(-0.1), None);
        assert_eq!(depth_from_f32(f32::NAN), None);
    }
}
