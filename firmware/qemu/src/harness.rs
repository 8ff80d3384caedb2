//! What both firmwares of this crate share: instructions counted by
//! SysTick, the exit through semihosting, the panic handler.

use cortex_m::peripheral::SYST;
use cortex_m_semihosting::{debug, hprintln};

/// SysTick ticks elapsed while running `f`; the counter runs down from
/// 2^24 - 1 and frames stay well below one wrap.
pub fn ticks<T>(syst: &mut SYST, f: impl FnOnce() -> T) -> (T, u32) {
    syst.clear_current();
    let start = SYST::get_current();
    let result = f();
    let end = SYST::get_current();
    (result, start.wrapping_sub(end) & 0x00FF_FFFF)
}

/// Instructions per SysTick tick, measured with a loop of known length:
/// `subs` + `bne`, two instructions an iteration.
pub fn instructions_per_tick(syst: &mut SYST) -> u32 {
    const ITERATIONS: u32 = 200_000;
    let ((), t) = ticks(syst, || {
        // SAFETY: a register-only countdown loop; it touches no memory.
        unsafe {
            core::arch::asm!("1:", "subs {0}, #1", "bne 1b", inout(reg) ITERATIONS => _, options(nomem, nostack));
        }
    });
    (2 * ITERATIONS + t / 2) / t.max(1)
}

/// Prints `passed` or "FAILED" and exits QEMU with 0 or 1.
pub fn finish(ok: bool, passed: &str) -> ! {
    hprintln!("{}", if ok { passed } else { "FAILED" });
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
