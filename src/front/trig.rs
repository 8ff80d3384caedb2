//! Sine and cosine in `f32` arithmetic alone, for the rotation matrices.
//!
//! `libm::sincosf` evaluates its polynomials in `f64`: on a core without
//! a double-precision unit (every Cortex-M0+, M4F and M33) that is
//! soft-float code, 5.6 KB of the RP2040 firmware's flash with its
//! argument reduction. This one is plain `f32` adds and multiplies (each
//! exactly rounded under IEEE 754, none fused), so it gives the same bits
//! on every target, the host included.
//!
//! **Method.** `x` is reduced to `r = x - j·π/2` with `|r| <= π/4` by
//! Cody and Waite's three-part `π/2` (the first part's 8 significant bits
//! make `j·part` exact for `|j| < 2^16`); `sin r` and `cos r` are odd and
//! even polynomials of degree 7 and 8 (Cephes' single-precision
//! coefficients); the quadrant `j mod 4` swaps and negates them.
//!
//! **Error.** For `|x| <= REDUCTION_LIMIT` (8192 radians), within
//! `SIN_COS_ERROR` (`2^-23`, two units of the last place at 1) of the
//! exact sine and cosine (tested against `f64` over the whole range and
//! at the quadrant boundaries). A larger `|x|` is first taken modulo the
//! `f32` nearest `2π` exactly (`libm::fmodf`); that `2π` is `1.75e-7`
//! above the true one, so the angle is off by that much per turn: a
//! rotation of `10^6` radians is off by about `0.03` radians. NaN and
//! infinities give NaN.

use core::f32::consts::FRAC_2_PI;

/// Below this `|x|` (radians) the reduction keeps the stated error.
pub const REDUCTION_LIMIT: f32 = 8192.0;

/// The largest error of [`sin_cos`] for `|x| <= REDUCTION_LIMIT` (the
/// tests hold it to this; measured 9.1e-8, 1.52 units of `2^-24`).
#[cfg_attr(not(test), allow(dead_code))]
pub const SIN_COS_ERROR: f64 = 1.0 / (1u32 << 23) as f64;

/// `π/2` in three parts: the first has 8 significant bits, the second
/// and third carry the rest (their sum is `π/2` to about `2^-55`).
const PIO2_HI: f32 = 1.570_312_5;
const PIO2_MID: f32 = 4.837_513e-4;
const PIO2_LO: f32 = 7.549_79e-8;

/// `(sin x, cos x)`.
pub fn sin_cos(x: f32) -> (f32, f32) {
    if !x.is_finite() {
        return (f32::NAN, f32::NAN);
    }
    let x = if x.abs() > REDUCTION_LIMIT {
        libm::fmodf(x, 2.0 * core::f32::consts::PI)
    } else {
        x
    };
    let y = x * FRAC_2_PI;
    // Rounded to nearest: |y| < 5216, no overflow.
    let j = (y + if y >= 0.0 { 0.5 } else { -0.5 }) as i32;
    let jf = j as f32;
    let r = ((x - jf * PIO2_HI) - jf * PIO2_MID) - jf * PIO2_LO;
    let z = r * r;
    let sin = r + r * z * ((-1.951_529_6e-4 * z + 8.332_161e-3) * z - 1.666_665_5e-1);
    let cos = 1.0 - 0.5 * z + z * z * ((2.443_315_7e-5 * z - 1.388_731_6e-3) * z + 4.166_664_6e-2);
    match j & 3 {
        0 => (sin, cos),
        1 => (cos, -sin),
        2 => (-sin, -cos),
        _ => (-cos, sin),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest error of `sin_cos` against `f64`'s sine and cosine of
    /// the same `f32`, over `xs`.
    fn largest_error(xs: impl Iterator<Item = f32>) -> f64 {
        let mut worst = 0.0f64;
        for x in xs {
            let (s, c) = sin_cos(x);
            let exact = f64::from(x);
            let e = (f64::from(s) - exact.sin())
                .abs()
                .max((f64::from(c) - exact.cos()).abs());
            assert!(e <= SIN_COS_ERROR, "{x:e}: error {e:e}");
            worst = worst.max(e);
        }
        worst
    }

    /// Every 257th `f32` up to the reduction limit, both signs, within
    /// the bound (and the bound is not loose by more than a factor 4).
    #[test]
    fn within_the_bound_up_to_the_reduction_limit() {
        let limit = REDUCTION_LIMIT.to_bits();
        let xs = (0..=limit)
            .step_by(257)
            .map(f32::from_bits)
            .flat_map(|x| [x, -x]);
        let worst = largest_error(xs);
        assert!(worst > SIN_COS_ERROR / 4.0, "{worst:e}");
    }

    /// Around every quadrant boundary `k·π/4` up to the limit, where the
    /// reduction and the quadrant switch meet.
    #[test]
    fn within_the_bound_at_the_quadrant_boundaries() {
        let mut xs = [0.0f32; 0].to_vec();
        let mut k = 0.0f64;
        while k * core::f64::consts::FRAC_PI_4 <= f64::from(REDUCTION_LIMIT) {
            let centre = (k * core::f64::consts::FRAC_PI_4) as f32;
            let mut x = centre;
            for _ in 0..4 {
                xs.extend([x, -x]);
                x = f32::from_bits(x.to_bits() + 1);
            }
            let mut x = centre;
            for _ in 0..4 {
                xs.extend([x, -x]);
                x = f32::from_bits(x.to_bits().saturating_sub(1));
            }
            k += 1.0;
        }
        largest_error(xs.into_iter());
    }

    /// Beyond the limit: the angle modulo the `f32` `2π`, as documented,
    /// and a unit vector still.
    #[test]
    fn beyond_the_limit_is_modulo_the_f32_two_pi() {
        let tau = f64::from(2.0 * core::f32::consts::PI);
        for x in [
            8192.5f32,
            -1.0e4,
            123_456.8,
            1.0e6,
            -3.0e9,
            f32::MAX,
            f32::MIN_POSITIVE,
        ] {
            let (s, c) = sin_cos(x);
            let reduced = f64::from(x) % tau;
            if x.abs() > REDUCTION_LIMIT {
                assert!(
                    (f64::from(s) - reduced.sin()).abs() <= 2.0 * SIN_COS_ERROR,
                    "{x:e}"
                );
                assert!(
                    (f64::from(c) - reduced.cos()).abs() <= 2.0 * SIN_COS_ERROR,
                    "{x:e}"
                );
            }
            let norm = f64::from(s).powi(2) + f64::from(c).powi(2);
            assert!((norm - 1.0).abs() < 1e-6, "{x:e}");
        }
        for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan());
        }
    }
}
