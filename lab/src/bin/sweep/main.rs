//! The methods side by side, charted: speed against accuracy, speed
//! against polygon count and resolution, memory against resolution.
//!
//! ```sh
//! cargo bench-peers                                  # optional: the peers' points
//! cargo run --release -p zline-lab --features charts --bin sweep                # writes docs/charts
//! cargo run --release -p zline-lab --features charts --bin sweep -- --quick     # CI's short run, to target/sweep-quick
//! ```
//!
//! Options: `--out DIR`, `--meshes DIR` (`../shared/meshes`), `--rounds N`
//! (11; 1 with `--quick`), `--peers FILE` (`target/bench/peers.csv`).
//!
//! Every frame is the whole pipeline (clear, transform, project, Lambert,
//! tables, the method, rows into a host frame) at the reference view (yaw
//! 30, pitch 20, no culling). Times are medians of interleaved rounds
//! (every configuration of a scene once per round, after one warm-up
//! round), wall-clock on one thread. Memory is what each method keeps for
//! the frame with Rgb565 colour ([`zline_lab::methods::Memory`]).
//!
//! It writes, to the output folder, one SVG and one CSV per chart:
//! `accuracy` (time against wrong-face pixels, every method and depth
//! format, the peers, the Pareto front), `polygons` (time against polygon
//! count: UV spheres of 100, 2,500 and 60,000 triangles and the bunny, at
//! 240x240 and 800x600), `resolution` (time against frame size for spot)
//! and `memory` (bytes against frame size, with the RP2040's 264 KB), and
//! `machine.txt` (machine, date, command). Progress goes to stderr.

mod chart;
mod measure;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use chart::{Panel, Point, Series};
use measure::{Config, Sample, Scene};
use plotters::chart::SeriesLabelPosition;
use zline_lab::cli::run_tool;
use zline_lab::cli::{help_requested, load_model};
use zline_lab::methods::Method;

struct Options {
    quick: bool,
    out: PathBuf,
    meshes: PathBuf,
    rounds: usize,
    peers: PathBuf,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut quick = false;
    let (mut out, mut rounds) = (None, None);
    let mut meshes = PathBuf::from("../shared/meshes");
    let mut peers = PathBuf::from("target/bench/peers.csv");
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value")).cloned();
        match a.as_str() {
            "--quick" => quick = true,
            "--out" => out = Some(PathBuf::from(value("--out")?)),
            "--meshes" => meshes = PathBuf::from(value("--meshes")?),
            "--peers" => peers = PathBuf::from(value("--peers")?),
            "--rounds" => {
                rounds = Some(
                    value("--rounds")?
                        .parse::<usize>()
                        .ok()
                        .filter(|&n| (1..=1000).contains(&n))
                        .ok_or("--rounds needs 1 to 1000")?,
                )
            }
            s => {
                return Err(format!(
                    "unexpected argument {s} (see the doc comment of examples/sweep)"
                ));
            }
        }
    }
    Ok(Options {
        quick,
        out: out.unwrap_or_else(|| {
            PathBuf::from(if quick {
                "target/sweep-quick"
            } else {
                "docs/charts"
            })
        }),
        meshes,
        rounds: rounds.unwrap_or(if quick { 1 } else { 11 }),
        peers,
    })
}

/// The machine and the date, for `machine.txt` and the charts' captions.
fn machine() -> String {
    let (cpu, threads) = zline_lab::machine::cpu();
    format!(
        "{cpu}, {threads} threads, {}-{}; {}",
        std::env::consts::OS,
        std::env::consts::ARCH,
        zline_lab::machine::now_utc()
    )
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The methods timed against polygon count and resolution (z16 for those
/// that store depth, as on a microcontroller).
fn timed_methods() -> Vec<Config> {
    [
        Method::Scanline,
        Method::ZBuffer,
        Method::Bands(8),
        Method::Interval,
        Method::Painter,
        Method::Reference,
    ]
    .into_iter()
    .map(|m| Config::new(m, false, false))
    .collect()
}

/// Chart 1: every method and depth format over the shared meshes.
fn accuracy_chart(o: &Options, caption: &str, progress: &mut Progress) -> Result<(), String> {
    let configs = [
        Config::new(Method::Scanline, false, false),
        Config::new(Method::Scanline, true, false),
        Config::new(Method::Scanline, false, true),
        Config::new(Method::Scanline, true, true),
        Config::new(Method::ZBuffer, false, false),
        Config::new(Method::ZBuffer, true, false),
        Config::new(Method::Bands(8), false, false),
        Config::new(Method::Bands(8), true, false),
        Config::new(Method::Interval, false, false),
        Config::new(Method::Painter, false, false),
        Config::new(Method::Reference, false, false),
    ];
    let (w, h) = (320u16, 240u16);
    let mut files = zline_lab::cli::obj_files(&o.meshes)?;
    if o.quick {
        files.retain(|f| {
            let n = f.file_stem().map(|s| s.to_string_lossy().into_owned());
            matches!(
                n.as_deref(),
                Some("suzanne" | "zju_planes" | "zju_six_boxes")
            )
        });
    }
    let mut totals = vec![Sample::default(); configs.len()];
    // Our scanline z16 time per mesh, to place the peers by their ratio.
    let mut scanline_ms = Vec::new();
    for file in &files {
        let name = measure::stem(file);
        progress.step(&format!("accuracy: {name} {w}x{h}"));
        let mesh = load_model(&file.to_string_lossy())?;
        let scene = Scene::new(&name, mesh, w, h)?;
        let samples = scene.run(&configs, o.rounds, true)?;
        scanline_ms.push((name, samples[0].median_ms));
        for (t, s) in totals.iter_mut().zip(samples) {
            t.add(&s);
        }
    }
    let pixels = totals[0].pixels.max(1) as f64;
    let peers = measure::peers(&o.peers, &format!("{w}x{h}"), &scanline_ms, pixels)?;
    if peers.is_empty() {
        eprintln!(
            "sweep: no peers' rows for every mesh at {w}x{h} in {} (run `cargo bench-peers` first); the chart shows zline's methods only",
            o.peers.display()
        );
    }
    let mut csv = String::from(
        "config,median_ms,pixels,mismatches,excused_at_edges,excused_as_ties,hard,wrong_pct,hard_pct,max_depth_error_lsb,pareto\n",
    );
    let points: Vec<(String, f64, f64, f64)> = configs
        .iter()
        .zip(&totals)
        .map(|(c, t)| {
            let pct = |n: usize| 100.0 * n as f64 / t.pixels.max(1) as f64;
            (c.label(), t.median_ms, pct(t.mismatches), pct(t.hard))
        })
        .chain(peers.iter().map(|p| (p.0.clone(), p.1, p.2, f64::NAN)))
        .collect();
    let front = chart::pareto(&points.iter().map(|p| (p.1, p.2)).collect::<Vec<_>>());
    for (k, (c, t)) in configs.iter().zip(&totals).enumerate() {
        csv += &format!(
            "{},{:.3},{},{},{},{},{},{:.5},{:.5},{},{}\n",
            c.label(),
            t.median_ms,
            t.pixels,
            t.mismatches,
            t.excused_at_edges,
            t.excused_as_ties,
            t.hard,
            points[k].2,
            points[k].3,
            t.max_depth_error_lsb
                .map_or("".into(), |e| format!("{e:.3}")),
            front.contains(&k)
        );
    }
    for (k, p) in peers.iter().enumerate() {
        csv += &format!(
            "{},{:.3},,,,,,{:.5},,,{}\n",
            p.0,
            p.1,
            p.2,
            front.contains(&(configs.len() + k))
        );
    }
    write(&o.out.join("accuracy.csv"), &csv)?;
    let point = |k: usize, y: f64, label: String| Point {
        x: points[k].1,
        y,
        label,
        color: k,
        peer: k >= configs.len(),
    };
    let all: Vec<Point> = (0..points.len())
        .map(|k| {
            point(
                k,
                points[k].2,
                format!("{} {:.4} %", points[k].0, points[k].2),
            )
        })
        .collect();
    let hard: Vec<Point> = (0..configs.len())
        .map(|k| {
            point(
                k,
                points[k].3,
                format!("{} {:.4} %", points[k].0, points[k].3),
            )
        })
        .collect();
    let depth: Vec<Point> = (0..configs.len())
        .filter_map(|k| {
            let e = totals[k].max_depth_error_lsb?;
            Some(point(k, e, format!("{} {e:.2} LSB", points[k].0)))
        })
        .collect();
    let depth_front = chart::pareto(&depth.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>());
    let hard_front = chart::pareto(&hard.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>());
    chart::scatter(
        &o.out.join("accuracy.svg"),
        &format!(
            "Time against accuracy: {} meshes at {w}x{h}, yaw 30 pitch 20, no culling; against the float64 reference",
            files.len()
        ),
        caption,
        &[
            Panel {
                title: "all wrong-face pixels (0 drawn at 1e-4 %)".into(),
                y_desc: "wrong-face pixels, % of frame".into(),
                floor: 1e-4,
                legend: SeriesLabelPosition::LowerRight,
                points: all,
                front,
            },
            Panel {
                title: "hard mismatches: neither at an edge nor a depth tie".into(),
                y_desc: "hard mismatches, % of frame".into(),
                floor: 1e-4,
                legend: SeriesLabelPosition::MiddleRight,
                points: hard,
                front: hard_front,
            },
            Panel {
                title: "largest depth error where the face is right".into(),
                y_desc: "|stored − exact| depth, LSB of the format".into(),
                floor: 1e-2,
                legend: SeriesLabelPosition::LowerRight,
                points: depth,
                front: depth_front,
            },
        ],
    )
}

/// Chart 2: time against polygon count.
fn polygon_chart(o: &Options, caption: &str, progress: &mut Progress) -> Result<(), String> {
    let configs = timed_methods();
    let mut meshes: Vec<String> = [
        "shape:sphere-100",
        "shape:sphere-2500",
        "shape:sphere-60000",
    ]
    .map(String::from)
    .to_vec();
    let bunny = o.meshes.join("stanford-bunny.obj");
    if !o.quick {
        meshes.push(bunny.to_string_lossy().into_owned());
    } else {
        meshes.truncate(2);
    }
    let sizes: &[(u16, u16)] = if o.quick {
        &[(240, 240)]
    } else {
        &[(240, 240), (800, 600)]
    };
    let mut csv = String::from("size,mesh,triangles,method,median_ms\n");
    let mut panels = Vec::new();
    for &(w, h) in sizes {
        let mut series: Vec<Series> = configs.iter().map(|c| Series::new(&c.label())).collect();
        for spec in &meshes {
            let mesh = load_model(spec)?;
            let name = spec
                .strip_prefix("shape:")
                .map_or_else(|| measure::stem(Path::new(spec)), String::from);
            let triangles = measure::triangles(&mesh);
            progress.step(&format!("polygons: {name} ({triangles} triangles) {w}x{h}"));
            let scene = Scene::new(&name, mesh, w, h)?;
            for (s, (c, sample)) in series
                .iter_mut()
                .zip(configs.iter().zip(scene.run(&configs, o.rounds, false)?))
            {
                csv += &format!(
                    "{w}x{h},{name},{triangles},{},{:.3}\n",
                    c.label(),
                    sample.median_ms
                );
                s.points.push((triangles as f64, sample.median_ms));
            }
        }
        panels.push((format!("{w}x{h}"), series));
    }
    write(&o.out.join("polygons.csv"), &csv)?;
    chart::lines(
        &o.out.join("polygons.svg"),
        "Time per frame against polygon count (UV spheres of 100, 2,500, 60,000 triangles; the bunny, 69,451)",
        caption,
        "triangles",
        "ms per frame",
        &panels,
        None,
    )
}

/// Charts 3 and 4: time and memory against resolution, for spot.
fn resolution_charts(o: &Options, caption: &str, progress: &mut Progress) -> Result<(), String> {
    let timed = timed_methods();
    let sizes: &[(u16, u16)] = if o.quick {
        &[(160, 128), (240, 240)]
    } else {
        &[
            (160, 128),
            (240, 240),
            (320, 240),
            (480, 320),
            (640, 480),
            (800, 600),
        ]
    };
    let spec = o.meshes.join("spot.obj").to_string_lossy().into_owned();
    let mesh = load_model(&spec)?;
    // Memory for these (z16 where there is depth; bands at 1, 8, 32 rows).
    let memory_configs: Vec<Config> = [
        Method::Scanline,
        Method::Bands(1),
        Method::Bands(8),
        Method::Bands(32),
        Method::ZBuffer,
        Method::Interval,
        Method::Painter,
    ]
    .into_iter()
    .map(|m| Config::new(m, false, false))
    .collect();
    let mut time_series: Vec<Series> = timed.iter().map(|c| Series::new(&c.label())).collect();
    let mut memory_series: Vec<Series> = memory_configs
        .iter()
        .map(|c| Series::new(&c.label()))
        .collect();
    let mut time_csv = String::from("size,pixels,method,median_ms\n");
    let mut memory_csv = String::from(
        "size,pixels,method,total_bytes,depth_bytes,color_bytes,table_bytes,working_bytes\n",
    );
    for &(w, h) in sizes {
        progress.step(&format!("resolution: spot {w}x{h}"));
        let pixels = f64::from(w) * f64::from(h);
        let scene = Scene::new("spot", mesh.clone(), w, h)?;
        for (s, (c, sample)) in time_series
            .iter_mut()
            .zip(timed.iter().zip(scene.run(&timed, o.rounds, false)?))
        {
            time_csv += &format!("{w}x{h},{pixels},{},{:.3}\n", c.label(), sample.median_ms);
            s.points.push((pixels, sample.median_ms));
        }
        for (s, (c, sample)) in memory_series
            .iter_mut()
            .zip(
                memory_configs
                    .iter()
                    .zip(scene.run(&memory_configs, 0, false)?),
            )
        {
            let m = sample.memory;
            memory_csv += &format!(
                "{w}x{h},{pixels},{},{},{},{},{},{}\n",
                c.label(),
                m.total(),
                m.depth,
                m.color,
                m.tables,
                m.working
            );
            s.points.push((pixels, m.total() as f64));
        }
    }
    write(&o.out.join("resolution.csv"), &time_csv)?;
    write(&o.out.join("memory.csv"), &memory_csv)?;
    chart::lines(
        &o.out.join("resolution.svg"),
        "Time per frame against resolution: spot (5,856 triangles), 160x128 to 800x600",
        caption,
        "pixels per frame",
        "ms per frame",
        &[("spot".into(), time_series)],
        None,
    )?;
    chart::lines(
        &o.out.join("memory.svg"),
        "Memory per frame against resolution: spot, Rgb565 colour, z16 depth",
        caption,
        "pixels per frame",
        "bytes",
        &[("spot".into(), memory_series)],
        Some(("RP2040 SRAM, 264 KB".into(), 264.0 * 1024.0, 240.0 * 240.0)),
    )
}

/// Chart 5: wrong faces against the far/near ratio, for each depth format
/// and method: the plates (gaps from 0.001 to 0.1 of the mesh radius) and
/// real meshes, far plane at 10, near at 10 / ratio.
fn precision_chart(o: &Options, caption: &str, progress: &mut Progress) -> Result<(), String> {
    let configs = [
        Config::new(Method::Scanline, false, false),
        Config::new(Method::Scanline, true, false),
        Config::new(Method::Scanline, false, true),
        Config::new(Method::Scanline, true, true),
        // The z-buffer and the bands draw the scanline's frames bit for bit
        // (tests/methods.rs): their lines would hide under its.
        Config::new(Method::Interval, false, false),
        Config::new(Method::Painter, false, false),
    ];
    let ratios: &[f64] = if o.quick {
        &[10.0, 1e5]
    } else {
        &[10.0, 100.0, 1e3, 1e4, 1e5]
    };
    let mut scenes: Vec<(String, zline::host::HostMesh)> =
        vec![("plates".into(), zline_lab::methods::catalogue::plates())];
    let real = if o.quick {
        &["suzanne"][..]
    } else {
        &["spot", "teapot", "cow"][..]
    };
    for name in real {
        let path = o.meshes.join(format!("{name}.obj"));
        scenes.push((name.to_string(), load_model(&path.to_string_lossy())?));
    }
    let (w, h) = (320u16, 240u16);
    let mut csv = String::from(
        "scene,far_over_near,near,far,method,pixels,mismatches,excused_at_edges,excused_as_ties,hard\n",
    );
    // Panel 0: the plates; panel 1: the real meshes, summed.
    let mut panels: Vec<Vec<Series>> = (0..2)
        .map(|_| configs.iter().map(|c| Series::new(&c.label())).collect())
        .collect();
    for &ratio in ratios {
        let camera = zline_lab::methods::ReferenceCamera {
            near: 10.0 / ratio,
            far: 10.0,
            ..zline_lab::methods::ReferenceCamera::STANDARD
        };
        let mut real_wrong = vec![0usize; configs.len()];
        for (k, (name, mesh)) in scenes.iter().enumerate() {
            progress.step(&format!("precision: {name}, far/near {ratio}"));
            let scene = Scene::with_camera(name, mesh.clone(), w, h, camera)?;
            for (c, (config, s)) in configs
                .iter()
                .zip(scene.run(&configs, 0, true)?)
                .enumerate()
            {
                csv += &format!(
                    "{name},{ratio},{},{},{},{},{},{},{},{}\n",
                    camera.near,
                    camera.far,
                    config.label(),
                    s.pixels,
                    s.mismatches,
                    s.excused_at_edges,
                    s.excused_as_ties,
                    s.hard
                );
                let wrong = s.mismatches - s.excused_at_edges;
                if k == 0 {
                    panels[0][c].points.push((ratio, wrong.max(1) as f64));
                } else {
                    real_wrong[c] += wrong;
                }
            }
        }
        for (c, wrong) in real_wrong.into_iter().enumerate() {
            panels[1][c].points.push((ratio, wrong.max(1) as f64));
        }
    }
    write(&o.out.join("precision.csv"), &csv)?;
    let mut named = panels.into_iter();
    let plates = named.next().unwrap_or_default();
    let real_panel = named.next().unwrap_or_default();
    chart::lines(
        &o.out.join("precision.svg"),
        "Depth precision: wrong faces (not at edges; 0 drawn at 1) against far/near, far 10, eye 3 from a mesh of radius 1",
        caption,
        "far / near",
        "wrong-face pixels not at an edge",
        &[
            ("plates: gaps 0.001 to 0.1 of the radius".into(), plates),
            (format!("{}, summed", real.join(", ")), real_panel),
        ],
        None,
    )
}

/// Numbered progress lines on stderr.
struct Progress {
    done: usize,
    total: usize,
}

impl Progress {
    fn step(&mut self, what: &str) {
        self.done += 1;
        eprintln!("sweep [{}/{}] {what}", self.done, self.total);
    }
}

fn run(args: &[String]) -> Result<(), String> {
    let o = parse(args)?;
    if !o.meshes.is_dir() {
        return Err(format!(
            "{}: not a folder of meshes (the shared meshes, or --meshes DIR)",
            o.meshes.display()
        ));
    }
    std::fs::create_dir_all(&o.out).map_err(|e| format!("{}: {e}", o.out.display()))?;
    let machine = machine();
    let command = format!(
        "cargo run --release -p zline-lab --features charts --bin sweep --{}",
        args.iter().map(|a| format!(" {a}")).collect::<String>()
    );
    println!("machine: {machine}");
    println!("command: {command}");
    write(
        &o.out.join("machine.txt"),
        &format!(
            "machine: {machine}\ncommand: {command}\nrounds: {}\n",
            o.rounds
        ),
    )?;
    let caption = format!("{machine}; median of {} rounds", o.rounds);
    let accuracy_scenes = if o.quick {
        3
    } else {
        zline_lab::cli::obj_files(&o.meshes)?.len()
    };
    let mut progress = Progress {
        done: 0,
        total: accuracy_scenes
            + if o.quick {
                2 + 2 + 2 * 2
            } else {
                8 + 6 + 5 * 4
            },
    };
    accuracy_chart(&o, &caption, &mut progress)?;
    polygon_chart(&o, &caption, &mut progress)?;
    resolution_charts(&o, &caption, &mut progress)?;
    precision_chart(&o, &caption, &mut progress)?;
    println!(
        "wrote {}/{{accuracy,polygons,resolution,memory,precision}}.{{svg,csv}} and machine.txt",
        o.out.display()
    );
    Ok(())
}

const USAGE: &str = "usage: sweep [--quick] [--out DIR] [--meshes DIR] [--rounds N] [--peers FILE]
The hidden-surface methods charted side by side (speed against accuracy, polygons, resolution;
memory against resolution): SVG charts and CSVs in DIR (docs/charts; target/sweep-quick with --quick).";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("sweep", USAGE, move || run(&args))
}
