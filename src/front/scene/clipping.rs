//! The hand-off to the clipper: whether a face that needs clipping is
//! wholly outside the frustum, clipped, or beyond the clipper's range
//! ([`CLIP_RANGE`]), and its corners streamed through the guard-band
//! clipper in `f64` and projected.

// Without the `clipping` feature only `CLIP_RANGE` is left.

#[cfg(feature = "clipping")]
use crate::error::Error;
#[cfg(feature = "clipping")]
use crate::front::clip::{self, ClipPoint, ClipValue, ClipVertex, Clipper};
#[cfg(feature = "clipping")]
use crate::front::mesh::Mesh;
#[cfg(feature = "clipping")]
use crate::front::scene::cache::NEEDS_CLIP;
#[cfg(feature = "clipping")]
use crate::front::scene::transform::Frame;
#[cfg(feature = "clipping")]
use crate::raster::vertex::ScreenVertex;

/// How far a face that needs clipping may reach, relative to the view
/// frustum's nearest point: its clip-space size (the largest sum of the
/// absolute terms of a corner's transform, `|projection| · |view| ·
/// |model| · |p|`, over its corners and coordinates) at most `2^28` times
/// the smallest clip-space `w` in the frustum (for a perspective camera,
/// the near distance). Within it, the `f64` transform and clipper place
/// every corner a cut makes within 1/256 pixel of the exact cut of the
/// given `f32` positions and matrices, and its depth within `2^-20`
/// (`tests/clipping.rs` checks both against a reference in twice `f64`'s
/// precision, over the whole `f32` range). A face beyond it is refused
/// with [`Error::ClipRange`]; a face wholly outside one frustum plane is
/// culled first, whatever its size.
///
/// (The `f64` arithmetic's error on a corner is a few units of `2^-53`
/// times that size, and it is divided by `w` when projected: at `2^28`
/// that is below `2^-22` of the frame's half-size, and of the depth
/// range.)
pub const CLIP_RANGE: f64 = (1u64 << 28) as f64;

#[cfg(feature = "clipping")]
/// A bound on the `f64` transform's error on a plane's distance to a
/// corner, per unit of the corner's clip-space size: the product of the
/// three matrices (two products of four terms) and the transform (four
/// more) err by at most about 12 units of `2^-53` of the size on each
/// coordinate, and a frustum plane sums two coordinates. `2^-46` is eight
/// times that.
const CLIP_ERROR: f64 = 1.0 / (1u64 << 46) as f64;

#[cfg(feature = "clipping")]
impl Frame {
    /// Whether a face that needs clipping lies wholly outside one frustum
    /// plane beyond doubt, whatever its size: each corner farther outside
    /// it than the arithmetic's error (a few units of 2^-53 of the corner's
    /// size on each coordinate; a frustum plane adds two of them), or each
    /// corner at or behind the eye (`w <= 0`) beyond doubt. Otherwise it
    /// is clipped, if it is within the clipper's range ([`CLIP_RANGE`]),
    /// and refused with [`Error::ClipRange`] if not (or if its size is not
    /// finite, or the projection is singular). Out of line: the rare
    /// path's, kept out of the common path's code.
    #[inline(never)]
    pub(super) fn wholly_outside<M: Mesh + ?Sized>(
        &self,
        mesh: &M,
        corners: &[u16],
    ) -> Result<bool, Error> {
        let (mut outside, mut size) = (u32::MAX, 0.0f64);
        for &index in corners {
            let p = self.clip_position64(mesh, usize::from(index));
            let corner_size = self.clip_size64(mesh, usize::from(index));
            let margin = CLIP_ERROR * corner_size;
            // Bit 6: not in front of the eye (w <= 0) for certain.
            let behind = if p.w <= -margin { 1 << 6 } else { 0 };
            outside &= clip::outside_mask(p, &clip::FRUSTUM, margin) | behind;
            size = size.max(corner_size);
        }
        if outside != 0 {
            return Ok(true);
        }
        // A singular projection has no frustum (its smallest w is 0): no
        // face can be clipped.
        let w_near = self.clip64().w_near;
        let within = w_near > 0.0 && size <= CLIP_RANGE * w_near;
        if within {
            Ok(false)
        } else {
            Err(Error::ClipRange)
        }
    }

    /// The clip-space size of mesh vertex `index`: the largest sum of the
    /// absolute terms of its transform, over the four coordinates (see
    /// [`CLIP_RANGE`]).
    fn clip_size64<M: Mesh + ?Sized>(&self, mesh: &M, index: usize) -> f64 {
        let p = mesh.position(index).map(|c| f64::from(c).abs());
        let row = |r: [f64; 4]| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3];
        let m = &self.clip64().mvp_abs;
        row(m[0]).max(row(m[1])).max(row(m[2])).max(row(m[3]))
    }

    /// [`Self::project`] in `f64`, for the corners clipping made.
    pub(super) fn project64(&self, p: ClipPoint) -> Option<ScreenVertex> {
        let inv_w = 1.0 / p.w;
        let x = (p.x * inv_w + 1.0) * 0.5 * f64::from(self.width);
        let y = (1.0 - p.y * inv_w) * 0.5 * f64::from(self.height);
        let z = ((p.z * inv_w + 1.0) * 0.5).clamp(0.0, 1.0);
        ScreenVertex::from_f64(x, y, z).ok()
    }

    /// The guard planes in `f64`.
    fn guard_planes(&self) -> [[f64; 4]; 6] {
        clip::guard_planes(f64::from(self.guard.0), f64::from(self.guard.1))
    }
}

#[cfg(feature = "clipping")]
/// Runs a face's corners through the guard-band clipper into `out`, each
/// with its value from `value` (of the mesh vertex's index; `()` for
/// none). Corners the cache holds as stored vertices go in tagged with
/// their index and known to be inside.
pub(super) fn clip_face<M: Mesh + ?Sized, S: ClipValue>(
    frame: &Frame,
    mesh: &M,
    slots: &[u16],
    corners: &[u16],
    mut value: impl FnMut(usize) -> S,
    out: &mut dyn FnMut(ClipVertex<S>) -> Result<(), Error>,
) -> Result<(), Error> {
    let mut clipper = Clipper::<6, S>::new(frame.guard_planes());
    for &index in corners {
        let index = usize::from(index);
        let tag = match slots[index] {
            NEEDS_CLIP => None,
            id => Some(id),
        };
        let point = frame.clip_position64(mesh, index);
        let corner = ClipVertex::with_value(point, tag, tag.is_some(), value(index));
        clipper.push(corner, out)?;
    }
    clipper.finish(out)
}
