//! The wiring and the display knobs: which pins the LCD is on, the SPI
//! clock and mode, and how the panel is set up. `board.rs` brings it up;
//! `lcd.rs` streams rows over it.
//!
//! # Pinout
//!
//! | LCD pin     | Pico pin | GPIO | use                       |
//! |-------------|----------|------|---------------------------|
//! | SCL / SCK   | 24       | GP18 | SPI0 SCK                  |
//! | SDA / MOSI  | 25       | GP19 | SPI0 TX                   |
//! | CS          | 22       | GP17 | chip select (GPIO output) |
//! | DC / RS     | 21       | GP16 | data/command              |
//! | RES / RST   | 26       | GP20 | reset, active low         |
//! | BLK / BL    | 27       | GP21 | backlight, high = on      |
//! | VCC         | 36       | 3V3(OUT) |                       |
//! | GND         | 38       | GND  |                           |
//!
//! The pins are chosen in one place, the block marked "Pinout" in
//! `board::init`, and named in the types [`LcdSpi`], [`LcdCs`] and [`LcdDc`]
//! (change both together). SCK and MOSI must belong to the SPI block chosen there
//! (SPI0: SCK on GP2/6/18/22, TX on GP3/7/19; SPI1: SCK on GP10/14/26, TX on
//! GP11/15/27); the HAL checks this at compile time. CS, DC, RST and the
//! backlight can be any free GPIO.
//!
//! Modules without a CS pin have CS tied low on the board: leave GP17
//! unconnected. They need SPI mode 3 (clock idles high), which is why
//! [`SPI_MODE`] is mode 3; modules with CS work in mode 3 as well.

use embedded_hal::spi::{MODE_3, Mode};
use mipidsi::options::{ColorInversion, ColorOrder, Orientation};

use crate::hal::gpio::bank0::{Gpio16, Gpio17, Gpio18, Gpio19};
use crate::hal::gpio::{FunctionSio, FunctionSpi, Pin, PullDown, SioOutput};
use crate::hal::{self, pac};

/// SPI0 with MOSI on GP19 and SCK on GP18, 8-bit frames.
pub type LcdSpi = hal::Spi<
    hal::spi::Enabled,
    pac::SPI0,
    (
        Pin<Gpio19, FunctionSpi, PullDown>,
        Pin<Gpio18, FunctionSpi, PullDown>,
    ),
    8,
>;
/// The LCD's chip select, GP17.
pub type LcdCs = Pin<Gpio17, FunctionSio<SioOutput>, PullDown>;
/// The LCD's data/command pin, GP16.
pub type LcdDc = Pin<Gpio16, FunctionSio<SioOutput>, PullDown>;

/// SPI clock asked for. The SPI block divides the peripheral clock by at
/// least 2: on the RP2040 (125 MHz) this is the fastest it can go, exactly
/// 62.5 MHz; on the RP2350 (150 MHz) the HAL takes the fastest rate at or
/// below it, 37.5 MHz (75 MHz is beyond the ST7789). Lower it (e.g. to
/// 31.25 MHz) if long wires garble the picture.
pub const SPI_HZ: u32 = 62_500_000;
/// SPI mode 3: clock idle high, data sampled on the rising edge (see the
/// module notes about modules without CS).
pub const SPI_MODE: Mode = MODE_3;

// The display knobs. Check them with `mipidsi::TestImage` if colours look
// wrong (see mipidsi's troubleshooting guide).

/// Most 240x240 ST7789 modules are IPS panels that show true colours only
/// with inversion on; if black shows as white, use `ColorInversion::Normal`.
pub const INVERSION: ColorInversion = ColorInversion::Inverted;
/// Subpixel order; if red and blue are swapped, use `ColorOrder::Bgr`.
pub const COLOR_ORDER: ColorOrder = ColorOrder::Rgb;
/// Rotation and mirroring of the picture.
pub const ORIENTATION: Orientation = Orientation::new();
/// Where the 240x240 panel sits in the controller's 240x320 memory: (0, 0)
/// for the default orientation. With a rotated `ORIENTATION` many modules
/// need 80 on one axis: if the picture is shifted, try (0, 80) or (80, 0).
pub const OFFSET: (u16, u16) = (0, 0);
