//! zline behind the [`Renderer`] trait, driven as its README's "Draw an
//! OBJ file" shows a user: `HostRenderer::<Rgb565, D>::for_mesh`, then
//! each frame `renderer.clear()`, `let light = Shading::lambert();`,
//! `renderer.draw_mesh(&mesh, &model, &camera, cull, |f|
//! light.color(f).into())` and `renderer.render(sink)`. Everything that
//! depends on zline's rendering API is in this file, so an API change is
//! adapted here alone.

use core::convert::Infallible;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use zline::host::{BandedRenderer, HostRenderer};
use zline::{
    Camera, Cull as ZCull, Depth24, DepthFormat, DrawTargetSink, FaceInfo, FrameBufferSink, Mat4,
    RowSpan, Shading, reference_model,
};

use crate::renderer::Renderer;
use crate::view::{BACKGROUND, Cull, Scene, View};

/// What zline does with `--cull none` on a closed mesh, or one closed by
/// caps over its holes, in every zline row's timed region.
pub const CLOSED_MESHES: &str = "with `--cull none`, a mesh `HostMesh` finds closed, or closed \
    by caps over its holes (`HostMesh::closed_hull`, `HostMesh::hull_caps`), has its back faces \
    left out by zline itself where none can show (`ClosedHull`: the same pixels covered; near a \
    cap that faces the viewer, back faces are drawn)";

/// Where zline's finished rows go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Output {
    /// Drawn in place into the rows of a `Vec<Rgb565>` frame
    /// (`FrameBufferSink`, which lends the scanner each row).
    InPlace,
    /// Through `DrawTargetSink` into a [`PlainTarget`]: a `Vec<Rgb565>`
    /// that implements only `draw_iter`, so each row's `fill_contiguous`
    /// is embedded-graphics' default, pixel by pixel. As a program drawing
    /// frame after frame into one display does it: `changed_only`, so each
    /// row sends only the columns that differ from the frame before.
    DrawTarget,
    /// No rendering: each row's columns that a `DrawTarget` row sends once
    /// the picture stands still (the span of pixels that are not
    /// background), taken from a frame drawn once before timing, handed to
    /// the same [`PlainTarget`] by `fill_contiguous`. What that target
    /// alone charges for the pixels [`Output::DrawTarget`] gives it: the
    /// floor under a `drawtarget` row's time above zline in place.
    TargetAlone,
}

/// A W×H Rgb565 frame that is the plainest `DrawTarget` a user writes:
/// `draw_iter` only (bounds-checked, pixel by pixel), none of
/// `fill_contiguous`, `fill_solid` or `clear` (embedded-graphics' defaults
/// apply).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlainTarget {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Pixels, row-major from the top.
    pub pixels: Vec<Rgb565>,
}

impl PlainTarget {
    /// A black frame.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            pixels: vec![Rgb565::BLACK; width * height],
        }
    }

    /// The pixels as raw Rgb565.
    pub fn raw(&self) -> Vec<u16> {
        self.pixels
            .iter()
            .map(|&c| RawU16::from(c).into_inner())
            .collect()
    }
}

impl OriginDimensions for PlainTarget {
    fn size(&self) -> Size {
        Size::new(self.width as u32, self.height as u32)
    }
}

impl DrawTarget for PlainTarget {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(p, color) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as usize) < self.width && (p.y as usize) < self.height {
                self.pixels[p.y as usize * self.width + p.x as usize] = color;
            }
        }
        Ok(())
    }
}

/// A colour no Lambert face and no background can have: a frame filled
/// with it before one render must have none of it left.
const POISON: Rgb565 = Rgb565::new(31, 0, 31);

/// zline's scanline renderer with depth format `D` (`Depth16` or
/// `Depth24`), sized for the mesh (`HostRenderer::for_mesh`).
///
/// Timed region (one frame), what a user's frame loop does:
/// `renderer.clear()` (empties the tables), `let light =
/// Shading::lambert();`, `renderer.draw_mesh(&mesh, &model, &camera,
/// cull, |f| light.color(f).into())` (transform every vertex, cull when
/// `--cull back`, clip, project, Lambert per face: `Shading::color` to
/// `Rgb888`, converted to `Rgb565`; fill the tables), then
/// `renderer.render(sink)` (prepare the tables, scan every row) into the
/// [`Output`]. The scanner writes every pixel of every row, background
/// included, so the frame needs no clear of its own: [`Self::new`] checks
/// that by rendering once into a frame filled with a colour no pixel can
/// have. The model matrix (`reference_model`) and camera are built once
/// per view, untimed, as every peer's are.
///
/// Face ids (untimed): the same renderer type with `u32` colours drawing
/// `|f| f.face`, in place. Rows through a [`PlainTarget`] give none: their
/// frame is checked to equal the in-place one, pixel for pixel.
pub struct ZlineRenderer<'a, D: DepthFormat> {
    scene: &'a Scene,
    renderer: HostRenderer<Rgb565, D>,
    frame: PlainTarget,
    model: Mat4,
    camera: Camera,
    cull: ZCull,
    output: Output,
    /// What the [`PlainTarget`] shows of each row (`changed_only`).
    shown: Vec<RowSpan>,
    /// For [`Output::TargetAlone`]: the frame drawn once, and each row's
    /// span of pixels that are not background in it.
    stored: Option<(Vec<Rgb565>, Vec<RowSpan>)>,
    name: String,
    view: View,
}

impl<'a, D: DepthFormat> ZlineRenderer<'a, D> {
    /// Builds the renderer for `view`, checking that one frame writes
    /// every pixel.
    pub fn new(scene: &'a Scene, view: &View, output: Output) -> Result<Self, String> {
        let mesh = &scene.mesh;
        let renderer =
            HostRenderer::<Rgb565, D>::for_mesh(mesh, view.width, view.height, Rgb565::BLACK)
                .map_err(|e| format!("zline: {e}"))?;
        let model = reference_model(mesh, view.yaw_deg, view.pitch_deg)
            .map_err(|e| format!("zline: {e}"))?;
        let name = match output {
            Output::InPlace => format!("zline {}", D::NAME),
            Output::DrawTarget => format!("zline {} drawtarget", D::NAME),
            Output::TargetAlone => format!("zline {} target alone", D::NAME),
        };
        let mut r = Self {
            scene,
            renderer,
            frame: PlainTarget::new(usize::from(view.width), usize::from(view.height)),
            model,
            camera: Camera::reference(view.width, view.height),
            cull: zline_cull(view.cull),
            output: if output == Output::TargetAlone {
                Output::InPlace
            } else {
                output
            },
            shown: vec![RowSpan::UNKNOWN; usize::from(view.height)],
            stored: None,
            name,
            view: *view,
        };
        r.frame.pixels.fill(POISON);
        r.render()?;
        if r.frame.pixels.contains(&POISON) {
            return Err(format!("{}: a frame left pixels unwritten", r.name));
        }
        if output == Output::TargetAlone {
            // The frame, and the columns of each row a still picture sends:
            // what `DrawTargetSink::changed_only` notes in `shown` as the
            // frame goes out once through it.
            r.output = Output::DrawTarget;
            r.render()?;
            r.stored = Some((r.frame.pixels.clone(), r.shown.clone()));
            r.output = Output::TargetAlone;
        }
        Ok(r)
    }
}

fn zline_cull(cull: Cull) -> ZCull {
    match cull {
        Cull::None => ZCull::None,
        Cull::Back => ZCull::Back,
    }
}

impl<D: DepthFormat> Renderer for ZlineRenderer<'_, D> {
    fn name(&self) -> &str {
        &self.name
    }

    fn timed_region(&self) -> String {
        let sink = match self.output {
            Output::InPlace => {
                "`FrameBufferSink`: each row drawn in place in a `Vec<Rgb565>` frame, every \
                 pixel written, background included, so no frame clear"
            }
            Output::DrawTarget => {
                "`DrawTargetSink::new(..).changed_only(..)` into a `Vec<Rgb565>` `DrawTarget` \
                 with `draw_iter` only (`fill_contiguous` falls back to pixel by pixel), each \
                 row sending the columns that changed since the frame before"
            }
            Output::TargetAlone => {
                return "no rendering: each row's span of pixels that are not background \
                        (what `changed_only` sends of a still picture), from a frame drawn \
                        before timing, handed by `fill_contiguous` to the `Vec<Rgb565>` \
                        `DrawTarget` of the drawtarget rows (`draw_iter` only): that target's \
                        own cost for the pixels the drawtarget rows send"
                    .to_string();
            }
        };
        format!(
            "`renderer.clear()` (its tables), `Shading::lambert()`, `renderer.draw_mesh(.., \
             |f| light.color(f).into())` (transform, cull, clip, project, Lambert per face), \
             `renderer.render(..)` through {sink}; depth {} in its one z row; {}",
            D::NAME,
            CLOSED_MESHES
        )
    }

    fn render(&mut self) -> Result<(), String> {
        if let (Output::TargetAlone, Some((pixels, spans))) = (self.output, &self.stored) {
            let width = self.frame.width;
            for (y, (span, row)) in spans.iter().zip(pixels.chunks(width)).enumerate() {
                let (start, end) = (usize::from(span.start()), usize::from(span.end()));
                let area = Rectangle::new(
                    Point::new(start as i32, y as i32),
                    Size::new((end - start) as u32, 1),
                );
                let _ = self
                    .frame
                    .fill_contiguous(&area, row[start..end].iter().copied());
            }
            return Ok(());
        }
        self.renderer.clear();
        let light = Shading::lambert();
        self.renderer
            .draw_mesh(
                &self.scene.mesh,
                &self.model,
                &self.camera,
                self.cull,
                |f| light.color(f).into(),
            )
            .map_err(|e| format!("zline: {e}"))?;
        let width = self.frame.width;
        match self.output {
            Output::InPlace => self
                .renderer
                .render(&mut FrameBufferSink::new(&mut self.frame.pixels, width))
                .map(|_| ())
                .map_err(|e| format!("zline: {e:?}")),
            Output::DrawTarget => self
                .renderer
                .render(
                    &mut DrawTargetSink::new(&mut self.frame)
                        .changed_only(&mut self.shown, Rgb565::BLACK),
                )
                .map(|_| ())
                .map_err(|e| format!("zline: {e:?}")),
            Output::TargetAlone => Err("zline: no stored frame".to_string()),
        }
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        if self.output != Output::InPlace {
            return Ok(None);
        }
        let (w, h) = (self.view.width, self.view.height);
        let mut ids = HostRenderer::<u32, D>::for_mesh(&self.scene.mesh, w, h, BACKGROUND)
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

/// zline drawing the frame in horizontal bands on several threads
/// ([`BandedRenderer::render_mesh`]) with 24-bit depth: the threads,
/// started once a frame, project the mesh's vertices and sort its faces
/// into the bands their rows reach (both in chunks), then each builds its
/// band's tables from that projection and its faces, shades them with
/// `Shading::lambert()` and scans its rows in place into its own part of
/// the frame. The same frame as `zline z24`, pixel for pixel (checked).
/// Timed by the wall clock, not thread CPU time (the work is on several
/// threads).
pub struct ZlineBandsRenderer<'a> {
    scene: &'a Scene,
    renderer: BandedRenderer<Rgb565, Depth24>,
    frame: PlainTarget,
    model: Mat4,
    camera: Camera,
    cull: ZCull,
    name: String,
}

impl<'a> ZlineBandsRenderer<'a> {
    /// Builds the renderer for `view` with `threads` bands, each band's
    /// tables sized for the whole mesh.
    pub fn new(scene: &'a Scene, view: &View, threads: usize) -> Result<Self, String> {
        let mesh = &scene.mesh;
        let renderer = BandedRenderer::new(
            &mesh.capacities(view.width),
            view.width,
            view.height,
            Rgb565::BLACK,
            threads,
        )
        .map_err(|e| format!("zline: {e}"))?;
        let model = reference_model(mesh, view.yaw_deg, view.pitch_deg)
            .map_err(|e| format!("zline: {e}"))?;
        Ok(Self {
            scene,
            renderer,
            frame: PlainTarget::new(usize::from(view.width), usize::from(view.height)),
            model,
            camera: Camera::reference(view.width, view.height),
            cull: zline_cull(view.cull),
            name: format!("zline z24 {threads} threads"),
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

    fn timed_region(&self) -> String {
        format!(
            "`BandedRenderer::render_mesh(.., |f| light.color(f).into())` with \
         `Shading::lambert()`: threads started, vertices projected and faces sorted into bands, \
         each band's tables filled and its rows drawn in place (`FrameBufferSink::from_row`); \
         wall clock, not thread CPU time; depth z24; {CLOSED_MESHES}"
        )
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
        let light = Shading::lambert();
        self.renderer
            .render_mesh(
                &self.scene.mesh,
                &self.model,
                &self.camera,
                self.cull,
                &mut sinks,
                |f: &FaceInfo| light.color(f).into(),
            )
            .map(|_| ())
            .map_err(|e| format!("zline: {e:?}"))
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        Ok(None)
    }

    fn rgb565(&self) -> Vec<u16> {
        self.frame.raw()
    }
}
