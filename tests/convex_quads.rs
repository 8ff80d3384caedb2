//! Planar faces of four corners that are strictly convex on screen are
//! drawn as two triangles (the scan's triangle path): they must cover
//! exactly the samples the quad covers, be judged and shaded once as a
//! face, and leave concave quads and quads with a shared plane to the
//! polygon path.

mod common;

use common::capture;
use proptest::prelude::*;
use zline::Mat4;
use zline::limits::{DEPTH_MAX, SUBPIXEL_STEPS};
use zline::{Camera, Cull, DrawStats, ProjectedVertex, VertexCache, draw_mesh, project_vertices};
use zline::{Depth16, Depth24, DepthFormat, Renderer, ScreenVertex};
use zline::{ScanArrays, TableArrays};
use zline::{SharedPlane, StaticMesh};

const W: usize = 64;
const H: u16 = 48;
const S: i32 = SUBPIXEL_STEPS;

type R<D> = Renderer<TableArrays<u32, 16, 8, 32>, ScanArrays<u32, D, W, 8, 16>>;

/// Whether the quad's four turns (cross products of consecutive edges)
/// all have one sign: strictly convex.
fn strictly_convex(q: &[ScreenVertex; 4]) -> bool {
    let turn = |k: usize| {
        let (a, b, c) = (q[k], q[(k + 1) % 4], q[(k + 2) % 4]);
        i64::from(b.x - a.x) * i64::from(c.y - b.y) - i64::from(b.y - a.y) * i64::from(c.x - b.x)
    };
    let t = [turn(0), turn(1), turn(2), turn(3)];
    t.iter().all(|&v| v > 0) || t.iter().all(|&v| v < 0)
}

/// The frame of `polygons` (each coloured 1) pushed as screen polygons.
fn frame<D: DepthFormat>(polygons: &[&[ScreenVertex]]) -> common::Frame<D::Value> {
    let mut renderer = R::<D>::with_height(H, 0).unwrap();
    for p in polygons {
        renderer.push_polygon_vertices(p, 1).unwrap();
    }
    capture(&mut renderer).0
}

/// A convex quad near the frame (corners on an ellipse, in order around
/// it either way, any size and slant: slivers too), its depths on one
/// plane (rounded to whole depth steps), steep planes included.
fn quad() -> impl Strategy<Value = [ScreenVertex; 4]> {
    (
        [0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0],
        (0.0f64..f64::from(W as u16), 0.0f64..f64::from(H)),
        (0.3f64..40.0, 0.3f64..40.0, 0.0f64..std::f64::consts::PI),
        (0.4f64..0.6, -0.001f64..0.001, -0.001f64..0.001),
        any::<bool>(),
    )
        .prop_map(
            |(turns, (cx, cy), (rx, ry, tilt), (z0, gx, gy), clockwise)| {
                let mut angles = turns.map(|t| t * std::f64::consts::TAU);
                angles.sort_by(f64::total_cmp);
                if clockwise {
                    angles.reverse();
                }
                angles.map(|a| {
                    let (u, v) = (rx * a.cos(), ry * a.sin());
                    let x = cx + u * tilt.cos() - v * tilt.sin();
                    let y = cy + u * tilt.sin() + v * tilt.cos();
                    // |gx·x| + |gy·y| < 0.001 · (104 + 88) < 0.2: z in (0, 1).
                    let z = z0 + gx * x + gy * y;
                    ScreenVertex {
                        x: (x * f64::from(S)).round() as i32,
                        y: (y * f64::from(S)).round() as i32,
                        z: (z * f64::from(DEPTH_MAX)).round() as u32,
                    }
                })
            },
        )
}

/// The quad and its two triangles cover the same samples, each sample by
/// one triangle only. With 16-bit depth each is within a step of the
/// exact plane (the 1-LSB bound), so they differ by two steps at most;
/// 24-bit steps also see the corners' depths rounded off the plane, so
/// only the samples are compared.
fn same_samples<D: DepthFormat>(
    q: &[ScreenVertex; 4],
    depth_steps: Option<i64>,
) -> Result<(), TestCaseError>
where
    D::Value: Into<i64>,
{
    let whole = frame::<D>(&[q]);
    let (first, second) = ([q[0], q[1], q[2]], [q[0], q[2], q[3]]);
    let halves = frame::<D>(&[&first, &second]);
    prop_assert_eq!(&whole.colors, &halves.colors);
    // Each half alone: no sample in both, none in neither.
    let (a, b) = (frame::<D>(&[&first]), frame::<D>(&[&second]));
    for (k, &c) in whole.colors.iter().enumerate() {
        let (in_a, in_b) = (a.colors[k] == 1, b.colors[k] == 1);
        prop_assert!(!(in_a && in_b), "sample {} in both halves", k);
        prop_assert_eq!(c == 1, in_a || in_b, "sample {}", k);
    }
    if let Some(steps) = depth_steps {
        for (a, b) in whole.depths.iter().zip(&halves.depths) {
            let (a, b): (i64, i64) = ((*a).into(), (*b).into());
            prop_assert!((a - b).abs() <= steps, "{} vs {}", a, b);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// The two triangles `0 1 2` and `0 2 3` of a strictly convex quad
    /// cover exactly the samples the quad does: none twice (the diagonal's
    /// samples go to one side by the fill rule), none missed.
    #[test]
    fn a_convex_quads_two_triangles_cover_its_samples(q in quad()) {
        // (Corners in order around an ellipse are convex; snapped to the
        // sub-pixel grid, a few of the thinnest are not.)
        prop_assume!(strictly_convex(&q));
        same_samples::<Depth16>(&q, Some(2))?;
        same_samples::<Depth24>(&q, None)?;
    }
}

/// Twice the signed area of a polygon (the shoelace sum).
fn twice_area(q: &[ScreenVertex]) -> i64 {
    (0..q.len())
        .map(|k| {
            let (a, b) = (q[k], q[(k + 1) % q.len()]);
            i64::from(a.x) * i64::from(b.y) - i64::from(b.x) * i64::from(a.y)
        })
        .sum()
}

/// The screen corners of face 0 of `mesh` under `model` and the reference
/// camera, when all four are projected.
fn screen_quad(mesh: &StaticMesh, model: &Mat4) -> Option<[ScreenVertex; 4]> {
    let camera = Camera::reference(W as u16, H);
    let mut projected = [ProjectedVertex::NonFinite; 4];
    project_vertices(mesh, model, &camera, 0, &mut projected).ok()?;
    let mut out = [ScreenVertex::default(); 4];
    for (slot, p) in out.iter_mut().zip(projected) {
        match p {
            ProjectedVertex::Screen(v) => *slot = v,
            _ => return None,
        }
    }
    Some(out)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(384))]

    /// Any flat face of four corners (random corners in the mesh's z = 0
    /// plane, in any order: convex, concave or crossed, either winding),
    /// drawn by `draw_mesh` under a random tilt: it is split into two
    /// triangles exactly when its snapped screen corners are strictly
    /// convex, it is judged a front or back face as one polygon, and it
    /// covers the samples of its screen polygon pushed whole.
    #[test]
    fn draw_mesh_splits_exactly_the_strictly_convex_quads(
        corners in [
            (-1.4f32..1.4, -1.0f32..1.0),
            (-1.4f32..1.4, -1.0f32..1.0),
            (-1.4f32..1.4, -1.0f32..1.0),
            (-1.4f32..1.4, -1.0f32..1.0),
        ],
        (yaw, pitch) in (-0.7f32..0.7, -0.7f32..0.7),
    ) {
        let positions = corners.map(|(x, y)| [x, y, 0.0]);
        let mesh = StaticMesh::new(&positions, &[0, 1, 2, 3], &[0]).unwrap();
        let model = Mat4::rotation_y(yaw).mul(&Mat4::rotation_x(pitch));
        let q = screen_quad(&mesh, &model);
        prop_assume!(q.is_some());
        let q = q.unwrap();
        let area = twice_area(&q);
        prop_assume!(area != 0);
        // The facing square of `POSITIONS` is a front face: a quad whose
        // area has its sign is one too.
        let facing = StaticMesh::new(&POSITIONS, &[0, 1, 2, 3], &[0]).unwrap();
        let facing = twice_area(&screen_quad(&facing, &Mat4::IDENTITY).unwrap());
        let front = (area < 0) == (facing < 0);
        let color = if front { 1 } else { 2 };

        let camera = Camera::reference(W as u16, H);
        let mut renderer = R::<Depth16>::with_height(H, 0).unwrap();
        let mut cache: VertexCache<16> = VertexCache::new();
        let mut fronts = Vec::new();
        let stats = draw_mesh(
            &mut renderer,
            &mut cache,
            &mesh,
            &model,
            &camera,
            Cull::None,
            |f| {
                fronts.push(f.front);
                if f.front { 1 } else { 2 }
            },
        )
        .unwrap();
        let drawn = capture(&mut renderer).0;
        prop_assert_eq!(stats.convex_quads, u32::from(strictly_convex(&q)), "{:?}", q);
        prop_assert!(fronts.len() <= 1, "shaded {} times", fronts.len());

        let mut whole = R::<Depth16>::with_height(H, 0).unwrap();
        whole.push_polygon_vertices(&q, color).unwrap();
        let whole = capture(&mut whole).0;
        prop_assert_eq!(&drawn.colors, &whole.colors, "{:?}", q);
        if whole.colors.iter().any(|&c| c != 0) {
            prop_assert_eq!(&fronts, &vec![front]);
        }
        for (a, b) in drawn.depths.iter().zip(&whole.depths) {
            prop_assert!((i64::from(*a) - i64::from(*b)).abs() <= 2, "{} vs {}", a, b);
        }
    }
}

/// Draws `mesh` (identity model, the reference camera) with every face
/// shaded 1 + its index, recording whether each shading call was for a
/// front face.
fn draw(mesh: &StaticMesh, cull: Cull) -> (common::Frame<u32>, DrawStats, Vec<bool>) {
    let camera = Camera::reference(W as u16, H);
    let mut renderer = R::<Depth24>::with_height(H, 0).unwrap();
    let mut cache: VertexCache<16> = VertexCache::new();
    let mut fronts = Vec::new();
    let stats = draw_mesh(
        &mut renderer,
        &mut cache,
        mesh,
        &Mat4::IDENTITY,
        &camera,
        cull,
        |f| {
            fronts.push(f.front);
            f.face + 1
        },
    )
    .unwrap();
    (capture(&mut renderer).0, stats, fronts)
}

/// A square facing the camera (counter-clockwise), an arrowhead (concave)
/// beside it, and the square again, turned away.
const POSITIONS: [[f32; 3]; 12] = [
    [-1.5, -0.5, 0.0],
    [-0.5, -0.5, 0.0],
    [-0.5, 0.5, 0.0],
    [-1.5, 0.5, 0.0],
    [0.2, -0.6, 0.0],
    [1.4, 0.0, 0.0],
    [0.2, 0.6, 0.0],
    [0.6, 0.0, 0.0],
    [-1.5, -0.5, -0.5],
    [-1.5, 0.5, -0.5],
    [-0.5, 0.5, -0.5],
    [-0.5, -0.5, -0.5],
];

#[test]
fn a_convex_quad_is_judged_and_shaded_once_and_a_concave_one_stays_whole() {
    let mesh = StaticMesh::new(&POSITIONS, &[0, 1, 2, 3, 4, 5, 6, 7], &[0, 4]).unwrap();
    let (frame, stats, fronts) = draw(&mesh, Cull::Back);
    assert_eq!((stats.convex_quads, stats.queued), (1, 3));
    assert_eq!(fronts, [true, true], "one shading call per face");
    let seen = |c: u32| frame.colors.iter().filter(|&&v| v == c).count();
    assert!(seen(1) > 100 && seen(2) > 50, "{} {}", seen(1), seen(2));
    // The square, drawn as two triangle faces of one colour, is the same
    // frame pixel for pixel (colours and depths).
    let halves = StaticMesh::new(&POSITIONS, &[0, 1, 2, 0, 2, 3, 4, 5, 6, 7], &[0, 3, 6]).unwrap();
    let (same, _, _) = draw(&halves, Cull::Back);
    for (k, (&a, &b)) in frame.colors.iter().zip(&same.colors).enumerate() {
        let b = match b {
            2 => 1, // the second triangle of the square
            3 => 2, // the arrowhead
            other => other,
        };
        assert_eq!(a, b, "pixel {k}");
    }
    assert_eq!(frame.depths, same.depths);
    // The arrowhead from each of its corners: concave whichever corner is
    // the dent, so never split.
    let whole = StaticMesh::new(&POSITIONS, &[4, 5, 6, 7], &[0]).unwrap();
    let (arrow, _, _) = draw(&whole, Cull::Back);
    for corners in [[5, 6, 7, 4], [6, 7, 4, 5], [7, 4, 5, 6]] {
        let mesh = StaticMesh::new(&POSITIONS, &corners, &[0]).unwrap();
        let (frame, stats, _) = draw(&mesh, Cull::Back);
        assert_eq!((stats.convex_quads, stats.queued), (0, 1), "{corners:?}");
        assert_eq!(frame.colors, arrow.colors, "{corners:?}");
    }
}

#[test]
fn a_convex_quad_turned_away_is_one_back_face() {
    let mesh = StaticMesh::new(&POSITIONS, &[8, 9, 10, 11], &[0]).unwrap();
    let (frame, stats, fronts) = draw(&mesh, Cull::Back);
    assert_eq!(
        (stats.back_faces, stats.convex_quads, stats.queued),
        (1, 0, 0)
    );
    assert!(fronts.is_empty());
    assert!(frame.colors.iter().all(|&c| c == 0));
    let (frame, stats, fronts) = draw(&mesh, Cull::None);
    assert_eq!(
        (stats.back_faces, stats.convex_quads, stats.queued),
        (0, 1, 2)
    );
    assert_eq!(fronts, [false], "shaded once, as a back face");
    assert!(frame.colors.iter().filter(|&&c| c == 1).count() > 100);
}

#[test]
fn a_quad_with_a_shared_plane_stays_whole() {
    const SHARED: [SharedPlane; 1] = [SharedPlane {
        face: 0,
        vertices: [0, 1, 2],
    }];
    let mesh = StaticMesh::new(&POSITIONS, &[0, 1, 2, 3], &[0])
        .unwrap()
        .with_shared_planes(&SHARED)
        .unwrap();
    let (_, stats, _) = draw(&mesh, Cull::None);
    assert_eq!(
        (stats.convex_quads, stats.queued, stats.shared_planes),
        (0, 1, 1)
    );
}

/// A convex quad that does not fit is an error naming the face, never a
/// quad drawn in part without one: with room for one polygon, its first
/// triangle is queued (as `draw_mesh` documents for faces queued as
/// triangles) and the second is `PolygonTableFull`.
#[test]
fn a_convex_quad_that_does_not_fit_is_an_error() {
    let mesh = StaticMesh::new(&POSITIONS, &[0, 1, 2, 3], &[0]).unwrap();
    let camera = Camera::reference(W as u16, H);
    let mut renderer: Renderer<TableArrays<u32, 16, 1, 32>, ScanArrays<u32, Depth24, W, 8, 16>> =
        Renderer::with_height(H, 0).unwrap();
    let mut cache: VertexCache<16> = VertexCache::new();
    let result = draw_mesh(
        &mut renderer,
        &mut cache,
        &mesh,
        &Mat4::IDENTITY,
        &camera,
        Cull::None,
        |f| f.face + 1,
    );
    let error = result.unwrap_err();
    assert_eq!(
        (error.error, error.face),
        (zline::Error::PolygonTableFull, Some(0))
    );
    assert_eq!(renderer.polygon_count(), 1);
}
