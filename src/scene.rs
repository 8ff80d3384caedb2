//! World to screen: transforms a mesh, culls and clips its faces, projects
//! them, shades them and offers them to the renderer's tables. Only faces
//! that can be visible enter the tables, and only the vertices they use.
//!
//! For each face, in order:
//! 1. **Transform** each corner to clip space (`projection · view · model`),
//!    once per vertex per frame. A [`VertexCache`] remembers where each mesh
//!    vertex went in the vertex table.
//! 2. **Non-finite** corners (NaN or infinity after transformation): the face
//!    is skipped and counted in [`DrawStats::non_finite`].
//! 3. **Frustum**: a face whose corners all lie outside one frustum plane is
//!    culled ([`DrawStats::outside`]).
//! 4. **Clipping**: a face with a corner behind the near plane, beyond the
//!    far plane, or outside the guard band ([`GUARD_BAND_PX`] pixels
//!    around the frame) is clipped in homogeneous space
//!    ([`crate::clip`]): cut, never dropped or turned inside out.
//! 5. **Back faces** (with [`Cull::Back`]): faces whose projected corners
//!    run clockwise as seen by the viewer are culled. The test is exact, on
//!    the sub-pixel grid the core uses.
//! 6. **Extremum test**: a face whose screen bounding box misses the frame is
//!    culled. The core then leaves out faces that cover no pixel sample.
//! 7. **Shading**: the face's colour comes from a closure over [`FaceInfo`],
//!    for example [`Shading::color`](crate::shade::Shading::color).
//!
//! A face that is not planar ([`crate::mesh::is_planar`]) has no single plane. It goes
//! through these steps as the fan of triangles from its first corner, each
//! with the face's id.
//!
//! Depth handed to the core is `z_ndc` mapped to `[0, 1]`. It is affine in
//! screen space, so the core's plane stepping is exact.

use heapless::Vec;

use crate::clip::{self, FRUSTUM};
use crate::error::Error;
use crate::fixed::SUBPIXEL_STEPS;
use crate::geometry::{Mat4, Vec3, Vec4, radians};
use crate::mesh::Mesh;
use crate::scanline::{Admission, PolygonTables, twice_area};
use crate::vertex::ScreenVertex;

/// Most corners a mesh face may have.
pub const MAX_FACE_CORNERS: usize = 26;
/// Most corners after clipping (a face gains at most one per plane).
pub const MAX_CLIPPED_CORNERS: usize = MAX_FACE_CORNERS + 6;
/// Half-width of the band around the frame, in pixels, inside which
/// vertices are projected as they are. Faces reaching beyond it are clipped
/// to it. It is half the core's guard band, so rounding can never push a
/// vertex out of the core's range.
pub const GUARD_BAND_PX: f32 = 4096.0;

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
pub fn reference_model<M: Mesh + ?Sized>(mesh: &M, yaw_deg: f32, pitch_deg: f32) -> Mat4 {
    let (centre, radius) = bounding_sphere(mesh);
    reference_model_around(centre, radius, yaw_deg, pitch_deg)
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

/// Centre of the axis-aligned bounding box of all vertices, and the largest
/// distance from it to a vertex.
pub fn bounding_sphere<M: Mesh + ?Sized>(mesh: &M) -> (Vec3, f32) {
    let count = mesh.vertex_count();
    if count == 0 {
        return (Vec3::default(), 0.0);
    }
    let mut lo = Vec3::from_array(mesh.position(0));
    let mut hi = lo;
    for i in 1..count {
        let p = Vec3::from_array(mesh.position(i));
        lo = Vec3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
        hi = Vec3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
    }
    let centre = (lo + hi) * 0.5;
    let radius2 = (0..count)
        .map(|i| {
            let d = Vec3::from_array(mesh.position(i)) - centre;
            d.dot(d)
        })
        .fold(0.0f32, f32::max);
    (centre, libm::sqrtf(radius2))
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

/// What a shading closure knows about a face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceInfo {
    /// Index of the face in the mesh.
    pub face: u32,
    /// Unit normal from the face's winding (Newell), in view space.
    pub normal: Vec3,
    /// Whether the face's front (counter-clockwise side) faces the viewer.
    pub front: bool,
    /// View-space distance of the face's centroid along the view axis.
    pub view_depth: f32,
}

/// Counts of what happened to a mesh's faces in one draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DrawStats {
    /// Faces in the mesh.
    pub faces: u32,
    /// Faces that entered the polygon table.
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
    /// ([`is_planar`](crate::mesh::is_planar)).
    pub split: u32,
}

/// Where each mesh vertex went in the vertex table this frame: 2 bytes per
/// mesh vertex, for meshes of up to `VM` vertices.
#[derive(Debug, Clone)]
pub struct VertexCache<const VM: usize> {
    slots: [u16; VM],
}

/// Not yet transformed this frame.
const EMPTY: u16 = u16::MAX;
/// Transformed, and it needs clipping: never projected as it is.
const NEEDS_CLIP: u16 = u16::MAX - 1;

impl<const VM: usize> VertexCache<VM> {
    /// An empty cache.
    pub const fn new() -> Self {
        Self { slots: [EMPTY; VM] }
    }

    /// Forgets every vertex: call once per frame (with the renderer's
    /// `clear`).
    pub fn clear(&mut self) {
        self.slots.fill(EMPTY);
    }
}

impl<const VM: usize> Default for VertexCache<VM> {
    fn default() -> Self {
        Self::new()
    }
}

/// A polygon to draw for a face: the face itself, or one triangle of its
/// fan.
#[derive(Debug, Clone, Copy)]
struct FacePart<'a> {
    /// Index of the face in the mesh.
    face: usize,
    /// Its corners, as mesh vertex indices.
    corners: &'a [u16],
}

/// One corner of the face being processed.
#[derive(Debug, Clone, Copy)]
enum Corner {
    /// In the vertex table.
    Stored(u16, ScreenVertex),
    /// Needs clipping.
    Clip,
}

/// Per-draw constants.
struct Frame {
    mvp: Mat4,
    model_view: Mat4,
    width: f32,
    height: f32,
    guard: [Vec4; 6],
    cull: Cull,
}

impl Frame {
    fn new(model: &Mat4, camera: &Camera, cull: Cull) -> Self {
        let model_view = camera.view.mul(model);
        let (width, height) = (f32::from(camera.width), f32::from(camera.height));
        Self {
            mvp: camera.projection.mul(&model_view),
            model_view,
            width,
            height,
            guard: clip::guard_planes(
                2.0 * GUARD_BAND_PX / width - 1.0,
                2.0 * GUARD_BAND_PX / height - 1.0,
            ),
            cull,
        }
    }

    /// Whether a clip-space point lies inside the near, far and guard-band
    /// planes (the same planes as `guard`, compared directly).
    fn inside_guard(&self, p: Vec4) -> bool {
        let (gx, gy) = (self.guard[0].w, self.guard[2].w);
        p.z >= -p.w && p.z <= p.w && p.x.abs() <= gx * p.w && p.y.abs() <= gy * p.w
    }

    /// Clip-space position, or `None` when not finite.
    fn clip_position<M: Mesh + ?Sized>(&self, mesh: &M, index: usize) -> Option<Vec4> {
        let p = self
            .mvp
            .transform_point(Vec3::from_array(mesh.position(index)));
        p.is_finite().then_some(p)
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

    /// The back-face and extremum tests on a projected polygon: `Some(front)`
    /// when it is kept (whether its front faces the viewer), `None` when it
    /// is culled, counted in `stats`. Screen y points down, so a
    /// counter-clockwise face (seen by the viewer) has negative area.
    fn keep(&self, corners: &[ScreenVertex], stats: &mut DrawStats) -> Option<bool> {
        let front = twice_area(corners) < 0;
        if !front && self.cull == Cull::Back {
            stats.back_faces += 1;
            None
        } else if self.misses_frame(corners) {
            stats.off_screen += 1;
            None
        } else {
            Some(front)
        }
    }

    /// Whether the screen bounding box of the corners misses the frame.
    fn misses_frame(&self, corners: &[ScreenVertex]) -> bool {
        let (w, h) = (
            self.width as i32 * SUBPIXEL_STEPS,
            self.height as i32 * SUBPIXEL_STEPS,
        );
        let (mut x0, mut x1, mut y0, mut y1) = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
        for c in corners {
            (x0, x1, y0, y1) = (x0.min(c.x), x1.max(c.x), y0.min(c.y), y1.max(c.y));
        }
        x1 < 0 || y1 < 0 || x0 >= w || y0 >= h
    }

    /// Normal (model space, turned into view space) and the view distance
    /// of the face's centroid. A triangle's normal is one cross product;
    /// larger faces use Newell's sum.
    fn face_info<M: Mesh + ?Sized>(&self, mesh: &M, part: FacePart<'_>, front: bool) -> FaceInfo {
        let corners = part.corners;
        let position =
            |k: usize| Vec3::from_array(mesh.position(usize::from(corners[k % corners.len()])));
        let origin = position(0);
        let (mut n, mut sum) = (Vec3::default(), origin);
        for k in 1..corners.len().saturating_sub(1) {
            let (p, q) = (position(k) - origin, position(k + 1) - origin);
            n = n + p.cross(q);
            sum = sum + position(k);
        }
        if corners.len() > 1 {
            sum = sum + position(corners.len() - 1);
        }
        let centroid = sum * (1.0 / corners.len().max(1) as f32);
        // Only the view-space z of the centroid is needed.
        let row = self.model_view.m[2];
        let view_z = row[0] * centroid.x + row[1] * centroid.y + row[2] * centroid.z + row[3];
        FaceInfo {
            face: part.face as u32,
            normal: self.model_view.transform_vector(n).normalized(),
            front,
            view_depth: -view_z,
        }
    }
}

/// Draws `mesh` with the `model` matrix through `camera` into `tables`:
/// culls, clips, projects and shades every face, and offers the survivors
/// to the polygon table. Call the renderer's `render` afterwards.
///
/// `cache` must hold at least `mesh.vertex_count()` entries and must be
/// cleared together with the renderer's tables. On `Err` (a table is full,
/// or the mesh is malformed) the faces before the failing one stay in the
/// tables.
pub fn draw_mesh<C, T, M, const VM: usize>(
    tables: &mut T,
    cache: &mut VertexCache<VM>,
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    cull: Cull,
    mut shade: impl FnMut(&FaceInfo) -> C,
) -> Result<DrawStats, Error>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh + ?Sized,
{
    if mesh.vertex_count() > VM {
        return Err(Error::MeshIndexOutOfRange);
    }
    let frame = Frame::new(model, camera, cull);
    let mut stats = DrawStats {
        faces: mesh.face_count() as u32,
        ..DrawStats::default()
    };
    for face in 0..mesh.face_count() {
        let corners = mesh.face(face);
        if corners.len() > 3 && !mesh.face_is_planar(face) {
            stats.split += 1;
            for k in 1..corners.len() - 1 {
                let triangle = [corners[0], corners[k], corners[k + 1]];
                let part = FacePart {
                    face,
                    corners: &triangle,
                };
                draw_face(tables, cache, mesh, &frame, part, &mut stats, &mut shade)?;
            }
        } else {
            let part = FacePart { face, corners };
            draw_face(tables, cache, mesh, &frame, part, &mut stats, &mut shade)?;
        }
    }
    Ok(stats)
}

fn draw_face<C: Copy, T: PolygonTables<C> + ?Sized, M: Mesh + ?Sized, const VM: usize>(
    tables: &mut T,
    cache: &mut VertexCache<VM>,
    mesh: &M,
    frame: &Frame,
    part: FacePart<'_>,
    stats: &mut DrawStats,
    shade: &mut impl FnMut(&FaceInfo) -> C,
) -> Result<(), Error> {
    let indices = part.corners;
    if indices.len() > MAX_FACE_CORNERS {
        return Err(Error::TooManyCorners);
    }
    if indices.len() < 3 {
        stats.degenerate += 1;
        return Ok(());
    }
    let mut corners: Vec<Corner, MAX_FACE_CORNERS> = Vec::new();
    for &index in indices {
        let index = usize::from(index);
        if index >= mesh.vertex_count() {
            return Err(Error::MeshIndexOutOfRange);
        }
        let Some(corner) = classify(tables, cache, mesh, frame, index)? else {
            stats.non_finite += 1;
            return Ok(());
        };
        corners.push(corner).map_err(|_| Error::TooManyCorners)?;
    }
    if corners.iter().any(|c| matches!(c, Corner::Clip)) {
        return draw_clipped(tables, mesh, frame, part, stats, shade);
    }
    let (mut screen, mut ids): (
        Vec<ScreenVertex, MAX_FACE_CORNERS>,
        Vec<u16, MAX_FACE_CORNERS>,
    ) = (Vec::new(), Vec::new());
    for corner in &corners {
        if let Corner::Stored(id, v) = *corner {
            screen.push(v).map_err(|_| Error::TooManyCorners)?;
            ids.push(id).map_err(|_| Error::TooManyCorners)?;
        }
    }
    let Some(front) = frame.keep(&screen, stats) else {
        return Ok(());
    };
    let color = shade(&frame.face_info(mesh, part, front));
    count(stats, tables.add_polygon(&ids, color)?);
    Ok(())
}

/// Looks a mesh vertex up in the cache, or transforms and classifies it.
/// A vertex that can be projected as it is goes into the vertex table at
/// once, so it is transformed only once per frame even when the first face
/// that uses it is culled. `Ok(None)` when its position is not finite.
fn classify<C, T: PolygonTables<C> + ?Sized, M: Mesh + ?Sized, const VM: usize>(
    tables: &mut T,
    cache: &mut VertexCache<VM>,
    mesh: &M,
    frame: &Frame,
    index: usize,
) -> Result<Option<Corner>, Error> {
    Ok(match cache.slots[index] {
        NEEDS_CLIP => Some(Corner::Clip),
        EMPTY => {
            let Some(p) = frame.clip_position(mesh, index) else {
                return Ok(None);
            };
            if !frame.inside_guard(p) {
                cache.slots[index] = NEEDS_CLIP;
                Some(Corner::Clip)
            } else if let Some(v) = frame.project(p) {
                Some(Corner::Stored(store(tables, cache, index, v)?, v))
            } else {
                None
            }
        }
        id => tables.get_vertex(id).map(|v| Corner::Stored(id, v)),
    })
}

/// Stores a projected mesh vertex and remembers its id.
fn store<C, T: PolygonTables<C> + ?Sized, const VM: usize>(
    tables: &mut T,
    cache: &mut VertexCache<VM>,
    index: usize,
    vertex: ScreenVertex,
) -> Result<u16, Error> {
    if let Some(&id) = cache
        .slots
        .get(index)
        .filter(|&&s| s != EMPTY && s != NEEDS_CLIP)
    {
        return Ok(id);
    }
    let id = tables.add_vertex(vertex)?;
    if id >= NEEDS_CLIP {
        return Err(Error::VertexTableFull);
    }
    cache.slots[index] = id;
    Ok(id)
}

/// The slow path for faces that cross the near or far plane or the guard
/// band: clip in homogeneous space, then project the new polygon. Its
/// vertices are not shared with other faces.
fn draw_clipped<C: Copy, T: PolygonTables<C> + ?Sized, M: Mesh + ?Sized>(
    tables: &mut T,
    mesh: &M,
    frame: &Frame,
    part: FacePart<'_>,
    stats: &mut DrawStats,
    shade: &mut impl FnMut(&FaceInfo) -> C,
) -> Result<(), Error> {
    let mut points: Vec<Vec4, MAX_FACE_CORNERS> = Vec::new();
    for &index in part.corners {
        let Some(p) = frame.clip_position(mesh, usize::from(index)) else {
            stats.non_finite += 1;
            return Ok(());
        };
        points.push(p).map_err(|_| Error::TooManyCorners)?;
    }
    if clip::outside_one_plane(&points, &FRUSTUM) {
        stats.outside += 1;
        return Ok(());
    }
    stats.clipped += 1;
    let clipped = clip::clip_polygon::<MAX_CLIPPED_CORNERS>(&points, &frame.guard)
        .map_err(|_| Error::TooManyCorners)?;
    let mut screen: Vec<ScreenVertex, MAX_CLIPPED_CORNERS> = Vec::new();
    for &p in &clipped {
        match frame.project(p) {
            Some(v) => screen.push(v).map_err(|_| Error::TooManyCorners)?,
            None => {
                stats.non_finite += 1;
                return Ok(());
            }
        }
    }
    if screen.len() < 3 {
        stats.outside += 1;
        return Ok(());
    }
    let Some(front) = frame.keep(&screen, stats) else {
        return Ok(());
    };
    let mut ids: Vec<u16, MAX_CLIPPED_CORNERS> = Vec::new();
    for v in &screen {
        ids.push(tables.add_vertex(*v)?)
            .map_err(|_| Error::TooManyCorners)?;
    }
    let color = shade(&frame.face_info(mesh, part, front));
    count(stats, tables.add_polygon(&ids, color)?);
    Ok(())
}

fn count(stats: &mut DrawStats, admission: Admission) {
    match admission {
        Admission::Queued(_) => stats.queued += 1,
        Admission::OffScreen => stats.off_screen += 1,
        Admission::Degenerate => stats.degenerate += 1,
    }
}
