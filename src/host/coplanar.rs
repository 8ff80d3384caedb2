//! Finding the faces of a mesh that overlap in one plane, so that they
//! can share it ([`SharedPlane`]).
//!
//! Faces whose planes agree (unit normals, either way round, within
//! [`NORMAL_TOLERANCE`]; distances from the origin within
//! [`OFFSET_TOLERANCE`] of the mesh's radius) form a coplanar set. Within
//! a set, faces whose interiors overlap (in the plane, by a separating-axis
//! test over their fan triangles) are joined, transitively; each group of
//! two or more faces gets one plane: three of its vertices spanning a
//! large triangle. Faces that only touch (the two triangles of a flat
//! quad) are not joined, so most meshes have no shared planes at all.
//!
//! Everything is in `f64` and deterministic; the cost is a sort of the
//! faces and, within each coplanar set, a sweep over bounding boxes.

use std::vec;
use std::vec::Vec;

use crate::front::mesh::{Mesh, SharedPlane};

/// Unit normals closer than this in every component are one plane's.
pub const NORMAL_TOLERANCE: f64 = 1e-5;
/// Plane offsets closer than this times the mesh's radius are one plane's.
/// Far below any deliberate offset (a decal lifted to win on depth) and
/// below a 24-bit depth step at any ordinary view distance.
pub const OFFSET_TOLERANCE: f64 = 1e-6;
/// Overlaps thinner than this times the mesh's radius are touching.
const TOUCH_TOLERANCE: f64 = 1e-9;

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// One face's plane: unit normal (sign fixed so its largest component is
/// positive) and offset over the mesh's radius, as `[nx, ny, nz, d]`.
struct FacePlane {
    face: usize,
    key: [f64; 4],
}

/// The faces of `mesh` that overlap another face of their plane, each
/// with the plane its group shares, sorted by face.
pub fn shared_planes<M: Mesh + ?Sized>(mesh: &M) -> Vec<SharedPlane> {
    let count = mesh.vertex_count();
    let position = |i: u16| mesh.position(usize::from(i)).map(f64::from);
    let finite = (0..count).all(|i| mesh.position(i).iter().all(|c| c.is_finite()));
    if !finite || count == 0 || count > 1 << 16 {
        return Vec::new();
    }
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for i in 0..count {
        let p = mesh.position(i).map(f64::from);
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let centre = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
    let radius = (0..count)
        .map(|i| {
            let d = sub(mesh.position(i).map(f64::from), centre);
            dot(d, d).sqrt()
        })
        .fold(0.0, f64::max);
    if radius == 0.0 {
        return Vec::new();
    }
    let mut planes: Vec<FacePlane> = (0..mesh.face_count())
        .filter_map(|face| {
            let corners = mesh.face(face);
            if corners.len() < 3
                || corners.iter().any(|&i| usize::from(i) >= count)
                || !mesh.face_is_planar(face)
            {
                return None;
            }
            let origin = position(corners[0]);
            let mut normal = [0.0; 3];
            for pair in corners[1..].windows(2) {
                let (p, q) = (
                    sub(position(pair[0]), origin),
                    sub(position(pair[1]), origin),
                );
                let c = cross(p, q);
                normal = [normal[0] + c[0], normal[1] + c[1], normal[2] + c[2]];
            }
            let length = dot(normal, normal).sqrt();
            if length <= 1e-12 * radius * radius {
                return None;
            }
            let mut n = normal.map(|c| c / length);
            let largest = (0..3)
                .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
                .unwrap_or(0);
            if n[largest] < 0.0 {
                n = n.map(|c| -c);
            }
            let d = dot(n, sub(origin, centre)) / radius;
            Some(FacePlane {
                face,
                key: [n[0], n[1], n[2], d],
            })
        })
        .collect();
    let mut out = Vec::new();
    for set in coplanar_sets(&mut planes) {
        let faces: Vec<usize> = set.iter().map(|p| p.face).collect();
        let normal = [set[0].key[0], set[0].key[1], set[0].key[2]];
        for group in overlapping_groups(mesh, &faces, normal, radius) {
            if let Some(vertices) = spanning_triangle(mesh, &group) {
                out.extend(group.iter().map(|&face| SharedPlane {
                    face: face as u32,
                    vertices,
                }));
            }
        }
    }
    out.sort_by_key(|p| p.face);
    out
}

/// Splits the faces into sets whose planes agree: sorted and split on the
/// offset, then on each normal component in turn, wherever neighbours in
/// the order differ by more than the tolerance. Two faces within the
/// tolerance on every coordinate always end in one set.
fn coplanar_sets(planes: &mut [FacePlane]) -> Vec<&[FacePlane]> {
    let tolerance = [
        NORMAL_TOLERANCE,
        NORMAL_TOLERANCE,
        NORMAL_TOLERANCE,
        OFFSET_TOLERANCE,
    ];
    let mut runs: Vec<&mut [FacePlane]> = vec![planes];
    for coordinate in [3, 0, 1, 2] {
        let mut next = Vec::new();
        for run in runs {
            run.sort_by(|a, b| a.key[coordinate].total_cmp(&b.key[coordinate]));
            let mut rest = run;
            while !rest.is_empty() {
                let mut end = 1;
                while end < rest.len()
                    && rest[end].key[coordinate] - rest[end - 1].key[coordinate]
                        <= tolerance[coordinate]
                {
                    end += 1;
                }
                let (head, tail) = rest.split_at_mut(end);
                if head.len() > 1 {
                    next.push(head);
                }
                rest = tail;
            }
        }
        runs = next;
    }
    runs.into_iter()
        .map(|run| {
            run.sort_by_key(|p| p.face);
            &*run
        })
        .collect()
}

/// A face's fan triangles in the plane's 2D coordinates.
fn fan_2d<M: Mesh + ?Sized>(mesh: &M, face: usize, axes: (usize, usize)) -> Vec<[[f64; 2]; 3]> {
    let corners = mesh.face(face);
    let point = |i: u16| {
        let p = mesh.position(usize::from(i)).map(f64::from);
        [p[axes.0], p[axes.1]]
    };
    (1..corners.len() - 1)
        .map(|k| [point(corners[0]), point(corners[k]), point(corners[k + 1])])
        .collect()
}

/// Whether two triangles' interiors overlap by more than `margin`: no
/// edge normal of either separates them.
fn triangles_overlap(a: &[[f64; 2]; 3], b: &[[f64; 2]; 3], margin: f64) -> bool {
    let separated_by = |edge_from: &[[f64; 2]; 3]| {
        (0..3).any(|k| {
            let (p, q) = (edge_from[k], edge_from[(k + 1) % 3]);
            let axis = [q[1] - p[1], p[0] - q[0]];
            let length = (axis[0] * axis[0] + axis[1] * axis[1]).sqrt();
            if length == 0.0 {
                return false;
            }
            let project = |t: &[[f64; 2]; 3]| {
                t.iter()
                    .map(|v| (v[0] * axis[0] + v[1] * axis[1]) / length)
                    .fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)))
            };
            let ((alo, ahi), (blo, bhi)) = (project(a), project(b));
            ahi <= blo + margin || bhi <= alo + margin
        })
    };
    !separated_by(a) && !separated_by(b)
}

/// Groups of two or more faces of one plane joined by overlapping
/// interiors (transitively): a sweep over the faces' bounding boxes in the
/// plane, then a separating-axis test per fan triangle pair.
fn overlapping_groups<M: Mesh + ?Sized>(
    mesh: &M,
    faces: &[usize],
    normal: P3,
    radius: f64,
) -> Vec<Vec<usize>> {
    // Drop the normal's largest component: the plane projects onto the
    // other two axes without collapsing.
    let axes = match (0..3)
        .max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs()))
        .unwrap_or(2)
    {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let margin = TOUCH_TOLERANCE * radius;
    let fans: Vec<Vec<[[f64; 2]; 3]>> = faces.iter().map(|&f| fan_2d(mesh, f, axes)).collect();
    let boxes: Vec<[f64; 4]> = fans
        .iter()
        .map(|fan| {
            fan.iter().flatten().fold(
                [f64::MAX, f64::MAX, f64::MIN, f64::MIN],
                |[x0, y0, x1, y1], v| [x0.min(v[0]), y0.min(v[1]), x1.max(v[0]), y1.max(v[1])],
            )
        })
        .collect();
    let mut order: Vec<usize> = (0..faces.len()).collect();
    order.sort_by(|&a, &b| boxes[a][0].total_cmp(&boxes[b][0]));
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    for (at, &a) in order.iter().enumerate() {
        for &b in &order[at + 1..] {
            if boxes[b][0] >= boxes[a][2] - margin {
                break;
            }
            let apart = boxes[b][1] >= boxes[a][3] - margin || boxes[a][1] >= boxes[b][3] - margin;
            if apart || root(&mut parent, a) == root(&mut parent, b) {
                continue;
            }
            let overlap = fans[a]
                .iter()
                .any(|s| fans[b].iter().any(|t| triangles_overlap(s, t, margin)));
            if overlap {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); faces.len()];
    for (k, &face) in faces.iter().enumerate() {
        let r = root(&mut parent, k);
        groups[r].push(face);
    }
    groups.retain(|g| g.len() > 1);
    groups
}

/// Three vertices of the group's faces spanning a large triangle: the
/// vertex farthest from the first, the one farthest from it, and the one
/// farthest from the line through both. `None` when they are collinear.
fn spanning_triangle<M: Mesh + ?Sized>(mesh: &M, faces: &[usize]) -> Option<[u16; 3]> {
    let mut vertices: Vec<u16> = faces
        .iter()
        .flat_map(|&f| mesh.face(f).iter().copied())
        .collect();
    vertices.sort_unstable();
    vertices.dedup();
    let at = |i: u16| mesh.position(usize::from(i)).map(f64::from);
    let farthest = |from: P3| {
        vertices.iter().copied().max_by(|&a, &b| {
            let (da, db) = (sub(at(a), from), sub(at(b), from));
            dot(da, da).total_cmp(&dot(db, db))
        })
    };
    let a = farthest(at(*vertices.first()?))?;
    let b = farthest(at(a))?;
    let area = |c: u16| {
        let n = cross(sub(at(b), at(a)), sub(at(c), at(a)));
        dot(n, n)
    };
    let c = vertices
        .iter()
        .copied()
        .max_by(|&p, &q| area(p).total_cmp(&area(q)))?;
    (area(c) > 0.0).then_some([a, b, c])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::host::HostMesh;

    fn mesh(positions: &[[f32; 3]], faces: &[&[u16]]) -> HostMesh {
        let mut m = HostMesh {
            positions: positions.to_vec(),
            ..HostMesh::default()
        };
        for f in faces {
            m.face_starts.push(m.corners.len() as u32);
            m.corners.extend_from_slice(f);
        }
        m
    }

    #[test]
    fn overlapping_coplanar_faces_share_one_plane() {
        // Two overlapping squares in z = 0, one square above them, and a
        // triangle touching the first square along an edge only.
        let m = mesh(
            &[
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
                [1.0, 1.0, 0.0],
                [3.0, 1.0, 0.0],
                [3.0, 3.0, 0.0],
                [1.0, 3.0, 0.0],
                [0.0, 0.0, 0.5],
                [2.0, 0.0, 0.5],
                [2.0, 2.0, 0.5],
                [0.0, -2.0, 0.0],
            ],
            &[&[0, 1, 2, 3], &[4, 5, 6, 7], &[8, 9, 10], &[0, 11, 1]],
        );
        let shared = shared_planes(&m);
        assert_eq!(
            shared.iter().map(|p| p.face).collect::<Vec<_>>(),
            vec![0, 1]
        );
        assert_eq!(shared[0].vertices, shared[1].vertices);
        // The plane's three vertices lie in z = 0 and span a triangle.
        for v in shared[0].vertices {
            assert_eq!(m.positions[usize::from(v)][2], 0.0);
        }
    }

    #[test]
    fn faces_that_only_touch_or_lie_apart_share_nothing() {
        // A flat quad split in two, and a parallel face 1e-3 away.
        let m = mesh(
            &[
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 0.001],
                [1.0, 0.0, 0.001],
                [1.0, 1.0, 0.001],
            ],
            &[&[0, 1, 2], &[0, 2, 3], &[4, 5, 6]],
        );
        assert!(shared_planes(&m).is_empty());
    }

    #[test]
    fn opposite_windings_are_one_plane() {
        // A double-sided card: the same triangle both ways round.
        let m = mesh(
            &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            &[&[0, 1, 2], &[0, 2, 1]],
        );
        let shared = shared_planes(&m);
        assert_eq!(shared.len(), 2);
    }
}
