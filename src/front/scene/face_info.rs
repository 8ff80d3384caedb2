//! What a shading closure knows about a face ([`FaceInfo`]): its index and
//! side at once, its normal and view depth computed only when asked for.

use crate::front::fixed_point::FixedFrame;
use crate::front::geometry::{Mat4, Vec3, newell_normal};
use crate::front::mesh::Mesh;
use crate::front::scene::transform::{Frame, normalised_view_normal};
use crate::limits::NORMAL_SCALE;

/// What a shading closure knows about a face. The face's index and side
/// are at hand; its normal and depth are computed only when asked for
/// ([`Self::normal`], [`Self::view_depth`]), so a shader that colours by
/// face id pays nothing for them.
#[derive(Clone, Copy)]
pub struct FaceInfo<'a> {
    /// Index of the face in the mesh.
    pub face: u32,
    /// Whether the face's front (counter-clockwise side) faces the viewer.
    pub front: bool,
    geometry: FaceGeometry<'a>,
}

/// Where a [`FaceInfo`]'s normal and depth come from.
#[derive(Clone, Copy)]
enum FaceGeometry<'a> {
    /// From the mesh, on demand: the normal the mesh stores for the
    /// polygon drawn, the face's ([`Mesh::face_normal`]) when `corners` are
    /// all of its corners, a triangle's of a bent face's fan
    /// ([`Mesh::fan_normal`]) when they are that; else Newell's of
    /// `corners`.
    Mesh {
        mesh: &'a dyn Mesh,
        corners: &'a [u16],
        frame: &'a Frame,
        stored: Option<PackedNormal>,
    },
    /// Given.
    Known { normal: Vec3, view_depth: f32 },
    /// From a quantized mesh: the stored normal, rotated in integers.
    Quantized {
        mesh: &'a dyn Mesh,
        corners: &'a [u16],
        model_view: &'a Mat4,
        normal: [i16; 3],
        frame: &'a FixedFrame,
    },
}

impl core::fmt::Debug for FaceInfo<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FaceInfo")
            .field("face", &self.face)
            .field("front", &self.front)
            .field("normal", &self.normal())
            .field("view_depth", &self.view_depth())
            .finish()
    }
}

impl FaceInfo<'static> {
    /// A face whose normal (unit, view space) and view depth are known.
    pub const fn new(face: u32, front: bool, normal: Vec3, view_depth: f32) -> Self {
        Self {
            face,
            front,
            geometry: FaceGeometry::Known { normal, view_depth },
        }
    }
}

impl FaceInfo<'_> {
    /// Unit normal from the face's winding (Newell's, from its corners), in
    /// view space. For a quantized mesh it is [`Self::normal_q15`] as a
    /// `f32` vector.
    pub fn normal(&self) -> Vec3 {
        match self.geometry {
            FaceGeometry::Mesh {
                mesh,
                corners,
                frame,
                stored,
            } => match stored {
                Some(n) => frame.view_normal(n.unpack()),
                None => mesh_normal(mesh, corners, &frame.model_view),
            },
            FaceGeometry::Known { normal, .. } => normal,
            FaceGeometry::Quantized {
                mesh,
                corners,
                model_view,
                normal,
                frame,
            } => match frame.view_normal(normal) {
                Some(n) => normal_vector_i32(n),
                None => mesh_normal(mesh, corners, model_view),
            },
        }
    }

    /// [`Self::normal`]`.dot(v)`, the same value. For a whole face whose
    /// mesh stores its normal ([`Mesh::face_normal`]) the product is taken
    /// where the normal is turned, and only the product leaves: no vector
    /// passes through memory between the two (Lambert's colour of each
    /// face takes it).
    #[inline(always)]
    pub fn normal_dot(&self, v: Vec3) -> f32 {
        match self.geometry {
            FaceGeometry::Mesh {
                frame,
                stored: Some(n),
                ..
            } => frame.view_normal_dot(n.unpack(), v),
            _ => self.other_normal_dot(v),
        }
    }

    /// [`Self::normal_dot`] for faces with no stored normal, out of line.
    #[inline(never)]
    fn other_normal_dot(&self, v: Vec3) -> f32 {
        self.normal().dot(v)
    }

    /// The unit normal in view space in integers, units of `1/32767`, when
    /// the face comes from a [quantized mesh](crate::QuantizedMesh):
    /// its stored normal rotated by the model-view rotation, the same on
    /// every target and with no floating point. `None` for other faces.
    pub fn normal_q15(&self) -> Option<[i32; 3]> {
        match self.geometry {
            FaceGeometry::Quantized { normal, frame, .. } => frame.view_normal(normal),
            _ => None,
        }
    }

    /// View-space distance of the face's centroid along the view axis.
    pub fn view_depth(&self) -> f32 {
        match self.geometry {
            FaceGeometry::Mesh {
                mesh,
                corners,
                frame: Frame { model_view, .. },
                ..
            }
            | FaceGeometry::Quantized {
                mesh,
                corners,
                model_view,
                ..
            } => {
                let mut sum = Vec3::default();
                for &i in corners {
                    sum = sum + Vec3::from_array(mesh.position(usize::from(i)));
                }
                let centroid = sum * (1.0 / corners.len().max(1) as f32);
                let row = model_view.m[2];
                -(row[0] * centroid.x + row[1] * centroid.y + row[2] * centroid.z + row[3])
            }
            FaceGeometry::Known { view_depth, .. } => view_depth,
        }
    }
}

/// The view-space unit normal of a face from its corners (Newell's).
fn mesh_normal(mesh: &dyn Mesh, corners: &[u16], model_view: &Mat4) -> Vec3 {
    let n = newell_normal(corners.iter().map(|&i| mesh.position(usize::from(i))));
    normalised_view_normal(n, model_view)
}

/// An integer normal in units of `1/32767` as a `f32` vector.
pub(super) fn normal_vector_i32(n: [i32; 3]) -> Vec3 {
    let s = 1.0 / NORMAL_SCALE as f32;
    Vec3::new(n[0] as f32 * s, n[1] as f32 * s, n[2] as f32 * s)
}

/// A stored normal as a [`FaceInfo`] holds it: its bits in one 8-byte and
/// one 4-byte word, each written and read whole. (As `[f32; 3]` it was
/// written in other pieces than it was read, and a load that spans two
/// stores waits for both to reach the cache: on the desktop that stall
/// was a fifth of Lambert's time a face.)
#[cfg(not(target_arch = "arm"))]
#[derive(Debug, Clone, Copy)]
struct PackedNormal {
    xy: u64,
    z: u32,
}

/// On 32-bit Arm the plain array: a Cortex-M has no such stall, and the
/// Cortex-M0+ pays for 64-bit shifts (`cargo qemu`: 7,800 more
/// instructions a frame of the torus knot packed).
#[cfg(target_arch = "arm")]
#[derive(Debug, Clone, Copy)]
struct PackedNormal([f32; 3]);

#[cfg(target_arch = "arm")]
impl PackedNormal {
    /// Keeps `n`.
    #[inline(always)]
    fn pack(n: [f32; 3]) -> Self {
        Self(n)
    }

    /// The normal.
    #[inline(always)]
    fn unpack(self) -> Vec3 {
        Vec3::from_array(self.0)
    }
}

#[cfg(not(target_arch = "arm"))]
impl PackedNormal {
    /// Packs `[x, y, z]`.
    #[inline(always)]
    fn pack([x, y, z]: [f32; 3]) -> Self {
        Self {
            xy: u64::from(x.to_bits()) | u64::from(y.to_bits()) << 32,
            z: z.to_bits(),
        }
    }

    /// The normal again, bit for bit.
    #[inline(always)]
    fn unpack(self) -> Vec3 {
        Vec3::new(
            f32::from_bits(self.xy as u32),
            f32::from_bits((self.xy >> 32) as u32),
            f32::from_bits(self.z),
        )
    }
}

/// Which polygon of a face is drawn: what says where its normal comes
/// from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum FacePart {
    /// The face, all of its corners.
    Whole,
    /// Triangle `k` (corners `0, k, k + 1`, `k` from 1) of the fan of a
    /// face that is not planar.
    Fan(u16),
}

impl Frame {
    /// What the shader may ask about a face: `face` of `mesh`, drawn as the
    /// polygon of `corners`, which are `part` of the face.
    pub(super) fn face_info<'a, M: Mesh>(
        &'a self,
        mesh: &'a M,
        (face, part): (usize, FacePart),
        corners: &'a [u16],
        front: bool,
    ) -> FaceInfo<'a> {
        let model_view = &self.model_view;
        let geometry = match (&self.fixed, mesh.quantized()) {
            (Some(frame), Some(q)) => FaceGeometry::Quantized {
                mesh,
                corners,
                model_view,
                normal: q.normals.get(face).copied().unwrap_or_default(),
                frame,
            },
            _ => FaceGeometry::Mesh {
                mesh,
                corners,
                frame: self,
                stored: match part {
                    FacePart::Whole => mesh.face_normal(face),
                    FacePart::Fan(k) => mesh.fan_normal(face, usize::from(k)),
                }
                .map(PackedNormal::pack),
            },
        };
        FaceInfo {
            face: face as u32,
            front,
            geometry,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A packed normal comes back bit for bit: signs, zeros, the smallest
    /// and largest values, each in each place.
    #[test]
    fn a_packed_normal_unpacks_to_the_same_bits() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -0.6,
            f32::MIN_POSITIVE,
            1e-45,
            f32::MAX,
            -3.5e7,
        ];
        for &x in &values {
            for &y in &values {
                for &z in &values {
                    let n = PackedNormal::pack([x, y, z]).unpack();
                    let bits = |v: [f32; 3]| v.map(f32::to_bits);
                    assert_eq!(bits([n.x, n.y, n.z]), bits([x, y, z]));
                }
            }
        }
    }
}
