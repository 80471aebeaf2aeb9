//! A process-wide stop request: the CLI's Ctrl-C (SIGINT) handler sets it, and every running
//! closed-loop simulation checks it where it reports progress and ends with
//! [`super::SimError::Interrupted`], so a long run stops promptly and its caller writes
//! nothing (run directories are only put in place once complete: [`crate::report::RunDir`]).

use std::sync::atomic::{AtomicBool, Ordering};

static STOP: AtomicBool = AtomicBool::new(false);

/// Ask every running simulation to stop (async-signal safe: one atomic store).
pub fn request_stop() {
    STOP.store(true, Ordering::SeqCst);
}

/// Whether a stop was requested.
#[must_use]
pub fn stop_requested() -> bool {
    STOP.load(Ordering::Relaxed)
}
