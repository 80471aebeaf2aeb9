//! Writing a grid (CSV and heat maps) and a case's trajectories to disk.

use std::path::{Path, PathBuf};

use super::{CaseRuns, CompareGrid, Preset, grid_csv, heat_map_svg};
use crate::analytic::{self, AnalyticVehicle};
use crate::report::{self, ReportError, RunDir};
use crate::sim::SimResult;

/// Write the run directory `dir` with `grid.csv` and one heat map per metric and environment
/// flown (`<metric>_err_<environment>.svg`), whole or not at all ([`RunDir`]).
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_grid(
    dir: &Path,
    grid: &CompareGrid,
    fidelities: &[Preset],
) -> Result<Vec<PathBuf>, ReportError> {
    let mut rd = RunDir::begin(dir)?;
    write_grid_into(&mut rd, grid, fidelities)?;
    rd.commit()
}

/// Write `grid.csv` and the heat maps into the run directory being written.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_grid_into(
    rd: &mut RunDir,
    grid: &CompareGrid,
    fidelities: &[Preset],
) -> Result<Vec<PathBuf>, ReportError> {
    let mut written = vec![rd.write("grid.csv", grid_csv(grid).as_bytes())?];
    for (m, metric) in grid.metrics.iter().enumerate() {
        for &f in fidelities {
            let name = format!("{}_err_{}.svg", metric.name, f.name());
            written.push(rd.write(name, heat_map_svg(grid, m, f)?.as_bytes())?);
        }
    }
    Ok(written)
}

/// Write the trajectories of one case as the run directory `dir` with sub-directories
/// `analytic/`, `simplified/`, `full/` (whichever exist), each with the numerical simulator's
/// report files; whole or not at all ([`RunDir`]).
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_case(
    dir: &Path,
    runs: &CaseRuns,
    vehicle: &AnalyticVehicle,
    scenario: &str,
) -> Result<Vec<PathBuf>, ReportError> {
    let mut rd = RunDir::begin(dir)?;
    write_case_into(&mut rd, Path::new(""), runs, vehicle, scenario)?;
    rd.commit()
}

/// Write the trajectories of one case under `sub` (relative) of the run directory being
/// written: `sub/analytic/`, `sub/simplified/`, `sub/full/` (whichever exist).
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_case_into(
    rd: &mut RunDir,
    sub: &Path,
    runs: &CaseRuns,
    vehicle: &AnalyticVehicle,
    scenario: &str,
) -> Result<(), ReportError> {
    let planet_r = analytic::planet().radius_m;
    // One run: the summary and the simulator's report files.
    let mut write = |name: &str, result: &SimResult, environment: &str| {
        let summary =
            report::summary_report(result, scenario, &vehicle.name, environment, planet_r);
        report::write_run_files(
            rd,
            &sub.join(name),
            result,
            &summary,
            &report::PlotLimits::of_vehicle(&vehicle.limits),
        )
    };
    if let Ok(a) = &runs.analytic {
        write(
            "analytic",
            &a.result,
            &analytic::environment_label(&a.atmosphere),
        )?;
    }
    for (f, res, _) in &runs.numerical {
        if let Some(res) = res {
            let env = match f {
                Preset::Simplified => {
                    "numerical: non-rotating sphere, central gravity, \
                     exponential atmosphere of the closed forms"
                }
                Preset::Full => "numerical: rotating sphere, US76, J2",
            };
            write(f.name(), res, env)?;
        }
    }
    Ok(())
}
