//! onboard-demo: firmware that runs `guidance-core` on a Cortex-M.
//!
//! Smoke mode (this binary): flies the scenario of [`scenario`] through the core's `Guidance`
//! and compares every command with the golden values computed on the host
//! (`onboard_spec::golden`, written by `cargo xtask golden`). It exits through semihosting with status 0
//! only if all match; a panic or HardFault exits with status 1.
//!
//! * `thumbv7em-none-eabihf` (QEMU `mps2-an386`, Cortex-M4F): guidance in `f32` on the FPU;
//!   compared to the host's `f32` run within 1e-6 rad (identical IEEE single-precision
//!   operations and the same pure-Rust libm, so the observed difference is 0).
//! * `thumbv7m-none-eabi` (QEMU `lm3s6965evb`, Cortex-M3, no FPU): guidance in fixed point
//!   (`I32F32`); integer arithmetic, compared bit for bit.
//!
//! Firmware only: built for the host (as `cargo test --workspace` and `cargo clippy
//! --workspace` do) this binary is a stub that says so and exits 2.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(missing_docs)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "onboard-demo: Cortex-M firmware, not a host program: build it with \
         --target thumbv7em-none-eabihf or thumbv7m-none-eabi (see README)"
    );
    std::process::exit(2);
}

/// The firmware (built for `target_os = "none"` only).
#[cfg(target_os = "none")]
mod firmware {
    use cortex_m_rt::{ExceptionFrame, entry, exception};
    use cortex_m_semihosting::hprintln;

    use onboard_spec::{golden, scenario};

    #[cfg(target_abi = "eabihf")]
    type Num = f32;
    #[cfg(not(target_abi = "eabihf"))]
    type Num = guidance_core::Fixed;

    /// Largest allowed |firmware - host| per angle [rad].
    #[cfg(target_abi = "eabihf")]
    const TOLERANCE_RAD: f64 = 1e-6;
    #[cfg(not(target_abi = "eabihf"))]
    const TOLERANCE_RAD: f64 = 0.0;

    fn golden_row(seq: usize, i: usize) -> Option<[f64; 4]> {
        #[cfg(target_abi = "eabihf")]
        let row = golden::F32.get(seq)?.get(i).map(|r| r.map(f64::from));
        #[cfg(not(target_abi = "eabihf"))]
        let row = golden::FIXED_BITS
            .get(seq)?
            .get(i)
            .map(|r| r.map(|b| guidance_core::Scalar::to_f64(guidance_core::Fixed::from_bits(b))));
        row
    }

    fn check() -> Result<u32, &'static str> {
        use guidance_core::Scalar;
        let zero = scenario::Row {
            alpha_rad: Num::ZERO,
            sigma_rad: Num::ZERO,
            cmd_alpha_rad: Num::ZERO,
            cmd_sigma_rad: Num::ZERO,
        };
        let mut out = [[zero; scenario::SAMPLES]; scenario::SEQUENCES];
        scenario::run(&mut out).map_err(|_| "guidance returned an error")?;
        let mut compared = 0u32;
        for (seq, rows) in out.iter().enumerate() {
            for (i, row) in rows.iter().enumerate() {
                let want = golden_row(seq, i).ok_or("golden table too short")?;
                let got = [
                    row.alpha_rad,
                    row.sigma_rad,
                    row.cmd_alpha_rad,
                    row.cmd_sigma_rad,
                ]
                .map(Scalar::to_f64);
                for (g, w) in got.iter().zip(want.iter()) {
                    let diff = g - w;
                    if !(diff <= TOLERANCE_RAD && -diff <= TOLERANCE_RAD) {
                        hprintln!(
                            "mismatch: sequence {} sample {}: firmware {} host {}",
                            seq,
                            i,
                            g,
                            w
                        );
                        return Err("command differs from host golden value");
                    }
                    compared += 1;
                }
            }
        }
        Ok(compared)
    }

    // With feature `defmt` the result goes out as defmt frames over semihosting (decoded on
    // the host by defmt-print, `cargo xtask defmt`); plain text would corrupt that stream.
    #[cfg(feature = "defmt")]
    use defmt_semihosting as _;

    #[entry]
    fn main() -> ! {
        match check() {
            Ok(n) => {
                #[cfg(feature = "defmt")]
                defmt::info!(
                    "onboard-demo: {=u32} guidance outputs match the host golden values",
                    n
                );
                #[cfg(not(feature = "defmt"))]
                hprintln!(
                    "onboard-demo: {} guidance outputs match the host golden values",
                    n
                );
                onboard_demo::exit(true)
            }
            Err(e) => {
                #[cfg(feature = "defmt")]
                defmt::error!("onboard-demo: FAIL: {=str}", e);
                #[cfg(not(feature = "defmt"))]
                hprintln!("onboard-demo: FAIL: {}", e);
                onboard_demo::exit(false)
            }
        }
    }

    #[exception]
    #[allow(unsafe_code)] // cortex-m-rt requires HardFault handlers to be `unsafe fn`.
    unsafe fn HardFault(_frame: &ExceptionFrame) -> ! {
        hprintln!("onboard-demo: HardFault");
        onboard_demo::exit(false)
    }
}
