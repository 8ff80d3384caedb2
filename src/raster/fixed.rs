//! Conversions to the fixed-point formats of [`crate::limits`] (the
//! sub-pixel grid, the input depth), and the rule that picks a pixel row
//! or column by its sample.
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

use crate::limits::{DEPTH_MAX, DEPTH_ONE, GUARD_BAND, HALF_PIXEL, SUBPIXEL_BITS, SUBPIXEL_STEPS};

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
    use crate::limits::GUARD_BAND_PX;

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
