//! The exact table sizes a mesh needs over a set of views, to set a
//! firmware's capacities, and the RAM the renderer then takes.
//!
//! ```sh
//! cargo run --release --example needs -- MODEL.obj [--size WxH] [--cull none|back] [--pitch DEG] [--views N]
//! ```
//!
//! Views: `N` yaw angles evenly spread over a full turn (default 36) at the
//! given pitch (default 20), in the reference view. For each count it
//! prints the largest over all views, then a `Renderer` type with those
//! capacities (Rgb565 colour, z16 and z24) and its RAM next to a full-frame
//! 16-bit z-buffer plus Rgb565 framebuffer.

use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb565;
use zline::Shading;
use zline::{Camera, Cull, reference_model};
use zline::{Capacities, Depth16, Depth24, FrameStats};
use zline_lab::cli::load_model;
use zline_lab::cli::parse_size;
use zline_lab::cli::run_tool;
use zline_lab::methods::HostScanline;

fn run(args: &[String]) -> Result<(), String> {
    let (mut path, mut size, mut cull, mut pitch, mut views) =
        (None, (240u16, 240u16), Cull::None, 20.0f32, 36usize);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{a} needs a value"));
        match a.as_str() {
            "--size" => size = parse_size(value()?)?,
            "--cull" => {
                cull = match value()?.as_str() {
                    "back" => Cull::Back,
                    "none" => Cull::None,
                    s => return Err(format!("--cull: unknown '{s}' (none, back)")),
                }
            }
            "--pitch" => {
                let v = value()?;
                pitch = v
                    .parse::<f32>()
                    .ok()
                    .filter(|p| p.is_finite())
                    .ok_or_else(|| format!("--pitch: expected degrees, got '{v}'"))?
            }
            "--views" => {
                views = value()?
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or("bad view count")?
            }
            s if path.is_none() && !s.starts_with("--") => path = Some(s.to_string()),
            s => return Err(format!("unexpected argument {s}")),
        }
    }
    let path = path.ok_or(
        "usage: needs MODEL.obj [--size WxH] [--cull none|back] [--pitch DEG] [--views N]",
    )?;
    let mesh = load_model(&path)?;
    let mut host = HostScanline::<Depth16>::new(size.0, size.1).map_err(|e| e.to_string())?;
    let camera = Camera::reference(size.0, size.1);
    let mut peak = FrameStats::default();
    for k in 0..views {
        let yaw = 360.0 * k as f32 / views as f32;
        let model = reference_model(&mesh, yaw, pitch).map_err(|e| format!("{path}: {e}"))?;
        let (_, s) = host
            .render(&mesh, &model, &camera, cull, &Shading::FaceId)
            .map_err(|e| e.to_string())?;
        peak = peak.max(s);
    }
    let w = usize::from(size.0);
    println!("mesh={path}");
    println!(
        "views={views} pitch={pitch} size={}x{} cull={cull:?}",
        size.0, size.1
    );
    println!("vertices={}", peak.vertices);
    println!("polygons={}", peak.polygons);
    println!("corners={}", peak.corners);
    println!("edges={}", peak.edges);
    println!("peak_active_polygons={}", peak.peak_active_polygons);
    println!("peak_active_edges={}", peak.peak_active_edges);
    println!("peak_pooled_edges={}", peak.peak_pooled_edges);
    println!("vertex_cache_bytes={}", 2 * mesh.positions.len());
    let z16 = peak.ram_bytes::<Rgb565, Depth16>(w) + 2 * mesh.positions.len();
    let z24 = peak.ram_bytes::<Rgb565, Depth24>(w) + 2 * mesh.positions.len();
    println!("ram_bytes_z16={z16}");
    println!("ram_bytes_z24={z24}");
    println!(
        "full_frame_z16_plus_rgb565_bytes={}",
        w * usize::from(size.1) * 4
    );
    let caps = Capacities::from_stats(&peak, w);
    println!(
        "\n// Capacities for this mesh at {}x{} (cull {cull:?}), as measured:\n\
         const CAPS: zline::Capacities = zline::Capacities {{\n    width: {},\n    vertices: {},\n    polygons: {},\n    corners: {},\n    active_polygons: {},\n    pooled_edges: {},\n}};\n\
         type Tables = zline::TableArrays<Rgb565, {{ CAPS.vertices }}, {{ CAPS.polygons }}, {{ CAPS.corners }}>;\n\
         type Rows = zline::ScanArrays<Rgb565, zline::Depth16, {{ CAPS.width }}, {{ CAPS.active_polygons }}, {{ CAPS.pooled_edges }}>;\n\
         type Zr = zline::Renderer<Tables, Rows>;\n\
         type Cache = zline::VertexCache<{}>;",
        size.0,
        size.1,
        caps.width,
        caps.vertices,
        caps.polygons,
        caps.corners,
        caps.active_polygons,
        caps.pooled_edges,
        mesh.positions.len()
    );
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    run_tool("needs", "", move || run(&args))
}
