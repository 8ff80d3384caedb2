//! The numbers every layer agrees on: the sub-pixel grid of screen
//! coordinates, the input depth format, the guard band, and the limits of
//! frames, polygons and mesh faces, and the scales of a quantized mesh.
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

/// Most corners a mesh face may have: clipping adds at most one corner per
/// plane (six), and a polygon has at most
/// [`MAX_POLYGON_CORNERS`].
pub const MAX_FACE_CORNERS: usize = MAX_POLYGON_CORNERS - 6;
/// Half-width of the band around the frame's centre, in pixels, inside
/// which vertices are projected as they are. Faces reaching beyond it are
/// clipped to it. It is half the core's guard band
/// ([`GUARD_BAND_PX`]), so rounding
/// can never push a vertex out of the core's range.
pub const CLIP_BAND_PX: f32 = (GUARD_BAND_PX / 2) as f32;

/// A quantized coordinate `q` is `q / POSITION_SCALE` bounding-sphere
/// radii from the centre.
pub const POSITION_SCALE: i32 = 32_767;
/// A quantized normal component `n` is `n / NORMAL_SCALE`.
pub const NORMAL_SCALE: i32 = 32_767;
/// A quantized texture coordinate `q` is `q / UV_SCALE` (so from -8 to
/// just under 8 texture sizes, in steps of `1/4096`).
pub const UV_SCALE: i32 = 4096;
