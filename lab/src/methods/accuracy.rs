//! Measuring a rendered id frame against the float64 reference.

use super::reference::{BACKGROUND, ReferenceFrame};

/// How a rendered frame compares with the reference.
///
/// A pixel whose face id differs from the reference's is a *mismatch*. It
/// is excused *at edges* when its sample lies within 1/16 px of the
/// boundary of either face (the one drawn or the reference's). Otherwise it
/// is excused as a *depth tie* when both are faces and the drawn face's
/// plane along the pixel's ray is within 0.1 % of the nearest surface's
/// depth. What remains is a *hard* mismatch: a visibility error.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Comparison {
    /// Pixels compared.
    pub pixels: usize,
    /// Pixels whose face id differs.
    pub mismatches: usize,
    /// Mismatches within 1/16 px of either face's boundary.
    pub excused_at_edges: usize,
    /// Mismatches where the drawn face is within 0.1 % of the nearest depth.
    pub excused_as_ties: usize,
    /// Everything else.
    pub hard: usize,
}

/// Largest sample-to-boundary distance excused as an edge effect, px.
pub const EDGE_TOLERANCE: f64 = 1.0 / 16.0;
/// Largest relative depth difference excused as a tie.
pub const DEPTH_TOLERANCE: f64 = 1e-3;

/// Compares `ids` (row-major, [`BACKGROUND`] for none) with the reference.
pub fn compare(reference: &ReferenceFrame, ids: &[u32]) -> Comparison {
    let mut c = Comparison {
        pixels: ids.len(),
        ..Comparison::default()
    };
    for (k, (&drawn, &expected)) in ids.iter().zip(&reference.ids).enumerate() {
        if drawn == expected {
            continue;
        }
        c.mismatches += 1;
        let (i, j) = (k % reference.width, k / reference.width);
        let near_edge = [drawn, expected]
            .iter()
            .any(|&f| f != BACKGROUND && reference.boundary_distance(f, i, j) <= EDGE_TOLERANCE);
        if near_edge {
            c.excused_at_edges += 1;
            continue;
        }
        let tie = drawn != BACKGROUND
            && expected != BACKGROUND
            && reference.face_depth(drawn, i, j).is_some_and(|d| {
                let nearest = reference.depths[k];
                (d - nearest).abs() <= DEPTH_TOLERANCE * nearest
            });
        if tie {
            c.excused_as_ties += 1;
        } else {
            c.hard += 1;
        }
    }
    c
}
