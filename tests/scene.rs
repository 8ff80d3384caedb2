//! The mesh-to-screen pipeline: culling, clipping, projection and the
//! depth it hands to the core.

mod common;

use common::capture;
use zline::limits::DEPTH_ONE;
use zline::{
    Camera, Cull, DrawError, DrawStats, VertexCache, draw_mesh, reference_model,
    reference_model_around,
};
use zline::{Depth24, Renderer};
use zline::{Mat4, Vec3};
use zline::{ScanArrays, TableArrays};
use zline::{SharedPlane, StaticMesh};

/// Unit cube, quads wound counter-clockwise seen from outside.
static CUBE: StaticMesh<'static> = match StaticMesh::new(
    &[
        [-1.0, -1.0, -1.0],
        [1.0, -1.0, -1.0],
        [1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, 1.0],
    ],
    &[
        4, 5, 6, 7, // +z
        1, 0, 3, 2, // -z
        5, 1, 2, 6, // +x
        0, 4, 7, 3, // -x
        7, 6, 2, 3, // +y
        0, 1, 5, 4, // -y
    ],
    &[0, 4, 8, 12, 16, 20],
) {
    Ok(m) => m,
    Err(_) => panic!("bad cube"),
};

type R = Renderer<TableArrays<u32, 256, 64, 256>, ScanArrays<u32, Depth24, 96, 64, 256>>;

fn draw(
    mesh: &StaticMesh,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
) -> (common::Frame<u32>, DrawStats) {
    let mut renderer = R::new(camera.width, camera.height, 0).unwrap();
    let mut cache: VertexCache<64> = VertexCache::new();
    let stats = draw_mesh(&mut renderer, &mut cache, mesh, model, camera, cull, |f| {
        f.face + 1
    })
    .unwrap();
    (capture(&mut renderer).0, stats)
}

#[test]
fn cube_shows_three_faces_and_culling_changes_nothing_visible() {
    let camera = Camera::reference(96, 72);
    let model = reference_model(&CUBE, 30.0, 20.0).unwrap();
    let (culled, stats) = draw(&CUBE, &model, &camera, Cull::Back);
    // Each front face, a convex quad on screen, is queued as two triangles.
    assert_eq!(
        (
            stats.faces,
            stats.convex_quads,
            stats.queued,
            stats.back_faces
        ),
        (6, 3, 6, 3)
    );
    // Ry(30°) turns +z to (0.5, 0, 0.87) and -x to (-0.87, 0, 0.5), both
    // towards the eye; Rx(20°) tips +y towards it: faces 0, 3 and 4.
    let mut seen: Vec<u32> = culled.colors.iter().copied().filter(|&c| c != 0).collect();
    seen.sort_unstable();
    seen.dedup();
    assert_eq!(seen, [1, 4, 5]);
    let (all, stats) = draw(&CUBE, &model, &camera, Cull::None);
    assert_eq!(
        (stats.convex_quads, stats.queued, stats.back_faces),
        (6, 12, 0)
    );
    assert_eq!(
        all.colors, culled.colors,
        "a closed convex mesh looks the same with back faces culled"
    );
}

/// Depth must be z_ndc, affine in screen space: compare every pixel of a
/// steeply tilted quad with z_ndc from an f64 ray cast.
#[test]
fn depth_is_z_ndc_at_every_pixel() {
    let camera = Camera::reference(96, 72);
    let quad = StaticMesh::new(
        &[
            [-3.0, -1.0, 1.0],
            [3.0, -1.0, 1.0],
            [3.0, 1.0, -6.0],
            [-3.0, 1.0, -6.0],
        ],
        &[0, 1, 2, 3],
        &[0],
    )
    .unwrap();
    let (frame, stats) = draw(&quad, &Mat4::IDENTITY, &camera, Cull::None);
    // Drawn as its two triangles, each with the plane through its corners.
    assert_eq!((stats.convex_quads, stats.queued), (1, 2));
    let (n, f) = (0.1f64, 10.0f64);
    let t = (22.5f64).to_radians().tan();
    let aspect = 96.0 / 72.0;
    let mut checked = 0;
    for j in 0..72 {
        for i in 0..96 {
            if frame.color(i, j) == 0 {
                continue;
            }
            // Ray from the eye (0, 0, 3) through the pixel centre.
            let xn = (i as f64 + 0.5) / 96.0 * 2.0 - 1.0;
            let yn = 1.0 - (j as f64 + 0.5) / 72.0 * 2.0;
            let d = [xn * t * aspect, yn * t, -1.0];
            // The quad's plane is 7y + 2z = -5; the ray is (0, 0, 3) + s·d.
            let s = (-5.0 - 2.0 * 3.0) / (7.0 * d[1] + 2.0 * d[2]);
            let z_view = s * d[2];
            // z_clip = -(f+n)/(f-n)·z_view - 2fn/(f-n), w = -z_view.
            let z_ndc = ((f + n) / (f - n) * z_view + 2.0 * f * n / (f - n)) / z_view;
            let expected = (z_ndc + 1.0) / 2.0 * f64::from(DEPTH_ONE);
            let got = f64::from(frame.depth(i, j));
            // f32 vertices and matrices: a few input steps of error, where
            // interpolating view-space z would be off by thousands.
            assert!(
                (got - expected).abs() < 24.0,
                "pixel ({i}, {j}): {got} vs {expected}"
            );
            checked += 1;
        }
    }
    assert!(checked > 2000, "{checked}");
}

/// A floor from far behind the eye to beyond the far plane: cut by the
/// near and far planes, it covers exactly the pixels whose ray meets the
/// floor between them (give or take the pixels along the cut lines).
#[test]
fn floor_crossing_near_and_far_planes_is_clipped_not_dropped() {
    let camera = Camera::perspective(Mat4::IDENTITY, 45.0, 96, 72, 0.1, 10.0);
    let floor = StaticMesh::new(
        &[
            [-50.0, -1.0, 40.0],
            [50.0, -1.0, 40.0],
            [50.0, -1.0, -40.0],
            [-50.0, -1.0, -40.0],
        ],
        &[0, 1, 2, 3],
        &[0],
    )
    .unwrap();
    let (frame, stats) = draw(&floor, &Mat4::IDENTITY, &camera, Cull::None);
    assert_eq!((stats.clipped, stats.queued), (1, 1));
    let t = (22.5f64).to_radians().tan();
    let (mut wrong, mut covered) = (0, 0);
    for j in 0..72 {
        let yn = 1.0 - (j as f64 + 0.5) / 72.0 * 2.0;
        for i in 0..96 {
            let dy = yn * t;
            // Hit distance along -z where the ray meets y = -1.
            let dist = if dy < 0.0 { -1.0 / dy } else { f64::INFINITY };
            let inside = dist <= 10.0;
            let margin = (dist - 10.0).abs() / 10.0 < 0.05;
            let drawn = frame.color(i, j) != 0;
            covered += usize::from(drawn);
            if drawn != inside && !margin {
                wrong += 1;
            }
        }
    }
    assert_eq!(wrong, 0);
    assert!(covered > 96 * 20, "{covered}");
}

#[test]
fn huge_triangle_beyond_the_guard_band_is_clipped_to_it() {
    let camera = Camera::perspective(Mat4::IDENTITY, 45.0, 96, 72, 0.1, 10.0);
    let tri = StaticMesh::new(
        &[[-1e4, -1e4, -2.0], [1e4, -1e4, -2.0], [0.0, 1e4, -2.0]],
        &[0, 1, 2],
        &[0],
    )
    .unwrap();
    let (frame, stats) = draw(&tri, &Mat4::IDENTITY, &camera, Cull::Back);
    assert_eq!((stats.clipped, stats.queued), (1, 1));
    assert!(
        frame.colors.iter().all(|&c| c == 1),
        "covers the whole frame"
    );
}

#[test]
fn mesh_behind_the_camera_is_culled_and_nan_is_skipped() {
    let camera = Camera::reference(96, 72);
    let behind = Mat4::translation(Vec3::new(0.0, 0.0, 10.0))
        .mul(&reference_model(&CUBE, 0.0, 0.0).unwrap());
    let (frame, stats) = draw(&CUBE, &behind, &camera, Cull::None);
    assert_eq!((stats.outside, stats.queued), (6, 0));
    assert!(frame.colors.iter().all(|&c| c == 0));
    let nan = Mat4::rotation_y(f32::NAN);
    let (frame, stats) = draw(&CUBE, &nan, &camera, Cull::None);
    assert_eq!((stats.non_finite, stats.queued), (6, 0));
    assert!(frame.colors.iter().all(|&c| c == 0));
}

#[test]
fn a_cache_smaller_than_the_mesh_is_an_error() {
    let camera = Camera::reference(96, 72);
    let mut renderer = R::new(96, 72, 0).unwrap();
    let mut cache: VertexCache<4> = VertexCache::new();
    let result = draw_mesh(
        &mut renderer,
        &mut cache,
        &CUBE,
        &Mat4::IDENTITY,
        &camera,
        Cull::None,
        |_| 1,
    );
    assert_eq!(
        result,
        Err(DrawError {
            face: None,
            error: zline::Error::VertexCacheTooSmall
        })
    );
}

/// A square in z = 0 with two overlapping faces of the same plane on it
/// (decals), all three sharing the square's plane; vertex 10, far up the
/// plane, spans a plane that cannot be projected.
static DECALS: StaticMesh<'static> = {
    const PLANE: [u16; 3] = [0, 1, 2];
    static SHARED: [SharedPlane; 3] = [
        SharedPlane {
            face: 0,
            vertices: PLANE,
        },
        SharedPlane {
            face: 1,
            vertices: PLANE,
        },
        SharedPlane {
            face: 2,
            vertices: [0, 1, 10],
        },
    ];
    match StaticMesh::new(
        &[
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [-0.8, -0.7, 0.0],
            [0.6, -0.5, 0.0],
            [0.1, 0.9, 0.0],
            [-0.5, 0.3, 0.0],
            [0.9, -0.9, 0.0],
            [0.7, 0.6, 0.0],
            [0.0, 1.0e6, 0.0],
        ],
        &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9],
        &[0, 4, 7],
    ) {
        Ok(m) => match m.with_shared_planes(&SHARED) {
            Ok(m) => m,
            Err(_) => panic!("bad shared planes"),
        },
        Err(_) => panic!("bad decals"),
    }
};

#[test]
fn faces_sharing_a_plane_keep_the_first_on_every_view() {
    let camera = Camera::reference(96, 72);
    for step in 0..12 {
        let (yaw, pitch) = (-40.0 + 7.3 * step as f32, 25.0 - 4.1 * step as f32);
        // Framed on the square (vertex 10 would make the mesh's sphere
        // huge).
        let model = reference_model_around(Vec3::default(), 1.5, yaw, pitch);
        let (frame, stats) = draw(&DECALS, &model, &camera, Cull::None);
        // Faces 0 and 1 take the square's plane; face 2's plane needs a
        // vertex a million units up, which is clipped: it keeps its own.
        assert_eq!((stats.shared_planes, stats.unshared_planes), (2, 1));
        let drawn: Vec<u32> = frame.colors.iter().copied().filter(|&c| c != 0).collect();
        assert!(drawn.len() > 1000);
        // Face 1 (the decal added second) never shows through the square.
        assert!(drawn.iter().all(|&c| c != 2), "view {yaw}/{pitch}");
    }
}

/// Two large triangles facing opposite ways and two tiny ones (far below a
/// pixel, between the samples) facing opposite ways.
static FACING: StaticMesh<'static> = match StaticMesh::new(
    &[
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.30, 0.30, 0.0],
        [0.31, 0.30, 0.0],
        [0.30, 0.31, 0.0],
    ],
    &[
        0, 1, 2, // large, counter-clockwise from +z
        0, 2, 1, // large, clockwise
        3, 4, 5, // tiny, counter-clockwise
        3, 5, 4, // tiny, clockwise
    ],
    &[0, 3, 6, 9],
) {
    Ok(m) => m,
    Err(_) => panic!("bad mesh"),
};

#[test]
fn back_faces_are_culled_wherever_they_lie_and_only_kept_faces_are_shaded() {
    let camera = Camera::reference(96, 72);
    let model = reference_model(&FACING, 0.0, 0.0).unwrap();
    let run = |cull: Cull| {
        let mut renderer = R::new(camera.width, camera.height, 0).unwrap();
        let mut cache: VertexCache<64> = VertexCache::new();
        let mut shaded = Vec::new();
        let stats = draw_mesh(
            &mut renderer,
            &mut cache,
            &FACING,
            &model,
            &camera,
            cull,
            |f| {
                shaded.push(f.face);
                f.face + 1
            },
        )
        .unwrap();
        (stats, shaded)
    };
    let (none, shaded) = run(Cull::None);
    // Without culling: both large faces drawn, both tiny ones cover no
    // sample; the shading closure sees only what is drawn.
    assert_eq!(
        (none.queued, none.back_faces, none.off_screen),
        (2, 0, 2),
        "{none:?}"
    );
    assert_eq!(shaded, [0, 1]);
    let (back, shaded) = run(Cull::Back);
    // Culled: one large face drawn; both back faces culled, the tiny one
    // too (before its sample test); the tiny front face covers no sample.
    assert_eq!(
        (back.queued, back.back_faces, back.off_screen),
        (1, 2, 1),
        "{back:?}"
    );
    assert_eq!(shaded.len(), 1);
}
