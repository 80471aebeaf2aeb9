//! Command-line interface (`host-sim simulate | atmosphere | vehicles`) and the TOML scenario
//! format behind it.
//!
//! Every error names the file, the field and the offending value; nothing panics on bad
//! input. The library entry point is [`run`], which `main` calls; tests call it directly.
//!
//! Scenario file (all sections and keys optional; defaults are the HORUS-2B reference
//! mission, thesis eq. 2.3 and table 2.1). `host-sim simulate --print-scenario` prints it:
//!
//! ```toml
//! name = "horus-2b-reference"
//! vehicle = "horus-2b"            # built-in name, or vehicle_file = "my.toml"
//!
//! [environment]
//! preset = "full"                 # full: US76, J2, rotating; simplified: exponential, central
//! # atmosphere = "us76" | "exponential"; gravity = "j2" | "central"; rotating = true
//!
//! [entry]
//! altitude_km = 122.0
//! longitude_deg = -106.7
//! latitude_deg = -22.3
//! speed_m_s = 7435.5              # planet-relative
//! flight_path_angle_deg = -1.43
//! heading_deg = 70.75
//!
//! [guidance]
//! independent = "time"            # or "energy" (normalised energy, 1 at entry)
//! interpolation = "linear"        # or "natural-cubic", "hermite" (with tension)
//! period_s = 2.0
//! alpha_rate_deg_s = 5.0
//! sigma_rate_deg_s = 15.0
//! initial_alpha_deg = 40.0
//! initial_sigma_deg = 0.0
//! nodes = [[0, 40, 0], [264, 40, 0], [290, 40, 79.6], ...]   # [x, alpha_deg, sigma_deg]
//!
//! [termination]
//! altitude_km = 25.0              # and/or mach = 2.5, normalized_energy = 0.01
//! max_time_s = 2500.0
//!
//! [integrator]
//! rtol = 1e-9
//! h_init_s = 0.1
//! h_min_s = 1e-9
//! h_max_s = 20.0
//! max_steps = 2000000
//! event_time_tol_s = 1e-6
//!
//! [monitors]
//! interface_altitude_km = 100.0   # exit/re-entry (skip) detection
//! g_rate_window_s = 0.1           # minimum window of the g-load-rate difference
//!
//! [output]
//! interval_s = 0.0                # 0: one sample per guidance tick
//! ```

mod atmosphere_cmd;
mod builtin;
mod fields;
mod flight;
mod guidance;
mod optimize_cmd;
mod optimize_structured;
mod parse;
mod parse_guidance;
mod scenario;
mod simulate_cmd;
mod to_toml;
mod vehicles_cmd;

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};

use crate::{report, sim, vehicle};

pub use builtin::HORUS_REFERENCE_NODES;
pub use flight::{Flight, RunOutput, fly, load_vehicle, simulate_scenario, write_flight};
pub use guidance::{build_guidance, guidance_bounds};
pub use optimize_cmd::{AlgorithmName, OptimizeArgs, OptimizeError, WeightsArg};
pub use parse::parse_scenario;
pub use scenario::{EnvSpec, GuidanceSpec, Independent, InterpolationKind, Scenario, VehicleSpec};
pub use to_toml::scenario_to_toml;

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
    Compare(crate::compare::CompareCliArgs),
    /// Multi-objective optimiser on a test problem (ZDT, DTLZ, CONSTR): summary, and with
    /// --out the final population, front CSV and summary JSON.
    Optimize(OptimizeArgs),
}

/// Arguments of `simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    /// Scenario TOML file (default: built-in HORUS-2B reference mission).
    #[arg(long, value_name = "FILE")]
    pub scenario: Option<PathBuf>,
    /// Output directory (default: runs/<scenario-name>/).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Built-in scenario instead of a file: horus-2b-reference (default) or srm-glide.
    #[arg(long, value_name = "NAME", conflicts_with = "scenario")]
    pub builtin: Option<String>,
    /// Print the scenario (default or loaded) as TOML and exit without simulating.
    #[arg(long)]
    pub print_scenario: bool,
    /// Do not show a progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Processor in the loop: fly the HORUS-2B reference mission with the guidance of this
    /// firmware ELF (`onboard-demo`'s `pil` binary) running in QEMU (see `host_sim::pil`).
    /// Only with the default scenario, whose table the firmware has compiled in.
    #[arg(long, value_name = "ELF", conflicts_with_all = ["scenario", "builtin"])]
    pub pil: Option<PathBuf>,
}

/// Atmosphere model choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AtmosphereModel {
    /// U.S. Standard Atmosphere 1976.
    Us76,
    /// Exponential, rho0 = 1.225 kg/m^3, H = 7.2 km.
    Exponential,
}

/// Arguments of `atmosphere`.
#[derive(Debug, clap::Args)]
pub struct AtmosphereArgs {
    /// Model.
    #[arg(long, value_enum, default_value = "us76")]
    pub model: AtmosphereModel,
    /// Altitudes [km] (default 0, 10, ..., 120).
    #[arg(value_name = "ALTITUDE_KM", allow_negative_numbers = true)]
    pub altitudes_km: Vec<f64>,
}

/// CLI failures; the message names file, field and value where there is one.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Command-line usage error (also `--help`/`--version`, which are not failures).
    #[error("{0}")]
    Usage(#[from] clap::Error),
    /// Bad scenario file or value.
    #[error("{0}")]
    Scenario(String),
    /// Vehicle could not be loaded.
    #[error("{0}")]
    Vehicle(#[from] vehicle::VehicleFileError),
    /// Simulation failed.
    #[error("simulation failed: {0}")]
    Sim(#[from] sim::SimError),
    /// Output could not be written.
    #[error("{0}")]
    Report(#[from] report::ReportError),
    /// Processor-in-the-loop run failed.
    #[error("PIL: {0}")]
    Pil(#[from] crate::pil::PilError),
    /// Analytical-vs-numerical comparison failed.
    #[error("{0}")]
    Compare(#[from] crate::compare::CompareError),
    /// Optimisation failed.
    #[error("{0}")]
    Optimize(#[from] OptimizeError),
    /// Writing to the console failed.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
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
            crate::compare::run_cli(&a, out)?;
            Ok(())
        }
        Command::Vehicles => vehicles_cmd::run(out),
        Command::Optimize(a) => Ok(optimize_cmd::run(&a, out)?),
    }
}
