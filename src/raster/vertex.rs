//! Screen-space vertices, the renderer's input, and their bounding
//! rectangle.

use core::ops::Range;

use crate::error::Error;
use crate::limits::{DEPTH_MAX, GUARD_BAND, HALF_PIXEL, SUBPIXEL_STEPS};
use crate::raster::fixed::{
    depth_from_f32, depth_from_f64, first_sample_at_or_after, subpixel_from_f32, subpixel_from_f64,
};

/// A vertex after projection: position on the sub-pixel grid and depth.
///
/// `x` and `y` are in 1/256 pixel ([`crate::limits::SUBPIXEL_STEPS`]),
/// `z` is Q0.24 with 0 at the near plane and
/// [`crate::limits::DEPTH_MAX`] at the far plane (smaller is
/// nearer). `z` must be affine in screen space (e.g. `z_ndc`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ScreenVertex {
    /// x in sub-pixel steps, to the right.
    pub x: i32,
    /// y in sub-pixel steps, downwards.
    pub y: i32,
    /// Depth, Q0.24, smaller is nearer.
    pub z: u32,
}

impl ScreenVertex {
    /// A vertex from raw fixed-point values, checked against the guard band
    /// and the depth range.
    pub const fn new(x: i32, y: i32, z: u32) -> Result<Self, Error> {
        let v = Self { x, y, z };
        match v.check() {
            Ok(()) => Ok(v),
            Err(e) => Err(e),
        }
    }

    /// A vertex from pixel coordinates and a depth in `[0, 1]`; NaN,
    /// infinities and out-of-range values are errors.
    pub fn from_f32(x: f32, y: f32, depth: f32) -> Result<Self, Error> {
        let x = subpixel_from_f32(x).ok_or(Error::OutsideGuardBand)?;
        let y = subpixel_from_f32(y).ok_or(Error::OutsideGuardBand)?;
        let z = depth_from_f32(depth).ok_or(Error::DepthOutOfRange)?;
        Ok(Self { x, y, z })
    }

    /// [`Self::from_f32`] for `f64` values.
    pub fn from_f64(x: f64, y: f64, depth: f64) -> Result<Self, Error> {
        let x = subpixel_from_f64(x).ok_or(Error::OutsideGuardBand)?;
        let y = subpixel_from_f64(y).ok_or(Error::OutsideGuardBand)?;
        let z = depth_from_f64(depth).ok_or(Error::DepthOutOfRange)?;
        Ok(Self { x, y, z })
    }

    /// Checks the guard band and the depth range.
    pub const fn check(&self) -> Result<(), Error> {
        if self.x <= -GUARD_BAND
            || self.x >= GUARD_BAND
            || self.y <= -GUARD_BAND
            || self.y >= GUARD_BAND
        {
            Err(Error::OutsideGuardBand)
        } else if self.z > DEPTH_MAX {
            Err(Error::DepthOutOfRange)
        } else {
            Ok(())
        }
    }
}

/// The bounding rectangle of some screen vertices, on the sub-pixel grid,
/// and the pixel samples it holds: the one bounding-box test the pipeline
/// and the core share.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScreenRect {
    /// Smallest x.
    pub x0: i32,
    /// Largest x.
    pub x1: i32,
    /// Smallest y.
    pub y0: i32,
    /// Largest y.
    pub y1: i32,
}

impl ScreenRect {
    /// The rectangle of one vertex.
    pub const fn point(v: ScreenVertex) -> Self {
        Self {
            x0: v.x,
            x1: v.x,
            y0: v.y,
            y1: v.y,
        }
    }

    /// Grows the rectangle to hold `v`.
    pub fn add(&mut self, v: ScreenVertex) {
        self.x0 = self.x0.min(v.x);
        self.x1 = self.x1.max(v.x);
        self.y0 = self.y0.min(v.y);
        self.y1 = self.y1.max(v.y);
    }

    /// The rectangle of `vertices`; `None` for none.
    pub fn of(vertices: impl IntoIterator<Item = ScreenVertex>) -> Option<Self> {
        let mut vertices = vertices.into_iter();
        let mut rect = Self::point(vertices.next()?);
        vertices.for_each(|v| rect.add(v));
        Some(rect)
    }

    /// Rows `[first, end)` of a `width` x `height` frame whose samples the
    /// rectangle may hold, or `None` when it holds no pixel sample of the
    /// frame (so no polygon inside it can cover one).
    pub fn sample_rows(&self, width: u16, height: u16) -> Option<(u16, u16)> {
        self.samples(width, height)
            .map(|(_, rows)| (rows.start, rows.end))
    }

    /// The columns and rows of a `width` x `height` frame whose samples
    /// (pixel centres) lie in the rectangle, or `None` when it holds none.
    /// As the fill rule: a sample on its left or top side is inside, on its
    /// right or bottom side outside (no polygon inside covers it).
    #[inline]
    pub fn samples(&self, width: u16, height: u16) -> Option<(Range<u16>, Range<u16>)> {
        let first_column = first_sample_at_or_after(self.x0).max(0);
        let end_column = first_sample_at_or_after(self.x1).min(i32::from(width));
        let first_row = first_sample_at_or_after(self.y0).max(0);
        let end_row = first_sample_at_or_after(self.y1).min(i32::from(height));
        (first_column < end_column && first_row < end_row).then_some((
            first_column as u16..end_column as u16,
            first_row as u16..end_row as u16,
        ))
    }
}

/// One edge of a [`TriangleTest`], its ends ordered top first.
#[derive(Debug, Clone, Copy)]
struct EdgeTest {
    top_x: i64,
    top_y: i32,
    bottom_y: i32,
    dx: i64,
    dy: i64,
}

impl EdgeTest {
    #[inline]
    fn new(p: ScreenVertex, q: ScreenVertex) -> Self {
        let (top, bottom) = if p.y <= q.y { (p, q) } else { (q, p) };
        Self {
            top_x: i64::from(top.x),
            top_y: top.y,
            bottom_y: bottom.y,
            dx: i64::from(bottom.x) - i64::from(top.x),
            dy: i64::from(bottom.y) - i64::from(top.y),
        }
    }

    /// Whether the edge spans row `ys` and crosses it at or left of `xs`:
    /// `top_x + (ys - top_y)·dx/dy <= xs` with `dy > 0`, multiplied out.
    /// Inside the guard band every product is below `2^44`. A horizontal
    /// edge spans no row. Branch-free: the three tests are combined with
    /// `&`, not `&&`.
    #[inline]
    fn counts(&self, xs: i32, ys: i32) -> bool {
        let spans = (ys >= self.top_y) & (ys < self.bottom_y);
        let left =
            (self.top_x - i64::from(xs)) * self.dy + i64::from(ys - self.top_y) * self.dx <= 0;
        spans & left
    }
}

/// The fill rule's sample test for one triangle, set up once and asked for
/// many samples (see [`TriangleTest::covers`]): the core uses it to drop tiny
/// triangles that cover none of the few samples in their bounding box, to
/// find the rows they do cover, and to draw those covering one row.
#[derive(Debug, Clone, Copy)]
pub struct TriangleTest {
    edges: [EdgeTest; 3],
}

impl TriangleTest {
    /// The test for triangle `a b c` (corners inside the guard band).
    #[inline]
    pub fn new(a: ScreenVertex, b: ScreenVertex, c: ScreenVertex) -> Self {
        Self {
            edges: [
                EdgeTest::new(a, b),
                EdgeTest::new(b, c),
                EdgeTest::new(c, a),
            ],
        }
    }

    /// Whether the triangle covers sample point `(xs, ys)` (sub-pixel steps).
    #[inline]
    pub fn covers(&self, xs: i32, ys: i32) -> bool {
        let [e0, e1, e2] = &self.edges;
        e0.counts(xs, ys) ^ e1.counts(xs, ys) ^ e2.counts(xs, ys)
    }

    /// Whether the triangle covers the sample of pixel `(column, row)`.
    #[inline]
    pub fn covers_pixel(&self, column: i32, row: i32) -> bool {
        self.covers(
            column * SUBPIXEL_STEPS + HALF_PIXEL,
            row * SUBPIXEL_STEPS + HALF_PIXEL,
        )
    }
}

/// A polygon's outline as the core judges it: its number of corners, twice
/// its signed area and its bounding rectangle, gathered corner by corner
/// (see [`OutlineBuilder`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Outline {
    /// Number of corners.
    pub corners: usize,
    /// Twice the signed area on the screen, in square sub-pixel steps
    /// (negative when the corners run counter-clockwise as seen on the
    /// screen, y pointing down).
    pub twice_area: i64,
    /// Bounding rectangle; `None` without corners.
    pub rect: Option<ScreenRect>,
}

/// Gathers an [`Outline`] corner by corner, with no buffer: the area is the
/// fan of cross products from the first corner (exactly Newell's `c`).
///
/// Feed it at most [`MAX_POLYGON_CORNERS`](crate::limits::MAX_POLYGON_CORNERS)
/// corners: then every term is below `2^45` and the sum below `2^55`.
#[derive(Debug, Clone, Copy, Default)]
pub struct OutlineBuilder {
    first: Option<ScreenVertex>,
    previous: Option<ScreenVertex>,
    corners: usize,
    twice_area: i64,
    rect: Option<ScreenRect>,
}

impl OutlineBuilder {
    /// Adds the next corner.
    pub fn add(&mut self, v: ScreenVertex) {
        match self.first {
            None => self.first = Some(v),
            Some(o) => {
                if let Some(p) = self.previous {
                    let (px, py) = (
                        i64::from(p.x) - i64::from(o.x),
                        i64::from(p.y) - i64::from(o.y),
                    );
                    let (qx, qy) = (
                        i64::from(v.x) - i64::from(o.x),
                        i64::from(v.y) - i64::from(o.y),
                    );
                    self.twice_area += px * qy - py * qx;
                }
                self.previous = Some(v);
            }
        }
        match &mut self.rect {
            Some(rect) => rect.add(v),
            None => self.rect = Some(ScreenRect::point(v)),
        }
        self.corners += 1;
    }

    /// Number of corners so far.
    pub fn corners(&self) -> usize {
        self.corners
    }

    /// The outline of the corners added.
    pub fn finish(&self) -> Outline {
        Outline {
            corners: self.corners,
            twice_area: self.twice_area,
            rect: self.rect,
        }
    }
}
