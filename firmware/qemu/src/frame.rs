//! One frame of a scene, exactly as both sides compute it: the firmware on
//! the emulated Cortex-M and its build script on the host (which includes
//! this file to produce the expected CRCs). Same code, same `f32`
//! arithmetic, same pixels.

use embedded_graphics_core::pixelcolor::Rgb565;
use zline::geometry::Vec3;
use zline::mesh::StaticMesh;
use zline::scene::{Camera, Cull, DrawStats, VertexCache, draw_mesh, reference_model_around};
use zline::shade::Shading;
use zline::{DepthFormat, FrameStats, RenderError, Renderer, RowSink};

/// Frame width and height.
pub const SIZE: u16 = 240;

/// Draws `mesh`, whose bounding sphere is `(centre, radius)` (computed once
/// per mesh), in the reference view at `yaw`/`pitch` (Lambert, back faces
/// culled) and sends the frame to `sink`.
#[allow(clippy::too_many_arguments)]
pub fn render_frame<
    D,
    S,
    const W: usize,
    const V: usize,
    const P: usize,
    const E: usize,
    const AP: usize,
    const AE: usize,
    const VM: usize,
>(
    renderer: &mut Renderer<Rgb565, D, W, V, P, E, AP, AE>,
    cache: &mut VertexCache<VM>,
    mesh: &StaticMesh<'_>,
    (centre, radius): (Vec3, f32),
    yaw: f32,
    pitch: f32,
    sink: &mut S,
) -> Result<(DrawStats, FrameStats), RenderError<S::Error>>
where
    D: DepthFormat,
    S: RowSink<Rgb565, D::Value>,
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
