//! Exact division for polygon set-up and the integer front end: rounded
//! quotients of wide integers, and division by a fixed divisor through a
//! reciprocal where a core has no divider (a Cortex-M0+'s library
//! division takes hundreds of instructions). Both the core and the front
//! end use it; it uses nothing of theirs.

use super::wide::{mul_i64_i32, mul_u32, mul_u32_by_size, shr_u64};

/// `num / den` rounded to the nearest integer (ties towards +inf), for any
/// non-zero `den`.
///
/// Its division is [`div_rem_bitwise`]'s, one bit at a time: it is the
/// rare path of [`div_round_q16`] (operands beyond `i64` or `2^45`), and
/// `i128`'s division cost 248 bytes more of a Cortex-M0+ firmware's
/// flash (the bit-by-bit routine is shared).
pub(crate) fn div_round_i128(num: i128, den: i128) -> i128 {
    debug_assert!(den != 0);
    let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
    // floor((2·num + den) / (2·den)), from the magnitudes: for a negative
    // dividend the floor is minus the ceiling of the magnitude's quotient.
    let (n, d) = (2 * num + den, (2 * den).unsigned_abs());
    let (q, r) = div_rem_bitwise(n.unsigned_abs(), d);
    if n >= 0 {
        q as i128
    } else {
        -(q as i128) - i128::from(r != 0)
    }
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
pub(crate) const DIVISION_IS_CHEAP: bool = cfg!(feature = "hardware-divider") || !super::ARMV6M;

/// Exact division by one 31-bit divisor, several times, without a 64-bit
/// division (a Cortex-M0+ has no divide instruction, and compiler-builtins'
/// 64-bit division costs hundreds of instructions there): a 32-bit
/// reciprocal from one 32-bit division and a Newton step
/// ([`reciprocal62`]), a quotient estimate from
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
        let recip = reciprocal62(d << (s - 1));
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
        let mut q = self.estimate(n);
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

    /// An estimate `q` of `n / d` for `n < 2^57`, with no correction: at
    /// most `n / d` plus 1 and at least `n / d - q·2^-28 - 2` (`R` is at
    /// most `2^62 / dn` and within 8 of it; the low product's dropped
    /// word and the final shift each lower it by less than one).
    #[inline]
    pub fn estimate(&self, n: u64) -> u64 {
        debug_assert!(n < 1 << 57);
        // n < 2^57, R < 2^32 and d < 2^31 (see the type's notes): every
        // product has 32-bit operands.
        let (high, low) = ((n >> 32) as u32, n as u32);
        let recip = self.recip as u32;
        let product = mul_u32_by_size(recip, high) + (mul_u32(low, recip) >> 32);
        // shift - 32 = 31 - s, below 32.
        shr_u64(product, self.shift - 32)
    }

    /// An estimate `q` of `a·2^k / d` for `k <= 31`, with no correction,
    /// by one 32x32→64 product: at most the quotient and at least the
    /// quotient `- q·2^-28 - 1` (`R` is at most `2^62 / dn` and within 8
    /// of it, and the shift floors once).
    ///
    /// Ranges: `a·R < 2^64`; the shift `63 - s - k` is at least 1 as `s`
    /// is at most 31, and at most 62.
    #[inline]
    pub fn estimate_scaled(&self, a: u32, k: u32) -> u64 {
        debug_assert!(k <= 31);
        let product = mul_u32(a, self.recip as u32);
        let shift = self.shift - k;
        if shift >= 32 {
            u64::from(((product >> 32) as u32) >> (shift - 32))
        } else {
            shr_u64(product, shift)
        }
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

/// `round(n / d)` (ties away from zero) for `d > 0`. When `|n|` and `d`
/// are below `2^61` (every call of an ordinary frame) the same rounding is
/// done in `i64` (`2·|n| + d < 2^63`), which a 32-bit core divides far
/// faster than `i128`. Out of line: the per-frame rotation set-up calls it
/// nine times, and inlined that was 29 KB of a Cortex-M0+ firmware's
/// flash for no speed.
#[inline(never)]
pub(crate) fn div_round_away_i128(n: i128, d: i128) -> i128 {
    const LIMIT: u128 = 1 << 61;
    if n.unsigned_abs() < LIMIT && d.unsigned_abs() < LIMIT {
        let (n, d) = (n as i64, d as i64);
        return i128::from(if n >= 0 {
            (2 * n + d) / (2 * d)
        } else {
            -((-2 * n + d) / (2 * d))
        });
    }
    let (magnitude, divisor) = (n.unsigned_abs(), d.unsigned_abs());
    let q = if magnitude < LIMIT && divisor >= LIMIT {
        // A quotient below 1 (the per-frame set-up's tiny matrix entries):
        // 1 when at least a half, else 0.
        u128::from(2 * magnitude >= divisor)
    } else if let Ok(small) = u16::try_from(d) {
        // A divisor below 2^16 (the dequantization's 32767): long division
        // in 16-bit digits, each step a 32-bit division.
        let (q, r) = div_rem_by_u16(magnitude, small);
        q + u128::from(2 * u32::from(r) >= u32::from(small))
    } else {
        // Never in a frame: bit by bit, in far less code than `i128`'s
        // division (832 bytes of a Cortex-M0+ firmware's flash).
        let (q, r) = div_rem_bitwise(magnitude, divisor);
        q + u128::from(2 * r >= divisor)
    };
    if n >= 0 { q as i128 } else { -(q as i128) }
}

/// `n / d` and `n % d` for `0 < d < 2^127`, one bit at a time from the
/// top (the remainder stays below `d`, so doubling it cannot overflow).
fn div_rem_bitwise(n: u128, d: u128) -> (u128, u128) {
    let (mut q, mut r) = (0u128, 0u128);
    for k in (0..128 - n.leading_zeros()).rev() {
        r = (r << 1) | ((n >> k) & 1);
        q <<= 1;
        if r >= d {
            r -= d;
            q |= 1;
        }
    }
    (q, r)
}

/// `n / d` and `n % d` for `d > 0`, by 16-bit digits from the top: each
/// partial dividend is `r·2^16 + digit < d·2^16 <= 2^32`, so every step is
/// one 32-bit division (on an RP2040, its 8-cycle divider; a `u128`
/// division is a long library call).
fn div_rem_by_u16(n: u128, d: u16) -> (u128, u16) {
    let d = u32::from(d);
    let (mut q, mut r) = (0u128, 0u32);
    let digits = (128 - n.leading_zeros()).div_ceil(16);
    for k in (0..digits).rev() {
        let partial = (r << 16) | ((n >> (16 * k)) as u32 & 0xFFFF);
        q = (q << 16) | u128::from(partial / d);
        r = partial % d;
    }
    (q, r as u16)
}

/// `2^62 / w` for `w` in `[2^30, 2^31)`, within 8 of the exact quotient
/// (relative error below `2^-28`): a 16-bit estimate from one 32-bit
/// division (the RP2040's SIO divider does it in 8 cycles), then one
/// Newton step in 64-bit products of 32-bit operands (from 16-bit halves
/// on a Cortex-M0+, `src/raster/wide.rs`).
///
/// Ranges: `d = w >> 15` in `[2^15, 2^16)`, so `r0 = (2^32 - 1) / d` in
/// `(2^16, 2^17)` and `R0 = r0·2^15` within `2^-15` (relative, from
/// above or below) of `2^62 / w`; `w·R0 < 2^63`; the residual
/// `e = 2^62 - w·R0` in `[-2^47, 2^47]`; `r0 · (e >> 2) <= 2^62`.
#[inline]
pub(crate) fn reciprocal62(w: u32) -> u64 {
    debug_assert!((1 << 30..1 << 31).contains(&w));
    let d = w >> 15;
    let r0 = u64::from(max_div(d));
    let r0s = r0 << 15;
    // r0 < 2^17, so r0s < 2^32 and r0 fits i32: 32-bit operands.
    let e = (1i64 << 62) - mul_u32(w, r0s as u32) as i64;
    let correction = mul_i64_i32(e >> 2, r0 as i32) >> 45;
    (r0s as i64 + correction) as u64
}

/// `(2^32 - 1) / d` exactly, for `d` in `[2^15, 2^16)`: the quotient is in
/// `(2^16, 2^17)`. Where a division is cheap it is one; on a Cortex-M0+
/// without a divider (where compiler-builtins' routine takes about 190
/// instructions for a 17-bit quotient) it is [`max_div_by_table`].
#[inline]
fn max_div(d: u32) -> u32 {
    if DIVISION_IS_CHEAP {
        u32::MAX / d
    } else {
        max_div_by_table(d)
    }
}

/// Entries of [`RECIPROCAL_TABLE`]: one per 2^7-wide interval of `d`.
const RECIPROCAL_ENTRIES: usize = 256;

/// `2^32 / m` for the midpoint `m = 2^15 + 2^7·i + 2^6` of interval `i`:
/// within `2^-9` (relative) of `2^32 / d` for every `d` of the interval.
/// Every entry is in `(2^16, 2^17)`.
static RECIPROCAL_TABLE: [u32; RECIPROCAL_ENTRIES] = {
    let mut table = [0u32; RECIPROCAL_ENTRIES];
    let mut i = 0;
    while i < RECIPROCAL_ENTRIES {
        let mid = (1u64 << 15) + ((i as u64) << 7) + (1 << 6);
        table[i] = ((1u64 << 32) / mid) as u32;
        i += 1;
    }
    table
};

/// The estimate of [`max_div_by_table`] before its corrections.
#[inline(always)]
fn max_div_estimate(d: u32) -> u32 {
    debug_assert!((1 << 15..1 << 16).contains(&d));
    let x0 = RECIPROCAL_TABLE[((d >> 7) & 0xFF) as usize];
    let e = 0u32.wrapping_sub(d.wrapping_mul(x0)) as i32;
    x0.wrapping_add_signed(((e >> 8) * (x0 >> 2) as i32) >> 22)
}

/// [`max_div`] by products alone: a table estimate `x0` (relative error
/// below `2^-9`), one Newton step in 32-bit products, and exact
/// corrections against the remainder.
///
/// Ranges (`d` in `[2^15, 2^16)`, `x0` in `(2^16, 2^17)`): `d·x0` is
/// within `2^32·2^-9` of `2^32`, so the residual `e = 2^32 - d·x0`
/// (wrapping, as `i32`) is at most `2^23` in magnitude; `(e >> 8)·(x0 >>
/// 2)` is at most `2^15·2^15 = 2^30`; the step leaves `q` within 2 of the
/// quotient (the tests check every `d`, and that each correction loop runs
/// at most twice); `q·d` wraps `u32`, but `2^32 - 1 - q·d` is within
/// `3·d < 2^18` of `[0, d)`, so its wrapping difference as `i32` is exact.
#[inline]
fn max_div_by_table(d: u32) -> u32 {
    let mut q = max_div_estimate(d);
    let mut r = u32::MAX.wrapping_sub(q.wrapping_mul(d)) as i32;
    while r < 0 {
        q -= 1;
        r += d as i32;
    }
    while r >= d as i32 {
        q += 1;
        r -= d as i32;
    }
    q
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
    fn max_div_by_table_is_exact_for_every_divisor() {
        let (mut worst_residual, mut worst_miss) = (0u32, 0u32);
        for d in 1u32 << 15..1 << 16 {
            let exact = u32::MAX / d;
            assert_eq!(max_div_by_table(d), exact, "d = {d}");
            let x0 = RECIPROCAL_TABLE[((d >> 7) & 0xFF) as usize];
            assert!((1 << 16..1 << 17).contains(&x0));
            let residual = ((1i64 << 32) - i64::from(d) * i64::from(x0)).unsigned_abs();
            worst_residual = worst_residual.max(residual as u32);
            worst_miss = worst_miss.max(max_div_estimate(d).abs_diff(exact));
        }
        // The ranges stated on `max_div_by_table`.
        assert!(worst_residual <= 1 << 23, "residual {worst_residual}");
        assert!(worst_miss <= 2, "estimate off by {worst_miss}");
    }

    fn div_round_wide(n: i128, d: i128) -> i128 {
        let (q, r) = (n.div_euclid(d), n.rem_euclid(d));
        // n = q·d + r, 0 <= r < d: round up when 2r > d, or 2r == d and the
        // value is positive (away from zero).
        if 2 * r > d || (2 * r == d && n >= 0) {
            q + 1
        } else {
            q
        }
    }

    /// Quotients below 1 with a divisor of `2^61` and more: exactly a
    /// half rounds away from zero, less than a half to zero.
    #[test]
    fn rounded_division_of_quotients_below_one_rounds_half_away() {
        let d = (1i128 << 61) + 2;
        for (n, q) in [
            (d / 2, 1),
            (-d / 2, -1),
            (d / 2 - 1, 0),
            (-(d / 2 - 1), 0),
            (0, 0),
        ] {
            assert_eq!(div_round_away_i128(n, d), q, "{n} / {d}");
            assert_eq!(div_round_wide(n, d), q, "{n} / {d}");
        }
    }

    #[test]
    fn rounded_division_is_exact_on_both_paths() {
        const LIMIT: i128 = 1 << 61;
        let nums = [
            0,
            1,
            -1,
            2,
            -2,
            3,
            -3,
            LIMIT - 1,
            -(LIMIT - 1),
            LIMIT,
            -LIMIT,
            1 << 100,
        ];
        let dens = [1, 2, 3, 32767, 65534, LIMIT - 1, LIMIT, 1 << 90];
        for &n in &nums {
            for &d in &dens {
                assert_eq!(div_round_away_i128(n, d), div_round_wide(n, d), "{n} / {d}");
            }
        }
    }

    #[test]
    fn reciprocal_within_eight() {
        let check = |w: u32| {
            let exact = (1u128 << 62) / u128::from(w);
            let r = u128::from(reciprocal62(w));
            assert!(r.abs_diff(exact) <= 8, "w {w}: {r} vs {exact}");
            // Never above the quotient, so below 2^32 (`Divisor` multiplies
            // it as a 32-bit operand).
            assert!(r <= exact && r < 1 << 32, "w {w}: {r} vs {exact}");
        };
        for w in [
            1 << 30,
            (1 << 30) + 1,
            (1 << 31) - 1,
            (1 << 31) - 2,
            3 << 29,
            0x5555_5555,
            0x7FFF_8000,
            0x4000_7FFF,
        ] {
            check(w);
        }
        let mut x = 0x1234_5678u32;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            check((1 << 30) | (x >> 2));
        }
    }

    proptest::proptest! {
        #[test]
        fn rounded_division_by_a_short_divisor_matches_its_definition(
            n in proptest::prelude::any::<i128>().prop_map(|n| n >> 2),
            d in 1i128..(1i128 << 16),
        ) {
            proptest::prop_assert_eq!(div_round_away_i128(n, d), div_round_wide(n, d));
        }

        #[test]
        fn nearest_division_matches_its_definition(
            num in proptest::prelude::any::<i128>().prop_map(|n| n >> 4),
            den_bits in 1u32..=124,
            den in proptest::prelude::any::<i128>(),
        ) {
            // Any sign, divisors from 1 to 2^123, dividends to 2^123:
            // against i128's own floor division.
            let den = (den >> (128 - den_bits)).max(1) * if den < 0 { -1 } else { 1 };
            let (n, d) = if den < 0 { (-num, -den) } else { (num, den) };
            proptest::prop_assert_eq!(div_round_i128(num, den), (2 * n + d).div_euclid(2 * d));
        }

        #[test]
        fn rounded_division_by_a_long_divisor_matches_its_definition(
            n in proptest::prelude::any::<i128>().prop_map(|n| n >> 8),
            d_bits in 16u32..120,
            d in proptest::prelude::any::<u128>(),
            small_n: bool,
        ) {
            // Divisors from 2^16 to 2^120, dividends to 2^119, or below
            // 2^61 (the quotients below 1 of the per-frame set-up).
            let d = (d >> (128 - d_bits)).max(1) as i128;
            let n = if small_n { n >> 60 } else { n };
            proptest::prop_assert_eq!(div_round_away_i128(n, d), div_round_wide(n, d));
        }

        #[test]
        fn rounded_division_matches_its_definition(
            n in -(1i128 << 62)..(1i128 << 62),
            d in 1i128..(1i128 << 62),
        ) {
            proptest::prop_assert_eq!(div_round_away_i128(n, d), div_round_wide(n, d));
        }
    }
}
