//! Board set-up: clocks, pins, SPI and the ST7789 LCD, brought up with
//! the wiring and display knobs of [`crate::wiring`].

use core::convert::Infallible;

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_hal::digital::{OutputPin, PinState};
use embedded_hal::spi::{Operation, SpiBus, SpiDevice};
use mipidsi::Builder;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use static_cell::ConstStaticCell;

use crate::Fault;
use crate::hal::Clock;
use crate::hal::dma::DMAExt;
use crate::hal::fugit::RateExtU32;
use crate::hal::gpio::{FunctionSpi, OutputDriveStrength, OutputSlewRate, Pins};
use crate::hal::{self, pac};
use crate::lcd::LcdRows;
use crate::sizes::{HEIGHT, SPI_BUFFER, WIDTH};
use crate::wiring::{COLOR_ORDER, INVERSION, LcdCs, LcdSpi, OFFSET, ORIENTATION, SPI_HZ, SPI_MODE};

/// The SPI bus and chip select as one SPI device, for mipidsi's start-up;
/// unlike embedded-hal-bus' `ExclusiveDevice`, it gives both back
/// ([`Self::into_parts`]) for the DMA row stream.
struct LcdDevice {
    spi: LcdSpi,
    cs: LcdCs,
}

impl LcdDevice {
    fn into_parts(self) -> (LcdSpi, LcdCs) {
        (self.spi, self.cs)
    }
}

impl embedded_hal::spi::ErrorType for LcdDevice {
    type Error = Infallible;
}

impl SpiDevice for LcdDevice {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), Infallible> {
        self.cs.set_low()?;
        for op in operations {
            match op {
                Operation::Write(bytes) => self.spi.write(bytes)?,
                Operation::Transfer(read, write) => self.spi.transfer(read, write)?,
                Operation::TransferInPlace(bytes) => self.spi.transfer_in_place(bytes)?,
                Operation::Read(bytes) => self.spi.read(bytes)?,
                Operation::DelayNs(ns) => {
                    self.spi.flush()?;
                    // 125 cycles a microsecond at 125 MHz (RP2040)...
                    #[cfg(feature = "rp2040")]
                    cortex_m::asm::delay(ns.div_ceil(8));
                    // ...150 at 150 MHz (RP2350).
                    #[cfg(feature = "rp2350")]
                    cortex_m::asm::delay((u64::from(*ns) * 150).div_ceil(1000) as u32);
                }
            }
        }
        self.spi.flush()?;
        self.cs.set_high()
    }
}

/// The microsecond timer.
#[cfg(feature = "rp2040")]
pub type Timer = hal::Timer;
/// The microsecond timer (the RP2350 has two; this is TIMER0).
#[cfg(feature = "rp2350")]
pub type Timer = hal::Timer<hal::timer::CopyableTimer0>;

/// Crystal on the Pico and the Pico 2.
const XTAL_HZ: u32 = 12_000_000;
/// mipidsi's SPI buffer: one row of Rgb565, so each row the renderer
/// sends goes out in one SPI write. In `.bss`, not on the stack.
static SPI_BUF: ConstStaticCell<[u8; SPI_BUFFER]> = ConstStaticCell::new([0; SPI_BUFFER]);

/// What [`init`] returns: the row stream and the timer (a microsecond
/// clock and delay).
#[cfg(not(feature = "dual-core"))]
pub type Board = (LcdRows, Timer);
/// What [`init`] returns: the row stream, the timer (a microsecond clock
/// and delay) and core 1, waiting for jobs (feature `dual-core`).
#[cfg(feature = "dual-core")]
pub type Board = (LcdRows, Timer, crate::dual::Core1);

/// Brings up clocks, the timer, SPI and the LCD (reset, initialised by
/// mipidsi, cleared to black, backlight on), then hands SPI0, CS, DC and
/// DMA channel 0 to the row stream (and, with `dual-core`, starts core 1).
pub fn init() -> Result<Board, Fault> {
    let mut pac = pac::Peripherals::take().ok_or(Fault::Peripherals)?;
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    // System and peripheral clocks from the 12 MHz crystal: 125 MHz on the
    // RP2040, 150 MHz on the RP2350.
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .map_err(|_| Fault::Clocks)?;
    #[cfg(feature = "rp2040")]
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    #[cfg(feature = "rp2350")]
    let mut timer = hal::Timer::new_timer0(pac.TIMER0, &mut pac.RESETS, &clocks);
    let sio = hal::Sio::new(pac.SIO);
    let pins = Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );

    // ---- Pinout: the only place to change pins (update the table above).
    let spi_block = pac.SPI0;
    let sck = pins.gpio18;
    let mosi = pins.gpio19;
    let cs = pins.gpio17;
    let dc = pins.gpio16;
    let rst = pins.gpio20;
    let backlight = pins.gpio21;
    // ----

    let mut sck = sck.into_function::<FunctionSpi>();
    let mut mosi = mosi.into_function::<FunctionSpi>();
    // Fast edges and strong drive for 62.5 MHz over jumper wires.
    sck.set_slew_rate(OutputSlewRate::Fast);
    sck.set_drive_strength(OutputDriveStrength::TwelveMilliAmps);
    mosi.set_slew_rate(OutputSlewRate::Fast);
    mosi.set_drive_strength(OutputDriveStrength::TwelveMilliAmps);
    let spi = hal::Spi::<_, _, _, 8>::new(spi_block, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        SPI_MODE,
    );
    let cs = cs.into_push_pull_output_in_state(PinState::High);
    let dc = dc.into_push_pull_output_in_state(PinState::Low);
    let rst = rst.into_push_pull_output_in_state(PinState::High);
    let mut backlight = backlight.into_push_pull_output_in_state(PinState::Low);

    let device = LcdDevice { spi, cs };
    let buffer = SPI_BUF.try_take().ok_or(Fault::Display)?;
    let mut display = Builder::new(ST7789, SpiInterface::new(device, dc, buffer))
        .display_size(WIDTH, HEIGHT)
        .display_offset(OFFSET.0, OFFSET.1)
        .orientation(ORIENTATION)
        .invert_colors(INVERSION)
        .color_order(COLOR_ORDER)
        .reset_pin(rst)
        .init(&mut timer)
        .map_err(|_| Fault::Display)?;
    // Black before the backlight comes on, not the controller's noise.
    display.clear(Rgb565::BLACK).map_err(|_| Fault::Display)?;
    // The pin keeps its level when `backlight` goes out of scope.
    backlight.set_high().map_err(|_| Fault::Display)?;
    // mipidsi has set the panel up; from now on rows go out by DMA.
    let (interface, _model, _reset) = display.release();
    let (device, dc) = interface.release();
    let (spi, cs) = device.into_parts();
    let dma = pac.DMA.split(&mut pac.RESETS);
    let rows = LcdRows::new(spi, cs, dc, dma.ch0, dma.ch1).ok_or(Fault::Display)?;
    #[cfg(not(feature = "dual-core"))]
    return Ok((rows, timer));
    #[cfg(feature = "dual-core")]
    Ok((
        rows,
        timer,
        crate::dual::Core1::start(&mut pac.PSM, &mut pac.PPB, sio.fifo)?,
    ))
}
