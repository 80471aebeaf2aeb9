//! The flight application on a real board: an STM32F407 with stm32f4xx-hal 0.23 (compile only,
//! a step of `cargo xtask test`: `--features stm32f4 --bin stm32f4-flight`), proving nothing in
//! `onboard_demo::app` is QEMU-specific. The link is USART2 (PA2 TX, PA3 RX, 115 200 baud): the
//! HAL's embedded-io `Write`, and its embedded-hal-nb receiver adapted to embedded-io `Read`;
//! the status discrete is PA5 (the user LED of the usual boards). Guidance is `f32` (FPU).
//! Without a set-up the board flies the HORUS-2B reference mission.
//!
//! Clock: free-running. TIM2 (32-bit) counts microseconds as the tick timer (it measures every
//! guidance tick against the period: overruns and the longest tick), and TIM5's embedded-hal
//! `DelayNs` waits out the rest of each 2 s period after a tick, so ticks start at most once
//! per period in real time. Guidance time stays the nav frame's time stamp.
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
    use onboard_demo::clock::{Pacing, TickTimer};
    use stm32f4xx_hal::pac;
    use stm32f4xx_hal::prelude::*;
    use stm32f4xx_hal::rcc::Config;
    use stm32f4xx_hal::serial::{Instance, Serial};
    use stm32f4xx_hal::timer::{CounterUs, TimerExt};

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

    /// TIM2 counting microseconds over its full 32-bit range: the tick timer. (The HAL's
    /// counter reloads at `u32::MAX - 1`, so a duration across a wrap reads 1 us too long: once
    /// every 71.6 min.)
    struct Tim2Us(CounterUs<pac::TIM2>);

    impl TickTimer for Tim2Us {
        fn now_us(&mut self) -> u32 {
            self.0.now().ticks()
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
            let mut counter = dp.TIM2.counter_us(&mut rcc);
            let delay = dp.TIM5.delay_us(&mut rcc);
            if let (Ok(serial), Ok(())) = (
                dp.USART2
                    .serial((gpioa.pa2, gpioa.pa3), 115_200.bps(), &mut rcc),
                counter.start(u32::MAX.micros()),
            ) {
                let mut link = UartLink(serial);
                let mut timer = Tim2Us(counter);
                let _ = serve::<f32, CAPACITY, f32, _, _, _, _>(
                    &mut link,
                    &mut led,
                    &mut timer,
                    Pacing::FreeRunning(delay),
                    reference,
                );
            }
            led.set_low();
        }
        loop {
            cortex_m::asm::wfi();
        }
    }
}
