//! The scanline core with host-sized capacities, for the render and
//! accuracy tools: faces up to 262,144 polygons and 65,534 table vertices,
//! frames up to 4096 wide.

use std::boxed::Box;
use std::vec;
use std::vec::Vec;

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use super::reference::BACKGROUND;
use zline::Capacities;
use zline::DepthFormat;
use zline::FnSink;
use zline::FrameStats;
use zline::Mat4;
use zline::Mesh;
use zline::Shading;
use zline::host::host_renderer;
use zline::{Camera, Cull, DrawError, DrawStats, VertexCache, draw_mesh};
use zline::{Error, RenderError};

/// What the host renderer stores per pixel: the face and its colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HostPixel {
    /// Face id, or [`BACKGROUND`].
    pub face: u32,
    /// Shaded colour.
    pub color: Rgb888,
}

/// The core with capacities for any mesh in `../shared/meshes`.
pub type HostRenderer<D> = zline::host::HostRenderer<HostPixel, D>;

/// Capacities for any mesh the host tools load: 65,536 vertices, 262,144
/// polygons, 786,432 corners, 32,768 polygons and 65,536 pooled edges
/// active on a row, rows up to 4,096 pixels (about 15 MB, on the heap).
pub const HOST_CAPACITIES: Capacities = Capacities {
    width: 4096,
    vertices: 65_536,
    polygons: 262_144,
    corners: 786_432,
    active_polygons: 32_768,
    pooled_edges: 65_536,
    mesh_vertices: 0,
};

/// A finished frame: face id and colour per pixel, row-major from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct HostFrame {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Face id per pixel ([`BACKGROUND`] for none).
    pub faces: Vec<u32>,
    /// Colour per pixel.
    pub colors: Vec<Rgb888>,
    /// Depth per pixel as stored by the format, widened to `u32`.
    pub depths: Vec<u32>,
}

/// The scanline core on the heap with its vertex cache.
pub struct HostScanline<D: DepthFormat> {
    renderer: Box<HostRenderer<D>>,
    cache: Box<VertexCache<65536>>,
    frame: HostFrame,
}

impl<D: DepthFormat> HostScanline<D>
where
    D::Value: Into<u32>,
{
    /// A renderer for `width` x `height` frames. The renderer is about
    /// 20 MB and is built on the stack before it moves to the heap: call
    /// this on a thread with a large stack.
    pub fn new(width: u16, height: u16) -> Result<Self, Error> {
        let background = HostPixel {
            face: BACKGROUND,
            color: Rgb888::BLACK,
        };
        let renderer = Box::new(host_renderer(&HOST_CAPACITIES, width, height, background)?);
        let (w, h) = (usize::from(width), usize::from(height));
        Ok(Self {
            renderer,
            cache: Box::default(),
            frame: HostFrame {
                width: w,
                height: h,
                faces: vec![BACKGROUND; w * h],
                colors: vec![Rgb888::BLACK; w * h],
                depths: vec![0; w * h],
            },
        })
    }

    /// Draws one whole frame: clears the tables, runs the scene pipeline
    /// and the scanline core, and copies each finished row into
    /// [`Self::frame`].
    pub fn render<M: Mesh>(
        &mut self,
        mesh: &M,
        model: &Mat4,
        camera: &Camera,
        cull: Cull,
        shading: &Shading,
    ) -> Result<(DrawStats, FrameStats), DrawError> {
        self.renderer.clear();
        let draw = draw_mesh(
            &mut *self.renderer,
            &mut *self.cache,
            mesh,
            model,
            camera,
            cull,
            |f| HostPixel {
                face: f.face,
                color: shading.color(f),
            },
        )?;
        let frame = &mut self.frame;
        let w = frame.width;
        let stats = self
            .renderer
            .render(&mut FnSink(
                |y: u16, row: &[HostPixel], depth: &[D::Value]| {
                    let start = usize::from(y) * w;
                    for (k, (p, z)) in row.iter().zip(depth).enumerate() {
                        frame.faces[start + k] = p.face;
                        frame.colors[start + k] = p.color;
                        frame.depths[start + k] = (*z).into();
                    }
                    Ok::<(), core::convert::Infallible>(())
                },
            ))
            .map_err(|e| match e {
                RenderError::Table(error) => DrawError { face: None, error },
                RenderError::Sink(never) => match never {},
            })?;
        Ok((draw, stats))
    }

    /// The last frame rendered.
    pub fn frame(&self) -> &HostFrame {
        &self.frame
    }
}
