//! The painted renderer (`zline::paint`): Gouraud shading after
//! visibility. Exact pixels of small scenes; values within the attribute
//! planes' bound of the exact plane at every pixel; and, for random scenes
//! of overlapping, concave and off-screen polygons, each polygon given one
//! colour at every corner paints exactly the frame the flat renderer draws
//! with those colours (the same winner at every pixel, one-row polygons
//! and steep slivers included).

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use proptest::prelude::*;
use zline::limits::{DEPTH_MAX, SUBPIXEL_STEPS};
use zline::paint::{Gouraud, Rgb8p8};
use zline::{Admission, Capacities, Depth16, Depth24, DepthFormat, Error, FnSink, ScreenVertex};

const S: i32 = SUBPIXEL_STEPS;
const W: u16 = 40;
const H: u16 = 32;

const CAPS: Capacities = Capacities {
    width: W as usize,
    vertices: 96,
    polygons: 16,
    corners: 96,
    active_polygons: 16,
    pooled_edges: 96,
    mesh_vertices: 0,
};

type Painted<D> = zline::painted_renderer_type!(Gouraud<Rgb888>, D, CAPS);
type Flat<D> = zline::renderer_type!(Rgb888, D, CAPS);

const BACKGROUND: Rgb888 = Rgb888::new(1, 2, 3);

/// A sink of boxed closure.
type Sink<'a, C, Z> = FnSink<Box<dyn FnMut(u16, &[C], &[Z]) -> Result<(), ()> + 'a>>;

/// Every row of a frame, top to bottom.
fn frame<C: Copy, Z>(render: impl FnOnce(&mut Sink<'_, C, Z>)) -> Vec<Vec<C>> {
    let mut rows = Vec::new();
    {
        let push = |_: u16, colors: &[C], _: &[Z]| {
            rows.push(colors.to_vec());
            Ok(())
        };
        let mut sink: Sink<'_, C, Z> = FnSink(Box::new(push));
        render(&mut sink);
    }
    rows
}

fn v(x: i32, y: i32, z: u32) -> ScreenVertex {
    ScreenVertex::new(x, y, z).unwrap()
}

fn rgb(r: u8, g: u8, b: u8) -> Rgb8p8 {
    Rgb8p8::from_rgb888(Rgb888::new(r, g, b))
}

/// A xorshift generator of values in `0..n`, from `seed`.
fn xorshift(seed: u64) -> impl FnMut(i32) -> i32 {
    let mut rng = seed;
    move |n: i32| {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng % n as u64) as i32
    }
}

/// The barycentric weights of pixel `(i, j)`'s centre in the triangle
/// `corners`.
fn barycentric(corners: &[ScreenVertex], i: usize, j: usize) -> [f64; 3] {
    let p = |k: usize| {
        (
            f64::from(corners[k].x) / 256.0,
            f64::from(corners[k].y) / 256.0,
        )
    };
    let (a, b, c) = (p(0), p(1), p(2));
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
    let wb = ((x - a.0) * (c.1 - a.1) - (y - a.1) * (c.0 - a.0)) / area;
    let wc = ((b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0)) / area;
    [1.0 - wb - wc, wb, wc]
}

/// A triangle whose red channel is `16·x + 32·y` (pixels) at every
/// point: at pixel (i, j), sampled at its centre, `16i + 32j + 24`. The
/// top-left rule leaves out the hypotenuse's samples (i + j = 3).
#[test]
fn a_triangle_paints_its_plane_exactly() {
    let mut r = Painted::<Depth16>::new(8, 8, Gouraud::new(), BACKGROUND).unwrap();
    let corners = [v(0, 0, 100), v(4 * S, 0, 100), v(0, 4 * S, 100)];
    let values = [rgb(0, 200, 9), rgb(64, 200, 9), rgb(128, 200, 9)];
    let admission = r.push_polygon_vertices(&corners, &values).unwrap();
    assert!(matches!(admission, Admission::Queued(_)));
    let rows = frame::<Rgb888, u16>(|sink| {
        r.render(sink).unwrap();
    });
    for (j, row) in rows.iter().enumerate() {
        for (i, &c) in row.iter().enumerate() {
            let want = if i + j <= 2 {
                Rgb888::new((16 * i + 32 * j + 24) as u8, 200, 9)
            } else {
                BACKGROUND
            };
            assert_eq!(c, want, "pixel ({i}, {j})");
        }
    }
}

/// At every covered pixel of random triangles, each channel is within
/// half an 8-bit step (the rounding to 8 bits), 1/512 of one (the
/// rounding to 8.8) and the planes' bound (2^-4 of an 8.8 step) of the
/// exact barycentric interpolation at the pixel's centre.
#[test]
fn channels_are_within_the_bound_of_the_exact_plane() {
    let mut next = xorshift(0x2545_f491);
    for _ in 0..400 {
        let mut r = Painted::<Depth24>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
        let corners: Vec<ScreenVertex> = (0..3)
            .map(|_| v(next(i32::from(W) * S), next(i32::from(H) * S), 1000))
            .collect();
        let values: Vec<Rgb8p8> = (0..3)
            .map(|_| Rgb8p8 {
                r: next(0xFF01) as u16,
                g: next(0xFF01) as u16,
                b: next(0xFF01) as u16,
            })
            .collect();
        if !matches!(
            r.push_polygon_vertices(&corners, &values).unwrap(),
            Admission::Queued(_)
        ) {
            continue;
        }
        let rows = frame::<Rgb888, u32>(|sink| {
            r.render(sink).unwrap();
        });
        for (j, row) in rows.iter().enumerate() {
            for (i, &color) in row.iter().enumerate() {
                if color == BACKGROUND {
                    continue;
                }
                let [wa, wb, wc] = barycentric(&corners, i, j);
                let exact = |f: fn(&Rgb8p8) -> u16| {
                    let value = wa * f64::from(f(&values[0]))
                        + wb * f64::from(f(&values[1]))
                        + wc * f64::from(f(&values[2]));
                    value.clamp(0.0, 65280.0) / 256.0
                };
                let got = [color.r(), color.g(), color.b()];
                let want = [exact(|c| c.r), exact(|c| c.g), exact(|c| c.b)];
                for k in 0..3 {
                    let error = (f64::from(got[k]) - want[k]).abs();
                    assert!(
                        error <= 0.5 + 1.0 / 512.0 + 1.0 / 4096.0,
                        "pixel ({i}, {j}) channel {k}: {} for {}",
                        got[k],
                        want[k]
                    );
                }
            }
        }
    }
}

/// A sliver narrower than a sub-pixel step across the frame has steep
/// planes: each of its pixels takes the exact value.
#[test]
fn a_steep_sliver_takes_exact_values() {
    let mut r = Painted::<Depth16>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
    // From (0, 10.5) to (40, 10.5), the third corner one sub-pixel step
    // below the middle: the samples of row 10 lie on its top edge.
    let corners = [
        v(0, 10 * S + S / 2, 5),
        v(40 * S, 10 * S + S / 2, 5),
        v(20 * S, 10 * S + S / 2 + 1, 5),
    ];
    let values = [rgb(0, 0, 0), rgb(0, 0, 0), rgb(255, 255, 255)];
    let admission = r.push_polygon_vertices(&corners, &values).unwrap();
    assert!(matches!(admission, Admission::Queued(_)));
    let rows = frame::<Rgb888, u16>(|sink| {
        r.render(sink).unwrap();
    });
    // On the top edge the exact value is 0 everywhere.
    let covered: Vec<_> = rows[10].iter().filter(|&&c| c != BACKGROUND).collect();
    assert!(!covered.is_empty());
    assert!(covered.iter().all(|&&c| c == Rgb888::BLACK), "{covered:?}");
}

/// Rgb565 rows are dithered by default (a 4x4 block of one 8.8 value
/// between two levels holds both), and not when asked.
#[test]
fn rgb565_is_dithered_by_default() {
    type Z = zline::painted_renderer_type!(Gouraud<Rgb565>, Depth16, CAPS);
    let background = Rgb565::new(0, 0, 0);
    let square = [
        v(0, 0, 7),
        v(8 * S, 0, 7),
        v(8 * S, 8 * S, 7),
        v(0, 8 * S, 7),
    ];
    // 100.0 in 8-bit red is 12.16 levels of 5 bits.
    let values = [rgb(100, 0, 0); 4];
    for (mode, levels) in [(Gouraud::new(), 2), (Gouraud::with_dither(false), 1)] {
        let mut r = Z::new(8, 8, mode, background).unwrap();
        r.push_polygon_vertices(&square, &values).unwrap();
        let rows = frame::<Rgb565, u16>(|sink| {
            r.render(sink).unwrap();
        });
        let mut reds: Vec<u8> = rows.iter().flatten().map(|c| c.r()).collect();
        reds.sort();
        reds.dedup();
        assert_eq!(reds.len(), levels, "{reds:?}");
    }
}

/// Rgb565 levels of random triangles, dithered and not: each pixel's
/// level is `floor(L + t)`, with `L` the exact barycentric value in the
/// channel's levels and `t` the pixel's Bayer threshold `(2b + 1)/32` (or
/// 1/2), wherever `L + t` is more than the stated error (corners rounded
/// to 1/256 of a level, planes within `2^-12` of one) from a level's edge;
/// where it is nearer, either neighbour. Values run to both ends of the
/// range, where a wrapped sum would show the far end.
#[test]
fn rgb565_levels_are_the_exact_plane_quantised() {
    type Z = zline::painted_renderer_type!(Gouraud<Rgb565>, Depth16, CAPS);
    const BAYER: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    let mut next = xorshift(0x9e37_79b9);
    let background = Rgb565::new(1, 2, 3);
    let mut checked = 0;
    for case in 0..600 {
        let dither = case % 2 == 0;
        let mut r = Z::new(W, H, Gouraud::with_dither(dither), background).unwrap();
        let corners: Vec<ScreenVertex> = (0..3)
            .map(|_| v(next(i32::from(W) * S), next(i32::from(H) * S), 1000))
            .collect();
        // Ends of the range half the time: 0 and 255 exactly.
        let channel = |n: i32| match n % 4 {
            0 => 0,
            1 => 0xFF00,
            _ => n as u16,
        };
        let values: Vec<Rgb8p8> = (0..3)
            .map(|_| Rgb8p8 {
                r: channel(next(0xFF01)),
                g: channel(next(0xFF01)),
                b: channel(next(0xFF01)),
            })
            .collect();
        if !matches!(
            r.push_polygon_vertices(&corners, &values).unwrap(),
            Admission::Queued(_)
        ) {
            continue;
        }
        let rows = frame::<Rgb565, u16>(|sink| {
            r.render(sink).unwrap();
        });
        for (j, row) in rows.iter().enumerate() {
            for (i, &color) in row.iter().enumerate() {
                let [wa, wb, wc] = barycentric(&corners, i, j);
                if wa < 0.0 || wb < 0.0 || wc < 0.0 {
                    continue; // outside, or on an edge the fill rule may leave out
                }
                let t = if dither {
                    f64::from(2 * BAYER[j & 3][i & 3] + 1) / 32.0
                } else {
                    0.5
                };
                let got = [color.r(), color.g(), color.b()];
                let value = |f: fn(&Rgb8p8) -> u16| {
                    wa * f64::from(f(&values[0]))
                        + wb * f64::from(f(&values[1]))
                        + wc * f64::from(f(&values[2]))
                };
                let exact = [value(|c| c.r), value(|c| c.g), value(|c| c.b)];
                for k in 0..3 {
                    let max = if k == 1 { 63.0 } else { 31.0 };
                    let level = exact[k] / 65280.0 * max + t;
                    let slack = 1.0 / 512.0 + 1.0 / 4096.0;
                    let (low, high) = ((level - slack).floor(), (level + slack).floor());
                    let got = f64::from(got[k]);
                    assert!(
                        got == low.min(max) || got == high.min(max),
                        "case {case} pixel ({i}, {j}) channel {k}: {got} for {level}"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 10_000, "{checked}");
}

/// Squares whose corner values are not coplanar get Newell's plane,
/// which leaves the range of the corners' values: with 255 at one corner
/// and 0 at the rest it falls to -119.5 (of 255) at the next corner, with
/// 0 at one and 255 at the rest it rises to 374.5. Those pixels are
/// clamped to black and to white, never wrapped round.
#[test]
fn a_plane_beyond_its_range_is_clamped() {
    type Z = zline::painted_renderer_type!(Gouraud<Rgb565>, Depth16, CAPS);
    let background = Rgb565::new(1, 2, 3);
    let square = [
        v(0, 0, 7),
        v(16 * S, 0, 7),
        v(16 * S, 16 * S, 7),
        v(0, 16 * S, 7),
    ];
    let (black, white) = (rgb(0, 0, 0), rgb(255, 255, 255));
    for mode in [Gouraud::new(), Gouraud::with_dither(false)] {
        let mut r = Z::new(16, 16, mode, background).unwrap();
        r.push_polygon_vertices(&square, &[black, black, black, white])
            .unwrap();
        let rows = frame::<Rgb565, u16>(|sink| {
            r.render(sink).unwrap();
        });
        assert_eq!(rows[0][15], Rgb565::BLACK);
        assert!(rows[15][0].r() >= 13, "{:?}", rows[15][0]);
        let mut r = Z::new(16, 16, mode, background).unwrap();
        r.push_polygon_vertices(&square, &[white, black, white, white])
            .unwrap();
        let rows = frame::<Rgb565, u16>(|sink| {
            r.render(sink).unwrap();
        });
        // The plane is at least 135.5 everywhere, 16.4 levels of 5 bits.
        for row in &rows {
            assert!(row.iter().all(|c| c.r() >= 16), "{row:?}");
        }
        assert!(rows.iter().flatten().any(|&c| c == Rgb565::WHITE));
    }
}

/// Capacities too small and values not one per corner are errors, and
/// nothing is added.
#[test]
fn mismatched_values_and_small_storage_are_errors() {
    let mut r = Painted::<Depth16>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
    let corners = [v(0, 0, 1), v(4 * S, 0, 1), v(0, 4 * S, 1)];
    assert_eq!(
        r.push_polygon_vertices(&corners, &[rgb(1, 2, 3); 2]),
        Err(Error::ValueCountMismatch)
    );
    assert_eq!(r.renderer.vertex_count(), 0);
    assert_eq!(
        Painted::<Depth16>::new(W + 1, H, Gouraud::new(), BACKGROUND).err(),
        Some(Error::BadFrameSize)
    );
}

fn polygon() -> impl Strategy<Value = Vec<ScreenVertex>> {
    prop::collection::vec(
        (
            -20 * S..(i32::from(W) + 20) * S,
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

/// A thin or one-row triangle: small polygons take the paths the flat
/// scan draws at once.
fn small_triangle() -> impl Strategy<Value = Vec<ScreenVertex>> {
    (0..i32::from(W) * S, 0..i32::from(H) * S, 0..=DEPTH_MAX).prop_flat_map(|(x, y, z)| {
        prop::collection::vec(
            (
                x..x + 3 * S,
                y..y + S,
                z..=z.saturating_add(9999).min(DEPTH_MAX),
            ),
            3,
        )
        .prop_map(|corners| {
            corners
                .into_iter()
                .map(|(x, y, z)| ScreenVertex { x, y, z })
                .collect()
        })
    })
}

fn color_of(k: usize) -> Rgb888 {
    Rgb888::new(
        (k * 37 + 11) as u8,
        (k * 91 + 5) as u8,
        (k * 13 + 200) as u8,
    )
}

fn flat_equals_painted<D: DepthFormat>(scene: &[Vec<ScreenVertex>]) -> Result<(), TestCaseError> {
    let mut flat = Flat::<D>::new(W, H, BACKGROUND).unwrap();
    let mut painted = Painted::<D>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
    for (k, polygon) in scene.iter().enumerate() {
        let color = color_of(k);
        let a = flat.push_polygon_vertices(polygon, color);
        let values = vec![Rgb8p8::from_rgb888(color); polygon.len()];
        let b = painted.push_polygon_vertices(polygon, &values);
        prop_assert_eq!(a, b);
    }
    let want = frame::<Rgb888, D::Value>(|sink| {
        flat.render(sink).unwrap();
    });
    let got = frame::<Rgb888, D::Value>(|sink| {
        painted.render(sink).unwrap();
    });
    prop_assert_eq!(got, want);
    Ok(())
}

/// The scene `scene` (each corner its own colour) painted in two bands,
/// rows `0..cut` by `painted`'s scanner and `cut..` by `other`'s scanner
/// and slots over `painted`'s prepared tables and vertex values (as a
/// second core paints), gives the rows `painted.render` gives.
fn bands_equal_one_scan<D: DepthFormat>(
    scene: &[Vec<ScreenVertex>],
    cut: u16,
) -> Result<(), TestCaseError> {
    use zline_lab::two_bands::paint_in_two_bands;
    let mut painted = Painted::<D>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
    let mut other = Painted::<D>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
    for (k, polygon) in scene.iter().enumerate() {
        let values: Vec<Rgb8p8> = (0..polygon.len())
            .map(|c| Rgb8p8::from_rgb888(color_of(k * 7 + c)))
            .collect();
        painted.push_polygon_vertices(polygon, &values).unwrap();
    }
    let want = frame::<Rgb888, D::Value>(|sink| {
        painted.render(sink).unwrap();
    });
    let got = frame::<Rgb888, D::Value>(|sink| {
        paint_in_two_bands(&mut painted, &mut other, cut, H, sink).unwrap();
    });
    prop_assert_eq!(got, want);
    Ok(())
}

/// A painter holding fewer slots than the scanner's APT, or fewer values
/// than the tables' vertices, is refused, not read past its end.
#[test]
fn a_painter_too_small_for_the_scan_is_refused() {
    use zline::paint::{PaintStorage, Painter};
    let mut r = Painted::<Depth16>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
    let corners = [v(0, 0, 1), v(4 * S, 0, 1), v(0, 4 * S, 1)];
    r.push_polygon_vertices(&corners, &[rgb(1, 2, 3); 3])
        .unwrap();
    let zline::paint::PaintedRenderer {
        renderer,
        paint,
        mode,
        ..
    } = &mut r;
    let prepared = renderer.tables.prepare();
    let parts = paint.parts_mut();
    let (slots, row) = (parts.slots, parts.row);
    let mut ignore = FnSink(|_: u16, _: &[Rgb888], _: &[u16]| Ok::<(), ()>(()));
    let short_slots = slots.len() - 1;
    let mut painter = Painter::new(
        &*mode,
        &*parts.vertices,
        &mut slots[..short_slots],
        BACKGROUND,
    );
    let result = zline::scan_painted(
        &prepared,
        &mut renderer.scanner,
        &mut painter,
        row,
        0..H,
        &mut ignore,
    );
    assert_eq!(
        result.err(),
        Some(zline::RenderError::Table(Error::PaintStorageTooSmall))
    );
    let mut painter = Painter::new(&*mode, &parts.vertices[..2], slots, BACKGROUND);
    let result = zline::scan_painted(
        &prepared,
        &mut renderer.scanner,
        &mut painter,
        row,
        0..H,
        &mut ignore,
    );
    assert_eq!(
        result.err(),
        Some(zline::RenderError::Table(Error::PaintStorageTooSmall))
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// One colour at every corner of each polygon paints the flat frame.
    #[test]
    fn uniform_corners_paint_the_flat_frame(
        scene in prop::collection::vec(prop_oneof![polygon(), small_triangle()], 1..12)
    ) {
        flat_equals_painted::<Depth16>(&scene)?;
        flat_equals_painted::<Depth24>(&scene)?;
    }

    /// Two scanners painting bands of one prepared scene paint the frame
    /// one scan paints.
    #[test]
    fn bands_paint_the_one_scan_frame(
        scene in prop::collection::vec(prop_oneof![polygon(), small_triangle()], 1..12),
        cut in 0..=H,
    ) {
        bands_equal_one_scan::<Depth16>(&scene, cut)?;
        bands_equal_one_scan::<Depth24>(&scene, cut)?;
    }
}

/// A smooth mesh drawn with Gouraud shading as a host mesh (`f32` front
/// end, `f32` vertex Lambert) and quantized with its vertex normals
/// (integer front end, Lambert in Q15): every vertex colour agrees within
/// one 8-bit step, and the frames nearly everywhere (the projections
/// differ by the quantization of positions). A quantized mesh's vertex
/// normals are checked: one per vertex, none too long.
#[test]
fn quantized_vertex_normals_light_as_the_float_path() {
    use std::cell::RefCell;
    use zline::host::{HostMesh, HostPaintedRenderer, QuantizedHostMesh};
    use zline::{Camera, Cull, MeshError, QuantizedMesh, Shading, VertexInfo, reference_model};
    type Painted = HostPaintedRenderer<Gouraud<Rgb888>, Depth24>;
    let obj = std::fs::read("assets/torus_knot.obj").expect("the README's mesh");
    let host = HostMesh::from_obj_smooth(&obj, 60.0).expect("smooth mesh");
    let quantized = QuantizedHostMesh::new(&host).expect("quantized");
    assert_eq!(quantized.vertex_normals.len(), host.positions.len());
    let mesh = quantized.mesh().expect("valid");
    let shading = Shading::lambert();
    let model = reference_model(&host, 30.0, 20.0).expect("model");
    let camera = Camera::reference(96, 96);
    let mut frames = Vec::new();
    let mut colors = Vec::new();
    for integer in [false, true] {
        let mut renderer =
            Painted::for_mesh(&host, 96, 96, Gouraud::new(), Rgb888::BLACK).expect("renderer");
        let seen = RefCell::new(vec![None; host.positions.len()]);
        let shade = |v: &VertexInfo| {
            assert_eq!(v.normal_q15().is_some(), integer, "vertex {}", v.vertex);
            let c = shading.vertex_color(v);
            seen.borrow_mut()[v.vertex as usize] = Some(c);
            c
        };
        if integer {
            renderer.draw_mesh(&mesh, &model, &camera, Cull::Back, shade)
        } else {
            renderer.draw_mesh(&host, &model, &camera, Cull::Back, shade)
        }
        .expect("draw");
        frames.push(frame(|sink| {
            renderer.render(sink).expect("render");
        }));
        colors.push(seen.into_inner());
    }
    let mut compared = 0;
    for (f, i) in colors[0].iter().zip(&colors[1]) {
        if let (Some(f), Some(i)) = (f, i) {
            compared += 1;
            for (a, b) in [(f.r, i.r), (f.g, i.g), (f.b, i.b)] {
                assert!((i32::from(a) - i32::from(b)).abs() <= 256, "{f:?} {i:?}");
            }
        }
    }
    assert!(compared > 100, "{compared} vertices shaded both ways");
    let (mut lit, mut far) = (0, 0);
    for (ra, rb) in frames[0].iter().zip(&frames[1]) {
        for (&pa, &pb) in ra.iter().zip(rb) {
            if pa != Rgb888::BLACK && pb != Rgb888::BLACK {
                lit += 1;
                let d = |x: u8, y: u8| (i32::from(x) - i32::from(y)).abs();
                if d(pa.r(), pb.r())
                    .max(d(pa.g(), pb.g()))
                    .max(d(pa.b(), pb.b()))
                    > 4
                {
                    far += 1;
                }
            }
        }
    }
    assert!(
        lit > 1000 && far * 50 < lit,
        "{far} of {lit} pixels more than 4 steps apart"
    );
    let view = mesh.view();
    let bare = QuantizedMesh::new(
        view.positions,
        view.normals,
        mesh.corners(),
        mesh.face_starts(),
        &quantized.planar,
        view.centre,
        view.radius,
    )
    .expect("mesh");
    let short = [[0i16, 0, 32767]; 1];
    assert_eq!(
        bare.with_vertex_normals(&short).err(),
        Some(MeshError::BadVertexAttributes)
    );
    let long = vec![[32767i16, 32767, 0]; view.positions.len()];
    assert_eq!(
        bare.with_vertex_normals(&long).err(),
        Some(MeshError::BadVertexAttributes)
    );
    assert!(bare.with_vertex_normals(view.vertex_normals).is_ok());
}

/// Lends one buffer for every row. When `filled` it refills it with the
/// background after each row, as a DMA-clearing sink would (the painter
/// then leaves uncovered pixels alone); otherwise the buffer keeps the
/// last row plus a pixel of junk.
struct Lender {
    buffer: Vec<Rgb888>,
    filled: bool,
    rows: Vec<Vec<Rgb888>>,
}

impl<Z> zline::RowSink<Rgb888, Z> for Lender {
    type Error = ();

    fn write_row(&mut self, _: u16, _: &[Rgb888], _: &[Z]) -> Result<(), ()> {
        Err(())
    }

    fn lend_row(
        &mut self,
        _: u16,
        width: usize,
        background: Rgb888,
    ) -> Result<Option<zline::LentRow<'_, Rgb888>>, ()> {
        assert_eq!(background, BACKGROUND);
        assert_eq!(width, usize::from(W));
        Ok(Some(zline::LentRow {
            colors: &mut self.buffer,
            filled: self.filled,
        }))
    }

    fn send_lent_row(&mut self, y: u16, _: &[Z]) -> Result<(), ()> {
        self.rows.push(self.buffer[..usize::from(W)].to_vec());
        if self.filled {
            self.buffer.fill(BACKGROUND);
        } else {
            self.buffer[usize::from(y) % usize::from(W)] = Rgb888::new(0xBA, 0xD0, 0x0D);
        }
        Ok(())
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    /// A sink lending its own rows, black or holding an old row, gets the
    /// rows a copying sink gets.
    #[test]
    fn lent_rows_equal_copied_rows(
        scene in prop::collection::vec(prop_oneof![polygon(), small_triangle()], 1..8),
        filled: bool,
    ) {
        let mut painted = Painted::<Depth16>::new(W, H, Gouraud::new(), BACKGROUND).unwrap();
        for (k, polygon) in scene.iter().enumerate() {
            let values: Vec<_> = (0..polygon.len())
                .map(|c| Rgb8p8::from_rgb888(color_of(k * 7 + c)))
                .collect();
            painted.push_polygon_vertices(polygon, &values).unwrap();
        }
        let copied = frame::<Rgb888, u16>(|sink| {
            painted.render(sink).unwrap();
        });
        let fill = if filled { BACKGROUND } else { Rgb888::new(0xDE, 0xAD, 0) };
        let mut lender = Lender { buffer: vec![fill; usize::from(W) + 3], filled, rows: Vec::new() };
        painted.render(&mut lender).unwrap();
        prop_assert_eq!(lender.rows, copied);
    }
}
