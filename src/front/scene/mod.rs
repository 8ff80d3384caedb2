//! World to screen: transforms a mesh, culls and clips its faces, projects
//! them, shades them and offers them to the renderer's tables. Only faces
//! that can be visible enter the tables, and only the vertices they use.
//! ([`draw_mesh_projected`] does the same with vertices projected
//! beforehand, for example on other threads.)
//!
//! For each face, in order:
//! 1. **Transform** each corner to clip space (`projection · view · model`),
//!    once per vertex per draw. A [`VertexCache`] remembers where each mesh
//!    vertex went in the vertex table; [`draw_mesh`] resets it, so one
//!    cache serves every mesh of a frame.
//! 2. **Non-finite** corners (NaN or infinity even in `f64`): the face is
//!    skipped and counted in [`DrawStats::non_finite`]. A corner whose `f32`
//!    transform overflows but whose `f64` one is finite is clipped instead.
//! 3. **Frustum**: a face whose corners all lie outside one frustum plane is
//!    culled ([`DrawStats::outside`]).
//! 4. **Clipping**: a face with a corner behind the near plane, beyond the
//!    far plane, or outside the clipping band ([`CLIP_BAND_PX`] pixels
//!    around the frame's centre) is clipped in homogeneous space, in `f64`
//!    ([`crate::front::clip`]): cut, never dropped or turned inside out, with the
//!    cut corners within 1/256 pixel of the exact ones, for faces within the
//!    clipper's range ([`CLIP_RANGE`]: up to `2^28` near distances for a
//!    perspective camera); a larger face that needs clipping is refused
//!    with [`Error::ClipRange`]. A vertex within the `f32` transform's error
//!    of the near or far plane is the clipper's too. Corners that needed no
//!    clipping keep their shared vertex, so clipped and unclipped
//!    neighbours stay watertight.
//! 5. The core leaves out faces of **zero area** and faces covering **no
//!    pixel sample** ([`DrawStats::degenerate`], [`DrawStats::off_screen`]).
//! 6. **Back faces** (with [`Cull::Back`]): faces whose projected corners
//!    run clockwise as seen by the viewer are culled. The test is exact, on
//!    the sub-pixel grid the core uses.
//! 7. **Shading**: the face's colour comes from a closure over [`FaceInfo`],
//!    for example [`Shading::color`](crate::front::shade::Shading::color).
//!
//! A face that is not planar ([`crate::front::mesh::is_planar`]) has no single plane. It goes
//! through these steps as the fan of triangles from its first corner, each
//! with the face's id. A planar quad that is strictly convex on screen and
//! shares no plane is judged and shaded once, as a face, and queued as its
//! two triangles ([`DrawStats::convex_quads`]): they cover exactly its
//! samples, and the scan's triangle path costs about a quarter of a
//! polygon's a row.
//!
//! No step needs a buffer per face: corners stream into the tables, so a
//! face may have up to [`MAX_FACE_CORNERS`] corners.
//!
//! Depth handed to the core is `z_ndc` mapped to `[0, 1]`. It is affine in
//! screen space, so the core's plane stepping is exact.
//!
//! **Precision of the `f32` transform.** A vertex that needs no clipping
//! is transformed and projected in `f32`: its error is a few units of
//! `2^-24` of the sum of its transform's absolute terms, divided by its
//! `w`. That is a fraction of a sub-pixel step when the model and camera
//! sit near the world's origin, but a camera far from the origin looking
//! at a mesh near it (translations that cancel) loses that precision, as
//! any `f32` pipeline does: keep the world's origin near what is drawn.
//!
//! Each job has its file: [`camera`] (the camera and the model matrix),
//! [`transform`] (a draw's matrices applied to each vertex, and
//! [`project_vertices`]), [`cache`] (where each vertex went in the vertex
//! table), [`cull`] and [`face_info`] (which faces are culled, and what
//! the shading sees of a face), [`clipping`] (the hand-off to the
//! clipper) and [`faces`] (the draw loop: each face culled, shaded and
//! offered to the tables, [`draw_mesh`]).
//!
//! [`CLIP_BAND_PX`]: crate::limits::CLIP_BAND_PX
//! [`Error::ClipRange`]: crate::Error::ClipRange
//! [`MAX_FACE_CORNERS`]: crate::limits::MAX_FACE_CORNERS

mod cache;
mod camera;
#[cfg(feature = "std")]
mod cap_cover;
mod clipping;
mod cull;
mod face_info;
mod faces;
mod transform;
mod vertex_info;

pub use cache::{CacheStorage, NoVertexCache, VertexCache};
pub use camera::{Camera, RADIUS_RANGE, bounding_sphere, reference_model, reference_model_around};
pub use clipping::CLIP_RANGE;
pub use cull::Cull;
pub use face_info::FaceInfo;
pub use faces::{DrawError, DrawStats, draw_mesh, draw_mesh_projected};
pub use transform::{ProjectedVertex, project_vertices};
pub use vertex_info::VertexInfo;

// What a painted renderer draws through.
pub(crate) use faces::{VertexValues, draw_mesh_with_values};

// What the host's banded renderer draws through.
#[cfg(feature = "std")]
pub(crate) use faces::draw_mesh_from;
#[cfg(feature = "std")]
pub(crate) use transform::{VertexSource, project_vertices_with};
