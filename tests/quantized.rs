//! The integer front end: quantized meshes drawn with no floating point per
//! vertex or face. The frames must be as right as the `f32` front end's
//! against the float64 reference (no hard mismatch), Lambert colours
//! within one step of the `f32` ones, and matrices the integer path cannot
//! take must fall back to `f32` and still draw the right faces.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use zline::QuantizedMesh;
use zline::Shading;
use zline::host::{HostMesh, QuantizedHostMesh};
use zline::{Camera, Cull, reference_model};
use zline::{Depth16, Depth24, DepthFormat};
use zline::{Mat4, Vec3};
use zline::{Mesh, StaticMesh};
use zline_lab::methods::{HostScanline, ReferenceFrame, ReferenceView, compare};
use zline_lab::shapes;

const W: u16 = 160;
const H: u16 = 120;

fn ids<D: DepthFormat, M: Mesh>(
    mesh: &M,
    model: &Mat4,
    cull: Cull,
    shading: &Shading,
) -> (Vec<u32>, Vec<Rgb888>)
where
    D::Value: Into<u32>,
{
    ids_with::<D, M>(mesh, model, &Camera::reference(W, H), cull, shading)
}

fn ids_with<D: DepthFormat, M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    shading: &Shading,
) -> (Vec<u32>, Vec<Rgb888>)
where
    D::Value: Into<u32>,
{
    let mut host = HostScanline::<D>::new(W, H).unwrap();
    host.render(mesh, model, camera, cull, shading).unwrap();
    (host.frame().faces.clone(), host.frame().colors.clone())
}

fn reference(mesh: &HostMesh, yaw: f32, pitch: f32, cull: Cull) -> ReferenceFrame {
    ReferenceFrame::render(
        mesh,
        &ReferenceView {
            width: usize::from(W),
            height: usize::from(H),
            yaw_deg: f64::from(yaw),
            pitch_deg: f64::from(pitch),
            cull_back: cull == Cull::Back,
        },
    )
}

/// The quantized mesh read back in `f32`, as an ordinary mesh: the same
/// geometry for the `f32` front end.
fn dequantized(q: &QuantizedMesh<'_>) -> HostMesh {
    HostMesh {
        positions: (0..q.vertex_count()).map(|i| q.position(i)).collect(),
        corners: q.corners().to_vec(),
        face_starts: q.face_starts().to_vec(),
        ..HostMesh::default()
    }
}

#[test]
fn integer_frames_have_no_hard_mismatch() {
    for (name, mesh) in [
        ("torus-knot", shapes::by_name("torus-knot").unwrap()),
        ("icosphere", shapes::by_name("icosphere").unwrap()),
        ("boxes", shapes::by_name("boxes").unwrap()),
    ] {
        let q = QuantizedHostMesh::new(&mesh).unwrap();
        let q = q.mesh().unwrap();
        for (yaw, pitch) in [(30.0, 20.0), (200.0, -35.0)] {
            for cull in [Cull::None, Cull::Back] {
                let model = reference_model(&mesh, yaw, pitch).unwrap();
                let r = reference(&mesh, yaw, pitch, cull);
                let (i24, _) = ids::<Depth24, _>(&q, &model, cull, &Shading::FaceId);
                let c = compare(&r, &i24);
                assert_eq!(c.hard, 0, "{name} {yaw}/{pitch} {cull:?} z24: {c:?}");
                // Not a frame of background: the mesh is there.
                assert!(
                    i24.iter().filter(|&&f| f != u32::MAX).count() > 1000,
                    "{name}"
                );
                let (i16, _) = ids::<Depth16, _>(&q, &model, cull, &Shading::FaceId);
                assert_eq!(
                    compare(&r, &i16).hard,
                    0,
                    "{name} {yaw}/{pitch} {cull:?} z16"
                );
            }
        }
    }
}

#[test]
fn integer_and_f32_front_ends_agree() {
    // The same geometry (the quantized positions, read back) through both
    // front ends: the same face almost everywhere, and Lambert colours
    // within one step where the face is the same.
    let mesh = shapes::by_name("torus-knot").unwrap();
    let q = QuantizedHostMesh::new(&mesh).unwrap();
    let q = q.mesh().unwrap();
    let plain = dequantized(&q);
    let shading = Shading::lambert();
    for (yaw, pitch) in [(30.0, 20.0), (110.0, 60.0)] {
        let model = reference_model(&plain, yaw, pitch).unwrap();
        let (fi, ci) = ids::<Depth24, _>(&q, &model, Cull::Back, &shading);
        let (ff, cf) = ids::<Depth24, _>(&plain, &model, Cull::Back, &shading);
        let same = fi.iter().zip(&ff).filter(|(a, b)| a == b).count();
        assert!(
            same * 1000 >= fi.len() * 998,
            "{same} of {} pixels agree",
            fi.len()
        );
        let mut lit = 0;
        for ((a, b), (x, y)) in fi.iter().zip(&ff).zip(ci.iter().zip(&cf)) {
            if a == b && *a != u32::MAX {
                lit += 1;
                for (u, v) in [(x.r(), y.r()), (x.g(), y.g()), (x.b(), y.b())] {
                    assert!(u.abs_diff(v) <= 1, "face {a}: {x:?} vs {y:?}");
                }
            }
        }
        assert!(lit > 1000);
    }
}

#[test]
fn matrices_outside_the_integer_ranges_fall_back_to_f32() {
    let mesh = shapes::by_name("icosphere").unwrap();
    let q = QuantizedHostMesh::new(&mesh).unwrap();
    let q = q.mesh().unwrap();
    let plain = dequantized(&q);
    let base = reference_model(&plain, 30.0, 20.0).unwrap();
    // A shear: the transform stays integer, the normals come from f32.
    let mut shear = Mat4::IDENTITY;
    shear.m[0][1] = 0.4;
    let shear = shear.mul(&base);
    let near = Camera::reference(W, H);
    // The mesh a billion times larger and further: the same picture, but
    // coefficients beyond the integer ranges, so the whole draw is f32.
    let far = Camera::perspective(
        Mat4::translation(Vec3::new(0.0, 0.0, -3.0e9)),
        45.0,
        W,
        H,
        1.0e8,
        1.0e10,
    );
    let huge = Mat4::scale(Vec3::new(1.0e9, 1.0e9, 1.0e9)).mul(&base);
    // (That the shear keeps the integer transform without integer
    // normals, and the huge scale leaves it, is a unit test of the
    // integer front end.)
    for (model, camera) in [(shear, near), (huge, far)] {
        let shading = Shading::lambert();
        let (fi, ci) = ids_with::<Depth24, _>(&q, &model, &camera, Cull::None, &shading);
        let (ff, cf) = ids_with::<Depth24, _>(&plain, &model, &camera, Cull::None, &shading);
        let same = fi.iter().zip(&ff).filter(|(a, b)| a == b).count();
        assert!(same * 1000 >= fi.len() * 998);
        assert!(
            fi.iter().filter(|&&f| f != u32::MAX).count() > 1000,
            "the sphere is in view"
        );
        for ((a, b), (x, y)) in fi.iter().zip(&ff).zip(ci.iter().zip(&cf)) {
            if a == b {
                assert!(x.r().abs_diff(y.r()) <= 1 && x.g().abs_diff(y.g()) <= 1);
            }
        }
    }
}

#[test]
fn static_and_quantized_meshes_are_both_meshes() {
    // A quantized tetrahedron as statics, as `obj2rust --quantized` writes.
    static POSITIONS: [[i16; 3]; 4] = [
        [18918, 18918, 18918],
        [18918, -18918, -18918],
        [-18918, 18918, -18918],
        [-18918, -18918, 18918],
    ];
    static NORMALS: [[i16; 3]; 4] = [
        [18918, 18918, -18918],
        [18918, -18918, 18918],
        [-18918, 18918, 18918],
        [-18918, -18918, -18918],
    ];
    static Q: QuantizedMesh<'static> = match QuantizedMesh::new(
        &POSITIONS,
        &NORMALS,
        &[0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2],
        &[0, 3, 6, 9],
        &[0xF],
        [0.0; 3],
        1.7320508,
    ) {
        Ok(m) => m,
        Err(_) => panic!(),
    };
    let p = Q.position(0);
    assert!((p[0] - 1.0).abs() < 1e-3);
    let s = StaticMesh::new(
        &[[1.0, 1.0, 1.0], [0.0; 3], [1.0, 0.0, 0.0]],
        &[0, 1, 2],
        &[0],
    )
    .unwrap();
    assert!(s.quantized().is_none() && Q.quantized().is_some());
}
