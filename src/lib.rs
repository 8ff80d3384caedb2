//! # zline
//!
//! A `no_std`, allocation-free **scanline z-buffer** rasteriser for small
//! framebuffers. It keeps one row of fixed-point depth and one row of
//! colour, never a frame, and hands each finished row to any
//! embedded-graphics [`DrawTarget`](embedded_graphics_core::draw_target::DrawTarget).
//!
//! The pipeline, one module a stage:
//! [`fixed`] (number formats) → [`vertex`] (screen-space input) →
//! [`scanline`] (polygon and edge tables, active lists, row buffers) →
//! [`sink`] (finished rows to a display). [`depth`] holds the depth
//! formats the row can store.
//!
//! ```
//! use embedded_graphics::mock_display::MockDisplay;
//! use embedded_graphics::pixelcolor::BinaryColor;
//! use zline::{Depth16, DrawTargetSink, Renderer, ScreenVertex};
//!
//! // 16x16 frame: up to 8 vertices, 2 polygons, 8 edges (corners), 2
//! // active polygons, no pooled active edges (triangles need none).
//! let mut renderer: Renderer<BinaryColor, Depth16, 16, 8, 2, 8, 2, 0> =
//!     Renderer::new(16, BinaryColor::Off).unwrap();
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

pub mod clip;
pub mod depth;
pub mod error;
pub mod fixed;
pub mod geometry;
pub mod mesh;
#[cfg(feature = "std")]
pub mod methods;
pub mod obj;
pub mod scanline;
pub mod scene;
pub mod shade;
pub mod sink;
pub mod vertex;

pub use depth::{Depth16, Depth24, DepthFormat};
pub use error::{Error, RenderError};
pub use scanline::{Admission, FrameStats, PolygonTables, Renderer};
pub use sink::{Crc32Sink, DrawTargetSink, FnSink, RowSink};
pub use vertex::{Outline, OutlineBuilder, ScreenRect, ScreenVertex};

/// Compiles the README's code examples as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
