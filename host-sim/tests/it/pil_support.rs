//! What the processor-in-the-loop tests share: where the `pil` firmware is, and SIL guidance
//! with a constant attitude offset (the derived PIL-vs-SIL bounds use its sensitivity).

use std::path::PathBuf;

use guidance_core::NavState;
use guidance_core::guidance::Command;
use host_sim::sim::AttitudeSource;

/// The `pil` firmware built for `target`: `<target dir>/<target>/firmware/pil`.
pub fn pil_elf(target: &str) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map_or_else(
            || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target"),
            PathBuf::from,
        )
        .join(target)
        .join("firmware/pil")
}

/// The Cortex-M4F `pil` firmware: `$PIL_ELF`, else [`pil_elf`] of `thumbv7em-none-eabihf`.
pub fn reference_pil_elf() -> PathBuf {
    std::env::var_os("PIL_ELF").map_or_else(|| pil_elf("thumbv7em-none-eabihf"), PathBuf::from)
}

/// Any attitude source with a constant offset [rad] added to both commanded angles.
pub struct Offset<A>(pub A, pub f64);

impl<A: AttitudeSource> AttitudeSource for Offset<A> {
    type Error = A::Error;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), Self::Error> {
        self.0.tick(nav)
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        let a = self.0.attitude_at(time_s);
        Command {
            alpha_rad: a.alpha_rad + self.1,
            sigma_rad: a.sigma_rad + self.1,
        }
    }
    fn next_tick_s(&self) -> f64 {
        self.0.next_tick_s()
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.0.next_kink_s(time_s)
    }
}
