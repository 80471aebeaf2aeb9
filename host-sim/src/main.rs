//! `host-sim` command-line entry point; everything lives in [`host_sim::cli`].

use std::process::ExitCode;

use host_sim::cli::{CliError, run};
use host_sim::sim;

/// Exit status after Ctrl-C (128 + SIGINT), as a shell reports a process killed by it.
const INTERRUPTED: u8 = 130;

fn main() -> ExitCode {
    // Ctrl-C asks the running simulation to stop at its next breakpoint; the command then
    // fails without putting a run directory in place (nothing half-written). With no
    // simulation running and no run directory being written (optimiser, hypervolume, a PIL
    // set-up), or at a second Ctrl-C, it exits at once. A run directory being written stops at
    // its next file and removes its temporary directory; one is swapped into place in one
    // step. Before exiting it stops any QEMU of a PIL run (its own process group, which the
    // terminal's SIGINT does not reach) and removes its FIFO directory; a PIL run that stops
    // at a breakpoint does so on drop.
    let second = std::sync::atomic::AtomicBool::new(false);
    let handler = ctrlc::set_handler(move || {
        // No run may start between the check and the exit (it would leave its temporary
        // directory behind): new runs wait on this guard, which the exit never releases.
        let _gate = sim::hold_new_runs();
        if second.swap(true, std::sync::atomic::Ordering::SeqCst) || !sim::runs_active() {
            // The handler runs on its own thread (ctrlc), not in signal context. Flag the stop
            // first: the cleanup below makes the main thread's PIL link fail, and if it returns
            // before this thread exits, it must report the interruption (130) too, not an error.
            sim::request_stop();
            host_sim::pil::interrupt_cleanup();
            eprintln!("interrupted; no run directory written");
            std::process::exit(i32::from(INTERRUPTED));
        }
        sim::request_stop();
    });
    if let Err(e) = handler {
        eprintln!("warning: cannot install the Ctrl-C handler: {e}");
    }
    let mut stdout = std::io::stdout().lock();
    match run(std::env::args_os(), &mut stdout) {
        Ok(()) if sim::stop_requested() => {
            eprintln!("interrupted after the run was written");
            ExitCode::from(INTERRUPTED)
        }
        Ok(()) => ExitCode::SUCCESS,
        // Help, version and usage errors: clap prints them and picks the exit code.
        Err(CliError::Usage(e)) => e.exit(),
        Err(e) if sim::stop_requested() => {
            eprintln!("interrupted: {e}; no run directory written");
            ExitCode::from(INTERRUPTED)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
