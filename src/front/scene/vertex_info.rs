//! What a vertex shading closure knows about a vertex ([`VertexInfo`]):
//! its index at once, its normal and texture coordinates when asked for.

use crate::front::clip_w::ClipW;
use crate::front::geometry::Vec3;
use crate::front::mesh::Mesh;
use crate::front::scene::face_info::normal_vector_i32;
use crate::front::scene::transform::Frame;
use crate::front::tex_coord::TexCoord;

/// What a vertex shading closure knows about a mesh vertex, for smooth
/// shading ([`PaintedRenderer::draw_mesh`](crate::paint::PaintedRenderer::draw_mesh)):
/// its index at hand, its view-space normal and its texture coordinates
/// computed only when asked for.
#[derive(Clone, Copy)]
pub struct VertexInfo<'a> {
    /// Index of the vertex in the mesh.
    pub vertex: u32,
    geometry: VertexGeometry<'a>,
}

/// Where a [`VertexInfo`]'s normal and texture coordinates come from.
#[derive(Clone, Copy)]
enum VertexGeometry<'a> {
    /// From the mesh, on demand.
    Mesh {
        mesh: &'a dyn Mesh,
        frame: &'a Frame,
    },
    /// Given.
    Known {
        normal: Option<Vec3>,
        uv: Option<[f32; 2]>,
    },
}

impl core::fmt::Debug for VertexInfo<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("VertexInfo")
            .field("vertex", &self.vertex)
            .field("normal", &self.normal())
            .field("uv", &self.uv())
            .finish()
    }
}

impl VertexInfo<'static> {
    /// A vertex whose normal (unit, view space) and texture coordinates
    /// are known.
    pub const fn new(vertex: u32, normal: Option<Vec3>, uv: Option<[f32; 2]>) -> Self {
        Self {
            vertex,
            geometry: VertexGeometry::Known { normal, uv },
        }
    }
}

impl<'a> VertexInfo<'a> {
    /// Vertex `index` of `mesh` in `frame`.
    pub(super) fn of_mesh(mesh: &'a dyn Mesh, frame: &'a Frame, index: usize) -> Self {
        Self {
            vertex: index as u32,
            geometry: VertexGeometry::Mesh { mesh, frame },
        }
    }

    /// The vertex's unit normal in view space, from the mesh's
    /// ([`Mesh::vertex_normal`]); `None` when the mesh has none. For a
    /// quantized mesh's stored normals, [`Self::normal_q15`] as a `f32`
    /// vector.
    pub fn normal(&self) -> Option<Vec3> {
        if let Some(n) = self.normal_q15() {
            return Some(normal_vector_i32(n));
        }
        match self.geometry {
            VertexGeometry::Mesh { mesh, frame } => mesh
                .vertex_normal(self.vertex as usize)
                .map(|n| frame.view_normal(Vec3::from_array(n))),
            VertexGeometry::Known { normal, .. } => normal,
        }
    }

    /// [`Self::normal`]`.map(|n| n.dot(v))`, the same value. The product
    /// is taken where the normal is turned, so no vector passes through
    /// memory between the two (Lambert's colour of each vertex takes it,
    /// as [`FaceInfo::normal_dot`](crate::FaceInfo::normal_dot) for faces).
    #[inline(always)]
    pub fn normal_dot(&self, v: Vec3) -> Option<f32> {
        if let Some(n) = self.normal_q15() {
            return Some(normal_vector_i32(n).dot(v));
        }
        match self.geometry {
            VertexGeometry::Mesh { mesh, frame } => mesh
                .vertex_normal(self.vertex as usize)
                .map(|n| frame.view_normal_dot(Vec3::from_array(n), v)),
            VertexGeometry::Known { normal, .. } => normal.map(|n| n.dot(v)),
        }
    }

    /// The unit normal in view space in integers, units of `1/32767`, when
    /// the vertex is a [quantized mesh](crate::QuantizedMesh)'s with a
    /// stored normal
    /// ([`QuantizedMesh::with_vertex_normals`](crate::QuantizedMesh::with_vertex_normals))
    /// drawn by the integer front end: rotated with no floating point, the
    /// same on every target. `None` otherwise.
    #[inline]
    pub fn normal_q15(&self) -> Option<[i32; 3]> {
        match self.geometry {
            VertexGeometry::Mesh { mesh, frame } => {
                let fixed = frame.fixed.as_ref()?;
                let n = *mesh.quantized()?.vertex_normals.get(self.vertex as usize)?;
                fixed.view_normal(n)
            }
            VertexGeometry::Known { .. } => None,
        }
    }

    /// View-space distance of the vertex along the view axis (0 for a
    /// vertex made with [`Self::new`]).
    pub fn view_depth(&self) -> f32 {
        match self.geometry {
            VertexGeometry::Mesh { mesh, frame } => {
                let p = mesh.position(self.vertex as usize);
                let row = frame.model_view.m[2];
                -(row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3])
            }
            VertexGeometry::Known { .. } => 0.0,
        }
    }

    /// The vertex's clip-space `w` (for a perspective camera, its distance
    /// along the view axis), which perspective-correct texture mapping
    /// divides by: from the integer front end's clip coordinates for a
    /// quantized mesh it draws, else from the `f32` transform.
    /// [`ClipW::ONE`] for a vertex made with [`Self::new`].
    pub fn clip_w(&self) -> ClipW {
        match self.geometry {
            VertexGeometry::Mesh { mesh, frame } => frame.clip_w(mesh, self.vertex as usize),
            VertexGeometry::Known { .. } => ClipW::ONE,
        }
    }

    /// Texture coordinates and `w` for [`Textured`](crate::paint::Textured)
    /// painting: [`Self::uv`] (as OBJ gives it, `v` up) and
    /// [`Self::clip_w`]; `(0, 0)` when the mesh has no coordinates. A
    /// quantized mesh's stored coordinates drawn by the integer front end
    /// take no floating point.
    pub fn tex_coord(&self) -> TexCoord {
        if let VertexGeometry::Mesh { mesh, frame } = self.geometry
            && frame.fixed.is_some()
            && let Some(&q) = mesh
                .quantized()
                .and_then(|q| q.vertex_uvs.get(self.vertex as usize))
        {
            return TexCoord::from_quantized(q, self.clip_w());
        }
        TexCoord::from_obj(self.uv().unwrap_or([0.0; 2]), self.clip_w())
    }

    /// The vertex's texture coordinates ([`Mesh::vertex_uv`]); `None` when
    /// the mesh has none.
    pub fn uv(&self) -> Option<[f32; 2]> {
        match self.geometry {
            VertexGeometry::Mesh { mesh, .. } => mesh.vertex_uv(self.vertex as usize),
            VertexGeometry::Known { uv, .. } => uv,
        }
    }
}
