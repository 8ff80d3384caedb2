//! A mesh with holes, closed by caps over them (`zline::host::capped_hull`,
//! `Mesh::hull_caps`), drawn with `Cull::None` from outside: back faces
//! are left out except where a cap faces the viewer, so that a hole still
//! shows the inside. Every frame covers the same pixels as the mesh drawn
//! two-sided, and a pixel differs only where the two-sided frame shows a
//! back face and the culled one a front face (a depth tie).

use proptest::prelude::*;
use zline::host::HostMesh;
use zline::{Camera, Cull, Depth24, DrawStats, Mat4, Vec3, radians, reference_model};
use zline_lab::shapes;

mod common;

use common::NO_FACE as NONE;

/// The frame's pixels as `face << 1 | front`, and the draw's counts.
fn frame(mesh: &HostMesh, model: &Mat4, camera: &Camera) -> (Vec<u32>, DrawStats) {
    common::mesh_frame(mesh, model, camera, Cull::None, |f| {
        f.face << 1 | u32::from(f.front)
    })
}

/// `mesh` with its hull and drawn two-sided (hull cleared); checks the
/// promise and returns the pixels that differ, the pixels of the two-sided
/// frame that show a back face, and whether back faces were culled.
fn compare(mesh: &HostMesh, model: &Mat4, camera: &Camera) -> (usize, usize, bool) {
    let (culled, stats) = frame(mesh, model, camera);
    let open = HostMesh {
        closed_hull: None,
        ..mesh.clone()
    };
    let (two_sided, two_sided_stats) = frame(&open, model, camera);
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
    let covered = two_sided.iter().filter(|&&p| p != NONE).count();
    assert!(
        differ <= covered / 64 + 4,
        "{differ} of {covered} pixels differ"
    );
    let inside = two_sided
        .iter()
        .filter(|&&p| p != NONE && p & 1 == 0)
        .count();
    (differ, inside, stats.back_faces > 0)
}

fn turned(yaw: f32, pitch: f32) -> Mat4 {
    Mat4::rotation_x(radians(pitch)).mul(&Mat4::rotation_y(radians(yaw)))
}

/// `mesh` without the faces `cut` picks (by their corners' positions),
/// its hull and caps found again.
fn holed(mesh: &HostMesh, cut: impl Fn(&[[f32; 3]]) -> bool) -> HostMesh {
    let mut corners = Vec::new();
    let mut face_starts = Vec::new();
    for f in 0..mesh.face_starts.len() {
        let start = mesh.face_starts[f] as usize;
        let end = mesh
            .face_starts
            .get(f + 1)
            .map_or(mesh.corners.len(), |&e| e as usize);
        let face = &mesh.corners[start..end];
        let points: Vec<[f32; 3]> = face
            .iter()
            .map(|&c| mesh.positions[usize::from(c)])
            .collect();
        if !cut(&points) {
            face_starts.push(corners.len() as u32);
            corners.extend_from_slice(face);
        }
    }
    HostMesh {
        positions: mesh.positions.clone(),
        corners,
        face_starts,
        ..HostMesh::default()
    }
    .with_face_analysis()
}

/// A unit sphere open at both poles (faces with a corner above 0.8 or
/// below -0.7 in y left out).
fn open_sphere() -> HostMesh {
    holed(&shapes::icosphere(3), |p| {
        p.iter().any(|q| q[1] > 0.8 || q[1] < -0.7)
    })
}

#[test]
fn a_sphere_open_at_its_poles_is_capped() {
    let mesh = open_sphere();
    assert!(mesh.closed_hull.is_some(), "capped");
    assert!(!mesh.hull_caps.is_empty(), "caps");
    // Closed meshes get no caps.
    let closed = shapes::icosphere(2).with_face_analysis();
    assert!(closed.closed_hull.is_some() && closed.hull_caps.is_empty());
}

#[test]
fn open_shapes_draw_as_two_sided_from_every_side() {
    let mesh = open_sphere();
    for (w, h) in [(64, 48), (240, 240)] {
        let camera = Camera::reference(w, h);
        let (mut differ, mut inside, mut culled_frames) = (0, 0, 0);
        for yaw in (0..360).step_by(45) {
            for pitch in [-90, -60, -20, 0, 35, 80, 90] {
                let base = reference_model(&mesh, yaw as f32, pitch as f32).expect("model");
                let (d, i, culled) = compare(&mesh, &base, &camera);
                differ += d;
                inside += i;
                culled_frames += usize::from(culled);
            }
        }
        eprintln!(
            "{w}x{h}: {differ} pixels differ in 56 frames, {inside} show the inside, \
             {culled_frames} frames culled"
        );
        // The inside shows through the holes in many views, and back
        // faces are still culled in most.
        assert!(inside > 0, "no view into a hole");
        assert!(culled_frames > 40, "{culled_frames} frames culled");
        assert!(differ < 56 * usize::from(w) / 8, "{differ} pixels differ");
    }
}

#[test]
fn looking_into_a_hole_shows_the_inside() {
    let mesh = open_sphere();
    let camera = Camera::reference(96, 96);
    // From above, tilted so the hole shows the sphere's inner wall.
    let model = reference_model(&mesh, 10.0, 70.0).expect("model");
    let (differ, inside, _) = compare(&mesh, &model, &camera);
    assert!(inside > 100, "{inside} pixels of the inside");
    assert!(differ < 20, "{differ} pixels differ");
}

#[test]
fn a_mirror_or_an_eye_inside_draws_both_sides() {
    let mesh = open_sphere();
    let camera = Camera::reference(64, 48);
    let model = reference_model(&mesh, 30.0, 20.0).expect("model");
    let mirror = model.mul(&Mat4::scale(Vec3::new(-1.0, 1.0, 1.0)));
    let (differ, _, culled) = compare(&mesh, &mirror, &camera);
    assert_eq!((differ, culled), (0, false));
    let big = Mat4::scale(Vec3::new(3.5, 3.5, 3.5)).mul(&model);
    let (differ, _, culled) = compare(&mesh, &big, &camera);
    assert_eq!((differ, culled), (0, false));
}

/// An icosphere with each vertex moved along its ray by its own factor,
/// then cut open by the half-space `p · dir > t`.
fn lumpy_holed(factors: &[f32], dir: [f32; 3], t: f32) -> HostMesh {
    let mut mesh = shapes::icosphere(2);
    for (p, &f) in mesh.positions.iter_mut().zip(factors.iter().cycle()) {
        *p = p.map(|c| c * f);
    }
    holed(&mesh, |p| {
        p.iter()
            .any(|q| q[0] * dir[0] + q[1] * dir[1] + q[2] * dir[2] > t)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any view, mirrored or not, from far off to with the eye inside, of
    /// a lumpy sphere with a hole cut: the culled frame covers what the
    /// two-sided one does, and differs only where a front face replaces a
    /// back one.
    #[test]
    fn lumpy_open_spheres_from_any_view(
        factors in prop::collection::vec(0.7f32..1.3, 1..40),
        dir in prop::array::uniform3(-1.0f32..1.0),
        t in 0.2f32..0.9,
        yaw in 0.0f32..360.0,
        pitch in -90.0f32..90.0,
        scale in 0.3f32..4.0,
        mirror in any::<bool>(),
        size in prop::sample::select(vec![(48u16, 40u16), (97, 61)]),
    ) {
        let length = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        prop_assume!(length > 0.1);
        let dir = dir.map(|c| c / length);
        let mesh = lumpy_holed(&factors, dir, t);
        let x = if mirror { -scale } else { scale };
        let model = Mat4::scale(Vec3::new(x, scale, scale)).mul(&turned(yaw, pitch));
        compare(&mesh, &model, &Camera::reference(size.0, size.1));
    }
}

#[test]
fn holes_that_touch_at_a_corner_are_not_capped() {
    let sphere = shapes::icosphere(0);
    let face = |f: usize| {
        let s = sphere.face_starts[f] as usize;
        sphere.corners[s..s + 3].to_vec()
    };
    // Two faces with exactly one corner in common.
    let n = sphere.face_starts.len();
    let (f, g) = (0..n)
        .flat_map(|f| (f + 1..n).map(move |g| (f, g)))
        .find(|&(f, g)| face(f).iter().filter(|c| face(g).contains(c)).count() == 1)
        .expect("two faces meeting at a corner");
    let (a, b) = (face(f), face(g));
    let mesh = holed(&sphere, |p| {
        let of = |corners: &[u16]| {
            corners
                .iter()
                .map(|&c| sphere.positions[usize::from(c)])
                .collect::<Vec<_>>()
        };
        p == of(&a).as_slice() || p == of(&b).as_slice()
    });
    assert_eq!(mesh.face_starts.len(), n - 2);
    assert!(mesh.closed_hull.is_none() && mesh.hull_caps.is_empty());
    // One of them alone is a hole with a rim of three edges.
    let one = holed(&sphere, |p| {
        p == a
            .iter()
            .map(|&c| sphere.positions[usize::from(c)])
            .collect::<Vec<_>>()
            .as_slice()
    });
    assert!(one.closed_hull.is_some());
    assert_eq!(one.hull_caps.len(), 1);
}

#[test]
fn a_lumpy_sphere_cut_open_is_capped() {
    for (factors, dir, t) in [
        (vec![1.0], [0.0, 1.0, 0.0], 0.5),
        (vec![0.9, 1.1, 1.0], [0.6, 0.8, 0.0], 0.4),
        (vec![0.8, 1.2], [0.0, 0.0, -1.0], 0.7),
    ] {
        let mesh = lumpy_holed(&factors, dir, t);
        assert!(mesh.closed_hull.is_some(), "{factors:?} {dir:?} {t}");
        assert!(!mesh.hull_caps.is_empty());
    }
}

/// A quantized mesh with a capped hull (as a user's own `Mesh` could
/// give): the integer front end places vertices by its own arithmetic, so
/// the caps cannot be placed as it does, and every face is drawn.
struct QuantizedWithCaps<'a> {
    inner: zline::QuantizedMesh<'a>,
    hull: zline::ClosedHull,
    caps: &'a [[[f32; 3]; 3]],
}

impl zline::Mesh for QuantizedWithCaps<'_> {
    fn vertex_count(&self) -> usize {
        self.inner.vertex_count()
    }
    fn position(&self, index: usize) -> [f32; 3] {
        self.inner.position(index)
    }
    fn face_count(&self) -> usize {
        self.inner.face_count()
    }
    fn face(&self, index: usize) -> &[u16] {
        self.inner.face(index)
    }
    fn quantized(&self) -> Option<zline::QuantizedView<'_>> {
        self.inner.quantized()
    }
    fn closed_hull(&self) -> Option<zline::ClosedHull> {
        Some(self.hull)
    }
    fn hull_caps(&self) -> &[[[f32; 3]; 3]] {
        self.caps
    }
}

#[test]
fn a_quantized_mesh_with_caps_draws_every_face() {
    use zline::Mesh;
    let mesh = open_sphere();
    let quantized = zline::host::QuantizedHostMesh::new(&mesh).expect("quantized");
    let inner = quantized.mesh().expect("mesh");
    let capped = QuantizedWithCaps {
        inner,
        hull: mesh.closed_hull.expect("hull"),
        caps: &mesh.hull_caps,
    };
    assert!(capped.quantized().is_some());
    let camera = Camera::reference(64, 48);
    // A view into neither hole: with the caps trusted, back faces would be
    // culled.
    let model = reference_model(&mesh, 30.0, 0.0).expect("model");
    let caps = mesh.capacities(64);
    let mut renderer =
        zline::host::host_renderer::<u32, Depth24>(&caps, 64, 48, NONE).expect("renderer");
    let stats = renderer
        .draw_mesh(&capped, &model, &camera, Cull::None, |f| f.face)
        .expect("draw");
    assert_eq!(stats.back_faces, 0);
}
