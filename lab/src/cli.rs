//! What the host tools (`examples/`, the simulator) share: loading a model
//! named on the command line or the meshes of a folder, reading a frame size, and running on a thread
//! with a stack large enough for a host-sized renderer.

use std::format;
use std::process::ExitCode;
use std::string::{String, ToString};

use crate::shapes;
use zline::host::HostMesh;

/// An OBJ file, or `shape:NAME` for a built-in mesh (see [`shapes::NAMES`]).
/// Errors name the file and, for a malformed OBJ, the line.
pub fn load_model(spec: &str) -> Result<HostMesh, String> {
    load_model_as(spec, false)
}

/// [`load_model`] for smooth shading: an OBJ file read with its normals
/// and texture coordinates ([`HostMesh::from_obj_smooth`]), a shape given
/// normals; each at the default crease angle
/// ([`zline::host::DEFAULT_CREASE_DEGREES`]).
pub fn load_model_smooth(spec: &str) -> Result<HostMesh, String> {
    load_model_as(spec, true)
}

fn load_model_as(spec: &str, smooth: bool) -> Result<HostMesh, String> {
    let crease = zline::host::DEFAULT_CREASE_DEGREES;
    let mesh = match spec.strip_prefix("shape:") {
        Some(name) => shapes::by_name(name).ok_or_else(|| {
            format!(
                "unknown shape '{name}' (one of {})",
                shapes::NAMES.join(", ")
            )
        })?,
        None => {
            let bytes = std::fs::read(spec).map_err(|e| format!("{spec}: {e}"))?;
            if bytes.contains(&0) {
                return Err(format!(
                    "{spec}: a binary file, not a Wavefront OBJ mesh (text: `v x y z` and `f a b c` lines)"
                ));
            }
            let mesh = if smooth {
                HostMesh::from_obj_smooth(&bytes, crease)
            } else {
                HostMesh::from_obj(&bytes)
            };
            mesh.map_err(|e| format!("{spec}: {e}"))?
        }
    };
    let mesh = if smooth && mesh.vertex_normals.is_empty() {
        mesh.with_vertex_normals(crease)
            .map_err(|e| format!("{spec}: {e}"))?
    } else {
        mesh
    };
    if mesh.positions.is_empty() && mesh.face_starts.is_empty() {
        return Err(format!(
            "{spec}: not a Wavefront OBJ mesh: no `v x y z` (vertex) or `f a b c` (face) lines"
        ));
    }
    if mesh.face_starts.is_empty() {
        return Err(format!(
            "{spec}: an OBJ file with no faces (`f` lines): nothing to draw"
        ));
    }
    // Its size must normalise for the reference view: said here, with the
    // file's name.
    zline::bounding_sphere(&mesh).map_err(|e| format!("{spec}: {e}"))?;
    Ok(mesh)
}

/// The `.obj` files of a folder, sorted by name; an error when there are
/// none.
pub fn obj_files(dir: &std::path::Path) -> Result<std::vec::Vec<std::path::PathBuf>, String> {
    let mut files: std::vec::Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(format!("{}: no .obj files", dir.display()));
    }
    Ok(files)
}

/// An angle in degrees for option `name`: any finite number.
pub fn parse_angle(name: &str, s: &str) -> Result<f32, String> {
    s.parse::<f32>()
        .ok()
        .filter(|a| a.is_finite())
        .ok_or_else(|| format!("{name}: expected degrees, got '{s}'"))
}

/// Whether `args` ask for help (`--help` or `-h`): then `usage` has been
/// printed on standard output, and the tool should exit with success.
pub fn help_requested(args: &[String], usage: &str) -> bool {
    let asked = args.iter().any(|a| a == "--help" || a == "-h");
    if asked {
        // (A closed pipe, as with `| head`, is no failure.)
        let _ =
            std::io::Write::write_all(&mut std::io::stdout(), std::format!("{usage}\n").as_bytes());
    }
    asked
}

/// A frame size `WxH`, each side 1 to 4096.
pub fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let bad = || format!("--size: expected WxH with each side 1 to 4096, got '{s}'");
    let (w, h) = s.split_once('x').ok_or_else(bad)?;
    let side = |v: &str| v.parse::<u16>().ok().filter(|&n| (1..=4096).contains(&n));
    Ok((side(w).ok_or_else(bad)?, side(h).ok_or_else(bad)?))
}

/// Runs a tool's `body` and reports how it ended: an `Err` is printed as
/// `NAME: message` (then `usage`, if not empty) and exits with 2; a panic
/// exits with 1. (It runs on a thread of its own so that a panic is caught
/// and reported as a failure of the tool.)
pub fn run_tool(
    name: &str,
    usage: &str,
    body: impl FnOnce() -> Result<(), String> + Send + 'static,
) -> ExitCode {
    let worker = std::thread::Builder::new().spawn(body);
    match worker.map(|w| w.join()) {
        Ok(Ok(Ok(()))) => ExitCode::SUCCESS,
        Ok(Ok(Err(message))) => {
            std::eprintln!("{name}: {message}");
            if !usage.is_empty() {
                std::eprintln!("{usage}");
            }
            ExitCode::from(2)
        }
        Ok(Err(panic)) => {
            let text = panic
                .downcast_ref::<&str>()
                .map(ToString::to_string)
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            std::eprintln!("{name}: internal failure {text}");
            ExitCode::FAILURE
        }
        Err(e) => {
            std::eprintln!("{name}: cannot start: {e}");
            ExitCode::FAILURE
        }
    }
}
