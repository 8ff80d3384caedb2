//! Every saved fuzzer input, replayed through the fuzzers' own checks
//! (`zline_lab::fuzz_checks`): the seed corpora in `fuzz/seeds/` and
//! each finding in `fuzz/regressions/`, named after what it found. A
//! finding is added here before its fix, so it fails until then.

use std::path::Path;

fn replay(target: &str, check: fn(&[u8])) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut replayed = 0;
    for dir in ["seeds", "regressions"] {
        let dir = root.join(dir).join(target);
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|entry| entry.expect("directory entry").path())
            .collect();
        files.sort();
        for file in files {
            let data = std::fs::read(&file).expect("readable input");
            let outcome = std::panic::catch_unwind(|| check(&data));
            assert!(outcome.is_ok(), "{target}: {} fails", file.display());
            replayed += 1;
        }
    }
    assert!(replayed > 0, "{target}: no inputs");
}

#[test]
fn obj_reader_inputs() {
    replay("obj_reader", zline_lab::fuzz_checks::obj_reader);
}

#[test]
fn core_scene_inputs() {
    replay("core_scene", zline_lab::fuzz_checks::core_scene);
}

#[test]
fn pipeline_inputs() {
    replay("pipeline", zline_lab::fuzz_checks::pipeline);
}

#[test]
fn painted_inputs() {
    replay("painted", zline_lab::fuzz_checks::painted);
}
