//! The back-face test of `f32` triangles in model space, before any of
//! their corners is transformed: each face's plane, found once per mesh
//! ([`FacePlane`]), against the eye of the frame's matrix, found once per
//! draw ([`PlaneEye`]). A face turned away beyond doubt is left out for
//! one dot product, and a vertex that only such faces use is never
//! transformed or projected. It is the `f32` front end's counterpart of
//! the integer one's test ([`crate::front::backface`]).
//!
//! # Why it holds
//!
//! The frame sends a model-space point `q` to clip rows `(x, y, w) = M·(q,
//! 1)`, `M` the `x`, `y` and `w` rows of its `f32` matrix (a 3x4 matrix).
//! The orientation of a triangle's projection is the sign of `D =
//! det[M·Q0, M·Q1, M·Q2]` (`Qi = (qi, 1)`) when its corners are in front
//! of the eye, and by the Cauchy-Binet formula `D = E·P`, where `E_j =
//! (-1)^j det(M without column j)` is the eye in homogeneous coordinates
//! and `P = (N, -N·q0)` is the triangle's plane (`N = (q1 - q0) x (q2 -
//! q0)`). `D` does not depend on the corners' `w`: its sign says on which
//! side of the plane the eye is, so a face whose `D` says "behind" is seen
//! from behind wherever it is drawn, clipped or not.
//!
//! Both factors are computed in `f64` with bounds on their error:
//!
//! * [`FacePlane::of_triangle`] rounds `N` and `k = N·q0`, computed in
//!   `f64` from the `f32` corners, to `f32` and keeps `τ`, a bound on
//!   `3 |N_f - N|_∞` and `|k_f - k|` together (the `f64` arithmetic's
//!   error, each step's relative error at most `u = 2^-53`, plus the
//!   rounding to `f32`).
//! * [`PlaneEye::new`] computes each `E_j` (three products of an entry and
//!   a 2x2 minor of `f32` entries, whose products are exact in `f64`) and
//!   bounds its error by `5u` times the sum of the absolute terms.
//! * [`PlaneEye::side`] computes `s = k_f E_w - N_f·E_xyz` (`-D`: front
//!   faces turn counter-clockwise in clip `x, y`, so `D` is negative for a
//!   back face) and the doubt `τ (max_j<3 (|E_j| + e_j) + |E_w| + e_w) +
//!   (|N_f|_1 + |k_f|) max(e_xyz + 5u |E_xyz|_∞, e_w + 5u |E_w|)`, which
//!   bounds `|s + D|`, and says which side only when `|s|` exceeds twice
//!   the doubt (the doubt's own
//!   rounding is far below that factor).
//!
//! As with the integer test, the early test only leaves out, earlier,
//! triangles that the exact projection turns away; a few of them, seen
//! almost edge-on, the rounded corners would have turned by a hair.

#[cfg(feature = "std")]
use crate::front::backface::Side;
#[cfg(feature = "std")]
use crate::front::geometry::Mat4;

/// `f64`'s unit roundoff.
const U: f64 = 1.0 / 9_007_199_254_740_992.0; // 2^-53

/// A triangle's plane in model space, for the early back-face test
/// ([`Mesh::face_planes`](crate::Mesh::face_planes)): `normal·q = offset`
/// for every point `q` of the plane, up to `tolerance`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FacePlane {
    /// `(q1 - q0) x (q2 - q0)`, not normalised, rounded to `f32`.
    pub normal: [f32; 3],
    /// `normal·q0`, from the unrounded normal, rounded to `f32`.
    pub offset: f32,
    /// A bound on three times the largest error of a component of
    /// `normal` and on the error of `offset`. Zero with a zero normal: a
    /// plane that tests nothing ([`FacePlane::NONE`]).
    pub tolerance: f32,
}

impl FacePlane {
    /// The plane of a face the test leaves alone (not a triangle, or not
    /// finite): every face with it is too close to call.
    pub const NONE: Self = Self {
        normal: [0.0; 3],
        offset: 0.0,
        tolerance: 0.0,
    };

    /// The plane of the triangle `q0, q1, q2` (counter-clockwise seen from
    /// its front), with the bound on its error (see the module notes);
    /// [`Self::NONE`] when any of it is not finite in `f32`.
    pub fn of_triangle(q0: [f32; 3], q1: [f32; 3], q2: [f32; 3]) -> Self {
        let (normal, normal_error, offset, offset_error) = plane64(q0, q1, q2);
        let normal_f = normal.map(|n| n as f32);
        let offset_f = offset as f32;
        // The rounding to `f32`, measured (within `u` of itself).
        let rounding = |rounded: f32, exact: f64| (f64::from(rounded) - exact).abs() * (1.0 + U);
        let normal_bound = (0..3)
            .map(|k| normal_error[k] + rounding(normal_f[k], normal[k]))
            .fold(0.0f64, f64::max);
        let offset_bound = offset_error + rounding(offset_f, offset);
        // Rounded up to `f32` with room for this line's own roundings.
        let tolerance = ((3.0 * normal_bound).max(offset_bound) * (1.0 + 1e-6)) as f32 * 1.000_001;
        let finite =
            normal_f.iter().all(|n| n.is_finite()) && offset_f.is_finite() && tolerance.is_finite();
        if finite {
            Self {
                normal: normal_f,
                offset: offset_f,
                tolerance,
            }
        } else {
            Self::NONE
        }
    }
}

/// The plane of `q0, q1, q2` in `f64`: `N`, a bound on each component's
/// error, `k = N·q0` and a bound on its error.
#[allow(clippy::type_complexity)]
fn plane64(q0: [f32; 3], q1: [f32; 3], q2: [f32; 3]) -> ([f64; 3], [f64; 3], f64, f64) {
    let [p0, p1, p2] = [q0, q1, q2].map(|q| q.map(f64::from));
    // Each difference within `u` of its exact value (relative).
    let d1: [f64; 3] = core::array::from_fn(|k| p1[k] - p0[k]);
    let d2: [f64; 3] = core::array::from_fn(|k| p2[k] - p0[k]);
    let (mut normal, mut normal_error) = ([0.0f64; 3], [0.0f64; 3]);
    for k in 0..3 {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let (a, b) = (d1[i] * d2[j], d1[j] * d2[i]);
        normal[k] = a - b;
        // Inputs within `u` each and the product's rounding: `3u`
        // relative per product (plus second order); the difference's
        // rounding `u` of the result. `5u` covers both with room.
        normal_error[k] = 5.0 * U * (a.abs() + b.abs());
    }
    let terms: [f64; 3] = core::array::from_fn(|k| normal[k] * p0[k]);
    let offset = terms[0] + terms[1] + terms[2];
    // The normal's error carried by `q0`, and the dot product's own
    // rounding (`3u` of the absolute terms, `4u` with room).
    let offset_error = (0..3)
        .map(|k| normal_error[k] * p0[k].abs() + 4.0 * U * terms[k].abs())
        .sum::<f64>();
    (normal, normal_error, offset, offset_error)
}

/// The eye of a frame's `f32` matrix in homogeneous model coordinates,
/// with bounds on its error, for [`PlaneEye::side`].
#[cfg(feature = "std")]
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PlaneEye {
    /// `-E`: a positive `s` is a back face.
    eye: [f64; 4],
    /// `max_j<3 (|E_j| + e_j) + |E_w| + e_w`: what `τ` multiplies.
    per_tolerance: f64,
    /// `max(e_xyz + 5u |E_xyz|_∞, e_w + 5u |E_w|)`: what `|N_f|_1 +
    /// |k_f|` multiplies.
    per_magnitude: f64,
}

#[cfg(feature = "std")]
impl PlaneEye {
    /// The eye of the matrix `mvp` (rows `x`, `y`, `w` taken); `None` when
    /// it is not finite.
    pub(crate) fn new(mvp: &Mat4) -> Option<Self> {
        let (eye, error) = eye_of(mvp);
        // `D = E·P` with `P = (N, -k)` is positive when the projected
        // corners turn counter-clockwise in clip `x, y` (a front face;
        // clockwise on the screen, whose `y` points down). With `-E` kept,
        // `s = N·(-E_xyz) + k E_w = -D` is positive for a back face.
        let xyz_max = (0..3).map(|j| eye[j].abs() + error[j]).fold(0.0, f64::max);
        let xyz_error = (0..3).map(|j| error[j]).fold(0.0, f64::max);
        let xyz_abs = (0..3).map(|j| eye[j].abs()).fold(0.0, f64::max);
        let per_tolerance = xyz_max + eye[3].abs() + error[3];
        let per_magnitude = (xyz_error + 5.0 * U * xyz_abs).max(error[3] + 5.0 * U * eye[3].abs());
        let finite = eye.iter().all(|e| e.is_finite()) && per_tolerance.is_finite();
        finite.then_some(Self {
            eye,
            per_tolerance,
            per_magnitude,
        })
    }

    /// Which side of `plane` the eye is on, beyond doubt, or
    /// [`Side::Unsure`] (see the module notes). A plane that is not
    /// finite compares as unsure.
    #[inline(always)]
    pub(crate) fn side(&self, plane: &FacePlane) -> Side {
        let [nx, ny, nz] = plane.normal.map(f64::from);
        let k = f64::from(plane.offset);
        let [ex, ey, ez, ew] = self.eye;
        let s = nx * ex + ny * ey + nz * ez - k * ew;
        let magnitude = nx.abs() + ny.abs() + nz.abs() + k.abs();
        let doubt =
            f64::from(plane.tolerance) * self.per_tolerance + magnitude * self.per_magnitude;
        // NaN compares false both ways: unsure.
        if s > 2.0 * doubt {
            Side::Back
        } else if s < -2.0 * doubt {
            Side::Front
        } else {
            Side::Unsure
        }
    }
}

/// `-E` of `mvp`'s `x`, `y` and `w` rows in `f64`, and a bound on each
/// component's error.
#[cfg(feature = "std")]
fn eye_of(mvp: &Mat4) -> ([f64; 4], [f64; 4]) {
    let rows = [mvp.m[0], mvp.m[1], mvp.m[3]].map(|r| r.map(f64::from));
    let mut eye = [0.0f64; 4];
    let mut error = [0.0f64; 4];
    for (j, (e, err)) in eye.iter_mut().zip(&mut error).enumerate() {
        // The three columns other than `j`.
        let c: [usize; 3] = match j {
            0 => [1, 2, 3],
            1 => [0, 2, 3],
            2 => [0, 1, 3],
            _ => [0, 1, 2],
        };
        let minor = |a: usize, b: usize| {
            let (p, q) = (rows[1][a] * rows[2][b], rows[1][b] * rows[2][a]);
            (p - q, p.abs() + q.abs())
        };
        let (m0, a0) = minor(c[1], c[2]);
        let (m1, a1) = minor(c[0], c[2]);
        let (m2, a2) = minor(c[0], c[1]);
        let (t0, t1, t2) = (rows[0][c[0]] * m0, rows[0][c[1]] * m1, rows[0][c[2]] * m2);
        let det = t0 - t1 + t2;
        // Products of two `f32` are exact; each minor's difference, each
        // product with a row-0 entry and the two sums round: within `4u`
        // of the absolute terms, `5u` with room.
        let absolute =
            rows[0][c[0]].abs() * a0 + rows[0][c[1]].abs() * a1 + rows[0][c[2]].abs() * a2;
        // `-E`, so that `s` is positive for a back face.
        *e = if j % 2 == 0 { -det } else { det };
        *err = 5.0 * U * absolute;
    }
    (eye, error)
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use proptest::strategy::ValueTree;

    /// `D = det[M·Q0, M·Q1, M·Q2]` exactly, for integer entries and
    /// corners (what the test's `s` must have the opposite sign of).
    fn exact_d(m: &[[i64; 4]; 3], q: &[[i64; 3]; 3]) -> i128 {
        let clip: [[i128; 3]; 3] = core::array::from_fn(|corner| {
            core::array::from_fn(|row| {
                let r = m[row];
                i128::from(r[0] * q[corner][0] + r[1] * q[corner][1] + r[2] * q[corner][2] + r[3])
            })
        });
        // Rows of `clip` are corners; the determinant is the same.
        let [a, b, c] = clip;
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
    }

    /// The matrix with rows `x`, `y`, `w` from `m` (row `z` anything),
    /// each entry scaled by `2^scale`.
    fn mat4(m: &[[i64; 4]; 3], scale: i32) -> Mat4 {
        let f = |v: i64| v as f32 * 2f32.powi(scale);
        Mat4 {
            m: [
                m[0].map(f),
                m[1].map(f),
                [0.5, -0.25, 3.0, 1.0],
                m[2].map(f),
            ],
        }
    }

    /// Checks the test's verdicts for corners `q` (scaled by `2^qs`) and
    /// matrix `m` (scaled by `2^ms`) against the exact `D`: back only when
    /// `D < 0`, front only when `D > 0`. Returns the verdict.
    fn check(m: &[[i64; 4]; 3], q: &[[i64; 3]; 3], (ms, qs): (i32, i32)) -> Side {
        let eye = PlaneEye::new(&mat4(m, ms)).expect("finite");
        let corner = |k: usize| q[k].map(|v| v as f32 * 2f32.powi(qs));
        let plane = FacePlane::of_triangle(corner(0), corner(1), corner(2));
        // Scaling the corners by `2^qs` scales the translation column's
        // share differently: compare with the exact `D` of the scaled
        // problem, integers again after multiplying through.
        let d = if qs >= 0 {
            let q = q.map(|c| c.map(|v| v << qs));
            exact_d(m, &q)
        } else {
            let m = m.map(|r| [r[0], r[1], r[2], r[3] << -qs]);
            exact_d(&m, q)
        };
        let side = eye.side(&plane);
        match side {
            Side::Back => assert!(d < 0, "back, D = {d}"),
            Side::Front => assert!(d > 0, "front, D = {d}"),
            Side::Unsure => {}
        }
        side
    }

    fn matrix() -> impl Strategy<Value = [[i64; 4]; 3]> {
        proptest::array::uniform3(proptest::array::uniform4(-64i64..=64))
    }

    fn corners(range: i64) -> impl Strategy<Value = [[i64; 3]; 3]> {
        proptest::array::uniform3(proptest::array::uniform3(-range..=range))
    }

    proptest! {
        /// Any triangle and matrix of small integers, scaled by powers of
        /// two from `2^-40` to `2^40`: every verdict is the exact one.
        #[test]
        fn verdicts_are_exact(m in matrix(), q in corners(1024), ms in -40i32..=40, qs in -12i32..=12) {
            check(&m, &q, (ms, qs));
        }

        /// Nearly edge-on triangles (the third corner near the line of the
        /// first two): the verdicts stay exact where `D` is small.
        #[test]
        fn near_edge_on_verdicts_are_exact(
            m in matrix(), a in proptest::array::uniform3(-1000i64..=1000),
            b in proptest::array::uniform3(-1000i64..=1000), t in -3i64..=3,
            off in proptest::array::uniform3(-1i64..=1),
        ) {
            let c = core::array::from_fn(|k| a[k] + t * (b[k] - a[k]) + off[k]);
            check(&m, &[a, b, c], (0, 0));
        }
    }

    /// `v·2^-12` for an integer `v` of up to 24 bits shifted left by
    /// `0..=12` (a value with 24 significant bits, exact in `f32`): as
    /// `f32` and as the integer `v << shift` over `2^12`.
    fn value() -> impl Strategy<Value = (f32, i128)> {
        (-(1i64 << 24)..(1i64 << 24), 0u32..=12).prop_map(|(v, shift)| {
            let scaled = i128::from(v) << shift;
            (scaled as f32 * 2f32.powi(-12), scaled)
        })
    }

    proptest! {
        /// The plane's bounds hold where `f64` rounds: corners with 24
        /// significant bits over 12 bits of range (the normal's products
        /// exceed 53 bits), against the exact normal and offset in `i128`
        /// (over `2^24` and `2^36`), in `f64` and rounded to `f32`.
        #[test]
        fn plane_bounds_hold(
            q in proptest::array::uniform3(proptest::array::uniform3(value())),
            at_origin in proptest::bool::ANY,
        ) {
            // A first corner at the origin makes the offset exact, so the
            // normal's share of the tolerance is tested alone.
            let mut q = q;
            if at_origin {
                q[0] = [(0.0, 0); 3];
            }
            let corner = |k: usize| q[k].map(|(f, _)| f);
            let v = |k: usize, c: usize| q[k][c].1;
            let (d1, d2): ([i128; 3], [i128; 3]) = (
                core::array::from_fn(|c| v(1, c) - v(0, c)),
                core::array::from_fn(|c| v(2, c) - v(0, c)),
            );
            let normal: [i128; 3] = core::array::from_fn(|k| {
                let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                d1[i] * d2[j] - d1[j] * d2[i]
            });
            let offset: i128 = (0..3).map(|c| normal[c] * v(0, c)).sum();
            // |computed - exact|, exactly (the computed values are
            // multiples of `2^-scale`), then in `f64`.
            let error = |computed: f64, exact: i128, scale: i32| {
                ((computed * 2f64.powi(scale)) as i128 - exact).abs() as f64 * 2f64.powi(-scale)
            };
            let (n64, n_err, k64, k_err) = plane64(corner(0), corner(1), corner(2));
            for c in 0..3 {
                prop_assert!(error(n64[c], normal[c], 24) <= n_err[c]);
            }
            prop_assert!(error(k64, offset, 36) <= k_err);
            let plane = FacePlane::of_triangle(corner(0), corner(1), corner(2));
            prop_assume!(plane != FacePlane::NONE);
            let tau = f64::from(plane.tolerance);
            for (c, (&rounded, &exact)) in plane.normal.iter().zip(&normal).enumerate() {
                let e = error(f64::from(rounded), exact, 24);
                prop_assert!(3.0 * e <= tau, "normal {c}: {e:e}, tolerance {tau:e}");
            }
            let e = error(f64::from(plane.offset), offset, 36);
            prop_assert!(e <= tau, "offset: {e:e}, tolerance {tau:e}");
        }

        /// The eye's bounds hold where `f64` rounds: entries of 24
        /// significant bits over 12 bits of range, each `E_j` exact in
        /// `i128` (over `2^36`).
        #[test]
        fn eye_bound_holds(rows in proptest::array::uniform3(proptest::array::uniform4(value()))) {
            let m = Mat4 {
                m: [rows[0].map(|v| v.0), rows[1].map(|v| v.0), [0.0; 4], rows[2].map(|v| v.0)],
            };
            let (eye, bound) = eye_of(&m);
            let r = |i: usize, j: usize| rows[i][j].1;
            for j in 0..4 {
                let c = match j {
                    0 => [1, 2, 3],
                    1 => [0, 2, 3],
                    2 => [0, 1, 3],
                    _ => [0, 1, 2],
                };
                let det = r(0, c[0]) * (r(1, c[1]) * r(2, c[2]) - r(1, c[2]) * r(2, c[1]))
                    - r(0, c[1]) * (r(1, c[0]) * r(2, c[2]) - r(1, c[2]) * r(2, c[0]))
                    + r(0, c[2]) * (r(1, c[0]) * r(2, c[1]) - r(1, c[1]) * r(2, c[0]));
                // `-E_j` as kept.
                let exact = if j % 2 == 0 { -det } else { det };
                let error = (eye[j] - exact as f64 * 2f64.powi(-36)).abs();
                prop_assert!(error <= bound[j], "E_{j}: error {error:e}, bound {:e}", bound[j]);
            }
        }
    }

    /// The test decides: of random triangles, nearly all are called (a
    /// test that always said "unsure" would pass the checks above).
    #[test]
    fn random_triangles_are_decided() {
        let mut runner = proptest::test_runner::TestRunner::deterministic();
        let (mut decided, mut total) = (0, 0);
        for _ in 0..2000 {
            let m = matrix().new_tree(&mut runner).expect("matrix").current();
            let q = corners(1024)
                .new_tree(&mut runner)
                .expect("corners")
                .current();
            total += 1;
            decided += usize::from(check(&m, &q, (0, 0)) != Side::Unsure);
        }
        assert!(decided * 100 >= total * 99, "{decided} of {total} decided");
    }

    /// Corners at the extremes of `f32`: a plane that overflows tests
    /// nothing, and a tiny one still decides.
    #[test]
    fn extremes() {
        let big = FacePlane::of_triangle([0.0; 3], [3e38, 0.0, 0.0], [0.0, 3e38, 0.0]);
        assert_eq!(big, FacePlane::NONE);
        let nan = FacePlane::of_triangle([f32::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(nan, FacePlane::NONE);
        let m = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, 3]];
        let eye = PlaneEye::new(&mat4(&m, 0)).expect("finite");
        assert_eq!(eye.side(&FacePlane::NONE), Side::Unsure);
        // `2^-60` units: facing the eye at (0, 0, 3).
        let t = 2f32.powi(-60);
        let tiny = FacePlane::of_triangle([0.0; 3], [t, 0.0, 0.0], [0.0, t, 0.0]);
        assert_eq!(eye.side(&tiny), Side::Front);
        let turned = FacePlane::of_triangle([0.0; 3], [0.0, t, 0.0], [t, 0.0, 0.0]);
        assert_eq!(eye.side(&turned), Side::Back);
    }
}
