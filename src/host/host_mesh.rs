//! A mesh in `std` vectors, for OBJ files of any size on the host.

use std::vec::Vec;

use crate::front::mesh::{Mesh, MeshArrays, SharedPlane, face_normals, planar_face_bits};
use crate::front::obj::{ObjError, ObjReader, Statement};
use crate::limits::MAX_FACE_CORNERS;
use crate::limits::{MAX_POLYGON_CORNERS, MAX_POLYGONS};
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
    /// Which faces are planar ([`is_planar`](crate::front::mesh::is_planar)): bit `f % 32` of word
    /// `f / 32` set when face `f` is, as in
    /// [`StaticMesh::with_planar_faces`](crate::front::mesh::StaticMesh::with_planar_faces).
    /// Faces past its end are tested each frame. [`Self::from_obj`] finds
    /// them.
    pub planar_faces: Vec<u32>,
    /// Each face's unit normal ([`Mesh::face_normal`](crate::Mesh::face_normal):
    /// the direction of Newell's, model space), so that shading reads it
    /// instead of the corners; empty or short, the faces past its end
    /// compute theirs each frame. [`Self::from_obj`] computes them.
    pub face_normals: Vec<[f32; 3]>,
}

impl HostMesh {
    /// Capacities for drawing this mesh whole into frames `width` pixels
    /// wide, from any view, culled or not: every face counted at its
    /// worst, clipped by all six of the front end's planes (what the host
    /// tools and the peers bench use). Per face of `n` corners:
    ///
    /// * a triangle, or a planar face, is one polygon (a planar quad two
    ///   triangles when it needs no clipping), of at most
    ///   `clipped_corners(n)` corners (see below), each of which may be a new
    ///   vertex a cut made; beyond two, its corners may be pooled edges;
    /// * a face that is not planar is its fan of `n - 2` triangles, each
    ///   of at most 9 corners;
    /// * a face with a shared plane adds its plane's three corners to each
    ///   polygon.
    ///
    /// `clipped_corners(n)` is 9 for a triangle (convex: a plane adds at
    /// most one corner); for a larger face, whose corners need not lie
    /// exactly in one plane, Sutherland and Hodgman's worst case: a plane
    /// keeps the corners inside it and adds two for each run of corners
    /// outside it, at most half as many again, six times over, and at most
    /// [`MAX_POLYGON_CORNERS`] (beyond, the front end refuses the face).
    ///
    /// The mesh's positions each enter the vertex table once. Every count
    /// is capped where the core stops: vertex indices are `u16` (a mesh
    /// whose worst case passes 65,536 vertices can still fill the table
    /// when enough faces are clipped at once), at most
    /// [`MAX_POLYGONS`] polygons, and at most 65,536 active polygons (the
    /// active polygon table's slots).
    pub fn capacities(&self, width: u16) -> Capacities {
        let (mut vertices, mut polygons, mut corners, mut pooled) =
            (0usize, 0usize, 0usize, 0usize);
        let mut shared = self
            .shared_planes
            .iter()
            .map(|p| p.face as usize)
            .peekable();
        for face in 0..self.face_count() {
            let n = self.face(face).len();
            let (face_polygons, face_corners, face_pooled) = if n > 3 && !self.face_is_planar(face)
            {
                (n - 2, 9 * (n - 2), 0)
            } else {
                let clipped = clipped_corners(n);
                // A planar quad that needs no clipping is two triangles.
                let polygons = if n == 4 { 2 } else { 1 };
                (
                    polygons,
                    clipped.max(3 * polygons),
                    clipped.saturating_sub(2),
                )
            };
            let shares = shared.next_if(|&f| f <= face).is_some_and(|f| f == face);
            vertices += face_corners;
            polygons += face_polygons;
            corners += face_corners + if shares { 3 * face_polygons } else { 0 };
            pooled += if n > 3 { face_pooled } else { 0 };
        }
        let polygons = polygons.min(MAX_POLYGONS);
        Capacities {
            width: usize::from(width),
            vertices: (self.positions.len() + vertices).min(1 << 16),
            polygons,
            corners,
            active_polygons: polygons.min(1 << 16),
            pooled_edges: pooled,
            mesh_vertices: self.positions.len(),
        }
    }

    /// Reads an OBJ file with the no_std reader (faces of up to
    /// [`MAX_FACE_CORNERS`] corners, all the pipeline draws), and finds
    /// its planar faces and its overlapping coplanar faces
    /// ([`Self::with_face_analysis`]).
    pub fn from_obj(bytes: &[u8]) -> Result<Self, ObjError> {
        let mut mesh = Self::default();
        for statement in ObjReader::<MAX_FACE_CORNERS>::new(bytes) {
            match statement? {
                Statement::Vertex(p) => mesh.positions.push(p),
                Statement::Face(corners) => {
                    mesh.face_starts.push(mesh.corners.len() as u32);
                    mesh.corners.extend(corners.iter().map(|c| c.vertex));
                }
                Statement::TexCoord(_) | Statement::Normal(_) | Statement::Other(_) => {}
            }
        }
        Ok(mesh.with_face_analysis())
    }

    /// The mesh with what its faces' geometry tells the pipeline found
    /// again: which faces are planar ([`Self::planar_faces`], so that no
    /// frame tests them), their normals ([`Self::face_normals`]) and which
    /// share a plane with overlapping coplanar faces
    /// ([`crate::host::coplanar::shared_planes`]). Call it after changing
    /// positions or faces: stale planarity bits would draw a face that is
    /// no longer planar as one polygon, stale normals would shade it wrong.
    pub fn with_face_analysis(mut self) -> Self {
        self.planar_faces = planar_face_bits(&self).collect();
        self.face_normals = face_normals(&self).collect();
        self.shared_planes = crate::host::coplanar::shared_planes(&self);
        self
    }
}

/// `clipped_corners(n)` of [`HostMesh::capacities`].
fn clipped_corners(n: usize) -> usize {
    if n <= 3 {
        return n + 6;
    }
    let mut c = n;
    for _ in 0..6 {
        c += c / 2;
    }
    c.min(MAX_POLYGON_CORNERS)
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

    fn planar_bits(&self) -> &[u32] {
        &self.planar_faces
    }

    fn shared_planes(&self) -> &[SharedPlane] {
        &self.shared_planes
    }

    fn face_normals(&self) -> &[[f32; 3]] {
        &self.face_normals
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::mesh::is_planar;
    use std::fmt::Write;
    use std::string::String;

    /// 40 quads in a row, every third one bent out of its plane (its
    /// fourth corner lifted), so the bits fill more than one word.
    fn quads() -> Vec<u8> {
        let mut obj = String::new();
        for k in 0..40 {
            let (x, lift) = (k as f32 * 2.0, if k % 3 == 0 { 0.5 } else { 0.0 });
            for (dx, dy, z) in [
                (0.0, 0.0, 0.0),
                (1.0, 0.0, 0.0),
                (1.0, 1.0, lift),
                (0.0, 1.0, 0.0),
            ] {
                let _ = writeln!(obj, "v {} {dy} {z}", x + dx);
            }
            let v = 4 * k + 1;
            let _ = writeln!(obj, "f {} {} {} {}", v, v + 1, v + 2, v + 3);
        }
        obj.into_bytes()
    }

    #[test]
    fn from_obj_records_each_faces_planarity() {
        let mesh = HostMesh::from_obj(&quads()).unwrap();
        assert_eq!(mesh.planar_faces.len(), 2);
        for f in 0..40 {
            assert_eq!(is_planar(&mesh, f), f % 3 != 0, "face {f}");
            assert_eq!(mesh.face_is_planar(f), f % 3 != 0, "face {f}");
        }
    }

    #[test]
    fn face_is_planar_reads_the_bits_and_tests_faces_past_them() {
        let mut mesh = HostMesh::from_obj(&quads()).unwrap();
        // The bits are what is answered: flipped, the answers flip.
        mesh.planar_faces[0] ^= 0b11;
        assert!(mesh.face_is_planar(0));
        assert!(!mesh.face_is_planar(1));
        // Faces 32..40 past a one-word list are tested.
        mesh.planar_faces.truncate(1);
        for f in 32..40 {
            assert_eq!(mesh.face_is_planar(f), f % 3 != 0, "face {f}");
        }
    }
}
