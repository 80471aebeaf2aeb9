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
//! Nothing hangs: QEMU runs under `timeout`, opening the FIFOs and every answer wait at most
//! [`PilConfig::reply_timeout`] (a reader thread with a channel), and on any failure QEMU is
//! killed and the FIFOs are removed (also on drop).

mod fifo;
mod guidance;
mod reference;

use std::path::PathBuf;
use std::time::Duration;

use guidance_core::link::LinkError;

use crate::scenario::ScenarioError;
use crate::sim;

pub use guidance::PilGuidance;
pub use reference::{fly_reference, fly_reference_pil, fly_reference_sil, reference_sil_guidance};

/// Where the firmware ELF is looked for by default (relative to the workspace root).
pub const DEFAULT_ELF: &str = "target/thumbv7em-none-eabihf/firmware/pil";

/// PIL settings.
#[derive(Clone, Debug)]
pub struct PilConfig {
    /// Firmware ELF (`onboard-demo`'s `pil` binary for `thumbv7em-none-eabihf`).
    pub elf: PathBuf,
    /// QEMU program.
    pub qemu: String,
    /// Directory created for the FIFOs (removed afterwards); must not exist.
    pub fifo_dir: PathBuf,
    /// Longest wait for the firmware to open a FIFO or answer one frame.
    pub reply_timeout: Duration,
    /// Wall-time limit of the whole QEMU run (`timeout`) \[s\].
    pub qemu_timeout_s: u32,
}

impl PilConfig {
    /// Settings for `elf` with a FIFO directory unique to this process and call.
    #[must_use]
    pub fn new(elf: PathBuf) -> Self {
        use std::sync::atomic::{AtomicU32, Ordering};
        static N: AtomicU32 = AtomicU32::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        Self {
            elf,
            qemu: onboard_spec::machines::QEMU_SYSTEM.into(),
            fifo_dir: std::env::temp_dir().join(format!("reentry-pil-{}-{n}", std::process::id())),
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
