//! onboard-demo support library: the board-independent flight application ([`app`], generic over
//! embedded-io and embedded-hal 1.0; it also builds on the host) with its clock ([`clock`]: tick
//! timer, overrun monitor, pacing), and, for the firmware
//! binaries, the instruction counter, stack painting, the SysTick tick timer of the QEMU boards
//! ([`systick`]) and the exit paths. (The smoke scenario
//! and its golden outputs live in `onboard-spec`.)
//!
//! Everything but [`app`] is firmware (`target_os = "none"`): a host build of this package (as
//! `cargo test --workspace` and `cargo clippy --workspace` do) compiles the application only
//! and stub binaries, and does not pull in the Cortex-M crates.
#![no_std]
#![deny(missing_docs)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(test)]
extern crate std;

pub mod app;
pub mod clock;
#[cfg(target_os = "none")]
pub mod flights;
#[cfg(target_os = "none")]
pub mod insn;
#[cfg(target_os = "none")]
pub mod stack;
#[cfg(target_os = "none")]
pub mod systick;

/// Exit QEMU through semihosting with the given success flag, then idle.
#[cfg(target_os = "none")]
pub fn exit(success: bool) -> ! {
    use cortex_m_semihosting::debug;
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::nop();
    }
}

#[cfg(target_os = "none")]
#[panic_handler]
fn panic(_info: &core::panic::PanicInfo) -> ! {
    cortex_m_semihosting::hprintln!("onboard-demo: panic");
    exit(false)
}
