//! Finding a mesh's [`ClosedHull`]: whether its faces close up, wound
//! consistently and outward, and the sphere that holds it.

use std::collections::HashMap;
use std::vec::Vec;

use crate::front::closed_hull::ClosedHull;
use crate::front::mesh::Mesh;
use crate::front::scene::bounding_sphere;

/// The hull of `mesh` when it is closed ([`ClosedHull`]): every directed
/// edge of its faces (between corners of different positions, positions
/// equal when their coordinates are: a transform maps them alike) met by
/// exactly one edge running the other way, and no directed edge twice;
/// the volume its faces enclose positive beyond rounding (counter-clockwise
/// seen from outside); every position finite. The sphere is
/// [`bounding_sphere`]'s, its radius taken a millionth larger. `None` for
/// anything else, a mesh with no faces included.
///
/// It cannot see whether the surface passes through itself inside out (a
/// region enclosed with the wrong sign): such a mesh, rare outside
/// tests, must not be given a hull.
pub fn closed_hull<M: Mesh + ?Sized>(mesh: &M) -> Option<ClosedHull> {
    if mesh.face_count() == 0 {
        return None;
    }
    // Positions by value (`+ 0.0` makes `-0.0` the same as `0.0`).
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let mut id_of = Vec::with_capacity(mesh.vertex_count());
    for v in 0..mesh.vertex_count() {
        let p = mesh.position(v);
        if !p.iter().all(|c| c.is_finite()) {
            return None;
        }
        let key = p.map(|c| (c + 0.0).to_bits());
        let next = ids.len() as u32;
        id_of.push(*ids.entry(key).or_insert(next));
    }
    let mut edges = Vec::new();
    let mut volume = 0.0f64;
    let mut magnitude = 0.0f64;
    for f in 0..mesh.face_count() {
        let corners = mesh.face(f);
        let n = corners.len();
        for k in 0..n {
            let (a, b) = (corners[k], corners[(k + 1) % n]);
            let (a, b) = (id_of[usize::from(a)], id_of[usize::from(b)]);
            if a != b {
                edges.push((a, b));
            }
        }
        // Six times the signed volume of the fan's tetrahedra from the
        // origin (any point gives the same sum for a closed surface).
        let p = |k: usize| mesh.position(usize::from(corners[k])).map(f64::from);
        for k in 1..n.saturating_sub(1) {
            let (a, b, c) = (p(0), p(k), p(k + 1));
            let cross = [
                b[1] * c[2] - b[2] * c[1],
                b[2] * c[0] - b[0] * c[2],
                b[0] * c[1] - b[1] * c[0],
            ];
            volume += a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2];
            magnitude += (0..3).map(|i| (a[i] * cross[i]).abs()).sum::<f64>();
        }
    }
    edges.sort_unstable();
    let unique = edges.windows(2).all(|w| w[0] != w[1]);
    let matched = edges
        .iter()
        .all(|&(a, b)| edges.binary_search(&(b, a)).is_ok());
    // A positive volume well beyond the sum's rounding (a closed surface
    // folded flat, two faces back to back, sums to about 0).
    let outward = volume > 1e-9 * magnitude;
    if !(unique && matched && outward) {
        return None;
    }
    let (centre, radius) = bounding_sphere(mesh).ok()?;
    let radius = radius * (1.0 + 1e-6) + f32::MIN_POSITIVE;
    radius.is_finite().then_some(ClosedHull {
        centre: [centre.x, centre.y, centre.z],
        radius,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::mesh::StaticMesh;

    /// A cube's positions: corner `k` at `(k & 1, k >> 1 & 1, k >> 2 & 1)`.
    const CUBE: [[f32; 3]; 8] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [1.0, 1.0, 1.0],
    ];

    /// The cube's faces as quads, counter-clockwise seen from outside.
    const QUADS: [u16; 24] = [
        0, 2, 3, 1, // z = 0
        4, 5, 7, 6, // z = 1
        0, 1, 5, 4, // y = 0
        2, 6, 7, 3, // y = 1
        0, 4, 6, 2, // x = 0
        1, 3, 7, 5, // x = 1
    ];
    const STARTS: [u32; 6] = [0, 4, 8, 12, 16, 20];

    fn hull(corners: &[u16], starts: &[u32]) -> Option<ClosedHull> {
        closed_hull(&StaticMesh::new(&CUBE, corners, starts).expect("mesh"))
    }

    #[test]
    fn a_cube_wound_outward_is_closed() {
        let h = hull(&QUADS, &STARTS).expect("closed");
        assert_eq!(h.centre, [0.5; 3]);
        let half_diagonal = 0.75f32.sqrt();
        assert!(h.radius >= half_diagonal && h.radius < half_diagonal * 1.00001);
    }

    #[test]
    fn a_cube_wound_inward_is_not() {
        let mut inward = QUADS;
        for face in inward.chunks_mut(4) {
            face.reverse();
        }
        assert_eq!(hull(&inward, &STARTS), None);
    }

    #[test]
    fn an_open_or_doubled_or_flipped_face_is_not() {
        // Without the last face: six edges unmatched.
        assert_eq!(hull(&QUADS[..20], &STARTS[..5]), None);
        // One face turned: its edges run the same way as its neighbours'.
        let mut flipped = QUADS;
        flipped[20..24].reverse();
        assert_eq!(hull(&flipped, &STARTS), None);
        // A face twice: its edges twice.
        let mut doubled = QUADS.to_vec();
        doubled.extend_from_slice(&QUADS[..4]);
        let mut starts = STARTS.to_vec();
        starts.push(24);
        assert_eq!(hull(&doubled, &starts), None);
    }

    #[test]
    fn faces_back_to_back_are_not() {
        // A closed surface of no volume: one quad and its reverse.
        let card = [0, 1, 3, 2, 0, 2, 3, 1];
        assert_eq!(hull(&card, &[0, 4]), None);
    }

    #[test]
    fn equal_positions_weld() {
        // The z = 1 face over its own four copies of its corners (as a
        // mesh split for texture seams has them): still closed.
        let mut positions = CUBE.to_vec();
        positions.extend_from_slice(&CUBE[4..8]);
        let mut corners = QUADS;
        corners[4..8].copy_from_slice(&[8, 9, 11, 10]);
        let mesh = StaticMesh::new(&positions, &corners, &STARTS).expect("mesh");
        assert!(closed_hull(&mesh).is_some());
        // A copy moved by one step of f32 does not weld.
        positions[11][0] = f32::from_bits(1.0f32.to_bits() + 1);
        let mesh = StaticMesh::new(&positions, &corners, &STARTS).expect("mesh");
        assert_eq!(closed_hull(&mesh), None);
    }

    #[test]
    fn a_position_not_finite_is_not() {
        let mut positions = CUBE;
        positions[7][1] = f32::NAN;
        let mesh = StaticMesh::new(&positions, &QUADS, &STARTS).expect("mesh");
        assert_eq!(closed_hull(&mesh), None);
    }
}
