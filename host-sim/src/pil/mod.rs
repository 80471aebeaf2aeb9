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
mod fifo;
mod guidance;
mod qemu;
mod record;
mod reference;

use std::path::PathBuf;
use std::time::Duration;

use guidance_core::link::LinkError;

use crate::scenario::ScenarioError;
use crate::sim;

pub use check::{ANGLE_SLACK_RAD, FrameLimits, FrameViolation, RELATIVE_SLACK};
pub use fifo::FIFO_DIR_PREFIX;
pub use guidance::PilGuidance;
pub use qemu::{QemuExit, interrupt_cleanup};
pub use record::{Exchange, PilRecord};
pub use reference::{
    fly_reference, fly_reference_pil, fly_reference_pil_recorded, fly_reference_sil,
    reference_sil_guidance,
};

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
}
