//! Row sinks: where finished scanlines go (tiny-skia would call this the
//! blitter). The renderer hands over each scanline exactly once, top to
//! bottom, with the final colours and depths of that row: by
//! [`RowSink::write_row`], or, for a sink that lends the scanner its own
//! row buffers (a display driver's DMA buffers), by
//! [`RowSink::send_lent_row`] for the row drawn into the buffer
//! [`RowSink::lend_row`] lent.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_graphics_core::prelude::IntoStorage as _;
use embedded_graphics_core::primitives::Rectangle;

/// Receives finished rows, one call per scanline.
pub trait RowSink<C, Z> {
    /// What can go wrong while writing a row.
    type Error;

    /// Takes row `y` (0 is the top): its colours and its depths, both
    /// `W` long.
    fn write_row(&mut self, y: u16, colors: &[C], depths: &[Z]) -> Result<(), Self::Error>;

    /// Lends the buffer that row `y`'s `width` colours are to be drawn
    /// into, for a sink that sends rows from its own memory: the scanner
    /// then draws the row there (filling it with `background` first unless
    /// [`LentRow::filled`] says it holds that already) and hands it back
    /// with [`RowSink::send_lent_row`], so the row is never copied. The
    /// default, `Ok(None)`: the scanner draws into its own colour row and
    /// calls [`RowSink::write_row`]. A buffer shorter than `width` is an
    /// error ([`Error::BadFrameSize`](crate::Error::BadFrameSize)).
    fn lend_row(
        &mut self,
        y: u16,
        width: usize,
        background: C,
    ) -> Result<Option<LentRow<'_, C>>, Self::Error> {
        let _ = (y, width, background);
        Ok(None)
    }

    /// Takes row `y`, drawn into the buffer [`RowSink::lend_row`] lent for
    /// it, and its `depths`. Called once after each lent row; the default
    /// does nothing.
    fn send_lent_row(&mut self, y: u16, depths: &[Z]) -> Result<(), Self::Error> {
        let _ = (y, depths);
        Ok(())
    }
}

/// A row buffer a sink lends the scanner ([`RowSink::lend_row`]).
///
/// A sink that sends rows from its own memory lends it, and gets each row
/// back drawn in place:
///
/// ```
/// use zline::{Renderer, ScanArrays, TableArrays};
/// use zline::{Depth16, LentRow, RowSink, ScreenVertex};
///
/// /// Sends rows from one buffer of its own (a DMA buffer, say).
/// struct Wire {
///     buffer: [u16; 8],
///     sent: Vec<[u16; 8]>,
/// }
///
/// impl RowSink<u16, u16> for Wire {
///     type Error = ();
///     fn write_row(&mut self, _: u16, colors: &[u16], _: &[u16]) -> Result<(), ()> {
///         self.buffer.copy_from_slice(colors); // only when not lending
///         self.sent.push(self.buffer);
///         Ok(())
///     }
///     fn lend_row(&mut self, _: u16, _: usize, _: u16) -> Result<Option<LentRow<'_, u16>>, ()> {
///         // It holds the last row: the scanner fills it with the background first.
///         Ok(Some(LentRow { colors: &mut self.buffer, filled: false }))
///     }
///     fn send_lent_row(&mut self, _: u16, _: &[u16]) -> Result<(), ()> {
///         self.sent.push(self.buffer);
///         Ok(())
///     }
/// }
///
/// type Zr = Renderer<TableArrays<u16, 3, 1, 3>, ScanArrays<u16, Depth16, 8, 1, 0>>;
/// let mut renderer = Zr::new(8, 4, 0).unwrap();
/// let v = |x, y| ScreenVertex::from_f32(x, y, 0.5).unwrap();
/// renderer.push_polygon_vertices(&[v(0.0, 0.0), v(8.0, 0.0), v(0.0, 4.0)], 7).unwrap();
/// let mut wire = Wire { buffer: [0; 8], sent: Vec::new() };
/// renderer.render(&mut wire).unwrap();
/// assert_eq!(wire.sent.len(), 4);
/// assert_eq!(wire.sent[0], [7, 7, 7, 7, 7, 7, 7, 0]);
/// assert_eq!(wire.sent[3], [7, 0, 0, 0, 0, 0, 0, 0]);
/// ```
#[derive(Debug)]
pub struct LentRow<'a, C> {
    /// Where the row's colours go: at least as long as the row.
    pub colors: &'a mut [C],
    /// Whether the first `width` entries already hold the background
    /// colour the scanner asked for (a sink that clears its buffers as they
    /// come back from the wire, by DMA for one); when `false` the scanner
    /// fills them.
    pub filled: bool,
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

/// A frame buffer in memory, row-major from the top, `width` pixels a
/// row: the scanner draws each row straight into it (the sink lends its
/// rows, [`RowSink::lend_row`]), so no row is copied. For a frame in RAM
/// that is sent or shown later; a display goes through
/// [`DrawTargetSink`]. A row that does not fit the buffer, or is wider
/// than `width`, is [`Error::BadFrameSize`](crate::Error::BadFrameSize).
#[derive(Debug)]
pub struct FrameBufferSink<'a, C> {
    pixels: &'a mut [C],
    width: usize,
    first_row: u16,
}

impl<'a, C> FrameBufferSink<'a, C> {
    /// Rows go to `pixels`, row `y` from index `y·width`.
    pub fn new(pixels: &'a mut [C], width: usize) -> Self {
        Self::from_row(pixels, width, 0)
    }

    /// Rows from `first_row` on go to `pixels`, row `y` from index `(y -
    /// first_row)·width`: the part of a frame that one band of rows
    /// draws.
    pub fn from_row(pixels: &'a mut [C], width: usize, first_row: u16) -> Self {
        Self {
            pixels,
            width,
            first_row,
        }
    }

    /// The first `len` pixels of row `y` in the buffer.
    fn row(&mut self, y: u16, len: usize) -> Result<&mut [C], crate::Error> {
        let start = y
            .checked_sub(self.first_row)
            .and_then(|index| usize::from(index).checked_mul(self.width))
            .filter(|_| len <= self.width);
        start
            .and_then(|start| self.pixels.get_mut(start..start.checked_add(len)?))
            .ok_or(crate::Error::BadFrameSize)
    }
}

impl<C: Copy, Z> RowSink<C, Z> for FrameBufferSink<'_, C> {
    type Error = crate::Error;

    fn write_row(&mut self, y: u16, colors: &[C], _depths: &[Z]) -> Result<(), crate::Error> {
        self.row(y, colors.len())?.copy_from_slice(colors);
        Ok(())
    }

    fn lend_row(
        &mut self,
        y: u16,
        width: usize,
        _background: C,
    ) -> Result<Option<LentRow<'_, C>>, crate::Error> {
        Ok(Some(LentRow {
            colors: self.row(y, width)?,
            filled: false,
        }))
    }
}

/// CRC-32 of a frame (the IEEE 802.3 / zlib CRC) as it would leave for an
/// ST7789: each pixel as Rgb565 big-endian, row after row. Two frames with
/// the same CRC are, for all practical purposes, the same pixels; the
/// emulated firmware checks its frames against the host's this way.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Crc32Sink {
    state: u32,
    rows: u32,
}

/// CRC-32 of each nibble value, reflected polynomial 0xEDB88320.
const CRC_NIBBLES: [u32; 16] = {
    let mut table = [0u32; 16];
    let mut n = 0;
    while n < 16 {
        let mut c = n as u32;
        let mut k = 0;
        while k < 4 {
            c = if c & 1 != 0 {
                (c >> 1) ^ 0xEDB8_8320
            } else {
                c >> 1
            };
            k += 1;
        }
        table[n] = c;
        n += 1;
    }
    table
};

impl Crc32Sink {
    /// A CRC over no data yet.
    pub const fn new() -> Self {
        Self { state: !0, rows: 0 }
    }

    /// Feeds bytes.
    pub fn update(&mut self, bytes: &[u8]) {
        for &b in bytes {
            let mut c = self.state ^ u32::from(b);
            c = (c >> 4) ^ CRC_NIBBLES[(c & 15) as usize];
            c = (c >> 4) ^ CRC_NIBBLES[(c & 15) as usize];
            self.state = c;
        }
    }

    /// The CRC of everything fed so far.
    pub const fn value(&self) -> u32 {
        !self.state
    }

    /// Rows received.
    pub const fn rows(&self) -> u32 {
        self.rows
    }
}

impl Default for Crc32Sink {
    fn default() -> Self {
        Self::new()
    }
}

impl<Z> RowSink<Rgb565, Z> for Crc32Sink {
    type Error = core::convert::Infallible;

    fn write_row(&mut self, _y: u16, colors: &[Rgb565], _depths: &[Z]) -> Result<(), Self::Error> {
        for c in colors {
            self.update(&c.into_storage().to_be_bytes());
        }
        self.rows += 1;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_check_value() {
        let mut crc = Crc32Sink::new();
        crc.update(b"123456789");
        assert_eq!(crc.value(), 0xCBF4_3926);
        assert_eq!(Crc32Sink::new().value(), 0);
    }

    #[test]
    fn rows_are_hashed_big_endian_rgb565() {
        let mut sink = Crc32Sink::new();
        let row = [Rgb565::new(31, 0, 0), Rgb565::new(0, 63, 1)];
        RowSink::<Rgb565, u16>::write_row(&mut sink, 0, &row, &[0, 0]).unwrap();
        let mut bytes = Crc32Sink::new();
        bytes.update(&[0xF8, 0x00, 0x07, 0xE1]);
        assert_eq!((sink.value(), sink.rows()), (bytes.value(), 1));
    }
}
