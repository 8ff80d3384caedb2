//! Face shading, chosen per draw: every face gets one colour from its
//! [`crate::front::scene::FaceInfo`].

use crate::front::geometry::Vec3;
use crate::front::scene::FaceInfo;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// How faces are coloured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shading {
    /// One colour for every face.
    Flat(Rgb888),
    /// Flat Lambert: `base · (ambient + (1 - ambient) · max(0, n · light))`,
    /// two-sided (a face seen from behind is lit as if turned to the
    /// viewer). `light` points towards the light, in view space.
    Lambert {
        /// Surface colour.
        base: Rgb888,
        /// Unit direction towards the light, view space.
        light: Vec3,
        /// Ambient fraction, 0 to 1.
        ambient: f32,
    },
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

impl Shading {
    /// Lambert in warm white, lit from the upper left behind the viewer,
    /// 20 % ambient.
    pub fn lambert() -> Self {
        Shading::Lambert {
            base: Rgb888::new(230, 220, 200),
            light: Vec3::new(-0.4, 0.5, 0.77).normalized(),
            ambient: 0.2,
        }
    }

    /// The colour of one face.
    pub fn color(&self, face: &FaceInfo) -> Rgb888 {
        match *self {
            Shading::Flat(c) => c,
            Shading::Lambert {
                base,
                light,
                ambient,
            } => {
                let n = if face.front {
                    face.normal()
                } else {
                    -face.normal()
                };
                let k = ambient + (1.0 - ambient) * n.dot(light).max(0.0);
                scale(base, k)
            }
            Shading::Depth { near, far } => {
                let t = ((far - face.view_depth()) / (far - near)).clamp(0.0, 1.0);
                scale(Rgb888::WHITE, t)
            }
            Shading::FaceId => face_id_color(face.face),
        }
    }
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
        let s = Shading::Lambert {
            base: Rgb888::new(200, 100, 50),
            light: Vec3::new(0.0, 0.0, 1.0),
            ambient: 0.25,
        };
        let facing = face(Vec3::new(0.0, 0.0, 1.0), true, 3.0);
        assert_eq!(s.color(&facing), Rgb888::new(200, 100, 50));
        let flipped = face(Vec3::new(0.0, 0.0, -1.0), false, 3.0);
        assert_eq!(s.color(&flipped), Rgb888::new(200, 100, 50));
        let grazing = face(Vec3::new(1.0, 0.0, 0.0), true, 3.0);
        assert_eq!(s.color(&grazing), Rgb888::new(50, 25, 13));
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
