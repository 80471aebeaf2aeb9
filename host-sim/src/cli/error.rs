//! The command line's errors: [`CliError`] (what `run` returns) and the `hypervolume`
//! subcommand's own [`HypervolumeCmdError`], below the subcommands that return them.

use std::path::PathBuf;

use super::optimize_cmd::OptimizeError;
use super::optimize_reentry::ReentryError;
use crate::optim::hypervolume::HypervolumeError;
use crate::{report, scenario, vehicle};

/// CLI failures; the message names file, field and value where there is one.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// Command-line usage error (also `--help`/`--version`, which are not failures).
    #[error("{0}")]
    Usage(#[from] clap::Error),
    /// A bad command-line value.
    #[error("command line: argument `{field}` = {value}: {reason}")]
    Argument {
        /// Argument name.
        field: &'static str,
        /// The value given.
        value: String,
        /// What is required.
        reason: &'static str,
    },
    /// Bad scenario, or a scenario that failed to fly.
    #[error(transparent)]
    Scenario(#[from] scenario::ScenarioError),
    /// Vehicle could not be loaded.
    #[error(transparent)]
    Vehicle(#[from] vehicle::VehicleFileError),
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
    /// `hypervolume` failed.
    #[error("{0}")]
    Hypervolume(#[from] HypervolumeCmdError),
    /// `sample` failed.
    #[error("{0}")]
    Sample(#[from] ReentryError),
    /// Writing to the console failed.
    #[error("cannot write output: {0}")]
    Io(#[from] std::io::Error),
    /// A dispersion campaign failed.
    #[error("{0}")]
    Campaign(Box<crate::campaign::CampaignError>),
    /// `dispersions --pil`: flights of the PIL leg break a PIL-vs-SIL tolerance (or failed).
    #[error(
        "PIL: {failed} of {total} flights break a PIL-vs-SIL tolerance (twin, counts, ending or miss bound) or failed: {}",
        file.display()
    )]
    PilTolerance {
        /// Flights outside the tolerances or failed.
        failed: usize,
        /// Flights flown.
        total: usize,
        /// The per-flight comparison (`pil-cases.csv`).
        file: PathBuf,
    },
}

/// Failures of `hypervolume`; each names the file and line, or the argument.
#[derive(Debug, thiserror::Error)]
pub enum HypervolumeCmdError {
    /// The front file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A field of a CSV line is not a finite number.
    #[error("{path}:{line}: field {field} = {value:?}: {reason}")]
    Field {
        /// The file.
        path: PathBuf,
        /// Line number, from 1.
        line: usize,
        /// Field (column) number, from 1.
        field: usize,
        /// The field's text.
        value: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A CSV line has a different number of fields than the reference point.
    #[error("{path}:{line}: {found} fields, but the reference point has {expected} coordinates")]
    Columns {
        /// The file.
        path: PathBuf,
        /// Line number, from 1.
        line: usize,
        /// Fields on the line.
        found: usize,
        /// Coordinates of the reference point.
        expected: usize,
    },
    /// The `--ref` argument is malformed.
    #[error(transparent)]
    Reference(#[from] crate::optim::reference::ReferenceArgError),
    /// The hypervolume could not be computed.
    #[error("{path}: {source}")]
    Hypervolume {
        /// The file.
        path: PathBuf,
        /// Why.
        source: HypervolumeError,
    },
}
