//! Stack measurement firmware of the full flight stack: the maximum stack depth (stack
//! painting, `onboard_demo::stack`) of each vehicle's campaign stack (`flight_stack_horus`,
//! `flight_stack_srm`: the set-up image decoded, the `FlightStack` built and every tick of its
//! recorded flight, `onboard_demo::flights`; `f32` on the Cortex-M4F, the fixed-point tick
//! with `f32` layers on the Cortex-M3, as the `pil` image). Prints one `stack NAME: N bytes`
//! line each and exits 0; `cargo xtask stack` reads them after `stack-bench`'s and checks
//! static RAM plus the largest against `<target>_pil_ram_plus_stack_bytes` in
//! `onboard-demo/size-budget.toml`. A binary of its own so that linking the whole stack does
//! not change how the core inlines in `stack-bench`'s measurements.
//!
//! Firmware only: built for the host this binary is a stub that exits 2.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!("stack-bench-flight: Cortex-M firmware, not a host program (see README)");
    std::process::exit(2);
}

/// The firmware (built for `target_os = "none"` only).
#[cfg(target_os = "none")]
mod firmware {
    use cortex_m_rt::{ExceptionFrame, entry, exception};
    use cortex_m_semihosting::hprintln;
    use onboard_demo::stack::{max_stack_bytes, report};

    #[cfg(target_abi = "eabihf")]
    type Num = f32;
    #[cfg(not(target_abi = "eabihf"))]
    type Num = guidance_core::Fixed;

    /// Each vehicle's campaign stack (`onboard_demo::flights`): the image decoded, the
    /// `FlightStack` built, and every tick of its recorded flight, all in one measurement (what
    /// the flight application does after the set-up image's last chunk and then per nav frame).
    fn flight_stacks() -> Result<bool, &'static str> {
        use guidance_core::nodes::DEFAULT_NODE_CAPACITY;
        use guidance_core::setup::image::decode;
        use guidance_core::stack::{FlightStack, Layers};
        use onboard_demo::flights::{Recorded, VEHICLES};
        let mut ok = true;
        for (vehicle, bytes) in VEHICLES {
            let f = Recorded::parse(bytes).ok_or("bad flight file")?;
            let (d, r) = max_stack_bytes(|| {
                let config = decode::<Num, DEFAULT_NODE_CAPACITY, f32>(
                    core::hint::black_box(f.image),
                    Layers::ALL,
                )
                .ok()?;
                let mut stack = FlightStack::new(&config).ok()?;
                let mut every = true;
                for (nav, sensed) in f.ticks() {
                    every &= stack.tick(&nav.to_scalar::<Num>(), sensed.as_ref()).is_ok();
                }
                Some(every)
            });
            if r != Some(true) {
                return Err("full-stack flight failed");
            }
            let name = if vehicle == "horus" {
                "flight_stack_horus"
            } else {
                "flight_stack_srm"
            };
            ok &= report(name, d);
        }
        Ok(ok)
    }

    #[entry]
    fn main() -> ! {
        match flight_stacks() {
            Ok(ok) => onboard_demo::exit(ok),
            Err(e) => {
                hprintln!("stack-bench-flight: FAIL: {}", e);
                onboard_demo::exit(false)
            }
        }
    }

    #[exception]
    #[allow(unsafe_code)] // cortex-m-rt requires HardFault handlers to be `unsafe fn`.
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        hprintln!("stack-bench-flight: HardFault");
        onboard_demo::exit(false)
    }
}
