//! One frame on several threads: the frame's rows are cut into bands, and
//! each band has tables and a scanner of its own. Every thread builds its
//! band's tables from the whole scene, keeping only the polygons that
//! cover a sample row of the band ([`BandTables`]), then scans the band.
//! No state is shared while a frame is drawn, and the rows sent are
//! exactly those one renderer over the whole frame sends (a band's scan
//! activates the polygons that started above it at its first row, as
//! [`scan`] does for several scanners over one set of tables).
//!
//! [`BandedRenderer::render_mesh`] shares the front end's first steps
//! between the threads: the mesh's vertices are projected once, the
//! threads taking chunks of them, and then the threads sort chunks of the
//! faces into the bands their rows reach. Each band then builds its tables
//! from that projection and its own faces. The threads start once a frame
//! and meet between the steps ([`SpinBarrier`]), sharing the projection
//! through atomics, with no lock and no copy. ([`BandedRenderer::render`],
//! given a closure that draws the whole scene, transforms every vertex
//! and judges every face in every band.)

use std::boxed::Box;
use std::ops::Range;
use std::sync::atomic::Ordering::{AcqRel, Acquire, Relaxed, Release};
use std::sync::atomic::{AtomicBool, AtomicI16, AtomicU32, AtomicU64, AtomicUsize};
use std::sync::{OnceLock, RwLock};
use std::time::{Duration, Instant};
use std::vec::Vec;

use crate::error::{Error, RenderError};
use crate::front::geometry::Mat4;
use crate::front::mesh::Mesh;
use crate::front::scene::{
    Camera, Cull, FaceInfo, ProjectedVertex, VertexCache, VertexSource, draw_mesh_from,
    project_vertices_with,
};
use crate::raster::depth::DepthFormat;
use crate::raster::fixed::first_sample_at_or_after;
use crate::raster::scan::scan;
use crate::raster::stats::FrameStats;
use crate::raster::vertex::{Outline, ScreenVertex};
use crate::raster::{Admission, Capacities, PolygonTables, Tables};
use crate::sink::RowSink;

use super::storage::{TableVecs, host_renderer};

/// Tables that keep only the polygons covering a sample on one band of
/// rows: every other polygon is declined ([`Admission::Declined`]) before
/// the caller's `decide` sees it. Everything else is passed through.
#[derive(Debug)]
pub struct BandTables<'a, T> {
    tables: &'a mut T,
    rows: Range<u16>,
    /// Whether triangles are tested against the band (see
    /// [`Self::triangles_reach`]).
    test_triangles: bool,
}

impl<'a, T> BandTables<'a, T> {
    /// `tables`, keeping polygons with a sample row in `rows`.
    pub fn new(tables: &'a mut T, rows: Range<u16>) -> Self {
        Self {
            tables,
            rows,
            test_triangles: true,
        }
    }

    /// `tables` for `rows`, for a caller whose triangles are known to reach
    /// the band (as the faces [`BandedRenderer::render_mesh`] sorts into
    /// bands do): triangles go straight to `tables`, other polygons are
    /// tested. A triangle that misses the band after all costs time, not
    /// pixels: a band's scan draws its own rows only.
    pub fn triangles_reach(tables: &'a mut T, rows: Range<u16>) -> Self {
        Self {
            tables,
            rows,
            test_triangles: false,
        }
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
        if !self.test_triangles {
            return self.tables.offer_triangle(corners, decide);
        }
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
type BandRenderer<C, D> = super::storage::HostRenderer<C, D>;

/// One band: its rows, its renderer, and the work it found on each of its
/// rows in the last frame.
#[derive(Debug, Clone)]
struct Band<C: Copy, D: DepthFormat> {
    rows: Range<u16>,
    renderer: BandRenderer<C, D>,
    /// Per row of `rows`, its work in the last frame, weighted by
    /// [`ROW_WORK`], [`ACTIVATION_WORK`] and [`ACTIVE_ROW_WORK`]: the row's
    /// own upkeep, the polygons activated on it and the polygons active on
    /// it (activations alone left a band of long-lived triangles, such as
    /// Spot's lower half at 240x240, a quarter slower than the other).
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
/// After each frame the cuts move so that each band holds about as much
/// work as the others did in that frame, counted per row: the row itself,
/// the polygons activated on it and the polygons active on it. The next
/// frame, if the scene has changed little, takes about as long on every
/// thread. Where the cuts lie does not
/// change a single pixel.
///
/// Each frame starts its threads afresh (tens of microseconds), so a
/// frame whose bands took less than about 0.1 ms of work the frame before
/// (and the first frame) is drawn band after band on the calling thread;
/// on such small scenes one renderer on one thread is still a little
/// faster. [`Self::set_one_thread_below`] moves that limit.
///
/// ```
/// use zline::{Camera, Cull, reference_model};
/// use zline::host::{BandedRenderer, HostMesh};
/// use zline::{Capacities, Depth16, FnSink};
///
/// // A cube.
/// let obj = b"v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
///     f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
/// let mesh = HostMesh::from_obj(obj)?;
/// let (width, height) = (160u16, 120u16);
/// let caps = Capacities {
///     width: usize::from(width),
///     vertices: 4096,
///     polygons: 2048,
///     corners: 8192,
///     active_polygons: 2048,
///     pooled_edges: 256,
///     mesh_vertices: 0,
/// };
/// let mut renderer = BandedRenderer::<u32, Depth16>::new(&caps, width, height, 0, 2)?;
/// let model = reference_model(&mesh, 30.0, 20.0)?;
/// let camera = Camera::reference(width, height);
/// // A sink per band, writing into its part of the frame.
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
/// // The vertices projected once, the faces sorted into the bands, each
/// // band built and scanned on its own thread.
/// let stats = renderer
///     .render_mesh(&mesh, &model, &camera, Cull::Back, &mut sinks, |f| f.face + 1)
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
    /// [`Self::render_mesh`]'s projection of the mesh's vertices and the
    /// faces it sorted into the bands, shared by the frame's threads.
    shared_front: SharedFront,
    /// [`Self::render_mesh`]'s scratch for each band.
    scratch: Vec<MeshScratch>,
    /// What [`Self::render_mesh`]'s shared steps took in the last frame.
    shared: SharedSteps,
    /// Below this much work in the last frame's bands, a frame stays on
    /// the calling thread ([`ONE_THREAD_BELOW`] unless set).
    one_thread_below: Duration,
}

/// A band's scratch in [`BandedRenderer::render_mesh`].
#[derive(Debug, Clone)]
struct MeshScratch {
    /// Which band it is.
    band: usize,
    /// Where the mesh's vertices went in its vertex table.
    cache: Box<VertexCache<MESH_VERTICES>>,
    /// Its faces, in increasing order.
    faces: Vec<u32>,
}

/// The wall-clock time of [`BandedRenderer::render_mesh`]'s steps shared
/// by the threads, before any band starts building its tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SharedSteps {
    /// Projecting the mesh's vertices.
    pub project: Duration,
    /// Sorting the faces into the bands their rows reach.
    pub sort_faces: Duration,
}

/// Most vertices a mesh drawn by [`BandedRenderer::render_mesh`] may have
/// (a face's corners are `u16` indices).
pub const MESH_VERTICES: usize = 1 << 16;

/// Vertices a thread of [`BandedRenderer::render_mesh`] projects at a
/// time (about 20 µs of work on a desktop core).
const VERTEX_CHUNK: usize = 2048;
/// Faces a thread of [`BandedRenderer::render_mesh`] sorts into bands at
/// a time (about 20 µs of work on a desktop core): each chunk has a list
/// per band.
const FACE_CHUNK: usize = 4096;

/// The row of a vertex that is not projected.
const NOT_PROJECTED: i16 = i16::MIN;

/// A row's own work in [`Band::work`] (clearing and sending it), in
/// units of roughly a hundred instructions on a desktop.
const ROW_WORK: u32 = 4;
/// A polygon's activation in [`Band::work`] (a triangle's plane and edge
/// set-up: about 500 instructions).
const ACTIVATION_WORK: u32 = 5;
/// A polygon's span and step on one row in [`Band::work`] (about 100
/// instructions).
const ACTIVE_ROW_WORK: u32 = 1;

/// Below this much work in the bands in the last frame (building and
/// scanning, summed over the bands), the next frame's bands are all drawn
/// on the calling thread: starting a thread and waiting for it costs
/// 30-60 µs on a desktop, more than sharing such a frame saves. The
/// peers bench's smallest scenes took 0.06-0.1 ms on two threads, 0.01-0.06
/// on one. The default of [`BandedRenderer::set_one_thread_below`].
pub const ONE_THREAD_BELOW: Duration = Duration::from_micros(120);

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
        Ok(Self {
            bands,
            height,
            shared_front: SharedFront::default(),
            scratch: Vec::new(),
            shared: SharedSteps::default(),
            one_thread_below: ONE_THREAD_BELOW,
        })
    }

    /// Draws the next frames on the calling thread alone, band after
    /// band, while the bands' work in the frame before (building and
    /// scanning, summed over the bands; none before the first frame) is
    /// below `work`: [`Duration::ZERO`] always starts threads,
    /// [`Duration::MAX`] never does. The default, [`ONE_THREAD_BELOW`],
    /// is a few times what starting a thread costs on a desktop.
    pub fn set_one_thread_below(&mut self, work: Duration) {
        self.one_thread_below = work;
    }

    /// Each band's rows, polygons and times in the last frame drawn, top
    /// to bottom.
    pub fn last_frame(&self) -> impl Iterator<Item = &BandTiming> + '_ {
        self.bands.iter().map(|band| &band.last)
    }

    /// What the last [`Self::render_mesh`]'s shared steps took.
    pub fn last_shared_steps(&self) -> SharedSteps {
        self.shared
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
        // At most 4,096 rows of under 2^23 each (see `draw_band`): sums
        // below 2^35, and times at most 4,096 bands below 2^47.
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

    /// Whether the next frame is drawn on the calling thread alone: its
    /// bands' work in the last frame (building and scanning, summed; none
    /// before the first) was below [`Self::set_one_thread_below`]'s limit.
    fn on_one_thread(&self) -> bool {
        let work: Duration = self.bands.iter().map(|b| b.last.build + b.last.scan).sum();
        work < self.one_thread_below
    }

    /// Moves the cuts to [`Self::balanced_cuts`] when they are usable.
    fn balance(&mut self) {
        let cuts = self.balanced_cuts();
        // Each band keeps at least one row: otherwise the cuts stay.
        let _ = self.set_cuts(&cuts);
    }

    /// Draws one frame of `mesh`, as [`draw_mesh`](crate::front::scene::draw_mesh)
    /// with these arguments followed by one renderer's `render` would, with
    /// the work spread over one thread per band:
    ///
    /// 1. the mesh's vertices are projected once (as
    ///    [`project_vertices`](crate::front::scene::project_vertices)
    ///    would), the threads taking chunks of them until none is left;
    /// 2. the threads take chunks of the faces and sort them into the
    ///    bands that hold a sample row between their corners' (a face with
    ///    a corner that needs clipping goes to every band);
    /// 3. each band builds its tables from the projection and its faces
    ///    (as [`draw_mesh_projected`](crate::front::scene::draw_mesh_projected)
    ///    would) and scans its rows into its entry of `sinks`, as
    ///    [`Self::render`] does.
    ///
    /// One thread a band does all three, the first on the calling thread;
    /// when the last frame's bands had little work (see the type's notes),
    /// the calling thread does everything. `shade` is called from several
    /// threads, for the faces each band keeps (a face reaching two bands is
    /// shaded in both). The mesh may have up to [`MESH_VERTICES`] vertices.
    /// A panic on one thread (in `shade`, or in the mesh's methods) is
    /// raised on the calling thread once every thread has stopped.
    #[allow(clippy::too_many_arguments)]
    pub fn render_mesh<M, K, S>(
        &mut self,
        mesh: &M,
        model: &Mat4,
        camera: &Camera,
        cull: Cull,
        sinks: &mut [K],
        shade: S,
    ) -> Result<Vec<FrameStats>, RenderError<K::Error>>
    where
        M: Mesh + Sync,
        K: RowSink<C, D::Value> + Send,
        K::Error: Send,
        S: Fn(&FaceInfo) -> C + Sync,
    {
        let count = mesh.vertex_count();
        if count > MESH_VERTICES {
            return Err(RenderError::Table(Error::VertexCacheTooSmall));
        }
        let n = self.bands.len();
        if sinks.len() != n {
            return Err(RenderError::Table(Error::BadFrameSize));
        }
        let faces = mesh.face_count();
        let front = &mut self.shared_front;
        front.projection.resize(count);
        front
            .lists
            .resize_with(faces.div_ceil(FACE_CHUNK), RwLock::default);
        let mut scratch = core::mem::take(&mut self.scratch);
        scratch.resize_with(n, || MeshScratch {
            band: 0,
            cache: Box::default(),
            faces: Vec::new(),
        });
        for (band, x) in scratch.iter_mut().enumerate() {
            x.band = band;
        }
        let bands: Vec<Range<u16>> = self.bands.iter().map(|b| b.rows.clone()).collect();
        let front = &self.shared_front;
        let height = self.height;
        // The shared steps: each thread takes chunk after chunk of the
        // vertices, then of the faces, until none is left (a thread that
        // starts late takes fewer).
        let (next_vertices, next_faces) = (AtomicUsize::new(0), AtomicUsize::new(0));
        let project = || loop {
            let first = next_vertices
                .fetch_add(1, Relaxed)
                .saturating_mul(VERTEX_CHUNK);
            if first >= count {
                return Ok(());
            }
            let indices = first..(first + VERTEX_CHUNK).min(count);
            front.projection.project(mesh, model, camera, indices)?;
        };
        let sort = || loop {
            let chunk = next_faces.fetch_add(1, Relaxed);
            let Some(lists) = front.lists.get(chunk) else {
                return;
            };
            let first = chunk * FACE_CHUNK;
            let chunk_faces = first..(first + FACE_CHUNK).min(faces);
            let mut lists = lists.write().unwrap_or_else(|e| e.into_inner());
            sort_faces(
                mesh,
                &front.projection.rows,
                chunk_faces,
                &bands,
                height,
                &mut lists,
            );
        };
        let build = |tables: &mut BandTables<'_, _>, x: &mut MeshScratch| {
            x.faces.clear();
            for run in &front.lists {
                let run = run.read().unwrap_or_else(|e| e.into_inner());
                x.faces.extend_from_slice(run[x.band].faces());
            }
            draw_mesh_from(
                tables,
                &mut *x.cache,
                (&front.projection, count),
                Some(&x.faces),
                mesh,
                (model, camera, cull),
                &shade,
            )
            .map(|_| ())
            .map_err(Error::from)
        };
        // The triangles of a band's faces reach it (see `sort_faces`).
        let draw = |(band, x, sink): (&mut Band<C, D>, &mut MeshScratch, &mut K)| {
            draw_band(band, x, sink, &build, false)
        };
        let start = Instant::now();
        // When the projection and the sort ended (on the first thread).
        let steps = [OnceLock::new(), OnceLock::new()];
        let one_thread = self.on_one_thread();
        let jobs = self
            .bands
            .iter_mut()
            .zip(scratch.iter_mut())
            .zip(sinks.iter_mut());
        let jobs = jobs.map(|((band, x), sink)| (band, x, sink));
        let stats = if one_thread {
            // Step after step on this thread.
            let projected = project();
            let _ = steps[0].set(Instant::now());
            match projected {
                Ok(()) => {
                    sort();
                    let _ = steps[1].set(Instant::now());
                    jobs.map(draw).collect::<Vec<_>>()
                }
                Err(e) => std::vec![Err(RenderError::Table(e))],
            }
        } else {
            // One thread a band, all started at once, meeting twice: once
            // every vertex is projected, once every face is sorted. (A
            // thread start costs 40-80 µs here, a meeting under 1 µs.)
            let barrier = SpinBarrier::new(n);
            let (barrier, steps) = (&barrier, &steps);
            // Should starting a thread fail (a panic), the threads already
            // started must not wait for it.
            let _poison = barrier.poison_on_panic();
            on_threads(jobs.enumerate(), |(k, job)| {
                let _poison = barrier.poison_on_panic();
                let projected = project();
                if projected.is_err() {
                    barrier.fail();
                }
                if !barrier.wait() {
                    // A thread failed (or panicked): its error is the frame's.
                    return projected
                        .map(|()| FrameStats::default())
                        .map_err(RenderError::Table);
                }
                if k == 0 {
                    let _ = steps[0].set(Instant::now());
                }
                sort();
                if !barrier.wait() {
                    // Only when another thread is panicking: the scope
                    // raises its panic once every thread has returned.
                    return Ok(FrameStats::default());
                }
                if k == 0 {
                    let _ = steps[1].set(Instant::now());
                }
                draw(job)
            })
        };
        let projected = steps[0].get().copied().unwrap_or(start);
        let sorted = steps[1].get().copied().unwrap_or(projected);
        self.shared = SharedSteps {
            project: projected - start,
            sort_faces: sorted - projected,
        };
        self.scratch = scratch;
        let stats = stats.into_iter().collect::<Result<Vec<_>, _>>()?;
        self.balance();
        Ok(stats)
    }

    /// Draws one frame. For each band, on its own thread (or all on the
    /// calling thread, when the last frame's bands had little work: see
    /// the type's notes): its tables are
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
        self.render_bands(scratch, sinks, build, true)
    }

    /// [`Self::render`], testing the triangles against each band or not
    /// (see [`BandTables::triangles_reach`]).
    fn render_bands<X, K, B>(
        &mut self,
        scratch: &mut [X],
        sinks: &mut [K],
        build: B,
        test_triangles: bool,
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
        // Little work in the last frame (or none, before the first): all
        // bands on the calling thread.
        let one_thread = self.on_one_thread();
        let jobs = self.bands.iter_mut().zip(scratch).zip(sinks);
        let job = |((band, x), sink)| draw_band(band, x, sink, &build, test_triangles);
        let stats = if one_thread {
            jobs.map(job).collect::<Vec<_>>()
        } else {
            on_threads(jobs, job)
        };
        let stats = stats.into_iter().collect::<Result<Vec<_>, _>>()?;
        self.balance();
        Ok(stats)
    }
}

/// `job` for each of `items`, each on a thread of its own but the first,
/// which runs on the calling thread: the results in the items' order.
fn on_threads<A, R, J>(items: impl Iterator<Item = A>, job: J) -> Vec<R>
where
    A: Send,
    R: Send,
    J: Fn(A) -> R + Sync,
{
    let mut items = items;
    let Some(first) = items.next() else {
        return Vec::new();
    };
    let job = &job;
    std::thread::scope(|s| {
        let others: Vec<_> = items.map(|item| s.spawn(move || job(item))).collect();
        let mut results = Vec::with_capacity(others.len() + 1);
        results.push(job(first));
        for handle in others {
            match handle.join() {
                Ok(r) => results.push(r),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        results
    })
}

/// The first sample row at or below a projected vertex, or
/// [`NOT_PROJECTED`]. Projected vertices lie in the guard band, whose rows
/// fit in `i16` with room to spare (`GUARD_BAND_PX` < 2^15).
fn vertex_row(vertex: &ProjectedVertex) -> i16 {
    const _: () = assert!(crate::limits::GUARD_BAND_PX < (1 << 14));
    match vertex {
        ProjectedVertex::Screen(v) => first_sample_at_or_after(v.y) as i16,
        _ => NOT_PROJECTED,
    }
}

/// What [`BandedRenderer::render_mesh`]'s threads share in a frame: the
/// projection, and the faces sorted into bands by each run of faces
/// (`lists[run][band]`), each run written by one thread and read by
/// every band.
#[derive(Debug, Default)]
struct SharedFront {
    projection: SharedProjection,
    lists: Vec<RwLock<Vec<FaceList>>>,
}

/// Scratch only: a clone starts empty.
impl Clone for SharedFront {
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// A mesh's projected vertices, each written by the thread projecting it
/// and read by every thread once they have met (see [`SpinBarrier`]): a
/// vertex is two atomic words (plain loads and stores on a desktop), so
/// the threads share it with no lock and no copy.
#[derive(Debug, Default)]
struct SharedProjection {
    /// x (low half) and y (high half) of a projected vertex, as bits.
    xy: Vec<AtomicU64>,
    /// Its depth (below 2^24), or [`NEEDS_CLIP`] or [`NON_FINITE`].
    z: Vec<AtomicU32>,
    /// The first sample row at or below each projected vertex
    /// ([`NOT_PROJECTED`] for the others): 2 bytes a vertex, so that
    /// sorting the faces into bands reads little memory.
    rows: Vec<AtomicI16>,
}

/// [`SharedProjection::z`] of a vertex whose faces are clipped.
const NEEDS_CLIP: u32 = u32::MAX - 1;
/// [`SharedProjection::z`] of a vertex that is not finite.
const NON_FINITE: u32 = u32::MAX;
const _: () = assert!(crate::limits::DEPTH_MAX < NEEDS_CLIP);

impl SharedProjection {
    /// Room for `count` vertices (the old values stay, to be written over).
    fn resize(&mut self, count: usize) {
        self.xy.resize_with(count, AtomicU64::default);
        self.z.resize_with(count, AtomicU32::default);
        self.rows.resize_with(count, AtomicI16::default);
    }

    /// Projects the vertices in `indices` into their entries.
    fn project<M: Mesh>(
        &self,
        mesh: &M,
        model: &Mat4,
        camera: &Camera,
        indices: Range<usize>,
    ) -> Result<(), Error> {
        project_vertices_with(mesh, model, camera, indices, |index, vertex| {
            let (xy, z) = match vertex {
                ProjectedVertex::Screen(v) => {
                    (u64::from(v.x as u32) | u64::from(v.y as u32) << 32, v.z)
                }
                ProjectedVertex::NeedsClip => (0, NEEDS_CLIP),
                ProjectedVertex::NonFinite => (0, NON_FINITE),
            };
            if let (Some(a), Some(b), Some(r)) =
                (self.xy.get(index), self.z.get(index), self.rows.get(index))
            {
                a.store(xy, Relaxed);
                b.store(z, Relaxed);
                r.store(vertex_row(&vertex), Relaxed);
            }
        })
    }
}

impl VertexSource for &SharedProjection {
    #[inline(always)]
    fn projected(self, index: usize) -> Option<ProjectedVertex> {
        let (xy, z) = (
            self.xy.get(index)?.load(Relaxed),
            self.z.get(index)?.load(Relaxed),
        );
        Some(match z {
            NEEDS_CLIP => ProjectedVertex::NeedsClip,
            NON_FINITE => ProjectedVertex::NonFinite,
            z => ProjectedVertex::Screen(ScreenVertex {
                x: xy as u32 as i32,
                y: (xy >> 32) as u32 as i32,
                z,
            }),
        })
    }
}

/// Where the threads of one frame wait for each other between steps,
/// spinning (a meeting costs well under a microsecond, where starting
/// threads afresh for each step cost tens), then yielding if it takes
/// long. It opens early, with `false`, when a thread has failed or is
/// panicking (see [`Self::poison_on_panic`]), so no thread waits forever.
#[derive(Debug)]
struct SpinBarrier {
    threads: usize,
    arrived: AtomicUsize,
    generation: AtomicUsize,
    failed: AtomicBool,
}

impl SpinBarrier {
    fn new(threads: usize) -> Self {
        Self {
            threads,
            arrived: AtomicUsize::new(0),
            generation: AtomicUsize::new(0),
            failed: AtomicBool::new(false),
        }
    }

    /// Opens the barrier for good: every wait returns `false`.
    fn fail(&self) {
        self.failed.store(true, Release);
    }

    /// A guard that fails the barrier if its thread unwinds.
    fn poison_on_panic(&self) -> impl Drop + '_ {
        struct Guard<'a>(&'a SpinBarrier);
        impl Drop for Guard<'_> {
            fn drop(&mut self) {
                if std::thread::panicking() {
                    self.0.fail();
                }
            }
        }
        Guard(self)
    }

    /// Waits until every thread has arrived: `true`, unless the barrier
    /// has failed.
    fn wait(&self) -> bool {
        let generation = self.generation.load(Acquire);
        if self.failed.load(Acquire) {
            return false;
        }
        if self.arrived.fetch_add(1, AcqRel) + 1 == self.threads {
            self.arrived.store(0, Relaxed);
            self.generation.fetch_add(1, Release);
            return !self.failed.load(Acquire);
        }
        let mut spins = 0u32;
        while self.generation.load(Acquire) == generation {
            if self.failed.load(Acquire) {
                return false;
            }
            if spins < 1 << 14 {
                spins += 1;
                std::hint::spin_loop();
            } else {
                std::thread::yield_now();
            }
        }
        !self.failed.load(Acquire)
    }
}

/// Sorts `faces` of `mesh` into the bands they can reach, `out[band]`
/// holding the band's faces in increasing order, from the first sample
/// row at or below each vertex (`rows`, see [`vertex_row`]). A face goes
/// to a band when the sample rows from its highest corner's to its lowest
/// corner's (that one left out) include one of the band's, as
/// [`BandTables`] decides for a triangle; a face covering no sample row
/// goes nowhere (the tables would leave it out). A face with a corner that
/// is not projected (to be clipped, not finite, or beyond the mesh) or
/// with fewer than three corners goes to every band, whose tables judge
/// it.
fn sort_faces<M: Mesh>(
    mesh: &M,
    rows: &[AtomicI16],
    faces: Range<usize>,
    bands: &[Range<u16>],
    height: u16,
    out: &mut Vec<FaceList>,
) {
    // Each list has room for every face, and a face is written at the
    // list's end whether it is kept or not, the length moving only when it
    // is: about half the faces reach a band, and a branch on it would be
    // mispredicted as often. The room stays from frame to frame (written
    // before it is read), so nothing is cleared.
    out.resize_with(bands.len(), FaceList::default);
    for list in out.iter_mut() {
        list.make_room(faces.len() + 1);
    }
    for face in faces {
        // Faces are counted in u32 (`DrawStats`).
        let id = face as u32;
        // `None`: every band.
        let (first, end) =
            sample_rows(mesh.face(face), rows, height).unwrap_or((i16::MIN, i16::MAX));
        for (band, list) in bands.iter().zip(out.iter_mut()) {
            list.room[list.len] = id;
            let reaches = first < end && first < band.end as i16 && end > band.start as i16;
            list.len += usize::from(reaches);
        }
    }
}

/// One run's faces for one band ([`sort_faces`]): the first `len` entries
/// of `room`, which has room for every face of the run and more.
#[derive(Debug, Clone, Default)]
struct FaceList {
    room: Vec<u32>,
    len: usize,
}

impl FaceList {
    /// Empties the list, with room for `count` faces (the old entries stay
    /// in the room, to be written over).
    fn make_room(&mut self, count: usize) {
        if self.room.len() < count {
            self.room.resize(count, 0);
        }
        self.len = 0;
    }

    /// The faces in the list.
    fn faces(&self) -> &[u32] {
        &self.room[..self.len]
    }
}

/// The sample rows `first..end` of a face whose corners are all projected
/// (empty when it covers none), clamped to the frame (`height` <= 4,096);
/// `None` when a corner is not projected or the face has fewer than three
/// corners. (The first sample row at or below a corner is monotonic in
/// its `y`, so the face's rows come from its corners' rows.)
#[inline]
fn sample_rows(corners: &[u16], rows: &[AtomicI16], height: u16) -> Option<(i16, i16)> {
    let row = |corner: u16| rows.get(usize::from(corner)).map(|r| r.load(Relaxed));
    if let &[a, b, c] = corners {
        // The common case, a triangle, with no loop.
        let (Some(a), Some(b), Some(c)) = (row(a), row(b), row(c)) else {
            return None;
        };
        if a == NOT_PROJECTED || b == NOT_PROJECTED || c == NOT_PROJECTED {
            return None;
        }
        return Some((a.min(b).min(c).max(0), a.max(b).max(c).min(height as i16)));
    }
    if corners.len() < 3 {
        return None;
    }
    let (mut low, mut high) = (i16::MAX, NOT_PROJECTED);
    for &corner in corners {
        match row(corner) {
            Some(row) if row != NOT_PROJECTED => {
                low = low.min(row);
                high = high.max(row);
            }
            _ => return None,
        }
    }
    Some((low.max(0), high.min(height as i16)))
}

/// One band's frame: build, prepare, scan; then its work per row.
fn draw_band<C, D, X, K, B>(
    band: &mut Band<C, D>,
    scratch: &mut X,
    sink: &mut K,
    build: &B,
    test_triangles: bool,
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
    let mut tables = BandTables {
        tables: &mut renderer.tables,
        rows: rows.clone(),
        test_triangles,
    };
    build(&mut tables, scratch).map_err(RenderError::Table)?;
    let built = Instant::now();
    let prepared = renderer.tables.prepare();
    let stats = scan(&prepared, &mut renderer.scanner, rows.clone(), sink)?;
    band.last = BandTiming {
        rows: rows.clone(),
        polygons: prepared.polygons.len(),
        build: built - start,
        scan: built.elapsed(),
    };
    // Per row: its own upkeep, each polygon activated on it (those from
    // above the band on its first), and each polygon active on it. The
    // tables hold at most MAX_POLYGONS = 2^20 polygons, so `live` stays in
    // 0..=2^20 and a row's work below 4 + 6·2^20 < 2^23 (u32).
    let n = rows.len();
    let mut active = std::vec![0i64; n + 1];
    band.work.clear();
    band.work.resize(n, ROW_WORK);
    for polygon in prepared.polygons {
        let first = polygon.first_row.max(rows.start);
        let end = polygon.end_row.min(rows.end);
        if first >= end {
            continue;
        }
        let at = usize::from(first - rows.start);
        band.work[at] += ACTIVATION_WORK;
        active[at] += 1;
        active[usize::from(end - rows.start)] -= 1;
    }
    let mut live = 0i64;
    for (w, d) in band.work.iter_mut().zip(&active) {
        live += d;
        *w += live as u32 * ACTIVE_ROW_WORK;
    }
    Ok(stats)
}
