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
//! Each mesh runs twice through the scanline core: in `f32` (`z16`,
//! `z24`), and quantized (`QuantizedHostMesh`: `i16` positions in its
//! bounding sphere, a unit normal per face) through the integer front end
//! (`z16 int`, `z24 int`), the path a microcontroller without an FPU
//! takes. Both are compared with the reference of the original mesh.

use std::path::PathBuf;
use std::process::ExitCode;

use zline::Mat4;
use zline::Mesh;
use zline::Shading;
use zline::host::{HostMesh, QuantizedHostMesh};
use zline::{Camera, Cull, reference_model};
use zline::{Depth16, Depth24, DepthFormat};
use zline_lab::cli::parse_size;
use zline_lab::cli::run_tool;
use zline_lab::cli::{help_requested, obj_files};
use zline_lab::methods::{
    Comparison, Method, MethodRenderer, ReferenceFrame, ReferenceView, compare,
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
    Ok(ok)
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
        false => Err("hard mismatches".into()),
    })
}
