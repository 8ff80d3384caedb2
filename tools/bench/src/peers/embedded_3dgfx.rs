//! embedded-3dgfx 0.7 behind the [`Renderer`] trait: its frame driver
//! lit and unlit, and its triangle rasteriser fed vertices transformed
//! once per frame.
//!
//! embedded-3dgfx's intended use is its frame driver: a `K3dengine` with
//! a camera, a `K3dMesh` over borrowed `Geometry` (vertices, triangle
//! faces as `[usize; 3]`, per-face normals from
//! `Geometry::compute_face_normals_into`, once per mesh, as its README
//! recommends), `engine.record` into a fixed-capacity `CommandBuffer`,
//! then `engine.execute` into an embedded-graphics `DrawTarget<Color =
//! Rgb565>` with a caller-owned z-buffer (`FrameCtx`). The crate is used
//! with its default features plus `lighting` (its lit modes; 32-bit
//! `ZDepth`, the default). Its README also shows its rasteriser driven
//! directly (`draw_zbuffered_with_state` with the engine's
//! `raster_state`), which [`Embedded3dgfxRasterRenderer`] does.

use core::convert::Infallible;

use embedded_3dgfx::engine::K3dengine;
use embedded_3dgfx::pipeline::assemble::primitive::DrawPrimitive;
use embedded_3dgfx::pipeline::command_buffer::{CommandBuffer, RenderCommand};
use embedded_3dgfx::pipeline::rasterize::draw::draw_zbuffered_with_textures_state;
use embedded_3dgfx::pipeline::rasterize::draw::state::RasterState;
use embedded_3dgfx::pipeline::rasterize::draw::zbuffered::draw_zbuffered_with_state;
use embedded_3dgfx::pipeline::rasterize::texture::{Texture, TextureManager};
use embedded_3dgfx::pipeline::renderer::FrameCtx;
use embedded_3dgfx::pipeline::vertex::mesh::{Geometry, K3dMesh, RenderMode};
use embedded_3dgfx::{Z_MAX_VALUE, ZDepth};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::prelude::*;
use nalgebra::{Point2, Point3, UnitQuaternion, Vector3};

use crate::framebuffer::Frame565;
use crate::renderer::Renderer;
use crate::view::{
    BACKGROUND, Cull, FAR, FOV_Y_DEG, Mat4, NEAR, Scene, SmoothScene, View, dot, lambert_rgb565,
    light_direction, transform,
};

/// Capacity of the command buffer: draw primitives per frame (a triangle
/// clipped by the frustum sides can become several).
pub const MAX_COMMANDS: usize = 1 << 18;

/// The mesh arrays a `K3dMesh` borrows, built once per mesh.
pub struct MeshData<'a> {
    scene: &'a Scene,
    faces: Vec<[usize; 3]>,
    /// embedded-3dgfx's own unit normals of the fan triangles
    /// (`Geometry::compute_face_normals_into`, counter-clockwise front).
    normals: Vec<[f32; 3]>,
    /// The bench's per-triangle normals ([`Scene::triangle_normals`]: a
    /// planar face's Newell normal), for the rasteriser fed by hand.
    shared_normals: Vec<[f32; 3]>,
    /// Per-vertex normals (the smooth mesh's, for `GouraudLightDir`);
    /// empty for the flat mesh.
    vertex_normals: &'a [[f32; 3]],
    /// Per-vertex texture coordinates with `v` flipped (`1 - v`: its
    /// textures put `v = 0` at the top row, OBJ at the bottom); empty
    /// without a texture.
    uvs: Vec<[f32; 2]>,
    /// The texture as embedded-3dgfx takes it (`&'static` texels, power
    /// of two a side), when the mesh has one it can take.
    texture: Option<Texture>,
}

impl<'a> MeshData<'a> {
    /// Fan triangles as `[usize; 3]` and their unit normals.
    pub fn new(scene: &'a Scene) -> Self {
        let faces: Vec<[usize; 3]> = scene
            .triangles
            .iter()
            .map(|t| t.map(|v| v as usize))
            .collect();
        let mut normals = vec![[0.0; 3]; faces.len()];
        Geometry::compute_face_normals_into(&scene.mesh.positions, &faces, &mut normals);
        Self {
            scene,
            faces,
            normals,
            shared_normals: scene.triangle_normals(),
            vertex_normals: &[],
            uvs: Vec::new(),
            texture: None,
        }
    }

    /// The smooth mesh's arrays: as [`Self::new`], with its vertex normals
    /// and, when it has a texture with sides that are powers of two
    /// (embedded-3dgfx takes no other), its texture coordinates and the
    /// texture (its texels leaked once, as `Texture::new` takes
    /// `&'static` data, as a `static` in firmware is).
    pub fn smooth(smooth: &'a SmoothScene) -> Self {
        let mut data = Self::new(&smooth.scene);
        data.vertex_normals = &smooth.scene.mesh.vertex_normals;
        if let Some(t) = &smooth.texture {
            let (w, h) = (u32::from(t.width), u32::from(t.height));
            if w.is_power_of_two() && h.is_power_of_two() {
                let texels: Vec<Rgb565> = t
                    .texels
                    .iter()
                    .map(|&raw| Rgb565::from(RawU16::new(raw)))
                    .collect();
                data.texture = Some(Texture::new(Box::leak(texels.into_boxed_slice()), w, h));
                data.uvs = smooth
                    .scene
                    .mesh
                    .uvs
                    .iter()
                    .map(|&[u, v]| [u, 1.0 - v])
                    .collect();
            }
        }
        data
    }

    /// Whether the textured row can be drawn (a texture embedded-3dgfx
    /// takes).
    pub fn has_texture(&self) -> bool {
        self.texture.is_some()
    }
}

/// Which of the frame driver's render modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// `RenderMode::SolidLightDir`: flat, per-face directional light.
    Lit,
    /// `RenderMode::Solid`: one colour for the whole mesh.
    Unlit,
    /// `RenderMode::GouraudLightDir`: per-vertex directional light from
    /// the vertex normals, colours interpolated (the smooth mesh).
    Gouraud,
    /// `RenderMode::Textured`: unlit, texture-sampled (the smooth mesh).
    Textured,
}

/// embedded-3dgfx 0.7's frame driver, [`Mode::Lit`] or [`Mode::Unlit`].
///
/// Timed region: clear the colour frame (`DrawTarget::clear`, black),
/// then `engine.record(mesh)`, then `engine.execute`, which clears the
/// z-buffer (the recorded `ClearDepth`) and rasterises every primitive
/// with its scanline z-buffered fill, pixel by pixel through
/// `DrawTarget::draw_iter`.
///
/// Unlit (`RenderMode::Solid`): `record` checks the mesh's bounding
/// sphere against the frustum, multiplies each triangle's three corners
/// by the model-view-projection matrix (no vertex sharing), culls, clips
/// against the near and side planes, projects to integer pixels and
/// integer depth, and stores one `ColoredTriangleWithDepth` per triangle,
/// all in the mesh's one colour (the Lambert base colour): no shading.
/// Culling is the engine's own back-face test, which it applies only when
/// the geometry has normals: `(eye - v0) · n < 0` in world space; so
/// `--cull back` passes the triangles' normals and `none` passes none.
///
/// Lit (`RenderMode::SolidLightDir(dir)`): `record` transforms the first
/// 256 vertices once into a cache and every other corner each time it is
/// used, turns each face's normal by the model matrix, culls back faces
/// with the test above (always: the lit modes need normals, and
/// `--cull none` cannot switch it off), computes the face's colour
/// inside the frame (`base·max(0, n·dir') + 0.1·base`, its own one-sided
/// rule with 10 % ambient, in `f32` per channel), and does not clip
/// (a triangle with a corner off screen is dropped). The direction is
/// zline's light with z negated (`SolidLightDir` negates z) and scaled by
/// the mesh's radius, which undoes the model matrix's `1/r` scale in the
/// turned normal: a user who left it out would get a darker or brighter
/// frame at the same cost.
///
/// Depth in both: `(z_ndc · (far - near) + near) as i32`, whole units of
/// world distance between about -10 and 10; with near 0.1 and far 10
/// and the mesh 2 to 4 units from the eye, the whole mesh gets one depth
/// value (9), so the last triangle drawn wins (its wrong-face rate shows
/// it). The lit mode gives a
/// triangle its first corner's depth at all three.
///
/// Gouraud (`RenderMode::GouraudLightDir(dir)`, over the smooth mesh
/// with its vertex normals as `Geometry::vertex_normals`): as lit, but
/// each corner gets its colour from its vertex normal turned by the model
/// matrix (the same rule and light), and the rasteriser interpolates the
/// three Rgb565 colours over the triangle; each corner keeps its own
/// depth. Textured (`RenderMode::Textured`, the smooth mesh's texture
/// coordinates with `v` flipped and the texture in a `TextureManager`):
/// corners transformed with their clip w, culled as unlit is, not
/// clipped, drawn by `engine.execute_with_textures` with the engine's
/// default `TextureMapping::PerspectiveCorrect`, nearest texel,
/// repeating; no lighting.
///
/// Face ids: recovered untimed. Each triangle is recorded alone (same
/// camera and model matrix) to learn how many primitives it makes, and
/// the frame's command buffer is replayed through the same
/// `draw_zbuffered_with_state` into a target that notes which triangle
/// wrote each pixel; the replayed colours are checked against the timed
/// frame.
pub struct Embedded3dgfxRenderer<'a> {
    data: &'a MeshData<'a>,
    engine: K3dengine,
    mesh: K3dMesh<'a>,
    commands: Box<CommandBuffer<MAX_COMMANDS>>,
    zbuffer: Vec<ZDepth>,
    frame: Frame565,
    mode: Mode,
    /// The texture manager `execute_with_textures` reads (textured mode).
    textures: Box<TextureManager<1>>,
}

impl<'a> Embedded3dgfxRenderer<'a> {
    /// Builds the engine, camera and mesh for `view`.
    pub fn new(data: &'a MeshData<'a>, view: &View, mode: Mode) -> Result<Self, String> {
        let scene = data.scene;
        let (w, h) = (usize::from(view.width), usize::from(view.height));
        let mut engine = K3dengine::new(view.width, view.height);
        engine.camera.set_fovy(FOV_Y_DEG.to_radians());
        engine.camera.set_near_far(NEAR, FAR);
        engine.camera.set_position(Point3::new(0.0, 0.0, 3.0));
        engine.camera.set_target(Point3::new(0.0, 0.0, 0.0));
        let normals: &[[f32; 3]] = match (mode, view.cull) {
            (Mode::Unlit | Mode::Textured, Cull::None) => &[],
            _ => &data.normals,
        };
        let mut geometry = Geometry::new(&scene.mesh.positions, &data.faces).with_normals(normals);
        let mut textures = Box::new(TextureManager::<1>::new());
        match mode {
            Mode::Gouraud => {
                if data.vertex_normals.len() != scene.mesh.positions.len() {
                    return Err("embedded-3dgfx gouraud: vertex normals missing".into());
                }
                geometry = geometry.with_vertex_normals(data.vertex_normals);
            }
            Mode::Textured => {
                let texture = data
                    .texture
                    .ok_or("embedded-3dgfx textured: no texture it takes")?;
                let id = textures
                    .add_texture(texture)
                    .ok_or("embedded-3dgfx textured: texture manager full")?;
                geometry = geometry.with_uvs(&data.uvs).with_texture(id);
            }
            Mode::Lit | Mode::Unlit => {}
        }
        let mut mesh = K3dMesh::new(geometry);
        place(&mut mesh, scene, view);
        mesh.set_color(Rgb565::from(RawU16::new(Scene::base_color())));
        // The light as the lit row gives it: zline's direction with z
        // negated (the lit modes negate z), scaled by the mesh's radius
        // (undoing the model matrix's `1/r` in the turned normals).
        let [x, y, z] = light_direction();
        let r = scene.radius;
        let light = Vector3::new(x * r, y * r, -z * r);
        match mode {
            Mode::Unlit => mesh.set_render_mode(RenderMode::Solid),
            Mode::Lit => mesh.set_render_mode(RenderMode::SolidLightDir(light)),
            Mode::Gouraud => mesh.set_render_mode(RenderMode::GouraudLightDir(light)),
            Mode::Textured => mesh.set_render_mode(RenderMode::Textured),
        }
        Ok(Self {
            data,
            engine,
            mesh,
            commands: Box::new(CommandBuffer::new()),
            zbuffer: vec![Z_MAX_VALUE; w * h],
            frame: Frame565::new(w, h),
            mode,
            textures,
        })
    }
}

/// The reference model matrix as the mesh's similarity: scale `1/r`,
/// rotation `Rx(pitch) · Ry(yaw)`, translation `-R·c/r`.
fn place(mesh: &mut K3dMesh<'_>, scene: &Scene, view: &View) {
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), view.pitch_deg.to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), view.yaw_deg.to_radians());
    let s = 1.0 / scene.radius;
    let t = rotation * Vector3::from(scene.centre) * -s;
    mesh.set_rotation(rotation);
    mesh.set_scale(s);
    mesh.set_position(t.x, t.y, t.z);
}

impl Renderer for Embedded3dgfxRenderer<'_> {
    fn name(&self) -> &str {
        match self.mode {
            Mode::Lit => "embedded-3dgfx lit",
            Mode::Unlit => "embedded-3dgfx unlit",
            Mode::Gouraud => "embedded-3dgfx gouraud",
            Mode::Textured => "embedded-3dgfx textured",
        }
    }

    fn timed_region(&self) -> String {
        match self.mode {
            Mode::Lit => {
                "colour frame cleared (`DrawTarget::clear`), `engine.record` with \
                          `RenderMode::SolidLightDir` (corners transformed per triangle past the \
                          first 256 vertices, back faces always culled, its own one-sided \
                          Lambert per face, no clipping), `engine.execute` (z-buffer cleared, \
                          triangles filled pixel by pixel through `draw_iter`); 32-bit z-buffer \
                          of integer depths"
            }
            Mode::Unlit => {
                "colour frame cleared (`DrawTarget::clear`), `engine.record` with \
                            `RenderMode::Solid` (each triangle's corners transformed, culled \
                            with `--cull back`, clipped, one colour: no shading), \
                            `engine.execute` (z-buffer cleared, triangles filled pixel by pixel \
                            through `draw_iter`); 32-bit z-buffer of integer depths"
            }
            Mode::Gouraud => {
                "colour frame cleared (`DrawTarget::clear`), `engine.record` with \
                 `RenderMode::GouraudLightDir` (corners transformed per triangle past the first \
                 256 vertices, back faces always culled, per corner its vertex normal turned by \
                 the model matrix and lit with its own one-sided rule, 10 % ambient, to Rgb565, \
                 no clipping), `engine.execute` (z-buffer cleared, colours interpolated over \
                 each triangle, filled pixel by pixel through `draw_iter`); 32-bit z-buffer of \
                 integer depths"
            }
            Mode::Textured => {
                "colour frame cleared (`DrawTarget::clear`), `engine.record` with \
                 `RenderMode::Textured` (corners transformed with their clip w, culled with \
                 `--cull back`, no clipping), `engine.execute_with_textures` (z-buffer \
                 cleared, its default `TextureMapping::PerspectiveCorrect`, nearest texel, \
                 repeating, filled pixel by pixel through `draw_iter`); texture as \
                 `Texture::new` over the same texels; 32-bit z-buffer of integer depths"
            }
        }
        .into()
    }

    fn render(&mut self) -> Result<(), String> {
        let _ = self.frame.clear(Rgb565::BLACK);
        self.engine
            .record(core::iter::once(&self.mesh), &mut self.commands, None)
            .map_err(|e| format!("embedded-3dgfx: record: {e:?}"))?;
        let mut ctx = FrameCtx {
            zbuffer: &mut self.zbuffer,
            width: self.frame.width,
            height: self.frame.height,
        };
        if self.mode == Mode::Textured {
            self.engine
                .execute_with_textures(
                    &mut self.frame,
                    &mut ctx,
                    &self.commands,
                    &self.textures,
                    None,
                )
                .map_err(|e| format!("embedded-3dgfx: execute: {e:?}"))?;
        } else {
            self.engine
                .execute(&mut self.frame, &mut ctx, &self.commands, None)
                .map_err(|e| format!("embedded-3dgfx: execute: {e:?}"))?;
        }
        Ok(())
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        let Some(owners) = self.primitive_faces()? else {
            eprintln!("embedded-3dgfx: primitives do not match triangles; no face ids");
            return Ok(None);
        };
        let (w, h) = (self.frame.width, self.frame.height);
        let mut target = IdTarget {
            ids: vec![BACKGROUND; w * h],
            colors: Frame565::new(w, h),
            current: BACKGROUND,
        };
        self.zbuffer.fill(Z_MAX_VALUE);
        let state = self.engine.raster_state(w, h);
        let mut draws = 0;
        for command in self.commands.iter() {
            match command {
                RenderCommand::Draw(primitive) => {
                    target.current = owners[draws];
                    draws += 1;
                    if self.mode == Mode::Textured {
                        draw_zbuffered_with_textures_state(
                            primitive.clone(),
                            &mut target,
                            &mut self.zbuffer,
                            &self.textures,
                            &state,
                        );
                    } else {
                        draw_zbuffered_with_state(
                            primitive.clone(),
                            &mut target,
                            &mut self.zbuffer,
                            &state,
                        );
                    }
                }
                RenderCommand::ClearDepth(value) => self.zbuffer.fill(*value),
                RenderCommand::ClearColor(_) => return Ok(None),
            }
        }
        if target.colors != self.frame {
            eprintln!("embedded-3dgfx: replayed frame differs from the timed one; no face ids");
            return Ok(None);
        }
        Ok(Some(target.ids))
    }

    fn rgb565(&self) -> Vec<u16> {
        self.frame.pixels.clone()
    }
}

impl Embedded3dgfxRenderer<'_> {
    /// The face of each draw primitive in the last recorded frame, found
    /// by recording every triangle alone; `None` when the primitives so
    /// recorded differ from the frame's.
    fn primitive_faces(&self) -> Result<Option<Vec<u32>>, String> {
        let scene = self.data.scene;
        let p = &scene.mesh.positions;
        let corners: Vec<[[f32; 3]; 3]> = self.data.faces.iter().map(|f| f.map(|v| p[v])).collect();
        let geometry = &self.mesh.geometry;
        let vertex_normals: Vec<[[f32; 3]; 3]> = if geometry.vertex_normals.is_empty() {
            Vec::new()
        } else {
            let n = geometry.vertex_normals;
            self.data.faces.iter().map(|f| f.map(|v| n[v])).collect()
        };
        let uvs: Vec<[[f32; 2]; 3]> = if geometry.uvs.is_empty() {
            Vec::new()
        } else {
            let uv = geometry.uvs;
            self.data.faces.iter().map(|f| f.map(|v| uv[v])).collect()
        };
        let cull = !self.mesh.geometry.normals.is_empty();
        let single = [[0usize, 1, 2]];
        let mut probe = K3dMesh::new(Geometry::new(&corners[0], &single));
        probe.similarity = self.mesh.similarity;
        probe.model_matrix = self.mesh.model_matrix;
        probe.render_mode = self.mesh.render_mode.clone();
        probe.color = self.mesh.color;
        let mut small = CommandBuffer::<16>::new();
        let mut frame = self.commands.iter().filter_map(|c| match c {
            RenderCommand::Draw(d) => Some(d),
            _ => None,
        });
        let mut owners = Vec::with_capacity(self.commands.len());
        for (t, tri) in corners.iter().enumerate() {
            let normal = &self.data.normals[t..t + 1];
            probe.geometry =
                Geometry::new(tri, &single).with_normals(if cull { normal } else { &[] });
            if let Some(n) = vertex_normals.get(t) {
                probe.geometry = probe.geometry.with_vertex_normals(n);
            }
            if let (Some(uv), Some(id)) = (uvs.get(t), geometry.texture_id) {
                probe.geometry = probe.geometry.with_uvs(uv).with_texture(id);
            }
            self.engine
                .record(core::iter::once(&probe), &mut small, None)
                .map_err(|e| format!("embedded-3dgfx: record: {e:?}"))?;
            for command in small.iter() {
                if let RenderCommand::Draw(d) = command {
                    match frame.next() {
                        Some(f) if same(f, d) => owners.push(scene.triangle_faces[t]),
                        _ => return Ok(None),
                    }
                }
            }
        }
        Ok(frame.next().is_none().then_some(owners))
    }
}

/// One mesh vertex after the frame's transform.
#[derive(Debug, Clone, Copy, Default)]
struct Projected {
    /// Pixel, as embedded-3dgfx's own projection truncates it.
    point: Point2<i32>,
    /// `z_ndc · (far - near) + near`, embedded-3dgfx's own depth (its
    /// `transform_point`), kept in `f32` rather than truncated to whole
    /// units: the rasteriser takes `depth · 2^16` as its 32-bit depth. A
    /// wider scale overflows its span stepper (`(Δz << 16) / span` in
    /// `i32`).
    depth: f32,
    /// Normalised device x and y, for the winding.
    ndc: [f32; 2],
    /// In front of the near plane.
    valid: bool,
}

/// embedded-3dgfx 0.7's triangle rasteriser fed by hand with shared,
/// once-transformed vertices: the fastest use of the crate we know (its
/// frame driver transforms each triangle's corners separately).
///
/// Timed region, per frame: clear the colour frame (`DrawTarget::clear`,
/// black) and the z-buffer (`fill(Z_MAX_VALUE)`); bring zline's light
/// and the eye into object space ([`Scene::object_light`]); transform
/// every vertex once (4×4 matrix, divide by w, pixel and depth as
/// embedded-3dgfx's `transform_point` computes them, the depth left in
/// `f32` instead of truncated to whole units); then
/// for each fan triangle with all corners in front of the near plane:
/// its winding from the corners' NDC, culled when clockwise and `--cull
/// back`; zline's two-sided Lambert colour from its object-space normal
/// (one dot product with the light, negated for a triangle seen from
/// behind; [`lambert_rgb565`]); one `ColoredTriangleWithDepth` handed to
/// `draw_zbuffered_with_state` with a `RasterState` built once per
/// frame, which fills it pixel by pixel through `draw_iter` against the
/// 32-bit z-buffer. No clipping (the view keeps every vertex in front of
/// the eye; the rasteriser clips to the frame).
///
/// Face ids: the frame drawn again, untimed, into a target that notes the
/// face of the triangle drawing each pixel.
pub struct Embedded3dgfxRasterRenderer<'a> {
    data: &'a MeshData<'a>,
    view: View,
    mvp: Mat4,
    projected: Vec<Projected>,
    zbuffer: Vec<ZDepth>,
    frame: Frame565,
}

impl<'a> Embedded3dgfxRasterRenderer<'a> {
    /// Builds the renderer for `view`.
    pub fn new(data: &'a MeshData<'a>, view: &View) -> Self {
        let scene = data.scene;
        let (w, h) = (usize::from(view.width), usize::from(view.height));
        Self {
            data,
            view: *view,
            mvp: scene.mvp(view),
            projected: vec![Projected::default(); scene.mesh.positions.len()],
            zbuffer: vec![Z_MAX_VALUE; w * h],
            frame: Frame565::new(w, h),
        }
    }

    /// Draws one frame into `target`, calling `before(target, t)` ahead
    /// of each triangle `t` it draws.
    fn draw<T>(&mut self, target: &mut T, mut before: impl FnMut(&mut T, usize))
    where
        T: DrawTarget<Color = Rgb565>,
        T::Error: core::fmt::Debug,
    {
        let scene = self.data.scene;
        self.zbuffer.fill(Z_MAX_VALUE);
        let light = scene.object_light(&self.view);
        let (w, h) = (f32::from(self.view.width), f32::from(self.view.height));
        for (p, out) in scene.mesh.positions.iter().zip(&mut self.projected) {
            let c = transform(&self.mvp, p);
            if c[3] <= NEAR {
                out.valid = false;
                continue;
            }
            let inv = 1.0 / c[3];
            let (x, y, z) = (c[0] * inv, c[1] * inv, c[2] * inv);
            *out = Projected {
                point: Point2::new(((1.0 + x) * 0.5 * w) as i32, ((1.0 - y) * 0.5 * h) as i32),
                depth: z * (FAR - NEAR) + NEAR,
                ndc: [x, y],
                valid: true,
            };
        }
        let state = RasterState::from_zbuffer(usize::from(self.view.width), self.zbuffer.len());
        let cull = self.view.cull == Cull::Back;
        for (t, (tri, n)) in scene
            .triangles
            .iter()
            .zip(&self.data.shared_normals)
            .enumerate()
        {
            let [a, b, c] = tri.map(|i| self.projected[i as usize]);
            if !(a.valid && b.valid && c.valid) {
                continue;
            }
            let winding = (b.ndc[0] - a.ndc[0]) * (c.ndc[1] - a.ndc[1])
                - (b.ndc[1] - a.ndc[1]) * (c.ndc[0] - a.ndc[0]);
            let front = winding > 0.0;
            if cull && !front {
                continue;
            }
            let d = dot(n, &light.light);
            let color = lambert_rgb565(if front { d } else { -d });
            before(target, t);
            draw_zbuffered_with_state(
                DrawPrimitive::ColoredTriangleWithDepth {
                    points: [a.point, b.point, c.point],
                    depths: [a.depth, b.depth, c.depth],
                    color: Rgb565::from(RawU16::new(color)),
                },
                target,
                &mut self.zbuffer,
                &state,
            );
        }
    }
}

impl Renderer for Embedded3dgfxRasterRenderer<'_> {
    fn name(&self) -> &str {
        "embedded-3dgfx raster shared"
    }

    fn timed_region(&self) -> String {
        "colour frame and z-buffer cleared, light into object space, every vertex transformed \
         once, per triangle: winding (culled with `--cull back`), zline's two-sided Lambert \
         from its object-space normal, `draw_zbuffered_with_state` (filled pixel by pixel \
         through `draw_iter`); 32-bit z-buffer of `(z_ndc·(far-near)+near)·2^16`"
            .into()
    }

    fn render(&mut self) -> Result<(), String> {
        let mut frame = core::mem::replace(&mut self.frame, Frame565::new(0, 0));
        let _ = frame.clear(Rgb565::BLACK);
        self.draw(&mut frame, |_, _| {});
        self.frame = frame;
        Ok(())
    }

    fn face_ids(&mut self) -> Result<Option<Vec<u32>>, String> {
        let (w, h) = (self.frame.width, self.frame.height);
        let mut target = IdTarget {
            ids: vec![BACKGROUND; w * h],
            colors: Frame565::new(w, h),
            current: BACKGROUND,
        };
        let faces = &self.data.scene.triangle_faces;
        self.draw(&mut target, |target, t| target.current = faces[t]);
        if target.colors != self.frame {
            eprintln!(
                "embedded-3dgfx raster shared: replayed frame differs from the timed one; no face ids"
            );
            return Ok(None);
        }
        Ok(Some(target.ids))
    }

    fn rgb565(&self) -> Vec<u16> {
        self.frame.pixels.clone()
    }
}

/// Whether two recorded primitives are the same triangle.
fn same(a: &DrawPrimitive, b: &DrawPrimitive) -> bool {
    match (a, b) {
        (
            DrawPrimitive::ColoredTriangleWithDepth {
                points: pa,
                depths: da,
                color: ca,
            },
            DrawPrimitive::ColoredTriangleWithDepth {
                points: pb,
                depths: db,
                color: cb,
            },
        ) => pa == pb && da == db && ca == cb,
        (
            DrawPrimitive::GouraudTriangleWithDepth {
                points: pa,
                depths: da,
                colors: ca,
            },
            DrawPrimitive::GouraudTriangleWithDepth {
                points: pb,
                depths: db,
                colors: cb,
            },
        ) => pa == pb && da == db && ca == cb,
        (
            DrawPrimitive::TexturedTriangleWithDepth {
                points: pa,
                depths: da,
                ws: wa,
                uvs: ua,
                texture_id: ia,
            },
            DrawPrimitive::TexturedTriangleWithDepth {
                points: pb,
                depths: db,
                ws: wb,
                uvs: ub,
                texture_id: ib,
            },
        ) => pa == pb && da == db && wa == wb && ua == ub && ia == ib,
        _ => false,
    }
}

/// A draw target that notes which face wrote each pixel.
struct IdTarget {
    ids: Vec<u32>,
    colors: Frame565,
    current: u32,
}

impl OriginDimensions for IdTarget {
    fn size(&self) -> Size {
        self.colors.size()
    }
}

impl DrawTarget for IdTarget {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        let (w, h) = (self.colors.width, self.colors.height);
        for Pixel(p, color) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as usize) < w && (p.y as usize) < h {
                let k = p.y as usize * w + p.x as usize;
                self.ids[k] = self.current;
                self.colors.pixels[k] = RawU16::from(color).into_inner();
            }
        }
        Ok(())
    }
}
