//! Instruction counts of the full flight stack on the target, under QEMU `-icount shift=0`
//! (run by `cargo xtask bench-firmware` after `insn-bench`; the method: `onboard_demo::insn`).
//! Each vehicle's campaign stack ticked over its recorded flight, and its layers alone
//! (`flight`). A binary of its own so that linking the whole stack does not change how the
//! compiler inlines the core's functions in `insn-bench`'s benchmarks (it doubled the M3's
//! fixed-point guidance tick there).
//!
//! Prints one line per benchmark: `bench <name>: <instructions> insn/call`; the first is the
//! calibration (10 000 `nop`s); the binary exits 1 if the calibration is off or a benchmark
//! fails.
//!
//! Firmware only: built for the host this binary is a stub that says so and exits 2.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "insn-bench-stack: Cortex-M firmware, not a host program: build it with \
         --target thumbv7em-none-eabihf or thumbv7m-none-eabi (see README)"
    );
    std::process::exit(2);
}

/// The full-stack benchmarks (firmware only).
#[cfg(target_os = "none")]
mod flight;

/// The firmware (built for `target_os = "none"` only).
#[cfg(target_os = "none")]
mod firmware {
    use cortex_m_rt::{ExceptionFrame, entry, exception};
    use onboard_demo::insn::InsnCounter;

    /// The guidance scalar: `f32` on the M4F, fixed point on the M3.
    #[cfg(target_abi = "eabihf")]
    pub(crate) type Num = f32;
    /// The guidance scalar: `f32` on the M4F, fixed point on the M3.
    #[cfg(not(target_abi = "eabihf"))]
    pub(crate) type Num = guidance_core::Fixed;

    pub(crate) use onboard_demo::insn::INSN_PER_TICK;

    #[entry]
    fn main() -> ! {
        let Some(p) = cortex_m::Peripherals::take() else {
            onboard_demo::exit(false)
        };
        let mut c = InsnCounter::new(p.SYST);
        if !onboard_demo::insn::calibrate(&mut c) {
            onboard_demo::exit(false)
        }
        onboard_demo::exit(crate::flight::bench_flight_stacks(&mut c))
    }

    #[exception]
    #[allow(unsafe_code)]
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        onboard_demo::exit(false)
    }
}
