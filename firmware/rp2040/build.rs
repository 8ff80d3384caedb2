//! Build script of the RP2040 firmware.
//!
//! 1. Puts the repository's `memory.x` (RP2040 memory map with BOOT2), or
//!    with the `rp2350` feature `memory-rp2350.x` (the Pico 2's, with the
//!    IMAGE_DEF block), on the linker's search path as `memory.x`, and
//!    passes cortex-m-rt's `link.x`.
//! 2. Writes the mesh as Rust statics (`OUT_DIR/mesh.rs`), so it stays in
//!    flash: the built-in torus knot, or the OBJ file named by the
//!    environment variable `ZLINE_MESH`.
//! 3. Renders every view the firmware shows on the host, with the very
//!    code the firmware runs (`src/frame.rs`), and writes the table
//!    capacities those views need (plus a margin) and each view's expected
//!    CRC-32 (of the big-endian Rgb565 stream the LCD receives) to
//!    `OUT_DIR/capacities.rs`. A mesh whose tables would not leave enough
//!    RAM for the stack fails the build here. `ZLINE_RP2040_BAD_CRC=1`
//!    corrupts the first expected CRC (a self-test of the emulator check).
//! 4. With the `textured` feature, the texture as a Rust static
//!    (`OUT_DIR/texture.rs`): the PNG named by `ZLINE_TEXTURE`, each
//!    texel the mean of a `ZLINE_TEXTURE_SHRINK` square of its pixels
//!    (default 1), or 64x64 tiles for the built-in textured torus knot.

#[path = "src/frame.rs"]
mod frame;

use std::env;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use zline::Shading;
use zline::bounding_sphere;
use zline::host::{DEFAULT_CREASE_DEGREES, HostPaintedRenderer};
use zline::host::{HostMesh, HostRenderer, QuantizedHostMesh, host_renderer};
use zline::limits::MAX_FACE_CORNERS;
use zline::paint::{Gouraud, Texture, Textured};
use zline::{Capacities, Crc32Sink, Depth16, FrameStats, RowSink};
use zline::{Mesh, StaticMesh};
use zline_lab::rust_source::quantized_mesh_source;
use zline_lab::shapes;
use zline_lab::textures::Rgb565Texture;

/// Room for any view on the host, where the capacities are measured.
const HOST_CAPACITIES: Capacities = Capacities {
    width: WIDTH as usize,
    vertices: 65_536,
    polygons: 65_536,
    corners: 262_144,
    active_polygons: 16_384,
    pooled_edges: 16_384,
    mesh_vertices: 65_536,
};

/// LCD size in pixels (ST7789 240x240 module).
const WIDTH: u16 = 240;
const HEIGHT: u16 = 240;
/// The firmware turns the mesh through a full turn in this many frames...
const YAW_STEPS: u32 = 120;
/// ...at this fixed pitch, in degrees.
const PITCH_DEG: f32 = 20.0;
/// Built-in mesh used when `ZLINE_MESH` is not set.
const DEFAULT_SHAPE: &str = "torus-knot";
/// Built-in mesh of the `textured` feature when `ZLINE_MESH` is not set.
const TEXTURED_SHAPE: &str = "textured-torus-knot";
/// RAM in `memory.x` (the RP2040's SRAM0-3; the two 4 KiB banks SRAM4/5
/// are left out).
const RAM_RP2040: usize = 256 * 1024;
/// RAM in `memory-rp2350.x` (the RP2350's SRAM0-7; SRAM8/9 are left out).
const RAM_RP2350: usize = 512 * 1024;

/// Whether this build is for the Pico 2 (feature `rp2350`).
fn rp2350() -> bool {
    env::var_os("CARGO_FEATURE_RP2350").is_some()
}
/// Stack kept free for start-up and the render loop (the largest frames in
/// the loop are about 3 KiB; `src/stack.rs` measures the real use on the
/// board).
const STACK_RESERVE: usize = 16 * 1024;
/// Bytes of the SPI interface buffer in the firmware (one 240-pixel row
/// of Rgb565).
const SPI_BUFFER: usize = 2 * WIDTH as usize;
/// Rows of buffers queued for DMA (`src/lcd.rs`): the CPU may run this
/// many rows ahead of the wire, which covers the light rows above and
/// below a mesh, where it outruns the wire. (Over a turn of the default
/// scene 48 rows left the CPU waiting about 20 K cycles a frame more
/// than 64; 96 gained nothing over 64.)
const ROW_BUFFERS: usize = 64;
/// Rows of core 1's own buffers with `dual-core` (`POOL_ROWS` in
/// `src/lcd.rs`).
const DUAL_CORE_POOL_ROWS: usize = 128;
/// Rows of core 1's own buffers with `dual-core` and `textured`.
const DUAL_CORE_POOL_ROWS_TEXTURED: usize = 176;
/// Bytes of code the flat `dual-core` build runs from RAM (`src/frame.rs`'s
/// `draw_scene`, 10,056 B on 2026-11-30), with room to grow.
const DUAL_CORE_RAM_CODE: usize = 12 * 1024;
/// Rows per DMA buffer (`src/lcd.rs`): each buffer holds this many rows,
/// sent and cleared by one transfer each, so the per-transfer work is paid
/// once per eight rows. It divides both `HEIGHT` and `ROW_BUFFERS`.
const ROWS_PER_BUFFER: usize = if HEIGHT.is_multiple_of(8) {
    8
} else if HEIGHT.is_multiple_of(4) {
    4
} else if HEIGHT.is_multiple_of(2) {
    2
} else {
    1
};

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let out = PathBuf::from(env::var_os("OUT_DIR").ok_or("OUT_DIR is not set")?);
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").ok_or("no manifest dir")?);
    println!("cargo:rerun-if-changed=build.rs");

    // 1. Memory map and linker scripts: the repository's for the RP2040,
    // this crate's memory-rp2350.x for the Pico 2.
    let memory_x = match rp2350() {
        false => manifest.join("../../memory.x"),
        true => manifest.join("memory-rp2350.x"),
    };
    fs::copy(&memory_x, out.join("memory.x"))
        .map_err(|e| format!("copying {}: {e}", memory_x.display()))?;
    println!("cargo:rerun-if-changed={}", memory_x.display());
    println!("cargo:rustc-link-search={}", out.display());
    // cortex-m-rt's script; it INCLUDEs memory.x (above) and device.x
    // (from rp2040-pac with the HAL's "rt" feature).
    println!("cargo:rustc-link-arg=-Tlink.x");
    // No page alignment of sections: keeps the flash image compact.
    println!("cargo:rustc-link-arg=--nmagic");

    // 2. The mesh, as statics in flash.
    println!("cargo:rerun-if-env-changed=ZLINE_MESH");
    println!("cargo:rerun-if-env-changed=ZLINE_TEXTURE");
    println!("cargo:rerun-if-env-changed=ZLINE_TEXTURE_SHRINK");
    println!("cargo:rerun-if-env-changed=ZLINE_RP2040_BAD_CRC");
    println!("cargo:rerun-if-changed=src/frame.rs");
    let textured = env::var_os("CARGO_FEATURE_TEXTURED").is_some();
    let (mesh, origin) = match env::var_os("ZLINE_MESH").filter(|p| !p.is_empty()) {
        Some(path) => {
            let path = from_command_directory(path);
            println!("cargo:rerun-if-changed={}", path.display());
            (load_obj(&path, textured)?, path.display().to_string())
        }
        None => {
            let shape = if textured {
                TEXTURED_SHAPE
            } else {
                DEFAULT_SHAPE
            };
            (
                shapes::by_name(shape).ok_or("built-in shape missing")?,
                format!("zline_lab::shapes::by_name({shape:?})"),
            )
        }
    };
    if textured && mesh.uvs.is_empty() {
        return Err(format!(
            "{origin}: the `textured` feature needs texture coordinates (`vt`)"
        ));
    }
    check_mesh(&mesh, &origin)?;
    // The `gouraud` feature draws the mesh with vertex normals (the file's,
    // or computed with a 60° crease).
    let gouraud = env::var_os("CARGO_FEATURE_GOURAUD").is_some();
    let mesh = if gouraud {
        mesh.with_vertex_normals(DEFAULT_CREASE_DEGREES)
            .map_err(|e| format!("{origin}: vertex normals: {e}"))?
    } else {
        mesh
    };
    // Quantized, so the firmware's integer front end draws it with no
    // floating point per vertex or face.
    let source = quantized_mesh_source(&mesh, "MESH", &origin)?;
    write(&out.join("mesh.rs"), &source)?;
    // A mesh of triangles alone is drawn as `zline::Triangles`, which
    // leaves the code for faces of more corners out of the flash.
    println!("cargo:rustc-check-cfg=cfg(mesh_triangles)");
    if (0..mesh.face_count()).all(|face| mesh.face(face).len() == 3) {
        println!("cargo:rustc-cfg=mesh_triangles");
    }

    // 4. The texture (before the capacities: the host frames map it).
    let texture = if textured {
        let texture = match env::var_os("ZLINE_TEXTURE").filter(|p| !p.is_empty()) {
            Some(path) => {
                let path = from_command_directory(path);
                println!("cargo:rerun-if-changed={}", path.display());
                let shrink = match env::var("ZLINE_TEXTURE_SHRINK") {
                    Ok(s) => s
                        .parse()
                        .ok()
                        .filter(|&n| n >= 1)
                        .ok_or("ZLINE_TEXTURE_SHRINK: expected a whole number from 1")?,
                    Err(_) => 1,
                };
                Rgb565Texture::read(&path, shrink)?
            }
            None => Rgb565Texture::tiles(64, 64),
        };
        write(
            &out.join("texture.rs"),
            &texture.rust_source("TEXTURE", "the firmware's build script"),
        )?;
        Some(texture)
    } else {
        None
    };

    // 3. Table capacities for every view the firmware shows.
    let capacities = measure(mesh, &origin, texture)?;
    write(&out.join("capacities.rs"), &capacities)?;
    Ok(())
}

/// `path` as given, a relative one taken from the directory the command
/// was run in (the shell's PWD; cargo runs build scripts in the package's
/// own directory), as every other path of the tools.
fn from_command_directory(path: std::ffi::OsString) -> PathBuf {
    let path = PathBuf::from(path);
    match env::var_os("PWD") {
        Some(pwd) if path.is_relative() => PathBuf::from(pwd).join(path),
        _ => path,
    }
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    fs::write(path, text).map_err(|e| format!("writing {}: {e}", path.display()))
}

/// An OBJ file, with its texture coordinates (and normals) when
/// `with_uvs`.
fn load_obj(path: &Path, with_uvs: bool) -> Result<HostMesh, String> {
    let shown = path.display();
    let bytes = fs::read(path).map_err(|e| {
        let resolved = env::current_dir()
            .map(|d| d.join(path).display().to_string())
            .unwrap_or_default();
        format!("ZLINE_MESH={shown}: {e} (read as {resolved}: a relative path starts at the directory the command was run in)")
    })?;
    match with_uvs {
        true => HostMesh::from_obj_smooth(&bytes, DEFAULT_CREASE_DEGREES),
        false => HostMesh::from_obj(&bytes),
    }
    .map_err(|e| format!("ZLINE_MESH={shown}: {e}"))
}

/// Refuses meshes the firmware cannot draw, with a message naming why.
fn check_mesh(mesh: &HostMesh, origin: &str) -> Result<(), String> {
    if mesh.face_count() == 0 {
        return Err(format!("{origin}: the mesh has no faces"));
    }
    StaticMesh::new(&mesh.positions, &mesh.corners, &mesh.face_starts)
        .map_err(|e| format!("{origin}: invalid mesh: {e:?}"))?;
    let widest = max_face_corners(mesh);
    if widest > MAX_FACE_CORNERS {
        return Err(format!(
            "{origin}: a face has {widest} corners; the pipeline draws at most {MAX_FACE_CORNERS}"
        ));
    }
    Ok(())
}

fn max_face_corners(mesh: &HostMesh) -> usize {
    (0..mesh.face_count())
        .map(|f| mesh.face(f).len())
        .max()
        .unwrap_or(3)
}

/// Renders every firmware view on the host (on a thread with a large
/// stack: the host renderer is built on the stack) and returns the source
/// of `capacities.rs`.
fn measure(mesh: HostMesh, origin: &str, texture: Option<Rgb565Texture>) -> Result<String, String> {
    let origin = origin.to_string();
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || measure_views(&mesh, &origin, texture.as_ref()))
        .map_err(|e| format!("starting the sizing thread: {e}"))?
        .join()
        .map_err(|_| "the sizing thread failed".to_string())?
}

/// The CRC-32 of rows of [`frame::WireColor`] pixels: their bytes as they
/// lie in memory, which is the big-endian Rgb565 the LCD receives.
struct WireCrc(Crc32Sink);

impl RowSink<frame::WireColor, u16> for WireCrc {
    type Error = core::convert::Infallible;

    fn write_row(
        &mut self,
        _y: u16,
        colors: &[frame::WireColor],
        _depths: &[u16],
    ) -> Result<(), Self::Error> {
        for c in colors {
            self.0.update(&c.to_ne_bytes());
        }
        Ok(())
    }
}

impl RowSink<frame::WirePixel, u16> for WireCrc {
    type Error = core::convert::Infallible;

    fn write_row(
        &mut self,
        _y: u16,
        colors: &[frame::WirePixel],
        _depths: &[u16],
    ) -> Result<(), Self::Error> {
        for c in colors {
            self.0.update(&c.0.to_ne_bytes());
        }
        Ok(())
    }
}

/// A host renderer of the firmware's: flat, Gouraud (the `gouraud`
/// feature) or textured (`textured`).
enum Host<'t> {
    Flat(Box<HostRenderer<frame::WireColor, Depth16>>),
    Gouraud(Box<HostPaintedRenderer<Gouraud<frame::WirePixel>, Depth16>>),
    Textured(Box<HostPaintedRenderer<Textured<'t, frame::WirePixel>, Depth16>>),
}

fn measure_views(
    mesh: &HostMesh,
    origin: &str,
    texture: Option<&Rgb565Texture>,
) -> Result<String, String> {
    // The very arrays the firmware's statics hold.
    let quantized = QuantizedHostMesh::new(mesh).map_err(|e| format!("{origin}: {e}"))?;
    let quantized = quantized
        .mesh()
        .map_err(|e| format!("{origin}: invalid quantized mesh: {e:?}"))?;
    let gouraud = env::var_os("CARGO_FEATURE_GOURAUD").is_some();
    let mut host = if let Some(texture) = texture {
        let texture = Texture::new(&texture.texels, texture.width, texture.height)
            .map_err(|e| format!("texture: {e}"))?;
        Host::Textured(Box::new(
            HostPaintedRenderer::with_capacities(
                &HOST_CAPACITIES,
                (WIDTH, HEIGHT),
                Textured::new(texture),
                frame::WirePixel(frame::WIRE_BLACK),
            )
            .map_err(|e| format!("host renderer: {e}"))?,
        ))
    } else if gouraud {
        Host::Gouraud(Box::new(
            HostPaintedRenderer::with_capacities(
                &HOST_CAPACITIES,
                (WIDTH, HEIGHT),
                Gouraud::new(),
                frame::WirePixel(frame::WIRE_BLACK),
            )
            .map_err(|e| format!("host renderer: {e}"))?,
        ))
    } else {
        Host::Flat(Box::new(
            host_renderer(&HOST_CAPACITIES, WIDTH, HEIGHT, frame::WIRE_BLACK)
                .map_err(|e| format!("host renderer: {e}"))?,
        ))
    };
    // The firmware computes the sphere once at start-up, the same way.
    let sphere = bounding_sphere(&quantized).map_err(|e| format!("{origin}: {e}"))?;
    let shading = Shading::lambert();
    let mut peak = FrameStats::default();
    let mut crcs = Vec::new();
    for step in 0..YAW_STEPS {
        let mut crc = WireCrc(Crc32Sink::new());
        let view = (yaw_deg(step), PITCH_DEG);
        let (_, s) = match &mut host {
            Host::Flat(r) => frame::render_frame(r, &quantized, &shading, sphere, view, &mut crc),
            Host::Gouraud(r) => {
                frame::render_frame_painted(r, &quantized, &shading, sphere, view, &mut crc)
            }
            Host::Textured(r) => {
                frame::render_frame_painted(r, &quantized, &shading, sphere, view, &mut crc)
            }
        }
        .map_err(|e| format!("{origin}: view {step} does not render on the host: {e:?}"))?;
        crcs.push(crc.0.value());
        peak.vertices = peak.vertices.max(s.vertices);
        peak.polygons = peak.polygons.max(s.polygons);
        peak.corners = peak.corners.max(s.corners);
        peak.peak_active_polygons = peak.peak_active_polygons.max(s.peak_active_polygons);
        peak.peak_pooled_edges = peak.peak_pooled_edges.max(s.peak_pooled_edges);
    }

    // A quarter more than the largest view needs, for rounding differences
    // between host and target arithmetic.
    let margin = |n: u32| n as usize + n as usize / 4 + 16;
    let vertices = margin(peak.vertices).min(1 << 16);
    let polygons = margin(peak.polygons);
    let corners = margin(peak.corners);
    let active_polygons = margin(peak.peak_active_polygons);
    let pooled_edges = margin(peak.peak_pooled_edges);
    let mesh_vertices = mesh.vertex_count().max(1);

    let sized = FrameStats {
        vertices: vertices as u32,
        polygons: polygons as u32,
        corners: corners as u32,
        peak_active_polygons: active_polygons as u32,
        peak_pooled_edges: pooled_edges as u32,
        ..FrameStats::default()
    };
    let mut renderer = sized.ram_bytes::<frame::WireColor, Depth16>(usize::from(WIDTH));
    if gouraud {
        // A colour per vertex (3 x u16), the planes of each active polygon
        // (3 x 24 bytes and its position) and the painted row.
        renderer += 6 * vertices + 76 * active_polygons + 2 * usize::from(WIDTH);
    }
    if texture.is_some() {
        // Texture coordinates and w per vertex (12 bytes), the planes of
        // each active polygon (3 x 24 bytes, shifts, offsets and its
        // position) and the painted row.
        renderer += 12 * vertices + 104 * active_polygons + 2 * usize::from(WIDTH);
    }
    let mut ram = renderer + 2 * mesh_vertices + SPI_BUFFER + ROW_BUFFERS * 2 * usize::from(WIDTH);
    if env::var_os("CARGO_FEATURE_DUAL_CORE").is_some() {
        // Both cores (`src/dual.rs`, `src/lcd.rs`): a second renderer and
        // vertex cache, the ring doubled and core 1's 128 rows of buffers;
        // when textured, one ring and 176 rows for core 1. (Core 1's stack
        // is in SRAM4/SRAM5, outside `memory.x`'s RAM.)
        let (ring, pool) = match texture {
            Some(_) => (0, DUAL_CORE_POOL_ROWS_TEXTURED),
            None => (ROW_BUFFERS, DUAL_CORE_POOL_ROWS),
        };
        ram += renderer + 2 * mesh_vertices + (ring + pool) * 2 * usize::from(WIDTH);
        // The flat build's scene code, run from RAM (`frame::draw_scene`).
        if !gouraud && texture.is_none() {
            ram += DUAL_CORE_RAM_CODE;
        }
    }
    // The renderer is built at compile time in its static
    // (`Renderer::new_in_static`), so it needs room once.
    let needed = ram + STACK_RESERVE;
    let (chip, map, ram_size) = match rp2350() {
        false => ("RP2040", "memory.x", RAM_RP2040),
        true => ("RP2350", "memory-rp2350.x", RAM_RP2350),
    };
    if needed > ram_size {
        return Err(format!(
            "{origin}: too big for the {chip}'s RAM: the renderer's tables for this mesh take \
             about {renderer} bytes, {needed} bytes in all with the vertex cache, the SPI buffer, \
             the DMA row queue and {STACK_RESERVE} bytes of stack, over the {ram_size} bytes in {map}; use a \
             smaller mesh ({} vertices, {} faces here){}",
            mesh.vertex_count(),
            mesh.face_count(),
            match env::var_os("CARGO_FEATURE_DUAL_CORE") {
                Some(_) => " or one core (without `dual-core`, which doubles the renderer)",
                None => "",
            }
        ));
    }

    let mut s = String::new();
    let _ = writeln!(
        s,
        "// Generated by build.rs from {}: the largest counts over {YAW_STEPS} yaw \
         steps at pitch {PITCH_DEG}, {WIDTH}x{HEIGHT}, back faces culled, plus a margin. \
         Do not edit.",
        origin.replace(char::is_control, "?")
    );
    let _ = writeln!(
        s,
        "// Measured: vertices={} polygons={} corners={} active polygons={} pooled edges={}.",
        peak.vertices,
        peak.polygons,
        peak.corners,
        peak.peak_active_polygons,
        peak.peak_pooled_edges
    );
    let _ = writeln!(
        s,
        "// Estimated RAM (renderer + cache + SPI buffer + DMA row queue): {ram} bytes.\n"
    );
    let items: [(&str, &str, String); 9] = [
        ("WIDTH", "u16", WIDTH.to_string()),
        ("HEIGHT", "u16", HEIGHT.to_string()),
        ("YAW_STEPS", "u32", YAW_STEPS.to_string()),
        ("YAW_STEP_DEG", "f32", format!("{:?}", yaw_step_deg())),
        ("PITCH_DEG", "f32", format!("{PITCH_DEG:?}")),
        ("SPI_BUFFER", "usize", SPI_BUFFER.to_string()),
        ("ROW_BUFFERS", "usize", ROW_BUFFERS.to_string()),
        ("ROWS_PER_BUFFER", "usize", ROWS_PER_BUFFER.to_string()),
        ("MESH_VERTICES", "usize", mesh_vertices.to_string()),
    ];
    for (name, ty, value) in items {
        let _ = writeln!(s, "pub const {name}: {ty} = {value};");
    }
    // ZLINE_RP2040_BAD_CRC=1 flips one bit of the first expected CRC: the
    // emulator check must then fail.
    if env::var_os("ZLINE_RP2040_BAD_CRC").is_some() {
        crcs[0] ^= 1;
    }
    let listed: Vec<String> = crcs.iter().map(|c| format!("0x{c:08X}")).collect();
    let _ = writeln!(
        s,
        "/// CRC-32 of each view's frame as the LCD receives it (big-endian Rgb565),\n\
         /// rendered on the host by the firmware's own frame code.\n\
         pub const EXPECTED_CRCS: [u32; {}] = [{}];",
        crcs.len(),
        listed.join(", ")
    );
    let _ = writeln!(
        s,
        "/// The renderer's capacities, by name.\n\
         pub const CAPS: zline::Capacities = zline::Capacities {{\n    width: {WIDTH},\n    \
         vertices: {vertices},\n    polygons: {polygons},\n    corners: {corners},\n    \
         active_polygons: {active_polygons},\n    pooled_edges: {pooled_edges},\n    \
         mesh_vertices: {mesh_vertices},\n}};"
    );
    Ok(s)
}

/// Yaw of firmware frame `step` (`0..YAW_STEPS`), in degrees. The firmware
/// computes the same product from the generated `YAW_STEP_DEG`.
fn yaw_deg(step: u32) -> f32 {
    step as f32 * yaw_step_deg()
}

fn yaw_step_deg() -> f32 {
    360.0 / YAW_STEPS as f32
}
