//! Shared planes (`Tables::share_plane`): polygons given one plane hold
//! exactly equal depths, so where they overlap the one added first wins,
//! in the scanline z-buffer and in the z-buffer bands alike, in both depth
//! formats; and every misuse is a clear error.

mod common;

use common::{Rows, scanline_rows, zbuffer_rows};
use proptest::prelude::*;
use zline::TableArrays;
use zline::host::TableVecs;
use zline::limits::{DEPTH_MAX, SUBPIXEL_STEPS};
use zline::zbuffer::DepthTest;
use zline::{Admission, Capacities, Depth16, Depth24, DepthFormat, Error, ScreenVertex, Tables};
use zline_lab::methods::exact::{Offered, check_frame_shared, covers};

const W: u16 = 40;
const H: u16 = 32;
const S: i32 = SUBPIXEL_STEPS;

const CAPS: Capacities = Capacities {
    width: W as usize,
    vertices: 256,
    polygons: 32,
    corners: 256,
    active_polygons: 32,
    pooled_edges: 64,
    mesh_vertices: 0,
};

/// A plane in screen space: depth at the frame's centre and gradients in
/// input steps per sub-pixel step.
#[derive(Debug, Clone, Copy)]
struct PlaneSpec {
    z0: f64,
    gx: f64,
    gy: f64,
}

impl PlaneSpec {
    fn vertex(&self, x: i32, y: i32) -> ScreenVertex {
        let (cx, cy) = (
            f64::from(W) * f64::from(S) / 2.0,
            f64::from(H) * f64::from(S) / 2.0,
        );
        let z = self.z0 + self.gx * (f64::from(x) - cx) + self.gy * (f64::from(y) - cy);
        let z = z.round().clamp(0.0, f64::from(DEPTH_MAX)) as u32;
        ScreenVertex::new(x, y, z).unwrap()
    }
}

fn plane() -> impl Strategy<Value = PlaneSpec> {
    (
        f64::from(DEPTH_MAX) * 0.3..f64::from(DEPTH_MAX) * 0.7,
        -150.0..150.0f64,
        -150.0..150.0f64,
    )
        .prop_map(|(z0, gx, gy)| PlaneSpec { z0, gx, gy })
}

/// Corner positions (sub-pixel steps) of 3 to 6 corners around the frame.
fn outline() -> impl Strategy<Value = Vec<(i32, i32)>> {
    prop::collection::vec(
        (
            -8 * S..(i32::from(W) + 8) * S,
            -8 * S..(i32::from(H) + 8) * S,
        ),
        3..=6,
    )
}

/// The polygons on `spec`, each sharing the plane through `triple`
/// (corner positions) when `share` is set; what was offered, as the
/// oracle sees it.
fn tables(
    spec: PlaneSpec,
    outlines: &[Vec<(i32, i32)>],
    triple: [(i32, i32); 3],
    share: bool,
) -> (Tables<TableVecs<u32>>, Vec<Offered>) {
    let mut t = Tables::new(TableVecs::new(&CAPS, 0).unwrap(), W, H).unwrap();
    let plane = triple.map(|(x, y)| spec.vertex(x, y));
    let ids = plane.map(|v| t.push_vertex(v).unwrap());
    let mut offered = Vec::new();
    for (k, corners) in outlines.iter().enumerate() {
        let corners: Vec<ScreenVertex> = corners.iter().map(|&(x, y)| spec.vertex(x, y)).collect();
        let admission = t.push_polygon_vertices(&corners, k as u32 + 1).unwrap();
        let queued = matches!(admission, Admission::Queued(_));
        let shared = queued && share && t.share_plane(ids).unwrap();
        offered.push(Offered {
            corners,
            plane: shared.then_some(plane),
            queued,
        });
    }
    (t, offered)
}

fn scanline<D: DepthFormat>(t: &mut Tables<TableVecs<u32>>) -> Rows
where
    D::Value: Into<u64>,
{
    scanline_rows::<D, { W as usize }>(&t.prepare())
}

fn zbuffer<D: DepthFormat>(t: &mut Tables<TableVecs<u32>>, k: u16) -> Rows
where
    D::Value: Into<u64>,
{
    zbuffer_rows::<D>(&t.in_drawing_order(), k, DepthTest::Nearer, None)
}

/// Pixels where a polygon covers the sample but a later one is drawn.
fn later_wins(offered: &[Offered], rows: &Rows) -> usize {
    let mut count = 0;
    for (y, colors, _) in rows {
        for (x, &drawn) in colors.iter().enumerate() {
            let first = offered
                .iter()
                .position(|p| p.queued && covers(&p.corners, x as i32, i32::from(*y)));
            if let Some(first) = first {
                count += usize::from(drawn != first as u32 + 1);
            }
        }
    }
    count
}

fn flatten(rows: &Rows) -> (Vec<u32>, Vec<u64>) {
    let colors = rows.iter().flat_map(|r| r.1.iter().copied()).collect();
    let depths = rows.iter().flat_map(|r| r.2.iter().copied()).collect();
    (colors, depths)
}

fn check<D: DepthFormat>(
    spec: PlaneSpec,
    outlines: &[Vec<(i32, i32)>],
    triple: [(i32, i32); 3],
    k: u16,
) -> Result<(), TestCaseError>
where
    D::Value: Into<u64>,
{
    let (mut t, offered) = tables(spec, outlines, triple, true);
    let rows = scanline::<D>(&mut t);
    prop_assert_eq!(later_wins(&offered, &rows), 0, "{}", D::NAME);
    let (colors, depths) = flatten(&rows);
    let judged = check_frame_shared::<D>(&offered, W.into(), H.into(), &colors, &depths);
    prop_assert!(judged.is_ok(), "{}: {:?}", D::NAME, judged);
    let (mut t, _) = tables(spec, outlines, triple, true);
    prop_assert_eq!(zbuffer::<D>(&mut t, k), rows, "{} bands of {}", D::NAME, k);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn polygons_of_one_shared_plane_keep_the_first_added(
        spec in plane(),
        outlines in prop::collection::vec(outline(), 2..=6),
        k in prop::sample::select(vec![1u16, 3, 32]),
    ) {
        // The plane's three vertices: far apart, one of them off-screen.
        let triple = [(-20 * S, -10 * S), (60 * S, 0), (10 * S, 45 * S)];
        check::<Depth24>(spec, &outlines, triple, k)?;
        check::<Depth16>(spec, &outlines, triple, k)?;
    }
}

#[test]
fn without_a_shared_plane_later_polygons_win_pixels() {
    // The test above can fail: the same kind of scene with each polygon
    // on its own rounded corners' plane shows later polygons in front of
    // earlier ones at z24.
    let spec = PlaneSpec {
        z0: 5e6,
        gx: 37.3,
        gy: -11.7,
    };
    let outlines: Vec<Vec<(i32, i32)>> = (0..8)
        .map(|k| {
            let (x, y) = (3 * S + k * 37, 2 * S + k * 53);
            vec![
                (x, y),
                (x + 30 * S + 17, y + 3 * S + 5),
                (x + 5 * S + 111, y + 26 * S + 91),
            ]
        })
        .collect();
    let triple = [(-20 * S, -10 * S), (60 * S, 0), (10 * S, 45 * S)];
    let (mut t, offered) = tables(spec, &outlines, triple, false);
    let lost = later_wins(&offered, &scanline::<Depth24>(&mut t));
    assert!(lost > 0, "own planes: {lost} pixels lost");
    let (mut t, offered) = tables(spec, &outlines, triple, true);
    assert_eq!(later_wins(&offered, &scanline::<Depth24>(&mut t)), 0);
}

#[test]
fn misuse_is_a_clear_error() {
    let v = |x: i32, y: i32| ScreenVertex::new(x * S, y * S, 1000).unwrap();
    let mut t = Tables::new(TableArrays::<u32, 16, 4, 9>::new(0), 8, 8).unwrap();
    let ids = [v(0, 0), v(7, 0), v(0, 7)].map(|p| t.push_vertex(p).unwrap());
    // Nothing queued yet.
    assert_eq!(t.share_plane(ids), Err(Error::NoPolygonToShare));
    assert!(matches!(t.push_polygon(&ids, 1), Ok(Admission::Queued(0))));
    // A vertex that does not exist; three collinear ones (nothing changes).
    assert_eq!(t.share_plane([0, 1, 15]), Err(Error::VertexOutOfRange));
    let line = [v(0, 0), v(1, 1), v(2, 2)].map(|p| t.push_vertex(p).unwrap());
    assert_eq!(t.share_plane(line), Ok(false));
    assert_eq!(t.share_plane(ids), Ok(true));
    // Only once per polygon.
    assert_eq!(t.share_plane(ids), Err(Error::NoPolygonToShare));
    // A polygon that was left out (off-screen) cannot take one.
    let far = [v(20, 20), v(30, 20), v(20, 30)].map(|p| t.push_vertex(p).unwrap());
    assert_eq!(t.push_polygon(&far, 2), Ok(Admission::OffScreen));
    assert_eq!(t.share_plane(ids), Err(Error::NoPolygonToShare));
    // The corner list (9) holds the first polygon, its plane, and the
    // next triangle, but not that one's plane.
    assert!(matches!(t.push_polygon(&ids, 3), Ok(Admission::Queued(1))));
    assert_eq!(t.corner_count(), 9);
    assert_eq!(t.share_plane(ids), Err(Error::EdgeTableFull));
    assert_eq!(t.polygon_count(), 2);
}
