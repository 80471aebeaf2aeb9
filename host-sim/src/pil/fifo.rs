//! The two named FIFOs of the link: creation and opening with a timeout; the per-run FIFO
//! directory, its owner record and the removal of stale directories of dead runs.

use std::fs::{File, OpenOptions};
use std::path::Path;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::qemu::Qemu;
use super::{FifoOp, PilError};

pub(super) fn mkfifo(path: &Path) -> Result<(), PilError> {
    let fail = |source| PilError::Fifo {
        path: path.into(),
        op: FifoOp::Create,
        source,
    };
    let out = std::process::Command::new("mkfifo")
        .arg(path)
        .output()
        .map_err(fail)?;
    if out.status.success() {
        Ok(())
    } else {
        // mkfifo(1) reports the failure on stderr only; it becomes the I/O error's text.
        Err(fail(std::io::Error::other(format!(
            "mkfifo exited with {}: {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        ))))
    }
}

/// Open `path` (read or write) in a thread; wait at most `timeout`, and stop waiting at once
/// if QEMU exits (its status and stderr are the error). A blocked open is released by opening
/// the FIFO read-write ourselves.
pub(super) fn open_fifo(
    path: &Path,
    write: bool,
    timeout: Duration,
    qemu: &mut Qemu,
) -> Result<File, PilError> {
    let (tx, rx) = mpsc::channel();
    let p = path.to_path_buf();
    std::thread::spawn(move || {
        let r = OpenOptions::new().read(!write).write(write).open(&p);
        let _ = tx.send(r);
    });
    let deadline = Instant::now() + timeout;
    loop {
        match rx.recv_timeout(Duration::from_millis(10)) {
            Ok(Ok(f)) => return Ok(f),
            Ok(Err(e)) => {
                return Err(PilError::Fifo {
                    path: path.into(),
                    op: FifoOp::Open,
                    source: e,
                });
            }
            Err(_) => {
                let exited = qemu.exited();
                if exited.is_some() || Instant::now() >= deadline {
                    // Unblock the opener thread (a read-write open of a FIFO never blocks on
                    // Linux).
                    let _unblock = OpenOptions::new().read(true).write(true).open(path);
                    return Err(match exited {
                        Some(e) => PilError::QemuExited(e),
                        None => PilError::Timeout(timeout, "the firmware to open its FIFOs"),
                    });
                }
            }
        }
    }
}

/// Prefix of every PIL FIFO directory (`<parent>/reentry-pil-<pid>-<n>`).
pub const FIFO_DIR_PREFIX: &str = "reentry-pil-";

/// The owner record in each FIFO directory, written atomically (temporary file and rename):
///
/// ```text
/// boot <the kernel's boot id, /proc/sys/kernel/random/boot_id>
/// host <host-sim's pid> <its start time, field 22 of /proc/<pid>/stat>
/// watchdog <QEMU's process group> <its leader's start time>
/// ```
///
/// (the `watchdog` line once QEMU is started). A later run judges the directory by it
/// (when it creates its own): a process is the one recorded only if its pid runs (not a zombie)
/// with the recorded start time, so a reused pid is never taken for the owner nor killed.
pub const OWNER_FILE: &str = "owner";

/// The kernel's boot id (`None` without `/proc`).
fn boot_id() -> Option<String> {
    std::fs::read_to_string("/proc/sys/kernel/random/boot_id")
        .ok()
        .map(|s| s.trim().to_string())
}

/// Process `pid` as `/proc` shows it: (start time in clock ticks since boot, whether it is a
/// zombie); `None` if no such process.
fn process(pid: u32) -> Option<(u64, bool)> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // After the command name (in parentheses, which may hold spaces): field 3 (state) first,
    // field 22 (start time) 20th.
    let mut rest = stat.rsplit_once(')')?.1.split_whitespace();
    let zombie = rest.next()? == "Z";
    let start = rest.nth(18)?.parse().ok()?;
    Some((start, zombie))
}

/// Whether the process recorded as (`pid`, `start`) still runs (a zombie is dead).
fn runs(pid: u32, start: u64) -> bool {
    process(pid).is_some_and(|(s, zombie)| s == start && !zombie)
}

/// Write the owner record of `dir` (this process; the watchdog's process group `watchdog` if
/// started). Without `/proc` nothing is written (no later run could judge the record).
pub(super) fn write_owner(dir: &Path, watchdog: Option<u32>) -> std::io::Result<()> {
    let (Some(boot), Some((start, _))) = (boot_id(), process(std::process::id())) else {
        return Ok(());
    };
    let mut text = format!("boot {boot}\nhost {} {start}\n", std::process::id());
    if let Some((pgid, (s, _))) = watchdog.and_then(|p| process(p).map(|q| (p, q))) {
        text.push_str(&format!("watchdog {pgid} {s}\n"));
    }
    let tmp = dir.join(format!("{OWNER_FILE}.tmp"));
    std::fs::write(&tmp, text)?;
    std::fs::rename(tmp, dir.join(OWNER_FILE))
}

/// An owner record as read back.
struct Owner {
    boot: String,
    host: (u32, u64),
    watchdog: Option<(u32, u64)>,
}

fn read_owner(dir: &Path) -> Option<Owner> {
    let text = std::fs::read_to_string(dir.join(OWNER_FILE)).ok()?;
    let (mut boot, mut host, mut watchdog) = (None, None, None);
    for line in text.lines() {
        let mut w = line.split_whitespace();
        let key = w.next()?;
        if key == "boot" {
            boot = Some(w.next()?.to_string());
            continue;
        }
        let id: (u32, u64) = (w.next()?.parse().ok()?, w.next()?.parse().ok()?);
        match key {
            "host" => host = Some(id),
            "watchdog" => watchdog = Some(id),
            _ => return None,
        }
    }
    Some(Owner {
        boot: boot?,
        host: host?,
        watchdog,
    })
}

/// Remove the FIFO directories in `parent` whose owner (by its record, [`OWNER_FILE`]) is dead,
/// first SIGKILLing their QEMU's process group if it still runs: what a host-sim killed with
/// its watchdog (e.g. SIGKILL to both) left. A directory without a readable record, or whose
/// owner runs, is left alone; so is every directory when `/proc` is absent.
fn remove_stale(parent: &Path) {
    let Some(boot) = boot_id() else {
        return;
    };
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for e in entries.flatten() {
        if !e.file_name().to_string_lossy().starts_with(FIFO_DIR_PREFIX) {
            continue;
        }
        let dir = e.path();
        let Some(owner) = read_owner(&dir) else {
            continue;
        };
        let same_boot = owner.boot == boot;
        if same_boot && runs(owner.host.0, owner.host.1) {
            continue;
        }
        if let Some((pgid, start)) = owner.watchdog.filter(|_| same_boot) {
            // The group's leader recorded, or no process with its pid at all (then only the
            // group's own members can hold that id): the group is that run's.
            if runs(pgid, start) || process(pgid).is_none() {
                super::qemu::kill_group(pgid);
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// The per-run FIFO directory, removed (with its FIFOs) on drop.
#[derive(Debug)]
pub(super) struct FifoDir {
    path: std::path::PathBuf,
}

impl FifoDir {
    /// Create a fresh directory under `parent`: `reentry-pil-<pid>-<n>` with the first `n`
    /// (from a process-wide counter) whose directory does not exist yet, so a leftover of a
    /// killed run whose process id is reused never blocks a new run; its owner record
    /// ([`OWNER_FILE`]) is written in it. Stale directories of dead runs in `parent` are
    /// removed first ([`remove_stale`]).
    pub(super) fn create(parent: &Path) -> Result<Self, PilError> {
        use std::sync::atomic::{AtomicU32, Ordering};
        static N: AtomicU32 = AtomicU32::new(0);
        remove_stale(parent);
        let pid = std::process::id();
        let mut last = None;
        for _ in 0..10_000 {
            let n = N.fetch_add(1, Ordering::Relaxed);
            let path = parent.join(format!("{FIFO_DIR_PREFIX}{pid}-{n}"));
            match std::fs::create_dir(&path) {
                Ok(()) => {
                    let me = Self { path };
                    write_owner(&me.path, None).map_err(|source| PilError::Fifo {
                        path: me.path.join(OWNER_FILE),
                        op: FifoOp::CreateDir,
                        source,
                    })?;
                    return Ok(me);
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some((path, e)),
                Err(source) => {
                    return Err(PilError::Fifo {
                        path,
                        op: FifoOp::CreateDir,
                        source,
                    });
                }
            }
        }
        // Every name tried exists: the last "already exists" error.
        let (path, source) = last.unwrap_or_else(|| {
            (
                parent.to_path_buf(),
                std::io::Error::from(std::io::ErrorKind::AlreadyExists),
            )
        });
        Err(PilError::Fifo {
            path,
            op: FifoOp::CreateDir,
            source,
        })
    }

    /// The directory.
    pub(super) fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for FifoDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.path);
    }
}
