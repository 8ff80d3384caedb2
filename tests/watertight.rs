//! Watertightness: triangles that tile a region, drawn one per frame into a
//! counting `DrawTarget`, cover every pixel sample inside the region exactly
//! once and none outside (top-left rule on the sub-pixel grid).

mod common;

use common::covers;
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use proptest::prelude::*;
use zline::limits::SUBPIXEL_STEPS;
use zline::{Depth16, DrawTargetSink, Renderer, ScreenVertex};
use zline::{ScanArrays, TableArrays};

const W: usize = 48;
const H: u16 = 40;
const S: i32 = SUBPIXEL_STEPS;

/// Counts, per pixel, how many frames drew it `On`.
struct CoverageCounter {
    counts: Vec<u32>,
}

impl OriginDimensions for CoverageCounter {
    fn size(&self) -> Size {
        Size::new(W as u32, u32::from(H))
    }
}

impl DrawTarget for CoverageCounter {
    type Color = BinaryColor;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<BinaryColor>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if c.is_on() && p.x >= 0 && p.y >= 0 && (p.x as usize) < W && p.y < i32::from(H) {
                self.counts[p.y as usize * W + p.x as usize] += 1;
            }
        }
        Ok(())
    }
}

/// Draws each triangle in a frame of its own and returns the per-pixel
/// count of frames that covered it.
fn coverage_counts(vertices: &[ScreenVertex], triangles: &[[usize; 3]]) -> Vec<u32> {
    let mut counter = CoverageCounter {
        counts: vec![0; W * usize::from(H)],
    };
    for t in triangles {
        let mut renderer: Renderer<
            TableArrays<BinaryColor, 3, 1, 3>,
            ScanArrays<BinaryColor, Depth16, W, 1, 3>,
        > = Renderer::with_height(H, BinaryColor::Off).unwrap();
        let corners = [vertices[t[0]], vertices[t[1]], vertices[t[2]]];
        renderer
            .push_polygon_vertices(&corners, BinaryColor::On)
            .unwrap();
        renderer
            .render(&mut DrawTargetSink::new(&mut counter))
            .unwrap();
    }
    counter.counts
}

/// Asserts counts are 1 exactly where `inside(i, j)`, 0 elsewhere.
fn assert_exactly_once(counts: &[u32], inside: impl Fn(i32, i32) -> bool) {
    for j in 0..i32::from(H) {
        for i in 0..W as i32 {
            let expected = u32::from(inside(i, j));
            let got = counts[j as usize * W + i as usize];
            assert_eq!(
                got, expected,
                "pixel ({i}, {j}) covered {got} times, expected {expected}"
            );
        }
    }
}

/// A grid of `nx` x `ny` cells over a rectangle (which may stick out of the
/// frame), inner vertices jittered on the sub-pixel grid, each cell split
/// along a random diagonal.
fn jittered_grid() -> impl Strategy<Value = (Vec<ScreenVertex>, Vec<[usize; 3]>, [i32; 4])> {
    (
        2usize..7,
        2usize..7,
        -8 * S..8 * S,
        -8 * S..8 * S,
        20 * S..(W as i32 + 8) * S,
        16 * S..(i32::from(H) + 8) * S,
    )
        .prop_flat_map(|(nx, ny, x0, y0, w, h)| {
            let jitter = prop::collection::vec((-S..S, -S..S, 0u32..1 << 20), (nx + 1) * (ny + 1));
            let diagonals = prop::collection::vec(any::<bool>(), nx * ny);
            (Just((nx, ny, x0, y0, w, h)), jitter, diagonals)
        })
        .prop_map(|((nx, ny, x0, y0, w, h), jitter, diagonals)| {
            let mut vertices = Vec::new();
            for gy in 0..=ny {
                for gx in 0..=nx {
                    let (jx, jy, z) = jitter[gy * (nx + 1) + gx];
                    // Boundary vertices slide only along the boundary.
                    let jx = if gx == 0 || gx == nx { 0 } else { jx };
                    let jy = if gy == 0 || gy == ny { 0 } else { jy };
                    let x = x0 + (w * gx as i32) / nx as i32 + jx;
                    let y = y0 + (h * gy as i32) / ny as i32 + jy;
                    vertices.push(ScreenVertex { x, y, z });
                }
            }
            let at = |gx: usize, gy: usize| gy * (nx + 1) + gx;
            let mut triangles = Vec::new();
            for gy in 0..ny {
                for gx in 0..nx {
                    let (a, b, c, d) = (
                        at(gx, gy),
                        at(gx + 1, gy),
                        at(gx + 1, gy + 1),
                        at(gx, gy + 1),
                    );
                    if diagonals[gy * nx + gx] {
                        triangles.push([a, b, c]);
                        triangles.push([a, c, d]);
                    } else {
                        triangles.push([a, b, d]);
                        triangles.push([b, c, d]);
                    }
                }
            }
            (vertices, triangles, [x0, y0, x0 + w, y0 + h])
        })
}

/// A fan around a centre: a star-shaped ring of corners at random radii
/// and strictly increasing angles.
fn fan() -> impl Strategy<Value = (Vec<ScreenVertex>, Vec<[usize; 3]>)> {
    (3usize..14, 10.0f32..38.0, 10.0f32..30.0)
        .prop_flat_map(|(n, cx, cy)| {
            // Each angular gap stays below half a turn (share <= 1 / (1 + 2 * 0.6)),
            // so every fan triangle winds the same way.
            let ring = prop::collection::vec((4.0f32..30.0, 0.6f32..1.0), n);
            (Just((cx, cy)), ring)
        })
        .prop_map(|((cx, cy), ring)| {
            let total: f32 = ring.iter().map(|r| r.1).sum();
            let mut angle = 0.0f32;
            let mut vertices = vec![ScreenVertex::from_f32(cx, cy, 0.5).unwrap()];
            for (radius, share) in &ring {
                angle += share / total * core::f32::consts::TAU;
                let v = ScreenVertex::from_f32(
                    cx + radius * angle.cos(),
                    cy + radius * angle.sin(),
                    0.5,
                )
                .unwrap();
                vertices.push(v);
            }
            let n = ring.len();
            let triangles = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
            (vertices, triangles)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn tiled_rectangle_is_covered_exactly_once((vertices, triangles, [x0, y0, x1, y1]) in jittered_grid()) {
        let counts = coverage_counts(&vertices, &triangles);
        // Inside the rectangle under the top-left rule: x0 <= xs < x1, y0 <= ys < y1.
        assert_exactly_once(&counts, |i, j| {
            let (xs, ys) = common::sample(i, j);
            (i64::from(x0)..i64::from(x1)).contains(&xs) && (i64::from(y0)..i64::from(y1)).contains(&ys)
        });
    }

    #[test]
    fn fan_covers_its_ring_exactly_once((vertices, triangles) in fan()) {
        let counts = coverage_counts(&vertices, &triangles);
        let ring = &vertices[1..];
        // The star-shaped ring is a simple polygon: its coverage by the
        // independent even-odd reference.
        assert_exactly_once(&counts, |i, j| covers(ring, i, j));
    }
}

/// Shared edges through pixel sample points exactly: the tie cases of the
/// fill rule (vertical, horizontal and diagonal edges on sample points).
#[test]
fn edges_through_sample_points_are_covered_once() {
    let s = |v: i32| v * S + S / 2; // whole pixel's sample coordinate
    let vertices = [
        ScreenVertex {
            x: s(4),
            y: s(4),
            z: 0,
        },
        ScreenVertex {
            x: s(20),
            y: s(4),
            z: 0,
        },
        ScreenVertex {
            x: s(20),
            y: s(20),
            z: 0,
        },
        ScreenVertex {
            x: s(4),
            y: s(20),
            z: 0,
        },
        ScreenVertex {
            x: s(12),
            y: s(12),
            z: 0,
        },
    ];
    let triangles = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
    let counts = coverage_counts(&vertices, &triangles);
    // Square [4.5, 20.5) x [4.5, 20.5): pixels 4..=19 on both axes.
    assert_exactly_once(&counts, |i, j| (4..20).contains(&i) && (4..20).contains(&j));
}
