//! `needs`: the capacities it prints for a mesh hold every view it says
//! they cover, culled and not, in a renderer sized by them alone, with the
//! mesh drawn through the renderer's own vertex cache.

use zline::host::{HostRenderer, host_renderer};
use zline::{Camera, Cull, Depth16, FnSink, Mesh, reference_model};
use zline_lab::needs::{Views, capacities, line};
use zline_lab::shapes;

/// Draws every view of `views` in a renderer of exactly `caps`.
fn draws_every_view<M: Mesh>(mesh: &M, views: &Views, caps: &zline::Capacities) {
    let (w, h) = views.size;
    let mut renderer: HostRenderer<u32, Depth16> = host_renderer(caps, w, h, 0).unwrap();
    let camera = Camera::reference(w, h);
    let mut drawn = 0;
    for (yaw, pitch, cull) in views.each() {
        let model = reference_model(mesh, yaw, pitch).unwrap();
        renderer.clear();
        renderer
            .draw_mesh(mesh, &model, &camera, cull, |f| f.face + 1)
            .unwrap_or_else(|e| panic!("yaw {yaw} pitch {pitch} {cull:?} at {caps:?}: {e}"));
        let frame = renderer
            .render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
            .unwrap_or_else(|e| panic!("yaw {yaw} pitch {pitch} {cull:?} at {caps:?}: {e:?}"));
        drawn += usize::from(frame.polygons > 0);
    }
    assert_eq!(drawn, views.each().count(), "every view draws something");
}

#[test]
fn the_printed_capacities_draw_every_view_culled_and_not() {
    for mesh in [shapes::torus_knot(2, 3, 64, 8, 0.45), shapes::box_field(3)] {
        let views = Views::grid((96, 72), 30.0, 45.0);
        assert_eq!(views.culls, [Cull::None, Cull::Back]);
        let caps = capacities(&mesh, &views, 0).unwrap();
        assert_eq!(caps.mesh_vertices, mesh.vertex_count());
        draws_every_view(&mesh, &views, &caps);
        // One line, pasteable.
        let text = line(&caps);
        assert!(text.starts_with("const CAPS: zline::Capacities = zline::Capacities {"));
        assert!(!text.contains('\n'));
        // And one count short of it does not draw them all: the sizes are
        // the views' own, not a guess.
        let short = zline::Capacities {
            corners: caps.corners - 1,
            ..caps
        };
        let result = std::panic::catch_unwind(|| draws_every_view(&mesh, &views, &short));
        assert!(result.is_err(), "one corner fewer still drew every view");
    }
}
