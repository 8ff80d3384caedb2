//! What the integration tests share: the exact oracle (from
//! `zline_lab::methods::exact`), frame capture, and recording tables.
#![allow(dead_code)]

use zline::{DepthFormat, FnSink, Renderer, ScreenVertex};
use zline::{ScanArrays, TableArrays};
#[allow(unused_imports)]
pub use zline_lab::methods::exact::{covers, exact_depth, exactly_rounded, format_scale, sample};

/// A frame captured from the renderer: colour and depth per pixel.
pub struct Frame<Z> {
    pub width: usize,
    pub height: usize,
    pub colors: Vec<u32>,
    pub depths: Vec<Z>,
    pub rows_written: Vec<u16>,
}

impl<Z: Copy> Frame<Z> {
    pub fn color(&self, i: usize, j: usize) -> u32 {
        self.colors[j * self.width + i]
    }
    pub fn depth(&self, i: usize, j: usize) -> Z {
        self.depths[j * self.width + i]
    }
    /// The frame as text, one char per pixel: '.' for 0, else
    /// `alphabet[color - 1]`.
    pub fn art(&self, alphabet: &str) -> String {
        let chars: Vec<char> = alphabet.chars().collect();
        let mut s = String::new();
        for j in 0..self.height {
            for i in 0..self.width {
                let c = self.color(i, j);
                s.push(if c == 0 { '.' } else { chars[(c - 1) as usize] });
            }
            s.push('\n');
        }
        s
    }
}

/// Renders with colours `u32` and captures the frame.
pub fn capture<
    D: DepthFormat,
    const W: usize,
    const V: usize,
    const P: usize,
    const E: usize,
    const AP: usize,
    const AE: usize,
>(
    renderer: &mut Renderer<TableArrays<u32, V, P, E>, ScanArrays<u32, D, W, AP, AE>>,
) -> (Frame<D::Value>, zline::FrameStats) {
    let h = usize::from(renderer.height());
    let mut frame = Frame {
        width: W,
        height: h,
        colors: vec![0; W * h],
        depths: vec![D::CLEAR; W * h],
        rows_written: Vec::new(),
    };
    let stats = renderer
        .render(&mut FnSink(
            |y: u16, colors: &[u32], depths: &[D::Value]| {
                let row = usize::from(y) * W;
                frame.colors[row..row + W].copy_from_slice(colors);
                frame.depths[row..row + W].copy_from_slice(depths);
                frame.rows_written.push(y);
                Ok::<(), ()>(())
            },
        ))
        .expect("render");
    (frame, stats)
}

/// Pixel-corner coordinates (whole pixels) to a vertex.
pub fn vtx(x: f32, y: f32, z: f32) -> ScreenVertex {
    ScreenVertex::from_f32(x, y, z).expect("valid vertex")
}

/// Dense art from a text block: strips leading/trailing blank lines and
/// indentation.
pub fn art(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(|l| format!("{l}\n"))
        .collect()
}

/// Polygon tables that only record what the scene pipeline offers them:
/// every queued polygon's corners as screen vertices. They judge polygons
/// with the core's own outline (zero area, no sample) so the pipeline sees
/// the same verdicts.
pub struct Recorder {
    pub width: u16,
    pub height: u16,
    pub vertices: Vec<zline::ScreenVertex>,
    pub polygons: Vec<(Vec<zline::ScreenVertex>, u32)>,
    /// Shared planes given: (polygon index, the plane's three corners).
    pub shared_planes: Vec<(usize, [zline::ScreenVertex; 3])>,
    open: Vec<u16>,
    mark: Option<usize>,
}

impl Recorder {
    pub fn new(width: u16, height: u16) -> Self {
        Self {
            width,
            height,
            vertices: Vec::new(),
            polygons: Vec::new(),
            shared_planes: Vec::new(),
            open: Vec::new(),
            mark: None,
        }
    }

    fn offer(
        &mut self,
        ids: Vec<u16>,
        decide: impl FnOnce(&zline::Outline) -> Option<u32>,
    ) -> zline::Admission {
        let corners: Vec<zline::ScreenVertex> =
            ids.iter().map(|&i| self.vertices[usize::from(i)]).collect();
        let mut outline = zline::OutlineBuilder::default();
        corners.iter().for_each(|&v| outline.add(v));
        let outline = outline.finish();
        if outline.twice_area == 0 {
            return zline::Admission::Degenerate;
        }
        let rect = outline.rect.expect("corners");
        if rect.sample_rows(self.width, self.height).is_none() {
            return zline::Admission::OffScreen;
        }
        match decide(&outline) {
            Some(color) => {
                self.polygons.push((corners, color));
                zline::Admission::Queued(self.polygons.len() as u32 - 1)
            }
            None => zline::Admission::Declined,
        }
    }
}

impl zline::PolygonTables<u32> for Recorder {
    fn frame_width(&self) -> u16 {
        self.width
    }
    fn frame_height(&self) -> u16 {
        self.height
    }
    fn add_vertex(&mut self, vertex: zline::ScreenVertex) -> Result<u16, zline::Error> {
        self.vertices.push(vertex);
        Ok((self.vertices.len() - 1) as u16)
    }
    fn get_vertex(&self, index: u16) -> Option<zline::ScreenVertex> {
        self.vertices.get(usize::from(index)).copied()
    }
    fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&zline::Outline) -> Option<u32>,
    ) -> Result<zline::Admission, zline::Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        let ids: Vec<u16> = corners.into_iter().collect();
        Ok(self.offer(ids, decide))
    }
    fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, zline::Error> {
        let last = self.polygons.len().checked_sub(1);
        let last = last.ok_or(zline::Error::NoPolygonToShare)?;
        let corner = |k: usize| self.vertices[usize::from(plane[k])];
        self.shared_planes
            .push((last, [corner(0), corner(1), corner(2)]));
        Ok(true)
    }
    fn begin_polygon(&mut self) {
        self.discard_polygon();
        self.mark = Some(self.vertices.len());
    }
    fn discard_polygon(&mut self) {
        self.open.clear();
        if let Some(mark) = self.mark.take() {
            self.vertices.truncate(mark);
        }
    }
    fn add_corner(&mut self, vertex: u16) -> Result<(), zline::Error> {
        self.open.push(vertex);
        Ok(())
    }
    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&zline::Outline) -> Option<u32>,
    ) -> Result<zline::Admission, zline::Error> {
        let ids = std::mem::take(&mut self.open);
        let admission = self.offer(ids, decide);
        if !matches!(admission, zline::Admission::Queued(_)) {
            self.discard_polygon();
        }
        self.mark = None;
        Ok(admission)
    }
}

/// Rows as a sink receives them: row, colours, depths widened to `u64`.
pub type Rows = Vec<(u16, Vec<u32>, Vec<u64>)>;

/// The rows the scanline core sends for prepared tables, `W` wide.
pub fn scanline_rows<D: DepthFormat, const W: usize>(prepared: &zline::Prepared<'_, u32>) -> Rows
where
    D::Value: Into<u64>,
{
    let mut scanner = zline::Scanner::new(ScanArrays::<u32, D, W, 32, 64>::new(0), 0);
    let mut rows = Vec::new();
    zline::scan(
        prepared,
        &mut scanner,
        0..prepared.height(),
        &mut FnSink(|y: u16, c: &[u32], z: &[D::Value]| {
            rows.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
            Ok::<(), ()>(())
        }),
    )
    .unwrap();
    rows
}

/// The rows the z-buffer sends for tables in drawing order, in bands of
/// `k` rows, with `test` and the drawing `order` (`None`: as added).
pub fn zbuffer_rows<D: DepthFormat>(
    drawn: &zline::Prepared<'_, u32>,
    k: u16,
    test: zline::zbuffer::DepthTest,
    order: Option<&[u32]>,
) -> Rows
where
    D::Value: Into<u64>,
{
    let width = usize::from(drawn.width());
    let n = usize::from(k) * width;
    let (mut depth, mut color, mut scratch) = (vec![D::CLEAR; n], vec![0u32; n], vec![0u32; width]);
    let mut active = vec![zline::ActivePolygon::filler(0u32); 1];
    let mut pool = vec![zline::ActiveEdge::EMPTY; 16];
    let mut rows = Vec::new();
    zline::zbuffer::render_bands::<u32, D, _>(
        drawn,
        zline::zbuffer::BandBuffers {
            depth: &mut depth,
            color: &mut color,
            scratch: &mut scratch,
            active: &mut active,
            pool: &mut pool,
        },
        k,
        0,
        test,
        order,
        &mut FnSink(|y: u16, c: &[u32], z: &[D::Value]| {
            rows.push((y, c.to_vec(), z.iter().map(|&v| v.into()).collect()));
            Ok::<(), ()>(())
        }),
    )
    .unwrap();
    rows
}

/// Screen polygons of 3 to `max_corners` corners (concave ones too), from
/// `margin` pixels off a `width` x `height` frame to inside, any depth.
pub fn random_polygon(
    width: u16,
    height: u16,
    margin: i32,
    max_corners: usize,
) -> impl proptest::strategy::Strategy<Value = Vec<ScreenVertex>> {
    use proptest::prelude::*;
    let s = zline::limits::SUBPIXEL_STEPS;
    prop::collection::vec(
        (
            -margin * s..(i32::from(width) + margin) * s,
            -margin * s..(i32::from(height) + margin) * s,
            0..=zline::limits::DEPTH_MAX,
        ),
        3..=max_corners,
    )
    .prop_map(|corners| {
        corners
            .into_iter()
            .map(|(x, y, z)| ScreenVertex { x, y, z })
            .collect()
    })
}

/// `Vec`-backed tables of `caps` holding `scene`, polygon `k` coloured
/// `k + 1`.
pub fn scene_tables(
    scene: &[Vec<ScreenVertex>],
    caps: &zline::Capacities,
    width: u16,
    height: u16,
) -> zline::Tables<zline::host::TableVecs<u32>> {
    let mut tables =
        zline::Tables::new(zline::host::TableVecs::new(caps, 0).unwrap(), width, height).unwrap();
    for (k, poly) in scene.iter().enumerate() {
        tables.push_polygon_vertices(poly, k as u32 + 1).unwrap();
    }
    tables
}

/// Capacities for small random scenes on a `width`-pixel frame: room for
/// ten polygons of up to seven corners, clipped.
pub fn small_caps(width: u16) -> zline::Capacities {
    zline::Capacities {
        width: usize::from(width),
        vertices: 256,
        polygons: 32,
        corners: 256,
        active_polygons: 32,
        pooled_edges: 64,
        mesh_vertices: 0,
    }
}

/// Capacities of the small textured scenes (`tests/textured.rs`,
/// `tests/lit_textured.rs`): an 8x8 frame of a few polygons.
pub const TEXTURED_CAPS: zline::Capacities = zline::Capacities {
    width: 16,
    vertices: 16,
    polygons: 4,
    corners: 16,
    active_polygons: 4,
    pooled_edges: 16,
    mesh_vertices: 0,
};

/// A 4x4 texture of distinct Rgb565 texels: texel `k` is `0x0841 · (k + 1)`.
pub const TILE_TEXELS: [u16; 16] = {
    let mut t = [0; 16];
    let mut k = 0;
    while k < 16 {
        t[k] = 0x0841 * (k as u16 + 1);
        k += 1;
    }
    t
};

/// No face: the background of [`mesh_frame`].
pub const NO_FACE: u32 = u32::MAX;

/// `mesh` drawn by a `HostRenderer` sized for it, z24, each face
/// coloured by `color` on a background of [`NO_FACE`]: the frame's
/// pixels, row-major from the top, and the draw's counts.
pub fn mesh_frame(
    mesh: &zline::host::HostMesh,
    model: &zline::Mat4,
    camera: &zline::Camera,
    cull: zline::Cull,
    color: impl FnMut(&zline::FaceInfo) -> u32,
) -> (Vec<u32>, zline::DrawStats) {
    let (w, h) = (camera.width, camera.height);
    let mut renderer =
        zline::host::HostRenderer::<u32, zline::Depth24>::for_mesh(mesh, w, h, NO_FACE)
            .expect("renderer");
    let stats = renderer
        .draw_mesh(mesh, model, camera, cull, color)
        .expect("draw");
    let mut pixels = Vec::with_capacity(usize::from(w) * usize::from(h));
    renderer
        .render(&mut FnSink(|_: u16, row: &[u32], _: &[u32]| {
            pixels.extend_from_slice(row);
            Ok::<(), ()>(())
        }))
        .expect("render");
    (pixels, stats)
}
