//! The integer arithmetic the core and the front end share, below both:
//! exact wide products (in 16-bit halves where a core has no long
//! multiply) and exact rounded division.

pub(crate) mod divide;
pub(crate) mod wide;
