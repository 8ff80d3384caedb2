//! Clipping against the near and far planes and the guard band: faces are
//! cut, never lost, and every cut edge lands within one step of the
//! 1/256-pixel grid of the exact edge (float64, computed in view space
//! independently of the pipeline's clip-space arithmetic). Over the whole
//! `f32` range: a face within the clipper's range (`CLIP_RANGE`) is drawn
//! as a reference in double-double arithmetic draws it, and a face beyond
//! it is refused with `Error::ClipRange`, never drawn wrong or dropped.

mod common;

use common::{Recorder, capture};
use proptest::prelude::*;
use zline::limits::CLIP_BAND_PX;
use zline::limits::SUBPIXEL_STEPS;
use zline::{CLIP_RANGE, Camera, Cull, DrawError, VertexCache, draw_mesh};
use zline::{Depth24, Error, Renderer};
use zline::{Mat4, Vec3};
use zline::{Mesh, StaticMesh};
use zline::{ScanArrays, TableArrays};
use zline_lab::methods::clip_reference::{FaceError, clipped_face, compare_face};

type R = Renderer<TableArrays<u32, 64, 16, 64>, ScanArrays<u32, Depth24, 160, 16, 16>>;

/// A line `a·x + b·y = c` in pixels, with `(a, b)` a unit normal.
#[derive(Debug, Clone, Copy)]
struct Line {
    a: f64,
    b: f64,
    c: f64,
}

impl Line {
    fn through(p: [f64; 2], q: [f64; 2]) -> Self {
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let len = (dx * dx + dy * dy).sqrt();
        let (a, b) = (-dy / len, dx / len);
        Self {
            a,
            b,
            c: a * p[0] + b * p[1],
        }
    }

    fn distance(&self, p: [f64; 2]) -> f64 {
        (self.a * p[0] + self.b * p[1] - self.c).abs()
    }
}

/// A perspective camera looking down -Z from the origin, as the exact
/// reference sees it.
#[derive(Debug, Clone, Copy)]
struct View {
    fov_deg: f64,
    width: f64,
    height: f64,
    near: f64,
}

impl View {
    /// Screen position (pixels) of a view-space point in front of the eye.
    fn project(&self, p: [f64; 3]) -> [f64; 2] {
        let t = (self.fov_deg.to_radians() / 2.0).tan();
        let aspect = self.width / self.height;
        let (x, y) = (p[0] / (-p[2] * t * aspect), p[1] / (-p[2] * t));
        [(x + 1.0) * 0.5 * self.width, (1.0 - y) * 0.5 * self.height]
    }

    /// The bounding box `[x0, x1, y0, y1]` (pixels) of the part of `tri`
    /// between the near plane and `far` and inside the frame, cut and
    /// projected in f64; `None` when no part is.
    fn visible_box(&self, tri: &[[f64; 3]; 3], far: f64) -> Option<[f64; 4]> {
        // Sutherland-Hodgman against depth >= near, then depth <= far.
        let cut = |polygon: Vec<[f64; 3]>, keep: &dyn Fn([f64; 3]) -> f64| {
            let mut out = Vec::new();
            for k in 0..polygon.len() {
                let (p, q) = (polygon[k], polygon[(k + 1) % polygon.len()]);
                let (dp, dq) = (keep(p), keep(q));
                if dp >= 0.0 {
                    out.push(p);
                }
                if (dp >= 0.0) != (dq >= 0.0) {
                    let t = dp / (dp - dq);
                    out.push([0, 1, 2].map(|i| p[i] + (q[i] - p[i]) * t));
                }
            }
            out
        };
        let near = self.near;
        let polygon = cut(tri.to_vec(), &|p| -p[2] - near);
        let polygon = cut(polygon, &|p| far + p[2]);
        // Projected (lines stay lines in front of the eye), then cut to the
        // frame.
        let mut polygon: Vec<[f64; 3]> = polygon
            .into_iter()
            .map(|p| {
                let [x, y] = self.project(p);
                [x, y, 0.0]
            })
            .collect();
        let (w, h) = (self.width, self.height);
        for side in [
            &(|p: [f64; 3]| p[0]) as &dyn Fn([f64; 3]) -> f64,
            &|p| w - p[0],
            &|p| p[1],
            &|p| h - p[1],
        ] {
            polygon = cut(polygon, side);
        }
        if polygon.len() < 3 {
            return None;
        }
        let mut b = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for [x, y, _] in polygon {
            b = [b[0].min(x), b[1].max(x), b[2].min(y), b[3].max(y)];
        }
        Some(b)
    }

    /// The exact screen lines a clipped triangle's edges may lie on: each
    /// edge's projection (where part of it is in front of the near plane),
    /// the near plane's cut, and the guard band's four sides.
    fn lines(&self, tri: &[[f64; 3]; 3]) -> Vec<Line> {
        let mut lines = Vec::new();
        let lerp = |p: [f64; 3], q: [f64; 3], t: f64| {
            [
                p[0] + (q[0] - p[0]) * t,
                p[1] + (q[1] - p[1]) * t,
                p[2] + (q[2] - p[2]) * t,
            ]
        };
        let mut near_points = Vec::new();
        for k in 0..3 {
            let (p, q) = (tri[k], tri[(k + 1) % 3]);
            let (dp, dq) = (-p[2] - self.near, -q[2] - self.near);
            if (dp >= 0.0) != (dq >= 0.0) {
                near_points.push(lerp(p, q, dp / (dp - dq)));
            }
            // Two points of the edge in front of the near plane, if any.
            let front: Vec<[f64; 3]> = [0.0, 0.25, 0.5, 0.75, 1.0]
                .iter()
                .map(|&t| lerp(p, q, t))
                .filter(|r| -r[2] > self.near)
                .collect();
            if front.len() >= 2 {
                lines.push(Line::through(
                    self.project(front[0]),
                    self.project(front[front.len() - 1]),
                ));
            } else if front.len() == 1 && near_points.last().is_some() {
                let n = *near_points.last().unwrap();
                lines.push(Line::through(
                    self.project(front[0]),
                    self.project(lerp(n, front[0], 0.5)),
                ));
            }
        }
        if near_points.len() == 2 {
            lines.push(Line::through(
                self.project(near_points[0]),
                self.project(near_points[1]),
            ));
        }
        let g = f64::from(CLIP_BAND_PX);
        let (w, h) = (self.width, self.height);
        for (x, y) in [(w - g, 0.0), (g, 0.0)] {
            lines.push(Line::through([x, y], [x, y + 1.0]));
        }
        for (x, y) in [(0.0, h - g), (0.0, g)] {
            lines.push(Line::through([x, y], [x + 1.0, y]));
        }
        lines
    }
}

/// Clips `tri` (view space, camera at the origin) through the pipeline
/// and checks that every edge of every polygon it makes lies, at both
/// ends, within one sub-pixel step of one exact line. Returns the number
/// of polygons made.
fn check_cut_edges(tri: [[f32; 3]; 3], view: View, far: f32) -> usize {
    let (w, h) = (view.width as u16, view.height as u16);
    let camera = Camera::perspective(
        Mat4::IDENTITY,
        view.fov_deg as f32,
        w,
        h,
        view.near as f32,
        far,
    );
    let mesh = StaticMesh::new(&tri, &[0, 1, 2], &[0]).unwrap();
    let mut tables = Recorder::new(w, h);
    let mut cache: VertexCache<3> = VertexCache::new();
    let stats = draw_mesh(
        &mut tables,
        &mut cache,
        &mesh,
        &Mat4::IDENTITY,
        &camera,
        Cull::None,
        |_| 1,
    )
    .unwrap();
    assert_eq!(stats.non_finite, 0, "{tri:?}: a corner was lost");
    let exact = tri.map(|p| p.map(f64::from));
    // The part in front of the near plane, cut and projected in f64: when
    // its bounding box holds a sample of the frame (with a margin for the
    // sub-pixel grid), the face is queued, or its snapped corners have no
    // area; it is never judged outside or dropped.
    if let Some([x0, x1, y0, y1]) = view.visible_box(&exact, f64::from(far)) {
        let margin = 0.02;
        let holds_sample = |low: f64, high: f64| {
            let first = (low + margin - 0.5).ceil() + 0.5;
            first <= high - margin
        };
        if holds_sample(x0, x1) && holds_sample(y0, y1) {
            assert_eq!(stats.outside, 0, "{tri:?}");
            assert!(
                tables.polygons.len() + stats.degenerate as usize >= 1,
                "{tri:?}: a face with samples on screen was dropped: {stats:?}"
            );
        }
    }
    if exact.iter().any(|p| -p[2] <= view.near) && stats.outside == 0 {
        assert_eq!(stats.clipped, 1, "{tri:?}: a corner behind the near plane");
    }
    let lines = view.lines(&exact);
    let step = 1.0 / f64::from(SUBPIXEL_STEPS);
    for (corners, _) in &tables.polygons {
        let px: Vec<[f64; 2]> = corners
            .iter()
            .map(|v| [f64::from(v.x) * step, f64::from(v.y) * step])
            .collect();
        for k in 0..px.len() {
            let (p, q) = (px[k], px[(k + 1) % px.len()]);
            let best = lines
                .iter()
                .map(|l| l.distance(p).max(l.distance(q)))
                .fold(f64::INFINITY, f64::min);
            assert!(
                best <= step,
                "{tri:?}: edge {p:?}-{q:?} is {:.4} px off every exact line",
                best
            );
        }
    }
    tables.polygons.len()
}

#[test]
fn issue_7_item_3_cut_edges_land_on_the_exact_edges() {
    // Eye at the origin looking down -Z, fov 120°, near 0.01, 64x48: two
    // corners behind the eye, one in front. In f32 the cut edges moved by
    // 3 to 4 pixels.
    let tri = [
        [535.9, 716.7, 788.9],
        [-1031.6, -951.4, -1377.3],
        [1155.5, -106.8, 774.9],
    ];
    let view = View {
        fov_deg: 120.0,
        width: 64.0,
        height: 48.0,
        near: 0.01,
    };
    assert_eq!(check_cut_edges(tri, view, 10_000.0), 1);
}

#[test]
fn issue_7_item_3_huge_ground_quad_is_cut_not_dropped() {
    // A ground quad at y = -1 reaching 1e7 in every direction, eye at
    // (0, 0, 3) looking at the origin, fov 60°, near 0.1, far 100,
    // 160x120. In f32 the cut corner projected to nothing and the whole
    // face was dropped as non-finite.
    let quad = StaticMesh::new(
        &[
            [-1e7, -1.0, 1e7],
            [1e7, -1.0, 1e7],
            [1e7, -1.0, -1e7],
            [-1e7, -1.0, -1e7],
        ],
        &[0, 1, 2, 3],
        &[0],
    )
    .unwrap();
    let (near, far) = (0.1f64, 100.0f64);
    let view = Mat4::look_at(
        Vec3::new(0.0, 0.0, 3.0),
        Vec3::default(),
        Vec3::new(0.0, 1.0, 0.0),
    );
    let camera = Camera::perspective(view, 60.0, 160, 120, near as f32, far as f32);
    let mut renderer = R::new(160, 120, 0).unwrap();
    let mut cache: VertexCache<4> = VertexCache::new();
    let stats = draw_mesh(
        &mut renderer,
        &mut cache,
        &quad,
        &Mat4::IDENTITY,
        &camera,
        Cull::None,
        |_| 1,
    )
    .unwrap();
    assert_eq!((stats.non_finite, stats.clipped, stats.queued), (0, 1, 1));
    let (frame, _) = capture(&mut renderer);
    // Exact coverage: the pixel's ray (view space = world shifted by -3
    // in z) meets y = -1 at view distance t, drawn when near <= t <= far.
    let t = (30.0f64).to_radians().tan();
    let (mut covered, mut wrong) = (0, 0);
    for j in 0..120 {
        for i in 0..160 {
            let dy = (1.0 - (j as f64 + 0.5) / 120.0 * 2.0) * t;
            let dist = if dy < 0.0 { -1.0 / dy } else { f64::INFINITY };
            // Along the far cut, allow the sub-pixel grid's rounding.
            let at_far_cut = (dist - far).abs() / far < 0.02;
            let expected = dist >= near && dist <= far;
            let drawn = frame.color(i, j) == 1;
            covered += usize::from(drawn);
            if drawn != expected && !at_far_cut {
                wrong += 1;
            }
        }
    }
    assert_eq!(wrong, 0);
    assert!(
        covered > 160 * 40,
        "the ground fills the lower part: {covered}"
    );
}

/// The clipper's size of a face (see `CLIP_RANGE`): the largest sum of
/// the absolute terms of a corner's transform, in f64.
fn clip_size(model: &Mat4, camera: &Camera, corners: &[[f32; 3]]) -> f64 {
    let abs = |m: &Mat4| m.m.map(|row| row.map(|v| f64::from(v).abs()));
    let mul = |a: [[f64; 4]; 4], b: [[f64; 4]; 4]| {
        let mut r = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                r[i][j] = (0..4).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        r
    };
    let m = mul(abs(&camera.projection), mul(abs(&camera.view), abs(model)));
    corners
        .iter()
        .flat_map(|p| {
            let p = [
                f64::from(p[0]).abs(),
                f64::from(p[1]).abs(),
                f64::from(p[2]).abs(),
                1.0,
            ];
            m.map(|row| (0..4).map(|k| row[k] * p[k]).sum::<f64>())
        })
        .fold(0.0, f64::max)
}

/// What became of one face drawn through a perspective camera.
#[derive(Debug)]
enum Outcome {
    /// Drawn: how far from the reference.
    Drawn(FaceError),
    /// Refused as beyond the clipper's range.
    Refused,
}

/// Draws the face `corners` with `model` through `camera` (a perspective
/// camera with near distance `near`) and judges it against the
/// double-double reference. Refusal and drawing must follow the range
/// rule: refused only beyond `CLIP_RANGE · near`, drawn within it.
fn judge_face(model: &Mat4, camera: &Camera, near: f64, corners: &[[f32; 3]]) -> Outcome {
    let n = corners.len() as u16;
    let indices: Vec<u16> = (0..n).collect();
    let mesh = StaticMesh::new(corners, &indices, &[0]).unwrap();
    let (w, h) = (camera.width, camera.height);
    let mut tables = Recorder::new(w, h);
    let mut cache: VertexCache<8> = VertexCache::new();
    let ratio = clip_size(model, camera, corners) / (CLIP_RANGE * near);
    match draw_mesh(
        &mut tables,
        &mut cache,
        &mesh,
        model,
        camera,
        Cull::None,
        |_| 1,
    ) {
        Err(DrawError {
            error: Error::ClipRange,
            ..
        }) => {
            assert!(
                ratio > 1.0 - 1e-6,
                "refused within the range ({ratio}): {corners:?}"
            );
            Outcome::Refused
        }
        Err(e) => panic!("{e}: {corners:?}"),
        Ok(stats) => {
            // Beyond the range only a face that needed no clipping (inside
            // the clip band) or lay wholly outside a plane is drawn.
            assert!(
                ratio < 1.0 + 1e-6 || stats.clipped == 0,
                "clipped beyond the range ({ratio}): {corners:?}"
            );
            assert_eq!(stats.non_finite, 0, "{corners:?}: a corner was lost");
            if ratio > 2f64.powi(40) {
                // Far beyond the range (a face culled as wholly outside a
                // plane, with a margin for the arithmetic's error): the
                // reference's own 106 bits no longer judge it.
                assert!(
                    tables.polygons.is_empty() && stats.outside >= 1 && stats.clipped == 0,
                    "{corners:?}: {stats:?}"
                );
                return Outcome::Drawn(FaceError::default());
            }
            let drawn: Vec<_> = tables.polygons.iter().map(|(p, _)| p.clone()).collect();
            // A face that is not planar is drawn as its fan of triangles.
            let reference: Vec<_> = if corners.len() > 3 && !mesh.face_is_planar(0) {
                (1..corners.len() - 1)
                    .map(|k| clipped_face(model, camera, &[corners[0], corners[k], corners[k + 1]]))
                    .collect()
            } else {
                vec![clipped_face(model, camera, corners)]
            };
            Outcome::Drawn(compare_face(&drawn, &reference, (w, h), 1.0 / 128.0))
        }
    }
}

/// Within the range: corners within one sub-pixel step of the reference
/// polygon's boundary (half a step of snapping, and the arithmetic),
/// depths within 2^-20, and every sample the reference covers covered
/// (samples within 1/128 pixel of its boundary excused).
fn assert_exact(outcome: &Outcome, what: &str) {
    if let Outcome::Drawn(e) = outcome {
        let step = 1.0 / f64::from(SUBPIXEL_STEPS);
        assert!(
            e.position_px <= step,
            "{what}: corner {} px off: {e:?}",
            e.position_px
        );
        assert!(
            e.depth <= 2f64.powi(-20),
            "{what}: depth {} off: {e:?}",
            e.depth
        );
        assert_eq!(e.wrong_samples, 0, "{what}: {e:?}");
    }
}

/// A camera at the origin looking down -Z, pitched down by `pitch`
/// degrees (the ground below it comes into view).
fn pitched_camera(pitch: f32, fov: f32, (w, h): (u16, u16), near: f32, far: f32) -> Camera {
    let view = Mat4::rotation_x(pitch.to_radians());
    Camera::perspective(view, fov, w, h, near, far)
}

/// Issue 28, item 2: a ground triangle and a ground quad one unit below
/// the eye, of every half-size from 1 to `f32::MAX`: each is drawn as the
/// reference draws it, or refused beyond the clipper's range. Before, at
/// half-size 1e16 the triangle drew 1,440 pixels beyond the far cut, and
/// from about 3e15 the faces were dropped (counted non-finite, outside or
/// degenerate).
#[test]
fn ground_faces_of_every_size_are_exact_or_refused() {
    let (near, far) = (0.1f32, 100.0f32);
    let camera = pitched_camera(20.0, 60.0, (64, 48), near, far);
    let mut sizes: Vec<f32> = (0..128).map(|k| 2f32.powi(k)).collect();
    sizes.extend([1e7, 1e8, 3e14, 3e15, 1e16, 3e16, f32::MAX]);
    let (mut drawn, mut refused) = (0, 0);
    for s in sizes {
        let triangle = [[-s, -1.0, s], [s, -1.0, s], [0.0, -1.0, -s]];
        let quad = [[-s, -1.0, s], [s, -1.0, s], [s, -1.0, -s], [-s, -1.0, -s]];
        for corners in [&triangle[..], &quad[..]] {
            let outcome = judge_face(&Mat4::IDENTITY, &camera, f64::from(near), corners);
            assert_exact(
                &outcome,
                &format!("half-size {s:e}, {} corners", corners.len()),
            );
            match outcome {
                Outcome::Drawn(..) => drawn += 1,
                Outcome::Refused => refused += 1,
            }
        }
    }
    // Up to about 2^24 (2^28 near distances) drawn, beyond refused.
    assert!(
        drawn >= 2 * 24 && refused >= 2 * 100,
        "{drawn} drawn, {refused} refused"
    );
    let s = 1e16f32;
    let triangle = [[-s, -1.0, s], [s, -1.0, s], [0.0, -1.0, -s]];
    assert!(matches!(
        judge_face(&Mat4::IDENTITY, &camera, f64::from(near), &triangle),
        Outcome::Refused
    ));
}

/// A finite `f32` anywhere in its range: either sign, any exponent.
fn any_magnitude() -> impl Strategy<Value = f32> {
    (any::<bool>(), 1.0f32..2.0, -126i32..=127).prop_map(|(negative, mantissa, exponent)| {
        let v = (mantissa * 2f32.powi(exponent)).min(f32::MAX);
        if negative { -v } else { v }
    })
}

/// A coordinate from tiny to huge, or an ordinary one.
fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![-2.0f32..2.0, -2000.0f32..2000.0, any_magnitude()]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Random triangles and quads with coordinates anywhere in the f32
    /// range, through random perspective cameras (turned, not moved, so
    /// that the f32 transform of the corners that need no clipping loses
    /// nothing to cancellation), scaled by a model matrix of any
    /// magnitude: exact within the clipper's range, refused beyond it.
    #[test]
    fn faces_of_any_magnitude_are_exact_or_refused(
        corners in prop::collection::vec(prop::array::uniform3(coordinate()), 3..=4),
        scale in prop_oneof![Just(1.0f32), any_magnitude().prop_map(f32::abs)],
        (yaw, pitch) in (-180.0f32..180.0, -89.0f32..89.0),
        fov in 20.0f32..150.0,
        near in prop_oneof![Just(0.001f32), Just(0.01), Just(0.1), Just(1.0), Just(1e4)],
        depth_ratio in prop_oneof![Just(10.0f32), Just(1e3), Just(1e6)],
        size in prop_oneof![Just((64u16, 48u16)), Just((160, 120)), Just((320, 240))],
    ) {
        let view = Mat4::rotation_x(pitch.to_radians()).mul(&Mat4::rotation_y(yaw.to_radians()));
        let camera = Camera::perspective(view, fov, size.0, size.1, near, near * depth_ratio);
        let model = Mat4::scale(Vec3::new(scale, scale, scale));
        let finite = model.m.iter().flatten().all(|v| v.is_finite());
        prop_assume!(finite);
        // A quad's corners must lie in one plane for one polygon.
        let corners: Vec<[f32; 3]> = if corners.len() == 4 {
            let mut c = corners.clone();
            c[3] = [c[0][0] + c[2][0] - c[1][0], c[0][1] + c[2][1] - c[1][1], c[0][2] + c[2][2] - c[1][2]];
            if !c[3].iter().all(|v| v.is_finite()) { c.truncate(3); }
            c
        } else {
            corners
        };
        let outcome = judge_face(&model, &camera, f64::from(near), &corners);
        assert_exact(&outcome, &format!("{corners:?} scale {scale:e}"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Faces through a visible point (on screen, between the near and far
    /// planes) reaching out to sizes from 1/16 to 2^32 near distances, so
    /// that most are clipped and many lie near the limit of the
    /// clipper's range: exact within it, refused beyond it.
    #[test]
    fn faces_through_the_view_are_exact_or_refused(
        (yaw, pitch) in (-180.0f64..180.0, -89.0f64..89.0),
        fov in 20.0f32..150.0,
        near in prop_oneof![Just(0.001f32), Just(0.1), Just(1.0), Just(1e4)],
        depth_ratio in prop_oneof![Just(10.0f32), Just(1e3), Just(1e6)],
        size in prop_oneof![Just((64u16, 48u16)), Just((160, 120)), Just((320, 240))],
        (sx, sy, along) in (-0.9f64..0.9, -0.9f64..0.9, 0.0f64..1.0),
        reach in prop::collection::vec((prop::array::uniform3(-1.0f64..1.0), -4.0f64..32.0), 2..=3),
    ) {
        let view = Mat4::rotation_x(pitch.to_radians() as f32)
            .mul(&Mat4::rotation_y(yaw.to_radians() as f32));
        let far = near * depth_ratio;
        let camera = Camera::perspective(view, fov, size.0, size.1, near, far);
        // The visible point in view space, then in world space (the view
        // is a rotation: its transpose undoes it).
        let t = (f64::from(fov).to_radians() / 2.0).tan();
        let aspect = f64::from(size.0) / f64::from(size.1);
        let distance = f64::from(near) * (f64::from(depth_ratio)).powf(along).min(0.999 * f64::from(depth_ratio));
        let p = [sx * t * aspect * distance, sy * t * distance, -distance];
        let r = view.m;
        let world: [f64; 3] = core::array::from_fn(|i| (0..3).map(|k| f64::from(r[k][i]) * p[k]).sum());
        let mut corners = vec![world.map(|c| c as f32)];
        for (direction, log_reach) in &reach {
            let length = f64::from(near) * 2f64.powf(*log_reach);
            corners.push(core::array::from_fn(|i| (world[i] + direction[i] * length) as f32));
        }
        if corners.len() == 4 {
            // A parallelogram: one plane.
            corners[3] = core::array::from_fn(|i| corners[0][i] + corners[2][i] - corners[1][i]);
        }
        prop_assume!(corners.iter().flatten().all(|c| c.is_finite()));
        let outcome = judge_face(&Mat4::IDENTITY, &camera, f64::from(near), &corners);
        assert_exact(&outcome, &format!("{corners:?}"));
    }
}
