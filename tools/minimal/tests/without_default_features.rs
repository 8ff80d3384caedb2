//! zline built without its default features (`zbuffer`, `clipping`,
//! `polygons`).

use zline::{
    Camera, Cull, Depth16, DrawError, Error, Mat4, Renderer, ScanArrays, StaticMesh, TableArrays,
    VertexCache,
};

type Small = Renderer<TableArrays<u8, 8, 4, 16>, ScanArrays<u8, Depth16, 32, 4, 8>, VertexCache<8>>;

/// Draws one triangle through a 60-degree camera at the origin, 32x32.
fn draw(corners: [[f32; 3]; 3]) -> Result<zline::DrawStats, DrawError> {
    draw_face(&corners)
}

/// Draws one face with these corners (in order), as above.
fn draw_face(corners: &[[f32; 3]]) -> Result<zline::DrawStats, DrawError> {
    let ids: Vec<u16> = (0..corners.len() as u16).collect();
    let mesh = StaticMesh::new(corners, &ids, &[0]).unwrap();
    let camera = Camera::perspective(Mat4::IDENTITY, 60.0, 32, 32, 0.5, 100.0);
    let mut renderer = Small::new(32, 32, 0).unwrap();
    renderer.draw_mesh(&mesh, &Mat4::IDENTITY, &camera, Cull::None, |_| 1)
}

/// A face with a corner behind the eye needs the clipper: refused with
/// `Error::NeedsClipping`, not dropped.
#[test]
fn a_face_that_needs_clipping_is_refused() {
    let drawn = draw([[-1.0, -1.0, -5.0], [1.0, -1.0, -5.0], [0.0, 1.0, 5.0]]);
    assert_eq!(
        drawn,
        Err(DrawError {
            face: Some(0),
            error: Error::NeedsClipping
        })
    );
}

/// A face inside the frustum is drawn as with the features.
#[test]
fn a_face_inside_the_frustum_is_drawn() {
    let stats = draw([[-1.0, -1.0, -5.0], [1.0, -1.0, -5.0], [0.0, 1.0, -5.0]]).unwrap();
    assert_eq!((stats.queued, stats.clipped), (1, 0));
}

/// A convex quad is drawn as two triangles; a pentagon needs the
/// `polygons` feature and is refused with `Error::NeedsPolygons`.
#[test]
fn polygons_of_more_corners_are_refused() {
    let quad = [
        [-1.0, -1.0, -5.0],
        [1.0, -1.0, -5.0],
        [1.0, 1.0, -5.0],
        [-1.0, 1.0, -5.0],
    ];
    let stats = draw_face(&quad).unwrap();
    assert_eq!(stats.queued, 2);
    let pentagon = [
        [-1.0, -1.0, -5.0],
        [1.0, -1.0, -5.0],
        [1.5, 0.5, -5.0],
        [0.0, 1.5, -5.0],
        [-1.5, 0.5, -5.0],
    ];
    assert_eq!(
        draw_face(&pentagon),
        Err(DrawError {
            face: Some(0),
            error: Error::NeedsPolygons
        })
    );
}
