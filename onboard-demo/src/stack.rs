//! Stack painting: the measured maximum stack depth of a call.
//!
//! [`max_stack_bytes`] fills the free stack below its own frame (down to the end of the static
//! data, `__sheap` of cortex-m-rt, at most [`PAINT_MAX_BYTES`]) with [`PATTERN`], runs the call,
//! and scans up from the bottom for the first word that changed. The depth reported is the
//! stack pointer at the call minus that address: the call's frames, anything it called, and any
//! exception frame stacked meanwhile (an over-estimate, except by 4 bytes per deepest word that
//! happens to hold the 32-bit pattern itself). A call deeper than the painted region reports
//! the whole region: [`StackDepth::overflowed`] then says so.

use core::ptr::{addr_of, read_volatile, write_volatile};

/// Paint word.
pub const PATTERN: u32 = 0xC0DE_5AFE;

/// Largest region painted \[bytes\].
pub const PAINT_MAX_BYTES: usize = 48 * 1024;

// SAFETY: a linker symbol of cortex-m-rt's `link.x`; only its address is used.
#[allow(unsafe_code)]
unsafe extern "C" {
    /// End of .bss/.data (start of the heap region) from cortex-m-rt's linker script.
    static __sheap: u32;
}

/// A measured stack depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StackDepth {
    /// Bytes used below the stack pointer at the call.
    pub bytes: usize,
    /// Whether the call reached the bottom of the painted region (depth at least `bytes`).
    pub overflowed: bool,
}

#[inline(always)]
fn sp() -> usize {
    cortex_m::register::msp::read() as usize
}

/// Runs `f` in a frame of its own below the measuring frame, so whatever the compiler inlines
/// into it is measured (inlined into [`max_stack_bytes`] it would sit above the painted region).
#[inline(never)]
fn call_below<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// The measured maximum stack depth of `f` (see the module docs), and its result.
#[inline(never)]
pub fn max_stack_bytes<R>(f: impl FnOnce() -> R) -> (StackDepth, R) {
    let top = sp();
    let heap = addr_of!(__sheap) as usize;
    let bottom = top
        .saturating_sub(PAINT_MAX_BYTES)
        .max(heap.saturating_add(16))
        & !3;
    // The painting loops run in this frame (above `top`), so the region reaches `top` itself.
    let paint_top = top & !3;
    let mut a = bottom;
    while a < paint_top {
        // SAFETY: [bottom, paint_top) lies between the end of the static data and this frame's
        // stack pointer; nothing lives there (ARM has no red zone, and this loop calls
        // nothing) and it is word aligned.
        #[allow(unsafe_code)]
        unsafe {
            write_volatile(a as *mut u32, PATTERN)
        };
        a += 4;
    }
    let r = call_below(f);
    let mut a = bottom;
    while a < paint_top {
        // SAFETY: as above; reading the painted words back.
        #[allow(unsafe_code)]
        let w = unsafe { read_volatile(a as *const u32) };
        if w != PATTERN {
            break;
        }
        a += 4;
    }
    (
        StackDepth {
            bytes: top.saturating_sub(a),
            overflowed: a == bottom,
        },
        r,
    )
}

/// Print `stack NAME: N bytes` (or that the painted region was exceeded) over semihosting;
/// true unless the measurement overflowed.
pub fn report(name: &str, d: StackDepth) -> bool {
    if d.overflowed {
        cortex_m_semihosting::hprintln!(
            "stack {}: over {} bytes (painted region exceeded)",
            name,
            d.bytes
        );
        false
    } else {
        cortex_m_semihosting::hprintln!("stack {}: {} bytes", name, d.bytes);
        true
    }
}
