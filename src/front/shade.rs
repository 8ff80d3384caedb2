//! Face shading, chosen per draw: every face gets one colour from its
//! [`crate::front::scene::FaceInfo`].
//!
//! Lambert shading has two paths that agree to within one step of 8-bit
//! colour: `f32` for meshes in `f32`, and integers for
//! [quantized meshes](crate::front::quantized), whose view-space normals
//! come from [`FaceInfo::normal_q15`](crate::front::scene::FaceInfo::normal_q15):
//! no floating point per face, the same colour on every target.

use crate::front::fixed_point::{fraction_bits, unit_q15};
use crate::front::geometry::Vec3;
use crate::front::rgb8p8::Rgb8p8;
use crate::front::scene::{FaceInfo, VertexInfo};
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// How faces are coloured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shading {
    /// One colour for every face.
    Flat(Rgb888),
    /// Flat Lambert (see [`Lambert`]).
    Lambert(Lambert),
    /// Grey by view distance of the face's centre: white at `near`, black
    /// at `far` (nearer is brighter).
    Depth {
        /// Distance drawn white.
        near: f32,
        /// Distance drawn black.
        far: f32,
    },
    /// A distinct false colour per face id.
    FaceId,
}

/// Flat Lambert shading: `base · (ambient + (1 - ambient) · max(0, n ·
/// light))`, two-sided (a face seen from behind is lit as if turned to the
/// viewer). `light` points towards the light, in view space.
///
/// The integer path (for faces with [`FaceInfo::normal_q15`]) computes the
/// same in units of `2^-15`: `d = max(0, n · l) >> 15` with `n`, `l` in
/// units of `1/32767` (each product and the sum below `2^31`), `k = a +
/// ((32768 - a) · d) >> 15`, each channel `(v · k + 2^14) >> 15`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lambert {
    base: Rgb888,
    light: Vec3,
    ambient: f32,
    /// `light` in units of `1/32767`.
    light_q15: [i32; 3],
    /// `ambient` in units of `2^-15`.
    ambient_q15: i32,
    /// `base`'s channels over 255, for [`Self::vertex_color`]'s `f32`
    /// path. Not on 32-bit Arm, whose firmware lights quantized normals
    /// in integers: there they are made where used ([`Self::unit_base`]).
    #[cfg(not(target_arch = "arm"))]
    base_unit: [f32; 3],
}

impl Lambert {
    /// Lambert shading of colour `base`, lit from the unit direction
    /// `light` (view space; normalised here), with `ambient` (0 to 1) of
    /// light everywhere.
    pub fn new(base: Rgb888, light: Vec3, ambient: f32) -> Self {
        let raw = light;
        let light = light.normalized();
        let ambient = if ambient.is_finite() {
            ambient.clamp(0.0, 1.0)
        } else {
            0.0
        };
        Self {
            base,
            light,
            ambient,
            // In exact integer arithmetic from the caller's values (not the
            // f32 normalisation above), so every target gets the same
            // integers whatever its floating-point library rounds.
            light_q15: unit_q15([raw.x, raw.y, raw.z]).unwrap_or([0; 3]),
            ambient_q15: fraction_bits(ambient, 15),
            #[cfg(not(target_arch = "arm"))]
            base_unit: unit_channels(base),
        }
    }

    /// The surface colour.
    pub fn base(&self) -> Rgb888 {
        self.base
    }

    /// The unit direction towards the light, view space.
    pub fn light(&self) -> Vec3 {
        self.light
    }

    /// The ambient fraction.
    pub fn ambient(&self) -> f32 {
        self.ambient
    }

    /// The colour of one face.
    pub fn color(&self, face: &FaceInfo) -> Rgb888 {
        if let Some(n) = face.normal_q15() {
            let dot = dot_q15(n, self.light_q15);
            let dot = if face.front { dot } else { -dot };
            // Below 2^15 · (1 + 2^-10) for the normals a quantized mesh
            // accepts; clamped for any other input.
            let d = (dot.max(0) >> 15).min(1 << 15) as i32;
            let a = self.ambient_q15;
            let k = a + (((32768 - a) * d) >> 15);
            let ch = |v: u8| ((i32::from(v) * k + (1 << 14)) >> 15).clamp(0, 255) as u8;
            return Rgb888::new(ch(self.base.r()), ch(self.base.g()), ch(self.base.b()));
        }
        // The same value either way: `normal_dot` keeps a desktop's vector
        // in registers, and on 32-bit Arm (whose integer front end rarely
        // comes here) the plain product keeps the firmware's code as small.
        let d = if cfg!(target_arch = "arm") {
            face.normal().dot(self.light)
        } else {
            face.normal_dot(self.light)
        };
        let d = if face.front { d } else { -d };
        let k = self.ambient + (1.0 - self.ambient) * d.max(0.0);
        scale(self.base, k)
    }

    /// The colour of one vertex, for Gouraud shading, in 8.8 fixed point
    /// (the 8 bits below the 8-bit step are kept for the interpolation):
    /// lit by its normal ([`VertexInfo::normal`]) one-sided, as a surface
    /// whose normals point out; a vertex with no normal is lit as if it
    /// faced the light. A quantized mesh's stored normal
    /// ([`VertexInfo::normal_q15`]) is lit in integers, as
    /// [`Self::color`] lights its faces: the same colour on every target.
    pub fn vertex_color(&self, vertex: &VertexInfo) -> Rgb8p8 {
        if let Some(n) = vertex.normal_q15() {
            // As in `color`: the dot product below 2^30 · (1 + 2^-10), `d`
            // and `k` in Q15, each channel `base · k` below 2^23.
            let d = (dot_q15(n, self.light_q15).max(0) >> 15).min(1 << 15) as i32;
            let a = self.ambient_q15;
            let k = a + (((32768 - a) * d) >> 15);
            // base · k / 2^15 in 8.8: (base · k · 2^8 + 2^14) >> 15.
            let ch = |v: u8| ((i32::from(v) * k + (1 << 6)) >> 7) as u16;
            return Rgb8p8 {
                r: ch(self.base.r()),
                g: ch(self.base.g()),
                b: ch(self.base.b()),
            };
        }
        let d = vertex.normal_dot(self.light).unwrap_or(1.0);
        let k = self.ambient + (1.0 - self.ambient) * d.max(0.0);
        scale_8p8(self.unit_base(), k)
    }

    /// `base`'s channels over 255: made once in [`Self::new`] on a host,
    /// where vertices are lit in `f32`; on 32-bit Arm made here, so that
    /// a firmware that lights quantized normals in integers, or faces
    /// alone, keeps its `Lambert` as small as before (with the field, the
    /// minimal QEMU firmware took 2,520 more instructions a frame). The
    /// same values either way.
    #[inline(always)]
    fn unit_base(&self) -> [f32; 3] {
        #[cfg(target_arch = "arm")]
        return unit_channels(self.base);
        #[cfg(not(target_arch = "arm"))]
        return self.base_unit;
    }
}

/// `n·l` for a view normal `n` from
/// [`FixedFrame::view_normal`](crate::front::fixed_point::FixedFrame::view_normal)
/// (`|n_k| <= 2^16`: an `i32` shifted right by 15) and a light direction
/// from [`unit_q15`] (`|l_k| <= 32767`). Each product is below `2^31` in
/// magnitude, so a 32-bit multiply does (one cycle on a Cortex-M0+, where
/// an `i64` product is a long call); the sum takes `i64`.
fn dot_q15(n: [i32; 3], l: [i32; 3]) -> i64 {
    (0..3).map(|k| i64::from(n[k].wrapping_mul(l[k]))).sum()
}

impl Shading {
    /// Lambert in warm white, lit from the upper left behind the viewer,
    /// 20 % ambient.
    pub fn lambert() -> Self {
        Shading::Lambert(Lambert::new(
            Rgb888::new(230, 220, 200),
            Vec3::new(-0.4, 0.5, 0.77),
            0.2,
        ))
    }

    /// The colour of one face.
    pub fn color(&self, face: &FaceInfo) -> Rgb888 {
        match *self {
            Shading::Flat(c) => c,
            Shading::Lambert(ref lambert) => lambert.color(face),
            Shading::Depth { near, far } => {
                let t = ((far - face.view_depth()) / (far - near)).clamp(0.0, 1.0);
                scale(Rgb888::WHITE, t)
            }
            Shading::FaceId => face_id_color(face.face),
        }
    }

    /// The colour of one vertex, for Gouraud shading (in 8.8 fixed point):
    /// [`Lambert::vertex_color`]; the flat colour; grey by the vertex's
    /// view distance; or a false colour per vertex id.
    pub fn vertex_color(&self, vertex: &VertexInfo) -> Rgb8p8 {
        match *self {
            Shading::Flat(c) => Rgb8p8::from_rgb888(c),
            Shading::Lambert(ref lambert) => lambert.vertex_color(vertex),
            Shading::Depth { near, far } => {
                let t = ((far - vertex.view_depth()) / (far - near)).clamp(0.0, 1.0);
                // White's channels over 255, each exactly 1.
                scale_8p8([1.0; 3], t)
            }
            Shading::FaceId => Rgb8p8::from_rgb888(face_id_color(vertex.vertex)),
        }
    }
}

/// `unit_base · k` in 8.8 fixed point (`unit_base` a colour's channels
/// over 255, [`unit_channels`]), `k` clamped to `[0, 1]` (NaN as 0).
fn scale_8p8(unit_base: [f32; 3], k: f32) -> Rgb8p8 {
    let k = if k.is_finite() {
        k.clamp(0.0, 1.0)
    } else {
        0.0
    };
    Rgb8p8::from_unit(unit_base.map(|v| v * k))
}

/// Each channel of `c` over 255 (the division made once, not per vertex).
fn unit_channels(c: Rgb888) -> [f32; 3] {
    [c.r(), c.g(), c.b()].map(|v| f32::from(v) / 255.0)
}

fn scale(c: Rgb888, k: f32) -> Rgb888 {
    let k = if k.is_finite() {
        k.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let ch = |v: u8| (f32::from(v) * k + 0.5) as u8;
    Rgb888::new(ch(c.r()), ch(c.g()), ch(c.b()))
}

/// A false colour for a face id: neighbouring ids get unrelated, bright
/// colours (an integer hash of the id).
pub fn face_id_color(id: u32) -> Rgb888 {
    let mut h = id.wrapping_mul(0x9E37_79B9) ^ 0x5bd1_e995;
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    // Keep every channel above 48 so no face looks like a black background.
    let ch = |shift: u32| 48 + ((h >> shift) & 0xFF) as u8 % 208;
    Rgb888::new(ch(0), ch(8), ch(16))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face(normal: Vec3, front: bool, depth: f32) -> FaceInfo<'static> {
        FaceInfo::new(7, front, normal, depth)
    }

    #[test]
    fn lambert_is_two_sided_with_ambient_floor() {
        let s = Shading::Lambert(Lambert::new(
            Rgb888::new(200, 100, 50),
            Vec3::new(0.0, 0.0, 1.0),
            0.25,
        ));
        let facing = face(Vec3::new(0.0, 0.0, 1.0), true, 3.0);
        assert_eq!(s.color(&facing), Rgb888::new(200, 100, 50));
        let flipped = face(Vec3::new(0.0, 0.0, -1.0), false, 3.0);
        assert_eq!(s.color(&flipped), Rgb888::new(200, 100, 50));
        let grazing = face(Vec3::new(1.0, 0.0, 0.0), true, 3.0);
        assert_eq!(s.color(&grazing), Rgb888::new(50, 25, 13));
    }

    /// The light's dot product at the ends of its operands' ranges.
    #[test]
    fn light_dot_products_at_the_extremes() {
        let ns = [-(1 << 16), -(1 << 16) + 1, -1, 0, 1, (1 << 16) - 1];
        let ls = [-32767, -1, 0, 1, 32767];
        for &n0 in &ns {
            for &n1 in &ns {
                for &l0 in &ls {
                    for &l1 in &ls {
                        let (n, l) = ([n0, n1, n0], [l0, l1, l1]);
                        let exact: i64 = (0..3).map(|k| i64::from(n[k]) * i64::from(l[k])).sum();
                        assert_eq!(dot_q15(n, l), exact, "{n:?} {l:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn depth_is_brighter_when_nearer() {
        let s = Shading::Depth {
            near: 2.0,
            far: 4.0,
        };
        let n = Vec3::new(0.0, 0.0, 1.0);
        assert_eq!(s.color(&face(n, true, 2.0)), Rgb888::WHITE);
        assert_eq!(s.color(&face(n, true, 4.0)), Rgb888::BLACK);
        assert!(s.color(&face(n, true, 2.5)).r() > s.color(&face(n, true, 3.5)).r());
    }

    #[test]
    fn face_ids_get_distinct_non_black_colours() {
        let colours: [Rgb888; 64] = core::array::from_fn(|i| face_id_color(i as u32));
        for (i, a) in colours.iter().enumerate() {
            assert!(a.r() >= 48 && a.g() >= 48 && a.b() >= 48);
            for b in &colours[i + 1..] {
                assert_ne!(a, b);
            }
        }
    }
}
