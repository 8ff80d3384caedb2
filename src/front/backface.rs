//! The back-face test of quantized triangles in model space, before any of
//! their corners is transformed: a face of a closed mesh whose front side
//! is turned away from the eye is left out for the cost of two small cross
//! products, and a vertex that only back faces use is never transformed or
//! projected.
//!
//! # Why it holds
//!
//! The integer frame ([`FixedFrame`]) sends a quantized position `q` to
//! clip rows `x, y, w = A·q + c` (`A` the 3x3 of those rows). Its *eye* is
//! the point `e` with `A·e + c = 0`. Then the determinant of the three
//! corners' `(x, y, w)` rows is `det(A) · N·(q0 - e)` with `N = (q1 - q0) x
//! (q2 - q0)`, and for corners in front of the eye (`w > 0`) its sign is
//! the sign of the projected triangle's orientation; screen `y` points
//! down, so the projected cross product that
//! [`draw_mesh`](crate::front::scene::draw_mesh) culls on (positive: turned
//! away) has the sign of `sign(det A) · N·(e - q0)`. Where the eye is on a
//! face's back side, every part of it, clipped or not, is seen from
//! behind.
//!
//! The test works in 32-bit integers (one multiply each on a Cortex-M0+)
//! and says "away" only beyond doubt:
//!
//! * `e` is solved by Cramer's rule, once per draw, to within `0.76` per
//!   component ([`EyeTest::new`]): below 1.
//! * `N` is exact in `i32` when every edge component lies in `[-2^15,
//!   2^15)` (each product at most `2^30`, and as a factor of `2^15` is out
//!   of range, each difference of two below `2^31 - 2^15` in magnitude);
//!   other triangles are not tested here.
//! * `N` is shifted right by `m` (0, 8, 16 or 17) so that each component
//!   of `n = N >> m` is below `2^14`, and `v = (e >> h) - (q0 >> h)` with
//!   `h` chosen per draw so that each component is at most `2^15`; so
//!   each product `n_k v_k` is below `2^29` and `s = n·v` below `3·2^29`.
//! * `N = 2^m n + r_N` with `0 <= r_N,k < 2^m`, and `e_exact - q0 = 2^h v +
//!   r_v` with `|r_v,k| < 2^h + 1`, so `N·(e_exact - q0) = 2^(m+h) s +
//!   2^m n·r_v + r_N·(e_exact - q0)`, and the last two terms together are
//!   below `2^(m+h) · ((1 + 2^-h) (|n|_1 + 3) + |v|_1)`. So `σ s > 2
//!   |n|_1 + |v|_1 + 6` (`σ = sign(det A)`) makes `σ N·(e_exact - q0)`
//!   positive: the exact projection is turned away; and `σ s < -(2
//!   |n|_1 + |v|_1 + 6)` makes it negative: turned towards the eye.
//!   `|v|_1` is bounded once per draw, for every `q0` a quantized mesh
//!   can hold.
//! * `n` depends on the triangle alone ([`exact_normal`]): a quantized
//!   mesh may carry them in a table, checked when it is made
//!   ([`QuantizedMesh::with_exact_normals`](crate::front::quantized::QuantizedMesh::with_exact_normals)), so a draw reads three
//!   numbers a face instead of working them out.
//!
//! A back face is left out at once. A front face skips the early
//! screen-space test on its projected (rounded) corners, which the tables
//! repeat when they take it; a triangle too close to call takes that test
//! as before. So the test only leaves out, earlier, triangles that the
//! exact projection turns away (a few of which, seen almost edge-on, the
//! rounded corners would have turned by a hair).

use crate::front::fixed_point::FixedFrame;

/// Largest eye coordinate, in quantized units, the test accepts.
const EYE_MAX: u64 = 1 << 28;

/// The eye of a draw's integer frame, ready for [`EyeTest::side_of`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EyeTest {
    /// The eye in quantized units, rounded, shifted right by `shift`.
    eye: [i32; 3],
    /// `h`: `(|e_k| + 2^15) <= (2^15 - 1) · 2^h` for every component.
    shift: u32,
    /// `sign(det A)`: `1` or `-1`.
    sign: i32,
    /// A bound on `|v|_1` for every quantized `q0` (`Σ_k floor((|e_k| +
    /// 2^15) / 2^h) + 1`), plus 6: see [`EyeTest::side_of`].
    slack: i32,
}

/// Which side of a triangle the eye is on, as far as [`EyeTest::side`]
/// can tell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The exact projection of the triangle is turned away: a back face.
    Back,
    /// The exact projection is turned towards the eye: a front face.
    Front,
    /// Too close to call (or an edge too long for the test).
    Unsure,
}

impl EyeTest {
    /// The eye of `frame`; `None` when its `x`, `y` and `w` rows are
    /// singular (no single eye) or the eye lies beyond `2^28` quantized
    /// units (the test would learn little).
    ///
    /// By Cramer's rule over the cofactors of `A`: `|A_ij| <= 2^30` and
    /// `|c_i| <= 2^45`, so each cofactor is below `2^61` (`i64`), `det A`
    /// below `2^93` and each numerator below `2^108` (`i128`). Each
    /// quotient is then taken in `i64`, numerator and `|det A|` shifted
    /// right alike until `|det A|` is below `2^32`: with the shifted
    /// numerator at most `2^60` the shifted quotient is within `(1 +
    /// 2^29) / 2^31 < 0.26` of the exact one, so the rounded eye is within
    /// `0.76` of it in each component.
    pub fn new(frame: &FixedFrame) -> Option<Self> {
        let (a, c) = frame.xyw_rows();
        Self::from_rows(a, c)
    }

    /// [`EyeTest::new`] for the rows `A·q + c` (`|A_ij| <= 2^30`, `|c_i| <=
    /// 2^45`).
    fn from_rows(a: [[i32; 3]; 3], c: [i64; 3]) -> Option<Self> {
        let p = |x: i32, y: i32| i64::from(x) * i64::from(y);
        let minor = |r: [usize; 2], k: [usize; 2]| {
            p(a[r[0]][k[0]], a[r[1]][k[1]]) - p(a[r[0]][k[1]], a[r[1]][k[0]])
        };
        // cofactor[i][j] of A: the signed minor without row i, column j.
        let cofactor: [[i64; 3]; 3] = core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                let others = |x: usize| match x {
                    0 => [1, 2],
                    1 => [0, 2],
                    _ => [0, 1],
                };
                let m = minor(others(i), others(j));
                if (i + j) % 2 == 0 { m } else { -m }
            })
        });
        let det: i128 = (0..3)
            .map(|j| i128::from(a[0][j]) * i128::from(cofactor[0][j]))
            .sum();
        if det == 0 {
            return None;
        }
        let sign = det.signum();
        let magnitude = det.unsigned_abs();
        let drop = (128 - magnitude.leading_zeros()).saturating_sub(32);
        let divisor = (magnitude >> drop) as i64;
        let mut eye = [0i32; 3];
        for (j, eye) in eye.iter_mut().enumerate() {
            // Column j replaced by -c.
            let numerator: i128 = (0..3)
                .map(|i| -i128::from(c[i]) * i128::from(cofactor[i][j]))
                .sum::<i128>()
                * sign;
            let shifted = numerator >> drop;
            if shifted.unsigned_abs() > 1 << 60 {
                return None;
            }
            let n = shifted as i64;
            // Rounded to nearest: 2|n| + divisor < 2^62.
            let e = if n >= 0 {
                (2 * n + divisor) / (2 * divisor)
            } else {
                -((-2 * n + divisor) / (2 * divisor))
            };
            if e.unsigned_abs() > EYE_MAX {
                return None;
            }
            *eye = e as i32;
        }
        // |e_k| <= 2^28: the shift ends at most at 14.
        let reach = eye.iter().map(|e| e.unsigned_abs()).max().unwrap_or(0) + (1 << 15);
        let mut shift = 0;
        while reach > ((1 << 15) - 1) << shift {
            shift += 1;
        }
        // Each term at most 2^15: the slack is below 2^17.
        let v_bound: u32 = eye
            .iter()
            .map(|e| ((e.unsigned_abs() + (1 << 15)) >> shift) + 1)
            .sum();
        Some(Self {
            eye: eye.map(|e| e >> shift),
            shift,
            sign: sign as i32,
            slack: v_bound as i32 + 6,
        })
    }

    /// Which side of the triangle of quantized corners `q0 q1 q2` the eye
    /// is on: [`EyeTest::side_of`] with the triangle's [`exact_normal`]
    /// (for a mesh without a table of them).
    #[inline(never)]
    pub fn side(&self, q0: &[i16; 3], q1: &[i16; 3], q2: &[i16; 3]) -> Side {
        self.side_of(&exact_normal(*q0, *q1, *q2), q0)
    }

    /// Which side of a triangle the eye is on, beyond doubt (see the module
    /// notes), or [`Side::Unsure`], from the triangle's shifted exact
    /// normal `n` ([`exact_normal`]: zero for a triangle not tested) and its
    /// first corner `q0`: `s = σ n·v` against the doubt `2 |n|_1 + slack`.
    /// Every product is below `2^29` and `s` below `3·2^29`.
    #[inline]
    pub fn side_of(&self, n: &[i16; 3], q0: &[i16; 3]) -> Side {
        let (nx, ny, nz) = (i32::from(n[0]), i32::from(n[1]), i32::from(n[2]));
        let h = self.shift;
        let (vx, vy, vz) = (
            self.eye[0] - (i32::from(q0[0]) >> h),
            self.eye[1] - (i32::from(q0[1]) >> h),
            self.eye[2] - (i32::from(q0[2]) >> h),
        );
        let s = self.sign * (nx * vx + ny * vy + nz * vz);
        // |n|_1 < 3·2^14: the doubt is below 2^18.
        let doubt = 2 * (nx.abs() + ny.abs() + nz.abs()) + self.slack;
        if s > doubt {
            Side::Back
        } else if s < -doubt {
            Side::Front
        } else {
            Side::Unsure
        }
    }
}

/// The exact normal `N = (q1 - q0) x (q2 - q0)` of a triangle of quantized
/// corners, shifted right (by 0, 8, 16 or 17 bits, rounding down) until
/// every component is below `2^14` in magnitude: what
/// [`EyeTest::side_of`] takes. Zero, which no test calls, when an edge
/// component lies outside `[-2^15, 2^15)`: `N` is exact in `i32` only
/// inside (each product at most `2^30`, each difference of two below
/// `2^31 - 2^15` in magnitude). `const`, so that a flash mesh's table
/// ([`QuantizedMesh::with_exact_normals`](crate::front::quantized::QuantizedMesh::with_exact_normals)) is checked at compile time.
pub const fn exact_normal(q0: [i16; 3], q1: [i16; 3], q2: [i16; 3]) -> [i16; 3] {
    let (x0, y0, z0) = (q0[0] as i32, q0[1] as i32, q0[2] as i32);
    let (ax, ay, az) = (q1[0] as i32 - x0, q1[1] as i32 - y0, q1[2] as i32 - z0);
    let (bx, by, bz) = (q2[0] as i32 - x0, q2[1] as i32 - y0, q2[2] as i32 - z0);
    // x + 2^15 below 2^16 as u32 exactly for x in [-2^15, 2^15), so the
    // `or` of all six is too.
    let short = (ax + (1 << 15)) as u32
        | (ay + (1 << 15)) as u32
        | (az + (1 << 15)) as u32
        | (bx + (1 << 15)) as u32
        | (by + (1 << 15)) as u32
        | (bz + (1 << 15)) as u32;
    if short >= 1 << 16 {
        return [0; 3];
    }
    let (nx, ny, nz) = (ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx);
    // The `or` of the magnitudes: at least the largest, below the same
    // powers of two.
    let big = nx.unsigned_abs() | ny.unsigned_abs() | nz.unsigned_abs();
    let m = if big < 1 << 14 {
        0
    } else if big < 1 << 22 {
        8
    } else if big < 1 << 30 {
        16
    } else {
        17
    };
    [(nx >> m) as i16, (ny >> m) as i16, (nz >> m) as i16]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::fixed_point::FixedFrame;
    use crate::front::geometry::Mat4;
    use crate::front::scene::Camera;
    use proptest::prelude::*;

    /// The exact side, for rows small enough that `i128` holds it: the
    /// sign of `sign(det A) · N·(e - q0)` with `e = num / det`, that is of
    /// `N·(num - q0·det)` (times `sign(det)^2`).
    fn exact(a: [[i32; 3]; 3], c: [i64; 3], q: [[i16; 3]; 3]) -> Option<i128> {
        let m = a.map(|r| r.map(i128::from));
        let det3 = |m: [[i128; 3]; 3]| {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        let det = det3(m);
        if det == 0 {
            return None;
        }
        let num: [i128; 3] = core::array::from_fn(|j| {
            let mut mj = m;
            for i in 0..3 {
                mj[i][j] = -i128::from(c[i]);
            }
            det3(mj)
        });
        let q = q.map(|p| p.map(i128::from));
        let d = |i: usize, k: usize| q[i][k] - q[0][k];
        let n = [
            d(1, 1) * d(2, 2) - d(1, 2) * d(2, 1),
            d(1, 2) * d(2, 0) - d(1, 0) * d(2, 2),
            d(1, 0) * d(2, 1) - d(1, 1) * d(2, 0),
        ];
        Some((0..3).map(|k| n[k] * (num[k] - q[0][k] * det)).sum())
    }

    fn coord() -> impl Strategy<Value = i16> {
        prop_oneof![any::<i16>(), -300i16..300, Just(i16::MIN), Just(i16::MAX)]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]

        /// Small rows (so the exact side fits `i128`), any corners: a side
        /// the test names is the exact one.
        #[test]
        fn a_named_side_is_the_exact_side(
            a in prop::array::uniform3(prop::array::uniform3(-(1i32 << 12)..(1 << 12))),
            c in prop::array::uniform3(-(1i64 << 22)..(1 << 22)),
            q in prop::array::uniform3(prop::array::uniform3(coord())),
        ) {
            let (Some(test), Some(exact)) = (EyeTest::from_rows(a, c), exact(a, c, q)) else {
                return Ok(());
            };
            match test.side(&q[0], &q[1], &q[2]) {
                Side::Back => prop_assert!(exact > 0, "{exact}"),
                Side::Front => prop_assert!(exact < 0, "{exact}"),
                Side::Unsure => {}
            }
        }
    }

    /// The extremes of every range: rows at `2^30` and offsets at `2^45`,
    /// the eye at the edge of `EYE_MAX`, corners at both ends of `i16` and
    /// edges at both ends of `[-2^15, 2^15)` (overflow checks on in tests).
    #[test]
    fn the_extremes_do_not_overflow() {
        let big = 1 << 30;
        let rows = [
            (
                [[big, 0, 0], [0, big, 0], [0, 0, big]],
                [1i64 << 45, -(1 << 45), 1 << 45],
            ),
            (
                [[big, -big, big], [-big, big, big], [big, big, -big]],
                [1 << 45; 3],
            ),
            // The eye at 2^28 units: x = y = w = 0 at e = (2^28, 0, 0).
            ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [-(1 << 28), 0, 0]),
            (
                [[4, 0, 0], [0, 4, 0], [0, 0, 4]],
                [1 << 30, 1 << 30, -(1 << 30)],
            ),
        ];
        let ends = [i16::MIN, -1, 0, 1, i16::MAX];
        let mut named = 0;
        for (a, c) in rows {
            let Some(test) = EyeTest::from_rows(a, c) else {
                continue;
            };
            for &x in &ends {
                for &y in &ends {
                    // Edges of -2^15 and 2^15 - 1 and the extreme corners.
                    let q0 = [x, y, 0];
                    let q1 = [x.wrapping_add(i16::MIN), y, i16::MAX];
                    let q2 = [x, y.wrapping_add(i16::MAX), i16::MIN];
                    let side = test.side(&q0, &q1, &q2);
                    if side != Side::Unsure {
                        named += 1;
                    }
                    // Rotating the corners moves no plane: a side named
                    // both ways is the same side.
                    let rotated = test.side(&q2, &q0, &q1);
                    if side != Side::Unsure && rotated != Side::Unsure {
                        assert_eq!(side, rotated, "{q0:?} {q1:?} {q2:?}");
                    }
                }
            }
        }
        assert!(named > 0);
        // Beyond 2^28 units: no test.
        assert_eq!(
            EyeTest::from_rows([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [-(1 << 29), 0, 0]),
            None
        );
        // Singular rows: no eye.
        assert_eq!(
            EyeTest::from_rows([[1, 2, 3], [2, 4, 6], [0, 0, 1]], [0; 3]),
            None
        );
    }

    /// Real frames (the integer front end's, for a quantized sphere of
    /// triangles seen from many sides): a triangle the test names faces the
    /// way its projected, rounded corners do, but for triangles of nearly
    /// no projected area; and most triangles are named.
    #[test]
    fn named_sides_agree_with_the_projected_corners() {
        let camera = Camera::reference(240, 240);
        let mut seed = 0x1234_5678_9abc_def1u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let (mut named, mut total) = (0, 0);
        for view in 0..40 {
            let yaw = (view * 37 % 360) as f32;
            let pitch = (view * 23 % 170) as f32 - 85.0;
            let model = crate::front::scene::reference_model_around(
                crate::front::geometry::Vec3::new(0.1, -0.2, 0.3),
                1.5,
                yaw,
                pitch,
            );
            let mv = camera.view.mul(&model);
            let mvp: Mat4 = camera.projection.mul(&mv);
            let frame = FixedFrame::new(&mvp, &mv, [0.1, -0.2, 0.3], 1.5, 240, 240).unwrap();
            let test = EyeTest::new(&frame).unwrap();
            for _ in 0..200 {
                // A small triangle on the sphere of radius 30000.
                let r = |k: u64| (k % 2001) as f64 / 1000.0 - 1.0;
                let (u, v) = (r(next()), r(next()));
                let theta = u * core::f64::consts::PI;
                let phi = v * core::f64::consts::FRAC_PI_2;
                let at = |t: f64, p: f64| {
                    [t.cos() * p.cos(), t.sin() * p.cos(), p.sin()].map(|x| (x * 30000.0) as i16)
                };
                let size = 0.002 + 0.1 * r(next()).abs();
                let q = [at(theta, phi), at(theta + size, phi), at(theta, phi + size)];
                let corners = q.map(|p| frame.project(&frame.clip(p)));
                let [Some(a), Some(b), Some(c)] = corners else {
                    continue;
                };
                let cross = i64::from(b.x - a.x) * i64::from(c.y - a.y)
                    - i64::from(b.y - a.y) * i64::from(c.x - a.x);
                // Rounding moves each corner by under a sub-pixel step.
                let slack = 4
                    * (i64::from(
                        (b.x - a.x).abs()
                            + (c.x - a.x).abs()
                            + (b.y - a.y).abs()
                            + (c.y - a.y).abs(),
                    ) + 4);
                total += 1;
                match test.side(&q[0], &q[1], &q[2]) {
                    Side::Back => {
                        named += 1;
                        assert!(cross > -slack, "view {view}: {cross}");
                    }
                    Side::Front => {
                        named += 1;
                        assert!(cross < slack, "view {view}: {cross}");
                    }
                    Side::Unsure => {}
                }
            }
        }
        assert!(named * 10 >= total * 9, "{named} of {total}");
    }
}
