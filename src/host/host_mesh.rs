//! A mesh in `std` vectors, for OBJ files of any size on the host.

use std::collections::HashMap;
use std::vec::Vec;

use crate::front::closed_hull::ClosedHull;
use crate::front::face_plane::FacePlane;
use crate::front::geometry::{Vec3, newell_normal, unit};
use crate::front::mesh::{
    Mesh, MeshArrays, MeshError, SharedPlane, StaticMesh, check_shared_planes, face_normals,
    face_planes, fan_normals, planar_face_bits,
};
use crate::front::obj::{Element, ObjCorner, ObjError, ObjErrorKind, ObjReader, Statement};
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
    /// The normals of the fans of faces that are not planar
    /// ([`Mesh::fan_normal`](crate::Mesh::fan_normal)), one slot per
    /// corner ([`fan_normals`](crate::fan_normals)); empty, each frame
    /// computes them. [`Self::from_obj`] computes them when the mesh has
    /// such a face.
    pub fan_normals: Vec<[f32; 3]>,
    /// Each vertex's unit normal, for smooth shading
    /// ([`Mesh::vertex_normal`](crate::Mesh::vertex_normal)); empty when
    /// the mesh has none ([`Self::from_obj_smooth`] and
    /// [`Self::with_vertex_normals`] give every vertex one).
    pub vertex_normals: Vec<[f32; 3]>,
    /// Each vertex's texture coordinates
    /// ([`Mesh::vertex_uv`](crate::Mesh::vertex_uv)); empty when the mesh
    /// has none.
    pub uvs: Vec<[f32; 2]>,
    /// The mesh's [`ClosedHull`] when it is a closed surface wound
    /// counter-clockwise seen from outside, once its holes are capped by
    /// [`Self::hull_caps`] ([`crate::host::capped_hull`]), so that a draw
    /// with [`Cull::None`](crate::Cull::None) leaves out the back faces
    /// where none can show; [`Self::from_obj`] and
    /// [`Self::with_face_analysis`] find it. Clear it to have every face
    /// drawn, or for a mesh that passes through itself inside out.
    pub closed_hull: Option<ClosedHull>,
    /// The caps over the mesh's holes that [`Self::closed_hull`] holds
    /// with ([`Mesh::hull_caps`](crate::Mesh::hull_caps)); empty for a
    /// closed mesh.
    pub hull_caps: Vec<[[f32; 3]; 3]>,
    /// Each face's plane ([`Mesh::face_planes`](crate::Mesh::face_planes)),
    /// so that a draw with back faces culled leaves out those turned away
    /// before transforming their corners; empty or short, the faces past
    /// its end are tested on their projected corners. [`Self::from_obj`]
    /// and [`Self::with_face_analysis`] compute them: stale planes would
    /// cull faces by their old positions.
    pub face_planes: Vec<FacePlane>,
}

/// The crease angle the tools give [`HostMesh::from_obj_smooth`] unless
/// told otherwise: faces meeting at a sharper angle keep a hard edge.
pub const DEFAULT_CREASE_DEGREES: f32 = 60.0;

impl HostMesh {
    /// Whether the mesh's arrays hold together, as a mesh built field by
    /// field may not: the rules of [`StaticMesh::new`] (every corner names
    /// one of the positions, face starts rise through the corners with at
    /// least three corners a face and at most
    /// [`MAX_FACE_CORNERS`]), vertex normals and texture coordinates each
    /// empty or one per position
    /// ([`MeshError::BadVertexAttributes`]), and the shared planes as
    /// [`StaticMesh::with_shared_planes`] checks them. The analyses return
    /// a mesh that fails it as it is, and a draw of it is
    /// [`Error::MeshIndexOutOfRange`](crate::Error::MeshIndexOutOfRange).
    pub fn check(&self) -> Result<(), MeshError> {
        self.faces_hold()?;
        let count = self.positions.len();
        if ![self.vertex_normals.len(), self.uvs.len()]
            .iter()
            .all(|&len| len == 0 || len == count)
        {
            return Err(MeshError::BadVertexAttributes);
        }
        check_shared_planes(&self.shared_planes, self.face_starts.len(), count)
    }

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
    /// [`MAX_FACE_CORNERS`] corners, all the pipeline draws), numbers its
    /// vertices in the order its faces first use them
    /// ([`Self::with_vertices_in_first_use_order`]: the file's numbering
    /// is not kept), and finds its planar faces and its overlapping
    /// coplanar faces ([`Self::with_face_analysis`]).
    pub fn from_obj(bytes: &[u8]) -> Result<Self, ObjError> {
        let mut mesh = Self::default();
        let mut reader = ObjReader::<MAX_FACE_CORNERS>::new(bytes);
        loop {
            // A face's corners go straight into the mesh (an error drops
            // the mesh, so a face cut short by one is never kept).
            let start = mesh.corners.len() as u32;
            let corners = &mut mesh.corners;
            let Some(statement) = reader.next_streamed(&mut |c| corners.push(c.vertex)) else {
                break;
            };
            match statement? {
                Statement::Vertex(p) => mesh.positions.push(p),
                Statement::Face(_) => mesh.face_starts.push(start),
                Statement::TexCoord(_) | Statement::Normal(_) | Statement::Other(_) => {}
            }
        }
        Ok(mesh.with_vertices_in_first_use_order().with_face_analysis())
    }

    /// Reads an OBJ file for smooth shading and textures: a vertex for each
    /// different position, texture coordinate and normal its faces' corners
    /// name together (as a GPU's vertex buffer has them), with the file's
    /// normals (normalised) and texture coordinates. A corner with no
    /// normal in the file gets its position's normal from the faces
    /// around it ([`Self::with_vertex_normals`]); a corner with no
    /// texture coordinate, `(0, 0)` when others have one. More than 65,536
    /// such vertices is [`ObjErrorKind::TooManyVertices`] at the face that
    /// passes the limit.
    pub fn from_obj_smooth(bytes: &[u8], crease_degrees: f32) -> Result<Self, ObjError> {
        let mut file = AttributedFaces::default();
        let mut reader = ObjReader::<MAX_FACE_CORNERS>::new(bytes);
        loop {
            let start = file.corners.len() as u32;
            let corners = &mut file.corners;
            let Some(statement) = reader.next_streamed(&mut |c| corners.push(c)) else {
                break;
            };
            match statement? {
                Statement::Vertex(p) => file.positions.push(p),
                Statement::TexCoord(uv) => file.texcoords.push(uv),
                Statement::Normal(n) => file.normals.push(n),
                Statement::Face(_) => {
                    file.face_starts.push(start);
                    file.face_lines.push(reader.line());
                }
                Statement::Other(_) => {}
            }
        }
        file.build(crease_degrees)
    }

    /// The same mesh with a normal for every vertex, for smooth shading:
    /// at each corner, the sum of the normals of the faces around its
    /// position (every position with the same coordinates), each weighted by its area (Newell's vector), over the
    /// faces within `crease_degrees` of the corner's own face, normalised.
    /// So a smooth surface shades smoothly and an edge sharper than the
    /// crease angle stays hard: a position whose corners get different
    /// normals becomes one vertex per normal. Texture coordinates are
    /// kept. Fails as [`Self::from_obj_smooth`] does when the vertices
    /// pass 65,536, and at line 0 when the faces break
    /// [`StaticMesh::new`]'s rules (a corner past the positions is
    /// [`ObjErrorKind::IndexOutOfRange`], counted from 1 as in a file).
    pub fn with_vertex_normals(self, crease_degrees: f32) -> Result<Self, ObjError> {
        if let Err(e) = self.faces_hold() {
            return Err(ObjError {
                line: 0,
                kind: self.mesh_error_kind(e),
            });
        }
        let has_uvs = !self.uvs.is_empty();
        let file = AttributedFaces {
            corners: self
                .corners
                .iter()
                .map(|&vertex| ObjCorner {
                    vertex,
                    texcoord: has_uvs.then_some(u32::from(vertex)),
                    normal: None,
                })
                .collect(),
            face_lines: std::vec![0; self.face_starts.len()],
            face_starts: self.face_starts,
            texcoords: self.uvs,
            normals: Vec::new(),
            positions: self.positions,
        };
        file.build(crease_degrees)
    }

    /// The same mesh with its vertices numbered in the order its faces
    /// first use them, face after face (vertices no face uses follow, in
    /// their order): what each vertex is and what each face draws are
    /// unchanged, and so is every frame. A frame transforms each vertex
    /// when a face first uses it, so in this order it reads the positions
    /// (and the per-vertex normals and texture coordinates) from front to
    /// back, where a file's own order may scatter them: the Stanford
    /// bunny's file order made a frame of it at 800x600 about 9 % slower
    /// (`docs/results/speed.md`). [`Self::from_obj_smooth`] numbers its
    /// vertices this way as it makes them. A mesh that is not valid
    /// ([`StaticMesh::new`], its shared planes as a mesh checks them), or
    /// whose per-vertex arrays are neither empty nor as long as its
    /// positions ([`Self::check`]), is returned as it is.
    pub fn with_vertices_in_first_use_order(mut self) -> Self {
        if self.check().is_err() {
            return self;
        }
        let count = self.positions.len();
        // New number of each old vertex; then the old vertex of each new
        // number. (`count` is at most 65,536: corners are `u16`.)
        const UNSEEN: u32 = u32::MAX;
        let mut new_of_old = std::vec![UNSEEN; count];
        let mut old_of_new = Vec::with_capacity(count);
        for &c in &self.corners {
            let slot = &mut new_of_old[usize::from(c)];
            if *slot == UNSEEN {
                *slot = old_of_new.len() as u32;
                old_of_new.push(c as usize);
            }
        }
        for (old, slot) in new_of_old.iter_mut().enumerate() {
            if *slot == UNSEEN {
                *slot = old_of_new.len() as u32;
                old_of_new.push(old);
            }
        }
        let renumber = |v: u16| new_of_old[usize::from(v)] as u16;
        for c in &mut self.corners {
            *c = renumber(*c);
        }
        for plane in &mut self.shared_planes {
            plane.vertices = plane.vertices.map(renumber);
        }
        fn permute<T: Copy>(values: &mut Vec<T>, old_of_new: &[usize]) {
            if !values.is_empty() {
                *values = old_of_new.iter().map(|&old| values[old]).collect();
            }
        }
        permute(&mut self.positions, &old_of_new);
        permute(&mut self.vertex_normals, &old_of_new);
        permute(&mut self.uvs, &old_of_new);
        self
    }

    /// The mesh with what its faces' geometry tells the pipeline found
    /// again: which faces are planar ([`Self::planar_faces`], so that no
    /// frame tests them), their normals ([`Self::face_normals`]) and which
    /// share a plane with overlapping coplanar faces
    /// ([`crate::host::coplanar::shared_planes`]), and whether it is closed
    /// ([`Self::closed_hull`]). Call it after changing
    /// positions or faces: stale planarity bits would draw a face that is
    /// no longer planar as one polygon, stale normals would shade it wrong.
    /// A mesh whose faces break [`StaticMesh::new`]'s rules is returned as
    /// it is.
    pub fn with_face_analysis(mut self) -> Self {
        if self.faces_hold().is_err() {
            return self;
        }
        self.planar_faces = planar_face_bits(&self).collect();
        self.face_normals = face_normals(&self).collect();
        self.face_planes = face_planes(&self).collect();
        let bent = (0..self.face_count()).any(|f| !self.face_is_planar(f));
        self.fan_normals = if bent {
            fan_normals(&self).collect()
        } else {
            Vec::new()
        };
        self.shared_planes = crate::host::coplanar::shared_planes(&self);
        (self.closed_hull, self.hull_caps) = match crate::host::capped_hull(&self) {
            Some((hull, caps)) => (Some(hull), caps),
            None => (None, Vec::new()),
        };
        self
    }

    /// Whether the positions, corners and face starts keep
    /// [`StaticMesh::new`]'s rules.
    pub(crate) fn faces_hold(&self) -> Result<(), MeshError> {
        StaticMesh::new(&self.positions, &self.corners, &self.face_starts).map(|_| ())
    }

    /// What [`Self::with_vertex_normals`] reports for a mesh whose arrays
    /// break `e`'s rule, in the terms of an OBJ file's faces.
    fn mesh_error_kind(&self, e: MeshError) -> ObjErrorKind {
        match e {
            MeshError::IndexOutOfRange { corner } => ObjErrorKind::IndexOutOfRange {
                element: Element::Vertex,
                index: self.corners.get(corner).map_or(0, |&c| i64::from(c) + 1),
                available: u32::try_from(self.positions.len()).unwrap_or(u32::MAX),
            },
            MeshError::FaceTooLarge { .. } => ObjErrorKind::TooManyCorners,
            MeshError::TooManyVertices => ObjErrorKind::TooManyVertices,
            _ => ObjErrorKind::TooFewCorners,
        }
    }
}

/// Faces whose corners name positions, texture coordinates and normals
/// each by their own index, as an OBJ file has them.
#[derive(Default)]
struct AttributedFaces {
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    normals: Vec<[f32; 3]>,
    corners: Vec<ObjCorner>,
    face_starts: Vec<u32>,
    /// Each face's line in the file, for errors.
    face_lines: Vec<u32>,
}

impl AttributedFaces {
    /// Face `f`'s corners.
    fn face(&self, f: usize) -> &[ObjCorner] {
        let start = self.face_starts[f] as usize;
        let end = self
            .face_starts
            .get(f + 1)
            .map_or(self.corners.len(), |&e| e as usize);
        &self.corners[start..end]
    }

    /// The mesh of one vertex per different (position, texture
    /// coordinate, normal) of the corners; see
    /// [`HostMesh::from_obj_smooth`].
    fn build(self, crease_degrees: f32) -> Result<HostMesh, ObjError> {
        let faces = self.face_starts.len();
        // Each face's Newell vector (its area times its unit normal).
        let area_normals: Vec<Vec3> = (0..faces)
            .map(|f| {
                newell_normal(
                    self.face(f)
                        .iter()
                        .map(|c| self.positions[usize::from(c.vertex)]),
                )
            })
            .collect();
        // Positions with the same coordinates are one point of the surface
        // (files often repeat a position at a texture seam): each position's
        // first index with its coordinates.
        let mut first: HashMap<[u32; 3], u32> = HashMap::new();
        let weld: Vec<u32> = (0..self.positions.len() as u32)
            .map(|k| {
                let bits = self.positions[k as usize].map(|c| (c + 0.0).to_bits());
                *first.entry(bits).or_insert(k)
            })
            .collect();
        let point = |c: &ObjCorner| weld[usize::from(c.vertex)] as usize;
        // The faces around each point.
        let mut around: Vec<Vec<u32>> = std::vec![Vec::new(); self.positions.len()];
        for f in 0..faces {
            for c in self.face(f) {
                let list = &mut around[point(c)];
                if list.last() != Some(&(f as u32)) {
                    list.push(f as u32);
                }
            }
        }
        let cos_crease = crease_degrees.to_radians().cos();
        let has_uvs = self.corners.iter().any(|c| c.texcoord.is_some());
        let mut mesh = HostMesh::default();
        let mut index: HashMap<(u16, Option<u32>, [u32; 3]), u16> = HashMap::new();
        for f in 0..faces {
            mesh.face_starts.push(mesh.corners.len() as u32);
            let own = unit(area_normals[f]);
            for c in self.face(f) {
                let normal = match c.normal.and_then(|n| self.normals.get(n as usize)) {
                    Some(&n) => unit(Vec3::from_array(n)),
                    None => {
                        let mut sum = Vec3::default();
                        for &g in &around[point(c)] {
                            let n = area_normals[g as usize];
                            let smooth = own.dot(unit(n)) >= cos_crease;
                            if smooth || g as usize == f {
                                sum = sum + n;
                            }
                        }
                        unit(sum)
                    }
                };
                let normal = [normal.x, normal.y, normal.z];
                let key = (c.vertex, c.texcoord, normal.map(f32::to_bits));
                let next = mesh.positions.len();
                let id = match index.get(&key) {
                    Some(&id) => id,
                    None => {
                        let id = u16::try_from(next).map_err(|_| ObjError {
                            line: self.face_lines[f],
                            kind: ObjErrorKind::TooManyVertices,
                        })?;
                        index.insert(key, id);
                        mesh.positions.push(self.positions[usize::from(c.vertex)]);
                        mesh.vertex_normals.push(normal);
                        if has_uvs {
                            let uv = c.texcoord.and_then(|t| self.texcoords.get(t as usize));
                            mesh.uvs.push(uv.copied().unwrap_or([0.0; 2]));
                        }
                        id
                    }
                };
                mesh.corners.push(id);
            }
        }
        Ok(mesh.with_face_analysis())
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

    fn fan_normals(&self) -> &[[f32; 3]] {
        &self.fan_normals
    }

    fn vertex_normals(&self) -> &[[f32; 3]] {
        &self.vertex_normals
    }

    fn uvs(&self) -> &[[f32; 2]] {
        &self.uvs
    }

    fn closed_hull(&self) -> Option<ClosedHull> {
        self.closed_hull
    }

    fn hull_caps(&self) -> &[[[f32; 3]; 3]] {
        &self.hull_caps
    }
    fn face_planes(&self) -> &[FacePlane] {
        &self.face_planes
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

    /// A bent face's fan triangles keep their normals (Newell's of each
    /// triangle, unit length, the value each frame computed before); a
    /// planar face's and a mesh's with none bent keep none.
    #[test]
    fn from_obj_stores_the_normals_of_bent_faces_fans() {
        let mesh = HostMesh::from_obj(&quads()).unwrap();
        assert_eq!(mesh.fan_normals.len(), mesh.corners.len());
        for f in 0..40 {
            let c = mesh.face(f);
            for k in [1, 2] {
                let got = mesh.fan_normal(f, k);
                if f % 3 != 0 {
                    assert_eq!(got, None, "face {f}");
                    continue;
                }
                let triangle = [c[0], c[k], c[k + 1]].map(|i| mesh.positions[usize::from(i)]);
                let n = unit(newell_normal(triangle));
                assert_eq!(got, Some([n.x, n.y, n.z]), "face {f}, triangle {k}");
            }
            assert_eq!(mesh.fan_normal(f, 0), None);
        }
        // The lifted corner tilts the two triangles apart.
        assert_ne!(mesh.fan_normal(0, 1), mesh.fan_normal(0, 2));
        let flat = HostMesh::from_obj(CUBE).unwrap();
        assert!(flat.fan_normals.is_empty());
        assert_eq!(flat.fan_normal(0, 1), None);
    }

    /// Drawing a bent face, the shading sees each fan triangle's stored
    /// normal (here replaced by marks no corner gives), not one computed
    /// from its corners.
    #[test]
    fn shading_reads_a_bent_faces_stored_fan_normals() {
        use crate::host::HostRenderer;
        use crate::{Camera, Cull, Mat4};
        let mut mesh = HostMesh::from_obj(&quads()).unwrap();
        let marks = [[0.0, 0.6, 0.8], [0.8, 0.0, 0.6]];
        mesh.fan_normals[0] = marks[0];
        mesh.fan_normals[1] = marks[1];
        let mut renderer = HostRenderer::<u32, crate::Depth16>::for_mesh(&mesh, 64, 64, 0).unwrap();
        let model = Mat4::translation(Vec3::new(-0.5, -0.5, -4.0));
        let camera = Camera::perspective(Mat4::IDENTITY, 60.0, 64, 64, 0.5, 100.0);
        let mut seen = Vec::new();
        renderer
            .draw_mesh(&mesh, &model, &camera, Cull::None, |f| {
                if f.face == 0 {
                    seen.push(f.normal());
                }
                f.face
            })
            .unwrap();
        let marks = marks.map(Vec3::from_array);
        assert_eq!(seen, marks.to_vec());
    }

    /// A cube of quads.
    const CUBE: &[u8] = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

    /// A cube's edges are sharper than 60 degrees: each corner keeps its
    /// face's normal (24 vertices); past 90 degrees every corner is
    /// smoothed along the cube's diagonal (8 vertices).
    #[test]
    fn creases_keep_hard_edges_hard() {
        let hard = HostMesh::from_obj_smooth(CUBE, 60.0).unwrap();
        assert_eq!((hard.positions.len(), hard.vertex_normals.len()), (24, 24));
        assert!(hard.uvs.is_empty());
        for f in 0..6 {
            for &v in hard.face(f) {
                assert_eq!(
                    hard.vertex_normals[usize::from(v)],
                    hard.face_normals[f],
                    "face {f}"
                );
            }
        }
        let smooth = HostMesh::from_obj_smooth(CUBE, 100.0).unwrap();
        assert_eq!(smooth.positions.len(), 8);
        let third = 1.0 / 3.0f32.sqrt();
        for (p, n) in smooth.positions.iter().zip(&smooth.vertex_normals) {
            for k in 0..3 {
                let want = if p[k] > 0.5 { third } else { -third };
                assert!((n[k] - want).abs() < 1e-6, "{p:?}: {n:?}");
            }
        }
        // Drawn flat, the cube is the same: the same faces, positions and
        // face normals as the positions-only mesh's.
        let flat = HostMesh::from_obj(CUBE).unwrap();
        assert_eq!(hard.face_normals, flat.face_normals);
        for f in 0..6 {
            let at = |m: &HostMesh, k: usize| m.positions[usize::from(m.face(f)[k])];
            assert!((0..4).all(|k| at(&hard, k) == at(&flat, k)));
        }
    }

    /// A file's normals are used, normalised; texture coordinates split
    /// vertices at seams, and a corner without one gets (0, 0).
    #[test]
    fn file_normals_and_texture_coordinates_are_kept() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.25\nvt 1 1\nvn 0 0 3\n\
f 1/1/1 2/1/1 3/2/1\nf 1/2/1 3/2/1 2//1\n";
        let mesh = HostMesh::from_obj_smooth(obj, 60.0).unwrap();
        // (v1, vt1), (v2, vt1), (v3, vt2), (v1, vt2), (v2, none).
        assert_eq!(mesh.positions.len(), 5);
        assert!(mesh.vertex_normals.iter().all(|&n| n == [0.0, 0.0, 1.0]));
        assert_eq!(
            mesh.uvs,
            [[0.5, 0.25], [0.5, 0.25], [1.0, 1.0], [1.0, 1.0], [0.0, 0.0]]
        );
        assert_eq!(mesh.face(1), &[3, 2, 4]);
        assert_eq!(mesh.vertex_uv(2), Some([1.0, 1.0]));
        assert_eq!(mesh.vertex_normal(4), Some([0.0, 0.0, 1.0]));
    }

    /// Positions repeated with the same coordinates (a texture seam) are
    /// one point for the normals: both sides of the seam get the same
    /// normal, as with one shared position.
    #[test]
    fn seams_share_their_normals() {
        let shared = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nf 1 2 3\nf 2 4 3\n";
        let seam = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.5\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 5 4 6\n";
        let shared = HostMesh::from_obj_smooth(shared, 60.0).unwrap();
        let seam = HostMesh::from_obj_smooth(seam, 60.0).unwrap();
        let normals = |m: &HostMesh| -> Vec<[f32; 3]> {
            m.corners
                .iter()
                .map(|&v| m.vertex_normals[usize::from(v)])
                .collect()
        };
        assert_eq!(normals(&shared), normals(&seam));
        // Smoothed: the corners on the shared edge are not face normals.
        assert_ne!(normals(&shared)[1], shared.face_normals[0]);
    }

    /// More than 65,536 vertices after the split is an error at the face
    /// that passes the limit.
    #[test]
    fn too_many_split_vertices_is_an_error() {
        let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        for k in 0..21_846 {
            let _ = writeln!(obj, "vt {k} 0");
        }
        for k in 0..21_846 {
            let t = k + 1;
            let _ = writeln!(obj, "f 1/{t} 2/{t} 3/{t}");
        }
        let error = HostMesh::from_obj_smooth(obj.as_bytes(), 60.0).unwrap_err();
        assert_eq!(error.kind, ObjErrorKind::TooManyVertices);
        // 21,845 faces of 3 new vertices fit (65,535); the next passes.
        assert_eq!(error.line, 3 + 21_846 + 21_846);
    }
}
