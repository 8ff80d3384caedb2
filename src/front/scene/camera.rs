//! Where a mesh is seen from: the [`Camera`] (view and projection), and
//! the reference model matrix that centres and scales a mesh by its
//! bounding sphere.

use crate::error::Error;
use crate::front::geometry::{Mat4, Vec3, radians};
use crate::front::mesh::Mesh;

/// A camera: view and projection matrices and the frame they map to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// World (after the model matrix) to view space.
    pub view: Mat4,
    /// View space to clip space.
    pub projection: Mat4,
    /// Frame width in pixels.
    pub width: u16,
    /// Frame height in pixels.
    pub height: u16,
}

impl Camera {
    /// A perspective camera: vertical field of view in degrees, aspect ratio
    /// from the frame, clip planes at `near` and `far`.
    pub fn perspective(
        view: Mat4,
        fov_y_deg: f32,
        width: u16,
        height: u16,
        near: f32,
        far: f32,
    ) -> Self {
        let aspect = f32::from(width) / f32::from(height);
        Self {
            view,
            projection: Mat4::perspective(radians(fov_y_deg), aspect, near, far),
            width,
            height,
        }
    }

    /// The reference view: eye at (0, 0, 3) looking down -Z with +Y up,
    /// vertical field of view 45 degrees, near 0.1, far 10.
    pub fn reference(width: u16, height: u16) -> Self {
        let view = Mat4::translation(Vec3::new(0.0, 0.0, -3.0));
        Self::perspective(view, 45.0, width, height, 0.1, 10.0)
    }
}

/// The reference model matrix: centre the mesh on its bounding box centre
/// `c` and scale by `1/r`, where `r` is the largest distance from `c` to a
/// vertex. Then apply `Rx(pitch) · Ry(yaw)`, angles in degrees.
/// `Err(`[`Error::MeshExtent`]`)` when `r` cannot be normalised (see
/// [`bounding_sphere`]).
pub fn reference_model<M: Mesh + ?Sized>(
    mesh: &M,
    yaw_deg: f32,
    pitch_deg: f32,
) -> Result<Mat4, Error> {
    let (centre, radius) = bounding_sphere(mesh)?;
    Ok(reference_model_around(centre, radius, yaw_deg, pitch_deg))
}

/// [`reference_model`] for a mesh whose [`bounding_sphere`] is already
/// known: an animation computes the sphere once per mesh, not per frame.
pub fn reference_model_around(centre: Vec3, radius: f32, yaw_deg: f32, pitch_deg: f32) -> Mat4 {
    let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
    let normalise = Mat4::scale(Vec3::new(scale, scale, scale)).mul(&Mat4::translation(-centre));
    Mat4::rotation_x(radians(pitch_deg))
        .mul(&Mat4::rotation_y(radians(yaw_deg)))
        .mul(&normalise)
}

/// Smallest and largest positive radius [`bounding_sphere`] accepts: both
/// `r` and `1/r` are then normal `f32` numbers.
pub const RADIUS_RANGE: (f32, f32) = (f32::MIN_POSITIVE, 1.0 / f32::MIN_POSITIVE);

/// Centre of the axis-aligned bounding box of all vertices, and the largest
/// distance from it to a vertex (0 for an empty or one-point mesh). For a
/// [quantized mesh](crate::QuantizedMesh) it is the sphere it was
/// quantized in: the original mesh's.
///
/// Computed in `f64`, so no finite `f32` coordinates overflow or underflow
/// on the way (`f32` squares of coordinates beyond about `1.8e19`, or
/// below about `1e-19`, would). `Err(`[`Error::MeshExtent`]`)` when the
/// radius is positive but outside [`RADIUS_RANGE`], where the scale `1/r`
/// would lose precision in `f32`, or when a position is not finite.
pub fn bounding_sphere<M: Mesh + ?Sized>(mesh: &M) -> Result<(Vec3, f32), Error> {
    if let Some(q) = mesh.quantized() {
        // The sphere the mesh was quantized in: the original mesh's
        // bounding sphere, known exactly, with no arithmetic (so no
        // floating-point library can round it differently).
        let [x, y, z] = q.centre;
        return Ok((Vec3::new(x, y, z), q.radius));
    }
    let count = mesh.vertex_count();
    if count == 0 {
        return Ok((Vec3::default(), 0.0));
    }
    let position = |i: usize| mesh.position(i).map(f64::from);
    let (mut lo, mut hi) = (position(0), position(0));
    for i in 1..count {
        let p = position(i);
        for axis in 0..3 {
            lo[axis] = lo[axis].min(p[axis]);
            hi[axis] = hi[axis].max(p[axis]);
        }
    }
    if !lo.iter().chain(&hi).all(|c| c.is_finite()) {
        return Err(Error::MeshExtent);
    }
    let centre = [0, 1, 2].map(|axis| (lo[axis] + hi[axis]) * 0.5);
    let radius2 = (0..count)
        .map(|i| {
            let p = position(i);
            (0..3)
                .map(|a| (p[a] - centre[a]) * (p[a] - centre[a]))
                .sum::<f64>()
        })
        .fold(0.0f64, f64::max);
    let radius = libm::sqrt(radius2);
    let centre = Vec3::new(centre[0] as f32, centre[1] as f32, centre[2] as f32);
    if radius == 0.0 {
        return Ok((centre, 0.0));
    }
    let (min, max) = RADIUS_RANGE;
    if !(f64::from(min)..=f64::from(max)).contains(&radius) {
        return Err(Error::MeshExtent);
    }
    Ok((centre, radius as f32))
}
