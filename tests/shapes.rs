//! The procedural meshes: counts, closed and consistently wound (every
//! directed edge appears once and its reverse once), and back-face culling
//! leaves what a closed shape looks like unchanged.

use std::collections::HashMap;

use zline::Depth24;
use zline::Mesh;
use zline::Shading;
use zline::host::HostMesh;
use zline::{Camera, Cull, reference_model};
use zline_lab::methods::HostScanline;
use zline_lab::shapes;

fn directed_edges(mesh: &HostMesh) -> HashMap<(u16, u16), u32> {
    let mut edges = HashMap::new();
    for f in 0..mesh.face_count() {
        let c = mesh.face(f);
        for k in 0..c.len() {
            *edges.entry((c[k], c[(k + 1) % c.len()])).or_insert(0) += 1;
        }
    }
    edges
}

/// Six times the signed volume: positive when faces wind counter-clockwise
/// seen from outside.
fn signed_volume(mesh: &HostMesh) -> f32 {
    let mut v = 0.0;
    for f in 0..mesh.face_count() {
        let c = mesh.face(f);
        let p = |k: usize| mesh.position(usize::from(c[k]));
        for k in 1..c.len() - 1 {
            let (a, b, d) = (p(0), p(k), p(k + 1));
            v += a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
                + a[2] * (b[0] * d[1] - b[1] * d[0]);
        }
    }
    v
}

fn assert_closed(mesh: &HostMesh) {
    assert!(signed_volume(mesh) > 0.0, "faces wind inwards");
    let edges = directed_edges(mesh);
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "edge {a}->{b} used {n} times");
        assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}->{b} has no twin");
    }
}

#[test]
fn counts() {
    assert_eq!(shapes::icosphere(3).face_count(), 1280);
    assert_eq!(shapes::icosphere(4).face_count(), 5120);
    assert_eq!(shapes::torus_knot(2, 3, 64, 8, 0.4).face_count(), 1024);
    assert_eq!(shapes::terrain(40).face_count(), 3200);
    assert_eq!(shapes::box_field(5).face_count(), 5 * 5 * 6 + 1);
}

#[test]
fn closed_shapes_are_consistently_wound() {
    assert_closed(&shapes::icosphere(2));
    assert_closed(&shapes::torus_knot(2, 3, 48, 6, 0.4));
    let mut boxes = shapes::box_field(1);
    // Without the floor, each box is closed.
    let floor = boxes.face_starts.pop().unwrap() as usize;
    boxes.corners.truncate(floor);
    assert_closed(&boxes);
}

#[test]
fn culling_back_faces_of_closed_shapes_changes_no_pixel() {
    // The host renderer is built on the stack before it moves to the heap.
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(compare_culled_and_unculled)
        .unwrap()
        .join()
        .unwrap();
}

fn compare_culled_and_unculled() {
    let mut host = HostScanline::<Depth24>::new(160, 120).unwrap();
    let camera = Camera::reference(160, 120);
    for mesh in [shapes::icosphere(3), shapes::torus_knot(2, 3, 64, 8, 0.4)] {
        let model = reference_model(&mesh, 30.0, 20.0).unwrap();
        let (none, _) = host
            .render(&mesh, &model, &camera, Cull::None, &Shading::FaceId)
            .unwrap();
        let all = host.frame().faces.clone();
        let (back, _) = host
            .render(&mesh, &model, &camera, Cull::Back, &Shading::FaceId)
            .unwrap();
        assert!(back.queued < none.queued && back.back_faces > 0);
        let differing = host
            .frame()
            .faces
            .iter()
            .zip(&all)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differing, 0,
            "pixels that change when back faces are culled"
        );
        assert!(all.iter().filter(|&&f| f != u32::MAX).count() > 2000);
    }
}

#[test]
fn spheres_of_the_classic_counts_are_exact_and_closed() {
    for n in [100, 2500, 60000] {
        let mesh = shapes::by_name(&format!("sphere-{n}")).expect("a sphere of n triangles");
        assert_eq!(mesh.face_count(), n);
        assert_closed(&mesh);
    }
    assert_eq!(shapes::uv_sphere(10, 6).map(|m| m.face_count()), Some(100));
    // Odd counts, counts beyond u16 indices and degenerate grids are refused.
    for bad in ["sphere-101", "sphere-200000", "sphere-0", "sphere-x"] {
        assert!(shapes::by_name(bad).is_none(), "{bad}");
    }
    assert!(shapes::uv_sphere(2, 6).is_none() && shapes::uv_sphere(10, 1).is_none());
}
