//! One frame on several threads: the frame's rows are cut into bands, and
//! each band has tables and a scanner of its own. Every thread builds its
//! band's tables from the whole scene, keeping only the polygons that
//! cover a sample row of the band ([`BandTables`]), then scans the band.
//! No state is shared while a frame is drawn, and the rows sent are
//! exactly those one renderer over the whole frame sends (a band's scan
//! activates the polygons that started above it at its first row, as
//! [`scan`] does for several scanners over one set of tables).
//!
//! The work that does not shrink with the band is the front end's
//! per-vertex and per-face tests: every thread transforms the vertices
//! and judges every face.

use std::ops::Range;
use std::time::{Duration, Instant};
use std::vec::Vec;

use crate::error::{Error, RenderError};
use crate::raster::depth::DepthFormat;
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::scan::{FrameStats, scan};
use crate::raster::vertex::{Outline, ScreenVertex};
use crate::raster::{Admission, Capacities, PolygonTables, Renderer, Tables};
use crate::sink::RowSink;

use super::storage::{ScanVecs, TableVecs, host_renderer};

/// Tables that keep only the polygons covering a sample on one band of
/// rows: every other polygon is declined ([`Admission::Declined`]) before
/// the caller's `decide` sees it. Everything else is passed through.
#[derive(Debug)]
pub struct BandTables<'a, T> {
    tables: &'a mut T,
    rows: Range<u16>,
}

impl<'a, T> BandTables<'a, T> {
    /// `tables`, keeping polygons with a sample row in `rows`.
    pub fn new(tables: &'a mut T, rows: Range<u16>) -> Self {
        Self { tables, rows }
    }

    /// The band's rows.
    pub fn rows(&self) -> Range<u16> {
        self.rows.clone()
    }
}

/// Whether `outline`'s bounding box holds a sample of a row in `rows` of
/// a `width` x `height` frame.
fn reaches(outline: &Outline, rows: &Range<u16>, width: u16, height: u16) -> bool {
    outline
        .rect
        .and_then(|r| r.sample_rows(width, height))
        .is_some_and(|(first, end)| first < rows.end && end > rows.start)
}

impl<C, T: PolygonTables<C>> PolygonTables<C> for BandTables<'_, T> {
    fn frame_width(&self) -> u16 {
        self.tables.frame_width()
    }

    fn frame_height(&self) -> u16 {
        self.tables.frame_height()
    }

    fn add_vertex(&mut self, vertex: ScreenVertex) -> Result<u16, Error> {
        self.tables.add_vertex(vertex)
    }

    fn get_vertex(&self, index: u16) -> Option<ScreenVertex> {
        self.tables.get_vertex(index)
    }

    fn offer_polygon<I>(
        &mut self,
        corners: I,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: Clone,
    {
        let (width, height, rows) = (self.frame_width(), self.frame_height(), &self.rows);
        self.tables.offer_polygon(corners, |outline| {
            reaches(outline, rows, width, height)
                .then(|| decide(outline))
                .flatten()
        })
    }

    fn offer_triangle(
        &mut self,
        corners: [u16; 3],
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        let (height, rows) = (self.frame_height(), &self.rows);
        // Most triangles miss a band: the rows of their corners tell, before
        // the tables' own tests (any other outcome is theirs to give).
        let y = |k: usize| self.tables.get_vertex(corners[k]).map(|v| v.y);
        if let (Some(a), Some(b), Some(c)) = (y(0), y(1), y(2)) {
            let first = first_sample_at_or_after(a.min(b).min(c)).max(0);
            let end = first_sample_at_or_after(a.max(b).max(c)).min(i32::from(height));
            let misses = end <= i32::from(rows.start) || first >= i32::from(rows.end);
            if first < end && misses {
                return Ok(Admission::Declined);
            }
        }
        // Past that test the triangle reaches the band, or the tables
        // refuse it before `decide` (its corners are the outline's).
        self.tables.offer_triangle(corners, decide)
    }

    fn share_plane(&mut self, plane: [u16; 3]) -> Result<bool, Error> {
        self.tables.share_plane(plane)
    }

    fn begin_polygon(&mut self) {
        self.tables.begin_polygon();
    }

    fn discard_polygon(&mut self) {
        self.tables.discard_polygon();
    }

    fn add_corner(&mut self, vertex: u16) -> Result<(), Error> {
        self.tables.add_corner(vertex)
    }

    fn finish_polygon(
        &mut self,
        decide: impl FnOnce(&Outline) -> Option<C>,
    ) -> Result<Admission, Error> {
        let (width, height, rows) = (self.frame_width(), self.frame_height(), &self.rows);
        self.tables.finish_polygon(|outline| {
            reaches(outline, rows, width, height)
                .then(|| decide(outline))
                .flatten()
        })
    }
}

/// Tables and a scanner in `Vec`s.
type BandRenderer<C, D> = Renderer<TableVecs<C>, ScanVecs<C, D>>;

/// One band: its rows, its renderer, and the work it found on each of its
/// rows in the last frame.
#[derive(Debug, Clone)]
struct Band<C: Copy, D: DepthFormat> {
    rows: Range<u16>,
    renderer: BandRenderer<C, D>,
    /// Per row of `rows`: the polygons whose first row it is, plus one
    /// (the row's own upkeep).
    work: Vec<u32>,
    /// What the last frame took in this band.
    last: BandTiming,
}

/// One band's share of the last frame ([`BandedRenderer::last_frame`]):
/// its rows, its polygons and the wall-clock time of each step on its
/// thread.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct BandTiming {
    /// The rows the band drew.
    pub rows: Range<u16>,
    /// Polygons in its tables (those reaching its rows).
    pub polygons: usize,
    /// Emptying its tables and building them from the scene.
    pub build: Duration,
    /// Preparing the tables and scanning its rows into its sink.
    pub scan: Duration,
}

/// A frame cut into bands of rows, each drawn on a thread of its own (the
/// first on the calling thread) with its own tables and scanner, sized by
/// the same [`Capacities`].
///
/// After each frame the cuts move so that each band holds about as many
/// polygon activations as the others did in that frame (a polygon is
/// activated on its first row): the next frame, if the scene has changed
/// little, takes about as long on every thread. Where the cuts lie does not
/// change a single pixel.
///
/// Each frame starts its threads afresh (tens of microseconds): on small
/// scenes one renderer on one thread is faster.
///
/// ```
/// use zline::front::scene::{Camera, Cull, VertexCache, draw_mesh, reference_model};
/// use zline::host::{BandedRenderer, shapes};
/// use zline::{Capacities, Depth16, Error, FnSink};
///
/// let mesh = shapes::torus_knot(2, 3, 64, 8, 0.45);
/// let (width, height) = (160u16, 120u16);
/// let caps = Capacities {
///     width: usize::from(width),
///     vertices: 4096,
///     polygons: 2048,
///     corners: 8192,
///     active_polygons: 2048,
///     pooled_edges: 256,
/// };
/// let mut renderer = BandedRenderer::<u32, Depth16>::new(&caps, width, height, 0, 2)?;
/// let model = reference_model(&mesh, 30.0, 20.0)?;
/// let camera = Camera::reference(width, height);
/// // One vertex cache per band, and a sink per band writing into its part
/// // of the frame.
/// let mut caches: Vec<Box<VertexCache<4096>>> = (0..2).map(|_| Box::default()).collect();
/// let mut frame = vec![0u32; usize::from(width) * usize::from(height)];
/// let mut rest = &mut frame[..];
/// let mut sinks = Vec::new();
/// for rows in renderer.bands() {
///     let (part, tail) = rest.split_at_mut(rows.len() * usize::from(width));
///     rest = tail;
///     sinks.push(FnSink(move |y: u16, colors: &[u32], _: &[u16]| {
///         let at = usize::from(y - rows.start) * colors.len();
///         part[at..at + colors.len()].copy_from_slice(colors);
///         Ok::<(), ()>(())
///     }));
/// }
/// let stats = renderer
///     .render(&mut caches, &mut sinks, |tables, cache| {
///         draw_mesh(tables, &mut **cache, &mesh, &model, &camera, Cull::Back, |f| f.face + 1)
///             .map(|_| ())
///             .map_err(Error::from)
///     })
///     .map_err(|e| format!("{e:?}"))?;
/// drop(sinks);
/// assert_eq!(stats.len(), 2);
/// assert!(frame.iter().any(|&c| c != 0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct BandedRenderer<C: Copy, D: DepthFormat> {
    bands: Vec<Band<C, D>>,
    height: u16,
}

impl<C: Copy + Send + Sync, D: DepthFormat> BandedRenderer<C, D>
where
    D::Value: Send,
{
    /// `count` bands (1 to the frame's height) of `width` x `height`
    /// frames, of as equal heights as can be, each with storage for
    /// `caps`, clearing to `background`.
    pub fn new(
        caps: &Capacities,
        width: u16,
        height: u16,
        background: C,
        count: usize,
    ) -> Result<Self, Error> {
        if count == 0 || count > usize::from(height) {
            return Err(Error::BadFrameSize);
        }
        let mut bands = Vec::with_capacity(count);
        for k in 0..count {
            // count <= height <= 4,096: no overflow in u32.
            let cut = |k: usize| (k as u32 * u32::from(height) / count as u32) as u16;
            bands.push(Band {
                rows: cut(k)..cut(k + 1),
                renderer: host_renderer(caps, width, height, background)?,
                work: Vec::new(),
                last: BandTiming::default(),
            });
        }
        Ok(Self { bands, height })
    }

    /// Each band's rows, polygons and times in the last frame drawn, top
    /// to bottom.
    pub fn last_frame(&self) -> impl Iterator<Item = &BandTiming> + '_ {
        self.bands.iter().map(|band| &band.last)
    }

    /// The bands' rows, top to bottom.
    pub fn bands(&self) -> impl Iterator<Item = Range<u16>> + '_ {
        self.bands.iter().map(|band| band.rows.clone())
    }

    /// Moves the cuts between the bands to `cuts` (one per pair of
    /// neighbouring bands, increasing, each strictly inside the frame), for
    /// example to even out the bands' work.
    pub fn set_cuts(&mut self, cuts: &[u16]) -> Result<(), Error> {
        let n = self.bands.len();
        let increasing = cuts.windows(2).all(|w| w[0] < w[1]);
        let inside = cuts.iter().all(|&c| c > 0 && c < self.height);
        if cuts.len() + 1 != n || !increasing || !inside {
            return Err(Error::BadFrameSize);
        }
        for (k, band) in self.bands.iter_mut().enumerate() {
            let start = if k == 0 { 0 } else { cuts[k - 1] };
            let end = cuts.get(k).copied().unwrap_or(self.height);
            band.rows = start..end;
        }
        Ok(())
    }

    /// Cuts where each band gets about an equal share of the last frame's
    /// work (see [`Band::work`]), every band keeping at least one row.
    fn balanced_cuts(&self) -> Vec<u16> {
        let n = self.bands.len();
        let work = self.bands.iter().flat_map(|band| band.work.iter().copied());
        let total: u64 = work.clone().map(u64::from).sum();
        let mut cuts = Vec::with_capacity(n - 1);
        let mut sum = 0u64;
        for (row, w) in (0u16..).zip(work) {
            sum += u64::from(w);
            // Cut k (1 <= k < n) after the row where the running sum
            // first reaches k/n of the total.
            let k = cuts.len() as u64 + 1;
            if k < n as u64 && sum * n as u64 >= total * k {
                cuts.push(row + 1);
            }
        }
        cuts
    }

    /// Moves the cuts to [`Self::balanced_cuts`] when they are usable.
    fn balance(&mut self) {
        let cuts = self.balanced_cuts();
        // Each band keeps at least one row: otherwise the cuts stay.
        let _ = self.set_cuts(&cuts);
    }

    /// Draws one frame. For each band, on its own thread: its tables are
    /// emptied, `build` fills them from the whole scene (given the band's
    /// tables and its entry of `scratch`, for example a vertex cache),
    /// they are prepared, and the band's rows are scanned into its entry
    /// of `sinks`. `scratch` and `sinks` hold one entry per band; the
    /// result holds each band's counts, top to bottom.
    ///
    /// The cuts move after each frame (see the type's notes): a sink that
    /// writes a band's rows into part of a frame buffer is made for the
    /// rows [`Self::bands`] gives just before the call.
    pub fn render<X, K, B>(
        &mut self,
        scratch: &mut [X],
        sinks: &mut [K],
        build: B,
    ) -> Result<Vec<FrameStats>, RenderError<K::Error>>
    where
        X: Send,
        K: RowSink<C, D::Value> + Send,
        K::Error: Send,
        B: Fn(&mut BandTables<'_, Tables<TableVecs<C>>>, &mut X) -> Result<(), Error> + Sync,
    {
        let n = self.bands.len();
        if scratch.len() != n || sinks.len() != n {
            return Err(RenderError::Table(Error::BadFrameSize));
        }
        let build = &build;
        let mut jobs = self.bands.iter_mut().zip(scratch).zip(sinks);
        let first = jobs.next();
        let stats = std::thread::scope(|s| {
            let others: Vec<_> = jobs
                .map(|((band, x), sink)| s.spawn(move || draw_band(band, x, sink, build)))
                .collect();
            // The first band on this thread, meanwhile.
            let mut stats = Vec::with_capacity(n);
            stats.extend(first.map(|((band, x), sink)| draw_band(band, x, sink, build)));
            for handle in others {
                match handle.join() {
                    Ok(band) => stats.push(band),
                    Err(panic) => std::panic::resume_unwind(panic),
                }
            }
            stats.into_iter().collect::<Result<Vec<_>, _>>()
        })?;
        self.balance();
        Ok(stats)
    }
}

/// One band's frame: build, prepare, scan; then its work per row.
fn draw_band<C, D, X, K, B>(
    band: &mut Band<C, D>,
    scratch: &mut X,
    sink: &mut K,
    build: &B,
) -> Result<FrameStats, RenderError<K::Error>>
where
    C: Copy,
    D: DepthFormat,
    K: RowSink<C, D::Value>,
    B: Fn(&mut BandTables<'_, Tables<TableVecs<C>>>, &mut X) -> Result<(), Error>,
{
    let rows = band.rows.clone();
    let renderer = &mut band.renderer;
    let start = Instant::now();
    renderer.clear();
    build(
        &mut BandTables::new(&mut renderer.tables, rows.clone()),
        scratch,
    )
    .map_err(RenderError::Table)?;
    let built = Instant::now();
    let prepared = renderer.tables.prepare();
    let stats = scan(&prepared, &mut renderer.scanner, rows.clone(), sink)?;
    band.last = BandTiming {
        rows: rows.clone(),
        polygons: prepared.polygons.len(),
        build: built - start,
        scan: built.elapsed(),
    };
    band.work.clear();
    band.work.resize(rows.len(), 1);
    // Sorted by first row: those of this band's rows are one run.
    let polygons = prepared.polygons;
    let from = polygons.partition_point(|p| p.first_row < rows.start);
    for polygon in polygons[from..]
        .iter()
        .take_while(|p| p.first_row < rows.end)
    {
        band.work[usize::from(polygon.first_row - rows.start)] += 1;
    }
    Ok(stats)
}
