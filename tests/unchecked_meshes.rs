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
