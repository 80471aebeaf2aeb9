//! onboard-demo support library: the instruction counter and the exit paths shared by the
//! firmware binaries. (The smoke scenario and its golden outputs live in `onboard-spec`.)
#![no_std]
#![deny(missing_docs)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

pub mod insn;

use core::panic::PanicInfo;
use cortex_m_semihosting::{debug, hprintln};

/// Exit QEMU through semihosting with the given success flag, then idle.
pub fn exit(success: bool) -> ! {
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::nop();
    }
}

#[panic_handler]
fn panic(_info: &PanicInfo) -> ! {
    hprintln!("onboard-demo: panic");
    exit(false)
}
