//! A vertex's clip-space `w` ([`ClipW`]) as perspective-correct
//! interpolation needs it: a 24-bit mantissa and an exponent in 32 bits,
//! so the ratio of two of them is taken with no floating point, the same
//! on every target, whether the `w` came from the `f32` or the integer
//! front end.

use crate::front::clip::ClipValue;

/// A positive clip-space `w` in 32 bits: `mantissa · 2^exponent`, a
/// 24-bit mantissa (`2^23..2^24`, as exact as an `f32`'s) and an exponent
/// from -151 to 104, packed so that comparing two
/// packed values compares the `w`s. Only ratios of the `w` of one
/// polygon's corners are used (texture coordinates are interpolated as
/// `u/w`, `v/w` and `1/w`), so any common unit will do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ClipW {
    /// `exponent - EXPONENT_MIN` in the top 8 bits, the mantissa's low 23
    /// bits at the bottom (its top bit, always set, is left out).
    packed: u32,
}

/// The smallest exponent: `w` below `2^(23 + EXPONENT_MIN)` (`2^-128`) is
/// taken as that.
pub(crate) const EXPONENT_MIN: i32 = -151;
/// The largest exponent: any `f32` fits (`2^128 > w`).
pub(crate) const EXPONENT_MAX: i32 = EXPONENT_MIN + 255;

impl ClipW {
    /// `w = 1` (an orthographic camera's, and what a `w` that is not
    /// positive and finite is taken as).
    pub const ONE: Self = Self::packed(1 << 23, -23);

    /// The packed form of a normalised mantissa (`2^23..2^24`) and an
    /// exponent in range.
    const fn packed(mantissa: u32, exponent: i32) -> Self {
        Self {
            packed: (((exponent - EXPONENT_MIN) as u32) << 24) | (mantissa & 0x7F_FFFF),
        }
    }

    /// The mantissa, `2^23..2^24`.
    fn mantissa(self) -> u32 {
        (self.packed & 0x7F_FFFF) | 1 << 23
    }

    /// The exponent.
    fn exponent(self) -> i32 {
        (self.packed >> 24) as i32 + EXPONENT_MIN
    }

    /// From an `f32` `w`, exactly (one below `2^-128` is taken as
    /// `2^-128`); `w` not positive, or not finite, gives [`Self::ONE`] (a
    /// drawn vertex always has `w > 0`: it lies inside the near plane).
    pub fn from_f32(w: f32) -> Self {
        if !(w > 0.0 && w.is_finite()) {
            return Self::ONE;
        }
        let bits = w.to_bits();
        let biased = ((bits >> 23) & 0xFF) as i32;
        let fraction = bits & 0x7F_FFFF;
        // Normal: 1.fraction · 2^(biased - 127); subnormal: 0.fraction ·
        // 2^-126.
        let (significand, exponent) = if biased == 0 {
            (fraction, -126 - 23)
        } else {
            (fraction | 1 << 23, biased - 127 - 23)
        };
        Self::from_parts(u64::from(significand), exponent)
    }

    /// From a positive integer `w` (the integer front end's, in its own
    /// unit), rounded down to 24 significant bits (a relative error below
    /// `2^-23`); `w <= 0` gives [`Self::ONE`].
    pub fn from_i64(w: i64) -> Self {
        if w <= 0 {
            return Self::ONE;
        }
        Self::from_parts(w as u64, 0)
    }

    /// `significand · 2^exponent` (`significand > 0`), normalised to 24
    /// bits (bits below dropped) and held within the exponent's range.
    fn from_parts(significand: u64, exponent: i32) -> Self {
        let shift = 40 - significand.leading_zeros() as i32;
        let mantissa = if shift >= 0 {
            (significand >> shift) as u32
        } else {
            (significand << -shift) as u32
        };
        match exponent + shift {
            e if e < EXPONENT_MIN => Self::packed(1 << 23, EXPONENT_MIN),
            e if e > EXPONENT_MAX => Self::packed(0xFF_FFFF, EXPONENT_MAX),
            e => Self::packed(mantissa, e),
        }
    }

    /// `w` as an `f64` (exact).
    pub fn to_f64(self) -> f64 {
        f64::from(self.mantissa()) * libm::exp2(f64::from(self.exponent()))
    }

    /// Whether `self <= other`.
    pub fn at_most(self, other: Self) -> bool {
        self.packed <= other.packed
    }

    /// `floor(2^bits · self / other)` for `self <= other` (`bits <= 31`),
    /// at least 1: the weight `w_min / w` of a corner whose `w` is
    /// `other`, in units of `2^-bits`. One 64-bit division.
    #[inline]
    pub(crate) fn ratio(self, other: Self, bits: u32) -> u32 {
        // self / other = (m_s / m_o) · 2^(e_s - e_o), with m_s / m_o in
        // (1/2, 2): (m_s << 32) / m_o < 2^33.
        let quotient = (u64::from(self.mantissa()) << 32) / u64::from(other.mantissa());
        // self <= other: e_s <= e_o, so this is at least 32 - bits.
        let down = (other.exponent() - self.exponent() + 32 - bits as i32).max(0) as u32;
        let value = if down >= 64 { 0 } else { quotient >> down };
        value.clamp(1, 1 << bits) as u32
    }
}

impl Default for ClipW {
    fn default() -> Self {
        Self::ONE
    }
}

impl ClipValue for ClipW {
    /// Interpolated in `f64` (as clipping interpolates positions),
    /// rounded to `f32`.
    fn lerp(self, other: Self, t: f64) -> Self {
        let (a, b) = (self.to_f64(), other.to_f64());
        Self::from_f32((a + (b - a) * t) as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_f32_is_exact() {
        for w in [
            1.0f32,
            0.1,
            3.25,
            2e-38,
            f32::MIN_POSITIVE,
            f32::MAX,
            123_456.79,
        ] {
            assert_eq!(ClipW::from_f32(w).to_f64(), f64::from(w), "{w}");
        }
        // Below 2^-128 (subnormal f32s among them): 2^-128.
        assert_eq!(ClipW::from_f32(1e-40).to_f64(), libm::exp2(-128.0));
        // Comparing packed values compares the ws.
        let ws = [1e-30f32, 0.1, 0.5, 1.0, 1.0000001, 7.0, 1e20, f32::MAX];
        for a in ws {
            for b in ws {
                assert_eq!(
                    ClipW::from_f32(a).at_most(ClipW::from_f32(b)),
                    a <= b,
                    "{a} {b}"
                );
            }
        }
        for w in [0.0f32, -1.0, f32::NAN, f32::INFINITY] {
            assert_eq!(ClipW::from_f32(w), ClipW::ONE, "{w}");
        }
        assert_eq!(ClipW::from_i64(1 << 47).to_f64(), (1u64 << 47) as f64);
        assert_eq!(ClipW::from_i64(12345).to_f64(), 12345.0);
        // 24 significant bits, the rest dropped.
        let w = (1i64 << 40) + 12345;
        assert_eq!(ClipW::from_i64(w).to_f64(), (1u64 << 40) as f64);
        assert_eq!(ClipW::from_i64(0), ClipW::ONE);
    }

    /// The ratio is the floored quotient, for `w`s close together, far
    /// apart and across exponents.
    #[test]
    fn ratios_are_floored_quotients() {
        let ws = [
            0.1f32, 0.1000001, 0.37, 1.0, 1.5, 2.0, 9.99, 10.0, 1e4, 3e-5,
        ];
        for &a in &ws {
            for &b in &ws {
                let (wa, wb) = (ClipW::from_f32(a), ClipW::from_f32(b));
                if !wa.at_most(wb) {
                    assert!(wb.at_most(wa));
                    continue;
                }
                for bits in [11, 16, 23] {
                    let exact = (f64::from(a) / f64::from(b) * f64::from(1u32 << bits)).floor();
                    let got = f64::from(wa.ratio(wb, bits));
                    assert_eq!(got, exact.max(1.0), "{a}/{b} at {bits}");
                }
            }
        }
        assert_eq!(ClipW::ONE.ratio(ClipW::ONE, 23), 1 << 23);
    }
}
