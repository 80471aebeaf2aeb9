//! Command-line interface: `host-sim simulate | compare | atmosphere | vehicles`, one file per
//! subcommand. clap lives here only; each subcommand parses its arguments, calls the library
//! and prints. The library entry point is [`run`], which `main` calls; tests call it directly.
//! Scenario files are the library's ([`crate::scenario`]).

mod atmosphere_cmd;
mod compare_cmd;
mod dispersions_cmd;
mod error;
mod hypervolume_cmd;
mod optimize_cmd;
mod optimize_common;
mod optimize_reentry;
#[cfg(test)]
mod optimize_reentry_tests;
#[cfg(test)]
mod optimize_resume_tests;
mod optimize_structured;
#[cfg(test)]
mod optimize_variants_tests;
mod sample_cmd;
mod simulate_cmd;
mod vehicles_cmd;

use std::ffi::OsString;
use std::io::Write;

use clap::{Parser, Subcommand};

pub use atmosphere_cmd::{AtmosphereArgs, AtmosphereModel};
pub use compare_cmd::{CliPhase, CompareCliArgs, EnvArg};
pub use dispersions_cmd::DispersionsArgs;
pub use error::{CliError, HypervolumeCmdError};
pub use hypervolume_cmd::HypervolumeArgs;
pub use optimize_cmd::{AlgorithmArgs, OptimizeArgs, OptimizeError};
pub use optimize_common::{DecompositionArgs, MhacoArgs, MoeadArgs, Nsga2Args, SceaArgs};
pub use optimize_reentry::{ReentryError, ReentryRunConfig, check_run_config};
pub use sample_cmd::SampleArgs;
pub use simulate_cmd::SimulateArgs;

/// `host-sim`: 3-DOF re-entry simulator flying guidance-core's guidance closed-loop.
#[derive(Debug, Parser)]
#[command(name = "host-sim", version, about, long_about = None)]
pub struct Cli {
    /// Subcommand.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Fly a scenario closed-loop (default: the HORUS-2B reference mission) and write a run
    /// directory with trajectory.csv, summary.json and SVG plots.
    Simulate(SimulateArgs),
    /// Query an atmosphere model at altitudes given in km.
    Atmosphere(AtmosphereArgs),
    /// List the built-in vehicles.
    Vehicles,
    /// Analytical (Vinh closed forms) against numerical simulation over a grid of entry
    /// altitude or speed x vertical lift coefficient (thesis fig. 8.5): grid.csv + SVG heat maps.
    Compare(CompareCliArgs),
    /// Multi-objective optimiser (subcommand: the algorithm, default moead) on a test
    /// problem (ZDT, DTLZ, CONSTR, VLMOP) or a re-entry design preset: summary, and with
    /// --out the final population, front CSV and summary JSON (re-entry: a run directory).
    Optimize(OptimizeArgs),
    /// Exact hypervolume of a front CSV (minimised objectives as columns) for a reference point.
    Hypervolume(HypervolumeArgs),
    /// Monte Carlo dispersion campaign of a scenario in three guidance modes.
    Dispersions(DispersionsArgs),
    /// Latin-hypercube sample of a re-entry design problem, evaluated in parallel
    /// (samples.csv: decision, objectives, constraints, violation).
    Sample(SampleArgs),
}

/// Run the CLI with `args` (including the program name), writing normal output to `out`.
///
/// # Errors
/// [`CliError`]; `CliError::Usage` also carries `--help`/`--version` output (see
/// [`clap::Error::exit`]).
pub fn run<I, T>(args: I, out: &mut dyn Write) -> Result<(), CliError>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = Cli::try_parse_from(args)?;
    match cli.command {
        Command::Simulate(a) => simulate_cmd::run(&a, out),
        Command::Atmosphere(a) => atmosphere_cmd::run(a, out),
        Command::Compare(a) => {
            compare_cmd::run(&a, out)?;
            Ok(())
        }
        Command::Vehicles => vehicles_cmd::run(out),
        Command::Optimize(a) => Ok(optimize_cmd::run(&a, out)?),
        Command::Hypervolume(a) => hypervolume_cmd::run(&a, out),
        Command::Dispersions(a) => dispersions_cmd::run(&a, out),
        Command::Sample(a) => Ok(sample_cmd::run(&a, out)?),
    }
}
