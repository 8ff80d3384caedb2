//! Stack high-water mark, for a debugger.
//!
//! [`paint`] fills the top [`WINDOW`] bytes of the stack below the stack
//! pointer (never below the end of the statics, where cortex-m-rt lets the
//! stack grow to) with a pattern; [`measure`] finds the lowest word that no
//! longer holds it and returns how many bytes of stack were used since.
//! Only a window is painted so that the measurement after the first frame
//! scans a few thousand words, not the whole free RAM (about 330,000 cycles
//! on the RP2040, which the first frame's period used to pay); a use that
//! reaches the window's bottom reads as the whole window, a lower bound.
//! `main` paints at boot, measures at the end of start-up into
//! [`STARTUP_HIGH_WATER_BYTES`], paints again, and measures after the first
//! frame (which runs every path of the render loop) into
//! [`HIGH_WATER_BYTES`]. [`STACK_BYTES`] is the stack's size.
//!
//! Read them with a debugger, for example in gdb:
//! `print zline_rp2040::stack::HIGH_WATER_BYTES` (or look the symbols up
//! with `nm -C` and read the words at their addresses with probe-rs).
//!
//! This is the only code here that touches raw memory; delete the module
//! and its calls in `main` to drop it.

use core::sync::atomic::{AtomicU32, Ordering};

/// What free stack is painted with.
const PAINT: u32 = 0x5A17_C0DE;
/// Bytes left unpainted below the stack pointer, for `paint`'s own frame.
const GUARD: usize = 256;
/// Bytes at the top of the stack that are painted: the build script keeps
/// 16 KiB free for the stack, and the render loop uses about 5 KiB.
pub const WINDOW: usize = 16 * 1024;

unsafe extern "C" {
    /// Top of the stack (the initial stack pointer), from cortex-m-rt.
    static _stack_start: u32;
    /// Lowest address the stack may reach (the end of the statics), from
    /// cortex-m-rt.
    static _stack_end: u32;
}

/// Most bytes of stack the render loop used, measured after the first
/// frame (0 before). These three are `#[used]`: LTO would remove a static
/// that is only written, and a debugger reads them.
#[used]
pub static HIGH_WATER_BYTES: AtomicU32 = AtomicU32::new(0);
/// Most bytes of stack start-up used (clocks, LCD, building the renderer).
#[used]
pub static STARTUP_HIGH_WATER_BYTES: AtomicU32 = AtomicU32::new(0);
/// Bytes between the end of the statics and the top of RAM.
#[used]
pub static STACK_BYTES: AtomicU32 = AtomicU32::new(0);

fn bounds() -> (usize, usize) {
    let bottom = (&raw const _stack_end) as usize;
    let top = (&raw const _stack_start) as usize;
    (bottom, top)
}

/// The lowest painted address: [`WINDOW`] bytes below the top, or the end
/// of the statics if the stack is smaller; word-aligned.
fn window_bottom(bottom: usize, top: usize) -> usize {
    (top.saturating_sub(WINDOW).max(bottom) + 3) & !3
}

/// Paints the free stack below the caller. Only while no interrupt
/// handler is enabled (this firmware enables none).
#[inline(never)]
pub fn paint() {
    let (bottom, top) = bounds();
    STACK_BYTES.store((top - bottom) as u32, Ordering::Relaxed);
    let limit = (cortex_m::register::msp::read() as usize).saturating_sub(GUARD) & !3;
    let mut at = window_bottom(bottom, top);
    while at < limit {
        // SAFETY: `at` is a word-aligned RAM address between the end of the
        // statics (or the window's bottom, above it) and GUARD bytes below
        // the current stack pointer. Nothing
        // lives there: there is no heap, this leaf function's frame sits
        // above `limit`, and no interrupt handler is enabled yet.
        unsafe { core::ptr::with_exposed_provenance_mut::<u32>(at).write_volatile(PAINT) };
        at += 4;
    }
}

/// Bytes of stack used since the last [`paint`], counted from the top.
#[inline(never)]
pub fn measure() -> u32 {
    let (bottom, top) = bounds();
    let mut at = window_bottom(bottom, top);
    // SAFETY: every address read is a word-aligned RAM address between the
    // window's bottom (at or above the end of the statics) and the top of
    // the stack, so the read is valid
    // and has no side effect; the scan stops at the first word the stack
    // has used, below every live frame.
    while at < top
        && unsafe { core::ptr::with_exposed_provenance::<u32>(at).read_volatile() } == PAINT
    {
        at += 4;
    }
    (top - at) as u32
}
