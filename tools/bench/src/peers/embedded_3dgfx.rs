//! embedded-3dgfx 0.7 behind the [`Renderer`] trait.
//!
//! embedded-3dgfx's intended use is its frame driver: a `K3dengine` with
//! a camera, a `K3dMesh` over borrowed `Geometry` (vertices, triangle
//! faces as `[usize; 3]`, optional per-face normals), `engine.record`
//! into a fixed-capacity `CommandBuffer`, then `engine.execute` into an
//! embedded-graphics `DrawTarget<Color = Rgb565>` with a caller-owned
//! z-buffer (`FrameCtx`). The crate is used with its default features
//! (32-bit `ZDepth`), as it comes.

use core::convert::Infallible;

use embedded_3dgfx::engine::K3dengine;
use embedded_3dgfx::pipeline::assemble::primitive::DrawPrimitive;
use embedded_3dgfx::pipeline::command_buffer::{CommandBuffer, RenderCommand};
use embedded_3dgfx::pipeline::rasterize::draw::zbuffered::draw_zbuffered_with_state;
use embedded_3dgfx::pipeline::renderer::FrameCtx;
use embedded_3dgfx::pipeline::vertex::mesh::{Geometry, K3dMesh, RenderMode};
use embedded_3dgfx::{Z_MAX_VALUE, ZDepth};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::prelude::*;
use nalgebra::{Point3, UnitQuaternion, Vector3};

use crate::framebuffer::Frame565;
use crate::renderer::Renderer;
use crate::view::{BACKGROUND, Cull, FAR, FOV_Y_DEG, NEAR, Scene, View};

/// Capacity of the command buffer: draw primitives per frame (a triangle
/// clipped by the frustum sides can become several).
pub const MAX_COMMANDS: usize = 1 << 18;

/// The mesh arrays a `K3dMesh` borrows, built once per mesh.
pub struct MeshData<'a> {
    scene: &'a Scene,
    faces: Vec<[usize; 3]>,
    normals: Vec<[f32; 3]>,
}

impl<'a> MeshData<'a> {
    /// Fan triangles as `[usize; 3]` and their unit normals
    /// (`Geometry::compute_face_normals_into`, counter-clockwise front).
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
        }
    }
}

/// embedded-3dgfx 0.7, `RenderMode::Solid`.
///
/// Timed region: clear the colour frame (`DrawTarget::clear`), then
/// `engine.record(mesh)`, which checks the mesh's bounding sphere against
/// the frustum, multiplies each triangle's three corners by the
/// model-view-projection matrix (no vertex sharing), culls, clips against
/// the near and side planes, projects to integer pixels and integer
/// depth, and stores one `ColoredTriangleWithDepth` per triangle; then
/// `engine.execute`, which clears the z-buffer (the recorded `ClearDepth`)
/// and rasterises every primitive with its scanline z-buffered fill,
/// pixel by pixel through `DrawTarget::draw_iter`.
///
/// Culling: the engine's own back-face test, which it applies only when
/// the geometry has per-face normals: `(eye - v0) · n < 0` in world space.
/// So `--cull back` passes the triangles' normals and `none` passes none.
///
/// Shading: `Solid` draws the whole mesh in one colour (`K3dMesh::color`);
/// per-face colour exists only in its `lighting` modes, which always cull
/// and do not clip, so the frames are single-coloured (the Lambert base
/// colour). Depth is `(z_ndc · (far - near) + near) as i32`, whole units
/// of world distance between about -10 and 10: with near 0.1 and far 10
/// the whole mesh gets one depth value, and the last triangle drawn wins.
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
}

impl<'a> Embedded3dgfxRenderer<'a> {
    /// Builds the engine, camera and mesh for `view`.
    pub fn new(data: &'a MeshData<'a>, view: &View) -> Result<Self, String> {
        let scene = data.scene;
        let (w, h) = (usize::from(view.width), usize::from(view.height));
        let mut engine = K3dengine::new(view.width, view.height);
        engine.camera.set_fovy(FOV_Y_DEG.to_radians());
        engine.camera.set_near_far(NEAR, FAR);
        engine.camera.set_position(Point3::new(0.0, 0.0, 3.0));
        engine.camera.set_target(Point3::new(0.0, 0.0, 0.0));
        let normals: &[[f32; 3]] = match view.cull {
            Cull::None => &[],
            Cull::Back => &data.normals,
        };
        let geometry = Geometry::new(&scene.mesh.positions, &data.faces).with_normals(normals);
        let mut mesh = K3dMesh::new(geometry);
        place(&mut mesh, scene, view);
        Ok(Self {
            data,
            engine,
            mesh,
            commands: Box::new(CommandBuffer::new()),
            zbuffer: vec![Z_MAX_VALUE; w * h],
            frame: Frame565::new(w, h),
        })
    }
}

/// Solid mode, the base colour, and the reference model matrix as the
/// mesh's similarity: scale `1/r`, rotation `Rx(pitch) · Ry(yaw)`,
/// translation `-R·c/r`.
fn place(mesh: &mut K3dMesh<'_>, scene: &Scene, view: &View) {
    mesh.set_render_mode(RenderMode::Solid);
    mesh.set_color(Rgb565::from(RawU16::new(Scene::base_color())));
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
        "embedded-3dgfx"
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
        self.engine
            .execute(&mut self.frame, &mut ctx, &self.commands, None)
            .map_err(|e| format!("embedded-3dgfx: execute: {e:?}"))?;
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
                    draw_zbuffered_with_state(
                        primitive.clone(),
                        &mut target,
                        &mut self.zbuffer,
                        &state,
                    );
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
