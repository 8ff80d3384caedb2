//! Judging a run and the lines printed for it.

use crate::contention::{Slave, Stalls};
use crate::crc32::crc32;
use crate::firmware::Firmware;
use crate::harness::{Outcome, Stop, core_cycles, period};
use crate::st7789::{FRAME_BYTES, FRAME_PIXELS};

/// The start-up commands the LCD must receive, in order: SLPOUT, MADCTL,
/// INVON, COLMOD, NORON, DISPON.
pub const START_UP: [u8; 6] = [0x11, 0x36, 0x21, 0x3A, 0x13, 0x29];

/// The CRC frame `index` must have: frame 0 is the start-up clear (black),
/// frame `k >= 1` shows view `(k - 1) % views` of `EXPECTED_CRCS`.
pub fn expected_crc(index: usize, expected_crcs: &[u32]) -> u32 {
    match index {
        0 => crc32(&[0; FRAME_BYTES]),
        k => expected_crcs[(k - 1) % expected_crcs.len()],
    }
}

/// The median of `values`; for an even count the mean of the middle two,
/// rounded half up. `None` for no values.
pub fn median(values: &[u64]) -> Option<u64> {
    let mut sorted = values.to_vec();
    sorted.sort_unstable();
    let n = sorted.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(sorted[n / 2]),
        _ => Some((sorted[n / 2 - 1] + sorted[n / 2]).div_ceil(2)),
    }
}

/// What a run came to.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// One line per whole frame, then a line of run details.
    pub lines: Vec<String>,
    /// Every problem found (empty: the run passed).
    pub failures: Vec<String>,
    /// Median period of frames 1..=N, in cycles.
    pub median_period: Option<u64>,
    /// The slowest of frames 1..=N and its period in cycles.
    pub slowest_frame: Option<(usize, u64)>,
    /// Every frame wanted was decoded and matched its CRC.
    pub crc_ok: bool,
}

/// Judges `outcome`, a run of `firmware` that wanted `frames` frames after
/// the start-up clear; lines are prefixed with `label`.
pub fn judge(label: &str, firmware: &Firmware, outcome: &Outcome, frames: usize) -> Verdict {
    let mut lines = Vec::new();
    let mut failures = Vec::new();
    let mut crc_ok = true;
    let mut periods = Vec::new();
    let mut slowest_frame = None;
    for f in outcome.frames.iter().take(frames + 1) {
        let want = expected_crc(f.index, &firmware.expected_crcs);
        let ok = f.crc32 == want && f.pixels == FRAME_PIXELS;
        let [core0, core1] = core_cycles(f);
        lines.push(format!(
            "{label} frame={} crc32={:08X} expected={want:08X} {} period_cycles={} \
             core0_cycles={core0} core1_cycles={core1}",
            f.index,
            f.crc32,
            crc_word(ok),
            period(f),
        ));
        if f.crc32 != want {
            failures.push(format!(
                "frame {}: crc32 {:08X} != expected {want:08X}",
                f.index, f.crc32
            ));
        }
        if f.pixels != FRAME_PIXELS {
            failures.push(format!(
                "frame {}: {} pixels, not {FRAME_PIXELS}",
                f.index, f.pixels
            ));
        }
        crc_ok &= ok;
        if f.index >= 1 {
            periods.push(period(f));
            if slowest_frame.is_none_or(|(_, p)| period(f) > p) {
                slowest_frame = Some((f.index, period(f)));
            }
        }
    }
    let decoded = outcome.frames.len().saturating_sub(1).min(frames);
    if decoded < frames {
        crc_ok = false;
        failures.push(format!(
            "only {decoded} of {frames} frames after the start-up clear were decoded"
        ));
    }
    failures.extend(stop_failure(outcome));
    match outcome.fault {
        None => failures.push("FAULT is not in the ELF (is it #[used]?)".into()),
        Some(0) => {}
        Some(fault) if outcome.stop != Stop::Fault(fault) => {
            failures.push(format!("FAULT = {fault} at the end"));
        }
        Some(_) => {}
    }
    if outcome.startup_commands != START_UP {
        failures.push(format!(
            "start-up commands {} != {}",
            hex_list(&outcome.startup_commands),
            hex_list(&START_UP)
        ));
    }
    lines.push(details(label, outcome));
    Verdict {
        lines,
        failures,
        median_period: median(&periods),
        slowest_frame,
        crc_ok,
    }
}

/// What an early stop says about the run.
fn stop_failure(outcome: &Outcome) -> Option<String> {
    Some(match &outcome.stop {
        Stop::Done => return None,
        Stop::CycleLimit => format!("stopped at the limit of {} cycles", outcome.cycles),
        Stop::Fault(fault) => format!("the firmware set FAULT = {fault}"),
        Stop::HardFault { core, pc } => format!("core {core} in HardFault (PC {pc:#010x})"),
        Stop::Panic { core, pc } => format!("core {core} panicked (PC {pc:#010x})"),
        Stop::Unsupported(block) => {
            format!("the firmware runs {block}, which this harness does not emulate")
        }
    })
}

/// The run's details: the firmware's statics, start-up commands, speed and
/// how the harness's workarounds were exercised.
fn details(label: &str, o: &Outcome) -> String {
    let show = |v: Option<u32>| v.map_or("-".to_string(), |v| v.to_string());
    let last_us = o
        .frames
        .last()
        .map(|f| period(f) as f64 * 1e6 / f64::from(o.sys_clk_hz.max(1)));
    let seconds = o.wall.as_secs_f64();
    let c = &o.counters;
    format!(
        "{label} run: FAULT={} FRAMES={} FRAME_US={} (last period {} us at {} MHz) \
         core1_stack_bytes={} startup={} cycles={} wall={seconds:.1}s ({:.1} emulated MHz) \
         spi_bytes_cpu={} spi_bytes_dma={} dma_al2_triggers={} dma_alias_redirects={} spi_loopback_sets={} idle_quanta={} \
         lockstep_wait_core0={} lockstep_wait_core1={} \
         bus_wait_core0={} bus_wait_core1={} bus_wait_by_slave={}",
        show(o.fault),
        show(o.frames_static),
        show(o.frame_us),
        last_us.map_or("-".to_string(), |us| format!("{us:.0}")),
        o.sys_clk_hz / 1_000_000,
        show(o.core1_stack),
        hex_list(&o.startup_commands),
        o.cycles,
        o.cycles as f64 / seconds.max(1e-9) / 1e6,
        c.cpu_spi_bytes,
        c.dma_spi_bytes,
        c.dma_triggers,
        c.dma_redirects,
        c.loopback_sets,
        c.idle_quanta,
        c.lockstep_wait[0],
        c.lockstep_wait[1],
        c.contention.per_core[0],
        c.contention.per_core[1],
        slave_list(&c.contention),
    )
}

/// The bus stalls by slave as `rom:0,xip:12,...`.
fn slave_list(stalls: &Stalls) -> String {
    let items: Vec<String> = Slave::KINDS
        .iter()
        .zip(stalls.per_slave)
        .map(|(name, n)| format!("{name}:{n}"))
        .collect();
    items.join(",")
}

/// Bytes as `11,36,21`.
fn hex_list(bytes: &[u8]) -> String {
    let items: Vec<String> = bytes.iter().map(|b| format!("{b:02X}")).collect();
    items.join(",")
}

/// `ok` or `MISMATCH`.
pub fn crc_word(ok: bool) -> &'static str {
    if ok { "ok" } else { "MISMATCH" }
}

/// The last line with one firmware.
pub fn single_summary(single: &Verdict) -> String {
    format!(
        "single-core: period={} crc={}",
        single.median_period.unwrap_or(0),
        crc_word(single.crc_ok)
    )
}

/// The dual/single ratio of median periods, if both are known.
pub fn period_ratio(single: &Verdict, dual: &Verdict) -> Option<f64> {
    match (single.median_period, dual.median_period) {
        (Some(s), Some(d)) if s > 0 => Some(d as f64 / s as f64),
        _ => None,
    }
}

/// The last line with both firmwares.
pub fn dual_summary(single: &Verdict, dual: &Verdict) -> String {
    let ratio = period_ratio(single, dual).map_or("nan".to_string(), |r| format!("{r:.3}"));
    let (frame, slowest) = dual.slowest_frame.unwrap_or((0, 0));
    format!(
        "dual-core: period_ratio={ratio} single={} dual={} dual_slowest={slowest} (frame {frame}) crc={}",
        single.median_period.unwrap_or(0),
        dual.median_period.unwrap_or(0),
        crc_word(single.crc_ok && dual.crc_ok)
    )
}

/// Why the two builds' periods cannot be compared, if they cannot: both
/// must carry the same views (`EXPECTED_CRCS`), or they draw different
/// frames.
pub fn incomparable(single: &[u32], dual: &[u32]) -> Option<String> {
    (single != dual).then(|| {
        format!(
            "the builds carry different EXPECTED_CRCS ({} and {} views, first {:08X} and {:08X}), \
             so they draw different frames and their periods do not compare",
            single.len(),
            dual.len(),
            single.first().copied().unwrap_or(0),
            dual.first().copied().unwrap_or(0)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians() {
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[5]), Some(5));
        assert_eq!(median(&[9, 1, 5]), Some(5));
        assert_eq!(median(&[4, 1, 3, 2]), Some(3), "(2 + 3) / 2 rounded up");
        assert_eq!(median(&[10, 20]), Some(15));
    }

    #[test]
    fn frame_k_shows_view_k_minus_one() {
        let crcs = [0xA, 0xB, 0xC];
        assert_eq!(expected_crc(0, &crcs), crc32(&[0; FRAME_BYTES]));
        assert_eq!(expected_crc(1, &crcs), 0xA);
        assert_eq!(expected_crc(3, &crcs), 0xC);
        assert_eq!(expected_crc(4, &crcs), 0xA, "the turn repeats");
    }

    fn verdict(median_period: Option<u64>, crc_ok: bool) -> Verdict {
        Verdict {
            lines: Vec::new(),
            failures: Vec::new(),
            median_period,
            slowest_frame: median_period.map(|p| (2, p + 1)),
            crc_ok,
        }
    }

    #[test]
    fn summaries() {
        let single = verdict(Some(4_000_000), true);
        let dual = verdict(Some(2_500_000), true);
        assert_eq!(
            single_summary(&single),
            "single-core: period=4000000 crc=ok"
        );
        assert_eq!(
            dual_summary(&single, &dual),
            "dual-core: period_ratio=0.625 single=4000000 dual=2500000 dual_slowest=2500001 \
             (frame 2) crc=ok"
        );
        let broken = verdict(None, false);
        assert_eq!(
            dual_summary(&single, &broken),
            "dual-core: period_ratio=nan single=4000000 dual=0 dual_slowest=0 (frame 0) \
             crc=MISMATCH"
        );
    }

    #[test]
    fn builds_of_different_views_do_not_compare() {
        assert_eq!(incomparable(&[1, 2], &[1, 2]), None);
        assert!(incomparable(&[1, 2], &[1, 3]).is_some());
        assert!(incomparable(&[1, 2], &[1]).is_some());
        assert!(incomparable(&[], &[7]).is_some());
    }
}
