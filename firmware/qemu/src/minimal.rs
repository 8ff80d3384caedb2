//! The smallest firmware of this crate: one mesh (the torus knot, drawn
//! as a `zline::Triangles`), one depth format (z16), flat Lambert, the
//! scanline, and zline without its default features (no comparison
//! methods, no clipper, no polygons of more than three corners). Its
//! flash is what the README states for a minimal firmware; `.ci/run`
//! builds it (`cargo qemu-minimal`), checks it against a budget and runs
//! it: the frame's CRC must be the host's, and it prints the instructions
//! of a second frame, as `zline-qemu` does.

#![no_std]
#![no_main]
// The generated scene list (`zline-qemu`'s, included below) holds meshes,
// scenes and textures this firmware does not use (and never links).
#![allow(dead_code)]

mod harness;

use core::convert::Infallible;

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use harness::{finish, instructions_per_tick, ticks};
use static_cell::ConstStaticCell;
use zline::reference_model_around;
use zline::{Camera, Cull, Depth16, QuantizedMesh, Renderer, ScanArrays, Shading, TableArrays};
use zline::{Crc32Sink, FnSink, Mesh, RenderError, RowSink, Triangles, Vec3, VertexCache};

/// Which depth format a scene uses (the generated scene list names it).
#[derive(Clone, Copy)]
enum DepthKind {
    Z16,
    Z24,
}

/// One frame of the generated scene list (`zline-qemu`'s); this firmware
/// draws the first and links none of the others' meshes.
struct Scene {
    name: &'static str,
    mesh: &'static QuantizedMesh<'static>,
    yaw: f32,
    pitch: f32,
    depth: DepthKind,
    expected_crc: u32,
}

// Meshes, SCENES and the capacities V, P, E, AP, AE, VM (from build.rs).
include!(concat!(env!("OUT_DIR"), "/scenes.rs"));

/// Frame width and height.
const SIZE: u16 = 240;

type Minimal =
    Renderer<TableArrays<Rgb565, V, P, E>, ScanArrays<Rgb565, Depth16, { SIZE as usize }, AP, AE>>;

static RENDERER: ConstStaticCell<Minimal> =
    ConstStaticCell::new(Minimal::new_in_static(SIZE, SIZE, Rgb565::BLACK));
static CACHE: ConstStaticCell<VertexCache<VM>> = ConstStaticCell::new(VertexCache::new());

/// What the firmware prints when every check passed (`.ci/run` reads it).
const PASSED: &str = "the frame matches the host";

#[entry]
fn main() -> ! {
    let Some(mut peripherals) = cortex_m::Peripherals::take() else {
        finish(false, PASSED)
    };
    let syst = &mut peripherals.SYST;
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(0x00FF_FFFF);
    syst.enable_counter();
    let per_tick = instructions_per_tick(syst);
    // The first scene: the torus knot at yaw 30, pitch 20, z16.
    let Some(scene) = SCENES.first() else {
        finish(false, PASSED)
    };
    let (yaw, pitch, expected) = (scene.yaw, scene.pitch, scene.expected_crc);
    let (renderer, cache) = (RENDERER.take(), CACHE.take());
    let (Ok(mesh), Ok(sphere)) = (
        Triangles::new(&TORUS_KNOT),
        zline::bounding_sphere(&TORUS_KNOT),
    ) else {
        finish(false, PASSED)
    };
    let shading = Shading::lambert();
    let view = (sphere, yaw, pitch, &shading);
    let mut crc = Crc32Sink::new();
    let drawn = render(renderer, cache, &mesh, view, &mut crc);
    let mut discard = FnSink(|_: u16, _: &[Rgb565], _: &[u16]| Ok::<(), Infallible>(()));
    let (_, t) = ticks(syst, || render(renderer, cache, &mesh, view, &mut discard));
    let ok = drawn.is_ok() && crc.value() == expected;
    hprintln!(
        "minimal: scene=torus-knot yaw={} pitch={} depth=z16 crc32={:08X} expected={:08X} {} instructions={}",
        // (As integers: `f32` formatting was 19 KB of flash.)
        yaw as i32,
        pitch as i32,
        crc.value(),
        expected,
        if ok { "ok" } else { "MISMATCH" },
        u64::from(t) * u64::from(per_tick)
    );
    finish(ok, PASSED)
}

/// The frame: `mesh` in the reference view at `yaw`/`pitch` (its bounding
/// sphere computed once), flat Lambert, back faces culled, into `sink`.
fn render<K: RowSink<Rgb565, u16>>(
    renderer: &mut Minimal,
    cache: &mut VertexCache<VM>,
    mesh: &impl Mesh,
    ((centre, radius), yaw, pitch, shading): ((Vec3, f32), f32, f32, &Shading),
    sink: &mut K,
) -> Result<(), RenderError<K::Error>> {
    renderer.clear();
    let model = reference_model_around(centre, radius, yaw, pitch);
    let camera = Camera::reference(SIZE, SIZE);
    zline::draw_mesh(renderer, cache, mesh, &model, &camera, Cull::Back, |f| {
        Rgb565::from(shading.color(f))
    })?;
    renderer.render(sink).map(|_| ())
}
