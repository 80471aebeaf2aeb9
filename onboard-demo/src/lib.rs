//! onboard-demo support library: the instruction counter and the exit paths shared by the
//! firmware binaries. (The smoke scenario and its golden outputs live in `onboard-spec`.)
//!
//! Everything here is firmware (`target_os = "none"`): a host build of this package (as
//! `cargo test --workspace` and `cargo clippy --workspace` do) compiles an empty library and
//! stub binaries, and does not pull in the Cortex-M crates.
#![no_std]
#![deny(missing_docs)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(target_os = "none")]
pub mod insn;
#[cfg(target_os = "none")]
pub mod stack;

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
