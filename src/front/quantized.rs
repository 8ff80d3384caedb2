//! Meshes quantized for the integer front end: positions as `i16` within
//! the mesh's bounding sphere and one unit normal per face, both made once
//! (by `cargo run --example obj2rust -- --quantized`, or a firmware's
//! build script) and kept in flash.
//!
//! A vertex `q` stands for the position `centre + radius · q / 32767`
//! ([`POSITION_SCALE`](crate::limits::POSITION_SCALE)), so every coordinate of a mesh inside its bounding
//! sphere is held to `radius / 65534`. A face normal `n` stands for the
//! unit vector `n / 32767` ([`NORMAL_SCALE`]), from Newell's method over
//! the face's original corners.
//!
//! [`draw_mesh`](crate::front::scene::draw_mesh) draws such a mesh with
//! integer arithmetic only (see [`crate::front::fixed_point`]): on a core
//! without an FPU it costs no floating point per vertex or per face, and
//! every target computes the same frame bit for bit.

use crate::front::backface::exact_normal;
use crate::front::mesh::{
    Mesh, MeshError, QuantizedView, SharedPlane, check_shared_planes, checked_face_of, is_planar,
};
use crate::limits::MAX_FACE_CORNERS;
use crate::limits::NORMAL_SCALE;
#[cfg(any(test, feature = "std"))]
use crate::limits::POSITION_SCALE;
use crate::limits::UV_SCALE;

/// Largest squared length a stored normal may have: `(32767 · (1 +
/// 2^-12))^2`, room for rounding each component of a unit vector. With it,
/// every rotated normal and every dot product with a unit light direction
/// in Q15 stays below `2^30 · (1 + 2^-11)`, far inside `i32`.
const NORMAL_LENGTH2_MAX: i64 = {
    let n = NORMAL_SCALE as i64;
    let len = n + n / 4096 + 1;
    len * len
};

/// A quantized mesh over borrowed slices: `'static` ones live in flash.
/// It is a [`Mesh`] like any other (positions read back in `f32`), and
/// [`Mesh::quantized`] lends the integer data to the integer front end.
#[derive(Debug, Clone, Copy)]
pub struct QuantizedMesh<'a> {
    view: QuantizedView<'a>,
    corners: &'a [u16],
    face_starts: &'a [u32],
    /// Bit `f` set when face `f` is planar.
    planar: &'a [u32],
    /// Faces with a shared plane, sorted by face.
    shared: &'a [SharedPlane],
}

impl<'a> QuantizedMesh<'a> {
    /// Checks the arrays and wraps them. `const`, so a static mesh is
    /// checked at compile time. `planar` holds one bit per face (bit
    /// `f % 32` of word `f / 32`), as
    /// [`planar_face_bits`](crate::front::mesh::planar_face_bits) makes.
    #[allow(clippy::too_many_arguments)]
    pub const fn new(
        positions: &'a [[i16; 3]],
        normals: &'a [[i16; 3]],
        corners: &'a [u16],
        face_starts: &'a [u32],
        planar: &'a [u32],
        centre: [f32; 3],
        radius: f32,
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
            if end - start > MAX_FACE_CORNERS {
                return Err(MeshError::FaceTooLarge { face: f });
            }
            f += 1;
        }
        if planar.len() < face_starts.len().div_ceil(32) {
            return Err(MeshError::BadPlanarity);
        }
        if normals.len() != face_starts.len() {
            return Err(MeshError::BadNormals { face: None });
        }
        let mut f = 0;
        while f < normals.len() {
            let [x, y, z] = normals[f];
            let (x, y, z) = (x as i64, y as i64, z as i64);
            if x * x + y * y + z * z > NORMAL_LENGTH2_MAX {
                return Err(MeshError::BadNormals { face: Some(f) });
            }
            f += 1;
        }
        let finite = centre[0].is_finite()
            && centre[1].is_finite()
            && centre[2].is_finite()
            && radius.is_finite();
        if !finite || radius <= 0.0 {
            return Err(MeshError::BadSphere);
        }
        Ok(Self {
            view: QuantizedView {
                positions,
                normals,
                centre,
                radius,
                exact_normals: &[],
                vertex_normals: &[],
                vertex_uvs: &[],
            },
            corners,
            face_starts,
            planar,
            shared: &[],
        })
    }

    /// The same mesh with faces that share planes ([`SharedPlane`]),
    /// sorted by face. `const`, so the list is checked at compile time.
    pub const fn with_shared_planes(self, shared: &'a [SharedPlane]) -> Result<Self, MeshError> {
        let vertices = self.view.positions.len();
        if let Err(e) = check_shared_planes(shared, self.face_starts.len(), vertices) {
            return Err(e);
        }
        Ok(Self { shared, ..self })
    }

    /// The exact normal `N = (q1 - q0) x (q2 - q0)` of a triangle of
    /// quantized corners, shifted right (by 0, 8, 16 or 17 bits, rounding
    /// down) until every component is below `2^14` in magnitude: what the
    /// integer front end's back-face test takes, and what
    /// [`Self::with_exact_normals`] checks each entry against. Zero when an
    /// edge component lies outside `[-2^15, 2^15)` (`N` is exact in `i32`
    /// only inside).
    pub const fn exact_normal(q0: [i16; 3], q1: [i16; 3], q2: [i16; 3]) -> [i16; 3] {
        exact_normal(q0, q1, q2)
    }

    /// The same mesh with a table of each face's [`Self::exact_normal`]
    /// (zero for a face that is not a triangle), which the integer front
    /// end's model-space back-face test reads instead of working them out
    /// each draw. `const`, so a flash mesh's table is checked entry by
    /// entry at compile time.
    pub const fn with_exact_normals(self, table: &'a [[i16; 3]]) -> Result<Self, MeshError> {
        if table.len() != self.face_starts.len() {
            return Err(MeshError::BadExactNormals { face: None });
        }
        let positions = self.view.positions;
        let mut f = 0;
        while f < table.len() {
            let start = self.face_starts[f] as usize;
            let end = if f + 1 < self.face_starts.len() {
                self.face_starts[f + 1] as usize
            } else {
                self.corners.len()
            };
            let expected = if end - start == 3 {
                let c = self.corners;
                exact_normal(
                    positions[c[start] as usize],
                    positions[c[start + 1] as usize],
                    positions[c[start + 2] as usize],
                )
            } else {
                [0; 3]
            };
            let got = table[f];
            if got[0] != expected[0] || got[1] != expected[1] || got[2] != expected[2] {
                return Err(MeshError::BadExactNormals { face: Some(f) });
            }
            f += 1;
        }
        let mut view = self.view;
        view.exact_normals = table;
        Ok(Self { view, ..self })
    }

    /// The same mesh with one unit normal per vertex, `n /
    /// NORMAL_SCALE` (each of length at most `NORMAL_SCALE · (1 + 2^-12)`,
    /// as face normals), for smooth shading: the integer front end rotates
    /// them with no floating point
    /// ([`VertexInfo::normal_q15`](crate::VertexInfo::normal_q15)).
    /// `const`, so a flash mesh's normals are checked at compile time.
    pub const fn with_vertex_normals(self, normals: &'a [[i16; 3]]) -> Result<Self, MeshError> {
        if normals.len() != self.view.positions.len() {
            return Err(MeshError::BadVertexAttributes);
        }
        let mut k = 0;
        while k < normals.len() {
            let [x, y, z] = normals[k];
            let (x, y, z) = (x as i64, y as i64, z as i64);
            if x * x + y * y + z * z > NORMAL_LENGTH2_MAX {
                return Err(MeshError::BadVertexAttributes);
            }
            k += 1;
        }
        let mut view = self.view;
        view.vertex_normals = normals;
        Ok(Self { view, ..self })
    }

    /// The same mesh with texture coordinates per vertex, `q /
    /// UV_SCALE` ([`UV_SCALE`](crate::limits::UV_SCALE), `v` up as OBJ's
    /// `vt`), for texture mapping: the integer front end passes them on
    /// with no floating point
    /// ([`VertexInfo::tex_coord`](crate::VertexInfo::tex_coord)).
    pub const fn with_vertex_uvs(self, uvs: &'a [[i16; 2]]) -> Result<Self, MeshError> {
        if uvs.len() != self.view.positions.len() {
            return Err(MeshError::BadVertexAttributes);
        }
        let mut view = self.view;
        view.vertex_uvs = uvs;
        Ok(Self { view, ..self })
    }

    /// The integer data.
    pub const fn view(&self) -> QuantizedView<'a> {
        self.view
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

impl Mesh for QuantizedMesh<'_> {
    fn vertex_count(&self) -> usize {
        self.view.positions.len()
    }

    fn position(&self, index: usize) -> [f32; 3] {
        self.view.position(index)
    }

    fn face_count(&self) -> usize {
        self.face_starts.len()
    }

    fn face(&self, index: usize) -> &[u16] {
        checked_face_of(self.corners, self.face_starts, index)
    }

    fn face_is_planar(&self, index: usize) -> bool {
        match self.planar.get(index / 32) {
            Some(word) => word & (1 << (index % 32)) != 0,
            None => is_planar(self, index),
        }
    }

    fn quantized(&self) -> Option<QuantizedView<'_>> {
        Some(self.view)
    }

    fn vertex_normal(&self, index: usize) -> Option<[f32; 3]> {
        let n = self.view.vertex_normals.get(index)?;
        Some(n.map(|c| f32::from(c) / NORMAL_SCALE as f32))
    }

    fn shared_planes(&self) -> &[SharedPlane] {
        self.shared
    }

    fn vertex_uv(&self, index: usize) -> Option<[f32; 2]> {
        let uv = self.view.vertex_uvs.get(index)?;
        Some(uv.map(|c| f32::from(c) / UV_SCALE as f32))
    }
}

/// A position quantized in a sphere: `round((p - centre) / radius ·
/// POSITION_SCALE)`, each component clamped to `±POSITION_SCALE` (a
/// position outside the sphere, which a bounding sphere never leaves out,
/// is pulled onto its box). (The host's quantizer writes meshes with it.)
#[cfg(any(test, feature = "std"))]
pub(crate) fn quantize_position(p: [f64; 3], centre: [f64; 3], radius: f64) -> [i16; 3] {
    let scale = f64::from(POSITION_SCALE) / radius;
    core::array::from_fn(|k| {
        let v = libm::round((p[k] - centre[k]) * scale);
        v.clamp(-f64::from(POSITION_SCALE), f64::from(POSITION_SCALE)) as i16
    })
}

/// A unit vector quantized to [`NORMAL_SCALE`] (normalised in `f64`
/// first); zero for a zero or non-finite vector.
#[cfg(any(test, feature = "std"))]
pub(crate) fn quantize_unit(n: [f64; 3]) -> [i16; 3] {
    let length = libm::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if !(length > 0.0 && length.is_finite()) {
        return [0; 3];
    }
    let s = f64::from(NORMAL_SCALE) / length;
    n.map(|v| libm::round(v * s) as i16)
}

/// A face's unit normal, quantized: Newell's normal of `corners` in `f64`,
/// normalised and rounded to [`NORMAL_SCALE`]; zero when the face has no
/// area.
#[cfg(any(test, feature = "std"))]
pub(crate) fn quantize_normal(corners: impl IntoIterator<Item = [f64; 3]> + Clone) -> [i16; 3] {
    let (mut a, mut b, mut c) = (0.0f64, 0.0f64, 0.0f64);
    let first = corners.clone().into_iter().next();
    let next = corners.clone().into_iter().skip(1).chain(first);
    for (p, q) in corners.into_iter().zip(next) {
        a += (p[1] - q[1]) * (p[2] + q[2]);
        b += (p[2] - q[2]) * (p[0] + q[0]);
        c += (p[0] - q[0]) * (p[1] + q[1]);
    }
    let length = libm::sqrt(a * a + b * b + c * c);
    if !(length > 0.0 && length.is_finite()) {
        return [0; 3];
    }
    let s = f64::from(NORMAL_SCALE) / length;
    [a, b, c].map(|v| libm::round(v * s) as i16)
}

#[cfg(test)]
mod tests {
    use super::*;

    const Q: [[i16; 3]; 4] = [[0, 0, 0], [32767, 0, 0], [32767, 32767, 0], [0, 32767, 0]];
    const N: [[i16; 3]; 2] = [[0, 0, 32767], [0, 0, 32767]];

    #[test]
    fn exact_normal_tables_are_checked_entry_by_entry() {
        // A triangle with short edges, a quad, a triangle with a long edge.
        let q = [
            [0, 0, 0],
            [300, 0, 0],
            [0, 200, 0],
            [300, 200, 0],
            [-20000, 0, 0],
            [20000, 5, 0],
        ];
        let n = [[0, 0, 32767]; 3];
        let corners = [0, 1, 2, 0, 1, 3, 2, 4, 5, 0];
        let m = QuantizedMesh::new(&q, &n, &corners, &[0, 3, 7], &[0b111], [0.0; 3], 1.0).unwrap();
        // (300, 0, 0) x (0, 200, 0) = (0, 0, 60000), shifted by 8: 234.
        let good = [[0, 0, 234], [0; 3], [0; 3]];
        let with = m.with_exact_normals(&good).unwrap();
        assert_eq!(with.view().exact_normals, &good);
        for (table, face) in [
            (&[[0, 0, 235], [0; 3], [0; 3]][..], Some(0)),
            (&[[0, 0, 234], [0, 0, 1], [0; 3]][..], Some(1)),
            (&[[0, 0, 234], [0; 3], [0, 0, -1]][..], Some(2)),
            (&[[0, 0, 234], [0; 3]][..], None),
        ] {
            assert_eq!(
                m.with_exact_normals(table).err(),
                Some(MeshError::BadExactNormals { face })
            );
        }
        assert!(m.view().exact_normals.is_empty());
    }

    #[test]
    fn validates_and_reads_back() {
        let m = QuantizedMesh::new(
            &Q,
            &N,
            &[0, 1, 2, 0, 2, 3],
            &[0, 3],
            &[0b11],
            [1.0, 2.0, 3.0],
            2.0,
        )
        .unwrap();
        assert_eq!(m.position(2), [3.0, 4.0, 3.0]);
        assert_eq!(m.face(1), &[0, 2, 3]);
        assert!(m.quantized().is_some());
        let bad = |r: Result<QuantizedMesh<'static>, MeshError>| r.err();
        assert_eq!(
            bad(QuantizedMesh::new(
                &Q,
                &N[..1],
                &[0, 1, 2, 0, 2, 3],
                &[0, 3],
                &[3],
                [0.0; 3],
                1.0
            )),
            Some(MeshError::BadNormals { face: None })
        );
        assert_eq!(
            bad(QuantizedMesh::new(
                &Q,
                &[[0, 0, 32767], [32767, 32767, 0]],
                &[0, 1, 2, 0, 2, 3],
                &[0, 3],
                &[3],
                [0.0; 3],
                1.0
            )),
            Some(MeshError::BadNormals { face: Some(1) })
        );
        assert_eq!(
            bad(QuantizedMesh::new(
                &Q,
                &N,
                &[0, 1, 2, 0, 2, 3],
                &[0, 3],
                &[3],
                [0.0; 3],
                0.0
            )),
            Some(MeshError::BadSphere)
        );
        assert_eq!(
            bad(QuantizedMesh::new(
                &Q,
                &N,
                &[0, 1, 2, 0, 2, 3],
                &[0, 3],
                &[3],
                [f32::NAN, 0.0, 0.0],
                1.0
            )),
            Some(MeshError::BadSphere)
        );
        assert_eq!(
            bad(QuantizedMesh::new(
                &Q,
                &N,
                &[0, 1, 2, 0, 2, 3],
                &[0, 3],
                &[],
                [0.0; 3],
                1.0
            )),
            Some(MeshError::BadPlanarity)
        );
        assert_eq!(
            bad(QuantizedMesh::new(
                &Q,
                &N,
                &[0, 1, 9],
                &[0],
                &[1],
                [0.0; 3],
                1.0
            )),
            Some(MeshError::IndexOutOfRange { corner: 2 })
        );
    }

    #[test]
    fn quantization_round_trips_within_half_a_step() {
        let (c, r) = ([0.5, -1.0, 2.0], 3.0);
        for p in [
            [0.5, -1.0, 2.0],
            [3.5, -1.0, 2.0],
            [-2.0, 1.0, 0.25],
            [0.123, 0.456, 0.789],
        ] {
            let q = quantize_position(p, c, r);
            for k in 0..3 {
                let back = c[k] + f64::from(q[k]) * r / f64::from(POSITION_SCALE);
                assert!((back - p[k]).abs() <= 0.5 * r / f64::from(POSITION_SCALE) + 1e-12);
            }
        }
        // Outside the sphere: clamped, never wrapped.
        assert_eq!(
            quantize_position([10.0, -10.0, 0.0], [0.0; 3], 1.0),
            [32767, -32767, 0]
        );
    }

    #[test]
    fn normals_are_unit_and_fit() {
        let n = quantize_normal([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(n, [0, 0, 32767]);
        let n = quantize_normal([[0.0, 0.0, 0.0], [1.0, 1.0, 0.3], [-0.2, 1.0, 0.7]]);
        let len2: i64 = n.iter().map(|&v| i64::from(v) * i64::from(v)).sum();
        assert!(((32767 - 2) * (32767 - 2)..=NORMAL_LENGTH2_MAX).contains(&len2));
        assert_eq!(
            quantize_normal([[1.0, 1.0, 1.0], [2.0, 2.0, 2.0], [3.0, 3.0, 3.0]]),
            [0; 3]
        );
    }
}
