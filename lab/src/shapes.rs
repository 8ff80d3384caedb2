//! Procedural meshes made by the project itself, for the simulator's
//! default scene, the firmware and the tests. Every face winds
//! counter-clockwise seen from outside.

use std::f32::consts::TAU;
use std::vec;
use std::vec::Vec;

use zline::host::HostMesh;

/// Building a [`HostMesh`] a vertex and a face at a time.
trait Build {
    /// Adds a position; its index.
    fn vertex(&mut self, p: [f32; 3]) -> u16;
    /// Adds a face of these corners.
    fn face(&mut self, corners: &[u16]);
}

impl Build for HostMesh {
    fn vertex(&mut self, p: [f32; 3]) -> u16 {
        self.positions.push(p);
        (self.positions.len() - 1) as u16
    }

    fn face(&mut self, corners: &[u16]) {
        self.face_starts.push(self.corners.len() as u32);
        self.corners.extend_from_slice(corners);
    }
}

/// A (p, q) torus knot: a tube of `sides` corners swept along the knot in
/// `segments` steps; `2 · segments · sides` triangles.
pub fn torus_knot(p: u32, q: u32, segments: usize, sides: usize, tube: f32) -> HostMesh {
    let mut mesh = HostMesh::default();
    for i in 0..segments {
        for j in 0..sides {
            mesh.vertex(torus_knot_point(p, q, (i, segments), (j, sides), tube));
        }
    }
    for i in 0..segments {
        for j in 0..sides {
            let at = |i: usize, j: usize| ((i % segments) * sides + j % sides) as u16;
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            mesh.face(&[a, c, b]);
            mesh.face(&[a, d, c]);
        }
    }
    mesh
}

/// [`torus_knot`] with texture coordinates: `u` from 0 to `repeats` along
/// the knot, `v` from 0 to 1 around the tube, the seams given their own
/// vertices (`(segments + 1) · (sides + 1)` of them) so no face spans
/// them; the same faces.
pub fn textured_torus_knot(
    p: u32,
    q: u32,
    segments: usize,
    sides: usize,
    tube: f32,
    repeats: f32,
) -> HostMesh {
    let mut mesh = HostMesh::default();
    for i in 0..=segments {
        for j in 0..=sides {
            mesh.vertex(torus_knot_point(p, q, (i, segments), (j, sides), tube));
            mesh.uvs.push([
                repeats * i as f32 / segments as f32,
                j as f32 / sides as f32,
            ]);
        }
    }
    for i in 0..segments {
        for j in 0..sides {
            let at = |i: usize, j: usize| (i * (sides + 1) + j) as u16;
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            mesh.face(&[a, c, b]);
            mesh.face(&[a, d, c]);
        }
    }
    mesh
}

/// The point of a (p, q) torus knot's tube at step `i` of `segments`
/// along the knot and `j` of `sides` around the tube.
fn torus_knot_point(
    p: u32,
    q: u32,
    (i, segments): (usize, usize),
    (j, sides): (usize, usize),
    tube: f32,
) -> [f32; 3] {
    let curve = |t: f32| {
        let r = 2.0 + libm::cosf(q as f32 * t);
        [
            r * libm::cosf(p as f32 * t),
            r * libm::sinf(p as f32 * t),
            libm::sinf(q as f32 * t),
        ]
    };
    // Whole turns give the first ring's point exactly.
    let t = TAU * (i % segments) as f32 / segments as f32;
    let (c, ahead) = (curve(t), curve(t + 1e-3));
    let tangent = normalize(sub(ahead, c));
    // A frame around the tangent: the normal points away from the
    // knot's axis, the binormal completes it.
    let binormal = normalize(cross(tangent, [c[0], c[1], c[2] + 1.0]));
    let normal = cross(binormal, tangent);
    let a = TAU * (j % sides) as f32 / sides as f32;
    let (s, k) = (libm::sinf(a) * tube, libm::cosf(a) * tube);
    [0, 1, 2].map(|d| c[d] + normal[d] * k + binormal[d] * s)
}

/// An icosphere of radius 1: the icosahedron with each triangle split in
/// four `subdivisions` times; `20 · 4^subdivisions` triangles.
pub fn icosphere(subdivisions: u32) -> HostMesh {
    let g = (1.0 + libm::sqrtf(5.0)) / 2.0;
    let mut points: Vec<[f32; 3]> = [
        [-1.0, g, 0.0],
        [1.0, g, 0.0],
        [-1.0, -g, 0.0],
        [1.0, -g, 0.0],
        [0.0, -1.0, g],
        [0.0, 1.0, g],
        [0.0, -1.0, -g],
        [0.0, 1.0, -g],
        [g, 0.0, -1.0],
        [g, 0.0, 1.0],
        [-g, 0.0, -1.0],
        [-g, 0.0, 1.0],
    ]
    .iter()
    .map(|&p| normalize(p))
    .collect();
    let mut faces: Vec<[u16; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoints = std::collections::HashMap::new();
        let mut mid = |a: u16, b: u16, points: &mut Vec<[f32; 3]>| {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (points[usize::from(a)], points[usize::from(b)]);
                points.push(normalize([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                (points.len() - 1) as u16
            })
        };
        let mut next = Vec::with_capacity(faces.len() * 4);
        for [a, b, c] in faces {
            let (ab, bc, ca) = (
                mid(a, b, &mut points),
                mid(b, c, &mut points),
                mid(c, a, &mut points),
            );
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    let mut mesh = HostMesh {
        positions: points,
        ..HostMesh::default()
    };
    for f in faces {
        mesh.face(&f);
    }
    mesh
}

/// A UV sphere of radius 1: `slices` meridians and `stacks` bands between
/// the poles; a triangle fan at each pole and two triangles per quad
/// between, so exactly `2 · slices · (stacks − 1)` triangles. `None` when
/// `slices < 3`, `stacks < 2` or the vertices overflow `u16` indices.
pub fn uv_sphere(slices: usize, stacks: usize) -> Option<HostMesh> {
    let rings = stacks.checked_sub(1)?;
    let vertices = slices.checked_mul(rings)?.checked_add(2)?;
    if slices < 3 || rings == 0 || vertices > usize::from(u16::MAX) + 1 {
        return None;
    }
    let mut mesh = HostMesh::default();
    let north = mesh.vertex([0.0, 1.0, 0.0]);
    for ring in 1..stacks {
        let polar = core::f32::consts::PI * ring as f32 / stacks as f32;
        for k in 0..slices {
            let azimuth = TAU * k as f32 / slices as f32;
            mesh.vertex([
                libm::sinf(polar) * libm::cosf(azimuth),
                libm::cosf(polar),
                -libm::sinf(polar) * libm::sinf(azimuth),
            ]);
        }
    }
    let south = mesh.vertex([0.0, -1.0, 0.0]);
    // Vertex `k` of ring `r` (1-based rings, from the north pole).
    let at = |r: usize, k: usize| (1 + (r - 1) * slices + k % slices) as u16;
    for k in 0..slices {
        mesh.face(&[north, at(1, k), at(1, k + 1)]);
    }
    for r in 1..rings {
        for k in 0..slices {
            let (a, b, c, d) = (at(r, k), at(r + 1, k), at(r + 1, k + 1), at(r, k + 1));
            mesh.face(&[a, b, c]);
            mesh.face(&[a, c, d]);
        }
    }
    for k in 0..slices {
        mesh.face(&[south, at(rings, k + 1), at(rings, k)]);
    }
    Some(mesh)
}

/// The UV sphere with exactly `triangles` triangles, for the classic
/// polygon counts (100, 2,500, 60,000): the most nearly square grid of
/// slices and stacks with `2 · slices · (stacks − 1) = triangles`, more
/// slices than stacks. `None` when no such grid fits `u16` indices.
pub fn sphere_with_triangles(triangles: usize) -> Option<HostMesh> {
    let half = triangles / 2;
    // A UV sphere has `half + 2` vertices.
    if !triangles.is_multiple_of(2) || half + 2 > usize::from(u16::MAX) + 1 {
        return None;
    }
    // slices · rings = half; pick the divisor pair nearest slices = 2 · rings
    // (a sphere's meridians are twice as long as its half-circles).
    let (slices, rings) = (1..=half)
        .filter(|r| half.is_multiple_of(*r))
        .map(|r| (half / r, r))
        .filter(|&(s, r)| s >= 3 && s >= r)
        .min_by_key(|&(s, r)| s.abs_diff(2 * r))?;
    uv_sphere(slices, rings + 1)
}

/// An `n` x `n` field of boxes of varying heights on a floor, as quads:
/// coplanar and touching faces, and plenty of occlusion.
pub fn box_field(n: usize) -> HostMesh {
    let mut mesh = HostMesh::default();
    let size = 2.0 / n as f32;
    for i in 0..n {
        for k in 0..n {
            let h = 0.15 + 0.6 * hash01((i * 31 + k * 17) as u32);
            let (x0, z0) = (
                -1.0 + i as f32 * size + 0.1 * size,
                -1.0 + k as f32 * size + 0.1 * size,
            );
            let (x1, z1) = (x0 + 0.8 * size, z0 + 0.8 * size);
            add_box(&mut mesh, [x0, -0.5, z0], [x1, -0.5 + h, z1]);
        }
    }
    // The floor, one quad facing up.
    let f = [
        [-1.0, -0.5, 1.0],
        [1.0, -0.5, 1.0],
        [1.0, -0.5, -1.0],
        [-1.0, -0.5, -1.0],
    ]
    .map(|p| mesh.vertex(p));
    mesh.face(&f);
    mesh
}

/// A heightfield over an `n` x `n` grid of quads split into triangles
/// (`2 n²` triangles), hills from a few sine waves.
pub fn terrain(n: usize) -> HostMesh {
    let mut mesh = HostMesh::default();
    for i in 0..=n {
        for k in 0..=n {
            let (x, z) = (
                -1.0 + 2.0 * i as f32 / n as f32,
                -1.0 + 2.0 * k as f32 / n as f32,
            );
            let y = 0.18 * libm::sinf(3.1 * x) * libm::cosf(2.3 * z)
                + 0.07 * libm::sinf(7.0 * x + 5.0 * z);
            mesh.vertex([x, y, z]);
        }
    }
    let at = |i: usize, k: usize| (i * (n + 1) + k) as u16;
    for i in 0..n {
        for k in 0..n {
            let (a, b, c, d) = (at(i, k), at(i, k + 1), at(i + 1, k + 1), at(i + 1, k));
            mesh.face(&[a, b, c]);
            mesh.face(&[a, c, d]);
        }
    }
    mesh
}

fn add_box(mesh: &mut HostMesh, lo: [f32; 3], hi: [f32; 3]) {
    let v: Vec<u16> = (0..8)
        .map(|k| {
            mesh.vertex([
                if k & 1 == 0 { lo[0] } else { hi[0] },
                if k & 2 == 0 { lo[1] } else { hi[1] },
                if k & 4 == 0 { lo[2] } else { hi[2] },
            ])
        })
        .collect();
    for q in [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ] {
        mesh.face(&q.map(|k| v[k]));
    }
}

fn hash01(x: u32) -> f32 {
    let mut h = x.wrapping_mul(0x9E37_79B9);
    h ^= h >> 16;
    h = h.wrapping_mul(0x85EB_CA6B);
    h ^= h >> 13;
    (h & 0xFFFF) as f32 / 65535.0
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(a: [f32; 3]) -> [f32; 3] {
    let l = libm::sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if l > 0.0 { a.map(|v| v / l) } else { a }
}

/// The named built-in meshes, as the tools accept them (`shape:NAME`):
/// `torus-knot` (1,024 triangles), `textured-torus-knot` (the same with
/// texture coordinates: 6 repeats along it, 1 around), `icosphere`
/// (5,120), `boxes` (217 quads), `terrain` (3,200 triangles); besides
/// these, `sphere-N` is a UV sphere of exactly `N` triangles
/// ([`sphere_with_triangles`]).
pub const NAMES: [&str; 5] = [
    "torus-knot",
    "textured-torus-knot",
    "icosphere",
    "boxes",
    "terrain",
];

/// A built-in mesh by name (see [`NAMES`]).
pub fn by_name(name: &str) -> Option<HostMesh> {
    match name {
        "torus-knot" => Some(torus_knot(2, 3, 64, 8, 0.45)),
        "textured-torus-knot" => Some(textured_torus_knot(2, 3, 64, 8, 0.45, 6.0)),
        "icosphere" => Some(icosphere(4)),
        "boxes" => Some(box_field(6)),
        "terrain" => Some(terrain(40)),
        _ => name
            .strip_prefix("sphere-")
            .and_then(|n| n.parse().ok())
            .and_then(sphere_with_triangles),
    }
}
