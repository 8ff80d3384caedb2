//! OBJ bytes and a camera through the whole pipeline to rows: every face
//! accounted for once, only capacity errors, every row once, in order.
//! The checks live in `zline_lab::fuzz_checks`, shared with the
//! regression tests that replay `fuzz/regressions/pipeline/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| zline_lab::fuzz_checks::pipeline(data));
