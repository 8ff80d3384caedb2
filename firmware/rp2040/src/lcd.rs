//! Rows to the ST7789 by DMA from a queue of row buffers: the renderer's
//! row sink.
//!
//! A frame opens the LCD's whole window (CASET, RASET, RAMWR) once; then
//! each finished row, already in the wire's byte order (the renderer
//! stores [`WireColor`] pixels), is copied into a free row buffer and
//! queued. DMA channel 0 feeds the queued rows to SPI0's transmit FIFO at
//! the wire's pace, one after another: its completion interrupt
//! (`DMA_IRQ_0`) frees the row just sent and starts the next one, so the
//! wire keeps going whatever the CPU does, building the next frame's scene
//! included. The CPU waits only when it is [`ROW_BUFFERS`] rows ahead of
//! the wire, and at a frame's start until the last frame's rows are out.

use core::cell::RefCell;

use cortex_m::interrupt::{Mutex, free as without_interrupts};
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use rp2040_hal::dma::{CH0, Channel, SingleChannel, single_buffer};
use rp2040_hal::pac::{self, interrupt};
use static_cell::ConstStaticCell;
use zline::RowSink;

use crate::board::{LcdCs, LcdDc, LcdSpi, OFFSET};
use crate::frame::WireColor;
use crate::sizes::{HEIGHT, ROW_BUFFERS, WIDTH};

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

/// The row buffers, in `.bss`.
static ROWS: ConstStaticCell<[RowBytes; ROW_BUFFERS]> =
    ConstStaticCell::new([const { RowBytes([0; ROW_BYTES]) }; ROW_BUFFERS]);

/// ST7789 commands.
const CASET: u8 = 0x2A;
const RASET: u8 = 0x2B;
const RAMWR: u8 = 0x2C;

/// Where the bus is: idle (the channel and SPI are free) or sending a row
/// (DMA holds them).
enum Bus {
    Idle { dma: Dma, spi: LcdSpi },
    Sending(Transfer),
}

/// A first-in first-out ring of row buffers.
struct Ring {
    slots: [Option<RowBuf>; ROW_BUFFERS],
    head: usize,
    len: usize,
}

impl Ring {
    const fn new() -> Self {
        Self {
            slots: [const { None }; ROW_BUFFERS],
            head: 0,
            len: 0,
        }
    }

    /// Appends `buf` (never full: there are `ROW_BUFFERS` buffers in all).
    fn push(&mut self, buf: RowBuf) {
        debug_assert!(self.len < ROW_BUFFERS);
        self.slots[wrap(self.head + self.len)] = Some(buf);
        self.len += 1;
    }

    fn pop(&mut self) -> Option<RowBuf> {
        let buf = self.slots[self.head].take()?;
        self.head = wrap(self.head + 1);
        self.len -= 1;
        Some(buf)
    }
}

/// `index mod ROW_BUFFERS` for `index < 2·ROW_BUFFERS`, by a compare: `%`
/// would be a call to the divider on every row.
fn wrap(index: usize) -> usize {
    if index >= ROW_BUFFERS {
        index - ROW_BUFFERS
    } else {
        index
    }
}

/// What the sink and the DMA interrupt share: the bus, the rows queued
/// for it and the free buffers.
struct Queue {
    /// `None` only while the sink sends commands with the SPI.
    bus: Option<Bus>,
    queued: Ring,
    free: Ring,
}

impl Queue {
    /// Takes back the buffer of a finished transfer (clearing its
    /// interrupt), then starts the next queued row if the bus is idle.
    fn advance(&mut self) {
        self.bus = match self.bus.take() {
            Some(Bus::Sending(transfer)) if transfer.is_done() => {
                let (mut dma, buf, spi) = transfer.wait();
                dma.check_irq0();
                self.free.push(buf);
                Some(Bus::Idle { dma, spi })
            }
            other => other,
        };
        if let Some(Bus::Idle { .. }) = self.bus
            && let Some(buf) = self.queued.pop()
            && let Some(Bus::Idle { dma, spi }) = self.bus.take()
        {
            self.bus = Some(Bus::Sending(
                single_buffer::Config::new(dma, buf, spi).start(),
            ));
        }
    }
}

/// The queue. Only core 0 touches it (the render loop and its DMA
/// interrupt), so masking interrupts is enough to share it: no spinlock.
static QUEUE: Mutex<RefCell<Option<Queue>>> = Mutex::new(RefCell::new(None));

/// Runs `f` on the queue with interrupts held off; `None` before
/// [`LcdRows::new`].
fn with_queue<R>(f: impl FnOnce(&mut Queue) -> R) -> Option<R> {
    without_interrupts(|cs| QUEUE.borrow(cs).borrow_mut().as_mut().map(f))
}

/// A row has left: free its buffer, start the next.
#[interrupt]
fn DMA_IRQ_0() {
    with_queue(Queue::advance);
}

/// The LCD as a row sink: see the module notes.
pub struct LcdRows {
    cs: LcdCs,
    dc: LcdDc,
}

/// The SPI or a pin failed.
#[derive(Debug, Clone, Copy)]
pub struct LcdError;

impl LcdRows {
    /// Takes over SPI0 (8-bit frames, the LCD initialised), its chip
    /// select and data/command pins, and DMA channel 0 with its
    /// interrupt. `None` if the row buffers were taken already.
    pub fn new(spi: LcdSpi, cs: LcdCs, dc: LcdDc, mut dma: Dma) -> Option<Self> {
        let mut free = Ring::new();
        for row in ROWS.try_take()? {
            free.push(&mut row.0);
        }
        dma.enable_irq0();
        without_interrupts(|cs| {
            QUEUE.borrow(cs).borrow_mut().replace(Queue {
                bus: Some(Bus::Idle { dma, spi }),
                queued: Ring::new(),
                free,
            })
        });
        // SAFETY: the handler only touches `QUEUE`, inside a critical
        // section; unmasking cannot break a critical section in progress.
        unsafe { pac::NVIC::unmask(pac::Interrupt::DMA_IRQ_0) };
        Some(Self { cs, dc })
    }

    /// Sends one command over the SPI (DC low for the command byte, high
    /// for the parameters).
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

    /// Waits until the queue is empty and the last row is out, and takes
    /// the channel and SPI from the bus (the interrupt then finds nothing
    /// to do).
    fn take_idle_bus() -> Result<(Dma, LcdSpi), LcdError> {
        loop {
            let taken = with_queue(|q| {
                // A transfer that ends with interrupts held off is seen
                // here too.
                q.advance();
                if q.queued.len == 0
                    && let Some(Bus::Idle { .. }) = q.bus
                    && let Some(Bus::Idle { dma, spi }) = q.bus.take()
                {
                    return Some((dma, spi));
                }
                None
            })
            .ok_or(LcdError)?;
            if let Some(parts) = taken {
                return Ok(parts);
            }
            core::hint::spin_loop();
        }
    }

    /// Opens the whole panel for writing, once the last frame's rows are
    /// out: CS cycled, CASET, RASET, RAMWR, then DC high for pixel data.
    fn begin_frame(&mut self) -> Result<(), LcdError> {
        let (dma, mut spi) = Self::take_idle_bus()?;
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
        with_queue(|q| q.bus = Some(Bus::Idle { dma, spi }));
        result
    }
}

impl RowSink<WireColor, u16> for LcdRows {
    type Error = LcdError;

    fn write_row(&mut self, y: u16, colors: &[WireColor], _depths: &[u16]) -> Result<(), LcdError> {
        if y == 0 {
            self.begin_frame()?;
        }
        // A free buffer; when every buffer is queued, wait for the wire.
        let buf = loop {
            if let Some(buf) = with_queue(|q| {
                q.advance();
                q.free.pop()
            })
            .ok_or(LcdError)?
            {
                break buf;
            }
            core::hint::spin_loop();
        };
        // The row's bytes are already big-endian Rgb565, as the ST7789
        // takes it over SPI: one copy (a row longer than the buffer is
        // cut, as the panel's window would cut it).
        let bytes: &[u8] = bytemuck::cast_slice(colors);
        let len = bytes.len().min(buf.len());
        buf[..len].copy_from_slice(&bytes[..len]);
        with_queue(|q| {
            q.queued.push(buf);
            q.advance();
        })
        .ok_or(LcdError)
    }
}
