//! [`PilGuidance`]: QEMU running the firmware, the FIFO link, and the closed loop's attitude
//! source that talks to it.

use std::fs::{File, OpenOptions};
use std::io::{Read, Write};
use std::path::PathBuf;
use std::process::{Child, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use guidance_core::NavState;
use guidance_core::guidance::Command;
use guidance_core::link::{CommandFrame, FRAME_LEN, Frame, LinkStatus, NavFrame, decode, encode};

use super::fifo::{mkfifo, open_fifo};
use super::{PilConfig, PilError, PilStats};
use crate::sim::AttitudeSource;

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
    /// The firmware's attitude before its first tick (the mission's initial attitude) \[rad\].
    initial: Command<f64>,
    seq: u32,
    stats: PilStats,
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
        let mission =
            guidance_core::missions::horus2b_reference::<f64>().map_err(PilError::Mission)?;
        let mut me = Self {
            cfg,
            child: None,
            nav: None,
            replies: None,
            last: None,
            next_tick_s: 0.0,
            period_s: mission.config.period_s,
            initial: mission.initial,
            seq: 0,
            stats: PilStats::default(),
        };
        let (nav_path, cmd_path) = me.paths();
        mkfifo(&nav_path)?;
        mkfifo(&cmd_path)?;
        let child = std::process::Command::new("timeout")
            .arg(me.cfg.qemu_timeout_s.to_string())
            .arg(&me.cfg.qemu)
            .args(onboard_spec::machines::PIL_MACHINE.qemu_args())
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

impl AttitudeSource for PilGuidance {
    type Error = PilError;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), PilError> {
        let c = self.exchange(nav)?;
        self.next_tick_s = c.tick_time_s + self.period_s;
        self.last = Some(c);
        Ok(())
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        match &self.last {
            Some(c) => c.attitude_at(time_s),
            // Before the first tick: the firmware's initial attitude.
            None => self.initial,
        }
    }
    fn next_tick_s(&self) -> f64 {
        self.next_tick_s
    }
    fn next_kink_s(&self, time_s: f64) -> f64 {
        self.last
            .and_then(|c| c.ramp_end().next_after(time_s))
            .unwrap_or(f64::INFINITY)
    }
}
