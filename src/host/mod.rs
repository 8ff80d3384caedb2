//! What a desktop program needs (feature `std`): meshes and core storage
//! in `Vec`s, sized from the mesh, and a frame drawn in bands on several
//! threads. None of it is needed on a microcontroller.

mod bands;
mod closed;
pub mod coplanar;
mod host_mesh;
mod quantize;
mod storage;

pub use bands::{
    BandTables, BandTiming, BandedRenderer, MESH_VERTICES, ONE_THREAD_BELOW, SharedSteps,
};
pub use closed::{CAP_EDGES_MAX, capped_hull, closed_hull};
pub use host_mesh::{DEFAULT_CREASE_DEGREES, HostMesh};
pub use quantize::QuantizedHostMesh;
pub use storage::{
    HostPaintedRenderer, HostRenderer, PaintVecs, SMALL_TABLE_ENTRIES_PER_COLUMN, ScanVecs,
    TableVecs, host_renderer,
};
