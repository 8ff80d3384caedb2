//! The sweep's measurements: one scene (a mesh at a frame size, the
//! reference view), every configuration timed in interleaved rounds,
//! compared with the float64 reference, its memory read off.

use std::path::Path;
use std::time::Instant;

use zline::Mesh;
use zline::Shading;
use zline::host::{HostMesh, QuantizedHostMesh};
use zline::{Camera, Cull, reference_model};
use zline::{Depth16, Depth24};
use zline_lab::methods::{
    BACKGROUND, Memory, Method, MethodFrame, MethodRenderer, ReferenceCamera, ReferenceFrame,
    ReferenceView, compare,
};

/// A method with a depth format (z16 or z24, for the methods that store
/// depth) and a front end (`f32`, or the integer path of a quantized mesh).
#[derive(Debug, Clone, Copy)]
pub struct Config {
    method: Method,
    z24: bool,
    quantized: bool,
}

impl Config {
    /// A configuration.
    pub fn new(method: Method, z24: bool, quantized: bool) -> Self {
        Self {
            method,
            z24,
            quantized,
        }
    }

    /// `scanline z24 int`, `bands:8 z16`, `interval`, ...
    pub fn label(&self) -> String {
        let mut s = self.method.name();
        if self.method.stores_depth() {
            s += if self.z24 { " z24" } else { " z16" };
        }
        if self.quantized {
            s += " int";
        }
        s
    }
}

/// What one configuration measured on one scene (or summed over several).
#[derive(Debug, Clone, Default)]
pub struct Sample {
    /// Median frame time, ms (a sum of medians after [`Sample::add`]).
    pub median_ms: f64,
    /// Pixels compared with the reference.
    pub pixels: usize,
    /// Pixels whose face differs from the reference's.
    pub mismatches: usize,
    /// Of those, within 1/16 px of an edge.
    pub excused_at_edges: usize,
    /// Of those, depth ties (0.1 %).
    pub excused_as_ties: usize,
    /// The rest.
    pub hard: usize,
    /// Largest |stored depth − exact depth of the reference's surface| in
    /// the format's LSB, over pixels that show the reference's face.
    pub max_depth_error_lsb: Option<f64>,
    /// Memory of the last frame.
    pub memory: Memory,
}

impl Sample {
    /// Adds `other`'s time and counts (the largest depth error).
    pub fn add(&mut self, other: &Sample) {
        self.median_ms += other.median_ms;
        self.pixels += other.pixels;
        self.mismatches += other.mismatches;
        self.excused_at_edges += other.excused_at_edges;
        self.excused_as_ties += other.excused_as_ties;
        self.hard += other.hard;
        self.max_depth_error_lsb = match (self.max_depth_error_lsb, other.max_depth_error_lsb) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        self.memory = other.memory;
    }
}

/// A mesh at one frame size, seen from the reference view.
pub struct Scene {
    name: String,
    mesh: HostMesh,
    quantized: QuantizedHostMesh,
    camera: Camera,
    reference_camera: ReferenceCamera,
    view: ReferenceView,
}

impl Scene {
    /// The scene of `mesh` at `width` x `height`.
    pub fn new(name: &str, mesh: HostMesh, width: u16, height: u16) -> Result<Self, String> {
        Self::with_camera(name, mesh, width, height, ReferenceCamera::STANDARD)
    }

    /// The scene seen by `camera` (both the methods and the reference).
    pub fn with_camera(
        name: &str,
        mesh: HostMesh,
        width: u16,
        height: u16,
        camera: ReferenceCamera,
    ) -> Result<Self, String> {
        let quantized = QuantizedHostMesh::new(&mesh).map_err(|e| format!("{name}: {e}"))?;
        Ok(Self {
            name: name.into(),
            mesh,
            quantized,
            camera: camera.camera(width, height),
            reference_camera: camera,
            view: ReferenceView {
                width: usize::from(width),
                height: usize::from(height),
                yaw_deg: 30.0,
                pitch_deg: 20.0,
                cull_back: false,
            },
        })
    }

    /// Every configuration once per round, `rounds` timed rounds after a
    /// warm-up round; with `accuracy`, the warm-up frames are compared
    /// with the reference. With `rounds` 0 only memory is measured.
    pub fn run(
        &self,
        configs: &[Config],
        rounds: usize,
        accuracy: bool,
    ) -> Result<Vec<Sample>, String> {
        let (w, h) = (self.camera.width, self.camera.height);
        let mut z16 = MethodRenderer::<Depth16>::new(w, h)?;
        let mut z24 = MethodRenderer::<Depth24>::new(w, h)?;
        z16.set_reference_camera(self.reference_camera);
        z24.set_reference_camera(self.reference_camera);
        let model =
            reference_model(&self.mesh, 30.0, 20.0).map_err(|e| format!("{}: {e}", self.name))?;
        let quantized = self
            .quantized
            .mesh()
            .map_err(|e| format!("{}: {e:?}", self.name))?;
        let reference = accuracy
            .then(|| ReferenceFrame::render_with(&self.mesh, &self.view, &self.reference_camera));
        let mut times = vec![Vec::with_capacity(rounds); configs.len()];
        let mut samples = vec![Sample::default(); configs.len()];
        for round in 0..=rounds {
            for (k, c) in configs.iter().enumerate() {
                let start = Instant::now();
                let frame = match (c.z24, c.quantized) {
                    (false, false) => self.frame(&mut z16, c.method, &self.mesh, &model)?,
                    (true, false) => self.frame(&mut z24, c.method, &self.mesh, &model)?,
                    (false, true) => self.frame(&mut z16, c.method, &quantized, &model)?,
                    (true, true) => self.frame(&mut z24, c.method, &quantized, &model)?,
                };
                let elapsed = start.elapsed().as_secs_f64() * 1e3;
                if round == 0 {
                    samples[k].memory = frame.memory;
                    if let Some(reference) = &reference {
                        self.compare(&mut samples[k], reference, &frame, c.z24);
                    }
                } else {
                    times[k].push(elapsed);
                }
            }
        }
        for (s, mut t) in samples.iter_mut().zip(times) {
            t.sort_by(f64::total_cmp);
            s.median_ms = t.get(t.len() / 2).copied().unwrap_or(f64::NAN);
        }
        Ok(samples)
    }

    fn frame<D: zline::DepthFormat, M: Mesh>(
        &self,
        r: &mut MethodRenderer<D>,
        method: Method,
        mesh: &M,
        model: &zline::Mat4,
    ) -> Result<MethodFrame, String>
    where
        D::Value: Into<u32>,
    {
        r.render(
            method,
            mesh,
            model,
            &self.camera,
            Cull::None,
            &Shading::lambert(),
            &self.view,
        )
        .map_err(|e| format!("{} by {}: {e}", self.name, method.name()))
    }

    fn compare(&self, s: &mut Sample, reference: &ReferenceFrame, frame: &MethodFrame, z24: bool) {
        let c = compare(reference, &frame.faces);
        s.pixels = c.pixels;
        s.mismatches = c.mismatches;
        s.excused_at_edges = c.excused_at_edges;
        s.excused_as_ties = c.excused_as_ties;
        s.hard = c.hard;
        let Some(depths) = &frame.depths else { return };
        // The depth the projection gives the reference's surface at view
        // distance d: z_ndc from the camera's own matrix, mapped to 0..1.
        let p = &self.camera.projection.m;
        let (a, b) = (f64::from(p[2][2]), f64::from(p[2][3]));
        let (c3, d3) = (f64::from(p[3][2]), f64::from(p[3][3]));
        let scale = f64::from(if z24 { 1u32 << 24 } else { 1 << 16 });
        let mut worst = 0.0f64;
        for ((&drawn, &expected), (&depth, &d)) in frame
            .faces
            .iter()
            .zip(&reference.ids)
            .zip(depths.iter().zip(&reference.depths))
        {
            if drawn != expected || drawn == BACKGROUND {
                continue;
            }
            let ndc = (a * -d + b) / (c3 * -d + d3);
            let exact = (ndc + 1.0) * 0.5 * scale;
            worst = worst.max((f64::from(depth) - exact).abs());
        }
        s.max_depth_error_lsb = Some(worst);
    }
}

/// A file's name without its extension.
pub fn stem(path: &Path) -> String {
    path.file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
}

/// Triangles of a mesh once its faces are fanned.
pub fn triangles(mesh: &HostMesh) -> usize {
    (0..mesh.face_count())
        .map(|f| mesh.face(f).len().saturating_sub(2))
        .sum()
}

/// The peers' points from `cargo bench-peers`' CSVs: for each peer row
/// with a row for every mesh in `ours` at `size` without culling, (name,
/// time, wrong-face %). A peer's time on a mesh is its time over the
/// bench's `zline z16` in the bench's own run (both are ratios to its
/// `zline z24`) times our scanline z16 time here, so the two runs'
/// machines need not match. The bench gives wrong faces as a share of
/// the object's pixels (its last column); the chart's share is of the
/// frames, `pixels` being the frame's pixels times meshes.
pub fn peers(
    path: &Path,
    size: &str,
    ours: &[(String, f64)],
    pixels: f64,
) -> Result<Vec<(String, f64, f64)>, String> {
    let (Ok(times), Ok(wrong)) = (
        std::fs::read_to_string(path),
        std::fs::read_to_string(path.with_file_name(format!("{}_wrong_faces.csv", stem(path)))),
    ) else {
        return Ok(Vec::new());
    };
    let rows = |text: &str| -> Vec<Vec<String>> {
        text.lines()
            .skip(1)
            .map(|l| l.split(',').map(String::from).collect())
            .collect()
    };
    let (times, wrong) = (rows(&times), rows(&wrong));
    let mut out = Vec::new();
    for peer in [
        "euc",
        "embedded-3dgfx unlit",
        "embedded-3dgfx lit",
        "embedded-3dgfx raster shared",
    ] {
        let (mut ms, mut wrong_pixels) = (0.0, 0.0);
        let mut complete = true;
        for (mesh, our_ms) in ours {
            let find = |rows: &[Vec<String>], renderer: &str, col: usize| {
                rows.iter()
                    .find(|r| {
                        r.len() > col
                            && r[0] == *mesh
                            && r[1] == size
                            && r[2] == "none"
                            && r[3] == renderer
                    })
                    .and_then(|r| r[col].parse::<f64>().ok())
            };
            match (
                find(&times, peer, 6),
                find(&times, "zline z16", 6),
                find(&wrong, peer, 4),
                find(&wrong, peer, 5),
            ) {
                (Some(ratio), Some(z16), Some(w), Some(object)) if z16 > 0.0 => {
                    ms += ratio / z16 * our_ms;
                    wrong_pixels += w * object;
                }
                _ => complete = false,
            }
        }
        if complete {
            out.push((format!("{peer} (peer)"), ms, 100.0 * wrong_pixels / pixels));
        }
    }
    Ok(out)
}
