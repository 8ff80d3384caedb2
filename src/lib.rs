//! # zline
//!
//! A `no_std`, allocation-free **scanline z-buffer** rasteriser for small
//! framebuffers. It keeps one row of fixed-point depth and one row of
//! colour, never a frame, and hands each finished row to any
//! embedded-graphics [`DrawTarget`](embedded_graphics_core::draw_target::DrawTarget)
//! (through [`DrawTargetSink`]), or to a [`RowSink`] of your own, such as
//! a display driver's DMA buffer.
//!
//! Its storage is fixed when it is built, sized from the scene (see
//! [`Capacities`]); anything that does not fit is an [`Error`], never a
//! panic and never silently dropped.
//!
//! ## What is where
//!
//! | you want to | use |
//! |---|---|
//! | draw a mesh | [`Renderer`] (tables and a scanner, sized by one [`Capacities`] value through [`renderer_type!`]; on a desktop `HostRenderer::for_mesh`, sized from the mesh), [`draw_mesh`] with a [`Camera`] and a model matrix ([`reference_model`], [`Mat4`]), then [`Renderer::render`] into a [`RowSink`] |
//! | give a mesh | [`StaticMesh`] (slices, for flash), [`QuantizedMesh`] (`i16` positions, drawn by the integer front end), the OBJ reader's [`obj::ObjMesh`], or your own [`Mesh`]; on a desktop [`host::HostMesh`] |
//! | colour faces | a closure over [`FaceInfo`], or [`Shading`] (flat, [`Lambert`], depth grey, face id) |
//! | send rows | [`DrawTargetSink`] (any embedded-graphics `DrawTarget`), [`FnSink`] (a closure), [`FrameBufferSink`] (a frame in memory, drawn in place), [`Crc32Sink`] (a checksum) |
//! | screen polygons of your own | [`Renderer::push_polygon_vertices`] with [`ScreenVertex`]es, or [`Renderer::push_vertex`] and [`Renderer::push_polygon`] |
//! | several scanners over one scene (threads, cores) | [`Tables::prepare`] and [`scan`] a band of rows each with a [`Scanner`]; on a desktop [`host::BandedRenderer`] |
//! | the numbers of the sub-pixel grid, depth and limits | [`limits`] |
//! | a renderer of your own over the same tables | [`inspect`]; the z-buffer methods on them, [`zbuffer`] |
//!
//! How it works (the polygon and edge tables bucketed by row, the active
//! tables, depth stepped from each polygon's screen-space plane) is in the
//! book, `docs/` in the repository.
//!
//! ```
//! use embedded_graphics::mock_display::MockDisplay;
//! use embedded_graphics::pixelcolor::BinaryColor;
//! use zline::{Capacities, Depth16, DrawTargetSink, ScreenVertex};
//!
//! // A 16x16 frame; room for 8 vertices, 2 polygons of 8 corners in all,
//! // 2 polygons on one row, no pooled edges (triangles need none) and no
//! // mesh (screen polygons only).
//! const CAPS: Capacities = Capacities {
//!     width: 16, vertices: 8, polygons: 2, corners: 8,
//!     active_polygons: 2, pooled_edges: 0, mesh_vertices: 0,
//! };
//! type Zr = zline::renderer_type!(BinaryColor, Depth16, CAPS);
//! let mut renderer = Zr::new(16, 16, BinaryColor::Off).unwrap();
//! let v = |x: f32, y: f32, z: f32| ScreenVertex::from_f32(x, y, z).unwrap();
//! renderer
//!     .push_polygon_vertices(&[v(2.0, 2.0, 0.5), v(14.0, 2.0, 0.5), v(8.0, 14.0, 0.5)], BinaryColor::On)
//!     .unwrap();
//! let mut display = MockDisplay::new();
//! let stats = renderer.render(&mut DrawTargetSink::new(&mut display)).unwrap();
//! assert_eq!(stats.polygons, 1);
//! assert_eq!(display.get_pixel(embedded_graphics::prelude::Point::new(8, 8)), Some(BinaryColor::On));
//! ```
#![cfg_attr(feature = "std", doc = "[`host::HostMesh`]: host::HostMesh")]
#![cfg_attr(
    feature = "std",
    doc = "[`host::BandedRenderer`]: host::BandedRenderer"
)]
#![cfg_attr(
    not(feature = "std"),
    doc = "[`host::HostMesh`]: https://docs.rs/zline/latest/zline/host/struct.HostMesh.html"
)]
#![cfg_attr(
    not(feature = "std"),
    doc = "[`host::BandedRenderer`]: https://docs.rs/zline/latest/zline/host/struct.BandedRenderer.html"
)]
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

#[cfg(feature = "std")]
extern crate std;

mod arith;
mod error;
mod front;
pub mod limits;
pub mod paint;
mod raster;
mod renderer;
mod sink;

#[cfg(feature = "std")]
pub mod host;
pub use front::obj;
pub use raster::inspect;
#[cfg(feature = "zbuffer")]
pub use raster::zbuffer;

pub use error::{Error, RenderError};
pub use front::clip::ClipValue;
pub use front::closed_hull::ClosedHull;
pub use front::face_plane::FacePlane;
pub use front::geometry::{Mat4, Vec3, Vec4, newell_normal, radians};
pub use front::mesh::{
    Mesh, MeshArrays, MeshError, PLANARITY_TOLERANCE, QuantizedView, SharedPlane, StaticMesh,
    face_normals, face_planes, fan_normals, is_planar, planar_face_bits,
};
pub use front::quantized::QuantizedMesh;
pub use front::scene::{
    CLIP_RANGE, CacheStorage, Camera, Cull, DrawError, DrawStats, FaceInfo, NoVertexCache,
    ProjectedVertex, RADIUS_RANGE, VertexCache, VertexInfo, bounding_sphere, draw_mesh,
    draw_mesh_projected, project_vertices, reference_model, reference_model_around,
};
pub use front::shade::{Lambert, Shading, face_id_color};
pub use front::triangles::Triangles;
pub use raster::paint::{NO_SLOT, RowPainter, scan_painted};
pub use raster::{
    ActiveEdge, ActivePolygon, Admission, Capacities, Depth16, Depth24, DepthFormat, EdgeEntry,
    FrameStats, MeshCounts, Outline, OutlineBuilder, PolygonEntry, PolygonTables, Prepared,
    ScanArrays, ScanParts, ScanStorage, Scanner, ScreenRect, ScreenVertex, SmallActive,
    TableArrays, TableParts, TablePartsRef, TableStorage, Tables, scan,
};
pub use renderer::Renderer;
pub use sink::{Crc32Sink, DrawTargetSink, FnSink, FrameBufferSink, LentRow, RowSink, RowSpan};

/// Compiles the README's code examples as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
