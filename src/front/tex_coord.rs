//! A vertex's texture coordinates with its clip-space `w`
//! ([`TexCoord`]), what perspective-correct texture mapping
//! ([`Textured`](crate::paint::Textured)) interpolates.

use crate::front::clip::ClipValue;
use crate::front::clip_w::ClipW;
use crate::limits::UV_SCALE;

/// Texture coordinates per texture size: `1.0` in [`TexCoord`]'s units.
pub const UV_ONE: i32 = 1 << 16;

/// A vertex's texture coordinates and clip-space `w`: `uv` in units of
/// `1/`[`UV_ONE`] of the texture's size, `u` to the right and `v` down
/// from the texture's top row (OBJ's `vt` has `v` up: see
/// [`Self::from_obj`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TexCoord {
    /// `u` and `v` (down), `1/UV_ONE` of the texture's size.
    pub uv: [i32; 2],
    /// The vertex's clip-space `w`.
    pub w: ClipW,
}

impl TexCoord {
    /// Coordinates as OBJ's `vt` gives them (`v` up from the bottom row),
    /// rounded to `1/UV_ONE`; values beyond `±2^14` texture sizes, and
    /// NaN, are taken as the nearest in range (0 for NaN).
    pub fn from_obj(uv: [f32; 2], w: ClipW) -> Self {
        const LIMIT: f32 = (1 << 14) as f32;
        let unit = |c: f32| {
            let scaled = c.clamp(-LIMIT, LIMIT) * UV_ONE as f32;
            // Saturating, NaN to 0.
            libm::floorf(scaled + 0.5) as i32
        };
        Self {
            uv: [unit(uv[0]), UV_ONE - unit(uv[1])],
            w,
        }
    }
}

impl TexCoord {
    /// Coordinates stored in a quantized mesh (`q / UV_SCALE`, `v` up),
    /// exactly: `UV_ONE / UV_SCALE` is 16.
    pub fn from_quantized(q: [i16; 2], w: ClipW) -> Self {
        const STEP: i32 = UV_ONE / UV_SCALE;
        Self {
            uv: [i32::from(q[0]) * STEP, UV_ONE - i32::from(q[1]) * STEP],
            w,
        }
    }
}

impl ClipValue for TexCoord {
    /// `u`, `v` and `w` interpolated in clip space, as a cut corner's
    /// position is (which is what perspective-correct means there).
    fn lerp(self, other: Self, t: f64) -> Self {
        let mix = |a: i32, b: i32| {
            let (a, b) = (f64::from(a), f64::from(b));
            libm::floor(a + (b - a) * t + 0.5) as i32
        };
        Self {
            uv: [mix(self.uv[0], other.uv[0]), mix(self.uv[1], other.uv[1])],
            w: self.w.lerp(other.w, t),
        }
    }
}
