//! The emulated RP2040, stepped one quantum at a time by this harness.
//!
//! rp2040-emu's own stepper (`Emulator::step`) hands its cores the
//! concrete `Bus`, so nothing outside the crate can see a store as it
//! happens. This scheduler does what that stepper does, through the
//! crate's public parts, with each core stepping through [`Tap`] instead:
//!
//! 1. The cores run until the quantum's cycles are used, interleaved in
//!    one of three ways ([`Interleave`]): the crate's *lockstep*, where
//!    cores 0 and 1 each execute one instruction (or take an exception)
//!    per round, core 0 first, and the master clock advances by the
//!    longer of the two; *independent*, where each core keeps its own
//!    time and the one behind runs next, so neither waits for the other's
//!    instructions; or *contended*, independent with each core waiting
//!    for a bus slave the other holds (`contention.rs`). After a core-0 step the SIO's multicore-launch
//!    handshake is checked and core 1 started when it completes. A halted
//!    core or one parked in WFE does not run.
//! 2. At the end of the quantum the peripherals advance by its cycles
//!    (the TIMER first; then UART, SPI, I2C, ADC, PWM, and one DMA
//!    transfer, as in the crate), the GPIO inputs follow the SIO outputs,
//!    and the interrupt lines are latched into both cores' NVICs (from
//!    the DMA, TIMER and SPI interrupt status registers: the crate's own
//!    pending-line word is private). Then WFE and WFI sleepers wake as in
//!    the crate.
//!
//! Differences from the crate's stepper: when both cores sleep, time
//! still passes (a quantum at a time, so DMA and SPI go on; the crate
//! only jumps to a TIMER alarm, and stops without one); PIO blocks and
//! SysTick are not stepped (the firmware uses neither; a run that enables
//! them is refused by the harness).
//!
//! The DMA moves at most one word a quantum; one written to SPI0's data
//! register is read back from its source to log the byte sent.

use rp2040_emu::bus::{DMA_BASE, SPI0_BASE, SPI1_BASE, TIMER_BASE};
use rp2040_emu::dma::NUM_CHANNELS;
use rp2040_emu::irq::{IRQ_DMA_IRQ_0, IRQ_DMA_IRQ_1, IRQ_SPI0_IRQ, IRQ_SPI1_IRQ};
use rp2040_emu::{Bus, Config, CortexM0Plus, Emulator, EmulatorBuilder};

use crate::contention::{BusModel, Stalls, StepAccesses};
use crate::tap::{SPI0_DR, SpiByte, Tap, TapLog};

/// The vector table's offset in flash, after the 256 bytes of boot2.
pub const VECTOR_TABLE_OFFSET: u32 = 0x100;
/// DMA `INTS0` and `INTS1`: channels interrupting on `DMA_IRQ_0` / `_1`.
const DMA_INTS0: u32 = DMA_BASE + 0x40C;
const DMA_INTS1: u32 = DMA_BASE + 0x41C;
/// TIMER `INTS`: alarms 0..3 interrupting on `TIMER_IRQ_0..3`.
const TIMER_INTS: u32 = TIMER_BASE + 0x40;
/// The PL022's masked interrupt status register.
const SPI_MIS: u32 = 0x01C;
/// GPIOs the RP2040 has (bits of the SIO's GPIO registers).
const GPIO_MASK: u32 = 0x3FFF_FFFF;

/// When something happened: the master clock and each core's own cycle
/// count.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stamp {
    /// Master-clock cycles since reset.
    pub cycle: u64,
    /// Cycles each core has spent executing (0 for a core never started).
    pub core_cycles: [u64; 2],
}

/// How the workarounds were exercised, for the report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Bytes the CPU pushed into SPI0's transmit FIFO.
    pub cpu_spi_bytes: u64,
    /// Bytes the DMA pushed into SPI0's transmit FIFO.
    pub dma_spi_bytes: u64,
    /// DMA channels started through `AL2_WRITE_ADDR_TRIG`.
    pub dma_triggers: u64,
    /// Stores to DMA aliases that must not start their channel, redirected.
    pub dma_redirects: u64,
    /// Times loopback was set after the CPU wrote `SSPCR1`.
    pub loopback_sets: u64,
    /// Quanta in which both cores slept.
    pub idle_quanta: u64,
    /// Cycles each core spent waiting for the other's longer instruction
    /// in rounds where both ran (the interleave's lockstep: the master
    /// clock takes the longer of the two).
    pub lockstep_wait: [u64; 2],
    /// Cycles the cores waited for a bus slave the other held (the
    /// contended interleave).
    pub contention: Stalls,
}

/// How the two cores' instructions share the master clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interleave {
    /// rp2040-emu's own model: one instruction of each core a round, the
    /// clock advancing by the longer (a core waits for the other's longer
    /// instruction).
    Lockstep,
    /// Each core keeps its own time and only the quantum boundaries
    /// synchronise them, as two cores sharing a bus without contention.
    Independent,
    /// As `Independent`, with each core waiting a cycle whenever it
    /// addresses a bus slave (an SRAM bank, the XIP cache, a peripheral
    /// bridge) the other holds in that cycle (`contention.rs`).
    Contended,
}

/// The emulator and the bytes it has sent the LCD since last drained.
pub struct Machine {
    emu: Emulator,
    quantum: u64,
    interleave: Interleave,
    /// Cycles each core's last instruction ran past the last quantum's
    /// end (independent interleave).
    ahead: [u64; 2],
    log: TapLog,
    /// The RP2040's bus slaves under two cores (contended interleave).
    bus_model: BusModel,
    /// The buffer a step's accesses are recorded in, kept between steps.
    accesses: StepAccesses,
    sent: Vec<(Stamp, SpiByte)>,
    counters: Counters,
}

impl Machine {
    /// An RP2040 with the boot ROM `rom`, `flash` at the XIP base and
    /// `sram` images loaded, booted as boot2 would (SP, VTOR and PC from
    /// the vector table at flash offset 0x100; core 1 halted until
    /// launched), stepping `quantum` cycles at a time with the cores
    /// interleaved as `interleave` says.
    pub fn new(
        rom: &[u8],
        flash: &[u8],
        sram: &[(u32, Vec<u8>)],
        quantum: u32,
        interleave: Interleave,
    ) -> Self {
        // The builder only fails for the threaded model.
        let mut emu = EmulatorBuilder::new(Config::default())
            .step_quantum(quantum)
            .build()
            .unwrap_or_else(|_| Emulator::new(Config::default()));
        emu.load_bootrom(rom);
        emu.load_flash(flash);
        emu.reset();
        for (address, bytes) in sram {
            emu.load_image(*address, bytes);
        }
        emu.direct_boot_from_flash(VECTOR_TABLE_OFFSET);
        Self {
            emu,
            quantum: u64::from(quantum.max(1)),
            interleave,
            ahead: [0; 2],
            log: TapLog::default(),
            bus_model: BusModel::default(),
            accesses: StepAccesses::default(),
            sent: Vec::new(),
            counters: Counters::default(),
        }
    }

    /// The master clock and the cores' cycle counts now.
    pub fn stamp(&self) -> Stamp {
        stamp(&self.emu)
    }

    /// The workaround and traffic counters so far.
    pub fn counters(&self) -> Counters {
        Counters {
            dma_triggers: self.log.dma_triggers,
            dma_redirects: self.log.dma_redirects,
            loopback_sets: self.log.loopback_sets,
            contention: self.bus_model.stalls(),
            ..self.counters
        }
    }

    /// A core enabled SysTick (which this scheduler does not tick).
    pub fn systick_enabled(&self) -> bool {
        self.log.systick_enabled
    }

    /// A PIO state machine runs (this scheduler does not step PIO).
    pub fn pio_active(&self) -> bool {
        !self.emu.bus.pio_all_idle()
    }

    /// The system clock the firmware has set up, in Hz.
    pub fn sys_clk_hz(&self) -> u32 {
        self.emu.bus.sys_clk_hz()
    }

    /// Core `id`.
    pub fn core(&self, id: usize) -> &CortexM0Plus {
        &self.emu.cores[id]
    }

    /// The word at `address` (SRAM, flash or ROM), without side effects.
    pub fn peek32(&self, address: u32) -> u32 {
        self.emu.bus.peek32(address)
    }

    /// The bytes sent to SPI0 since the last call, in order, stamped.
    pub fn drain_sent(&mut self) -> std::vec::Drain<'_, (Stamp, SpiByte)> {
        self.sent.drain(..)
    }

    /// Runs one quantum: see the module notes.
    pub fn step_quantum(&mut self) {
        let start = self.emu.clock.cycles;
        match self.interleave {
            Interleave::Lockstep => self.run_cores_lockstep(),
            Interleave::Independent | Interleave::Contended => self.run_cores_independent(),
        }
        let emu = &mut self.emu;
        let mut consumed = emu.clock.cycles - start;
        if consumed == 0 {
            // Both cores asleep: the chip's clock runs on.
            consumed = self.quantum;
            emu.clock.cycles += consumed;
            self.counters.idle_quanta += 1;
        }
        // The bus's own clock (the TIMER reads it) follows the master one.
        emu.bus.advance_lazy_scheduled(consumed);
        let dma_before = DmaSnapshot::take(&emu.bus);
        emu.bus.tick_peripherals(consumed as u32);
        if let Some(byte) = dma_before.and_then(|s| s.spi_byte(&emu.bus)) {
            self.counters.dma_spi_bytes += 1;
            self.sent.push((stamp(emu), byte));
        }
        emu.bus.gpio_in = merged_gpio_in(&emu.bus);
        latch_interrupts(&mut emu.bus);
        wake_sleepers(emu);
    }

    /// The crate's interleave: rounds of one instruction a core, the
    /// master clock advancing by the longer, until the quantum is used.
    fn run_cores_lockstep(&mut self) {
        let target = self.emu.clock.cycles + self.quantum;
        while self.emu.clock.cycles < target {
            let before = stamp(&self.emu);
            let c0 = self.step_core(0, before);
            let c1 = self.step_core(1, before);
            if c0 == 0 && c1 == 0 {
                break;
            }
            let round = c0.max(c1);
            if c0 != 0 && c1 != 0 {
                self.counters.lockstep_wait[0] += round - c0;
                self.counters.lockstep_wait[1] += round - c1;
            }
            self.emu.clock.cycles += round;
        }
    }

    /// Each core on its own clock: the runnable core that is behind runs
    /// next, until both reach the quantum's end (an instruction that
    /// crosses it is paid for in the next quantum).
    fn run_cores_independent(&mut self) {
        let start = self.emu.clock.cycles;
        let target = start + self.quantum;
        let mut local = [start + self.ahead[0], start + self.ahead[1]];
        let mut ran = false;
        loop {
            let next = (0..2)
                .filter(|&id| runnable(&self.emu, id) && local[id] < target)
                .min_by_key(|&id| local[id]);
            let Some(id) = next else {
                break;
            };
            let mut at = stamp(&self.emu);
            at.cycle = local[id];
            let core1_was_halted = self.emu.cores[1].is_halted();
            let cycles = self.step_core(id, at);
            local[id] += cycles;
            if core1_was_halted && !self.emu.cores[1].is_halted() {
                // Launched by core 0's last instruction: it starts now.
                local[1] = local[0];
            }
            ran |= cycles != 0;
        }
        let mut busy = ran;
        for (id, (ahead, &time)) in self.ahead.iter_mut().zip(&local).enumerate() {
            let running = runnable(&self.emu, id);
            busy |= running;
            *ahead = if running {
                time.saturating_sub(target)
            } else {
                0
            };
        }
        if busy {
            self.emu.clock.cycles = target;
        }
    }

    /// Steps core `id` once if it can run (through [`Tap`]); bytes it
    /// sends are stamped `at`. Returns the cycles it took (0: it could not
    /// run), with the contended interleave's wait for the bus.
    fn step_core(&mut self, id: usize, at: Stamp) -> u64 {
        let emu = &mut self.emu;
        if !runnable(emu, id) {
            if id == 1 {
                emu.bus.end_core1_step();
            }
            return 0;
        }
        emu.bus.set_active_core(id);
        if id == 1 {
            emu.bus.begin_core1_step();
        }
        if self.interleave == Interleave::Contended {
            let mut accesses = std::mem::take(&mut self.accesses);
            accesses.pc = None;
            accesses.data.clear();
            self.log.accesses = Some(accesses);
        }
        let mut cycles = u64::from(emu.cores[id].step(&mut Tap::new(&mut emu.bus, &mut self.log)));
        if let Some(accesses) = self.log.accesses.take() {
            if cycles != 0 {
                cycles += self.bus_model.charge(id, at.cycle, cycles, &accesses);
            }
            self.accesses = accesses;
        }
        drain_decode_invalidations(&mut emu.bus, &mut emu.cores);
        if id == 0 {
            launch_core1(emu);
        } else {
            emu.bus.end_core1_step();
        }
        if !self.log.spi.is_empty() {
            self.counters.cpu_spi_bytes += self.log.spi.len() as u64;
            self.sent
                .extend(self.log.spi.drain(..).map(|byte| (at, byte)));
        }
        cycles
    }
}

/// The master clock and the cores' cycle counts of `emu`.
fn stamp(emu: &Emulator) -> Stamp {
    Stamp {
        cycle: emu.clock.cycles,
        core_cycles: [emu.cores[0].cycles, emu.cores[1].cycles],
    }
}

/// Core `id` is neither halted nor parked in WFE.
fn runnable(emu: &Emulator, id: usize) -> bool {
    !emu.cores[id].is_halted() && !emu.bus.wfe_waiting[id]
}

/// Applies the decoded-instruction cache invalidations the last step's
/// stores queued: addresses to the core that ran, whole regions to both.
fn drain_decode_invalidations(bus: &mut Bus, cores: &mut [CortexM0Plus; 2]) {
    if !bus.pending_cache_invalidations.is_empty() {
        let active = bus.active_core();
        cores[active].invalidate_decode_cache_entries(&bus.pending_cache_invalidations);
        bus.pending_cache_invalidations.clear();
    }
    if bus.pending_invalidation_regions != 0 {
        let regions = std::mem::take(&mut bus.pending_invalidation_regions);
        cores[0].invalidate_decode_cache_regions(regions);
        cores[1].invalidate_decode_cache_regions(regions);
    }
}

/// Starts core 1 if core 0 has just completed the launch handshake
/// through the SIO FIFO (VTOR, stack pointer, entry point), as the boot
/// ROM's core-1 wait loop would.
fn launch_core1(emu: &mut Emulator) {
    let Some(launch) = emu.bus.sio.take_pending_launch() else {
        return;
    };
    emu.bus.ppb[1].vtor = launch.vtor;
    let core1 = &mut emu.cores[1];
    core1.regs.msp = launch.sp;
    core1.regs.r[13] = launch.sp;
    core1.regs.set_pc(launch.entry & !1);
    core1.reset_control_for_launch();
    emu.bus.event_flag[1] = false;
    emu.wake_core1();
}

/// What GPIO_IN reads: the pins the SIO drives (no PIO, no external
/// drivers but the bus's override mask).
fn merged_gpio_in(bus: &Bus) -> u32 {
    let driven = bus.sio.gpio_out & bus.sio.gpio_oe & GPIO_MASK;
    let mask = bus.external_gpio_in_mask;
    (driven & !mask) | (bus.external_gpio_in_override & mask)
}

/// Latches the asserted interrupt lines into both cores' NVICs (each
/// core takes only those it enables).
fn latch_interrupts(bus: &mut Bus) {
    let mut lines = bus.read32(TIMER_INTS) & 0xF;
    for (register, irq) in [
        (DMA_INTS0, IRQ_DMA_IRQ_0),
        (DMA_INTS1, IRQ_DMA_IRQ_1),
        (SPI0_BASE + SPI_MIS, IRQ_SPI0_IRQ),
        (SPI1_BASE + SPI_MIS, IRQ_SPI1_IRQ),
    ] {
        if bus.read32(register) != 0 {
            lines |= 1 << irq;
        }
    }
    while lines != 0 {
        let irq = lines.trailing_zeros() as u8;
        lines &= lines - 1;
        bus.nvics[0].set_pending(irq);
        bus.nvics[1].set_pending(irq);
    }
}

/// Wakes a core parked in WFE with an event latched, and a halted core
/// (WFI) with an enabled interrupt pending.
fn wake_sleepers(emu: &mut Emulator) {
    for id in 0..2 {
        if emu.bus.wfe_waiting[id] && emu.bus.event_flag[id] {
            emu.bus.event_flag[id] = false;
            emu.bus.wfe_waiting[id] = false;
        }
        if emu.cores[id].is_halted() && emu.bus.nvics[id].pending_and_enabled() != 0 {
            emu.cores[id].wake();
        }
    }
}

/// The DMA channels' progress before the peripherals tick, to tell which
/// one moved a word and what it read.
struct DmaSnapshot {
    issued: [u64; NUM_CHANNELS],
    read_addr: [u32; NUM_CHANNELS],
    write_addr: [u32; NUM_CHANNELS],
}

impl DmaSnapshot {
    /// The channels' state, or `None` when none is busy.
    fn take(bus: &Bus) -> Option<Self> {
        if !(0..NUM_CHANNELS).any(|i| bus.dma_channel(i).busy) {
            return None;
        }
        let mut snapshot = Self {
            issued: [0; NUM_CHANNELS],
            read_addr: [0; NUM_CHANNELS],
            write_addr: [0; NUM_CHANNELS],
        };
        for i in 0..NUM_CHANNELS {
            let channel = bus.dma_channel(i);
            snapshot.issued[i] = channel.transfers_issued;
            snapshot.read_addr[i] = channel.read_addr;
            snapshot.write_addr[i] = channel.write_addr;
        }
        Some(snapshot)
    }

    /// The byte a channel has written to SPI0's data register since the
    /// snapshot: the low byte of the word it read (little-endian, so the
    /// byte at its read address), with the LCD's pins now.
    fn spi_byte(&self, bus: &Bus) -> Option<SpiByte> {
        let channel = (0..NUM_CHANNELS).find(|&i| {
            bus.dma_channel(i).transfers_issued != self.issued[i]
                && self.write_addr[i] & !0x3000 == SPI0_DR
        })?;
        let address = self.read_addr[channel];
        let word = bus.peek32(address & !3);
        Some(SpiByte::with_pins(bus, (word >> (8 * (address & 3))) as u8))
    }
}
