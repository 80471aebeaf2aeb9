//! Instruction counting under QEMU with `-icount shift=0`.
//!
//! With `-icount shift=0` QEMU advances its virtual clock by exactly 1 ns per executed
//! instruction. SysTick, clocked from the CPU clock (`CLKSOURCE = 1`; 25 MHz on `mps2-an386`,
//! 12.5 MHz on `lm3s6965evb` under QEMU, as calibrated), then decrements once every `1e9 / f_cpu` instructions. A
//! measurement runs the code `reps` times between two SysTick reads and converts ticks to
//! instructions with the ratio calibrated against a loop of known length, so the result is the
//! mean instruction count per call with a resolution of `ns_per_tick / reps` instructions.
//! (DWT CYCCNT reads 0 under QEMU, hence this method.) On real hardware these numbers are
//! instruction counts, not cycles: multiply by the core's CPI for time.

use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;

/// SysTick reload value: the full 24-bit range.
const RELOAD: u32 = 0x00FF_FFFF;

/// A free-running SysTick used as an instruction counter.
pub struct InsnCounter {
    syst: SYST,
}

impl InsnCounter {
    /// Take SysTick and start it free-running from the core clock.
    pub fn new(mut syst: SYST) -> Self {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_counter();
        Self { syst }
    }

    /// SysTick ticks elapsed while `f` runs (must be < 2^24 ticks; SysTick counts down).
    pub fn ticks<F: FnMut()>(&mut self, mut f: F) -> u32 {
        self.syst.clear_current();
        let start = SYST::get_current();
        f();
        let end = SYST::get_current();
        // Reading just after clear_current may see RELOAD; the counter counts down.
        start.wrapping_sub(end) & RELOAD
    }

    /// Keep the counter alive for the caller's lifetime (returns the peripheral).
    pub fn free(self) -> SYST {
        self.syst
    }
}

/// Instructions per SysTick tick on the M4F board (`mps2-an386`: SysTick at 25 MHz under
/// `-icount shift=0`).
#[cfg(target_abi = "eabihf")]
pub const INSN_PER_TICK: u32 = 40;
/// Instructions per SysTick tick on the M3 board (`lm3s6965evb`: SysTick at 12.5 MHz under
/// QEMU, as calibrated).
#[cfg(not(target_abi = "eabihf"))]
pub const INSN_PER_TICK: u32 = 80;

/// Time 10 000 `nop`s, print `bench calibration_10000_nop: N insn/call` over semihosting, and
/// return whether `N` is within one tick ([`INSN_PER_TICK`] instructions, the resolution plus
/// one tick of phase) of 10 000: the check every instruction-count binary runs first.
pub fn calibrate(c: &mut InsnCounter) -> bool {
    let t = c.ticks(|| {
        #[allow(unsafe_code)]
        // SAFETY: 10 000 `nop` instructions: no memory, register or flag effects.
        unsafe {
            core::arch::asm!(
                ".rept 10000",
                "nop",
                ".endr",
                options(nomem, nostack, preserves_flags)
            );
        }
    });
    let calibrated = t * INSN_PER_TICK;
    cortex_m_semihosting::hprintln!("bench calibration_10000_nop: {} insn/call", calibrated);
    calibrated.abs_diff(10_000) <= INSN_PER_TICK
}
