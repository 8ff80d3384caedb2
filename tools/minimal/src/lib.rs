//! zline without its default features, as a firmware links it; the
//! tests are in `tests/`. Nothing here: the crate exists so that cargo
//! builds zline with exactly these features.
#![no_std]
