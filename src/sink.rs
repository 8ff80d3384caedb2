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
///
/// Drawing frame after frame into the same display, [`Self::changed_only`]
/// sends of each row only the part that differs from what the display
/// shows: the pixels between the first and the last that are not
/// background, in this frame or the last.
pub struct DrawTargetSink<'a, T: DrawTarget> {
    target: &'a mut T,
    origin: Point,
    shown: Option<(&'a mut [RowSpan], T::Color)>,
}

impl<T: DrawTarget> core::fmt::Debug for DrawTargetSink<'_, T> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("DrawTargetSink")
            .field("origin", &self.origin)
            .field("changed_only", &self.shown.is_some())
            .finish_non_exhaustive()
    }
}

impl<'a, T: DrawTarget> DrawTargetSink<'a, T> {
    /// Sends rows to `target`, with the frame's top-left corner at (0, 0).
    pub fn new(target: &'a mut T) -> Self {
        Self::with_origin(target, Point::zero())
    }

    /// Sends rows to `target`, with the frame's top-left corner at `origin`.
    pub fn with_origin(target: &'a mut T, origin: Point) -> Self {
        Self {
            target,
            origin,
            shown: None,
        }
    }

    /// Sends of each row only what changed since the frame before, for a
    /// display that keeps what it was sent: the columns from the first to
    /// the last pixel that is not `background` (the renderer's) in this
    /// row or in the one `shown` says the display holds. `shown[y]` is
    /// updated as row `y` goes out; keep it from frame to frame, one entry
    /// a row. Start it with [`RowSpan::UNKNOWN`] (the first frame then
    /// sends whole rows), and set it so again when the display was drawn
    /// on by anything else, or the frame moved. Rows beyond `shown` go out
    /// whole.
    ///
    /// ```
    /// use embedded_graphics::mock_display::MockDisplay;
    /// use embedded_graphics::pixelcolor::BinaryColor;
    /// use zline::{Capacities, Depth16, DrawTargetSink, RowSpan, ScreenVertex};
    ///
    /// const CAPS: Capacities = Capacities {
    ///     width: 8, vertices: 3, polygons: 1, corners: 3,
    ///     active_polygons: 1, pooled_edges: 0, mesh_vertices: 0,
    /// };
    /// type Zr = zline::renderer_type!(BinaryColor, Depth16, CAPS);
    /// let mut renderer = Zr::new(8, 4, BinaryColor::Off)?;
    /// let mut display = MockDisplay::new();
    /// display.set_allow_overdraw(true);
    /// let mut shown = [RowSpan::UNKNOWN; 4];
    /// let v = |x, y| ScreenVertex::from_f32(x, y, 0.5).unwrap();
    /// for frame in 0..2 {
    ///     renderer.clear();
    ///     renderer.push_polygon_vertices(&[v(0.0, 0.0), v(4.0, 0.0), v(0.0, 4.0)], BinaryColor::On)?;
    ///     let mut sink = DrawTargetSink::new(&mut display).changed_only(&mut shown, BinaryColor::Off);
    ///     renderer.render(&mut sink)?;
    /// }
    /// // Row 0 (samples at y = 0.5) shows columns 0..3 lit; the rest is
    /// // background, which the second frame did not send again.
    /// assert_eq!(shown[0], RowSpan::new(0, 3));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn changed_only(mut self, shown: &'a mut [RowSpan], background: T::Color) -> Self {
        self.shown = Some((shown, background));
        self
    }

    /// Sends columns `start..end` of row `y`.
    fn send(
        &mut self,
        y: u16,
        colors: &[T::Color],
        start: usize,
        end: usize,
    ) -> Result<(), T::Error> {
        let Some(part) = colors.get(start..end) else {
            return Ok(());
        };
        if part.is_empty() {
            return Ok(());
        }
        // Beyond `i32` (an origin near its end) no display has a pixel:
        // nothing to send.
        let (Some(x), Some(y)) = (
            i32::try_from(start)
                .ok()
                .and_then(|x| self.origin.x.checked_add(x)),
            self.origin.y.checked_add(i32::from(y)),
        ) else {
            return Ok(());
        };
        let area = Rectangle::new(
            Point::new(x, y),
            Size::new(u32::try_from(part.len()).unwrap_or(u32::MAX), 1),
        );
        self.target.fill_contiguous(&area, part.iter().copied())
    }
}

/// Which columns of a row a display shows in other than the background:
/// `start..end` (empty when `start == end`), or [`Self::UNKNOWN`]. Kept
/// from frame to frame by [`DrawTargetSink::changed_only`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RowSpan {
    start: u16,
    end: u16,
}

impl RowSpan {
    /// Nothing known of the row: it is sent whole.
    pub const UNKNOWN: Self = Self {
        start: 0,
        end: u16::MAX,
    };
    /// A row of background only.
    pub const EMPTY: Self = Self { start: 0, end: 0 };

    /// Columns `start..end` (empty when `end <= start`).
    pub const fn new(start: u16, end: u16) -> Self {
        if end <= start {
            Self::EMPTY
        } else {
            Self { start, end }
        }
    }

    /// The first column.
    pub const fn start(self) -> u16 {
        self.start
    }

    /// One past the last column.
    pub const fn end(self) -> u16 {
        self.end
    }

    /// Whether it holds no column.
    pub const fn is_empty(self) -> bool {
        self.end <= self.start
    }

    /// The columns of `colors` from the first to the last that is not
    /// `background`.
    fn of<C: PartialEq>(colors: &[C], background: &C) -> Self {
        let Some(first) = first_not(colors, background) else {
            return Self::EMPTY;
        };
        // There is a last: the first is one.
        let last = last_not(colors, background).unwrap_or(first);
        let column = |k: usize| u16::try_from(k).unwrap_or(u16::MAX);
        Self::new(column(first), column(last + 1))
    }

    /// The smallest span holding both.
    fn union(self, other: Self) -> Self {
        match (self.is_empty(), other.is_empty()) {
            (true, _) => other,
            (_, true) => self,
            _ => Self {
                start: self.start.min(other.start),
                end: self.end.max(other.end),
            },
        }
    }
}

/// Pixels [`RowSpan::of`] compares with the background at once, with no
/// branch among them: a host compiler makes the test of a block a few
/// vector instructions. (Found a pixel at a time, a row's span was most of
/// what the peers bench's `drawtarget` rows paid above rows drawn in
/// place, on frames that are mostly background.)
const SPAN_BLOCK: usize = 16;

/// Whether every pixel of `block` is `background`.
#[inline(always)]
fn all_background<C: PartialEq>(block: &[C; SPAN_BLOCK], background: &C) -> bool {
    block.iter().fold(true, |all, c| all & (c == background))
}

/// The index of the first pixel of `colors` that is not `background`.
fn first_not<C: PartialEq>(colors: &[C], background: &C) -> Option<usize> {
    let (blocks, _) = colors.as_chunks::<SPAN_BLOCK>();
    let skipped = blocks
        .iter()
        .take_while(|block| all_background(block, background))
        .count()
        * SPAN_BLOCK;
    let rest = colors.get(skipped..).unwrap_or_default();
    rest.iter()
        .position(|c| c != background)
        .map(|k| skipped + k)
}

/// The index of the last pixel of `colors` that is not `background`.
fn last_not<C: PartialEq>(colors: &[C], background: &C) -> Option<usize> {
    let (_, blocks) = colors.as_rchunks::<SPAN_BLOCK>();
    let skipped = blocks
        .iter()
        .rev()
        .take_while(|block| all_background(block, background))
        .count()
        * SPAN_BLOCK;
    let rest = colors.get(..colors.len() - skipped).unwrap_or_default();
    rest.iter().rposition(|c| c != background)
}

impl<T, Z> RowSink<T::Color, Z> for DrawTargetSink<'_, T>
where
    T: DrawTarget,
{
    type Error = T::Error;

    fn write_row(&mut self, y: u16, colors: &[T::Color], _depths: &[Z]) -> Result<(), T::Error> {
        let Some((shown, background)) = &mut self.shown else {
            return self.send(y, colors, 0, colors.len());
        };
        let Some(was) = shown.get_mut(usize::from(y)) else {
            return self.send(y, colors, 0, colors.len());
        };
        let now = RowSpan::of(colors, background);
        let send = was.union(now);
        *was = now;
        let end = usize::from(send.end).min(colors.len());
        self.send(y, colors, usize::from(send.start), end)
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

    /// A row's span is its first and last pixels that are not background,
    /// found a pixel at a time, whatever the row's length and wherever
    /// they fall against the blocks of [`SPAN_BLOCK`] pixels.
    #[test]
    fn row_span_is_the_first_and_last_pixel_not_background() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for round in 0..20_000 {
            let len = (next() % 100) as usize;
            // Mostly background, a few lit pixels (none in some rows).
            let lit = [0, 1, 2, 5][round % 4];
            let mut row = [0u8; 100];
            for _ in 0..lit {
                if len > 0 {
                    row[(next() % len as u64) as usize] = 1 + (next() % 3) as u8;
                }
            }
            let row = &row[..len];
            let first = row.iter().position(|&c| c != 0);
            let last = row.iter().rposition(|&c| c != 0);
            let want = match (first, last) {
                (Some(f), Some(l)) => RowSpan::new(f as u16, l as u16 + 1),
                _ => RowSpan::EMPTY,
            };
            assert_eq!(RowSpan::of(row, &0), want, "{row:?}");
        }
    }

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
