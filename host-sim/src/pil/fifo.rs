//! The two named FIFOs of the link: creation and opening with a timeout.

use std::fs::{File, OpenOptions};
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

use super::PilError;

pub(super) fn mkfifo(path: &Path) -> Result<(), PilError> {
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
pub(super) fn open_fifo(path: &Path, write: bool, timeout: Duration) -> Result<File, PilError> {
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
