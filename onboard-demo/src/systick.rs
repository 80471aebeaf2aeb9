//! The QEMU boards' tick timer: SysTick, free-running over its full 24-bit range from the core
//! clock, extended to 64 bits by counting its wraps in the SysTick exception.
//!
//! The firmware's `#[exception] fn SysTick()` must call [`on_wrap`] (one exception every 2^24
//! core clocks: 0.67 s on `mps2-an386` at 25 MHz, 1.34 s on `lm3s6965evb` at 12.5 MHz under
//! QEMU, as calibrated by `insn-bench`). DWT CYCCNT reads 0 under QEMU, hence SysTick.
//!
//! Under QEMU without `-icount` (the PIL run) SysTick follows QEMU's virtual clock, which runs
//! with host wall time: the measured tick durations are how long the emulator took, not a
//! real core's execution time (`cargo xtask bench-firmware` gives instruction counts).

use core::sync::atomic::{AtomicU32, Ordering};

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::{SCB, SYST};

use crate::clock::TickTimer;

/// SysTick reload value: the full 24-bit range.
const RELOAD: u32 = 0x00FF_FFFF;

/// SysTick period of the core clock under QEMU \[ns\]: 25 MHz on `mps2-an386` (Cortex-M4F).
#[cfg(target_abi = "eabihf")]
pub const NS_PER_SYSTICK: u64 = 40;
/// SysTick period of the core clock under QEMU \[ns\]: 12.5 MHz on `lm3s6965evb` (Cortex-M3,
/// as calibrated by `insn-bench`).
#[cfg(not(target_abi = "eabihf"))]
pub const NS_PER_SYSTICK: u64 = 80;

/// SysTick wraps so far (incremented by [`on_wrap`]).
static WRAPS: AtomicU32 = AtomicU32::new(0);

/// Count one SysTick wrap: call from the firmware's SysTick exception handler, and only there.
pub fn on_wrap() {
    // Single core, one writer (the handler): load and store cannot race with another write.
    WRAPS.store(
        WRAPS.load(Ordering::Relaxed).wrapping_add(1),
        Ordering::Relaxed,
    );
}

/// SysTick as a [`TickTimer`] (owns the peripheral).
pub struct SysTickTimer {
    syst: SYST,
}

impl SysTickTimer {
    /// Take SysTick: reload the full 24-bit range from the core clock, enable its exception
    /// (the binary's handler calls [`on_wrap`]) and start it.
    #[must_use]
    pub fn start(mut syst: SYST) -> Self {
        syst.disable_counter();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        WRAPS.store(0, Ordering::Relaxed);
        syst.enable_interrupt();
        syst.enable_counter();
        Self { syst }
    }

    /// Core clocks since [`SysTickTimer::start`] (64-bit; exact while the exception runs at
    /// least once per 2^24 clocks, i.e. interrupts are never masked that long).
    #[must_use]
    pub fn clocks(&mut self) -> u64 {
        cortex_m::interrupt::free(|_| {
            // With interrupts masked the handler cannot run: WRAPS is stable, and a wrap not yet
            // counted shows as a pending SysTick exception.
            let mut wraps = u64::from(WRAPS.load(Ordering::Relaxed));
            let mut current = SYST::get_current();
            if SCB::is_pendst_pending() {
                // Read again, after the wrap for sure.
                current = SYST::get_current();
                wraps += 1;
            }
            (wraps << 24) + u64::from(RELOAD - current.min(RELOAD))
        })
    }

    /// Give the peripheral back (its exception disabled, the counter stopped).
    pub fn free(mut self) -> SYST {
        self.syst.disable_interrupt();
        self.syst.disable_counter();
        self.syst
    }
}

impl TickTimer for SysTickTimer {
    fn now_us(&mut self) -> u32 {
        // Truncation to u32 is the documented wrap of `TickTimer::now_us`.
        #[allow(clippy::cast_possible_truncation)]
        let us = (self.clocks().wrapping_mul(NS_PER_SYSTICK) / 1_000) as u32;
        us
    }
}
