//! What the host tools share (feature `std`): meshes and core storage in
//! `Vec`s, a frame drawn in bands on several threads, procedural shapes, the mesh-to-Rust writer, command-line
//! helpers, the machine a measurement ran on, and the properties the fuzzers check. None of it is a
//! rendering method and none is needed on a microcontroller.

mod bands;
mod cli;
pub mod coplanar;
pub mod fuzz_checks;
mod host_mesh;
mod machine;
mod quantize;
mod rust_source;
pub mod shapes;
mod storage;

pub use bands::{
    BandTables, BandTiming, BandedRenderer, MESH_VERTICES, ONE_THREAD_BELOW, SharedSteps,
};
pub use cli::{load_model, obj_files, parse_angle, parse_size, run_tool};
pub use host_mesh::HostMesh;
pub use machine::{cpu, now_utc};
pub use quantize::QuantizedHostMesh;
pub use rust_source::{quantized_mesh_source, static_mesh_source};
pub use storage::{ScanVecs, TableVecs, host_renderer};
