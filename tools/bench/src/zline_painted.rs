//! zline's painted renderer (Gouraud and textured rows) behind the
//! [`Renderer`] trait, driven as docs/guide/shading.md shows a user:
//! `HostPaintedRenderer::<M, Depth24>::for_mesh` once per view, then each
//! frame `renderer.clear()`, `renderer.draw_mesh(&mesh, &model, &camera,
//! cull, shade)` and `renderer.render(sink)`, the mesh read with
//! `HostMesh::from_obj_smooth`.

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use zline::host::{HostPaintedRenderer, HostRenderer};
use zline::paint::{Gouraud, PaintMode, Textured};
use zline::{Camera, Cull as ZCull, Depth24, FrameBufferSink, Mat4, Shading, reference_model};

use crate::renderer::Renderer;
use crate::view::{BACKGROUND, Cull, Scene, View};
use crate::zline_renderer::{CLOSED_MESHES, PlainTarget};

/// A paint mode the bench times: its row name, its timed region and the
/// per-vertex closure its frame draws with.
pub trait PaintKind: PaintMode<Color = Rgb565> + Sized {
    /// The row's name.
    const NAME: &'static str;

    /// What the frame's `draw_mesh` computes per vertex.
    const SHADE: &'static str;

    /// `renderer.draw_mesh(..)` with this mode's closure; the closure's
    /// inputs (the Lambert light) are made inside, so inside the frame.
    fn draw(
        renderer: &mut HostPaintedRenderer<Self, Depth24>,
        scene: &Scene,
        model: &Mat4,
        camera: &Camera,
        cull: ZCull,
    ) -> Result<(), String>;
}

impl PaintKind for Gouraud<Rgb565> {
    const NAME: &'static str = "zline gouraud z24";
    const SHADE: &'static str = "`Shading::lambert()`, `renderer.draw_mesh(.., |v| \
        shading.vertex_color(v))` (transform, cull, clip, project; per vertex its view-space \
        normal normalised and lit one-sided, 8.8 fixed-point colour), `Gouraud::new()` \
        (channels interpolated as screen-space planes, 4x4 Bayer dither to Rgb565)";

    fn draw(
        renderer: &mut HostPaintedRenderer<Self, Depth24>,
        scene: &Scene,
        model: &Mat4,
        camera: &Camera,
        cull: ZCull,
    ) -> Result<(), String> {
        let shading = Shading::lambert();
        renderer
            .draw_mesh(&scene.mesh, model, camera, cull, |v| {
                shading.vertex_color(v)
            })
            .map(|_| ())
            .map_err(|e| format!("zline: {e}"))
    }
}

impl PaintKind for Textured<'_, Rgb565> {
    const NAME: &'static str = "zline textured z24";
    const SHADE: &'static str = "`renderer.draw_mesh(.., |v| v.tex_coord())` (transform, cull, \
        clip, project; per vertex its `vt` and clip w), `Textured::new(texture)` \
        (perspective-correct: u/w, v/w, 1/w planes, divided exactly at the ends of spans of up \
        to 16 px and stepped between; nearest texel, repeat; unlit)";

    fn draw(
        renderer: &mut HostPaintedRenderer<Self, Depth24>,
        scene: &Scene,
        model: &Mat4,
        camera: &Camera,
        cull: ZCull,
    ) -> Result<(), String> {
        renderer
            .draw_mesh(&scene.mesh, model, camera, cull, |v| v.tex_coord())
            .map(|_| ())
            .map_err(|e| format!("zline: {e}"))
    }
}

/// zline's painted scanline renderer with 24-bit depth, sized for the
/// smooth mesh (`HostPaintedRenderer::for_mesh`), painting with `M`.
///
/// Timed region (one frame): `renderer.clear()`, then [`PaintKind::draw`]
/// (the light, if any, made inside the frame), then `renderer.render(..)`
/// into a `FrameBufferSink` over a `Vec<Rgb565>` frame, as the flat
/// `zline z24` row draws: every pixel of every row written, background
/// included (checked in [`Self::new`]), so no frame clear. Model matrix
/// and camera built once per view, untimed.
///
/// Face ids (untimed): zline's flat `HostRenderer<u32, Depth24>` drawing
/// the same smooth mesh with `|f| f.face` (the painted scan decides
/// visibility with the same tables and depth; its rows hold slots, not
/// face ids, and the row sink sees colours only).
pub struct ZlinePaintedRenderer<'a, M: PaintKind> {
    scene: &'a Scene,
    renderer: HostPaintedRenderer<M, Depth24>,
    frame: PlainTarget,
    model: Mat4,
    camera: Camera,
    cull: ZCull,
    view: View,
}

impl<'a, M: PaintKind> ZlinePaintedRenderer<'a, M> {
    /// Builds the renderer for `view` painting with `mode`, and checks
    /// that a frame writes every pixel: rendered once into a frame filled
    /// with one colour and once into a frame filled with another, no
    /// pixel may keep its fill.
    pub fn new(scene: &'a Scene, view: &View, mode: M) -> Result<Self, String> {
        let renderer = HostPaintedRenderer::<M, Depth24>::for_mesh(
            &scene.mesh,
            view.width,
            view.height,
            mode,
            Rgb565::BLACK,
        )
        .map_err(|e| format!("{}: {e}", M::NAME))?;
        let model = reference_model(&scene.mesh, view.yaw_deg, view.pitch_deg)
            .map_err(|e| format!("{}: {e}", M::NAME))?;
        let mut r = Self {
            scene,
            renderer,
            frame: PlainTarget::new(usize::from(view.width), usize::from(view.height)),
            model,
            camera: Camera::reference(view.width, view.height),
            cull: match view.cull {
                Cull::None => ZCull::None,
                Cull::Back => ZCull::Back,
            },
            view: *view,
        };
        let fills = [Rgb565::new(31, 0, 31), Rgb565::new(0, 63, 0)];
        let mut frames = Vec::new();
        for fill in fills {
            r.frame.pixels.fill(fill);
            r.render()?;
            frames.push(r.frame.pixels.clone());
        }
        if frames[0] != frames[1] {
            return Err(format!("{}: a frame left pixels unwritten", M::NAME));
        }
        Ok(r)
    }
}

impl<M: PaintKind> Renderer for ZlinePaintedRenderer<'_, M> {
    fn name(&self) -> &str {
        M::NAME
    }

    fn timed_region(&self) -> String {
        format!(
            "`renderer.clear()` (its tables), {}, `renderer.render(..)` through \
             `FrameBufferSink`: each row painted in place in a `Vec<Rgb565>` frame, every pixel \
             written, background included, so no frame clear; mesh from \
             `HostMesh::from_obj_smooth(.., DEFAULT_CREASE_DEGREES)`; depth z24 in its one z row; \
             {}",
            M::SHADE,
            CLOSED_MESHES
        )
    }

    fn render(&mut self) -> Result<(), String> {
        self.renderer.clear();
        M::draw(
            &mut self.renderer,
            self.scene,
            &self.model,
            &self.camera,
            self.cull,
        )?;
        let width = self.frame.width;
        self.renderer
            .render(&mut FrameBufferSink::new(&mut self.frame.pixels, width))
            .map(|_| ())
            .map_err(|e| format!("{}: {e:?}", M::NAME))
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        let (w, h) = (self.view.width, self.view.height);
        let mut ids = HostRenderer::<u32, Depth24>::for_mesh(&self.scene.mesh, w, h, BACKGROUND)
            .map_err(|e| format!("zline: {e}"))?;
        ids.draw_mesh(
            &self.scene.mesh,
            &self.model,
            &self.camera,
            self.cull,
            |f| f.face,
        )
        .map_err(|e| format!("zline: {e}"))?;
        let mut out = vec![BACKGROUND; usize::from(w) * usize::from(h)];
        ids.render(&mut FrameBufferSink::new(&mut out, usize::from(w)))
            .map_err(|e| format!("zline: {e:?}"))?;
        Ok(Some(out))
    }

    fn rgb565(&self) -> Vec<u16> {
        self.frame.raw()
    }
}
