//! The integer arithmetic the core and the front end share, below both:
//! exact wide products (in 16-bit halves where a core has no long
//! multiply) and exact rounded division.

/// Whether this is an ARMv6-M core (Cortex-M0/M0+): no divide
/// instruction, no 32x32→64 multiply, and (what `cfg` can see) no
/// compare-and-swap atomics. The arithmetic and the scanner's loops take
/// their ARMv6-M forms by it.
pub(crate) const ARMV6M: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

pub(crate) mod divide;
pub(crate) mod wide;
