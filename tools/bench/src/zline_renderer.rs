//! zline behind the [`Renderer`] trait. Everything that depends on zline's
//! rendering API is in this file, so an API change is adapted here alone.

use zline::Mat4 as ZMat4;
use zline::Shading;
use zline::host::{BandedRenderer, host_renderer};
use zline::{Camera, Cull as ZCull, FaceInfo, VertexCache, draw_mesh, reference_model};
use zline::{Depth16, FrameBufferSink};
use zline_lab::methods::HostScanline;

use crate::framebuffer::Frame565;
use crate::renderer::Renderer;
use crate::view::{Cull, Scene, View};

/// zline's scanline core with 16-bit depth, in `Vec` storage sized for the
/// mesh.
///
/// Timed region (one frame): clear the tables, `draw_mesh` (transform
/// every vertex with the model matrix from
/// `zline::reference_model` and `Camera::reference`; cull,
/// when `--cull back`, faces running clockwise on screen; clip; project;
/// shade each face with `Shading::lambert()`, converted to Rgb565; offer
/// it to the tables), then prepare the tables (bucket sort by first row)
/// and scan every row with the one z row, drawn straight into its row of
/// the same Rgb565 frame the peers draw into (`FrameBufferSink`, zline's
/// colour type being the frame's raw `u16`). Shading: each face's colour
/// from the same per-face Lambert table the peers use
/// ([`Scene::face_colors`], computed before timing); zline's shading
/// closure looks it up by face id. Face ids (untimed) come from a second,
/// host-sized render of the same view.
pub struct ZlineRenderer<'a> {
    scene: &'a Scene,
    renderer: zline::host::HostRenderer<u16, Depth16>,
    cache: Box<VertexCache<65536>>,
    frame: Frame565,
    model: ZMat4,
    camera: Camera,
    cull: ZCull,
    colors: Vec<u16>,
    view: View,
}

impl<'a> ZlineRenderer<'a> {
    /// Builds the renderer for `view`, its tables sized for the mesh.
    pub fn new(scene: &'a Scene, view: &View) -> Result<Self, String> {
        let mesh = &scene.mesh;
        let renderer = host_renderer(
            &scene.mesh.capacities(view.width),
            view.width,
            view.height,
            0,
        )
        .map_err(|e| format!("zline: {e}"))?;
        let model = reference_model(mesh, view.yaw_deg, view.pitch_deg)
            .map_err(|e| format!("zline: {e}"))?;
        Ok(Self {
            scene,
            renderer,
            cache: Box::default(),
            frame: Frame565::new(usize::from(view.width), usize::from(view.height)),
            model,
            camera: Camera::reference(view.width, view.height),
            cull: match view.cull {
                Cull::None => ZCull::None,
                Cull::Back => ZCull::Back,
            },
            colors: scene.face_colors(view),
            view: *view,
        })
    }
}

impl Renderer for ZlineRenderer<'_> {
    fn name(&self) -> &str {
        "zline"
    }

    fn render(&mut self) -> Result<(), String> {
        self.renderer.clear();
        let colors = &self.colors;
        draw_mesh(
            &mut self.renderer,
            &mut *self.cache,
            &self.scene.mesh,
            &self.model,
            &self.camera,
            self.cull,
            |f| colors[f.face as usize],
        )
        .map_err(|e| format!("zline: {e}"))?;
        let width = self.frame.width;
        self.renderer
            .render(&mut FrameBufferSink::new(&mut self.frame.pixels, width))
            .map(|_| ())
            .map_err(|e| format!("zline: {e:?}"))
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        let mut host = HostScanline::<Depth16>::new(self.view.width, self.view.height)
            .map_err(|e| format!("zline: {e}"))?;
        host.render(
            &self.scene.mesh,
            &self.model,
            &self.camera,
            self.cull,
            &Shading::FaceId,
        )
        .map_err(|e| format!("zline: {e}"))?;
        Ok(Some(host.frame().faces.clone()))
    }

    fn rgb565(&self) -> Vec<u16> {
        self.frame.pixels.clone()
    }
}

/// zline drawing the frame in horizontal bands on several threads
/// ([`BandedRenderer::render_mesh`]): the threads, started once a frame,
/// project the mesh's vertices and sort its faces into the bands their
/// rows reach (both in chunks), then each builds its band's tables from
/// that projection and its faces and scans its rows into its own part of
/// the frame. The same frame as [`ZlineRenderer`], bit for bit. Timed by
/// the wall clock, not thread CPU time (the work is on several threads);
/// the timed region is [`ZlineRenderer`]'s.
pub struct ZlineBandsRenderer<'a> {
    scene: &'a Scene,
    renderer: BandedRenderer<u16, Depth16>,
    frame: Frame565,
    model: ZMat4,
    camera: Camera,
    cull: ZCull,
    colors: Vec<u16>,
    name: String,
}

impl<'a> ZlineBandsRenderer<'a> {
    /// Builds the renderer for `view` with `threads` bands, each band's
    /// tables sized as [`ZlineRenderer`]'s.
    pub fn new(scene: &'a Scene, view: &View, threads: usize) -> Result<Self, String> {
        let single = ZlineRenderer::new(scene, view)?;
        let renderer = BandedRenderer::new(
            &scene.mesh.capacities(view.width),
            view.width,
            view.height,
            0,
            threads,
        )
        .map_err(|e| format!("zline: {e}"))?;
        Ok(Self {
            scene,
            renderer,
            frame: single.frame,
            model: single.model,
            camera: single.camera,
            cull: single.cull,
            colors: single.colors,
            name: format!("zline-{threads}-threads"),
        })
    }
}

impl Renderer for ZlineBandsRenderer<'_> {
    fn name(&self) -> &str {
        &self.name
    }

    fn wall_clock(&self) -> bool {
        true
    }

    fn render(&mut self) -> Result<(), String> {
        let width = self.frame.width;
        // Each band draws into its own rows of the frame.
        let mut rest = &mut self.frame.pixels[..];
        let mut sinks = Vec::new();
        for rows in self.renderer.bands() {
            let (part, tail) = rest.split_at_mut(rows.len() * width);
            rest = tail;
            sinks.push(FrameBufferSink::from_row(part, width, rows.start));
        }
        let colors = &self.colors;
        self.renderer
            .render_mesh(
                &self.scene.mesh,
                &self.model,
                &self.camera,
                self.cull,
                &mut sinks,
                |f: &FaceInfo| colors[f.face as usize],
            )
            .map(|_| ())
            .map_err(|e| format!("zline: {e:?}"))
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        Ok(None)
    }

    fn rgb565(&self) -> Vec<u16> {
        self.frame.pixels.clone()
    }
}
