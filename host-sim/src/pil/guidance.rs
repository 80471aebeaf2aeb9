//! [`PilGuidance`]: QEMU running the firmware, the FIFO link, and the closed loop's attitude
//! source that talks to it.

use std::fs::{File, OpenOptions};
use std::io::{Read, Write};
use std::path::PathBuf;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use guidance_core::NavState;
use guidance_core::estimate::SensedAero;
use guidance_core::guidance::Command;
use guidance_core::link::{
    CommandFrame, FRAME_LEN, Frame, ImageFrame, LinkStatus, NavFrame, SetupFrame, decode, encode,
};
use guidance_core::setup::SetupItem;

use super::fifo::{FifoDir, mkfifo, open_fifo};
use super::qemu::Qemu;
use super::{Exchange, FifoOp, FrameLimits, PilConfig, PilError, PilRecord, PilStats};

/// A FIFO failure.
fn fifo(path: PathBuf, op: FifoOp, source: std::io::Error) -> PilError {
    PilError::Fifo { path, op, source }
}
use crate::sim::AttitudeSource;

/// The firmware in QEMU as the closed loop's attitude source (see the module docs).
pub struct PilGuidance {
    cfg: PilConfig,
    // Field order is drop order: the link first, then QEMU, then the directory.
    nav: Option<File>,
    replies: Option<Receiver<std::io::Result<[u8; FRAME_LEN]>>>,
    qemu: Option<Qemu>,
    dir: FifoDir,
    pub(super) last: Option<CommandFrame>,
    pub(super) next_tick_s: f64,
    /// The firmware's guidance period \[s\].
    pub(super) period_s: f64,
    /// What every command frame must respect.
    limits: FrameLimits,
    seq: u32,
    pub(super) stats: PilStats,
    pub(super) record: PilRecord,
    /// The link fault injector (`None`: a clean link).
    pub(super) faults: Option<super::faults::FaultInjector>,
    /// The measurement of the coming tick (sent in its nav frame).
    sensed: Option<SensedAero<f64>>,
    /// Whether the uploaded stack uses sensed accelerations.
    senses: bool,
}

impl PilGuidance {
    /// Create the FIFOs, start QEMU on the firmware and open the link, for the HORUS-2B
    /// reference mission compiled into the firmware.
    ///
    /// # Errors
    /// [`PilError::QemuMissing`], [`PilError::ElfMissing`], [`PilError::Fifo`],
    /// [`PilError::QemuSpawn`], [`PilError::QemuExited`] or [`PilError::Timeout`]; QEMU is stopped
    /// and the FIFOs removed.
    pub fn start(cfg: PilConfig) -> Result<Self, PilError> {
        let mission =
            guidance_core::missions::horus2b_reference::<f64>().map_err(PilError::Mission)?;
        let limits = FrameLimits {
            bounds: mission.table.bounds(),
            rates: mission.config.rates,
            initial: mission.initial,
            period_s: mission.config.period_s,
        };
        Self::start_with(cfg, limits, &[])
    }

    /// As [`PilGuidance::start`], first uploading `setup` (the items of
    /// [`super::scenario_setup`]; none: the firmware's compiled-in reference mission) and
    /// checking command frames against `limits` (the configuration the firmware flies).
    ///
    /// # Errors
    /// As [`PilGuidance::start`]; [`PilError::SetupRejected`] if the firmware rejects an item.
    pub fn start_with(
        cfg: PilConfig,
        limits: FrameLimits,
        setup: &[SetupItem],
    ) -> Result<Self, PilError> {
        cfg.check_tools()?;
        let dir = FifoDir::create(&cfg.fifo_parent)?;
        let faults = cfg.faults.map(super::faults::FaultInjector::new);
        let mut me = Self {
            cfg,
            nav: None,
            replies: None,
            qemu: None,
            dir,
            last: None,
            next_tick_s: 0.0,
            period_s: limits.period_s,
            limits,
            seq: 0,
            stats: PilStats::default(),
            record: PilRecord::default(),
            faults: None,
            sensed: None,
            senses: false,
        };
        let (nav_path, cmd_path) = me.paths();
        mkfifo(&nav_path)?;
        mkfifo(&cmd_path)?;
        let qemu = me.qemu.insert(Qemu::spawn(&me.cfg, me.dir.path())?);
        // Without the record a later run cannot stop this QEMU; its watchdog still does.
        let _ = super::fifo::write_owner(me.dir.path(), Some(qemu.pgid()));
        let t = me.cfg.reply_timeout;
        me.nav = Some(open_fifo(&nav_path, true, t, qemu)?);
        let mut cmd = open_fifo(&cmd_path, false, t, qemu)?;
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            loop {
                let mut b = [0u8; FRAME_LEN];
                let r = cmd.read_exact(&mut b).map(|()| b);
                let stop = r.is_err();
                if tx.send(r).is_err() || stop {
                    break;
                }
            }
        });
        me.replies = Some(rx);
        for (index, item) in setup.iter().enumerate() {
            me.upload(index, *item)?;
        }
        // Faults only on the flight's nav frames, after a clean set-up.
        me.faults = faults;
        Ok(me)
    }

    /// Write `buf` and wait for one answer frame (raw bytes). `waiting_for` names the answer
    /// in a timeout.
    pub(super) fn roundtrip(&mut self, buf: &[u8; FRAME_LEN]) -> Result<[u8; FRAME_LEN], PilError> {
        self.roundtrip_for(buf, "an answer")
    }

    fn roundtrip_for(
        &mut self,
        buf: &[u8; FRAME_LEN],
        waiting_for: &'static str,
    ) -> Result<[u8; FRAME_LEN], PilError> {
        let (nav_path, cmd_path) = self.paths();
        let Some(f) = self.nav.as_mut() else {
            return Err(fifo(
                nav_path,
                FifoOp::Write,
                std::io::ErrorKind::NotConnected.into(),
            ));
        };
        if let Err(e) = f.write_all(buf) {
            return Err(self.dead_or(fifo(nav_path, FifoOp::Write, e)));
        }
        let Some(rx) = self.replies.as_ref() else {
            return Err(fifo(
                cmd_path,
                FifoOp::Read,
                std::io::ErrorKind::NotConnected.into(),
            ));
        };
        let err = match rx.recv_timeout(self.cfg.reply_timeout) {
            Ok(Ok(b)) => return Ok(b),
            Ok(Err(e)) => fifo(cmd_path, FifoOp::Read, e),
            Err(RecvTimeoutError::Timeout) => {
                PilError::Timeout(self.cfg.reply_timeout, waiting_for)
            }
            // The reader thread stopped after reporting its error.
            Err(RecvTimeoutError::Disconnected) => fifo(
                cmd_path,
                FifoOp::Read,
                std::io::ErrorKind::BrokenPipe.into(),
            ),
        };
        Err(self.dead_or(err))
    }

    /// Next sequence number.
    pub(super) fn next_seq(&mut self) -> u32 {
        let s = self.seq;
        self.seq = self.seq.wrapping_add(1);
        s
    }

    /// As [`PilGuidance::start_with`], uploading a set-up image (protocol v2,
    /// `guidance_core::setup::image`: the whole stack) instead of set-up items; `senses`: the
    /// stack uses sensed accelerations (they then go with every tick's nav frame).
    ///
    /// # Errors
    /// As [`PilGuidance::start`]; [`PilError::ImageRejected`] if the firmware refuses a chunk
    /// or the image.
    pub fn start_with_image(
        cfg: PilConfig,
        limits: FrameLimits,
        image: &[u8],
        senses: bool,
    ) -> Result<Self, PilError> {
        let faults = cfg.faults;
        let mut cfg = cfg;
        cfg.faults = None;
        let mut me = Self::start_with(cfg, limits, &[])?;
        for (index, count, data) in guidance_core::setup::image::chunks(image) {
            let seq = me.next_seq();
            let mut buf = [0u8; FRAME_LEN];
            encode(
                &Frame::Image(ImageFrame {
                    seq,
                    index,
                    count,
                    data,
                }),
                &mut buf,
            )
            .map_err(PilError::Link)?;
            let bytes = me.roundtrip_for(&buf, "a set-up image answer")?;
            match decode(&bytes).map_err(PilError::Link)? {
                Frame::Command(c) if c.seq == seq && c.status == LinkStatus::Ok => {}
                Frame::Command(c) if c.seq == seq => {
                    return Err(PilError::ImageRejected {
                        index,
                        count,
                        status: c.status,
                    });
                }
                Frame::Command(c) => {
                    return Err(PilError::OutOfSequence {
                        seq,
                        got: c.seq,
                        status: c.status,
                    });
                }
                frame => return Err(PilError::UnexpectedFrame { seq, frame }),
            }
        }
        me.senses = senses;
        me.faults = faults.map(super::faults::FaultInjector::new);
        Ok(me)
    }

    /// Send one set-up item and wait for its status.
    fn upload(&mut self, index: usize, item: SetupItem) -> Result<(), PilError> {
        let seq = self.seq;
        self.seq = self.seq.wrapping_add(1);
        let mut buf = [0u8; FRAME_LEN];
        encode(&Frame::Setup(SetupFrame { seq, item }), &mut buf).map_err(PilError::Link)?;
        let bytes = self.roundtrip_for(&buf, "a set-up answer")?;
        match decode(&bytes).map_err(PilError::Link)? {
            Frame::Command(c) if c.seq == seq && c.status == LinkStatus::Ok => Ok(()),
            Frame::Command(c) if c.seq == seq => Err(PilError::SetupRejected {
                index,
                item,
                status: c.status,
            }),
            Frame::Command(c) => Err(PilError::OutOfSequence {
                seq,
                got: c.seq,
                status: c.status,
            }),
            frame => Err(PilError::UnexpectedFrame { seq, frame }),
        }
    }

    /// The record of the frames exchanged (a handle: clone it before the run to keep it after
    /// a failure).
    #[must_use]
    pub fn record(&self) -> PilRecord {
        self.record.clone()
    }

    /// The FIFO directory of this run (removed when the run ends).
    #[must_use]
    pub fn fifo_dir(&self) -> &std::path::Path {
        self.dir.path()
    }

    /// If QEMU has exited, the error reporting its status and output; else `fallback`.
    fn dead_or(&mut self, fallback: PilError) -> PilError {
        match self
            .qemu
            .as_mut()
            .map(|q| q.wait(Duration::from_millis(200)))
        {
            Some(Some(e)) => PilError::QemuExited(e),
            _ => fallback,
        }
    }

    fn paths(&self) -> (PathBuf, PathBuf) {
        (self.dir.path().join("nav"), self.dir.path().join("cmd"))
    }

    /// Counters so far.
    #[must_use]
    pub fn stats(&self) -> PilStats {
        self.stats
    }

    /// Send one nav state and wait for the answer; check the answer against the configured
    /// bounds, rates and tick timing.
    ///
    /// # Errors
    /// [`PilError`] naming the failure (FIFO write, timeout, QEMU exit, bad frame, firmware
    /// status, [`PilError::BadCommand`]); the exchange is in the record, marked.
    pub fn exchange(&mut self, nav: &NavState<f64>) -> Result<CommandFrame, PilError> {
        let seq = self.seq;
        self.record.push(Exchange {
            seq,
            nav: *nav,
            reply: None,
            failure: None,
            fault: None,
        });
        let r = self.exchange_inner(seq, nav);
        if let Err(e) = &r {
            self.record.mark_failed(e.to_string());
        }
        r
    }

    fn exchange_inner(&mut self, seq: u32, nav: &NavState<f64>) -> Result<CommandFrame, PilError> {
        let started = Instant::now();
        self.seq = self.seq.wrapping_add(1);
        let mut buf = [0u8; FRAME_LEN];
        let sensed = self.sensed.take();
        encode(
            &Frame::Nav(NavFrame {
                seq,
                nav: *nav,
                sensed,
            }),
            &mut buf,
        )
        .map_err(PilError::Link)?;
        let bytes = self.roundtrip_for(&buf, "a command frame")?;
        self.stats.frames += 1;
        self.stats.link_s += started.elapsed().as_secs_f64();
        let frame = decode(&bytes).map_err(PilError::Link)?;
        if let Frame::Command(c) = frame {
            self.record.set_reply(c);
        }
        match frame {
            Frame::Command(c) if c.seq == seq && c.status == LinkStatus::Ok => {
                self.limits
                    .check(&c, nav.time_s, self.last.as_ref())
                    .map_err(|violation| PilError::BadCommand {
                        seq,
                        time_s: nav.time_s,
                        violation,
                    })?;
                Ok(c)
            }
            Frame::Command(c) if c.seq == seq => Err(PilError::FirmwareStatus {
                seq,
                status: c.status,
            }),
            Frame::Command(c) => Err(PilError::OutOfSequence {
                seq,
                got: c.seq,
                status: c.status,
            }),
            frame => Err(PilError::UnexpectedFrame { seq, frame }),
        }
    }

    /// Send the end frame and wait for QEMU to exit 0.
    ///
    /// # Errors
    /// [`PilError::QemuExited`] if the firmware fails, [`PilError::Timeout`] if it does not
    /// exit in time.
    pub fn finish(mut self) -> Result<PilStats, PilError> {
        let mut buf = [0u8; FRAME_LEN];
        encode(&Frame::End(self.seq), &mut buf).map_err(PilError::Link)?;
        let nav_path = self.paths().0;
        if let Some(f) = self.nav.as_mut() {
            f.write_all(&buf)
                .map_err(|e| fifo(nav_path, FifoOp::Write, e))?;
        }
        self.nav = None;
        let timeout = self.cfg.reply_timeout;
        let Some(q) = self.qemu.as_mut() else {
            return Err(PilError::QemuNotRunning);
        };
        match q.wait(timeout) {
            Some(e) if q.succeeded() => {
                // "pil: end of run after N frames; faults F; ticks K; overruns O;
                // max tick T us; stack M bytes"
                let field = |key: &str| summary_field(&e.stdout, key);
                self.stats.firmware_stack_bytes = field("stack");
                self.stats.firmware_faults = field("faults");
                self.stats.firmware_ticks = field("ticks");
                self.stats.firmware_overruns = field("overruns");
                self.stats.firmware_max_tick_us = field("max tick");
                Ok(self.stats)
            }
            Some(e) => Err(PilError::QemuExited(e)),
            None => Err(PilError::Timeout(
                timeout,
                "QEMU to exit after the end frame",
            )),
        }
    }
}

/// The number after `; KEY ` in the firmware's summary line (`None` if absent or not a
/// number).
fn summary_field(stdout: &str, key: &str) -> Option<u64> {
    let rest = stdout.split(&format!("; {key} ")).nth(1)?;
    rest.split([';', ' ']).next()?.trim().parse().ok()
}

impl Drop for PilGuidance {
    fn drop(&mut self) {
        self.nav = None;
        // Stop QEMU (its process group): the reader thread then sees the end of the cmd FIFO.
        if let Some(mut q) = self.qemu.take() {
            q.stop();
        }
        // Release a reader thread still blocked in opening the cmd FIFO; `dir` is removed when
        // the fields drop.
        drop(
            OpenOptions::new()
                .read(true)
                .write(true)
                .open(self.paths().1),
        );
        self.replies = None;
    }
}

impl AttitudeSource for PilGuidance {
    type Error = PilError;
    fn tick(&mut self, nav: &NavState<f64>) -> Result<(), PilError> {
        if self.faults.is_some() {
            return self.tick_with_faults(nav);
        }
        let c = self.exchange(nav)?;
        self.next_tick_s = c.tick_time_s + self.period_s;
        self.last = Some(c);
        Ok(())
    }
    fn sense(&mut self, _nav: &NavState<f64>, sensed: &SensedAero<f64>) -> Result<(), PilError> {
        self.sensed = Some(*sensed);
        Ok(())
    }
    fn senses(&self) -> bool {
        self.senses
    }
    fn attitude_at(&self, time_s: f64) -> Command<f64> {
        match &self.last {
            Some(c) => c.attitude_at(time_s),
            // Before the first tick: the firmware's initial attitude.
            None => self.limits.initial,
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

#[cfg(test)]
mod tests {
    use super::summary_field;

    #[test]
    fn summary_line_fields() {
        let line = "pil: end of run after 812 frames; faults 3; ticks 405; overruns 0; \
                    max tick 1234 us; stack 8636 bytes\n";
        assert_eq!(summary_field(line, "faults"), Some(3));
        assert_eq!(summary_field(line, "ticks"), Some(405));
        assert_eq!(summary_field(line, "overruns"), Some(0));
        assert_eq!(summary_field(line, "max tick"), Some(1234));
        assert_eq!(summary_field(line, "stack"), Some(8636));
        // An older firmware's line: the timing is not reported.
        let old = "pil: end of run after 812 frames; faults 3; stack 8636 bytes or more\n";
        assert_eq!(summary_field(old, "overruns"), None);
        assert_eq!(summary_field(old, "stack"), Some(8636));
        assert_eq!(summary_field("pil: FAIL", "stack"), None);
    }
}
