//! The fixed-point depth of every covered pixel, across full-width spans,
//! against the exact plane through the snapped corners (rational, i128).
//!
//! Spec: every stored depth is within 1 LSB of the exactly rounded plane
//! value. The analysis in `src/scanline/plane.rs` gives a tighter figure,
//! so this also checks `|stored - exact| <= 0.5 + 1/4 LSB` (z24) and
//! `<= 0.5 + 1/16 LSB` (z16): a format that drifted by a whole LSB would fail.

mod common;

use common::{capture, covers, exact_depth, exactly_rounded, format_scale};
use proptest::prelude::*;
use zline::limits::{DEPTH_MAX, SUBPIXEL_STEPS};
use zline::{Depth16, Depth24, DepthFormat, Renderer, ScreenVertex};
use zline::{ScanArrays, TableArrays};

const S: i32 = SUBPIXEL_STEPS;

/// A triangle whose spans cross the whole frame: one corner far left, one
/// far right, one anywhere; sub-pixel positions and depths uniform.
fn wide_triangle(width: i32, height: i32) -> impl Strategy<Value = [ScreenVertex; 3]> {
    let z = 0..=DEPTH_MAX;
    let y = (-4 * height * S)..(5 * height * S);
    (
        (-7000 * S..-S, y.clone(), z.clone()),
        ((width + 1) * S..8000 * S, y.clone(), z.clone()),
        (-8000 * S..8000 * S, y, z),
    )
        .prop_map(|((x0, y0, z0), (x1, y1, z1), (x2, y2, z2))| {
            [
                ScreenVertex {
                    x: x0,
                    y: y0,
                    z: z0,
                },
                ScreenVertex {
                    x: x1,
                    y: y1,
                    z: z1,
                },
                ScreenVertex {
                    x: x2,
                    y: y2,
                    z: z2,
                },
            ]
        })
}

/// Renders one triangle and checks every pixel: coverage exactly as the
/// reference, depth within the bound. Returns the number of pixels checked.
fn check<D: DepthFormat, const W: usize>(
    tri: [ScreenVertex; 3],
    height: u16,
    slack_16ths: i128,
) -> usize
where
    D::Value: Into<u64>,
{
    let mut renderer: Renderer<TableArrays<u32, 3, 1, 3>, ScanArrays<u32, D, W, 1, 3>> =
        Renderer::with_height(height, 0).unwrap();
    renderer.push_polygon_vertices(&tri, 1).unwrap();
    let (frame, _) = capture(&mut renderer);
    let (lsb, max) = format_scale::<D>();
    let mut checked = 0;
    for j in 0..i32::from(height) {
        for i in 0..W as i32 {
            let drawn = frame.color(i as usize, j as usize) == 1;
            assert_eq!(
                drawn,
                covers(&tri, i, j),
                "coverage at ({i}, {j}) for {tri:?}"
            );
            if !drawn {
                continue;
            }
            let (num, den) = exact_depth(&tri, i, j);
            let stored = i128::from(frame.depth(i as usize, j as usize).into());
            let rounded = exactly_rounded(num, den, lsb, max);
            assert!(
                (stored - rounded).abs() <= 1,
                "{}: pixel ({i}, {j}) stored {stored}, exactly rounded {rounded}, tri {tri:?}",
                D::NAME
            );
            // |stored·lsb·den - num| <= (1/2 + slack) · lsb · den, unless clamped.
            if rounded > 0 && rounded < max {
                let err16 = (stored * lsb * den - num).abs() * 16;
                assert!(
                    err16 <= (8 + slack_16ths) * lsb * den,
                    "{}: pixel ({i}, {j}) error above 0.5 + {slack_16ths}/16 LSB",
                    D::NAME
                );
            }
            checked += 1;
        }
    }
    checked
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn z24_within_one_lsb_over_512_wide_spans(tri in wide_triangle(512, 12)) {
        check::<Depth24, 512>(tri, 12, 4);
    }

    #[test]
    fn z16_within_one_lsb_over_512_wide_spans(tri in wide_triangle(512, 12)) {
        check::<Depth16, 512>(tri, 12, 1);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The largest frame width the renderer accepts.
    #[test]
    fn both_formats_within_one_lsb_over_4096_wide_spans(tri in wide_triangle(4096, 3)) {
        check::<Depth24, 4096>(tri, 3, 4);
        check::<Depth16, 4096>(tri, 3, 1);
    }
}

/// Steep (nearly edge-on) triangles take the exact path: still within the
/// bound, no panic.
#[test]
fn edge_on_triangle_depths_are_exact() {
    // Two corners at the near plane, the third at the far plane 0.16 px off
    // their line: depth crosses the whole range within a sixth of a pixel.
    let tri = [
        ScreenVertex {
            x: -10 * S,
            y: 5 * S + 100,
            z: 0,
        },
        ScreenVertex {
            x: 300 * S,
            y: 5 * S + 140,
            z: 0,
        },
        ScreenVertex {
            x: 140 * S,
            y: 5 * S + 160,
            z: DEPTH_MAX,
        },
    ];
    let n = check::<Depth24, 256>(tri, 12, 4) + check::<Depth16, 256>(tri, 12, 1);
    assert!(n > 0, "the sliver should cover some samples");
}

/// Any polygon, every pixel: coverage exactly as the reference where its
/// exactly rounded depth is nearer than the far plane, nothing where it is
/// at or beyond it, and stored depths within 1 LSB.
fn check_polygon<D: DepthFormat, const W: usize>(poly: &[ScreenVertex], height: u16) -> usize
where
    D::Value: Into<u64>,
{
    let mut renderer: Renderer<TableArrays<u32, 8, 1, 8>, ScanArrays<u32, D, W, 1, 8>> =
        Renderer::with_height(height, 0).unwrap();
    renderer.push_polygon_vertices(poly, 1).unwrap();
    let (frame, _) = capture(&mut renderer);
    let (lsb, max) = format_scale::<D>();
    let mut drawn_pixels = 0;
    for j in 0..i32::from(height) {
        for i in 0..W as i32 {
            let drawn = frame.color(i as usize, j as usize) == 1;
            let stored = i128::from(frame.depth(i as usize, j as usize).into());
            if !covers(poly, i, j) {
                assert!(!drawn, "{}: ({i}, {j}) drawn outside {poly:?}", D::NAME);
                continue;
            }
            let (num, den) = exact_depth(poly, i, j);
            if den == 0 {
                // Zero net area (a figure-eight, say): no plane, left out.
                assert!(!drawn, "{}: ({i}, {j}) drawn without a plane", D::NAME);
                continue;
            }
            let rounded = exactly_rounded(num, den, lsb, max);
            if rounded >= max - 1 {
                // At the far plane: drawn only if it stores a nearer value.
                assert!(!drawn || stored < max, "{}: ({i}, {j})", D::NAME);
            } else {
                assert!(drawn, "{}: ({i}, {j}) not drawn, depth {rounded}", D::NAME);
            }
            if drawn {
                drawn_pixels += 1;
                assert!(
                    (stored - rounded).abs() <= 1,
                    "{}: pixel ({i}, {j}) stored {stored}, exactly rounded {rounded}, {poly:?}",
                    D::NAME
                );
            }
        }
    }
    drawn_pixels
}

/// Issue 7, item 1: the x-gradient numerator is 2^46 - 256; the one-division
/// rounding shortcut overflowed and pixel 20 stored depth 0 where the plane
/// is at 1,262,143.
#[test]
fn gradient_numerator_near_2_pow_46() {
    let tri = [
        ScreenVertex::new(5120, 2560, 1_000_000).unwrap(),
        ScreenVertex::new(7680, 2560, 6_242_860).unwrap(),
        ScreenVertex::new(5120, 54_989, 1_000_000).unwrap(),
    ];
    assert!(check_polygon::<Depth24, 128>(&tri, 256) > 500);
    assert!(check_polygon::<Depth16, 128>(&tri, 256) > 500);
}

/// Issue 7, item 2: a self-intersecting quad of twice-area 1 whose exact
/// depth runs far beyond the far plane: clamped to i64::MAX and then
/// rounded, it wrapped to depth 0 and was drawn in front of everything.
#[test]
fn exact_path_beyond_the_far_plane_is_not_drawn() {
    let quad = [
        ScreenVertex::new(0, 1, DEPTH_MAX).unwrap(),
        ScreenVertex::new(8189, 8189, 0).unwrap(),
        ScreenVertex::new(8190, 0, 11_777_215).unwrap(),
        ScreenVertex::new(0, 8190, DEPTH_MAX).unwrap(),
    ];
    check_polygon::<Depth24, 32>(&quad, 32);
    check_polygon::<Depth16, 32>(&quad, 32);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Polygons of 3 to 8 corners with coordinates drawn near the guard
    /// band and depths near both ends: the inputs that reach the set-up
    /// arithmetic's limits.
    #[test]
    fn extreme_polygons_within_one_lsb(
        poly in prop::collection::vec(
            (
                prop_oneof![Just(1 - zline::limits::GUARD_BAND), Just(zline::limits::GUARD_BAND - 1), -S..40 * S, -20_000..20_000],
                prop_oneof![Just(1 - zline::limits::GUARD_BAND), Just(zline::limits::GUARD_BAND - 1), -S..40 * S, -20_000..20_000],
                prop_oneof![Just(0), Just(DEPTH_MAX), 0..=DEPTH_MAX],
            ),
            3..=8,
        )
    ) {
        let poly: Vec<ScreenVertex> = poly.into_iter().map(|(x, y, z)| ScreenVertex::new(x, y, z).unwrap()).collect();
        check_polygon::<Depth24, 32>(&poly, 32);
        check_polygon::<Depth16, 32>(&poly, 32);
    }
}
