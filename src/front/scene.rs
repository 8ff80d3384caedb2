//! World to screen: transforms a mesh, culls and clips its faces, projects
//! them, shades them and offers them to the renderer's tables. Only faces
//! that can be visible enter the tables, and only the vertices they use.
//! ([`draw_mesh_projected`] does the same with vertices projected
//! beforehand, for example on other threads.)
//!
//! For each face, in order:
//! 1. **Transform** each corner to clip space (`projection · view · model`),
//!    once per vertex per draw. A [`VertexCache`] remembers where each mesh
//!    vertex went in the vertex table; [`draw_mesh`] resets it, so one
//!    cache serves every mesh of a frame.
//! 2. **Non-finite** corners (NaN or infinity even in `f64`): the face is
//!    skipped and counted in [`DrawStats::non_finite`]. A corner whose `f32`
//!    transform overflows but whose `f64` one is finite is clipped instead.
//! 3. **Frustum**: a face whose corners all lie outside one frustum plane is
//!    culled ([`DrawStats::outside`]).
//! 4. **Clipping**: a face with a corner behind the near plane, beyond the
//!    far plane, or outside the clipping band ([`CLIP_BAND_PX`] pixels
//!    around the frame's centre) is clipped in homogeneous space, in `f64`
//!    ([`crate::front::clip`]): cut, never dropped or turned inside out, with the
//!    cut corners within 1/256 pixel of the exact ones, for faces within the
//!    clipper's range ([`CLIP_RANGE`]: up to `2^28` near distances for a
//!    perspective camera); a larger face that needs clipping is refused
//!    with [`Error::ClipRange`]. A vertex within the `f32` transform's error
//!    of the near or far plane is the clipper's too. Corners that needed no
//!    clipping keep their shared vertex, so clipped and unclipped
//!    neighbours stay watertight.
//! 5. The core leaves out faces of **zero area** and faces covering **no
//!    pixel sample** ([`DrawStats::degenerate`], [`DrawStats::off_screen`]).
//! 6. **Back faces** (with [`Cull::Back`]): faces whose projected corners
//!    run clockwise as seen by the viewer are culled. The test is exact, on
//!    the sub-pixel grid the core uses.
//! 7. **Shading**: the face's colour comes from a closure over [`FaceInfo`],
//!    for example [`Shading::color`](crate::front::shade::Shading::color).
//!
//! A face that is not planar ([`crate::front::mesh::is_planar`]) has no single plane. It goes
//! through these steps as the fan of triangles from its first corner, each
//! with the face's id. A planar quad that is strictly convex on screen and
//! shares no plane is judged and shaded once, as a face, and queued as its
//! two triangles ([`DrawStats::convex_quads`]): they cover exactly its
//! samples, and the scan's triangle path costs about a quarter of a
//! polygon's a row.
//!
//! No step needs a buffer per face: corners stream into the tables, so a
//! face may have up to [`MAX_FACE_CORNERS`] corners.
//!
//! Depth handed to the core is `z_ndc` mapped to `[0, 1]`. It is affine in
//! screen space, so the core's plane stepping is exact.
//!
//! **Precision of the `f32` transform.** A vertex that needs no clipping
//! is transformed and projected in `f32`: its error is a few units of
//! `2^-24` of the sum of its transform's absolute terms, divided by its
//! `w`. That is a fraction of a sub-pixel step when the model and camera
//! sit near the world's origin, but a camera far from the origin looking
//! at a mesh near it (translations that cancel) loses that precision, as
//! any `f32` pipeline does: keep the world's origin near what is drawn.

use core::cell::OnceCell;
use core::fmt;

use crate::arith::wide::cross;
use crate::error::Error;
use crate::front::backface::{EyeTest, Side};
use crate::front::clip::{self, ClipPoint, ClipVertex, Clipper};
use crate::front::fixed_point::FixedFrame;
use crate::front::geometry::{Mat4, Vec3, Vec4, newell_normal, radians};
use crate::front::mesh::QuantizedView;
use crate::front::mesh::{Mesh, SharedPlane};
use crate::limits::NORMAL_SCALE;
use crate::limits::{CLIP_BAND_PX, MAX_FACE_CORNERS, MAX_POLYGON_CORNERS};
use crate::raster::vertex::{Outline, OutlineBuilder, ScreenVertex};
use crate::raster::{Admission, PolygonTables};

/// A camera: view and projection matrices and the frame they map to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// World (after the model matrix) to view space.
    pub view: Mat4,
    /// View space to clip space.
    pub projection: Mat4,
    /// Frame width in pixels.
    pub width: u16,
    /// Frame height in pixels.
    pub height: u16,
}

impl Camera {
    /// A perspective camera: vertical field of view in degrees, aspect ratio
    /// from the frame, clip planes at `near` and `far`.
    pub fn perspective(
        view: Mat4,
        fov_y_deg: f32,
        width: u16,
        height: u16,
        near: f32,
        far: f32,
    ) -> Self {
        let aspect = f32::from(width) / f32::from(height);
        Self {
            view,
            projection: Mat4::perspective(radians(fov_y_deg), aspect, near, far),
            width,
            height,
        }
    }

    /// The reference view: eye at (0, 0, 3) looking down -Z with +Y up,
    /// vertical field of view 45 degrees, near 0.1, far 10.
    pub fn reference(width: u16, height: u16) -> Self {
        let view = Mat4::translation(Vec3::new(0.0, 0.0, -3.0));
        Self::perspective(view, 45.0, width, height, 0.1, 10.0)
    }
}

/// The reference model matrix: centre the mesh on its bounding box centre
/// `c` and scale by `1/r`, where `r` is the largest distance from `c` to a
/// vertex. Then apply `Rx(pitch) · Ry(yaw)`, angles in degrees.
/// `Err(`[`Error::MeshExtent`]`)` when `r` cannot be normalised (see
/// [`bounding_sphere`]).
pub fn reference_model<M: Mesh + ?Sized>(
    mesh: &M,
    yaw_deg: f32,
    pitch_deg: f32,
) -> Result<Mat4, Error> {
    let (centre, radius) = bounding_sphere(mesh)?;
    Ok(reference_model_around(centre, radius, yaw_deg, pitch_deg))
}

/// [`reference_model`] for a mesh whose [`bounding_sphere`] is already
/// known: an animation computes the sphere once per mesh, not per frame.
pub fn reference_model_around(centre: Vec3, radius: f32, yaw_deg: f32, pitch_deg: f32) -> Mat4 {
    let scale = if radius > 0.0 { 1.0 / radius } else { 1.0 };
    let normalise = Mat4::scale(Vec3::new(scale, scale, scale)).mul(&Mat4::translation(-centre));
    Mat4::rotation_x(radians(pitch_deg))
        .mul(&Mat4::rotation_y(radians(yaw_deg)))
        .mul(&normalise)
}

/// Smallest and largest positive radius [`bounding_sphere`] accepts: both
/// `r` and `1/r` are then normal `f32` numbers.
pub const RADIUS_RANGE: (f32, f32) = (f32::MIN_POSITIVE, 1.0 / f32::MIN_POSITIVE);

/// Centre of the axis-aligned bounding box of all vertices, and the largest
/// distance from it to a vertex (0 for an empty or one-point mesh). For a
/// [quantized mesh](crate::QuantizedMesh) it is the sphere it was
/// quantized in: the original mesh's.
///
/// Computed in `f64`, so no finite `f32` coordinates overflow or underflow
/// on the way (`f32` squares of coordinates beyond about `1.8e19`, or
/// below about `1e-19`, would). `Err(`[`Error::MeshExtent`]`)` when the
/// radius is positive but outside [`RADIUS_RANGE`], where the scale `1/r`
/// would lose precision in `f32`, or when a position is not finite.
pub fn bounding_sphere<M: Mesh + ?Sized>(mesh: &M) -> Result<(Vec3, f32), Error> {
    if let Some(q) = mesh.quantized() {
        // The sphere the mesh was quantized in: the original mesh's
        // bounding sphere, known exactly, with no arithmetic (so no
        // floating-point library can round it differently).
        let [x, y, z] = q.centre;
        return Ok((Vec3::new(x, y, z), q.radius));
    }
    let count = mesh.vertex_count();
    if count == 0 {
        return Ok((Vec3::default(), 0.0));
    }
    let position = |i: usize| mesh.position(i).map(f64::from);
    let (mut lo, mut hi) = (position(0), position(0));
    for i in 1..count {
        let p = position(i);
        for axis in 0..3 {
            lo[axis] = lo[axis].min(p[axis]);
            hi[axis] = hi[axis].max(p[axis]);
        }
    }
    if !lo.iter().chain(&hi).all(|c| c.is_finite()) {
        return Err(Error::MeshExtent);
    }
    let centre = [0, 1, 2].map(|axis| (lo[axis] + hi[axis]) * 0.5);
    let radius2 = (0..count)
        .map(|i| {
            let p = position(i);
            (0..3)
                .map(|a| (p[a] - centre[a]) * (p[a] - centre[a]))
                .sum::<f64>()
        })
        .fold(0.0f64, f64::max);
    let radius = libm::sqrt(radius2);
    let centre = Vec3::new(centre[0] as f32, centre[1] as f32, centre[2] as f32);
    if radius == 0.0 {
        return Ok((centre, 0.0));
    }
    let (min, max) = RADIUS_RANGE;
    if !(f64::from(min)..=f64::from(max)).contains(&radius) {
        return Err(Error::MeshExtent);
    }
    Ok((centre, radius as f32))
}

/// Which faces to cull before they reach the tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Cull {
    /// Draw both sides (for meshes with inconsistent winding).
    #[default]
    None,
    /// Cull faces whose corners run clockwise on screen: their back is
    /// turned to the viewer when the mesh winds its faces counter-clockwise
    /// seen from outside (the OBJ convention).
    Back,
}

/// What a shading closure knows about a face. The face's index and side
/// are at hand; its normal and depth are computed only when asked for
/// ([`Self::normal`], [`Self::view_depth`]), so a shader that colours by
/// face id pays nothing for them.
#[derive(Clone, Copy)]
pub struct FaceInfo<'a> {
    /// Index of the face in the mesh.
    pub face: u32,
    /// Whether the face's front (counter-clockwise side) faces the viewer.
    pub front: bool,
    geometry: FaceGeometry<'a>,
}

/// Where a [`FaceInfo`]'s normal and depth come from.
#[derive(Clone, Copy)]
enum FaceGeometry<'a> {
    /// From the mesh, on demand.
    Mesh {
        mesh: &'a dyn Mesh,
        corners: &'a [u16],
        model_view: &'a Mat4,
    },
    /// Given.
    Known { normal: Vec3, view_depth: f32 },
    /// From a quantized mesh: the stored normal, rotated in integers.
    Quantized {
        mesh: &'a dyn Mesh,
        corners: &'a [u16],
        model_view: &'a Mat4,
        normal: [i16; 3],
        frame: &'a FixedFrame,
    },
}

impl core::fmt::Debug for FaceInfo<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FaceInfo")
            .field("face", &self.face)
            .field("front", &self.front)
            .field("normal", &self.normal())
            .field("view_depth", &self.view_depth())
            .finish()
    }
}

impl FaceInfo<'static> {
    /// A face whose normal (unit, view space) and view depth are known.
    pub const fn new(face: u32, front: bool, normal: Vec3, view_depth: f32) -> Self {
        Self {
            face,
            front,
            geometry: FaceGeometry::Known { normal, view_depth },
        }
    }
}

impl FaceInfo<'_> {
    /// Unit normal from the face's winding (Newell's, from its corners), in
    /// view space. For a quantized mesh it is [`Self::normal_q15`] as a
    /// `f32` vector.
    pub fn normal(&self) -> Vec3 {
        match self.geometry {
            FaceGeometry::Mesh {
                mesh,
                corners,
                model_view,
            } => mesh_normal(mesh, corners, model_view),
            FaceGeometry::Known { normal, .. } => normal,
            FaceGeometry::Quantized {
                mesh,
                corners,
                model_view,
                normal,
                frame,
            } => match frame.view_normal(normal) {
                Some(n) => normal_vector_i32(n),
                None => mesh_normal(mesh, corners, model_view),
            },
        }
    }

    /// The unit normal in view space in integers, units of `1/32767`, when
    /// the face comes from a [quantized mesh](crate::QuantizedMesh):
    /// its stored normal rotated by the model-view rotation, the same on
    /// every target and with no floating point. `None` for other faces.
    pub fn normal_q15(&self) -> Option<[i32; 3]> {
        match self.geometry {
            FaceGeometry::Quantized { normal, frame, .. } => frame.view_normal(normal),
            _ => None,
        }
    }

    /// View-space distance of the face's centroid along the view axis.
    pub fn view_depth(&self) -> f32 {
        match self.geometry {
            FaceGeometry::Mesh {
                mesh,
                corners,
                model_view,
            }
            | FaceGeometry::Quantized {
                mesh,
                corners,
                model_view,
                ..
            } => {
                let mut sum = Vec3::default();
                for &i in corners {
                    sum = sum + Vec3::from_array(mesh.position(usize::from(i)));
                }
                let centroid = sum * (1.0 / corners.len().max(1) as f32);
                let row = model_view.m[2];
                -(row[0] * centroid.x + row[1] * centroid.y + row[2] * centroid.z + row[3])
            }
            FaceGeometry::Known { view_depth, .. } => view_depth,
        }
    }
}

/// The view-space unit normal of a face from its corners (Newell's).
fn mesh_normal(mesh: &dyn Mesh, corners: &[u16], model_view: &Mat4) -> Vec3 {
    let n = newell_normal(corners.iter().map(|&i| mesh.position(usize::from(i))));
    model_view.transform_vector(n).normalized()
}

/// An integer normal in units of `1/32767` as a `f32` vector.
fn normal_vector_i32(n: [i32; 3]) -> Vec3 {
    let s = 1.0 / NORMAL_SCALE as f32;
    Vec3::new(n[0] as f32 * s, n[1] as f32 * s, n[2] as f32 * s)
}

/// Counts of what happened to a mesh's faces in one draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DrawStats {
    /// Faces in the mesh.
    pub faces: u32,
    /// Polygons that entered the polygon table: whole faces, and the
    /// triangles of split faces and of convex quads.
    pub queued: u32,
    /// Back faces culled.
    pub back_faces: u32,
    /// Faces wholly outside the frustum, or clipped away entirely.
    pub outside: u32,
    /// Faces that were clipped (and drawn, or culled afterwards).
    pub clipped: u32,
    /// Faces left out by the extremum test or as covering no sample.
    pub off_screen: u32,
    /// Faces of zero screen area.
    pub degenerate: u32,
    /// Faces skipped for a non-finite corner.
    pub non_finite: u32,
    /// Non-planar faces drawn as fans of triangles
    /// ([`is_planar`](crate::front::mesh::is_planar)).
    pub split: u32,
    /// Planar faces of four corners, convex on screen, drawn as two
    /// triangles (the two are counted as queued polygons).
    pub convex_quads: u32,
    /// Queued polygons given the plane their face shares with others
    /// ([`SharedPlane`]).
    pub shared_planes: u32,
    /// Queued polygons whose face has a shared plane they could not take
    /// because a vertex of that plane needs clipping (behind the camera or
    /// beyond the clipping band): they keep their own plane this frame.
    pub unshared_planes: u32,
}

/// Where each mesh vertex went in the vertex table during one
/// [`draw_mesh`]: 2 bytes per mesh vertex, for meshes of up to `VM`
/// vertices. It is scratch space: `draw_mesh` resets the entries it uses
/// before it starts, so one cache serves any number of meshes (and any
/// number of draws of one mesh with different model matrices) in a frame.
#[derive(Debug, Clone)]
pub struct VertexCache<const VM: usize> {
    slots: [u16; VM],
}

/// Not yet transformed in this draw.
const EMPTY: u16 = u16::MAX;
/// Transformed, and it needs clipping: never projected as it is.
const NEEDS_CLIP: u16 = u16::MAX - 1;
/// Its position is not finite even in `f64`.
const NON_FINITE: u16 = u16::MAX - 2;

impl<const VM: usize> VertexCache<VM> {
    /// An empty cache.
    pub const fn new() -> Self {
        Self { slots: [EMPTY; VM] }
    }

    /// Forgets every vertex. [`draw_mesh`] does this itself for the
    /// vertices it uses; there is no need to call it between draws.
    pub fn clear(&mut self) {
        self.slots.fill(EMPTY);
    }
}

impl<const VM: usize> Default for VertexCache<VM> {
    fn default() -> Self {
        Self::new()
    }
}

/// Where [`draw_mesh`] remembers, for one draw, which vertex-table entry
/// each mesh vertex went to: a [`VertexCache`], a `Vec<u16>` on a desktop
/// (feature `std`, one entry per mesh vertex), or none ([`NoVertexCache`],
/// for a [`Renderer`](crate::Renderer) that does not draw meshes). Its
/// contents between draws do not matter: each draw resets the entries it
/// uses.
pub trait CacheStorage: cache_seal::Sealed {
    /// An empty cache of this kind (for a `Vec`, of no entries).
    #[doc(hidden)]
    const EMPTY: Self;
    /// The entries, one per mesh vertex.
    #[doc(hidden)]
    fn slots_mut(&mut self) -> &mut [u16];
}

/// No vertex cache: a [`Renderer`](crate::Renderer) with it draws screen
/// polygons only ([`draw_mesh`] needs a cache).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoVertexCache;

impl CacheStorage for NoVertexCache {
    const EMPTY: Self = Self;

    fn slots_mut(&mut self) -> &mut [u16] {
        &mut []
    }
}

impl<const VM: usize> CacheStorage for VertexCache<VM> {
    const EMPTY: Self = Self::new();

    fn slots_mut(&mut self) -> &mut [u16] {
        &mut self.slots
    }
}

#[cfg(feature = "std")]
impl CacheStorage for std::vec::Vec<u16> {
    const EMPTY: Self = std::vec::Vec::new();

    fn slots_mut(&mut self) -> &mut [u16] {
        self
    }
}

/// Keeps [`CacheStorage`] to this crate's caches.
mod cache_seal {
    pub trait Sealed {}
    impl Sealed for super::NoVertexCache {}
    impl<const VM: usize> Sealed for super::VertexCache<VM> {}
    #[cfg(feature = "std")]
    impl Sealed for std::vec::Vec<u16> {}
}

/// Why [`draw_mesh`] stopped: the error, and the face it stopped at
/// (`None` when it stopped before the first face). Faces before that face
/// stay in the tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DrawError {
    /// Index of the face being drawn.
    pub face: Option<u32>,
    /// What went wrong.
    pub error: Error,
}

impl fmt::Display for DrawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.face {
            Some(face) => write!(f, "face {face}: {}", self.error),
            None => write!(f, "{}", self.error),
        }
    }
}

impl core::error::Error for DrawError {}

impl From<DrawError> for Error {
    fn from(e: DrawError) -> Self {
        e.error
    }
}

impl<E> From<DrawError> for crate::error::RenderError<E> {
    fn from(e: DrawError) -> Self {
        crate::error::RenderError::Table(e.error)
    }
}

/// One corner of the face being processed, from the cache.
#[derive(Debug, Clone, Copy)]
enum Corner {
    /// In the vertex table (its index is in the cache).
    Stored,
    /// Needs clipping.
    Clip,
    /// Not finite.
    NonFinite,
}

/// How far a face that needs clipping may reach, relative to the view
/// frustum's nearest point: its clip-space size (the largest sum of the
/// absolute terms of a corner's transform, `|projection| · |view| ·
/// |model| · |p|`, over its corners and coordinates) at most `2^28` times
/// the smallest clip-space `w` in the frustum (for a perspective camera,
/// the near distance). Within it, the `f64` transform and clipper place
/// every corner a cut makes within 1/256 pixel of the exact cut of the
/// given `f32` positions and matrices, and its depth within `2^-20`
/// (`tests/clipping.rs` checks both against a reference in twice `f64`'s
/// precision, over the whole `f32` range). A face beyond it is refused
/// with [`Error::ClipRange`]; a face wholly outside one frustum plane is
/// culled first, whatever its size.
///
/// (The `f64` arithmetic's error on a corner is a few units of `2^-53`
/// times that size, and it is divided by `w` when projected: at `2^28`
/// that is below `2^-22` of the frame's half-size, and of the depth
/// range.)
pub const CLIP_RANGE: f64 = (1u64 << 28) as f64;

/// The `f32` front end's error on a vertex's distance to the near or far
/// plane, per unit of the sum of the absolute terms of its transform
/// (`2^-20`): the `f32` product of the three matrices and the transform
/// err by a few units of `2^-24` of those terms on `z` and on `w`. A vertex
/// nearer to one of those planes than that may lie on either side of it;
/// it goes to the `f64` clipper, which decides. (With far 10^6 times near,
/// a vertex a millionth of the far distance beyond the far plane passed
/// the `f32` test, and a face grazing the far plane kept it: a corner 200
/// pixels off.)
const NEAR_FAR_ERROR: f32 = 1.0 / (1u32 << 20) as f32;

/// A bound on the `f64` transform's error on a plane's distance to a
/// corner, per unit of the corner's clip-space size: the product of the
/// three matrices (two products of four terms) and the transform (four
/// more) err by at most about 12 units of `2^-53` of the size on each
/// coordinate, and a frustum plane sums two coordinates. `2^-46` is eight
/// times that.
const CLIP_ERROR: f64 = 1.0 / (1u64 << 46) as f64;

/// The `f64` state of a frame for faces that need clipping.
#[derive(Debug, Clone, Copy)]
struct Clip64 {
    /// `projection · view · model`.
    mvp: [[f64; 4]; 4],
    /// `|projection| · |view| · |model|` (entrywise absolute values): a
    /// corner's transform terms, whose sum bounds the arithmetic's error.
    mvp_abs: [[f64; 4]; 4],
    /// The smallest clip-space `w` in the view frustum (with the guard
    /// band): below it no cut corner can lie.
    w_near: f64,
}

impl Clip64 {
    fn new([projection, view, model]: &[Mat4; 3]) -> Self {
        let abs = |m: &Mat4| m.m.map(|row| row.map(|v| f64::from(v).abs()));
        let mvp = mul64(&to64(projection), &mul64(&to64(view), &to64(model)));
        let mvp_abs = mul64(&abs(projection), &mul64(&abs(view), &abs(model)));
        Self {
            mvp,
            mvp_abs,
            w_near: 0.0,
        }
    }
}

/// The smallest clip-space `w` of a point of view space inside the
/// frustum `|x|, |y| <= g·w`, `|z| <= w` of `projection` (`0` when it cannot
/// be found: a singular projection).
///
/// The frustum is a cone in clip space, and view space the hyperplane
/// `r · c = 1` where `r` is the last row of the projection's inverse; the
/// cone's edges `k = (±gx, ±gy, ±1, 1)` meet it at `w = 1 / (r · k)` where
/// `r · k > 0`, and the smallest of those is the frustum's smallest `w`.
fn frustum_w_near(projection: &Mat4, (gx, gy): (f64, f64)) -> f64 {
    // r solves projection^T · r = e_3 (Gaussian elimination, partial
    // pivoting).
    let mut a = [[0.0f64; 5]; 4];
    for (i, row) in a.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().take(4).enumerate() {
            *cell = f64::from(projection.m[j][i]);
        }
        row[4] = if i == 3 { 1.0 } else { 0.0 };
    }
    for col in 0..4 {
        let Some(pivot) = (col..4).max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))
        else {
            return 0.0;
        };
        // (A zero or NaN pivot: singular, or not finite.)
        let usable = a[pivot][col].abs() > 0.0;
        if !usable {
            return 0.0;
        }
        a.swap(col, pivot);
        let pivot_row = a[col];
        for (k, row) in a.iter_mut().enumerate() {
            if k != col {
                let f = row[col] / pivot_row[col];
                for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                    *x -= f * p;
                }
            }
        }
    }
    let r: [f64; 4] = core::array::from_fn(|i| a[i][4] / a[i][i]);
    let mut largest = 0.0f64;
    for sx in [-gx, gx] {
        for sy in [-gy, gy] {
            for sz in [-1.0, 1.0] {
                largest = largest.max(r[0] * sx + r[1] * sy + r[2] * sz + r[3]);
            }
        }
    }
    let w = 1.0 / largest;
    if w.is_finite() && w > 0.0 { w } else { 0.0 }
}

/// Per-draw constants.
struct Frame {
    mvp: Mat4,
    /// The same product and the frustum's nearest `w` in `f64`, for faces
    /// that need clipping: made the first time one does (on a core without
    /// an FPU it is hundreds of soft-float operations, every frame).
    clip64: OnceCell<Clip64>,
    /// What `mvp64` is the product of: projection, view and model.
    factors: [Mat4; 3],
    model_view: Mat4,
    width: f32,
    height: f32,
    /// Guard band half-widths in NDC units, x and y.
    guard: (f32, f32),
    /// The sum of the absolute terms of the `z` and `w` rows of
    /// `|projection| · |view| · |model|`: per unit of a position's largest
    /// coordinate, and the constant (see [`Frame::inside_guard`]).
    near_far_terms: (f32, f32),
    cull: Cull,
    /// The integer front end, for a quantized mesh whose matrices fit it.
    fixed: Option<FixedFrame>,
}

/// `a · b` in `f64`.
fn mul64(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let mut r = [[0.0f64; 4]; 4];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    r
}

fn to64(m: &Mat4) -> [[f64; 4]; 4] {
    m.m.map(|row| row.map(f64::from))
}

impl Frame {
    fn new(model: &Mat4, camera: &Camera, cull: Cull, quantized: Option<&QuantizedView>) -> Self {
        let model_view = camera.view.mul(model);
        let (width, height) = (f32::from(camera.width), f32::from(camera.height));
        let mvp = camera.projection.mul(&model_view);
        let fixed = quantized.and_then(|q| {
            FixedFrame::new(
                &mvp,
                &model_view,
                q.centre,
                q.radius,
                camera.width,
                camera.height,
            )
        });
        // Only the f32 front end uses them: the integer one takes every
        // vertex when it takes the mesh (and on a core without an FPU the
        // two products cost about 10,000 instructions a draw).
        let near_far_terms = if fixed.is_some() {
            (0.0, 0.0)
        } else {
            let abs = |m: &Mat4| Mat4 {
                m: m.m.map(|row| row.map(f32::abs)),
            };
            let terms = abs(&camera.projection).mul(&abs(&camera.view).mul(&abs(model)));
            let [z, w] = [terms.m[2], terms.m[3]];
            (z[0] + z[1] + z[2] + w[0] + w[1] + w[2], z[3] + w[3])
        };
        Self {
            mvp,
            near_far_terms,
            clip64: OnceCell::new(),
            factors: [camera.projection, camera.view, *model],
            model_view,
            fixed,
            width,
            height,
            guard: (
                2.0 * CLIP_BAND_PX / width - 1.0,
                2.0 * CLIP_BAND_PX / height - 1.0,
            ),
            cull,
        }
    }

    /// Whether the clip-space point `p` of a position whose largest
    /// coordinate is `extent` lies inside the guard-band planes, and
    /// inside the near and far planes by more than the `f32` transform's
    /// error ([`NEAR_FAR_ERROR`]): nearer to one of those, it is the `f64`
    /// clipper's to decide. (Outside the guard band by a rounding, a point
    /// is still far inside the core's.)
    fn inside_guard(&self, p: Vec4, extent: f32) -> bool {
        let (gx, gy) = self.guard;
        let (per_unit, constant) = self.near_far_terms;
        let margin = (per_unit * extent + constant) * NEAR_FAR_ERROR;
        p.z + p.w > margin && p.w - p.z > margin && p.x.abs() <= gx * p.w && p.y.abs() <= gy * p.w
    }

    /// Transforms mesh vertex `index` to clip space and classifies it: a
    /// vertex inside the near, far and clipping-band planes is projected
    /// and given to `screen`; for the others, `needs_clip` or `non_finite`
    /// (what [`ProjectedVertex`] names). With the integer front end
    /// (`positions`), a point outside the band is clipped in `f64` like any
    /// other, and none is non-finite. (The outcomes are the caller's: an
    /// enum returned and matched cost 0.25 % of an RP2040 frame.)
    #[inline(always)]
    fn vertex<M: Mesh + ?Sized, R>(
        &self,
        mesh: &M,
        positions: Option<&[[i16; 3]]>,
        index: usize,
        screen: impl FnOnce(ScreenVertex) -> Result<R, Error>,
        (needs_clip, non_finite): (R, R),
    ) -> Result<R, Error> {
        if let (Some(fixed), Some(positions)) = (&self.fixed, positions) {
            let q = positions.get(index).ok_or(Error::MeshIndexOutOfRange)?;
            let c = fixed.clip(*q);
            let stored = if fixed.inside(&c) {
                fixed.project(&c)
            } else {
                None
            };
            return match stored {
                Some(v) => screen(v),
                None => Ok(needs_clip),
            };
        }
        let position = mesh.position(index);
        let p = self.mvp.transform_point(Vec3::from_array(position));
        let extent = position[0]
            .abs()
            .max(position[1].abs())
            .max(position[2].abs());
        let stored = if !p.is_finite() {
            None
        } else if self.inside_guard(p, extent) {
            self.project(p)
        } else {
            None
        };
        match stored {
            Some(v) => screen(v),
            None if self.clip_position64(mesh, index).is_finite() => Ok(needs_clip),
            None => Ok(non_finite),
        }
    }

    /// The frame's `f64` state for clipping, made on first use.
    fn clip64(&self) -> &Clip64 {
        self.clip64.get_or_init(|| {
            let mut clip = Clip64::new(&self.factors);
            let (gx, gy) = self.guard;
            clip.w_near = frustum_w_near(&self.factors[0], (f64::from(gx), f64::from(gy)));
            clip
        })
    }

    /// Clip-space position in `f64`.
    fn clip_position64<M: Mesh + ?Sized>(&self, mesh: &M, index: usize) -> ClipPoint {
        let p = mesh.position(index).map(f64::from);
        let row = |r: [f64; 4]| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3];
        let m = &self.clip64().mvp;
        ClipPoint::new(row(m[0]), row(m[1]), row(m[2]), row(m[3]))
    }

    /// Whether a face that needs clipping lies wholly outside one frustum
    /// plane beyond doubt, whatever its size: each corner farther outside
    /// it than the arithmetic's error (a few units of 2^-53 of the corner's
    /// size on each coordinate; a frustum plane adds two of them), or each
    /// corner at or behind the eye (`w <= 0`) beyond doubt. Otherwise it
    /// is clipped, if it is within the clipper's range ([`CLIP_RANGE`]),
    /// and refused with [`Error::ClipRange`] if not (or if its size is not
    /// finite, or the projection is singular). Out of line: the rare
    /// path's, kept out of the common path's code.
    #[inline(never)]
    fn wholly_outside<M: Mesh + ?Sized>(&self, mesh: &M, corners: &[u16]) -> Result<bool, Error> {
        let (mut outside, mut size) = (u32::MAX, 0.0f64);
        for &index in corners {
            let p = self.clip_position64(mesh, usize::from(index));
            let corner_size = self.clip_size64(mesh, usize::from(index));
            let margin = CLIP_ERROR * corner_size;
            // Bit 6: not in front of the eye (w <= 0) for certain.
            let behind = if p.w <= -margin { 1 << 6 } else { 0 };
            outside &= clip::outside_mask(p, &clip::FRUSTUM, margin) | behind;
            size = size.max(corner_size);
        }
        if outside != 0 {
            return Ok(true);
        }
        // A singular projection has no frustum (its smallest w is 0): no
        // face can be clipped.
        let w_near = self.clip64().w_near;
        let within = w_near > 0.0 && size <= CLIP_RANGE * w_near;
        if within {
            Ok(false)
        } else {
            Err(Error::ClipRange)
        }
    }

    /// The clip-space size of mesh vertex `index`: the largest sum of the
    /// absolute terms of its transform, over the four coordinates (see
    /// [`CLIP_RANGE`]).
    fn clip_size64<M: Mesh + ?Sized>(&self, mesh: &M, index: usize) -> f64 {
        let p = mesh.position(index).map(|c| f64::from(c).abs());
        let row = |r: [f64; 4]| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3];
        let m = &self.clip64().mvp_abs;
        row(m[0]).max(row(m[1])).max(row(m[2])).max(row(m[3]))
    }

    /// Screen vertex of a clip-space point inside the near, far and guard
    /// planes.
    fn project(&self, p: Vec4) -> Option<ScreenVertex> {
        let inv_w = 1.0 / p.w;
        let x = (p.x * inv_w + 1.0) * 0.5 * self.width;
        let y = (1.0 - p.y * inv_w) * 0.5 * self.height;
        let z = ((p.z * inv_w + 1.0) * 0.5).clamp(0.0, 1.0);
        ScreenVertex::from_f32(x, y, z).ok()
    }

    /// [`Self::project`] in `f64`, for the corners clipping made.
    fn project64(&self, p: ClipPoint) -> Option<ScreenVertex> {
        let inv_w = 1.0 / p.w;
        let x = (p.x * inv_w + 1.0) * 0.5 * f64::from(self.width);
        let y = (1.0 - p.y * inv_w) * 0.5 * f64::from(self.height);
        let z = ((p.z * inv_w + 1.0) * 0.5).clamp(0.0, 1.0);
        ScreenVertex::from_f64(x, y, z).ok()
    }

    /// The guard planes in `f64`.
    fn guard_planes(&self) -> [[f64; 4]; 6] {
        clip::guard_planes(f64::from(self.guard.0), f64::from(self.guard.1))
    }

    /// What the shader may ask about a face.
    fn face_info<'a, M: Mesh>(
        &'a self,
        mesh: &'a M,
        face: usize,
        corners: &'a [u16],
        front: bool,
    ) -> FaceInfo<'a> {
        let model_view = &self.model_view;
        let geometry = match (&self.fixed, mesh.quantized()) {
            (Some(frame), Some(q)) => FaceGeometry::Quantized {
                mesh,
                corners,
                model_view,
                normal: q.normals.get(face).copied().unwrap_or_default(),
                frame,
            },
            _ => FaceGeometry::Mesh {
                mesh,
                corners,
                model_view,
            },
        };
        FaceInfo {
            face: face as u32,
            front,
            geometry,
        }
    }
}

/// Draws `mesh` with the `model` matrix through `camera` into `tables`:
/// culls, clips, projects and shades every face, and offers the survivors
/// to the polygon table. Call the renderer's `render` afterwards.
///
/// `cache` must hold at least `mesh.vertex_count()` entries; it is reset
/// here, so one cache serves every mesh of a frame. On `Err` (a table is
/// full, the mesh is malformed, or a face that needs clipping is beyond
/// the clipper's range, [`CLIP_RANGE`]) the faces before the failing one stay in
/// the tables, and the error names the face; of a failing face queued as
/// triangles (a fan, or a convex quad's two), those queued before the one
/// that did not fit stay too.
pub fn draw_mesh<C, T, M, K>(
    tables: &mut T,
    cache: &mut K,
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    shade: impl FnMut(&FaceInfo) -> C,
) -> Result<DrawStats, DrawError>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh,
    K: CacheStorage,
{
    let vertex_count = mesh.vertex_count();
    let Some(slots) = cache.slots_mut().get_mut(..vertex_count) else {
        return Err(DrawError {
            face: None,
            error: Error::VertexCacheTooSmall,
        });
    };
    slots.fill(EMPTY);
    draw_faces(
        tables,
        slots,
        mesh,
        TransformEach,
        (model, camera, cull),
        shade,
        None,
    )
}

/// Where one mesh vertex lands in a frame ([`project_vertices`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProjectedVertex {
    /// Inside the near, far and clipping-band planes: its screen vertex.
    Screen(ScreenVertex),
    /// Outside one of those planes: the faces using it are clipped.
    NeedsClip,
    /// Not finite even in `f64`: the faces using it are skipped.
    NonFinite,
}

/// Transforms and projects mesh vertices `first..first + out.len()` as
/// [`draw_mesh`] does (step 1), for [`draw_mesh_projected`]. Independent
/// ranges can be projected on different threads (or cores) and the
/// results put side by side.
pub fn project_vertices<M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    first: usize,
    out: &mut [ProjectedVertex],
) -> Result<(), Error> {
    let mut out = out.iter_mut();
    project_vertices_with(
        mesh,
        model,
        camera,
        first..first + out.len(),
        |_, vertex| {
            if let Some(slot) = out.next() {
                *slot = vertex;
            }
        },
    )
}

/// [`project_vertices`] for the vertices in `indices`, each handed to
/// `store` with its index (for storage other than a slice, such as the
/// host's banded renderer's, shared by its threads).
pub(crate) fn project_vertices_with<M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    indices: core::ops::Range<usize>,
    mut store: impl FnMut(usize, ProjectedVertex),
) -> Result<(), Error> {
    let quantized = mesh.quantized();
    let frame = Frame::new(model, camera, Cull::None, quantized.as_ref());
    let positions = quantized
        .filter(|_| frame.fixed.is_some())
        .map(|q| q.positions);
    for index in indices {
        if index >= mesh.vertex_count() {
            return Err(Error::MeshIndexOutOfRange);
        }
        let fates = (ProjectedVertex::NeedsClip, ProjectedVertex::NonFinite);
        let vertex = frame.vertex(
            mesh,
            positions,
            index,
            |v| Ok(ProjectedVertex::Screen(v)),
            fates,
        )?;
        store(index, vertex);
    }
    Ok(())
}

/// [`draw_mesh`] with the vertices already projected, for the faces in
/// `faces` (all of them when it is `None`).
///
/// `projected` holds [`project_vertices`]' result for the first
/// `projected.len()` vertices of `mesh` (normally all of them) under the
/// same `model` and `camera`. A vertex enters the vertex table on its
/// first use, as in `draw_mesh`, taken from `projected` instead of
/// transformed (a vertex beyond `projected` is transformed). The faces go
/// through steps 2 to 7 as in `draw_mesh`, in order: the rows drawn are
/// those `draw_mesh` draws for the same faces.
///
/// Several tables (bands of one frame on several threads, as the host's
/// `BandedRenderer::render_mesh` draws them) can share one projection
/// instead of each transforming every vertex, and each draw only the
/// faces that can reach its rows.
///
/// Errors: more entries in `projected` than `mesh` has vertices, or a
/// face in `faces` beyond the mesh, is [`Error::MeshIndexOutOfRange`];
/// faces not in increasing order are [`Error::FacesOutOfOrder`]. A
/// projection made with another model or camera is not detected (its
/// vertices are valid, only not this view's).
#[allow(clippy::too_many_arguments)]
pub fn draw_mesh_projected<C, T, M, K>(
    tables: &mut T,
    cache: &mut K,
    projected: &[ProjectedVertex],
    faces: Option<&[u32]>,
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    shade: impl FnMut(&FaceInfo) -> C,
) -> Result<DrawStats, DrawError>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh,
    K: CacheStorage,
{
    let count = projected.len();
    draw_mesh_from(
        tables,
        cache,
        (projected, count),
        faces,
        mesh,
        (model, camera, cull),
        shade,
    )
}

/// [`draw_mesh_projected`] with the projection of the first `count`
/// vertices in any [`VertexSource`].
pub(crate) fn draw_mesh_from<C, T, M, P, K>(
    tables: &mut T,
    cache: &mut K,
    (projected, count): (P, usize),
    faces: Option<&[u32]>,
    mesh: &M,
    (model, camera, cull): (&Mat4, &Camera, Cull),
    shade: impl FnMut(&FaceInfo) -> C,
) -> Result<DrawStats, DrawError>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh,
    K: CacheStorage,
    P: VertexSource,
{
    let fail = |error| DrawError { face: None, error };
    let Some(slots) = cache.slots_mut().get_mut(..mesh.vertex_count()) else {
        return Err(fail(Error::VertexCacheTooSmall));
    };
    if count > slots.len() {
        return Err(fail(Error::MeshIndexOutOfRange));
    }
    if let Some(faces) = faces {
        if faces.windows(2).any(|w| w[0] >= w[1]) {
            return Err(fail(Error::FacesOutOfOrder));
        }
        if let Some(&last) = faces.last()
            && last as usize >= mesh.face_count()
        {
            return Err(DrawError {
                face: Some(last),
                error: Error::MeshIndexOutOfRange,
            });
        }
    }
    slots.fill(EMPTY);
    draw_faces(
        tables,
        slots,
        mesh,
        projected,
        (model, camera, cull),
        shade,
        faces,
    )
}

/// Adds a projected vertex to the tables: its index, which must stay
/// below the cache's markers.
#[inline(always)]
fn store_vertex<C, T: PolygonTables<C> + ?Sized>(
    tables: &mut T,
    vertex: ScreenVertex,
) -> Result<u16, Error> {
    let id = tables.add_vertex(vertex)?;
    if id >= NON_FINITE {
        return Err(Error::VertexTableFull);
    }
    Ok(id)
}

/// Steps 2 to 7 for `faces` of `mesh` (increasing; all of them for
/// `None`), with the cache reset
/// and the first `projected.len()` vertices projected beforehand (see
/// [`draw_mesh_projected`]).
#[inline(always)]
fn draw_faces<C, T, M, P>(
    tables: &mut T,
    slots: &mut [u16],
    mesh: &M,
    projected: P,
    (model, camera, cull): (&Mat4, &Camera, Cull),
    mut shade: impl FnMut(&FaceInfo) -> C,
    faces: Option<&[u32]>,
) -> Result<DrawStats, DrawError>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh,
    P: VertexSource,
{
    let quantized = mesh.quantized();
    let frame = Frame::new(model, camera, cull, quantized.as_ref());
    let mut stats = DrawStats {
        faces: mesh.face_count() as u32,
        ..DrawStats::default()
    };
    let positions = quantized
        .filter(|_| frame.fixed.is_some())
        .map(|q| q.positions);
    // The model-space back-face test, for the integer front end.
    let eye = match (&frame.fixed, positions) {
        (Some(fixed), Some(_)) if cull == Cull::Back => EyeTest::new(fixed),
        _ => None,
    };
    let mut draw = Draw {
        tables,
        slots,
        mesh,
        projected,
        positions,
        eye,
        exact_normals: quantized.map_or(&[][..], |q| q.exact_normals),
        frame: &frame,
        stats: &mut stats,
        shade: &mut shade,
        planes: mesh.shared_planes(),
    };
    let mut draw_face = |face: usize| {
        draw.face(face).map_err(|error| DrawError {
            face: Some(face as u32),
            error,
        })
    };
    match faces {
        // (`draw_mesh` passes `None`: its loop is a plain count.)
        None => (0..mesh.face_count()).try_for_each(&mut draw_face)?,
        Some(faces) => faces
            .iter()
            .try_for_each(|&face| draw_face(face as usize))?,
    }
    Ok(stats)
}

/// Where a [`Draw`] finds a vertex on its first use, before transforming
/// it itself: nowhere in [`draw_mesh`], in the projection given to
/// [`draw_mesh_projected`]. (A type, so that `draw_mesh` pays nothing for
/// it.)
pub(crate) trait VertexSource: Copy {
    /// Vertex `index`, if it was projected beforehand.
    fn projected(self, index: usize) -> Option<ProjectedVertex>;
}

/// [`draw_mesh`]'s source: every vertex is transformed on its first use.
#[derive(Debug, Clone, Copy)]
struct TransformEach;

impl VertexSource for TransformEach {
    #[inline(always)]
    fn projected(self, _: usize) -> Option<ProjectedVertex> {
        None
    }
}

impl VertexSource for &[ProjectedVertex] {
    #[inline(always)]
    fn projected(self, index: usize) -> Option<ProjectedVertex> {
        self.get(index).copied()
    }
}

/// The state of one [`draw_mesh`].
struct Draw<'a, T: ?Sized, M: ?Sized, S, P> {
    tables: &'a mut T,
    /// Where each mesh vertex went in the vertex table this draw.
    slots: &'a mut [u16],
    mesh: &'a M,
    /// The vertices projected beforehand ([`draw_mesh_projected`]).
    projected: P,
    /// The quantized positions, when the integer front end transforms
    /// this mesh.
    positions: Option<&'a [[i16; 3]]>,
    /// The eye for the model-space back-face test (integer front end,
    /// back faces culled).
    eye: Option<EyeTest>,
    /// The quantized mesh's exact normals, if it has them.
    exact_normals: &'a [[i16; 3]],
    frame: &'a Frame,
    stats: &'a mut DrawStats,
    shade: &'a mut S,
    /// The mesh's shared planes not yet reached (sorted by face).
    planes: &'a [SharedPlane],
}

impl<C, T, M, S, P> Draw<'_, T, M, S, P>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh,
    S: FnMut(&FaceInfo) -> C,
    P: VertexSource,
{
    fn face(&mut self, face: usize) -> Result<(), Error> {
        let corners = self.mesh.face(face);
        if corners.len() > MAX_FACE_CORNERS {
            return Err(Error::TooManyCorners);
        }
        if corners.len() < 3 {
            self.stats.degenerate += 1;
            return Ok(());
        }
        let mut side = Side::Unsure;
        if let (Some(eye), Some(positions), &[i0, i1, i2]) = (&self.eye, self.positions, corners)
            && let (Some(q0), Some(q1), Some(q2)) = (
                positions.get(usize::from(i0)),
                positions.get(usize::from(i1)),
                positions.get(usize::from(i2)),
            )
        {
            side = match self.exact_normals.get(face) {
                Some(n) => eye.side_of(n, q0),
                None => eye.side(q0, q1, q2),
            };
            if side == Side::Back {
                // Turned away beyond doubt: no corner is transformed for
                // it.
                self.stats.back_faces += 1;
                return Ok(());
            }
        }
        if corners.len() > 3 && !self.mesh.face_is_planar(face) {
            self.stats.split += 1;
            for k in 1..corners.len() - 1 {
                self.part(
                    face,
                    &[corners[0], corners[k], corners[k + 1]],
                    Side::Unsure,
                )?;
            }
            Ok(())
        } else {
            self.part(face, corners, side)
        }
    }

    /// Draws one polygon of a face: the face itself, or one triangle of
    /// its fan.
    fn part(&mut self, face: usize, corners: &[u16], side: Side) -> Result<(), Error> {
        if let &[i0, i1, i2] = corners {
            // The common case: a triangle whose corners are all projected.
            let ids = [self.slot(i0)?, self.slot(i1)?, self.slot(i2)?];
            if ids.iter().all(|&id| id < NON_FINITE) {
                // (A front face beyond doubt skips the early test: the
                // tables test its rounded corners anyway.)
                if self.frame.cull == Cull::Back && side != Side::Front && self.faces_away(ids) {
                    // Culled before the tables' frame and sample tests, and
                    // their call into the shading closure.
                    self.stats.back_faces += 1;
                    return Ok(());
                }
                let (frame, mesh, stats) = (self.frame, self.mesh, &mut *self.stats);
                let shade = &mut *self.shade;
                let admission = self.tables.offer_triangle(ids, |outline| {
                    shade_front_face(frame, mesh, face, corners, outline, stats, shade)
                })?;
                self.count(face, admission)?;
                return Ok(());
            }
        }
        let (mut clip, mut non_finite) = (false, false);
        for &index in corners {
            match self.classify(usize::from(index))? {
                Corner::Stored => {}
                Corner::Clip => clip = true,
                Corner::NonFinite => non_finite = true,
            }
        }
        if non_finite {
            self.stats.non_finite += 1;
            return Ok(());
        }
        if clip {
            return self.clipped_part(face, corners);
        }
        self.stored_polygon(face, corners)
    }

    /// Draws a polygon of more than three corners, or a triangle that
    /// missed the fast path, whose corners are all in the vertex table: a
    /// convex quad as two triangles, any other as one polygon. Out of
    /// line: rare in a mesh of triangles, whose path in [`Self::part`]
    /// stays small (on the RP2040 the frame's cycles are those of the code
    /// before the quads' path was added, within 0.02 %).
    #[inline(never)]
    fn stored_polygon(&mut self, face: usize, corners: &[u16]) -> Result<(), Error> {
        if let &[i0, i1, i2, i3] = corners {
            let slots = &self.slots;
            let ids = [i0, i1, i2, i3].map(|index| slots[usize::from(index)]);
            if let Some(twice_area) = self.convex_quad(face, ids) {
                return self.quad_as_triangles(face, corners, ids, twice_area);
            }
        }
        let (frame, mesh, stats) = (self.frame, self.mesh, &mut *self.stats);
        let shade = &mut *self.shade;
        let slots = &self.slots;
        let ids = corners.iter().map(|&index| slots[usize::from(index)]);
        let admission = self.tables.offer_polygon(ids, |outline| {
            shade_front_face(frame, mesh, face, corners, outline, stats, shade)
        })?;
        self.count(face, admission)
    }

    /// Twice the signed area of a quad of vertex-table entries when it is
    /// strictly convex on screen (its four turns, taken at the snapped
    /// corners, all of one sign) and its face has no shared plane; else
    /// `None`. Such a quad is exactly the union of the triangles `0 1 2`
    /// and `0 2 3`, which share the diagonal: the fill rule gives each
    /// sample on it to one of them, so they cover what the quad covers.
    /// (With turns of one sign, four corners cannot cross over or wind
    /// twice; a zero turn, a spike or a straight corner, is left to the
    /// polygon path.)
    fn convex_quad(&self, face: usize, ids: [u16; 4]) -> Option<i64> {
        // The list is sorted by face (and walked past earlier faces).
        let mut later = self.planes.iter().map(|p| p.face as usize);
        if later.find(|&f| f >= face) == Some(face) {
            return None;
        }
        let vertex = |k: usize| self.tables.get_vertex(ids[k]);
        let p = [vertex(0)?, vertex(1)?, vertex(2)?, vertex(3)?];
        // Table vertices lie inside the guard band: differences below
        // 2^23, each product below 2^46, a turn below 2^47.
        let turn = |k: usize| {
            let (a, b, c) = (p[k], p[(k + 1) % 4], p[(k + 2) % 4]);
            cross(b.x - a.x, b.y - a.y, c.x - b.x, c.y - b.y)
        };
        let turns = [turn(0), turn(1), turn(2), turn(3)];
        let convex = turns.iter().all(|&t| t > 0) || turns.iter().all(|&t| t < 0);
        // The fan's two areas have the turns' sign: their sum has no
        // cancellation and stays below 2^48.
        let (a, c) = (p[0], p[2]);
        let area =
            |b: ScreenVertex, d: ScreenVertex| cross(b.x - a.x, b.y - a.y, d.x - a.x, d.y - a.y);
        convex.then(|| area(p[1], c) + area(c, p[3]))
    }

    /// Draws a convex quad ([`Self::convex_quad`]) as its two triangles,
    /// which take the triangle path of the scan (a polygon's costs about
    /// four times as much a row). The face is judged once, as the polygon
    /// path judges it: a back face by the quad's area, and one colour from
    /// the face's shading, asked for when the first triangle is queued.
    fn quad_as_triangles(
        &mut self,
        face: usize,
        corners: &[u16],
        ids: [u16; 4],
        twice_area: i64,
    ) -> Result<(), Error> {
        let front = twice_area < 0;
        if !front && self.frame.cull == Cull::Back {
            self.stats.back_faces += 1;
            return Ok(());
        }
        self.stats.convex_quads += 1;
        // The quad's outline for the shading (a front face, or culling is
        // off). Shaded through `shade_front_face`, so that the shading
        // closure keeps one call site and stays inlined there (with a
        // second one, the firmware's build kept the closure out of line).
        let outline = Outline {
            corners: 4,
            twice_area,
            rect: None,
        };
        let mut color = None;
        for triangle in [[ids[0], ids[1], ids[2]], [ids[0], ids[2], ids[3]]] {
            let (frame, mesh, stats) = (self.frame, self.mesh, &mut *self.stats);
            let shade = &mut *self.shade;
            let admission = self.tables.offer_triangle(triangle, |_| {
                *color.get_or_insert_with(|| {
                    shade_front_face(frame, mesh, face, corners, &outline, stats, shade)
                })
            })?;
            self.count(face, admission)?;
        }
        Ok(())
    }

    /// Whether the triangle of these vertex-table entries runs clockwise
    /// on screen, a back face: the sign `shade_front_face` tests, of the
    /// same exact cross product the tables take (zero area is not a back
    /// face: the tables count it as degenerate).
    #[inline]
    fn faces_away(&self, ids: [u16; 3]) -> bool {
        let vertex = |id: u16| self.tables.get_vertex(id);
        let (Some(a), Some(b), Some(c)) = (vertex(ids[0]), vertex(ids[1]), vertex(ids[2])) else {
            // Not in the table: the tables report it.
            return false;
        };
        // Table vertices lie inside the guard band: differences below
        // 2^23, products below 2^46.
        cross(b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y) > 0
    }

    /// Counts what became of a polygon of `face`; a queued one whose face
    /// shares a plane takes that plane.
    #[inline(always)]
    fn count(&mut self, face: usize, admission: Admission) -> Result<(), Error> {
        if matches!(admission, Admission::Queued(_)) && !self.planes.is_empty() {
            self.share(face)?;
        }
        match admission {
            Admission::Queued(_) => self.stats.queued += 1,
            Admission::OffScreen => self.stats.off_screen += 1,
            Admission::Degenerate => self.stats.degenerate += 1,
            Admission::Declined => {}
        }
        Ok(())
    }

    /// Gives the polygon of `face` just queued the plane its face shares,
    /// if it has one and the plane's three vertices are projected (out of
    /// line: rare). Faces come in order, so the sorted list is walked once
    /// per draw.
    #[inline(never)]
    fn share(&mut self, face: usize) -> Result<(), Error> {
        while let Some((first, rest)) = self.planes.split_first() {
            if first.face as usize >= face {
                break;
            }
            self.planes = rest;
        }
        let plane = match self.planes.first() {
            Some(first) if first.face as usize == face => first.vertices,
            _ => return Ok(()),
        };
        let ids = [
            self.slot(plane[0])?,
            self.slot(plane[1])?,
            self.slot(plane[2])?,
        ];
        if ids.iter().all(|&id| id < NON_FINITE) {
            if self.tables.share_plane(ids)? {
                self.stats.shared_planes += 1;
            }
        } else {
            self.stats.unshared_planes += 1;
        }
        Ok(())
    }

    /// Looks a mesh vertex up in the cache, or transforms and classifies
    /// it. A vertex that can be projected as it is goes into the vertex
    /// table at once, so it is transformed only once per draw even when the
    /// first face that uses it is culled.
    fn classify(&mut self, index: usize) -> Result<Corner, Error> {
        let index = u16::try_from(index).map_err(|_| Error::MeshIndexOutOfRange)?;
        Ok(match self.slot(index)? {
            NEEDS_CLIP => Corner::Clip,
            NON_FINITE => Corner::NonFinite,
            _ => Corner::Stored,
        })
    }

    /// The cache slot of mesh vertex `index`, transforming and classifying
    /// the vertex on its first use: its vertex-table index, `NEEDS_CLIP` or
    /// `NON_FINITE`.
    #[inline]
    fn slot(&mut self, index: u16) -> Result<u16, Error> {
        let index = usize::from(index);
        match self.slots.get(index) {
            Some(&slot) if slot != EMPTY => return Ok(slot),
            _ if index >= self.mesh.vertex_count() => return Err(Error::MeshIndexOutOfRange),
            _ => {}
        }
        let slot = self.transform_vertex(index)?;
        self.slots[index] = slot;
        Ok(slot)
    }

    /// Transforms mesh vertex `index` to clip space and classifies it: a
    /// vertex that can be projected as it is goes into the vertex table at
    /// once (its index is the slot); others need clipping or are not
    /// finite. Once per vertex per draw (the profile's "transform" stage).
    #[inline(never)]
    fn transform_vertex(&mut self, index: usize) -> Result<u16, Error> {
        let tables = &mut *self.tables;
        let mut store = |v| store_vertex(tables, v);
        if let Some(vertex) = self.projected.projected(index) {
            return match vertex {
                ProjectedVertex::Screen(v) => store(v),
                ProjectedVertex::NeedsClip => Ok(NEEDS_CLIP),
                ProjectedVertex::NonFinite => Ok(NON_FINITE),
            };
        }
        let fates = (NEEDS_CLIP, NON_FINITE);
        self.frame
            .vertex(self.mesh, self.positions, index, store, fates)
    }

    /// The slow path for faces that cross the near or far plane or the
    /// guard band: clip in homogeneous space in `f64`. A first pass judges
    /// the clipped polygon (corners, area, bounding box, back face) without
    /// storing anything; only a polygon that will be queued is streamed
    /// into the tables by the second, identical pass. Corners that need no
    /// clipping keep their shared vertex.
    fn clipped_part(&mut self, face: usize, corners: &[u16]) -> Result<(), Error> {
        let frame = self.frame;
        if frame.wholly_outside(self.mesh, corners)? {
            self.stats.outside += 1;
            return Ok(());
        }
        self.stats.clipped += 1;

        // Pass 1: the outline of the clipped polygon.
        let mut outline = OutlineBuilder::default();
        let mut unprojectable = false;
        let tables = &*self.tables;
        let slots = &self.slots[..];
        clip_face(
            frame,
            self.mesh,
            slots,
            corners,
            &mut |v: ClipVertex| -> Result<(), Error> {
                let screen = match v.tag {
                    Some(id) => tables.get_vertex(id),
                    None => frame.project64(v.point),
                };
                match screen {
                    Some(screen) if outline.corners() < MAX_POLYGON_CORNERS => outline.add(screen),
                    _ => unprojectable = true,
                }
                Ok(())
            },
        )?;
        if unprojectable {
            // A concave face can come out with more corners than it went
            // in with. (Within the clipper's range a cut corner lies
            // inside the clip band, far inside the core's guard band, so
            // it always projects.)
            return Err(if outline.corners() == MAX_POLYGON_CORNERS {
                Error::TooManyCorners
            } else {
                Error::OutsideGuardBand
            });
        }
        let outline = outline.finish();
        if outline.corners < 3 {
            self.stats.outside += 1;
            return Ok(());
        }
        if outline.twice_area == 0 {
            self.stats.degenerate += 1;
            return Ok(());
        }
        let (width, height) = (self.tables.frame_width(), self.tables.frame_height());
        if outline
            .rect
            .and_then(|r| r.sample_rows(width, height))
            .is_none()
        {
            self.stats.off_screen += 1;
            return Ok(());
        }
        let (mesh, stats, shade) = (self.mesh, &mut *self.stats, &mut *self.shade);
        let Some(color) = shade_front_face(frame, mesh, face, corners, &outline, stats, shade)
        else {
            return Ok(());
        };

        // Pass 2: the same corners, into the tables.
        self.tables.begin_polygon();
        let tables = &mut *self.tables;
        let slots = &self.slots[..];
        let streamed = clip_face(
            frame,
            self.mesh,
            slots,
            corners,
            &mut |v: ClipVertex| -> Result<(), Error> {
                let id = match v.tag {
                    Some(id) => id,
                    // Projectable: pass 1 projected the same point.
                    None => match frame.project64(v.point) {
                        Some(screen) => tables.add_vertex(screen)?,
                        None => return Err(Error::OutsideGuardBand),
                    },
                };
                tables.add_corner(id)
            },
        );
        if let Err(e) = streamed {
            self.tables.discard_polygon();
            return Err(e);
        }
        let admission = self.tables.finish_polygon(|_| Some(color))?;
        self.count(face, admission)
    }
}

/// Runs a face's corners through the guard-band clipper into `out`.
/// Corners the cache holds as stored vertices go in tagged with their index
/// and known to be inside.
fn clip_face<M: Mesh + ?Sized>(
    frame: &Frame,
    mesh: &M,
    slots: &[u16],
    corners: &[u16],
    out: &mut dyn FnMut(ClipVertex) -> Result<(), Error>,
) -> Result<(), Error> {
    let mut clipper = Clipper::new(frame.guard_planes());
    for &index in corners {
        let index = usize::from(index);
        let tag = match slots[index] {
            NEEDS_CLIP => None,
            id => Some(id),
        };
        let point = frame.clip_position64(mesh, index);
        clipper.push(ClipVertex::corner(point, tag, tag.is_some()), out)?;
    }
    clipper.finish(out)
}

/// The back-face test and the shading of a face the core accepted: its
/// colour, or `None` (counted) for a culled back face. Screen y points
/// down, so a face counter-clockwise as the viewer sees it has negative
/// area. (With the `profile` feature it is kept out of line: the
/// profile's "shade" stage.)
#[cfg_attr(feature = "profile", inline(never))]
fn shade_front_face<C, M: Mesh>(
    frame: &Frame,
    mesh: &M,
    face: usize,
    corners: &[u16],
    outline: &Outline,
    stats: &mut DrawStats,
    shade: &mut impl FnMut(&FaceInfo) -> C,
) -> Option<C> {
    let front = outline.twice_area < 0;
    if !front && frame.cull == Cull::Back {
        stats.back_faces += 1;
        return None;
    }
    Some(shade(&frame.face_info(mesh, face, corners, front)))
}
