//! The ST7789 as the firmware drives it over SPI: the command stream
//! decoded into the controller's 240x320 memory, cut into frames.
//!
//! A byte sent with DC low is a command, with DC high its parameters or
//! pixel data. CASET and RASET set the window, RAMWR starts writing
//! big-endian Rgb565 pixels into it row by row (MADCTL may swap and mirror
//! the axes). A frame starts at a RAMWR whose window starts at row 0 and
//! ends where the next one starts; its CRC-32 is that of the panel's
//! visible 240x240 pixels (the top-left of the memory), big-endian,
//! row-major: the bytes the firmware sent for a full-window frame. These
//! rules are the ones `../shared/rp2040-emu/run-fw.mjs` decodes by, so
//! the two emulators' frames compare.

use crate::crc32::Crc32;

/// Columns of the controller's memory.
pub const MEMORY_WIDTH: usize = 240;
/// Rows of the controller's memory.
pub const MEMORY_HEIGHT: usize = 320;
/// The visible panel: this many columns and rows from the memory's origin.
pub const PANEL: usize = 240;
/// Pixels of a whole frame.
pub const FRAME_PIXELS: usize = PANEL * PANEL;
/// Bytes of a whole frame on the wire.
pub const FRAME_BYTES: usize = 2 * FRAME_PIXELS;

/// Column address set.
pub const CASET: u8 = 0x2A;
/// Row address set.
pub const RASET: u8 = 0x2B;
/// Memory write: pixel data follows.
pub const RAMWR: u8 = 0x2C;
/// Memory data access control (axis swap and mirrors).
pub const MADCTL: u8 = 0x36;

/// MADCTL's row/column exchange bit.
const MADCTL_MV: u8 = 0x20;
/// MADCTL's column-order (X mirror) bit.
const MADCTL_MX: u8 = 0x40;
/// MADCTL's row-order (Y mirror) bit.
const MADCTL_MY: u8 = 0x80;
/// Commands other than the window ones kept for the start-up check.
const STARTUP_KEPT: usize = 16;

/// A frame the panel has received whole (the next one has started).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Frame<T> {
    /// Frames before it since the panel was first written (0: the first).
    pub index: usize,
    /// What the caller stamped the CASET before the frame's first RAMWR
    /// with (or the RAMWR itself, without a CASET).
    pub start: T,
    /// The next frame's start, stamped the same way: where this one ended.
    pub end: T,
    /// CRC-32 of the visible pixels when the frame ended.
    pub crc32: u32,
    /// Pixels written during the frame.
    pub pixels: usize,
}

/// The frame being received.
#[derive(Debug, Clone, Copy)]
struct Current<T> {
    index: usize,
    start: T,
    pixels: usize,
}

/// The controller: its memory, window, parser state and the frame in
/// progress. `T` is whatever the caller stamps bytes with (a cycle count).
#[derive(Debug, Clone)]
pub struct St7789<T> {
    memory: Vec<u16>,
    madctl: u8,
    columns: (u16, u16),
    rows: (u16, u16),
    x: u16,
    y: u16,
    command: Option<u8>,
    params: [u8; 4],
    param_count: usize,
    high_byte: Option<u8>,
    window_stamp: Option<T>,
    startup: Vec<u8>,
    current: Option<Current<T>>,
    frames_started: usize,
}

impl<T: Copy> Default for St7789<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Copy> St7789<T> {
    /// A controller after reset: memory black, full window, no frame yet.
    pub fn new() -> Self {
        Self {
            memory: vec![0; MEMORY_WIDTH * MEMORY_HEIGHT],
            madctl: 0,
            columns: (0, MEMORY_WIDTH as u16 - 1),
            rows: (0, MEMORY_HEIGHT as u16 - 1),
            x: 0,
            y: 0,
            command: None,
            params: [0; 4],
            param_count: 0,
            high_byte: None,
            window_stamp: None,
            startup: Vec::new(),
            current: None,
            frames_started: 0,
        }
    }

    /// One byte off the wire, with DC high (`data`) or low (a command),
    /// stamped `stamp`. Returns the frame this byte ended, if any.
    pub fn byte(&mut self, data: bool, byte: u8, stamp: T) -> Option<Frame<T>> {
        if data {
            self.data(byte);
            None
        } else {
            self.command(byte, stamp)
        }
    }

    /// The first commands other than CASET, RASET and RAMWR (at most 16):
    /// the start-up sequence.
    pub fn startup_commands(&self) -> &[u8] {
        &self.startup
    }

    /// CRC-32 of the visible 240x240 pixels, big-endian, row-major.
    pub fn visible_crc(&self) -> u32 {
        let mut crc = Crc32::new();
        let mut row = [0u8; 2 * PANEL];
        for y in 0..PANEL {
            let line = &self.memory[y * MEMORY_WIDTH..y * MEMORY_WIDTH + PANEL];
            for (bytes, &pixel) in row.chunks_exact_mut(2).zip(line) {
                bytes.copy_from_slice(&pixel.to_be_bytes());
            }
            crc.update(&row);
        }
        crc.finish()
    }

    fn command(&mut self, byte: u8, stamp: T) -> Option<Frame<T>> {
        self.command = Some(byte);
        self.param_count = 0;
        self.high_byte = None;
        match byte {
            CASET => {
                self.window_stamp = Some(stamp);
                None
            }
            RASET => None,
            RAMWR => {
                self.x = self.columns.0;
                self.y = self.rows.0;
                if self.rows.0 == 0 {
                    self.start_frame(self.window_stamp.unwrap_or(stamp))
                } else {
                    None
                }
            }
            other => {
                if self.startup.len() < STARTUP_KEPT {
                    self.startup.push(other);
                }
                None
            }
        }
    }

    /// Starts a frame stamped `start`, ending the one in progress.
    fn start_frame(&mut self, start: T) -> Option<Frame<T>> {
        let ended = self.current.map(|c| Frame {
            index: c.index,
            start: c.start,
            end: start,
            crc32: self.visible_crc(),
            pixels: c.pixels,
        });
        self.current = Some(Current {
            index: self.frames_started,
            start,
            pixels: 0,
        });
        self.frames_started += 1;
        ended
    }

    fn data(&mut self, byte: u8) {
        let Some(command) = self.command else {
            return;
        };
        if command == RAMWR {
            match self.high_byte.take() {
                None => self.high_byte = Some(byte),
                Some(high) => self.pixel(u16::from_be_bytes([high, byte])),
            }
            return;
        }
        if self.param_count < self.params.len() {
            self.params[self.param_count] = byte;
        }
        self.param_count += 1;
        let p = self.params;
        let span = || {
            (
                u16::from_be_bytes([p[0], p[1]]),
                u16::from_be_bytes([p[2], p[3]]),
            )
        };
        match (command, self.param_count) {
            (CASET, 4) => self.columns = span(),
            (RASET, 4) => self.rows = span(),
            (MADCTL, 1) => self.madctl = byte,
            _ => {}
        }
    }

    /// Stores one pixel at the write position and moves it on, wrapping
    /// within the window.
    fn pixel(&mut self, value: u16) {
        let (mut px, mut py) = (usize::from(self.x), usize::from(self.y));
        let swapped = self.madctl & MADCTL_MV != 0;
        if swapped {
            (px, py) = (py, px);
        }
        let (width, height) = if swapped {
            (MEMORY_HEIGHT, MEMORY_WIDTH)
        } else {
            (MEMORY_WIDTH, MEMORY_HEIGHT)
        };
        if self.madctl & MADCTL_MX != 0 {
            px = (width - 1).wrapping_sub(px);
        }
        if self.madctl & MADCTL_MY != 0 {
            py = (height - 1).wrapping_sub(py);
        }
        if px < MEMORY_WIDTH && py < MEMORY_HEIGHT {
            self.memory[py * MEMORY_WIDTH + px] = value;
        }
        if let Some(current) = &mut self.current {
            current.pixels += 1;
        }
        if self.x >= self.columns.1 {
            self.x = self.columns.0;
            if self.y >= self.rows.1 {
                self.y = self.rows.0;
            } else {
                self.y += 1;
            }
        } else {
            self.x += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crc32::crc32;

    /// Sends a command and its parameters, stamped `stamp`.
    fn send(lcd: &mut St7789<u64>, command: u8, params: &[u8], stamp: u64) -> Option<Frame<u64>> {
        let ended = lcd.byte(false, command, stamp);
        for &b in params {
            assert!(lcd.byte(true, b, stamp).is_none());
        }
        ended
    }

    /// Opens columns `x0..=x1`, rows `y0..=y1` and sends RAMWR.
    fn window(
        lcd: &mut St7789<u64>,
        (x0, x1): (u16, u16),
        (y0, y1): (u16, u16),
        stamp: u64,
    ) -> Option<Frame<u64>> {
        let span = |a: u16, b: u16| [(a >> 8) as u8, a as u8, (b >> 8) as u8, b as u8];
        assert!(send(lcd, CASET, &span(x0, x1), stamp).is_none());
        assert!(send(lcd, RASET, &span(y0, y1), stamp + 1).is_none());
        send(lcd, RAMWR, &[], stamp + 2)
    }

    /// A test picture: pixel (x, y) of the panel.
    fn pattern(x: usize, y: usize) -> u16 {
        ((x * 7 + y * 13) & 0xFFFF) as u16
    }

    fn pattern_bytes() -> Vec<u8> {
        (0..PANEL)
            .flat_map(|y| (0..PANEL).flat_map(move |x| pattern(x, y).to_be_bytes()))
            .collect()
    }

    #[test]
    fn start_up_commands_and_a_full_window_frame() {
        let mut lcd = St7789::new();
        for (cmd, params) in [
            (0x11, &[][..]),
            (MADCTL, &[0]),
            (0x21, &[]),
            (0x3A, &[0x55]),
            (0x13, &[]),
            (0x29, &[]),
        ] {
            assert!(send(&mut lcd, cmd, params, 0).is_none());
        }
        assert_eq!(
            lcd.startup_commands(),
            &[0x11, 0x36, 0x21, 0x3A, 0x13, 0x29]
        );

        // Frame 0: black, the start-up clear.
        assert!(window(&mut lcd, (0, 239), (0, 239), 100).is_none());
        for _ in 0..FRAME_BYTES {
            lcd.byte(true, 0, 150);
        }
        // Frame 1: the pattern; it ends frame 0.
        let frame0 = window(&mut lcd, (0, 239), (0, 239), 1000).expect("frame 0 ends");
        let black = crc32(&[0; FRAME_BYTES]);
        let expected = Frame {
            index: 0,
            start: 100,
            end: 1000,
            crc32: black,
            pixels: FRAME_PIXELS,
        };
        assert_eq!(frame0, expected);
        for b in pattern_bytes() {
            lcd.byte(true, b, 1500);
        }
        let frame1 = window(&mut lcd, (0, 239), (0, 239), 5000).expect("frame 1 ends");
        assert_eq!(frame1.index, 1);
        assert_eq!(
            (frame1.start, frame1.end),
            (1000, 5000),
            "stamped at the CASETs"
        );
        assert_eq!(frame1.crc32, crc32(&pattern_bytes()));
        assert_eq!(frame1.pixels, FRAME_PIXELS);
        assert_eq!(
            lcd.startup_commands().len(),
            6,
            "window commands are not start-up ones"
        );
    }

    #[test]
    fn row_windows_compose_one_frame() {
        let mut lcd = St7789::new();
        for y in 0..PANEL {
            let ended = window(&mut lcd, (0, 239), (y as u16, y as u16), 10 * y as u64);
            assert!(ended.is_none(), "only a window at row 0 starts a frame");
            for x in 0..PANEL {
                for b in pattern(x, y).to_be_bytes() {
                    lcd.byte(true, b, 0);
                }
            }
        }
        let frame = window(&mut lcd, (0, 239), (0, 239), 9999).expect("ends");
        assert_eq!(frame.start, 0);
        assert_eq!(frame.crc32, crc32(&pattern_bytes()));
        assert_eq!(frame.pixels, FRAME_PIXELS);
    }

    #[test]
    fn a_short_frame_has_fewer_pixels() {
        let mut lcd = St7789::new();
        window(&mut lcd, (0, 239), (0, 239), 0);
        for _ in 0..100 {
            lcd.byte(true, 0xFF, 1);
        }
        let frame = window(&mut lcd, (0, 239), (0, 239), 2).expect("ends");
        assert_eq!(frame.pixels, 50);
    }

    #[test]
    fn madctl_mirrors_columns() {
        let mut lcd = St7789::new();
        send(&mut lcd, MADCTL, &[MADCTL_MX], 0);
        // One pixel at logical (0, 0) lands in the memory's last column.
        window(&mut lcd, (0, 0), (0, 0), 0);
        lcd.byte(true, 0x12, 0);
        lcd.byte(true, 0x34, 0);
        assert_eq!(lcd.memory[MEMORY_WIDTH - 1], 0x1234);
    }
}
