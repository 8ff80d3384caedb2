//! euc 0.5 behind the [`Renderer`] trait.
//!
//! euc's intended use: a `Pipeline` whose vertex shader gets one entry of
//! a vertex slice, groups of 3 consecutive entries make a triangle
//! (`rasterizer::Triangles`), and the fragment shader gets the
//! perspective-correct interpolation of what the vertex shader returned.
//! Here the vertex slice is the corner numbers `0..3T` of the fan
//! triangles; the vertex shader looks up the corner's OBJ vertex and
//! multiplies it by the model-view-projection matrix, and hands on the
//! triangle's face colour (the same value at all three corners, so it
//! interpolates to itself: euc 0.5 has no flat varyings). Colour target:
//! [`Frame565`]; depth: euc's own `Buffer2d<f32>` with its default
//! `IfLessWrite` (`<=`) test.

use core::marker::PhantomData;

use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingDisabled, BackfaceCullingEnabled, BackfaceMode, Triangles};
use euc::{Pipeline, Target};

use crate::framebuffer::Frame565;
use crate::renderer::Renderer;
use crate::view::{BACKGROUND, Cull, Mat4, Scene, View, transform};

/// What a pipeline writes per pixel, from the rounded per-triangle value.
trait FromAttr: Clone {
    fn from_attr(v: f32) -> Self;
}

impl FromAttr for u16 {
    #[inline(always)]
    fn from_attr(v: f32) -> Self {
        (v + 0.5) as u16
    }
}

impl FromAttr for u32 {
    #[inline(always)]
    fn from_attr(v: f32) -> Self {
        (v + 0.5) as u32
    }
}

/// The pipeline: positions by corner, one value per triangle (its face's
/// colour, or its face id for the id pass).
struct FlatPipeline<'a, P> {
    mvp: Mat4,
    positions: &'a [[f32; 3]],
    corners: &'a [u32],
    values: &'a [f32],
    _pixel: PhantomData<P>,
}

impl<P: FromAttr> Pipeline for FlatPipeline<'_, P> {
    type Vertex = u32;
    type VsOut = f32;
    type Pixel = P;

    #[inline(always)]
    fn vert(&self, corner: &u32) -> ([f32; 4], f32) {
        let k = *corner as usize;
        let p = &self.positions[self.corners[k] as usize];
        (transform(&self.mvp, p), self.values[k / 3])
    }

    #[inline(always)]
    fn frag(&self, value: &f32) -> P {
        P::from_attr(*value)
    }
}

/// euc 0.5.
///
/// Timed region: clear the colour frame and the depth buffer, then one
/// `Pipeline::draw::<Triangles<_, B>, _>` call over all fan triangles. That
/// call runs the vertex shader three times per triangle (euc has no vertex
/// cache or index buffer: 4×4 matrix times position), divides by w, culls,
/// and rasterises with pixel-centre sampling and a float depth buffer.
/// Culling: euc's own (`BackfaceCullingEnabled`: triangles whose NDC
/// winding is clockwise, the same rule as the view's) when `--cull back`,
/// `BackfaceCullingDisabled` for `none`. euc 0.5 does not clip: the
/// reference view keeps every vertex in front of the eye, so nothing
/// needs it. Face colours are flat Lambert (`Scene::triangle_colors`),
/// computed once per view before timing. Face ids: drawn again, untimed,
/// with the face id as the per-triangle value (exact in f32 below 2^24).
pub struct EucRenderer<'a> {
    draw: Draw<'a>,
    colors: Vec<f32>,
    color: Frame565,
    depth: Buffer2d<f32>,
}

/// What every draw call of one view shares.
struct Draw<'a> {
    scene: &'a Scene,
    mvp: Mat4,
    cull: Cull,
    corners: Vec<u32>,
    corner_list: Vec<u32>,
}

impl<'a> EucRenderer<'a> {
    /// Builds the renderer for `view`: the flat corner list and the
    /// per-triangle colours.
    pub fn new(scene: &'a Scene, view: &View) -> Result<Self, String> {
        let corners: Vec<u32> = scene.triangles.iter().flatten().copied().collect();
        let count = u32::try_from(corners.len())
            .map_err(|_| "euc: too many triangle corners for u32".to_string())?;
        let colors = scene
            .triangle_colors(view)
            .into_iter()
            .map(f32::from)
            .collect();
        let (w, h) = (usize::from(view.width), usize::from(view.height));
        Ok(Self {
            draw: Draw {
                scene,
                mvp: scene.mvp(view),
                cull: view.cull,
                corners,
                corner_list: (0..count).collect(),
            },
            colors,
            color: Frame565::new(w, h),
            depth: Buffer2d::new([w, h], 1.0),
        })
    }
}

impl Draw<'_> {
    /// Draws every triangle with `values` per triangle into `target`,
    /// depth-testing against the (already cleared) depth buffer.
    fn draw<P: FromAttr, T: Target<Item = P>>(
        &self,
        values: &[f32],
        target: &mut T,
        depth: &mut Buffer2d<f32>,
    ) {
        let pipeline = FlatPipeline::<P> {
            mvp: self.mvp,
            positions: &self.scene.mesh.positions,
            corners: &self.corners,
            values,
            _pixel: PhantomData,
        };
        match self.cull {
            Cull::None => draw_with::<BackfaceCullingDisabled, P, T>(
                &pipeline,
                &self.corner_list,
                target,
                depth,
            ),
            Cull::Back => draw_with::<BackfaceCullingEnabled, P, T>(
                &pipeline,
                &self.corner_list,
                target,
                depth,
            ),
        }
    }
}

fn draw_with<B: BackfaceMode, P: FromAttr, T: Target<Item = P>>(
    pipeline: &FlatPipeline<'_, P>,
    corners: &[u32],
    target: &mut T,
    depth: &mut Buffer2d<f32>,
) {
    pipeline.draw::<Triangles<'_, Buffer2d<f32>, B>, T>(corners, target, Some(depth));
}

impl Renderer for EucRenderer<'_> {
    fn name(&self) -> &str {
        "euc"
    }

    fn render(&mut self) -> Result<(), String> {
        Target::clear(&mut self.color, 0);
        self.depth.clear(1.0);
        self.draw
            .draw::<u16, Frame565>(&self.colors, &mut self.color, &mut self.depth);
        Ok(())
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        let scene = self.draw.scene;
        if scene.face_count() >= 1 << 24 {
            return Ok(None);
        }
        let ids: Vec<f32> = scene.triangle_faces.iter().map(|&f| f as f32).collect();
        let (w, h) = (self.color.width, self.color.height);
        let mut target = Buffer2d::new([w, h], BACKGROUND);
        self.depth.clear(1.0);
        self.draw
            .draw::<u32, Buffer2d<u32>>(&ids, &mut target, &mut self.depth);
        Ok(Some(target.as_ref().to_vec()))
    }

    fn rgb565(&self) -> Vec<u16> {
        self.color.pixels.clone()
    }
}
