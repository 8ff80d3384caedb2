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
//! * [`shade`]: one colour per face.

pub mod clip;
pub mod geometry;
pub mod mesh;
pub mod obj;
pub mod scene;
pub mod shade;
