//! The OBJ reader on any bytes: its three ways in agree, errors carry a
//! real line, and what it accepts is a valid mesh.
//! The checks live in `zline_lab::fuzz_checks`, shared with the
//! regression tests that replay `fuzz/regressions/obj_reader/`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| zline_lab::fuzz_checks::obj_reader(data));
