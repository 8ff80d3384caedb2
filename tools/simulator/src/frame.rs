//! Drawing one frame into the simulator display, by the scanline core or
//! by the float64 reference renderer.
//!
//! The scanline path is the same pipeline as `examples/render.rs`
//! (`reference_model`, `Camera::reference`, `draw_mesh`, lambert shading
//! by default, no culling, z24), with rows sent through
//! [`zline::DrawTargetSink`], so at the default view it gives the same
//! pixels as `cargo run --release --example render -- MODEL --out x.png`.

use std::time::Instant;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_simulator::SimulatorDisplay;
use zline::Shading;
use zline::host::HostMesh;
use zline::host::host_renderer;
use zline::host::{DEFAULT_CREASE_DEGREES, HostPaintedRenderer};
use zline::paint::{Gouraud, PaintMode, Texture, Textured};
use zline::{Camera, Cull, VertexCache, draw_mesh, reference_model};
use zline::{Depth16, Depth24, DepthFormat, DrawTargetSink, RenderError};
use zline::{Mat4, Vec3};
use zline_lab::methods::{BACKGROUND, MethodRenderer, ReferenceFrame, ReferenceView};

/// Most vertices a mesh may have (the vertex cache's capacity).
pub const MAX_MESH_VERTICES: usize = 65_536;

/// The core with host-sized capacities: rows up to 4096 pixels, 65,536
/// table vertices, 262,144 polygons, 786,432 corners, 32,768 active
/// polygons, 65,536 pooled edges, 32 corners per polygon.
type WindowRenderer<D> = zline::host::HostRenderer<Rgb888, D>;
/// The scanline core's Gouraud renderer.
type GouraudRenderer<D> = HostPaintedRenderer<Gouraud<Rgb888>, D>;
/// The scanline core's texture-mapping renderer.
type TexturedRenderer<D> = HostPaintedRenderer<Textured<'static, Rgb888>, D>;

/// Which method draws the frame: the core straight to the window, or any
/// of the comparison methods ([`zline_lab::methods::Method`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// The fixed-point scanline core.
    Scanline,
    /// A full-frame z-buffer.
    ZBuffer,
    /// A z-buffer of 8 rows at a time.
    Bands8,
    /// The interval scanline, no depth buffer.
    Interval,
    /// The painter's algorithm.
    Painter,
    /// The float64 reference renderer (slow for big meshes).
    Reference,
}

impl Method {
    /// Every method, in the order `m` cycles through them.
    pub const ALL: [Method; 6] = [
        Method::Scanline,
        Method::ZBuffer,
        Method::Bands8,
        Method::Interval,
        Method::Painter,
        Method::Reference,
    ];

    /// The next method (key `m`).
    pub fn next(self) -> Self {
        let k = Self::ALL.iter().position(|&m| m == self).unwrap_or(0);
        Self::ALL[(k + 1) % Self::ALL.len()]
    }

    /// Name for the overlay.
    pub fn name(self) -> &'static str {
        match self {
            Method::Scanline => "scanline",
            Method::ZBuffer => "zbuffer",
            Method::Bands8 => "bands:8",
            Method::Interval => "interval",
            Method::Painter => "painter",
            Method::Reference => "reference",
        }
    }

    /// The comparison method, for those the library's method renderer draws.
    fn comparison(self) -> Option<zline_lab::methods::Method> {
        use zline_lab::methods::Method as M;
        match self {
            Method::ZBuffer => Some(M::ZBuffer),
            Method::Bands8 => Some(M::Bands(8)),
            Method::Interval => Some(M::Interval),
            Method::Painter => Some(M::Painter),
            Method::Scanline | Method::Reference => None,
        }
    }
}

/// Which depth format the scanline core uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthChoice {
    /// [`Depth16`].
    Z16,
    /// [`Depth24`].
    Z24,
}

impl DepthChoice {
    /// The next format (key `d`).
    pub fn next(self) -> Self {
        match self {
            DepthChoice::Z16 => DepthChoice::Z24,
            DepthChoice::Z24 => DepthChoice::Z16,
        }
    }

    /// Name for the overlay.
    pub fn name(self) -> &'static str {
        match self {
            DepthChoice::Z16 => Depth16::NAME,
            DepthChoice::Z24 => Depth24::NAME,
        }
    }
}

/// The shadings key `s` cycles through, by name (see [`shading`]):
/// `gouraud` is Lambert per vertex, interpolated; `texture` maps the
/// texture perspective-correctly by the mesh's `vt` (both the scanline
/// core's painted renderers; the other methods draw Lambert per face).
pub const SHADINGS: [&str; 6] = ["lambert", "flat", "depth", "id", "gouraud", "texture"];

/// Index of `gouraud` in [`SHADINGS`].
const GOURAUD: usize = 4;
/// Index of `texture` in [`SHADINGS`].
const TEXTURE: usize = 5;

/// The overlay's name of `view`'s shading.
pub fn shading_name(view: &View) -> &'static str {
    match (view.shading % SHADINGS.len(), view.method) {
        (GOURAUD, Method::Scanline) => "gouraud",
        (TEXTURE, Method::Scanline) => "texture, perspective-correct",
        (GOURAUD | TEXTURE, _) => "lambert (gouraud, texture: scanline only)",
        (k, _) => SHADINGS[k],
    }
}

/// The shading at `index` into [`SHADINGS`], as the render tool's
/// `--shade` makes them.
pub fn shading(index: usize) -> Shading {
    match index % SHADINGS.len() {
        0 => Shading::lambert(),
        1 => Shading::Flat(Rgb888::new(200, 190, 170)),
        2 => Shading::Depth {
            near: 2.0,
            far: 4.0,
        },
        3 => Shading::FaceId,
        _ => Shading::lambert(),
    }
}

/// Everything that decides what one frame shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Degrees about the vertical axis.
    pub yaw: f32,
    /// Degrees about the horizontal axis.
    pub pitch: f32,
    /// Zoom steps: the model is scaled by `1.1^zoom`.
    pub zoom: i32,
    /// Index into [`SHADINGS`].
    pub shading: usize,
    /// Back-face culling.
    pub cull: Cull,
    /// Depth format of the scanline core.
    pub depth: DepthChoice,
    /// Renderer.
    pub method: Method,
}

impl Default for View {
    /// The render tool's defaults: yaw 30, pitch 20, no zoom, lambert, no
    /// culling, z24, scanline.
    fn default() -> Self {
        Self {
            yaw: 30.0,
            pitch: 20.0,
            zoom: 0,
            shading: 0,
            cull: Cull::None,
            depth: DepthChoice::Z24,
            method: Method::Scanline,
        }
    }
}

impl View {
    /// The model matrix: [`reference_model`], then the zoom as a uniform
    /// scale (left out at zoom 0, so the default view is exactly the render
    /// tool's).
    pub fn model(&self, mesh: &HostMesh) -> Result<Mat4, String> {
        let model = reference_model(mesh, self.yaw, self.pitch).map_err(|e| e.to_string())?;
        Ok(if self.zoom == 0 {
            model
        } else {
            let s = 1.1f32.powi(self.zoom);
            Mat4::scale(Vec3::new(s, s, s)).mul(&model)
        })
    }
}

/// What the overlay reports about the last frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrameReport {
    /// Milliseconds spent rendering (draw_mesh + render for the scanline
    /// core; the reference render when it had to run again).
    pub ms: f64,
    /// Polygons in the polygon table (scanline), or faces seen (reference).
    pub polygons: u32,
    /// Bytes a renderer sized for this scene needs, plus the vertex cache
    /// (scanline only).
    pub ram_bytes: Option<usize>,
}

/// The last reference frame, coloured, kept while the view stays the same.
struct ReferenceCache {
    key: (f32, f32, Cull, usize),
    colors: Vec<Rgb888>,
    visible: u32,
    ms: f64,
}

/// The renderers, on the heap: one scanline core per depth format, the
/// vertex cache, and the last reference frame.
pub struct Renderers {
    width: u16,
    height: u16,
    z16: Box<WindowRenderer<Depth16>>,
    z24: Box<WindowRenderer<Depth24>>,
    cache: Box<VertexCache<MAX_MESH_VERTICES>>,
    reference: Option<ReferenceCache>,
    /// The comparison methods' renderers, made on first use.
    methods16: Option<Box<MethodRenderer<Depth16>>>,
    methods24: Option<Box<MethodRenderer<Depth24>>>,
    /// The Gouraud renderers and the mesh with vertex normals (keyed by
    /// the flat mesh's address and sizes), made on first use.
    gouraud16: Option<Box<GouraudRenderer<Depth16>>>,
    gouraud24: Option<Box<GouraudRenderer<Depth24>>>,
    smooth: Option<((usize, usize, usize), HostMesh)>,
    /// The texture-mapping renderers, made on first use, and the texture.
    textured16: Option<Box<TexturedRenderer<Depth16>>>,
    textured24: Option<Box<TexturedRenderer<Depth24>>>,
    texture: Texture<'static>,
}

/// The texture when none is given: an 8x8 checker of two creams.
static CHECKER: [u16; 64] = {
    let mut t = [0; 64];
    let mut k = 0;
    while k < 64 {
        t[k] = if (k % 8 + k / 8) % 2 == 0 {
            0xFFDB
        } else {
            0x6A69
        };
        k += 1;
    }
    t
};

impl Renderers {
    /// Renderers for `width` x `height` frames. Each core takes tens of MB
    /// and is built on the stack before it moves to the heap: call this on
    /// a thread with a large stack.
    pub fn new(width: u16, height: u16) -> Result<Self, String> {
        let e = |e: zline::Error| format!("renderer: {e}");
        let caps = &zline_lab::methods::HOST_CAPACITIES;
        let z16 = Box::new(host_renderer(caps, width, height, Rgb888::BLACK).map_err(e)?);
        let z24 = Box::new(host_renderer(caps, width, height, Rgb888::BLACK).map_err(e)?);
        Ok(Self {
            width,
            height,
            z16,
            z24,
            cache: Box::new(VertexCache::new()),
            reference: None,
            methods16: None,
            methods24: None,
            gouraud16: None,
            gouraud24: None,
            smooth: None,
            textured16: None,
            textured24: None,
            texture: Texture::new(&CHECKER, 8, 8).map_err(e)?,
        })
    }

    /// Maps `texture` in the `texture` shading (an 8x8 checker until
    /// then).
    pub fn set_texture(&mut self, texture: Texture<'static>) {
        self.texture = texture;
        self.textured16 = None;
        self.textured24 = None;
    }

    /// Draws the painted shadings from `mesh` (read with its normals and
    /// texture coordinates) instead of vertex normals computed from the
    /// flat mesh `flat`.
    pub fn set_smooth(&mut self, flat: &HostMesh, mesh: HostMesh) {
        self.smooth = Some((Self::key(flat), mesh));
    }

    /// What identifies a flat mesh for its smooth one.
    fn key(mesh: &HostMesh) -> (usize, usize, usize) {
        (
            mesh as *const HostMesh as usize,
            mesh.positions.len(),
            mesh.corners.len(),
        )
    }

    /// Draws `mesh` as `view` says into every pixel of `display`.
    pub fn draw(
        &mut self,
        mesh: &HostMesh,
        view: &View,
        display: &mut SimulatorDisplay<Rgb888>,
    ) -> Result<FrameReport, String> {
        let painted = view.shading % SHADINGS.len();
        if view.method == Method::Scanline && (painted == GOURAUD || painted == TEXTURE) {
            return self.painted(mesh, view, display);
        }
        match (view.method, view.depth) {
            (Method::Scanline, DepthChoice::Z16) => {
                scanline(&mut self.z16, &mut self.cache, mesh, view, display)
            }
            (Method::Scanline, DepthChoice::Z24) => {
                scanline(&mut self.z24, &mut self.cache, mesh, view, display)
            }
            (Method::Reference, _) => Ok(self.reference(mesh, view, display)),
            (method, depth) => {
                let comparison = method.comparison().ok_or("no such method")?;
                let (w, h) = (self.width, self.height);
                match depth {
                    DepthChoice::Z16 => {
                        let r = match &mut self.methods16 {
                            Some(r) => r,
                            slot => slot.insert(Box::new(MethodRenderer::new(w, h)?)),
                        };
                        compared(r, comparison, mesh, view, display)
                    }
                    DepthChoice::Z24 => {
                        let r = match &mut self.methods24 {
                            Some(r) => r,
                            slot => slot.insert(Box::new(MethodRenderer::new(w, h)?)),
                        };
                        compared(r, comparison, mesh, view, display)
                    }
                }
            }
        }
    }

    /// A Gouraud or textured frame by the scanline core's painted
    /// renderers, of the mesh with vertex normals (60° crease) and its
    /// texture coordinates.
    fn painted(
        &mut self,
        mesh: &HostMesh,
        view: &View,
        display: &mut SimulatorDisplay<Rgb888>,
    ) -> Result<FrameReport, String> {
        let key = Self::key(mesh);
        if self.smooth.as_ref().is_none_or(|(k, _)| *k != key) {
            let smooth = mesh
                .clone()
                .with_vertex_normals(DEFAULT_CREASE_DEGREES)
                .map_err(|e| format!("vertex normals: {e}"))?;
            self.smooth = Some((key, smooth));
        }
        let Some((_, smooth)) = &self.smooth else {
            return Err("no smooth mesh".into());
        };
        let caps = zline::Capacities {
            mesh_vertices: MAX_MESH_VERTICES,
            ..zline_lab::methods::HOST_CAPACITIES
        };
        let size = (self.width, self.height);
        let shade = Shading::lambert();
        let lit = |v: &zline::VertexInfo<'_>| shade.vertex_color(v);
        let textured = view.shading % SHADINGS.len() == TEXTURE;
        let texture = Textured::new(self.texture);
        match (view.depth, textured) {
            (DepthChoice::Z16, false) => {
                let r = painted_renderer(&mut self.gouraud16, &caps, size, Gouraud::new())?;
                painted_frame(r, smooth, view, display, lit)
            }
            (DepthChoice::Z24, false) => {
                let r = painted_renderer(&mut self.gouraud24, &caps, size, Gouraud::new())?;
                painted_frame(r, smooth, view, display, lit)
            }
            (DepthChoice::Z16, true) => {
                let r = painted_renderer(&mut self.textured16, &caps, size, texture)?;
                painted_frame(r, smooth, view, display, |v| v.tex_coord())
            }
            (DepthChoice::Z24, true) => {
                let r = painted_renderer(&mut self.textured24, &caps, size, texture)?;
                painted_frame(r, smooth, view, display, |v| v.tex_coord())
            }
        }
    }

    fn reference(
        &mut self,
        mesh: &HostMesh,
        view: &View,
        display: &mut SimulatorDisplay<Rgb888>,
    ) -> FrameReport {
        let key = (view.yaw, view.pitch, view.cull, view.shading);
        if self.reference.as_ref().is_none_or(|r| r.key != key) {
            let start = Instant::now();
            let frame = ReferenceFrame::render(
                mesh,
                &ReferenceView {
                    width: usize::from(self.width),
                    height: usize::from(self.height),
                    yaw_deg: f64::from(view.yaw),
                    pitch_deg: f64::from(view.pitch),
                    cull_back: view.cull == Cull::Back,
                },
            );
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let shade = shading(view.shading);
            let colors = frame.colors(&shade);
            let mut seen: Vec<u32> = frame
                .ids
                .iter()
                .copied()
                .filter(|&i| i != BACKGROUND)
                .collect();
            seen.sort_unstable();
            seen.dedup();
            self.reference = Some(ReferenceCache {
                key,
                colors,
                visible: seen.len() as u32,
                ms,
            });
        }
        let Some(cached) = &self.reference else {
            return FrameReport::default();
        };
        let width = u32::from(self.width);
        for (y, row) in cached.colors.chunks(usize::from(self.width)).enumerate() {
            let area = Rectangle::new(Point::new(0, y as i32), Size::new(width, 1));
            let Ok(()) = display.fill_contiguous(&area, row.iter().copied());
        }
        FrameReport {
            ms: cached.ms,
            polygons: cached.visible,
            ram_bytes: None,
        }
    }
}

/// One frame by a comparison method, copied into the window.
fn compared<D: DepthFormat>(
    renderer: &mut MethodRenderer<D>,
    method: zline_lab::methods::Method,
    mesh: &HostMesh,
    view: &View,
    display: &mut SimulatorDisplay<Rgb888>,
) -> Result<FrameReport, String>
where
    D::Value: Into<u32>,
{
    let size = display.size();
    let (w, h) = (size.width as u16, size.height as u16);
    let camera = Camera::reference(w, h);
    let model = view.model(mesh)?;
    let reference = ReferenceView {
        width: usize::from(w),
        height: usize::from(h),
        yaw_deg: f64::from(view.yaw),
        pitch_deg: f64::from(view.pitch),
        cull_back: view.cull == Cull::Back,
    };
    let start = Instant::now();
    let frame = renderer.render(
        method,
        mesh,
        &model,
        &camera,
        view.cull,
        &shading(view.shading),
        &reference,
    )?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    for (y, row) in frame.colors.chunks(usize::from(w)).enumerate() {
        let area = Rectangle::new(Point::new(0, y as i32), Size::new(u32::from(w), 1));
        let Ok(()) = display.fill_contiguous(&area, row.iter().copied());
    }
    Ok(FrameReport {
        ms,
        polygons: frame.draw.queued,
        ram_bytes: Some(frame.memory.total() + 2 * mesh.positions.len()),
    })
}

/// The painted renderer in `slot`, made with `mode` on first use.
fn painted_renderer<'a, M: PaintMode<Color = Rgb888>, D: DepthFormat>(
    slot: &'a mut Option<Box<HostPaintedRenderer<M, D>>>,
    caps: &zline::Capacities,
    size: (u16, u16),
    mode: M,
) -> Result<&'a mut HostPaintedRenderer<M, D>, String> {
    if slot.is_none() {
        let renderer = HostPaintedRenderer::with_capacities(caps, size, mode, Rgb888::BLACK)
            .map_err(|e| format!("renderer: {e}"))?;
        *slot = Some(Box::new(renderer));
    }
    slot.as_deref_mut()
        .ok_or_else(|| "no painted renderer".to_string())
}

/// One frame by a painted renderer: clear, draw with each vertex's value
/// from `value`, render through a [`DrawTargetSink`].
fn painted_frame<M: PaintMode<Color = Rgb888>, D: DepthFormat>(
    renderer: &mut HostPaintedRenderer<M, D>,
    mesh: &HostMesh,
    view: &View,
    display: &mut SimulatorDisplay<Rgb888>,
    value: impl Fn(&zline::VertexInfo<'_>) -> M::Source,
) -> Result<FrameReport, String> {
    let camera = Camera::reference(renderer.width(), renderer.height());
    let model = view.model(mesh)?;
    let start = Instant::now();
    renderer.clear();
    renderer
        .draw_mesh(mesh, &model, &camera, view.cull, value)
        .map_err(|e| format!("draw_mesh: {e}"))?;
    let stats = renderer
        .render(&mut DrawTargetSink::new(display))
        .map_err(|e| match e {
            RenderError::Table(e) => format!("render: {e}"),
            RenderError::Sink(never) => match never {},
        })?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(FrameReport {
        ms,
        polygons: stats.polygons,
        ram_bytes: None,
    })
}

/// One frame by the scanline core: clear, [`draw_mesh`], render through a
/// [`DrawTargetSink`] (one `fill_contiguous` per row).
fn scanline<D: DepthFormat>(
    renderer: &mut WindowRenderer<D>,
    cache: &mut VertexCache<MAX_MESH_VERTICES>,
    mesh: &HostMesh,
    view: &View,
    display: &mut SimulatorDisplay<Rgb888>,
) -> Result<FrameReport, String> {
    let camera = Camera::reference(renderer.width(), renderer.height());
    let model = view.model(mesh)?;
    let shade = shading(view.shading);
    let start = Instant::now();
    renderer.clear();
    draw_mesh(renderer, cache, mesh, &model, &camera, view.cull, |f| {
        shade.color(f)
    })
    .map_err(|e| format!("draw_mesh: {e}"))?;
    let stats = renderer
        .render(&mut DrawTargetSink::new(display))
        .map_err(|e| match e {
            RenderError::Table(e) => format!("render: {e}"),
            RenderError::Sink(never) => match never {},
        })?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let cache_bytes = 2 * mesh.positions.len();
    Ok(FrameReport {
        ms,
        polygons: stats.polygons,
        ram_bytes: Some(stats.ram_bytes::<Rgb565, D>(usize::from(renderer.width())) + cache_bytes),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every method, depth format, shading and culling draws; the reference
    /// at the default view has the scanline's silhouette almost everywhere.
    #[test]
    fn every_mode_draws() {
        let run = || {
            let mesh = zline_lab::shapes::by_name("torus-knot").unwrap();
            let (w, h) = (96u16, 72u16);
            let mut r = Renderers::new(w, h).unwrap();
            let size = Size::new(u32::from(w), u32::from(h));
            let mut frames = Vec::new();
            for method in Method::ALL {
                for depth in [DepthChoice::Z16, DepthChoice::Z24] {
                    for shading in 0..SHADINGS.len() {
                        for cull in [Cull::None, Cull::Back] {
                            for zoom in [0, 3] {
                                let view = View {
                                    method,
                                    depth,
                                    shading,
                                    cull,
                                    zoom,
                                    ..View::default()
                                };
                                let mut display = SimulatorDisplay::<Rgb888>::new(size);
                                let report = r.draw(&mesh, &view, &mut display).unwrap();
                                assert!(report.polygons > 0);
                                let painted = method == Method::Scanline
                                    && (shading == GOURAUD || shading == TEXTURE);
                                assert_eq!(
                                    report.ram_bytes.is_some(),
                                    method != Method::Reference && !painted
                                );
                                frames.push((view, display));
                            }
                        }
                    }
                }
            }
            let lit = |d: &SimulatorDisplay<Rgb888>| {
                d.bounding_box()
                    .points()
                    .map(|p| d.get_pixel(p) != Rgb888::BLACK)
                    .collect::<Vec<_>>()
            };
            let scan = lit(&frames[0].1);
            let reference = frames
                .iter()
                .find(|(v, _)| v.method == Method::Reference && v.zoom == 0)
                .map(|(_, d)| lit(d))
                .unwrap();
            let differ = scan.iter().zip(&reference).filter(|(a, b)| a != b).count();
            assert!(scan.iter().filter(|&&x| x).count() > 500);
            assert!(differ < 40, "{differ} pixels differ in coverage");
        };
        run();
    }
}
