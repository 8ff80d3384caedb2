//! The z-buffer methods against the scanline z-buffer: on the same tables
//! with the same fill rule, plane set-up and depth format, the full-frame
//! z-buffer and every band height give the same frame, colour and depth,
//! bit for bit (both keep a tie with the polygon added first). The
//! painter's pass draws the last polygon on top, whatever its depth.

mod common;

use common::{Rows, scanline_rows, zbuffer_rows};
use proptest::prelude::*;
use zline::limits::SUBPIXEL_STEPS;
use zline::zbuffer::DepthTest;
use zline::{Capacities, Depth16, Depth24, DepthFormat, ScreenVertex};

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

fn scanline<D: DepthFormat>(scene: &[Vec<ScreenVertex>]) -> Rows
where
    D::Value: Into<u64>,
{
    scanline_rows::<D, { W as usize }>(&common::scene_tables(scene, &CAPS, W, H).prepare())
}

fn bands<D: DepthFormat>(
    scene: &[Vec<ScreenVertex>],
    k: u16,
    test: DepthTest,
    order: Option<&[u32]>,
) -> Rows
where
    D::Value: Into<u64>,
{
    zbuffer_rows::<D>(
        &common::scene_tables(scene, &CAPS, W, H).in_drawing_order(),
        k,
        test,
        order,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn every_band_height_equals_the_scanline(
        scene in prop::collection::vec(common::random_polygon(W, H, 10, 6), 1..=10),
        k in prop::sample::select(vec![1u16, 2, 5, 8, 32]),
    ) {
        let want24 = scanline::<Depth24>(&scene);
        prop_assert_eq!(bands::<Depth24>(&scene, k, DepthTest::Nearer, None), want24);
        let want16 = scanline::<Depth16>(&scene);
        prop_assert_eq!(bands::<Depth16>(&scene, k, DepthTest::Nearer, None), want16);
    }
}

#[test]
fn coplanar_tie_goes_to_the_first_added_in_both() {
    let v = |x: i32, y: i32, z: u32| ScreenVertex::new(x * S, y * S, z).unwrap();
    let square = |z| vec![v(2, 2, z), v(30, 2, z), v(30, 28, z), v(2, 28, z)];
    let scene = vec![square(1000), square(1000)];
    let rows = bands::<Depth24>(&scene, H, DepthTest::Nearer, None);
    assert_eq!(rows, scanline::<Depth24>(&scene));
    assert_eq!(rows[10].1[10], 1, "the first added keeps the tie");
}

#[test]
fn the_painter_draws_the_last_on_top() {
    let v = |x: i32, y: i32, z: u32| ScreenVertex::new(x * S, y * S, z).unwrap();
    // The near square is added first; painted in the given order (near
    // first, far last), the far one covers it.
    let scene = vec![
        vec![v(2, 2, 100), v(30, 2, 100), v(30, 28, 100), v(2, 28, 100)],
        vec![
            v(10, 10, 9_000_000),
            v(38, 10, 9_000_000),
            v(38, 30, 9_000_000),
            v(10, 30, 9_000_000),
        ],
    ];
    let painted = bands::<Depth24>(&scene, H, DepthTest::Overwrite, Some(&[0, 1]));
    assert_eq!(painted[20].1[20], 2, "painted last, on top");
    assert_eq!(painted[5].1[5], 1);
    let zbuffered = bands::<Depth24>(&scene, H, DepthTest::Nearer, None);
    assert_eq!(zbuffered[20].1[20], 1, "nearer wins");
    let reversed = bands::<Depth24>(&scene, H, DepthTest::Overwrite, Some(&[1, 0]));
    assert_eq!(reversed[20].1[20], 1);
}
