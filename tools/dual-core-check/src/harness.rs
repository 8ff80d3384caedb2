//! One firmware run: boot it on the emulated RP2040, feed what it sends
//! SPI0 to the ST7789 model, and collect whole frames until enough are
//! in, the firmware fails, or the cycle limit is reached.

use std::time::{Duration, Instant};

use crate::firmware::Firmware;
use crate::machine::{Counters, Interleave, Machine, Stamp};
use crate::st7789::{Frame, St7789};

/// Cycles between checks for a fault, a panic or an unsupported block.
const CHECK_EVERY: u64 = 1 << 20;

/// How to run.
#[derive(Debug, Clone, Copy)]
pub struct RunOptions {
    /// Frames wanted after the start-up clear (frame 0).
    pub frames: usize,
    /// Cycles per scheduling quantum.
    pub quantum: u32,
    /// How the cores share the master clock.
    pub interleave: Interleave,
    /// Master-clock cycles after which the run gives up.
    pub max_cycles: u64,
}

/// Why the run stopped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Stop {
    /// All the frames wanted are in.
    Done,
    /// The cycle limit was reached first.
    CycleLimit,
    /// The firmware set `FAULT` (its start-up failed).
    Fault(u32),
    /// A core is in its HardFault handler.
    HardFault { core: usize, pc: u32 },
    /// A core is spinning in a panic function.
    Panic { core: usize, pc: u32 },
    /// The firmware uses a block this harness does not step.
    Unsupported(&'static str),
}

/// A whole frame, stamped at its start and at the next one's.
pub type FrameRecord = Frame<Stamp>;

/// Master-clock cycles from a frame's start to the next one's.
pub fn period(frame: &FrameRecord) -> u64 {
    frame.end.cycle.saturating_sub(frame.start.cycle)
}

/// Cycles each core executed over a frame's period.
pub fn core_cycles(frame: &FrameRecord) -> [u64; 2] {
    let (a, b) = (frame.start.core_cycles, frame.end.core_cycles);
    [b[0].saturating_sub(a[0]), b[1].saturating_sub(a[1])]
}

/// What a run produced.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Whole frames, in order from frame 0.
    pub frames: Vec<FrameRecord>,
    /// The start-up commands the LCD received.
    pub startup_commands: Vec<u8>,
    /// Why the run stopped.
    pub stop: Stop,
    /// `FAULT` at the end, if the ELF keeps it.
    pub fault: Option<u32>,
    /// `FRAMES` at the end, if kept.
    pub frames_static: Option<u32>,
    /// `FRAME_US` at the end, if kept.
    pub frame_us: Option<u32>,
    /// `CORE1_HIGH_WATER_BYTES` at the end, if kept.
    pub core1_stack: Option<u32>,
    /// Master-clock cycles emulated.
    pub cycles: u64,
    /// The system clock at the end, in Hz.
    pub sys_clk_hz: u32,
    /// Host time the run took.
    pub wall: Duration,
    /// How the harness's workarounds were exercised.
    pub counters: Counters,
}

/// Runs `firmware` with the boot ROM `rom`.
pub fn run(firmware: &Firmware, rom: &[u8], options: RunOptions) -> Outcome {
    let started = Instant::now();
    let mut machine = Machine::new(
        rom,
        &firmware.flash,
        &firmware.sram,
        options.quantum,
        options.interleave,
    );
    let mut lcd: St7789<Stamp> = St7789::new();
    let mut frames = Vec::new();
    let mut next_check = CHECK_EVERY;
    let mut spinning_in_panic = false;
    let stop = loop {
        machine.step_quantum();
        for (stamp, sent) in machine.drain_sent() {
            if !sent.selected {
                continue;
            }
            if let Some(frame) = lcd.byte(sent.data, sent.byte, stamp) {
                frames.push(frame);
            }
        }
        if frames.len() > options.frames {
            break Stop::Done;
        }
        let now = machine.stamp().cycle;
        if now < next_check {
            continue;
        }
        next_check = now + CHECK_EVERY;
        if now >= options.max_cycles {
            break Stop::CycleLimit;
        }
        if let Some(stop) = failure(&machine, firmware, &mut spinning_in_panic) {
            break stop;
        }
    };
    let read = |address: Option<u32>| address.map(|a| machine.peek32(a));
    Outcome {
        frames,
        startup_commands: lcd.startup_commands().to_vec(),
        stop,
        fault: read(firmware.fault),
        frames_static: read(firmware.frames),
        frame_us: read(firmware.frame_us),
        core1_stack: read(firmware.core1_stack),
        cycles: machine.stamp().cycle,
        sys_clk_hz: machine.sys_clk_hz(),
        wall: started.elapsed(),
        counters: machine.counters(),
    }
}

/// A reason to stop early: a fault, a panic, or a block this harness
/// cannot run. A core's PC in a panic function at two checks in a row
/// counts as a panic.
fn failure(machine: &Machine, firmware: &Firmware, spinning_in_panic: &mut bool) -> Option<Stop> {
    if machine.systick_enabled() {
        return Some(Stop::Unsupported("SysTick"));
    }
    if machine.pio_active() {
        return Some(Stop::Unsupported("PIO"));
    }
    if let Some(address) = firmware.fault {
        let fault = machine.peek32(address);
        if fault != 0 {
            return Some(Stop::Fault(fault));
        }
    }
    let mut in_panic = None;
    for id in 0..2 {
        let core = machine.core(id);
        let pc = core.regs.pc();
        if core.is_in_hardfault() {
            return Some(Stop::HardFault { core: id, pc });
        }
        if !core.is_halted() && firmware.panic_code.iter().any(|r| r.contains(&pc)) {
            in_panic = Some(Stop::Panic { core: id, pc });
        }
    }
    let was = std::mem::replace(spinning_in_panic, in_panic.is_some());
    if was { in_panic } else { None }
}
