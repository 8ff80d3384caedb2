//! Exact references shared by the integration tests: coverage by the
//! even-odd rule with the top-left convention, and the plane's depth, both
//! in exact integer (rational) arithmetic, written independently of the
//! renderer's incremental code.
#![allow(dead_code)]

use zline::fixed::{HALF_PIXEL, SUBPIXEL_STEPS};
use zline::{DepthFormat, FnSink, Renderer, ScreenVertex};

/// Sample point of pixel `(i, j)` in sub-pixel steps.
pub fn sample(i: i32, j: i32) -> (i64, i64) {
    (
        i64::from(i * SUBPIXEL_STEPS + HALF_PIXEL),
        i64::from(j * SUBPIXEL_STEPS + HALF_PIXEL),
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
/// input depth steps (Q0.24 units): depth = num / den exactly, den > 0.
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

/// Exact depth as f64 (for tie tolerance only).
pub fn exact_depth_f64(poly: &[ScreenVertex], i: i32, j: i32) -> f64 {
    let (n, d) = exact_depth(poly, i, j);
    n as f64 / d as f64
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
        24 => (1, i128::from(zline::fixed::DEPTH_MAX)),
        bits => panic!("unknown format with {bits} bits"),
    }
}

/// A frame captured from the renderer: colour and depth per pixel.
pub struct Frame<Z> {
    pub width: usize,
    pub height: usize,
    pub colors: Vec<u32>,
    pub depths: Vec<Z>,
    pub rows_written: Vec<u16>,
}

impl<Z: Copy> Frame<Z> {
    pub fn color(&self, i: usize, j: usize) -> u32 {
        self.colors[j * self.width + i]
    }
    pub fn depth(&self, i: usize, j: usize) -> Z {
        self.depths[j * self.width + i]
    }
    /// The frame as text, one char per pixel: '.' for 0, else
    /// `alphabet[color - 1]`.
    pub fn art(&self, alphabet: &str) -> String {
        let chars: Vec<char> = alphabet.chars().collect();
        let mut s = String::new();
        for j in 0..self.height {
            for i in 0..self.width {
                let c = self.color(i, j);
                s.push(if c == 0 { '.' } else { chars[(c - 1) as usize] });
            }
            s.push('\n');
        }
        s
    }
}

/// Renders with colours `u32` and captures the frame.
pub fn capture<
    D: DepthFormat,
    const W: usize,
    const V: usize,
    const P: usize,
    const E: usize,
    const AP: usize,
    const AE: usize,
    const N: usize,
>(
    renderer: &mut Renderer<u32, D, W, V, P, E, AP, AE, N>,
) -> (Frame<D::Value>, zline::FrameStats) {
    let h = usize::from(renderer.height());
    let mut frame = Frame {
        width: W,
        height: h,
        colors: vec![0; W * h],
        depths: vec![D::CLEAR; W * h],
        rows_written: Vec::new(),
    };
    let stats = renderer
        .render(&mut FnSink(
            |y: u16, colors: &[u32], depths: &[D::Value]| {
                let row = usize::from(y) * W;
                frame.colors[row..row + W].copy_from_slice(colors);
                frame.depths[row..row + W].copy_from_slice(depths);
                frame.rows_written.push(y);
                Ok::<(), ()>(())
            },
        ))
        .expect("render");
    (frame, stats)
}

/// Pixel-corner coordinates (whole pixels) to a vertex.
pub fn vtx(x: f32, y: f32, z: f32) -> ScreenVertex {
    ScreenVertex::from_f32(x, y, z).expect("valid vertex")
}

/// Dense art from a text block: strips leading/trailing blank lines and
/// indentation.
pub fn art(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(|l| format!("{l}\n"))
        .collect()
}
