//! Just enough of a 32-bit little-endian ELF file: its loadable segments
//! (what goes to flash, by physical address) and its symbols, with the
//! initial value of a static read from the segment that holds it.

use std::fmt;

/// `PT_LOAD`: a segment the loader copies into memory.
const PT_LOAD: u32 = 1;
/// `SHT_SYMTAB`: the full symbol table.
const SHT_SYMTAB: u32 = 2;
/// Size of one `Elf32_Sym`.
const SYM_SIZE: usize = 16;
/// `STT_OBJECT`: a data object (a static).
pub const STT_OBJECT: u8 = 1;
/// `STT_FUNC`: a function.
pub const STT_FUNC: u8 = 2;

/// Why an ELF file could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ElfError {
    /// Not an ELF file, or not 32-bit little-endian.
    NotElf32Le,
    /// A header or table points outside the file.
    Truncated(&'static str),
    /// No symbol of that name (with what was looked for).
    NoSymbol(String),
    /// More than one static of that name (the mangled names found).
    Ambiguous(String, Vec<String>),
    /// The symbol's address is not in a loaded segment's file bytes.
    NotLoaded(String),
}

impl fmt::Display for ElfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotElf32Le => write!(f, "not a 32-bit little-endian ELF file"),
            Self::Truncated(what) => write!(f, "truncated ELF file ({what} out of bounds)"),
            Self::NoSymbol(name) => write!(f, "no symbol {name} (is it #[used]?)"),
            Self::Ambiguous(name, found) => {
                write!(f, "more than one static named {name}: {}", found.join(", "))
            }
            Self::NotLoaded(name) => write!(f, "{name} is not in a loaded segment"),
        }
    }
}

impl std::error::Error for ElfError {}

/// One `PT_LOAD` program header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Segment {
    /// Where the segment's bytes are in the file.
    pub offset: u32,
    /// Run-time (virtual) address.
    pub vaddr: u32,
    /// Load (physical) address: where its bytes are stored (flash for
    /// `.data`, which the start-up code copies to RAM).
    pub paddr: u32,
    /// Bytes in the file.
    pub filesz: u32,
    /// Bytes in memory (`.bss` is all memory, no file).
    pub memsz: u32,
}

/// One symbol of the symbol table.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Symbol {
    /// Its name as stored (mangled for Rust items without `#[no_mangle]`).
    pub name: String,
    /// Its address (with the Thumb bit for functions).
    pub value: u32,
    /// Its size in bytes.
    pub size: u32,
    /// Its type (`STT_*`).
    pub kind: u8,
}

/// A parsed ELF file, borrowing its bytes.
#[derive(Debug)]
pub struct Elf<'a> {
    data: &'a [u8],
    segments: Vec<Segment>,
    symbols: Vec<Symbol>,
}

impl<'a> Elf<'a> {
    /// Reads the headers, the `PT_LOAD` segments and the symbol table.
    pub fn parse(data: &'a [u8]) -> Result<Self, ElfError> {
        if data.len() < 52 || &data[..4] != b"\x7fELF" || data[4] != 1 || data[5] != 1 {
            return Err(ElfError::NotElf32Le);
        }
        let phoff = u32_at(data, 0x1C, "e_phoff")? as usize;
        let shoff = u32_at(data, 0x20, "e_shoff")? as usize;
        let phentsize = usize::from(u16_at(data, 0x2A, "e_phentsize")?);
        let phnum = usize::from(u16_at(data, 0x2C, "e_phnum")?);
        let shentsize = usize::from(u16_at(data, 0x2E, "e_shentsize")?);
        let shnum = usize::from(u16_at(data, 0x30, "e_shnum")?);

        let mut segments = Vec::new();
        for i in 0..phnum {
            let ph = phoff + i * phentsize;
            if u32_at(data, ph, "program header")? != PT_LOAD {
                continue;
            }
            segments.push(Segment {
                offset: u32_at(data, ph + 4, "program header")?,
                vaddr: u32_at(data, ph + 8, "program header")?,
                paddr: u32_at(data, ph + 12, "program header")?,
                filesz: u32_at(data, ph + 16, "program header")?,
                memsz: u32_at(data, ph + 20, "program header")?,
            });
        }
        for s in &segments {
            bytes_at(data, s.offset as usize, s.filesz as usize, "segment")?;
        }

        let mut symbols = Vec::new();
        for i in 0..shnum {
            let sh = shoff + i * shentsize;
            if u32_at(data, sh + 4, "section header")? != SHT_SYMTAB {
                continue;
            }
            let offset = u32_at(data, sh + 16, "section header")? as usize;
            let size = u32_at(data, sh + 20, "section header")? as usize;
            let link = u32_at(data, sh + 24, "section header")? as usize;
            let strtab = u32_at(data, shoff + link * shentsize + 16, "string table header")?;
            let table = bytes_at(data, offset, size, "symbol table")?;
            for entry in table.chunks_exact(SYM_SIZE) {
                let name_off = u32_at(entry, 0, "symbol")? as usize;
                symbols.push(Symbol {
                    name: c_string(data, strtab as usize + name_off)?,
                    value: u32_at(entry, 4, "symbol")?,
                    size: u32_at(entry, 8, "symbol")?,
                    kind: entry[12] & 0xF,
                });
            }
        }
        Ok(Self {
            data,
            segments,
            symbols,
        })
    }

    /// The `PT_LOAD` segments.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The bytes a segment stores in the file.
    pub fn segment_bytes(&self, segment: &Segment) -> &'a [u8] {
        let start = segment.offset as usize;
        // Checked in `parse`.
        &self.data[start..start + segment.filesz as usize]
    }

    /// Every symbol, in table order.
    pub fn symbols(&self) -> &[Symbol] {
        &self.symbols
    }

    /// The symbol named exactly `name`.
    pub fn symbol(&self, name: &str) -> Option<&Symbol> {
        self.symbols.iter().find(|s| s.name == name)
    }

    /// The static `name`: the object symbol of exactly that name (a
    /// `#[no_mangle]` static), else the one Rust object symbol whose
    /// mangled path ends in `name` (e.g. `zline_rp2040::FAULT`, as
    /// `_ZN12zline_rp20405FAULT17h<hash>E` or, in the v0 scheme,
    /// `_RNvCs<hash>_12zline_rp20405FAULT`).
    pub fn rust_static(&self, name: &str) -> Result<&Symbol, ElfError> {
        if let Some(s) = self.symbol(name) {
            return Ok(s);
        }
        let found: Vec<&Symbol> = self
            .symbols
            .iter()
            .filter(|s| s.kind == STT_OBJECT && last_path_component(&s.name) == Some(name))
            .collect();
        match found.as_slice() {
            [] => Err(ElfError::NoSymbol(name.to_string())),
            [one] => Ok(one),
            many => Err(ElfError::Ambiguous(
                name.to_string(),
                many.iter().map(|s| s.name.clone()).collect(),
            )),
        }
    }

    /// The initial value of `symbol` (a static with an initialiser) as
    /// little-endian 32-bit words, read from the loaded segment whose
    /// run-time addresses hold it.
    pub fn initial_words(&self, symbol: &Symbol) -> Result<Vec<u32>, ElfError> {
        let segment = self
            .segments
            .iter()
            .find(|s| {
                symbol.value >= s.vaddr
                    && u64::from(symbol.value) + u64::from(symbol.size)
                        <= u64::from(s.vaddr) + u64::from(s.filesz)
            })
            .ok_or_else(|| ElfError::NotLoaded(symbol.name.clone()))?;
        let start = (symbol.value - segment.vaddr) as usize;
        let bytes = &self.segment_bytes(segment)[start..start + symbol.size as usize];
        Ok(bytes
            .chunks_exact(4)
            .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
            .collect())
    }
}

/// The last path component of a mangled Rust symbol, legacy or v0.
fn last_path_component(name: &str) -> Option<&str> {
    legacy_last_component(name).or_else(|| v0_last_component(name))
}

/// The last identifier of a v0-mangled Rust path made of crate roots and
/// nested names only (`_R[N<ns>]…C[s<n>_]<len>crate…<len>ident`); `None`
/// for anything else (generics, back-references, Punycode).
fn v0_last_component(name: &str) -> Option<&str> {
    fn path(s: &str) -> Option<(&str, &str)> {
        match s.as_bytes().first()? {
            b'C' => identifier(&s[1..]),
            b'N' => {
                let (_, rest) = path(s.get(2..)?)?;
                identifier(rest)
            }
            _ => None,
        }
    }
    fn identifier(s: &str) -> Option<(&str, &str)> {
        let mut s = s;
        if let Some(rest) = s.strip_prefix('s') {
            s = &rest[rest.find('_')? + 1..];
        }
        let digits = s.bytes().take_while(u8::is_ascii_digit).count();
        let len: usize = s.get(..digits)?.parse().ok()?;
        let mut rest = &s[digits..];
        if let Some(after) = rest.strip_prefix('_') {
            rest = after;
        }
        Some((rest.get(..len)?, &rest[len..]))
    }
    let (last, _) = path(name.strip_prefix("_R")?)?;
    Some(last)
}

/// The last path component of a legacy-mangled Rust symbol
/// (`_ZN<len><ident>…17h<16 hex>E`), the hash left out; `None` for
/// anything else.
fn legacy_last_component(name: &str) -> Option<&str> {
    let mut rest = name.strip_prefix("_ZN")?;
    let mut components = Vec::new();
    while !rest.starts_with('E') {
        let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
        let len: usize = rest[..digits].parse().ok()?;
        let ident = rest.get(digits..digits + len)?;
        components.push(ident);
        rest = &rest[digits + len..];
    }
    let is_hash = |c: &&str| {
        c.len() == 17 && c.starts_with('h') && c[1..].bytes().all(|b| b.is_ascii_hexdigit())
    };
    match components.as_slice() {
        [.., last, hash] if is_hash(hash) => Some(last),
        [.., last] => Some(last),
        [] => None,
    }
}

fn bytes_at<'d>(
    data: &'d [u8],
    offset: usize,
    len: usize,
    what: &'static str,
) -> Result<&'d [u8], ElfError> {
    offset
        .checked_add(len)
        .and_then(|end| data.get(offset..end))
        .ok_or(ElfError::Truncated(what))
}

fn u16_at(data: &[u8], offset: usize, what: &'static str) -> Result<u16, ElfError> {
    let b = bytes_at(data, offset, 2, what)?;
    Ok(u16::from_le_bytes([b[0], b[1]]))
}

fn u32_at(data: &[u8], offset: usize, what: &'static str) -> Result<u32, ElfError> {
    let b = bytes_at(data, offset, 4, what)?;
    Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// The NUL-terminated string at `offset`.
fn c_string(data: &[u8], offset: usize) -> Result<String, ElfError> {
    let tail = data
        .get(offset..)
        .ok_or(ElfError::Truncated("symbol name"))?;
    let end = tail
        .iter()
        .position(|&b| b == 0)
        .ok_or(ElfError::Truncated("symbol name"))?;
    Ok(String::from_utf8_lossy(&tail[..end]).into_owned())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A symbol for [`build_elf`]: name, value, size, type.
    pub(crate) type TestSymbol<'a> = (&'a str, u32, u32, u8);

    /// A minimal ELF: one `PT_LOAD` segment of `payload` at `vaddr`
    /// (physical address `paddr`), a symbol table and its strings.
    pub(crate) fn build_elf(
        vaddr: u32,
        paddr: u32,
        payload: &[u8],
        symbols: &[TestSymbol<'_>],
    ) -> Vec<u8> {
        let mut strtab = vec![0u8];
        let mut symtab = vec![0u8; SYM_SIZE]; // the null symbol
        for &(name, value, size, kind) in symbols {
            let name_off = strtab.len() as u32;
            strtab.extend_from_slice(name.as_bytes());
            strtab.push(0);
            symtab.extend_from_slice(&name_off.to_le_bytes());
            symtab.extend_from_slice(&value.to_le_bytes());
            symtab.extend_from_slice(&size.to_le_bytes());
            symtab.extend_from_slice(&[kind, 0, 1, 0]);
        }
        let phoff = 52u32;
        let payload_off = phoff + 32;
        let symtab_off = payload_off + payload.len() as u32;
        let strtab_off = symtab_off + symtab.len() as u32;
        let shoff = strtab_off + strtab.len() as u32;

        let mut elf = Vec::new();
        elf.extend_from_slice(b"\x7fELF\x01\x01\x01\0\0\0\0\0\0\0\0\0");
        elf.extend_from_slice(&2u16.to_le_bytes()); // ET_EXEC
        elf.extend_from_slice(&40u16.to_le_bytes()); // EM_ARM
        elf.extend_from_slice(&1u32.to_le_bytes());
        elf.extend_from_slice(&vaddr.to_le_bytes()); // entry
        elf.extend_from_slice(&phoff.to_le_bytes());
        elf.extend_from_slice(&shoff.to_le_bytes());
        elf.extend_from_slice(&0u32.to_le_bytes()); // flags
        for v in [52u16, 32, 1, 40, 3, 0] {
            // ehsize, phentsize, phnum, shentsize, shnum, shstrndx
            elf.extend_from_slice(&v.to_le_bytes());
        }
        let len = payload.len() as u32;
        for v in [PT_LOAD, payload_off, vaddr, paddr, len, len, 5, 4] {
            elf.extend_from_slice(&v.to_le_bytes());
        }
        elf.extend_from_slice(payload);
        elf.extend_from_slice(&symtab);
        elf.extend_from_slice(&strtab);
        let sections: [[u32; 10]; 3] = [
            [0; 10],
            [
                0,
                SHT_SYMTAB,
                0,
                0,
                symtab_off,
                symtab.len() as u32,
                2,
                1,
                4,
                16,
            ],
            [0, 3, 0, 0, strtab_off, strtab.len() as u32, 0, 0, 1, 0],
        ];
        for section in sections {
            for v in section {
                elf.extend_from_slice(&v.to_le_bytes());
            }
        }
        elf
    }

    #[test]
    fn reads_segments_and_a_no_mangle_static() {
        let payload: Vec<u8> = [0xDEAD_BEEFu32, 7, 0x1234_5678]
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .collect();
        let elf = build_elf(
            0x1000_0100,
            0x1000_0100,
            &payload,
            &[("EXPECTED_CRCS", 0x1000_0104, 8, STT_OBJECT)],
        );
        let elf = Elf::parse(&elf).expect("parses");
        assert_eq!(elf.segments().len(), 1);
        assert_eq!(elf.segment_bytes(&elf.segments()[0]), payload.as_slice());
        let sym = elf.rust_static("EXPECTED_CRCS").expect("found");
        assert_eq!(elf.initial_words(sym), Ok(vec![7, 0x1234_5678]));
    }

    #[test]
    fn finds_a_mangled_static_by_its_last_path_component() {
        let elf = build_elf(
            0x2000_0000,
            0x1000_4000,
            &[0; 8],
            &[
                (
                    "_ZN12zline_rp20405FAULT17h9bac2a14d01da009E",
                    0x2000_0004,
                    4,
                    STT_OBJECT,
                ),
                (
                    "_ZN12zline_rp20408FRAME_US17h8b1b21e3c314dae4E",
                    0x2000_0000,
                    4,
                    STT_OBJECT,
                ),
                (
                    "_ZN4core5FAULT17h0000000000000000E",
                    0x1000_0000,
                    4,
                    STT_FUNC,
                ),
            ],
        );
        let elf = Elf::parse(&elf).expect("parses");
        assert_eq!(elf.rust_static("FAULT").map(|s| s.value), Ok(0x2000_0004));
        assert_eq!(
            elf.rust_static("FRAME_US").map(|s| s.value),
            Ok(0x2000_0000)
        );
        assert!(matches!(
            elf.rust_static("FRAMES"),
            Err(ElfError::NoSymbol(_))
        ));
    }

    #[test]
    fn two_statics_of_one_name_are_ambiguous() {
        let elf = build_elf(
            0x2000_0000,
            0x2000_0000,
            &[0; 8],
            &[
                (
                    "_ZN1a5FAULT17h0000000000000000E",
                    0x2000_0000,
                    4,
                    STT_OBJECT,
                ),
                (
                    "_ZN1b5FAULT17h1111111111111111E",
                    0x2000_0004,
                    4,
                    STT_OBJECT,
                ),
            ],
        );
        let elf = Elf::parse(&elf).expect("parses");
        assert!(matches!(
            elf.rust_static("FAULT"),
            Err(ElfError::Ambiguous(..))
        ));
    }

    #[test]
    fn a_static_outside_the_file_bytes_is_not_loaded() {
        let elf = build_elf(
            0x1000_0000,
            0x1000_0000,
            &[0; 4],
            &[("X", 0x1000_0002, 4, 1)],
        );
        let elf = Elf::parse(&elf).expect("parses");
        let sym = elf.symbol("X").expect("found");
        assert!(matches!(
            elf.initial_words(sym),
            Err(ElfError::NotLoaded(_))
        ));
    }

    #[test]
    fn rejects_non_elf_and_truncated_files() {
        assert_eq!(Elf::parse(b"not an elf").unwrap_err(), ElfError::NotElf32Le);
        let mut elf = build_elf(0, 0, &[0; 4], &[]);
        elf.truncate(90);
        assert!(matches!(Elf::parse(&elf), Err(ElfError::Truncated(_))));
    }

    #[test]
    fn v0_mangling() {
        assert_eq!(
            v0_last_component("_RNvCsk3x_12zline_rp20405FAULT"),
            Some("FAULT")
        );
        assert_eq!(
            v0_last_component("_RNvNtCseold96UKqg_4core9panicking9panic_fmt"),
            Some("panic_fmt")
        );
        assert_eq!(v0_last_component("_RNvCs_3foo4__bar"), Some("_bar"));
        assert_eq!(v0_last_component("_RINvCs_3foo3barEB2_"), None, "generic");
        assert_eq!(last_path_component("_RNvCs1_1a5FAULT"), Some("FAULT"));
    }

    #[test]
    fn legacy_mangling() {
        assert_eq!(
            legacy_last_component("_ZN12zline_rp20405stack11STACK_BYTES17hfd3487ad71a57d58E"),
            Some("STACK_BYTES")
        );
        assert_eq!(legacy_last_component("_ZN3foo3barE"), Some("bar"));
        assert_eq!(legacy_last_component("EXPECTED_CRCS"), None);
        assert_eq!(legacy_last_component("_ZN99shortE"), None);
    }
}
