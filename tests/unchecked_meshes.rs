//! Meshes whose arrays were never checked (a `HostMesh` built field by
//! field) and ranges at the ends of the integer types: each comes back as
//! an error, never a panic (the tests run with overflow checks).

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use zline::host::{HostMesh, HostRenderer};
use zline::{Camera, Cull, Depth16, DrawTargetSink, Error, ProjectedVertex, reference_model};

/// A unit quad in front of the reference camera, as one face of four
/// corners.
fn quad() -> HostMesh {
    HostMesh {
        positions: vec![
            [-0.5, -0.5, 0.0],
            [0.5, -0.5, 0.0],
            [0.5, 0.5, 0.0],
            [-0.5, 0.5, 0.0],
        ],
        corners: vec![0, 1, 2, 3],
        face_starts: vec![0],
        ..HostMesh::default()
    }
}

/// Draws `mesh` into a 32x32 renderer; the error, if any.
fn draw(mesh: &HostMesh) -> Result<(), Error> {
    let mut renderer =
        HostRenderer::<Rgb565, Depth16>::for_mesh(&quad(), 32, 32, Rgb565::BLACK).unwrap();
    let model = reference_model(&quad(), 0.0, 0.0).unwrap();
    renderer
        .draw_mesh(mesh, &model, &Camera::reference(32, 32), Cull::None, |_| {
            Rgb565::WHITE
        })
        .map(|_| ())
        .map_err(|e| e.error)
}

#[test]
fn the_checked_quad_draws() {
    assert_eq!(draw(&quad()), Ok(()));
}

/// Whether an unchecked mesh's draw reports its fault as an error: not
/// for texture coordinates (flat drawing reads none), nor for a face of
/// one or two corners, which a draw counts as degenerate, as it does a
/// face of no area.
fn draw_fails(what: &str) -> bool {
    !what.contains("texture") && !what.contains("one corner")
}

#[test]
fn every_unchecked_mesh_is_an_error_to_draw() {
    for (what, mesh) in unchecked_meshes() {
        if draw_fails(what) {
            assert_eq!(draw(&mesh), Err(Error::MeshIndexOutOfRange), "{what}");
        }
    }
}

#[test]
fn a_face_of_one_corner_is_counted_degenerate() {
    let mut mesh = quad();
    mesh.face_starts = vec![0, 3];
    let mut renderer =
        HostRenderer::<Rgb565, Depth16>::for_mesh(&quad(), 32, 32, Rgb565::BLACK).unwrap();
    let model = reference_model(&quad(), 0.0, 0.0).unwrap();
    let stats = renderer
        .draw_mesh(
            &mesh,
            &model,
            &Camera::reference(32, 32),
            Cull::None,
            |_| Rgb565::WHITE,
        )
        .unwrap();
    assert_eq!(stats.degenerate, 1);
}

#[test]
fn a_corner_beyond_the_positions_is_an_error() {
    for bad in [4u16, 9, u16::MAX] {
        let mut mesh = quad();
        mesh.corners[3] = bad;
        assert_eq!(draw(&mesh), Err(Error::MeshIndexOutOfRange), "corner {bad}");
    }
}

#[test]
fn face_starts_beyond_the_corners_are_an_error() {
    for starts in [vec![0, 10], vec![5], vec![3, 1], vec![u32::MAX]] {
        let mut mesh = quad();
        mesh.face_starts = starts.clone();
        assert_eq!(
            draw(&mesh),
            Err(Error::MeshIndexOutOfRange),
            "face starts {starts:?}"
        );
    }
}

#[test]
fn projecting_past_the_end_of_usize_is_an_error() {
    let mesh = quad();
    let model = reference_model(&mesh, 0.0, 0.0).unwrap();
    let mut out = [ProjectedVertex::NonFinite; 2];
    assert_eq!(
        zline::project_vertices(
            &mesh,
            &model,
            &Camera::reference(32, 32),
            usize::MAX,
            &mut out
        ),
        Err(Error::MeshIndexOutOfRange)
    );
}

#[test]
fn an_origin_at_the_end_of_i32_sends_nothing_past_it() {
    let mesh = quad();
    let mut renderer =
        HostRenderer::<Rgb565, Depth16>::for_mesh(&mesh, 8, 4, Rgb565::BLACK).unwrap();
    let model = reference_model(&mesh, 0.0, 0.0).unwrap();
    renderer
        .draw_mesh(&mesh, &model, &Camera::reference(8, 4), Cull::None, |_| {
            Rgb565::WHITE
        })
        .unwrap();
    // Rows 1 to 3 would lie below i32::MAX; row 0 lands on it, off the
    // mock display, which then ignores it.
    let mut display = MockDisplay::<Rgb565>::new();
    display.set_allow_out_of_bounds_drawing(true);
    renderer
        .render(&mut DrawTargetSink::with_origin(
            &mut display,
            Point::new(0, i32::MAX),
        ))
        .unwrap();
    let mut display = MockDisplay::<Rgb565>::new();
    display.set_allow_out_of_bounds_drawing(true);
    renderer
        .render(&mut DrawTargetSink::with_origin(
            &mut display,
            Point::new(i32::MAX, 0),
        ))
        .unwrap();
}

/// Quads and triangles whose arrays break [`zline::StaticMesh::new`]'s
/// rules, each with what is wrong.
fn unchecked_meshes() -> Vec<(&'static str, HostMesh)> {
    let mut meshes = Vec::new();
    for (what, bad) in [("corner 4", 4u16), ("corner 65535", u16::MAX)] {
        let mut mesh = quad();
        mesh.corners[3] = bad;
        meshes.push((what, mesh));
    }
    for (what, starts) in [
        ("starts past the corners", vec![0, 10]),
        ("a face of one corner", vec![3]),
        ("starts decreasing", vec![3, 1]),
        ("a start at u32::MAX", vec![u32::MAX]),
    ] {
        let mut mesh = quad();
        mesh.face_starts = starts;
        meshes.push((what, mesh));
    }
    let mut short_uvs = quad();
    short_uvs.uvs = vec![[0.0; 2]; 2];
    meshes.push(("two texture coordinates for four vertices", short_uvs));
    meshes
}

#[test]
fn analysing_an_unchecked_mesh_is_an_error_or_leaves_it_as_it_is() {
    for (what, mesh) in unchecked_meshes() {
        // Sizing never panics; the analyses leave the mesh as it is.
        let _ = mesh.capacities(32);
        assert!(mesh.check().is_err(), "{what}");
        if what.contains("texture") {
            // Only the reordering reads texture coordinates.
            assert_eq!(
                mesh.clone().with_vertices_in_first_use_order(),
                mesh,
                "{what}"
            );
            continue;
        }
        assert_eq!(mesh.clone().with_face_analysis(), mesh, "{what}");
        assert_eq!(
            mesh.clone().with_vertices_in_first_use_order(),
            mesh,
            "{what}"
        );
        assert!(mesh.clone().with_vertex_normals(60.0).is_err(), "{what}");
        assert_eq!(
            zline::host::QuantizedHostMesh::new(&mesh).err(),
            Some(Error::MeshIndexOutOfRange),
            "{what}"
        );
        assert_eq!(zline::host::closed_hull(&mesh), None, "{what}");
        assert_eq!(zline::host::capped_hull(&mesh), None, "{what}");
        assert!(
            zline::host::coplanar::shared_planes(&mesh).is_empty(),
            "{what}"
        );
        assert!(zline::Triangles::new(&mesh).is_err(), "{what}");
    }
}

#[test]
fn drawing_an_unchecked_mesh_in_bands_is_an_error() {
    use zline::FrameBufferSink;
    use zline::host::BandedRenderer;
    for (what, mesh) in unchecked_meshes() {
        if !draw_fails(what) {
            continue;
        }
        let mut renderer = BandedRenderer::<Rgb565, Depth16>::new(
            &quad().capacities(32),
            32,
            32,
            Rgb565::BLACK,
            2,
        )
        .unwrap();
        let model = reference_model(&quad(), 0.0, 0.0).unwrap();
        let mut top = vec![Rgb565::BLACK; 32 * 16];
        let mut bottom = vec![Rgb565::BLACK; 32 * 16];
        let mut sinks = [
            FrameBufferSink::new(&mut top, 32),
            FrameBufferSink::from_row(&mut bottom, 32, 16),
        ];
        let result = renderer.render_mesh(
            &mesh,
            &model,
            &Camera::reference(32, 32),
            Cull::None,
            &mut sinks,
            |_| Rgb565::WHITE,
        );
        assert!(
            matches!(
                result,
                Err(zline::RenderError::Table(Error::MeshIndexOutOfRange))
            ),
            "{what}: {result:?}"
        );
    }
}

#[test]
fn storage_larger_than_memory_is_an_error() {
    let mut caps = quad().capacities(32);
    for huge in [usize::MAX, usize::MAX / 2, 1 << 60] {
        caps.corners = huge;
        assert!(
            zline::host::host_renderer::<Rgb565, Depth16>(&caps, 32, 32, Rgb565::BLACK).is_err(),
            "corners {huge}"
        );
    }
}

#[test]
fn capacities_of_meshes_past_usize_saturate() {
    use zline::{Capacities, MeshCounts};
    for (faces, corners) in [
        (usize::MAX, usize::MAX),
        (usize::MAX / 3, usize::MAX / 2 + 7),
    ] {
        let counts = MeshCounts {
            vertices: usize::MAX,
            faces,
            corners,
            shared_plane_faces: 1,
        };
        let caps = Capacities::worst_case(&counts, 240);
        assert_eq!(caps.vertices, 1 << 16);
        assert_eq!(caps.ram_bytes::<Rgb565, Depth16>(), usize::MAX);
    }
}

#[test]
fn a_dither_threshold_past_16_bits_gives_a_colour() {
    use zline::paint::{CHANNEL_MAX, PaintColor};
    for threshold in [1 << 16, u32::MAX - 1, u32::MAX] {
        let _ = Rgb565::from_channels([CHANNEL_MAX; 3], Some(threshold));
    }
}
