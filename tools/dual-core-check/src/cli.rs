//! The command line.

use std::path::PathBuf;

use crate::machine::Interleave;

/// The usage message.
pub const USAGE: &str = "\
usage: dual-core-check --single ELF [--dual ELF] [--frames N] [--budget-ratio R]
                       [--budget-period N] [--budget-frame N] [--bootrom PATH]
                       [--quantum Q]
                       [--interleave MODE] [--max-cycles N]

Runs each RP2040 firmware ELF on the emulated RP2040 (rp2040-emu), decodes
what it sends the ST7789 over SPI0, checks every frame's CRC-32 against the
ELF's EXPECTED_CRCS and prints emulated cycles per frame. With --dual, the
last line compares the median frame periods of the two builds.

  --single ELF        the single-core firmware (required)
  --dual ELF          the dual-core build of the same firmware (the same
                      EXPECTED_CRCS, else the check fails)
  --frames N          frames to check after the start-up clear (default 4)
  --budget-ratio R    fail if the dual/single period ratio exceeds R (needs --dual)
  --budget-period N   fail if the median frame period (the dual build's, with
                      --dual) exceeds N cycles (at 125 MHz, 5,000,000 is 25 fps)
  --budget-frame N    fail if any checked frame's period (the dual build's, with
                      --dual) exceeds N cycles: the slowest frame, not the median
  --bootrom PATH      the boot ROM module, rp2040js's bootrom.mjs (default:
                      $ZLINE_RP2040_BOOTROM, else ../shared/rp2040-emu/bootrom.mjs
                      beside the repository)
  --quantum Q         cycles per scheduling quantum (default 4; the emulator's DMA
                      moves one word a quantum, so keep it at most 4)
  --interleave MODE   how the two cores share the clock: lockstep (default,
                      rp2040-emu's model: one instruction of each core a round,
                      the clock advancing by the longer), independent (each
                      core on its own clock, synchronised every quantum) or
                      contended (independent, and a core waits a cycle for a
                      bus slave, an SRAM bank or the XIP cache, the other
                      core holds in that cycle)
  --max-cycles N      give up after N emulated cycles per firmware
                      (default 100,000,000 + 20,000,000 × (N + 2))
  -h, --help          this message

Exit status: 0 when every frame matches; 1 on a CRC mismatch, a missing
frame, a fault, a ratio over the budget, builds of different frames or a
panic of the emulator; 2 on bad arguments or files.";

/// Default `--frames`.
pub const DEFAULT_FRAMES: usize = 4;
/// Default `--quantum`.
pub const DEFAULT_QUANTUM: u32 = 4;

/// What the command line asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// The single-core firmware.
    pub single: PathBuf,
    /// The dual-core firmware, if any.
    pub dual: Option<PathBuf>,
    /// Frames to check after the start-up clear.
    pub frames: usize,
    /// Largest dual/single period ratio accepted.
    pub budget_ratio: Option<f64>,
    /// Largest median frame period accepted, in cycles (the dual build's
    /// when there is one).
    pub budget_period: Option<u64>,
    /// Largest period accepted of any checked frame, in cycles (the dual
    /// build's when there is one).
    pub budget_frame: Option<u64>,
    /// The boot ROM module, if given.
    pub bootrom: Option<PathBuf>,
    /// Cycles per quantum.
    pub quantum: u32,
    /// How the cores share the clock.
    pub interleave: Interleave,
    /// Cycle limit per firmware, if given.
    pub max_cycles: Option<u64>,
}

impl Options {
    /// The cycle limit: `--max-cycles`, else enough for the start-up and
    /// the frames at several times the expected period.
    pub fn cycle_limit(&self) -> u64 {
        self.max_cycles
            .unwrap_or(100_000_000 + 20_000_000 * (self.frames as u64 + 2))
    }
}

/// A parsed command line.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    /// Run the checks.
    Run(Options),
    /// Print the usage message.
    Help,
}

/// Parses the arguments after the program name.
pub fn parse(args: impl IntoIterator<Item = String>) -> Result<Command, String> {
    let mut single = None;
    let mut dual = None;
    let mut frames = None;
    let mut budget_ratio = None;
    let mut budget_period = None;
    let mut budget_frame = None;
    let mut bootrom = None;
    let mut quantum = None;
    let mut max_cycles = None;
    let mut interleave = None;
    let mut args = args.into_iter();
    while let Some(arg) = args.next() {
        if arg == "-h" || arg == "--help" {
            return Ok(Command::Help);
        }
        let (flag, inline) = match arg.split_once('=') {
            Some((flag, value)) if flag.starts_with("--") => {
                (flag.to_string(), Some(value.to_string()))
            }
            _ => (arg.clone(), None),
        };
        let mut value = || {
            inline
                .clone()
                .or_else(|| args.next())
                .ok_or_else(|| format!("{flag} needs a value"))
        };
        match flag.as_str() {
            "--single" => set(&mut single, &flag, PathBuf::from(value()?))?,
            "--dual" => set(&mut dual, &flag, PathBuf::from(value()?))?,
            "--bootrom" => set(&mut bootrom, &flag, PathBuf::from(value()?))?,
            "--frames" => set(&mut frames, &flag, number::<usize>(&flag, &value()?)?)?,
            "--quantum" => set(&mut quantum, &flag, number::<u32>(&flag, &value()?)?)?,
            "--max-cycles" => set(&mut max_cycles, &flag, number::<u64>(&flag, &value()?)?)?,
            "--budget-ratio" => set(&mut budget_ratio, &flag, ratio(&value()?)?)?,
            "--budget-period" => set(&mut budget_period, &flag, number::<u64>(&flag, &value()?)?)?,
            "--budget-frame" => set(&mut budget_frame, &flag, number::<u64>(&flag, &value()?)?)?,
            "--interleave" => set(&mut interleave, &flag, interleave_mode(&value()?)?)?,
            other => return Err(format!("unknown argument {other:?}")),
        }
    }
    let single = single.ok_or("--single ELF is required")?;
    let frames = frames.unwrap_or(DEFAULT_FRAMES);
    if frames == 0 {
        return Err("--frames must be at least 1".into());
    }
    let quantum = quantum.unwrap_or(DEFAULT_QUANTUM);
    if quantum == 0 {
        return Err("--quantum must be at least 1".into());
    }
    if budget_ratio.is_some() && dual.is_none() {
        return Err("--budget-ratio compares two builds: it needs --dual".into());
    }
    Ok(Command::Run(Options {
        single,
        dual,
        frames,
        budget_ratio,
        budget_period,
        budget_frame,
        bootrom,
        quantum,
        interleave: interleave.unwrap_or(Interleave::Lockstep),
        max_cycles,
    }))
}

/// Stores `value` in `slot`, refusing a flag given twice.
fn set<T>(slot: &mut Option<T>, flag: &str, value: T) -> Result<(), String> {
    if slot.replace(value).is_some() {
        return Err(format!("{flag} is given twice"));
    }
    Ok(())
}

/// A whole number (`_` and `,` allowed as digit separators).
fn number<T: std::str::FromStr>(flag: &str, text: &str) -> Result<T, String> {
    let digits: String = text.chars().filter(|&c| c != '_' && c != ',').collect();
    digits
        .parse()
        .map_err(|_| format!("{flag} takes a whole number, not {text:?}"))
}

/// `lockstep`, `independent` or `contended`.
fn interleave_mode(text: &str) -> Result<Interleave, String> {
    match text {
        "lockstep" => Ok(Interleave::Lockstep),
        "independent" => Ok(Interleave::Independent),
        "contended" => Ok(Interleave::Contended),
        _ => Err(format!(
            "--interleave takes lockstep, independent or contended, not {text:?}"
        )),
    }
}

/// A positive, finite ratio.
fn ratio(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(r) if r.is_finite() && r > 0.0 => Ok(r),
        _ => Err(format!(
            "--budget-ratio takes a positive number, not {text:?}"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_args(args: &[&str]) -> Result<Command, String> {
        parse(args.iter().map(|s| s.to_string()))
    }

    #[test]
    fn defaults() {
        let Ok(Command::Run(o)) = parse_args(&["--single", "a.elf"]) else {
            panic!("parses");
        };
        assert_eq!(o.single, PathBuf::from("a.elf"));
        assert_eq!((o.dual, o.frames, o.quantum), (None, 4, 4));
        assert_eq!(
            (o.budget_ratio, o.bootrom, o.max_cycles),
            (None, None, None)
        );
        assert_eq!((o.budget_period, o.budget_frame), (None, None));
        assert_eq!(o.interleave, Interleave::Lockstep);
    }

    #[test]
    fn every_option() {
        let parsed = parse_args(&[
            "--single",
            "s",
            "--dual=d",
            "--frames",
            "5",
            "--budget-ratio",
            "0.6",
            "--budget-period=5_000_000",
            "--budget-frame",
            "5_100_000",
            "--bootrom",
            "rom.mjs",
            "--quantum=2",
            "--max-cycles",
            "1_000_000",
            "--interleave",
            "independent",
        ]);
        let Ok(Command::Run(o)) = parsed else {
            panic!("parses: {parsed:?}");
        };
        assert_eq!(o.dual, Some(PathBuf::from("d")));
        assert_eq!((o.frames, o.quantum, o.max_cycles), (5, 2, Some(1_000_000)));
        assert_eq!(o.budget_ratio, Some(0.6));
        assert_eq!(o.budget_period, Some(5_000_000));
        assert_eq!(o.budget_frame, Some(5_100_000));
        assert_eq!(o.bootrom, Some(PathBuf::from("rom.mjs")));
        assert_eq!(o.interleave, Interleave::Independent);
    }

    #[test]
    fn errors() {
        assert!(parse_args(&[]).is_err());
        assert!(parse_args(&["--single"]).is_err());
        assert!(parse_args(&["--single", "a", "--frames", "x"]).is_err());
        assert!(parse_args(&["--single", "a", "--frames", "0"]).is_err());
        assert!(parse_args(&["--single", "a", "--budget-ratio", "1.1"]).is_err());
        assert!(parse_args(&["--single", "a", "--dual", "b", "--budget-ratio", "-1"]).is_err());
        assert!(parse_args(&["--single", "a", "--single", "b"]).is_err());
        assert!(parse_args(&["--single", "a", "--budget-period", "25fps"]).is_err());
        assert!(parse_args(&["--single", "a", "--budget-frame", "-1"]).is_err());
        assert!(parse_args(&["--single", "a", "--wat"]).is_err());
        assert!(parse_args(&["--single", "a", "--interleave", "both"]).is_err());
        let Ok(Command::Run(o)) = parse_args(&["--single", "a", "--interleave", "contended"])
        else {
            panic!("parses");
        };
        assert_eq!(o.interleave, Interleave::Contended);
        assert_eq!(parse_args(&["--single", "a", "-h"]), Ok(Command::Help));
    }
}
