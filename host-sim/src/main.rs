//! `host-sim` command-line entry point; everything lives in [`host_sim::cli`].

use std::process::ExitCode;

use host_sim::cli::{CliError, run};

fn main() -> ExitCode {
    // Ctrl-C: stop any QEMU of a PIL run (its own process group, which the terminal's SIGINT
    // does not reach) and remove its FIFO directory, then exit as interrupted.
    let _ = ctrlc::set_handler(|| {
        host_sim::pil::interrupt_cleanup();
        std::process::exit(130);
    });
    let mut stdout = std::io::stdout().lock();
    match run(std::env::args_os(), &mut stdout) {
        Ok(()) => ExitCode::SUCCESS,
        // Help, version and usage errors: clap prints them and picks the exit code.
        Err(CliError::Usage(e)) => e.exit(),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
