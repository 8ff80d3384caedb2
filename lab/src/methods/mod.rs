//! Host-side comparison renderers and checks (feature `std`): the float64
//! reference renderer, the exact rational oracle for the core, the
//! accuracy comparison against the reference, the scanline core over `Vec`
//! storage with a whole-frame output, the interval (span) scanline and the
//! painter's algorithm, and [`MethodRenderer`], which runs any [`Method`]
//! (these, and the core's z-buffer and bands) on the same scene, and the
//! catalogue of adversarial scenes where methods break. None of
//! this is needed by the core.

mod accuracy;
pub mod catalogue;
pub mod clip_reference;
pub mod exact;
pub mod interval;
pub mod painter;
mod reference;
mod run;
mod scanline_host;

pub use accuracy::{Comparison, EDGE_TOLERANCE, compare};
pub use reference::{BACKGROUND, ReferenceCamera, ReferenceFrame, ReferenceView, rotate};
pub use run::{Memory, Method, MethodFrame, MethodRenderer};
pub use scanline_host::{HOST_CAPACITIES, HostFrame, HostPixel, HostRenderer, HostScanline};
