//! The RP2040 boot ROM, read at run time from the JavaScript module rp2040js
//! ships it in (`../shared/rp2040-emu/bootrom.mjs`: an
//! `export const … = new Uint32Array([0x…, …]);` of little-endian words).
//! The firmware calls the ROM's routines (memcpy, memset, float helpers)
//! through its function table, so the emulator needs the real image.

use std::fmt;
use std::path::{Path, PathBuf};

/// Size of the RP2040 boot ROM.
pub const ROM_BYTES: usize = 16 * 1024;

/// Environment variable that names the boot ROM module when `--bootrom` is
/// not given.
pub const ENV_VAR: &str = "ZLINE_RP2040_BOOTROM";

/// Where the module is when neither `--bootrom` nor [`ENV_VAR`] says: the
/// emulator folder next to the repository (`../shared/rp2040-emu`).
pub fn default_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/rp2040-emu/bootrom.mjs")
}

/// Why the boot ROM could not be read.
#[derive(Debug)]
pub enum BootromError {
    /// The file could not be read.
    Io(PathBuf, std::io::Error),
    /// The text has no `Uint32Array([ … ])`.
    NoArray,
    /// An element of the array is not a 32-bit number.
    BadWord(String),
    /// The array is not 16 KiB.
    WrongSize(usize),
}

impl fmt::Display for BootromError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io(path, e) => write!(f, "cannot read the boot ROM {}: {e}", path.display()),
            Self::NoArray => write!(f, "the boot ROM module has no `Uint32Array([...])`"),
            Self::BadWord(word) => write!(f, "the boot ROM module has a bad word {word:?}"),
            Self::WrongSize(n) => {
                write!(f, "the boot ROM module holds {n} bytes, not {ROM_BYTES}")
            }
        }
    }
}

impl std::error::Error for BootromError {}

/// Reads the boot ROM module at `path` and returns the image's bytes.
pub fn load(path: &Path) -> Result<Vec<u8>, BootromError> {
    let text =
        std::fs::read_to_string(path).map_err(|e| BootromError::Io(path.to_path_buf(), e))?;
    parse(&text)
}

/// The image in the module's text: the words of its first
/// `Uint32Array([ … ])`, little-endian. `//` comments are skipped.
pub fn parse(text: &str) -> Result<Vec<u8>, BootromError> {
    let open = "Uint32Array([";
    let start = text.find(open).ok_or(BootromError::NoArray)? + open.len();
    let len = text[start..].find(']').ok_or(BootromError::NoArray)?;
    let mut bytes = Vec::with_capacity(ROM_BYTES);
    for line in text[start..start + len].lines() {
        let code = line.split("//").next().unwrap_or("");
        for token in code.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            bytes.extend_from_slice(&parse_word(token)?.to_le_bytes());
        }
    }
    if bytes.len() != ROM_BYTES {
        return Err(BootromError::WrongSize(bytes.len()));
    }
    Ok(bytes)
}

/// One element: hexadecimal (`0x…`) or decimal.
fn parse_word(token: &str) -> Result<u32, BootromError> {
    let parsed = match token
        .strip_prefix("0x")
        .or_else(|| token.strip_prefix("0X"))
    {
        Some(hex) => u32::from_str_radix(hex, 16),
        None => token.parse(),
    };
    parsed.map_err(|_| BootromError::BadWord(token.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A module of `words` in the layout of rp2040js's, eight a line.
    fn module(words: &[u32]) -> String {
        let mut text = String::from("// boot ROM\nexport const rom = new Uint32Array([\n");
        for chunk in words.chunks(8) {
            let line: Vec<String> = chunk.iter().map(|w| format!("0x{w:08x}")).collect();
            text.push_str("  ");
            text.push_str(&line.join(", "));
            text.push_str(",\n");
        }
        text.push_str("]);\n");
        text
    }

    #[test]
    fn parses_little_endian_words() {
        let mut words = vec![0u32; ROM_BYTES / 4];
        words[0] = 0x2004_1F00;
        words[1] = 0x0000_00EF;
        words[4095] = 0xBE00_BE00;
        let rom = parse(&module(&words)).expect("parses");
        assert_eq!(rom.len(), ROM_BYTES);
        assert_eq!(&rom[..8], &[0x00, 0x1F, 0x04, 0x20, 0xEF, 0, 0, 0]);
        assert_eq!(&rom[ROM_BYTES - 4..], &[0x00, 0xBE, 0x00, 0xBE]);
    }

    #[test]
    fn rejects_wrong_size_and_bad_words() {
        assert!(matches!(
            parse(&module(&[1, 2, 3])),
            Err(BootromError::WrongSize(12))
        ));
        assert!(matches!(
            parse("new Uint32Array([0x12, zz]);"),
            Err(BootromError::BadWord(_))
        ));
        assert!(matches!(parse("nothing here"), Err(BootromError::NoArray)));
    }
}
