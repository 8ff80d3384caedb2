//! The scanline core on arbitrary screen-space polygons against the exact
//! oracle: coverage exact, depth within 1 LSB, or a documented error.
//! The checks live in `zline_lab::fuzz_checks`, shared with the
//! regression tests that replay `fuzz/regressions/core_scene/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| zline_lab::fuzz_checks::core_scene(data));
