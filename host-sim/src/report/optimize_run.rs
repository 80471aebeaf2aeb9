//! The run directory of an optimisation run on a test problem (`host-sim optimize --out`,
//! `reentry-dask optimize --out`, `Optimizer.write_run` in Python): population.csv,
//! front.csv and summary.json, written whole or not at all ([`RunDir`]).

use std::path::Path;

use super::{ReportError, RunDir};
use crate::optim::chromosome::Chromosome;
use crate::optim::run::{RunReport, RunSummary, chromosome_csv, front_csv, population_csv};

/// Write the run directory `dir` of a test-problem run: `population` (the population's CSV
/// text), front.csv of `front` and summary.json of `summary`.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_optimize_run(
    dir: &Path,
    population: &str,
    front: &[&[f64]],
    summary: &RunSummary<'_>,
) -> Result<(), ReportError> {
    let mut rd = RunDir::begin(dir)?;
    rd.write("population.csv", population.as_bytes())?;
    rd.write(
        "front.csv",
        front_csv(front, summary.objectives)
            .map_err(ReportError::from)?
            .as_bytes(),
    )?;
    let json = serde_json::to_string_pretty(summary).map_err(ReportError::Json)?;
    rd.write("summary.json", json.as_bytes())?;
    rd.commit()?;
    Ok(())
}

/// [`write_optimize_run`] of a real-vector run's [`RunReport`].
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_run_report(dir: &Path, report: &RunReport<'_>) -> Result<(), ReportError> {
    let population = population_csv(report.population)?;
    write_optimize_run(dir, &population, &report.front, &report.summary)
}

/// [`write_optimize_run`] of a variable-length run's [`RunReport`] (population.csv: one
/// chromosome per row, [`chromosome_csv`]).
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_chromosome_run_report(
    dir: &Path,
    report: &RunReport<'_, Chromosome>,
) -> Result<(), ReportError> {
    let s = &report.summary;
    let population = chromosome_csv(report.population, s.objectives, s.constraints)?;
    write_optimize_run(dir, &population, &report.front, s)
}
