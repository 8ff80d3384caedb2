//! `dual-core-check`: runs the RP2040 board firmware (a single-core build
//! and, optionally, a dual-core build of it) on rp2040-emu, an emulated
//! RP2040 with both Cortex-M0+ cores; checks every frame the LCD receives
//! against the CRCs the firmware carries, and compares the two builds'
//! frame periods in emulated cycles. See `cli.rs` for the options and
//! `machine.rs` and `tap.rs` for what the harness adds to the emulator.

mod bootrom;
mod cli;
mod contention;
mod crc32;
mod elf;
mod firmware;
mod harness;
mod machine;
mod report;
mod st7789;
mod tap;

use std::path::PathBuf;
use std::process::ExitCode;

use cli::{Command, Options};
use firmware::Firmware;
use harness::RunOptions;
use report::Verdict;

fn main() -> ExitCode {
    let options = match cli::parse(std::env::args().skip(1)) {
        Ok(Command::Run(options)) => options,
        Ok(Command::Help) => {
            println!("{}", cli::USAGE);
            return ExitCode::SUCCESS;
        }
        Err(message) => {
            eprintln!("dual-core-check: {message}\n\n{}", cli::USAGE);
            return ExitCode::from(2);
        }
    };
    match check(&options) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(message) => {
            eprintln!("dual-core-check: {message}");
            ExitCode::from(2)
        }
    }
}

/// Runs the checks and prints the report; `Ok(true)` when everything
/// passed, `Err` when a file could not be used.
fn check(options: &Options) -> Result<bool, String> {
    let rom_path = bootrom_path(options);
    let rom = bootrom::load(&rom_path).map_err(|e| e.to_string())?;
    let single = Firmware::load(&options.single).map_err(|e| e.to_string())?;
    let dual = match &options.dual {
        Some(path) => Some(Firmware::load(path).map_err(|e| e.to_string())?),
        None => None,
    };
    if options.quantum > cli::DEFAULT_QUANTUM {
        eprintln!(
            "dual-core-check: warning: a quantum of {} cycles lets the emulated DMA move \
             fewer words than the hardware would",
            options.quantum
        );
    }
    let run = RunOptions {
        frames: options.frames,
        quantum: options.quantum,
        interleave: options.interleave,
        max_cycles: options.cycle_limit(),
    };
    // The two runs are independent machines: run them side by side.
    let (single_outcome, dual_outcome) = std::thread::scope(|scope| {
        let dual_run = dual
            .as_ref()
            .map(|fw| scope.spawn(|| harness::run(fw, &rom, run)));
        let single_outcome = harness::run(&single, &rom, run);
        (single_outcome, dual_run.map(|handle| handle.join()))
    });
    let dual_outcome = match dual_outcome {
        Some(Ok(outcome)) => Some(outcome),
        Some(Err(_)) => {
            // The harness failed on this firmware: a failed check, not a
            // bad argument.
            println!("FAIL: dual: the emulator run panicked");
            return Ok(false);
        }
        None => None,
    };

    let single_verdict = report::judge("single", &single, &single_outcome, options.frames);
    print_verdict("single", &single_verdict);
    let mut passed = single_verdict.failures.is_empty();
    let Some((dual, dual_outcome)) = dual.as_ref().zip(dual_outcome.as_ref()) else {
        passed &= within_period_budget(options.budget_period, &single_verdict);
        passed &= within_frame_budget(options.budget_frame, &single_verdict);
        println!("{}", report::single_summary(&single_verdict));
        return Ok(passed);
    };
    let dual_verdict = report::judge("dual", dual, dual_outcome, options.frames);
    print_verdict("dual", &dual_verdict);
    passed &= dual_verdict.failures.is_empty();
    if let Some(why) = report::incomparable(&single.expected_crcs, &dual.expected_crcs) {
        println!("FAIL: {why}");
        passed = false;
    }
    if let (Some(budget), Some(ratio)) = (
        options.budget_ratio,
        report::period_ratio(&single_verdict, &dual_verdict),
    ) && ratio > budget
    {
        println!("FAIL: period ratio {ratio:.3} is over the budget of {budget:.3}");
        passed = false;
    }
    passed &= within_period_budget(options.budget_period, &dual_verdict);
    passed &= within_frame_budget(options.budget_frame, &dual_verdict);
    println!("{}", report::dual_summary(&single_verdict, &dual_verdict));
    Ok(passed)
}

/// Whether the median period of `verdict` is within `budget` cycles
/// (`--budget-period`; none given: yes), saying why not.
fn within_period_budget(budget: Option<u64>, verdict: &Verdict) -> bool {
    match (budget, verdict.median_period) {
        (Some(budget), Some(period)) if period > budget => {
            println!("FAIL: median period {period} cycles is over the budget of {budget}");
            false
        }
        _ => true,
    }
}

/// Whether every checked frame's period in `verdict` is within `budget`
/// cycles (`--budget-frame`; none given: yes), saying which is not.
fn within_frame_budget(budget: Option<u64>, verdict: &Verdict) -> bool {
    match (budget, verdict.slowest_frame) {
        (Some(budget), Some((frame, period))) if period > budget => {
            println!("FAIL: frame {frame}'s period {period} cycles is over the budget of {budget}");
            false
        }
        _ => true,
    }
}

/// The boot ROM module: `--bootrom`, else `$ZLINE_RP2040_BOOTROM`, else the
/// emulator folder beside the repository.
fn bootrom_path(options: &Options) -> PathBuf {
    options
        .bootrom
        .clone()
        .or_else(|| std::env::var_os(bootrom::ENV_VAR).map(PathBuf::from))
        .unwrap_or_else(bootrom::default_path)
}

/// Prints a run's frame and detail lines, then its failures.
fn print_verdict(label: &str, verdict: &Verdict) {
    for line in &verdict.lines {
        println!("{line}");
    }
    for failure in &verdict.failures {
        println!("FAIL: {label}: {failure}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn verdict(median_period: u64, slowest: (usize, u64)) -> Verdict {
        Verdict {
            lines: Vec::new(),
            failures: Vec::new(),
            median_period: Some(median_period),
            slowest_frame: Some(slowest),
            crc_ok: true,
        }
    }

    /// The median budget passes a run whose first frame alone is over it;
    /// the frame budget does not.
    #[test]
    fn the_frame_budget_holds_every_frame() {
        let run = verdict(3_900_000, (1, 5_100_000));
        assert!(within_period_budget(Some(5_000_000), &run));
        assert!(!within_frame_budget(Some(5_000_000), &run));
        assert!(within_frame_budget(Some(5_100_000), &run));
        assert!(within_frame_budget(None, &run));
    }
}
