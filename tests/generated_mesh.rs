//! What `obj2rust` writes for a closed mesh compiles, and is what the
//! generator writes today: `tests/data/closed_cube.rs` is its output for
//! `tests/data/closed_cube.obj` (regenerate with
//! `cargo run --release --example obj2rust -- tests/data/closed_cube.obj CUBE`,
//! the origin comment aside).

use zline::host::HostMesh;
use zline::{ClosedHull, Mesh};
use zline_lab::rust_source::static_mesh_source;

mod cube {
    include!("data/closed_cube.rs");
}

#[test]
fn the_generated_cube_compiles_with_its_hull() {
    assert_eq!(cube::CUBE.face_count(), 6);
    let hull: ClosedHull = cube::CUBE.closed_hull().expect("a closed mesh's hull");
    assert_eq!(hull.centre, [0.5; 3]);
    assert!(hull.radius >= 0.75f32.sqrt());
}

#[test]
fn the_generator_writes_the_checked_in_source() {
    let mesh = HostMesh::from_obj(include_bytes!("data/closed_cube.obj")).expect("mesh");
    let source = static_mesh_source(&mesh, "CUBE", "`cube.obj` by obj2rust").expect("source");
    assert_eq!(source, include_str!("data/closed_cube.rs"));
}
