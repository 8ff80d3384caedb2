//! A firmware ELF as the harness needs it: its flash image, the expected
//! CRC of each view, and where its diagnostic statics and panic loop are.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::elf::{Elf, ElfError, STT_FUNC};

/// Where the RP2040 maps flash (XIP).
pub const FLASH_BASE: u32 = 0x1000_0000;
/// The emulator's flash size.
pub const FLASH_SIZE: u32 = 2 * 1024 * 1024;
/// Where the RP2040's SRAM is.
const SRAM: std::ops::Range<u32> = 0x2000_0000..0x2004_2000;

/// Why a firmware could not be used.
#[derive(Debug)]
pub enum FirmwareError {
    /// The file could not be read.
    Io(PathBuf, std::io::Error),
    /// The ELF file could not be read or lacks a symbol.
    Elf(PathBuf, ElfError),
    /// A segment is to be loaded outside flash and SRAM.
    Segment(PathBuf, u32),
    /// `EXPECTED_CRCS` is empty.
    NoCrcs(PathBuf),
}

impl fmt::Display for FirmwareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io(path, e) => write!(f, "cannot read {}: {e}", path.display()),
            Self::Elf(path, e) => write!(f, "{}: {e}", path.display()),
            Self::Segment(path, address) => write!(
                f,
                "{}: a segment loads at {address:#010x}, outside flash and SRAM",
                path.display()
            ),
            Self::NoCrcs(path) => write!(f, "{}: EXPECTED_CRCS is empty", path.display()),
        }
    }
}

impl std::error::Error for FirmwareError {}

/// A firmware ready to run.
#[derive(Debug, Clone)]
pub struct Firmware {
    /// The flash image from offset 0 (boot2, vector table, code, `.data`'s
    /// initial values).
    pub flash: Vec<u8>,
    /// Segments stored straight in SRAM (none in a flash image), by
    /// address.
    pub sram: Vec<(u32, Vec<u8>)>,
    /// Each view's expected CRC-32 (`EXPECTED_CRCS`): frame `k >= 1` shows
    /// view `(k - 1) % len`.
    pub expected_crcs: Vec<u32>,
    /// Address of `FAULT` (0: start-up went well), if the ELF keeps it.
    pub fault: Option<u32>,
    /// Address of `FRAMES` (frames sent whole), if kept.
    pub frames: Option<u32>,
    /// Address of `FRAME_US` (the firmware's own frame period), if kept.
    pub frame_us: Option<u32>,
    /// Address of `CORE1_HIGH_WATER_BYTES` (core 1's stack use; the
    /// dual-core build's), if kept.
    pub core1_stack: Option<u32>,
    /// Address ranges of the panic functions (`panic-halt` spins in them).
    pub panic_code: Vec<std::ops::Range<u32>>,
}

impl Firmware {
    /// Reads the ELF file at `path`.
    pub fn load(path: &Path) -> Result<Self, FirmwareError> {
        let data = std::fs::read(path).map_err(|e| FirmwareError::Io(path.to_path_buf(), e))?;
        Self::from_elf(&data).map_err(|e| match e {
            LoadError::Elf(e) => FirmwareError::Elf(path.to_path_buf(), e),
            LoadError::Segment(address) => FirmwareError::Segment(path.to_path_buf(), address),
            LoadError::NoCrcs => FirmwareError::NoCrcs(path.to_path_buf()),
        })
    }

    fn from_elf(data: &[u8]) -> Result<Self, LoadError> {
        let elf = Elf::parse(data).map_err(LoadError::Elf)?;
        let mut flash = Vec::new();
        let mut sram = Vec::new();
        for segment in elf.segments().iter().filter(|s| s.filesz > 0) {
            let bytes = elf.segment_bytes(segment);
            let start = segment.paddr;
            let end = u64::from(start) + u64::from(segment.filesz);
            if start >= FLASH_BASE && end <= u64::from(FLASH_BASE + FLASH_SIZE) {
                let offset = (start - FLASH_BASE) as usize;
                if flash.len() < offset + bytes.len() {
                    flash.resize(offset + bytes.len(), 0xFF);
                }
                flash[offset..offset + bytes.len()].copy_from_slice(bytes);
            } else if SRAM.contains(&start) && end <= u64::from(SRAM.end) {
                sram.push((start, bytes.to_vec()));
            } else {
                return Err(LoadError::Segment(start));
            }
        }
        let crcs = elf.rust_static("EXPECTED_CRCS").map_err(LoadError::Elf)?;
        let expected_crcs = elf.initial_words(crcs).map_err(LoadError::Elf)?;
        if expected_crcs.is_empty() {
            return Err(LoadError::NoCrcs);
        }
        let address = |name: &str| elf.rust_static(name).ok().map(|s| s.value);
        let panic_code = elf
            .symbols()
            .iter()
            .filter(|s| s.kind == STT_FUNC && s.size > 0 && is_panic_function(&s.name))
            .map(|s| {
                let start = s.value & !1;
                start..start + s.size
            })
            .collect();
        Ok(Self {
            flash,
            sram,
            expected_crcs,
            fault: address("FAULT"),
            frames: address("FRAMES"),
            frame_us: address("FRAME_US"),
            core1_stack: address("CORE1_HIGH_WATER_BYTES"),
            panic_code,
        })
    }
}

/// What `Firmware::from_elf` can fail on, before the path is attached.
enum LoadError {
    Elf(ElfError),
    Segment(u32),
    NoCrcs,
}

/// The functions a panic ends in: the panic handler and core's
/// `panic_fmt` family, where `panic-halt` loops forever.
fn is_panic_function(name: &str) -> bool {
    name == "rust_begin_unwind" || name.contains("panicking") || name.contains("panic_fmt")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elf::STT_OBJECT;
    use crate::elf::tests::build_elf;

    #[test]
    fn flash_image_expected_crcs_and_statics() {
        let payload: Vec<u8> = [0x2004_0000u32, 0x1000_01C1, 0xAAAA_5555, 0x1234_5678]
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        let elf = build_elf(
            0x1000_0100,
            0x1000_0100,
            &payload,
            &[
                ("EXPECTED_CRCS", 0x1000_0108, 8, STT_OBJECT),
                (
                    "_ZN4fw_x5FAULT17h0123456789abcdefE",
                    0x2000_0010,
                    4,
                    STT_OBJECT,
                ),
                ("rust_begin_unwind", 0x1000_0105, 4, STT_FUNC),
            ],
        );
        let fw = Firmware::from_elf(&elf).unwrap_or_else(|_| panic!("loads"));
        assert_eq!(fw.flash.len(), 0x100 + payload.len());
        assert!(
            fw.flash[..0x100].iter().all(|&b| b == 0xFF),
            "erased flash before"
        );
        assert_eq!(&fw.flash[0x100..], payload.as_slice());
        assert_eq!(fw.expected_crcs, vec![0xAAAA_5555, 0x1234_5678]);
        assert_eq!(fw.fault, Some(0x2000_0010));
        assert_eq!(fw.frames, None);
        assert_eq!(fw.panic_code, vec![0x1000_0104..0x1000_0108]);
    }

    #[test]
    fn a_segment_outside_memory_is_refused() {
        let elf = build_elf(0x4000_0000, 0x4000_0000, &[0; 4], &[]);
        assert!(matches!(
            Firmware::from_elf(&elf),
            Err(LoadError::Segment(0x4000_0000))
        ));
    }
}
