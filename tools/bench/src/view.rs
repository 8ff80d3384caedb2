//! The view contract every renderer draws: zline's reference view
//! (`zline_lab::methods::ReferenceFrame`, `examples/render.rs`), restated here
//! in `f32` for the peers.
//!
//! * The mesh is an OBJ file read by `zline::host::HostMesh::from_obj`;
//!   the peers draw each face as the fan of triangles from its corner 0,
//!   and every triangle keeps the id (index) of its face.
//! * Normalise `p' = (p - c) / r` (`c` the centre of the bounding box of
//!   all vertices, `r` the largest distance from `c` to a vertex), then
//!   rotate `p'' = Rx(pitch) · Ry(yaw) · p'` (right-handed, column vectors:
//!   `Ry` turns z towards x, `Rx` turns y towards z).
//! * Eye at (0, 0, 3) looking down -Z, +Y up, vertical field of view 45°,
//!   aspect W/H, near 0.1, far 10, OpenGL-style perspective.
//! * Pixel (i, j) is sampled at (i + 0.5, j + 0.5), y down; the nearest
//!   surface wins.
//! * Culling `none` or `back` (back: faces whose projected corners run
//!   clockwise on screen, the OBJ counter-clockwise-front convention).
//! * Output: a W×H Rgb565 frame, one colour per face: flat, two-sided
//!   Lambert with zline's `Shading::lambert()` constants ([`LAMBERT_BASE`],
//!   [`LAMBERT_LIGHT`], [`LAMBERT_AMBIENT`]), computed by every renderer
//!   inside its timed frame (zline by `Shading::lambert()` itself, the
//!   peers by [`lambert_rgb565`] of a normal turned to the viewer), and,
//!   where the renderer can, a face id per pixel ([`BACKGROUND`] where
//!   none).
//!
//! Nothing that depends on the view's colours is prepared before timing:
//! what a renderer gets once per mesh is what its users keep with the
//! mesh (positions, faces, and for the peers per-triangle unit normals in
//! object space, [`Scene::triangle_normals`], as embedded-3dgfx's
//! `Geometry::normals` and a vertex buffer's normals are).

use std::path::Path;

use zline::Mesh as _;
use zline::host::{DEFAULT_CREASE_DEGREES, HostMesh};
use zline_lab::methods::ReferenceView;
use zline_lab::textures::Rgb565Texture;

/// Face id of pixels that no face covers.
pub const BACKGROUND: u32 = u32::MAX;
/// Distance from the eye to the origin of the normalised mesh.
pub const EYE_DISTANCE: f32 = 3.0;
/// Vertical field of view, degrees.
pub const FOV_Y_DEG: f32 = 45.0;
/// Near clip plane.
pub const NEAR: f32 = 0.1;
/// Far clip plane.
pub const FAR: f32 = 10.0;
/// Default rotation about +Y, degrees.
pub const DEFAULT_YAW_DEG: f32 = 30.0;
/// Default rotation about +X (after yaw), degrees.
pub const DEFAULT_PITCH_DEG: f32 = 20.0;

/// Lambert surface colour (zline's `Shading::lambert()`).
pub const LAMBERT_BASE: [u8; 3] = [230, 220, 200];
/// Direction towards the light in view space, before normalising
/// (zline's `Shading::lambert()`).
pub const LAMBERT_LIGHT: [f32; 3] = [-0.4, 0.5, 0.77];
/// Ambient fraction (zline's `Shading::lambert()`).
pub const LAMBERT_AMBIENT: f32 = 0.2;

/// A 4×4 matrix, row-major, applied to column vectors (`p' = M · p`).
pub type Mat4 = [[f32; 4]; 4];

/// Which faces are left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cull {
    /// Draw every face.
    None,
    /// Leave out faces whose projection runs clockwise on screen.
    Back,
}

impl Cull {
    /// The name used on the command line and in the CSV.
    pub fn name(self) -> &'static str {
        match self {
            Cull::None => "none",
            Cull::Back => "back",
        }
    }

    /// Parses `none` or `back`.
    pub fn parse(s: &str) -> Result<Self, String> {
        match s {
            "none" => Ok(Cull::None),
            "back" => Ok(Cull::Back),
            _ => Err(format!("--cull: unknown '{s}' (none, back)")),
        }
    }
}

/// One view of a mesh: frame size, rotation and culling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Frame width in pixels.
    pub width: u16,
    /// Frame height in pixels.
    pub height: u16,
    /// Rotation about +Y, degrees.
    pub yaw_deg: f32,
    /// Rotation about +X (after yaw), degrees.
    pub pitch_deg: f32,
    /// Which faces are left out.
    pub cull: Cull,
}

impl View {
    /// `WxH`, as in the CSV.
    pub fn size_label(&self) -> String {
        format!("{}x{}", self.width, self.height)
    }

    /// The same view for zline's float64 reference renderer.
    pub fn reference(&self) -> ReferenceView {
        ReferenceView {
            width: usize::from(self.width),
            height: usize::from(self.height),
            yaw_deg: f64::from(self.yaw_deg),
            pitch_deg: f64::from(self.pitch_deg),
            cull_back: self.cull == Cull::Back,
        }
    }

    /// `Rx(pitch) · Ry(yaw)` as a 3×3 rotation, row-major.
    pub fn rotation(&self) -> [[f32; 3]; 3] {
        let (sy, cy) = self.yaw_deg.to_radians().sin_cos();
        let (sx, cx) = self.pitch_deg.to_radians().sin_cos();
        let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
        let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
        let mut r = [[0.0; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..3).map(|k| rx[i][k] * ry[k][j]).sum();
            }
        }
        r
    }

    /// World to view space: the eye at (0, 0, 3) looking down -Z.
    pub fn view_matrix(&self) -> Mat4 {
        translation([0.0, 0.0, -EYE_DISTANCE])
    }

    /// OpenGL-style perspective: 45° vertical field of view, aspect W/H,
    /// near 0.1, far 10 (clip z from -w to w).
    pub fn projection(&self) -> Mat4 {
        let f = 1.0 / (FOV_Y_DEG.to_radians() / 2.0).tan();
        let aspect = f32::from(self.width) / f32::from(self.height);
        [
            [f / aspect, 0.0, 0.0, 0.0],
            [0.0, f, 0.0, 0.0],
            [
                0.0,
                0.0,
                (FAR + NEAR) / (NEAR - FAR),
                2.0 * FAR * NEAR / (NEAR - FAR),
            ],
            [0.0, 0.0, -1.0, 0.0],
        ]
    }
}

/// A loaded mesh with what every renderer needs of it.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The mesh's name (file name without `.obj`).
    pub name: String,
    /// The mesh as zline reads it.
    pub mesh: HostMesh,
    /// Every face as a fan of triangles from its corner 0 (vertex indices).
    pub triangles: Vec<[u32; 3]>,
    /// The face of each triangle.
    pub triangle_faces: Vec<u32>,
    /// Centre of the bounding box of all vertices.
    pub centre: [f32; 3],
    /// Largest distance from the centre to a vertex (1 for a single point).
    pub radius: f32,
}

impl Scene {
    /// Reads an OBJ file. Errors name the file.
    pub fn load(path: &Path) -> Result<Self, String> {
        let shown = path.display();
        let bytes = std::fs::read(path).map_err(|e| format!("{shown}: {e}"))?;
        let mesh = HostMesh::from_obj(&bytes).map_err(|e| format!("{shown}: {e}"))?;
        let name = path
            .file_stem()
            .map_or_else(|| shown.to_string(), |s| s.to_string_lossy().into_owned());
        Self::new(name, mesh).map_err(|e| format!("{shown}: {e}"))
    }

    /// Triangulates and measures `mesh`.
    pub fn new(name: String, mesh: HostMesh) -> Result<Self, String> {
        if mesh.positions.is_empty() {
            return Err("no vertices".into());
        }
        if mesh.face_starts.is_empty() {
            return Err("no faces".into());
        }
        let vertex_count = mesh.positions.len();
        let mut triangles = Vec::with_capacity(mesh.corners.len());
        let mut triangle_faces = Vec::with_capacity(mesh.corners.len());
        for f in 0..mesh.face_starts.len() {
            let corners = face_corners(&mesh, f).ok_or_else(|| format!("face {f}: bad corners"))?;
            if corners.len() < 3 || corners.iter().any(|&c| usize::from(c) >= vertex_count) {
                return Err(format!("face {f}: bad corners"));
            }
            for k in 1..corners.len() - 1 {
                triangles.push([
                    u32::from(corners[0]),
                    u32::from(corners[k]),
                    u32::from(corners[k + 1]),
                ]);
                triangle_faces.push(f as u32);
            }
        }
        let (centre, radius) = bounding_sphere(&mesh.positions);
        Ok(Self {
            name,
            mesh,
            triangles,
            triangle_faces,
            centre,
            radius,
        })
    }

    /// Number of faces (polygons) in the OBJ file.
    pub fn face_count(&self) -> usize {
        self.mesh.face_starts.len()
    }

    /// The model matrix `Rx(pitch) · Ry(yaw) · S(1/r) · T(-c)`.
    pub fn model(&self, view: &View) -> Mat4 {
        let r = view.rotation();
        let s = 1.0 / self.radius;
        let c = self.centre;
        let mut m = [[0.0; 4]; 4];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = r[i][j] * s;
            }
            m[i][3] = -(0..3).map(|k| r[i][k] * c[k]).sum::<f32>() * s;
        }
        m[3][3] = 1.0;
        m
    }

    /// Model, view and projection in one: object space to clip space.
    pub fn mvp(&self, view: &View) -> Mat4 {
        mul(
            &view.projection(),
            &mul(&view.view_matrix(), &self.model(view)),
        )
    }

    /// Unit normal of every fan triangle in object space, computed once
    /// per mesh (what a peer's user keeps with the mesh: embedded-3dgfx's
    /// `Geometry::normals`, a vertex buffer's normals). The normal is the
    /// face's (Newell) normal, or, for a face that is not planar
    /// (`zline::Mesh::face_is_planar`), the triangle's own, as zline's
    /// pipeline and reference shade such faces. The model matrix is a
    /// rotation times a uniform scale, so these turn into view space by
    /// the rotation alone.
    pub fn triangle_normals(&self) -> Vec<[f32; 3]> {
        let p = &self.mesh.positions;
        let face_normals: Vec<[f32; 3]> = (0..self.face_count())
            .map(|f| {
                let corners = face_corners(&self.mesh, f).unwrap_or(&[]);
                newell(corners.iter().map(|&i| p[usize::from(i)]))
            })
            .collect();
        self.triangles
            .iter()
            .zip(&self.triangle_faces)
            .map(|(t, &f)| {
                let f = f as usize;
                let triangle = face_corners(&self.mesh, f).is_some_and(|c| c.len() == 3);
                if triangle || self.mesh.face_is_planar(f) {
                    face_normals[f]
                } else {
                    newell(t.iter().map(|&i| p[i as usize]))
                }
            })
            .collect()
    }

    /// The light direction and the eye in object space for `view`: with
    /// the model `p_world = R·(p - c)/r`, `light = Rᵀ·l` and `eye = c +
    /// r·Rᵀ·(0, 0, 3)`. A peer computes this once per frame (inside its
    /// timed frame: a moving model changes it every frame), then a face's
    /// Lambert term is one dot product of its object-space normal.
    pub fn object_light(&self, view: &View) -> ObjectLight {
        let r = view.rotation();
        let back = |v: [f32; 3]| -> [f32; 3] {
            [0, 1, 2].map(|j| (0..3).map(|i| r[i][j] * v[i]).sum::<f32>())
        };
        let light = back(light_direction());
        let eye = back([0.0, 0.0, EYE_DISTANCE]);
        ObjectLight {
            light,
            eye: [0, 1, 2].map(|a| self.centre[a] + self.radius * eye[a]),
        }
    }

    /// Each face's Lambert colour (for a face that is not planar, its first
    /// triangle's), for the reference frame's image dump only (untimed).
    pub fn face_colors(&self, view: &View) -> Vec<u16> {
        let normals = self.triangle_normals();
        let light = self.object_light(view);
        let mut colors = vec![0; self.face_count()];
        for ((t, n), &f) in self
            .triangles
            .iter()
            .zip(&normals)
            .zip(&self.triangle_faces)
            .rev()
        {
            let p = self.mesh.positions[t[0] as usize];
            let d = dot(n, &light.light);
            colors[f as usize] = lambert_rgb565(if light.front(n, &p) { d } else { -d });
        }
        colors
    }

    /// The unshaded Lambert base colour, for renderers with one colour per
    /// mesh.
    pub fn base_color() -> u16 {
        let [r, g, b] = LAMBERT_BASE;
        rgb565(r, g, b)
    }
}

/// The mesh read for smooth shading and textures, for the `gouraud` and
/// `textured` rows: `HostMesh::from_obj_smooth(bytes,
/// DEFAULT_CREASE_DEGREES)` (a vertex for each different position,
/// texture coordinate and normal its corners name; the file's normals, or
/// normals from the faces around a position within 60°), triangulated and
/// measured as [`Scene`] is. Its faces are the flat mesh's, in the same
/// order and with the same corners' positions (checked), so face ids
/// compare with the flat reference's.
#[derive(Debug, Clone)]
pub struct SmoothScene {
    /// The smooth mesh as a [`Scene`]; its `mesh.vertex_normals` are the
    /// vertex normals every Gouraud row lights.
    pub scene: Scene,
    /// `NAME_texture.png` beside `NAME.obj`, as raw Rgb565 texels row by
    /// row from the top (OBJ's `v = 1`), when there is one and the mesh
    /// has texture coordinates: the textured rows' texture.
    pub texture: Option<Rgb565Texture>,
}

impl SmoothScene {
    /// Reads `path` again for smooth shading, and its texture if any.
    pub fn load(path: &Path, flat: &Scene) -> Result<Self, String> {
        let shown = path.display();
        let bytes = std::fs::read(path).map_err(|e| format!("{shown}: {e}"))?;
        let mesh = HostMesh::from_obj_smooth(&bytes, DEFAULT_CREASE_DEGREES)
            .map_err(|e| format!("{shown}: smooth: {e}"))?;
        if mesh.vertex_normals.len() != mesh.positions.len() {
            return Err(format!("{shown}: smooth: not every vertex has a normal"));
        }
        let scene = Scene::new(flat.name.clone(), mesh).map_err(|e| format!("{shown}: {e}"))?;
        let same_faces = scene.face_count() == flat.face_count()
            && scene.triangles.len() == flat.triangles.len()
            && scene.triangle_faces == flat.triangle_faces
            && scene.triangles.iter().zip(&flat.triangles).all(|(s, f)| {
                (0..3).all(|k| {
                    scene.mesh.positions[s[k] as usize] == flat.mesh.positions[f[k] as usize]
                })
            });
        if !same_faces || scene.centre != flat.centre || scene.radius != flat.radius {
            return Err(format!(
                "{shown}: the smooth mesh's faces differ from the flat mesh's"
            ));
        }
        let png = path.with_file_name(format!("{}_texture.png", flat.name));
        let texture = if png.is_file() && !scene.mesh.uvs.is_empty() {
            Some(Rgb565Texture::read(&png, 1)?)
        } else {
            None
        };
        Ok(Self { scene, texture })
    }
}

/// The light and the eye in object space ([`Scene::object_light`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectLight {
    /// Unit direction towards the light.
    pub light: [f32; 3],
    /// The eye.
    pub eye: [f32; 3],
}

impl ObjectLight {
    /// Whether the side of a plane through `p` with normal `n` that the
    /// normal points to faces the eye.
    #[inline(always)]
    pub fn front(&self, n: &[f32; 3], p: &[f32; 3]) -> bool {
        let to_eye = [0, 1, 2].map(|a| self.eye[a] - p[a]);
        dot(n, &to_eye) > 0.0
    }
}

/// The unit direction towards the light in view space
/// ([`LAMBERT_LIGHT`] normalised).
pub fn light_direction() -> [f32; 3] {
    normalised(LAMBERT_LIGHT)
}

/// Flat Lambert with zline's `Shading::lambert()` rule as Rgb565: `d` is
/// `n · l` for the unit normal `n` turned to the viewer (two-sided) and
/// the unit light direction `l`; `k = ambient + (1 - ambient)·max(0, d)`,
/// each channel `base·k` rounded, then packed (truncating) to Rgb565.
#[inline(always)]
pub fn lambert_rgb565(d: f32) -> u16 {
    let k = LAMBERT_AMBIENT + (1.0 - LAMBERT_AMBIENT) * d.max(0.0);
    let k = if k.is_finite() {
        k.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let [r, g, b] = LAMBERT_BASE.map(|v| (f32::from(v) * k + 0.5) as u8);
    rgb565(r, g, b)
}

/// `a · b`.
#[inline(always)]
pub fn dot(a: &[f32; 3], b: &[f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Corners of face `f`.
pub fn face_corners(mesh: &HostMesh, f: usize) -> Option<&[u16]> {
    let start = *mesh.face_starts.get(f)? as usize;
    let end = mesh
        .face_starts
        .get(f + 1)
        .map_or(mesh.corners.len(), |&e| e as usize);
    mesh.corners.get(start..end)
}

/// Packs 8-bit channels into Rgb565 (truncating).
pub fn rgb565(r: u8, g: u8, b: u8) -> u16 {
    (u16::from(r >> 3) << 11) | (u16::from(g >> 2) << 5) | u16::from(b >> 3)
}

/// Newell's unit normal of the polygon `corners` (counter-clockwise
/// front); zero for a degenerate polygon.
fn newell(corners: impl Iterator<Item = [f32; 3]>) -> [f32; 3] {
    let mut pts: Vec<[f32; 3]> = corners.collect();
    // Relative to the first corner, so that far-off meshes keep their bits.
    let o = pts.first().copied().unwrap_or_default();
    for p in &mut pts {
        *p = [0, 1, 2].map(|a| p[a] - o[a]);
    }
    let mut n = [0.0f32; 3];
    for (k, p) in pts.iter().enumerate() {
        let q = pts[(k + 1) % pts.len()];
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    normalised(n)
}

/// `a · b`.
pub fn mul(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut m = [[0.0; 4]; 4];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

/// `m · (p, 1)`.
#[inline(always)]
pub fn transform(m: &Mat4, p: &[f32; 3]) -> [f32; 4] {
    let row = |r: &[f32; 4]| r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3];
    [row(&m[0]), row(&m[1]), row(&m[2]), row(&m[3])]
}

fn translation(t: [f32; 3]) -> Mat4 {
    [
        [1.0, 0.0, 0.0, t[0]],
        [0.0, 1.0, 0.0, t[1]],
        [0.0, 0.0, 1.0, t[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

fn normalised(v: [f32; 3]) -> [f32; 3] {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if len > 0.0 { v.map(|x| x / len) } else { v }
}

/// Bounding-box centre and largest distance to it, computed in `f64` as
/// the reference does.
fn bounding_sphere(positions: &[[f32; 3]]) -> ([f32; 3], f32) {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in positions {
        for a in 0..3 {
            lo[a] = lo[a].min(f64::from(p[a]));
            hi[a] = hi[a].max(f64::from(p[a]));
        }
    }
    let c = [0, 1, 2].map(|a| (lo[a] + hi[a]) / 2.0);
    let r = positions
        .iter()
        .map(|p| {
            let d = [0, 1, 2].map(|a| f64::from(p[a]) - c[a]);
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        })
        .fold(0.0f64, f64::max);
    let r = if r > 0.0 && (r as f32).is_normal() {
        r
    } else {
        1.0
    };
    (c.map(|v| v as f32), r as f32)
}
