//! Converts a Wavefront OBJ file into Rust source for a
//! [`StaticMesh`](zline::StaticMesh) static:
//!
//! ```sh
//! cargo run --example obj2rust -- [--quantized [--smooth]] MODEL.obj NAME > name.rs
//! ```
//!
//! With `--quantized` it writes a
//! [`QuantizedMesh`](zline::QuantizedMesh) instead:
//! `i16` positions in the mesh's bounding sphere and a unit normal per
//! face (6 bytes a vertex and 6 a face), which `draw_mesh` transforms,
//! projects and shades with integers only: the choice for a core without
//! an FPU. With `--smooth` as well it adds a unit normal per vertex
//! (the file's `vn`, or computed with a 60° crease angle; a vertex for
//! each different position and normal) for Gouraud shading
//! ([`zline::paint::Gouraud`]), lit with integers too, and the file's
//! `vt` texture coordinates as `i16` (steps of 1/4096, within -8..8) for
//! texture mapping ([`zline::paint::Textured`]); `png2rust` writes the
//! texture.
//!
//! `name.rs` defines `pub static NAME: zline::StaticMesh<'static>`
//! over three `const` arrays (positions, corners, face starts). Include it
//! in firmware with `include!("name.rs")`: the arrays are read-only data,
//! so they stay in flash and cost no RAM. The mesh is checked by the
//! `const` [`StaticMesh::new`](zline::StaticMesh::new) while
//! compiling, so an invalid mesh is a compile error, not a runtime one.
//!
//! Positions are printed with `{:?}`, which round-trips every `f32`
//! exactly. The file is read with zline's own `no_std` reader
//! ([`ObjReader`]); faces may have up to [`MAX_CORNERS`] corners. Errors
//! (unreadable file, bad name, malformed OBJ with its line) go to stderr
//! with a non-zero exit code.

use std::io::Write as _;
use std::process::ExitCode;

use zline_lab::cli::help_requested;

use zline::host::{DEFAULT_CREASE_DEGREES, HostMesh};
use zline_lab::rust_source::quantized_mesh_source;
use zline_lab::rust_source::static_mesh_source;

fn run(args: &[String]) -> Result<(), String> {
    let (quantized, rest) = match args.first().map(String::as_str) {
        Some("--quantized") => (true, &args[1..]),
        _ => (false, args),
    };
    let (smooth, rest) = match rest.first().map(String::as_str) {
        Some("--smooth") if quantized => (true, &rest[1..]),
        Some("--smooth") => return Err("--smooth needs --quantized (before it)".into()),
        _ => (false, rest),
    };
    let [path, name] = rest else {
        return Err("usage: obj2rust [--quantized [--smooth]] MODEL.obj NAME > name.rs".into());
    };
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let mesh = if smooth {
        HostMesh::from_obj_smooth(&bytes, DEFAULT_CREASE_DEGREES)
    } else {
        HostMesh::from_obj(&bytes)
    }
    .map_err(|e| format!("{path}: {e}"))?;
    let origin = std::path::Path::new(path)
        .file_name()
        .map_or(path.clone(), |f| f.to_string_lossy().into_owned());
    let origin = format!("`{origin}` by obj2rust");
    let text = if quantized {
        quantized_mesh_source(&mesh, name, &origin)?
    } else {
        static_mesh_source(&mesh, name, &origin)?
    };
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| format!("cannot write the output: {e}"))
}

const USAGE: &str = "usage: obj2rust [--quantized [--smooth]] MODEL.obj NAME > name.rs
Writes Rust source for MODEL.obj as a StaticMesh static named NAME (with --quantized, a
QuantizedMesh: i16 positions and unit face normals, drawn with integers only; with --smooth
too, i16 vertex normals for Gouraud shading and the file's vt for texture mapping).";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("obj2rust: {message}");
            ExitCode::FAILURE
        }
    }
}
