//! QEMU as a child process that every exit path stops: its own process group (so a terminal's
//! Ctrl-C does not reach it half-way and a kill reaches all of it), a watchdog that dies with
//! the host ([`WATCHDOG`]: a SIGKILLed host-sim leaves neither QEMU nor the FIFO directory),
//! `timeout -k` for the run's wall-time limit, output drained by threads (QEMU never blocks on
//! a full pipe), and a registry the Ctrl-C handler empties ([`interrupt_cleanup`]).
//!
//! No `unsafe` (so no `PR_SET_PDEATHSIG`): the host holds the only write end of a pipe on the
//! watchdog's stdin, and the kernel closes it when the host dies, however it dies.

use std::io::Write;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, ExitStatus, Stdio};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use super::{PilConfig, PilError};

/// Grace period `timeout -k` gives QEMU after its SIGTERM before a SIGKILL \[s\].
const KILL_AFTER_S: u32 = 2;

/// The watchdog QEMU runs under (`sh -c WATCHDOG watchdog DIR timeout ... QEMU ...`), leader
/// of QEMU's process group. Its stdin is a pipe whose write end only the host holds; a
/// background reader waits on it:
///
/// * a line (the host's orderly [`Qemu::stop`], after QEMU is stopped): the reader exits;
/// * end of file without a line (the host died, SIGKILL included, or closed it without
///   stopping): the reader removes the FIFO directory `DIR` and SIGKILLs the process group
///   (itself, the shell, `timeout` and QEMU, which `timeout --foreground` keeps in the group).
///
/// The shell itself runs QEMU (stdin `/dev/null`) and exits with its status (that of
/// `timeout`: 124 if the wall-time limit hit). The remaining case, the watchdog killed with
/// the host, is cleaned by the next run (the FIFO directory's owner record, `pil::OWNER_FILE`,
/// which names the group: [`Qemu::pgid`]).
pub(super) const WATCHDOG: &str = r#"d=$1; shift
exec 3<&0
{ if read -r _ <&3; then exit 0; fi; rm -rf -- "$d"; kill -s KILL 0; } </dev/null >/dev/null 2>&1 &
exec 3<&-
"$@" </dev/null &
wait $!
"#;

/// Live PIL runs: (process group, FIFO directory), for [`interrupt_cleanup`].
static LIVE: Mutex<Vec<(u32, PathBuf)>> = Mutex::new(Vec::new());

fn live() -> std::sync::MutexGuard<'static, Vec<(u32, PathBuf)>> {
    LIVE.lock().unwrap_or_else(PoisonError::into_inner)
}

/// SIGKILL to the whole process group `pgid` (QEMU blocked in a FIFO open ignores SIGTERM).
pub(super) fn kill_group(pgid: u32) {
    let _ = std::process::Command::new("kill")
        .args(["-s", "KILL", "--", &format!("-{pgid}")])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
}

/// Stop every QEMU this process started and remove their FIFO directories. For a signal
/// handler (the CLI calls it on Ctrl-C before exiting); runs stopped here are also stopped
/// again harmlessly by their own drop.
pub fn interrupt_cleanup() {
    let runs: Vec<(u32, PathBuf)> = live().drain(..).collect();
    for (pgid, dir) in runs {
        kill_group(pgid);
        let _ = std::fs::remove_dir_all(dir);
    }
}

/// How QEMU ended: exit status and what it printed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct QemuExit {
    /// Exit status (of the watchdog, which passes `timeout`'s on, which passes QEMU's on; 124
    /// if the wall-time limit hit).
    pub status: String,
    /// QEMU's (and the firmware's semihosting) stdout.
    pub stdout: String,
    /// QEMU's stderr.
    pub stderr: String,
}

impl std::fmt::Display for QemuExit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "QEMU exited with {}", self.status)?;
        let err = self.stderr.trim();
        if !err.is_empty() {
            write!(f, "; stderr: {err}")?;
        }
        let out = self.stdout.trim();
        if !out.is_empty() {
            write!(f, "; stdout: {out}")?;
        }
        Ok(())
    }
}

type Sink = (Arc<Mutex<Vec<u8>>>, Option<std::thread::JoinHandle<()>>);

fn drain(mut r: impl std::io::Read + Send + 'static) -> Sink {
    let sink: Arc<Mutex<Vec<u8>>> = Arc::default();
    let s = Arc::clone(&sink);
    let h = std::thread::spawn(move || {
        let mut buf = [0u8; 4096];
        while let Ok(n) = r.read(&mut buf) {
            if n == 0 {
                break;
            }
            if let Some(b) = buf.get(..n) {
                s.lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .extend_from_slice(b);
            }
        }
    });
    (sink, Some(h))
}

/// Wait (at most 2 s) for a drain thread to reach the end of its pipe, then its text.
fn text(s: &mut Sink) -> String {
    if let Some(h) = s.1.take() {
        let deadline = Instant::now() + Duration::from_secs(2);
        while !h.is_finished() && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(1));
        }
        if h.is_finished() {
            let _ = h.join();
        }
    }
    String::from_utf8_lossy(&s.0.lock().unwrap_or_else(PoisonError::into_inner)).into_owned()
}

/// QEMU running the firmware (see the module docs); stopped on drop.
pub(super) struct Qemu {
    child: Child,
    /// The watchdog's stdin ([`WATCHDOG`]): a line, then closed, by [`Qemu::stop`].
    watchdog: Option<std::process::ChildStdin>,
    pgid: u32,
    stdout: Sink,
    stderr: Sink,
    exit: Option<ExitStatus>,
}

impl Qemu {
    /// Start QEMU on `cfg.elf` (made absolute) with working directory `dir` (the FIFO
    /// directory: the firmware opens `./nav` and `./cmd`, so neither the directory's length nor
    /// its characters matter), command line `.`, under the [`WATCHDOG`] (which removes `dir`
    /// if the host dies).
    pub(super) fn spawn(cfg: &PilConfig, dir: &Path) -> Result<Self, PilError> {
        let elf =
            std::fs::canonicalize(&cfg.elf).map_err(|_| PilError::ElfMissing(cfg.elf.clone()))?;
        // The registry stays locked from the spawn until QEMU is in it: a Ctrl-C in between
        // ([`interrupt_cleanup`], which then exits the process) waits for it and kills it,
        // instead of missing a QEMU that outlives the host in its own process group.
        let mut registry = live();
        let mut child = std::process::Command::new("sh")
            .arg("-c")
            .arg(WATCHDOG)
            .arg("reentry-pil-watchdog")
            .arg(dir)
            .arg("timeout")
            .arg("--foreground")
            .arg("-k")
            .arg(KILL_AFTER_S.to_string())
            .arg(cfg.qemu_timeout_s.to_string())
            .arg(&cfg.qemu)
            .args(
                cfg.machine
                    .unwrap_or_else(|| super::machine_of_elf(&elf))
                    .qemu_args(),
            )
            .arg(&elf)
            .arg("-append")
            .arg(".")
            .current_dir(dir)
            .process_group(0)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|source| PilError::QemuSpawn {
                program: cfg.qemu.clone().into(),
                source,
            })?;
        let pgid = child.id();
        registry.push((pgid, dir.to_path_buf()));
        drop(registry);
        let watchdog = child.stdin.take();
        let stdout = child
            .stdout
            .take()
            .map_or_else(|| (Arc::default(), None), drain);
        let stderr = child
            .stderr
            .take()
            .map_or_else(|| (Arc::default(), None), drain);
        Ok(Self {
            child,
            watchdog,
            pgid,
            stdout,
            stderr,
            exit: None,
        })
    }

    /// The exit report if QEMU has exited (output threads given a moment to finish).
    pub(super) fn exited(&mut self) -> Option<QemuExit> {
        if self.exit.is_none() {
            self.exit = self.child.try_wait().ok().flatten();
        }
        let status = self.exit?;
        // The pipes close with the process: the drain threads reach their end (joined, so the
        // last line is never lost to a slow thread).
        Some(QemuExit {
            status: status.to_string(),
            stdout: text(&mut self.stdout),
            stderr: text(&mut self.stderr),
        })
    }

    /// Wait at most `timeout` for QEMU to exit; its report, or `None` if still running.
    pub(super) fn wait(&mut self, timeout: Duration) -> Option<QemuExit> {
        let deadline = Instant::now() + timeout;
        loop {
            if let Some(e) = self.exited() {
                return Some(e);
            }
            if Instant::now() >= deadline {
                return None;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// QEMU's process group (the watchdog's pid).
    pub(super) fn pgid(&self) -> u32 {
        self.pgid
    }

    /// Whether the exit status was success.
    pub(super) fn succeeded(&self) -> bool {
        self.exit.is_some_and(|s| s.success())
    }

    /// SIGKILL the process group and reap the watchdog; then release the watchdog's reader
    /// (a line, then end of file), which leaves the FIFO directory to its owner.
    pub(super) fn stop(&mut self) {
        if self.exit.is_none() {
            kill_group(self.pgid);
            self.exit = self.child.wait().ok();
        }
        if let Some(mut w) = self.watchdog.take() {
            // Fails (broken pipe) if the group was killed: nothing is left to release then.
            let _ = w.write_all(b"\n");
        }
        live().retain(|(p, _)| *p != self.pgid);
    }
}

impl Drop for Qemu {
    fn drop(&mut self) {
        self.stop();
    }
}
