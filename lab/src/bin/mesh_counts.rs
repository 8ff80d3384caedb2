//! Checks the OBJ reader against the counts table of a mesh directory's
//! `README.md` (columns `file | v | vt | vn | f | tris | ...`):
//!
//! ```sh
//! cargo run --release -p zline-lab --bin mesh_counts -- ../shared/meshes
//! ```
//!
//! Every listed file is counted with [`zline::obj::count`] and loaded into
//! a fixed-capacity [`ObjMesh`]; v, vt, vn, f and tris must match the
//! table exactly, and the mesh's vertex and face counts must match the
//! count. Prints one line a file and a summary; exits non-zero if a file
//! is missing, fails to load or mismatches.

use std::path::Path;
use std::process::ExitCode;

use zline_lab::cli::help_requested;

use zline::Mesh;
use zline::obj::{ObjCounts, ObjMesh, count};

/// Room for the Stanford bunny (35,947 vertices, 69,451 triangles) and
/// faces of up to 8 corners.
type Big = ObjMesh<40_000, 220_000, 70_000, 8>;

/// The table's columns after `file`, in order.
const COLUMNS: [&str; 5] = ["v", "vt", "vn", "f", "tris"];

/// One row of the table.
struct Row {
    file: String,
    /// v, vt, vn, f, tris.
    expected: [usize; 5],
}

fn cells(line: &str) -> Vec<&str> {
    line.trim()
        .trim_matches('|')
        .split('|')
        .map(str::trim)
        .collect()
}

/// The rows of the first table whose first column is `file`.
fn table(readme: &str) -> Result<Vec<Row>, String> {
    let mut header_seen = false;
    let mut rows = Vec::new();
    for line in readme.lines().filter(|l| l.trim_start().starts_with('|')) {
        let cells = cells(line);
        if cells.first() == Some(&"file") {
            if cells.get(1..6) != Some(&COLUMNS[..]) {
                return Err(format!("unexpected table header: {line}"));
            }
            header_seen = true;
        } else if header_seen && cells.first().is_some_and(|f| f.ends_with(".obj")) {
            rows.push(row(&cells).map_err(|e| format!("{e} in row: {line}"))?);
        }
    }
    if rows.is_empty() {
        return Err("no `| file | v | vt | vn | f | tris |` table rows found".into());
    }
    Ok(rows)
}

fn row(cells: &[&str]) -> Result<Row, String> {
    let mut expected = [0; 5];
    for (k, slot) in expected.iter_mut().enumerate() {
        let cell = cells.get(k + 1).ok_or("missing column")?;
        *slot = cell
            .replace(',', "")
            .parse()
            .map_err(|_| format!("bad number {cell:?}"))?;
    }
    Ok(Row {
        file: cells.first().unwrap_or(&"").to_string(),
        expected,
    })
}

#[derive(PartialEq)]
enum Outcome {
    Ok,
    Mismatch,
    Failed,
}

fn actual(c: &ObjCounts) -> [usize; 5] {
    [c.vertices, c.texcoords, c.normals, c.faces, c.triangles]
}

fn show(counts: &[usize; 5]) -> String {
    COLUMNS
        .iter()
        .zip(counts)
        .map(|(name, n)| format!("{name} {n:>6}"))
        .collect::<Vec<_>>()
        .join("  ")
}

/// Counts, loads and compares one file; prints its line.
fn check(dir: &Path, row: &Row, mesh: &mut Big) -> Outcome {
    let loaded = std::fs::read(dir.join(&row.file))
        .map_err(|e| format!("cannot read: {e}"))
        .and_then(|bytes| {
            let counts = count(&bytes).map_err(|e| format!("count: {e}"))?;
            mesh.load(&bytes).map_err(|e| format!("ObjMesh: {e}"))?;
            Ok(counts)
        });
    let counts = match loaded {
        Ok(counts) => counts,
        Err(e) => {
            println!("{:<26} FAILED: {e}", row.file);
            return Outcome::Failed;
        }
    };
    let found = actual(&counts);
    let mesh_agrees = mesh.vertex_count() == counts.vertices
        && mesh.face_count() == counts.faces
        && mesh.corners().len() == counts.corners
        && mesh.as_static().face_count() == counts.faces;
    let mut line = format!("{:<26} {}", row.file, show(&found));
    let outcome = if found != row.expected {
        line += &format!("  MISMATCH (README: {})", show(&row.expected));
        Outcome::Mismatch
    } else if !mesh_agrees {
        line += &format!(
            "  MISMATCH (ObjMesh: {} vertices, {} faces)",
            mesh.vertex_count(),
            mesh.face_count()
        );
        Outcome::Mismatch
    } else {
        line += "  OK";
        Outcome::Ok
    };
    println!("{line}");
    outcome
}

fn run(dir: &Path) -> Result<bool, String> {
    let readme_path = dir.join("README.md");
    let readme = std::fs::read_to_string(&readme_path)
        .map_err(|e| format!("cannot read {}: {e}", readme_path.display()))?;
    let rows = table(&readme)?;
    let mut mesh = Box::new(Big::new());
    let outcomes: Vec<Outcome> = rows.iter().map(|r| check(dir, r, &mut mesh)).collect();
    let tally = |o: Outcome| outcomes.iter().filter(|&x| *x == o).count();
    let (ok, mismatched, failed) = (
        tally(Outcome::Ok),
        tally(Outcome::Mismatch),
        tally(Outcome::Failed),
    );
    println!(
        "mesh counts: {} files, {ok} ok, {mismatched} mismatched, {failed} failed",
        rows.len()
    );
    Ok(ok == rows.len())
}

const USAGE: &str = "usage: mesh_counts [MESH_DIR]
Counts every mesh listed in MESH_DIR/README.md (default ../shared/meshes) with the OBJ reader and
checks v, vt, vn, f and triangle counts against the table; exits non-zero on a mismatch.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    let dir = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "../shared/meshes".into());
    // `ObjMesh` is built on the stack before it is boxed: give it room.
    let worker = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || run(Path::new(&dir)));
    match worker.map(|handle| handle.join()) {
        Ok(Ok(Ok(true))) => ExitCode::SUCCESS,
        Ok(Ok(Ok(false))) => ExitCode::FAILURE,
        Ok(Ok(Err(message))) => {
            eprintln!("mesh_counts: {message}");
            ExitCode::FAILURE
        }
        Ok(Err(_)) => {
            eprintln!("mesh_counts: the worker thread panicked");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("mesh_counts: cannot start the worker thread: {e}");
            ExitCode::FAILURE
        }
    }
}
