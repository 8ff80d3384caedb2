//! The exact oracle for the scanline core: coverage by the even-odd rule
//! with the top-left convention and each polygon's plane depth, in exact
//! integer (rational) arithmetic, written independently of the renderer's
//! incremental code. The tests and the fuzzers judge the core by it.

use std::format;
use std::string::String;
use std::vec::Vec;

use zline::DepthFormat;
use zline::ScreenVertex;
use zline::limits::{DEPTH_MAX, HALF_PIXEL, SUBPIXEL_STEPS};

/// Sample point of pixel `(i, j)` in sub-pixel steps.
pub fn sample(i: i32, j: i32) -> (i64, i64) {
    (
        i64::from(i) * i64::from(SUBPIXEL_STEPS) + i64::from(HALF_PIXEL),
        i64::from(j) * i64::from(SUBPIXEL_STEPS) + i64::from(HALF_PIXEL),
    )
}

/// Whether pixel `(i, j)`'s sample is inside `poly`: the number of edges
/// crossing the sample's row (top inclusive, bottom exclusive) at or left of
/// the sample is odd.
pub fn covers(poly: &[ScreenVertex], i: i32, j: i32) -> bool {
    let (xs, ys) = sample(i, j);
    let mut inside = false;
    for k in 0..poly.len() {
        let (mut a, mut b) = (poly[k], poly[(k + 1) % poly.len()]);
        if a.y == b.y {
            continue;
        }
        if a.y > b.y {
            core::mem::swap(&mut a, &mut b);
        }
        let (ax, ay, bx, by) = (
            i64::from(a.x),
            i64::from(a.y),
            i64::from(b.x),
            i64::from(b.y),
        );
        if ay <= ys && ys < by {
            // crossing x = ax + (ys - ay)(bx - ax)/(by - ay) <= xs
            if (ax - xs) * (by - ay) + (ys - ay) * (bx - ax) <= 0 {
                inside = !inside;
            }
        }
    }
    inside
}

/// The plane through `poly` (Newell's normal, through corner 0) as
/// `(numerator, denominator)` of the depth at pixel `(i, j)`'s sample, in
/// input depth steps (Q0.24 units): depth = num / den exactly, `den > 0`;
/// `den == 0` for a polygon of zero area.
pub fn exact_depth(poly: &[ScreenVertex], i: i32, j: i32) -> (i128, i128) {
    let o = poly[0];
    let rel = |v: ScreenVertex| {
        (
            i128::from(v.x) - i128::from(o.x),
            i128::from(v.y) - i128::from(o.y),
            i128::from(v.z) - i128::from(o.z),
        )
    };
    let (mut a, mut b, mut c) = (0i128, 0i128, 0i128);
    for k in 0..poly.len() {
        let (px, py, pz) = rel(poly[k]);
        let (qx, qy, qz) = rel(poly[(k + 1) % poly.len()]);
        a += (py - qy) * (pz + qz);
        b += (pz - qz) * (px + qx);
        c += (px - qx) * (py + qy);
    }
    let (xs, ys) = sample(i, j);
    let num = i128::from(o.z) * c
        - a * (i128::from(xs) - i128::from(o.x))
        - b * (i128::from(ys) - i128::from(o.y));
    if c < 0 { (-num, -c) } else { (num, c) }
}

/// The exactly rounded stored value of a format with `lsb` input steps per
/// step and `max` its largest value: round-half-up of num/(den·lsb),
/// clamped.
pub fn exactly_rounded(num: i128, den: i128, lsb: i128, max: i128) -> i128 {
    let d = den * lsb;
    (2 * num + d).div_euclid(2 * d).clamp(0, max)
}

/// Input-depth steps per stored step and largest stored value of a format.
pub fn format_scale<D: DepthFormat>() -> (i128, i128) {
    match D::BITS {
        16 => (256, i128::from(u16::MAX)),
        _ => (1, i128::from(DEPTH_MAX)),
    }
}

/// A polygon offered to the tables, as the oracle sees it.
#[derive(Debug, Clone)]
pub struct Offered {
    /// Its corners.
    pub corners: Vec<ScreenVertex>,
    /// The three corners of the plane it shares, if it was given one
    /// ([`Tables::share_plane`](zline::Tables::share_plane)).
    pub plane: Option<[ScreenVertex; 3]>,
    /// Whether it was queued.
    pub queued: bool,
}

impl Offered {
    /// The exact depth of its plane (the shared one, if any) at pixel
    /// `(i, j)`, as [`exact_depth`].
    pub fn depth(&self, i: i32, j: i32) -> (i128, i128) {
        match &self.plane {
            Some(plane) => exact_depth(plane, i, j),
            None => exact_depth(&self.corners, i, j),
        }
    }
}

/// Checks a rendered frame against a brute-force exact z-buffer.
///
/// `polygons` are the scene's polygons in the order they were offered, with
/// whether each was queued; polygon `k` was drawn in colour `k + 1` and
/// background is 0. Per pixel the reference takes every queued polygon
/// whose sample test passes and whose exactly rounded depth (clamped to
/// the format's range) is nearer than the far plane. The frame must show
/// background where there is none, and otherwise one whose exactly rounded
/// depth is within 2 steps of the nearest (a tie the format cannot order),
/// with its stored depth within 1 LSB of its exactly rounded one. A polygon
/// left out must cover no sample. `Err` describes the first violation.
pub fn check_frame<D: DepthFormat>(
    polygons: &[(Vec<ScreenVertex>, bool)],
    width: usize,
    height: usize,
    colors: &[u32],
    depths: &[u64],
) -> Result<(), String> {
    let offered: Vec<Offered> = polygons
        .iter()
        .map(|(corners, queued)| Offered {
            corners: corners.clone(),
            plane: None,
            queued: *queued,
        })
        .collect();
    check_frame_shared::<D>(&offered, width, height, colors, depths)
}

/// [`check_frame`] for polygons that may share planes: a polygon's depth
/// is its shared plane's, and where polygons of one shared plane cover a
/// pixel, a later one of them is never drawn over the first (their depths
/// are equal exactly, so the first added wins unless another is nearer).
pub fn check_frame_shared<D: DepthFormat>(
    polygons: &[Offered],
    width: usize,
    height: usize,
    colors: &[u32],
    depths: &[u64],
) -> Result<(), String> {
    let (lsb, max) = format_scale::<D>();
    for (
        k,
        Offered {
            corners: poly,
            queued,
            ..
        },
    ) in polygons.iter().enumerate()
    {
        if *queued {
            continue;
        }
        for j in 0..height as i32 {
            for i in 0..width as i32 {
                let (_, den) = exact_depth(poly, i, j);
                if den != 0 && covers(poly, i, j) {
                    return Err(format!("left-out polygon {k} covers ({i}, {j}): {poly:?}"));
                }
            }
        }
    }
    for j in 0..height as i32 {
        for i in 0..width as i32 {
            let at = j as usize * width + i as usize;
            let (drawn, stored) = (colors[at], i128::from(depths[at]));
            // (exactly rounded depth, colour) of every covering polygon.
            let candidates: Vec<(i128, u32)> = polygons
                .iter()
                .enumerate()
                .filter(|(_, p)| p.queued && covers(&p.corners, i, j))
                .map(|(k, p)| {
                    let (num, den) = p.depth(i, j);
                    (exactly_rounded(num, den, lsb, max), k as u32 + 1)
                })
                .collect();
            let best = candidates.iter().map(|c| c.0).min().unwrap_or(max);
            if drawn == 0 {
                // The row clears to the far plane (max) and the depth test
                // is strict: a surface within 1 LSB of it may go unseen.
                if best >= max - 1 {
                    continue;
                }
                return Err(format!(
                    "({i}, {j}) is background, expected one of {candidates:?}"
                ));
            }
            let Some(hit) = candidates.iter().find(|c| c.1 == drawn) else {
                return Err(format!(
                    "({i}, {j}) drew {drawn}, which does not cover it; expected one of {candidates:?}"
                ));
            };
            if hit.0 - best > 2 {
                return Err(format!(
                    "({i}, {j}) drew {drawn} at depth {}, but the nearest is at {best}: {candidates:?}",
                    hit.0
                ));
            }
            let drawn_plane = polygons[drawn as usize - 1].plane;
            let earlier_same_plane = candidates.iter().find(|c| {
                c.1 < drawn
                    && drawn_plane.is_some()
                    && polygons[c.1 as usize - 1].plane == drawn_plane
            });
            if let Some(first) = earlier_same_plane {
                return Err(format!(
                    "({i}, {j}) drew {drawn} over {}, added earlier on the same shared plane",
                    first.1
                ));
            }
            if (stored - hit.0).abs() > 1 {
                return Err(format!(
                    "({i}, {j}) stored depth {stored}, exactly rounded {}",
                    hit.0
                ));
            }
        }
    }
    Ok(())
}
