// Generated from `cube.obj` by obj2rust: 8 vertices, 6 faces, 24 corners. Do not edit.

static CUBE_POSITIONS: [[f32; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [1.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [0.0, 1.0, 1.0],
];

static CUBE_CORNERS: [u16; 24] = [
    0, 1, 2, 3, 4, 5, 6, 7, 0, 3, 5, 4, 1, 7, 6, 2,
    0, 4, 7, 1, 3, 2, 6, 5,
];

static CUBE_FACE_STARTS: [u32; 6] = [
    0, 4, 8, 12, 16, 20,
];

// Bit f set: face f is planar (precomputed, so the pipeline need not test it).
static CUBE_PLANAR: [u32; 1] = [
    0x0000003F,
];

// Faces that share one plane with overlapping coplanar faces.
static CUBE_SHARED: [zline::SharedPlane; 0] = [
];

// Each face's normal (Newell's, model space), so shading need not read its corners.
static CUBE_NORMALS: [[f32; 3]; 6] = [
    [0.0, 0.0, -1.0],
    [0.0, 0.0, 1.0],
    [0.0, -1.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
];

/// Mesh from `cube.obj` by obj2rust, checked at compile time.
pub static CUBE: zline::StaticMesh<'static> = match zline::StaticMesh::new(
    &CUBE_POSITIONS,
    &CUBE_CORNERS,
    &CUBE_FACE_STARTS,
) {
    Ok(mesh) => match mesh.with_planar_faces(&CUBE_PLANAR) {
        Ok(mesh) => match mesh.with_shared_planes(&CUBE_SHARED) {
            Ok(mesh) => match mesh.with_face_normals(&CUBE_NORMALS) {
                Ok(mesh) => mesh.with_closed_hull(zline::ClosedHull { centre: [0.5, 0.5, 0.5], radius: 0.8660262 }),
                Err(_) => panic!("CUBE: invalid face normals"),
            },
            Err(_) => panic!("CUBE: invalid shared planes"),
        },
        Err(_) => panic!("CUBE: invalid planarity bits"),
    },
    Err(_) => panic!("CUBE: invalid mesh"),
};
