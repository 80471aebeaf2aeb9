//! The two named FIFOs of the link: creation and opening with a timeout.

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

/// The per-run FIFO directory, removed (with its FIFOs) on drop.
#[derive(Debug)]
pub(super) struct FifoDir {
    path: std::path::PathBuf,
}

impl FifoDir {
    /// Create a fresh directory under `parent`: `reentry-pil-<pid>-<n>` with the first `n`
    /// (from a process-wide counter) whose directory does not exist yet, so a leftover of a
    /// killed run whose process id is reused never blocks a new run.
    pub(super) fn create(parent: &Path) -> Result<Self, PilError> {
        use std::sync::atomic::{AtomicU32, Ordering};
        static N: AtomicU32 = AtomicU32::new(0);
        let pid = std::process::id();
        let mut last = None;
        for _ in 0..10_000 {
            let n = N.fetch_add(1, Ordering::Relaxed);
            let path = parent.join(format!("{FIFO_DIR_PREFIX}{pid}-{n}"));
            match std::fs::create_dir(&path) {
                Ok(()) => return Ok(Self { path }),
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
