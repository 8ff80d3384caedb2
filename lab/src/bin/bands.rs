//! Where a frame drawn in bands on several threads (`BandedRenderer`)
//! spends its time, next to one renderer on one thread: the steps the
//! threads share (projecting the vertices, sorting the faces into bands),
//! then each band's polygons, its table building (from the projection and
//! its faces) and its scan, and the frame's wall-clock time. Medians over the frames, after a few untimed ones.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin bands -- MODEL.obj [--size WxH] [--cull none|back] [--threads N] [--frames N]
//! ```
//!
//! The frame is the peers bench's (reference view, each face's Lambert
//! colour from a table, z16, rows copied into an Rgb565 frame buffer);
//! the banded frame is checked equal to the single renderer's.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::IntoStorage;
use zline::Mat4;
use zline::Mesh;
use zline::Shading;
use zline::host::{BandedRenderer, HostMesh, SharedSteps, host_renderer};
use zline::{Camera, Cull, FaceInfo, VertexCache, draw_mesh, reference_model};
use zline::{Depth16, FnSink};
use zline_lab::cli::parse_size;
use zline_lab::cli::run_tool;
use zline_lab::cli::{help_requested, load_model};

/// Untimed frames before the timed ones.
const WARM_UP: usize = 5;

/// The options.
struct Options {
    path: String,
    size: (u16, u16),
    cull: Cull,
    threads: usize,
    frames: usize,
}

fn median(mut v: Vec<Duration>) -> f64 {
    v.sort();
    v.get(v.len() / 2)
        .map_or(f64::NAN, |d| d.as_secs_f64() * 1e3)
}

fn run(args: &[String]) -> Result<(), String> {
    let o = options(args)?;
    let mesh = load_model(&o.path)?;
    let (width, height) = o.size;
    let caps = mesh.capacities(width);
    let model = reference_model(&mesh, 30.0, 20.0).map_err(|e| e.to_string())?;
    let camera = Camera::reference(width, height);
    let shading = Shading::lambert();
    let colors: Vec<Rgb565> = (0..mesh.face_count())
        .map(|f| {
            Rgb565::from(shading.color(&FaceInfo::new(f as u32, true, Default::default(), 0.0)))
        })
        .collect();
    let pixels = usize::from(width) * usize::from(height);
    let black = Rgb565::new(0, 0, 0);

    // One renderer on this thread.
    let mut single =
        host_renderer::<Rgb565, Depth16>(&caps, width, height, black).map_err(|e| e.to_string())?;
    let mut cache: Box<VertexCache<65536>> = Box::default();
    let mut frame = vec![0u16; pixels];
    let (mut builds, mut scans) = (Vec::new(), Vec::new());
    for k in 0..WARM_UP + o.frames {
        let start = Instant::now();
        single.clear();
        draw_mesh(
            &mut single,
            &mut *cache,
            &mesh,
            &model,
            &camera,
            o.cull,
            |f| colors[f.face as usize],
        )
        .map_err(|e| e.to_string())?;
        let built = Instant::now();
        single
            .render(&mut FnSink(|y: u16, c: &[Rgb565], _: &[u16]| {
                copy(&mut frame, usize::from(width), usize::from(y), c);
                Ok::<(), ()>(())
            }))
            .map_err(|e| format!("{e:?}"))?;
        if k >= WARM_UP {
            builds.push(built - start);
            scans.push(built.elapsed());
        }
    }
    let polygons = single.polygon_count();

    // The same frame in bands.
    let mut banded = BandedRenderer::<Rgb565, Depth16>::new(&caps, width, height, black, o.threads)
        .map_err(|e| e.to_string())?;
    let mut bands_frame = vec![0u16; pixels];
    let (mut walls, mut shared) = (Vec::new(), Vec::new());
    let mut per_band: Vec<Vec<(usize, Duration, Duration)>> = vec![Vec::new(); o.threads];
    let scene = SceneView {
        mesh: &mesh,
        model: &model,
        camera: &camera,
        cull: o.cull,
        colors: &colors,
    };
    for k in 0..WARM_UP + o.frames {
        let start = Instant::now();
        draw_bands(&mut banded, &mut bands_frame, width, &scene)?;
        if k >= WARM_UP {
            walls.push(start.elapsed());
            shared.push(banded.last_shared_steps());
            for (band, t) in per_band.iter_mut().zip(banded.last_frame()) {
                band.push((t.polygons, t.build, t.scan));
            }
        }
    }
    if bands_frame != frame {
        return Err("the banded frame differs from the single renderer's".into());
    }
    report(
        &o,
        &mesh,
        polygons,
        (builds, scans),
        &banded,
        per_band,
        (shared, walls),
    );
    Ok(())
}

/// Copies row `y`'s colours into the frame buffer.
fn copy(frame: &mut [u16], width: usize, y: usize, colors: &[Rgb565]) {
    for (out, c) in frame[y * width..][..width].iter_mut().zip(colors) {
        *out = c.into_storage();
    }
}

/// What a banded frame draws.
struct SceneView<'a> {
    mesh: &'a HostMesh,
    model: &'a Mat4,
    camera: &'a Camera,
    cull: Cull,
    colors: &'a [Rgb565],
}

/// One banded frame into `frame`, each band's sink writing its rows.
fn draw_bands(
    banded: &mut BandedRenderer<Rgb565, Depth16>,
    frame: &mut [u16],
    width: u16,
    scene: &SceneView,
) -> Result<(), String> {
    let width = usize::from(width);
    let mut rest = frame;
    let mut sinks = Vec::new();
    for rows in banded.bands() {
        let (part, tail) = rest.split_at_mut(rows.len() * width);
        rest = tail;
        sinks.push(FnSink(move |y: u16, c: &[Rgb565], _: &[u16]| {
            copy(part, width, usize::from(y - rows.start), c);
            Ok::<(), ()>(())
        }));
    }
    let colors = scene.colors;
    banded
        .render_mesh(
            scene.mesh,
            scene.model,
            scene.camera,
            scene.cull,
            &mut sinks,
            |f: &FaceInfo| colors[f.face as usize],
        )
        .map(|_| ())
        .map_err(|e| format!("{e:?}"))
}

fn report(
    o: &Options,
    mesh: &HostMesh,
    polygons: usize,
    (builds, scans): (Vec<Duration>, Vec<Duration>),
    banded: &BandedRenderer<Rgb565, Depth16>,
    per_band: Vec<Vec<(usize, Duration, Duration)>>,
    (shared, walls): (Vec<SharedSteps>, Vec<Duration>),
) {
    let (build, scan) = (median(builds), median(scans));
    println!(
        "{} ({} faces), {}x{}, cull {}, {} frames (median ms, wall clock)\n",
        o.path,
        mesh.face_count(),
        o.size.0,
        o.size.1,
        if o.cull == Cull::Back { "back" } else { "none" },
        o.frames
    );
    println!("| renderer | rows | polygons | build | prepare + scan | frame |");
    println!("|---|---|---:|---:|---:|---:|");
    println!(
        "| one thread | 0..{} | {polygons} | {build:.2} | {scan:.2} | {:.2} |",
        o.size.1,
        build + scan
    );
    println!(
        "| projecting the vertices, {} threads | | | {:.2} | | |",
        o.threads,
        median(shared.iter().map(|s| s.project).collect())
    );
    println!(
        "| sorting the faces into bands, {} threads | | | {:.2} | | |",
        o.threads,
        median(shared.iter().map(|s| s.sort_faces).collect())
    );
    for (k, (band, last)) in per_band.into_iter().zip(banded.last_frame()).enumerate() {
        let polygons = band.last().map_or(0, |b| b.0);
        let build = median(band.iter().map(|b| b.1).collect());
        let scan = median(band.iter().map(|b| b.2).collect());
        println!(
            "| band {k} of {} | {:?} | {polygons} | {build:.2} | {scan:.2} | {:.2} |",
            o.threads,
            last.rows,
            build + scan
        );
    }
    println!(
        "| {} threads, whole frame | | | | | {:.2} |",
        o.threads,
        median(walls)
    );
}

fn options(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        path: String::new(),
        size: (800, 600),
        cull: Cull::None,
        threads: 2,
        frames: 41,
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{a} needs a value"));
        match a.as_str() {
            "--size" => o.size = parse_size(value()?)?,
            "--cull" => {
                o.cull = match value()?.as_str() {
                    "none" => Cull::None,
                    "back" => Cull::Back,
                    s => return Err(format!("--cull: unknown '{s}' (none, back)")),
                }
            }
            "--threads" => {
                o.threads = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=64).contains(n))
                    .ok_or("--threads: expected 1 to 64")?
            }
            "--frames" => {
                o.frames = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=10_000).contains(n))
                    .ok_or("--frames: expected 1 to 10000")?
            }
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s => o.path = s.to_string(),
        }
    }
    if o.path.is_empty() {
        return Err("missing MODEL.obj".into());
    }
    Ok(o)
}

const USAGE: &str =
    "usage: bands MODEL.obj [--size WxH] [--cull none|back] [--threads N] [--frames N]
Where a frame drawn in bands on threads spends its time, next to one renderer on one thread; fails
if the banded frame differs from the single renderer's.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("bands", USAGE, move || run(&args))
}
