//! Quantizing a host mesh for the integer front end: positions in its
//! bounding sphere, a unit normal per face, planarity bits; owned in
//! `Vec`s and lent out as a [`QuantizedMesh`].

use crate::error::Error;
use crate::front::backface::exact_normal;
use crate::front::mesh::{Mesh, MeshError, SharedPlane, planar_face_bits};
use crate::front::quantized::{QuantizedMesh, quantize_normal, quantize_position, quantize_unit};
use crate::front::scene::bounding_sphere;
use crate::host::HostMesh;
use crate::limits::UV_SCALE;
use std::vec::Vec;

/// A mesh quantized for the integer front end, in `Vec`s.
#[derive(Debug, Clone, PartialEq)]
pub struct QuantizedHostMesh {
    /// Quantized positions.
    pub positions: Vec<[i16; 3]>,
    /// One quantized unit normal per face.
    pub normals: Vec<[i16; 3]>,
    /// Corners of all faces, face after face.
    pub corners: Vec<u16>,
    /// Where each face starts in `corners`.
    pub face_starts: Vec<u32>,
    /// Planarity bits of the original faces.
    pub planar: Vec<u32>,
    /// Centre of the quantization sphere (the mesh's bounding sphere).
    pub centre: [f32; 3],
    /// Its radius (1 for a mesh of one point).
    pub radius: f32,
    /// The original mesh's shared planes (quantizing keeps the vertices).
    pub shared_planes: Vec<SharedPlane>,
    /// Each face's [`QuantizedMesh::exact_normal`](crate::QuantizedMesh::exact_normal) from the quantized positions (zero for
    /// a face that is not a triangle).
    pub exact_normals: Vec<[i16; 3]>,
    /// One quantized unit normal per vertex (the original mesh's vertex
    /// normals), or empty when it has none.
    pub vertex_normals: Vec<[i16; 3]>,
    /// Each vertex's texture coordinates, `q / UV_SCALE`
    /// ([`UV_SCALE`](crate::limits::UV_SCALE)), or empty when the mesh has
    /// none.
    pub vertex_uvs: Vec<[i16; 2]>,
}

impl QuantizedHostMesh {
    /// Quantizes `mesh` in its [`bounding_sphere`]; each face's normal
    /// comes from its original corners, in `f64`; texture coordinates are
    /// rounded to `1/UV_SCALE`, `Err(`[`Error::TexCoordRange`]`)` when one
    /// is outside `-8..8` (or not finite); `Err(`[`Error::MeshIndexOutOfRange`]`)`
    /// when its faces break [`StaticMesh::new`](crate::StaticMesh::new)'s
    /// rules.
    pub fn new(mesh: &HostMesh) -> Result<Self, Error> {
        if mesh.faces_hold().is_err() {
            return Err(Error::MeshIndexOutOfRange);
        }
        let (centre, radius) = bounding_sphere(mesh)?;
        let radius = if radius > 0.0 { radius } else { 1.0 };
        let c = [
            f64::from(centre.x),
            f64::from(centre.y),
            f64::from(centre.z),
        ];
        let positions: Vec<[i16; 3]> = mesh
            .positions
            .iter()
            .map(|p| quantize_position(p.map(f64::from), c, f64::from(radius)))
            .collect();
        let normals = (0..mesh.face_count())
            .map(|f| {
                let corners = mesh.face(f);
                quantize_normal(
                    corners
                        .iter()
                        .map(|&i| mesh.positions[usize::from(i)].map(f64::from)),
                )
            })
            .collect();
        let exact_normals = exact_normals(mesh, &positions);
        let vertex_normals = mesh
            .vertex_normals
            .iter()
            .map(|n| quantize_unit(n.map(f64::from)))
            .collect();
        let vertex_uvs = mesh
            .uvs
            .iter()
            .map(|uv| {
                let q = uv.map(|c| libm::round(f64::from(c) * f64::from(UV_SCALE)));
                let fits = |c: f64| (f64::from(i16::MIN)..=f64::from(i16::MAX)).contains(&c);
                match fits(q[0]) && fits(q[1]) {
                    true => Ok(q.map(|c| c as i16)),
                    false => Err(Error::TexCoordRange),
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            exact_normals,
            vertex_normals,
            vertex_uvs,
            positions,
            normals,
            corners: mesh.corners.clone(),
            face_starts: mesh.face_starts.clone(),
            planar: planar_face_bits(mesh).collect(),
            centre: [centre.x, centre.y, centre.z],
            radius,
            shared_planes: mesh.shared_planes.clone(),
        })
    }

    /// The mesh, checked, over these arrays.
    pub fn mesh(&self) -> Result<QuantizedMesh<'_>, MeshError> {
        QuantizedMesh::new(
            &self.positions,
            &self.normals,
            &self.corners,
            &self.face_starts,
            &self.planar,
            self.centre,
            self.radius,
        )?
        .with_shared_planes(&self.shared_planes)?
        .with_exact_normals(&self.exact_normals)
        .and_then(|m| match self.vertex_normals.is_empty() {
            true => Ok(m),
            false => m.with_vertex_normals(&self.vertex_normals),
        })
        .and_then(|m| match self.vertex_uvs.is_empty() {
            true => Ok(m),
            false => m.with_vertex_uvs(&self.vertex_uvs),
        })
    }
}

/// Each face's [`exact_normal`] over the quantized `positions` (zero for a
/// face that is not a triangle, or that names a vertex beyond them).
fn exact_normals(mesh: &HostMesh, positions: &[[i16; 3]]) -> Vec<[i16; 3]> {
    (0..mesh.face_count())
        .map(|f| match mesh.face(f) {
            &[a, b, c] => match (
                positions.get(usize::from(a)),
                positions.get(usize::from(b)),
                positions.get(usize::from(c)),
            ) {
                (Some(&a), Some(&b), Some(&c)) => exact_normal(a, b, c),
                _ => [0; 3],
            },
            _ => [0; 3],
        })
        .collect()
}
