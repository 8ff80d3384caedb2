//! Host-side comparison renderers and checks (feature `std`): a float64
//! reference renderer, the accuracy comparison against it, and a mesh in
//! growable storage for loading large OBJ files. None of this is needed by
//! the core.

mod accuracy;
pub mod exact;
pub mod fuzz_checks;
mod host_mesh;
mod reference;
mod rust_source;
mod scanline_host;
pub mod shapes;
mod tool;

pub use accuracy::{Comparison, compare};
pub use host_mesh::HostMesh;
pub use reference::{BACKGROUND, ReferenceFrame, ReferenceView};
pub use rust_source::static_mesh_source;
pub use scanline_host::{HostFrame, HostPixel, HostRenderer, HostScanline};
pub use tool::{load_model, parse_size, run_tool};
