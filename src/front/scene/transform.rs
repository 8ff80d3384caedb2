//! Matrices applied to vertices: a draw's constants ([`Frame`]: the
//! product of the model, view and projection, the clipping band, the
//! integer front end when it takes the mesh), each mesh vertex to clip
//! space and onto the screen in `f32` or in integers, the `f64` transform
//! that clipping starts from, and [`project_vertices`], the same step on
//! its own.

#[cfg(feature = "clipping")]
use core::cell::OnceCell;

use crate::arith::wide::cross;
use crate::error::Error;
#[cfg(feature = "clipping")]
use crate::front::clip::ClipPoint;
use crate::front::clip_w::ClipW;
use crate::front::fixed_point::FixedFrame;
use crate::front::geometry::{Mat4, Vec3, Vec4};
use crate::front::mesh::{Mesh, QuantizedView};
use crate::front::scene::camera::Camera;
#[cfg(feature = "std")]
use crate::front::scene::cap_cover::CapCover;
use crate::front::scene::cull::Cull;
use crate::limits::{CLIP_BAND_PX, DEPTH_MAX, DEPTH_ONE, GUARD_BAND, SUBPIXEL_STEPS};
use crate::raster::vertex::{ScreenRect, ScreenVertex};

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

#[cfg(feature = "clipping")]
/// The `f64` state of a frame for faces that need clipping.
#[derive(Debug, Clone, Copy)]
pub(super) struct Clip64 {
    /// `projection · view · model`.
    mvp: [[f64; 4]; 4],
    /// `|projection| · |view| · |model|` (entrywise absolute values): a
    /// corner's transform terms, whose sum bounds the arithmetic's error.
    pub(super) mvp_abs: [[f64; 4]; 4],
    /// The smallest clip-space `w` in the view frustum (with the guard
    /// band): below it no cut corner can lie.
    pub(super) w_near: f64,
}

#[cfg(feature = "clipping")]
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

#[cfg(feature = "clipping")]
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

/// How far from 1 the squared length of a vector may be for
/// [`Frame::view_normal`] to take it as unit: a unit `f32` vector from
/// [`unit`] is within a few units of `2^-24`.
const UNIT_TOLERANCE: f32 = 1.0 / (1 << 16) as f32;

/// One over the scale of the upper 3x3 of `m`, when that 3x3 is a
/// rotation (or reflection) times one scale: its columns of equal length
/// and at right angles to within `2^-16` of their squared length, and the
/// columns divided by the scale finite. `None` otherwise (a shear, a
/// non-uniform scale, a singular or non-finite matrix).
fn similarity_inverse_scale(m: &Mat4) -> Option<f32> {
    let column = |j: usize| Vec3::new(m.m[0][j], m.m[1][j], m.m[2][j]);
    let [c0, c1, c2] = [column(0), column(1), column(2)];
    let squared = c0.dot(c0);
    if !squared.is_normal() {
        return None;
    }
    let tolerance = squared * UNIT_TOLERANCE;
    let near = |value: f32, want: f32| (value - want).abs() <= tolerance;
    let similar = near(c1.dot(c1), squared)
        && near(c2.dot(c2), squared)
        && near(c0.dot(c1), 0.0)
        && near(c0.dot(c2), 0.0)
        && near(c1.dot(c2), 0.0);
    if !similar {
        return None;
    }
    let s = 1.0 / libm::sqrtf(squared);
    let finite = [c0, c1, c2].iter().all(|c| (*c * s).is_finite());
    (s.is_normal() && finite).then_some(s)
}

/// A model-space normal `n` (any length) as a unit normal in view space:
/// transformed by `model_view`, then normalised.
pub(super) fn normalised_view_normal(n: Vec3, model_view: &Mat4) -> Vec3 {
    model_view.transform_vector(n).normalized()
}

/// Per-draw constants.
pub(super) struct Frame {
    mvp: Mat4,
    #[cfg(feature = "clipping")]
    /// The same product and the frustum's nearest `w` in `f64`, for faces
    /// that need clipping: made the first time one does (on a core without
    /// an FPU it is hundreds of soft-float operations, every frame).
    clip64: OnceCell<Clip64>,
    /// What `mvp64` is the product of: projection, view and model.
    #[cfg(feature = "clipping")]
    factors: [Mat4; 3],
    pub(super) model_view: Mat4,
    /// One over the scale of `model_view` when it is a rotation with
    /// uniform scale: a unit normal turned by it and multiplied by this
    /// stays unit, with no square root per face ([`Frame::view_normal`]).
    /// Zero for any other model-view, and for the integer front end, whose
    /// normals are its own. (One `f32`, not the rotation's rows: with the
    /// rows, the larger frame cost the Cortex-M0+ 1,000 more instructions
    /// a frame of the torus knot, which never uses them.)
    inverse_scale: f32,
    pub(super) width: f32,
    pub(super) height: f32,
    /// Guard band half-widths in NDC units, x and y.
    pub(super) guard: (f32, f32),
    /// The sum of the absolute terms of the `z` and `w` rows of
    /// `|projection| · |view| · |model|`: per unit of a position's largest
    /// coordinate, and the constant (see [`Frame::inside_guard`]).
    near_far_terms: (f32, f32),
    pub(super) cull: Cull,
    /// With [`Cull::Back`] from a hull closed by caps, the screen
    /// rectangles of the caps that face the viewer: back faces that meet
    /// one are drawn ([`Self::cap_window`], [`CapCover`]). Only with the
    /// `std` feature (the host's meshes have caps; a microcontroller's
    /// frame stays as it was, and a mesh with caps draws every face
    /// there).
    #[cfg(feature = "std")]
    cap_cover: Option<CapCover>,
    /// The integer front end, for a quantized mesh whose matrices fit it.
    pub(super) fixed: Option<FixedFrame>,
}

#[cfg(feature = "clipping")]
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

#[cfg(feature = "clipping")]
fn to64(m: &Mat4) -> [[f64; 4]; 4] {
    m.m.map(|row| row.map(f64::from))
}

impl Frame {
    pub(super) fn new(
        model: &Mat4,
        camera: &Camera,
        cull: Cull,
        quantized: Option<&QuantizedView>,
    ) -> Self {
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
        let inverse_scale = if fixed.is_some() {
            0.0
        } else {
            similarity_inverse_scale(&model_view).unwrap_or(0.0)
        };
        Self {
            mvp,
            near_far_terms,
            inverse_scale,
            #[cfg(feature = "clipping")]
            clip64: OnceCell::new(),
            #[cfg(feature = "clipping")]
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
            #[cfg(feature = "std")]
            cap_cover: None,
        }
    }

    /// A model-space normal `n` as a unit normal in view space. A unit `n`
    /// (as [`face_normals`](crate::face_normals) stores them) under a
    /// model-view that is a rotation with uniform scale is turned by the
    /// rotation alone; any other is [`normalised_view_normal`].
    #[inline]
    pub(super) fn view_normal(&self, n: Vec3) -> Vec3 {
        self.turned_by_rotation(n)
            .unwrap_or_else(|| normalised_view_normal(n, &self.model_view))
    }

    /// `n` turned by the model-view's rotation alone, when that is its view
    /// normal: `n` of unit length and the model-view a rotation with
    /// uniform scale (see [`Self::view_normal`]).
    #[inline(always)]
    fn turned_by_rotation(&self, n: Vec3) -> Option<Vec3> {
        (self.inverse_scale != 0.0 && (n.dot(n) - 1.0).abs() <= UNIT_TOLERANCE)
            .then(|| self.model_view.transform_vector(n) * self.inverse_scale)
    }

    /// [`Self::view_normal`]`(n).dot(v)`, the same value, with the turn
    /// by the rotation alone in line and any other out of line: only a
    /// number leaves either ([`FaceInfo::normal_dot`]).
    ///
    /// [`FaceInfo::normal_dot`]: crate::front::scene::FaceInfo::normal_dot
    #[inline(always)]
    pub(super) fn view_normal_dot(&self, n: Vec3, v: Vec3) -> f32 {
        match self.turned_by_rotation(n) {
            Some(turned) => turned.dot(v),
            None => self.normalised_view_normal_dot(n, v),
        }
    }

    /// [`normalised_view_normal`]`(n, ..).dot(v)`, out of line.
    #[inline(never)]
    fn normalised_view_normal_dot(&self, n: Vec3, v: Vec3) -> f32 {
        normalised_view_normal(n, &self.model_view).dot(v)
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
    pub(super) fn vertex<M: Mesh + ?Sized, R>(
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
        let Some(v) = stored else {
            // Only a vertex that cannot be projected as it is asks the
            // `f64` transform whether it is finite (each vertex asking
            // cost the bunny at 800x600 64 instructions a vertex). Without
            // the clipper it always needs clipping: its faces are refused
            // with `Error::NeedsClipping`, none is dropped as non-finite.
            #[cfg(feature = "clipping")]
            let finite = self.clip_position64(mesh, index).is_finite();
            #[cfg(not(feature = "clipping"))]
            let finite = true;
            return Ok(if finite { needs_clip } else { non_finite });
        };
        screen(v)
    }

    /// Where the `f32` front end puts a vertex at model-space `position`
    /// ([`Self::vertex`]'s path for a mesh it transforms, the same lines):
    /// `None` when it is not finite or needs clipping. (`Self::vertex`
    /// keeps its own copy: calling this from it changed the Cortex-M0+
    /// build's code, and `cargo qemu` counted 3,360 more instructions a
    /// frame of the torus knot.)
    #[inline(always)]
    fn screen_position(&self, position: [f32; 3]) -> Option<ScreenVertex> {
        let p = self.mvp.transform_point(Vec3::from_array(position));
        let extent = position[0]
            .abs()
            .max(position[1].abs())
            .max(position[2].abs());
        if !p.is_finite() {
            None
        } else if self.inside_guard(p, extent) {
            self.project(p)
        } else {
            None
        }
    }

    /// Where a hole of a mesh closed by `caps` (model space) can show its
    /// inside: `Some(None)` when every cap triangle faces away on screen
    /// or covers nothing, `Some(Some(window))` when some face the viewer,
    /// `window` holding them all with a pixel to spare each way (a back
    /// face whose corners lie outside it cannot show: see
    /// [`ClosedHull`](crate::ClosedHull)). Each corner is placed where the
    /// `f32` front end puts a vertex at it ([`Self::screen_position`]) and
    /// the winding tested as the back-face test tests a face's. `None`
    /// when a corner is not projected as it is, or the integer front end
    /// draws the mesh (it places vertices by its own arithmetic).
    pub(super) fn cap_window(
        &self,
        caps: &[[[f32; 3]; 3]],
        quantized: bool,
    ) -> Option<Option<ScreenRect>> {
        if quantized {
            return None;
        }
        let mut window: Option<ScreenRect> = None;
        for triangle in caps {
            if let Some(rect) = self.cap_rect(triangle)? {
                match window.as_mut() {
                    Some(w) => {
                        (w.x0, w.x1) = (w.x0.min(rect.x0), w.x1.max(rect.x1));
                        (w.y0, w.y1) = (w.y0.min(rect.y0), w.y1.max(rect.y1));
                    }
                    None => window = Some(rect),
                }
            }
        }
        Some(window)
    }

    /// The screen rectangle of cap `triangle` grown by a pixel each way
    /// when it faces the viewer and may cover a sample (`Some(None)` when
    /// not); `None` when a corner is not projected as it is.
    fn cap_rect(&self, triangle: &[[f32; 3]; 3]) -> Option<Option<ScreenRect>> {
        let [a, b, c] = triangle.map(|corner| self.screen_position(corner));
        let (a, b, c) = (a?, b?, c?);
        // Inside the guard band: differences below 2^23, products below
        // 2^46. Zero area covers no sample, nor does a cap that no sample
        // lies near (on a host: a `no_std` build keeps no window, and its
        // code stays as it was).
        let faces_viewer = cross(b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y) < 0;
        if !(faces_viewer && (!cfg!(feature = "std") || may_cover_a_sample([a, b, c]))) {
            return Some(None);
        }
        let mut rect = ScreenRect::point(a);
        rect.add(b);
        rect.add(c);
        // The continuous cap lies within half a sub-pixel step of its
        // snapped corners' rectangle; a pixel is far beyond that.
        Some(Some(ScreenRect {
            x0: rect.x0 - SUBPIXEL_STEPS,
            x1: rect.x1 + SUBPIXEL_STEPS,
            y0: rect.y0 - SUBPIXEL_STEPS,
            y1: rect.y1 + SUBPIXEL_STEPS,
        }))
    }

    /// The model-view-projection matrix of the `f32` front end.
    #[cfg(feature = "std")]
    pub(super) fn mvp(&self) -> &Mat4 {
        &self.mvp
    }

    /// Whether back faces are drawn where caps face the viewer
    /// ([`Self::cap_window`]); never without the `std` feature.
    #[inline(always)]
    pub(super) fn has_window(&self) -> bool {
        #[cfg(feature = "std")]
        return self.cap_cover.is_some();
        #[cfg(not(feature = "std"))]
        return false;
    }

    /// Keeps `window` ([`Self::cap_window`] of `caps`) with each cap's
    /// own rectangle ([`CapCover`]); `false` when there is one and this
    /// build keeps none (without the `std` feature), so the frame must
    /// cull nothing.
    pub(super) fn keep_window(
        &mut self,
        window: Option<ScreenRect>,
        caps: &[[[f32; 3]; 3]],
    ) -> bool {
        #[cfg(feature = "std")]
        {
            self.cap_cover = window.map(|window| {
                let mut cover = CapCover::new(window);
                for triangle in caps {
                    if let Some(Some(rect)) = self.cap_rect(triangle) {
                        cover.add(&rect);
                    }
                }
                cover
            });
            true
        }
        #[cfg(not(feature = "std"))]
        {
            let _ = caps;
            window.is_none()
        }
    }

    /// Whether a back face within `rect` may be culled: always, unless
    /// a cap of the mesh's hull faces the viewer
    /// ([`Self::cap_window`]) and `rect` (`None`: not known) meets a cap's
    /// rectangle ([`CapCover::meets`]).
    #[inline(always)]
    pub(super) fn may_cull_within(&self, rect: Option<ScreenRect>) -> bool {
        #[cfg(feature = "std")]
        return match (&self.cap_cover, rect) {
            (None, _) => true,
            (Some(cover), Some(r)) => !cover.meets(&r),
            (Some(_), None) => false,
        };
        #[cfg(not(feature = "std"))]
        {
            let _ = rect;
            true
        }
    }

    /// Mesh vertex `index`'s clip-space `w`: the integer front end's
    /// when it draws the mesh, else the `f32` transform's (as
    /// [`Self::vertex`] computes them).
    pub(super) fn clip_w<M: Mesh + ?Sized>(&self, mesh: &M, index: usize) -> ClipW {
        if let (Some(fixed), Some(q)) = (&self.fixed, mesh.quantized())
            && let Some(&p) = q.positions.get(index)
        {
            return ClipW::from_i64(fixed.clip(p)[3]);
        }
        let p = self
            .mvp
            .transform_point(Vec3::from_array(mesh.position(index)));
        ClipW::from_f32(p.w)
    }

    /// The frame's `f64` state for clipping, made on first use.
    #[cfg(feature = "clipping")]
    pub(super) fn clip64(&self) -> &Clip64 {
        self.clip64.get_or_init(|| {
            let mut clip = Clip64::new(&self.factors);
            let (gx, gy) = self.guard;
            clip.w_near = frustum_w_near(&self.factors[0], (f64::from(gx), f64::from(gy)));
            clip
        })
    }

    /// Clip-space position in `f64`.
    #[cfg(feature = "clipping")]
    pub(super) fn clip_position64<M: Mesh + ?Sized>(&self, mesh: &M, index: usize) -> ClipPoint {
        let p = mesh.position(index).map(f64::from);
        let row = |r: [f64; 4]| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3];
        let m = &self.clip64().mvp;
        ClipPoint::new(row(m[0]), row(m[1]), row(m[2]), row(m[3]))
    }

    /// Screen vertex of a clip-space point inside the near, far and guard
    /// planes: [`ScreenVertex::from_f32`] of its pixel position and depth,
    /// with no branch (the same values, to the bit; tested below).
    #[inline(always)]
    fn project(&self, p: Vec4) -> Option<ScreenVertex> {
        let inv_w = 1.0 / p.w;
        let x = (p.x * inv_w + 1.0) * 0.5 * self.width;
        let y = (1.0 - p.y * inv_w) * 0.5 * self.height;
        let z = ((p.z * inv_w + 1.0) * 0.5).clamp(0.0, 1.0);
        let (x, y) = (snap(x), snap(y));
        let depth = ((z * DEPTH_ONE as f32 + 0.5) as u32).min(DEPTH_MAX);
        // `snap`'s values within the guard band; NaN compares false.
        let inside = |v: Option<i32>| v.is_some_and(|v| v.unsigned_abs() < GUARD_BAND as u32);
        (inside(x) & inside(y) & (0.0..=1.0).contains(&z)).then(|| ScreenVertex {
            x: x.unwrap_or_default(),
            y: y.unwrap_or_default(),
            z: depth,
        })
    }
}

/// Whether the triangle `t` (snapped corners, clockwise on the screen:
/// its inside is where each edge's `cross(b - a, p - a)` is at most
/// zero) may cover a pixel sample once each corner is moved by up to a
/// sub-pixel step each way: whether a sample lies within that distance
/// (`r`, one step, in the maximum norm) of it. A point `q` of `t` with
/// `|p - q| <= r` has each edge's value at `p` at most `r (|e_x| +
/// |e_y|)`, so a sample beyond that for some edge is not near; and none
/// beyond the triangle's rectangle grown by `r` is. A triangle whose
/// rectangle holds more than 64 samples is taken to cover one.
fn may_cover_a_sample(t: [ScreenVertex; 3]) -> bool {
    let Some(rect) = ScreenRect::of(t) else {
        return false;
    };
    let r = 1i64;
    let (step, half) = (i64::from(SUBPIXEL_STEPS), i64::from(SUBPIXEL_STEPS / 2));
    // Samples at `k·S + S/2`: the first at or after `lo - r`, the last at
    // or before `hi + r`.
    let samples = |lo: i32, hi: i32| {
        let first = (i64::from(lo) - r - half + step - 1).div_euclid(step);
        let last = (i64::from(hi) + r - half).div_euclid(step);
        first..=last
    };
    let (columns, rows) = (samples(rect.x0, rect.x1), samples(rect.y0, rect.y1));
    let count =
        (columns.end() - columns.start() + 1).max(0) * (rows.end() - rows.start() + 1).max(0);
    if count > 64 {
        return true;
    }
    rows.clone().any(|row| {
        columns.clone().any(|column| {
            let (px, py) = (column * step + half, row * step + half);
            (0..3).all(|k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let (ex, ey) = (i64::from(b.x - a.x), i64::from(b.y - a.y));
                let value = ex * (py - i64::from(a.y)) - ey * (px - i64::from(a.x));
                value <= r * (ex.abs() + ey.abs())
            })
        })
    })
}

/// `pixels` on the sub-pixel grid, rounded half away from zero, as
/// [`ScreenVertex::from_f32`] rounds it; `None` outside `±2^31`, or NaN.
#[inline(always)]
fn snap(pixels: f32) -> Option<i32> {
    let scaled = pixels * SUBPIXEL_STEPS as f32;
    let rounded = scaled + 0.5f32.copysign(scaled);
    (rounded.abs() < 2147483648.0).then_some(rounded as i32)
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
///
/// [`draw_mesh`]: crate::draw_mesh
/// [`draw_mesh_projected`]: crate::draw_mesh_projected
pub fn project_vertices<M: Mesh>(
    mesh: &M,
    model: &Mat4,
    camera: &Camera,
    first: usize,
    out: &mut [ProjectedVertex],
) -> Result<(), Error> {
    let end = first
        .checked_add(out.len())
        .ok_or(Error::MeshIndexOutOfRange)?;
    let mut out = out.iter_mut();
    project_vertices_with(mesh, model, camera, first..end, |_, vertex| {
        if let Some(slot) = out.next() {
            *slot = vertex;
        }
    })
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

/// Where a [`Draw`] finds a vertex on its first use, before transforming
/// it itself: nowhere in [`draw_mesh`], in the projection given to
/// [`draw_mesh_projected`]. (A type, so that `draw_mesh` pays nothing for
/// it.)
///
/// [`Draw`]: super::faces
/// [`draw_mesh`]: crate::draw_mesh
/// [`draw_mesh_projected`]: crate::draw_mesh_projected
pub(crate) trait VertexSource: Copy {
    /// Vertex `index`, if it was projected beforehand.
    fn projected(self, index: usize) -> Option<ProjectedVertex>;
}

/// [`draw_mesh`]'s source: every vertex is transformed on its first use.
///
/// [`draw_mesh`]: crate::draw_mesh
#[derive(Debug, Clone, Copy)]
pub(super) struct TransformEach;

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::geometry::unit;
    use crate::front::scene::face_info::FacePart;

    fn similarity(scale: f32, yaw: f32, pitch: f32) -> Mat4 {
        Mat4::translation(Vec3::new(0.5, -2.0, -7.0))
            .mul(&Mat4::rotation_x(pitch))
            .mul(&Mat4::rotation_y(yaw))
            .mul(&Mat4::scale(Vec3::new(scale, scale, scale)))
    }

    /// A corner in sub-pixel steps.
    fn sv(x: i32, y: i32) -> ScreenVertex {
        ScreenVertex { x, y, z: 0 }
    }

    /// A cap covers a sample only if one lies within a sub-pixel step of
    /// it: samples sit at `k·256 + 128`.
    #[test]
    fn caps_near_no_sample_cover_none() {
        // Clockwise on the screen (`y` down), between the samples of
        // pixels (0, 0) and (1, 1).
        let between = [sv(140, 140), sv(140, 360), sv(360, 140)];
        assert!(!may_cover_a_sample(between));
        // Its corner moved onto pixel (0, 0)'s sample, and to within a
        // step of it; two steps away it is clear again.
        assert!(may_cover_a_sample([
            sv(128, 128),
            sv(140, 360),
            sv(360, 140)
        ]));
        assert!(may_cover_a_sample([
            sv(129, 129),
            sv(140, 360),
            sv(360, 140)
        ]));
        assert!(!may_cover_a_sample([
            sv(130, 130),
            sv(140, 360),
            sv(360, 140)
        ]));
        // Another between the samples, each beyond one of its edges.
        assert!(!may_cover_a_sample([
            sv(300, 140),
            sv(140, 300),
            sv(300, 300)
        ]));
        // A large cap, and one holding a sample well inside.
        assert!(may_cover_a_sample([
            sv(0, 0),
            sv(0, 1 << 14),
            sv(1 << 14, 0)
        ]));
        assert!(may_cover_a_sample([
            sv(300, 300),
            sv(300, 500),
            sv(500, 300)
        ]));
        // Far below zero the samples' grid holds as well.
        let shifted = between.map(|v| sv(v.x - 256 * 40, v.y - 256 * 7));
        assert!(!may_cover_a_sample(shifted));
    }

    /// The projection's snapping gives what `ScreenVertex::from_f32`
    /// gives, value for value: every kind of `f32` near the grid's
    /// roundings, the guard band's edges and beyond, NaN and infinities.
    #[test]
    fn projection_rounds_as_from_f32() {
        let camera = Camera::reference(64, 48);
        let frame = Frame::new(&Mat4::IDENTITY, &camera, Cull::None, None);
        let (w, h) = (frame.width, frame.height);
        let mut values = std::vec::Vec::new();
        for base in [
            0.0f32,
            0.5 / 256.0,
            1.0 / 256.0,
            3.0,
            63.5,
            8191.99,
            8192.0,
            1e9,
        ] {
            for sign in [1.0f32, -1.0] {
                let v = base * sign;
                values.push(v);
                let mut up = v;
                let mut down = v;
                for _ in 0..4 {
                    up = f32::from_bits(up.to_bits() + 1);
                    down = f32::from_bits(down.to_bits().wrapping_sub(1));
                    values.extend([up, down]);
                }
            }
        }
        values.extend([f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -0.0]);
        let mut next = 0x2545_f491u32;
        for _ in 0..100_000 {
            next ^= next << 13;
            next ^= next >> 17;
            next ^= next << 5;
            values.push(f32::from_bits(next) % 9000.0);
        }
        for (k, &x) in values.iter().enumerate() {
            let y = values[(k * 7 + 3) % values.len()];
            let z = values[(k * 13 + 1) % values.len()].abs() % 1.5;
            // The clip-space point that projects to (x, y, z) with w = 1.
            let p = Vec4::new(2.0 * x / w - 1.0, 1.0 - 2.0 * y / h, 2.0 * z - 1.0, 1.0);
            let (px, py) = ((p.x + 1.0) * 0.5 * w, (1.0 - p.y) * 0.5 * h);
            let pz = ((p.z + 1.0) * 0.5).clamp(0.0, 1.0);
            assert_eq!(
                frame.project(p),
                ScreenVertex::from_f32(px, py, pz).ok(),
                "{x} {y} {z}"
            );
        }
    }

    /// A rotation times one scale gives its rotation: orthonormal rows
    /// that turn a vector as the matrix does, less the scale. A shear, a
    /// non-uniform scale, a singular or a non-finite matrix gives none.
    #[test]
    fn a_similarity_gives_its_rotation_and_nothing_else_does() {
        for scale in [1e-6, 0.37, 1.0, 3.0, 1e6] {
            for (yaw, pitch) in [(0.0, 0.0), (0.3, -1.2), (2.9, 0.7)] {
                let m = similarity(scale, yaw, pitch);
                let s = similarity_inverse_scale(&m).expect("a similarity");
                let column = |j: usize| Vec3::new(m.m[0][j], m.m[1][j], m.m[2][j]) * s;
                let rows = [0, 1, 2].map(column);
                for (i, a) in rows.iter().enumerate() {
                    for (j, b) in rows.iter().enumerate() {
                        let want = if i == j { 1.0 } else { 0.0 };
                        assert!((a.dot(*b) - want).abs() < 1e-6, "{scale} {i} {j}");
                    }
                }
                let v = Vec3::new(0.2, -0.9, 0.4);
                let turned = m.transform_vector(v) * (1.0 / scale);
                let by_scale = m.transform_vector(v) * s;
                assert!((turned - by_scale).length() < 1e-5, "{scale}");
            }
        }
        let squash = similarity(1.0, 0.3, 0.2).mul(&Mat4::scale(Vec3::new(1.0, 1.001, 1.0)));
        let mut shear = Mat4::IDENTITY;
        shear.m[0][1] = 0.01;
        let flat = Mat4::scale(Vec3::new(1.0, 1.0, 0.0));
        let mut nan = similarity(1.0, 0.1, 0.1);
        nan.m[2][2] = f32::NAN;
        let huge = Mat4::scale(Vec3::new(1e30, 1e30, 1e30));
        for m in [squash, shear, flat, nan, huge, Mat4::scale(Vec3::default())] {
            assert!(similarity_inverse_scale(&m).is_none(), "{m:?}");
        }
    }

    /// A unit normal turned by the rotation alone is the normal the full
    /// path gives (transformed and normalised) to within `2^-20` per
    /// component; a normal not of unit length, or a model-view that is
    /// not a similarity, takes the full path and gives exactly its
    /// result.
    #[test]
    fn view_normals_by_the_rotation_agree_with_the_normalised_ones() {
        let camera = Camera::reference(64, 64);
        let full = |frame: &Frame, n: Vec3| unit(frame.model_view.transform_vector(n));
        for scale in [0.01, 1.0, 40.0] {
            let model = similarity(scale, 0.8, -0.4);
            let frame = Frame::new(&model, &camera, Cull::None, None);
            assert!(frame.inverse_scale != 0.0);
            for k in 0..200 {
                let t = k as f32 * 0.37;
                let n = unit(Vec3::new(t.sin(), (1.7 * t).cos(), (0.3 * t).sin() - 0.2));
                let (fast, want) = (frame.view_normal(n), full(&frame, n));
                assert!((fast - want).length() < 1.0 / (1 << 20) as f32, "{n:?}");
                let long = n * 3.0;
                assert_eq!(frame.view_normal(long), full(&frame, long));
            }
        }
        let model = Mat4::scale(Vec3::new(1.0, 2.0, 1.0));
        let frame = Frame::new(&model, &camera, Cull::None, None);
        assert_eq!(frame.inverse_scale, 0.0);
        let n = unit(Vec3::new(0.3, 0.4, -0.5));
        assert_eq!(frame.view_normal(n), full(&frame, n));
    }

    /// `view_normal_dot(n, v)` is `view_normal(n).dot(v)` to the bit on
    /// both of its paths (the rotation alone, and the normalised turn for
    /// a normal not of unit length or a model-view that is not a
    /// similarity), and so is `FaceInfo::normal_dot`, for a face with a
    /// stored normal, one without (Newell's of its corners) and a known
    /// one.
    #[test]
    fn normal_dot_is_the_normals_dot_product() {
        use crate::front::mesh::StaticMesh;
        use crate::front::scene::FaceInfo;
        use crate::front::scene::VertexInfo;
        let camera = Camera::reference(64, 64);
        let lights = [
            Vec3::new(-0.4, 0.5, 0.77),
            unit(Vec3::new(0.9, -0.1, 0.3)),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        let squash = Mat4::scale(Vec3::new(1.0, 2.0, 1.0));
        for model in [
            similarity(0.01, 0.8, -0.4),
            similarity(40.0, 2.1, 0.3),
            squash,
        ] {
            let frame = Frame::new(&model, &camera, Cull::None, None);
            for k in 0..200 {
                let t = k as f32 * 0.37;
                let n = unit(Vec3::new(t.sin(), (1.7 * t).cos(), (0.3 * t).sin() - 0.2));
                for v in lights {
                    for n in [n, n * 3.0] {
                        let (got, want) =
                            (frame.view_normal_dot(n, v), frame.view_normal(n).dot(v));
                        assert_eq!(got.to_bits(), want.to_bits(), "{n:?} {v:?}");
                    }
                }
            }
            let positions = [[0.0, 0.0, 0.0], [1.0, 0.2, 0.1], [0.3, 1.0, -0.2]];
            let normal = unit(Vec3::new(-0.12, 0.13, 1.0));
            let normals = [[normal.x, normal.y, normal.z]];
            let plain = StaticMesh::new(&positions, &[0, 1, 2], &[0]).unwrap();
            let stored = plain.with_face_normals(&normals).unwrap();
            let (whole, fan) = (FacePart::Whole, FacePart::Fan(1));
            for (front, part) in [(true, whole), (false, whole), (true, fan)] {
                for face in [
                    frame.face_info(&plain, (0, part), &[0, 1, 2], front),
                    frame.face_info(&stored, (0, part), &[0, 1, 2], front),
                    FaceInfo::new(0, front, normal, 2.0),
                ] {
                    for v in lights {
                        let (got, want) = (face.normal_dot(v), face.normal().dot(v));
                        assert_eq!(got.to_bits(), want.to_bits(), "{face:?} {v:?}");
                    }
                }
            }
            // And a vertex's: with a stored normal of unit length and one
            // not, with none, and a known one.
            let long = [[normal.x * 3.0, normal.y * 3.0, normal.z * 3.0]; 3];
            let units = [[normal.x, normal.y, normal.z]; 3];
            let smooth = plain.with_vertex_normals(&units).unwrap();
            let scaled = plain.with_vertex_normals(&long).unwrap();
            for vertex in [
                VertexInfo::of_mesh(&smooth, &frame, 1),
                VertexInfo::of_mesh(&scaled, &frame, 2),
                VertexInfo::of_mesh(&plain, &frame, 0),
                VertexInfo::new(0, Some(normal), None),
                VertexInfo::new(0, None, None),
            ] {
                for v in lights {
                    let (got, want) = (vertex.normal_dot(v), vertex.normal().map(|n| n.dot(v)));
                    assert_eq!(got.map(f32::to_bits), want.map(f32::to_bits), "{vertex:?}");
                }
            }
        }
    }
}
