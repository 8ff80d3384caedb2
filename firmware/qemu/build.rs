//! Prepares the emulated firmware on the host:
//! 1. the memory map (`memory-mps2.x` for QEMU's mps2-an385 and mps2-an386,
//!    which share it; `memory-an505.x` for mps2-an505, the Cortex-M33
//!    board) and cortex-m-rt's linker script;
//! 2. the scenes' meshes (and the textured scenes' texture) as Rust
//!    statics, quantized for the integer front end, so they live in flash;
//! 3. each scene's expected CRC, from rendering it on the host with the
//!    very same code (`src/frame.rs`); the firmware fails if its own frame
//!    differs;
//! 4. the renderer's capacities: the exact largest needs over all scenes,
//!    as measured on the host.
//!
//! `ZLINE_QEMU_SCENE=K` keeps only flat scene K, `ZLINE_QEMU_SCENE=gouraud`
//! only the Gouraud scenes, `ZLINE_QEMU_SCENE=textured` only the textured
//! ones (for profiling one frame);
//! `ZLINE_QEMU_BAD_CRC=1` corrupts one expected CRC (a self-test of the
//! failure path).

#[path = "src/frame.rs"]
mod frame;

use std::fmt::Write as _;
use std::path::PathBuf;

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use zline::Mesh;
use zline::QuantizedMesh;
use zline::VertexCache;
use zline::host::host_renderer;
use zline::host::{DEFAULT_CREASE_DEGREES, HostPaintedRenderer};
use zline::host::{HostMesh, QuantizedHostMesh};
use zline::paint::{Gouraud, LitTextured, PaintMode, Textured};
use zline::{Capacities, Crc32Sink, Depth16, Depth24, DepthFormat, FrameStats};
use zline_lab::rust_source::quantized_mesh_source;
use zline_lab::shapes;
use zline_lab::textures::Rgb565Texture;

/// (shape, yaw, pitch) drawn with Gouraud shading (z16), the shape read
/// smooth (vertex normals within a 60° crease).
const GOURAUD_SCENES: [(&str, f32, f32); 1] = [("torus-knot", 30.0, 20.0)];

/// (shape, yaw, pitch) texture-mapped (z16, perspective-correct, nearest
/// texels of `TILES`, repeating).
const TEXTURED_SCENES: [(&str, f32, f32); 1] = [("textured-torus-knot", 30.0, 20.0)];

/// (shape, yaw, pitch) texture-mapped as above and lit per vertex
/// (`LitTextured`, by `Shading::lambert()`'s light; dithered to Rgb565).
const LIT_TEXTURED_SCENES: [(&str, f32, f32); 1] = [("textured-torus-knot", 30.0, 20.0)];

/// `TILES` is this many texels a side.
const TEXTURE_SIZE: u16 = 64;

/// (shape, yaw, pitch): each is rendered with both depth formats.
const SCENES: [(&str, f32, f32); 4] = [
    ("torus-knot", 30.0, 20.0),
    ("torus-knot", 200.0, -35.0),
    ("icosphere", 30.0, 20.0),
    ("boxes", 30.0, 20.0),
];

type HostRenderer<D> = zline::host::HostRenderer<Rgb565, D>;

/// Room for every scene on the host, where the capacities are measured.
const HOST_CAPACITIES: Capacities = Capacities {
    width: 240,
    vertices: 65_536,
    polygons: 65_536,
    corners: 262_144,
    active_polygons: 16_384,
    pooled_edges: 16_384,
    mesh_vertices: 0,
};

fn main() {
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
    let target = std::env::var("TARGET").expect("TARGET");
    let (memory, board) = match target.as_str() {
        t if t.starts_with("thumbv8m") => ("memory-an505.x", "mps2-an505"),
        t if t.starts_with("thumbv7em") => ("memory-mps2.x", "mps2-an386"),
        _ => ("memory-mps2.x", "mps2-an385"),
    };
    std::fs::copy(memory, out.join("memory.x")).expect("copy the memory map");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg=-Tlink.x");
    println!("cargo:rustc-env=ZLINE_QEMU_BOARD={board}");
    println!("cargo:rustc-env=ZLINE_QEMU_TARGET={target}");
    println!("cargo:rerun-if-changed=memory-mps2.x");
    println!("cargo:rerun-if-changed=memory-an505.x");
    println!("cargo:rerun-if-changed=src/frame.rs");
    println!("cargo:rerun-if-env-changed=ZLINE_QEMU_SCENE");
    println!("cargo:rerun-if-env-changed=ZLINE_QEMU_BAD_CRC");
    // The host renderer is large: build it on a thread with a large stack.
    let source = std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(generate)
        .expect("spawn")
        .join()
        .expect("scene generation failed");
    std::fs::write(out.join("scenes.rs"), source).expect("write scenes.rs");
}

/// Largest needs over all frames.
#[derive(Default)]
struct Needs {
    vertices: u32,
    polygons: u32,
    corners: u32,
    active_polygons: u32,
    pooled_edges: u32,
    mesh_vertices: usize,
}

impl Needs {
    fn add(&mut self, s: &FrameStats) {
        self.vertices = self.vertices.max(s.vertices);
        self.polygons = self.polygons.max(s.polygons);
        self.corners = self.corners.max(s.corners);
        self.active_polygons = self.active_polygons.max(s.peak_active_polygons);
        self.pooled_edges = self.pooled_edges.max(s.peak_pooled_edges);
    }
}

fn const_name(shape: &str) -> String {
    shape.to_uppercase().replace('-', "_")
}

fn generate() -> String {
    // ZLINE_QEMU_SCENE=K keeps only scene K (for profiling one frame).
    // ZLINE_QEMU_SCENE=gouraud keeps only the Gouraud scenes.
    let gouraud_only = std::env::var("ZLINE_QEMU_SCENE").is_ok_and(|v| v == "gouraud");
    let textured_only = std::env::var("ZLINE_QEMU_SCENE").is_ok_and(|v| v == "textured");
    let only: Option<usize> = match gouraud_only || textured_only {
        true => Some(usize::MAX),
        false => std::env::var("ZLINE_QEMU_SCENE")
            .ok()
            .and_then(|v| v.parse().ok()),
    };
    let scene_list: Vec<(&str, f32, f32)> = SCENES
        .iter()
        .enumerate()
        .filter(|(k, _)| only.is_none_or(|o| o == *k))
        .map(|(_, s)| *s)
        .collect();
    let mut out = String::new();
    let mut needs = Needs::default();
    let mut meshes: Vec<(&str, HostMesh)> = Vec::new();
    for &(shape, _, _) in &scene_list {
        if !meshes.iter().any(|(s, _)| *s == shape) {
            let mesh = shapes::by_name(shape).expect("known shape");
            let source = quantized_mesh_source(
                &mesh,
                &const_name(shape),
                &format!("zline_lab::shapes `{shape}`"),
            )
            .expect("mesh source");
            out.push_str(&source);
            out.push('\n');
            needs.mesh_vertices = needs.mesh_vertices.max(mesh.vertex_count());
            meshes.push((shape, mesh));
        }
    }
    let (size, black) = (frame::SIZE, Rgb565::BLACK);
    let mut z16: HostRenderer<Depth16> =
        host_renderer(&HOST_CAPACITIES, size, size, black).expect("renderer");
    let mut z24: HostRenderer<Depth24> =
        host_renderer(&HOST_CAPACITIES, size, size, black).expect("renderer");
    let mut cache: Box<VertexCache<65536>> = Box::default();
    let mut scenes = String::new();
    for &(shape, yaw, pitch) in &scene_list {
        let host = &meshes.iter().find(|(s, _)| *s == shape).expect("mesh").1;
        // The very arrays the firmware's statics hold.
        let quantized = QuantizedHostMesh::new(host).expect("quantizable mesh");
        let mesh = quantized.mesh().expect("valid mesh");
        let crc16 = expected(&mut z16, &mut cache, &mesh, yaw, pitch, &mut needs);
        let crc24 = expected(&mut z24, &mut cache, &mesh, yaw, pitch, &mut needs);
        // ZLINE_QEMU_BAD_CRC=1 flips one bit of one expected CRC: a self-test
        // that the emulated run fails when a frame differs from the host's.
        let flip = u32::from(std::env::var_os("ZLINE_QEMU_BAD_CRC").is_some() && scenes.is_empty());
        for (depth, crc) in [("Z16", crc16 ^ flip), ("Z24", crc24)] {
            let _ = writeln!(
                scenes,
                "    Scene {{ name: {shape:?}, mesh: &{}, yaw: {yaw:?}, pitch: {pitch:?}, depth: DepthKind::{depth}, expected_crc: 0x{crc:08X} }},",
                const_name(shape)
            );
        }
    }
    let _ = writeln!(
        out,
        "/// Every scene, with its CRC as rendered on the host.\nstatic SCENES: [Scene; {}] = [\n{scenes}];\n",
        scene_list.len() * 2
    );
    gouraud_scenes(&mut out, only.is_none() || gouraud_only);
    textured_scenes(&mut out, only.is_none() || textured_only);
    let _ = writeln!(
        out,
        "// Capacities: the exact largest needs over all scenes, measured on the host.\n\
         const V: usize = {};\nconst P: usize = {};\nconst E: usize = {};\nconst AP: usize = {};\nconst AE: usize = {};\n\
         const VM: usize = {};",
        needs.vertices,
        needs.polygons,
        needs.corners,
        needs.active_polygons,
        needs.pooled_edges,
        needs.mesh_vertices
    );
    out
}

/// The Gouraud scenes (all of them, or none when one flat scene is
/// kept): their smooth meshes, `GOURAUD_SCENES` with the host's CRCs, and
/// `GOURAUD_CAPS`, the painted renderer's capacities measured on the host.
fn gouraud_scenes(out: &mut String, all: bool) {
    let list: &[(&str, f32, f32)] = if all { &GOURAUD_SCENES } else { &[] };
    painted_scenes(
        out,
        ("GOURAUD", "SMOOTH", "smooth"),
        list,
        Gouraud::new(),
        &mut Vec::new(),
    );
}

/// The textured scenes (all of them, or none when one flat scene is
/// kept): the texture (`TILES`, written by zline-lab's
/// `Rgb565Texture::tiles`), the meshes with their texture coordinates,
/// `TEXTURED_SCENES` with the host's CRCs and `TEXTURED_CAPS`.
fn textured_scenes(out: &mut String, all: bool) {
    let list: &[(&str, f32, f32)] = if all { &TEXTURED_SCENES } else { &[] };
    let tiles = Rgb565Texture::tiles(TEXTURE_SIZE, TEXTURE_SIZE);
    out.push_str(&tiles.rust_source("TILES", "zline-lab's Rgb565Texture::tiles"));
    out.push('\n');
    let texture = tiles.texture().expect("texture");
    let mut emitted = Vec::new();
    painted_scenes(
        out,
        ("TEXTURED", "UV", "with texture coordinates"),
        list,
        Textured::new(texture),
        &mut emitted,
    );
    let list: &[(&str, f32, f32)] = if all { &LIT_TEXTURED_SCENES } else { &[] };
    painted_scenes(
        out,
        ("LIT_TEXTURED", "UV", "with texture coordinates"),
        list,
        LitTextured::new(texture),
        &mut emitted,
    );
}

/// The scenes `list` of one painted mode (`mode`, drawn by
/// `frame::render_frame_painted`):
/// each shape read smooth (normals within a 60° crease, texture
/// coordinates kept) as the static `SHAPE_SUFFIX`, the scenes as
/// `KIND_SCENES` with the host's CRCs, and `KIND_CAPS`, the painted
/// renderer's capacities: the scenes' largest needs, measured on the
/// host. A mesh whose static is in `emitted` is not written again.
fn painted_scenes<M: PaintMode<Color = Rgb565, Source: frame::VertexSource>>(
    out: &mut String,
    (kind, suffix, what): (&str, &str, &str),
    list: &[(&str, f32, f32)],
    mode: M,
    emitted: &mut Vec<String>,
) {
    let mut needs = Needs::default();
    let mut scenes = String::new();
    // The painted renderer holds its vertex cache.
    let caps = Capacities {
        mesh_vertices: 65_536,
        ..HOST_CAPACITIES
    };
    let mut painted = HostPaintedRenderer::<M, Depth16>::with_capacities(
        &caps,
        (frame::SIZE, frame::SIZE),
        mode,
        Rgb565::BLACK,
    )
    .expect("painted renderer");
    for &(shape, yaw, pitch) in list {
        let name = format!("{}_{suffix}", const_name(shape));
        let host = shapes::by_name(shape)
            .expect("known shape")
            .with_vertex_normals(DEFAULT_CREASE_DEGREES)
            .expect("smooth mesh");
        if !emitted.contains(&name) {
            let source = quantized_mesh_source(
                &host,
                &name,
                &format!("zline_lab::shapes `{shape}`, {what}"),
            )
            .expect("mesh source");
            out.push_str(&source);
            out.push('\n');
            emitted.push(name.clone());
        }
        needs.mesh_vertices = needs.mesh_vertices.max(host.vertex_count());
        let quantized = QuantizedHostMesh::new(&host).expect("quantizable mesh");
        let mesh = quantized.mesh().expect("valid mesh");
        let mut crc = Crc32Sink::new();
        let sphere = zline::bounding_sphere(&mesh).expect("mesh size");
        let (_, stats) =
            frame::render_frame_painted(&mut painted, &mesh, sphere, (yaw, pitch), &mut crc)
                .expect("host render");
        needs.add(&stats);
        let _ = writeln!(
            scenes,
            "    Scene {{ name: {shape:?}, mesh: &{name}, yaw: {yaw:?}, pitch: {pitch:?}, depth: DepthKind::Z16, expected_crc: 0x{:08X} }},",
            crc.value()
        );
    }
    let _ = writeln!(
        out,
        "/// The {kind} scenes (z16), with their CRCs as rendered on the host.\n\
         static {kind}_SCENES: [Scene; {}] = [\n{scenes}];\n\n\
         /// The painted renderer's capacities: the largest needs of the\n\
         /// scenes, measured on the host.\n\
         const {kind}_CAPS: zline::Capacities = zline::Capacities {{\n    \
         width: {},\n    vertices: {},\n    polygons: {},\n    corners: {},\n    \
         active_polygons: {},\n    pooled_edges: {},\n    mesh_vertices: {},\n}};",
        list.len(),
        frame::SIZE,
        needs.vertices.max(1),
        needs.polygons.max(1),
        needs.corners.max(1),
        needs.active_polygons.max(1),
        needs.pooled_edges,
        needs.mesh_vertices
    );
}

fn expected<D: DepthFormat>(
    renderer: &mut HostRenderer<D>,
    cache: &mut VertexCache<65536>,
    mesh: &QuantizedMesh<'_>,
    yaw: f32,
    pitch: f32,
    needs: &mut Needs,
) -> u32 {
    let mut crc = Crc32Sink::new();
    let (_, stats) = frame::render_frame(
        renderer,
        cache,
        mesh,
        zline::bounding_sphere(mesh).expect("mesh size"),
        (yaw, pitch),
        &mut crc,
    )
    .expect("host render");
    needs.add(&stats);
    crc.value()
}
