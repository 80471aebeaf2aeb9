//! Processor-in-the-loop (PIL): the closed loop flies the firmware's guidance running in QEMU.
//!
//! [`PilGuidance`] is an [`AttitudeSource`](crate::sim::AttitudeSource): at every 2 s tick it sends the navigation state to
//! the firmware (`onboard-demo`'s `pil` binary, `f32` guidance with the HORUS-2B reference
//! table compiled in) as a `guidance_core::link` [`NavFrame`](guidance_core::link::NavFrame) and waits for the
//! [`CommandFrame`](guidance_core::link::CommandFrame); between ticks it reproduces the rate-limited ramp from that frame
//! ([`CommandFrame::attitude_at`](guidance_core::link::CommandFrame::attitude_at)). The frames go through two named FIFOs,
//! `<dir>/nav` and `<dir>/cmd`, that the firmware opens through semihosting; `<dir>` is passed
//! to the firmware as QEMU's `-append` command line.
//!
//! QEMU runs with the FIFO directory as its working directory and `-append .`, so the firmware
//! opens `./nav` and `./cmd` whatever the directory's length or characters.
//!
//! Nothing hangs and nothing is left behind: QEMU runs in its own process group under
//! `timeout -k`; opening the FIFOs and every answer wait at most [`PilConfig::reply_timeout`]
//! and stop at once if QEMU exits (its status and stderr are the error); on every exit path
//! (error, drop, unwinding panic, and Ctrl-C through [`interrupt_cleanup`]) the process group is
//! SIGKILLed and the FIFO directory removed. Every command frame is checked
//! ([`FrameLimits::check`]) before it is flown; the exchanged frames are kept in a
//! [`PilRecord`] that outlives a failed run.

mod check;
mod faults;
mod fifo;
mod guidance;
mod qemu;
mod record;
mod reference;
mod scenario;

use std::path::PathBuf;
use std::time::Duration;

use guidance_core::link::LinkError;

use crate::scenario::ScenarioError;
use crate::sim;

pub use check::{ANGLE_SLACK_RAD, FrameLimits, FrameViolation, RELATIVE_SLACK};
pub use faults::{FaultConfig, FaultCounts, MAX_RETRIES};
pub use fifo::FIFO_DIR_PREFIX;
pub use guidance::PilGuidance;
pub use qemu::{QemuExit, interrupt_cleanup};
pub use record::{Exchange, PilRecord};
pub use reference::{
    fly_reference, fly_reference_pil, fly_reference_pil_recorded, fly_reference_sil,
    reference_sil_guidance,
};
pub use scenario::{fly_scenario_pil, scenario_setup};

/// Where the firmware ELF is looked for by default (relative to the workspace root).
pub const DEFAULT_ELF: &str = "target/thumbv7em-none-eabihf/firmware/pil";

/// PIL settings.
#[derive(Clone, Debug)]
pub struct PilConfig {
    /// Firmware ELF (`onboard-demo`'s `pil` binary for `thumbv7em-none-eabihf`).
    pub elf: PathBuf,
    /// QEMU program (`$REENTRY_PIL_QEMU`, else `qemu-system-arm`).
    pub qemu: String,
    /// Where the run's FIFO directory (`reentry-pil-<pid>-<n>`, removed afterwards) is made.
    pub fifo_parent: PathBuf,
    /// Longest wait for the firmware to open a FIFO or answer one frame.
    pub reply_timeout: Duration,
    /// Wall-time limit of the whole QEMU run (`timeout`) \[s\].
    pub qemu_timeout_s: u32,
    /// Link fault injection on the flight's nav frames (`None`: a clean link).
    pub faults: Option<FaultConfig>,
    /// The QEMU machine (`None`: from the ELF, see [`machine_of_elf`]).
    pub machine: Option<onboard_spec::machines::QemuMachine>,
}

/// The machine an ELF is built for: the Cortex-M4F for a hard-float ELF (`EF_ARM_ABI_FLOAT_HARD`
/// in `e_flags`), else the Cortex-M3 (`onboard_spec::machines`). An unreadable or non-ELF file
/// gives the PIL machine (QEMU then reports what is wrong with it).
#[must_use]
pub fn machine_of_elf(elf: &std::path::Path) -> onboard_spec::machines::QemuMachine {
    use onboard_spec::machines::{CORTEX_M3, CORTEX_M4F, PIL_MACHINE};
    const EF_ARM_ABI_FLOAT_HARD: u32 = 0x400;
    let Ok(bytes) = std::fs::read(elf) else {
        return PIL_MACHINE;
    };
    // ELF32 (class 1), ARM (e_machine 40); e_flags at byte 36.
    let is_arm32 = bytes.get(..4) == Some(b"\x7fELF".as_slice())
        && bytes.get(4) == Some(&1)
        && bytes.get(18..20) == Some([40u8, 0].as_slice());
    match bytes.get(36..40) {
        Some(&[a, b, c, d]) if is_arm32 => {
            if u32::from_le_bytes([a, b, c, d]) & EF_ARM_ABI_FLOAT_HARD != 0 {
                CORTEX_M4F
            } else {
                CORTEX_M3
            }
        }
        _ => PIL_MACHINE,
    }
}

impl PilConfig {
    /// Settings for `elf`, the FIFO directory made in the system temporary directory.
    #[must_use]
    pub fn new(elf: PathBuf) -> Self {
        Self {
            elf,
            qemu: std::env::var("REENTRY_PIL_QEMU")
                .unwrap_or_else(|_| onboard_spec::machines::QEMU_SYSTEM.into()),
            fifo_parent: std::env::temp_dir(),
            reply_timeout: Duration::from_secs(10),
            qemu_timeout_s: 600,
            machine: None,
            faults: None,
        }
    }
}

/// PIL failures; each names what failed.
#[derive(Debug, thiserror::Error)]
pub enum PilError {
    /// QEMU is not installed.
    #[error("`{0} --version` failed: QEMU is missing (install qemu-system-arm)")]
    QemuMissing(String),
    /// The firmware ELF is missing.
    #[error(
        "firmware ELF {0} not found (build it: cargo build -p onboard-demo --profile firmware --target thumbv7em-none-eabihf)"
    )]
    ElfMissing(PathBuf),
    /// Creating, opening or using a FIFO failed.
    #[error("FIFO {path}: {reason}")]
    Fifo {
        /// The FIFO.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// QEMU could not be started or failed.
    #[error("QEMU: {0}")]
    Qemu(String),
    /// QEMU exited before the run ended (bad ELF, firmware failure, ...).
    #[error("{0}")]
    QemuExited(QemuExit),
    /// A command frame failed the checks against the configuration; the run ends there.
    #[error("command frame {seq} (tick at t = {time_s} s) rejected: {violation}")]
    BadCommand {
        /// Sequence number.
        seq: u32,
        /// Time of the nav sample it answered \[s\].
        time_s: f64,
        /// What it violated.
        #[source]
        violation: FrameViolation,
    },
    /// The firmware did not answer in time.
    #[error("timeout after {0:?} waiting for {1}")]
    Timeout(Duration, &'static str),
    /// A received frame was malformed.
    #[error("bad frame from the firmware: {0}")]
    Link(LinkError),
    /// The firmware rejected a set-up item (its status names the core's check).
    #[error("firmware rejected set-up item {index} ({item:?}) with status {status:?}")]
    SetupRejected {
        /// Position of the item in the set-up sequence.
        index: usize,
        /// The item.
        item: guidance_core::setup::SetupItem,
        /// The firmware's status.
        status: guidance_core::link::LinkStatus,
    },
    /// The firmware answered with an error status or an unexpected frame.
    #[error("firmware answered frame {seq} with {what}")]
    Firmware {
        /// Sequence number of the nav frame.
        seq: u32,
        /// The status or frame received.
        what: String,
    },
    /// The reference mission the firmware flies could not be set up on the host.
    #[error("reference mission guidance: {0}")]
    Mission(guidance_core::GuidanceError),
    /// The simulation around the firmware failed.
    #[error("simulation: {0}")]
    Sim(#[from] sim::SimError),
    /// The reference mission could not be set up (e.g. its vehicle did not load).
    #[error("reference mission: {0}")]
    Scenario(#[from] ScenarioError),
}

/// Counters of one PIL run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PilStats {
    /// Nav/command round trips.
    pub frames: u64,
    /// Total time spent waiting for answers (write + read) \[s\].
    pub link_s: f64,
    /// Deepest stack of the firmware's whole run, as it measured it (stack painting) and
    /// printed at the end \[bytes\] (`None`: not reported).
    pub firmware_stack_bytes: Option<u64>,
    /// Link faults injected by the host and their outcomes.
    pub faults: FaultCounts,
    /// Faults the firmware counted (rejected frames and samples), as it printed at the end
    /// (`None`: not reported).
    pub firmware_faults: Option<u64>,
}
