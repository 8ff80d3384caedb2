//! One firmware frame, exactly as both sides compute it: the firmware on
//! the RP2040 and its build script on the host (which includes this file
//! to produce each view's expected CRC-32). Same code, same integer front
//! end (the mesh is quantized), same pixels.

use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::prelude::IntoStorage;
use zline::DrawError;
use zline::Mesh;
use zline::Shading;
use zline::Vec3;
use zline::VertexInfo;
use zline::{CacheStorage, Camera, Cull, DrawStats, reference_model_around};
use zline::{DepthFormat, FrameStats, RenderError, Renderer, RowSink};
use zline::{ScanStorage, TableStorage};

/// A pixel as the ST7789 takes it: Rgb565 whose two bytes in memory are
/// big-endian, the wire's order. The scanner is generic over its colour,
/// so it stores these, and a finished row leaves by a plain copy of its
/// bytes (no per-pixel conversion).
pub type WireColor = u16;

/// Black, in wire order.
pub const WIRE_BLACK: WireColor = 0;

/// `c` in wire order.
pub fn wire(c: Rgb565) -> WireColor {
    u16::from_ne_bytes(c.into_storage().to_be_bytes())
}

/// Draws `mesh` (bounding sphere `(centre, radius)`, computed once) in the
/// reference view at `yaw`/`pitch` degrees, shaded by `shading` (made
/// once: its light's unit vector takes a square root) with back faces
/// culled, and sends the frame to `sink` row by row, in wire order
/// ([`WireColor`]).
#[allow(clippy::too_many_arguments)]
#[cfg_attr(
    any(feature = "gouraud", feature = "textured", feature = "dual-core"),
    allow(dead_code)
)]
pub fn render_frame<T, S, C, K, M>(
    renderer: &mut Renderer<T, S, C>,
    mesh: &M,
    shading: &Shading,
    (centre, radius): (Vec3, f32),
    (yaw, pitch): (f32, f32),
    sink: &mut K,
) -> Result<(DrawStats, FrameStats), RenderError<K::Error>>
where
    T: TableStorage<Color = WireColor>,
    S: ScanStorage<Color = WireColor>,
    C: CacheStorage,
    K: RowSink<WireColor, <S::Depth as DepthFormat>::Value>,
    M: Mesh,
{
    renderer.clear();
    let model = reference_model_around(centre, radius, yaw, pitch);
    let camera = Camera::reference(renderer.width(), renderer.height());
    let draw = renderer.draw_mesh(mesh, &model, &camera, Cull::Back, |f| {
        wire(Rgb565::from(shading.color(f)))
    })?;
    let frame = renderer.render(sink)?;
    Ok((draw, frame))
}

/// The scene of [`render_frame`] alone (feature `dual-core`, where two
/// cores scan it in bands): `renderer`'s tables cleared and `mesh` drawn
/// into them, as `render_frame` draws it.
///
/// On the board it runs from RAM (`.data`, which cortex-m-rt copies from
/// flash before `main`): core 1 runs it while core 0 scans rows with code
/// from flash, and the two cores' fetches from the XIP cache, one slave
/// of the bus, made one wait for the other (`tools/dual-core-check
/// --interleave contended`: the period ratio fell from 0.547 to 0.540).
/// The face loop, the tables' admission and the shading are inlined here
/// (about 10 KB); the functions it calls in flash are reached through the
/// linker's long-branch thunks.
#[cfg(feature = "dual-core")]
#[allow(dead_code)]
// The build script includes this file for `render_frame`.
// SAFETY: `.data.*` is linked into RAM with its image in flash and copied
// there by cortex-m-rt's reset handler before `main`, like any
// initialised static; the RP2040 executes from SRAM, and nothing writes
// this section after the copy.
#[cfg_attr(target_arch = "arm", unsafe(link_section = ".data.draw_scene"))]
pub fn draw_scene<T, S, C, M>(
    renderer: &mut Renderer<T, S, C>,
    mesh: &M,
    shading: &Shading,
    (centre, radius): (Vec3, f32),
    (yaw, pitch): (f32, f32),
) -> Result<DrawStats, DrawError>
where
    T: TableStorage<Color = WireColor>,
    S: ScanStorage<Color = WireColor>,
    C: CacheStorage,
    M: Mesh,
{
    renderer.clear();
    let model = reference_model_around(centre, radius, yaw, pitch);
    let camera = Camera::reference(renderer.width(), renderer.height());
    renderer.draw_mesh(mesh, &model, &camera, Cull::Back, |f| {
        wire(Rgb565::from(shading.color(f)))
    })
}

/// A Gouraud-painted pixel in wire order: the bytes of a [`WireColor`].
/// (The `gouraud` feature's colour: `zline::paint` quantises into any
/// [`PaintColor`](zline::paint::PaintColor), and this one is the LCD's.)
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[repr(transparent)]
#[allow(dead_code)] // The flat build uses the rest of this file only.
pub struct WirePixel(pub WireColor);

// SAFETY: a `repr(transparent)` wrapper of a `u16`: every bit pattern is
// valid, there is no padding, and zero is a valid value.
unsafe impl bytemuck::Zeroable for WirePixel {}
// SAFETY: as above; `u16` is `Pod` and the wrapper adds nothing.
unsafe impl bytemuck::Pod for WirePixel {}

impl zline::paint::PaintColor for WirePixel {
    const MAX: [u32; 3] = <Rgb565 as zline::paint::PaintColor>::MAX;

    #[inline(always)]
    fn from_levels(levels: [u32; 3]) -> Self {
        WirePixel(wire(<Rgb565 as zline::paint::PaintColor>::from_levels(
            levels,
        )))
    }
}

/// What a painted frame gives each vertex, by its paint mode's source:
/// Gouraud's colour (each vertex lit by `shading` and its normal, the
/// quantized mesh's, rotated and lit in integers) or texture mapping's
/// coordinates (the quantized mesh's, with no floating point; `shading`
/// is not used).
#[allow(dead_code)] // The flat build uses the rest of this file only.
pub trait VertexSource {
    /// The source of `vertex`.
    fn of(shading: &Shading, vertex: &VertexInfo<'_>) -> Self;
}

impl VertexSource for zline::paint::Rgb8p8 {
    fn of(shading: &Shading, vertex: &VertexInfo<'_>) -> Self {
        shading.vertex_color(vertex)
    }
}

impl VertexSource for zline::paint::TexCoord {
    fn of(_: &Shading, vertex: &VertexInfo<'_>) -> Self {
        vertex.tex_coord()
    }
}

/// [`render_frame`] painted by the renderer's mode (`zline::paint`), each
/// vertex's [`VertexSource`] interpolated over each polygon: Gouraud (the
/// colours dithered to Rgb565) or texture mapping (perspective-correct,
/// nearest texels).
#[allow(dead_code)] // The flat build uses the rest of this file only.
pub fn render_frame_painted<T, S, C, A, K, M>(
    renderer: &mut zline::paint::PaintedRenderer<T, S, C, A>,
    mesh: &M,
    shading: &Shading,
    (centre, radius): (Vec3, f32),
    (yaw, pitch): (f32, f32),
    sink: &mut K,
) -> Result<(DrawStats, FrameStats), RenderError<K::Error>>
where
    T: TableStorage<Color = u16>,
    S: ScanStorage<Color = u16>,
    C: CacheStorage,
    A: zline::paint::PaintStorage,
    A::Mode: zline::paint::PaintMode<Color = WirePixel, Source: VertexSource>,
    K: RowSink<WirePixel, <S::Depth as DepthFormat>::Value>,
    M: Mesh,
{
    let draw = draw_scene_painted(renderer, mesh, shading, (centre, radius), (yaw, pitch))?;
    let frame = renderer.render(sink)?;
    Ok((draw, frame))
}

/// The scene of [`render_frame_painted`] alone: `renderer`'s tables
/// cleared and `mesh` drawn into them with each vertex's value (feature
/// `dual-core`: two cores scan it in bands).
#[allow(dead_code)] // The flat build uses the rest of this file only.
pub fn draw_scene_painted<T, S, C, A, M>(
    renderer: &mut zline::paint::PaintedRenderer<T, S, C, A>,
    mesh: &M,
    shading: &Shading,
    (centre, radius): (Vec3, f32),
    (yaw, pitch): (f32, f32),
) -> Result<DrawStats, DrawError>
where
    T: TableStorage<Color = u16>,
    S: ScanStorage<Color = u16>,
    C: CacheStorage,
    A: zline::paint::PaintStorage,
    A::Mode: zline::paint::PaintMode<Color = WirePixel, Source: VertexSource>,
    M: Mesh,
{
    renderer.clear();
    let model = reference_model_around(centre, radius, yaw, pitch);
    let camera = Camera::reference(renderer.width(), renderer.height());
    renderer.draw_mesh(mesh, &model, &camera, Cull::Back, |v| {
        VertexSource::of(shading, v)
    })
}
