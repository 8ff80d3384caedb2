//! Polygon clipping in homogeneous clip space, in `f64`, streamed.
//!
//! A plane is a 4-vector `q`; a clip-space point `p` is inside when
//! `q · p >= 0`. Clipping happens before the divide by `w`, so polygons that
//! cross the near plane (or pass behind the eye) are cut, never inverted.
//!
//! [`Clipper`] is Sutherland and Hodgman's re-entrant form: one stage per
//! plane, each holding only its first and previous vertex, so a polygon of
//! any size streams through with no buffer and comes out corner by corner.
//!
//! **Precision.** Clipping runs in `f64` on positions transformed in `f64`
//! (rare: only faces crossing the near or far plane or the guard band take
//! this path). A cut corner divides by its `w`, which near the eye is
//! small, so the arithmetic's rounding (a few units of `2^-53` of the
//! face's size) is amplified by `size / w`: in `f32` a cut edge moved by
//! pixels. In `f64`, a face up to `2^28` times the near distance in size
//! has every cut corner within 1/256 pixel of the exact one and its depth
//! within `2^-20`; [`draw_mesh`](crate::front::scene::draw_mesh) refuses
//! a larger face that needs clipping
//! ([`CLIP_RANGE`](crate::front::scene::CLIP_RANGE)). `tests/clipping.rs`
//! checks both against a reference in double-double arithmetic over the
//! whole `f32` range.
//!
//! **Watertight.** Each intersection is computed from the inside end of the
//! edge towards the outside end, whichever way the polygon walks the edge,
//! so two faces that share an edge get bit-identical new corners.
//! A vertex marked [`ClipVertex::known_inside`] (a corner the caller has
//! already projected, shared with faces that are not clipped) counts as
//! inside every plane, so it is never moved by a cut.

// Without the `clipping` feature nothing calls the clipper.
#![cfg_attr(not(feature = "clipping"), allow(dead_code))]

/// A point in homogeneous clip space.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClipPoint {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
    /// w.
    pub w: f64,
}

impl ClipPoint {
    /// `(x, y, z, w)`.
    pub const fn new(x: f64, y: f64, z: f64, w: f64) -> Self {
        Self { x, y, z, w }
    }

    /// Signed distance-like value `q · p` for the plane `q`.
    pub fn dot(self, q: [f64; 4]) -> f64 {
        self.x * q[0] + self.y * q[1] + self.z * q[2] + self.w * q[3]
    }

    /// `self + (o - self) · t`.
    pub fn lerp(self, o: Self, t: f64) -> Self {
        Self::new(
            self.x + (o.x - self.x) * t,
            self.y + (o.y - self.y) * t,
            self.z + (o.z - self.z) * t,
            self.w + (o.w - self.w) * t,
        )
    }

    /// Whether every component is finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite() && self.w.is_finite()
    }
}

/// Near plane: `z >= -w`.
pub const NEAR: [f64; 4] = [0.0, 0.0, 1.0, 1.0];
/// Far plane: `z <= w`.
pub const FAR: [f64; 4] = [0.0, 0.0, -1.0, 1.0];

/// The six frustum planes: left, right, bottom, top, near, far.
pub const FRUSTUM: [[f64; 4]; 6] = [
    [1.0, 0.0, 0.0, 1.0],
    [-1.0, 0.0, 0.0, 1.0],
    [0.0, 1.0, 0.0, 1.0],
    [0.0, -1.0, 0.0, 1.0],
    NEAR,
    FAR,
];

/// Planes that keep `|x/w| <= gx`, `|y/w| <= gy` (a guard band in NDC
/// units), plus near and far.
pub fn guard_planes(gx: f64, gy: f64) -> [[f64; 4]; 6] {
    [
        [1.0, 0.0, 0.0, gx],
        [-1.0, 0.0, 0.0, gx],
        [0.0, 1.0, 0.0, gy],
        [0.0, -1.0, 0.0, gy],
        NEAR,
        FAR,
    ]
}

/// Bit `k` set when `p` lies outside `planes[k]` by more than `margin`
/// (the planes it lies beyond for certain when each of its distances may
/// be off by `margin`). A polygon whose corners' masks share a bit lies
/// wholly outside that plane.
pub fn outside_mask(p: ClipPoint, planes: &[[f64; 4]], margin: f64) -> u32 {
    planes
        .iter()
        .enumerate()
        .filter(|(_, q)| p.dot(**q) < -margin)
        .fold(0, |mask, (k, _)| mask | 1 << k)
}

/// A value carried by a vertex through clipping (a colour, texture
/// coordinates): at a corner where the near plane or the guard band cuts
/// a face's edge it is interpolated between the edge's ends with the
/// cut's parameter, as the position is (a value linear over a face in
/// model space is linear in clip space too). `()` carries nothing.
pub trait ClipValue: Copy {
    /// `self + (other - self) · t`, for `t` in `[0, 1]`.
    fn lerp(self, other: Self, t: f64) -> Self;
}

impl ClipValue for () {
    #[inline(always)]
    fn lerp(self, _: Self, _: f64) -> Self {}
}

/// A vertex streaming through the [`Clipper`], with a value `S`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipVertex<S = ()> {
    /// Position in clip space.
    pub point: ClipPoint,
    /// For a corner of the input polygon, the caller's tag (for example
    /// its vertex-table index); `None` for a new corner made by a cut.
    pub tag: Option<u16>,
    /// Treat the vertex as inside every plane (distances below zero are
    /// taken as zero), so it comes out unchanged.
    pub known_inside: bool,
    /// The vertex's value (interpolated at a cut).
    pub value: S,
}

impl<S> ClipVertex<S> {
    /// A corner of the input polygon with a value.
    pub const fn with_value(
        point: ClipPoint,
        tag: Option<u16>,
        known_inside: bool,
        value: S,
    ) -> Self {
        Self {
            point,
            tag,
            known_inside,
            value,
        }
    }

    fn distance(&self, plane: [f64; 4]) -> f64 {
        let d = self.point.dot(plane);
        if self.known_inside { d.max(0.0) } else { d }
    }
}

/// One plane's stage: the first vertex it saw and the previous one, with
/// their distances.
#[derive(Debug, Clone, Copy)]
struct Stage<S> {
    first: Option<(ClipVertex<S>, f64)>,
    previous: Option<(ClipVertex<S>, f64)>,
}

impl<S> Stage<S> {
    const EMPTY: Self = Self {
        first: None,
        previous: None,
    };
}

/// A re-entrant Sutherland-Hodgman clipper over `P` planes: push the
/// polygon's corners in order with [`Clipper::push`], then call
/// [`Clipper::finish`]. The clipped polygon's corners arrive in order at
/// `out` (possibly fewer than three, when it is clipped away); a polygon of
/// `n` corners comes out with at most `n + P`.
#[derive(Debug, Clone)]
pub struct Clipper<const P: usize, S = ()> {
    planes: [[f64; 4]; P],
    stages: [Stage<S>; P],
}

impl<const P: usize, S: ClipValue> Clipper<P, S> {
    /// A clipper against `planes`, applied in order.
    pub const fn new(planes: [[f64; 4]; P]) -> Self {
        Self {
            planes,
            stages: [Stage::EMPTY; P],
        }
    }

    /// Feeds the next corner of the polygon.
    pub fn push<E>(
        &mut self,
        vertex: ClipVertex<S>,
        out: &mut dyn FnMut(ClipVertex<S>) -> Result<(), E>,
    ) -> Result<(), E> {
        self.receive(0, vertex, out)
    }

    /// Closes the polygon: emits the corners its closing edge makes, and
    /// readies the clipper for the next polygon.
    pub fn finish<E>(
        &mut self,
        out: &mut dyn FnMut(ClipVertex<S>) -> Result<(), E>,
    ) -> Result<(), E> {
        let result = self.close(0, out);
        self.stages = [Stage::EMPTY; P];
        result
    }

    fn emit<E>(
        &mut self,
        stage: usize,
        vertex: ClipVertex<S>,
        out: &mut dyn FnMut(ClipVertex<S>) -> Result<(), E>,
    ) -> Result<(), E> {
        if stage + 1 < P {
            self.receive(stage + 1, vertex, out)
        } else {
            out(vertex)
        }
    }

    fn receive<E>(
        &mut self,
        stage: usize,
        vertex: ClipVertex<S>,
        out: &mut dyn FnMut(ClipVertex<S>) -> Result<(), E>,
    ) -> Result<(), E> {
        if P == 0 {
            return out(vertex);
        }
        let d = vertex.distance(self.planes[stage]);
        let state = &mut self.stages[stage];
        let previous = state.previous.replace((vertex, d));
        if state.first.is_none() {
            state.first = Some((vertex, d));
        }
        if let Some((p, dp)) = previous
            && (dp >= 0.0) != (d >= 0.0)
        {
            self.emit(stage, crossing(p, dp, vertex, d), out)?;
        }
        if d >= 0.0 {
            self.emit(stage, vertex, out)?;
        }
        Ok(())
    }

    fn close<E>(
        &mut self,
        stage: usize,
        out: &mut dyn FnMut(ClipVertex<S>) -> Result<(), E>,
    ) -> Result<(), E> {
        if stage >= P {
            return Ok(());
        }
        let state = self.stages[stage];
        if let (Some((f, df)), Some((p, dp))) = (state.first, state.previous)
            && (dp >= 0.0) != (df >= 0.0)
        {
            self.emit(stage, crossing(p, dp, f, df), out)?;
        }
        self.close(stage + 1, out)
    }
}

/// Where the edge `a`–`b` meets the plane, computed from its inside end.
fn crossing<S: ClipValue>(a: ClipVertex<S>, da: f64, b: ClipVertex<S>, db: f64) -> ClipVertex<S> {
    let (inside, d_in, outside, d_out) = if da >= 0.0 {
        (a, da, b, db)
    } else {
        (b, db, a, da)
    };
    let t = d_in / (d_in - d_out);
    ClipVertex {
        point: inside.point.lerp(outside.point, t),
        tag: None,
        known_inside: false,
        value: inside.value.lerp(outside.value, t),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use heapless::Vec;

    fn v(x: f64, z: f64) -> ClipPoint {
        ClipPoint::new(x, 0.0, z, 1.0)
    }

    fn clip<const P: usize>(poly: &[ClipPoint], planes: [[f64; 4]; P]) -> Vec<ClipPoint, 16> {
        let mut clipper = Clipper::new(planes);
        let mut out: Vec<ClipPoint, 16> = Vec::new();
        let mut sink = |c: ClipVertex| out.push(c.point).map_err(|_| ());
        for &p in poly {
            clipper
                .push(ClipVertex::with_value(p, None, false, ()), &mut sink)
                .unwrap();
        }
        clipper.finish(&mut sink).unwrap();
        out
    }

    #[test]
    fn near_plane_cuts_a_triangle_into_a_quad() {
        // Two corners behind the near plane (z < -w), one in front.
        let tri = [v(-1.0, -2.0), v(1.0, -2.0), v(0.0, 0.0)];
        assert_eq!(clip(&tri, [NEAR]).len(), 3);
        let tri = [v(-1.0, 0.0), v(1.0, 0.0), v(0.0, -3.0)];
        let out = clip(&tri, [NEAR]);
        assert_eq!(out.len(), 4);
        assert!(out.iter().all(|p| p.dot(NEAR) >= -1e-12));
    }

    #[test]
    fn wholly_outside_is_empty_and_inside_is_unchanged() {
        let behind = [v(-1.0, -2.0), v(1.0, -2.0), v(0.0, -3.0)];
        assert!(clip(&behind, FRUSTUM).is_empty());
        let masks = behind
            .iter()
            .fold(u32::MAX, |m, &p| m & outside_mask(p, &FRUSTUM, 0.0));
        assert_eq!(masks, 1 << 4, "all outside the near plane");
        let inside = [v(-0.5, 0.0), v(0.5, 0.0), v(0.0, 0.5)];
        assert_eq!(clip(&inside, FRUSTUM).as_slice(), &inside);
        assert_eq!(outside_mask(inside[0], &FRUSTUM, 0.0), 0);
    }

    #[test]
    fn streaming_matches_the_textbook_two_buffer_form() {
        // A square through two planes: the re-entrant form gives the same
        // cyclic sequence as clipping by one plane after the other.
        let square = [v(-2.0, -2.0), v(2.0, -2.0), v(2.0, 2.0), v(-2.0, 2.0)];
        let one = clip(&square, [FRUSTUM[0]]);
        let two = clip(&one, [FRUSTUM[4]]);
        let both = clip(&square, [FRUSTUM[0], FRUSTUM[4]]);
        assert_eq!(two.len(), both.len());
        let shift = (0..both.len()).find(|&k| both[k] == two[0]).unwrap();
        for k in 0..two.len() {
            assert_eq!(two[k], both[(k + shift) % both.len()]);
        }
    }

    #[test]
    fn shared_edges_clip_to_identical_points() {
        // Two triangles sharing the edge (p, q), walked in opposite
        // directions; q is behind the near plane.
        let p = ClipPoint::new(0.3, 0.1, 0.7, 1.3);
        let q = ClipPoint::new(-0.7, 0.9, -2.9, 0.4);
        let a = clip(&[p, q, ClipPoint::new(1.0, 1.0, 0.0, 1.0)], [NEAR]);
        let b = clip(&[q, p, ClipPoint::new(-1.0, 1.0, 0.0, 1.0)], [NEAR]);
        let on_plane = |poly: &Vec<ClipPoint, 16>| {
            *poly
                .iter()
                .find(|c| c.dot(NEAR).abs() < 1e-9 && c.x < 0.3 && c.y < 0.9 && c.y > 0.1)
                .unwrap()
        };
        assert_eq!(on_plane(&a), on_plane(&b));
    }

    #[test]
    fn known_inside_corners_are_never_cut() {
        // A corner a hair outside the near plane, known inside: it comes
        // out as it went in, with its tag.
        let eps = ClipPoint::new(0.0, 0.0, -1.0 - 1e-12, 1.0);
        let mut clipper = Clipper::new(FRUSTUM);
        let mut out: Vec<ClipVertex, 16> = Vec::new();
        let mut sink = |c: ClipVertex| out.push(c).map_err(|_| ());
        for (k, p) in [eps, v(0.5, 0.0), v(0.0, 0.5)].into_iter().enumerate() {
            clipper
                .push(
                    ClipVertex::with_value(p, Some(k as u16), k == 0, ()),
                    &mut sink,
                )
                .unwrap();
        }
        clipper.finish(&mut sink).unwrap();
        let tags: Vec<Option<u16>, 16> = out.iter().map(|c| c.tag).collect();
        assert_eq!(tags.as_slice(), &[Some(0), Some(1), Some(2)]);
    }
}
