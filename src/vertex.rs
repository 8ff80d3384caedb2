//! Screen-space vertices: the renderer's input.

use crate::error::Error;
use crate::fixed::{DEPTH_MAX, GUARD_BAND, depth_from_f32, subpixel_from_f32};

/// A vertex after projection: position on the sub-pixel grid and depth.
///
/// `x` and `y` are in 1/256 pixel ([`SUBPIXEL_STEPS`](crate::fixed::SUBPIXEL_STEPS)),
/// `z` is Q0.24 with 0 at the near plane and
/// [`DEPTH_MAX`](crate::fixed::DEPTH_MAX) at the far plane (smaller is
/// nearer). `z` must be affine in screen space (e.g. `z_ndc`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ScreenVertex {
    /// x in sub-pixel steps, to the right.
    pub x: i32,
    /// y in sub-pixel steps, downwards.
    pub y: i32,
    /// Depth, Q0.24, smaller is nearer.
    pub z: u32,
}

impl ScreenVertex {
    /// A vertex from raw fixed-point values, checked against the guard band
    /// and the depth range.
    pub const fn new(x: i32, y: i32, z: u32) -> Result<Self, Error> {
        let v = Self { x, y, z };
        match v.check() {
            Ok(()) => Ok(v),
            Err(e) => Err(e),
        }
    }

    /// A vertex from pixel coordinates and a depth in `[0, 1]`; NaN,
    /// infinities and out-of-range values are errors.
    pub fn from_f32(x: f32, y: f32, depth: f32) -> Result<Self, Error> {
        let x = subpixel_from_f32(x).ok_or(Error::OutsideGuardBand)?;
        let y = subpixel_from_f32(y).ok_or(Error::OutsideGuardBand)?;
        let z = depth_from_f32(depth).ok_or(Error::DepthOutOfRange)?;
        Ok(Self { x, y, z })
    }

    /// Checks the guard band and the depth range.
    pub const fn check(&self) -> Result<(), Error> {
        if self.x <= -GUARD_BAND
            || self.x >= GUARD_BAND
            || self.y <= -GUARD_BAND
            || self.y >= GUARD_BAND
        {
            Err(Error::OutsideGuardBand)
        } else if self.z > DEPTH_MAX {
            Err(Error::DepthOutOfRange)
        } else {
            Ok(())
        }
    }
}
