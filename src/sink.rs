//! Row sinks: where finished scanlines go (tiny-skia would call this the
//! blitter). The renderer calls [`RowSink::write_row`] exactly once per
//! scanline, top to bottom, with the final colours and depths of that row.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

/// Receives finished rows, one call per scanline.
pub trait RowSink<C, Z> {
    /// What can go wrong while writing a row.
    type Error;

    /// Takes row `y` (0 is the top): its colours and its depths, both
    /// `W` long.
    fn write_row(&mut self, y: u16, colors: &[C], depths: &[Z]) -> Result<(), Self::Error>;
}

/// The standard sink: writes each row into an embedded-graphics
/// [`DrawTarget`] with one `fill_contiguous` call.
///
/// Works with any display driver (e.g. `mipidsi`) or framebuffer
/// implementing `DrawTarget`; the target clips rows that do not fit.
#[derive(Debug)]
pub struct DrawTargetSink<'a, T> {
    target: &'a mut T,
    origin: Point,
}

impl<'a, T: DrawTarget> DrawTargetSink<'a, T> {
    /// Sends rows to `target`, with the frame's top-left corner at (0, 0).
    pub fn new(target: &'a mut T) -> Self {
        Self::with_origin(target, Point::zero())
    }

    /// Sends rows to `target`, with the frame's top-left corner at `origin`.
    pub fn with_origin(target: &'a mut T, origin: Point) -> Self {
        Self { target, origin }
    }
}

impl<T, Z> RowSink<T::Color, Z> for DrawTargetSink<'_, T>
where
    T: DrawTarget,
{
    type Error = T::Error;

    fn write_row(&mut self, y: u16, colors: &[T::Color], _depths: &[Z]) -> Result<(), T::Error> {
        let width = u32::try_from(colors.len()).unwrap_or(u32::MAX);
        let area = Rectangle::new(
            self.origin + Point::new(0, i32::from(y)),
            Size::new(width, 1),
        );
        self.target.fill_contiguous(&area, colors.iter().copied())
    }
}

/// Adapts a closure `FnMut(y, colors, depths) -> Result<(), E>` into a
/// [`RowSink`], for checksums, tests and custom transports.
#[derive(Debug)]
pub struct FnSink<F>(pub F);

impl<C, Z, E, F> RowSink<C, Z> for FnSink<F>
where
    F: FnMut(u16, &[C], &[Z]) -> Result<(), E>,
{
    type Error = E;

    fn write_row(&mut self, y: u16, colors: &[C], depths: &[Z]) -> Result<(), E> {
        (self.0)(y, colors, depths)
    }
}
