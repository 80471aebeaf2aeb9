//! A process-wide stop request: the CLI's Ctrl-C (SIGINT) handler sets it, and every running
//! closed-loop simulation checks it where it reports progress and ends with
//! [`super::SimError::Interrupted`], so a long run stops promptly and its caller writes
//! nothing (run directories are only put in place once complete: [`crate::report::RunDir`]).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};

static STOP: AtomicBool = AtomicBool::new(false);
static ACTIVE: AtomicUsize = AtomicUsize::new(0);
/// Held while an [`ActiveRun`] starts and by [`hold_new_runs`].
static GATE: Mutex<()> = Mutex::new(());

fn gate() -> MutexGuard<'static, ()> {
    GATE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Marks work that stops cleanly on request (a running simulation, a run directory being
/// written) while it lives, so Ctrl-C asks it to stop instead of exiting the process.
#[derive(Debug)]
pub(crate) struct ActiveRun;

impl ActiveRun {
    pub(crate) fn start() -> Self {
        let _gate = gate();
        ACTIVE.fetch_add(1, Ordering::SeqCst);
        Self
    }
}

impl Drop for ActiveRun {
    fn drop(&mut self) {
        ACTIVE.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Whether work that stops cleanly on request is running now: a simulation (which checks
/// [`stop_requested`]) or a run directory being written ([`crate::report::RunDir`], which
/// removes its temporary directory when stopped). When none is (an optimiser, a PIL set-up),
/// Ctrl-C need not wait: the CLI exits at once.
#[must_use]
pub fn runs_active() -> bool {
    ACTIVE.load(Ordering::SeqCst) > 0
}

/// Hold back the start of new runs while the guard lives. The CLI's Ctrl-C handler holds it
/// from its [`runs_active`] check until it exits the process, so no run (and no temporary run
/// directory) can start between the check and the exit.
pub fn hold_new_runs() -> MutexGuard<'static, ()> {
    gate()
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
