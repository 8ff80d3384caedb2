//! Adversarial scenes: where hidden-surface methods break. Each case is a
//! small world-space mesh with a camera, rendered by every [`Method`] and
//! compared with the float64 reference, with the outcome each method is
//! expected to have. `tests/catalogue.rs` holds every method to its
//! expectation; `examples/catalogue.rs` prints the method × case table and
//! renders the gallery.
//!
//! Every mesh carries six unused *anchor* vertices at distance 1 on the
//! axes, so the reference normalisation (bounding-box centre, largest
//! distance) is the identity: the coordinates below are the view's, before
//! the eye moves back by the camera's `eye_distance`. +X is right, +Y up,
//! and the eye looks down -Z.

use std::format;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

use super::accuracy::{Comparison, compare};
use super::reference::{ReferenceCamera, ReferenceFrame, ReferenceView};
use super::run::{Method, MethodFrame, MethodRenderer};
use zline::Shading;
use zline::host::HostMesh;
use zline::{Cull, reference_model};
use zline::{Depth16, Depth24, DepthFormat};

/// What a method is expected to do with a case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expect {
    /// No hard mismatch against the reference (edge and tie pixels are
    /// excused, as in the accuracy run).
    Correct,
    /// Hard mismatches: the method cannot draw this scene.
    Wrong,
    /// A clear error, and no frame.
    Error,
}

/// What a method did with a case.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// A frame; its comparison with the reference.
    Frame(Comparison),
    /// An error, as the method reported it.
    Error(String),
}

impl Outcome {
    /// The outcome as an expectation, to check against one.
    pub fn kind(&self) -> Expect {
        match self {
            Self::Frame(c) if c.hard == 0 => Expect::Correct,
            Self::Frame(_) => Expect::Wrong,
            Self::Error(_) => Expect::Error,
        }
    }

    /// A table cell: `correct`, `correct (N excused)`, `wrong: N px`, or
    /// `error: ...`.
    pub fn cell(&self) -> String {
        match self {
            Self::Frame(c) if c.hard == 0 && c.mismatches == 0 => "correct".into(),
            Self::Frame(c) if c.hard == 0 => format!("correct ({} excused)", c.mismatches),
            Self::Frame(c) => format!("**wrong: {} px**", c.hard),
            Self::Error(e) => format!("error: {e}"),
        }
    }
}

/// One adversarial scene.
pub struct Case {
    /// Short name (file names of the gallery).
    pub name: &'static str,
    /// What it tests.
    pub what: &'static str,
    /// The mesh, or the loader's error (the NaN case).
    pub mesh: Result<HostMesh, String>,
    /// View rotation, degrees.
    pub yaw_pitch: (f32, f32),
    /// The camera.
    pub camera: ReferenceCamera,
    /// Which methods are expected to fail it (hard mismatches).
    pub breaks: &'static [Method],
    /// Whether every method is expected to refuse it with an error.
    pub refused: bool,
}

impl Case {
    /// What `method` is expected to do.
    pub fn expect(&self, method: Method) -> Expect {
        if self.refused {
            Expect::Error
        } else if self.breaks.contains(&method) {
            Expect::Wrong
        } else {
            Expect::Correct
        }
    }
}

/// Builds meshes face by face, with the six anchors.
struct Builder(HostMesh);

impl Builder {
    fn new() -> Self {
        let mut mesh = HostMesh::default();
        for a in 0..3 {
            for s in [-1.0f32, 1.0] {
                let mut p = [0.0; 3];
                p[a] = s;
                mesh.positions.push(p);
            }
        }
        Self(mesh)
    }

    /// A face with these corners (counter-clockwise seen from the front).
    fn face(mut self, corners: &[[f32; 3]]) -> Self {
        self.0.face_starts.push(self.0.corners.len() as u32);
        for &p in corners {
            self.0.corners.push(self.0.positions.len() as u16);
            self.0.positions.push(p);
        }
        self
    }

    fn done(self) -> Result<HostMesh, String> {
        Ok(self.0.with_face_analysis())
    }
}

/// `n` bars in a pinwheel: bar `k` runs along the direction at angle
/// `2πk/n`, offset from the centre, and climbs in depth along its length,
/// so each bar lies over the next where they cross, and the last over the
/// first: a cycle no drawing order resolves.
fn pinwheel(n: usize) -> Result<HostMesh, String> {
    let mut b = Builder::new();
    for k in 0..n {
        let a = core::f32::consts::TAU * k as f32 / n as f32;
        let (u, v) = ([a.cos(), a.sin()], [-a.sin(), a.cos()]);
        let (offset, half, width, rise) = (0.22, 0.85, 0.14, 0.35);
        let at = |t: f32, s: f32| {
            [
                offset * v[0] + t * u[0] + s * v[0],
                offset * v[1] + t * u[1] + s * v[1],
                rise * t / half,
            ]
        };
        b = b.face(&[
            at(-half, -width),
            at(half, -width),
            at(half, width),
            at(-half, width),
        ]);
    }
    b.done()
}

/// A closed unit sphere (an icosphere of 320 triangles) with the anchors.
fn sphere() -> Result<HostMesh, String> {
    let s = crate::shapes::icosphere(2);
    let mut b = Builder::new();
    for f in 0..s.face_starts.len() {
        let start = s.face_starts[f] as usize;
        let end = s
            .face_starts
            .get(f + 1)
            .map_or(s.corners.len(), |&e| e as usize);
        let corners: Vec<[f32; 3]> = s.corners[start..end]
            .iter()
            .map(|&i| s.positions[usize::from(i)].map(|c| c * 0.98))
            .collect();
        b = b.face(&corners);
    }
    b.done()
}

/// View-space x and y at depth `z` of the screen point `(px, py)` (pixels,
/// y down) for a `width` x `height` frame seen by `camera`.
fn unproject(
    camera: &ReferenceCamera,
    (width, height): (f64, f64),
    (px, py): (f64, f64),
    z: f64,
) -> [f32; 3] {
    let d = camera.eye_distance - z;
    let tan_half = (camera.fov_y_deg / 2.0).to_radians().tan();
    let x = (px / width * 2.0 - 1.0) * d * tan_half * width / height;
    let y = (1.0 - py / height * 2.0) * d * tan_half;
    [x as f32, y as f32, z as f32]
}

/// Frame size of the catalogue.
pub const SIZE: (u16, u16) = (160, 120);

/// The catalogue.
pub fn cases() -> Vec<Case> {
    let standard = ReferenceCamera::STANDARD;
    let size = (f64::from(SIZE.0), f64::from(SIZE.1));
    let quad = |z: f32, r: f32| [[-r, -r, z], [r, -r, z], [r, r, z], [-r, r, z]];
    let painter_breaks: &'static [Method] = &[Method::Painter];
    vec![
        Case {
            name: "cyclic-3",
            what: "three bars, each over the next and the last over the first",
            mesh: pinwheel(3),
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: painter_breaks,
            refused: false,
        },
        Case {
            name: "cyclic-4",
            what: "four bars in a cycle",
            mesh: pinwheel(4),
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: painter_breaks,
            refused: false,
        },
        Case {
            name: "interpenetrating",
            what: "two triangles that pierce each other along a line",
            mesh: Builder::new()
                .face(&[[-0.8, -0.6, -0.4], [0.8, -0.6, 0.4], [0.0, 0.7, 0.0]])
                .face(&[[-0.8, 0.6, 0.4], [0.0, -0.7, 0.0], [0.8, 0.6, -0.4]])
                .done(),
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: painter_breaks,
            refused: false,
        },
        Case {
            name: "coplanar",
            what: "three overlapping faces in one plane: the one added first wins, every frame",
            mesh: Builder::new()
                .face(&[
                    [-0.7, -0.5, 0.0],
                    [0.3, -0.5, 0.0],
                    [0.3, 0.5, 0.0],
                    [-0.7, 0.5, 0.0],
                ])
                .face(&[
                    [-0.3, -0.7, 0.0],
                    [0.7, -0.7, 0.0],
                    [0.7, 0.3, 0.0],
                    [-0.3, 0.3, 0.0],
                ])
                .face(&[[-0.5, -0.2, 0.0], [0.5, -0.2, 0.0], [0.0, 0.8, 0.0]])
                .done(),
            yaw_pitch: (20.0, 10.0),
            camera: standard,
            breaks: &[],
            refused: false,
        },
        Case {
            name: "edge-on",
            what: "a face 0.06 degrees from edge-on (c → 0) in front of a wall",
            mesh: Builder::new()
                .face(&quad(-0.5, 0.7))
                .face(&[
                    [0.0, -0.6, 0.6],
                    [0.001, -0.6, -0.4],
                    [0.001, 0.6, -0.4],
                    [0.0, 0.6, 0.6],
                ])
                .done(),
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: &[],
            refused: false,
        },
        Case {
            name: "slivers",
            what: "a fan of 40 triangles 1.6 long and 0.004 wide over a tilted face",
            mesh: {
                let mut b = Builder::new().face(&[
                    [-0.8, -0.6, -0.3],
                    [0.8, -0.6, 0.3],
                    [0.8, 0.6, 0.3],
                    [-0.8, 0.6, -0.3],
                ]);
                for k in 0..40 {
                    let a = core::f32::consts::PI * k as f32 / 40.0;
                    let (c, s) = (a.cos(), a.sin());
                    let w = 0.002;
                    b = b.face(&[
                        [-0.8 * c - w * s, -0.8 * s + w * c, 0.45],
                        [0.8 * c - w * s, 0.8 * s + w * c, 0.35],
                        [0.8 * c + w * s, 0.8 * s - w * c, 0.35],
                    ]);
                }
                b.done()
            },
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: &[],
            refused: false,
        },
        Case {
            name: "t-junction",
            what: "a square as one face on the left and two on the right, meeting at a T: no crack",
            mesh: Builder::new()
                .face(&[
                    [-0.6, -0.6, 0.0],
                    [0.0, -0.6, 0.0],
                    [0.0, 0.0, 0.0],
                    [0.0, 0.6, 0.0],
                    [-0.6, 0.6, 0.0],
                ])
                .face(&[
                    [0.0, -0.6, 0.0],
                    [0.6, -0.6, 0.0],
                    [0.6, 0.0, 0.0],
                    [0.0, 0.0, 0.0],
                ])
                .face(&[
                    [0.0, 0.0, 0.0],
                    [0.6, 0.0, 0.0],
                    [0.6, 0.6, 0.0],
                    [0.0, 0.6, 0.0],
                ])
                .face(&quad(-0.3, 0.9))
                .done(),
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: &[],
            refused: false,
        },
        Case {
            name: "sub-pixel",
            what: "200 triangles of a third of a pixel and 20 of zero area over a face",
            mesh: {
                let mut b = Builder::new().face(&quad(-0.2, 0.8));
                let px = 2.0 * 3.0 * (22.5f32).to_radians().tan() / f32::from(SIZE.1);
                for k in 0..200 {
                    let (x, y) = ((k % 20) as f32 * 0.07 - 0.7, (k / 20) as f32 * 0.12 - 0.55);
                    let r = px / 3.0;
                    b = b.face(&[[x, y, 0.1], [x + r, y, 0.1], [x, y + r, 0.1]]);
                }
                for k in 0..20 {
                    let x = k as f32 * 0.06 - 0.6;
                    b = b.face(&[[x, -0.3, 0.2], [x + 0.1, -0.2, 0.2], [x + 0.2, -0.1, 0.2]]);
                }
                b.done()
            },
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: &[],
            refused: false,
        },
        Case {
            name: "pixel-centres",
            what: "corners exactly on pixel centres and on row boundaries (the fill rule's ties)",
            mesh: {
                let at = |px: f64, py: f64| unproject(&standard, size, (px, py), 0.0);
                Builder::new()
                    .face(&[
                        at(20.5, 20.5),
                        at(80.5, 20.5),
                        at(80.5, 80.5),
                        at(20.5, 80.5),
                    ])
                    .face(&[
                        at(80.5, 20.5),
                        at(140.5, 20.5),
                        at(140.5, 80.5),
                        at(80.5, 80.5),
                    ])
                    .face(&[at(20.0, 80.0), at(140.0, 80.0), at(80.0, 110.0)])
                    .done()
            },
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: &[],
            refused: false,
        },
        Case {
            name: "guard-band",
            what: "a face 0.05 from the eye: corners tens of thousands of pixels off screen, clipped to the guard band",
            mesh: Builder::new()
                .face(&[[-0.9, -0.9, 0.9], [0.9, -0.9, 0.9], [0.0, 0.95, 0.9]])
                .face(&quad(-0.6, 0.5))
                .done(),
            yaw_pitch: (0.0, 0.0),
            camera: ReferenceCamera {
                eye_distance: 0.95,
                near: 0.01,
                ..standard
            },
            breaks: &[],
            refused: false,
        },
        Case {
            name: "nan",
            what: "a NaN coordinate in the OBJ file",
            mesh: HostMesh::from_obj(b"v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n")
                .map_err(|e| e.to_string()),
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: &[],
            refused: true,
        },
        Case {
            name: "inf",
            what: "an infinite coordinate in the OBJ file",
            mesh: HostMesh::from_obj(b"v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n")
                .map_err(|e| e.to_string()),
            yaw_pitch: (0.0, 0.0),
            camera: standard,
            breaks: &[],
            refused: true,
        },
        Case {
            name: "camera-inside",
            what: "the eye inside a closed sphere: its inside, every face crossing the frame",
            mesh: sphere(),
            yaw_pitch: (10.0, 20.0),
            camera: ReferenceCamera {
                eye_distance: 0.2,
                fov_y_deg: 90.0,
                ..standard
            },
            breaks: &[],
            refused: false,
        },
        Case {
            name: "behind-camera",
            what: "faces behind the eye and one straddling it, with a face in front",
            mesh: Builder::new()
                .face(&quad(0.9, 0.8))
                .face(&[[-0.5, -0.5, 0.95], [0.5, -0.5, 0.95], [0.0, 0.5, -0.3]])
                .face(&quad(-0.5, 0.4))
                .done(),
            yaw_pitch: (0.0, 0.0),
            camera: ReferenceCamera {
                eye_distance: 0.5,
                near: 0.05,
                ..standard
            },
            breaks: &[],
            refused: false,
        },
        Case {
            name: "near-far",
            what: "long faces crossing the near and the far plane",
            mesh: Builder::new()
                .face(&[
                    [-0.6, -0.3, 0.95],
                    [0.1, -0.3, 0.95],
                    [0.1, -0.1, -0.95],
                    [-0.6, -0.1, -0.95],
                ])
                .face(&[[0.3, -0.6, -0.95], [0.7, -0.6, -0.95], [0.5, 0.7, 0.95]])
                .done(),
            yaw_pitch: (0.0, 0.0),
            camera: ReferenceCamera {
                eye_distance: 1.5,
                near: 0.7,
                far: 2.2,
                ..standard
            },
            breaks: &[],
            refused: false,
        },
    ]
}

/// The methods the catalogue runs, with the depth format of those that
/// store depth.
pub const METHODS: [(Method, bool); 7] = [
    (Method::Scanline, false),
    (Method::Scanline, true),
    (Method::ZBuffer, false),
    (Method::Bands(8), false),
    (Method::Interval, false),
    (Method::Painter, false),
    (Method::Reference, false),
];

/// A method's column label: `scanline z16`, `interval`, ...
pub fn label(method: Method, z24: bool) -> String {
    if method.stores_depth() {
        format!("{} {}", method.name(), if z24 { "z24" } else { "z16" })
    } else {
        method.name()
    }
}

/// The reference view of the catalogue's frame at `yaw`/`pitch`.
fn view_at((yaw, pitch): (f32, f32)) -> ReferenceView {
    ReferenceView {
        width: usize::from(SIZE.0),
        height: usize::from(SIZE.1),
        yaw_deg: f64::from(yaw),
        pitch_deg: f64::from(pitch),
        cull_back: false,
    }
}

/// `mesh` by `method` at `yaw`/`pitch`, seen by `camera` (the reference
/// too), no culling, in the depth format `D`.
fn render_in<D: DepthFormat>(
    method: Method,
    mesh: &HostMesh,
    at: (f32, f32),
    camera: &ReferenceCamera,
    shading: &Shading,
) -> Result<MethodFrame, String>
where
    D::Value: Into<u32>,
{
    let (w, h) = SIZE;
    let model = reference_model(mesh, at.0, at.1).map_err(|e| e.to_string())?;
    let mut renderer = MethodRenderer::<D>::new(w, h)?;
    renderer.set_reference_camera(*camera);
    renderer.render(
        method,
        mesh,
        &model,
        &camera.camera(w, h),
        Cull::None,
        shading,
        &view_at(at),
    )
}

/// [`render_in`] with z24 or z16.
fn render_at(
    method: Method,
    z24: bool,
    mesh: &HostMesh,
    at: (f32, f32),
    camera: &ReferenceCamera,
    shading: &Shading,
) -> Result<MethodFrame, String> {
    if z24 {
        render_in::<Depth24>(method, mesh, at, camera, shading)
    } else {
        render_in::<Depth16>(method, mesh, at, camera, shading)
    }
}

/// Renders `case` by `method` (z24 or z16) and compares the frame with the
/// reference; the frame too, for the gallery.
pub fn run(case: &Case, method: Method, z24: bool) -> (Outcome, Option<MethodFrame>) {
    let mesh = match &case.mesh {
        Ok(mesh) => mesh,
        Err(e) => return (Outcome::Error(e.clone()), None),
    };
    let frame = render_at(
        method,
        z24,
        mesh,
        case.yaw_pitch,
        &case.camera,
        &Shading::lambert(),
    );
    match frame {
        Ok(frame) => {
            let reference =
                ReferenceFrame::render_with(mesh, &view_at(case.yaw_pitch), &case.camera);
            (
                Outcome::Frame(compare(&reference, &frame.faces)),
                Some(frame),
            )
        }
        Err(e) => (Outcome::Error(e), None),
    }
}

/// One fixed-capacity renderer drawing `mesh` in the catalogue's view: the
/// first error, or `None` when the frame fits.
fn draw_with<const V: usize, const P: usize, const E: usize, const AP: usize, const VM: usize>(
    mesh: &HostMesh,
) -> Option<String> {
    use zline::{FnSink, Renderer};
    use zline::{ScanArrays, TableArrays};
    use zline::{VertexCache, draw_mesh};
    let (w, h) = SIZE;
    let mut renderer: std::boxed::Box<
        Renderer<TableArrays<u32, V, P, E>, ScanArrays<u32, Depth16, 160, AP, 8>>,
    > = match Renderer::with_height(h, u32::MAX) {
        Ok(r) => std::boxed::Box::new(r),
        Err(e) => return Some(e.to_string()),
    };
    let mut cache = std::boxed::Box::new(VertexCache::<VM>::new());
    let model = reference_model(mesh, 0.0, 0.0).ok()?;
    let camera = ReferenceCamera::STANDARD.camera(w, h);
    if let Err(e) = draw_mesh(
        &mut *renderer,
        &mut *cache,
        mesh,
        &model,
        &camera,
        Cull::None,
        |f| f.face,
    ) {
        return Some(e.to_string());
    }
    let mut sink = FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), core::convert::Infallible>(()));
    renderer.render(&mut sink).err().map(|e| match e {
        zline::RenderError::Table(e) => e.to_string(),
        zline::RenderError::Sink(never) => match never {},
    })
}

/// Each capacity exceeded, on the four bars of `cyclic-4` (22 vertices with
/// the anchors, 4 polygons, 16 corners, up to 4 active): what the scanline
/// core and the z-buffer say. The host's methods (`interval`, `painter`,
/// `reference`) keep their lists on the heap and have no such limit.
pub fn capacity_errors() -> Vec<(&'static str, String)> {
    let Ok(mesh) = pinwheel(4) else {
        return Vec::new();
    };
    let say =
        |r: Option<String>| r.map_or_else(|| "fits (UNEXPECTED)".into(), |e| format!("error: {e}"));
    let zbuffer_short = {
        use zline::zbuffer::{BandBuffers, DepthTest, render_bands};
        use zline::{ActiveEdge, ActivePolygon, TableArrays, Tables};
        let (w, h) = SIZE;
        let model = reference_model(&mesh, 0.0, 0.0).ok();
        let camera = ReferenceCamera::STANDARD.camera(w, h);
        let mut tables: std::boxed::Box<Tables<TableArrays<u32, 64, 8, 32>>> =
            match Tables::new(TableArrays::new(0), w, h) {
                Ok(t) => std::boxed::Box::new(t),
                Err(e) => return vec![("tables", e.to_string())],
            };
        let mut cache = std::boxed::Box::new(zline::VertexCache::<64>::new());
        let drawn = model.map(|m| {
            zline::draw_mesh(
                &mut *tables,
                &mut *cache,
                &mesh,
                &m,
                &camera,
                Cull::None,
                |f| f.face,
            )
        });
        let prepared = tables.in_drawing_order();
        // Depth and colour for 10 rows where the frame has 120.
        let (mut depth, mut color) = (
            vec![0u16; usize::from(w) * 10],
            vec![0u32; usize::from(w) * 10],
        );
        let (mut scratch, mut active) = (
            vec![0u32; usize::from(w)],
            vec![ActivePolygon::filler(0u32)],
        );
        let mut pool = vec![ActiveEdge::EMPTY; 4];
        let mut sink =
            FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), core::convert::Infallible>(()));
        let result = render_bands::<u32, Depth16, _>(
            &prepared,
            BandBuffers {
                depth: &mut depth,
                color: &mut color,
                scratch: &mut scratch,
                active: &mut active,
                pool: &mut pool,
            },
            h,
            0,
            DepthTest::Nearer,
            None,
            &mut sink,
        );
        match (drawn, result) {
            (Some(Ok(_)), Err(zline::RenderError::Table(e))) => Some(e.to_string()),
            _ => None,
        }
    };
    use zline::FnSink;
    vec![
        (
            "scanline: vertex table (V = 8)",
            say(draw_with::<8, 8, 32, 8, 64>(&mesh)),
        ),
        (
            "scanline: polygon table (P = 2)",
            say(draw_with::<64, 2, 32, 8, 64>(&mesh)),
        ),
        (
            "scanline: corners and edge table (E = 8)",
            say(draw_with::<64, 8, 8, 8, 64>(&mesh)),
        ),
        (
            "scanline: active polygon table (AP = 1)",
            say(draw_with::<64, 8, 32, 1, 64>(&mesh)),
        ),
        (
            "scanline: vertex cache (VM = 16 for a 22-vertex mesh)",
            say(draw_with::<64, 8, 32, 8, 16>(&mesh)),
        ),
        (
            "zbuffer: depth and colour for 10 rows of a 120-row frame",
            say(zbuffer_short),
        ),
    ]
}

/// `mesh` with only the faces `keep` (the anchors stay, so the view is the
/// same).
pub fn only_faces(mesh: &HostMesh, keep: &[usize]) -> HostMesh {
    let mut out = HostMesh {
        positions: mesh.positions.clone(),
        ..HostMesh::default()
    };
    for &f in keep {
        let start = mesh.face_starts[f] as usize;
        let end = mesh
            .face_starts
            .get(f + 1)
            .map_or(mesh.corners.len(), |&e| e as usize);
        out.face_starts.push(out.corners.len() as u32);
        out.corners.extend_from_slice(&mesh.corners[start..end]);
    }
    out
}

/// Face ids of `mesh` by `method` at `yaw`/`pitch`, standard camera.
pub fn faces_at(
    method: Method,
    z24: bool,
    mesh: &HostMesh,
    at: (f32, f32),
) -> Result<Vec<u32>, String> {
    render_at(
        method,
        z24,
        mesh,
        at,
        &ReferenceCamera::STANDARD,
        &Shading::FaceId,
    )
    .map(|frame| frame.faces)
}

/// The views of the coplanar sequence: 21 frames, the camera turning a
/// quarter of a degree of yaw and a tenth of pitch a frame.
pub fn coplanar_views() -> impl Iterator<Item = (f32, f32)> {
    (0..21).map(|k| (20.0 + 0.25 * k as f32, 10.0 - 0.1 * k as f32))
}

/// How a method keeps the coplanar case's tie over the sequence: per
/// frame, the pixels where face 0 (added first) covers the sample but a
/// later coplanar face is drawn, and face 0's pixels. Each frame is drawn
/// twice and must come out the same (`Err` otherwise). With `shared`, the
/// faces share their plane (as the mesh finds them); without, each face's
/// plane comes from its own rounded corners.
pub fn coplanar_losses(
    method: Method,
    z24: bool,
    shared: bool,
) -> Result<Vec<(usize, usize)>, String> {
    let case = cases()
        .into_iter()
        .find(|c| c.name == "coplanar")
        .ok_or("no coplanar case")?;
    let mut mesh = case.mesh?;
    if !shared {
        mesh.shared_planes.clear();
    }
    let first = only_faces(&mesh, &[0]);
    coplanar_views()
        .map(|view| {
            let mask = faces_at(Method::Scanline, true, &first, view)?;
            let faces = faces_at(method, z24, &mesh, view)?;
            if faces != faces_at(method, z24, &mesh, view)? {
                return Err(format!(
                    "{} draws two frames of one view differently",
                    label(method, z24)
                ));
            }
            let own = mask.iter().filter(|&&f| f == 0).count();
            let lost = mask
                .iter()
                .zip(&faces)
                .filter(|&(&m, &f)| m == 0 && f != 0)
                .count();
            Ok((lost, own))
        })
        .collect()
}

/// Gaps between the plates of [`plates`], in units of the normalised
/// mesh (its radius is 1, the eye 3 away).
pub const PLATE_GAPS: [f32; 5] = [0.001, 0.003, 0.01, 0.03, 0.1];

/// The depth-precision scene: five pairs of parallel plates, the front
/// plate of pair `k` covering the left part of its back plate at a gap of
/// [`PLATE_GAPS`]`[k]`, so that a depth format too coarse for the gap
/// shows the back plate through the front one.
pub fn plates() -> HostMesh {
    let mut b = Builder::new();
    for (k, &gap) in PLATE_GAPS.iter().enumerate() {
        let top = 0.8 - 0.34 * k as f32;
        let bottom = top - 0.28;
        b = b
            .face(&[
                [-0.8, bottom, 0.0],
                [0.8, bottom, 0.0],
                [0.8, top, 0.0],
                [-0.8, top, 0.0],
            ])
            .face(&[
                [-0.8, bottom, gap],
                [0.2, bottom, gap],
                [0.2, top, gap],
                [-0.8, top, gap],
            ]);
    }
    b.0
}
