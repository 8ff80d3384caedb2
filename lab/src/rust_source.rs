//! Writing a mesh as Rust statics, so that it stays in flash: the
//! generator behind `examples/obj2rust.rs` and the firmware build scripts.

use std::fmt::Write as _;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use zline::host::{HostMesh, QuantizedHostMesh};
use zline::{SharedPlane, face_normals, planar_face_bits};

/// Rust source defining `pub static NAME: zline::StaticMesh<'static>`
/// and its arrays (`NAME_POSITIONS`, `NAME_CORNERS`, `NAME_FACE_STARTS`;
/// the precomputed planarity bits, shared planes and face normals, and
/// the hull of a closed mesh). The mesh goes through the `const`
/// `StaticMesh::new`, so a broken one fails at compile time. Floats are
/// written so they read back bit for bit. `origin` names the source in a
/// comment. `Err` when `name` is not a Rust identifier.
pub fn static_mesh_source(mesh: &HostMesh, name: &str, origin: &str) -> Result<String, String> {
    check_name(name)?;
    let origin = origin.replace(char::is_control, "?");
    let HostMesh {
        positions,
        corners,
        face_starts,
        shared_planes,
        ..
    } = mesh;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// Generated from {origin}: {} vertices, {} faces, {} corners. Do not edit.\n",
        positions.len(),
        face_starts.len(),
        corners.len()
    );
    let _ = writeln!(
        out,
        "static {name}_POSITIONS: [[f32; 3]; {}] = [\n{}];\n",
        positions.len(),
        rows(positions, 1, |p| format!(
            "[{:?}, {:?}, {:?}]",
            p[0], p[1], p[2]
        ))
    );
    let _ = writeln!(
        out,
        "static {name}_CORNERS: [u16; {}] = [\n{}];\n",
        corners.len(),
        rows(corners, 16, u16::to_string)
    );
    let _ = writeln!(
        out,
        "static {name}_FACE_STARTS: [u32; {}] = [\n{}];\n",
        face_starts.len(),
        rows(face_starts, 16, u32::to_string)
    );
    let planar: Vec<u32> = planar_face_bits(mesh).collect();
    let _ = writeln!(
        out,
        "// Bit f set: face f is planar (precomputed, so the pipeline need not test it).\n\
         static {name}_PLANAR: [u32; {}] = [\n{}];\n",
        planar.len(),
        rows(&planar, 8, |b| format!("0x{b:08X}"))
    );
    shared_planes_source(&mut out, name, shared_planes);
    let normals: Vec<[f32; 3]> = face_normals(mesh).collect();
    let _ = writeln!(
        out,
        "// Each face's normal (Newell's, model space), so shading need not read its corners.\n\
         static {name}_NORMALS: [[f32; 3]; {}] = [\n{}];\n",
        normals.len(),
        rows(&normals, 1, |n| format!(
            "[{:?}, {:?}, {:?}]",
            n[0], n[1], n[2]
        ))
    );
    // A closed mesh's hull: `Cull::None` then leaves out the back faces
    // where none can show (`zline::ClosedHull`). A hull that holds only
    // with caps over holes is not written (a static mesh carries no caps).
    let hull = mesh.closed_hull.filter(|_| mesh.hull_caps.is_empty());
    let closed = hull.map_or(String::new(), |h| {
        format!(
            ".with_closed_hull(zline::ClosedHull {{ centre: [{:?}, {:?}, {:?}], radius: {:?} }})",
            h.centre[0], h.centre[1], h.centre[2], h.radius
        )
    });
    let _ = writeln!(
        out,
        "/// Mesh from {origin}, checked at compile time.\n\
         pub static {name}: zline::StaticMesh<'static> = match zline::StaticMesh::new(\n    \
         &{name}_POSITIONS,\n    &{name}_CORNERS,\n    &{name}_FACE_STARTS,\n) {{\n    \
         Ok(mesh) => match mesh.with_planar_faces(&{name}_PLANAR) {{\n        \
         Ok(mesh) => match mesh.with_shared_planes(&{name}_SHARED) {{\n            \
         Ok(mesh) => match mesh.with_face_normals(&{name}_NORMALS) {{\n                \
         Ok(mesh) => mesh{closed},\n                Err(_) => panic!(\"{name}: invalid face normals\"),\n            }},\n            \
         Err(_) => panic!(\"{name}: invalid shared planes\"),\n        }},\n        \
         Err(_) => panic!(\"{name}: invalid planarity bits\"),\n    }},\n    \
         Err(_) => panic!(\"{name}: invalid mesh\"),\n}};"
    );
    Ok(out)
}

/// Rust source for a [`QuantizedMesh`](zline::QuantizedMesh)
/// of `mesh` named `name` (see [`QuantizedHostMesh`]): 6 bytes a vertex
/// and 12 a face (its unit normal and its exact normal) in flash instead of
/// 12 a vertex, and the integer front end draws it with no floating point
/// per vertex or face.
pub fn quantized_mesh_source(mesh: &HostMesh, name: &str, origin: &str) -> Result<String, String> {
    check_name(name)?;
    let origin = origin.replace(char::is_control, "?");
    let q = QuantizedHostMesh::new(mesh).map_err(|e| format!("{origin}: {e}"))?;
    q.mesh().map_err(|e| format!("{origin}: {e:?}"))?;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// Generated from {origin}: {} vertices, {} faces, {} corners, quantized in the\n\
         // sphere centre {:?}, radius {:?}. Do not edit.\n",
        q.positions.len(),
        q.face_starts.len(),
        q.corners.len(),
        q.centre,
        q.radius
    );
    let triple = |p: &[i16; 3]| format!("[{}, {}, {}]", p[0], p[1], p[2]);
    let _ = writeln!(
        out,
        "static {name}_POSITIONS: [[i16; 3]; {}] = [\n{}];\n",
        q.positions.len(),
        rows(&q.positions, 4, triple)
    );
    let _ = writeln!(
        out,
        "static {name}_NORMALS: [[i16; 3]; {}] = [\n{}];\n",
        q.normals.len(),
        rows(&q.normals, 4, triple)
    );
    let _ = writeln!(
        out,
        "static {name}_CORNERS: [u16; {}] = [\n{}];\n",
        q.corners.len(),
        rows(&q.corners, 16, u16::to_string)
    );
    let _ = writeln!(
        out,
        "static {name}_FACE_STARTS: [u32; {}] = [\n{}];\n",
        q.face_starts.len(),
        rows(&q.face_starts, 16, u32::to_string)
    );
    let _ = writeln!(
        out,
        "// Bit f set: face f is planar.\nstatic {name}_PLANAR: [u32; {}] = [\n{}];\n",
        q.planar.len(),
        rows(&q.planar, 8, |b| format!("0x{b:08X}"))
    );
    shared_planes_source(&mut out, name, &q.shared_planes);
    let _ = writeln!(
        out,
        "// Each face's exact normal, for the model-space back-face test.\n\
         static {name}_EXACT_NORMALS: [[i16; 3]; {}] = [\n{}];\n",
        q.exact_normals.len(),
        rows(&q.exact_normals, 4, triple)
    );
    // A mesh with vertex normals (smooth shading) gets them too.
    let vertex_normals = if q.vertex_normals.is_empty() {
        ""
    } else {
        let _ = writeln!(
            out,
            "// Each vertex's unit normal, for smooth shading.\n\
             static {name}_VERTEX_NORMALS: [[i16; 3]; {}] = [\n{}];\n",
            q.vertex_normals.len(),
            rows(&q.vertex_normals, 4, triple)
        );
        "match mesh.with_vertex_normals(&NAME_VERTEX_NORMALS) {\n                \
         Ok(mesh) => mesh,\n                Err(_) => panic!(\"NAME: invalid vertex normals\"),\n            }"
    };
    // And one with texture coordinates (texture mapping), those.
    let vertex_uvs = if q.vertex_uvs.is_empty() {
        ""
    } else {
        let _ = writeln!(
            out,
            "// Each vertex's texture coordinates, `q / zline::limits::UV_SCALE`.\n\
             static {name}_VERTEX_UVS: [[i16; 2]; {}] = [\n{}];\n",
            q.vertex_uvs.len(),
            rows(&q.vertex_uvs, 6, |uv| format!("[{}, {}]", uv[0], uv[1]))
        );
        "match mesh.with_vertex_uvs(&NAME_VERTEX_UVS) {\n                \
         Ok(mesh) => mesh,\n                Err(_) => panic!(\"NAME: invalid texture coordinates\"),\n            }"
    };
    let mut last = "mesh".to_string();
    for step in [vertex_normals, vertex_uvs] {
        let step = step.replace("NAME", name);
        last = match (step.is_empty(), last == "mesh") {
            (true, _) => last,
            (false, true) => step,
            // Each step takes the mesh the one before made.
            (false, false) => {
                format!("{{\n            let mesh = {last};\n            {step}\n        }}")
            }
        };
    }
    let _ = writeln!(
        out,
        "/// Mesh from {origin}, quantized, checked at compile time.\n\
         pub static {name}: zline::QuantizedMesh<'static> = match zline::QuantizedMesh::new(\n    \
         &{name}_POSITIONS,\n    &{name}_NORMALS,\n    &{name}_CORNERS,\n    &{name}_FACE_STARTS,\n    &{name}_PLANAR,\n    \
         [{:?}, {:?}, {:?}],\n    {:?},\n) {{\n    \
         Ok(mesh) => match mesh.with_shared_planes(&{name}_SHARED) {{\n        \
         Ok(mesh) => match mesh.with_exact_normals(&{name}_EXACT_NORMALS) {{\n            \
         Ok(mesh) => {last},\n            Err(_) => panic!(\"{name}: invalid exact normals\"),\n        }},\n        \
         Err(_) => panic!(\"{name}: invalid shared planes\"),\n    }},\n    \
         Err(_) => panic!(\"{name}: invalid mesh\"),\n}};",
        q.centre[0], q.centre[1], q.centre[2], q.radius
    );
    Ok(out)
}

/// The static `NAME_SHARED`: the mesh's shared planes.
fn shared_planes_source(out: &mut String, name: &str, shared: &[SharedPlane]) {
    let _ = writeln!(
        out,
        "// Faces that share one plane with overlapping coplanar faces.\n\
         static {name}_SHARED: [zline::SharedPlane; {}] = [\n{}];\n",
        shared.len(),
        rows(shared, 1, |p| format!(
            "zline::SharedPlane {{ face: {}, vertices: [{}, {}, {}] }}",
            p.face, p.vertices[0], p.vertices[1], p.vertices[2]
        ))
    );
}

/// Rust's strict and reserved keywords (edition 2024): none can name a
/// static.
const KEYWORDS: [&str; 52] = [
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut",
    "pub", "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "try", "typeof", "unsized", "virtual", "yield",
];

fn check_name(name: &str) -> Result<(), String> {
    let mut chars = name.chars();
    let first_ok = chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if !first_ok || !chars.all(|c| c.is_ascii_alphanumeric() || c == '_') || name == "_" {
        Err(format!("NAME {name:?} is not a Rust identifier"))
    } else if KEYWORDS.contains(&name) {
        Err(format!("NAME {name:?} is a Rust keyword"))
    } else {
        Ok(())
    }
}

fn rows<T>(items: &[T], per_line: usize, show: impl Fn(&T) -> String) -> String {
    let mut out = String::new();
    for chunk in items.chunks(per_line) {
        let line: Vec<String> = chunk.iter().map(&show).collect();
        let _ = writeln!(out, "    {},", line.join(", "));
    }
    out
}
