//! The flash and static RAM footprint of a firmware image, read from its ELF32 little-endian
//! section headers (no external tools), and the `key = integer` lines of the budget files
//! (`onboard-demo/size-budget.toml`) it is checked against. Used by `cargo xtask size` /
//! `stack` and by `host-sim`'s PIL tests (static RAM plus the whole-run stack).

use core::fmt;

/// Flash and RAM footprint of a firmware image \[bytes\].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Footprint {
    /// Bytes stored in flash: allocated sections with contents (.vector_table, .text, .rodata,
    /// .data) \[bytes\].
    pub flash: u64,
    /// Bytes of static RAM: writable allocated sections (.data, .bss, .uninit) \[bytes\].
    pub ram: u64,
}

/// Why an image's footprint could not be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElfError {
    /// The file does not start with the ELF magic.
    NotElf,
    /// Not a 32-bit little-endian ELF file.
    NotElf32Le,
    /// A header field lies past the end of the file (its byte offset).
    Truncated(usize),
}

impl fmt::Display for ElfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotElf => write!(f, "not an ELF file"),
            Self::NotElf32Le => write!(f, "not a 32-bit little-endian ELF file"),
            Self::Truncated(off) => write!(f, "ELF truncated at offset {off}"),
        }
    }
}

const SHF_WRITE: u32 = 0x1;
const SHF_ALLOC: u32 = 0x2;
const SHT_NOBITS: u32 = 8;

fn bytes_at<const N: usize>(b: &[u8], off: usize) -> Result<[u8; N], ElfError> {
    off.checked_add(N)
        .and_then(|end| b.get(off..end))
        .and_then(|s| s.try_into().ok())
        .ok_or(ElfError::Truncated(off))
}

fn u16_at(b: &[u8], off: usize) -> Result<u16, ElfError> {
    bytes_at(b, off).map(u16::from_le_bytes)
}

fn u32_at(b: &[u8], off: usize) -> Result<u32, ElfError> {
    bytes_at(b, off).map(u32::from_le_bytes)
}

/// Sum the allocated sections of an ELF32 little-endian file.
///
/// # Errors
/// [`ElfError`] if `bytes` is not an ELF32 little-endian file or is truncated.
pub fn footprint(bytes: &[u8]) -> Result<Footprint, ElfError> {
    if bytes.get(0..4) != Some(b"\x7fELF".as_slice()) {
        return Err(ElfError::NotElf);
    }
    if bytes.get(4) != Some(&1) || bytes.get(5) != Some(&1) {
        return Err(ElfError::NotElf32Le);
    }
    let shoff = u32_at(bytes, 0x20)? as usize;
    let shentsize = usize::from(u16_at(bytes, 0x2E)?);
    let shnum = usize::from(u16_at(bytes, 0x30)?);
    let mut fp = Footprint { flash: 0, ram: 0 };
    for i in 0..shnum {
        let base = i
            .checked_mul(shentsize)
            .and_then(|o| o.checked_add(shoff))
            .ok_or(ElfError::Truncated(usize::MAX))?;
        let sh_type = u32_at(bytes, base.saturating_add(4))?;
        let flags = u32_at(bytes, base.saturating_add(8))?;
        let size = u64::from(u32_at(bytes, base.saturating_add(20))?);
        if flags & SHF_ALLOC == 0 {
            continue;
        }
        if sh_type != SHT_NOBITS {
            fp.flash += size;
        }
        if flags & SHF_WRITE != 0 {
            fp.ram += size;
        }
    }
    Ok(fp)
}

/// Why a budget value could not be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BudgetError {
    /// No `key = ...` line.
    Missing,
    /// The value is not a non-negative integer (`_` separators allowed).
    NotAnInteger,
}

impl fmt::Display for BudgetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Missing => write!(f, "is missing"),
            Self::NotAnInteger => write!(f, "is not a non-negative integer"),
        }
    }
}

/// The value of the first `key = integer` line of a budget file's `text` (`_` separators
/// allowed, e.g. `8_192`); `key` must be the whole key (`a_b` does not match `a_b_c`).
///
/// # Errors
/// [`BudgetError`] if the key is missing or its value is not an integer.
pub fn budget_value(text: &str, key: &str) -> Result<u64, BudgetError> {
    for line in text.lines() {
        if let Some(rest) = line.trim().strip_prefix(key)
            && let Some(v) = rest.trim_start().strip_prefix('=')
        {
            let mut n: u64 = 0;
            let mut digits = 0;
            for c in v.trim().chars().filter(|&c| c != '_') {
                let d = c.to_digit(10).ok_or(BudgetError::NotAnInteger)?;
                n = n
                    .checked_mul(10)
                    .and_then(|n| n.checked_add(u64::from(d)))
                    .ok_or(BudgetError::NotAnInteger)?;
                digits += 1;
            }
            return if digits == 0 {
                Err(BudgetError::NotAnInteger)
            } else {
                Ok(n)
            };
        }
    }
    Err(BudgetError::Missing)
}

#[cfg(test)]
mod tests {
    use super::{BudgetError, ElfError, budget_value, footprint};

    #[test]
    fn budget_values_are_whole_keys_with_separators() {
        let text = "# c\na_b_c = 5\na_b = 8_192\nbad = 1.5\n";
        assert_eq!(budget_value(text, "a_b"), Ok(8192));
        assert_eq!(budget_value(text, "a_b_c"), Ok(5));
        assert_eq!(budget_value(text, "bad"), Err(BudgetError::NotAnInteger));
        assert_eq!(budget_value(text, "none"), Err(BudgetError::Missing));
    }

    #[test]
    fn non_elf_and_truncated_files_are_errors() {
        assert_eq!(footprint(b"hello"), Err(ElfError::NotElf));
        assert_eq!(footprint(b"\x7fELF\x02\x01"), Err(ElfError::NotElf32Le));
        assert_eq!(
            footprint(b"\x7fELF\x01\x01"),
            Err(ElfError::Truncated(0x20))
        );
    }
}
