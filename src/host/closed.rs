//! Finding a mesh's [`ClosedHull`]: whether its faces close up, wound
//! consistently and outward, and the sphere that holds it.

use std::collections::HashMap;
use std::vec;
use std::vec::Vec;

use crate::front::closed_hull::ClosedHull;
use crate::front::mesh::Mesh;
use crate::front::scene::bounding_sphere;

/// The hull of `mesh` when it is closed ([`ClosedHull`]): every directed
/// edge of its faces (between corners of different positions, positions
/// equal when their coordinates are: a transform maps them alike) met by
/// exactly one edge running the other way, and no directed edge twice;
/// the volume its faces enclose positive beyond rounding (counter-clockwise
/// seen from outside); every position finite; every face of more than
/// three corners turned one way as drawn (a simple outline seen along its
/// normal, and, when the draw splits it into a fan, no triangle of the
/// fan turned back: a face that crosses itself, a bow tie, has a lobe
/// that shows its back from any side). The sphere is
/// [`bounding_sphere`]'s, its radius taken a millionth larger. `None` for
/// anything else, a mesh with no faces included.
///
/// It cannot see whether the surface passes through itself inside out (a
/// region enclosed with the wrong sign): such a mesh, rare outside
/// tests, must not be given a hull.
pub fn closed_hull<M: Mesh + ?Sized>(mesh: &M) -> Option<ClosedHull> {
    match capped_hull(mesh)? {
        (hull, caps) if caps.is_empty() => Some(hull),
        _ => None,
    }
}

/// Largest number of edges of a hole [`capped_hull`] caps.
pub const CAP_EDGES_MAX: usize = 256;

/// The hull of `mesh` closed by caps over its holes, and the caps'
/// triangles ([`Mesh::hull_caps`]): as [`closed_hull`], but each edge
/// that no other edge meets running the other way may lie on a hole's
/// rim, a loop of such edges in which every position starts one and ends
/// one. Each hole is capped by triangles between its rim's positions
/// (the triangulation of the rim whose triangles turn least from its
/// Newell normal, along which it must show as a simple polygon of at most
/// [`CAP_EDGES_MAX`] edges), wound against the rim, so that mesh and caps are closed; the volume they
/// enclose together must be positive. A closed mesh gets no caps. `None`
/// for anything else.
///
/// As with [`closed_hull`], a surface (mesh and caps) that passes through
/// itself inside out is not seen: a cap that crosses the mesh, which a
/// rim curled over its own hole could make, is such a surface.
pub fn capped_hull<M: Mesh + ?Sized>(mesh: &M) -> Option<(ClosedHull, Vec<[[f32; 3]; 3]>)> {
    if mesh.face_count() == 0 {
        return None;
    }
    // Positions by value (`+ 0.0` makes `-0.0` the same as `0.0`).
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let mut id_of = Vec::with_capacity(mesh.vertex_count());
    let mut positions: Vec<[f32; 3]> = Vec::new();
    for v in 0..mesh.vertex_count() {
        let p = mesh.position(v);
        if !p.iter().all(|c| c.is_finite()) {
            return None;
        }
        let key = p.map(|c| (c + 0.0).to_bits());
        let next = ids.len() as u32;
        let id = *ids.entry(key).or_insert(next);
        if id == next {
            positions.push(p);
        }
        id_of.push(id);
    }
    let mut edges = Vec::new();
    let mut volume = Volume::default();
    for f in 0..mesh.face_count() {
        let corners = mesh.face(f);
        let n = corners.len();
        // A face of fewer than three corners, or one naming a vertex
        // beyond the mesh, is not part of any surface.
        if n < 3 || corners.iter().any(|&c| usize::from(c) >= id_of.len()) {
            return None;
        }
        for k in 0..n {
            let (a, b) = (corners[k], corners[(k + 1) % n]);
            let (a, b) = (id_of[usize::from(a)], id_of[usize::from(b)]);
            if a != b {
                edges.push((a, b));
            }
        }
        if n > 3 && !turned_one_way(mesh, f, &id_of) {
            return None;
        }
        let p = |k: usize| mesh.position(usize::from(corners[k]));
        for k in 1..n.saturating_sub(1) {
            volume.add([p(0), p(k), p(k + 1)]);
        }
    }
    edges.sort_unstable();
    if !edges.windows(2).all(|w| w[0] != w[1]) {
        return None;
    }
    // The rims: edges no edge meets running the other way, followed from
    // the position each ends at (one rim edge must start there).
    let rims: Vec<(u32, u32)> = edges
        .iter()
        .copied()
        .filter(|&(a, b)| edges.binary_search(&(b, a)).is_err())
        .collect();
    let mut next: HashMap<u32, u32> = HashMap::with_capacity(rims.len());
    for &(a, b) in &rims {
        if next.insert(a, b).is_some() {
            return None;
        }
    }
    let mut caps = Vec::new();
    let mut done: HashMap<u32, ()> = HashMap::with_capacity(rims.len());
    for &(start, _) in &rims {
        if done.contains_key(&start) {
            continue;
        }
        let mut rim = Vec::new();
        let mut at = start;
        loop {
            if rim.len() >= CAP_EDGES_MAX || done.insert(at, ()).is_some() {
                return None;
            }
            rim.push(positions[at as usize]);
            at = *next.get(&at)?;
            if at == start {
                break;
            }
        }
        // The cap runs against the rim.
        rim.reverse();
        for triangle in cap_triangles(&rim)? {
            volume.add(triangle);
            caps.push(triangle);
        }
    }
    if !volume.outward() {
        return None;
    }
    let (centre, radius) = bounding_sphere(mesh).ok()?;
    let radius = radius * (1.0 + 1e-6) + f32::MIN_POSITIVE;
    let hull = ClosedHull {
        centre: [centre.x, centre.y, centre.z],
        radius,
    };
    radius.is_finite().then_some((hull, caps))
}

/// Six times the signed volume of triangles' tetrahedra from the origin
/// (any point gives the same sum for a closed surface), with the sum of
/// its terms' magnitudes for the rounding.
#[derive(Default)]
struct Volume {
    sum: f64,
    magnitude: f64,
}

impl Volume {
    fn add(&mut self, [a, b, c]: [[f32; 3]; 3]) {
        let (a, b, c) = (a.map(f64::from), b.map(f64::from), c.map(f64::from));
        let cross = [
            b[1] * c[2] - b[2] * c[1],
            b[2] * c[0] - b[0] * c[2],
            b[0] * c[1] - b[1] * c[0],
        ];
        self.sum += a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2];
        self.magnitude += (0..3).map(|i| (a[i] * cross[i]).abs()).sum::<f64>();
    }

    /// A positive volume well beyond the sum's rounding (a closed surface
    /// folded flat, two faces back to back, sums to about 0).
    fn outward(&self) -> bool {
        self.sum > 1e-9 * self.magnitude
    }
}

/// Whether face `f` of more than three corners (`id_of`: each vertex's
/// position id) is drawn as a surface turned one way, as every face of a
/// hull must be: with its repeated corners taken once, a triangle or
/// less, or an outline that is a simple polygon seen along its Newell
/// normal; and, for a face the draw splits into a fan (one that is not
/// planar, [`Mesh::face_is_planar`]), each triangle of the fan of no area
/// or turned less than a right angle from that normal. A face that
/// crosses itself (a bow tie) shows one lobe from the front and the other
/// from behind, so no view hides all its back.
fn turned_one_way<M: Mesh + ?Sized>(mesh: &M, f: usize, id_of: &[u32]) -> bool {
    let corners = mesh.face(f);
    let id = |k: usize| id_of[usize::from(corners[k])];
    let n = corners.len();
    let distinct: Vec<[f64; 3]> = (0..n)
        .filter(|&k| id(k) != id((k + 1) % n))
        .map(|k| mesh.position(usize::from(corners[k])).map(f64::from))
        .collect();
    if distinct.len() <= 3 {
        return true;
    }
    let Some((normal, flat)) = outline_along_normal(&distinct) else {
        return false;
    };
    if !simple(&flat) {
        return false;
    }
    if mesh.face_is_planar(f) {
        return true;
    }
    let p = |k: usize| mesh.position(usize::from(corners[k])).map(f64::from);
    (1..n - 1).all(|k| {
        let t = cross3(sub3(p(k), p(0)), sub3(p(k + 1), p(0)));
        dot3(t, t) == 0.0 || dot3(t, normal) > 0.0
    })
}

/// The unit Newell normal of the polygon `p` (3D, in order) and its
/// outline seen along it: in a basis `(u, v)` of the plane across the
/// normal with `(u, v, normal)` right-handed, so a polygon wound
/// counter-clockwise about its normal runs counter-clockwise in `(u, v)`.
/// `None` when the normal has no length (or is not finite).
fn outline_along_normal(p: &[[f64; 3]]) -> Option<([f64; 3], Vec<[f64; 2]>)> {
    let n = p.len();
    let mut normal = [0.0f64; 3];
    for k in 0..n {
        let (a, b) = (p[k], p[(k + 1) % n]);
        normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
        normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
        normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let length = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
    if !(length > 0.0 && length.is_finite()) {
        return None;
    }
    let normal = normal.map(|c| c / length);
    let helper = if normal[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let u = unit(cross3(helper, normal));
    let v = cross3(normal, u);
    let flat = p.iter().map(|q| [dot3(*q, u), dot3(*q, v)]).collect();
    Some((normal, flat))
}

/// Triangles covering the polygon `rim` (3D, in order), wound as it is,
/// each turned as little as can be from its Newell normal. `None` when
/// its outline seen along that normal is not a simple polygon (edges that
/// cross or touch, a normal of no length) or some triangle would be
/// turned a right angle from it or more.
fn cap_triangles(rim: &[[f32; 3]]) -> Option<Vec<[[f32; 3]; 3]>> {
    let n = rim.len();
    let p: Vec<[f64; 3]> = rim.iter().map(|v| v.map(f64::from)).collect();
    let (normal, flat) = outline_along_normal(&p)?;
    if n < 3 || !simple(&flat) {
        return None;
    }
    // The triangulation whose triangles turn least from the normal (the
    // largest smallest cosine; dynamic programming over the outline's
    // sub-polygons `i..=j`). Every triangle turned less than a right angle
    // from it is positive seen along it, so the triangles tile the simple
    // outline without overlap.
    let cosine = |a: usize, b: usize, c: usize| {
        let t = cross3(sub3(p[b], p[a]), sub3(p[c], p[a]));
        let length = dot3(t, t).sqrt();
        if length > 0.0 {
            dot3(t, normal) / length
        } else {
            -1.0
        }
    };
    let mut best = vec![f64::INFINITY; n * n];
    let mut split = vec![0usize; n * n];
    for span in 2..n {
        for i in 0..n - span {
            let j = i + span;
            let (mut value, mut at) = (f64::NEG_INFINITY, i + 1);
            for k in i + 1..j {
                let v = best[i * n + k].min(best[k * n + j]).min(cosine(i, k, j));
                if v > value {
                    (value, at) = (v, k);
                }
            }
            best[i * n + j] = value;
            split[i * n + j] = at;
        }
    }
    // (The whole outline is the sub-polygon 0..=n-1; NaN fails.)
    if best[n - 1].partial_cmp(&MIN_CAP_COSINE) != Some(core::cmp::Ordering::Greater) {
        return None;
    }
    let mut triangles = Vec::with_capacity(n - 2);
    let mut stack = vec![(0, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j > i + 1 {
            let k = split[i * n + j];
            triangles.push([rim[i], rim[k], rim[j]]);
            stack.push((i, k));
            stack.push((k, j));
        }
    }
    Some(triangles)
}

/// The least cosine between a cap triangle's normal and its hole's: a
/// triangle nearly on edge to the hole is refused.
const MIN_CAP_COSINE: f64 = 1e-3;

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let length = dot3(a, a).sqrt();
    a.map(|c| c / length)
}

/// Twice the signed area of `a b c` (positive counter-clockwise).
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether the closed outline `q` is a simple polygon: no two edges meet
/// but neighbours at their shared end (and those only there), no position
/// twice.
fn simple(q: &[[f64; 2]]) -> bool {
    let n = q.len();
    let edge = |k: usize| (q[k], q[(k + 1) % n]);
    for i in 0..n {
        for j in i + 1..n {
            let ((a, b), (c, d)) = (edge(i), edge(j));
            let neighbours = j == i + 1 || (i == 0 && j == n - 1);
            if neighbours {
                // Meeting only at the shared end: not folded back on
                // each other.
                let (shared, p, r) = if j == i + 1 { (b, a, d) } else { (a, b, c) };
                if orient(p, shared, r) == 0.0 && dot2(sub2(p, shared), sub2(r, shared)) > 0.0 {
                    return false;
                }
                continue;
            }
            if segments_meet(a, b, c, d) {
                return false;
            }
        }
    }
    true
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Whether segments `a b` and `c d` share any point.
fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (d1, d2) = (orient(a, b, c), orient(a, b, d));
    let (d3, d4) = (orient(c, d, a), orient(c, d, b));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |p: [f64; 2], q: [f64; 2], r: [f64; 2], o: f64| {
        o == 0.0
            && r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4)
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

    fn capped(corners: &[u16], starts: &[u32]) -> Option<(ClosedHull, Vec<[[f32; 3]; 3]>)> {
        capped_hull(&StaticMesh::new(&CUBE, corners, starts).expect("mesh"))
    }

    #[test]
    fn a_box_open_on_top_is_capped() {
        let (found, caps) = capped(&QUADS[..20], &STARTS[..5]).expect("capped");
        assert_eq!(found, hull_of_cube());
        assert_eq!(caps.len(), 2);
        // The caps lie on x = 1 and face +x, as the missing face did.
        for [a, b, c] in caps {
            assert!([a, b, c].iter().all(|p| p[0] == 1.0));
            let turn = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
            assert!(turn > 0.0, "{a:?} {b:?} {c:?}");
        }
        assert_eq!(hull(&QUADS[..20], &STARTS[..5]), None);
        // A tube, open at both ends: two caps of two triangles.
        let (_, caps) = capped(&QUADS[8..24], &STARTS[..4]).expect("capped");
        assert_eq!(caps.len(), 4);
    }

    fn hull_of_cube() -> ClosedHull {
        hull(&QUADS, &STARTS).expect("closed")
    }

    #[test]
    fn an_open_box_wound_inward_or_a_card_is_not() {
        let mut inward = QUADS;
        for face in inward.chunks_mut(4) {
            face.reverse();
        }
        assert_eq!(capped(&inward[..20], &STARTS[..5]), None);
        // One quad: capped by its own reverse, it encloses nothing.
        assert_eq!(capped(&QUADS[..4], &STARTS[..1]), None);
    }

    /// A closed mesh with a face that crosses itself (the fuzzer's case:
    /// face 0 a bow tie in z = 0, the others bent quads), which showed a
    /// lobe of that face from behind where nothing hid it.
    #[test]
    fn a_face_that_crosses_itself_is_not() {
        let positions = [
            [-1.0, -1.0, -1.0],
            [1.0, -1.0, -1.0],
            [1.0, 1.0, -9.0],
            [-1.0, 1.0, -1.0],
            [1.0, -1.0, 0.0],
            [1.0, 5.0, 0.0],
            [0.5, 1.0, 0.0],
            [5.5, -0.5, 0.0],
        ];
        let corners = [4, 5, 6, 7, 1, 0, 3, 2, 5, 1, 2, 6, 0, 4, 7, 3, 3, 7, 2, 3];
        let starts = [0, 4, 8, 12, 17];
        let mesh = StaticMesh::new(&positions, &corners, &starts).expect("mesh");
        assert_eq!(closed_hull(&mesh), None);
    }

    /// A pyramid over the flat quad `base` (corners in z = 0), its apex
    /// at `(2, 1, 3)`, its sides wound against the base's edges.
    fn pyramid(base: [[f32; 2]; 4]) -> Option<ClosedHull> {
        let mut positions: Vec<[f32; 3]> = base.iter().map(|&[x, y]| [x, y, 0.0]).collect();
        positions.push([2.0, 1.0, 3.0]);
        let mut corners = vec![0, 1, 2, 3];
        for k in 0..4u16 {
            corners.extend_from_slice(&[(k + 1) % 4, k, 4]);
        }
        let starts = [0, 4, 7, 10, 13];
        closed_hull(&StaticMesh::new(&positions, &corners, &starts).expect("mesh"))
    }

    #[test]
    fn a_flat_bow_tie_is_not() {
        // Wound clockwise seen from above (its normal points down, out of
        // the pyramid): closed.
        assert!(pyramid([[0.0, 0.0], [0.0, 1.0], [4.0, 2.0], [4.0, 0.0]]).is_some());
        // Two of its corners swapped: a bow tie whose larger lobe runs
        // clockwise and smaller one counter-clockwise, enclosing a volume
        // of the right sign, drawn as one polygon (it is flat).
        assert_eq!(
            pyramid([[0.0, 0.0], [4.0, 2.0], [4.0, 0.0], [0.0, 1.0]]),
            None
        );
    }

    /// A pyramid over the dart-shaped quad `(4, 0), (0, 0), (0, 4), (1, 1)`
    /// (its corner at `(1, 1)` raised by `lift`, the base listed from
    /// corner `first`), wound outward.
    fn dart_pyramid(lift: f32, first: usize) -> Option<ClosedHull> {
        let positions = [
            [4.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, 4.0, 0.0],
            [1.0, 1.0, lift],
            [0.5, 0.5, 3.0],
        ];
        let base: Vec<u16> = (0..4).map(|k| ((first + k) % 4) as u16).collect();
        let mut corners = base.clone();
        for k in 0..4 {
            corners.extend_from_slice(&[base[(k + 1) % 4], base[k], 4]);
        }
        let starts = [0, 4, 7, 10, 13];
        closed_hull(&StaticMesh::new(&positions, &corners, &starts).expect("mesh"))
    }

    #[test]
    fn a_bent_face_whose_fan_turns_back_is_not() {
        // Flat, the dart is drawn as one polygon: closed from any corner.
        assert!(dart_pyramid(0.0, 0).is_some());
        assert!(dart_pyramid(0.0, 1).is_some());
        // Bent, it is drawn as a fan from its first corner: from (0, 0)
        // both triangles face down with the base, from (4, 0) the one
        // through (1, 1) faces up, into the pyramid.
        assert!(dart_pyramid(0.3, 1).is_some());
        assert_eq!(dart_pyramid(0.3, 0), None);
    }

    #[test]
    fn a_position_not_finite_is_not() {
        let mut positions = CUBE;
        positions[7][1] = f32::NAN;
        let mesh = StaticMesh::new(&positions, &QUADS, &STARTS).expect("mesh");
        assert_eq!(closed_hull(&mesh), None);
    }
}
