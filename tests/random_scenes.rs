//! Random scenes of overlapping, interpenetrating, concave and off-screen
//! polygons against a brute-force exact z-buffer: per pixel, the reference
//! takes every polygon whose sample test passes (independent even-odd
//! reference) and the smallest exact depth. The renderer must draw that
//! polygon, except where another covering polygon's exactly rounded depth
//! (clamped to the format's range) is within two steps (a tie the format
//! cannot resolve), and its stored depth must be within 1 LSB of the
//! exactly rounded winner's.

mod common;

use common::{capture, covers, exact_depth, exactly_rounded, format_scale};
use proptest::prelude::*;
use zline::fixed::{DEPTH_MAX, SUBPIXEL_STEPS};
use zline::{Admission, Depth16, Depth24, DepthFormat, Renderer, ScreenVertex};

const W: usize = 40;
const H: u16 = 32;
const S: i32 = SUBPIXEL_STEPS;

fn polygon() -> impl Strategy<Value = Vec<ScreenVertex>> {
    // 3..=6 corners anywhere from well off-screen to inside, any depth.
    prop::collection::vec(
        (
            -20 * S..(W as i32 + 20) * S,
            -20 * S..(i32::from(H) + 20) * S,
            0..=DEPTH_MAX,
        ),
        3..=6,
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
    let mut renderer: Renderer<u32, D, W, 64, 12, 64, 12, 64, 6> = Renderer::new(H, 0).unwrap();
    let mut kept = Vec::new();
    for (k, poly) in scene.iter().enumerate() {
        if let Admission::Queued(_) = renderer.push_polygon_vertices(poly, k as u32 + 1).unwrap() {
            kept.push(k);
        } else {
            // Left out: must truly cover no sample (or have zero area).
            for j in 0..i32::from(H) {
                for i in 0..W as i32 {
                    let (_, den) = exact_depth(poly, i, j);
                    assert!(
                        den == 0 || !covers(poly, i, j),
                        "left out polygon {k} covers ({i}, {j})"
                    );
                }
            }
        }
    }
    let (frame, _) = capture(&mut renderer);
    let (lsb, max) = format_scale::<D>();
    for j in 0..i32::from(H) {
        for i in 0..W as i32 {
            // (exact depth as f64 in stored steps, exactly rounded, colour)
            let mut candidates: Vec<(f64, i128, u32)> = kept
                .iter()
                .filter(|&&k| covers(&scene[k], i, j))
                .map(|&k| {
                    let (num, den) = exact_depth(&scene[k], i, j);
                    (
                        num as f64 / den as f64 / lsb as f64,
                        exactly_rounded(num, den, lsb, max),
                        k as u32 + 1,
                    )
                })
                .collect();
            candidates.sort_by(|a, b| a.0.total_cmp(&b.0));
            let drawn = frame.color(i as usize, j as usize);
            let stored = i128::from(frame.depth(i as usize, j as usize).into());
            // Quantised to the far plane (the clear value) is not drawn.
            candidates.retain(|c| c.1 < max);
            if candidates.is_empty() {
                assert_eq!(drawn, 0, "pixel ({i}, {j}) should be background");
                continue;
            }
            // Ties the format cannot order: exactly rounded values (clamped
            // to the format's range) within 2 steps of the nearest.
            let best_rounded = candidates.iter().map(|c| c.1).min().unwrap_or(0);
            let near: Vec<&(f64, i128, u32)> = candidates
                .iter()
                .filter(|c| c.1 - best_rounded <= 2)
                .collect();
            let hit = near.iter().find(|c| c.2 == drawn);
            let hit = hit.unwrap_or_else(|| {
                panic!(
                    "{}: pixel ({i}, {j}) drew {drawn}, expected one of {near:?}",
                    D::NAME
                )
            });
            assert!(
                (stored - hit.1).abs() <= 1,
                "{}: pixel ({i}, {j}) depth {stored} vs {}",
                D::NAME,
                hit.1
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn matches_brute_force_exact_z_buffer(scene in prop::collection::vec(polygon(), 1..=12)) {
        check::<Depth16>(&scene);
        check::<Depth24>(&scene);
    }
}
