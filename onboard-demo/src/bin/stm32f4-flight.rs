//! The flight application on a real board: an STM32F407 with stm32f4xx-hal 0.23 (compile only,
//! a step of `cargo xtask test`: `--features stm32f4 --bin stm32f4-flight`), proving nothing in
//! `onboard_demo::app` is QEMU-specific. The link is USART2 (PA2 TX, PA3 RX, 115 200 baud): the
//! HAL's embedded-io `Write`, and its embedded-hal-nb receiver adapted to embedded-io `Read`;
//! the status discrete is PA5 (the user LED of the usual boards). Guidance is `f32` (FPU).
//! Without a set-up the board flies the HORUS-2B reference mission.
//!
//! Not run here (no STM32F4 machine in QEMU 7.2 that the HAL supports); the panic handler of
//! `onboard_demo` uses semihosting, which needs a debugger on hardware.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!("stm32f4-flight: STM32F4 firmware, not a host program");
    std::process::exit(2);
}

/// The firmware (built for `target_os = "none"` only).
#[cfg(target_os = "none")]
mod firmware {
    use cortex_m_rt::entry;
    use embedded_hal_nb::serial::Read as _;
    use guidance_core::guidance::Guidance;
    use guidance_core::missions::horus2b_reference;
    use onboard_demo::app::serve;
    use stm32f4xx_hal::pac;
    use stm32f4xx_hal::prelude::*;
    use stm32f4xx_hal::rcc::Config;
    use stm32f4xx_hal::serial::{Instance, Serial};

    const CAPACITY: usize = guidance_core::nodes::DEFAULT_NODE_CAPACITY;

    /// The USART as an embedded-io link (blocking reads of the HAL's nb receiver).
    struct UartLink<U: Instance>(Serial<U, u8>);

    impl<U: Instance> embedded_io::ErrorType for UartLink<U> {
        type Error = stm32f4xx_hal::serial::Error;
    }

    impl<U: Instance> embedded_io::Read for UartLink<U> {
        fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
            let Some(first) = buf.first_mut() else {
                return Ok(0);
            };
            *first = nb::block!(self.0.read())?;
            Ok(1)
        }
    }

    impl<U: Instance> embedded_io::Write for UartLink<U> {
        fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
            embedded_io::Write::write(&mut self.0, buf)
        }
        fn flush(&mut self) -> Result<(), Self::Error> {
            embedded_io::Write::flush(&mut self.0)
        }
    }

    fn reference() -> Option<Guidance<f32, CAPACITY>> {
        let mission = horus2b_reference::<f32>().ok()?;
        let energy = mission.earth_energy_normalizer().ok()?;
        mission.guidance(energy).ok()
    }

    #[entry]
    fn main() -> ! {
        if let Some(dp) = pac::Peripherals::take() {
            let mut rcc = dp.RCC.freeze(Config::hse(8.MHz()).sysclk(168.MHz()));
            let gpioa = dp.GPIOA.split(&mut rcc);
            let mut led = gpioa.pa5.into_push_pull_output();
            if let Ok(serial) = dp
                .USART2
                .serial((gpioa.pa2, gpioa.pa3), 115_200.bps(), &mut rcc)
            {
                let mut link = UartLink(serial);
                let _ = serve::<f32, CAPACITY, f32, _, _>(&mut link, &mut led, reference);
            }
            led.set_low();
        }
        loop {
            cortex_m::asm::wfi();
        }
    }
}
