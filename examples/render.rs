//! Headless render of an OBJ mesh in the reference view, by any of the
//! hidden-surface methods: the scanline core, the full-frame and banded
//! z-buffers, the interval scanline, the painter, or the float64 reference.
//!
//! ```sh
//! cargo run --release --example render -- MODEL.obj [options]
//! ```
//!
//! `MODEL` is an OBJ file or `shape:NAME` for a built-in mesh
//! (`torus-knot`, `icosphere`, `boxes`, `terrain`).
//!
//! Options (defaults in brackets):
//! * `--size WxH` [320x240]
//! * `--yaw DEG` [30] and `--pitch DEG` [20]
//! * `--shade flat|lambert|depth|id|gouraud|texture|lit-texture`
//!   [lambert]: `gouraud` is Lambert per vertex, interpolated; `texture`
//!   maps `--texture` perspective-correctly by the mesh's `vt`
//!   coordinates; `lit-texture` scales it by Lambert light per vertex (a
//!   white surface), interpolated (each a painted renderer's colours, the
//!   scanline method's face ids)
//! * `--texture FILE.png`: the texture for `--shade texture|lit-texture`, read as
//!   Rgb565 texels; `--filter nearest|bilinear` [nearest], `--wrap
//!   repeat|clamp` [repeat]
//! * `--cull none|back` [none]
//! * `--depth z16|z24` [z24]
//! * `--method scanline|zbuffer|bands:K|interval|painter|reference`
//!   [scanline]: `bands:K` keeps a z-buffer of K rows (1 to 4096)
//! * `--out FILE.png`: the frame as PNG (through embedded-graphics-simulator,
//!   no SDL)
//! * `--ids FILE.bin`: W·H little-endian u32, row-major from the top: the
//!   visible face id (0-based index among the `f` lines), or 0xFFFFFFFF
//! * `--stats`: `key=value` lines: timing over repeated frames, the
//!   method's memory and counts, what the front end did (listed in
//!   `docs/guide/render-tool.md`)
//! * `--frames N` [15]: timed frames after 3 warm-up frames
//!
//! The view: positions normalised to the unit sphere about their bounding
//! box centre, rotated `Rx(pitch) · Ry(yaw)`, eye at (0, 0, 3) looking down
//! -Z, 45° vertical field of view, near 0.1, far 10 (see
//! `zline::reference_model` and `zline_lab::methods::ReferenceView`).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use zline::FnSink;
use zline::Shading;
use zline::host::{HostMesh, HostPaintedRenderer};
use zline::paint::{Filter, Gouraud, LitTexCoord, LitTextured, PaintMode, Textured, Wrap};
use zline::{Camera, Cull, reference_model};
use zline::{Depth16, Depth24, DepthFormat};
use zline::{DrawStats, VertexInfo};
use zline_lab::cli::parse_size;
use zline_lab::cli::{help_requested, run_tool};
use zline_lab::cli::{load_model, load_model_smooth};
use zline_lab::methods::{BACKGROUND, Method, MethodRenderer, ReferenceView};
use zline_lab::textures::{Rgb565Texture, white_light};

/// Parsed command line.
#[derive(Debug)]
struct Options {
    model: PathBuf,
    width: u16,
    height: u16,
    yaw: f32,
    pitch: f32,
    shade: Shading,
    painted: Painted,
    texture: Option<PathBuf>,
    filter: Filter,
    wrap: Wrap,
    cull: Cull,
    depth: String,
    method: Method,
    out: Option<PathBuf>,
    ids: Option<PathBuf>,
    stats: bool,
    frames: usize,
}

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        model: PathBuf::new(),
        width: 320,
        height: 240,
        yaw: 30.0,
        pitch: 20.0,
        shade: Shading::lambert(),
        painted: Painted::No,
        texture: None,
        filter: Filter::Nearest,
        wrap: Wrap::Repeat,
        cull: Cull::None,
        depth: "z24".into(),
        method: Method::Scanline,
        out: None,
        ids: None,
        stats: false,
        frames: 15,
    };
    let mut model = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--size" => (o.width, o.height) = parse_size(value()?)?,
            "--yaw" => o.yaw = parse_angle(arg, value()?)?,
            "--pitch" => o.pitch = parse_angle(arg, value()?)?,
            "--shade" => {
                o.shade = match value()?.as_str() {
                    "flat" => Shading::Flat(Rgb888::new(200, 190, 170)),
                    "lambert" => Shading::lambert(),
                    "depth" => Shading::Depth {
                        near: 2.0,
                        far: 4.0,
                    },
                    "id" => Shading::FaceId,
                    "gouraud" => {
                        o.painted = Painted::Gouraud;
                        Shading::lambert()
                    }
                    "texture" => {
                        o.painted = Painted::Texture;
                        Shading::lambert()
                    }
                    "lit-texture" => {
                        o.painted = Painted::LitTexture;
                        Shading::Lambert(white_light())
                    }
                    s => {
                        return Err(format!(
                            "--shade: unknown '{s}' (flat, lambert, depth, id, gouraud, texture, lit-texture)"
                        ));
                    }
                }
            }
            "--cull" => {
                o.cull = match value()?.as_str() {
                    "none" => Cull::None,
                    "back" => Cull::Back,
                    s => return Err(format!("--cull: unknown '{s}' (none, back)")),
                }
            }
            "--depth" => {
                o.depth = value()?.clone();
                if o.depth != "z16" && o.depth != "z24" {
                    return Err(format!("--depth: unknown '{}' (z16, z24)", o.depth));
                }
            }
            "--method" => {
                o.method = Method::parse(value()?).map_err(|e| format!("--method: {e}"))?
            }
            "--texture" => o.texture = Some(value()?.into()),
            "--filter" => {
                o.filter = match value()?.as_str() {
                    "nearest" => Filter::Nearest,
                    "bilinear" => Filter::Bilinear,
                    s => return Err(format!("--filter: unknown '{s}' (nearest, bilinear)")),
                }
            }
            "--wrap" => {
                o.wrap = match value()?.as_str() {
                    "repeat" => Wrap::Repeat,
                    "clamp" => Wrap::Clamp,
                    s => return Err(format!("--wrap: unknown '{s}' (repeat, clamp)")),
                }
            }
            "--out" => o.out = Some(value()?.into()),
            "--ids" => o.ids = Some(value()?.into()),
            "--frames" => {
                o.frames = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=MAX_FRAMES).contains(n))
                    .ok_or_else(|| {
                        format!("--frames: expected a whole number from 1 to {MAX_FRAMES}")
                    })?
            }
            "--stats" => o.stats = true,
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s if model.is_none() => model = Some(PathBuf::from(s)),
            s => return Err(format!("unexpected argument {s}")),
        }
    }
    o.model = model.ok_or("missing MODEL.obj")?;
    let textured = matches!(o.painted, Painted::Texture | Painted::LitTexture);
    if textured != o.texture.is_some() {
        return Err("--shade texture|lit-texture and --texture FILE.png go together".into());
    }
    Ok(o)
}

/// Which painted renderer draws the colours, if any.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Painted {
    No,
    Gouraud,
    Texture,
    LitTexture,
}

fn parse_angle(name: &str, s: &str) -> Result<f32, String> {
    s.parse::<f32>()
        .ok()
        .filter(|a| a.is_finite())
        .ok_or_else(|| format!("{name}: expected degrees, got '{s}'"))
}

/// A rendered frame, whichever method made it.
struct Output {
    faces: Vec<u32>,
    colors: Vec<Rgb888>,
    times_ms: Vec<f64>,
    stats: Vec<(String, String)>,
}

/// Most timed frames `--frames` accepts.
const MAX_FRAMES: usize = 100_000;

/// The median, or NaN for no times.
fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times.get(times.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Frames of a painted renderer with `mode`, each vertex's value from
/// `value`: the last frame's colours and each timed frame's time (ms).
fn painted_frames<M, D>(
    mode: M,
    (model, camera, cull, mesh): (zline::Mat4, Camera, Cull, &HostMesh),
    (warm_up, frames): (usize, usize),
    value: impl Fn(&VertexInfo<'_>) -> M::Source,
) -> Result<(Vec<Rgb888>, Vec<f64>), String>
where
    M: PaintMode<Color = Rgb888>,
    D: DepthFormat,
{
    let mut painted = HostPaintedRenderer::<M, D>::for_mesh(
        mesh,
        camera.width,
        camera.height,
        mode,
        Rgb888::BLACK,
    )
    .map_err(|e| e.to_string())?;
    let (mut colors, mut times) = (Vec::new(), Vec::new());
    for k in 0..warm_up + frames {
        colors.clear();
        let start = Instant::now();
        painted.clear();
        let _: DrawStats = painted
            .draw_mesh(mesh, &model, &camera, cull, &value)
            .map_err(|e| e.to_string())?;
        painted
            .render(&mut FnSink(|_: u16, row: &[Rgb888], _: &[D::Value]| {
                colors.extend_from_slice(row);
                Ok::<(), ()>(())
            }))
            .map_err(|e| format!("{e:?}"))?;
        if k >= warm_up {
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
    }
    Ok((colors, times))
}

fn run_method<D: DepthFormat>(o: &Options, mesh: &HostMesh) -> Result<Output, String>
where
    D::Value: Into<u32>,
{
    let mut r = MethodRenderer::<D>::new(o.width, o.height)?;
    let model = reference_model(mesh, o.yaw, o.pitch).map_err(|e| e.to_string())?;
    let camera = Camera::reference(o.width, o.height);
    let view = ReferenceView {
        width: usize::from(o.width),
        height: usize::from(o.height),
        yaw_deg: f64::from(o.yaw),
        pitch_deg: f64::from(o.pitch),
        cull_back: o.cull == Cull::Back,
    };
    // The reference is slow: fewer warm-up and timed frames.
    let (warm_up, frames) = if o.method == Method::Reference {
        (1, o.frames.min(3))
    } else {
        (3, o.frames)
    };
    let mut times = Vec::new();
    let mut last = None;
    for k in 0..warm_up + frames {
        let start = Instant::now();
        let frame = r.render(o.method, mesh, &model, &camera, o.cull, &o.shade, &view)?;
        if k >= warm_up {
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        last = Some(frame);
    }
    let mut f = last.ok_or("no frame rendered")?;
    if o.painted != Painted::No {
        if o.method != Method::Scanline {
            return Err(format!(
                "--shade gouraud|texture|lit-texture: drawn by the scanline method only, not {}",
                o.method.name()
            ));
        }
        // The painted renderer's colours and times; the face ids above.
        let draw = (model, camera, o.cull, mesh);
        let png = o
            .texture
            .as_ref()
            .map(|path| Rgb565Texture::read(path, 1))
            .transpose()?;
        let texture = png
            .as_ref()
            .map(|png| {
                png.texture()
                    .map(|t| t.with_filter(o.filter).with_wrap(o.wrap))
            })
            .transpose()?;
        let (colors, painted_times) = match (o.painted, texture) {
            (Painted::Texture, Some(texture)) => painted_frames::<_, D>(
                Textured::<Rgb888>::new(texture),
                draw,
                (warm_up, frames),
                |v| v.tex_coord(),
            )?,
            (Painted::LitTexture, Some(texture)) => {
                let light = white_light();
                painted_frames::<_, D>(
                    LitTextured::<Rgb888>::new(texture),
                    draw,
                    (warm_up, frames),
                    |v| LitTexCoord::new(v.tex_coord(), light.vertex_color(v)),
                )?
            }
            (Painted::Texture | Painted::LitTexture, None) => {
                return Err("--shade texture|lit-texture needs --texture".into());
            }
            _ => painted_frames::<_, D>(Gouraud::<Rgb888>::new(), draw, (warm_up, frames), |v| {
                o.shade.vertex_color(v)
            })?,
        };
        times = painted_times;
        f.colors = colors;
    }
    let s = |k: &str, v: &dyn ToString| (k.to_string(), v.to_string());
    let cache_bytes = 2 * mesh.positions.len();
    let m = f.memory;
    let mut stats = vec![
        s(
            "depth",
            &if o.method.stores_depth() {
                D::NAME
            } else {
                "none"
            },
        ),
        s("memory_bytes", &m.total()),
        s("depth_bytes", &m.depth),
        s("color_bytes", &m.color),
        s("table_bytes", &m.tables),
        s("working_bytes", &m.working),
    ];
    if o.method != Method::Reference {
        let d = f.draw;
        stats.extend([
            s("ram_bytes", &(m.total() + cache_bytes)),
            s("faces", &d.faces),
            s("queued", &d.queued),
            s("back_faces", &d.back_faces),
            s("outside", &d.outside),
            s("clipped", &d.clipped),
            s("off_screen", &d.off_screen),
            s("degenerate", &d.degenerate),
            s("non_finite", &d.non_finite),
            s("split", &d.split),
            s("convex_quads", &d.convex_quads),
            s("shared_planes", &d.shared_planes),
            s("unshared_planes", &d.unshared_planes),
        ]);
    } else {
        let drawn: std::collections::HashSet<u32> = f
            .faces
            .iter()
            .copied()
            .filter(|&i| i != BACKGROUND)
            .collect();
        stats.push(s("visible_faces", &drawn.len()));
    }
    stats.extend(f.counts.iter().cloned());
    Ok(Output {
        faces: f.faces,
        colors: f.colors,
        times_ms: times,
        stats,
    })
}

fn write_outputs(o: &Options, out: &Output) -> Result<(), String> {
    if let Some(path) = &o.out {
        let size = Size::new(u32::from(o.width), u32::from(o.height));
        let mut display = SimulatorDisplay::<Rgb888>::new(size);
        for (y, row) in out.colors.chunks(usize::from(o.width)).enumerate() {
            let area = Rectangle::new(Point::new(0, y as i32), Size::new(size.width, 1));
            display
                .fill_contiguous(&area, row.iter().copied())
                .map_err(|e| format!("{e:?}"))?;
        }
        display
            .to_rgb_output_image(&OutputSettings::default())
            .save_png(path)
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    if let Some(path) = &o.ids {
        let bytes: Vec<u8> = out.faces.iter().flat_map(|id| id.to_le_bytes()).collect();
        std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

fn run(args: &[String]) -> Result<(), String> {
    let o = parse_args(args)?;
    let spec = o.model.to_string_lossy();
    let mesh = if o.painted != Painted::No {
        load_model_smooth(&spec)?
    } else {
        load_model(&spec)?
    };
    let mut out = match o.depth.as_str() {
        "z16" => run_method::<Depth16>(&o, &mesh)?,
        _ => run_method::<Depth24>(&o, &mesh)?,
    };
    write_outputs(&o, &out)?;
    if o.stats {
        println!("method={}", o.method.name());
        println!("width={}\nheight={}", o.width, o.height);
        println!("frames={}", out.times_ms.len());
        println!("frame_ms_median={:.3}", median(&mut out.times_ms));
        for (k, v) in &out.stats {
            println!("{k}={v}");
        }
        let covered = out.faces.iter().filter(|&&f| f != BACKGROUND).count();
        println!("covered_pixels={covered}");
        println!(
            "zbuffer_framebuffer_bytes={}",
            usize::from(o.width) * usize::from(o.height) * 4
        );
    }
    if o.out.is_none() && o.ids.is_none() && !o.stats {
        // Asked for nothing to keep: say what was done.
        let covered = out.faces.iter().filter(|&&f| f != BACKGROUND).count();
        println!(
            "render: drew {} at {}x{} with {} ({} frame{}, median {:.2} ms, {covered} pixels covered); \
             nothing written: add --out FILE.png, --ids FILE.bin or --stats",
            o.model.display(),
            o.width,
            o.height,
            o.method.name(),
            out.times_ms.len(),
            if out.times_ms.len() == 1 { "" } else { "s" },
            median(&mut out.times_ms),
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("render", USAGE, move || run(&args))
}

const USAGE: &str = "usage: render MODEL.obj|shape:NAME [--size WxH] [--yaw DEG] [--pitch DEG] [--shade flat|lambert|depth|id|gouraud|texture|lit-texture] [--texture FILE.png] [--filter nearest|bilinear] [--wrap repeat|clamp] [--cull none|back] [--depth z16|z24] [--method scanline|zbuffer|bands:K|interval|painter|reference] [--out FILE.png] [--ids FILE.bin] [--stats] [--frames N]";
