//! Accuracy of the scanline core against the float64 reference, for every
//! mesh in a folder at three views, for both depth formats.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin accuracy -- ../shared/meshes [--size WxH] [--cull none|back]
//! ```
//!
//! For each mesh, view and format it prints: pixels, mismatches (face id
//! differs from the reference), excused at edges (the sample lies within
//! 1/16 px of the boundary of the drawn or the reference face), excused as
//! depth ties (the drawn face's plane is within 0.1 % of the nearest
//! depth along the pixel's ray), and hard mismatches (the rest). It exits
//! non-zero when any z24 frame has a hard mismatch. z16 is reported, not
//! enforced.
//!
//! Gouraud shading ([`zline::paint::Gouraud`], per-vertex Lambert of
//! [`Shading::lambert`]) is measured on each mesh read smooth
//! (`HostMesh::from_obj_smooth`, 60° crease) at the same views, z24: face
//! ids against the reference (hard mismatches as above), and over the
//! pixels whose face id matches, each channel's error in 8-bit steps
//! against the reference's vertex colours (Lambert in `f64` from the
//! mesh's normals turned by the view) interpolated as the reference
//! defines it ([`ReferenceFrame::interpolated`]): of the interpolated
//! value before quantisation (`8.8`), and of the 8-bit colour it rounds
//! to, which is what a display gets before dithering. It exits non-zero
//! unless every frame has no hard mismatch, its 8-bit error at most 1
//! step on 99.9 % of its matched pixels and at most 2 steps on every pixel
//! more than 1/16 px from its face's boundary (the tolerance of face ids
//! at edges: there, corners snapped to 1/256 px can move a sliver's
//! values by more; the largest error of all pixels is printed too).
//!
//! Each mesh runs twice through the scanline core: in `f32` (`z16`,
//! `z24`), and quantized (`QuantizedHostMesh`: `i16` positions in its
//! bounding sphere, a unit normal per face) through the integer front end
//! (`z16 int`, `z24 int`), the path a microcontroller without an FPU
//! takes. Both are compared with the reference of the original mesh.

use std::path::PathBuf;
use std::process::ExitCode;

use embedded_graphics_core::pixelcolor::RgbColor;
use zline::Mat4;
use zline::Mesh;
use zline::Shading;
use zline::host::HostPaintedRenderer;
use zline::host::{HostMesh, QuantizedHostMesh};
use zline::paint::{CHANNEL_MAX, Gouraud, PaintColor};
use zline::{Camera, Cull, reference_model};
use zline::{Depth16, Depth24, DepthFormat};
use zline::{FnSink, Lambert};
use zline_lab::cli::parse_size;
use zline_lab::cli::run_tool;
use zline_lab::cli::{help_requested, obj_files};
use zline_lab::methods::EDGE_TOLERANCE;
use zline_lab::methods::{
    BACKGROUND, Comparison, Method, MethodRenderer, ReferenceCamera, ReferenceFrame, ReferenceView,
    compare, rotate,
};

/// (yaw, pitch) of the three views, degrees.
const VIEWS: [(f32, f32); 3] = [(30.0, 20.0), (135.0, -30.0), (250.0, 65.0)];

struct Options {
    dir: PathBuf,
    width: u16,
    height: u16,
    cull: Cull,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        dir: PathBuf::new(),
        width: 320,
        height: 240,
        cull: Cull::None,
    };
    let mut dir = None;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--size" => (o.width, o.height) = parse_size(it.next().ok_or("--size needs WxH")?)?,
            "--cull" => {
                o.cull = match it.next().map(String::as_str) {
                    Some("none") => Cull::None,
                    Some("back") => Cull::Back,
                    _ => return Err("--cull needs none or back".into()),
                }
            }
            s if dir.is_none() && !s.starts_with("--") => dir = Some(PathBuf::from(s)),
            s => return Err(format!("unexpected argument {s}")),
        }
    }
    o.dir = dir.ok_or("usage: accuracy MESH_DIR [--size WxH] [--cull none|back]")?;
    Ok(o)
}

/// One configuration of the run: a method, a depth format, and whether the
/// mesh goes through the integer front end (quantized).
struct Config {
    label: &'static str,
    method: Method,
    z24: bool,
    quantized: bool,
    /// Whether CI fails on a hard mismatch (every method but the painter).
    enforced: bool,
}

const CONFIGS: [Config; 8] = [
    Config {
        label: "scanline z16",
        method: Method::Scanline,
        z24: false,
        quantized: false,
        enforced: false,
    },
    Config {
        label: "scanline z24",
        method: Method::Scanline,
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "scanline z16 int",
        method: Method::Scanline,
        z24: false,
        quantized: true,
        enforced: false,
    },
    Config {
        label: "scanline z24 int",
        method: Method::Scanline,
        z24: true,
        quantized: true,
        enforced: true,
    },
    Config {
        label: "zbuffer z24",
        method: Method::ZBuffer,
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "bands:8 z24",
        method: Method::Bands(8),
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "interval",
        method: Method::Interval,
        z24: true,
        quantized: false,
        enforced: true,
    },
    Config {
        label: "painter",
        method: Method::Painter,
        z24: true,
        quantized: false,
        enforced: false,
    },
];

fn ids<D: DepthFormat, M: Mesh>(
    r: &mut MethodRenderer<D>,
    method: Method,
    mesh: &M,
    model: &Mat4,
    o: &Options,
    view: &ReferenceView,
) -> Result<Vec<u32>, String>
where
    D::Value: Into<u32>,
{
    let camera = Camera::reference(o.width, o.height);
    Ok(
        r.render(method, mesh, model, &camera, o.cull, &Shading::FaceId, view)?
            .faces,
    )
}

/// A painted pixel's channels as the core interpolated them (8.8, before
/// any quantisation).
#[derive(Debug, Clone, Copy, Default)]
struct Channels([u32; 3]);

impl PaintColor for Channels {
    const COARSE: bool = false;
    fn from_channels(rgb: [u32; 3], _: Option<u32>) -> Self {
        Self(rgb.map(|c| c.min(CHANNEL_MAX)))
    }
}

/// Colour errors of one Gouraud frame over its matched pixels, in 8-bit
/// steps.
#[derive(Default)]
struct ColorErrors {
    matched: u64,
    /// Largest and summed error of the interpolated values (8.8).
    max_value: f64,
    sum_value: f64,
    /// Largest and summed error of the 8-bit colours.
    max_8bit: f64,
    sum_8bit: f64,
    /// Pixels whose 8-bit colour is more than 1 step off.
    over_one: u64,
    /// Largest 8-bit error of pixels whose sample is more than
    /// [`EDGE_TOLERANCE`] from the face's boundary (nearer, corners
    /// snapped to the sub-pixel grid can move a sliver's values by more).
    max_8bit_inside: f64,
}

impl ColorErrors {
    fn add(&mut self, other: &Self) {
        self.matched += other.matched;
        self.max_value = self.max_value.max(other.max_value);
        self.sum_value += other.sum_value;
        self.max_8bit = self.max_8bit.max(other.max_8bit);
        self.sum_8bit += other.sum_8bit;
        self.over_one += other.over_one;
        self.max_8bit_inside = self.max_8bit_inside.max(other.max_8bit_inside);
    }

    /// Share of matched pixels within 1 step (8-bit).
    fn within_one(&self) -> f64 {
        1.0 - self.over_one as f64 / self.matched.max(1) as f64
    }

    /// The bar: at most 1 step on 99.9 % of the matched pixels, at most 2
    /// on every pixel more than [`EDGE_TOLERANCE`] from its face's
    /// boundary (the tolerance that excuses face-id mismatches at edges).
    fn meets_the_bar(&self) -> bool {
        self.max_8bit_inside <= 2.0 && self.within_one() >= 0.999
    }
}

/// The reference's vertex colours for `lambert` (8-bit units, `f64`): its
/// Lambert of each vertex normal turned by the view, one-sided; a vertex
/// with no normal lit as if it faced the light.
fn reference_vertex_colors<'a>(
    mesh: &'a HostMesh,
    view: &'a ReferenceView,
    lambert: &'a Lambert,
) -> impl Fn(usize) -> [f64; 3] + 'a {
    let l = lambert.light();
    let l = [l.x, l.y, l.z].map(f64::from);
    let len = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
    let l = l.map(|c| c / len);
    let ambient = f64::from(lambert.ambient());
    let base = lambert.base();
    let base = [base.r(), base.g(), base.b()].map(f64::from);
    move |v| {
        let d = mesh.vertex_normal(v).map_or(1.0, |n| {
            let n = rotate(view, n.map(f64::from));
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len
        });
        let k = ambient + (1.0 - ambient) * d.max(0.0);
        base.map(|c| c * k)
    }
}

/// One Gouraud frame of `mesh` (read smooth) against the reference:
/// face-id comparison and colour errors.
fn gouraud_frame(
    mesh: &HostMesh,
    view: (f32, f32),
    reference_view: &ReferenceView,
    o: &Options,
    ids_renderer: &mut MethodRenderer<Depth24>,
) -> Result<(Comparison, ColorErrors), String> {
    let Shading::Lambert(lambert) = Shading::lambert() else {
        return Err("Shading::lambert() is not Lambert".into());
    };
    let colors = reference_vertex_colors(mesh, reference_view, &lambert);
    let reference = ReferenceFrame::render_with_values(
        mesh,
        reference_view,
        &ReferenceCamera::STANDARD,
        &colors,
    );
    let model = reference_model(mesh, view.0, view.1).map_err(|e| e.to_string())?;
    let faces = ids(
        ids_renderer,
        Method::Scanline,
        mesh,
        &model,
        o,
        reference_view,
    )?;
    let comparison = compare(&reference, &faces);
    let camera = Camera::reference(o.width, o.height);
    let mut painted = HostPaintedRenderer::<Gouraud<Channels>, Depth24>::for_mesh(
        mesh,
        o.width,
        o.height,
        Gouraud::new(),
        Channels::default(),
    )
    .map_err(|e| e.to_string())?;
    let shading = Shading::Lambert(lambert);
    painted
        .draw_mesh(mesh, &model, &camera, o.cull, |v| shading.vertex_color(v))
        .map_err(|e| e.to_string())?;
    let mut values = Vec::with_capacity(usize::from(o.width) * usize::from(o.height));
    painted
        .render(&mut FnSink(|_: u16, row: &[Channels], _: &[u32]| {
            values.extend_from_slice(row);
            Ok::<(), ()>(())
        }))
        .map_err(|e| format!("{e:?}"))?;
    let mut errors = ColorErrors::default();
    let width = usize::from(o.width);
    for (k, (&id, value)) in faces.iter().zip(&values).enumerate() {
        if id == BACKGROUND || id != reference.ids[k] {
            continue;
        }
        let Some(exact) = reference.interpolated(id, k % width, k / width) else {
            continue;
        };
        let (mut worst_value, mut worst_8bit) = (0.0f64, 0.0f64);
        for c in 0..3 {
            let v = f64::from(value.0[c]) / 256.0;
            let eight_bit = ((value.0[c] + 128) >> 8) as f64;
            let exact = exact[c].clamp(0.0, 255.0);
            worst_value = worst_value.max((v - exact).abs());
            worst_8bit = worst_8bit.max((eight_bit - exact).abs());
        }
        errors.matched += 1;
        errors.max_value = errors.max_value.max(worst_value);
        errors.sum_value += worst_value;
        errors.max_8bit = errors.max_8bit.max(worst_8bit);
        errors.sum_8bit += worst_8bit;
        errors.over_one += u64::from(worst_8bit > 1.0);
        if reference.boundary_distance(id, k % width, k / width) > EDGE_TOLERANCE {
            errors.max_8bit_inside = errors.max_8bit_inside.max(worst_8bit);
        }
    }
    Ok((comparison, errors))
}

fn gouraud_row(name: &str, view: (f32, f32), c: &Comparison, e: &ColorErrors) {
    let mean = |sum: f64| sum / e.matched.max(1) as f64;
    println!(
        "| {name} | {:.0}/{:.0} | {} | {} | {:.3} | {:.4} | {:.3} | {:.3} | {:.4} | {:.4} % |",
        view.0,
        view.1,
        c.hard,
        e.matched,
        e.max_value,
        mean(e.sum_value),
        e.max_8bit,
        e.max_8bit_inside,
        mean(e.sum_8bit),
        100.0 * e.within_one()
    );
}

/// The Gouraud table: every mesh read smooth, at the three views, z24.
fn gouraud(o: &Options) -> Result<bool, String> {
    let mut ids_renderer = MethodRenderer::<Depth24>::new(o.width, o.height)?;
    println!();
    println!(
        "Gouraud, z24: colour error in 8-bit steps (largest channel) over pixels whose face id matches the reference"
    );
    println!();
    println!(
        "| mesh | yaw/pitch | hard mismatches | matched pixels | max (8.8 value) | mean (8.8 value) | max (8-bit) | max (8-bit) beyond 1/16 px of an edge | mean (8-bit) | within 1 step (8-bit) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let (mut ok, mut hard) = (true, 0);
    let mut all = ColorErrors::default();
    for path in obj_files(&o.dir)? {
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mesh = HostMesh::from_obj_smooth(&bytes, zline::host::DEFAULT_CREASE_DEGREES)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        for view in VIEWS {
            let reference_view = ReferenceView {
                width: usize::from(o.width),
                height: usize::from(o.height),
                yaw_deg: f64::from(view.0),
                pitch_deg: f64::from(view.1),
                cull_back: o.cull == Cull::Back,
            };
            let (c, e) = gouraud_frame(&mesh, view, &reference_view, o, &mut ids_renderer)?;
            gouraud_row(&name, view, &c, &e);
            ok &= c.hard == 0 && e.meets_the_bar();
            hard += c.hard;
            all.add(&e);
        }
    }
    let total = Comparison {
        hard,
        ..Comparison::default()
    };
    gouraud_row("**all**", (0.0, 0.0), &total, &all);
    println!(
        "gouraud: hard mismatches {hard}, largest 8-bit error {:.3} ({:.3} beyond 1/16 px of an edge), within 1 step {:.4} % ({})",
        all.max_8bit,
        all.max_8bit_inside,
        100.0 * all.within_one(),
        if ok { "ok" } else { "FAILED" }
    );
    Ok(ok)
}

fn row(name: &str, view: (f32, f32), format: &str, c: &Comparison) {
    println!(
        "| {name} | {:.0}/{:.0} | {format} | {} | {} | {} | {} | {} |",
        view.0, view.1, c.pixels, c.mismatches, c.excused_at_edges, c.excused_as_ties, c.hard
    );
}

fn run(args: &[String]) -> Result<bool, String> {
    let o = parse(args)?;
    let mut z16 = MethodRenderer::<Depth16>::new(o.width, o.height)?;
    let mut z24 = MethodRenderer::<Depth24>::new(o.width, o.height)?;
    println!(
        "| mesh | yaw/pitch | method | pixels | mismatches | excused at edges | excused as ties | hard |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut totals = [(); CONFIGS.len()].map(|()| Comparison::default());
    for path in obj_files(&o.dir)? {
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mesh = HostMesh::from_obj(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        let quantized =
            QuantizedHostMesh::new(&mesh).map_err(|e| format!("{}: {e}", path.display()))?;
        let quantized = quantized
            .mesh()
            .map_err(|e| format!("{}: {e:?}", path.display()))?;
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        for view in VIEWS {
            let reference_view = ReferenceView {
                width: usize::from(o.width),
                height: usize::from(o.height),
                yaw_deg: f64::from(view.0),
                pitch_deg: f64::from(view.1),
                cull_back: o.cull == Cull::Back,
            };
            let reference = ReferenceFrame::render(&mesh, &reference_view);
            let model = reference_model(&mesh, view.0, view.1).map_err(|e| e.to_string())?;
            for (config, totals) in CONFIGS.iter().zip(&mut totals) {
                let v = &reference_view;
                let faces = match (config.z24, config.quantized) {
                    (false, false) => ids(&mut z16, config.method, &mesh, &model, &o, v)?,
                    (true, false) => ids(&mut z24, config.method, &mesh, &model, &o, v)?,
                    (false, true) => ids(&mut z16, config.method, &quantized, &model, &o, v)?,
                    (true, true) => ids(&mut z24, config.method, &quantized, &model, &o, v)?,
                };
                let c = compare(&reference, &faces);
                row(&name, view, config.label, &c);
                totals.pixels += c.pixels;
                totals.mismatches += c.mismatches;
                totals.excused_at_edges += c.excused_at_edges;
                totals.excused_as_ties += c.excused_as_ties;
                totals.hard += c.hard;
            }
        }
    }
    let mut ok = true;
    let mut summary = Vec::new();
    for (config, t) in CONFIGS.iter().zip(&totals) {
        row("**all**", (0.0, 0.0), config.label, t);
        if config.enforced && t.hard > 0 {
            ok = false;
        }
        summary.push(format!("{} {}", config.label, t.hard));
    }
    println!(
        "accuracy: hard mismatches (0 required for every method but the painter and z16): {}",
        summary.join(", ")
    );
    let gouraud_ok = gouraud(&o)?;
    Ok(ok && gouraud_ok)
}

const USAGE: &str = "usage: accuracy MESH_DIR [--size WxH] [--cull none|back]
Every method against the float64 reference on every mesh of MESH_DIR at three views, both depth
formats; prints Markdown tables and exits non-zero on a hard mismatch of any method but the painter.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("accuracy", USAGE, move || match run(&args)? {
        true => Ok(()),
        false => Err("hard mismatches, or Gouraud colour errors above the bar".into()),
    })
}
