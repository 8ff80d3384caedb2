//! The front end: meshes in world space to screen polygons in the core's
//! tables.
//!
//! * [`mesh`]: the [`Mesh`](mesh::Mesh) trait over one array layout, flash
//!   meshes ([`StaticMesh`](mesh::StaticMesh)), the planarity rule.
//! * [`obj`]: the `no_std` Wavefront OBJ reader.
//! * [`geometry`]: vectors, matrices, the camera transforms, Newell's
//!   normal.
//! * [`clip`]: streaming homogeneous clipping in `f64`.
//! * [`scene`]: [`draw_mesh`](scene::draw_mesh): transform, cull, clip,
//!   project, shade, and offer each face to the tables.
//! * [`shade`]: one colour per face, in `f32` or, for quantized meshes,
//!   in integers, or per vertex ([`rgb8p8`]: colours with 8 bits below
//!   the 8-bit step).
//! * [`quantized`]: meshes quantized for the integer front end (`i16`
//!   positions, unit face normals), kept in flash.
//! * [`fixed_point`]: the integer front end: transform, clip tests,
//!   projection and normals without floating point.
//! * [`backface`]: the integer front end's back-face test in model space,
//!   before a triangle's corners are transformed.
//! * [`face_plane`]: the same test for `f32` meshes, from each face's
//!   plane found once per mesh.

pub(crate) mod backface;
pub(crate) mod clip;
pub(crate) mod clip_w;
pub(crate) mod closed_hull;
pub(crate) mod face_plane;
pub(crate) mod fixed_point;
pub(crate) mod geometry;
pub(crate) mod mesh;
pub mod obj;
pub(crate) mod quantized;
pub(crate) mod rgb8p8;
pub(crate) mod scene;
pub(crate) mod shade;
pub(crate) mod tex_coord;
pub(crate) mod triangles;
pub(crate) mod trig;
