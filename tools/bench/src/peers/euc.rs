//! euc 0.5 behind the [`Renderer`] trait.
//!
//! euc's intended use: a `Pipeline` whose vertex shader gets one entry of
//! a vertex slice, groups of 3 consecutive entries make a triangle
//! (`rasterizer::Triangles`), and the fragment shader gets the
//! perspective-correct interpolation of what the vertex shader returned.
//! Here the vertex slice is the corner numbers `0..3T` of the fan
//! triangles; the vertex shader looks up the corner's OBJ vertex and
//! multiplies it by the model-view-projection matrix, and computes the
//! triangle's flat Lambert colour from its object-space normal (the same
//! value at all three corners, so it interpolates to itself: euc 0.5 has
//! no flat varyings); the fragment shader returns it. Colour target:
//! [`Frame565`]; depth: euc's own `Buffer2d<f32>` with its default
//! `IfLessWrite` (`<=`) test.
//!
//! [`EucPaintedRenderer`] draws the smooth mesh the same way, Gouraud
//! ([`GouraudPipeline`]: Lambert per vertex in the vertex shader, colour
//! interpolated) or textured ([`TexturedPipeline`]: the vertex's `vt`
//! interpolated, the texel looked up in the fragment shader).

use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingDisabled, BackfaceCullingEnabled, BackfaceMode, Triangles};
use euc::{Pipeline, Target};

use crate::framebuffer::Frame565;
use crate::renderer::Renderer;
use crate::view::{
    BACKGROUND, Cull, LAMBERT_AMBIENT, LAMBERT_BASE, Mat4, ObjectLight, Scene, View, dot,
    lambert_rgb565, rgb565, transform,
};

/// The pipeline as a user writes flat Lambert in euc 0.5: positions by
/// corner, the triangle's object-space normal by corner, and the light
/// and eye in object space as uniforms. The vertex shader computes the
/// two-sided Lambert colour (one dot product with the light, negated when
/// the triangle's plane faces away from the eye), as `f32`, and the
/// fragment shader rounds it back to Rgb565.
struct LambertPipeline<'a> {
    mvp: Mat4,
    positions: &'a [[f32; 3]],
    corners: &'a [u32],
    normals: &'a [[f32; 3]],
    light: ObjectLight,
}

impl Pipeline for LambertPipeline<'_> {
    type Vertex = u32;
    type VsOut = f32;
    type Pixel = u16;

    #[inline(always)]
    fn vert(&self, corner: &u32) -> ([f32; 4], f32) {
        let k = *corner as usize;
        let p = &self.positions[self.corners[k] as usize];
        let n = &self.normals[k / 3];
        let d = dot(n, &self.light.light);
        let d = if self.light.front(n, p) { d } else { -d };
        (transform(&self.mvp, p), f32::from(lambert_rgb565(d)))
    }

    #[inline(always)]
    fn frag(&self, color: &f32) -> u16 {
        (*color + 0.5) as u16
    }
}

/// The id pass's pipeline: positions by corner, one value per triangle
/// (its face id, exact in `f32` below 2^24).
struct IdPipeline<'a> {
    mvp: Mat4,
    positions: &'a [[f32; 3]],
    corners: &'a [u32],
    ids: &'a [f32],
}

impl Pipeline for IdPipeline<'_> {
    type Vertex = u32;
    type VsOut = f32;
    type Pixel = u32;

    #[inline(always)]
    fn vert(&self, corner: &u32) -> ([f32; 4], f32) {
        let k = *corner as usize;
        let p = &self.positions[self.corners[k] as usize];
        (transform(&self.mvp, p), self.ids[k / 3])
    }

    #[inline(always)]
    fn frag(&self, id: &f32) -> u32 {
        (*id + 0.5) as u32
    }
}

/// euc 0.5.
///
/// Timed region: clear the colour frame and the depth buffer (each to
/// its clear value: black, 1.0), bring zline's light and the eye into
/// object space ([`Scene::object_light`]), then one
/// `Pipeline::draw::<Triangles<_, B>, _>` call over all fan triangles.
/// That call runs the vertex shader three times per triangle (euc has no
/// vertex cache or index buffer: 4×4 matrix times position, and the
/// triangle's Lambert colour, [`LambertPipeline`]), divides by w, culls,
/// and rasterises with pixel-centre sampling and a float depth buffer,
/// running the fragment shader per covered pixel. Culling: euc's own
/// (`BackfaceCullingEnabled`: triangles whose NDC winding is clockwise,
/// the same rule as the view's) when `--cull back`,
/// `BackfaceCullingDisabled` for `none`. euc 0.5 does not clip: the
/// reference view keeps every vertex in front of the eye, so nothing
/// needs it. Face ids: drawn again, untimed, with the face id as the
/// per-triangle value.
pub struct EucRenderer<'a> {
    scene: &'a Scene,
    view: View,
    mvp: Mat4,
    corners: Vec<u32>,
    corner_list: Vec<u32>,
    normals: Vec<[f32; 3]>,
    color: Frame565,
    depth: Buffer2d<f32>,
}

impl<'a> EucRenderer<'a> {
    /// Builds the renderer for `view`: the flat corner list (the vertex
    /// buffer) and the per-triangle normals, once per mesh.
    pub fn new(scene: &'a Scene, view: &View) -> Result<Self, String> {
        let corners: Vec<u32> = scene.triangles.iter().flatten().copied().collect();
        let count = u32::try_from(corners.len())
            .map_err(|_| "euc: too many triangle corners for u32".to_string())?;
        let (w, h) = (usize::from(view.width), usize::from(view.height));
        Ok(Self {
            scene,
            view: *view,
            mvp: scene.mvp(view),
            corners,
            corner_list: (0..count).collect(),
            normals: scene.triangle_normals(),
            color: Frame565::new(w, h),
            depth: Buffer2d::new([w, h], 1.0),
        })
    }
}

/// One draw call over `corners` with backface mode `B`.
fn draw_with<B: BackfaceMode, P: Pipeline<Vertex = u32>, T: Target<Item = P::Pixel>>(
    pipeline: &P,
    corners: &[u32],
    target: &mut T,
    depth: &mut Buffer2d<f32>,
) {
    pipeline.draw::<Triangles<'_, Buffer2d<f32>, B>, T>(corners, target, Some(depth));
}

/// One draw call with the view's culling.
fn draw<P: Pipeline<Vertex = u32>, T: Target<Item = P::Pixel>>(
    cull: Cull,
    pipeline: &P,
    corners: &[u32],
    target: &mut T,
    depth: &mut Buffer2d<f32>,
) {
    match cull {
        Cull::None => draw_with::<BackfaceCullingDisabled, P, T>(pipeline, corners, target, depth),
        Cull::Back => draw_with::<BackfaceCullingEnabled, P, T>(pipeline, corners, target, depth),
    }
}

impl Renderer for EucRenderer<'_> {
    fn name(&self) -> &str {
        "euc"
    }

    fn timed_region(&self) -> String {
        "colour frame and depth buffer cleared, light into object space, one `Pipeline::draw` \
         (vertex shader per triangle corner: 4×4 transform and the triangle's two-sided Lambert \
         colour; its own culling with `--cull back`; fragment shader per pixel); f32 depth \
         buffer"
            .into()
    }

    fn render(&mut self) -> Result<(), String> {
        Target::clear(&mut self.color, 0);
        self.depth.clear(1.0);
        let pipeline = LambertPipeline {
            mvp: self.mvp,
            positions: &self.scene.mesh.positions,
            corners: &self.corners,
            normals: &self.normals,
            light: self.scene.object_light(&self.view),
        };
        draw(
            self.view.cull,
            &pipeline,
            &self.corner_list,
            &mut self.color,
            &mut self.depth,
        );
        Ok(())
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        Ok(face_ids(
            self.scene,
            &self.view,
            &self.corners,
            &self.corner_list,
            &mut self.depth,
        ))
    }

    fn rgb565(&self) -> Vec<u16> {
        self.color.pixels.clone()
    }
}

/// The frame's face ids, drawn untimed with [`IdPipeline`] over the same
/// positions and corners as the timed frame (so the same visibility);
/// `None` for a mesh whose face ids `f32` cannot hold exactly.
fn face_ids(
    scene: &Scene,
    view: &View,
    corners: &[u32],
    corner_list: &[u32],
    depth: &mut Buffer2d<f32>,
) -> Option<Vec<u32>> {
    if scene.face_count() >= 1 << 24 {
        return None;
    }
    let ids: Vec<f32> = scene.triangle_faces.iter().map(|&f| f as f32).collect();
    let (w, h) = (usize::from(view.width), usize::from(view.height));
    let mut target = Buffer2d::new([w, h], BACKGROUND);
    depth.clear(1.0);
    let pipeline = IdPipeline {
        mvp: scene.mvp(view),
        positions: &scene.mesh.positions,
        corners,
        ids: &ids,
    };
    draw(view.cull, &pipeline, corner_list, &mut target, depth);
    Some(target.as_ref().to_vec())
}

/// Gouraud in euc 0.5 as a user writes it: positions and vertex normals
/// by corner (the smooth mesh's, object space), the light in object space
/// as a uniform; the vertex shader lights its vertex one-sided as zline's
/// `Lambert::vertex_color` does (`k = ambient + (1 - ambient)·max(0, n·l)`,
/// each channel `base·k` as `f32`), euc interpolates the three channels
/// (perspective-correct: the only interpolation it has), and the
/// fragment shader rounds them to 8 bits and packs them (truncating) to
/// Rgb565, without dithering.
struct GouraudPipeline<'a> {
    mvp: Mat4,
    positions: &'a [[f32; 3]],
    normals: &'a [[f32; 3]],
    corners: &'a [u32],
    light: [f32; 3],
}

impl Pipeline for GouraudPipeline<'_> {
    type Vertex = u32;
    type VsOut = (f32, f32, f32);
    type Pixel = u16;

    #[inline(always)]
    fn vert(&self, corner: &u32) -> ([f32; 4], (f32, f32, f32)) {
        let v = self.corners[*corner as usize] as usize;
        let d = dot(&self.normals[v], &self.light);
        let k = LAMBERT_AMBIENT + (1.0 - LAMBERT_AMBIENT) * d.max(0.0);
        let [r, g, b] = LAMBERT_BASE.map(|c| f32::from(c) * k);
        (transform(&self.mvp, &self.positions[v]), (r, g, b))
    }

    #[inline(always)]
    fn frag(&self, &(r, g, b): &(f32, f32, f32)) -> u16 {
        rgb565((r + 0.5) as u8, (g + 0.5) as u8, (b + 0.5) as u8)
    }
}

/// Texture mapping in euc 0.5 as a user writes it: euc 0.5 has no
/// sampler (its `sampler` module is an empty TODO), so the fragment
/// shader samples the texels itself. Positions and texture coordinates by
/// corner; the vertex shader returns the corner's `vt`, which euc
/// interpolates perspective-correctly; the fragment shader takes the
/// nearest texel, repeating (`floor(u·W) mod W`, row `floor((1 - v)·H) mod
/// H` from the top, as zline's texture stores rows).
struct TexturedPipeline<'a> {
    mvp: Mat4,
    positions: &'a [[f32; 3]],
    uvs: &'a [[f32; 2]],
    corners: &'a [u32],
    texels: &'a [u16],
    width: usize,
    height: usize,
}

impl Pipeline for TexturedPipeline<'_> {
    type Vertex = u32;
    type VsOut = (f32, f32);
    type Pixel = u16;

    #[inline(always)]
    fn vert(&self, corner: &u32) -> ([f32; 4], (f32, f32)) {
        let v = self.corners[*corner as usize] as usize;
        let [s, t] = self.uvs[v];
        (transform(&self.mvp, &self.positions[v]), (s, t))
    }

    #[inline(always)]
    fn frag(&self, &(s, t): &(f32, f32)) -> u16 {
        let (w, h) = (self.width as f32, self.height as f32);
        let x = ((s * w).floor() as i64).rem_euclid(self.width as i64) as usize;
        let y = (((1.0 - t) * h).floor() as i64).rem_euclid(self.height as i64) as usize;
        self.texels[y * self.width + x]
    }
}

/// What an [`EucPaintedRenderer`] paints.
pub enum Paint<'a> {
    /// Per-vertex Lambert, interpolated ([`GouraudPipeline`]).
    Gouraud,
    /// Nearest texels of a texture ([`TexturedPipeline`]): raw Rgb565
    /// texels row by row from the top, width, height.
    Textured(&'a [u16], usize, usize),
}

/// euc 0.5 drawing the smooth mesh with Gouraud shading or a texture.
///
/// Timed region: clear the colour frame and the depth buffer (black,
/// 1.0); for Gouraud, bring zline's light into object space
/// ([`Scene::object_light`]); then one `Pipeline::draw::<Triangles<_, B>,
/// _>` call over all fan triangles of the smooth mesh, with the view's
/// culling as the flat `euc` row has it. The vertex shader runs three
/// times per triangle (no vertex cache: a 4×4 transform, and for Gouraud
/// the vertex's Lambert colour), the fragment shader once per covered
/// pixel. Face ids: drawn again, untimed, with the face id as the
/// per-triangle value over the same corners.
pub struct EucPaintedRenderer<'a> {
    scene: &'a Scene,
    paint: Paint<'a>,
    view: View,
    mvp: Mat4,
    corners: Vec<u32>,
    corner_list: Vec<u32>,
    color: Frame565,
    depth: Buffer2d<f32>,
}

impl<'a> EucPaintedRenderer<'a> {
    /// Builds the renderer for `view`: the flat corner list (the vertex
    /// buffer), once per mesh. `scene` is the smooth mesh's.
    pub fn new(scene: &'a Scene, view: &View, paint: Paint<'a>) -> Result<Self, String> {
        let corners: Vec<u32> = scene.triangles.iter().flatten().copied().collect();
        let count = u32::try_from(corners.len())
            .map_err(|_| "euc: too many triangle corners for u32".to_string())?;
        if let Paint::Textured(texels, w, h) = paint
            && (texels.len() != w * h || scene.mesh.uvs.len() != scene.mesh.positions.len())
        {
            return Err("euc textured: texture or texture coordinates missing".into());
        }
        if scene.mesh.vertex_normals.len() != scene.mesh.positions.len() {
            return Err("euc gouraud: vertex normals missing".into());
        }
        let (w, h) = (usize::from(view.width), usize::from(view.height));
        Ok(Self {
            scene,
            paint,
            view: *view,
            mvp: scene.mvp(view),
            corners,
            corner_list: (0..count).collect(),
            color: Frame565::new(w, h),
            depth: Buffer2d::new([w, h], 1.0),
        })
    }
}

impl Renderer for EucPaintedRenderer<'_> {
    fn name(&self) -> &str {
        match self.paint {
            Paint::Gouraud => "euc gouraud",
            Paint::Textured(..) => "euc textured",
        }
    }

    fn timed_region(&self) -> String {
        match self.paint {
            Paint::Gouraud => {
                "colour frame and depth buffer cleared, light into object space, one \
                 `Pipeline::draw` (vertex shader per triangle corner: 4×4 transform and the \
                 vertex's one-sided Lambert from its vertex normal, as `(f32, f32, f32)`; \
                 channels interpolated perspective-correctly by euc; fragment shader per pixel \
                 rounds and packs to Rgb565, no dither); its own culling with `--cull back`; \
                 f32 depth buffer"
            }
            Paint::Textured(..) => {
                "colour frame and depth buffer cleared, one `Pipeline::draw` (vertex shader per \
                 triangle corner: 4×4 transform and the vertex's `vt`; interpolated \
                 perspective-correctly by euc; fragment shader per pixel: nearest texel, \
                 repeating, looked up by hand since euc 0.5 has no sampler); its own culling \
                 with `--cull back`; f32 depth buffer"
            }
        }
        .into()
    }

    fn render(&mut self) -> Result<(), String> {
        Target::clear(&mut self.color, 0);
        self.depth.clear(1.0);
        let mesh = &self.scene.mesh;
        match self.paint {
            Paint::Gouraud => {
                let pipeline = GouraudPipeline {
                    mvp: self.mvp,
                    positions: &mesh.positions,
                    normals: &mesh.vertex_normals,
                    corners: &self.corners,
                    light: self.scene.object_light(&self.view).light,
                };
                draw(
                    self.view.cull,
                    &pipeline,
                    &self.corner_list,
                    &mut self.color,
                    &mut self.depth,
                );
            }
            Paint::Textured(texels, width, height) => {
                let pipeline = TexturedPipeline {
                    mvp: self.mvp,
                    positions: &mesh.positions,
                    uvs: &mesh.uvs,
                    corners: &self.corners,
                    texels,
                    width,
                    height,
                };
                draw(
                    self.view.cull,
                    &pipeline,
                    &self.corner_list,
                    &mut self.color,
                    &mut self.depth,
                );
            }
        }
        Ok(())
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        Ok(face_ids(
            self.scene,
            &self.view,
            &self.corners,
            &self.corner_list,
            &mut self.depth,
        ))
    }

    fn rgb565(&self) -> Vec<u16> {
        self.color.pixels.clone()
    }
}
