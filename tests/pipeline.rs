//! The scene pipeline's guarantees that once failed at the edges of the
//! input range (issue 7): meshes of any finite size are normalised, one
//! vertex cache serves several meshes, and faces of many corners draw.

mod common;

use common::capture;
use zline::host::HostMesh;
use zline::limits::MAX_FACE_CORNERS;
use zline::{Camera, Cull, DrawError, VertexCache, bounding_sphere, draw_mesh, reference_model};
use zline::{Depth24, Error, Renderer};
use zline::{Mat4, Vec3};
use zline::{Mesh, StaticMesh};
use zline::{ScanArrays, TableArrays};
use zline_lab::shapes;

type Big = Renderer<TableArrays<u32, 2048, 2048, 6144>, ScanArrays<u32, Depth24, 96, 512, 512>>;
const W: u16 = 96;
const H: u16 = 72;

/// Face ids (+1, 0 for background) of `mesh` in the reference view.
fn ids(mesh: &HostMesh, model: &Mat4) -> Vec<u32> {
    let mut renderer = Box::new(Big::new(W, H, 0).unwrap());
    let mut cache: Box<VertexCache<4096>> = Box::new(VertexCache::new());
    let camera = Camera::reference(W, H);
    draw_mesh(
        &mut *renderer,
        &mut *cache,
        mesh,
        model,
        &camera,
        Cull::None,
        |f| f.face + 1,
    )
    .unwrap();
    capture(&mut *renderer).0.colors
}

fn scaled(mesh: &HostMesh, factor: f32) -> HostMesh {
    let mut out = mesh.clone();
    for p in &mut out.positions {
        *p = p.map(|c| c * factor);
    }
    out
}

/// A mesh's frame is the same whether its planarity bits are known or
/// each face is tested per frame (the bits only save the test).
#[test]
fn planarity_bits_change_no_pixel() {
    // Quads, some bent out of their plane (drawn as fans), some planar.
    let mut obj = String::new();
    for k in 0..12 {
        let (x, lift) = (k as f32 * 0.4 - 2.4, if k % 2 == 0 { 0.3 } else { 0.0 });
        for (dx, dy, z) in [
            (0.0, 0.0, 0.0),
            (0.5, 0.0, 0.2),
            (0.5, 1.0, lift),
            (0.0, 1.0, 0.1),
        ] {
            obj += &format!("v {} {} {}\n", x + dx, dy - 0.5 * (k % 3) as f32, z);
        }
        let v = 4 * k + 1;
        obj += &format!("f {} {} {} {}\n", v, v + 1, v + 2, v + 3);
    }
    let mesh = HostMesh::from_obj(obj.as_bytes()).unwrap();
    let bent = (0..mesh.face_count())
        .filter(|&f| !mesh.face_is_planar(f))
        .count();
    assert_eq!(bent, 6);
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let with_bits = ids(&mesh, &model);
    assert!(with_bits.iter().filter(|&&c| c != 0).count() > 500);
    let untested = HostMesh {
        planar_faces: Vec::new(),
        ..mesh.clone()
    };
    assert_eq!(ids(&untested, &model), with_bits);
}

/// Lambert colours (packed `0x00RRGGBB`) of `mesh` in the reference view.
fn lambert_colors(mesh: &HostMesh, model: &Mat4) -> Vec<u32> {
    let mut renderer = Box::new(Big::new(W, H, 0).unwrap());
    let mut cache: Box<VertexCache<4096>> = Box::new(VertexCache::new());
    let camera = Camera::reference(W, H);
    let light = zline::Shading::lambert();
    draw_mesh(
        &mut *renderer,
        &mut *cache,
        mesh,
        model,
        &camera,
        Cull::None,
        |f| {
            use embedded_graphics::prelude::RgbColor;
            let c = light.color(f);
            (u32::from(c.r()) << 16) | (u32::from(c.g()) << 8) | u32::from(c.b())
        },
    )
    .unwrap();
    capture(&mut *renderer).0.colors
}

/// Stored face normals (`HostMesh::face_normals`) only save reading the
/// corners: every pixel's Lambert colour is the same as with each normal
/// computed per frame, on planar faces and on the triangles of a bent
/// face's fan, each of which keeps its own normal.
#[test]
fn stored_face_normals_change_no_colour() {
    let mut obj = String::new();
    for k in 0..12 {
        let (x, lift) = (k as f32 * 0.4 - 2.4, if k % 2 == 0 { 0.3 } else { 0.0 });
        // Tilted differently quad by quad; the even ones bent.
        let (tx, ty) = (0.25 * (k % 4) as f32, -0.2 * (k % 3) as f32);
        for (dx, dy, z) in [
            (0.0, 0.0, 0.0),
            (0.5, 0.0, tx),
            (0.5, 1.0, tx + ty + lift),
            (0.0, 1.0, ty),
        ] {
            obj += &format!("v {} {} {}\n", x + dx, dy - 0.5 * (k % 3) as f32, z);
        }
        let v = 4 * k + 1;
        obj += &format!("f {} {} {} {}\n", v, v + 1, v + 2, v + 3);
    }
    let mesh = HostMesh::from_obj(obj.as_bytes()).unwrap();
    assert_eq!(mesh.face_normals.len(), mesh.face_count());
    assert_eq!(
        (0..mesh.face_count())
            .filter(|&f| !mesh.face_is_planar(f))
            .count(),
        6
    );
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let stored = lambert_colors(&mesh, &model);
    let computed = HostMesh {
        face_normals: Vec::new(),
        ..mesh.clone()
    };
    let per_frame = lambert_colors(&computed, &model);
    assert!(per_frame.iter().filter(|&&c| c != 0).count() > 500);
    // More than a handful of colours: the fans' triangles differ.
    let mut distinct = per_frame.clone();
    distinct.sort_unstable();
    distinct.dedup();
    assert!(distinct.len() > 12, "{} colours", distinct.len());
    assert_eq!(stored, per_frame);
}

fn knot() -> HostMesh {
    shapes::torus_knot(2, 3, 48, 8, 0.45)
}

#[test]
fn issue_7_item_4_meshes_of_any_size_are_normalised() {
    let mesh = knot();
    let base = ids(&mesh, &reference_model(&mesh, 30.0, 20.0).unwrap());
    assert!(base.iter().filter(|&&c| c != 0).count() > 1000);
    // Scaling by a power of two is exact: the frame is bit for bit the
    // same from 2^-100 to 2^100 (f32 squares overflowed beyond 2^63).
    for e in (-100..=100).step_by(10) {
        let big = scaled(&mesh, 2f32.powi(e));
        let model = reference_model(&big, 30.0, 20.0).unwrap();
        assert_eq!(ids(&big, &model), base, "scaled by 2^{e}");
    }
    // Powers of ten round each coordinate: nearly every pixel agrees.
    for factor in [1e-30f32, 1e-19, 1e19, 1e30, 1e36] {
        let other = scaled(&mesh, factor);
        let frame = ids(&other, &reference_model(&other, 30.0, 20.0).unwrap());
        let same = frame.iter().zip(&base).filter(|(a, b)| a == b).count();
        assert!(
            same * 100 >= base.len() * 99,
            "scaled by {factor:e}: {same} of {} pixels agree",
            base.len()
        );
    }
    // Beyond f32's normal range the scale is refused, not drawn blank.
    let huge = scaled(&mesh, 2f32.powi(126));
    assert_eq!(bounding_sphere(&huge), Err(Error::MeshExtent));
    assert!(reference_model(&huge, 0.0, 0.0).is_err());
    let tiny = scaled(&mesh, 2f32.powi(-128));
    assert_eq!(bounding_sphere(&tiny), Err(Error::MeshExtent));
    let infinite = scaled(&mesh, 2f32.powi(127));
    assert_eq!(bounding_sphere(&infinite), Err(Error::MeshExtent));
    // A one-point mesh has radius 0 and is drawn at its place unscaled.
    let point = StaticMesh::new(&[[1.0, 2.0, 3.0]; 3], &[0, 1, 2], &[0]).unwrap();
    assert_eq!(bounding_sphere(&point), Ok((Vec3::new(1.0, 2.0, 3.0), 0.0)));
}

#[test]
fn issue_7_item_5_one_cache_serves_two_meshes() {
    // Two meshes side by side in one frame, sharing one cache, against the
    // same two meshes merged into one.
    let knot = knot();
    let sphere = shapes::icosphere(1);
    let left = Mat4::translation(Vec3::new(-0.9, 0.0, 0.0))
        .mul(&reference_model(&knot, 30.0, 20.0).unwrap())
        .mul(&Mat4::scale(Vec3::new(1.0, 1.0, 1.0)));
    let right =
        Mat4::translation(Vec3::new(0.9, 0.2, -0.5)).mul(&Mat4::scale(Vec3::new(0.5, 0.5, 0.5)));
    let camera = Camera::reference(W, H);
    let mut renderer = Box::new(Big::new(W, H, 0).unwrap());
    let mut cache: Box<VertexCache<4096>> = Box::new(VertexCache::new());
    draw_mesh(
        &mut *renderer,
        &mut *cache,
        &knot,
        &left,
        &camera,
        Cull::Back,
        |f| f.face + 1,
    )
    .unwrap();
    let offset = knot.face_count() as u32;
    draw_mesh(
        &mut *renderer,
        &mut *cache,
        &sphere,
        &right,
        &camera,
        Cull::Back,
        |f| offset + f.face + 1,
    )
    .unwrap();
    let two = capture(&mut *renderer).0.colors;

    // The merged mesh, positions already placed in the world.
    let mut merged = HostMesh::default();
    for (mesh, model) in [(&knot, &left), (&sphere, &right)] {
        let base = merged.positions.len() as u16;
        for p in &mesh.positions {
            let q = model.transform_point(Vec3::from_array(*p));
            merged.positions.push([q.x, q.y, q.z]);
        }
        for f in 0..mesh.face_count() {
            merged.face_starts.push(merged.corners.len() as u32);
            merged
                .corners
                .extend(mesh.face(f).iter().map(|&c| c + base));
        }
    }
    let mut renderer = Box::new(Big::new(W, H, 0).unwrap());
    draw_mesh(
        &mut *renderer,
        &mut *cache,
        &merged,
        &Mat4::IDENTITY,
        &camera,
        Cull::Back,
        |f| f.face + 1,
    )
    .unwrap();
    let one = capture(&mut *renderer).0.colors;
    let both_seen = [1..=offset, offset + 1..=u32::MAX]
        .iter()
        .all(|r| two.iter().any(|c| r.contains(c)));
    assert!(both_seen, "both meshes are visible");
    let same = one.iter().zip(&two).filter(|(a, b)| a == b).count();
    // Transforming in two steps rounds differently from one: a few edge
    // pixels may differ, never whole faces.
    assert!(
        same * 1000 >= one.len() * 995,
        "{same} of {} pixels agree",
        one.len()
    );

    // The same mesh drawn twice with two model matrices: both copies show.
    let mut renderer = Box::new(Big::new(W, H, 0).unwrap());
    for (k, model) in [&left, &right].into_iter().enumerate() {
        draw_mesh(
            &mut *renderer,
            &mut *cache,
            &sphere,
            model,
            &camera,
            Cull::Back,
            |_| k as u32 + 1,
        )
        .unwrap();
    }
    let twice = capture(&mut *renderer).0.colors;
    for k in 1..=2 {
        let n = twice.iter().filter(|&&c| c == k).count();
        assert!(n > 200, "copy {k} covers {n} pixels");
    }
}

/// A disc of `n` corners (a planar face), facing the viewer.
fn disc(n: usize) -> HostMesh {
    let mut mesh = HostMesh::default();
    for k in 0..n {
        let a = std::f32::consts::TAU * k as f32 / n as f32;
        mesh.positions.push([libm::cosf(a), libm::sinf(a), 0.0]);
    }
    mesh.face_starts.push(0);
    mesh.corners.extend(0..n as u16);
    mesh
}

#[test]
fn issue_7_item_6_faces_of_many_corners_draw() {
    let camera = Camera::reference(W, H);
    let t = (22.5f64).to_radians().tan();
    for n in [27, 64, 256, MAX_FACE_CORNERS] {
        let mesh = disc(n);
        let frame = ids(&mesh, &Mat4::IDENTITY);
        // The unit disc at distance 3: a pixel whose ray meets z = 0
        // within radius cos(pi/n) (the polygon's inner circle) is drawn,
        // one beyond radius 1 is not.
        let (mut inside, mut outside) = (0, 0);
        for j in 0..usize::from(H) {
            for i in 0..usize::from(W) {
                let x = ((i as f64 + 0.5) / f64::from(W) * 2.0 - 1.0) * t * f64::from(W)
                    / f64::from(H)
                    * 3.0;
                let y = (1.0 - (j as f64 + 0.5) / f64::from(H) * 2.0) * t * 3.0;
                let r = (x * x + y * y).sqrt();
                let drawn = frame[j * usize::from(W) + i] == 1;
                if r < (std::f64::consts::PI / n as f64).cos() - 1e-3 {
                    assert!(drawn, "{n} corners: ({i}, {j}) at r = {r}");
                    inside += 1;
                } else if r > 1.0 + 1e-3 {
                    assert!(!drawn, "{n} corners: ({i}, {j}) at r = {r}");
                    outside += 1;
                }
            }
        }
        assert!(inside > 500 && outside > 500);
        let _ = camera;
    }
    // One corner more than the pipeline draws: an error naming the face.
    let mut mesh = disc(8);
    let big = disc(MAX_FACE_CORNERS + 1);
    mesh.positions = big.positions;
    mesh.face_starts.push(mesh.corners.len() as u32);
    mesh.corners.extend(0..(MAX_FACE_CORNERS + 1) as u16);
    let mut renderer = Box::new(Big::new(W, H, 0).unwrap());
    let mut cache: Box<VertexCache<4096>> = Box::new(VertexCache::new());
    let result = draw_mesh(
        &mut *renderer,
        &mut *cache,
        &mesh,
        &Mat4::IDENTITY,
        &camera,
        Cull::None,
        |_| 1,
    );
    let expected = DrawError {
        face: Some(1),
        error: Error::TooManyCorners,
    };
    assert_eq!(result, Err(expected));
    assert!(
        expected
            .to_string()
            .starts_with("face 1: polygon has more than 1024 corners")
    );
    // The OBJ reader refuses such a face at its line.
    let mut obj = String::new();
    for p in &mesh.positions {
        obj.push_str(&format!("v {} {} {}\n", p[0], p[1], p[2]));
    }
    obj.push('f');
    for k in 1..=MAX_FACE_CORNERS + 1 {
        obj.push_str(&format!(" {k}"));
    }
    let error = zline::obj::count(obj.as_bytes()).unwrap_err();
    assert_eq!(error.line, MAX_FACE_CORNERS as u32 + 2);
    assert_eq!(error.kind, zline::obj::ObjErrorKind::TooManyCorners);
    // So do the host's loaders, and they take a face of the most.
    for load in [
        |b: &[u8]| zline::host::HostMesh::from_obj(b).map(|_| ()),
        |b: &[u8]| zline::host::HostMesh::from_obj_smooth(b, 60.0).map(|_| ()),
    ] {
        let error = load(obj.as_bytes()).unwrap_err();
        assert_eq!(error.line, MAX_FACE_CORNERS as u32 + 2);
        assert_eq!(error.kind, zline::obj::ObjErrorKind::TooManyCorners);
        let most = obj.replace(&format!(" {}", MAX_FACE_CORNERS + 1), "");
        load(most.as_bytes()).unwrap();
    }
}

/// `HostMesh::from_obj` numbers vertices in the order faces first use
/// them: each face keeps its corners' positions, a vertex no face uses
/// comes last, shared planes keep their vertices, and every pixel (face
/// ids and Lambert colours) is the frame of the file's own numbering.
#[test]
fn first_use_order_changes_no_pixel() {
    // A torus knot written with its vertices in a scattered order, two
    // overlapping coplanar quads (a shared plane) and a vertex no face uses.
    let knot = shapes::torus_knot(2, 3, 48, 8, 0.3);
    let n = knot.positions.len();
    // The quads' vertices first in the file, the knot's after them.
    let file_index = |v: usize| 8 + (v * 37) % n; // 37 and n coprime
    assert_ne!(n % 37, 0);
    let mut file_positions = vec![
        [-1.0, -1.0, 1.2],
        [0.2, -1.0, 1.2],
        [0.2, 0.2, 1.2],
        [-1.0, 0.2, 1.2],
        [-0.6, -0.6, 1.2],
        [0.6, -0.6, 1.2],
        [0.6, 0.6, 1.2],
        [-0.6, 0.6, 1.2],
    ];
    file_positions.resize(8 + n, [0.0; 3]);
    for (v, p) in knot.positions.iter().enumerate() {
        file_positions[file_index(v)] = *p;
    }
    file_positions.push([0.05, 0.05, 0.05]);
    let mut file_corners: Vec<u16> = knot
        .corners
        .iter()
        .map(|&c| file_index(usize::from(c)) as u16)
        .collect();
    let mut face_starts = knot.face_starts.clone();
    for quad in [[0, 1, 2, 3], [4, 5, 6, 7]] {
        face_starts.push(file_corners.len() as u32);
        file_corners.extend(quad);
    }
    let mut obj = String::new();
    for p in &file_positions {
        obj += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for (f, &start) in face_starts.iter().enumerate() {
        let end = face_starts
            .get(f + 1)
            .map_or(file_corners.len(), |&e| e as usize);
        obj += "f";
        for &c in &file_corners[start as usize..end] {
            obj += &format!(" {}", c + 1);
        }
        obj += "\n";
    }
    let loaded = HostMesh::from_obj(obj.as_bytes()).unwrap();
    let file_order = HostMesh {
        positions: loaded_positions_in_file_order(&obj),
        corners: file_corners,
        face_starts,
        ..HostMesh::default()
    }
    .with_face_analysis();
    assert!(!file_order.shared_planes.is_empty());
    assert_eq!(loaded.shared_planes.len(), file_order.shared_planes.len());
    // First use order: each corner names a vertex seen before or the next.
    let mut next = 0;
    for &c in &loaded.corners {
        assert!(usize::from(c) <= next, "{c} after {next} vertices");
        next = next.max(usize::from(c) + 1);
    }
    assert_eq!(next, loaded.positions.len() - 1);
    assert_eq!(loaded.positions.last(), Some(&[0.05, 0.05, 0.05]));
    for f in 0..loaded.face_count() {
        let at = |m: &HostMesh| -> Vec<[f32; 3]> {
            m.face(f)
                .iter()
                .map(|&c| m.positions[usize::from(c)])
                .collect()
        };
        assert_eq!(at(&loaded), at(&file_order), "face {f}");
    }
    for (a, b) in loaded.shared_planes.iter().zip(&file_order.shared_planes) {
        assert_eq!(a.face, b.face);
        let at = |m: &HostMesh, v: [u16; 3]| v.map(|v| m.positions[usize::from(v)]);
        assert_eq!(at(&loaded, a.vertices), at(&file_order, b.vertices));
    }
    let model = reference_model(&loaded, 30.0, 20.0).unwrap();
    let frame = ids(&loaded, &model);
    let covered = frame.iter().filter(|&&c| c != 0).count();
    assert!(covered > 1000, "{covered}");
    assert_eq!(frame, ids(&file_order, &model));
    assert_eq!(
        lambert_colors(&loaded, &model),
        lambert_colors(&file_order, &model)
    );
    // Renumbering an analysed mesh keeps its shared planes' vertices.
    let renumbered = file_order.clone().with_vertices_in_first_use_order();
    assert_eq!(
        (&renumbered.positions, &renumbered.corners),
        (&loaded.positions, &loaded.corners)
    );
    for (a, b) in renumbered
        .shared_planes
        .iter()
        .zip(&file_order.shared_planes)
    {
        let at = |m: &HostMesh, v: [u16; 3]| v.map(|v| m.positions[usize::from(v)]);
        assert_eq!(at(&renumbered, a.vertices), at(&file_order, b.vertices));
    }
    assert_eq!(ids(&renumbered, &model), frame);
    // A mesh whose corners name a vertex it lacks is left as it is.
    let broken = HostMesh {
        corners: vec![2, 1, 7],
        face_starts: vec![0],
        positions: vec![[0.0; 3], [1.0; 3], [2.0; 3]],
        ..HostMesh::default()
    };
    assert_eq!(broken.clone().with_vertices_in_first_use_order(), broken);
}

/// The `v` lines of an OBJ file, in its order.
fn loaded_positions_in_file_order(obj: &str) -> Vec<[f32; 3]> {
    obj.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f32> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            [c[0], c[1], c[2]]
        })
        .collect()
}
