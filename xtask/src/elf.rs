//! Minimal ELF32 little-endian section-header reader: enough to sum the flash and RAM
//! footprint of a Cortex-M firmware image without external tools.

/// Flash and RAM footprint of a firmware image [bytes].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Footprint {
    /// Bytes stored in flash: allocated sections with contents (.vector_table, .text, .rodata, .data).
    pub flash: u64,
    /// Bytes of static RAM: writable allocated sections (.data, .bss, .uninit).
    pub ram: u64,
}

const SHF_WRITE: u32 = 0x1;
const SHF_ALLOC: u32 = 0x2;
const SHT_NOBITS: u32 = 8;

fn u16_at(b: &[u8], off: usize) -> Result<u16, String> {
    b.get(off..off + 2)
        .map(|s| u16::from_le_bytes([s[0], s[1]]))
        .ok_or_else(|| format!("ELF truncated at offset {off}"))
}

fn u32_at(b: &[u8], off: usize) -> Result<u32, String> {
    b.get(off..off + 4)
        .map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
        .ok_or_else(|| format!("ELF truncated at offset {off}"))
}

/// Sum the allocated sections of an ELF32 little-endian file.
pub fn footprint(bytes: &[u8]) -> Result<Footprint, String> {
    if bytes.get(0..4) != Some(b"\x7fELF".as_slice()) {
        return Err("not an ELF file".into());
    }
    if bytes.get(4) != Some(&1) || bytes.get(5) != Some(&1) {
        return Err("not a 32-bit little-endian ELF file".into());
    }
    let shoff = u32_at(bytes, 0x20)? as usize;
    let shentsize = u16_at(bytes, 0x2E)? as usize;
    let shnum = u16_at(bytes, 0x30)? as usize;
    let mut fp = Footprint { flash: 0, ram: 0 };
    for i in 0..shnum {
        let base = shoff + i * shentsize;
        let sh_type = u32_at(bytes, base + 4)?;
        let flags = u32_at(bytes, base + 8)?;
        let size = u64::from(u32_at(bytes, base + 20)?);
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
