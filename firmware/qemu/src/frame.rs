//! One frame of a scene, exactly as both sides compute it: the firmware on
//! the emulated Cortex-M and its build script on the host (which includes
//! this file to produce the expected CRCs). Same code, same arithmetic
//! (the meshes are quantized, so the integer front end draws them), same
//! pixels.

use embedded_graphics_core::pixelcolor::Rgb565;
use zline::Mesh;
use zline::Shading;
use zline::Vec3;
use zline::VertexInfo;
use zline::{Camera, Cull, DrawStats, VertexCache, draw_mesh, reference_model_around};
use zline::{DepthFormat, FrameStats, RenderError, Renderer, RowSink};
use zline::{ScanStorage, TableStorage};

/// Frame width and height.
pub const SIZE: u16 = 240;

/// Draws `mesh`, whose bounding sphere is `(centre, radius)` (computed once
/// per mesh), in the reference view at `yaw`/`pitch` (Lambert, back faces
/// culled) and sends the frame to `sink`.
pub fn render_frame<T, S, C, K, M, const VM: usize>(
    renderer: &mut Renderer<T, S, C>,
    cache: &mut VertexCache<VM>,
    mesh: &M,
    (centre, radius): (Vec3, f32),
    (yaw, pitch): (f32, f32),
    sink: &mut K,
) -> Result<(DrawStats, FrameStats), RenderError<K::Error>>
where
    T: TableStorage<Color = Rgb565>,
    S: ScanStorage<Color = Rgb565>,
    K: RowSink<Rgb565, <S::Depth as DepthFormat>::Value>,
    M: Mesh,
{
    renderer.clear();
    let model = reference_model_around(centre, radius, yaw, pitch);
    let camera = Camera::reference(SIZE, SIZE);
    let shading = Shading::lambert();
    let draw = draw_mesh(renderer, cache, mesh, &model, &camera, Cull::Back, |f| {
        Rgb565::from(shading.color(f))
    })?;
    let frame = renderer.render(sink)?;
    Ok((draw, frame))
}

/// [`render_frame`] by the full-frame z-buffer instead of the scanline
/// (`zline::zbuffer`, with the same tables, formats and fill rule):
/// the frame must be the scanline's, bit for bit. `buffers` holds the
/// frame's depth and colour.
#[allow(dead_code)] // The build script includes this file but only needs `render_frame`.
pub fn render_frame_zbuffer<T, D, K, M, const VM: usize>(
    tables: &mut zline::Tables<T>,
    cache: &mut VertexCache<VM>,
    mesh: &M,
    (centre, radius): (Vec3, f32),
    (yaw, pitch): (f32, f32),
    buffers: zline::zbuffer::BandBuffers<'_, Rgb565, D>,
    sink: &mut K,
) -> Result<(DrawStats, zline::zbuffer::BandStats), RenderError<K::Error>>
where
    T: TableStorage<Color = Rgb565>,
    D: DepthFormat,
    K: RowSink<Rgb565, D::Value>,
    M: Mesh,
{
    use embedded_graphics_core::pixelcolor::RgbColor;
    use zline::zbuffer::{DepthTest, render_bands};
    tables.clear();
    let model = reference_model_around(centre, radius, yaw, pitch);
    let camera = Camera::reference(SIZE, SIZE);
    let shading = Shading::lambert();
    let draw = draw_mesh(tables, cache, mesh, &model, &camera, Cull::Back, |f| {
        Rgb565::from(shading.color(f))
    })?;
    let prepared = tables.in_drawing_order();
    let stats = render_bands(
        &prepared,
        buffers,
        SIZE,
        Rgb565::BLACK,
        DepthTest::Nearer,
        None,
        sink,
    )?;
    Ok((draw, stats))
}

/// What a painted frame gives each vertex, by its paint mode's source:
/// Gouraud's colour (each vertex lit by `shading` and its normal, the
/// quantized mesh's, rotated in integers) or texture mapping's
/// coordinates (the quantized mesh's, with no floating point).
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

/// Lit texture mapping's: the coordinates, and the light of `shading`
/// (its warm white surface colour, the light's colour here) at the vertex.
impl VertexSource for zline::paint::LitTexCoord {
    fn of(shading: &Shading, vertex: &VertexInfo<'_>) -> Self {
        Self::new(vertex.tex_coord(), shading.vertex_color(vertex))
    }
}

/// [`render_frame`] painted by the renderer's mode (`zline::paint`), each
/// vertex's [`VertexSource`] interpolated over each polygon: Gouraud
/// (the same view and light, colours dithered to `Rgb565`) or texture
/// mapping (perspective-correct, nearest texels).
#[allow(dead_code)] // Each side uses its own subset of this file.
pub fn render_frame_painted<T, S, C, A, K, M>(
    renderer: &mut zline::paint::PaintedRenderer<T, S, C, A>,
    mesh: &M,
    (centre, radius): (Vec3, f32),
    (yaw, pitch): (f32, f32),
    sink: &mut K,
) -> Result<(DrawStats, FrameStats), RenderError<K::Error>>
where
    T: TableStorage<Color = u16>,
    S: ScanStorage<Color = u16>,
    C: zline::CacheStorage,
    A: zline::paint::PaintStorage,
    A::Mode: zline::paint::PaintMode<Color = Rgb565, Source: VertexSource>,
    K: RowSink<Rgb565, <S::Depth as DepthFormat>::Value>,
    M: Mesh,
{
    renderer.clear();
    let model = reference_model_around(centre, radius, yaw, pitch);
    let camera = Camera::reference(SIZE, SIZE);
    let shading = Shading::lambert();
    let draw = renderer.draw_mesh(mesh, &model, &camera, Cull::Back, |v| {
        VertexSource::of(&shading, v)
    })?;
    let frame = renderer.render(sink)?;
    Ok((draw, frame))
}
