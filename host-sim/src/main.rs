//! `host-sim` command-line entry point; everything lives in [`host_sim::cli`].

use std::process::ExitCode;

use host_sim::cli::{CliError, run};

fn main() -> ExitCode {
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
