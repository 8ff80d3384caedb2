//! The `f32` front end's model-space back-face test (`Mesh::face_planes`):
//! a mesh drawn with `Cull::Back` and its face planes gives the frame it
//! gives without them, but where a face seen almost edge-on, which the
//! exact projection turns away, would have covered a sample by its
//! rounded corners; and it leaves faces out before their corners are
//! transformed.

use proptest::prelude::*;
use zline::host::{HostMesh, HostRenderer};
use zline::{Camera, Cull, Depth24, DrawStats, Mat4, Vec3, reference_model};
use zline_lab::shapes;

mod common;

use common::NO_FACE as NONE;

/// The frame's face ids and the draw's counts.
fn frame(mesh: &HostMesh, model: &Mat4, camera: &Camera) -> (Vec<u32>, DrawStats) {
    common::mesh_frame(mesh, model, camera, Cull::Back, |f| f.face)
}

/// Face `face` of `mesh` on the screen, in `f64`: twice its signed area
/// (pixels squared, `y` down) and the sum of its edges' lengths.
fn screen_area(mesh: &HostMesh, face: usize, model: &Mat4, camera: &Camera) -> (f64, f64) {
    let mvp = camera.projection.mul(&camera.view.mul(model));
    let start = mesh.face_starts[face] as usize;
    let corners = &mesh.corners[start..start + 3];
    let p: Vec<(f64, f64)> = corners
        .iter()
        .map(|&i| {
            let [x, y, z] = mesh.positions[usize::from(i)].map(f64::from);
            let row = |r: [f32; 4]| {
                f64::from(r[0]) * x + f64::from(r[1]) * y + f64::from(r[2]) * z + f64::from(r[3])
            };
            let w = row(mvp.m[3]);
            (
                (row(mvp.m[0]) / w + 1.0) * 0.5 * f64::from(camera.width),
                (1.0 - row(mvp.m[1]) / w) * 0.5 * f64::from(camera.height),
            )
        })
        .collect();
    let cross = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[1].1 - p[0].1) * (p[2].0 - p[0].0);
    let length = |a: (f64, f64), b: (f64, f64)| ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
    (
        cross,
        length(p[0], p[1]) + length(p[1], p[2]) + length(p[2], p[0]),
    )
}

/// `mesh` with its planes and without: the same frame, but for pixels of
/// faces seen edge-on (within a tenth of a pixel of no area), which the
/// frame with planes leaves out. Returns the pixels that differ and the
/// back faces each draw counted.
fn compare(mesh: &HostMesh, model: &Mat4, camera: &Camera) -> (usize, u32, u32) {
    assert!(!mesh.face_planes.is_empty(), "planes");
    let (with, with_stats) = frame(mesh, model, camera);
    let bare = HostMesh {
        face_planes: Vec::new(),
        ..mesh.clone()
    };
    let (without, without_stats) = frame(&bare, model, camera);
    let mut differ = 0;
    for (k, (&a, &b)) in with.iter().zip(&without).enumerate() {
        if a != b {
            differ += 1;
            assert_ne!(b, NONE, "pixel {k}: drawn only with planes");
            let (cross, perimeter) = screen_area(mesh, b as usize, model, camera);
            assert!(
                cross.abs() <= 0.1 * perimeter,
                "pixel {k}: face {b} left out, twice its area {cross} px², perimeter {perimeter} px"
            );
        }
    }
    (differ, with_stats.back_faces, without_stats.back_faces)
}

#[test]
fn shapes_draw_the_same_frames_with_planes() {
    let meshes = [
        shapes::torus_knot(2, 3, 64, 8, 0.45).with_face_analysis(),
        shapes::icosphere(3).with_face_analysis(),
    ];
    for mesh in &meshes {
        for (w, h) in [(64, 48), (240, 240)] {
            let camera = Camera::reference(w, h);
            for yaw in (0..360).step_by(45) {
                for pitch in [-60, -20, 0, 35, 80] {
                    let model = reference_model(mesh, yaw as f32, pitch as f32).expect("model");
                    let (differ, with, without) = compare(mesh, &model, &camera);
                    assert!(differ <= 2, "{differ} pixels differ");
                    // Every back face is counted either way.
                    assert!(with.abs_diff(without) <= 2, "{with} against {without}");
                    assert!(with > 0);
                }
            }
        }
    }
}

/// A face turned away beyond doubt has no corner transformed: a mesh
/// whose back half uses vertices of its own fills fewer vertex-table
/// entries with its planes.
#[test]
fn back_faces_transform_no_corner() {
    let mesh = shapes::icosphere(3).with_face_analysis();
    let camera = Camera::reference(240, 240);
    let model = reference_model(&mesh, 30.0, 20.0).expect("model");
    let vertices = |mesh: &HostMesh| {
        let mut renderer =
            HostRenderer::<u32, Depth24>::for_mesh(mesh, 240, 240, NONE).expect("renderer");
        renderer
            .draw_mesh(mesh, &model, &camera, Cull::Back, |f| f.face)
            .expect("draw");
        renderer.vertex_count()
    };
    let bare = HostMesh {
        face_planes: Vec::new(),
        ..mesh.clone()
    };
    let (with, without) = (vertices(&mesh), vertices(&bare));
    assert_eq!(without, mesh.positions.len());
    assert!(with * 10 < without * 7, "{with} of {without} vertices");
}

fn soup() -> impl Strategy<Value = HostMesh> {
    let point = || proptest::array::uniform3(-1.0f32..1.0);
    proptest::collection::vec(proptest::array::uniform3(point()), 1..40).prop_map(|triangles| {
        let mut mesh = HostMesh::default();
        for t in triangles {
            mesh.face_starts.push(mesh.corners.len() as u32);
            for p in t {
                mesh.corners.push(mesh.positions.len() as u16);
                mesh.positions.push(p);
            }
        }
        mesh.with_face_analysis()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random triangles from random views: the same frames, but for
    /// edge-on faces.
    #[test]
    fn random_triangles_draw_the_same_frames(
        mesh in soup(), yaw in 0.0f32..360.0, pitch in -80.0f32..80.0,
        scale in 0.2f32..3.0,
    ) {
        let camera = Camera::reference(96, 80);
        let model = reference_model(&mesh, yaw, pitch)
            .expect("model")
            .mul(&Mat4::scale(Vec3::new(scale, scale, scale)));
        let (differ, _, _) = compare(&mesh, &model, &camera);
        prop_assert!(differ <= 4, "{differ} pixels differ");
    }
}
