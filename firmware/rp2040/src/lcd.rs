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

#[cfg(not(feature = "dual-core"))]
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
/// Rings of [`ROW_BUFFERS`] rows: two with `dual-core`, where core 0
/// starts a frame while core 1's rows of the last one may still be
/// leaving; one with `textured`, whose frames take many times the wire's
/// and whose two renderers leave no room for a second.
const RINGS: usize = if cfg!(all(feature = "dual-core", not(feature = "textured"))) {
    2
} else {
    1
};
/// Buffers in the ring.
const BUFFERS: usize = RINGS * ROW_BUFFERS / ROWS_PER_BUFFER;
/// Rows core 1 may draw in a frame (feature `dual-core`): its own
/// buffers hold them all, so it never waits for core 0's rows to leave.
/// More with `textured` (whose ring is not doubled), where the frame's
/// work would otherwise leave core 0 twice core 1's.
#[cfg(feature = "dual-core")]
pub const POOL_ROWS: usize = if cfg!(feature = "textured") { 176 } else { 128 };
/// Core 1's buffers.
#[cfg(feature = "dual-core")]
const POOL_BUFFERS: usize = POOL_ROWS / ROWS_PER_BUFFER;
/// Buffers in all, the capacity of every ring.
#[cfg(feature = "dual-core")]
const ALL_BUFFERS: usize = BUFFERS + POOL_BUFFERS;
/// Buffers in all, the capacity of every ring.
#[cfg(not(feature = "dual-core"))]
const ALL_BUFFERS: usize = BUFFERS;

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

/// Core 1's row buffers, in `.bss` (feature `dual-core`).
#[cfg(feature = "dual-core")]
static POOL: ConstStaticCell<[RowBytes; POOL_BUFFERS]> =
    ConstStaticCell::new([const { RowBytes([0; BUFFER_BYTES]) }; POOL_BUFFERS]);

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

/// A first-in first-out ring of row buffers (or of queued ones).
struct Ring<T = RowBuf> {
    slots: [Option<T>; ALL_BUFFERS],
    head: usize,
    len: usize,
}

impl<T> Ring<T> {
    const fn new() -> Self {
        Self {
            slots: [const { None }; ALL_BUFFERS],
            head: 0,
            len: 0,
        }
    }

    /// Appends `buf` (never full: there are `ALL_BUFFERS` buffers in
    /// all).
    fn push(&mut self, buf: T) {
        debug_assert!(self.len < ALL_BUFFERS);
        self.slots[wrap(self.head + self.len)] = Some(buf);
        self.len += 1;
    }

    #[inline]
    fn pop(&mut self) -> Option<T> {
        let buf = self.slots[self.head].take()?;
        self.head = wrap(self.head + 1);
        self.len -= 1;
        Some(buf)
    }
}

/// `index mod ALL_BUFFERS` for `index < 2·ALL_BUFFERS`, by a compare:
/// `%` would be a call to the divider on every row.
fn wrap(index: usize) -> usize {
    if index >= ALL_BUFFERS {
        index - ALL_BUFFERS
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
    queued: Ring<Queued>,
    sent: Ring,
    free: Ring,
    /// `None` only inside [`Queue::advance`].
    clearer: Option<Clearer>,
    /// Core 1's share of the frame and the LCD's pins (feature
    /// `dual-core`).
    #[cfg(feature = "dual-core")]
    dual: Dual,
}

/// A full buffer queued for the wire. (With one core, the sink opens each
/// frame's window before queueing its first buffer.)
#[cfg(not(feature = "dual-core"))]
type Queued = RowBuf;

/// A full buffer queued for the wire (feature `dual-core`): the first of a
/// frame opens the panel's window before it is sent, since core 1's rows
/// of the last frame may still be leaving when core 0 starts the next.
#[cfg(feature = "dual-core")]
struct Queued {
    buf: RowBuf,
    opens_frame: bool,
}

/// What the queue holds for two cores (feature `dual-core`).
#[cfg(feature = "dual-core")]
struct Dual {
    /// Chip select and data/command, to open a frame's window.
    pins: (LcdCs, LcdDc),
    /// Core 1's free buffers.
    free: Ring,
    /// Core 1's full buffers, held until core 0's rows above are queued.
    held: Ring,
    /// Whether core 0 has queued its rows of this frame: core 1's full
    /// buffers then go straight to the wire.
    top_done: bool,
    /// The addresses core 1's buffers lie in, to send a cleared buffer
    /// home.
    addresses: core::ops::Range<usize>,
    /// The first row core 1 draws this frame ([`choose_cut`]); the
    /// frame's height until it has chosen.
    cut: u16,
    /// The rows core 0 has started this frame (a whole buffer's at a
    /// time): core 1 cuts no higher.
    core0_rows: u16,
    /// Microseconds each buffer of rows took to draw, in the last frame
    /// that drew it (on either core; a buffer the cut splits, both cores'
    /// parts): what [`choose_cut`] balances.
    profile: [u32; PROFILE_BUFFERS],
    /// Core 0's part of the buffer the cut splits (the buffer and its
    /// rows above the cut), once core 0 has drawn it and before core 1's
    /// part is full: whichever core finishes its part last copies core
    /// 0's rows into core 1's buffer, which then goes to the wire whole.
    partial: Option<(RowBuf, usize)>,
}

/// Buffers of rows in a frame (feature `dual-core`).
#[cfg(feature = "dual-core")]
pub const PROFILE_BUFFERS: usize = HEIGHT as usize / ROWS_PER_BUFFER;

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
                #[cfg(not(feature = "dual-core"))]
                self.free.push(buf);
                // Home to the free ring of the core it came from.
                #[cfg(feature = "dual-core")]
                if self.dual.addresses.contains(&(buf.as_ptr() as usize)) {
                    self.dual.free.push(buf);
                } else {
                    self.free.push(buf);
                }
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
            && let Some(next) = self.queued.pop()
            && let Some(Bus::Idle { dma, spi }) = self.bus.take()
        {
            #[cfg(not(feature = "dual-core"))]
            let buf = next;
            #[cfg(feature = "dual-core")]
            let (mut spi, buf) = (spi, next.buf);
            #[cfg(feature = "dual-core")]
            if next.opens_frame {
                let (cs, dc) = &mut self.dual.pins;
                open_window(&mut spi, cs, dc);
            }
            self.bus = Some(Bus::Sending(
                single_buffer::Config::new(dma, buf, spi).start(),
            ));
        }
    }
}

/// Opens the whole panel for writing: CS cycled, CASET, RASET, RAMWR,
/// then DC high for pixel data. (A few microseconds of blocking SPI, in
/// the interrupt or the sink's call that finds the bus idle, so the CPU
/// never waits for the last frame's rows to leave before drawing the
/// next.) The pins and the SPI cannot fail on this chip.
#[cfg(feature = "dual-core")]
fn open_window(spi: &mut LcdSpi, cs: &mut LcdCs, dc: &mut LcdDc) {
    let span = |offset: u16, size: u16| {
        let (a, b) = (offset, offset + size - 1);
        [(a >> 8) as u8, a as u8, (b >> 8) as u8, b as u8]
    };
    // The last frame's last bytes may still be in the FIFO or the shift
    // register when its transfer is done: out first, before CS and DC
    // move.
    let Ok(()) = spi.flush();
    let Ok(()) = cs.set_high();
    let Ok(()) = cs.set_low();
    command(spi, dc, CASET, &span(OFFSET.0, WIDTH));
    command(spi, dc, RASET, &span(OFFSET.1, HEIGHT));
    command(spi, dc, RAMWR, &[]);
}

/// Sends one command over the SPI (DC low for the command byte, high for
/// the parameters).
#[cfg(feature = "dual-core")]
fn command(spi: &mut LcdSpi, dc: &mut LcdDc, cmd: u8, params: &[u8]) {
    let Ok(()) = dc.set_low();
    let Ok(()) = spi.write(&[cmd]);
    let Ok(()) = spi.flush();
    let Ok(()) = dc.set_high();
    if !params.is_empty() {
        let Ok(()) = spi.write(params);
        let Ok(()) = spi.flush();
    }
}

/// The queue. With one core drawing, only core 0 touches it (the render
/// loop and its DMA interrupt), so masking interrupts is enough to share
/// it: no spinlock.
#[cfg(not(feature = "dual-core"))]
static QUEUE: Mutex<RefCell<Option<Queue>>> = Mutex::new(RefCell::new(None));

/// Runs `f` on the queue with interrupts held off; `None` before
/// [`LcdRows::new`].
#[cfg(not(feature = "dual-core"))]
fn with_queue<R>(f: impl FnOnce(&mut Queue) -> R) -> Option<R> {
    without_interrupts(|cs| QUEUE.borrow(cs).borrow_mut().as_mut().map(f))
}

/// The queue, shared by both cores (feature `dual-core`): taken under
/// rp2040-hal's critical section, a hardware spinlock with interrupts
/// held off on the taking core.
#[cfg(feature = "dual-core")]
static QUEUE: critical_section::Mutex<RefCell<Option<Queue>>> =
    critical_section::Mutex::new(RefCell::new(None));

/// Runs `f` on the queue under the two cores' critical section; `None`
/// before [`LcdRows::new`].
#[cfg(feature = "dual-core")]
fn with_queue<R>(f: impl FnOnce(&mut Queue) -> R) -> Option<R> {
    critical_section::with(|cs| QUEUE.borrow_ref_mut(cs).as_mut().map(f))
}

/// A row has left: free its buffer, start the next.
#[interrupt]
fn DMA_IRQ_0() {
    with_queue(Queue::advance);
}

/// The LCD as a row sink: see the module notes.
pub struct LcdRows {
    /// Chip select and data/command (with one core; with two, the queue
    /// holds them).
    #[cfg(not(feature = "dual-core"))]
    cs: LcdCs,
    #[cfg(not(feature = "dual-core"))]
    dc: LcdDc,
    /// The buffer being filled, row after row, and how many of its rows
    /// are done.
    filling: Option<(RowBuf, usize)>,
    /// Whether the buffer being filled is its frame's first (feature
    /// `dual-core`).
    #[cfg(feature = "dual-core")]
    opens_frame: bool,
    /// What the cut between the cores needs (feature `dual-core`).
    #[cfg(feature = "dual-core")]
    band: Band,
}

/// A core's band of rows (feature `dual-core`): the clock its buffers are
/// timed by, the buffer being filled and when it began, and whether the
/// band ended at the cut.
#[cfg(feature = "dual-core")]
struct Band {
    timer: Option<crate::board::Timer>,
    buffer: usize,
    began: u32,
    stopped: bool,
    /// Core 0's: the cut, when it splits the buffer being filled (the
    /// band ends at that row, not at the buffer's end); the frame's height
    /// otherwise.
    stop_at: u16,
    /// Core 1's: whether the buffer being filled is one the cut splits
    /// (its time is then added to core 0's part's).
    split: bool,
}

#[cfg(feature = "dual-core")]
impl Band {
    const fn new() -> Self {
        Self {
            timer: None,
            buffer: 0,
            began: 0,
            stopped: false,
            stop_at: HEIGHT,
            split: false,
        }
    }

    /// A buffer of rows starts at row `y`.
    fn start(&mut self, y: u16) {
        self.buffer = usize::from(y) / ROWS_PER_BUFFER;
        self.began = self.now();
    }

    /// Microseconds since the buffer began.
    fn elapsed(&self) -> u32 {
        self.now().wrapping_sub(self.began)
    }

    fn now(&self) -> u32 {
        self.timer.as_ref().map_or(0, |t| t.get_counter_low())
    }
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
        #[cfg(not(feature = "dual-core"))]
        without_interrupts(|cs| {
            QUEUE.borrow(cs).borrow_mut().replace(Queue {
                bus: Some(Bus::Idle { dma, spi }),
                queued: Ring::new(),
                sent: Ring::new(),
                free,
                clearer: Some(Clearer::Idle(clear_dma)),
            })
        });
        #[cfg(feature = "dual-core")]
        {
            let buffers = POOL.try_take()?;
            let start = buffers.as_ptr() as usize;
            let addresses = start..start + core::mem::size_of_val(buffers);
            let mut pool = Ring::new();
            for row in buffers {
                pool.push(&mut row.0);
            }
            let queue = Queue {
                bus: Some(Bus::Idle { dma, spi }),
                queued: Ring::new(),
                sent: Ring::new(),
                free,
                clearer: Some(Clearer::Idle(clear_dma)),
                dual: Dual {
                    pins: (cs, dc),
                    free: pool,
                    held: Ring::new(),
                    top_done: false,
                    addresses,
                    cut: HEIGHT,
                    core0_rows: 0,
                    profile: [0; PROFILE_BUFFERS],
                    partial: None,
                },
            };
            critical_section::with(|cs| QUEUE.borrow_ref_mut(cs).replace(queue));
        }
        // SAFETY: the handler only touches `QUEUE`, inside a critical
        // section; unmasking cannot break a critical section in progress.
        unsafe { cortex_m::peripheral::NVIC::unmask(pac::Interrupt::DMA_IRQ_0) };
        #[cfg(not(feature = "dual-core"))]
        return Some(Self {
            cs,
            dc,
            filling: None,
        });
        #[cfg(feature = "dual-core")]
        Some(Self {
            filling: None,
            opens_frame: false,
            band: Band::new(),
        })
    }
}

#[cfg(not(feature = "dual-core"))]
impl LcdRows {
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

#[cfg(not(feature = "dual-core"))]
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
fn queue_row(buf: Queued) -> Result<(), LcdError> {
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
            // With one core the window opens now, once the last frame's
            // rows are out; with two, when the wire reaches this frame's
            // first buffer (core 1's rows of the last frame may still be
            // leaving).
            #[cfg(not(feature = "dual-core"))]
            self.begin_frame()?;
            #[cfg(feature = "dual-core")]
            {
                self.opens_frame = true;
            }
            if let Some((buf, _)) = self.filling.take() {
                with_queue(|q| {
                    q.sent.push(buf);
                    q.advance();
                })
                .ok_or(LcdError)?;
            }
        }
        // The cut splits the buffer being filled: core 1 draws from here.
        #[cfg(feature = "dual-core")]
        if y >= self.band.stop_at {
            self.band.stopped = true;
            return Err(LcdError);
        }
        let (buf, done) = match self.filling.take() {
            Some((buf, done)) if done < ROWS_PER_BUFFER => (buf, done),
            #[cfg(not(feature = "dual-core"))]
            _ => (free_buffer()?, 0),
            #[cfg(feature = "dual-core")]
            _ => (self.claim_buffer(y)?, 0),
        };
        let (buf, done) = self.filling.insert((buf, done));
        Ok((buf, *done * ROW_BYTES))
    }

    /// Row done: a full buffer is queued for the wire.
    fn row_done(&mut self) -> Result<(), LcdError> {
        match self.filling.take() {
            #[cfg(not(feature = "dual-core"))]
            Some((buf, done)) if done + 1 == ROWS_PER_BUFFER => queue_row(buf),
            #[cfg(feature = "dual-core")]
            Some((buf, done)) if done + 1 == ROWS_PER_BUFFER => {
                let (index, micros) = (self.band.buffer, self.band.elapsed());
                with_queue(|q| {
                    if let Some(slot) = q.dual.profile.get_mut(index) {
                        *slot = micros;
                    }
                })
                .ok_or(LcdError)?;
                queue_row(Queued {
                    buf,
                    opens_frame: core::mem::take(&mut self.opens_frame),
                })
            }
            Some((buf, done)) => {
                self.filling = Some((buf, done + 1));
                Ok(())
            }
            None => Err(LcdError),
        }
    }
}

/// Copies a row's bytes (already big-endian Rgb565, as the ST7789 takes
/// them over SPI) into its place at byte `at` of a buffer: one copy; a
/// row longer than the buffer's row is cut, as the panel's window would
/// cut it.
#[inline(always)]
fn copy_row(buf: &mut [u8; BUFFER_BYTES], at: usize, bytes: &[u8]) {
    let len = bytes.len().min(ROW_BYTES);
    buf[at..at + len].copy_from_slice(&bytes[..len]);
}

/// The row at byte `at` of a buffer, lent as pixels (black already, so
/// filled when the background is black). A row wider than the buffer's
/// row is the renderer's error.
#[inline(always)]
fn lend_row_of(
    buf: &mut [u8; BUFFER_BYTES],
    at: usize,
    background: WireColor,
) -> Result<LentRow<'_, WireColor>, LcdError> {
    let colors =
        bytemuck::try_cast_slice_mut(&mut buf[at..at + ROW_BYTES]).map_err(|_| LcdError)?;
    Ok(LentRow {
        colors,
        filled: background == WIRE_BLACK,
    })
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
        copy_row(buf, at, bytemuck::cast_slice(colors));
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
        copy_row(buf, at, bytemuck::cast_slice(colors));
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
        lend_row_of(buf, at, background).map(Some)
    }

    fn send_lent_row(&mut self, _y: u16, _depths: &[u16]) -> Result<(), LcdError> {
        self.row_done()
    }
}
/// Core 1's rows (feature `dual-core`): the bottom rows of each frame,
/// drawn in place into core 1's own buffers. A full buffer is held until
/// core 0 has queued its rows above ([`LcdRows::top_done`]), then queued
/// behind them; after that, each goes to the wire as it fills.
#[cfg(feature = "dual-core")]
pub struct PoolRows {
    filling: Option<(RowBuf, usize)>,
    band: Band,
}

#[cfg(feature = "dual-core")]
impl PoolRows {
    /// Core 1's sink, with no buffer yet.
    pub const fn new() -> Self {
        Self {
            filling: None,
            band: Band::new(),
        }
    }

    /// Times each buffer of rows by `timer` (for the cut's balance).
    pub fn set_timer(&mut self, timer: crate::board::Timer) {
        self.band.timer = Some(timer);
    }

    /// Starts core 1's band of a frame: a buffer left part-filled by a
    /// band an error cut short is cleared, not continued.
    pub fn begin_band(&mut self) -> Result<(), LcdError> {
        match self.filling.take() {
            Some((buf, _)) => with_queue(|q| {
                q.sent.push(buf);
                q.advance();
            })
            .ok_or(LcdError),
            None => Ok(()),
        }
    }

    /// The buffer the next row goes into and the byte offset of its row
    /// there. Core 1's band may start inside a buffer's rows (the cut
    /// splits it): its first rows then go where they lie in that buffer,
    /// below core 0's part, which joins them before the buffer is sent.
    fn row_slot(&mut self, y: u16) -> Result<(&mut [u8; BUFFER_BYTES], usize), LcdError> {
        let (buf, done) = match self.filling.take() {
            Some((buf, done)) if done < ROWS_PER_BUFFER => (buf, done),
            _ => {
                let buf = pool_buffer()?;
                self.band.start(y);
                let skipped = usize::from(y) % ROWS_PER_BUFFER;
                self.band.split = skipped != 0;
                (buf, skipped)
            }
        };
        let (buf, done) = self.filling.insert((buf, done));
        Ok((buf, *done * ROW_BYTES))
    }

    /// Row done: a full buffer is held, or queued once core 0's rows are.
    fn row_done(&mut self) -> Result<(), LcdError> {
        match self.filling.take() {
            Some((buf, done)) if done + 1 == ROWS_PER_BUFFER => with_queue(|q| {
                if let Some(slot) = q.dual.profile.get_mut(self.band.buffer) {
                    // A split buffer's time is both cores' parts.
                    let micros = self.band.elapsed();
                    *slot = if self.band.split {
                        slot.saturating_add(micros)
                    } else {
                        micros
                    };
                }
                if q.dual.top_done {
                    // Core 0's part of a split buffer came first: it joins
                    // this one, the first of the band.
                    let buf = match q.dual.partial.take() {
                        Some((part, rows)) => merge_split(buf, part, rows, &mut q.sent),
                        None => buf,
                    };
                    q.queued.push(Queued {
                        buf,
                        opens_frame: false,
                    });
                    if let Some(Bus::Idle { .. }) = q.bus {
                        q.advance();
                    }
                } else {
                    q.dual.held.push(buf);
                }
            })
            .ok_or(LcdError),
            Some((buf, done)) => {
                self.filling = Some((buf, done + 1));
                Ok(())
            }
            None => Err(LcdError),
        }
    }
}

/// Core 1's first buffer of a band whose cut splits it, with core 0's
/// `rows` rows above the cut copied in from `part` (which goes to be
/// cleared): the buffer, whole. (At most `ROWS_PER_BUFFER - 1` rows, once
/// a frame.)
#[cfg(feature = "dual-core")]
fn merge_split(first: RowBuf, part: RowBuf, rows: usize, sent: &mut Ring) -> RowBuf {
    let bytes = rows.min(ROWS_PER_BUFFER) * ROW_BYTES;
    first[..bytes].copy_from_slice(&part[..bytes]);
    sent.push(part);
    first
}

/// A free buffer of core 1's; when all are held or on their way out,
/// waits for the wire (taking the queue's lock each time: the cores share
/// no flag outside it).
#[cfg(feature = "dual-core")]
fn pool_buffer() -> Result<RowBuf, LcdError> {
    loop {
        if let Some(buf) = with_queue(|q| {
            q.dual.free.pop().or_else(|| {
                q.advance();
                q.dual.free.pop()
            })
        })
        .ok_or(LcdError)?
        {
            return Ok(buf);
        }
        core::hint::spin_loop();
    }
}

/// Core 1's painted rows (`dual-core` with `gouraud` or `textured`): the
/// painted renderer's row, copied into a buffer as core 0's are.
#[cfg(all(feature = "dual-core", any(feature = "gouraud", feature = "textured")))]
impl RowSink<crate::frame::WirePixel, u16> for PoolRows {
    type Error = LcdError;

    fn write_row(
        &mut self,
        y: u16,
        colors: &[crate::frame::WirePixel],
        _depths: &[u16],
    ) -> Result<(), LcdError> {
        let (buf, at) = self.row_slot(y)?;
        copy_row(buf, at, bytemuck::cast_slice(colors));
        self.row_done()
    }
}

#[cfg(feature = "dual-core")]
impl RowSink<WireColor, u16> for PoolRows {
    type Error = LcdError;

    /// A row from the renderer's own colour row: copied into a buffer.
    fn write_row(&mut self, y: u16, colors: &[WireColor], _depths: &[u16]) -> Result<(), LcdError> {
        let (buf, at) = self.row_slot(y)?;
        copy_row(buf, at, bytemuck::cast_slice(colors));
        self.row_done()
    }

    /// Lends the next row of a buffer, black already.
    fn lend_row(
        &mut self,
        y: u16,
        _width: usize,
        background: WireColor,
    ) -> Result<Option<LentRow<'_, WireColor>>, LcdError> {
        let (buf, at) = self.row_slot(y)?;
        lend_row_of(buf, at, background).map(Some)
    }

    fn send_lent_row(&mut self, _y: u16, _depths: &[u16]) -> Result<(), LcdError> {
        self.row_done()
    }
}

#[cfg(feature = "dual-core")]
impl LcdRows {
    /// Core 0's rows of this frame are queued: core 1's held buffers
    /// follow them, and its later ones go straight to the wire. Core 0's
    /// part of a buffer the cut splits goes into core 1's first buffer
    /// here when that is full already, else it waits for core 1 there
    /// ([`merge_split`]).
    pub fn top_done(&mut self) -> Result<(), LcdError> {
        // Core 0's part of a buffer the cut splits: its rows above the cut.
        let part = match self.filling.take() {
            Some((buf, rows)) if self.band.stopped && rows > 0 => {
                Some((buf, rows, self.band.buffer, self.band.elapsed()))
            }
            other => {
                self.filling = other;
                None
            }
        };
        with_queue(|q| {
            if let Some((buf, rows, index, micros)) = part {
                if let Some(slot) = q.dual.profile.get_mut(index) {
                    *slot = slot.saturating_add(micros);
                }
                // Core 1's first buffer holds the rows below the cut: when
                // it is full already, core 0's rows go into it here, else
                // core 1 takes them when it is.
                match q.dual.held.pop() {
                    Some(first) => {
                        let merged = merge_split(first, buf, rows, &mut q.sent);
                        q.queued.push(Queued {
                            buf: merged,
                            opens_frame: false,
                        });
                    }
                    None => q.dual.partial = Some((buf, rows)),
                }
            }
            while let Some(buf) = q.dual.held.pop() {
                q.queued.push(Queued {
                    buf,
                    opens_frame: false,
                });
            }
            q.dual.top_done = true;
            if let Some(Bus::Idle { .. }) = q.bus {
                q.advance();
            }
        })
        .ok_or(LcdError)
    }

    /// Both cores' rows of this frame are queued: the next frame's core-1
    /// buffers are held again until core 0's rows are queued, and core 0
    /// draws every row until core 1 cuts its share.
    pub fn frame_done(&mut self) -> Result<(), LcdError> {
        self.band.stopped = false;
        self.band.stop_at = HEIGHT;
        with_queue(|q| {
            // Left only when core 1's rows failed: cleared, not sent.
            if let Some((buf, _)) = q.dual.partial.take() {
                q.sent.push(buf);
            }
            // Held buffers are left only when core 0's rows failed: they
            // are cleared, not sent after the next frame's rows.
            while let Some(buf) = q.dual.held.pop() {
                q.sent.push(buf);
            }
            q.advance();
            q.dual.top_done = false;
            q.dual.cut = HEIGHT;
            q.dual.core0_rows = 0;
        })
        .ok_or(LcdError)
    }

    /// Times each buffer of rows by `timer` (for the cut's balance).
    pub fn set_timer(&mut self, timer: crate::board::Timer) {
        self.band.timer = Some(timer);
    }

    /// Whether this frame's scan ended at the cut (its error is then the
    /// band's end, not a fault).
    pub fn stopped_at_cut(&self) -> bool {
        self.band.stopped
    }

    /// A free buffer for the rows from `y` (a buffer's first row), or the
    /// band's end when core 1 has cut its share at or above `y`; the
    /// rows taken are noted, so that core 1 cuts below them. Waits for the
    /// wire when every buffer is in use.
    fn claim_buffer(&mut self, y: u16) -> Result<RowBuf, LcdError> {
        loop {
            let claimed = with_queue(|q| {
                if y >= q.dual.cut {
                    return Err(());
                }
                let buf = q.free.pop().or_else(|| {
                    q.advance();
                    q.free.pop()
                });
                if buf.is_some() {
                    q.dual.core0_rows = y + ROWS_PER_BUFFER as u16;
                }
                Ok(buf.map(|buf| (buf, q.dual.cut)))
            })
            .ok_or(LcdError)?;
            match claimed {
                Err(()) => {
                    self.band.stopped = true;
                    return Err(LcdError);
                }
                Ok(Some((buf, cut))) => {
                    self.band.start(y);
                    // A cut inside this buffer ends the band there (the
                    // cut is chosen at or below the rows core 0 has
                    // claimed, so it is known by the time core 0 claims
                    // its buffer).
                    self.band.stop_at = if cut < y + ROWS_PER_BUFFER as u16 {
                        cut
                    } else {
                        HEIGHT
                    };
                    return Ok(buf);
                }
                Ok(None) => core::hint::spin_loop(),
            }
        }
    }
}

#[cfg(feature = "dual-core")]
/// Core 1's share of this frame (feature `dual-core`): the first row it
/// draws, chosen once it has drawn the next frame's scene, and noted for
/// core 0 (which stops there). By the last frame's time per buffer of
/// rows: the row (below the rows core 0 has started, leaving core 1 no
/// more rows than its buffers hold) at which core 0's rows still to draw,
/// plus `bias` microseconds (what the rows' times leave out: core 0's
/// waits for the wire, the rest of the buffer it is in), take as long as
/// core 1's, within the buffer where the two meet taken as spread evenly
/// over its rows. A cut inside a buffer splits it between the cores
/// (see [`merge_split`]): cut at buffers' edges only, the cores' ends
/// were apart by up to a buffer's time (about 0.13 M cycles), and the cut
/// swung from frame to frame between two edges. Before any row below core
/// 0's has a time (the first frame), the rows core 0 has still to draw are
/// halved, as if each took as long, unless `estimate` gives each buffer's
/// time ([`crate::row_costs::estimate`]): it then stands for the times.
/// Returns the cut and whether it came from times (not from an estimate
/// or the halving).
pub fn choose_cut(bias: i32, estimate: Option<&[u32; PROFILE_BUFFERS]>) -> Option<(u16, bool)> {
    with_queue(|q| {
        let d = &mut q.dual;
        let per_buffer = ROWS_PER_BUFFER as i32;
        // Core 0's next buffer, and the first that core 1 may take (its
        // own buffers hold every row below).
        let next = usize::from(d.core0_rows.div_ceil(ROWS_PER_BUFFER as u16)).min(PROFILE_BUFFERS);
        let first = next.max(PROFILE_BUFFERS.saturating_sub(POOL_BUFFERS));
        // Microseconds, each buffer's capped so that the sums and the
        // split's `gap · 8 + m` below stay in an i32 (a frame takes far
        // fewer than 2^26 of them).
        let micros_of = |m: u32| m.min(i32::MAX as u32 / 32) as i32;
        let sum = |p: &[u32]| p.iter().fold(0i32, |s, &m| s.saturating_add(micros_of(m)));
        let estimated = match estimate {
            Some(estimate) if d.profile[next..].iter().all(|&m| m == 0) => {
                d.profile[next..].copy_from_slice(&estimate[next..]);
                true
            }
            _ => false,
        };
        let mut core1 = sum(&d.profile[first..]);
        let lowest = first as i32 * per_buffer;
        if core1 == 0 {
            let from = i32::from(d.core0_rows);
            d.cut = (from + (i32::from(HEIGHT) - from) / 2).max(lowest) as u16;
            return (d.cut, false);
        }
        // Core 0's rows above those core 1 may take are core 0's whatever
        // the cut. (Left out until 2026-12-03, they were what `bias`
        // learnt: about 8,000 µs on the Gouraud torus knot, so the frames
        // before it was learnt gave core 0 a third more than core 1.)
        let mut core0 = bias.saturating_add(sum(&d.profile[next..first]));
        let mut cut = lowest;
        for &micros in d.profile.iter().skip(first) {
            let m = micros_of(micros);
            if core0.saturating_add(m) <= core1 - m {
                core0 = core0.saturating_add(m);
                core1 -= m;
                cut += per_buffer;
                continue;
            }
            // They meet in this buffer: `r` of its rows to core 0, where
            // core0 + r·m/8 = core1 - r·m/8, rounded.
            if core1 > core0 && m > 0 {
                let gap = (core1 - core0).min(2 * m);
                cut += ((gap * per_buffer + m) / (2 * m)).min(per_buffer - 1);
            }
            break;
        }
        // (`cut` is at most the frame's height.)
        d.cut = cut as u16;
        // Both cores add their parts of a split buffer's time.
        if cut % per_buffer != 0
            && let Some(slot) = d.profile.get_mut(cut as usize / ROWS_PER_BUFFER)
        {
            *slot = 0;
        }
        (d.cut, !estimated)
    })
}
