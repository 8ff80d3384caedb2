//! The scene-sized tables of the scanline z-buffer: the vertex table, the
//! polygon table (PT) with its corner list, and the edge table (ET).
//!
//! Polygons are offered one by one ([`Tables::push_polygon`],
//! [`Tables::offer_polygon`], or corner by corner); those that can cover no
//! pixel sample are counted and left out. [`Tables::prepare`] then buckets
//! the PT by first row with a stable radix sort (O(n), no comparisons) and
//! builds the ET, and hands out a [`Prepared`] view that any number of
//! [`Scanner`](super::Scanner)s may scan at once.
//!
//! Triangles, nearly every polygon of a mesh, need no ET entry: a triangle
//! switches from its upper to its lower short edge by itself (see
//! `stepping.rs`). The ET holds, for polygons of four or more corners, the
//! rows below their first row where further edges start.
//!
//! All logic is written once against capacity-erased views of the storage
//! ([`TableStorage`]), so it compiles once per colour type.
//!
//! Each job has its file: `storage` (where the tables live:
//! [`TableStorage`], [`TableArrays`]), `entry` (the packed polygon-table
//! entry, [`PolygonEntry`]), `state` ([`Tables`] itself: the lengths of
//! its lists and its counts, made, resized and cleared), `admission`
//! (vertices and polygons offered, judged and queued: [`Admission`]) and
//! `prepare` (the bucket sort by row and the edge table: [`Prepared`]).

// `state` first: the Tables page of the docs lists the methods of its
// impl blocks in the order their files are declared, constructors first.
mod state;

mod admission;
pub(crate) mod entry;
mod prepare;
mod storage;

pub use admission::Admission;
pub use entry::PolygonEntry;
pub use prepare::Prepared;
pub use state::Tables;
pub use storage::{TableArrays, TableParts, TablePartsRef, TableStorage};
