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

/// A mesh whose hull holds with caps over its holes (`Mesh::hull_caps`),
/// around a front face and a back face.
struct Capped<'a> {
    mesh: StaticMesh<'a>,
    caps: &'a [[[f32; 3]; 3]],
}

impl zline::Mesh for Capped<'_> {
    fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }
    fn position(&self, index: usize) -> [f32; 3] {
        self.mesh.position(index)
    }
    fn face_count(&self) -> usize {
        self.mesh.face_count()
    }
    fn face(&self, index: usize) -> &[u16] {
        self.mesh.face(index)
    }
    fn closed_hull(&self) -> Option<zline::ClosedHull> {
        Some(zline::ClosedHull {
            centre: [0.0, 0.0, -5.5],
            radius: 2.0,
        })
    }
    fn hull_caps(&self) -> &[[[f32; 3]; 3]] {
        self.caps
    }
}

/// Without the `std` feature the caps' window is not kept: a mesh with a
/// cap that faces the viewer is drawn with every face, and one whose hull
/// needs no caps culls its back face.
#[test]
fn a_mesh_with_caps_facing_the_viewer_draws_every_face() {
    use zline::Mesh;
    // A front face on the right, a back face (clockwise) on the left.
    let positions = [
        [0.2, -0.5, -5.0],
        [1.2, -0.5, -5.0],
        [0.7, 0.5, -5.0],
        [-1.2, -0.5, -6.0],
        [-0.7, 0.5, -6.0],
        [-0.2, -0.5, -6.0],
    ];
    let corners = [0, 1, 2, 3, 4, 5];
    let mesh = StaticMesh::new(&positions, &corners, &[0, 3]).unwrap();
    let camera = Camera::perspective(Mat4::IDENTITY, 60.0, 32, 32, 0.5, 100.0);
    let draw = |caps: &[[[f32; 3]; 3]]| {
        let capped = Capped { mesh, caps };
        assert_eq!(capped.face_count(), 2);
        let mut renderer = Small::new(32, 32, 0).unwrap();
        renderer
            .draw_mesh(&capped, &Mat4::IDENTITY, &camera, Cull::None, |_| 1)
            .unwrap()
    };
    // A cap facing the viewer, far to the right of the back face.
    let cap = [[[0.9, 0.6, -5.0], [1.4, 0.6, -5.0], [1.1, 0.9, -5.0]]];
    assert_eq!(draw(&cap).back_faces, 0);
    assert_eq!(draw(&[]).back_faces, 1);
}
