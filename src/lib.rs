//! # zline
//!
//! A `no_std`, allocation-free **scanline z-buffer** rasteriser for small
//! framebuffers. It keeps one row of fixed-point depth and one row of
//! colour, never a frame, and hands each finished row to any
//! embedded-graphics [`DrawTarget`](embedded_graphics_core::draw_target::DrawTarget).
//!
//! The pipeline, one module a stage (tiny-skia's shape: geometry, then
//! edges, then scan conversion, then a blitter that receives finished
//! rows):
//!
//! | stage | module | what it does |
//! |---|---|---|
//! | front end | [`front`] | world-space meshes to screen polygons in the core's tables |
//! | | [`front::mesh`] | the [`Mesh`](front::mesh::Mesh) trait over one array layout; [`StaticMesh`](front::mesh::StaticMesh) for flash; the planarity rule |
//! | | [`front::obj`] | the `no_std` OBJ reader, with line numbers in every error |
//! | | [`front::geometry`] | vectors, matrices, camera transforms, Newell's normal |
//! | | [`front::clip`] | streaming homogeneous clipping in `f64` |
//! | | [`front::scene`] | [`draw_mesh`](front::scene::draw_mesh): transform, cull, clip, project, shade, offer each face to the tables |
//! | | [`front::shade`] | one colour per face: flat, Lambert, depth grey, face id |
//! | | [`front::quantized`] | meshes quantized for the integer front end: `i16` positions, unit and exact face normals, in flash |
//! | | [`front::fixed_point`] | the integer front end: transform, clip tests, projection and normals without floating point |
//! | | [`front::backface`] | the integer front end's back-face test in model space, before a triangle's corners are transformed |
//! | core | [`raster`] | the scanline z-buffer: screen polygons in, finished rows out |
//! | | [`raster::fixed`] | the sub-pixel grid, input depth, guard band, exact rounding and division |
//! | | [`raster::vertex`] | [`ScreenVertex`], the outline and bounding rectangle a polygon is judged by, the fill rule's sample test |
//! | | [`raster::tables`] | the scene-sized tables (vertices, polygons, corners, edge table), sorted by first row in O(n) |
//! | | [`raster::scan`](mod@raster::scan) | the row-sized [`Scanner`] (active polygon table, active edge pool, the rows) and [`scan()`] |
//! | | [`raster::depth`] | the depth formats a row stores ([`Depth16`], [`Depth24`]) |
//! | | [`raster::zbuffer`] | the z-buffer of K rows (a band, or the whole frame) on the same tables, formats and fill rule |
//! | | [`raster::capacities`] | [`Capacities`] by name, and the [`Renderer`] bundle of tables and scanner |
//! | | `raster::plane`, `raster::edge`, `raster::active`, `raster::slots`, `raster::lanes`, `raster::wide` (internal) | the plane set-up, the exact edge DDA, the active tables, the capacity-erased lists they live in (the active polygon table's with an order array of slots), the branch-free span blocks for hosts, exact 32x32→64 products for cores without a long multiply |
//! | blitter | [`sink`] | finished rows to a `DrawTarget` ([`DrawTargetSink`]), a closure ([`FnSink`]) or a checksum ([`Crc32Sink`]); or drawn straight into a sink's own buffers ([`LentRow`]), a frame buffer's rows for one ([`FrameBufferSink`]) |
//! | | [`error`] | what can go wrong, by name |
//! | desktop (feature `std`) | [`host`] | what a desktop program needs: storage sized from the mesh, a frame in bands on threads |
//! | | `host::host_mesh`, `host::storage` | meshes and core storage in `Vec`s ([`host::HostMesh`], [`host::TableVecs`], [`host::ScanVecs`]) |
//! | | `host::bands` | one frame in bands of rows on several threads, each band's tables built from the whole scene ([`host::BandedRenderer`], [`host::BandTables`]) |
//! | | [`host::coplanar`] | the faces of a mesh that overlap in one plane, to share it ([`front::mesh::SharedPlane`]) |
//! | | `host::quantize` | a mesh quantized for the integer front end, in `Vec`s ([`host::QuantizedHostMesh`]) |
//!
//! ```
//! use embedded_graphics::mock_display::MockDisplay;
//! use embedded_graphics::pixelcolor::BinaryColor;
//! use zline::raster::{Renderer, ScanArrays, TableArrays};
//! use zline::{Depth16, DrawTargetSink, ScreenVertex};
//!
//! // A 16x16 frame. Tables: 8 vertices, 2 polygons, 8 corners. Scanner:
//! // rows of 16 pixels, 2 active polygons, no pooled edges (triangles need
//! // none).
//! type Zr = Renderer<TableArrays<BinaryColor, 8, 2, 8>, ScanArrays<BinaryColor, Depth16, 16, 2, 0>>;
//! let mut renderer = Zr::with_size(16, 16, BinaryColor::Off).unwrap();
//! let v = |x: f32, y: f32, z: f32| ScreenVertex::from_f32(x, y, z).unwrap();
//! renderer
//!     .push_polygon_vertices(&[v(2.0, 2.0, 0.5), v(14.0, 2.0, 0.5), v(8.0, 14.0, 0.5)], BinaryColor::On)
//!     .unwrap();
//! let mut display = MockDisplay::new();
//! let stats = renderer.render(&mut DrawTargetSink::new(&mut display)).unwrap();
//! assert_eq!(stats.polygons, 1);
//! assert_eq!(display.get_pixel(embedded_graphics::prelude::Point::new(8, 8)), Some(BinaryColor::On));
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

#[cfg(feature = "std")]
extern crate std;

pub mod error;
pub mod front;
#[cfg(feature = "std")]
pub mod host;
pub mod raster;
pub mod sink;

pub use error::{Error, RenderError};
pub use raster::depth::{Depth16, Depth24, DepthFormat};
pub use raster::vertex::ScreenVertex;
pub use raster::{
    Admission, Capacities, FrameStats, PolygonTables, Renderer, ScanArrays, ScanStorage, Scanner,
    TableArrays, TableStorage, Tables, scan,
};
pub use sink::{Crc32Sink, DrawTargetSink, FnSink, FrameBufferSink, LentRow, RowSink};

/// Compiles the README's code examples as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
