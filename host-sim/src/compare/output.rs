//! Writing a grid (CSV and heat maps) and a case's trajectories to disk.

use std::path::{Path, PathBuf};

use super::{CaseRuns, CompareGrid, Preset, grid_csv, heat_map_svg};
use crate::analytic::{self, AnalyticVehicle};
use crate::report::{self, ReportError};
use crate::sim::SimResult;

/// Write `grid.csv` and one heat map per metric and environment flown
/// (`<metric>_err_<environment>.svg`) into `dir` (created if needed), atomically.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_grid(
    dir: &Path,
    grid: &CompareGrid,
    fidelities: &[Preset],
) -> Result<Vec<PathBuf>, ReportError> {
    std::fs::create_dir_all(dir).map_err(|source| ReportError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    let csv = dir.join("grid.csv");
    report::write_atomic(&csv, grid_csv(grid).as_bytes())?;
    written.push(csv);
    for (m, metric) in grid.metrics.iter().enumerate() {
        for &f in fidelities {
            let p = dir.join(format!("{}_err_{}.svg", metric.name, f.name()));
            report::write_atomic(&p, heat_map_svg(grid, m, f)?.as_bytes())?;
            written.push(p);
        }
    }
    Ok(written)
}

/// Write the trajectories of one case as run directories `analytic/`, `simplified/`, `full/`
/// (whichever exist) under `dir`, each with the numerical simulator's report files.
///
/// # Errors
/// [`ReportError`] naming the path.
pub fn write_case(
    dir: &Path,
    runs: &CaseRuns,
    vehicle: &AnalyticVehicle,
    scenario: &str,
) -> Result<Vec<PathBuf>, ReportError> {
    let planet_r = analytic::planet().radius_m;
    // One run directory: the summary and the simulator's report files.
    let write = |sub: &str, result: &SimResult, environment: &str| {
        let summary =
            report::summary_report(result, scenario, &vehicle.name, environment, planet_r);
        report::write_run(
            &dir.join(sub),
            result,
            &summary,
            vehicle.limits.heat_flux_w_m2,
            vehicle.limits.g_load,
        )
    };
    let mut written = Vec::new();
    if let Ok(a) = &runs.analytic {
        written.extend(write(
            "analytic",
            &a.result,
            &analytic::environment_label(&a.atmosphere),
        )?);
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
            written.extend(write(f.name(), res, env)?);
        }
    }
    Ok(written)
}
