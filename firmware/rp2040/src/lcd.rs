//! Rows to the ST7789 by DMA from a queue of row buffers: the renderer's
//! row sink.
//!
//! A frame opens the LCD's whole window (CASET, RASET, RAMWR) once; then
//! the renderer draws each row straight into the next row of a free
//! buffer the sink lends it ([`RowSink::lend_row`]), already in the wire's
//! byte order (it stores [`WireColor`] pixels): no copy. Each buffer holds
//! [`ROWS_PER_BUFFER`] rows (8 for a 240-row panel), and a full one is
//! queued. DMA channel 0 feeds the queued buffers to SPI0's transmit FIFO
//! at the wire's pace, one after another. A buffer that has been sent is
//! cleared to black by DMA channel 1 (from black rows in flash) before it
//! is free again, so the renderer never clears a row's colours itself.
//! Channel 0's completion interrupt (`DMA_IRQ_0`) moves buffers on (sent →
//! cleared → free) and starts the next transfers, so the wire keeps going
//! whatever the CPU does, building the next frame's scene included; a
//! finished clearing is collected there or at the sink's next call (its
//! own interrupt would cost more than it saves: clearing a buffer takes a
//! fraction of sending one). Moving a buffer on costs a few hundred
//! cycles (the queue's critical sections, the transfers' set-up), which
//! is why a buffer holds several rows. The CPU waits only when it is
//! [`ROW_BUFFERS`] rows ahead of the wire, and at a frame's start until
//! the last frame's rows are out.

use core::cell::RefCell;

use cortex_m::interrupt::{Mutex, free as without_interrupts};
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiBus;
use static_cell::ConstStaticCell;
use zline::{LentRow, RowSink};

use crate::frame::{WIRE_BLACK, WireColor};
use crate::hal::dma::{CH0, CH1, Channel, SingleChannel, single_buffer};
use crate::hal::pac::{self, interrupt};
use crate::sizes::{HEIGHT, ROW_BUFFERS, ROWS_PER_BUFFER, WIDTH};
use crate::wiring::{LcdCs, LcdDc, LcdSpi, OFFSET};

/// Bytes of one row on the wire.
pub const ROW_BYTES: usize = 2 * WIDTH as usize;
/// Bytes of one buffer: [`ROWS_PER_BUFFER`] rows.
const BUFFER_BYTES: usize = ROWS_PER_BUFFER * ROW_BYTES;
/// Buffers in the ring: [`ROW_BUFFERS`] rows of them.
const BUFFERS: usize = ROW_BUFFERS / ROWS_PER_BUFFER;

/// One buffer of rows, lent to DMA while it is sent.
type RowBuf = &'static mut [u8; BUFFER_BYTES];
/// The DMA channel rows go out on.
type Dma = Channel<CH0>;
/// A row on its way out.
type Transfer = single_buffer::Transfer<Dma, RowBuf, LcdSpi>;
/// The DMA channel that clears sent rows.
type ClearDma = Channel<CH1>;
/// A sent row being cleared.
type Clearing = single_buffer::Transfer<ClearDma, &'static [u8; BUFFER_BYTES], RowBuf>;

/// Black rows ([`WIRE_BLACK`] is all zero bits), the source of the
/// clearing channel.
static BLACK_ROWS: [u8; BUFFER_BYTES] = [0; BUFFER_BYTES];

/// A buffer of rows, word-aligned so that a row is lent as `u16` pixels
/// and copied into it a word at a time (the boot ROM's memcpy copies byte
/// by byte between buffers of different alignment).
#[repr(C, align(4))]
struct RowBytes([u8; BUFFER_BYTES]);

/// The row buffers, in `.bss`.
static ROWS: ConstStaticCell<[RowBytes; BUFFERS]> =
    ConstStaticCell::new([const { RowBytes([0; BUFFER_BYTES]) }; BUFFERS]);

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
    slots: [Option<RowBuf>; BUFFERS],
    head: usize,
    len: usize,
}

impl Ring {
    const fn new() -> Self {
        Self {
            slots: [const { None }; BUFFERS],
            head: 0,
            len: 0,
        }
    }

    /// Appends `buf` (never full: there are `BUFFERS` buffers in all).
    fn push(&mut self, buf: RowBuf) {
        debug_assert!(self.len < BUFFERS);
        self.slots[wrap(self.head + self.len)] = Some(buf);
        self.len += 1;
    }

    #[inline]
    fn pop(&mut self) -> Option<RowBuf> {
        let buf = self.slots[self.head].take()?;
        self.head = wrap(self.head + 1);
        self.len -= 1;
        Some(buf)
    }
}

/// `index mod BUFFERS` for `index < 2·BUFFERS`, by a compare: `%`
/// would be a call to the divider on every row.
fn wrap(index: usize) -> usize {
    if index >= BUFFERS {
        index - BUFFERS
    } else {
        index
    }
}

/// Where the clearing channel is.
enum Clearer {
    Idle(ClearDma),
    Clearing(Clearing),
}

/// What the sink and the DMA interrupt share: the bus, the rows queued
/// for it, the sent buffers waiting to be cleared and the free (black)
/// ones.
struct Queue {
    /// `None` only while the sink sends commands with the SPI.
    bus: Option<Bus>,
    queued: Ring,
    sent: Ring,
    free: Ring,
    /// `None` only inside [`Queue::advance`].
    clearer: Option<Clearer>,
}

impl Queue {
    /// Takes back the buffers of finished transfers (clearing their
    /// interrupts): a sent row goes to be cleared, a cleared one is free.
    /// Then starts the next clearing if that channel is idle, and the next
    /// queued row if the bus is.
    fn advance(&mut self) {
        self.bus = match self.bus.take() {
            Some(Bus::Sending(transfer)) if transfer.is_done() => {
                let (mut dma, buf, spi) = transfer.wait();
                dma.check_irq0();
                self.sent.push(buf);
                Some(Bus::Idle { dma, spi })
            }
            other => other,
        };
        self.clearer = match self.clearer.take() {
            Some(Clearer::Clearing(transfer)) if transfer.is_done() => {
                let (mut dma, _, buf) = transfer.wait();
                dma.check_irq0();
                self.free.push(buf);
                Some(Clearer::Idle(dma))
            }
            other => other,
        };
        if let Some(Clearer::Idle(_)) = self.clearer
            && let Some(buf) = self.sent.pop()
            && let Some(Clearer::Idle(dma)) = self.clearer.take()
        {
            self.clearer = Some(Clearer::Clearing(
                single_buffer::Config::new(dma, &BLACK_ROWS, buf).start(),
            ));
        }
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
    /// The buffer being filled, row after row, and how many of its rows
    /// are done.
    filling: Option<(RowBuf, usize)>,
}

/// The SPI or a pin failed.
#[derive(Debug, Clone, Copy)]
pub struct LcdError;

impl LcdRows {
    /// Takes over SPI0 (8-bit frames, the LCD initialised), its chip
    /// select and data/command pins, and DMA channels 0 (rows out, with
    /// its interrupt) and 1 (clearing). `None` if the row buffers were
    /// taken already.
    pub fn new(
        spi: LcdSpi,
        cs: LcdCs,
        dc: LcdDc,
        mut dma: Dma,
        clear_dma: ClearDma,
    ) -> Option<Self> {
        // The buffers start zeroed (`.bss`): black, so free.
        let mut free = Ring::new();
        for row in ROWS.try_take()? {
            free.push(&mut row.0);
        }
        dma.enable_irq0();
        without_interrupts(|cs| {
            QUEUE.borrow(cs).borrow_mut().replace(Queue {
                bus: Some(Bus::Idle { dma, spi }),
                queued: Ring::new(),
                sent: Ring::new(),
                free,
                clearer: Some(Clearer::Idle(clear_dma)),
            })
        });
        // SAFETY: the handler only touches `QUEUE`, inside a critical
        // section; unmasking cannot break a critical section in progress.
        unsafe { cortex_m::peripheral::NVIC::unmask(pac::Interrupt::DMA_IRQ_0) };
        Some(Self {
            cs,
            dc,
            filling: None,
        })
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

/// A free buffer; when every buffer is queued or being cleared, waits for
/// the wire. (The queue moves on only when none is free: the interrupt
/// moves it on as each row leaves.)
fn free_buffer() -> Result<RowBuf, LcdError> {
    loop {
        if let Some(buf) = with_queue(|q| {
            q.free.pop().or_else(|| {
                q.advance();
                q.free.pop()
            })
        })
        .ok_or(LcdError)?
        {
            return Ok(buf);
        }
        core::hint::spin_loop();
    }
}

/// Queues a finished buffer of rows for the wire, starting it if the bus
/// is idle (while it is busy, the interrupt starts the next one).
fn queue_row(buf: RowBuf) -> Result<(), LcdError> {
    with_queue(|q| {
        q.queued.push(buf);
        if let Some(Bus::Idle { .. }) = q.bus {
            q.advance();
        }
    })
    .ok_or(LcdError)
}

impl LcdRows {
    /// The buffer row `y` goes into, and the byte offset of its row there:
    /// at a frame's start the window is opened and a buffer left over from
    /// a frame an error cut short is cleared, not sent; a full buffer
    /// makes way for a free one.
    fn row_slot(&mut self, y: u16) -> Result<(&mut [u8; BUFFER_BYTES], usize), LcdError> {
        if y == 0 {
            self.begin_frame()?;
            if let Some((buf, _)) = self.filling.take() {
                with_queue(|q| {
                    q.sent.push(buf);
                    q.advance();
                })
                .ok_or(LcdError)?;
            }
        }
        let (buf, done) = match self.filling.take() {
            Some((buf, done)) if done < ROWS_PER_BUFFER => (buf, done),
            _ => (free_buffer()?, 0),
        };
        let (buf, done) = self.filling.insert((buf, done));
        Ok((buf, *done * ROW_BYTES))
    }

    /// Row done: a full buffer is queued for the wire.
    fn row_done(&mut self) -> Result<(), LcdError> {
        match self.filling.take() {
            Some((buf, done)) if done + 1 == ROWS_PER_BUFFER => queue_row(buf),
            Some((buf, done)) => {
                self.filling = Some((buf, done + 1));
                Ok(())
            }
            None => Err(LcdError),
        }
    }
}

/// Painted rows (the `gouraud` and `textured` features): the painted
/// renderer's row, copied into a buffer as the flat rows are.
#[cfg(any(feature = "gouraud", feature = "textured"))]
impl RowSink<crate::frame::WirePixel, u16> for LcdRows {
    type Error = LcdError;

    fn write_row(
        &mut self,
        y: u16,
        colors: &[crate::frame::WirePixel],
        _depths: &[u16],
    ) -> Result<(), LcdError> {
        let (buf, at) = self.row_slot(y)?;
        let bytes: &[u8] = bytemuck::cast_slice(colors);
        let len = bytes.len().min(ROW_BYTES);
        buf[at..at + len].copy_from_slice(&bytes[..len]);
        self.row_done()
    }
}

impl RowSink<WireColor, u16> for LcdRows {
    type Error = LcdError;

    /// A row from the renderer's own colour row: copied into a buffer.
    /// (The renderer takes [`Self::lend_row`] instead; this serves any
    /// other caller.)
    fn write_row(&mut self, y: u16, colors: &[WireColor], _depths: &[u16]) -> Result<(), LcdError> {
        let (buf, at) = self.row_slot(y)?;
        // The row's bytes are already big-endian Rgb565, as the ST7789
        // takes it over SPI: one copy (a row longer than the buffer's row
        // is cut, as the panel's window would cut it).
        let bytes: &[u8] = bytemuck::cast_slice(colors);
        let len = bytes.len().min(ROW_BYTES);
        buf[at..at + len].copy_from_slice(&bytes[..len]);
        self.row_done()
    }

    /// Lends the next row of a buffer, black already: the renderer draws
    /// the row in place. (A row wider than the buffer's row is the
    /// renderer's error.)
    fn lend_row(
        &mut self,
        y: u16,
        _width: usize,
        background: WireColor,
    ) -> Result<Option<LentRow<'_, WireColor>>, LcdError> {
        let (buf, at) = self.row_slot(y)?;
        let colors =
            bytemuck::try_cast_slice_mut(&mut buf[at..at + ROW_BYTES]).map_err(|_| LcdError)?;
        Ok(Some(LentRow {
            colors,
            filled: background == WIRE_BLACK,
        }))
    }

    fn send_lent_row(&mut self, _y: u16, _depths: &[u16]) -> Result<(), LcdError> {
        self.row_done()
    }
}
