//! Meshes the pipeline can draw: positions and polygonal faces.
//!
//! [`StaticMesh`] borrows plain slices, so a mesh written as Rust statics
//! (see `examples/obj2rust.rs`) stays in flash with no RAM copy. The OBJ
//! reader's [`ObjMesh`](crate::front::obj::ObjMesh) holds the same layout in
//! fixed-capacity storage.
//!
//! Layout: `positions[i]` is vertex `i`; face `f` is the run of `corners`
//! from `face_starts[f]` up to `face_starts[f + 1]` (or the end of
//! `corners` for the last face), each corner a 0-based vertex index.

use crate::front::closed_hull::ClosedHull;
use crate::front::face_plane::FacePlane;
use crate::front::geometry::{newell_normal, unit};
use crate::limits::POSITION_SCALE;

/// A polygon mesh: positions and faces of 3 or more corners.
pub trait Mesh {
    /// Number of vertices.
    fn vertex_count(&self) -> usize;
    /// Position of vertex `index` (`index < vertex_count()`).
    fn position(&self, index: usize) -> [f32; 3];
    /// Number of faces.
    fn face_count(&self) -> usize;
    /// Vertex indices of face `index` (`index < face_count()`), in order
    /// around the face.
    fn face(&self, index: usize) -> &[u16];

    /// Whether face `index` is planar ([`is_planar`]). A mesh that knows it
    /// in advance (for example a [`StaticMesh`] with planarity bits from
    /// its generator) answers without any arithmetic.
    fn face_is_planar(&self, index: usize) -> bool {
        is_planar(self, index)
    }

    /// The mesh's positions quantized in its bounding sphere and its face
    /// normals ([`QuantizedView`]), when it has them: then
    /// [`draw_mesh`](crate::front::scene::draw_mesh) transforms, projects
    /// and shades it in integers. `None` (the default) for meshes in `f32`.
    fn quantized(&self) -> Option<QuantizedView<'_>> {
        None
    }

    /// Faces that take their depth from a plane shared with other faces
    /// ([`SharedPlane`]), sorted by face, each face at most once. Empty
    /// (the default) when the mesh has none or does not know.
    fn shared_planes(&self) -> &[SharedPlane] {
        &[]
    }

    /// Face `index`'s normal in model space, the direction of
    /// [`newell_normal`](crate::newell_normal) of the face's corners, when
    /// the mesh stores it: then a shading that asks for the face's normal
    /// ([`FaceInfo::normal`](crate::FaceInfo::normal)) gets it without
    /// reading the corners. Stored at unit length ([`face_normals`] writes
    /// them so), it is turned into view space by one rotation and no
    /// square root when the model-view matrix is a rotation with uniform
    /// scale; any other length is normalised each time. `None` (the
    /// default) when it is not stored; it is then computed each frame.
    fn face_normal(&self, index: usize) -> Option<[f32; 3]> {
        let _ = index;
        None
    }

    /// The unit normal of triangle `k` (corners `0, k, k + 1`, `k` from 1)
    /// of face `face`'s fan, when the face is not planar (the pipeline
    /// draws such a face as its fan) and the mesh stores it: in model
    /// space, as [`Self::face_normal`], so that shading reads it instead
    /// of the triangle's corners. `None` (the default) when it is not
    /// stored; it is then computed each frame.
    fn fan_normal(&self, face: usize, k: usize) -> Option<[f32; 3]> {
        let _ = (face, k);
        None
    }

    /// Vertex `index`'s normal in model space, for smooth shading
    /// ([`VertexInfo::normal`](crate::VertexInfo::normal)), when the mesh
    /// has one: at unit length it is turned into view space with no square
    /// root, as a face's is. `None` (the default) when it has none.
    fn vertex_normal(&self, index: usize) -> Option<[f32; 3]> {
        let _ = index;
        None
    }

    /// Vertex `index`'s texture coordinates `(u, v)`, `(0, 0)` the
    /// texture's bottom-left corner and `(1, 1)` its top-right, when the
    /// mesh has them. `None` (the default) when it has none.
    fn vertex_uv(&self, index: usize) -> Option<[f32; 2]> {
        let _ = index;
        None
    }

    /// Whether every face is a triangle, known to the type: `true` for a
    /// [`Triangles`](crate::Triangles) mesh, and then
    /// [`draw_mesh`](crate::front::scene::draw_mesh) leaves out of the code its paths
    /// for faces of more corners (non-planar splits, convex quads, polygon
    /// outlines). `false` (the default) for any other.
    fn triangles_only(&self) -> bool {
        false
    }

    /// The mesh's [`ClosedHull`], when it is a closed surface that winds
    /// counter-clockwise seen from outside: then a draw with
    /// [`Cull::None`](crate::Cull::None) leaves out the back faces
    /// wherever they cannot show. `None` (the default) when it is not
    /// closed or does not know.
    fn closed_hull(&self) -> Option<ClosedHull> {
        None
    }

    /// Triangles (model space, corners counter-clockwise seen from
    /// outside) that close the mesh's holes, when its
    /// [`closed_hull`](Self::closed_hull) is that of the mesh with them:
    /// a draw with [`Cull::None`](crate::Cull::None) then leaves out back
    /// faces only when every cap faces away, so that no hole shows the
    /// inside. Empty (the default) for a closed mesh or one with no hull.
    fn hull_caps(&self) -> &[[[f32; 3]; 3]] {
        &[]
    }

    /// Each face's plane ([`FacePlane::of_triangle`] for a triangle,
    /// [`FacePlane::NONE`] for any other), so that a draw with back faces
    /// culled leaves out a face turned away beyond doubt before any of its
    /// corners is transformed (host builds, the `std` feature). Empty (the
    /// default) when the mesh has none; faces past its end are tested on
    /// their projected corners.
    fn face_planes(&self) -> &[FacePlane] {
        &[]
    }
}

/// A face whose depth comes from a plane it shares with other faces of
/// its mesh: the plane through three of the mesh's vertices. Faces of one
/// plane that overlap (decals, double-sided cards, stacked coplanar
/// faces) share one, so they hold exactly equal depths and the face
/// listed first wins wherever they overlap, on every frame and from every
/// camera ([`Tables::share_plane`](crate::raster::Tables::share_plane)).
/// The host finds them (`zline::host::coplanar`); `obj2rust` writes them
/// into flash meshes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SharedPlane {
    /// The face.
    pub face: u32,
    /// Three vertices of the mesh that span the plane.
    pub vertices: [u16; 3],
}

/// Why a mesh's arrays do not describe a valid mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshError {
    /// A corner names a vertex index at or beyond the vertex count.
    IndexOutOfRange {
        /// Position of the offending corner in `corners`.
        corner: usize,
    },
    /// Face starts decrease, exceed the corner count, or leave a face with
    /// fewer than 3 corners.
    BadFaceStarts {
        /// The offending face.
        face: usize,
    },
    /// More than 65,536 vertices (corners are `u16`).
    TooManyVertices,
    /// Fewer planarity bits than faces.
    BadPlanarity,
    /// A face has more corners than the pipeline draws
    /// ([`MAX_FACE_CORNERS`](crate::limits::MAX_FACE_CORNERS)).
    FaceTooLarge {
        /// The offending face.
        face: usize,
    },
    /// A quantized mesh's normals: not one per face (`face: None`), or one
    /// longer than a unit vector rounded (`face: Some(f)`).
    BadNormals {
        /// The offending face, if one.
        face: Option<usize>,
    },
    /// A quantized mesh's sphere: its centre is not finite, or its radius
    /// is not finite and positive.
    BadSphere,
    /// Shared plane `index` names a face or vertex beyond the mesh, or the
    /// list is not sorted by face with each face once.
    BadSharedPlane {
        /// The offending entry.
        index: usize,
    },
    /// A quantized mesh's table of exact normals: not one per face (`face:
    /// None`), or one that is not its triangle's
    /// [`QuantizedMesh::exact_normal`](crate::QuantizedMesh::exact_normal) (`face:
    /// Some(f)`; zero for a face that is not a triangle).
    BadExactNormals {
        /// The offending face, if one.
        face: Option<usize>,
    },
    /// Vertex normals or texture coordinates, not one per vertex.
    BadVertexAttributes,
}

/// A mesh over borrowed slices: `'static` ones live in flash.
#[derive(Debug, Clone, Copy)]
pub struct StaticMesh<'a> {
    positions: &'a [[f32; 3]],
    corners: &'a [u16],
    face_starts: &'a [u32],
    /// Bit `f` set when face `f` is planar; empty when not precomputed.
    planar: &'a [u32],
    /// Faces with a shared plane, sorted by face.
    shared: &'a [SharedPlane],
    /// Newell's normal of each face; empty when not precomputed.
    normals: &'a [[f32; 3]],
    /// Each vertex's normal; empty when the mesh has none.
    vertex_normals: &'a [[f32; 3]],
    /// Each vertex's texture coordinates; empty when the mesh has none.
    uvs: &'a [[f32; 2]],
    /// The hull of a closed mesh, when it is one.
    closed_hull: Option<ClosedHull>,
}

impl<'a> StaticMesh<'a> {
    /// Checks the arrays and wraps them. `const`, so a static mesh is
    /// checked at compile time:
    ///
    /// ```
    /// use zline::{Mesh, StaticMesh};
    /// static QUAD: StaticMesh<'static> = match StaticMesh::new(
    ///     &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     &[0, 1, 2, 3],
    ///     &[0],
    /// ) {
    ///     Ok(mesh) => mesh,
    ///     Err(_) => panic!("invalid mesh"),
    /// };
    /// assert_eq!(QUAD.face(0), &[0, 1, 2, 3]);
    /// ```
    pub const fn new(
        positions: &'a [[f32; 3]],
        corners: &'a [u16],
        face_starts: &'a [u32],
    ) -> Result<Self, MeshError> {
        if positions.len() > 1 << 16 {
            return Err(MeshError::TooManyVertices);
        }
        let mut k = 0;
        while k < corners.len() {
            if corners[k] as usize >= positions.len() {
                return Err(MeshError::IndexOutOfRange { corner: k });
            }
            k += 1;
        }
        let mut f = 0;
        while f < face_starts.len() {
            let start = face_starts[f] as usize;
            let end = if f + 1 < face_starts.len() {
                face_starts[f + 1] as usize
            } else {
                corners.len()
            };
            if end > corners.len() || start + 3 > end {
                return Err(MeshError::BadFaceStarts { face: f });
            }
            if end - start > crate::limits::MAX_FACE_CORNERS {
                return Err(MeshError::FaceTooLarge { face: f });
            }
            f += 1;
        }
        Ok(Self {
            positions,
            corners,
            face_starts,
            planar: &[],
            shared: &[],
            normals: &[],
            vertex_normals: &[],
            uvs: &[],
            closed_hull: None,
        })
    }

    /// The same mesh with faces that share planes ([`SharedPlane`]),
    /// sorted by face. `const`, so the list is checked at compile time.
    pub const fn with_shared_planes(self, shared: &'a [SharedPlane]) -> Result<Self, MeshError> {
        if let Err(e) = check_shared_planes(shared, self.face_starts.len(), self.positions.len()) {
            return Err(e);
        }
        Ok(Self { shared, ..self })
    }

    /// The same mesh with its faces' planarity precomputed: bit `f % 32`
    /// of `bits[f / 32]` is set when face `f` is planar ([`is_planar`]).
    /// `Err` when `bits` is too short for the faces.
    pub const fn with_planar_faces(self, bits: &'a [u32]) -> Result<Self, MeshError> {
        if bits.len() < self.face_starts.len().div_ceil(32) {
            return Err(MeshError::BadPlanarity);
        }
        Ok(Self {
            planar: bits,
            ..self
        })
    }

    /// The same mesh with each face's normal precomputed: `normals[f]` is
    /// the unit normal of face `f`, as [`face_normals`] writes them. `Err`
    /// when there is not one for every face.
    pub const fn with_face_normals(self, normals: &'a [[f32; 3]]) -> Result<Self, MeshError> {
        if normals.len() != self.face_starts.len() {
            return Err(MeshError::BadNormals { face: None });
        }
        Ok(Self { normals, ..self })
    }

    /// The same mesh with a normal for each vertex, for smooth shading
    /// ([`Mesh::vertex_normal`]; unit length, as `HostMesh::with_vertex_normals`
    /// and `obj2rust` write them). `Err` when there is not one for every
    /// vertex.
    pub const fn with_vertex_normals(self, normals: &'a [[f32; 3]]) -> Result<Self, MeshError> {
        if normals.len() != self.positions.len() {
            return Err(MeshError::BadVertexAttributes);
        }
        Ok(Self {
            vertex_normals: normals,
            ..self
        })
    }

    /// The same mesh with texture coordinates for each vertex
    /// ([`Mesh::vertex_uv`]). `Err` when there are not some for every
    /// vertex.
    pub const fn with_uvs(self, uvs: &'a [[f32; 2]]) -> Result<Self, MeshError> {
        if uvs.len() != self.positions.len() {
            return Err(MeshError::BadVertexAttributes);
        }
        Ok(Self { uvs, ..self })
    }

    /// The same mesh declared closed, with its hull ([`ClosedHull`]: every
    /// edge met once by a face running the other way, faces
    /// counter-clockwise seen from outside, every position in the
    /// sphere), as `obj2rust` writes it for a mesh the host found closed
    /// (`HostMesh::closed_hull`). A hull that does not hold can leave out
    /// faces that show.
    pub const fn with_closed_hull(self, hull: ClosedHull) -> Self {
        Self {
            closed_hull: Some(hull),
            ..self
        }
    }

    /// All positions.
    pub const fn positions(&self) -> &'a [[f32; 3]] {
        self.positions
    }

    /// All corners, face after face.
    pub const fn corners(&self) -> &'a [u16] {
        self.corners
    }

    /// Where each face starts in [`Self::corners`].
    pub const fn face_starts(&self) -> &'a [u32] {
        self.face_starts
    }
}

/// Checks a mesh's shared planes: sorted by face, each face once, every
/// face and vertex in the mesh (`faces` faces, `vertices` vertices).
pub(crate) const fn check_shared_planes(
    shared: &[SharedPlane],
    faces: usize,
    vertices: usize,
) -> Result<(), MeshError> {
    let mut k = 0;
    while k < shared.len() {
        let entry = shared[k];
        let sorted = k == 0 || shared[k - 1].face < entry.face;
        let in_mesh = (entry.face as usize) < faces
            && (entry.vertices[0] as usize) < vertices
            && (entry.vertices[1] as usize) < vertices
            && (entry.vertices[2] as usize) < vertices;
        if !sorted || !in_mesh {
            return Err(MeshError::BadSharedPlane { index: k });
        }
        k += 1;
    }
    Ok(())
}

/// Face `index` of a mesh in the shared layout whose arrays were checked
/// when it was made ([`StaticMesh::new`], `QuantizedMesh::new`): `index`
/// below the face count.
pub(crate) fn checked_face_of<'c>(
    corners: &'c [u16],
    face_starts: &[u32],
    index: usize,
) -> &'c [u16] {
    let start = face_starts[index] as usize;
    let end = face_starts
        .get(index + 1)
        .map_or(corners.len(), |&e| e as usize);
    &corners[start..end]
}

/// Face `index` of a mesh in the shared layout; empty when `index` or the
/// arrays are out of range (a mesh whose arrays were never checked, such
/// as a `HostMesh` built field by field: drawing it is then an error,
/// not a panic).
pub(crate) fn face_of<'c>(corners: &'c [u16], face_starts: &[u32], index: usize) -> &'c [u16] {
    let Some(&start) = face_starts.get(index) else {
        return &[];
    };
    let end = face_starts
        .get(index + 1)
        .map_or(corners.len(), |&e| e as usize);
    corners.get(start as usize..end).unwrap_or(&[])
}

/// A mesh in the one array layout every zline mesh keeps: positions,
/// the corners of all faces face after face, where each face starts, and
/// optional planarity bits. Whatever owns the arrays ([`StaticMesh`] in
/// flash, [`ObjMesh`](crate::front::obj::ObjMesh) in fixed capacity, the
/// host's `HostMesh` in `Vec`s) lends them here and gets [`Mesh`] for
/// free, written once.
pub trait MeshArrays {
    /// Vertex positions.
    fn positions(&self) -> &[[f32; 3]];
    /// Corners (vertex indices) of all faces, face after face.
    fn corners(&self) -> &[u16];
    /// Where each face starts in [`Self::corners`].
    fn face_starts(&self) -> &[u32];
    /// Bit `f % 32` of word `f / 32` set when face `f` is planar; empty
    /// when not known in advance.
    fn planar_bits(&self) -> &[u32] {
        &[]
    }
    /// Faces with a shared plane ([`Mesh::shared_planes`]).
    fn shared_planes(&self) -> &[SharedPlane] {
        &[]
    }
    /// Each face's normal ([`Mesh::face_normal`]); empty when not known in
    /// advance.
    fn face_normals(&self) -> &[[f32; 3]] {
        &[]
    }
    /// The normals of the fans of faces that are not planar
    /// ([`Mesh::fan_normal`]), one slot per corner as [`fan_normals`]
    /// lays them out; empty when not known in advance.
    fn fan_normals(&self) -> &[[f32; 3]] {
        &[]
    }
    /// Each vertex's normal ([`Mesh::vertex_normal`]); empty when none.
    fn vertex_normals(&self) -> &[[f32; 3]] {
        &[]
    }
    /// Each vertex's texture coordinates ([`Mesh::vertex_uv`]); empty when
    /// none.
    fn uvs(&self) -> &[[f32; 2]] {
        &[]
    }
    /// The hull of a closed mesh ([`Mesh::closed_hull`]); `None` when it is
    /// not one or is not known to be.
    fn closed_hull(&self) -> Option<ClosedHull> {
        None
    }
    /// The caps over the holes of a mesh whose hull holds with them
    /// ([`Mesh::hull_caps`]); empty when none.
    fn hull_caps(&self) -> &[[[f32; 3]; 3]] {
        &[]
    }
    /// Each face's plane ([`Mesh::face_planes`]); empty when none.
    fn face_planes(&self) -> &[FacePlane] {
        &[]
    }
}

impl<T: MeshArrays + ?Sized> Mesh for T {
    fn vertex_count(&self) -> usize {
        self.positions().len()
    }

    fn position(&self, index: usize) -> [f32; 3] {
        // NaN beyond the positions (a mesh whose arrays were never
        // checked): the front end finds such a corner out of range first,
        // and anything else sees a non-finite position, not a panic.
        self.positions()
            .get(index)
            .copied()
            .unwrap_or([f32::NAN; 3])
    }

    fn face_count(&self) -> usize {
        self.face_starts().len()
    }

    fn face(&self, index: usize) -> &[u16] {
        face_of(self.corners(), self.face_starts(), index)
    }

    fn face_is_planar(&self, index: usize) -> bool {
        match self.planar_bits().get(index / 32) {
            Some(word) => word & (1 << (index % 32)) != 0,
            None => is_planar(self, index),
        }
    }

    fn shared_planes(&self) -> &[SharedPlane] {
        MeshArrays::shared_planes(self)
    }

    fn face_normal(&self, index: usize) -> Option<[f32; 3]> {
        self.face_normals().get(index).copied()
    }

    fn fan_normal(&self, face: usize, k: usize) -> Option<[f32; 3]> {
        let normals = self.fan_normals();
        if normals.is_empty() {
            return None;
        }
        let start = *self.face_starts().get(face)? as usize;
        // (A zero slot is no normal: a planar face's, or no area's.)
        let n = *normals.get(start + k.checked_sub(1)?)?;
        (n != [0.0; 3]).then_some(n)
    }

    fn vertex_normal(&self, index: usize) -> Option<[f32; 3]> {
        self.vertex_normals().get(index).copied()
    }

    fn vertex_uv(&self, index: usize) -> Option<[f32; 2]> {
        self.uvs().get(index).copied()
    }

    fn closed_hull(&self) -> Option<ClosedHull> {
        MeshArrays::closed_hull(self)
    }

    fn hull_caps(&self) -> &[[[f32; 3]; 3]] {
        MeshArrays::hull_caps(self)
    }

    fn face_planes(&self) -> &[FacePlane] {
        MeshArrays::face_planes(self)
    }
}

impl MeshArrays for StaticMesh<'_> {
    fn positions(&self) -> &[[f32; 3]] {
        self.positions
    }

    fn corners(&self) -> &[u16] {
        self.corners
    }

    fn face_starts(&self) -> &[u32] {
        self.face_starts
    }

    fn planar_bits(&self) -> &[u32] {
        self.planar
    }

    fn shared_planes(&self) -> &[SharedPlane] {
        self.shared
    }

    fn face_normals(&self) -> &[[f32; 3]] {
        self.normals
    }

    fn vertex_normals(&self) -> &[[f32; 3]] {
        self.vertex_normals
    }

    fn uvs(&self) -> &[[f32; 2]] {
        self.uvs
    }

    fn closed_hull(&self) -> Option<ClosedHull> {
        self.closed_hull
    }
}

/// Each face's normal for [`StaticMesh::with_face_normals`] (and
/// [`Mesh::face_normal`]): [`newell_normal`] of its corners, in model
/// space, at unit length (zero for a face of no area).
pub fn face_normals<M: Mesh + ?Sized>(mesh: &M) -> impl Iterator<Item = [f32; 3]> + '_ {
    (0..mesh.face_count()).map(move |f| unit_normal_of(mesh, mesh.face(f)))
}

/// Each face's plane for [`Mesh::face_planes`]: [`FacePlane::of_triangle`]
/// of a triangle's corners, [`FacePlane::NONE`] for a face of more
/// corners (the early back-face test takes triangles only).
pub fn face_planes<M: Mesh + ?Sized>(mesh: &M) -> impl Iterator<Item = FacePlane> + '_ {
    (0..mesh.face_count()).map(move |f| match mesh.face(f) {
        &[a, b, c] => {
            let p = |i: u16| mesh.position(usize::from(i));
            FacePlane::of_triangle(p(a), p(b), p(c))
        }
        _ => FacePlane::NONE,
    })
}

/// [`newell_normal`] of the polygon of `corners` of `mesh`, at unit length
/// (zero for no area).
fn unit_normal_of<M: Mesh + ?Sized>(mesh: &M, corners: &[u16]) -> [f32; 3] {
    let n = unit(newell_normal(
        corners.iter().map(|&i| mesh.position(usize::from(i))),
    ));
    [n.x, n.y, n.z]
}

/// The normals of the fans of a mesh's faces that are not planar, for
/// [`MeshArrays::fan_normals`] (and [`Mesh::fan_normal`]): one slot per
/// corner, so that face `f`'s slots start where its corners do. Slot
/// `k - 1` of a face of `n > 3` corners that is not planar holds the
/// normal of its fan's triangle `k` (corners `0, k, k + 1`, for `k` in
/// `1..n - 1`): [`newell_normal`] of those corners, model space, at unit
/// length (zero for no area), the normal a frame would compute for it.
/// Every other slot is zero.
pub fn fan_normals<M: Mesh + ?Sized>(mesh: &M) -> impl Iterator<Item = [f32; 3]> + '_ {
    (0..mesh.face_count()).flat_map(move |f| {
        let corners = mesh.face(f);
        let bent = corners.len() > 3 && !mesh.face_is_planar(f);
        (0..corners.len()).map(move |slot| match corners.get(slot + 1..slot + 3) {
            Some(&[b, c]) if bent => unit_normal_of(mesh, &[corners[0], b, c]),
            _ => [0.0; 3],
        })
    })
}

/// Planarity bits for [`StaticMesh::with_planar_faces`]: one bit per face.
pub fn planar_face_bits<M: Mesh + ?Sized>(mesh: &M) -> impl Iterator<Item = u32> + '_ {
    (0..mesh.face_count().div_ceil(32)).map(move |word| {
        (0..32)
            .filter(|bit| word * 32 + bit < mesh.face_count() && is_planar(mesh, word * 32 + bit))
            .fold(0u32, |bits, bit| bits | 1 << bit)
    })
}

/// Largest deviation from planar, relative to the face's size, for which a
/// face is drawn as one polygon.
pub const PLANARITY_TOLERANCE: f32 = 1e-3;

/// Whether face `index` is planar: every corner lies within
/// [`PLANARITY_TOLERANCE`] times the face's radius of the plane through its
/// centroid with its Newell normal. Triangles always are.
///
/// A face that is not planar has no single plane, so the pipeline (and the
/// float64 reference) draw it as the fan of triangles from its first corner,
/// as OBJ loaders usually do. A planar face is drawn whole, so a concave
/// planar face stays exact (a convex quad goes to the tables as its two
/// triangles, which cover the same samples).
pub fn is_planar<M: Mesh + ?Sized>(mesh: &M, index: usize) -> bool {
    let corners = mesh.face(index);
    let count = corners.len();
    if count <= 3 {
        return true;
    }
    // In f64, relative to corner 0, so that no finite f32 corners overflow
    // or underflow: a difference is below 2^129 in magnitude (and 0 or at
    // least 2^-149); with up to 2^16 corners, `d` (below) stays under
    // 2^146, the normal's components under 2^275, and the squares compared
    // under 2^846, while a non-zero deviation squared stays above 2^-894.
    // (In f32 a face with sides near 1e9 judged 4th and 6th powers both
    // infinite, and one with sides near 1e-9 saw its deviation vanish.)
    let origin = mesh.position(usize::from(corners[0])).map(f64::from);
    let relative = |k: usize| {
        let p = mesh.position(usize::from(corners[k]));
        [0, 1, 2].map(|i| f64::from(p[i]) - origin[i])
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // Newell's normal: the fan's cross products from corner 0.
    let mut normal = [0.0f64; 3];
    for k in 1..count - 1 {
        let (p, q) = (relative(k), relative(k + 1));
        normal[0] += p[1] * q[2] - p[2] * q[1];
        normal[1] += p[2] * q[0] - p[0] * q[2];
        normal[2] += p[0] * q[1] - p[1] * q[0];
    }
    // Everything scaled by `count` so the centroid needs no division;
    // compared squared, so no square root either.
    let mut sum = [0.0f64; 3];
    for k in 1..count {
        let p = relative(k);
        sum = [0, 1, 2].map(|i| sum[i] + p[i]);
    }
    let n = count as f64;
    let (mut radius2, mut deviation2) = (0.0f64, 0.0f64);
    for k in 0..count {
        // count · (corner - centroid)
        let p = relative(k);
        let d = [0, 1, 2].map(|i| p[i] * n - sum[i]);
        radius2 = radius2.max(dot(d, d));
        let along = dot(d, normal);
        deviation2 = deviation2.max(along * along);
    }
    let length2 = dot(normal, normal);
    let tolerance = f64::from(PLANARITY_TOLERANCE);
    // distance = along / |normal| <= tolerance · radius, squared.
    length2 > 0.0 && deviation2 <= tolerance * tolerance * radius2 * length2
}

/// What the integer front end reads from a quantized mesh: its positions,
/// its face normals, and the sphere they are quantized in.
#[derive(Debug, Clone, Copy)]
pub struct QuantizedView<'a> {
    /// Vertex positions, `centre + radius · q / POSITION_SCALE`.
    pub positions: &'a [[i16; 3]],
    /// One unit normal per face, `n / NORMAL_SCALE`; zero for a face of no
    /// area.
    pub normals: &'a [[i16; 3]],
    /// Centre of the quantization sphere.
    pub centre: [f32; 3],
    /// Radius of the quantization sphere (positive, finite).
    pub radius: f32,
    /// Each triangle's exact normal (see
    /// [`QuantizedMesh::with_exact_normals`](crate::front::quantized::QuantizedMesh::with_exact_normals);
    /// zero for a face that is not a triangle), or empty: the model-space
    /// back-face test then works them out.
    pub exact_normals: &'a [[i16; 3]],
    /// One unit normal per vertex, `n / NORMAL_SCALE`, for smooth shading
    /// ([`QuantizedMesh::with_vertex_normals`](crate::front::quantized::QuantizedMesh::with_vertex_normals)),
    /// or empty.
    pub vertex_normals: &'a [[i16; 3]],
    /// Each vertex's texture coordinates, `q / UV_SCALE`
    /// ([`UV_SCALE`](crate::limits::UV_SCALE); OBJ's `vt`, `v` up), for
    /// texture mapping
    /// ([`QuantizedMesh::with_vertex_uvs`](crate::front::quantized::QuantizedMesh::with_vertex_uvs)),
    /// or empty.
    pub vertex_uvs: &'a [[i16; 2]],
}

impl QuantizedView<'_> {
    /// The position vertex `index` stands for, in `f64` (exact: a 16-bit
    /// integer times a `f32` fits a `f64`'s mantissa, up to the final sum).
    pub fn position64(&self, index: usize) -> [f64; 3] {
        let q = self.positions[index];
        let scale = f64::from(self.radius) / f64::from(POSITION_SCALE);
        core::array::from_fn(|k| f64::from(self.centre[k]) + f64::from(q[k]) * scale)
    }

    /// The position vertex `index` stands for, in `f32`.
    pub fn position(&self, index: usize) -> [f32; 3] {
        self.position64(index).map(|v| v as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: [[f32; 3]; 4] = [[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

    /// One normal per face or none: the stored ones are what
    /// `face_normals` computes, and a mesh without them has none.
    #[test]
    fn face_normals_are_one_per_face() {
        let mesh = StaticMesh::new(&P, &[0, 1, 2, 0, 2, 3], &[0, 3]).unwrap();
        assert_eq!(mesh.face_normal(0), None);
        let normals: [[f32; 3]; 2] = [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]];
        assert_eq!(face_normals(&mesh).collect::<std::vec::Vec<_>>(), normals);
        assert_eq!(
            mesh.with_face_normals(&normals[..1]).err(),
            Some(MeshError::BadNormals { face: None })
        );
        let with = mesh.with_face_normals(&normals).unwrap();
        assert_eq!(with.face_normal(1), Some([0.0, 0.0, 1.0]));
        assert_eq!(with.face_normal(2), None);
    }

    /// Stored normals are unit whatever the face's size, and zero for a
    /// face of no area.
    #[test]
    fn face_normals_are_unit() {
        let positions = [
            [0.0, 0.0, 0.0],
            [300.0, 0.0, 0.0],
            [0.0, 0.02, 0.0],
            [0.0, 0.0, 1e-9],
        ];
        let mesh = StaticMesh::new(&positions, &[0, 1, 2, 0, 1, 3, 0, 0, 1], &[0, 3, 6]).unwrap();
        let normals: std::vec::Vec<_> = face_normals(&mesh).collect();
        assert_eq!(normals[0], [0.0, 0.0, 1.0]);
        assert_eq!(normals[1], [0.0, -1.0, 0.0]);
        assert_eq!(normals[2], [0.0, 0.0, 0.0]);
    }

    #[test]
    fn validates() {
        assert!(StaticMesh::new(&P, &[0, 1, 2, 0, 2, 3], &[0, 3]).is_ok());
        assert_eq!(
            StaticMesh::new(&P, &[0, 1, 4], &[0]).err(),
            Some(MeshError::IndexOutOfRange { corner: 2 })
        );
        assert_eq!(
            StaticMesh::new(&P, &[0, 1, 2, 3], &[0, 2]).err(),
            Some(MeshError::BadFaceStarts { face: 0 })
        );
        assert_eq!(
            StaticMesh::new(&P, &[0, 1, 2], &[0, 5]).err(),
            Some(MeshError::BadFaceStarts { face: 0 })
        );
        let m = StaticMesh::new(&P, &[0, 1, 2, 0, 2, 3], &[0, 3]).unwrap();
        assert_eq!((m.face(0), m.face(1)), (&[0, 1, 2][..], &[0, 2, 3][..]));
        assert_eq!(m.face_count(), 2);
    }

    #[test]
    fn shared_planes_are_checked() {
        let m = StaticMesh::new(&P, &[0, 1, 2, 0, 2, 3], &[0, 3]).unwrap();
        let plane = |face: u32, v: u16| SharedPlane {
            face,
            vertices: [0, 1, v],
        };
        let good = [plane(0, 2), plane(1, 3)];
        assert_eq!(
            Mesh::shared_planes(&m.with_shared_planes(&good).unwrap()),
            &good
        );
        let bad = |list: &[SharedPlane]| m.with_shared_planes(list).err();
        let index = |index| Some(MeshError::BadSharedPlane { index });
        assert_eq!(bad(&[plane(1, 2), plane(0, 3)]), index(1));
        assert_eq!(bad(&[plane(0, 2), plane(0, 3)]), index(1));
        assert_eq!(bad(&[plane(2, 2)]), index(0));
        assert_eq!(bad(&[plane(0, 2), plane(1, 4)]), index(1));
        assert!(Mesh::shared_planes(&m).is_empty());
    }

    #[test]
    fn planarity() {
        let flat = StaticMesh::new(&P, &[0, 1, 2, 3], &[0]).unwrap();
        assert!(is_planar(&flat, 0));
        const BENT: [[f32; 3]; 4] = [[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.1], [0.0, 1.0, 0.0]];
        let bent = StaticMesh::new(&BENT, &[0, 1, 2, 3], &[0]).unwrap();
        assert!(!is_planar(&bent, 0));
        let tri = StaticMesh::new(&BENT, &[0, 1, 2], &[0]).unwrap();
        assert!(is_planar(&tri, 0));
        // Precomputed bits answer the same, and say what they are told.
        let both = StaticMesh::new(&BENT, &[0, 1, 2, 3, 0, 1, 2], &[0, 4]).unwrap();
        let bits: [u32; 1] = [planar_face_bits(&both).next().unwrap()];
        assert_eq!(bits[0], 0b10);
        let known = both.with_planar_faces(&bits).unwrap();
        assert!(!known.face_is_planar(0) && known.face_is_planar(1));
        let lying = both.with_planar_faces(&[0b01]).unwrap();
        assert!(lying.face_is_planar(0));
        assert_eq!(
            both.with_planar_faces(&[]).err(),
            Some(MeshError::BadPlanarity)
        );
    }

    /// The test holds at every scale a finite `f32` corner allows: a flat
    /// pentagon is planar and the same with one corner lifted by half its
    /// size is not, from sides of 2^-120 to corners near `f32::MAX` (in
    /// `f32` the powers overflowed from sides near 1e8 and the deviation
    /// vanished below 1e-8).
    #[test]
    fn planarity_at_every_scale() {
        const SHAPE: [[f32; 2]; 5] = [[0.0, 0.0], [1.0, 0.0], [1.5, 0.8], [0.6, 1.3], [-0.4, 0.7]];
        for exponent in (-120..=126).step_by(2) {
            let size = 2f32.powi(exponent);
            let corners = |lift: f32| {
                let mut p = SHAPE.map(|[x, y]| [x * size, y * size, 0.0]);
                p[2][2] = lift * size;
                p
            };
            let (flat, bent) = (corners(0.0), corners(0.5));
            let face = [0, 1, 2, 3, 4];
            let flat = StaticMesh::new(&flat, &face, &[0]).unwrap();
            let bent = StaticMesh::new(&bent, &face, &[0]).unwrap();
            assert!(is_planar(&flat, 0), "flat, size 2^{exponent}");
            assert!(!is_planar(&bent, 0), "bent, size 2^{exponent}");
        }
        // At the extremes of f32: corners up to f32::MAX apart, and
        // differences of the smallest subnormal.
        let huge = [
            [-f32::MAX, -f32::MAX, 0.0],
            [f32::MAX, -f32::MAX, 0.0],
            [f32::MAX, f32::MAX, f32::MAX],
            [-f32::MAX, f32::MAX, 0.0],
        ];
        let huge = StaticMesh::new(&huge, &[0, 1, 2, 3], &[0]).unwrap();
        assert!(!is_planar(&huge, 0));
        let tiny = f32::from_bits(1);
        let small = [
            [0.0; 3],
            [4.0 * tiny, 0.0, 0.0],
            [4.0 * tiny, 4.0 * tiny, 2.0 * tiny],
            [0.0, 4.0 * tiny, 0.0],
        ];
        let small = StaticMesh::new(&small, &[0, 1, 2, 3], &[0]).unwrap();
        assert!(!is_planar(&small, 0));
    }
}
