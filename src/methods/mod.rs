//! Host-side comparison renderers and checks (feature `std`): the float64
//! reference renderer, the exact rational oracle for the core, the
//! accuracy comparison against the reference, and the scanline core over
//! `Vec` storage with a whole-frame output. None of this is needed by the
//! core.

mod accuracy;
pub mod exact;
mod reference;
mod scanline_host;

pub use accuracy::{Comparison, compare};
pub use reference::{BACKGROUND, ReferenceFrame, ReferenceView};
pub use scanline_host::{HOST_CAPACITIES, HostFrame, HostPixel, HostRenderer, HostScanline};
