//! Vertices projected beforehand (`project_vertices`,
//! `draw_mesh_projected`) and the banded renderer's shared front end
//! (`BandedRenderer::render_mesh`): the rows are those `draw_mesh` and one
//! renderer send, on the float and the integer front end, with clipped
//! and non-finite vertices, culled or not.

use zline::Mat4;
use zline::Mesh;
use zline::host::{BandedRenderer, HostMesh, MESH_VERTICES, QuantizedHostMesh, host_renderer};
use zline::{
    Camera, Cull, DrawError, FaceInfo, ProjectedVertex, VertexCache, bounding_sphere, draw_mesh,
    draw_mesh_projected, project_vertices, reference_model, reference_model_around,
};
use zline::{Capacities, Depth16, Error, FnSink};
use zline_lab::shapes;

const WIDTH: u16 = 96;
const HEIGHT: u16 = 72;

/// A frame as (row, colours, depths), in the order the rows were sent.
type Rows = Vec<(u16, Vec<u32>, Vec<u16>)>;

type HostRenderer = zline::host::HostRenderer<u32, Depth16>;

fn caps() -> Capacities {
    Capacities {
        width: usize::from(WIDTH),
        vertices: 8192,
        polygons: 8192,
        corners: 32768,
        active_polygons: 8192,
        pooled_edges: 1024,
        mesh_vertices: 0,
    }
}

/// Each face in its own colour.
fn shade(f: &FaceInfo) -> u32 {
    f.face + 1
}

/// One renderer's rows after `build` filled its tables.
fn rows_of(build: impl FnOnce(&mut HostRenderer)) -> Rows {
    rows_sized(&caps(), (WIDTH, HEIGHT), build)
}

/// [`rows_of`] for other capacities and frame sizes.
fn rows_sized(
    caps: &Capacities,
    (width, height): (u16, u16),
    build: impl FnOnce(&mut HostRenderer),
) -> Rows {
    let mut renderer = host_renderer::<u32, Depth16>(caps, width, height, 0).unwrap();
    build(&mut renderer);
    let mut rows = Rows::new();
    renderer
        .render(&mut FnSink(|y: u16, c: &[u32], z: &[u16]| {
            rows.push((y, c.to_vec(), z.to_vec()));
            Ok::<(), ()>(())
        }))
        .unwrap();
    rows
}

/// The view the tests draw from: mesh, model matrix, camera, culling.
type View<'a, M> = (&'a M, &'a Mat4, &'a Camera, Cull);

/// The rows `draw_mesh` draws.
fn mesh_rows<M: Mesh>((mesh, model, camera, cull): View<'_, M>) -> Rows {
    let mut cache = Box::new(VertexCache::<4096>::new());
    rows_of(|r| {
        draw_mesh(r, &mut *cache, mesh, model, camera, cull, shade).unwrap();
    })
}

/// [`mesh_rows`] for a large mesh, in a `caps`-sized renderer of
/// `width` x `height`, no culling.
fn large_mesh_rows(
    caps: &Capacities,
    (width, height): (u16, u16),
    (mesh, model, camera): (&HostMesh, &Mat4, &Camera),
) -> Rows {
    rows_sized(caps, (width, height), |r| {
        let mut cache = Box::new(VertexCache::<65536>::new());
        draw_mesh(r, &mut *cache, mesh, model, camera, Cull::None, shade).unwrap();
    })
}

/// The rows `draw_mesh_projected` draws from `projection` and `faces`.
fn projected_rows<M: Mesh>(
    (mesh, model, camera, cull): View<'_, M>,
    projection: &[ProjectedVertex],
    faces: Option<&[u32]>,
) -> Rows {
    let mut cache = Box::new(VertexCache::<4096>::new());
    rows_of(|r| {
        let c = &mut *cache;
        draw_mesh_projected(r, c, projection, faces, mesh, model, camera, cull, shade).unwrap();
    })
}

fn drawn(rows: &Rows) -> usize {
    rows.iter().flat_map(|r| &r.1).filter(|&&c| c != 0).count()
}

/// Every vertex of `mesh`, projected in `runs` runs put side by side.
fn projected<M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    runs: usize,
) -> Vec<ProjectedVertex> {
    let mut out = vec![ProjectedVertex::NonFinite; mesh.vertex_count()];
    let run = mesh.vertex_count().div_ceil(runs).max(1);
    for (k, part) in out.chunks_mut(run).enumerate() {
        project_vertices(mesh, model, camera, k * run, part).unwrap();
    }
    out
}

/// A corridor around the reference camera (at z = 3, looking down -z):
/// walls, floor and ceiling from z = 4, behind the camera, to z = -6, in
/// two lengths of two triangles each. The nearer length crosses the near
/// plane: its faces are clipped, and they cover most of the frame.
fn corridor() -> HostMesh {
    let mut mesh = HostMesh::default();
    let section = [[-0.5f32, -0.4], [0.5, -0.4], [0.5, 0.4], [-0.5, 0.4]];
    for side in 0..4 {
        let (a, b) = (section[side], section[(side + 1) % 4]);
        let base = mesh.positions.len() as u16;
        for z in [4.0, -1.0, -6.0] {
            mesh.positions.push([a[0], a[1], z]);
            mesh.positions.push([b[0], b[1], z]);
        }
        for k in 0..2 {
            let [p, q, r, t] = [0, 1, 2, 3].map(|i| base + 2 * k + i);
            for face in [[p, q, t], [p, t, r]] {
                mesh.face_starts.push(mesh.corners.len() as u32);
                mesh.corners.extend_from_slice(&face);
            }
        }
    }
    mesh
}

/// The meshes and views the tests draw: a torus knot from the reference
/// view and from close up; a corridor through the camera (clipped faces);
/// a field of boxes (quads, shared planes); a mesh with a non-finite
/// vertex.
fn scenes() -> Vec<(&'static str, HostMesh, Mat4)> {
    let knot = shapes::torus_knot(2, 3, 64, 8, 0.45);
    let view = reference_model(&knot, 30.0, 20.0).unwrap();
    let (centre, radius) = bounding_sphere(&knot).unwrap();
    let close = Mat4::translation(zline::Vec3::new(0.3, 0.2, 1.6)).mul(&reference_model_around(
        centre,
        radius * 0.3,
        30.0,
        20.0,
    ));
    let boxes = shapes::box_field(4).with_face_analysis();
    let boxes_view = reference_model(&boxes, 30.0, 35.0).unwrap();
    let mut broken = knot.clone();
    broken.positions[7] = [f32::NAN, 0.0, 0.0];
    vec![
        ("torus knot", knot.clone(), view),
        ("torus knot, close up", knot, close),
        ("corridor", corridor(), Mat4::IDENTITY),
        ("boxes", boxes, boxes_view),
        ("a NaN vertex", broken, view),
    ]
}

#[test]
fn projected_draws_equal_draw_mesh() {
    let camera = Camera::reference(WIDTH, HEIGHT);
    let (mut clipped_seen, mut non_finite_seen) = (false, false);
    for (name, mesh, model) in scenes() {
        let whole = projected(&mesh, &model, &camera, 1);
        assert_eq!(whole, projected(&mesh, &model, &camera, 3), "{name}");
        clipped_seen |= whole.contains(&ProjectedVertex::NeedsClip);
        non_finite_seen |= whole.contains(&ProjectedVertex::NonFinite);
        for cull in [Cull::None, Cull::Back] {
            let mut cache = Box::new(VertexCache::<4096>::new());
            let mut stats = None;
            let one = rows_of(|r| {
                stats =
                    Some(draw_mesh(r, &mut *cache, &mesh, &model, &camera, cull, shade).unwrap());
            });
            assert!(drawn(&one) > 500, "{name}: {} pixels", drawn(&one));
            if name == "corridor" {
                assert!(
                    stats.is_some_and(|s| s.clipped >= 8 && s.queued == 16),
                    "{stats:?}"
                );
            }
            let all_faces: Vec<u32> = (0..mesh.face_count() as u32).collect();
            let half = &whole[..whole.len() / 2];
            for (projection, faces) in [
                (&whole[..], None),
                (&whole[..], Some(&all_faces[..])),
                // The rest transformed as draw_mesh does.
                (half, None),
                (&[][..], None),
            ] {
                let rows = projected_rows((&mesh, &model, &camera, cull), projection, faces);
                assert_eq!(
                    rows,
                    one,
                    "{name}, {cull:?}, {} projected, faces {:?}",
                    projection.len(),
                    faces.map(<[u32]>::len)
                );
            }
        }
    }
    assert!(clipped_seen, "no scene has a vertex to clip");
    assert!(non_finite_seen, "no scene has a non-finite vertex");
}

#[test]
fn projected_draws_equal_draw_mesh_on_the_integer_front_end() {
    let camera = Camera::reference(WIDTH, HEIGHT);
    let knot = shapes::torus_knot(2, 3, 64, 8, 0.45);
    let quantized = QuantizedHostMesh::new(&knot).unwrap();
    let mesh = quantized.mesh().unwrap();
    assert!(mesh.quantized().is_some());
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let whole = projected(&mesh, &model, &camera, 2);
    for cull in [Cull::None, Cull::Back] {
        let view = (&mesh, &model, &camera, cull);
        let one = mesh_rows(view);
        assert!(drawn(&one) > 500);
        let rows = projected_rows(view, &whole, None);
        assert_eq!(rows, one, "{cull:?}");
    }
}

#[test]
fn a_face_list_draws_those_faces_only() {
    let camera = Camera::reference(WIDTH, HEIGHT);
    let mesh = shapes::torus_knot(2, 3, 64, 8, 0.45);
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let whole = projected(&mesh, &model, &camera, 1);
    let view = (&mesh, &model, &camera, Cull::None);
    let none = projected_rows(view, &whole, Some(&[]));
    assert_eq!(drawn(&none), 0);
    // Every colour drawn is that of a listed face (even faces here).
    let even: Vec<u32> = (0..mesh.face_count() as u32).step_by(2).collect();
    let rows = projected_rows(view, &whole, Some(&even));
    assert!(drawn(&rows) > 500);
    assert!(
        rows.iter()
            .flat_map(|r| &r.1)
            .all(|&c| c == 0 || (c - 1) % 2 == 0)
    );
}

#[test]
fn bad_projections_and_face_lists_are_errors() {
    let camera = Camera::reference(WIDTH, HEIGHT);
    let mesh = shapes::torus_knot(2, 3, 16, 4, 0.45);
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let whole = projected(&mesh, &model, &camera, 1);
    let mut cache = Box::new(VertexCache::<4096>::new());
    let mut renderer = host_renderer::<u32, Depth16>(&caps(), WIDTH, HEIGHT, 0).unwrap();
    let mut draw = |projection: &[ProjectedVertex], faces: Option<&[u32]>| {
        renderer.clear();
        draw_mesh_projected(
            &mut renderer,
            &mut *cache,
            projection,
            faces,
            &mesh,
            &model,
            &camera,
            Cull::None,
            shade,
        )
        .map(|_| ())
    };
    let error = |face, error| Err(DrawError { face, error });
    let mut longer = whole.clone();
    longer.push(ProjectedVertex::NeedsClip);
    assert_eq!(draw(&longer, None), error(None, Error::MeshIndexOutOfRange));
    assert_eq!(
        draw(&whole, Some(&[3, 2])),
        error(None, Error::FacesOutOfOrder)
    );
    assert_eq!(
        draw(&whole, Some(&[2, 2])),
        error(None, Error::FacesOutOfOrder)
    );
    let beyond = mesh.face_count() as u32;
    assert_eq!(
        draw(&whole, Some(&[0, beyond])),
        error(Some(beyond), Error::MeshIndexOutOfRange)
    );
    assert_eq!(draw(&whole, Some(&[0, 1])), Ok(()));
    // Projecting past the mesh's last vertex.
    let mut out = vec![ProjectedVertex::NonFinite; 2];
    let last = mesh.vertex_count() - 1;
    assert_eq!(
        project_vertices(&mesh, &model, &camera, last, &mut out),
        Err(Error::MeshIndexOutOfRange)
    );
    // A cache smaller than the mesh.
    let mut small = VertexCache::<4>::new();
    assert_eq!(
        draw_mesh_projected(
            &mut renderer,
            &mut small,
            &whole,
            None,
            &mesh,
            &model,
            &camera,
            Cull::None,
            shade,
        )
        .map(|_| ()),
        error(None, Error::VertexCacheTooSmall)
    );
}

/// The banded renderer's rows of one `render_mesh` frame, band after band.
fn banded_rows<M: Mesh + Sync>(
    renderer: &mut BandedRenderer<u32, Depth16>,
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
) -> Result<Rows, String> {
    banded_rows_shaded(renderer, mesh, (model, camera, cull), shade)
}

/// [`banded_rows`] with the faces coloured by `shade`.
fn banded_rows_shaded<M: Mesh + Sync>(
    renderer: &mut BandedRenderer<u32, Depth16>,
    mesh: &M,
    (model, camera, cull): (&Mat4, &Camera, Cull),
    shade: impl Fn(&FaceInfo) -> u32 + Sync,
) -> Result<Rows, String> {
    let mut bands: Vec<Rows> = vec![Rows::new(); renderer.bands().count()];
    let mut sinks: Vec<_> = bands
        .iter_mut()
        .map(|rows| {
            FnSink(move |y: u16, c: &[u32], z: &[u16]| {
                rows.push((y, c.to_vec(), z.to_vec()));
                Ok::<(), ()>(())
            })
        })
        .collect();
    renderer
        .render_mesh(mesh, model, camera, cull, &mut sinks, shade)
        .map_err(|e| format!("{e:?}"))?;
    drop(sinks);
    Ok(bands.into_iter().flatten().collect())
}

#[test]
fn render_mesh_equals_one_renderer() {
    let camera = Camera::reference(WIDTH, HEIGHT);
    for (name, mesh, model) in scenes() {
        for cull in [Cull::None, Cull::Back] {
            let one = mesh_rows((&mesh, &model, &camera, cull));
            for count in 1..=4 {
                let mut renderer =
                    BandedRenderer::<u32, Depth16>::new(&caps(), WIDTH, HEIGHT, 0, count).unwrap();
                // The cuts move after each frame.
                for frame in 0..3 {
                    let cuts: Vec<_> = renderer.bands().collect();
                    let rows = banded_rows(&mut renderer, &mesh, &model, &camera, cull).unwrap();
                    assert_eq!(rows, one, "{name}, {cull:?}, bands {cuts:?}, frame {frame}");
                }
            }
        }
    }
}

#[test]
fn render_mesh_on_a_large_mesh_uses_every_thread_and_equals_one_renderer() {
    // Over 4,096 vertices and faces a thread: the shared steps run on two
    // threads.
    let mesh = shapes::torus_knot(2, 3, 1024, 12, 0.45);
    assert!(mesh.vertex_count() >= 8192 && mesh.face_count() >= 8192);
    let (width, height) = (160u16, 120u16);
    let caps = mesh.capacities(width);
    let model = reference_model(&mesh, 30.0, 20.0).unwrap();
    let camera = Camera::reference(width, height);
    let one = large_mesh_rows(&caps, (width, height), (&mesh, &model, &camera));
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&caps, width, height, 0, 2).unwrap();
    for frame in 0..2 {
        let rows = banded_rows(&mut renderer, &mesh, &model, &camera, Cull::None).unwrap();
        assert_eq!(rows, one, "frame {frame}");
    }
}

#[test]
fn one_banded_renderer_draws_large_and_small_meshes_in_turn() {
    // The face lists keep their room from frame to frame: a small mesh
    // after a large one must not draw the large one's faces left in it,
    // nor the large one after the small one miss any.
    let large = shapes::torus_knot(2, 3, 1024, 12, 0.45);
    let small = shapes::torus_knot(2, 3, 64, 8, 0.45);
    let (width, height) = (160u16, 120u16);
    let caps = large.capacities(width);
    let camera = Camera::reference(width, height);
    let one = |mesh: &HostMesh, model: &Mat4| {
        large_mesh_rows(&caps, (width, height), (mesh, model, &camera))
    };
    let large_view = reference_model(&large, 30.0, 20.0).unwrap();
    let small_view = reference_model(&small, 30.0, 20.0)
        .unwrap()
        .mul(&Mat4::translation(zline::Vec3::new(0.4, 0.0, 0.0)));
    let (large_rows, small_rows) = (one(&large, &large_view), one(&small, &small_view));
    assert_ne!(large_rows, small_rows);
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&caps, width, height, 0, 2).unwrap();
    for (frame, (mesh, view, expected)) in [
        (&large, &large_view, &large_rows),
        (&large, &large_view, &large_rows),
        (&small, &small_view, &small_rows),
        (&large, &large_view, &large_rows),
        (&small, &small_view, &small_rows),
    ]
    .into_iter()
    .enumerate()
    {
        let rows = banded_rows(&mut renderer, mesh, view, &camera, Cull::None).unwrap();
        assert_eq!(&rows, expected, "frame {frame}");
    }
}

#[test]
fn render_mesh_refuses_a_mesh_beyond_its_cache() {
    let mesh = HostMesh {
        positions: vec![[0.0; 3]; MESH_VERTICES + 1],
        ..HostMesh::default()
    };
    let camera = Camera::reference(WIDTH, HEIGHT);
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&caps(), WIDTH, HEIGHT, 0, 2).unwrap();
    let result = banded_rows(&mut renderer, &mesh, &Mat4::IDENTITY, &camera, Cull::None);
    assert_eq!(
        result,
        Err(format!(
            "{:?}",
            zline::RenderError::<()>::Table(Error::VertexCacheTooSmall)
        ))
    );
}

/// A mesh whose `position` panics for one vertex.
struct PanicsAt {
    mesh: HostMesh,
    vertex: usize,
}

impl Mesh for PanicsAt {
    fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }
    fn position(&self, index: usize) -> [f32; 3] {
        assert_ne!(index, self.vertex, "the mesh's own panic");
        self.mesh.position(index)
    }
    fn face_count(&self) -> usize {
        self.mesh.face_count()
    }
    fn face(&self, index: usize) -> &[u16] {
        self.mesh.face(index)
    }
}

/// A panic on any thread of a banded frame, in any step, reaches the
/// caller: no thread is left waiting for the others. (The threads meet
/// between the steps; a thread that panics opens the meeting.) The
/// renderer draws the next frame as before.
#[test]
fn a_panic_in_a_banded_frame_reaches_the_caller() {
    // A thread left waiting would hang the test: fail it instead.
    let done = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let watched = done.clone();
    std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_secs(60));
        if !watched.load(std::sync::atomic::Ordering::Acquire) {
            eprintln!("a banded frame with a panic did not return within 60 s");
            std::process::exit(1);
        }
    });
    let knot = shapes::torus_knot(2, 3, 1024, 12, 0.45);
    let (width, height) = (160u16, 120u16);
    let caps = knot.capacities(width);
    let model = reference_model(&knot, 30.0, 20.0).unwrap();
    let camera = Camera::reference(width, height);
    let one = large_mesh_rows(&caps, (width, height), (&knot, &model, &camera));
    let last = knot.vertex_count() - 1;
    let mut renderer = BandedRenderer::<u32, Depth16>::new(&caps, width, height, 0, 2).unwrap();
    for threads in [false, true] {
        renderer.set_one_thread_below(if threads {
            std::time::Duration::ZERO
        } else {
            std::time::Duration::MAX
        });
        // In the projection (the first chunk, which the calling thread
        // takes, and the last), then in the shading of the last face (on
        // the second band's thread, or the calling thread's last band).
        for vertex in [0, last] {
            let panics = PanicsAt {
                mesh: knot.clone(),
                vertex,
            };
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                banded_rows(&mut renderer, &panics, &model, &camera, Cull::None)
            }));
            assert!(result.is_err(), "threads {threads}, vertex {vertex}");
        }
        let faces = knot.face_count() as u32;
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let view = (&model, &camera, Cull::None);
            banded_rows_shaded(&mut renderer, &knot, view, |f| {
                assert_ne!(f.face + 1, faces, "the shading's own panic");
                shade(f)
            })
        }));
        assert!(result.is_err(), "threads {threads}: the shading's panic");
        let rows = banded_rows(&mut renderer, &knot, &model, &camera, Cull::None).unwrap();
        assert_eq!(rows, one, "threads {threads}: the frame after");
    }
    done.store(true, std::sync::atomic::Ordering::Release);
}
