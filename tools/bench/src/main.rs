//! `zline-bench`: zline against two peer rasterisers, embedded-3dgfx 0.7
//! and euc 0.5, drawing the same reference view (see [`view`]) of real
//! meshes, side by side, each as its users write it, shading included.
//!
//! For each mesh × size × cull it builds every renderer once, draws
//! untimed warm-up frames with each (at least one, for at least a second in
//! all), then times N interleaved rounds (each round draws one frame with
//! every renderer, in an order that rotates from round to round) by
//! per-thread CPU time, single-threaded. Nothing that depends on the
//! view's colours is prepared before timing: every renderer computes its
//! faces' Lambert colours inside its timed frame. It writes the median
//! and minimum to a CSV, prints them as a Markdown table with each
//! renderer's share of wrong pixels (pixels whose face differs from
//! zline's float64 `ReferenceFrame`, over the pixels the reference's
//! object covers), and reports progress on stderr.
//!
//! Rows (one renderer name per row kind): `zline z24`, `zline z16` (drawn
//! in place), `zline z24 drawtarget`, `zline z16 drawtarget` (through a
//! plain `DrawTarget`), `zline z24 target alone` (no rendering: that
//! `DrawTarget` taking the pixels the drawtarget rows send it, its own
//! share of their time), `embedded-3dgfx lit`, `embedded-3dgfx unlit`,
//! `embedded-3dgfx raster shared`, `euc`, and with `--threads N > 1`
//! `zline z24 N threads` (wall clock). Each row's timed region is printed
//! with the table.
//!
//! With `--shading gouraud|textured|all` (the default, `flat`, is the
//! rows above alone), smooth rows over the mesh read with
//! `HostMesh::from_obj_smooth(.., DEFAULT_CREASE_DEGREES)`, every one
//! lighting or sampling inside its timed frame: `zline gouraud z24`,
//! `embedded-3dgfx gouraud` and `euc gouraud` (Lambert per vertex from the
//! smooth mesh's vertex normals, interpolated), and, on meshes with a
//! `NAME_texture.png` beside `NAME.obj`, `zline textured z24`,
//! `embedded-3dgfx textured` and `euc textured` (nearest texel,
//! perspective-correct).
//!
//! Ratio ([`ratio_base`]): a row's median over the median of `zline z24`
//! in the same mesh, size and cull, except a `drawtarget` row, whose base
//! is zline in place with the same depth, a Gouraud row, whose base is
//! `zline gouraud z24`, and a textured row, whose base is `zline textured
//! z24`. Above 1.00, zline is faster.
//!
//! Build: `cargo bench-peers` builds with the root `Cargo.toml`'s
//! `[profile.peers]` (release with fat LTO and one codegen unit for every
//! crate); the report states the profile the binary was built with.
//!
//! ```sh
//! cargo bench-peers --quick
//! cargo run --profile peers -p zline-bench -- --quick ../shared/meshes
//! ```

mod cli;
mod framebuffer;
mod peers;
mod png;
mod renderer;
mod report;
mod timing;
mod view;
mod zline_painted;
mod zline_renderer;

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb565;
use zline::paint::{Gouraud, Textured};
use zline::{Depth16, Depth24};
use zline_lab::methods::ReferenceFrame;

use crate::cli::Options;
use crate::peers::embedded_3dgfx::{
    Embedded3dgfxRasterRenderer, Embedded3dgfxRenderer, MeshData, Mode,
};
use crate::peers::euc::{EucPaintedRenderer, EucRenderer, Paint};
use crate::renderer::Renderer;
use crate::report::Row;
use crate::view::{BACKGROUND, Scene, SmoothScene, View};
use crate::zline_painted::ZlinePaintedRenderer;
use crate::zline_renderer::{Output, ZlineBandsRenderer, ZlineRenderer};

/// Stack for the worker thread: zline's host renderer is built on the
/// stack (about 20 MB) before it moves to the heap.
const STACK_BYTES: usize = 512 << 20;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let worker = std::thread::Builder::new()
        .name("zline-bench".into())
        .stack_size(STACK_BYTES)
        .spawn(move || run(&args));
    match worker.map(|w| w.join()) {
        Ok(Ok(Ok(()))) => ExitCode::SUCCESS,
        Ok(Ok(Err(message))) => {
            eprintln!("zline-bench: {message}");
            eprintln!("{}", cli::USAGE.lines().next().unwrap_or_default());
            ExitCode::from(2)
        }
        Ok(Err(_)) => {
            eprintln!("zline-bench: internal failure (panic)");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("zline-bench: cannot start worker thread: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &[String]) -> Result<(), String> {
    let options = cli::parse(args)?;
    if options.help {
        return say(cli::USAGE);
    }
    let files = mesh_files(&options)?;
    let scenes = files
        .iter()
        .map(|path| Scene::load(path))
        .collect::<Result<Vec<_>, _>>()?;
    // The smooth meshes (and textures) for the Gouraud and textured rows.
    let smooth = if options.shading.smooth() {
        files
            .iter()
            .zip(&scenes)
            .map(|(path, scene)| SmoothScene::load(path, scene).map(Some))
            .collect::<Result<Vec<_>, _>>()?
    } else {
        vec![None; scenes.len()]
    };
    report::prepare_output(&options.out)?;
    say(&format!(
        "# zline vs embedded-3dgfx 0.7 and euc 0.5, shading timed\n\n\
         - machine: {}\n\
         - date: {}\n\
         - build: {}\n\
         - view: yaw {}°, pitch {}°; flat two-sided Lambert as zline's `Shading::lambert()`, \
         computed inside every timed frame{}\n\
         - timing: median (and min) of {} interleaved rounds per configuration after a second \
         of warm-up, per-thread CPU time, single-threaded (the `threads` row: wall clock)\n\
         - ratio: a row's median / the median of `zline z24` in the same configuration \
         (a `drawtarget` row: / zline in place with its depth{}); above 1.00 zline is faster\n\
         - wrong faces: pixels whose face differs from the float64 reference's, as a share of \
         the pixels the reference's object covers (not of the frame)\n",
        report::machine(),
        zline_lab::machine::now_utc(),
        report::build(),
        options.yaw,
        options.pitch,
        smooth_note(&options),
        options.rounds,
        if options.shading.smooth() {
            "; a `gouraud` row: / `zline gouraud z24`; a `textured` row: / `zline textured z24`"
        } else {
            ""
        }
    ))?;

    let mut rows = Vec::new();
    let mut timed: Vec<TimedRegion> = Vec::new();
    for (i, scene) in scenes.iter().enumerate() {
        eprintln!(
            "[{}/{}] {}: {} vertices, {} faces, {} triangles",
            i + 1,
            scenes.len(),
            scene.name,
            scene.mesh.positions.len(),
            scene.face_count(),
            scene.triangles.len()
        );
        let e3d = MeshData::new(scene);
        let smooth = smooth[i].as_ref();
        let e3d_smooth = smooth.map(MeshData::smooth);
        let painted = smooth.zip(e3d_smooth.as_ref());
        for &(width, height) in &options.sizes {
            for &cull in &options.culls {
                let view = View {
                    width,
                    height,
                    yaw_deg: options.yaw,
                    pitch_deg: options.pitch,
                    cull,
                };
                let (done, regions) = bench_view(scene, &e3d, painted, &view, &options)?;
                rows.extend(done);
                for region in regions {
                    if !timed.iter().any(|(name, _)| *name == region.0) {
                        timed.push(region);
                    }
                }
            }
        }
    }

    report::write_csv(&options.out, &rows)?;
    let wrong_out = report::wrong_faces_path(&options.out);
    report::write_wrong_csv(&wrong_out, &rows)?;
    say(&report::timed_regions(&timed))?;
    say(&report::markdown(&rows))?;
    say(&report::checks(&rows))?;
    eprintln!(
        "wrote {} and {}",
        options.out.display(),
        wrong_out.display()
    );
    Ok(())
}

/// Prints `text` and a newline to stdout; a closed pipe is not an error
/// (the CSV is still written).
fn say(text: &str) -> Result<(), String> {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(format!("stdout: {e}")),
        _ => Ok(()),
    }
}

/// The mesh files named on the command line: files as given, directories
/// as their `.obj` files sorted by name; with `--quick`, the 3 smallest
/// files.
fn mesh_files(options: &Options) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    for input in &options.inputs {
        if input.is_dir() {
            let entries =
                std::fs::read_dir(input).map_err(|e| format!("{}: {e}", input.display()))?;
            let mut found: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.is_file() && p.extension().is_some_and(|x| x.eq_ignore_ascii_case("obj"))
                })
                .collect();
            if found.is_empty() {
                return Err(format!("{}: no .obj files", input.display()));
            }
            found.sort();
            files.extend(found);
        } else if input.is_file() {
            files.push(input.clone());
        } else {
            return Err(format!("{}: no such file or directory", input.display()));
        }
    }
    if options.quick {
        let mut sized = files
            .into_iter()
            .map(|p| {
                let len = std::fs::metadata(&p)
                    .map_err(|e| format!("{}: {e}", p.display()))?
                    .len();
                Ok((len, p))
            })
            .collect::<Result<Vec<_>, String>>()?;
        sized.sort();
        files = sized.into_iter().take(3).map(|(_, p)| p).collect();
    }
    Ok(files)
}

/// Least untimed rendering per configuration before its timed rounds.
const WARM_UP: std::time::Duration = std::time::Duration::from_millis(1000);

/// A renderer's name and what its timed frame does.
type TimedRegion = (String, String);

/// The `view:` line's words on the smooth rows, when they run.
fn smooth_note(options: &Options) -> String {
    let rows = options.shading;
    let mut note = String::new();
    if rows.gouraud {
        note.push_str(
            "; Gouraud rows: one-sided Lambert per vertex from the vertex normals of \
             `HostMesh::from_obj_smooth(.., DEFAULT_CREASE_DEGREES)` (same light as \
             `Shading::lambert()`; embedded-3dgfx: its own rule), interpolated, computed inside \
             every timed frame",
        );
    }
    if rows.textured {
        note.push_str(
            "; textured rows (meshes with `NAME_texture.png` only): unlit, nearest texel, \
             repeating, perspective-correct",
        );
    }
    if rows.smooth() {
        note.push_str(
            "; zline's Gouraud and textured rows' wrong faces: the face ids of zline's flat scan \
             of the same smooth mesh (its painted rows hold slots, not face ids)",
        );
    }
    if !rows.flat {
        note.push_str("; flat rows left out (`--shading`)");
    }
    note
}

/// The kind of shading a row draws, from its name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Flat Lambert per face.
    Flat,
    /// Lambert per vertex, interpolated.
    Gouraud,
    /// A texture.
    Textured,
}

/// A row's kind: its name says `gouraud` or `textured`, or it is flat.
pub fn kind(renderer: &str) -> Kind {
    if renderer.contains(" gouraud") {
        Kind::Gouraud
    } else if renderer.contains(" textured") {
        Kind::Textured
    } else {
        Kind::Flat
    }
}

/// The row a row's ratio divides by: zline in place with the same depth
/// for a `drawtarget` row, `zline gouraud z24` for a Gouraud row, `zline
/// textured z24` for a textured row, `zline z24` for every other.
pub fn ratio_base(renderer: &str) -> &'static str {
    match (renderer, kind(renderer)) {
        ("zline z16 drawtarget", _) => "zline z16",
        (_, Kind::Gouraud) => "zline gouraud z24",
        (_, Kind::Textured) => "zline textured z24",
        (_, Kind::Flat) => "zline z24",
    }
}

/// Rows whose frame must equal another row's, pixel for pixel.
fn same_frame_as(renderer: &str) -> Option<&'static str> {
    match renderer {
        "zline z16 drawtarget" => Some("zline z16"),
        "zline z24 drawtarget" => Some("zline z24"),
        "zline z24 target alone" => Some("zline z24"),
        r if r.starts_with("zline z24 ") && r.ends_with(" threads") => Some("zline z24"),
        _ => None,
    }
}

/// Builds every renderer for one view, times them, and measures their
/// face ids against the reference. Returns the rows and each renderer's
/// (name, timed region).
fn bench_view<'a>(
    scene: &'a Scene,
    e3d: &'a MeshData<'a>,
    painted: Option<(&'a SmoothScene, &'a MeshData<'a>)>,
    view: &View,
    options: &Options,
) -> Result<(Vec<Row>, Vec<TimedRegion>), String> {
    let label = format!("{} {} {}", scene.name, view.size_label(), view.cull.name());
    eprintln!("  {label}: reference");
    let reference = ReferenceFrame::render(&scene.mesh, &view.reference());

    let rows = options.shading;
    let mut renderers: Vec<Box<dyn Renderer + 'a>> = Vec::new();
    if rows.flat {
        renderers.extend(flat_renderers(scene, e3d, view)?);
    }
    if rows.flat && options.threads > 1 && usize::from(view.height) >= options.threads {
        renderers.push(Box::new(ZlineBandsRenderer::new(
            scene,
            view,
            options.threads,
        )?));
    }
    if let Some((smooth, e3d_smooth)) = painted {
        let s = &smooth.scene;
        if rows.gouraud {
            renderers.push(Box::new(ZlinePaintedRenderer::new(
                s,
                view,
                Gouraud::<Rgb565>::new(),
            )?));
            renderers.push(Box::new(Embedded3dgfxRenderer::new(
                e3d_smooth,
                view,
                Mode::Gouraud,
            )?));
            renderers.push(Box::new(EucPaintedRenderer::new(s, view, Paint::Gouraud)?));
        }
        if let (true, Some(texture)) = (rows.textured, &smooth.texture) {
            let zline_texture = texture.texture()?;
            renderers.push(Box::new(ZlinePaintedRenderer::new(
                s,
                view,
                Textured::<Rgb565>::new(zline_texture),
            )?));
            if e3d_smooth.has_texture() {
                renderers.push(Box::new(Embedded3dgfxRenderer::new(
                    e3d_smooth,
                    view,
                    Mode::Textured,
                )?));
            } else {
                eprintln!(
                    "  {label}: embedded-3dgfx textured left out: its texture is not a power of \
                     two a side"
                );
            }
            let (w, h) = (usize::from(texture.width), usize::from(texture.height));
            renderers.push(Box::new(EucPaintedRenderer::new(
                s,
                view,
                Paint::Textured(&texture.texels, w, h),
            )?));
        }
    }
    if renderers.is_empty() {
        eprintln!("  {label}: no rows (no texture for --shading textured)");
        return Ok((Vec::new(), Vec::new()));
    }
    // Warm-up, untimed: every renderer at least once, and for at least
    // WARM_UP in all. On this shared machine the first configurations
    // after loading the meshes measured up to 45 % slow after a single
    // warm-up frame, and still after 100 ms; after a second they did not.
    let warm_up = std::time::Instant::now();
    loop {
        for r in &mut renderers {
            r.render()?;
        }
        if warm_up.elapsed() >= WARM_UP {
            break;
        }
    }
    let n = renderers.len();
    let mut times = vec![Vec::with_capacity(options.rounds); n];
    for round in 0..options.rounds {
        for k in 0..n {
            let which = (round + k) % n;
            let renderer = &mut renderers[which];
            let time = if renderer.wall_clock() {
                timing::wall_ms(|| renderer.render())?
            } else {
                timing::time_ms(|| renderer.render())?
            };
            times[which].push(time);
        }
    }
    let stats: Vec<(f64, f64)> = times.iter().map(|t| timing::median_min(t)).collect();
    let names: Vec<String> = renderers.iter().map(|r| r.name().to_string()).collect();
    let index = |name: &str| {
        names
            .iter()
            .position(|r| r == name)
            .ok_or_else(|| format!("{label}: no renderer {name}"))
    };
    // Rows drawn through another sink or on threads must draw the same
    // frame as zline in place, pixel for pixel.
    for other in &renderers {
        if let Some(base) = same_frame_as(other.name())
            && other.rgb565() != renderers[index(base)?].rgb565()
        {
            return Err(format!(
                "{label}: {} drew another frame than {base}",
                other.name()
            ));
        }
    }

    let object_pixels = reference.ids.iter().filter(|&&id| id != BACKGROUND).count();
    let mut rows = Vec::with_capacity(n);
    let mut summary = Vec::with_capacity(n);
    for k in 0..n {
        let (median_ms, min_ms) = stats[k];
        let base = stats[index(ratio_base(&names[k]))?].0;
        let renderer = &mut renderers[k];
        let wrong = match renderer.face_ids()? {
            Some(ids) => Some(wrong_fraction(&ids, &reference.ids, object_pixels)?),
            None => None,
        };
        if let Some(dir) = &options.dump {
            dump(dir, &label, renderer.name(), view, &renderer.rgb565())?;
        }
        summary.push(format!("{} {median_ms:.2} ms", renderer.name()));
        rows.push(Row {
            mesh: scene.name.clone(),
            size: view.size_label(),
            cull: view.cull.name().into(),
            renderer: renderer.name().into(),
            median_ms,
            min_ms,
            ratio: median_ms / base,
            wrong,
            object_pixels,
        });
    }
    if let Some(dir) = &options.dump {
        let colors = scene.face_colors(view);
        let frame: Vec<u16> = reference
            .ids
            .iter()
            .map(|&id| colors.get(id as usize).copied().unwrap_or(0))
            .collect();
        dump(dir, &label, "reference", view, &frame)?;
    }
    eprintln!("  {label}: {}", summary.join(", "));
    let regions = renderers
        .iter()
        .map(|r| (r.name().to_string(), r.timed_region()))
        .collect();
    Ok((rows, regions))
}

/// Today's flat rows, in their order: zline in place and through a
/// `DrawTarget` at both depths, that `DrawTarget` alone taking what it is
/// sent, embedded-3dgfx lit, unlit and its rasteriser fed shared vertices,
/// euc.
fn flat_renderers<'a>(
    scene: &'a Scene,
    e3d: &'a MeshData<'a>,
    view: &View,
) -> Result<Vec<Box<dyn Renderer + 'a>>, String> {
    Ok(vec![
        Box::new(ZlineRenderer::<Depth24>::new(scene, view, Output::InPlace)?),
        Box::new(ZlineRenderer::<Depth16>::new(scene, view, Output::InPlace)?),
        Box::new(ZlineRenderer::<Depth24>::new(
            scene,
            view,
            Output::DrawTarget,
        )?),
        Box::new(ZlineRenderer::<Depth16>::new(
            scene,
            view,
            Output::DrawTarget,
        )?),
        Box::new(ZlineRenderer::<Depth24>::new(
            scene,
            view,
            Output::TargetAlone,
        )?),
        Box::new(Embedded3dgfxRenderer::new(e3d, view, Mode::Lit)?),
        Box::new(Embedded3dgfxRenderer::new(e3d, view, Mode::Unlit)?),
        Box::new(Embedded3dgfxRasterRenderer::new(e3d, view)),
        Box::new(EucRenderer::new(scene, view)?),
    ])
}

/// Pixels whose face id differs from the reference's (anywhere in the
/// frame: a face drawn over the background counts too), over the pixels
/// the reference's object covers (`object_pixels`; 1 when it covers
/// none).
fn wrong_fraction(ids: &[u32], reference: &[u32], object_pixels: usize) -> Result<f64, String> {
    if ids.len() != reference.len() || ids.is_empty() {
        return Err(format!(
            "face ids: {} pixels, reference {}",
            ids.len(),
            reference.len()
        ));
    }
    let wrong = ids.iter().zip(reference).filter(|(a, b)| a != b).count();
    Ok(wrong as f64 / object_pixels.max(1) as f64)
}

/// Writes a frame as PNG, `DIR/LABEL-RENDERER.png` (spaces as `-`).
fn dump(
    dir: &Path,
    label: &str,
    renderer: &str,
    view: &View,
    rgb565: &[u16],
) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let path = dir.join(format!(
        "{}-{}.png",
        label.replace(' ', "-"),
        renderer.replace(' ', "-")
    ));
    let rgb: Vec<[u8; 3]> = rgb565.iter().map(|&p| framebuffer::rgb888(p)).collect();
    let bytes = png::encode(u32::from(view.width), u32::from(view.height), &rgb);
    std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}
