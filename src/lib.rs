//! # zline
//!
//! A `no_std`, allocation-free **scanline z-buffer** rasteriser for small
//! framebuffers. It keeps one row of fixed-point depth and one row of
//! colour, never a frame, and hands each finished row to any
//! embedded-graphics [`DrawTarget`](embedded_graphics_core::draw_target::DrawTarget).
//!
//! The pipeline, one module a stage:
//!
//! | stage | module | what it does |
//! |---|---|---|
//! | front end | [`front`] | meshes ([`front::mesh`], [`front::obj`]) in world space through the camera ([`front::geometry`]), culled, clipped ([`front::clip`]), projected and shaded ([`front::shade`]) into screen polygons ([`front::scene`]) |
//! | core | [`raster`] | screen polygons ([`raster::vertex`], [`raster::fixed`]) into the scene-sized tables ([`raster::tables`]), scanned row by row ([`raster::scan`]) into one depth row ([`raster::depth`]) and one colour row |
//! | blitter | [`sink`] | finished rows to a `DrawTarget`, a closure or a checksum |
//! | | [`error`] | what can go wrong, by name |
//! | host side (feature `std`) | [`methods`] | the comparison renderers and checks: the float64 reference, the exact rational oracle, the accuracy comparison, the scanline core on `Vec`s |
//! | | [`host`] | the tools' support: meshes in `Vec`s and `Vec`-backed storage, procedural shapes, the mesh-to-Rust writer, command-line helpers, the fuzzers' checks |
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
#[cfg(feature = "std")]
pub mod methods;
pub mod raster;
pub mod sink;

pub use error::{Error, RenderError};
pub use raster::depth::{Depth16, Depth24, DepthFormat};
pub use raster::vertex::ScreenVertex;
pub use raster::{
    Admission, Capacities, FrameStats, PolygonTables, Renderer, ScanArrays, ScanStorage, Scanner,
    TableArrays, TableStorage, Tables, scan,
};
pub use sink::{Crc32Sink, DrawTargetSink, FnSink, RowSink};

/// Compiles the README's code examples as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
