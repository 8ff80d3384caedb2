//! Where a frame's time goes, stage by stage, counted by valgrind's
//! callgrind (instructions, not seconds: the same on every run).
//!
//! ```sh
//! cargo build --release -p zline-lab --features profile --bin profile
//! valgrind --tool=callgrind --callgrind-out-file=cg.out \
//!     target/release/profile ../shared/meshes/stanford-bunny.obj --size 800x600 --frames 4
//! cargo run --release -p zline-lab --features profile --bin profile -- --report cg.out
//! ```
//!
//! The frame is the peers bench's `zline z24` row, as the README draws:
//! the reference view, each face's colour from `Shading::lambert()` in
//! the frame (`--table`: from a table made once, as the bench before
//! 2026-11-26 did), no culling (or `--cull back`), 24-bit depth (or
//! `--depth z16`), every row copied into an Rgb565 frame buffer. The
//! stages are functions the core and the front end keep out of line for
//! this purpose; `--report` reads a
//! callgrind file and prints each stage's share of the instructions spent
//! in the frames (loading the mesh excluded), as a Markdown table:
//!
//! | stage | functions (inclusive) |
//! |---|---|
//! | transform | `Draw::transform_vertex` |
//! | cull/clip | `Draw::clipped_part` |
//! | shade | `shade_front_face` |
//! | table building | `draw_mesh`, less the three above |
//! | sorting | `Tables::prepare` |
//! | polygon/edge activation | `ScanState::activate_*` |
//! | spans | `RowBuffers::fill`, `RowBuffers::fill_in_range` |
//! | sink | `profile::copy_row` |
//! | row upkeep | `scan_rows`, less activation, spans and sink |
//!
//! `--texture FILE.png` draws the peers bench's `zline textured z24` row
//! instead: the mesh read with `HostMesh::from_obj_smooth`, painted
//! perspective-correct from the texture (nearest texel, repeat, unlit);
//! `--gouraud` its `zline gouraud z24` row (Lambert per vertex, dithered);
//! `--report` then gives only the whole frame (`--report` stages are the
//! flat scan's). It prints the last frame's hash, so a change meant to
//! keep every pixel can be checked.
//!
//! Instructions are not time: a host also waits on memory and on
//! mispredicted branches. `--perf-report` reads a sampling profile of the
//! same frames instead and prints each stage's share of the samples, by
//! each function's own samples (perf cannot see the inlined stages
//! inclusive):
//!
//! ```sh
//! perf record -e cpu-clock -F 5000 -o perf.data \
//!     target/release/profile ../shared/meshes/stanford-bunny.obj --size 800x600 --frames 400
//! cargo run --release -p zline-lab --features profile --bin profile -- --perf-report perf.data
//! ```

use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::IntoStorage;
use zline::Mesh;
use zline::Shading;
use zline::host::{DEFAULT_CREASE_DEGREES, HostPaintedRenderer};
use zline::host::{HostMesh, host_renderer};
use zline::paint::{Gouraud, PaintMode, Textured};
use zline::{Camera, Cull, VertexCache, draw_mesh, reference_model};
use zline::{Depth16, Depth24, DepthFormat, FnSink, FrameBufferSink};
use zline_lab::cli::parse_size;
use zline_lab::cli::run_tool;
use zline_lab::cli::{help_requested, load_model};
use zline_lab::textures::Rgb565Texture;

/// Copies one finished row into the frame buffer (the sink stage).
#[inline(never)]
fn copy_row(frame: &mut [u16], width: usize, y: u16, colors: &[Rgb565]) {
    let row = &mut frame[usize::from(y) * width..][..width];
    for (out, c) in row.iter_mut().zip(colors) {
        *out = c.into_storage();
    }
}

fn frames<D: DepthFormat>(
    mesh: &HostMesh,
    size: (u16, u16),
    cull: Cull,
    count: usize,
    live_shading: bool,
) -> Result<(), String> {
    let caps = mesh.capacities(size.0);
    let black = Rgb565::new(0, 0, 0);
    let mut renderer =
        host_renderer::<Rgb565, D>(&caps, size.0, size.1, black).map_err(|e| e.to_string())?;
    let mut cache: Box<VertexCache<65536>> = Box::default();
    let model = reference_model(mesh, 30.0, 20.0).map_err(|e| e.to_string())?;
    let camera = Camera::reference(size.0, size.1);
    let shading = Shading::lambert();
    // `--table`: each face's Lambert colour, computed once (none is made
    // for live shading).
    let table_faces = if live_shading { 0 } else { mesh.face_count() };
    let table: Vec<Rgb565> = (0..table_faces)
        .map(|f| {
            Rgb565::from(shading.color(&zline::FaceInfo::new(
                f as u32,
                true,
                Default::default(),
                0.0,
            )))
        })
        .collect();
    let width = usize::from(size.0);
    let mut frame = vec![0u16; width * usize::from(size.1)];
    for _ in 0..count {
        renderer.clear();
        draw_mesh(
            &mut renderer,
            &mut *cache,
            mesh,
            &model,
            &camera,
            cull,
            |f| {
                if live_shading {
                    Rgb565::from(shading.color(f))
                } else {
                    table[f.face as usize]
                }
            },
        )
        .map_err(|e| e.to_string())?;
        renderer
            .render(&mut FnSink(|y: u16, colors: &[Rgb565], _: &[D::Value]| {
                copy_row(&mut frame, width, y, colors);
                Ok::<(), ()>(())
            }))
            .map_err(|e| format!("{e:?}"))?;
    }
    Ok(())
}

/// `count` painted frames of the mesh at `path` (read for smooth shading):
/// textured with the texture at `png` (`Some`), as the peers bench's
/// textured row draws, or Gouraud shaded (`None`), as its Gouraud row.
fn painted_frames(
    path: &str,
    png: Option<&str>,
    size: (u16, u16),
    cull: Cull,
    count: usize,
) -> Result<(), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    let mesh = HostMesh::from_obj_smooth(&bytes, DEFAULT_CREASE_DEGREES)
        .map_err(|e| format!("{path}: {e}"))?;
    let view = (&mesh, size, cull, count);
    match png {
        Some(png) => {
            let texels = Rgb565Texture::read(std::path::Path::new(png), 1)?;
            let mode = Textured::<Rgb565>::new(texels.texture()?);
            painted(view, mode, |v| v.tex_coord())
        }
        None => {
            let shading = Shading::lambert();
            painted(view, Gouraud::<Rgb565>::new(), |v| shading.vertex_color(v))
        }
    }
}

/// The frames of [`painted_frames`] with `mode`, each vertex's value from
/// `shade`; prints the last frame's FNV-1a hash, so that a change to the
/// painter meant to keep every pixel can be checked.
fn painted<M: PaintMode<Color = Rgb565>>(
    (mesh, size, cull, count): (&HostMesh, (u16, u16), Cull, usize),
    mode: M,
    shade: impl Fn(&zline::VertexInfo<'_>) -> M::Source,
) -> Result<(), String> {
    let black = Rgb565::new(0, 0, 0);
    let mut renderer =
        HostPaintedRenderer::<_, Depth24>::for_mesh(mesh, size.0, size.1, mode, black)
            .map_err(|e| e.to_string())?;
    let model = reference_model(mesh, 30.0, 20.0).map_err(|e| e.to_string())?;
    let camera = Camera::reference(size.0, size.1);
    let width = usize::from(size.0);
    let mut frame = vec![black; width * usize::from(size.1)];
    for _ in 0..count {
        renderer.clear();
        renderer
            .draw_mesh(mesh, &model, &camera, cull, &shade)
            .map_err(|e| e.to_string())?;
        renderer
            .render(&mut FrameBufferSink::new(&mut frame, width))
            .map_err(|e| format!("{e:?}"))?;
    }
    let hash = frame.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, c| {
        (h ^ u64::from(c.into_storage())).wrapping_mul(0x100_0000_01b3)
    });
    eprintln!("frame hash {hash:016x}");
    Ok(())
}

/// Inclusive instruction counts per function from `callgrind_annotate`.
fn inclusive(path: &str) -> Result<Vec<(u64, String)>, String> {
    let out = std::process::Command::new("callgrind_annotate")
        .args(["--inclusive=yes", "--threshold=100", path])
        .output()
        .map_err(|e| format!("callgrind_annotate: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    Ok(text
        .lines()
        .filter_map(|line| {
            let line = line.trim();
            let (count, rest) = line.split_once(' ')?;
            let count: u64 = count.replace(',', "").parse().ok()?;
            Some((count, rest.to_string()))
        })
        .collect())
}

fn report(path: &str) -> Result<(), String> {
    let rows = inclusive(path)?;
    // The largest inclusive count of a function whose name contains all
    // of `parts` (callgrind lists a function once per file it spans).
    let cost = |parts: &[&str]| -> u64 {
        rows.iter()
            .filter(|(_, name)| parts.iter().all(|p| name.contains(p)))
            .map(|(c, _)| *c)
            .max()
            .unwrap_or(0)
    };
    let transform = cost(&["Draw", "transform_vertex"]);
    let clip = cost(&["Draw", "clipped_part"]);
    let shade = cost(&["shade_front_face"]);
    let draw = cost(&["scene::faces::draw_mesh"]);
    let prepare = cost(&["Tables", "prepare"]);
    let activation = cost(&["ScanState", "activate_polygon"]);
    let edges = cost(&["ScanState", "activate_edges"]);
    let fill_in_range = cost(&["span::RowBuffers<C,D>::fill_in_range"]);
    let fill = rows
        .iter()
        .filter(|(_, name)| {
            name.contains("span::RowBuffers<C,D>::fill") && !name.contains("fill_in_range")
        })
        .map(|(c, _)| *c)
        .max()
        .unwrap_or(0);
    let spans = fill + fill_in_range;
    let sink = cost(&["profile::copy_row"]);
    let scan = cost(&["scan::scan_rows"]);
    let total = draw + prepare + scan;
    let stages = [
        ("transform", transform),
        ("cull/clip (clipped faces)", clip),
        ("shade (back-face test, Lambert)", shade),
        (
            "table building (per face: corners, outline, sample test)",
            draw.saturating_sub(transform + clip + shade),
        ),
        ("sorting (bucket sort, edge table)", prepare),
        ("polygon/edge activation", activation + edges),
        ("spans (depth test and write)", spans),
        ("sink (row copy)", sink),
        (
            "row upkeep (edge stepping, active tables)",
            scan.saturating_sub(activation + edges + spans + sink),
        ),
    ];
    println!("| stage | instructions | share |");
    println!("|---|---:|---:|");
    for (name, count) in stages {
        println!(
            "| {name} | {count} | {:.1} % |",
            100.0 * count as f64 / total.max(1) as f64
        );
    }
    println!("| **frames in all** | {total} | 100 % |");
    Ok(())
}

/// Each function's own share of the samples, in percent, from `perf
/// report`.
fn perf_self(path: &str) -> Result<Vec<(f64, String)>, String> {
    let out = std::process::Command::new("perf")
        .args([
            "report",
            "-i",
            path,
            "--no-children",
            "--sort",
            "symbol",
            "--stdio",
        ])
        .output()
        .map_err(|e| format!("perf report: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    Ok(text
        .lines()
        .filter_map(|line| {
            let (share, rest) = line.trim().split_once('%')?;
            let share: f64 = share.trim().parse().ok()?;
            let name = rest.trim().strip_prefix("[.]")?.trim();
            Some((share, format!("{name} ")))
        })
        .collect())
}

fn perf_report(path: &str) -> Result<(), String> {
    let rows = perf_self(path)?;
    let stages: [(&str, &[&str]); 7] = [
        ("transform", &["transform_vertex", "Frame::project"]),
        ("shade (back-face test, colour)", &["shade_front_face"]),
        (
            "table building (per face: corners, outline, sample test)",
            &[
                "offer_triangle",
                "::part ",
                "scene::faces::draw_mesh ",
                "face_of",
            ],
        ),
        (
            "sorting (bucket sort, edge table)",
            &["Tables<S>>::prepare", "radix_sort_by_row"],
        ),
        (
            "polygon/edge activation (one-row triangles drawn there)",
            &[
                "ScanState<C>>::activate_",
                "value_at_pixel",
                "RowBuffers<C,D>::fill ",
            ],
        ),
        ("spans (depth test and write)", &["fill_in_range"]),
        (
            "row upkeep (edge stepping, active tables, row clearing)",
            &[
                "scan_row ",
                "switch_triangle",
                "scan_rows",
                "clear_color_row",
                "fill_and_step",
            ],
        ),
    ];
    println!("| stage | share of the samples |");
    println!("|---|---:|");
    let mut staged = 0.0;
    for (name, keys) in stages {
        let share: f64 = rows
            .iter()
            .filter(|(_, symbol)| keys.iter().any(|k| symbol.contains(k)))
            .map(|(share, _)| share)
            .sum();
        staged += share;
        println!("| {name} | {share:.1} % |");
    }
    println!(
        "| the rest (the colour closure, the sink, loading the mesh) | {:.1} % |",
        100.0 - staged
    );
    Ok(())
}

fn run(args: &[String]) -> Result<(), String> {
    let (mut path, mut size, mut cull, mut count) = (None, (800, 600), Cull::None, 4);
    let (mut live_shading, mut z16, mut texture, mut gouraud) = (true, false, None, false);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{a} needs a value"));
        match a.as_str() {
            "--report" => return report(value()?),
            "--perf-report" => return perf_report(value()?),
            "--table" => live_shading = false,
            "--depth" => {
                z16 = match value()?.as_str() {
                    "z16" => true,
                    "z24" => false,
                    s => return Err(format!("--depth: unknown '{s}' (z16, z24)")),
                }
            }
            "--size" => size = parse_size(value()?)?,
            "--texture" => texture = Some(value()?.clone()),
            "--gouraud" => gouraud = true,
            "--cull" => {
                cull = match value()?.as_str() {
                    "none" => Cull::None,
                    "back" => Cull::Back,
                    s => return Err(format!("--cull: unknown '{s}' (none, back)")),
                }
            }
            "--frames" => {
                count = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=1000).contains(n))
                    .ok_or("--frames: expected 1 to 1000")?
            }
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s => path = Some(s.to_string()),
        }
    }
    let path = path.ok_or("missing MODEL.obj")?;
    if texture.is_some() || gouraud {
        return painted_frames(&path, texture.as_deref(), size, cull, count);
    }
    let mesh = load_model(&path)?;
    if z16 {
        frames::<Depth16>(&mesh, size, cull, count, live_shading)
    } else {
        frames::<Depth24>(&mesh, size, cull, count, live_shading)
    }
}

const USAGE: &str =
    "usage: profile MODEL.obj [--size WxH] [--cull none|back] [--depth z24|z16] [--frames N] [--table]
               [--texture FILE.png | --gouraud]
       profile --report CALLGRIND.OUT | profile --perf-report PERF.DATA
Draws frames for valgrind's callgrind or perf to profile (build with --features profile), or reports
each stage's share of a profile.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("profile", USAGE, move || run(&args))
}
