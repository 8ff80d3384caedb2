//! A float64 reference renderer for the reference view: exact per-pixel
//! visibility, to measure the scanline core against.
//!
//! Everything is in `f64` and computed directly from the view's definition
//! (it shares no matrices with the `f32` pipeline):
//! * positions are normalised (bounding-box centre `c`, largest distance
//!   `r`: `p' = (p - c) / r`), rotated `p'' = Rx(pitch) · Ry(yaw) · p'`, and
//!   seen from the eye at (0, 0, 3) looking down -Z, 45° vertical field of
//!   view, near 0.1, far 10 ([`ReferenceCamera::STANDARD`]; another
//!   [`ReferenceCamera`] moves the eye and the clip planes);
//! * each face is clipped to the near and far planes in view space and
//!   projected; pixel `(i, j)` is covered when its sample `(i + 0.5, j + 0.5)`
//!   is inside the projected face by the even-odd rule (top-left on ties),
//!   so concave faces are exact;
//! * depth is the distance along the view axis at which the pixel's ray
//!   meets the face's plane (Newell normal in view space); the nearest
//!   face wins, and on an exact tie the lower face id;
//! * a face that is not planar ([`Mesh::face_is_planar`], the same test the pipeline
//!   uses) is the fan of triangles from its first corner;
//! * values given at the vertices ([`ReferenceFrame::render_with_values`],
//!   e.g. Gouraud's vertex colours) are carried through clipping (linear
//!   in view space) and interpolated over each drawn part as Gouraud
//!   shading in this library is defined ([`ReferenceFrame::interpolated`]):
//!   over a triangle, the screen-space interpolation of its corners'
//!   values; a quad strictly convex on screen (not cut by clipping) is the
//!   two triangles `0 1 2` and `0 2 3`, each interpolated so; any other
//!   polygon takes the plane in screen space through its first projected
//!   corner with the Newell normal of its corners `(x, y, value)` (exact
//!   when those are coplanar).

use std::vec;
use std::vec::Vec;

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use zline::FaceInfo;
use zline::Mesh;
use zline::Vec3;

/// Face id of pixels no face covers.
pub const BACKGROUND: u32 = u32::MAX;

/// Where the reference view's eye is and what it sees: the reference view
/// has [`ReferenceCamera::STANDARD`]; the adversarial catalogue and the
/// depth-precision study move the eye and the clip planes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceCamera {
    /// The eye at (0, 0, `eye_distance`) of the normalised mesh, looking
    /// down -Z with +Y up.
    pub eye_distance: f64,
    /// Vertical field of view, degrees.
    pub fov_y_deg: f64,
    /// Near clip plane, view-axis distance.
    pub near: f64,
    /// Far clip plane, view-axis distance.
    pub far: f64,
}

impl ReferenceCamera {
    /// The reference view's camera: eye at distance 3, 45 degrees, near 0.1,
    /// far 10 (the same as [`Camera::reference`](zline::Camera::reference)).
    pub const STANDARD: Self = Self {
        eye_distance: 3.0,
        fov_y_deg: 45.0,
        near: 0.1,
        far: 10.0,
    };

    /// The same camera for the `f32` pipeline, at `width` x `height`.
    pub fn camera(&self, width: u16, height: u16) -> zline::Camera {
        use zline::{Mat4, Vec3};
        let view = Mat4::translation(Vec3::new(0.0, 0.0, -(self.eye_distance as f32)));
        zline::Camera::perspective(
            view,
            self.fov_y_deg as f32,
            width,
            height,
            self.near as f32,
            self.far as f32,
        )
    }
}

/// The reference view of a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceView {
    /// Frame width in pixels.
    pub width: usize,
    /// Frame height in pixels.
    pub height: usize,
    /// Rotation about +Y, degrees.
    pub yaw_deg: f64,
    /// Rotation about +X (after yaw), degrees.
    pub pitch_deg: f64,
    /// Leave out faces whose projection runs clockwise on screen.
    pub cull_back: bool,
}

type V3 = [f64; 3];

/// Three values carried by a vertex (a colour's channels).
pub type Values = [f64; 3];

/// A face as the reference sees it.
#[derive(Debug, Clone)]
struct Face {
    /// Projected corners after near/far clipping, in pixels.
    screen: Vec<[f64; 2]>,
    /// The values at those corners.
    values: Vec<Values>,
    /// The view-axis distance of those corners (clip-space `w`).
    distances: Vec<f64>,
    /// Whether clipping left the face whole.
    whole: bool,
    /// View-space plane: `normal · p = offset`.
    normal: V3,
    offset: f64,
    /// Counter-clockwise as the viewer sees it.
    front: bool,
    /// Mean view-axis distance of the corners.
    mean_depth: f64,
}

/// A frame rendered by the reference: face id and depth per pixel, and the
/// faces' geometry for measuring other renderers against it.
#[derive(Debug, Clone)]
pub struct ReferenceFrame {
    /// Frame width.
    pub width: usize,
    /// Frame height.
    pub height: usize,
    /// Visible face per pixel, row-major from the top; [`BACKGROUND`] where
    /// none.
    pub ids: Vec<u32>,
    /// Depth (view-axis distance) of the visible face per pixel;
    /// infinity for background.
    pub depths: Vec<f64>,
    /// The drawn parts of each face: the face itself, or the triangles of
    /// its fan when it is not planar; empty when culled or clipped away.
    faces: Vec<Vec<Face>>,
    tan_half: f64,
    aspect: f64,
    /// Near and far clip distances.
    clip: (f64, f64),
}

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl ReferenceFrame {
    /// Renders `mesh` in the reference view.
    pub fn render<M: Mesh + ?Sized>(mesh: &M, view: &ReferenceView) -> Self {
        Self::render_with(mesh, view, &ReferenceCamera::STANDARD)
    }

    /// Renders `mesh` in the reference view's orientation seen by `camera`.
    pub fn render_with<M: Mesh + ?Sized>(
        mesh: &M,
        view: &ReferenceView,
        camera: &ReferenceCamera,
    ) -> Self {
        Self::render_with_values(mesh, view, camera, &|_| [0.0; 3])
    }

    /// [`Self::render_with`] with `values(v)` at each vertex `v`, for
    /// [`Self::interpolated`].
    pub fn render_with_values<M: Mesh + ?Sized>(
        mesh: &M,
        view: &ReferenceView,
        camera: &ReferenceCamera,
        values: &dyn Fn(usize) -> Values,
    ) -> Self {
        let positions = view_positions(mesh, view, camera.eye_distance);
        let mut frame = Self {
            width: view.width,
            height: view.height,
            ids: vec![BACKGROUND; view.width * view.height],
            depths: vec![f64::INFINITY; view.width * view.height],
            faces: Vec::with_capacity(mesh.face_count()),
            tan_half: (camera.fov_y_deg / 2.0).to_radians().tan(),
            clip: (camera.near, camera.far),
            aspect: view.width as f64 / view.height as f64,
        };
        for f in 0..mesh.face_count() {
            let corners: Vec<(V3, Values)> = mesh
                .face(f)
                .iter()
                .map(|&i| (positions[usize::from(i)], values(usize::from(i))))
                .collect();
            let outlines: Vec<Vec<(V3, Values)>> = if corners.len() > 3 && !mesh.face_is_planar(f) {
                (1..corners.len() - 1)
                    .map(|k| vec![corners[0], corners[k], corners[k + 1]])
                    .collect()
            } else {
                vec![corners]
            };
            let parts: Vec<Face> = outlines
                .iter()
                .filter_map(|p| frame.face(p, view.cull_back))
                .collect();
            for part in &parts {
                frame.draw(f as u32, part);
            }
            frame.faces.push(parts);
        }
        frame
    }

    /// Clips, projects and culls one face.
    fn face(&self, corners: &[(V3, Values)], cull_back: bool) -> Option<Face> {
        let mut normal = [0.0; 3];
        for (k, &(p, _)) in corners.iter().enumerate() {
            let q = corners[(k + 1) % corners.len()].0;
            normal[0] += (p[1] - q[1]) * (p[2] + q[2]);
            normal[1] += (p[2] - q[2]) * (p[0] + q[0]);
            normal[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        let clipped = clip_depth(corners, self.clip);
        if clipped.len() < 3 {
            return None;
        }
        let screen: Vec<[f64; 2]> = clipped.iter().map(|&(p, _)| self.project(p)).collect();
        let values = clipped.iter().map(|&(_, v)| v).collect();
        let distances = clipped.iter().map(|&(p, _)| -p[2]).collect();
        let whole = clipped == corners;
        let area: f64 = (0..screen.len())
            .map(|k| {
                let (a, b) = (screen[k], screen[(k + 1) % screen.len()]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum();
        if area == 0.0 || (cull_back && area > 0.0) {
            return None;
        }
        Some(Face {
            screen,
            values,
            distances,
            whole,
            normal,
            offset: dot(normal, corners[0].0),
            front: area < 0.0,
            mean_depth: -corners.iter().map(|(p, _)| p[2]).sum::<f64>() / corners.len() as f64,
        })
    }

    fn project(&self, p: V3) -> [f64; 2] {
        let d = -p[2];
        let x = p[0] / (d * self.tan_half * self.aspect);
        let y = p[1] / (d * self.tan_half);
        [
            (x + 1.0) * 0.5 * self.width as f64,
            (1.0 - y) * 0.5 * self.height as f64,
        ]
    }

    /// Direction of pixel `(i, j)`'s ray in view space, with z = -1.
    fn ray(&self, i: usize, j: usize) -> V3 {
        let x = (i as f64 + 0.5) / self.width as f64 * 2.0 - 1.0;
        let y = 1.0 - (j as f64 + 0.5) / self.height as f64 * 2.0;
        [x * self.tan_half * self.aspect, y * self.tan_half, -1.0]
    }

    fn draw(&mut self, id: u32, face: &Face) {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in &face.screen {
            (x0, x1, y0, y1) = (x0.min(p[0]), x1.max(p[0]), y0.min(p[1]), y1.max(p[1]));
        }
        let range = |lo: f64, hi: f64, n: usize| {
            let first = (lo - 0.5).ceil().max(0.0) as usize;
            let last = ((hi - 0.5).floor() + 1.0).clamp(0.0, n as f64) as usize;
            first..last
        };
        for j in range(y0, y1, self.height) {
            for i in range(x0, x1, self.width) {
                if !inside(&face.screen, i as f64 + 0.5, j as f64 + 0.5) {
                    continue;
                }
                let Some(depth) = plane_depth(face, self.ray(i, j)) else {
                    continue;
                };
                let k = j * self.width + i;
                if depth < self.depths[k] {
                    self.depths[k] = depth;
                    self.ids[k] = id;
                }
            }
        }
    }

    /// The drawn part of face `id` that covers pixel `(i, j)`'s sample, or
    /// else the part whose boundary is nearest to it.
    fn part(&self, id: u32, i: usize, j: usize) -> Option<&Face> {
        let parts = self.faces.get(id as usize)?;
        let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
        parts.iter().find(|p| inside(&p.screen, x, y)).or_else(|| {
            parts
                .iter()
                .min_by(|a, b| part_distance(a, x, y).total_cmp(&part_distance(b, x, y)))
        })
    }

    /// The values of face `id` at pixel `(i, j)`'s sample (see the
    /// module's notes), whether or not the face covers it; `None` for
    /// culled or clipped-away faces and parts of no area.
    pub fn interpolated(&self, id: u32, i: usize, j: usize) -> Option<Values> {
        self.interpolate(id, i, j, false, |part, k| part.values[k])
    }

    /// [`Self::interpolated`] over the part's corners rounded to the
    /// rasteriser's sub-pixel grid (1/256 px), as the core interpolates:
    /// the values of the plane through the corners it is given. Near a
    /// sliver's edge the two differ by more than the core's own error
    /// (moving a corner by 1/512 px can move a thin triangle's values
    /// by steps).
    pub fn interpolated_on_grid(&self, id: u32, i: usize, j: usize) -> Option<Values> {
        self.interpolate(id, i, j, true, |part, k| part.values[k])
    }

    /// The values of face `id` at pixel `(i, j)`'s sample interpolated
    /// perspective-correctly (as texture coordinates are): `value/w` and
    /// `1/w` interpolated over the same parts as [`Self::interpolated`]
    /// (affine in screen space), then divided, which is the value at the
    /// point of the part's plane the pixel's ray meets. Values 0 and 1
    /// only (the third is not interpolated).
    pub fn interpolated_perspective(&self, id: u32, i: usize, j: usize) -> Option<[f64; 2]> {
        let [u, v, q] = self.interpolate(id, i, j, false, |part, k| {
            let w = part.distances[k];
            [part.values[k][0] / w, part.values[k][1] / w, 1.0 / w]
        })?;
        Some([u / q, v / q])
    }

    /// The screen-affine interpolation of `corner(part, k)` over the part
    /// of face `id` at pixel `(i, j)` (see [`Self::interpolated`]), the
    /// part's corners rounded to 1/256 px first when `on_grid`.
    fn interpolate(
        &self,
        id: u32,
        i: usize,
        j: usize,
        on_grid: bool,
        corner: impl Fn(&Face, usize) -> Values,
    ) -> Option<Values> {
        let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
        // The nearest of the parts that hold the sample (the triangles of a
        // folded face's fan can overlap on screen), else the nearest part.
        let ray = self.ray(i, j);
        let depth = |p: &Face| plane_depth(p, ray).unwrap_or(f64::INFINITY);
        let part = self
            .faces
            .get(id as usize)?
            .iter()
            .filter(|p| inside(&p.screen, x, y))
            .min_by(|a, b| depth(a).total_cmp(&depth(b)))
            .or_else(|| self.part(id, i, j))?;
        let corners: Vec<usize> = if part.whole && strictly_convex(&part.screen) {
            // The triangle of the two that holds the sample (or is
            // nearer to it).
            let half = |t: [usize; 3]| {
                let screen = t.map(|k| part.screen[k]);
                let distance = (0..3)
                    .map(|m| segment_distance([x, y], screen[m], screen[(m + 1) % 3]))
                    .fold(f64::INFINITY, f64::min);
                (inside(&screen, x, y), distance)
            };
            let (first, second) = ([0, 1, 2], [0, 2, 3]);
            let (a, b) = (half(first), half(second));
            let take_first = a.0 || (!b.0 && a.1 <= b.1);
            if take_first {
                first.to_vec()
            } else {
                second.to_vec()
            }
        } else {
            (0..part.screen.len()).collect()
        };
        let n = corners.len();
        let grid = |p: [f64; 2]| {
            if on_grid {
                p.map(|c| (c * 256.0).round() / 256.0)
            } else {
                p
            }
        };
        let o = grid(part.screen[corners[0]]);
        let mut out = [0.0; 3];
        for (k, out) in out.iter_mut().enumerate() {
            // Newell's normal of the corners (x, y, value).
            let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
            for m in 0..n {
                let (p, q) = (
                    grid(part.screen[corners[m]]),
                    grid(part.screen[corners[(m + 1) % n]]),
                );
                let (pv, qv) = (
                    corner(part, corners[m])[k],
                    corner(part, corners[(m + 1) % n])[k],
                );
                a += (p[1] - q[1]) * (pv + qv);
                b += (pv - qv) * (p[0] + q[0]);
                c += (p[0] - q[0]) * (p[1] + q[1]);
            }
            if c == 0.0 {
                return None;
            }
            *out = corner(part, corners[0])[k] - (a * (x - o[0]) + b * (y - o[1])) / c;
        }
        Some(out)
    }

    /// Each pixel's colour: `shading` of its face, black where none.
    pub fn colors(&self, shading: &zline::Shading) -> Vec<Rgb888> {
        self.ids
            .iter()
            .map(|&id| {
                self.face_info(id)
                    .map_or(Rgb888::BLACK, |f| shading.color(&f))
            })
            .collect()
    }

    /// Depth of face `id`'s plane (of the part at the pixel) along pixel
    /// `(i, j)`'s ray, whether or not the face covers the pixel; `None` for
    /// culled or clipped-away faces and rays parallel to the plane.
    pub fn face_depth(&self, id: u32, i: usize, j: usize) -> Option<f64> {
        plane_depth(self.part(id, i, j)?, self.ray(i, j))
    }

    /// What a shader knows of face `id` (for colouring reference frames
    /// like the scanline's); `None` for culled or clipped-away faces.
    pub fn face_info(&self, id: u32) -> Option<FaceInfo<'static>> {
        let face = self.faces.get(id as usize)?.first()?;
        let n = face.normal;
        let len = dot(n, n).sqrt();
        let unit = if len > 0.0 { n.map(|v| v / len) } else { n };
        Some(FaceInfo::new(
            id,
            face.front,
            Vec3::new(unit[0] as f32, unit[1] as f32, unit[2] as f32),
            face.mean_depth as f32,
        ))
    }

    /// Distance in pixels from pixel `(i, j)`'s sample to the boundary of
    /// face `id`'s drawn parts; infinity for background, culled or
    /// clipped-away faces.
    pub fn boundary_distance(&self, id: u32, i: usize, j: usize) -> f64 {
        let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
        self.faces.get(id as usize).map_or(f64::INFINITY, |parts| {
            parts
                .iter()
                .map(|p| part_distance(p, x, y))
                .fold(f64::INFINITY, f64::min)
        })
    }
}

fn part_distance(face: &Face, x: f64, y: f64) -> f64 {
    (0..face.screen.len())
        .map(|k| {
            segment_distance(
                [x, y],
                face.screen[k],
                face.screen[(k + 1) % face.screen.len()],
            )
        })
        .fold(f64::INFINITY, f64::min)
}

/// `v` turned as the reference view turns the mesh: `Rx(pitch) · Ry(yaw)`.
pub fn rotate(view: &ReferenceView, v: [f64; 3]) -> [f64; 3] {
    let (sy, cy) = view.yaw_deg.to_radians().sin_cos();
    let (sx, cx) = view.pitch_deg.to_radians().sin_cos();
    let y = [cy * v[0] + sy * v[2], v[1], -sy * v[0] + cy * v[2]];
    [y[0], cx * y[1] - sx * y[2], sx * y[1] + cx * y[2]]
}

/// Normalised, rotated, view-space positions of every vertex.
fn view_positions<M: Mesh + ?Sized>(mesh: &M, view: &ReferenceView, eye: f64) -> Vec<V3> {
    let p = |i: usize| mesh.position(i).map(f64::from);
    let n = mesh.vertex_count();
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for i in 0..n {
        let v = p(i);
        for a in 0..3 {
            lo[a] = lo[a].min(v[a]);
            hi[a] = hi[a].max(v[a]);
        }
    }
    let c = [
        (lo[0] + hi[0]) / 2.0,
        (lo[1] + hi[1]) / 2.0,
        (lo[2] + hi[2]) / 2.0,
    ];
    let r = (0..n)
        .map(|i| dot(sub(p(i), c), sub(p(i), c)).sqrt())
        .fold(0.0f64, f64::max);
    let r = if r > 0.0 { r } else { 1.0 };
    (0..n)
        .map(|i| {
            // Ry(yaw), then Rx(pitch), then the eye at (0, 0, 3).
            let x = rotate(view, sub(p(i), c).map(|v| v / r));
            [x[0], x[1], x[2] - eye]
        })
        .collect()
}

/// Sutherland-Hodgman against the near (`-z >= near`) and far (`-z <= far`)
/// planes in view space.
/// Values are interpolated at the cuts as positions are.
fn clip_depth(corners: &[(V3, Values)], (near, far): (f64, f64)) -> Vec<(V3, Values)> {
    let near = |p: V3| -p[2] - near;
    let far = |p: V3| far + p[2];
    let mut poly = corners.to_vec();
    for plane in [&near as &dyn Fn(V3) -> f64, &far] {
        let mut out = Vec::with_capacity(poly.len() + 1);
        for k in 0..poly.len() {
            let (a, b) = (poly[(k + poly.len() - 1) % poly.len()], poly[k]);
            let (da, db) = (plane(a.0), plane(b.0));
            if (da >= 0.0) != (db >= 0.0) {
                let t = da / (da - db);
                let lerp = |p: V3, q: V3| core::array::from_fn(|m| p[m] + (q[m] - p[m]) * t);
                out.push((lerp(a.0, b.0), lerp(a.1, b.1)));
            }
            if db >= 0.0 {
                out.push(b);
            }
        }
        poly = out;
        if poly.is_empty() {
            break;
        }
    }
    poly
}

/// Whether `poly` is a quad whose four turns all have one sign.
fn strictly_convex(poly: &[[f64; 2]]) -> bool {
    if poly.len() != 4 {
        return false;
    }
    let turn = |k: usize| {
        let (a, b, c) = (poly[k], poly[(k + 1) % 4], poly[(k + 2) % 4]);
        (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
    };
    let turns = [turn(0), turn(1), turn(2), turn(3)];
    turns.iter().all(|&t| t > 0.0) || turns.iter().all(|&t| t < 0.0)
}

/// Even-odd test with the half-open rule: an edge counts when it spans
/// `y` (top inclusive) and crosses at or left of `x`.
fn inside(poly: &[[f64; 2]], x: f64, y: f64) -> bool {
    let mut odd = false;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if (a[1] <= y) != (b[1] <= y) {
            let cross = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if cross <= x {
                odd = !odd;
            }
        }
    }
    odd
}

fn plane_depth(face: &Face, ray: V3) -> Option<f64> {
    let denom = dot(face.normal, ray);
    let t = face.offset / denom;
    (denom != 0.0 && t.is_finite() && t > 0.0).then_some(t)
}

fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (ex, ey) = (a[0] + dx * t - p[0], a[1] + dy * t - p[1]);
    (ex * ex + ey * ey).sqrt()
}
