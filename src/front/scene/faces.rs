//! Face offering, the draw loop: for each face of a mesh, the back-face
//! and frustum decisions, the split of a non-planar face and of a convex
//! quad, the clipped path's two passes, the shading, and the offer to the
//! tables, counted in [`DrawStats`]; [`draw_mesh`] and
//! [`draw_mesh_projected`] run it.

use core::fmt;

use crate::arith::wide::cross;
use crate::error::Error;
use crate::front::backface::{EyeTest, Side};
use crate::front::clip::ClipValue;
#[cfg(feature = "clipping")]
use crate::front::clip::ClipVertex;
#[cfg(feature = "std")]
use crate::front::face_plane::{FacePlane, PlaneEye};
use crate::front::geometry::Mat4;
use crate::front::mesh::{Mesh, SharedPlane};
use crate::front::scene::cache::{CacheStorage, EMPTY, NEEDS_CLIP, NON_FINITE};
use crate::front::scene::camera::Camera;
#[cfg(feature = "clipping")]
use crate::front::scene::clipping::clip_face;
use crate::front::scene::cull::Cull;
use crate::front::scene::face_info::{FaceInfo, FacePart};
use crate::front::scene::transform::{Frame, ProjectedVertex, TransformEach, VertexSource};
use crate::front::scene::vertex_info::VertexInfo;
use crate::limits::MAX_FACE_CORNERS;
#[cfg(feature = "clipping")]
use crate::limits::MAX_POLYGON_CORNERS;
#[cfg(feature = "clipping")]
use crate::raster::vertex::OutlineBuilder;
use crate::raster::vertex::{Outline, ScreenRect, ScreenVertex};
use crate::raster::{Admission, PolygonTables};

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

/// What a draw stores beside each vertex it adds to the vertex table: a
/// painted renderer's vertex values ([`crate::paint`]), or nothing
/// ([`NoValues`], flat shading, whose draw runs none of this).
pub(crate) trait VertexValues {
    /// The value a mesh vertex gets before projection, carried through
    /// clipping.
    type Source: ClipValue;
    /// Whether anything is stored.
    const STORES: bool;
    /// The value of a mesh vertex, and where the value of a vertex-table
    /// entry is stored: apart, so that a clipped face can ask for its
    /// corners' values while it stores those of the corners cuts make.
    #[allow(clippy::type_complexity)] // two closures, named where they are used
    fn split(
        &mut self,
    ) -> (
        impl Fn(&VertexInfo<'_>) -> Self::Source + '_,
        impl FnMut(u16, Self::Source) -> Result<(), Error> + '_,
    );
}

impl<T: VertexValues> VertexValues for &mut T {
    type Source = T::Source;
    const STORES: bool = T::STORES;
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn split(
        &mut self,
    ) -> (
        impl Fn(&VertexInfo<'_>) -> Self::Source + '_,
        impl FnMut(u16, Self::Source) -> Result<(), Error> + '_,
    ) {
        (**self).split()
    }
}

/// Nothing stored beside the vertices: flat shading.
pub(crate) struct NoValues;

impl VertexValues for NoValues {
    type Source = ();
    const STORES: bool = false;
    #[inline(always)]
    fn split(
        &mut self,
    ) -> (
        impl Fn(&VertexInfo<'_>) + '_,
        impl FnMut(u16, ()) -> Result<(), Error> + '_,
    ) {
        (|_: &VertexInfo<'_>| (), |_: u16, (): ()| Ok(()))
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
///
/// [`CLIP_RANGE`]: crate::CLIP_RANGE
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
        (shade, NoValues),
        None,
    )
}

/// [`draw_mesh`] storing each vertex's value in `values` as it enters the
/// vertex table (a painted renderer's draw); faces get colour 0.
pub(crate) fn draw_mesh_with_values<T, M, K, V>(
    tables: &mut T,
    cache: &mut K,
    mesh: &M,
    (model, camera, cull): (&Mat4, &Camera, Cull),
    values: &mut V,
) -> Result<DrawStats, DrawError>
where
    T: PolygonTables<u16> + ?Sized,
    M: Mesh,
    K: CacheStorage,
    V: VertexValues,
{
    let Some(slots) = cache.slots_mut().get_mut(..mesh.vertex_count()) else {
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
        (|_: &FaceInfo| 0u16, values),
        None,
    )
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
///
/// [`project_vertices`]: crate::project_vertices
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
        (shade, NoValues),
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
fn draw_faces<C, T, M, P, V>(
    tables: &mut T,
    slots: &mut [u16],
    mesh: &M,
    projected: P,
    (model, camera, cull): (&Mat4, &Camera, Cull),
    (mut shade, values): (impl FnMut(&FaceInfo) -> C, V),
    faces: Option<&[u32]>,
) -> Result<DrawStats, DrawError>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh,
    P: VertexSource,
    V: VertexValues,
{
    let quantized = mesh.quantized();
    // A closed mesh seen from outside shows no back face: `Cull::None`
    // culls them (the same samples covered; see `ClosedHull`). Decided
    // before the frame is made, so that a draw with `Cull::Back` builds
    // the very frame it did before.
    let hull_culls = match (cull, mesh.closed_hull()) {
        (Cull::None, Some(hull)) => hull.hides_back_faces(&mvp_of(model, camera)),
        _ => false,
    };
    let cull = if hull_culls { Cull::Back } else { cull };
    let mut frame = Frame::new(model, camera, cull, quantized.as_ref());
    // A mesh closed by caps over its holes: where a cap faces the viewer
    // a hole may show the inside, and back faces there are drawn.
    if hull_culls {
        let kept = match cap_window(&frame, mesh) {
            Some(window) => frame.keep_window(window, mesh.hull_caps()),
            None => false,
        };
        if !kept {
            frame.cull = Cull::None;
        }
    }
    let mut stats = DrawStats {
        faces: mesh.face_count() as u32,
        ..DrawStats::default()
    };
    let positions = quantized
        .filter(|_| frame.fixed.is_some())
        .map(|q| q.positions);
    // The model-space back-face test, for the integer front end.
    let eye = match (&frame.fixed, positions) {
        (Some(fixed), Some(_)) if frame.cull == Cull::Back => EyeTest::new(fixed),
        _ => None,
    };
    // The model-space back-face test for the `f32` front end, from the
    // mesh's face planes (host builds; a window of caps facing the viewer
    // needs each back face's screen rectangle).
    #[cfg(feature = "std")]
    let plane_eye = match mesh.face_planes() {
        [] => None,
        _ if frame.cull != Cull::Back || frame.fixed.is_some() || frame.has_window() => None,
        _ => PlaneEye::new(frame.mvp()),
    };
    let mut draw = Draw {
        tables,
        slots,
        mesh,
        projected,
        positions,
        eye,
        #[cfg(feature = "std")]
        plane_eye,
        #[cfg(feature = "std")]
        face_planes: mesh.face_planes(),
        exact_normals: quantized.map_or(&[][..], |q| q.exact_normals),
        frame: &frame,
        stats: &mut stats,
        shade: &mut shade,
        planes: mesh.shared_planes(),
        drawing: FacePart::Whole,
        values,
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

/// The state of one [`draw_mesh`].
struct Draw<'a, T: ?Sized, M: ?Sized, S, P, V> {
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
    /// The eye for the model-space back-face test of the `f32` front end
    /// ([`PlaneEye`]: back faces culled, the mesh's face planes known).
    #[cfg(feature = "std")]
    plane_eye: Option<PlaneEye>,
    /// The mesh's face planes ([`Mesh::face_planes`]).
    #[cfg(feature = "std")]
    face_planes: &'a [FacePlane],
    frame: &'a Frame,
    stats: &'a mut DrawStats,
    shade: &'a mut S,
    /// The mesh's shared planes not yet reached (sorted by face).
    planes: &'a [SharedPlane],
    /// Which part of the face being drawn the polygon in hand is: all of
    /// it, or a triangle of its fan (a face that is not planar; set back to
    /// `Whole` after the fan, and an error ends the draw).
    drawing: FacePart,
    /// Where each vertex's value goes (nothing for flat shading).
    values: V,
}

impl<C, T, M, S, P, V> Draw<'_, T, M, S, P, V>
where
    C: Copy,
    T: PolygonTables<C> + ?Sized,
    M: Mesh,
    S: FnMut(&FaceInfo) -> C,
    P: VertexSource,
    V: VertexValues,
{
    fn face(&mut self, face: usize) -> Result<(), Error> {
        let corners = self.mesh.face(face);
        if self.mesh.triangles_only() && corners.len() != 3 {
            // (`Triangles::new` checked; a mesh of triangles draws none.)
            return Err(Error::NotATriangle);
        }
        if corners.len() > MAX_FACE_CORNERS {
            return Err(Error::TooManyCorners);
        }
        if corners.len() < 3 {
            if corners.is_empty() {
                // Out-of-range face starts (a mesh that was never checked,
                // e.g. a `HostMesh` built field by field): a valid mesh
                // has at least three corners a face.
                return Err(Error::MeshIndexOutOfRange);
            }
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
        #[cfg(feature = "std")]
        if let (Some(eye), Some(plane), 3) =
            (&self.plane_eye, self.face_planes.get(face), corners.len())
        {
            side = eye.side(plane);
            if side == Side::Back {
                // The same for a mesh the `f32` front end draws.
                self.stats.back_faces += 1;
                return Ok(());
            }
        }
        if !self.mesh.triangles_only() && corners.len() > 3 && !self.planar(face, corners)? {
            self.stats.split += 1;
            for k in 1..corners.len() - 1 {
                // (`k` is below `MAX_FACE_CORNERS`, checked above.)
                self.drawing = FacePart::Fan(k as u16);
                self.part(
                    face,
                    &[corners[0], corners[k], corners[k + 1]],
                    Side::Unsure,
                )?;
            }
            self.drawing = FacePart::Whole;
            Ok(())
        } else {
            self.part(face, corners, side)
        }
    }

    /// Whether face `face` (of more than three corners) is planar; an
    /// error when a corner lies beyond the mesh's vertices (a mesh whose
    /// arrays were never checked), before the test reads its position.
    /// Out of line: faces of triangles never come here.
    #[inline(never)]
    fn planar(&self, face: usize, corners: &[u16]) -> Result<bool, Error> {
        let count = self.mesh.vertex_count();
        if corners.iter().any(|&i| usize::from(i) >= count) {
            return Err(Error::MeshIndexOutOfRange);
        }
        Ok(self.mesh.face_is_planar(face))
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
                if self.frame.cull == Cull::Back
                    && side != Side::Front
                    && self.faces_away(ids)
                    && self.may_cull(ids)
                {
                    // Culled before the tables' frame and sample tests, and
                    // their call into the shading closure.
                    self.stats.back_faces += 1;
                    return Ok(());
                }
                let part = self.drawing;
                let (frame, mesh, stats) = (self.frame, self.mesh, &mut *self.stats);
                let shade = &mut *self.shade;
                let admission = self.tables.offer_triangle(ids, |outline| {
                    shade_front_face(frame, mesh, (face, part), corners, outline, stats, shade)
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
            #[cfg(feature = "clipping")]
            return self.clipped_part(face, corners);
            #[cfg(not(feature = "clipping"))]
            return Err(Error::NeedsClipping);
        }
        // Every corner is in the vertex table: a triangle took the fast
        // path above, so this is a face of more corners, which a mesh of
        // triangles never has (and whose code it leaves out).
        if self.mesh.triangles_only() {
            return Err(Error::NotATriangle);
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
        let part = self.drawing;
        let (frame, mesh, stats) = (self.frame, self.mesh, &mut *self.stats);
        let shade = &mut *self.shade;
        let slots = &self.slots;
        let ids = corners.iter().map(|&index| slots[usize::from(index)]);
        let admission = self.tables.offer_polygon(ids, |outline| {
            shade_front_face(frame, mesh, (face, part), corners, outline, stats, shade)
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
        if !front && self.frame.cull == Cull::Back && !self.frame.has_window() {
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
                    let whole = (face, FacePart::Whole);
                    shade_front_face(frame, mesh, whole, corners, &outline, stats, shade)
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

    /// Whether a back face of these vertex-table entries may be culled:
    /// always, but where a cap of the mesh's hull faces the viewer
    /// ([`Frame::cap_window`]).
    #[inline(always)]
    fn may_cull(&self, ids: [u16; 3]) -> bool {
        !self.frame.has_window() || self.may_cull_near_caps(ids)
    }

    /// [`Self::may_cull`] with a window, out of line.
    #[inline(never)]
    fn may_cull_near_caps(&self, ids: [u16; 3]) -> bool {
        let [a, b, c] = ids.map(|id| self.tables.get_vertex(id));
        // The triangle's rectangle in line (through `ScreenRect::of`'s
        // iterator it was a call of its own: 4 % of the teapot's frame
        // unculled at 240x240).
        let rect = match (a, b, c) {
            (Some(a), Some(b), Some(c)) => Some(ScreenRect {
                x0: a.x.min(b.x).min(c.x),
                x1: a.x.max(b.x).max(c.x),
                y0: a.y.min(b.y).min(c.y),
                y1: a.y.max(b.y).max(c.y),
            }),
            _ => ScreenRect::of([a, b, c].into_iter().flatten()),
        };
        self.frame.may_cull_within(rect)
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
        if !V::STORES {
            return self
                .frame
                .vertex(self.mesh, self.positions, index, store, fates);
        }
        let slot = self
            .frame
            .vertex(self.mesh, self.positions, index, store, fates)?;
        if slot < NON_FINITE {
            let info = VertexInfo::of_mesh(self.mesh, self.frame, index);
            let (source, mut store) = self.values.split();
            store(slot, source(&info))?;
        }
        Ok(slot)
    }

    /// The slow path for faces that cross the near or far plane or the
    /// guard band: clip in homogeneous space in `f64`. A first pass judges
    /// the clipped polygon (corners, area, bounding box, back face) without
    /// storing anything; only a polygon that will be queued is streamed
    /// into the tables by the second, identical pass. Corners that need no
    /// clipping keep their shared vertex. Out of line: rare, and its
    /// clipper's state stays off the common path's stack.
    #[cfg(feature = "clipping")]
    #[inline(never)]
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
            |_| (),
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
        let part = (face, self.drawing);
        let (mesh, stats, shade) = (self.mesh, &mut *self.stats, &mut *self.shade);
        let Some(color) = shade_front_face(frame, mesh, part, corners, &outline, stats, shade)
        else {
            return Ok(());
        };

        // Pass 2: the same corners, into the tables.
        self.tables.begin_polygon();
        let (tables, mesh) = (&mut *self.tables, self.mesh);
        let (source, mut store) = self.values.split();
        let slots = &self.slots[..];
        let streamed = clip_face(
            frame,
            mesh,
            slots,
            corners,
            |index| source(&VertexInfo::of_mesh(mesh, frame, index)),
            &mut |v: ClipVertex<V::Source>| -> Result<(), Error> {
                let id = match v.tag {
                    Some(id) => id,
                    // Projectable: pass 1 projected the same point.
                    None => match frame.project64(v.point) {
                        Some(screen) => {
                            let id = tables.add_vertex(screen)?;
                            store(id, v.value)?;
                            id
                        }
                        None => return Err(Error::OutsideGuardBand),
                    },
                };
                tables.add_corner(id)
            },
        );
        drop((source, store));
        if let Err(e) = streamed {
            self.tables.discard_polygon();
            return Err(e);
        }
        let admission = self.tables.finish_polygon(|_| Some(color))?;
        self.count(face, admission)
    }
}

/// Where the holes of `mesh`'s hull may show in `frame`
/// ([`Frame::cap_window`]; nowhere for a closed mesh). Out of line: rare,
/// and a closed mesh's draw keeps its code.
#[inline(never)]
fn cap_window<M: Mesh>(frame: &Frame, mesh: &M) -> Option<Option<ScreenRect>> {
    match mesh.hull_caps() {
        [] => Some(None),
        caps => frame.cap_window(caps, frame.fixed.is_some()),
    }
}

/// Projection · view · model, as the frame makes it.
fn mvp_of(model: &Mat4, camera: &Camera) -> Mat4 {
    camera.projection.mul(&camera.view.mul(model))
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
    face: (usize, FacePart),
    corners: &[u16],
    outline: &Outline,
    stats: &mut DrawStats,
    shade: &mut impl FnMut(&FaceInfo) -> C,
) -> Option<C> {
    let front = outline.twice_area < 0;
    if !front && frame.cull == Cull::Back && frame.may_cull_within(outline.rect) {
        stats.back_faces += 1;
        return None;
    }
    Some(shade(&frame.face_info(mesh, face, corners, front)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::mesh::StaticMesh;
    use crate::front::scene::VertexCache;
    use crate::{Depth16, Renderer, ScanArrays, TableArrays};

    /// A triangle with a corner behind the eye is clipped. (Without the
    /// `clipping` feature it is refused with [`Error::NeedsClipping`]:
    /// `tools/minimal` checks that build, which this workspace's tests
    /// cannot make, its lab enabling the feature.)
    #[test]
    fn a_face_behind_the_eye_is_clipped() {
        let corners = [[-1.0, -1.0, -5.0], [1.0, -1.0, -5.0], [0.0, 1.0, 5.0]];
        let mesh = StaticMesh::new(&corners, &[0, 1, 2], &[0]).unwrap();
        let camera = Camera::perspective(Mat4::IDENTITY, 60.0, 32, 32, 0.5, 100.0);
        let mut renderer: Renderer<
            TableArrays<u8, 8, 4, 16>,
            ScanArrays<u8, Depth16, 32, 4, 8>,
            VertexCache<3>,
        > = Renderer::new(32, 32, 0).unwrap();
        let drawn = renderer.draw_mesh(&mesh, &Mat4::IDENTITY, &camera, Cull::None, |_| 1);
        assert_eq!(drawn.map(|stats| stats.clipped), Ok(1));
    }
}
