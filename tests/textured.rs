//! Texture mapping (`zline::paint::Textured`): exact pixels of small
//! scenes (a texel per 2x2 pixels, both as one quad and as two
//! triangles; repeat and clamp; perspective), and a mesh drawn end to end
//! against the float64 reference's perspective-correct coordinates.

mod common;

use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888};
use zline::host::{HostMesh, HostPaintedRenderer};
use zline::limits::SUBPIXEL_STEPS;
use zline::paint::{ClipW, Filter, TexCoord, Texture, Textured, UV_ONE, Wrap};
use zline::{
    Admission, Camera, Capacities, Cull, Depth24, Error, FnSink, Mesh, ScreenVertex,
    reference_model,
};
use zline_lab::methods::{BACKGROUND, ReferenceCamera, ReferenceFrame, ReferenceView};

const S: i32 = SUBPIXEL_STEPS;

const CAPS: Capacities = common::TEXTURED_CAPS;

type Painted<'a> = zline::painted_renderer_type!(Textured<'a, Rgb565>, Depth24, CAPS);

const BACKGROUND_COLOR: Rgb565 = Rgb565::new(0, 0, 0);

const TEXELS: [u16; 16] = common::TILE_TEXELS;

fn texel(i: usize, j: usize) -> Rgb565 {
    Rgb565::from(RawU16::new(TEXELS[(j % 4) * 4 + i % 4]))
}

fn corner(x: i32, y: i32, u: i32, v: i32, w: f32) -> (ScreenVertex, TexCoord) {
    (
        ScreenVertex::new(x * S, y * S, 1000).unwrap(),
        TexCoord {
            uv: [u, v],
            w: ClipW::from_f32(w),
        },
    )
}

/// Every row of a frame of `polygons`, each a list of corners.
fn render(texture: Texture<'_>, polygons: &[&[(ScreenVertex, TexCoord)]]) -> Vec<Vec<Rgb565>> {
    let mut r = Painted::new(8, 8, Textured::new(texture), BACKGROUND_COLOR).unwrap();
    for polygon in polygons {
        let (corners, values): (Vec<_>, Vec<_>) = polygon.iter().copied().unzip();
        let admission = r.push_polygon_vertices(&corners, &values).unwrap();
        assert!(matches!(admission, Admission::Queued(_)));
    }
    let mut rows = Vec::new();
    r.render(&mut FnSink(|_: u16, row: &[Rgb565], _: &[u32]| {
        rows.push(row.to_vec());
        Ok::<(), ()>(())
    }))
    .unwrap();
    rows
}

/// An 8x8 square mapped to the 4x4 texture: pixel `(x, y)`'s centre is
/// at texel coordinates `((x + 1/2) / 2, (y + 1/2) / 2)`, in texel
/// `(x / 2, y / 2)`, whether drawn as one quad or as two triangles.
#[test]
fn a_square_shows_each_texel_on_two_by_two_pixels() {
    let texture = Texture::new(&TEXELS, 4, 4).unwrap();
    let one = UV_ONE;
    let [a, b, c, d] = [
        corner(0, 0, 0, 0, 1.0),
        corner(0, 8, 0, one, 1.0),
        corner(8, 8, one, one, 1.0),
        corner(8, 0, one, 0, 1.0),
    ];
    for rows in [
        render(texture, &[&[a, b, c, d]]),
        render(texture, &[&[a, b, c], &[a, c, d]]),
    ] {
        for (y, row) in rows.iter().enumerate() {
            for (x, &pixel) in row.iter().enumerate() {
                assert_eq!(pixel, texel(x / 2, y / 2), "({x}, {y})");
            }
        }
    }
}

/// Coordinates from 0 to 2 repeat the texture twice; clamped, the edge
/// texels extend past 1.
#[test]
fn repeat_and_clamp() {
    let two = 2 * UV_ONE;
    let square = [
        corner(0, 0, 0, 0, 1.0),
        corner(0, 8, 0, two, 1.0),
        corner(8, 8, two, two, 1.0),
        corner(8, 0, two, 0, 1.0),
    ];
    let repeat = render(Texture::new(&TEXELS, 4, 4).unwrap(), &[&square]);
    let clamp = render(
        Texture::new(&TEXELS, 4, 4).unwrap().with_wrap(Wrap::Clamp),
        &[&square],
    );
    for y in 0..8 {
        for x in 0..8 {
            assert_eq!(repeat[y][x], texel(x % 4, y % 4), "repeat ({x}, {y})");
            assert_eq!(
                clamp[y][x],
                texel((x).min(3), (y).min(3)),
                "clamp ({x}, {y})"
            );
        }
    }
}

/// A triangle whose bottom edge is four times nearer than its top
/// corner (`w` 4 there, 1 below): each covered pixel shows the texel of
/// its perspective-correct coordinates (`u/w`, `v/w`, `1/w` interpolated
/// barycentrically in `f64`, then divided), where no texel boundary lies
/// within 1/32 texel of them; and an affine mapping would differ.
#[test]
fn perspective_is_correct() {
    let texture = Texture::new(&TEXELS, 4, 4).unwrap();
    let one = UV_ONE;
    let triangle = [
        corner(0, 0, 0, 0, 4.0),
        corner(0, 8, 0, one, 1.0),
        corner(8, 8, one, one, 1.0),
    ];
    let rows = render(texture, &[&triangle]);
    let (mut checked, mut affine_differs) = (0, false);
    for (y, row) in rows.iter().enumerate() {
        for (x, &pixel) in row.iter().enumerate() {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            // Barycentric weights of (0,0), (0,8), (8,8).
            let l2 = px / 8.0;
            let l1 = py / 8.0 - l2;
            let l0 = 1.0 - l1 - l2;
            if l0 <= 0.0 || l1 <= 0.0 || l2 <= 0.0 {
                assert_eq!(pixel, BACKGROUND_COLOR, "({x}, {y})");
                continue;
            }
            let q = l0 / 4.0 + l1 + l2;
            let (u, v) = (4.0 * l2 / q, 4.0 * (l1 + l2) / q);
            let near_boundary = |c: f64| (c - c.round()).abs() < 1.0 / 32.0;
            affine_differs |= (4.0 * (l1 + l2)).floor() != v.floor();
            if near_boundary(u) || near_boundary(v) {
                continue;
            }
            assert_eq!(pixel, texel(u as usize, v as usize), "({x}, {y})");
            checked += 1;
        }
    }
    assert!(checked >= 20 && affine_differs, "{checked}");
}

#[test]
fn texture_sizes_are_checked() {
    assert_eq!(Texture::new(&TEXELS, 4, 3), Err(Error::BadTextureSize));
    assert_eq!(Texture::new(&TEXELS, 0, 16), Err(Error::BadTextureSize));
    assert!(Texture::new(&TEXELS, 16, 1).is_ok());
}

/// A textured, tilted, folded mesh drawn through `draw_mesh` (the `f32`
/// front end, clipping at none) against the reference: at every pixel
/// whose face matches, the nearest texel is the one holding the exact
/// perspective-correct coordinates, or one within 1/32 texel of them.
#[test]
fn a_mesh_maps_as_the_reference() {
    let obj = b"v -1 -1 0\nv 1 -1 0.5\nv 1 1 -0.5\nv -1 1 0\nv 0 0 0.8\n\
        vt 0 0\nvt 3 0\nvt 3 2\nvt 0 2\nvt 1.5 1\n\
        f 1/1 2/2 5/5\nf 2/2 3/3 5/5\nf 3/3 4/4 5/5\nf 4/4 1/1 5/5\n";
    let mesh = HostMesh::from_obj_smooth(obj, 60.0).unwrap();
    let (w, h) = (64u16, 48u16);
    let texels: Vec<u16> = (0..16 * 8)
        .map(|k| (k as u16).wrapping_mul(0x9E37))
        .collect();
    let texture = Texture::new(&texels, 16, 8).unwrap();
    for (yaw, pitch) in [(30.0, 20.0), (-60.0, 70.0)] {
        let view = ReferenceView {
            width: usize::from(w),
            height: usize::from(h),
            yaw_deg: f64::from(yaw),
            pitch_deg: f64::from(pitch),
            cull_back: false,
        };
        let uv = |v: usize| {
            let [u, v] = mesh.vertex_uv(v).unwrap();
            [f64::from(u), f64::from(v), 0.0]
        };
        let reference =
            ReferenceFrame::render_with_values(&mesh, &view, &ReferenceCamera::STANDARD, &uv);
        let model = reference_model(&mesh, yaw, pitch).unwrap();
        let camera = Camera::reference(w, h);
        let mode = Textured::<Rgb888>::new(texture.with_filter(Filter::Nearest));
        let mut painted =
            HostPaintedRenderer::<_, Depth24>::for_mesh(&mesh, w, h, mode, Rgb888::new(1, 2, 3))
                .unwrap();
        painted
            .draw_mesh(&mesh, &model, &camera, Cull::None, |v| v.tex_coord())
            .unwrap();
        let mut colors = Vec::new();
        painted
            .render(&mut FnSink(|_: u16, row: &[Rgb888], _: &[u32]| {
                colors.extend_from_slice(row);
                Ok::<(), ()>(())
            }))
            .unwrap();
        let mut checked = 0;
        for (k, &id) in reference.ids.iter().enumerate() {
            let (i, j) = (k % usize::from(w), k / usize::from(w));
            if id == BACKGROUND || reference.boundary_distance(id, i, j) < 0.1 {
                continue;
            }
            let [u, v] = reference.interpolated_perspective(id, i, j).unwrap();
            let (x, y) = (u * 16.0, (1.0 - v) * 8.0);
            let tolerance = 1.0 / 32.0;
            let candidates: Vec<Rgb888> = [x - tolerance, x + tolerance]
                .iter()
                .flat_map(|&x| [y - tolerance, y + tolerance].map(|y| (x, y)))
                .map(|(x, y)| {
                    let (i, j) = (
                        (x.floor() as i64).rem_euclid(16),
                        (y.floor() as i64).rem_euclid(8),
                    );
                    Rgb888::from(Rgb565::from(RawU16::new(texels[(j * 16 + i) as usize])))
                })
                .collect();
            assert!(
                candidates.contains(&colors[k]),
                "{yaw}/{pitch} pixel ({i}, {j}) face {id}: {:?} not in {candidates:?}",
                colors[k]
            );
            checked += 1;
        }
        assert!(checked > 300, "{checked}");
    }
}
