//! Opens the desktop window: a mesh drawn by zline in
//! embedded-graphics-simulator (SDL2), with keys to turn it, zoom, and
//! switch shading, culling, depth format and renderer.
//!
//! ```sh
//! cargo run --release --example simulator [-- MODEL] [options]
//! ```
//!
//! This example is only a launcher. The window needs SDL2, and the root
//! crate must not (so that `cargo test` never builds it), so the window is
//! its own crate in `tools/simulator/`. This builds it first with cargo's
//! progress shown (the first build compiles SDL2's bindings and takes a
//! few minutes), then runs `cargo run --release --quiet --manifest-path
//! tools/simulator/Cargo.toml -- ARGS` with every argument and the
//! environment passed through, and exits with its exit code. See
//! `tools/simulator/src/main.rs` for the options and keys; `-- --help`
//! prints them.
//!
//! `EG_SIMULATOR_DUMP=frame.png` saves the first frame as PNG and exits
//! without opening a window. With `--scale 1 --no-overlay` it equals
//! `cargo run --release --example render -- MODEL --out x.png`.

use std::path::Path;
use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/simulator/Cargo.toml");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    eprintln!(
        "simulator: building the window crate (tools/simulator); the first build takes a few minutes"
    );
    let built = Command::new(&cargo)
        .args(["build", "--release", "--manifest-path"])
        .arg(&manifest)
        .status();
    if !built.is_ok_and(|s| s.success()) {
        eprintln!(
            "simulator: building {} failed (is SDL2 installed? see the README)",
            manifest.display()
        );
        return ExitCode::FAILURE;
    }
    let status = Command::new(&cargo)
        .args(["run", "--release", "--quiet", "--manifest-path"])
        .arg(&manifest)
        .arg("--")
        .args(std::env::args_os().skip(1))
        .status();
    match status {
        Ok(status) => match status.code() {
            Some(0) => ExitCode::SUCCESS,
            // Exit codes are 0..=255 on the platforms that report them.
            Some(code) => ExitCode::from(u8::try_from(code).unwrap_or(1)),
            // Ended by a signal.
            None => {
                eprintln!("simulator: the window process was stopped ({status})");
                ExitCode::FAILURE
            }
        },
        Err(e) => {
            eprintln!(
                "simulator: cannot start cargo ({}) to build and run {}: {e}",
                Path::new(&cargo).display(),
                manifest.display()
            );
            ExitCode::FAILURE
        }
    }
}
