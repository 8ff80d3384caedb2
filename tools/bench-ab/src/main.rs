//! `zline-bench-ab`: zline today against the code of commit c6aebe4, in
//! one run, on one frame (by default the Stanford bunny at 800x600
//! without culling, z24, Lambert timed: issue 30's A/B).
//!
//! Each side is driven as its users write it with its own API, building
//! its renderer, model matrix and camera once, and each timed frame doing:
//!
//! * today (`zline`): `renderer.clear()`, `let light =
//!   Shading::lambert();`, `renderer.draw_mesh(&mesh, &model, &camera,
//!   cull, |f| light.color(f).into())`, `renderer.render(&mut
//!   FrameBufferSink::new(&mut frame, w))` with a
//!   `HostRenderer::<Rgb565, Depth24>::for_mesh` renderer (its README);
//! * c6aebe4 (`zline_c6aebe4`): `renderer.clear()`, `let light =
//!   Shading::lambert();`, `draw_mesh(&mut renderer, &mut cache, &mesh,
//!   &model, &camera, cull, |f| Rgb565::from(light.color(f)))`,
//!   `renderer.render(&mut FrameBufferSink::new(&mut frame, w))` with a
//!   `host_renderer::<Rgb565, Depth24>(&mesh.capacities(w), ..)` renderer
//!   and a boxed `VertexCache<65536>` (its README and its peers bench).
//!
//! Both draw every pixel of every row in place into a `Vec<Rgb565>`
//! frame (background included, so no frame clear). After a second of
//! untimed warm-up, rounds alternate which side goes first; each frame is
//! timed by the thread's CPU time, single-threaded. It prints both
//! medians and minimums, whether the two frames are the same pixels, and
//! a last line
//!
//! ```text
//! ab: mesh=stanford-bunny size=800x600 cull=none depth=z24 old_ms=.. new_ms=.. ratio=..
//! ```
//!
//! with `ratio = old_ms / new_ms` (above 1.00 today's code is faster;
//! issue 30 asks for at least 2.00).

use std::process::ExitCode;

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zline_c6aebe4 as old;

// The peers bench's timing, the same file: thread CPU time and medians.
#[path = "../../bench/src/timing.rs"]
#[allow(dead_code)] // (its wall-clock timer is the bench's alone)
mod timing;
use timing::{median_min, time_ms};

const USAGE: &str = "\
usage: zline-bench-ab [MESH.obj] [--size WxH] [--cull none|back] [--rounds N]

Times zline (this repository) against zline at commit c6aebe4 (extracted
into target/ab/c6aebe4 by tools/bench-ab/run.sh) drawing the same frame,
Lambert shading timed, 24-bit depth, rows drawn in place, in interleaved
rounds by per-thread CPU time; prints the medians and their ratio
(old / new).

  MESH.obj       [../shared/meshes/stanford-bunny.obj]
  --size WxH     frame size [800x600]
  --cull MODE    none or back [none]
  --rounds N     timed rounds, after a second of untimed warm-up [41]";

/// The commit the old side was built from.
const OLD_COMMIT: &str = "c6aebe4";

struct Options {
    mesh: std::path::PathBuf,
    width: u16,
    height: u16,
    cull_back: bool,
    rounds: usize,
}

fn parse(args: &[String]) -> Result<Option<Options>, String> {
    let mut o = Options {
        mesh: "../shared/meshes/stanford-bunny.obj".into(),
        width: 800,
        height: 600,
        cull_back: false,
        rounds: 41,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "-h" | "--help" => return Ok(None),
            "--size" => {
                let s = value()?;
                let bad = || format!("--size: expected WxH, each 1 to 4096, got '{s}'");
                let (w, h) = s.split_once('x').ok_or_else(bad)?;
                let side = |v: &str| v.parse::<u16>().ok().filter(|n| (1..=4096).contains(n));
                o.width = side(w).ok_or_else(bad)?;
                o.height = side(h).ok_or_else(bad)?;
            }
            "--cull" => {
                o.cull_back = match value()?.as_str() {
                    "none" => false,
                    "back" => true,
                    s => return Err(format!("--cull: expected none or back, got '{s}'")),
                }
            }
            "--rounds" => {
                o.rounds = value()?
                    .parse()
                    .ok()
                    .filter(|n| (1..=100_000).contains(n))
                    .ok_or("--rounds: expected 1 to 100000")?
            }
            s if s.starts_with('-') && s.len() > 1 => return Err(format!("unknown option {s}")),
            s => o.mesh = s.into(),
        }
    }
    Ok(Some(o))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match parse(&args).and_then(|o| match o {
        None => {
            println!("{USAGE}");
            Ok(())
        }
        Some(o) => run(&o),
    }) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("zline-bench-ab: {e}");
            ExitCode::from(2)
        }
    }
}

/// One side of the A/B: draws one frame per call.
trait Side {
    fn frame(&mut self) -> Result<(), String>;
    fn pixels(&self) -> &[Rgb565];
}

/// Today's zline, as its README draws an OBJ file.
struct Today {
    mesh: zline::host::HostMesh,
    renderer: zline::host::HostRenderer<Rgb565, zline::Depth24>,
    model: zline::Mat4,
    camera: zline::Camera,
    cull: zline::Cull,
    frame: Vec<Rgb565>,
    width: usize,
}

impl Today {
    fn new(bytes: &[u8], o: &Options) -> Result<Self, String> {
        let e = |e: &dyn std::fmt::Display| format!("zline: {e}");
        let mesh = zline::host::HostMesh::from_obj(bytes).map_err(|x| e(&x))?;
        let renderer = zline::host::HostRenderer::<Rgb565, zline::Depth24>::for_mesh(
            &mesh,
            o.width,
            o.height,
            Rgb565::BLACK,
        )
        .map_err(|x| e(&x))?;
        let model = zline::reference_model(&mesh, 30.0, 20.0).map_err(|x| e(&x))?;
        Ok(Self {
            mesh,
            renderer,
            model,
            camera: zline::Camera::reference(o.width, o.height),
            cull: if o.cull_back {
                zline::Cull::Back
            } else {
                zline::Cull::None
            },
            frame: vec![Rgb565::BLACK; usize::from(o.width) * usize::from(o.height)],
            width: usize::from(o.width),
        })
    }
}

impl Side for Today {
    fn frame(&mut self) -> Result<(), String> {
        self.renderer.clear();
        let light = zline::Shading::lambert();
        self.renderer
            .draw_mesh(&self.mesh, &self.model, &self.camera, self.cull, |f| {
                light.color(f).into()
            })
            .map_err(|e| format!("zline: {e}"))?;
        self.renderer
            .render(&mut zline::FrameBufferSink::new(
                &mut self.frame,
                self.width,
            ))
            .map_err(|e| format!("zline: {e:?}"))?;
        Ok(())
    }

    fn pixels(&self) -> &[Rgb565] {
        &self.frame
    }
}

/// zline at c6aebe4, as its README and its peers bench drew a mesh.
struct Old {
    mesh: old::host::HostMesh,
    renderer:
        old::Renderer<old::host::TableVecs<Rgb565>, old::host::ScanVecs<Rgb565, old::Depth24>>,
    cache: Box<old::front::scene::VertexCache<65536>>,
    model: old::front::geometry::Mat4,
    camera: old::front::scene::Camera,
    cull: old::front::scene::Cull,
    frame: Vec<Rgb565>,
    width: usize,
}

impl Old {
    fn new(bytes: &[u8], o: &Options) -> Result<Self, String> {
        let e = |e: &dyn std::fmt::Display| format!("zline {OLD_COMMIT}: {e}");
        let mesh = old::host::HostMesh::from_obj(bytes).map_err(|x| e(&x))?;
        let renderer = old::host::host_renderer::<Rgb565, old::Depth24>(
            &mesh.capacities(o.width),
            o.width,
            o.height,
            Rgb565::BLACK,
        )
        .map_err(|x| e(&x))?;
        let model = old::front::scene::reference_model(&mesh, 30.0, 20.0).map_err(|x| e(&x))?;
        Ok(Self {
            mesh,
            renderer,
            cache: Box::default(),
            model,
            camera: old::front::scene::Camera::reference(o.width, o.height),
            cull: if o.cull_back {
                old::front::scene::Cull::Back
            } else {
                old::front::scene::Cull::None
            },
            frame: vec![Rgb565::BLACK; usize::from(o.width) * usize::from(o.height)],
            width: usize::from(o.width),
        })
    }
}

impl Side for Old {
    fn frame(&mut self) -> Result<(), String> {
        self.renderer.clear();
        let light = old::front::shade::Shading::lambert();
        old::front::scene::draw_mesh(
            &mut self.renderer,
            &mut *self.cache,
            &self.mesh,
            &self.model,
            &self.camera,
            self.cull,
            |f| Rgb565::from(light.color(f)),
        )
        .map_err(|e| format!("zline {OLD_COMMIT}: {e}"))?;
        self.renderer
            .render(&mut old::FrameBufferSink::new(&mut self.frame, self.width))
            .map_err(|e| format!("zline {OLD_COMMIT}: {e:?}"))?;
        Ok(())
    }

    fn pixels(&self) -> &[Rgb565] {
        &self.frame
    }
}

fn run(o: &Options) -> Result<(), String> {
    let shown = o.mesh.display();
    let bytes = std::fs::read(&o.mesh).map_err(|e| format!("{shown}: {e}"))?;
    let name = o
        .mesh
        .file_stem()
        .map_or_else(|| shown.to_string(), |s| s.to_string_lossy().into_owned());
    let mut sides: [Box<dyn Side>; 2] = [
        Box::new(Old::new(&bytes, o)?),
        Box::new(Today::new(&bytes, o)?),
    ];
    let warm_up = std::time::Instant::now();
    while warm_up.elapsed() < std::time::Duration::from_secs(1) {
        for side in &mut sides {
            side.frame()?;
        }
    }
    let mut times = [Vec::new(), Vec::new()];
    for round in 0..o.rounds {
        for k in 0..2 {
            let which = (round + k) % 2;
            times[which].push(time_ms(|| sides[which].frame())?);
        }
    }
    let [(old_ms, old_min), (new_ms, new_min)] = [median_min(&times[0]), median_min(&times[1])];
    let differing = sides[0]
        .pixels()
        .iter()
        .zip(sides[1].pixels())
        .filter(|(a, b)| a != b)
        .count();
    let (size, cull) = (
        format!("{}x{}", o.width, o.height),
        if o.cull_back { "back" } else { "none" },
    );
    println!("# A/B: zline today against zline at {OLD_COMMIT}, one run");
    println!();
    let (model, cpus) = zline_lab::machine::cpu();
    println!("- machine: {model}, {cpus} cores");
    println!("- date: {}", zline_lab::machine::now_utc());
    println!(
        "- build: {} (tools/bench-ab/Cargo.toml [profile.release]: fat LTO, one codegen unit for every crate)",
        if cfg!(debug_assertions) {
            "debug assertions ON: not the release profile"
        } else {
            "release"
        }
    );
    println!(
        "- frame: {name} {size}, cull {cull}, z24, Lambert (`Shading::lambert()`) inside the timed frame, rows in place"
    );
    println!(
        "- timing: median (and min) of {} interleaved rounds after a second of warm-up, per-thread CPU time, single-threaded",
        o.rounds
    );
    println!(
        "- frames: {}",
        if differing == 0 {
            "the same pixels".to_string()
        } else {
            format!("{differing} pixels differ")
        }
    );
    println!();
    println!("| code | median ms | min ms |");
    println!("|---|---:|---:|");
    println!("| zline {OLD_COMMIT} | {old_ms:.3} | {old_min:.3} |");
    println!("| zline today | {new_ms:.3} | {new_min:.3} |");
    println!();
    println!("ratio = old_ms / new_ms (above 1.00 today's code is faster)");
    println!(
        "ab: mesh={name} size={size} cull={cull} depth=z24 old_ms={old_ms:.3} new_ms={new_ms:.3} ratio={:.2}",
        old_ms / new_ms
    );
    Ok(())
}
