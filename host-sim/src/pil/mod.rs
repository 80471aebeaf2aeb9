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
//! Nothing hangs and nothing is left behind: QEMU runs in its own process group under a
//! watchdog shell and `timeout -k`; opening the FIFOs and every answer wait at most
//! [`PilConfig::reply_timeout`] and stop at once if QEMU exits (its status and stderr are the
//! error); on every exit path (error, drop, unwinding panic, and Ctrl-C through
//! [`interrupt_cleanup`]) the process group is SIGKILLed and the FIFO directory removed. If
//! host-sim itself dies (SIGKILL included), the watchdog sees the end of the pipe host-sim
//! held on its stdin and SIGKILLs the group and removes the directory; a directory whose
//! owner and watchdog both died is removed, its QEMU killed, by the next run in the same
//! parent directory (the owner record: [`OWNER_FILE`]). Every command frame is checked
//! ([`FrameLimits::check`]) before it is flown; the exchanged frames are kept in a
//! [`PilRecord`] that outlives a failed run.

mod campaign;
mod campaign_run;
mod check;
mod faults;
mod faulty_link;
mod fifo;
mod guidance;
mod qemu;
mod record;
mod reference;
mod scenario;

use std::path::PathBuf;
use std::time::Duration;

use guidance_core::link::{Frame, LinkError, LinkStatus};

use crate::scenario::ScenarioError;
use crate::sim;

pub use campaign::{PilCase, TwinCheck, fly_case_pil};
pub use campaign_run::{
    PIL_CHECKS_FILE, PilCaseCheck, PilSilComparison, check_pil_cases, fly_campaign_pil,
    miss_bound_m, pil_mode, write_pil_checks,
};
pub use check::{ANGLE_SLACK_RAD, FrameLimits, FrameViolation, RELATIVE_SLACK};
pub use faults::{FaultConfig, FaultCounts, MAX_RETRIES, RejectedFault};
pub use fifo::{FIFO_DIR_PREFIX, OWNER_FILE};
pub use guidance::PilGuidance;
pub use qemu::{QemuExit, interrupt_cleanup};
pub use record::{Exchange, PilRecord};
pub use reference::{
    fly_reference, fly_reference_pil, fly_reference_pil_recorded, fly_reference_sil,
    reference_sil_guidance,
};
pub use scenario::{ScenarioPil, fly_scenario_pil, scenario_setup};

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
    /// Whether a PIL run can start: QEMU (`qemu --version` runs and succeeds) and the firmware
    /// ELF (a file) are there. Every run checks it before it starts QEMU; a campaign's PIL leg
    /// ([`fly_campaign_pil`]) and `host-sim dispersions --pil` check it before any flight.
    ///
    /// # Errors
    /// [`PilError::QemuMissing`] or [`PilError::ElfMissing`].
    pub fn check_tools(&self) -> Result<(), PilError> {
        let probe = std::process::Command::new(&self.qemu)
            .arg("--version")
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status();
        if !probe.as_ref().is_ok_and(std::process::ExitStatus::success) {
            return Err(PilError::QemuMissing {
                program: self.qemu.clone().into(),
                source: probe.err(),
            });
        }
        if !self.elf.is_file() {
            return Err(PilError::ElfMissing(self.elf.clone()));
        }
        Ok(())
    }

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

/// What was being done with a FIFO (or the FIFO directory) when it failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FifoOp {
    /// Creating the per-run FIFO directory.
    CreateDir,
    /// Creating the FIFO (`mkfifo`).
    Create,
    /// Opening it.
    Open,
    /// Writing a frame to it.
    Write,
    /// Reading a frame from it (did the firmware exit?).
    Read,
}

impl std::fmt::Display for FifoOp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FifoOp::CreateDir => "cannot create the FIFO directory",
            FifoOp::Create => "mkfifo failed",
            FifoOp::Open => "cannot open",
            FifoOp::Write => "write failed",
            FifoOp::Read => "read failed (did the firmware exit?)",
        })
    }
}

/// PIL failures; each names what failed.
#[derive(Debug, thiserror::Error)]
pub enum PilError {
    /// QEMU is not installed (`program --version` could not run, or failed).
    #[error(
        "`{} --version` failed{}: QEMU is missing (install qemu-system-arm)",
        program.display(),
        source.as_ref().map_or_else(String::new, |e| format!(" ({e})"))
    )]
    QemuMissing {
        /// The QEMU program tried.
        program: PathBuf,
        /// Why it could not be run (`None`: it ran and exited with a failure).
        #[source]
        source: Option<std::io::Error>,
    },
    /// The firmware ELF is missing.
    #[error(
        "firmware ELF {} not found (build it: cargo build -p onboard-demo --profile firmware --target thumbv7em-none-eabihf)",
        .0.display()
    )]
    ElfMissing(PathBuf),
    /// Creating, opening or using a FIFO failed.
    #[error("FIFO {}: {op}: {source}", path.display())]
    Fifo {
        /// The FIFO (or the FIFO directory).
        path: PathBuf,
        /// What was being done.
        op: FifoOp,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// QEMU (under its watchdog `sh` and `timeout`) could not be started.
    #[error("cannot start QEMU `{}` (through sh and timeout): {source}", program.display())]
    QemuSpawn {
        /// The QEMU program.
        program: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// QEMU was not running when the run was finished (the link was never started).
    #[error("QEMU is not running")]
    QemuNotRunning,
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
    Link(#[source] LinkError),
    /// The firmware rejected a set-up item (its status names the core's check).
    #[error("firmware rejected set-up item {index} ({item:?}) with status {status:?}")]
    SetupRejected {
        /// Position of the item in the set-up sequence.
        index: usize,
        /// The item.
        item: guidance_core::setup::SetupItem,
        /// The firmware's status.
        status: LinkStatus,
    },
    /// The firmware refused a set-up image chunk (protocol v2; after the last chunk: the image
    /// or the stack it describes).
    #[error("firmware refused set-up image chunk {index} of {count} with status {status:?}")]
    ImageRejected {
        /// Index of the chunk.
        index: u16,
        /// Number of chunks.
        count: u16,
        /// The firmware's status.
        status: LinkStatus,
    },
    /// A campaign case could not be set up or flown (not a link or firmware failure).
    #[error("campaign case: {0}")]
    Campaign(Box<crate::campaign::CampaignError>),
    /// The stack of a campaign case cannot be written as a set-up image.
    #[error("set-up image: {0}")]
    Image(guidance_core::setup::image::ImageError),
    /// The firmware answered a nav frame with an error status (its guidance rejected the sample,
    /// or it could not decode the frame).
    #[error("firmware answered frame {seq} with status {status:?}{}", guidance_error_text(*status))]
    FirmwareStatus {
        /// Sequence number of the nav frame.
        seq: u32,
        /// The firmware's status.
        status: LinkStatus,
    },
    /// The firmware answered with another sequence number than the frame sent.
    #[error("firmware answered frame {seq} with sequence number {got} (status {status:?})")]
    OutOfSequence {
        /// Sequence number of the frame sent.
        seq: u32,
        /// Sequence number of the answer.
        got: u32,
        /// The answer's status.
        status: LinkStatus,
    },
    /// The firmware answered with a frame that is not a command frame.
    #[error("firmware answered frame {seq} with an unexpected {frame:?}")]
    UnexpectedFrame {
        /// Sequence number of the frame sent.
        seq: u32,
        /// The frame received.
        frame: Frame,
    },
    /// The firmware accepted an injected fault it must reject.
    #[error("firmware did not reject the {fault} frame {seq}: it answered {answer:?}")]
    FaultNotRejected {
        /// Sequence number of the faulty frame.
        seq: u32,
        /// The fault.
        fault: RejectedFault,
        /// The firmware's answer.
        answer: Frame,
    },
    /// The reference mission the firmware flies could not be set up on the host.
    #[error("reference mission guidance: {0}")]
    Mission(#[source] guidance_core::GuidanceError),
    /// The simulation around the firmware failed.
    #[error("simulation: {0}")]
    Sim(#[from] sim::SimError),
    /// The scenario flown (the reference mission or any other) could not be set up on the
    /// host (e.g. its vehicle did not load): not a firmware error.
    #[error("scenario: {0}")]
    Scenario(#[from] ScenarioError),
}

/// The firmware link's own error, as it was raised (not wrapped as a guidance failure).
pub(super) fn unwrap_pil_error(e: sim::SimError) -> PilError {
    match e {
        sim::SimError::Guidance { source, time_s } => match source.downcast::<PilError>() {
            Ok(e) => *e,
            Err(source) => PilError::Sim(sim::SimError::Guidance { time_s, source }),
        },
        e => PilError::Sim(e),
    }
}

/// `": guidance error: ..."` for a status that stands for a guidance error, else nothing.
fn guidance_error_text(status: LinkStatus) -> String {
    status
        .to_error()
        .map_or_else(String::new, |e| format!(" (guidance error: {e})"))
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
    /// Guidance ticks the firmware timed with its tick timer, as it printed at the end
    /// (`None`: not reported).
    pub firmware_ticks: Option<u64>,
    /// Ticks whose execution (nav frame read to command written) exceeded the guidance period
    /// on the firmware's tick timer (`None`: not reported). Under QEMU this is emulator wall
    /// time, not a real core's.
    pub firmware_overruns: Option<u64>,
    /// Longest tick execution on the firmware's tick timer \[us\] (`None`: not reported).
    pub firmware_max_tick_us: Option<u64>,
}
