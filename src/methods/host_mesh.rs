//! A mesh in `std` vectors, for OBJ files of any size on the host.

use std::vec::Vec;

use crate::mesh::{Mesh, face_of};
use crate::obj::{ObjError, ObjReader, Statement};
use crate::scene::MAX_FACE_CORNERS;

/// Positions and faces in growable storage, in the layout of
/// [`StaticMesh`](crate::mesh::StaticMesh).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HostMesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Corners of all faces, face after face.
    pub corners: Vec<u16>,
    /// Where each face starts in `corners`.
    pub face_starts: Vec<u32>,
}

impl HostMesh {
    /// Reads an OBJ file with the no_std reader (faces of up to
    /// [`MAX_FACE_CORNERS`] corners, all the pipeline draws).
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
        Ok(mesh)
    }
}

impl Mesh for HostMesh {
    fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    fn position(&self, index: usize) -> [f32; 3] {
        self.positions[index]
    }

    fn face_count(&self) -> usize {
        self.face_starts.len()
    }

    fn face(&self, index: usize) -> &[u16] {
        face_of(&self.corners, &self.face_starts, index)
    }
}
