//! The second core (feature `dual-core`): core 1 waits on the SIO FIFO
//! for a job from core 0, runs it and answers on the FIFO. [`Core1::join`]
//! runs one job on each core and returns when both are done, so a job may
//! borrow what core 0 owns (as `std::thread::scope` lets a thread), and
//! the cores meet only through the FIFO: no flag in memory is polled.
//!
//! This file and the stack's paint are the firmware's only raw-pointer
//! code: the job's address crosses the FIFO as a word, and core 1's stack
//! (SRAM4 and SRAM5) is painted and measured here.

use core::sync::atomic::{AtomicBool, AtomicU32, Ordering, compiler_fence};

use crate::Fault;
use crate::hal::multicore::{Multicore, StackAllocation};
use crate::hal::pac;
use crate::hal::sio::{Sio, SioFifo};

/// Words of core 1's stack: its job draws a frame's scene and scans
/// rows, as core 0 does in about 5 KiB.
const CORE1_STACK_WORDS: usize = 2048;

/// Where core 1's stack lies: SRAM4 and SRAM5, the RP2040's two 4 KiB
/// banks at 0x2004_0000..0x2004_2000, which the repository's `memory.x`
/// leaves out of `RAM` (so no static and neither core's other data is
/// there; core 0's stack starts below them, at the top of `RAM`, and
/// grows down). Each is a bus slave of its own: core 1's stack accesses
/// never wait for core 0's, which they did in the striped banks SRAM0–3
/// (`tools/dual-core-check --interleave contended`: the two cores' waits
/// for the striped banks fell from 274,667 to 59,544 cycles over 10
/// frames, the period ratio from 0.549 to 0.547), and `.bss` is 8 KiB
/// smaller. (pico-sdk puts each core's stack in one of these banks the
/// same way.)
const CORE1_STACK_START: usize = 0x2004_0000;
const _: () = assert!(CORE1_STACK_WORDS * core::mem::size_of::<usize>() == 8 * 1024);

/// What core 1's stack is painted with before it starts, so that
/// [`measure_core1_stack`] sees how deep it went.
const PAINT: usize = 0x5A17_C0DE;

/// Most bytes of its stack core 1 used, measured after the first frame
/// (0 before; `#[used]`, for a debugger and `tools/dual-core-check`).
#[used]
pub static CORE1_HIGH_WATER_BYTES: AtomicU32 = AtomicU32::new(0);

/// Whether core 1's stack has been handed out.
static TAKEN: AtomicBool = AtomicBool::new(false);

/// Core 1's stack, painted, the first time only.
fn take_core1_stack() -> Option<StackAllocation> {
    // (The Cortex-M0+ has no atomic swap: the flag is tested and set
    // under the critical section.)
    let taken = critical_section::with(|_| {
        let taken = TAKEN.load(Ordering::Relaxed);
        TAKEN.store(true, Ordering::Relaxed);
        taken
    });
    if taken {
        return None;
    }
    let start = CORE1_STACK_START as *mut usize;
    for k in 0..CORE1_STACK_WORDS {
        // SAFETY: `k` is inside SRAM4/SRAM5, which nothing else uses (see
        // CORE1_STACK_START) and core 1 does not yet (it is taken once,
        // here, before core 1 starts).
        unsafe { start.add(k).write_volatile(PAINT) };
    }
    // SAFETY: the range is SRAM4 and SRAM5, memory no section or stack
    // of the program uses, always there, aligned to 32 bytes (as
    // rp2040-hal asks: 8 at least, 32 for its MPU guard), 8 KiB, and
    // handed out once, to core 1 alone.
    Some(unsafe { StackAllocation::from_raw_parts(start, start.add(CORE1_STACK_WORDS)) })
}

/// Bytes of its stack core 1 has used, from the lowest word that no
/// longer holds the paint. Call while core 1 waits for a job (between
/// [`Core1::join`]s): it then writes no word of the stack this reads.
pub fn measure_core1_stack() -> u32 {
    let start = CORE1_STACK_START as *const usize;
    let mut untouched = 0;
    // SAFETY: every word read is inside core 1's stack (SRAM4/SRAM5,
    // which nothing else uses); core 1 is waiting on
    // the FIFO in `core1_main`, whose frame is at the stack's top, above
    // the painted words this stops at.
    while untouched < CORE1_STACK_WORDS && unsafe { start.add(untouched).read_volatile() } == PAINT
    {
        untouched += 1;
    }
    ((CORE1_STACK_WORDS - untouched) * core::mem::size_of::<usize>()) as u32
}

/// What core 1 answers when a job is done.
const DONE: u32 = 0x0D0E;

/// A job for core 1: a closure on core 0's stack, borrowed for the length
/// of one [`Core1::join`].
type Job<'a> = &'a mut (dyn FnMut() + Send);

/// Core 0's end of the link to core 1.
pub struct Core1 {
    fifo: SioFifo,
}

impl Core1 {
    /// Starts core 1 (through the boot ROM's launch protocol on the FIFO)
    /// waiting for jobs.
    pub fn start(psm: &mut pac::PSM, ppb: &mut pac::PPB, mut fifo: SioFifo) -> Result<Self, Fault> {
        let stack = take_core1_stack().ok_or(Fault::Core1)?;
        let mut multicore = Multicore::new(psm, ppb, &mut fifo);
        let core1 = multicore.cores().get_mut(1).ok_or(Fault::Core1)?;
        core1.spawn(stack, core1_main).map_err(|_| Fault::Core1)?;
        Ok(Self { fifo })
    }

    /// Runs `theirs` on core 1 and `ours` here; returns `ours`' result
    /// once both have returned.
    pub fn join<R>(&mut self, theirs: impl FnOnce() + Send, ours: impl FnOnce() -> R) -> R {
        let mut theirs = Some(theirs);
        let mut call = move || {
            if let Some(job) = theirs.take() {
                job();
            }
        };
        let mut job: Job<'_> = &mut call;
        // The address of `job` (a fat reference on this stack frame),
        // which outlives core 1's use of it: this function returns only
        // after core 1 has answered.
        let address = core::ptr::addr_of_mut!(job) as u32;
        // The job's stores before the FIFO write, the results' loads after
        // the FIFO read: the FIFO's volatile accesses alone do not order
        // them. (The SIO's accesses are in order on the bus.)
        compiler_fence(Ordering::SeqCst);
        self.fifo.write_blocking(address);
        let result = ours();
        // Anything but DONE cannot come (core 1 writes nothing else);
        // either way core 1 is no longer running the job.
        let _ = self.fifo.read_blocking();
        compiler_fence(Ordering::SeqCst);
        result
    }
}

/// Core 1's loop: each word from the FIFO is the address of a [`Job`].
fn core1_main() {
    // SAFETY: core 1 touches only its own end of the SIO FIFO (each core
    // sees its own FIFO registers at the same addresses); core 0's `Sio`
    // never reads core 1's end.
    let pac = unsafe { pac::Peripherals::steal() };
    let mut fifo = Sio::new(pac.SIO).fifo;
    loop {
        let address = fifo.read_blocking();
        compiler_fence(Ordering::SeqCst);
        // SAFETY: core 0 sent the address of a live `Job` in
        // `Core1::join`, which does not return (ending the borrow) until
        // the DONE below; the closure is `Send`.
        let job = unsafe { &mut *(address as *mut Job<'static>) };
        job();
        compiler_fence(Ordering::SeqCst);
        fifo.write_blocking(DONE);
    }
}
