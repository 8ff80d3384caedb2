//! Polygon clipping in homogeneous clip space (Sutherland-Hodgman).
//!
//! A plane is a 4-vector `q`; a clip-space point `p` is inside when
//! `q · p >= 0`. Clipping happens before the divide by `w`, so polygons that
//! cross the near plane (or pass behind the eye) are cut, never inverted.
//!
//! Each intersection is computed from the inside end of the edge towards the
//! outside end, whichever way the polygon walks the edge. Two faces that
//! share an edge therefore get bit-identical new corners, and the shared edge
//! stays watertight after clipping.

use crate::geometry::Vec4;
use heapless::Vec;

/// Near plane: `z >= -w`.
pub const NEAR: Vec4 = Vec4::new(0.0, 0.0, 1.0, 1.0);
/// Far plane: `z <= w`.
pub const FAR: Vec4 = Vec4::new(0.0, 0.0, -1.0, 1.0);

/// The six frustum planes: left, right, bottom, top, near, far.
pub const FRUSTUM: [Vec4; 6] = [
    Vec4::new(1.0, 0.0, 0.0, 1.0),
    Vec4::new(-1.0, 0.0, 0.0, 1.0),
    Vec4::new(0.0, 1.0, 0.0, 1.0),
    Vec4::new(0.0, -1.0, 0.0, 1.0),
    NEAR,
    FAR,
];

/// Planes that keep `|x/w| <= gx`, `|y/w| <= gy` (a guard band in NDC
/// units), plus near and far.
pub fn guard_planes(gx: f32, gy: f32) -> [Vec4; 6] {
    [
        Vec4::new(1.0, 0.0, 0.0, gx),
        Vec4::new(-1.0, 0.0, 0.0, gx),
        Vec4::new(0.0, 1.0, 0.0, gy),
        Vec4::new(0.0, -1.0, 0.0, gy),
        NEAR,
        FAR,
    ]
}

/// Whether every point lies outside one and the same plane: then the
/// polygon is wholly outside the region the planes bound.
pub fn outside_one_plane(points: &[Vec4], planes: &[Vec4]) -> bool {
    planes
        .iter()
        .any(|q| points.iter().all(|p| q.dot(*p) < 0.0))
}

/// The clipped polygon did not fit `M` corners.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TooManyCorners;

/// Clips the polygon `input` by every plane in turn. The result (possibly
/// empty, when the polygon is wholly outside) has at most
/// `input.len() + planes.len()` corners; it must fit `M`.
pub fn clip_polygon<const M: usize>(
    input: &[Vec4],
    planes: &[Vec4],
) -> Result<Vec<Vec4, M>, TooManyCorners> {
    let mut current: Vec<Vec4, M> = Vec::from_slice(input).map_err(|_| TooManyCorners)?;
    let mut next: Vec<Vec4, M> = Vec::new();
    for plane in planes {
        next.clear();
        clip_by_plane(&current, *plane, &mut next)?;
        core::mem::swap(&mut current, &mut next);
        if current.is_empty() {
            break;
        }
    }
    Ok(current)
}

fn clip_by_plane<const M: usize>(
    input: &[Vec4],
    plane: Vec4,
    output: &mut Vec<Vec4, M>,
) -> Result<(), TooManyCorners> {
    let Some(&last) = input.last() else {
        return Ok(());
    };
    let mut a = last;
    let mut da = plane.dot(a);
    for &b in input {
        let db = plane.dot(b);
        if (da >= 0.0) != (db >= 0.0) {
            let (inside, d_in, outside, d_out) = if da >= 0.0 {
                (a, da, b, db)
            } else {
                (b, db, a, da)
            };
            let crossing = inside.lerp(outside, d_in / (d_in - d_out));
            output.push(crossing).map_err(|_| TooManyCorners)?;
        }
        if db >= 0.0 {
            output.push(b).map_err(|_| TooManyCorners)?;
        }
        a = b;
        da = db;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f32, z: f32) -> Vec4 {
        Vec4::new(x, 0.0, z, 1.0)
    }

    #[test]
    fn near_plane_cuts_a_triangle_into_a_quad() {
        // Two corners behind the near plane (z < -w), one in front.
        let tri = [v(-1.0, -2.0), v(1.0, -2.0), v(0.0, 0.0)];
        let out = clip_polygon::<8>(&tri, &[NEAR]).unwrap();
        assert_eq!(out.len(), 3);
        let tri = [v(-1.0, 0.0), v(1.0, 0.0), v(0.0, -3.0)];
        let out = clip_polygon::<8>(&tri, &[NEAR]).unwrap();
        assert_eq!(out.len(), 4);
        assert!(out.iter().all(|p| NEAR.dot(*p) >= -1e-6));
    }

    #[test]
    fn wholly_outside_is_empty_and_inside_is_unchanged() {
        let behind = [v(-1.0, -2.0), v(1.0, -2.0), v(0.0, -3.0)];
        assert!(clip_polygon::<8>(&behind, &FRUSTUM).unwrap().is_empty());
        assert!(outside_one_plane(&behind, &FRUSTUM));
        let inside = [v(-0.5, 0.0), v(0.5, 0.0), v(0.0, 0.5)];
        assert_eq!(
            clip_polygon::<8>(&inside, &FRUSTUM).unwrap().as_slice(),
            &inside
        );
        assert!(!outside_one_plane(&inside, &FRUSTUM));
    }

    #[test]
    fn shared_edges_clip_to_identical_points() {
        // Two triangles sharing the edge (p, q), walked in opposite
        // directions; q is behind the near plane.
        let p = Vec4::new(0.3, 0.1, 0.7, 1.3);
        let q = Vec4::new(-0.7, 0.9, -2.9, 0.4);
        let a = clip_polygon::<8>(&[p, q, Vec4::new(1.0, 1.0, 0.0, 1.0)], &[NEAR]).unwrap();
        let b = clip_polygon::<8>(&[q, p, Vec4::new(-1.0, 1.0, 0.0, 1.0)], &[NEAR]).unwrap();
        let on_plane = |poly: &Vec<Vec4, 8>| {
            *poly
                .iter()
                .find(|c| **c != p && c.x < 0.3 && c.y < 0.9 && c.y > 0.1)
                .unwrap()
        };
        assert_eq!(on_plane(&a), on_plane(&b));
    }

    #[test]
    fn overflow_is_an_error() {
        let tri = [v(-1.0, 0.0), v(1.0, 0.0), v(0.0, -3.0)];
        assert_eq!(clip_polygon::<3>(&tri, &[NEAR]), Err(TooManyCorners));
    }
}
