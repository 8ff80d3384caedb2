//! What a firmware's renderer needs for a mesh over the views it will
//! show: the largest counts over a grid of views, as one [`Capacities`]
//! value, and the line to paste (`examples/needs.rs` prints it;
//! `tests/needs.rs` draws every view it covers at exactly those
//! capacities).

use std::format;
use std::string::String;
use std::vec::Vec;

use zline::{Camera, Capacities, Cull, Depth16, FnSink, FrameStats, Mesh, reference_model};

/// The views a firmware will show: the reference view, the mesh turned to
/// every yaw in `yaws` at every pitch in `pitches`, with each cull in
/// `culls`.
#[derive(Debug, Clone, PartialEq)]
pub struct Views {
    /// Frame size, pixels.
    pub size: (u16, u16),
    /// Yaw angles, degrees.
    pub yaws: Vec<f32>,
    /// Pitch angles, degrees.
    pub pitches: Vec<f32>,
    /// Cull modes.
    pub culls: Vec<Cull>,
}

impl Views {
    /// Every `yaw_step` degrees of a full turn, every `pitch_step` degrees
    /// from -90 to 90, culled and not, at `size`.
    pub fn grid(size: (u16, u16), yaw_step: f32, pitch_step: f32) -> Self {
        let yaws = (0..)
            .map(|k| k as f32 * yaw_step)
            .take_while(|&y| y < 360.0)
            .collect();
        let pitches = (0..)
            .map(|k| -90.0 + k as f32 * pitch_step)
            .take_while(|&p| p <= 90.0)
            .collect();
        Self {
            size,
            yaws,
            pitches,
            culls: std::vec![Cull::None, Cull::Back],
        }
    }

    /// Each view: (yaw, pitch, cull).
    pub fn each(&self) -> impl Iterator<Item = (f32, f32, Cull)> + '_ {
        self.culls.iter().flat_map(move |&cull| {
            self.pitches
                .iter()
                .flat_map(move |&pitch| self.yaws.iter().map(move |&yaw| (yaw, pitch, cull)))
        })
    }

    /// The views in words, for the comment above the pasted line.
    pub fn describe(&self) -> String {
        let range = |v: &[f32]| match (v.first(), v.last()) {
            (Some(a), Some(b)) if v.len() > 1 => {
                format!("{a}..={b} every {}", v[1] - v[0])
            }
            (Some(a), _) => format!("{a}"),
            _ => String::from("none"),
        };
        let culls: Vec<&str> = self
            .culls
            .iter()
            .map(|c| match c {
                Cull::None => "none",
                Cull::Back => "back",
            })
            .collect();
        format!(
            "{}x{}, yaw {} deg, pitch {} deg, cull {}",
            self.size.0,
            self.size.1,
            range(&self.yaws),
            range(&self.pitches),
            culls.join(" and ")
        )
    }
}

/// The largest counts of `mesh` over `views` (z16; the counts are the same
/// for z24), each view drawn in storage with room for any view.
pub fn peak<M: Mesh>(mesh: &M, views: &Views) -> Result<FrameStats, String> {
    let (w, h) = views.size;
    let room = Capacities::worst_case(
        &zline::MeshCounts {
            vertices: mesh.vertex_count(),
            faces: mesh.face_count(),
            corners: (0..mesh.face_count()).map(|f| mesh.face(f).len()).sum(),
            shared_plane_faces: mesh.shared_planes().len(),
        },
        usize::from(w),
    );
    let mut renderer =
        zline::host::host_renderer::<u32, Depth16>(&room, w, h, 0).map_err(|e| e.to_string())?;
    let camera = Camera::reference(w, h);
    let mut peak = FrameStats::default();
    for (yaw, pitch, cull) in views.each() {
        let model = reference_model(mesh, yaw, pitch).map_err(|e| e.to_string())?;
        renderer.clear();
        renderer
            .draw_mesh(mesh, &model, &camera, cull, |f| f.face)
            .map_err(|e| format!("yaw {yaw} pitch {pitch} {cull:?}: {e}"))?;
        let stats = renderer
            .render(&mut FnSink(|_: u16, _: &[u32], _: &[u16]| Ok::<(), ()>(())))
            .map_err(|e| format!("yaw {yaw} pitch {pitch} {cull:?}: {e:?}"))?;
        peak = peak.max(stats);
    }
    Ok(peak)
}

/// The capacities `mesh` needs over `views`: the peak counts, and its
/// vertex cache; `margin_percent` more of each count (rounded up) for the
/// views between them.
pub fn capacities<M: Mesh>(
    mesh: &M,
    views: &Views,
    margin_percent: u32,
) -> Result<Capacities, String> {
    let peak = peak(mesh, views)?;
    let grow = |n: usize| n + (n * margin_percent as usize).div_ceil(100);
    let exact = Capacities::from_stats(&peak, usize::from(views.size.0));
    Ok(Capacities {
        width: exact.width,
        vertices: grow(exact.vertices).min(1 << 16),
        polygons: grow(exact.polygons),
        corners: grow(exact.corners),
        active_polygons: grow(exact.active_polygons),
        pooled_edges: grow(exact.pooled_edges),
        mesh_vertices: mesh.vertex_count(),
    })
}

/// `caps` as the one line to paste into a firmware.
pub fn line(caps: &Capacities) -> String {
    format!(
        "const CAPS: zline::Capacities = zline::Capacities {{ width: {}, vertices: {}, polygons: {}, corners: {}, active_polygons: {}, pooled_edges: {}, mesh_vertices: {} }};",
        caps.width,
        caps.vertices,
        caps.polygons,
        caps.corners,
        caps.active_polygons,
        caps.pooled_edges,
        caps.mesh_vertices
    )
}
