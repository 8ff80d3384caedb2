//! Exact wide products (and 64-bit shifts), cheap on a core without a
//! long multiply.
//!
//! A Cortex-M0+ (ARMv6-M) multiplies 32x32 to the low 32 bits only: every
//! `i64` product compiles to a call of compiler-builtins' `__aeabi_lmul`,
//! about 37 instructions plus the call. Most of the set-up products of the
//! core have 32-bit operands, or one 64-bit operand and one small one, and
//! need far less: these functions compute them from 16-bit halves inline.
//! Everywhere else (the host, ARMv7-M and later, which have `UMULL`) they
//! are the ordinary product, so the host's code does not change.
//!
//! Every function returns the exact product; those with an `i64` result
//! require that the product fits `i64` (each call site states its range),
//! and compute it modulo `2^64`, which is then exact. The halves path is
//! compiled and tested on every target.

/// Whether this target lacks a 32x32→64 multiply: ARMv6-M, the one Arm
/// profile without it.
const HALVES: bool = super::ARMV6M;

/// `a·b` for unsigned 32-bit operands, from four 16-bit products.
#[inline(always)]
fn umul32_by_halves(a: u32, b: u32) -> u64 {
    let (a0, a1) = (a & 0xFFFF, a >> 16);
    let (b0, b1) = (b & 0xFFFF, b >> 16);
    // Each partial product is below 2^32.
    let (low, high) = (a0 * b0, a1 * b1);
    let (mid, mid_carry) = (a0 * b1).overflowing_add(a1 * b0);
    let (low, low_carry) = low.overflowing_add(mid << 16);
    // The high word of the exact product, which is below 2^32: no partial
    // sum overflows.
    let high = high + (mid >> 16) + (u32::from(mid_carry) << 16) + u32::from(low_carry);
    (u64::from(high) << 32) | u64::from(low)
}

/// `a·b` for unsigned 32-bit operands.
#[inline(always)]
pub(crate) fn mul_u32(a: u32, b: u32) -> u64 {
    if HALVES {
        umul32_by_halves(a, b)
    } else {
        u64::from(a) * u64::from(b)
    }
}

/// [`mul_u32`] when `b` is often below `2^16`: on a core without a long
/// multiply, two 16-bit products then, four otherwise.
#[inline(always)]
pub(crate) fn mul_u32_by_size(a: u32, b: u32) -> u64 {
    if HALVES {
        if b < 1 << 16 {
            umul32_small(a, b)
        } else {
            umul32_by_halves(a, b)
        }
    } else {
        u64::from(a) * u64::from(b)
    }
}

/// `p_x·q_y - p_y·q_x`, the cross product of two screen vectors whose
/// components fit `i32` (below `2^63` in magnitude). On a core without a
/// long multiply: when every component lies in `[-2^15, 2^15)` (triangles
/// under 128 px each way), in 32 bits (each product at most `2^30`, the
/// difference below `2^31`); else when `q`'s components are below `2^16`,
/// from two 16-bit products each.
#[inline(always)]
pub(crate) fn cross(px: i32, py: i32, qx: i32, qy: i32) -> i64 {
    if HALVES {
        cross_by_halves(px, py, qx, qy)
    } else {
        i64::from(px) * i64::from(qy) - i64::from(py) * i64::from(qx)
    }
}

/// Whether every one of `xs` lies in `[-2^15, 2^15)`, so that a product
/// of two is at most `2^30` and a difference of two products fits `i32`.
#[inline(always)]
fn all_short(xs: [i32; 4]) -> bool {
    // x + 2^15 < 2^16 as u32 exactly when -2^15 <= x < 2^15.
    let short = |x: i32| x.wrapping_add(1 << 15) as u32;
    (short(xs[0]) | short(xs[1]) | short(xs[2]) | short(xs[3])) < 1 << 16
}

/// [`cross`] on a core without a long multiply.
#[inline(always)]
fn cross_by_halves(px: i32, py: i32, qx: i32, qy: i32) -> i64 {
    if all_short([px, py, qx, qy]) {
        i64::from(px * qy - py * qx)
    } else if qx.unsigned_abs() < 1 << 16 && qy.unsigned_abs() < 1 << 16 {
        mul_i32_small_by_halves(px, qy) - mul_i32_small_by_halves(py, qx)
    } else {
        mul_i32_by_halves(px, qy) - mul_i32_by_halves(py, qx)
    }
}

/// `a·b` for signed 32-bit operands (`|a·b| <= 2^62`, always in `i64`)
/// from 16-bit halves. With `A = a mod 2^32`, `B = b mod
/// 2^32`: `A·B = a·b + 2^32·([a<0]·b + [b<0]·a) (mod 2^64)`, so the high
/// word only needs two subtractions.
#[inline(always)]
fn mul_i32_by_halves(a: i32, b: i32) -> i64 {
    let p = umul32_by_halves(a as u32, b as u32);
    let mut high = (p >> 32) as u32;
    if a < 0 {
        high = high.wrapping_sub(b as u32);
    }
    if b < 0 {
        high = high.wrapping_sub(a as u32);
    }
    ((u64::from(high) << 32) | (p & 0xFFFF_FFFF)) as i64
}

/// `a·b` for an unsigned and a signed 32-bit operand (`|a·b| < 2^63`,
/// always in `i64`).
#[inline(always)]
pub(crate) fn mul_u32_i32(a: u32, b: i32) -> i64 {
    if HALVES {
        // The product of the magnitudes, then the sign (see
        // `mul_i64_i32_by_halves` for why not a correction).
        let p = umul32_by_halves(a, b.unsigned_abs()) as i64;
        if b < 0 { -p } else { p }
    } else {
        i64::from(a) * i64::from(b)
    }
}

/// Largest coefficient magnitude [`dot3_plus`] takes: `2^30`.
pub(crate) const DOT3_COEFFICIENT_MAX: i32 = 1 << 30;

/// `a·q + offset`: the dot product of three coefficients with three 16-bit
/// coordinates, plus an offset. Every `|a[k]|` is at most
/// [`DOT3_COEFFICIENT_MAX`], so `|a·q| <= 3·2^45`, and `|offset| < 2^62`
/// keeps the sum in `i64`.
#[inline(always)]
pub(crate) fn dot3_plus(a: [i32; 3], q: [i16; 3], offset: i64) -> i64 {
    if HALVES {
        dot3_plus_by_halves(a, q, offset)
    } else {
        (0..3)
            .map(|k| i64::from(a[k]) * i64::from(q[k]))
            .sum::<i64>()
            + offset
    }
}

/// [`dot3_plus`] in 32-bit products: each coefficient is split as
/// `a = h·2^16 + l` (`h = a >> 16`, `l` in `[0, 2^16)`), and as
/// `|a| <= 2^30`, `|h| <= 2^14`:
///
/// | quantity | range | held in |
/// |---|---|---|
/// | `h·q` | `[-2^29, 2^29]` | `i32` |
/// | `Σ h·q` (three terms) | `[-3·2^29, 3·2^29]` | `i32` |
/// | `l·q` | `(-2^31, 2^31)` | `i32` |
/// | `Σ l·q` | `(-3·2^31, 3·2^31)` | `i64` |
///
/// and `Σ h·q · 2^16 + Σ l·q + offset` in `i64`.
#[inline(always)]
fn dot3_plus_by_halves(a: [i32; 3], q: [i16; 3], offset: i64) -> i64 {
    let q = q.map(i32::from);
    let high = (a[0] >> 16) * q[0] + (a[1] >> 16) * q[1] + (a[2] >> 16) * q[2];
    let low = |k: usize| i64::from((a[k] & 0xFFFF) * q[k]);
    (i64::from(high) << 16) + low(0) + low(1) + low(2) + offset
}

/// `a·b` for a 64-bit and a signed 32-bit operand, when the product fits
/// `i64`.
#[inline(always)]
pub(crate) fn mul_i64_i32(a: i64, b: i32) -> i64 {
    if HALVES {
        mul_i64_i32_by_halves(a, b)
    } else {
        a * i64::from(b)
    }
}

/// [`mul_i64_i32`] from 16-bit halves, modulo `2^64`: with `m = |b|` and
/// `a = h·2^32 + l` (`l` unsigned), `a·m = l·m + 2^32·h·m`, of which only
/// the low word of `h·m` matters; then the sign of `b`. (Written with
/// `|b|` rather than a correction for `b < 0`: LLVM recognises the latter
/// as a 64-bit product and calls `__aeabi_lmul` again.)
#[inline(always)]
fn mul_i64_i32_by_halves(a: i64, b: i32) -> i64 {
    mul_i64_by_magnitude(a, b, umul32_by_halves)
}

/// `a·b` modulo `2^64` from `|b|`: the low word's product by `low_product`
/// (exact for the `|b|` it is given), the high word's low half, the sign.
#[inline(always)]
fn mul_i64_by_magnitude(a: i64, b: i32, low_product: impl Fn(u32, u32) -> u64) -> i64 {
    let (low, high) = (a as u32, (a >> 32) as u32);
    let m = b.unsigned_abs();
    let p = low_product(low, m).wrapping_add(u64::from(high.wrapping_mul(m)) << 32);
    let p = p as i64;
    if b < 0 { p.wrapping_neg() } else { p }
}

/// `a·s - b·t` for 32-bit `a`, `b` and small `s`, `t` (`|s|, |t| <
/// 2^16`, so each product is below `2^47`): on a core without a long
/// multiply, in 32 bits when all four lie in `[-2^15, 2^15)` (as for
/// [`cross`]), else each from two 16-bit products.
#[inline(always)]
pub(crate) fn mul_sub_small(a: i32, s: i32, b: i32, t: i32) -> i64 {
    if HALVES {
        mul_sub_small_by_halves(a, s, b, t)
    } else {
        i64::from(a) * i64::from(s) - i64::from(b) * i64::from(t)
    }
}

/// [`mul_sub_small`] on a core without a long multiply.
#[inline(always)]
fn mul_sub_small_by_halves(a: i32, s: i32, b: i32, t: i32) -> i64 {
    debug_assert!(s.unsigned_abs() < 1 << 16 && t.unsigned_abs() < 1 << 16);
    if all_short([a, s, b, t]) {
        i64::from(a * s - b * t)
    } else {
        mul_i32_small_by_halves(a, s) - mul_i32_small_by_halves(b, t)
    }
}

/// `a·m` for `m < 2^16`: `a = h·2^16 + l`, and `l·m`, `h·m` are each below
/// `2^32`.
#[inline(always)]
fn umul32_small(a: u32, m: u32) -> u64 {
    let (low, high) = ((a & 0xFFFF) * m, (a >> 16) * m);
    u64::from(low) + (u64::from(high) << 16)
}

/// `a·b` for a 32-bit `a` and a small `b` (`|b| < 2^16`, so the product
/// is below `2^47`) from two 16-bit products of the magnitudes, not four
/// (see `mul_i64_i32_by_halves` for why not a correction).
#[inline(always)]
fn mul_i32_small_by_halves(a: i32, b: i32) -> i64 {
    let p = umul32_small(a.unsigned_abs(), b.unsigned_abs()) as i64;
    if (a ^ b) < 0 { -p } else { p }
}

/// `a·b` for a 64-bit `a` and a small `b` (`|b| < 2^16`), when the
/// product fits `i64`: three 16-bit products instead of five.
#[inline(always)]
pub(crate) fn mul_i64_small(a: i64, b: i32) -> i64 {
    debug_assert!(b.unsigned_abs() < 1 << 16);
    if HALVES {
        mul_i64_small_by_halves(a, b)
    } else {
        a * i64::from(b)
    }
}

/// [`mul_i64_small`] modulo `2^64`, as [`mul_i64_i32_by_halves`].
#[inline(always)]
fn mul_i64_small_by_halves(a: i64, b: i32) -> i64 {
    mul_i64_by_magnitude(a, b, umul32_small)
}

/// `v >> s` for `s < 32`: a variable 64-bit shift is another call on an
/// ARMv6-M core (`__aeabi_llsr`); from the two words it is a few
/// instructions.
#[inline(always)]
pub(crate) fn shr_u64(v: u64, s: u32) -> u64 {
    debug_assert!(s < 32);
    if HALVES {
        shr_u64_by_words(v, s)
    } else {
        v >> s
    }
}

/// `v >> s` (arithmetic) for `s < 32`: [`shr_u64`] for signed values.
#[inline(always)]
pub(crate) fn shr_i64(v: i64, s: u32) -> i64 {
    debug_assert!(s < 32);
    if HALVES {
        shr_i64_by_words(v, s)
    } else {
        v >> s
    }
}

/// [`shr_i64`] from the two 32-bit words.
#[inline(always)]
fn shr_i64_by_words(v: i64, s: u32) -> i64 {
    let (low, high) = (v as u32, (v >> 32) as i32);
    let low = (low >> s) | (((high as u32) << 1) << (31 - s));
    (i64::from(high >> s) << 32) | i64::from(low)
}

/// `v << s` for `s < 32`, when the result fits `i64`.
#[inline(always)]
pub(crate) fn shl_i64(v: i64, s: u32) -> i64 {
    debug_assert!(s < 32);
    if HALVES {
        shl_i64_by_words(v, s)
    } else {
        v << s
    }
}

/// [`shl_i64`] from the two 32-bit words.
#[inline(always)]
fn shl_i64_by_words(v: i64, s: u32) -> i64 {
    let (low, high) = (v as u32, (v >> 32) as u32);
    let high = (high << s) | ((low >> 1) >> (31 - s));
    ((u64::from(high) << 32) | u64::from(low << s)) as i64
}

/// Leading zeros of a 64-bit value, from its words: one 32-bit count (a
/// call on ARMv6-M, which has no count instruction) rather than two.
#[inline(always)]
pub(crate) fn leading_zeros_u64(v: u64) -> u32 {
    if HALVES {
        let high = (v >> 32) as u32;
        if high != 0 {
            high.leading_zeros()
        } else {
            32 + (v as u32).leading_zeros()
        }
    } else {
        v.leading_zeros()
    }
}

/// [`shr_u64`] from the two 32-bit words.
#[inline(always)]
fn shr_u64_by_words(v: u64, s: u32) -> u64 {
    let (low, high) = (v as u32, (v >> 32) as u32);
    // `high << (32 - s)` would be a shift by 32 when s = 0: shift twice.
    let low = (low >> s) | ((high << 1) << (31 - s));
    (u64::from(high >> s) << 32) | u64::from(low)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const EDGES32: [u32; 9] = [
        0,
        1,
        2,
        0xFFFF,
        0x1_0000,
        0x7FFF_FFFF,
        0x8000_0000,
        0xFFFF_FFFE,
        0xFFFF_FFFF,
    ];

    #[test]
    fn extremes() {
        for &a in &EDGES32 {
            for &b in &EDGES32 {
                assert_eq!(umul32_by_halves(a, b), u64::from(a) * u64::from(b));
                assert_eq!(mul_u32(a, b), u64::from(a) * u64::from(b));
                let (sa, sb) = (a as i32, b as i32);
                let exact = i64::from(sa) * i64::from(sb);
                assert_eq!(mul_i32_by_halves(sa, sb), exact, "{sa} * {sb}");
                assert_eq!(mul_u32_i32(a, sb), i64::from(a) * i64::from(sb));
            }
        }
        // 64-bit by 32-bit at the ends of the ranges the core uses (|a| <
        // 2^40 by |b| < 2^22) and of i64 itself.
        for a in [
            0i64,
            1,
            -1,
            (1 << 40) - 1,
            -(1 << 40) + 1,
            i64::MAX,
            i64::MIN,
        ] {
            for b in [
                0i32,
                1,
                -1,
                (1 << 22) - 1,
                -(1 << 22) + 1,
                i32::MIN,
                i32::MAX,
            ] {
                let exact = i128::from(a) * i128::from(b);
                if let Ok(exact) = i64::try_from(exact) {
                    assert_eq!(mul_i64_i32_by_halves(a, b), exact, "{a} * {b}");
                    assert_eq!(mul_i64_i32(a, b), exact);
                }
            }
        }
    }

    #[test]
    fn small_products_at_the_extremes() {
        let smalls = [-(1 << 16) + 1, -1, 0, 1, 0xFFFF];
        for a in [i32::MIN, i32::MIN + 1, -1, 0, 1, 0xFFFF, 0x1_0000, i32::MAX] {
            for &b in &smalls {
                let exact = i64::from(a) * i64::from(b);
                assert_eq!(mul_i32_small_by_halves(a, b), exact, "{a} * {b}");
            }
        }
        for a in [
            0i64,
            1,
            -1,
            (1 << 40) - 1,
            -(1 << 40) + 1,
            (1 << 47) - 1,
            -(1 << 47),
        ] {
            for &b in &smalls {
                let exact = a * i64::from(b);
                assert_eq!(mul_i64_small_by_halves(a, b), exact, "{a} * {b}");
                assert_eq!(mul_i64_small(a, b), exact);
            }
        }
    }

    #[test]
    fn products_by_size() {
        for &a in &EDGES32 {
            for &b in &EDGES32 {
                assert_eq!(mul_u32_by_size(a, b), u64::from(a) * u64::from(b));
                if b < 1 << 16 {
                    assert_eq!(umul32_small(a, b), u64::from(a) * u64::from(b));
                }
            }
        }
    }

    #[test]
    fn dot_products_at_the_extremes() {
        let m = DOT3_COEFFICIENT_MAX;
        let ends = [
            -m,
            -m + 1,
            -(1 << 16) - (1 << 15),
            -(1 << 15) - 1,
            -(1 << 15),
            -(1 << 15) + 1,
            -1,
            0,
            1,
            (1 << 15) - 1,
            1 << 15,
            (1 << 15) + 1,
            0xFFFF,
            0x1_0000,
            m - 1,
            m,
        ];
        let coords = [i16::MIN, i16::MIN + 1, -1, 0, 1, i16::MAX - 1, i16::MAX];
        let offsets = [0, 1 << 45, -(1 << 61), (1 << 61) + 12345];
        let mut terms = [(0i32, 0i16); 16 * 7];
        for (k, term) in terms.iter_mut().enumerate() {
            *term = (ends[k / 7], coords[k % 7]);
        }
        // Every extreme term in every place, with a spread of partners.
        for (k, &(a0, q0)) in terms.iter().enumerate() {
            for &(a1, q1) in terms.iter().skip(k % 7).step_by(7) {
                for &(a2, q2) in terms.iter().skip(k % 5).step_by(5) {
                    for &offset in &offsets {
                        let (a3, q3) = ([a0, a1, a2], [q0, q1, q2]);
                        let exact: i64 = (0..3).map(|j| i64::from(a3[j]) * i64::from(q3[j])).sum();
                        let got = dot3_plus_by_halves(a3, q3, offset);
                        assert_eq!(got, exact + offset, "{a3:?} {q3:?}");
                        assert_eq!(dot3_plus(a3, q3, offset), exact + offset);
                    }
                }
            }
        }
        // The largest sums of each part: every `h·q` and `l·q` at its end.
        for (a, q) in [
            (m, i16::MIN),
            (-m, i16::MIN),
            (1 << 15, i16::MIN),
            (-(1 << 15) + 1, i16::MIN),
        ] {
            let exact = 3 * i64::from(a) * i64::from(q);
            assert_eq!(dot3_plus_by_halves([a; 3], [q; 3], 0), exact, "{a} {q}");
        }
    }

    #[test]
    fn shifts_by_words() {
        for v in [
            0u64,
            1,
            u64::MAX,
            1 << 63,
            0x8000_0000,
            0x1_0000_0000,
            0x0123_4567_89AB_CDEF,
        ] {
            for s in 0..32 {
                assert_eq!(shr_u64_by_words(v, s), v >> s, "{v:#x} >> {s}");
                assert_eq!(shr_u64(v, s), v >> s);
            }
        }
    }

    #[test]
    fn signed_shifts_and_counts_at_the_extremes() {
        for v in [
            0i64,
            1,
            -1,
            i64::MAX,
            i64::MIN,
            1 << 47,
            -(1 << 47),
            0x0123_4567_89AB_CDEF,
        ] {
            for s in 0..32 {
                assert_eq!(shr_i64_by_words(v, s), v >> s, "{v:#x} >> {s}");
                assert_eq!(shr_i64(v, s), v >> s);
                if let Some(exact) = v.checked_mul(1 << s) {
                    assert_eq!(shl_i64_by_words(v, s), exact, "{v:#x} << {s}");
                    assert_eq!(shl_i64(v, s), exact);
                }
            }
            assert_eq!(leading_zeros_u64(v as u64), (v as u64).leading_zeros());
        }
        for k in 0..64 {
            assert_eq!(leading_zeros_u64(1 << k), 63 - k);
        }
    }

    /// `mul_sub_small` on both paths, at the edges of the 32-bit one.
    #[test]
    fn small_differences_at_the_short_bounds() {
        let wide = [
            i32::MIN,
            -(1 << 24),
            -(1 << 15) - 1,
            -(1 << 15),
            -1,
            0,
            1,
            (1 << 15) - 1,
            1 << 15,
            1 << 24,
            i32::MAX,
        ];
        let small = [
            -(1 << 16) + 1,
            -(1 << 15) - 1,
            -(1 << 15),
            -1,
            0,
            1,
            (1 << 15) - 1,
            1 << 15,
            (1 << 16) - 1,
        ];
        for a in wide {
            for s in small {
                for b in wide {
                    for t in small {
                        let exact = i64::from(a) * i64::from(s) - i64::from(b) * i64::from(t);
                        assert_eq!(
                            mul_sub_small_by_halves(a, s, b, t),
                            exact,
                            "{a} {s} {b} {t}"
                        );
                        assert_eq!(mul_sub_small(a, s, b, t), exact);
                    }
                }
            }
        }
    }

    /// The 32-bit path of the cross product at its edges: every component
    /// at `-2^15` or `2^15 - 1` (in it), and one at `2^15` or `-2^15 - 1`
    /// (out of it).
    #[test]
    fn cross_products_at_the_short_bounds() {
        let values = [-(1 << 15) - 1, -(1 << 15), -1, 0, 1, (1 << 15) - 1, 1 << 15];
        for px in values {
            for py in values {
                for qx in values {
                    for qy in values {
                        let exact = i64::from(px) * i64::from(qy) - i64::from(py) * i64::from(qx);
                        assert_eq!(
                            cross_by_halves(px, py, qx, qy),
                            exact,
                            "{px} {py} {qx} {qy}"
                        );
                    }
                }
            }
        }
    }

    proptest! {
        #[test]
        fn shifts_are_exact(v: u64, s in 0u32..32) {
            prop_assert_eq!(shr_u64_by_words(v, s), v >> s);
            prop_assert_eq!(shr_i64_by_words(v as i64, s), (v as i64) >> s);
            prop_assert_eq!(shl_i64_by_words(v as i64, s), (v as i64) << s);
        }

        #[test]
        fn small_products_are_exact(a: i32, b in -(1i32 << 16) + 1..(1 << 16), c in -(1i64 << 47)..(1i64 << 47)) {
            prop_assert_eq!(mul_i32_small_by_halves(a, b), i64::from(a) * i64::from(b));
            prop_assert_eq!(mul_i64_small_by_halves(c, b), c * i64::from(b));
        }

        #[test]
        fn cross_products_are_exact(
            p in proptest::array::uniform2(-(1i32 << 30)..(1 << 30)),
            q in proptest::array::uniform2(-(1i32 << 16) + 1..(1 << 16)),
            wide: bool,
        ) {
            // Small q (the halves path on an M0+) or any; and every
            // component short (the 32-bit path there).
            let q = if wide { [q[0] << 14, q[1] << 14] } else { q };
            for p in [p, [p[0] >> 15, p[1] >> 15]] {
                let q = if p[0].unsigned_abs() < 1 << 15 { [q[0] >> 1, q[1] >> 1] } else { q };
                let exact = i128::from(p[0]) * i128::from(q[1]) - i128::from(p[1]) * i128::from(q[0]);
                prop_assert_eq!(i128::from(cross(p[0], p[1], q[0], q[1])), exact);
                prop_assert_eq!(i128::from(cross_by_halves(p[0], p[1], q[0], q[1])), exact);
            }
        }

        #[test]
        fn dot_products_are_exact(
            a in prop::array::uniform3(-DOT3_COEFFICIENT_MAX..=DOT3_COEFFICIENT_MAX),
            q: [i16; 3],
            offset in -(1i64 << 61)..(1i64 << 61),
        ) {
            let exact: i64 = (0..3).map(|k| i64::from(a[k]) * i64::from(q[k])).sum();
            prop_assert_eq!(dot3_plus_by_halves(a, q, offset), exact + offset);
        }

        #[test]
        fn products_are_exact(a: u32, b: u32, c in -(1i64 << 40)..(1i64 << 40), d in -(1i32 << 22)..(1i32 << 22)) {
            prop_assert_eq!(umul32_by_halves(a, b), u64::from(a) * u64::from(b));
            let (sa, sb) = (a as i32, b as i32);
            prop_assert_eq!(mul_i32_by_halves(sa, sb), i64::from(sa) * i64::from(sb));
            prop_assert_eq!(mul_u32_i32(a, sb), i64::from(a) * i64::from(sb));
            prop_assert_eq!(mul_i64_i32_by_halves(c, d), c * i64::from(d));
            // Any i64 by any i32 whose product fits.
            let e = (i64::from(a) << 32 | i64::from(b)) >> (a % 40);
            if let Ok(exact) = i64::try_from(i128::from(e) * i128::from(sb)) {
                prop_assert_eq!(mul_i64_i32_by_halves(e, sb), exact);
            }
        }
    }
}
