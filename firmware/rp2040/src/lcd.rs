//! Rows to the ST7789 by DMA, double-buffered: the renderer's row sink.
//!
//! A frame opens the LCD's whole window (CASET, RASET, RAMWR) once; then
//! each finished row, already in the wire's byte order (the renderer
//! stores [`WireColor`] pixels), is copied into whichever of the two row
//! buffers is free, and handed to DMA channel 0, which feeds
//! SPI0's transmit FIFO at the wire's pace. While it goes out, the CPU
//! computes the next row. The CPU waits only when it outruns the wire: at a
//! row, for the previous row's transfer; at a frame's start, for the last
//! row of the frame before.

use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use rp2040_hal::dma::{CH0, Channel, single_buffer};
use static_cell::ConstStaticCell;
use zline::RowSink;

use crate::board::{LcdCs, LcdDc, LcdSpi, OFFSET};
use crate::frame::WireColor;
use crate::sizes::{HEIGHT, WIDTH};

/// Bytes of one row on the wire.
pub const ROW_BYTES: usize = 2 * WIDTH as usize;

/// One row buffer, lent to DMA while it is sent.
type RowBuf = &'static mut [u8; ROW_BYTES];
/// The DMA channel rows go out on.
type Dma = Channel<CH0>;
/// A row on its way out.
type Transfer = single_buffer::Transfer<Dma, RowBuf, LcdSpi>;

/// A row buffer, word-aligned so that copying a row into it goes a word at
/// a time (the boot ROM's memcpy copies byte by byte between buffers of
/// different alignment).
#[repr(C, align(4))]
struct RowBytes([u8; ROW_BYTES]);

/// The two row buffers, in `.bss`.
static ROW_A: ConstStaticCell<RowBytes> = ConstStaticCell::new(RowBytes([0; ROW_BYTES]));
static ROW_B: ConstStaticCell<RowBytes> = ConstStaticCell::new(RowBytes([0; ROW_BYTES]));

/// ST7789 commands.
const CASET: u8 = 0x2A;
const RASET: u8 = 0x2B;
const RAMWR: u8 = 0x2C;

/// Where the bus is: idle (the CPU holds the channel and SPI) or sending a
/// row (DMA holds them).
enum Bus {
    Idle { dma: Dma, spi: LcdSpi },
    Sending(Transfer),
}

/// The LCD as a row sink: see the module notes.
pub struct LcdRows {
    bus: Option<Bus>,
    /// Row buffers not in flight (one or two).
    free: [Option<RowBuf>; 2],
    cs: LcdCs,
    dc: LcdDc,
}

/// The SPI or a pin failed.
#[derive(Debug, Clone, Copy)]
pub struct LcdError;

impl LcdRows {
    /// Takes over SPI0 (8-bit frames, the LCD initialised), its chip
    /// select and data/command pins, and DMA channel 0. `None` if the row
    /// buffers were taken already.
    pub fn new(spi: LcdSpi, cs: LcdCs, dc: LcdDc, dma: Dma) -> Option<Self> {
        Some(Self {
            bus: Some(Bus::Idle { dma, spi }),
            free: [
                Some(&mut ROW_A.try_take()?.0),
                Some(&mut ROW_B.try_take()?.0),
            ],
            cs,
            dc,
        })
    }

    /// Waits until nothing is in flight and returns the channel and SPI;
    /// a buffer that was in flight is free again.
    fn idle(&mut self) -> Result<(Dma, LcdSpi), LcdError> {
        match self.bus.take() {
            Some(Bus::Idle { dma, spi }) => Ok((dma, spi)),
            Some(Bus::Sending(t)) => {
                let (dma, buf, spi) = t.wait();
                self.give_back(buf);
                Ok((dma, spi))
            }
            // Only after a panic in between: never in this firmware.
            None => Err(LcdError),
        }
    }

    fn give_back(&mut self, buf: RowBuf) {
        if let Some(slot) = self.free.iter_mut().find(|b| b.is_none()) {
            *slot = Some(buf);
        }
    }

    fn take_free(&mut self) -> Option<RowBuf> {
        self.free.iter_mut().find_map(Option::take)
    }

    /// Sends one command and its parameters with the CPU (DC low for the
    /// command byte, high for the parameters).
    fn command(spi: &mut LcdSpi, dc: &mut LcdDc, cmd: u8, params: &[u8]) -> Result<(), LcdError> {
        dc.set_low().map_err(|_| LcdError)?;
        spi.write(&[cmd]).map_err(|_| LcdError)?;
        spi.flush().map_err(|_| LcdError)?;
        dc.set_high().map_err(|_| LcdError)?;
        if !params.is_empty() {
            spi.write(params).map_err(|_| LcdError)?;
            spi.flush().map_err(|_| LcdError)?;
        }
        Ok(())
    }

    /// Opens the whole panel for writing, once the last frame's rows are
    /// out: CS cycled, CASET, RASET, RAMWR, then DC high for pixel data.
    fn begin_frame(&mut self) -> Result<(), LcdError> {
        let (dma, mut spi) = self.idle()?;
        let span = |offset: u16, size: u16| {
            let (a, b) = (offset, offset + size - 1);
            [(a >> 8) as u8, a as u8, (b >> 8) as u8, b as u8]
        };
        let (cs, dc) = (&mut self.cs, &mut self.dc);
        let result = cs
            .set_high()
            .and_then(|()| cs.set_low())
            .map_err(|_| LcdError)
            .and_then(|()| Self::command(&mut spi, dc, CASET, &span(OFFSET.0, WIDTH)))
            .and_then(|()| Self::command(&mut spi, dc, RASET, &span(OFFSET.1, HEIGHT)))
            .and_then(|()| Self::command(&mut spi, dc, RAMWR, &[]));
        self.bus = Some(Bus::Idle { dma, spi });
        result
    }
}

impl RowSink<WireColor, u16> for LcdRows {
    type Error = LcdError;

    fn write_row(&mut self, y: u16, colors: &[WireColor], _depths: &[u16]) -> Result<(), LcdError> {
        if y == 0 {
            self.begin_frame()?;
        }
        // A free buffer, waiting for the row in flight if both are taken.
        let buf = match self.take_free() {
            Some(buf) => buf,
            None => {
                let (dma, spi) = self.idle()?;
                self.bus = Some(Bus::Idle { dma, spi });
                self.take_free().ok_or(LcdError)?
            }
        };
        // The row's bytes are already big-endian Rgb565, as the ST7789
        // takes it over SPI: one copy (a row longer than the buffer is
        // cut, as the panel's window would cut it).
        let bytes: &[u8] = bytemuck::cast_slice(colors);
        let len = bytes.len().min(buf.len());
        buf[..len].copy_from_slice(&bytes[..len]);
        let (dma, spi) = self.idle()?;
        self.bus = Some(Bus::Sending(
            single_buffer::Config::new(dma, buf, spi).start(),
        ));
        Ok(())
    }
}
