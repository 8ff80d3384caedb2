//! [`Triangles`]: a mesh known, by its type, to be all triangles.

use crate::error::Error;
use crate::front::closed_hull::ClosedHull;
use crate::front::face_plane::FacePlane;
use crate::front::mesh::{Mesh, QuantizedView, SharedPlane};

/// A mesh whose faces are all triangles, checked once when it is made:
/// drawn like the mesh it wraps (the same frames, bit for bit), but
/// [`draw_mesh`](crate::draw_mesh) then leaves out the code for faces of
/// more corners: 6 KB of the RP2040 firmware's flash.
///
/// ```
/// use zline::{Error, StaticMesh, Triangles};
///
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
/// let triangles = StaticMesh::new(&positions, &[0, 1, 2, 2, 1, 3], &[0, 3]).unwrap();
/// assert!(Triangles::new(&triangles).is_ok());
/// let quad = StaticMesh::new(&positions, &[0, 1, 3, 2], &[0]).unwrap();
/// assert_eq!(Triangles::new(&quad).err(), Some(Error::NotATriangle));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Triangles<'a, M: ?Sized> {
    mesh: &'a M,
}

impl<'a, M: Mesh + ?Sized> Triangles<'a, M> {
    /// `mesh`, when every face has three corners;
    /// `Err(`[`Error::NotATriangle`]`)` otherwise.
    pub fn new(mesh: &'a M) -> Result<Self, Error> {
        if (0..mesh.face_count()).all(|face| mesh.face(face).len() == 3) {
            Ok(Self { mesh })
        } else {
            Err(Error::NotATriangle)
        }
    }

    /// The mesh it wraps.
    pub fn mesh(&self) -> &'a M {
        self.mesh
    }
}

impl<M: Mesh + ?Sized> Mesh for Triangles<'_, M> {
    fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }

    fn position(&self, index: usize) -> [f32; 3] {
        self.mesh.position(index)
    }

    fn face_count(&self) -> usize {
        self.mesh.face_count()
    }

    fn face(&self, index: usize) -> &[u16] {
        self.mesh.face(index)
    }

    fn face_is_planar(&self, _index: usize) -> bool {
        true
    }

    fn quantized(&self) -> Option<QuantizedView<'_>> {
        self.mesh.quantized()
    }

    fn shared_planes(&self) -> &[SharedPlane] {
        self.mesh.shared_planes()
    }

    fn face_normal(&self, index: usize) -> Option<[f32; 3]> {
        self.mesh.face_normal(index)
    }

    fn vertex_normal(&self, index: usize) -> Option<[f32; 3]> {
        self.mesh.vertex_normal(index)
    }

    fn vertex_uv(&self, index: usize) -> Option<[f32; 2]> {
        self.mesh.vertex_uv(index)
    }

    fn triangles_only(&self) -> bool {
        true
    }

    fn closed_hull(&self) -> Option<ClosedHull> {
        self.mesh.closed_hull()
    }

    fn hull_caps(&self) -> &[[[f32; 3]; 3]] {
        self.mesh.hull_caps()
    }

    fn face_planes(&self) -> &[FacePlane] {
        self.mesh.face_planes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::mesh::StaticMesh;
    use crate::front::scene::{Camera, Cull, VertexCache, reference_model};
    use crate::{Depth16, FrameBufferSink, Renderer, ScanArrays, TableArrays};

    type Small =
        Renderer<TableArrays<u8, 8, 16, 64>, ScanArrays<u8, Depth16, 48, 16, 32>, VertexCache<6>>;

    /// An octahedron: eight triangles, each coloured by its index.
    const POSITIONS: [[f32; 3]; 6] = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    const CORNERS: [u16; 24] = [
        0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5,
    ];
    const STARTS: [u32; 8] = [0, 3, 6, 9, 12, 15, 18, 21];

    /// The frame of `mesh` at `yaw`, 48x48, and the draw's stats.
    fn frame(mesh: &impl Mesh, yaw: f32, cull: Cull) -> ([u8; 48 * 48], crate::DrawStats) {
        let model = reference_model(mesh, yaw, 20.0).unwrap();
        let camera = Camera::reference(48, 48);
        let mut renderer = Small::new(48, 48, 0).unwrap();
        let stats = renderer
            .draw_mesh(mesh, &model, &camera, cull, |f| 1 + f.face as u8)
            .unwrap();
        let mut pixels = [0u8; 48 * 48];
        renderer
            .render(&mut FrameBufferSink::new(&mut pixels, 48))
            .unwrap();
        (pixels, stats)
    }

    /// A mesh of triangles draws the same frames, pixel for pixel, as
    /// the mesh it wraps, culled or not, at several views.
    #[test]
    fn draws_what_the_mesh_draws() {
        let mesh = StaticMesh::new(&POSITIONS, &CORNERS, &STARTS).unwrap();
        let triangles = Triangles::new(&mesh).unwrap();
        for yaw in [0.0, 30.0, 75.0, 200.0] {
            for cull in [Cull::None, Cull::Back] {
                let (expected, expected_stats) = frame(&mesh, yaw, cull);
                assert!(expected.iter().filter(|&&p| p != 0).count() > 100);
                assert_eq!(frame(&triangles, yaw, cull), (expected, expected_stats));
            }
        }
    }
}
