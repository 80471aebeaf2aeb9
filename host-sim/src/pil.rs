//! Processor-in-the-loop (PIL): the closed loop flies the firmware's guidance running in QEMU.
//!
//! [`PilGuidance`] is an [`AttitudeSource`]: at every 2 s tick it sends the navigation state to
//! the firmware (`onboard-demo`'s `pil` binary, `f32` guidance with the HORUS-2B reference
//! table compiled in) as a `guidance_core::link` [`NavFrame`] and waits for the
//! [`CommandFrame`]; between ticks it reproduces the rate-limited ramp from that frame
//! ([`CommandFrame::attitude_at`]). The frames go through two named FIFOs,
//! `<dir>/nav` and `<dir>/cmd`, that the firmware opens through semihosting; `<dir>` is passed
//! to the firmware as QEMU's `-append` command line.
//!
//! Nothing hangs: QEMU runs under `timeout`, opening the FIFOs and every answer wait at most
//! [`PilConfig::reply_timeout`] (a reader thread with a channel), and on any failure QEMU is
//! killed and the FIFOs are removed (also on drop).

use guidance_core::guidance::Command;
use std::fs::{File, OpenOptions};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use guidance_core::NavState;
use guidance_core::link::{
    CommandFrame, FRAME_LEN, Frame, LinkError, LinkStatus, NavFrame, decode, encode,
};

use crate::dynamics::Dynamics;
use crate::env::Environment;
use crate::scenario::{Scenario, ScenarioError, build_guidance};
use crate::sim::{self, AttitudeSource, SimResult, ramp_kink};
use crate::vehicle::Vehicle;

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
            qemu: "qemu-system-arm".into(),
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

/// The firmware in QEMU as the closed loop's attitude source (see the module docs).
pub struct PilGuidance {
    cfg: PilConfig,
    child: Option<Child>,
    nav: Option<File>,
    replies: Option<Receiver<Result<[u8; FRAME_LEN], String>>>,
    last: Option<CommandFrame>,
    next_tick_s: f64,
    /// The firmware's guidance period \[s\] (the thesis 2 s compiled into the `pil` binary).
    period_s: f64,
    seq: u32,
    stats: PilStats,
    /// The first error, kept typed (the loop only sees its message).
    error: Option<String>,
}

fn mkfifo(path: &Path) -> Result<(), PilError> {
    let out = std::process::Command::new("mkfifo")
        .arg(path)
        .output()
        .map_err(|e| PilError::Fifo {
            path: path.into(),
            reason: format!("cannot run mkfifo: {e}"),
        })?;
    if out.status.success() {
        Ok(())
    } else {
        Err(PilError::Fifo {
            path: path.into(),
            reason: format!(
                "mkfifo failed: {}",
                String::from_utf8_lossy(&out.stderr).trim()
            ),
        })
    }
}

/// Open `path` (read or write) in a thread; wait at most `timeout`. A blocked open is released
/// by opening the FIFO read-write ourselves.
fn open_fifo(path: &Path, write: bool, timeout: Duration) -> Result<File, PilError> {
    let (tx, rx) = mpsc::channel();
    let p = path.to_path_buf();
    std::thread::spawn(move || {
        let r = OpenOptions::new().read(!write).write(write).open(&p);
        let _ = tx.send(r);
    });
    match rx.recv_timeout(timeout) {
        Ok(Ok(f)) => Ok(f),
        Ok(Err(e)) => Err(PilError::Fifo {
            path: path.into(),
            reason: format!("cannot open: {e}"),
        }),
        Err(_) => {
            // Unblock the opener thread (a read-write open of a FIFO never blocks on Linux).
            let _unblock = OpenOptions::new().read(true).write(true).open(path);
            Err(PilError::Timeout(timeout, "the firmware to open its FIFOs"))
        }
    }
}

impl PilGuidance {
    /// Create the FIFOs, start QEMU on the firmware and open the link.
    ///
    /// # Errors
    /// [`PilError::QemuMissing`], [`PilError::ElfMissing`], [`PilError::Fifo`],
    /// [`PilError::Qemu`] or [`PilError::Timeout`]; QEMU is stopped and the FIFOs removed.
    pub fn start(cfg: PilConfig) -> Result<Self, PilError> {
        let ok = std::process::Command::new(&cfg.qemu)
            .arg("--version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if !ok {
            return Err(PilError::QemuMissing(cfg.qemu.clone()));
        }
        if !cfg.elf.is_file() {
            return Err(PilError::ElfMissing(cfg.elf.clone()));
        }
        std::fs::create_dir(&cfg.fifo_dir).map_err(|e| PilError::Fifo {
            path: cfg.fifo_dir.clone(),
            reason: format!("cannot create the FIFO directory: {e}"),
        })?;
        let mut me = Self {
            cfg,
            child: None,
            nav: None,
            replies: None,
            last: None,
            next_tick_s: 0.0,
            period_s: 2.0,
            seq: 0,
            stats: PilStats::default(),
            error: None,
        };
        let (nav_path, cmd_path) = me.paths();
        mkfifo(&nav_path)?;
        mkfifo(&cmd_path)?;
        let child = std::process::Command::new("timeout")
            .arg(me.cfg.qemu_timeout_s.to_string())
            .arg(&me.cfg.qemu)
            .args(["-cpu", "cortex-m4", "-machine", "mps2-an386", "-nographic"])
            .args(["-semihosting-config", "enable=on,target=native", "-kernel"])
            .arg(&me.cfg.elf)
            .arg("-append")
            .arg(&me.cfg.fifo_dir)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| PilError::Qemu(format!("cannot start: {e}")))?;
        me.child = Some(child);
        let t = me.cfg.reply_timeout;
        me.nav = Some(open_fifo(&nav_path, true, t)?);
        let mut cmd = open_fifo(&cmd_path, false, t)?;
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            loop {
                let mut b = [0u8; FRAME_LEN];
                let r = cmd
                    .read_exact(&mut b)
                    .map(|()| b)
                    .map_err(|e| e.to_string());
                let stop = r.is_err();
                if tx.send(r).is_err() || stop {
                    break;
                }
            }
        });
        me.replies = Some(rx);
        Ok(me)
    }

    fn paths(&self) -> (PathBuf, PathBuf) {
        (self.cfg.fifo_dir.join("nav"), self.cfg.fifo_dir.join("cmd"))
    }

    /// Counters so far.
    #[must_use]
    pub fn stats(&self) -> PilStats {
        self.stats
    }

    /// Send one nav state and wait for the answer.
    ///
    /// # Errors
    /// [`PilError`] naming the failure (FIFO write, timeout, bad frame, firmware status).
    pub fn exchange(&mut self, nav: &NavState<f64>) -> Result<CommandFrame, PilError> {
        let started = Instant::now();
        let seq = self.seq;
        self.seq = self.seq.wrapping_add(1);
        let mut buf = [0u8; FRAME_LEN];
        encode(&Frame::Nav(NavFrame { seq, nav: *nav }), &mut buf).map_err(PilError::Link)?;
        let nav_path = self.paths().0;
        let f = self.nav.as_mut().ok_or_else(|| PilError::Fifo {
            path: nav_path.clone(),
            reason: "link is closed".into(),
        })?;
        f.write_all(&buf).map_err(|e| PilError::Fifo {
            path: nav_path,
            reason: format!("write failed: {e}"),
        })?;
        let rx = self.replies.as_ref().ok_or(PilError::Timeout(
            Duration::ZERO,
            "a command frame (link closed)",
        ))?;
        let bytes = match rx.recv_timeout(self.cfg.reply_timeout) {
            Ok(Ok(b)) => b,
            Ok(Err(e)) => {
                return Err(PilError::Fifo {
                    path: self.paths().1,
                    reason: format!("read failed: {e} (did the firmware exit?)"),
                });
            }
            Err(RecvTimeoutError::Timeout) => {
                return Err(PilError::Timeout(self.cfg.reply_timeout, "a command frame"));
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PilError::Fifo {
                    path: self.paths().1,
                    reason: "reader stopped".into(),
                });
            }
        };
        self.stats.frames += 1;
        self.stats.link_s += started.elapsed().as_secs_f64();
        match decode(&bytes).map_err(PilError::Link)? {
            Frame::Command(c) if c.seq == seq && c.status == LinkStatus::Ok => Ok(c),
            Frame::Command(c) => Err(PilError::Firmware {
                seq,
                what: match c.status.to_error() {
                    Some(e) if c.seq == seq => format!("guidance error: {e}"),
                    _ => format!("status {:?}, sequence {}", c.status, c.seq),
                },
            }),
            other => Err(PilError::Firmware {
                seq,
                what: format!("unexpected frame {other:?}"),
            }),
        }
    }

    /// Send the end frame and wait for QEMU to exit 0.
    ///
    /// # Errors
    /// [`PilError::Qemu`] if the firmware fails or does not exit in time.
    pub fn finish(mut self) -> Result<PilStats, PilError> {
        let mut buf = [0u8; FRAME_LEN];
        encode(&Frame::End(self.seq), &mut buf).map_err(PilError::Link)?;
        if let Some(f) = self.nav.as_mut() {
            f.write_all(&buf).map_err(|e| PilError::Fifo {
                path: self.cfg.fifo_dir.join("nav"),
                reason: format!("write failed: {e}"),
            })?;
        }
        self.nav = None;
        let Some(mut child) = self.child.take() else {
            return Err(PilError::Qemu("not running".into()));
        };
        let deadline = Instant::now() + self.cfg.reply_timeout;
        loop {
            match child.try_wait() {
                Ok(Some(status)) => {
                    let mut out = String::new();
                    if let Some(mut o) = child.stdout.take() {
                        let _ = o.read_to_string(&mut out);
                    }
                    return if status.success() {
                        Ok(self.stats)
                    } else {
                        Err(PilError::Qemu(format!(
                            "firmware exited with {status}: {}",
                            out.trim()
                        )))
                    };
                }
                Ok(None) if Instant::now() < deadline => {
                    std::thread::sleep(Duration::from_millis(5));
                }
                Ok(None) => {
                    stop(&mut child);
                    return Err(PilError::Timeout(
                        self.cfg.reply_timeout,
                        "QEMU to exit after the end frame",
                    ));
                }
                Err(e) => return Err(PilError::Qemu(format!("wait failed: {e}"))),
            }
        }
    }
}

/// Stop QEMU: SIGTERM to `timeout`, which passes it on to QEMU (a SIGKILL would orphan QEMU);
/// SIGKILL if it is still running after 2 s.
fn stop(child: &mut Child) {
    if matches!(child.try_wait(), Ok(Some(_))) {
        return;
    }
    let _ = std::process::Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .stderr(Stdio::null())
        .status();
    let deadline = Instant::now() + Duration::from_secs(2);
    while Instant::now() < deadline {
        if !matches!(child.try_wait(), Ok(None)) {
            return;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let _ = child.kill();
    let _ = child.wait();
}

impl Drop for PilGuidance {
    fn drop(&mut self) {
        self.nav = None;
        if let Some(mut c) = self.child.take() {
            stop(&mut c);
        }
        // Release a reader thread still blocked on the cmd FIFO, then remove the FIFOs.
        let (nav, cmd) = self.paths();
        drop(OpenOptions::new().read(true).write(true).open(&cmd));
        let _ = std::fs::remove_file(nav);
        let _ = std::fs::remove_file(cmd);
        let _ = std::fs::remove_dir(&self.cfg.fifo_dir);
    }
}

fn attitude(c: guidance_core::guidance::Command<f64>) -> Command<f64> {
    Command {
        alpha_rad: c.alpha_rad,
        sigma_rad: c.sigma_rad,
    }
}

impl AttitudeSource for PilGuidance {
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), String> {
        match self.exchange(nav) {
            Ok(c) => {
                self.next_tick_s = c.tick_time_s + self.period_s;
                self.last = Some(c);
                Ok(())
            }
            Err(e) => {
                let msg = format!("PIL: {e}");
                self.error.get_or_insert_with(|| msg.clone());
                Err(msg)
            }
        }
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        match &self.last {
            Some(c) => attitude(c.attitude_at(time_s)),
            // Before the first tick: the firmware's initial attitude (40 deg, 0 deg).
            None => Command {
                alpha_rad: 40f64.to_radians(),
                sigma_rad: 0.0,
            },
        }
    }
    fn next_tick_s(&self) -> f64 {
        self.next_tick_s
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        let Some(c) = &self.last else {
            return f64::INFINITY;
        };
        ramp_kink(
            time_s,
            c.tick_time_s,
            attitude(c.ramp_start),
            attitude(c.command),
            (c.rates.alpha_rad_s, c.rates.sigma_rad_s),
        )
    }
}

/// The HORUS-2B reference mission's models and settings (the default scenario, full
/// environment), as flown by SIL and PIL.
fn reference_setup() -> Result<(Scenario, Environment, Vehicle), ScenarioError> {
    let sc = Scenario::default();
    let env = sc.environment.build();
    let veh = sc.vehicle.load()?;
    Ok((sc, env, veh))
}

/// The SIL guidance of the reference mission: `guidance-core`'s `Guidance<f64>` built from the
/// default scenario (the same table, rates, period and initial attitude as the firmware).
///
/// # Errors
/// [`ScenarioError`] if the reference mission cannot be set up.
pub fn reference_sil_guidance() -> Result<sim::CoreGuidance, ScenarioError> {
    let (sc, env, _) = reference_setup()?;
    Ok(sim::CoreGuidance(build_guidance(
        &sc,
        &env.planet,
        "(built-in)",
    )?))
}

/// Fly the HORUS-2B reference mission (default scenario: full environment, HORUS-2B vehicle,
/// its termination, tolerances and output settings) with any attitude source.
///
/// # Errors
/// [`ScenarioError`] naming the failure.
pub fn fly_reference<A: AttitudeSource>(source: A) -> Result<(SimResult, A), ScenarioError> {
    let (sc, env, veh) = reference_setup()?;
    let dynm = Dynamics::from_environment(&env, &veh);
    Ok(sim::simulate(
        dynm,
        source,
        &sc.sim_config(),
        &mut |_, _| {},
    )?)
}

/// Fly the HORUS-2B reference mission in SIL (`f64` core guidance in-process).
///
/// # Errors
/// [`ScenarioError`] naming the failure.
pub fn fly_reference_sil() -> Result<SimResult, ScenarioError> {
    Ok(fly_reference(reference_sil_guidance()?)?.0)
}

/// Fly the HORUS-2B reference mission in PIL: the firmware (`cfg.elf`, with the same reference
/// table, rates, period and initial attitude compiled in) computes every command. Returns the
/// same [`SimResult`] as SIL, plus the link counters.
///
/// # Errors
/// [`PilError`] naming what failed; QEMU is stopped and the FIFOs are removed in every case.
pub fn fly_reference_pil(cfg: PilConfig) -> Result<(SimResult, PilStats), PilError> {
    let (sc, env, veh) = reference_setup()?;
    let source = PilGuidance::start(cfg)?;
    let dynm = Dynamics::from_environment(&env, &veh);
    let (result, source) = sim::simulate(dynm, source, &sc.sim_config(), &mut |_, _| {})?;
    let stats = source.finish()?;
    Ok((result, stats))
}
