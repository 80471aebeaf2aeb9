//! The QEMU machines the firmware runs on: one table, used by `cargo xtask` (smoke test,
//! instruction counts, size budget), by `host-sim`'s processor-in-the-loop run and, through
//! the runners of `.cargo/config.toml` (which cargo cannot compute, so a workspace test checks
//! them against [`runner`]), by `cargo run -p onboard-demo --target <triple>`.

/// The QEMU system emulator for every machine here.
pub const QEMU_SYSTEM: &str = "qemu-system-arm";

/// Wall-time limit the `cargo run` runners give QEMU \[s\], as `timeout` takes it.
pub const RUNNER_TIMEOUT_S: &str = "120";

/// Grace period after `timeout`'s SIGTERM before its SIGKILL (`timeout -k`) \[s\]: QEMU blocked
/// in a semihosting FIFO open ignores SIGTERM, so every `timeout` around QEMU has `-k`.
pub const RUNNER_KILL_AFTER_S: &str = "5";

/// One emulated machine and the Rust target the firmware is built for on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QemuMachine {
    /// Rust target triple of the firmware.
    pub target: &'static str,
    /// QEMU `-cpu`.
    pub cpu: &'static str,
    /// QEMU `-machine`.
    pub machine: &'static str,
    /// What runs there (for messages).
    pub description: &'static str,
}

/// Arguments after [`QEMU_SYSTEM`] up to and including `-kernel` (the ELF follows).
pub const QEMU_ARG_COUNT: usize = 8;

impl QemuMachine {
    /// `-cpu CPU -machine MACHINE -nographic -semihosting-config enable=on,target=native
    /// -kernel`: semihosting prints to the host's stdout and sets QEMU's exit status.
    #[must_use]
    pub fn qemu_args(&self) -> [&'static str; QEMU_ARG_COUNT] {
        [
            "-cpu",
            self.cpu,
            "-machine",
            self.machine,
            "-nographic",
            "-semihosting-config",
            "enable=on,target=native",
            "-kernel",
        ]
    }
}

/// Cortex-M4F with FPU (`mps2-an386`): `f32` guidance; also the PIL machine.
pub const CORTEX_M4F: QemuMachine = QemuMachine {
    target: "thumbv7em-none-eabihf",
    cpu: "cortex-m4",
    machine: "mps2-an386",
    description: "mps2-an386, Cortex-M4F, f32 guidance",
};

/// Cortex-M3 without FPU (`lm3s6965evb`): fixed-point guidance.
pub const CORTEX_M3: QemuMachine = QemuMachine {
    target: "thumbv7m-none-eabi",
    cpu: "cortex-m3",
    machine: "lm3s6965evb",
    description: "lm3s6965evb, Cortex-M3 without FPU, fixed-point guidance",
};

/// Every machine the firmware is built for and run on, in the order the checks run.
pub const MACHINES: [QemuMachine; 2] = [CORTEX_M4F, CORTEX_M3];

/// The machine processor-in-the-loop runs on (`onboard-demo`'s `pil` binary).
pub const PIL_MACHINE: QemuMachine = CORTEX_M4F;

/// The machine of a target triple, if the firmware runs on one.
#[must_use]
pub fn by_target(target: &str) -> Option<&'static QemuMachine> {
    MACHINES.iter().find(|m| m.target == target)
}

/// The words of the `.cargo/config.toml` runner of `machine`: `timeout -k`
/// [`RUNNER_KILL_AFTER_S`] [`RUNNER_TIMEOUT_S`], [`QEMU_SYSTEM`], then
/// [`QemuMachine::qemu_args`] (cargo appends the ELF).
#[must_use]
pub fn runner(machine: &QemuMachine) -> [&'static str; QEMU_ARG_COUNT + 5] {
    let a = machine.qemu_args();
    [
        "timeout",
        "-k",
        RUNNER_KILL_AFTER_S,
        RUNNER_TIMEOUT_S,
        QEMU_SYSTEM,
        a[0],
        a[1],
        a[2],
        a[3],
        a[4],
        a[5],
        a[6],
        a[7],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_lookups() {
        assert_eq!(by_target("thumbv7em-none-eabihf"), Some(&CORTEX_M4F));
        assert_eq!(by_target("thumbv7m-none-eabi"), Some(&CORTEX_M3));
        assert_eq!(by_target("thumbv6m-none-eabi"), None);
        assert_eq!(PIL_MACHINE, CORTEX_M4F);
        let r = runner(&CORTEX_M3);
        assert_eq!(
            r.get(..7),
            Some(
                [
                    "timeout",
                    "-k",
                    "5",
                    "120",
                    "qemu-system-arm",
                    "-cpu",
                    "cortex-m3"
                ]
                .as_slice()
            )
        );
        assert_eq!(r.last(), Some(&"-kernel"));
        assert!(RUNNER_TIMEOUT_S.parse::<u32>().is_ok_and(|s| s > 0));
    }
}
