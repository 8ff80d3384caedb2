//! Every hidden-surface method behind one scene input and one output, for
//! the tools (`render --method`, the bench, the sweep and its charts, the
//! simulator's `m` key, the accuracy run): the same mesh through the same
//! front end into the same tables, then each method's own way to the
//! frame, with its frame and what it keeps in memory.

use std::boxed::Box;
use std::format;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};

use super::interval::render_intervals;
use super::painter::painter_order;
use super::reference::{BACKGROUND, ReferenceCamera, ReferenceFrame, ReferenceView};
use super::scanline_host::{HOST_CAPACITIES, HostPixel};
use zline::DepthFormat;
use zline::FnSink;
use zline::Mat4;
use zline::Mesh;
use zline::PolygonEntry;
use zline::RenderError;
use zline::ScreenVertex;
use zline::Shading;
use zline::host::{ScanVecs, TableVecs};
use zline::zbuffer::{BandBuffers, DepthTest, render_bands};
use zline::{ActiveEdge, ActivePolygon, Capacities, FrameStats, Scanner, Tables, scan};
use zline::{Camera, Cull, DrawStats, VertexCache, draw_mesh};

/// A hidden-surface method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// The scanline z-buffer: the core.
    Scanline,
    /// A full-frame z-buffer.
    ZBuffer,
    /// A z-buffer of this many rows at a time.
    Bands(u16),
    /// The interval (span) scanline, with no depth buffer.
    Interval,
    /// Depth sort with Newell's tests, no depth buffer.
    Painter,
    /// The float64 ray caster.
    Reference,
}

impl Method {
    /// Parses `scanline`, `zbuffer`, `bands:K`, `interval`, `painter` or
    /// `reference`.
    pub fn parse(s: &str) -> Result<Self, String> {
        Ok(match s {
            "scanline" => Self::Scanline,
            "zbuffer" => Self::ZBuffer,
            "interval" => Self::Interval,
            "painter" => Self::Painter,
            "reference" => Self::Reference,
            _ => match s.strip_prefix("bands:").map(str::parse::<u16>) {
                Some(Ok(k)) if (1..=4096).contains(&k) => Self::Bands(k),
                _ => {
                    return Err(format!(
                        "unknown method '{s}' (scanline, zbuffer, bands:K with K 1 to 4096, interval, painter, reference)"
                    ));
                }
            },
        })
    }

    /// The name `parse` reads back.
    pub fn name(&self) -> String {
        match self {
            Self::Scanline => "scanline".into(),
            Self::ZBuffer => "zbuffer".into(),
            Self::Bands(k) => format!("bands:{k}"),
            Self::Interval => "interval".into(),
            Self::Painter => "painter".into(),
            Self::Reference => "reference".into(),
        }
    }

    /// Whether the method stores depth (and so has a depth format).
    pub fn stores_depth(&self) -> bool {
        matches!(self, Self::Scanline | Self::ZBuffer | Self::Bands(_))
    }

    /// The methods the tools compare: each once, bands at 1, 8 and 32 rows.
    pub const ALL: [Method; 8] = [
        Self::Scanline,
        Self::ZBuffer,
        Self::Bands(1),
        Self::Bands(8),
        Self::Bands(32),
        Self::Interval,
        Self::Painter,
        Self::Reference,
    ];
}

/// What a method keeps in memory for one frame, in bytes, with Rgb565
/// colour (as on a microcontroller).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Memory {
    /// Depth storage: rows or a whole frame of the depth format.
    pub depth: usize,
    /// Colour storage: a row for the scanline methods, `K` rows for bands,
    /// a whole frame for the z-buffer and the painter.
    pub color: usize,
    /// The scene tables (vertices, polygons, corners, and the scanline's
    /// edge table).
    pub tables: usize,
    /// Everything else it keeps: active tables, span lists, draw order.
    pub working: usize,
}

impl Memory {
    /// All of it.
    pub fn total(&self) -> usize {
        self.depth + self.color + self.tables + self.working
    }
}

/// One frame by one method.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodFrame {
    /// Face id per pixel ([`BACKGROUND`] for none), row-major.
    pub faces: Vec<u32>,
    /// Colour per pixel.
    pub colors: Vec<Rgb888>,
    /// Stored depth per pixel (widened), for the methods that store it.
    pub depths: Option<Vec<u32>>,
    /// Memory.
    pub memory: Memory,
    /// The method's own counts, as `key=value` pairs for `--stats`.
    pub counts: Vec<(String, String)>,
    /// What the front end did.
    pub draw: DrawStats,
}

/// Renders frames by any [`Method`], reusing its buffers from frame to
/// frame (on the heap).
pub struct MethodRenderer<D: DepthFormat> {
    width: u16,
    height: u16,
    tables: Box<Tables<TableVecs<HostPixel>>>,
    scanner: Box<Scanner<ScanVecs<HostPixel, D>>>,
    cache: Box<VertexCache<65536>>,
    band_depth: Vec<D::Value>,
    band_color: Vec<HostPixel>,
    scratch: Vec<u32>,
    active: Vec<ActivePolygon<HostPixel>>,
    pool: Vec<ActiveEdge>,
    reference_camera: ReferenceCamera,
}

/// The pixel no polygon covers.
const EMPTY: HostPixel = HostPixel {
    face: BACKGROUND,
    color: Rgb888::BLACK,
};

impl<D: DepthFormat> MethodRenderer<D>
where
    D::Value: Into<u32>,
{
    /// Buffers for `width` x `height` frames (each 1 to 4096), tables of
    /// [`HOST_CAPACITIES`].
    pub fn new(width: u16, height: u16) -> Result<Self, String> {
        Self::with_capacities(width, height, &HOST_CAPACITIES)
    }

    /// Buffers for `width` x `height` frames, tables of `caps` (smaller
    /// ones set up faster: the fuzzer makes one per input).
    pub fn with_capacities(width: u16, height: u16, caps: &Capacities) -> Result<Self, String> {
        let tables = Tables::new(
            TableVecs::new(caps, EMPTY).map_err(|e| e.to_string())?,
            width,
            height,
        )
        .map_err(|e| e.to_string())?;
        let scanner = Scanner::new(
            ScanVecs::<HostPixel, D>::new(caps, EMPTY).map_err(|e| e.to_string())?,
            EMPTY,
        );
        let frame = usize::from(width) * usize::from(height);
        Ok(Self {
            width,
            height,
            tables: Box::new(tables),
            scanner: Box::new(scanner),
            cache: Box::default(),
            band_depth: vec![D::CLEAR; frame],
            band_color: vec![EMPTY; frame],
            scratch: vec![0; usize::from(width)],
            active: vec![ActivePolygon::filler(EMPTY); 1],
            pool: vec![ActiveEdge::EMPTY; zline::limits::MAX_POLYGON_CORNERS],
            reference_camera: ReferenceCamera::STANDARD,
        })
    }

    /// The camera the reference renders with ([`ReferenceCamera::STANDARD`]
    /// unless set): give the other methods the same camera
    /// ([`ReferenceCamera::camera`]) to compare them.
    pub fn set_reference_camera(&mut self, camera: ReferenceCamera) {
        self.reference_camera = camera;
    }

    /// One frame of `mesh` by `method`. The reference ignores `model`,
    /// `camera` and `cull` and renders `view` (the reference view) with its
    /// own camera ([`Self::set_reference_camera`]) instead.
    #[allow(clippy::too_many_arguments)]
    pub fn render<M: Mesh>(
        &mut self,
        method: Method,
        mesh: &M,
        model: &Mat4,
        camera: &Camera,
        cull: Cull,
        shading: &Shading,
        view: &ReferenceView,
    ) -> Result<MethodFrame, String> {
        let (w, h) = (usize::from(self.width), usize::from(self.height));
        if method == Method::Reference {
            let frame = ReferenceFrame::render_with(mesh, view, &self.reference_camera);
            let colors = frame.colors(shading);
            return Ok(MethodFrame {
                faces: frame.ids,
                colors,
                depths: None,
                // Its own f64 buffers: a face id and a depth per pixel.
                memory: Memory {
                    depth: w * h * 8,
                    color: w * h * 4,
                    ..Memory::default()
                },
                counts: Vec::new(),
                draw: DrawStats::default(),
            });
        }
        self.tables.clear();
        let draw = draw_mesh(
            &mut *self.tables,
            &mut *self.cache,
            mesh,
            model,
            camera,
            cull,
            |f| HostPixel {
                face: f.face,
                color: shading.color(f),
            },
        )
        .map_err(|e| e.to_string())?;
        let mut faces = vec![BACKGROUND; w * h];
        let mut colors = vec![Rgb888::BLACK; w * h];
        let mut depths = vec![0u32; w * h];
        let mut sink = FnSink(|y: u16, row: &[HostPixel], z: &[D::Value]| {
            let at = usize::from(y) * w;
            for (k, (p, d)) in row.iter().zip(z).enumerate() {
                faces[at + k] = p.face;
                colors[at + k] = p.color;
                depths[at + k] = (*d).into();
            }
            Ok::<(), core::convert::Infallible>(())
        });
        let table_bytes = |vertices: usize, polygons: usize, corners: usize| {
            vertices * core::mem::size_of::<ScreenVertex>()
                + polygons * core::mem::size_of::<PolygonEntry<Rgb565>>()
                + corners * 2
        };
        let (vertices, polygons, corners) = (
            self.tables.vertex_count(),
            self.tables.polygon_count(),
            self.tables.corner_count(),
        );
        let plain_tables = table_bytes(vertices, polygons, corners);
        let depth_size = core::mem::size_of::<D::Value>();
        let unwrap = |e: RenderError<core::convert::Infallible>| match e {
            RenderError::Table(e) => e.to_string(),
            RenderError::Sink(never) => match never {},
        };
        let (memory, counts) = match method {
            Method::Scanline => {
                let prepared = self.tables.prepare();
                let stats: FrameStats =
                    scan(&prepared, &mut self.scanner, 0..self.height, &mut sink)
                        .map_err(unwrap)?;
                let ram = Capacities::from_stats(&stats, w).ram_bytes::<Rgb565, D>();
                let (depth, color, tables) = (w * depth_size, w * 2, plain_tables + corners * 4);
                (
                    Memory {
                        depth,
                        color,
                        tables,
                        // Active tables and the tie-break key row.
                        working: ram.saturating_sub(depth + color + tables),
                    },
                    vec![
                        ("polygons".into(), stats.polygons.to_string()),
                        ("edges".into(), stats.edges.to_string()),
                        ("vertices".into(), stats.vertices.to_string()),
                        ("corners".into(), stats.corners.to_string()),
                        (
                            "peak_active_polygons".into(),
                            stats.peak_active_polygons.to_string(),
                        ),
                        (
                            "peak_active_edges".into(),
                            stats.peak_active_edges.to_string(),
                        ),
                        (
                            "peak_pooled_edges".into(),
                            stats.peak_pooled_edges.to_string(),
                        ),
                        ("spans".into(), stats.spans.to_string()),
                    ],
                )
            }
            Method::ZBuffer | Method::Bands(_) | Method::Painter => {
                let k = match method {
                    Method::Bands(k) => k.min(self.height),
                    _ => self.height,
                };
                let (test, order) = if method == Method::Painter {
                    let prepared = self.tables.in_drawing_order();
                    let (order, stats) = painter_order(&prepared);
                    (DepthTest::Overwrite, Some((order, stats)))
                } else {
                    (DepthTest::Nearer, None)
                };
                let prepared = self.tables.in_drawing_order();
                let stats = render_bands::<HostPixel, D, _>(
                    &prepared,
                    BandBuffers {
                        depth: &mut self.band_depth,
                        color: &mut self.band_color,
                        scratch: &mut self.scratch,
                        active: &mut self.active,
                        pool: &mut self.pool,
                    },
                    k,
                    EMPTY,
                    test,
                    order.as_ref().map(|(o, _)| o.as_slice()),
                    &mut sink,
                )
                .map_err(unwrap)?;
                let band = usize::from(k) * w;
                let working = core::mem::size_of::<ActivePolygon<Rgb565>>()
                    + stats.scan.peak_pooled_edges as usize * core::mem::size_of::<ActiveEdge>()
                    + w * 4;
                match order {
                    Some((order, p)) => (
                        Memory {
                            depth: 0,
                            color: w * h * 2,
                            tables: plain_tables,
                            working: working + order.len() * 4,
                        },
                        vec![
                            ("comparisons".into(), p.comparisons.to_string()),
                            ("moves".into(), p.moves.to_string()),
                            ("unresolved".into(), p.unresolved.to_string()),
                        ],
                    ),
                    None => (
                        Memory {
                            depth: band * depth_size,
                            color: band * 2,
                            tables: plain_tables,
                            working,
                        },
                        vec![
                            ("bands".into(), stats.bands.to_string()),
                            ("polygon_visits".into(), stats.visits.to_string()),
                            ("polygons_drawn_into_bands".into(), stats.drawn.to_string()),
                        ],
                    ),
                }
            }
            Method::Interval => {
                let prepared = self.tables.prepare();
                let stats = render_intervals::<HostPixel, D, _>(&prepared, EMPTY, &mut sink)
                    .map_err(unwrap)?;
                (
                    Memory {
                        depth: 0,
                        color: w * 2,
                        tables: plain_tables,
                        working: stats.working_bytes::<Rgb565>(w) - w * 2,
                    },
                    vec![
                        ("spans".into(), stats.spans.to_string()),
                        ("intervals".into(), stats.intervals.to_string()),
                        ("peak_spans".into(), stats.peak_spans.to_string()),
                    ],
                )
            }
            Method::Reference => unreachable!("handled above"),
        };
        // The sink's borrows of the row buffers end here.
        let _ = sink;
        Ok(MethodFrame {
            faces,
            colors,
            depths: method.stores_depth().then_some(depths),
            memory,
            counts,
            draw,
        })
    }
}
