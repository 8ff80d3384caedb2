//! A model of the RP2040's bus fabric under two cores: what the
//! `contended` interleave charges that rp2040-emu does not.
//!
//! On the RP2040 each core has one AHB-Lite port into a crossbar whose
//! slaves each serve one access a cycle: the boot ROM, the XIP cache (flash,
//! where the firmware's code runs), the four striped SRAM banks SRAM0–3
//! (word `n` of 0x2000_0000.. is in bank `n mod 4`), SRAM4 and SRAM5, the
//! APB bridge and the AHB-Lite peripherals (DMA, PIO, USB). When both cores
//! address the same slave in the same cycle, one waits a cycle. The SIO
//! (FIFO, spinlocks, divider, GPIO) is on each core's single-cycle IOPORT
//! and the PPB is private to each core: neither contends. (RP2040
//! datasheet, section 2.1, "Bus Fabric".)
//!
//! The emulated cores report what each instruction touched, not when, so
//! the model places the accesses in the instruction's cycles: the fetch of
//! a new 32-bit word of code (the Cortex-M0+ fetches a word, two 16-bit
//! instructions, at a time; an instruction in the word last fetched costs
//! no fetch) in its first cycle, the data accesses one a cycle after it.
//! When both cores want a slave in the same cycle, the arbiter grants it
//! round robin (per slave, the core that lost the last conflict wins the
//! next) and the loser waits a cycle, with everything after the access in
//! its instruction.
//!
//! Each core keeps its own clock (the `independent` interleave) and the
//! core behind runs next, so the other core's accesses up to the cycle of
//! any access checked here are already placed. When the core that ran
//! later wins, the other core's access moves to the next cycle and that
//! core is charged the cycle at its next step (its later accesses in the
//! same instruction stay where they were placed). The DMA's reads of
//! the row buffers (one a byte sent, 115,200 a 240x240 frame, each from
//! one bank: about 5 % of a two-core frame's cycles) are not charged.

/// Grants each core remembers: more than one instruction's accesses (the
/// other core is at most one instruction ahead of the one being charged).
const REMEMBERED: usize = 32;

/// A slave of the RP2040's bus crossbar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slave {
    /// The boot ROM.
    Rom,
    /// The XIP cache (flash and XIP SRAM).
    Xip,
    /// SRAM bank 0–5.
    Sram(u8),
    /// The APB bridge (SPI, UART, timer, ...).
    Apb,
    /// The AHB-Lite peripherals (DMA, PIO, USB).
    Ahb,
}

impl Slave {
    /// The slaves counted apart in the report, in this order.
    pub const KINDS: [&'static str; 5] = ["rom", "xip", "sram", "apb", "ahb"];

    /// How many slaves there are ([`Slave::index`]).
    pub const COUNT: usize = 10;

    /// This slave's number, `0..COUNT`.
    pub fn index(self) -> usize {
        match self {
            Slave::Rom => 0,
            Slave::Xip => 1,
            Slave::Sram(bank) => 2 + usize::from(bank.min(5)),
            Slave::Apb => 8,
            Slave::Ahb => 9,
        }
    }

    /// This slave's position in [`Slave::KINDS`].
    pub fn kind(self) -> usize {
        match self {
            Slave::Rom => 0,
            Slave::Xip => 1,
            Slave::Sram(_) => 2,
            Slave::Apb => 3,
            Slave::Ahb => 4,
        }
    }

    /// The slave that serves `address`; `None` for the SIO and the PPB
    /// (no contention) and unmapped addresses.
    pub fn of(address: u32) -> Option<Slave> {
        /// Striped SRAM0–3, then SRAM4 and SRAM5 (4 KiB each).
        const STRIPED: u32 = 0x2000_0000;
        const SRAM4: u32 = 0x2004_0000;
        const SRAM5: u32 = 0x2004_1000;
        const SRAM_END: u32 = 0x2004_2000;
        /// The same six banks unstriped: 64 KiB each, then 4 KiB each.
        const UNSTRIPED: u32 = 0x2100_0000;
        const UNSTRIPED_SMALL: u32 = 0x2104_0000;
        const UNSTRIPED_END: u32 = 0x2104_2000;
        match address {
            0x0000_0000..0x1000_0000 => Some(Slave::Rom),
            0x1000_0000..0x2000_0000 => Some(Slave::Xip),
            STRIPED..SRAM4 => Some(Slave::Sram(((address >> 2) & 3) as u8)),
            SRAM4..SRAM5 => Some(Slave::Sram(4)),
            SRAM5..SRAM_END => Some(Slave::Sram(5)),
            UNSTRIPED..UNSTRIPED_SMALL => Some(Slave::Sram(((address - UNSTRIPED) >> 16) as u8)),
            UNSTRIPED_SMALL..UNSTRIPED_END => {
                Some(Slave::Sram(4 + ((address - UNSTRIPED_SMALL) >> 12) as u8))
            }
            0x4000_0000..0x5000_0000 => Some(Slave::Apb),
            0x5000_0000..0x6000_0000 => Some(Slave::Ahb),
            _ => None,
        }
    }
}

/// What one step of a core touched on the bus, as its [`Tap`] saw it.
///
/// [`Tap`]: crate::tap::Tap
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct StepAccesses {
    /// The instruction's address, if the step ran one (not for an
    /// exception's entry or return).
    pub pc: Option<u32>,
    /// The addresses of its loads and stores, in order (not its fetch).
    pub data: Vec<u32>,
}

/// The cycles lost to the other core, per core and per kind of slave.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stalls {
    /// Cycles each core waited for a slave the other held.
    pub per_core: [u64; 2],
    /// The same cycles by the slave waited for ([`Slave::KINDS`]).
    pub per_slave: [u64; 5],
}

/// The two cores' recent grants and the stalls charged so far.
#[derive(Debug, Clone)]
pub struct BusModel {
    /// Each core's last grants: `(cycle, slave)`, a ring.
    grants: [[Option<(u64, Slave)>; REMEMBERED]; 2],
    /// Where each core's ring is written next.
    next: [usize; 2],
    /// The word of code each core fetched last.
    fetched: [Option<u32>; 2],
    /// Per slave ([`Slave::index`]), the core that won its last conflict:
    /// the other wins the next (round robin).
    last_winner: [usize; Slave::COUNT],
    /// Cycles each core lost to the other after its last step, charged at
    /// its next.
    owed: [u64; 2],
    /// The stalls charged so far.
    stalls: Stalls,
}

impl Default for BusModel {
    fn default() -> Self {
        Self {
            grants: [[None; REMEMBERED]; 2],
            next: [0; 2],
            fetched: [None; 2],
            last_winner: [1; Slave::COUNT],
            owed: [0; 2],
            stalls: Stalls::default(),
        }
    }
}

impl BusModel {
    /// The stalls charged so far.
    pub fn stalls(&self) -> Stalls {
        self.stalls
    }

    /// Charges core `core`'s step that began at cycle `start` and took
    /// `cycles` without contention: returns the cycles it waits for the
    /// other core on top.
    pub fn charge(&mut self, core: usize, start: u64, cycles: u64, step: &StepAccesses) -> u64 {
        // Cycles this core lost, since its last step, to accesses of the
        // other core that were placed after its own.
        let mut waited = std::mem::take(&mut self.owed[core]);
        let mut place = |model: &mut Self, offset: u64, slave: Slave| {
            let mut at = start + offset + waited;
            while let Some(held) = model.held_by_other(core, at, slave) {
                model.stalls.per_slave[slave.kind()] += 1;
                let turn = &mut model.last_winner[slave.index()];
                let loser = if *turn == 1 - core { 1 - core } else { core };
                *turn = 1 - loser;
                model.stalls.per_core[loser] += 1;
                if loser == core {
                    at += 1;
                    waited += 1;
                } else {
                    // The other core's access (already run) takes the next
                    // cycle: it loses the cycle at its next step.
                    model.grants[1 - core][held] = Some((at + 1, slave));
                    model.owed[1 - core] += 1;
                    break;
                }
            }
            let slot = &mut model.next[core];
            model.grants[core][*slot] = Some((at, slave));
            *slot = (*slot + 1) % REMEMBERED;
        };
        if let Some(pc) = step.pc {
            let word = pc & !3;
            if self.fetched[core] != Some(word) {
                self.fetched[core] = Some(word);
                if let Some(slave) = Slave::of(word) {
                    place(self, 0, slave);
                }
            }
        } else {
            // An exception's entry or return: the next instruction is
            // fetched afresh.
            self.fetched[core] = None;
        }
        let last = cycles.saturating_sub(1);
        for (k, &address) in step.data.iter().enumerate() {
            if let Some(slave) = Slave::of(address) {
                place(self, (k as u64 + 1).min(last), slave);
            }
        }
        waited
    }

    /// Where in the other core's ring its grant of `slave` in cycle `at`
    /// is, if it holds it then.
    fn held_by_other(&self, core: usize, at: u64, slave: Slave) -> Option<usize> {
        self.grants[1 - core]
            .iter()
            .position(|&grant| grant == Some((at, slave)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(pc: u32, data: &[u32]) -> StepAccesses {
        StepAccesses {
            pc: Some(pc),
            data: data.to_vec(),
        }
    }

    #[test]
    fn maps_the_crossbar() {
        assert_eq!(Slave::of(0x0000_1234), Some(Slave::Rom));
        assert_eq!(Slave::of(0x1000_0100), Some(Slave::Xip));
        assert_eq!(Slave::of(0x1500_0000), Some(Slave::Xip), "XIP SRAM");
        for (address, bank) in [
            (0x2000_0000, 0),
            (0x2000_0004, 1),
            (0x2000_0008, 2),
            (0x2000_000C, 3),
            (0x2000_0010, 0),
            (0x2003_FFFC, 3),
            (0x2004_0000, 4),
            (0x2004_0FFC, 4),
            (0x2004_1000, 5),
            (0x2100_0000, 0),
            (0x2101_0000, 1),
            (0x2103_FFFC, 3),
            (0x2104_0000, 4),
            (0x2104_1000, 5),
        ] {
            assert_eq!(Slave::of(address), Some(Slave::Sram(bank)), "{address:#x}");
        }
        assert_eq!(Slave::of(0x2004_2000), None, "past SRAM5");
        assert_eq!(Slave::of(0x4003_C008), Some(Slave::Apb), "SPI0");
        assert_eq!(Slave::of(0x5000_0000), Some(Slave::Ahb), "DMA");
        assert_eq!(Slave::of(0xD000_0050), None, "the SIO's FIFO");
        assert_eq!(Slave::of(0xE000_E010), None, "the PPB");
    }

    #[test]
    fn same_slave_same_cycle_costs_a_cycle_round_robin() {
        let mut bus = BusModel::default();
        // Core 1 runs first: a load from bank 1 in cycle 11.
        assert_eq!(bus.charge(1, 10, 2, &step(0x1000_0000, &[0x2000_0004])), 0);
        // Core 0's load from bank 1 in the same cycle wins the first
        // conflict: core 1 waits, charged at its next step.
        assert_eq!(bus.charge(0, 10, 2, &step(0x2000_1000, &[0x2000_0104])), 0);
        assert_eq!(bus.charge(1, 12, 1, &step(0x1000_0002, &[])), 1);
        // The next conflict for bank 1 goes to core 1: core 0 waits.
        assert_eq!(bus.charge(1, 20, 2, &step(0x1000_0004, &[0x2000_0204])), 0);
        assert_eq!(bus.charge(0, 20, 2, &step(0x2000_1002, &[0x2000_0304])), 1);
        assert_eq!(bus.stalls().per_core, [1, 1]);
        assert_eq!(bus.stalls().per_slave, [0, 0, 2, 0, 0]);
    }

    #[test]
    fn other_banks_and_cycles_are_free() {
        let mut bus = BusModel::default();
        bus.charge(1, 10, 2, &step(0x1000_0000, &[0x2000_0004]));
        assert_eq!(bus.charge(0, 10, 2, &step(0x2000_1000, &[0x2000_0008])), 0);
        let mut bus = BusModel::default();
        bus.charge(1, 10, 2, &step(0x1000_0000, &[0x2000_0004]));
        assert_eq!(bus.charge(0, 11, 2, &step(0x2000_1000, &[0x2000_0004])), 0);
        assert_eq!(bus.charge(1, 12, 1, &step(0x1000_0002, &[])), 0);
        assert_eq!(bus.stalls().per_core, [0, 0]);
    }

    #[test]
    fn fetches_contend_for_the_xip_cache_once_a_word() {
        let mut bus = BusModel::default();
        // Both cores fetch code from flash in cycle 20: core 0 wins the
        // first conflict.
        assert_eq!(bus.charge(0, 20, 1, &step(0x1000_0200, &[])), 0);
        assert_eq!(bus.charge(1, 20, 1, &step(0x1000_0400, &[])), 1);
        // The next instructions are in the words fetched: no access.
        assert_eq!(bus.charge(0, 21, 1, &step(0x1000_0202, &[])), 0);
        assert_eq!(bus.charge(1, 22, 1, &step(0x1000_0402, &[])), 0);
        let stalls = bus.stalls();
        assert_eq!(stalls.per_core, [0, 1]);
        assert_eq!(stalls.per_slave, [0, 1, 0, 0, 0]);
    }

    #[test]
    fn a_stall_moves_the_rest_of_the_instruction() {
        let mut bus = BusModel::default();
        // Core 0 holds XIP in cycle 0 and bank 0 in cycles 1 and 2.
        bus.charge(0, 0, 3, &step(0x1000_0000, &[0x2000_0000, 0x2000_0010]));
        // Core 1: its fetch waits for cycle 1, its first load then finds
        // bank 0 taken in cycle 2 and waits for cycle 3, its second load
        // (bank 0, now cycle 4) is free.
        assert_eq!(
            bus.charge(1, 0, 3, &step(0x1000_0100, &[0x2000_0020, 0x2000_0030])),
            2
        );
        assert_eq!(bus.stalls().per_slave, [0, 1, 1, 0, 0]);
    }

    #[test]
    fn the_sio_and_the_ppb_never_wait() {
        // (The fetches are from different banks.)
        let mut bus = BusModel::default();
        bus.charge(0, 5, 2, &step(0x2000_0100, &[0xD000_0050]));
        assert_eq!(bus.charge(1, 5, 2, &step(0x2000_0204, &[0xD000_0050])), 0);
        bus.charge(0, 7, 2, &step(0x2000_0108, &[0xE000_E100]));
        assert_eq!(bus.charge(1, 7, 2, &step(0x2000_020C, &[0xE000_E100])), 0);
    }
}
