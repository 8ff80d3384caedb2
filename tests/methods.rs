//! Every method on the same scenes: the z-buffer and every band height give
//! the scanline's frame bit for bit (face, colour and depth); the interval
//! scanline has no hard mismatch against the float64 reference; the
//! painter draws, and its memory has no depth at all.

use zline::Shading;
use zline::{Camera, Cull, reference_model};
use zline::{Depth16, Depth24, DepthFormat};
use zline_lab::methods::{Method, MethodRenderer, ReferenceView, compare};
use zline_lab::shapes;

const W: u16 = 160;
const H: u16 = 120;

fn frames<D: DepthFormat>(
    name: &str,
    yaw: f32,
    pitch: f32,
    cull: Cull,
) -> Vec<(Method, zline_lab::methods::MethodFrame)>
where
    D::Value: Into<u32>,
{
    let mesh = shapes::by_name(name).unwrap();
    let model = reference_model(&mesh, yaw, pitch).unwrap();
    let view = ReferenceView {
        width: usize::from(W),
        height: usize::from(H),
        yaw_deg: f64::from(yaw),
        pitch_deg: f64::from(pitch),
        cull_back: cull == Cull::Back,
    };
    let mut r = MethodRenderer::<D>::new(W, H).unwrap();
    Method::ALL
        .iter()
        .map(|&m| {
            let f = r
                .render(
                    m,
                    &mesh,
                    &model,
                    &Camera::reference(W, H),
                    cull,
                    &Shading::lambert(),
                    &view,
                )
                .unwrap();
            (m, f)
        })
        .collect()
}

#[test]
fn methods_agree_where_they_should() {
    for (name, yaw, pitch) in [
        ("torus-knot", 30.0, 20.0),
        ("boxes", 200.0, -35.0),
        ("icosphere", 30.0, 20.0),
    ] {
        for cull in [Cull::None, Cull::Back] {
            let all = frames::<Depth24>(name, yaw, pitch, cull);
            let get = |m: Method| &all.iter().find(|(k, _)| *k == m).unwrap().1;
            let scanline = get(Method::Scanline);
            for m in [
                Method::ZBuffer,
                Method::Bands(1),
                Method::Bands(8),
                Method::Bands(32),
            ] {
                let f = get(m);
                assert_eq!(f.faces, scanline.faces, "{name} {cull:?} {}", m.name());
                assert_eq!(f.depths, scanline.depths, "{name} {cull:?} {}", m.name());
                assert_eq!(f.colors, scanline.colors);
            }
            let reference = zline_lab::methods::ReferenceFrame::render(
                &shapes::by_name(name).unwrap(),
                &ReferenceView {
                    width: usize::from(W),
                    height: usize::from(H),
                    yaw_deg: f64::from(yaw),
                    pitch_deg: f64::from(pitch),
                    cull_back: cull == Cull::Back,
                },
            );
            // The runner's reference is the float64 reference of this view
            // (its size, angles and culling passed through).
            assert!(reference.ids.iter().any(|&f| f != u32::MAX), "{name}");
            assert_eq!(get(Method::Reference).faces, reference.ids);
            for m in [Method::Scanline, Method::Interval] {
                let c = compare(&reference, &get(m).faces);
                assert_eq!(c.hard, 0, "{name} {cull:?} {}: {c:?}", m.name());
            }
            // The painter runs; where it is wrong is the catalogue's business.
            let painter = get(Method::Painter);
            assert!(painter.faces.iter().any(|&f| f != u32::MAX));
            assert_eq!(painter.memory.depth, 0);
            assert_eq!(get(Method::Interval).memory.depth, 0);
        }
    }
}

#[test]
fn memory_follows_the_method() {
    let all = frames::<Depth16>("torus-knot", 30.0, 20.0, Cull::Back);
    let get = |m: Method| all.iter().find(|(k, _)| *k == m).unwrap().1.memory;
    assert_eq!(get(Method::ZBuffer).depth, 160 * 120 * 2, "a z16 frame");
    assert_eq!(get(Method::Bands(8)).depth, 160 * 8 * 2);
    assert_eq!(get(Method::Bands(1)).depth, 160 * 2);
    assert_eq!(get(Method::Scanline).depth, 160 * 2, "one row");
    assert!(get(Method::Scanline).total() < get(Method::ZBuffer).total());
}

#[test]
fn methods_parse_and_print() {
    for m in Method::ALL {
        assert_eq!(Method::parse(&m.name()), Ok(m));
    }
    assert!(Method::parse("bands:0").is_err());
    assert!(Method::parse("bands:x").is_err());
    assert!(Method::parse("zbuf").is_err());
}

/// A surface at the far plane's depth (depth 1, the value a cleared depth
/// row holds): the scanline and the z-buffer never draw it (a pixel is
/// written only where strictly nearer than what the row holds, or equal
/// to a written value), the interval method, comparing plane values with
/// no stored depth, does. In z16, where the far plane's value is the last
/// step, that holds for any depth rounding to it.
#[test]
fn a_surface_at_the_far_plane_shows_only_in_the_interval_method() {
    use zline::limits::DEPTH_MAX;
    use zline::{FnSink, ScreenVertex};
    use zline_lab::methods::interval::render_intervals;
    let s = zline::limits::SUBPIXEL_STEPS;
    let far = [(1, 1), (14, 1), (1, 10)]
        .map(|(x, y)| ScreenVertex::new(x * s, y * s, DEPTH_MAX).unwrap());
    let caps = zline::Capacities {
        width: 16,
        vertices: 8,
        polygons: 2,
        corners: 8,
        active_polygons: 2,
        pooled_edges: 0,
        mesh_vertices: 0,
    };
    let mut renderer = zline::host::host_renderer::<u32, Depth24>(&caps, 16, 12, 0).unwrap();
    renderer.push_polygon_vertices(&far, 1).unwrap();
    let (mut scanline, mut interval) = (0, 0);
    renderer
        .render(&mut FnSink(|_: u16, c: &[u32], _: &[u32]| {
            scanline += c.iter().filter(|&&c| c == 1).count();
            Ok::<(), ()>(())
        }))
        .unwrap();
    let prepared = renderer.tables.prepare();
    render_intervals::<u32, Depth24, _>(
        &prepared,
        0,
        &mut FnSink(|_: u16, c: &[u32], _: &[u32]| {
            interval += c.iter().filter(|&&c| c == 1).count();
            Ok::<(), ()>(())
        }),
    )
    .unwrap();
    assert_eq!(scanline, 0);
    assert!(interval > 40, "{interval}");
}
