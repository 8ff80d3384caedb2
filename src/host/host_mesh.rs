//! A mesh in `std` vectors, for OBJ files of any size on the host.

use std::vec::Vec;

use crate::front::mesh::{MeshArrays, SharedPlane};
use crate::front::obj::{ObjError, ObjReader, Statement};
use crate::front::scene::MAX_FACE_CORNERS;
use crate::raster::Capacities;

/// Positions and faces in growable storage, in the layout of
/// [`StaticMesh`](crate::front::mesh::StaticMesh).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HostMesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Corners of all faces, face after face.
    pub corners: Vec<u16>,
    /// Where each face starts in `corners`.
    pub face_starts: Vec<u32>,
    /// Faces that share a plane with overlapping coplanar faces, sorted by
    /// face ([`crate::host::coplanar`]); [`Self::from_obj`] finds them.
    pub shared_planes: Vec<SharedPlane>,
}

impl HostMesh {
    /// Capacities for drawing this mesh whole into frames `width` pixels
    /// wide: room for every face's fan and for the corners clipping adds
    /// (what the host tools and the peers bench use).
    pub fn capacities(&self, width: u16) -> Capacities {
        let corners = self.corners.len();
        Capacities {
            width: usize::from(width),
            vertices: (self.positions.len() * 2 + 1024).min(1 << 16),
            polygons: corners + 64,
            corners: 3 * corners + 256,
            active_polygons: corners + 64,
            pooled_edges: 4096,
        }
    }

    /// Reads an OBJ file with the no_std reader (faces of up to
    /// [`MAX_FACE_CORNERS`] corners, all the pipeline draws), and finds
    /// its overlapping coplanar faces ([`Self::with_shared_planes`]).
    pub fn from_obj(bytes: &[u8]) -> Result<Self, ObjError> {
        let mut mesh = Self::default();
        for statement in ObjReader::<MAX_FACE_CORNERS>::new(bytes) {
            match statement? {
                Statement::Vertex(p) => mesh.positions.push(p),
                Statement::Face(corners) => {
                    mesh.face_starts.push(mesh.corners.len() as u32);
                    mesh.corners.extend_from_slice(&corners);
                }
                Statement::Other(_) => {}
            }
        }
        Ok(mesh.with_shared_planes())
    }

    /// The mesh with its overlapping coplanar faces found again
    /// ([`crate::host::coplanar::shared_planes`]): call it after changing
    /// positions or faces.
    pub fn with_shared_planes(mut self) -> Self {
        self.shared_planes = crate::host::coplanar::shared_planes(&self);
        self
    }
}

impl MeshArrays for HostMesh {
    fn positions(&self) -> &[[f32; 3]] {
        &self.positions
    }

    fn corners(&self) -> &[u16] {
        &self.corners
    }

    fn face_starts(&self) -> &[u32] {
        &self.face_starts
    }

    fn shared_planes(&self) -> &[SharedPlane] {
        &self.shared_planes
    }
}
