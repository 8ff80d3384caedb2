//! Lit texture mapping (`zline::paint::LitTextured`): exact pixels of a
//! small scene under a uniform light and a light ramp, the unlit mode's
//! frame under full light, random triangles against the texel times the
//! interpolated light, and a lit mesh drawn end to end.

mod common;

use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use proptest::prelude::*;
use zline::host::{HostMesh, HostPaintedRenderer};
use zline::limits::SUBPIXEL_STEPS;
use zline::paint::{
    CHANNEL_MAX, ClipW, LitTexCoord, LitTextured, Rgb8p8, TexCoord, Texture, Textured, UV_ONE,
};
use zline::{
    Admission, Camera, Capacities, Cull, Depth24, FnSink, Lambert, Mesh, ScreenVertex, Vec3,
    reference_model,
};

const S: i32 = SUBPIXEL_STEPS;

const CAPS: Capacities = common::TEXTURED_CAPS;

type Lit<'a> = zline::painted_renderer_type!(LitTextured<'a, Rgb888>, Depth24, CAPS);
type Unlit<'a> = zline::painted_renderer_type!(Textured<'a, Rgb888>, Depth24, CAPS);

const TEXELS: [u16; 16] = common::TILE_TEXELS;

/// Texel `(i, j)` widened to 8-bit channels, as embedded-graphics widens.
fn texel(i: usize, j: usize) -> [u32; 3] {
    let c = Rgb888::from(Rgb565::from(RawU16::new(TEXELS[(j % 4) * 4 + i % 4])));
    [c.r(), c.g(), c.b()].map(u32::from)
}

fn light(level: u16) -> Rgb8p8 {
    Rgb8p8 {
        r: level,
        g: level,
        b: level,
    }
}

fn corner(x: i32, y: i32, u: i32, v: i32, l: Rgb8p8) -> (ScreenVertex, LitTexCoord) {
    let tex = TexCoord {
        uv: [u, v],
        w: ClipW::from_f32(1.0),
    };
    (
        ScreenVertex::new(x * S, y * S, 1000).unwrap(),
        LitTexCoord::new(tex, l),
    )
}

/// Every row of an 8x8 frame of `polygons` drawn lit, undithered.
fn render_lit(polygons: &[&[(ScreenVertex, LitTexCoord)]]) -> Vec<Vec<Rgb888>> {
    let texture = Texture::new(&TEXELS, 4, 4).unwrap();
    let mode = LitTextured::with_dither(texture, false);
    let mut r = Lit::new(8, 8, mode, Rgb888::BLACK).unwrap();
    for polygon in polygons {
        let (corners, values): (Vec<_>, Vec<_>) = polygon.iter().copied().unzip();
        let admission = r.push_polygon_vertices(&corners, &values).unwrap();
        assert!(matches!(admission, Admission::Queued(_)));
    }
    let mut rows = Vec::new();
    r.render(&mut FnSink(|_: u16, row: &[Rgb888], _: &[u32]| {
        rows.push(row.to_vec());
        Ok::<(), ()>(())
    }))
    .unwrap();
    rows
}

/// The 8x8 square mapped to the 4x4 texture (a texel per 2x2 pixels), its
/// corners lit `lights` (top left, bottom left, bottom right, top right).
fn square(lights: [u16; 4]) -> [(ScreenVertex, LitTexCoord); 4] {
    let one = UV_ONE;
    [
        corner(0, 0, 0, 0, light(lights[0])),
        corner(0, 8, 0, one, light(lights[1])),
        corner(8, 8, one, one, light(lights[2])),
        corner(8, 0, one, 0, light(lights[3])),
    ]
}

/// `round(c · l / 65,280)` in 8.8, then to 8 bits rounded: the exact
/// product of an 8-bit channel and an 8.8 light, rounded once more.
fn lit_channel(c: u32, l: u32) -> u32 {
    let product = (c << 8) * l;
    let p = (product + CHANNEL_MAX / 2) / CHANNEL_MAX;
    (p + 128) >> 8
}

/// Under a uniform light every pixel is its texel times the light, as one
/// quad and as two triangles; full light gives the unlit mode's frame.
#[test]
fn a_uniform_light_scales_every_texel() {
    for level in [0u16, 0x4000, 0x7F80, 0xC000, CHANNEL_MAX as u16] {
        let [a, b, c, d] = square([level; 4]);
        for rows in [
            render_lit(&[&[a, b, c, d]]),
            render_lit(&[&[a, b, c], &[a, c, d]]),
        ] {
            for (y, row) in rows.iter().enumerate() {
                for (x, &pixel) in row.iter().enumerate() {
                    let want = texel(x / 2, y / 2).map(|c| lit_channel(c, u32::from(level)));
                    let got = [pixel.r(), pixel.g(), pixel.b()].map(u32::from);
                    assert_eq!(got, want, "light {level:#x} ({x}, {y})");
                }
            }
        }
    }
    // Full light: the unlit mode's pixels.
    let texture = Texture::new(&TEXELS, 4, 4).unwrap();
    let mut unlit = Unlit::new(8, 8, Textured::with_dither(texture, false), Rgb888::BLACK).unwrap();
    let full = square([CHANNEL_MAX as u16; 4]);
    let (corners, values): (Vec<_>, Vec<_>) = full.iter().copied().unzip();
    let tex: Vec<TexCoord> = values.iter().map(|v| v.tex).collect();
    unlit.push_polygon_vertices(&corners, &tex).unwrap();
    let mut rows = Vec::new();
    unlit
        .render(&mut FnSink(|_: u16, row: &[Rgb888], _: &[u32]| {
            rows.push(row.to_vec());
            Ok::<(), ()>(())
        }))
        .unwrap();
    assert_eq!(rows, render_lit(&[&full]));
}

/// A light from 0 on the left edge to full on the right, on the square:
/// pixel `x`'s sample at `(x + 1/2) / 8` of the way, its light
/// `CHANNEL_MAX · (2x + 1) / 16` (exact on this grid), times its texel.
#[test]
fn a_light_ramp_is_interpolated_across_the_square() {
    let full = CHANNEL_MAX as u16;
    let rows = render_lit(&[&square([0, 0, full, full])]);
    for (y, row) in rows.iter().enumerate() {
        for (x, &pixel) in row.iter().enumerate() {
            let l = CHANNEL_MAX * (2 * x as u32 + 1) / 16;
            let want = texel(x / 2, y / 2).map(|c| lit_channel(c, l));
            let got = [pixel.r(), pixel.g(), pixel.b()].map(u32::from);
            assert_eq!(got, want, "({x}, {y})");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    /// Random triangles over a white texture with random corner lights:
    /// every painted pixel is within one 8-bit step of the light
    /// interpolated exactly (in f64) at its sample, and the frame covers
    /// the unlit mode's pixels.
    #[test]
    fn random_triangles_show_the_interpolated_light(
        xy in prop::array::uniform3((0..8 * S, 0..8 * S)),
        lights in prop::array::uniform3(0u16..=CHANNEL_MAX as u16),
    ) {
        let area = (xy[1].0 - xy[0].0) * (xy[2].1 - xy[0].1) - (xy[2].0 - xy[0].0) * (xy[1].1 - xy[0].1);
        prop_assume!(area != 0);
        let white = [0xFFFFu16; 4];
        let texture = Texture::new(&white, 2, 2).unwrap();
        let mode = LitTextured::with_dither(texture, false);
        let mut r = Lit::new(8, 8, mode, Rgb888::new(1, 2, 3)).unwrap();
        let corners: Vec<ScreenVertex> =
            xy.iter().map(|&(x, y)| ScreenVertex::new(x, y, 1000).unwrap()).collect();
        let values: Vec<LitTexCoord> = lights
            .iter()
            .map(|&l| LitTexCoord::new(TexCoord { uv: [0, 0], w: ClipW::from_f32(1.0) }, light(l)))
            .collect();
        r.push_polygon_vertices(&corners, &values).unwrap();
        let mut rows = Vec::new();
        r.render(&mut FnSink(|_: u16, row: &[Rgb888], _: &[u32]| {
            rows.push(row.to_vec());
            Ok::<(), ()>(())
        }))
        .unwrap();
        let p = |k: usize| (f64::from(xy[k].0), f64::from(xy[k].1));
        let ((x0, y0), (x1, y1), (x2, y2)) = (p(0), p(1), p(2));
        let a = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        for (y, row) in rows.iter().enumerate() {
            for (x, &pixel) in row.iter().enumerate() {
                if pixel == Rgb888::new(1, 2, 3) {
                    continue;
                }
                let (px, py) = (f64::from(x as i32 * S + S / 2), f64::from(y as i32 * S + S / 2));
                let l1 = ((px - x0) * (y2 - y0) - (x2 - x0) * (py - y0)) / a;
                let l2 = ((x1 - x0) * (py - y0) - (px - x0) * (y1 - y0)) / a;
                let w = [1.0 - l1 - l2, l1, l2];
                let exact: f64 = (0..3).map(|k| w[k] * f64::from(lights[k])).sum::<f64>() / 256.0;
                for c in [pixel.r(), pixel.g(), pixel.b()] {
                    prop_assert!((f64::from(c) - exact).abs() <= 1.0, "({}, {}): {} vs {}", x, y, c, exact);
                }
            }
        }
    }
}

/// A mesh lit end to end: Spot-like use on a procedural cube with its
/// texture coordinates, lit by Lambert of a white base, draws frames whose
/// pixels are never brighter than the unlit frame's and darker somewhere.
#[test]
fn a_lit_mesh_is_the_unlit_one_darkened() {
    let obj = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
               f 1/1 4/4 3/3 2/2\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\nf 2/1 3/2 7/3 6/4\nf 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\n";
    let mesh = HostMesh::from_obj_smooth(obj.as_bytes(), 0.0).unwrap();
    let texture = Texture::new(&TEXELS, 4, 4).unwrap();
    let (w, h) = (64u16, 64u16);
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let camera = Camera::reference(w, h);
    let lambert = Lambert::new(Rgb888::WHITE, Vec3::new(-0.4, 0.5, 0.77), 0.2);
    let mut lit = HostPaintedRenderer::<LitTextured<'_, Rgb888>, Depth24>::for_mesh(
        &mesh,
        w,
        h,
        LitTextured::with_dither(texture, false),
        Rgb888::BLACK,
    )
    .unwrap();
    lit.draw_mesh(&mesh, &model, &camera, Cull::Back, |v| {
        LitTexCoord::new(v.tex_coord(), lambert.vertex_color(v))
    })
    .unwrap();
    let mut unlit = HostPaintedRenderer::<Textured<'_, Rgb888>, Depth24>::for_mesh(
        &mesh,
        w,
        h,
        Textured::with_dither(texture, false),
        Rgb888::BLACK,
    )
    .unwrap();
    unlit
        .draw_mesh(&mesh, &model, &camera, Cull::Back, |v| v.tex_coord())
        .unwrap();
    let mut a = Vec::new();
    lit.render(&mut FnSink(|_: u16, row: &[Rgb888], _: &[u32]| {
        a.extend_from_slice(row);
        Ok::<(), ()>(())
    }))
    .unwrap();
    let mut b = Vec::new();
    unlit
        .render(&mut FnSink(|_: u16, row: &[Rgb888], _: &[u32]| {
            b.extend_from_slice(row);
            Ok::<(), ()>(())
        }))
        .unwrap();
    assert_eq!(a.len(), b.len());
    assert!(mesh.face_count() > 0);
    let mut darker = 0;
    for (l, u) in a.iter().zip(&b) {
        for (cl, cu) in [(l.r(), u.r()), (l.g(), u.g()), (l.b(), u.b())] {
            assert!(cl <= cu, "lit {l:?} brighter than unlit {u:?}");
            darker += usize::from(cl < cu);
        }
    }
    assert!(darker > 100, "only {darker} channels darker");
}
