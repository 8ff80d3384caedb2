//! Random scenes of overlapping, interpenetrating, concave and off-screen
//! polygons against a brute-force exact z-buffer: per pixel, the reference
//! takes every polygon whose sample test passes (independent even-odd
//! reference) and the smallest exact depth. The renderer must draw that
//! polygon, except where another covering polygon's exactly rounded depth
//! (clamped to the format's range) is within two steps (a tie the format
//! cannot resolve), and its stored depth must be within 1 LSB of the
//! exactly rounded winner's.

mod common;

use common::capture;
use proptest::prelude::*;
use zline::limits::{DEPTH_MAX, SUBPIXEL_STEPS};
use zline::{Admission, Depth16, Depth24, DepthFormat, Renderer, ScreenVertex};
use zline::{ScanArrays, TableArrays};
use zline_lab::methods::exact::check_frame;

const W: usize = 40;
const H: u16 = 32;
const S: i32 = SUBPIXEL_STEPS;
/// Most polygons in a scene, and most corners of one.
const MAX_POLYGONS: usize = 12;
const MAX_CORNERS: usize = 6;
/// Vertices and corners (edges) of the largest scene: the tables hold any
/// scene the strategies make.
const MAX_VERTICES: usize = MAX_POLYGONS * MAX_CORNERS;

fn polygon() -> impl Strategy<Value = Vec<ScreenVertex>> {
    // 3..=6 corners anywhere from well off-screen to inside, any depth.
    prop::collection::vec(
        (
            -20 * S..(W as i32 + 20) * S,
            -20 * S..(i32::from(H) + 20) * S,
            0..=DEPTH_MAX,
        ),
        3..=MAX_CORNERS,
    )
    .prop_map(|corners| {
        corners
            .into_iter()
            .map(|(x, y, z)| ScreenVertex { x, y, z })
            .collect()
    })
}

fn check<D: DepthFormat>(scene: &[Vec<ScreenVertex>])
where
    D::Value: Into<u64>,
{
    let mut renderer: Renderer<
        TableArrays<u32, MAX_VERTICES, MAX_POLYGONS, MAX_VERTICES>,
        ScanArrays<u32, D, W, MAX_POLYGONS, MAX_VERTICES>,
    > = Renderer::with_height(H, 0).unwrap();
    let polygons: Vec<(Vec<ScreenVertex>, bool)> = scene
        .iter()
        .enumerate()
        .map(|(k, poly)| {
            let admission = renderer.push_polygon_vertices(poly, k as u32 + 1).unwrap();
            (poly.clone(), matches!(admission, Admission::Queued(_)))
        })
        .collect();
    let (frame, _) = capture(&mut renderer);
    let depths: Vec<u64> = frame.depths.iter().map(|&d| d.into()).collect();
    if let Err(e) = check_frame::<D>(&polygons, W, usize::from(H), &frame.colors, &depths) {
        panic!("{}: {e}", D::NAME);
    }
}

/// Tiny triangles: corners within a few pixels of each other, anywhere on
/// the sub-pixel grid, so most hold one sample or none in their bounding
/// box (the core tests those samples before queuing them).
fn tiny_triangle() -> impl Strategy<Value = Vec<ScreenVertex>> {
    (0..W as i32 * S, 0..i32::from(H) * S, 1..3 * S).prop_flat_map(|(x, y, size)| {
        prop::collection::vec((x..x + size, y..y + size, 0..=DEPTH_MAX), 3).prop_map(|corners| {
            corners
                .into_iter()
                .map(|(x, y, z)| ScreenVertex { x, y, z })
                .collect()
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn tiny_triangles_match_the_exact_z_buffer(scene in prop::collection::vec(tiny_triangle(), 1..=MAX_POLYGONS)) {
        check::<Depth16>(&scene);
        check::<Depth24>(&scene);
    }

    #[test]
    fn matches_brute_force_exact_z_buffer(scene in prop::collection::vec(polygon(), 1..=MAX_POLYGONS)) {
        check::<Depth16>(&scene);
        check::<Depth24>(&scene);
    }
}
