//! zline on an emulated Cortex-M: QEMU `-machine mps2-an385` with code
//! built for `thumbv6m-none-eabi` (Cortex-M0+ code; it runs on the board's
//! Cortex-M3), `mps2-an386` with `thumbv7em-none-eabihf` (Cortex-M4F) or
//! `mps2-an505` with `thumbv8m.main-none-eabihf` (Cortex-M33).
//!
//! For every scene (built-in meshes in flash, two views, both depth formats,
//! 240x240; then Gouraud-shaded, texture-mapped and lit texture-mapped
//! frames) it renders one frame into a CRC sink and compares the CRC with
//! the host's (computed by `build.rs` with the same code). It then renders
//! the frame again into a sink that discards rows, counting instructions
//! with SysTick under `-icount shift=0`. It prints one line per scene and
//! exits through semihosting: 0 when every CRC matched, 1 otherwise.
//!
//! Run with `cargo qemu`, `cargo qemu-m4f` or `cargo qemu-m33` from the
//! repository root.

#![no_std]
#![no_main]

mod frame;
mod harness;

use core::convert::Infallible;

use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use harness::{finish, instructions_per_tick, ticks};
use static_cell::ConstStaticCell;
use zline::QuantizedMesh;
use zline::VertexCache;
use zline::paint::{Gouraud, LitTextured, Texture, Textured};
use zline::zbuffer::BandBuffers;
use zline::{ActiveEdge, ActivePolygon, ScanArrays, ScanStorage, TableArrays};
use zline::{Crc32Sink, Depth16, Depth24, DepthFormat, FnSink, FrameStats, Renderer};

/// Which depth format a scene uses.
#[derive(Clone, Copy)]
enum DepthKind {
    Z16,
    Z24,
}

/// One frame to check.
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

/// The tables, sized by the build script.
type Tables = TableArrays<Rgb565, V, P, E>;
/// Rows of 240 pixels with 16-bit depth.
type Rows16 = ScanArrays<Rgb565, Depth16, { frame::SIZE as usize }, AP, AE>;
/// Rows of 240 pixels with 24-bit depth.
type Rows24 = ScanArrays<Rgb565, Depth24, { frame::SIZE as usize }, AP, AE>;
type Renderer16 = Renderer<Tables, Rows16>;
type Renderer24 = Renderer<Tables, Rows24>;

// The renderers live in statics, built at compile time: no copy on the stack.
static RENDERER16: ConstStaticCell<Renderer16> = ConstStaticCell::new(Renderer16::new_in_static(
    frame::SIZE,
    frame::SIZE,
    Rgb565::BLACK,
));
static RENDERER24: ConstStaticCell<Renderer24> = ConstStaticCell::new(Renderer24::new_in_static(
    frame::SIZE,
    frame::SIZE,
    Rgb565::BLACK,
));
static CACHE: ConstStaticCell<VertexCache<VM>> = ConstStaticCell::new(VertexCache::new());

/// The Gouraud renderer (z16): slots in its rows, colours painted after.
type Gouraud16 = zline::painted_renderer_type!(Gouraud<Rgb565>, Depth16, GOURAUD_CAPS);
static GOURAUD16: ConstStaticCell<Gouraud16> = ConstStaticCell::new(Gouraud16::new_in_static(
    frame::SIZE,
    frame::SIZE,
    Gouraud::new(),
    Rgb565::BLACK,
));

/// The textured scenes' texture, in flash.
const TEXTURE: Texture<'static> = match Texture::new(&TILES, TILES_WIDTH, TILES_HEIGHT) {
    Ok(texture) => texture,
    Err(_) => panic!("TILES: bad texture size"),
};

/// The texture-mapping renderer (z16): slots in its rows, texels painted
/// after.
type Textured16 = zline::painted_renderer_type!(Textured<'static, Rgb565>, Depth16, TEXTURED_CAPS);
static TEXTURED16: ConstStaticCell<Textured16> = ConstStaticCell::new(Textured16::new_in_static(
    frame::SIZE,
    frame::SIZE,
    Textured::new(TEXTURE),
    Rgb565::BLACK,
));

/// The lit texture-mapping renderer (z16).
type LitTextured16 =
    zline::painted_renderer_type!(LitTextured<'static, Rgb565>, Depth16, LIT_TEXTURED_CAPS);
static LIT_TEXTURED16: ConstStaticCell<LitTextured16> =
    ConstStaticCell::new(LitTextured16::new_in_static(
        frame::SIZE,
        frame::SIZE,
        LitTextured::new(TEXTURE),
        Rgb565::BLACK,
    ));

/// Pixels of a frame.
const FRAME_PIXELS: usize = frame::SIZE as usize * frame::SIZE as usize;
/// Edges a concave polygon may keep beyond its first two, for the
/// z-buffer (the built-in meshes are triangles and convex quads).
const ZBUFFER_POOL: usize = 32;

/// The full-frame z-buffer's depth (z16: 115,200 bytes) and colour
/// (Rgb565: 115,200 bytes), its row of scratch, its one active polygon and
/// its edge pool.
static Z_DEPTH: ConstStaticCell<[u16; FRAME_PIXELS]> =
    ConstStaticCell::new([u16::MAX; FRAME_PIXELS]);
static Z_COLOR: ConstStaticCell<[Rgb565; FRAME_PIXELS]> =
    ConstStaticCell::new([Rgb565::BLACK; FRAME_PIXELS]);
static Z_SCRATCH: ConstStaticCell<[u32; frame::SIZE as usize]> =
    ConstStaticCell::new([0; frame::SIZE as usize]);
static Z_ACTIVE: ConstStaticCell<[ActivePolygon<Rgb565>; 1]> =
    ConstStaticCell::new([ActivePolygon::filler(Rgb565::BLACK)]);
static Z_POOL: ConstStaticCell<[ActiveEdge; ZBUFFER_POOL]> =
    ConstStaticCell::new([ActiveEdge::EMPTY; ZBUFFER_POOL]);

/// The z-buffer's lent buffers, borrowed for one frame at a time.
struct ZBuffer {
    depth: &'static mut [u16; FRAME_PIXELS],
    color: &'static mut [Rgb565; FRAME_PIXELS],
    scratch: &'static mut [u32; frame::SIZE as usize],
    active: &'static mut [ActivePolygon<Rgb565>; 1],
    pool: &'static mut [ActiveEdge; ZBUFFER_POOL],
}

impl ZBuffer {
    fn buffers(&mut self) -> BandBuffers<'_, Rgb565, Depth16> {
        BandBuffers {
            depth: &mut self.depth[..],
            color: &mut self.color[..],
            scratch: &mut self.scratch[..],
            active: &mut self.active[..],
            pool: &mut self.pool[..],
        }
    }
}

/// A z16 scene by the full-frame z-buffer: its CRC (which must be the
/// scanline's) and the instructions of a second, discarded frame.
fn run_zbuffer<S: ScanStorage<Color = Rgb565>>(
    renderer: &mut Renderer<Tables, S>,
    z: &mut ZBuffer,
    cache: &mut VertexCache<VM>,
    scene: &Scene,
    syst: &mut SYST,
) -> Result<(u32, u32), zline::RenderError<Infallible>> {
    let sphere = zline::bounding_sphere(scene.mesh)?;
    let view = (scene.yaw, scene.pitch);
    let mut crc = Crc32Sink::new();
    frame::render_frame_zbuffer(
        &mut renderer.tables,
        cache,
        scene.mesh,
        sphere,
        view,
        z.buffers(),
        &mut crc,
    )?;
    let mut discard = FnSink(|_: u16, _: &[Rgb565], _: &[u16]| Ok::<(), Infallible>(()));
    let (result, ticks) = ticks(syst, || {
        frame::render_frame_zbuffer(
            &mut renderer.tables,
            cache,
            scene.mesh,
            sphere,
            view,
            z.buffers(),
            &mut discard,
        )
    });
    result?;
    Ok((crc.value(), ticks))
}

struct Outcome {
    crc: u32,
    ticks: u32,
    stats: FrameStats,
}

fn run<S: ScanStorage<Color = Rgb565>>(
    renderer: &mut Renderer<Tables, S>,
    cache: &mut VertexCache<VM>,
    scene: &Scene,
    syst: &mut SYST,
) -> Result<Outcome, zline::RenderError<Infallible>> {
    let mut crc = Crc32Sink::new();
    // Once per mesh, outside the timed frame.
    let sphere = zline::bounding_sphere(scene.mesh)?;
    frame::render_frame(
        renderer,
        cache,
        scene.mesh,
        sphere,
        (scene.yaw, scene.pitch),
        &mut crc,
    )?;
    let mut discard = FnSink(
        |_: u16, _: &[Rgb565], _: &[<S::Depth as DepthFormat>::Value]| Ok::<(), Infallible>(()),
    );
    let (result, ticks) = ticks(syst, || {
        frame::render_frame(
            renderer,
            cache,
            scene.mesh,
            sphere,
            (scene.yaw, scene.pitch),
            &mut discard,
        )
    });
    let (_, stats) = result?;
    Ok(Outcome {
        crc: crc.value(),
        ticks,
        stats,
    })
}

/// A painted renderer's frame of a scene (`frame::render_frame_painted`),
/// for every z16 painted renderer whose mode `frame` can draw.
trait PaintedFrame {
    fn frame<K: zline::RowSink<Rgb565, u16>>(
        &mut self,
        mesh: &QuantizedMesh<'static>,
        sphere: (zline::Vec3, f32),
        view: (f32, f32),
        sink: &mut K,
    ) -> Result<(zline::DrawStats, FrameStats), zline::RenderError<K::Error>>;
}

impl<T, S, C, A> PaintedFrame for zline::paint::PaintedRenderer<T, S, C, A>
where
    T: zline::TableStorage<Color = u16>,
    S: ScanStorage<Color = u16, Depth = Depth16>,
    C: zline::CacheStorage,
    A: zline::paint::PaintStorage,
    A::Mode: zline::paint::PaintMode<Color = Rgb565, Source: frame::VertexSource>,
{
    fn frame<K: zline::RowSink<Rgb565, u16>>(
        &mut self,
        mesh: &QuantizedMesh<'static>,
        sphere: (zline::Vec3, f32),
        view: (f32, f32),
        sink: &mut K,
    ) -> Result<(zline::DrawStats, FrameStats), zline::RenderError<K::Error>> {
        frame::render_frame_painted(self, mesh, sphere, view, sink)
    }
}

/// A painted scene: its CRC and the instructions of a second, discarded
/// frame.
fn run_painted<R: PaintedFrame>(
    renderer: &mut R,
    scene: &Scene,
    syst: &mut SYST,
) -> Result<Outcome, zline::RenderError<Infallible>> {
    let mut crc = Crc32Sink::new();
    let sphere = zline::bounding_sphere(scene.mesh)?;
    let view = (scene.yaw, scene.pitch);
    renderer.frame(scene.mesh, sphere, view, &mut crc)?;
    let mut discard = FnSink(|_: u16, _: &[Rgb565], _: &[u16]| Ok::<(), Infallible>(()));
    let (result, ticks) = ticks(syst, || {
        renderer.frame(scene.mesh, sphere, view, &mut discard)
    });
    let (_, stats) = result?;
    Ok(Outcome {
        crc: crc.value(),
        ticks,
        stats,
    })
}

/// Runs painted scenes and prints a line for each (`shade=NAME ...`);
/// whether every CRC matched.
fn painted_scenes<R: PaintedFrame>(
    shade: &str,
    scenes: &[Scene],
    renderer: &mut R,
    syst: &mut SYST,
    per_tick: u32,
) -> bool {
    let mut all_ok = true;
    for scene in scenes {
        match run_painted(renderer, scene, syst) {
            Ok(o) => {
                let ok = o.crc == scene.expected_crc;
                all_ok &= ok;
                hprintln!(
                    "shade={} scene={} yaw={} pitch={} depth=z16 crc32={:08X} expected={:08X} {} instructions={} polygons={} peak_active_polygons={}",
                    shade,
                    scene.name,
                    scene.yaw,
                    scene.pitch,
                    o.crc,
                    scene.expected_crc,
                    if ok { "ok" } else { "MISMATCH" },
                    u64::from(o.ticks) * u64::from(per_tick),
                    o.stats.polygons,
                    o.stats.peak_active_polygons
                );
            }
            Err(e) => {
                all_ok = false;
                hprintln!("shade={} scene={} error: {}", shade, scene.name, e);
            }
        }
    }
    all_ok
}

/// What the firmware prints when every check passed (`.ci/run` reads it).
const PASSED: &str = "all frames match the host";

#[entry]
fn main() -> ! {
    let stack_floor = stack::paint();
    let Some(mut peripherals) = cortex_m::Peripherals::take() else {
        finish(false, PASSED)
    };
    let syst = &mut peripherals.SYST;
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(0x00FF_FFFF);
    syst.enable_counter();
    let per_tick = instructions_per_tick(syst);
    hprintln!(
        "zline on qemu {} ({} code), {}x{}, SysTick tick = {} instructions",
        env!("ZLINE_QEMU_BOARD"),
        env!("ZLINE_QEMU_TARGET"),
        frame::SIZE,
        frame::SIZE,
        per_tick
    );

    let z16 = RENDERER16.take();
    let z24 = RENDERER24.take();
    let cache = CACHE.take();
    let mut all_ok = true;
    for scene in &SCENES {
        let outcome = match scene.depth {
            DepthKind::Z16 => run(z16, cache, scene, syst),
            DepthKind::Z24 => run(z24, cache, scene, syst),
        };
        let depth = match scene.depth {
            DepthKind::Z16 => Depth16::NAME,
            DepthKind::Z24 => Depth24::NAME,
        };
        match outcome {
            Ok(o) => {
                let ok = o.crc == scene.expected_crc;
                all_ok &= ok;
                hprintln!(
                    "scene={} yaw={} pitch={} depth={} crc32={:08X} expected={:08X} {} instructions={} polygons={} edges={} peak_active_polygons={}",
                    scene.name,
                    scene.yaw,
                    scene.pitch,
                    depth,
                    o.crc,
                    scene.expected_crc,
                    if ok { "ok" } else { "MISMATCH" },
                    u64::from(o.ticks) * u64::from(per_tick),
                    o.stats.polygons,
                    o.stats.edges,
                    o.stats.peak_active_polygons
                );
            }
            Err(e) => {
                all_ok = false;
                hprintln!("scene={} depth={} error: {}", scene.name, depth, e);
            }
        }
    }
    all_ok &= painted_scenes("gouraud", &GOURAUD_SCENES, GOURAUD16.take(), syst, per_tick);
    all_ok &= painted_scenes(
        "texture",
        &TEXTURED_SCENES,
        TEXTURED16.take(),
        syst,
        per_tick,
    );
    all_ok &= painted_scenes(
        "lit-texture",
        &LIT_TEXTURED_SCENES,
        LIT_TEXTURED16.take(),
        syst,
        per_tick,
    );
    // The same z16 scenes by the full-frame z-buffer: the same frames (the
    // CRCs the scanline must match), 230 KB of depth and colour.
    let mut z = ZBuffer {
        depth: Z_DEPTH.take(),
        color: Z_COLOR.take(),
        scratch: Z_SCRATCH.take(),
        active: Z_ACTIVE.take(),
        pool: Z_POOL.take(),
    };
    for scene in SCENES.iter().filter(|s| matches!(s.depth, DepthKind::Z16)) {
        match run_zbuffer(z16, &mut z, cache, scene, syst) {
            Ok((crc, ticks)) => {
                let ok = crc == scene.expected_crc;
                all_ok &= ok;
                hprintln!(
                    "method=zbuffer scene={} yaw={} pitch={} depth=z16 crc32={:08X} expected={:08X} {} instructions={} buffer_bytes={}",
                    scene.name,
                    scene.yaw,
                    scene.pitch,
                    crc,
                    scene.expected_crc,
                    if ok { "ok" } else { "MISMATCH" },
                    u64::from(ticks) * u64::from(per_tick),
                    FRAME_PIXELS * 4
                );
            }
            Err(e) => {
                all_ok = false;
                hprintln!("method=zbuffer scene={} error: {}", scene.name, e);
            }
        }
    }
    let renderer_bytes = core::mem::size_of::<Renderer16>()
        + core::mem::size_of::<Renderer24>()
        + core::mem::size_of::<VertexCache<VM>>();
    hprintln!(
        "stack_high_water_bytes={} renderer_static_bytes={} gouraud_renderer_static_bytes={} textured_renderer_static_bytes={}",
        stack::high_water(stack_floor),
        renderer_bytes,
        core::mem::size_of::<Gouraud16>(),
        core::mem::size_of::<Textured16>()
    );
    finish(all_ok, PASSED)
}

/// Stack painting: fill the free stack with a pattern at boot, then find how
/// far down it was overwritten.
mod stack {
    const PATTERN: u32 = 0x5A5A_A5A5;

    unsafe extern "C" {
        /// End of .bss (cortex-m-rt): the stack may grow down to here.
        static mut __ebss: u32;
        /// Top of the stack (cortex-m-rt: the end of RAM).
        static mut _stack_start: u32;
    }

    /// Paints from the end of .bss up to just below the current stack
    /// pointer; returns the lowest painted address.
    pub fn paint() -> usize {
        let floor = (&raw const __ebss) as usize;
        let sp = cortex_m::register::msp::read() as usize;
        let mut at = floor;
        while at + 64 < sp {
            // SAFETY: [floor, sp - 64) is free RAM between .bss and the
            // live stack; nothing else uses it yet.
            unsafe { core::ptr::write_volatile(at as *mut u32, PATTERN) };
            at += 4;
        }
        floor
    }

    /// Bytes of stack used so far: from the top of RAM down to the lowest
    /// word no longer holding the pattern.
    pub fn high_water(floor: usize) -> usize {
        let stack_top = (&raw const _stack_start) as usize;
        let mut at = floor;
        // SAFETY: reads of RAM inside [floor, stack_top).
        while at < stack_top && unsafe { core::ptr::read_volatile(at as *const u32) } == PATTERN {
            at += 4;
        }
        stack_top - at
    }
}
