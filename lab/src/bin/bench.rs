//! Speed, measured side by side in one run: for each mesh, every method
//! asked for (each depth format of those that store depth), timed in
//! interleaved rounds (every configuration once per round), so machine
//! noise falls on all of them alike. Prints the median frame time of each,
//! its ratio to the first, and its memory, as a Markdown table.
//!
//! ```sh
//! cargo run --release -p zline-lab --bin bench -- [--size WxH] [--rounds N] [--cull none|back]
//!     [--method LIST] MESH.obj...
//! ```
//!
//! `LIST` is comma-separated methods (`scanline`, `zbuffer`, `bands:K`,
//! `interval`, `painter`, `reference`); all of them by default, bands at
//! 1, 8 and 32 rows.
//!
//! A frame is the whole pipeline: clear, transform, cull, clip, project,
//! shade (Lambert), build the tables, scan every row into a frame buffer
//! on the host (the row sink). The view is the reference view (yaw 30,
//! pitch 20).

use std::process::ExitCode;
use std::time::Instant;

use zline::Shading;
use zline::{Camera, Cull, reference_model};
use zline::{Depth16, Depth24};
use zline_lab::cli::parse_size;
use zline_lab::cli::run_tool;
use zline_lab::cli::{help_requested, load_model};
use zline_lab::methods::{Method, MethodRenderer, ReferenceView};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn run(args: &[String]) -> Result<(), String> {
    let (mut size, mut rounds, mut paths) = ((320u16, 240u16), 15usize, Vec::new());
    let (mut cull, mut methods) = (Cull::None, Method::ALL.to_vec());
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
            "--cull" => {
                cull = match it.next().map(String::as_str) {
                    Some("none") => Cull::None,
                    Some("back") => Cull::Back,
                    _ => return Err("--cull needs none or back".into()),
                }
            }
            "--method" => {
                methods = it
                    .next()
                    .ok_or("--method needs a list")?
                    .split(',')
                    .map(Method::parse)
                    .collect::<Result<_, _>>()?
            }
            "--frames" => {
                return Err("unknown option --frames (the bench times rounds: --rounds N)".into());
            }
            s if s.starts_with("--") => return Err(format!("unknown option {s}")),
            s => paths.push(s.to_string()),
        }
    }
    if paths.is_empty() {
        return Err("usage: bench [--size WxH] [--rounds N] [--cull none|back] [--method LIST] MESH.obj... (or shape:NAME)".into());
    }
    // Every method, and each depth format of those that store depth.
    let configs: Vec<(Method, bool)> = methods
        .iter()
        .flat_map(|&m| {
            if m.stores_depth() {
                vec![(m, false), (m, true)]
            } else {
                vec![(m, false)]
            }
        })
        .collect();
    let mut z16 = MethodRenderer::<Depth16>::new(size.0, size.1)?;
    let mut z24 = MethodRenderer::<Depth24>::new(size.0, size.1)?;
    let camera = Camera::reference(size.0, size.1);
    let shading = Shading::lambert();
    println!(
        "{}x{}, {}, median of {rounds} interleaved rounds (after one warm-up round)\n",
        size.0,
        size.1,
        if cull == Cull::Back {
            "back faces culled"
        } else {
            "no culling"
        }
    );
    println!("| mesh | faces | method | median ms | ratio | memory bytes |");
    println!("|---|---|---|---:|---:|---:|");
    for path in &paths {
        let mesh = load_model(path)?;
        let model = reference_model(&mesh, 30.0, 20.0).map_err(|e| format!("{path}: {e}"))?;
        let view = ReferenceView {
            width: usize::from(size.0),
            height: usize::from(size.1),
            yaw_deg: 30.0,
            pitch_deg: 20.0,
            cull_back: cull == Cull::Back,
        };
        let mut times: Vec<Vec<f64>> = vec![Vec::new(); configs.len()];
        let mut memory = vec![0usize; configs.len()];
        for round in 0..=rounds {
            for (k, &(method, deep)) in configs.iter().enumerate() {
                let start = Instant::now();
                let frame = if deep {
                    z24.render(method, &mesh, &model, &camera, cull, &shading, &view)?
                } else {
                    z16.render(method, &mesh, &model, &camera, cull, &shading, &view)?
                };
                if round > 0 {
                    times[k].push(start.elapsed().as_secs_f64() * 1e3);
                }
                memory[k] = frame.memory.total();
            }
        }
        let base = median(times[0].clone());
        let name = std::path::Path::new(path)
            .file_name()
            .map_or(path.clone(), |n| n.to_string_lossy().into_owned());
        for ((&(method, deep), t), bytes) in configs.iter().zip(times).zip(memory) {
            let m = median(t);
            let label = if method.stores_depth() {
                format!("{} {}", method.name(), if deep { "z24" } else { "z16" })
            } else {
                method.name()
            };
            println!(
                "| {name} | {} | {label} | {m:.2} | {:.2} | {bytes} |",
                mesh.face_starts.len(),
                m / base
            );
        }
    }
    Ok(())
}

const USAGE: &str = "usage: bench [--size WxH] [--rounds N] [--cull none|back] [--method LIST] MESH.obj... (or shape:NAME)
Speed of the hidden-surface methods side by side, in interleaved rounds: median frame time, ratio to
the first, memory. LIST: comma-separated scanline, zbuffer, bands:K, interval, painter, reference.";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("bench", USAGE, move || run(&args))
}
