//! What the processor-in-the-loop tests share: where the `pil` firmware is, its whole-run
//! stack and RAM budget check, and SIL guidance with a constant attitude offset (the derived
//! PIL-vs-SIL bounds use its sensitivity).

use std::path::{Path, PathBuf};

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

/// Whether a missing QEMU or ELF fails a PIL test instead of skipping it: `PIL_REQUIRED` set
/// (`cargo xtask pil` / `cargo xtask test`) or `CI=true`.
pub fn pil_required() -> bool {
    std::env::var_os("PIL_REQUIRED").is_some() || std::env::var("CI").is_ok_and(|v| v == "true")
}

/// The Cortex-M4F `pil` firmware: `$PIL_ELF`, else [`pil_elf`] of `thumbv7em-none-eabihf`.
pub fn reference_pil_elf() -> PathBuf {
    std::env::var_os("PIL_ELF").map_or_else(|| pil_elf("thumbv7em-none-eabihf"), PathBuf::from)
}

/// Check a PIL run's firmware memory against `onboard-demo/size-budget.toml` (the file's
/// comments give the measured figures): the deepest stack of the whole run, `stack` \[bytes\]
/// as the firmware measured it, within `<target>_pil_run_stack_bytes`, and the `elf` image's
/// static RAM (.data + .bss, read from the ELF as `cargo xtask size` does) plus that stack
/// within `<target>_pil_ram_plus_stack_bytes`. `name` labels the messages.
pub fn check_pil_memory_budget(name: &str, target: &str, elf: &Path, stack: u64) {
    use onboard_spec::footprint::{budget_value, footprint};
    let budget_file =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../onboard-demo/size-budget.toml");
    let text = std::fs::read_to_string(&budget_file).unwrap();
    let key = target.replace('-', "_");
    let budget = |k: String| {
        budget_value(&text, &k)
            .unwrap_or_else(|e| panic!("{}: field `{k}` {e}", budget_file.display()))
    };
    let stack_max = budget(format!("{key}_pil_run_stack_bytes"));
    let total_max = budget(format!("{key}_pil_ram_plus_stack_bytes"));
    let ram = footprint(&std::fs::read(elf).unwrap())
        .unwrap_or_else(|e| panic!("{}: {e}", elf.display()))
        .ram;
    println!(
        "{name}: firmware whole-run stack {stack} bytes (budget {stack_max}); static RAM {ram} + stack = {} bytes (budget {total_max})",
        ram + stack
    );
    assert!(
        stack <= stack_max,
        "{name}: stack {stack} > budget {stack_max}"
    );
    assert!(
        ram + stack <= total_max,
        "{name}: static RAM {ram} + stack {stack} > budget {total_max}"
    );
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
