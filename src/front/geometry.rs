//! Vectors, 4x4 matrices and the camera transforms, in `f32` with `libm`
//! for the trigonometry (no FPU or `std` needed).
//!
//! Conventions: right-handed world, column vectors (`p' = M · p`), the
//! camera looks down -Z with +Y up, and [`Mat4::perspective`] maps view
//! space to OpenGL-style clip space (`-w <= x, y, z <= w` inside; `z = -w`
//! on the near plane, `z = w` on the far plane).

use core::ops::{Add, Mul, Neg, Sub};

use crate::front::trig::sin_cos;

/// A 3-vector.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec3 {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component.
    pub z: f32,
}

/// A homogeneous 4-vector (clip-space position).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec4 {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component.
    pub z: f32,
    /// w component.
    pub w: f32,
}

/// A 4x4 matrix, row-major: `m[row][column]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mat4 {
    /// Rows of the matrix.
    pub m: [[f32; 4]; 4],
}

impl Vec3 {
    /// `(x, y, z)`.
    pub const fn new(x: f32, y: f32, z: f32) -> Self {
        Self { x, y, z }
    }

    /// From an array.
    pub const fn from_array(a: [f32; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// Dot product.
    pub fn dot(self, o: Self) -> f32 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product.
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Euclidean length.
    pub fn length(self) -> f32 {
        libm::sqrtf(self.dot(self))
    }

    /// Unit vector in the same direction; the zero vector stays zero.
    pub fn normalized(self) -> Self {
        let len = self.length();
        if len > 0.0 { self * (1.0 / len) } else { self }
    }

    /// Whether every component is finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
}

impl Add for Vec3 {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for Vec3 {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Mul<f32> for Vec3 {
    type Output = Self;
    fn mul(self, s: f32) -> Self {
        Self::new(self.x * s, self.y * s, self.z * s)
    }
}

impl Neg for Vec3 {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl Vec4 {
    /// `(x, y, z, w)`.
    pub const fn new(x: f32, y: f32, z: f32, w: f32) -> Self {
        Self { x, y, z, w }
    }

    /// Dot product.
    pub fn dot(self, o: Self) -> f32 {
        self.x * o.x + self.y * o.y + self.z * o.z + self.w * o.w
    }

    /// `self + (o - self) · t`.
    pub fn lerp(self, o: Self, t: f32) -> Self {
        Self::new(
            self.x + (o.x - self.x) * t,
            self.y + (o.y - self.y) * t,
            self.z + (o.z - self.z) * t,
            self.w + (o.w - self.w) * t,
        )
    }

    /// Whether every component is finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite() && self.w.is_finite()
    }
}

impl Mat4 {
    /// The identity.
    pub const IDENTITY: Self = Self {
        m: [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ],
    };

    /// Translation by `t`.
    pub fn translation(t: Vec3) -> Self {
        let mut r = Self::IDENTITY;
        r.m[0][3] = t.x;
        r.m[1][3] = t.y;
        r.m[2][3] = t.z;
        r
    }

    /// Scale by `s` along each axis.
    pub fn scale(s: Vec3) -> Self {
        let mut r = Self::IDENTITY;
        r.m[0][0] = s.x;
        r.m[1][1] = s.y;
        r.m[2][2] = s.z;
        r
    }

    /// Rotation about +X by `radians` (y towards z).
    ///
    /// The rotations take sine and cosine from one reduction in `f32`
    /// arithmetic alone (`front::trig`: within `2^-23` of the exact values
    /// for angles up to 8192 radians, the same bits on every target).
    pub fn rotation_x(radians: f32) -> Self {
        let (s, c) = sin_cos(radians);
        let mut r = Self::IDENTITY;
        r.m[1][1] = c;
        r.m[1][2] = -s;
        r.m[2][1] = s;
        r.m[2][2] = c;
        r
    }

    /// Rotation about +Y by `radians` (z towards x).
    pub fn rotation_y(radians: f32) -> Self {
        let (s, c) = sin_cos(radians);
        let mut r = Self::IDENTITY;
        r.m[0][0] = c;
        r.m[0][2] = s;
        r.m[2][0] = -s;
        r.m[2][2] = c;
        r
    }

    /// Rotation about +Z by `radians` (x towards y).
    pub fn rotation_z(radians: f32) -> Self {
        let (s, c) = sin_cos(radians);
        let mut r = Self::IDENTITY;
        r.m[0][0] = c;
        r.m[0][1] = -s;
        r.m[1][0] = s;
        r.m[1][1] = c;
        r
    }

    /// View matrix of a camera at `eye` looking at `target` with `up`
    /// roughly up: maps the eye to the origin looking down -Z. When `up`
    /// is parallel to the view direction (a camera looking straight down
    /// with `up` +Y) or zero, the world axis least aligned with the view
    /// direction stands in for it. The view direction is normalised
    /// without overflow or underflow for any finite `eye` and `target`;
    /// only `eye == target` (no direction) gives no view.
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3) -> Self {
        let f = unit(target - eye);
        let mut s = f.cross(up).normalized();
        if s.length() < 0.5 {
            let axis = if f.x.abs() <= f.y.abs() && f.x.abs() <= f.z.abs() {
                Vec3::new(1.0, 0.0, 0.0)
            } else if f.y.abs() <= f.z.abs() {
                Vec3::new(0.0, 1.0, 0.0)
            } else {
                Vec3::new(0.0, 0.0, 1.0)
            };
            s = f.cross(axis).normalized();
        }
        let u = s.cross(f);
        Self {
            m: [
                [s.x, s.y, s.z, -s.dot(eye)],
                [u.x, u.y, u.z, -u.dot(eye)],
                [-f.x, -f.y, -f.z, f.dot(eye)],
                [0.0, 0.0, 0.0, 1.0],
            ],
        }
    }

    /// Perspective projection: vertical field of view `fov_y` in radians,
    /// `aspect` = width / height, clip planes at distances `near` and `far`.
    /// After the divide by `w`, `z_ndc` runs from -1 (near) to 1 (far) and is
    /// affine in screen space.
    pub fn perspective(fov_y: f32, aspect: f32, near: f32, far: f32) -> Self {
        let f = 1.0 / libm::tanf(fov_y / 2.0);
        Self {
            m: [
                [f / aspect, 0.0, 0.0, 0.0],
                [0.0, f, 0.0, 0.0],
                [
                    0.0,
                    0.0,
                    (far + near) / (near - far),
                    2.0 * far * near / (near - far),
                ],
                [0.0, 0.0, -1.0, 0.0],
            ],
        }
    }

    /// The product `self · o`.
    pub fn mul(&self, o: &Self) -> Self {
        let mut r = [[0.0f32; 4]; 4];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                *cell = (0..4).map(|k| self.m[i][k] * o.m[k][j]).sum();
            }
        }
        Self { m: r }
    }

    /// `self · (p, 1)`.
    pub fn transform_point(&self, p: Vec3) -> Vec4 {
        let row = |r: [f32; 4]| r[0] * p.x + r[1] * p.y + r[2] * p.z + r[3];
        Vec4::new(
            row(self.m[0]),
            row(self.m[1]),
            row(self.m[2]),
            row(self.m[3]),
        )
    }

    /// `self · (v, 0)`: a direction, ignoring translation.
    pub fn transform_vector(&self, v: Vec3) -> Vec3 {
        let row = |r: [f32; 4]| r[0] * v.x + r[1] * v.y + r[2] * v.z;
        Vec3::new(row(self.m[0]), row(self.m[1]), row(self.m[2]))
    }
}

/// `v` as a unit vector: normalised in `f32` as [`Vec3::normalized`] does
/// when its squared length is a normal `f32` (components between about
/// 10^-18 and 10^18), and in `f64` otherwise, where the square of any
/// finite `f32` is representable (a direction between points 10^20
/// apart, or 10^-20); zero stays zero.
pub(crate) fn unit(v: Vec3) -> Vec3 {
    let squared = v.dot(v);
    if squared.is_normal() {
        return v.normalized();
    }
    let [x, y, z] = [v.x, v.y, v.z].map(f64::from);
    let length = libm::sqrt(x * x + y * y + z * z);
    if length > 0.0 && length.is_finite() {
        Vec3::new(
            (x / length) as f32,
            (y / length) as f32,
            (z / length) as f32,
        )
    } else {
        v
    }
}

/// Newell's normal of a polygon (not normalised): the sum of the cross
/// products of the fan from its first corner, relative to that corner so
/// no large coordinates multiply. Its length is twice the polygon's area;
/// for a triangle it is the cross product of two edges. The one place the
/// front end computes a face normal (planarity, shading).
pub fn newell_normal(corners: impl IntoIterator<Item = [f32; 3]>) -> Vec3 {
    let mut corners = corners.into_iter();
    let Some(origin) = corners.next().map(Vec3::from_array) else {
        return Vec3::default();
    };
    let Some(mut p) = corners.next().map(|q| Vec3::from_array(q) - origin) else {
        return Vec3::default();
    };
    let mut n = Vec3::default();
    for q in corners {
        let q = Vec3::from_array(q) - origin;
        n = n + p.cross(q);
        p = q;
    }
    n
}

/// Degrees to radians.
pub fn radians(degrees: f32) -> f32 {
    degrees * (core::f32::consts::PI / 180.0)
}

#[cfg(test)]
mod tests {
    #[test]
    fn look_at_gives_a_view_for_any_eye_but_the_target() {
        let orthonormal = |m: &Mat4| {
            let row = |r: usize| Vec3::new(m.m[r][0], m.m[r][1], m.m[r][2]);
            let (a, b, c) = (row(0), row(1), row(2));
            let unit = |v: Vec3| (v.length() - 1.0).abs() < 1e-5;
            unit(a) && unit(b) && unit(c) && a.dot(b).abs() < 1e-5 && b.dot(c).abs() < 1e-5
        };
        let up = Vec3::new(0.0, 1.0, 0.0);
        for eye in [
            Vec3::new(0.0, 5.0, 0.0),         // straight above, up parallel
            Vec3::new(0.0, -5.0, 0.0),        // straight below
            Vec3::new(1e-11, -3.6e34, 3e-30), // squared length overflows
            Vec3::new(3e-30, 2e-30, 1e-30),   // squared length underflows
            Vec3::new(2.0, 1.0, 3.0),
        ] {
            let view = Mat4::look_at(eye, Vec3::default(), up);
            assert!(orthonormal(&view), "{eye:?}: {view:?}");
            // The target lies straight ahead.
            let t = view.transform_point(Vec3::default());
            assert!(
                t.x.abs() <= 1e-5 * t.z.abs() && t.y.abs() <= 1e-5 * t.z.abs() && t.z < 0.0,
                "{t:?}"
            );
        }
        // An ordinary view is what it always was.
        let (eye, target) = (Vec3::new(2.0, 1.0, 3.0), Vec3::new(0.5, 0.0, 0.0));
        let f = (target - eye).normalized();
        assert_eq!(Mat4::look_at(eye, target, up).m[2][..3], [-f.x, -f.y, -f.z]);
    }

    use super::*;

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() < 1e-5
    }

    #[test]
    fn rotations_follow_the_right_hand_rule() {
        let q = core::f32::consts::FRAC_PI_2;
        let y = Mat4::rotation_x(q).transform_point(Vec3::new(0.0, 1.0, 0.0));
        assert!(close(y.z, 1.0) && close(y.y, 0.0));
        let z = Mat4::rotation_y(q).transform_point(Vec3::new(0.0, 0.0, 1.0));
        assert!(close(z.x, 1.0) && close(z.z, 0.0));
        let x = Mat4::rotation_z(q).transform_point(Vec3::new(1.0, 0.0, 0.0));
        assert!(close(x.y, 1.0) && close(x.x, 0.0));
    }

    #[test]
    fn perspective_maps_near_and_far_to_minus_one_and_one() {
        let p = Mat4::perspective(radians(45.0), 1.5, 0.1, 10.0);
        let near = p.transform_point(Vec3::new(0.0, 0.0, -0.1));
        let far = p.transform_point(Vec3::new(0.0, 0.0, -10.0));
        assert!(close(near.z / near.w, -1.0) && close(near.w, 0.1));
        assert!(close(far.z / far.w, 1.0) && close(far.w, 10.0));
        // The top edge of the view at distance d is at y = d·tan(22.5°).
        let d = 3.0;
        let top = p.transform_point(Vec3::new(0.0, d * libm::tanf(radians(22.5)), -d));
        assert!(close(top.y / top.w, 1.0));
    }

    #[test]
    fn look_at_puts_the_target_on_the_minus_z_axis() {
        let v = Mat4::look_at(
            Vec3::new(0.0, 0.0, 3.0),
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        );
        assert_eq!(v, Mat4::translation(Vec3::new(0.0, 0.0, -3.0)));
        let v = Mat4::look_at(
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(2.0, 1.0, -5.0),
            Vec3::new(0.0, 1.0, 0.0),
        );
        let t = v.transform_point(Vec3::new(2.0, 1.0, -5.0));
        assert!(close(t.x, 0.0) && close(t.y, 0.0) && close(t.z, -5.0));
    }

    #[test]
    fn products_compose_right_to_left() {
        let t = Mat4::translation(Vec3::new(1.0, 2.0, 3.0));
        let s = Mat4::scale(Vec3::new(2.0, 2.0, 2.0));
        let p = t.mul(&s).transform_point(Vec3::new(1.0, 1.0, 1.0));
        assert_eq!((p.x, p.y, p.z, p.w), (3.0, 4.0, 5.0, 1.0));
    }
}
