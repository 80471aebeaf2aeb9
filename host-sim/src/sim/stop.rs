//! A process-wide stop request: the CLI's Ctrl-C (SIGINT) handler sets it, and every running
//! closed-loop simulation checks it where it reports progress and ends with
//! [`super::SimError::Interrupted`], so a long run stops promptly and its caller writes
//! nothing (run directories are only put in place once complete: [`crate::report::RunDir`]).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

static STOP: AtomicBool = AtomicBool::new(false);
static ACTIVE: AtomicUsize = AtomicUsize::new(0);

/// Marks a simulation as running (and so able to stop on request) while it lives.
pub(super) struct ActiveRun;

impl ActiveRun {
    pub(super) fn start() -> Self {
        ACTIVE.fetch_add(1, Ordering::SeqCst);
        Self
    }
}

impl Drop for ActiveRun {
    fn drop(&mut self) {
        ACTIVE.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Whether a simulation is running now (one that checks [`stop_requested`]). When none is
/// (an optimiser, the writing of a run directory), Ctrl-C need not wait: the CLI exits at
/// once, which leaves no half-written run directory either ([`crate::report::RunDir`]).
#[must_use]
pub fn runs_active() -> bool {
    ACTIVE.load(Ordering::SeqCst) > 0
}

/// Ask every running simulation to stop (async-signal safe: one atomic store).
pub fn request_stop() {
    STOP.store(true, Ordering::SeqCst);
}

/// Whether a stop was requested.
#[must_use]
pub fn stop_requested() -> bool {
    STOP.load(Ordering::Relaxed)
}
