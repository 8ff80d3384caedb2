//! Writes one of the lab's procedural meshes as an OBJ file, on stdout.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin shape_obj -- torus-knot > assets/torus_knot.obj
//! ```
//!
//! `assets/torus_knot.obj`, which the README's first program draws, is
//! written by that command. Positions are printed in the shortest decimal
//! that reads back as the same `f32`, so the file draws exactly as the
//! built-in mesh (`shape:torus-knot`) does.

use std::fmt::Write as _;
use std::io::Write as _;
use std::process::ExitCode;

use zline::host::HostMesh;
use zline_lab::cli::help_requested;
use zline_lab::shapes;

const USAGE: &str = "usage: shape_obj NAME > FILE.obj
Writes a procedural mesh as OBJ on stdout. NAME: torus-knot, icosphere, boxes, terrain, or sphere-N.";

/// The mesh as OBJ text, with a comment naming where it came from.
fn obj_text(name: &str, mesh: &HostMesh) -> String {
    let mut text = format!(
        "# zline's procedural mesh `{name}`: {} vertices, {} faces.\n\
         # Written by `cargo run --release -p zline-lab --bin shape_obj -- {name}`.\n",
        mesh.positions.len(),
        mesh.face_starts.len()
    );
    for [x, y, z] in &mesh.positions {
        let _ = writeln!(text, "v {x} {y} {z}");
    }
    let ends = mesh.face_starts.iter().skip(1).map(|&e| e as usize);
    let ends = ends.chain(std::iter::once(mesh.corners.len()));
    for (&start, end) in mesh.face_starts.iter().zip(ends) {
        text.push('f');
        for &corner in &mesh.corners[start as usize..end] {
            let _ = write!(text, " {}", u32::from(corner) + 1);
        }
        text.push('\n');
    }
    text
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    let [name] = args.as_slice() else {
        eprintln!("{USAGE}");
        return ExitCode::from(2);
    };
    let Some(mesh) = shapes::by_name(name) else {
        eprintln!("shape_obj: no shape named {name:?}\n{USAGE}");
        return ExitCode::from(2);
    };
    let text = obj_text(name, &mesh);
    match std::io::stdout().write_all(text.as_bytes()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("shape_obj: {e}");
            ExitCode::FAILURE
        }
    }
}
