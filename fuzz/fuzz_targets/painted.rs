//! Gouraud shading on arbitrary screen-space polygons: uniform corners
//! paint the flat frame, a triangle's pixels stay within its corners'
//! colours, nothing panics or overflows. The checks live in
//! `zline_lab::fuzz_checks`, shared with the regression tests that replay
//! `fuzz/seeds/painted/` and `fuzz/regressions/painted/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| zline_lab::fuzz_checks::painted(data));
