//! The properties the fuzzers check, as plain functions over raw bytes, so
//! that the `cargo fuzz` targets in `fuzz/` and the regression tests
//! (`tests/fuzz_regressions.rs`, which replays every saved finding) run
//! the very same code. Each function decodes its input deterministically,
//! runs zline on it and panics when a property does not hold.
//!
//! * [`obj_reader`]: the OBJ reader on any bytes: its three ways in agree,
//!   errors carry a real line, and what it accepts is a valid mesh.
//! * [`core_scene`]: the scanline core on arbitrary screen-space polygons
//!   (coordinates anywhere in the guard band, depths anywhere in range)
//!   against the exact oracle ([`crate::methods::exact::check_frame`]): coverage
//!   exact, depth within 1 LSB, or a documented `Err`.
//! * [`pipeline`]: OBJ bytes and a camera through [`draw_mesh`] to rows:
//!   every face accounted for exactly once, only capacity errors, every
//!   row delivered once, in order; then every other method on the same
//!   scene ([`crate::methods::MethodRenderer`]): the z-buffer and the bands
//!   draw the scanline's frame exactly, the interval and the painter's
//!   methods and the reference finish with valid face ids (a wrong
//!   picture from the painter is no finding; a panic or an overflow in any
//!   method is); and the same scene from vertices projected beforehand
//!   ([`draw_mesh_projected`]) and in two bands on two threads
//!   ([`crate::host::BandedRenderer::render_mesh`]) gives the same rows.

use std::boxed::Box;
use std::format;
use std::string::ToString;
use std::vec;
use std::vec::Vec;

use crate::error::{Error, RenderError};
use crate::front::geometry::{Mat4, Vec3};
use crate::front::mesh::{Mesh, StaticMesh};
use crate::front::obj::{ObjMesh, ObjReader, Statement, count};
use crate::front::scene::{
    Camera, Cull, DrawError, ProjectedVertex, VertexCache, draw_mesh, draw_mesh_projected,
    project_vertices, reference_model,
};
use crate::front::shade::Shading;
use crate::host::{BandedRenderer, host_renderer};
use crate::host::{HostMesh, QuantizedHostMesh};
use crate::methods::exact::{Offered, check_frame_shared};
use crate::raster::depth::{Depth16, Depth24, DepthFormat};
use crate::raster::fixed::{DEPTH_MAX, GUARD_BAND, SUBPIXEL_STEPS};
use crate::raster::vertex::ScreenVertex;
use crate::raster::{Admission, Capacities};
use crate::sink::FnSink;

/// Reads fixed-size values from the front of the input; zeros once it
/// runs out, so every input decodes to something.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }

    fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// The OBJ reader on any bytes.
pub fn obj_reader(data: &[u8]) {
    type Small = ObjMesh<64, 256, 64, 8>;
    let lines = data.split(|&b| b == b'\n' || b == b'\r').count() as u32;
    let counted = count(data);
    let parsed = Small::parse(data);
    let host = HostMesh::from_obj(data);
    if let Err(e) = &counted {
        assert!(
            e.line >= 1 && e.line <= lines,
            "error line {} of {lines}",
            e.line
        );
        assert!(!e.to_string().is_empty());
    }
    match (&counted, &host) {
        (Ok(c), Ok(h)) => {
            assert_eq!(
                (c.vertices, c.faces, c.corners),
                (h.positions.len(), h.face_starts.len(), h.corners.len())
            );
            let mesh = StaticMesh::new(&h.positions, &h.corners, &h.face_starts);
            assert!(mesh.is_ok(), "accepted mesh is invalid: {mesh:?}");
            assert!(h.positions.iter().flatten().all(|x| x.is_finite()));
        }
        (c, h) => assert_eq!(
            c.as_ref().err(),
            h.as_ref().err(),
            "count and the host mesh disagree"
        ),
    }
    match (&parsed, &counted) {
        (Ok(mesh), Ok(c)) => {
            assert_eq!(
                (mesh.vertex_count(), mesh.face_count(), mesh.corners().len()),
                (c.vertices, c.faces, c.corners)
            );
            assert_eq!(
                (mesh.texcoord_count(), mesh.normal_count()),
                (c.texcoords, c.normals)
            );
        }
        (Ok(_), Err(e)) => panic!("count failed ({e}) where parse succeeded"),
        (Err(e), Ok(c)) => {
            let fits = c.vertices <= 64 && c.corners <= 256 && c.faces <= 64 && c.max_corners <= 8;
            assert!(!fits, "parse failed ({e}) on a mesh that fits: {c:?}");
        }
        (Err(p), Err(c)) => assert!(p.line <= c.line),
    }
    // The streaming reader stops at the first error, and every face it
    // yields names vertices that exist.
    let mut vertices = 0usize;
    for statement in ObjReader::<8>::new(data) {
        match statement {
            Ok(Statement::Vertex(_)) => vertices += 1,
            Ok(Statement::Face(corners)) => assert!(corners.len() >= 3),
            Ok(Statement::Other(_)) => {}
            Err(_) => break,
        }
    }
    if let Ok(c) = counted {
        assert_eq!(vertices.min(c.vertices), vertices);
    }
}

/// A sub-pixel coordinate for a frame `size` pixels wide: near the frame,
/// anywhere in the guard band, at its very edge, or on pixel boundaries
/// and sample points.
fn coordinate(bytes: &mut Bytes<'_>, size: u16) -> i32 {
    let s = SUBPIXEL_STEPS;
    match bytes.u8() % 4 {
        0 => i32::from(bytes.u16()) % ((i32::from(size) + 16) * s) - 8 * s,
        1 => (bytes.u32() as i32) % GUARD_BAND,
        2 => {
            let inset = i32::from(bytes.u8());
            if bytes.u8().is_multiple_of(2) {
                GUARD_BAND - 1 - inset
            } else {
                1 - GUARD_BAND + inset
            }
        }
        _ => {
            let pixel = i32::from(bytes.u8()) % (i32::from(size) + 2) - 1;
            pixel * s + [0, s / 2, 1, s - 1][usize::from(bytes.u8() % 4)]
        }
    }
}

/// A depth: anywhere, or near either end of the range.
fn depth(bytes: &mut Bytes<'_>) -> u32 {
    match bytes.u8() % 4 {
        0 => bytes.u32() % (DEPTH_MAX + 1),
        1 => u32::from(bytes.u8()),
        2 => DEPTH_MAX - u32::from(bytes.u8()),
        _ => u32::from(bytes.u16()) << 8,
    }
}

/// Widest frame [`core_scene`] draws.
const CORE_WIDTH: usize = 48;
/// Most polygons [`core_scene`] draws.
const CORE_POLYGONS: usize = 10;

/// The scanline core on arbitrary screen-space polygons, against the exact
/// oracle.
pub fn core_scene(data: &[u8]) {
    let mut bytes = Bytes(data);
    let width = 1 + u16::from(bytes.u8()) % CORE_WIDTH as u16;
    let height = 1 + u16::from(bytes.u8()) % 40;
    // Bit 0: the depth format; bit k (1 to 7): polygon k takes the plane
    // of polygon k - 1's first three corners (a shared plane).
    let flags = bytes.u8();
    let z24 = flags % 2 == 0;
    let mut polygons = Vec::new();
    while !bytes.is_empty() && polygons.len() < CORE_POLYGONS {
        let corners = 3 + usize::from(bytes.u8() % 6);
        let poly: Vec<ScreenVertex> = (0..corners)
            .map(|_| {
                let x = coordinate(&mut bytes, width);
                let y = coordinate(&mut bytes, height);
                ScreenVertex::new(x, y, depth(&mut bytes)).expect("inside the guard band")
            })
            .collect();
        polygons.push(poly);
    }
    let shares = |k: usize| (1..8).contains(&k) && flags & (1 << k) != 0;
    if z24 {
        core_check::<Depth24>(&polygons, shares, width, height);
    } else {
        core_check::<Depth16>(&polygons, shares, width, height);
    }
}

fn core_check<D: DepthFormat>(
    polygons: &[Vec<ScreenVertex>],
    shares: impl Fn(usize) -> bool,
    width: u16,
    height: u16,
) where
    D::Value: Into<u64>,
{
    // Room for every polygon and shared plane: no capacity error is
    // possible.
    let caps = Capacities {
        width: CORE_WIDTH,
        vertices: 128,
        polygons: 12,
        corners: 128,
        active_polygons: 12,
        pooled_edges: 96,
    };
    let mut renderer = host_renderer::<u32, D>(&caps, width, height, 0).expect("frame size");
    let offered: Vec<Offered> = polygons
        .iter()
        .enumerate()
        .map(|(k, poly)| {
            let admission = renderer
                .push_polygon_vertices(poly, k as u32 + 1)
                .expect("the tables have room");
            let queued = matches!(admission, Admission::Queued(_));
            let mut plane = None;
            if queued && shares(k) {
                let corners = [0, 1, 2].map(|c| polygons[k - 1][c]);
                let ids = corners.map(|v| renderer.push_vertex(v).expect("room"));
                if renderer.share_plane(ids).expect("just queued") {
                    plane = Some(corners);
                }
            }
            Offered {
                corners: poly.clone(),
                plane,
                queued,
            }
        })
        .collect();
    let (w, h) = (usize::from(width), usize::from(height));
    let (mut colors, mut depths) = (vec![0u32; w * h], vec![0u64; w * h]);
    let mut next_row = 0u16;
    renderer
        .render(&mut FnSink(|y: u16, c: &[u32], z: &[D::Value]| {
            assert_eq!(y, next_row, "rows in order, once each");
            next_row += 1;
            let at = usize::from(y) * w;
            colors[at..at + w].copy_from_slice(c);
            for (out, &d) in depths[at..at + w].iter_mut().zip(z) {
                *out = d.into();
            }
            Ok::<(), ()>(())
        }))
        .expect("render");
    assert_eq!(next_row, height);
    if let Err(e) = check_frame_shared::<D>(&offered, w, h, &colors, &depths) {
        panic!("{}: {e}\npolygons: {offered:?}", D::NAME);
    }
}

/// Frame size limit of [`pipeline`].
const PIPELINE_WIDTH: usize = 64;

/// A finite `f32` from the input, or `fallback`.
fn finite(bytes: &mut Bytes<'_>, fallback: f32) -> f32 {
    let v = f32::from_bits(bytes.u32());
    if v.is_finite() { v } else { fallback }
}

/// OBJ bytes and a camera through the whole pipeline to rows.
///
/// The first 32 bytes choose the view; the rest is the OBJ file.
pub fn pipeline(data: &[u8]) {
    let (head, obj) = data.split_at(data.len().min(32));
    let mut bytes = Bytes(head);
    let width = 1 + u16::from(bytes.u8()) % PIPELINE_WIDTH as u16;
    let height = 1 + u16::from(bytes.u8()) % 48;
    let flags = bytes.u8();
    let (z24, cull, reference_view) = (flags & 1 != 0, flags & 2 != 0, flags & 4 == 0);
    let cull = if cull { Cull::Back } else { Cull::None };
    let yaw = f32::from(bytes.u16()) / 64.0;
    let pitch = f32::from(bytes.u16()) / 64.0;
    let fov = 5.0 + f32::from(bytes.u8()) * (170.0 / 255.0);
    let near = 10f32.powf(f32::from(bytes.u8() % 8) - 4.0);
    let far = near * 10f32.powf(1.0 + f32::from(bytes.u8() % 6));
    let eye = Vec3::new(
        finite(&mut bytes, 0.0),
        finite(&mut bytes, 0.0),
        finite(&mut bytes, 3.0),
    );
    let Ok(mesh) = HostMesh::from_obj(obj) else {
        return; // The reader's own target checks its errors.
    };
    let (model, camera) = if reference_view {
        let Ok(model) = reference_model(&mesh, yaw, pitch) else {
            return; // Error::MeshExtent: documented and tested.
        };
        (
            model,
            Camera::perspective(
                Mat4::translation(Vec3::new(0.0, 0.0, -3.0)),
                fov,
                width,
                height,
                near,
                far,
            ),
        )
    } else {
        let view = Mat4::look_at(eye, Vec3::default(), Vec3::new(0.0, 1.0, 0.0));
        (
            Mat4::IDENTITY,
            Camera::perspective(view, fov, width, height, near, far),
        )
    };
    // Flags 16..: the band height of the bands method.
    let band_rows = 1 + u16::from(flags >> 4);
    let reference_camera = reference_view.then_some(crate::methods::ReferenceCamera {
        eye_distance: 3.0,
        fov_y_deg: f64::from(fov),
        near: f64::from(near),
        far: f64::from(far),
    });
    let view = crate::methods::ReferenceView {
        width: usize::from(width),
        height: usize::from(height),
        yaw_deg: f64::from(yaw),
        pitch_deg: f64::from(pitch),
        cull_back: cull == Cull::Back,
    };
    let methods = OtherMethods {
        band_rows,
        reference: reference_camera.map(|c| (c, view)),
    };
    // Flag 8: the same mesh quantized, through the integer front end.
    if flags & 8 != 0 {
        let Ok(quantized) = QuantizedHostMesh::new(&mesh) else {
            return; // Error::MeshExtent, as for the f32 mesh.
        };
        let quantized = quantized.mesh().expect("a quantized host mesh is valid");
        if z24 {
            pipeline_check::<Depth24, _>(&quantized, &model, &camera, cull, &methods);
        } else {
            pipeline_check::<Depth16, _>(&quantized, &model, &camera, cull, &methods);
        }
    } else if z24 {
        pipeline_check::<Depth24, _>(&mesh, &model, &camera, cull, &methods);
    } else {
        pipeline_check::<Depth16, _>(&mesh, &model, &camera, cull, &methods);
    }
}

/// What [`pipeline`] asks of the methods beyond the scanline core.
struct OtherMethods {
    /// Rows of the bands method.
    band_rows: u16,
    /// The reference's camera and view, when the view is the reference
    /// view's (the reference knows no other).
    reference: Option<(
        crate::methods::ReferenceCamera,
        crate::methods::ReferenceView,
    )>,
}

/// Every method on the scene: the z-buffer and the bands give the
/// scanline's frame exactly; the interval and painter's methods and the
/// reference give valid face ids.
fn other_methods_check<D: DepthFormat, M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    other: &OtherMethods,
) where
    D::Value: Into<u32>,
{
    use crate::methods::{BACKGROUND, Method, MethodRenderer};
    let mut renderer = MethodRenderer::<D>::new(camera.width, camera.height).expect("frame size");
    if let Some((c, _)) = other.reference {
        renderer.set_reference_camera(c);
    }
    let shading = Shading::lambert();
    let (view, reference) = match other.reference {
        Some((c, v)) => (v, Some(c)),
        None => (
            crate::methods::ReferenceView {
                width: usize::from(camera.width),
                height: usize::from(camera.height),
                yaw_deg: 0.0,
                pitch_deg: 0.0,
                cull_back: false,
            },
            None,
        ),
    };
    let mut frame = |method: Method| {
        renderer
            .render(method, mesh, model, camera, cull, &shading, &view)
            .unwrap_or_else(|e| panic!("{}: {e}", method.name()))
            .faces
    };
    let scanline = frame(Method::Scanline);
    for method in [Method::ZBuffer, Method::Bands(other.band_rows)] {
        assert!(
            frame(method) == scanline,
            "{} differs from the scanline",
            method.name()
        );
    }
    let faces = mesh.face_count() as u32;
    for method in [Method::Interval, Method::Painter] {
        let ids = frame(method);
        assert!(
            ids.iter().all(|&id| id == BACKGROUND || id < faces),
            "{} names no face",
            method.name()
        );
    }
    if reference.is_some() {
        let ids = frame(Method::Reference);
        assert!(ids.iter().all(|&id| id == BACKGROUND || id < faces));
    }
}

/// A row as (row, colours, depths).
type Rows = Vec<(u16, Vec<u32>, Vec<u32>)>;

fn row_of<V: Copy + Into<u32>>(y: u16, colors: &[u32], depths: &[V]) -> (u16, Vec<u32>, Vec<u32>) {
    (
        y,
        colors.to_vec(),
        depths.iter().map(|&z| z.into()).collect(),
    )
}

/// The scene `rows` came from, drawn from vertices projected beforehand
/// (in two runs) and by the banded renderer in two bands on two threads:
/// the same rows, and no error where `draw_mesh` had none.
fn projected_check<D: DepthFormat, M: Mesh + Sync>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    rows: &Rows,
) where
    D::Value: Into<u32> + Send,
{
    let count = mesh.vertex_count();
    let mut projected = vec![ProjectedVertex::NonFinite; count];
    let (low, high) = projected.split_at_mut(count / 2);
    project_vertices(mesh, model, camera, 0, low).expect("vertices of the mesh");
    project_vertices(mesh, model, camera, count / 2, high).expect("vertices of the mesh");
    let mut renderer =
        host_renderer::<u32, D>(&PIPELINE_CAPACITIES, camera.width, camera.height, 0)
            .expect("frame size");
    let mut cache: Box<VertexCache<4096>> = Box::default();
    draw_mesh_projected(
        &mut renderer,
        &mut *cache,
        &projected,
        None,
        mesh,
        model,
        camera,
        cull,
        |f| f.face + 1,
    )
    .expect("draw_mesh drew it");
    let mut again = Rows::new();
    renderer
        .render(&mut FnSink(
            |y: u16, colors: &[u32], depths: &[D::Value]| {
                again.push(row_of(y, colors, depths));
                Ok::<(), ()>(())
            },
        ))
        .expect("draw_mesh's frame was rendered");
    assert!(again == *rows, "draw_mesh_projected's rows differ");
    if camera.height < 2 {
        return;
    }
    let mut banded =
        BandedRenderer::<u32, D>::new(&PIPELINE_CAPACITIES, camera.width, camera.height, 0, 2)
            .expect("bands");
    // Two threads even for the first (and only) frame: their shared steps
    // and meetings are what is checked.
    banded.set_one_thread_below(std::time::Duration::ZERO);
    let mut bands: Vec<Rows> = vec![Rows::new(); 2];
    let mut sinks: Vec<_> = bands
        .iter_mut()
        .map(|band| {
            FnSink(move |y: u16, colors: &[u32], depths: &[D::Value]| {
                band.push(row_of(y, colors, depths));
                Ok::<(), ()>(())
            })
        })
        .collect();
    banded
        .render_mesh(mesh, model, camera, cull, &mut sinks, |f| f.face + 1)
        .expect("one renderer drew it");
    drop(sinks);
    let banded_rows: Rows = bands.into_iter().flatten().collect();
    assert!(banded_rows == *rows, "the banded renderer's rows differ");
}

/// Capacities of [`pipeline`]'s renderer.
const PIPELINE_CAPACITIES: Capacities = Capacities {
    width: PIPELINE_WIDTH,
    vertices: 4096,
    polygons: 1024,
    corners: 4096,
    active_polygons: 256,
    pooled_edges: 256,
};

fn pipeline_check<D: DepthFormat, M: Mesh + Sync>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    other: &OtherMethods,
) where
    D::Value: Into<u32> + Send,
{
    let mut renderer =
        host_renderer::<u32, D>(&PIPELINE_CAPACITIES, camera.width, camera.height, 0)
            .expect("frame size");
    let mut cache: Box<VertexCache<4096>> = Box::default();
    if mesh.vertex_count() > 4096 {
        return;
    }
    let shading = Shading::lambert();
    let stats = match draw_mesh(&mut renderer, &mut *cache, mesh, model, camera, cull, |f| {
        // Lambert too (the integer path for a quantized mesh): any panic
        // or overflow in it is a finding.
        core::hint::black_box(shading.color(f));
        f.face + 1
    }) {
        Ok(stats) => stats,
        Err(DrawError { error, face }) => {
            assert!(
                matches!(
                    error,
                    Error::VertexTableFull
                        | Error::PolygonTableFull
                        | Error::EdgeTableFull
                        | Error::ClipRange
                ),
                "face {face:?}: {error}"
            );
            return;
        }
    };
    // Every face (every triangle of a split face, each of a convex quad's
    // two triangles) ends exactly one way.
    let parts: u32 = (0..mesh.face_count())
        .map(|f| {
            let n = mesh.face(f).len() as u32;
            if n > 3 && !mesh.face_is_planar(f) {
                n - 2
            } else {
                1
            }
        })
        .sum();
    let outcomes = stats.queued
        + stats.back_faces
        + stats.outside
        + stats.off_screen
        + stats.degenerate
        + stats.non_finite;
    assert_eq!(outcomes, parts + stats.convex_quads, "{stats:?}");
    assert_eq!(stats.faces as usize, mesh.face_count());
    let mut next_row = 0u16;
    let faces = mesh.face_count() as u32;
    let mut rows = Rows::new();
    let result = renderer.render(&mut FnSink(
        |y: u16, colors: &[u32], depths: &[D::Value]| {
            assert_eq!(y, next_row, "rows in order, once each");
            next_row += 1;
            assert_eq!(colors.len(), usize::from(camera.width));
            assert!(colors.iter().all(|&c| c <= faces), "a colour names no face");
            rows.push(row_of(y, colors, depths));
            Ok::<(), ()>(())
        },
    ));
    match result {
        Ok(frame) => {
            assert_eq!(next_row, camera.height);
            assert_eq!(frame.polygons, stats.queued);
            other_methods_check::<D, M>(mesh, model, camera, cull, other);
            projected_check::<D, M>(mesh, model, camera, cull, &rows);
        }
        Err(RenderError::Table(e)) => assert!(
            matches!(
                e,
                Error::ActivePolygonsFull { .. } | Error::ActiveEdgesFull { .. }
            ),
            "{e}"
        ),
        Err(RenderError::Sink(())) => unreachable!("the sink never fails"),
    }
    let _ = format!("{stats:?}");
}
