//! Speed, measured side by side in one run: for each mesh, the scanline
//! core with each depth format, with and without back-face culling, and
//! the float64 reference, timed in interleaved rounds (every configuration
//! once per round), so machine noise falls on all of them alike. Prints the
//! median frame time of each and its ratio to the first, as a Markdown
//! table.
//!
//! ```sh
//! cargo run --release --example bench -- [--size WxH] [--rounds N] MESH.obj...
//! ```
//!
//! A frame is the whole pipeline: clear, transform, cull, clip, project,
//! shade (Lambert), build the tables, scan every row into a frame buffer
//! on the host (the row sink). The view is the reference view (yaw 30,
//! pitch 20).

use std::process::ExitCode;
use std::time::Instant;

use zline::front::scene::{Camera, Cull, reference_model};
use zline::front::shade::Shading;
use zline::host::{load_model, parse_size, run_tool};
use zline::methods::{HostScanline, ReferenceFrame, ReferenceView};
use zline::{Depth16, Depth24};

/// One configuration to time.
#[derive(Clone, Copy)]
enum Config {
    Scanline { z24: bool, cull: Cull },
    Reference,
}

impl Config {
    fn name(self) -> &'static str {
        match self {
            Config::Scanline {
                z24: false,
                cull: Cull::None,
            } => "scanline z16",
            Config::Scanline {
                z24: true,
                cull: Cull::None,
            } => "scanline z24",
            Config::Scanline {
                z24: false,
                cull: Cull::Back,
            } => "scanline z16, back faces culled",
            Config::Scanline {
                z24: true,
                cull: Cull::Back,
            } => "scanline z24, back faces culled",
            Config::Reference => "float64 reference",
        }
    }
}

const CONFIGS: [Config; 5] = [
    Config::Scanline {
        z24: false,
        cull: Cull::None,
    },
    Config::Scanline {
        z24: true,
        cull: Cull::None,
    },
    Config::Scanline {
        z24: false,
        cull: Cull::Back,
    },
    Config::Scanline {
        z24: true,
        cull: Cull::Back,
    },
    Config::Reference,
];

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn run(args: &[String]) -> Result<(), String> {
    let (mut size, mut rounds, mut paths) = ((320u16, 240u16), 15usize, Vec::new());
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--size" => size = parse_size(it.next().ok_or("--size needs WxH")?)?,
            "--rounds" => {
                rounds = it
                    .next()
                    .and_then(|v| v.parse().ok())
                    .filter(|&n| n > 0)
                    .ok_or("bad --rounds")?
            }
            "--frames" => {
                return Err("unknown option --frames (the bench times rounds: --rounds N)".into());
            }
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s => paths.push(s.to_string()),
        }
    }
    if paths.is_empty() {
        return Err("usage: bench [--size WxH] [--rounds N] MESH.obj... (or shape:NAME)".into());
    }
    let mut z16 = HostScanline::<Depth16>::new(size.0, size.1).map_err(|e| e.to_string())?;
    let mut z24 = HostScanline::<Depth24>::new(size.0, size.1).map_err(|e| e.to_string())?;
    let camera = Camera::reference(size.0, size.1);
    let shading = Shading::lambert();
    println!(
        "{}x{}, median of {rounds} interleaved rounds (after one warm-up round)\n",
        size.0, size.1
    );
    println!("| mesh | faces | configuration | median ms | ratio to scanline z16 |");
    println!("|---|---|---|---|---|");
    for path in &paths {
        let mesh = load_model(path)?;
        let model = reference_model(&mesh, 30.0, 20.0).map_err(|e| format!("{path}: {e}"))?;
        let view = ReferenceView {
            width: usize::from(size.0),
            height: usize::from(size.1),
            yaw_deg: 30.0,
            pitch_deg: 20.0,
            cull_back: false,
        };
        let mut times: Vec<Vec<f64>> = vec![Vec::new(); CONFIGS.len()];
        for round in 0..=rounds {
            for (k, config) in CONFIGS.iter().enumerate() {
                let start = Instant::now();
                match *config {
                    Config::Scanline { z24: false, cull } => drop(
                        z16.render(&mesh, &model, &camera, cull, &shading)
                            .map_err(|e| e.to_string())?,
                    ),
                    Config::Scanline { z24: true, cull } => drop(
                        z24.render(&mesh, &model, &camera, cull, &shading)
                            .map_err(|e| e.to_string())?,
                    ),
                    Config::Reference => drop(ReferenceFrame::render(&mesh, &view)),
                }
                if round > 0 {
                    times[k].push(start.elapsed().as_secs_f64() * 1e3);
                }
            }
        }
        let base = median(times[0].clone());
        let name = std::path::Path::new(path)
            .file_name()
            .map_or(path.clone(), |n| n.to_string_lossy().into_owned());
        for (config, t) in CONFIGS.iter().zip(times) {
            let m = median(t);
            println!(
                "| {name} | {} | {} | {m:.2} | {:.2} |",
                mesh.face_starts.len(),
                config.name(),
                m / base
            );
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    run_tool("bench", "", move || run(&args))
}
