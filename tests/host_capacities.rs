//! `HostMesh::capacities`: storage sized from the mesh alone holds every
//! view of it, culled or not, with faces clipped by the near and far
//! planes and the clip band: no capacity error, ever.

use proptest::prelude::*;
use zline::host::{HostMesh, host_renderer};
use zline::{Camera, Cull, VertexCache, draw_mesh};
use zline::{Depth16, Error, FnSink};
use zline::{Mat4, Vec3};

/// Draws `mesh` through `camera` in storage of `mesh.capacities(..)` and
/// renders it: any error is returned (none is expected).
fn draw(mesh: &HostMesh, camera: &Camera, cull: Cull) -> Result<(), Error> {
    let caps = mesh.capacities(camera.width);
    let mut renderer = host_renderer::<u32, Depth16>(&caps, camera.width, camera.height, 0)?;
    let mut cache: Box<VertexCache<65536>> = Box::default();
    draw_mesh(
        &mut renderer,
        &mut *cache,
        mesh,
        &Mat4::IDENTITY,
        camera,
        cull,
        |f| f.face + 1,
    )
    .map_err(|e| e.error)?;
    renderer
        .render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
        .map_err(|e| match e {
            zline::RenderError::Table(e) => e,
            zline::RenderError::Sink(()) => unreachable!(),
        })?;
    Ok(())
}

/// A camera at `eye` looking at `target`, 64x48, fov 90, near 0.1, far 100.
fn camera(eye: Vec3, target: Vec3) -> Camera {
    let view = Mat4::look_at(eye, target, Vec3::new(0.0, 1.0, 0.0));
    Camera::perspective(view, 90.0, 64, 48, 0.1, 100.0)
}

/// Issue 28, item 3: a fan of 1,100 triangles whose centre lies behind
/// the eye: every triangle is clipped and makes corners of its own, more
/// than the 2 x positions + 1,024 vertices the capacities allowed
/// (`VertexTableFull`).
#[test]
fn a_fan_around_a_point_behind_the_eye_fits() {
    let n = 1100;
    let mut mesh = HostMesh::default();
    mesh.positions.push([0.0, 0.0, 1.0]); // behind the eye at the origin
    for k in 0..n {
        let a = k as f32 / n as f32 * std::f32::consts::TAU;
        mesh.positions.push([a.cos() * 2.0, a.sin() * 2.0, -3.0]);
    }
    for k in 0..n {
        mesh.face_starts.push(mesh.corners.len() as u32);
        let (b, c) = (1 + k as u16, 1 + ((k + 1) % n) as u16);
        mesh.corners.extend([0, b, c]);
    }
    let mesh = mesh.with_face_analysis();
    let camera = camera(Vec3::default(), Vec3::new(0.0, 0.0, -1.0));
    for cull in [Cull::None, Cull::Back] {
        draw(&mesh, &camera, cull).unwrap();
    }
}

/// A face of 3 to 8 corners: a regular polygon, a star (concave), or one
/// bent out of its plane, around `centre`, of radius `r`, turned by
/// `tilt`.
fn face() -> impl Strategy<Value = Vec<[f32; 3]>> {
    (
        3usize..=8,
        0u8..3,
        prop::array::uniform3(-4.0f32..4.0),
        0.5f32..20.0,
        prop::array::uniform2(-3.2f32..3.2),
    )
        .prop_map(|(n, kind, centre, r, [tx, ty])| {
            let turn = Mat4::rotation_x(tx).mul(&Mat4::rotation_y(ty));
            (0..n)
                .map(|k| {
                    let a = k as f32 / n as f32 * std::f32::consts::TAU;
                    let radius = if kind == 1 && k % 2 == 1 { r * 0.3 } else { r };
                    let lift = if kind == 2 && k == n - 1 {
                        r * 0.5
                    } else {
                        0.0
                    };
                    let p =
                        turn.transform_point(Vec3::new(a.cos() * radius, a.sin() * radius, lift));
                    [centre[0] + p.x, centre[1] + p.y, centre[2] + p.z]
                })
                .collect()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Meshes of triangles, convex and concave polygons and bent faces,
    /// seen from inside and around them (most faces clipped by the near
    /// plane or the clip band), culled or not: the mesh's own capacities
    /// always hold the frame.
    #[test]
    fn capacities_hold_every_view(
        faces in prop::collection::vec(face(), 1..40),
        fan in prop::option::of((200usize..1500, 0.1f32..0.9, 0.1f32..2.0)),
        eye in prop::array::uniform3(-6.0f32..6.0),
        target in prop::array::uniform3(-6.0f32..6.0),
        cull in any::<bool>(),
    ) {
        let mut mesh = HostMesh::default();
        for corners in &faces {
            mesh.face_starts.push(mesh.corners.len() as u32);
            for p in corners {
                mesh.corners.push(mesh.positions.len() as u16);
                mesh.positions.push(*p);
            }
        }
        // A fan of many triangles around a centre just behind the eye,
        // its rim in view around the target: each triangle clipped by the
        // near plane makes corners of its own.
        let (e, t) = (Vec3::from_array(eye), Vec3::from_array(target));
        let d = (t - e).normalized();
        let u = d.cross(Vec3::new(0.0, 1.0, 0.0));
        if let (Some((n, spread, behind)), true) = (fan, u.length() > 0.1) {
            let (u, radius) = (u.normalized(), (t - e).length() * spread);
            let v = u.cross(d);
            let centre = mesh.positions.len() as u16;
            let c = e - d * behind;
            mesh.positions.push([c.x, c.y, c.z]);
            for k in 0..n {
                let a = k as f32 / n as f32 * std::f32::consts::TAU;
                let p = t + u * (a.cos() * radius) + v * (a.sin() * radius);
                mesh.positions.push([p.x, p.y, p.z]);
            }
            for k in 0..n {
                mesh.face_starts.push(mesh.corners.len() as u32);
                let (b, c) = (centre + 1 + k as u16, centre + 1 + ((k + 1) % n) as u16);
                mesh.corners.extend([centre, b, c]);
            }
        }
        let mesh = mesh.with_face_analysis();
        let (eye, target) = (Vec3::from_array(eye), Vec3::from_array(target));
        prop_assume!((eye - target).length() > 0.1);
        let cull = if cull { Cull::Back } else { Cull::None };
        prop_assert_eq!(draw(&mesh, &camera(eye, target), cull), Ok(()));
    }
}
