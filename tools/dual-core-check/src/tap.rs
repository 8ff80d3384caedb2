//! The bus a core steps through: the emulator's own [`Bus`], with the
//! CPU's stores to a few registers seen (and two of them fixed up) on the
//! way.
//!
//! * SPI0 `SSPDR`: every byte the CPU pushes into the transmit FIFO is
//!   recorded with the DC and CS pins' levels at that moment (the LCD
//!   stream; bytes sent by DMA are seen in `machine.rs`).
//! * SPI0 `SSPCR1`: after the CPU's write, the loopback bit (LBM) is set.
//!   rp2040-emu's PL022 only fills the receive FIFO in loopback, and the
//!   HAL's blocking SPI writes wait for a received byte after each one
//!   they send; on the board the LCD's MISO-less wiring receives zeros,
//!   which the HAL discards, so loopback changes nothing the firmware
//!   sees but the wait.
//! * DMA channel aliases: rp2040-emu 0.1.5 swaps which two of them
//!   trigger. On the RP2040, `AL1_WRITE_ADDR` (channel offset 0x18) and
//!   `AL2_TRANS_COUNT` (0x24) only store, and `AL2_WRITE_ADDR_TRIG` (0x2C)
//!   stores and starts the channel; the emulator starts the channel on
//!   0x18 and 0x24 and not on 0x2C, so the transfer rp2040-hal starts
//!   through 0x2C never starts. A store to 0x18 or 0x24 goes to the
//!   register's plain alias (`WRITE_ADDR`, `TRANS_COUNT`) instead; after
//!   a store to 0x2C the channel is started through `MULTI_CHAN_TRIGGER`
//!   (which the emulator models: the channel starts if it is enabled and
//!   has a count).
//! * SysTick `SYST_CSR`: a write that enables SysTick is noted. The
//!   harness's scheduler (`machine.rs`) cannot tick SysTick (the emulator
//!   keeps its timers private), so such a run is refused, not measured
//!   wrong.

use rp2040_emu::Bus;
use rp2040_emu::bus::ppb::Ppb;
use rp2040_emu::bus::{DMA_BASE, SPI0_BASE};
use rp2040_emu::core::{CoreBus, Nvic};

use crate::contention::StepAccesses;

/// SPI0's data register (transmit FIFO on write).
pub const SPI0_DR: u32 = SPI0_BASE + 0x008;
/// SPI0's control register 1 (enable, loopback).
const SPI0_CR1: u32 = SPI0_BASE + 0x004;
/// SPI0's status register.
const SPI0_SR: u32 = SPI0_BASE + 0x00C;
/// `SSPCR1.LBM`: loopback.
const CR1_LBM: u32 = 1 << 0;
/// `SSPCR1.SSE`: the port is enabled.
const CR1_SSE: u32 = 1 << 1;
/// `SSPSR.TNF`: the transmit FIFO has room.
const SR_TNF: u32 = 1 << 1;
/// The SET alias of an RP2040 peripheral register (`addr | 0x2000`).
const ALIAS_SET: u32 = 0x2000;
/// The alias bits of a peripheral address.
const ALIAS_MASK: u32 = 0x3000;
/// DMA channel register blocks: 12 of 0x40 bytes.
const DMA_CHANNELS_END: u32 = DMA_BASE + 12 * 0x40;
/// Offsets in a channel's block: `WRITE_ADDR`, `TRANS_COUNT`, and the
/// aliases rp2040-emu gets wrong.
const WRITE_ADDR: u32 = 0x04;
const TRANS_COUNT: u32 = 0x08;
const AL1_WRITE_ADDR: u32 = 0x18;
const AL2_TRANS_COUNT: u32 = 0x24;
const AL2_WRITE_ADDR_TRIG: u32 = 0x2C;
/// `MULTI_CHAN_TRIGGER`: writing bit N starts channel N.
pub const DMA_MULTI_CHAN_TRIGGER: u32 = DMA_BASE + 0x430;
/// SysTick's control and status register (each core has its own).
const SYST_CSR: u32 = 0xE000_E010;
/// `SYST_CSR.ENABLE`.
const SYST_ENABLE: u32 = 1;
/// GPIO of the LCD's data/command pin (high: data).
pub const PIN_DC: u32 = 16;
/// GPIO of the LCD's chip select (low: selected).
pub const PIN_CS: u32 = 17;

/// A byte pushed into SPI0's transmit FIFO, with the LCD's pins then.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpiByte {
    /// The byte.
    pub byte: u8,
    /// DC was high: a parameter or pixel byte, not a command.
    pub data: bool,
    /// CS was not driven high: the LCD listens.
    pub selected: bool,
}

impl SpiByte {
    /// `byte` with the DC and CS levels the SIO drives now.
    pub fn with_pins(bus: &Bus, byte: u8) -> Self {
        let driven_high = |pin: u32| {
            let mask = 1 << pin;
            bus.sio.gpio_oe & mask != 0 && bus.sio.gpio_out & mask != 0
        };
        Self {
            byte,
            data: bus.sio.gpio_out & (1 << PIN_DC) != 0,
            selected: !driven_high(PIN_CS),
        }
    }
}

/// What the CPU's stores did to the watched registers during one step.
#[derive(Debug, Default)]
pub struct TapLog {
    /// Bytes the CPU pushed into SPI0's transmit FIFO, in order.
    pub spi: Vec<SpiByte>,
    /// Channels started through `AL2_WRITE_ADDR_TRIG` (the workaround).
    pub dma_triggers: u64,
    /// Stores to `AL1_WRITE_ADDR` or `AL2_TRANS_COUNT` kept from
    /// starting their channel (the workaround).
    pub dma_redirects: u64,
    /// Writes to `SSPCR1` after which loopback was set (the workaround).
    pub loopback_sets: u64,
    /// A core enabled SysTick, which the harness cannot run.
    pub systick_enabled: bool,
    /// With the `contended` interleave, what the step touched (its
    /// instruction's address and its loads and stores); `None`: not
    /// recorded.
    pub accesses: Option<StepAccesses>,
}

/// Which watched register a store goes to.
#[derive(Debug, PartialEq, Eq)]
enum Watched {
    SpiData,
    SpiControl1,
    /// `AL2_WRITE_ADDR_TRIG` of this channel.
    DmaWriteAddrTrigger(u32),
    /// A non-triggering alias the emulator triggers on: store to this
    /// address (the plain alias) instead.
    DmaPlainAlias(u32),
    SysTickControl,
}

/// The watched register `addr` is (any alias), if it is one.
#[inline]
fn watched(addr: u32) -> Option<Watched> {
    if addr >> 28 != 0x4 && addr >> 28 != 0x5 {
        return (addr == SYST_CSR).then_some(Watched::SysTickControl);
    }
    let canonical = addr & !ALIAS_MASK;
    match canonical {
        SPI0_DR => Some(Watched::SpiData),
        SPI0_CR1 => Some(Watched::SpiControl1),
        DMA_BASE..DMA_CHANNELS_END => match canonical & 0x3F {
            AL2_WRITE_ADDR_TRIG => {
                Some(Watched::DmaWriteAddrTrigger((canonical - DMA_BASE) / 0x40))
            }
            AL1_WRITE_ADDR => Some(Watched::DmaPlainAlias(addr - AL1_WRITE_ADDR + WRITE_ADDR)),
            AL2_TRANS_COUNT => Some(Watched::DmaPlainAlias(addr - AL2_TRANS_COUNT + TRANS_COUNT)),
            _ => None,
        },
        _ => None,
    }
}

/// The emulator's bus with the CPU's stores to the watched registers
/// logged and fixed up; everything else passes straight through.
pub struct Tap<'a> {
    bus: &'a mut Bus,
    log: &'a mut TapLog,
    /// The instruction's own halfwords may still be read (its fetch, on
    /// the emulator's first decode of it): no load or store came yet.
    fetching: bool,
}

impl<'a> Tap<'a> {
    /// Wraps `bus` for one core step, logging into `log`.
    pub fn new(bus: &'a mut Bus, log: &'a mut TapLog) -> Self {
        Self {
            bus,
            log,
            fetching: false,
        }
    }

    /// Records a load or store of `addr` when accesses are recorded; a
    /// 16-bit read of the instruction's own halfwords before any load or
    /// store (`fetch`) is its fetch, which the bus model charges by
    /// address, and is not recorded.
    #[inline(always)]
    fn note(&mut self, addr: u32, fetch: bool) {
        if let Some(accesses) = &mut self.log.accesses {
            if fetch
                && self.fetching
                && accesses
                    .pc
                    .is_some_and(|pc| addr == pc || addr == pc.wrapping_add(2))
            {
                return;
            }
            self.fetching = false;
            accesses.data.push(addr);
        }
    }

    /// Runs `store` (the CPU's store, given the bus and the address to
    /// store to) to the watched register `target` at `addr`, with the
    /// register's bookkeeping around it. `low_byte` is the stored value's
    /// low byte.
    #[cold]
    fn watched_store(
        &mut self,
        target: Watched,
        addr: u32,
        low_byte: u8,
        store: impl FnOnce(&mut Bus, u32),
    ) {
        match target {
            Watched::SpiData => {
                // The PL022 drops a byte while disabled or with its FIFO
                // full: record only what it takes.
                let enabled = self.bus.read32(SPI0_CR1) & CR1_SSE != 0;
                let room = self.bus.read32(SPI0_SR) & SR_TNF != 0;
                if enabled && room {
                    self.log.spi.push(SpiByte::with_pins(self.bus, low_byte));
                }
                store(self.bus, addr);
            }
            Watched::SpiControl1 => {
                store(self.bus, addr);
                if self.bus.read32(SPI0_CR1) & CR1_LBM == 0 {
                    self.bus.write32(SPI0_CR1 | ALIAS_SET, CR1_LBM);
                    self.log.loopback_sets += 1;
                }
            }
            Watched::DmaWriteAddrTrigger(channel) => {
                store(self.bus, addr);
                self.bus.write32(DMA_MULTI_CHAN_TRIGGER, 1 << channel);
                self.log.dma_triggers += 1;
            }
            Watched::DmaPlainAlias(plain) => {
                store(self.bus, plain);
                self.log.dma_redirects += 1;
            }
            Watched::SysTickControl => {
                store(self.bus, addr);
                if u32::from(low_byte) & SYST_ENABLE != 0 {
                    self.log.systick_enabled = true;
                }
            }
        }
    }
}

impl CoreBus for Tap<'_> {
    #[inline(always)]
    fn read8(&mut self, addr: u32) -> u8 {
        self.note(addr, false);
        self.bus.read8(addr)
    }
    #[inline(always)]
    fn read16(&mut self, addr: u32) -> u16 {
        self.note(addr, true);
        self.bus.read16(addr)
    }
    #[inline(always)]
    fn read32(&mut self, addr: u32) -> u32 {
        self.note(addr, false);
        self.bus.read32(addr)
    }

    #[inline(always)]
    fn write8(&mut self, addr: u32, val: u8) {
        self.note(addr, false);
        match watched(addr) {
            None => self.bus.write8(addr, val),
            Some(target) => self.watched_store(target, addr, val, |bus, a| bus.write8(a, val)),
        }
    }
    #[inline(always)]
    fn write16(&mut self, addr: u32, val: u16) {
        self.note(addr, false);
        match watched(addr) {
            None => self.bus.write16(addr, val),
            Some(target) => {
                self.watched_store(target, addr, val as u8, |bus, a| bus.write16(a, val))
            }
        }
    }
    #[inline(always)]
    fn write32(&mut self, addr: u32, val: u32) {
        self.note(addr, false);
        match watched(addr) {
            None => self.bus.write32(addr, val),
            Some(target) => {
                self.watched_store(target, addr, val as u8, |bus, a| bus.write32(a, val))
            }
        }
    }

    #[inline(always)]
    fn set_active_pc(&mut self, pc: u32) {
        if let Some(accesses) = &mut self.log.accesses {
            accesses.pc = Some(pc);
            self.fetching = true;
        }
        self.bus.set_active_pc(pc)
    }
    #[inline(always)]
    fn bus_fault(&self) -> bool {
        self.bus.bus_fault()
    }
    #[inline(always)]
    fn bus_fault_addr(&self) -> u32 {
        self.bus.bus_fault_addr()
    }
    #[inline(always)]
    fn clear_bus_fault(&mut self) {
        self.bus.clear_bus_fault()
    }
    #[inline(always)]
    fn ppb(&self, core: usize) -> &Ppb {
        &self.bus.ppb[core]
    }
    #[inline(always)]
    fn ppb_mut(&mut self, core: usize) -> &mut Ppb {
        &mut self.bus.ppb[core]
    }
    #[inline(always)]
    fn nvic(&self, core: usize) -> &Nvic {
        &self.bus.nvics[core]
    }
    #[inline(always)]
    fn nvic_mut(&mut self, core: usize) -> &mut Nvic {
        &mut self.bus.nvics[core]
    }
    #[inline(always)]
    fn active_core(&self) -> usize {
        self.bus.active_core()
    }
    #[inline(always)]
    fn event_flag(&self, core: usize) -> bool {
        <Bus as CoreBus>::event_flag(self.bus, core)
    }
    #[inline(always)]
    fn consume_event_flag(&mut self, core: usize) -> bool {
        <Bus as CoreBus>::consume_event_flag(self.bus, core)
    }
    #[inline(always)]
    fn set_wfe_waiting(&mut self, core: usize, val: bool) {
        <Bus as CoreBus>::set_wfe_waiting(self.bus, core, val)
    }
    #[inline(always)]
    fn signal_sev(&mut self) {
        self.bus.signal_sev()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn watches_its_registers_through_any_alias() {
        assert_eq!(watched(0x4003_C008), Some(Watched::SpiData));
        assert_eq!(watched(0x4003_E008), Some(Watched::SpiData), "SET alias");
        assert_eq!(watched(0x4003_C004), Some(Watched::SpiControl1));
        assert_eq!(watched(0x4004_0008), None, "SPI1");
        assert_eq!(watched(0xE000_E010), Some(Watched::SysTickControl));
        assert_eq!(watched(0xE000_E014), None);
        assert_eq!(watched(0x2000_002C), None);
    }

    #[test]
    fn fixes_the_dma_trigger_aliases() {
        assert_eq!(watched(0x5000_002C), Some(Watched::DmaWriteAddrTrigger(0)));
        assert_eq!(watched(0x5000_006C), Some(Watched::DmaWriteAddrTrigger(1)));
        assert_eq!(watched(0x5000_02EC), Some(Watched::DmaWriteAddrTrigger(11)));
        assert_eq!(
            watched(0x5000_0058),
            Some(Watched::DmaPlainAlias(0x5000_0044))
        );
        assert_eq!(
            watched(0x5000_2064),
            Some(Watched::DmaPlainAlias(0x5000_2048))
        );
        // The aliases the emulator gets right pass through.
        for offset in [
            0x00, 0x04, 0x08, 0x0C, 0x10, 0x14, 0x1C, 0x20, 0x28, 0x30, 0x3C,
        ] {
            assert_eq!(watched(0x5000_0040 + offset), None, "offset {offset:#x}");
        }
        assert_eq!(watched(0x5000_032C), None, "past the channels");
    }
}
