//! The capacities a firmware's renderer needs for a mesh over the views it
//! will show, as one line to paste, and the RAM they take.
//!
//! ```sh
//! cargo run --release --example needs -- MODEL.obj [--size WxH] [--cull none|back|both]
//!     [--yaw-step DEG] [--pitch DEG | --pitch-step DEG] [--margin PERCENT]
//! ```
//!
//! Views: the reference view with the mesh turned to every `--yaw-step`
//! degrees of a full turn (default 10) at every `--pitch-step` degrees from
//! -90 to 90 (default 15), or at the one `--pitch`, with back faces culled
//! and not (`--cull both`, the default). The line it prints covers exactly
//! those views; `--margin` adds that many percent to each count for the
//! views between them. Paste it, then
//! `type Zr = zline::renderer_type!(Rgb565, Depth16, CAPS);`.

use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb565;
use zline::{Cull, Depth16, Depth24};
use zline_lab::cli::{help_requested, load_model, parse_angle, parse_size, run_tool};
use zline_lab::needs::{Views, capacities, line, peak};

const USAGE: &str = "usage: needs MODEL.obj [--size WxH] [--cull none|back|both] [--yaw-step DEG] \
[--pitch DEG | --pitch-step DEG] [--margin PERCENT]
Prints the capacities a renderer needs for MODEL.obj (or shape:NAME) over a grid of views
(default: 240x240, yaw every 10 degrees, pitch every 15 from -90 to 90, culled and not) as one
line to paste, `const CAPS: zline::Capacities = ...;`, and the RAM they take.";

fn run(args: &[String]) -> Result<(), String> {
    let (mut path, mut size) = (None, (240u16, 240u16));
    let (mut yaw_step, mut pitch_step, mut pitch) = (10.0f32, 15.0f32, None);
    let (mut culls, mut margin) = (vec![Cull::None, Cull::Back], 0u32);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{a} needs a value"));
        match a.as_str() {
            "--size" => size = parse_size(value()?)?,
            "--cull" => {
                culls = match value()?.as_str() {
                    "back" => vec![Cull::Back],
                    "none" => vec![Cull::None],
                    "both" => vec![Cull::None, Cull::Back],
                    s => return Err(format!("--cull: unknown '{s}' (none, back, both)")),
                }
            }
            "--yaw-step" => yaw_step = step(a, value()?)?,
            "--pitch-step" => pitch_step = step(a, value()?)?,
            "--pitch" => pitch = Some(parse_angle(a, value()?)?),
            "--margin" => {
                let v = value()?;
                margin = v
                    .parse()
                    .map_err(|_| format!("--margin: expected a percentage, got '{v}'"))?
            }
            s if path.is_none() && !s.starts_with("--") => path = Some(s.to_string()),
            s => return Err(format!("unexpected argument {s}")),
        }
    }
    let path = path.ok_or("no model given")?;
    let mesh = load_model(&path)?;
    let mut views = Views::grid(size, yaw_step, pitch_step);
    if let Some(p) = pitch {
        views.pitches = vec![p];
    }
    views.culls = culls;
    let peak = peak(&mesh, &views).map_err(|e| format!("{path}: {e}"))?;
    let caps = capacities(&mesh, &views, margin).map_err(|e| format!("{path}: {e}"))?;
    println!("mesh={path}");
    println!("views={} ({})", views.each().count(), views.describe());
    println!("vertices={}", peak.vertices);
    println!("polygons={}", peak.polygons);
    println!("corners={}", peak.corners);
    println!("peak_active_polygons={}", peak.peak_active_polygons);
    println!("peak_pooled_edges={}", peak.peak_pooled_edges);
    println!("mesh_vertices={}", caps.mesh_vertices);
    println!("ram_bytes_z16={}", caps.ram_bytes::<Rgb565, Depth16>());
    println!("ram_bytes_z24={}", caps.ram_bytes::<Rgb565, Depth24>());
    println!(
        "full_frame_z16_plus_rgb565_bytes={}",
        usize::from(size.0) * usize::from(size.1) * 4
    );
    println!();
    let covers = if margin == 0 {
        String::from("exactly these views")
    } else {
        format!("these views, plus {margin} %")
    };
    println!("// {path}: {} ({covers})", views.describe());
    println!("{}", line(&caps));
    Ok(())
}

/// A step in degrees: finite and above zero.
fn step(name: &str, v: &str) -> Result<f32, String> {
    Some(parse_angle(name, v)?)
        .filter(|&d| d > 0.0)
        .ok_or_else(|| format!("{name}: expected a step above 0 degrees, got '{v}'"))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if help_requested(&args, USAGE) {
        return ExitCode::SUCCESS;
    }
    run_tool("needs", USAGE, move || run(&args))
}
