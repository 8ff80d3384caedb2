//! A closed mesh drawn with `Cull::None` from outside leaves out its back
//! faces (`ClosedHull`): every frame covers the same pixels as the mesh
//! drawn two-sided, and a pixel differs only where the two-sided frame
//! shows a back face and the culled one a front face (a depth tie at a
//! silhouette, which the nearer front face wins in exact arithmetic).

use proptest::prelude::*;
use zline::host::{HostMesh, closed_hull};
use zline::{Camera, Cull, DrawStats, Mat4, Vec3, radians, reference_model};
use zline_lab::shapes;

mod common;

use common::NO_FACE as NONE;

/// The frame's pixels as `face << 1 | front`, and the draw's counts.
fn frame(mesh: &HostMesh, model: &Mat4, camera: &Camera, cull: Cull) -> (Vec<u32>, DrawStats) {
    common::mesh_frame(mesh, model, camera, cull, |f| {
        f.face << 1 | u32::from(f.front)
    })
}

/// `mesh` as it is (with its hull) and two-sided (without), drawn with
/// `Cull::None`; checks the promise and returns the pixels that differ
/// and whether back faces were culled.
fn compare(mesh: &HostMesh, model: &Mat4, camera: &Camera) -> (usize, bool) {
    let (culled, stats) = frame(mesh, model, camera, Cull::None);
    let open = HostMesh {
        closed_hull: None,
        ..mesh.clone()
    };
    let (two_sided, two_sided_stats) = frame(&open, model, camera, Cull::None);
    assert_eq!(two_sided_stats.back_faces, 0);
    let mut differ = 0;
    for (k, (&a, &b)) in culled.iter().zip(&two_sided).enumerate() {
        if a != b {
            differ += 1;
            assert!(
                a != NONE && a & 1 == 1 && b != NONE && b & 1 == 0,
                "pixel {k}: culled {a:#x}, two-sided {b:#x}"
            );
        }
    }
    // The colour is which face: a front face that is not the nearest
    // would show here as many pixels changed, not a few ties.
    let covered = two_sided.iter().filter(|&&p| p != NONE).count();
    assert!(
        differ <= covered / 64 + 4,
        "{differ} of {covered} pixels differ"
    );
    (differ, stats.back_faces > 0)
}

fn turned(yaw: f32, pitch: f32) -> Mat4 {
    Mat4::rotation_x(radians(pitch)).mul(&Mat4::rotation_y(radians(yaw)))
}

#[test]
fn closed_shapes_draw_as_two_sided_from_every_side() {
    for mut mesh in [shapes::torus_knot(2, 3, 64, 8, 0.45), shapes::icosphere(3)] {
        mesh.closed_hull = closed_hull(&mesh);
        assert!(mesh.closed_hull.is_some(), "closed");
        for (w, h) in [(64, 48), (240, 240)] {
            let camera = Camera::reference(w, h);
            let mut differ = 0;
            for yaw in (0..360).step_by(45) {
                for pitch in [-60, -20, 0, 35, 80] {
                    let base = reference_model(&mesh, yaw as f32, pitch as f32).expect("model");
                    let (d, culled) = compare(&mesh, &base, &camera);
                    assert!(culled, "yaw {yaw} pitch {pitch}: back faces drawn");
                    differ += d;
                }
            }
            // Ties are rare: a few silhouette pixels in 40 frames.
            eprintln!("{w}x{h}: {differ} pixels differ in 40 frames");
            assert!(differ < 40 * usize::from(w) / 8, "{differ} pixels differ");
        }
    }
}

#[test]
fn a_mirror_or_an_eye_inside_draws_both_sides() {
    let mut mesh = shapes::icosphere(2);
    mesh.closed_hull = closed_hull(&mesh);
    let camera = Camera::reference(64, 48);
    let model = reference_model(&mesh, 30.0, 20.0).expect("model");
    // Mirrored: the front faces turn clockwise on screen.
    let mirror = model.mul(&Mat4::scale(Vec3::new(-1.0, 1.0, 1.0)));
    assert_eq!(compare(&mesh, &mirror, &camera), (0, false));
    // The unit sphere scaled to reach past the near plane (the eye at 3).
    let big = Mat4::scale(Vec3::new(3.5, 3.5, 3.5)).mul(&model);
    assert_eq!(compare(&mesh, &big, &camera), (0, false));
}

#[test]
fn open_meshes_have_no_hull() {
    assert_eq!(closed_hull(&shapes::terrain(8)), None);
    let mut mesh = shapes::icosphere(1);
    let n = mesh.face_starts.len();
    mesh.face_starts.truncate(n - 1);
    mesh.corners.truncate(3 * (n - 1));
    assert_eq!(closed_hull(&mesh), None);
}

/// An icosphere with each vertex moved along its ray by its own factor:
/// star-shaped, so closed, wound outward and never through itself.
fn lumpy(factors: &[f32]) -> HostMesh {
    let mut mesh = shapes::icosphere(2);
    for (p, &f) in mesh.positions.iter_mut().zip(factors.iter().cycle()) {
        *p = p.map(|c| c * f);
    }
    mesh.closed_hull = closed_hull(&mesh);
    mesh
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Any view, mirrored or not, from far off to with the eye inside the mesh: the
    /// culled frame covers what the two-sided one does, and differs only
    /// where a front face replaces a back one.
    #[test]
    fn lumpy_spheres_from_any_view(
        factors in prop::collection::vec(0.3f32..1.6, 1..40),
        yaw in 0.0f32..360.0,
        pitch in -90.0f32..90.0,
        scale in 0.3f32..4.0,
        mirror in any::<bool>(),
        size in prop::sample::select(vec![(48u16, 40u16), (97, 61)]),
    ) {
        let mesh = lumpy(&factors);
        prop_assert!(mesh.closed_hull.is_some());
        let x = if mirror { -scale } else { scale };
        let model = Mat4::scale(Vec3::new(x, scale, scale)).mul(&turned(yaw, pitch));
        compare(&mesh, &model, &Camera::reference(size.0, size.1));
    }
}
