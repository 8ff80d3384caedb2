//! zline behind the [`Renderer`] trait. Everything that depends on zline's
//! rendering API is in this file, so an API change is adapted here alone.

use zline::Depth16;
use zline::geometry::Mat4 as ZMat4;
use zline::methods::HostScanline;
use zline::scene::{Camera, Cull as ZCull, reference_model};
use zline::shade::Shading;

use crate::renderer::Renderer;
use crate::view::{Cull, Scene, View, rgb565};

/// zline's scanline core with 16-bit depth, host-sized
/// (`zline::methods::HostScanline<Depth16>`).
///
/// Timed region (one `HostScanline::render` call): clear the polygon
/// tables, transform every vertex (model matrix from
/// `zline::scene::reference_model`, `Camera::reference`), cull (when
/// `--cull back`: faces running clockwise on screen, by their projected
/// winding), clip, project, shade each face (`Shading::lambert()`), build
/// the edge and polygon tables, scan every row with the z row, and copy
/// each finished row into the host frame (face id, Rgb888 colour and depth
/// per pixel). Gives face ids.
pub struct ZlineRenderer<'a> {
    scene: &'a Scene,
    host: HostScanline<Depth16>,
    model: ZMat4,
    camera: Camera,
    cull: ZCull,
    shading: Shading,
}

impl<'a> ZlineRenderer<'a> {
    /// Builds the renderer for `view` (about 20 MB on the stack first:
    /// call on a thread with a large stack).
    pub fn new(scene: &'a Scene, view: &View) -> Result<Self, String> {
        let host = HostScanline::<Depth16>::new(view.width, view.height)
            .map_err(|e| format!("zline: {e}"))?;
        let model = reference_model(&scene.mesh, view.yaw_deg, view.pitch_deg)
            .map_err(|e| format!("zline: {e}"))?;
        Ok(Self {
            scene,
            host,
            model,
            camera: Camera::reference(view.width, view.height),
            cull: match view.cull {
                Cull::None => ZCull::None,
                Cull::Back => ZCull::Back,
            },
            shading: Shading::lambert(),
        })
    }
}

impl Renderer for ZlineRenderer<'_> {
    fn name(&self) -> &str {
        "zline"
    }

    fn render(&mut self) -> Result<(), String> {
        self.host
            .render(
                &self.scene.mesh,
                &self.model,
                &self.camera,
                self.cull,
                &self.shading,
            )
            .map(|_| ())
            .map_err(|e| format!("zline: {e}"))
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        Ok(Some(self.host.frame().faces.clone()))
    }

    fn rgb565(&self) -> Vec<u16> {
        use embedded_graphics::pixelcolor::RgbColor;
        self.host
            .frame()
            .colors
            .iter()
            .map(|c| rgb565(c.r(), c.g(), c.b()))
            .collect()
    }
}
